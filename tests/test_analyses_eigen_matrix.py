"""Modes of the discrete rungs (dynstiff/analyses/eigen_matrix.py, theory.md §7.1-§7.2): sparse
shift-invert equals dense, platform shapes are mass-normalised with the held DOFs zero, and
the cable energies and node shapes of the lumped model."""

import re

import numpy as np
import pytest
from conftest import linearised, point_mass_robot

import dynstiff as ds
from dynstiff.analyses import eigen_matrix
from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import LumpedModalResult


def test_sparse_shift_invert_equals_dense(lumped, monkeypatch):
    model = lumped(20)
    assert model.n_dof > eigen_matrix.DENSE_LIMIT
    f_sparse = ds.eigenfrequencies(model, 12)
    monkeypatch.setattr(eigen_matrix, "DENSE_LIMIT", 10**6)
    np.testing.assert_allclose(ds.eigenfrequencies(model, 12), f_sparse, rtol=1e-10)


def test_modes_normalisation_and_energy(cogiro, lumped):
    model = lumped(20)
    md = ds.modes(model, 12)
    assert isinstance(md, LumpedModalResult)
    M_p = ds.robot.platform.platform_mass_matrix(cogiro.robot.platform, model.pose.matrix)
    x = md.platform_shapes
    np.testing.assert_allclose(np.einsum("ni,ij,nj->n", x, M_p, x), 1.0, rtol=1e-10)
    np.testing.assert_allclose(md.cable_energy.sum(axis=1), md.cable_energy_fraction,
                               rtol=1e-12)
    kinds = np.array(md.kind)
    assert np.all(md.cable_energy_fraction[kinds == "global"] < 0.5)
    assert np.all(md.cable_energy_fraction[kinds == "local"] >= 0.5)
    # node shapes: anchors at rest, the last node moves with the platform point B_i
    _, r = cogiro.robot.attachment_points(model.pose)
    k = int(np.flatnonzero(kinds == "global")[0])
    B_motion = np.array([ns[k, -1] for ns in md.node_shapes])
    scale = B_motion[0, 0] / (x[k, :3] + np.cross(x[k, 3:], r[0]))[0]
    np.testing.assert_allclose(B_motion, scale * (x[k, :3] + np.cross(x[k, 3:], r)),
                               atol=1e-12 * np.abs(B_motion).max())
    assert all(np.all(ns[:, 0] == 0) for ns in md.node_shapes)
    # massless-cable (condensed) frequencies lie above the global ones (cable inertia)
    g = kinds == "global"
    assert np.all(md.massless_freq_hz[g] > md.freq_hz[g])


def test_point_mass_held_rotations_are_zero():
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.2, -0.1, 1.0])
    md = ds.modes(linearised(rob, eq.unstretched_lengths, 8), 10)
    assert np.all(md.platform_shapes[:, 3:] == 0)
    np.testing.assert_allclose(np.sum(md.platform_shapes[:, :3] ** 2, axis=1) * 20.0, 1.0,
                               rtol=1e-12)


def test_band_request_counts_first_and_solves_once(lumped, cogiro_eq, monkeypatch):
    """The number of modes below fmax is the W-W count of the condensed K (exact for a
    discrete model): it equals the dense eigenvalue count at every probe, and a band request
    then takes one sparse solve of exactly that many modes."""
    import scipy.linalg
    model = lumped(20)
    K, M = model.matrices()
    K = 0.5 * (K + K.T)
    lam = scipy.linalg.eigh(K.toarray(), M.toarray(), eigvals_only=True)
    f_all = np.sqrt(np.abs(lam)) * np.sign(lam) / (2 * np.pi)
    for f_probe in (0.5, 2.3, 3.4, 6.0, 9.97):
        gap = np.abs(f_all / f_probe - 1).min()
        assert gap > 1e-6                                  # probe away from any mode
        assert eigen_matrix.count_below(model, 2 * np.pi * f_probe) == \
            np.sum(f_all < f_probe)
    spring = ds.build_model(cogiro_eq, "spring")
    Ks, Ms = spring.matrices()
    lam_s = scipy.linalg.eigh(0.5 * (Ks + Ks.T), Ms, eigvals_only=True)
    assert eigen_matrix.count_below(spring, 2 * np.pi * 3.0) == \
        np.sum(lam_s < (2 * np.pi * 3.0) ** 2) > 0
    calls = []
    eig = eigen_matrix.eig
    monkeypatch.setattr(eigen_matrix, "eig", lambda m, n: calls.append(n) or eig(m, n))
    f = ds.eigenfrequencies(model, fmax_hz=10.0)
    assert calls == [np.sum(f_all < 10.0)] == [len(f)]
    np.testing.assert_allclose(f, f_all[:len(f)], rtol=1e-9)


