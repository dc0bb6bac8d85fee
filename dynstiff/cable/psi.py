"""The closed form's functions of psi = Omega / 2 (theory.md §3.2, §5.2): cancellation-free
kernels with their Taylor branch, the admissible frequency range, the Wittrick-Williams
count J0 of the clamped cable and the clamped spectrum (the Irvine-Caughey roots).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import omega_array
from dynstiff.cable.chord import chord_parameters
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.cable.catenary import CatenaryState
    from dynstiff.cable.chord import ChordParameters

__all__ = [
    "MAX_OMEGA_ND", "PSI_SERIES", "cable_mode_count", "check_frequency_range",
    "closed_form_spectrum", "irvine_symmetric_roots", "mode_count_nondimensional",
    "mode_count_psi", "psi_functions",
]


_SERIES_RADIUS = 1.0
_N_TERMS = 16

#: Largest nondimensional frequency |Omega| = |omega| L sqrt(m/T) at which the closed forms
#: are evaluated: there sin and cos of psi = Omega/2 still carry 9 correct digits (the phase
#: error is ulp(psi) ~ 1e-9) and the mode counts are exact integers; about 3 million clamped
#: modes of the cable lie below it.
MAX_OMEGA_ND = 1e7
#: Largest |Im psi| (damped or complex frequencies): sin and cos overflow near 710.
MAX_IMAG_PSI = 350.0


def check_frequency_range(params: ChordParameters, omega: NDArray[Any],
                          name: str = "omega") -> None:
    """Raise InvalidParameterError naming ``name`` unless every omega [rad/s] keeps
    |Omega| <= MAX_OMEGA_ND and |Im psi| <= MAX_IMAG_PSI for the cable(s) ``params``
    (ChordParameters, single or stacked); the message gives the admissible bound [rad/s]."""
    scale = np.max(np.atleast_1d(params.L * np.sqrt(params.m / params.T)))   # Omega per rad/s
    w = np.abs(np.asarray(omega))
    if w.size and w.max() * scale > MAX_OMEGA_ND:
        bad = np.asarray(omega).ravel()[int(np.argmax(w))]
        bad = complex(bad) if np.iscomplexobj(omega) else float(bad)
        raise InvalidParameterError(
            f"{name} must be <= {MAX_OMEGA_ND / scale:.6g} rad/s for this cable model "
            f"(omega L sqrt(m/T) <= {MAX_OMEGA_ND:g}, beyond which the closed form loses its "
            f"digits), got {bad:.6g}")
    # psi is complex for a complex omega, and for a real one on a cable with viscous
    # damping (c != 0), whose Im psi tends to L c / (4 sqrt(m T)) as omega grows
    if w.size and (np.iscomplexobj(omega) or np.any(np.asarray(params.c) != 0)):
        psi = np.abs(np.imag(params.psi(np.asarray(omega).reshape(-1, 1)
                                        if np.ndim(params.L) else np.asarray(omega))))
        if psi.max() > MAX_IMAG_PSI:
            what = ("has an imaginary part too large for the closed form"
                    if np.iscomplexobj(omega) else
                    "is too large for the closed form with the cables' viscous damping")
            raise InvalidParameterError(
                f"{name} {what} (|Im psi| = {psi.max():.4g} > {MAX_IMAG_PSI:g}: sin and cos "
                f"overflow), got |{name}| up to {w.max():.6g} rad/s")


# --------------------------------------------------------------------------- psi kernels
def _series_coefficients() -> tuple[NDArray[np.float64], ...]:
    """Taylor coefficients (in powers psi^(2k), k = 0..N-1) of E, P~ and Q~."""
    from math import factorial
    a = [(-1) ** k * 4**k / factorial(2 * k + 1) for k in range(_N_TERMS + 2)]  # sin2psi/2
    b = [(-1) ** k * 4**k / factorial(2 * k) for k in range(_N_TERMS + 2)]      # cos 2psi
    E = [(-1) ** n * 2 * n / factorial(2 * n + 1) for n in range(1, _N_TERMS + 1)]
    P = [a[k] + a[k - 1] for k in range(1, _N_TERMS + 1)]
    Q = [b[k] + a[k - 1] - a[k] for k in range(1, _N_TERMS + 1)]
    # numpy.polyval wants the highest power first
    return np.array(E[::-1]), np.array(P[::-1]), np.array(Q[::-1])


_E_COEF, _P_COEF, _Q_COEF = _series_coefficients()
#: (radius, E coefficients, P~ coefficients) of the series branch of :func:`psi_functions`,
#: highest power of psi^2 first, for compiled kernels that evaluate the same functions.
PSI_SERIES = (_SERIES_RADIUS, _E_COEF, _P_COEF)


def psi_functions(psi: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Cancellation-free functions of psi (real or complex array).

    Returns (c, s_over_psi, cos2, E, Pt, Qt) with
    E  = (psi cos psi - sin psi) / psi^3,
    Pt = ((1 + psi^2) sin(2 psi)/2 - psi) / psi^3,
    Qt = (psi cos 2psi + (psi^2 - 1) sin(2 psi)/2) / psi^3,
    each by its Taylor series for |psi| < 1 (no cancellation) and directly otherwise.
    """
    s, c = np.sin(psi), np.cos(psi)
    cos2 = c * c - s * s
    small = np.abs(psi) < _SERIES_RADIUS
    with np.errstate(divide="ignore", invalid="ignore"):
        s_over_psi = np.where(psi == 0, 1.0, s / np.where(psi == 0, 1.0, psi))
        p3 = psi**3
        E = (psi * c - s) / p3
        Pt = ((1 + psi * psi) * s * c - psi) / p3
        Qt = (psi * cos2 + (psi * psi - 1) * s * c) / p3
    if np.any(small):
        x = psi[small] ** 2
        E[small] = np.polyval(_E_COEF, x)
        Pt[small] = np.polyval(_P_COEF, x)
        Qt[small] = np.polyval(_Q_COEF, x)
    return c, s_over_psi, cos2, E, Pt, Qt


