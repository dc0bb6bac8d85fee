"""TOML scene reader with schema checks that name the key and its line."""

import os
import re
import reprlib
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.constants import DOF_NAMES, STANDARD_GRAVITY
from dynstiff.errors import DynstiffError, InvalidParameterError
from dynstiff.params import DEFAULT_DAMPING, Cable, Damping
from dynstiff.robot.platform import Platform
from dynstiff.robot.pose import Pose
from dynstiff.robot.robot import Robot
from dynstiff.robot.waypoints import WaypointPath

if TYPE_CHECKING:
    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["Scene", "SceneError", "read_scene", "load_scene", "list_scenes"]

#: Folder of the built-in scene files.
SCENE_DIR = Path(__file__).resolve().parent

_SCHEMA = {
    "scene": {"name", "description", "g"},
    "platform": {"mass", "center_of_mass", "inertia", "free_dofs"},
    "cable": {"mass_per_length", "EA", "viscous_damping", "loss_factor"},
    "tension_limits": {"min", "max"},
    "cables": {"anchor", "attachment", "mass_per_length", "EA", "viscous_damping",
               "loss_factor"},
    "pose": {"position", "rotation", "unstretched_lengths"},
    "analysis": {"band_hz", "n_modes", "forbidden_band_hz", "model", "model_rtol",
                 "segments"},
    "damping": {"platform_ratio", "cable_loss_factor", "cable_viscous_damping"},
    "study": None,                  # free-form: parameters of the scene's validation study
    "workspace": {"box"},
    "trajectories": {"name", "law", "times", "positions", "rotations", "velocities",
                     "accelerations", "blend_times"},
}
_REQUIRED = {"platform": {"mass"}, "cables": {"anchor", "attachment"},
             "workspace": {"box"}, "trajectories": {"name", "law", "times", "positions"}}
#: Sections that are arrays of tables ([[name]]).
_ARRAYS = ("cables", "trajectories")

# the type every key must have as written in the file (no coercion: "1" is not a number and
# true is not 1): "number", "int", "str", "vector" (3 numbers), "numbers" (a list of numbers),
# "names" (a list of strings), "inertia" (a number, 3 numbers or 3 rows of 3 numbers)
_TYPES = {
    "name": "str", "description": "str", "g": "number", "mass": "number",
    "center_of_mass": "vector", "inertia": "inertia", "free_dofs": "names",
    "mass_per_length": "number", "EA": "number", "viscous_damping": "number",
    "loss_factor": "number", "min": "number", "max": "number", "anchor": "vector",
    "attachment": "vector", "position": "vector", "rotation": "vector",
    "unstretched_lengths": "numbers", "band_hz": "numbers", "forbidden_band_hz": "numbers",
    "n_modes": "int", "model": "str", "model_rtol": "number", "segments": "int",
    "platform_ratio": "number", "cable_loss_factor": "number",
    "cable_viscous_damping": "number", "box": "numbers", "law": "str", "times": "numbers",
    "positions": "points", "rotations": "points", "velocities": "points",
    "accelerations": "points", "blend_times": "numbers",
}


def _is_number(v):
    """A TOML number a float can hold: not a boolean, and no integer beyond 1.8e308."""
    return isinstance(v, float) or (isinstance(v, int) and not isinstance(v, bool)
                                    and abs(v) <= sys.float_info.max)


def _type_error(value, kind):
    """None if ``value`` has the type ``kind`` of _TYPES, else what was expected."""
    if kind == "number" and not _is_number(value):
        return "a number"
    if kind == "int" and (not isinstance(value, int) or isinstance(value, bool)):
        return "an integer"
    if kind == "str" and not isinstance(value, str):
        return "a string"
    if kind in ("vector", "numbers") and not (
            isinstance(value, list) and all(_is_number(v) for v in value)
            and (len(value) == 3 if kind == "vector" else len(value) > 0)):
        return "3 numbers" if kind == "vector" else "a list of numbers"
    if kind == "points" and not (
            isinstance(value, list) and value and all(
                isinstance(r, list) and len(r) == 3 and all(_is_number(v) for v in r)
                for r in value)):
        return "a list of points (3 numbers each)"
    if kind == "names" and not (isinstance(value, list)
                                and all(isinstance(v, str) for v in value)):
        return "a list of names"
    if kind == "inertia" and not (
            _is_number(value)
            or (isinstance(value, list) and len(value) == 3
                and (all(_is_number(v) for v in value)
                     or all(isinstance(r, list) and len(r) == 3
                            and all(_is_number(v) for v in r) for r in value)))):
        return "a number, 3 numbers or 3 rows of 3 numbers"
    return None


