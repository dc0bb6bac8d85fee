"""The `dynstiff` command line, run in this process (conftest.run_cli): the main job `demo`
and `report` (dynstiff/cli/report.py)."""

import re
from pathlib import Path

import pytest
from conftest import cli_help, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


# ------------------------------------- what demo/report pass to the library, print, document
# (fast: the report functions are replaced by spies that write nothing)

@pytest.fixture
def robot_spy(monkeypatch):
    """robot_report replaced by a spy: records its arguments, returns a text and two files
    (under the output folder) and writes nothing."""
    calls = []

    def fake(scene, out, settings=None, n_points=3000):
        calls.append(dict(scene=scene, out=out, settings=settings, n_points=n_points))
        return f"report of {scene.name}\n", [Path(out) / "modes.csv", Path(out) / "frf.png"]
    monkeypatch.setattr("dynstiff.report.robot.robot_report", fake)
    return calls


class _FakeCableReport:
    def text(self):
        return "single cable text\nsecond line\n"


@pytest.fixture
def cable_spy(monkeypatch):
    """cable_report and write_report replaced by spies (nothing computed nor written)."""
    calls = {"cable_report": [], "write_report": []}

    def fake_cable_report(**kw):
        calls["cable_report"].append(kw)
        return _FakeCableReport()

    def fake_write_report(*a, **kw):
        calls["write_report"].append((a, kw))
        out = Path(a[1])
        return [out / "report.txt", out / "statics.csv", out / "modes.csv"]
    monkeypatch.setattr("dynstiff.report.cable.cable_report", fake_cable_report)
    monkeypatch.setattr("dynstiff.report.cable.write_report", fake_write_report)
    return calls


def _wrote(files):
    return "\nwrote:\n" + "".join(f"  {f}\n" for f in files)


def test_report_passes_every_option_to_robot_report_and_prints_its_text(tmp_path, robot_spy):
    """`report SCENE` with --band, -n, --model, --damping, --points, --out: robot_report gets
    the scene, the output folder, the settings of analysis_settings with those overrides and
    n_points; stdout is exactly its text then the "wrote:" list of its files."""
    from dynstiff.analyses.settings import analysis_settings
    out_dir = tmp_path / "o"
    out = run_cli("report", "planar2", "--band", "0.5", "4", "-n", "5", "--model", "spring",
                  "--damping", "0.03", "--points", "57", "--out", out_dir)
    assert out.returncode == 0, out.stderr
    [call] = robot_spy
    scene = ds.load_scene("planar2")
    assert call["scene"].name == scene.name and call["scene"].pose == scene.pose
    assert call["out"] == str(out_dir)
    assert call["n_points"] == 57
    expected = analysis_settings(scene, band_hz=(0.5, 4.0), n_modes=5, rung="spring",
                                 damping=[0.03])
    assert expected != analysis_settings(scene)
    assert call["settings"] == expected
    files = [out_dir / "modes.csv", out_dir / "frf.png"]
    assert out.stdout == f"report of {scene.name}\n" + _wrote(files)
    assert not out_dir.exists()


def test_report_and_demo_defaults(tmp_path, robot_spy):
    """Without options: `report SCENE` writes to ./dynstiff-report, `demo` analyses CoGiRo
    and writes to ./dynstiff-demo; both with the scene's own settings and the documented
    3000 FRF points (--points, "default 3000")."""
    from dynstiff.analyses.settings import analysis_settings
    rep = run_cli("report", "fourcable", cwd=tmp_path)
    demo = run_cli("demo", cwd=tmp_path)
    assert rep.returncode == 0 and demo.returncode == 0, rep.stderr + demo.stderr
    [r, d] = robot_spy
    for call, name, folder in ((r, "fourcable", "dynstiff-report"),
                               (d, "cogiro", "dynstiff-demo")):
        scene = ds.load_scene(name)
        assert call["scene"].name == scene.name
        assert call["out"] == folder
        assert call["n_points"] == 3000
        assert call["settings"] == analysis_settings(scene)
    assert demo.stdout == f"report of {ds.load_scene('cogiro').name}\n" + _wrote(
        [Path("dynstiff-demo") / "modes.csv", Path("dynstiff-demo") / "frf.png"])
    assert list(tmp_path.iterdir()) == []


def test_report_pose_moves_the_scene(tmp_path, robot_spy):
    """--pose: robot_report gets the scene at that pose (position and rotation), its
    unstretched lengths dropped (solved again at the new pose)."""
    from dynstiff.robot.pose import as_pose
    pose = [0.1, 0.0, -9.5]
    scene = ds.load_scene("planar2")
    want = as_pose(pose)
    assert want != scene.pose
    out = run_cli("report", "planar2", "--pose", *pose, "--out", tmp_path / "o")
    assert out.returncode == 0, out.stderr
    [call] = robot_spy
    got = call["scene"]
    assert got.name == scene.name and got.pose == want
    assert list(got.pose.position) == pose and list(got.pose.rotation) == [0.0, 0.0, 0.0]
    assert got.unstretched_lengths is None


