"""Model ladder and recommend_model: a case where each rung is the right answer, checked
against a converged lumped-mass reference (Richardson, N = 20 and 40), and the validation
study's headline numbers."""

import importlib.util
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import dynstiff as ds

spec = importlib.util.spec_from_file_location(
    "model_selection", Path(__file__).resolve().parents[1] / "validation" / "model_selection.py")
ms = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ms)


def three_cable(R, H, mass, E, m, pose=(0.3, -0.2, 1.0)):
    ang = np.radians([90, 210, 330])
    A = np.column_stack([R * np.cos(ang), R * np.sin(ang), np.full(3, H)])
    rob = ds.Robot(A, np.zeros((3, 3)), ds.Cable(m, 8.2e-6 * E),
                   ds.Platform(mass, free_dofs=("x", "y", "z")), tension_limits=(1, 1e7))
    return rob.equilibrium(pose=list(pose))


def cable_f1(eq):
    return min(ds.cable_natural_frequencies(s, 1, guard_rtol=None).freq_hz[0] for s in eq.states)


def actual_errors(eq, band, segments=None):
    ref = ms.reference_frequencies(eq, band[1] * 1.5)
    with warnings.catch_warnings():     # every rung's error is measured, the dsm's included:
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)      # its guard may warn
        out = {r: ms.band_error(ds.eigenfrequencies(ds.build_model(eq, r),
                                                    fmax_hz=band[1] * 1.5), ref, band)
               for r in ("spring", "catenary", "dsm")}
    out["exact"] = ms.band_error(ds.eigenfrequencies(
        ds.build_model(eq, "exact", fmax_hz=band[1] * 1.6), fmax_hz=band[1] * 1.5), ref, band)
    if segments:
        out["lumped"] = ms.band_error(
            ds.eigenfrequencies(ds.build_model(eq, "lumped", segments), fmax_hz=band[1] * 1.5), ref,
            band)
    return out


def test_spring_is_enough_for_a_stiff_taut_robot():
    eq = three_cable(5, 5, 1000, 120e9, 0.064)
    band = (0.01, 0.8 * cable_f1(eq))
    rec = ds.recommend_model(eq, band, 1e-2)
    assert rec.rung == "spring"
    assert actual_errors(eq, band)["spring"] <= 1e-2


def test_catenary_when_sag_matters_but_cable_inertia_does_not():
    eq = three_cable(12, 8, 50, 17e9, 0.064)
    band = (0.01, 0.8 * cable_f1(eq))
    rec = ds.recommend_model(eq, band, 1e-2)
    assert rec.rung == "catenary"
    err = actual_errors(eq, band)
    assert err["spring"] > 1e-2 >= err["catenary"]        # spring too crude, catenary enough
    assert rec.errors["spring"] == pytest.approx(err["spring"], rel=0.1)
    assert rec.errors["catenary"] == pytest.approx(err["catenary"], rel=0.1)


def test_dsm_when_cable_modes_are_in_the_band():
    eq = ds.load_scene("cogiro").equilibrium()
    band = (0.1, 6.0)
    rec = ds.recommend_model(eq, band, 1e-2)
    assert rec.rung == "dsm" and rec.estimates["cable_modes_in_band"] > 0
    err = actual_errors(eq, band)
    assert np.isinf(err["spring"]) and np.isinf(err["catenary"]) and err["dsm"] <= 1e-2


def test_exact_when_the_tolerance_is_below_the_closed_form_error():
    """1e-4 is below the closed form's error on CoGiRo (1.6e-4 measured): the exact rung is
    the cheapest adequate one, and it meets the tolerance against the converged lumped
    reference (whose own error, Richardson N = 20/40, is ~1e-6)."""
    eq = ds.load_scene("cogiro").equilibrium()
    band = (0.1, 3.0)
    rec = ds.recommend_model(eq, band, 1e-4)
    assert rec.rung == "exact" and rec.segments is None
    err = actual_errors(eq, band)
    assert err["dsm"] > 1e-4 >= err["exact"]              # the closed form is not enough
    df = rec.to_frame().set_index("rung")
    assert list(df.index) == ["spring", "catenary", "dsm", "exact", "lumped"]
    assert df["recommended"].sum() == 1 and df.loc["exact", "recommended"]
    assert (df.loc[["spring", "catenary", "dsm"], "predicted error [-]"] > 1e-4).all()


