"""Compiled (numba) whole time-domain runs of the lumped-mass robot with fixed lengths
(theory.md §14.5, §14.6): velocity-Verlet (explicit) and Newmark with Newton on kept LU
factors (implicit), with the records, the energy ledger rows and the checks of every step.
Arrays in, arrays out; imports nothing from dynstiff but its sibling kernels.
"""

from __future__ import annotations

import numba
import numpy as np

from dynstiff.compiled.chain import (
    JIT,
    chain_pass,
    compose,
    cross_add,
    energies,
    lu_solve,
    platform,
    solve_free,
    weight_wrench,
)

__all__ = ["explicit_run", "implicit_run"]


@numba.njit(**JIT)
def _step_done(k, n_steps, record_every, t_min, strain, de, dd, ledger, info, out):
    """The running bookkeeping after step k of a run (as the loop of time_domain.simulate):
    ``de`` and ``dd`` are dx . (f_ext,n + f_ext,n+1) and dx . (f_d,n + f_d,n+1) of the step.
    ``ledger`` (7,): (E0, |E0 - V_eq|, floor, W_ext, D, peak |W_ext|, peak |D|) [J], the last
    four updated; ``info`` (5,) int: steps with a slack segment, the first of them (0 if
    none) with its first slack (cable, segment), the first step whose energy residual passed
    0.1 times the scale (0 if none); ``out`` (5,): the largest strain [-], the residual and
    the scale [J] of the last ledger row, and those of the warning step. Returns 2 for a
    strain above 1, 1 when the step needs its ledger row (:func:`_ledger_row`: a recorded
    step, a slack step, the last step), else 0."""
    ledger[3] += 0.5 * de
    ledger[4] -= 0.5 * dd
    ledger[5], ledger[6] = max(ledger[5], abs(ledger[3])), max(ledger[6], abs(ledger[4]))
    out[0] = strain
    if t_min <= 0.0:
        info[0] += 1
    if strain > 1.0:
        return 2
    return 1 if (k % record_every == 0 or t_min <= 0.0 or k == n_steps) else 0


@numba.njit(**JIT)
def _ledger_row(k, record_every, pos, rot, X, vp, vn, anchors, attachments, seg, l0, EA,
                node_mass, g, mass, com, inertia, mu, ledger, info, out, rec_pose, rec_vel,
                rec_t_end, rec_t_anchor, rec_E, rec_X):
    """The ledger row of step k (:func:`_step_done`): the energies, the checks and, at a
    recorded step (record_every divides k), row k // record_every of ``rec_pose`` (6,),
    ``rec_vel`` (6,), ``rec_t_end``, ``rec_t_anchor`` (n,), ``rec_E`` (8,) and, when it has
    rows, ``rec_X``. Returns 0, or 2 for a strain above 1, 3 for an energy residual above 10
    times the scale plus the floor."""
    record = k % record_every == 0
    el, gr, kin, t_end, t_anchor, strain, sc, ss = energies(
        pos, rot, X, vp, vn, anchors, attachments, seg, l0, EA, node_mass, g, mass, com,
        inertia, mu)
    res = kin + el + gr - ledger[0] - (ledger[3] - ledger[4])
    scale = ledger[1] + ledger[5] + ledger[6]
    out[0], out[1], out[2] = strain, res, scale
    if abs(res) > 0.1 * (scale + ledger[2]) and info[4] == 0:
        info[4], out[3], out[4] = k, res, scale
    if strain > 1.0 or abs(res) > 10.0 * (scale + ledger[2]):
        return 2 if strain > 1.0 else 3
    if sc >= 0 and info[1] == 0:
        info[1], info[2], info[3] = k, sc, ss
    if record:
        o = k // record_every
        for j in range(3):
            rec_pose[o, j], rec_pose[o, 3 + j] = pos[j], rot[j]
        for j in range(6):
            rec_vel[o, j] = vp[j]
        for i in range(t_end.size):
            rec_t_end[o, i], rec_t_anchor[o, i] = t_end[i], t_anchor[i]
        rec_E[o, 0], rec_E[o, 1], rec_E[o, 2], rec_E[o, 3] = kin, gr, el, ledger[3]
        rec_E[o, 4], rec_E[o, 5], rec_E[o, 6], rec_E[o, 7] = 0.0, 0.0, ledger[4], res
        if rec_X.shape[0]:
            for j in range(X.size):
                rec_X[o, j] = X[j]
    return 0


