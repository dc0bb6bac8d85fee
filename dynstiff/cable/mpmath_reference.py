"""High-precision (mpmath) reference of the dynamic stiffness of one sagging cable.

Scalar, slow and independent of :mod:`dynstiff.cable.dsm`: it evaluates the *naive*
textbook forms of theory.md §3.2-3.4 (Irvine & Caughey 1974 linear theory written as an
end-force / end-displacement relation, Starossek 1991),

    tau = 1 - tan(psi) / psi,         D = 1 - lambda^2 tau / (4 psi^2),
    k_s = T beta cot(Omega),          k_c = -T beta / sin(Omega),
    K_uu = K0 / D,  K_uv = -alpha tau K0 / D,  K_vv = k_s + (alpha tau)^2 K0 / D,  K_ww = k_s,

which cancel badly near psi = 0 (tau ~ -psi^2/3), near Omega = (2k+1) pi (k_s and the sag
term both grow without bound) and near the symmetric poles (D -> 0); in float64 they lose up
to all 16 digits. At omega = 0 exactly the static limit of theory.md §3.6 is used. Every
subtraction is checked for the digits it cancels, and the working precision is raised until
``dps`` significant digits survive (see ``_Evaluator``), so the result is the exact value of
the formulas at the float inputs to about ``dps`` digits. Only the tests and ``validation/``
use this module; :mod:`dynstiff` never imports it (STYLE.md §12).

Notation (theory.md §1.2, §3.1)
-------------------------------
==========  ===========================================================  ========
symbol      meaning                                                      unit
==========  ===========================================================  ========
L           chord length                                                 m
T           tension of the linear theory                                 N
m           mass per unit chord length                                   kg/m
c           viscous damping per unit chord length                        N s/m^2
EA          axial stiffness, EA (1 + i eta) with hysteretic damping      N
L_e         compliance length                                            m
q           weight per chord length perpendicular to the chord           N/m
K0          EA / L_e                                                     N/m
alpha       q L / (2 T), static end slope to the chord                   --
lambda^2    (q L / T)^2 L EA / (T L_e), Irvine parameter (complex if     --
            eta > 0)
beta        sqrt((omega^2 m - i omega c) / T), principal branch          1/m
Omega, psi  beta L and Omega / 2                                         --
m~          m - i c / omega, complex mass                                kg/m
==========  ===========================================================  ========

Conventions are those of :func:`dynstiff.cable.dsm.local_end_stiffness` and
:func:`dynstiff.cable.dsm.local_two_end_stiffness`: forces applied **to** the cable ends,
local chord frame (u along A -> B, v sag direction, w out of plane), and, with
``chordwise_inertia``, the consistent axial mass -omega^2 m~ (L/6) [[2, 1], [1, 2]] on
(u_A, u_B) (so -omega^2 m~ L / 3 on K_uu of the one-end matrix; theory.md §3.6).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import mpmath
import numpy as np

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.cable.chord import ChordParameters

__all__ = [
    "params_to_mp_args",
    "end_stiffness_mp",
    "two_end_stiffness_mp",
    "irvine_symmetric_roots_mp",
]

#: Working digits above ``dps`` before any cancellation is measured.
_GUARD_DIGITS = 20
#: Digits that must remain above ``dps`` after the measured cancellation.
_SPARE_DIGITS = 5
_LOG10_2 = math.log10(2.0)
#: Working precision never exceeds this many digits (a psi of 1e-900 would need ~1800).
_MAX_DPS = 4000


def params_to_mp_args(params: ChordParameters) -> tuple[complex, ...]:
    """Scalars of a :class:`dynstiff.cable.dsm.ChordParameters` in the order of this module.

    Parameters
    ----------
    params : ChordParameters

    Returns
    -------
    tuple
        ``(L, T, m, c, EA, L_e, q)`` as Python floats (``EA`` a complex when it has an
        imaginary part), ready for ``end_stiffness_mp(*args, omega)``.
    """
    EA = complex(params.EA)
    EA = EA.real if EA.imag == 0 else EA
    return (float(params.L), float(params.T), float(params.m), float(params.c), EA,
            float(params.L_e), float(params.q))


def _mp(x: complex) -> Any:
    """Exact conversion of a Python/numpy real or complex number to mpf / mpc."""
    if isinstance(x, (mpmath.mpf, mpmath.mpc)):
        return +x
    z = complex(x)
    if z.imag == 0:
        return mpmath.mpf(float(z.real))
    return mpmath.mpc(float(z.real), float(z.imag))


class _Evaluator:
    """Tracks the decimal digits lost to cancellation in the subtractions of one evaluation.

    ``sub(a, b)`` returns a - b and adds about log10(max(|a|, |b|) / |a - b|) (+1 digit of
    slack) to ``lost``. The relative error of a chain of such operations is bounded by
    10^(lost - working digits) times a small factor, so a result computed with
    ``working >= dps + lost + spare`` is good to ``dps`` digits. A difference that is exactly
    0 sets ``lost`` to inf (no finite precision was shown to be enough).
    """

    def __init__(self) -> None:
        self.lost = 0.0

    def sub(self, a: Any, b: Any) -> Any:
        r = a - b
        if a != 0 or b != 0:
            if r == 0:
                self.lost = math.inf
            else:   # binary exponents are enough (and cheap): +1 digit of slack per call
                big = max(mpmath.mag(a), mpmath.mag(b))
                self.lost += max(0.0, (big - mpmath.mag(r)) * _LOG10_2 + 1.0)
        return r


def _entries(L: float, T: float, m: float, c: float, EA: complex, L_e: float, q: float,
             omega: float, chordwise_inertia: bool) -> tuple[tuple[Any, Any, Any, Any, Any], float]:
    """Building blocks at the current working precision, plus the digits lost.

    Returns ``(parts, lost)`` with parts = (K0/D, alpha tau, k_s, k_c, m_axial), where
    m_axial = -omega^2 m~ L / 6 (0 without chordwise inertia).
    """
    ev = _Evaluator()
    L, T, m, c, EA, L_e, q, omega = (_mp(v) for v in (L, T, m, c, EA, L_e, q, omega))
    K0 = EA / L_e
    alpha = q * L / (2 * T)
    lam2 = (q * L / T) ** 2 * L * EA / (T * L_e)
    j = mpmath.mpc(0, 1)
    # -omega^2 m~ L / 6 with m~ = m - i c / omega, written without the division by omega
    m_axial = -(omega**2 * m - j * omega * c) * L / 6 if chordwise_inertia else mpmath.mpf(0)
    if omega == 0:
        # static limit (theory.md §3.6): tau -> 0, D -> 1 + lambda^2/12, k_s = -k_c = T/L
        return (K0 / (1 + lam2 / 12), mpmath.mpf(0), T / L, -T / L, m_axial), 0.0
    beta = mpmath.sqrt((omega**2 * m - j * omega * c) / T)       # principal branch
    Omega = beta * L
    psi = Omega / 2
    tau = ev.sub(1, mpmath.tan(psi) / psi)                        # theory.md §3.1
    D = ev.sub(1, lam2 * tau / (4 * psi**2))
    k_s = T * beta * mpmath.cot(Omega)
    k_c = -T * beta / mpmath.sin(Omega)
    K0_D = K0 / D
    at = alpha * tau
    # the sums formed in the assembly, checked here for cancellation
    sag_term = at**2 * K0_D
    ev.sub(k_s, -sag_term)                        # K_vv
    ev.sub(k_c, -sag_term)                        # K_vAvB
    if chordwise_inertia:
        ev.sub(K0_D, -2 * m_axial)                # K_uu
        ev.sub(-K0_D, -m_axial)                   # K_uAuB
    return (K0_D, at, k_s, k_c, m_axial), ev.lost


def _entries_to_dps(args: tuple[complex, ...], omega: float, chordwise_inertia: bool,
                    dps: int) -> tuple[tuple[Any, Any, Any, Any, Any], int] | None:
    """Raise the working precision until ``dps`` digits survive the cancellation.

    Starts from dps + guard + 2 log10(1/|psi|) (tau = 1 - tan psi / psi loses about
    2 log10(1/|psi|) digits for small psi) and repeats with the cancellation measured at
    the previous precision until it is covered. (If the previous precision was too low, the
    noisy difference shows a loss of about all the working digits, so the loop raises the
    precision rather than accepting it.)
    """
    L, T, m = (float(abs(complex(v))) for v in args[:3])
    psi_est = 0.5 * L * abs(complex(omega)) * math.sqrt(m / T) if T > 0 else 0.0
    extra = 2.0 * max(0.0, -math.log10(psi_est)) if psi_est > 0 else 0.0
    work = int(dps + _GUARD_DIGITS + math.ceil(extra))
    while True:
        with mpmath.workdps(work):
            entries, lost = _entries(*args, omega, chordwise_inertia)
        # a difference that came out exactly 0 cancelled every digit: double the precision
        need = (2 * work if not math.isfinite(lost)
                else int(dps + _SPARE_DIGITS + math.ceil(lost)))
        if need <= work:
            return entries, work
        if need > _MAX_DPS:
            raise ValueError(
                f"precision reference needs {need} digits at omega={omega!r} "
                f"(cancellation {lost:.0f} digits); limit is {_MAX_DPS}")
        work = need + _GUARD_DIGITS - _SPARE_DIGITS


def _to_output(K: list[list[Any]], as_mpmath: bool) -> Any:
    if as_mpmath:
        return mpmath.matrix(K)
    return np.array([[complex(x) for x in row] for row in K], dtype=complex)


def end_stiffness_mp(L: float, T: float, m: float, c: float, EA: complex, L_e: float, q: float,
                     omega: float, chordwise_inertia: bool = True, dps: int = 50,
                     as_mpmath: bool = False) -> NDArray[np.complex128] | None:
    """3x3 dynamic stiffness of end B (A clamped), local (u, v, w), at high precision.

    Naive forms of theory.md §3.4::

        K_B = [[K0/D,            -alpha tau K0/D,              0  ],
               [-alpha tau K0/D,  k_s + (alpha tau)^2 K0/D,    0  ],
               [0,                0,                           k_s]]

    plus -omega^2 m~ L / 3 on K_uu with ``chordwise_inertia``. At omega = 0 the limit
    diag(K0 / (1 + lambda^2/12), T/L, T/L) is returned.

    Parameters
    ----------
    L, T, m, c : float
        Chord length [m], tension [N], mass per chord length [kg/m], viscous damping per
        length [N s/m^2] (>= 0).
    EA : float or complex
        Axial stiffness [N]; EA (1 + i eta) with hysteretic damping.
    L_e : float
        Compliance length [m].
    q : float
        Weight per chord length perpendicular to the chord [N/m].
    omega : float
        Angular frequency [rad/s], >= 0.
    chordwise_inertia : bool
        Add the consistent chordwise mass (theory.md §3.6).
    dps : int
        Significant decimal digits wanted in the result (the working precision is higher
        where the formulas cancel).
    as_mpmath : bool
        Return an ``mpmath.matrix`` (values at the working precision) instead of numpy.

    Returns
    -------
    ndarray, shape (3, 3), complex [N/m], or mpmath.matrix
        Exact to about ``dps`` digits before the conversion to complex128 (which rounds each
        entry to 1.1e-16 relative). Non-finite or overflowing at a pole.
    """
    args = (L, T, m, c, EA, L_e, q)
    (K0_D, at, k_s, _, m_ax), work = _entries_to_dps(args, omega, chordwise_inertia, dps)
    with mpmath.workdps(work):
        zero = mpmath.mpf(0)
        K = [[K0_D + 2 * m_ax, -at * K0_D, zero],
             [-at * K0_D, k_s + at**2 * K0_D, zero],
             [zero, zero, k_s]]
        return _to_output(K, as_mpmath)


def two_end_stiffness_mp(L: float, T: float, m: float, c: float, EA: complex, L_e: float, q: float,
                         omega: float, chordwise_inertia: bool = True, dps: int = 50,
                         as_mpmath: bool = False) -> Any | None:
    """6x6 dynamic stiffness of both ends, local (u_A, v_A, w_A, u_B, v_B, w_B), mpmath.

    Naive forms of theory.md §3.2-3.3: in-plane (K0/D) g g^T + [[0,0,0,0],[0,k_s,0,k_c],
    [0,0,0,0],[0,k_c,0,k_s]] on (u_A, v_A, u_B, v_B) with g = [1, alpha tau, -1, alpha tau];
    out-of-plane [[k_s, k_c], [k_c, k_s]] on (w_A, w_B); with ``chordwise_inertia``
    -omega^2 m~ (L/6) [[2, 1], [1, 2]] on (u_A, u_B).

    Parameters
    ----------
    L, T, m, c, EA, L_e, q, omega, chordwise_inertia, dps, as_mpmath
        As in :func:`end_stiffness_mp`.

    Returns
    -------
    ndarray, shape (6, 6), complex [N/m], or mpmath.matrix
    """
    args = (L, T, m, c, EA, L_e, q)
    (K0_D, at, k_s, k_c, m_ax), work = _entries_to_dps(args, omega, chordwise_inertia, dps)
    with mpmath.workdps(work):
        uA, vA, wA, uB, vB, wB = range(6)
        K = [[mpmath.mpf(0)] * 6 for _ in range(6)]
        g = {uA: 1, vA: at, uB: -1, vB: at}
        for i in g:
            for k in g:
                K[i][k] = K0_D * g[i] * g[k]
        string = {(vA, vA): k_s, (vB, vB): k_s, (vA, vB): k_c, (vB, vA): k_c,
                  (wA, wA): k_s, (wB, wB): k_s, (wA, wB): k_c, (wB, wA): k_c,
                  (uA, uA): 2 * m_ax, (uB, uB): 2 * m_ax, (uA, uB): m_ax, (uB, uA): m_ax}
        for (i, k), val in string.items():
            K[i][k] += val
        return _to_output(K, as_mpmath)


def irvine_symmetric_roots_mp(lambda_sq: Any, n_roots: int, dps: int = 50) -> list[Any] | None:
    """First ``n_roots`` symmetric in-plane roots of Irvine & Caughey (1974), mpmath.

    tan(Omega/2) = Omega/2 - (4/lambda^2) (Omega/2)^3 (theory.md §2.2). With psi = Omega/2
    the equation is multiplied by cos(psi) / (4 psi^3 / lambda^2 + psi), which is finite and
    nonzero inside each branch ((2k-1) pi/2, (2k+1) pi/2), giving

        g(psi) = (4 psi^3 cos(psi) / lambda^2 - psi cos psi + sin psi)
                 / (4 psi^3 / lambda^2 + psi) = 0:

    continuous, and equal to sin(psi) / (4 psi^3 / lambda^2 + psi) at the two ends of the
    branch (of opposite signs). The k-th root is found in its branch by ``mpmath.findroot``
    with the bracketing Anderson-Bjorck solver (bisection if that stalls); |g| < 10^-dps is
    then checked (g' is of order one there). For small lambda^2 the root lies
    u ~ lambda^2 / (4 psi_k^3) above the branch's start psi_k = (2k-1) pi/2 (then g ~ cos psi:
    |sin u| = |cos psi| <= lambda^2 / (4 psi^3 - lambda^2 psi)); where that offset is below
    10^-(dps+10) of psi_k, the end values of g would drown in the rounding of cos(psi_k), and
    the taut-string root (2k-1) pi is returned instead: it is the root to more than dps
    digits.

    Parameters
    ----------
    lambda_sq : float, str or mpf
        Irvine parameter lambda^2 >= 0; ``mpmath.inf`` gives the inextensible limit
        tan(Omega/2) = Omega/2. Strings are read at full precision (e.g. "39.4784...").
    n_roots : int
        Number of roots, >= 1.
    dps : int
        Decimal digits.

    Returns
    -------
    list of mpf, length n_roots
        Omega_k with (2k-1) pi < Omega_k < (2k+1) pi, to ``dps`` digits. lambda^2 = 0 gives
        the taut string, (2k-1) pi.
    """
    n = int(n_roots)
    if n < 1:
        raise ValueError(f"n_roots must be >= 1, got {n_roots!r}")
    with mpmath.workdps(dps + _GUARD_DIGITS):
        lam2 = mpmath.mpf(lambda_sq)
        if not lam2 >= 0:
            raise ValueError(f"lambda_sq must be >= 0, got {lambda_sq!r}")
        roots = []
        for k in range(1, n + 1):
            lo = (2 * k - 1) * mpmath.pi / 2
            hi = (2 * k + 1) * mpmath.pi / 2
            if lam2 == 0:                              # taut string: Omega = (2k-1) pi
                roots.append(2 * lo)
                continue
            if lam2 < mpmath.mpf(10) ** (-dps - 10) * lo**4:   # u / psi_k < 10^-(dps+10)
                roots.append(2 * lo)
                continue
            inv = 1 / lam2                             # 0 for lambda^2 = inf

            def g(x: Any, inv: Any = inv) -> Any:
                cx = mpmath.cos(x)
                return (4 * x**3 * cx * inv - x * cx + mpmath.sin(x)) / (4 * x**3 * inv + x)

            tol = mpmath.mpf(10) ** (-dps)
            x = mpmath.findroot(g, (lo, hi), solver="anderson", verify=False)
            if not (lo <= x <= hi and abs(g(x)) < tol):
                # Anderson-Bjorck can stall when the root hugs a branch end (lambda^2 << 1e-20)
                x = mpmath.findroot(g, (lo, hi), solver="bisect", verify=False,
                                    maxsteps=4 * mpmath.mp.prec)
            if not (lo <= x <= hi and abs(g(x)) < tol):
                raise ArithmeticError(
                    f"Irvine root {k} of lambda^2 = {lam2} not converged: psi = {x}, "
                    f"residual {abs(g(x))}")
            roots.append(2 * x)
    with mpmath.workdps(dps):
        return [+r for r in roots]
