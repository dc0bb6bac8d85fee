"""Rigid platform: parameters, pose, and the Lagrangian rigid-body mass matrix.

Notation (theory.md §4)
-----------------------
=========  ===============================================================  =======
symbol     meaning                                                          unit
=========  ===============================================================  =======
P          reference point of the platform (origin of the platform frame)   m
p          position of P in the base frame                                  m
R_p        rotation of the platform frame into the base frame               --
c_G        centre of mass G in the platform frame                           m
I_G        inertia tensor about G, platform axes (tensor entries)           kg m^2
x          small motion (dp, dtheta): translation of P, rotation vector     m, rad
=========  ===============================================================  =======

Inertia convention: ``inertia`` is the *tensor* I_G with diagonal entries int (y^2 + z^2) dm
etc. and off-diagonal entries **I_xy = -int x y dm** (minus the product of inertia). A CAD
table that prints products of inertia P_xy = int x y dm must be entered with the sign changed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import positive_scalar, real_array
from dynstiff._vec import cross
from dynstiff.constants import DOF_NAMES
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["Platform", "DOF_NAMES", "skew", "lever_map", "lever_maps", "rotation_matrix",
           "platform_mass_matrix", "rotvec_to_quaternion", "quaternion_to_rotvec",
           "quaternion_product"]



def skew(a: NDArray[np.float64]) -> NDArray[np.float64]:
    """Cross-product matrix [a]x with [a]x b = a x b; a of shape (3,) -> (3, 3)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def lever_map(r: NDArray[np.float64],
              free_index: NDArray[np.int64] | None = None) -> NDArray[np.float64]:
    """J = [I, -[r]x] [-, m], shape (3, 6), or (3, n_free) restricted to ``free_index``.

    Maps a small platform motion x = (dp, dtheta) about P (base frame) to the motion
    dp + dtheta x r of the point at lever arm r [m] (theory.md §4); J^T f is the wrench about
    P of a force f applied there.
    """
    J = np.hstack([np.eye(3), -skew(r)])
    return J if free_index is None else J[:, free_index]


def lever_maps(r: NDArray[np.float64],
               free_index: NDArray[np.int64] | None = None) -> NDArray[np.float64]:
    """:func:`lever_map` of many lever arms at once: r of shape (n, 3) -> (n, 3, 6), or
    (n, 3, n_free) restricted to ``free_index`` [-, m]."""
    r = np.asarray(r, dtype=float)
    J = np.zeros((r.shape[0], 3, 6))
    J[:, 0, 0] = J[:, 1, 1] = J[:, 2, 2] = 1.0
    # -[r]x entry by entry (5 us for 8 arms, where stacking it took 31 us)
    J[:, 0, 4], J[:, 0, 5] = r[:, 2], -r[:, 1]
    J[:, 1, 3], J[:, 1, 5] = -r[:, 2], r[:, 0]
    J[:, 2, 3], J[:, 2, 4] = r[:, 1], -r[:, 0]
    return J if free_index is None else J[:, :, free_index]


