"""The calibrate command of dynstiff/cli/exchange.py, run in this process
(conftest.run_cli): EA fitted to a measured table, and with a fake fit, the options it
passes on, its report, tables and progress."""

import numpy as np
import pytest
from conftest import run_cli

import dynstiff as ds


def test_calibrate_fits_EA_to_a_measured_table(tmp_path):
    """Frequencies of CoGiRo at 60 GPa (first 3 platform modes, the closed-form model,
    rounded to 4 digits as a measurement would print them): EA = 60 GPa x 8.2051e-6 m^2
    lies in the interval reported."""
    table = tmp_path / "measured.csv"
    table.write_text("freq [Hz]\n4.1965\n4.6405\n5.9685\n")
    out_csv = tmp_path / "residuals.csv"
    out = run_cli("calibrate", "cogiro", "--measured", table, "--parameter", "EA",
                  "--csv", out_csv)
    assert out.returncode == 0, out.stderr
    line = next(ln for ln in out.stdout.splitlines() if ln.startswith("EA"))
    _, initial, est, lo, hi = line.split()
    assert float(initial) == pytest.approx(139486.7, rel=1e-5)     # printed to 6 digits
    assert float(lo) < 60e9 * 8.2051e-6 < float(hi)
    import pandas as pd
    df = pd.read_csv(out_csv, comment="#")
    assert np.all(np.abs(df["residual [-]"]) < 1e-4)
    out = run_cli("calibrate", "cogiro", "--measured", table, "--parameter", "stiffness")
    assert out.returncode == 2 and "'stiffness' is not one of" in out.stderr


# ---------------------------------------------------------------------------- calibrate
class _FakeFit:
    """What calibrate returns, without the fit."""
    n_evaluations = 7

    def text(self):
        return "EA fitted\n"

    def to_frame(self):
        import pandas as pd
        return pd.DataFrame({"mode": [1, 2], "residual [-]": [0.25, -0.5]})

    def plot(self):
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(2, 2))
        ax.plot([0, 1], [0, 1])
        return fig


@pytest.fixture
def fake_calibrate(monkeypatch):
    """calibrate() replaced by a spy: its calls (args, kwargs) in a list."""
    import dynstiff.analyses.calibrate as cal
    calls = []

    def spy(*a, **kw):
        calls.append((a, kw))
        return _FakeFit()
    monkeypatch.setattr(cal, "calibrate", spy)
    return calls


def _measured(tmp_path):
    table = tmp_path / "measured.csv"
    table.write_text("freq [Hz]\n1.5\n2.5\n")
    return table


def test_calibrate_passes_its_options_to_the_fit(tmp_path, fake_calibrate):
    """The parameters, the pose of --pose, the model, confidence and max modes reach
    calibrate(); their defaults are the scene's pose (None), dsm, 0.95 and 2000."""
    table = _measured(tmp_path)
    out = run_cli("calibrate", "planar2", "--measured", table, "--parameter", "EA")
    assert out.returncode == 0, out.stderr
    (a, kw), = fake_calibrate
    assert a[0].name == "planar2" and len(a[1]) == 2
    assert kw == dict(parameters=("EA",), pose=None, rung="dsm", confidence=0.95,
                      max_modes=2000)
    out = run_cli("calibrate", "planar2", "--measured", table, "--parameter", "EA",
                  "--parameter", "mass", "--pose", 0.1, 0.0, 1.2, "--model", "spring",
                  "--confidence", 0.9, "--max-modes", 50)
    assert out.returncode == 0, out.stderr
    kw = fake_calibrate[-1][1]
    assert kw == dict(parameters=("EA", "mass"), pose=ds.Pose([0.1, 0.0, 1.2]),
                      rung="spring", confidence=0.9, max_modes=50)


