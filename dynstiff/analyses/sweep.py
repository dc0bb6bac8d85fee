"""Modes along a path of poses or over a parameter (theory.md §6): the platform modes found
at every step (:mod:`dynstiff.analyses.platform_modes`), tracked from step to step by the
modal assurance criterion of their platform shapes, the other modes listed, infeasible steps
recorded; the veering table and diagram.
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff._validate import positive_scalar, real_array
from dynstiff.analyses.modes import modes
from dynstiff.analyses.platform_modes import find_platform_modes
from dynstiff.errors import ConvergenceError, DynstiffError, InvalidParameterError
from dynstiff.models.ladder import build_model
from dynstiff.robot.equilibrium import Equilibrium
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from typing import Any

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.results import ModalResult
    from dynstiff.robot.pose import Pose

__all__ = ["SweepResult", "sweep"]


#: Track id given to modes that are not tracked (local modes) in :class:`SweepResult`.
UNTRACKED = -1


# ------------------------------------------------------------------------ sweep
@dataclass(frozen=True)
class SweepResult:
    """Modes along a path of poses or a parameter, with tracked platform modes.

    One row per mode and step (a tidy table); the arrays below are its columns, all of shape
    (n_rows,).

    Attributes
    ----------
    parameter : str
        Name (with unit) of the swept quantity, e.g. ``"arc length [m]"``.
    values : ndarray, shape (n_steps,)
        Value of the swept quantity at each step (arc length along the path [m] for a sweep
        of poses, unless values were given).
    modal : tuple of ModalResult
        The modes at each step, length n_steps.
    equilibria : tuple of Equilibrium
        The static equilibrium at each step, length n_steps.
    step : ndarray of int
        Step index, 0 .. n_steps - 1.
    value : ndarray of float
        ``values[step]``.
    mode : ndarray of int
        Mode number at its step, 1-based (as in :meth:`ModalResult.to_frame`).
    track : ndarray of int
        Track id of a platform mode, 0, 1, ... numbered by frequency at the track's first
        step; the same id at different steps is the same physical mode (matched by MAC),
        and no two modes of a step share a track. The other modes hold :data:`UNTRACKED`
        (-1).
    freq_hz : ndarray of float
        Natural frequency [Hz].
    kind : ndarray of str
        "global", "mixed" or "local" (platform share, :func:`dynstiff.results.mode_kinds`).
    cable_energy_fraction : ndarray of float
        Cable kinetic energy / total kinetic energy [-].
    failures : tuple of (int, float, str)
        Steps recorded as infeasible (``on_error="record"``): step, value, error message;
        their row has kind "infeasible" and NaN frequency, ``modal`` and ``equilibria`` None.
    massless_freq_hz : ndarray of float
        Frequency of the matching massless-cable mode [Hz] (NaN for local modes).

    Examples
    --------
    >>> import dynstiff as ds
    >>> robot = ds.load_scene("cogiro").robot
    >>> s = ds.sweep(robot, poses=[[0, 0, 1.0], [0.5, 0, 1.0]], n_modes=4)
    >>> s.parameter, s.values.tolist(), s.n_steps, s.n_tracks
    ('arc length [m]', [0.0, 0.5], 2, 6)
    """

    parameter: str
    values: np.ndarray
    modal: tuple
    equilibria: tuple
    step: np.ndarray
    value: np.ndarray
    mode: np.ndarray
    track: np.ndarray
    freq_hz: np.ndarray
    kind: np.ndarray
    cable_energy_fraction: np.ndarray
    massless_freq_hz: np.ndarray
    failures: tuple = ()

    def __len__(self) -> int:
        return len(self.step)

    def __repr__(self) -> str:
        v = self.values
        return (f"SweepResult({self.parameter} {v.min():.4g}..{v.max():.4g}, "
                f"{counted(self.n_steps, 'step')}, {counted(len(self), 'mode')}, "
                f"{counted(self.n_tracks, 'platform-mode track')})")

    def plot(self, ax: Axes | None = None, show_local: bool = True) -> Figure:
        """Veering diagram: :func:`dynstiff.plot.plot_veering`. Returns the Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> s = ds.sweep(ds.load_scene("cogiro").robot, [[0, 0, 1.0], [0.5, 0, 1.0]], n_modes=4)
        >>> import matplotlib.pyplot as plt
        >>> plt.close(s.plot())
        """
        from dynstiff.plot import plot_veering
        return plot_veering(self, ax=ax, show_local=show_local)

    @property
    def n_steps(self) -> int:
        """Number of steps."""
        return len(self.values)

    @property
    def n_tracks(self) -> int:
        """Number of platform-mode tracks."""
        t = self.track[self.track != UNTRACKED]
        return int(t.max()) + 1 if t.size else 0

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per mode and step.

        Columns ``step``, ``value``, ``mode``, ``track`` (nullable integer, <NA> for the
        modes that are not platform modes), ``freq [Hz]``, ``kind``, ``cable energy
        fraction [-]``, ``massless freq [Hz]``.
        ``df.attrs["parameter"]`` names the quantity in ``value``.

        Examples
        --------
        >>> import dynstiff as ds
        >>> s = ds.sweep(ds.load_scene("cogiro").robot, [[0, 0, 1.0], [0.5, 0, 1.0]], n_modes=4)
        >>> len(s.to_frame())
        14
        """
        import pandas as pd
        track = pd.array(self.track, dtype="Int64")
        track[self.track == UNTRACKED] = pd.NA
        df = pd.DataFrame({
            "step": self.step,
            "value": self.value,
            "mode": self.mode,
            "track": track,
            "freq [Hz]": self.freq_hz,
            "kind": self.kind,
            "cable energy fraction [-]": self.cable_energy_fraction,
            "massless freq [Hz]": self.massless_freq_hz,
        })
        df.attrs["parameter"] = self.parameter
        return df

    def veering_table(self) -> Any:
        """Frequencies of the platform-mode tracks, one row per step and one column per
        track.

        Returns
        -------
        pandas.DataFrame, shape (n_steps, n_tracks)
            Frequencies [Hz]; index ``step`` (the abscissa is ``values[step]``), columns the
            track ids. NaN where a track has no platform mode at a step.

        Examples
        --------
        >>> import dynstiff as ds
        >>> s = ds.sweep(ds.load_scene("cogiro").robot, [[0, 0, 1.0], [0.5, 0, 1.0]], n_modes=4)
        >>> s.veering_table().shape
        (2, 6)
        """
        import pandas as pd
        table = np.full((self.n_steps, self.n_tracks), np.nan)
        sel = self.track != UNTRACKED
        table[self.step[sel], self.track[sel]] = self.freq_hz[sel]
        return pd.DataFrame(table, index=pd.RangeIndex(self.n_steps, name="step"),
                            columns=pd.RangeIndex(self.n_tracks, name="track"))


