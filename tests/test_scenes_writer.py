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


def test_header_comments_are_written_line_by_line_empty_lines_as_a_bare_hash():
    """Each comment line becomes "# line" at the top, an empty one "#", then [scene]."""
    from dynstiff.scenes import scene_text
    r = ds.load_scene("planar2").robot
    text = scene_text(r, comments=["source: CASPR", "", "units: SI"])
    assert text.splitlines()[:5] == ["# source: CASPR", "#", "# units: SI", "", "[scene]"]


def test_values_are_written_as_repr_with_their_unit_comment_on_the_same_line():
    """g, mass and tension limits are written as the float repr, unit comment on that line."""
    import re

    from dynstiff.scenes import scene_text
    r = replace(ds.load_scene("pendulum").robot, g=9.80665, tension_limits=(0.1, 1 / 3))
    r = replace(r, platform=replace(r.platform, mass=2 / 3))
    lines = scene_text(r).splitlines()
    for key, value, unit in (("g", 9.80665, "[m/s^2]"), ("mass", 2 / 3, "[kg]"),
                             ("min", 0.1, "[N]"), ("max", 1 / 3, "[N]")):
        pattern = rf"^{key} = {re.escape(repr(value))} +# {re.escape(unit)}$"
        assert sum(bool(re.match(pattern, ln)) for ln in lines) == 1, (key, lines)


def test_single_cable_robot_without_name_or_description_reads_back(tmp_path):
    """One damped cable ([cable] table), no name ("scene") and no description ("") read back."""
    r = ds.load_scene("pendulum").robot
    cable = replace(r.cables[0], viscous_damping=0.25, loss_factor=0.02)
    r1 = replace(r, anchors=r.anchors[:1], attachments=r.attachments[:1], cables=[cable],
                 name="")
    back = ds.load_scene(write_scene(tmp_path / "s.toml", r1))
    assert_same_robot(back.robot, r1)
    assert back.robot.cables[0].viscous_damping == 0.25
    assert back.name == "scene" and back.robot.name == "scene" and back.description == ""


def test_trajectories_with_notes_and_workspace_box_read_back(tmp_path):
    """Trajectories (velocities, accelerations, blend times), notes and box read back."""
    sc = ds.load_scene("cogiro")
    quintic = ds.WaypointPath([0.0, 1.5, 3.0], [[0, 0, 1.0], [0.2, 0.1, 1.1], [0.4, 0, 1.0]],
                              [[0, 0, 0], [0, 0, 0.1], [0, 0, 0.2]], law="quintic",
                              velocities=[[0, 0, 0], [0.1, 0.05, 0], [0, 0, 0]],
                              accelerations=[[0, 0, 0], [0.02, 0, -0.01], [0, 0, 0]],
                              name="pick")
    blend = ds.WaypointPath([0.0, 2.0], [[0, 0, 1.0], [0.1, 0, 1.0]], [[0, 0, 0]] * 2,
                            law="parabolic_blend", blend_times=[0.5], name="slow")
    box = (-1.0, 1.0, -0.5, 0.5, 0.25, 2.0)
    path = write_scene(tmp_path / "s.toml", sc.robot, sc.pose, trajectories=[quintic, blend],
                       workspace_box=box, trajectory_notes={"pick": "pick and place along X"})
    lines = path.read_text(encoding="utf-8").splitlines()
    heads = [ln for ln in lines if ln.startswith("[[trajectories]]")]
    assert len(heads) == 2
    assert heads[0].split(None, 1)[1] == "# pick and place along X"
    assert heads[1] == "[[trajectories]]"
    back = ds.load_scene(path)
    assert back.workspace_box == box
    assert list(back.trajectories) == ["pick", "slow"]
    for want in (quintic, blend):
        got = back.trajectories[want.name]
        assert got.law == want.law
        for f in ("times", "positions", "rotations", "velocities", "accelerations"):
            np.testing.assert_array_equal(getattr(got, f), getattr(want, f))
    np.testing.assert_array_equal(back.trajectories["slow"].blend_times, [0.5])


@pytest.mark.parametrize("kw, message", [
    (dict(robot={"anchors": []}), "robot must be a dynstiff.Robot, got dict"),
    (dict(trajectories=[1.0]), "trajectories must be dynstiff.WaypointPath objects"),
    (dict(workspace_box=[0, 1, 0, 1]), "workspace_box must be 6 finite numbers x0 x1 y0 y1 "
     "z0 z1 [m] with x0 <= x1 ..., got [0, 1, 0, 1]"),
    (dict(workspace_box=[0, np.nan, 0, 1, 0, 1]), "workspace_box must be 6 finite numbers "
     "x0 x1 y0 y1 z0 z1 [m] with x0 <= x1 ..., got [0, nan, 0, 1, 0, 1]"),
    (dict(workspace_box=[False, True, 0, 1, 0, 1]), "workspace_box must be real numbers, "
     "not booleans, got [False, True, 0, 1, 0, 1]"),
    (dict(workspace_box=["0", "1", "a", "1", "0", "1"]), "workspace_box must be 6 finite "
     "numbers x0 x1 y0 y1 z0 z1 [m] with x0 <= x1 ..., got ['0', '1', 'a', '1', '0', '1']"),
])
def test_bad_robot_trajectory_or_box_gives_the_exact_message_and_no_file(tmp_path, kw,
                                                                         message):
    """A non-Robot, a non-WaypointPath or a box of 4, non-finite, boolean or non-numeric
    values: exact message."""
    import re
    path = tmp_path / "s.toml"
    kw = {"robot": ds.load_scene("planar2").robot} | kw
    with pytest.raises(ds.InvalidParameterError, match=f"^{re.escape(message)}$"):
        write_scene(path, **kw)
    assert not path.exists()


