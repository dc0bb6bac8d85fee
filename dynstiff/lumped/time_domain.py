"""Time-domain simulation of the lumped-mass robot: nonlinear free and forced vibration,
winches, energy bookkeeping (theory.md §7.3).

The equations of motion are those of :class:`~dynstiff.lumped.LumpedMassModel` (theory.md
§7.1) without linearisation: point masses m l0 at the interior nodes, tension-only springs
EA / l0 (no force while l < l0), gravity, and the rigid platform (any free-DOF subset, large
rotations) carrying the half node masses m l0 / 2 at the attachment points B_i::

    M(q) a = R(q) + f_ext(t) + f_d(q, v) - g(q, v)

R is the model's own residual (``LumpedMassModel._residual``: spring forces, gravity, the
platform wrench about P) and its tangent K = -dR/dx (``LumpedMassModel._tangent``) drives the
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
R_{n+1} = exp([dtheta]x) R_n (scipy ``Rotation``), so large rotations are integrated
properly (a Lie-group Newmark scheme with the angular velocity in the base frame; the
Newton matrix neglects the derivatives of M(q) and g(q, v), which slows the iterations for
fast rotations but does not change their solution).

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

Energy bookkeeping (every step, stored at the recorded ones)::

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
"""

import functools
import time as _time
import warnings
from dataclasses import dataclass
from numbers import Integral

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from .._validate import positive_scalar
from ..errors import ConvergenceError, DynstiffError, InvalidParameterError, SlackCableError
from ..frf import OUTPUT_NAMES
from ..platform import platform_mass_matrix, skew
from ..robot import Pose
from .chain import chain_equilibrium
from .robot_model import LumpedMassModel, _lever_map, _segments
from .time_response import EnergyBalance, Spectrum, TimeResponse

__all__ = [
    "simulate",
    "TimeResponse",
    "EnergyBalance",
    "Spectrum",
    "TimeDamping",
    "IntegrationError",
    "SlackSegmentWarning",
    "TimeStepWarning",
    "EnergyBalanceWarning",
    "explicit_step_limit",
]

#: A segment stretched beyond this strain means the integration has blown up.
_STRAIN_LIMIT = 1.0
#: Energy balance residual / energy scale above which the integration has blown up, and
#: above which the ledger is reported inaccurate (EnergyBalanceWarning).
_BLOW_UP = 10.0
_LEDGER_WARN = 0.1
_SCHEMES = ("implicit", "explicit")


class IntegrationError(DynstiffError, RuntimeError):
    """The time integration blew up (non-finite state, an absurd strain, or energy created
    beyond the energy scale of the run).

    Attributes ``step``, ``time`` [s] and ``dt`` [s] locate the failure.
    """

    def __init__(self, message, step=None, time=None, dt=None):
        super().__init__(message)
        self.step, self.time, self.dt = step, time, dt


class SlackSegmentWarning(RuntimeWarning):
    """A cable segment went slack (l < l0, zero tension) during a simulation."""


class EnergyBalanceWarning(RuntimeWarning):
    """The energy balance residual passed 10 % of the run's energy scale: the ledger (not
    necessarily the motion) is inaccurate at this dt; halve dt to check."""


class TimeStepWarning(RuntimeWarning):
    """The explicit scheme was asked for a step above its predicted stability limit."""


