"""Design checks (dynstiff/checks.py); the `dynstiff check` command is run in test_cli.py."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.checks import design_checks
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
    assert not bad.passed and not r["global modes outside band"]["passed"]
    # two root searches, each converged to 1e-12 relative
    assert abs(r["global modes outside band"]["value"] / fg[1] - 1) < 1e-11
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
    assert res["global modes outside band"]["passed"]
    assert res["local modes near global modes"]["passed"]


def test_cable_model_row_names_the_model_the_checks_need():
    """CoGiRo: the closed-form DSM meets 1 % up to the checked modes (its predicted error is
    recommend_model's); sixcable (20 m heavy cables, sag 2.4 %): it does not, and the row
    names the lumped model."""
    from dynstiff.recommend import recommend_model
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
    for name in ("tension limits", "global modes outside band", "local modes near global modes",
                 "cable model"):
        assert rows["lumped"][name]["passed"] == rows["dsm"][name]["passed"]
    assert "lumped-mass model used here" in rows["lumped"]["cable model"]["detail"]
    assert rows["catenary"]["cable model"]["passed"]
    wide = rows_by_name(design_checks(cogiro.robot, cogiro.pose, band_hz=band, fmax_hz=6.0,
                                      rung="catenary"))["cable model"]
    assert not wide["passed"] and wide["value"] == np.inf
    with pytest.raises(InvalidParameterError, match="rung"):
        design_checks(cogiro.robot, cogiro.pose, rung="fem")
