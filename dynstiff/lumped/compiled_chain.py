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

__all__ = ["chain_forces", "robot_chain_forces", "explicit_steps", "energies"]


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


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _quat(v):
    """Unit quaternion (x, y, z, w) of a rotation vector (as platform.rotvec_to_quaternion)."""
    theta = np.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if theta <= 1e-3:
        t2 = theta * theta
        scale = 0.5 - t2 / 48 + t2 * t2 / 3840
    else:
        scale = np.sin(theta / 2) / theta
    return np.array([scale * v[0], scale * v[1], scale * v[2], np.cos(theta / 2)])


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _compose(d, rot):
    """Rotation vector of exp(d) R(rot) (as Pose.moved)."""
    p, q = _quat(d), _quat(rot)
    x = p[3] * q[0] + q[3] * p[0] + (p[1] * q[2] - p[2] * q[1])
    y = p[3] * q[1] + q[3] * p[1] + (p[2] * q[0] - p[0] * q[2])
    z = p[3] * q[2] + q[3] * p[2] + (p[0] * q[1] - p[1] * q[0])
    w = p[3] * q[3] - (p[0] * q[0] + p[1] * q[1] + p[2] * q[2])
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    n = np.sqrt(x * x + y * y + z * z)
    theta = 2 * np.arctan2(n, w)
    if theta <= 1e-3:
        t2 = theta * theta
        scale = 2 + t2 / 12 + 7 * t2 * t2 / 2880
    else:
        scale = theta / np.sin(theta / 2)
    return np.array([scale * x, scale * y, scale * z])


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _matrix(rot):
    """Rotation matrix of a rotation vector (as platform.rotation_matrix)."""
    q = _quat(rot)
    x, y, z, w = q[0], q[1], q[2], q[3]
    return np.array([
        [w * w + x * x - y * y - z * z, 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), w * w - x * x + y * y - z * z, 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), w * w - x * x - y * y + z * z]])


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _cross(a, b):
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _platform(pos, rot, attachments, half, mass, com, inertia):
    """Frame quantities (as time_dynamics.Frame): B, r, M6, rG, first moment."""
    R = _matrix(rot)
    r = attachments @ R.T
    B = r + pos
    rG = R @ com
    S = _skew(rG)
    M = np.zeros((6, 6))
    for k in range(3):
        M[k, k] = mass
    M[:3, 3:] = -mass * S
    M[3:, :3] = mass * S
    M[3:, 3:] = R @ inertia @ R.T - mass * (S @ S)
    hr = half @ r
    Sh = _skew(hr)
    hs = half.sum()
    for k in range(3):
        M[k, k] += hs
    M[:3, 3:] -= Sh
    M[3:, :3] += Sh
    rr = 0.0
    for i in range(half.size):
        rr += half[i] * (r[i, 0] ** 2 + r[i, 1] ** 2 + r[i, 2] ** 2)
    outer = np.zeros((3, 3))
    for i in range(half.size):
        for j in range(3):
            for k in range(3):
                outer[j, k] += half[i] * r[i, j] * r[i, k]
    for k in range(3):
        M[3 + k, 3 + k] += rr
    M[3:, 3:] -= outer
    return B, r, M, rG, mass * rG + hr


@numba.njit(cache=True, error_model="numpy", nogil=True)
def _forces(pos, rot, X, vp, vn, load, free, anchors, attachments, l0, EA, c_ax, weight,
            platform_weight, half, mass, com, inertia, mu, alpha, c_visc, cv):
    """Generalised forces of the explicit step (as Dynamics.forces with beta = 0), platform
    part as a full 6-vector (0 on held DOFs): F, fe, fd (each platform (6,), nodes),
    M6, strain, t_min, and the slack (cable, segment) or (-1, -1)."""
    B, r, M6, rG, first = _platform(pos, rot, attachments, half, mass, com, inertia)
    inner, d_inner, W, Wd, t_max, t_min, strain = robot_chain_forces(
        anchors, X, B, r, vn, vp, l0, EA, c_ax, weight, platform_weight, rG)
    fd_p = Wd.copy()
    fd_n = d_inner.copy()
    if alpha != 0.0:
        fd_p -= alpha * (M6 @ vp)
        fd_n -= alpha * mu * vn
    for i in range(c_visc.size):
        if c_visc[i] != 0.0:
            # 0.5 c l0 J^T J v, J = [I, -[r]x]: J v = v_P + w x r
            jv = vp[:3] + _cross(vp[3:], r[i])
            c = 0.5 * c_visc[i] * l0[i]
            fd_p[:3] -= c * jv
            fd_p[3:] -= c * _cross(r[i], jv)
    fd_n -= cv * vn
    w = vp[3:]
    g = np.zeros(6)
    if w[0] != 0.0 or w[1] != 0.0 or w[2] != 0.0:
        g[:3] = _cross(w, _cross(w, first))
        Iw = np.zeros(3)
        for j in range(3):
            for k in range(3):
                Iw[j] += M6[3 + j, 3 + k] * w[k]
        g[3:] = _cross(w, Iw)
    Fp = W + load + fd_p - g
    for k in range(6):
        if not free[k]:
            Fp[k] = 0.0
            fd_p[k] = 0.0
    return Fp, inner + fd_n, load, fd_p, fd_n, M6, strain, t_min, B


