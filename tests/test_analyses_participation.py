"""Platform participation and receptance amplification (dynstiff/analyses/participation.py,
theory.md §12.1, docs/theory.md §13.3): shares, the per-DOF participation and its sum rule,
the fast shares of the closed form, the modes every verdict uses."""

import dataclasses

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.participation import modal_data, platform_shares, receptance_amplification


def with_mass(robot, mass):
    return ds.Robot(robot.anchors, robot.attachments, robot.cables,
                    dataclasses.replace(robot.platform, mass=mass), g=robot.g,
                    tension_limits=robot.tension_limits)


@pytest.fixture(scope="module")
def robot():
    return ds.load_scene("cogiro").robot


@pytest.fixture(scope="module")
def cogiro50():
    sc = ds.load_scene("cogiro")
    eq = with_mass(sc.robot, 50.0).equilibrium(pose=sc.pose)
    m = ds.FrequencyModel(eq)
    return m, ds.modes(m, fmax_hz=3.0)


def test_kinds_shares_and_participation(cogiro50):
    """The share is 1 - the cable fraction; participations are >= 0 and, for each mode,
    sum over the DOFs to its share when M_p is diagonal in the DOFs a mode moves (CoGiRo's
    platform: to 1e-2 with its centre of mass off P); the 50 kg CoGiRo's 2.216 Hz mode holds
    42 % of its energy in the platform: "mixed", one label in every table."""
    m, mo = cogiro50
    assert np.allclose(mo.platform_share, 1 - mo.cable_energy_fraction, atol=1e-15)
    p = mo.participation
    assert np.all(p >= 0) and np.all(p[:, [k for k in range(6) if k not in m.free_index]] == 0)
    k = int(np.argmin(np.abs(mo.freq_hz - 2.216)))
    assert abs(mo.freq_hz[k] - 2.216) < 5e-4
    assert 0.40 < mo.platform_share[k] < 0.44 and mo.kind[k] == "mixed"
    df = mo.to_frame()
    assert list(df["kind"]) == list(mo.kind) and "participation y [-]" in df
    assert "category" not in df


def test_participations_of_all_the_modes_sum_to_one_per_dof():
    """The effective-mass sum rule (theory.md §12.1): over every mode of a discrete model
    each free DOF's participations sum to 1 (the lumped CoGiRo with 3 segments per cable,
    all 54 modes), and over the modes below a frequency they grow towards it."""
    sc = ds.load_scene("cogiro")
    lm = ds.build_model(sc.equilibrium(), "lumped", segments=3)
    res = ds.modes(lm, n_modes=lm.n_dof)
    np.testing.assert_allclose(res.participation.sum(axis=0), 1.0, rtol=1e-10)
    assert np.all(np.diff(np.cumsum(res.participation, axis=0), axis=0) >= -1e-15)


def test_modal_data_of_the_closed_form_equals_the_modes(robot):
    """The verdicts' modes of the closed form (fast shares) equal dynstiff.modes: the same
    frequencies, shares to 1e-8, shapes to 1e-7 (up to sign), labels and participation."""
    m = ds.build_model(robot.equilibrium(pose=[1.0, -0.5, 1.5]), "dsm")
    fast, ref = modal_data(m, 6.0), ds.modes(m, fmax_hz=6.0)
    np.testing.assert_array_equal(fast.freq_hz, ref.freq_hz)
    np.testing.assert_allclose(fast.platform_share, ref.platform_share, atol=1e-8)
    sign = np.sign(np.sum(fast.platform_shapes * ref.platform_shapes, axis=1))[:, None]
    np.testing.assert_allclose(fast.platform_shapes * sign, ref.platform_shapes, atol=1e-7)
    assert fast.kind == ref.kind
    np.testing.assert_allclose(fast.participation, ref.participation, atol=1e-7)
    # the fast path gives no cable energies: NaN, floats
    assert fast.cable_energy.dtype == float and np.all(np.isnan(fast.cable_energy))


def test_modal_data_of_coincident_roots_takes_the_full_modes():
    """The octahedron's degenerate pairs (C3v): their shapes need the null space of K, so
    modal_data takes dynstiff.modes (with the cable energies) and equals it."""
    from conftest import inverted_stewart
    rob = inverted_stewart()
    m = ds.build_model(rob.equilibrium(pose=[0.0, 0.0, 1.5], tol=1e-12), "dsm")
    res, ref = modal_data(m, 45.0), ds.modes(m, fmax_hz=45.0)
    assert res.freq_hz.size == 3 and res.freq_hz[2] - res.freq_hz[1] <= 1e-8 * res.freq_hz[2]
    assert np.all(np.isfinite(res.cable_energy))
    np.testing.assert_array_equal(res.platform_share, ref.platform_share)


