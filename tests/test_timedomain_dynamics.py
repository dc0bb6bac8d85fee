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


def test_slack_segments_are_those_without_tension(cogiro, cogiro_eq):
    """Straight chains whose segments carry 0.5 N are taut (none reported slack, 0.5 N at
    both ends); a chain a little shorter than its unstretched length has zero tension: slack,
    reported at its first segment."""
    from dynstiff.timedomain.dynamics import interior_views
    rob, pose, N = cogiro.robot, cogiro_eq.pose, 4
    B, _ = rob.attachment_points(pose)
    chord = np.linalg.norm(B - rob.anchors, axis=1)
    EA = np.array([c.EA for c in rob.cables])
    L0 = chord / (1.0 + 0.5 / EA)                                 # T = 0.5 N when straight
    L0[5] = chord[5] * (1.0 + 1e-9)                               # shorter than l0: T = 0
    mm = LumpedMassModel(rob, L0, segments=N)
    X = np.concatenate([(a + np.outer(np.arange(1, N) / N, b - a)).ravel()
                        for a, b in zip(rob.anchors, B)])
    assert [x.shape for x in interior_views(mm, X)] == [(N - 1, 3)] * 8
    _, _, t_end, t_anchor, slack, strain = potential_energy(mm, Frame(mm, pose), X)
    np.testing.assert_allclose(np.delete(t_end, 5), 0.5, rtol=1e-6)
    np.testing.assert_allclose(np.delete(t_anchor, 5), 0.5, rtol=1e-6)
    assert t_end[5] == 0.0 and slack == [(5, 0)]
    assert strain == pytest.approx(0.5 / EA.min(), rel=1e-6)


def test_model_at_other_lengths_and_an_increment_about_x_alone(lumped):
    """model_at keeps the model for equal lengths and rebuilds it for others; an increment
    that rotates about x alone turns the platform (composed exactly, as Pose.moved)."""
    from dynstiff.timedomain.dynamics import FastPose, advance, model_at
    mm, st = lumped
    assert model_at(mm, mm.unstretched_lengths.copy()) is mm
    other = model_at(mm, 1.001 * mm.unstretched_lengths)
    np.testing.assert_array_equal(other.unstretched_lengths, 1.001 * mm.unstretched_lengths)
    assert list(other.segments) == list(mm.segments) and other.robot is mm.robot
    pose = FastPose(st.pose.position, st.pose.rotation)
    X = np.concatenate([x.ravel() for x in st.interior])
    dx = np.zeros(mm.n_dof)
    dx[3] = 1e-3                                                   # rx only
    moved, X2 = advance(mm, pose, X, dx)
    want = st.pose.moved(np.r_[0.0, 0.0, 0.0, 1e-3, 0.0, 0.0])
    np.testing.assert_allclose(moved.rotation, want.rotation, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(moved.position, st.pose.position)
    np.testing.assert_array_equal(X2, X)


def test_loads_are_six_floats_whatever_the_excitation_returns():
    """An excitation may return integers or numeric text: the loads are float64; anything but
    6 finite numbers is refused with the time."""
    from dynstiff.errors import InvalidParameterError
    from dynstiff.timedomain.dynamics import load_at
    f = load_at(lambda t: [0, 0, 1, 0, 0, 0], 0.0)
    assert f.dtype == np.float64 and f.tolist() == [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    assert load_at(lambda t: ["0", "0", "2.5", "0", "0", "0"], 0.0)[2] == 2.5
    with pytest.raises(InvalidParameterError, match=r"6 real finite loads .* at t = 0.5 s"):
        load_at(lambda t: [0.0, np.inf, 0.0, 0.0, 0.0, 0.0], 0.5)
