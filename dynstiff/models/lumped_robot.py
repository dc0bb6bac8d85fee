"""Lumped-mass model of a whole cable robot: nonlinear statics, tangent stiffness and mass
(its linearisation about an equilibrium is the "lumped" rung,
:class:`dynstiff.lumped.LumpedLinearModel`, whose modes and FRFs come from the same
functions as every rung's).

Every cable i is a chain of N_i straight, tension-only springs between point masses
(theory.md §7.1); the platform is the rigid body of the same :class:`~dynstiff.Robot`, with
any subset of free DOFs. This model uses no catenary closed form and no linear cable theory,
so it is the independent cross-check of the closed-form dynamic-stiffness model
(:class:`~dynstiff.FrequencyModel`, theory.md §4).

Notation (theory.md §4, §7.1)
-----------------------------
=================  ==============================================================  =======
symbol             meaning                                                         unit
=================  ==============================================================  =======
N_i                segments of cable i; nodes 0..N_i, node 0 = anchor A_i (fixed)  --
L0_i, l0_i         unstretched length, segment length L0_i / N_i                   m
m, EA              mass per unstretched length, axial stiffness                    kg/m, N
T, n, l            segment tension EA (l / l0 - 1)_+, unit vector, length          N, --, m
K_e                element tangent (EA/l0) n n^T + (T/l)(I - n n^T)                N/m
p, R_p             position of P, rotation of the platform                         m, --
b_i, r_i           attachment in the platform frame, lever arm R_p b_i              m
B_i                attachment point p + R_p b_i = node N_i of cable i              m
J_i                [I, -[r_i]x], maps x = (dp, dtheta) to dB_i                      --
F_i                force on the platform at B_i: -T n of the last segment plus      N
                   the weight of the half node mass m l0 / 2 carried there
m_p, M_p           platform mass, 6x6 rigid-body mass matrix about P                kg, --
=================  ==============================================================  =======

Masses: m l0 at every interior node; of the two end half masses m l0 / 2, the anchor one is
dropped (the anchor does not move) and the platform one is added to the platform as a point
mass at B_i (mass J_i^T (m l0 / 2) J_i, weight at B_i). The weight is then the cable's whole
weight m L0 g, as in the elastic catenary.

Degrees of freedom: x = (x_f, u_0, u_1, ...): the free platform DOFs (``DOF_NAMES`` order,
small motion (dp, dtheta) about P, dtheta a rotation vector in the base frame), then the
interior nodes 1..N_i - 1 of cable 0 (node-major x, y, z), of cable 1, ...

Conventions: the residual R(x) is the net *applied* force (zero at equilibrium) and the
tangent stiffness is K = -dR/dx, so K u = f_applied, as in :mod:`dynstiff.cable.lumped_chain`.
Gravity is (0, 0, -g).
"""

from __future__ import annotations

from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import _validate
from dynstiff._text import counted
from dynstiff._vec import cross
from dynstiff.cable.lumped_elements import block_tridiagonal_entries, element_stiffness
from dynstiff.errors import InvalidParameterError
from dynstiff.models.lumped_statics import lumped_equilibrium, segment_forces
from dynstiff.robot.platform import lever_map, platform_mass_matrix, skew
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.lumped_statics import LumpedEquilibrium
    from dynstiff.robot.pose import Pose

__all__ = ["LumpedMassModel"]


def _validated_segments(segments: ArrayLike | str, n: int) -> NDArray[np.int64]:
    """Segments per cable, shape (n,), from one integer or one per cable; raise naming
    ``segments`` otherwise."""
    if isinstance(segments, Integral) and not isinstance(segments, bool):
        segments = [segments] * n
    try:
        segs = list(segments)
    except TypeError:
        raise InvalidParameterError(
            f"segments must be an integer >= 1 or a sequence of {n} such integers, got "
            f"{segments!r}") from None
    if len(segs) != n or not all(isinstance(s, Integral) and not isinstance(s, bool)
                                 for s in segs):
        raise InvalidParameterError(
            f"segments must be an integer >= 1 or a sequence of {n} integers (one per "
            f"cable), got {segments!r}")
    if min(segs) < 1:
        raise InvalidParameterError(f"segments must be >= 1 for every cable, got {segs}")
    return np.array(segs, dtype=int)


