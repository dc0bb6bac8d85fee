"""Batched elastic catenaries for prescribed end tensions (dynstiff/cable/catenary_batch.py,
docs/theory.md §13.1): against the scalar bracketing solver of dynstiff/cable/catenary.py, the
analytic Jacobian against finite differences, the taut branch, and the hand-over of the
cases the batch does not take (vertical chord, weightless cable, unreachable tension)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.cable.catenary_batch import states_for_tensions, taut_catenaries
from dynstiff.cable.catenary_solve import solve_catenary, unstretched_length_for_tension
from dynstiff.errors import SlackCableError

G = 9.81
CABLE = ds.Cable(0.064, 1.39487e5)          # CoGiRo, E = 17 GPa


def arrays(cables, g=G):
    return (np.array([c.EA for c in cables]),
            np.array([c.mass_per_length for c in cables]) * g)


@settings(max_examples=40, deadline=None)
@given(st.floats(1.0, 20.0), st.floats(-8.0, 8.0), st.floats(-1.0, 1.0),
       st.floats(30.0, 5000.0), st.sampled_from([1.39487e5, 9.8461e5, 2e4]))
def test_equals_the_scalar_solver(span, rise, side, tension, EA):
    """Same unstretched length and (H, V0) as Brent's search on the scalar catenary
    (1e-10 relative), over spans, rises, tensions (deep sag at 30 N) and moduli."""
    cable = ds.Cable(0.064, EA)
    A = np.array([[0.0, 0.0, 0.0]])
    B = np.array([[span, side * span, rise]])
    try:
        ref = unstretched_length_for_tension(A[0], B[0], tension, cable, G)
    except SlackCableError:
        return
    H, V0, L0, res, pending = taut_catenaries(A, B, np.array([tension]), *arrays([cable]))
    assert not pending[0]
    assert res[0] < 1e-12
    assert L0[0] == pytest.approx(ref.unstretched_length, rel=1e-10)
    assert H[0] == pytest.approx(ref.H, rel=1e-9)
    assert V0[0] == pytest.approx(ref.V0, rel=1e-9, abs=1e-9 * tension)


def test_solution_is_a_catenary_with_the_prescribed_tension():
    """Round trip: the scalar catenary with the returned L0 between the same ends has the
    prescribed end tension (an independent solve on (H, V0) only)."""
    A = np.array([[-7.1775, -5.4361, 5.3911], [7.2, 5.3, 5.4]])
    B = np.array([[0.5, -0.49, 1.0], [-3.0, 1.0, 0.4]])
    t = np.array([850.0, 120.0])
    H, _, L0, _, _ = taut_catenaries(A, B, t, *arrays([CABLE, CABLE]))
    for i in range(2):
        s = solve_catenary(A[i], B[i], L0[i], CABLE, G)
        assert s.tension_at_end == pytest.approx(t[i], rel=1e-12)
        assert s.H == pytest.approx(H[i], rel=1e-10)


def test_jacobian_matches_finite_differences():
    from dynstiff.cable import catenary_batch as cb
    x0 = np.array([400.0, -900.0, 11.0])
    EA, w0 = np.array([1.39487e5]), np.array([0.064 * G])

    def f(x):
        x_, z_, T_, _ = cb._equations(x[0:1], x[1:2], x[2:3], EA, w0)
        return np.array([x_[0], z_[0], T_[0]])

    J = cb._equations(x0[0:1], x0[1:2], x0[2:3], EA, w0)[3][0]
    for k in range(3):
        h = 1e-6 * abs(x0[k])
        e = np.zeros(3)
        e[k] = h
        fd = (f(x0 + e) - f(x0 - e)) / (2 * h)
        np.testing.assert_allclose(J[:, k], fd, rtol=1e-6, atol=1e-10 * np.abs(J).max())


def test_keeps_the_taut_branch_from_a_start_on_the_hanging_one():
    """Two lengths give 60 N at B (10.2 m taut, about 190 m hanging in a deep loop);
    started on the hanging solution itself, the result is still the taut one the scalar
    solver returns."""
    from scipy.optimize import brentq
    A, B = np.array([[0.0, 0.0, 0.0]]), np.array([[10.0, 0.0, -2.0]])
    t = np.array([60.0])
    ref = unstretched_length_for_tension(A[0], B[0], 60.0, CABLE, G)
    L_deep = brentq(lambda L0: solve_catenary(A[0], B[0], L0, CABLE, G).tension_at_end - 60.0,
                    150.0, 300.0, xtol=1e-12)
    deep = solve_catenary(A[0], B[0], L_deep, CABLE, G)
    assert L_deep > 10 * ref.unstretched_length
    start = (np.array([deep.H]), np.array([deep.V0]), np.array([deep.unstretched_length]))
    _, _, L0, _, pending = taut_catenaries(A, B, t, *arrays([CABLE]), start=start)
    assert not pending[0]
    assert L0[0] == pytest.approx(ref.unstretched_length, rel=1e-10)


def test_warm_start_gives_the_cold_result():
    A = np.array([[-7.1775, -5.4361, 5.3911]] * 3)
    B = np.array([[0.5, -0.49, 1.0], [1.5, 0.49, 2.0], [-2.0, 1.0, 0.3]])
    t = np.array([400.0, 900.0, 2500.0])
    EA, w0 = arrays([CABLE] * 3)
    cold = taut_catenaries(A, B, t, EA, w0)
    warm = taut_catenaries(A, B, 1.01 * t, EA, w0, start=cold[:3])
    again = taut_catenaries(A, B, 1.01 * t, EA, w0)
    np.testing.assert_allclose(warm[2], again[2], rtol=1e-13)


def test_vertical_weightless_and_unreachable_cables_go_to_the_scalar_solver():
    A = np.array([[0.0, 0.0, 5.0], [0.0, 0.0, 5.0], [0.0, 0.0, 0.0]])
    B = np.array([[0.0, 0.0, 1.0], [3.0, 0.0, 1.0], [30.0, 0.0, 0.0]])
    cables = [CABLE, ds.Cable(1e-12, 1e5), CABLE]
    t = np.array([500.0, 500.0, 1.0])                 # 30 m span at 1 N: out of reach
    EA, w0 = arrays(cables)
    w0[1] = 0.0
    *_, pending = taut_catenaries(A, B, t, EA, w0)
    assert pending.tolist() == [True, True, True]
    with pytest.raises(SlackCableError, match="not reachable"):
        states_for_tensions(A, B, t, cables, G)
    st_ = states_for_tensions(A[:2], B[:2], t[:2], cables[:2], G)
    assert st_[0].tension_at_end == pytest.approx(500.0, rel=1e-10)
    assert st_[0].H == 0.0


def test_sag_ratios_equal_the_profile_of_each_state():
    """The batched sag (one point, where the cable runs parallel to the chord) equals
    CatenaryState.sag / chord (a 401-point profile and that point) on every CoGiRo cable at
    a central and an edge pose, and is at least the sampled profile's."""
    from dynstiff.cable.catenary_batch import catenary_arrays, sag_ratios
    robot = ds.load_scene("cogiro").robot
    for p in ([0.0, 0.0, 1.0], [5.0, 3.0, 1.0]):
        eq = robot.equilibrium(pose=p)
        B, _ = robot.attachment_points(eq.pose)
        got = sag_ratios(robot.anchors, B, *catenary_arrays(eq.states),
                         *arrays(robot.cables))
        ref = np.array([s.sag / s.chord_length for s in eq.states])
        np.testing.assert_allclose(got, ref, rtol=1e-12)
        assert ref.max() > 1e-4
        sampled = []
        for state in eq.states:                  # the 401-point profile alone
            q = state.profile(401) - state.anchor
            e = state.chord / state.chord_length
            sampled.append(np.max(np.linalg.norm(q - np.outer(q @ e, e), axis=1))
                           / state.chord_length)
        assert np.all(got >= np.array(sampled) * (1 - 1e-14))
        np.testing.assert_allclose(got, sampled, rtol=1e-5)      # the sampling's O(1/n^2)


