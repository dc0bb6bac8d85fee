"""Time-domain simulation of the lumped-mass robot: nonlinear free and forced vibration,
winches, energy bookkeeping (theory.md §7.3).

The equations of motion are those of :class:`~dynstiff.lumped.LumpedMassModel` (theory.md
§7.1) without linearisation: point masses m l0 at the interior nodes, tension-only springs
EA / l0 (no force while l < l0), gravity, and the rigid platform (any free-DOF subset, large
rotations) carrying the half node masses m l0 / 2 at the attachment points B_i::

    M(q) a = R(q) + f_ext(t) + f_d(q, v) - g(q, v)

R is the model's own residual (``LumpedMassModel.residual_unchecked``: spring forces, gravity, the
platform wrench about P) and its tangent K = -dR/dx
(``LumpedMassModel.tangent_unchecked``) drives the
Newton iterations; no second force assembly is written here.

Notation (theory.md §4, §7.1)
-----------------------------
=================  ==============================================================  ==========
symbol             meaning                                                         unit
=================  ==============================================================  ==========
q                  configuration: platform pose (p, R_p) and interior node positions  m, --
x, dx              DOF vector of the model (free platform DOFs, then interior nodes); m, rad
                   dx = (dp, dtheta, du): dtheta a rotation-vector increment, base
v = (v_P, w, u')   platform velocity of P, angular velocity (base frame), node      m/s, rad/s
                   velocities
a                  the matching accelerations                                      m/s^2, ...
M(q)               lumped mass: m l0 per interior node; M_p + sum J^T (m l0/2) J    kg, kg m^2
g(q, v)            centripetal and gyroscopic terms of the platform and of the      N, N m
                   half node masses: [w x (w x S); w x (I_P w)], S first moment,
                   I_P inertia about P (of the body plus the masses m l0/2 at B_i)
f_d                damping: -alpha M v - beta K_0 v - C_visc v - axial dashpots    N, N m
c_ax               axial dashpot of every segment, force c_ax d(epsilon)/dt         N s
dt, beta_N         time step, Newmark parameters beta_N = 1/4, gamma_N = 1/2        s, --
=================  ==============================================================  ==========

Schemes
-------
``"implicit"``: Newmark average acceleration (trapezoidal rule), unconditionally stable
for the linearised system and free of numerical damping, solved by Newton's method with the
sparse tangent K + 4 M / dt^2 + 2 C / dt (the LU factors are kept while Newton converges
fast and refreshed when it slows down). The displacement update is dx = dt v_n +
dt^2 / 4 (a_n + a_{n+1}); the platform rotation is composed exactly,
R_{n+1} = exp([dtheta]x) R_n (unit quaternions), so large rotations are integrated
properly (a Lie-group Newmark scheme with the angular velocity in the base frame; the
Newton matrix neglects the derivatives of M(q) and g(q, v), which slows the iterations for
fast rotations but does not change their solution).

``"energy"``: the momentum balance at the mid-step with the discrete gradient of the
elastic and gravity energy between the two configurations (theory.md §7.3,
:mod:`dynstiff.timedomain.energy_scheme`): the segments' energy is conserved to the Newton
tolerance whatever the step, through slack and snap, where the trapezoidal rule's force at
the end of a step that crosses l = l0 misses the kink of the tension law and feeds the
snaps; a step whose Newton iteration fails is retried as two halves. Equal to
``"implicit"`` for a linear system; not compiled (a Python loop).

``"explicit"``: velocity Verlet (central differences), stable for dt < l0 / sqrt(EA / m),
the period of the highest axial chain mode (theory.md §7.3, :func:`explicit_step_limit`);
velocity-dependent forces use the half-step velocity.

Winches (``lengths=``): every cable keeps its N_i segments and l0_i(t) = L0_i(t) / N_i, so
stiffness EA / l0, node mass m l0 and the platform's share m l0 / 2 all follow L0_i(t). The
paid-out mass is spread over the nodes (the chain stretches in material coordinates) and
joins each node at that node's velocity: no thrust, and the axial transport velocity of the
material (of order dL0/dt) is neglected. The energy balance then counts

* the work of the winch, W_w = int dV/dL0 . dL0/dt dt, V the elastic + gravity potential
  (exact for this discretisation; per cable dV/dL0 = (1/N) sum_s (-T_s - T_s^2 / 2EA) +
  (m g / N)(sum_j z_j + z_B / 2)). For a chain in static equilibrium -T + m g z is constant
  along the cable (dT = m g dz), so W_w tends to int (-T_A + m g z_A) dL0/dt dt: the anchor
  tension times the paid-out rate plus the potential energy of the mass entering at the
  anchor height;
* the kinetic energy carried in with the mass, int 1/2 sum_j dmu_j/dt |v_j|^2 dt.

Energy bookkeeping (the work terms every step; the energies, a pass over every segment, at
the recorded steps, at the last one and, with winches, every step; theory.md §14.4)::

    E(t) - E(0) = W_ext - D + W_w + E_c + residual

E = kinetic + gravity (z from the base origin) + elastic sum EA / (2 l0) (l - l0)_+^2;
W_ext = sum dx . (f_ext,n + f_ext,n+1) / 2 (moments times the rotation increment);
D = -sum dx . (f_d,n + f_d,n+1) / 2, exactly the energy the scheme's damping forces remove.
For a linear system with constant mass the trapezoidal rule makes the residual vanish; here
it measures the trapezoidal quadrature of the nonlinear spring forces, of the rotating
platform and of the winch terms, and the Newton tolerance.

Not modelled: the cable's hysteretic ``loss_factor`` (a frequency-domain idealisation; use
``TimeDamping(axial=...)``), contact, bending, and the axial transport velocity of paid-out
material.

Code: this module checks the inputs and runs the loop; ``damping`` holds the damping
options and the explicit step limit, ``dynamics`` the forces, mass and Newton matrix,
``stepping`` the implicit and explicit steps, the blow-up checks and the energy ledger,
``energy_scheme`` the energy-consistent step and its step control, ``discrete_gradient``
its forces.
"""

