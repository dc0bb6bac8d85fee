"""The `dynstiff` command line, run in this process (conftest.run_cli): the sweep commands
(dynstiff/cli/sweep.py)."""

import numpy as np
import pytest
from conftest import cli_help, inverted_stewart_scene, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


def test_cli_sweep_line_and_parameter(tmp_path):
    out = run_cli("sweep", "cogiro", "--line", "0", "0", "1", "2", "1", "1.5", "--steps", "3",
                  "-n", "8", "--csv", str(tmp_path / "s.csv"), "--plot", str(tmp_path / "v.png"))
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""                # no progress bar where stderr is not a terminal
    import pandas as pd
    df = pd.read_csv(tmp_path / "s.csv", comment="#")
    assert sorted(df["step"].unique()) == [0, 1, 2]
    # the 8 lowest modes and the 6 platform modes (3 of them above) at every step
    assert (df.groupby("step").size() >= 8).all() and df["track"].nunique() == 6
    assert (df.groupby("step")["track"].count() == 6).all()
    assert abs(df["value"].max() - (4 + 1 + 0.25) ** 0.5) < 1e-9     # arc length [m]
    assert (tmp_path / "v.png").stat().st_size > 10_000
    out = run_cli("sweep", "cogiro", "--parameter", "EA", "--values", "1.4e5", "9.8e5",
                  "-n", "6", "--quiet")
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""                                  # --quiet: no progress bar
    assert "EA [N]" in out.stdout
    bad = run_cli("sweep", "cogiro")
    assert bad.returncode == 2 and "--line, --path, --trajectory or --parameter" in bad.stderr
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
    import pandas as pd

    f = tmp_path / "path.csv"
    f.write_text("# a path\nx,y,z\n0,0,1\n0.5,0.2,1.1  # comment\n\n1,0.4,1.2,0,0,0.05\n")
    out = run_cli("sweep", "cogiro", "--path", str(f), "-n", "6", "--quiet", "--csv",
                  str(tmp_path / "s.csv"))
    assert out.returncode == 0, out.stderr
    df = pd.read_csv(tmp_path / "s.csv", comment="#")
    rob = ds.load_scene("cogiro").robot
    for k, pose in enumerate([[0, 0, 1], [0.5, 0.2, 1.1], [1, 0.4, 1.2, 0, 0, 0.05]]):
        ref = ds.eigenfrequencies(ds.FrequencyModel(rob.equilibrium(pose=pose)), 6)
        np.testing.assert_allclose(df.loc[df["step"] == k, "freq [Hz]"][:6], ref, rtol=1e-12)
    f.write_text("0 0 1\n0 0 1.1\n0 0\n")
    bad = run_cli("sweep", "cogiro", "--path", str(f), "-n", "6")
    assert bad.returncode == 2 and "line 3" in bad.stderr and str(f) in bad.stderr




def test_cli_sweep_follows_a_trajectory_of_the_scene(tmp_path):
    """A CASPR trajectory (quintic, three waypoints at 0, 2, 4 s) read by import-caspr
    drives the sweep: the steps are equally spaced in time, the veering diagram marks the
    waypoints, and every step has the six platform modes (global) under the cables' first
    mode (the start, symmetric, has degenerate pairs whose shapes the tracking may pair
    differently, so the number of tracks is not asserted)."""
    scene = inverted_stewart_scene(tmp_path / "s.toml")
    out = run_cli("sweep", str(scene), "--trajectory", "lift_and_turn", "--steps", "5", "-n",
                  "6", "--quiet", "--csv", str(tmp_path / "s.csv"), "--plot",
                  str(tmp_path / "v.png"))
    assert out.returncode == 0, out.stderr
    import pandas as pd
    df = pd.read_csv(tmp_path / "s.csv", comment="#")
    assert sorted(df["value"].unique()) == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert (df["kind"] == "global").all() and (df.groupby("step").size() == 6).all()
    f0 = ds.eigenfrequencies(ds.build_model(ds.load_scene(scene).equilibrium(), "dsm"), 6)
    np.testing.assert_allclose(np.sort(df[df["step"] == 0]["freq [Hz]"]), f0, rtol=1e-9)
    assert "time along trajectory lift_and_turn [s]" in out.stdout
    assert (tmp_path / "v.png").stat().st_size > 10_000
    bad = run_cli("sweep", str(scene), "--trajectory", "nope")
    assert bad.returncode == 2 and "the trajectories ['lift_and_turn', 'square'" in bad.stderr
    bad = run_cli("sweep", "cogiro", "--trajectory", "nope")
    assert bad.returncode == 2 and "no [[trajectories]]" in bad.stderr


