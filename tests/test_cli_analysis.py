"""The `dynstiff` command line, run in this process (conftest.run_cli): `scenes`, `modes`,
`frf` and `check` (dynstiff/cli/analysis.py)."""

import re

import numpy as np
import pytest
from conftest import run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")





def test_cli_modes_table_and_csv(tmp_path):
    out = run_cli("modes", "cogiro", "-n", "6", "--csv", str(tmp_path / "m.csv"))
    assert out.returncode == 0, out.stderr
    assert "global" in out.stdout and "freq [Hz]" in out.stdout
    import pandas as pd
    df = pd.read_csv(tmp_path / "m.csv", comment="#")
    assert len(df) == 6 and df["freq [Hz]"].is_monotonic_increasing
    assert df["kind"].isin(["global", "mixed", "local"]).all()


def test_cli_modes_model_choice(tmp_path):
    """--model: the 30-segment lumped model lands within 1e-3 of the closed form on CoGiRo's
    first modes, the exact cable within 3e-4 (the closed form's error); the massless rungs
    give platform modes only, the straight spring stiffer than the catenary (sag softens the
    cable)."""
    import pandas as pd
    tables = {}
    for m in ("dsm", "exact", "lumped", "catenary", "spring"):
        out = run_cli("modes", "cogiro", "-n", "3", "--model", m, "--csv",
                      str(tmp_path / f"{m}.csv"))
        assert out.returncode == 0, out.stderr
        assert out.stdout.startswith(f"{m} model")
        tables[m] = pd.read_csv(tmp_path / f"{m}.csv", comment="#")["freq [Hz]"].to_numpy()
    assert abs(tables["lumped"] / tables["dsm"] - 1).max() < 1e-3
    assert 1e-6 < abs(tables["exact"] / tables["dsm"] - 1).max() < 3e-4   # theory.md §11.5
    assert (tables["spring"] > tables["catenary"]).all()
    assert (pd.read_csv(tmp_path / "spring.csv", comment="#")["kind"] == "global").all()
    bad = run_cli("modes", "cogiro", "--model", "lumped", "--segments", "0")
    assert bad.returncode == 2 and "--segments" in bad.stderr
    bad = run_cli("modes", "cogiro", "--model", "beam")
    assert bad.returncode == 2 and "beam" in bad.stderr


def test_cli_frf_writes_table_and_figure(tmp_path):
    out = run_cli("frf", "cogiro", "--load", "fz", "--response", "z", "--band", "1", "3",
                  "--points", "400", "--csv", str(tmp_path / "f.csv"), "--plot",
                  str(tmp_path / "f.png"))
    assert out.returncode == 0, out.stderr
    import pandas as pd
    df = pd.read_csv(tmp_path / "f.csv", comment="#")
    assert len(df) > 400 and set(df["output"]) == {"z"} and set(df["input"]) == {"fz"}
    # the largest response in 1-3 Hz is the first (vertical) global mode of CoGiRo
    import dynstiff as ds
    f1 = ds.eigenfrequencies(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), 1)[0]
    peak = df.loc[df["magnitude"].idxmax(), "freq [Hz]"]
    assert abs(peak / f1 - 1) < 1e-3              # the grid is refined at the mode
    assert (tmp_path / "f.png").stat().st_size > 10_000
    bad = run_cli("frf", "cogiro", "--band", "5", "1")
    assert bad.returncode == 2 and "--band" in bad.stderr
    bad = run_cli("frf", "cogiro", "--load", "fq")
    assert bad.returncode == 2 and "fq" in bad.stderr


def test_frf_of_a_held_dof_is_refused_not_zero():
    """The pendulum has one free DOF (ry): naming fx or the output y would give an FRF that
    is identically 0; that is an error naming the channel, and x of D = (0, 0, d) is not."""
    import dynstiff as ds
    from dynstiff.errors import InvalidParameterError
    model = ds.FrequencyModel(ds.load_scene("pendulum").equilibrium())
    with pytest.raises(InvalidParameterError, match=r"inputs \['fx'\].*\('ry',\)"):
        ds.frf(model, [1.0], inputs="fx", outputs="x")
    with pytest.raises(InvalidParameterError, match=r"outputs \['y'\]"):
        ds.frf(model, [1.0], inputs="my", outputs=["x", "y"], point=[0, 0, 0.75])
    # x of D moves by d dphi: H_x,my = d H_ry,my
    h = ds.frf(model, [1.0], inputs="my", outputs=["x", "ry"], point=[0, 0, 0.75]).H[0, :, 0]
    assert h[0] == pytest.approx(0.75 * h[1], rel=1e-12) and abs(h[1]) > 0
    assert ds.frf(model, [1.0]).H.shape == (1, 6, 6)           # the default keeps zero channels
    bad = run_cli("frf", "pendulum", "--load", "fx", "--response", "x")
    assert bad.returncode == 2 and "held DOFs only" in bad.stderr and "fx" in bad.stderr


