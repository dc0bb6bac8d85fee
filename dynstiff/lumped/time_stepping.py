"""Stepping of the lumped-mass time-domain model (theory.md §7.3): the Newmark
average-acceleration and velocity-Verlet steps, the blow-up checks, the running energy
ledger and the recorder. Internal to :mod:`dynstiff.lumped.time_domain` (see its notes for
the schemes and the energy bookkeeping), except the failure types it raises."""

import warnings

import numpy as np

from .._vec import cross
from ..errors import ConvergenceError, DynstiffError
from .time_damping import explicit_step_limit
from .time_dynamics import (FastPose, Frame, advance, interior_views, load_at,
                            potential_energy, twist_of)
from .time_response import EnergyBalance, TimeResponse

#: A segment stretched beyond this strain means the integration has blown up.
_STRAIN_LIMIT = 1.0
#: Energy balance residual / energy scale above which the integration has blown up, and
#: above which the ledger is reported inaccurate (EnergyBalanceWarning).
_BLOW_UP = 10.0
_LEDGER_WARN = 0.1


class IntegrationError(DynstiffError, RuntimeError):
    """The time integration blew up (non-finite state, an absurd strain, or energy created
    beyond the energy scale of the run).

    Attributes ``step``, ``time`` [s] and ``dt`` [s] locate the failure.
    """

    def __init__(self, message, step=None, time=None, dt=None):
        super().__init__(message)
        self.step, self.time, self.dt = step, time, dt


class EnergyBalanceWarning(RuntimeWarning):
    """The energy balance residual passed 10 % of the run's energy scale: the ledger (not
    necessarily the motion) is inaccurate at this dt; halve dt to check."""


class StepNewton:
    """Newton options, the kept LU factors and the iteration counters of a run."""

    def __init__(self, tol, max_iter):
        self.tol, self.max_iter = tol, max_iter
        self.lu = None
        self.a_prev = None
        self.iterations = self.updates = 0


def implicit_step(dyn, pose, X, v, a, t1, dt, k, newton):
    """One Newmark average-acceleration step solved by (modified) Newton iterations.

    Unknown: the increment d = x_{n+1} - x_n; a_{n+1} = 4 (d - dt v_n) / dt^2 - a_n and
    v_{n+1} = v_n + dt (a_n + a_{n+1}) / 2; residual G(d) = M a_{n+1} - F(q_{n+1}, v_{n+1}).
    The iteration starts from a_{n+1} = 2 a_n - a_{n-1} (theory.md §14.4).
    The LU factors of K + 4 M / dt^2 + 2 C / dt are kept while each iteration reduces the
    residual tenfold, and refreshed otherwise.
    """
    import scipy.sparse.linalg
    m = dyn.model
    c0 = 4.0 / dt ** 2
    # predictor: a_{n+1} extrapolated linearly from a_{n-1}, a_n (a_n at the first step)
    a_pred = a if newton.a_prev is None or newton.a_prev.shape != a.shape else \
        2.0 * a - newton.a_prev
    d = dt * v + 0.25 * dt ** 2 * (a + a_pred)
    newton.a_prev = a
    prev = np.inf
    for it in range(newton.max_iter + 1):
        pose1, X1 = advance(m, pose, X, d)
        a1 = c0 * (d - dt * v) - a
        v1 = v + 0.5 * dt * (a + a1)
        F1, fe1, fd1, t_max, frame1 = dyn.forces(pose1, X1, v1, t1)
        G = dyn.mass_times(frame1, a1) - F1
        if not (np.all(np.isfinite(G)) and np.all(np.isfinite(d))):
            raise IntegrationError(
                f"simulate: non-finite state at step {k} (t = {t1:g} s) with implicit dt = "
                f"{dt:g} s", step=k, time=t1, dt=dt)
        res = m.relative_residual(G, t_max)
        if res <= newton.tol:
            break
        if it == newton.max_iter:
            raise ConvergenceError(
                f"simulate: Newton did not converge in {newton.max_iter} iterations at step "
                f"{k} (t = {t1:g} s) with dt = {dt:g} s: relative residual {res:.3e} > tol "
                f"{newton.tol:g}; reduce dt (slack snapping or a blow-up)", residual=res)
        if newton.lu is None or res > 0.1 * prev:
            newton.lu = scipy.sparse.linalg.splu(dyn.newton_matrix(pose1, X1, dt))
            newton.updates += 1
        prev = res
        d = d - newton.lu.solve(G)
    newton.iterations += it
    return d, pose1, X1, v1, a1, fe1, fd1, frame1


