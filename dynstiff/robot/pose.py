"""Platform pose: position of the reference point P and rotation vector.

Small motions about a pose are x = (dp, dtheta), dtheta a small rotation vector in the base
frame (docs/theory.md §4).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import refuse_bools
from dynstiff.constants import MAX_COORDINATE
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.platform import (
    quaternion_product,
    quaternion_to_rotvec,
    rotation_matrix,
    rotvec_to_quaternion,
)

if TYPE_CHECKING:

    from numpy.typing import NDArray

__all__ = ["Pose", "as_pose"]


@dataclass(frozen=True, eq=False)
class Pose:
    """Platform pose: position [m] of P and rotation vector [rad], both (3,), copies of
    what is given.

    Examples
    --------
    >>> import dynstiff as ds
    >>> pose = ds.Pose([0.0, 0.0, 1.0], rotation=[0.0, 0.0, 0.1])
    >>> pose.position.tolist(), pose.rotation.tolist()
    ([0.0, 0.0, 1.0], [0.0, 0.0, 0.1])
    """

    position: np.ndarray
    rotation: np.ndarray = field(default_factory=lambda: np.zeros(3))

    def __post_init__(self) -> None:
        for name in ("position", "rotation"):
            refuse_bools(f"pose {name}", getattr(self, name))
            try:
                v = np.array(getattr(self, name), dtype=float)
            except (TypeError, ValueError):
                v = np.zeros(0)
            if v.shape != (3,) or not np.all(np.isfinite(v)) or \
                    np.abs(v).max() > MAX_COORDINATE:
                raise InvalidParameterError(
                    f"pose {name} must be 3 finite numbers within {MAX_COORDINATE:g}, got "
                    f"{getattr(self, name)!r}")
            object.__setattr__(self, name, v)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Pose):
            return NotImplemented
        return (np.array_equal(self.position, other.position)
                and np.array_equal(self.rotation, other.rotation))

    def __hash__(self) -> int:
        return hash((tuple(self.position.tolist()), tuple(self.rotation.tolist())))

    def __repr__(self) -> str:
        p = ", ".join(f"{v:.5g}" for v in self.position)
        r = ", ".join(f"{v:.3g}" for v in self.rotation)
        return f"Pose(position=[{p}] m, rotation=[{r}] rad)"

    @property
    def matrix(self) -> NDArray[np.float64]:
        """Rotation matrix R_p, shape (3, 3) (a new array; computed again only when the
        rotation vector has changed)."""
        key = self.rotation.tobytes()
        cached = self.__dict__.get("_matrix")
        if cached is None or cached[0] != key:
            cached = self.__dict__["_matrix"] = (key, rotation_matrix(self.rotation))
        return cached[1].copy()

    def as_vector(self) -> NDArray[np.float64]:
        """(x, y, z, rx, ry, rz), shape (6,)."""
        return np.concatenate([self.position, self.rotation])

    def moved(self, dx: NDArray[np.float64]) -> Pose:
        """Pose after the small motion dx = (dp, dtheta) (dtheta in the base frame)."""
        q = quaternion_product(rotvec_to_quaternion(dx[3:]),
                               rotvec_to_quaternion(self.rotation))
        return Pose(self.position + dx[:3], quaternion_to_rotvec(q))


def as_pose(pose: list[float] | Pose) -> Pose:
    """A :class:`Pose` from a Pose, (position, rotation), or 3 / 6 numbers."""
    if isinstance(pose, Pose):
        return pose
    if isinstance(pose, (tuple, list)) and len(pose) == 2:
        return Pose(*pose)
    refuse_bools("pose", pose)
    try:
        v = np.asarray(pose, dtype=float)
    except (TypeError, ValueError):
        v = None
    if v is not None and v.shape == (3,):
        return Pose(v)
    if v is not None and v.shape == (6,):
        return Pose(v[:3], v[3:])
    raise InvalidParameterError(
        f"pose must be a Pose, (position, rotation), 3 or 6 numbers, got {pose!r}")
