"""Compiled (numba) Wittrick-Williams search of the "dsm" rung with undamped cables: the
roots of the count in one call (theory.md §5, §14.2), after the batched count of the seed
grid (:func:`dsm_counts`, which keeps det K for the regula falsi's first end values).

The count at a frequency comes from the signs of the pivots of an elimination without row
interchanges (Sylvester's law of inertia), from the eigenvalues where a pivot is unsure; in
an isolated bracket the regula falsi runs on (-1)^s det K. The numpy search of
:mod:`dynstiff.analyses.eigen` stays the reference it is tested against.
"""

import numba
import numpy as np

from dynstiff.compiled.dsm import BLOCK, JIT, assembled_block, unpack_symmetric

__all__ = ["dsm_counts", "dsm_search"]

#: The search's Illinois step adds a second point 0.45 rtol hi beyond its iterate (to close
#: the bracket at once) when the iterate moved less than this many rtol hi since the last.
_NEAR = 64.0


@numba.njit(**JIT)
def _pivots(K, work, last_free):
    """Signs and product of the pivots of symmetric K by elimination without interchanges
    (K = L D L^T: by Sylvester's law of inertia, D has as many negative entries as K has
    negative eigenvalues, and det K = prod D). Returns (negative pivots, det K, ok); ok is
    False where a pivot (but the last, with ``last_free``) is below 1e-9 of K's largest
    entry or an entry grew beyond 1e5 times it: rounding could then flip a sign, and the
    caller takes the eigenvalues instead."""
    n = K.shape[0]
    big = 0.0
    for i in range(n):
        for j in range(n):
            work[i, j] = K[i, j]
            big = max(big, abs(K[i, j]))
    neg = 0
    det = 1.0
    for k in range(n):
        d = work[k, k]
        if not abs(d) > 1e-9 * big and not (last_free and k == n - 1):
            return 0, np.nan, False
        if d < 0.0:
            neg += 1
        det *= d
        if k == n - 1:
            break
        inv = 1.0 / d
        for i in range(k + 1, n):
            f = work[i, k] * inv
            for j in range(k + 1, n):
                work[i, j] -= f * work[k, j]
                if not abs(work[i, j]) <= 1e5 * big:
                    return 0, np.nan, False
    return neg, det, True


@numba.njit(**JIT)
def _assembled_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk):
    """Kk = K(w) at one frequency w [rad/s]; returns (J0, K finite)."""
    wa = np.empty(1)
    wa[0] = w
    J0 = np.empty(1, dtype=np.int64)
    Kb = assembled_block(wa, L, m, T, lam2, alpha, K0, chordwise, series, assembly, J0, True)
    return J0[0], np.isfinite(unpack_symmetric(Kb[0], K_static, M, w, Kk))


@numba.njit(**JIT)
def _count_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk,
               work):
    """(J, J0, det) of the Wittrick-Williams count at one frequency w [rad/s]: the negative
    eigenvalues of K(w) from the signs of its pivots (:func:`_pivots`), from its eigenvalues
    where the pivots are not sure; none where K is not finite (as :func:`dsm_count` with
    ``numpy.sum(ev < 0)``). det is the product of the pivots where they are sure (what
    :func:`_det_one` returns there: the same elimination), NaN elsewhere."""
    J0, finite = _assembled_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                                K_static, M, Kk)
    if not finite:
        return J0, J0, np.nan
    neg, det, ok = _pivots(Kk, work, False)
    if not ok:
        neg = 0
        for v in np.linalg.eigvalsh(Kk):
            if v < 0.0:
                neg += 1
    return J0 + neg, J0, det


