"""The closed-form robot model (dynstiff/models/dsm.py, FrequencyModel; theory.md §4): the
massless-cable limit against an independent straight-cable model, the geometric stiffness
at equilibrium, and frequencies and mode shapes that turn and mirror with the robot."""

import sys
import warnings

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


def test_the_guard_warns_on_slack_static_and_local_errors_and_is_silent_on_cogiro(cogiro_eq):
    """FrequencyModel's guard (theory.md §11.5): silent on CoGiRo up to 20 Hz at its default
    tolerance; a ClosedFormWarning names the cable and the cause on a heavy sagging robot, and
    guard_rtol=None turns it off."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    with warnings.catch_warnings():
        warnings.simplefilter("error", ClosedFormWarning)
        m = ds.FrequencyModel(cogiro_eq)
        ds.eigenfrequencies(m, fmax_hz=20.0)
        assert m.static_error()[0] < 1e-4
    # a three-cable point mass on heavy, sagging, steep cables
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    rob = ds.Robot(A, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6))
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    with pytest.warns(ClosedFormWarning) as rec:
        m = ds.FrequencyModel(eq)
        ds.eigenfrequencies(m, fmax_hz=1.5)
    causes = {(w.message.cable, w.message.cause) for w in rec}
    assert (0, "static") in causes and {c for c, k in causes if k == "local"} == {0, 1, 2}
    assert all(str(w.message).endswith(": use the 'exact' rung") for w in rec)
    assert len(rec) == len(causes)                         # once per cable and cause
    with warnings.catch_warnings():
        warnings.simplefilter("error", ClosedFormWarning)
        ds.eigenfrequencies(ds.FrequencyModel(eq, guard_rtol=None), fmax_hz=1.5)
    for bad in (-1.0, 0.0, np.inf):
        with pytest.raises(InvalidParameterError, match="guard_rtol"):
            ds.FrequencyModel(eq, guard_rtol=bad)


def test_static_error_equals_the_cable_by_cable_sum(cogiro_eq):
    """The guard's static check (all cables at once) against the sum written cable by
    cable with each state's own end stiffness and the general kernel at omega = 0: error
    and cable equal on CoGiRo and on a heavy sagging three-cable robot where it warns, with
    and without damping."""
    from scipy.linalg import eigh

    from dynstiff.robot.platform import lever_map

    def by_cable(m):
        fi, nf = m.free_index, m.n_free
        K_ex, dK = m.K_geo_free.copy(), []
        K0 = m.cable_coefficients(np.zeros(1)).real.reshape(len(m.params), 5)
        for i, (s, r) in enumerate(zip(m.equilibrium.states, m.lever_arms)):
            J = lever_map(r, fi)
            Ke = J.T @ s.end_stiffness @ J
            K_ex += Ke
            dK.append((K0[i] @ m.assembly_map[5 * i:5 * i + 5]).reshape(nf, nf) - Ke)
        lam, X = eigh(0.5 * (K_ex + K_ex.T), m.platform_mass)
        X, lam = X[:, lam > 0], lam[lam > 0]
        per = np.array([np.einsum("ik,ij,jk->k", X, d, X) for d in dK]) / (2 * lam)
        k = int(np.argmax(np.abs(per.sum(axis=0))))
        return abs(per.sum(axis=0)[k]), int(np.argmax(np.abs(per[:, k])))

    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    rob = ds.Robot(A, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6))
    heavy = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    slow = _three_cable_point_mass(g=0.3)          # global modes below 1 rad/s
    for eq, kw in ((cogiro_eq, {}), (heavy, {}), (slow, {}),
                   (cogiro_eq, {"cable_loss_factor": 0.02}), (heavy, {"damping": False})):
        m = ds.FrequencyModel(eq, guard_rtol=None, **kw)
        err, i = m.static_error()
        ref, i_ref = by_cable(m)
        assert i == i_ref
        np.testing.assert_allclose(err, ref, rtol=1e-8)
    assert ds.FrequencyModel(heavy, guard_rtol=None).static_error()[0] > 1e-2


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


def _place(filename, line):
    """A warning's place (file, line), compared with the caller's. A mutation-testing run
    (MUTANT_UNDER_TEST set) puts the tool's own frames between caller and library, so
    there the place is not compared (the normal run compares it)."""
    import os
    return (None, None) if "MUTANT_UNDER_TEST" in os.environ else (filename, line)


def _three_cable_point_mass(g=9.81, lower=False):
    """A 1 kg point mass on three heavy cables from 8 m around and 6 m up (0.064 kg/m,
    EA 1.4e5 N), optionally a fourth straight down to a floor anchor, at (0.3, -0.2, 1)."""
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    if lower:
        A = np.vstack([A, [0.3, -0.2, -4.0]])
    rob = ds.Robot(A, np.zeros((len(A), 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6),
                   g=g)
    return rob.equilibrium(pose=[0.3, -0.2, 1.0])


def test_guard_warnings_point_at_the_callers_line_and_name_the_slack_cable():
    """The lower cable of the four-cable robot is held at 0.01 N at its anchor and carries
    its weight (3.1 N) at B: t_min / t_max < 0.1, the closed form does not apply (cause
    'slack', cable 3), said once when the model is built. The warning is attributed to the
    line of the user's call, not to the library."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    eq = _three_cable_point_mass(lower=True)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        ds.FrequencyModel(eq)
    got = [(w.message.cable, w.message.cause) + _place(w.filename, w.lineno) for w in rec
           if issubclass(w.category, ClosedFormWarning)]
    assert got == [(3, "slack") + _place(__file__, line)]
    from dynstiff.cable.guard import DEFAULT_GUARD_RTOL, closed_form_validity
    reasons = closed_form_validity(eq.states[3]).reasons(DEFAULT_GUARD_RTOL)
    slack = [str(w.message) for w in rec if issubclass(w.category, ClosedFormWarning)][0]
    assert slack == ("cable 3: the closed form does not apply: " + "; ".join(reasons)
                     + ": use the 'exact' rung")


