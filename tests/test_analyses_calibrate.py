"""Calibration (dynstiff/analyses/calibrate.py, theory.md §15.6): a known EA recovered from noisy
synthetic frequencies of the model itself (within the reported interval), and from the
frequencies of the independent lumped model, whose discretisation bias falls at the rate of
its convergence (O(1/N^2)); per-cable EA and platform mass; bad requests named."""

import warnings
from dataclasses import replace

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.calibrate import calibrate
from dynstiff.analyses.measured import MeasuredModes, massless_pairing
from dynstiff.errors import ClosedFormWarning

AREA = 8.2051e-6          # CoGiRo cable cross-section [m^2] (theory.md §8.1)
E_TRUE = 60e9             # [Pa], inside CoGiRo's 17-120 GPa


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def with_E(robot, E):
    return replace(robot, cables=[replace(c, EA=AREA * E) for c in robot.cables])


def platform_frequencies(robot, pose, rung, n, **kw):
    """The first n platform modes of a rung, continued from the massless-cable modes."""
    m = ds.build_model(robot.equilibrium(pose), rung, **kw)
    md = ds.modes(m, fmax_hz=12.0)
    return md.freq_hz[massless_pairing(md, m, n)]


def test_recovers_EA_from_noisy_synthetic_frequencies(scene):
    f = platform_frequencies(with_E(scene.robot, E_TRUE), scene.pose, "dsm", 4)
    noisy = f * (1 + 0.003 * np.random.default_rng(1).standard_normal(f.size))
    # frequencies alone among cable modes: the right pairing here, but warned (it may not be)
    with pytest.warns(ds.CalibrationWarning, match="paired without shapes"):
        res = calibrate(scene, noisy, parameters="EA")      # starts at 17 GPa
    E, lo, hi = res.estimate[0] / AREA, res.ci_low[0] / AREA, res.ci_high[0] / AREA
    assert lo < E_TRUE < hi
    assert abs(E / E_TRUE - 1) < 0.01 and hi / lo - 1 < 0.03
    assert np.sqrt(np.mean(res.residual**2)) < 0.005       # the noise level, 0.3 %
    assert np.all(np.abs(res.initial_hz / noisy - 1) > 0.3)  # 17 GPa was far off
    assert res.robot.cables[3].EA == pytest.approx(res.estimate[0])
    df = res.to_frame()
    assert list(df["mode"]) == [1, 2, 3, 4] and "cable energy fraction [-]" in df


def test_recovers_EA_from_the_independent_lumped_model(scene):
    """The lumped model (40 segments per cable) is an independent discretisation: the EA the
    closed-form model fits to its first 3 platform frequencies is within 3e-4 of the true
    one, inside the reported interval."""
    f = platform_frequencies(with_E(scene.robot, E_TRUE), scene.pose, "lumped", 3,
                             segments=40)
    with pytest.warns(ds.CalibrationWarning, match="paired without shapes"):
        res = calibrate(scene, f, parameters="EA")
    assert abs(res.estimate[0] / AREA / E_TRUE - 1) < 3e-4
    assert res.ci_low[0] / AREA < E_TRUE < res.ci_high[0] / AREA


@pytest.mark.slow
def test_lumped_calibration_bias_falls_at_the_convergence_rate(scene):
    """The fitted EA's error is the lumped model's discretisation error: 3.8e-4 at N = 20,
    1.2e-4 at N = 40, the 1/N^2 rate of theory.md §7 (ratio 3.2 of the ideal 4)."""
    truth = with_E(scene.robot, E_TRUE)
    err = []
    for N in (20, 40):
        f = platform_frequencies(truth, scene.pose, "lumped", 3, segments=N)
        with pytest.warns(ds.CalibrationWarning, match="paired without shapes"):
            err.append(calibrate(scene, f, parameters="EA").estimate[0] / AREA / E_TRUE - 1)
    assert abs(err[0]) < 1e-3 and abs(err[1]) < 0.4 * abs(err[0])


