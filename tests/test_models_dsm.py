"""The closed-form robot model (dynstiff/models/dsm.py, FrequencyModel; theory.md §4): the
massless-cable limit against an independent straight-cable model, the geometric stiffness
at equilibrium, frequencies and mode shapes that turn and mirror with the robot, its
arguments and cable fields, and its damping (theory.md §12.2, §12.3)."""

import numpy as np
import pytest
import scipy.linalg

import dynstiff as ds
from dynstiff.errors import InvalidParameterError


def skew(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def straight_cable_frequencies(eq):
    """Independent massless straight-cable model: K = sum J^T (k u u^T + t/l (I - u u^T)) J
    + K_geo, with k = EA/L0, mass matrix of the rigid body written out here (Hz)."""
    rob, pose = eq.robot, eq.pose
    R = pose.matrix
    K = np.zeros((6, 6))
    Kgeo = np.zeros((3, 3))
    for i, s in enumerate(eq.states):
        r = R @ rob.attachments[i]
        B = pose.position + r
        d = rob.anchors[i] - B
        l = np.linalg.norm(d)
        u = d / l
        t = s.tension_at_end
        Kc = rob.cables[i].EA / eq.unstretched_lengths[i] * np.outer(u, u) + t / l * (
            np.eye(3) - np.outer(u, u))
        J = np.hstack([np.eye(3), -skew(r)])
        K += J.T @ Kc @ J
        f = t * u
        Kgeo += (r @ f) * np.eye(3) - np.outer(r, f)      # -[f]x[r]x = (f.r) I - r f^T
    m = rob.platform.mass
    rG = R @ rob.platform.center_of_mass
    fg = m * np.array([0, 0, -rob.g])
    Kgeo += (rG @ fg) * np.eye(3) - np.outer(rG, fg)
    K[3:, 3:] += Kgeo
    M = np.zeros((6, 6))
    M[:3, :3] = m * np.eye(3)
    M[:3, 3:] = -m * skew(rG)
    M[3:, :3] = m * skew(rG)
    M[3:, 3:] = R @ rob.platform.inertia @ R.T + m * (np.dot(rG, rG) * np.eye(3) - np.outer(rG, rG))
    fi = rob.platform.free_index
    lam = scipy.linalg.eigh(0.5 * (K + K.T)[np.ix_(fi, fi)], M[np.ix_(fi, fi)],
                            eigvals_only=True)
    return np.sqrt(lam) / (2 * np.pi)


def test_massless_limit_matches_straight_cable_model(cogiro):
    light = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments,
                     ds.Cable(1e-7, cogiro.robot.cables[0].EA), cogiro.robot.platform,
                     tension_limits=cogiro.robot.tension_limits)
    eq = light.equilibrium(pose=cogiro.pose)
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), 6)
    np.testing.assert_allclose(f, straight_cable_frequencies(eq), rtol=1e-6)


def test_geometric_stiffness_symmetric_at_equilibrium(cogiro_eq):
    Kg = ds.FrequencyModel(cogiro_eq).K_geo
    assert np.abs(Kg).max() > 10          # not trivially zero
    np.testing.assert_allclose(Kg, Kg.T, atol=1e-10 * np.abs(Kg).max())


def rotated_robot(rob, pose, phi):
    """The robot turned by phi about the vertical (gravity unchanged)."""
    c, s = np.cos(phi), np.sin(phi)
    Q = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    from scipy.spatial.transform import Rotation
    rot = (Rotation.from_matrix(Q) * Rotation.from_rotvec(pose.rotation)).as_rotvec()
    return (ds.Robot(rob.anchors @ Q.T, rob.attachments, rob.cables, rob.platform,
                     tension_limits=rob.tension_limits), ds.Pose(Q @ pose.position, rot))


