"""Scene files written from a robot (dynstiff/scenes/writer.py): a written scene reads back
to the same robot and pose bit for bit, and bad trajectories or boxes are refused before
anything is written (CASPR import: tests/test_scenes_caspr.py)."""

from dataclasses import replace

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.scenes import write_scene


def assert_same_robot(a, b):
    for f in ("anchors", "attachments"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f))
    assert a.cables == b.cables and a.g == b.g and a.tension_limits == b.tension_limits
    for f in ("mass", "center_of_mass", "inertia"):
        np.testing.assert_array_equal(getattr(a.platform, f), getattr(b.platform, f))
    assert a.platform.free_dofs == b.platform.free_dofs


@pytest.mark.parametrize("name", ["cogiro", "planar2", "fourcable"])
def test_written_scene_reads_back_bit_for_bit(tmp_path, name):
    sc = ds.load_scene(name)
    pose = sc.pose or ds.Pose([0.1, -0.2, 1.0], [0.01, 0.02, 1 / 3])
    path = write_scene(tmp_path / "s.toml", sc.robot, pose, description="round trip",
                       comments=["a comment"])
    back = ds.load_scene(path)
    assert_same_robot(back.robot, sc.robot)
    assert back.pose == pose and back.description == "round trip"


def test_cables_that_differ_are_written_one_by_one(tmp_path):
    r = ds.load_scene("cogiro").robot
    cables = [replace(c, EA=c.EA * (1 + k / 10), loss_factor=0.01 * k)
              for k, c in enumerate(r.cables)]
    r2 = replace(r, cables=cables, tension_limits=(10.0, np.inf))
    back = ds.load_scene(write_scene(tmp_path / "s.toml", r2)).robot
    assert_same_robot(back, r2)


@pytest.mark.parametrize("kw, match", [
    (dict(trajectories=[1.0]), "trajectories must be dynstiff.WaypointPath"),
    (dict(trajectories=[ds.WaypointPath([0, 1], np.zeros((2, 3)), np.zeros((2, 3)))]),
     "distinct, non-empty names"),
    (dict(workspace_box=[0, 1, 0, 1, 2, 1]), "workspace_box must be 6 finite numbers"),
])
def test_bad_trajectories_and_boxes_are_refused_before_writing(tmp_path, kw, match):
    r = ds.load_scene("cogiro").robot
    with pytest.raises(ds.InvalidParameterError, match=match):
        write_scene(tmp_path / "s.toml", r, **kw)
    assert not (tmp_path / "s.toml").exists()


def test_names_with_quotes_backslashes_and_newlines_read_back_exactly(tmp_path):
    sc = ds.load_scene("planar2")
    text = 'robot "A"\\B\nsecond line\ttab'
    path = write_scene(tmp_path / "s.toml", sc.robot, sc.pose, name=text, description=text)
    back = ds.load_scene(path)
    assert back.name == text and back.description == text


@pytest.mark.parametrize("kw, message", [
    (dict(name=5), "^name must be a str, got 5$"),
    (dict(description=["a"]), r"^description must be a str, got \['a'\]$"),
    (dict(comments="abc"), r"^comments must be a sequence of str \(lines\), got 'abc'$"),
    (dict(cable_names=["a"]), r"^cable_names must be 2 names \(one per cable\), got \['a'\]$"),
    (dict(pose=[True, 0, 1]), "^pose must be real numbers, not booleans")])
def test_scene_text_arguments_are_checked_and_no_file_is_written(tmp_path, kw, message):
    """cable_names too short was an IndexError, a pose given as numbers an AttributeError,
    a name 5 the text "5"."""
    from dynstiff.scenes import write_scene
    sc = ds.load_scene("planar2")
    path = tmp_path / "s.toml"
    with pytest.raises(ds.InvalidParameterError, match=message):
        write_scene(path, sc.robot, **({"pose": sc.pose} | kw))
    assert not path.exists()


def test_a_pose_given_as_numbers_is_written_and_read_back(tmp_path):
    from dynstiff.scenes import write_scene
    sc = ds.load_scene("planar2")
    back = ds.load_scene(write_scene(tmp_path / "s.toml", sc.robot, [0.1, 0.0, -10.0]))
    np.testing.assert_array_equal(back.pose.position, [0.1, 0.0, -10.0])
