"""Compiled (numba) Newton on (H, V0, L0) of many elastic catenaries with prescribed end
tensions: the kernel of :func:`dynstiff.cable.catenary_batch.taut_catenaries` (docs/theory.md
§13.1, §13.6), one cable at a time in a compiled loop instead of a handful of array
operations per iteration.

Imported only when numba is installed (``pip install "dynstiff[fast]"``); the numpy Newton of
:mod:`dynstiff.cable.catenary_batch` stays the reference it is tested against. Same equations,
same divided differences (:func:`dynstiff.cable.catenary.divided_differences`), same step limits,
stopping rule and taut-branch test; the 3 x 3 Newton step is an LU solve with partial
pivoting written out (LAPACK's in the numpy path), so the two agree to round-off. A cable
whose Newton matrix is exactly singular stops alone (the numpy path stops every cable).
Compiled on first use and cached on disk (``cache=True``).
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["newton_taut"]

_JIT = {"cache": True, "error_model": "numpy", "nogil": True}


@numba.njit(**_JIT)
def _divided(a, b, delta):
    """Scalar :func:`dynstiff.cable.catenary.divided_differences` (same branches and formulas)."""
    sa = math.hypot(1.0, a)
    sb = math.hypot(1.0, b)
    if delta == 0.0:
        return 1.0 / sa, 1.0 / sa**3, -a / sa**3, a / sa
    if a * b > 0:
        iod = (a + b) / (b * sa + a * sb)
        inner = delta * iod
    else:
        inner = b * sa - a * sb
        iod = inner / delta
    return (math.asinh(inner) / delta, iod / (sa * sb), -(a + b) / ((sa + sb) * sa * sb),
            (a + b) / (sa + sb))


@numba.njit(**_JIT)
def _equations(H, V0, L0, EA, w0, J):
    """End offsets x, z [m], end tension T [N]; the Jacobian into J (3, 3)."""
    W = w0 * L0
    Vb = V0 + W
    d_asinh, d_f, d_g, d_sqrt = _divided(V0 / H, Vb / H, W / H)
    x = L0 * (H / EA + d_asinh)
    z = L0 * ((V0 + 0.5 * W) / EA + d_sqrt)
    T = np.hypot(H, Vb)
    J[0, 0] = L0 / EA + (L0 / H) * (d_asinh - d_f)
    J[0, 1] = (L0 / H) * d_g
    J[1, 0] = J[0, 1]
    J[1, 1] = L0 / EA + (L0 / H) * d_f
    J[0, 2] = H / EA + H / T
    J[1, 2] = Vb / EA + Vb / T
    J[2, 0] = H / T
    J[2, 1] = Vb / T
    J[2, 2] = w0 * Vb / T
    return x, z, T


@numba.njit(**_JIT)
def _solve3(J, r, A, s):
    """s = -J^-1 r by LU with partial pivoting (A scratch); False when a pivot is 0."""
    A[:, :] = J
    for i in range(3):
        s[i] = -r[i]
    for k in range(3):
        p = k
        for i in range(k + 1, 3):
            if abs(A[i, k]) > abs(A[p, k]):
                p = i
        if A[p, k] == 0.0:
            return False
        if p != k:
            for j in range(3):
                A[k, j], A[p, j] = A[p, j], A[k, j]
            s[k], s[p] = s[p], s[k]
        for i in range(k + 1, 3):
            f = A[i, k] / A[k, k]
            for j in range(k + 1, 3):
                A[i, j] -= f * A[k, j]
            s[i] -= f * s[k]
    for k in range(2, -1, -1):
        v = s[k]
        for j in range(k + 1, 3):
            v -= A[k, j] * s[j]
        s[k] = v / A[k, k]
    return True


@numba.njit(**_JIT)
def _residual(x, z, T, lh, h, t, scale, r):
    """r = (x - lh, z - h, T - t) and the largest |r_i| / scale_i (NaN if any is NaN)."""
    r[0], r[1], r[2] = x - lh, z - h, T - t
    res = 0.0
    for i in range(3):
        q = abs(r[i]) / scale[i]
        if math.isnan(q):
            return q
        res = max(res, q)
    return res


@numba.njit(**_JIT)
def newton_taut(lh, h, L, t, EA, w0, H, V0, L0, rtol, max_iter: int):
    """Newton on (H, V0, L0) of every cable, as ``catenary_batch._newton``.

    Parameters: arrays of shape (n,) [m, m, m, N, N, N/m, N, N, m] (horizontal and vertical
    chord, chord length, end tension, EA, weight per length; the start), ``rtol`` the
    relative residual at convergence, ``max_iter`` the iterations.

    Returns H, V0, L0, ok (converged to the taut branch), residual: arrays of shape (n,).
    """
    n = lh.size
    H, V0, L0 = H.copy(), V0.copy(), L0.copy()
    ok = np.zeros(n, dtype=np.bool_)
    out_res = np.empty(n)
    J = np.empty((3, 3))
    A = np.empty((3, 3))
    r = np.empty(3)
    s = np.empty(3)
    scale = np.empty(3)
    for c in range(n):
        scale[0], scale[1], scale[2] = lh[c], max(L[c], L0[c]), t[c]
        h_, v_, l_ = H[c], V0[c], L0[c]
        done = False
        for _ in range(max_iter):
            x, z, T = _equations(h_, v_, l_, EA[c], w0[c], J)
            res = _residual(x, z, T, lh[c], h[c], t[c], scale, r)
            if res <= rtol or not np.isfinite(res):
                done = True
                break
            if not _solve3(J, r, A, s):
                done = True
                break
            # keep H and L0 positive: at most a tenfold reduction per step
            v = h_ + s[0]
            h_ = v if not v < 0.1 * h_ else 0.1 * h_
            v_ = v_ + s[1]
            v = l_ + s[2]
            l_ = v if not v < 0.1 * l_ else 0.1 * l_
        if not done:
            x, z, T = _equations(h_, v_, l_, EA[c], w0[c], J)
            res = _residual(x, z, T, lh[c], h[c], t[c], scale, r)
        # taut branch: dT/dL0 at fixed ends, T_L - [T_H, T_V] F^-1 [x_L, z_L], is negative
        det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
        y0 = (J[1, 1] * J[0, 2] - J[0, 1] * J[1, 2]) / det
        y1 = (J[0, 0] * J[1, 2] - J[1, 0] * J[0, 2]) / det
        dT_dL0 = J[2, 2] - J[2, 0] * y0 - J[2, 1] * y1
        ok[c] = (res <= rtol and np.isfinite(res) and dT_dL0 < 0 and h_ > 0 and l_ > 0)
        H[c], V0[c], L0[c], out_res[c] = h_, v_, l_, res
    return H, V0, L0, ok, out_res
