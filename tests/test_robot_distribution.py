"""The tension distribution (dynstiff/robot/distribution.py, theory.md §4, §13.6): the
tensions closest to a reference within the limits, checked against an independent brute-force
solution (every assignment of the cables to {free, at t_min, at t_max} solved as an
equality-constrained least-squares problem; the best feasible one is the optimum, unique as
the objective is strictly convex), from every start of its active-set method (warm, from the
LP, from inside the box, and with zero lower limits, which let any start pass the box test),
and its messages where there is none."""

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dynstiff.errors import SlackCableError
from dynstiff.robot.distribution import (
    _closest_in_box,
    distribution_with_active_set,
    tension_distribution,
)


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


# ------------------------------------------- against the brute-force optimum, messages
@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2 ** 31 - 1), n=st.sampled_from([7, 8]))
def test_matches_brute_force_on_random_structure_matrices(seed, n):
    rng = np.random.default_rng(seed)
    k = 6
    W = rng.normal(size=(k, n))
    lo, hi = 100.0, 600.0
    t_feasible = rng.uniform(lo, hi, n)
    # push a few cables to the limits so that bounds are active at the optimum
    t_feasible[rng.random(n) < 0.3] = lo
    w = W @ t_feasible
    r = np.full(n, lo) if seed % 2 else rng.uniform(lo, hi, n)
    t = tension_distribution(W, w, lo, hi, r)
    ref = optimum(W, w, np.full(n, lo), np.full(n, hi), r)
    np.testing.assert_allclose(W @ t, w, atol=1e-8 * np.abs(w).max())
    assert np.all(t >= lo - 1e-7) and np.all(t <= hi + 1e-7)
    np.testing.assert_allclose(t, ref, atol=1e-6)


def test_infeasible_wrench_is_reported():
    rng = np.random.default_rng(3)
    W = rng.normal(size=(6, 8))
    w = W @ np.full(8, 1000.0)
    with pytest.raises(SlackCableError, match="wrench-feasible"):
        tension_distribution(W, w, 100.0, 200.0)


def test_infeasible_distributions_name_the_limits_uniform_or_per_cable():
    """A square system has one distribution; when it leaves the limits the error gives it and
    the limits, as [lo, hi] when all cables share them, else per cable."""
    from dynstiff.robot.statics import tension_distribution
    W = np.array([[1.0, -1.0], [1.0, 1.0]])
    w = np.array([0.0, -2.0])                               # t = (-1, -1) N
    with pytest.raises(SlackCableError) as err:
        tension_distribution(W, w, 10.0, 500.0)
    assert str(err.value) == ("the unique tension distribution [-1.0, -1.0] N violates the "
                              "limits [10, 500] N")
    with pytest.raises(SlackCableError) as err:
        tension_distribution(W, w, [10.0, 20.0], [500.0, 400.0])
    assert str(err.value).endswith("limits [[10.0, 20.0], [500.0, 400.0]] N")
    with pytest.raises(SlackCableError) as err:
        tension_distribution(W, w, [10.0, 10.0], [500.0, 400.1234])
    assert str(err.value).endswith("limits [[10.0, 10.0], [500.0, 400.123]] N")
    with pytest.raises(SlackCableError) as err:
        tension_distribution(W, w, [10.0, 20.5678], [500.0, 500.0])
    assert str(err.value).endswith("limits [[10.0, 20.568], [500.0, 500.0]] N")
    W3 = np.array([[1.0, -1.0, 0.5]])                       # redundant: LP finds none
    with pytest.raises(SlackCableError, match=r"no tension distribution within \[10, 20\] N"):
        tension_distribution(W3, np.array([100.0]), 10.0, 20.0)


def test_distribution_from_any_active_set_is_the_optimum():
    """Started from no active set (then from the violated limits), a right, a wrong or an
    infeasible one, the distribution is the one started from the LP (bitwise: the result
    depends on the final active set alone) and the brute-force optimum."""
    from dynstiff.robot import statics

    rng = np.random.default_rng(7)
    tried = 0
    for _ in range(60):
        W = rng.normal(size=(3, 6))
        w = W @ rng.uniform(0.0, 3.0, 6)
        lo, hi, r = 1.0, 2.5, rng.uniform(0.5, 2.0, 6)
        try:
            cold, sides = statics._distribution(W, w, lo, hi, r, warm=False)
        except SlackCableError:
            continue
        if not np.any(sides):
            continue
        tried += 1
        np.testing.assert_allclose(cold, optimum(W, w, np.full(6, lo), np.full(6, hi), r),
                                   rtol=0, atol=1e-8)
        for start in (None, sides, -sides, np.roll(sides, 1), np.where(sides == 0, -1, sides)):
            t, s = statics._distribution(W, w, lo, hi, r, start)
            np.testing.assert_array_equal(t, cold)
            np.testing.assert_array_equal(s, sides)
    assert tried >= 10