def test_rotating_robot_with_gravity_leaves_frequencies(cogiro, cogiro_eq):
    f = ds.eigenfrequencies(ds.FrequencyModel(cogiro_eq), 12)
    rob, pose = rotated_robot(cogiro.robot, cogiro.pose, 0.7)
    eq = rob.equilibrium(pose=pose)
    np.testing.assert_allclose(ds.eigenfrequencies(ds.FrequencyModel(eq), 12), f, rtol=1e-9)


def test_mirrored_robot_gives_mirrored_modes(cogiro, cogiro_eq):
    Mx = np.diag([-1.0, 1, 1])
    p = cogiro.robot.platform
    pm = ds.Platform(p.mass, Mx @ p.center_of_mass, Mx @ p.inertia @ Mx)
    rob = ds.Robot(cogiro.robot.anchors @ Mx, cogiro.robot.attachments @ Mx, cogiro.robot.cables,
                   pm, tension_limits=cogiro.robot.tension_limits)
    eq = rob.equilibrium(pose=Mx @ cogiro.pose.position)
    a = ds.modes(ds.FrequencyModel(cogiro_eq), 8)
    b = ds.modes(ds.FrequencyModel(eq), 8)
    np.testing.assert_allclose(b.freq_hz, a.freq_hz, rtol=1e-9)
    # translation mirrors with Mx, rotation (axial vector) with -Mx
    T = np.diag([-1.0, 1, 1, 1, -1, -1])
    for k in np.flatnonzero(np.array(a.kind) == "global"):
        ma, mb = T @ a.platform_shapes[k], b.platform_shapes[k]
        assert abs(ma @ mb) == pytest.approx(np.linalg.norm(ma) * np.linalg.norm(mb), rel=1e-6)


def test_bad_equilibrium_and_frequencies_name_the_argument(cogiro_eq):
    with pytest.raises(InvalidParameterError, match="equilibrium must be an Equilibrium"):
        ds.FrequencyModel("eq")
    m = ds.FrequencyModel(cogiro_eq)
    assert m.dynamic_stiffness([]).shape == (0, 6, 6)
    with pytest.raises(InvalidParameterError, match="omega must be <="):
        m.dynamic_stiffness([1.0, 1e9])
    with pytest.raises(InvalidParameterError, match="imaginary part too large"):
        m.dynamic_stiffness([10.0 + 1e5j])


def test_cable_fields_at_rest_give_every_chord(cogiro_eq):
    """No platform motion: every cable's chord points from anchor to attachment (41 by
    default, the closed form's fields live on the chord) and zero displacement."""
    m = ds.FrequencyModel(cogiro_eq)
    pos, disp = m.cable_displacements(3.0, np.zeros(6))
    assert pos.shape == disp.shape == (8, 41, 3) and not np.any(disp)
    for s, p in zip(cogiro_eq.states, pos):
        np.testing.assert_allclose(p[0], s.anchor, atol=1e-12)
        np.testing.assert_allclose(p[-1], s.end, atol=1e-12)
        np.testing.assert_allclose(np.diff(p, axis=0), np.tile(s.chord / 40, (40, 1)),
                                   atol=1e-12)


def test_the_tension_asked_reaches_every_cable(cogiro_eq):
    """FrequencyModel(tension="chord") builds every cable's closed form with Irvine's chord
    tension H / cos(theta), not the mean tension."""
    from dynstiff.cable.chord import chord_parameters
    m = ds.FrequencyModel(cogiro_eq, tension="chord")
    for p, s in zip(m.params, cogiro_eq.states):
        assert p.T == chord_parameters(s, "chord").T != chord_parameters(s, "mean").T


@pytest.mark.parametrize("kw, name", [(dict(chordwise_inertia="no"), "chordwise_inertia"),
                                      (dict(damping="no"), "damping"),
                                      (dict(damping=0), "damping")])
def test_worded_or_numeric_flags_are_refused(cogiro_eq, kw, name):
    """chordwise_inertia="no" was True (a non-empty string), damping=0 was False: neither
    is a flag."""
    with pytest.raises(InvalidParameterError, match=f"^{name} must be True or False, got "):
        ds.FrequencyModel(cogiro_eq, **kw)


