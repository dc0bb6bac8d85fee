"""Compiled (numba) kernels of the "dsm" rung: the robot's K(omega) fused with the small real
solve C K^-1 B of an FRF (theory.md §4, §14.1), and with the eigenvalues and cable count of
a Wittrick-Williams count (theory.md §5, §14.2), one frequency at a time.

Imported only when an FRF or an eigen search asks for it and numba is installed (``pip
install "dynstiff[fast]"``); :mod:`dynstiff.frf` and :mod:`dynstiff.analyses.eigen` fall back to the
numpy paths (K(omega) batched over frequency, then ``np.linalg``), which stay the reference
the kernels are tested against. Compiled on first use and cached on disk (``cache=True``).

The cable entries are those of :func:`dynstiff.cable.dsm.local_entries` for an undamped
cable at real omega (same formulas, same series branch for |psi| < 1); the assembly is
``cable_coefficients(omega) @ assembly_map`` of :class:`dynstiff.models.dsm.FrequencyModel`.
"""

import numba
import numpy as np

__all__ = ["dsm_receptance", "dsm_count", "dsm_search", "real_receptance"]

_JIT = {"cache": True, "error_model": "numpy", "nogil": True}
#: Frequencies per block of the fused kernel (its coefficients stay in cache).
_BLOCK = 256
#: The search's Illinois step adds a second point 0.45 rtol hi beyond its iterate (to close
#: the bracket at once) when the iterate moved less than this many rtol hi since the last.
_NEAR = 64.0


@numba.njit(**_JIT)
def _horner(coef, x):
    y = 0.0
    for a in coef:
        y = y * x + a
    return y


@numba.njit(**_JIT)
def _lu_solve_into(K, B, C, c_identity, out, work):
    """out = C K^-1 B for one real K (nf, nf), by LU with partial pivoting (K overwritten,
    work (nf, n_in) scratch; C skipped when ``c_identity``); returns False where a pivot is
    exactly 0 (K singular)."""
    nf = K.shape[0]
    n_in = B.shape[1]
    work[:, :] = B
    for k in range(nf):
        p = k
        big = abs(K[k, k])
        for i in range(k + 1, nf):
            if abs(K[i, k]) > big:
                big = abs(K[i, k])
                p = i
        if big == 0.0 or not np.isfinite(big):
            return False
        if p != k:
            for j in range(nf):
                K[k, j], K[p, j] = K[p, j], K[k, j]
            for j in range(n_in):
                work[k, j], work[p, j] = work[p, j], work[k, j]
        inv = 1.0 / K[k, k]
        for i in range(k + 1, nf):
            f = K[i, k] * inv
            for j in range(k + 1, nf):
                K[i, j] -= f * K[k, j]
            for j in range(n_in):
                work[i, j] -= f * work[k, j]
    for k in range(nf - 1, -1, -1):
        for i in range(k + 1, nf):
            f = K[k, i]
            for j in range(n_in):
                work[k, j] -= f * work[i, j]
        inv = 1.0 / K[k, k]
        for j in range(n_in):
            work[k, j] *= inv
    if c_identity:
        out[:, :] = work
        return True
    for o in range(C.shape[0]):
        for j in range(n_in):
            s = 0.0
            for i in range(nf):
                s += C[o, i] * work[i, j]
            out[o, j] = s
    return True


@numba.njit(**_JIT)
def real_receptance(K, B, C):
    """C K^-1 B for a real stack K (n, nf, nf), B (nf, n_in), C (n_out, nf).

    Returns
    -------
    H : ndarray, shape (n, n_out, n_in), real
    singular : ndarray of bool, shape (n,)
        Where K is exactly singular (H left 0 there); NaN where K is not finite.
    """
    n, nf = K.shape[0], K.shape[1]
    c_identity = C.shape[0] == nf and (C == np.eye(nf)).all()
    H = np.zeros((n, C.shape[0], B.shape[1]))
    singular = np.zeros(n, dtype=np.bool_)
    Kk = np.empty((nf, nf))
    work = np.empty((nf, B.shape[1]))
    for k in range(n):
        Kk[:, :] = K[k]
        if not np.isfinite(Kk).all():          # exactly on a cable pole: as numpy, NaN
            H[k] = np.nan
            continue
        singular[k] = not _lu_solve_into(Kk, B, C, c_identity, H[k], work)
    return H, singular