def test_mass_and_measured_shapes(scene):
    """Platform mass from 4 frequencies with shapes (MAC pairing), sigma-weighted: the
    interval uses the given sigmas (normal quantile)."""
    r = scene.robot
    truth = replace(r, platform=replace(r.platform, mass=100.0))
    m = ds.build_model(truth.equilibrium(scene.pose), "catenary")
    md = ds.modes(m, n_modes=4)
    meas = MeasuredModes(md.freq_hz, shapes=md.platform_shapes, sigma_hz=0.002 * md.freq_hz)
    res = calibrate(scene, meas, parameters=["mass"], rung="catenary")
    assert res.estimate[0] == pytest.approx(100.0, rel=1e-6)
    assert res.ci_low[0] < 100.0 < res.ci_high[0]
    np.testing.assert_allclose(res.mac, 1.0, atol=1e-9)


def test_the_analytic_jacobian_gives_the_same_fit_with_a_third_of_the_evaluations(scene):
    """theory.md §16.5: EA and the platform mass from 6 platform frequencies. The analytic
    Jacobian (the eigenfrequency sensitivities of each evaluation) and the differences find
    the same estimate and interval; the differences cost n (forward) and 2 n (central, at
    the estimate) evaluations per Jacobian: 30 evaluations against 9 (measured)."""
    true = replace(with_E(scene.robot, E_TRUE), platform=replace(scene.robot.platform,
                                                                 mass=100.0))
    f = platform_frequencies(true, scene.pose, "dsm", 6)
    # 6 frequencies without shapes reach CoGiRo's cable modes: the pairing warning is
    # expected and is not this test's subject
    with pytest.warns(ds.CalibrationWarning, match="paired without shapes"):
        a = calibrate(scene, f, parameters=["EA", "mass"], jacobian="analytic")
    with pytest.warns(ds.CalibrationWarning, match="paired without shapes"):
        d = calibrate(scene, f, parameters=["EA", "mass"], jacobian="differences")
    assert (a.jacobian_kind, d.jacobian_kind) == ("analytic", "differences")
    np.testing.assert_allclose(a.estimate, [AREA * E_TRUE, 100.0], rtol=1e-6)
    np.testing.assert_allclose(a.estimate, d.estimate, rtol=1e-7)
    # the central differences (step 1e-4 in ln p) carry a truncation error of about 3e-5
    np.testing.assert_allclose(a.jacobian, d.jacobian, rtol=1e-4, atol=1e-9)
    assert a.n_evaluations <= 10 and d.n_evaluations >= 2.5 * a.n_evaluations


def test_bad_requests_are_named(scene):
    with pytest.raises(ds.InvalidParameterError, match="'stiffness' is not one of"):
        calibrate(scene, [1.0, 2.0], parameters="stiffness")
    with pytest.raises(ds.InvalidParameterError, match="1 measured values cannot fix 2"):
        calibrate(scene, [2.2], parameters=["EA", "mass"])
    with pytest.raises(ds.InvalidParameterError, match="name a quantity twice"):
        calibrate(scene, [2.2, 2.4, 3.0], parameters=["EA", "EA_1"])
    with pytest.raises(ds.InvalidParameterError, match="needs the pose"):
        calibrate(scene.robot, [2.2], parameters="EA")
    with pytest.raises(ds.InvalidParameterError, match="confidence must be in"):
        calibrate(scene, [2.2], confidence=95)
    with pytest.raises(ds.InvalidParameterError, match="jacobian='analytic' needs"):
        calibrate(scene, [2.2], parameters="EA", rung="dsm", jacobian="analytic",
                  frf=object())


