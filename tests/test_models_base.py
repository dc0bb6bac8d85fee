"""The interface every model shares (dynstiff/models/base.py)."""

import re
from dataclasses import replace

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.models.base import PlatformModel, require_model


class Toy(PlatformModel):
    rung = "toy"

    def __init__(self, eq):
        self._init_platform(eq.robot, eq, eq.pose)
        self.K = np.eye(self.n_free)
        self._freeze()


def test_platform_fields_and_immutability(cogiro_eq):
    m = Toy(cogiro_eq)
    assert m.free_dofs == ("x", "y", "z", "rx", "ry", "rz") and m.n_free == 6
    np.testing.assert_array_equal(m.free_index, np.arange(6))
    assert m.platform_mass[0, 0] == pytest.approx(cogiro_eq.robot.platform.mass)
    np.testing.assert_array_equal(m.cable_mode_count([0.0, 1e3]), [0, 0])
    assert m.undamped() is m and not m.damped
    with pytest.raises(AttributeError, match="immutable"):
        m.K = None
    with pytest.raises(ValueError):
        m.K[0, 0] = 2.0


def test_require_model_names_what_is_missing(cogiro_eq):
    with pytest.raises(InvalidParameterError, match="dynamic_stiffness"):
        require_model(cogiro_eq)
    mm = ds.LumpedMassModel(cogiro_eq.robot, cogiro_eq.unstretched_lengths, 3)
    with pytest.raises(InvalidParameterError, match="LumpedLinearModel"):
        require_model(mm)
    fm = ds.FrequencyModel(cogiro_eq)
    assert require_model(fm) is fm


class DampedToy(Toy):
    def __init__(self, eq, **attrs):
        self._init_platform(eq.robot, eq, eq.pose)
        self.K = np.eye(self.n_free)
        self.damped = True
        for k, v in attrs.items():
            setattr(self, k, v)
        self._freeze()


def test_repr_names_the_class_rung_cables_dofs_pose_and_damping(cogiro_eq):
    assert repr(Toy(cogiro_eq)) == (
        "Toy(rung='toy', 8 cables, free ('x', 'y', 'z', 'rx', 'ry', 'rz'), "
        "Pose(position=[0, 0, 1] m, rotation=[0, 0, 0] rad), undamped)")


def test_damping_text_lists_each_part(cogiro_eq):
    """The analysis' platform modal ratio and cable loss factor, then the cables' own
    viscous damping and loss factor (their largest), each only when not zero."""
    m = DampedToy(cogiro_eq, platform_damping_ratio=0.02, cable_loss_factor=0.005)
    assert m.damping_text() == "damped: platform modal ratio 0.02, cable loss factor 0.005"
    assert DampedToy(cogiro_eq, cable_loss_factor=0.005).damping_text() == (
        "damped: cable loss factor 0.005")
    assert DampedToy(cogiro_eq, platform_damping_ratio=0.02).damping_text() == (
        "damped: platform modal ratio 0.02")
    robot = cogiro_eq.robot
    cables = [replace(c, viscous_damping=3.0 * (i == 2), loss_factor=0.01 * (i == 5))
              for i, c in enumerate(robot.cables)]
    eq = replace(cogiro_eq, robot=replace(robot, cables=tuple(cables)))
    assert DampedToy(eq).damping_text() == (
        "damped: cable viscous damping up to 3 N s/m^2, cables' own loss factor up to 0.01")


def test_require_model_messages_say_how_to_build_one(cogiro_eq):
    """An equilibrium is told to build a model; a lumped-mass model to linearise first."""
    with pytest.raises(InvalidParameterError, match=re.escape(
            "model must be a model of the ladder, got Equilibrium without "
            "'dynamic_stiffness' (build one with build_model(equilibrium, rung))")):
        require_model(cogiro_eq)
    mm = ds.LumpedMassModel(cogiro_eq.robot, cogiro_eq.unstretched_lengths, 3)
    with pytest.raises(InvalidParameterError, match=re.escape(
            "model must be a model of the ladder, got LumpedMassModel without "
            "'dynamic_stiffness': linearise it first, LumpedLinearModel(m, m.equilibrium()) "
            "or build_model(eq, 'lumped')")):
        require_model(mm)


def test_require_equilibrium_names_what_it_got():
    from dynstiff.models.base import require_equilibrium
    with pytest.raises(InvalidParameterError, match=re.escape(
            "equilibrium must be an Equilibrium (from Robot.equilibrium or "
            "Scene.equilibrium), got str without 'robot'")):
        require_equilibrium("cogiro")
