"""The verdicts of a pose (dynstiff/analyses/verdicts.py, theory.md §12.1): one set of rows
for the design checks, the workspace maps and the reports; each check moved by its own
options only; nothing passes on modes not computed."""

import dataclasses
import re
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.analyses.checks import design_checks
from dynstiff.analyses.platform_modes import find_platform_modes

IPA = ("tests/data/caspr/IPAnema_1_bodies.xml", "tests/data/caspr/IPAnema_1_cables.xml")
#: Each check and the options that may move its verdict (the rest must not).
OWN = {"workspace (tension-feasible pose)": (),
       "tension limits": (),
       "sag / chord": ("max_sag_ratio",),
       "platform modes outside band": ("band_hz", "margin", "participation"),
       "platform receptance in band": ("band_hz", "frf_limit"),
       "local modes near platform modes": ("proximity_rtol",),
       "cable model": ("model_rtol", "model_band_hz")}


@pytest.fixture(scope="module")
def cogiro():
    return ds.load_scene("cogiro")


def verdicts(robot, pose, **kw):
    return design_checks(robot, pose, **kw).verdicts


def real(lo, hi):
    return st.floats(lo, hi, allow_subnormal=False)


@settings(max_examples=8, deadline=None)
@given(band=st.one_of(st.none(), st.tuples(real(0.0, 3.0), real(0.2, 3.0))
                      .map(lambda b: (b[0], b[0] + b[1]))),
       margin=real(0.0, 0.2), participation=real(0.01, 0.5), frf_limit=real(1.5, 50.0),
       proximity_rtol=real(0.005, 0.05), max_sag_ratio=real(1e-3, 0.05),
       model_rtol=real(1e-4, 1e-1), top=real(2.0, 14.0))
def test_each_verdict_moves_with_its_own_options_only(cogiro, band, margin, participation,
                                                      frf_limit, proximity_rtol,
                                                      max_sag_ratio, model_rtol, top):
    """Every option drawn at once gives each check the verdict it has with only its own
    options set (the others at their defaults): the forbidden band does not move the
    proximity verdict, the band of interest does not move the margin, and so on."""
    opts = dict(band_hz=band, margin=margin, participation=participation,
                frf_limit=frf_limit, proximity_rtol=proximity_rtol,
                max_sag_ratio=max_sag_ratio, model_rtol=model_rtol,
                model_band_hz=(0.0, top))
    got = verdicts(cogiro.robot, cogiro.pose, **opts)
    for check, own in OWN.items():
        alone = verdicts(cogiro.robot, cogiro.pose, **{k: opts[k] for k in own})
        assert got[check] == alone[check], (check, opts)


# the closed form's robot-level bound warns on sixcable and fast (theory.md §11.6): not the subject
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
def test_sixcable_proximity_verdict_does_not_move_with_a_forbidden_band():
    """sixcable fails "local modes near platform modes" with and without the 0.3-0.5 Hz
    forbidden band (the band once changed how many modes were computed, and so the verdict)."""
    six = ds.load_scene("sixcable")
    a = design_checks(six.robot, six.pose)
    b = design_checks(six.robot, six.pose, band_hz=(0.3, 0.5))
    key = "local modes near platform modes"
    assert a.verdicts[key] == b.verdicts[key] == "fail"
    row = {r["check"]: r for r in a.rows}[key]
    assert row["value"] == {r["check"]: r for r in b.rows}[key]["value"]


@pytest.fixture(scope="module")
def ipanema():
    """IPAnema 1 from CASPR with a light cable (0.0095 kg/m, EA 1e5 N, 10-200 N): its x
    platform mode (13.4 Hz) lies above 20 modes, 13 of them local."""
    scene = ds.scenes.import_caspr(*IPA, cable=ds.Cable(0.0095, 1e5))
    return dataclasses.replace(scene, robot=dataclasses.replace(
        scene.robot, tension_limits=(10.0, 200.0)))


