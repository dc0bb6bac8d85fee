"""Design checks (dynstiff/analyses/checks.py); the `dynstiff check` command is run in
test_cli.py."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.checks import design_checks
from dynstiff.errors import InvalidParameterError


def rows_by_name(res):
    return {r["check"]: r for r in res.rows}


def test_checks_pass_and_fail_on_cogiro():
    scene = ds.load_scene("cogiro")
    f = ds.modes(ds.FrequencyModel(scene.equilibrium()), 40)
    fg = f.freq_hz[np.array(f.kind) == "global"]
    ok = design_checks(scene.robot, scene.pose, band_hz=(0.5, 0.9 * fg[0] / 1.05))
    assert ok.passed
    # a band around the 2nd global mode must fail exactly that check
    bad = design_checks(scene.robot, scene.pose, band_hz=(fg[1] * 0.99, fg[1] * 1.01))
    r = rows_by_name(bad)
    assert not bad.passed and not r["platform modes outside band"]["passed"]
    # two root searches, each converged to 1e-12 relative
    assert abs(r["platform modes outside band"]["value"] / fg[1] - 1) < 1e-11
    assert r["tension limits"]["passed"] and r["sag / chord"]["passed"]
    # sag limit below the largest sag ratio fails
    s = max(st.sag / st.chord_length for st in scene.equilibrium().states)
    r = rows_by_name(design_checks(scene.robot, scene.pose, max_sag_ratio=0.99 * s))
    assert not r["sag / chord"]["passed"] and abs(r["sag / chord"]["value"] - s) < 1e-12


def test_proximity_check_at_stiff_cables():
    """At E = 120 GPa CoGiRo's global modes sit among cable families (theory.md §9.2): the
    proximity row fails exactly when a local mode (platform share < 5 %) lies within 2 % of
    a platform mode. The platform modes are found here from their definition over all the
    modes below 20 Hz (each DOF's largest participation up to the frequency by which every
    DOF is half found, and the global modes below it)."""
    scene = ds.load_scene("cogiro")
    r0 = scene.robot
    rob = ds.Robot(r0.anchors, r0.attachments, ds.Cable(0.064, 8.2051e-6 * 120e9), r0.platform,
                   tension_limits=r0.tension_limits)
    m = ds.modes(ds.FrequencyModel(rob.equilibrium(pose=scene.pose)), fmax_hz=20.0)
    p = m.participation
    found = max(np.flatnonzero(np.cumsum(p[:, j]) >= 0.5)[0] for j in range(6))
    assert found < len(m) - 1
    platform = {int(np.argmax(p[:found + 1, j])) for j in range(6)}
    platform |= {k for k in range(found + 1) if m.kind[k] == "global"}
    fp = m.freq_hz[sorted(platform)]
    fl = m.freq_hz[np.array(m.kind) == "local"]
    gaps = np.abs(fl[None, :] - fp[:, None]) / fp[:, None]
    res = rows_by_name(design_checks(rob, scene.pose, band_hz=(0.1, 7.0), proximity_rtol=0.02))
    row = res["local modes near platform modes"]
    assert row["verdict"] == ("fail" if gaps.min() <= 0.02 else "pass")
    if row["verdict"] == "fail":
        assert row["value"] == pytest.approx(gaps.min(), rel=1e-12)


def test_band_below_every_mode_passes(cogiro):
    """A forbidden band whose 1.5x top is below the first natural frequency: no mode is
    computed below fmax, and the check passes (it used to fail on the empty mode list)."""
    rob = cogiro.robot
    stiff = ds.Robot(rob.anchors, rob.attachments, ds.Cable(0.064, 8.2051e-6 * 120e9),
                     rob.platform, tension_limits=rob.tension_limits)
    f1 = ds.eigenfrequencies(ds.FrequencyModel(stiff.equilibrium(pose=cogiro.pose)), 1)[0]
    res = rows_by_name(design_checks(stiff, cogiro.pose, band_hz=(0.4 * f1, 0.6 * f1)))
    assert res["platform modes outside band"]["verdict"] == "pass"
    assert res["local modes near platform modes"]["verdict"] in ("pass", "fail")


def test_cable_model_row_is_the_models_estimated_error_over_the_band_of_interest():
    """The cable-model row holds the estimate of dynstiff.analyses.recommend.estimated_error
    up to the band of interest's top: on CoGiRo to 12 Hz 2.2e-4, above the 1.6e-4 measured
    against the exact rung (recommend_model), below 1 %; on sixcable (20 m heavy cables) the
    closed form's robot-level bound (theory.md §11.6) is 2.5e-2 (measured 4e-3), so it fails
    1e-3 naming the cable and warns;
    the exact rung passes at its floor; the massless catenary passes below CoGiRo's first
    platform mode (2.2 Hz) and misses the cable modes from 3.2 Hz (inf)."""
    from dynstiff.analyses.recommend import estimated_error, recommend_model
    scene = ds.load_scene("cogiro")
    eq = scene.equilibrium()
    r = rows_by_name(design_checks(scene.robot, scene.pose, model_band_hz=(0.1, 12.0)))
    r = r["cable model"]
    est = estimated_error(ds.FrequencyModel(eq), (0.1, 12.0))[0]
    assert r["passed"] and r["value"] == est
    assert recommend_model(eq, (0.1, 12.0), 1e-2).errors["dsm"] < est < 1e-3
    six = ds.load_scene("sixcable")
    with pytest.warns(ds.errors.ClosedFormWarning, match="coupled modes"):
        r = rows_by_name(design_checks(six.robot, six.pose, model_rtol=1e-3,
                                       model_band_hz=(0.05, 2.0)))["cable model"]
    assert not r["passed"] and 1e-2 < r["value"] < 3e-2 and "cable" in r["detail"]
    with pytest.raises(InvalidParameterError, match="model_rtol"):
        design_checks(six.robot, six.pose, model_rtol=-1.0)
    r = rows_by_name(design_checks(six.robot, six.pose, model_rtol=1e-3, rung="exact",
                                   model_band_hz=(0.05, 2.0)))["cable model"]
    assert r["passed"] and r["value"] <= 1e-8
    for top, verdict in ((2.0, "pass"), (6.0, "fail")):
        r = rows_by_name(design_checks(scene.robot, scene.pose, rung="catenary",
                                       model_band_hz=(0.0, top)))["cable model"]
        assert r["verdict"] == verdict and (r["value"] < 1e-2 if verdict == "pass"
                                            else r["value"] == np.inf)


def test_checks_run_on_any_rung(cogiro):
    """The modal checks take their model from the ladder: the lumped model (N = 8) gives the
    closed form's verdicts at CoGiRo's pose, its cable-model row its own segment error."""
    band = (0.0, 1.5)
    rows = {r: rows_by_name(design_checks(cogiro.robot, cogiro.pose, band_hz=band, rung=r,
                                          model_band_hz=(0.1, 6.0),
                                          **({"segments": 8} if r == "lumped" else {})))
            for r in ("dsm", "lumped")}
    for name in ("tension limits", "platform modes outside band",
                 "local modes near platform modes"):
        assert rows["lumped"][name]["verdict"] == rows["dsm"][name]["verdict"]
    assert "8 segments per cable" in rows["lumped"]["cable model"]["detail"]
    with pytest.raises(InvalidParameterError, match="rung"):
        design_checks(cogiro.robot, cogiro.pose, rung="fem")


def test_mixed_platform_mode_in_band_fails_with_its_share():
    """CoGiRo with a 50 kg platform: the 2.216 Hz mode holds 42 % of its kinetic energy in
    the platform (a "local" mode by the old > 50 % rule, which let the check pass). Both the
    margin check and the receptance check fail, the margin row naming the mode and share."""
    from test_analyses_participation import with_mass
    scene = ds.load_scene("cogiro")
    rob = with_mass(scene.robot, 50.0)
    res = design_checks(rob, scene.pose, band_hz=(2.0, 2.3))
    r = rows_by_name(res)
    assert not res.passed
    row = r["platform modes outside band"]
    assert not row["passed"] and abs(row["value"] - 2.216) < 5e-4
    assert "platform share 42 %" in row["detail"]
    assert not r["platform receptance in band"]["passed"]
    assert r["platform receptance in band"]["value"] > 10
    # a threshold above its share lets the margin row pass (it is the threshold that holds it)
    r = rows_by_name(design_checks(rob, scene.pose, band_hz=(2.0, 2.3), participation=0.45))
    assert r["platform modes outside band"]["passed"]
    with pytest.raises(InvalidParameterError, match="participation"):
        design_checks(rob, scene.pose, band_hz=(2.0, 2.3), participation=0.7)
    with pytest.raises(InvalidParameterError, match="frf_limit"):
        design_checks(rob, scene.pose, band_hz=(2.0, 2.3), frf_limit=0.5)


def test_default_cogiro_verdicts():
    """The 91 kg CoGiRo at its central pose and its 0-1.5 Hz forbidden band: the nearest
    mode holding >= 5 % platform energy is the 2.206 Hz z mode (99 %), 47 % above the band,
    and the z receptance at 1.5 Hz is 1.85 x static (the 1 / (1 - (1.5 / 2.206)^2) = 1.86 of
    one mode): every check passes."""
    scene = ds.load_scene("cogiro")
    res = design_checks(scene.robot, scene.pose, band_hz=(0.0, 1.5), model_band_hz=(0.1, 12.0))
    r = rows_by_name(res)
    assert res.passed
    assert abs(r["platform modes outside band"]["value"] - 2.2061) < 1e-3
    assert "platform share 99 %" in r["platform modes outside band"]["detail"]
    assert r["platform receptance in band"]["value"] == pytest.approx(
        1 / (1 - (1.5 / 2.2061) ** 2), rel=0.02)


@pytest.mark.parametrize("lo_factor, verdict", [(1.005, "fail"), (1.02, "pass")])
def test_a_mode_just_below_the_forbidden_band_is_held_to_the_margin(lo_factor, verdict):
    """The margin applies below the band too: CoGiRo's first mode (2.206 Hz, global) 0.5 %
    below a band starting at 1.005 f1 is within a 1 % margin (fail), 2 % below it is not
    (pass); the band's top, 2.3 Hz with 1 %, stays clear of the next mode (2.359 Hz)."""
    scene = ds.load_scene("cogiro")
    f1 = ds.eigenfrequencies(ds.FrequencyModel(scene.equilibrium()), 1)[0]
    row = rows_by_name(design_checks(scene.robot, scene.pose, band_hz=(lo_factor * f1, 2.3),
                                     margin=0.01))["platform modes outside band"]
    assert row["verdict"] == verdict
    assert row["value"] == pytest.approx(f1, rel=1e-11)


