"""The ``dynstiff workspace`` command (dynstiff/cli/workspace.py): a small CoGiRo map
written to netCDF with its figure and table (run in this process: conftest.run_cli); argument
errors on one line."""

import sys

import numpy as np
import pytest
from conftest import cli_help, inverted_stewart_scene, run_cli

pytest.importorskip("xarray")


def run(*args, cwd):
    return run_cli("workspace", *args, cwd=cwd)


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


def test_workspace_command_maps_the_frequency_optimal_tensions(tmp_path):
    from dynstiff.maps.dataset import open_workspace
    r = run("cogiro", "--box", "4", "4", "-2.5", "-2.5", "1", "1", "--step", "1", "-n", "3",
            "--tensions", "max-frequency", "--out", "map.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    m = open_workspace(tmp_path / "map.nc")
    assert m.attrs["tensions"] == "max-frequency"
    assert float(m["first_platform_hz"].max()) == pytest.approx(2.2204, abs=2e-4)


@pytest.mark.parametrize("args, match", [
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.txt"], "--out"),
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.nc",
      "--parameter", "EA"], "go together"),
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.nc",
      "--workers", "2", "--scheduler", "tcp://x:1"], "not allowed with"),
    (["--step", "1", "--out", "m.nc"], "--box X0 X1 Y0 Y1 Z0 Z1 is needed: scene 'cogiro' "
                                       "has no [workspace] box"),
    (["--box", "-6", "6", "-4", "4", "0", "5", "--step", "0.1", "--out", "m.nc"],
     "gives 499,851 poses, more than max_poses=200,000 (about "),
    (["--box", "-6", "6", "-4", "4", "0", "5", "--step", "0.0005", "--out", "m.nc"],
     "more than 10000: raise step= (--step)"),
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.nc", "-n", "30000"],
     "n_modes must be at most max_modes=2000"),
    (["--box", "0", "1", "0", "1", "1", "2", "--step", "1", "--out", "m.nc",
      "--max-poses", "7"], "gives 8 poses, more than max_poses=7 (about "),
])
def test_bad_workspace_arguments_fail_on_one_line(tmp_path, args, match):
    r = run("cogiro", *args, cwd=tmp_path)
    assert r.returncode == 2 and match in r.stderr and len(r.stderr.splitlines()) == 1


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


def test_an_interrupted_workspace_command_resumes(tmp_path, monkeypatch, capsys):
    """Ctrl-C (planted in the per-pose statics) stops the command with one line, exit 130,
    the completed chunks saved beside --out; a run without --resume is refused; --resume
    writes the map of an uninterrupted run and removes the saved chunks."""
    import dynstiff.maps.workspace as wsmod
    from dynstiff.cli import main
    from dynstiff.maps.dataset import open_workspace
    monkeypatch.chdir(tmp_path)
    args = ["workspace", "cogiro", "--box", "-6", "6", "-4", "4", "1", "1", "--step", "4",
            "-n", "3", "--chunk-size", "4", "--quiet"]
    assert main(args + ["--out", "whole.nc"]) == 0
    statics, calls = wsmod.tension_equilibrium, [0]

    def planted(*a, **kw):
        calls[0] += 1
        if calls[0] > 5:
            raise KeyboardInterrupt
        return statics(*a, **kw)
    monkeypatch.setattr(wsmod, "tension_equilibrium", planted)
    capsys.readouterr()
    assert main(args + ["--out", "m.nc"]) == 130
    err = capsys.readouterr().err.strip()
    assert err == ("dynstiff: workspace interrupted: 4 of 12 poses saved in m.nc.parts; run "
                   "again with resume=True (dynstiff workspace --resume) to continue")
    assert not (tmp_path / "m.nc").exists() and (tmp_path / "m.nc.parts").is_dir()
    monkeypatch.undo()
    monkeypatch.chdir(tmp_path)
    assert main(args + ["--out", "m.nc"]) == 2
    assert "holds a run already: give resume=True (--resume)" in capsys.readouterr().err
    assert main(args + ["--out", "m.nc", "--resume"]) == 0
    assert not (tmp_path / "m.nc.parts").exists()
    a, b = open_workspace(tmp_path / "m.nc"), open_workspace(tmp_path / "whole.nc")
    for name in a.data_vars:
        if a[name].dtype == object:                    # the reasons
            assert a[name].values.tolist() == b[name].values.tolist(), name
        else:
            assert a[name].values.tobytes() == b[name].values.tobytes(), name


