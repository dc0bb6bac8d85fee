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


def test_least_end_tension_locates_the_fold_where_the_tension_stops_falling():
    """The unstretched length returned is the root of dT_B/dL0 (central differences, h =
    1e-4 m, then Brent to 1e-13 m) to 1e-7 m: a loose search tolerance (1e-5 m) leaves it
    ~7e-7 m off while T_B itself barely moves (the minimum is flat)."""
    from scipy.optimize import brentq
    for A, B, m in [([3.0, 3.0, 0.0], [0.0, 0.0, 2.0], 0.2),
                    ([3.0, 3.0, 0.0], [0.0, 1.0, 4.0], 0.5)]:
        A, B, cable = np.array(A), np.array(B), ds.Cable(m, 1e6)
        T_star, L_star = least_end_tension(A, B, cable, 9.81)

        def slope(L0, h=1e-4):
            return (ds.solve_catenary(A, B, L0 + h, cable, 9.81).tension_at_end
                    - ds.solve_catenary(A, B, L0 - h, cable, 9.81).tension_at_end) / (2 * h)
        L_ref = brentq(slope, L_star - 1e-2, L_star + 1e-2, xtol=1e-13)
        assert abs(L_star - L_ref) < 1e-7
        T_ref = ds.solve_catenary(A, B, L_ref, cable, 9.81).tension_at_end
        assert T_star == pytest.approx(T_ref, rel=1e-12)


def _limits(W, w, t_min, t_max, lo=(0.0, 0.0), hi=(0.0, 0.0)):
    from dynstiff.robot.feasibility import diagnose_limits
    return diagnose_limits(np.array(W), np.array(w), t_min, t_max, np.array(lo),
                           np.array(hi), "here")


def test_limits_wrong_together_name_both_remedies():
    """t1 + t2 = 1 N within [2, 0.4] N: neither limit alone helps (best t_min -inf, best
    t_max inf); half of the unbounded best t_min (0.5 N) and the t_max it then needs
    (0.5 N) are named together, and they work."""
    from dynstiff.robot.feasibility import limit_bounds
    e = _limits([[1.0, 1.0]], [1.0], 2.0, 0.4)
    assert e.cause == "tension limits"
    assert e.remedies == pytest.approx({"t_min": 0.25, "t_max": 0.5})
    assert str(e) == ("here: no tension distribution within [2, 0.4] N balances the "
                      "platform: the tensions that hold the platform here do not fit in the "
                      "limits; change the tension limits: feasible with t_min <= about 0.25 N "
                      "and t_max >= about 0.5 N")
    lo, hi = limit_bounds(np.array([[1.0, 1.0]]), np.array([1.0]), 0.25, 0.5, np.zeros(2),
                          np.zeros(2))
    assert lo >= 0.25 and hi <= 0.5 + 1e-12


def test_no_positive_tension_is_no_limit_problem():
    """t1 + t2 = 0: only zero tensions balance (the largest t_min that works is 0, not a
    positive one): the wrench, not the limits."""
    e = _limits([[1.0, 1.0]], [0.0], 1.0, 5.0)
    assert e.cause == "wrench" and not e.remedies


def test_weight_margins_message_names_the_weight_and_the_t_max():
    """t1 + t2 = 10 N with margins of 2 N each side within [2, 6] N: weightless cables fit
    (5 N each), the margins leave [4, 4] N; t_max = 5 + 2 = 7 N is named."""
    e = _limits([[1.0, 1.0]], [10.0], 2.0, 6.0, lo=(2.0, 2.0), hi=(2.0, 2.0))
    assert e.cause == "cable weight" and e.remedies == pytest.approx({"t_max": 7.0})
    assert str(e) == ("here: no tension distribution within [2, 6] N balances the platform: "
                      "the cables' weight (the tension varies along each cable by up to 2 N) "
                      "leaves no room within the limits; use lighter cables, or change the "
                      "tension limits: t_max >= about 7 N")


@pytest.mark.parametrize("anchor, end, lo_i, words", [
    ([3.0, 3.0, 0.0], [0.0, 0.0, 2.0], 1.0, "rising 2 m"),
    ([3.0, 3.0, 4.0], [0.0, 0.0, 2.0], 1.0, "falling 2 m"),
    ([3.0, 3.0, 0.0], [0.0, 0.0, 2.0], 6.0, "rising 2 m"),     # lo_i above the tension
])
def test_unreachable_tension_message_and_remedies(anchor, end, lo_i, words):
    """The message's numbers from their definitions: the chord's weight m g |B - A|, the
    least tension T* (least_end_tension), t_min + T* - T, and the lighter cable m (T -
    lo_i) / (T* - lo_i), named only when that factor is in (0, 1)."""
    from dynstiff.robot.feasibility import diagnose_unreachable
    rob = point_mass(UPPER + [anchor], 0.2, limits=(1.5, np.inf))
    A, B = np.array(anchor), np.array(end)
    T_star, _ = least_end_tension(A, B, rob.cables[3], rob.g)
    tension = T_star - 3.0
    e = diagnose_unreachable(rob, 3, A, B, tension, lo_i, "here")
    weight = 0.2 * rob.g * np.linalg.norm(B - A)
    scale = (tension - lo_i) / (T_star - lo_i)
    lighter = f" or use a cable lighter than about {scale * 0.2:.4g} kg/m" if scale > 0 else ""
    assert str(e) == (f"here: cable 3 ({words} to the platform, chord weight {weight:.4g} N) "
                      f"is asked {tension:.4g} N at the platform; not reachable: no catenary "
                      f"between its ends has less than {T_star:.4g} N there (the cable is too "
                      f"heavy for its tension); raise t_min to above about {4.5:.4g} N "
                      f"(tension limits){lighter}")
    assert e.cable == 3 and e.cause == "cable weight"
    assert e.remedies["t_min"] == pytest.approx(4.5)
    assert ("mass_per_length" in e.remedies) == (scale > 0)
    assert diagnose_unreachable(rob, 3, A, B, T_star + 1.0, lo_i, "here") is None