def test_the_guard_checks_bands_below_one_radian_per_second():
    """At g = 0.3 m/s^2 the three heavy cables' local modes start at 0.76-0.84 rad/s; K at
    0.99 rad/s reaches them, and the closed form's error there is above guard_rtol: a
    'local' warning for each cable, from the evaluation's line."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    with pytest.warns(ClosedFormWarning, match="static stiffness shifts a global mode"):
        m = ds.FrequencyModel(_three_cable_point_mass(g=0.3), guard_rtol=1e-2)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        m.dynamic_stiffness([0.99])
        m.dynamic_stiffness([1.2])                 # a wider band: said once per cable only
    got = {(w.message.cable, w.message.cause) + _place(w.filename, w.lineno) for w in rec
           if issubclass(w.category, ClosedFormWarning)}
    assert got == {(i, "local") + _place(__file__, line) for i in range(3)}
    assert len(rec) == 3
    for w in rec:
        i = w.message.cable
        p = m.params[i]                      # lowest taut-string frequency, model tension
        f_loc = np.sqrt(p.T / p.m) / (2 * p.L)
        assert f_loc < 0.99 / (2 * np.pi)
        assert str(w.message).startswith(f"cable {i}: its local modes (from {f_loc:.4g} Hz) are "
                                         f"in the band asked and the closed form's are ")


def test_a_cable_error_below_one_radian_per_second_is_measured():
    """The three heavy cables' envelope (0.34-0.47) is above 1e-2, so their error is measured
    against the exact cable, also for a band below 1 rad/s (0.5 rad/s here): the number of
    closed_form_local_error, kept with its band of 8 times the first local frequency."""
    from dynstiff.cable.guard import closed_form_local_error
    eq = _three_cable_point_mass(g=0.3)
    m = ds.FrequencyModel(eq, guard_rtol=None)
    for i, state in enumerate(eq.states):
        assert m._validity[i].error > 0.3
        err = closed_form_local_error(state, 0.5, m.tension)
        assert m.cable_error(i, 0.5) == err > 0.01
        assert m._measured[i] == (8 * m._local_omega[i], err)


def test_a_cable_error_ends_at_axial_modes_below_one_radian_per_second():
    """A soft cable (EA 0.01 N, g = 0.02 m/s^2) has its first axial mode at 0.15 Hz: below
    AXIAL_MARGIN of it (0.85 rad/s) its error is its envelope, from there on inf."""
    from dynstiff.cable.guard import AXIAL_MARGIN, closed_form_validity
    one = ds.Robot(np.array([[1.0, 0.0, 5.0]]), np.zeros((1, 3)), ds.Cable(0.064, 0.01),
                   ds.Platform(1.0, free_dofs=("z",)), tension_limits=(1e-6, 1e6), g=0.02)
    s = one.equilibrium(pose=[0.0, 0.0, 1.0]).states[0]
    w_ax = AXIAL_MARGIN * np.pi * np.sqrt(0.01 / 0.064) / s.unstretched_length
    m = ds.FrequencyModel(one.equilibrium(pose=[0.0, 0.0, 1.0]), guard_rtol=None)
    assert 0.8 < w_ax < 0.9
    assert m.cable_error(0, 0.5) == closed_form_validity(s).error < 1e-2
    assert m.cable_error(0, w_ax) == np.inf


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


def test_the_tension_asked_reaches_every_cable(cogiro_eq):
    """FrequencyModel(tension="chord") builds every cable's closed form with Irvine's chord
    tension H / cos(theta), not the mean tension."""
    from dynstiff.cable.chord import chord_parameters
    m = ds.FrequencyModel(cogiro_eq, tension="chord")
    for p, s in zip(m.params, cogiro_eq.states):
        assert p.T == chord_parameters(s, "chord").T != chord_parameters(s, "mean").T


def test_the_static_warning_lists_every_cause_above_a_tenth_of_guard_rtol(cogiro_eq):
    """CoGiRo's closed-form static error is 4.6e-5 (cable 1); at guard_rtol = 3e-5 it warns,
    and the message lists the validity's reasons above 3e-6: the sag (9e-5), the chordwise
    weight (5e-5) and the tension variation (2.3e-5, below guard_rtol itself)."""
    from dynstiff.cable.guard import closed_form_validity
    from dynstiff.errors import ClosedFormWarning
    err, i = ds.FrequencyModel(cogiro_eq, guard_rtol=None).static_error()
    with pytest.warns(ClosedFormWarning) as rec:
        ds.FrequencyModel(cogiro_eq, guard_rtol=3e-5)
    reasons = closed_form_validity(cogiro_eq.states[i]).reasons(3e-6)
    assert len(reasons) == 3 and "tension varies" in reasons[-1]
    assert [str(w.message) for w in rec] == [
        f"cable {i}: the closed form's static stiffness shifts a global mode by {err:.2g} "
        f"(estimate, > guard_rtol 3e-05; {'; '.join(reasons)}): use the 'exact' rung"]


def test_guard_warnings_from_deep_calls_point_at_the_callers_line_too():
    """The guard also runs inside the eigen search and the cable-level functions: their
    warnings are attributed to the user's line as well, not to a line of the package."""
    import dataclasses
    import warnings

    from dynstiff.errors import ClosedFormWarning
    r = ds.load_scene("planar2").robot
    eq = dataclasses.replace(r, cables=(ds.Cable(1.0, 2.0e4),) * 2).equilibrium(
        ds.Pose([0, 0, -10]))
    m = ds.FrequencyModel(eq)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        ds.eigenfrequencies(m, fmax_hz=40.0)
        ds.cable_natural_frequencies(eq.states[0], 40)
    places = {_place(w.filename, w.lineno) for w in rec
              if issubclass(w.category, ClosedFormWarning)}
    assert places == {_place(__file__, line), _place(__file__, line + 1)}
    f_ax = np.sqrt(2.0e4 / 1.0) / (2 * eq.states[0].unstretched_length)
    axial = [str(w.message) for w in rec if getattr(w.message, "cause", "") == "axial"]
    assert axial[0] == (f"cable 0: its axial modes from {f_ax:.4g} Hz lie in the band asked "
                        f"(up to 40 Hz); the closed form has none, so mode counts and "
                        f"frequencies above are wrong: use the 'exact' rung")


