"""Design checks of a cable robot at a pose: tensions, sag, workspace, frequency margins of
every mode that moves the platform, the platform's dynamic amplification in the forbidden
band, modal proximity and the accuracy of the cable model the checks use. Each check gives a
pass/fail row with the value and the limit it was held to (theory.md §12.1).
"""

from dataclasses import dataclass, replace

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.analyses.eigen import modes as modal
from dynstiff.analyses.interaction import proximity_warnings
from dynstiff.analyses.participation import (
    FRF_AMPLIFICATION_LIMIT,
    PLATFORM_SHARE_THRESHOLD,
    platform_participation,
    receptance_amplification,
)
from dynstiff.analyses.recommend import recommend_model
from dynstiff.errors import DynstiffError, InvalidParameterError
from dynstiff.models.ladder import RUNGS, build_model
from dynstiff.params import DEFAULT_DAMPING, Damping

__all__ = ["CheckResult", "design_checks", "damped_model"]


def damped_model(equilibrium, damping=DEFAULT_DAMPING, rung="dsm", **options):
    """The model of ``rung`` at ``equilibrium`` with the analysis damping ``damping``.

    The viscous part is added to every cable's own ``viscous_damping`` (all rungs with
    cable mass); the cable loss factor and the platform modal ratio are options of the
    closed-form and exact models (:class:`dynstiff.FrequencyModel`, :class:`ExactModel`,
    theory.md §12.2). The massless
    rungs carry no damping; the lumped rung takes the viscous part only.

    Parameters
    ----------
    equilibrium : Equilibrium
    damping : Damping
    rung : str
    **options
        Passed to :func:`dynstiff.build_model`.
    """
    if not isinstance(damping, Damping):
        raise InvalidParameterError(f"damping must be a dynstiff.Damping, got {damping!r}")
    eq = equilibrium
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

_RUNG_NAMES = {"spring": "massless straight-spring model", "catenary": "massless catenary model",
               "dsm": "closed-form DSM", "exact": "exact cable DSM",
               "lumped": "lumped-mass model"}


@dataclass(frozen=True)
class CheckResult:
    """Outcome of the design checks.

    Attributes
    ----------
    rows : tuple of dict
        One per check: ``check``, ``passed`` (bool), ``value``, ``limit``, ``detail``.
    """

    rows: tuple

    def __repr__(self):
        failed = [r["check"] for r in self.rows if not r["passed"]]
        return (f"CheckResult({'passed' if not failed else 'FAILED: ' + ', '.join(failed)}; "
                f"{len(self.rows)} checks)")

    @property
    def passed(self):
        """True when every check passed."""
        return all(r["passed"] for r in self.rows)

    def to_frame(self):
        """pandas DataFrame, one row per check."""
        import pandas as pd
        return pd.DataFrame(list(self.rows))

    def text(self):
        """Plain-text report."""
        out = []
        for r in self.rows:
            flag = "PASS" if r["passed"] else "FAIL"
            out.append(f"{flag}  {r['check']:<34s} {r['detail']}")
        out.append("all checks passed" if self.passed else "some checks FAILED")
        return "\n".join(out) + "\n"


