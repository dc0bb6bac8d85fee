"""The tension distribution of a redundant robot (theory.md §4): among the tensions that
balance the platform, W t = w, the one closest (2-norm) to a reference within the limits
[t_min, t_max], by an active-set method started from a previous active set, from the limits
the minimum-distance solution violates, or from an LP's feasible point.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import ConvergenceError, SlackCableError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["distribution_with_active_set", "tension_distribution"]


def tension_distribution(W: NDArray[np.float64], w: NDArray[np.float64], t_min: ArrayLike,
                         t_max: ArrayLike,
                         t_ref: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Tensions t [N] with W t = w closest to t_ref in the 2-norm, t_min <= t <= t_max.

    Parameters
    ----------
    W : ndarray, shape (k, n)
        Structure matrix (columns: unit wrenches of the cables), k <= n.
    w : ndarray, shape (k,)
        Wrench the cables must supply.
    t_min, t_max : float or ndarray, shape (n,)
        Tension limits [N] (per cable where arrays).
    t_ref : float or ndarray, shape (n,), optional
        Reference tensions (default t_min: the least tensions in the 2-norm sense).

    Returns
    -------
    ndarray, shape (n,)

    Raises
    ------
    SlackCableError
        No admissible distribution exists (the message names the violated limit).
    """
    return distribution_with_active_set(W, w, np.asarray(t_min, dtype=float),
                                        np.asarray(t_max, dtype=float), t_ref)[0]


def distribution_with_active_set(
        W: NDArray[np.float64], w: NDArray[np.float64], t_min: NDArray[np.float64],
        t_max: NDArray[np.float64], t_ref: NDArray[np.float64] | None = None,
        sides: NDArray[np.int64] | None = None,
        warm: bool = True) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """:func:`tension_distribution` and the active set it ends with.

    ``sides`` (shape (n,), -1 / +1 for a tension held at its lower / upper limit, 0 free),
    e.g. the previous fixed-point iteration's, then the limits that the minimum-distance
    solution violates, are tried as starts of the active-set method when that solution
    leaves the limits: if the tensions an active set gives (the held ones at their limits,
    the free ones the minimum-distance solution of the balance) are within the limits, they
    replace the LP's feasible point. The optimum is unique and the result a function of the
    final active set alone, so the start does not change it. ``warm=False``: always the
    LP's feasible point (the reference).

    Returns
    -------
    t : ndarray, shape (n,)
    sides : ndarray of int, shape (n,)
        The final active set (all 0 when the minimum-distance solution is within limits).
    """
    k, n = W.shape
    t_min = np.broadcast_to(np.asarray(t_min, dtype=float), (n,))
    t_max = np.broadcast_to(np.asarray(t_max, dtype=float), (n,))
    t_ref = t_min.copy() if t_ref is None else np.broadcast_to(
        np.asarray(t_ref, dtype=float), (n,)).copy()
    # minimum-distance solution of the equality (its SVD gives the rank, with
    # np.linalg.matrix_rank's threshold: eps max(k, n) times the largest singular value);
    # if it leaves the limits, a feasible point (the previous active set's solution, else an
    # LP in the null space of W), then the exact closest one (active set)
    dt, _, rank, _ = np.linalg.lstsq(W, w - W @ t_ref, rcond=None)
    if rank < k:
        raise SlackCableError(
            f"the cable directions span only {rank} of the {k} free DOFs "
            f"(singular configuration), no tension distribution balances the platform")
    t = t_ref + dt
    tol = 1e-9 * max(1.0, np.abs(t).max())
    if np.all(t >= t_min - tol) and np.all(t <= t_max + tol):
        return t, np.zeros(n, dtype=int)
    ub = np.where(np.isfinite(t_max), t_max, np.inf)
    # active sets to start from: the given one, then the limits the solution violates
    guesses = [] if sides is None or not np.any(sides) else [sides]
    guesses.append(np.where(t < t_min, -1, np.where(t > t_max, 1, 0)))
    for guess in guesses if n > k and warm else ():
        bound = np.where(guess < 0, t_min, np.where(guess > 0, ub, np.nan))
        start = _active_solution(W, w, bound, t_ref)
        if start is not None and np.all(start >= t_min) and np.all(start <= ub):
            return _closest_in_box(W, w, t_min, ub, t_ref, start, tol, bound)
    if n == k:
        raise SlackCableError(
            f"the unique tension distribution {np.round(t, 6).tolist()} N violates the "
            f"limits {_limits(t_min, t_max)} N")
    from scipy.linalg import null_space
    from scipy.optimize import linprog
    N = null_space(W)
    # feasibility: find lambda with t_min <= t + N lambda <= t_max
    A_ub = np.vstack([-N, N])
    b_ub = np.concatenate([t - t_min, np.where(np.isfinite(t_max), t_max, 1e300) - t])
    lp = linprog(np.zeros(N.shape[1]), A_ub=A_ub, b_ub=b_ub, bounds=[(None, None)] * N.shape[1],
                 method="highs")
    if lp.status != 0:
        raise SlackCableError(
            f"no tension distribution within {_limits(t_min, t_max)} N balances the platform "
            f"(the pose is outside the wrench-feasible workspace)")
    return _closest_in_box(W, w, t_min, ub, t_ref, lp.x @ N.T + t, tol)


