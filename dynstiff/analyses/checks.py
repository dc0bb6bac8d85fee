"""Design checks of a cable robot at a pose: tensions, sag, workspace, frequency margins of
every mode that moves the platform, the platform's dynamic amplification in the forbidden
band, modal proximity and the accuracy of the cable model the checks use. Each check gives a
verdict with the value and the limit it was held to (theory.md §12.1); the rows are those
of :mod:`dynstiff.analyses.verdicts`, which the workspace maps use too.
"""

from dataclasses import dataclass, replace
from numbers import Integral
from typing import TYPE_CHECKING

from dynstiff._validate import count, positive_scalar
from dynstiff.analyses.participation import FRF_AMPLIFICATION_LIMIT, PLATFORM_SHARE_THRESHOLD
from dynstiff.analyses.platform_modes import MAX_PLATFORM_MODES
from dynstiff.analyses.uncertainty import uncertain_items, uncertain_parameters, uncertain_row
from dynstiff.analyses.verdicts import CheckOptions, pose_rows
from dynstiff.errors import InvalidParameterError
from dynstiff.models.ladder import RUNGS, build_model
from dynstiff.params import DEFAULT_DAMPING, Damping
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    import numpy as np
    import pandas

    from dynstiff.robot.robot import Pose, Robot

__all__ = ["CheckResult", "check_options", "damped_model", "design_checks",
           "modal_model_options"]


def damped_model(equilibrium, damping=DEFAULT_DAMPING, rung="dsm", like=None, **options):
    """The model of ``rung`` at ``equilibrium`` with the analysis damping ``damping``.

    The viscous part is added to every cable's own ``viscous_damping`` (all rungs with
    cable mass); the cable loss factor and the platform modal ratio are options of the
    closed-form and exact models (:class:`dynstiff.FrequencyModel`,
    :class:`~dynstiff.models.exact.ExactModel`, theory.md §12.2). The massless
    rungs carry no damping; the lumped rung takes the viscous part only.

    Parameters
    ----------
    equilibrium : Equilibrium
    damping : Damping
    rung : str
    like : model, optional
        The model of ``rung`` built at ``equilibrium`` with ``options`` and no damping: the
        closed form's damped model then shares its cable terms (the same model, built
        without recomputing them, theory.md §13.7).
    **options
        Passed to :func:`dynstiff.build_model`.
    """
    if not isinstance(damping, Damping):
        raise InvalidParameterError(f"damping must be a dynstiff.Damping, got {damping!r}")
    eq = equilibrium
    if (like is not None and rung == "dsm" and damping.cable_viscous_damping == 0
            and set(options) <= {"tension", "chordwise_inertia", "guard_rtol"}
            and like.equilibrium is eq and all(
                getattr(like, k) == v for k, v in options.items())):
        new = like._with_model_damping(damping.cable_loss_factor, damping.platform_ratio)
        if new is not None:
            return new
    if damping.cable_viscous_damping > 0 and rung in ("dsm", "exact", "lumped"):
        from dynstiff.robot.robot import Robot
        rob = eq.robot
        cables = [replace(c, viscous_damping=c.viscous_damping + damping.cable_viscous_damping)
                  for c in rob.cables]
        rob = Robot(rob.anchors, rob.attachments, cables, rob.platform, g=rob.g,
                    tension_limits=rob.tension_limits, name=rob.name)
        eq = rob.equilibrium(pose=eq.pose)
    if rung in ("dsm", "exact"):
        options = {"cable_loss_factor": damping.cable_loss_factor,
                   "platform_damping_ratio": damping.platform_ratio, **options}
    return build_model(eq, rung, **options)