# ----------------------------------------------------------------------------- damping
@dataclass(frozen=True)
class TimeDamping:
    """Damping of the time-domain model (besides the cables' ``viscous_damping``).

    Parameters
    ----------
    alpha : float
        Mass-proportional Rayleigh coefficient [1/s], >= 0: force -alpha M(q) v.
    beta : float
        Stiffness-proportional Rayleigh coefficient [s], >= 0: force -beta K_0 v, K_0 the
        (symmetrised) tangent stiffness at the starting equilibrium, so the modal damping
        ratio of the linearised model is zeta = alpha / (2 omega) + beta omega / 2.
    axial : float or sequence of float
        Axial dashpot c_ax [N s] of every segment (one value or one per cable), >= 0: the
        force c_ax d(epsilon)/dt acts along a taut segment (none while it is slack), as
        MoorDyn's internal damping ``BA``. Its damping ratio on the highest axial chain
        mode is about c_ax / (l0 sqrt(EA m)).
    """

    alpha: float = 0.0
    beta: float = 0.0
    axial: object = 0.0

    def __post_init__(self):
        object.__setattr__(self, "alpha", positive_scalar("alpha", self.alpha, True))
        object.__setattr__(self, "beta", positive_scalar("beta", self.beta, True))
        c = np.atleast_1d(np.asarray(self.axial, dtype=float))
        if c.ndim != 1 or not np.all(np.isfinite(c)) or np.any(c < 0):
            raise InvalidParameterError(
                f"axial must be a finite dashpot c_ax >= 0 [N s] or one per cable, got "
                f"{self.axial!r}")
        object.__setattr__(self, "axial",
                           tuple(float(x) for x in c) if c.size > 1 else float(c[0]))

    @classmethod
    def rayleigh(cls, zeta, freq1_hz, freq2_hz):
        """Rayleigh damping with ratio ``zeta`` [-] at the two frequencies [Hz]."""
        zeta = positive_scalar("zeta", zeta, True)
        w1 = 2 * np.pi * positive_scalar("freq1_hz", freq1_hz)
        w2 = 2 * np.pi * positive_scalar("freq2_hz", freq2_hz)
        return cls(alpha=2 * zeta * w1 * w2 / (w1 + w2), beta=2 * zeta / (w1 + w2))

    def axial_per_cable(self, n):
        """c_ax of every cable [N s], shape (n,)."""
        if np.ndim(self.axial) == 0:
            return np.full(n, float(self.axial))
        if np.size(self.axial) != n:
            raise InvalidParameterError(
                f"damping.axial must be one value or {n} values (one per cable), got "
                f"{np.size(self.axial)}")
        return np.array(self.axial, dtype=float)


def explicit_step_limit(model, unstretched_lengths=None, damping=None):
    """Predicted stability limit of the explicit scheme [s].

    Central differences are stable for omega_max dt < 2 (sqrt(1 + zeta^2) - zeta), with the
    highest axial chain mode omega_max ~ 2 sqrt(EA / m) / l0 and zeta its damping ratio
    (theory.md §7.3); undamped, dt < l0 / sqrt(EA / m). The exact chain value of omega_max
    is smaller by sin((N - 1) pi / 2N), so the true limit lies slightly above this one.

    Parameters
    ----------
    model : LumpedMassModel
    unstretched_lengths : array_like, shape (n_cables,), optional
        L0_i [m] (default the model's).
    damping : TimeDamping, optional
        Its axial dashpots and Rayleigh terms give zeta = c_ax / (l0 sqrt(EA m)) +
        beta omega_max / 2 + alpha / (2 omega_max) on the highest mode.

    Returns
    -------
    float
        min over the cables [s].
    """
    L0 = model.unstretched_lengths if unstretched_lengths is None else \
        np.asarray(unstretched_lengths, dtype=float)
    cables = model.robot.cables
    EA = np.array([cb.EA for cb in cables])
    mass = np.array([cb.mass_per_length for cb in cables])
    l0 = L0 / model.segments
    dt0 = l0 / np.sqrt(EA / mass)
    if damping is None:
        return float(dt0.min())
    w_max = 2.0 / dt0
    zeta = damping.axial_per_cable(len(cables)) / (l0 * np.sqrt(EA * mass)) \
        + 0.5 * damping.beta * w_max + 0.5 * damping.alpha / w_max
    return float(np.min(dt0 * (np.sqrt(1.0 + zeta ** 2) - zeta)))


# ----------------------------------------------------------------------------- kernels
def _model_at(model, L0):
    """The model with other unstretched lengths (same robot and segments)."""
    if np.array_equal(L0, model.unstretched_lengths):
        return model
    return LumpedMassModel(model.robot, L0, [int(s) for s in model.segments])


def _interior(model, X):
    """Views of the flat interior-node vector X as the model's list of (N_i - 1, 3)."""
    nf = model.n_free
    return [X[o - nf:o - nf + 3 * (N - 1)].reshape(-1, 3)
            for o, N in zip(model._offsets, model.segments)]