# -------------------------------------------------------------------------------- check
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


def test_cli_frf_peak_does_not_depend_on_points():
    """The damped CoGiRo z/fz receptance: the largest |H| from 300 and from 4000 uniform
    points differ by < 1 % (the grid is refined at every mode); --damping 0 0 0 gives the
    undamped model, whose peak is far higher."""
    def peak(*a):
        out = run_cli("frf", "cogiro", "--band", "0.5", "6", *a)
        assert out.returncode == 0, out.stderr
        assert "damping: platform modal ratio" in out.stdout
        return float(re.search(r"largest \|H\| = ([0-9.e+-]+)", out.stdout).group(1))
    p300, p4000 = peak("--points", "300"), peak("--points", "4000")
    assert abs(p300 / p4000 - 1) < 0.01
    assert peak("--points", "300", "--damping", "0.03") < 0.6 * p300
    assert peak("--points", "300", "--damping", "0", "0", "0") > 10 * p300


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


def test_lengths_on_a_scene_with_held_dofs_hold_them_at_the_scene_pose(capsys):
    """planar2 holds y and the rotations: forward statics from --lengths starts from (and
    keeps the held DOFs of) the scene's pose instead of asking for an option that does not
    exist; the lengths of the scene's own pose give back its frequencies."""
    from dynstiff.cli import main
    scene = ds.load_scene("planar2")
    L0 = scene.equilibrium().unstretched_lengths
    assert main(["modes", "planar2", "-n", "3", "--csv", "-", "--lengths",
                 *[repr(float(x)) for x in L0]]) == 0
    via_lengths = capsys.readouterr().out
    assert main(["modes", "planar2", "-n", "3", "--csv", "-"]) == 0
    at_pose = capsys.readouterr().out

    def rows(text):
        return [ln for ln in text.splitlines() if not ln.startswith("# ")][1:4]
    f1 = [float(r.split(",")[1]) for r in rows(via_lengths)]
    f2 = [float(r.split(",")[1]) for r in rows(at_pose)]
    np.testing.assert_allclose(f1, f2, rtol=1e-7)


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


def test_cli_frf_figure_has_a_phase_panel(tmp_path, monkeypatch):
    """The command's figure is the demo's: magnitude over phase, read back from the Figure."""
    import dynstiff.plot
    from dynstiff.cli import main
    seen = {}
    real = dynstiff.plot.plot_frf

    def spy(*a, **kw):
        seen["fig"] = real(*a, **kw)
        return seen["fig"]

    monkeypatch.setattr(dynstiff.plot, "plot_frf", spy)
    assert main(["frf", "planar2", "--points", "200", "--plot", str(tmp_path / "f.png")]) == 0
    mag, ph = seen["fig"].axes
    assert mag.get_yscale() == "log" and ph.get_ylabel() == "phase [deg]"
    curves = [ln for ln in ph.get_lines() if ln.get_gid().startswith("frf-")]
    assert curves and all(np.nanmax(np.abs(ln.get_ydata())) <= 180 for ln in curves)
    assert (tmp_path / "f.png").stat().st_size > 10_000


def test_modes_band_lists_every_mode_in_it_and_frf_defaults_to_a_free_dof(tmp_path, capsys):
    """--band LO HI is the band of interest in every command: `modes --band 3 6` lists the
    eigenfrequencies in [3, 6] Hz (Wittrick-Williams, none missed), `--fmax 6` all below;
    `frf` without --load/--response takes the scene's first free DOF (the pendulum's ry)."""
    import pandas as pd

    from dynstiff.cli import main
    eq = ds.load_scene("planar2").equilibrium()
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=6.0)
    assert main(["modes", "planar2", "--band", "3", "6", "--csv", str(tmp_path / "b.csv")]) == 0
    got = pd.read_csv(tmp_path / "b.csv", comment="#")["freq [Hz]"].to_numpy()
    np.testing.assert_allclose(got, f[f >= 3.0], rtol=1e-9)
    assert main(["modes", "planar2", "--fmax", "6", "--csv", str(tmp_path / "f.csv")]) == 0
    got = pd.read_csv(tmp_path / "f.csv", comment="#")["freq [Hz]"].to_numpy()
    np.testing.assert_allclose(got, f, rtol=1e-9)
    assert 0 < np.sum(f < 3.0) < f.size                     # the band cut something
    capsys.readouterr()
    assert main(["frf", "pendulum", "--points", "50"]) == 0
    assert capsys.readouterr().out.startswith("receptance ry/my:")