@numba.njit(**JIT)
def dsm_counts(omega, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M):
    """The Wittrick-Williams count J(omega) and the cable count J0(omega) at every frequency
    of ``omega`` (n,) [rad/s], in blocks as :func:`dynstiff.compiled.dsm.dsm_count` but with
    the negative eigenvalues of K counted from its pivots (:func:`_count_one`'s rule, the
    eigenvalues only where a pivot is unsure): the counts of the search's seed grid, which
    needs no eigenvalue. Where K is not finite J = J0, as there.

    Returns
    -------
    J, J0 : ndarray of int, shape (n,)
    det : ndarray, shape (n,)
        det K(omega) where the pivots are sure (as :func:`_count_one`), else NaN: the
        search's regula falsi starts from it instead of computing it again.
    """
    n, nf = omega.size, K_static.shape[0]
    J = np.empty(n, dtype=np.int64)
    J0 = np.empty(n, dtype=np.int64)
    det = np.full(n, np.nan)
    Kk = np.empty((nf, nf))
    work = np.empty((nf, nf))
    for start in range(0, n, BLOCK):
        w = omega[start:start + BLOCK]
        Kb = assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                             J0[start:start + BLOCK], True)
        for b in range(w.size):
            J[start + b] = J0[start + b]
            if not np.isfinite(unpack_symmetric(Kb[b], K_static, M, w[b], Kk)):
                continue
            neg, d, ok = _pivots(Kk, work, False)
            if ok:
                det[start + b] = d
            else:
                neg = 0
                for v in np.linalg.eigvalsh(Kk):
                    if v < 0.0:
                        neg += 1
            J[start + b] += neg
    return J, J0, det


@numba.njit(**JIT)
def _det_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk,
             work):
    """det K(w) at one frequency w [rad/s] (NaN where K is not finite): the product of the
    pivots (:func:`_pivots`, the last one free to vanish), or by LU with partial pivoting
    where an earlier pivot is not sure."""
    _, finite = _assembled_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                               K_static, M, Kk)
    if not finite:
        return np.nan
    _, det, ok = _pivots(Kk, work, True)
    return det if ok else np.linalg.det(Kk)


