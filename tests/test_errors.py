"""Exception and warning types (dynstiff/errors.py): their attributes and the stack level
that points a warning at the user's line."""

import os
import warnings

import pytest

import dynstiff as ds
from dynstiff import errors


def _package_functions():
    """Two functions whose code reports a file inside the package, outer -> inner, the inner
    one warning with ``user_stacklevel()`` and returning it (as the package's guards do)."""
    package = os.path.dirname(os.path.abspath(errors.__file__))
    src = ("import warnings\n"
           "from dynstiff.errors import user_stacklevel\n"
           "def inner():\n"
           "    level = user_stacklevel()\n"
           "    warnings.warn('probe', UserWarning, stacklevel=level)\n"
           "    return level\n"
           "def outer():\n"
           "    return inner()\n")
    scope = {}
    exec(compile(src, os.path.join(package, "_stacklevel_probe.py"), "exec"), scope)
    return scope["outer"]


def test_user_stacklevel_counts_the_package_frames_above_the_caller():
    """Called from the test itself: level 1 (the caller's own line); called two package
    frames deep: level 3, and the warning lands on the test's line. A mutation-testing run
    (MUTANT_UNDER_TEST set) puts the tool's own frames between caller and library, so
    there the levels are not compared (the normal run compares them)."""
    if "MUTANT_UNDER_TEST" in os.environ:
        pytest.skip("the mutation tool's frames stand between the package's frames")
    assert errors.user_stacklevel() == 1
    outer = _package_functions()
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = _line() + 1
        level = outer()
    assert level == 3
    assert len(rec) == 1
    assert (os.path.abspath(rec[0].filename), rec[0].lineno) == (os.path.abspath(__file__),
                                                                  line)


def _line():
    import sys
    return sys._getframe(1).f_lineno


def test_interrupted_defaults_and_attributes():
    exc = errors.Interrupted("stopped")
    assert (exc.saved, exc.total, str(exc)) == (0, 0, "stopped")
    assert isinstance(exc, KeyboardInterrupt)
    exc = errors.Interrupted("stopped at 3 of 8", saved=3, total=8)
    assert (exc.saved, exc.total) == (3, 8)


def test_error_attributes_and_defaults():
    assert errors.ConvergenceError("x").residual is None
    inf = errors.InfeasiblePoseError("no statics")
    assert (inf.cause, inf.remedies, inf.cable) == (None, {}, None)
    remedies = {"t_min": 10.0}
    inf = errors.InfeasiblePoseError("no statics", cause="wrench", remedies=remedies, cable=2)
    assert (inf.cause, inf.remedies, inf.cable) == ("wrench", {"t_min": 10.0}, 2)
    assert inf.remedies is not remedies                     # a copy
    assert errors.CalibrationWarning("w").cause is None
    assert errors.CalibrationError("e", cause="bound").cause == "bound"
    w = errors.ClosedFormWarning("m", cable=1, cause="sag")
    assert (w.cable, w.cause) == (1, "sag")
    assert errors.ClosedFormWarning("m").cable is None


@pytest.mark.parametrize("name", errors.__all__)
def test_every_type_is_exported_and_derives_from_the_base(name):
    t = getattr(ds.errors, name)
    base = ds.DynstiffWarning if issubclass(t, Warning) else (ds.DynstiffError,
                                                                  KeyboardInterrupt)
    assert issubclass(t, base)