# ----------------------------------------------------------- damping of all cable motions
def test_cable_loss_factor_damps_the_transverse_string_term(cogiro_eq):
    """Hysteretic damping of all stiffness forces (theory.md §12.2): the out-of-plane (ww)
    dyad coefficient of a cable is the taut string's T s beta cot(beta L) with s = 1 + i eta
    and beta^2 = (omega^2 m - i omega c) / (T s), written out here; the cable's own
    loss_factor (EA only) leaves it undamped (real), which is why that term was needed."""
    eta, c = 0.03, 0.02
    rob = cogiro_eq.robot
    cables = [ds.Cable(cb.mass_per_length, cb.EA, viscous_damping=c) for cb in rob.cables]
    eq = ds.Robot(rob.anchors, rob.attachments, cables, rob.platform,
                  tension_limits=rob.tension_limits).equilibrium(pose=cogiro_eq.pose)
    m = ds.FrequencyModel(eq, chordwise_inertia=False, cable_loss_factor=eta)
    w = 2 * np.pi * np.array([0.7, 3.3, 7.9])
    C = m.cable_coefficients(w).reshape(len(w), -1, 5)
    s = 1 + 1j * eta
    for i, p in enumerate(m.params):
        beta = np.sqrt((w**2 * p.m - 1j * w * p.c) / (p.T * s))
        expect = p.T * s * beta / np.tan(beta * p.L)
        assert np.allclose(C[:, i, 4], expect, rtol=1e-10, atol=0)
    axial_only = ds.FrequencyModel(ds.Robot(
        rob.anchors, rob.attachments, [ds.Cable(cb.mass_per_length, cb.EA, loss_factor=eta)
                                       for cb in rob.cables], rob.platform,
        tension_limits=rob.tension_limits).equilibrium(pose=cogiro_eq.pose))
    ww = axial_only.cable_coefficients(w).reshape(len(w), -1, 5)[..., 4]
    assert np.all(np.abs(ww.imag) <= 1e-12 * np.abs(ww.real))
    assert np.all(np.abs(C[..., 4].imag) > 1e-3 * np.abs(C[..., 4].real))


def test_damping_ratios_of_the_platform_z_mode(cogiro_eq):
    """CoGiRo's first mode (2.21 Hz, 99 % platform energy in z, cable stiffness only): the
    cable loss factor eta gives it the damping ratio eta / 2 and the platform modal ratio
    zeta_p gives it zeta_p, each to 3 % (the rest: the cables' 1 % energy, the geometric
    stiffness that stays undamped); both together add. Undamped(): the options removed."""
    base = ds.FrequencyModel(cogiro_eq)
    f1 = ds.eigenfrequencies(base, 1)[0]
    for opts, zeta in [(dict(cable_loss_factor=0.04), 0.02),
                       (dict(platform_damping_ratio=0.015), 0.015),
                       (dict(cable_loss_factor=0.04, platform_damping_ratio=0.015), 0.035)]:
        m = ds.FrequencyModel(cogiro_eq, **opts)
        assert m.damped and not m.undamped().damped
        d = ds.damped_modes(m, n_modes=1)
        assert abs(d.freq_hz[0] / f1 - 1) < 2e-3
        assert d.damping_ratio[0] == pytest.approx(zeta, rel=0.03), opts
    with pytest.raises(InvalidParameterError, match="cable_loss_factor"):
        ds.FrequencyModel(cogiro_eq, cable_loss_factor=-0.1)
    with pytest.raises(InvalidParameterError, match="platform_damping_ratio"):
        ds.build_model(cogiro_eq, "dsm", platform_damping_ratio=np.nan)