@numba.njit(**JIT)
def dsm_search(grid, J_grid, J0_grid, det_grid, n_roots, rtol, max_iter, L, m, T, lam2,
               alpha, K0, chordwise, series, assembly, K_static, M):
    """The ``n_roots`` lowest natural frequencies [rad/s] of the "dsm" rung with undamped
    cables from its counts on ``grid``, in one compiled call (theory.md §5, §14.2).

    Root by root, its bracket from the grid is bisected on the count (pivot signs,
    :func:`_count_one`) until it holds that root alone and no cable pole; every count also
    tightens the brackets of the roots above that contain its frequency. In an isolated
    bracket exactly one eigenvalue of K crosses zero, decreasing, so g = (-1)^s det K (s the
    negative eigenvalues at its low end) goes once from >= 0 to < 0; the Illinois iteration
    of :func:`dynstiff.analyses.eigen._illinois` closes the bracket on g (Anderson-Bjorck
    scaling, a bisection where the bracket has not halved in three steps, and once the
    iterates settle (within ``_NEAR`` rtol hi) a second point 0.45 rtol hi towards the far
    end, which closes the bracket at once). Multiple roots and roots on a cable
    pole are bisected to ``rtol``.

    Parameters
    ----------
    grid : ndarray, shape (n,)
        Ascending frequencies [rad/s], grid[0] = 0, with J(grid[-1]) >= n_roots.
    J_grid, J0_grid : ndarray of int, shape (n,)
        The counts there (J_grid[0] = J0_grid[0] = 0).
    det_grid : ndarray, shape (n,)
        det K there where known (:func:`dsm_counts`), NaN elsewhere: a bracket's end
        values are read from it (or from the bisection's counts) before they are computed.
    n_roots : int
    rtol : float
        Relative width of the final brackets.
    max_iter : int
        Most Illinois steps per root.
    L .. M :
        As :func:`dsm_receptance`.

    Returns
    -------
    roots : ndarray, shape (n_roots,) [rad/s]
    failed : int
        The first root whose Illinois bracket stayed wider than ``rtol`` after ``max_iter``
        steps, -1 if none.
    width : float
        That bracket's relative width (0 if none).
    """
    nf = K_static.shape[0]
    Kk = np.empty((nf, nf))
    work = np.empty((nf, nf))
    lo, hi = np.empty(n_roots), np.empty(n_roots)
    J_lo, J_hi = np.empty(n_roots, np.int64), np.empty(n_roots, np.int64)
    J0_lo, J0_hi = np.empty(n_roots, np.int64), np.empty(n_roots, np.int64)
    d_lo, d_hi = np.empty(n_roots), np.empty(n_roots)
    i = 1
    for r in range(n_roots):                       # the first grid point with J >= r + 1
        while J_grid[i] < r + 1:
            i += 1
        lo[r], hi[r] = grid[i - 1], grid[i]
        J_lo[r], J_hi[r] = J_grid[i - 1], J_grid[i]
        J0_lo[r], J0_hi[r] = J0_grid[i - 1], J0_grid[i]
        d_lo[r], d_hi[r] = det_grid[i - 1], det_grid[i]
    roots = np.empty(n_roots)
    for r in range(n_roots):
        while True:
            isolated = J_lo[r] == r and J_hi[r] == r + 1 and J0_lo[r] == J0_hi[r]
            if isolated or hi[r] - lo[r] <= rtol * hi[r]:
                break
            mid = 0.5 * (lo[r] + hi[r])
            J, J0, d = _count_one(mid, L, m, T, lam2, alpha, K0, chordwise, series,
                                  assembly, K_static, M, Kk, work)
            for s in range(r, n_roots):
                if lo[s] >= mid:                  # the brackets above lie above mid
                    break
                if mid < hi[s]:
                    if J >= s + 1:
                        hi[s], J_hi[s], J0_hi[s], d_hi[s] = mid, J, J0, d
                    else:
                        lo[s], J_lo[s], J0_lo[s], d_lo[s] = mid, J, J0, d
        if not isolated:
            roots[r] = 0.5 * (lo[r] + hi[r])
            continue
        sign = 1.0 if (J_lo[r] - J0_lo[r]) % 2 == 0 else -1.0
        a_, b_ = lo[r], hi[r]
        # the end values where the counts gave them (the same elimination), else computed
        fl = sign * (d_lo[r] if np.isfinite(d_lo[r]) else _det_one(
            a_, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk, work))
        fh = sign * (d_hi[r] if np.isfinite(d_hi[r]) else _det_one(
            b_, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk, work))
        side, stall = 0, 0
        last = np.inf
        for _ in range(max_iter):
            if not b_ - a_ > rtol * b_:
                break
            width = b_ - a_
            x = (a_ * fh - b_ * fl) / (fh - fl)
            if not np.isfinite(x) or x <= a_ or x >= b_ or stall >= 3:
                x = 0.5 * (a_ + b_)
            near = abs(x - last) <= _NEAR * rtol * b_   # the iterates have settled
            last = x
            fx = sign * _det_one(x, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                                 K_static, M, Kk, work)
            if near:
                step = (1.0 if b_ - x > x - a_ else -1.0) * 0.45 * rtol * b_
                x2 = min(max(x + step, np.nextafter(a_, b_)), np.nextafter(b_, a_))
                fx2 = sign * _det_one(x2, L, m, T, lam2, alpha, K0, chordwise, series,
                                      assembly, K_static, M, Kk, work)
            else:
                x2, fx2 = x, fx
            a, b = min(x, x2), max(x, x2)
            fa, fb = (fx, fx2) if x <= x2 else (fx2, fx)
            up = fb >= 0                            # both points below the root: lo moves
            dn = fa < 0                             # both above: hi moves
            if not near and not up and not dn:      # g not finite at x: bisect next
                stall = 3
                continue
            g_up, g_dn = 1.0 - fb / fl, 1.0 - fa / fh
            if not (g_up > 0 and g_up < 1):
                g_up = 0.5
            if not (g_dn > 0 and g_dn < 1):
                g_dn = 0.5
            if up and side == 1:                  # Anderson-Bjorck scaling
                fh = g_up * fh
            if dn and side == -1:
                fl = g_dn * fl
            if up:
                a_, fl = b, fb
            if dn:
                b_, fh = a, fa
            if not up and not dn:                 # the pair brackets the root
                a_, fl, b_, fh = a, fa, b, fb
            side = 1 if up else (-1 if dn else 0)
            if fa == 0 or fb == 0:
                a_ = b_ = a if fa == 0 else b
            stall = 0 if b_ - a_ <= 0.5 * width else stall + 1
        if b_ - a_ > rtol * b_:
            return roots, r, (b_ - a_) / b_
        roots[r] = 0.5 * (a_ + b_)
    return roots, -1, 0.0