def test_report_infeasible_pose_fails_before_any_work(tmp_path, robot_spy):
    """A pose outside the wrench-feasible workspace: exit 2 with the statics' one-line
    error, robot_report is never called and no folder is created."""
    from dynstiff.errors import InfeasiblePoseError
    from dynstiff.robot.pose import as_pose
    pose = [0.0, 0.0, 100.0]
    with pytest.raises(InfeasiblePoseError) as exc:
        ds.load_scene("planar2").robot.equilibrium(pose=as_pose(pose))
    out = run_cli("report", "planar2", "--pose", *pose, "--out", tmp_path / "o")
    assert out.returncode == 2
    assert out.stderr == f"dynstiff: error: {exc.value}\n"
    assert out.stdout == ""
    assert robot_spy == [] and not (tmp_path / "o").exists()


def test_report_refuses_lengths(tmp_path, robot_spy):
    """demo/report take --pose only: --lengths is an unrecognized argument (exit 2)."""
    for cmd in ("report", "demo"):
        out = run_cli(cmd, "planar2", "--lengths", "30", "30", "--out", tmp_path / "o")
        assert out.returncode == 2
        assert "unrecognized arguments: --lengths 30 30" in out.stderr
    assert robot_spy == [] and not (tmp_path / "o").exists()


@pytest.mark.parametrize("opts, fmax", [([], 12.0), (["--fmax", "7"], 7.0),
                                        (["--band", "1", "9"], 9.0)])
def test_demo_cable_passes_band_top_and_points(tmp_path, cable_spy, robot_spy, opts, fmax):
    """`demo --cable`: cable_report gets the top of --band, else --fmax, else the documented
    12 Hz, and --points; write_report gets that report and --out; stdout is exactly the
    report's text then the "wrote:" list of the files write_report returns."""
    out_dir = tmp_path / "c"
    out = run_cli("demo", "--cable", *opts, "--points", "33", "--out", out_dir)
    assert out.returncode == 0, out.stderr
    assert cable_spy["cable_report"] == [{"fmax_hz": fmax, "n_points": 33}]
    [(a, kw)] = cable_spy["write_report"]
    assert isinstance(a[0], _FakeCableReport) and a[1] == str(out_dir) and kw == {}
    files = [out_dir / "report.txt", out_dir / "statics.csv", out_dir / "modes.csv"]
    assert out.stdout == _FakeCableReport().text() + _wrote(files)
    assert robot_spy == []


@pytest.mark.parametrize("given, message", [
    (("planar2",), "demo --cable reports CoGiRo's cable 0, not a scene's: drop 'planar2' "
                   "(or --cable)"),
    (("--pose", "0", "0", "1"), "--pose does not apply with --cable (the single-cable "
                                "report of CoGiRo's cable 0)"),
    (("-n", "3", "--model", "exact", "--damping", "0"),
     "-n, --model, --damping do not apply with --cable (the single-cable report of "
     "CoGiRo's cable 0)"),
])
def test_demo_cable_refuses_what_it_would_ignore(tmp_path, cable_spy, robot_spy, given,
                                                 message):
    """`demo --cable` reports CoGiRo's cable 0: a scene, a pose, a mode count, a model or a
    damping would be ignored, so each is refused with one line, exit 2, no report made and
    no folder created."""
    out = run_cli("demo", "--cable", *given, "--out", tmp_path / "c")
    assert (out.returncode, out.stdout, out.stderr) == (2, "", f"dynstiff: error: {message}\n")
    assert cable_spy["cable_report"] == [] and robot_spy == []
    assert not (tmp_path / "c").exists()


@pytest.mark.parametrize("argv, label", [
    (["demo", "--cable"], "demo --cable"),
    (["report", "planar2"], "report " + ds.load_scene("planar2").name),
    (["demo", "pendulum"], "demo " + ds.load_scene("pendulum").name)])
def test_elapsed_bar_label_and_quiet(tmp_path, cable_spy, robot_spy, argv, label):
    """On a terminal the command shows a bar labelled with the job (the cable demo, or the
    command and the scene's name) and the time elapsed; --quiet: nothing on stderr."""
    run = run_cli(*argv, "--out", tmp_path / "o", terminal=True)
    code, err = run.returncode, run.stderr
    assert code == 0
    assert re.search(rf"\r{re.escape(label)}: \d\d:\d\d\r", err), err
    run = run_cli(*argv, "--out", tmp_path / "o", "--quiet", terminal=True)
    code, err = run.returncode, run.stderr
    assert code == 0 and err == ""


