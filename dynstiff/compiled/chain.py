"""Compiled (numba) kernels of the lumped robot's time stepping (theory.md §7.1, §7.3,
§14.4, §14.5): the spring, weight and axial-dashpot forces of every chain in one pass over
the segments (with the extreme tension and strain the step checks), the ledger
energies, and whole runs with their records, ledger and checks: explicit (velocity Verlet)
and implicit (Newmark, Newton with LU factors made by scipy; theory.md §14.6).

Imported only by :mod:`dynstiff.timedomain.dynamics` when numba is installed (``pip
install "dynstiff[fast]"``); without it the numpy path (``LumpedMassModel.residual_unchecked``
and the stacked axial dashpot, the stepwise loop of :mod:`dynstiff.timedomain.simulation`) is
used, and stays the reference the kernels are tested against. Compiled on first use and
cached on disk. The stepping functions write into buffers they are given: a step allocates
nothing.
"""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["energies", "robot_chain_forces"]

JIT = {"cache": True, "error_model": "numpy", "nogil": True}


@numba.njit(**JIT)
def chain_pass(anchors, X, B, r, vn, twist, seg, l0, EA, c_ax, weight, inner, dash, W, Wd):
    """Forces of n chains of seg[i] = N_i segments, in place.

    Node s of chain i is the anchor (s = 0), the attachment B_i (s = N_i) or the interior
    node X[o_i + 3 (s - 1):...] between, o_i = 3 sum_{j < i} (N_j - 1). ``inner`` and
    ``dash`` (3 sum (N_i - 1),) receive the spring + weight and the axial-dashpot forces on
    the interior nodes [N]; the forces of the last segments on the platform,
    -T_N n_N + weight / 2 and the dashpot's, and their moments r_i x f about P are added to
    ``W`` and ``Wd`` (6,). The dashpot c_ax d(eps)/dt acts on taut segments only; B_i moves
    with the twist (v_P, w).
    Returns the largest and smallest tension [N] and the largest strain l / l0 - 1 [-].
    """
    n = anchors.shape[0]
    t_max, t_min, strain_max = 0.0, np.inf, -np.inf
    o = 0
    for i in range(n):
        damped = c_ax[i] > 0.0
        N = seg[i]
        vb0 = vb1 = vb2 = 0.0
        if damped:
            vb0 = twist[0] + twist[4] * r[i, 2] - twist[5] * r[i, 1]
            vb1 = twist[1] + twist[5] * r[i, 0] - twist[3] * r[i, 2]
            vb2 = twist[2] + twist[3] * r[i, 1] - twist[4] * r[i, 0]
        p0 = p1 = p2 = q0 = q1 = q2 = 0.0             # force of the previous segment
        for s in range(N):
            if s == 0:
                a0, a1, a2 = anchors[i, 0], anchors[i, 1], anchors[i, 2]
                va0 = va1 = va2 = 0.0
            else:
                j = o + 3 * (s - 1)
                a0, a1, a2 = X[j], X[j + 1], X[j + 2]
                va0, va1, va2 = vn[j], vn[j + 1], vn[j + 2]
            if s == N - 1:
                b0, b1, b2 = B[i, 0], B[i, 1], B[i, 2]
                wb0, wb1, wb2 = vb0, vb1, vb2
            else:
                j = o + 3 * s
                b0, b1, b2 = X[j], X[j + 1], X[j + 2]
                wb0, wb1, wb2 = vn[j], vn[j + 1], vn[j + 2]
            d0, d1, d2 = b0 - a0, b1 - a1, b2 - a2
            length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            u0, u1, u2 = d0 / length, d1 / length, d2 / length
            T = EA[i] * max(length / l0[i] - 1.0, 0.0)
            t_max, t_min = max(t_max, T), min(t_min, T)
            strain_max = max(strain_max, length / l0[i] - 1.0)
            f0, f1, f2 = T * u0, T * u1, T * u2
            g0 = g1 = g2 = 0.0
            if damped:
                rate = (u0 * (wb0 - va0) + u1 * (wb1 - va1) + u2 * (wb2 - va2)) / l0[i]
                c = c_ax[i] * rate if length > l0[i] else 0.0
                g0, g1, g2 = c * u0, c * u1, c * u2
            if s >= 1:
                j = o + 3 * (s - 1)
                inner[j] = f0 - p0 + weight[i, 0]
                inner[j + 1] = f1 - p1 + weight[i, 1]
                inner[j + 2] = f2 - p2 + weight[i, 2]
                dash[j], dash[j + 1], dash[j + 2] = g0 - q0, g1 - q1, g2 - q2
            p0, p1, p2, q0, q1, q2 = f0, f1, f2, g0, g1, g2
        o += 3 * (N - 1)
        for src, dst in (((-p0 + 0.5 * weight[i, 0], -p1 + 0.5 * weight[i, 1],
                           -p2 + 0.5 * weight[i, 2]), W), ((-q0, -q1, -q2), Wd)):
            e0, e1, e2 = src
            dst[0] += e0
            dst[1] += e1
            dst[2] += e2
            dst[3] += r[i, 1] * e2 - r[i, 2] * e1
            dst[4] += r[i, 2] * e0 - r[i, 0] * e2
            dst[5] += r[i, 0] * e1 - r[i, 1] * e0
    return t_max, t_min, strain_max


