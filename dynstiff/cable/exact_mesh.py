"""The static state along an exact cable and its spectral-element mesh (theory.md §11.2):
Gauss-Lobatto-Legendre rules, the tension and tangent of the elastic catenary at any arc
length, the element boundaries graded towards low tension and sized to the band, and the
closed-form integrals of t t^T along the arc (the hysteretic static stiffness, §11.3).
Internal to :mod:`dynstiff.cable.exact`."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.cable.catenary import CatenaryState

__all__ = ["gll", "static_along", "mesh", "tangent_integrals", "ELEMENTS_PER_EFOLD"]

#: Elements per e-fold of the tension measure asinh(V/H) (grading towards low tension).
ELEMENTS_PER_EFOLD = 1.0


@functools.lru_cache(maxsize=16)
def gll(order: int) -> tuple[NDArray[np.float64], ...]:
    """Gauss-Lobatto-Legendre nodes xi (p+1,) on [-1, 1], weights (p+1,) and the
    differentiation matrix Dm (p+1, p+1), Dm[q, a] = l_a'(xi_q)."""
    p = int(order)
    Pp = np.polynomial.legendre.Legendre.basis(p)
    xi = np.concatenate([[-1.0], np.sort(Pp.deriv().roots().real), [1.0]])
    P = Pp(xi)
    w = 2.0 / (p * (p + 1) * P**2)
    with np.errstate(divide="ignore"):
        Dm = P[:, None] / (P[None, :] * (xi[:, None] - xi[None, :]))
    np.fill_diagonal(Dm, 0.0)
    Dm[0, 0], Dm[p, p] = -p * (p + 1) / 4.0, p * (p + 1) / 4.0
    for a in (xi, w, Dm):
        a.flags.writeable = False
    return xi, w, Dm


@dataclass(frozen=True)
class _Static:
    """The static state along the cable at arc lengths s: tension T [N], tangent (tx, tz)
    in the cable plane, stretch factor 1 + T/EA."""

    T: np.ndarray
    tx: np.ndarray
    tz: np.ndarray


def static_along(state: CatenaryState, s: NDArray[np.float64]) -> _Static:
    """T(s), t(s) of the elastic catenary at unstretched arc lengths s [m] (theory.md §1.1)."""
    w0 = state.cable.weight_per_length(state.g)
    V = state.V0 + w0 * np.asarray(s, dtype=float)
    T = np.hypot(state.H, V)
    return _Static(T=T, tx=state.H / T, tz=V / T)


def mesh(state: CatenaryState, omega_max: float, half_waves: float,
         per_efold: float = ELEMENTS_PER_EFOLD) -> NDArray[np.float64]:
    """Element boundaries in s [m], shape (n_el + 1,) (theory.md §11.2).

    Elements are spread evenly in the measure
        Phi(s) = s / L0 + per_efold abs(asinh(V/H) - asinh(V0/H)) + int k_t ds / (pi half_waves)
    where k_t = omega_max sqrt(m (1 + T/EA) / T) is the transverse wavenumber: the second term
    grades the mesh geometrically towards a point of low tension (a slack cable's U), the third
    resolves the waves of the band.
    """
    L0, EA, m = state.unstretched_length, state.cable.EA, state.cable.mass_per_length
    w0 = state.cable.weight_per_length(state.g)
    s = np.linspace(0.0, L0, 4001)
    if state.H > 0 and w0 > 0:
        a0, a1 = np.arcsinh(state.V0 / state.H), np.arcsinh(state.Vb / state.H)
        s_psi = (state.H * np.sinh(np.linspace(a0, a1, 4001)) - state.V0) / w0
        s = np.unique(np.clip(np.concatenate([s, s_psi]), 0.0, L0))
    st = static_along(state, s)
    if state.H > 0:
        psi = np.arcsinh((state.V0 + w0 * s) / state.H)
    else:
        psi = np.log(np.maximum(st.T, 1e-300))
    k = omega_max * np.sqrt(m * (1.0 + st.T / EA) / np.maximum(st.T, 1e-300))
    wave = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(s))])
    phi = s / L0 + per_efold * np.abs(psi - psi[0]) + wave / (np.pi * half_waves)
    phi = np.maximum.accumulate(phi)
    n_el = max(1, int(np.ceil(phi[-1])))
    edges = np.interp(np.linspace(0.0, phi[-1], n_el + 1), phi, s)
    edges[0], edges[-1] = 0.0, L0
    return edges


def tangent_integrals(state: CatenaryState) -> tuple[float, float, float]:
    """int_0^L0 t t^T ds in the cable plane, (I_xx, I_xz, I_zz) [m], closed form."""
    H, V0, Vb, L0 = state.H, state.V0, state.Vb, state.unstretched_length
    W = Vb - V0
    T0sq = H * H + V0 * V0
    if H == 0.0:
        return 0.0, 0.0, L0
    if W == 0.0:
        Ixx, Ixz = L0 * H * H / T0sq, L0 * H * V0 / T0sq
    else:
        Ixx = H * L0 * np.arctan2(H * W, H * H + V0 * Vb) / W
        Ixz = 0.5 * H * L0 * np.log1p(W * (V0 + Vb) / T0sq) / W
    return Ixx, Ixz, L0 - Ixx