def test_rich_display_holds_every_verdict_and_reason():
    from conftest import assert_valid_html
    scene = ds.load_scene("cogiro")
    res = design_checks(scene.robot, scene.pose, band_hz=(0.5, 1.0))
    text = assert_valid_html(res._repr_html_())
    for r in res.rows:
        assert r["check"] in text and r["detail"] in text
        assert r["verdict"].upper() in text


@pytest.mark.parametrize("damping, options", [
    (ds.Damping(), {}), (ds.Damping(0.02, 0.0), {"tension": "chord"}),
    (ds.Damping(0.0, 0.03), {"chordwise_inertia": False, "guard_rtol": 0.05}),
    (ds.Damping(0.01, 0.01, 0.5), {}),                  # viscous: built anew (re-statics)
    (ds.Damping(), {"cable_loss_factor": 0.02})])      # a damped model: built anew
def test_the_damped_model_from_the_undamped_one_is_the_damped_build(cogiro_eq, damping,
                                                                   options):
    """damped_model(..., like=the undamped model) is the model damped_model builds: the same
    K(omega) bit for bit at real and complex omega, the same damping, undamped copy, static
    error and roots; an undamped model of another pose is not used."""
    from dynstiff.analyses.checks import damped_model
    eq = cogiro_eq
    like = ds.build_model(eq, "dsm", **options)
    like.massless_stiffness(), like.static_error()   # computed before the copy is made
    a = damped_model(eq, damping, "dsm", **options)
    b = damped_model(eq, damping, "dsm", like, **options)
    assert b is not like and type(b) is type(a)
    w = 2 * np.pi * np.linspace(0.0, 3.0, 61)
    for om in (w, w * (1 + 0.2j)):
        np.testing.assert_array_equal(a.dynamic_stiffness(om), b.dynamic_stiffness(om))
    assert (a.damped, a.damping_text(), a.guard_rtol) == (b.damped, b.damping_text(),
                                                          b.guard_rtol)
    np.testing.assert_array_equal(a.massless_stiffness(), b.massless_stiffness())
    np.testing.assert_array_equal(a.undamped().dynamic_stiffness(w),
                                  b.undamped().dynamic_stiffness(w))
    assert a.static_error() == b.static_error()
    np.testing.assert_array_equal(ds.eigenfrequencies(a, n_modes=8),
                                  ds.eigenfrequencies(b, n_modes=8))
    # the undamped model's cable terms are shared (the same arrays, not recomputed) when
    # only the model damping differs: no viscous damping, no damping among the options
    shared = [k for k, v in vars(like).items()
              if isinstance(v, np.ndarray) and vars(b).get(k) is v]
    reusable = damping.cable_viscous_damping == 0 and "cable_loss_factor" not in options
    assert bool(shared) == reusable, shared
    assert not [k for k, v in vars(like).items()
                if isinstance(v, np.ndarray) and vars(a).get(k) is v]
    other = ds.build_model(eq.robot.equilibrium(pose=[1.0, 0.5, 1.2]), "dsm", **options)
    c = damped_model(eq, damping, "dsm", other, **options)
    np.testing.assert_array_equal(a.dynamic_stiffness(w), c.dynamic_stiffness(w))