def test_loss_factor_from_measured_damping_ratios(scene):
    """The cables' loss factor from the damping ratios of 3 platform modes (2 % error on
    each): 0.02 recovered within its interval; a damping parameter needs a start when the
    robot has none, and measured ratios."""
    r = scene.robot
    truth = replace(r, cables=[replace(c, loss_factor=0.02) for c in r.cables])
    m = ds.build_model(truth.equilibrium(scene.pose), "dsm")
    md = ds.modes(m, fmax_hz=6.0)
    idx = massless_pairing(md, m, 3)
    zeta = ds.damped_modes(m, fmax_hz=6.0).damping_ratio[idx]
    noisy = zeta * (1 + 0.02 * np.array([1, -1, 0.5]))
    meas = MeasuredModes(md.freq_hz[idx], damping_ratio=noisy)
    res = calibrate(scene, meas, parameters="loss_factor", start={"loss_factor": 0.005})
    assert res.ci_low[0] < 0.02 < res.ci_high[0]
    assert res.estimate[0] == pytest.approx(0.02, rel=0.02)
    assert "fitted damping ratio [-]" in res.to_frame()
    with pytest.raises(ds.InvalidParameterError, match="are 0 in the robot: give start"):
        calibrate(scene, meas, parameters="loss_factor")
    with pytest.raises(ds.InvalidParameterError, match="needs measured damping ratios"):
        calibrate(scene, meas.freq_hz, parameters="loss_factor", start={"loss_factor": 0.01})


def test_EA_from_measured_frf_magnitudes(scene):
    """FRF magnitudes alone (the driving point fz -> z from 0.1 to 1.5 Hz, below the first
    mode of both the 17 GPa start (2.2 Hz) and the 60 GPa truth, 2 % noise on each
    magnitude): the log-magnitude residuals fix EA within its interval."""
    truth = with_E(scene.robot, E_TRUE)
    model = ds.build_model(truth.equilibrium(scene.pose), "dsm")
    f = np.linspace(0.1, 1.5, 30)
    res = ds.frf(model, 2 * np.pi * f, inputs="fz", outputs="z")
    noise = 1 + 0.02 * np.random.default_rng(3).standard_normal(res.H.shape)
    meas = ds.FRFResult(res.freq_hz, res.H * noise, res.inputs, res.outputs, res.kind)
    fit = calibrate(scene, None, parameters="EA", frf=meas)
    lo, hi = fit.ci_low[0] / AREA, fit.ci_high[0] / AREA
    assert lo < E_TRUE < hi and hi / lo - 1 < 0.05
    assert 0.01 < fit.frf_log_error < 0.03                       # the 2 % noise
    assert fit.measured_hz.size == 0 and "ln|H|" in repr(fit)
    with pytest.raises(ds.InvalidParameterError, match="give measured frequencies"):
        calibrate(scene, None)


def test_calibration_warns_when_it_paired_cable_modes_without_shapes(scene):
    """The first 6 modes of CoGiRo at 60 GPa are cable-dominated (4 local, 2 mixed): fitted
    from their frequencies alone, EA comes out far off, and the calibration says so, naming
    the pairing and the residual (and, strict, refuses)."""
    rob = with_E(scene.robot, E_TRUE)
    md = ds.modes(ds.FrequencyModel(rob.equilibrium(scene.pose)), 6)
    assert "global" not in md.kind
    with pytest.warns(ds.CalibrationWarning) as rec:
        res = calibrate(scene, md.freq_hz, parameters="EA")
    causes = {w.message.cause for w in rec}
    assert {"pairing", "residual"} <= causes
    assert abs(res.estimate[0] / (AREA * E_TRUE) - 1) > 0.02        # wrong, and said so
    assert any("give the measured platform shapes" in str(w.message) for w in rec)
    with pytest.raises(ds.CalibrationError, match="paired without shapes"):
        calibrate(scene, md.freq_hz, parameters="EA", strict=True)


