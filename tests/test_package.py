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


@pytest.mark.parametrize("first", ["dynstiff", "xarray"])
def test_xarray_accessor_works_in_either_import_order_without_loading_xarray(first):
    pytest.importorskip("xarray")
    second = "xarray" if first == "dynstiff" else "dynstiff"
    code = (f"import sys; import {first}; "
            "print('xarray' in sys.modules, 'pandas' in sys.modules); "
            f"import {second}; import xarray as xr; "
            "print(type(xr.Dataset().dynstiff).__name__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded, name = out.stdout.split("\n")[:2]
    if first == "dynstiff":
        assert loaded == "False False"           # import dynstiff alone loads neither
    assert name == "WorkspaceAccessor"