def test_the_static_error_and_massless_stiffness_are_computed_once(cogiro_eq):
    """The closed form's static error and massless stiffness are the model's (computed
    once): repeated calls agree, and changing the returned matrix does not change the
    model's."""
    from dynstiff.models import dsm_guard
    m = ds.FrequencyModel(cogiro_eq)
    assert m.static_error() == m.static_error() == dsm_guard.static_error(m)
    K = m.massless_stiffness()
    K[0, 0] = np.nan
    np.testing.assert_array_equal(m.massless_stiffness(), m.dynamic_stiffness(0.0)[0].real)


@pytest.mark.parametrize("kw, message", [
    (dict(participation=0.5 + 1e-12), r"participation must be in \(0, 0\.5\]"),
    (dict(participation=0.0), "^participation must be > 0"),
    (dict(frf_limit=-1.0), "^frf_limit must be > 0"),
    (dict(frf_limit=1.0), "frf_limit must be > 1, got 1.0"),
    (dict(max_modes=True), "max_modes must be an integer >= 1, got True"),
    (dict(max_modes=2.0), "max_modes must be an integer >= 1, got 2.0"),
    (dict(max_modes=0), "max_modes must be an integer >= 1, got 0"),
    (dict(band_hz=(2.0, 2.0)), r"band_hz must be \(low, high\) with 0 <= low < high \[Hz\], "
                               r"got \(2\.0, 2\.0\)"),
    (dict(band_hz=(-1.0, 2.0)), r"band_hz must be \(low, high\)"),
    (dict(band_hz=3.0), r"band_hz must be \(low, high\)"),
    (dict(model_band_hz=(5.0, 1.0)), r"model_band_hz must be \(low, high\)"),
    (dict(margin=-0.1), "^margin must be"), (dict(proximity_rtol=0.0), "^proximity_rtol "),
    (dict(max_sag_ratio=np.nan), "^max_sag_ratio "), (dict(model_rtol=-1.0), "^model_rtol ")])