def test_a_users_folder_at_the_checkpoint_path_is_refused_before_work(tmp_path, capsys):
    """OUT.parts is where the command saves its chunks and what it removes at the end: a
    folder of the user's there is refused (one line, exit 2) and left as it was."""
    from dynstiff.cli import main
    user = tmp_path / "m.nc.parts"
    user.mkdir()
    (user / "scene.toml").write_text("mine")
    args = ["workspace", "cogiro", "--box", "-6", "6", "-4", "4", "1", "1", "--step", "4",
            "-n", "3", "--quiet", "--out", str(tmp_path / "m.nc")]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "scene.toml" in err[0] and "m.nc.parts" in err[0]
    assert (user / "scene.toml").read_text() == "mine"
    assert not (tmp_path / "m.nc").exists()


def test_workspace_command_maps_the_uncertain_row_as_check_does(tmp_path, capsys):
    """--uncertain adds the checks' uncertain row to every pose (200 samples, seed 0, as
    `dynstiff check --uncertain`); the CSV holds its probability and verdict."""
    import pandas as pd

    from dynstiff.analyses.checks import design_checks
    from dynstiff.cli import main
    from dynstiff.scenes import load_scene
    args = ["workspace", "cogiro", "--box", "4", "4", "-3", "-3", "1", "1", "--step", "1",
            "-n", "3", "--uncertain", "mass=10%", "--quiet", "--out", str(tmp_path / "m.nc"),
            "--csv", str(tmp_path / "m.csv")]
    assert main(args) == 0
    df = pd.read_csv(tmp_path / "m.csv", comment="#")
    res = design_checks(load_scene("cogiro").robot, [4.0, -3.0, 1.0], band_hz=(0.0, 1.5),
                        uncertain={"mass": "10%"})
    col = "check: platform modes outside band, uncertain"
    assert df[col].tolist() == [res.rows[-1]["verdict"]]
    assert df["probability of a platform mode in the band [-]"].tolist() == [
        pytest.approx(res.rows[-1]["value"], abs=0)]
    assert main(args[:-4] + ["--uncertain", "mass", "--out", str(tmp_path / "n.nc")]) == 2
    assert "--uncertain mass: give NAME=VALUE[%]" in capsys.readouterr().err


def rotated_cogiro(path, rz=0.1):
    """CoGiRo's scene file with its pose turned by ``rz`` [rad] about z."""
    from pathlib import Path

    import dynstiff
    text = (Path(dynstiff.__file__).parent / "scenes" / "cogiro.toml").read_text()
    assert "rotation = [0.0, 0.0, 0.0]" in text
    path.write_text(text.replace("rotation = [0.0, 0.0, 0.0]", f"rotation = [0.0, 0.0, {rz}]"))
    return path


