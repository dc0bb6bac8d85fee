"""The discrete gradient of the lumped robot's potential energy (dynstiff/timedomain/
discrete_gradient.py, theory.md §7.3): exact work over any step, slack and snap included."""

import numpy as np
import pytest
from scipy.integrate import quad_vec
from scipy.linalg import expm

import dynstiff as ds
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.robot.platform import skew
from dynstiff.timedomain.discrete_gradient import (
    discrete_gradient_force,
    rotation_mean,
    secant_elements,
    secant_tension,
)
from dynstiff.timedomain.dynamics import FastPose, Frame, advance, interior_views, potential_energy


@pytest.mark.parametrize("angle", [0.0, 2e-4, 9.9e-3, 1.01e-2, 0.3, 2.5])
def test_rotation_mean_is_the_mean_of_the_rotation_along_the_step(angle):
    """Phi(theta) = int_0^1 exp(s [theta]x) ds, by adaptive quadrature of scipy's expm,
    both sides of the series switch at |theta| = 1e-2."""
    theta = angle * np.array([0.48, -0.6, 0.64])
    ref = quad_vec(lambda s: expm(s * skew(theta)), 0.0, 1.0, epsabs=1e-15, epsrel=1e-14)[0]
    np.testing.assert_allclose(rotation_mean(theta), ref, rtol=0, atol=2e-15)


def test_secant_tension_is_the_mean_tension_over_the_step():
    """[phi(l_b) - phi(l_a)] / (l_b - l_a) with phi = EA / (2 l0) (l - l0)_+^2, on taut,
    slack and switching steps (evaluated here in 50-digit arithmetic); the tension T(l) when
    l_a = l_b."""
    import mpmath
    mpmath.mp.dps = 50
    l0, EA = 2.0, 1e7
    rng = np.random.default_rng(3)
    la = l0 * (1 + rng.uniform(-1e-3, 1e-3, 400))
    lb = l0 * (1 + rng.uniform(-1e-3, 1e-3, 400))

    def phi(x):
        s = max(mpmath.mpf(x) - l0, 0)
        return mpmath.mpf(EA) / (2 * l0) * s * s
    ref = np.array([float((phi(b) - phi(a)) / (mpmath.mpf(b) - mpmath.mpf(a)))
                    for a, b in zip(la, lb)])
    T = secant_tension(la, lb, l0, EA)
    np.testing.assert_allclose(T, ref, rtol=1e-9, atol=1e-9)
    assert (np.sign(la - l0) != np.sign(lb - l0)).sum() > 100        # switches tested
    np.testing.assert_allclose(secant_tension(la, la, l0, EA),
                               EA * np.maximum(la / l0 - 1, 0), rtol=1e-12, atol=1e-12)


@pytest.fixture(scope="module", params=[5, (3, 4, 5, 6, 5, 4)], ids=["equal", "unequal"])
def sixcable(request):
    """The six-cable robot at its equilibrium, with 5 segments per cable (all chains at
    once) or 3 to 6 (chain by chain)."""
    scene = ds.load_scene("sixcable")
    rob = scene.robot
    eq = rob.equilibrium(pose=scene.pose)
    m = LumpedMassModel(rob, [s.unstretched_length for s in eq.states], request.param)
    leq = m.equilibrium(initial_pose=eq.pose)
    pose = FastPose(leq.pose.position, leq.pose.rotation)
    return m, pose, np.concatenate([x.ravel() for x in leq.interior])


def _energy(m, pose, X):
    return sum(potential_energy(m, Frame(m, pose), X)[:2])