class _Pose(Pose):
    """A :class:`Pose` that computes its rotation matrix once (the model's residual, its
    tangent and the platform terms all ask for it)."""

    @functools.cached_property
    def matrix(self):
        """Rotation matrix R_p, shape (3, 3)."""
        return super().matrix


def _advance(model, pose, X, dx):
    """Configuration after the increment dx (rotation composed exactly)."""
    d6 = np.zeros(6)
    d6[model._fi] = dx[:model.n_free]
    if np.any(d6[3:]):
        moved = pose.moved(d6)
        pose = _Pose(moved.position, moved.rotation)
    else:
        new = _Pose(pose.position + d6[:3], pose.rotation)
        if "matrix" in pose.__dict__:                      # same rotation: keep R_p
            new.__dict__["matrix"] = pose.__dict__["matrix"]
        pose = new
    return pose, X + dx[model.n_free:]


def _twist(model, v):
    """Full platform twist (v_P, w), shape (6,), from the free-DOF velocities."""
    t = np.zeros(6)
    t[model._fi] = v[:model.n_free]
    return t


class _Frame:
    """Pose-dependent platform quantities of one model at one pose.

    The rotation-dependent part is copied from ``like`` when the rotation and the model
    are the same (always so for a platform without free rotations).
    """

    def __init__(self, model, pose, like=None):
        rob = model.robot
        if like is not None and like.model is model and \
                np.array_equal(like.rotation, pose.rotation):
            self.__dict__.update(like.__dict__)
            self.B = pose.position + self.r
            self.zG = pose.position[2] + self.rG[2]
            return
        self.model, self.rotation = model, pose.rotation
        self.R = pose.matrix
        self.r = rob.attachments @ self.R.T
        self.B = pose.position + self.r
        self._fi = fi = model._fi
        half = 0.5 * model._node_mass
        Mp = platform_mass_matrix(rob.platform, self.R)
        hr = half @ self.r                                  # sum (m l0 / 2) r_i
        S = skew(hr)
        Mp[:3, :3] += half.sum() * np.eye(3)
        Mp[:3, 3:] -= S
        Mp[3:, :3] += S
        # - sum h [r]x [r]x = sum h (|r|^2 I - r r^T)
        Mp[3:, 3:] += (half @ np.sum(self.r ** 2, axis=1)) * np.eye(3) \
            - np.einsum("i,ij,ik->jk", half, self.r, self.r)
        self.M6 = Mp                                   # body + half node masses about P
        self.Mff = Mp[np.ix_(fi, fi)]
        self.rG = rG = self.R @ rob.platform.center_of_mass
        self.first_moment = rob.platform.mass * rG + hr
        self.zG = pose.position[2] + rG[2]

    @property
    def J(self):
        """Lever maps J_i restricted to the free DOFs, list of (3, n_free)."""
        return [_lever_map(ri, self._fi) for ri in self.r]


def _node_mass_vector(model):
    """Diagonal of the interior-node mass, shape (n_dof - n_free,) [kg]."""
    return np.repeat(model._node_mass, 3 * (model.segments - 1))


def _gyroscopic(model, frame, tw):
    """Centripetal / gyroscopic terms g(q, v) on the free DOFs [N, N m].

    [w x (w x S); w x (I_P w)] with S the first moment and I_P the inertia about P of the
    body and the half node masses (the M6 rotation block); zero without rotation.
    """
    w = tw[3:]
    if not np.any(w):
        return np.zeros(model.n_free)
    g6 = np.concatenate([np.cross(w, np.cross(w, frame.first_moment)),
                         np.cross(w, frame.M6[3:, 3:] @ w)])
    return g6[model._fi]


