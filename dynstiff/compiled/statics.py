"""Compiled (numba) inverse statics of a robot with taut cables: the fixed point of cable
directions and tension distribution (theory.md §13.1, §13.6) in one call.

:func:`fixed_point` is the loop of :func:`dynstiff.robot.statics.inverse_statics` for its
regular case: the distribution found by the active-set method from the previous active set
or from the limits the minimum-distance solution violates, and every cable solved by the
batched Newton (:func:`dynstiff.compiled.catenary.newton_taut`). A distribution that needs
the LP's feasible point returns :data:`NEEDS_LP` with the state it stopped at: the caller
finds the active set by the LP and calls again from that state. Whatever else happens (a
singular configuration, no feasible distribution, a cable left to the scalar solver, no
convergence) returns a status and the state of the failing iteration, from which the
numpy loop continues: it stays the reference and says what went wrong.
"""

import numba
import numpy as np

from dynstiff.compiled.catenary import newton_taut

__all__ = ["CONVERGED", "NEEDS_LP", "fixed_point"]

_JIT = {"cache": True, "error_model": "numpy", "nogil": True}
#: Status of :func:`fixed_point`: converged; a distribution needs the LP's feasible point
#: (the caller finds its active set and calls again); anything else is the numpy loop's case.
CONVERGED = 0
_NUMPY = 1
NEEDS_LP = 2
_EPS = np.finfo(np.float64).eps
_CAT_RTOL = 1e-13         # as dynstiff.cable.catenary_batch
_CAT_MAX_ITER = 40


@numba.njit(**_JIT)
def _lstsq(A, b):
    """Minimum-norm least squares with numpy's default cut-off (eps max(m, n) of the
    largest singular value); returns (x, rank)."""
    m, n = A.shape
    x, _, rank, _ = np.linalg.lstsq(np.ascontiguousarray(A), b, rcond=_EPS * max(m, n))
    return x, rank


@numba.njit(**_JIT)
def _matvec(A, x):
    out = np.zeros(A.shape[0])
    for i in range(A.shape[0]):
        for j in range(A.shape[1]):
            out[i] += A[i, j] * x[j]
    return out


@numba.njit(**_JIT)
def _active_solution(W, w, bound, r):
    """As ``statics._active_solution``: (tensions, ok)."""
    act = np.flatnonzero(~np.isnan(bound))
    free = np.flatnonzero(np.isnan(bound))
    target = np.where(np.isnan(bound), 0.0, bound)
    if free.size == 0:
        return target, False
    b = w - _matvec(W[:, act], bound[act])
    Wf = W[:, free]
    sol, rank = _lstsq(Wf, b - _matvec(Wf, r[free]))
    if rank < W.shape[0]:
        return target, False
    target[free] = r[free] + sol
    return target, True


@numba.njit(**_JIT)
def _closest_in_box(W, w, lb, ub, r, t, tol, bound):
    """As ``statics._closest_in_box``: (t, sides, ok)."""
    k, n = W.shape
    t = t.copy()
    bound = bound.copy()
    scale = max(1.0, np.abs(t).max(), np.abs(r).max())
    for _ in range(10 * n + 10):
        act = np.flatnonzero(~np.isnan(bound))
        free = np.flatnonzero(np.isnan(bound))
        target = np.where(np.isnan(bound), 0.0, bound)
        b = w - _matvec(W[:, act], bound[act])
        Wf = W[:, free]
        if free.size:
            target[free] = r[free] + _lstsq(Wf, b - _matvec(Wf, r[free]))[0]
        p = target - t
        if np.abs(p).max() > 1e-12 * scale:
            j, least = -1, np.inf
            for i in free:               # largest step in [0, 1] keeping the free in the box
                if abs(p[i]) <= 1e-12 * scale:
                    continue
                room = (t[i] - lb[i]) / -p[i] if p[i] < 0 else (ub[i] - t[i]) / p[i]
                if room < least:
                    j, least = i, room
            if j >= 0 and least < 1.0:
                t += max(least, 0.0) * p
                bound[j] = lb[j] if p[j] < 0 else ub[j]
                t[j] = bound[j]
                continue
        t = target
        sides = np.zeros(n, dtype=np.int64)
        if act.size == 0:
            return t, sides, True
        nu = _lstsq(np.ascontiguousarray(Wf.T), -(t - r)[free])[0] if free.size \
            else np.zeros(k)
        g = (t - r) + _matvec(np.ascontiguousarray(W.T), nu)
        i_min, mu_min = -1, np.inf
        for i in act:
            mu = g[i] if bound[i] == lb[i] else -g[i]
            if mu < mu_min:
                i_min, mu_min = i, mu
        if mu_min >= -tol:
            for i in act:
                sides[i] = -1 if bound[i] == lb[i] else 1
            return t, sides, True
        bound[i_min] = np.nan
    return t, np.zeros(n, dtype=np.int64), False