def test_help_of_demo_and_report(monkeypatch):
    """`dynstiff -h` describes demo and report; `demo -h` / `report -h` document the
    optional scene (demo), --cable, --pose, -n, --points and --out with their defaults."""
    from dynstiff.cli.options import MEANINGS
    top = cli_help(monkeypatch)
    assert ("demo main job on a scene (default: CoGiRo): statics, modes, model choice, "
            "design checks, FRF and mode-shape figures, CSV tables report the demo's "
            "analysis of one scene: tables, figures and a self-contained report.html "
            "scenes ") in top
    for cmd, folder in (("demo", "dynstiff-demo"), ("report", "dynstiff-report")):
        h = cli_help(monkeypatch, cmd)
        assert "--lengths" not in h
        for text in (
                f"--pose X [X ...] {MEANINGS['--pose']}: default: the scene's pose --band",
                f"-n N, --n-modes N {MEANINGS['--n-modes']}: in the modes table (default: "
                f"the scene's n_modes) --model",
                "--points POINTS uniform frequencies of the FRFs: refined around every mode "
                "(default 3000) --damping",
                f"--out FOLDER write the main result to: the output folder, created (default "
                f"{folder}) --quiet"):
            assert text in h, (cmd, text)
    demo = cli_help(monkeypatch, "demo")
    assert demo.startswith("usage: dynstiff demo [-h] [--cable] ")
    assert "[--quiet] [scene] " in demo
    assert f"scene {MEANINGS['scene']}: default cogiro options:" in demo
    assert ("--cable single-cable report instead (CoGiRo cable 0: statics, fixed-end "
            "frequencies, dynamic stiffness plot; the top of --band or --fmax, default "
            "12 Hz) --pose") in demo




# --------------------------------------------------------------------------------- demo
def test_demo_main_job_on_cogiro(tmp_path):
    out = run_cli("demo", "--out", tmp_path, "--points", "400")
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
    shapes = sorted(tmp_path.glob("mode_shape_*.png"))      # one per platform mode
    assert len(shapes) == (modes["platform mode"]).sum() >= 6
    for path in [tmp_path / "frf.png", *shapes]:
        assert path.stat().st_size > 10_000
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
    for argv in (["demo", "fourcable"], ["report", "fourcable"]):
        out_dir = tmp_path / argv[0]
        out = run_cli(*argv, "--out", out_dir, "--points", "200")
        assert out.returncode == 0, out.stderr
        p = Collect()
        p.feed((out_dir / "report.html").read_text())
        text = " ".join(p.text)
        assert "script" not in p.tags and "link" not in p.tags
        assert [ln.split(",")[0] for ln in p.links] == ["data:text/csv;base64"]  # modes.csv
        assert base64.b64decode(p.links[0].split(",", 1)[1]).decode() == \
            (out_dir / "modes.csv").read_text()
        shapes = list(out_dir.glob("mode_shape_*.png"))
        assert p.tags.count("table") >= 3 and len(p.srcs) == 1 + len(shapes) > 1
        for src in p.srcs:
            assert src.startswith("data:image/png;base64,")
            assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
        assert "PASS" in text and "Recommended for this band" in text and "damping" in text


def test_demo_and_check_agree_on_every_scene(tmp_path):
    """One source of defaults: on every built-in scene `demo` and `check` print the same
    PASS/FAIL verdicts and the same recommended model (segments included)."""
    def verdicts(text):
        return [ln[:40] for ln in text.splitlines()
                if ln.startswith(("PASS", "FAIL", "UNKNOWN", "n/a"))]

    def recommendation(text):
        m = re.findall(r"recommended model: (\w+)(?: with N = (\d+)| \((\d+) segments)?",
                       text)
        return {(r, n or k) for r, n, k in m}
    for name in ds.list_scenes():
        demo = run_cli("demo", name, "--out", tmp_path / name, "--points", "100")
        check = run_cli("check", name)
        assert demo.returncode == 0 and check.returncode in (0, 1), demo.stderr + check.stderr
        assert verdicts(demo.stdout) == verdicts(check.stdout) != [], name
        rd, rc = recommendation(demo.stdout), recommendation(check.stdout)
        assert len(rd) == 1 and rd == rc, (name, rd, rc)
        assert "band 0.1-12 Hz; forbidden band none" not in demo.stdout


def test_demo_cable_report(tmp_path):
    out = run_cli("demo", "--cable", "--out", tmp_path, "--points", "400")
    assert out.returncode == 0, out.stderr
    assert "in-plane symmetric 1" in out.stdout
    for name in ["report.txt", "statics.csv", "modes.csv", "dynamic_stiffness.png"]:
        assert (tmp_path / name).stat().st_size > 0
    import pandas as pd
    modes = pd.read_csv(tmp_path / "modes.csv", comment="#")
    assert list(modes.columns) == ["freq [Hz]", "Omega [-]", "family", "order"]
    assert modes["freq [Hz]"].is_monotonic_increasing


@pytest.mark.parametrize("argv", [["demo", "--fmax", "-1"],
                                  ["demo", "--damping", "0.01", "0.01", "0", "1"],
                                  ["demo", "--damping", "-0.1"],
                                  ["report", "cogiro", "--damping", "0.01", "2"]])
def test_demo_validates_every_input_before_writing(tmp_path, argv):
    out = run_cli(*argv, "--out", tmp_path / "o")
    assert out.returncode == 2 and "error" in out.stderr
    assert not (tmp_path / "o").exists()


