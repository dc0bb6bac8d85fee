"""Compiled FRF kernels (dynstiff/compiled/dsm.py, theory.md §14.1) against the numpy path:
the fused K(omega) + solve of the "dsm" rung, the batched real solve, the reduced assembly
map, and exact singularity."""

import warnings

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.frf import channel_maps
from dynstiff.models.dsm_compiled import compiled_arguments, symmetric_assembly

cf = pytest.importorskip("dynstiff.compiled.dsm", exc_type=ImportError)
cs = pytest.importorskip("dynstiff.compiled.dsm_search", exc_type=ImportError)


def _fused(model, omega, B, C):
    return cf.dsm_receptance(omega, *compiled_arguments(model), B, C)


def _relative_error(H, H0):
    return np.abs(H - H0).max(axis=(1, 2)) / np.abs(H0).max(axis=(1, 2))


@pytest.mark.parametrize("chordwise", [True, False])
def test_fused_kernel_equals_numpy_k_and_solve(cogiro_eq, chordwise):
    """Both paths are backward-stable LU solves of the same K: they agree to 1e-12 where
    K is well conditioned, and to a few eps x cond(K) next to a resonance. The grid crosses
    psi = 1 (the series branch) and several cable and robot modes."""
    m = ds.FrequencyModel(cogiro_eq, chordwise_inertia=chordwise, damping=False)
    omega = 2 * np.pi * np.concatenate([[0.0, 1e-3], np.linspace(0.05, 12.0, 3001)])
    psi = m.stacked_params.psi(omega[:, None])
    assert np.any(psi < 1) and np.any(psi > 1)
    B, C = np.eye(6), np.eye(6)
    H, kmax, singular = _fused(m, omega, B, C)
    K = m.dynamic_stiffness(omega)
    H0 = np.linalg.solve(K, np.broadcast_to(B, K.shape))
    err = _relative_error(H, H0)
    cond = np.linalg.cond(K)
    assert not singular.any()
    assert err[cond < 1e3].max() < 1e-12
    assert np.all(err < 8 * np.finfo(float).eps * cond)
    np.testing.assert_allclose(kmax, np.abs(K).max(axis=(1, 2)), rtol=1e-13)