def test_map_check_and_report_agree_on_an_imported_robot_with_high_platform_modes(
        ipanema, tmp_path):
    """At every pose of a small grid the workspace map (20 modes stored), design_checks and
    the report give the same verdict for every check; no pose passes with a platform mode
    uncomputed, and at the home pose a platform mode lies above the 20 modes stored."""
    rob = ipanema.robot
    kw = dict(band_hz=(0.0, 0.3), model_band_hz=(0.1, 12.0))
    with warnings.catch_warnings():      # light cables: the guard speaks of a few poses
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
        w = ds.workspace(rob, box=(-0.3, 0.3, -0.3, 0.3, 0.8, 1.1), step=0.3, n_modes=20,
                         **kw)
        table = w.dynstiff.to_frame()
        assert 0 < table["dynamic"].sum() < table["feasible"].sum() < len(table)
        failing = (table.filter(like="check: ") != "pass").sum(axis=1)
        assert ((failing == 1) & ~table["dynamic"]).any()      # one failure is enough
        for _, row in table.iterrows():
            res = design_checks(rob, [row.x, row.y, row.z], **kw)
            mapped = {c: row[f"check: {c}"] for c in w["check"].values}
            assert mapped == res.verdicts, (row.x, row.y, row.z)
            assert row.dynamic == res.passed
            assert not row.dynamic or np.isfinite(row.first_platform_hz)
        from dynstiff.analyses.settings import analysis_settings
        from dynstiff.report.robot import robot_report
        for pose in ([0.0, 0.0, 1.1], [-0.3, -0.3, 0.8]):
            scene = dataclasses.replace(ipanema, pose=ds.Pose(pose))
            st = analysis_settings(scene, forbidden_hz=kw["band_hz"], band_hz=kw["model_band_hz"])
            robot_report(scene, tmp_path / str(pose), settings=st, n_points=50, html=False)
            import pandas as pd
            report = pd.read_csv(tmp_path / str(pose) / "checks.csv", comment="#")
            assert dict(zip(report["check"], report["verdict"])) == \
                design_checks(rob, pose, **kw).verdicts
        m = ds.build_model(rob.equilibrium(pose=[0.0, 0.0, 1.1]), "dsm")
        pm = find_platform_modes(m)
    f20 = ds.eigenfrequencies(m, 20)[-1]
    assert pm.freq_hz.max() > f20 and pm.complete
    home = table[(table.x == 0) & (table.y == 0) & (table.z == 1.1)].iloc[0]
    assert home.first_platform_hz == pytest.approx(pm.first_hz, rel=1e-9)


def test_fast_platform_modes_found_by_participation_and_said_to_be_spread():
    # FAST feed support: the cables weigh ~0.9 x the cabin; no mode below 2 Hz keeps half of
    # its kinetic energy in the cabin for x, y, z, rz, yet the carriers are found
    sc = ds.load_scene("fast")
    eq = sc.equilibrium()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)   # the bound's subject
        res = design_checks(sc.robot, eq.pose, band_hz=sc.forbidden_band_hz)
        pm = find_platform_modes(ds.FrequencyModel(eq))
    text = res.text()
    assert pm.complete and set(pm.carriers) == {"x", "y", "z", "rx", "ry", "rz"}
    assert "unknown" not in text.split("cable model")[0]
    assert "spread over" in text and "platform-dominated" in text
    assert float(np.min(pm.modes.platform_share[pm.index])) < 0.5
    # the margin check still sees the lowest mode the cabin moves in (8 % share, 0.1558 Hz)
    assert "closest 0.1558 Hz" in text
    # local modes lie next to the carriers (none of them global): the proximity row fails
    row = {r["check"]: r for r in res.rows}["local modes near platform modes"]
    assert row["verdict"] == "fail" and 0 <= row["value"] <= 0.03
    assert re.match(r"\d+ local mode\(s\) within 3\.00% of a platform mode, closest gap "
                    r"\d\.\d\d%", row["detail"])


def test_light_cables_leave_no_spread_sentence(cogiro):
    # CoGiRo (cables 0.06 kg/m, 91 kg platform): every DOF has a global carrier
    pm = find_platform_modes(ds.FrequencyModel(cogiro.equilibrium()))
    assert pm.complete and pm.spread() == ""
    assert "spread over" not in design_checks(cogiro.robot, cogiro.pose).text()


def _rows(rows):
    return {r["check"]: r for r in rows}


