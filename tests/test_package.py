"""The package as imported (dynstiff/__init__.py): `import dynstiff` stays light, checked in
a fresh interpreter."""

import subprocess
import sys

import pytest

pytestmark = pytest.mark.integration


def test_import_does_not_load_matplotlib_or_pandas():
    code = ("import sys, dynstiff; "
            "bad = [m for m in ('matplotlib', 'pandas', 'mpmath') if m in sys.modules]; "
            "print(','.join(bad))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_import_does_not_load_heavy_scipy_submodules_or_numba():
    """scipy.optimize alone costs ~1 s to import on a loaded machine; the solvers import it
    (and scipy.linalg, scipy.sparse, numba) inside the functions that use it."""
    heavy = ("scipy.optimize", "scipy.linalg", "scipy.sparse", "scipy.signal", "numba")
    code = ("import sys, dynstiff; "
            f"bad = [m for m in {heavy!r} if m in sys.modules]; "
            "print(','.join(bad))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
    # the check can fail: a submodule that is imported is reported
    code = ("import sys, dynstiff, scipy.optimize; "
            f"print(','.join(m for m in {heavy!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "scipy.optimize" in out.stdout