def _axial_dashpot(model, frame, X, v, tw, c_ax):
    """Generalised force of the axial dashpots c_ax d(epsilon)/dt (taut segments only)."""
    F = np.zeros(model.n_dof)
    nf = model.n_free
    rob = model.robot
    interior = _interior(model, X)
    vint = [v[o:o + 3 * (N - 1)].reshape(-1, 3) for o, N in zip(model._offsets,
                                                                  model.segments)]
    W = np.zeros(6)
    for i, (xi, vi) in enumerate(zip(interior, vint)):
        if c_ax[i] == 0.0:
            continue
        l0 = model.segment_lengths[i]
        nodes = np.vstack((rob.anchors[i], xi, frame.B[i]))
        vB = tw[:3] + np.cross(tw[3:], frame.r[i])
        vel = np.vstack((np.zeros(3), vi, vB))
        units, lengths, _ = _segments(nodes, l0, rob.cables[i].EA)
        rate = np.einsum("ij,ij->i", units, np.diff(vel, axis=0)) / l0
        f = (np.where(lengths > l0, c_ax[i] * rate, 0.0))[:, None] * units
        o = model._offsets[i]
        F[o:o + xi.size] = (f[1:] - f[:-1]).ravel()
        W[:3] -= f[-1]
        W[3:] -= np.cross(frame.r[i], f[-1])
    F[:nf] = W[model._fi]
    return F


def _potential(model, frame, X):
    """Elastic and gravity energy [J], end tensions [N], slack segments, largest strain."""
    rob = model.robot
    g = rob.g
    elastic = 0.0
    gravity = rob.platform.mass * g * frame.zG
    t_end, t_anchor = np.empty(rob.n_cables), np.empty(rob.n_cables)
    slack, strain = [], 0.0
    for i, xi in enumerate(_interior(model, X)):
        l0, EA = model.segment_lengths[i], rob.cables[i].EA
        nodes = np.vstack((rob.anchors[i], xi, frame.B[i]))
        _, lengths, T = _segments(nodes, l0, EA)
        stretch = np.maximum(lengths - l0, 0.0)
        elastic += 0.5 * EA / l0 * np.dot(stretch, stretch)
        gravity += model._node_mass[i] * g * (xi[:, 2].sum() + 0.5 * frame.B[i, 2])
        t_end[i], t_anchor[i] = T[-1], T[0]
        strain = max(strain, float(np.max(lengths)) / l0 - 1.0)
        if np.any(T <= 0.0):
            slack.append((i, int(np.argmax(T <= 0.0))))
    return elastic, gravity, t_end, t_anchor, slack, strain