def test_calibration_from_dynstiffs_own_modes_table_reads_its_shapes(scene, tmp_path):
    """dynstiff's modes table (shape columns with their units in the headers, metadata
    lines) reads back with its shapes: the six platform modes of CoGiRo at 60 GPa (one of
    them mixed), measured with 1e-4 noise, give EA exact to the noise by MAC pairing from a
    start at 17 GPa, with no warning."""
    import warnings

    from dynstiff.analyses.platform_modes import find_platform_modes
    from dynstiff.report.robot import write_csv
    m = ds.FrequencyModel(with_E(scene.robot, E_TRUE).equilibrium(scene.pose))
    pm = find_platform_modes(m)
    md = ds.modes(m, fmax_hz=pm.searched_hz)
    table = md.to_frame().iloc[pm.index].copy()
    table["freq [Hz]"] *= 1 + 1e-4 * np.random.default_rng(3).standard_normal(len(table))
    write_csv(table, tmp_path / "modes.csv", {"scene": "cogiro"})
    measured = ds.read_measured_modes(tmp_path / "modes.csv")
    assert measured.shapes is not None and "mixed" in table["kind"].tolist()
    np.testing.assert_allclose(measured.shapes, md.platform_shapes[pm.index], rtol=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = calibrate(scene, measured, parameters="EA")
    assert abs(res.estimate[0] / (AREA * E_TRUE) - 1) < 2e-4
    assert np.all(res.mac > 0.999)


def test_calibration_on_a_bound_and_far_residual_says_so(scene):
    """A "measured" mode at 40 Hz cannot be CoGiRo's first platform mode (2.2 Hz; 22 Hz at
    100 times its EA): EA runs to its bound (100 times the start) and the residual stays far
    above the uncertainty, both reported; with two true modes beside it, the residual."""
    f = platform_frequencies(scene.robot, scene.pose, "dsm", 2)
    with pytest.warns(ds.CalibrationWarning) as rec:
        res = calibrate(scene, [40.0], parameters="EA")
    assert res.estimate[0] == pytest.approx(100 * scene.robot.cables[0].EA, rel=1e-6)
    assert {"bound", "residual"} <= {w.message.cause for w in rec}
    with pytest.warns(ds.CalibrationWarning) as rec:
        calibrate(scene, np.r_[f, 40.0], parameters="EA")
    assert "residual" in {w.message.cause for w in rec}


def _platform_modes_measured(robot, pose, sigma=None):
    """The platform modes of the closed form at ``pose``, measured with their shapes."""
    from dynstiff.analyses.platform_modes import find_platform_modes
    pm = find_platform_modes(ds.FrequencyModel(robot.equilibrium(pose)))
    f = pm.modes.freq_hz[pm.index[:3]]
    return MeasuredModes(f, shapes=pm.modes.platform_shapes[pm.index[:3]],
                         sigma_hz=None if sigma is None else sigma * f)


def test_confidence_interval_width_is_the_linear_one(scene):
    """With stated sigmas (1 % of each frequency) the 95 % interval of ln EA is
    +- 1.96 / sqrt(sum_k (d f_k / d ln EA / sigma_k)^2), the sensitivities taken here by
    central differences of independent solves (not the calibration's own Jacobian)."""
    from scipy.stats import norm
    truth = with_E(scene.robot, E_TRUE)
    meas = _platform_modes_measured(truth, scene.pose, sigma=0.01)
    res = calibrate(scene, meas, parameters="EA")
    h = 1e-4
    up = _platform_modes_measured(with_E(scene.robot, E_TRUE * np.exp(h)), scene.pose)
    down = _platform_modes_measured(with_E(scene.robot, E_TRUE * np.exp(-h)), scene.pose)
    dfdu = (up.freq_hz - down.freq_hz) / (2 * h)
    half = norm.ppf(0.975) / np.sqrt(np.sum((dfdu / meas.sigma_hz) ** 2))
    assert np.log(res.ci_high[0] / res.estimate[0]) == pytest.approx(half, rel=1e-3)
    assert np.log(res.estimate[0] / res.ci_low[0]) == pytest.approx(half, rel=1e-3)
    assert abs(res.estimate[0] / (AREA * E_TRUE) - 1) < 1e-5


def test_fits_the_least_tension(scene):
    """t_min moves the tension distribution (the one closest to t_min): frequencies of the
    robot with t_min = 150 N (the scene has 100 N) give it back within 1e-3."""
    truth = replace(scene.robot, tension_limits=(150.0, scene.robot.tension_limits[1]))
    meas = _platform_modes_measured(truth, scene.pose)
    res = calibrate(scene, meas, parameters="t_min")
    assert res.estimate[0] == pytest.approx(150.0, rel=1e-3)
    assert res.robot.tension_limits[0] == pytest.approx(res.estimate[0])


def test_rich_display_holds_the_estimate_and_the_residuals(scene):
    from conftest import assert_valid_html
    f = platform_frequencies(with_E(scene.robot, E_TRUE), scene.pose, "dsm", 4)
    with pytest.warns(ds.CalibrationWarning, match="paired without shapes"):
        res = calibrate(scene, f, parameters="EA")
    text = assert_valid_html(res._repr_html_())
    assert f"{res.estimate[0]:.5g}" in text and f"{res.ci_low[0]:.5g}" in text
    assert f"{res.measured_hz[2]:.5g}" in text and f"{res.residual[1]:.5g}" in text


def test_a_singular_statics_derivative_falls_back_to_differences():
    """The pendulum's cables both sit exactly at t_min (a degenerate active set): the
    statics' derivative of the analytic Jacobian is singular (theory.md §16.2). "auto"
    then fits by differences and says so (jacobian_kind), recovering a modulus 1.3 times
    the scene's from the first frequency within 1 %; "analytic" refuses, naming the
    cause."""
    scene = ds.load_scene("pendulum")
    model = ds.build_model(scene.equilibrium(), "dsm")
    f = ds.eigenfrequencies(model, 1)
    EA0 = scene.robot.cables[0].EA
    moved = replace(scene.robot, cables=[replace(c, EA=1.3 * c.EA)
                                                     for c in scene.robot.cables])
    f_meas = ds.eigenfrequencies(ds.build_model(moved.equilibrium(scene.pose), "dsm"), 1)
    assert f_meas[0] > 1.001 * f[0]
    fit = ds.calibrate(scene, f_meas, parameters="EA", rung="dsm")
    assert fit.jacobian_kind == "differences"
    assert fit.estimate[0] == pytest.approx(1.3 * EA0, rel=1e-2)
    with pytest.raises(ds.InvalidParameterError, match="singular"):
        ds.calibrate(scene, f_meas, parameters="EA", rung="dsm", jacobian="analytic")


def test_a_measured_frequency_far_above_the_cables_modes_is_refused_before_the_fit(scene):
    """3000 Hz (a unit slip) holds thousands of the model's modes in its band: refused from
    one count, naming the measured mode and the count, instead of computing them all."""
    model = ds.FrequencyModel(scene.equilibrium())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)   # the band holds axial modes
        n = int(ds.mode_count(model, 2 * np.pi * 1.3 * 3000.0)[0])
    assert n > 2000
    with pytest.raises(ds.InvalidParameterError,
                       match=f"measured mode 3 at 3000 Hz: the model has {n} modes below "
                             f"3900 Hz .* max_modes = 2000"):
        calibrate(scene, [2.2, 2.4, 3000.0], parameters="EA")
    for bad in (True, 0, 2.5):
        with pytest.raises(ds.InvalidParameterError, match="max_modes must be an integer"):
            calibrate(scene, [2.2, 2.4], parameters="EA", max_modes=bad)