class SceneError(DynstiffError, ValueError):
    """A scene file is malformed; the message names the file, the key and its line.

    Examples
    --------
    >>> import os, tempfile
    >>> import dynstiff as ds
    >>> path = os.path.join(tempfile.mkdtemp(), "bad.toml")
    >>> with open(path, "w") as f:
    ...     _ = f.write("robot = 1")
    >>> try:
    ...     ds.load_scene(path)
    ... except ds.SceneError as exc:
    ...     print(type(exc).__name__, isinstance(exc, ValueError))
    SceneError True
    """

@dataclass(frozen=True)
class Scene:
    """A robot with the pose (or cable lengths) and analysis settings of a scene file.

    Attributes
    ----------
    robot : Robot
    pose : Pose or None
    unstretched_lengths : ndarray or None, shape (n,) [m]
    band_hz : (float, float) or None
        Band of interest of the analysis [Hz].
    n_modes : int or None
    forbidden_band_hz : (float, float) or None
        Band no global mode may enter, with its margin (the design checks) [Hz].
    model : str or None
        Rung of the cable model the analyses use (``[analysis] model``).
    model_rtol : float or None
        Admissible relative frequency error of the cable model [-].
    segments : int or None
        Segments per cable of the "lumped" rung.
    damping : Damping
        The ``[damping]`` section, its defaults where absent (:class:`dynstiff.Damping`).
    study : dict
        The free-form ``[study]`` table: parameters of the scene's validation study
        (trajectory, excitation, drums ...), with units in the file's comments; not read
        by the analysis itself.
    name, description : str
    path : Path
    trajectories : dict
        The ``[[trajectories]]``: :class:`dynstiff.WaypointPath` by name (empty if none).
    workspace_box : tuple of 6 float or None
        ``[workspace] box`` (x0, x1, y0, y1, z0, z1) [m]: the default box of a workspace
        map.

    Examples
    --------
    >>> import dynstiff as ds
    >>> scene = ds.load_scene("cogiro")
    >>> scene.pose.position.tolist()
    [0.0, 0.0, 1.0]
    >>> eq = scene.equilibrium()
    >>> print(f"{eq.tensions.max():.1f} N")
    304.1 N
    """

    robot: Robot
    pose: object = None
    unstretched_lengths: object = None
    band_hz: object = None
    n_modes: object = None
    forbidden_band_hz: object = None
    model: object = None
    model_rtol: object = None
    segments: object = None
    damping: object = DEFAULT_DAMPING
    study: object = None
    name: str = ""
    description: str = ""
    path: object = None
    trajectories: object = None
    workspace_box: object = None

    def __post_init__(self):
        object.__setattr__(self, "trajectories", dict(self.trajectories or {}))

    def equilibrium(self, pose: "Pose | np.typing.ArrayLike | None" = None,
                    unstretched_lengths: "np.typing.ArrayLike | None" = None,
                    **kw: object) -> "Equilibrium":
        """Static equilibrium of the scene's robot (:meth:`Robot.equilibrium`).

        At ``pose`` (inverse statics) or for ``unstretched_lengths`` [m] (forward statics)
        when one is given (at most one), otherwise at the scene's own pose or lengths.
        Other keywords go to :meth:`Robot.equilibrium` (``tol``, ``initial_pose``, ...).
        """
        if pose is not None and unstretched_lengths is not None:
            raise InvalidParameterError(
                "give at most one of pose= or unstretched_lengths= (with neither, the scene's "
                "own is used)")
        if pose is not None:
            return self.robot.equilibrium(pose=pose, **kw)
        if unstretched_lengths is not None:
            return self.robot.equilibrium(unstretched_lengths=unstretched_lengths, **kw)
        if self.pose is not None:
            return self.robot.equilibrium(pose=self.pose, **kw)
        if self.unstretched_lengths is not None:
            return self.robot.equilibrium(unstretched_lengths=self.unstretched_lengths, **kw)
        raise SceneError(f"scene {self.name!r} names neither a [pose] nor unstretched_lengths; "
                         f"give pose= or unstretched_lengths=")


#: A table header line, ``[name]`` or ``[[name]]`` (not the continuation line of an array
#: that spans lines, such as a row ``[1.0, 2.0, 3.0]]`` of a tensor).
_HEADER = re.compile(r"^\s*\[\[?\s*[A-Za-z_][\w-]*(\.[\w-]+)*\s*\]\]?\s*(#.*)?$")


