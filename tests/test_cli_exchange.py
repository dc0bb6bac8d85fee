"""The subcommands of dynstiff/cli/exchange.py, run in this process (conftest.run_cli):
import-caspr writes a scene that loads and equals the built-in CoGiRo; bad files fail in one
line."""

from pathlib import Path

import numpy as np
import pytest
from conftest import run_cli

import dynstiff as ds

DATA = Path(__file__).parent / "data" / "caspr"


def test_import_caspr_writes_a_loadable_commented_scene(tmp_path):
    ref = ds.load_scene("cogiro").robot
    path = tmp_path / "cogiro.toml"
    out = run_cli("import-caspr", DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml",
                  "--mass-per-length", 0.064, "--EA", 139486.7, "--out", path)
    assert out.returncode == 0, out.stderr
    assert "warning: " in out.stderr and "products of inertia" in out.stderr
    assert "8 cables" in out.stdout
    text = path.read_text()
    assert text.startswith("# CoGiRo: imported from CASPR") and "inertia_convention" in text
    sc = ds.load_scene(path)
    for f in ("anchors", "attachments"):
        np.testing.assert_array_equal(getattr(sc.robot, f), getattr(ref, f))
    np.testing.assert_array_equal(sc.robot.platform.inertia, ref.platform.inertia)
    assert sc.robot.cables == ref.cables and sc.pose == ds.Pose([0, 0, 2.0])


def test_import_caspr_named_set_to_stdout_and_bad_file():
    out = run_cli("import-caspr", DATA / "IPAnema_1_bodies.xml", DATA / "IPAnema_1_cables.xml",
                  "--mass-per-length", 0.02, "--EA", 2e5, "--cable-set", "IROS_CASPR_2016",
                  "--out", "-")
    assert out.returncode == 0, out.stderr
    assert "anchor = [-2.0, 3.0, 5.0]" in out.stdout and "max = 200.0" in out.stdout
    out = run_cli("import-caspr", DATA / "CoGiRo_cables.xml", DATA / "CoGiRo_cables.xml",
                  "--mass-per-length", 0.064, "--EA", 1e5, "--out", "-")
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and "root element <cables>" in out.stderr


def test_import_caspr_reads_the_trajectories_and_bounds_beside_the_bodies(tmp_path):
    """InvertedStewart_*.xml (a test robot in CASPR's format): the trajectories and
    operational-space files beside the bodies file are read by default; the scene holds
    the trajectories and the joint's bounds as [workspace] box; kinds not read are said."""
    path = tmp_path / "inv.toml"
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml",
                  DATA / "InvertedStewart_cables.xml", "--mass-per-length", 0.01, "--EA", 1e5,
                  "--out", path)
    assert out.returncode == 0, out.stderr
    assert "6 cables" in out.stdout and "workspace box (q_min, q_max): [-1.0, 1.0" in out.stdout
    assert "lift_and_turn (quintic, 3 waypoints, 4 s)" in out.stdout
    assert "trajectory 'recorded' not read: samples in the file 'recorded.traj'" in out.stdout
    assert "operational spaces from" in out.stdout and "tool (1 marker)" in out.stdout
    sc = ds.load_scene(path)
    assert list(sc.trajectories) == ["lift_and_turn", "square", "swing", "mean_speed", "blend"]
    assert sc.workspace_box == (-1.0, 1.0, -1.0, 1.0, 0.5, 2.5)
    assert "# operational set 'tool': position of the point [0.0, 0.0, -0.2] m" in \
        path.read_text()
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml",
                  DATA / "InvertedStewart_cables.xml", "--mass-per-length", 0.01, "--EA", 1e5,
                  "--no-siblings", "--out", path)
    assert out.returncode == 0 and "trajectories" not in out.stdout
    assert ds.load_scene(path).trajectories == {}


def test_import_caspr_never_writes_over_an_input(tmp_path):
    cables = tmp_path / "c.xml"
    cables.write_text((DATA / "InvertedStewart_cables.xml").read_text())
    before = cables.read_text()
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml", cables,
                  "--mass-per-length", 0.01, "--EA", 1e5, "--out", cables)
    assert out.returncode == 2 and "is the same file as cables" in out.stderr
    assert cables.read_text() == before


def test_frf_uff_writes_records_that_pyuff_reads(tmp_path):
    pyuff = pytest.importorskip("pyuff")
    path = tmp_path / "frf.uff"
    out = run_cli("frf", "cogiro", "--load", "fz", "mx", "--response", "z", "--band", 0.5, 4,
                  "--points", 20, "--kind", "accelerance", "--uff", path)
    assert out.returncode == 0, out.stderr
    assert f"wrote {path}" in out.stdout
    sets = pyuff.UFF(str(path)).read_sets()
    assert len(sets) == 2 and {s["ref_dir"] for s in sets} == {3, 4}
    assert all(s["ordinate_spec_data_type"] == 12 for s in sets)
    # the command's model is the scene's, damped as its settings say; its grid holds the 20
    # uniform points and is refined at every mode (theory.md §12): compare at the uniform ones
    from dynstiff.analyses.settings import analysis_settings
    sc = ds.load_scene("cogiro")
    model = analysis_settings(sc).model(sc.equilibrium())
    f = np.linspace(0.5, 4, 20)
    x = np.asarray(sets[0]["x"])
    idx = [int(np.argmin(np.abs(x - fk))) for fk in f]
    np.testing.assert_allclose(x[idx], f, rtol=5e-6)                  # 6 digits in ASCII
    res = ds.frf(model, 2 * np.pi * f, inputs="fz", outputs="z", kind="accelerance")
    np.testing.assert_allclose(np.asarray(sets[0]["data"])[idx], res.H[:, 0, 0], rtol=1e-11)


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


def test_a_caspr_name_with_line_breaks_cannot_set_keys_of_the_written_scene(tmp_path):
    """A CASPR robot name holding "&#10;" (line breaks) and TOML reaches the scene's header
    comment as comment lines: the written scene has no [workspace] box from the name, and
    the pose of the file."""
    bodies = (DATA / "CoGiRo_bodies.xml").read_text(encoding="utf-8").replace(
        'name="CoGiRo"', 'name="CoGiRo&#10;[workspace]&#10;box = [0.0, 1.0, 0.0, 1.0, 0.0, '
        '1.0]&#10;#"')
    (tmp_path / "b.xml").write_text(bodies, encoding="utf-8")
    out = run_cli("import-caspr", tmp_path / "b.xml", DATA / "CoGiRo_cables.xml",
                  "--mass-per-length", 0.064, "--EA", 139486.7, "--out", tmp_path / "s.toml")
    assert out.returncode == 0, out.stderr
    back = ds.load_scene(tmp_path / "s.toml")
    assert back.workspace_box is None
    np.testing.assert_array_equal(back.pose.position, [0.0, 0.0, 2.0])
    assert "# CoGiRo\n# [workspace]\n# box = " in (tmp_path / "s.toml").read_text(
        encoding="utf-8")
