"""The `dynstiff` command line, run in this process (conftest.run_cli): `check`, its options,
verdicts, exit codes, table and recommended model (dynstiff/cli/analysis.py)."""

import re

import numpy as np
import pytest
from conftest import _spy, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


# ------------------------------------------------------------------------ check
def test_cli_check_passes_the_options_to_the_design_checks(monkeypatch, capsys):
    """Every option of `check` reaches the design checks: the forbidden band, margin,
    tolerance, participation, FRF limit, model, damping, proximity, sag limit, max modes and
    the uncertain parameters, with the scene's band of interest."""
    import dynstiff.analyses.checks
    from dynstiff.analyses.uncertainty import Uncertain
    from dynstiff.cli import main
    from dynstiff.params import Damping
    calls = []
    _spy(monkeypatch, dynstiff.analyses.checks, "design_checks", calls)
    code = main(["check", "planar2", "--forbidden-band", "0.5", "1.5", "--margin", "0.2",
                 "--rtol", "0.004", "--participation", "0.3", "--frf-limit", "7",
                 "--model", "catenary", "--damping", "0.02", "0.03", "--proximity", "0.07",
                 "--max-sag", "0.015", "--max-modes", "300", "--uncertain", "EA=10%"])
    assert code in (0, 1)
    capsys.readouterr()
    (args, kw), = calls
    scene = ds.load_scene("planar2")
    np.testing.assert_allclose(args[0].anchors, scene.robot.anchors)
    np.testing.assert_allclose(args[1].position, scene.pose.position)
    assert kw == dict(proximity_rtol=0.07, max_sag_ratio=0.015,
                      uncertain={"EA": Uncertain.parse("10%")}, max_modes=300,
                      band_hz=(0.5, 1.5), margin=0.2, model_rtol=0.004, rung="catenary",
                      participation=0.3, frf_limit=7.0,
                      damping=Damping(0.02, 0.03, scene.damping.cable_viscous_damping),
                      model_band_hz=scene.band_hz)


def test_cli_check_advice_when_the_bound_fails_the_recommended_model(tmp_path):
    """planar2 at --rtol 1e-4: the cable-model row fails (its bound) though the recommended
    model is the one checked: the advice line follows the recommendation; with --csv - both go
    to standard error and standard output holds the table alone."""
    from dynstiff.analyses.settings import analysis_settings
    scene = ds.load_scene("planar2")
    rec = ds.recommend_model(scene.equilibrium(), scene.band_hz, 1e-4)
    assert rec.rung == analysis_settings(scene).rung
    out = run_cli("check", "planar2", "--rtol", "1e-4", "--csv", "-")
    assert out.returncode == 1
    assert "FAIL    cable model" in out.stderr
    lines = out.stderr.splitlines()
    i = lines.index(rec.text().splitlines()[0] + f" (over {scene.band_hz[0]:g}-"
                    f"{scene.band_hz[1]:g} Hz, the closed form measured against the exact "
                    f"rung)")
    assert lines[i + 1:] == [
        "  (advice, not a verdict: the measured error is within the tolerance, the "
        "cable-model row holds the model to its bound, computed without the exact rung "
        "(theory.md §11.6); --model exact passes the row)"]
    assert "advice" not in out.stdout and "recommended" not in out.stdout
    assert out.stdout.startswith("# dynstiff: ")


def test_cli_check_recommends_a_model_for_the_tolerance_given():
    """The recommendation under the verdicts is the cheapest model for --rtol: on the
    pendulum 1e-4 asks for another model than the default 1e-2."""
    scene = ds.load_scene("pendulum")
    eq = scene.equilibrium()
    rec = ds.recommend_model(eq, scene.band_hz, 1e-4)
    assert rec.rung != ds.recommend_model(eq, scene.band_hz).rung
    out = run_cli("check", "pendulum", "--rtol", "1e-4")
    assert out.returncode == 0, out.stdout + out.stderr
    assert (rec.text().splitlines()[0] + f" (over {scene.band_hz[0]:g}-{scene.band_hz[1]:g} "
            f"Hz, the closed form measured against the exact rung)") in out.stdout.splitlines()


def test_cli_check_has_no_lengths_option():
    """`check` takes a pose, not unstretched lengths: --lengths is refused, exit 2."""
    out = run_cli("check", "planar2", "--lengths", "20", "20")
    assert out.returncode == 2 and out.stdout == ""
    assert "unrecognized arguments: --lengths 20 20" in out.stderr


def test_cli_check_exit_codes():
    def run(*a):
        return run_cli("check", *a)
    assert run("cogiro", "--forbidden-band", "1", "2").returncode == 0
    out = run("cogiro", "--forbidden-band", "4", "5")
    assert out.returncode == 1 and "FAIL    platform modes outside band" in out.stdout
    out = run("cogiro", "--pose", "9", "0", "1")
    assert out.returncode == 1 and "FAIL    workspace" in out.stdout