def _mac(X: NDArray[np.float64], Mx: NDArray[np.float64], Y: NDArray[np.float64],
         My: NDArray[np.float64]) -> NDArray[np.float64]:
    """Mass-weighted MAC between the rows of X (n, 6) and Y (k, 6), shape (n, k) [-].

    Uses the mean mass matrix of the two steps, M = (Mx + My)/2 (M_p changes with the pose).
    MAC (Allemang & Brown 1982, Proc. 1st IMAC; cited from memory):
    (x^T M y)^2 / ((x^T M x)(y^T M y)).
    """
    M = 0.5 * (Mx + My)
    xy = X @ M @ Y.T
    xx = np.einsum("ij,jk,ik->i", X, M, X)
    yy = np.einsum("ij,jk,ik->i", Y, M, Y)
    return xy**2 / np.outer(xx, yy)


def _assign(candidates: list[tuple[int, NDArray[np.float64], NDArray[np.float64]]],
            X: NDArray[np.float64], M: NDArray[np.float64], mac_min: float) -> dict[int, int]:
    """Match rows of X to the tracks ``candidates`` (list of (id, shape, M)) by largest total
    MAC (Hungarian algorithm); returns {row: track id} for pairs with MAC >= mac_min."""
    if not candidates or X.shape[0] == 0:
        return {}
    from scipy.optimize import linear_sum_assignment
    mac = np.array([_mac(s[None, :], Ms, X, M)[0] for _, s, Ms in candidates])  # (n_t, n_x)
    rows, cols = linear_sum_assignment(-mac)
    return {int(c): candidates[r][0] for r, c in zip(rows, cols) if mac[r, c] >= mac_min}


