"""The "exact" rung at robot level (dynstiff/models/exact.py, theory.md §11): complete mode
counts where the closed form misses axial modes, CoGiRo against the converged lumped model,
and the model interface (dynstiff/models/base.py)."""

import dataclasses
import warnings

import numpy as np
import pytest
from conftest import exact_float_poles

import dynstiff as ds
from dynstiff.errors import ClosedFormWarning, InvalidParameterError

TWO_PI = 2 * np.pi


def richardson3(f):
    """Two-level Richardson of O(N^-2) + O(N^-4) results at N, 2N, 4N (dict in that order)."""
    a, b, c = (f[k] for k in sorted(f))
    r1, r2 = (4 * b - a) / 3, (4 * c - b) / 3
    return (16 * r2 - r1) / 15


def lumped_reference(eq, n, segments):
    f = {N: ds.eigenfrequencies(ds.build_model(eq, "lumped", segments=N), n_modes=n)
         for N in segments}
    return richardson3(f)


@pytest.fixture(scope="module")
def soft_planar2():
    r = ds.load_scene("planar2").robot
    rob = dataclasses.replace(r, cables=(ds.Cable(1.0, 2.0e4),) * 2)
    return rob.equilibrium(ds.Pose([0, 0, -10]))


def test_axial_modes_are_counted_where_the_closed_form_misses_them(soft_planar2):
    """planar2 with Cable(1, 2e4) at (0, 0, -10): the closed form finds 18 modes below 4.5 Hz
    and warns that the cables' axial modes (from 4.12 Hz) are in the band; the exact rung
    finds 20, the same as the lumped model (N = 40, 80, 160 extrapolated) to 1e-6."""
    eq = soft_planar2
    with pytest.warns(ClosedFormWarning, match="axial modes from 4.12") as rec:
        f_dsm = ds.eigenfrequencies(ds.build_model(eq, "dsm"), fmax_hz=4.5)
    assert {w.message.cause for w in rec} >= {"axial"}
    assert {w.message.cable for w in rec if w.message.cause == "axial"} == {0, 1}
    assert len(f_dsm) == 18
    mx = ds.build_model(eq, "exact", fmax_hz=5.0)
    f_ex = ds.eigenfrequencies(mx, fmax_hz=4.5)
    assert len(f_ex) == 20
    ref = lumped_reference(eq, 20, (40, 80, 160))
    np.testing.assert_allclose(f_ex, ref, rtol=1e-6)
    # the count agrees below every frequency between two reference modes
    mid = TWO_PI * 0.5 * (ref[:-1] + ref[1:])
    gaps = np.diff(ref) > 1e-6 * ref[1:]
    np.testing.assert_array_equal(ds.mode_count(mx, mid[gaps]), np.arange(1, 20)[gaps])


def _cogiro(E):
    sc = ds.load_scene("cogiro")
    r0 = sc.robot
    cables = tuple(dataclasses.replace(c, EA=8.2051e-6 * E) for c in r0.cables)
    return dataclasses.replace(r0, cables=cables), sc.pose