def _line_of(text, key, section=None, occurrence=0):
    """1-based line of ``key =`` (inside ``[section]`` or its ``[[section]]`` number
    ``occurrence`` if given), or of the section header; None if not found."""
    lines = text.splitlines()
    start, count = 0, -1
    if section is not None:
        for i, ln in enumerate(lines):
            if re.match(rf"^\s*\[\[?\s*{re.escape(section)}\s*\]\]?", ln):
                count += 1
                if count == occurrence:
                    start = i
                    break
        else:
            return None
        if key is None:
            return start + 1
    for i in range(start, len(lines)):
        if i > start and section is not None and _HEADER.match(lines[i]):
            break
        if re.match(rf"^\s*{re.escape(str(key))}\s*=", lines[i]):
            return i + 1
    return None


def read_scene(path):
    """Read a scene TOML file.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        Syntax errors (with line), unknown or missing keys and invalid values (with key and
        line). :class:`FileNotFoundError` if the file does not exist.
    """
    import tomllib
    path = Path(path)
    if path.is_dir():
        raise SceneError(f"{path}: is a folder, not a scene file")
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise SceneError(f"{path}: not a UTF-8 text (TOML) file ({exc.reason} at byte "
                         f"{exc.start})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{path}: TOML syntax error: {exc}") from None

    def fail(msg, key=None, section=None, occurrence=0):
        line = _line_of(text, key, section, occurrence)
        where = f"line {line}: " if line else ""
        raise SceneError(f"{path}: {where}{msg}")

    for sec in data:
        if sec not in _SCHEMA:
            fail(f"unknown section [{sec}] (expected one of {sorted(_SCHEMA)})", None, sec)
    for sec, keys in _SCHEMA.items():
        if keys is None:
            continue
        tables = data.get(sec, [] if sec in _ARRAYS else {})
        tables = tables if isinstance(tables, list) else [tables]
        for k, tab in enumerate(tables):
            for key in tab:
                if key not in keys:
                    fail(f"unknown key {key!r} in [{sec}] (expected one of {sorted(keys)})",
                         key, sec, k)
            for key in _REQUIRED.get(sec, ()) if sec in data else ():
                if key not in tab:
                    fail(f"missing key {key!r} in [{sec}]", None, sec, k)
            for key, value in tab.items():
                expected = _type_error(value, _TYPES[key])
                if expected:
                    fail(f"{key} in [{sec}] must be {expected}, got {reprlib.repr(value)}",
                         key, sec, k)
            if sec == "pose" and "position" in tab and "unstretched_lengths" in tab:
                fail("[pose] gives both position and unstretched_lengths: give one (inverse "
                     "or forward statics)", "unstretched_lengths", "pose")
    if not data.get("cables"):
        fail("no [[cables]] table: a scene needs at least one cable")
    if "platform" not in data:
        fail("missing section [platform]")

    def build(what, fn, key, section, occurrence=0):
        try:
            return fn()
        except (InvalidParameterError, TypeError, ValueError) as exc:
            fail(f"[{section}] {what}: {exc}", key, section, occurrence)

    default = data.get("cable", {})
    cables, anchors, attach = [], [], []
    for k, tab in enumerate(data["cables"]):
        spec = {**default, **{c: v for c, v in tab.items() if c not in ("anchor", "attachment")}}
        if "mass_per_length" not in spec or "EA" not in spec:
            fail(f"cable {k}: mass_per_length and EA must be given in [cable] or [[cables]]",
                 None, "cables", k)
        cables.append(build(f"cable {k}", lambda: Cable(**spec),
                            next(iter(tab), None), "cables", k))
        anchors.append(tab["anchor"])
        attach.append(tab["attachment"])
    pl = data["platform"]
    platform = build("platform", lambda: Platform(
        mass=pl["mass"], center_of_mass=pl.get("center_of_mass", [0, 0, 0]),
        inertia=pl.get("inertia", 0.0),
        free_dofs=tuple(pl.get("free_dofs", DOF_NAMES))),
        "mass", "platform")
    sc = data.get("scene", {})
    lim = data.get("tension_limits", {})
    robot = build("robot", lambda: Robot(
        anchors=np.array(anchors, dtype=float), attachments=np.array(attach, dtype=float),
        cables=cables, platform=platform, g=sc.get("g", STANDARD_GRAVITY),
        tension_limits=(lim.get("min", 1.0), lim.get("max", np.inf)),
        name=sc.get("name", path.stem)), "anchor", "cables")
    pose = lengths = None
    ps = data.get("pose", {})
    if "unstretched_lengths" in ps:
        lengths = build("unstretched_lengths", lambda: np.asarray(
            ps["unstretched_lengths"], dtype=float), "unstretched_lengths", "pose")
        if lengths.shape != (robot.n_cables,):
            fail(f"unstretched_lengths needs {robot.n_cables} values", "unstretched_lengths",
                 "pose")
    if "position" in ps:
        pose = build("pose", lambda: Pose(ps["position"], ps.get("rotation", [0, 0, 0])),
                     "position", "pose")
    study = data.get("study", {})
    if not isinstance(study, dict):
        fail("[study] must be a table", None, "study")
    an = data.get("analysis", {})
    bands = {}
    for key in ("band_hz", "forbidden_band_hz"):
        band = an.get(key)
        if band is not None and (not isinstance(band, list) or len(band) != 2
                                 or not all(isinstance(b, (int, float)) for b in band)
                                 or not 0 <= band[0] < band[1]):
            fail(f"{key} must be [low, high] with 0 <= low < high, got {band!r}", key,
                 "analysis")
        bands[key] = None if band is None else tuple(float(b) for b in band)
    for key in ("model_rtol", "segments", "n_modes"):
        if key in an and not an[key] > 0:
            fail(f"{key} in [analysis] must be > 0, got {an[key]!r}", key, "analysis")
    damping = build("damping", lambda: Damping(**data.get("damping", {})), None, "damping")
    box = data.get("workspace", {}).get("box")
    if box is not None and (len(box) != 6 or any(b < a for a, b in zip(box[::2], box[1::2]))):
        fail(f"box must be 6 numbers x0 x1 y0 y1 z0 z1 [m] with x0 <= x1 ..., got {box!r}",
             "box", "workspace")
    trajectories = {}
    for k, tab in enumerate(data.get("trajectories", [])):
        if not isinstance(data["trajectories"], list):
            fail("trajectories must be [[trajectories]] tables", None, "trajectories")
        if tab["name"] in trajectories:
            fail(f"two trajectories named {tab['name']!r}", "name", "trajectories", k)
        trajectories[tab["name"]] = build(
            f"trajectory {tab['name']!r}", lambda tab=tab: WaypointPath(
                times=tab["times"], positions=tab["positions"],
                rotations=tab.get("rotations", [[0.0, 0.0, 0.0]] * len(tab["times"])),
                law=tab["law"], velocities=tab.get("velocities"),
                accelerations=tab.get("accelerations"), blend_times=tab.get("blend_times"),
                name=tab["name"]), "name", "trajectories", k)
    return Scene(robot=robot, pose=pose, unstretched_lengths=lengths,
                 band_hz=bands["band_hz"], n_modes=an.get("n_modes"),
                 forbidden_band_hz=bands["forbidden_band_hz"],
                 model=an.get("model"), model_rtol=an.get("model_rtol"),
                 segments=an.get("segments"), damping=damping,
                 study=study, name=sc.get("name", path.stem),
                 description=sc.get("description", ""),
                 path=path, trajectories=trajectories,
                 workspace_box=None if box is None else tuple(float(b) for b in box))


def list_scenes() -> list[str]:
    """Names of the built-in scenes.

    Examples
    --------
    >>> import dynstiff as ds
    >>> ds.list_scenes()
    ['cogiro', 'fast', 'fourcable', 'pendulum', 'planar2', 'simulator', 'sixcable']
    """
    return sorted(p.stem for p in SCENE_DIR.glob("*.toml"))


def load_scene(name: str | Path) -> Scene:
    """Built-in scene by name (see :func:`list_scenes`) or a path to a TOML file.

    Returns
    -------
    Scene

    Examples
    --------
    >>> import dynstiff as ds
    >>> scene = ds.load_scene("cogiro")
    >>> scene.name, scene.robot.n_cables
    ('cogiro', 8)
    """
    if not isinstance(name, (str, os.PathLike)):
        raise InvalidParameterError(
            f"name must be a built-in scene's name or a path to a TOML file, got {name!r}")
    p = Path(name)
    if p.suffix == ".toml" or p.exists():
        return read_scene(p)
    if name not in list_scenes():
        raise SceneError(f"unknown scene {name!r}; built-in scenes: {list_scenes()}")
    return read_scene(SCENE_DIR / f"{name}.toml")
