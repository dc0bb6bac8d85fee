"""The `dynstiff` command line, run in this process (conftest.run_cli): the simulate command
(dynstiff/cli/simulate.py) along a line (--target) or a scene's trajectory (--trajectory);
the options it passes on, its report, tables and progress checked against a fake of the
tracking."""

import json
import re
import warnings
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from conftest import inverted_stewart_scene, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


def test_cli_simulate_follows_a_trajectory_of_the_scene(tmp_path):
    """A CASPR cubic trajectory (1.5 s, ending at 0.1 m/s) commanded through quasi-static
    lengths: the platform follows it within 1 % of the cable length; the CSV holds the
    path's 1.5 s plus the 0.1 s settling, every 10 ms."""
    scene = inverted_stewart_scene(tmp_path / "s.toml")
    out = run_cli("simulate", str(scene), "--trajectory", "swing", "--segments", "1",
                  "--time", "0.1", "--dt", "1e-2", "--quiet", "--csv", str(tmp_path / "t.csv"))
    assert out.returncode == 0, out.stderr
    m = re.search(r"trajectory 'swing' \(1.5 s, 2 waypoints\).*deviation from the "
                  r"quasi-static path ([0-9.e-]+) m \(([0-9.e-]+) % of", out.stdout)
    assert m and 0 < float(m.group(2)) < 1.0
    import pandas as pd
    df = pd.read_csv(tmp_path / "t.csv", comment="#")
    assert len(df) == 161 and abs(df["x desired [m]"].iloc[-1] - 0.2) < 1e-12
    bad = run_cli("simulate", str(scene), "--trajectory", "swing", "--target", "0", "0", "1")
    assert bad.returncode == 2 and "--target or --trajectory, not both" in bad.stderr
    bad = run_cli("simulate", "fourcable", "--trajectory", "swing")
    assert bad.returncode == 2 and "no [[trajectories]]" in bad.stderr


class _FakeTracking:
    max_deviation = 0.0012345
    relative_max_deviation = 0.00034567

    def __init__(self, traj):
        self.trajectory, self.response = traj, "time response"

    def to_frame(self):
        return pd.DataFrame({"x [m]": [1.0, 1.5], "deviation [m]": [0.0, 1e-3]},
                            index=pd.Index([0.0, 0.1], name="time [s]"))


@pytest.fixture
def track_spy(monkeypatch):
    """track replaced by a spy: records its arguments, reports 3 quasi-static poses done
    to its progress, warns (a slack segment; an energy drift if ``spy.warn``) and returns
    a fake result; plot_tracking replaced by a spy too."""
    from dynstiff.lumped import SlackSegmentWarning
    from dynstiff.timedomain.stepping import EnergyBalanceWarning
    spy = SimpleNamespace(calls=[], plots=[], warn=False)

    def track(robot, trajectory, segments=10, dt=2e-3, settle=0.0, progress=None, **kw):
        spy.calls.append(dict(robot=robot, traj=trajectory, segments=segments, dt=dt,
                              settle=settle, progress=progress, kw=kw))
        for j in range(1, 4):
            progress(j, 3)
        warnings.warn("a segment went slack (fake)", SlackSegmentWarning, stacklevel=2)
        if spy.warn:
            warnings.warn("energy balance drifts (fake)", EnergyBalanceWarning, stacklevel=2)
        return _FakeTracking(trajectory)

    def plot_tracking(tr):
        import matplotlib.pyplot as plt
        spy.plots.append(tr)
        return plt.figure(figsize=(1, 1))
    monkeypatch.setattr("dynstiff.timedomain.trajectory.track", track)
    monkeypatch.setattr("dynstiff.plot.plot_tracking", plot_tracking)
    return spy


def _line_report(start, target, speed, ramp, segments, dt):
    return (f"line {start} -> {target} m at {speed:g} m/s (ramp {ramp:g} s), {segments} "
            f"segments per cable, dt = {dt:g} s: largest deviation from the quasi-static path "
            f"{0.0012345:.4g} m ({100 * 0.00034567:.3g} % of the mean cable length)\n")


def test_line_from_the_pose_given_with_default_speed_and_ramp(track_spy, tmp_path):
    """--target from the start of --pose, defaults --speed 0.5 and --ramp 1: the line
    from that start to the target reaches track with the options (segments, dt, settle =
    --time, a progress); the report names the line and the fake's deviations; slack
    segments are not warned about; the CSV's pose is the line's start."""
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", "planar2", "--pose", "0.5", "0", "-10", "--target", "1", "0",
                  "-10", "--segments", "2", "--dt", "0.01", "--time", "0.3", "--csv", csv)
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""
    assert out.stdout == _line_report([0.5, 0.0, -10.0], [1.0, 0.0, -10.0], 0.5, 1.0, 2,
                                      0.01) + f"wrote {csv}\n"
    (c,) = track_spy.calls
    assert c["robot"].n_cables == ds.load_scene("planar2").robot.n_cables
    assert c["segments"] == 2 and c["dt"] == 0.01 and c["settle"] == 0.3
    assert c["progress"] is not None and c["kw"] == {}
    traj = c["traj"]
    assert traj.positions[0] == pytest.approx([0.5, 0.0, -10.0])
    assert traj.positions[-1] == pytest.approx([1.0, 0.0, -10.0])
    assert traj.duration == pytest.approx(0.5 / 0.5 + 1.0)      # length / speed + ramp
    meta = {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in
                                          csv.read_text().splitlines() if line.startswith("#"))}
    assert meta["pose"]["position [m]"] == pytest.approx([0.5, 0.0, -10.0])
    assert meta["segments"] == 2 and meta["dt [s]"] == 0.01
    assert meta["units"] == "SI, in the column names"
    assert pd.read_csv(csv, comment="#")["x [m]"].tolist() == [1.0, 1.5]


