"""The ``dynstiff workspace`` command (dynstiff/cli/workspace.py): a small CoGiRo map
written to netCDF with its figure and table, in a subprocess; argument errors on one line."""

import subprocess
import sys

import numpy as np
import pytest
from conftest import inverted_stewart_scene

pytest.importorskip("xarray")


def run(*args, cwd):
    return subprocess.run([sys.executable, "-m", "dynstiff", "workspace", *args], check=False,
                          cwd=cwd, capture_output=True, text=True, timeout=600)


@pytest.mark.integration
def test_workspace_command_writes_map_figure_and_table(tmp_path):
    from dynstiff.maps.dataset import open_workspace
    (tmp_path / "rot.txt").write_text("# rx ry rz\n0 0 0\n0 0 0.1\n")
    r = run("cogiro", "--box", "-6", "6", "0", "0", "1", "1", "--step", "6",
            "--orientations", "rot.txt", "-n", "3", "--out", "map.nc", "--plot", "map.png",
            "--csv", "map.csv", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "6 poses" in r.stdout and "wrote map.nc" in r.stdout
    m = open_workspace(tmp_path / "map.nc")
    assert dict(m.sizes)["x"] == 3 and dict(m.sizes)["orientation"] == 2
    np.testing.assert_allclose(m["rotation"].values[1], [0, 0, 0.1])
    assert m.attrs["band_hz"].tolist() == [0.0, 1.5]          # the scene's forbidden band
    assert (tmp_path / "map.png").stat().st_size > 10_000
    import pandas as pd
    df = pd.read_csv(tmp_path / "map.csv", comment="#")      # the one metadata header
    assert len(df) == 6 and {"x [m]", "first platform freq [Hz]", "band margin [-]",
                             "least tension [N]"} <= set(df.columns)
    head = [ln for ln in (tmp_path / "map.csv").read_text().splitlines() if ln[:1] == "#"]
    assert [ln.split(":")[0] for ln in head[:5]] == ["# dynstiff", "# scene", "# pose",
                                                     "# model", "# date"]


@pytest.mark.integration
def test_workspace_command_maps_the_frequency_optimal_tensions(tmp_path):
    from dynstiff.maps.dataset import open_workspace
    r = run("cogiro", "--box", "4", "4", "-2.5", "-2.5", "1", "1", "--step", "1", "-n", "3",
            "--tensions", "max-frequency", "--out", "map.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    m = open_workspace(tmp_path / "map.nc")
    assert m.attrs["tensions"] == "max-frequency"
    assert float(m["first_platform_hz"].max()) == pytest.approx(2.2204, abs=2e-4)


@pytest.mark.integration
@pytest.mark.parametrize("args, match", [
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.txt"], "--out"),
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.nc",
      "--parameter", "EA"], "go together"),
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.nc",
      "--workers", "2", "--scheduler", "tcp://x:1"], "not allowed with"),
    (["--step", "1", "--out", "m.nc"], "--box X0 X1 Y0 Y1 Z0 Z1 is needed: scene 'cogiro' "
                                       "has no [workspace] box"),
])
def test_bad_workspace_arguments_fail_on_one_line(tmp_path, args, match):
    r = run("cogiro", *args, cwd=tmp_path)
    assert r.returncode == 2 and match in r.stderr and len(r.stderr.splitlines()) == 1


@pytest.mark.integration
def test_workspace_box_defaults_to_the_scenes(tmp_path):
    """A scene imported from CASPR carries its joint's q_min / q_max as [workspace] box
    (x, y in [-1, 1], z in [0.5, 2.5] m): with a 2 m step, the map's 8 corners."""
    from dynstiff.maps.dataset import open_workspace
    scene = inverted_stewart_scene(tmp_path / "s.toml")
    r = run(str(scene), "--step", "2", "-n", "3", "--out", "m.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    m = open_workspace(tmp_path / "m.nc")
    assert m["x"].values.tolist() == [-1.0, 1.0] and m["z"].values.tolist() == [0.5, 2.5]
    assert int(m["feasible"].sum()) == 8
