"""Uncertainty of the natural frequencies and of the verdicts (theory.md §16.6).

Stated distributions of parameters (:class:`Uncertain`: normal or uniform, relative or
absolute, independent) are propagated to the frequencies two ways, side by side on the same
seeded Latin-hypercube sample (scipy.stats.qmc):

* first order: the linearised model f(p0) + sum_j (df/dp_j)(p_j - p0_j), the
  eigenfrequency sensitivities of theory.md §16.1 (one sensitivity solve), evaluated at
  the samples; its standard deviation is sqrt(sum_j (df/dp_j sigma_j)^2);
* Monte Carlo: the full model (statics, model, platform modes) at every sample, serially,
  on local processes or on a Dask cluster (as the workspace maps).

The quantities are the first modes by index, the first platform mode
(:attr:`dynstiff.analyses.platform_modes.PlatformModes.first_hz`) and, with a forbidden band,
the band margin of the modes held to it (theory.md §13.2). A sample whose statics fail is
recorded (``failed``), its values NaN.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import count, flag, positive_scalar
from dynstiff.analyses.eigen import eigenfrequencies
from dynstiff.analyses.optimal_tensions import band_margin
from dynstiff.analyses.participation import PLATFORM_SHARE_THRESHOLD
from dynstiff.analyses.platform_modes import find_platform_modes
from dynstiff.analyses.sensitivity import sensitivities_at, whole_clusters
from dynstiff.analyses.sensitivity_parameters import equilibrium_with, expand_parameters
from dynstiff.analyses.uncertainty_result import UncertaintyResult
from dynstiff.errors import DynstiffError, InvalidParameterError
from dynstiff.models.ladder import build_model
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.analyses.platform_modes import PlatformModes
    from dynstiff.analyses.sensitivity_parameters import Parameter
    from dynstiff.analyses.verdicts import CheckOptions
    from dynstiff.models.base import PlatformModel
    from dynstiff.models.dsm import FrequencyModel
    from dynstiff.robot.pose import Pose
    from dynstiff.scenes.loader import Scene

__all__ = ["UNCERTAIN_CHECK", "Uncertain", "UncertaintyResult", "propagate_uncertainty",
           "uncertain_items", "uncertain_parameters", "uncertain_row"]

_DISTRIBUTIONS = ("normal", "uniform")


@dataclass(frozen=True)
class Uncertain:
    """A parameter's stated uncertainty.

    Parameters
    ----------
    scale : float
        Standard deviation (normal) or half-width (uniform), > 0; a fraction of the value
        when ``relative`` (0.1 for 10 %), else in the parameter's unit.
    distribution : {"normal", "uniform"}
    relative : bool

    Examples
    --------
    >>> Uncertain.parse("10%:uniform")
    Uncertain(scale=0.1, distribution='uniform', relative=True)
    >>> Uncertain.parse("0.002").std(1.0)
    0.002
    """

    scale: float
    distribution: str = "normal"
    relative: bool = True

    def __post_init__(self) -> None:
        if self.distribution not in _DISTRIBUTIONS:
            raise InvalidParameterError(f"distribution must be one of {_DISTRIBUTIONS}, got "
                                        f"{self.distribution!r}")
        try:
            s = positive_scalar("scale", self.scale)
        except InvalidParameterError:
            raise InvalidParameterError(
                f"scale must be finite and > 0, got {self.scale!r}") from None
        object.__setattr__(self, "scale", s)
        object.__setattr__(self, "relative", flag("relative", self.relative))

    @classmethod
    def parse(cls, text: str) -> Uncertain:
        """From ``"VALUE[%][:normal|:uniform]"``: a percentage is relative, a plain number
        absolute; normal (standard deviation) unless ``:uniform`` (half-width)."""
        m = re.fullmatch(r"\s*([0-9.eE+-]+)\s*(%?)\s*(?::\s*(normal|uniform))?\s*", str(text))
        if not m:
            raise InvalidParameterError(
                f"uncertainty {text!r}: give VALUE[%][:normal|:uniform], e.g. 10% or "
                f"0.002:uniform")
        try:
            v = float(m.group(1))
        except ValueError:
            raise InvalidParameterError(f"uncertainty {text!r}: {m.group(1)!r} is not a "
                                        f"number") from None
        rel = m.group(2) == "%"
        return cls(v / 100 if rel else v, m.group(3) or "normal", rel)

    def std(self, value: float) -> float:
        """Standard deviation in the parameter's unit at ``value``."""
        s = self.scale * (abs(value) if self.relative else 1.0)
        return s / np.sqrt(3.0) if self.distribution == "uniform" else s

    def values(self, value: float, u: ArrayLike) -> NDArray[np.float64]:
        """Parameter values at the uniform [0, 1] sample ``u`` (inverse CDF)."""
        s = self.scale * (abs(value) if self.relative else 1.0)
        if self.distribution == "uniform":
            return value + s * (2.0 * np.asarray(u) - 1.0)
        from scipy.stats import norm
        return value + s * norm.ppf(u)

    def text(self) -> str:
        """E.g. ``"+-10 % (uniform)"``."""
        v = f"{100 * self.scale:g} %" if self.relative else f"{self.scale:g}"
        return f"{'+-' if self.distribution == 'uniform' else 'sigma '}{v} ({self.distribution})"


