"""The import-caspr command of dynstiff/cli/exchange.py, run in this process
(conftest.run_cli): it writes a scene that loads and equals the built-in CoGiRo, reports
what it read and passes its options to the library; bad files fail in one line. Also `frf
--uff`, whose records pyuff reads."""

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


@pytest.mark.parametrize("missing", ["--mass-per-length", "--EA", "--out"])
def test_import_caspr_refuses_a_missing_required_option(tmp_path, missing):
    """Without --mass-per-length, --EA or --out, import-caspr stops with exit 2 and one
    line naming the option; nothing is written."""
    given = {"--mass-per-length": "0.01", "--EA": "1e5", "--out": str(tmp_path / "s.toml")}
    rest = [x for k, v in given.items() if k != missing for x in (k, v)]
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml",
                  DATA / "InvertedStewart_cables.xml", *rest)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr == ("dynstiff: error: dynstiff import-caspr: the following arguments are "
                          f"required: {missing} (dynstiff -h, or dynstiff COMMAND -h)\n")
    assert list(tmp_path.iterdir()) == []


# ----------------------------------------------------------------------- import-caspr
def _inverted_stewart_scene(**kw):
    """The library's import of InvertedStewart_*.xml with its two sibling files."""
    from dynstiff.scenes.caspr import import_caspr
    return import_caspr(DATA / "InvertedStewart_bodies.xml",
                        DATA / "InvertedStewart_cables.xml", ds.Cable(0.01, 1e5),
                        trajectories_xml=DATA / "InvertedStewart_trajectories.xml",
                        operational_spaces_xml=DATA / "InvertedStewart_operational_spaces.xml",
                        **kw)


def _summary(scene, convention="products"):
    r = scene.robot
    return (f"{scene.name}: {r.n_cables} cables, platform {r.platform.mass:g} kg, free "
            f"{' '.join(r.platform.free_dofs)}, pose {scene.pose.position.tolist()} m, "
            f"tensions {r.tension_limits[0]:g}-{r.tension_limits[1]:g} N, inertia convention "
            f"{convention!r}")


def test_import_caspr_prints_each_line_of_its_summary(tmp_path):
    """The report of an import with both sibling files, line by line: the robot (name,
    cables, mass, free DOFs, pose, tensions, convention), the workspace box, the
    trajectories read and those not read, the operational sets, the file written."""
    sc = _inverted_stewart_scene()
    traj = DATA / "InvertedStewart_trajectories.xml"
    ops = DATA / "InvertedStewart_operational_spaces.xml"
    path = tmp_path / "inv.toml"
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml",
                  DATA / "InvertedStewart_cables.xml", "--mass-per-length", 0.01, "--EA", 1e5,
                  "--out", path)
    assert out.returncode == 0 and out.stderr == ""
    sets = sc.study["caspr_operational_sets"]
    assert [len(v) for v in sets.values()] == [1, 1]
    expected = [
        _summary(sc),
        f"workspace box (q_min, q_max): {list(sc.workspace_box)} m",
        f"trajectories from {traj}: " + ", ".join(
            f"{k} ({p.law}, {p.times.size} waypoints, {p.duration:g} s)"
            for k, p in sc.trajectories.items()),
        *[f"trajectory {tid!r} not read: {why}"
          for tid, why in sc.study["caspr_skipped_trajectories"]],
        f"operational spaces from {ops}: "
        + ", ".join(f"{k} (1 marker)" for k in sets) + " (markers, no bounds)",
        f"wrote {path}",
    ]
    assert out.stdout.splitlines() == expected
    assert len(sc.study["caspr_skipped_trajectories"]) == 2
    assert "free x y z rx ry rz, pose [0.0, 0.0, 1.5] m" in expected[0]