@pytest.mark.parametrize("position", [(0.0, 0.0, 1.0), (3.0, 2.0, 2.5), (5.0, 3.0, 1.0)])
def test_platform_participation_from_the_derivative_of_k_equals_the_cable_energies(
        robot, position):
    """-x^T dK/d(omega^2) x is the total modal mass (docs/theory.md §13.3): the platform
    share from it equals 1 - the closed-form cable energy fraction of dynstiff.modes
    (1e-8) over 30 modes, global and local."""
    m = ds.build_model(robot.equilibrium(pose=position), "dsm")
    res = ds.modes(m, n_modes=30)
    np.testing.assert_allclose(platform_shares(m, res.freq_hz)[0],
                               1.0 - res.cable_energy_fraction, rtol=0, atol=1e-8)


def test_platform_participation_near_a_cable_pole_takes_the_closed_form_energies(
        robot, monkeypatch):
    """With a step so wide that cable poles fall inside it, every such mode takes the
    closed-form cable energies: the result still equals dynstiff.modes."""
    import importlib
    wsmod = importlib.import_module("dynstiff.analyses.participation")
    m = ds.build_model(robot.equilibrium(pose=[0.0, 0.0, 1.0]), "dsm")
    res = ds.modes(m, n_modes=12)
    monkeypatch.setattr(wsmod, "_FD_STEP", 0.2)
    w = 2 * np.pi * res.freq_hz
    assert np.any(m.cable_mode_count(1.2 * w) != m.cable_mode_count(0.8 * w))
    near = m.cable_mode_count(1.2 * w) != m.cable_mode_count(0.8 * w)
    got = wsmod.platform_shares(m, res.freq_hz)[0]
    np.testing.assert_allclose(got[near], 1.0 - res.cable_energy_fraction[near], atol=1e-12)


def _participation_mode_by_mode(model, freq_hz):
    """platform_shares written one mode at a time (its first form, theory.md
    §13.3), the reference of the batched one."""
    w = 2.0 * np.pi * np.asarray(freq_hz, dtype=float)
    n, h = w.size, 1e-6
    steps = np.array([1 + h, 1 - h, 1 + h / 2, 1 - h / 2, 1 + 1e-9, 1 - 1e-9])
    K = model.dynamic_stiffness(w)
    Ks = model.dynamic_stiffness(np.outer(steps[:4], w).ravel()).reshape(4, n, *K.shape[1:])
    J0 = model.cable_mode_count(np.outer(steps, w).ravel()).reshape(6, n)
    Mp = model.platform_mass
    scale = np.abs(np.linalg.eigvalsh(model.massless_stiffness())).max()
    out = np.zeros(n)
    for k in range(n):
        if not np.all(np.isfinite(K[k])):
            continue
        ev, V = np.linalg.eigh(K[k])
        if J0[4, k] > J0[5, k] and np.abs(ev).min() > 1e-6 * scale:
            continue
        x = V[:, np.argmin(np.abs(ev))]
        x = x / np.sqrt(x @ Mp @ x)
        if J0[0, k] != J0[1, k]:
            full = np.zeros(6)
            full[model.free_index] = x
            out[k] = 1.0 / (1.0 + model.cable_kinetic_energies(w[k], full).sum())
            continue
        d1 = (Ks[0, k] - Ks[1, k]) / (w[k] ** 2 * ((1 + h) ** 2 - (1 - h) ** 2))
        d2 = (Ks[2, k] - Ks[3, k]) / (w[k] ** 2 * ((1 + h / 2) ** 2 - (1 - h / 2) ** 2))
        out[k] = 1.0 / -(x @ ((4.0 * d2 - d1) / 3.0) @ x)
    return out