@numba.njit(**JIT)
def _run(implicit, steps, dt, record_every, state, newton, loads, free, anchors, attachments, seg,
         l0, EA, c_ax, weight, platform_weight, node_mass, g, mass, com, inertia, mu, alpha, c_visc,
         cv, beta, K0, lu, tol, max_iter: int, arm, force_weight, ledger, info, out, rec_pose,
         rec_vel, rec_t_end, rec_t_anchor, rec_E, rec_X):
    """The steps of :func:`explicit_run` (``implicit`` False) or :func:`implicit_run` (True):
    one loop for both schemes, so that the force evaluation, the most expensive part of a
    step, is written once and compiled inline (a call of a separate compiled function with
    its thirty arrays cost more than the whole step of a 20-segment line)."""
    pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n, app, apn, dp, dn = state
    nint, nflt = newton
    Kp, Ki, Kx = K0
    n, nx = anchors.shape[0], X.size
    fi = np.flatnonzero(free)
    nf = fi.size
    R, r, B = np.empty((3, 3)), np.empty((n, 3)), np.empty((n, 3))
    M6, rG, first = np.empty((6, 6)), np.empty(3), np.empty(3)
    half = 0.5 * node_mass
    frot = rot.copy()                              # the rotation of the frame buffers
    platform(frot, attachments, half, mass, com, inertia, R, r, M6, rG, first)
    pos1, rot1, X1 = np.empty(3), np.empty(3), np.empty(nx)
    a1p, a1n, v1p, v1n = np.zeros(6), np.empty(nx), np.empty(6), np.empty(nx)
    inner, dash, W, Wd = np.empty(nx), np.empty(nx), np.empty(6), np.empty(6)
    Fp, fdp, fdn, load = np.empty(6), np.empty(6), np.empty(nx), np.zeros(6)
    vm, Kv = np.zeros(nf + nx), np.zeros(nf + nx)
    G, y, x = np.empty(nf + nx), np.empty(nf + nx), np.empty(nf + nx)
    A, b = np.empty((6, 6)), np.empty(6)
    c0, h = 4.0 / dt ** 2, 0.5 * dt
    k0, k1, n_steps = steps
    for k in range(k0 + 1, k1 + 1):
        if loads.shape[0]:
            for j in range(6):
                load[j] = loads[k - k0 - 1, j]
        it0, fresh = 0, False
        if not implicit:                           # d = dt v_{n+1/2}
            for j in range(6):
                v1p[j] = vp[j] + h * ap[j]
                dp[j] = dt * v1p[j]
            for j in range(nx):
                v1n[j] = vn[j] + h * an[j]
                dn[j] = dt * v1n[j]
        elif nint[3] == 1:                         # new factors at the kept increment
            it0, fresh = nint[4], True
            nint[3] = 0
        else:                                      # predictor: a_{n+1} = 2 a_n - a_{n-1}
            for j in range(6):
                pred = 2.0 * ap[j] - app[j] if nint[1] else ap[j]
                dp[j] = dt * vp[j] + 0.25 * dt ** 2 * (ap[j] + pred)
                app[j] = ap[j]
            for j in range(nx):
                pred = 2.0 * an[j] - apn[j] if nint[1] else an[j]
                dn[j] = dt * vn[j] + 0.25 * dt ** 2 * (an[j] + pred)
                apn[j] = an[j]
            nint[1] = 1
        prev = np.inf
        it = it0
        for it in range(it0, max_iter + 1 if implicit else 1):
            # ---- the configuration of the increment d (rotation composed exactly)
            for j in range(3):
                pos1[j], rot1[j] = pos[j] + dp[j], rot[j]
            if dp[3] != 0.0 or dp[4] != 0.0 or dp[5] != 0.0:
                compose(dp[3], dp[4], dp[5], rot1)
            if rot1[0] != frot[0] or rot1[1] != frot[1] or rot1[2] != frot[2]:
                frot[:] = rot1
                platform(frot, attachments, half, mass, com, inertia, R, r, M6, rG, first)
            for i in range(n):
                for j in range(3):
                    B[i, j] = pos1[j] + r[i, j]
            finite = True
            for j in range(nx):
                X1[j] = X[j] + dn[j]
            if implicit:                           # a_{n+1}, v_{n+1} of the increment
                for j in range(6):
                    a1p[j] = c0 * (dp[j] - dt * vp[j]) - ap[j]
                    v1p[j] = vp[j] + h * (ap[j] + a1p[j])
                    finite = finite and np.isfinite(dp[j])
                for j in range(nx):
                    a1n[j] = c0 * (dn[j] - dt * vn[j]) - an[j]
                    v1n[j] = vn[j] + h * (an[j] + a1n[j])
                    finite = finite and np.isfinite(dn[j])
            # ---- forces at (pos1, rot1, X1) and the velocity (v1p, v1n), as
            # time_dynamics.Dynamics.forces: chains, weights, load, damping (axial
            # dashpots, -alpha M v, -beta K0 v, cable viscous c l0 on the nodes and c l0 / 2
            # at B_i), minus the gyroscopic terms; Fp 0 on the held DOFs
            weight_wrench(platform_weight, rG, W, Wd)
            t_max, t_min, strain = chain_pass(anchors, X1, B, r, v1n, v1p, seg, l0, EA, c_ax,
                                               weight, inner, dash, W, Wd)
            for j in range(6):
                fdp[j] = Wd[j]
            if beta != 0.0:
                for j in range(nf):
                    vm[j] = v1p[fi[j]]
                for j in range(nx):
                    vm[nf + j] = v1n[j]
                for j in range(nf + nx):
                    s = 0.0
                    for q in range(Kp[j], Kp[j + 1]):
                        s += Kx[q] * vm[Ki[q]]
                    Kv[j] = beta * s
                for j in range(nf):
                    fdp[fi[j]] -= Kv[j]
            if alpha != 0.0:
                for j in range(6):
                    s = 0.0
                    for m in range(6):
                        s += M6[j, m] * v1p[m]
                    fdp[j] -= alpha * s
            for i in range(n):
                if c_visc[i] != 0.0:
                    # 0.5 c l0 J^T J v, J = [I, -[r]x]: J v = v_P + w x r
                    j0 = v1p[0] + v1p[4] * r[i, 2] - v1p[5] * r[i, 1]
                    j1 = v1p[1] + v1p[5] * r[i, 0] - v1p[3] * r[i, 2]
                    j2 = v1p[2] + v1p[3] * r[i, 1] - v1p[4] * r[i, 0]
                    c = 0.5 * c_visc[i] * l0[i]
                    fdp[0] -= c * j0
                    fdp[1] -= c * j1
                    fdp[2] -= c * j2
                    cross_add(r[i, 0], r[i, 1], r[i, 2], j0, j1, j2, -c, fdp, 3)
            for j in range(6):
                Fp[j] = W[j] + load[j] + fdp[j]
            w0, w1, w2 = v1p[3], v1p[4], v1p[5]
            if w0 != 0.0 or w1 != 0.0 or w2 != 0.0:
                # g = [w x (w x S); w x (I_P w)]
                e0 = w1 * first[2] - w2 * first[1]
                e1 = w2 * first[0] - w0 * first[2]
                e2 = w0 * first[1] - w1 * first[0]
                cross_add(w0, w1, w2, e0, e1, e2, -1.0, Fp, 0)
                i0 = M6[3, 3] * w0 + M6[3, 4] * w1 + M6[3, 5] * w2
                i1 = M6[4, 3] * w0 + M6[4, 4] * w1 + M6[4, 5] * w2
                i2 = M6[5, 3] * w0 + M6[5, 4] * w1 + M6[5, 5] * w2
                cross_add(w0, w1, w2, i0, i1, i2, -1.0, Fp, 3)
            for j in range(6):
                if not free[j]:
                    Fp[j] = 0.0
                    fdp[j] = 0.0
            for j in range(nx):
                fdn[j] = dash[j] - alpha * mu[j] * v1n[j] - cv[j] * v1n[j] - Kv[nf + j]
            if not implicit:
                break
            # ---- Newton: residual G = M a_{n+1} - F, its relative size, the kept factors
            big = 0.0
            for q in range(nf):
                j = fi[q]
                s = 0.0
                for m in range(6):
                    s += M6[j, m] * a1p[m]
                G[q] = s - Fp[j]
                big = max(big, abs(G[q]) / arm if j >= 3 else abs(G[q]))
                finite = finite and np.isfinite(G[q])
            for j in range(nx):
                G[nf + j] = mu[j] * a1n[j] - (inner[j] + fdn[j])
                big = max(big, abs(G[nf + j]))
                finite = finite and np.isfinite(G[nf + j])
            if not finite:
                return 1, k
            res = big / max(force_weight + t_max, np.finfo(np.float64).tiny)
            if res <= tol:
                break
            if it == max_iter:
                nflt[0] = res
                return 4, k
            if not fresh and (nint[0] == 0 or res > 0.1 * prev):
                nint[4] = it
                return 5, k
            fresh = False
            prev = res
            lu_solve(lu, G, y, x)
            for q in range(nf):
                dp[fi[q]] -= x[q]
            for j in range(nx):
                dn[j] -= x[nf + j]
        if implicit:
            nint[2] += it
        else:                                      # a_{n+1} = M^-1 F, v_{n+1}
            solve_free(M6, Fp, free, A, b, a1p)
            finite = True
            for j in range(6):
                v1p[j] += h * a1p[j]
                finite = finite and np.isfinite(a1p[j]) and np.isfinite(v1p[j])
            for j in range(nx):
                a1n[j] = (inner[j] + fdn[j]) / mu[j]
                v1n[j] += h * a1n[j]
                finite = finite and np.isfinite(a1n[j]) and np.isfinite(v1n[j])
            if not finite:
                return 1, k
        # ---- the step is taken: state, ledger work terms, checks, records
        de = dd = 0.0
        for j in range(6):
            de += dp[j] * (fe_p[j] + load[j])
            dd += dp[j] * (fd_p[j] + fdp[j])
            vp[j], ap[j], fe_p[j], fd_p[j] = v1p[j], a1p[j], load[j], fdp[j]
        for j in range(3):
            pos[j], rot[j] = pos1[j], rot1[j]
        for j in range(nx):
            dd += dn[j] * (fd_n[j] + fdn[j])
            X[j], vn[j], an[j], fd_n[j] = X1[j], v1n[j], a1n[j], fdn[j]
        status = _step_done(k, n_steps, record_every, t_min, strain, de, dd, ledger, info, out)
        if status == 1:
            status = _ledger_row(k, record_every, pos, rot, X, vp, vn, anchors, attachments,
                                 seg, l0, EA, node_mass, g, mass, com, inertia, mu, ledger,
                                 info, out, rec_pose, rec_vel, rec_t_end, rec_t_anchor, rec_E,
                                 rec_X)
        if status:
            return status, k
    return 0, k1