def explicit_step(dyn, pose, X, v, a, t1, dt, k, newton):
    """One velocity-Verlet step (velocity-dependent forces at the half-step velocity)."""
    m = dyn.model
    vh = v + 0.5 * dt * a
    d = dt * vh
    pose1, X1 = advance(m, pose, X, d)
    F1, fe1, fd1, _, frame1 = dyn.forces(pose1, X1, vh, t1)
    a1 = dyn.accelerations(frame1, F1)
    v1 = vh + 0.5 * dt * a1
    if not (np.all(np.isfinite(a1)) and np.all(np.isfinite(v1))):
        raise IntegrationError(
            f"simulate: non-finite state at step {k} (t = {t1:g} s) with explicit dt = "
            f"{dt:g} s; the predicted stability limit is "
            f"{explicit_step_limit(m, damping=dyn.damping):g} s (theory.md §7.3)",
            step=k, time=t1, dt=dt)
    return d, pose1, X1, v1, a1, fe1, fd1, frame1


def check_blow_up(strain, residual, ledger, scheme, dt, k, t1, m, damping, stacklevel=3):
    """IntegrationError when a strain exceeds 1 or the energy balance residual exceeds
    ``_BLOW_UP`` times the energy scale of the run (plus 1e-3 of the initial strain
    energy); an :class:`EnergyBalanceWarning`, once, when it passes ``_LEDGER_WARN`` of it.

    An unstable integration makes the residual grow without bound; a bounded residual of
    the order of the scale is the trapezoidal quadrature of the winch work missing the
    axial chain modes (their period below dt), which leaves the motion itself accurate."""
    if abs(residual) > _LEDGER_WARN * ledger.limit() and not ledger.warned:
        ledger.warned = True
        warnings.warn(
            f"simulate: at step {k} (t = {t1:g} s) the energy balance residual {residual:.3g} "
            f"J is {abs(residual) / ledger.scale():.2g} of the energy scale "
            f"{ledger.scale():.3g} J: the energy ledger is inaccurate at dt = {dt:g} s "
            f"(axial chain modes faster than 1 / dt, typically with winches, or an unstable "
            f"explicit step); halve dt to "
            f"check the motion", EnergyBalanceWarning, stacklevel=stacklevel)
    if strain <= _STRAIN_LIMIT and abs(residual) <= _BLOW_UP * ledger.limit():
        return
    why = (f"a segment is stretched to {1 + strain:.3g} l0" if strain > _STRAIN_LIMIT
           else f"the energy balance residual {residual:.3g} J exceeds {_BLOW_UP:g} times "
                f"the energy scale of the run {ledger.scale():.3g} J")
    hint = (f"; the predicted explicit stability limit is dt < "
            f"{explicit_step_limit(m, damping=damping):g} s (theory.md §7.3)"
            if scheme == "explicit" else "; reduce dt")
    raise IntegrationError(
        f"simulate: blow-up at step {k} (t = {t1:g} s) with {scheme} dt = {dt:g} s: "
        f"{why}{hint}", step=k, time=t1, dt=dt)