@pytest.mark.parametrize("position", [[0.0, 0.0, 1.0], [-3.0, 2.0, 2.5], [4.0, -3.0, 0.8]])
def test_batched_participation_equals_the_mode_by_mode_one(robot, position, monkeypatch):
    """The batched platform participation equals the mode-by-mode form to 1e-12 over 30
    modes with the same (numpy) K; at a cable pole (a local mode there, the platform at
    rest, and modes with a pole within the steps) too. With the compiled K, whose entries
    agree with numpy's to 50 eps (test_compiled_dsm), the difference quotient over the
    relative step 1e-6 carries that to 50 eps / 1e-6 = 1.1e-8 at most."""
    from dynstiff import compiled
    m = ds.build_model(robot.equilibrium(pose=position), "dsm")
    f = ds.eigenfrequencies(m, n_modes=30)
    pole = np.pi * np.sqrt(m.params[0].T / m.params[0].m) / m.params[0].L / (2 * np.pi)
    g = np.sort(np.concatenate([f[:5], [pole, pole * (1 + 3e-7)]]))
    ref_f, ref_g = _participation_mode_by_mode(m, f), _participation_mode_by_mode(m, g)
    compiled_f, compiled_g = platform_shares(m, f)[0], platform_shares(m, g)[0]
    monkeypatch.setattr(compiled, "load", lambda name: None)
    np.testing.assert_allclose(platform_shares(m, f)[0], ref_f, rtol=0, atol=1e-12)
    np.testing.assert_allclose(platform_shares(m, g)[0], ref_g, rtol=0, atol=1e-12)
    np.testing.assert_allclose(compiled_f, ref_f, rtol=0, atol=1.1e-8)
    np.testing.assert_allclose(compiled_g, ref_g, rtol=0, atol=1.1e-8)


def test_receptance_amplification_of_a_massless_model():
    """Point mass on 3 CoGiRo cables (closed-form model) with the platform ratio applied as
    i 2 zeta K_s: every mode peaks at 1 / (2 zeta) times its own static value; for the
    direct receptance of the mode's DOF the ratio is >= that in a band around the mode and
    about 1 far below it."""
    from conftest import point_mass_robot
    eq = point_mass_robot().equilibrium(pose=[0.2, -0.1, 1.0, 0, 0, 0])
    m = ds.build_model(eq, "dsm", platform_damping_ratio=0.02)
    f = ds.eigenfrequencies(m.undamped(), 3)
    r, f_at, dof = receptance_amplification(m, (0.0, 0.3 * f[0]), f)
    assert 1.0 <= r < 1.11                          # 1 / (1 - 0.09) plus the cables
    r, f_at, dof = receptance_amplification(m, (0.9 * f[0], 1.1 * f[0]), f)
    assert r > 0.6 / (2 * 0.02) and abs(f_at / f[0] - 1) < 0.01


@pytest.mark.parametrize("band", [(0.0, 1.5), (1.5, 3.0), (2.0, 6.0)])
def test_the_receptance_checks_uniform_count_does_not_set_its_ratio(band):
    """On CoGiRo with the default damping, the largest ratio read with the default 100
    uniform points (plus the points clustered at every mode of the band) is that of 4000
    uniform points to 1e-3: the peaks are read at the clustered points (theory.md §12.3).
    Without the clustered points, 100 points miss the damped peaks of a band holding
    platform modes."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.analyses.platform_modes import find_platform_modes
    scene = ds.load_scene("cogiro")
    eq = scene.equilibrium()
    m = ds.build_model(eq, "dsm")
    modes = find_platform_modes(m, band[1] * 1.05, 0.03).modes.freq_hz
    dm = damped_model(eq, scene.damping, "dsm", m)
    fine = receptance_amplification(dm, band, modes, 4000)[0]
    assert receptance_amplification(dm, band, modes)[0] == pytest.approx(fine, rel=1e-3)
    if np.any((modes >= band[0]) & (modes <= band[1])) and band[0] > 0:
        assert receptance_amplification(dm, band, (), 100)[0] < 0.999 * fine


def test_modal_data_of_a_first_coincident_pair_alone_takes_the_full_modes():
    """The octahedron with ten times the inertia: its first two modes coincide (C3v). Below
    20 Hz they are the only modes, and modal_data still takes dynstiff.modes for them
    (cable energies computed), as it does for a longer list."""
    from conftest import inverted_stewart
    rob = inverted_stewart(inertia=(100.0, 100.0, 150.0))
    m = ds.build_model(rob.equilibrium(pose=[0.0, 0.0, 1.5], tol=1e-12), "dsm")
    res, ref = modal_data(m, 20.0), ds.modes(m, fmax_hz=20.0)
    assert res.freq_hz.size == 2 and res.freq_hz[1] - res.freq_hz[0] <= 1e-8 * res.freq_hz[1]
    assert np.all(np.isfinite(res.cable_energy))
    np.testing.assert_array_equal(res.platform_share, ref.platform_share)


def test_modal_data_of_the_lumped_rung_obeys_the_sum_rule():
    """Other rungs go through dynstiff.modes: on the lumped CoGiRo (2 segments per cable,
    all 30 modes) the frequencies are those of the dense generalized eigenproblem (K, M)
    and each free DOF's participations sum to 1 (theory.md §12.1)."""
    import scipy.linalg
    sc = ds.load_scene("cogiro")
    lm = ds.build_model(sc.equilibrium(), "lumped", segments=2)
    res = modal_data(lm, 1e6, max_modes=lm.n_dof)
    K, M = (a.toarray() if hasattr(a, "toarray") else np.asarray(a) for a in lm.matrices())
    lam = scipy.linalg.eigh(K, M, eigvals_only=True)
    np.testing.assert_allclose(res.freq_hz, np.sqrt(lam) / (2 * np.pi), rtol=1e-8)
    np.testing.assert_allclose(res.participation.sum(axis=0), 1.0, rtol=1e-10)