def _check_against_lumped(eq, fmax_hz, rtol, segments=(40, 80, 160)):
    mx = ds.build_model(eq, "exact", fmax_hz=1.05 * fmax_hz)
    f = ds.eigenfrequencies(mx, fmax_hz=fmax_hz)
    ref = lumped_reference(eq, len(f) + 2, segments)
    # modes closer than 2e-3 (pairs of local modes of symmetric cables) change order between
    # the lumped N, so their Richardson values pair different modes: within such a cluster
    # the mean (a smooth function of N) is compared to rtol, each mode to the cluster width
    n = len(f)
    edges = np.flatnonzero(np.diff(f) > 2e-3 * f[1:]) + 1
    for lo, hi in zip(np.r_[0, edges], np.r_[edges, n]):
        assert np.mean(f[lo:hi]) == pytest.approx(np.mean(ref[lo:hi]), rel=rtol)
        width = (f[hi - 1] - f[lo]) / f[lo]
        np.testing.assert_allclose(f[lo:hi], ref[lo:hi], rtol=rtol + width)
    isolated = np.diff(np.r_[0, edges, n]) == 1
    assert isolated.sum() >= min(15, n // 4)         # many modes are checked one by one
    # the count agrees below every frequency between two clusters of reference modes
    ends = np.r_[edges, n]
    mid = np.array([0.5 * (ref[lo:hi].max() + ref[hi:nx].min()) for lo, hi, nx in
                    zip(np.r_[0, edges], ends, np.r_[ends[1:], n + 1])])
    mid = np.minimum(mid, 1.04 * fmax_hz)                     # inside the model's band
    np.testing.assert_array_equal(ds.mode_count(mx, TWO_PI * mid), ends[:mid.size])
    return f


def test_cogiro_matches_the_converged_lumped_model():
    """CoGiRo at its scene pose, E = 17 GPa: every frequency to 10 Hz (38 modes) equals the
    lumped model extrapolated from N = 40, 80, 160 to 2e-5 (measured 1e-7)."""
    rob, pose = _cogiro(17e9)
    f = _check_against_lumped(rob.equilibrium(pose), 10.0, 2e-5)
    assert len(f) >= 30


@pytest.mark.slow
@pytest.mark.parametrize("E", [17e9, 120e9])
@pytest.mark.parametrize("position", [[0, 0, 1.0], [2.0, 1.0, 1.5], [-3.0, -2.0, 2.0],
                                      [4.0, -2.5, 0.5]])
def test_cogiro_over_the_workspace_to_20_hz(E, position):
    """Four poses x E = 17 and 120 GPa, all modes to 20 Hz (about 90): 2e-5 against the
    lumped model extrapolated from N = 80, 160, 320 (measured 1e-8; from N = 40 the close
    pairs of local modes near 19 Hz change order between N and are paired wrongly), and the
    same count below every gap."""
    rob, pose = _cogiro(E)
    _check_against_lumped(rob.equilibrium(ds.Pose(position, pose.rotation)), 20.0, 2e-5,
                          segments=(80, 160, 320))


@pytest.fixture(scope="module")
def cogiro_exact(cogiro_eq):
    return ds.build_model(cogiro_eq, "exact", fmax_hz=8.0)


def test_static_limit_and_closeness_to_the_closed_form(cogiro_eq, cogiro_exact):
    """K(0) is the exact catenaries' stiffness (the "catenary" rung) to 1e-12; on CoGiRo's
    shallow taut cables the first global modes are within 3e-4 of the closed form (its
    measured error, theory.md §11.5)."""
    K_cat = ds.build_model(cogiro_eq, "catenary").K
    np.testing.assert_allclose(cogiro_exact.massless_stiffness(), K_cat, rtol=0,
                               atol=1e-12 * np.abs(K_cat).max())
    f_ex = ds.eigenfrequencies(cogiro_exact, n_modes=6)
    f_cf = ds.eigenfrequencies(ds.build_model(cogiro_eq, "dsm"), n_modes=6)
    np.testing.assert_allclose(f_cf, f_ex, rtol=3e-4)
    assert np.max(np.abs(f_cf / f_ex - 1)) > 1e-6                # but they are not the same


def test_modes_fields_and_energies(cogiro_exact):
    md = ds.modes(cogiro_exact, fmax_hz=4.0)
    assert {"global", "local"} <= set(md.kind)
    k = list(md.kind).index("global")
    pos, disp = ds.cable_fields(cogiro_exact, md, k)
    assert pos.shape == disp.shape == (8, 41, 3)
    # the field ends at the attachment's motion; it starts at rest at the anchor
    x = md.platform_shapes[k]
    r = cogiro_exact.lever_arms
    np.testing.assert_allclose(disp[:, -1], x[:3] + np.cross(x[3:], r), atol=1e-12)
    np.testing.assert_allclose(disp[:, 0], 0.0, atol=1e-15)
    np.testing.assert_allclose(pos[:, 0], cogiro_exact.robot.anchors, atol=1e-12)
    # kinetic energy identity: cable share from -x^T dK/d(omega^2) x (M_p-normalised x)
    w = TWO_PI * md.freq_hz[k]
    h = 1e-6 * w
    K = cogiro_exact.dynamic_stiffness([w - h, w + h])
    dK = (K[1] - K[0]) / (4 * w * h)
    total = -x @ dK @ x
    cab = cogiro_exact.cable_kinetic_energies(w, x).sum()
    plat = x @ cogiro_exact.platform_mass @ x
    assert total == pytest.approx(cab + plat, rel=1e-6)


def test_damped_exact_model(cogiro):
    rob = dataclasses.replace(cogiro.robot, cables=dataclasses.replace(
        cogiro.robot.cables[0], loss_factor=0.02, viscous_damping=0.01))
    eq = rob.equilibrium(pose=cogiro.pose)
    m = ds.build_model(eq, "exact", fmax_hz=6.0)
    assert m.damped and not m.undamped().damped
    f0 = ds.eigenfrequencies(m, n_modes=3)
    np.testing.assert_allclose(f0, ds.eigenfrequencies(m.undamped(), n_modes=3), rtol=0)
    H = ds.frf(m, TWO_PI * f0[:1])
    assert np.all(np.isfinite(H.H)) and np.abs(H.H.imag).max() > 0
    dm = ds.damped_modes(m, 1)
    assert dm.damping_ratio[0] > 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)
        dd = ds.damped_modes(ds.build_model(eq, "dsm"), 1)
    assert dm.omega[0] == pytest.approx(dd.omega[0], rel=1e-3)
    assert dm.damping_ratio[0] == pytest.approx(dd.damping_ratio[0], rel=0.05)


