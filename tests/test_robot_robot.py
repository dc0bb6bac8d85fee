"""The robot (dynstiff/robot/robot.py): bad inputs raise naming the field, and each stiffness of a
robot at a pose has its own name (theory.md §4)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError


def test_bad_robot_inputs_raise_naming_field(cogiro):
    r = cogiro.robot
    with pytest.raises(InvalidParameterError, match="anchors"):
        ds.Robot(r.anchors[:5], r.attachments[:5], r.cables[:5], r.platform)
    A = r.anchors.copy()
    A[3] = A[2]
    with pytest.raises(InvalidParameterError, match="anchors 2 and 3"):
        ds.Robot(A, r.attachments, r.cables, r.platform)
    with pytest.raises(InvalidParameterError, match="inertia"):
        ds.Platform(10.0, inertia=np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(InvalidParameterError, match="inertia"):
        ds.Platform(10.0, inertia=np.diag([1.0, 1.0, 5.0]))      # triangle inequality
    with pytest.raises(InvalidParameterError, match="free_dofs"):
        ds.Platform(10.0, free_dofs=("x", "q"))


def test_each_stiffness_has_its_own_name(cogiro_eq):
    """One name per quantity: the 3x3 end stiffness of one cable (CatenaryState.end_stiffness),
    the 6x6 platform stiffness at a pose (Robot/Equilibrium.platform_stiffness) and a
    model's massless_stiffness on its free DOFs; the catenary rung assembles the first
    into the second."""
    s = cogiro_eq.states[0]
    assert s.end_stiffness.shape == (3, 3)
    K6 = cogiro_eq.platform_stiffness()
    np.testing.assert_allclose(
        K6, cogiro_eq.robot.platform_stiffness(cogiro_eq.pose, cogiro_eq.states), rtol=0)
    cat = ds.build_model(cogiro_eq, "catenary")
    np.testing.assert_allclose(cat.massless_stiffness(), 0.5 * (K6 + K6.T), rtol=1e-12)
    for obj in (s, cogiro_eq, cogiro_eq.robot, cat):
        assert not hasattr(obj, "static_stiffness") and not hasattr(obj, "dof_names")


def test_coordinates_beyond_1e100_m_are_named(cogiro):
    r = cogiro.robot
    far = r.attachments.copy()
    far[0, 0] = 1.0000000000000002e100
    with pytest.raises(InvalidParameterError, match="attachments must lie within"):
        ds.Robot(r.anchors, far, r.cables, r.platform)
    with pytest.raises(InvalidParameterError, match="pose position"):
        ds.Pose([1e101, 0.0, 0.0])
