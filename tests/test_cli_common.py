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