@pytest.mark.parametrize("tension", ["mean", "chord"])
def test_a_cable_within_tolerance_does_not_stop_the_check_of_the_others(tension):
    """At g = 0.3 m/s^2 a light taut cable (estimated error 1e-5) comes first, two heavy ones
    after it: K at 30 rad/s reaches all their local modes, and the two heavy cables are
    each said once, in full: the error measured against the exact cable with the model's
    tension up to min(omega, axial), and every cause above a tenth of guard_rtol."""
    import warnings

    from dynstiff.cable.guard import closed_form_local_error, closed_form_validity
    from dynstiff.errors import ClosedFormWarning
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    heavy = ds.Cable(0.064, 1.4e5)
    rob = ds.Robot(A, np.zeros((3, 3)), (ds.Cable(0.0005, 1.4e5), heavy, heavy),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6),
                   g=0.3)
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    with pytest.warns(ClosedFormWarning, match="static stiffness"):
        m = ds.FrequencyModel(eq, tension=tension, guard_rtol=1e-2)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        m.dynamic_stiffness([30.0])
    assert [w.message.cable for w in rec] == [1, 2]
    for w in rec:
        i = w.message.cable
        s = eq.states[i]
        f_ax = np.sqrt(s.cable.EA / s.cable.mass_per_length) / (2 * s.unstretched_length)
        err = closed_form_local_error(s, min(30.0, 2 * np.pi * f_ax), tension)
        reasons = "; ".join(closed_form_validity(s, tension=tension).reasons(1e-3))
        p = m.params[i]                      # lowest taut-string frequency, model tension
        f_loc = np.sqrt(p.T / p.m) / (2 * p.L)
        assert str(w.message) == (
            f"cable {i}: its local modes (from {f_loc:.4g} Hz) are in the band asked and the "
            f"closed form's are {err:.2g} off the exact model's (> guard_rtol 0.01; "
            f"{reasons}): use the 'exact' rung")