@numba.njit(**JIT)
def explicit_run(steps, dt, record_every, state, loads, free, anchors, attachments, seg, l0,
                 EA, c_ax, weight, platform_weight, node_mass, g, mass, com, inertia, mu, alpha,
                 c_visc, cv, beta, K0, ledger, info, out, rec_pose, rec_vel, rec_t_end,
                 rec_t_anchor, rec_E, rec_X):
    """A whole velocity-Verlet run of the lumped robot with fixed lengths (as
    time_stepping.explicit_step, step after step; theory.md §7.3, §14.5).

    Parameters
    ----------
    steps : tuple of int
        (k0, k1, n_steps): steps k = k0 + 1 ... k1 of a run of n_steps (a run may be taken in
        blocks).
    dt, record_every : float [s], int
        The state after step k is recorded in row k // record_every when record_every
        divides k.
    state : tuple of ndarray
        (pos (3,) [m], rot (3,) rotation vector, X (n_x,) interior nodes [m], vp (6,)
        twist, vn (n_x,) node velocities, ap (6,), an (n_x,) accelerations, fe_p (6,)
        external and fd_p (6,), fd_n (n_x,) damping forces of the current step), platform
        DOFs as full 6-vectors with the held ones 0; updated in place.
    loads : ndarray, shape (k1 - k0, 6) or (0, 6)
        External load at the end of every step (held DOFs 0), or none.
    free : ndarray of bool, shape (6,)
    anchors, attachments, seg, l0, EA, c_ax, weight, platform_weight : as robot_chain_forces
    node_mass : ndarray, shape (n,)
        m l0 of every cable [kg]; half of it rides at B_i.
    g, mass, com, inertia : gravity [m/s^2], the platform's mass, centre of mass, inertia.
    mu, cv : ndarray, shape (n_x,)
        Node masses [kg] and cable viscous dashpots c l0 [N s / m].
    alpha : float
        Mass-proportional damping [1/s].
    c_visc : ndarray, shape (n,)
        Cable viscous damping c [N s / m^2].
    beta, K0 : float [s], (indptr, indices, data)
        Stiffness-proportional damping -beta K0 v, K0 in CSR form in the model's DOF order
        (free platform DOFs, then the interior nodes) [N/m]; unused when beta is 0.
    ledger, info, out, rec_pose, rec_vel, rec_t_end, rec_t_anchor, rec_E, rec_X : ndarray
        The ledger, the run's counters and the records, updated in place (see
        :func:`_step_done`).

    Returns
    -------
    status, step : int
        0 done (step k1); or the step k where the run stopped: 1 a non-finite state, 2 a
        strain above 1, 3 an energy residual above 10 times the energy scale (plus the floor).
    """
    pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n = state
    nx = X.size
    full = (pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n, np.zeros(6), np.zeros(nx),
            np.zeros(6), np.zeros(nx))
    z = np.zeros(1, dtype=np.int64)
    lu = (z, z[:0], np.zeros(0), z, z[:0], np.zeros(0), z[:0], z[:0])
    return _run(False, steps, dt, record_every, full, (np.zeros(5, dtype=np.int64), np.zeros(1)),
                loads, free, anchors, attachments, seg, l0, EA, c_ax, weight, platform_weight,
                node_mass, g, mass, com, inertia, mu, alpha, c_visc, cv, beta, K0, lu, 0.0, 0,
                1.0, 1.0, ledger, info, out, rec_pose, rec_vel, rec_t_end, rec_t_anchor, rec_E,
                rec_X)


