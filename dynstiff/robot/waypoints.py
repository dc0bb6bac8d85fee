"""A path of the platform through timed waypoints, interpolated as CASPR's joint
trajectories are (theory.md §15.8).

Between two waypoints (t_a, p_a, R_a) and (t_b, p_b, R_b), with tau = (t - t_a) / (t_b - t_a):

* the position of P follows, per coordinate, CASPR's ``Spline`` polynomial of the law: a
  line (``"linear"``), the cubic with the end velocities (``"cubic"``), the quintic with
  the end velocities and accelerations (``"quintic"``), or a parabolic blend (constant
  acceleration for ``blend_time`` at both ends, constant speed between,
  ``"parabolic_blend"``);
* the orientation turns about the fixed axis of R_a^T R_b: R(t) = R_a exp(sigma(tau) theta k)
  with theta k the rotation vector of R_a^T R_b and sigma the same law from 0 to 1 with zero
  end rates (CASPR's ``Quaternion.*Interpolation`` of its spherical joints).

Source: CASPR (Lau et al., darwinlau/CASPR), ``src/Util/Mathematics/Geometry/Spline.m``,
``Quaternion.m`` and ``JointTrajectory.m`` (each segment's polynomial solved from its end
conditions; time_definition "relative" or "absolute").
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import real_array
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["LAWS", "WaypointPath"]

#: Interpolation laws between waypoints.
LAWS = ("linear", "cubic", "quintic", "parabolic_blend")


def _hermite(ya: NDArray[np.float64], va: NDArray[np.float64], aa: NDArray[np.float64],
             yb: NDArray[np.float64], vb: NDArray[np.float64], ab: NDArray[np.float64], T: float,
             tau: NDArray[np.float64], law: str) -> NDArray[np.float64]:
    """Per-coordinate polynomial of ``law`` on a segment of duration T [s] at tau in
    [0, 1]; ya.. shape (3,), tau shape (m,). Returns shape (m, 3)."""
    s = tau[:, None]
    if law == "linear":
        return ya + s * (yb - ya)
    if law == "cubic":                     # Hermite basis with end velocities
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        return h00 * ya + h10 * T * va + h01 * yb + h11 * T * vb
    # quintic Hermite basis with end velocities and accelerations
    s2, s3, s4, s5 = s**2, s**3, s**4, s**5
    h0 = 1 - 10 * s3 + 15 * s4 - 6 * s5
    h1 = s - 6 * s3 + 8 * s4 - 3 * s5
    h2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5)
    h3 = 10 * s3 - 15 * s4 + 6 * s5
    h4 = -4 * s3 + 7 * s4 - 3 * s5
    h5 = 0.5 * (s3 - 2 * s4 + s5)
    return (h0 * ya + h1 * T * va + h2 * T**2 * aa + h3 * yb + h4 * T * vb
            + h5 * T**2 * ab)


def _blend(tau: NDArray[np.float64], T: float, tb: float) -> NDArray[np.float64]:
    """Parabolic blend from 0 to 1 over a segment of duration T [s] with blend time tb [s]
    at each end (CASPR's ``Spline.ParabolicBlend``), shape of tau."""
    t = tau * T
    acc = 1.0 / (tb * (T - tb))            # reaches speed acc tb, covers 1 in total
    return np.where(t < tb, 0.5 * acc * t**2,
                    np.where(t > T - tb, 1.0 - 0.5 * acc * (T - t)**2,
                             0.5 * acc * tb**2 + acc * tb * (t - tb)))


def _sigma(tau: NDArray[np.float64], law: str, T: float, tb: float | None) -> NDArray[np.float64]:
    """The scalar law from 0 to 1 with zero end rates (linear: constant rate)."""
    if law == "linear":
        return tau
    if law == "cubic":
        return 3 * tau**2 - 2 * tau**3
    if law == "quintic":
        return 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    return _blend(tau, T, tb)


def _rows(name: str, value: ArrayLike | None, k: int, required: bool = True) -> NDArray[np.float64]:
    if value is None:
        if required:
            raise InvalidParameterError(f"{name} is required")
        return np.zeros((k, 3))
    a = real_array(name, value, f"finite, shape ({k}, 3) (one row per waypoint)")
    if a.shape != (k, 3) or not np.all(np.isfinite(a)):
        raise InvalidParameterError(
            f"{name} must be finite, shape ({k}, 3) (one row per waypoint), got shape "
            f"{a.shape}")
    return a


@dataclass(frozen=True, eq=False)
class WaypointPath:
    """Timed waypoints of the platform and the law that joins them.

    Parameters
    ----------
    times : array_like, shape (k,)
        Waypoint times [s], strictly increasing from 0, k >= 2.
    positions : array_like, shape (k, 3)
        P at the waypoints [m], base frame.
    rotations : array_like, shape (k, 3)
        Platform orientation at the waypoints, rotation vectors [rad].
    law : {"linear", "cubic", "quintic", "parabolic_blend"}
        Interpolation between waypoints (module notes).
    velocities : array_like, shape (k, 3), optional
        Velocity of P at the waypoints [m/s] ("cubic", "quintic"; default 0).
    accelerations : array_like, shape (k, 3), optional
        Acceleration of P at the waypoints [m/s^2] ("quintic"; default 0).
    blend_times : array_like, shape (k - 1,), optional
        Blend time of each segment [s] ("parabolic_blend", required there), less than half
        the segment.
    name : str

    Examples
    --------
    >>> import dynstiff as ds
    >>> path = ds.WaypointPath(times=[0.0, 2.0], positions=[[0, 0, 1.0], [0.5, 0, 1.0]],
    ...                     rotations=[[0, 0, 0], [0, 0, 0]])
    >>> path.duration
    2.0
    >>> position, rotation = path.at(1.0)
    >>> position.tolist()
    [[0.25, 0.0, 1.0]]
    """

    times: np.ndarray
    positions: np.ndarray
    rotations: np.ndarray
    law: str = "quintic"
    velocities: object = None
    accelerations: object = None
    blend_times: object = None
    name: str = ""

    def __post_init__(self) -> None:
        t = real_array("times", self.times, "strictly increasing from 0 [s]")
        if t.ndim != 1 or t.size < 2 or t[0] != 0 or not np.all(np.isfinite(t)) \
                or np.any(np.diff(t) <= 0):
            raise InvalidParameterError(
                f"times must be strictly increasing from 0 [s] with at least 2 waypoints, "
                f"got {np.asarray(self.times).tolist()!r}")
        k = t.size
        if self.law not in LAWS:
            raise InvalidParameterError(f"law must be one of {LAWS}, got {self.law!r}")
        p = _rows("positions", self.positions, k)
        r = _rows("rotations", self.rotations, k)
        v = _rows("velocities", self.velocities, k, required=False)
        a = _rows("accelerations", self.accelerations, k, required=False)
        if self.law in ("linear", "parabolic_blend") and (np.any(v) or np.any(a)):
            raise InvalidParameterError(
                f"velocities and accelerations go with law 'cubic' or 'quintic', not "
                f"{self.law!r}")
        if self.law == "cubic" and np.any(a):
            raise InvalidParameterError("accelerations go with law 'quintic', not 'cubic'")
        tb = None
        if self.law == "parabolic_blend":
            if self.blend_times is None:
                raise InvalidParameterError("law 'parabolic_blend' needs blend_times [s], "
                                            "one per segment")
            what = f"{k - 1} value{'s' if k > 2 else ''} > 0 [s]"
            tb = real_array("blend_times", self.blend_times, what)
            if tb.shape != (k - 1,) or not np.all(tb > 0) or np.any(2 * tb >= np.diff(t)):
                raise InvalidParameterError(
                    f"blend_times must be {what}, each less than half its "
                    f"segment {np.diff(t).tolist()}, got {np.asarray(self.blend_times)!r}")
        elif self.blend_times is not None:
            raise InvalidParameterError("blend_times go with law 'parabolic_blend'")
        for name, val in (("times", t), ("positions", p), ("rotations", r),
                          ("velocities", v), ("accelerations", a), ("blend_times", tb)):
            object.__setattr__(self, name, val)

    @property
    def duration(self) -> float:
        """Time of the last waypoint [s]."""
        return float(self.times[-1])

    def at(self, t: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Positions [m] and rotation vectors [rad] at times ``t`` [s], shapes (m, 3); held
        before 0 and after the end."""
        from scipy.spatial.transform import Rotation
        t = np.atleast_1d(real_array("t", t, "times [s]"))
        if not np.all(np.isfinite(t)):
            raise InvalidParameterError(f"t must be finite times [s], got {t!r}")
        t = np.clip(t, 0.0, self.duration)
        seg = np.clip(np.searchsorted(self.times, t, side="right") - 1, 0, self.times.size - 2)
        P, R = np.empty((t.size, 3)), np.empty((t.size, 3))
        for j in np.unique(seg):
            m = seg == j
            T = self.times[j + 1] - self.times[j]
            tau = (t[m] - self.times[j]) / T
            tb = None if self.blend_times is None else self.blend_times[j]
            if self.law == "parabolic_blend":
                s = _blend(tau, T, tb)[:, None]
                P[m] = self.positions[j] + s * (self.positions[j + 1] - self.positions[j])
            else:
                P[m] = _hermite(self.positions[j], self.velocities[j], self.accelerations[j],
                                self.positions[j + 1], self.velocities[j + 1],
                                self.accelerations[j + 1], T, tau, self.law)
            Ra = Rotation.from_rotvec(self.rotations[j])
            rel = (Ra.inv() * Rotation.from_rotvec(self.rotations[j + 1])).as_rotvec()
            sig = _sigma(tau, self.law, T, tb)
            R[m] = (Ra * Rotation.from_rotvec(sig[:, None] * rel)).as_rotvec()
        return P, R

    def poses(self, n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``n`` poses (x y z rx ry rz [m, rad]) at equally spaced times from 0 to the end,
        shape (n, 6), and those times [s], shape (n,)."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
            raise InvalidParameterError(f"n must be an integer >= 2, got {n!r}")
        t = np.linspace(0.0, self.duration, n)
        P, R = self.at(t)
        return np.hstack([P, R]), t