@dataclass(frozen=True)
class CheckResult:
    """Outcome of the design checks.

    Attributes
    ----------
    rows : tuple of dict
        One per check of :data:`dynstiff.analyses.verdicts.CHECKS`: ``check``, ``verdict``
        ("pass", "fail", "unknown" or "not asked"), ``passed`` (bool: "pass" or "not
        asked"), ``value``, ``limit``, ``detail``.
    platform : PlatformModes or None
        The modes the modal verdicts were taken from (None without an equilibrium).
    uncertainty : UncertaintyResult or None
        With stated uncertainties: the distributions behind the last row
        (:func:`dynstiff.analyses.uncertainty.uncertain_row`).

    Examples
    --------
    >>> import dynstiff as ds
    >>> scene = ds.load_scene("cogiro")
    >>> res = ds.design_checks(scene.robot, scene.equilibrium().pose, band_hz=(0.0, 1.5))
    >>> res.passed
    True
    >>> res.to_frame()["verdict"].tolist()
    ['pass', 'pass', 'pass', 'pass', 'pass', 'pass', 'pass']
    """

    rows: tuple
    platform: object = None
    uncertainty: object = None

    def __repr__(self) -> str:
        bad = [f"{r['check']} ({r['verdict']})" for r in self.rows if not r["passed"]]
        return (f"CheckResult({'passed' if not bad else 'FAILED: ' + ', '.join(bad)}; "
                f"{len(self.rows)} checks)")

    @property
    def passed(self) -> bool:
        """True when every check passed (a check "not asked" cannot fail; "unknown" does).

        Examples
        --------
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> res = ds.design_checks(scene.robot, scene.equilibrium().pose, band_hz=(0.0, 1.5))
        >>> res.passed
        True
        """
        return all(r["passed"] for r in self.rows)

    @property
    def verdicts(self) -> dict[str, str]:
        """{check: verdict}.

        Examples
        --------
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> res = ds.design_checks(scene.robot, scene.equilibrium().pose, band_hz=(0.0, 1.5))
        >>> res.verdicts["platform modes outside band"]
        'pass'
        """
        return {r["check"]: r["verdict"] for r in self.rows}

    def _repr_html_(self) -> str:
        """Jupyter display: the verdict, check and reason of every row."""
        from dynstiff._html import html_table
        return html_table(
            "Design checks: " + ("all passed" if self.passed else "some FAILED"),
            ["verdict", "check", "detail"],
            [[r["verdict"].upper(), r["check"], r["detail"]] for r in self.rows])

    def to_frame(self) -> "pandas.DataFrame":
        """pandas DataFrame, one row per check.

        Examples
        --------
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> res = ds.design_checks(scene.robot, scene.equilibrium().pose, band_hz=(0.0, 1.5))
        >>> list(res.to_frame().columns)
        ['check', 'verdict', 'passed', 'value', 'limit', 'detail']
        """
        import pandas as pd
        return pd.DataFrame(list(self.rows))

    def text(self) -> str:
        """Plain-text report.

        Examples
        --------
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> res = ds.design_checks(scene.robot, scene.equilibrium().pose, band_hz=(0.0, 1.5))
        >>> print(res.text().splitlines()[0])
        PASS    workspace (tension-feasible pose) statics residual 8.9e-14
        """
        flags = {"pass": "PASS", "fail": "FAIL", "unknown": "UNKNOWN", "not asked": "n/a"}
        out = [f"{flags[r['verdict']]:<7s} {r['check']:<33s} {r['detail']}" for r in self.rows]
        out.append("all checks passed" if self.passed else "some checks FAILED")
        return "\n".join(out) + "\n"


def check_options(band_hz=None, margin=0.05, proximity_rtol=0.03, max_sag_ratio=0.02,
                  model_rtol=1e-2, participation=PLATFORM_SHARE_THRESHOLD,
                  frf_limit=FRF_AMPLIFICATION_LIMIT, model_band_hz=None,
                  max_modes=MAX_PLATFORM_MODES):
    """The validated :class:`dynstiff.analyses.verdicts.CheckOptions` of
    :func:`design_checks`' arguments (each named in its error)."""
    model_rtol = positive_scalar("model_rtol", model_rtol)
    participation = positive_scalar("participation", participation)
    if not participation <= 0.5:
        raise InvalidParameterError(
            f"participation must be in (0, 0.5] (a platform share), got {participation!r}")
    frf_limit = positive_scalar("frf_limit", frf_limit)
    if not frf_limit > 1:
        raise InvalidParameterError(f"frf_limit must be > 1, got {frf_limit!r}")
    if isinstance(max_modes, bool) or not isinstance(max_modes, Integral) or max_modes < 1:
        raise InvalidParameterError(f"max_modes must be an integer >= 1, got {max_modes!r}")
    return CheckOptions(
        forbidden_hz=None if band_hz is None else _band("band_hz", band_hz),
        margin=positive_scalar("margin", margin, allow_zero=True),
        participation=participation, frf_limit=frf_limit,
        proximity_rtol=positive_scalar("proximity_rtol", proximity_rtol),
        max_sag_ratio=positive_scalar("max_sag_ratio", max_sag_ratio),
        model_rtol=model_rtol,
        model_band_hz=(0.0, 20.0) if model_band_hz is None
        else _band("model_band_hz", model_band_hz),
        max_modes=int(max_modes))


def _band(name, band):
    try:
        lo, hi = (positive_scalar(name, b, allow_zero=True) for b in band)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be (low, high) with 0 <= low < high [Hz], got {band!r}") from None
    if not lo < hi:
        raise InvalidParameterError(
            f"{name} must be (low, high) with 0 <= low < high [Hz], got {band!r}")
    return lo, hi