class _Chain:
    """Model stub with ``matrices()``: ``n`` masses ``m`` [kg] in a row joined by springs
    ``k`` [N/m], both ends fixed, optionally a negative ground spring at the middle mass
    (an unstable equilibrium)."""

    rung = "chain"

    def __init__(self, n, k, m, negative_spring=0.0):
        import scipy.sparse
        self.n_dof = n
        K = scipy.sparse.diags([-k * np.ones(n - 1), 2 * k * np.ones(n), -k * np.ones(n - 1)],
                               [-1, 0, 1]).tolil()
        K[n // 2, n // 2] -= negative_spring
        self.K, self.M = K.tocsr(), scipy.sparse.diags(m * np.ones(n), format="csr")

    def matrices(self):
        return self.K, self.M


@pytest.mark.parametrize("k, m", [(1.0, 1.0), (1e-3, 1e4), (1e6, 1e3)])
def test_sparse_shift_invert_any_units(k, m):
    """The sparse path finds the lowest eigenpairs of a soft-heavy or stiff-heavy chain."""
    n = eigen_matrix.DENSE_LIMIT + 1
    chain = _Chain(n, k, m)
    lam, V = eigen_matrix.eig(chain, 10)
    j = np.arange(1, 11)
    np.testing.assert_allclose(lam, 2 * k / m * (1 - np.cos(j * np.pi / (n + 1))), rtol=1e-9)
    np.testing.assert_allclose(V.T @ (chain.M @ V), np.eye(10), atol=1e-12)


def test_small_model_reports_unstable_eigenvalue():
    """A small model's lowest modes include an unstable equilibrium's negative eigenvalue."""
    import scipy.linalg
    chain = _Chain(20, 1.0, 2.0, negative_spring=5.0)
    ref = scipy.linalg.eigh(chain.K.toarray(), chain.M.toarray(), eigvals_only=True)[:3]
    assert ref[0] < 0 < ref[1]
    lam, _ = eigen_matrix.eig(chain, 3)
    np.testing.assert_allclose(lam, ref, rtol=1e-10)
    np.testing.assert_allclose(eigen_matrix.eigenfrequencies(chain, 3),
                               np.sign(ref) * np.sqrt(np.abs(ref)) / (2 * np.pi), rtol=1e-10)


def test_a_large_unstable_model_keeps_its_negative_eigenvalue(monkeypatch):
    """Above DENSE_LIMIT the shift-invert solve about a negative shift misses eigenvalues
    below it (an unstable equilibrium): the inertia of K counts them and the dense solver
    takes over, up to UNSTABLE_DENSE_LIMIT DOFs; above, an error says so."""
    import scipy.linalg

    from dynstiff.errors import ConvergenceError
    n = eigen_matrix.DENSE_LIMIT + 100
    chain = _Chain(n, 1.0, 2.0, negative_spring=5.0)
    ref = scipy.linalg.eigh(chain.K.toarray(), chain.M.toarray(), eigvals_only=True)[:3]
    assert ref[0] < 0 < ref[1]
    assert eigen_matrix._negative_count(chain.K) == 1
    assert eigen_matrix._negative_count(_Chain(n, 1.0, 2.0).K) == 0
    lam, _ = eigen_matrix.eig(chain, 3)
    np.testing.assert_allclose(lam, ref, rtol=1e-10)
    monkeypatch.setattr(eigen_matrix, "UNSTABLE_DENSE_LIMIT", n - 1)
    with pytest.raises(ConvergenceError, match=rf"^the 'chain' model's stiffness has negative "
                                                rf"eigenvalues .*1 counted.*{n} DOFs"):
        eigen_matrix.eig(chain, 3)
    lam, _ = eigen_matrix.eig(_Chain(n, 1.0, 2.0), 3)        # stable: the sparse path
    assert lam[0] > 0


def test_eig_n_modes_range(cogiro_eq):
    """eig takes 1 to n_dof modes (all of them at n_dof) and names n_modes otherwise."""
    import scipy.linalg
    spring = ds.build_model(cogiro_eq, "spring")
    K, M = spring.matrices()
    ref = scipy.linalg.eigh(0.5 * (K + K.T), M, eigvals_only=True)
    for n in (1, np.int64(3), spring.n_dof):
        np.testing.assert_allclose(eigen_matrix.eig(spring, n)[0], ref[:n], rtol=1e-12)
    for bad in (0, spring.n_dof + 1, True, 2.0):
        msg = (f"n_modes must be an integer in [1, {spring.n_dof}] (the number of DOFs of the "
               f"'spring' model), got {bad!r}")
        with pytest.raises(InvalidParameterError, match=re.escape(msg) + "$"):
            eigen_matrix.eig(spring, bad)
    with pytest.raises(InvalidParameterError, match=re.escape("n_modes must be an integer in")):
        ds.eigenfrequencies(spring, spring.n_dof + 1)


def _dense_frequencies(model):
    """All eigenfrequencies [Hz] of the model's (K, M) by a dense solve, ascending."""
    import scipy.linalg
    K, M = model.matrices()
    K = 0.5 * (K + K.T)
    dense = [A.toarray() if hasattr(A, "toarray") else A for A in (K, M)]
    lam = scipy.linalg.eigh(*dense, eigvals_only=True)
    return np.sign(lam) * np.sqrt(np.abs(lam)) / (2 * np.pi)


def _recorded_eig(monkeypatch):
    """Patch eig to record the mode counts it is asked for (at most 6 solves)."""
    calls, eig = [], eigen_matrix.eig

    def recording(model, n):
        calls.append(n)
        assert len(calls) <= 6, f"eig called for {calls}"
        return eig(model, n)
    monkeypatch.setattr(eigen_matrix, "eig", recording)
    return calls


def test_band_request_capped_by_n_modes(lumped, monkeypatch):
    """With n_modes and fmax both given, one solve returns the first n_modes of the band."""
    model = lumped(5)
    f_all = _dense_frequencies(model)
    fmax = 0.5 * (f_all[10] + f_all[11])                   # 11 modes in the band
    calls = _recorded_eig(monkeypatch)
    for n_modes in (1, 10, 11, 12, model.n_dof):
        calls.clear()
        f = ds.eigenfrequencies(model, n_modes, fmax_hz=fmax)
        assert calls == [min(11, n_modes)]
        np.testing.assert_allclose(f, f_all[:min(11, n_modes)], rtol=1e-9)


@pytest.mark.parametrize("n_modes, band, solves", [
    (None, (15, 16), [12, 24]),       # 16 modes below fmax: 12, then 24
    (None, (2, 3), [12]),             # 3 modes: the first solve covers the band
    (5, (6, 7), [5, 10]),             # 7 modes below fmax, the first 5 of them
    (5, (2, 3), [5]),                 # 3 modes, fewer than n_modes
])
def test_band_request_without_count(lumped, monkeypatch, n_modes, band, solves):
    """Where the W-W count is unavailable, the solve doubles its count (from 12, or from
    n_modes) until the band is covered and returns exactly the modes below fmax."""
    model = lumped(5)
    f_all = _dense_frequencies(model)
    fmax = 0.5 * (f_all[band[0]] + f_all[band[1]])
    expected = f_all[:band[1]][:n_modes]
    monkeypatch.setattr(eigen_matrix, "count_below", lambda m, w: None)
    calls = _recorded_eig(monkeypatch)
    f = ds.eigenfrequencies(model, n_modes, fmax_hz=fmax)
    assert calls == solves
    np.testing.assert_allclose(f, expected, rtol=1e-9)


def test_band_request_without_count_edges(lumped, cogiro_eq, monkeypatch):
    """Count unavailable: fmax on the 12th mode takes one solve and excludes that mode; a
    band above every mode returns all of them; an overcount still gives the band."""
    model = lumped(5)
    f_all = _dense_frequencies(model)
    f12 = ds.eigenfrequencies(model, 12)[-1]
    monkeypatch.setattr(eigen_matrix, "count_below", lambda m, w: None)
    calls = _recorded_eig(monkeypatch)
    f = ds.eigenfrequencies(model, fmax_hz=f12)
    assert calls == [12]
    np.testing.assert_allclose(f, f_all[:11], rtol=1e-9)
    spring = ds.build_model(cogiro_eq, "spring")
    np.testing.assert_allclose(ds.eigenfrequencies(spring, fmax_hz=100.0),
                               _dense_frequencies(spring), rtol=1e-12)
    fmax = 0.5 * (f_all[15] + f_all[16])
    monkeypatch.setattr(eigen_matrix, "count_below", lambda m, w: 19)
    np.testing.assert_allclose(ds.eigenfrequencies(model, fmax_hz=fmax), f_all[:16], rtol=1e-9)


def _modal_result(shapes, cable_fraction):
    n = len(shapes)
    return ds.ModalResult(freq_hz=np.arange(1.0, n + 1), platform_shapes=np.asarray(shapes),
                          cable_energy_fraction=np.asarray(cable_fraction),
                          cable_energy=np.asarray(cable_fraction)[:, None])


def test_massless_pairing_brute_force():
    """The pairing maximises the summed participation over all one-to-one assignments and
    keeps the pairs from 0.1 (inclusive)."""
    import itertools

    import scipy.linalg
    rng = np.random.default_rng(3)
    fi = np.array([0, 2, 4])
    A, B = rng.normal(size=(2, 3, 3))
    Mp, K0 = A @ A.T + np.eye(3), 1e4 * (B @ B.T + np.eye(3))
    X = rng.normal(size=(5, 3))
    X /= np.sqrt(np.einsum("ni,ij,nj->n", X, Mp, X))[:, None]          # x^T Mp x = 1
    shapes = np.zeros((5, 6))
    shapes[:, fi] = X
    frac = rng.uniform(0.0, 1.0, 5)
    out = eigen_matrix.massless_pairing(_modal_result(shapes, frac), K0, Mp, fi)
    lam0, X0 = scipy.linalg.eigh(K0, Mp)
    score = (X @ Mp @ X0) ** 2 * (1 - frac)[:, None]
    best = max(itertools.permutations(range(5), 3),                   # massless mode j -> p[j]
               key=lambda p: sum(score[p[j], j] for j in range(3)))
    expected = np.full(5, np.nan)
    kept = [j for j in range(3) if score[best[j], j] >= 0.1]
    assert 0 < len(kept) < 3                                   # both outcomes are exercised
    expected[[best[j] for j in kept]] = np.sqrt(lam0[kept]) / (2 * np.pi)
    np.testing.assert_allclose(out, expected, rtol=1e-12)
    # a pair of participation exactly 0.1 is kept, one just below it is not
    for c, keep in ((np.sqrt(0.1), True), (np.nextafter(np.sqrt(0.1), 0.0), False)):
        assert bool(c * c == 0.1) == keep
        shapes = np.zeros((2, 6))
        shapes[0, 0], shapes[1, :2] = 1.0, (np.sqrt(1 - c * c), c)
        out = eigen_matrix.massless_pairing(_modal_result(shapes, np.zeros(2)),
                                            np.diag([1.0, 4.0]) * (2 * np.pi) ** 2,
                                            np.eye(2), np.array([0, 1]))
        np.testing.assert_allclose(out, [1.0, 2.0 if keep else np.nan], rtol=1e-12)


def test_massless_modes_solve_the_static_problem_once_per_model(cogiro_eq):
    """(lam, X) of (K0, M_p): for a point mass (M_p = m I) lam = eig(K0) / m; for CoGiRo
    the eigenvalues of M_p^-1 K(0) by the general nonsymmetric solver, K0 X = M_p X diag(lam)
    and X^T M_p X = I, read-only. The closed form keeps them in its memo (a second call
    returns the same arrays); a model without a memo solves each time."""
    spring = ds.build_model(point_mass_robot().equilibrium(pose=[0.2, -0.1, 1.0]), "spring")
    assert not hasattr(spring, "_memo")
    K0 = spring.massless_stiffness()
    for _ in range(2):
        lam, X = eigen_matrix.massless_modes(spring)
        np.testing.assert_allclose(lam, np.linalg.eigvalsh(K0) / 20.0, rtol=1e-12)
    m = ds.FrequencyModel(cogiro_eq)
    K0, Mp = np.real(m.dynamic_stiffness(0.0))[0], m.platform_mass
    lam, X = eigen_matrix.massless_modes(m)
    ref = np.sort(np.linalg.eigvals(np.linalg.solve(Mp, K0)).real)
    np.testing.assert_allclose(lam, ref, rtol=1e-10)
    np.testing.assert_allclose(K0 @ X, Mp @ X * lam, atol=1e-9 * np.abs(K0).max())
    np.testing.assert_allclose(X.T @ Mp @ X, np.eye(6), atol=1e-12)
    assert not lam.flags.writeable and not X.flags.writeable
    again = eigen_matrix.massless_modes(m)
    assert again[0] is lam and again[1] is X
