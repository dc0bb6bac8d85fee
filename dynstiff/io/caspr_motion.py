"""Reader of CASPR's trajectories and operational-space files of single-body robots.

*Trajectories* (``*_trajectories.xml``, root ``<trajectories>``): ``<joint_trajectories>``
holds trajectories in joint space, each an element named after its spline,
``linear_spline_trajectory``, ``cubic_spline_trajectory``, ``quintic_spline_trajectory``,
``cubic_spline_average_velocity_trajectory`` or ``parabolic_blend_trajectory``, with an
``id``, ``time_definition`` ("relative": each point's ``time`` is the duration of the
segment ending there; "absolute": the time itself), ``time_step`` [s] (CASPR's sampling) and
``<points>`` of ``<point time=...>`` with ``<q>`` (joint coordinates), ``<q_dot>`` and
``<q_ddot>`` (their rates, one per DOF; cubic and quintic). The first point is at t = 0.
``cubic_spline_average_velocity_trajectory`` gives the rates at the first and last points
only; at the others CASPR takes the mean of the two neighbouring segments' slopes.
``parabolic_blend_trajectory`` has ``blend_time_default`` [s] and a ``blend_time`` per
point (for the segment ending there). ``file_trajectory`` (samples in a separate ``.traj``
file) and ``<operational_trajectories>`` (paths of a marker) are listed as not read.

CASPR interpolates the orientation of its spherical joints on the geodesic between the
waypoint orientations and refuses nonzero orientation rates at the waypoints
(``SphericalEulerXYZ.generateTrajectory*``, ``Quaternion.*Interpolation``); the same holds
here, so a trajectory is its waypoint poses, times, the rates of P and a law
(:class:`dynstiff.WaypointPath`, theory.md §15.8).

*Operational spaces* (``*_operational_spaces.xml``, root ``<operational_spaces
default_operational_set=...>``): ``<operational_set id>`` of markers ``<position>``,
``<orientation_euler_xyz>`` or ``<pose_euler_xyz>`` (``marker_id``, ``name``), each a point of
a link (``<link>``, ``<offset>`` [m, link frame]) and the coordinates it controls
(``<axes active_axes="xyz">``). They hold no bounds: the bounds of a single-body robot's
workspace are its joint's ``q_min`` / ``q_max``
(:attr:`~dynstiff.io.caspr.CasprModel.workspace_box`).
"""

from dataclasses import dataclass

import numpy as np

from dynstiff.io.caspr import JOINT_TYPES, CasprError, parse_root, read_numbers

__all__ = ["CasprMarker", "CasprOperationalSpaces", "CasprTrajectories", "CasprTrajectory",
           "TRAJECTORY_LAWS", "read_caspr_operational_spaces", "read_caspr_trajectories"]

#: CASPR's joint-trajectory elements read, and the law of their waypoints.
TRAJECTORY_LAWS = {
    "linear_spline_trajectory": "linear",
    "cubic_spline_trajectory": "cubic",
    "quintic_spline_trajectory": "quintic",
    "cubic_spline_average_velocity_trajectory": "cubic",
    "parabolic_blend_trajectory": "parabolic_blend",
}

_MARKERS = ("position", "orientation_euler_xyz", "pose_euler_xyz")


@dataclass(frozen=True)
class CasprTrajectory:
    """One joint-space trajectory of a CASPR file.

    Attributes
    ----------
    name : str
        Its ``id``.
    kind : str
        The XML element (``quintic_spline_trajectory`` ...).
    law : str
        Interpolation between waypoints, one of :data:`dynstiff.robot.waypoints.LAWS`.
    times : ndarray, shape (k,)
        Waypoint times from 0 [s].
    q : ndarray, shape (k, n_q)
        Joint coordinates at the waypoints [m, rad].
    q_dot, q_ddot : ndarray, shape (k, n_dof), or None
        Their rates at the waypoints (cubic: q_dot; quintic: both) [m/s, rad/s; /s^2].
    blend_times : ndarray, shape (k - 1,), or None
        Blend time of each segment [s] (parabolic blend).
    time_step : float
        CASPR's sampling step [s] (NaN when not given).
    """

    name: str
    kind: str
    law: str
    times: np.ndarray
    q: np.ndarray
    q_dot: object
    q_ddot: object
    blend_times: object
    time_step: float