def test_active_set_method_that_cannot_settle_says_so_with_its_residual():
    """With no multiplier ever accepted (tol = -inf) the active-set loop drops and retakes a
    bound until its step limit: it raises ConvergenceError naming the balance residual of
    its last (feasible) iterate, not a wrong distribution."""
    from dynstiff.errors import ConvergenceError
    from dynstiff.robot.distribution import _closest_in_box
    W = np.array([[1.0, 1.0, 1.0]])
    lb, ub = np.array([2.0, 0.0, 0.0]), np.full(3, 5.0)
    t, bound = np.array([2.0, 0.5, 0.5]), np.array([2.0, np.nan, np.nan])
    with pytest.raises(ConvergenceError, match=r"did not settle in 40 steps \(balance "
                                               r"residual 0\.000e\+00 N\)") as err:
        _closest_in_box(W, np.array([3.0]), lb, ub, np.zeros(3), t, -np.inf, bound)
    assert err.value.residual == 0.0


def test_active_set_method_from_inside_the_box_returns_the_free_solution():
    """From a feasible start whose minimum-distance solution is inside the box, no bound
    becomes active: that solution, with every side 0."""
    from dynstiff.robot.distribution import _closest_in_box
    W = np.array([[1.0, 1.0, 1.0]])
    t, sides = _closest_in_box(W, np.array([3.0]), np.zeros(3), np.full(3, 5.0),
                               np.array([0.5, 1.0, 1.5]), np.array([1.0, 1.0, 1.0]), 1e-9)
    np.testing.assert_allclose(t, [0.5, 1.0, 1.5], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(sides, [0, 0, 0])
    assert sides.dtype.kind == "i"


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2 ** 31 - 1), n=st.sampled_from([4, 6, 8]),
       start=st.sampled_from(["interior", "active"]))
def test_active_set_method_from_any_feasible_start_is_the_brute_force_optimum(seed, n, start):
    """_closest_in_box itself (Nocedal & Wright Alg. 16.3) from a feasible start inside the
    box, or from one with a random set of tensions held at their bounds: it takes steps,
    adds and drops bounds, and ends at the brute-force optimum; the tensions it reports
    held (-1, +1) are exactly at their lower or upper bound."""
    from dynstiff.robot.distribution import _closest_in_box
    rng = np.random.default_rng(seed)
    k = 3
    W = rng.normal(size=(k, n))
    lo, hi = np.full(n, 100.0), np.full(n, 600.0)
    t0 = rng.uniform(150.0, 550.0, n)
    bound = np.full(n, np.nan)
    if start == "active":
        held = rng.random(n) < 0.3
        bound[held] = np.where(rng.random(held.sum()) < 0.5, lo[held], hi[held])
        t0[held] = bound[held]
    w = W @ t0
    r = rng.uniform(0.0, 800.0, n)           # references inside and outside the box
    ref = optimum(W, w, lo, hi, r)
    t, sides = _closest_in_box(W, w, lo, hi, r, t0, 1e-9, bound if start == "active"
                               else None)
    np.testing.assert_allclose(t, ref, atol=1e-6)
    assert sides.dtype.kind == "i" and set(sides.tolist()) <= {-1, 0, 1}
    np.testing.assert_array_equal(t[sides == -1], lo[sides == -1])
    np.testing.assert_array_equal(t[sides == 1], hi[sides == 1])


def test_limits_equal_for_all_cables_are_written_once_also_when_unbounded():
    """The limits in an infeasibility message: one [lo, hi] pair when every cable has the
    same, an unbounded t_max included (inf - inf is not 0), else the lists per cable."""
    import warnings

    from dynstiff.robot.distribution import _limits
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _limits(np.array([1.0, 1.0]), np.array([np.inf, np.inf])) == "[1, inf]"
        assert _limits(np.array([1.0, 2.0]), np.array([5.0, 5.0])) == "[[1.0, 2.0], [5.0, 5.0]]"
