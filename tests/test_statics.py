"""Robot statics (dynstiff/statics.py, theory.md §4): inverse and forward statics, the
workspace edge, and the tension distribution.

The tension distribution (closest to a reference within the limits) is checked against an
independent brute-force solution: every assignment of the cables to {free, at t_min, at
t_max} is solved as an equality-constrained least-squares problem, and the best feasible one
is the optimum (the objective is strictly convex, so it is unique)."""

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.errors import InvalidParameterError, SlackCableError
from dynstiff.statics import tension_distribution


# ----------------------------------------------------------------- tension distribution
def brute_force(W, w, lo, hi, r):
    """Enumerate the 3^n active sets [N]."""
    k, n = W.shape
    best, best_t = np.inf, None
    for state in itertools.product((0, 1, 2), repeat=n):
        state = np.array(state)
        t = np.where(state == 1, lo, np.where(state == 2, hi, 0.0))
        free = state == 0
        if free.sum() < np.linalg.matrix_rank(W):
            continue
        b = w - W[:, ~free] @ t[~free]
        Wf = W[:, free]
        t[free] = r[free] + np.linalg.lstsq(Wf, b - Wf @ r[free], rcond=None)[0]
        if np.linalg.norm(W @ t - w) > 1e-8 * max(1.0, np.abs(w).max()):
            continue
        if np.any(t < lo - 1e-8) or np.any(t > hi + 1e-8):
            continue
        f = np.sum((t - r) ** 2)
        if f < best:
            best, best_t = f, t
    return best_t


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
    ref = brute_force(W, w, np.full(n, lo), np.full(n, hi), r)
    np.testing.assert_allclose(W @ t, w, atol=1e-8 * np.abs(w).max())
    assert np.all(t >= lo - 1e-7) and np.all(t <= hi + 1e-7)
    np.testing.assert_allclose(t, ref, atol=1e-6)


def test_infeasible_wrench_is_reported():
    rng = np.random.default_rng(3)
    W = rng.normal(size=(6, 8))
    w = W @ np.full(8, 1000.0)
    with pytest.raises(SlackCableError, match="wrench-feasible"):
        tension_distribution(W, w, 100.0, 200.0)


# ---------------------------------------------------------- inverse and forward statics
def test_inverse_then_forward_statics_round_trip(cogiro, cogiro_eq):
    assert cogiro_eq.residual < 1e-10
    fwd = cogiro.robot.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    np.testing.assert_allclose(fwd.pose.position, cogiro.pose.position, atol=1e-9)
    np.testing.assert_allclose(fwd.pose.rotation, cogiro.pose.rotation, atol=1e-9)
    t_min, t_max = cogiro.robot.tension_limits
    assert np.all(cogiro_eq.tensions >= t_min - 1e-9) and np.all(cogiro_eq.tensions <= t_max)


def test_forward_statics_with_held_dofs_needs_initial_pose(cogiro, cogiro_eq):
    p = cogiro.robot.platform
    planar = ds.Platform(p.mass, p.center_of_mass, p.inertia, free_dofs=("x", "z", "ry"))
    rob = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments, cogiro.robot.cables, planar,
                   tension_limits=cogiro.robot.tension_limits)
    with pytest.raises(InvalidParameterError, match="initial_pose"):
        rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    eq = rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths,
                         initial_pose=cogiro.pose)
    np.testing.assert_allclose(eq.pose.position, cogiro.pose.position, atol=1e-9)
    m = ds.FrequencyModel(eq)
    K = m.dynamic_stiffness([0.0, 10.0])
    np.testing.assert_allclose(K, K.transpose(0, 2, 1), atol=1e-9 * np.abs(K).max())


def test_pose_outside_workspace_raises(cogiro):
    with pytest.raises(SlackCableError, match="pose"):
        cogiro.robot.equilibrium(pose=[9.0, 0.0, 1.0])


def test_cogiro_near_the_workspace_edge_converges():
    """(5, 3, 1) m: two cables at t_min; the fixed point of directions and tensions needs an
    exact distribution (an inexact one stalled the iteration at a 5e-6 wrench residual)."""
    eq = ds.load_scene("cogiro").robot.equilibrium(pose=[5.0, 3.0, 1.0])
    assert eq.residual < 1e-10
    assert eq.min_tensions.min() == pytest.approx(100.0, abs=1e-6)


def test_bad_tolerance_and_iteration_count_name_the_argument(cogiro):
    with pytest.raises(InvalidParameterError, match="tol must be finite"):
        cogiro.robot.equilibrium(pose=cogiro.pose, tol=float("nan"))
    with pytest.raises(InvalidParameterError, match="max_iter must be an integer >= 1"):
        cogiro.robot.equilibrium(pose=cogiro.pose, max_iter=0)
    with pytest.raises(InvalidParameterError, match="max_iter"):
        cogiro.robot.equilibrium(unstretched_lengths=[12.0] * 8, max_iter=2.5)
