"""Elements of a lumped-mass chain (dynstiff/cable/lumped_elements.py, theory.md §7.1): the
element stiffness, the banded interior block, forces and energy."""

import numpy as np
import pytest


def _dense_interior(ke):
    """K_II of a chain assembled element by element ([[k, -k], [-k, k]] at nodes i, i+1),
    the end nodes dropped."""
    n_el = ke.shape[0]
    K = np.zeros((3 * (n_el + 1),) * 2, dtype=ke.dtype)
    for i, k in enumerate(ke):
        s = slice(3 * i, 3 * i + 6)
        K[s, s] += np.block([[k, -k], [-k, k]])
    return K[3:-3, 3:-3]


@pytest.mark.parametrize("factor, extra", [(1.0, 0.0), (1.0 + 0.02j, 0.0),
                                           (1.0, -3.0 + 0.5j), (1.0 + 0.02j, 2.5)])
def test_banded_interior_block_is_the_assembled_one(factor, extra):
    """interior_banded in upper (symmetric) and general form holds K_II + extra I of the
    element-by-element assembly, complex element stiffnesses (hysteretic damping) and
    complex diagonal terms included."""
    from dynstiff.cable.lumped_elements import BANDWIDTH, interior_banded
    rng = np.random.default_rng(5)
    a = rng.normal(size=(5, 3, 3))
    ke = (a + a.transpose(0, 2, 1)) * factor
    K = _dense_interior(ke) + extra * np.eye(12)
    for symmetric in (True, False):
        ab = interior_banded(ke, extra, symmetric=symmetric)
        dense = np.zeros_like(K)
        for d in range(ab.shape[0]):
            off = BANDWIDTH - d                    # ab[u + i - j, j] = A[i, j]
            j = np.arange(max(0, off), 12 + min(0, off))
            dense[j - off, j] = ab[d, j]
        if symmetric:
            dense = np.triu(dense) + np.triu(dense, 1).T
        np.testing.assert_allclose(dense, K, rtol=0, atol=1e-14)




def _chain(strain, seed=3):
    """Unit vectors of a chain sagging downwards (random, normalised) and its strains."""
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(len(strain), 3)) + [0.0, 0.0, -1.0]
    return np.asarray(strain, dtype=float), u / np.linalg.norm(u, axis=1)[:, None]


def test_potential_energy_written_out_and_its_gradient_is_minus_the_residual():
    """Pi = sum EA l0 / 2 (eps)_+^2 + m l0 g sum z_j, z_j the heights of the interior nodes
    above A (written out for three segments, one slack); moving the interior nodes by a
    small dx changes Pi by -F . dx, F the interior forces (central differences: to third order)."""
    from dynstiff.cable.lumped_elements import interior_forces, potential_energy, update_segments
    l0, EA, w = 2.0, 1000.0, 5.0
    eps, u = _chain([0.01, -0.002, 0.005])
    z1 = l0 * (1 + eps[0]) * u[0, 2]
    z2 = z1 + l0 * (1 + eps[1]) * u[1, 2]
    expected = 0.5 * EA * l0 * (0.01 ** 2 + 0.005 ** 2) + w * (z1 + z2)
    assert potential_energy(eps, u, l0, EA, w) == pytest.approx(expected, rel=1e-14)
    eps, u = _chain([0.01, 0.004, 0.005])                  # all taut: Pi is smooth here
    F = interior_forces(eps, u, EA, w)
    dx = 1e-6 * np.random.default_rng(1).normal(size=(2, 3))
    dseg = np.vstack([dx[0], dx[1] - dx[0], -dx[1]])       # node j moves: d_j-1 += dx_j ...
    pi = [potential_energy(*update_segments(eps, u, l0, sgn * dseg), l0, EA, w)
          for sgn in (1.0, -1.0)]
    assert 0.5 * (pi[0] - pi[1]) == pytest.approx(-np.sum(F * dx), rel=1e-6)


def test_update_segments_keeps_the_strain_exact():
    """The new strain is |l0 (1 + eps) n + dd| / l0 - 1 and the new unit vector its
    direction, here against 40-digit arithmetic; a strain of 1e-13 moved by 1e-14 keeps
    its relative precision (1e-12), which |d| / l0 - 1 in floats would not (n is taken
    as exactly a unit vector)."""
    import mpmath

    from dynstiff.cable.lumped_elements import update_segments
    l0 = 1.7
    for eps0, scale in (([0.01, -0.003, 0.02], 1e-3), ([1e-13, 2e-13, 3e-13], 1e-14)):
        eps, u = _chain(eps0, seed=8)
        dseg = scale * np.random.default_rng(2).normal(size=(3, 3))
        got_e, got_u = update_segments(eps, u, l0, dseg)
        with mpmath.workdps(40):
            for k in range(3):
                un = [mpmath.mpf(c) for c in u[k]]
                un = [c / mpmath.sqrt(sum(x * x for x in un)) for c in un]
                d = [mpmath.mpf(l0) * (1 + mpmath.mpf(eps[k])) * c + mpmath.mpf(dd)
                     for c, dd in zip(un, dseg[k])]
                n = mpmath.sqrt(sum(c * c for c in d))
                want = n / mpmath.mpf(l0) - 1
                assert abs(got_e[k] - want) <= 1e-12 * abs(want)
                np.testing.assert_allclose(got_u[k], [float(c / n) for c in d], rtol=1e-14,
                                           atol=1e-15)