def test_check_options_name_each_bad_argument(kw, message):
    from dynstiff.analyses.checks import check_options
    with pytest.raises(InvalidParameterError, match=message):
        check_options(**kw)


def test_check_options_keep_what_they_are_given():
    from dynstiff.analyses.checks import check_options
    from dynstiff.analyses.verdicts import CheckOptions
    o = check_options(band_hz=(0, 2), margin=0, proximity_rtol=0.01, max_sag_ratio=0.1,
                      model_rtol=0.2, participation=0.5, frf_limit=1.5,
                      model_band_hz=(1, 3), max_modes=7)
    assert o == CheckOptions(forbidden_hz=(0.0, 2.0), margin=0.0, participation=0.5,
                             frf_limit=1.5, proximity_rtol=0.01, max_sag_ratio=0.1,
                             model_rtol=0.2, model_band_hz=(1.0, 3.0), max_modes=7)
    assert check_options().forbidden_hz is None
    assert check_options().model_band_hz == (0.0, 20.0)
    assert check_options() == CheckOptions(model_band_hz=(0.0, 20.0))    # the defaults
    assert type(check_options(max_modes=np.int64(5)).max_modes) is int


def test_the_exact_rungs_band_holds_what_the_checks_compute():
    """fmax_hz of the exact rung: 1.1 x the highest of the band of interest and the
    forbidden band's top with its margin, times (1 + proximity_rtol); other rungs and a
    given fmax_hz are left alone."""
    from dynstiff.analyses.checks import check_options, modal_model_options
    o = check_options(band_hz=(1.0, 30.0), margin=0.1, proximity_rtol=0.05,
                      model_band_hz=(0.0, 20.0))
    got = modal_model_options("exact", o, {"segments": 3})
    assert got == {"fmax_hz": pytest.approx(1.1 * 33.0 * 1.05, rel=1e-15), "segments": 3}
    o = check_options(band_hz=(1.0, 10.0), margin=0.1, proximity_rtol=0.05,
                      model_band_hz=(0.0, 20.0))
    assert modal_model_options("exact", o, {})["fmax_hz"] == pytest.approx(1.1 * 20 * 1.05)
    no_band = check_options(model_band_hz=(0.0, 8.0), proximity_rtol=0.03)
    assert modal_model_options("exact", no_band, {})["fmax_hz"] == pytest.approx(
        1.1 * 8 * 1.03)
    assert modal_model_options("exact", o, {"fmax_hz": 5.0}) == {"fmax_hz": 5.0}
    assert modal_model_options("dsm", o, {"tension": "x"}) == {"tension": "x"}