@numba.njit(**_JIT)
def dsm_receptance(omega, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static,
                   M, B, C):
    """Receptance C K(omega)^-1 B of the "dsm" rung with undamped cables, K(omega) built and
    solved one frequency at a time (theory.md §3.5, §4).

    Parameters
    ----------
    omega : ndarray, shape (n,)
        [rad/s], >= 0, within the closed form's range (checked by the caller).
    L, m, T, lam2, alpha, K0 : ndarray, shape (n_cables,)
        Chord parameters (real): chord length [m], mass per chord length [kg/m], tension
        [N], Irvine lambda^2 [-], end slope [-], EA / L_e [N/m].
    chordwise : bool
        Consistent chordwise mass -omega^2 m L / 3 on k_uu (theory.md §3.6).
    series : tuple (radius, E_coef, P_coef)
        ``cable_dsm.PSI_SERIES``.
    assembly : ndarray, shape (4 n_cables, nf (nf + 1) / 2)
        :func:`dynstiff.models.dsm_compiled.symmetric_assembly` of ``FrequencyModel.assembly_map``.
    K_static, M : ndarray, shape (nf, nf)
        Geometric stiffness and platform mass on the free DOFs.
    B, C : ndarray, shape (nf, n_in), (n_out, nf)

    Returns
    -------
    H : ndarray, shape (n, n_out, n_in), complex (real values)
    kmax : ndarray, shape (n,)
        max |K_ij(omega)| (to find the frequencies near a cable pole).
    singular : ndarray of bool, shape (n,)
        Where K(omega) is exactly singular (H left 0 there). Where K is not finite (exactly
        on a cable pole) H is NaN and kmax inf.
    """
    n, nf = omega.size, K_static.shape[0]
    c_identity = C.shape[0] == nf and (C == np.eye(nf)).all()
    H = np.zeros((n, C.shape[0], B.shape[1]), dtype=np.complex128)
    Hk = np.empty((C.shape[0], B.shape[1]))
    kmax = np.empty(n)
    singular = np.zeros(n, dtype=np.bool_)
    Kk = np.empty((nf, nf))
    work = np.empty((nf, B.shape[1]))
    J0 = np.empty(_BLOCK, dtype=np.int64)
    for start in range(0, n, _BLOCK):
        w = omega[start:start + _BLOCK]
        Kb = _assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, J0,
                              False)
        for b in range(w.size):
            k = start + b
            big = _unpack(Kb[b], K_static, M, w[b], Kk)
            if not np.isfinite(big):                   # exactly on a cable pole
                kmax[k] = np.inf
                H[k] = np.nan
                continue
            kmax[k] = big
            singular[k] = not _lu_solve_into(Kk, B, C, c_identity, Hk, work)
            for o in range(Hk.shape[0]):
                for i in range(Hk.shape[1]):
                    H[k, o, i] = Hk[o, i]
    return H, kmax, singular


@numba.njit(**_JIT)
def dsm_count(omega, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M):
    """Ascending eigenvalues of K(omega) and the cable count J0(omega) of the "dsm" rung with
    undamped cables, from one evaluation of the cable kernels per frequency (theory.md §5,
    §14.2). Arguments as :func:`dsm_receptance`.

    Returns
    -------
    ev : ndarray, shape (n, nf)
        Eigenvalues of K(omega) [N/m ...], ascending; NaN where K is not finite.
    J0 : ndarray of int, shape (n,)
        Clamped-clamped cable modes strictly below omega, summed over the cables (as
        :func:`dynstiff.cable.psi.mode_count_nondimensional`).
    """
    n, nf = omega.size, K_static.shape[0]
    ev = np.empty((n, nf))
    J0 = np.empty(n, dtype=np.int64)
    Kk = np.empty((nf, nf))
    for start in range(0, n, _BLOCK):
        w = omega[start:start + _BLOCK]
        Kb = _assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                              J0[start:start + _BLOCK], True)
        for b in range(w.size):
            if np.isfinite(_unpack(Kb[b], K_static, M, w[b], Kk)):
                ev[start + b] = np.linalg.eigvalsh(Kk)
            else:
                ev[start + b] = np.nan
    return ev, J0