def test_a_measured_frequency_beyond_the_cable_models_range_is_refused_naming_it():
    """On planar2 (30 m cables of 0.1 kg/m), 6.4 MHz lies beyond the closed form's digits
    (Omega > 1e7): the count's own error is given with the measured mode it came from, not
    as a bare omega."""
    with pytest.raises(ds.InvalidParameterError,
                       match=r"measured mode 2 at 6\.44347e\+06 Hz: the band up to .* is "
                             r"beyond the model: omega must be <="):
        calibrate(ds.load_scene("planar2"), [1.0, 6443468.0], parameters="EA")


def test_one_cables_EA_is_scaled_alone_and_read_back():
    """The parameter "EA_2" scales cable 2's EA only, and its value is cable 2's."""
    from dynstiff.analyses.calibrate import _value, _with
    robot = ds.load_scene("cogiro").robot
    scaled = _with(robot, ("EA_2",), np.array([1.5]))
    EA0 = np.array([c.EA for c in robot.cables])
    np.testing.assert_array_equal([c.EA for c in scaled.cables],
                                  np.where(np.arange(8) == 2, 1.5 * EA0, EA0))
    assert _value(scaled, "EA_2") == 1.5 * EA0[2] and _value(scaled, "EA_3") == EA0[3]


def test_max_modes_is_a_ceiling_the_band_may_reach():
    """The pendulum has one mode below 1.3 times its first (22.5 Hz): max_modes = 1 is
    enough; on planar2 the band of a 2.6 Hz measurement holds 4 modes: max_modes = 4 is
    enough and 3 is refused by the count."""
    pend = ds.load_scene("pendulum")
    f1 = ds.eigenfrequencies(ds.FrequencyModel(pend.equilibrium()), n_modes=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.DynstiffWarning)
        fit = calibrate(pend, 1.01 * f1, parameters="EA", max_modes=1)
    assert fit.fitted_hz[0] == pytest.approx(1.01 * f1[0], rel=1e-4)
    planar = ds.load_scene("planar2")
    f = ds.eigenfrequencies(ds.FrequencyModel(planar.equilibrium()), n_modes=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.DynstiffWarning)
        calibrate(planar, 1.01 * f, parameters="EA", max_modes=4)
    with pytest.raises(ds.InvalidParameterError, match="the model has 4 modes below .* "
                                                       "more than max_modes = 3"):
        calibrate(planar, 1.01 * f, parameters="EA", max_modes=3)


