"""Forces and energy of the lumped time-domain model (dynstiff/timedomain/dynamics.py):
the residual the time stepping integrates is minus the gradient of the potential energy the
energy ledger books (theory.md §7.1, §7.3)."""

import numpy as np
import pytest

from dynstiff.lumped import LumpedMassModel
from dynstiff.timedomain.dynamics import Frame, node_mass_vector, potential_energy


@pytest.fixture(scope="module")
def lumped(cogiro, cogiro_eq):
    mm = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=5)
    return mm, mm.equilibrium(initial_pose=cogiro.pose)


def _energy(mm, pose, interior):
    X = np.concatenate([x.ravel() for x in interior])
    elastic, gravity, *_ = potential_energy(mm, Frame(mm, pose), X)
    return elastic + gravity


def test_residual_is_minus_the_gradient_of_the_potential(lumped):
    """Away from equilibrium, along random directions of every DOF (platform translations and
    rotations, interior nodes): dV/de = -R . d, central differences agree to 1e-7."""
    mm, st = lumped
    rng = np.random.default_rng(3)
    pose, interior = mm.displaced(st.pose, st.interior, 2e-3 * rng.standard_normal(mm.n_dof))
    R = mm.residual(pose, interior)
    for _ in range(3):
        d = rng.standard_normal(mm.n_dof)
        h = 1e-6
        Vp = _energy(mm, *mm.displaced(pose, interior, h * d))
        Vm = _energy(mm, *mm.displaced(pose, interior, -h * d))
        slope = (Vp - Vm) / (2 * h)
        assert slope == pytest.approx(-R @ d, rel=1e-6, abs=1e-7 * np.abs(R).max())


def test_potential_is_stationary_at_equilibrium_and_nodes_carry_their_mass(lumped):
    mm, st = lumped
    rng = np.random.default_rng(5)
    d = rng.standard_normal(mm.n_dof)
    h = 1e-5
    V0 = _energy(mm, st.pose, st.interior)
    Vp = _energy(mm, *mm.displaced(st.pose, st.interior, h * d))
    Vm = _energy(mm, *mm.displaced(st.pose, st.interior, -h * d))
    K = mm.tangent_stiffness(st.pose, st.interior).toarray()
    curvature = (Vp - 2 * V0 + Vm) / h**2                 # d^T K d at the equilibrium
    # stationary: the slope (measured 6e-5 J, the O(h^2) difference error) is far below the
    # curvature times the step (47 J); one newton of unbalanced force would give ~2 J
    assert abs(Vp - Vm) / (2 * h) < 1e-3 * abs(curvature) * h
    assert curvature == pytest.approx(d @ (0.5 * (K + K.T)) @ d, rel=1e-4)
    m = node_mass_vector(mm)
    assert m.size == mm.n_dof - mm.n_free
    assert m.sum() == pytest.approx(3 * sum(                 # x, y, z of every interior node
        c.mass_per_length * l0 * (N - 1) for c, l0, N in
            zip(mm.robot.cables, mm.segment_lengths, mm.segments)), rel=1e-14)


def test_axial_dashpot_stacked_equals_loop_and_dissipates_its_power(lumped):
    """The stacked axial dashpot (chains of equal N at once) gives the cable-by-cable forces,
    and its power is the dissipation -sum c_ax l0 (d eps/dt)^2 over the taut segments."""
    from dynstiff.models.lumped_statics import segment_forces
    from dynstiff.timedomain import dynamics as td
    mm, st = lumped
    rng = np.random.default_rng(5)
    pose, interior = mm.displaced(st.pose, st.interior, 1e-3 * rng.standard_normal(mm.n_dof))
    X = np.concatenate([x.ravel() for x in interior])
    v = rng.standard_normal(mm.n_dof)
    frame = Frame(mm, pose)
    tw = td.twist_of(mm, v)
    c_ax = np.linspace(0.0, 30.0, mm.robot.n_cables)         # the first cable undamped
    F = td._axial_dashpot_stacked(mm, frame, X, v, tw, c_ax)
    np.testing.assert_allclose(F, td._axial_dashpot_loop(mm, frame, X, v, tw, c_ax),
                               rtol=1e-12, atol=1e-12 * np.abs(F).max())
    power = 0.0
    for i, xi in enumerate(td.interior_views(mm, X)):
        nodes = np.vstack((mm.robot.anchors[i], xi, frame.B[i]))
        vi = v[mm.offsets[i]:mm.offsets[i] + xi.size].reshape(-1, 3)
        vel = np.vstack((np.zeros(3), vi, tw[:3] + np.cross(tw[3:], frame.r[i])))
        l0 = mm.segment_lengths[i]
        units, lengths, _ = segment_forces(nodes, l0, mm.robot.cables[i].EA)
        rate = np.einsum("ij,ij->i", units, np.diff(vel, axis=0)) / l0
        power -= c_ax[i] * l0 * np.sum(np.where(lengths > l0, rate**2, 0.0))
    assert power < 0
    assert F @ v == pytest.approx(power, rel=1e-10)
