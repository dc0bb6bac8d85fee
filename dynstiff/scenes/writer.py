"""Scene files written from a robot: the inverse of :func:`read_scene`.

Values are formatted by tomli-w (strings escaped; floats with ``repr``, the shortest text
that reads back to the same float), so ``read_scene(write_scene(...))`` gives the same robot
bit for bit; the layout and the comments (units, conventions) are the writer's.
"""

import unicodedata
from pathlib import Path

import numpy as np

from dynstiff._validate import real_array
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot
from dynstiff.robot.waypoints import WaypointPath

__all__ = ["scene_text", "write_scene"]


def _value(v):
    """TOML text of one string or number, formatted by tomli-w (floats as ``repr``)."""
    import tomli_w
    return tomli_w.dumps({"v": v})[4:].rstrip("\n")


def _num(v):
    return _value(float(v))


def _vec(v):
    return "[" + ", ".join(_num(x) for x in np.ravel(v)) + "]"


def _toml_str(s):
    return _value(str(s))


def _comment(text):
    """``text`` made safe for a TOML comment: a line break would end the comment and let the
    rest be read as TOML (a cable name ``"a\\nEA = 1"`` would set that cable's EA), and TOML
    forbids the other control characters in a comment, so all of them but the tab are
    written as their escapes (``\\n``, ``\\x1b``)."""
    return "".join(ch if ch == "\t" or unicodedata.category(ch) != "Cc"
                   else ch.encode("unicode_escape").decode("ascii") for ch in str(text))


def _cable_lines(c):
    lines = [f"mass_per_length = {_num(c.mass_per_length)}", f"EA = {_num(c.EA)}"]
    if c.viscous_damping:
        lines.append(f"viscous_damping = {_num(c.viscous_damping)}")
    if c.loss_factor:
        lines.append(f"loss_factor = {_num(c.loss_factor)}")
    return lines


def _rows(a):
    return "[" + ", ".join(_vec(r) for r in np.asarray(a)) + "]"


def _trajectory_lines(path, note):
    head = "[[trajectories]]"
    out = ["", f"{head:<44}# {_comment(note)}" if note else head,
           f"name = {_toml_str(path.name)}",
           f"law = {_toml_str(path.law)}                          # between the waypoints",
           f"times = {_vec(path.times)}   # [s]",
           f"positions = {_rows(path.positions)}   # [m], P",
           f"rotations = {_rows(path.rotations)}   # [rad], rotation vectors"]
    if np.any(path.velocities):
        out.append(f"velocities = {_rows(path.velocities)}   # [m/s], P")
    if np.any(path.accelerations):
        out.append(f"accelerations = {_rows(path.accelerations)}   # [m/s^2], P")
    if path.blend_times is not None:
        out.append(f"blend_times = {_vec(path.blend_times)}   # [s], one per segment")
    return out