def test_requests_beyond_the_band_are_refused(cogiro_exact):
    with pytest.raises(InvalidParameterError) as err:
        cogiro_exact.dynamic_stiffness(TWO_PI * np.array([1.0, 9.5, 9.0]))
    assert str(err.value) == (f"omega must be <= {TWO_PI * 8:.6g} rad/s: the exact model was "
                              f"built for fmax_hz = 8 Hz, got {TWO_PI * 9.5:.6g} rad/s (9.5 Hz); "
                              f"build it with a larger fmax_hz")
    with pytest.raises(InvalidParameterError, match="larger fmax_hz"):
        ds.eigenfrequencies(cogiro_exact, n_modes=500)
    with pytest.raises(InvalidParameterError, match="out of the 'exact' model's range"):
        ds.eigenfrequencies(cogiro_exact, fmax_hz=9.0)
    for bad in (0.0, -1.0, np.nan, "ten", True):
        with pytest.raises(InvalidParameterError, match="fmax_hz"):
            ds.build_model(cogiro_exact.equilibrium, "exact", fmax_hz=bad)


@pytest.mark.parametrize("damped", [False, True])
def test_frequency_blocks_give_the_one_block_result(cogiro, monkeypatch, damped):
    """K(omega) is evaluated in blocks of frequencies (a cache-sized temporary); blocks of 7
    frequencies, the last one partial, give the single-block result, real and complex omega."""
    import dynstiff.models.exact as em
    rob = cogiro.robot
    if damped:
        rob = dataclasses.replace(rob, cables=dataclasses.replace(
            rob.cables[0], loss_factor=0.02, viscous_damping=0.01))
    m = ds.build_model(rob.equilibrium(pose=cogiro.pose), "exact", fmax_hz=6.0)
    w = TWO_PI * np.linspace(0.0, 5.9, 52)
    for omega in (w, w * (1 + 0.01j)):
        monkeypatch.setattr(em, "BLOCK_ELEMENTS", 10**9)
        one = m.dynamic_stiffness(omega)
        n_modes = sum(c.flexibilities.size for c in m.cables)
        monkeypatch.setattr(em, "BLOCK_ELEMENTS", 7 * n_modes)
        blocks = m.dynamic_stiffness(omega)
        assert blocks.dtype == one.dtype == (complex if damped or np.iscomplexobj(omega)
                                             else float)
        scale = np.abs(one).max(axis=(1, 2))          # BLAS blocking: rounding differs
        assert (np.abs(blocks - one).max(axis=(1, 2)) <= 1e-14 * scale).all()


def test_model_level_damping_options_match_the_closed_forms(cogiro_eq):
    """cable_loss_factor and platform_damping_ratio (theory.md §12.2) act on the exact rung as
    on the closed form: CoGiRo's first damped root agrees to the rungs' frequency gap (2e-4)
    and its damping ratio to 1e-3; undamped() drops them."""
    opts = {"cable_loss_factor": 0.04, "platform_damping_ratio": 0.015}
    mx = ds.build_model(cogiro_eq, "exact", fmax_hz=6.0, **opts)
    md = ds.build_model(cogiro_eq, "dsm", **opts)
    assert mx.damped and not mx.undamped().damped
    a, b = ds.damped_modes(mx, 1), ds.damped_modes(md, 1)
    assert a.freq_hz[0] == pytest.approx(b.freq_hz[0], rel=2e-4)
    assert a.damping_ratio[0] == pytest.approx(b.damping_ratio[0], rel=1e-3)
    assert a.damping_ratio[0] == pytest.approx(0.035, rel=0.03)
    with pytest.raises(InvalidParameterError, match="cable_loss_factor"):
        ds.build_model(cogiro_eq, "exact", cable_loss_factor=-1.0)


