"""Solving for one elastic catenary (theory.md §1.1): its state from its ends and unstretched
length (Newton on the end offsets with the analytic flexibility, from several starting
guesses; the vertical cable in closed form), and the unstretched length that gives a
prescribed tension at its upper end (bracketing).
"""

from __future__ import annotations

from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import point, positive_scalar
from dynstiff.cable.catenary import CatenaryState, end_offsets_and_flexibility
from dynstiff.constants import MAX_COORDINATE, STANDARD_GRAVITY
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError
from dynstiff.params import Cable

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["solve_catenary", "unstretched_length_for_tension"]


_RTOL = 1e-12


# --------------------------------------------------------------------------- solver
def _validate_ends(
        anchor: NDArray[np.float64], end: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    A = point("anchor", anchor)
    B = point("end", end)
    if max(np.abs(A).max(), np.abs(B).max()) > MAX_COORDINATE:
        raise InvalidParameterError(
            f"anchor and end must lie within {MAX_COORDINATE:g} m of the origin (the "
            f"catenary's squares and products must stay finite), got anchor={A.tolist()} "
            f"end={B.tolist()}")
    L = float(np.linalg.norm(B - A))
    if L <= 1e-12 * max(1.0, float(np.max(np.abs(A)))):
        raise InvalidParameterError(
            f"anchor and end must be distinct points, got anchor={A.tolist()} end={B.tolist()}")
    return A, B, L


def _vertical_solution(lh: float, h: float, L0: float, EA: float, w0: float) -> float:
    """Exactly vertical chord: straight cable, H = 0; returns V0 [N]."""
    W = w0 * L0
    # h = L0 (V0 + W/2)/EA + sign * L0 for a cable in tension throughout
    if h < 0:       # B below A: V0 + W < 0 everywhere
        V0 = EA * (h + L0) / L0 - 0.5 * W
        if V0 + W >= 0:
            raise SlackCableError(
                f"vertical cable with end below anchor is slack: drop {-h!r} m is not larger "
                f"than the hanging length of the unstretched_length {L0!r} m")
    else:           # B above A: V0 > 0
        V0 = EA * (h - L0) / L0 - 0.5 * W
        if V0 <= 0:
            raise SlackCableError(
                f"vertical cable rising from the anchor is slack: rise {h!r} m is not larger than "
                f"unstretched_length {L0!r} m stretched by its own weight")
    return V0


def _initial_guesses(lh: float, h: float, L0: float, EA: float,
                     w0: float) -> list[tuple[float, float]]:
    """Candidate (H, V0) starting points [N]: elastic straight cable, and Peyrot-Goulois."""
    W = w0 * L0
    L = float(np.hypot(lh, h))
    guesses = []
    if L > L0:          # taut: straight elastic cable, tension from strain, plus weight
        T = EA * (L / L0 - 1.0)
        if not np.isfinite(T):      # a strain beyond float64 (L0 ~ 1e-300 m): no guess
            raise InvalidParameterError(
                f"unstretched_length {L0!r} m: the straight cable's strain to its chord "
                f"{L!r} m overflows (EA {EA!r} N)")
        T = max(T, 0.5 * W)
        H = T * lh / L
        guesses.append((H, T * h / L - 0.5 * W))
    # Peyrot & Goulois (1979) catenary starting value
    if L0 * L0 <= L * L:
        lam = 0.2
    elif lh <= 1e-6 * L:
        lam = 1e6
    else:
        lam = np.sqrt(3.0 * ((L0 * L0 - h * h) / (lh * lh) - 1.0))
    H = max(abs(0.5 * w0 * lh / lam), 1e-8 * (W + EA * 1e-9))
    V0 = 0.5 * w0 * (h / np.tanh(lam) - L0) if lam < 700 else 0.5 * w0 * (h - L0)
    guesses.append((H, V0))
    return guesses


def _newton(lh: float, h: float, L0: float, EA: float, w0: float, H: float, V0: float,
            max_iter: int) -> tuple[float, float, float]:
    """Damped Newton on (H, V0) keeping H > 0. Returns (H, V0, relative residual)."""
    target = np.array([lh, h])
    # each offset relative to its own size: x is resolved to 1e-12 of l_h even for
    # an almost vertical chord (H / l_h is the out-of-plane stiffness)
    scale = np.array([lh, max(np.hypot(lh, h), L0)])
    xz, F = end_offsets_and_flexibility(H, V0, L0, EA, w0)
    r = xz - target
    res = np.max(np.abs(r) / scale)
    for _ in range(max_iter):
        if res <= _RTOL:
            return H, V0, res
        try:
            step = np.linalg.solve(F, -r)
        except np.linalg.LinAlgError:
            break
        t = 1.0
        while True:
            H_new = H + t * step[0]
            if H_new > 0.1 * H:       # keep H positive: at most a 10x reduction per step
                V_new = V0 + t * step[1]
                xz_new, F_new = end_offsets_and_flexibility(H_new, V_new, L0, EA, w0)
                r_new = xz_new - target
                res_new = np.max(np.abs(r_new) / scale)
                if res_new < res or t < 1e-3 or res_new <= _RTOL:
                    break
            t *= 0.5
            if t < 1e-6:
                return H, V0, res
        H, V0, xz, F, r, res = H_new, V_new, xz_new, F_new, r_new, res_new
    return H, V0, res


def solve_catenary(anchor: ArrayLike, end: ArrayLike, unstretched_length: float,
                   cable: Cable, g: float = STANDARD_GRAVITY, max_iter: int = 100) -> CatenaryState:
    """Static equilibrium of an elastic catenary between anchor A and end B.

    Solves x(L0) = l_h, z(L0) = h of the exact elastic catenary (theory.md §1.1, Irvine 1981)
    for (H, V0) by Newton's method with the analytic Jacobian, to relative residuals
    |x - l_h| / l_h <= 1e-12 and |z - h| / max(|B - A|, L0) <= 1e-12. Exactly vertical chords use
    the closed form of a straight hanging cable.

    Parameters
    ----------
    anchor, end : array_like, shape (3,)
        Positions of A (fixed) and B [m]; z is up, gravity is (0, 0, -g).
    unstretched_length : float
        L0 [m], > 0.
    cable : Cable
    g : float, optional
        Gravity [m/s^2], >= 0 (default :data:`STANDARD_GRAVITY`). With g = 0 the cable is a
        straight elastic spring.
    max_iter : int, optional
        Newton iterations per starting guess.

    Returns
    -------
    CatenaryState

    Raises
    ------
    InvalidParameterError
        Bad argument (named in the message).
    SlackCableError
        A vertical or weightless cable shorter than its chord would need compression.
    ConvergenceError
        Newton failed from every starting guess; the message gives the residual.

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.solve_catenary([0, 0, 0], [4.0, 0, 3.0], 5.0, cable)   # a 5 m chord
    >>> print(f"H = {state.H:.1f} N, residual below 1e-12: {state.residual < 1e-12}")
    H = 60.4 N, residual below 1e-12: True
    """
    A, B, L = _validate_ends(anchor, end)
    L0 = positive_scalar("unstretched_length", unstretched_length)
    if isinstance(max_iter, bool) or not isinstance(max_iter, Integral) or max_iter < 1:
        raise InvalidParameterError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    if not isinstance(cable, Cable):
        raise InvalidParameterError(f"cable must be a dynstiff.Cable, got {type(cable).__name__}")
    g = positive_scalar("g", g, allow_zero=True)
    EA, w0 = cable.EA, cable.mass_per_length * g
    d = B - A
    lh, h = float(np.hypot(d[0], d[1])), float(d[2])

    def make(H: float, V0: float, res: float) -> CatenaryState:
        return CatenaryState(anchor=A, end=B, unstretched_length=L0, cable=cable, g=g,
                             H=float(H), V0=float(V0), residual=float(res))

    if w0 == 0.0:      # straight spring
        if L <= L0:
            raise SlackCableError(
                f"weightless cable is slack: chord {L!r} m <= unstretched_length {L0!r} m")
        T = EA * (L / L0 - 1.0)
        return make(T * lh / L, T * h / L, 0.0)
    if lh <= 1e-14 * L:
        return make(0.0, _vertical_solution(lh, h, L0, EA, w0), 0.0)

    best = (None, None, np.inf)
    for H0, V00 in _initial_guesses(lh, h, L0, EA, w0):
        H, V0, res = _newton(lh, h, L0, EA, w0, H0, V00, max_iter)
        if res <= _RTOL:
            return make(H, V0, res)
        if res < best[2]:
            best = (H, V0, res)
    raise ConvergenceError(
        f"elastic catenary did not converge: relative residual {best[2]:.3e} > {_RTOL:.0e} "
        f"(anchor={A.tolist()}, end={B.tolist()}, unstretched_length={L0!r})",
        residual=best[2])


def unstretched_length_for_tension(anchor: ArrayLike, end: ArrayLike, tension: float, cable: Cable,
                                   g: float = STANDARD_GRAVITY, at: str = "end") -> CatenaryState:
    """Unstretched length L0 [m] that gives a prescribed tension at B (or at A).

    Parameters
    ----------
    anchor, end : array_like, shape (3,)
        Positions of A and B [m].
    tension : float
        Prescribed tension [N], > 0, at ``at``.
    cable : Cable
    g : float, optional
        Gravity [m/s^2].
    at : {"end", "anchor"}
        Where the tension is prescribed.

    Returns
    -------
    CatenaryState
        The equilibrium; its ``unstretched_length`` is the answer.

    Notes
    -----
    Brent's method on log(T(L0) / T) in L0, bracketed by growing L0 from below the chord
    until the tension first drops under the target. The tension first decreases as L0
    grows, reaches a minimum, then rises again as the cable hangs deeper; the solution
    returned is the shorter, taut one. Raises :class:`SlackCableError` when the target is
    below the minimum tension any cable between these points can have,
    :class:`InvalidParameterError` when the strain tension / EA leaves no unstretched length
    above 0 (EA below about 1e-300 N), and :class:`ConvergenceError` with its residual when
    the tension found misses the target by more than 1e-9, relative. Brent's step tolerance
    is relative to L0's scale, so a very soft cable (L0 far below the chord) is solved as
    accurately as a stiff one.

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> print(f"L0 = {state.unstretched_length:.6f} m, T_B = {state.tension_at_end:.6f} N")
    L0 = 4.999103 m, T_B = 300.000000 N
    """
    from scipy.optimize import brentq

    A, B, L = _validate_ends(anchor, end)
    T_target = positive_scalar("tension", tension)
    if at not in ("end", "anchor"):
        raise InvalidParameterError(f"at must be 'end' or 'anchor', got {at!r}")
    g = positive_scalar("g", g, allow_zero=True)

    def tension_of(state: CatenaryState) -> float:
        return state.tension_at_end if at == "end" else state.tension_at_anchor

    def f(L0: float) -> float:
        return np.log(tension_of(solve_catenary(A, B, L0, cable, g)) / T_target)

    # Upper bracket: a short cable is stiff, so tension is high; lower tension needs longer L0.
    L_hi_tension = L / (1.0 + 2.0 * T_target / cable.EA)
    if not L_hi_tension > 0.0:
        raise InvalidParameterError(
            f"tension {T_target!r} N at the {at}: its strain tension / EA = "
            f"{T_target / cable.EA:.3g} (EA {cable.EA!r} N) leaves no unstretched length above "
            f"0 between anchor {A.tolist()} and end {B.tolist()}")

    def too_long(L0: float) -> bool | None:  # tension under the target, or slack (vertical cable)
        try:
            return f(L0) < 0
        except SlackCableError:
            return True

    while too_long(L_hi_tension):
        L_hi_tension *= 1.0 - 0.5 * min(0.5, 1.0 / max(np.log10(cable.EA), 1.0))
    # Lower bracket: grow L0 until the tension drops under the target; a straight (vertical)
    # cable that goes slack first, at a length where the tension would be negative, is
    # bisected back between the last length too tensioned and the first slack one.
    L_lo_tension = L / (1.0 + 0.5 * T_target / cable.EA)
    taut, slack = L_hi_tension, np.inf
    k = 0
    while True:
        try:
            val = f(L_lo_tension)
        except SlackCableError:
            val, slack = None, L_lo_tension
        except ConvergenceError:
            val = None
        if val is not None and val < 0:
            break
        if val is not None:
            taut = L_lo_tension
        L_lo_tension = 1.05 * L_lo_tension if np.isinf(slack) else 0.5 * (taut + slack)
        k += 1
        if k > 200:
            raise SlackCableError(
                f"tension {T_target!r} N at the {at} is not reachable between anchor "
                f"{A.tolist()} and end {B.tolist()}: no unstretched length gives a tension "
                f"this low")
    # xtol on the scale of L0 itself: a very soft cable's L0 is far below the chord L
    L0 = brentq(f, L_hi_tension, L_lo_tension, xtol=1e-15 * L_hi_tension, rtol=1e-15,
                maxiter=200)
    state = solve_catenary(A, B, L0, cable, g)
    miss = abs(tension_of(state) / T_target - 1.0)
    if not miss <= 1e-9:
        raise ConvergenceError(
            f"unstretched length for tension {T_target!r} N at the {at}: the tension found "
            f"is {tension_of(state)!r} N (relative residual {miss:.2e})", residual=miss)
    return state
