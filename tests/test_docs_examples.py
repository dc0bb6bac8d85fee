"""The examples in the docstrings run and print what they say (doctest over every module of
the package), every public name has an ``Examples`` section, and the public API is
annotated (its return types at least, for the editor and for ``mypy dynstiff`` in .ci/run).
"""

import doctest
import importlib
import inspect
import pkgutil
import re

import numpy as np
import pytest

import dynstiff

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE

MODULES = sorted(m.name for m in pkgutil.walk_packages(dynstiff.__path__, "dynstiff.")
                 if not m.name.endswith("__main__"))

#: The result types whose public methods are documented with examples too (their properties
#: are shown by the example of the class).
RESULTS = ("FRFResult", "ModalResult", "DampedModes", "LumpedModalResult", "SweepResult",
           "CableModes", "CheckResult", "SensitivityResult", "OptimalTensions",
           "UncertaintyResult", "CalibrationResult", "MeasuredModes", "ModalModel",
           "Recommendation", "Equilibrium")


def _doctests(module):
    finder = doctest.DocTestFinder(exclude_empty=True)
    return [t for t in finder.find(module, module.__name__) if t.examples]


def _run(module):
    """``(failed, attempted, report)`` of the doctests of one module."""
    out = []
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    with np.printoptions(legacy="1.25"):      # ``0.5``, not ``np.float64(0.5)``
        for test in _doctests(module):
            runner.run(test, out=out.append)
    failed, attempted = runner.summarize(verbose=False)
    return failed, attempted, "".join(out)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_run(name):
    pytest.importorskip("matplotlib")
    if name.startswith(("dynstiff.maps", "dynstiff.cli.workspace")):
        pytest.importorskip("xarray")
    module = importlib.import_module(name)
    failed, attempted, report = _run(module)
    assert failed == 0, report


def test_a_wrong_example_fails():
    import types
    module = types.ModuleType("example_module")
    exec('def f():\n    """One.\n\n    >>> 1 + 1\n    3\n    """\n', module.__dict__)
    failed, attempted, report = _run(module)
    assert (failed, attempted) == (1, 1) and "Expected" in report


def _public_callables():
    for name in dynstiff.__all__:
        obj = getattr(dynstiff, name)
        if callable(obj):
            yield name, obj


def _members(cls, properties=True):
    """Public methods (and properties) defined in a class itself."""
    for name, attr in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(attr, property):
            if properties:
                yield name, attr.fget
        elif isinstance(attr, (staticmethod, classmethod)):
            yield name, attr.__func__
        elif inspect.isfunction(attr):
            yield name, attr


def _has_examples(obj):
    doc = inspect.getdoc(obj) or ""
    return re.search(r"^Examples\n-{8}\n(.|\n)*^>>> ", doc, re.MULTILINE) is not None


def test_every_public_name_has_an_examples_section():
    missing = [name for name, obj in _public_callables() if not _has_examples(obj)]
    for cls in RESULTS:
        missing += [f"{cls}.{name}" for name, f in _members(getattr(dynstiff, cls), False)
                    if not _has_examples(f)]
    assert not missing, missing


def _returns_annotated(func):
    return inspect.signature(func).return_annotation is not inspect.Signature.empty


def test_every_public_callable_has_a_return_annotation():
    missing = []
    for name, obj in _public_callables():
        if inspect.isclass(obj):
            missing += [f"{name}.{m}" for m, f in _members(obj) if not _returns_annotated(f)]
            init = vars(obj).get("__init__")
            if init is not None and not _returns_annotated(init):
                missing.append(f"{name}.__init__")
        elif not _returns_annotated(obj):
            missing.append(name)
    assert not missing, missing


def test_the_checks_can_fail():
    def bare(x):
        """No example."""
    def typed(x: float) -> float:
        """An example.

        Examples
        --------
        >>> typed(1.0)
        1.0
        """
        return x
    assert not _has_examples(bare) and _has_examples(typed)
    assert not _returns_annotated(bare) and _returns_annotated(typed)


def test_the_package_ships_its_type_marker():
    import tomllib
    from pathlib import Path
    root = Path(dynstiff.__file__).parent
    assert (root / "py.typed").is_file()
    data = tomllib.loads((root.parent / "pyproject.toml").read_text())
    assert "py.typed" in data["tool"]["setuptools"]["package-data"]["dynstiff"]
    assert "mypy dynstiff" in (root.parent / ".ci" / "run").read_text()
