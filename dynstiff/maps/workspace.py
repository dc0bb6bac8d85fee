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

import sys
import time
import warnings
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import flag
from dynstiff.analyses.checks import check_options, damped_model, modal_model_options
from dynstiff.analyses.optimal_tensions import TENSIONS, band_margin, tension_equilibrium
from dynstiff.analyses.participation import FRF_AMPLIFICATION_LIMIT, PLATFORM_SHARE_THRESHOLD
from dynstiff.analyses.platform_modes import MAX_PLATFORM_MODES
from dynstiff.analyses.uncertainty import UNCERTAIN_CHECK, uncertain_row
from dynstiff.analyses.verdicts import CHECKS, equilibrium_sag_ratios, modal_rows, statics_rows
from dynstiff.errors import ClosedFormWarning, DynstiffError, Interrupted, InvalidParameterError
from dynstiff.maps.arguments import box_grid, checked_uncertain, robot_with, validate_arguments
from dynstiff.maps.guards import MAX_POSES, check_model_options, check_size, estimate_text
from dynstiff.maps.store import resumed
from dynstiff.models.dsm import ROBOT_BOUND_MESSAGE
from dynstiff.models.ladder import build_model
from dynstiff.params import DEFAULT_DAMPING, Damping
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    import os

    import xarray

__all__ = ["CHECKS", "box_grid", "evaluate_chunk", "workspace"]

def _band_margin(pm, options):
    """Smallest relative distance outside the forbidden band of the modes the margin check
    holds (platform share >= participation) [-], negative inside: f / f_hi - 1 above the
    band, 1 - f / f_lo below it (docs/theory.md §13.2), as
    :func:`dynstiff.analyses.optimal_tensions.band_margin`; NaN without a band or modes."""
    if options.forbidden_hz is None:
        return np.nan
    return band_margin(pm, options.forbidden_hz, options.participation)


def _proximity_gap(pm):
    """Smallest |f_l - f_p| / f_p over local modes l and platform modes p [-] (inf if no
    pair; NaN if the platform modes were not all found)."""
    if not pm.complete:
        return np.nan
    f = np.asarray(pm.modes.freq_hz)
    local = np.asarray(pm.modes.kind) == "local"
    if not local.any() or not pm.index.size:
        return np.inf
    fp = f[pm.index]
    return float(np.min(np.abs(f[local][None, :] - fp[:, None]) / fp[:, None]))


