"""Uncertainty of the frequencies and of the verdicts (dynstiff/analyses/uncertainty.py,
theory.md §16.6): the first order against Monte Carlo on the same Latin-hypercube sample,
its second-order growth, the seed, the engines, and the design checks' uncertain row."""

import numpy as np
import pytest

from dynstiff.analyses.checks import design_checks
from dynstiff.analyses.uncertainty import (
    UNCERTAIN_CHECK,
    Uncertain,
    propagate_uncertainty,
    uncertain_row,
)
from dynstiff.analyses.verdicts import CheckOptions
from dynstiff.errors import InvalidParameterError


def test_stated_distributions():
    u = Uncertain.parse("10%")
    assert (u.distribution, u.relative) == ("normal", True) and u.std(2.0) == pytest.approx(0.2)
    u = Uncertain.parse("0.5:uniform")
    assert not u.relative and u.std(7.0) == pytest.approx(0.5 / np.sqrt(3))
    np.testing.assert_allclose(u.values(7.0, [0.0, 0.5, 1.0]), [6.5, 7.0, 7.5])
    np.testing.assert_allclose(Uncertain(0.1).values(1.0, [0.5, 0.8413447460685429]),
                               [1.0, 1.1])
    for bad in ("ten", "10%:lognormal", "-1", "0"):
        with pytest.raises(InvalidParameterError):
            Uncertain.parse(bad)


def test_first_order_and_monte_carlo_agree_for_small_uncertainty_and_part_at_second_order(
        cogiro):
    """EA with sigma 1 %: every sample's Monte Carlo value of the first platform mode is
    within 2 % of sigma of its first-order value; at 10 % the difference has grown 100
    times (second order: (10 / 1)^2). LHS reproduces the standard deviation to 3 %."""
    diffs, stds = [], []
    for s in ("1%", "10%"):
        res = propagate_uncertainty(cogiro, uncertain={"EA": s}, n_modes=1, n_samples=24)
        assert res.failed == 0
        i = res.quantities.index("first_platform_hz")
        diffs.append(np.abs(res.monte_carlo[:, i] - res.first_order[:, i]).max())
        stds.append(res.std_first_order[i])
        assert np.std(res.first_order[:, i], ddof=1) == pytest.approx(stds[-1], rel=0.03)
    assert diffs[0] < 0.02 * stds[0]
    assert 50 < diffs[1] / diffs[0] < 200
    assert stds[1] / stds[0] == pytest.approx(10.0, rel=1e-9)


def test_results_are_reproducible_from_the_seed_on_every_engine(cogiro):
    kw = dict(uncertain={"EA": "5%", "mass": "2:uniform"}, n_modes=2, n_samples=8,
              chunk_size=4)
    a = propagate_uncertainty(cogiro, seed=3, **kw)
    b = propagate_uncertainty(cogiro, seed=3, workers=2, **kw)
    c = propagate_uncertainty(cogiro, seed=4, **kw)
    np.testing.assert_array_equal(a.samples, b.samples)
    np.testing.assert_allclose(a.monte_carlo, b.monte_carlo, rtol=1e-12)
    assert not np.allclose(a.samples, c.samples)
    assert np.all(np.abs(a.samples[:, 1] - 91.058) <= 2.0)
    df = a.to_frame()
    assert list(df["quantity"]) == ["f1", "f2", "first_platform_hz"]


def test_the_uncertain_row_of_the_design_checks(cogiro):
    """Band (0, 2) Hz, first platform mode 2.206 Hz: nominally the margin holds (0.103 >
    0.05), with EA's sigma 10 % about 16 % of the robots fail it (the normal tail below
    2.1 Hz of sigma ~ 0.11 Hz) and the margin at 95 % confidence is below 0.05; the other
    rows are those of the nominal check."""
    nominal = design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 2.0))
    res = design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 2.0),
                        uncertain={"EA": "10%"}, n_samples=40)
    assert res.rows[:-1] == nominal.rows
    row = res.rows[-1]
    assert row["check"] == UNCERTAIN_CHECK and row["verdict"] == "fail"
    assert 0.08 < row["value"] < 0.25
    assert res.uncertainty.quantile("band_margin", 0.05) < 0.05
    ok = design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 1.5),
                       uncertain={"EA": "10%"}, n_samples=16)
    assert ok.rows[-1]["verdict"] == "pass" and ok.rows[-1]["value"] == 0.0
    row, _ = uncertain_row(cogiro.robot, cogiro.pose, CheckOptions(), {"EA": "10%"})
    assert row["verdict"] == "not asked"


