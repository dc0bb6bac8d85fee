"""Trajectories and their quasi-static cable lengths (dynstiff/timedomain/trajectory.py)."""

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.robot.waypoints import WaypointPath
from dynstiff.timedomain.trajectory import circle, following, line, quasi_static_lengths


def test_line_with_ramps_covers_its_length_at_its_speed():
    """(1 - cos)/2 ramps of R seconds: duration L/v + R, cruise speed v, zero end speeds."""
    tr = line([0, 0, 1], [2, 1, 1], speed=0.5, ramp=1.0)
    L = np.sqrt(5.0)
    assert tr.duration == pytest.approx(L / 0.5 + 1.0, rel=1e-14)
    p0, _ = tr.at(0.0)
    p1, _ = tr.at(tr.duration)
    np.testing.assert_allclose(p0[0], [0, 0, 1], atol=1e-15)
    np.testing.assert_allclose(p1[0], [2, 1, 1], atol=1e-12)
    h = 1e-6
    t_mid = tr.duration / 2
    v_mid = (tr.at(t_mid + h)[0] - tr.at(t_mid - h)[0])[0] / (2 * h)
    assert np.linalg.norm(v_mid) == pytest.approx(0.5, rel=1e-8)
    v_start = (tr.at(h)[0] - tr.at(0.0)[0])[0] / h
    assert np.linalg.norm(v_start) < 1e-5
    with pytest.raises(InvalidParameterError, match="ramp"):
        line([0, 0, 1], [1, 0, 1], speed=1.0, ramp=2.0)


def test_circle_stays_on_its_radius_and_turns_counter_clockwise():
    tr = circle([0, 0, 1], radius=0.5, speed=0.25, turns=0.25)
    pos = tr.positions
    np.testing.assert_allclose(np.linalg.norm(pos[:, :2], axis=1), 0.5, rtol=1e-14)
    np.testing.assert_allclose(pos[:, 2], 1.0)
    np.testing.assert_allclose(pos[-1], [0.0, 0.5, 1.0], atol=1e-12)     # a quarter turn


def test_quasi_static_lengths_are_inverse_statics_at_every_sample(cogiro):
    tr = line([0, 0, 1], [1, 0, 1], speed=1.0, samples_per_s=2.0)
    L, T = quasi_static_lengths(cogiro.robot, tr)
    assert L.shape == T.shape == (tr.times.size, 8)
    for k in (0, tr.times.size - 1):
        eq = cogiro.robot.equilibrium(pose=np.concatenate([tr.positions[k], tr.rotations[k]]))
        np.testing.assert_allclose(L[k], eq.unstretched_lengths, rtol=1e-12)
        np.testing.assert_allclose(T[k], eq.tensions, rtol=1e-10)


def test_following_a_waypoint_path_samples_it_and_every_waypoint():
    path = WaypointPath([0.0, 0.75, 2.0], [[0, 0, 1.0], [0.3, 0, 1.0], [0.3, 0.2, 1.2]],
                           np.zeros((3, 3)), "quintic", name="w")
    tr = following(path, samples_per_s=2.0)
    assert set(path.times) <= set(tr.times) and tr.name == "w" and tr.duration == 2.0
    np.testing.assert_allclose(tr.times, [0.0, 0.5, 0.75, 1.0, 1.5, 2.0])
    np.testing.assert_array_equal(tr.at([0.3, 1.7])[0], path.at([0.3, 1.7])[0])
    with pytest.raises(InvalidParameterError, match="waypoints must be a dynstiff"):
        following("w")


@pytest.mark.parametrize("call, message", [
    (lambda: line([np.nan, 0, 0], [1, 0, 1], 0.5), r"^start must be finite, got \[nan"),
    (lambda: line([0, 0, 1], [True, 0, 1], 0.5), "^end must be real numbers, not booleans"),
    (lambda: circle([np.nan, 0, 1], 1.0, 0.5), r"^center must be finite, got \[nan"),
    (lambda: circle([0, 0, 1], 1.0, 0.5, start_angle=np.nan), "^start_angle must be finite"),
    (lambda: circle([0, 0, 1], 1.0, 0.5, start_angle="a"),
     "^start_angle must be a real number, got 'a'")])
def test_a_path_names_the_argument_that_is_not_a_number(call, message):
    """A NaN start was said as "length must be finite", a NaN start angle as "positions
    must be finite": arguments the user did not give."""
    with pytest.raises(InvalidParameterError, match=message):
        call()