@numba.njit(**JIT)
def weight_wrench(platform_weight, rG, W, Wd) -> None:
    """W = (m_p g, rG x m_p g), Wd = 0: the start of the wrench sums."""
    for k in range(3):
        W[k] = platform_weight[k]
    W[3] = rG[1] * platform_weight[2] - rG[2] * platform_weight[1]
    W[4] = rG[2] * platform_weight[0] - rG[0] * platform_weight[2]
    W[5] = rG[0] * platform_weight[1] - rG[1] * platform_weight[0]
    Wd[:] = 0.0


@numba.njit(**JIT)
def robot_chain_forces(anchors, X, B, r, v_nodes, twist, seg, l0, EA, c_ax, weight,
                       platform_weight, rG):
    """The chains' generalised forces on a robot (interior nodes flat, chain after chain),
    with the platform's weight (:func:`chain_pass` with fresh outputs).

    Parameters
    ----------
    anchors, B, r : ndarray, shape (n, 3)
        Anchors, attachment points and lever arms r_i = R_p b_i [m].
    X, v_nodes : ndarray, shape (3 sum (N_i - 1),)
        Interior node positions [m] and velocities [m/s], chain after chain.
    twist : ndarray, shape (6,)
        Platform twist (v_P [m/s], w [rad/s]).
    seg : ndarray of int, shape (n,)
        Segments N_i of every chain.
    l0, EA, c_ax : ndarray, shape (n,)
        Unstretched segment length [m], axial stiffness [N], axial dashpot [N s].
    weight : ndarray, shape (n, 3)
        Weight of one node, m l0 g [N].
    platform_weight : ndarray, shape (3,)
        m_p g [N].
    rG : ndarray, shape (3,)
        R_p c_G [m].

    Returns
    -------
    inner, dash_inner : ndarray, shape (3 sum (N_i - 1),)
        Residual (spring + weight) and axial-dashpot forces on the interior nodes [N].
    W, W_dash : ndarray, shape (6,)
        Wrench about P [N, N m] of the chains and the platform weight, and of the dashpots.
    t_max, t_min, strain_max : float
        Largest and smallest tension [N], largest strain [-].
    """
    inner, dash = np.empty(X.size), np.empty(X.size)
    W, Wd = np.empty(6), np.empty(6)
    weight_wrench(platform_weight, rG, W, Wd)
    t_max, t_min, strain = chain_pass(anchors, X, B, r, v_nodes, twist, seg, l0, EA, c_ax,
                                       weight, inner, dash, W, Wd)
    return inner, dash, W, Wd, t_max, t_min, strain


@numba.njit(**JIT)
def quat(v0, v1, v2):
    """Unit quaternion (x, y, z, w) of a rotation vector (as platform.rotvec_to_quaternion)."""
    theta = np.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    if theta <= 1e-3:
        t2 = theta * theta
        scale = 0.5 - t2 / 48 + t2 * t2 / 3840
    else:
        scale = np.sin(theta / 2) / theta
    return scale * v0, scale * v1, scale * v2, np.cos(theta / 2)


@numba.njit(**JIT)
def compose(d0, d1, d2, rot) -> None:
    """rot <- the rotation vector of exp(d) R(rot) (as Pose.moved), in place."""
    p0, p1, p2, p3 = quat(d0, d1, d2)
    q0, q1, q2, q3 = quat(rot[0], rot[1], rot[2])
    x = p3 * q0 + q3 * p0 + (p1 * q2 - p2 * q1)
    y = p3 * q1 + q3 * p1 + (p2 * q0 - p0 * q2)
    z = p3 * q2 + q3 * p2 + (p0 * q1 - p1 * q0)
    w = p3 * q3 - (p0 * q0 + p1 * q1 + p2 * q2)
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    n = np.sqrt(x * x + y * y + z * z)
    theta = 2 * np.arctan2(n, w)
    if theta <= 1e-3:
        t2 = theta * theta
        scale = 2 + t2 / 12 + 7 * t2 * t2 / 2880
    else:
        scale = theta / np.sin(theta / 2)
    rot[0], rot[1], rot[2] = scale * x, scale * y, scale * z


