"""Trajectories of the platform and their tracking by the lumped-mass time-domain model.

The workflow of trajectory planning with heavy cables (seed paper 000): the cable lengths
along a desired path come from the *quasi-static* inverse kinematics with sagging cables
(inverse statics at each sample of the path, :meth:`Robot.equilibrium`), and are fed, as
winch commands L0_i(t), to the dynamic model (:func:`dynstiff.lumped.simulate`); the
platform then moves along and vibrates around the desired path. :func:`track` runs the
whole chain and returns the deviation from the desired path.

A path is sampled as a :class:`Trajectory` (times, positions, rotation vectors of P);
:func:`line` and :func:`circle` build the common ones, at constant speed (the platform
starts at rest, so the commanded velocity jumps at t = 0 as in a constant-speed command)
or with a smooth start and stop (``ramp`` > 0: the speed follows (1 - cos) / 2 over ``ramp``
seconds).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import finite_scalar, point, positive_scalar
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    import pandas as pd
    from numpy.typing import ArrayLike, NDArray

__all__ = ["Trajectory", "line", "circle", "following", "quasi_static_lengths",
           "TrackingResult", "track"]


@dataclass(frozen=True)
class Trajectory:
    """A sampled path of the platform reference point P.

    Attributes
    ----------
    times : ndarray, shape (k,)
        Sample times [s], strictly increasing, from 0.
    positions : ndarray, shape (k, 3)
        Position of P [m], base frame.
    rotations : ndarray, shape (k, 3)
        Rotation vector of the platform [rad].
    name : str
    path : callable, optional
        Exact path ``t (n,) [s] -> (positions (n, 3), rotations (n, 3))``; without it,
        :meth:`at` interpolates the samples linearly.
    """

    times: np.ndarray
    positions: np.ndarray
    rotations: np.ndarray
    name: str = ""
    path: object = None

    def __post_init__(self) -> None:
        t = np.asarray(self.times, dtype=float)
        p = np.asarray(self.positions, dtype=float)
        r = np.asarray(self.rotations, dtype=float)
        if t.ndim != 1 or t.size < 2 or t[0] != 0 or np.any(np.diff(t) <= 0) \
                or not np.all(np.isfinite(t)):
            raise InvalidParameterError(
                f"times must be strictly increasing from 0 [s] with >= 2 samples, got {t!r}")
        for name, a in (("positions", p), ("rotations", r)):
            if a.shape != (t.size, 3) or not np.all(np.isfinite(a)):
                raise InvalidParameterError(
                    f"{name} must be finite, shape ({t.size}, 3), got shape {a.shape}")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "positions", p)
        object.__setattr__(self, "rotations", r)

    @property
    def duration(self) -> float:
        """Last sample time [s]."""
        return float(self.times[-1])

    def at(self, t: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Positions [m] and rotation vectors [rad] at times ``t`` [s], shapes (n, 3): from
        the exact path when there is one, else linearly interpolated; held after the end."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if self.path is not None:
            return self.path(np.clip(t, 0.0, self.duration))
        P = np.column_stack([np.interp(t, self.times, self.positions[:, k]) for k in range(3)])
        R = np.column_stack([np.interp(t, self.times, self.rotations[:, k]) for k in range(3)])
        return P, R

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame: time [s], x y z [m], rx ry rz [rad]."""
        import pandas as pd
        cols = {"time [s]": self.times}
        for k, n in enumerate("xyz"):
            cols[f"{n} [m]"] = self.positions[:, k]
        for k, n in enumerate(("rx", "ry", "rz")):
            cols[f"{n} [rad]"] = self.rotations[:, k]
        return pd.DataFrame(cols)


