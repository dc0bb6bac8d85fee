"""Calibration: the robot's uncertain parameters fitted to measured natural frequencies.

Weighted least squares on the relative frequency residuals (theory.md §15.6)

    r_k(p) = (f_k(p) - f_k^meas) / s_k,      s_k = sigma_k  or  f_k^meas (relative),

over the parameters p = p0 exp(u) (positive; u free), solved by scipy's trust-region
least squares. The sensitivities J = dr/du = p df/dp / s are analytic
(:func:`dynstiff.analyses.sensitivity.sensitivities_at`, theory.md §16.5) for frequency
residuals of the structural parameters (EA, EA_i, mass, inertia, t_min) on a rung with
sensitivities: they come with the evaluation they differentiate, so a search costs no
evaluation beyond its residuals. Otherwise (damping ratios, FRFs) finite differences (step
1e-4 in u, far above the 1e-10 tolerance of the statics; forward during the search, central
at the estimate), n or 2 n evaluations more per Jacobian.
At the optimum the covariance of u is

    C = s^2 (J^T J)^-1,   s^2 = |r|^2 / (m - n)   (or 1 when every sigma_k is given and
                                                   nothing else is fitted),

and the confidence interval of p_j is p0_j exp(u_j -+ t_{m-n} sqrt(C_jj)) (Student's t at
the chosen level; a normal quantile when the sigmas are given). With as many measured values
(frequencies, damping ratios, FRF entries) as parameters the spread of the residuals is
unknown: the interval is NaN unless sigmas are given. A bound beyond the floating-point range
is inf (0 for the lower one), without a numpy warning.

Parameters (names):

=============  ==================================================  =========
``"EA"``        one factor on every cable's EA; reported as EA of     N
                cable 0
``"EA_i"``      EA of cable i alone (``"EA_*"``: one per cable)        N
``"mass"``      platform mass                                         kg
``"inertia"``   one factor on the platform inertia tensor about G      --
``"t_min"``     least tension of the tension distribution              N
``"loss_factor"``      hysteretic loss factor of every cable         --
``"viscous_damping"``  viscous damping of every cable                N s/m^2
=============  ==================================================  =========

A damping parameter is fitted to the measured damping ratios (``MeasuredModes.damping_ratio``)
with the residuals zeta_k(p) / zeta_k^meas - 1 appended to the frequency residuals; the
model's ratios are those of :func:`dynstiff.damped_modes` for the paired modes.

Every evaluation solves the inverse statics at the pose again (EA and mass change the
equilibrium) and the modes of the chosen rung, paired with the measured ones at every
evaluation: by MAC with the measured shapes when there are some, otherwise the k-th measured
frequency with the continuation of the k-th platform mode of the massless-cable model
(:func:`dynstiff.analyses.measured.massless_pairing`), which keeps its order while E moves the whole
spectrum. The sensitivities at the estimate are the analytic ones, or central differences
(step 1e-4 in ln p).
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import flag
from dynstiff.analyses.calibration_checks import calibration_findings, fit_options, report_findings
from dynstiff.analyses.calibration_result import CalibrationResult
from dynstiff.analyses.damped import damped_modes
from dynstiff.analyses.eigen import mode_count
from dynstiff.analyses.frf import frf as frf_of
from dynstiff.analyses.measured import MeasuredModes, massless_pairing, pair_modes
from dynstiff.analyses.modes import modes
from dynstiff.analyses.sensitivity import RUNGS as SENSITIVITY_RUNGS
from dynstiff.analyses.sensitivity import sensitivities_at
from dynstiff.errors import ClosedFormWarning, ConvergenceError, InvalidParameterError
from dynstiff.models.ladder import build_model

if TYPE_CHECKING:
    from collections.abc import Sequence
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.results import FRFResult
    from dynstiff.robot.pose import Pose
    from dynstiff.robot.robot import Robot
    from dynstiff.scenes.loader import Scene

__all__ = ["CalibrationResult", "calibrate", "PARAMETERS"]

#: Parameter names (module notes); "EA_<i>" and "EA_*" name cables.
PARAMETERS = ("EA", "EA_i", "EA_*", "mass", "inertia", "t_min", "loss_factor",
              "viscous_damping")
_DAMPING = ("loss_factor", "viscous_damping")
#: Jacobians of :func:`calibrate`.
JACOBIANS = ("auto", "analytic", "differences")


def _expand(parameters: str | list[str] | tuple[str], n_cables: int) -> tuple[str, ...]:
    if isinstance(parameters, str):
        parameters = (parameters,)
    if not isinstance(parameters, (tuple, list)) or not parameters:
        raise InvalidParameterError(f"parameters must be names among {PARAMETERS}")
    names = []
    for p in parameters:
        if p == "EA_*":
            names += [f"EA_{i}" for i in range(n_cables)]
        elif p in ("EA", "mass", "inertia", "t_min") + _DAMPING:
            names.append(p)
        elif isinstance(p, str) and p.startswith("EA_") and p[3:].isdigit() \
                and int(p[3:]) < n_cables:
            names.append(p)
        else:
            raise InvalidParameterError(
                f"parameters: {p!r} is not one of {PARAMETERS} (EA_i with i < {n_cables})")
    if len(set(names)) != len(names) or ("EA" in names and any(n.startswith("EA_")
                                                               for n in names)):
        raise InvalidParameterError(f"parameters name a quantity twice: {names}")
    return tuple(names)


def _value(robot: Robot, name: str) -> float:
    """Current value of a parameter of ``robot`` (units: module notes)."""
    if name == "EA":
        return robot.cables[0].EA
    if name.startswith("EA_"):
        return robot.cables[int(name[3:])].EA
    if name == "mass":
        return robot.platform.mass
    if name == "inertia":
        return 1.0
    if name in _DAMPING:
        return getattr(robot.cables[0], name)
    return robot.tension_limits[0]


def _with(robot: Robot, names: tuple[str, ...], factors: NDArray[np.float64]) -> Robot:
    """``robot`` with each parameter multiplied by its factor."""
    cables = list(robot.cables)
    platform, limits = robot.platform, robot.tension_limits
    for name, s in zip(names, factors):
        if name == "EA":
            cables = [replace(c, EA=c.EA * s) for c in cables]
        elif name.startswith("EA_"):
            i = int(name[3:])
            cables[i] = replace(cables[i], EA=cables[i].EA * s)
        elif name == "mass":
            platform = replace(platform, mass=platform.mass * s)
        elif name == "inertia":
            platform = replace(platform, inertia=platform.inertia * s)
        elif name in _DAMPING:
            cables = [replace(c, **{name: getattr(c, name) * s}) for c in cables]
        else:
            limits = (limits[0] * s, limits[1])
    return replace(robot, cables=cables, platform=platform, tension_limits=limits)


def _refuse_too_many_modes(model: Any, measured: MeasuredModes, fmax: float,
                           fmax_factor: float, max_modes: int) -> None:
    """Refuse, from one Wittrick-Williams count, a band of the start model holding more than
    ``max_modes`` modes, naming the highest measured mode. The closed form's band warnings
    are held back here: it misses the axial modes, so its count is a lower bound, and the
    modes computed after this check give the warnings where they apply."""
    k = int(np.argmax(measured.freq_hz))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)
        try:
            n = int(mode_count(model, 2 * np.pi * fmax)[0])
        except InvalidParameterError as err:     # beyond the cable model's frequency range
            raise InvalidParameterError(
                f"measured mode {k + 1} at {measured.freq_hz[k]:g} Hz: the band up to {fmax:g} "
                f"Hz (fmax_factor {fmax_factor:g} times it) is beyond the model: {err}; check "
                f"the measured frequencies' unit (Hz)") from None
    if n > max_modes:
        raise InvalidParameterError(
            f"measured mode {k + 1} at {measured.freq_hz[k]:g} Hz: the model has {n} modes below "
            f"{fmax:g} Hz (fmax_factor {fmax_factor:g} times it), more than max_modes = "
            f"{max_modes}; check the measured frequencies' unit (Hz), or raise max_modes")


def calibrate(scene_or_robot: Robot | Scene, measured: ArrayLike | MeasuredModes | None,
              parameters: str | Sequence[str] = ("EA",),
              pose: ArrayLike | Pose | None = None, rung: str = "dsm", pairing: str | None = None,
              confidence: float = 0.95, bounds: tuple[float, float] = (1e-2, 1e2),
              xtol: float = 1e-6, max_nfev: int = 40, fmax_factor: float = 1.3,
              start: dict[str, float] | None = None, frf: FRFResult | None = None,
              frf_point: ArrayLike | None = None, jacobian: str = "auto", strict: bool = False,
              max_modes: int = 2000, **model_options: Any) -> CalibrationResult:
    """Fit robot parameters to measured natural frequencies (module notes, theory.md §15.6).

    Parameters
    ----------
    scene_or_robot : Scene or Robot
        The start; a Scene gives its pose too.
    measured : MeasuredModes or array_like of frequencies [Hz], or None
        None: fit the FRF magnitudes ``frf`` alone.
    parameters : str or sequence of str
        Among :data:`PARAMETERS` (module notes).
    pose : Pose or array_like, optional
        Platform pose of the measurement (default: the scene's).
    rung : str
        Model of the cables (:func:`dynstiff.build_model`); ``model_options`` go there.
    pairing : {"mac", "massless"}, optional
        "mac" (default with measured shapes): :func:`dynstiff.analyses.measured.pair_modes`;
        "massless" (default without): the k-th measured mode is the continuation of the k-th
        massless-cable platform mode (:func:`dynstiff.analyses.measured.massless_pairing`).
        "mac" needs measured shapes (InvalidParameterError otherwise).
    confidence : float
        Level of the intervals, in (0, 1).
    bounds : (float, float)
        Range of each factor p / p0 searched.
    xtol, max_nfev : passed to :func:`scipy.optimize.least_squares`
    fmax_factor : float
        The model's modes are computed up to this times the highest measured frequency.
    start : dict, optional
        Start values {name: value} replacing the robot's (needed for a damping parameter the
        robot has at 0).
    frf : FRFResult, optional
        Measured FRFs (:func:`dynstiff.read_measured_frf`): the residuals
        ln |H_model| - ln |H_measured| of every finite entry are appended (a relative
        magnitude error, on the scale of the relative frequency residuals). Undamped
        magnitudes are smooth in the parameters only away from resonances: choose a band
        that no mode of the start or of the measurement enters (e.g. the stiffness line
        below the first mode), and driving-point FRFs: a cross FRF has antiresonances,
        where ln |H| is singular.
    frf_point : array_like, shape (3,), optional
        Platform point of the measured translations [m, platform frame] (default P).
    jacobian : {"auto", "analytic", "differences"}
        The sensitivities dr/du: "analytic" from the eigenfrequency sensitivities (frequency
        residuals of EA, EA_i, mass, inertia, t_min on the rungs "dsm", "exact", "lumped",
        "spring", "catenary"), "differences" by finite differences, "auto" the first where
        it applies.
    max_modes : int
        Most modes of the model computed per evaluation: a measured frequency whose band
        (``fmax_factor`` times it) holds more is refused before the fit, since it is almost
        always a unit error (rad/s or mHz for Hz) or a mode far above the cables' first
        modes, which the model pairs only by chance.
    strict : bool
        Raise a :class:`~dynstiff.errors.CalibrationError` instead of warning when the
        calibration finds fault with itself
        (:mod:`dynstiff.analyses.calibration_checks`). Anything but a bool (e.g. the text
        "no") raises InvalidParameterError.

    Returns
    -------
    CalibrationResult

    Raises
    ------
    InvalidParameterError
        Unknown parameter, bad confidence, more parameters than measured values.
    ConvergenceError
        The least-squares search failed (its message and cost are named).
    CalibrationError
        With ``strict``: an ambiguous pairing, a residual far above the measurement
        uncertainty, or an estimate on a bound.

    Warns
    -----
    CalibrationWarning
        The same findings, without ``strict``.

    Examples
    --------
    >>> import dataclasses
    >>> import dynstiff as ds
    >>> scene = ds.load_scene("cogiro")
    >>> stiffer = dataclasses.replace(scene.robot, cables=tuple(
    ...     dataclasses.replace(c, EA=1.1 * c.EA) for c in scene.robot.cables))
    >>> f = ds.eigenfrequencies(ds.FrequencyModel(stiffer.equilibrium(scene.pose)), n_modes=2)
    >>> cal = ds.calibrate(scene, f)                  # "measured": the cables 10 % stiffer
    >>> print(f"EA x {cal.estimate[0] / cal.initial[0]:.4f}")
    EA x 1.1000
    """
    from scipy.optimize import least_squares
    from scipy.stats import norm
    from scipy.stats import t as student_t
    robot = getattr(scene_or_robot, "robot", scene_or_robot)
    if pose is None:
        pose = getattr(scene_or_robot, "pose", None)
    if pose is None:
        raise InvalidParameterError("calibrate needs the pose of the measurement: give pose= "
                                    "or a scene with a [pose]")
    if measured is None and frf is None:
        raise InvalidParameterError("give measured frequencies, measured FRFs (frf=) or both")
    if measured is not None and not isinstance(measured, MeasuredModes):
        measured = MeasuredModes(measured)
    names = _expand(parameters, robot.n_cables)
    if jacobian not in JACOBIANS:
        raise InvalidParameterError(f"jacobian must be one of {JACOBIANS}, got {jacobian!r}")
    strict = flag("strict", strict)
    analytic = (measured is not None and frf is None and rung in SENSITIVITY_RUNGS
                and not any(nm in _DAMPING for nm in names))
    if jacobian == "analytic" and not analytic:
        raise InvalidParameterError(
            "jacobian='analytic' needs frequency residuals only (no FRF, no damping "
            f"parameter) on one of the rungs {SENSITIVITY_RUNGS}")
    analytic = analytic and jacobian != "differences"
    asked_jacobian = jacobian
    b_lo, b_hi = fit_options(confidence, bounds)
    for name, value in (start or {}).items():
        if name not in names:
            raise InvalidParameterError(f"start names {name!r}, not a fitted parameter {names}")
        robot = _with(robot, [name], [value / _value(robot, name)]) if _value(robot, name) \
            else replace(robot, cables=[replace(c, **{name: value}) for c in robot.cables])
    zero = [nm for nm in names if not _value(robot, nm) > 0]
    if zero:
        raise InvalidParameterError(f"parameters {zero} are 0 in the robot: give start values, "
                                    f"e.g. start={{{zero[0]!r}: 0.01}}")
    damp = [nm for nm in names if nm in _DAMPING]
    if damp and (measured is None or measured.damping_ratio is None) and frf is None:
        raise InvalidParameterError(f"fitting {damp} needs measured damping ratios or FRFs")
    use_zeta = bool(damp) and measured is not None and measured.damping_ratio is not None
    n_modes = 0 if measured is None else len(measured)
    H_meas = None
    if frf is not None:
        H_meas = np.asarray(frf.H)
        frf_ok = np.isfinite(H_meas) & (np.abs(H_meas) > 0)
    m = n_modes * (2 if use_zeta else 1) + (0 if frf is None else int(frf_ok.sum()))
    n = len(names)
    if m < n:
        raise InvalidParameterError(f"{m} measured values cannot fix {n} parameters {names}")
    chosen_pairing = pairing                     # the user's choice: no pairing warning
    if measured is not None:
        scale = measured.sigma_hz if measured.sigma_hz is not None else measured.freq_hz
        pairing = pairing or ("mac" if measured.shapes is not None else "massless")
        if pairing not in ("mac", "massless"):
            raise InvalidParameterError(f"pairing must be 'mac' (measured shapes) or "
                                        f"'massless', got {pairing!r}")
        fmax = fmax_factor * measured.freq_hz.max()
    if isinstance(max_modes, bool) or not isinstance(max_modes, Integral) or max_modes < 1:
        raise InvalidParameterError(f"max_modes must be an integer >= 1, got {max_modes!r}")
    count = [0]
    empty = np.zeros(0)

    def evaluate(u: NDArray[np.float64]) -> dict[str, Any]:
        """Paired frequencies [Hz], MAC, cable shares, damping ratios and the FRF residual
        at ln(factors) u."""
        model = build_model(_with(robot, names, np.exp(u)).equilibrium(pose), rung,
                            **model_options)
        count[0] += 1
        out = {"f": empty, "mac": empty, "share": empty, "zeta": None, "r_frf": empty}
        if measured is not None:
            if count[0] == 1:
                _refuse_too_many_modes(model, measured, fmax, fmax_factor, max_modes)
            md = modes(model, fmax_hz=fmax, max_modes=max_modes)
            if pairing == "mac":
                idx, mac = pair_modes(md, measured, "mac")
            else:
                idx, mac = massless_pairing(md, model, n_modes), np.full(n_modes, np.nan)
            out.update(f=md.freq_hz[idx], mac=mac, modes=md, model=model, idx=idx,
                       share=np.asarray(md.cable_energy_fraction)[idx])
            if use_zeta:
                out["zeta"] = damped_modes(model, fmax_hz=fmax).damping_ratio[idx]
        if frf is not None:
            Hm = frf_of(model, 2 * np.pi * frf.freq_hz, inputs=list(frf.inputs),
                        outputs=list(frf.outputs), point=frf_point, kind=frf.kind).H
            out["r_frf"] = np.log(np.abs(Hm[frf_ok]) / np.abs(H_meas[frf_ok]))
        r = [out["f"] - (measured.freq_hz if measured is not None else 0.0)]
        if measured is not None:
            r[0] = r[0] / scale
        if use_zeta:
            r.append(out["zeta"] / measured.damping_ratio - 1.0)
        r.append(out["r_frf"])
        out["r"] = np.concatenate(r)
        return out

    last_eval = {}

    def residual(u: NDArray[np.float64]) -> NDArray[np.float64]:
        out = evaluate(u)
        last_eval.update(u=np.array(u, dtype=float), r=out["r"], out=out)
        return out["r"]

    def analytic_jacobian(out: dict[str, Any]) -> NDArray[np.float64]:
        """dr/du = p df/dp / s of the paired modes, from the evaluation ``out``
        (theory.md §16.5)."""
        idx = out["idx"]
        f = out["modes"].freq_hz[:int(np.max(idx)) + 1]
        sens = sensitivities_at(out["model"], f, list(names))
        return sens.derivative[idx] * sens.values[None, :] / np.asarray(scale)[:, None]

    def jacobian(u: NDArray[np.float64], h: float = 1e-4,
                 central: bool = False) -> NDArray[np.float64]:
        """Analytic (from the evaluation at u), else differences in ln p with a step far
        above the statics' tolerance (1e-10): forward (reusing the residual just evaluated
        at u) during the search, central for the sensitivities at the estimate."""
        nonlocal analytic
        if analytic:
            if not np.array_equal(last_eval.get("u"), u):
                residual(u)
            try:
                return analytic_jacobian(last_eval["out"])
            except InvalidParameterError:
                # the statics' derivative is singular (e.g. cables exactly at t_min):
                # "auto" falls back to differences, "analytic" says so
                if asked_jacobian == "analytic":
                    raise
                analytic = False
        if central:
            return np.column_stack([(residual(u + h * e) - residual(u - h * e)) / (2 * h)
                                    for e in np.eye(n)])
        r0 = last_eval["r"] if np.array_equal(last_eval.get("u"), u) else residual(u)
        u = np.array(u, dtype=float)
        return np.column_stack([(residual(u + h * e) - r0) / h for e in np.eye(n)])

    u0 = np.zeros(n)
    first = evaluate(u0)
    lo, hi = np.log(b_lo), np.log(b_hi)
    sol = least_squares(residual, u0, jac=jacobian, bounds=(np.full(n, lo), np.full(n, hi)),
                        xtol=xtol, max_nfev=max_nfev)
    if sol.status <= 0:
        raise ConvergenceError(f"calibration did not converge: {sol.message} (cost "
                               f"{sol.cost:.3g} after {sol.nfev} evaluations)")
    if not np.array_equal(last_eval.get("u"), sol.x):
        residual(sol.x)
    last = last_eval["out"]
    if not np.all(np.isfinite(last["r"])):
        raise ConvergenceError(f"calibration: a residual is not finite at the estimate (a "
                               f"paired mode without a damped root, or an FRF pole): "
                               f"{last['r']}")
    J = jacobian(sol.x, central=True)   # sensitivities at the estimate
    dof = m - n
    sigmas = measured is not None and measured.sigma_hz is not None and not use_zeta \
        and frf is None
    if sigmas:
        s2, q = 1.0, norm.ppf(0.5 + confidence / 2)
    elif dof > 0:
        s2, q = 2 * sol.cost / dof, student_t.ppf(0.5 + confidence / 2, dof)
    else:
        s2, q = np.nan, np.nan
    try:
        se = np.sqrt(np.diag(s2 * np.linalg.inv(J.T @ J)))
    except np.linalg.LinAlgError:
        se = np.full(n, np.nan)
    p0 = np.array([_value(robot, nm) for nm in names])
    with np.errstate(over="ignore"):      # a parameter the data do not fix: an infinite bound
        ci_low, ci_high = p0 * np.exp(sol.x - q * se), p0 * np.exp(sol.x + q * se)
    report_findings(calibration_findings(
        measured, last["f"], (pairing if chosen_pairing is None else "chosen")
        if measured is not None else None,
        [first.get("modes"), last.get("modes")] if measured is not None else [], names,
        sol.x, (b_lo, b_hi)), strict)
    return CalibrationResult(
        parameters=names, initial=p0, estimate=p0 * np.exp(sol.x),
        ci_low=ci_low, ci_high=ci_high,
        confidence=confidence,
        measured_hz=empty if measured is None else measured.freq_hz,
        initial_hz=first["f"], fitted_hz=last["f"], mac=last["mac"],
        cable_fraction=last["share"], robot=_with(robot, names, np.exp(sol.x)),
        n_evaluations=count[0], jacobian=J,
        measured_damping=measured.damping_ratio if use_zeta else None,
        fitted_damping=last["zeta"],
        frf_log_error=None if frf is None else float(np.sqrt(np.mean(last["r_frf"]**2))),
        jacobian_kind="analytic" if analytic else "differences")