def test_calibrate_prints_its_report_and_the_files_written(tmp_path, fake_calibrate):
    """The report: scene, number of measured modes, model, evaluations, the result's text,
    then one 'wrote' line per file (no line for an option not given)."""
    table = _measured(tmp_path)
    csv, plot = tmp_path / "r.csv", tmp_path / "r.png"
    out = run_cli("calibrate", "planar2", "--measured", table, "--parameter", "EA",
                  "--model", "spring", "--csv", csv, "--plot", plot)
    assert out.returncode == 0, out.stderr
    assert out.stdout == (f"planar2: 2 measured modes, spring model, "
                          f"{_FakeFit.n_evaluations} evaluations\n" + _FakeFit().text()
                          + f"wrote {csv}\nwrote {plot}\n")
    assert plot.read_bytes().startswith(b"\x89PNG")
    out = run_cli("calibrate", "planar2", "--measured", table, "--parameter", "EA")
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [
        f"planar2: 2 measured modes, dsm model, {_FakeFit.n_evaluations} evaluations",
        "EA fitted"]


def test_calibrate_table_to_stdout_and_its_header(tmp_path, fake_calibrate):
    """--csv -: standard output holds the table alone, its header naming the scene, the
    pose of --pose, the model, the measured file, the parameters and the confidence; the
    report goes to standard error with no 'wrote' line."""
    import io
    import json

    import pandas as pd
    table = _measured(tmp_path)
    out = run_cli("calibrate", "planar2", "--measured", table, "--parameter", "EA",
                  "--parameter", "t_min", "--pose", 0.1, 0.0, 1.2, "--confidence", 0.8,
                  "--csv", "-")
    assert out.returncode == 0, out.stderr
    assert out.stderr == (f"planar2: 2 measured modes, dsm model, "
                          f"{_FakeFit.n_evaluations} evaluations\n" + _FakeFit().text())
    head = {k: json.loads(v) for k, v in (ln[2:].split(": ", 1) for ln in
                                          out.stdout.splitlines() if ln.startswith("# "))}
    assert head["scene"] == "planar2" and head["model"] == "dsm"
    assert head["pose"] == {"position [m]": [0.1, 0.0, 1.2], "rotation [rad]": [0.0, 0.0, 0.0]}
    assert head["measured"] == str(table)
    assert head["parameters"] == ["EA", "t_min"] and head["confidence"] == 0.8
    df = pd.read_csv(io.StringIO(out.stdout), comment="#")
    pd.testing.assert_frame_equal(df, _FakeFit().to_frame())


def test_calibrate_table_header_has_the_scene_pose_by_default(tmp_path, fake_calibrate):
    """Without --pose, the JSON table's header holds the scene's own pose."""
    import json
    table = _measured(tmp_path)
    path = tmp_path / "r.json"
    out = run_cli("calibrate", "planar2", "--measured", table, "--parameter", "EA",
                  "--json", path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-1] == f"wrote {path}"
    pose = ds.load_scene("planar2").pose
    meta = json.loads(path.read_text())["metadata"]
    assert meta["pose"] == {"position [m]": pose.position.tolist(),
                            "rotation [rad]": pose.rotation.tolist()}
    assert meta["measured"] == str(table) and meta["confidence"] == 0.95


@pytest.mark.parametrize("quiet", [False, True])
def test_calibrate_progress_follows_quiet(tmp_path, fake_calibrate, monkeypatch, quiet):
    """The elapsed-time bar of the fit is labelled 'calibrate SCENE' and is off with
    --quiet."""
    import contextlib

    import dynstiff.cli.console as console
    seen = []

    def spy(label, q=False):
        seen.append((label, q))
        return contextlib.nullcontext()
    monkeypatch.setattr(console, "elapsed", spy)
    out = run_cli("calibrate", "planar2", "--measured", _measured(tmp_path), "--parameter",
                  "EA", *(["--quiet"] if quiet else []))
    assert out.returncode == 0, out.stderr
    assert seen == [("calibrate planar2", quiet)]
