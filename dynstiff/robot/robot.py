"""Cable robot model and its statics with sagging cables.

A robot is n cables, cable i running from its anchor A_i (base frame, the winch exit point,
clamped) to the attachment point b_i on the platform (platform frame), plus a rigid platform.
Its static equilibrium uses the exact elastic catenary of every cable (theory.md §1.1) and the
platform's wrench balance; gravity is (0, 0, -g).

Pose: ``position`` p [m] of the platform reference point P and ``rotation`` vector [rad]
(axis * angle, base frame) of R_p. Small motions are x = (dp, dtheta), dtheta a small rotation
vector in the base frame, so dB_i = dp + dtheta x r_i with r_i = R_p b_i.
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import _validate
from dynstiff._text import counted
from dynstiff._validate import flag, positive_scalar, real_array
from dynstiff._vec import cross
from dynstiff.cable.catenary_solve import solve_catenary
from dynstiff.constants import MAX_COORDINATE, STANDARD_GRAVITY
from dynstiff.errors import InvalidParameterError
from dynstiff.io.caspr import read_caspr
from dynstiff.params import Cable
from dynstiff.robot.equilibrium import Equilibrium
from dynstiff.robot.forward_statics import forward_statics
from dynstiff.robot.platform import Platform, lever_map
from dynstiff.robot.pose import Pose, as_pose
from dynstiff.robot.statics import inverse_statics

if TYPE_CHECKING:
    from pathlib import Path

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.cable.catenary import CatenaryState

__all__ = ["Robot", "Pose", "Equilibrium", "as_pose", "geometric_stiffness"]


@dataclass(frozen=True)
class Robot:
    """Cable-driven parallel robot with heavy elastic cables.

    Parameters
    ----------
    anchors : array_like, shape (n, 3)
        Cable exit points A_i in the base frame [m]. Cables may share an anchor point (an
        inverted Stewart platform, two winches behind one pulley).
    attachments : array_like, shape (n, 3)
        Attachment points b_i in the platform frame [m]. Cables may share an attachment
        point; two cables sharing both ends are refused (one cable counted twice).
    cables : Cable or sequence of n Cable
    platform : Platform
    g : float, optional
        Gravity [m/s^2] (default :data:`STANDARD_GRAVITY`).
    tension_limits : (float, float), optional
        Admissible tension range [t_min, t_max] [N] of the tension distribution, held all
        along each cable (inverse statics, design checks).
    name : str, optional

    Examples
    --------
    >>> import dynstiff as ds
    >>> robot = ds.load_scene("cogiro").robot
    >>> robot.n_cables, robot.platform.mass
    (8, 91.058)
    >>> eq = robot.equilibrium(pose=[0.0, 0.0, 1.0])
    >>> print(f"{eq.tensions.min():.1f} N")
    270.3 N
    """

    anchors: np.ndarray
    attachments: np.ndarray
    cables: tuple
    platform: Platform
    g: float = STANDARD_GRAVITY
    tension_limits: tuple = (1.0, np.inf)
    name: str = ""

    def __post_init__(self) -> None:
        A = real_array("anchors", self.anchors, "a finite (n, 3) array [m]")
        b = real_array("attachments", self.attachments, "a finite (n, 3) array [m]")
        if A.ndim != 2 or A.shape[1] != 3 or not np.all(np.isfinite(A)):
            raise InvalidParameterError(
                f"anchors must be a finite (n, 3) array [m], got shape {A.shape}")
        if b.shape != A.shape or not np.all(np.isfinite(b)):
            raise InvalidParameterError(
                f"attachments must be a finite array of shape {A.shape} like anchors, got "
                f"shape {b.shape}")
        for name, X in (("anchors", A), ("attachments", b)):
            if np.abs(X).max(initial=0.0) > MAX_COORDINATE:
                raise InvalidParameterError(
                    f"{name} must lie within {MAX_COORDINATE:g} m of the origin, got "
                    f"{np.abs(X).max(initial=0.0):.3g} m")
        n = A.shape[0]
        cables = self.cables
        if isinstance(cables, Cable):
            cables = (cables,) * n
        cables = tuple(cables)
        if len(cables) != n or not all(isinstance(c, Cable) for c in cables):
            raise InvalidParameterError(
                f"cables must be one Cable or a sequence of {counted(n, 'Cable')}, got "
                f"{self.cables!r}")
        if not isinstance(self.platform, Platform):
            raise InvalidParameterError(
                f"platform must be a dynstiff.Platform, got {type(self.platform).__name__}")
        n_free = len(self.platform.free_dofs)
        if n < n_free:
            raise InvalidParameterError(
                f"anchors: {counted(n, 'cable')} cannot hold a platform with "
                f"{counted(n_free, 'free DOF')} {self.platform.free_dofs}; at least {n_free} "
                f"{'is' if n_free == 1 else 'are'} needed")
        _refuse_duplicate_cables(A, b)
        g = positive_scalar("g", self.g, allow_zero=True)
        limits = real_array("tension_limits", self.tension_limits, "(t_min, t_max) [N]")
        if limits.shape != (2,):
            raise InvalidParameterError(
                f"tension_limits must be (t_min, t_max) [N], got {self.tension_limits!r}")
        t_min, t_max = (float(t) for t in limits)
        if not (0 <= t_min < t_max):
            raise InvalidParameterError(
                f"tension_limits must satisfy 0 <= t_min < t_max [N], got {self.tension_limits!r}")
        object.__setattr__(self, "anchors", A)
        object.__setattr__(self, "attachments", b)
        object.__setattr__(self, "cables", cables)
        object.__setattr__(self, "g", g)
        object.__setattr__(self, "tension_limits", (t_min, t_max))

    @classmethod
    def from_caspr(cls, bodies_xml: str | Path, cables_xml: str | Path, cable: Cable,
                   cable_set: str | None = None, inertia_convention: str = "products",
                   g: float = STANDARD_GRAVITY, min_tension: float = 1.0) -> Robot:
        """Robot of a single-body CASPR model (:mod:`dynstiff.io.caspr`, theory.md §15.1).

        Parameters
        ----------
        bodies_xml, cables_xml : str or Path
            CASPR's ``*_bodies.xml`` and ``*_cables.xml``.
        cable : Cable or sequence of Cable
            Cable properties (CASPR holds no cable mass or axial stiffness).
        cable_set : str, optional
            ``<cable_set>`` id (default: the file's ``default_cable_set``).
        inertia_convention : {"products", "tensor"}
            Meaning of the printed Ixy, Ixz, Iyz: products of inertia (default; tensor entry
            = -value, theory.md §15.2) or tensor entries.
        g : float
            Gravity [m/s^2].
        min_tension : float
            Least t_min [N]: CASPR's force_min is often 0, a slack (and singular) sagging
            cable; t_min = max(force_min, min_tension).

        Returns
        -------
        Robot
            Its ``tension_limits`` are the tightest pair holding for every cable. The pose
            ``q_initial`` is ``dynstiff.io.caspr.read_caspr(...).position`` / ``.rotation``
            (or :func:`dynstiff.scenes.import_caspr`, which returns a Scene with it).
        """
        m = read_caspr(bodies_xml, cables_xml, cable_set, inertia_convention, stacklevel=3)
        platform = Platform(mass=m.mass, center_of_mass=m.center_of_mass, inertia=m.inertia,
                            free_dofs=m.free_dofs)
        return cls(anchors=m.anchors, attachments=m.attachments, cables=cable,
                   platform=platform, g=g,
                   tension_limits=(max(m.tension_limits[0], positive_scalar(
                       "min_tension", min_tension)), m.tension_limits[1]),
                   name=m.name)

    @property
    def n_cables(self) -> int:
        """Number of cables."""
        return self.anchors.shape[0]

    @property
    def gravity_vector(self) -> NDArray[np.float64]:
        """(0, 0, -g) [m/s^2]."""
        return np.array([0.0, 0.0, -self.g])

    # ------------------------------------------------------------------ geometry
    def attachment_points(self, pose: Pose) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Attachment points B_i in the base frame [m], shape (n, 3), and lever arms r_i."""
        pose = as_pose(pose)
        r = self.attachments @ pose.matrix.T
        return pose.position + r, r

    def gravity_wrench(self, pose: Pose) -> NDArray[np.float64]:
        """Gravity wrench on the platform about P [N, N m], shape (6,)."""
        pose = as_pose(pose)
        fg = self.platform.mass * self.gravity_vector
        rG = pose.matrix @ self.platform.center_of_mass
        return np.concatenate([fg, cross(rG, fg)])

    def cable_states(self, pose: Pose,
                     unstretched_lengths: NDArray[np.float64]) -> list[CatenaryState]:
        """Elastic-catenary state of every cable at a pose, list of CatenaryState."""
        B, _ = self.attachment_points(pose)
        L0 = _validate.unstretched_lengths(unstretched_lengths, self.n_cables)
        return [solve_catenary(self.anchors[i], B[i], L0[i], self.cables[i], self.g)
                for i in range(self.n_cables)]

    def wrench(self, pose: Pose, states: list[CatenaryState]) -> NDArray[np.float64]:
        """Total wrench on the platform about P (cables + gravity), shape (6,)."""
        _, r = self.attachment_points(pose)
        f = np.array([s.force_on_end for s in states])
        w = self.gravity_wrench(pose)
        w[:3] += f.sum(axis=0)
        w[3:] += cross(r, f).sum(axis=0)
        return w

    def platform_stiffness(self, pose: Pose,
                           states: list[CatenaryState] | tuple[CatenaryState, ...],
                           symmetric_part: bool = False) -> NDArray[np.float64]:
        """6x6 static stiffness -dW/dx of the platform about P [N/m, N, N m/rad].

        K = sum_i J_i^T K_i J_i + K_geo, J_i = [I, -[r_i]x], K_geo = [[0, 0], [0,
        -sum [f_i]x [r_i]x - [m g]x [r_G]x]] (theory.md §4), valid at any pose (not only at
        equilibrium, where K_geo becomes symmetric).
        """
        pose = as_pose(pose)
        symmetric_part = flag("symmetric_part", symmetric_part)
        _, r = self.attachment_points(pose)
        K = np.zeros((6, 6))
        for ri, s in zip(r, states):
            J = lever_map(ri)
            K += J.T @ s.end_stiffness @ J
        K[3:, 3:] += geometric_stiffness(self, pose, states)
        return 0.5 * (K + K.T) if symmetric_part else K

    # ------------------------------------------------------------------ statics
    def equilibrium(self, pose: ArrayLike | Pose | None = None,
                    unstretched_lengths: ArrayLike | None = None,
                    tension_reference: ArrayLike | None = None,
                    initial_pose: Pose | None = None, tol: float = 1e-10,
                    max_iter: int | None = None, start: ArrayLike | None = None) -> Equilibrium:
        """Static equilibrium with sagging cables.

        Give exactly one of:

        ``pose``
            Inverse statics: the tension distribution that balances the platform at this
            pose (see :func:`~dynstiff.robot.statics.tension_distribution`), with the cable
            directions at B taken from the elastic catenary and iterated to convergence, then
            each cable's unstretched length for its tension at B.
        ``unstretched_lengths``
            Forward statics: the pose of the free DOFs at which the platform is in
            equilibrium (Newton with the analytic 6x6 stiffness), starting from the
            straight-cable estimate (or ``initial_pose``).

        ``max_iter`` defaults to 500 fixed-point iterations for inverse statics (they contract
        slowly when the cables are light or nearly slack, since the direction at B then
        depends strongly on the tension) and 50 Newton iterations for forward statics.

        ``start`` (inverse statics): an :class:`Equilibrium` of this robot at a neighbouring
        pose; its cable directions and catenaries start the iteration (a sweep over poses
        warm-starts each pose from the previous one). The equilibrium reached is the same;
        where the iteration from ``start`` fails, the pose is solved without it, and an
        error is that of the pose without a start.

        Returns
        -------
        Equilibrium

        Raises
        ------
        InvalidParameterError, SlackCableError, ConvergenceError
        """
        if (pose is None) == (unstretched_lengths is None):
            raise InvalidParameterError("give exactly one of pose= or unstretched_lengths=")
        tol = positive_scalar("tol", tol)
        if tol < 1e-15:
            raise InvalidParameterError(
                f"tol must be >= 1e-15 (the residual is computed in float64), got {tol!r}")
        if max_iter is not None and (isinstance(max_iter, bool) or
                                     not isinstance(max_iter, Integral) or max_iter < 1):
            raise InvalidParameterError(f"max_iter must be an integer >= 1, got {max_iter!r}")
        if start is not None and not (isinstance(start, Equilibrium)
                                      and start.robot.n_cables == self.n_cables
                                      and np.array_equal(start.robot.anchors, self.anchors)):
            raise InvalidParameterError(
                f"start must be an Equilibrium of this robot (same anchors), got "
                f"{type(start).__name__}")
        if pose is not None:
            return inverse_statics(self, as_pose(pose), tension_reference, tol,
                                   500 if max_iter is None else max_iter, start)
        return forward_statics(self, _validate.unstretched_lengths(unstretched_lengths,
                                                                   self.n_cables),
                               None if initial_pose is None else as_pose(initial_pose), tol,
                               50 if max_iter is None else max_iter)


def _refuse_duplicate_cables(A: NDArray[np.float64], b: NDArray[np.float64]) -> None:
    """Raise when two cables share both ends: the same anchor and the same attachment point.

    Cables may share an anchor (two winches behind one exit point or pulley, the inverted
    Stewart platform of the NIST RoboCrane) or an attachment point (cables meeting at one
    point of the platform); each cable's catenary, stiffness and modes are its own. Two
    cables with both ends in common are one cable counted twice: their tensions are not
    determined separately, and the message says how to merge them.
    """
    n = A.shape[0]
    if n < 2:
        return
    tol_a = 1e-9 * max(1.0, np.abs(A).max())
    tol_b = 1e-9 * max(1.0, np.abs(b).max())
    same_a = np.linalg.norm(A[:, None, :] - A[None, :, :], axis=2) <= tol_a
    same_b = np.linalg.norm(b[:, None, :] - b[None, :, :], axis=2) <= tol_b
    both = np.triu(same_a & same_b, k=1)
    if np.any(both):
        i, j = (int(k) for k in np.argwhere(both)[0])
        raise InvalidParameterError(
            f"anchors, attachments: cables {i} and {j} have both ends in common (anchor "
            f"{A[i].tolist()} m, attachment {b[i].tolist()} m): one cable counted twice, "
            f"whose two tensions no statics can tell apart; merge them into one cable (mass "
            f"per length and EA the sums of the two) or remove one")


def geometric_stiffness(
        robot: Robot, pose: Pose, states: list[CatenaryState] | tuple[CatenaryState, ...],
) -> NDArray[np.float64]:
    """Rotational block of K_geo [N m/rad], shape (3, 3): -sum [f_i]x [r_i]x - [m g]x [r_G]x,
    each product written as [a]x [b]x = b a^T - (a . b) I, all cables at once."""
    pose = as_pose(pose)
    _, r = robot.attachment_points(pose)
    f = np.array([s.force_on_end for s in states]).reshape(-1, 3)
    rG = pose.matrix @ robot.platform.center_of_mass
    mg = robot.platform.mass * robot.gravity_vector
    return (np.einsum("ij,ij", f, r) + mg @ rG) * np.eye(3) - r.T @ f - np.outer(rG, mg)
