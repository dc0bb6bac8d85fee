"""The closed form's cable fields: the displacement along the chord for an end motion at a
natural frequency, and its kinetic energy (theory.md §5.3, §6), for one cable or for several
cables and motions in one broadcast call (the fields of :func:`dynstiff.modes`).
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.cable.dsm import local_entries

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.cable.chord import ChordParameters

__all__ = ["cable_field", "cable_kinetic_energy", "field_kinetic_energies"]


def _fields(p: ChordParameters, omega: NDArray[Any], d_local: NDArray[Any],
            x: NDArray[np.float64]) -> tuple[NDArray[Any], NDArray[Any], NDArray[Any]]:
    """(u, v, w) of :func:`cable_field`, elementwise: ``p``'s fields and ``omega`` broadcast
    to a shape S (scalars for one cable, (n_cables,) for :func:`stack_parameters`),
    ``d_local`` has shape S + (3,), ``x`` shape S + (n_points,) or (n_points,); each result
    has shape S + (n_points,)."""
    uB, vB, wB = np.moveaxis(np.asarray(d_local), -1, 0)
    k_uu, k_uv, *_ = local_entries(p, omega, False)
    h = k_uu * uB - k_uv * vB                         # dynamic tension [N]
    beta = 2.0 * p.psi(omega) / p.L
    Om = beta * p.L
    vp = h * p.q / (p.T * beta) ** 2
    C2 = (vB - vp + vp * np.cos(Om)) / np.sin(Om)
    bx = beta[..., None] * x
    v = -vp[..., None] * np.cos(bx) + C2[..., None] * np.sin(bx) + vp[..., None]
    w = (wB / np.sin(Om))[..., None] * np.sin(bx)
    return uB[..., None] * x / np.asarray(p.L)[..., None], v, w


def cable_field(p: ChordParameters, omega: float, d_local: NDArray[np.float64],
                x: NDArray[np.float64]) -> NDArray[np.float64]:
    """Closed-form displacement (u, v, w) [m] along the chord at positions x [m], shape
    (len(x), 3), for the end-B motion d_local = (u_B, v_B, w_B) [m, chord frame] at omega
    [rad/s] with A clamped (theory.md §5.3); ``p`` the cable's :class:`ChordParameters`:
    v = C1 cos(beta x) + C2 sin(beta x) + q h / (T beta)^2, w = w_B sin(beta x)/sin(beta L),
    u = u_B x / L (quasi-static stretching)."""
    u, v, w = _fields(p, np.array([omega]), np.asarray(d_local)[None], np.asarray(x))
    return np.column_stack([u[0], v[0], w[0]])


@functools.lru_cache(maxsize=8)
def _gauss(n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Gauss-Legendre nodes and weights on [-1, 1] (cached)."""
    return np.polynomial.legendre.leggauss(n)


def field_kinetic_energies(p: ChordParameters, omega: NDArray[np.float64],
                           d_local: NDArray[np.float64], chordwise_inertia: bool,
                           n_gauss: int = 64) -> NDArray[np.float64]:
    """:func:`cable_kinetic_energy` of many cables and end motions in one broadcast call.

    Parameters
    ----------
    p : ChordParameters
        One cable's, or several cables' stacked (:func:`stack_parameters`, fields (n_cables,)).
    omega : ndarray, shape (n,)
        Natural frequencies [rad/s], real.
    d_local : ndarray, shape (n, n_cables, 3) (or (n, 3) for one cable)
        End-B motions in each cable's chord frame [m].
    chordwise_inertia : bool
    n_gauss : int

    Returns
    -------
    ndarray, shape (n, n_cables) (or (n,) for one cable)
        [kg m^2 per unit amplitude^2], as :func:`cable_kinetic_energy` (theory.md §6).

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> d = np.tile([1e-3, 2e-3, -1e-3], (2, 8, 1))      # 2 motions of every cable's end
    >>> E = field_kinetic_energies(m.stacked_params, 2 * np.pi * np.array([1.0, 2.5]), d,
    ...                            True)
    >>> E.shape, bool(np.allclose(E[1, 3], cable_kinetic_energy(
    ...     m.params[3], 2 * np.pi * 2.5, d[1, 3], True), rtol=1e-13))
    ((2, 8), True)
    """
    stacked = np.ndim(p.L) > 0
    om = np.asarray(omega, dtype=float)[:, None] if stacked else np.asarray(omega, float)
    xi, wts = _gauss(n_gauss)
    L = np.asarray(p.L)[..., None]
    _, v, w = _fields(p, om, d_local, 0.5 * L * (xi + 1.0))
    E = p.m * np.sum(0.5 * L * wts * (np.abs(v) ** 2 + np.abs(w) ** 2), axis=-1)
    if chordwise_inertia:
        E = E + p.m * p.L / 3.0 * np.abs(np.asarray(d_local)[..., 0]) ** 2
    return E


def cable_kinetic_energy(p: ChordParameters, omega: float, d_local: NDArray[np.float64],
                         chordwise_inertia: bool, n_gauss: int = 64) -> float:
    """Kinetic energy per unit omega^2 / 2 of the closed-form field, int m (|v|^2 + |w|^2) dx
    (+ m L/3 |u_B|^2 with ``chordwise_inertia``) [kg m^2 per unit amplitude^2], by
    ``n_gauss``-point Gauss-Legendre quadrature (theory.md §6)."""
    return float(field_kinetic_energies(p, np.array([omega]), np.asarray(d_local)[None],
                                        chordwise_inertia, n_gauss)[0])