def test_the_sag_of_a_shallow_cable_is_the_parabolas():
    """Horizontal chords of 20 m, nearly inextensible cables: the sag ratio is the inextensible
    catenary's (H / w0) (cosh(w0 L / (2 H)) - 1) / L, and the parabola's w0 L / (8 H) to its
    relative O((w0 L / H)^2 / 48) (theory.md §1.2)."""
    from dynstiff.cable.catenary_batch import catenary_arrays, sag_ratios
    # w0 = 1 N/m; the stretch moves the sag by about 1e-8 T / (EA (d/L)^2): EA = 1e15
    cable = ds.Cable(mass_per_length=1.0 / G, EA=1e15)
    A, B = np.zeros(3), np.array([20.0, 0.0, 0.0])
    for T in (1e2, 1e3, 1e4):
        state = ds.unstretched_length_for_tension(A, B, T, cable, g=G)
        got = sag_ratios(A[None], B[None], *catenary_arrays([state]), np.array([1e15]),
                         np.array([1.0]))[0]
        H = state.H
        assert got == pytest.approx(H * (np.cosh(20.0 / (2 * H)) - 1.0) / 20.0, rel=1e-9)
        parabola = 20.0 / (8 * H)
        assert abs(got / parabola - 1) <= (20.0 / H) ** 2 / 48 * 1.01


