"""Small vector kernels (dynstiff/_vec.py)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from dynstiff._vec import cross

finite = st.floats(-1e6, 1e6, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(arrays(float, (4, 3), elements=finite), arrays(float, (4, 3), elements=finite))
def test_cross_equals_numpy_for_single_vectors_and_stacks(a, b):
    np.testing.assert_array_equal(cross(a, b), np.cross(a, b))
    np.testing.assert_array_equal(cross(a[0], b[0]), np.cross(a[0], b[0]))
    np.testing.assert_array_equal(cross(a, b[0]), np.cross(a, b[0]))


def test_cross_broadcasts_over_several_leading_axes():
    """Stacks of shape (2, 3, 3) against (3, 3): the components stay on the last axis."""
    rng = np.random.default_rng(4)
    a, b = rng.normal(size=(2, 3, 3)), rng.normal(size=(3, 3))
    np.testing.assert_array_equal(cross(a, b), np.cross(a, b))
