"""Mode shapes and energies (dynstiff/analyses/modes.py, theory.md §6): the basis of a
cluster of coincident modes, and the mode-count limit on both paths."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.modes import _energy_basis
from dynstiff.errors import InvalidParameterError


@pytest.mark.parametrize("c", [2, 3])
def test_the_basis_of_a_cluster_is_mass_orthonormal_and_diagonal_in_cable_energy(c):
    """Any span of c platform motions (random here, at a frequency between CoGiRo's modes)
    comes back as a basis of the same span, M_p-orthonormal, whose cable kinetic energies
    do not couple: E(x_a + x_b) = E(x_a) + E(x_b), the polarisation written out here."""
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    fi, Mf = m.free_index, m.platform_mass
    omega = 2 * np.pi * 2.5
    V = np.random.default_rng(c).standard_normal((len(fi), c))
    X = _energy_basis(m, omega, V, Mf, fi)
    np.testing.assert_allclose(X.T @ Mf @ X, np.eye(c), atol=1e-12)
    coef = np.linalg.lstsq(V, X, rcond=None)[0]
    np.testing.assert_allclose(V @ coef, X, atol=1e-12 * np.abs(X).max())   # same span
    full = np.zeros((c, 6))
    full[:, fi] = X.T
    E = [m.cable_kinetic_energies(omega, x).sum() for x in full]
    assert max(E) > 1.5 * min(E)                        # distinct: the basis is unique
    for a in range(c):
        for b in range(a + 1, c):
            cross = m.cable_kinetic_energies(omega, full[a] + full[b]).sum() - E[a] - E[b]
            assert abs(cross) < 1e-10 * (E[a] + E[b])


def test_a_lone_roots_shape_is_the_general_basis_to_the_bit():
    """One platform motion: V / sqrt(V^T M_p V), the same numbers as the general basis
    (eigh of the 1 x 1 mass, lam = B, U = 1), without computing cable energies."""
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    fi, Mf = m.free_index, m.platform_mass
    V = np.random.default_rng(11).standard_normal((len(fi), 1))
    B = V.T @ Mf @ V
    lam, U = np.linalg.eigh(0.5 * (B + B.T))
    np.testing.assert_array_equal(_energy_basis(m, 2 * np.pi * 2.5, V, Mf, fi),
                                  V @ (U / np.sqrt(lam)))


def test_the_mode_count_limit_holds_on_both_paths():
    """20000 modes by default: 20001 asked of the closed form is refused naming the limit;
    a discrete rung with more DOFs than max_modes is refused when the band holds more
    modes than that (the spring model's 2 modes against max_modes = 1)."""
    eq = ds.load_scene("planar2").equilibrium()
    with pytest.raises(InvalidParameterError,
                       match="^n_modes = 20001 is more than max_modes = 20000;"):
        ds.modes(ds.build_model(eq, "dsm"), n_modes=20001)
    spring = ds.build_model(eq, "spring")
    assert spring.n_dof == 2 and len(ds.modes(spring, fmax_hz=1e4).freq_hz) == 2
    with pytest.raises(InvalidParameterError,
                       match=r"^fmax_hz = 10000 Hz holds 2 modes, more than max_modes = 1;"):
        ds.modes(spring, fmax_hz=1e4, max_modes=1)


def test_each_cables_energy_is_its_share_of_the_modes_kinetic_energy():
    """cable_energy[k, c] = E_c / (1 + sum E_c), E_c the cable's kinetic energy for the
    M_p-normalised platform shape (platform energy 1), written out here from the model's
    cable_kinetic_energies; its sum is the cable energy fraction."""
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    r = ds.modes(m, n_modes=12)
    for k in range(12):
        x = r.platform_shapes[k]
        assert x @ r.platform_mass @ x == pytest.approx(1.0, rel=1e-12)
        E = m.cable_kinetic_energies(2 * np.pi * r.freq_hz[k], x)
        np.testing.assert_allclose(r.cable_energy[k], E / (1 + E.sum()), rtol=1e-12)
    np.testing.assert_allclose(r.cable_energy.sum(axis=1), r.cable_energy_fraction, rtol=1e-12)
    assert r.cable_energy_fraction.max() > 0.1                 # CoGiRo's cables do move


class _ExactlyOnAPole:
    """The closed-form planar2 model, except that K is not finite at one root, as exactly on
    a cable pole (float rarely lands there: cot(n pi) is 1e16, not inf)."""

    def __init__(self, model, root_hz):
        self._m, self._w = model, 2 * np.pi * root_hz

    def __getattr__(self, name):
        return getattr(self._m, name)

    def undamped(self):
        return self

    def dynamic_stiffness(self, omega):
        K = self._m.dynamic_stiffness(omega)
        K[np.abs(np.asarray(omega) - self._w) < 1e-9 * self._w] = np.inf
        return K


def test_a_root_where_k_is_not_finite_is_all_cable_and_the_next_modes_are_still_shaped():
    m = ds.FrequencyModel(ds.load_scene("planar2").equilibrium())
    ref = ds.modes(m, n_modes=8)
    local = int(np.flatnonzero(np.abs(ref.platform_shapes).max(axis=1) == 0)[0])
    poisoned = ds.modes(_ExactlyOnAPole(m, ref.freq_hz[local]), n_modes=8)
    np.testing.assert_allclose(poisoned.freq_hz, ref.freq_hz, rtol=1e-11)
    np.testing.assert_allclose(np.abs(poisoned.platform_shapes), np.abs(ref.platform_shapes),
                               atol=1e-8)
    assert poisoned.cable_energy_fraction[local] == 1.0
    assert np.abs(ref.platform_shapes[local + 1:]).max() > 0      # modes after it move


@pytest.mark.parametrize("k, n_points, message", [
    (True, 5, r"^k must be an integer in \[0, 3\), got True$"),
    (2.0, 5, r"^k must be an integer in \[0, 3\), got 2\.0$"),
    (3, 5, r"^k must be an integer in \[0, 3\), got 3$"),
    (-1, 5, r"^k must be an integer in \[0, 3\), got -1$"),
    (0, True, r"^n_points must be an integer >= 2, got True$"),
    (0, 1, r"^n_points must be an integer >= 2, got 1$"),
    (0, 4.0, r"^n_points must be an integer >= 2, got 4\.0$")])
def test_cable_fields_refuse_a_mode_or_a_point_count_that_is_not_one(k, n_points, message):
    """Before, numpy's broadcasting or index errors came out, or mode -1 (the last) was
    drawn for a mode that does not exist."""
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    with pytest.raises(InvalidParameterError, match=message):
        ds.cable_fields(m, ds.modes(m, n_modes=3), k, n_points=n_points)
    assert ds.cable_fields(m, ds.modes(m, n_modes=3), np.int64(2), n_points=2)[0].shape == \
        (8, 2, 3)


def test_cable_fields_of_no_model_is_refused():
    with pytest.raises(InvalidParameterError, match="^model must be a model of the ladder"):
        ds.cable_fields(None, None, 0)


def test_cable_fields_are_taken_at_the_modes_frequency_and_refused_without_fields(cogiro_eq,
                                                                                  monkeypatch):
    """The field of mode k is the model's cable displacement at omega = 2 pi f_k for its
    platform shape; the rungs without continuous fields are refused, the lumped one pointing
    to its node shapes."""
    from dynstiff.errors import UnsupportedAnalysisError
    m = ds.FrequencyModel(cogiro_eq)
    res = ds.modes(m, n_modes=3)
    seen, real = [], type(m).cable_displacements

    def spy(self, omega, shape, n_points):
        seen.append((omega, shape))
        return real(self, omega, shape, n_points)
    monkeypatch.setattr(type(m), "cable_displacements", spy)
    ds.cable_fields(m, res, 2, n_points=5)
    assert seen[0][0] == 2 * np.pi * res.freq_hz[2]
    np.testing.assert_array_equal(seen[0][1], res.platform_shapes[2])
    for rung, tail in (("lumped", r": its node motions are modes\(model, \.\.\.\)\.node_shapes$"),
                       ("spring", r" \(massless cables\)$")):
        with pytest.raises(UnsupportedAnalysisError,
                           match=rf"^cable_fields needs closed-form cable fields \(rung 'dsm'\); "
                                 rf"the '{rung}' model has none{tail}"):
            ds.cable_fields(ds.build_model(cogiro_eq, rung, segments=4), res, 0)


def test_near_a_pole_each_roots_share_is_that_of_its_total_modal_mass():
    """Roots a few 1e-9 from the cables' poles (FAST's 4th root is 3.3e-9 from the first pole
    of all six cables), where K's null eigenvalue is far from zero on the massless scale:
    only a pole within 1e-9 of the root may hold the platform at rest, so such a root that
    moves the platform keeps its shape, and dynstiff.modes' platform shares equal those of
    the total modal mass identity (participation.platform_shares, theory.md §13.3) to 1e-8.
    FAST's closed form is built without its guard (guard_rtol=None), which would warn that
    the exact rung is closer; the identity holds on either."""
    from dynstiff.analyses.modes import _clusters
    from dynstiff.analyses.participation import platform_shares
    m = ds.build_model(ds.load_scene("fast").equilibrium(), "dsm",
                       guard_rtol=None).undamped()        # FAST's closed form would warn
    r = ds.modes(m, n_modes=24)
    scale = np.abs(np.linalg.eigvalsh(m.massless_stiffness())).max()
    K = m.dynamic_stiffness(2 * np.pi * r.freq_hz)
    share, _ = platform_shares(m, r.freq_hz)
    far = [k for ks in _clusters(r.freq_hz) for k in ks[:1]
           if np.abs(np.linalg.eigvalsh(K[k])).min() > 1e-6 * scale and share[k] > 1e-3]
    assert far == [3, 5]                                   # the case this test is about
    np.testing.assert_allclose(1.0 - r.cable_energy_fraction, share, rtol=0, atol=1e-8)


@pytest.mark.parametrize("factor, moves", [(0.5, True), (2.0, False)])
def test_a_root_on_a_cable_pole_moves_the_platform_only_with_a_small_null_eigenvalue(factor,
                                                                                     moves):
    """A pole planted at CoGiRo's 2nd root (J0 steps there): the root keeps its platform
    shape when K's null eigenvalue is at most 1e-6 of the massless stiffness's largest
    |eigenvalue| (here 0.5e-6), and is purely local, all cable, above it (2e-6); the other
    roots are unchanged (theory.md §5.3). The wrapped model's roots come from the numpy
    search, not the compiled one: the same to 2e-13."""
    from conftest import PoleAtTheRoot
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    ref = ds.modes(m, n_modes=4)
    scale = np.abs(np.linalg.eigvalsh(m.massless_stiffness())).max()
    r = ds.modes(PoleAtTheRoot(m, ref.freq_hz[1], factor * 1e-6 * scale), n_modes=4)
    np.testing.assert_allclose(r.freq_hz, ref.freq_hz, rtol=1e-11)  # the numpy search's
    others = [0, 2, 3]
    np.testing.assert_allclose(r.platform_shapes[others], ref.platform_shapes[others],
                               rtol=1e-9, atol=1e-12)
    if moves:
        np.testing.assert_allclose(np.abs(r.platform_shapes[1]),
                                   np.abs(ref.platform_shapes[1]), rtol=1e-9, atol=1e-12)
        assert r.cable_energy_fraction[1] == pytest.approx(ref.cable_energy_fraction[1],
                                                           rel=1e-9)
    else:
        assert not np.any(r.platform_shapes[1]) and r.cable_energy_fraction[1] == 1.0