def test_cables_measured_within_tolerance_are_passed_over_and_the_rest_said(cogiro_eq):
    """CoGiRo at guard_rtol = 3e-5 up to 20 Hz: every cable's estimate exceeds it, so each is
    measured against the exact cable; cables 2 and 5 measure within it and are passed over,
    the other six are said in full, each with every cause above a tenth of guard_rtol."""
    import warnings

    from dynstiff.cable.guard import closed_form_local_error, closed_form_validity
    from dynstiff.errors import ClosedFormWarning
    with pytest.warns(ClosedFormWarning, match="static stiffness"):
        m = ds.FrequencyModel(cogiro_eq, guard_rtol=3e-5)
    top = 2 * np.pi * 20.0
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        m.dynamic_stiffness([top])
    said = [w.message.cable for w in rec]
    assert said == [0, 1, 3, 4, 6, 7]
    for i in (2, 5):
        assert closed_form_local_error(cogiro_eq.states[i], top) <= 3e-5
    for w, i in zip(rec, said):
        s = cogiro_eq.states[i]
        err = closed_form_local_error(s, top)
        p = m.params[i]                      # lowest taut-string frequency, model tension
        f_loc = np.sqrt(p.T / p.m) / (2 * p.L)
        assert str(w.message) == (
            f"cable {i}: its local modes (from {f_loc:.4g} Hz) are in the band asked and the "
            f"closed form's are {err:.2g} off the exact model's (> guard_rtol 3e-05; "
            + "; ".join(closed_form_validity(s).reasons(3e-6)) + "): use the 'exact' rung")


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


def test_on_fast_the_guard_warns_or_the_closed_form_is_within_guard_rtol_mode_by_mode():
    # the FAST feed support at the bottom of its focal surface: cables ~0.9 x the cabin's mass
    eq = ds.load_scene("fast").equilibrium()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ds.errors.ClosedFormWarning)
        m = ds.FrequencyModel(eq)
        f_d = ds.eigenfrequencies(m, fmax_hz=0.4)
    warned = any(isinstance(w.message, ds.errors.ClosedFormWarning) for w in caught)
    f_x = ds.eigenfrequencies(ds.build_model(eq, "exact", fmax_hz=0.45), fmax_hz=0.4)
    assert f_d.size == f_x.size > 20
    err = np.abs(f_d / f_x - 1)
    assert warned or err.max() <= m.guard_rtol
    # the robot-level bound holds here: measured 5.1e-3, bound 2.5 x (static + own) >= it
    bound = m.robot_error(2 * np.pi * 0.4)[0]
    assert err.max() <= bound
    assert warned == (bound > m.guard_rtol)


def test_robot_error_is_the_factor_times_static_plus_largest_cable_error(cogiro_eq):
    from dynstiff.cable.guard import ROBOT_ERROR_FACTOR
    m = ds.FrequencyModel(cogiro_eq)
    w = 2 * np.pi * 12.0
    own = [m.cable_error(i, w) for i in range(8)]
    bound, i = m.robot_error(w)
    assert bound == pytest.approx(ROBOT_ERROR_FACTOR * (m.static_error()[0] + max(own)))
    assert own[i] == max(own)


@pytest.mark.parametrize("kw, name", [(dict(chordwise_inertia="no"), "chordwise_inertia"),
                                      (dict(damping="no"), "damping"),
                                      (dict(damping=0), "damping")])
def test_worded_or_numeric_flags_are_refused(cogiro_eq, kw, name):
    """chordwise_inertia="no" was True (a non-empty string), damping=0 was False: neither
    is a flag."""
    with pytest.raises(InvalidParameterError, match=f"^{name} must be True or False, got "):
        ds.FrequencyModel(cogiro_eq, **kw)
