"""Scenes of CASPR robots (dynstiff/scenes/caspr.py, theory.md §15.1, §15.8): the scene is at
q_initial; its trajectories follow CASPR's interpolation (checked against scipy's Slerp on
the geodesic and the quintic time law), its workspace box is the joint's bounds, and a
written scene reads back to the same paths bit for bit."""

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

import dynstiff as ds
from dynstiff.io.caspr import CasprError, InertiaConventionWarning
from dynstiff.scenes import import_caspr, read_scene, write_scene
from dynstiff.scenes.caspr import caspr_comments, caspr_siblings

DATA = Path(__file__).parent / "data" / "caspr"
INV = (DATA / "InvertedStewart_bodies.xml", DATA / "InvertedStewart_cables.xml")
TRAJ = DATA / "InvertedStewart_trajectories.xml"
OPS = DATA / "InvertedStewart_operational_spaces.xml"
CABLE = ds.Cable(0.05, 1e6)


@pytest.fixture(scope="module")
def scene():
    return import_caspr(*INV, CABLE, trajectories_xml=TRAJ, operational_spaces_xml=OPS)


def test_import_caspr_scene_is_at_q_initial():
    cable = ds.load_scene("cogiro").robot.cables[0]
    with pytest.warns(InertiaConventionWarning):
        sc = import_caspr(DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml", cable)
    assert sc.pose == ds.Pose([0.0, 0.0, 2.0])
    assert "products" in sc.description and "original" in sc.description
    assert sc.trajectories == {} and sc.workspace_box is None
    with pytest.raises(ds.InvalidParameterError, match="cable must be a dynstiff.Cable"):
        import_caspr(DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml", 1e5)


def test_trajectory_follows_caspr_interpolation(scene):
    """lift_and_turn, second segment (2 to 4 s, quintic at rest at both ends): P moves on
    the line by s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 and the orientation turns on the
    geodesic from R_x(0) R_y(0) R_z(0) to R_x(0.1) R_y(0) R_z(0.2) by the same s."""
    path = scene.trajectories["lift_and_turn"]
    tau = np.linspace(0.0, 1.0, 9)
    P, R = path.at(2.0 + 2.0 * tau)
    s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    a, b = np.array([0.3, 0.0, 1.8]), np.array([0.3, 0.3, 1.6])
    np.testing.assert_allclose(P, a + s[:, None] * (b - a), atol=1e-12)
    ends = Rotation.concatenate([Rotation.identity(),
                                 Rotation.from_euler("XYZ", [0.1, 0.0, 0.2])])
    ref = Slerp([0.0, 1.0], ends)(s)
    np.testing.assert_allclose(Rotation.from_rotvec(R).as_matrix(), ref.as_matrix(),
                               atol=1e-12)


def test_rates_laws_and_skipped_kinds_reach_the_scene(scene):
    tr = scene.trajectories
    assert [p.law for p in tr.values()] == ["quintic", "linear", "cubic", "cubic",
                                            "parabolic_blend"]
    np.testing.assert_array_equal(tr["swing"].velocities[1], [0.1, 0.0, 0.0])
    np.testing.assert_array_equal(tr["blend"].blend_times, [0.5, 1.0])
    assert [k for k, _ in scene.study["caspr_skipped_trajectories"]] == ["recorded",
                                                                        "tool_path"]
    assert scene.study["caspr_operational_sets"]["tool"][0]["offset"] == [0.0, 0.0, -0.2]
    assert scene.workspace_box == (-1.0, 1.0, -1.0, 1.0, 0.5, 2.5)


def test_nonzero_orientation_rates_are_refused_as_caspr_does(tmp_path):
    p = tmp_path / "t.xml"
    p.write_text(TRAJ.read_text().replace(
        "<point time=\"1.5\"><q>0.2 0 1.5 0 0 0</q><q_dot>0.1 0 0 0 0 0</q_dot>",
        "<point time=\"1.5\"><q>0.2 0 1.5 0 0 0</q><q_dot>0.1 0 0 0 0 0.3</q_dot>"))
    with pytest.raises(CasprError, match="trajectory 'swing': nonzero orientation velocity"):
        import_caspr(*INV, CABLE, trajectories_xml=p)


def test_an_averaged_orientation_rate_is_refused_saying_where_it_comes_from(tmp_path):
    """An average-velocity spline whose orientation changes at an inner waypoint: the rate
    refused there is the mean of the two segments' rates, which the file did not give; the
    message says so and names the waypoint. One whose orientation stays put is read."""
    def spline(rz):
        return ('<cubic_spline_average_velocity_trajectory id="avg" time_definition='
                '"relative"><points>'
                '<point><q>0 0 1.5 0 0 0</q><q_dot>0 0 0 0 0 0</q_dot></point>'
                f'<point time="1.0"><q>0.1 0 1.5 0 0 {rz}</q></point>'
                '<point time="2.0"><q>0.2 0 1.5 0 0 0</q><q_dot>0 0 0 0 0 0</q_dot></point>'
                '</points></cubic_spline_average_velocity_trajectory>')
    t = _trajectories(tmp_path, spline("0.2"))
    with pytest.raises(CasprError) as exc:
        import_caspr(*INV, CABLE, trajectories_xml=t)
    assert str(exc.value) == (
        f"{t}: trajectory 'avg': nonzero orientation velocity at waypoint 1 (the mean of "
        f"its two segments' rates, which an average-velocity spline takes there: the "
        f"orientation changes at that waypoint); {REFUSAL}")
    scene = import_caspr(*INV, CABLE, trajectories_xml=_trajectories(tmp_path, spline("0")))
    # relative times: the segments last 1 s and 2 s, their x rates 0.1 and 0.05 m/s
    np.testing.assert_allclose(scene.trajectories["avg"].velocities[1], [0.075, 0.0, 0.0],
                               rtol=1e-14)


@pytest.mark.parametrize("first", [True, False])
def test_an_end_rate_of_an_averaged_spline_is_refused_as_given(tmp_path, first):
    """An average-velocity spline's first and last rates are the file's own: a nonzero
    orientation rate there is refused naming the waypoint (0 or the last, 2) without saying
    it is a mean of two segments' rates."""
    end = "0 0 0 0 0 0.3"
    zero = "0 0 0 0 0 0"
    t = _trajectories(tmp_path, (
        '<cubic_spline_average_velocity_trajectory id="avg" time_definition="relative">'
        f'<points><point><q>0 0 1.5 0 0 0</q><q_dot>{end if first else zero}</q_dot></point>'
        '<point time="1.0"><q>0.1 0 1.5 0 0 0</q></point>'
        f'<point time="2.0"><q>0.2 0 1.5 0 0 0</q><q_dot>{zero if first else end}</q_dot>'
        '</point></points></cubic_spline_average_velocity_trajectory>'))
    with pytest.raises(CasprError) as exc:
        import_caspr(*INV, CABLE, trajectories_xml=t)
    assert str(exc.value) == (f"{t}: trajectory 'avg': nonzero orientation velocity at "
                              f"waypoint {0 if first else 2}; {REFUSAL}")


def test_written_scene_reads_back_the_trajectories_and_box(tmp_path, scene):
    path = write_scene(tmp_path / "s.toml", scene.robot, scene.pose,
                       trajectories=scene.trajectories.values(),
                       workspace_box=scene.workspace_box)
    back = read_scene(path)
    assert back.workspace_box == scene.workspace_box
    assert list(back.trajectories) == list(scene.trajectories)
    for name, p in scene.trajectories.items():
        q = back.trajectories[name]
        for f in ("times", "positions", "rotations", "velocities", "accelerations"):
            np.testing.assert_array_equal(getattr(q, f), getattr(p, f))
        assert q.law == p.law and q.name == p.name
        np.testing.assert_array_equal(q.at([0.7, 2.9])[1], p.at([0.7, 2.9])[1])


def test_siblings_are_found_beside_the_bodies_file(tmp_path):
    assert caspr_siblings(INV[0]) == (TRAJ, OPS)
    assert caspr_siblings(DATA / "CoGiRo_bodies.xml") == (None, None)
    assert caspr_siblings(tmp_path / "robot.xml") == (None, None)


# ---------------------------------------------------------------- other joints, exact output
STEWART = "inverted Stewart platform"          # the link's name in InvertedStewart_bodies.xml
JOINT_6 = ('<joint type="SPATIAL_EULER_XYZ" q_initial="0 0 1.5 0 0 0"\n'
           '             q_min="-1.0 -1.0 0.5 -0.5 -0.5 -0.5" q_max="1.0 1.0 2.5 0.5 0.5 0.5"/>')
REFUSAL = ("CASPR interpolates orientations with zero rates at the waypoints and refuses "
           "these too")


def _place(filename):
    """A warning's file, compared with the caller's (as tests/test_io_caspr.py): a mutation
    run (MUTANT_UNDER_TEST set) puts the tool's frames between caller and library."""
    import os
    return None if "MUTANT_UNDER_TEST" in os.environ else filename


def _bodies(tmp_path, joint, origin="0.5 -0.5 1.5"):
    """InvertedStewart_bodies.xml with the joint element ``joint`` and the parent location
    ``origin`` (the joint's origin, base frame)."""
    text = (DATA / "InvertedStewart_bodies.xml").read_text()
    assert JOINT_6 in text and text.count("<location>0 0 0</location>") == 1
    b = tmp_path / "robot_bodies.xml"
    b.write_text(text.replace(JOINT_6, joint).replace("<location>0 0 0</location>",
                                                      f"<location>{origin}</location>"))
    return b


def _trajectories(tmp_path, body):
    """A trajectories file holding ``body`` in its <joint_trajectories>."""
    t = tmp_path / "robot_trajectories.xml"
    t.write_text(f"<trajectories><joint_trajectories>{body}</joint_trajectories>"
                 f"</trajectories>")
    return t


def _quintic(q0, q1, v1, a1, name="q"):
    """A quintic trajectory from q0 (at rest) to q1 at 2 s, with rates v1 and a1 there."""
    zero = " ".join("0" for _ in v1.split())
    return (f'<quintic_spline_trajectory id="{name}" time_definition="relative">'
            f"<points><point><q>{q0}</q><q_dot>{zero}</q_dot><q_ddot>{zero}</q_ddot></point>"
            f'<point time="2.0"><q>{q1}</q><q_dot>{v1}</q_dot><q_ddot>{a1}</q_ddot></point>'
            f"</points></quintic_spline_trajectory>")


def test_spherical_joint_coordinates_land_in_the_rotation_not_the_position(tmp_path):
    """S_EULER_XYZ (q = alpha beta gamma, rotations only): every waypoint's P is the joint's
    origin (0.5, -0.5, 1.5), its rotation R_x(alpha) R_y(beta) R_z(gamma); the rates of P
    are zero (3 per waypoint), with zero orientation rates at the waypoints; the scene pose
    is q_initial's, there is no workspace box (no translation), the comments list only the
    rotations as free DOFs and nothing about a box, operational sets or skipped kinds."""
    b = _bodies(tmp_path, '<joint type="S_EULER_XYZ" q_initial="0.1 -0.2 0.3"/>')
    t = _trajectories(tmp_path, _quintic("0 0 0", "0.4 -0.3 0.2", "0 0 0", "0 0 0", "tilt"))
    sc = import_caspr(b, INV[1], CABLE, trajectories_xml=t)
    origin = np.array([0.5, -0.5, 1.5])
    np.testing.assert_array_equal(sc.pose.position, origin)
    np.testing.assert_allclose(
        sc.pose.rotation, Rotation.from_euler("XYZ", [0.1, -0.2, 0.3]).as_rotvec(), atol=1e-15)
    assert sc.workspace_box is None
    p = sc.trajectories["tilt"]
    assert p.name == "tilt" and p.law == "quintic"
    np.testing.assert_array_equal(p.times, [0.0, 2.0])
    np.testing.assert_array_equal(p.positions, [origin, origin])
    np.testing.assert_allclose(p.rotations, [
        [0.0, 0.0, 0.0], Rotation.from_euler("XYZ", [0.4, -0.3, 0.2]).as_rotvec()],
        atol=1e-15)
    np.testing.assert_array_equal(p.velocities, np.zeros((2, 3)))
    np.testing.assert_array_equal(p.accelerations, np.zeros((2, 3)))
    assert sc.study == {"caspr_cable_names": ["winch 1a", "winch 1b", "winch 2a", "winch 2b",
                                              "winch 3a", "winch 3b"],
                        "caspr_skipped_trajectories": [],
                        "caspr_trajectory_kinds": {"tilt": "quintic_spline_trajectory"}}
    plain = import_caspr(b, INV[1], CABLE)               # no trajectories, no operational sets
    assert plain.trajectories == {} and plain.study == {
        "caspr_cable_names": ["winch 1a", "winch 1b", "winch 2a", "winch 2b", "winch 3a",
                              "winch 3b"]}
    assert caspr_comments(plain, b, INV[1]) == [
        f"{STEWART}: imported from CASPR",
        f"bodies: {b}",
        f"cables: {INV[1]}",
        f"{STEWART} from CASPR (robot_bodies.xml, InvertedStewart_cables.xml, cable set "
        f"'octahedron', joint S_EULER_XYZ), inertia_convention 'products'",
        "CASPR holds no cable mass or EA: [cable] holds the values given at import.",
        "free DOFs of the joint: rx, ry, rz",
        "Units: SI.",
    ]


def test_translation_joint_rates_keep_all_three_axes(tmp_path):
    """T_XYZ (q = x y z): P = origin + q, no rotation; the rates of P are q_dot / q_ddot
    whole, z included; the workspace box is q_min / q_max moved by the origin."""
    b = _bodies(tmp_path, '<joint type="T_XYZ" q_initial="0.1 0.2 -0.3" q_min="-1 -2 -1.5" '
                          'q_max="1 2 0.5"/>')
    t = _trajectories(tmp_path, _quintic("0 0 0", "0.2 -0.1 0.4", "0.05 -0.1 0.3",
                                         "0.01 0.02 -0.5", "climb"))
    sc = import_caspr(b, INV[1], CABLE, trajectories_xml=t)
    np.testing.assert_allclose(sc.pose.position, [0.6, -0.3, 1.2], atol=1e-15)
    np.testing.assert_array_equal(sc.pose.rotation, [0.0, 0.0, 0.0])
    assert sc.workspace_box == (-0.5, 1.5, -2.5, 1.5, 0.0, 2.0)
    p = sc.trajectories["climb"]
    np.testing.assert_allclose(p.positions, [[0.5, -0.5, 1.5], [0.7, -0.6, 1.9]], atol=1e-15)
    np.testing.assert_array_equal(p.rotations, np.zeros((2, 3)))
    np.testing.assert_array_equal(p.velocities, [[0.0, 0.0, 0.0], [0.05, -0.1, 0.3]])
    np.testing.assert_array_equal(p.accelerations, [[0.0, 0.0, 0.0], [0.01, 0.02, -0.5]])
    comments = caspr_comments(sc, b, INV[1], t)
    assert comments[3] == f"trajectories: {t}"
    assert comments[6:] == ["free DOFs of the joint: x, y, z",
                            "[workspace] box: the joint's q_min / q_max (translations).",
                            "Units: SI."]


def test_spatial_joint_rates_are_the_translation_part_of_q_dot_and_q_ddot(tmp_path):
    """SPATIAL_EULER_XYZ (q = x y z alpha beta gamma): the rates of P are the first three
    entries of q_dot and q_ddot (x, y and z each), the Euler angles land in the rotation."""
    t = _trajectories(tmp_path, _quintic("0 0 1.5 0 0 0", "0.1 0.2 1.8 0.3 0 0",
                                         "0.1 -0.2 0.3 0 0 0", "-0.4 0.5 -0.6 0 0 0"))
    p = import_caspr(*INV, CABLE, trajectories_xml=t).trajectories["q"]
    np.testing.assert_array_equal(p.positions, [[0.0, 0.0, 1.5], [0.1, 0.2, 1.8]])
    np.testing.assert_allclose(p.rotations, [[0.0, 0.0, 0.0], [0.3, 0.0, 0.0]], atol=1e-15)
    np.testing.assert_array_equal(p.velocities, [[0.0, 0.0, 0.0], [0.1, -0.2, 0.3]])
    np.testing.assert_array_equal(p.accelerations, [[0.0, 0.0, 0.0], [-0.4, 0.5, -0.6]])


@pytest.mark.parametrize("joint, n_trans", [("SPATIAL_EULER_XYZ", 3), ("S_EULER_XYZ", 0)])
@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("tag, what", [("q_dot", "velocity"), ("q_ddot", "acceleration")])
def test_each_nonzero_orientation_rate_is_refused_by_name(tmp_path, joint, n_trans, axis,
                                                          tag, what):
    """A nonzero rate of rx, ry or rz (velocity or acceleration) at a waypoint is refused
    as CASPR does, the message naming the file, the trajectory and the kind of rate; the
    rotation rates follow the translation ones (SPATIAL_EULER_XYZ) or stand alone."""
    b = INV[0] if joint == "SPATIAL_EULER_XYZ" else _bodies(
        tmp_path, '<joint type="S_EULER_XYZ" q_initial="0 0 0"/>')
    n = n_trans + 3
    rates = {"q_dot": ["0"] * n, "q_ddot": ["0"] * n}
    rates[tag][n_trans + axis] = "0.25"
    q = " ".join(["0.1"] * n)
    t = _trajectories(tmp_path, _quintic(" ".join(["0"] * n), q, " ".join(rates["q_dot"]),
                                         " ".join(rates["q_ddot"]), "turn"))
    with pytest.raises(CasprError) as exc:
        import_caspr(b, INV[1], CABLE, trajectories_xml=t)
    assert str(exc.value) == (f"{t}: trajectory 'turn': nonzero orientation {what} at "
                              f"waypoint 1; {REFUSAL}")


def test_comments_of_the_inverted_stewart_scene_line_by_line(scene):
    """caspr_comments of the scene with trajectories and operational spaces: the name, the
    four source files, the description (files, cable set, joint, convention), the cable
    note, the six free DOFs in DOF order, the box note, one line per operational set
    (kind, offset, axes of each marker), one per trajectory not read (its reason), units."""
    assert caspr_comments(scene, INV[0], INV[1], TRAJ, OPS) == [
        f"{STEWART}: imported from CASPR",
        f"bodies: {INV[0]}",
        f"cables: {INV[1]}",
        f"trajectories: {TRAJ}",
        f"operational spaces: {OPS}",
        f"{STEWART} from CASPR (InvertedStewart_bodies.xml, InvertedStewart_cables.xml, cable "
        f"set 'octahedron', joint SPATIAL_EULER_XYZ), inertia_convention 'products'",
        "CASPR holds no cable mass or EA: [cable] holds the values given at import.",
        "free DOFs of the joint: x, y, z, rx, ry, rz",
        "[workspace] box: the joint's q_min / q_max (translations).",
        "operational set 'tool': position of the point [0.0, 0.0, -0.2] m, axes xyz",
        "operational set 'tool_pose': pose_euler_xyz of the point [0.0, 0.0, -0.2] m, "
        "axes xyzabg",
        "trajectory 'recorded' not read: samples in the file 'recorded.traj', not read",
        "trajectory 'tool_path' not read: an operational-space trajectory (a marker's "
        "path), not read",
        "Units: SI.",
    ]


def test_operational_markers_and_trajectory_kinds_reach_the_study(scene):
    """study holds each marker's kind, name, offset [m] and active axes per operational
    set, the cable names, the trajectories not read and the kind of each one read."""
    assert scene.study == {
        "caspr_cable_names": ["winch 1a", "winch 1b", "winch 2a", "winch 2b", "winch 3a",
                              "winch 3b"],
        "caspr_skipped_trajectories": [
            ["recorded", "samples in the file 'recorded.traj', not read"],
            ["tool_path", "an operational-space trajectory (a marker's path), not read"]],
        "caspr_trajectory_kinds": {
            "lift_and_turn": "quintic_spline_trajectory", "square": "linear_spline_trajectory",
            "swing": "cubic_spline_trajectory",
            "mean_speed": "cubic_spline_average_velocity_trajectory",
            "blend": "parabolic_blend_trajectory"},
        "caspr_operational_sets": {
            "tool": [{"kind": "position", "name": "tool tip", "offset": [0.0, 0.0, -0.2],
                      "axes": "xyz"}],
            "tool_pose": [{"kind": "pose_euler_xyz", "name": "tool frame",
                           "offset": [0.0, 0.0, -0.2], "axes": "xyzabg"}]},
    }


def test_scene_name_defaults_to_the_link_and_a_given_name_names_scene_and_robot():
    """Without name the scene and its robot carry the CASPR link's name; name= renames
    both (and the first comment line), the description still names the link."""
    sc = import_caspr(*INV, CABLE)
    assert sc.name == STEWART and sc.robot.name == STEWART
    named = import_caspr(*INV, CABLE, name="crane")
    assert named.name == "crane" and named.robot.name == "crane"
    assert named.robot.n_cables == 6
    np.testing.assert_array_equal(named.robot.anchors, sc.robot.anchors)
    assert named.description.startswith(f"{STEWART} from CASPR (")
    assert caspr_comments(named, *INV)[0] == "crane: imported from CASPR"


def test_tensor_convention_reaches_the_warning_description_and_inertia():
    """inertia_convention="tensor" on CoGiRo (Ixy, Ixz, Iyz = -0.453, 3.012, -1.539): one
    warning, at the caller's line, saying the values were read as tensor entries; the
    description names the convention and the robot's off-diagonal entries are the printed
    values unchanged."""
    cog = (DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml")
    with pytest.warns(InertiaConventionWarning) as rec:
        sc = import_caspr(*cog, CABLE, inertia_convention="tensor")
    assert [str(w.message) for w in rec] == [
        f"{cog[0]}: Ixy, Ixz, Iyz read as tensor entries (CASPR's code; products of inertia "
        f"would change sign): inertia_convention='tensor'"]
    assert _place(rec[0].filename) == _place(__file__)
    assert sc.description == ("CoGiRo from CASPR (CoGiRo_bodies.xml, CoGiRo_cables.xml, "
                              "cable set 'original', joint SPATIAL_EULER_XYZ), "
                              "inertia_convention 'tensor'")
    inertia = sc.robot.platform.inertia
    assert (inertia[0, 1], inertia[0, 2], inertia[1, 2]) == (-0.453, 3.012, -1.539)
