"""Compiled kernels of the lumped-mass chains (dynstiff/compiled/chain.py, theory.md §14.4)
against the numpy path: forces, dashpots, extreme tensions and strains."""

import numpy as np
import pytest

from dynstiff import compiled
from dynstiff.lumped import LumpedMassModel, TimeDamping
from dynstiff.timedomain import dynamics as td

pytest.importorskip("numba")


def test_extremes_see_a_slack_segment(cogiro, cogiro_eq):
    """A chain pushed together has a slack segment: smallest tension 0, strain < 0 there."""
    from dynstiff.compiled.chain import robot_chain_forces
    X = np.array([1.0, 0, 0, 1.5, 0, 0])                 # segments 1, 0.5, 1.5 m
    z3 = np.zeros((1, 3))
    inner, _, W, _, t_max, t_min, strain = robot_chain_forces(
        z3, X, np.array([[3.0, 0, 0]]), z3, np.zeros(6), np.zeros(6), np.array([3]),
        np.array([1.0]), np.array([100.0]), np.array([0.0]), z3, np.zeros(3), np.zeros(3))
    assert t_min == 0.0 and t_max == pytest.approx(50.0) and strain == pytest.approx(0.5)
    np.testing.assert_allclose(inner.reshape(2, 3), [[0.0, 0, 0], [50.0, 0, 0]])
    np.testing.assert_allclose(W, [-50.0, 0, 0, 0, 0, 0])


@pytest.mark.parametrize("c_first, segments", [(0.0, 6), (12.0, 6),
                                               (12.0, [1, 2, 3, 4, 5, 6, 7, 3])])
def test_compiled_forces_equal_the_numpy_path(cogiro, cogiro_eq, monkeypatch, c_first,
                                              segments):
    mm = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=segments)
    st = mm.equilibrium(initial_pose=cogiro.pose)
    rng = np.random.default_rng(11)
    pose, interior = mm.displaced(st.pose, st.interior, 2e-3 * rng.standard_normal(mm.n_dof))
    pose = td.FastPose(pose.position, pose.rotation)
    X = np.concatenate([x.ravel() for x in interior])
    v = rng.standard_normal(mm.n_dof)
    c_ax = np.r_[c_first, np.linspace(5.0, 30.0, mm.robot.n_cables - 1)]
    out = {}
    for fast in (True, False):
        if not fast:
            monkeypatch.setattr(compiled, "load", lambda name: None)
        dyn = td.Dynamics(mm, TimeDamping(axial=c_ax), None, None)
        F, fe, fd, t_max, _ = dyn.forces(pose, X, v, 0.0)
        out[fast] = (F, fd, t_max, dyn.extremes)
    (F1, fd1, t1, e1), (F0, fd0, t0, e0) = out[True], out[False]
    assert np.abs(fd0).max() > 1e-3 * np.abs(F0).max()           # the dashpots act
    np.testing.assert_allclose(F1, F0, rtol=0, atol=1e-12 * np.abs(F0).max())
    np.testing.assert_allclose(fd1, fd0, rtol=0, atol=1e-12 * np.abs(fd0).max())
    assert t1 == pytest.approx(t0, rel=1e-14)
    np.testing.assert_allclose(e1, e0, rtol=1e-12, atol=1e-15)