from __future__ import annotations

import time as _time
import warnings
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import compiled
from dynstiff._validate import flag, positive_scalar
from dynstiff.cable.lumped_chain import chain_equilibrium
from dynstiff.errors import (
    ConvergenceError,
    DynstiffWarning,
    InvalidParameterError,
    SlackCableError,
)
from dynstiff.models.lumped import LumpedLinearModel
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.models.lumped_statics import LumpedEquilibrium
from dynstiff.timedomain.damping import TimeDamping, explicit_step_limit
from dynstiff.timedomain.dynamics import (
    Dynamics,
    FastPose,
    Frame,
    load_at,
    model_at,
    node_mass_vector,
    potential_energy,
)
from dynstiff.timedomain.energy_scheme import EnergyStepper
from dynstiff.timedomain.inputs import (
    excitation_function,
    initial_state,
    lengths_function,
    step_count,
)
from dynstiff.timedomain.response import EnergyBalance, Spectrum, TimeResponse
from dynstiff.timedomain.stepping import (
    EnergyBalanceWarning,
    IntegrationError,
    Ledger,
    Recorder,
    StepNewton,
    carried_energy,
    check_blow_up,
    compiled_explicit_run,
    compiled_implicit_run,
    explicit_step,
    implicit_step,
)

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import NDArray

__all__ = [
    "simulate", "TimeResponse", "EnergyBalance", "Spectrum", "TimeDamping", "IntegrationError",
    "SlackSegmentWarning", "TimeStepWarning", "EnergyBalanceWarning", "explicit_step_limit"
]

_SCHEMES = ("implicit", "explicit", "energy")


class SlackSegmentWarning(DynstiffWarning, RuntimeWarning):
    """A cable segment went slack (l < l0, zero tension) during a simulation."""

class TimeStepWarning(DynstiffWarning, RuntimeWarning):
    """The explicit scheme was asked for a step above its predicted stability limit."""


