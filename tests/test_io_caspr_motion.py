"""CASPR trajectories and operational spaces (dynstiff/io/caspr_motion.py, theory.md §15.8): a
test file in CASPR's format with one trajectory of each kind CASPR reads
(tests/data/caspr/InvertedStewart_trajectories.xml, written for dynstiff), relative and
absolute times, the average velocities CASPR computes, the kinds not read, operational
sets, and malformed files."""

from pathlib import Path

import numpy as np
import pytest

from dynstiff.io.caspr import CasprError
from dynstiff.io.caspr_motion import read_caspr_operational_spaces, read_caspr_trajectories

DATA = Path(__file__).parent / "data" / "caspr"
TRAJ = DATA / "InvertedStewart_trajectories.xml"
OPS = DATA / "InvertedStewart_operational_spaces.xml"


@pytest.fixture(scope="module")
def read():
    return read_caspr_trajectories(TRAJ, "SPATIAL_EULER_XYZ")


def test_every_kind_is_read_with_its_law_and_times(read):
    tr = read.trajectories
    assert list(tr) == ["lift_and_turn", "square", "swing", "mean_speed", "blend"]
    assert [t.law for t in tr.values()] == ["quintic", "linear", "cubic", "cubic",
                                            "parabolic_blend"]
    np.testing.assert_array_equal(tr["lift_and_turn"].times, [0.0, 2.0, 4.0])   # relative
    np.testing.assert_array_equal(tr["square"].times, [0.0, 1.0, 3.0])          # absolute
    np.testing.assert_array_equal(tr["lift_and_turn"].q[2], [0.3, 0.3, 1.6, 0.1, 0.0, 0.2])
    assert tr["lift_and_turn"].q_ddot.shape == (3, 6) and tr["lift_and_turn"].time_step == 0.05
    assert tr["swing"].q_ddot is None and tr["swing"].q_dot[1, 0] == 0.1
    assert tr["square"].q_dot is None


def test_average_velocity_spline_takes_the_mean_of_the_neighbouring_slopes(read):
    """CASPR's cubic_spline_average_velocity: at an inner point, the mean of the slopes of
    the two segments (x and z: 0.2 m/s then 0; y: 0 then 0.4 m / 2 s)."""
    qd = read.trajectories["mean_speed"].q_dot
    np.testing.assert_allclose(qd[1], [0.1, 0.1, 0.1, 0.0, 0.0, 0.0])
    np.testing.assert_array_equal(qd[[0, 2]], 0.0)


def test_parabolic_blend_times_default_or_per_point(read):
    b = read.trajectories["blend"]
    np.testing.assert_array_equal(b.blend_times, [0.5, 1.0])
    np.testing.assert_array_equal(b.times, [0.0, 2.0, 5.0])


def test_kinds_not_read_are_listed_with_the_reason(read):
    assert dict(read.skipped) == {
        "recorded": "samples in the file 'recorded.traj', not read",
        "tool_path": "an operational-space trajectory (a marker's path), not read"}


def test_empty_file_has_no_trajectory(tmp_path):
    """CASPR's template (and six of its ten spatial robots): an empty <joint_trajectories>."""
    p = tmp_path / "t.xml"
    p.write_text("<trajectories><joint_trajectories></joint_trajectories></trajectories>")
    r = read_caspr_trajectories(p, "T_XYZ")
    assert r.trajectories == {} and r.skipped == ()


POINTS = ("<trajectories><joint_trajectories><{tag} id=\"a\" time_definition=\"{td}\" "
          "time_step=\"0.1\"><points>{pts}</points></{tag}></joint_trajectories>"
          "</trajectories>")
P0 = "<point><q>0 0 1</q><q_dot>0 0 0</q_dot><q_ddot>0 0 0</q_ddot></point>"
P1 = "<point time=\"1\"><q>1 0 1</q><q_dot>0 0 0</q_dot><q_ddot>0 0 0</q_ddot></point>"


@pytest.mark.parametrize("tag, td, pts, match", [
    ("quintic_spline_trajectory", "relative", P0, "has 1 point"),
    ("quintic_spline_trajectory", "later", P0 + P1, "time_definition 'later'"),
    ("quintic_spline_trajectory", "relative", P0 + P1.replace("1 0 1", "1 0"),
     "point 1 <q> must be 3 finite numbers"),
    ("quintic_spline_trajectory", "relative", P0 + P1.replace(
        "<q_ddot>0 0 0</q_ddot>", ""), "point 1: missing <q_ddot>"),
    ("quintic_spline_trajectory", "absolute", P0 + P1 + P1, "are not increasing"),
    ("spiral_trajectory", "relative", P0 + P1, "<spiral_trajectory> is not a CASPR joint"),
])
def test_malformed_trajectories_are_named(tmp_path, tag, td, pts, match):
    p = tmp_path / "t.xml"
    p.write_text(POINTS.format(tag=tag, td=td, pts=pts))
    with pytest.raises(CasprError, match=match) as err:
        read_caspr_trajectories(p, "T_XYZ")
    assert str(p) in str(err.value) and "\n" not in str(err.value)


def test_operational_sets_are_markers_without_bounds():
    ops = read_caspr_operational_spaces(OPS)
    assert ops.default == "tool" and list(ops.sets) == ["tool", "tool_pose"]
    (m,) = ops.sets["tool"]
    assert (m.kind, m.name, m.link, m.axes) == ("position", "tool tip", 1, "xyz")
    np.testing.assert_array_equal(m.offset, [0.0, 0.0, -0.2])
    assert ops.sets["tool_pose"][0].axes == "xyzabg"


def test_empty_and_nested_operational_space_files(tmp_path):
    """The ten spatial robots' files hold no set; one CASPR file nests a second
    <operational_spaces> in the first: its sets are read."""
    p = tmp_path / "o.xml"
    p.write_text('<operational_spaces default_operational_set=""></operational_spaces>')
    assert read_caspr_operational_spaces(p).sets == {}
    p.write_text('<operational_spaces default_operational_set=""><operational_spaces '
                 'default_operational_set="a"><operational_set id="a"><position marker_id="1">'
                 '<link>1</link><offset>0 0 0.8</offset><axes active_axes="xyz"/></position>'
                 '</operational_set></operational_spaces></operational_spaces>')
    assert list(read_caspr_operational_spaces(p).sets) == ["a"]


@pytest.mark.parametrize("edit, match", [
    (("<link>1</link>", "<link>2</link>", 1), "on link '2'; a single-body robot"),
    (('active_axes="xyz"', 'active_axes="xyq"', 1), "active_axes 'xyq'"),
    (('default_operational_set="tool"', 'default_operational_set="none"', 1),
     "default_operational_set 'none' not found"),
    (("<position ", "<velocity ", 1), "unknown marker"),
])
def test_malformed_operational_spaces_are_named(tmp_path, edit, match):
    p = tmp_path / "o.xml"
    text = OPS.read_text().replace(*edit)
    if edit[0] == "<position ":
        text = text.replace("</position>", "</velocity>")
    p.write_text(text)
    with pytest.raises(CasprError, match=match):
        read_caspr_operational_spaces(p)