def _arc_length(total: float, speed: float, ramp: float) -> tuple[float, Callable[..., Any]]:
    """(duration [s], s(t) [m]): arc length of a constant-speed move with smooth
    (1 - cos) / 2 speed ramps of ``ramp`` seconds at both ends (s(duration) = total)."""
    total = positive_scalar("length", total)
    speed = positive_scalar("speed", speed)
    ramp = positive_scalar("ramp", ramp, allow_zero=True)
    duration = total / speed + ramp           # each ramp covers speed * ramp / 2
    if ramp > total / speed:
        raise InvalidParameterError(
            f"ramp = {ramp:g} s is too long for a {total:g} m move at {speed:g} m/s "
            f"(at most {total / speed:g} s)")

    def s(t: NDArray[np.float64]) -> NDArray[np.float64]:
        t = np.clip(np.asarray(t, dtype=float), 0.0, duration)
        if ramp == 0:
            return speed * t

        # distance covered x seconds into a ramp
        def up(x: NDArray[np.float64] | float) -> NDArray[np.float64] | float:
            return 0.5 * speed * (x - ramp / np.pi * np.sin(np.pi * x / ramp))
        return np.where(t < ramp, up(t), np.where(
            t > duration - ramp, total - up(duration - t), up(ramp) + speed * (t - ramp)))
    return duration, s


def _sampled(duration: float, samples_per_s: float) -> NDArray[np.float64]:
    samples_per_s = positive_scalar("samples_per_s", samples_per_s)
    return np.linspace(0.0, duration, max(int(np.ceil(duration * samples_per_s)), 2) + 1)


