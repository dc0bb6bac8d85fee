"""The `dynstiff` command line, run in this process (conftest.run_cli): the sweep commands
(dynstiff/cli/sweep.py)."""

import numpy as np
import pytest
from conftest import inverted_stewart_scene, run_cli

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