# ------------------------------------------------------------------ helpers of the tests below
def _header(text):
    """The ``# key: value`` metadata header of a CSV written by the command, as a dict."""
    import json
    head = {}
    for line in text.splitlines():
        if not line.startswith("# "):
            break
        key, _, value = line[2:].partition(": ")
        head[key] = json.loads(value)
    return head


def _scene_file(path, name="pendulum", g=None, trajectory=False):
    """A copy of the built-in scene ``name`` at ``path``, with gravity ``g`` [m/s^2] if
    given and, with ``trajectory``, a linear trajectory "slide" of three waypoints."""
    from pathlib import Path
    text = (Path(ds.__file__).parent / "scenes" / f"{name}.toml").read_text()
    if g is not None:
        assert "g = 9.81\n" in text
        text = text.replace("g = 9.81\n", f"g = {g}\n")
    if trajectory:
        text += ('\n[[trajectories]]\nname = "slide"\nlaw = "linear"\n'
                 "times = [0.0, 1.0, 3.0]\n"
                 "positions = [[0.0, 0.0, -10.0], [2.0, 0.0, -10.0], [4.0, 0.0, -9.0]]\n")
    path.write_text(text)
    return path


def _spy_sweep(monkeypatch):
    """Record the arguments of every call of dynstiff.analyses.sweep.sweep (which still
    runs) and its result: a list of (args, kwargs, result)."""
    import dynstiff.analyses.sweep as mod
    real, calls = mod.sweep, []

    def spy(*a, **kw):
        res = real(*a, **kw)
        calls.append((a, kw, res))
        return res
    monkeypatch.setattr(mod, "sweep", spy)
    return calls


# ------------------------------------------------------------------ --parameter
@pytest.mark.parametrize("name, unit, values", [
    ("EA", "N", [5e4, 2e5]),
    ("mass_per_length", "kg/m", [0.002, 0.02]),
    ("mass", "kg", [5.0, 20.0]),
    ("t_min", "N", [1000.0, 3000.0]),
])
def test_cli_sweep_parameter_changes_the_robot(tmp_path, name, unit, values):
    """--parameter NAME --values: at each value the frequencies are those of the scene's
    robot (its gravity kept, here not the standard one) with that one parameter changed, at
    the scene's pose; the table header names the scene, the pose, the model, the band and
    the unit of the value, and the printed veering table is headed by "NAME [unit]"."""
    from dataclasses import replace

    import pandas as pd

    scene_path = _scene_file(tmp_path / "p.toml", g=4.0)
    csv = tmp_path / "s.csv"
    out = run_cli("sweep", scene_path, "--parameter", name, "--values",
                  *[repr(v) for v in values], "-n", "2", "--quiet", "--csv", csv)
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""
    scene = ds.load_scene(scene_path)
    rob = scene.robot
    assert rob.g == 4.0
    df = pd.read_csv(csv, comment="#")
    assert df["value"].unique().tolist() == values
    for k, v in enumerate(values):
        cables, platform, limits = rob.cables, rob.platform, rob.tension_limits
        if name in ("EA", "mass_per_length"):
            cables = [replace(c, **{name: v}) for c in cables]
        elif name == "mass":
            platform = replace(platform, mass=v)
        else:
            limits = (v, limits[1])
        changed = ds.Robot(rob.anchors, rob.attachments, cables, platform, g=rob.g,
                           tension_limits=limits, name=rob.name)
        ref = ds.eigenfrequencies(ds.FrequencyModel(changed.equilibrium(pose=scene.pose)), 2)
        got = df.loc[df["step"] == k, "freq [Hz]"].to_numpy()
        np.testing.assert_allclose(got, ref, rtol=1e-9)
    head = _header(csv.read_text())
    assert list(head) == ["dynstiff", "scene", "pose", "model", "date", "band_hz", "units"]
    assert head["scene"] == scene.name
    assert head["pose"] == {"position [m]": scene.pose.position.tolist(),
                            "rotation [rad]": scene.pose.rotation.tolist()}
    assert head["model"] == "dsm"
    assert head["band_hz"] == list(scene.band_hz)
    assert head["units"] == f"Hz; value in {name} [{unit}]"
    lines = out.stdout.splitlines()
    assert lines[-1] == f"wrote {csv}"
    assert [ln.split() for ln in lines if ln.lstrip().startswith(name)] == [
        [name, f"[{unit}]", "track", "0", "[Hz]"]]