def test_with_damping_keeps_the_band_and_mesh_and_still_fields_every_cable(cogiro_eq):
    """``with_damping`` keeps fmax_hz, order and half_waves (the same K as a direct build),
    its defaults undamped; ``cable_displacements`` with no motion gives every cable's
    static profile (41 points by default) and zero displacement."""
    from dynstiff.models.exact import ExactModel
    m = ExactModel(cogiro_eq, fmax_hz=6.0, order=10, half_waves=3.0)
    direct = ExactModel(cogiro_eq, 6.0, 10, 3.0, cable_loss_factor=0.02,
                           platform_damping_ratio=0.01)
    damped = m.with_damping(0.02, 0.01)
    assert (damped.fmax_hz, damped.order, damped.half_waves) == (6.0, 10, 3.0)
    w = TWO_PI * np.array([0.7, 4.1])
    np.testing.assert_array_equal(damped.dynamic_stiffness(w), direct.dynamic_stiffness(w))
    assert damped.damped and not m.with_damping().damped
    np.testing.assert_array_equal(m.with_damping().dynamic_stiffness(w),
                                  m.dynamic_stiffness(w))
    pos, disp = m.cable_displacements(w[0], np.zeros(6))
    assert pos.shape == disp.shape == (8, 41, 3)
    assert not np.any(disp)
    for c, p in zip(m.cables, pos):
        np.testing.assert_allclose(p, c.state.profile(41), rtol=0, atol=0)


def test_cable_damping_at_robot_level_is_the_undamped_model_at_a_complex_frequency():
    """Viscous cable damping c is the complex mass m - i c / omega (theory.md §11.3): the
    robot's K(omega) equals the undamped robot's at omega_c = sqrt(omega^2 - i omega c / m)
    once the platform's own inertia term is put back at the real omega. Hysteretic damping
    makes even the static stiffness complex. ``damping=False`` drops every damping option,
    ``undamped`` keeps the band and the mesh, and any band above 0 Hz is accepted."""
    from dynstiff.models.exact import ExactModel
    base = ds.load_scene("cogiro")
    c, m = 0.4, base.robot.cables[0].mass_per_length
    viscous = dataclasses.replace(base.robot, cables=tuple(
        dataclasses.replace(k, viscous_damping=c) for k in base.robot.cables))
    eq_v = viscous.equilibrium(pose=base.pose)
    md = ExactModel(eq_v, fmax_hz=6.0, half_waves=3.0)
    mu = md.undamped()
    assert md.damped and not mu.damped and (mu.fmax_hz, mu.half_waves) == (6.0, 3.0)
    w = TWO_PI * np.array([0.7, 2.3, 4.9])
    wc = np.sqrt(w**2 - 1j * w * c / m)
    expected = mu.dynamic_stiffness(wc) + (wc**2 - w**2)[:, None, None] * mu.platform_mass
    K = md.dynamic_stiffness(w)
    np.testing.assert_allclose(K, expected, rtol=0, atol=1e-10 * np.abs(K).max())
    hyst = dataclasses.replace(base.robot, cables=tuple(
        dataclasses.replace(k, loss_factor=0.02) for k in base.robot.cables))
    K0 = ExactModel(hyst.equilibrium(pose=base.pose), fmax_hz=2.0).dynamic_stiffness(0.0)[0]
    assert np.abs(K0.imag).max() > 1e-3 * np.abs(K0.real).max()
    off = ExactModel(eq_v, fmax_hz=6.0, half_waves=3.0, damping=False,
                     cable_loss_factor=0.01, platform_damping_ratio=0.02)
    assert not off.damped
    np.testing.assert_array_equal(off.dynamic_stiffness(w), mu.dynamic_stiffness(w))
    assert ExactModel(base.equilibrium(), fmax_hz=0.5, cable_loss_factor=0.5).damped