def test_import_caspr_writes_the_scene_of_the_library_import(tmp_path):
    """The file written is the library's scene as scene_text writes it: the pose, the
    header comments naming the four files read, the CASPR cable names, the trajectories with
    their CASPR kind noted above each, the workspace box."""
    from dynstiff.scenes.caspr import caspr_comments
    from dynstiff.scenes.writer import scene_text
    sc = _inverted_stewart_scene()
    bodies, cables = DATA / "InvertedStewart_bodies.xml", DATA / "InvertedStewart_cables.xml"
    traj = DATA / "InvertedStewart_trajectories.xml"
    ops = DATA / "InvertedStewart_operational_spaces.xml"
    path = tmp_path / "inv.toml"
    out = run_cli("import-caspr", bodies, cables, "--mass-per-length", 0.01, "--EA", 1e5,
                  "--out", path)
    assert out.returncode == 0, out.stderr
    kinds = sc.study["caspr_trajectory_kinds"]
    text = path.read_text()
    assert text == scene_text(
        sc.robot, sc.pose, name=sc.name, description=sc.description,
        comments=caspr_comments(sc, str(bodies), str(cables), traj, ops),
        cable_names=[f"CASPR {n!r}" for n in sc.study["caspr_cable_names"]],
        trajectories=sc.trajectories.values(), workspace_box=sc.workspace_box,
        trajectory_notes={k: f"CASPR {v}" for k, v in kinds.items()})
    lines = text.splitlines()
    assert lines[1:5] == [f"# bodies: {bodies}", f"# cables: {cables}",
                          f"# trajectories: {traj}", f"# operational spaces: {ops}"]
    for name, kind in kinds.items():
        i = lines.index(f'name = "{name}"')
        assert lines[i - 1].startswith("[[trajectories]]")
        assert lines[i - 1].endswith(f"# CASPR {kind}")
    back = ds.load_scene(path)
    assert back.pose == sc.pose and back.workspace_box == sc.workspace_box
    assert "[pose]" in lines and "[workspace]" in lines


def test_import_caspr_passes_its_options_to_the_library(tmp_path, monkeypatch):
    """--cable-set, --inertia-convention, --min-tension, --name and the explicit
    --trajectories / --operational-spaces reach import_caspr with the cable of
    --mass-per-length / --EA; their defaults are None, 'products', 1.0, None."""
    import dynstiff.scenes.caspr as caspr
    real, calls = caspr.import_caspr, []

    def spy(*a, **kw):
        calls.append((a, kw))
        return real(*a, **kw)
    monkeypatch.setattr(caspr, "import_caspr", spy)
    bodies, cables = DATA / "InvertedStewart_bodies.xml", DATA / "InvertedStewart_cables.xml"
    traj = DATA / "InvertedStewart_trajectories.xml"
    ops = DATA / "InvertedStewart_operational_spaces.xml"
    out = run_cli("import-caspr", bodies, cables, "--mass-per-length", 0.02, "--EA", 3e5,
                  "--no-siblings", "--out", tmp_path / "a.toml")
    assert out.returncode == 0, out.stderr
    assert calls[-1] == ((str(bodies), str(cables), ds.Cable(0.02, 3e5)), dict(
        cable_set=None, inertia_convention="products", name=None, min_tension=1.0,
        trajectories_xml=None, operational_spaces_xml=None))
    path = tmp_path / "b.toml"
    out = run_cli("import-caspr", bodies, cables, "--mass-per-length", 0.02, "--EA", 3e5,
                  "--cable-set", "octahedron", "--inertia-convention", "products",
                  "--min-tension", 2.5, "--name", "my crane", "--no-siblings",
                  "--trajectories", traj, "--operational-spaces", ops, "--out", path)
    assert out.returncode == 0, out.stderr
    assert calls[-1][1] == dict(cable_set="octahedron", inertia_convention="products",
                                name="my crane", min_tension=2.5, trajectories_xml=str(traj),
                                operational_spaces_xml=str(ops))
    assert out.stdout.startswith("my crane: 6 cables, ")
    assert ds.load_scene(path).name == "my crane"
    assert path.read_text().startswith("# my crane: imported from CASPR\n")
    out = run_cli("import-caspr", bodies, cables, "--mass-per-length", 0.02, "--EA", 3e5,
                  "--inertia-convention", "tensor", "--no-siblings", "--out", path)
    assert out.returncode == 0, out.stderr
    assert calls[-1][1]["inertia_convention"] == "tensor"
    assert out.stdout.splitlines()[0].endswith(", inertia convention 'tensor'")