def design_checks(robot, pose, band_hz=None, margin=0.05, proximity_rtol=0.03,
                  max_sag_ratio=0.02, fmax_hz=None, model_rtol=1e-2, rung="dsm",
                  participation=PLATFORM_SHARE_THRESHOLD, frf_limit=FRF_AMPLIFICATION_LIMIT,
                  damping=DEFAULT_DAMPING, model_band_hz=None, **model_options):
    """Run the design checks at a pose.

    Parameters
    ----------
    robot : Robot
    pose : Pose or array_like
        Platform pose (inverse statics).
    band_hz : (float, float), optional
        Forbidden excitation band [Hz]: every mode whose platform share reaches
        ``participation`` (global and mixed modes) must lie outside it by ``margin``, and
        the platform's direct receptances inside it must stay below ``frf_limit`` times
        their static values.
    margin : float
        Relative frequency margin of the checked modes to the band [-].
    participation : float
        Platform share of the kinetic energy from which a mode is held to the margin [-]
        (default :data:`dynstiff.analyses.participation.PLATFORM_SHARE_THRESHOLD`, theory.md §12.1).
    frf_limit : float
        Largest admissible |H_jj(f)| / |H_jj(0)| of a direct platform receptance in the
        forbidden band [-] (default
        :data:`dynstiff.analyses.participation.FRF_AMPLIFICATION_LIMIT`).
    damping : Damping
        Damping of the FRF check (closed-form model, :func:`damped_model`).
    model_band_hz : (float, float), optional
        Band over which the cable model is judged [Hz] (the scene's band of interest);
        default 0 to the highest mode checked.
    proximity_rtol : float
        A local cable mode within this relative distance of a global mode fails [-].
    max_sag_ratio : float
        Largest admissible sag / chord of any cable [-].
    fmax_hz : float, optional
        Modes are computed up to this frequency [Hz] (default: 1.5 x the band's top, or
        the 6th global mode).
    rung : str
        The model the modal checks use, one of :data:`dynstiff.models.ladder.RUNGS` (default "dsm",
        the closed-form dynamic stiffness).
    **model_options
        Passed to :func:`dynstiff.models.ladder.build_model` (e.g. ``segments`` of "lumped").
    model_rtol : float
        Admissible relative frequency error of the cable model the checks use up to the
        highest mode checked [-]: the "cable model"
        row fails when :func:`dynstiff.recommend_model` predicts a larger error, and names
        the cheapest model that meets it.

    Returns
    -------
    CheckResult
    """
    model_rtol = positive_scalar("model_rtol", model_rtol)
    participation = positive_scalar("participation", participation)
    if not participation <= 0.5:
        raise InvalidParameterError(
            f"participation must be in (0, 0.5] (a platform share), got {participation!r}")
    frf_limit = positive_scalar("frf_limit", frf_limit)
    if not frf_limit > 1:
        raise InvalidParameterError(f"frf_limit must be > 1, got {frf_limit!r}")
    if not isinstance(damping, Damping):
        raise InvalidParameterError(f"damping must be a dynstiff.Damping, got {damping!r}")
    margin = positive_scalar("margin", margin, allow_zero=True)
    proximity_rtol = positive_scalar("proximity_rtol", proximity_rtol)
    max_sag_ratio = positive_scalar("max_sag_ratio", max_sag_ratio)
    if fmax_hz is not None:
        fmax_hz = positive_scalar("fmax_hz", fmax_hz)
    if band_hz is not None:
        try:
            lo, hi = (positive_scalar("band_hz", b, allow_zero=True) for b in band_hz)
        except (TypeError, ValueError):
            raise InvalidParameterError(
                f"band_hz must be (low, high) with 0 <= low < high [Hz], got {band_hz!r}") from None
        if not lo < hi:
            raise InvalidParameterError(
                f"band_hz must be (low, high) with 0 <= low < high [Hz], got {band_hz!r}")
        band_hz = (lo, hi)
    if rung not in RUNGS:
        raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
    rows = []
    t_min, t_max = robot.tension_limits
    try:
        eq = robot.equilibrium(pose=pose)
    except DynstiffError as exc:
        rows.append(dict(check="workspace (tension-feasible pose)", passed=False, value=np.nan,
                         limit=np.nan, detail=str(exc)))
        return CheckResult(rows=tuple(rows))
    rows.append(dict(check="workspace (tension-feasible pose)", passed=True, value=eq.residual,
                     limit=1e-10, detail=f"statics residual {eq.residual:.1e}"))
    lo, hi = eq.min_tensions, eq.max_tensions
    tol = 1e-9 * max(1.0, t_min)
    ok = bool(np.all(lo >= t_min - tol) and np.all(hi <= t_max + tol))
    rows.append(dict(check="tension limits", passed=ok, value=float(hi.max()), limit=t_max,
                     detail=f"tensions along the cables {lo.min():.1f}-{hi.max():.1f} N "
                            f"within [{t_min:g}, {t_max:g}] N"))
    sag = np.array([s.sag / s.chord_length for s in eq.states])
    rows.append(dict(check="sag / chord", passed=bool(sag.max() <= max_sag_ratio),
                     value=float(sag.max()), limit=max_sag_ratio,
                     detail=f"largest {sag.max():.2e} (cable {int(sag.argmax())}), "
                            f"limit {max_sag_ratio:g}"))
    if fmax_hz is None:
        fmax_hz = 1.5 * band_hz[1] if band_hz is not None else None
    if rung == "exact" and fmax_hz is not None:      # the exact cables resolve the checked band
        model_options = {"fmax_hz": 1.1 * fmax_hz * (1 + proximity_rtol), **model_options}
    model = build_model(eq, rung, **model_options)
    if fmax_hz is None:
        n = 40
        while True:
            modes = modal(model, n_modes=int(min(n, getattr(model, "n_dof", n))))
            if sum(k == "global" for k in modes.kind) >= model.n_free or n >= 320 or \
                    n >= getattr(model, "n_dof", np.inf):
                break
            n *= 2
    else:
        # up to (1 + rtol) fmax so global modes near fmax see their local partners
        modes = modal(model, fmax_hz=fmax_hz * (1 + proximity_rtol))
    part = platform_participation(model, modes, participation)
    if band_hz is not None:
        lo, hi = band_hz
        rows.append(_margin_row(part, lo, hi, margin, participation))
        dm = damped_model(eq, damping, "dsm", **(model_options if rung == "dsm" else {}))
        ratio, f_at, dof = receptance_amplification(dm, band_hz, modes.freq_hz)
        rows.append(dict(
            check="platform receptance in band", passed=bool(ratio <= frf_limit),
            value=ratio, limit=frf_limit,
            detail=f"largest |H_{dof}{dof}| / static {ratio:.3g} at {f_at:.4g} Hz in "
                   f"[{lo:g}, {hi:g}] Hz (limit {frf_limit:g}; {damping.text()})"))
    top = float(fmax_hz * (1 + proximity_rtol) if fmax_hz is not None else modes.freq_hz.max())
    judged = (0.0, top) if model_band_hz is None else tuple(model_band_hz)
    rec = recommend_model(eq, band_hz=judged, rtol=model_rtol)
    top = judged[1]
    err = rec.errors[rung]
    if rung == "lumped":                 # the error of the segment count used, not recommended
        n_seg = int(np.min(model.segments))
        err = float((max(1.0, rec.estimates["highest_harmonic"]) * np.pi / n_seg) ** 2 / 24)
    need = rec.rung if rec.predicted_error <= model_rtol else "none on the ladder"
    rows.append(dict(
        check="cable model", passed=bool(err <= model_rtol), value=float(err),
        limit=model_rtol,
        detail=(f"{_RUNG_NAMES[rung]} used here, predicted error {err:.1e} to {top:.3g} Hz "
                f"(limit {model_rtol:g}); recommended model: {need}"
                + ("" if err <= model_rtol else
                   f" ({rec.segments} segments per cable)" if rec.rung == "lumped" else ""))))
    warns = proximity_warnings(modes, rtol=proximity_rtol)
    rows.append(dict(
        check="local modes near global modes", passed=not warns,
        value=min((w.relative_gap for w in warns), default=np.nan), limit=proximity_rtol,
        detail=(f"{len(warns)} local mode(s) within {proximity_rtol:.2%} of a global mode, "
                f"closest gap {min(w.relative_gap for w in warns):.2%}") if warns
        else f"no local mode within {proximity_rtol:.2%} of a global mode"))
    return CheckResult(rows=tuple(rows))