def test_the_platform_damping_stands_on_the_lossy_cables_static_stiffness(cogiro_eq):
    """The platform term 2 i zeta_p sym(K_s) (theory.md §12.3) takes K_s = Re K(0) of the
    cables as the model has them: their own loss factor (a complex EA) times the model's
    s = 1 + i eta, whose product has a real part eta Im(EA) away from Re(EA), 1 % of the axial
    stiffness here. Checked against the same model without zeta_p at omega -> 0."""
    rob = cogiro_eq.robot
    lossy = ds.Robot(rob.anchors, rob.attachments,
                     [ds.Cable(cb.mass_per_length, cb.EA, loss_factor=0.02) for cb in rob.cables],
                     rob.platform, tension_limits=rob.tension_limits).equilibrium(
                         pose=cogiro_eq.pose)
    w = np.array([1e-6])                                    # omega^2 M_p ~ 1e-9 N/m
    bare = ds.FrequencyModel(lossy, cable_loss_factor=0.5).dynamic_stiffness(w)[0]
    damped = ds.FrequencyModel(lossy, cable_loss_factor=0.5,
                               platform_damping_ratio=0.05).dynamic_stiffness(w)[0]
    Ks = bare.real
    np.testing.assert_allclose(damped - bare, 2j * 0.05 * 0.5 * (Ks + Ks.T), rtol=0,
                               atol=1e-9 * np.abs(Ks).max())


def test_with_damping_keeps_the_options_and_the_fused_kernel_equals_two_calls(cogiro_eq):
    """``with_damping`` is the same model (tension, chordwise inertia) with the model-level
    damping, its defaults undamped; ``dynamic_stiffness_and_count`` equals K(omega) of the
    undamped model and the clamped-mode count J0, for every option, damped models and
    subclasses included (theory.md §5, §14.2)."""
    w = 2 * np.pi * np.array([0.4, 3.3, 7.9])
    for opts in ({}, {"tension": "chord", "chordwise_inertia": False},
                 {"chordwise_inertia": True}):
        m = ds.FrequencyModel(cogiro_eq, **opts)
        direct = ds.FrequencyModel(cogiro_eq, cable_loss_factor=0.03,
                                   platform_damping_ratio=0.02, **opts)
        damped = m.with_damping(0.03, 0.02)
        assert damped.damped and not m.with_damping().damped
        np.testing.assert_array_equal(damped.dynamic_stiffness(w), direct.dynamic_stiffness(w))
        np.testing.assert_array_equal(m.with_damping().dynamic_stiffness(w),
                                      m.dynamic_stiffness(w))
        for model in (m, damped):
            K, J0 = model.dynamic_stiffness_and_count(w)
            np.testing.assert_allclose(K, m.dynamic_stiffness(w), rtol=1e-13,
                                       atol=1e-13 * np.abs(K).max())
            np.testing.assert_array_equal(J0, m.cable_mode_count(w))

    class Softer(ds.FrequencyModel):
        """A subclass with its own K(omega): the fused kernel must defer to it."""

        def dynamic_stiffness(self, omega):
            return 0.5 * super().dynamic_stiffness(omega)

    sub = Softer(cogiro_eq)
    K, J0 = sub.dynamic_stiffness_and_count(w)
    np.testing.assert_allclose(K, 0.5 * ds.FrequencyModel(cogiro_eq).dynamic_stiffness(w),
                               rtol=1e-13, atol=1e-13 * np.abs(K).max())
    np.testing.assert_array_equal(J0, sub.cable_mode_count(w))