@numba.njit(**_JIT)
def _distribution(W, w, t_min, t_max, t_ref, sides):
    """As ``statics._distribution`` without its LP: (t, sides, ok)."""
    k, n = W.shape
    dt, rank = _lstsq(W, w - _matvec(W, t_ref))
    zero = np.zeros(n, dtype=np.int64)
    if rank < k:
        return t_ref, zero, False
    t = t_ref + dt
    tol = 1e-9 * max(1.0, np.abs(t).max())
    if np.all(t >= t_min - tol) and np.all(t <= t_max + tol):
        return t, zero, True
    if n <= k:
        return t, zero, False
    violated = np.where(t < t_min, -1, np.where(t > t_max, 1, 0))
    for g in range(2):
        guess = sides if g == 0 else violated
        if g == 0 and not np.any(sides != 0):
            continue
        bound = np.where(guess < 0, t_min, np.where(guess > 0, t_max, np.nan))
        start, ok = _active_solution(W, w, bound, t_ref)
        # within the limits to rounding: the LP's optimum has free tensions on a limit
        # (its active set, given as ``sides``, puts them there to the last digits)
        near = 1e-12 * max(1.0, np.abs(start).max())
        if ok and np.all(start >= t_min - near) and np.all(start <= t_max + near):
            return _closest_in_box(W, w, t_min, t_max, t_ref, start, tol, bound)
    return t, zero, False


@numba.njit(**_JIT)
def _end_quantities(A, B, H, V0, L0, w0):
    """As ``statics._end_quantities``: unit force directions on B (n, 3), lo, hi (n,)."""
    n = H.size
    u = np.empty((n, 3))
    lo, hi = np.empty(n), np.empty(n)
    for i in range(n):
        d0, d1, d2 = B[i, 0] - A[i, 0], B[i, 1] - A[i, 1], B[i, 2] - A[i, 2]
        lh = np.hypot(d0, d1)
        vertical = lh <= 1e-14 * np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        e0, e1 = (1.0, 0.0) if vertical else (d0 / lh, d1 / lh)
        Vb = V0[i] + w0[i] * L0[i]
        T_B = np.hypot(H[i], Vb)
        T_A = np.hypot(H[i], V0[i])
        u[i, 0], u[i, 1], u[i, 2] = -H[i] * e0 / T_B, -H[i] * e1 / T_B, -Vb / T_B
        T_min = H[i] if (V0[i] < 0.0 and Vb > 0.0) else np.hypot(H[i], min(abs(V0[i]),
                                                                          abs(Vb)))
        lo[i], hi[i] = T_B - T_min, max(T_B, T_A) - T_B
    return u, lo, hi


@numba.njit(**_JIT)
def _catenaries(A, B, t, EA, w0, H, V0, L0, warm):
    """As ``catenary_batch.taut_catenaries`` when every cable is solved by the batch:
    (H, V0, L0, residual, ok)."""
    n = t.size
    lh, h, L = np.empty(n), np.empty(n), np.empty(n)
    for i in range(n):
        d0, d1, h[i] = B[i, 0] - A[i, 0], B[i, 1] - A[i, 1], B[i, 2] - A[i, 2]
        lh[i] = np.hypot(d0, d1)
        L[i] = np.hypot(lh[i], h[i])
        if not (lh[i] > 1e-14 * L[i] and w0[i] > 0):    # vertical or weightless
            return H, V0, L0, np.full(n, np.nan), False
    sL0 = L / (1.0 + t / EA)                       # the straight elastic cable
    sH, sV0 = t * lh / L, t * h / L - w0 * sL0
    valid = warm and np.all(np.isfinite(H)) and np.all(np.isfinite(V0)) \
        and np.all(np.isfinite(L0)) and np.all(H > 0) and np.all(L0 > 0)
    gH, gV0, gL0 = (H, V0, L0) if valid else (sH, sV0, sL0)
    H1, V1, L1, ok, res = newton_taut(lh, h, L, t, EA, w0, gH, gV0, gL0, _CAT_RTOL,
                                      _CAT_MAX_ITER)
    if warm and not np.all(ok):                    # the others from the straight cable
        redo = np.flatnonzero(~ok)
        H2, V2, L2, ok2, res2 = newton_taut(lh[redo], h[redo], L[redo], t[redo], EA[redo],
                                            w0[redo], sH[redo], sV0[redo], sL0[redo],
                                            _CAT_RTOL, _CAT_MAX_ITER)
        H1[redo], V1[redo], L1[redo], ok[redo], res[redo] = H2, V2, L2, ok2, res2
    return H1, V1, L1, res, np.all(ok)


