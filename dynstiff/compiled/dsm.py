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

__all__ = ["BLOCK", "JIT", "assembled_block", "dsm_count", "dsm_receptance",
           "dsm_receptance_damped", "dsm_stiffness", "real_receptance", "unpack_symmetric"]

#: Options of every kernel here (cached on disk, numpy errors, no GIL).
JIT = {"cache": True, "error_model": "numpy", "nogil": True}
#: Frequencies per block of the fused kernel (its coefficients stay in cache).
BLOCK = 256


@numba.njit(**JIT)
def _matmul(a, b):
    """a @ b by loops: the kernels' products are small (a block of frequencies times the
    assembly map), where a threaded BLAS spends more on its threads than on the product
    (30 us instead of 2 us a frequency with two threads on a busy two-core machine)."""
    n, m = a.shape
    p = b.shape[1]
    out = np.zeros((n, p), dtype=a.dtype)        # a and b share their dtype here
    for i in range(n):
        for k in range(m):
            x = a[i, k]
            if x == 0:
                continue
            for j in range(p):
                out[i, j] += x * b[k, j]
    return out


@numba.njit(**JIT)
def _horner(coef, x):
    y = 0.0
    for a in coef:
        y = y * x + a
    return y


@numba.njit(**JIT)
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


@numba.njit(**JIT)
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


@numba.njit(**JIT)
def _solve_block(Kb, w, start, K_static, M, B, C, c_identity, H, kmax, singular, Kk, Hk, work):
    """H[start + b] = C K^-1 B for the block's upper entries Kb (w.size, nf (nf + 1) / 2) at
    the frequencies w [rad/s], with kmax and singular as :func:`dsm_receptance`; Kk, Hk and
    work are scratch of K's dtype (real or complex)."""
    for b in range(w.size):
        k = start + b
        big = unpack_symmetric(Kb[b], K_static, M, w[b], Kk)
        if not np.isfinite(big):                   # exactly on a cable pole
            kmax[k] = np.inf
            H[k] = np.nan
            continue
        kmax[k] = big
        singular[k] = not _lu_solve_into(Kk, B, C, c_identity, Hk, work)
        for o in range(Hk.shape[0]):
            for i in range(Hk.shape[1]):
                H[k, o, i] = Hk[o, i]


@numba.njit(**JIT)
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
    J0 = np.empty(BLOCK, dtype=np.int64)
    for start in range(0, n, BLOCK):
        w = omega[start:start + BLOCK]
        Kb = assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, J0,
                              False)
        _solve_block(Kb, w, start, K_static, M, B, C, c_identity, H, kmax, singular, Kk, Hk,
                     work)
    return H, kmax, singular


@numba.njit(**JIT)
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
    for start in range(0, n, BLOCK):
        w = omega[start:start + BLOCK]
        Kb = assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                              J0[start:start + BLOCK], True)
        for b in range(w.size):
            if np.isfinite(unpack_symmetric(Kb[b], K_static, M, w[b], Kk)):
                ev[start + b] = np.linalg.eigvalsh(Kk)
            else:
                ev[start + b] = np.nan
    return ev, J0


@numba.njit(**JIT)
def _count_multiples_below(x, step):
    """#{n >= 1 : n step < x}, as :func:`dynstiff.cable.psi._count_multiples_below`."""
    n = max(int(np.ceil(x / step)) - 1, 0)
    if n >= 1 and n * step >= x:
        n -= 1
    if (n + 1) * step < x:
        n += 1
    return n


@numba.njit(**JIT)
def unpack_symmetric(Ku, K_static, M, w, Kk):
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


@numba.njit(**JIT)
def assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly, J0, count):
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
    return _matmul(coef, assembly)


@numba.njit(**JIT)
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
                E = _horner(e_coef, psi2)
                Pt = _horner(p_coef, psi2)
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
    return _matmul(coef, assembly)


@numba.njit(**JIT)
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
    for start in range(0, n, BLOCK):
        w = omega[start:start + BLOCK]
        Kb = _assembled_block_damped(w, scale, L, m, T, lam2, alpha, K0, chordwise, series,
                                     assembly)
        _solve_block(Kb, w, start, K_static, M, Bc, Cc, c_identity, H, kmax, singular, Kk, Hk,
                     work)
    return H, kmax, singular


@numba.njit(**JIT)
def dsm_stiffness(omega, L, m, T, lam2, alpha, K0, chordwise, series, assembly, K_static, M):
    """K(omega) of the "dsm" rung with undamped cables and the cable count J0(omega), from
    one evaluation of the cable kernels per frequency (as
    ``FrequencyModel.dynamic_stiffness_and_count``). Arguments as :func:`dsm_receptance`.

    Returns
    -------
    K : ndarray, shape (n, nf, nf)
        Real, symmetric; not finite exactly on a cable pole.
    J0 : ndarray of int, shape (n,)
    """
    n, nf = omega.size, K_static.shape[0]
    K = np.empty((n, nf, nf))
    J0 = np.empty(n, dtype=np.int64)
    for start in range(0, n, BLOCK):
        w = omega[start:start + BLOCK]
        Kb = assembled_block(w, L, m, T, lam2, alpha, K0, chordwise, series, assembly,
                             J0[start:start + BLOCK], True)
        for b in range(w.size):
            unpack_symmetric(Kb[b], K_static, M, w[b], K[start + b])
    return K, J0