def _check_sweep_args(
        robot: str | Robot | None,
        poses: int | list[list[float] | tuple[float, float, float] | Pose] | None,
        parameter: int | str | None, values: NDArray[np.float64] | list[float | str] | None,
        build: int | Callable[..., Any] | None, n_modes: float | None, fmax_hz: float | None,
        progress: int | Callable[..., Any] | None, mac_min: float,
) -> tuple[list[Pose] | None, NDArray[np.float64], str, float | None, float]:
    if poses is None and build is None:
        raise InvalidParameterError(
            "give poses= (a path of poses for robot) or build= (a callable value -> "
            "Equilibrium) with values=; got neither")
    if poses is not None and build is not None:
        raise InvalidParameterError("give poses= or build=, not both")
    if n_modes is None and fmax_hz is None:
        raise InvalidParameterError("give n_modes (number of modes per step) or fmax_hz "
                                    "(band top [Hz]), got neither")
    if n_modes is not None and (isinstance(n_modes, bool) or not isinstance(n_modes, Integral)
                                or n_modes < 1):
        raise InvalidParameterError(f"n_modes must be an integer >= 1, got {n_modes!r}")
    if fmax_hz is not None:
        fmax_hz = positive_scalar("fmax_hz", fmax_hz)
    if progress is not None and not callable(progress):
        raise InvalidParameterError(
            f"progress must be a callable (step, n_steps) or None, got {progress!r}")
    mac_min = positive_scalar("mac_min", mac_min)
    if mac_min > 1:
        raise InvalidParameterError(f"mac_min must be in (0, 1], got {mac_min!r}")
    if parameter is not None and not isinstance(parameter, str):
        raise InvalidParameterError(f"parameter must be a str (name [unit]), got {parameter!r}")
    if values is not None:
        values = real_array("values", values)
        if values.ndim != 1 or values.size == 0:
            raise InvalidParameterError(
                f"values must be a non-empty 1-D sequence, got shape {values.shape}")
        if not np.all(np.isfinite(values)):
            raise InvalidParameterError(f"values must be finite, got {values.tolist()}")
    if build is not None:
        if not callable(build):
            raise InvalidParameterError(
                f"build must be a callable value -> Equilibrium, got {build!r}")
        if values is None:
            raise InvalidParameterError("build= needs values= (the parameter values to sweep)")
        return None, values, parameter or "value", fmax_hz, mac_min
    if not isinstance(robot, Robot):
        raise InvalidParameterError(
            f"robot must be a dynstiff.Robot for a sweep of poses, got {type(robot).__name__}")
    try:
        poses = [as_pose(p) for p in poses]
    except TypeError:
        raise InvalidParameterError(
            f"poses must be a sequence of poses, got {type(poses).__name__}") from None
    if not poses:
        raise InvalidParameterError("poses must hold at least one pose, got an empty sequence")
    if values is None:
        P = np.array([p.position for p in poses])
        values = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(P, axis=0), axis=1))])
        parameter = parameter or "arc length [m]"
    elif values.size != len(poses):
        raise InvalidParameterError(
            f"values must give one value per pose ({len(poses)}), got {values.size}")
    return poses, values, parameter or "value", fmax_hz, mac_min