def test_requests_without_a_pose_or_with_an_impossible_jacobian_are_named(scene):
    with pytest.raises(ds.InvalidParameterError,
                       match="^calibrate needs the pose of the measurement: give pose= "
                             "or a scene with a \\[pose\\]$"):
        calibrate(scene.robot, [2.2, 2.4], parameters="EA")
    frf = ds.frf(ds.FrequencyModel(scene.equilibrium()), 2 * np.pi * np.linspace(0.5, 1.5, 5),
                 inputs="fx", outputs="x")             # below the first mode: no warning
    with pytest.raises(ds.InvalidParameterError,
                       match=r"jacobian='analytic' needs frequency residuals only \(no FRF"):
        calibrate(scene, None, parameters="EA", frf=frf, jacobian="analytic")


def test_a_parameter_the_frequencies_do_not_fix_has_no_interval():
    """planar2's platform is a point mass: its inertia factor moves no frequency, J^T J is
    singular, and both intervals are NaN (not a number made up)."""
    planar = ds.load_scene("planar2")
    f = ds.eigenfrequencies(ds.FrequencyModel(planar.equilibrium()), n_modes=2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.DynstiffWarning)
        fit = calibrate(planar, 1.02 * f, parameters=["EA", "inertia"])
    assert np.all(np.isnan(fit.ci_low)) and np.all(np.isnan(fit.ci_high))
    assert np.all(np.isfinite(fit.estimate))


def test_a_fit_stopped_by_max_nfev_is_an_error_and_a_start_value_is_the_start(scene):
    f = platform_frequencies(with_E(scene.robot, E_TRUE), scene.pose, "dsm", 3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.DynstiffWarning)
        with pytest.raises(ds.ConvergenceError, match="calibration did not converge"):
            calibrate(scene, f, parameters="EA", jacobian="differences", max_nfev=1)
        fit = calibrate(scene, f, parameters="EA", start={"EA": AREA * 50e9})
    assert fit.initial[0] == pytest.approx(AREA * 50e9, rel=1e-15)
    assert fit.estimate[0] == pytest.approx(AREA * E_TRUE, rel=1e-6)


def test_forward_differences_reuse_the_residual_at_the_point(scene, monkeypatch):
    """Each forward-difference Jacobian of n parameters costs n evaluations (the residual
    at the point is the one just evaluated), so a fit costs at most 1 + nfev + n njev + 1
    evaluations, plus 2 n for the central Jacobian at the estimate."""
    import scipy.optimize
    real, seen = scipy.optimize.least_squares, []

    def spy(*a, **k):
        sol = real(*a, **k)
        seen.append(sol)
        return sol
    monkeypatch.setattr(scipy.optimize, "least_squares", spy)
    f = platform_frequencies(with_E(scene.robot, 0.8 * E_TRUE), scene.pose, "dsm", 3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.DynstiffWarning)
        fit = calibrate(scene, f, parameters=["EA", "mass"], jacobian="differences")
    sol, n = seen[0], 2
    assert sol.njev >= 2
    assert fit.n_evaluations <= 1 + sol.nfev + n * sol.njev + 1 + 2 * n