def rotation_matrix(rotvec: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation matrix [-] of a rotation vector [rad] (axis * angle), shape (3,) -> (3, 3).

    From the unit quaternion of :func:`rotvec_to_quaternion` (the same arithmetic as
    ``scipy.spatial.transform.Rotation.from_rotvec(...).as_matrix()``, without its
    per-call overhead: it runs several times per time step)."""
    x, y, z, w = rotvec_to_quaternion(rotvec)
    return np.array([
        [w * w + x * x - y * y - z * z, 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), w * w - x * x + y * y - z * z, 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), w * w - x * x - y * y + z * z]])


def rotvec_to_quaternion(rotvec: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit quaternion (x, y, z, w) of a rotation vector [rad], shape (3,) -> (4,); the
    factor sin(theta/2)/theta by its series below theta = 1e-3 (as scipy's Rotation)."""
    v = np.asarray(rotvec, dtype=float)
    theta = float(np.sqrt(v @ v))
    if theta <= 1e-3:
        t2 = theta * theta
        scale = 0.5 - t2 / 48 + t2 * t2 / 3840
    else:
        scale = np.sin(theta / 2) / theta
    return np.array([*(scale * v), np.cos(theta / 2)])


def quaternion_to_rotvec(q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation vector [rad] of a unit quaternion (x, y, z, w), angle in [0, pi] (as
    scipy's ``Rotation.as_rotvec``), shape (4,) -> (3,)."""
    q = np.asarray(q, dtype=float)
    if q[3] < 0:
        q = -q
    n = float(np.sqrt(q[:3] @ q[:3]))
    theta = 2 * np.arctan2(n, q[3])
    if theta <= 1e-3:
        t2 = theta * theta
        scale = 2 + t2 / 12 + 7 * t2 * t2 / 2880
    else:
        scale = theta / np.sin(theta / 2)
    return scale * q[:3]


def quaternion_product(p: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Quaternion product p q (x, y, z, w): the rotation q followed by p, shape (4,)."""
    pv, pw, qv, qw = p[:3], p[3], q[:3], q[3]
    return np.array([*(pw * qv + qw * pv + cross(pv, qv)), pw * qw - pv @ qv])


@dataclass(frozen=True)
class Platform:
    """Rigid platform of a cable robot.

    Parameters
    ----------
    mass : float
        Mass [kg], > 0.
    center_of_mass : array_like, shape (3,)
        Centre of mass G in the platform frame [m].
    inertia : array_like, shape (3, 3)
        Inertia tensor about G in platform axes [kg m^2]; symmetric positive definite,
        off-diagonal entries are minus the products of inertia (see module notes). A point
        mass has zero inertia: use ``inertia=0`` together with free translations only. The
        checks are relative, so a tensor's verdict does not depend on its units: symmetric
        to 1e-12 of its largest entry, no eigenvalue below -1e-12 of the largest.
    free_dofs : sequence of str, optional
        Free degrees of freedom among ``DOF_NAMES`` (default all six). Held DOFs are fixed
        (a pinned pendulum, a planar body, a point mass are the same model with some held).

    Examples
    --------
    >>> import dynstiff as ds
    >>> import numpy as np
    >>> p = ds.Platform(mass=10.0, inertia=np.diag([0.5, 0.5, 0.8]), free_dofs=("x", "y", "z"))
    >>> p.mass, p.free_dofs
    (10.0, ('x', 'y', 'z'))
    """

    mass: float
    center_of_mass: np.ndarray = field(default_factory=lambda: np.zeros(3))
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))
    free_dofs: tuple = DOF_NAMES

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", positive_scalar("mass", self.mass))
        c = real_array("center_of_mass", self.center_of_mass, "3 finite numbers [m]")
        if c.shape != (3,) or not np.all(np.isfinite(c)):
            raise InvalidParameterError(
                f"center_of_mass must be 3 finite numbers [m], got {self.center_of_mass!r}")
        I = real_array("inertia", self.inertia, "a finite 3x3 tensor [kg m^2]")
        if I.shape == ():
            I = np.eye(3) * float(I)
        if I.shape != (3, 3) or not np.all(np.isfinite(I)):
            raise InvalidParameterError(
                f"inertia must be a finite 3x3 tensor [kg m^2], got shape {I.shape}")
        if not np.allclose(I, I.T, rtol=1e-12, atol=1e-12 * np.abs(I).max()):
            raise InvalidParameterError(f"inertia must be symmetric, got {I.tolist()}")
        if isinstance(self.free_dofs, str):
            raise InvalidParameterError(
                f"free_dofs must be a sequence of names from {DOF_NAMES}, not one string, got "
                f"{self.free_dofs!r}")
        dofs = tuple(self.free_dofs)
        unknown = [d for d in dofs if d not in DOF_NAMES]
        if unknown or len(set(dofs)) != len(dofs) or not dofs:
            raise InvalidParameterError(
                f"free_dofs must be distinct names from {DOF_NAMES}, got {self.free_dofs!r}")
        dofs = tuple(d for d in DOF_NAMES if d in dofs)       # canonical order
        ev = np.linalg.eigvalsh(I)
        rotational = any(d in dofs for d in ("rx", "ry", "rz"))
        if rotational and ev[0] <= 0:
            raise InvalidParameterError(
                f"inertia must be positive definite when a rotation is free, eigenvalues "
                f"{ev.tolist()} [kg m^2]")
        if ev[0] < -1e-12 * abs(ev[-1]):
            raise InvalidParameterError(f"inertia must be positive semi-definite, eigenvalues "
                                        f"{ev.tolist()} [kg m^2]")
        if rotational and (ev[2] > ev[0] + ev[1] + 1e-9 * ev[2]):
            raise InvalidParameterError(
                f"inertia violates the triangle inequality of principal moments "
                f"{ev.tolist()} [kg m^2]: not a physical body")
        object.__setattr__(self, "center_of_mass", c)
        object.__setattr__(self, "inertia", I)
        object.__setattr__(self, "free_dofs", dofs)

    @property
    def free_index(self) -> NDArray[np.int64]:
        """Indices of the free DOFs in ``DOF_NAMES`` order, shape (n_free,)."""
        return np.array([DOF_NAMES.index(d) for d in self.free_dofs])


def platform_mass_matrix(platform: Platform, rotation: NDArray[np.float64]) -> NDArray[np.float64]:
    """6x6 rigid-body mass matrix about the reference point P, base axes.

    M_p = [[m I, -m [r_G]x], [m [r_G]x, I_G^w - m [r_G]x [r_G]x]], r_G = R_p c_G,
    I_G^w = R_p I_G R_p^T (theory.md §4), for the motion x = (dp, dtheta).

    Parameters
    ----------
    platform : Platform
    rotation : ndarray, shape (3, 3)
        R_p.

    Returns
    -------
    ndarray, shape (6, 6) [kg, kg m, kg m^2]
    """
    m = platform.mass
    rG = rotation @ platform.center_of_mass
    S = skew(rG)
    M = np.zeros((6, 6))
    M[:3, :3] = m * np.eye(3)
    M[:3, 3:] = -m * S
    M[3:, :3] = m * S
    M[3:, 3:] = rotation @ platform.inertia @ rotation.T - m * S @ S
    return M
