"""Kernels of the lumped-mass time-domain model (theory.md §7.3): configuration updates
with exactly composed rotations, the pose-dependent platform terms, damping forces, the
potential energy and the :class:`Dynamics` that assembles forces, mass and the Newton
matrix. Internal to :mod:`dynstiff.timedomain.simulation` (see its notes for the equations)."""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import compiled
from dynstiff._vec import cross
from dynstiff.errors import InvalidParameterError
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.models.lumped_statics import segment_forces
from dynstiff.robot.platform import (
    lever_map,
    platform_mass_matrix,
    quaternion_product,
    quaternion_to_rotvec,
    rotvec_to_quaternion,
    skew,
)
from dynstiff.robot.robot import Pose

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.timedomain.damping import TimeDamping


def model_at(model: LumpedMassModel, L0: NDArray[np.float64]) -> LumpedMassModel:
    """The model with other unstretched lengths (same robot and segments)."""
    if np.array_equal(L0, model.unstretched_lengths):
        return model
    return LumpedMassModel(model.robot, L0, [int(s) for s in model.segments])


def interior_views(model: LumpedMassModel, X: NDArray[np.float64]) -> list[NDArray[np.float64]]:
    """Views of the flat interior-node vector X as the model's list of (N_i - 1, 3)."""
    nf = model.n_free
    return [X[o - nf:o - nf + 3 * (N - 1)].reshape(-1, 3)
            for o, N in zip(model.offsets, model.segments)]


class FastPose(Pose):
    """A :class:`Pose` that computes its rotation matrix once (the model's residual, its
    tangent and the platform terms all ask for it), built by the integrator without the
    user-input checks of :class:`Pose` (its state is checked for finiteness every step)."""

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", np.asarray(self.position, dtype=float))
        object.__setattr__(self, "rotation", np.asarray(self.rotation, dtype=float))

    @functools.cached_property
    def matrix(self) -> NDArray[np.float64]:
        """Rotation matrix R_p, shape (3, 3)."""
        return super().matrix


def advance(model: LumpedMassModel, pose: FastPose, X: NDArray[np.float64],
            dx: NDArray[np.float64]) -> tuple[FastPose, NDArray[np.float64]]:
    """Configuration after the increment dx (rotation composed exactly)."""
    d6 = np.zeros(6)
    d6[model.free_index] = dx[:model.n_free]
    if np.any(d6[3:]):
        q = quaternion_product(rotvec_to_quaternion(d6[3:]),
                               rotvec_to_quaternion(pose.rotation))   # as Pose.moved
        pose = FastPose(pose.position + d6[:3], quaternion_to_rotvec(q))
    else:
        new = FastPose(pose.position + d6[:3], pose.rotation)
        if "matrix" in pose.__dict__:                      # same rotation: keep R_p
            new.__dict__["matrix"] = pose.__dict__["matrix"]
        pose = new
    return pose, X + dx[model.n_free:]


def twist_of(model: LumpedMassModel, v: NDArray[np.float64]) -> NDArray[np.float64]:
    """Full platform twist (v_P, w), shape (6,), from the free-DOF velocities."""
    t = np.zeros(6)
    t[model.free_index] = v[:model.n_free]
    return t


class Frame:
    """Pose-dependent platform quantities of one model at one pose.

    The rotation-dependent part is copied from ``like`` when the rotation and the model
    are the same (always so for a platform without free rotations).
    """

    def __init__(self, model: LumpedMassModel, pose: Pose, like: Frame | None = None) -> None:
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
        self._fi = fi = model.free_index
        half = 0.5 * model.node_masses
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
    def J(self) -> list[NDArray[np.float64]]:
        """Lever maps J_i restricted to the free DOFs, list of (3, n_free)."""
        return [lever_map(ri, self._fi) for ri in self.r]


def node_mass_vector(model: LumpedMassModel) -> NDArray[np.float64]:
    """Diagonal of the interior-node mass, shape (n_dof - n_free,) [kg]."""
    return np.repeat(model.node_masses, 3 * (model.segments - 1))