@dataclass(frozen=True)
class CasprTrajectories:
    """The trajectories of a file: ``trajectories`` (dict id -> :class:`CasprTrajectory`,
    in file order) and ``skipped`` (tuple of (id, reason) of those not read)."""

    trajectories: dict
    skipped: tuple = ()


@dataclass(frozen=True)
class CasprMarker:
    """One marker of an operational set: ``kind`` (position, orientation_euler_xyz,
    pose_euler_xyz), ``marker_id``, ``name``, ``link``, ``offset`` (3,) [m, link frame] and
    ``axes`` (the active coordinates, letters of "xyzabg")."""

    kind: str
    marker_id: str
    name: str
    link: int
    offset: np.ndarray
    axes: str


@dataclass(frozen=True)
class CasprOperationalSpaces:
    """``default`` set id ("" when none) and ``sets`` (dict id -> tuple of
    :class:`CasprMarker`)."""

    default: str
    sets: dict


def _point_rates(path, where, point, tag, n):
    el = point.find(tag)
    return None if el is None else read_numbers(path, el, f"{where} <{tag}>", n)


def _read_one(path, el, joint_type):
    name = el.get("id") or "?"
    where = f"trajectory {name!r}"
    n_q, free = JOINT_TYPES[joint_type]
    n_dof = len(free)
    law = TRAJECTORY_LAWS[el.tag]
    definition = el.get("time_definition", "relative")
    if definition not in ("relative", "absolute"):
        raise CasprError(f"{path}: {where}: time_definition {definition!r} (expected "
                         f"'relative' or 'absolute')")
    step = el.get("time_step")
    time_step = np.nan if step is None else \
        read_numbers(path, step, f"{where} time_step", 1)[0]
    if not (step is None or time_step > 0):
        raise CasprError(f"{path}: {where}: time_step {step!r} (a sampling step > 0 [s])")
    points = el.findall("points/point")
    if len(points) < 2:
        raise CasprError(f"{path}: {where} has {len(points)} point(s); a trajectory needs 2")
    times, q, qd, qdd, blends = [0.0], [], [], [], []
    default_blend = el.get("blend_time_default")
    for k, pt in enumerate(points):
        q.append(read_numbers(path, pt.find("q"), f"{where} point {k} <q>", n_q))
        qd.append(_point_rates(path, f"{where} point {k}", pt, "q_dot", n_dof))
        qdd.append(_point_rates(path, f"{where} point {k}", pt, "q_ddot", n_dof))
        if k == 0:
            continue
        t = read_numbers(path, pt.get("time"), f"{where} point {k} time", 1)[0]
        times.append(t if definition == "absolute" else times[-1] + t)
        if law == "parabolic_blend":
            b = pt.get("blend_time") or default_blend
            blends.append(read_numbers(path, b, f"{where} point {k} blend_time (or "
                                            f"blend_time_default)", 1)[0])
    times = np.array(times)
    if np.any(np.diff(times) <= 0):
        raise CasprError(f"{path}: {where}: point times {times.tolist()} s are not increasing")
    q = np.array(q)
    q_dot = q_ddot = None
    if el.tag == "cubic_spline_average_velocity_trajectory":
        if qd[0] is None or qd[-1] is None:
            raise CasprError(f"{path}: {where}: the first and last points need <q_dot>")
        slope = np.diff(q, axis=0) / np.diff(times)[:, None]
        mid = 0.5 * (slope[:-1] + slope[1:])
        if n_q != n_dof:
            raise CasprError(f"{path}: {where}: average velocities of a quaternion joint "
                             f"({joint_type}) are not defined")
        q_dot = np.vstack([qd[0], mid, qd[-1]])
    elif law in ("cubic", "quintic"):
        need = ("q_dot",) if law == "cubic" else ("q_dot", "q_ddot")
        for tag, vals in zip(("q_dot", "q_ddot"), (qd, qdd)):
            if tag in need and any(v is None for v in vals):
                k = next(j for j, v in enumerate(vals) if v is None)
                raise CasprError(f"{path}: {where} point {k}: missing <{tag}> (a {law} "
                                 f"spline needs it at every point)")
        q_dot = np.array(qd)
        q_ddot = np.array(qdd) if law == "quintic" else None
    return CasprTrajectory(name=name, kind=el.tag, law=law, times=times, q=q, q_dot=q_dot,
                           q_ddot=q_ddot, blend_times=np.array(blends) if blends else None,
                           time_step=float(time_step))