def test_bad_inputs():
    eq = ds.load_scene("cogiro").equilibrium()
    with pytest.raises(ds.InvalidParameterError, match="band_hz"):
        ds.recommend_model(eq, (5.0, 1.0), 1e-2)
    with pytest.raises(ds.InvalidParameterError, match="rtol"):
        ds.recommend_model(eq, (0.1, 1.0), -1.0)
    with pytest.raises(ds.InvalidParameterError, match="rung"):
        ds.build_model(eq, "fem")


def test_model_selection_study_quick():
    """validation/model_selection.py, quick suite: the choice meets rtol in >= 95 % of cases
    and is never more than one rung too expensive (issue acceptance)."""
    df = ms.run(quick=True)
    assert len(df) == 18                                  # 3 cases x 2 bands x 3 rtol
    assert df["meets rtol"].mean() >= 0.95
    assert df["rungs too expensive"].max() <= 1
    assert set(df["recommended"]) >= {"spring", "catenary", "dsm"}


@pytest.mark.slow
def test_model_selection_study_full_and_random_robots():
    df = ms.run()
    assert df["meets rtol"].mean() >= 0.95 and df["rungs too expensive"].max() <= 1
    rng = np.random.default_rng(7)
    hits, too_costly, n = 0, 0, 0
    for _ in range(20):
        R, H = rng.uniform(4, 14), rng.uniform(4, 10)
        mass, E, m = rng.uniform(10, 1000), rng.uniform(17e9, 120e9), rng.uniform(0.03, 0.5)
        try:
            eq = three_cable(R, H, mass, E, m, pose=(rng.uniform(-.5, .5), rng.uniform(-.5, .5),
                                                    rng.uniform(0.5, 2.0)))
        except ds.DynstiffError:
            continue
        band = (0.01, rng.uniform(0.5, 2.0) * cable_f1(eq))
        for rtol in (3e-2, 1e-3):
            rec = ds.recommend_model(eq, band, rtol)
            err = actual_errors(eq, band, rec.segments if rec.rung == "lumped" else None)
            n += 1
            hits += err[rec.rung] <= rtol
            adequate = [r for r in ds.RUNGS if err.get(r, np.inf) <= rtol]
            if adequate:
                too_costly += ds.RUNGS.index(rec.rung) - ds.RUNGS.index(adequate[0]) > 1
    assert n >= 20 and hits / n >= 0.95 and too_costly == 0


@pytest.mark.parametrize("mass", [50.0, 5.0, 1.0, 0.3])
def test_near_slack_cables_answer_or_raise(mass):
    """As the platform gets lighter the cables approach slack (tension ~ cable weight): every
    model still answers, with recommend_model's closed-form error (measured against the
    exact rung) equal to its actual error against the converged lumped reference, or
    statics raises SlackCableError with the pose and the tension."""
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    rob = ds.Robot(A, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(mass, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6))
    if mass < 0.5:
        with pytest.raises(ds.SlackCableError, match="not reachable"):
            rob.equilibrium(pose=[0.3, -0.2, 1.0])
        return
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    assert eq.residual < 1e-10
    band = (0.01, 1.5 * cable_f1(eq))
    rec = ds.recommend_model(eq, band, 1e-2)
    err = actual_errors(eq, band)
    assert np.isinf(err["spring"]) and np.isinf(err["catenary"])   # cable modes in the band
    # the prediction is the measurement against the exact rung: equal to the actual error up
    # to the lumped reference's own error (Richardson N = 20/40, ~1e-6 absolute)
    assert abs(err["dsm"] - rec.errors["dsm"]) <= 1e-5 + 1e-2 * err["dsm"]
    assert err["exact"] <= 1e-5