def test_bad_requests_are_refused(cogiro):
    with pytest.raises(InvalidParameterError, match="loss factor"):
        propagate_uncertainty(cogiro, uncertain={"loss_factor": "10%"})
    with pytest.raises(InvalidParameterError, match="each parameter by its own name"):
        propagate_uncertainty(cogiro, uncertain={"EA_*": "10%"})
    with pytest.raises(InvalidParameterError, match="needs a pose"):
        propagate_uncertainty(cogiro.robot, uncertain={"EA": "10%"})
    with pytest.raises(InvalidParameterError, match="non-empty dict"):
        propagate_uncertainty(cogiro, uncertain={})
    with pytest.raises(InvalidParameterError, match="confidence"):
        design_checks(cogiro.robot, cogiro.pose, confidence=95)


def test_a_stated_uncertainty_in_words():
    assert Uncertain(0.1, "uniform", True).text() == "+-10 % (uniform)"
    assert Uncertain(0.002, "normal", False).text() == "sigma 0.002 (normal)"
    assert Uncertain(0.05).text() == "sigma 5 % (normal)"


def test_more_refusals_in_their_own_words(cogiro):
    with pytest.raises(InvalidParameterError, match=r"^propagate_uncertainty needs a pose: "
                       r"give pose= or a scene with a \[pose\]$"):
        propagate_uncertainty(cogiro.robot, uncertain={"EA": "10%"})
    with pytest.raises(InvalidParameterError, match="^n_modes must be an integer >= 1, got 0$"):
        propagate_uncertainty(cogiro, uncertain={"EA": "10%"}, n_modes=0)
    with pytest.raises(InvalidParameterError,
                       match=r"^band_hz must be \(lo, hi\), 0 <= lo < hi \[Hz\], got "
                             r"\(2\.0, 1\.0\)$"):
        propagate_uncertainty(cogiro, uncertain={"EA": "10%"}, band_hz=(2.0, 1.0))
    with pytest.raises(InvalidParameterError, match=r"\(no wildcards: each needs its "
                                                    r"distribution\)$"):
        propagate_uncertainty(cogiro, uncertain={"EA_*": "10%"})


def test_refusals_in_their_own_words_and_counts_from_one(cogiro):
    with pytest.raises(InvalidParameterError,
                       match="^uncertain: a loss factor moves no undamped frequency$"):
        propagate_uncertainty(cogiro, uncertain={"loss_factor": "10%"})
    with pytest.raises(InvalidParameterError,
                       match=r"^uncertain: give each parameter by its own name \(no "):
        propagate_uncertainty(cogiro, uncertain={"EA_*": "10%"})
    for name, bad in (("n_samples", 0), ("n_samples", "5"), ("chunk_size", 0),
                      ("chunk_size", True)):
        with pytest.raises(InvalidParameterError, match=f"^{name} must be an integer >= 1"):
            propagate_uncertainty(cogiro, uncertain={"EA": "10%"}, **{name: bad})


def test_the_uncertain_row_fields(cogiro):
    """A row has the design checks' fields: unknown with its detail where the nominal pose
    has no equilibrium, and the limit 1 - confidence."""
    options = CheckOptions(forbidden_hz=(0.0, 1.5))
    row, res = uncertain_row(cogiro.robot, [7.4, 5.2, 0.5, 0, 0, 0], options, {"EA": "10%"},
                             n_samples=4, confidence=0.9)
    assert res is None
    assert row["verdict"] == "unknown" and row["passed"] is False
    assert row["detail"].startswith("no nominal equilibrium or modes: ")
    assert row["limit"] == pytest.approx(0.1) and row["check"] == UNCERTAIN_CHECK
    row, res = uncertain_row(cogiro.robot, cogiro.pose, options, {"EA": "10%"}, n_samples=4)
    assert set(row) == {"check", "value", "limit", "verdict", "passed", "detail"}
    assert row["verdict"] == "pass" and row["passed"] is True
    assert "first order 0.0%" in row["detail"] and "EA sigma 10 % (normal)" in row["detail"]