def test_numpy_newton_solves_every_taut_cable_as_the_scalar_solver():
    """The numpy Newton (compiled=False, the reference of the compiled one) leaves none of
    these cables pending: spans of 0.4 to 15 m (L0 < 1 m included), rises of either sign,
    tensions from a deep sag (30 N) to taut (5 kN); (H, V0, L0) equal the scalar solver's
    (1e-10) and the residual is converged (< 1e-12). From a start on the hanging branch it
    still returns the taut one."""
    A = np.zeros((6, 3))
    B = np.array([[0.4, 0.1, 0.2], [0.6, 0.0, -0.3], [4.0, 1.0, 3.0], [10.0, -2.0, -4.0],
                  [15.0, 0.0, 0.5], [8.0, 3.0, 6.0]])
    t = np.array([50.0, 300.0, 30.0, 800.0, 5000.0, 120.0])
    EA, w0 = arrays([CABLE] * 6)
    H, V0, L0, res, pending = taut_catenaries(A, B, t, EA, w0, compiled=False)
    assert not pending.any() and np.all(res < 1e-12)
    assert L0[0] < 1.0
    for i in range(6):
        ref = unstretched_length_for_tension(A[i], B[i], t[i], CABLE, G)
        assert L0[i] == pytest.approx(ref.unstretched_length, rel=1e-10)
        assert H[i] == pytest.approx(ref.H, rel=1e-9)
        assert V0[i] == pytest.approx(ref.V0, rel=1e-9, abs=1e-9 * t[i])
    from scipy.optimize import brentq
    A1, B1 = np.array([[0.0, 0.0, 0.0]]), np.array([[10.0, 0.0, -2.0]])
    L_deep = brentq(lambda L: solve_catenary(A1[0], B1[0], L, CABLE, G).tension_at_end - 60.0,
                    150.0, 300.0, xtol=1e-12)
    deep = solve_catenary(A1[0], B1[0], L_deep, CABLE, G)
    start = (np.array([deep.H]), np.array([deep.V0]), np.array([L_deep]))
    *_, L1, _, pend = taut_catenaries(A1, B1, np.array([60.0]), *arrays([CABLE]), start=start,
                                     compiled=False)
    ref = unstretched_length_for_tension(A1[0], B1[0], 60.0, CABLE, G)
    assert not pend[0] and L1[0] == pytest.approx(ref.unstretched_length, rel=1e-10)


def test_states_carry_the_batch_residual():
    """Each state solved by the batch records the batch's residual (converged, < 1e-12)."""
    A = np.array([[-7.1775, -5.4361, 5.3911], [7.2, 5.3, 5.4]])
    B = np.array([[0.5, -0.49, 1.0], [-3.0, 1.0, 0.4]])
    t = np.array([850.0, 120.0])
    res = taut_catenaries(A, B, t, *arrays([CABLE, CABLE]))[3]
    states = states_for_tensions(A, B, t, [CABLE, CABLE], G)
    assert [s.residual for s in states] == res.tolist() and np.all(res < 1e-12)


def test_straight_start_is_the_straight_elastic_cable():
    """The start: L0 = L / (1 + t / EA), the tension t along the chord at B, so H = t lh / L
    and V_B = t h / L, and V0 = V_B - w0 L0 (the weight taken off at A)."""
    from dynstiff.cable.catenary_batch import _straight_start
    lh, h, t, EA, w0 = np.array([3.0]), np.array([4.0]), np.array([500.0]), np.array([1e5]), \
        np.array([0.6])
    H, V0, L0 = _straight_start(lh, h, np.array([5.0]), t, EA, w0)
    assert L0[0] == pytest.approx(5.0 / 1.005, rel=1e-15)
    assert H[0] == pytest.approx(300.0, rel=1e-15)
    assert V0[0] == pytest.approx(400.0 - 0.6 * 5.0 / 1.005, rel=1e-15)


def test_sag_ratio_of_a_short_sloped_cable():
    """A cable spanning 0.5 m horizontally (rising 0.3 m, 2 N at B, deep enough to sag) has
    the sag ratio of its CatenaryState, not the zero of a straight cable."""
    from dynstiff.cable.catenary_batch import catenary_arrays, sag_ratios
    A, B = np.zeros((1, 3)), np.array([[0.5, 0.0, 0.3]])
    st_ = unstretched_length_for_tension(A[0], B[0], 2.0, CABLE, G)
    got = sag_ratios(A, B, *catenary_arrays([st_]), *arrays([CABLE]))
    assert got[0] > 1e-3
    assert got[0] == pytest.approx(st_.sag / st_.chord_length, rel=1e-12)
