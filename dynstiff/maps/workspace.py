"""Workspace maps: statics, modes and design checks over a grid of poses (docs/theory.md §13).

:func:`workspace` evaluates every pose of a box grid of positions (optionally crossed with a
set of orientations) or of a list of poses, for every value of an optional cable parameter
(e.g. ``EA`` over its uncertain range). Per pose: feasibility (and the reason when the
statics fail: such a pose is recorded, never dropped), tensions and unstretched lengths, the
first ``n_modes`` modes with their platform participation (the platform's share of the
kinetic energy), the first global frequency, the relative margin of the global modes to the
forbidden band and the check verdicts; the poses where every check passes form the dynamic
workspace.

The poses are cut into chunks in input order; a chunk is one task, and along a chunk each
pose's statics start from the previous pose's equilibrium
(:meth:`dynstiff.Robot.equilibrium`, ``start=``). The chunking depends only on the input
and ``chunk_size``, so a serial run, local processes and a Dask cluster compute the same
numbers. Results come back as an ``xarray.Dataset`` (:mod:`dynstiff.maps.dataset`).
"""

import dataclasses
import sys
import time
from numbers import Integral

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.analyses.eigen import eigenfrequencies
from dynstiff.analyses.eigen import modes as modal
from dynstiff.cable.catenary_batch import catenary_arrays, sag_ratios
from dynstiff.errors import DynstiffError, InvalidParameterError
from dynstiff.models.ladder import RUNGS, build_model
from dynstiff.params import Cable
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

__all__ = ["CHECKS", "box_grid", "evaluate_chunk", "platform_participation", "workspace"]

#: The checks of a workspace map, in the order of the ``check`` dimension.
CHECKS = ("statics", "tension limits", "sag / chord", "global modes outside band",
          "local modes near global modes")
_CABLE_PARAMETERS = tuple(f.name for f in dataclasses.fields(Cable))