def test_cli_check_fails_a_mixed_platform_mode_in_band(tmp_path):
    """CoGiRo with a 50 kg platform, band 2.0-2.3 Hz: exit 1, naming the 2.216 Hz mode and
    its 42 % platform share (it passed when only > 50 % shares counted)."""
    from dynstiff.scenes.loader import SCENE_DIR
    text = (SCENE_DIR / "cogiro.toml").read_text().replace("mass = 91.058", "mass = 50.0")
    (tmp_path / "m50.toml").write_text(text)
    out = run_cli("check", tmp_path / "m50.toml", "--forbidden-band", "2.0", "2.3")
    assert out.returncode == 1, out.stdout + out.stderr
    line = [ln for ln in out.stdout.splitlines() if "platform modes outside band" in ln][0]
    assert line.startswith("FAIL") and "2.216 Hz" in line and "platform share 42 %" in line
    assert "FAIL    platform receptance in band" in out.stdout
    # --participation above the share and --frf-limit above the amplification: passes
    out = run_cli("check", tmp_path / "m50.toml", "--forbidden-band", "2.0", "2.3",
                  "--participation", "0.45", "--frf-limit", "100")
    assert "PASS    platform modes outside band" in out.stdout
    assert "PASS    platform receptance in band" in out.stdout


def test_cli_check_defaults_to_the_scenes_forbidden_band():
    def run(*a):
        return run_cli("check", *a)
    out = run("cogiro")                                    # forbidden_band_hz = [0, 1.5]
    assert out.returncode == 0 and "[0, 1.5] Hz" in out.stdout, out.stdout + out.stderr
    out = run("sixcable")                                  # no forbidden band in the scene
    assert out.returncode == 1 and "no forbidden band" in out.stdout
    # the closed form's error on sixcable, measured against the exact rung, is 4e-3 < 1e-2,
    # but its robot-level bound (theory.md §11.6) is 2.5e-2: the cable-model row fails
    assert "FAIL    cable model" in out.stdout and "FAIL    local modes near" in out.stdout
    assert "recommended model: dsm" in out.stdout
    assert "n/a     platform modes outside band       no forbidden band given" in out.stdout


# the closed form's robot-level bound warns on sixcable and fast (theory.md §11.6); the
# table's "cable model" row says it too
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
@pytest.mark.parametrize("scene", ds.list_scenes())
def test_check_writes_its_table_on_every_built_in_scene(tmp_path, scene, capsys):
    """`dynstiff check SCENE --csv FILE` at the scene's own pose: exit 0 or 1 (a verdict), a
    table with one row per check whose verdicts are the printed ones, and the pose in its
    metadata (the command crashed without --pose)."""
    import json

    import pandas as pd

    from dynstiff.cli import main
    out = tmp_path / "checks.csv"
    code = main(["check", scene, "--csv", str(out)])
    text = capsys.readouterr().out
    assert code in (0, 1)
    df = pd.read_csv(out, comment="#")
    assert len(df) == 7 and set(df["passed"]) <= {True, False}
    assert (code == 0) == bool(df["passed"].all())
    flags = {"pass": "PASS", "fail": "FAIL", "unknown": "UNKNOWN", "not asked": "n/a"}
    for row in df.itertuples():
        assert f"{flags[row.verdict]:<7s} {row.check}" in text
        assert row.passed == (row.verdict in ("pass", "not asked"))
    meta = dict(line[2:].split(": ", 1) for line in out.read_text().splitlines()
                if line.startswith("# "))
    pose = json.loads(meta["pose"])
    scn = ds.load_scene(scene)
    expected = scn.pose if scn.pose is not None else scn.equilibrium().pose
    np.testing.assert_allclose(pose["position [m]"], expected.position, atol=1e-12)


def test_cli_check_with_uncertain_parameters():
    """``--uncertain EA=10%``: the uncertain row (EA's sigma 10 %: about 16 % of the robots
    put a platform mode within 5 % of a 0-2 Hz band) and the exit code of a failing row."""
    def run(*a):
        return run_cli("check", *a)
    out = run("cogiro", "--forbidden-band", "0", "2", "--uncertain", "EA=10%")
    assert out.returncode == 1
    assert re.search(r"FAIL    platform modes outside band, uncertain P\(.*\) = 1\d\.\d%",
                     out.stdout)
    bad = run("cogiro", "--uncertain", "EA")
    assert bad.returncode == 2 and "--uncertain EA: give NAME=VALUE" in bad.stderr


@pytest.mark.parametrize("pose", [["0", "0", "nan"], ["0", "0", "1", "0", "inf", "0"], ["1", "2"]])
def test_check_of_a_bad_pose_is_an_error_not_a_verdict(pose):
    """A pose that is not a pose is bad input, exit 2 with one line naming it, not a FAIL
    verdict with exit 1 (as if the robot had failed)."""
    out = run_cli("check", "cogiro", "--pose", *pose)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and "pose" in out.stderr
