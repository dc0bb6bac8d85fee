"""Every public name has its page: a build fails (with ``-W``) when a name of
``dynstiff.__all__``, or of a documented subpackage's ``__all__``, has no generated API page.
"""

import importlib

#: Packages whose ``__all__`` is documented; a name they share with ``dynstiff`` is
#: documented once, under ``dynstiff``.
PACKAGES = ("dynstiff", "dynstiff.plot", "dynstiff.plot.workspace", "dynstiff.report.robot3d",
            "dynstiff.lumped", "dynstiff.scenes", "dynstiff.timedomain.trajectory",
            "dynstiff.timedomain.pendulum", "dynstiff.maps.workspace", "dynstiff.maps.dataset",
            "dynstiff.maps.guards", "dynstiff.maps.store", "dynstiff.io.caspr",
            "dynstiff.io.caspr_motion", "dynstiff.io.exchange", "dynstiff.io.files")


def missing_pages(env):
    """``[(package, name)]`` of public names without a page under ``api/generated``."""
    objects = env.get_domain("py").objects
    top = set(importlib.import_module("dynstiff").__all__)
    missing = []
    for package in PACKAGES:
        names = importlib.import_module(package).__all__
        for name in names:
            if package != "dynstiff" and name in top:
                name, where = name, "dynstiff"
            else:
                where = package
            entry = objects.get(f"{where}.{name}")
            if entry is None or entry.docname != f"api/generated/{where}.{name}":
                missing.append((package, name))
    return missing


def check(app, env):
    from sphinx.util import logging
    logger = logging.getLogger(__name__)
    for package, name in missing_pages(env):
        logger.warning(f"{package}.{name} is public (in __all__) but has no API page",
                       type="dynstiff", subtype="api")


def setup(app):
    app.connect("env-check-consistency", check)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