def box_grid(box, step):
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
    """
    try:
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
                f"step {step!r} m gives {n} points along one axis of box {b.tolist()}; "
                f"at most 10000")
        axes.append(lo + step * np.arange(n))
    return tuple(axes)


def _robot_with(robot, parameter, value):
    """The robot with cable field ``parameter`` set to ``value`` on every cable."""
    if parameter is None:
        return robot
    cables = tuple(dataclasses.replace(c, **{parameter: float(value)}) for c in robot.cables)
    return dataclasses.replace(robot, cables=cables)


def _proximity_gap(f, glob):
    """Smallest |f_l - f_g| / f_g over local l and global g modes [-] (inf if none), the
    gap of :func:`dynstiff.proximity_warnings`."""
    if not glob.any() or glob.all():
        return np.inf
    fg, fl = f[glob], f[~glob]
    return float(np.min(np.abs(fl[None, :] - fg[:, None]) / fg[:, None]))


def _margin(f_global, band_hz):
    """Smallest relative distance of the global modes outside the band [-] (negative
    inside): f / f_hi - 1 above the band, 1 - f / f_lo below it (docs/theory.md §13.2)."""
    if band_hz is None or f_global.size == 0:
        return np.nan
    lo, hi = band_hz
    above = f_global / hi - 1.0
    below = 1.0 - f_global / lo if lo > 0 else np.full(f_global.shape, -np.inf)
    return float(np.min(np.maximum(above, below)))


_FD_STEP = 1e-6        # relative frequency step of the derivative of K(omega) in omega^2


def _quadratic(x, A):
    """x_k^T A_k x_k for x (n, m) and A (n, m, m), each as ``x[k] @ A[k] @ x[k]`` (the same
    products, so the same rounding, as one mode at a time: the form is close to
    cancellation, and the order of its sums moves it by 1e-9)."""
    return np.array([xk @ Ak @ xk for xk, Ak in zip(x, A)])


def platform_participation(model, freq_hz):
    """Platform share of the kinetic energy of the modes at ``freq_hz`` [-], shape (n,).

    For an exact dynamic stiffness the total modal mass is -x^T dK/d(omega^2) x
    (docs/theory.md §13.3), so the share is x^T M_p x / (-x^T dK/d(omega^2) x), x the null
    vector of K(omega_r). The derivative is a central difference in omega^2 with steps
    1e-6 and 5e-7 (relative), Richardson-extrapolated: all modes in one call of
    ``dynamic_stiffness``. A mode with a cable pole within the steps takes the closed-form
    cable energies instead (``cable_kinetic_energies``, as :func:`dynstiff.modes`); a mode
    on a cable pole with the platform at rest has share 0. The modes' null vectors come
    from one batched ``eigh`` (docs/theory.md §13.6).

    Parameters
    ----------
    model : FrequencyModel (closed-form rung, undamped)
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz].
    """
    w = 2.0 * np.pi * np.asarray(freq_hz, dtype=float)
    n = w.size
    if n == 0:
        return np.zeros(0)
    h = _FD_STEP
    steps = np.array([1.0, 1 + h, 1 - h, 1 + h / 2, 1 - h / 2, 1 + 1e-9, 1 - 1e-9])
    K = model.dynamic_stiffness(w)
    Ks = model.dynamic_stiffness(np.outer(steps[1:5], w).ravel()).reshape(4, n, *K.shape[1:])
    J0 = model.cable_mode_count(np.outer(steps[1:], w).ravel()).reshape(6, n)
    Mp = model.platform_mass
    out = np.zeros(n)
    fin = np.flatnonzero(np.all(np.isfinite(K), axis=(1, 2)))
    if not fin.size:
        return out
    ev, V = np.linalg.eigh(K[fin])
    least = np.abs(ev).min(axis=1)
    pole = J0[4, fin] > J0[5, fin]             # a cable pole at the root
    if np.any(pole):
        scale = np.abs(np.linalg.eigvalsh(model.massless_stiffness())).max()
        keep = ~pole | (least <= 1e-6 * scale)
        fin, ev, V = fin[keep], ev[keep], V[keep]  # else local mode, platform at rest
    x = np.array([v[:, j] / np.sqrt(v[:, j] @ Mp @ v[:, j])
                  for v, j in zip(V, np.argmin(np.abs(ev), axis=1))])
    wk = w[fin]
    d1 = (Ks[0, fin] - Ks[1, fin]) / (wk**2 * ((1 + h) ** 2 - (1 - h) ** 2))[:, None, None]
    d2 = (Ks[2, fin] - Ks[3, fin]) / (wk**2 * ((1 + h / 2) ** 2 - (1 - h / 2) ** 2))[:, None,
                                                                                    None]
    out[fin] = 1.0 / -_quadratic(x, (4.0 * d2 - d1) / 3.0)
    for j in np.flatnonzero(J0[0, fin] != J0[1, fin]):     # a cable pole within the steps
        full = np.zeros(6)
        full[model.free_index] = x[j]
        out[fin[j]] = 1.0 / (1.0 + model.cable_kinetic_energies(w[fin[j]], full).sum())
    return out


def _modes(model, n_modes):
    """Frequencies [Hz], platform participation [-] and global flags of the lowest
    ``n_modes`` modes: Wittrick-Williams frequencies (the seeded, compiled count of
    theory.md §14.2) and :func:`platform_participation` for the closed-form rung,
    :func:`dynstiff.modes` otherwise."""
    if model.rung != "dsm" or model.damped:
        res = modal(model, n_modes=n_modes)
        return res.freq_hz, 1.0 - res.cable_energy_fraction, np.asarray(res.kind) == "global"
    f = eigenfrequencies(model, n_modes=n_modes)
    part = platform_participation(model, f)
    return f, part, part > 0.5


def evaluate_chunk(robot, poses, n_modes, band_hz, margin, proximity_rtol, max_sag_ratio,
                   rung, model_options):
    """Statics, modes and checks at consecutive poses, each warm-started from the last
    feasible one.

    Parameters
    ----------
    robot : Robot
    poses : ndarray, shape (k, 6)
        Positions [m] and rotation vectors [rad].
    n_modes : int
    band_hz : (float, float) or None
    margin, proximity_rtol, max_sag_ratio : float
    rung : str
    model_options : dict

    Returns
    -------
    dict of ndarray
        Keys of :data:`dynstiff.maps.dataset.VARIABLES` plus ``reason`` (list of str);
        leading axis k.
    """
    k, n, m = len(poses), robot.n_cables, n_modes
    nan = np.nan
    out = {"feasible": np.zeros(k, bool), "residual": np.full(k, nan),
               "tension": np.full((k, n), nan), "unstretched_length": np.full((k, n), nan),
               "min_tension": np.full((k, n), nan), "max_tension": np.full((k, n), nan),
               "sag_ratio": np.full((k, n), nan), "freq": np.full((k, m), nan),
               "platform_participation": np.full((k, m), nan), "is_global": np.zeros((k, m), bool),
               "first_global_hz": np.full(k, nan), "band_margin": np.full(k, nan),
               "proximity_gap": np.full(k, nan), "passed": np.zeros((k, len(CHECKS)), bool)}
    reasons = [""] * k
    EA = np.array([c.EA for c in robot.cables])
    w0 = np.array([c.mass_per_length for c in robot.cables]) * robot.g
    t_min, t_max = robot.tension_limits
    prev = None
    for j, x in enumerate(poses):
        pose = as_pose(x)
        try:
            try:
                eq = robot.equilibrium(pose=pose, start=prev)
            except DynstiffError:
                if prev is None:
                    raise
                eq = robot.equilibrium(pose=pose)        # a far neighbour: start afresh
            f, part, glob = _modes(build_model(eq, rung, **model_options), n_modes)
        except (DynstiffError, ArithmeticError, np.linalg.LinAlgError) as exc:
            reasons[j] = f"{type(exc).__name__}: {exc}"
            continue
        prev = eq
        B, _ = robot.attachment_points(pose)
        out["feasible"][j] = True
        out["residual"][j] = eq.residual
        out["tension"][j] = eq.tensions
        out["unstretched_length"][j] = eq.unstretched_lengths
        out["min_tension"][j] = eq.min_tensions
        out["max_tension"][j] = eq.max_tensions
        out["sag_ratio"][j] = sag_ratios(robot.anchors, B, *catenary_arrays(eq.states), EA, w0)
        r = min(m, len(f))
        out["freq"][j, :r] = f[:r]
        out["platform_participation"][j, :r] = part[:r]
        out["is_global"][j, :r] = glob[:r]
        fg = f[glob]
        out["first_global_hz"][j] = fg[0] if fg.size else nan
        out["band_margin"][j] = _margin(fg, band_hz)
        gap = _proximity_gap(f, glob)
        out["proximity_gap"][j] = gap if gap <= proximity_rtol else nan
        tol = 1e-9 * max(1.0, t_min)
        out["passed"][j] = (
            True,
            bool(np.all(eq.min_tensions >= t_min - tol) and np.all(eq.max_tensions
                                                                   <= t_max + tol)),
            bool(out["sag_ratio"][j].max() <= max_sag_ratio),
            bool(band_hz is None or out["band_margin"][j] >= margin),
            not gap <= proximity_rtol)
    out["reason"] = reasons
    return out


def _validated(robot, poses, box, step, orientations, parameter, values, n_modes, band_hz,
               margin, proximity_rtol, max_sag_ratio, rung, chunk_size, workers, client):
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a dynstiff.Robot, got "
                                    f"{type(robot).__name__}")
    if (poses is None) == (box is None):
        raise InvalidParameterError("give exactly one of poses= (a list of poses) or box= "
                                    "(with step=, a grid of positions)")
    if box is not None:
        if step is None:
            raise InvalidParameterError("box= needs step= (the grid spacing [m])")
        axes = box_grid(box, step)
        rot = np.zeros((1, 3))
        if orientations is not None:
            try:
                rot = np.asarray(orientations, dtype=float).reshape(-1, 3)
            except (TypeError, ValueError):
                raise InvalidParameterError(
                    f"orientations must be rotation vectors, shape (n, 3) [rad], got "
                    f"{orientations!r}") from None
            if rot.shape[0] == 0 or not np.all(np.isfinite(rot)):
                raise InvalidParameterError(
                    f"orientations must be finite rotation vectors, shape (n, 3) [rad], got "
                    f"{orientations!r}")
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
        layout = {"kind": "poses"}
    if (parameter is None) != (values is None):
        raise InvalidParameterError("parameter= and values= go together")
    if parameter is not None:
        if parameter not in _CABLE_PARAMETERS:
            raise InvalidParameterError(f"parameter must be a cable field, one of "
                                        f"{_CABLE_PARAMETERS}, got {parameter!r}")
        values = np.atleast_1d(np.asarray(values, dtype=float))
        if values.ndim != 1 or values.size == 0 or not np.all(np.isfinite(values)):
            raise InvalidParameterError(f"values must be a non-empty 1-D sequence of finite "
                                        f"numbers, got {values!r}")
        for v in values:                  # each value makes a valid cable (checked once)
            _robot_with(robot, parameter, v)
    for name, v in (("n_modes", n_modes), ("chunk_size", chunk_size)):
        if isinstance(v, bool) or not isinstance(v, Integral) or v < 1:
            raise InvalidParameterError(f"{name} must be an integer >= 1, got {v!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, Integral)
                                or workers < 1):
        raise InvalidParameterError(f"workers must be an integer >= 1, got {workers!r}")
    if workers is not None and client is not None:
        raise InvalidParameterError("give workers= (local processes) or client= (Dask), "
                                    "not both")
    if band_hz is not None:
        try:
            lo, hi = (positive_scalar("band_hz", b, allow_zero=True) for b in band_hz)
        except (TypeError, ValueError):
            raise InvalidParameterError(f"band_hz must be (low, high) with 0 <= low < high "
                                        f"[Hz], got {band_hz!r}") from None
        if not lo < hi:
            raise InvalidParameterError(f"band_hz must be (low, high) with 0 <= low < high "
                                        f"[Hz], got {band_hz!r}")
        band_hz = (lo, hi)
    if rung not in RUNGS:
        raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
    positive_scalar("margin", margin, allow_zero=True)
    positive_scalar("proximity_rtol", proximity_rtol)
    positive_scalar("max_sag_ratio", max_sag_ratio)
    return X, layout, values, band_hz


class _Progress:
    """One line on stderr: poses done, rate and time left."""

    def __init__(self, total, show):
        self.total, self.done, self.show, self.t0 = total, 0, show, time.perf_counter()

    def __call__(self, n):
        self.done += n
        if not self.show:
            return
        dt = time.perf_counter() - self.t0
        rate = self.done / dt if dt > 0 else 0.0
        left = (self.total - self.done) / rate if rate > 0 else float("nan")
        sys.stderr.write(f"\rworkspace: {self.done}/{self.total} poses, {rate:.0f} poses/s, "
                         f"{left:.0f} s left ")
        if self.done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def _run(tasks, workers, client, progress):
    """Results of ``evaluate_chunk(*args)`` for every task, in task order: serially, on
    ``workers`` local processes or on a Dask client."""
    results = [None] * len(tasks)
    if client is not None:
        from distributed import as_completed
        futures = [client.submit(evaluate_chunk, *args, pure=False) for args in tasks]
        index = {f.key: i for i, f in enumerate(futures)}
        for fut in as_completed(futures):
            i = index[fut.key]
            results[i] = fut.result()
            progress(len(tasks[i][1]))
        return results
    if workers is not None and workers > 1:
        from concurrent.futures import ProcessPoolExecutor, as_completed
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futures = {pool.submit(evaluate_chunk, *args): i for i, args in enumerate(tasks)}
            for fut in as_completed(futures):
                i = futures[fut]
                results[i] = fut.result()
                progress(len(tasks[i][1]))
        return results
    for i, args in enumerate(tasks):
        results[i] = evaluate_chunk(*args)
        progress(len(args[1]))
    return results


def workspace(robot, poses=None, *, box=None, step=None, orientations=None, parameter=None,
              values=None, n_modes=20, band_hz=None, margin=0.05, proximity_rtol=0.03,
              max_sag_ratio=0.02, rung="dsm", chunk_size=25, workers=None, client=None,
              progress=False, **model_options):
    """Map statics, modes and design checks over a grid or a list of poses.

    Parameters
    ----------
    robot : Robot
    poses : sequence of Pose or of 3 / 6 numbers, optional
        The poses, in this order (dimension ``pose``). Give ``poses`` or ``box``.
    box : sequence of 6 float, optional
        (x0, x1, y0, y1, z0, z1) [m]: a grid of positions with spacing ``step`` [m]
        (dimensions ``x``, ``y``, ``z``), see :func:`box_grid`.
    orientations : array_like, shape (n_o, 3), optional
        Rotation vectors [rad] crossed with the grid positions (dimension ``orientation``).
    parameter : str, optional
        A :class:`Cable` field set on every cable, e.g. ``"EA"`` [N].
    values : array_like, shape (n_v,), optional
        Its values (dimension ``parameter``).
    n_modes : int
        Modes per pose (dimension ``mode``), lowest first.
    band_hz : (float, float), optional
        Forbidden band [Hz]; ``band_margin`` is the relative distance of the global modes
        (among the ``n_modes``) outside it, and its check asks for at least ``margin``.
    margin, proximity_rtol, max_sag_ratio : float
        Limits of the checks, as :func:`dynstiff.analyses.checks.design_checks`.
    rung : str
        Model of the modes, one of :data:`dynstiff.models.ladder.RUNGS` (default "dsm").
    chunk_size : int
        Poses per task; statics are warm-started along a task.
    workers : int, optional
        Local worker processes (``concurrent.futures.ProcessPoolExecutor``).
    client : distributed.Client, optional
        A Dask client: the tasks run on its cluster.
    progress : bool
        Show a progress line on stderr.
    **model_options
        Passed to :func:`dynstiff.models.ladder.build_model`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``x, y, z[, orientation]`` (or ``pose``) ``[, parameter], mode, cable,
        check``; variables and attributes as :func:`dynstiff.maps.dataset.to_dataset`.
        Infeasible poses hold ``feasible = False``, their ``reason`` and NaN.
    """
    X, layout, values, band_hz = _validated(
        robot, poses, box, step, orientations, parameter, values, n_modes, band_hz, margin,
        proximity_rtol, max_sag_ratio, rung, chunk_size, workers, client)
    from dynstiff.maps.dataset import to_dataset
    robots = ([robot] if parameter is None
              else [_robot_with(robot, parameter, v) for v in values])
    tasks = []
    for rob in robots:
        for s in range(0, len(X), chunk_size):
            tasks.append((rob, X[s:s + chunk_size], n_modes, band_hz, margin, proximity_rtol,
                          max_sag_ratio, rung, model_options))
    t0 = time.perf_counter()
    results = _run(tasks, workers, client, _Progress(len(X) * len(robots), progress))
    settings = {"checks": CHECKS, "n_modes": n_modes, "band_hz": band_hz, "margin": margin,
                    "proximity_rtol": proximity_rtol, "max_sag_ratio": max_sag_ratio, "rung": rung,
                    "chunk_size": chunk_size, "wall_time_s": time.perf_counter() - t0,
                    "engine": ("dask" if client is not None else
                            f"{workers} processes" if workers and workers > 1 else "serial")}
    return to_dataset(robot, X, layout, parameter, values, results, settings)
