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