def _uncertain_items(uncertain: dict[str, str]) -> dict[str, Uncertain]:
    if not isinstance(uncertain, dict) or not uncertain:
        raise InvalidParameterError(f"uncertain must be a non-empty dict {{name: Uncertain "
                                    f"or '10%'}}, got {uncertain!r}")
    out = {}
    for name, u in uncertain.items():
        if isinstance(u, Uncertain):
            out[name] = u
        elif isinstance(u, str):
            out[name] = Uncertain.parse(u)
        else:
            raise InvalidParameterError(f"uncertain[{name!r}] must be an Uncertain or a "
                                        f"string like '10%', got {u!r}")
    return out


def uncertain_parameters(names: list[str], robot: Robot, pose: Pose,
                         tension_reference: NDArray[np.float64] | float | None = None,
                         ) -> list[Parameter]:
    """The :class:`~dynstiff.analyses.sensitivity_parameters.Parameter` of each uncertain
    name at ``pose``, refusing a loss factor (it moves no undamped frequency) and wildcards
    (each parameter needs its own distribution)."""
    params = expand_parameters(names, robot, pose, "pose", tension_reference)
    if any(p.kind == "damping" for p in params):
        raise InvalidParameterError("uncertain: a loss factor moves no undamped frequency")
    if len(params) != len(names):
        raise InvalidParameterError("uncertain: give each parameter by its own name (no "
                                    "wildcards: each needs its distribution)")
    return params


def uncertain_items(uncertain: dict[str, str]) -> dict[str, Uncertain]:
    """{name: Uncertain} of ``uncertain`` ({name: Uncertain or "10%"}), or
    InvalidParameterError naming the entry."""
    return _uncertain_items(uncertain)


def evaluate_samples(robot: Robot, pose: Pose, names: list[str], values: NDArray[np.float64],
                     rung: str, model_options: dict[Any, Any], n_modes: int,
                     band: tuple[float, float] | None, participation: float,
                     tension_reference: ArrayLike | None = None) -> NDArray[np.float64]:
    """The quantities of :class:`UncertaintyResult` with the full model at every row of
    ``values`` (n, p): (n, q) with NaN where the statics or the modes failed.

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> q = evaluate_samples(sc.robot, sc.pose, ["EA"], [[139486.7]], "dsm", {}, 1, None,
    ...                      0.05)
    >>> [round(float(v), 4) for v in q[0]]          # f1, first platform mode [Hz]
    [2.2061, 2.2061]
    """
    q = n_modes + 1 + (band is not None)
    out = np.full((len(values), q), np.nan)
    cover = band[1] * 1.05 if band is not None else 0.0
    for k, row in enumerate(values):
        try:
            eq = equilibrium_with(robot, pose, names, row, "pose", tension_reference)
            model = build_model(eq, rung, **model_options)
            pm = find_platform_modes(model, cover)
            f = _first_modes(model, pm, n_modes)[:n_modes]
        except (DynstiffError, ArithmeticError, np.linalg.LinAlgError):
            continue
        out[k, :f.size] = f
        out[k, n_modes] = pm.first_hz
        if band is not None:
            out[k, n_modes + 1] = band_margin(pm, band, participation)
    return out