@pytest.mark.parametrize("size", [1e-4, 1e-2, 0.3])
def test_the_work_of_the_discrete_gradient_is_the_energy_change(sixcable, size):
    """R_bar . d = -(V(q + d) - V(q)) to 1e-12 of |dV| for random increments, large platform
    rotations and slack segments included; R_bar(q, q) is the model's residual R(q)."""
    m, pose, X = sixcable
    rng = np.random.default_rng(7)
    frame = Frame(m, pose)
    nodes, _ = m.full_nodes(pose, interior_views(m, X))
    g = m.robot.gravity_vector
    R0, t_max, _ = discrete_gradient_force(m, nodes, nodes, frame.r, np.zeros(3), frame.rG, g)
    R, _ = m.residual_unchecked(pose, interior_views(m, X))
    np.testing.assert_allclose(R0, R, rtol=0, atol=1e-9 * np.abs(m.robot.platform.mass * 9.81))
    strain = [np.linalg.norm(np.diff(x, axis=0), axis=1) / l0 - 1
              for x, l0 in zip(nodes, m.segment_lengths)]      # the largest tension, EA e
    # (strains of 1e-4 lose four digits to l - l0, hence 1e-10)
    assert t_max == pytest.approx(max(c.EA * e.max() for c, e in zip(m.robot.cables, strain)),
                                  rel=1e-10)
    slack = 0
    for _ in range(5):
        d = size * rng.normal(size=m.n_dof)
        pose1, X1 = advance(m, pose, X, d)
        nodes1, _ = m.full_nodes(pose1, interior_views(m, X1))
        Rb, _, _ = discrete_gradient_force(m, nodes, nodes1, frame.r, d[3:6], frame.rG, g)
        dV = _energy(m, pose1, X1) - _energy(m, pose, X)
        assert Rb @ d == pytest.approx(-dV, rel=1e-12, abs=1e-9)
        slack += potential_energy(m, Frame(m, pose1), X1)[4] != []
    if size >= 1e-2:
        assert slack > 0                                   # the step crosses l = l0


def test_secant_elements_are_the_derivative_of_the_discrete_gradient(sixcable):
    """Along an increment d, the secant elements give (K_sec / 2) d = -d R_bar / d eps
    (central difference) to 1e-3 on the interior nodes, where the only approximation is the
    symmetric form of the element (module notes); their end forces are the model's at
    d = 0."""
    m, pose, X = sixcable
    rng = np.random.default_rng(11)
    frame = Frame(m, pose)
    g = m.robot.gravity_vector
    nodes, _ = m.full_nodes(pose, interior_views(m, X))
    d = np.zeros(m.n_dof)
    d[m.n_free:] = 1e-3 * rng.normal(size=m.n_dof - m.n_free)
    dx = np.zeros(m.n_dof)
    dx[m.n_free:] = 1e-4 * rng.normal(size=m.n_dof - m.n_free)

    def R_of(e):
        pose1, X1 = advance(m, pose, X, d + e * dx)
        n1, _ = m.full_nodes(pose1, interior_views(m, X1))
        return discrete_gradient_force(m, nodes, n1, frame.r, np.zeros(3), frame.rG, g)[0]
    h = 1e-3
    dR = (R_of(h) - R_of(-h)) / (2 * h)
    pose1, X1 = advance(m, pose, X, d)
    n1, _ = m.full_nodes(pose1, interior_views(m, X1))
    el = secant_elements(m, nodes, n1, np.zeros(6), 1e-3)
    K = m.tangent_unchecked(pose1, interior_views(m, X1), lambda i: 1.0, el)
    Kd = 0.5 * (K @ dx)
    nf = m.n_free
    np.testing.assert_allclose(Kd[nf:], -dR[nf:], rtol=0, atol=1e-3 * np.abs(dR[nf:]).max())
    el0 = secant_elements(m, nodes, nodes, np.zeros(6), 1e-3)
    R, _ = m.residual_unchecked(pose, interior_views(m, X))
    W = m.robot.gravity_wrench(pose)
    W[:3] += sum(F for _, F in el0)
    np.testing.assert_allclose(W[:3], R[:3], rtol=0, atol=1e-6)


def test_the_mean_dashpot_dissipates_and_is_continuous_through_a_switch(sixcable):
    """The axial dashpots enter as the mean force over the step, c_ax theta (l_b - l_a) /
    (h l0) (theta the taut fraction of the step): R_bar . d = -(dV + D) with D = sum c_ax
    theta dl^2 / (h l0) >= 0, and R_bar is continuous as a segment's end length crosses
    l0 (the dashpot of a taut segment, c_ax dl / (h l0), would jump by c_ax |dl| / (h l0),
    17 N here)."""
    m, pose, X = sixcable
    frame = Frame(m, pose)
    g = m.robot.gravity_vector
    nodes, _ = m.full_nodes(pose, interior_views(m, X))
    c_ax, h = np.full(6, 300.0), 1e-3
    rng = np.random.default_rng(5)
    d = 1e-2 * rng.normal(size=m.n_dof)
    pose1, X1 = advance(m, pose, X, d)
    n1, _ = m.full_nodes(pose1, interior_views(m, X1))
    R, _, D = discrete_gradient_force(m, nodes, n1, frame.r, d[3:6], frame.rG, g, c_ax, h)
    dV = _energy(m, pose1, X1) - _energy(m, pose, X)
    assert D > 0 and R @ d == pytest.approx(-(dV + D), rel=1e-12)
    # move one interior node along its segment so that the segment's end length crosses l0
    i, s = 0, 1                                  # cable 0, segment 1 (nodes 1 and 2)
    l0 = m.segment_lengths[i]
    seg = nodes[i][s + 1] - nodes[i][s]
    u = seg / np.linalg.norm(seg)
    shift = np.linalg.norm(seg) - l0             # moving node 2 back by it makes l_b = l0
    vals = []
    for eps in (-1e-11, 1e-11):
        nb = [x.copy() for x in nodes]
        nb[i][s + 1] -= (shift + eps) * u
        nb[i][s + 2:] = nodes[i][s + 2:]
        vals.append(discrete_gradient_force(m, nodes, nb, frame.r, np.zeros(3), frame.rG, g,
                                            c_ax, h)[0])
    assert np.abs(vals[1] - vals[0]).max() < 1e-3                # [N]; a jump would be 17


