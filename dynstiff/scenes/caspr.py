"""Scenes of CASPR robots: the robot at ``q_initial``, its trajectories as waypoint paths and
its workspace box (theory.md §15.1, §15.8)."""

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

from dynstiff.constants import DOF_NAMES, STANDARD_GRAVITY
from dynstiff.errors import InvalidParameterError
from dynstiff.io.caspr import (
    JOINT_TYPES,
    CasprError,
    InertiaConventionWarning,
    joint_pose,
    read_caspr,
)
from dynstiff.io.caspr_motion import read_caspr_operational_spaces, read_caspr_trajectories
from dynstiff.params import Cable
from dynstiff.robot.pose import Pose
from dynstiff.robot.robot import Robot
from dynstiff.robot.waypoints import WaypointPath
from dynstiff.scenes.loader import Scene

__all__ = ["caspr_comments", "caspr_siblings", "import_caspr", "waypoint_path"]


def _rates(path, traj, joint_type, values, what):
    """Rates of P [m/s or m/s^2] (k, 3) from CASPR's joint rates; CASPR's spherical joints
    refuse nonzero orientation rates at the waypoints, and so does this."""
    free = JOINT_TYPES[joint_type][1]
    if values is None:
        return None
    trans = [k for k, d in enumerate(free) if d in ("x", "y", "z")]
    rot = [k for k, d in enumerate(free) if d in ("rx", "ry", "rz")]
    bad = np.flatnonzero(np.any(values[:, rot] != 0, axis=1))
    if bad.size:
        k = int(bad[0])
        averaged = (traj.kind == "cubic_spline_average_velocity_trajectory"
                    and 0 < k < values.shape[0] - 1)
        source = (" (the mean of its two segments' rates, which an average-velocity spline "
                  "takes there: the orientation changes at that waypoint)" if averaged else "")
        raise CasprError(
            f"{path}: trajectory {traj.name!r}: nonzero orientation {what} at waypoint "
            f"{k}{source}; CASPR interpolates orientations with zero rates at the waypoints "
            f"and refuses these too")
    out = np.zeros((values.shape[0], 3))
    out[:, :len(trans)] = values[:, trans]
    return out


def waypoint_path(traj, joint_type, origin, path=""):
    """The :class:`WaypointPath` of a CASPR joint trajectory.

    Parameters
    ----------
    traj : CasprTrajectory
    joint_type : str
        The robot's joint (:data:`dynstiff.io.caspr.JOINT_TYPES`).
    origin : array_like, shape (3,)
        The joint's parent location [m].
    path : str
        The file, for messages.

    Returns
    -------
    WaypointPath
        Waypoint poses from :func:`dynstiff.io.caspr.joint_pose`, the rates of P from the
        translation part of ``q_dot`` / ``q_ddot``, CASPR's law.
    """
    try:
        poses = [joint_pose(joint_type, origin, q) for q in traj.q]
    except ValueError as exc:
        raise CasprError(f"{path}: trajectory {traj.name!r}: {exc}") from None
    return WaypointPath(
        times=traj.times, positions=np.array([p for p, _ in poses]),
        rotations=np.array([r for _, r in poses]), law=traj.law,
        velocities=_rates(path, traj, joint_type, traj.q_dot, "velocity"),
        accelerations=_rates(path, traj, joint_type, traj.q_ddot, "acceleration"),
        blend_times=traj.blend_times, name=traj.name)


def caspr_siblings(bodies_xml):
    """CASPR's trajectories and operational-space files beside ``bodies_xml``
    (``<stem>_trajectories.xml``, ``<stem>_operational_spaces.xml`` for
    ``<stem>_bodies.xml``), each a Path or None when absent."""
    p = Path(bodies_xml)
    if not p.name.endswith("_bodies.xml"):
        return None, None
    stem = p.name[:-len("_bodies.xml")]
    found = [p.with_name(f"{stem}_{kind}.xml") for kind in ("trajectories",
                                                             "operational_spaces")]
    return tuple(f if f.is_file() else None for f in found)