def test_the_damped_copy_checks_its_damping_naming_it(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    with pytest.raises(InvalidParameterError, match="^platform_damping_ratio"):
        m._with_model_damping(0.01, -0.1)
    with pytest.raises(InvalidParameterError, match="^cable_loss_factor"):
        m._with_model_damping(np.nan, 0.01)
    assert ds.FrequencyModel(cogiro_eq, cable_loss_factor=0.01)._with_model_damping(
        0.01, 0.0) is None                                   # a damped model has no copy


@pytest.mark.parametrize("damping", [{"loss_factor": 0.02}, {"viscous_damping": 0.5}])
def test_the_undamped_copy_keeps_the_guard_and_drops_the_damping(cogiro_eq, damping):
    """undamped() of a model whose cables have a loss factor or viscous damping: real K
    (float64), equal to the model of the same cables without damping, and the same guard
    tolerance."""
    import dataclasses
    rob = cogiro_eq.robot
    c = rob.cables[0]
    damped = dataclasses.replace(rob, cables=(ds.Cable(c.mass_per_length, c.EA,
                                                       **damping),) * rob.n_cables)
    eq = damped.equilibrium(pose=cogiro_eq.pose)
    m = ds.FrequencyModel(eq, guard_rtol=0.05)
    assert m.damped
    u = m.undamped()
    assert not u.damped and u.guard_rtol == 0.05
    w = 2 * np.pi * np.array([0.5, 3.0, 9.0])
    K = u.dynamic_stiffness(w)
    assert K.dtype == np.float64
    ref = ds.FrequencyModel(dataclasses.replace(damped, cables=(c,) * rob.n_cables)
                            .equilibrium(pose=cogiro_eq.pose))
    np.testing.assert_allclose(K, ref.dynamic_stiffness(w), rtol=1e-12, atol=1e-9)


def test_cable_fields_without_motion_and_the_loss_factor_with_chordwise_inertia_off(cogiro_eq):
    """With no platform motion every cable's chord points are returned (anchor to end) with
    zero displacement. With chordwise_inertia=False and a loss factor eta the cables' end
    coefficients are (1 + i eta) times the undamped ones at omega / sqrt(1 + i eta), the
    chordwise inertia still off (theory.md §12.2)."""
    m = ds.FrequencyModel(cogiro_eq)
    pos, disp = m.cable_displacements(2.0, np.zeros(6), n_points=5)
    for p, s in zip(pos, cogiro_eq.states):
        np.testing.assert_allclose(p[[0, -1]], [s.anchor, s.end], rtol=0, atol=1e-12)
    assert not np.any(disp)
    sq = np.sqrt(1 + 0.03j)
    w = 2 * np.pi * np.array([0.7, 3.1, 11.0])
    lossy = ds.FrequencyModel(cogiro_eq, chordwise_inertia=False, cable_loss_factor=0.03)
    plain = ds.FrequencyModel(cogiro_eq, chordwise_inertia=False)
    np.testing.assert_allclose(lossy.cable_coefficients(w),
                               sq**2 * plain.cable_coefficients(w / sq), rtol=1e-12)
    with_inertia = ds.FrequencyModel(cogiro_eq, cable_loss_factor=0.03)
    assert np.abs(with_inertia.cable_coefficients(w) - lossy.cable_coefficients(w)).max() > 1.0


@pytest.mark.parametrize("chordwise_inertia", [True, False])
def test_cable_energies_of_many_motions_at_once_are_each_cables_own(cogiro_eq,
                                                                   chordwise_inertia):
    """cable_kinetic_energies with omega (n,) and x (n, 6) gives, row by row, the energies of
    one motion at a time, and each entry is that cable's own cable_kinetic_energy of its end
    motion in its chord frame (the per-cable quadrature of theory.md §6, tested against an
    adaptive quadrature of the field in test_cable_dsm.py), to rounding."""
    from dynstiff.cable.dsm_fields import cable_kinetic_energy
    m = ds.FrequencyModel(cogiro_eq, chordwise_inertia=chordwise_inertia)
    w = 2 * np.pi * np.array([0.7, 2.5, 4.1, 9.3])
    X = np.random.default_rng(7).standard_normal((4, 6))
    E = m.cable_kinetic_energies(w, X)
    assert E.shape == (4, 8) and np.all(E > 0)
    for k in range(4):
        row = m.cable_kinetic_energies(w[k], X[k])
        assert row.shape == (8,)
        np.testing.assert_allclose(E[k], row, rtol=1e-13)
        for i, (p, r) in enumerate(zip(m.params, m.lever_arms)):
            d = p.rotation.T @ (X[k, :3] + np.cross(X[k, 3:], r))
            assert E[k, i] == pytest.approx(
                cable_kinetic_energy(p, w[k], d, chordwise_inertia), rel=1e-13)