def carried_energy(m, m_prev, frame, v, dmu):
    """sum dmu |v|^2 of the interior nodes and the half masses at B_i [J * 2]."""
    nf = m.n_free
    tw = twist_of(m, v)
    dhalf = 0.5 * (m.node_masses - m_prev.node_masses)
    vB = tw[:3] + cross(tw[3:], frame.r)
    return float(dmu @ v[nf:] ** 2 + dhalf @ np.sum(vB ** 2, axis=1))


class Ledger:
    """Running energy balance E - E0 = W_ext - D + W_w + E_c + residual (module notes)."""

    def __init__(self, E0, V_eq, elastic0):
        self.E0 = E0
        self.excess = abs(E0 - V_eq)
        self.floor = 1e-3 * elastic0          # for runs that start at rest, unloaded
        self.ext = self.winch = self.carried = self.diss = 0.0
        self.peaks = np.zeros(4)
        self.warned = False

    def track(self):
        """Update the peaks of the work terms (the energy scale) at a step without a row."""
        p = self.peaks
        p[0], p[1] = max(p[0], abs(self.ext)), max(p[1], abs(self.winch))
        p[2], p[3] = max(p[2], abs(self.carried)), max(p[3], abs(self.diss))

    def row(self, kinetic, pot):
        """(kinetic, gravity, elastic, ext, winch, carried, dissipated, residual) [J]."""
        self.track()
        E = kinetic + pot[0] + pot[1]
        res = E - self.E0 - (self.ext - self.diss + self.winch + self.carried)
        return (kinetic, pot[1], pot[0], self.ext, self.winch, self.carried, self.diss, res)

    def scale(self):
        """Energy scale of the run so far [J] (as EnergyBalance.scale)."""
        return self.excess + float(self.peaks.sum())

    def limit(self):
        """Energy scale with its floor [J]: the reference of the blow-up test."""
        return self.scale() + self.floor


class Recorder:
    def __init__(self, n_rec, n, model, nodes):
        self.t = np.empty(n_rec)
        self.pose = np.empty((n_rec, 6))
        self.vel = np.empty((n_rec, 6))
        self.t_end = np.empty((n_rec, n))
        self.t_anchor = np.empty((n_rec, n))
        self.L = np.empty((n_rec, n))
        self.E = np.empty((n_rec, 8))
        self.nodes = [np.empty((n_rec, N + 1, 3)) for N in model.segments] if nodes else None

    def store(self, j, t, pose, v, model, pot, row, X):
        self.t[j] = t
        self.pose[j] = pose.as_vector()
        self.vel[j] = twist_of(model, v)
        self.t_end[j], self.t_anchor[j] = pot[2], pot[3]
        self.L[j] = model.unstretched_lengths
        self.E[j] = row
        if self.nodes is not None:
            B, _ = model.robot.attachment_points(pose)
            for i, xi in enumerate(interior_views(model, X)):
                self.nodes[i][j] = np.vstack((model.robot.anchors[i], xi, B[i]))

    def result(self, model, eq_pose, static_energy, **info):
        self.E.setflags(write=False)
        energy = EnergyBalance(*self.E.T, static_energy=static_energy)
        out = [self.t, self.pose, self.vel, self.t_end, self.t_anchor, self.L, energy]
        for a in out[:-1] + (self.nodes or []):
            a.setflags(write=False)
        return TimeResponse(*out, nodes=None if self.nodes is None else tuple(self.nodes),
                            free_dofs=model.free_dofs, equilibrium_pose=eq_pose.as_vector(),
                            **info)