@pytest.mark.parametrize("rows, match", [
    ("# rx ry\n0 0\n", "need 3 numbers a line (rx ry rz [rad]), got shape (1, 2)"),
    ("0 0 x\n", "--orientations r.txt: could not convert"),
])
def test_a_bad_orientations_file_fails_on_one_line_naming_it(tmp_path, rows, match):
    (tmp_path / "r.txt").write_text(rows)
    r = run("cogiro", "--box", "0", "0", "0", "0", "1", "1", "--step", "1", "-n", "3",
            "--orientations", "r.txt", "--out", "m.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 2 and match in r.stderr and len(r.stderr.splitlines()) == 1
    assert r.stderr.count("--orientations r.txt:") == 1
    assert not (tmp_path / "m.nc").exists()


def test_workers_below_one_are_refused_with_the_documented_line(tmp_path):
    r = run("cogiro", "--box", "0", "0", "0", "0", "1", "1", "--step", "1", "-n", "3",
            "--workers", "0", "--out", "m.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 2
    assert r.stderr.strip() == "dynstiff: error: --workers must be >= 1, got 0"


def test_missing_zarr_and_dask_are_named_with_the_install_line(tmp_path, monkeypatch):
    """NAME.zarr is a valid --out, refused (one line) only when the zarr package is missing;
    --scheduler without Dask says how to install it (both imports blocked here)."""
    monkeypatch.setitem(sys.modules, "zarr", None)
    monkeypatch.setitem(sys.modules, "distributed", None)
    base = ["cogiro", "--box", "0", "0", "0", "0", "1", "1", "--step", "1", "-n", "3"]
    r = run(*base, "--out", "m.zarr", cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.strip() == (
        "dynstiff: error: --out m.zarr: Zarr output needs the zarr package (pip install "
        "zarr); or give NAME.nc")
    r = run(*base, "--scheduler", "tcp://127.0.0.1:1", "--out", "m.nc", "--quiet",
            cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.strip() == (
        'dynstiff: error: --scheduler needs Dask: pip install "dynstiff[workspace]"')
    assert not list(tmp_path.iterdir())


def test_the_scenes_rotation_values_band_and_settings_reach_map_and_table(tmp_path):
    """A scene posed with a rotation maps its positions at that rotation; --values of
    --parameter, the scene's model band (its [analysis] band_hz) and --workers 1 (one
    process) reach the map; the JSON table's header records the model, n_modes and step."""
    import json

    from dynstiff.maps.dataset import open_workspace
    scene = rotated_cogiro(tmp_path / "s.toml")
    r = run(str(scene), "--box", "0", "0", "0", "0", "1", "1", "--step", "1", "-n", "3",
            "--parameter", "EA", "--values", "1.5e5", "3e5", "--workers", "1",
            "--out", "m.nc", "--json", "m.json", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    m = open_workspace(tmp_path / "m.nc")
    assert dict(m.sizes)["orientation"] == 1 and dict(m.sizes)["parameter"] == 2
    np.testing.assert_array_equal(m["rotation"].values, [[0.0, 0.0, 0.1]])
    assert m["parameter"].values.tolist() == [1.5e5, 3e5]
    assert m.attrs["model_band_hz"].tolist() == [0.1, 12.0]       # the scene's band_hz
    assert m.attrs["engine"] == "serial" and m.attrs["rung"] == "dsm"
    f1 = m["first_platform_hz"].values.ravel()
    assert f1[1] > f1[0] > 0                                       # stiffer cables, higher
    meta = json.loads((tmp_path / "m.json").read_text())["metadata"]
    assert meta["model"] == "dsm" and meta["n_modes"] == 3 and meta["step [m]"] == 1.0
    assert meta["box"] == [0.0, 0.0, 0.0, 0.0, 1.0, 1.0] and meta["map"] == "m.nc"


def test_an_unrotated_scene_maps_positions_only(tmp_path):
    """CoGiRo's pose has no rotation: the map has no orientation dimension."""
    from dynstiff.maps.dataset import open_workspace
    r = run("cogiro", "--box", "0", "0", "0", "0", "1", "1", "--step", "1", "-n", "3",
            "--out", "m.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    m = open_workspace(tmp_path / "m.nc")
    assert "orientation" not in m.dims and m.attrs["engine"] == "serial"


def test_workers_two_run_on_two_processes(tmp_path):
    from dynstiff.maps.dataset import open_workspace
    r = run("cogiro", "--box", "-1", "1", "0", "0", "1", "1", "--step", "2", "-n", "3",
            "--workers", "2", "--chunk-size", "1", "--out", "m.nc", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert open_workspace(tmp_path / "m.nc").attrs["engine"] == "2 processes"


def test_scheduler_runs_the_scenes_robot_on_a_dask_cluster(tmp_path):
    """--scheduler ADDRESS: the map of the scene's robot computed on that cluster (an
    in-process one here) equals the serial map."""
    distributed = pytest.importorskip("distributed")
    from dynstiff.maps.dataset import open_workspace
    args = ["cogiro", "--box", "-1", "1", "0", "0", "1", "1", "--step", "2", "-n", "3",
            "--quiet"]
    assert run(*args, "--out", "serial.nc", cwd=tmp_path).returncode == 0
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        r = run(*args, "--scheduler", cluster.scheduler_address, "--out", "m.nc",
                cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    a, b = open_workspace(tmp_path / "m.nc"), open_workspace(tmp_path / "serial.nc")
    assert a.attrs["engine"] == "dask" and a.attrs["robot"] == "cogiro"
    np.testing.assert_array_equal(a["first_platform_hz"].values, b["first_platform_hz"].values)


def test_workspace_help(monkeypatch):
    """`dynstiff workspace -h`: the usage line and every option with its metavar, choices,
    default and help; and the command's line in `dynstiff -h`."""
    from dynstiff.cli.options import MEANINGS
    from dynstiff.maps.guards import MAX_POSES
    assert ("workspace map statics, modes and design checks over a box grid of positions "
            "(optionally x orientations x a cable parameter); netCDF output"
            in cli_help(monkeypatch))
    h = cli_help(monkeypatch, "workspace")
    assert h == " ".join((
        "usage: dynstiff workspace [-h] [--box X0 X1 Y0 Y1 Z0 Z1] [--step STEP] "
        "[--orientations FILE] [--parameter {EA,mass_per_length}] [--values V [V ...]] "
        "[-n N] [--max-modes N] [--forbidden-band LO HI] [--margin MARGIN] "
        "[--uncertain NAME=VALUE[%]] [--tensions {default,max-frequency}] "
        "[--chunk-size CHUNK_SIZE] [--workers WORKERS | --scheduler ADDRESS] --out FILE "
        "[--csv FILE] [--json FILE] [--plot FILE] [--quiet] [--resume] "
        "[--max-poses MAX_POSES] scene",
        f"positional arguments: scene {MEANINGS['scene']}",
        "options: -h, --help show this help message and exit",
        "--box X0 X1 Y0 Y1 Z0 Z1 grid box [m] (default: the scene's [workspace] box, e.g. a "
        "CASPR joint's q_min / q_max)",
        "--step STEP grid spacing [m] (default: a quarter of the box's longest side)",
        "--orientations FILE rotation vectors rx ry rz [rad], one a line ('#' comments), "
        "crossed with the positions (default: the scene's rotation)",
        f"--parameter {{EA,mass_per_length}} {MEANINGS['--parameter']}: set on every cable, "
        "crossed with the poses: EA (axial stiffness of every cable [N]), mass_per_length "
        "(mass per unstretched length of every cable [kg/m])",
        "--values V [V ...] values of --parameter, in its unit",
        f"-n N, --n-modes N {MEANINGS['--n-modes']}: per pose (default: the scene's n_modes)",
        f"--max-modes N {MEANINGS['--max-modes']}: beyond it the search stops with an error "
        "or an 'unknown' verdict (default 2000)",
        f"--forbidden-band LO HI {MEANINGS['--forbidden-band']}: no platform mode may lie in "
        "it (default: the scene's forbidden_band_hz)",
        f"--margin MARGIN {MEANINGS['--margin']} (default: the scene's, else 0.05)",
        f"--uncertain NAME=VALUE[%] {MEANINGS['--uncertain']}: EA=10% is a standard deviation "
        "of 10 %, EA=10%:uniform +-10 %, mass=2 absolute; adds the probability that a "
        "platform mode enters the band and the margin at 95 % confidence (Monte Carlo, 200 "
        "samples)",
        "--tensions {default,max-frequency} tension distribution at every pose: the default "
        "(closest to t_min) or the one that maximises the first platform mode",
        "--chunk-size CHUNK_SIZE poses per task, warm-started along it (default 25)",
        "--workers WORKERS local worker processes",
        "--scheduler ADDRESS Dask scheduler address, e.g. tcp://10.0.0.5:8786",
        f"--out FILE {MEANINGS['--out']}: the map file, NAME.nc (netCDF) or NAME.zarr "
        "(Zarr folder)",
        f"--csv FILE {MEANINGS['--csv']}: one row per pose ('-': standard output)",
        f"--json FILE {MEANINGS['--json']}: one row per pose ('-': standard output)",
        f"--plot FILE {MEANINGS['--plot']}: the slices of the map (PNG, PDF, SVG, ...)",
        f"--quiet {MEANINGS['--quiet']}: nor the first-run notice (bars are off too when "
        "standard error is not a terminal)",
        "--resume continue an interrupted run (its chunks are saved in OUT.parts)",
        f"--max-poses MAX_POSES refuse a map of more poses (default {MAX_POSES})"))