def test_fourcable_needs_only_the_light_model():
    """Seed paper 002's small robot: the cable modes sit above 28 Hz, sag/chord ~1e-4 and the
    cables weigh 0.1 % of the platform, so straight massless springs meet 1 % up to 20 Hz."""
    eq = ds.load_scene("fourcable").equilibrium()
    rec = ds.recommend_model(eq, (0.1, 20.0), 1e-2)
    assert rec.rung == "spring"
    assert rec.estimates["cable_f1_hz"] > 20.0 and rec.estimates["mass_ratio"] < 0.01
    f_spring = ds.eigenfrequencies(ds.build_model(eq, "spring"), fmax_hz=20.0)
    f_dsm = ds.eigenfrequencies(ds.build_model(eq, "dsm"), fmax_hz=20.0)
    np.testing.assert_allclose(f_spring, f_dsm, rtol=1e-2)


def test_segments_only_where_the_lumped_rung_is_named():
    """The table gives the lumped rung's segment count on its own row only; the repr names
    a segment count only for a lumped recommendation."""
    eq = ds.load_scene("cogiro").equilibrium()
    rec = ds.recommend_model(eq, (0.1, 3.0), 1e-4)
    df = rec.to_frame().set_index("rung")
    n = rec.estimates["lumped_segments"]
    assert n >= 4 and df.loc["lumped", "segments"] == n
    assert df.drop(index="lumped")["segments"].isna().all()
    assert repr(rec) == f"Recommendation('exact', predicted error {rec.predicted_error:.2e})"
    lumped = replace(rec, rung="lumped", segments=n)
    assert repr(lumped) == (f"Recommendation('lumped', {n} segments, predicted error "
                            f"{rec.predicted_error:.2e})")


def test_closed_form_error_in_band_and_axial_cut():
    """_dsm_error on soft heavy cables (axial modes from ~3.6 Hz): just below the guard's
    axial margin the closed form's error is the largest relative gap of each exact mode in
    the band to its nearest closed-form mode (an independent pairing); just above it, inf,
    naming the axial modes."""
    from dynstiff.analyses.recommend import _dsm_error
    from dynstiff.cable.guard import AXIAL_MARGIN, closed_form_validity
    from dynstiff.models.exact import ExactModel
    eq = three_cable(5, 5, 50, 2e8, 1.0)
    f_ax = min(closed_form_validity(s, 0.0).values["axial_hz"] for s in eq.states)
    hi = 0.99 * AXIAL_MARGIN * f_ax
    lo = 0.5 * hi                                      # modes below lo are not compared
    err, eps, causes = _dsm_error(eq, (lo, hi))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
        f_d = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=1.2 * hi)
    f_x = ds.eigenfrequencies(ExactModel(eq, fmax_hz=1.25 * hi), fmax_hz=1.2 * hi)
    band = f_x[(f_x >= lo) & (f_x < hi)]
    assert band.size >= 3 and np.any(f_x < lo)
    ref = max(np.min(np.abs(f_d / f - 1)) for f in band)
    assert err == pytest.approx(ref, rel=1e-9) and 0 < err < 0.05
    assert not any("axial" in c for c in causes) and eps > 0.1
    err_up, eps_up, causes_up = _dsm_error(eq, (lo, 1.01 * AXIAL_MARGIN * f_ax))
    assert np.isinf(err_up) and eps_up == eps
    assert sum("axial modes from" in c for c in causes_up) >= 1