def test_a_value_equal_to_its_limit_passes_and_one_ulp_above_fails(cogiro):
    """Each limit is admissible itself (module table: "<="): the receptance ratio, the
    model's estimated error and the sag taken as their own limits pass, and fail once the
    limit is one float below them."""
    band = (0.1, 20.0)
    first = _rows(design_checks(cogiro.robot, cogiro.pose, band_hz=band).rows)
    names = {"platform receptance in band": "frf_limit", "cable model": "model_rtol",
             "sag / chord": "max_sag_ratio"}
    at = {opt: first[check]["value"] for check, opt in names.items()}
    assert at["frf_limit"] > 1 and 0 < at["model_rtol"] and 0 < at["max_sag_ratio"]
    rows = _rows(design_checks(cogiro.robot, cogiro.pose, band_hz=band, **at).rows)
    equal = {check: row["verdict"] for check, row in rows.items()}
    for check, opt in names.items():
        assert rows[check]["limit"] == at[opt] and rows[check]["value"] == at[opt]
    below = verdicts(cogiro.robot, cogiro.pose, band_hz=band,
                     **{k: np.nextafter(v, 0.0) for k, v in at.items()})
    for check in names:
        assert (equal[check], below[check]) == ("pass", "fail"), check


def test_the_receptance_is_taken_at_the_platform_modes_in_the_band(cogiro):
    """Over a wide band the receptance row's ratio is at least the direct receptance over
    its static value at every platform mode in the band (the grid is refined there: a
    uniform grid of the wide band misses the resonance peak by 5 %)."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.constants import DOF_NAMES
    band = (0.1, 20.0)
    res = design_checks(cogiro.robot, cogiro.pose, band_hz=band)
    value = _rows(res.rows)["platform receptance in band"]["value"]
    m = damped_model(cogiro.equilibrium())
    names = [DOF_NAMES[k] for k in m.free_index]
    loads = ["f" + n if len(n) == 1 else "m" + n[1] for n in names]
    f = res.platform.freq_hz
    f = f[(f >= band[0]) & (f <= band[1])]
    H = ds.frf(m, 2 * np.pi * np.concatenate([[0.0], f]), inputs=loads, outputs=names).H
    d = np.abs(np.diagonal(H, axis1=1, axis2=2))
    at_modes = np.max(d[1:] / d[0])
    assert f.size == 6 and value >= at_modes * (1 - 1e-9)


def test_the_modes_cover_the_forbidden_band_with_its_margin(cogiro):
    """A forbidden band above the platform modes: the modes are computed up to its top times
    (1 + margin), beyond where the platform modes alone would stop (7.3 Hz)."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.analyses.verdicts import CheckOptions, modal_rows
    eq = cogiro.equilibrium()
    rows, pm = modal_rows(ds.FrequencyModel(eq), CheckOptions(forbidden_hz=(8.0, 10.0),
                                                              margin=0.1),
                          damped_model=lambda: damped_model(eq))
    assert pm.complete and pm.searched_hz >= 11.0
    assert np.max(pm.modes.freq_hz) >= 11.0 * 0.95


def test_modal_rows_without_a_band_or_past_the_ceiling_say_so(cogiro):
    """No forbidden band: its two rows are "not asked" with that reason; a ceiling of 3
    modes leaves the platform modes unfound: the margin and proximity rows are "unknown"
    (never a pass)."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.analyses.verdicts import CHECKS, CheckOptions, modal_rows
    model = ds.FrequencyModel(cogiro.equilibrium())
    rows, _ = modal_rows(model, CheckOptions())
    got = _rows(rows)
    for check in CHECKS[3:5]:
        assert got[check]["verdict"] == "not asked" and got[check]["passed"]
        assert got[check]["detail"] == "no forbidden band given"
    rows, pm = modal_rows(model, CheckOptions(forbidden_hz=(0.5, 1.0), max_modes=3),
                          damped_model=damped_model(cogiro.equilibrium()))
    got = _rows(rows)
    assert not pm.complete
    for check in (CHECKS[3], CHECKS[5]):
        assert got[check]["verdict"] == "unknown" and not got[check]["passed"], check
    assert got[CHECKS[3]]["detail"].startswith("the modes up to 1.05 Hz were not all computed")
    assert got[CHECKS[5]]["detail"] == f"the platform modes were not all found: {pm.reason}"
    assert "more than 3 modes" in pm.reason


def test_a_mode_whose_share_equals_the_threshold_is_held_to_the_margin(cogiro):
    """"Platform share >= participation" is inclusive: with the threshold set to a mode's
    own share and the band just above it, that mode fails the margin row; one float above
    its share, it is not held to the margin (and no other mode is near)."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.analyses.verdicts import CHECKS, CheckOptions, modal_rows
    eq = cogiro.equilibrium()
    model, damped = ds.FrequencyModel(eq), damped_model(eq)
    f = float(find_platform_modes(model).first_hz)  # the lowest platform mode, 2.206 Hz
    band = (f * 1.01, f * 1.02)

    def margin_row(participation):
        opts = CheckOptions(forbidden_hz=band, margin=0.01, participation=participation)
        rows, pm = modal_rows(model, opts, damped_model=damped)
        return _rows(rows)[CHECKS[3]], pm
    # the share as the row's own search computes it (its reach, set by the band, moves the
    # roots by rounding and the shares by their difference quotient's rounding, ~1e-10)
    _, pm = margin_row(0.05)
    k = int(pm.index[0])
    f, share = float(pm.modes.freq_hz[k]), float(pm.modes.platform_share[k])
    others = np.delete(np.asarray(pm.modes.freq_hz), k)
    assert not np.any((others > band[0] * 0.99) & (others < band[1] * 1.01))
    assert margin_row(share)[0]["verdict"] == "fail"
    assert margin_row(share)[0]["value"] == f
    assert margin_row(np.nextafter(share, 1.0))[0]["verdict"] == "pass"


