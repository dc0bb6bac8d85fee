"""Text helpers (dynstiff/_text.py)."""

import numpy as np
import pytest

from dynstiff._text import counted


@pytest.mark.parametrize("n, want", [(0, "0 cables"), (1, "1 cable"), (2, "2 cables"),
                                     (8, "8 cables"), (np.int64(1), "1 cable")])
def test_counted_is_singular_for_one_only(n, want):
    assert counted(n, "cable") == want
