"""Trajectories and their quasi-static cable lengths (dynstiff/timedomain/trajectory.py)."""

import numpy as np
import pytest
from conftest import point_mass_robot

from dynstiff.errors import InvalidParameterError
from dynstiff.robot.waypoints import WaypointPath
from dynstiff.timedomain.damping import TimeDamping
from dynstiff.timedomain.trajectory import (
    Trajectory,
    circle,
    following,
    line,
    quasi_static_lengths,
    track,
)


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


def test_a_sampled_trajectory_is_interpolated_linearly_and_held_after_its_end():
    """Two samples, 2 s apart, P from (0, 0, 1) to (2, 4, 1) m and the rotation about z from
    0 to 0.2 rad: at 0.5 s a quarter of the way, (0.5, 1, 1) m and 0.05 rad; at 3 s (after
    the end) the last sample. Integer and list inputs are stored as float arrays."""
    tr = Trajectory([0, 2], [[0, 0, 1], [2, 4, 1]], [[0, 0, 0], [0, 0, 0.2]])
    assert tr.positions.dtype == np.float64 and tr.times.dtype == np.float64
    assert isinstance(tr.rotations, np.ndarray)
    np.testing.assert_array_equal(tr.rotations, [[0, 0, 0], [0, 0, 0.2]])
    P, R = tr.at([0.5, 3.0])
    np.testing.assert_allclose(P, [[0.5, 1.0, 1.0], [2.0, 4.0, 1.0]], rtol=1e-15)
    np.testing.assert_allclose(R, [[0.0, 0.0, 0.05], [0.0, 0.0, 0.2]], rtol=1e-15)


def test_a_trajectory_as_a_table():
    """Columns time [s], x y z [m], rx ry rz [rad], in this order, holding the samples."""
    tr = Trajectory([0.0, 1.0], [[1, 2, 3], [4, 5, 6]], [[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]])
    df = tr.to_frame()
    assert list(df.columns) == ["time [s]", "x [m]", "y [m]", "z [m]",
                                "rx [rad]", "ry [rad]", "rz [rad]"]
    np.testing.assert_array_equal(df.to_numpy(), [[0.0, 1, 2, 3, 0.1, 0.2, 0.3],
                                                  [1.0, 4, 5, 6, 0.4, 0.5, 0.6]])


@pytest.mark.parametrize("times, message", [
    ([0.0], r"^times must be strictly increasing from 0 \[s\] with >= 2 samples, "
            r"got array\(\[0\.\]\)$"),
    ([0.0, 1.0, 1.0], r"^times must be strictly increasing from 0 \[s\] with >= 2 samples, "
                      r"got array\(\[0\., 1\., 1\.\]\)$")])
def test_a_trajectory_needs_two_samples_at_distinct_times(times, message):
    """A single sample is no path, and a repeated time leaves the interpolation undefined."""
    n = len(times)
    with pytest.raises(InvalidParameterError, match=message):
        Trajectory(times, np.zeros((n, 3)), np.zeros((n, 3)))


@pytest.mark.parametrize("call, message", [
    (lambda: line([0, 0, 1], [0, 0, 1], 0.5),
     r"^start and end must be two different points \(3,\) \[m\], got \[0, 0, 1\], "
     r"\[0, 0, 1\]$"),
    (lambda: line([0, 0, 1], [1, 0, 1], 0.5, samples_per_s=0.0),
     r"^samples_per_s must be > 0, got 0\.0$"),
    (lambda: circle([0, 0, 1], -1.0, 0.5), r"^radius must be > 0, got -1\.0$"),
    (lambda: circle([0, 0, 1], 1.0, 0.5, turns=0.0), r"^turns must be > 0, got 0\.0$"),
    (lambda: quasi_static_lengths("robot", line([0, 0, 1], [1, 0, 1], 0.5)),
     r"^robot must be a Robot, got str$"),
    (lambda: track(point_mass_robot(), [0.0, 1.0]),
     r"^trajectory must be a Trajectory, got list$"),
    (lambda: track(point_mass_robot(), line([0, 0, 1], [1, 0, 1], 0.5), t_end=-1.0),
     r"^t_end must be > 0, got -1\.0$")])