def gyroscopic(model: LumpedMassModel, frame: Frame,
               tw: NDArray[np.float64]) -> NDArray[np.float64]:
    """Centripetal / gyroscopic terms g(q, v) on the free DOFs [N, N m].

    [w x (w x S); w x (I_P w)] with S the first moment and I_P the inertia about P of the
    body and the half node masses (the M6 rotation block); zero without rotation.
    """
    w = tw[3:]
    if not np.any(w):
        return np.zeros(model.n_free)
    g6 = np.concatenate([cross(w, cross(w, frame.first_moment)),
                         cross(w, frame.M6[3:, 3:] @ w)])
    return g6[model.free_index]


def _axial_dashpot(model: LumpedMassModel, frame: Frame, X: NDArray[np.float64],
                   v: NDArray[np.float64], tw: NDArray[np.float64],
                   c_ax: NDArray[np.float64]) -> NDArray[np.float64]:
    """Generalised force of the axial dashpots c_ax d(epsilon)/dt (taut segments only)."""
    if np.all(model.segments == model.segments[0]):
        return _axial_dashpot_stacked(model, frame, X, v, tw, c_ax)
    return _axial_dashpot_loop(model, frame, X, v, tw, c_ax)


def _axial_dashpot_stacked(model: LumpedMassModel, frame: Frame, X: NDArray[np.float64],
                           v: NDArray[np.float64], tw: NDArray[np.float64],
                           c_ax: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`_axial_dashpot` for chains of equal N, all at once (one segment_forces call)."""
    rob = model.robot
    n, N, nf = rob.n_cables, int(model.segments[0]), model.n_free
    nodes = np.empty((n, N + 1, 3))
    nodes[:, 0] = rob.anchors
    nodes[:, 1:-1] = X.reshape(n, N - 1, 3)
    nodes[:, -1] = frame.B
    vel = np.zeros((n, N + 1, 3))
    vel[:, 1:-1] = v[nf:].reshape(n, N - 1, 3)
    vel[:, -1] = tw[:3] + cross(tw[3:], frame.r)
    l0 = model.segment_lengths[:, None]
    EA = np.array([c.EA for c in rob.cables])[:, None]
    units, lengths, _ = segment_forces(nodes, l0, EA)
    rate = np.einsum("ijk,ijk->ij", units, np.diff(vel, axis=1)) / l0
    f = np.where(lengths > l0, np.asarray(c_ax)[:, None] * rate, 0.0)[..., None] * units
    F = np.empty(model.n_dof)
    F[nf:] = (f[:, 1:] - f[:, :-1]).ravel()
    W = np.concatenate([-f[:, -1].sum(axis=0), -cross(frame.r, f[:, -1]).sum(axis=0)])
    F[:nf] = W[model.free_index]
    return F


def _axial_dashpot_loop(model: LumpedMassModel, frame: Frame, X: NDArray[np.float64],
                        v: NDArray[np.float64], tw: NDArray[np.float64],
                        c_ax: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`_axial_dashpot` cable by cable (any N per cable)."""
    F = np.zeros(model.n_dof)
    nf = model.n_free
    rob = model.robot
    interior = interior_views(model, X)
    vint = [v[o:o + 3 * (N - 1)].reshape(-1, 3) for o, N in zip(model.offsets,
                                                                  model.segments)]
    W = np.zeros(6)
    for i, (xi, vi) in enumerate(zip(interior, vint)):
        if c_ax[i] == 0.0:
            continue
        l0 = model.segment_lengths[i]
        nodes = np.vstack((rob.anchors[i], xi, frame.B[i]))
        vB = tw[:3] + cross(tw[3:], frame.r[i])
        vel = np.vstack((np.zeros(3), vi, vB))
        units, lengths, _ = segment_forces(nodes, l0, rob.cables[i].EA)
        rate = np.einsum("ij,ij->i", units, np.diff(vel, axis=0)) / l0
        f = (np.where(lengths > l0, c_ax[i] * rate, 0.0))[:, None] * units
        o = model.offsets[i]
        F[o:o + xi.size] = (f[1:] - f[:-1]).ravel()
        W[:3] -= f[-1]
        W[3:] -= cross(frame.r[i], f[-1])
    F[:nf] = W[model.free_index]
    return F


def potential_energy(
        model: LumpedMassModel, frame: Frame, X: NDArray[np.float64],
) -> tuple[float, float, NDArray[np.float64], NDArray[np.float64], list[tuple[int, int]], float]:
    """Elastic and gravity energy [J], end tensions [N], slack segments, largest strain."""
    rob = model.robot
    g = rob.g
    elastic = 0.0
    gravity = rob.platform.mass * g * frame.zG
    t_end, t_anchor = np.empty(rob.n_cables), np.empty(rob.n_cables)
    slack, strain = [], 0.0
    for i, xi in enumerate(interior_views(model, X)):
        l0, EA = model.segment_lengths[i], rob.cables[i].EA
        nodes = np.vstack((rob.anchors[i], xi, frame.B[i]))
        _, lengths, T = segment_forces(nodes, l0, EA)
        stretch = np.maximum(lengths - l0, 0.0)
        elastic += 0.5 * EA / l0 * np.dot(stretch, stretch)
        gravity += model.node_masses[i] * g * (xi[:, 2].sum() + 0.5 * frame.B[i, 2])
        t_end[i], t_anchor[i] = T[-1], T[0]
        strain = max(strain, float(np.max(lengths)) / l0 - 1.0)
        if np.any(T <= 0.0):
            slack.append((i, int(np.argmax(T <= 0.0))))
    return elastic, gravity, t_end, t_anchor, slack, strain


class Dynamics:
    """Forces, mass and Newton matrix of the lumped robot at given lengths (internal)."""

    def __init__(self, model: LumpedMassModel, damping: TimeDamping, K0: Any | None,
                 excitation: Callable[..., Any] | None) -> None:
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
        self._load = None
        self.extremes = (np.inf, 0.0)
        self.set_model(model)

    def set_model(self, model: LumpedMassModel) -> None:
        self.model = model
        self.EA = np.array([cb.EA for cb in model.robot.cables])
        self.node_weights = model.node_masses[:, None] * model.robot.gravity_vector
        self.platform_weight = model.robot.platform.mass * model.robot.gravity_vector
        self._any_c_ax = bool(np.any(self.c_ax))
        self.seg = np.asarray(model.segments, dtype=np.int64)
        self.mu = node_mass_vector(model)
        self.cv = np.repeat(self.c_visc * model.segment_lengths, 3 * (model.segments - 1))

    def load(self, t: float) -> NDArray[np.float64]:
        """External load at t [s] on the free DOFs, shape (n_dof,); the excitation is
        called once per time (the Newton iterations of a step share it)."""
        if self._load is not None and self._load[0] == t:
            return self._load[1].copy()
        F = np.zeros(self.model.n_dof)
        if self.excitation is not None:
            F[:self.model.n_free] = load_at(self.excitation, t)[self.model.free_index]
        self._load = (t, F)
        return F.copy()

    def mass_times(self, frame: Frame, a: NDArray[np.float64]) -> NDArray[np.float64]:
        nf = self.model.n_free
        return np.concatenate([frame.Mff @ a[:nf], self.mu * a[nf:]])

    def platform_viscous(self, frame: Frame) -> NDArray[np.float64]:
        m = self.model
        Cb = np.zeros((m.n_free, m.n_free))
        for i, J in enumerate(frame.J):
            Cb += 0.5 * self.c_visc[i] * m.segment_lengths[i] * J.T @ J
        return Cb

    def forces(
            self, pose: FastPose, X: NDArray[np.float64], v: NDArray[np.float64], t: float,
            dashpots: bool = True,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float, Frame]:
        """Total generalised force F and its external and damping parts, max tension; the
        smallest tension and largest strain of the configuration are kept in
        ``self.extremes``."""
        m = self.model
        frame = self._last = Frame(m, pose, self._last)
        tw = twist_of(m, v)
        nf = m.n_free
        fast = compiled.load("chain")
        if fast is not None:
            R, dash, t_max = self._compiled_chain_forces(fast, frame, pose, X, v, tw)
        else:
            ext = []
            R, t_max = m.residual_unchecked(pose, interior_views(m, X), ext)
            self.extremes = ext[0]
        fe = self.load(t)
        fd = np.zeros(m.n_dof)
        if self.alpha:
            fd -= self.alpha * self.mass_times(frame, v)
        if self.beta:
            fd -= self.beta * (self.K0 @ v)
        if np.any(self.c_visc):
            fd[:nf] -= self.platform_viscous(frame) @ v[:nf]
            fd[nf:] -= self.cv * v[nf:]
        if not dashpots:              # the energy scheme applies its own (discrete_gradient)
            pass
        elif fast is not None:
            fd += dash
        elif np.any(self.c_ax):
            fd += _axial_dashpot(m, frame, X, v, tw, self.c_ax)
        F = R + fe + fd - np.concatenate([gyroscopic(m, frame, tw), np.zeros(m.n_dof - nf)])
        return F, fe, fd, t_max, frame

    def _compiled_chain_forces(
            self, fast: Any, frame: Frame, pose: FastPose, X: NDArray[np.float64],
            v: NDArray[np.float64], tw: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        """Residual R, axial-dashpot force and largest tension from the compiled chain kernel
        (:mod:`dynstiff.compiled.chain`); sets ``extremes``."""
        m = self.model
        rob = m.robot
        nf = m.n_free
        inner, d_inner, W, Wd, t_max, t_min, strain = fast.robot_chain_forces(
            rob.anchors, X, frame.B, frame.r, v[nf:], tw, self.seg, m.segment_lengths,
            self.EA, self.c_ax, self.node_weights, self.platform_weight, frame.rG)
        self.extremes = (t_min, strain)
        fi = m.free_index
        return np.concatenate([W[fi], inner]), np.concatenate([Wd[fi], d_inner]), t_max

    def newton_matrix(
            self, pose: FastPose, X: NDArray[np.float64], dt: float,
            elements: list[tuple[NDArray[np.float64], NDArray[np.float64]]] | None = None,
    ) -> Any:
        """K + 4 M / dt^2 + 2 C / dt at a configuration (sparse CSC); ``elements`` as
        :meth:`LumpedMassModel.tangent_unchecked` (their axial dashpots included)."""
        import scipy.sparse
        m = self.model
        frame = Frame(m, pose, self._last)
        EA = np.array([cb.EA for cb in m.robot.cables])
        extra = 2.0 * self.c_ax / (dt * EA)
        K = m.tangent_unchecked(pose, interior_views(m, X), lambda i: 1.0 + extra[i],
                                elements)
        c_mass = 4.0 / dt ** 2 + 2.0 * self.alpha / dt
        block = c_mass * frame.Mff + (2.0 / dt) * self.platform_viscous(frame)
        diag = c_mass * self.mu + (2.0 / dt) * self.cv
        D = scipy.sparse.block_diag([scipy.sparse.csr_matrix(block),
                                     scipy.sparse.diags(diag)], format="csr")
        J = K + D
        if self.beta:
            J = J + (2.0 * self.beta / dt) * self.K0
        return J.tocsc()

    def accelerations(self, frame: Frame, F: NDArray[np.float64]) -> NDArray[np.float64]:
        nf = self.model.n_free
        return np.concatenate([np.linalg.solve(frame.Mff, F[:nf]) if nf else np.zeros(0),
                               F[nf:] / self.mu])

    def kinetic(self, frame: Frame, v: NDArray[np.float64]) -> float:
        return 0.5 * float(v @ self.mass_times(frame, v))


def load_at(excitation: Callable[..., Any], t: float) -> NDArray[np.float64]:
    """The loads ``excitation(t)`` returns, as 6 real finite floats, or InvalidParameterError
    naming t (complex loads are refused, not cut to their real parts; text or ragged ones
    too)."""
    raw = excitation(t)
    f = None
    if not np.iscomplexobj(raw):
        try:
            f = np.asarray(raw, dtype=float)
        except (TypeError, ValueError):
            pass
    if f is None or f.shape != (6,) or not np.all(np.isfinite(f)):
        raise InvalidParameterError(
            f"excitation(t) must return 6 real finite loads (fx, fy, fz [N], mx, my, mz "
            f"[N m]), got {raw!r} at t = {t:g} s")
    return f