def test_build_options_reach_every_cable_and_bad_ones_are_named(cogiro_eq):
    """half_waves sets every cable's mesh (the edges of an ExactCable built with it), M_p is
    the platform's 6x6 mass matrix about P at the pose (its free block the model's
    platform_mass), and a negative damping option is refused by its own name."""
    from dynstiff.cable.exact import ExactCable
    from dynstiff.models.exact import ExactModel
    from dynstiff.robot.platform import platform_mass_matrix
    m = ExactModel(cogiro_eq, fmax_hz=6.0, half_waves=5.0)
    for c, s in zip(m.cables, cogiro_eq.states):
        np.testing.assert_array_equal(c.edges, ExactCable(s, m.max_omega, half_waves=5.0).edges)
    assert not np.array_equal(m.cables[0].edges, ExactModel(cogiro_eq, 6.0).cables[0].edges)
    M = platform_mass_matrix(cogiro_eq.robot.platform, cogiro_eq.pose.matrix)
    np.testing.assert_array_equal(m.M_p, M)
    np.testing.assert_array_equal(m.platform_mass, M[np.ix_(m.free_index, m.free_index)])
    for name in ("cable_loss_factor", "platform_damping_ratio"):
        with pytest.raises(InvalidParameterError) as err:
            ExactModel(cogiro_eq, fmax_hz=6.0, **{name: -0.5})
        assert str(err.value) == f"{name} must be >= 0, got -0.5"
        with pytest.raises(InvalidParameterError) as err:
            ds.FrequencyModel(cogiro_eq, **{name: -0.5})
        assert str(err.value) == f"{name} must be >= 0, got -0.5"


def test_platform_damping_is_hysteretic_and_proportional_to_the_static_stiffness(cogiro_eq):
    """platform_damping_ratio alone (theory.md §12.2): the model is damped, and its K(omega)
    is the undamped one plus 2 i zeta K(0), K(0) the model's static stiffness, geometric
    part included, at every omega."""
    from dynstiff.models.exact import ExactModel
    base = ExactModel(cogiro_eq, fmax_hz=6.0)
    damped = ExactModel(cogiro_eq, fmax_hz=6.0, platform_damping_ratio=0.02)
    assert damped.damped and not base.damped
    w = TWO_PI * np.array([0.0, 1.3, 4.7])
    K0 = base.dynamic_stiffness(0.0)[0]
    np.testing.assert_allclose(damped.dynamic_stiffness(w),
                               base.dynamic_stiffness(w) + 0.04j * 0.5 * (K0 + K0.T),
                               rtol=1e-12, atol=1e-12 * np.abs(K0).max())


def test_a_worded_damping_flag_is_refused():
    from dynstiff.models.exact import ExactModel
    eq = ds.load_scene("planar2").equilibrium()
    with pytest.raises(InvalidParameterError, match="^damping must be True or False, got 'no'"):
        ExactModel(eq, damping="no")


def test_the_stiffness_exactly_on_a_clamped_pole_is_not_finite_and_silent(cogiro_exact):
    """Float frequencies do land on a clamped pole (w^2 mu = 1 exactly): K there is not
    finite, as documented, with no floating-point warning (the package's RuntimeWarnings are
    errors in the tests); a relative 1e-9 below it, K is finite."""
    m = cogiro_exact
    poles = exact_float_poles(m._mu, m.max_omega)
    assert len(poles) >= 2
    for w in poles[:2]:
        assert not np.all(np.isfinite(m.dynamic_stiffness(w)))
        assert np.all(np.isfinite(m.dynamic_stiffness(w * (1 - 1e-9))))


def test_exact_cable_energies_of_many_motions_at_once_are_each_motions(cogiro_exact):
    """The exact rung's cable_kinetic_energies with omega (n,) and x (n, 6): row k is the
    energies of motion k alone, shape (n, n_cables); one motion gives (n_cables,)."""
    w = 2 * np.pi * np.array([0.9, 3.3, 5.2])
    X = np.random.default_rng(3).standard_normal((3, 6))
    E = cogiro_exact.cable_kinetic_energies(w, X)
    assert E.shape == (3, 8) and np.all(E > 0)
    for k in range(3):
        np.testing.assert_array_equal(E[k], cogiro_exact.cable_kinetic_energies(w[k], X[k]))