def test_cable_estimates_against_the_exact_clamped_cables():
    """CoGiRo: the lowest taut-string frequency sqrt(T/m) / 2L of the estimates is the
    lowest exact clamped out-of-plane frequency to 1 % (shallow taut cables), and the
    highest harmonic in the band is the band top over it."""
    eq = ds.load_scene("cogiro").equilibrium()
    hi = 6.0
    errors, est, segments = ds.analyses.recommend.predicted_errors(eq, (0.1, hi), 1e-2)
    exact = min(ds.cable_natural_frequencies(s, 2, model="exact").freq_hz.min()
                for s in eq.states)
    assert est["cable_f1_hz"] == pytest.approx(exact, rel=1e-2)
    assert est["highest_harmonic"] == pytest.approx(hi / est["cable_f1_hz"], rel=1e-12)


@pytest.mark.parametrize("rtol", [1e-2, 1e-3, 1e-4])
def test_lumped_segments_from_the_discrete_string_error(rtol):
    """The lumped rung's estimate: a chain of N masses gives harmonic n at sin(x)/x of the
    string's, x = n pi / 2N, so 1 - sin(x)/x ~ (n pi / N)^2 / 24 (to x^4 / 120); the
    segments are the fewest (at least 4) that keep it within rtol / 2."""
    eq = ds.load_scene("cogiro").equilibrium()
    errors, est, N = ds.analyses.recommend.predicted_errors(eq, (0.1, 6.0), rtol)
    n = max(1.0, est["highest_harmonic"])
    x = n * np.pi / (2 * N)
    assert abs(errors["lumped"] - (1 - np.sin(x) / x)) <= x**4 / 100
    assert errors["lumped"] <= rtol / 2
    assert N == 4 or (n * np.pi / (N - 1)) ** 2 / 24 > rtol / 2
    assert est["lumped_segments"] == N


def test_lumped_models_estimated_error_is_the_discrete_string_error():
    """estimated_error of a lumped model: the highest harmonic 2 f L sqrt(m / T) over its
    cables (chord, end tension) and its segment count, as the discrete string's error."""
    from dynstiff.analyses.recommend import estimated_error
    eq = ds.load_scene("cogiro").equilibrium()
    model = ds.build_model(eq, "lumped", 12)
    err, cause = estimated_error(model, (0.1, 4.0))
    leq = model.equilibrium
    harm = max(2 * 4.0 * np.linalg.norm(x[-1] - x[0]) * np.sqrt(c.mass_per_length / t)
               for x, c, t in zip(leq.nodes, model.robot.cables, leq.end_tensions))
    x = max(1.0, harm) * np.pi / (2 * 12)
    assert abs(err - (1 - np.sin(x) / x)) <= x**4 / 100 and err > 0
    assert cause == "12 segments per cable against the highest cable harmonic in the band"


@pytest.mark.parametrize("fraction", [0.5, 0.9])
def test_no_massless_mode_in_the_band_no_massless_error(fraction):
    """A band ending below the first platform mode (half of it: no mode within 1.5 x the
    top; 0.9 of it: the mode is within 1.5 x but its shift keeps it above the band): the
    massless rungs miss nothing and shift nothing there."""
    from dynstiff.analyses.recommend import _massless_errors
    eq = three_cable(12, 8, 50, 17e9, 0.064)
    f1 = ds.eigenfrequencies(ds.build_model(eq, "catenary"), n_modes=1)[0]
    with warnings.catch_warnings():       # the closed form's guard may speak
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
        f_dsm = ds.eigenfrequencies(ds.FrequencyModel(eq), n_modes=1)[0]
    assert f_dsm > fraction * f1         # the heavy cables' first mode is above the band
    assert _massless_errors(eq, fraction * 2 * np.pi * f1, 0) == (0.0, 0.0)


