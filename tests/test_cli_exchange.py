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


# ------------------------------------------------------------------ the parsers' options
def _subparsers():
    import argparse

    from dynstiff.cli import build_parser
    return next(a for a in build_parser()._actions
                if isinstance(a, argparse._SubParsersAction))


def _options(command):
    """{dest: (flags, metavar, required, default, type, choices, nargs, help as printed)}
    of ``dynstiff COMMAND``."""
    import argparse
    fmt = argparse.HelpFormatter("x")
    return {a.dest: (tuple(a.option_strings), a.metavar, a.required, a.default, a.type,
                     a.choices, a.nargs, fmt._expand_help(a))
            for a in _subparsers().choices[command]._actions if a.dest != "help"}


def test_the_commands_are_listed_with_their_help():
    """`dynstiff -h` lists import-caspr and calibrate under these names, each with its
    one-line help."""
    sub = _subparsers()
    helps = {a.dest: a.help for a in sub._choices_actions}
    assert helps["import-caspr"] == ("write a scene file from CASPR's XML model files "
                                     "(single rigid body)")
    assert helps["calibrate"] == ("fit EA, platform mass ... to measured natural frequencies; "
                                  "estimates with confidence intervals")


def test_import_caspr_options_and_their_help():
    """Every option of `dynstiff import-caspr`: its flag, metavar, whether it is required,
    default, type, choices and the help a user reads."""
    from dynstiff.cli.options import MEANINGS, PARAMETERS
    beside = "(default: the file beside BODIES, if any)"
    assert _options("import-caspr") == {
        "bodies": ((), None, True, None, None, None, None, "CASPR *_bodies.xml"),
        "cables": ((), None, True, None, None, None, None, "CASPR *_cables.xml"),
        "mass_per_length": (("--mass-per-length",), None, True, None, float, None, None,
                            f"{PARAMETERS['mass_per_length']} (CASPR holds none)"),
        "EA": (("--EA",), None, True, None, float, None, None,
               f"{PARAMETERS['EA']} (CASPR holds none)"),
        "cable_set": (("--cable-set",), None, False, None, None, None, None,
                      "cable set id (default: the file's default_cable_set)"),
        "inertia_convention": (
            ("--inertia-convention",), None, False, "products", None, ["products", "tensor"],
            None, "printed Ixy, Ixz, Iyz are products of inertia (default; tensor entry = "
                  "-value) or tensor entries (CASPR's code)"),
        "min_tension": (("--min-tension",), None, False, 1.0, float, None, None,
                        "least t_min [N] where CASPR's force_min is lower (default 1.0)"),
        "trajectories": (("--trajectories",), "FILE", False, None, None, None, None,
                         "CASPR *_trajectories.xml: its joint trajectories become the "
                         f"scene's [[trajectories]] {beside}"),
        "operational_spaces": (("--operational-spaces",), "FILE", False, None, None, None,
                               None, "CASPR *_operational_spaces.xml: its markers are listed "
                                     f"in the scene's header {beside}"),
        "no_siblings": (("--no-siblings",), None, False, False, None, None, 0,
                        "do not read the trajectories and operational-space files beside "
                        "BODIES"),
        "name": (("--name",), None, False, None, None, None, None,
                 "scene name (default: the CASPR link's name)"),
        "out": (("--out",), "FILE", True, None, None, None, None,
                MEANINGS["--out"] + ": the scene file ('-': standard output); its cables are "
                                    "numbered from 0, as in every output"),
    }


def test_calibrate_options_and_their_help():
    """Every option of `dynstiff calibrate`: flag, metavar, required, default (dsm model,
    2000 modes at most, 95 % intervals), type and the help a user reads; no --lengths."""
    from dynstiff.cli.options import MEANINGS, MODELS, PARAMETERS
    opts = _options("calibrate")
    assert list(opts) == ["scene", "measured", "parameter", "pose", "model", "max_modes",
                          "confidence", "csv", "json", "plot", "quiet"]
    assert opts["scene"] == ((), None, True, None, None, None, None, MEANINGS["scene"])
    assert opts["measured"] == (("--measured",), "FILE", True, None, None, None, None,
                                "CSV of measured modes: 'freq [Hz]', optional 'sigma [Hz]' "
                                "and shape columns x y z rx ry rz")
    assert opts["parameter"] == (
        ("--parameter",), None, True, None, None, None, None,
        MEANINGS["--parameter"] + ": to fit (repeat for several): "
        f"EA ({PARAMETERS['EA']}), mass ({PARAMETERS['mass']}), t_min ({PARAMETERS['t_min']})"
        ", EA_<i> (cable i's, from 0), EA_* (each cable's), inertia, loss_factor, "
        "viscous_damping (the last two need a 'damping ratio [-]' column and a nonzero value "
        "in the scene)")
    assert opts["pose"] == (("--pose",), "X", False, None, float, None, "+",
                            MEANINGS["--pose"] + ": of the measurement (default: the scene's "
                                                 "pose)")
    assert opts["model"][:7] == (("--model",), None, False, "dsm", None, MODELS, None)
    assert opts["model"][7].startswith(MEANINGS["--model"] + ": ")
    assert opts["model"][7].endswith("; default dsm")
    assert opts["max_modes"][:7] == (("--max-modes",), "N", False, 2000, int, None, None)
    assert opts["max_modes"][7].endswith("(default 2000)")
    assert opts["confidence"] == (("--confidence",), None, False, 0.95, float, None, None,
                                  "level of the intervals (default 0.95)")
    assert opts["csv"] == (("--csv",), "FILE", False, None, None, None, None,
                           MEANINGS["--csv"] + ": the residual of every mode ('-': standard "
                                               "output)")
    assert opts["json"] == (("--json",), "FILE", False, None, None, None, None,
                            MEANINGS["--json"] + ": the residual of every mode ('-': standard "
                                                 "output)")
    assert opts["plot"][:7] == (("--plot",), "FILE", False, None, None, None, None)
    assert opts["plot"][7].startswith(MEANINGS["--plot"] + ": the relative error of every "
                                                           "mode before and after the fit")
    assert opts["quiet"][:4] == (("--quiet",), None, False, False)


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