def test_secant_elements_hold_the_derivative_of_the_mean_dashpot(sixcable):
    """With axial dashpots (c_ax = 3000 N s, h = 1 ms) the elements' axial stiffness gains
    2 c_ax / (h l0) on taut segments, twice the derivative of the mean dashpot force
    c_ax (l_b - l_a) / (h l0): (K_sec / 2) d = -d R_bar / d eps as without dashpots, to
    1e-3 of the change on the interior nodes, of which the dashpots make a third (measured
    37 % of the largest entry)."""
    m, pose, X = sixcable
    rng = np.random.default_rng(11)
    frame = Frame(m, pose)
    g = m.robot.gravity_vector
    nodes, _ = m.full_nodes(pose, interior_views(m, X))
    c_ax, h = np.full(6, 3000.0), 1e-3
    d = np.zeros(m.n_dof)
    d[m.n_free:] = 1e-5 * rng.normal(size=m.n_dof - m.n_free)
    dx = np.zeros(m.n_dof)
    dx[m.n_free:] = 1e-6 * rng.normal(size=m.n_dof - m.n_free)

    def R_of(e, c):
        pose1, X1 = advance(m, pose, X, d + e * dx)
        n1, _ = m.full_nodes(pose1, interior_views(m, X1))
        return discrete_gradient_force(m, nodes, n1, frame.r, np.zeros(3), frame.rG, g, c,
                                       h)[0]
    eps = 1e-3
    dR = (R_of(eps, c_ax) - R_of(-eps, c_ax)) / (2 * eps)
    dR0 = (R_of(eps, None) - R_of(-eps, None)) / (2 * eps)
    pose1, X1 = advance(m, pose, X, d)
    n1, _ = m.full_nodes(pose1, interior_views(m, X1))
    K = m.tangent_unchecked(pose1, interior_views(m, X1), lambda i: 1.0,
                            secant_elements(m, nodes, n1, c_ax, h))
    nf = m.n_free
    Kd = 0.5 * (K @ dx)[nf:]
    assert np.abs(dR - dR0)[nf:].max() > 0.2 * np.abs(dR[nf:]).max()
    np.testing.assert_allclose(Kd, -dR[nf:], rtol=0, atol=1e-3 * np.abs(dR[nf:]).max())


def test_mean_dashpot_acts_over_the_taut_part_of_the_step():
    """c_ax theta (l_b - l_a) / (h l0), theta the fraction of [l_a, l_b] above l0: a segment
    slack over the whole step has none, one taut throughout all of it, one that crosses l0
    half of it (written out for c_ax = 50 N s, h = 0.01 s, l0 = 1 m); D = T_d (l_b - l_a)."""
    from dynstiff.timedomain.discrete_gradient import _mean_dashpot
    la = np.array([0.8, 1.1, 0.9, 1.1])
    lb = np.array([0.9, 1.2, 1.1, 0.9])
    T_d, D = _mean_dashpot(la, lb, 1.0, np.array([50.0]), 0.01)
    rate = (lb - la) / 0.01
    np.testing.assert_allclose(T_d, 50.0 * np.array([0.0, 1.0, 0.5, 0.5]) * rate, rtol=1e-12)
    assert D == pytest.approx(np.sum(T_d * (lb - la)), rel=1e-12)
    assert _mean_dashpot(la, lb, 1.0, None, 0.01) == (0.0, 0.0)
    assert _mean_dashpot(la, lb, 1.0, np.zeros(1), 0.01) == (0.0, 0.0)
