"""What the commands share (dynstiff.cli.common): the command line's overrides of a scene's
settings, the equilibrium asked for, and the tables' and figures' writers."""

import json
from argparse import Namespace

import numpy as np
import pandas as pd
import pytest

import dynstiff as ds
from dynstiff.analyses.settings import analysis_settings, scene_equilibrium
from dynstiff.cli import common


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def test_every_override_of_the_command_line_reaches_the_settings(scene):
    """Each option given replaces the scene's value (each differs from it here), by the
    same function the Python API uses; options not given keep the scene's."""
    args = Namespace(band=[0.5, 12.0], fmax=None, forbidden_band=[0.5, 1.8], margin=0.1,
                     participation=0.2, frf_limit=5.0, rtol=0.02, model="lumped",
                     segments=4, n=7, damping=[0.02])
    got = common.scene_settings(scene, args)
    assert got == analysis_settings(
        scene, band_hz=(0.5, 12.0), forbidden_hz=(0.5, 1.8), margin=0.1, participation=0.2,
        frf_limit=5.0, model_rtol=0.02, rung="lumped", segments=4, n_modes=7,
        damping=[0.02])
    own = analysis_settings(scene)
    for name, value in (("band_hz", (0.5, 12.0)), ("forbidden_hz", (0.5, 1.8)),
                        ("margin", 0.1), ("participation", 0.2), ("frf_limit", 5.0),
                        ("model_rtol", 0.02), ("rung", "lumped"), ("segments", 4),
                        ("n_modes", 7)):
        assert getattr(got, name) == value and getattr(own, name) != value, name
    assert got.damping.platform_ratio == 0.02 != own.damping.platform_ratio
    assert common.scene_settings(scene, Namespace()) == own


@pytest.mark.parametrize("fmax, band", [(12.0, (0.1, 12.0)), (0.1, (0.05, 0.1))])
def test_fmax_is_the_top_of_the_band_with_the_scenes_bottom(scene, fmax, band):
    """--fmax F: the band (LO, F) with the scene's LO, or F/2 where LO is not below it."""
    assert scene.band_hz is None or scene.band_hz[0] == 0.1
    got = common.scene_settings(scene, Namespace(fmax=fmax))
    assert got.band_hz == band


def test_the_equilibrium_of_the_pose_or_the_lengths_asked(scene):
    eq = common.equilibrium(scene, Namespace(pose=[1.0, 0.5, 1.2], lengths=None))
    assert eq.pose == ds.Pose([1.0, 0.5, 1.2])
    L0 = eq.unstretched_lengths
    by_lengths = common.equilibrium(scene, Namespace(pose=None, lengths=list(L0)))
    np.testing.assert_allclose(by_lengths.pose.position, [1.0, 0.5, 1.2], atol=1e-6)
    assert common.equilibrium(scene, Namespace()).pose == scene_equilibrium(scene).pose


def test_a_tables_header_comes_first_and_its_date_is_now(tmp_path, capsys):
    """The metadata keys of table_metadata come first in their order, the others after;
    a Pose is written as numbers and the header's own date replaces a stale one; CSV
    starts with `# key: value` lines, JSON is {"metadata", "data"} indented by one;
    standard output ends with a newline."""
    df = pd.DataFrame({"mode": [1, 2], "freq [Hz]": [1.5, 2.5]})
    pose = ds.Pose([1.0, 0.0, 1.0])
    meta = {"band": [0, 2], "model": "dsm", "scene": "cogiro", "pose": pose,
            "date": "1999-01-01"}
    common.write_table(df, tmp_path / "t.csv", "csv", dict(meta))
    lines = (tmp_path / "t.csv").read_text().splitlines()
    keys = [ln[2:].split(":")[0] for ln in lines if ln.startswith("# ")]
    assert keys == ["dynstiff", "scene", "pose", "model", "date", "band"]
    assert json.loads(lines[2].split(": ", 1)[1]) == {"position [m]": [1.0, 0.0, 1.0],
                                                      "rotation [rad]": [0.0, 0.0, 0.0]}
    assert json.loads(lines[3].split(": ", 1)[1]) == "dsm"
    assert not lines[4].endswith('"1999-01-01"')
    back = pd.read_csv(tmp_path / "t.csv", comment="#")
    pd.testing.assert_frame_equal(back, df)
    common.write_table(df, tmp_path / "t.json", "json", dict(meta))
    text = (tmp_path / "t.json").read_text()
    doc = json.loads(text)
    assert text.startswith('{\n "metadata": {\n  "dynstiff": ')
    assert doc["metadata"]["scene"] == "cogiro" and doc["metadata"]["date"] != "1999-01-01"
    assert doc["data"] == [{"mode": 1, "freq [Hz]": 1.5}, {"mode": 2, "freq [Hz]": 2.5}]
    common.write_table(df, tmp_path / "bare.json", "json")
    assert (tmp_path / "bare.json").read_text().startswith('[\n {\n  "mode":1,')
    common.write_table(df, "-", "csv")
    out = capsys.readouterr().out
    assert out == df.to_csv(index=False) and out.endswith("\n") and not out.endswith("\n\n")
    common.write_table(df, "-", "json")
    out = capsys.readouterr().out
    assert out.endswith("]\n") and json.loads(out) == doc["data"]


