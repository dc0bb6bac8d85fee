"""The parameters a natural frequency can be differentiated by, uncertain in or optimised
over: their names, values, units, their direction among the primitive parameters of
:mod:`dynstiff.analyses.sensitivity_kernels`, and the robot (pose, reference, lengths) that a
new value gives (theory.md §16.1).

=====================================  ==========================================  =========
name                                   meaning                                     unit
=====================================  ==========================================  =========
``EA``                                 every cable's EA together (in proportion;    N
                                       the value is cable 0's)
``EA_i``, ``EA_*``                     cable i's EA; one per cable                  N
``mass_per_length`` (``_i``, ``_*``)   mass per unstretched length                  kg/m
``loss_factor`` (``_i``, ``_*``)       hysteretic loss factor (damping ratios only) --
``mass``                               platform mass                                kg
``inertia``                            a factor on the platform's inertia tensor    --
``inertia_xx`` ... ``inertia_yz``      one entry of the tensor about G (both        kg m^2
                                       symmetric entries)
``com_x``, ``com_y``, ``com_z``        centre of mass, platform frame               m
``pose_x`` ... ``pose_z``              position of P (at a fixed pose)              m
``pose_rx`` ... ``pose_rz``            rotation vector (at a fixed pose)            rad
``anchor_i_x`` (``anchor_i``,          anchor coordinates; the three of cable i;    m
``anchor_*``)                          all
``attachment_i_x`` (...)               attachment coordinates, platform frame       m
``t_min``, ``t_max``                   tension limits of the distribution (fixed    N
                                       pose; t_min is also the default reference)
``t_ref_i``, ``t_ref_*``               reference tension of cable i in the          N
                                       distribution (fixed pose, given reference)
``L0_i``, ``L0_*``                     unstretched length (fixed lengths)           m
=====================================  ==========================================  =========
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import InvalidParameterError
from dynstiff.robot.pose import Pose

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.robot.equilibrium import Equilibrium
    from dynstiff.robot.robot import Robot

__all__ = ["Parameter", "equilibrium_with", "expand_parameters", "parameter_names",
           "with_values"]

_CABLE = {"EA": ("EA", "N"), "mass_per_length": ("m0", "kg/m"),
          "loss_factor": ("axial", "-")}
_INERTIA = {"xx": (0, 0), "yy": (1, 1), "zz": (2, 2), "xy": (0, 1), "xz": (0, 2),
            "yz": (1, 2)}
_AXES = "xyz"


@dataclass(frozen=True)
class Parameter:
    """One parameter: its name, base value, unit and direction (a dict of primitive
    increments per unit of the parameter).

    ``kind`` is "damping" for a loss factor (it moves the damping ratios, not the undamped
    frequencies), else "frequency".
    """

    name: str
    value: float
    unit: str
    direction: dict
    kind: str = "frequency"


def parameter_names(n_cables: int) -> tuple[str, ...]:
    """Every parameter name of a robot with ``n_cables`` cables (wildcards expanded).

    Examples
    --------
    >>> parameter_names(2)[:5]
    ('EA', 'mass_per_length', 'loss_factor', 'EA_0', 'EA_1')
    """
    out = ["EA", "mass_per_length", "loss_factor"]
    for base in _CABLE:
        out += [f"{base}_{i}" for i in range(n_cables)]
    out += ["mass", "inertia"] + [f"inertia_{k}" for k in _INERTIA]
    out += [f"com_{a}" for a in _AXES] + [f"pose_{a}" for a in ("x", "y", "z", "rx", "ry",
                                                                  "rz")]
    for what in ("anchor", "attachment"):
        out += [f"{what}_{i}_{a}" for i in range(n_cables) for a in _AXES]
    out += ["t_min", "t_max"] + [f"t_ref_{i}" for i in range(n_cables)]
    out += [f"L0_{i}" for i in range(n_cables)]
    return tuple(out)


def _expand_names(parameters: list[str], n: int) -> list[str]:
    if isinstance(parameters, str):
        parameters = (parameters,)
    names = []
    for p in parameters:
        if not isinstance(p, str):
            raise InvalidParameterError(f"parameters must be names (str), got {p!r}")
        m = re.fullmatch(r"(EA|mass_per_length|loss_factor|t_ref|L0)_\*", p)
        if m:
            names += [f"{m.group(1)}_{i}" for i in range(n)]
            continue
        m = re.fullmatch(r"(anchor|attachment)_(\*|\d+)", p)
        if m:
            cables = range(n) if m.group(2) == "*" else [int(m.group(2))]
            names += [f"{m.group(1)}_{i}_{a}" for i in cables for a in _AXES]
            continue
        names.append(p)
    return names


def expand_parameters(parameters: list[str], robot: Robot, pose: Pose, hold: str = "pose",
                      tension_reference: NDArray[np.float64] | None = None,
                      unstretched_lengths: NDArray[np.float64] | None = None) -> list[Parameter]:
    """The :class:`Parameter` of each name (module table; wildcards expanded).

    Parameters
    ----------
    parameters : str or sequence of str
    robot : Robot
    pose : Pose
    hold : {"pose", "lengths"}
    tension_reference : float or ndarray, optional
        The distribution's reference [N] (needed by ``t_ref_i``).
    unstretched_lengths : ndarray, shape (n,), optional
        [m] (the values of ``L0_i``).

    Raises
    ------
    InvalidParameterError
        An unknown name (the message lists the kinds), a name twice, or a name that the
        ``hold`` does not allow.

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> [(p.name, p.unit) for p in expand_parameters(["mass", "anchor_2"], sc.robot, sc.pose)]
    [('mass', 'kg'), ('anchor_2_x', 'm'), ('anchor_2_y', 'm'), ('anchor_2_z', 'm')]
    """
    n = robot.n_cables
    valid = set(parameter_names(n))
    out, seen = [], set()
    for name in _expand_names(parameters, n):
        if name not in valid:
            raise InvalidParameterError(
                f"parameters: {name!r} is not a parameter; the kinds are EA, "
                f"mass_per_length, loss_factor (each with _i or _* for cable i < {n}), mass, "
                f"inertia, inertia_xx..inertia_yz, com_x..com_z, pose_x..pose_rz, "
                f"anchor_i_x, attachment_i_x (or anchor_i, anchor_*), t_min, t_max, t_ref_i, "
                f"L0_i")
        if name in seen:
            raise InvalidParameterError(f"parameters name {name!r} twice")
        seen.add(name)
        out.append(_parameter(name, robot, pose, hold, tension_reference,
                              unstretched_lengths))
    if not out:
        raise InvalidParameterError("parameters must name at least one parameter")
    return out


def _parameter(name: str, robot: Robot, pose: Pose, hold: str, t_ref: NDArray[np.float64] | None,
               L0: NDArray[np.float64] | None) -> Parameter:
    n = robot.n_cables
    pl = robot.platform
    at_pose = ("pose_", "t_min", "t_max", "t_ref_")
    if hold == "lengths" and name.startswith(at_pose):
        raise InvalidParameterError(
            f"parameters: {name!r} applies at a fixed pose (hold='pose'); at fixed lengths "
            f"the pose and the tensions follow from the unstretched lengths")
    if hold == "pose" and name.startswith("L0_"):
        raise InvalidParameterError(
            f"parameters: {name!r} applies at fixed lengths (hold='lengths'); at a fixed "
            f"pose the lengths follow from the tension distribution")
    for base, (key, unit) in _CABLE.items():
        values = np.array([getattr(c, base) for c in robot.cables], dtype=float)
        if base == "loss_factor":
            scale = np.ones(n)
        elif name == base:
            scale = values / values[0]
        if name == base:
            return Parameter(name, float(values[0]), unit, {key: scale},
                             "damping" if base == "loss_factor" else "frequency")
        if name.startswith(base + "_") and name[len(base) + 1:].isdigit():
            i = int(name[len(base) + 1:])
            return Parameter(name, float(values[i]), unit, {key: np.eye(n)[i]},
                             "damping" if base == "loss_factor" else "frequency")
    if name == "mass":
        return Parameter(name, pl.mass, "kg", {"mass": 1.0})
    if name == "inertia":
        return Parameter(name, 1.0, "-", {"inertia": np.array(pl.inertia)})
    if name.startswith("inertia_"):
        a, b = _INERTIA[name[8:]]
        d = np.zeros((3, 3))
        d[a, b] = d[b, a] = 1.0
        return Parameter(name, float(pl.inertia[a, b]), "kg m^2", {"inertia": d})
    if name.startswith("com_"):
        k = _AXES.index(name[4:])
        return Parameter(name, float(pl.center_of_mass[k]), "m", {"com": np.eye(3)[k]})
    if name.startswith("pose_"):
        coord = name[5:]
        if coord.startswith("r"):
            k = _AXES.index(coord[1])
            return Parameter(name, float(pose.rotation[k]), "rad", {"rotvec": np.eye(3)[k]})
        k = _AXES.index(coord)
        return Parameter(name, float(pose.position[k]), "m", {"position": np.eye(3)[k]})
    m = re.fullmatch(r"(anchor|attachment)_(\d+)_([xyz])", name)
    if m:
        i, k = int(m.group(2)), _AXES.index(m.group(3))
        d = np.zeros((n, 3))
        d[i, k] = 1.0
        key = "anchors" if m.group(1) == "anchor" else "attachments"
        return Parameter(name, float(getattr(robot, key)[i, k]), "m", {key: d})
    if name in ("t_min", "t_max"):
        k = 0 if name == "t_min" else 1
        if not np.isfinite(robot.tension_limits[k]):
            raise InvalidParameterError(f"parameters: {name!r} is infinite in this robot")
        return Parameter(name, float(robot.tension_limits[k]), "N", {name: 1.0})
    if name.startswith("t_ref_"):
        if t_ref is None:
            raise InvalidParameterError(
                f"parameters: {name!r} needs the distribution's reference: give "
                f"tension_reference= (e.g. the equilibrium's tensions)")
        i = int(name[6:])
        value = float(np.broadcast_to(np.asarray(t_ref, float), (n,))[i])
        return Parameter(name, value, "N", {"t_ref": np.eye(n)[i]})
    i = int(name[3:])
    return Parameter(name, float(L0[i]) if L0 is not None else np.nan, "m",
                     {"L0": np.eye(n)[i]})


def with_values(
        robot: Robot, pose: Pose, names: list[str], values: ArrayLike,
        tension_reference: NDArray[np.float64] | None = None,
        unstretched_lengths: NDArray[np.float64] | None = None,
) -> tuple[Robot, Pose, NDArray[np.float64] | None, NDArray[np.float64] | None]:
    """The robot, pose, reference and lengths with each parameter set to its value (the
    inverse of :func:`expand_parameters`' base values): a new equilibrium of these gives
    the frequencies at the new values.

    Returns
    -------
    robot : Robot
    pose : Pose
    tension_reference : ndarray or None
    unstretched_lengths : ndarray or None

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> rob, pose, _, _ = with_values(sc.robot, sc.pose, ["mass", "pose_z"], [100.0, 1.5])
    >>> rob.platform.mass, pose.position.tolist()
    (100.0, [0.0, 0.0, 1.5])
    """
    n = robot.n_cables
    cables = list(robot.cables)
    pl = robot.platform
    anchors, attach = robot.anchors.copy(), robot.attachments.copy()
    limits = list(robot.tension_limits)
    position, rot = pose.position.copy(), pose.rotation.copy()
    t_ref = None if tension_reference is None else \
        np.broadcast_to(np.asarray(tension_reference, float), (n,)).copy()
    L0 = None if unstretched_lengths is None else np.array(unstretched_lengths, float)
    mass, com, inertia = pl.mass, pl.center_of_mass.copy(), pl.inertia.copy()
    for name, v in zip(names, values):
        v = float(v)
        hit = False
        for base in _CABLE:
            if name == base:
                v0 = getattr(cables[0], base)
                cables = [replace(c, **{base: (getattr(c, base) * v / v0 if v0 else v)})
                          for c in cables]
                hit = True
            elif name.startswith(base + "_") and name[len(base) + 1:].isdigit():
                i = int(name[len(base) + 1:])
                cables[i] = replace(cables[i], **{base: v})
                hit = True
        if hit:
            continue
        if name == "mass":
            mass = v
        elif name == "inertia":
            inertia = pl.inertia * v
        elif name.startswith("inertia_"):
            a, b = _INERTIA[name[8:]]
            inertia[a, b] = inertia[b, a] = v
        elif name.startswith("com_"):
            com[_AXES.index(name[4:])] = v
        elif name.startswith("pose_r"):
            rot[_AXES.index(name[6:])] = v
        elif name.startswith("pose_"):
            position[_AXES.index(name[5:])] = v
        elif name.startswith(("anchor_", "attachment_")):
            what, i, a = name.split("_")
            (anchors if what == "anchor" else attach)[int(i), _AXES.index(a)] = v
        elif name in ("t_min", "t_max"):
            limits[0 if name == "t_min" else 1] = v
        elif name.startswith("t_ref_"):
            t_ref[int(name[6:])] = v
        elif name.startswith("L0_"):
            L0[int(name[3:])] = v
        else:
            raise InvalidParameterError(f"unknown parameter {name!r}")
    platform = replace(pl, mass=mass, center_of_mass=com, inertia=inertia)
    rob = replace(robot, anchors=anchors, attachments=attach, cables=tuple(cables),
                  platform=platform, tension_limits=tuple(limits))
    return rob, Pose(position, rot), t_ref, L0


def equilibrium_with(robot: Robot, pose: Pose, names: list[str], values: ArrayLike,
                     hold: str = "pose", tension_reference: NDArray[np.float64] | None = None,
                     unstretched_lengths: NDArray[np.float64] | None = None,
                     **statics: float) -> Equilibrium:
    """The equilibrium at the new values: inverse statics at the (new) pose with the (new)
    reference (``hold="pose"``), or forward statics of the (new) lengths started at the pose
    (``hold="lengths"``); ``statics`` go to :meth:`dynstiff.Robot.equilibrium`.

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> eq = equilibrium_with(sc.robot, sc.pose, ["mass"], [100.0])
    >>> round(float(eq.tensions.sum() / sc.equilibrium().tensions.sum()), 3)
    1.096
    """
    rob, ps, t_ref, L0 = with_values(robot, pose, names, values, tension_reference,
                                     unstretched_lengths)
    if hold == "lengths":
        return rob.equilibrium(unstretched_lengths=L0, initial_pose=ps, **statics)
    return rob.equilibrium(pose=ps, tension_reference=t_ref, **statics)
