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


def _traj_file(tmp_path, tag, attrs, pts):
    """A file holding one joint trajectory <tag id="a" attrs> with the points pts."""
    p = tmp_path / "t.xml"
    p.write_text(f"<trajectories><joint_trajectories><{tag} id=\"a\" {attrs}><points>{pts}"
                 f"</points></{tag}></joint_trajectories></trajectories>")
    return p


@pytest.mark.parametrize("attrs, pts, message", [
    ('time_step="0.1"', P0 + P1.replace("<q_dot>0 0 0</q_dot>", "<q_dot>0 0</q_dot>"),
     "trajectory 'a' point 1 <q_dot> must be 3 finite numbers, got '0 0'"),
    ('time_step="0.1"', P0 + P1.replace("<q_ddot>0 0 0</q_ddot>", "<q_ddot>0 0 0 0</q_ddot>"),
     "trajectory 'a' point 1 <q_ddot> must be 3 finite numbers, got '0 0 0 0'"),
    ('time_step="0.1"', P0 + P1.replace('time="1"', 'time="x"'),
     "trajectory 'a' point 1 time must be 1 finite number, got 'x'"),
    ('time_step="0.1"', P0 + P1.replace('time="1"', 'time="1 2"'),
     "trajectory 'a' point 1 time must be 1 finite number, got '1 2'"),
    ('time_step="0.1"', P0 + P1.replace(' time="1"', ""), "missing trajectory 'a' point 1 time"),
    ('time_step="0.1 0.2"', P0 + P1,
     "trajectory 'a' time_step must be 1 finite number, got '0.1 0.2'"),
])
def test_bad_numbers_of_a_trajectory_are_named_exactly(tmp_path, attrs, pts, message):
    """A rate, time or time_step with the wrong count of values (or none, or not a number) is
    refused with the file, the trajectory, the point and the value in the message."""
    p = _traj_file(tmp_path, "quintic_spline_trajectory", attrs, pts)
    with pytest.raises(CasprError) as err:
        read_caspr_trajectories(p, "T_XYZ")
    assert str(err.value) == f"{p}: {message}"


B0 = "<point><q>0 0 1</q></point>"


@pytest.mark.parametrize("attrs, pts, message", [
    ('blend_time_default="0.5"', B0 + '<point time="1" blend_time="0.5 0.6"><q>1 0 1</q></point>',
     "trajectory 'a' point 1 blend_time (or blend_time_default) must be 1 finite number, "
     "got '0.5 0.6'"),
    ('blend_time_default="fast"', B0 + '<point time="1"><q>1 0 1</q></point>',
     "trajectory 'a' point 1 blend_time (or blend_time_default) must be 1 finite number, "
     "got 'fast'"),
    ("", B0 + '<point time="1"><q>1 0 1</q></point>',
     "missing trajectory 'a' point 1 blend_time (or blend_time_default)"),
])
def test_bad_blend_times_are_named_exactly(tmp_path, attrs, pts, message):
    """A parabolic blend's blend_time (own or default) must be one number; its absence is
    named too."""
    p = _traj_file(tmp_path, "parabolic_blend_trajectory", attrs, pts)
    with pytest.raises(CasprError) as err:
        read_caspr_trajectories(p, "T_XYZ")
    assert str(err.value) == f"{p}: {message}"


def test_cubic_spline_needs_q_dot_at_every_point(tmp_path):
    """A cubic spline (not the average-velocity one) missing <q_dot> at an inner point is
    refused, naming the first such point; <q_ddot> is not needed."""
    pts = (B0.replace("</q>", "</q><q_dot>0 0 0</q_dot>")
           + '<point time="1"><q>1 0 1</q></point>'
           + '<point time="1"><q>2 0 1</q><q_dot>0 0 0</q_dot></point>')
    p = _traj_file(tmp_path, "cubic_spline_trajectory", "", pts)
    with pytest.raises(CasprError) as err:
        read_caspr_trajectories(p, "T_XYZ")
    assert str(err.value) == (f"{p}: trajectory 'a' point 1: missing <q_dot> (a cubic spline "
                              f"needs it at every point)")


def test_time_definition_defaults_to_relative_and_time_step_to_nan(tmp_path):
    """Without time_definition the times are durations of the segments; without time_step
    the step is NaN; the rates are read back exactly."""
    pts = P0 + P1 + P1.replace('time="1"', 'time="2"').replace("<q_dot>0 0 0", "<q_dot>1 2 3")
    p = _traj_file(tmp_path, "cubic_spline_trajectory", "", pts)
    t = read_caspr_trajectories(p, "T_XYZ").trajectories["a"]
    np.testing.assert_array_equal(t.times, [0.0, 1.0, 3.0])
    np.testing.assert_array_equal(t.q_dot, [[0, 0, 0], [0, 0, 0], [1, 2, 3]])
    assert t.q_ddot is None and t.blend_times is None and np.isnan(t.time_step)