def test_cli_sweep_parameter_needs_values(tmp_path):
    """--parameter without --values: exit 2 with the one-line error, nothing written."""
    out = run_cli("sweep", "pendulum", "--parameter", "EA", "--csv", tmp_path / "s.csv")
    assert out.returncode == 2
    assert out.stderr == "dynstiff: error: --parameter needs --values V1 V2 ...\n"
    assert out.stdout == ""
    assert not (tmp_path / "s.csv").exists()


# ------------------------------------------------------------------ modes asked per step
@pytest.mark.parametrize("extra, n_modes, fmax", [
    ([], "scene", None),
    (["-n", "3"], 3, None),
    (["--band", "0.05", "3.5"], None, 3.5),
    (["--band", "0.05", "3.5", "-n", "3"], 3, 3.5),
    (["--fmax", "3.5"], None, 3.5),
    (["--fmax", "3.5", "-n", "3"], 3, 3.5),
])
def test_cli_sweep_modes_asked_reach_the_sweep(tmp_path, monkeypatch, extra, n_modes, fmax):
    """The modes listed per step: the scene's n_modes by default, -n N, all modes up to the
    top of --band / --fmax (with -n: the first N of them): n_modes and fmax_hz passed to
    the sweep, with the scene's model, failures recorded and the progress bar."""
    calls = _spy_sweep(monkeypatch)
    out = run_cli("sweep", "planar2", "--line", "0", "0", "-10", "1", "0", "-10", "--steps",
                  "2", *extra, "--quiet")
    assert out.returncode == 0, out.stderr
    assert len(calls) == 1
    (robot,), kw, res = calls[0]
    scene = ds.load_scene("planar2")
    assert robot.name == scene.robot.name
    assert kw["n_modes"] == (scene.n_modes if n_modes == "scene" else n_modes)
    assert kw["fmax_hz"] == fmax
    assert kw["rung"] == "dsm" and kw["on_error"] == "record" and callable(kw["progress"])
    assert [p.tolist() for p in kw["poses"]] == [[0, 0, -10, 0, 0, 0], [1, 0, -10, 0, 0, 0]]


# ------------------------------------------------------------------ the table header
def test_cli_sweep_line_table_header(tmp_path):
    """A sweep along --line writes the header: the scene, a text for the pose (the pose
    columns vary), the model, the band, the segments of the lumped model, the unit."""
    from dynstiff.analyses.settings import analysis_settings
    csv = tmp_path / "s.csv"
    out = run_cli("sweep", "planar2", "--line", "0", "0", "-10", "1", "0", "-10", "--steps",
                  "2", "-n", "2", "--model", "lumped", "--quiet", "--csv", csv)
    assert out.returncode == 0, out.stderr
    head = _header(csv.read_text())
    scene = ds.load_scene("planar2")
    assert list(head) == ["dynstiff", "scene", "pose", "model", "date", "band_hz", "segments",
                          "units"]
    assert head["scene"] == scene.name
    assert head["pose"] == "along arc length [m] (the pose columns of each step)"
    assert head["model"] == "lumped"
    assert head["segments"] == analysis_settings(scene, rung="lumped").segments
    assert head["band_hz"] == list(scene.band_hz)
    assert head["units"] == "Hz; value in arc length [m]"
    assert out.stdout.splitlines()[-1] == f"wrote {csv}"


# ------------------------------------------------------------------ infeasible steps
def test_cli_sweep_report_goes_to_stderr_with_csv_on_stdout(monkeypatch):
    """With --csv -, the report, and the line of each infeasible step (step, value and the
    first line of the error), go to standard error; standard output holds the table only."""
    import io

    import pandas as pd

    calls = _spy_sweep(monkeypatch)
    out = run_cli("sweep", "planar2", "--line", "0", "0", "-10", "20", "0", "-10", "--steps",
                  "3", "-n", "2", "--quiet", "--csv", "-")
    assert out.returncode == 0, out.stderr
    res = calls[0][2]
    assert len(res.failures) >= 1
    expected = [f"step {k} (arc length [m] = {v:g}): infeasible, skipped: "
                f"{msg.splitlines()[0]}" for k, v, msg in res.failures]
    err = out.stderr.splitlines()
    assert err[-len(expected):] == expected
    assert err[0].startswith("dsm model, undamped natural frequencies (")
    assert "infeasible, skipped" not in out.stdout
    df = pd.read_csv(io.StringIO(out.stdout), comment="#")
    assert df["step"].unique().tolist() == [0, 1, 2]
    assert (df["kind"] == "infeasible").sum() == len(res.failures)


