"""Sphinx configuration of the dynstiff documentation.

Build (from the repository root): ``python -m sphinx -b html -W --keep-going -n docs
docs/_build/html``. The build needs no network: cross-references to numpy, scipy, pandas,
xarray and matplotlib are plain text unless ``DYNSTIFF_DOCS_INTERSPHINX=1`` asks for their
inventories.
"""

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

from gallery_scraper import TightScraper  # noqa: E402

import dynstiff  # noqa: E402

project = "dynstiff"
copyright = "the dynstiff developers"
author = "the dynstiff developers"
version = release = dynstiff.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "dynstiff_cli",
    "dynstiff_api_check",
    "dynstiff_refs",
    "dynstiff_docstrings",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "**.ipynb_checkpoints", "examples/README.txt"]
templates_path = ["_templates"]
nitpicky = True
# quotes and ellipses only: "--option" in help texts stays two hyphens
smartquotes_action = "qe"

# ---------------------------------------------------------------- MyST (Markdown pages)
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# ---------------------------------------------------------------- API reference
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "none"
autoclass_content = "class"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = True
# only the names below become links; other words of a type description stay text
numpydoc_xref_ignore = "all"
numpydoc_xref_aliases = {name: f"dynstiff.{name}" for name in dynstiff.__all__
                         if name[0].isupper() and name not in ("RUNGS", "STANDARD_GRAVITY")}
numpydoc_xref_aliases.update({
    "PlatformModel": "dynstiff.models.base.PlatformModel",
})
if os.environ.get("DYNSTIFF_DOCS_INTERSPHINX") != "1":
    # numpydoc's default links point into the Python and NumPy inventories: offline, the
    # words stay text (see nitpick_ignore_regex)
    from numpydoc.xref import DEFAULT_LINKS
    numpydoc_xref_aliases.update({word: word for word in DEFAULT_LINKS
                                  if word not in numpydoc_xref_aliases})
numpydoc_validation_checks = set()

# Targets outside the package (numpy, scipy, pandas, xarray, matplotlib, the standard
# library): without their inventories (offline) the references stay text.
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|scipy|pandas|pd|xarray|xr|matplotlib|mpl|dask|distributed|control"
               r"|pyuff|numba|mpl_toolkits|dataclasses|pathlib|os|typing|collections"
               r"|warnings)(\..*)?"),
    (r"py:.*", r"(array_like|array|ndarray|float|int|bool|str|complex|dict|list|tuple|callable"
               r"|None|path-like|Path|pathlib\.Path|os\.PathLike|sequence|Sequence|iterable"
               r"|mapping|object|optional|default)"),
]

# Optional inventories (DYNSTIFF_DOCS_INTERSPHINX=1): links to the libraries' documentation.
if os.environ.get("DYNSTIFF_DOCS_INTERSPHINX") == "1":
    extensions.append("sphinx.ext.intersphinx")
    intersphinx_mapping = {
        "python": ("https://docs.python.org/3", None),
        "numpy": ("https://numpy.org/doc/stable/", None),
        "scipy": ("https://docs.scipy.org/doc/scipy/", None),
        "pandas": ("https://pandas.pydata.org/docs/", None),
        "xarray": ("https://docs.xarray.dev/en/stable/", None),
        "matplotlib": ("https://matplotlib.org/stable/", None),
    }

# ---------------------------------------------------------------- gallery
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "doc_module": ("dynstiff",),
    "backreferences_dir": None,
    "show_memory": False,
    "matplotlib_animations": False,
    "image_scrapers": (TightScraper(),),
}

# ---------------------------------------------------------------- HTML
html_theme = "pydata_sphinx_theme"
html_title = f"dynstiff {release}"
html_static_path = []
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 7,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_show_sourcelink = False
# pages without sub-pages: no empty navigation column
html_sidebars = {page: [] for page in ("getting_started", "cli", "theory", "validation")}
html_context = {"default_mode": "light"}