@numba.njit(**_JIT)
def fixed_point(A, B, r, free_index, w, EA, w0, t_min, t_max, t_ref, has_ref, u, lo, hi,
                H, V0, L0, warm, sides, max_iter):
    """The fixed point of :func:`dynstiff.robot.statics.inverse_statics` (module notes).

    Parameters
    ----------
    A, B : ndarray, shape (n, 3)
        Anchors and platform attachment points [m].
    r : ndarray, shape (n, 3)
        Lever arms of the attachment points about P [m].
    free_index : ndarray of int, shape (k,)
    w : ndarray, shape (k,)
        Minus the platform weight's wrench on the free DOFs [N, N m].
    EA, w0 : ndarray, shape (n,)
        [N], weight per unstretched length [N/m].
    t_min, t_max : ndarray, shape (n,)
        Tension limits [N] (t_max may be inf).
    t_ref : ndarray, shape (n,)
        Reference of the distribution [N], used when ``has_ref`` (else the lower bound of
        each iteration, as the numpy loop).
    u, lo, hi : ndarray, shape (n, 3), (n,), (n,)
        The start: unit cable-end directions and the tension margins along the cables [N].
    H, V0, L0 : ndarray, shape (n,)
        Catenaries to start Newton from when ``warm``.
    sides : ndarray of int, shape (n,)
        The active set to try first (-1 / +1 at the lower / upper limit, 0 free), e.g. that
        of the LP's distribution at this start.
    max_iter : int

    Returns
    -------
    status : int
        :data:`CONVERGED`; :data:`NEEDS_LP` when a distribution needs the LP's feasible
        point; else the numpy loop's case.
    iterations : int
        Iterations done; at a failure, the failing one is not counted.
    t, H, V0, L0, residual : ndarray, shape (n,)
        Tensions at B [N] and the catenaries [N, N, m], their relative residual [-]; at a
        failure, H, V0, L0 are the start's catenaries of the failing iteration.
    u, lo, hi : ndarray, shape (n, 3), (n,), (n,)
        The directions and margins the last iteration started from (at a failure, the
        numpy loop continues from them, with ``warm`` = iterations > 0 or the start's).
    """
    n, k = u.shape[0], free_index.size
    sides = sides.copy()
    best, since_best, last = np.inf, 0, np.inf
    t = np.full(n, np.nan)
    res = np.full(n, np.nan)
    for it in range(max_iter):
        W = np.empty((k, n))
        for i in range(n):
            m0 = r[i, 1] * u[i, 2] - r[i, 2] * u[i, 1]          # r x u
            m1 = r[i, 2] * u[i, 0] - r[i, 0] * u[i, 2]
            m2 = r[i, 0] * u[i, 1] - r[i, 1] * u[i, 0]
            for q in range(k):
                j = free_index[q]
                W[q, i] = u[i, j] if j < 3 else (m0 if j == 3 else (m1 if j == 4 else m2))
        lower, upper = t_min + lo, t_max - hi
        t, sides, ok = _distribution(W, w, lower, upper, t_ref if has_ref else lower, sides)
        if not ok:
            return NEEDS_LP, it, t, H, V0, L0, res, u, lo, hi
        H1, V1, L1, res, ok = _catenaries(A, B, t, EA, w0, H, V0, L0, warm)
        if not ok:
            return _NUMPY, it, t, H, V0, L0, res, u, lo, hi
        H, V0, L0 = H1, V1, L1
        warm = True
        u_new, lo_new, hi_new = _end_quantities(A, B, H, V0, L0, w0)
        change = max(np.abs(u_new - u).max(),
                     max(np.abs(lo_new - lo).max(), np.abs(hi_new - hi).max()) / t.max())
        u, lo, hi = u_new, lo_new, hi_new
        if change < best:
            best, since_best = change, 0
        else:
            since_best += 1
        rho = change / last if 0 < last < np.inf else 1.0
        last = change
        if change < 1e-15 or (rho < 0.5 and change * rho / (1 - rho) < 2e-16) \
                or (best < 1e-9 and since_best >= 10):
            return CONVERGED, it + 1, t, H, V0, L0, res, u, lo, hi
    return _NUMPY, max_iter, t, H, V0, L0, res, u, lo, hi