# ------------------------------------------------------------------ --path
def test_cli_sweep_path_file_comments_and_headers(tmp_path, monkeypatch):
    """--path: everything after the first '#' of a line is a comment (even one holding
    another '#'); only one header line is skipped: a second non-numeric line is an error
    naming the file, the line and its text."""
    calls = _spy_sweep(monkeypatch)
    f = tmp_path / "path.txt"
    f.write_text("0 0 -10 # start # of the path\n1 0 -10  # end\n")
    out = run_cli("sweep", "planar2", "--path", f, "-n", "2", "--quiet")
    assert out.returncode == 0, out.stderr
    rot = ds.load_scene("planar2").pose.rotation.tolist()
    assert [p.tolist() for p in calls[0][1]["poses"]] == [[0, 0, -10, *rot], [1, 0, -10, *rot]]
    f.write_text("x y z\nlabel a b\n0 0 -10\n1 0 -10\n")
    bad = run_cli("sweep", "planar2", "--path", f, "-n", "2", "--quiet")
    assert bad.returncode == 2
    assert bad.stderr == (f"dynstiff: error: --path {f}: line 2: expected numbers, got "
                          f"'label a b'\n")
    assert len(calls) == 1


# ------------------------------------------------------------------ --trajectory, the figure
def test_cli_sweep_trajectory_figure_marks_the_waypoints(tmp_path, monkeypatch):
    """--trajectory with --plot: one dotted grey vertical line per waypoint of the
    trajectory (gid waypoint-K, at its time, beneath the tracks), one legend entry
    "waypoints" (the first line's), the legend (font 8) with its top left corner at (1.01,
    1.0) in axes coordinates; the figure is written."""
    import dynstiff.cli.sweep as cli_sweep
    scene_path = _scene_file(tmp_path / "t.toml", name="planar2", trajectory=True)
    seen = {}
    real_save = cli_sweep.save_figure

    def spy_save(fig, path):
        ax = fig.axes[0]
        fig.canvas.draw()
        leg = ax.get_legend()
        box = leg.get_window_extent()
        seen["corner"] = ax.transAxes.inverted().transform((box.x0, box.y1))
        seen["texts"] = [(t.get_text(), t.get_fontsize()) for t in leg.get_texts()]
        seen["lines"] = [(ln.get_gid(), [float(x) for x in ln.get_xdata()], ln.get_label(),
                          ln.get_linestyle(), ln.get_color(), ln.get_zorder())
                         for ln in ax.get_lines() if (ln.get_gid() or "").startswith("way")]
        real_save(fig, path)
    monkeypatch.setattr(cli_sweep, "save_figure", spy_save)
    png = tmp_path / "v.png"
    out = run_cli("sweep", scene_path, "--trajectory", "slide", "--steps", "3", "-n", "2",
                  "--quiet", "--plot", png)
    assert out.returncode == 0, out.stderr
    assert png.stat().st_size > 0
    assert out.stdout.splitlines()[-1] == f"wrote {png}"
    times = ds.load_scene(scene_path).trajectories["slide"].times.tolist()
    lines = seen["lines"]
    assert [ln[0] for ln in lines] == [f"waypoint-{k}" for k in range(len(times))]
    assert [ln[1] for ln in lines] == [[t, t] for t in times]
    assert lines[0][2] == "waypoints"
    assert all(ln[2].startswith("_") for ln in lines[1:])
    assert all(ln[3] == ":" and ln[4] == "0.55" and ln[5] == 0 for ln in lines)
    assert [t for t, _ in seen["texts"]].count("waypoints") == 1
    assert {size for _, size in seen["texts"]} == {8.0}
    np.testing.assert_allclose(seen["corner"], [1.01, 1.0], atol=1e-6)


# ------------------------------------------------------------------ --steps default, help
def test_cli_sweep_steps_default(monkeypatch):
    """--line without --steps: 11 poses equally spaced from the start to the end."""
    calls = _spy_sweep(monkeypatch)
    out = run_cli("sweep", "planar2", "--line", "0", "0", "-10", "1", "0", "-10", "-n", "1",
                  "--quiet")
    assert out.returncode == 0, out.stderr
    poses = calls[0][1]["poses"]
    np.testing.assert_allclose([p[0] for p in poses], np.linspace(0, 1, 11))