# ------------------------------------------------------------------------ the dynamics
class _Dynamics:
    """Forces, mass and Newton matrix of the lumped robot at given lengths (internal)."""

    def __init__(self, model, damping, K0, excitation):
        self.model = model
        n = model.robot.n_cables
        self.damping = damping
        self.alpha = damping.alpha
        self.beta = damping.beta
        self.c_ax = damping.axial_per_cable(n)
        self.K0 = K0
        self.excitation = excitation
        self.c_visc = np.array([cb.viscous_damping for cb in model.robot.cables])
        self._last = None
        self.set_model(model)

    def set_model(self, model):
        self.model = model
        self.mu = _node_mass_vector(model)
        self.cv = np.repeat(self.c_visc * model.segment_lengths, 3 * (model.segments - 1))

    def load(self, t):
        F = np.zeros(self.model.n_dof)
        if self.excitation is not None:
            F[:self.model.n_free] = _load(self.excitation, t)[self.model._fi]
        return F

    def mass_times(self, frame, a):
        nf = self.model.n_free
        return np.concatenate([frame.Mff @ a[:nf], self.mu * a[nf:]])

    def platform_viscous(self, frame):
        m = self.model
        Cb = np.zeros((m.n_free, m.n_free))
        for i, J in enumerate(frame.J):
            Cb += 0.5 * self.c_visc[i] * m.segment_lengths[i] * J.T @ J
        return Cb

    def forces(self, pose, X, v, t):
        """Total generalised force F and its external and damping parts, max tension."""
        m = self.model
        frame = self._last = _Frame(m, pose, self._last)
        R, t_max = m._residual(pose, _interior(m, X))
        fe = self.load(t)
        tw = _twist(m, v)
        nf = m.n_free
        fd = np.zeros(m.n_dof)
        if self.alpha:
            fd -= self.alpha * self.mass_times(frame, v)
        if self.beta:
            fd -= self.beta * (self.K0 @ v)
        if np.any(self.c_visc):
            fd[:nf] -= self.platform_viscous(frame) @ v[:nf]
            fd[nf:] -= self.cv * v[nf:]
        if np.any(self.c_ax):
            fd += _axial_dashpot(m, frame, X, v, tw, self.c_ax)
        F = R + fe + fd - np.concatenate([_gyroscopic(m, frame, tw), np.zeros(m.n_dof - nf)])
        return F, fe, fd, t_max, frame

    def newton_matrix(self, pose, X, dt):
        """K + 4 M / dt^2 + 2 C / dt at a configuration (sparse CSC)."""
        m = self.model
        frame = _Frame(m, pose, self._last)
        EA = np.array([cb.EA for cb in m.robot.cables])
        extra = 2.0 * self.c_ax / (dt * EA)
        K = m._tangent(pose, _interior(m, X), lambda i: 1.0 + extra[i])
        c_mass = 4.0 / dt ** 2 + 2.0 * self.alpha / dt
        block = c_mass * frame.Mff + (2.0 / dt) * self.platform_viscous(frame)
        diag = c_mass * self.mu + (2.0 / dt) * self.cv
        D = scipy.sparse.block_diag([scipy.sparse.csr_matrix(block),
                                     scipy.sparse.diags(diag)], format="csr")
        J = K + D
        if self.beta:
            J = J + (2.0 * self.beta / dt) * self.K0
        return J.tocsc()

    def accelerations(self, frame, F):
        nf = self.model.n_free
        return np.concatenate([np.linalg.solve(frame.Mff, F[:nf]) if nf else np.zeros(0),
                               F[nf:] / self.mu])

    def kinetic(self, frame, v):
        return 0.5 * float(v @ self.mass_times(frame, v))


def _load(excitation, t):
    f = np.asarray(excitation(t), dtype=float)
    if f.shape != (6,) or not np.all(np.isfinite(f)):
        raise InvalidParameterError(
            f"excitation(t) must return 6 finite loads (fx, fy, fz [N], mx, my, mz [N m]), "
            f"got {f!r} at t = {t:g} s")
    return f


# -------------------------------------------------------------------------- inputs
def _lengths_function(lengths, n):
    if lengths is None:
        return None
    if callable(lengths):
        fn = lengths
    else:
        try:
            times, table = lengths
            times = np.asarray(times, dtype=float)
            table = np.asarray(table, dtype=float)
        except (TypeError, ValueError):
            raise InvalidParameterError(
                "lengths must be a callable t -> (n_cables,) unstretched lengths [m] or a "
                f"table (times (k,) [s], lengths (k, {n}) [m]), got {lengths!r}") from None
        if times.ndim != 1 or table.shape != (times.size, n) or times.size < 1 or \
                not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
            raise InvalidParameterError(
                f"lengths table must be (times (k,) strictly increasing [s], lengths "
                f"(k, {n}) [m]), got shapes {times.shape} and {table.shape}")
        if times[0] > 0:
            raise InvalidParameterError(
                f"lengths table must start at t <= 0, starts at {times[0]:g} s")

        def fn(t):
            return np.array([np.interp(t, times, table[:, i]) for i in range(n)])

    def checked(t):
        L = np.asarray(fn(t), dtype=float)
        if L.shape != (n,) or not np.all(np.isfinite(L)) or np.any(L <= 0):
            raise InvalidParameterError(
                f"lengths(t) must give {n} finite positive unstretched lengths [m], got "
                f"{L!r} at t = {t:g} s")
        return L
    return checked