def _active_solution(W: NDArray[np.float64], w: NDArray[np.float64], bound: NDArray[np.float64],
                     r: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Tensions with the active ones at ``bound`` (NaN: free) and the free ones the
    minimum-distance solution of the balance (the target of :func:`_closest_in_box`), or
    None when the free cables cannot balance the rest."""
    act = ~np.isnan(bound)
    free = ~act
    target = np.where(act, bound, 0.0)
    b = w - W[:, act] @ bound[act]
    Wf = W[:, free]
    if not np.any(free):
        return None
    sol, _, rank, _ = np.linalg.lstsq(Wf, b - Wf @ r[free], rcond=None)
    if rank < W.shape[0]:
        return None
    target[free] = r[free] + sol
    return target


def _closest_in_box(
        W: NDArray[np.float64], w: NDArray[np.float64], lb: NDArray[np.float64],
        ub: NDArray[np.float64], r: NDArray[np.float64], t: NDArray[np.float64], tol: float,
        bound: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """min ||t - r||^2 subject to W t = w, lb <= t <= ub, by a primal active-set method
    (Nocedal & Wright, Numerical Optimization, 2nd ed., Alg. 16.3) from the feasible t.

    Each step holds the active tensions at their bounds exactly and gives the free ones the
    minimum-distance solution of the balance; a step that would leave the box stops at the
    first bound, which joins the active set; at the subproblem's optimum the bound with the
    most negative multiplier leaves it. The optimum is unique (strictly convex objective),
    so the result does not depend on the start: the inverse-statics fixed point it feeds is
    well defined (a general NLP solver stopped at varying points and stalled that iteration).

    Parameters
    ----------
    W : ndarray, shape (k, n); w : ndarray, shape (k,)
    lb, ub : ndarray, shape (n,)
        Bounds [N] (ub may be inf).
    r : ndarray, shape (n,)
        Reference tensions [N].
    t : ndarray, shape (n,)
        A feasible start [N].
    tol : float
        Feasibility and multiplier tolerance [N].
    bound : ndarray, shape (n,), optional
        Starting active set: the bound each active tension is held at (``t`` holds it
        there), NaN for a free one; default none active.

    Returns
    -------
    t : ndarray, shape (n,)
    sides : ndarray of int, shape (n,)
        -1 / +1 where the tension ends at its lower / upper bound (active), 0 free.
    """
    n = t.size
    t = t.copy()
    # the bound an active tension is held at, else nan
    bound = np.full(n, np.nan) if bound is None else bound.copy()
    scale = max(1.0, np.abs(t).max(), np.abs(r).max())
    for _ in range(10 * n + 10):
        act = ~np.isnan(bound)
        free = ~act
        target = np.where(act, bound, 0.0)
        b = w - W[:, act] @ bound[act]
        Wf = W[:, free]
        if np.any(free):
            target[free] = r[free] + np.linalg.lstsq(Wf, b - Wf @ r[free], rcond=None)[0]
        p = target - t
        if np.abs(p).max() > 1e-12 * scale:
            # largest step in [0, 1] that keeps the free tensions in the box
            with np.errstate(divide="ignore", invalid="ignore"):
                room = np.where(p < 0, (t - lb) / -p, np.where(p > 0, (ub - t) / p, np.inf))
            room = np.where(free & (np.abs(p) > 1e-12 * scale), room, np.inf)
            j = int(np.argmin(room))
            if room[j] < 1.0:
                t += max(room[j], 0.0) * p
                bound[j] = lb[j] if p[j] < 0 else ub[j]
                t[j] = bound[j]
                continue
        t = target
        if not np.any(act):
            return t, np.zeros(n, dtype=int)
        nu = (np.linalg.lstsq(Wf.T, -(t - r)[free], rcond=None)[0] if np.any(free)
              else np.zeros(W.shape[0]))
        g = (t - r) + W.T @ nu                # = mu_lower - mu_upper
        mu = np.where(bound == lb, g, -g)
        mu[free] = np.inf
        i = int(np.argmin(mu))
        if mu[i] >= -tol:
            return t, np.where(act, np.where(bound == lb, -1, 1), 0)
        bound[i] = np.nan
    raise ConvergenceError(
        f"tension distribution: the active-set method did not settle in {10 * n + 10} "
        f"steps (balance residual {np.linalg.norm(W @ t - w):.3e} N)",
        residual=float(np.linalg.norm(W @ t - w)))


def _limits(t_min: NDArray[np.float64], t_max: NDArray[np.float64]) -> str:
    """The limits as text: [lo, hi] when equal for all cables, else per cable."""
    if np.all(t_min == t_min[0]) and np.all(t_max == t_max[0]):     # inf limits included
        return f"[{t_min[0]:g}, {t_max[0]:g}]"
    return f"[{np.round(t_min, 3).tolist()}, {np.round(t_max, 3).tolist()}]"