def test_table_metadata_of_one_pose_or_many():
    pose = ds.Pose([1.0, 2.0, 3.0], [0.0, 0.0, 0.5])
    m = common.table_metadata("cogiro", pose, "exact", band=[0, 1])
    assert list(m) == ["dynstiff", "scene", "pose", "model", "date", "band"]
    assert m["pose"] == {"position [m]": [1.0, 2.0, 3.0], "rotation [rad]": [0.0, 0.0, 0.5]}
    assert common.table_metadata("x", "343 poses", None)["pose"] == "343 poses"
    assert common.table_metadata("x", None, None)["pose"] is None


def test_a_figure_is_saved_laid_out_and_closed(tmp_path):
    """--plot: 120 dpi with the tight bounding box (a 4 x 3 in figure whose text reaches
    out of its frame is not 480 x 360 pixels), and the figure is closed."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.plot([0, 1], [0, 1])
    ax.set_title("a title " * 8)
    common.save_figure(fig, tmp_path / "f.png")
    h, w = mpimg.imread(tmp_path / "f.png").shape[:2]
    assert (w, h) != (480, 360) and w > 480
    assert not plt.fignum_exists(fig.number)


@pytest.mark.parametrize("opt, flag, least", [
    ("points", "--points", 2), ("steps", "--steps", 2), ("segments", "--segments", 1),
    ("n", "-n", 1), ("max_modes", "--max-modes", 1)])
def test_counts_below_their_least_are_refused_by_name(opt, flag, least):
    common.check_outputs(Namespace(**{opt: least}))
    with pytest.raises(ds.InvalidParameterError) as err:
        common.check_outputs(Namespace(**{opt: least - 1}))
    assert str(err.value) == f"{flag} must be >= {least}, got {least - 1}"


@pytest.mark.parametrize("opt", ["fmax", "time", "dt", "speed", "rtol", "proximity", "max_sag",
                                 "participation", "frf_limit"])
@pytest.mark.parametrize("bad", [0.0, -1.0, float("inf"), float("nan")])
def test_positive_options_are_finite_and_positive(opt, bad):
    common.check_outputs(Namespace(**{opt: 1e-9}))
    with pytest.raises(ds.InvalidParameterError) as err:
        common.check_outputs(Namespace(**{opt: bad}))
    assert str(err.value) == f"--{opt.replace('_', '-')} must be finite and > 0, got {bad}"


@pytest.mark.parametrize("opt", ["band", "forbidden_band"])
@pytest.mark.parametrize("bad", [(-1.0, 2.0), (2.0, 2.0), (1.0, float("inf"))])
def test_bands_are_ordered_and_finite(opt, bad):
    common.check_outputs(Namespace(**{opt: (0.0, 2.0)}))
    with pytest.raises(ds.InvalidParameterError) as err:
        common.check_outputs(Namespace(**{opt: bad}))
    assert str(err.value) == (f"--{opt.replace('_', '-')} must be LO HI with 0 <= LO < HI "
                              f"[Hz], got {bad[0]} {bad[1]}")


def test_a_pose_has_three_or_six_numbers():
    common.check_outputs(Namespace(pose=[0.0, 0.0, 1.0]))
    common.check_outputs(Namespace(pose=[0.0] * 6))
    with pytest.raises(ds.InvalidParameterError) as err:
        common.check_outputs(Namespace(pose=[0.0] * 4))
    assert str(err.value) == ("--pose needs 3 numbers (x y z [m]) or 6 (and rx ry rz [rad]), "
                              "got 4: [0.0, 0.0, 0.0, 0.0]")


@pytest.mark.parametrize("opt", ["csv", "json", "plot", "uff"])
def test_output_paths_folder_missing_folder_and_standard_output(opt, tmp_path):
    name = str(tmp_path / "x.png")
    common.check_outputs(Namespace(**{opt: name}))
    with pytest.raises(ds.InvalidParameterError) as err:
        common.check_outputs(Namespace(**{opt: str(tmp_path)}))
    assert str(err.value) == f"--{opt} {tmp_path}: is a folder; give a file name"
    missing = tmp_path / "no" / "x.png"
    with pytest.raises(ds.InvalidParameterError) as err:
        common.check_outputs(Namespace(**{opt: str(missing)}))
    assert str(err.value) == (f"--{opt} {missing}: folder {str(missing.parent)!r} does not "
                              f"exist")
    if opt in ("csv", "json"):                          # standard output
        common.check_outputs(Namespace(**{opt: "-"}))
    elif opt == "plot":                                 # no figure format named "-"
        with pytest.raises(ds.InvalidParameterError, match=r"^--plot -: the file name must"):
            common.check_outputs(Namespace(plot="-"))


def test_file_arguments_name_inputs_and_outputs(tmp_path):
    """Inputs named as the command line spells them (positional names bare, options with
    dashes); a built-in scene name is no file; standard output is no file."""
    scene = tmp_path / "s.toml"
    scene.write_text("")
    args = Namespace(scene=str(scene), bodies="b.xml", cables="c.xml", measured="m.csv",
                     operational_spaces="o.xml", out="o.toml", csv="-", plot="p.png")
    assert common.file_arguments(args) == (
        [("scene", str(scene)), ("--measured", "m.csv"), ("bodies", "b.xml"),
         ("cables", "c.xml"), ("--operational-spaces", "o.xml")],
        [("--out", "o.toml"), ("--plot", "p.png")])
    assert common.file_arguments(Namespace(scene="cogiro")) == ([], [])


def test_an_output_on_an_input_is_refused_before_the_other_checks(tmp_path):
    m = tmp_path / "m.csv"
    m.write_text("")
    from dynstiff.io.files import OutputPathError
    with pytest.raises(OutputPathError, match="--csv .* is the same file as "
                       "--measured"):
        common.check_outputs(Namespace(measured=str(m), csv=str(m), points=0))


def test_fmax_keeps_a_scenes_own_band_bottom(scene):
    from dataclasses import replace
    own = replace(scene, band_hz=(0.3, 5.0))
    assert common.scene_settings(own, Namespace(fmax=12.0)).band_hz == (0.3, 12.0)


def test_a_figure_is_saved_at_120_dpi(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from PIL import Image
    fig, ax = plt.subplots(figsize=(4, 3))
    common.save_figure(fig, tmp_path / "f.png")
    with Image.open(tmp_path / "f.png") as im:
        # PNG stores whole pixels per metre: 120 dpi is 4724 px/m, read back 119.99 dpi
        assert im.info["dpi"] == pytest.approx((120, 120), abs=0.1)


def test_the_damping_option_reads_numbers():
    import argparse
    p = argparse.ArgumentParser()
    common.damping_option(p)
    assert p.parse_args(["--damping", "0.02", "0", "1.5"]).damping == [0.02, 0.0, 1.5]
    assert "cable viscous damping [N s/m^2]" in " ".join(p.format_help().split())


def test_tables_only_where_asked(tmp_path):
    """write_tables with no --json attribute at all (a command without the option)."""
    df = pd.DataFrame({"a [m]": [1.0]})
    common.write_tables(Namespace(csv=str(tmp_path / "t.csv")), df, {"scene": "x"})
    assert (tmp_path / "t.csv").exists() and not (tmp_path / "t.json").exists()


def test_the_date_of_a_header_is_utc():
    from datetime import datetime
    stamp = common.table_metadata("x", None, None)["date"]
    assert stamp.endswith("+00:00") and datetime.fromisoformat(stamp).utcoffset().seconds == 0


def test_refuse_unused_names_every_option_given_in_one_line():
    """refuse_unused: the options given (not None: 0 is given), each found under its argparse
    name (leading dashes dropped, inner ones as underscores, any first letter), in the order
    listed, with "does" for one and "do" for more; none given: nothing refused."""
    import argparse
    options = ("-n", "--max-modes", "-X", "--pose")
    p = argparse.ArgumentParser()
    for opt in options:
        p.add_argument(opt, type=float)
    why = "without --line (the poses are the line's)"
    common.refuse_unused(p.parse_args([]), options, why)
    for argv, names, verb in ((["-X", "0"], "-X", "does"),
                              (["--max-modes", "2"], "--max-modes", "does"),
                              (["--pose", "1", "-n", "0"], "-n, --pose", "do")):
        with pytest.raises(ds.InvalidParameterError) as err:
            common.refuse_unused(p.parse_args(argv), options, why)
        assert str(err.value) == f"{names} {verb} not apply {why}"