def _initial(initial, model):
    """(offset (6,), velocity (6,)) from ``initial``."""
    zero = np.zeros(6)
    if initial is None:
        return zero, zero
    if isinstance(initial, (tuple, list)) and len(initial) == 2 and \
            not np.isscalar(initial[0]):
        parts = [zero if p is None else p for p in initial]
    else:
        parts = [initial, zero]
    out = []
    for name, p in zip(("initial offset", "initial velocity"), parts):
        try:
            p = np.asarray(p, dtype=float)
        except (TypeError, ValueError):
            p = None
        if p is None or p.shape != (6,) or not np.all(np.isfinite(p)):
            raise InvalidParameterError(
                f"initial must be a platform offset (6,) [m, rad] or (offset, velocity) with "
                f"velocity (6,) [m/s, rad/s]; the {name} is {parts[len(out)]!r}")
        held = [k for k in range(6) if k not in model._fi and p[k] != 0]
        if held:
            raise InvalidParameterError(
                f"initial: the {name} is nonzero on held DOF(s) "
                f"{[OUTPUT_NAMES[k] for k in held]}; only {model.free_dofs} are free")
        out.append(p)
    return out[0], out[1]


def _step_count(t_end, dt):
    return max(1, int(np.ceil(t_end / dt - 1e-9)))