def test_the_design_checks_refuse_bad_damping_rung_and_confidence(cogiro):
    pose = cogiro.pose
    with pytest.raises(InvalidParameterError, match="damping must be a dynstiff.Damping"):
        design_checks(cogiro.robot, pose, damping=0.02)
    with pytest.raises(InvalidParameterError, match="rung must be one of"):
        design_checks(cogiro.robot, pose, rung="beam")
    for bad in (1.0, 0.0, 1, "0.9"):
        with pytest.raises(InvalidParameterError, match=r"confidence must be a number in "
                                                        r"\(0, 1\), got"):
            design_checks(cogiro.robot, pose, confidence=bad)
    from dynstiff.analyses.checks import damped_model
    with pytest.raises(InvalidParameterError, match="damping must be a dynstiff.Damping"):
        damped_model(cogiro.equilibrium(), damping=None)


def test_repr_and_text_of_a_result(cogiro):
    res = design_checks(cogiro.robot, cogiro.pose, band_hz=(2.0, 2.3))
    bad = [f"{r['check']} ({r['verdict']})" for r in res.rows if not r["passed"]]
    assert bad and repr(res) == (f"CheckResult(FAILED: {', '.join(bad)}; "
                                 f"{len(res.rows)} checks)")
    lines = res.text().splitlines()
    assert lines[-1] == "some checks FAILED" and len(lines) == len(res.rows) + 1
    assert lines[3].startswith("FAIL    platform modes outside band ")
    ok = design_checks(cogiro.robot, cogiro.pose)
    assert repr(ok) == f"CheckResult(passed; {len(ok.rows)} checks)"
    text = ok.text().splitlines()
    assert text[-1] == "all checks passed"
    assert "<p><b>Design checks: all passed</b></p>" in ok._repr_html_()
    html = res._repr_html_()
    assert "<p><b>Design checks: some FAILED</b></p>" in html
    assert "<tr><th>verdict</th><th>check</th><th>detail</th></tr>" in html
    assert text[3] == "n/a     platform modes outside band       no forbidden band given"
    assert rows_by_name(ok)["cable model"]["limit"] == 1e-2        # the default model_rtol
    frame = ok.to_frame()
    unknown = design_checks(cogiro.robot, cogiro.pose, max_modes=3).text().splitlines()
    assert unknown[5].startswith("UNKNOWN local modes near platform modes ")
    assert list(frame["verdict"]) == [r["verdict"] for r in ok.rows]


