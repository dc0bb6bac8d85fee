"""Assembly and exact condensation of the exact cable's spectral elements (theory.md §11.2,
§11.3). Internal to :mod:`dynstiff.cable.exact`.

The stiffness coefficient D = EA t t^T + D_t (I - t t^T), D_t = T / (1 + T / EA), is split
as D = D_t I + kappa t t^T with kappa = EA - D_t. The string part D_t I (all that the
out-of-plane family has) is assembled as it is. The axial excess kappa is kept in mixed
form: at every quadrature point q of element e the axial force increment
tau = kappa t . u' is an unknown, and the in-plane interior solves

    [[K_T, B^T], [B, -C]] [u; tau] = [f; 0],
    B[eq, (a, c)] = sigma_e w_q Dm[q, a] t_c(s_q),   C[eq] = sigma_e^2 (h_e / 2) w_q / kappa_q,

(sigma_e a scale of tau per element, the mean D_t / h_e, which balances the rows).
Eliminating tau gives back the stiffness K_T + B^T C^-1 B = K of the displacement form
exactly, so the discretisation is unchanged; but no entry of this matrix is of order
EA / h, so the soft transverse stiffness D_t / h of the short elements at the bottom of a U
(h ~ 1e-6 m) is not lost to the rounding of their axial stiffness. In the displacement form
that rounding, eps EA / h, exceeded the whole static stiffness of the cable below
T_min / T_max ~ 1e-3 (theory.md §11.2).

Each family's condensation gives its clamped modes in flexibility form (the eigenvalues of
M^1/2 F M^1/2, F = (Z^-1)_uu, are 1 / lambda_j), the static constraint modes and the
discretisation's own static stiffness with a bound of its rounding error.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.cable.exact_mesh import gll

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.cable.catenary import CatenaryState

__all__ = ["Family", "quadrature_state", "string_matrix", "axial_coupling", "condense"]


@dataclass(frozen=True)
class Family:
    """One decoupled family (out-of-plane or in-plane) of the clamped interior.

    mu: flexibility eigenvalues 1/lambda_j [s^2/rad^2]; shapes: phi_j (n_i, n_modes),
    M-orthonormal; psi: static constraint modes -K_ii^-1 K_ib (n_i, n_b); beta: (n_modes, 6)
    couplings phi_j^T M Psi placed in the local 6-vector; M_psi: (6, 6) Psi^T M Psi; local:
    the family's positions in the 6-vector; static: the discretisation's static stiffness
    K_bb - K_bi K_ii^-1 K_ib (n_b, n_b) [N/m]; floor: an estimate of its rounding error
    (n_b, n_b) [N/m], entrywise."""

    mu: np.ndarray
    shapes: np.ndarray
    psi: np.ndarray
    beta: np.ndarray
    M_psi: np.ndarray
    local: list
    static: np.ndarray
    floor: np.ndarray


@dataclass(frozen=True)
class Quadrature:
    """The static state at the quadrature points, shape (n_el, p + 1) each: tension T [N],
    tangent (tx, tz) [-], string coefficient D_t [N]; h (n_el,) element lengths [m], idx
    (n_el, p + 1) node numbers, n the number of nodes."""

    T: np.ndarray
    tx: np.ndarray
    tz: np.ndarray
    Dt: np.ndarray
    h: np.ndarray
    idx: np.ndarray
    n: int


def quadrature_state(static_along: Callable[..., Any], state: CatenaryState,
                     edges: NDArray[np.float64], order: int) -> Quadrature:
    """:class:`Quadrature` of the elements ``edges`` [m] at GLL order ``order``."""
    xi, _, _ = gll(order)
    p, n_el = order, len(edges) - 1
    h = np.diff(edges)
    s = edges[:-1, None] + 0.5 * (xi[None, :] + 1.0) * h[:, None]
    st = static_along(state, s)
    Dt = st.T / (1.0 + st.T / state.cable.EA)
    idx = np.arange(n_el)[:, None] * p + np.arange(p + 1)[None, :]
    return Quadrature(T=st.T, tx=st.tx, tz=st.tz, Dt=Dt, h=h, idx=idx, n=n_el * p + 1)


def string_matrix(q: Quadrature, order: int) -> NDArray[np.float64]:
    """K_T of one displacement component, (n, n) [N/m]: Ke[a, b] = (2/h) sum_q w_q Dm[q, a]
    Dm[q, b] D_t(s_q), assembled."""
    _, wq, Dm = gll(order)
    G = np.einsum("q,qa,qb->qab", wq, Dm, Dm)
    ke = np.einsum("e,eq,qab->eab", 2.0 / q.h, q.Dt, G)
    K = np.zeros((q.n, q.n))
    for e in range(q.h.size):
        K[np.ix_(q.idx[e], q.idx[e])] += ke[e]
    return K


def axial_coupling(q: Quadrature, order: int,
                   EA: complex) -> tuple[NDArray[np.float64], NDArray[Any]]:
    """B (n_tau, 2 n) [N/m] and C (n_tau,) [N/m] of the mixed form (module notes), in-plane
    DOFs interleaved (x_0, z_0, x_1, ...); ``EA`` [N] real or complex (hysteretic)."""
    _, wq, Dm = gll(order)
    n_el, p1 = q.Dt.shape
    sigma = q.Dt.mean(axis=1) / q.h                                    # (n_el,)
    kappa = EA - q.Dt
    B = np.zeros((n_el * p1, 2 * q.n))
    for e in range(n_el):
        rows = e * p1 + np.arange(p1)
        blk = sigma[e] * wq[:, None] * Dm                               # (q, a)
        B[np.ix_(rows, 2 * q.idx[e])] = blk * q.tx[e][:, None]
        B[np.ix_(rows, 2 * q.idx[e] + 1)] = blk * q.tz[e][:, None]
    C = (sigma[:, None] ** 2 * 0.5 * q.h[:, None] * wq[None, :] / kappa).ravel()
    return B, C


def condense(K: NDArray[np.float64], m_inner: NDArray[np.float64], inner: NDArray[np.int64],
             bnd: list[int], local: list[int], B: NDArray[np.float64] | None = None,
             C: NDArray[np.float64] | None = None) -> Family:
    """Flexibility-form modal condensation of one family (theory.md §11.3).

    Parameters
    ----------
    K : ndarray, shape (n_dof, n_dof)
        The string part K_T of the family [N/m].
    m_inner : ndarray, shape (n_i,)
        Masses of the interior DOFs [kg].
    inner, bnd : sequence of int
        Interior and boundary DOFs of the family.
    local : list of int
        The boundary DOFs' positions in the local 6-vector (A x y z, B x y z).
    B, C : ndarray, optional
        The axial coupling of the mixed form (:func:`axial_coupling`); None for the
        out-of-plane family (a string).

    Returns
    -------
    Family
    """
    from scipy.linalg import eig, eigh, lu_factor, lu_solve
    inner, bnd = np.asarray(inner), np.asarray(bnd)
    n_i = inner.size
    Z_rr, Z_rb = K[np.ix_(inner, inner)], K[np.ix_(inner, bnd)]
    if B is not None:
        Bi, Bb = B[:, inner], B[:, bnd]
        Z_rr = np.block([[Z_rr, Bi.T], [Bi, -np.diag(C)]])
        Z_rb = np.vstack([Z_rb, Bb])
    fac = lu_factor(Z_rr, check_finite=False)
    X = -lu_solve(fac, Z_rb, check_finite=False)                  # [Psi; tau of Psi]
    rhs = np.zeros((Z_rr.shape[0], n_i))
    rhs[:n_i] = np.eye(n_i)
    F = lu_solve(fac, rhs, check_finite=False)[:n_i]              # (Z^-1)_uu
    psi = X[:n_i]
    # S = Z_bb + Z_br X; its rounding, from the sums and the backward error of the LU
    # solve, estimated as sqrt(n) eps (|Z_bb| + 2 |Z_br| |X| + |X|^T |Z_rr| |X|) (errors of
    # random sign add in quadrature; the worst case has n for sqrt(n))
    static = K[np.ix_(bnd, bnd)] + Z_rb.T @ X
    aX = np.abs(X)
    floor = (np.abs(K[np.ix_(bnd, bnd)]) + 2.0 * np.abs(Z_rb.T) @ aX
             + aX.T @ (np.abs(Z_rr) @ aX)) * (np.sqrt(Z_rr.shape[0]) * np.finfo(float).eps)
    complex_ = np.iscomplexobj(F)
    r = np.sqrt(m_inner)
    A = r[:, None] * F * r[None, :]
    A = 0.5 * (A + A.T)
    if complex_:
        mu, V = eig(A)
        V = V / np.sqrt(np.einsum("ij,ij->j", V, V))[None, :]
    else:
        mu, V = eigh(A)
    shapes = V / r[:, None]
    b = (V.T * r[None, :]) @ psi                                  # (n_modes, n_b)
    beta = np.zeros((mu.size, 6), dtype=b.dtype)
    beta[:, local] = b
    M_psi = np.zeros((6, 6), dtype=b.dtype)
    M_psi[np.ix_(local, local)] = psi.T @ (m_inner[:, None] * psi)
    return Family(mu=mu, shapes=shapes, psi=psi, beta=beta, M_psi=M_psi, local=list(local),
                  static=static, floor=floor)