def test_import_caspr_without_sibling_files_says_nothing_of_them(tmp_path):
    """--no-siblings: no trajectories nor operational spaces are read; the report is the
    robot's line and the file written, and the scene has no trajectory."""
    from dynstiff.scenes.caspr import import_caspr
    bodies, cables = DATA / "InvertedStewart_bodies.xml", DATA / "InvertedStewart_cables.xml"
    sc = import_caspr(bodies, cables, ds.Cable(0.01, 1e5))
    path = tmp_path / "s.toml"
    out = run_cli("import-caspr", bodies, cables, "--mass-per-length", 0.01, "--EA", 1e5,
                  "--no-siblings", "--out", path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [
        _summary(sc), f"workspace box (q_min, q_max): {list(sc.workspace_box)} m",
        f"wrote {path}"]
    assert "[[trajectories]]" not in path.read_text()


def test_import_caspr_reports_files_that_hold_no_trajectory_and_no_set(tmp_path):
    """A trajectories file holding only a trajectory it cannot read and an operational-space
    file with no set: the report says 'none' and 'no operational set'."""
    traj, ops = tmp_path / "t.xml", tmp_path / "o.xml"
    traj.write_text('<trajectories><joint_trajectories><file_trajectory id="rec" '
                    'filename="rec.traj"/></joint_trajectories></trajectories>\n')
    ops.write_text("<operational_spaces></operational_spaces>\n")
    path = tmp_path / "s.toml"
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml",
                  DATA / "InvertedStewart_cables.xml", "--mass-per-length", 0.01, "--EA", 1e5,
                  "--trajectories", traj, "--operational-spaces", ops, "--out", path)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[2:] == [f"trajectories from {traj}: none",
                         "trajectory 'rec' not read: samples in the file 'rec.traj', not read",
                         f"operational spaces from {ops}: no operational set (markers, no "
                         "bounds)",
                         f"wrote {path}"]


def test_import_caspr_counts_markers_of_a_set(tmp_path):
    """A set of two markers is reported as '2 markers', one of one as '1 marker'."""
    ops = tmp_path / "o.xml"
    one = ('<{k} marker_id="{i}" name="m{i}"><link>1</link><offset>0 0 -0.{i}</offset>'
           '<axes active_axes="xyz"/></{k}>')
    ops.write_text('<operational_spaces><operational_set id="pair">'
                   + one.format(k="position", i=1) + one.format(k="position", i=2)
                   + '</operational_set><operational_set id="single">'
                   + one.format(k="position", i=3) + "</operational_set></operational_spaces>")
    out = run_cli("import-caspr", DATA / "InvertedStewart_bodies.xml",
                  DATA / "InvertedStewart_cables.xml", "--mass-per-length", 0.01, "--EA", 1e5,
                  "--operational-spaces", ops, "--out", tmp_path / "s.toml")
    assert out.returncode == 0, out.stderr
    assert (f"operational spaces from {ops}: pair (2 markers), single (1 marker) (markers, "
            "no bounds)") in out.stdout.splitlines()


def test_import_caspr_to_stdout_reports_on_stderr():
    """--out -: the scene text is the only thing on standard output; the report goes to
    standard error, after the convention warning, and names no file written."""
    from dynstiff.scenes.caspr import import_caspr
    bodies, cables = DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml"
    with pytest.warns(Warning) as caught:
        sc = import_caspr(bodies, cables, ds.Cable(0.064, 139486.7))
    out = run_cli("import-caspr", bodies, cables, "--mass-per-length", 0.064, "--EA", 139486.7,
                  "--out", "-")
    assert out.returncode == 0
    assert out.stdout.startswith("# CoGiRo: imported from CASPR\n")
    assert out.stderr.splitlines() == [
        *[f"dynstiff: warning: {w.message}" for w in caught], _summary(sc)]
    assert len(caught) == 1
