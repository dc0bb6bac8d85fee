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
    """At E = 120 GPa CoGiRo's global modes sit among cable families (theory.md §9.2)."""
    scene = ds.load_scene("cogiro")
    r0 = scene.robot
    rob = ds.Robot(r0.anchors, r0.attachments, ds.Cable(0.064, 8.2051e-6 * 120e9), r0.platform,
                   tension_limits=r0.tension_limits)
    m = ds.modes(ds.FrequencyModel(rob.equilibrium(pose=scene.pose)), 40)
    warns = ds.proximity_warnings(m, rtol=0.02)
    res = rows_by_name(design_checks(rob, scene.pose, band_hz=(0.1, 7.0), proximity_rtol=0.02))
    assert res["local modes near global modes"]["passed"] == (len(
        [w for w in warns if w.freq_global_hz <= 10.5]) == 0)


def test_band_below_every_mode_passes(cogiro):
    """A forbidden band whose 1.5x top is below the first natural frequency: no mode is
    computed below fmax, and the check passes (it used to fail on the empty mode list)."""
    rob = cogiro.robot
    stiff = ds.Robot(rob.anchors, rob.attachments, ds.Cable(0.064, 8.2051e-6 * 120e9),
                     rob.platform, tension_limits=rob.tension_limits)
    f1 = ds.eigenfrequencies(ds.FrequencyModel(stiff.equilibrium(pose=cogiro.pose)), 1)[0]
    res = rows_by_name(design_checks(stiff, cogiro.pose, band_hz=(0.4 * f1, 0.6 * f1)))
    assert res["platform modes outside band"]["passed"]
    assert res["local modes near global modes"]["passed"]


def test_cable_model_row_names_the_model_the_checks_need():
    """CoGiRo: the closed-form DSM meets 1 % up to the checked modes (its predicted error is
    recommend_model's); sixcable (20 m heavy cables, sag 2.4 %): it does not, and the row
    names the lumped model."""
    from dynstiff.analyses.recommend import recommend_model
    scene = ds.load_scene("cogiro")
    res = design_checks(scene.robot, scene.pose, band_hz=(0.0, 1.5))
    r = rows_by_name(res)["cable model"]
    rec = recommend_model(scene.equilibrium(), band_hz=(0.0, 1.5 * 1.5 * 1.03), rtol=1e-2)
    assert r["passed"] and r["value"] == rec.errors["dsm"] and r["value"] < 1e-3
    six = ds.load_scene("sixcable")
    # sixcable (20 m heavy cables, sag 2.4 %): the closed form's local modes are 5e-3 off the
    # exact model's (measured by the guard), so it fails 1e-3 and the row names the exact rung
    r = rows_by_name(design_checks(six.robot, six.pose, model_rtol=1e-3))["cable model"]
    assert not r["passed"] and 1e-3 < r["value"] < 1e-2 and "exact" in r["detail"]
    with pytest.raises(InvalidParameterError, match="model_rtol"):
        design_checks(six.robot, six.pose, model_rtol=-1.0)
    # a looser tolerance lets the DSM pass there
    r = rows_by_name(design_checks(six.robot, six.pose, model_rtol=1e-2))["cable model"]
    assert r["passed"]
    r = rows_by_name(design_checks(six.robot, six.pose, model_rtol=1e-3, rung="exact",
                                   fmax_hz=3.0))["cable model"]
    assert r["passed"] and r["value"] <= 1e-8


def test_checks_run_on_any_rung(cogiro):
    """The modal checks take their model from the ladder. The lumped model (N = 8) gives the
    closed form's verdicts at CoGiRo's pose. The massless catenary is adequate while the
    checked modes stay below the first cable mode (3.2 Hz; modes to 2.3 Hz for a 0-1.5 Hz
    band) and fails its own "cable model" row (predicted error inf) once they do not."""
    band = (0.0, 1.5)
    rows = {r: rows_by_name(design_checks(cogiro.robot, cogiro.pose, band_hz=band, rung=r,
                                          **({"segments": 8} if r == "lumped" else {})))
            for r in ("dsm", "lumped", "catenary")}
    for name in ("tension limits", "platform modes outside band", "local modes near global modes",
                 "cable model"):
        assert rows["lumped"][name]["passed"] == rows["dsm"][name]["passed"]
    assert "lumped-mass model used here" in rows["lumped"]["cable model"]["detail"]
    assert rows["catenary"]["cable model"]["passed"]
    wide = rows_by_name(design_checks(cogiro.robot, cogiro.pose, band_hz=band, fmax_hz=6.0,
                                      rung="catenary"))["cable model"]
    assert not wide["passed"] and wide["value"] == np.inf
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
    assert 0.40 < row["share"] < 0.44 and "platform share 42 %" in row["detail"]
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
    assert r["platform modes outside band"]["share"] > 0.98
    assert r["platform receptance in band"]["value"] == pytest.approx(
        1 / (1 - (1.5 / 2.2061) ** 2), rel=0.02)