@pytest.mark.parametrize("given, message", [
    (("--line", "0", "0", "-10", "1", "0", "-10", "--pose", "0", "0", "-10"),
     "--pose does not apply without --parameter (the poses are the path's)"),
    (("--trajectory", "t", "--values", "1", "2"),
     "--values does not apply without --parameter (the poses are the path's)"),
    (("--path", "p.csv", "--pose", "0", "0", "-10", "--values", "1"),
     "--pose, --values do not apply without --parameter (the poses are the path's)"),
    (("--path", "p.csv", "--steps", "4"), "--steps does not apply without --line or "
                                           "--trajectory"),
    (("--parameter", "EA", "--values", "1e6", "2e6", "--steps", "4"),
     "--steps does not apply without --line or --trajectory"),
    (("--line", "0", "0", "-10", "1", "0", "-10", "--segments", "4"),
     "--segments applies to the lumped model only (--model lumped), not to the 'dsm' model"),
])
def test_cli_sweep_options_that_do_not_apply_are_refused(given, message, tmp_path,
                                                         monkeypatch):
    """An option the sweep asked for would ignore is refused with one line naming it, exit
    2, before any step is computed and before any file is written."""
    calls = _spy_sweep(monkeypatch)
    csv = tmp_path / "s.csv"
    out = run_cli("sweep", "planar2", *given, "--csv", csv, cwd=tmp_path)
    assert (out.returncode, out.stdout, out.stderr) == (2, "", f"dynstiff: error: {message}\n")
    assert calls == [] and not csv.exists()


def test_cli_sweep_lumped_model_takes_the_segments_given(monkeypatch):
    """--model lumped --segments 4: the sweep's lumped models have 4 segments per cable
    (the scene's count without --segments)."""
    calls = _spy_sweep(monkeypatch)
    line = ("--line", "0", "0", "-10", "1", "0", "-10", "--steps", "2", "-n", "2", "--quiet")
    assert run_cli("sweep", "planar2", *line, "--model", "lumped", "--segments", "4"
                   ).returncode == 0
    assert run_cli("sweep", "planar2", *line, "--model", "lumped").returncode == 0
    (_, kw4, _), (_, kw, _) = calls
    assert (kw4["rung"], kw4["segments"]) == ("lumped", 4)
    from dynstiff.analyses.settings import analysis_settings
    assert kw["segments"] == analysis_settings(ds.load_scene("planar2"),
                                               rung="lumped").segments != 4


def test_cli_sweep_help(monkeypatch):
    """`dynstiff -h` lists sweep with its help, `dynstiff sweep -h` shows each option with
    its metavars and help; the sweep takes --pose but no --lengths."""
    assert ("sweep modes along a straight path or over a parameter, platform modes tracked; "
            "table and veering diagram") in cli_help(monkeypatch)
    text = cli_help(monkeypatch, "sweep")
    for opt in [
        "--line X0 Y0 Z0 X1 Y1 Z1 path of P from (X0, Y0, Z0) to (X1, Y1, Z1) [m], the "
        "scene's rotation",
        "--steps STEPS poses along --line or --trajectory (default 11)",
        "--path FILE poses from a text/CSV file, one a line: x y z [m] (the scene's rotation) "
        "or x y z rx ry rz [m, rad]; '#' comments, a header line",
        "--trajectory NAME the scene's trajectory NAME: poses along it ([[trajectories]], "
        "e.g. from dynstiff import-caspr), --steps of them equally spaced in time",
        "--values V [V ...] values of --parameter, in its unit",
        "--pose X [X ...] platform pose x y z [m] (and rx ry rz [rad]), by inverse statics: "
        "of the --parameter sweep (default: the scene's pose)",
        "-n N, --n-modes N number of modes: per step (default: the scene's n_modes; with "
        "--band or --fmax, all in the band)",
        "--band LO HI band of interest LO HI [Hz]: every mode up to its top at every step "
        "(default: the first --n-modes)",
        "--csv FILE write the table as CSV: one row per mode and step ('-': standard output)",
        "--json FILE write the table as JSON: one row per mode and step ('-': standard "
        "output)",
        "--plot FILE write a figure: the veering diagram (PNG, PDF, SVG, ...)",
        "--segments SEGMENTS segments per cable of the lumped model (default: the scene's, "
        "else 30)",
    ]:
        assert opt in text, opt
    assert "--lengths" not in text
    bad = run_cli("sweep", "pendulum", "--lengths", "1", "1")
    assert bad.returncode == 2 and "unrecognized arguments: --lengths" in bad.stderr
