"""The arguments of a workspace map (docs/theory.md §13, §13.8): the box grid's axes, the
robot at each value of a cable parameter, and every argument checked before the first pose
(a bad one is an error naming it, never a column of "infeasible" poses)."""

import dataclasses
from numbers import Integral, Real

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.analyses.verdicts import CHECKS
from dynstiff.errors import DynstiffError, InvalidParameterError
from dynstiff.maps.guards import check_orientations, check_size
from dynstiff.models.ladder import RUNGS
from dynstiff.params import Cable, Damping
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

__all__ = ["CABLE_PARAMETERS", "box_grid", "checked_uncertain", "robot_with", "validate_arguments"]

CABLE_PARAMETERS = tuple(f.name for f in dataclasses.fields(Cable))


def box_grid(box: "np.typing.ArrayLike",
             step: "float | np.typing.ArrayLike") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Axes of a box grid of positions [m].

    Parameters
    ----------
    box : sequence of 6 float
        (x0, x1, y0, y1, z0, z1) [m], x0 <= x1 etc.
    step : float
        Grid spacing [m], > 0; each axis runs from its low end in steps of ``step`` up to
        its high end (included when it falls on the grid, within 1e-9 step).

    Returns
    -------
    tuple of three ndarray
        x, y and z axes [m].

    Examples
    --------
    >>> from dynstiff import box_grid
    >>> x, y, z = box_grid([-0.5, 0.5, 0.0, 0.0, 1.0, 1.0], 0.5)
    >>> x.tolist(), y.tolist(), z.tolist()
    ([-0.5, 0.0, 0.5], [0.0], [1.0])
    """
    try:
        if np.asarray(box).dtype.kind not in "iuf" or any(     # text, booleans: no lengths
                isinstance(v, (bool, np.bool_)) for v in np.asarray(box, dtype=object).ravel()):
            raise TypeError
        b = np.asarray(box, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"box must be 6 numbers x0 x1 y0 y1 z0 z1 [m], got "
                                    f"{box!r}") from None
    if b.shape != (6,) or not np.all(np.isfinite(b)) or np.any(b[1::2] < b[0::2]):
        raise InvalidParameterError(
            f"box must be 6 finite numbers x0 x1 y0 y1 z0 z1 [m] with x0 <= x1, y0 <= y1, "
            f"z0 <= z1, got {box!r}")
    step = positive_scalar("step", step)
    axes = []
    for lo, hi in b.reshape(3, 2):
        n = int(np.floor((hi - lo) / step + 1e-9)) + 1
        if n > 10_000:
            raise InvalidParameterError(
                f"step {step!r} m gives {n} points along one axis of box {b.tolist()}, "
                f"more than 10000: raise step= (--step) or shrink the box (--box)")
        axes.append(lo + step * np.arange(n))
    return tuple(axes)


def robot_with(robot, parameter, value):
    """The robot with cable field ``parameter`` set to ``value`` on every cable."""
    if parameter is None:
        return robot
    cables = tuple(dataclasses.replace(c, **{parameter: float(value)}) for c in robot.cables)
    return dataclasses.replace(robot, cables=cables)


def validate_arguments(robot, poses, box, step, orientations, parameter, values, n_modes, rung,
               chunk_size, workers, client, damping, max_modes, max_poses):
    """Check a map's arguments before its first pose (theory.md §13.8) and return its poses
    (n, 6), layout and parameter values; every bad argument is an InvalidParameterError
    naming it."""
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a dynstiff.Robot, got "
                                    f"{type(robot).__name__}")
    for name, v in (("n_modes", n_modes), ("chunk_size", chunk_size)):
        if isinstance(v, bool) or not isinstance(v, Integral) or v < 1:
            raise InvalidParameterError(f"{name} must be an integer >= 1, got {v!r}")
    if n_modes > max_modes:
        raise InvalidParameterError(f"n_modes must be at most max_modes={max_modes} (the "
                                    f"most modes a pose computes), got {n_modes!r}")
    if (parameter is None) != (values is None):
        raise InvalidParameterError("parameter= and values= go together")
    if parameter is not None:
        if parameter not in CABLE_PARAMETERS:
            raise InvalidParameterError(f"parameter must be a cable field, one of "
                                        f"{CABLE_PARAMETERS}, got {parameter!r}")
        given = values
        try:
            values = np.atleast_1d(np.asarray(values, dtype=float))
            flags = [isinstance(v, (bool, np.bool_))
                     for v in np.atleast_1d(np.asarray(given, dtype=object)).ravel()]
        except (TypeError, ValueError):
            values, flags = np.empty(0), []
        if (values.ndim != 1 or values.size == 0 or not np.all(np.isfinite(values))
                or any(flags)):
            raise InvalidParameterError(f"values must be a non-empty 1-D sequence of finite "
                                        f"numbers, got {given!r}")
        for v in values:                  # each value makes a valid cable (checked once)
            robot_with(robot, parameter, v)
    n_values = 1 if parameter is None else len(values)
    if (poses is None) == (box is None):
        raise InvalidParameterError("give exactly one of poses= (a list of poses) or box= "
                                    "(with step=, a grid of positions)")
    if box is not None:
        if step is None:
            raise InvalidParameterError("box= needs step= (the grid spacing [m])")
        if isinstance(step, (bool, np.bool_)):
            raise InvalidParameterError(f"step must be a number > 0 [m], got {step!r}")
        axes = box_grid(box, step)
        rot = np.zeros((1, 3)) if orientations is None else check_orientations(orientations)
        n = int(np.prod([len(a) for a in axes])) * len(rot) * n_values
        check_size(n, robot.n_cables, n_modes, len(CHECKS), max_poses,
                   what=f"box {list(map(float, box))} with step {float(step)} m"
                        + (f" x {len(rot)} orientations" if len(rot) > 1 else "")
                        + (f" x {n_values} values" if n_values > 1 else ""))
        P = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
        X = np.concatenate([np.repeat(P, len(rot), axis=0), np.tile(rot, (len(P), 1))], 1)
        layout = {"kind": "grid", "axes": axes, "orientations": None if orientations is None
                      else rot}
    else:
        if orientations is not None:
            raise InvalidParameterError("orientations= goes with box=; give each pose its "
                                        "rotation in poses=")
        try:
            X = np.array([as_pose(p).as_vector() for p in poses])
        except (TypeError, ValueError, DynstiffError) as exc:
            raise InvalidParameterError(f"poses must be a sequence of poses (3 or 6 numbers "
                                        f"or Pose): {exc}") from None
        if X.shape[0] == 0:
            raise InvalidParameterError("poses must hold at least one pose")
        check_size(len(X) * n_values, robot.n_cables, n_modes, len(CHECKS), max_poses,
                   what=f"{len(X)} poses" + (f" x {n_values} values" if n_values > 1 else ""))
        layout = {"kind": "poses"}
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, Integral)
                                or workers < 1):
        raise InvalidParameterError(f"workers must be an integer >= 1, got {workers!r}")
    if workers is not None and client is not None:
        raise InvalidParameterError("give workers= (local processes) or client= (Dask), "
                                    "not both")
    if rung not in RUNGS:
        raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
    if not isinstance(damping, Damping):
        raise InvalidParameterError(f"damping must be a dynstiff.Damping, got {damping!r}")
    return X, layout, values


def checked_uncertain(robot, first_pose, uncertain, n_samples, seed, confidence, options,
                      tensions):
    """The map's uncertain row settings (:func:`dynstiff.maps.workspace.workspace`) checked
    before any pose: (items, n_samples, seed, confidence), items {name: Uncertain} with
    every name a parameter of ``robot`` at ``first_pose`` (6 numbers)."""
    from dynstiff.analyses.uncertainty import uncertain_items, uncertain_parameters
    items = uncertain_items(uncertain)
    for name, v in (("n_samples", n_samples), ("seed", seed)):
        if isinstance(v, bool) or not isinstance(v, Integral) or v < (1 if name == "n_samples"
                                                                     else 0):
            raise InvalidParameterError(f"{name} must be an integer >= "
                                        f"{1 if name == 'n_samples' else 0}, got {v!r}")
    if isinstance(confidence, bool) or not isinstance(confidence, Real) \
            or not 0 < confidence < 1:
        raise InvalidParameterError(f"confidence must be a number in (0, 1), got "
                                    f"{confidence!r}")
    if options.forbidden_hz is None:
        raise InvalidParameterError("uncertain= needs band_hz: its row is the probability "
                                    "that a platform mode enters the forbidden band")
    if tensions != "default":
        raise InvalidParameterError(f"uncertain= maps the default tensions (those of the "
                                    f"design checks), not tensions={tensions!r}")
    uncertain_parameters(list(items), robot, as_pose(first_pose))
    return items, int(n_samples), int(seed), float(confidence)