# --------------------------------------------------------------------------- fixed-end modes
def cable_mode_count(state: CatenaryState, omega: ArrayLike,
                     tension: str = "mean") -> NDArray[np.int64]:
    """Wittrick-Williams J0: number of clamped-clamped cable frequencies strictly below omega.

    J0 = #{n pi < Omega} + #{2 n pi < Omega} + N_sym, N_sym = 0 if k = 0, else
    (k - 1) + [g(psi) > 0], k = floor(psi/pi + 1/2), psi = Omega/2 (theory.md §5.2), where
    g(psi) = tan psi - psi + 4 psi^3/lambda^2 > 0 is evaluated without division as
    (4 cos psi - lambda^2 E(psi)) cos psi > 0 together with cos psi having the sign
    (-1)^k of branch k (at a branch end, where rounding may give cos psi the wrong sign,
    g -> -inf and the root of that branch is not yet passed). The chordwise-inertia
    correction adds no clamped-clamped mode.

    Parameters
    ----------
    state : CatenaryState
    omega : float or array_like, shape (n_omega,)
        Angular frequencies [rad/s].

    Returns
    -------
    ndarray of int, shape (n_omega,)

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> f1 = ds.cable_natural_frequencies(state, 1).freq_hz[0]
    >>> ds.cable_mode_count(state, [0.99 * 2 * np.pi * f1, 1.01 * 2 * np.pi * f1]).tolist()
    [0, 1]
    """
    omega = omega_array(omega)
    p = chord_parameters(state, tension)
    check_frequency_range(p, omega)
    return mode_count_nondimensional(omega * p.L * np.sqrt(p.m / p.T), p.lambda_sq)


def mode_count_nondimensional(Omega: NDArray[np.float64],
                              lambda_sq: NDArray[np.float64] | float) -> NDArray[np.int64]:
    """J0 as a function of the nondimensional frequency Omega >= 0 (see cable_mode_count)."""
    psi = 0.5 * Omega
    c, _, _, E, _, _ = psi_functions(psi)
    return mode_count_psi(psi, c, E, lambda_sq)


def mode_count_psi(psi: NDArray[np.float64], c: NDArray[np.float64], E: NDArray[np.float64],
                   lambda_sq: NDArray[np.float64] | float) -> NDArray[np.int64]:
    """J0 from psi = Omega / 2 and its cos psi and E(psi) (see cable_mode_count)."""
    Omega = 2.0 * psi
    k = np.floor(psi / np.pi + 0.5).astype(int)
    on_branch = c * np.where(k % 2 == 0, 1.0, -1.0) > 0
    upper = (((4.0 * c - lambda_sq * E) * c > 0) & on_branch).astype(int)
    n_sym = np.where(k == 0, 0, k - 1 + upper)
    return _count_multiples_below(Omega, np.pi) + _count_multiples_below(Omega, 2 * np.pi) + n_sym