def test_comment_text_cannot_end_its_comment_and_be_read_as_toml(tmp_path):
    """Line breaks and control characters in the header comments, the cable names and the
    trajectory notes (a CASPR file's names reach all three) are written as escapes: the
    scene reads back to the same robot, with no key set by the text; a note ending in "#"
    keeps it."""
    from dynstiff.scenes import scene_text
    sc = ds.load_scene("cogiro")
    inject = "x\n[workspace]\nbox = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0]\r\nEA = 1.0\x1b\x00#"
    names = [f"c{k}" for k in range(8)]
    names[3] = "a\nEA = 1.0\n#"
    path_ = ds.WaypointPath([0.0, 1.0], [[0, 0, 1.0], [0.1, 0, 1.0]], [[0, 0, 0]] * 2,
                            name="p")
    text = scene_text(sc.robot, sc.pose, comments=[inject, "two\nlines"], cable_names=names,
                      trajectories=[path_], trajectory_notes={"p": inject})
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    back = ds.load_scene(tmp_path / "s.toml")
    assert_same_robot(back.robot, sc.robot)
    assert back.workspace_box is None
    lines = text.splitlines()
    escaped = r"x\n[workspace]\nbox = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0]\r\nEA = 1.0\x1b\x00#"
    assert lines[:5] == ["# x", "# [workspace]", "# box = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0]",
                         r"# EA = 1.0\x1b\x00#", "# two"]
    assert sum(ln.endswith(r"# cable 3 (a\nEA = 1.0\n#)") for ln in lines) == 1
    head = [ln for ln in lines if ln.startswith("[[trajectories]]")]
    assert head == [f"{'[[trajectories]]':<44}# {escaped}"]
    tab = scene_text(sc.robot, comments=["a\tb"]).splitlines()[0]
    assert tab == "# a\tb"



def test_platform_inertia_is_written_under_its_comment_and_an_integer_box_as_floats():
    """The [platform] table's inertia comes under the comment that says its frame and which
    entries are products of inertia; a box of integers is written as the floats it means."""
    from dynstiff.scenes import scene_text
    text = scene_text(ds.load_scene("cogiro").robot, workspace_box=[-5, 5, -3, 3, 1, 2])
    lines = text.splitlines()
    k = lines.index("# inertia tensor about G [kg m^2], platform axes; off-diagonal entries are")
    assert lines[k + 1].startswith("# ") and lines[k + 2].startswith("inertia = ")
    assert "box = [-5.0, 5.0, -3.0, 3.0, 1.0, 2.0]   # [m], x0 x1 y0 y1 z0 z1 of P" in lines


def test_identical_cables_share_one_cable_table_and_its_unit_line():
    """Cables all alike are written once, in a [cable] table followed by the comment of its
    units; each [[cables]] entry then holds its anchor and attachment only. Cables that
    differ have no [cable] table and give their own properties."""
    from dynstiff.scenes import scene_text
    r = ds.load_scene("cogiro").robot
    lines = scene_text(r).splitlines()
    k = lines.index("[cable]                                     # every cable")
    assert lines[k + 1].startswith("mass_per_length = ")
    assert "# mass_per_length [kg/m], EA [N]" in lines[k + 1:k + 8]
    entries = [i for i, ln in enumerate(lines) if ln.startswith("[[cables]]")]
    assert len(entries) == r.n_cables
    for i in entries:
        assert [ln.split(" = ")[0] for ln in lines[i + 1:i + 4]][:2] == ["anchor",
                                                                       "attachment"]
        assert not any(ln.startswith("mass_per_length") for ln in lines[i + 1:i + 4])
    cables = [replace(c, EA=c.EA * (1 + k / 10)) for k, c in enumerate(r.cables)]
    text = scene_text(replace(r, cables=cables))
    assert "[cable] " not in text and text.count("mass_per_length = ") == r.n_cables


def test_a_flat_box_is_written():
    """A box with a dimension of zero length (x0 = x1: a map in a plane) is a box: written
    as given; a box whose upper bound is below its lower one is refused."""
    from dynstiff.scenes import scene_text
    r = ds.load_scene("planar2").robot
    text = scene_text(r, workspace_box=[-1.0, 1.0, 0.0, 0.0, -12.0, -8.0])
    assert "box = [-1.0, 1.0, 0.0, 0.0, -12.0, -8.0]   # [m], x0 x1 y0 y1 z0 z1 of P" in text
    with pytest.raises(ds.InvalidParameterError, match="^workspace_box must be 6 finite"):
        scene_text(r, workspace_box=[-1.0, 1.0, 0.1, 0.0, -12.0, -8.0])