def evaluate_chunk(robot, poses, n_modes, options, rung, damping, model_options, checks,
                   tensions="default", uncertain=None):
    """Statics, modes and the verdicts of :mod:`dynstiff.analyses.verdicts` at consecutive
    poses, each warm-started from the last feasible one (the statics, and nothing else,
    depend on the start: the verdicts are those of
    :func:`dynstiff.analyses.checks.design_checks` at the same pose).

    Parameters
    ----------
    robot : Robot
    poses : ndarray, shape (k, 6)
        Positions [m] and rotation vectors [rad].
    n_modes : int
        Modes stored per pose (the verdicts use every mode they need).
    options : CheckOptions
    rung : str
    damping : Damping
    model_options : dict
    checks : tuple of str
        The checks mapped (those asked).
    tensions : {"default", "max-frequency"}
        The tension distribution
        (:func:`~dynstiff.analyses.optimal_tensions.tension_equilibrium`).
    uncertain : (dict, int, int, float), optional
        Stated uncertainties {name: Uncertain}, the Monte Carlo's sample size and seed and
        the confidence of the uncertain row
        (:func:`dynstiff.analyses.uncertainty.uncertain_row`, as the design checks give it).

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
           "platform_share": np.full((k, m), nan), "is_platform": np.zeros((k, m), bool),
           "first_platform_hz": np.full(k, nan), "band_margin": np.full(k, nan),
           "proximity_gap": np.full(k, nan), "uncertain_probability": np.full(k, nan),
           "uncertain_margin": np.full(k, nan), "passed": np.zeros((k, len(checks)), bool),
           "unknown": np.zeros((k, len(checks)), bool)}
    reasons = [""] * k
    prev = None
    for j, x in enumerate(poses):
        pose = as_pose(x)
        eq = error = None
        try:
            try:
                eq = tension_equilibrium(robot, pose, tensions, prev, rung, **model_options)
            except DynstiffError:
                # a far neighbour: start afresh (the default distribution's statics do so
                # themselves)
                if prev is None or tensions == "default":
                    raise
                eq = tension_equilibrium(robot, pose, tensions, None, rung, **model_options)
        except DynstiffError as exc:
            error = exc
        sag = None if eq is None else equilibrium_sag_ratios(robot, eq)
        rows = statics_rows(robot, eq, error, options, sag)
        pm = None
        if eq is not None:
            try:
                with warnings.catch_warnings():
                    # the closed form's robot-level bound is each pose's "cable model" row
                    warnings.filterwarnings("ignore", ROBOT_BOUND_MESSAGE, ClosedFormWarning)
                    model = build_model(eq, rung, **model_options)
                    modal, pm = modal_rows(model, options,
                                           lambda: damped_model(eq, damping, rung, model,
                                                                **model_options))
                rows += modal
            except (DynstiffError, ArithmeticError, np.linalg.LinAlgError) as exc:
                error, eq = exc, None
                rows = statics_rows(robot, None, exc, options)
        if uncertain is not None:
            items, n_samples, seed, confidence = uncertain
            row, res = uncertain_row(robot, pose, options, items, rung, model_options,
                                     n_samples, seed, confidence)
            rows.append(row)
            out["uncertain_probability"][j] = row["value"]
            if res is not None:
                out["uncertain_margin"][j] = res.quantile("band_margin", 1.0 - confidence)
        verdict = {r["check"]: r["verdict"] for r in rows}
        out["passed"][j] = [verdict[c] == "pass" for c in checks]
        out["unknown"][j] = [verdict[c] == "unknown" for c in checks]
        if eq is None:
            reasons[j] = f"{type(error).__name__}: {error}"
            continue
        prev = eq
        out["feasible"][j] = True
        out["residual"][j] = eq.residual
        out["tension"][j] = eq.tensions
        out["unstretched_length"][j] = eq.unstretched_lengths
        out["min_tension"][j] = eq.min_tensions
        out["max_tension"][j] = eq.max_tensions
        out["sag_ratio"][j] = sag
        if pm.modes is not None:
            r = min(m, len(pm.modes))
            out["freq"][j, :r] = pm.modes.freq_hz[:r]
            out["platform_share"][j, :r] = pm.modes.platform_share[:r]
            out["is_platform"][j, :r] = np.isin(np.arange(r), pm.index)
        out["first_platform_hz"][j] = pm.first_hz
        out["band_margin"][j] = _band_margin(pm, options)
        gap = _proximity_gap(pm)
        out["proximity_gap"][j] = gap if gap <= options.proximity_rtol else nan
        reasons[j] = "; ".join(f"{r['check']}: {r['detail']}" for r in rows
                               if r["verdict"] == "unknown")
    out["reason"] = reasons
    return out


class _Progress:
    """A tqdm bar on stderr: poses done, rate and time left (off when ``show`` is False or
    stderr is not a terminal)."""

    def __init__(self, total, show):
        self.bar = None
        if show:
            from tqdm import tqdm
            self.bar = tqdm(total=total, desc="workspace", unit="pose", file=sys.stderr,
                            disable=None, dynamic_ncols=True)

    def __call__(self, n):
        if self.bar is not None:
            self.bar.update(n)
            if self.bar.n >= self.bar.total:
                self.bar.close()


def _run(tasks, workers, client, progress, results, done):
    """Fill ``results[i]`` with ``evaluate_chunk(*tasks[i])`` where it is None, in task
    order: serially, on ``workers`` local processes or on a Dask client; ``done(i)`` is
    called as each task completes (the checkpoint saves it)."""
    todo = [i for i, r in enumerate(results) if r is None]
    if client is not None:
        from distributed import as_completed
        futures = [client.submit(evaluate_chunk, *tasks[i], pure=False) for i in todo]
        index = {f.key: i for i, f in zip(todo, futures)}
        try:
            for fut in as_completed(futures):
                i = index[fut.key]
                results[i] = fut.result()
                done(i)
                progress(len(tasks[i][1]))
        finally:
            client.cancel([f for f in futures if not f.done()])
        return results
    if workers is not None and workers > 1:
        from concurrent.futures import ProcessPoolExecutor, as_completed
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futures = {pool.submit(evaluate_chunk, *tasks[i]): i for i in todo}
            try:
                for fut in as_completed(futures):
                    i = futures[fut]
                    results[i] = fut.result()
                    done(i)
                    progress(len(tasks[i][1]))
            except BaseException:
                pool.shutdown(wait=True, cancel_futures=True)
                raise
        return results
    for i in todo:
        results[i] = evaluate_chunk(*tasks[i])
        done(i)
        progress(len(tasks[i][1]))
    return results


def workspace(robot: Robot, poses: "np.typing.ArrayLike | None" = None, *,
              box: "np.typing.ArrayLike | None" = None,
              step: "float | np.typing.ArrayLike | None" = None,
              orientations: "np.typing.ArrayLike | None" = None, parameter: str | None = None,
              values: "np.typing.ArrayLike | None" = None, n_modes: int = 20,
              band_hz: tuple[float, float] | None = None, margin: float = 0.05,
              proximity_rtol: float = 0.03, max_sag_ratio: float = 0.02,
              model_rtol: float = 1e-2, participation: float = PLATFORM_SHARE_THRESHOLD,
              frf_limit: float = FRF_AMPLIFICATION_LIMIT, damping: Damping = DEFAULT_DAMPING,
              model_band_hz: tuple[float, float] | None = None,
              max_modes: int = MAX_PLATFORM_MODES, rung: str = "dsm", chunk_size: int = 25,
              workers: int | None = None, client: object = None, progress: bool = False,
              tensions: str = "default", max_poses: int = MAX_POSES,
              checkpoint: "str | os.PathLike[str] | None" = None, resume: bool = False,
              uncertain: dict | None = None, n_samples: int = 200, seed: int = 0,
              confidence: float = 0.95, **model_options: object) -> "xarray.Dataset":
    """Map statics, modes and the design checks over a grid or a list of poses.

    Every pose gets the verdicts :func:`dynstiff.analyses.checks.design_checks` gives it
    with the same arguments (the rows of :mod:`dynstiff.analyses.verdicts`); a pose belongs
    to the dynamic workspace when every check asked passes ("unknown" fails).

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
        Modes stored per pose (dimension ``mode``), lowest first; the verdicts use every
        mode they need, whatever this number.
    band_hz, margin, proximity_rtol, max_sag_ratio, model_rtol, participation, frf_limit, \