def test_modal_data_of_a_point_mass_holds_the_rotations():
    """A point mass (x, y, z free, 20 kg) on three cables, closed form: the fast path's
    platform mass is 20 kg on the translations and 0 on the held rotations, whose
    participations are 0; each translation's participations over the modes below 60 Hz sum
    to at most 1 (the sum rule) and equal dynstiff.modes'; every global mode continues a
    mode of the massless-cable model, eigenvalues of (K0, m I)."""
    import scipy.linalg
    from conftest import point_mass_robot
    eq = point_mass_robot(mass=20.0).equilibrium(pose=[0.2, -0.1, 1.0, 0, 0, 0])
    m = ds.build_model(eq, "dsm")
    res, ref = modal_data(m, 12.0), ds.modes(m, fmax_hz=12.0)
    assert np.all(np.isnan(res.cable_energy))
    np.testing.assert_array_equal(res.platform_mass, np.diag([20.0] * 3 + [0.0] * 3))
    p = res.participation
    assert np.all(p[:, 3:] == 0) and np.all(p.sum(axis=0)[:3] <= 1 + 1e-9)
    np.testing.assert_allclose(p, ref.participation, atol=1e-7)
    f0 = np.sqrt(scipy.linalg.eigvalsh(m.massless_stiffness(), 20.0 * np.eye(3))) / (2 * np.pi)
    glob = np.array(res.kind) == "global"
    assert glob.sum() >= 2
    got = res.massless_freq_hz[glob]
    assert np.all(np.min(np.abs(got[:, None] - f0[None, :]), axis=1) <= 1e-9 * f0.max())
    assert len(set(got)) == got.size                    # one to one
    np.testing.assert_array_equal(res.massless_freq_hz, ref.massless_freq_hz)


def test_modal_data_of_nearly_coincident_roots_takes_the_full_modes():
    """Roots split by less than 1e-8 of the higher one count as coincident: the octahedron
    of inertia (100, 100 (1 + 1e-9), 150) kg m^2 splits its C3v pair at 16.7 Hz by 5e-10
    (relative), and modal_data takes dynstiff.modes (cable energies computed); a split of
    5e-8 (inertia 1 + 1e-7) takes the fast path (cable energies NaN)."""
    from conftest import inverted_stewart
    for eps, full in ((1e-9, True), (1e-7, False)):
        rob = inverted_stewart(inertia=(100.0, 100.0 * (1 + eps), 150.0))
        m = ds.build_model(rob.equilibrium(pose=[0.0, 0.0, 1.5], tol=1e-12), "dsm")
        res, ref = modal_data(m, 20.0), ds.modes(m, fmax_hz=20.0)
        split = (res.freq_hz[1] - res.freq_hz[0]) / res.freq_hz[1]
        assert res.freq_hz.size == 2 and 0.1 * eps < split < eps     # split, not coincident
        assert np.all(np.isfinite(res.cable_energy)) == full
        assert np.all(np.isnan(res.cable_energy)) == (not full)
        np.testing.assert_allclose(res.platform_share, ref.platform_share, atol=1e-8)
