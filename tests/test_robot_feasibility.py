"""Why a pose has no statics and what would give it one (dynstiff/robot/feasibility.py,
theory.md §15.7): each cause is provoked on a small robot whose answer is known (an
analytic tension, an independent scan of catenaries), and each remedy the error names is
applied and must make the pose solve."""

from dataclasses import replace

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InfeasiblePoseError, SlackCableError
from dynstiff.robot.feasibility import least_end_tension

POSE = [0.0, 0.0, 1.5, 0.0, 0.0, 0.0]


def hexa(limits):
    """Six anchors, three shared platform points (C3v): one tension distribution, every
    cable at T = m g L / (6 h) at the centre."""
    ang_a = np.radians(np.arange(0.0, 360.0, 60.0))
    ang_b = np.radians([30.0, 30.0, 150.0, 150.0, 270.0, 270.0])
    A = np.c_[3.5 * np.cos(ang_a), 3.5 * np.sin(ang_a), np.full(6, 3.0)]
    b = np.c_[0.9 * np.cos(ang_b), 0.9 * np.sin(ang_b), np.zeros(6)]
    rob = ds.Robot(A, b, ds.Cable(1e-4, 1e7), ds.Platform(100.0, inertia=np.diag([10.0,
                                                                                  10.0, 15.0])),
                   tension_limits=limits)
    T = 100.0 * rob.g * np.linalg.norm(A[0] - (b[0] + [0.0, 0.0, 1.5])) / (6 * 1.5)
    return rob, T


def point_mass(anchors, mass_per_length, limits=(1.0, np.inf)):
    n = len(anchors)
    return ds.Robot(np.asarray(anchors, float), np.zeros((n, 3)),
                    ds.Cable(mass_per_length, 1e6), ds.Platform(20.0, free_dofs=("x", "y", "z")),
                    tension_limits=limits)


UPPER = [[-4.0, -3.0, 5.0], [4.5, -2.0, 5.2], [0.3, 4.0, 4.8]]


def test_too_high_t_min_names_the_largest_that_works():
    """FAST's case: six cables, one distribution below t_min."""
    rob, T = hexa((400.0, np.inf))
    assert 340.0 < T < 345.0
    with pytest.raises(InfeasiblePoseError) as err:
        rob.equilibrium(pose=POSE)
    e = err.value
    assert e.cause == "tension limits" and set(e.remedies) == {"t_min"}
    np.testing.assert_allclose(e.remedies["t_min"], T, rtol=1e-4)
    assert "t_min <= about" in str(e) and "\n" not in str(e)
    assert isinstance(e, SlackCableError)                  # old handlers still catch it
    replace(rob, tension_limits=(0.99 * e.remedies["t_min"], np.inf)).equilibrium(pose=POSE)


def test_too_low_t_max_names_the_smallest_that_works():
    rob, T = hexa((1.0, 300.0))
    with pytest.raises(InfeasiblePoseError) as err:
        rob.equilibrium(pose=POSE)
    assert err.value.cause == "tension limits" and set(err.value.remedies) == {"t_max"}
    np.testing.assert_allclose(err.value.remedies["t_max"], T, rtol=1e-4)
    replace(rob, tension_limits=(1.0, 1.01 * err.value.remedies["t_max"])).equilibrium(
        pose=POSE)


def test_heavy_cable_rising_to_the_platform_names_the_cable_and_two_remedies():
    """IPAnema 2's case: a cable from a low anchor carries its own weight up to the
    platform; the least tension it can have there (an independent scan of catenaries)
    exceeds what the distribution asks. Both remedies (t_min, a lighter cable) work."""
    rob = point_mass(UPPER + [[3.0, 3.0, 0.0]], 0.2)
    pose = [0.0, 0.0, 2.0]
    with pytest.raises(InfeasiblePoseError, match="cable 3 .*not reachable") as err:
        rob.equilibrium(pose=pose)
    e = err.value
    assert e.cause == "cable weight" and e.cable == 3
    assert set(e.remedies) == {"t_min", "mass_per_length"}
    assert e.remedies["t_min"] > 1.0 and e.remedies["mass_per_length"] < 0.2
    replace(rob, tension_limits=(1.05 * e.remedies["t_min"], np.inf)).equilibrium(pose=pose)
    lighter = ds.Cable(0.95 * e.remedies["mass_per_length"], 1e6)
    replace(rob, cables=(lighter,) * 4).equilibrium(pose=pose)


