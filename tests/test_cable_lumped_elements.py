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