def test_a_non_bool_strict_and_mac_pairing_without_shapes_are_refused(scene):
    with pytest.raises(ds.InvalidParameterError, match="^strict must be True or False, got 'no'"):
        calibrate(scene, [2.2, 2.4], parameters="EA", strict="no")
    with pytest.raises(ds.InvalidParameterError, match="pairing='mac' needs measured shapes"):
        calibrate(scene, [2.2, 2.4], parameters="EA", pairing="mac")


def test_one_mode_with_its_damping_ratio_fixes_EA_and_the_loss_factor(scene):
    """A measured damping ratio is a measured value: one mode's frequency and damping ratio
    are two values, enough for EA and the loss factor (recovered exactly from the noiseless
    mode of the robot at 20 GPa and loss factor 0.02), with no spread left to estimate:
    both intervals NaN."""
    truth = replace(scene.robot, cables=[replace(c, EA=AREA * 20e9, loss_factor=0.02)
                                         for c in scene.robot.cables])
    m = ds.build_model(truth.equilibrium(scene.pose), "dsm")
    md = ds.modes(m, fmax_hz=6.0)
    idx = massless_pairing(md, m, 1)
    meas = MeasuredModes(md.freq_hz[idx],
                         damping_ratio=ds.damped_modes(m, fmax_hz=6.0).damping_ratio[idx])
    res = calibrate(scene, meas, parameters=["EA", "loss_factor"], start={"loss_factor": 0.005})
    np.testing.assert_allclose(res.estimate, [AREA * 20e9, 0.02], rtol=1e-6)
    assert np.all(np.isnan(res.ci_low)) and np.all(np.isnan(res.ci_high))


def test_frf_translations_at_a_platform_point_are_fitted_at_that_point(scene):
    """The measured fx -> x FRF of a point 0.5 m off P in each direction (below the first
    mode, noiseless, at 60 GPa; about half P's magnitude): with frf_point the
    model's FRF is taken at the same point and EA is recovered exactly."""
    model = ds.build_model(with_E(scene.robot, E_TRUE).equilibrium(scene.pose), "dsm")
    point = np.array([0.5, 0.5, 0.5])
    meas = ds.frf(model, 2 * np.pi * np.linspace(0.1, 1.5, 10), inputs="fx", outputs="x",
                  point=point)
    fit = calibrate(scene, None, parameters="EA", frf=meas, frf_point=point)
    assert fit.estimate[0] == pytest.approx(AREA * E_TRUE, rel=1e-8)
    assert fit.frf_log_error < 1e-8


def test_an_interval_bound_beyond_the_float_range_is_infinite_without_a_warning(scene):
    """Two modes (with shapes, 0.1 % noise) and one parameter: one degree of freedom, and at
    the level 1 - 1e-9 Student's t quantile is about 6e8 (a Cauchy tail), so
    exp(u + q se) overflows: the upper bound is inf, the lower 0, and numpy's overflow is
    not reported (the estimate is still within 2e-5 of the truth)."""
    from scipy.stats import t as student_t
    assert student_t.ppf(1 - 5e-10, 1) > 1e8
    full = _platform_modes_measured(with_E(scene.robot, E_TRUE), scene.pose)
    meas = MeasuredModes(full.freq_hz[:2] * (1 + 1e-3 * np.array([1.0, -1.0])),
                         shapes=full.shapes[:2])
    with warnings.catch_warnings():
        warnings.simplefilter("error")                 # numpy's RuntimeWarning too
        res = calibrate(scene, meas, parameters="EA", confidence=1 - 1e-9)
    assert abs(res.estimate[0] / (AREA * E_TRUE) - 1) < 2e-5
    assert res.ci_high[0] == np.inf and res.ci_low[0] == 0.0