def test_least_end_tension_matches_a_scan_of_cable_lengths():
    A, B = np.array([3.0, 3.0, 0.0]), np.array([0.0, 0.0, 2.0])
    cable = ds.Cable(0.2, 1e6)
    T_star, L_star = least_end_tension(A, B, cable, 9.81)
    chord = np.linalg.norm(B - A)
    scan = [ds.solve_catenary(A, B, L, cable, 9.81).tension_at_end
            for L in np.linspace(chord * 1.0001, chord * 2.0, 1500)]
    assert T_star <= min(scan) + 1e-9 and T_star > min(scan) - 1e-4 * min(scan)
    assert L_star > chord


def test_weight_margins_beyond_t_max_blame_the_cable_weight():
    """Three heavy cables (1 kg/m, one distribution): the tensions at the platform fit
    under t_max, those at the top anchors (T_B + w0 h) do not; weightless cables would
    fit, so the cause is the weight, and the t_max given covers the anchors' tension."""
    rob = point_mass(UPPER, 1.0)
    eq = rob.equilibrium(pose=[0.0, 0.0, 1.0])
    t_max = 0.5 * (eq.tensions.max() + eq.max_tensions.max())
    with pytest.raises(InfeasiblePoseError, match="the cables' weight") as err:
        replace(rob, tension_limits=(1.0, t_max)).equilibrium(pose=[0.0, 0.0, 1.0])
    need = err.value.remedies["t_max"]
    assert err.value.cause == "cable weight"
    assert eq.max_tensions.max() <= need <= 1.1 * eq.max_tensions.max()
    replace(rob, tension_limits=(1.0, 1.01 * need)).equilibrium(pose=[0.0, 0.0, 1.0])


@pytest.mark.parametrize("z, cause, words", [
    (7.0, "wrench", "outside the wrench-feasible workspace"),      # above the anchors
    (5.0, "singular", "span only 2 of the 3 free DOFs"),           # in their plane
])
def test_poses_no_limit_can_save_say_so(z, cause, words):
    rob = point_mass([[-4.0, -3.0, 5.0], [4.5, -2.0, 5.0], [0.3, 4.0, 5.0]], 0.05)
    with pytest.raises(InfeasiblePoseError, match=words) as err:
        rob.equilibrium(pose=[0.0, 0.0, z])
    assert err.value.cause == cause and err.value.remedies == {}


@pytest.mark.parametrize("W, w, t_min, t_max, lo, hi, expect", [
    # t1 + 2 t2 = 12 with t1 >= s + 1, t2 >= s and both <= 4: t2 = t1 = 4, so s = 3 (the
    # upper bounds hold it below the unbounded 11/3); min s with t1 >= 3, t2 >= 2,
    # t1, t2 <= s: t1 = t2 = 4
    ([[1.0, 2.0]], [12.0], 2.0, 4.0, [1.0, 0.0], [0.0, 0.0], (3.0, 4.0)),
    # t1 - t2 = 2 with both >= 3 and t1 + 1 <= s, t2 <= s: t2 = 3, t1 = 5, s = 6 (the lower
    # bound binds: without it t2 = 0, t1 = 2, s = 3); s <= t2 with t1 <= 6 - 1: s = 3
    ([[1.0, -1.0]], [2.0], 3.0, 6.0, [0.0, 0.0], [1.0, 0.0], (3.0, 6.0)),
    # t1 + t2 = 10, both <= 3: no tensions balance whatever t_min (-inf); t1, t2 >= 6:
    # none whatever t_max (inf)
    ([[1.0, 1.0]], [10.0], 6.0, 3.0, [0.0, 0.0], [0.0, 0.0], (-np.inf, np.inf)),
])
def test_limit_bounds_solve_small_programs_by_hand(W, w, t_min, t_max, lo, hi, expect):
    """limit_bounds' two linear programs on one-equation cases solved by hand: the tension
    bounds are constraints of both programs, and an infeasible program gives -inf / inf."""
    from dynstiff.robot.feasibility import limit_bounds
    got = limit_bounds(np.array(W), np.array(w), t_min, t_max, np.array(lo), np.array(hi))
    np.testing.assert_allclose(got, expect, rtol=1e-9)


def test_a_t_min_below_one_newton_is_a_remedy_too():
    """t1 + t2 = 1 N: the largest t_min that works is 0.5 N, named alone (not with a t_max)."""
    from dynstiff.robot.feasibility import diagnose_limits
    e = diagnose_limits(np.array([[1.0, 1.0]]), np.array([1.0]), 2.0, 10.0, np.zeros(2),
                        np.zeros(2), "here")
    assert e.cause == "tension limits" and e.remedies == pytest.approx({"t_min": 0.5})