def test_a_path_or_a_tracking_run_names_the_argument_out_of_range(call, message):
    """Each refused argument is named, with the value given."""
    with pytest.raises(InvalidParameterError, match=message):
        call()


def test_quasi_static_lengths_report_their_progress():
    """progress(done, total) after each of the k samples: (1, k), (2, k), ..., (k, k)."""
    tr = line([0, 0, 1], [0.2, 0, 1], speed=0.5, samples_per_s=10.0)
    calls = []
    quasi_static_lengths(point_mass_robot(), tr, progress=lambda d, n: calls.append((d, n)))
    k = tr.times.size
    assert k == 5 and calls == [(j, k) for j in range(1, k + 1)]


def _small_move():
    """2 cm along x at 0.1 m/s with 0.1 s ramps (duration 0.3 s), sampled every 0.05 s."""
    return line([0, 0, 1], [0.02, 0, 1], speed=0.1, ramp=0.1, samples_per_s=20.0)


@pytest.fixture(scope="module")
def tracked():
    """The 3-cable point-mass robot (3 segments per cable, dt = 10 ms) along the small move."""
    return track(point_mass_robot(), _small_move(), segments=3, dt=1e-2)


def test_tracking_starts_at_the_static_offset_and_tabulates_the_deviation(tracked):
    """The run starts at the lumped model's equilibrium and the path at its start, so the
    deviation at t = 0 is the static offset [m] (nonzero: a 3-segment chain does not hang
    as the catenary); the table's deviation is the distance between its simulated and
    desired x y z columns."""
    assert 0.0 < tracked.static_offset < 1e-3
    assert tracked.deviation[0] == pytest.approx(tracked.static_offset, rel=1e-12, abs=1e-15)
    df = tracked.to_frame()
    d = np.sqrt(sum((df[f"{n} [m]"] - df[f"{n} desired [m]"]) ** 2 for n in "xyz"))
    np.testing.assert_allclose(df["deviation [m]"].to_numpy(dtype=float), d.to_numpy(),
                               rtol=1e-12, atol=1e-18)
    assert tracked.response.times[-1] == pytest.approx(0.3, abs=1e-12)


def test_damping_given_to_track_dissipates_energy(tracked):
    """Without damping (the cables have no viscous damping) no energy is dissipated; with
    mass-proportional Rayleigh damping (alpha = 5 1/s) the moving platform loses some."""
    assert tracked.response.energy.dissipated[-1] == 0.0
    damped = track(point_mass_robot(), _small_move(), segments=3, dt=1e-2,
                   damping=TimeDamping(alpha=5.0), t_end=0.1)
    assert damped.response.energy.dissipated[-1] > 0.0


def test_constant_commanded_lengths_hold_a_platform_on_nearly_inextensible_cables():
    """Cables of EA = 1.6e9 N (10 segments each) commanded at their starting lengths for
    50 ms: the spring forces are rounded to about EA eps, and the run converges with a
    tolerance no finer than that rounding; the platform stays at its equilibrium (to 1e-9 m)
    and the result holds the lengths given, not the quasi-static ones."""
    rob = point_mass_robot(E=2e14)
    tr = _small_move()
    L, _ = quasi_static_lengths(rob, tr)
    held = np.tile(L[0], (tr.times.size, 1))
    res = track(rob, tr, segments=10, dt=1e-2, lengths=held.tolist(), t_end=0.05)
    assert res.response.times[-1] == pytest.approx(0.05, abs=1e-12)
    np.testing.assert_array_equal(res.lengths, held)
    assert np.abs(res.response.pose - res.response.pose[0]).max() < 1e-9
    with pytest.raises(InvalidParameterError,
                       match=r"^lengths must have shape \(7, 3\) \(one row per path sample\), "
                             r"got \(6, 3\)$"):
        track(rob, tr, segments=10, dt=1e-2, lengths=held[1:], t_end=0.05)
