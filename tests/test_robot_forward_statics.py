"""Forward statics (dynstiff/robot/forward_statics.py): the pose for given unstretched
lengths, and its kinematic start."""

import numpy as np

import dynstiff as ds
from dynstiff.robot.forward_statics import _kinematic_guess, forward_statics


def test_kinematic_start_makes_the_chords_a_little_shorter_than_the_lengths():
    """The start fits the free DOFs so that straight chords are 0.999 L0 (taut cables):
    planar2 has as many cables as free DOFs, so the fit is exact."""
    scene = ds.load_scene("planar2")
    robot = scene.robot
    L0 = scene.equilibrium().unstretched_lengths
    pose = _kinematic_guess(robot, L0)
    B, _ = robot.attachment_points(pose)
    np.testing.assert_allclose(np.linalg.norm(robot.anchors - B, axis=1), 0.999 * L0,
                               rtol=1e-9)


def test_forward_statics_returns_the_pose_of_the_lengths():
    """CoGiRo (all six DOFs free) at a pose off centre, given back its own unstretched
    lengths, is found again from the kinematic start (to 1e-8 m and rad)."""
    robot = ds.load_scene("cogiro").robot
    eq = robot.equilibrium(pose=ds.Pose([1.0, -0.5, 1.5], [0.02, -0.01, 0.03]))
    got = forward_statics(robot, eq.unstretched_lengths)
    np.testing.assert_allclose(got.pose.position, eq.pose.position, rtol=0, atol=1e-8)
    np.testing.assert_allclose(got.pose.rotation, eq.pose.rotation, rtol=0, atol=1e-8)


def test_a_held_rotation_needs_the_initial_pose():
    """CoGiRo with ry held (its attachments are off the reference point, so rotations
    matter): without an initial pose the held angle is unknown, and the call is refused
    naming the free DOFs."""
    import dataclasses

    import pytest

    from dynstiff.errors import InvalidParameterError
    robot = ds.load_scene("cogiro").robot
    held = dataclasses.replace(robot, platform=dataclasses.replace(
        robot.platform, free_dofs=("x", "y", "z", "rx", "rz")))
    L0 = ds.load_scene("cogiro").equilibrium().unstretched_lengths
    with pytest.raises(InvalidParameterError,
                       match=r"^initial_pose is required when DOFs are held \(free_dofs="
                             r"\('x', 'y', 'z', 'rx', 'rz'\)\): it fixes the held "
                             r"coordinates$"):
        forward_statics(held, L0)


def test_the_residual_is_relative_to_the_platform_weight():
    """With no iteration allowed the start is returned as a failure whose residual is
    |W_free| / (m max(g, 1)), written out here for g = 1.5 m/s^2 (a weaker gravity)."""
    import dataclasses

    import pytest

    from dynstiff.errors import ConvergenceError
    scene = ds.load_scene("cogiro")
    robot = dataclasses.replace(scene.robot, g=1.5)
    L0 = scene.equilibrium().unstretched_lengths
    pose = ds.Pose([0.1, 0.0, 1.0])
    W = robot.wrench(pose, robot.cable_states(pose, L0))
    want = np.linalg.norm(W) / (robot.platform.mass * 1.5)
    with pytest.raises(ConvergenceError, match="forward statics did not converge") as err:
        forward_statics(robot, L0, initial_pose=pose, max_iter=0)
    assert err.value.residual == pytest.approx(want, rel=1e-12)


def test_a_singular_stiffness_is_a_failure_with_its_residual(monkeypatch):
    """When the stiffness cannot be solved the iteration stops with a ConvergenceError
    giving the residual of the start (it never returns without a pose)."""
    import pytest

    from dynstiff.errors import ConvergenceError
    from dynstiff.robot.robot import Robot
    scene = ds.load_scene("cogiro")
    L0 = scene.equilibrium().unstretched_lengths
    pose = ds.Pose([0.1, 0.0, 1.0])
    monkeypatch.setattr(Robot, "platform_stiffness", lambda self, p, s: np.zeros((6, 6)))
    with pytest.raises(ConvergenceError, match="wrench residual") as err:
        forward_statics(scene.robot, L0, initial_pose=pose)
    assert err.value.residual > 1e-6