@numba.njit(**JIT)
def platform(rot, attachments, half, mass, com, inertia, R, r, M, rG, first) -> None:
    """Rotation-dependent frame quantities (as time_dynamics.Frame), in place: R_p (3, 3),
    lever arms r (n, 3), the 6x6 mass about P of the body and the half node masses ``half``
    at B_i (M6), rG = R_p c_G and the first moment m_p rG + sum half_i r_i."""
    x, y, z, w = quat(rot[0], rot[1], rot[2])
    R[0, 0], R[0, 1], R[0, 2] = w * w + x * x - y * y - z * z, 2 * (x * y - z * w), \
        2 * (x * z + y * w)
    R[1, 0], R[1, 1], R[1, 2] = 2 * (x * y + z * w), w * w - x * x + y * y - z * z, \
        2 * (y * z - x * w)
    R[2, 0], R[2, 1], R[2, 2] = 2 * (x * z - y * w), 2 * (y * z + x * w), \
        w * w - x * x - y * y + z * z
    n = attachments.shape[0]
    h = np.zeros(3)                                # sum half_i r_i
    hs = rr = 0.0
    outer = np.zeros((3, 3))
    for i in range(n):
        for j in range(3):
            r[i, j] = R[j, 0] * attachments[i, 0] + R[j, 1] * attachments[i, 1] \
                + R[j, 2] * attachments[i, 2]
        hs += half[i]
        rr += half[i] * (r[i, 0] ** 2 + r[i, 1] ** 2 + r[i, 2] ** 2)
        for j in range(3):
            h[j] += half[i] * r[i, j]
            for k in range(3):
                outer[j, k] += half[i] * r[i, j] * r[i, k]
    for j in range(3):
        rG[j] = R[j, 0] * com[0] + R[j, 1] * com[1] + R[j, 2] * com[2]
        first[j] = mass * rG[j] + h[j]
    g2 = rG[0] ** 2 + rG[1] ** 2 + rG[2] ** 2
    M[:, :] = 0.0
    for j in range(3):
        M[j, j] = mass + hs
        for k in range(3):
            RI = 0.0
            for a in range(3):
                for b in range(3):
                    RI += R[j, a] * inertia[a, b] * R[k, b]
            # -m [rG]x [rG]x = m (|rG|^2 I - rG rG^T); - sum h [r]x [r]x likewise
            M[3 + j, 3 + k] = RI + mass * ((g2 if j == k else 0.0) - rG[j] * rG[k]) \
                + (rr if j == k else 0.0) - outer[j, k]
    # [S]x = skew(m rG + h): M[:3, 3:] = -[S]x, M[3:, :3] = [S]x
    s0, s1, s2 = mass * rG[0] + h[0], mass * rG[1] + h[1], mass * rG[2] + h[2]
    M[0, 4], M[0, 5], M[1, 3], M[1, 5], M[2, 3], M[2, 4] = s2, -s1, -s2, s0, s1, -s0
    M[4, 0], M[5, 0], M[3, 1], M[5, 1], M[3, 2], M[4, 2] = s2, -s1, -s2, s0, s1, -s0