# ------------------------------------------------------------------------------ model
class LumpedMassModel:
    """Lumped-mass (bead-and-spring) model of a whole cable robot (theory.md §7.1).

    Parameters
    ----------
    robot : Robot
        Anchors, attachments, cables, platform (its free DOFs), gravity.
    unstretched_lengths : array_like, shape (n_cables,)
        L0_i [m], > 0.
    segments : int or sequence of int
        N_i >= 1, the same for every cable or one per cable.

    Attributes
    ----------
    free_dofs : tuple of str
        Names of the free platform DOFs, the first rows of every matrix.
    n_free, n_dof : int
        Free platform DOFs; all DOFs (free platform + 3 (N_i - 1) per cable).
    segment_lengths : ndarray, shape (n_cables,)
        l0_i = L0_i / N_i [m].
    free_index : ndarray of int, shape (n_free,)
        Indices of the free platform DOFs in ``DOF_NAMES``.
    offsets : ndarray of int, shape (n_cables,)
        Index of the first interior DOF of every cable in the DOF vector.
    node_masses : ndarray, shape (n_cables,)
        m l0_i of an interior node [kg].

    Notes
    -----
    This model holds no state: :meth:`equilibrium` returns an equilibrium and changes
    nothing. Its linearisation about one is the "lumped" rung,
    :class:`~dynstiff.lumped.LumpedLinearModel` (``build_model(eq, "lumped")``).

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> mm = ds.LumpedMassModel(eq.robot, eq.unstretched_lengths, segments=4)
    >>> mm.segments
    array([4, 4, 4, 4, 4, 4, 4, 4])
    """

    def __init__(self, robot: Robot, unstretched_lengths: ArrayLike,
                 segments: int | ArrayLike = 30) -> None:
        if not isinstance(robot, Robot):
            raise InvalidParameterError(
                f"robot must be a dynstiff.Robot, got {type(robot).__name__}")
        n = robot.n_cables
        self.robot = robot
        self.unstretched_lengths = _validate.unstretched_lengths(unstretched_lengths, n)
        self.segments = _validated_segments(segments, n)
        self.segment_lengths = self.unstretched_lengths / self.segments
        self.free_dofs = robot.platform.free_dofs
        self.free_index = robot.platform.free_index
        self.n_free = len(self.free_index)
        sizes = 3 * (self.segments - 1)
        self.offsets = self.n_free + np.concatenate([[0], np.cumsum(sizes)[:-1]])
        self.n_dof = int(self.n_free + sizes.sum())
        self.node_masses = np.array([c.mass_per_length for c in robot.cables]) * \
            self.segment_lengths
        size = max(np.linalg.norm(robot.attachments, axis=1).max(),
                   np.linalg.norm(robot.platform.center_of_mass))
        self._moment_arm = size if size > 0 else 1.0

    def __repr__(self) -> str:
        return (f"LumpedMassModel({counted(self.robot.n_cables, 'cable')}, segments "
                f"{self.segments.tolist()}, unstretched lengths "
                f"{np.round(self.unstretched_lengths, 6).tolist()} m)")

    # ---------------------------------------------------------------- configuration
    def full_nodes(
            self, pose: Pose, interior: list[NDArray[np.float64]],
    ) -> tuple[list[NDArray[np.float64]], NDArray[np.float64]]:
        B, r = self.robot.attachment_points(pose)
        nodes = [np.vstack((self.robot.anchors[i], interior[i], B[i]))
                 for i in range(self.robot.n_cables)]
        return nodes, r

    def _check_config(
            self, pose: Pose, interior: list[NDArray[np.float64]],
    ) -> tuple[Pose, list[NDArray[np.float64]]]:
        pose = as_pose(pose)
        if len(interior) != self.robot.n_cables:
            raise InvalidParameterError(
                f"interior must hold {self.robot.n_cables} arrays (one per cable), got "
                f"{len(interior)}")
        out = []
        for i, (x, N) in enumerate(zip(interior, self.segments)):
            x = np.asarray(x, dtype=float).reshape(-1, 3) if np.size(x) else np.zeros((0, 3))
            if x.shape != (N - 1, 3):
                raise InvalidParameterError(
                    f"interior[{i}] must have shape ({N - 1}, 3), got {np.shape(x)}")
            out.append(x)
        return pose, out

    def displaced(self, pose: Pose, interior: list[NDArray[np.float64]],
                  dx: NDArray[np.float64]) -> tuple[Pose, list[NDArray[np.float64]]]:
        """Configuration after the increment dx (platform by :meth:`Pose.moved`).

        Parameters
        ----------
        pose : Pose
        interior : list of ndarray, shape (N_i - 1, 3)
            Interior node positions [m].
        dx : ndarray, shape (n_dof,)
            Increment in the DOF order of the model [m, rad].

        Returns
        -------
        pose : Pose
        interior : list of ndarray
        """
        pose, interior = self._check_config(pose, interior)
        dx = np.asarray(dx, dtype=float)
        if dx.shape != (self.n_dof,):
            raise InvalidParameterError(
                f"dx must have shape ({self.n_dof},) (n_dof), got {dx.shape}")
        d6 = np.zeros(6)
        d6[self.free_index] = dx[:self.n_free]
        new = [x + dx[o:o + x.size].reshape(-1, 3) for x, o in zip(interior, self.offsets)]
        return pose.moved(d6), new

    # ------------------------------------------------------------------- residual
    def residual(self, pose: Pose, interior: list[NDArray[np.float64]]) -> NDArray[np.float64]:
        """Net applied force R(x) on the free platform DOFs and the interior nodes.

        Node j of cable i: T_j n_j - T_{j-1} n_{j-1} + m l0 g_vec. Platform: the wrench about P
        of gravity and of F_i = -T_{N-1} n_{N-1} + (m l0 / 2) g_vec at every B_i.

        Parameters
        ----------
        pose : Pose or array_like
        interior : list of ndarray, shape (N_i - 1, 3)
            Interior node positions [m].

        Returns
        -------
        ndarray, shape (n_dof,)
            [N] on the translations and nodes, [N m] on the rotations; zero at equilibrium.
        """
        pose, interior = self._check_config(pose, interior)
        return self.residual_unchecked(pose, interior)[0]

    def residual_unchecked(self, pose: Pose, interior: list[NDArray[np.float64]],
                           extremes: list[Any] | None = None) -> tuple[NDArray[np.float64], float]:
        """:meth:`residual` without the argument checks (for solvers and time stepping), and
        the largest tension [N]: (R, shape (n_dof,) [N, N m]; t_max). With a list
        ``extremes``, (smallest tension [N], largest strain l / l0 - 1 [-]) is appended to it
        (what a time step checks: slack segments and blow-ups)."""
        nodes, r = self.full_nodes(pose, interior)
        uniform = np.all(self.segments == self.segments[0])
        inner, F, t_max = (self._chain_forces_stacked if uniform
                           else self._chain_forces_loop)(nodes, extremes)
        R = np.empty(self.n_dof)
        R[self.n_free:] = inner
        W = self.robot.gravity_wrench(pose)
        W[:3] += F.sum(axis=0)
        W[3:] += cross(r, F).sum(axis=0)
        R[:self.n_free] = W[self.free_index]
        return R, t_max

    def _chain_forces_stacked(
            self, nodes: list[NDArray[np.float64]], extremes: list[Any] | None = None,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        """Forces of every chain with the same N at once, from nodes (n, N + 1, 3) [m]:
        interior-node forces (flat, 3 n (N - 1)), forces on the platform at each B_i
        (n, 3) (the last segment and the half node weight) [N], the largest tension [N]
        (and, into a list ``extremes``, the smallest tension and the largest strain)."""
        gvec = self.robot.gravity_vector
        EA = np.array([c.EA for c in self.robot.cables])
        l0 = self.segment_lengths[:, None]
        units, lengths, T = segment_forces(np.stack(nodes), l0, EA[:, None])
        if extremes is not None:
            extremes.append((float(T.min()), float((lengths / l0).max()) - 1.0))
        f = T[..., None] * units                                   # (n, N, 3)
        mg = self.node_masses[:, None] * gvec
        return ((f[:, 1:] - f[:, :-1] + mg[:, None, :]).ravel(), -f[:, -1] + 0.5 * mg,
                float(T.max()))

    def _chain_forces_loop(
            self, nodes: list[NDArray[np.float64]], extremes: list[Any] | None = None,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        """As :meth:`_chain_forces_stacked`, cable by cable (any N per cable)."""
        gvec = self.robot.gravity_vector
        inner, F, t_max = [], np.empty((len(nodes), 3)), 0.0
        t_min, strain = np.inf, -np.inf
        for i, x in enumerate(nodes):
            l0 = self.segment_lengths[i]
            units, lengths, T = segment_forces(x, l0, self.robot.cables[i].EA)
            f = T[:, None] * units
            inner.append((f[1:] - f[:-1] + self.node_masses[i] * gvec).ravel())
            F[i] = -f[-1] + 0.5 * self.node_masses[i] * gvec
            t_max = max(t_max, float(T.max()))
            t_min, strain = min(t_min, float(T.min())), max(strain, lengths.max() / l0 - 1.0)
        if extremes is not None:
            extremes.append((t_min, float(strain)))
        return np.concatenate(inner), F, t_max

    def residual_scales(self) -> tuple[float, float]:
        """(moment arm [m], weight [N]) of :meth:`relative_residual`: moments are divided by
        the arm, and the force scale is weight + t_max."""
        return self._moment_arm, self._force_scale(0.0)

    def _force_scale(self, t_max: float) -> float:
        rob = self.robot
        weight = rob.g * (rob.platform.mass + np.sum(
            [c.mass_per_length for c in rob.cables] * self.unstretched_lengths))
        return max(weight + t_max, np.finfo(float).tiny)

    def rounding_floor(self, pose: Pose, t_max: float) -> float:
        """Relative residual [-] below which rounding, not the configuration, decides.

        A segment tension EA (l / l0 - 1) is computed from node coordinates of size |x| with
        relative rounding eps, so it carries an error of about eps EA |x| / l0; summed on a
        node and scaled like :meth:`relative_residual`: 4 eps max_i(EA_i / l0_i) |x|_max /
        (m_p g + sum m L0 g + t_max).
        """
        pose = as_pose(pose)
        B, _ = self.robot.attachment_points(pose)
        size = max(np.abs(self.robot.anchors).max(), np.abs(B).max(), 1.0)
        EA = np.array([c.EA for c in self.robot.cables])
        return float(4 * np.finfo(float).eps * np.max(EA / self.segment_lengths) * size
                     / self._force_scale(t_max))

    def relative_residual(self, R: NDArray[np.float64], t_max: float) -> float:
        """Largest unbalanced force of R (moments divided by the platform size) over the
        force scale m_p g + sum m L0 g + t_max [-]: the measure of ``equilibrium(tol=)``."""
        scaled = np.abs(R)
        rot = np.array([d in ("rx", "ry", "rz") for d in self.free_dofs])
        scaled[:self.n_free][rot] /= self._moment_arm
        return float(scaled.max(initial=0.0)) / self._force_scale(t_max)

    # -------------------------------------------------------------------- tangent
    def tangent_stiffness(self, pose: Pose, interior: list[NDArray[np.float64]],
                          axial_factor: ArrayLike = 1.0) -> Any:
        """Tangent stiffness K = -dR/dx, sparse, at any configuration.

        Element tangents K_e = k_a n n^T + (T/l)(I - n n^T) (k_a = axial_factor EA / l0 where
        the segment is stretched, 0 where slack) assembled as [[K_e, -K_e], [-K_e, K_e]];
        the node B_i is slaved to the platform, dB_i = J_i x; the lever arms rotating under
        fixed forces add -sum_i [F_i]x [r_i]x - [m_p g_vec]x [r_G]x to the rotation block
        (theory.md §4, §7.1). Symmetric at an equilibrium.

        Parameters
        ----------
        pose : Pose or array_like
        interior : list of ndarray, shape (N_i - 1, 3)
            Interior node positions [m].
        axial_factor : float or complex, or sequence of n_cables of them
            Multiplies EA in the axial term only, e.g. 1 + i eta for hysteretic damping
            (one value for every cable, or one per cable).

        Returns
        -------
        scipy.sparse.csr_matrix, shape (n_dof, n_dof)
            [N/m, N, N m/rad]; complex when ``axial_factor`` is.
        """
        pose, interior = self._check_config(pose, interior)
        factors = np.broadcast_to(np.asarray(axial_factor), (self.robot.n_cables,))
        if not np.all(np.isfinite(factors)):
            raise InvalidParameterError(
                f"axial_factor must be finite, one value or one per cable, got {axial_factor!r}")
        return self.tangent_unchecked(pose, interior, lambda i: factors[i])

    def tangent_unchecked(
            self, pose: Pose, interior: list[NDArray[np.float64]], axial_of: Callable[..., Any],
            elements: list[tuple[NDArray[np.float64], NDArray[np.float64]]] | None = None,
    ) -> Any:
        """:meth:`tangent_stiffness` without the argument checks, with ``axial_of(i)`` the
        axial factor of cable i (for solvers and time stepping); ``elements``, a list of
        (K_e (N_i, 3, 3) [N/m], force on the platform at B_i (3,) [N]) per cable, replaces
        the elements of the configuration (the energy scheme's secant elements)."""
        import scipy.sparse
        rob = self.robot
        fi, nf = self.free_index, self.n_free
        gvec = rob.gravity_vector
        nodes, r = self.full_nodes(pose, interior)
        rows, cols, vals = [], [], []
        dtype = np.result_type(*[axial_of(i) for i in range(rob.n_cables)], float)
        Kpp = np.zeros((nf, nf), dtype=dtype)
        Kgeo = np.zeros((3, 3))
        for i, x in enumerate(nodes):
            N = self.segments[i]
            l0, EA = self.segment_lengths[i], rob.cables[i].EA
            if elements is None:
                units, lengths, T = segment_forces(x, l0, EA)
                axial = np.where(T > 0, axial_of(i) * EA / l0, 0.0)
                ke = element_stiffness(units, lengths, T, axial)
                F = -T[-1] * units[-1] + 0.5 * self.node_masses[i] * gvec
            else:
                ke, F = elements[i]
            J = lever_map(r[i], fi)
            o = self.offsets[i]
            if N > 1:
                rr, cc, vv = block_tridiagonal_entries(ke)
                keep = (rr >= 3) & (rr < 3 * N) & (cc >= 3) & (cc < 3 * N)
                rows.append(rr[keep] - 3 + o)
                cols.append(cc[keep] - 3 + o)
                vals.append(vv[keep])
                kip = -ke[-1] @ J                                  # (3, nf)
                ri = o + 3 * (N - 2) + np.arange(3)
                ci = np.arange(nf)
                rows += [np.repeat(ri, nf), np.tile(ci, 3)]
                cols += [np.tile(ci, 3), np.repeat(ri, nf)]
                vals += [kip.ravel(), kip.ravel()]        # K_pi = K_ip^T
            Kpp += J.T @ ke[-1] @ J
            Kgeo -= skew(F) @ skew(r[i])
        rG = pose.matrix @ rob.platform.center_of_mass
        Kgeo -= skew(rob.platform.mass * gvec) @ skew(rG)
        K6 = np.zeros((6, 6))
        K6[3:, 3:] = Kgeo
        Kpp += K6[np.ix_(fi, fi)]
        ip, jp = np.meshgrid(np.arange(nf), np.arange(nf), indexing="ij")
        rows.append(ip.ravel())
        cols.append(jp.ravel())
        vals.append(Kpp.ravel())
        K = scipy.sparse.coo_matrix(
            (np.concatenate(vals).astype(dtype), (np.concatenate(rows), np.concatenate(cols))),
            shape=(self.n_dof, self.n_dof))
        return K.tocsr()

    def _node_matrix(self, pose: Pose, per_node: NDArray[np.float64],
                     platform_block: NDArray[np.float64]) -> Any:
        """Sparse matrix with ``per_node[i]`` on the interior nodes of cable i (diagonal) and
        the free-DOF block ``platform_block`` + sum_i J_i^T (per_node[i] / 2) J_i."""
        import scipy.sparse
        fi, nf = self.free_index, self.n_free
        _, r = self.robot.attachment_points(pose)
        diag = np.zeros(self.n_dof)
        block = np.array(platform_block, dtype=float)
        for i in range(self.robot.n_cables):
            o, size = self.offsets[i], 3 * (self.segments[i] - 1)
            diag[o:o + size] = per_node[i]
            J = lever_map(r[i], fi)
            block += 0.5 * per_node[i] * J.T @ J
        ip, jp = np.meshgrid(np.arange(nf), np.arange(nf), indexing="ij")
        idx = np.arange(nf, self.n_dof)
        return scipy.sparse.coo_matrix(
            (np.concatenate([block.ravel(), diag[nf:]]),
             (np.concatenate([ip.ravel(), idx]), np.concatenate([jp.ravel(), idx]))),
            shape=(self.n_dof, self.n_dof)).tocsr()

    def mass_matrix(self, pose: Pose) -> Any:
        """Lumped mass matrix at a pose, sparse, shape (n_dof, n_dof) [kg, kg m, kg m^2].

        Interior nodes m l0 (diagonal); platform block M_p + sum_i J_i^T (m l0 / 2) J_i.
        """
        pose = as_pose(pose)
        fi = self.free_index
        Mp = platform_mass_matrix(self.robot.platform, pose.matrix)[np.ix_(fi, fi)]
        return self._node_matrix(pose, self.node_masses, Mp)

    def damping_matrix(self, pose: Pose) -> Any:
        """Viscous damping C at a pose, sparse, shape (n_dof, n_dof) [N s/m]: c l0 at the
        interior nodes, J^T (c l0 / 2) J at B_i, none on the platform."""
        pose = as_pose(pose)
        c = np.array([cb.viscous_damping for cb in self.robot.cables]) * self.segment_lengths
        return self._node_matrix(pose, c, np.zeros((self.n_free, self.n_free)))

    # -------------------------------------------------------------------- statics
    def equilibrium(self, initial_pose: ArrayLike | Pose | None = None, tol: float = 1e-10,
                    max_iter: int = 50) -> LumpedEquilibrium:
        """Static equilibrium of all interior nodes and the free platform DOFs.

        Newton's method with the analytic sparse tangent (:meth:`tangent_stiffness`) and a
        backtracking line search on the residual. Start: the elastic-catenary equilibrium of
        the robot for the same lengths (:meth:`Robot.equilibrium`, forward statics) gives the
        pose, and :func:`~dynstiff.lumped.chain_equilibrium` of every cable at that pose
        gives the nodes. The lumped nodes lie on the catenary (theory.md §1.1); only the
        straight segments replacing the curved arcs change the end forces, by O(l0^2), so
        one or two iterations suffice. Nothing in the model changes: linearise about the result
        with :class:`~dynstiff.lumped.LumpedLinearModel`.

        Parameters
        ----------
        initial_pose : Pose or array_like, optional
            Start of the elastic-catenary forward statics (default: its straight-cable
            guess). Held platform DOFs keep the values of this start pose, so give it
            whenever some DOFs are held.
        tol : float
            Converged when the largest unbalanced force (node, platform force, or platform
            moment / platform size) is <= tol (m_p g + sum m L0 g + max T), or below the
            rounding floor of the residual (:meth:`rounding_floor`) when that is larger
            (stiff cables in short segments); ``residual`` of the result is what was reached.
        max_iter : int
            Maximum Newton iterations.

        Returns
        -------
        LumpedEquilibrium

        Raises
        ------
        ConvergenceError
            Newton failed; the message and ``.residual`` give the relative residual.
        SlackCableError
            A cable has a zero-tension segment (at the start or at the solution).
        """
        return lumped_equilibrium(self, initial_pose, tol, max_iter)
