"""What a calibration says about itself (theory.md §12.6): whether its pairing of measured
and model modes was ambiguous, whether its residuals stand far above the measurement
uncertainty, and whether an estimate sits on its search bound. Each finding is a
:class:`~dynstiff.errors.CalibrationWarning` naming the mode or parameter and what to give
(or a :class:`~dynstiff.errors.CalibrationError` when asked to be strict).
"""

import warnings
from numbers import Real

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.errors import (
    CalibrationError,
    CalibrationWarning,
    InvalidParameterError,
    user_stacklevel,
)

__all__ = ["DEFAULT_RELATIVE_UNCERTAINTY", "RESIDUAL_LIMIT", "calibration_findings",
           "fit_options",
           "report_findings"]

#: Relative standard uncertainty of a measured frequency without ``sigma [Hz]`` [-].
DEFAULT_RELATIVE_UNCERTAINTY = 0.01
#: A residual above this many standard uncertainties is reported [-].
RESIDUAL_LIMIT = 3.0


def calibration_findings(measured, fitted_hz, pairing, model_modes, parameters, u, bounds):
    """The findings (cause, message) of a calibration.

    Parameters
    ----------
    measured : MeasuredModes or None
    fitted_hz : ndarray, shape (n,)
        The paired model frequencies at the estimate [Hz].
    pairing : str or None
        "mac", "massless" (the default without shapes) or "chosen" (a pairing the caller
        chose: not reported as ambiguous); None without measured modes.
    model_modes : list of ModalResult
        The model's modes at the start and at the estimate.
    parameters : tuple of str
    u : ndarray, shape (n_par,)
        ln(estimate / start).
    bounds : (float, float)
        The factors searched.

    Returns
    -------
    list of (str, str)
    """
    out = []
    if measured is not None and pairing == "massless":
        top = 1.05 * measured.freq_hz.max()
        for when, md in zip(("start", "estimate"), model_modes):
            f = np.asarray(md.freq_hz)
            local = np.flatnonzero((np.asarray(md.kind) != "global") & (f <= top))
            if local.size:
                out.append(("pairing", (
                    f"the measured frequencies (up to {measured.freq_hz.max():.4g} Hz) lie "
                    f"among {local.size} cable-dominated modes of the model at the {when} "
                    f"(from {f[local[0]]:.4g} Hz) and were paired without shapes: a measured "
                    f"mode may be a cable mode; give the measured platform shapes (pairing by "
                    f"MAC), choose the pairing (pairing=), or measure below "
                    f"{f[local[0]]:.4g} Hz")))
                break
    if measured is not None and len(fitted_hz):
        sigma = (measured.sigma_hz if measured.sigma_hz is not None
                 else DEFAULT_RELATIVE_UNCERTAINTY * measured.freq_hz)
        z = np.abs(fitted_hz - measured.freq_hz) / sigma
        k = int(np.argmax(z))
        if z[k] > RESIDUAL_LIMIT:
            stated = "its sigma" if measured.sigma_hz is not None else (
                f"the {DEFAULT_RELATIVE_UNCERTAINTY:.0%} assumed without sigma [Hz]")
            out.append(("residual", (
                f"measured mode {k + 1}: fitted {fitted_hz[k]:.5g} Hz against "
                f"{measured.freq_hz[k]:.5g} Hz measured, {z[k]:.3g} times {stated}: the "
                f"model does not explain it (check the pairing, the pose, the band, or fit "
                f"another parameter)")))
    lo, hi = np.log(bounds[0]), np.log(bounds[1])
    for name, x in zip(parameters, u):
        for edge, factor in ((lo, bounds[0]), (hi, bounds[1])):
            if abs(x - edge) <= 1e-6 * max(1.0, abs(edge)):
                out.append(("bound", (
                    f"{name} sits on its search bound ({factor:g} times its start): the data "
                    f"do not fix it within bounds={tuple(bounds)}; check the pairing and the "
                    f"measured modes, or widen the bounds")))
    return out


def report_findings(findings, strict=False):
    """Warn (CalibrationWarning) for each finding, or raise a CalibrationError naming the
    first when ``strict``."""
    for cause, message in findings:
        if strict:
            raise CalibrationError(f"calibration: {message}", cause=cause)
        warnings.warn(CalibrationWarning(f"calibration: {message}", cause=cause),
                      stacklevel=user_stacklevel())


def fit_options(confidence, bounds):
    """The search bounds (low, high) of a calibration's factors, checked with its confidence
    level (0 < confidence < 1; 0 < low < 1 < high: the start, factor 1, inside); a bool is
    not a number. Raises InvalidParameterError naming the argument."""
    if (isinstance(confidence, (bool, np.bool_)) or not isinstance(confidence, Real)
            or not 0 < confidence < 1):
        raise InvalidParameterError(f"confidence must be in (0, 1), got {confidence!r}")
    try:
        lo, hi = (positive_scalar("bounds", b) for b in bounds)
    except (TypeError, ValueError):
        lo = hi = np.nan
    if not lo < 1 < hi:
        raise InvalidParameterError(f"bounds must be (low, high) factors of the start with "
                                    f"0 < low < 1 < high, got {bounds!r}")
    return lo, hi