def test_the_receptance_check_uses_the_models_options_with_viscous_damping(cogiro):
    """With viscous cable damping the damped model is built anew: with the model options
    of the checks (here the chord tension), so the receptance row is that model's."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.analyses.participation import receptance_amplification
    band, damping = (1.5, 3.0), ds.Damping(0.01, 0.01, 0.5)
    res = design_checks(cogiro.robot, cogiro.pose, band_hz=band, damping=damping,
                        tension="chord")
    value = rows_by_name(res)["platform receptance in band"]["value"]
    eq = cogiro.equilibrium()
    chord = receptance_amplification(damped_model(eq, damping, tension="chord"), band,
                                     res.platform.modes.freq_hz)[0]
    plain = receptance_amplification(damped_model(eq, damping), band,
                                     res.platform.modes.freq_hz)[0]
    assert value == pytest.approx(chord, rel=1e-12) and abs(chord - plain) > 1e-6 * chord
    # the viscous part is added to each cable's own; the robot keeps its name and limits
    rob = damped_model(eq, damping).equilibrium.robot
    assert rob.name == eq.robot.name and rob.tension_limits == eq.robot.tension_limits
    assert [c.viscous_damping for c in rob.cables] == [c.viscous_damping + 0.5
                                                       for c in eq.robot.cables]


@pytest.mark.parametrize("robot, pose, message", [
    ("cogiro", [np.nan, 0.0, 1.0], "^pose position must be 3 finite numbers"),
    ("cogiro", [True, 0, 1], "^pose must be real numbers, not booleans"),
    ("cogiro", [0.0, 0.0, 1.0, 0.0, 0.0], "^pose must be a Pose, .*, 3 or 6 numbers"),
    (None, [0.0, 0.0, 1.0], "^robot must be a dynstiff.Robot, got NoneType")])
def test_a_pose_or_robot_that_is_not_one_is_an_error_not_a_fail_verdict(robot, pose, message):
    """design_checks(robot, [nan, 0, 1]) gave the verdict "fail" (statics) and "unknown"
    (the rest), the message of the bad pose in the row's detail: the caller's mistake
    signed as the robot's failure. The command line and the map refused it already."""
    sc = ds.load_scene("cogiro")
    with pytest.raises(InvalidParameterError, match=message):
        design_checks(sc.robot if robot == "cogiro" else robot, pose)


def test_stated_uncertainties_add_the_last_row_with_its_samples(cogiro):
    """uncertain= adds a last row (the uncertain_row of the same options, samples and seed)
    and the distributions behind it; its names are checked at the pose before any work."""
    from dynstiff.analyses.uncertainty import UNCERTAIN_CHECK
    from dynstiff.analyses.verdicts import CheckOptions
    unc = {"EA": "10%", "pose_z": "0.001"}
    res = design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 1.5), uncertain=unc,
                        n_samples=8, seed=3)
    assert [r["check"] for r in res.rows[:-1]] == [r["check"] for r in design_checks(
        cogiro.robot, cogiro.pose, band_hz=(0.0, 1.5)).rows]
    last = res.rows[-1]
    assert last["check"] == UNCERTAIN_CHECK
    assert "Monte Carlo, 8 samples, seed 3" in last["detail"]
    u = res.uncertainty
    assert u.samples.shape == (8, 2) and u.seed == 3
    from dynstiff.analyses.uncertainty import uncertain_row
    row, _ = uncertain_row(cogiro.robot, cogiro.pose, CheckOptions(forbidden_hz=(0.0, 1.5)),
                           unc, n_samples=8, seed=3)
    assert row == last
    with pytest.raises(InvalidParameterError, match="nope"):
        design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 1.5), uncertain={"nope": "1%"})
    with pytest.raises(InvalidParameterError, match="^n_samples must be an integer >= 1"):
        design_checks(cogiro.robot, cogiro.pose, band_hz=(0.0, 1.5), uncertain=unc,
                      n_samples=0)