@pytest.mark.parametrize("band, side", [((0.0, 1.5), "above"), ((2.0, 2.25), "inside, near hi"),
                                        ((2.3, 3.0), "inside, near lo"),
                                        ((2.25, 2.3), "below")])
def test_the_band_margin_gradient_is_the_derivative_on_either_side_of_the_band(cogiro, band,
                                                                               side):
    """The first order of the band margin against Monte Carlo at EA +-0.01 % (uniform): the
    mode that sets the margin is above the band (derivative over f_hi), inside near either
    edge or below it (over -f_lo); CoGiRo's platform modes at 2.206 and 2.359 Hz. The
    changes agree to 1e-3 of their size (second order: about 1e-5 here), and the margin
    moves (the gradient is not zero)."""
    res = propagate_uncertainty(cogiro, uncertain={"EA": "0.01%:uniform"}, n_modes=1,
                                n_samples=4, band_hz=band)
    i = res.quantities.index("band_margin")
    mc = res.monte_carlo[:, i] - res.nominal[i]
    fo = res.first_order[:, i] - res.nominal[i]
    assert np.all(np.abs(mc) > 1e-6), side
    np.testing.assert_allclose(fo, mc, rtol=1e-3, atol=0)


def test_a_model_given_keeps_its_own_build_options(cogiro):
    """propagate_uncertainty of a model rebuilds its samples with the model's own options:
    the closed form's tension and chordwise inertia, the exact rung's band, order and
    half-waves, the lumped rung's segments (one number when all cables share it, also
    for a one-cable robot, else one per cable); the nominal frequencies are the model's."""
    import dynstiff as ds
    from dynstiff.analyses.eigen import eigenfrequencies
    from dynstiff.analyses.uncertainty import _own_options
    eq = cogiro.robot.equilibrium(pose=cogiro.pose)
    m = ds.FrequencyModel(eq, tension="chord", chordwise_inertia=False)
    assert _own_options(m) == {"tension": "chord", "chordwise_inertia": False}
    res = propagate_uncertainty(m, uncertain={"EA": "1%"}, n_modes=3, method="first-order")
    np.testing.assert_allclose(res.nominal[:3], eigenfrequencies(m, 3), rtol=1e-10)
    assert abs(res.nominal[0] / eigenfrequencies(ds.FrequencyModel(eq), 1)[0] - 1) > 1e-6
    ex = ds.build_model(eq, "exact", fmax_hz=12.0)
    assert _own_options(ex) == {"fmax_hz": 12.0, "order": ex.order,
                                "half_waves": ex.half_waves}
    segs = [3, 3, 3, 3, 3, 3, 3, 4]
    assert _own_options(ds.build_model(eq, "lumped", segments=segs)) == {"segments": segs}
    assert _own_options(ds.build_model(eq, "lumped", segments=3)) == {"segments": 3}
    one = ds.Robot(np.array([[0.0, 0.0, 5.0]]), np.zeros((1, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(10.0, free_dofs=("z",)), tension_limits=(0.01, 1e6))
    lumped = ds.build_model(one.equilibrium(pose=[0.0, 0.0, 1.0]), "lumped", segments=5)
    assert _own_options(lumped) == {"segments": 5}
    assert _own_options(ds.build_model(eq, "spring")) == {}


def test_the_first_order_at_a_tension_reference_and_the_default_sample(cogiro):
    """At a tension reference other than the robot's (2000 N on every cable, at a pose
    where it lifts the first platform mode from 2.136 to 2.220 Hz and its EA derivative by
    about 45 %), the gradient is taken there too: first order and Monte Carlo agree at EA
    +-0.01 %. The sample has 200 rows unless told; a parameter of the lengths (L0_0) is
    refused at a fixed pose."""
    pose, kw = [4.0, -2.5, 1.0], dict(uncertain={"EA": "0.01%:uniform"}, n_modes=1,
                                      n_samples=4)
    res = propagate_uncertainty(cogiro.robot, pose, tension_reference=np.full(8, 2000.0),
                                **kw)
    base = propagate_uncertainty(cogiro.robot, pose, method="first-order", **kw)
    i = res.quantities.index("first_platform_hz")
    assert res.nominal[i] > 1.03 * base.nominal[i]
    assert res.gradient[i, 0] > 1.3 * base.gradient[i, 0]
    np.testing.assert_allclose(res.first_order[:, i] - res.nominal[i],
                               res.monte_carlo[:, i] - res.nominal[i], rtol=1e-3)
    fo = propagate_uncertainty(cogiro, uncertain={"EA": "1%"}, n_modes=1,
                               method="first-order")
    assert fo.samples.shape == (200, 1) and fo.failed == 0 and fo.monte_carlo is None
    ref = propagate_uncertainty(cogiro.robot, pose, uncertain={"t_ref_0": "1%"}, n_modes=1,
                                tension_reference=np.full(8, 2000.0), method="first-order")
    assert ref.nominal_values[0] == 2000.0           # the reference's own, not the robot's
    band = propagate_uncertainty(cogiro.robot, pose, band_hz=(0.0, 2.0),
                                 tension_reference=np.full(8, 2000.0), **kw)
    j = band.quantities.index("band_margin")
    np.testing.assert_allclose(band.first_order[:, j] - band.nominal[j],
                               band.monte_carlo[:, j] - band.nominal[j], rtol=1e-3)
    with pytest.raises(InvalidParameterError, match="L0_0"):
        propagate_uncertainty(cogiro, uncertain={"L0_0": "1%"})


def test_the_band_margin_of_the_modes_held_to_the_band(cogiro):
    """The margin and its gradient concern the modes with platform share >= participation:
    at 0.95 the mode that sets the margin (2.206 Hz, share 0.989) is another than at 0.05
    (2.359 Hz, share 0.944), and first order and
    Monte Carlo still agree; where no mode has that share the margin and its gradient are
    NaN (one row, one column per parameter)."""
    kw = dict(uncertain={"EA": "0.01%:uniform", "mass": "0.01%"}, n_modes=1, n_samples=4,
              band_hz=(2.2, 2.4))
    low = propagate_uncertainty(cogiro, participation=0.05, **kw)
    high = propagate_uncertainty(cogiro, participation=0.95, **kw)
    i = low.quantities.index("band_margin")
    assert abs(high.nominal[i] - low.nominal[i]) > 1e-3
    for res in (low, high):
        np.testing.assert_allclose(res.first_order[:, i] - res.nominal[i],
                                   res.monte_carlo[:, i] - res.nominal[i], rtol=2e-3)
    none = propagate_uncertainty(cogiro, participation=0.999, method="first-order", **kw)
    assert np.isnan(none.nominal[i]) and none.gradient.shape == (3, 2)
    assert np.all(np.isnan(none.gradient[i]))


def test_the_uncertain_row_passes_its_engine_and_seed_on(cogiro, monkeypatch):
    """uncertain_row: the default seed is 0, the workers reach the Monte Carlo, and the
    detail gives the first order's probability beside Monte Carlo's."""
    import dynstiff.analyses.uncertainty as unc
    options = CheckOptions(forbidden_hz=(0.0, 2.0))
    calls = []
    real = unc.propagate_uncertainty

    def spy(*a, **kw):
        calls.append(kw)
        return real(*a, **kw)

    monkeypatch.setattr(unc, "propagate_uncertainty", spy)
    row, res = uncertain_row(cogiro.robot, cogiro.pose, options, {"EA": "10%"}, n_samples=40,
                             workers=1)
    assert calls[0]["seed"] == 0 and calls[0]["workers"] == 1
    assert "seed 0;" in row["detail"]
    p_fo = res.probability_below("band_margin", options.margin, "first-order")
    p_mc = res.probability_below("band_margin", options.margin)
    assert p_fo != p_mc
    assert f"first order {p_fo:.1%}); band margin at 95% confidence " in row["detail"]
    assert f"= {p_mc:.1%} (Monte Carlo, 40 samples" in row["detail"]


def test_an_incomplete_platform_search_gives_nan_rows(cogiro, monkeypatch):
    """Where the nominal search for the platform modes is incomplete (planted), the first
    platform mode and its gradient row are NaN (one row, a column per parameter) and so is
    its first order; the frequencies keep theirs."""
    from dataclasses import replace

    import dynstiff.analyses.uncertainty as unc
    real = unc.find_platform_modes
    monkeypatch.setattr(unc, "find_platform_modes",
                        lambda *a, **kw: replace(real(*a, **kw), complete=False,
                                                 reason="planted"))
    res = propagate_uncertainty(cogiro, uncertain={"EA": "1%", "mass": "1%"}, n_modes=2,
                                n_samples=8, method="first-order")
    i = res.quantities.index("first_platform_hz")
    assert res.gradient.shape == (3, 2)
    assert np.isnan(res.nominal[i]) and np.all(np.isnan(res.gradient[i]))
    assert np.all(np.isnan(res.first_order[:, i]))
    assert np.all(np.isfinite(res.gradient[:2])) and np.all(np.isfinite(res.first_order[:, :2]))
    monkeypatch.setattr(unc, "find_platform_modes",             # and it found none of them
                        lambda *a, **kw: replace(real(*a, **kw), complete=False,
                                                 reason="planted", index=np.array([], int)))
    none = propagate_uncertainty(cogiro, uncertain={"EA": "1%"}, n_modes=2, n_samples=4,
                                 method="first-order")
    np.testing.assert_array_equal(none.nominal[:2], res.nominal[:2])
    assert np.isnan(none.nominal[2]) and np.all(np.isnan(none.gradient[2]))


def test_samples_without_equilibrium_are_counted_as_failing(cogiro):
    """A platform mass of 91 kg +-200 kg (uniform) draws negative masses: those samples
    have no equilibrium, are counted and named in the row's detail, and fail; the margin
    at 95 % confidence lies among them: -inf (not numpy's NaN of -inf + inf), with no
    warning."""
    options = CheckOptions(forbidden_hz=(0.0, 1.5))
    row, res = uncertain_row(cogiro.robot, cogiro.pose, options, {"mass": "200:uniform"},
                             n_samples=8)
    assert 0 < res.failed < 8
    assert f"; {res.failed} samples without equilibrium, counted as failing)" in row["detail"]
    assert row["value"] >= res.failed / 8
    assert res.quantile("band_margin", 0.05) == -np.inf
    assert "band margin at 95% confidence -inf" in row["detail"]
    assert row["verdict"] == "fail"


def test_a_cluster_cut_by_the_modes_asked_keeps_its_eigenvalue_derivatives():
    """The octahedron's modes 2 and 3 coincide (C3v). With n_modes=2 the list of modes
    whose gradients are taken would end inside that pair: it is extended to the whole
    pair, so f2's gradient is the pair's eigenvalue derivative (as the sensitivities of
    all six modes give it) and not that of some vector of its null space."""
    from conftest import inverted_stewart

    import dynstiff as ds
    from dynstiff.analyses.sensitivity import frequency_sensitivities
    rob, pose = inverted_stewart(), ds.Pose([0.0, 0.0, 1.5])
    names = ["EA_0", "anchor_1_x"]
    res = propagate_uncertainty(rob, pose, uncertain={"EA_0": "1%", "anchor_1_x": "0.01"},
                                n_modes=2, method="first-order")
    s = frequency_sensitivities(ds.build_model(rob.equilibrium(pose=pose), "dsm"), names,
                                n_modes=6)
    assert s.cluster.tolist()[:3] == [0, 1, 1]
    np.testing.assert_allclose(res.gradient[:2], s.derivative[:2], rtol=1e-9, atol=1e-12)


def test_more_modes_than_the_platform_search_finds(cogiro):
    """n_modes beyond the modes the platform search needs (38 up to CoGiRo's last platform
    mode): the list is continued by the mode search, so every f_k has its value, gradient
    and samples, and the first platform mode keeps its row."""
    import dynstiff as ds
    from dynstiff.analyses.eigen import eigenfrequencies
    from dynstiff.analyses.platform_modes import find_platform_modes
    res = propagate_uncertainty(cogiro, uncertain={"EA": "0.01%:uniform"}, n_modes=45,
                                n_samples=2)
    assert len(res.quantities) == res.nominal.size == res.gradient.shape[0] == 46
    model = ds.build_model(cogiro.robot.equilibrium(pose=cogiro.pose), "dsm")
    pm = find_platform_modes(model)
    assert len(pm.modes.freq_hz) < 45                  # the platform search stops earlier
    np.testing.assert_allclose(res.nominal[:45], eigenfrequencies(model, n_modes=45),
                               rtol=1e-10)
    assert res.nominal[45] == pm.first_hz
    assert np.all(np.isfinite(res.monte_carlo)) and np.all(np.isfinite(res.gradient))


def test_stated_uncertainties_in_more_forms():
    """Exponents in either case, a scale stored as a float, the items of a row joined."""
    assert Uncertain.parse("1E-2") == Uncertain.parse("1e-2") == Uncertain(0.01, "normal",
                                                                           False)
    u = Uncertain(np.int64(2), "uniform", relative=False)
    assert type(u.scale) is float and u.scale == 2.0


def test_a_robot_with_one_platform_mode_and_the_rows_not_asked(cogiro):
    """A one-cable robot (an inclined cable) with its platform free in z has one platform
    mode: its row is taken from it. Without a forbidden band the uncertain row is "not
    asked" and passes; with two stated uncertainties its detail names both, joined by
    "; "."""
    import dynstiff as ds
    one = ds.Robot(np.array([[1.0, 0.0, 5.0]]), np.zeros((1, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(10.0, free_dofs=("z",)), tension_limits=(0.01, 1e6))
    res = propagate_uncertainty(one, [0.0, 0.0, 1.0], uncertain={"EA": "1%"}, n_modes=1,
                                method="first-order")
    i = res.quantities.index("first_platform_hz")
    assert np.isfinite(res.nominal[i]) and np.isfinite(res.gradient[i, 0])
    row, _ = uncertain_row(cogiro.robot, cogiro.pose, CheckOptions(), {"EA": "10%"})
    assert row["verdict"] == "not asked" and row["passed"] is True
    row, _ = uncertain_row(cogiro.robot, cogiro.pose, CheckOptions(forbidden_hz=(0.0, 1.5)),
                           {"EA": "10%", "mass": "2:uniform"}, n_samples=4)
    assert row["detail"].endswith("; EA sigma 10 % (normal); mass +-2 (uniform)")


@pytest.mark.parametrize("kw, message", [
    (dict(scale=True), "^scale must be finite and > 0, got True$"),
    (dict(scale="a"), "^scale must be finite and > 0, got 'a'$"),
    (dict(scale=0.1, relative="no"), "^relative must be True or False, got 'no'$"),
    (dict(scale=0.1, relative=0), "^relative must be True or False, got 0$")])
def test_an_uncertainty_of_a_boolean_scale_or_a_worded_flag_is_refused(kw, message):
    """Uncertain(True) was a scale of 1 (100 %), and relative="no" was relative (a
    non-empty string is true in Python)."""
    with pytest.raises(InvalidParameterError, match=message):
        Uncertain(**kw)
    assert Uncertain(0.1, relative=np.False_).relative is False


@pytest.mark.parametrize("kw, message", [
    (dict(seed=True), "^seed must be an integer >= 0, got True$"),
    (dict(seed=1.5), r"^seed must be an integer >= 0, got 1\.5$"),
    (dict(workers=True), "^workers must be an integer >= 1, got True$"),
    (dict(participation=True), "^participation must be a real number, got True$"),
    (dict(participation=1.5), r"^participation must be in \(0, 1\] \(a platform share\)")])
def test_the_sampling_options_are_checked_naming_them(cogiro, kw, message):
    """seed=1.5 came out as numpy's ValueError, seed=True and workers=True were 1."""
    with pytest.raises(InvalidParameterError, match=message):
        propagate_uncertainty(cogiro, uncertain={"EA": "10%"}, n_samples=4, **kw)


@pytest.mark.parametrize("kw, message", [
    (dict(uncertain={"EAX": "10%"}), "^parameters: 'EAX' is not a parameter"),
    (dict(uncertain={"EA": "10%"}, n_samples=4.0), r"^n_samples must be an integer >= 1, got 4\.0"),
    (dict(uncertain={"EA": "10%"}, seed=True), "^seed must be an integer >= 0, got True")])
def test_a_bad_uncertainty_argument_of_the_checks_is_an_error_not_a_verdict(cogiro, kw, message):
    """The uncertainty row turned the argument's error into the verdict "unknown" ("no nominal
    equilibrium or modes: ..."): the caller's mistake read as the robot's."""
    with pytest.raises(InvalidParameterError, match=message):
        design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 1.5), **kw)


def test_a_scene_robot_or_model_that_is_none_of_them_is_refused():
    with pytest.raises(InvalidParameterError, match="^scene_or_model must be a Scene, a Robot "
                                                    "or a model, got NoneType$"):
        propagate_uncertainty(None, [0.0, 0.0, 1.0], uncertain={"EA": "10%"}, n_samples=4)


def test_a_pose_without_equilibrium_leaves_the_uncertain_row_unknown(cogiro):
    """The arguments are checked before any pose; what the pose itself makes impossible
    (here no equilibrium, 20 m off the frame's centre) stays the verdict "unknown", as in
    the map, never an error."""
    res = design_checks(cogiro.robot, [20.0, 0.0, 1.0], band_hz=(0.0, 1.5),
                        uncertain={"EA": "10%"}, n_samples=4)
    assert res.verdicts["workspace (tension-feasible pose)"] == "fail"
    assert res.verdicts[UNCERTAIN_CHECK] == "unknown"


def test_the_nominal_band_margin_counts_the_modes_up_to_five_percent_above_the_band(cogiro):
    """At participation 0.004 a cable mode at 6.42 Hz (platform share 0.0044), above
    CoGiRo's last platform mode (5.85 Hz, where the platform search stops), is held to the
    band (6.1, 6.2) Hz and sets its margin (0.036 above it; 5.85 Hz is 0.040 below): the
    nominal margin is that of every held mode of a search well beyond the band (12 Hz)."""
    import dynstiff as ds
    from dynstiff.analyses.platform_modes import find_platform_modes
    lo, hi = 6.1, 6.2
    res = propagate_uncertainty(cogiro, uncertain={"EA": "1%"}, n_modes=1, n_samples=2,
                                band_hz=(lo, hi), participation=0.004, method="first-order")
    model = ds.build_model(cogiro.robot.equilibrium(pose=cogiro.pose), "dsm")
    m = find_platform_modes(model, 12.0).modes
    f = np.asarray(m.freq_hz)[np.asarray(m.platform_share) >= 0.004]
    ref = np.min(np.maximum(f / hi - 1.0, 1.0 - f / lo))
    assert 0.03 < ref < 0.04 and f[np.argmin(np.maximum(f / hi - 1, 1 - f / lo))] > hi
    assert res.nominal[res.quantities.index("band_margin")] == pytest.approx(ref, rel=1e-9)


def test_a_stated_pose_coordinate_and_a_distribution_not_known():
    """A pose coordinate is uncertain at the pose given (pose_z = 1 m of CoGiRo's scene),
    the result names its parameters; a distribution not known is refused in words."""
    import dynstiff as ds
    sc = ds.load_scene("cogiro")
    res = propagate_uncertainty(sc, uncertain={"pose_z": "0.001", "EA": "1%"}, n_modes=1,
                                n_samples=2, method="first-order")
    assert res.parameters == ("pose_z", "EA")
    assert res.nominal_values[0] == sc.pose.position[2] == 1.0
    with pytest.raises(InvalidParameterError, match=r"^distribution must be one of "
                                                    r"\('normal', 'uniform'\), got 'lognormal'$"):
        Uncertain(0.1, "lognormal")
