"""The calibration's result (dynstiff/analyses/calibration_result.py): its one-line summary,
its Jupyter tables, its text report and its figure say exactly what it holds (a result built
by hand, so every number is known)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest

from dynstiff._html import html_table
from dynstiff.analyses.calibration_result import CalibrationResult


def result(**kw):
    base = dict(parameters=("EA", "mass"), initial=np.array([1.0e6, 50.0]),
                estimate=np.array([1.2e6, 55.0]), ci_low=np.array([1.1e6, 52.0]),
                ci_high=np.array([1.3e6, 58.0]), confidence=0.9,
                measured_hz=np.array([2.0, 4.0, 5.0]), initial_hz=np.array([1.9, 4.2, 5.5]),
                fitted_hz=np.array([2.02, 3.96, 5.0]), mac=np.array([0.99, 0.95, np.nan]),
                cable_fraction=np.array([0.1, 0.2, 0.3]), robot=None, n_evaluations=17,
                jacobian=np.zeros((3, 2)))
    base.update(kw)
    return CalibrationResult(**base)


def test_the_summary_line_names_every_estimate_its_interval_and_the_residuals():
    r = result()
    rms = np.sqrt(np.mean(np.array([0.01, -0.01, 0.0]) ** 2))
    assert repr(r) == (
        "CalibrationResult(EA = 1.2e+06 [1.1e+06, 1.3e+06], mass = 55 [52, 58] (90 %), "
        f"rms frequency residual {rms:.3g}, 17 evaluations)")
    frf = result(frf_log_error=0.0123)
    assert repr(frf).endswith(f"rms frequency residual {rms:.3g}, rms ln|H| residual "
                              "0.0123, 17 evaluations)")
    only_frf = result(measured_hz=np.zeros(0), initial_hz=np.zeros(0), fitted_hz=np.zeros(0),
                      mac=np.zeros(0), cable_fraction=np.zeros(0), frf_log_error=0.5)
    assert "(90 %), rms ln|H| residual 0.5, 17 evaluations)" in repr(only_frf)
    none = result(measured_hz=np.zeros(0), initial_hz=np.zeros(0), fitted_hz=np.zeros(0),
                  mac=np.zeros(0), cable_fraction=np.zeros(0))
    assert "(90 %), , 17 evaluations)" in repr(none)


def test_the_jupyter_tables_hold_the_parameters_and_the_modes():
    r = result()
    pars = html_table(repr(r), ["parameter", "initial", "estimate", "ci low", "ci high"],
                      [("EA", 1.0e6, 1.2e6, 1.1e6, 1.3e6), ("mass", 50.0, 55.0, 52.0, 58.0)])
    modes = html_table("modes", ["mode", "measured [Hz]", "fitted [Hz]", "residual [-]",
                                 "MAC"],
                       [(k + 1, m, f, f / m - 1, c) for k, (m, f, c) in
                        enumerate(zip(r.measured_hz, r.fitted_hz, r.mac))])
    assert r._repr_html_() == pars + modes


def test_the_text_report_lists_the_estimates_then_the_modes():
    lines = result().text().splitlines()
    assert lines[0] == (f"{'parameter':<10} {'initial':>12} {'estimate':>12} "
                        f"{'ci low':>12} {'ci high':>12}")
    assert lines[1] == f"{'EA':<10} {1e6:12.6g} {1.2e6:12.6g} {1.1e6:12.6g} {1.3e6:12.6g}"
    assert lines[3] == "(90 % confidence)"
    assert lines[4].split()[:3] == ["mode", "measured", "[Hz]"]


def test_the_figure_shows_the_errors_before_and_after_side_by_side():
    r = result()
    fig = r.plot()
    ax = fig.axes[0]
    initial, fitted = ax.containers
    np.testing.assert_allclose([b.get_height() for b in initial],
                               100 * (r.initial_hz / r.measured_hz - 1), rtol=1e-12)
    np.testing.assert_allclose([b.get_height() for b in fitted], 100 * r.residual,
                               rtol=1e-12)
    np.testing.assert_allclose([b.get_x() + b.get_width() / 2 for b in initial],
                               [0.8, 1.8, 2.8], rtol=1e-12)
    np.testing.assert_allclose([b.get_x() + b.get_width() / 2 for b in fitted],
                               [1.2, 2.2, 3.2], rtol=1e-12)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["initial", "fitted"]
    assert ax.get_xlabel() == "measured mode"
    assert ax.get_ylabel() == "model / measured - 1 [%]"
    assert list(ax.get_xticks()) == [1, 2, 3]
    zero = [ln for ln in ax.get_lines() if list(ln.get_ydata()) == [0, 0]]
    assert len(zero) == 1 and zero[0].get_color() == "0.4"
    assert zero[0].get_linewidth() == pytest.approx(0.8)


def test_the_table_has_one_row_per_mode_and_the_damping_when_fitted():
    df = result().to_frame()
    assert list(df.columns) == ["mode", "measured [Hz]", "initial [Hz]", "fitted [Hz]",
                                "residual [-]", "MAC [-]", "cable energy fraction [-]"]
    np.testing.assert_allclose(df["residual [-]"], [0.01, -0.01, 0.0], atol=1e-15)
    np.testing.assert_array_equal(df["fitted [Hz]"], [2.02, 3.96, 5.0])
    damped = result(measured_damping=np.array([0.01, 0.02, 0.03]),
                    fitted_damping=np.array([0.011, 0.019, 0.03])).to_frame()
    np.testing.assert_array_equal(damped["measured damping ratio [-]"], [0.01, 0.02, 0.03])
    np.testing.assert_array_equal(damped["fitted damping ratio [-]"], [0.011, 0.019, 0.03])
