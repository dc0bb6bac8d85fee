"""Stepping of the lumped-mass time-domain model (theory.md §7.3): the Newmark
average-acceleration and velocity-Verlet steps, the blow-up checks, the running energy
ledger and the recorder. Internal to :mod:`dynstiff.timedomain.simulation` (see its notes for
the schemes and the energy bookkeeping), except the failure types it raises."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.errors import ConvergenceError, DynstiffError, DynstiffWarning
from dynstiff.timedomain.damping import explicit_step_limit
from dynstiff.timedomain.dynamics import FastPose, advance, interior_views, load_at, twist_of
from dynstiff.timedomain.response import EnergyBalance, TimeResponse

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.models.lumped_robot import LumpedMassModel
    from dynstiff.robot.pose import Pose
    from dynstiff.timedomain.damping import TimeDamping
    from dynstiff.timedomain.dynamics import Dynamics, Frame

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

    def __init__(self, message: str, step: int | None = None, time: float | None = None,
                 dt: float | None = None) -> None:
        super().__init__(message)
        self.step, self.time, self.dt = step, time, dt


class EnergyBalanceWarning(DynstiffWarning, RuntimeWarning):
    """The energy balance residual passed 10 % of the run's energy scale: the ledger (not
    necessarily the motion) is inaccurate at this dt; halve dt to check."""

class StepNewton:
    """Newton options, the kept LU factors and the iteration counters of a run."""

    def __init__(self, tol: float, max_iter: int) -> None:
        self.tol, self.max_iter = tol, max_iter
        self.lu = None
        self.a_prev = None
        self.iterations = self.updates = 0


def implicit_step(dyn: Dynamics, pose: FastPose, X: NDArray[np.float64], v: NDArray[np.float64],
                  a: NDArray[np.float64], t1: float, dt: float, k: int,
                  newton: StepNewton) -> tuple[NDArray[np.float64] | FastPose | Frame, ...]:
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


def explicit_step(dyn: Dynamics, pose: FastPose, X: NDArray[np.float64], v: NDArray[np.float64],
                  a: NDArray[np.float64], t1: float, dt: float, k: int,
                  newton: StepNewton) -> tuple[NDArray[np.float64] | FastPose | Frame, ...]:
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


def check_blow_up(strain: float, residual: float, ledger: Ledger, scheme: str, dt: float, k: int,
                  t1: float, m: LumpedMassModel, damping: TimeDamping, stacklevel: int = 3) -> None:
    """IntegrationError when a strain exceeds 1 or the energy balance residual exceeds
    ``_BLOW_UP`` times the energy scale of the run (plus 1e-3 of the initial strain
    energy); an :class:`EnergyBalanceWarning`, once, when it passes ``_LEDGER_WARN`` of it.

    An unstable integration makes the residual grow without bound; a bounded residual of
    the order of the scale is the trapezoidal quadrature of the winch work missing the
    axial chain modes (their period below dt), which leaves the motion itself accurate."""
    if abs(residual) > _LEDGER_WARN * ledger.limit() and not ledger.warned:
        ledger.warned = True
        ledger_warning(k, t1, residual, ledger.scale(), dt, stacklevel + 1)
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


def ledger_warning(k: int, t1: float, residual: float, scale: float, dt: float,
                   stacklevel: int = 5) -> None:
    """The :class:`EnergyBalanceWarning` of step k (residual and energy scale [J])."""
    warnings.warn(
        f"simulate: at step {k} (t = {t1:g} s) the energy balance residual {residual:.3g} "
        f"J is {abs(residual) / scale:.2g} of the energy scale "
        f"{scale:.3g} J: the energy ledger is inaccurate at dt = {dt:g} s "
        f"(axial chain modes faster than 1 / dt, typically with winches, or an unstable "
        f"explicit step); halve dt to "
        f"check the motion", EnergyBalanceWarning, stacklevel=stacklevel)


def carried_energy(m: LumpedMassModel, m_prev: LumpedMassModel, frame: Frame,
                   v: NDArray[np.float64], dmu: NDArray[np.float64]) -> float:
    """sum dmu |v|^2 of the interior nodes and the half masses at B_i [J * 2]."""
    nf = m.n_free
    tw = twist_of(m, v)
    dhalf = 0.5 * (m.node_masses - m_prev.node_masses)
    vB = tw[:3] + cross(tw[3:], frame.r)
    return float(dmu @ v[nf:] ** 2 + dhalf @ np.sum(vB ** 2, axis=1))


class Ledger:
    """Running energy balance E - E0 = W_ext - D + W_w + E_c + residual (module notes)."""

    def __init__(self, E0: float, V_eq: float, elastic0: float) -> None:
        self.E0 = E0
        self.excess = abs(E0 - V_eq)
        self.floor = 1e-3 * elastic0          # for runs that start at rest, unloaded
        self.ext = self.winch = self.carried = self.diss = 0.0
        self.peaks = np.zeros(4)
        self.warned = False

    def track(self) -> None:
        """Update the peaks of the work terms (the energy scale) at a step without a row."""
        p = self.peaks
        p[0], p[1] = max(p[0], abs(self.ext)), max(p[1], abs(self.winch))
        p[2], p[3] = max(p[2], abs(self.carried)), max(p[3], abs(self.diss))

    def row(
            self, kinetic: float,
            pot: tuple[float, float, NDArray[np.float64], NDArray[np.float64], list[tuple[int,
                       int]], float],
    ) -> tuple[float, ...]:
        """(kinetic, gravity, elastic, ext, winch, carried, dissipated, residual) [J]."""
        self.track()
        E = kinetic + pot[0] + pot[1]
        res = E - self.E0 - (self.ext - self.diss + self.winch + self.carried)
        return (kinetic, pot[1], pot[0], self.ext, self.winch, self.carried, self.diss, res)

    def scale(self) -> float:
        """Energy scale of the run so far [J] (as EnergyBalance.scale)."""
        return self.excess + float(self.peaks.sum())

    def limit(self) -> float:
        """Energy scale with its floor [J]: the reference of the blow-up test."""
        return self.scale() + self.floor


class Recorder:
    def __init__(self, n_rec: int, n: int, model: LumpedMassModel, nodes: bool) -> None:
        self.t = np.empty(n_rec)
        self.pose = np.empty((n_rec, 6))
        self.vel = np.empty((n_rec, 6))
        self.t_end = np.empty((n_rec, n))
        self.t_anchor = np.empty((n_rec, n))
        self.L = np.empty((n_rec, n))
        self.E = np.empty((n_rec, 8))
        self.nodes = [np.empty((n_rec, N + 1, 3)) for N in model.segments] if nodes else None

    def store(
            self, j: int, t: float, pose: FastPose, v: NDArray[np.float64], model: LumpedMassModel,
            pot: tuple[float, float, NDArray[np.float64], NDArray[np.float64], list[tuple[int,
                       int]], float],
            row: tuple[float, ...], X: NDArray[np.float64],
    ) -> None:
        self.t[j] = t
        self.pose[j] = pose.as_vector()
        self.vel[j] = twist_of(model, v)
        self.t_end[j], self.t_anchor[j] = pot[2], pot[3]
        self.L[j] = model.unstretched_lengths
        self.E[j] = row
        if self.nodes is not None:
            self.store_nodes(j, pose, model, X)

    def store_nodes(self, j: int, pose: FastPose, model: LumpedMassModel,
                    X: NDArray[np.float64]) -> None:
        B, _ = model.robot.attachment_points(pose)
        for i, xi in enumerate(interior_views(model, X)):
            self.nodes[i][j] = np.vstack((model.robot.anchors[i], xi, B[i]))

    def result(self, model: LumpedMassModel, eq_pose: Pose, static_energy: float,
               **info: float | str) -> TimeResponse:
        self.E.setflags(write=False)
        energy = EnergyBalance(*self.E.T, static_energy=static_energy)
        out = [self.t, self.pose, self.vel, self.t_end, self.t_anchor, self.L, energy]
        for a in out[:-1] + (self.nodes or []):
            a.setflags(write=False)
        return TimeResponse(*out, nodes=None if self.nodes is None else tuple(self.nodes),
                            free_dofs=model.free_dofs, equilibrium_pose=eq_pose.as_vector(),
                            **info)


#: Steps per call of the compiled explicit run (its load table: 1.5 MB).
_BLOCK = 32768


def excitation_loads(excitation: Callable[..., Any] | None, table, free: NDArray[np.bool_],
                     dt: float, k0: int, k1: int) -> NDArray[np.float64]:
    """External loads at the end of steps k0 + 1 ... k1, shape (k1 - k0, 6), held DOFs 0 (or
    (0, 6) without excitation): the table interpolated at all steps at once, or the callable
    called step by step (checked as :func:`load_at`)."""
    if excitation is None:
        return np.zeros((0, 6))
    times = np.arange(k0 + 1, k1 + 1) * dt
    n_steps = times.size
    if table is not None:
        loads = np.column_stack([np.interp(times, table[0], table[1][:, j]) for j in range(6)])
    else:
        loads = np.array([load_at(excitation, t) for t in times]).reshape(n_steps, 6)
    loads[:, ~free] = 0.0
    return loads


def _six(model: LumpedMassModel, x: NDArray[np.float64]) -> NDArray[np.float64]:
    """The free-DOF part of x as a full 6-vector (0 on the held DOFs)."""
    out = np.zeros(6)
    out[model.free_index] = x[:model.n_free]
    return out


def _kernel_arguments(
        dyn: Dynamics, pose: FastPose, X: NDArray[np.float64], v: NDArray[np.float64],
        a: NDArray[np.float64], fe: NDArray[np.float64], fd: NDArray[np.float64], rec: Recorder,
        ledger: Ledger,
) -> tuple[NDArray[np.bool_], tuple[NDArray[np.float64], ...], tuple[NDArray[Any], ...],
           tuple[NDArray[Any], ...]]:
    """(free (6,) bool, state, constants, tail) of the compiled runs: the state arrays as
    in :func:`dynstiff.compiled.chain_run.explicit_run`, the model's constants from free
    to K0, then the ledger, counters and records (ledger, info, out, records, rec_X)."""
    m = dyn.model
    rob, p = m.robot, m.robot.platform
    nf = m.n_free
    free = np.zeros(6, dtype=bool)
    free[m.free_index] = True
    state = (np.array(pose.position, dtype=float), np.array(pose.rotation, dtype=float),
             np.array(X, dtype=float), _six(m, v), v[nf:].copy(), _six(m, a), a[nf:].copy(),
             _six(m, fe), _six(m, fd), fd[nf:].copy())
    led = np.array([ledger.E0, ledger.excess, ledger.floor, ledger.ext, ledger.diss,
                    ledger.peaks[0], ledger.peaks[3]])
    rec_X = np.empty((rec.t.size if rec.nodes is not None else 0, X.size))
    if dyn.beta:
        K = dyn.K0.tocsr()
        K0 = (K.indptr.astype(np.int64), K.indices.astype(np.int64), K.data.astype(float))
    else:
        K0 = (np.zeros(1, dtype=np.int64), np.zeros(0, dtype=np.int64), np.zeros(0))
    consts = (free, rob.anchors.astype(float), rob.attachments.astype(float), dyn.seg,
              m.segment_lengths, dyn.EA, np.asarray(dyn.c_ax, dtype=float), dyn.node_weights,
              dyn.platform_weight, m.node_masses, float(rob.g), float(p.mass),
              np.asarray(p.center_of_mass, dtype=float), np.asarray(p.inertia, dtype=float),
              dyn.mu, float(dyn.alpha), np.asarray(dyn.c_visc, dtype=float), dyn.cv,
              float(dyn.beta), K0)
    tail = (led, np.zeros(5, dtype=np.int64), np.zeros(5), rec.pose, rec.vel, rec.t_end,
            rec.t_anchor, rec.E, rec_X)
    return free, state, consts, tail


def compiled_explicit_run(fast: Any, dyn: Dynamics, pose: FastPose, X: NDArray[np.float64],
                          v: NDArray[np.float64], a: NDArray[np.float64], fe: NDArray[np.float64],
                          fd: NDArray[np.float64], dt: float, n_steps: int, record_every: int,
                          rec: Recorder, ledger: Ledger, damping: TimeDamping, slack_warning: type,
                          table) -> int:
    """The velocity-Verlet steps of a run with fixed lengths (any damping, any N per cable)
    in calls of ``_BLOCK`` steps of the compiled kernel
    (:func:`dynstiff.compiled.chain_run.explicit_run`, theory.md §14.5), records, ledger
    rows and checks included; the warnings and the failure it reports are raised here as in
    the stepwise loop. ``table``: the excitation as (times, loads), or None. Returns the
    number of steps with a slack segment."""
    free, state, consts, tail = _kernel_arguments(dyn, pose, X, v, a, fe, fd, rec, ledger)
    k, status = 0, 0
    while k < n_steps and not status:
        k1 = min(n_steps, k + _BLOCK)
        status, k = fast.explicit_run((k, k1, n_steps), dt, record_every, state,
                                      excitation_loads(dyn.excitation, table, free, dt, k, k1),
                                      *consts, *tail)
    return finish_compiled_run(status, k, tail, ledger, rec, dyn.model, dt, record_every,
                               damping, slack_warning, "explicit")


def _lu_arrays(lu: Any) -> tuple[NDArray[Any], ...]:
    """The SuperLU factors as arrays for compiled_chain._lu_solve (L, U in CSR, perms)."""
    L, U = lu.L.tocsr(), lu.U.tocsr()
    return (L.indptr.astype(np.int64), L.indices.astype(np.int64), L.data.astype(float),
            U.indptr.astype(np.int64), U.indices.astype(np.int64), U.data.astype(float),
            lu.perm_r.astype(np.int64), lu.perm_c.astype(np.int64))


def compiled_implicit_run(fast: Any, dyn: Dynamics, pose: FastPose, X: NDArray[np.float64],
                          v: NDArray[np.float64], a: NDArray[np.float64], fe: NDArray[np.float64],
                          fd: NDArray[np.float64], dt: float, n_steps: int, record_every: int,
                          rec: Recorder, ledger: Ledger, damping: TimeDamping, slack_warning: type,
                          table, newton: StepNewton) -> int:
    """The Newmark steps of a run with fixed lengths in calls of the compiled kernel
    (:func:`dynstiff.compiled.chain_run.implicit_run`, theory.md §14.6): Newton with the
    kept LU factors runs in the kernel; when they are missing or Newton slows down, the
    kernel returns, the Newton matrix is assembled and factorised here (as in
    :func:`implicit_step`) and the kernel resumes the same step. Records, ledger, checks,
    warnings and failures as in the stepwise loop. Returns the number of steps with a slack
    segment."""
    import scipy.sparse.linalg
    m = dyn.model
    free, state, consts, tail = _kernel_arguments(dyn, pose, X, v, a, fe, fd, rec, ledger)
    nx = state[2].size
    state = state + (np.zeros(6), np.zeros(nx), np.zeros(6), np.zeros(nx))
    counters = (np.zeros(5, dtype=np.int64), np.zeros(1))
    z = np.zeros(1, dtype=np.int64)
    lu = (z, z[:0], np.zeros(0), z, z[:0], np.zeros(0), z[:0], z[:0])
    arm, weight = m.residual_scales()
    k, status = 0, 0
    while k < n_steps and not status:
        k1 = min(n_steps, k + _BLOCK)
        loads = excitation_loads(dyn.excitation, table, free, dt, k, k1)
        start = k
        while True:
            status, k = fast.implicit_run(
                (start, k1, n_steps), dt, record_every, state, counters,
                loads[start - (k1 - loads.shape[0]):] if loads.shape[0] else loads, *consts,
                lu, newton.tol, newton.max_iter, arm, weight, *tail)
            if status != 5:
                break
            d = np.concatenate([state[12][m.free_index], state[13]])
            pose1, X1 = advance(m, FastPose(state[0].copy(), state[1].copy()), state[2], d)
            lu = _lu_arrays(scipy.sparse.linalg.splu(dyn.newton_matrix(pose1, X1, dt)))
            newton.updates += 1
            counters[0][0] = counters[0][3] = 1
            start = k - 1
    newton.iterations += int(counters[0][2])
    slack_steps = finish_compiled_run(0 if status == 4 else status, k, tail, ledger, rec, m,
                                      dt, record_every, damping, slack_warning, "implicit")
    if status == 4:
        res = counters[1][0]
        raise ConvergenceError(
            f"simulate: Newton did not converge in {newton.max_iter} iterations at step "
            f"{k} (t = {k * dt:g} s) with dt = {dt:g} s: relative residual {res:.3e} > tol "
            f"{newton.tol:g}; reduce dt (slack snapping or a blow-up)", residual=res)
    return slack_steps


def finish_compiled_run(status: int, step: int, tail: tuple[NDArray[Any], ...], ledger: Ledger,
                        rec: Recorder, m: LumpedMassModel, dt: float, record_every: int,
                        damping: TimeDamping, slack_warning: type, scheme: str) -> int:
    """After a compiled run: the ledger back, the warnings in the order of their steps, the
    failure the kernel reported, the record times, lengths and nodes. Returns the number of
    steps with a slack segment."""
    led, info, out, rec_X = tail[0], tail[1], tail[2], tail[-1]
    slack_steps, slack_step, cable, segment, warn_step = (int(x) for x in info)
    strain, residual, _, warn_res, warn_scale = out
    ledger.ext, ledger.diss = led[3], led[4]
    ledger.peaks[0], ledger.peaks[3] = led[5], led[6]
    events = []                                   # warnings in the order of their steps
    if warn_step:
        events.append((warn_step, 0, lambda: ledger_warning(warn_step, warn_step * dt,
                                                            warn_res, warn_scale, dt, 6)))
    if slack_step:
        events.append((slack_step, 1, lambda: warnings.warn(
            f"simulate: cable {cable} segment {segment} went slack at step {slack_step} "
            f"(t = {slack_step * dt:g} s); tension-only springs carry no force until it is "
            f"taut again", slack_warning, stacklevel=5)))  # user > simulate > run > here
    for *_, warn in sorted(events, key=lambda e: e[:2]):
        warn()
    ledger.warned = ledger.warned or warn_step > 0
    if status == 1:
        raise IntegrationError(
            f"simulate: non-finite state at step {step} (t = {step * dt:g} s) with {scheme} "
            f"dt = {dt:g} s; the predicted stability limit is "
            f"{explicit_step_limit(m, damping=damping):g} s (theory.md §7.3)"
            if scheme == "explicit" else
            f"simulate: non-finite state at step {step} (t = {step * dt:g} s) with {scheme} "
            f"dt = {dt:g} s", step=step, time=step * dt, dt=dt)
    if status:
        check_blow_up(strain, residual, ledger, scheme, dt, step, step * dt, m, damping, 5)
    n_rec = rec.t.size
    rec.t[1:] = np.arange(1, n_rec) * record_every * dt
    rec.L[1:] = m.unstretched_lengths
    if rec.nodes is not None:
        for j in range(1, n_rec):
            p6 = rec.pose[j]
            rec.store_nodes(j, FastPose(p6[:3], p6[3:]), m, rec_X[j])
    return slack_steps