damping, model_band_hz, max_modes
        The checks' bands and limits, as :func:`dynstiff.analyses.checks.design_checks`
        (``band_hz`` is the forbidden band; None: its two checks are not asked and not
        mapped).
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
    tensions : {"default", "max-frequency"}
        The tension distribution at every pose: the default (closest to t_min) or the one
        that maximises the first platform mode (:func:`dynstiff.optimal_tensions`,
        warm-started from the neighbour's optimum along a chunk).
    max_poses : int or None
        Refuse a map of more poses (times parameter values) than this, before any work
        (:data:`dynstiff.maps.guards.MAX_POSES`; None: no limit but the machine's memory,
        :func:`dynstiff.maps.guards.check_size`).
    checkpoint : str or path-like, optional
        A folder where each task's results are saved as it completes
        (:mod:`dynstiff.maps.store`); it is left in place (remove it once the map is saved).
    resume : bool
        Continue the run saved in ``checkpoint``: its tasks are read, not computed again,
        and the map equals that of an uninterrupted run bit for bit. Without ``resume``, a
        checkpoint that holds a run is refused.
    uncertain : dict, optional
        Stated uncertainties {parameter: Uncertain or "10%"}: every pose gets the design
        checks' uncertain row (the check ``"platform modes outside band, uncertain"``, the
        variables ``uncertain_probability`` and ``uncertain_margin``), the same Monte Carlo
        :func:`dynstiff.analyses.checks.design_checks` runs at that pose (theory.md §16.6):
        ``n_samples`` equilibria and mode searches per pose. Needs ``band_hz`` and the
        default tensions.
    n_samples, seed : int
        The Monte Carlo's Latin-hypercube sample and its seed.
    confidence : float
        Level in (0, 1) of the margin the uncertain row holds to ``margin``.
    **model_options
        Passed to :func:`dynstiff.models.ladder.build_model`; checked before any pose
        (:func:`dynstiff.maps.guards.check_model_options`).

    Returns
    -------
    xarray.Dataset
        Dimensions ``x, y, z[, orientation]`` (or ``pose``) ``[, parameter], mode, cable,
        check``; variables and attributes as :func:`dynstiff.maps.dataset.to_dataset`.
        Infeasible poses hold ``feasible = False``, their ``reason`` and NaN.

    Raises
    ------
    InvalidParameterError
        A bad argument, before the first pose.
    dynstiff.errors.Interrupted
        Ctrl-C (a KeyboardInterrupt) during the run: its message says how many poses are
        saved in ``checkpoint`` and how to resume.

    Examples
    --------
    >>> import dynstiff as ds
    >>> robot = ds.load_scene("cogiro").robot
    >>> maps = ds.workspace(robot, box=[-0.5, 0.5, 0, 0, 1.0, 1.0], step=0.5, n_modes=3)
    >>> dict(maps.sizes)
    {'x': 3, 'y': 1, 'z': 1, 'cable': 8, 'mode': 3, 'check': 5}
    >>> maps["feasible"].values.ravel().tolist()
    [True, True, True]
    """
    options = check_options(band_hz, margin, proximity_rtol, max_sag_ratio, model_rtol,
                            participation, frf_limit, model_band_hz, max_modes)
    X, layout, values = validate_arguments(robot, poses, box, step, orientations, parameter, values,
                                   n_modes, rung, chunk_size, workers, client, damping,
                                   options.max_modes, max_poses)
    if tensions not in TENSIONS:
        raise InvalidParameterError(f"tensions must be one of {TENSIONS}, got {tensions!r}")
    progress, resume = flag("progress", progress), flag("resume", resume)
    check_model_options(rung, model_options)
    from dynstiff.maps.dataset import to_dataset
    checks = tuple(c for c in CHECKS if options.forbidden_hz is not None
                   or c not in ("platform modes outside band", "platform receptance in band"))
    if uncertain is not None:
        uncertain = checked_uncertain(robot, X[0], uncertain, n_samples, seed, confidence,
                                      options, tensions)
        checks += (UNCERTAIN_CHECK,)
    model_options = modal_model_options(rung, options, model_options)
    robots = ([robot] if parameter is None
              else [robot_with(robot, parameter, v) for v in values])
    tasks = []
    for rob in robots:
        for s in range(0, len(X), chunk_size):
            tasks.append((rob, X[s:s + chunk_size], n_modes, options, rung, damping,
                          model_options, checks, tensions, uncertain))
    results, done = resumed(tasks, checkpoint, resume)
    total = len(X) * len(robots)
    if progress:
        sample = np.unique(np.linspace(0, len(X) - 1, min(5, len(X))).round().astype(int))
        evaluate_chunk(tasks[0][0], X[:1], *tasks[0][2:])       # warm up, then time a sample
        t0 = time.perf_counter()
        evaluate_chunk(tasks[0][0], X[sample], *tasks[0][2:])
        per_pose = (time.perf_counter() - t0) / len(sample)
        sys.stderr.write(estimate_text(total, per_pose, check_size(
            total, robot.n_cables, n_modes, len(checks), None), workers or 1) + "\n")
    t0 = time.perf_counter()
    bar = _Progress(total, progress)
    if any(r is not None for r in results):
        bar(sum(len(tasks[i][1]) for i, r in enumerate(results) if r is not None))
    try:
        results = _run(tasks, workers, client, bar, results, done)
    except KeyboardInterrupt:
        saved = sum(len(tasks[i][1]) for i, r in enumerate(results) if r is not None)
        how = (f"saved in {checkpoint}; run again with resume=True (dynstiff workspace "
               f"--resume) to continue" if checkpoint is not None
               else "not saved (give checkpoint= to keep them)")
        raise Interrupted(f"workspace interrupted: {saved} of {total} poses {how}",
                          saved=saved, total=total) from None
    settings = {"checks": checks, "n_modes": n_modes, "band_hz": options.forbidden_hz,
                "margin": options.margin, "proximity_rtol": options.proximity_rtol,
                "max_sag_ratio": options.max_sag_ratio, "model_rtol": options.model_rtol,
                "model_band_hz": options.model_band_hz,
                "participation": options.participation, "frf_limit": options.frf_limit,
                "damping": damping.text(), "max_modes": options.max_modes, "rung": rung,
                "chunk_size": chunk_size, "tensions": tensions,
                "uncertain": ("none" if uncertain is None else "; ".join(
                    f"{n} {u.text()}" for n, u in uncertain[0].items())),
                "n_samples": n_samples if uncertain else 0, "seed": seed,
                "confidence": confidence,
                "wall_time_s": time.perf_counter() - t0,
                "engine": ("dask" if client is not None else
                           f"{workers} processes" if workers and workers > 1 else "serial")}
    return to_dataset(robot, X, layout, parameter, values, results, settings)