def sweep(robot: Robot | None,
          poses: Sequence[ArrayLike | Pose] | None = None,
          parameter: str | None = None,
          values: ArrayLike | None = None,
          build: Callable[[Any], Equilibrium] | None = None, n_modes: int | None = None,
          fmax_hz: float | None = None, progress: Callable[..., Any] | None = None,
          mac_min: float = 0.5, rung: str = "dsm", on_error: str = "raise",
          **model_options: Any) -> SweepResult:
    """Modes along a path of poses or a parameter, global modes tracked from step to step.

    Two ways to call it:

    (a) ``sweep(robot, poses=[...], ...)``: the robot at each pose of the path (inverse
        statics, :meth:`Robot.equilibrium`); ``value`` is the arc length of the reference
        point P along the path [m] (rotations not counted), or ``values`` if given.
    (b) ``sweep(None, build=f, values=[...], parameter="E [Pa]", ...)``: ``f(value)`` returns
        the :class:`Equilibrium` for each value (Young's modulus, tension level, platform
        mass, ...); ``robot`` is not used.

    At each step the platform modes are found by
    :func:`dynstiff.analyses.platform_modes.find_platform_modes` (whatever ``n_modes`` asks:
    a track is never lost because its mode lies above the modes listed), of
    ``build_model(eq, rung, **model_options)``; the step lists the modes asked (``n_modes``
    and / or ``fmax_hz``) and every platform mode. The platform modes are tracked: those of
    a step are matched to the tracks of the previous step, then to older tracks missing at
    the previous step, by the largest total mass-weighted MAC of the platform shapes
    (Hungarian assignment, one mode per track), a pair counting only if MAC >= ``mac_min``;
    the rest start new tracks; the tracks are numbered by their frequency at their first
    step. Tracking by shape follows a mode through a veering, so in a veering diagram the
    two tracks cross while the frequencies stay apart. The other modes are listed and not
    tracked.

    Parameters
    ----------
    robot : Robot or None
        The robot for (a); not used (may be None) for (b).
    poses : sequence of Pose, or of 3 or 6 numbers, optional
        Path (a): positions [m] and rotation vectors [rad] of the platform.
    parameter : str, optional
        Name with unit of the swept quantity, e.g. ``"E [Pa]"`` (default ``"arc length [m]"``
        for (a), ``"value"`` for (b)).
    values : array_like, shape (n_steps,), optional
        Parameter values for (b) (required); for (a), optional abscissa replacing the arc
        length, one per pose.
    build : callable, optional
        ``build(value) -> Equilibrium`` for (b).
    n_modes : int, optional
        Number of lowest modes per step.
    fmax_hz : float, optional
        Band top [Hz]: all modes below it (the first ``n_modes`` of them if both are given).
        Give ``n_modes`` or ``fmax_hz``.
    progress : callable, optional
        ``progress(done, n_steps)``, called after each step (e.g. a progress bar).
    mac_min : float
        Least MAC, in (0, 1], for a global mode to continue a track (default 0.5).
    rung : str
        Model of every step, one of :data:`dynstiff.models.ladder.RUNGS` (default "dsm").
    on_error : {"raise", "record"}
        A step whose statics or modes fail (an infeasible pose, a slack cable): "raise" the
        error (with a note naming the step), or "record" it as one row of kind
        "infeasible" (frequency NaN, the message in ``SweepResult.failures``) and go on.
    **model_options
        Passed to :func:`dynstiff.models.ladder.build_model` (e.g. ``segments`` of "lumped").

    Returns
    -------
    SweepResult
        Tidy table (``.to_frame()``) and ``.veering_table()`` of the global tracks.

    Raises
    ------
    InvalidParameterError
        Neither or both of ``poses`` and ``build``; ``build`` without ``values``; empty
        ``poses`` or ``values``; neither ``n_modes`` nor ``fmax_hz``; ``build`` not returning
        an Equilibrium. The message names the argument.
    SlackCableError, ConvergenceError
        From the statics at a step (the note on the exception names the step).

    Examples
    --------
    >>> import dynstiff as ds
    >>> robot = ds.load_scene("cogiro").robot
    >>> s = ds.sweep(robot, poses=[[0, 0, 1.0], [0.5, 0, 1.0]], n_modes=4)
    >>> s.n_steps, s.n_tracks
    (2, 6)
    >>> print(s.veering_table().round(3))
    track      0      1      2      3      4      5
    step
    0      2.206  2.359  2.991  3.869  4.972  5.854
    1      2.208  2.369  2.985  3.949  4.971  5.834
    """
    if on_error not in ("raise", "record"):
        raise InvalidParameterError(f"on_error must be 'raise' or 'record', got {on_error!r}")
    failures = []
    poses, values, parameter, fmax_hz, mac_min = _check_sweep_args(
        robot, poses, parameter, values, build, n_modes, fmax_hz, progress, mac_min)
    n_steps = values.size
    tracks = {}                     # id -> (shape (6,), M_p (6, 6), last step seen)
    first_hz = {}                   # id -> frequency at its first step [Hz]
    rows = {k: [] for k in ("step", "value", "mode", "track", "freq", "kind", "frac", "f0")}
    modal, equilibria = [], []
    for k in range(n_steps):
        try:
            if build is not None:
                eq = build(values[k])
                if not isinstance(eq, Equilibrium):
                    raise InvalidParameterError(
                        f"build must return an Equilibrium, got {type(eq).__name__} for "
                        f"value {values[k]!r}")
            else:
                eq = robot.equilibrium(pose=poses[k])
            model = build_model(eq, rung, **model_options)
            pm = find_platform_modes(model)
            res, platform = pm.modes, pm.index
            if not pm.complete:
                raise ConvergenceError(f"the platform modes were not all found: {pm.reason}")
            if (n_modes is not None and n_modes > len(res)) or (
                    fmax_hz is not None and fmax_hz > pm.searched_hz):
                res = modes(model, n_modes=n_modes, fmax_hz=fmax_hz)   # the lowest: a superset
            keep = _listed(res, n_modes, fmax_hz, platform)
            res, platform = _subset(res, keep), np.searchsorted(keep, platform)
        except DynstiffError as exc:
            if on_error == "raise":
                exc.add_note(f"in sweep step {k} ({parameter} = {values[k]:g})")
                raise
            failures.append((k, float(values[k]), f"{type(exc).__name__}: {exc}"))
            for key, v in zip(rows, (k, values[k], 0, UNTRACKED, np.nan, "infeasible",
                                     np.nan, np.nan)):
                rows[key].append(np.array([v], dtype=object if key == "kind" else None))
            modal.append(None)
            equilibria.append(None)
            if progress is not None:
                progress(k + 1, n_steps)
            continue
        M = np.zeros((6, 6))                     # M_p on all six DOFs (held ones 0)
        M[np.ix_(model.free_index, model.free_index)] = model.platform_mass
        ig = platform
        X = res.platform_shapes[ig]
        # previous step's tracks first, then older dormant ones, then new tracks
        recent = [(t, s, Ms) for t, (s, Ms, last) in tracks.items() if last == k - 1]
        match = _assign(recent, X, M, mac_min)
        left = np.array([j for j in range(ig.size) if j not in match], dtype=int)
        dormant = [(t, s, Ms) for t, (s, Ms, last) in tracks.items() if last < k - 1]
        match.update({int(left[j]): t for j, t in
                      _assign(dormant, X[left], M, mac_min).items()})
        track = np.full(len(res), UNTRACKED, dtype=int)
        for j in range(ig.size):
            t = match.get(j)
            if t is None:
                t = len(tracks)
                first_hz[t] = res.freq_hz[ig[j]]
            track[ig[j]] = t
            tracks[t] = (X[j], M, k)
        n = len(res)
        rows["step"].append(np.full(n, k))
        rows["value"].append(np.full(n, values[k]))
        rows["mode"].append(np.arange(1, n + 1))
        rows["track"].append(track)
        rows["freq"].append(res.freq_hz)
        rows["kind"].append(np.asarray(res.kind, dtype=object).reshape(n))
        rows["frac"].append(res.cable_energy_fraction)
        rows["f0"].append(res.massless_freq_hz)
        modal.append(res)
        equilibria.append(eq)
        if progress is not None:
            progress(k + 1, n_steps)
    col = {key: np.concatenate(v) for key, v in rows.items()}
    # tracks numbered by frequency at their first step
    order = sorted(first_hz, key=lambda t: (first_hz[t], t))
    renumber = np.full(len(order) + 1, UNTRACKED)
    renumber[order] = np.arange(len(order))
    col["track"] = renumber[col["track"].astype(int)]
    return SweepResult(parameter=parameter, values=values, modal=tuple(modal),
                       equilibria=tuple(equilibria), step=col["step"].astype(int),
                       value=col["value"].astype(float), mode=col["mode"].astype(int),
                       track=col["track"].astype(int), freq_hz=col["freq"].astype(float),
                       kind=col["kind"].astype(str), cable_energy_fraction=col["frac"],
                       massless_freq_hz=col["f0"].astype(float), failures=tuple(failures))


def _listed(res: ModalResult, n_modes: int | None, fmax_hz: float | None,
            platform: NDArray[np.int64]) -> NDArray[np.int64]:
    """Indices of the modes a step lists: those asked (the lowest ``n_modes`` and / or all
    below ``fmax_hz``) and every platform mode."""
    f = np.asarray(res.freq_hz)
    asked = np.ones(f.size, bool)
    if n_modes is not None:
        asked &= np.arange(f.size) < n_modes
    if fmax_hz is not None:
        asked &= f < fmax_hz
    asked[platform] = True
    return np.flatnonzero(asked)


def _subset(res: ModalResult, keep: NDArray[np.int64]) -> ModalResult:
    """The modes ``keep`` (indices) of a ModalResult."""
    from dataclasses import replace
    return replace(res, freq_hz=res.freq_hz[keep], platform_shapes=res.platform_shapes[keep],
                   cable_energy_fraction=res.cable_energy_fraction[keep],
                   cable_energy=res.cable_energy[keep], kind=tuple(np.asarray(res.kind)[keep]),
                   massless_freq_hz=res.massless_freq_hz[keep])