def test_no_mode_held_to_the_margin_passes_with_no_closest_mode(cogiro):
    """A threshold above every share (possible in CheckOptions, which is not validated):
    no mode is checked, the margin row passes with no value and names no closest mode."""
    from dynstiff.analyses.checks import damped_model
    from dynstiff.analyses.verdicts import CHECKS, CheckOptions, modal_rows
    eq = cogiro.equilibrium()
    rows, _ = modal_rows(ds.FrequencyModel(eq), CheckOptions(forbidden_hz=(0.5, 1.0),
                                                             participation=1.01),
                         damped_model=damped_model(eq))
    row = _rows(rows)[CHECKS[3]]
    assert row["verdict"] == "pass" and np.isnan(row["value"])
    assert "closest" not in row["detail"]


def test_the_proximity_row_follows_its_own_tolerance(cogiro):
    """CoGiRo's closest local mode is 6.1 % from a platform mode: the proximity row passes
    at 0.9 times that gap and fails at 1.5 times it, with the gap as its value."""
    from dynstiff.analyses.interaction import proximity_warnings
    pm = find_platform_modes(ds.FrequencyModel(cogiro.equilibrium()), 0.0, 1.0)
    gap = min(w.relative_gap for w in proximity_warnings(pm.modes, rtol=1.0,
                                                          platform=pm.index))
    assert 0.05 < gap < 0.07
    key = "local modes near platform modes"
    near = {r["check"]: r for r in design_checks(cogiro.robot, cogiro.pose,
                                                  proximity_rtol=1.5 * gap).rows}[key]
    assert near["verdict"] == "fail" and near["value"] == pytest.approx(gap, rel=1e-9)
    assert verdicts(cogiro.robot, cogiro.pose, proximity_rtol=0.9 * gap)[key] == "pass"


def test_a_pose_without_equilibrium_fails_the_workspace_row_with_its_reason(cogiro):
    """statics_rows given the statics' error: the workspace row fails with the error's text,
    every other row is "unknown" (no equilibrium to judge)."""
    from dynstiff.analyses.verdicts import CHECKS, CheckOptions, statics_rows
    error = ds.errors.InfeasiblePoseError("no tensions within the limits at this pose")
    rows = statics_rows(cogiro.robot, None, error, CheckOptions())
    assert [r["check"] for r in rows] == list(CHECKS)
    assert rows[0]["verdict"] == "fail" and rows[0]["detail"] == str(error)
    assert not rows[0]["passed"] and np.isnan(rows[0]["value"])
    for r in rows[1:]:
        assert (r["verdict"], r["passed"], r["detail"]) == (
            "unknown", False, "no equilibrium at this pose")


def test_the_tension_row_fails_when_a_tension_leaves_the_limits(cogiro):
    """The same equilibrium judged against limits that end just below its largest tension
    fails the tension row (value: that tension, limit: t_max), and passes at limits that
    end at it exactly."""
    from dynstiff.analyses.verdicts import CHECKS, CheckOptions, statics_rows
    eq = cogiro.equilibrium()
    top = float(eq.max_tensions.max())
    t_min = cogiro.robot.tension_limits[0]
    for t_max, verdict in ((top * (1 - 1e-6), "fail"), (top, "pass")):
        robot = dataclasses.replace(cogiro.robot, tension_limits=(t_min, t_max))
        row = {r["check"]: r for r in statics_rows(robot, eq, None, CheckOptions())}[CHECKS[1]]
        assert (row["verdict"], row["value"], row["limit"]) == (verdict, top, t_max)
