"""Damped complex natural frequencies (dynstiff/analyses/damped.py, theory.md §5.4)."""

import numpy as np
import pytest
import scipy.linalg
from conftest import inverted_stewart

import dynstiff as ds
from dynstiff.analyses.damped import _perturbation_estimates, damped_modes


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def skew(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def robot_with(scene, **cable_kw):
    r = scene.robot
    cable = ds.Cable(cable_kw.pop("mass_per_length", 0.064), r.cables[0].EA, **cable_kw)
    return ds.Robot(r.anchors, r.attachments, cable, r.platform, tension_limits=r.tension_limits)


def test_massless_hysteretic_matches_complex_eigenproblem(scene):
    """Massless cables with EA(1 + i eta): K_c = sum J^T (k (1 + i eta) u u^T + t/l (I - u u^T))
    J + K_geo is frequency independent, so omega^2 are the eigenvalues of (K_c, M)."""
    eta = 0.05
    rob = robot_with(scene, mass_per_length=1e-7, loss_factor=eta)
    eq = rob.equilibrium(pose=scene.pose)
    m = ds.FrequencyModel(eq)
    K = np.zeros((6, 6), dtype=complex)
    for i, s in enumerate(eq.states):
        r = eq.lever_arms[i]
        d = s.anchor - s.end
        l = np.linalg.norm(d)
        u = d / l
        t = s.tension_at_end
        Kc = rob.cables[i].EA * (1 + 1j * eta) / eq.unstretched_lengths[i] * np.outer(u, u) \
            + t / l * (np.eye(3) - np.outer(u, u))
        J = np.hstack([np.eye(3), -skew(r)])
        K += J.T @ Kc @ J
    K += m.K_geo
    lam = scipy.linalg.eigvals(K, m.M_p)
    w_ref = np.sort_complex(np.sqrt(lam))                 # principal root: Im > 0
    d = damped_modes(m, 6)
    np.testing.assert_allclose(np.sort_complex(d.omega), w_ref, rtol=1e-7)
    assert np.all(d.damping_ratio > 0) and np.all(d.damping_ratio < eta / 2 + 1e-6)


@pytest.mark.parametrize("zeta", [0.02, 0.25, 0.4])
def test_platform_damping_on_massless_cables_is_classical(scene, zeta):
    """Massless cables, platform ratio zeta: roots w_r sqrt(1+2i zeta), estimates w_r (1+i zeta)."""
    # K = K_s (1 + 2i zeta) - omega^2 M_p; at zeta = 0.25 the estimates are 4.5 % off, all
    # found; at 0.4 mode 0's root is nearer mode 1's estimate than its own, and only its
    # shape tells whose it is (it was given to mode 1, and mode 0 left NaN)
    rob = robot_with(scene, mass_per_length=1e-7)
    m = ds.FrequencyModel(rob.equilibrium(pose=scene.pose), platform_damping_ratio=zeta)
    w_r = np.sqrt(scipy.linalg.eigvalsh(m.massless_stiffness(), m.platform_mass))
    d = damped_modes(m, 6)
    np.testing.assert_allclose(d.omega, w_r * np.sqrt(1 + 2j * zeta), rtol=1e-7)
    est = _perturbation_estimates(m, ds.modes(m, 6))
    np.testing.assert_allclose(est, w_r * (1 + 1j * zeta), rtol=1e-7)


def test_damping_ratio_is_linear_in_loss_factor(scene):
    z = []
    for eta in (1e-3, 2e-3):
        m = ds.FrequencyModel(robot_with(scene, loss_factor=eta).equilibrium(pose=scene.pose))
        z.append(damped_modes(m, 3).damping_ratio)
    np.testing.assert_allclose(z[1] / z[0], 2.0, rtol=2e-3)


def test_viscous_damping_gives_decaying_modes(scene):
    m = ds.FrequencyModel(robot_with(scene, viscous_damping=0.02).equilibrium(pose=scene.pose))
    d = damped_modes(m, 24)
    ok = np.isfinite(d.omega)
    glob = np.array(ds.modes(m, 24).kind) == "global"
    assert glob.sum() == 6 and np.all(ok[glob])      # every global mode is found
    # overlapping local modes (spacing ~ their damping) are NaN, never a wrong root
    assert len(set(np.round(d.omega[ok], 9))) == ok.sum()
    assert np.all(d.damping_ratio[ok] > 0)
    assert np.all(d.residual[ok] < 1e-8)
    np.testing.assert_allclose(d.freq_hz[ok], d.undamped_freq_hz[ok], rtol=5e-3)


def test_purely_local_modes_are_nan_and_the_modes_above_them_are_found():
    """Platform-at-rest modes: NaN root and residual; the global modes above them are found."""
    eq = inverted_stewart(mass_per_length=0.1, EA=1e5).equilibrium(pose=ds.Pose([0, 0, 1.5]))
    m = ds.FrequencyModel(eq, platform_damping_ratio=0.02)      # symmetric: purely local modes
    u = ds.modes(m, fmax_hz=14.0)
    d = damped_modes(m, fmax_hz=14.0)
    at_rest = ~np.any(u.platform_shapes, axis=1)
    assert at_rest.any()
    assert np.all(np.isnan(d.omega[at_rest])) and np.all(np.isnan(d.residual[at_rest]))
    above = (np.arange(len(u)) > np.flatnonzero(at_rest)[0]) & (np.array(u.kind) == "global")
    assert above.any() and np.all(d.residual[above] < 1e-8)
    np.testing.assert_allclose(d.freq_hz[above], u.freq_hz[above], rtol=1e-3)
    assert np.all(d.damping_ratio[above] > 0)


@pytest.mark.parametrize("kw", [dict(tol=0.5), dict(max_iter=1)])
def test_a_root_stopped_after_one_secant_step_is_nan_with_its_residual(scene, kw):
    """Stopped after one secant step (tol=0.5 or max_iter=1): NaN, with that step's residual."""
    m = ds.FrequencyModel(scene.equilibrium(), platform_damping_ratio=0.05)
    u = ds.modes(m, 1)
    x, w = u.platform_shapes[0][m.free_index], 2 * np.pi * u.freq_hz[0]
    mu, h = m.undamped(), 1e-6 * w
    dK = (mu.dynamic_stiffness(w + h)[0] - mu.dynamic_stiffness(w - h)[0]) / (2 * h)
    est = w - x @ (m.dynamic_stiffness(w)[0] - mu.dynamic_stiffness(w)[0]) @ x / (x @ dK @ x)

    def det(z):
        return np.linalg.det(m.dynamic_stiffness(z)[0])
    e = 1e-7 * abs(est)
    K = m.dynamic_stiffness(est - det(est) * 2 * e / (det(est + e) - det(est - e)))[0]
    # |lambda_min(K)| / ||K||_2 after a Newton step from the estimate (= the secant's to 1e-3)
    residual = np.abs(np.linalg.eigvals(K)).min() / np.linalg.svd(K, compute_uv=False)[0]
    assert residual > 1e-6                        # far from converged
    d = damped_modes(m, 1, **kw)
    assert np.isnan(d.omega[0])
    np.testing.assert_allclose(d.residual[0], residual, rtol=1e-2)
    assert damped_modes(m, 1).residual[0] < 1e-8  # the default tol converges


@pytest.mark.parametrize("kw, message", [
    (dict(tol=True), "^tol must be a real number, got True$"),
    (dict(tol="a"), "^tol must be a real number, got 'a'$"),
    (dict(tol=-1.0), r"^tol must be > 0, got -1\.0$"),
    (dict(max_iter=True), "^max_iter must be an integer >= 1, got True$"),
    (dict(max_iter=2.0), r"^max_iter must be an integer >= 1, got 2\.0$")])
def test_the_secant_options_are_checked_naming_them(scene, kw, message):
    """max_iter=True was one secant step, and tol text a TypeError in the loop."""
    m = ds.FrequencyModel(scene.equilibrium(), platform_damping_ratio=0.02)
    with pytest.raises(ds.InvalidParameterError, match=message):
        ds.damped_modes(m, n_modes=1, **kw)


def test_both_copies_of_a_double_mode_have_the_root():
    """A symmetric robot's double modes (equal undamped frequencies): the damped root is a
    double zero of det K, the root of both copies, w_r sqrt(1 + 2i zeta) for massless cables
    and platform damping zeta (the second copy was NaN, its root taken by the first)."""
    eq = inverted_stewart(mass_per_length=1e-7).equilibrium(pose=ds.Pose([0, 0, 1.5]))
    m = ds.FrequencyModel(eq, platform_damping_ratio=0.02)
    w_r = np.sqrt(scipy.linalg.eigvalsh(m.massless_stiffness(), m.platform_mass))
    assert np.sum(np.isclose(np.diff(w_r), 0.0, atol=1e-9 * w_r.max())) == 2   # two doubles
    d = damped_modes(m, 6)
    np.testing.assert_allclose(d.omega, w_r * np.sqrt(1 + 0.04j), rtol=1e-7)
    assert np.all(d.residual < 1e-8)


def test_a_root_whose_shape_is_ambiguous_goes_to_the_nearest_estimate(scene, monkeypatch):
    """Where the shape names no mode (MAC test inconclusive), the root goes to the mode whose
    estimate is nearest; a lone mode (no other estimate) keeps its root: the same roots as
    with the shape test."""
    import dynstiff.analyses.damped as damped
    m = ds.FrequencyModel(robot_with(scene, loss_factor=0.01).equilibrium(pose=scene.pose))
    want = [damped_modes(m, n).omega for n in (1, 3)]
    monkeypatch.setattr(damped, "_shape_owner", lambda *a: None)
    for n, w in zip((1, 3), want):
        got = damped_modes(m, n).omega
        assert np.all(np.isfinite(got))
        np.testing.assert_array_equal(got, w)



@pytest.mark.parametrize("scale, found", [(0.85, True), (0.75, False)])
def test_a_secant_that_leaves_its_estimates_disc_gives_up(scene, monkeypatch, scale, found):
    """The secant is confined to |omega - estimate| <= 0.2 |estimate|. The first mode's
    estimate moved down (no root below it): at 0.85 of it the root is 0.15 / 0.85 = 18 % of
    the estimate away and is found; at 0.75 it is 33 % away, outside the disc: NaN."""
    import dynstiff.analyses.damped as damped
    m = ds.FrequencyModel(scene.equilibrium(), platform_damping_ratio=0.02)
    root = damped_modes(m, 1).omega[0]
    monkeypatch.setattr(damped, "_perturbation_estimates",
                        lambda model, und: scale * _perturbation_estimates(model, und))
    got = damped_modes(m, 1)
    if found:
        np.testing.assert_allclose(got.omega[0], root, rtol=1e-10)
    else:
        assert np.isnan(got.omega[0])


class Overflowing(ds.FrequencyModel):
    """K overflowing in an intermediate at complex omega, returned finite (1 / inf = 0)."""

    def dynamic_stiffness(self, omega):
        if np.any(np.imag(omega) != 0):
            1.0 / np.exp(np.full(1, 800.0))
        return super().dynamic_stiffness(omega)


def test_floating_point_warnings_of_k_at_complex_iterates_are_silenced(scene):
    """A model whose K overflows in an intermediate at complex omega (an exact rung's
    hyperbolic functions far from the real axis) but is finite: no RuntimeWarning leaves
    damped_modes, and the roots are those of the same K without the overflow."""
    import warnings
    eq = scene.equilibrium()
    want = damped_modes(ds.FrequencyModel(eq, platform_damping_ratio=0.02), 2).omega
    m = Overflowing(eq, platform_damping_ratio=0.02)
    with pytest.warns(RuntimeWarning, match="overflow"):
        m.dynamic_stiffness(14.0 + 0.3j)                # the planted overflow does warn
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = damped_modes(m, 2).omega
    np.testing.assert_array_equal(got, want)


def test_a_multiple_root_found_again_goes_to_the_copy_whose_search_found_it(monkeypatch):
    """Bookkeeping of a triple root on a synthetic 4-DOF K(w): a(w) I on three DOFs with a
    Jordan coupling (so the null vector is e0 alone, its shape unambiguous), a = (1 + 2i zeta)
    - w^2, root r = sqrt(1 + 2i zeta). Three copies of the undamped mode (shapes e0, e1, e2):
    copy 0's estimate is 0.75 r (its secant leaves the disc, gives up); copy 1's search finds
    r, which its shape gives to copy 0; copy 2's search, deflated once, finds r again and keeps
    it (not copy 1, the first NaN copy). With every search converging, all three hold r."""
    from types import SimpleNamespace

    import dynstiff.analyses.damped as damped
    zeta = 0.02
    r = np.sqrt(1 + 2j * zeta)

    def K(w):
        k = np.zeros((1, 4, 4), complex)
        k[0, [0, 1, 2], [0, 1, 2]] = (1 + 2j * zeta) - complex(w) ** 2
        k[0, [0, 1], [1, 2]] = 1.0
        k[0, 3, 3] = 10.0
        return k

    class Undamped:
        freq_hz = np.full(3, 1 / (2 * np.pi))
        platform_shapes = np.eye(4)[:3]

        def __len__(self):
            return 3
    model = SimpleNamespace(dynamic_stiffness=K, free_index=np.arange(4),
                            platform_mass=np.eye(4))
    monkeypatch.setattr(damped, "modes", lambda *a, **kw: Undamped())
    for first, want in ((0.75, [r, np.nan, r]), (1.002, [r, r, r])):
        monkeypatch.setattr(damped, "_perturbation_estimates",
                            lambda *a, first=first: np.array([first, 1.004, 1.006]) * r)
        d = damped_modes(model, 3)
        np.testing.assert_allclose(d.omega, want, rtol=1e-7)
        assert np.all(d.residual[1:] < 1e-8)


@pytest.mark.parametrize("eta", [1e-3, 0.02])
def test_an_exactly_double_mode_gives_both_copies_the_damped_root(eta):
    """The octahedron's two degenerate pairs (C3v, equal to the last bit) under a loss
    factor of every cable, which keeps them double: both copies of each pair get the damped
    root, a zero of K (residual below 1e-8). Before, at eta = 1e-3, the first copy's root
    matched neither shape of the pair alone and tied with its twin's estimate, and was left
    NaN (at 0.02 its null vector happened to match one shape)."""
    eq = inverted_stewart().equilibrium(pose=ds.Pose([0.0, 0.0, 1.5]), tol=1e-12)
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), n_modes=6)
    assert f[1] == f[2] and f[3] == f[4]
    d = damped_modes(ds.build_model(eq, "dsm", cable_loss_factor=eta), n_modes=6)
    assert np.all(np.isfinite(d.omega)) and np.all(d.residual < 1e-8)
    np.testing.assert_allclose(d.omega[[2, 4]], d.omega[[1, 3]], rtol=1e-10)  # secant's tol
    assert np.all(np.abs(np.diff(d.omega[[0, 1, 3, 5]])) > 0.1 * np.abs(d.omega[0]))
