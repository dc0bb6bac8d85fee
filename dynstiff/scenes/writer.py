"""Scene files written from a robot: the inverse of :func:`read_scene`, and CASPR import.

Numbers are written with ``repr`` (the shortest text that reads back to the same float), so
``read_scene(write_scene(...))`` gives the same robot bit for bit.
"""

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

from dynstiff.constants import DOF_NAMES, STANDARD_GRAVITY
from dynstiff.errors import InvalidParameterError
from dynstiff.io.caspr import InertiaConventionWarning, read_caspr
from dynstiff.params import Cable
from dynstiff.robot.pose import Pose
from dynstiff.robot.robot import Robot
from dynstiff.scenes.loader import Scene

__all__ = ["import_caspr", "scene_text", "write_scene"]


def _num(v):
    v = float(v)
    return repr(int(v)) + ".0" if v.is_integer() and abs(v) < 1e15 else repr(v)


def _vec(v):
    return "[" + ", ".join(_num(x) for x in np.ravel(v)) + "]"


def _toml_str(s):
    return '"' + str(s).replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def _cable_lines(c):
    lines = [f"mass_per_length = {_num(c.mass_per_length)}", f"EA = {_num(c.EA)}"]
    if c.viscous_damping:
        lines.append(f"viscous_damping = {_num(c.viscous_damping)}")
    if c.loss_factor:
        lines.append(f"loss_factor = {_num(c.loss_factor)}")
    return lines


def scene_text(robot, pose=None, name=None, description="", comments=(), cable_names=None):
    """TOML text of a scene file for ``robot`` (format: :mod:`dynstiff.scenes`).

    Parameters
    ----------
    robot : Robot
    pose : Pose, optional
        Written as ``[pose]`` (position [m], rotation vector [rad]).
    name, description : str
    comments : sequence of str
        Lines for the header comment (source, conventions ...).
    cable_names : sequence of str, optional
        A comment above each ``[[cables]]``.

    Returns
    -------
    str
    """
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a dynstiff.Robot, got {type(robot).__name__}")
    name = name or robot.name or "scene"
    out = [f"# {c}" if c else "#" for c in comments]
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
    out += ["", "# anchor a_j [m, base frame]; attachment b_j [m, platform frame]"]
    for k in range(robot.n_cables):
        label = cable_names[k] if cable_names is not None else f"cable {k + 1}"
        out += [f"[[cables]]                                  # {label}",
                f"anchor = {_vec(robot.anchors[k])}",
                f"attachment = {_vec(robot.attachments[k])}"]
        if not same:
            out += _cable_lines(cables[k])
    if pose is not None:
        out += ["", "[pose]", f"position = {_vec(pose.position)}   # [m]",
                f"rotation = {_vec(pose.rotation)}   # [rad], rotation vector"]
    return "\n".join(out) + "\n"


def write_scene(path, robot, pose=None, **kw):
    """Write :func:`scene_text` to ``path`` (keywords as there); returns the Path."""
    path = Path(path)
    path.write_text(scene_text(robot, pose, **kw), encoding="utf-8")
    return path


def import_caspr(bodies_xml, cables_xml, cable, cable_set=None, inertia_convention="products",
                 g=STANDARD_GRAVITY, name=None, min_tension=1.0):
    """Scene of a single-body CASPR robot: its :meth:`Robot.from_caspr` at the pose
    ``q_initial`` (theory.md §15.1).

    Parameters
    ----------
    bodies_xml, cables_xml : str or Path
    cable : Cable
        Every cable's properties (CASPR holds none).
    cable_set, inertia_convention, g, min_tension : as :meth:`Robot.from_caspr`
    name : str, optional
        Scene name (default: the CASPR link's name).

    Returns
    -------
    Scene
        ``description`` names the source files and the inertia convention.
    """
    if not isinstance(cable, Cable):
        raise InvalidParameterError(f"cable must be a dynstiff.Cable, got {cable!r}")
    m = read_caspr(bodies_xml, cables_xml, cable_set, inertia_convention, stacklevel=3)
    with warnings.catch_warnings():         # the same file warned once already
        warnings.simplefilter("ignore", InertiaConventionWarning)
        robot = Robot.from_caspr(bodies_xml, cables_xml, cable, cable_set, inertia_convention,
                                 g, min_tension)
    if name:
        robot = replace(robot, name=name)
    desc = (f"{m.name} from CASPR ({Path(bodies_xml).name}, {Path(cables_xml).name}, cable set "
            f"{m.cable_set!r}, joint {m.joint_type}), inertia_convention {m.convention!r}")
    return Scene(robot=robot, pose=Pose(m.position, m.rotation), name=name or m.name,
                 description=desc, study={"caspr_cable_names": list(m.cable_names)})


def caspr_comments(scene, bodies_xml, cables_xml):
    """Header comment lines of a scene imported from CASPR."""
    return [f"{scene.name}: imported from CASPR", f"bodies: {bodies_xml}",
            f"cables: {cables_xml}", scene.description,
            "CASPR holds no cable mass or EA: [cable] holds the values given at import.",
            "free DOFs of the joint: " + ", ".join(
                d for d in DOF_NAMES if d in scene.robot.platform.free_dofs),
            "Units: SI."]