def _count_multiples_below(x: NDArray[np.float64], step: float) -> NDArray[np.int64]:
    """#{n >= 1 : n * step < x}, with ties decided in the same float arithmetic as n * step."""
    n = np.maximum(np.ceil(x / step).astype(int) - 1, 0)
    n = n - ((n >= 1) & (n * step >= x))    # x / step rounded up past an integer
    return n + ((n + 1) * step < x)         # x / step rounded down below one


def irvine_symmetric_roots(lambda_sq: float, n_roots: int) -> NDArray[np.float64]:
    """First ``n_roots`` roots Omega of the Irvine-Caughey symmetric equation.

    tan(Omega/2) = Omega/2 - (4/lambda^2)(Omega/2)^3, solved as 4 cos psi - lambda^2 E(psi) = 0,
    psi = Omega/2, with exactly one root in each ((2k-1) pi/2, (2k+1) pi/2) (theory.md §2.2),
    by Brent's method to machine precision. lambda_sq = 0 gives the taut string (2k-1) pi.

    Returns
    -------
    ndarray, shape (n_roots,)
    """
    from scipy.optimize import brentq

    lam2 = float(lambda_sq)
    if not np.isfinite(lam2) or lam2 < 0:
        raise InvalidParameterError(f"lambda_sq must be finite and >= 0, got {lambda_sq!r}")
    out = np.empty(int(n_roots))
    for k in range(1, int(n_roots) + 1):
        lo, hi = (2 * k - 1) * np.pi / 2, (2 * k + 1) * np.pi / 2
        if lam2 == 0.0:
            out[k - 1] = 2 * lo
            continue
        # high branches: the root sits delta ~ lambda^2 / (4 psi^3) above the branch start,
        # where 4 cos(psi) is below its own rounding (ulp(psi)); tan(lo + delta) = -1/delta
        # + O(delta) then gives delta to O(delta^2), below the ulp of psi
        delta = lam2 / (4.0 * lo**3)
        if delta < 1e-8:
            out[k - 1] = 2.0 * (lo + delta)
            continue

        def f(x: float) -> float:
            c, _, _, E, _, _ = psi_functions(np.array([x]))
            return float(4.0 * c[0] - lam2 * E[0])

        out[k - 1] = 2.0 * brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=500)
    return out


def closed_form_spectrum(
        lambda_sq: float, n_modes: int,
) -> tuple[NDArray[np.float64], tuple[str, ...], NDArray[np.int64]]:
    """The first ``n_modes`` clamped-clamped frequencies of the closed form, ascending.

    Out-of-plane Omega = n pi, in-plane antisymmetric Omega = 2 n pi, in-plane symmetric the
    roots of :func:`irvine_symmetric_roots` (theory.md §2.2); ties keep that family order.

    Parameters
    ----------
    lambda_sq : float
        Irvine's parameter [-].
    n_modes : int
        Number of modes, >= 1.

    Returns
    -------
    Omega : ndarray, shape (n_modes,)
        Nondimensional frequencies omega L sqrt(m / T) [-].
    family : tuple of str
    order : ndarray of int, shape (n_modes,)
        Number of the mode within its family, from 1.

    Examples
    --------
    >>> import numpy as np
    >>> Omega, family, order = closed_form_spectrum(0.0, 3)   # a taut string
    >>> np.round(Omega / np.pi, 12).tolist(), family[:2], order.tolist()
    ([1.0, 1.0, 2.0], ('out-of-plane', 'in-plane symmetric'), [1, 1, 2])
    """
    k = np.arange(1, n_modes + 1)
    Om = np.concatenate([k * np.pi, 2 * k * np.pi, irvine_symmetric_roots(lambda_sq, n_modes)])
    family = (["out-of-plane"] * n_modes + ["in-plane antisymmetric"] * n_modes
              + ["in-plane symmetric"] * n_modes)
    order = np.concatenate([k, k, k])
    idx = np.argsort(Om, kind="stable")[:n_modes]
    return Om[idx], tuple(family[i] for i in idx), order[idx]