@numba.njit(**_JIT)
def _count_multiples_below(x, step):
    """#{n >= 1 : n step < x}, as :func:`dynstiff.cable.psi._count_multiples_below`."""
    n = max(int(np.ceil(x / step)) - 1, 0)
    if n >= 1 and n * step >= x:
        n -= 1
    if (n + 1) * step < x:
        n += 1
    return n


@numba.njit(**_JIT)
def _unpack(Ku, K_static, M, w, Kk):
    """Kk = the symmetric K from its upper entries Ku of the cable part, plus K_static -
    w^2 M; returns max |K_ij| (inf if any entry is not finite)."""
    nf = Kk.shape[0]
    w2 = w * w
    big = 0.0
    q = 0
    for i in range(nf):
        for j in range(i, nf):
            v = Ku[q] + K_static[i, j] - w2 * M[i, j]
            if not np.isfinite(v):
                big = np.inf
            big = max(big, abs(v))
            Kk[i, j] = v
            Kk[j, i] = v
            q += 1
    return big


@numba.njit(**_JIT)
def _assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, J0, count):
    """Cable part of K (upper entries, shape (w.size, nf (nf + 1) / 2)) at the frequencies w
    [rad/s] (a block), and with ``count`` the cable count J0 (written into J0[:w.size])."""
    radius, e_coef, p_coef = series
    nc = L.size
    half_L = 0.5 * L
    TL = T / L
    k0_4 = 4.0 * K0
    k0_4a = 4.0 * alpha * K0
    m_l6 = m * L / 6.0 if chordwise else np.zeros(nc)
    coef = np.empty((w.size, 4 * nc))
    for b in range(w.size):
        w2 = w[b] * w[b]
        if count:
            J0[b] = 0
        for j in range(nc):
            psi = half_L[j] * np.sqrt(w2 * m[j] / T[j])     # as ChordParameters.psi
            s, c = np.sin(psi), np.cos(psi)
            cos2 = c * c - s * s
            psi2 = psi * psi
            if psi < radius:
                s_over_psi = 1.0 if psi == 0.0 else s / psi
                E = _horner(e_coef, psi2)
                Pt = _horner(p_coef, psi2)
            else:
                s_over_psi = s / psi
                ip3 = 1.0 / (psi2 * psi)
                E = (psi * c - s) * ip3
                Pt = ((1.0 + psi2) * s * c - psi) * ip3
            den = 4.0 * c - lam2[j] * E
            iden = 1.0 / den
            coef[b, 4 * j] = k0_4[j] * c * iden - 2.0 * w2 * m_l6[j]
            coef[b, 4 * j + 1] = -k0_4a[j] * psi2 * E * iden
            coef[b, 4 * j + 2] = TL[j] * (4.0 * cos2 + lam2[j] * Pt) * iden / s_over_psi
            coef[b, 4 * j + 3] = TL[j] * cos2 / (s_over_psi * c)
            if count:                                 # theory.md §5.2
                Omega = 2.0 * psi
                kb = int(np.floor(psi / np.pi + 0.5))
                n_sym = 0
                if kb > 0:
                    on_branch = c * (1.0 if kb % 2 == 0 else -1.0) > 0
                    n_sym = kb - 1 + (1 if (den * c > 0 and on_branch) else 0)
                J0[b] += (_count_multiples_below(Omega, np.pi)
                          + _count_multiples_below(Omega, 2 * np.pi) + n_sym)
    return coef @ assembly


@numba.njit(**_JIT)
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