def line(start: list[float], end: list[float], speed: float,
         rotation: tuple[float, float, float] = (0.0, 0.0, 0.0), ramp: float = 0.0,
         samples_per_s: float = 10.0) -> Trajectory:
    """Straight line of P from ``start`` to ``end`` [m] at ``speed`` [m/s], fixed
    ``rotation`` (rotation vector [rad]); ``ramp`` [s] smooths the start and the stop.

    ``samples_per_s`` [1/s] sets the samples at which the quasi-static inverse kinematics is
    solved; the desired pose itself is exact at any time (:meth:`Trajectory.at`).

    Returns
    -------
    Trajectory
    """
    a, b = point("start", start), point("end", end)
    if np.allclose(a, b):
        raise InvalidParameterError(
            f"start and end must be two different points (3,) [m], got {start!r}, {end!r}")
    length = np.linalg.norm(b - a)
    duration, s = _arc_length(length, speed, ramp)
    u = (b - a) / length
    rot = as_pose([0, 0, 0, *rotation]).rotation

    def path(t: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        t = np.atleast_1d(t)
        return a + s(t)[:, None] * u, np.broadcast_to(rot, (t.size, 3)).copy()
    t = _sampled(duration, samples_per_s)
    return Trajectory(t, *path(t), name=f"line at {speed:g} m/s", path=path)


def circle(center, radius, speed, turns: float = 1.0, start_angle: float = 0.0,
           rotation=(0.0, 0.0, 0.0), ramp: float = 0.0, samples_per_s: float = 10.0):
    """Horizontal circle of P about ``center`` [m] of ``radius`` [m], counter-clockwise from
    ``start_angle`` [rad], at ``speed`` [m/s] for ``turns`` turns, fixed ``rotation``.

    Returns
    -------
    Trajectory
    """
    c = point("center", center)
    start_angle = finite_scalar("start_angle", start_angle)
    radius = positive_scalar("radius", radius)
    turns = positive_scalar("turns", turns)
    duration, s = _arc_length(2 * np.pi * radius * turns, speed, ramp)
    rot = as_pose([0, 0, 0, *rotation]).rotation

    def path(t):
        t = np.atleast_1d(t)
        ang = start_angle + s(t) / radius
        pos = c + radius * np.column_stack([np.cos(ang), np.sin(ang), np.zeros_like(ang)])
        return pos, np.broadcast_to(rot, (t.size, 3)).copy()
    t = _sampled(duration, samples_per_s)
    return Trajectory(t, *path(t), name=f"circle r = {radius:g} m at {speed:g} m/s",
                      path=path)


def following(waypoints, samples_per_s: float = 10.0):
    """The :class:`Trajectory` of a :class:`dynstiff.WaypointPath` (a scene's trajectory,
    e.g. a CASPR joint trajectory): its exact path, sampled at ``samples_per_s`` [1/s] for
    the quasi-static inverse kinematics, and at every waypoint.

    Returns
    -------
    Trajectory
    """
    from dynstiff.robot.waypoints import WaypointPath
    if not isinstance(waypoints, WaypointPath):
        raise InvalidParameterError(
            f"waypoints must be a dynstiff.WaypointPath, got {type(waypoints).__name__}")
    t = np.union1d(_sampled(waypoints.duration, samples_per_s), waypoints.times)
    return Trajectory(t, *waypoints.at(t), name=waypoints.name or "waypoints",
                      path=waypoints.at)


def quasi_static_lengths(
        robot: Robot, trajectory: Trajectory, progress: Callable[..., Any] | bool | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Unstretched cable lengths along a path from the quasi-static inverse kinematics with
    sagging cables (inverse statics at every sample, :meth:`Robot.equilibrium`).

    Parameters
    ----------
    robot : Robot
    trajectory : Trajectory
    progress : callable, optional
        ``progress(done, total)`` after each sample.

    Returns
    -------
    lengths : ndarray, shape (k, n_cables)
        L0_i at each sample [m].
    tensions : ndarray, shape (k, n_cables)
        Quasi-static tension at B [N].

    Raises
    ------
    SlackCableError
        A sample of the path is outside the tension-feasible workspace (the note names it).
    """
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a Robot, got {type(robot).__name__}")
    k = trajectory.times.size
    L = np.empty((k, robot.n_cables))
    T = np.empty_like(L)
    for j in range(k):
        pose = np.concatenate([trajectory.positions[j], trajectory.rotations[j]])
        try:
            eq = robot.equilibrium(pose=pose)
        except Exception as exc:                      # noqa: BLE001 - re-raised with context
            exc.add_note(f"quasi_static_lengths: at sample {j}, t = {trajectory.times[j]:g} s, "
                         f"pose {pose.tolist()}")
            raise
        L[j], T[j] = eq.unstretched_lengths, eq.tensions
        if progress is not None:
            progress(j + 1, k)
    return L, T


@dataclass(frozen=True, eq=False)
class TrackingResult:
    """A path commanded through quasi-static cable lengths and the simulated motion.

    Attributes
    ----------
    trajectory : Trajectory
        The desired path.
    lengths, tensions : ndarray, shape (k, n_cables)
        Commanded unstretched lengths [m] and quasi-static tensions [N] at its samples.
    response : TimeResponse
        The lumped-mass simulation.
    desired : ndarray, shape (n_t, 6)
        Desired pose at the recorded times [m, rad].
    static_offset : float
        Distance between the lumped model's static equilibrium at L0(0) and the desired
        start [m]: the discretisation part of the deviation (the catenary and the chain of
        N segments do not hang exactly alike).
    mean_cable_length : float
        Chord length averaged over the cables and the path samples [m].
    """

    trajectory: Trajectory
    lengths: np.ndarray
    tensions: np.ndarray
    response: object
    desired: np.ndarray
    static_offset: float
    mean_cable_length: float

    @property
    def deviation(self) -> NDArray[np.float64]:
        """Distance of P from the desired position at the recorded times [m], (n_t,)."""
        return np.linalg.norm(self.response.pose[:, :3] - self.desired[:, :3], axis=1)

    @property
    def max_deviation(self) -> float:
        """Largest deviation [m]."""
        return float(self.deviation.max())

    @property
    def relative_max_deviation(self):
        """Largest deviation / mean cable length [-]."""
        return self.max_deviation / self.mean_cable_length

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame indexed by time [s]: simulated and desired x y z [m], deviation
        [m], end tensions [N]."""
        import pandas as pd
        r = self.response
        cols = {}
        for k, n in enumerate("xyz"):
            cols[f"{n} [m]"] = r.pose[:, k]
            cols[f"{n} desired [m]"] = self.desired[:, k]
        cols["deviation [m]"] = self.deviation
        for i in range(r.end_tensions.shape[1]):
            cols[f"T_B{i} [N]"] = r.end_tensions[:, i]
        return pd.DataFrame(cols, index=pd.Index(r.times, name="time [s]"))


def track(robot: Robot, trajectory: Trajectory, segments: int = 10, dt: float = 2e-3,
          settle: float = 0.0, scheme: str = "implicit", damping=None, record_every: int = 1,
          lengths: ArrayLike | None = None, progress: Callable[..., Any] | bool | None = None,
          t_end=None) -> TrackingResult:
    """Command a path through its quasi-static cable lengths and simulate the motion.

    The lumped-mass robot (``segments`` per cable) starts from its static equilibrium at
    L0(0) and its winches follow L0(t) of :func:`quasi_static_lengths` (linear between the
    path samples, held after the end for ``settle`` seconds).

    Parameters
    ----------
    robot : Robot
    trajectory : Trajectory
    segments : int or sequence of int
        Segments per cable of the lumped model.
    dt : float
        Time step [s] (implicit Newmark by default, see :func:`dynstiff.lumped.simulate`).
    settle : float
        Extra time after the end of the path [s], >= 0.
    scheme, damping, record_every
        As :func:`dynstiff.lumped.simulate`.
    lengths : ndarray, shape (k, n_cables), optional
        Commanded lengths at the path samples instead of the quasi-static ones (e.g. rigid
        straight-cable kinematics, to show what ignoring sag and stretch costs).
    progress : callable, optional
        ``progress(done, total)`` during the quasi-static inverse kinematics.
    t_end : float, optional
        End of the simulation [s] (default: the path's duration plus ``settle``).

    Returns
    -------
    TrackingResult
    """
    from dynstiff.models.lumped_robot import LumpedMassModel
    from dynstiff.timedomain.simulation import simulate
    if not isinstance(trajectory, Trajectory):
        raise InvalidParameterError(
            f"trajectory must be a Trajectory, got {type(trajectory).__name__}")
    settle = positive_scalar("settle", settle, allow_zero=True)
    t_end = trajectory.duration + settle if t_end is None else positive_scalar("t_end", t_end)
    L, T = quasi_static_lengths(robot, trajectory, progress)
    if lengths is not None:
        lengths = np.asarray(lengths, dtype=float)
        if lengths.shape != L.shape:
            raise InvalidParameterError(
                f"lengths must have shape {L.shape} (one row per path sample), got "
                f"{lengths.shape}")
        L = lengths
    from scipy.interpolate import CubicSpline
    spline = CubicSpline(trajectory.times, L, axis=0)     # not-a-knot: keeps the end speeds
    t_path = trajectory.duration

    def commanded(t: float) -> NDArray[np.float64]:  # smooth between samples, held after the end
        return spline(min(t, t_path))

    model = LumpedMassModel(robot, L[0], segments)
    start = np.concatenate([trajectory.positions[0], trajectory.rotations[0]])
    # relative force tolerance no finer than the rounding of the stiffest cable's spring force
    EA = max(c.EA for c in robot.cables)
    tol = max(1e-10, 50 * np.finfo(float).eps * EA / max(float(T.min()), 1e-300))
    eq0 = model.equilibrium(initial_pose=start, tol=tol)
    resp = simulate(model, t_end, dt, lengths=commanded,
                    tol=max(1e-9, tol), start=eq0,
                    scheme=scheme, damping=damping, record_every=record_every)
    P, R = trajectory.at(resp.times)
    desired = np.hstack([P, R])
    chords = np.array([[np.linalg.norm(a - b) for a, b in zip(
        robot.anchors, robot.attachment_points(as_pose(np.concatenate([p, r])))[0])]
        for p, r in zip(trajectory.positions, trajectory.rotations)])
    return TrackingResult(
        trajectory=trajectory, lengths=L, tensions=T, response=resp, desired=desired,
        static_offset=float(np.linalg.norm(eq0.pose.position - start[:3])),
        mean_cable_length=float(chords.mean()))