def _margin_row(part, lo, hi, margin, threshold):
    """The frequency-margin row: modes with platform share >= threshold near [lo, hi]."""
    f = part.freq_hz
    near = part.checked & (f > lo * (1 - margin)) & (f < hi * (1 + margin))
    dom = part.dominant_dof()

    def name(k):
        return (f"{f[k]:.4g} Hz ({part.category[k]}, platform share "
                f"{100 * part.platform_share[k]:.0f} %, mostly {dom[k]})")
    if np.any(near):
        ks = np.flatnonzero(near)
        detail = (f"{ks.size} mode(s) with platform share >= {threshold:.0%} within "
                  f"{margin:.1%} of [{lo:g}, {hi:g}] Hz: " + "; ".join(name(k) for k in ks))
        return dict(check="platform modes outside band", passed=False, value=float(f[ks[0]]),
                    limit=margin, share=float(part.platform_share[ks[0]]), detail=detail)
    checked = np.flatnonzero(part.checked)
    if checked.size:
        fc = f[checked]
        gap = np.where(fc < lo, (lo - fc) / max(lo, 1e-300), (fc - hi) / hi)
        k = checked[int(np.argmin(gap))]
        closest = f"; closest {name(k)}"
    else:
        closest, k = "", None
    return dict(check="platform modes outside band", passed=True,
                value=float(f[k]) if k is not None else np.nan, limit=margin,
                share=float(part.platform_share[k]) if k is not None else np.nan,
                detail=f"no mode with platform share >= {threshold:.0%} within {margin:.1%} "
                       f"of [{lo:g}, {hi:g}] Hz{closest}")
