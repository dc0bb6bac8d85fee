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
from dynstiff.scenes.caspr import caspr_siblings

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