def read_caspr_trajectories(path, joint_type):
    """Read the joint-space trajectories of a CASPR ``*_trajectories.xml``.

    Parameters
    ----------
    path : str or Path
    joint_type : str
        The robot's joint (one of :data:`dynstiff.io.caspr.JOINT_TYPES`): the number of
        coordinates and rates each point must give.

    Returns
    -------
    CasprTrajectories
        Possibly empty (CASPR's template has an empty ``<joint_trajectories>``).

    Raises
    ------
    CasprError
        Malformed XML, a point with the wrong number of values, times not increasing, a
        spline missing its rates, an unknown trajectory element. :class:`FileNotFoundError`.
    """
    if joint_type not in JOINT_TYPES:
        raise CasprError(f"joint_type must be one of {list(JOINT_TYPES)}, got {joint_type!r}")
    path, root = parse_root(path, ("trajectories",))
    found, skipped = {}, []
    for section in root:
        if section.tag == "operational_trajectories":
            skipped += [(e.get("id") or "?", "an operational-space trajectory (a marker's "
                                             "path), not read") for e in section]
            continue
        if section.tag != "joint_trajectories":
            raise CasprError(f"{path}: <{section.tag}> in <trajectories> (expected "
                             f"<joint_trajectories>)")
        for el in section:
            if el.tag == "file_trajectory":
                skipped.append((el.get("id") or "?", f"samples in the file "
                                                     f"{el.get('filename')!r}, not read"))
                continue
            if el.tag not in TRAJECTORY_LAWS:
                raise CasprError(f"{path}: <{el.tag}> is not a CASPR joint trajectory (one of "
                                 f"{list(TRAJECTORY_LAWS) + ['file_trajectory']})")
            traj = _read_one(path, el, joint_type)
            if traj.name in found:
                raise CasprError(f"{path}: two trajectories named {traj.name!r}")
            found[traj.name] = traj
    return CasprTrajectories(trajectories=found, skipped=tuple(skipped))


def read_caspr_operational_spaces(path):
    """Read the operational sets of a CASPR ``*_operational_spaces.xml``.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    CasprOperationalSpaces
        Possibly with no set (the spatial robots' files are empty).

    Raises
    ------
    CasprError
        Malformed XML, an unknown marker, a marker on a link other than the platform (1), a
        bad offset or axes (letters of ``xyzabg``, each once), two sets with one id.
    """
    path, root = parse_root(path, ("operational_spaces",))
    default = root.get("default_operational_set", "")
    sets = {}
    for s in root.iter("operational_set"):      # also inside a nested <operational_spaces>
        sid = s.get("id") or "?"
        markers = []
        for m in s:
            where = f"operational set {sid!r} marker <{m.tag}>"
            if m.tag not in _MARKERS:
                raise CasprError(f"{path}: {where}: unknown marker (one of {list(_MARKERS)})")
            link = (m.findtext("link") or "").strip()
            if link != "1":
                raise CasprError(f"{path}: {where} is on link {link!r}; a single-body robot's "
                                 f"markers are on its platform, link 1")
            axes = m.find("axes")
            active = "" if axes is None else axes.get("active_axes", "")
            if not active or set(active) - set("xyzabg") or len(set(active)) < len(active):
                raise CasprError(f"{path}: {where}: active_axes {active!r} (distinct letters "
                                 f"of 'xyzabg')")
            markers.append(CasprMarker(kind=m.tag, marker_id=m.get("marker_id", ""),
                                       name=m.get("name", ""), link=1,
                                       offset=read_numbers(path, m.find("offset"),
                                                       f"{where} <offset>", 3),
                                       axes=active))
        if sid in sets:
            raise CasprError(f"{path}: two operational sets with id {sid!r}")
        sets[sid] = tuple(markers)
    if default and default not in sets:
        raise CasprError(f"{path}: default_operational_set {default!r} not found; sets: "
                         f"{list(sets)}")
    return CasprOperationalSpaces(default=default, sets=sets)