@numba.njit(**JIT)
def implicit_run(steps, dt, record_every, state, newton, loads, free, anchors, attachments, seg, l0,
                 EA, c_ax, weight, platform_weight, node_mass, g, mass, com, inertia, mu, alpha,
                 c_visc, cv, beta, K0, lu, tol, max_iter: int, arm, force_weight, ledger, info, out,
                 rec_pose, rec_vel, rec_t_end, rec_t_anchor, rec_E, rec_X):
    """Newmark average-acceleration steps of the lumped robot with fixed lengths, solved by
    modified Newton iterations with kept LU factors (as time_stepping.implicit_step, step
    after step; theory.md §7.3, §14.4, §14.6).

    Parameters as :func:`explicit_run`, and:

    state : tuple of ndarray
        As in :func:`explicit_run`, then the acceleration of the previous step (6,), (n_x,)
        (the predictor's a_{n-1}), then the increment d of the current step (6,), (n_x,).
    newton : tuple of ndarray
        (int64 (5,): LU given, a_{n-1} given, Newton iterations so far, resume flag, the
        iteration to resume at; float (1,): the residual where Newton failed).
    lu : tuple
        The factors of K + 4 M / dt^2 + 2 C / dt in the model's DOF order (see
        :func:`lu_solve`).
    tol, max_iter : float, int
        Newton tolerance on the relative residual and iterations per step.
    arm, force_weight : float
        Moment arm [m] and weight [N] of the relative residual (LumpedMassModel.
        residual_scales).

    Returns
    -------
    status, step : int
        As :func:`explicit_run`, and 4: Newton did not converge at ``step`` (residual in
        newton[1][0]); 5: the LU factors are missing or Newton slowed down at ``step``: the
        caller factorises the Newton matrix at the configuration advanced by the increment
        in ``state``, sets the resume flag and calls again from that step.
    """
    return _run(True, steps, dt, record_every, state, newton, loads, free, anchors,
                attachments, seg, l0, EA, c_ax, weight, platform_weight, node_mass, g, mass,
                com, inertia, mu, alpha, c_visc, cv, beta, K0, lu, tol, max_iter, arm,
                force_weight, ledger, info, out, rec_pose, rec_vel, rec_t_end, rec_t_anchor,
                rec_E, rec_X)