def test_unknown_trajectory_element_lists_the_known_ones(tmp_path):
    """The message of an unknown joint-trajectory element lists CASPR's five splines and
    file_trajectory."""
    p = _traj_file(tmp_path, "spiral_trajectory", "", P0 + P1)
    with pytest.raises(CasprError) as err:
        read_caspr_trajectories(p, "T_XYZ")
    assert str(err.value) == (
        f"{p}: <spiral_trajectory> is not a CASPR joint trajectory (one of "
        f"['linear_spline_trajectory', 'cubic_spline_trajectory', 'quintic_spline_trajectory', "
        f"'cubic_spline_average_velocity_trajectory', 'parabolic_blend_trajectory', "
        f"'file_trajectory'])")


def test_skipped_trajectories_keep_file_order_and_unnamed_ones_are_question_marks(tmp_path):
    """Skipped trajectories of both sections accumulate in file order; one without id is
    listed as '?'."""
    p = tmp_path / "t.xml"
    p.write_text('<trajectories><joint_trajectories><file_trajectory id="f" filename="f.traj"/>'
                 '</joint_trajectories><operational_trajectories>'
                 '<quintic_spline_trajectory id="o"/><linear_spline_trajectory/>'
                 '</operational_trajectories></trajectories>')
    r = read_caspr_trajectories(p, "T_XYZ")
    op = "an operational-space trajectory (a marker's path), not read"
    assert r.trajectories == {}
    assert r.skipped == (("f", "samples in the file 'f.traj', not read"), ("o", op), ("?", op))


def test_marker_without_optional_attributes(tmp_path):
    """Without default_operational_set, marker_id or name, they read as ""; given, they are
    read back."""
    p = tmp_path / "o.xml"
    p.write_text('<operational_spaces><operational_set id="s"><orientation_euler_xyz>'
                 '<link>1</link><offset>0.1 0.2 0.3</offset><axes active_axes="abg"/>'
                 '</orientation_euler_xyz></operational_set></operational_spaces>')
    ops = read_caspr_operational_spaces(p)
    assert ops.default == ""
    (m,) = ops.sets["s"]
    assert (m.kind, m.marker_id, m.name, m.axes) == ("orientation_euler_xyz", "", "", "abg")
    np.testing.assert_array_equal(m.offset, [0.1, 0.2, 0.3])
    given = read_caspr_operational_spaces(OPS)
    assert [(m.marker_id, m.name) for s in given.sets.values() for m in s] == [
        ("1", "tool tip"), ("2", "tool frame")]


@pytest.mark.parametrize("offset", ["0 0", "0 0 0 1", "0 0 inf"])
def test_bad_marker_offset_is_named_exactly(tmp_path, offset):
    """A marker's offset must be 3 finite numbers; the message names the set and marker."""
    p = tmp_path / "o.xml"
    p.write_text(OPS.read_text().replace("<offset>0 0 -0.2</offset>",
                                         f"<offset>{offset}</offset>", 1))
    with pytest.raises(CasprError) as err:
        read_caspr_operational_spaces(p)
    assert str(err.value) == (f"{p}: operational set 'tool' marker <position> <offset> must be "
                              f"3 finite numbers, got {offset!r}")


@pytest.mark.parametrize("step", ["0", "-0.1", ""])
def test_a_time_step_not_above_zero_or_empty_is_refused(tmp_path, step):
    """CASPR's sampling step must be > 0 [s]; an empty attribute is not taken as absent."""
    p = _traj_file(tmp_path, "quintic_spline_trajectory", f'time_step="{step}"', P0 + P1)
    with pytest.raises(CasprError) as err:
        read_caspr_trajectories(p, "T_XYZ")
    want = "trajectory 'a' time_step must be 1 finite number, got ''" if step == "" else \
        f"trajectory 'a': time_step '{step}' (a sampling step > 0 [s])"
    assert str(err.value) == f"{p}: {want}"


@pytest.mark.parametrize("sets, message", [
    ('<operational_set id="s"/><operational_set id="s"/>', "two operational sets with id 's'"),
    ('<operational_set id="s"><position><link>1</link><offset>0 0 0</offset>'
     '<axes active_axes="xxz"/></position></operational_set>',
     "operational set 's' marker <position>: active_axes 'xxz' (distinct letters of "
     "'xyzabg')"),
])
def test_duplicate_sets_and_repeated_axes_are_refused(tmp_path, sets, message):
    """A second operational set with an id already read would replace the first: refused, as
    two trajectories of one name are; an axis letter given twice too."""
    p = tmp_path / "o.xml"
    p.write_text(f"<operational_spaces>{sets}</operational_spaces>")
    with pytest.raises(CasprError) as err:
        read_caspr_operational_spaces(p)
    assert str(err.value) == f"{p}: {message}"
