"""The tension distribution's active-set method (dynstiff/robot/distribution.py, theory.md
§13.6) on problems where a zero lower limit lets any start pass the box test: every start,
warm or from the LP, must end at the brute-force optimum (the 3^n active sets enumerated)."""

import itertools

import numpy as np
import pytest

from dynstiff.errors import SlackCableError
from dynstiff.robot.distribution import _closest_in_box, distribution_with_active_set


def optimum(W, w, lo, hi, r):
    """min ||t - r|| subject to W t = w, lo <= t <= hi, over every active set."""
    best, best_t = np.inf, None
    for state in itertools.product((0, 1, 2), repeat=W.shape[1]):
        state = np.array(state)
        t = np.where(state == 1, lo, np.where(state == 2, hi, 0.0)).astype(float)
        free = state == 0
        if np.any(~np.isfinite(t[~free])) or free.sum() < np.linalg.matrix_rank(W):
            continue
        Wf = W[:, free]
        t[free] = r[free] + np.linalg.lstsq(Wf, w - W[:, ~free] @ t[~free] - Wf @ r[free],
                                            rcond=None)[0]
        if np.linalg.norm(W @ t - w) > 1e-8 * max(1.0, np.abs(w).max()) \
                or np.any(t < lo - 1e-8) or np.any(t > hi + 1e-8):
            continue
        if np.sum((t - r) ** 2) < best:
            best, best_t = np.sum((t - r) ** 2), t
    return best_t


@pytest.mark.parametrize("hi", [2.5, np.inf])
def test_zero_lower_limits_every_start_ends_at_the_optimum(hi):
    rng = np.random.default_rng(11)
    tried = 0
    for _ in range(200):
        W = rng.normal(size=(3, 6))
        w = W @ rng.uniform(0.0, 3.0, 6)
        r = rng.uniform(0.5, 2.0, 6)
        try:
            cold, sides = distribution_with_active_set(W, w, 0.0, hi, r, warm=False)
        except SlackCableError:
            continue
        if not np.any(sides):
            continue
        tried += 1
        ref = optimum(W, w, np.zeros(6), np.full(6, hi), r)
        np.testing.assert_allclose(cold, ref, rtol=0, atol=1e-8)
        for start in (None, sides, -sides, np.roll(sides, 1), np.where(sides == 0, -1, sides)):
            t, s = distribution_with_active_set(W, w, 0.0, hi, r, start)
            np.testing.assert_allclose(t, ref, rtol=0, atol=1e-8)
            np.testing.assert_array_equal(s, sides)
    assert tried >= 10


def test_the_box_method_from_a_feasible_interior_point():
    """_closest_in_box from a feasible point inside the box, for random problems whose
    optimum has bounds active: the optimum, and the sides it ends with (the steps go
    towards the target, stopping at the first bound met)."""
    rng = np.random.default_rng(5)
    tried = 0
    for _ in range(60):
        W = rng.normal(size=(2, 5))
        t0 = rng.uniform(1.2, 1.8, 5)                 # strictly inside [1, 2]
        w = W @ t0
        r = rng.uniform(0.0, 3.0, 5)
        ref = optimum(W, w, np.ones(5), np.full(5, 2.0), r)
        t, sides = _closest_in_box(W, w, np.ones(5), np.full(5, 2.0), r, t0, 1e-9)
        np.testing.assert_allclose(t, ref, rtol=0, atol=1e-8)
        np.testing.assert_array_equal(sides, np.where(np.isclose(ref, 1.0, atol=1e-9), -1,
                                                      np.where(np.isclose(ref, 2.0, atol=1e-9),
                                                               1, 0)))
        tried += np.any(sides != 0)
    assert tried >= 20


def test_a_unique_distribution_outside_the_limits_is_named_to_six_decimals():
    from dynstiff.robot.distribution import tension_distribution
    W = np.eye(2)
    with pytest.raises(SlackCableError) as err:
        tension_distribution(W, np.array([0.12345678, 3.5]), 1.0, 500.0)
    assert str(err.value) == ("the unique tension distribution [0.123457, 3.5] N violates "
                              "the limits [1, 500] N")
