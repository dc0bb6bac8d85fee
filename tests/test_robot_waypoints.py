"""Waypoint paths (dynstiff/robot/waypoints.py, theory.md §15.8): the position laws against
CASPR's way of computing them (each segment's polynomial solved from its end conditions,
Spline.m), the orientation on the geodesic between waypoint orientations, the parabolic
blend's speeds, and bad inputs."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from dynstiff.errors import InvalidParameterError
from dynstiff.robot.waypoints import WaypointPath


def caspr_spline(ya, va, aa, yb, vb, ab, ta, tb, t, law):
    """CASPR's Spline.Cubic/QuinticInterpolation: solve the coefficients of the polynomial
    in absolute time from the end conditions (T \\ b), then evaluate."""
    if law == "linear":
        M = np.array([[1, ta], [1, tb]])
        b = np.array([ya, yb])
    elif law == "cubic":
        M = np.array([[1, ta, ta**2, ta**3], [0, 1, 2 * ta, 3 * ta**2],
                      [1, tb, tb**2, tb**3], [0, 1, 2 * tb, 3 * tb**2]])
        b = np.array([ya, va, yb, vb])
    else:
        def rows(x):
            return [[1, x, x**2, x**3, x**4, x**5], [0, 1, 2 * x, 3 * x**2, 4 * x**3, 5 * x**4],
                    [0, 0, 2, 6 * x, 12 * x**2, 20 * x**3]]
        M = np.array(rows(ta) + rows(tb))
        b = np.array([ya, va, aa, yb, vb, ab])
    c = np.linalg.solve(M, b)
    return sum(ck * t**k for k, ck in enumerate(c))


@pytest.mark.parametrize("law", ["linear", "cubic", "quintic"])
def test_position_laws_equal_caspr_polynomials(law):
    rng = np.random.default_rng(1)
    times = np.array([0.0, 1.5, 4.0])
    P = rng.normal(size=(3, 3))
    V = rng.normal(size=(3, 3)) if law != "linear" else None
    A = rng.normal(size=(3, 3)) if law == "quintic" else None
    path = WaypointPath(times, P, np.zeros((3, 3)), law, V, A)
    t = np.linspace(0.0, 4.0, 41)
    got, rot = path.at(t)
    Vz = np.zeros((3, 3)) if V is None else V
    Az = np.zeros((3, 3)) if A is None else A
    for j, tj in enumerate(t):
        s = 0 if tj < 1.5 else 1
        ref = [caspr_spline(P[s, c], Vz[s, c], Az[s, c], P[s + 1, c], Vz[s + 1, c],
                            Az[s + 1, c], times[s], times[s + 1], tj, law) for c in range(3)]
        np.testing.assert_allclose(got[j], ref, rtol=1e-9, atol=1e-9)
    np.testing.assert_array_equal(rot, 0.0)


def test_orientation_turns_on_the_geodesic_with_the_law():
    """From R_a (a tilt about x) to R_b = R_a R_z(90 deg), quintic: R_a^T R(t) is a
    rotation about z by sigma(tau) 90 deg, sigma = 10 tau^3 - 15 tau^4 + 6 tau^5."""
    Ra = Rotation.from_rotvec([0.3, 0.0, 0.0])
    Rb = Ra * Rotation.from_rotvec([0.0, 0.0, np.pi / 2])
    path = WaypointPath([0.0, 2.0], np.zeros((2, 3)), np.vstack([Ra.as_rotvec(),
                                                                Rb.as_rotvec()]))
    tau = np.linspace(0.0, 1.0, 11)
    _, R = path.at(2.0 * tau)
    rel = (Ra.inv() * Rotation.from_rotvec(R)).as_rotvec()
    sigma = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    np.testing.assert_allclose(rel, np.c_[0 * tau, 0 * tau, sigma * np.pi / 2], atol=1e-12)


def test_parabolic_blend_speed_is_continuous_and_constant_between_blends():
    path = WaypointPath([0.0, 4.0], [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], np.zeros((2, 3)),
                        "parabolic_blend", blend_times=[1.0])
    t = np.linspace(0.0, 4.0, 4001)
    x = path.at(t)[0][:, 0]
    v = np.gradient(x, t)
    acc = 2.0 / (1.0 * (4.0 - 1.0))                     # reaches speed acc * tb
    np.testing.assert_allclose(v[(t > 1.01) & (t < 2.99)], acc * 1.0, rtol=1e-9)
    assert np.abs(np.diff(v)).max() < 2 * acc * (t[1] - t[0])   # no jump in speed
    assert x[0] == 0.0 and abs(x[-1] - 2.0) < 1e-12


def blend_fraction(t, T, tb):
    """Fraction of a segment covered at time t [s] by a parabolic blend: cruise speed
    1 / (T - tb), reached in tb with constant acceleration and lost the same way at the end."""
    vc = 1.0 / (T - tb)
    if t <= tb:
        return vc * t**2 / (2 * tb)
    if t >= T - tb:
        return 1.0 - vc * (T - t)**2 / (2 * tb)
    return vc * (t - tb / 2)


def test_parabolic_blend_positions_equal_the_blend_formula_on_each_segment():
    """Parabolic blend positions on two segments (blends of 0.5 s and 0.25 s) equal
    P_a + s(t) (P_b - P_a) with s from constant acceleration, cruise, deceleration."""
    times, tbs = [0.0, 2.0, 3.0], [0.5, 0.25]
    P = np.array([[0.0, 1.0, -1.0], [1.0, 3.0, 0.0], [-0.5, 2.0, 2.0]])
    path = WaypointPath(times, P, np.zeros((3, 3)), "parabolic_blend", blend_times=tbs)
    t = np.array([0.25, 0.5, 0.8, 1.0, 1.7, 2.0, 2.1, 2.25, 2.5, 2.8, 3.0])
    got = path.at(t)[0]
    for ti, g in zip(t, got):
        j = 0 if ti < 2.0 else 1
        s = blend_fraction(ti - times[j], times[j + 1] - times[j], tbs[j])
        np.testing.assert_allclose(g, P[j] + s * (P[j + 1] - P[j]), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("law, kw", [("linear", {}), ("cubic", {}), ("quintic", {}),
                                     ("parabolic_blend", dict(blend_times=[0.2, 0.3]))])
def test_a_time_at_a_waypoint_starts_its_segment_at_the_waypoint_exactly(law, kw):
    """At t = 0 and at an inner waypoint's time the position is that waypoint's, exactly."""
    P = np.array([[0.3, 1.1, 0.7], [-0.9, 0.3, 0.1], [0.4, 0.0, 1.0]])
    path = WaypointPath([0.0, 1.0, 2.5], P, np.zeros((3, 3)), law, **kw)
    np.testing.assert_array_equal(path.at([0.0, 1.0])[0], P[:2])


def test_poses_are_equally_spaced_in_time_and_hold_outside():
    path = WaypointPath([0.0, 1.0, 3.0], [[0, 0, 1.0], [1, 0, 1.0], [1, 1, 1.0]],
                        np.zeros((3, 3)), "linear")
    X, t = path.poses(7)
    np.testing.assert_allclose(t, np.linspace(0.0, 3.0, 7))
    np.testing.assert_allclose(X[2, :3], [1.0, 0.0, 1.0])         # t = 1 s, a waypoint
    np.testing.assert_allclose(path.at([-1.0, 9.0])[0], [[0, 0, 1.0], [1, 1, 1.0]])


@pytest.mark.parametrize("n", [1, 0, 2.0, True])
def test_poses_need_an_integer_count_of_at_least_two(n):
    """poses(n) refuses a count below 2, a float or a bool, naming n and its value."""
    path = WaypointPath([0.0, 1.0], np.zeros((2, 3)), np.zeros((2, 3)), "linear")
    with pytest.raises(InvalidParameterError, match=rf"^n must be an integer >= 2, got {n!r}$"):
        path.poses(n)


@pytest.mark.parametrize("kw, match", [
    (dict(times=[0.0, 0.0]), "times must be strictly increasing"),
    (dict(times=[1.0, 2.0]), "from 0"),
    (dict(law="spline"), "law must be one of"),
    (dict(positions=[[0, 0, 0]]), r"positions must be finite, shape \(2, 3\)"),
    (dict(rotations=[[0, 0, 0]]), r"^rotations must be finite, shape \(2, 3\)"),
    (dict(law="linear", velocities=[[1, 0, 0], [0, 0, 0]]), "velocities and accel"),
    (dict(law="linear", accelerations=[[0, 0, 0], [0, 0, 1]]),
     "^velocities and accelerations go with law 'cubic' or 'quintic', not 'linear'$"),
    (dict(law="parabolic_blend", blend_times=[0.2], accelerations=[[1, 0, 0], [0, 0, 0]]),
     "^velocities and accelerations go with law 'cubic' or 'quintic', not 'parabolic_blend'$"),
    (dict(law="cubic", accelerations=[[0, 0, 0], [0, 1, 0]]),
     "^accelerations go with law 'quintic', not 'cubic'$"),
    (dict(law="parabolic_blend"),
     r"^law 'parabolic_blend' needs blend_times \[s\], one per segment$"),
    (dict(law="parabolic_blend", blend_times=[0.6]),
     r"^blend_times must be 1 value > 0 \[s\], each less than half its segment \[1\.0\], "
     r"got array\(\[0\.6\]\)$"),
    (dict(law="parabolic_blend", blend_times=[0.5]), "^blend_times .* less than half"),
    (dict(law="parabolic_blend", blend_times=[0.0]), "^blend_times must be 1 value > 0"),
    (dict(law="parabolic_blend", blend_times=[-0.1]), "^blend_times must be 1 value > 0"),
    (dict(law="parabolic_blend", blend_times=[0.1, 0.1]), "^blend_times must be 1 value > 0"),
    (dict(law="parabolic_blend", blend_times=[True]),
     "^blend_times must be real numbers, not booleans"),
    (dict(law="parabolic_blend", blend_times="abc"),
     r"^blend_times must be 1 value > 0 \[s\], got 'abc'$"),
    (dict(blend_times=[0.1]), "blend_times go with"),
])
def test_bad_waypoints_are_named(kw, match):
    """Each bad argument of a two-waypoint path is refused with a message naming it."""
    args = dict(times=[0.0, 1.0], positions=np.zeros((2, 3)), rotations=np.zeros((2, 3)))
    args.update(kw)
    with pytest.raises(InvalidParameterError, match=match):
        WaypointPath(**args)


@pytest.mark.parametrize("times, positions, message", [
    ([False, True], [[0, 0, 1], [0, 0, 1.1]], "^times must be real numbers, not booleans"),
    ([0, 1.0], [[0, 0, True], [0, 0, 1.1]], "^positions must be real numbers, not booleans"),
    ([0, 1.0], "abc", r"^positions must be finite, shape \(2, 3\) \(one row per waypoint\), "
                      "got 'abc'"),
    (["a", "b"], [[0, 0, 1], [0, 0, 1.1]], r"^times must be strictly increasing from 0 \[s\]")])
def test_waypoints_of_booleans_or_text_are_refused_naming_the_argument(times, positions,
                                                                        message):
    with pytest.raises(InvalidParameterError, match=message):
        WaypointPath(times, positions, np.zeros((2, 3)))


@pytest.mark.parametrize("t, message", [(True, "^t must be real numbers, not booleans"),
                                        (np.nan, r"^t must be finite times \[s\]"),
                                        ("a", r"^t must be times \[s\], got 'a'")])
def test_a_path_is_read_at_times_only(t, message):
    path = WaypointPath([0, 1.0], [[0, 0, 1], [0, 0, 1.1]], np.zeros((2, 3)))
    with pytest.raises(InvalidParameterError, match=message):
        path.at(t)
