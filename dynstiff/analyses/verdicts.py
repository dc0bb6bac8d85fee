"""The verdicts of a pose: one function for the design checks, the workspace maps and the
reports, so that a pose gets the same verdict wherever it is asked (theory.md §12.5).

Each check has its own band or limit and nothing else moves it:

=================================  =========================================================
check                              passes when
=================================  =========================================================
workspace (tension-feasible pose)  the statics find tensions within the limits
tension limits                     every cable's tension stays within [t_min, t_max]
sag / chord                        every cable's sag / chord <= ``max_sag_ratio``
platform modes outside band        no mode with platform share >= ``participation`` lies
                                   within ``margin`` of the forbidden band
platform receptance in band        |H_jj(f)| / |H_jj(0)| <= ``frf_limit`` in the forbidden
                                   band (the damped model)
local modes near platform modes    no local mode within ``proximity_rtol`` of a platform mode
                                   (:mod:`dynstiff.analyses.platform_modes`)
cable model                        the model's estimated error up to the band of interest's
                                   top is <= ``model_rtol``
=================================  =========================================================

A verdict is "pass", "fail", "unknown" (what it needs was not computed: a ceiling was
reached; it fails the pose, never passes it) or "not asked" (no forbidden band given: the two
band checks do not apply). Modes come from
:func:`dynstiff.analyses.platform_modes.find_platform_modes`, computed until they hold the
platform modes and cover the forbidden band, whatever number of modes a table shows.
"""

from dataclasses import dataclass

import numpy as np

from dynstiff.analyses.interaction import proximity_warnings
from dynstiff.analyses.participation import receptance_amplification
from dynstiff.analyses.platform_modes import MAX_PLATFORM_MODES, find_platform_modes
from dynstiff.analyses.recommend import estimated_error
from dynstiff.cable.catenary_batch import catenary_arrays, sag_ratios

__all__ = ["CHECKS", "VERDICTS", "CheckOptions", "equilibrium_sag_ratios", "modal_rows",
           "pose_rows", "statics_rows"]

#: The checks of a pose, in order.
CHECKS = ("workspace (tension-feasible pose)", "tension limits", "sag / chord",
          "platform modes outside band", "platform receptance in band",
          "local modes near platform modes", "cable model")
#: The verdicts a check can give.
VERDICTS = ("pass", "fail", "unknown", "not asked")


@dataclass(frozen=True)
class CheckOptions:
    """The limits and bands of the checks of a pose (validated by their callers).

    Attributes
    ----------
    forbidden_hz : (float, float) or None
        Forbidden band [Hz]; None: its two checks are not asked.
    margin : float
        Relative margin of the checked modes to the forbidden band [-].
    participation : float
        Platform share from which a mode is held to the margin [-].
    frf_limit : float
        Largest admissible receptance / static value in the forbidden band [-].
    proximity_rtol : float
        Relative gap below which a local mode near a platform mode fails [-].
    max_sag_ratio : float
        Largest admissible sag / chord [-].
    model_rtol : float
        Admissible estimated error of the cable model [-].
    model_band_hz : (float, float)
        Band over which the cable model is judged [Hz].
    max_modes : int
        Ceiling of the modes computed (beyond it the modal verdicts are "unknown").
    """

    forbidden_hz: object = None
    margin: float = 0.05
    participation: float = 0.05
    frf_limit: float = 10.0
    proximity_rtol: float = 0.03
    max_sag_ratio: float = 0.02
    model_rtol: float = 1e-2
    model_band_hz: tuple = (0.1, 20.0)
    max_modes: int = MAX_PLATFORM_MODES


def _row(check, verdict, value=np.nan, limit=np.nan, detail=""):
    return dict(check=check, verdict=verdict, passed=verdict in ("pass", "not asked"),
                value=float(value), limit=float(limit), detail=detail)


def equilibrium_sag_ratios(robot, equilibrium):
    """Largest distance from the chord / chord length of every cable [-], shape (n,): the
    profile of :attr:`dynstiff.cable.catenary.CatenaryState.sag`, all cables at once
    (:func:`dynstiff.cable.catenary_batch.sag_ratios`)."""
    eq = equilibrium
    B, _ = robot.attachment_points(eq.pose)
    EA = np.array([c.EA for c in robot.cables])
    w0 = np.array([c.mass_per_length for c in robot.cables]) * robot.g
    return sag_ratios(robot.anchors, B, *catenary_arrays(eq.states), EA, w0)


def statics_rows(robot, equilibrium, error, options, sag=None):
    """The workspace, tension and sag rows from the statics (``error``: the exception of a
    failed statics, else None; ``sag``: :func:`equilibrium_sag_ratios` when the caller has
    them already)."""
    if error is not None:
        return [_row(CHECKS[0], "fail", detail=str(error))] + [
            _row(c, "unknown", detail="no equilibrium at this pose") for c in CHECKS[1:]]
    eq = equilibrium
    t_min, t_max = robot.tension_limits
    lo, hi = eq.min_tensions, eq.max_tensions
    tol = 1e-9 * max(1.0, t_min)
    ok = bool(np.all(lo >= t_min - tol) and np.all(hi <= t_max + tol))
    sag = equilibrium_sag_ratios(robot, eq) if sag is None else sag
    return [
        _row(CHECKS[0], "pass", eq.residual, 1e-10, f"statics residual {eq.residual:.1e}"),
        _row(CHECKS[1], "pass" if ok else "fail", hi.max(), t_max,
             f"tensions along the cables {lo.min():.1f}-{hi.max():.1f} N within "
             f"[{t_min:g}, {t_max:g}] N"),
        _row(CHECKS[2], "pass" if sag.max() <= options.max_sag_ratio else "fail", sag.max(),
             options.max_sag_ratio, f"largest {sag.max():.2e} (cable {int(sag.argmax())}), "
                                    f"limit {options.max_sag_ratio:g}")]


