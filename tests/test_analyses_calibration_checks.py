"""What a calibration says about itself (dynstiff/analyses/calibration_checks.py): the
ambiguous pairing among cable modes, the residual beyond the measurement's uncertainty and
the estimate on its bound, each at its threshold, with hand-made modes and residuals."""

from types import SimpleNamespace

import numpy as np
import pytest

from dynstiff.analyses.calibration_checks import (
    DEFAULT_RELATIVE_UNCERTAINTY,
    RESIDUAL_LIMIT,
    calibration_findings,
)
from dynstiff.analyses.measured import MeasuredModes


def modes(freq, kind):
    return SimpleNamespace(freq_hz=np.array(freq), kind=tuple(kind))


def findings(measured, fitted, pairing="massless", model_modes=(), u=(0.0,), bounds=(0.1, 10)):
    return calibration_findings(measured, np.asarray(fitted, dtype=float), pairing,
                                list(model_modes), ("EA",), np.array(u), bounds)


def test_pairing_without_shapes_among_cable_modes_names_them_at_the_start_or_the_estimate():
    measured = MeasuredModes([2.0, 3.0])
    top = 1.05 * 3.0                                       # cable modes up to here count
    clean = modes([2.0, 3.0, 5.0], ["global", "global", "local"])
    start = modes([2.0, 2.5, 2.7, 3.0], ["global", "local", "local", "global"])
    (cause, msg), = findings(measured, [2.0, 3.0], model_modes=[start, clean])
    assert cause == "pairing"
    assert "among 2 cable-dominated modes of the model at the start (from 2.5 Hz)" in msg
    assert msg.endswith("or measure below 2.5 Hz")
    at_top = modes([2.0, 3.0, top], ["global", "global", "local"])
    (cause, msg), = findings(measured, [2.0, 3.0], model_modes=[clean, at_top])
    assert f"among 1 cable-dominated modes of the model at the estimate (from {top:.4g} Hz)" \
        in msg
    assert findings(measured, [2.0, 3.0], model_modes=[clean, clean]) == []
    assert findings(measured, [2.0, 3.0], "mac", model_modes=[start, start]) == []


def test_a_residual_is_reported_beyond_three_uncertainties_not_at_three():
    with_sigma = MeasuredModes([1.0, 2.0], sigma_hz=[0.25, 0.25])
    assert RESIDUAL_LIMIT == 3.0
    assert findings(with_sigma, [1.75, 2.0], "mac") == []            # exactly 3 sigma
    (cause, msg), = findings(with_sigma, [1.0, 2.8], "mac")
    assert cause == "residual"
    assert msg.startswith("measured mode 2: fitted 2.8 Hz against 2 Hz measured, 3.2 times "
                          "its sigma:")
    # without sigma: 1 % of the frequency; the same fit is then far off
    (cause, msg), = findings(MeasuredModes([1.0, 2.0]), [1.0, 2.1], "mac")
    assert DEFAULT_RELATIVE_UNCERTAINTY == 0.01
    assert "5 times the 1% assumed without sigma [Hz]:" in msg
    # a sigma of its own decides, not the 1 %: 0.1 Hz off with sigma 0.25 Hz is fine
    assert findings(MeasuredModes([1.0, 2.0], sigma_hz=0.25), [1.0, 2.1], "mac") == []


def test_without_measured_modes_only_the_bounds_are_judged():
    assert findings(None, [2.0], None) == []
    (cause, msg), = findings(None, [], None, u=[np.log(10.0)])
    assert cause == "bound"
    assert msg.startswith("EA sits on its search bound (10 times its start)")


@pytest.mark.parametrize("u", [np.log(0.1), np.log(10.0) * (1 - 1e-7)])
def test_an_estimate_on_or_within_rounding_of_a_bound_is_reported(u):
    (cause, _), = findings(None, [], None, u=[u])
    assert cause == "bound"
    assert findings(None, [], None, u=[u * 0.99]) == []


def test_the_bound_finding_names_the_bound_and_keeps_to_its_tolerance():
    """Within 1e-6 max(1, |ln bound|) of ln(bound), and no further."""
    (_, msg), = findings(None, [], None, u=[np.log(0.1)])
    assert msg.startswith("EA sits on its search bound (0.1 times its start)")
    edge = np.log(10.0)                                   # tolerance 1e-6 x 2.30
    assert len(findings(None, [], None, u=[edge - 2.0e-6])) == 1
    assert findings(None, [], None, u=[edge - 2.5e-6]) == []
    small = np.log(2.0)                                   # |edge| < 1: tolerance 1e-6
    assert len(findings(None, [], None, u=[small - 0.9e-6], bounds=(0.5, 2.0))) == 1
    assert findings(None, [], None, u=[small - 1.5e-6], bounds=(0.5, 2.0)) == []
    assert findings(None, [], None, u=[-small + 1.5e-6], bounds=(0.5, 2.0)) == []


def test_fit_options_refuse_what_is_not_a_confidence_or_a_bracket_of_the_start():
    from dynstiff.analyses.calibration_checks import fit_options
    from dynstiff.errors import InvalidParameterError
    assert fit_options(0.95, (0.5, 1.5)) == (0.5, 1.5)
    for bad in (0.0, 1.0, 1.5, True, "x", None):
        with pytest.raises(InvalidParameterError, match="confidence must be in \\(0, 1\\)"):
            fit_options(bad, (0.5, 2.0))
    for bad in ((1.0, 2.0), (0.5, 1.0), ("a", 2.0), (-1.0, 2.0), (0.5,)):
        with pytest.raises(InvalidParameterError,
                           match=r"bounds must be \(low, high\) factors of the start with "
                                 r"0 < low < 1 < high, got"):
            fit_options(0.95, bad)


def test_strict_findings_raise_the_first_with_its_cause():
    from dynstiff.analyses.calibration_checks import report_findings
    from dynstiff.errors import CalibrationError, CalibrationWarning
    found = [("residual", "mode 2 off"), ("bound", "EA on its bound")]
    with pytest.raises(CalibrationError, match="calibration: mode 2 off") as err:
        report_findings(found, strict=True)
    assert err.value.cause == "residual"
    with pytest.warns(CalibrationWarning) as caught:
        report_findings(found)
    assert [w.message.cause for w in caught] == ["residual", "bound"]