def _first_modes(model: PlatformModel, pm: PlatformModes, n_modes: int) -> NDArray[np.float64]:
    """The frequencies of ``pm`` [Hz], continued by the mode search to at least ``n_modes``
    (the platform search stops once every free DOF's modes are found)."""
    f = np.asarray(pm.modes.freq_hz)
    if f.size >= n_modes:
        return f
    return np.concatenate([f, eigenfrequencies(model, n_modes=n_modes)[f.size:]])


def _run(tasks: list[tuple[Any | None, ...]], workers: int | None,
         client: Any) -> list[NDArray[np.float64]]:
    if client is not None:
        return client.gather([client.submit(evaluate_samples, *t, pure=False) for t in tasks])
    if workers is not None and workers > 1:
        from concurrent.futures import ProcessPoolExecutor
        with ProcessPoolExecutor(max_workers=workers) as pool:
            return list(pool.map(evaluate_samples, *zip(*tasks)))
    return [evaluate_samples(*t) for t in tasks]


def propagate_uncertainty(scene_or_model: Scene | Robot | PlatformModel,
                          pose: ArrayLike | Pose | None = None,
                          uncertain: dict[str, Uncertain | str] | None = None,
                          n_modes: int = 6,
                          band_hz: tuple[float, float] | None = None,
                          participation: float = PLATFORM_SHARE_THRESHOLD, n_samples: int = 200,
                          seed: int = 0, method: str = "both", rung: str = "dsm",
                          workers: int | None = None, client: Any | None = None,
                          chunk_size: int = 25, tension_reference: ArrayLike | None = None,
                          **model_options: Any) -> UncertaintyResult:
    """Distributions of the frequencies from stated parameter distributions (module notes,
    theory.md §16.6).

    Parameters
    ----------
    scene_or_model : Scene, Robot or model
        A scene (its robot and pose), a robot (give ``pose``) or a model of the ladder
        (its robot, pose and rung; ``rung`` and ``model_options`` are then its own).
    pose : Pose or array_like, optional
    uncertain : dict
        {parameter name (:mod:`dynstiff.analyses.sensitivity_parameters`): Uncertain or a
        string such as ``"10%"``, ``"10%:uniform"``, ``"0.002"``}; independent.
    n_modes : int
        Modes by index in the quantities.
    band_hz : (float, float), optional
        Forbidden band [Hz]: adds the band margin.
    participation : float
        Platform share from which a mode is held to the band [-].
    n_samples : int
        Latin-hypercube samples.
    seed : int
        Seed of the sample (the results are reproducible from it).
    method : {"both", "first-order"}
        "first-order": no Monte Carlo.
    rung : str
    workers, client, chunk_size
        The Monte Carlo's engine (as :func:`dynstiff.workspace`): local processes or a Dask
        client, samples in chunks.
    tension_reference : float or ndarray, optional
        The distribution's reference [N] (default the robot's).
    **model_options
        Passed to :func:`dynstiff.build_model`.

    Returns
    -------
    UncertaintyResult

    Examples
    --------
    >>> import dynstiff as ds
    >>> res = ds.propagate_uncertainty(ds.load_scene("cogiro"), uncertain={"EA": "1%"},
    ...                                n_modes=1, n_samples=16, method="first-order")
    >>> round(float(res.std_first_order[0]), 4)            # Hz, for sigma(EA) = 1 %
    0.0108
    """
    robot = getattr(scene_or_model, "robot", scene_or_model)
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"scene_or_model must be a Scene, a Robot or a model, got "
                                    f"{type(scene_or_model).__name__}")
    if hasattr(scene_or_model, "dynamic_stiffness"):
        pose, rung = scene_or_model.pose, scene_or_model.rung
        model_options = {**_own_options(scene_or_model), **model_options}
    elif pose is None:
        pose = getattr(scene_or_model, "pose", None)
    if pose is None:
        raise InvalidParameterError("propagate_uncertainty needs a pose: give pose= or a "
                                    "scene with a [pose]")
    pose = as_pose(pose)
    items = _uncertain_items(uncertain)
    for name, v in (("n_modes", n_modes), ("n_samples", n_samples),
                    ("chunk_size", chunk_size)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
            raise InvalidParameterError(f"{name} must be an integer >= 1, got {v!r}")
    seed = count("seed", seed, least=0)
    if workers is not None:
        workers = count("workers", workers)
    participation = positive_scalar("participation", participation)
    if not participation <= 1:
        raise InvalidParameterError(
            f"participation must be in (0, 1] (a platform share), got {participation!r}")
    if method not in ("both", "first-order"):
        raise InvalidParameterError(f"method must be 'both' or 'first-order', got "
                                    f"{method!r}")
    if band_hz is not None:
        band_hz = tuple(float(b) for b in band_hz)
        if len(band_hz) != 2 or not 0 <= band_hz[0] < band_hz[1]:
            raise InvalidParameterError(f"band_hz must be (lo, hi), 0 <= lo < hi [Hz], got "
                                        f"{band_hz!r}")
    names = list(items)
    params = uncertain_parameters(names, robot, pose, tension_reference)
    eq = robot.equilibrium(pose=pose, tension_reference=tension_reference)
    model = build_model(eq, rung, **model_options).undamped()
    pm = find_platform_modes(model, band_hz[1] * 1.05 if band_hz else 0.0)
    f = _first_modes(model, pm, n_modes)
    top = max(n_modes, int(pm.index[0]) + 1 if pm.index.size else 1)
    sens = sensitivities_at(model, f[:whole_clusters(f, top)], params, "pose",
                            tension_reference)
    nominal, gradient = [f[:n_modes]], [sens.derivative[:n_modes]]
    quantities = [f"f{k + 1}" for k in range(n_modes)] + ["first_platform_hz"]
    nominal.append([pm.first_hz])
    gradient.append(sens.derivative[[int(pm.index[0])]] if pm.complete
                    else np.full((1, len(params)), np.nan))
    if band_hz is not None:
        quantities.append("band_margin")
        nominal.append([band_margin(pm, band_hz, participation)])
        gradient.append(_margin_gradient(model, pm, band_hz, participation, params,
                                         tension_reference))
    nominal, gradient = np.concatenate(nominal), np.vstack(gradient)
    from scipy.stats import qmc
    u = qmc.LatinHypercube(d=len(params), seed=seed).random(n_samples)
    values = np.column_stack([items[p.name].values(p.value, u[:, j])
                              for j, p in enumerate(params)])
    p0 = np.array([p.value for p in params])
    first = nominal[None, :] + (values - p0[None, :]) @ gradient.T
    mc, failed = None, 0
    if method == "both":
        tasks = [(robot, pose, names, values[s:s + chunk_size], rung, model_options, n_modes,
                  band_hz, participation, tension_reference)
                 for s in range(0, n_samples, chunk_size)]
        mc = np.vstack(_run(tasks, workers, client))
        failed = int(np.sum(np.isnan(mc[:, n_modes])))
    return UncertaintyResult(
        parameters=tuple(names), nominal_values=p0, uncertain=tuple(items[n] for n in names),
        samples=values, quantities=tuple(quantities), nominal=nominal, gradient=gradient,
        first_order=first, monte_carlo=mc, failed=failed, seed=seed)


def _own_options(model):
    """The build options of a model of the ladder that change its frequencies."""
    if model.rung == "dsm":
        return {"tension": model.tension, "chordwise_inertia": model.chordwise_inertia}
    if model.rung == "exact":
        return {"fmax_hz": model.fmax_hz, "order": model.order,
                "half_waves": model.half_waves}
    if model.rung == "lumped":
        segs = model.segments
        return {"segments": int(segs[0]) if np.all(segs == segs[0]) else segs.tolist()}
    return {}


def _margin_gradient(model: FrequencyModel, pm: PlatformModes, band: tuple[float, float],
                     participation: float, params: list[Parameter],
                     tension_reference: ArrayLike | None) -> NDArray[np.float64]:
    """d(band margin)/dp: the sensitivity of the mode that sets the margin, over f_hi (above
    the band) or -f_lo (below)."""
    m = pm.modes
    k = np.flatnonzero(m.platform_share >= participation)
    if not k.size:                       # no mode held to the band: the margin is NaN
        return np.full((1, len(params)), np.nan)
    f = np.asarray(m.freq_hz)[k]
    lo, hi = band
    below = 1.0 - f / lo if lo > 0 else np.full(f.shape, -np.inf)
    marg = np.maximum(f / hi - 1.0, below)
    j = int(k[np.argmin(marg)])
    fm = np.asarray(m.freq_hz)
    d = sensitivities_at(model, fm[:whole_clusters(fm, j + 1)], params, "pose",
                         tension_reference).derivative[j]
    above = f[np.argmin(marg)] / hi - 1.0 >= below[np.argmin(marg)]
    return (d / hi if above else -d / lo)[None, :]


#: The row that the design checks add with stated uncertainties.
UNCERTAIN_CHECK = "platform modes outside band, uncertain"


def uncertain_row(
        robot: Robot, pose: Pose, options: CheckOptions, uncertain: dict[str, str],
        rung: str = "dsm", model_options: dict[Any, Any] | None = None, n_samples: int = 200,
        seed: int = 0, confidence: float = 0.95, workers: int | None = None,
) -> tuple[dict[str, float | str], UncertaintyResult | None]:
    """The design checks' row for stated uncertainties (theory.md §16.6): the probability
    that a mode with platform share >= ``options.participation`` lies within
    ``options.margin`` of the forbidden band (the margin check fails), by Monte Carlo with
    the first order beside it, and the band margin reached with probability ``confidence``;
    "pass" when that margin is >= ``options.margin``. The other rows keep their meaning.

    Returns
    -------
    row : dict (as :mod:`dynstiff.analyses.verdicts`)
    result : UncertaintyResult or None

    Examples
    --------
    >>> import dynstiff as ds
    >>> from dynstiff.analyses.verdicts import CheckOptions
    >>> sc = ds.load_scene("cogiro")
    >>> row, res = uncertain_row(sc.robot, sc.pose, CheckOptions(forbidden_hz=(0.0, 1.5)),
    ...                          {"EA": "10%"}, n_samples=8)
    >>> row["verdict"], row["value"]
    ('pass', 0.0)
    """
    text = "; ".join(f"{n} {Uncertain.parse(u).text() if isinstance(u, str) else u.text()}"
                     for n, u in uncertain.items())
    base = dict(check=UNCERTAIN_CHECK, value=np.nan, limit=1.0 - confidence)
    if options.forbidden_hz is None:
        return {**base, "verdict": "not asked", "passed": True,
                "detail": "no forbidden band given"}, None
    try:
        res = propagate_uncertainty(robot, pose, uncertain, n_modes=1,
                                    band_hz=options.forbidden_hz,
                                    participation=options.participation, n_samples=n_samples,
                                    seed=seed, rung=rung, workers=workers,
                                    **(model_options or {}))
    except DynstiffError as exc:       # the arguments were checked before any pose
        return {**base, "verdict": "unknown", "passed": False,
                "detail": f"no nominal equilibrium or modes: {exc}"}, None
    p_mc = res.probability_below("band_margin", options.margin)
    p_fo = res.probability_below("band_margin", options.margin, "first-order")
    q = res.quantile("band_margin", 1.0 - confidence)
    lo, hi = options.forbidden_hz
    ok = q >= options.margin
    detail = (f"P(a mode with platform share >= {options.participation:.0%} within "
              f"{options.margin:.1%} of [{lo:g}, {hi:g}] Hz) = {p_mc:.1%} (Monte Carlo, "
              f"{n_samples} samples, seed {seed}; first order {p_fo:.1%}"
              + (f"; {res.failed} samples without equilibrium, counted as failing"
                 if res.failed else "")
              + f"); band margin at {confidence:.0%} confidence {q:.3g} (limit "
              f"{options.margin:g}); {text}")
    return {**base, "verdict": "pass" if ok else "fail", "passed": bool(ok),
            "value": float(p_mc), "detail": detail}, res