def modal_rows(model, options, damped_model=None):
    """The four modal rows of ``model`` (margin, receptance, proximity, cable model) and the
    platform modes they were taken from.

    Parameters
    ----------
    model : model of any rung (undamped modes are used)
    options : CheckOptions
    damped_model : model or callable, optional
        The model of the receptance check (with the analysis damping), or a function of no
        argument that builds it (called only when a forbidden band is given); default
        ``model``.

    Returns
    -------
    rows : list of dict
    platform : PlatformModes
    """
    o = options
    fb = o.forbidden_hz
    cover = fb[1] * (1 + o.margin) if fb is not None else 0.0
    pm = find_platform_modes(model, cover, o.proximity_rtol, o.max_modes)
    rows = [_margin_row(pm, o, cover)]
    if fb is None:
        rows.append(_row(CHECKS[4], "not asked", detail="no forbidden band given"))
    else:
        in_band = [] if pm.modes is None else pm.modes.freq_hz
        if callable(damped_model):
            damped_model = damped_model()
        ratio, f_at, dof = receptance_amplification(damped_model or model, fb, in_band)
        rows.append(_row(
            CHECKS[4], "pass" if ratio <= o.frf_limit else "fail", ratio, o.frf_limit,
            f"largest |H_{dof}{dof}| / static {ratio:.3g} at {f_at:.4g} Hz in "
            f"[{fb[0]:g}, {fb[1]:g}] Hz (limit {o.frf_limit:g})"))
    rows.append(_proximity_row(pm, o))
    err, cause = estimated_error(model, o.model_band_hz)
    rows.append(_row(CHECKS[6], "pass" if err <= o.model_rtol else "fail", err, o.model_rtol,
                     f"{model.rung} model, estimated error {err:.1e} up to "
                     f"{o.model_band_hz[1]:g} Hz (limit {o.model_rtol:g}; {cause})"))
    return rows, pm


def pose_rows(robot, pose, model_of, options, damped_of=None):
    """Every row of a pose: statics, then (when the pose has an equilibrium) the modal rows of
    ``model_of(equilibrium)``; ``damped_of(equilibrium)`` gives the receptance check's model.
    Returns (rows, equilibrium or None, PlatformModes or None)."""
    from dynstiff.errors import DynstiffError
    try:
        eq, error = robot.equilibrium(pose=pose), None
    except DynstiffError as exc:
        eq, error = None, exc
    rows = statics_rows(robot, eq, error, options)
    if eq is None:
        return rows, None, None
    modal, pm = modal_rows(model_of(eq), options,
                           None if damped_of is None else lambda: damped_of(eq))
    return rows + modal, eq, pm


def _margin_row(pm, o, cover):
    """The frequency-margin row: modes with platform share >= participation near the band."""
    if o.forbidden_hz is None:
        return _row(CHECKS[3], "not asked", detail="no forbidden band given")
    lo, hi = o.forbidden_hz
    if pm.modes is None or pm.searched_hz < cover:
        return _row(CHECKS[3], "unknown", detail=f"the modes up to {cover:.4g} Hz were not "
                                                 f"all computed: {pm.reason}")
    m = pm.modes
    f = np.asarray(m.freq_hz)
    checked = m.platform_share >= o.participation
    near = checked & (f > lo * (1 - o.margin)) & (f < hi * (1 + o.margin))
    name = pm.describe
    if np.any(near):
        ks = np.flatnonzero(near)
        return _row(CHECKS[3], "fail", f[ks[0]], o.margin,
                    f"{ks.size} mode(s) with platform share >= {o.participation:.0%} within "
                    f"{o.margin:.1%} of [{lo:g}, {hi:g}] Hz: " + "; ".join(map(name, ks))
                    + _spread(pm))
    ks = np.flatnonzero(checked)
    if ks.size:
        gap = np.where(f[ks] < lo, (lo - f[ks]) / max(lo, 1e-300), (f[ks] - hi) / hi)
        k = ks[int(np.argmin(gap))]
        closest = f"; closest {name(k)}"
    else:
        k, closest = None, ""
    return _row(CHECKS[3], "pass", f[k] if k is not None else np.nan, o.margin,
                f"no mode with platform share >= {o.participation:.0%} within {o.margin:.1%} "
                f"of [{lo:g}, {hi:g}] Hz{closest}" + _spread(pm))


def _spread(pm):
    """"; " and the sentence of a spread platform motion, or ""."""
    text = pm.spread()
    return f"; {text}" if text else ""


def _proximity_row(pm, o):
    """The proximity row: local modes within proximity_rtol of a platform mode."""
    if not pm.complete:
        return _row(CHECKS[5], "unknown", detail=f"the platform modes were not all found: "
                                                 f"{pm.reason}")
    warns = proximity_warnings(pm.modes, rtol=o.proximity_rtol, platform=pm.index)
    if warns:
        return _row(CHECKS[5], "fail", min(w.relative_gap for w in warns), o.proximity_rtol,
                    f"{len(warns)} local mode(s) within {o.proximity_rtol:.2%} of a platform "
                    f"mode, closest gap {min(w.relative_gap for w in warns):.2%}" + _spread(pm))
    return _row(CHECKS[5], "pass", np.nan, o.proximity_rtol,
                f"no local mode within {o.proximity_rtol:.2%} of the {pm.index.size} platform "
                f"modes ({pm.freq_hz.min():.4g}-{pm.freq_hz.max():.4g} Hz)" + _spread(pm))