def test_the_text_names_the_segments_and_every_rungs_error():
    eq = ds.load_scene("cogiro").equilibrium()
    rec = ds.recommend_model(eq, (0.1, 3.0), 1e-4)
    lumped = replace(rec, rung="lumped", segments=rec.estimates["lumped_segments"])
    lines = lumped.text().splitlines()
    assert lines[0] == (f"recommended model: lumped with N = {lumped.segments} segments per "
                        f"cable (predicted error {rec.predicted_error:.2e})")
    assert lines[3] == "  predicted errors: " + ", ".join(
        f"{k} {v:.2e}" for k, v in rec.errors.items())
    assert rec.text().splitlines()[0] == (f"recommended model: exact (predicted error "
                                          f"{rec.predicted_error:.2e})")


def test_massless_and_closed_form_estimates_with_their_causes():
    """estimated_error of the massless rungs is the recommendation's prediction for each
    (catenary, spring), with the cause in words: the cables' inertia when no cable mode is
    in the band, the count of missed cable modes otherwise; the closed form with axial
    modes in the band is inf, naming them."""
    from dynstiff.analyses.recommend import estimated_error, predicted_errors
    from dynstiff.cable.guard import AXIAL_MARGIN, closed_form_validity
    eq = three_cable(12, 8, 50, 17e9, 0.064)
    band = (0.01, 0.8 * cable_f1(eq))
    errors = predicted_errors(eq, band)[0]
    for rung in ("catenary", "spring"):
        err, cause = estimated_error(ds.build_model(eq, rung), band)
        assert err == errors[rung] and cause == "the cables' inertia shifts the platform modes"
    assert errors["spring"] > errors["catenary"] > 0
    cogiro = ds.load_scene("cogiro").equilibrium()
    err, cause = estimated_error(ds.build_model(cogiro, "catenary"), (0.1, 6.0))
    n = predicted_errors(cogiro, (0.1, 6.0))[1]["cable_modes_in_band"]
    assert np.isinf(err) and cause == f"{n} cable modes in the band, which the massless " \
                                      f"cables miss" and n > 0
    soft = three_cable(5, 5, 50, 2e8, 1.0)
    f_ax = min(closed_form_validity(s, 0.0).values["axial_hz"] for s in soft.states)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
        err, cause = estimated_error(ds.FrequencyModel(soft), (0.0, 1.01 * AXIAL_MARGIN * f_ax))
    assert np.isinf(err) and "axial modes from" in cause and cause.startswith("cable ")


@pytest.mark.parametrize("band", [(0.0, True), (False, 2.0), "ab", (0.0, "x"), (2.0, 1.0),
                                  (0.0, np.inf), 5.0])
def test_a_band_that_is_not_one_is_refused_naming_band_hz(band):
    """(0, True) was the band up to 1 Hz, and text came out as numpy's ValueError."""
    eq = ds.load_scene("planar2").equilibrium()
    with pytest.raises(ds.InvalidParameterError, match="^band_hz must be "):
        ds.recommend_model(eq, band_hz=band)


def test_an_equilibrium_that_is_not_one_is_refused():
    with pytest.raises(ds.InvalidParameterError, match="^equilibrium must be an Equilibrium"):
        ds.recommend_model(None, band_hz=(0.0, 2.0))


def test_the_estimates_name_the_closed_forms_causes():
    """The estimates carry the causes the closed form's guard names for the cables at the
    band's top (cable.guard.closed_form_validity, reasons above 1e-2): on soft heavy cables
    with axial modes in the band, the axial modes among them."""
    from dynstiff.analyses.recommend import predicted_errors
    from dynstiff.cable.guard import AXIAL_MARGIN, closed_form_validity
    soft = three_cable(5, 5, 50, 2e8, 1.0)
    f_ax = min(closed_form_validity(s, 0.0).values["axial_hz"] for s in soft.states)
    hi = 1.01 * AXIAL_MARGIN * f_ax
    errors, est, _ = predicted_errors(soft, (0.0, hi))
    causes = sorted({r for s in soft.states
                     for r in closed_form_validity(s, 2 * np.pi * hi).reasons(1e-2)})
    assert est["closed_form_causes"] == causes and np.isinf(errors["dsm"])
    assert any("axial modes from" in c for c in causes)
