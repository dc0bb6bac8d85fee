"""Linear dynamics of the lumped-mass cable about its equilibrium (theory.md §7.1): the
chain's tangent stiffness and mass, its dynamic stiffness condensed onto the ends, and its
fixed-end natural frequencies. Notation and conventions as :mod:`dynstiff.cable.lumped_chain`."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import omega_array
from dynstiff.cable.lumped_chain import check_chain_state, checked_integer
from dynstiff.cable.lumped_elements import (
    BANDWIDTH,
    block_tridiagonal_entries,
    element_stiffness,
    interior_banded,
)
from dynstiff.errors import InvalidParameterError, PoleWarning

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.cable.lumped_chain import ChainState

__all__ = ["chain_matrices", "chain_end_dynamic_stiffness", "chain_fixed_end_frequencies"]


def _stiffness_elements(state: ChainState, axial_factor: complex = 1.0) -> NDArray[Any]:
    """Element stiffnesses of a converged chain, shape (N, 3, 3) [N/m]."""
    axial = axial_factor * state.cable.EA / state.segment_length
    return element_stiffness(state.units, state.lengths, state.tensions, axial)


def chain_matrices(state: str | ChainState) -> tuple[Any, NDArray[np.float64]]:
    """Tangent stiffness and lumped mass of the whole chain, end nodes included.

    K = sum_e [[K_e, -K_e], [-K_e, K_e]] with K_e = (EA/l0) n n^T + (T/l)(I - n n^T)
    (theory.md §7.1); M = diag(m l0) with m l0 / 2 at the two end nodes.

    Parameters
    ----------
    state : ChainState
        Equilibrium from `chain_equilibrium`.

    Returns
    -------
    K : scipy.sparse.csr_matrix, shape (3(N+1), 3(N+1))
        Symmetric tangent stiffness [N/m], node-major DOF order; undamped (real EA).
    M : ndarray, shape (3(N+1),)
        Diagonal of the lumped mass matrix [kg].
    """
    import scipy.sparse
    check_chain_state(state)
    n_dof = 3 * (state.n_segments + 1)
    rows, cols, vals = block_tridiagonal_entries(_stiffness_elements(state))
    K = scipy.sparse.coo_matrix((vals, (rows, cols)), shape=(n_dof, n_dof)).tocsr()
    node_mass = state.cable.mass_per_length * state.segment_length
    M = np.full(n_dof, node_mass)
    M[:3] = M[-3:] = 0.5 * node_mass
    return K, M


def chain_end_dynamic_stiffness(state: ChainState, omega: ArrayLike,
                                ends: str = "end") -> NDArray[Any]:
    """Dynamic stiffness of the chain condensed onto its end nodes.

    D(omega) = K - omega^2 M + i omega C, with K built with EA (1 + i eta) in the axial
    term and C = diag(c l0) (c l0 / 2 at the ends), i.e. the complex mass m - i c / omega of
    `Cable` acting on all three components. The interior nodes are eliminated:
    S = D_bb - D_bi D_ii^{-1} D_ib (one banded LU solve per frequency). The end nodes carry
    their half masses.

    Parameters
    ----------
    state : ChainState
        Equilibrium from `chain_equilibrium`.
    omega : float or array_like, shape (n_omega,)
        Angular frequencies [rad/s], >= 0.
    ends : {"end", "both"}
        "end": A clamped, condensed onto B. "both": condensed onto A and B.

    Returns
    -------
    ndarray, shape (n_omega, 3, 3) or (n_omega, 6, 6)
        Force to apply to the end node(s) per unit displacement [N/m], global xyz; for
        "both" the order is (A x, y, z, B x, y, z). Real when the cable is undamped, complex
        otherwise. Exactly on a fixed-end natural frequency (a pole, singular interior
        block) the value is inf and a `PoleWarning` is issued; close to one it is large.

    Warns
    -----
    PoleWarning
        If an omega makes the interior block exactly singular.
    """
    import scipy.linalg
    check_chain_state(state)
    omega = omega_array(omega)
    if ends not in ("end", "both"):
        raise InvalidParameterError(f'ends must be "end" or "both", got {ends!r}')
    cable = state.cable
    n_el = state.n_segments
    l0 = state.segment_length
    ke = _stiffness_elements(state, axial_factor=1.0 + 1j * cable.loss_factor)
    if not cable.is_damped:
        ke = ke.real
    node_mass = cable.mass_per_length * l0
    node_damp = cable.viscous_damping * l0
    boundary = [0, 1] if ends == "both" else [1]       # 0: A, 1: B
    n_b = 3 * len(boundary)
    dtype = ke.dtype
    out = np.empty((omega.size, n_b, n_b), dtype=dtype)
    eye = np.eye(3)
    # coupling of the first / last interior node to A / B (zero when N = 1)
    n_int = 3 * (n_el - 1)
    coupling = np.zeros((n_int, 6), dtype=dtype)
    if n_el > 1:
        coupling[:3, :3] = -ke[0]
        coupling[-3:, 3:] = -ke[-1]
    cols = np.concatenate([np.arange(3 * b, 3 * b + 3) for b in boundary])
    coupling = coupling[:, cols]
    if n_el > 1:
        ab0 = interior_banded(ke, symmetric=False)
    for k, w in enumerate(omega):
        inertia = -w ** 2 * node_mass + (1j * w * node_damp if cable.is_damped else 0.0)
        direct = np.zeros((6, 6), dtype=dtype)
        direct[:3, :3] = ke[0] + 0.5 * inertia * eye
        direct[3:, 3:] = ke[-1] + 0.5 * inertia * eye
        if n_el == 1:
            direct[:3, 3:] = direct[3:, :3] = -ke[0]
        s = direct[np.ix_(cols, cols)]
        if n_el > 1:
            ab = ab0.copy()
            ab[BANDWIDTH] += inertia
            try:
                x = scipy.linalg.solve_banded((BANDWIDTH, BANDWIDTH), ab, coupling,
                                              check_finite=False)
            except np.linalg.LinAlgError:
                warnings.warn(f"chain_end_dynamic_stiffness: omega = {w:.9g} rad/s is a "
                              f"fixed-end natural frequency (pole); returning inf",
                              PoleWarning, stacklevel=2)
                s = np.full((n_b, n_b), np.inf, dtype=dtype)
            else:
                s = s - coupling.T @ x
        out[k] = s
    return out


def chain_fixed_end_frequencies(state: ChainState, n_modes: int) -> NDArray[np.float64]:
    """Natural frequencies of the chain with both ends clamped.

    Lowest eigenvalues of K_ii phi = omega^2 (m l0) phi, K_ii the interior block of the
    undamped tangent stiffness (banded symmetric eigensolver). These are the poles of
    `chain_end_dynamic_stiffness`.

    Parameters
    ----------
    state : ChainState
        Equilibrium from `chain_equilibrium`, N >= 2.
    n_modes : int
        Number of frequencies, 1 <= n_modes <= 3(N-1).

    Returns
    -------
    ndarray, shape (n_modes,)
        Natural frequencies [Hz], ascending.
    """
    import scipy.linalg
    check_chain_state(state)
    n_int = 3 * (state.n_segments - 1)
    if n_int == 0:
        raise InvalidParameterError(
            "state must have n_segments >= 2 for fixed-end frequencies, got 1")
    n_modes = checked_integer("n_modes", n_modes, 1)
    if n_modes > n_int:
        raise InvalidParameterError(
            f"n_modes must be <= 3(N-1) = {n_int}, got {n_modes}")
    node_mass = state.cable.mass_per_length * state.segment_length
    ab = interior_banded(_stiffness_elements(state)) / node_mass
    eig = scipy.linalg.eig_banded(ab, lower=False, eigvals_only=True, select="i",
                                  select_range=(0, n_modes - 1), check_finite=False)
    return np.sqrt(eig) / (2.0 * np.pi)