@numba.njit(**_JIT)
def _assembled_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk):
    """Kk = K(w) at one frequency w [rad/s]; returns (J0, K finite)."""
    wa = np.empty(1)
    wa[0] = w
    J0 = np.empty(1, dtype=np.int64)
    Kb = _assembled_block(wa, L, m, T, lam2, alpha, K0, chordwise, series, assembly, J0, True)
    return J0[0], np.isfinite(_unpack(Kb[0], K_static, M, w, Kk))


@numba.njit(**_JIT)
def _count_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M, Kk,
               work):
    """(J, J0) of the Wittrick-Williams count at one frequency w [rad/s]: the negative
    eigenvalues of K(w) from the signs of its pivots (:func:`_pivots`), from its eigenvalues
    where the pivots are not sure; none where K is not finite (as :func:`dsm_count` with
    ``numpy.sum(ev < 0)``)."""
    J0, finite = _assembled_one(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                                K_static, M, Kk)
    if not finite:
        return J0, J0
    neg, _, ok = _pivots(Kk, work, False)
    if not ok:
        neg = 0
        for v in np.linalg.eigvalsh(Kk):
            if v < 0.0:
                neg += 1
    return J0 + neg, J0


@numba.njit(**_JIT)
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


@numba.njit(**_JIT)
def dsm_search(grid, J_grid, J0_grid, n_roots, rtol, max_iter, L, m, T, lam2, alpha, K0,
               chordwise, series, assembly, K_static, M):
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
    i = 1
    for r in range(n_roots):                       # the first grid point with J >= r + 1
        while J_grid[i] < r + 1:
            i += 1
        lo[r], hi[r] = grid[i - 1], grid[i]
        J_lo[r], J_hi[r] = J_grid[i - 1], J_grid[i]
        J0_lo[r], J0_hi[r] = J0_grid[i - 1], J0_grid[i]
    roots = np.empty(n_roots)
    for r in range(n_roots):
        while True:
            isolated = J_lo[r] == r and J_hi[r] == r + 1 and J0_lo[r] == J0_hi[r]
            if isolated or hi[r] - lo[r] <= rtol * hi[r]:
                break
            mid = 0.5 * (lo[r] + hi[r])
            J, J0 = _count_one(mid, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                               K_static, M, Kk, work)
            for s in range(r, n_roots):
                if lo[s] >= mid:                  # the brackets above lie above mid
                    break
                if mid < hi[s]:
                    if J >= s + 1:
                        hi[s], J_hi[s], J0_hi[s] = mid, J, J0
                    else:
                        lo[s], J_lo[s], J0_lo[s] = mid, J, J0
        if not isolated:
            roots[r] = 0.5 * (lo[r] + hi[r])
            continue
        sign = 1.0 if (J_lo[r] - J0_lo[r]) % 2 == 0 else -1.0
        a_, b_ = lo[r], hi[r]
        fl = sign * _det_one(a_, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                             K_static, M, Kk, work)
        fh = sign * _det_one(b_, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                             K_static, M, Kk, work)
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


@numba.njit(**_JIT)
def _assembled_block_damped(w, scale, L, m, T, lam2, alpha, K0, chordwise, series, assembly):
    """Cable part of a damped K (upper entries, complex, shape (w.size, nf (nf + 1) / 2)) at
    the real frequencies w [rad/s]: every cable's coefficients of :func:`_assembled_block`,
    complex, evaluated at w / sqrt(scale) and multiplied by ``scale`` = 1 + i eta (a
    hysteretic loss factor eta of every cable stiffness force,
    ``FrequencyModel.cable_coefficients``); the series branch where |psi| < its radius."""
    radius, e_coef, p_coef = series
    nc = L.size
    half_L = 0.5 * L
    TL = T / L
    k0_4 = 4.0 * K0
    k0_4a = 4.0 * alpha * K0
    m_l6 = m * L / 6.0 if chordwise else np.zeros(nc)
    root = np.sqrt(scale)
    coef = np.empty((w.size, 4 * nc), dtype=np.complex128)
    for b in range(w.size):
        wc = w[b] / root
        w2 = wc * wc
        for j in range(nc):
            psi = half_L[j] * np.sqrt(w2 * m[j] / T[j])
            s, c = np.sin(psi), np.cos(psi)
            cos2 = c * c - s * s
            psi2 = psi * psi
            if abs(psi) < radius:
                s_over_psi = 1.0 + 0j if psi == 0.0 else s / psi
                E = _horner_c(e_coef, psi2)
                Pt = _horner_c(p_coef, psi2)
            else:
                s_over_psi = s / psi
                ip3 = 1.0 / (psi2 * psi)
                E = (psi * c - s) * ip3
                Pt = ((1.0 + psi2) * s * c - psi) * ip3
            iden = 1.0 / (4.0 * c - lam2[j] * E)
            coef[b, 4 * j] = scale * (k0_4[j] * c * iden - 2.0 * w2 * m_l6[j])
            coef[b, 4 * j + 1] = -scale * k0_4a[j] * psi2 * E * iden
            coef[b, 4 * j + 2] = scale * TL[j] * (4.0 * cos2 + lam2[j] * Pt) * iden / s_over_psi
            coef[b, 4 * j + 3] = scale * TL[j] * cos2 / (s_over_psi * c)
    return coef @ assembly