def test_line_keeps_the_start_rotation_and_warns_of_other_things(track_spy, tmp_path):
    """A line of cogiro from a rotated start: the path keeps the rotation and the table's
    pose has it; a warning other than a slack segment still reaches standard error as
    one line."""
    track_spy.warn = True
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", "cogiro", "--pose", "0", "0", "1", "0", "0", "0.05",
                  "--target", "0.2", "0", "1", "--speed", "0.4", "--ramp", "0.25",
                  "--segments", "1", "--quiet", "--csv", csv)
    assert out.returncode == 0, out.stderr
    assert out.stderr == "dynstiff: warning: energy balance drifts (fake)\n"
    traj = track_spy.calls[0]["traj"]
    assert traj.rotations[0] == pytest.approx([0.0, 0.0, 0.05])
    assert out.stdout == _line_report([0.0, 0.0, 1.0], [0.2, 0.0, 1.0], 0.4, 0.25, 1,
                                      0.002) + f"wrote {csv}\n"
    meta = {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in
                                          csv.read_text().splitlines() if line.startswith("#"))}
    assert meta["pose"]["rotation [rad]"] == pytest.approx([0.0, 0.0, 0.05])


def test_line_table_on_stdout_keeps_the_report_on_stderr(track_spy, tmp_path):
    """--csv - with a line: standard output holds the table alone; the report and the
    'wrote' line of --plot (the tracking figure of the result) go to standard error."""
    png = tmp_path / "line.png"
    out = run_cli("simulate", "planar2", "--target", "1", "0", "-10", "--speed", "1",
                  "--ramp", "0.5", "--quiet", "--csv", "-", "--plot", png)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("# dynstiff: ") and "line [" not in out.stdout
    assert "wrote" not in out.stdout
    start = [float(v) for v in ds.load_scene("planar2").pose.position]
    assert out.stderr == _line_report(start, [1.0, 0.0, -10.0], 1, 0.5, 10, 0.002) + (
        f"wrote {png}\n")
    (tr,) = track_spy.plots
    assert isinstance(tr, _FakeTracking) and png.stat().st_size > 0


def test_line_progress_on_a_terminal(track_spy):
    """On a terminal: a bar 'quasi-static lengths' counting poses, then, once they are
    done, the time elapsed while 'time stepping'; neither with --quiet."""
    run = run_cli("simulate", "planar2", "--target", "1", "0", "-10", terminal=True)
    code, err = run.returncode, run.stderr
    assert code == 0
    m = re.search(r"quasi-static lengths: 100%.*3/3 \[[^\]]*(pose/s|s/pose)\]", err)
    assert m, err
    step = re.search(r"\rtime stepping: \d\d:\d\d\r", err)
    assert step and step.start() > m.start(), err
    run = run_cli("simulate", "planar2", "--target", "1", "0", "-10", "--quiet", terminal=True)
    assert (run.returncode, run.stderr) == (0, "")                       # --quiet: no bars


def test_trajectory_of_the_scene_reaches_track(track_spy, tmp_path):
    """--trajectory: the scene's waypoints followed (start and duration of the path) reach
    track; the report names the trajectory, its duration and waypoints; the table's pose
    is the path's start."""
    scene_file = inverted_stewart_scene(tmp_path / "s.toml")
    path = ds.load_scene(scene_file).trajectories["swing"]
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", scene_file, "--trajectory", "swing", "--segments", "1",
                  "--time", "0.1", "--dt", "1e-2", "--csv", csv)
    assert out.returncode == 0, out.stderr
    (c,) = track_spy.calls
    traj = c["traj"]
    assert traj.duration == pytest.approx(path.duration) and c["settle"] == 0.1
    first = path.at(np.array([path.times[0]]))
    assert traj.positions[0] == pytest.approx(first[0][0])
    assert out.stdout.startswith(f"trajectory 'swing' ({path.duration:g} s, "
                                 f"{path.times.size} waypoints), 1 segments per cable, "
                                 f"dt = 0.01 s: largest deviation")
    meta = {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in
                                          csv.read_text().splitlines() if line.startswith("#"))}
    assert meta["pose"]["position [m]"] == pytest.approx(first[0][0])


def test_target_and_trajectory_refused_with_one_line(tmp_path):
    """--target with --trajectory: exit 2, the error on one line, nothing written."""
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", "fourcable", "--trajectory", "swing", "--target", "0", "0", "1",
                  "--csv", csv)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr == "dynstiff: error: give --target or --trajectory, not both\n"
    assert not csv.exists()
