"""The steps of inverse statics' fixed point (dynstiff/robot/statics.py, theory.md §4), each
against values computed here from the catenary's own formulas: a cable's end force direction
and its tension margins along the span."""

import numpy as np


def test_end_quantities_take_the_tension_along_the_whole_span():
    """Three catenaries of one weight w0 L0 = 100 N, H = 100 N: (a) the lowest point inside
    the span (V0 = -40 N at A, Vb = 60 N at B): the least tension is H there; (b) rising all
    the way (V0 = 20 N): the least is at A, hypot(H, 20); (c) falling all the way (V0 = -150,
    Vb = -50 N): the least is at B, hypot(H, 50), and the largest at A. lo = T_B - min T and
    hi = max T - T_B along the cable; the unit force on B is -(H e_h + Vb e_z) / T_B."""
    from dynstiff.robot.statics import _end_quantities
    anchors = np.zeros((3, 3))
    ends = np.array([[3.0, 4.0, 1.0], [0.0, 2.0, -1.0], [-6.0, 0.0, 0.5]])
    H = np.full(3, 100.0)
    V0 = np.array([-40.0, 20.0, -150.0])
    L0, w0 = np.full(3, 10.0), np.full(3, 10.0)
    u, lo, hi = _end_quantities(anchors, ends, H, V0, L0, w0)
    Vb = V0 + 100.0
    T_A, T_B = np.hypot(H, V0), np.hypot(H, Vb)
    T_min = np.array([100.0, np.hypot(100.0, 20.0), np.hypot(100.0, 50.0)])
    np.testing.assert_allclose(lo, T_B - T_min, rtol=1e-14, atol=1e-12)
    np.testing.assert_allclose(hi, np.maximum(T_A, T_B) - T_B, rtol=1e-14, atol=1e-12)
    assert lo[0] > 0 and lo[2] == 0 and hi[1] == 0 and hi[2] > 0
    e_h = ends[:, :2] / np.linalg.norm(ends[:, :2], axis=1)[:, None]
    want = -np.column_stack([H[:, None] * e_h, Vb]) / T_B[:, None]
    np.testing.assert_allclose(u, want, rtol=1e-14, atol=1e-15)