# -------------------------------------------------------------------------- simulate
def simulate(model, t_end, dt, excitation=None, lengths=None, scheme="implicit",
             initial=None, damping=None, record_every=1, *, record_nodes=False, tol=1e-9,
             max_iter=25):
    """Integrate the nonlinear equations of motion of the lumped-mass robot.

    Starts from the static equilibrium of the model (its last :meth:`equilibrium`, or the
    equilibrium for ``lengths(0)``), optionally displaced by ``initial``, and steps with a
    constant ``dt``. See the module notes for the equations, schemes, winch model and
    energy bookkeeping.

    Parameters
    ----------
    model : LumpedMassModel
    t_end : float
        Duration [s], > 0; ``ceil(t_end / dt)`` steps are taken.
    dt : float
        Time step [s], > 0. The implicit scheme is stable for any dt (its accuracy needs
        about 20 steps per period of interest); the explicit one needs
        dt < :func:`explicit_step_limit`.
    excitation : callable, optional
        t [s] -> platform load (fx, fy, fz [N], mx, my, mz [N m]) about P, base axes,
        shape (6,); loads on held DOFs are ignored.
    lengths : callable or (times, lengths), optional
        Unstretched lengths L0_i(t) [m], shape (n_cables,), as a callable or a table
        (times (k,) [s] strictly increasing, from t <= 0; lengths (k, n_cables) [m]),
        interpolated linearly and held after its end. Default: the model's, fixed.
    scheme : {"implicit", "explicit"}
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
    if not isinstance(model, LumpedMassModel):
        raise InvalidParameterError(
            f"model must be a LumpedMassModel, got {type(model).__name__}")
    t_end = positive_scalar("t_end", t_end)
    dt = positive_scalar("dt", dt)
    if dt > t_end:
        raise InvalidParameterError(f"dt must be <= t_end = {t_end:g} s, got {dt:g} s")
    if scheme not in _SCHEMES:
        raise InvalidParameterError(f"scheme must be one of {_SCHEMES}, got {scheme!r}")
    for name, val in (("record_every", record_every), ("max_iter", max_iter)):
        if isinstance(val, bool) or not isinstance(val, Integral) or val < 1:
            raise InvalidParameterError(f"{name} must be an integer >= 1, got {val!r}")
    tol = positive_scalar("tol", tol)
    if excitation is not None and not callable(excitation):
        raise InvalidParameterError(
            f"excitation must be a callable t -> (6,) load or None, got {excitation!r}")
    if excitation is not None:
        _load(excitation, 0.0)
    if damping is None:
        damping = TimeDamping()
    if not isinstance(damping, TimeDamping):
        raise InvalidParameterError(
            f"damping must be a TimeDamping or None, got {type(damping).__name__}")
    n = model.robot.n_cables
    damping.axial_per_cable(n)
    length_fn = _lengths_function(lengths, n)
    offset, velocity = _initial(initial, model)

    # ---- start: static equilibrium at L0(0), then the offset
    L_prev = model.unstretched_lengths if length_fn is None else length_fn(0.0)
    m = _model_at(model, L_prev)
    try:
        if m is model:
            eq = model.state
        else:
            start = model._state.pose if model._state is not None else None
            eq = m.equilibrium(initial_pose=start)
    except (SlackCableError, ConvergenceError) as exc:
        what = "lengths(0)" if length_fn is not None else "the model's unstretched_lengths"
        raise SlackCableError(
            f"simulate: no taut static equilibrium for {what} = {L_prev.tolist()} m: "
            f"{exc}") from None
    pose = eq.pose.moved(offset) if np.any(offset) else eq.pose
    pose = _Pose(pose.position, pose.rotation)
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
    v[:m.n_free] = velocity[m._fi]

    K0 = None
    if damping.beta:
        K0 = m._tangent(eq.pose, eq.interior, lambda i: 1.0)
        K0 = (0.5 * (K0 + K0.T)).tocsr()
    dyn = _Dynamics(m, damping, K0, excitation)
    V_eq = _potential(m, _Frame(m, eq.pose), np.concatenate(
        [x.ravel() for x in eq.interior]))
    F, fe, fd, t_max, frame = dyn.forces(pose, X, v, 0.0)
    pot = _potential(m, frame, X)
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
    n_steps = _step_count(t_end, dt)
    rec = _Recorder(n_steps // record_every + 1, n, m, record_nodes)
    ledger = _Ledger(dyn.kinetic(frame, v) + pot[0] + pot[1], V_eq[0] + V_eq[1], pot[0])
    rec.store(0, 0.0, pose, v, m, pot, ledger.row(dyn.kinetic(frame, v), pot), X)
    newton = _Newton(tol, max_iter)
    slack_steps = 0
    for k in range(1, n_steps + 1):
        t1 = k * dt
        m_prev = m
        if length_fn is not None:
            m = _model_at(model, length_fn(t1))
            dyn.set_model(m)
        step = _implicit_step if scheme == "implicit" else _explicit_step
        d, pose1, X1, v1, a1, fe1, fd1, frame1 = step(dyn, pose, X, v, a, t1, dt, k, newton)
        # ---- bookkeeping and checks
        pot1 = _potential(m, frame1, X1)
        ledger.ext += 0.5 * d @ (fe + fe1)
        ledger.diss -= 0.5 * d @ (fd + fd1)
        if m is not m_prev:
            ledger.winch += 0.5 * (
                sum(_potential(m, frame, X)[:2]) - pot[0] - pot[1]
                + pot1[0] + pot1[1] - sum(_potential(m_prev, frame1, X1)[:2]))
            dmu = _node_mass_vector(m) - _node_mass_vector(m_prev)
            ledger.carried += 0.25 * (_carried(m, m_prev, frame, v, dmu)
                                      + _carried(m, m_prev, frame1, v1, dmu))
        row = ledger.row(dyn.kinetic(frame1, v1), pot1)
        _check_blow_up(pot1[5], row[-1], ledger, scheme, dt, k, t1, m, damping)
        if pot1[4]:
            slack_steps += 1
            if slack_steps == 1:
                i, s = pot1[4][0]
                warnings.warn(
                    f"simulate: cable {i} segment {s} went slack at step {k} (t = {t1:g} s); "
                    f"tension-only springs carry no force until it is taut again",
                    SlackSegmentWarning, stacklevel=2)
        pose, X, v, a, fe, fd, frame, pot = pose1, X1, v1, a1, fe1, fd1, frame1, pot1
        if k % record_every == 0:
            rec.store(k // record_every, t1, pose, v, m, pot, row, X)
    return rec.result(
        model=model, scheme=scheme, dt=dt, n_steps=n_steps, eq_pose=eq.pose,
        newton_iterations=newton.iterations, jacobian_updates=newton.updates,
        slack_steps=slack_steps, explicit_limit=limit,
        wall_time=_time.perf_counter() - wall0, static_energy=V_eq[0] + V_eq[1],
        record_every=record_every)


class _Newton:
    """Newton options, the kept LU factors and the iteration counters of a run."""

    def __init__(self, tol, max_iter):
        self.tol, self.max_iter = tol, max_iter
        self.lu = None
        self.iterations = self.updates = 0


def _implicit_step(dyn, pose, X, v, a, t1, dt, k, newton):
    """One Newmark average-acceleration step solved by (modified) Newton iterations.

    Unknown: the increment d = x_{n+1} - x_n; a_{n+1} = 4 (d - dt v_n) / dt^2 - a_n and
    v_{n+1} = v_n + dt (a_n + a_{n+1}) / 2; residual G(d) = M a_{n+1} - F(q_{n+1}, v_{n+1}).
    The LU factors of K + 4 M / dt^2 + 2 C / dt are kept while each iteration reduces the
    residual tenfold, and refreshed otherwise.
    """
    m = dyn.model
    c0 = 4.0 / dt ** 2
    d = dt * v + 0.5 * dt ** 2 * a                    # predictor: a_{n+1} = a_n
    prev = np.inf
    for it in range(newton.max_iter + 1):
        pose1, X1 = _advance(m, pose, X, d)
        a1 = c0 * (d - dt * v) - a
        v1 = v + 0.5 * dt * (a + a1)
        F1, fe1, fd1, t_max, frame1 = dyn.forces(pose1, X1, v1, t1)
        G = dyn.mass_times(frame1, a1) - F1
        if not (np.all(np.isfinite(G)) and np.all(np.isfinite(d))):
            raise IntegrationError(
                f"simulate: non-finite state at step {k} (t = {t1:g} s) with implicit dt = "
                f"{dt:g} s", step=k, time=t1, dt=dt)
        res = m._relative_residual(G, t_max)
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


def _explicit_step(dyn, pose, X, v, a, t1, dt, k, newton):
    """One velocity-Verlet step (velocity-dependent forces at the half-step velocity)."""
    m = dyn.model
    vh = v + 0.5 * dt * a
    d = dt * vh
    pose1, X1 = _advance(m, pose, X, d)
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


def _check_blow_up(strain, residual, ledger, scheme, dt, k, t1, m, damping):
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
            f"check the motion", EnergyBalanceWarning, stacklevel=3)
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


def _carried(m, m_prev, frame, v, dmu):
    """sum dmu |v|^2 of the interior nodes and the half masses at B_i [J * 2]."""
    nf = m.n_free
    tw = _twist(m, v)
    dhalf = 0.5 * (m._node_mass - m_prev._node_mass)
    vB = tw[:3] + np.cross(tw[3:], frame.r)
    return float(dmu @ v[nf:] ** 2 + dhalf @ np.sum(vB ** 2, axis=1))


class _Ledger:
    """Running energy balance E - E0 = W_ext - D + W_w + E_c + residual (module notes)."""

    def __init__(self, E0, V_eq, elastic0):
        self.E0 = E0
        self.excess = abs(E0 - V_eq)
        self.floor = 1e-3 * elastic0          # for runs that start at rest, unloaded
        self.ext = self.winch = self.carried = self.diss = 0.0
        self.peaks = np.zeros(4)
        self.warned = False

    def row(self, kinetic, pot):
        """(kinetic, gravity, elastic, ext, winch, carried, dissipated, residual) [J]."""
        terms = np.array([self.ext, self.winch, self.carried, self.diss])
        self.peaks = np.maximum(self.peaks, np.abs(terms))
        E = kinetic + pot[0] + pot[1]
        res = E - self.E0 - (self.ext - self.diss + self.winch + self.carried)
        return (kinetic, pot[1], pot[0], self.ext, self.winch, self.carried, self.diss, res)

    def scale(self):
        """Energy scale of the run so far [J] (as EnergyBalance.scale)."""
        return self.excess + float(self.peaks.sum())

    def limit(self):
        """Energy scale with its floor [J]: the reference of the blow-up test."""
        return self.scale() + self.floor


class _Recorder:
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
        self.vel[j] = _twist(model, v)
        self.t_end[j], self.t_anchor[j] = pot[2], pot[3]
        self.L[j] = model.unstretched_lengths
        self.E[j] = row
        if self.nodes is not None:
            B, _ = model.robot.attachment_points(pose)
            for i, xi in enumerate(_interior(model, X)):
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


# ------------------------------------------------------------------------------ results