@numba.njit(**_JIT)
def _horner_c(coef, x):
    y = 0.0 + 0j
    for a in coef:
        y = y * x + a
    return y


@numba.njit(**_JIT)
def dsm_receptance_damped(omega, scale, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                          K_static, M, B, C):
    """Receptance C K(omega)^-1 B of the "dsm" rung with hysteretic damping (a loss factor
    of the cables, :func:`_assembled_block_damped`, and the platform's modal damping in the
    complex ``K_static``), K(omega) built and solved one frequency at a time in complex
    arithmetic (theory.md §12.2, §14.1). Cables with viscous damping are not handled here.

    Parameters
    ----------
    omega : ndarray, shape (n,)
        [rad/s], >= 0, within the closed form's range (checked by the caller).
    scale : complex
        1 + i eta, eta the model's cable loss factor.
    L, m, T : ndarray, shape (n_cables,)
        Chord length [m], mass per chord length [kg/m], tension [N] (real).
    lam2, alpha, K0 : ndarray of complex, shape (n_cables,)
        Irvine lambda^2, end slope, EA / L_e [N/m] (complex where a cable's own EA is).
    chordwise, series :
        As :func:`dsm_receptance`.
    assembly : ndarray of complex, shape (4 n_cables, nf (nf + 1) / 2)
    K_static : ndarray of complex, shape (nf, nf)
        Geometric stiffness plus the platform's damping on the free DOFs.
    M, B, C :
        Real; as :func:`dsm_receptance`.

    Returns
    -------
    H, kmax, singular :
        As :func:`dsm_receptance`; H complex.
    """
    n, nf = omega.size, K_static.shape[0]
    c_identity = C.shape[0] == nf and (C == np.eye(nf)).all()
    Bc = B.astype(np.complex128)
    Cc = C.astype(np.complex128)
    H = np.zeros((n, C.shape[0], B.shape[1]), dtype=np.complex128)
    Hk = np.empty((C.shape[0], B.shape[1]), dtype=np.complex128)
    kmax = np.empty(n)
    singular = np.zeros(n, dtype=np.bool_)
    Kk = np.empty((nf, nf), dtype=np.complex128)
    work = np.empty((nf, B.shape[1]), dtype=np.complex128)
    for start in range(0, n, _BLOCK):
        w = omega[start:start + _BLOCK]
        Kb = _assembled_block_damped(w, scale, L, m, T, lam2, alpha, K0, chordwise, series,
                                     assembly)
        for b in range(w.size):
            k = start + b
            big = _unpack(Kb[b], K_static, M, w[b], Kk)
            if not np.isfinite(big):                   # exactly on a cable pole
                kmax[k] = np.inf
                H[k] = np.nan
                continue
            kmax[k] = big
            singular[k] = not _lu_solve_into(Kk, Bc, Cc, c_identity, Hk, work)
            for o in range(Hk.shape[0]):
                for i in range(Hk.shape[1]):
                    H[k, o, i] = Hk[o, i]
    return H, kmax, singular