@numba.njit(cache=True, error_model="numpy", nogil=True)
def energies(pos, rot, X, vp, vn, anchors, attachments, l0, EA, node_mass, g, mass, com,
             inertia, mu):
    """Ledger quantities of a state (as time_dynamics.potential_energy and
    Dynamics.kinetic): elastic, gravity and kinetic energy [J], end and anchor tensions (n,)
    [N], largest strain [-]."""
    n = anchors.shape[0]
    N = X.size // (3 * n) + 1
    B, r, M6, rG, first = _platform(pos, rot, attachments, 0.5 * node_mass, mass, com,
                                    inertia)
    elastic, strain = 0.0, -np.inf
    gravity = mass * g * (pos[2] + rG[2])
    t_end, t_anchor = np.empty(n), np.empty(n)
    for i in range(n):
        zsum = 0.0
        for s in range(N):
            a = anchors[i] if s == 0 else X[3 * ((N - 1) * i + s - 1):3 * ((N - 1) * i + s)]
            b = B[i] if s == N - 1 else X[3 * ((N - 1) * i + s):3 * ((N - 1) * i + s + 1)]
            d0, d1, d2 = b[0] - a[0], b[1] - a[1], b[2] - a[2]
            length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            stretch = max(length - l0[i], 0.0)
            elastic += 0.5 * EA[i] / l0[i] * stretch * stretch
            T = EA[i] * max(length / l0[i] - 1.0, 0.0)
            if s == 0:
                t_anchor[i] = T
            if s == N - 1:
                t_end[i] = T
            strain = max(strain, length / l0[i] - 1.0)
            if s < N - 1:
                zsum += b[2]
        gravity += node_mass[i] * g * (zsum + 0.5 * B[i, 2])
    kinetic = 0.5 * (vp @ (M6 @ vp) + vn @ (mu * vn))
    return elastic, gravity, kinetic, t_end, t_anchor, strain


@numba.njit(cache=True, error_model="numpy", nogil=True)
def explicit_steps(n_steps, dt, pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n, loads, free,
                   anchors, attachments, l0, EA, c_ax, weight, platform_weight, half, mass,
                   com, inertia, mu, alpha, c_visc, cv, ext, diss, stop_at_slack):
    """``n_steps`` velocity-Verlet steps of the lumped robot (as time_stepping.explicit_step
    with beta = 0 and fixed lengths; theory.md §7.3, §14.4), platform DOFs as full 6-vectors
    with the held ones 0.

    ``loads`` (n_steps, 6) are the external loads at the end of each step. ``ext`` and
    ``diss`` are the running work terms of the ledger. Returns the state after the steps
    taken, the last fe, fd, the updated ext, diss, their peaks, the largest strain, the number
    of steps with a slack segment and the first of them (step, cable, segment), and the
    number of steps taken (fewer when the state became non-finite or a strain exceeded 1).
    """
    n_free = 0
    for k in range(6):
        n_free += 1 if free[k] else 0
    fi = np.empty(n_free, dtype=np.int64)
    j = 0
    for k in range(6):
        if free[k]:
            fi[j] = k
            j += 1
    peak_ext, peak_diss = abs(ext), abs(diss)
    strain_max = -np.inf
    slack_steps = 0
    taken = 0
    status = 0
    for s in range(n_steps):
        vhp = vp + 0.5 * dt * ap
        vhn = vn + 0.5 * dt * an
        dp, dn = dt * vhp, dt * vhn
        if dp[3] != 0.0 or dp[4] != 0.0 or dp[5] != 0.0:
            rot = _compose(dp[3:], rot)
        pos = pos + dp[:3]
        X = X + dn
        Fp, Fn, fe1, fd1_p, fd1_n, M6, strain, t_min, B = _forces(
            pos, rot, X, vhp, vhn, loads[s], free, anchors, attachments, l0, EA, c_ax,
            weight, platform_weight, half, mass, com, inertia, mu, alpha, c_visc, cv)
        a1p = np.zeros(6)
        if n_free:
            Mff = np.empty((n_free, n_free))
            Ff = np.empty(n_free)
            for i in range(n_free):
                Ff[i] = Fp[fi[i]]
                for k in range(n_free):
                    Mff[i, k] = M6[fi[i], fi[k]]
            sol = np.linalg.solve(Mff, Ff)
            for i in range(n_free):
                a1p[fi[i]] = sol[i]
        a1n = Fn / mu
        v1p = vhp + 0.5 * dt * a1p
        v1n = vhn + 0.5 * dt * a1n
        if not (np.isfinite(a1p).all() and np.isfinite(a1n).all()
                and np.isfinite(v1p).all() and np.isfinite(v1n).all()):
            status = 1
            break
        ext += 0.5 * (dp @ (fe_p + fe1))
        diss -= 0.5 * (dp @ (fd_p + fd1_p) + dn @ (fd_n + fd1_n))
        peak_ext, peak_diss = max(peak_ext, abs(ext)), max(peak_diss, abs(diss))
        strain_max = max(strain_max, strain)
        if t_min <= 0.0:
            slack_steps += 1
        vp, vn, ap, an = v1p, v1n, a1p, a1n
        fe_p, fd_p, fd_n = fe1, fd1_p, fd1_n
        taken = s + 1
        if strain > 1.0:
            status = 2
            break
        if t_min <= 0.0 and stop_at_slack:
            status = 3
            break
    return (pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n, ext, diss, peak_ext, peak_diss,
            strain_max, slack_steps, taken, status)