def import_caspr(bodies_xml, cables_xml, cable, cable_set=None, inertia_convention="products",
                 g=STANDARD_GRAVITY, name=None, min_tension=1.0, trajectories_xml=None,
                 operational_spaces_xml=None):
    """Scene of a single-body CASPR robot: its :meth:`Robot.from_caspr` at the pose
    ``q_initial`` (theory.md §15.1), its trajectories and workspace box (§15.8).

    Parameters
    ----------
    bodies_xml, cables_xml : str or Path
    cable : Cable
        Every cable's properties (CASPR holds none).
    cable_set, inertia_convention, g, min_tension : as :meth:`Robot.from_caspr`
    name : str, optional
        Scene name (default: the CASPR link's name).
    trajectories_xml : str or Path, optional
        CASPR's ``*_trajectories.xml``: its joint trajectories become
        ``Scene.trajectories`` (waypoint paths, :func:`waypoint_path`).
    operational_spaces_xml : str or Path, optional
        CASPR's ``*_operational_spaces.xml``: its markers are listed in
        ``Scene.study["caspr_operational_sets"]`` (they hold no bounds).

    Returns
    -------
    Scene
        ``description`` names the source files and the inertia convention;
        ``workspace_box`` is the joint's q_min / q_max (None without them);
        ``study["caspr_skipped_trajectories"]`` lists (id, reason) of trajectories not read.
    """
    if not isinstance(cable, Cable):
        raise InvalidParameterError(f"cable must be a dynstiff.Cable, got {cable!r}")
    m = read_caspr(bodies_xml, cables_xml, cable_set, inertia_convention, stacklevel=3)
    paths, skipped, markers = {}, [], {}
    if trajectories_xml is not None:
        read = read_caspr_trajectories(trajectories_xml, m.joint_type)
        paths = {k: waypoint_path(t, m.joint_type, m.origin, trajectories_xml)
                 for k, t in read.trajectories.items()}
        skipped = [list(s) for s in read.skipped]
    if operational_spaces_xml is not None:
        ops = read_caspr_operational_spaces(operational_spaces_xml)
        markers = {sid: [{"kind": mk.kind, "name": mk.name, "offset": mk.offset.tolist(),
                          "axes": mk.axes} for mk in mks] for sid, mks in ops.sets.items()}
    with warnings.catch_warnings():         # the same file warned once already
        warnings.simplefilter("ignore", InertiaConventionWarning)
        robot = Robot.from_caspr(bodies_xml, cables_xml, cable, cable_set, inertia_convention,
                                 g, min_tension)
    if name:
        robot = replace(robot, name=name)
    desc = (f"{m.name} from CASPR ({Path(bodies_xml).name}, {Path(cables_xml).name}, cable set "
            f"{m.cable_set!r}, joint {m.joint_type}), inertia_convention {m.convention!r}")
    study = {"caspr_cable_names": list(m.cable_names)}
    if trajectories_xml is not None:
        study["caspr_skipped_trajectories"] = skipped
        study["caspr_trajectory_kinds"] = {k: t.kind for k, t in read.trajectories.items()}
    if operational_spaces_xml is not None:
        study["caspr_operational_sets"] = markers
    return Scene(robot=robot, pose=Pose(m.position, m.rotation), name=name or m.name,
                 description=desc, study=study, trajectories=paths,
                 workspace_box=m.workspace_box)


def caspr_comments(scene, bodies_xml, cables_xml, trajectories_xml=None,
                   operational_spaces_xml=None):
    """Header comment lines of a scene imported from CASPR."""
    out = [f"{scene.name}: imported from CASPR", f"bodies: {bodies_xml}",
           f"cables: {cables_xml}"]
    if trajectories_xml is not None:
        out.append(f"trajectories: {trajectories_xml}")
    if operational_spaces_xml is not None:
        out.append(f"operational spaces: {operational_spaces_xml}")
    out += [scene.description,
            "CASPR holds no cable mass or EA: [cable] holds the values given at import.",
            "free DOFs of the joint: " + ", ".join(
                d for d in DOF_NAMES if d in scene.robot.platform.free_dofs)]
    if scene.workspace_box is not None:
        out.append("[workspace] box: the joint's q_min / q_max (translations).")
    for sid, mks in (scene.study or {}).get("caspr_operational_sets", {}).items():
        out.append(f"operational set {sid!r}: " + "; ".join(
            f"{mk['kind']} of the point {mk['offset']} m, axes {mk['axes']}" for mk in mks))
    for tid, why in (scene.study or {}).get("caspr_skipped_trajectories", []):
        out.append(f"trajectory {tid!r} not read: {why}")
    out.append("Units: SI.")
    return out