def design_checks(robot: "Robot", pose: "Pose | np.typing.ArrayLike",
                  band_hz: tuple[float, float] | None = None, margin: float = 0.05,
                  proximity_rtol: float = 0.03, max_sag_ratio: float = 0.02,
                  model_rtol: float = 1e-2, rung: str = "dsm",
                  participation: float = PLATFORM_SHARE_THRESHOLD,
                  frf_limit: float = FRF_AMPLIFICATION_LIMIT, damping: Damping = DEFAULT_DAMPING,
                  model_band_hz: tuple[float, float] | None = None,
                  max_modes: int = MAX_PLATFORM_MODES, uncertain: dict | None = None,
                  n_samples: int = 200, seed: int = 0, confidence: float = 0.95,
                  **model_options: object) -> "CheckResult":
    """Run the design checks at a pose (theory.md §12.1; the rows of
    :mod:`dynstiff.analyses.verdicts`, the same a workspace map gives).

    Parameters
    ----------
    robot : Robot
    pose : Pose or array_like
        Platform pose (inverse statics).
    band_hz : (float, float), optional
        Forbidden excitation band [Hz]: every mode whose platform share reaches
        ``participation`` (global and mixed modes) must lie outside it by ``margin``, and
        the platform's direct receptances inside it must stay below ``frf_limit`` times
        their static values. None: these two checks are not asked.
    margin : float
        Relative frequency margin of the checked modes to the band [-].
    participation : float
        Platform share of the kinetic energy from which a mode is held to the margin [-]
        (default :data:`dynstiff.analyses.participation.PLATFORM_SHARE_THRESHOLD`).
    frf_limit : float
        Largest admissible |H_jj(f)| / |H_jj(0)| of a direct platform receptance in the
        forbidden band [-] (default
        :data:`dynstiff.analyses.participation.FRF_AMPLIFICATION_LIMIT`).
    damping : Damping
        Damping of the receptance check (:func:`damped_model` of ``rung``).
    model_band_hz : (float, float), optional
        Band over which the cable model is judged [Hz] (the scene's band of interest;
        default (0, 20) Hz).
    proximity_rtol : float
        A local cable mode within this relative distance of a platform mode fails [-].
    max_sag_ratio : float
        Largest admissible sag / chord of any cable [-].
    rung : str
        The model the modal checks use, one of :data:`dynstiff.models.ladder.RUNGS`
        (default "dsm", the closed-form dynamic stiffness).
    model_rtol : float
        Admissible estimated relative frequency error of that model up to the top of
        ``model_band_hz`` [-] (:func:`dynstiff.analyses.recommend.estimated_error`).
    max_modes : int
        Ceiling of the modes computed; beyond it the modal verdicts are "unknown" (which
        fails the pose).
    uncertain : dict, optional
        Stated uncertainties {parameter: Uncertain or "10%"}
        (:func:`~dynstiff.propagate_uncertainty`): a last row gives the probability that
        the margin check fails and the band margin at ``confidence`` (theory.md §16.6); the
        other rows are those of the nominal robot.
    n_samples, seed : int
        The Monte Carlo's Latin-hypercube sample and its seed.
    confidence : float
        Level in (0, 1) of the margin the uncertain row holds to ``margin``.
    **model_options
        Passed to :func:`dynstiff.models.ladder.build_model` (e.g. ``segments`` of "lumped").

    Returns
    -------
    CheckResult

    Examples
    --------
    >>> import dynstiff as ds
    >>> from dynstiff.analyses.checks import design_checks
    >>> scene = ds.load_scene("cogiro")
    >>> res = design_checks(scene.robot, scene.equilibrium().pose, band_hz=(0.0, 1.5))
    >>> res.passed, res.verdicts["platform modes outside band"]
    (True, 'pass')
    """
    options = check_options(band_hz, margin, proximity_rtol, max_sag_ratio, model_rtol,
                            participation, frf_limit, model_band_hz, max_modes)
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a dynstiff.Robot, got {type(robot).__name__}")
    pose = as_pose(pose)       # the caller's pose is checked, never read as the robot's failure
    if not isinstance(damping, Damping):
        raise InvalidParameterError(f"damping must be a dynstiff.Damping, got {damping!r}")
    if rung not in RUNGS:
        raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
    if not (isinstance(confidence, float) and 0 < confidence < 1):
        raise InvalidParameterError(f"confidence must be a number in (0, 1), got "
                                    f"{confidence!r}")
    if uncertain:            # checked before any pose, as the map does: never a verdict
        n_samples, seed = count("n_samples", n_samples), count("seed", seed, least=0)
        uncertain_parameters(list(uncertain_items(uncertain)), robot, pose)
    options_of = modal_model_options(rung, options, model_options)
    built = []

    def model_of(eq):
        built.append(build_model(eq, rung, **options_of))
        return built[-1]
    rows, eq, pm = pose_rows(robot, pose, model_of, options,
                             lambda eq: damped_model(eq, damping, rung, built[-1],
                                                     **options_of))
    res = None
    if uncertain:
        row, res = uncertain_row(robot, pose, options, uncertain, rung, options_of, n_samples,
                                 seed, confidence)
        rows.append(row)
    return CheckResult(rows=tuple(rows), platform=pm, uncertainty=res)


def modal_model_options(rung, options, model_options):
    """The model options of ``rung`` for the checks: the exact rung's band holds what they
    compute (1.1 x the highest of the forbidden band with its margin and the band of
    interest, and room for the proximity neighbours)."""
    if rung != "exact" or "fmax_hz" in model_options:
        return dict(model_options)
    tops = [options.model_band_hz[1]]
    if options.forbidden_hz is not None:
        tops.append(options.forbidden_hz[1] * (1 + options.margin))
    return {"fmax_hz": 1.1 * max(tops) * (1 + options.proximity_rtol), **model_options}