def test_fused_kernel_applies_the_channel_maps(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    omega = 2 * np.pi * np.array([0.3, 1.1, 2.9])
    B, C, _, _ = channel_maps(m.free_index, m.pose.matrix, ["fz", "my"], ["x", "rz"],
                              [0.1, 0.2, 0.3])
    H = _fused(m, omega, np.ascontiguousarray(B), np.ascontiguousarray(C))[0]
    K = m.dynamic_stiffness(omega)
    H0 = C @ np.linalg.solve(K, np.broadcast_to(B, (3,) + B.shape))
    np.testing.assert_allclose(H, H0, rtol=1e-12, atol=1e-14 * np.abs(H0).max())


def test_symmetric_assembly_rebuilds_k(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    omega = np.array([0.7, 8.0])
    coef = m.cable_coefficients(omega).reshape(2, -1, 5)
    reduced = np.stack([coef[..., 0], coef[..., 1], coef[..., 3], coef[..., 4]], axis=-1)
    Ku = reduced.reshape(2, -1) @ symmetric_assembly(m.assembly_map, 6)
    iu, ju = np.triu_indices(6)
    K = m.dynamic_stiffness(omega) - m.K_geo_free + (omega**2)[:, None, None] * m.platform_mass
    np.testing.assert_allclose(Ku, K[:, iu, ju], rtol=1e-12, atol=1e-12 * np.abs(K).max())


def test_real_receptance_solves_and_flags_exact_singularity():
    rng = np.random.default_rng(3)
    K = rng.standard_normal((50, 5, 5))
    K[7] = 0.0
    K[9, 2] = K[9, 4]                                   # two equal rows: singular
    K[11, 1, 1] = np.inf
    B = rng.standard_normal((5, 2))
    C = rng.standard_normal((3, 5))
    H, singular = cf.real_receptance(K, B, C)
    assert np.flatnonzero(singular).tolist() == [7, 9]
    assert np.all(np.isnan(H[11]))
    ok = np.setdiff1d(np.arange(50), [7, 9, 11])
    H0 = C @ np.linalg.solve(K[ok], np.broadcast_to(B, (ok.size, 5, 2)))
    np.testing.assert_allclose(H[ok], H0, rtol=1e-10, atol=1e-12 * np.abs(H0).max())


def test_count_kernel_equals_numpy_eigenvalues_and_cable_count(cogiro_eq):
    """Eigenvalues of K(omega) and the cable count J0 of the compiled count against the numpy
    path, on a grid that crosses many cable poles (J0 up to dozens) and passes within 1e-9
    (relative) of some of them."""
    m = ds.FrequencyModel(cogiro_eq, damping=False)
    p = m.params[0]
    poles = np.pi * np.sqrt(p.T / p.m) / p.L * np.arange(1, 6)
    omega = np.sort(np.concatenate([np.linspace(0.0, 150.0, 4001), poles * (1 - 1e-9),
                                    poles * (1 + 1e-9)]))
    ev, J0 = cf.dsm_count(omega, *compiled_arguments(m))
    K, J0_ref = m.dynamic_stiffness_and_count(omega)
    np.testing.assert_array_equal(J0, J0_ref)
    np.testing.assert_array_equal(J0_ref, m.cable_mode_count(omega))
    assert J0.max() > 30
    ev_ref = np.linalg.eigvalsh(K)
    # Weyl: both are within a few eps ||K|| of the exact eigenvalues
    scale = np.abs(ev_ref).max(axis=1, keepdims=True)
    assert np.all(np.abs(ev - ev_ref) <= 50 * np.finfo(float).eps * scale)


def test_sign_counts_equal_the_eigenvalue_counts(cogiro_eq, monkeypatch):
    """The seed grid's counts from the pivots' signs (dsm_counts) equal J0 + #(ev < 0) of
    the eigenvalue kernel, on the pole-crossing grid above (within 1e-9 of poles, where K
    is not finite: J = J0 there) and at CoGiRo's first 40 roots -+ 1e-9, where K is
    nearly singular and a pivot may be unsure (the eigenvalues decide then)."""
    m = ds.FrequencyModel(cogiro_eq, damping=False)
    p = m.params[0]
    poles = np.pi * np.sqrt(p.T / p.m) / p.L * np.arange(1, 6)
    roots = 2 * np.pi * ds.eigenfrequencies(m, n_modes=40)
    omega = np.sort(np.concatenate([np.linspace(0.0, 150.0, 4001), poles * (1 - 1e-9),
                                    poles * (1 + 1e-9), poles, roots * (1 - 1e-9),
                                    roots * (1 + 1e-9)]))
    args = compiled_arguments(m)
    ev, J0_ref = cf.dsm_count(omega, *args)
    J, J0, det = cs.dsm_counts(omega, *args)
    np.testing.assert_array_equal(J0, J0_ref)
    np.testing.assert_array_equal(J, J0_ref + np.sum(ev < 0, axis=1))
    assert J.dtype == J0.dtype == np.int64 and J.max() > 30
    k = np.searchsorted(omega, roots * (1 + 1e-9))
    np.testing.assert_array_equal(J[k], np.arange(1, 41))
    # det K where the pivots are sure: what the regula falsi's own evaluation gives, to the
    # bit; NaN where K is not finite (at the poles)
    known = np.isfinite(det)
    assert known.mean() > 0.95 and not np.any(known & np.isnan(ev[:, 0]))
    nf = m.n_free
    Kk, work = np.empty((nf, nf)), np.empty((nf, nf))
    for i in np.flatnonzero(known)[::40]:
        assert det[i] == cs._det_one(omega[i], *args, Kk, work)
    # a pivot planted unsure everywhere: the eigenvalues give the same counts, det unknown
    import numba

    @numba.njit
    def unsure(K, work, last_free):
        return 0, np.nan, False
    monkeypatch.setattr(cs, "_pivots", unsure)
    J2, _, det2 = cs.dsm_counts.py_func(omega[:50], *args)
    assert J2.tolist() == J[:50].tolist() and np.all(np.isnan(det2))


def test_search_from_the_counts_det_gives_the_same_roots_to_the_bit(cogiro_eq):
    """The search reads a bracket's end values of det K from the counts where they knew
    them (the same elimination as its own evaluation): its roots are those of the search
    that computes every end value itself (det_grid all NaN), to the bit."""
    from dynstiff.analyses.eigen import _seed_grid
    m = ds.FrequencyModel(cogiro_eq, damping=False)
    args = compiled_arguments(m)
    grid = _seed_grid(m, 2 * np.pi * 15.0)
    J, J0, det = cs.dsm_counts(grid, *args)
    J[0] = J0[0] = 0
    N = int(J[-1])
    assert N > 60 and np.isfinite(det).sum() > 0.9 * grid.size
    fast = cs.dsm_search(grid, J, J0, det, N, 1e-12, 200, *args)
    slow = cs.dsm_search(grid, J, J0, np.full(grid.size, np.nan), N, 1e-12, 200, *args)
    assert fast[1] == slow[1] == -1
    np.testing.assert_array_equal(fast[0], slow[0])


def test_one_loader_gives_every_kernel_or_none(monkeypatch):
    """dynstiff.compiled.load returns the kernel module, None when switched off by the
    environment, and refuses an unknown name."""
    from dynstiff import compiled
    assert compiled.load("dsm") is cf
    compiled.load.cache_clear()
    monkeypatch.setenv("DYNSTIFF_DISABLE_NUMBA", "1")
    try:
        assert all(compiled.load(name) is None for name in compiled.KERNELS)
    finally:
        compiled.load.cache_clear()
    with pytest.raises(ValueError, match="'nope'"):
        compiled.load("nope")


def test_pivot_signs_count_negative_eigenvalues_or_say_they_are_not_sure():
    """Sylvester's law of inertia: where the elimination is sure, its negative pivots are
    the negative eigenvalues and their product is det K; a zero leading pivot (inertia (1,
    1) of [[0, 1], [1, 0]]) or a tiny one is 'not sure', never a wrong count."""
    rng = np.random.default_rng(7)
    work = np.empty((6, 6))
    sure = 0
    for _ in range(400):
        A = rng.normal(size=(6, 6)) * 10.0 ** rng.uniform(-3, 6)
        K = A + A.T
        neg, det, ok = cs._pivots(K, work, False)
        if ok:
            sure += 1
            assert neg == int(np.sum(np.linalg.eigvalsh(K) < 0))
            assert det == pytest.approx(np.linalg.det(K), rel=1e-9)
    assert sure > 300
    work2 = np.empty((2, 2))
    for K in (np.array([[0.0, 1.0], [1.0, 0.0]]), np.array([[1e-12, 1.0], [1.0, 1e-12]])):
        assert cs._pivots(K, work2, False)[2] is False
    # the last pivot may vanish for the determinant (next to a root), not for the count
    K = np.array([[2.0, 1.0], [1.0, 0.5]])
    assert cs._pivots(K, work2, True)[:2] == (0, 0.0)
    assert cs._pivots(K, work2, False)[2] is False


@pytest.mark.parametrize("scene", ["cogiro", "simulator", "planar2"])
def test_compiled_search_equals_the_numpy_search(scene, monkeypatch):
    """The compiled W-W search (bisection on pivot signs, Illinois on (-1)^s det K) and the
    numpy one (Illinois on the crossing eigenvalue) close brackets of relative width rtol
    on the same roots: they agree to 2 rtol, over enough modes to hold clusters of local
    cable modes (identical cables: multiple roots, bisected) and roots near cable poles."""
    from dynstiff.analyses import eigen
    from dynstiff.errors import ClosedFormWarning
    sc = ds.load_scene(scene)
    m = ds.FrequencyModel(sc.equilibrium(), damping=False)
    # 120 modes reach beyond the closed form's accurate band (it warns): the two searches
    # solve the same K(omega), which is what is compared here
    monkeypatch.setattr(warnings, "filters", list(warnings.filters))
    warnings.simplefilter("ignore", ClosedFormWarning)
    fast = ds.eigenfrequencies(m, n_modes=120, rtol=1e-12)
    counter = eigen._counter

    def without_search(model):
        count = counter(model)
        return lambda omega: count(omega)
    monkeypatch.setattr(eigen, "_counter", without_search)
    ref = ds.eigenfrequencies(m, n_modes=120, rtol=1e-12)
    np.testing.assert_allclose(fast, ref, rtol=2e-12, atol=0)
    if scene != "cogiro":                                   # symmetric: multiple roots
        assert np.any(np.diff(ref) < 1e-9 * ref[1:])
    k = np.arange(120)
    assert np.all(ds.mode_count(m, 2 * np.pi * fast * (1 - 1e-9)) <= k)
    assert np.all(ds.mode_count(m, 2 * np.pi * fast * (1 + 1e-9)) >= k + 1)


@pytest.mark.parametrize("damping", [
    {"cable_loss_factor": 0.01, "platform_damping_ratio": 0.01},
    {"cable_loss_factor": 0.05},
    {"platform_damping_ratio": 0.02},
    "own",
])
def test_damped_kernel_equals_numpy_k_and_solve(cogiro_eq, damping):
    """The complex kernel (loss factors through K(w / sqrt(1 + i eta)) (1 + i eta), the
    platform's damping in K_static, a cable's own complex EA) against numpy's K and solve,
    over a band with cable and robot modes (series branch included)."""
    from dataclasses import replace

    from dynstiff.models.dsm_compiled import damped_compiled_arguments
    eq = cogiro_eq
    if damping == "own":
        robot = replace(eq.robot, cables=[replace(c, loss_factor=0.02) for c in eq.robot.cables])
        eq, damping = robot.equilibrium(pose=eq.pose), {}
    m = ds.FrequencyModel(eq, **damping)
    assert m.damped or damping == {}
    omega = 2 * np.pi * np.concatenate([[0.0, 1e-3], np.linspace(0.05, 6.0, 1201)])
    B, C = np.eye(6), np.eye(6)[[0, 2, 5]]
    H, kmax, singular = cf.dsm_receptance_damped(omega, *damped_compiled_arguments(m), B, C)
    K = m.dynamic_stiffness(omega)
    H0 = C @ np.linalg.solve(K, np.broadcast_to(B, K.shape))
    assert np.iscomplexobj(K) and not singular.any()
    assert _relative_error(H, H0).max() < 1e-11
    np.testing.assert_allclose(kmax, np.abs(K).max(axis=(1, 2)), rtol=1e-13)


def test_viscous_cable_damping_is_left_to_the_numpy_path(cogiro_eq):
    from dataclasses import replace

    from dynstiff.models.dsm_compiled import damped_compiled_arguments
    robot = replace(cogiro_eq.robot,
                    cables=[replace(c, viscous_damping=0.1) for c in cogiro_eq.robot.cables])
    m = ds.FrequencyModel(robot.equilibrium(pose=cogiro_eq.pose))
    assert damped_compiled_arguments(m) is None


def test_stiffness_kernel_equals_numpy_k_and_cable_count(cogiro_eq):
    """K(omega) and J0 of the compiled kernel against FrequencyModel's numpy path, across
    cable poles and the series branch: the same formulas in another order of operations,
    so within a few eps of the largest entry, up to tens of eps next to a pole, where the
    entries divide by a vanishing denominator (the bound of the count kernel's test)."""
    m = ds.FrequencyModel(cogiro_eq, damping=False)
    omega = np.linspace(0.0, 150.0, 3001)
    K, J0 = cf.dsm_stiffness(omega, *compiled_arguments(m))
    K_ref, J0_ref = m.dynamic_stiffness_and_count(omega)
    np.testing.assert_array_equal(J0, J0_ref)
    scale = np.abs(K_ref).max(axis=(1, 2), keepdims=True)
    assert np.all(np.abs(K - K_ref) <= 50 * np.finfo(float).eps * scale)
    assert np.array_equal(K, np.swapaxes(K, 1, 2))