def compiled_explicit_run(fast, dyn, pose, X, v, a, fe, fd, dt, n_steps, record_every, rec,
                          ledger, damping, slack_warning):
    """The velocity-Verlet steps of a run with fixed lengths, beta = 0 and chains of equal N,
    ``record_every`` steps per call of the compiled kernel
    (:func:`dynstiff.lumped.compiled_chain.explicit_steps`, theory.md §14.4); the ledger
    rows, records, checks and warnings at the recorded steps as in the stepwise loop.
    Returns the number of steps with a slack segment."""
    m = dyn.model
    rob, p = m.robot, m.robot.platform
    nf, fi = m.n_free, m.free_index
    free = np.zeros(6, dtype=bool)
    free[fi] = True

    def six(x):
        out = np.zeros(6)
        out[fi] = x[:nf]
        return out

    pos, rot = np.array(pose.position, dtype=float), np.array(pose.rotation, dtype=float)
    vp, vn, ap, an = six(v), v[nf:].copy(), six(a), a[nf:].copy()
    fe_p, fd_p, fd_n = six(fe), six(fd), fd[nf:].copy()
    consts = (rob.anchors.astype(float), rob.attachments.astype(float), m.segment_lengths,
              dyn.EA, np.asarray(dyn.c_ax, dtype=float), dyn.node_weights,
              dyn.platform_weight, 0.5 * m.node_masses, float(p.mass),
              np.asarray(p.center_of_mass, dtype=float), np.asarray(p.inertia, dtype=float),
              dyn.mu, float(dyn.alpha), np.asarray(dyn.c_visc, dtype=float), dyn.cv)
    k, slack_steps, warned = 0, 0, False
    while k < n_steps:
        count = min(n_steps, (k // record_every + 1) * record_every) - k
        loads = np.zeros((count, 6))
        if dyn.excitation is not None:
            for j in range(count):
                loads[j] = load_at(dyn.excitation, (k + 1 + j) * dt)
            loads[:, ~free] = 0.0
        (pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n, ledger.ext, ledger.diss, pk_ext,
         pk_diss, strain, n_slack, taken, status) = fast.explicit_steps(
            count, dt, pos, rot, X, vp, vn, ap, an, fe_p, fd_p, fd_n, loads, free, *consts,
            ledger.ext, ledger.diss, not warned)
        ledger.peaks[0] = max(ledger.peaks[0], pk_ext)
        ledger.peaks[3] = max(ledger.peaks[3], pk_diss)
        slack_steps += n_slack
        k += taken
        t1 = k * dt
        if status == 1:
            raise IntegrationError(
                f"simulate: non-finite state at step {k + 1} (t = {t1 + dt:g} s) with explicit "
                f"dt = {dt:g} s; the predicted stability limit is "
                f"{explicit_step_limit(m, damping=damping):g} s (theory.md §7.3)",
                step=k + 1, time=t1 + dt, dt=dt)
        pose = FastPose(pos, rot)
        v = np.concatenate([vp[fi], vn])
        if status == 2:
            check_blow_up(strain, 0.0, ledger, "explicit", dt, k, t1, m, damping, 4)
        pot = None
        if status == 3:
            pot = potential_energy(m, Frame(m, pose), X)
            row = ledger.row(dyn.kinetic(Frame(m, pose), v), pot)
            check_blow_up(pot[5], row[-1], ledger, "explicit", dt, k, t1, m, damping, 4)
        elif k % record_every == 0 or k == n_steps:
            elastic, gravity, kinetic, t_end, t_anchor, strain = fast.energies(
                pos, rot, X, vp, vn, consts[0], consts[1], m.segment_lengths, dyn.EA,
                m.node_masses, rob.g, *consts[8:12])
            pot = (elastic, gravity, t_end, t_anchor, [], strain)
            row = ledger.row(kinetic, pot)
            check_blow_up(pot[5], row[-1], ledger, "explicit", dt, k, t1, m, damping, 4)
        if status == 3:
            warned = True
            i, s = pot[4][0]
            warnings.warn(
                f"simulate: cable {i} segment {s} went slack at step {k} (t = {t1:g} s); "
                f"tension-only springs carry no force until it is taut again",
                slack_warning, stacklevel=3)
        if k % record_every == 0:
            rec.store(k // record_every, t1, pose, v, m, pot, row, X)
    return slack_steps