def scene_text(robot, pose=None, name=None, description="", comments=(), cable_names=None,
               trajectories=(), workspace_box=None, trajectory_notes=None):
    """TOML text of a scene file for ``robot`` (format: :mod:`dynstiff.scenes`).

    Parameters
    ----------
    robot : Robot
    pose : Pose, optional
        Written as ``[pose]`` (position [m], rotation vector [rad]).
    name, description : str
    comments : sequence of str
        Lines for the header comment (source, conventions ...); one holding line breaks
        gives a comment line for each of its lines. In every comment (these, the cable
        names, the trajectory notes) control characters are written as escapes, so no
        text can end a comment and be read as TOML.
    cable_names : sequence of str, optional
        Names in the comment above each ``[[cables]]``, after its 0-based number
        (``# cable 0 (NAME)``).
    trajectories : sequence of WaypointPath
        Written as ``[[trajectories]]`` tables (names must differ).
    workspace_box : sequence of 6 float, optional
        (x0, x1, y0, y1, z0, z1) [m], written as ``[workspace] box``: the default box of a
        workspace map.
    trajectory_notes : dict, optional
        A comment above a trajectory's table, by its name.

    Returns
    -------
    str
    """
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a dynstiff.Robot, got {type(robot).__name__}")
    for label, text in (("name", name), ("description", description)):
        if text is not None and not isinstance(text, str):
            raise InvalidParameterError(f"{label} must be a str, got {text!r}")
    if isinstance(comments, str) or not all(isinstance(c, str) for c in comments):
        raise InvalidParameterError(f"comments must be a sequence of str (lines), got "
                                    f"{comments!r}")
    if cable_names is not None and (isinstance(cable_names, str)
                                    or len(cable_names) != robot.n_cables):
        raise InvalidParameterError(f"cable_names must be {robot.n_cables} names (one per "
                                    f"cable), got {cable_names!r}")
    pose = None if pose is None else as_pose(pose)
    trajectories = tuple(trajectories)
    if not all(isinstance(t, WaypointPath) for t in trajectories):
        raise InvalidParameterError("trajectories must be dynstiff.WaypointPath objects")
    names = [t.name for t in trajectories]
    if len(set(names)) != len(names) or not all(names):
        raise InvalidParameterError(f"trajectories need distinct, non-empty names, got {names}")
    if workspace_box is not None:
        what = "6 finite numbers x0 x1 y0 y1 z0 z1 [m] with x0 <= x1 ..."
        box = real_array("workspace_box", workspace_box, what)      # no bools, no text
        if box.shape != (6,) or not np.all(np.isfinite(box)) or np.any(box[1::2] < box[::2]):
            raise InvalidParameterError(f"workspace_box must be {what}, got {workspace_box!r}")
    name = name or robot.name or "scene"
    out = [f"# {_comment(line)}".rstrip() for c in comments for line in c.splitlines() or [""]]
    out += ["", "[scene]", f"name = {_toml_str(name)}",
            f"description = {_toml_str(description)}",
            f"g = {_num(robot.g)}                                  # [m/s^2]", ""]
    p = robot.platform
    rows = ",\n           ".join(_vec(r) for r in p.inertia)
    out += ["[platform]", f"mass = {_num(p.mass)}                              # [kg]",
            f"center_of_mass = {_vec(p.center_of_mass)}   # [m], platform frame",
            "# inertia tensor about G [kg m^2], platform axes; off-diagonal entries are",
            "# minus the products of inertia",
            f"inertia = [{rows}]",
            "free_dofs = [" + ", ".join(f'"{d}"' for d in p.free_dofs) + "]", ""]
    cables = robot.cables
    same = all(c == cables[0] for c in cables)
    if same:
        out += ["[cable]                                     # every cable"]
        out += _cable_lines(cables[0])
        out += ["# mass_per_length [kg/m], EA [N]", ""]
    t_min, t_max = robot.tension_limits
    out += ["[tension_limits]", f"min = {_num(t_min)}                                # [N]"]
    if np.isfinite(t_max):
        out += [f"max = {_num(t_max)}                                # [N]"]
    out += ["", "# anchor a_j [m, base frame]; attachment b_j [m, platform frame]; cables are",
            "# numbered from 0 in the order below, as in every output of dynstiff"]
    for k in range(robot.n_cables):
        label = f"cable {k}" + (f" ({_comment(cable_names[k])})" if cable_names is not None
                                else "")
        out += [f"[[cables]]                                  # {label}",
                f"anchor = {_vec(robot.anchors[k])}",
                f"attachment = {_vec(robot.attachments[k])}"]
        if not same:
            out += _cable_lines(cables[k])
    if pose is not None:
        out += ["", "[pose]", f"position = {_vec(pose.position)}   # [m]",
                f"rotation = {_vec(pose.rotation)}   # [rad], rotation vector"]
    if workspace_box is not None:
        out += ["", "[workspace]", f"box = {_vec(box)}   # [m], x0 x1 y0 y1 z0 z1 of P"]
    for t in trajectories:
        out += _trajectory_lines(t, (trajectory_notes or {}).get(t.name, ""))
    return "\n".join(out) + "\n"


def write_scene(path, robot, pose=None, **kw):
    """Write :func:`scene_text` to ``path`` (keywords as there); returns the Path."""
    from dynstiff.io.files import write_text
    path = Path(path)
    write_text(path, scene_text(robot, pose, **kw))      # atomic: all or nothing
    return path
