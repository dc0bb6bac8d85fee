"""Compiled (numba) kernel of the lumped chains' forces for the time stepping (theory.md
§7.1, §7.3, §14.4): spring, weight and axial-dashpot forces of every chain of equal N in one
pass over the segments, with the extreme tension and strain the step checks.

Imported only by :mod:`dynstiff.lumped.time_dynamics` when numba is installed (``pip
install "dynstiff[fast]"``); without it the numpy path (``LumpedMassModel.residual_unchecked``
and the stacked axial dashpot) is used, and stays the reference the kernel is tested
against. Compiled on first use and cached on disk.
"""

import numba
import numpy as np

__all__ = ["chain_forces", "robot_chain_forces"]


@numba.njit(cache=True, error_model="numpy", nogil=True)
def chain_forces(nodes, vel, l0, EA, c_ax, weight):
    """Forces of n chains of N segments.

    Parameters
    ----------
    nodes : ndarray, shape (n, N + 1, 3)
        Node positions [m], anchor first, attachment B last.
    vel : ndarray, shape (n, N + 1, 3)
        Node velocities [m/s] (anchor 0); used only where c_ax > 0.
    l0, EA, c_ax : ndarray, shape (n,)
        Unstretched segment length [m], axial stiffness [N], axial dashpot [N s].
    weight : ndarray, shape (n, 3)
        Weight of one node, m l0 g [N].

    Returns
    -------
    inner : ndarray, shape (n, N - 1, 3)
        Spring + weight force on every interior node [N] (as ``residual_unchecked``).
    end : ndarray, shape (n, 3)
        Force on the platform at B: -T_N n_N + weight / 2 [N].
    dash_inner, dash_end : ndarray, shapes (n, N - 1, 3), (n, 3)
        Axial-dashpot forces c_ax d(eps)/dt on the interior nodes and on the platform at B
        (taut segments only).
    t_max, t_min, strain_max : float
        Largest and smallest tension [N], largest strain l / l0 - 1 [-].
    """
    n, N = nodes.shape[0], nodes.shape[1] - 1
    inner = np.empty((n, N - 1, 3))
    end = np.empty((n, 3))
    dash_inner = np.zeros((n, N - 1, 3))
    dash_end = np.zeros((n, 3))
    f = np.empty((N, 3))
    fd = np.empty((N, 3))
    t_max, t_min, strain_max = 0.0, np.inf, -np.inf
    for i in range(n):
        damped = c_ax[i] > 0.0
        for s in range(N):
            d0 = nodes[i, s + 1, 0] - nodes[i, s, 0]
            d1 = nodes[i, s + 1, 1] - nodes[i, s, 1]
            d2 = nodes[i, s + 1, 2] - nodes[i, s, 2]
            length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            u0, u1, u2 = d0 / length, d1 / length, d2 / length
            T = EA[i] * max(length / l0[i] - 1.0, 0.0)
            t_max, t_min = max(t_max, T), min(t_min, T)
            strain_max = max(strain_max, length / l0[i] - 1.0)
            f[s, 0], f[s, 1], f[s, 2] = T * u0, T * u1, T * u2
            if damped:
                rate = (u0 * (vel[i, s + 1, 0] - vel[i, s, 0])
                        + u1 * (vel[i, s + 1, 1] - vel[i, s, 1])
                        + u2 * (vel[i, s + 1, 2] - vel[i, s, 2])) / l0[i]
                c = c_ax[i] * rate if length > l0[i] else 0.0
                fd[s, 0], fd[s, 1], fd[s, 2] = c * u0, c * u1, c * u2
        for s in range(N - 1):
            for k in range(3):
                inner[i, s, k] = f[s + 1, k] - f[s, k] + weight[i, k]
                if damped:
                    dash_inner[i, s, k] = fd[s + 1, k] - fd[s, k]
        for k in range(3):
            end[i, k] = -f[N - 1, k] + 0.5 * weight[i, k]
            if damped:
                dash_end[i, k] = -fd[N - 1, k]
    return inner, end, dash_inner, dash_end, t_max, t_min, strain_max


@numba.njit(cache=True, error_model="numpy", nogil=True)
def robot_chain_forces(anchors, X, B, r, v_nodes, twist, l0, EA, c_ax, weight, platform_weight,
                       rG):
    """The chains' generalised forces on a robot (chains of equal N, interior nodes flat),
    with the platform's weight: what :func:`chain_forces` gives, assembled.

    Parameters
    ----------
    anchors, B, r : ndarray, shape (n, 3)
        Anchors, attachment points and lever arms r_i = R_p b_i [m].
    X, v_nodes : ndarray, shape (3 n (N - 1),)
        Interior node positions [m] and velocities [m/s], chain after chain.
    twist : ndarray, shape (6,)
        Platform twist (v_P [m/s], w [rad/s]).
    l0, EA, c_ax, weight : as :func:`chain_forces`
    platform_weight : ndarray, shape (3,)
        m_p g [N].
    rG : ndarray, shape (3,)
        R_p c_G [m].

    Returns
    -------
    inner, dash_inner : ndarray, shape (3 n (N - 1),)
        Residual (spring + weight) and axial-dashpot forces on the interior nodes [N].
    W, W_dash : ndarray, shape (6,)
        Wrench about P [N, N m] of the chains and the platform weight, and of the dashpots.
    t_max, t_min, strain_max : float
    """
    n = anchors.shape[0]
    N = X.size // (3 * n) + 1
    nodes = np.empty((n, N + 1, 3))
    vel = np.zeros((n, N + 1, 3))
    damped = False
    for i in range(n):
        damped = damped or c_ax[i] > 0.0
    for i in range(n):
        for k in range(3):
            nodes[i, 0, k] = anchors[i, k]
            nodes[i, N, k] = B[i, k]
        for s in range(N - 1):
            for k in range(3):
                nodes[i, s + 1, k] = X[3 * ((N - 1) * i + s) + k]
                vel[i, s + 1, k] = v_nodes[3 * ((N - 1) * i + s) + k]
        if damped:
            w0, w1, w2 = twist[3], twist[4], twist[5]
            vel[i, N, 0] = twist[0] + w1 * r[i, 2] - w2 * r[i, 1]
            vel[i, N, 1] = twist[1] + w2 * r[i, 0] - w0 * r[i, 2]
            vel[i, N, 2] = twist[2] + w0 * r[i, 1] - w1 * r[i, 0]
    inner, end, d_inner, d_end, t_max, t_min, strain = chain_forces(nodes, vel, l0, EA, c_ax,
                                                                    weight)
    W = np.zeros(6)
    Wd = np.zeros(6)
    for k in range(3):
        W[k] = platform_weight[k]
    W[3] = rG[1] * platform_weight[2] - rG[2] * platform_weight[1]
    W[4] = rG[2] * platform_weight[0] - rG[0] * platform_weight[2]
    W[5] = rG[0] * platform_weight[1] - rG[1] * platform_weight[0]
    for i in range(n):
        for src, dst in ((end, W), (d_end, Wd)):
            f0, f1, f2 = src[i, 0], src[i, 1], src[i, 2]
            dst[0] += f0
            dst[1] += f1
            dst[2] += f2
            dst[3] += r[i, 1] * f2 - r[i, 2] * f1
            dst[4] += r[i, 2] * f0 - r[i, 0] * f2
            dst[5] += r[i, 0] * f1 - r[i, 1] * f0
    return inner.ravel(), d_inner.ravel(), W, Wd, t_max, t_min, strain