# -------------------------------------------------------------------------- simulate
def simulate(
        model: LumpedLinearModel | LumpedMassModel, t_end: float, dt: float,
        excitation: Callable[..., Any] | None = None, lengths: Callable[..., Any] | None = None,
        scheme: str = "implicit",
        initial: list[float] | tuple[NDArray[np.float64] | list[float], list[float]] | None = None,
        damping: TimeDamping | None = None, record_every: int = 1, *, record_nodes: bool = False,
        tol: float = 1e-9, max_iter: int = 25, start: LumpedEquilibrium | None = None,
        max_records: int = 1_000_000,
) -> TimeResponse:
    """Integrate the nonlinear equations of motion of the lumped-mass robot.

    Starts from a static equilibrium (``start``, or the equilibrium for ``lengths(0)``),
    optionally displaced by ``initial``, and steps with a
    constant ``dt``. See the module notes for the equations, schemes, winch model and
    energy bookkeeping.

    Parameters
    ----------
    model : LumpedMassModel or LumpedLinearModel
        The lumped-mass robot; a linearised one (the "lumped" rung) also gives the default
        ``start``, its own equilibrium.
    t_end : float
        Duration [s], > 0; ``ceil(t_end / dt)`` steps are taken.
    dt : float
        Time step [s], > 0. The implicit scheme is stable for any dt (its accuracy needs
        about 20 steps per period of interest); the explicit one needs
        dt < :func:`explicit_step_limit`.
    excitation : callable or (times, loads), optional
        t [s] -> platform load (fx, fy, fz [N], mx, my, mz [N m]) about P, base axes,
        shape (6,), or a table (times (k,) [s] strictly increasing, from t <= 0; loads
        (k, 6)) interpolated linearly and held after its end (the compiled explicit run
        evaluates a table at all steps at once, a callable step by step); loads on held
        DOFs are ignored.
    lengths : callable or (times, lengths), optional
        Unstretched lengths L0_i(t) [m], shape (n_cables,), as a callable or a table
        (times (k,) [s] strictly increasing, from t <= 0; lengths (k, n_cables) [m]),
        interpolated linearly and held after its end. Default: the model's, fixed.
    scheme : {"implicit", "explicit", "energy"}
        "energy" steps through slack segments and snaps with the energy conserved (the
        choice when cables go slack); see the module notes.
    initial : array_like, optional
        Platform offset (6,) [m, rad] from the equilibrium (rotation vector composed with
        the equilibrium rotation; interior nodes in static equilibrium for the displaced
        platform), or a pair (offset, velocity), velocity (6,) [m/s, rad/s] the platform
        twist (v_P, w) right after an impulse (cable nodes at rest). Held DOFs must be 0.
    damping : TimeDamping, optional
        Rayleigh and axial-dashpot damping; the cables' ``viscous_damping`` always acts.
    record_every : int
        Record every k-th step (the start is always recorded) [-], >= 1.
    record_nodes : bool
        Also record all node positions (memory n_records x sum (N_i + 1) x 3 floats).
    tol : float
        Newton tolerance on the largest unbalanced force relative to the force scale
        (as :meth:`LumpedMassModel.equilibrium`).
    max_iter : int
        Newton iterations per step before a :class:`ConvergenceError`.
    max_records : int
        Largest number of recorded time steps, ceil(t_end / dt) / record_every + 1 (a guard
        on memory: each record holds the pose, velocity and tensions); raise it, or
        ``record_every``, for longer runs.
    start : LumpedEquilibrium, optional
        Equilibrium of ``model`` to start from (default: that of a LumpedLinearModel,
        otherwise ``model.equilibrium()``). With ``lengths``, its pose starts the search
        for the equilibrium at ``lengths(0)``.

    Returns
    -------
    TimeResponse

    Raises
    ------
    InvalidParameterError
        A bad argument (named in the message).
    SlackCableError
        A cable is slack at the start (``lengths`` or ``initial`` too large).
    ConvergenceError
        Newton failed in a step of the implicit scheme (the message gives step, time, dt
        and the residual).
    IntegrationError
        The state blew up: non-finite, a strain above 1, or an energy balance residual
        above 10 times the energy scale of the run (the message names step, time and dt);
        never NaN output.

    Warns
    -----
    SlackSegmentWarning
        Once, when a segment first goes slack (TimeResponse.slack_steps counts them all).
    TimeStepWarning
        ``scheme="explicit"`` with dt above :func:`explicit_step_limit`.
    EnergyBalanceWarning
        Once, when the energy balance residual passes 10 % of the energy scale (an
        inaccurate ledger, e.g. winch work with unresolved axial chain modes).
    """
    wall0 = _time.perf_counter()
    if isinstance(model, LumpedLinearModel):
        start = model.equilibrium if start is None else start
        model = model.mass_model
    if not isinstance(model, LumpedMassModel):
        raise InvalidParameterError(
            f"model must be a LumpedMassModel or LumpedLinearModel, got "
            f"{type(model).__name__}")
    if start is not None and not isinstance(start, LumpedEquilibrium):
        raise InvalidParameterError(
            f"start must be a LumpedEquilibrium (from model.equilibrium()), got "
            f"{type(start).__name__}")
    t_end = positive_scalar("t_end", t_end)
    dt = positive_scalar("dt", dt)
    if dt > t_end:
        raise InvalidParameterError(f"dt must be <= t_end = {t_end:g} s, got {dt:g} s")
    if scheme not in _SCHEMES:
        raise InvalidParameterError(f"scheme must be one of {_SCHEMES}, got {scheme!r}")
    record_nodes = flag("record_nodes", record_nodes)
    for name, val in (("record_every", record_every), ("max_iter", max_iter)):
        if isinstance(val, bool) or not isinstance(val, Integral) or val < 1:
            raise InvalidParameterError(f"{name} must be an integer >= 1, got {val!r}")
    if isinstance(max_records, bool) or not isinstance(max_records, Integral) or \
            max_records < 1:
        raise InvalidParameterError(f"max_records must be an integer >= 1, got {max_records!r}")
    n_records = step_count(t_end, dt) // record_every + 1
    if n_records > max_records:
        raise InvalidParameterError(
            f"t_end = {t_end:g} s at dt = {dt:g} s with record_every = {record_every} makes "
            f"{n_records} records, more than max_records = {max_records}; raise record_every "
            f"or max_records, or shorten t_end")
    tol = positive_scalar("tol", tol)
    excitation, table = excitation_function(excitation)
    if excitation is not None:
        load_at(excitation, 0.0)
    if damping is None:
        damping = TimeDamping()
    if not isinstance(damping, TimeDamping):
        raise InvalidParameterError(
            f"damping must be a TimeDamping or None, got {type(damping).__name__}")
    n = model.robot.n_cables
    damping.axial_per_cable(n)
    length_fn = lengths_function(lengths, n)
    offset, velocity = initial_state(initial, model)

    # ---- start: static equilibrium at L0(0), then the offset
    L_prev = model.unstretched_lengths if length_fn is None else length_fn(0.0)
    m = model_at(model, L_prev)
    try:
        if m is model:
            eq = model.equilibrium() if start is None else start
        else:
            eq = m.equilibrium(initial_pose=None if start is None else start.pose)
    except (SlackCableError, ConvergenceError) as exc:
        what = "lengths(0)" if length_fn is not None else "the model's unstretched_lengths"
        raise SlackCableError(
            f"simulate: no taut static equilibrium for {what} = {L_prev.tolist()} m: "
            f"{exc}") from None
    pose = eq.pose.moved(offset) if np.any(offset) else eq.pose
    pose = FastPose(pose.position, pose.rotation)
    rob = m.robot
    if np.any(offset):
        B, _ = rob.attachment_points(pose)
        try:
            X = np.concatenate([chain_equilibrium(
                rob.anchors[i], B[i], m.unstretched_lengths[i], rob.cables[i],
                int(m.segments[i]), rob.g).nodes[1:-1].ravel() for i in range(n)])
        except (SlackCableError, ConvergenceError) as exc:
            raise SlackCableError(
                f"simulate: initial offset {offset.tolist()} leaves a cable without a taut "
                f"equilibrium: {exc}") from None
    else:
        X = np.concatenate([x.ravel() for x in eq.interior])
    v = np.zeros(m.n_dof)
    v[:m.n_free] = velocity[m.free_index]

    K0 = None
    if damping.beta:
        K0 = m.tangent_unchecked(eq.pose, eq.interior, lambda i: 1.0)
        K0 = (0.5 * (K0 + K0.T)).tocsr()
    dyn = Dynamics(m, damping, K0, excitation)
    V_eq = potential_energy(m, Frame(m, eq.pose), np.concatenate(
        [x.ravel() for x in eq.interior]))
    F, fe, fd, t_max, frame = dyn.forces(pose, X, v, 0.0)
    pot = potential_energy(m, frame, X)
    if pot[5] > 1.0:
        raise InvalidParameterError(
            f"simulate: the start stretches a segment to strain {pot[5]:.3g} (> 1): "
            f"{'initial offset ' + str(offset.tolist()) if np.any(offset) else 'lengths(0)'} "
            f"is far outside the cables' elastic range; give a smaller one")
    if pot[4]:
        i, s = pot[4][0]
        raise SlackCableError(
            f"simulate: cable {i} segment {s} is slack at the start "
            f"({'initial offset ' + str(offset.tolist()) if np.any(offset) else 'lengths'})")
    a = dyn.accelerations(frame, F)
    limit = explicit_step_limit(m, damping=damping)
    if scheme == "explicit" and dt > limit:
        warnings.warn(
            f"simulate: explicit dt = {dt:g} s exceeds the predicted stability limit "
            f"{limit:g} s (l0 / sqrt(EA / m), reduced by damping; theory.md §7.3); expect a "
            f"blow-up",
            TimeStepWarning, stacklevel=2)

    # ---- stepping
    n_steps = step_count(t_end, dt)
    rec = Recorder(n_steps // record_every + 1, n, m, record_nodes)
    ledger = Ledger(dyn.kinetic(frame, v) + pot[0] + pot[1], V_eq[0] + V_eq[1], pot[0])
    rec.store(0, 0.0, pose, v, m, pot, ledger.row(dyn.kinetic(frame, v), pot), X)
    newton = StepNewton(tol, max_iter)
    stepper = EnergyStepper(dyn, m, length_fn, newton) if scheme == "energy" else None
    slack_steps = 0
    fast = compiled.load("chain_run")
    if scheme == "explicit" and fast is not None and length_fn is None:
        slack_steps = compiled_explicit_run(fast, dyn, pose, X, v, a, fe, fd, dt, n_steps,
                                            record_every, rec, ledger, damping,
                                            SlackSegmentWarning, table)
        n_steps_done = n_steps
    elif scheme == "implicit" and fast is not None and length_fn is None:
        slack_steps = compiled_implicit_run(fast, dyn, pose, X, v, a, fe, fd, dt, n_steps,
                                            record_every, rec, ledger, damping,
                                            SlackSegmentWarning, table, newton)
        n_steps_done = n_steps
    else:
        n_steps_done = 0
    for k in range(n_steps_done + 1, n_steps + 1):
        t1 = k * dt
        m_prev = m
        if length_fn is not None and stepper is None:
            m = model_at(model, length_fn(t1))
            dyn.set_model(m)
        if stepper is not None:
            (pose1, X1, v1, a1, fe1, fd1, frame1), work = stepper.step(
                pose, X, v, fe, fd, frame, t1 - dt, dt, k)
            m = dyn.model
        else:
            step = implicit_step if scheme == "implicit" else explicit_step
            d, pose1, X1, v1, a1, fe1, fd1, frame1 = step(dyn, pose, X, v, a, t1, dt, k,
                                                          newton)
        # ---- bookkeeping and checks: strain and slack from the step's own force
        # evaluation at every step; the energies (a pass over every segment) where a record,
        # a winch term, a slack segment or the end of the run needs them
        t_min, strain = dyn.extremes
        if stepper is not None:                  # the scheme's own ledger of its sub-steps
            ledger.ext += work[0]
            ledger.diss += work[1]
            ledger.winch += work[2]
            ledger.carried += work[3]
        else:
            ledger.ext += 0.5 * d @ (fe + fe1)
            ledger.diss -= 0.5 * d @ (fd + fd1)
        record = k % record_every == 0
        pot1 = None
        if record or length_fn is not None or t_min <= 0.0 or k == n_steps:
            pot1 = potential_energy(m, frame1, X1)
        if m is not m_prev and stepper is None:
            ledger.winch += 0.5 * (
                sum(potential_energy(m, frame, X)[:2]) - pot[0] - pot[1]
                + pot1[0] + pot1[1] - sum(potential_energy(m_prev, frame1, X1)[:2]))
            dmu = node_mass_vector(m) - node_mass_vector(m_prev)
            ledger.carried += 0.25 * (carried_energy(m, m_prev, frame, v, dmu)
                                      + carried_energy(m, m_prev, frame1, v1, dmu))
        if pot1 is None:
            ledger.track()
            check_blow_up(strain, 0.0, ledger, scheme, dt, k, t1, m, damping)
        else:
            row = ledger.row(dyn.kinetic(frame1, v1), pot1)
            check_blow_up(pot1[5], row[-1], ledger, scheme, dt, k, t1, m, damping)
        if pot1 is not None and pot1[4]:
            slack_steps += 1
            if slack_steps == 1:
                i, s = pot1[4][0]
                warnings.warn(
                    f"simulate: cable {i} segment {s} went slack at step {k} (t = {t1:g} s); "
                    f"tension-only springs carry no force until it is taut again",
                    SlackSegmentWarning, stacklevel=2)
        pose, X, v, a, fe, fd, frame, pot = pose1, X1, v1, a1, fe1, fd1, frame1, pot1
        if record:
            rec.store(k // record_every, t1, pose, v, m, pot, row, X)
    return rec.result(
        model=model, scheme=scheme, dt=dt, n_steps=n_steps, eq_pose=eq.pose,
        newton_iterations=newton.iterations, jacobian_updates=newton.updates,
        slack_steps=slack_steps, explicit_limit=limit,
        wall_time=_time.perf_counter() - wall0, static_energy=V_eq[0] + V_eq[1],
        record_every=record_every, substeps=0 if stepper is None else stepper.substeps)
