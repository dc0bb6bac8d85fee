"""The interface every model shares (dynstiff/models/base.py)."""

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