@numba.njit(**JIT)
def energies(pos, rot, X, vp, vn, anchors, attachments, seg, l0, EA, node_mass, g, mass, com,
             inertia, mu):
    """Ledger quantities of a state (as time_dynamics.potential_energy and
    Dynamics.kinetic): elastic, gravity and kinetic energy [J], end and anchor tensions (n,)
    [N], largest strain [-], and the first slack segment (cable, segment) or (-1, -1)."""
    n = anchors.shape[0]
    R, r, M6 = np.empty((3, 3)), np.empty((n, 3)), np.empty((6, 6))
    rG, first = np.empty(3), np.empty(3)
    platform(rot, attachments, 0.5 * node_mass, mass, com, inertia, R, r, M6, rG, first)
    elastic, strain = 0.0, -np.inf
    gravity = mass * g * (pos[2] + rG[2])
    t_end, t_anchor = np.empty(n), np.empty(n)
    slack_cable, slack_segment = -1, -1
    o = 0
    for i in range(n):
        zsum = 0.0
        N = seg[i]
        for s in range(N):
            if s == 0:
                a0, a1, a2 = anchors[i, 0], anchors[i, 1], anchors[i, 2]
            else:
                a0, a1, a2 = X[o + 3 * s - 3], X[o + 3 * s - 2], X[o + 3 * s - 1]
            if s == N - 1:
                b0, b1, b2 = pos[0] + r[i, 0], pos[1] + r[i, 1], pos[2] + r[i, 2]
            else:
                b0, b1, b2 = X[o + 3 * s], X[o + 3 * s + 1], X[o + 3 * s + 2]
                zsum += b2
            d0, d1, d2 = b0 - a0, b1 - a1, b2 - a2
            length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            stretch = max(length - l0[i], 0.0)
            elastic += 0.5 * EA[i] / l0[i] * stretch * stretch
            T = EA[i] * max(length / l0[i] - 1.0, 0.0)
            if s == 0:
                t_anchor[i] = T
            if s == N - 1:
                t_end[i] = T
            if T <= 0.0 and slack_cable < 0:
                slack_cable, slack_segment = i, s
            strain = max(strain, length / l0[i] - 1.0)
        gravity += node_mass[i] * g * (zsum + 0.5 * (pos[2] + r[i, 2]))
        o += 3 * (N - 1)
    kinetic = 0.0
    for j in range(6):
        for k in range(6):
            kinetic += vp[j] * M6[j, k] * vp[k]
    for j in range(vn.size):
        kinetic += vn[j] * mu[j] * vn[j]
    return (elastic, gravity, 0.5 * kinetic, t_end, t_anchor, strain, slack_cable,
            slack_segment)


@numba.njit(**JIT)
def solve_free(M, F, free, A, b, out) -> None:
    """out <- M_ff^-1 F_f on the free DOFs (0 on held ones): Gaussian elimination with
    partial pivoting of the (n_free, n_free) block copied into the scratch ``A``, ``b``."""
    n = 0
    for k in range(6):
        if free[k]:
            m = 0
            for j in range(6):
                if free[j]:
                    A[n, m] = M[k, j]
                    m += 1
            b[n] = F[k]
            n += 1
    for c in range(n):
        p = c
        for i in range(c + 1, n):
            if abs(A[i, c]) > abs(A[p, c]):
                p = i
        if p != c:
            for j in range(n):
                A[c, j], A[p, j] = A[p, j], A[c, j]
            b[c], b[p] = b[p], b[c]
        for i in range(c + 1, n):
            f = A[i, c] / A[c, c]
            for j in range(c, n):
                A[i, j] -= f * A[c, j]
            b[i] -= f * b[c]
    for c in range(n - 1, -1, -1):
        s = b[c]
        for j in range(c + 1, n):
            s -= A[c, j] * b[j]
        b[c] = s / A[c, c]
    n = 0
    for k in range(6):
        out[k] = 0.0
        if free[k]:
            out[k] = b[n]
            n += 1


@numba.njit(**JIT)
def cross_add(a0, a1, a2, b0, b1, b2, scale, out, o) -> None:
    """out[o:o + 3] += scale (a x b)."""
    out[o] += scale * (a1 * b2 - a2 * b1)
    out[o + 1] += scale * (a2 * b0 - a0 * b2)
    out[o + 2] += scale * (a0 * b1 - a1 * b0)


@numba.njit(**JIT)
def lu_solve(lu, b, y, x) -> None:
    """x <- A^-1 b from the SuperLU factors Pr A Pc = L U (scipy's ``splu``): ``lu`` =
    (L, U as CSR indptr, indices, data, then perm_r, perm_c); ``y`` scratch (n,)."""
    Lp, Li, Lx, Up, Ui, Ux, perm_r, perm_c = lu
    n = b.size
    for i in range(n):
        y[perm_r[i]] = b[i]
    for i in range(n):
        s, diag = y[i], 1.0
        for q in range(Lp[i], Lp[i + 1]):
            j = Li[q]
            if j < i:
                s -= Lx[q] * y[j]
            elif j == i:
                diag = Lx[q]
        y[i] = s / diag
    for i in range(n - 1, -1, -1):
        s, diag = y[i], 1.0
        for q in range(Up[i], Up[i + 1]):
            j = Ui[q]
            if j > i:
                s -= Ux[q] * y[j]
            elif j == i:
                diag = Ux[q]
        y[i] = s / diag
    for i in range(n):
        x[i] = y[perm_c[i]]


