"""The command line (dynstiff/cli/__init__.py, `python -m dynstiff`), run in subprocesses: demo,
modes, frf, sweep, simulate and check; their tables and figures are read back and compared
with the library, and bad arguments exit with status 2 and a message naming them."""

import re
import subprocess
import sys

import numpy as np
import pytest

import dynstiff as ds

pytestmark = pytest.mark.integration


@pytest.fixture(autouse=True)
def no_traceback(monkeypatch):
    """Every command line run here (subprocess or in-process) may fail, but with one line:
    a traceback without --debug fails the test."""
    run = subprocess.run

    def checked(args, *a, **kw):
        out = run(args, *a, **kw)
        err = out.stderr.decode() if isinstance(out.stderr, bytes) else (out.stderr or "")
        assert "Traceback" not in err or "--debug" in args, err[-2000:]
        return out
    monkeypatch.setattr(subprocess, "run", checked)


# --------------------------------------------------------------------------------- demo
def test_demo_main_job_on_cogiro(tmp_path):
    out = subprocess.run([sys.executable, "-m", "dynstiff", "demo", "--out", str(tmp_path),
                          "--points", "400"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    import pandas as pd

    import dynstiff as ds
    modes = pd.read_csv(tmp_path / "modes.csv", comment="#")
    ref = ds.eigenfrequencies(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), 40)
    assert len(modes) == 40
    assert abs(modes["freq [Hz]"] / ref - 1).max() < 1e-9
    statics = pd.read_csv(tmp_path / "statics.csv", comment="#")
    assert len(statics) == 8 and (statics["tension at B [N]"] >= 100 - 1e-6).all()
    checks = pd.read_csv(tmp_path / "checks.csv", comment="#")
    assert len(checks) == 7 and checks["passed"].all()
    frf = pd.read_csv(tmp_path / "frf.csv", comment="#")
    # 400 uniform frequencies plus the clusters at the modes of the 0.1-12 Hz band
    assert set(frf["input"]) == {"fx", "fz"} and frf["freq [Hz]"].nunique() > 400
    for name in ("frf.png", "mode_shape.png"):
        assert (tmp_path / name).stat().st_size > 10_000
    assert "recommended model: dsm" in out.stdout
    assert "cheapest adequate" not in out.stdout
    head = (tmp_path / "modes.csv").read_text().splitlines()[:12]
    for key in ("dynstiff", "scene", "model", "damping", "pose", "units"):
        assert any(h.startswith(f"# {key}:") for h in head), (key, head)
    assert "platform modal ratio 0.01, cable loss factor 0.01" in out.stdout


def test_demo_and_report_write_one_self_contained_html(tmp_path):
    """report.html: parsed with html.parser, it has the check table, the modes table and
    every figure as a base64 PNG data URI, and no external asset (no src/href to a file
    or a URL, no script)."""
    import base64
    from html.parser import HTMLParser

    class Collect(HTMLParser):
        def __init__(self):
            super().__init__()
            self.tags, self.srcs, self.links, self.text = [], [], [], []

        def handle_starttag(self, tag, attrs):
            self.tags.append(tag)
            a = dict(attrs)
            if "src" in a:
                self.srcs.append(a["src"])
            if "href" in a:
                self.links.append(a["href"])

        def handle_data(self, data):
            self.text.append(data)
    for argv in (["demo", "--scene", "fourcable"], ["report", "fourcable"]):
        out_dir = tmp_path / argv[0]
        out = subprocess.run([sys.executable, "-m", "dynstiff", *argv, "--out", str(out_dir),
                              "--points", "200"], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        p = Collect()
        p.feed((out_dir / "report.html").read_text())
        text = " ".join(p.text)
        assert "script" not in p.tags and "link" not in p.tags and not p.links
        assert p.tags.count("table") >= 3 and len(p.srcs) == 2
        for src in p.srcs:
            assert src.startswith("data:image/png;base64,")
            assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
        assert "PASS" in text and "recommended model" in text and "damping" in text


def test_demo_and_check_agree_on_every_scene(tmp_path):
    """One source of defaults: on every built-in scene `demo` and `check` print the same
    PASS/FAIL verdicts and the same recommended model (segments included)."""
    def verdicts(text):
        return [ln[:40] for ln in text.splitlines() if ln.startswith(("PASS", "FAIL"))]

    def recommendation(text):
        m = re.findall(r"recommended model: (\w+)(?: with N = (\d+)| \((\d+) segments)?",
                       text)
        return {(r, n or k) for r, n, k in m}
    for name in ds.list_scenes():
        demo = subprocess.run([sys.executable, "-m", "dynstiff", "demo", "--scene", name,
                               "--out", str(tmp_path / name), "--points", "100"],
                              capture_output=True, text=True)
        check = subprocess.run([sys.executable, "-m", "dynstiff", "check", name],
                               capture_output=True, text=True)
        assert demo.returncode == 0 and check.returncode in (0, 1), demo.stderr + check.stderr
        assert verdicts(demo.stdout) == verdicts(check.stdout) != [], name
        rd, rc = recommendation(demo.stdout), recommendation(check.stdout)
        assert len(rd) == 1 and rd == rc, (name, rd, rc)
        assert "band 0.1-12 Hz; forbidden band none" not in demo.stdout


def test_demo_cable_report(tmp_path):
    out = subprocess.run([sys.executable, "-m", "dynstiff", "demo", "--cable", "--out",
                          str(tmp_path), "--points", "400"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "in-plane symmetric 1" in out.stdout
    for name in ["report.txt", "statics.csv", "modes.csv", "dynamic_stiffness.png"]:
        assert (tmp_path / name).stat().st_size > 0
    import pandas as pd
    modes = pd.read_csv(tmp_path / "modes.csv", comment="#")
    assert list(modes.columns) == ["freq [Hz]", "Omega [-]", "family", "order"]
    assert modes["freq [Hz]"].is_monotonic_increasing


# ---------------------------------------------------------- modes, frf, sweep, simulate
def test_cli_rejects_unknown_option():
    out = subprocess.run([sys.executable, "-m", "dynstiff", "demo", "--bogus"],
                         capture_output=True, text=True)
    assert out.returncode == 2
    assert "--bogus" in out.stderr


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "dynstiff", *args], capture_output=True,
                          text=True)


def test_cli_modes_table_and_csv(tmp_path):
    out = run_cli("modes", "cogiro", "-n", "6", "--csv", str(tmp_path / "m.csv"))
    assert out.returncode == 0, out.stderr
    assert "global" in out.stdout and "freq [Hz]" in out.stdout
    import pandas as pd
    df = pd.read_csv(tmp_path / "m.csv", comment="#")
    assert len(df) == 6 and df["freq [Hz]"].is_monotonic_increasing
    assert df["kind"].isin(["global", "local"]).all()


def test_cli_modes_model_choice(tmp_path):
    """--model: the 30-segment lumped model lands within 1e-3 of the closed form on CoGiRo's
    first modes, the exact cable within 3e-4 (the closed form's error); the massless rungs give platform modes only, the straight spring stiffer
    than the catenary (sag softens the cable)."""
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


def test_cli_errors_exit_nonzero_with_message(tmp_path):
    out = run_cli("modes", "nope")
    assert out.returncode == 2 and "unknown scene 'nope'" in out.stderr
    out = run_cli("modes", "cogiro", "--pose", "9", "0", "1")
    assert out.returncode == 2 and "pose [9.0" in out.stderr
    bad = tmp_path / "bad.toml"
    bad.write_text("[platform]\nmass = 1.0\nbogus_key = 3\n[[cables]]\nanchor=[0,0,1]\n"
                   "attachment=[0,0,0]\n")
    out = run_cli("modes", str(bad))
    assert out.returncode == 2 and "line 3" in out.stderr and "bogus_key" in out.stderr
    out = run_cli("modes", str(tmp_path / "missing.toml"))
    assert out.returncode == 2 and "missing.toml" in out.stderr


def test_cli_frf_writes_table_and_figure(tmp_path):
    out = run_cli("frf", "cogiro", "--from", "fz", "--to", "z", "--band", "1", "3", "--points",
                  "400", "--csv", str(tmp_path / "f.csv"), "--plot", str(tmp_path / "f.png"))
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
    bad = run_cli("frf", "cogiro", "--from", "fq")
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
    bad = run_cli("frf", "pendulum", "--from", "fx", "--to", "x")
    assert bad.returncode == 2 and "held DOFs only" in bad.stderr and "fx" in bad.stderr


def test_cli_sweep_line_and_parameter(tmp_path):
    out = run_cli("sweep", "cogiro", "--line", "0", "0", "1", "2", "1", "1.5", "--steps", "3",
                  "-n", "8", "--csv", str(tmp_path / "s.csv"), "--plot", str(tmp_path / "v.png"))
    assert out.returncode == 0, out.stderr
    assert "3/3" in out.stderr                              # the progress bar ran to the end
    import pandas as pd
    df = pd.read_csv(tmp_path / "s.csv", comment="#")
    assert len(df) == 24 and sorted(df["step"].unique()) == [0, 1, 2]
    assert abs(df["value"].max() - (4 + 1 + 0.25) ** 0.5) < 1e-9     # arc length [m]
    assert (tmp_path / "v.png").stat().st_size > 10_000
    out = run_cli("sweep", "cogiro", "--parameter", "EA", "--values", "1.4e5", "9.8e5",
                  "-n", "6", "--quiet")
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""                                  # --quiet: no progress bar
    assert "EA [N]" in out.stdout
    bad = run_cli("sweep", "cogiro")
    assert bad.returncode == 2 and "--line, --path or --parameter" in bad.stderr
    bad = run_cli("sweep", "cogiro", "--parameter", "colour", "--values", "1")
    assert bad.returncode == 2 and "colour" in bad.stderr


def test_cli_sweep_goes_on_past_an_infeasible_pose(tmp_path):
    out = run_cli("sweep", "cogiro", "--line", "0", "0", "1", "9", "0", "1", "--steps", "3",
                  "-n", "4", "--quiet", "--csv", str(tmp_path / "s.csv"))
    assert out.returncode == 0, out.stderr
    assert "infeasible, skipped" in out.stdout
    import pandas as pd
    df = pd.read_csv(tmp_path / "s.csv", comment="#")
    assert set(df["step"]) == {0, 1, 2} and (df["kind"] == "infeasible").sum() >= 1
    assert (tmp_path / "s.csv").read_text().startswith("# dynstiff: ")


def test_cli_sweep_path_file(tmp_path):
    """--path: a CSV with a header, a comment and a blank line gives the same frequencies as
    the closed-form model at each pose; a malformed line is an error naming file and line."""
    import numpy as np
    import pandas as pd

    import dynstiff as ds
    f = tmp_path / "path.csv"
    f.write_text("# a path\nx,y,z\n0,0,1\n0.5,0.2,1.1  # comment\n\n1,0.4,1.2,0,0,0.05\n")
    out = run_cli("sweep", "cogiro", "--path", str(f), "-n", "6", "--quiet", "--csv",
                  str(tmp_path / "s.csv"))
    assert out.returncode == 0, out.stderr
    df = pd.read_csv(tmp_path / "s.csv", comment="#")
    rob = ds.load_scene("cogiro").robot
    for k, pose in enumerate([[0, 0, 1], [0.5, 0.2, 1.1], [1, 0.4, 1.2, 0, 0, 0.05]]):
        ref = ds.eigenfrequencies(ds.FrequencyModel(rob.equilibrium(pose=pose)), 6)
        np.testing.assert_allclose(df.loc[df["step"] == k, "freq [Hz]"], ref, rtol=1e-12)
    f.write_text("0 0 1\n0 0 1.1\n0 0\n")
    bad = run_cli("sweep", "cogiro", "--path", str(f), "-n", "6")
    assert bad.returncode == 2 and "line 3" in bad.stderr and str(f) in bad.stderr


def test_cli_simulate_free_vibration_and_line(tmp_path):
    out = run_cli("simulate", "fourcable", "--time", "2", "--segments", "1", "--csv",
                  str(tmp_path / "t.csv"), "--plot", str(tmp_path / "s.png"))
    assert out.returncode == 0, out.stderr
    import re
    pairs = re.findall(r"  ([0-9.]+) Hz ~ mode ([0-9.]+) Hz \(([-+0-9.e]+) Hz\)", out.stdout)
    peaks = [float(p) for p, _, _ in pairs]
    assert pairs and "prominence >= 3%" in out.stdout
    for p, m, d in pairs:                     # each peak named with its nearest mode
        assert abs(float(p) - float(m) - float(d)) < 2e-3 * max(1.0, float(p))
    import dynstiff as ds
    f1 = ds.eigenfrequencies(ds.FrequencyModel(ds.load_scene("fourcable").equilibrium()), 1)[0]
    assert min(abs(p - f1) for p in peaks) < 0.5                       # resolution 0.5 Hz
    import pandas as pd
    assert len(pd.read_csv(tmp_path / "t.csv", comment="#")) == 1001
    out = run_cli("simulate", "planar2", "--to", "1", "0", "-10", "--speed", "1", "--ramp",
                  "0.5", "--time", "0.2", "--segments", "2", "--quiet", "--plot",
                  str(tmp_path / "line.png"))
    assert out.returncode == 0, out.stderr
    assert f"wrote {tmp_path / 'line.png'}" in out.stdout
    assert (tmp_path / "line.png").stat().st_size > 10_000      # announced and written
    dev = float(re.search(r"quasi-static path ([0-9.e-]+) m", out.stdout).group(1))
    assert 0 < dev < 0.01
    bad = run_cli("simulate", "cogiro", "--offset", "1", "2")
    assert bad.returncode == 2 and "--offset needs 6 values" in bad.stderr
    bad = run_cli("simulate", "cogiro", "--band", "5", "1")
    assert bad.returncode == 2 and "--band" in bad.stderr
    bad = run_cli("simulate", "cogiro", "--dt", "-1")
    assert bad.returncode == 2 and "dt" in bad.stderr


def test_cli_simulate_spectrum_reports_no_leakage():
    """CoGiRo free vibration from 1 mm in x: the spectrum named peaks at 0.55 and 1.55 Hz,
    leakage 1000 times below the real ones, inside the forbidden band. With the prominence
    rule every reported peak is within 2 resolution bins of a linearised mode."""
    out = run_cli("simulate", "cogiro", "--time", "5", "--segments", "4")
    assert out.returncode == 0, out.stderr
    pairs = re.findall(r"  ([0-9.]+) Hz ~ mode ([0-9.]+) Hz", out.stdout)
    assert pairs
    for p, m in pairs:
        assert float(p) > 1.6 and abs(float(p) - float(m)) < 0.4, out.stdout


def test_cli_malformed_toml_and_unknown_options(tmp_path):
    bad = tmp_path / "broken.toml"
    bad.write_text("[platform\nmass = 1\n")
    for cmd in ("modes", "check", "sweep", "simulate", "frf"):
        out = run_cli(cmd, str(bad))
        assert out.returncode == 2, cmd
        assert "TOML syntax error" in out.stderr and "broken.toml" in out.stderr, cmd
        out = run_cli(cmd, "cogiro", "--no-such-option")
        assert out.returncode == 2 and "--no-such-option" in out.stderr, cmd


# -------------------------------------------------------------------------------- check
def test_cli_check_exit_codes():
    run = lambda *a: subprocess.run([sys.executable, "-m", "dynstiff", "check", *a],
                                    capture_output=True, text=True)
    assert run("cogiro", "--band", "1", "2").returncode == 0
    out = run("cogiro", "--band", "4", "5")
    assert out.returncode == 1 and "FAIL  platform modes outside band" in out.stdout
    out = run("cogiro", "--pose", "9", "0", "1")
    assert out.returncode == 1 and "FAIL  workspace" in out.stdout


def test_cli_check_fails_a_mixed_platform_mode_in_band(tmp_path):
    """CoGiRo with a 50 kg platform, band 2.0-2.3 Hz: exit 1, naming the 2.216 Hz mode and
    its 42 % platform share (it passed when only > 50 % shares counted)."""
    from dynstiff.scenes.loader import SCENE_DIR
    text = (SCENE_DIR / "cogiro.toml").read_text().replace("mass = 91.058", "mass = 50.0")
    (tmp_path / "m50.toml").write_text(text)
    out = subprocess.run([sys.executable, "-m", "dynstiff", "check", str(tmp_path / "m50.toml"),
                          "--band", "2.0", "2.3"], capture_output=True, text=True)
    assert out.returncode == 1, out.stdout + out.stderr
    line = [ln for ln in out.stdout.splitlines() if "platform modes outside band" in ln][0]
    assert line.startswith("FAIL") and "2.216 Hz" in line and "platform share 42 %" in line
    assert "FAIL  platform receptance in band" in out.stdout
    # --participation above the share and --frf-limit above the amplification: passes
    out = subprocess.run([sys.executable, "-m", "dynstiff", "check", str(tmp_path / "m50.toml"),
                          "--band", "2.0", "2.3", "--participation", "0.45", "--frf-limit",
                          "100"], capture_output=True, text=True)
    assert "PASS  platform modes outside band" in out.stdout
    assert "PASS  platform receptance in band" in out.stdout


def test_cli_frf_peak_does_not_depend_on_points():
    """The damped CoGiRo z/fz receptance: the largest |H| from 300 and from 4000 uniform
    points differ by < 1 % (the grid is refined at every mode); --damping 0 0 0 gives the
    undamped model, whose peak is far higher."""
    def peak(*a):
        out = subprocess.run([sys.executable, "-m", "dynstiff", "frf", "cogiro", "--band",
                              "0.5", "6", *a], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        assert "damping: platform modal ratio" in out.stdout
        return float(re.search(r"largest \|H\| = ([0-9.e+-]+)", out.stdout).group(1))
    p300, p4000 = peak("--points", "300"), peak("--points", "4000")
    assert abs(p300 / p4000 - 1) < 0.01
    assert peak("--points", "300", "--damping", "0.03") < 0.6 * p300
    assert peak("--points", "300", "--damping", "0", "0", "0") > 10 * p300


def test_cli_version_and_metadata_in_json(tmp_path):
    import json
    out = subprocess.run([sys.executable, "-m", "dynstiff", "--version"], capture_output=True,
                         text=True)
    assert out.returncode == 0 and out.stdout.strip() == f"dynstiff {ds.__version__}"
    out = subprocess.run([sys.executable, "-m", "dynstiff", "modes", "planar2", "-n", "4",
                          "--json", str(tmp_path / "m.json")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    d = json.loads((tmp_path / "m.json").read_text())
    meta = d["metadata"]
    assert meta["dynstiff"] == ds.__version__ and meta["scene"] == "planar2"
    assert meta["model"] == "dsm" and "pose" in meta and "units" in meta
    assert set(meta["damping"]) >= {"platform_ratio", "cable_loss_factor"}
    assert len(d["data"]) == 4 and "platform share [-]" in d["data"][0]


@pytest.mark.parametrize("argv", [["demo", "--fmax", "-1"],
                                  ["demo", "--damping", "0.01", "0.01", "0", "1"],
                                  ["demo", "--damping", "-0.1"],
                                  ["report", "cogiro", "--damping", "0.01", "2"]])
def test_demo_validates_every_input_before_writing(tmp_path, argv):
    out = subprocess.run([sys.executable, "-m", "dynstiff", *argv, "--out",
                          str(tmp_path / "o")], capture_output=True, text=True)
    assert out.returncode == 2 and "error" in out.stderr
    assert not (tmp_path / "o").exists()


def test_cli_check_defaults_to_the_scenes_forbidden_band():
    run = lambda *a: subprocess.run([sys.executable, "-m", "dynstiff", "check", *a],
                                    capture_output=True, text=True)
    out = run("cogiro")                                    # forbidden_band_hz = [0, 1.5]
    assert out.returncode == 0 and "[0, 1.5] Hz" in out.stdout, out.stdout + out.stderr
    out = run("sixcable")                                  # no forbidden band in the scene
    assert out.returncode == 1 and "no forbidden band" in out.stdout
    # the closed form's error on sixcable, measured against the exact rung, is 5e-3 < 1e-2
    assert "PASS  cable model" in out.stdout and "FAIL  local modes near" in out.stdout
    assert "platform modes outside band" not in out.stdout


@pytest.mark.parametrize("argv, message", [
    (["modes", "{tmp}"], "is a folder, not a scene file"),
    (["modes", "{latin}"], "not a UTF-8"),
    (["modes", "{blob}"], "not a UTF-8"),
    (["check", "planar2", "--max-sag", "nan"], "--max-sag must be finite and > 0"),
    (["check", "planar2", "--margin", "-1"], "margin must be >= 0"),
    (["frf", "planar2", "--points", "0"], "--points must be >= 2"),
    (["frf", "planar2", "--points", "-3"], "--points must be >= 2"),
    (["frf", "planar2", "--plot", "{tmp}/f.xyz"], "the file name must end in one of"),
    (["frf", "planar2", "--plot", "{tmp}"], "is a folder"),
    (["modes", "planar2", "--csv", "{tmp}"], "is a folder"),
    (["modes", "planar2", "--json", "{tmp}/missing/t.json"], "does not exist"),
    (["sweep", "planar2", "--path", "{tmp}"], "Is a directory"),
    (["sweep", "planar2", "--path", "{blob}"], "UnicodeDecodeError"),
    (["modes", "cogiro", "--fmax", "1e9"], "fmax_hz = 1e\\+09 Hz is out of"),
    (["modes", "planar2", "--pose", "0", "0"], "--pose needs 3 numbers .* got 2: \\[0.0, 0.0\\]"),
    (["modes", "planar2", "--bogus"], "unrecognized arguments: --bogus"),
    ([], "required: command"),
])
def test_bad_command_lines_give_one_line_and_exit_2(tmp_path, capsys, argv, message):
    """Every error is one line on standard error with exit code 2, and nothing is written
    (no traceback unless --debug)."""
    from dynstiff.cli import main
    latin, blob = tmp_path / "latin.toml", tmp_path / "blob.toml"
    latin.write_bytes('[scene]\nname = "grün"\n'.encode("latin-1"))
    blob.write_bytes(bytes(range(256)))
    argv = [a.format(tmp=tmp_path, latin=latin, blob=blob) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("dynstiff: error: ")
    assert re.search(message, err), err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["blob.toml", "latin.toml"]


def test_debug_shows_the_traceback_and_dash_writes_to_stdout(capsys):
    from dynstiff.cli import main
    with pytest.raises(ds.InvalidParameterError):
        main(["--debug", "modes", "planar2", "--pose", "0", "0"])
    assert main(["modes", "planar2", "-n", "2", "--csv", "-"]) == 0
    cap = capsys.readouterr()
    data = [ln for ln in cap.out.splitlines() if not ln.startswith("# ")]
    assert cap.out.startswith("# dynstiff: ")                     # the metadata header
    assert data[0].startswith("mode,freq [Hz],kind,") and len(data) == 3
    assert "dsm model" in cap.err                 # the report moves out of the data's way


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
