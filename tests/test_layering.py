"""The package's structure: no module imports another module's private (underscore) names,
and the import-linter contracts of pyproject.toml hold (layers, no cycles)."""

import ast
import importlib
import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "dynstiff"


def _private_imports(path):
    """(line, text) of every ``from <dynstiff module> import _name`` in ``path``, where
    ``_name`` is not itself a package-private module (``_validate``, ``_vec``)."""
    out = []
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom):
            continue
        internal = node.level > 0 or (node.module or "").split(".")[0] == "dynstiff"
        if not internal:
            continue
        base = path.parent
        for _ in range(max(node.level - 1, 0)):
            base = base.parent
        if node.level == 0:
            base = ROOT
        target = base.joinpath(*(node.module or "").split(".")) if node.module else base
        for alias in node.names:
            name = alias.name
            if not name.startswith("_") or name.startswith("__"):
                continue
            if (target / f"{name}.py").exists() or (target / name).is_dir():
                continue                                  # a package-private module
            out.append((node.lineno, f"from {'.' * node.level}{node.module or ''} import {name}"))
    return out


def test_no_module_imports_another_modules_private_names():
    found = [f"{p.relative_to(ROOT)}:{line}: {text}"
             for p in sorted(PACKAGE.rglob("*.py")) for line, text in _private_imports(p)]
    assert not found, "private names imported across modules:\n" + "\n".join(found)


def test_the_private_import_check_can_fail(tmp_path):
    """The check above finds a planted private import (so its silence means something)."""
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "a.py").write_text("def _helper():\n    return 1\n")
    (pkg / "_kernel.py").write_text("x = 1\n")
    bad = pkg / "b.py"
    bad.write_text("from .a import _helper\nfrom . import _kernel\nfrom .a import public\n")
    assert [text for _, text in _private_imports(bad)] == ["from .a import _helper"]


@pytest.mark.integration
def test_import_linter_contracts_hold():
    """The contracts of pyproject.toml (layers, no cycles, private modules) hold."""
    run = subprocess.run([sys.executable, "-c",
                          "import sys; from importlinter.cli import lint_imports; "
                          "sys.exit(lint_imports())"],
                         cwd=ROOT, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    assert "0 broken" in run.stdout


def test_no_module_is_longer_than_500_lines():
    """Small files with one job: no module of the package passes 500 lines."""
    long = {str(p.relative_to(ROOT)): n for p in sorted(PACKAGE.rglob("*.py"))
            if (n := len(p.read_text().splitlines())) > 500}
    assert not long, long


def test_numba_is_loaded_in_one_place_only():
    """Every compiled kernel is reached through dynstiff.compiled.load: numba is imported
    only by the kernels of dynstiff/compiled/, and looked for only by its loader."""
    compiled = PACKAGE / "compiled"
    found = []
    for p in sorted(PACKAGE.rglob("*.py")):
        text = p.read_text()
        if p.parent != compiled and ("import numba" in text or "find_spec(\"numba\")" in text):
            found.append(str(p.relative_to(ROOT)))
        if p.parent == compiled and p.name != "__init__.py" and "find_spec" in text:
            found.append(str(p.relative_to(ROOT)))
    assert not found, found


def _dotted_references(text):
    """Every ``dynstiff.a.b`` written in ``text`` (docstrings, prose), without the xarray
    accessor (``ds.dynstiff.x``) or file names."""
    refs = re.findall(r"(?<![\w./])dynstiff((?:\.\w+)+)", text)
    return {"dynstiff" + r for r in refs if not r.endswith((".py", ".toml", ".csv", ".nc"))}


def _resolves(dotted):
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for name in parts[i:]:
            if not hasattr(obj, name):
                return False
            obj = getattr(obj, name)
        return True
    return False


def test_every_dotted_reference_in_the_package_and_its_documents_resolves():
    """A module or name that moved leaves no stale ``dynstiff.old.path`` behind in the
    package's docstrings, the README or docs/ (the command line's module is not imported)."""
    files = [*sorted(PACKAGE.rglob("*.py")), ROOT / "README.md",
             *sorted((ROOT / "docs").glob("*.md"))]
    stale = sorted({f"{p.relative_to(ROOT)}: {ref}" for p in files if p.exists()
                    for ref in _dotted_references(p.read_text())
                    if "__main__" not in ref and not _resolves(ref)})
    assert not stale, "\n".join(stale)


_BROKEN_ROLE = re.compile(r":(?:func|class|meth|mod|attr|data|exc):`[^`]*\n")


def test_no_cross_reference_is_broken_over_lines():
    """Sphinx resolves ``:func:`a.b.c``` only when the target is on one line; a reference
    broken at a dot renders as a missing target (a warning in the documentation build)."""
    broken = sorted(f"{p.relative_to(ROOT)}: {m.group(0)!r}" for p in PACKAGE.rglob("*.py")
                    for m in _BROKEN_ROLE.finditer(p.read_text()))
    assert not broken, "\n".join(broken)
    assert _BROKEN_ROLE.search(":func:`dynstiff.\n    modes`")


def test_the_reference_check_can_fail():
    assert _dotted_references("see :func:`dynstiff.cable.dsm.nope` and dynstiff/x.py") == \
        {"dynstiff.cable.dsm.nope"}
    assert not _resolves("dynstiff.cable.dsm.nope") and _resolves("dynstiff.cable.dsm")
