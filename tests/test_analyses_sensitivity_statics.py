"""LinearisedEquilibrium (theory.md §16.2): the equilibrium as equations and its derivative.

Its active set and the multipliers of the held tension limits against re-solved tension
distributions (``Robot.equilibrium``), the ``active`` attribute at fixed lengths, and the
refusals (a vertical chord, an equilibrium of another reference, singular equations) with
their reasons.
"""

import dataclasses

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.sensitivity_statics import LinearisedEquilibrium
from dynstiff.errors import InvalidParameterError


@pytest.fixture(scope="module")
def cogiro():
    return ds.load_scene("cogiro")


#: CoGiRo's reference with cable 0 asking far more than the others: the distribution
#: holds cable 6 at t_min = 100 N (a binding limit).
T_REF = np.array([3000.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0])


def tensions(eq):
    return np.asarray(eq.tensions, dtype=float)


def test_multiplier_of_a_held_limit_is_the_reference_shift_that_frees_the_cable(cogiro):
    """KKT: a cable held at t_min with multiplier mu > 0 stays at the limit (the distribution
    unchanged) while its reference rises by less than mu, and leaves it beyond mu."""
    rob, n = cogiro.robot, cogiro.robot.n_cables
    eq = rob.equilibrium(pose=cogiro.pose, tension_reference=T_REF, tol=1e-12)
    lin = LinearisedEquilibrium(eq, tension_reference=T_REF)
    assert lin.active.tolist() == [0, 0, 0, 0, 0, 0, -1, 0]
    assert lin.multipliers[6] > 0
    np.testing.assert_array_equal(lin.multipliers[np.arange(n) != 6], 0.0)
    t0 = tensions(eq)
    assert eq.states[6].min_tension == pytest.approx(100.0, abs=1e-9)
    mu = lin.multipliers[6]
    for s, held in [(0.5, True), (0.97, True), (1.03, False)]:
        ref = T_REF.copy()
        ref[6] += s * mu
        e2 = rob.equilibrium(pose=cogiro.pose, tension_reference=ref, tol=1e-12)
        if held:
            np.testing.assert_allclose(tensions(e2), t0, rtol=1e-9)
            assert LinearisedEquilibrium(e2, tension_reference=ref).active[6] == -1
        else:
            assert e2.states[6].min_tension > 100.0 + 1.0
            assert LinearisedEquilibrium(e2, tension_reference=ref).active[6] == 0


def test_derivative_at_a_held_limit_matches_central_differences(cogiro):
    """dy/dp with cable 6 held at t_min: the tensions at B along t_min against re-solved
    distributions (the active set stays the same over the steps)."""
    rob, n, h = cogiro.robot, cogiro.robot.n_cables, 0.01
    eq = rob.equilibrium(pose=cogiro.pose, tension_reference=T_REF, tol=1e-12)
    lin = LinearisedEquilibrium(eq, tension_reference=T_REF)
    dt = lin.derivatives([{"t_min": 1.0}])[0, 3 * n:4 * n]
    t = [tensions(dataclasses.replace(rob, tension_limits=(100.0 + s, 5000.0)).equilibrium(
        pose=cogiro.pose, tension_reference=T_REF, tol=1e-12)) for s in (h, -h)]
    np.testing.assert_allclose(dt, (t[0] - t[1]) / (2 * h), rtol=1e-5, atol=1e-6)
    assert abs(dt[6]) > 0.5


def test_a_limit_met_to_a_relative_tolerance_of_the_tensions_is_held(cogiro):
    """The active set takes a least tension within 1e-7 of the largest tension of t_min as
    held: CoGiRo with t_min = 5 N holds cable 6 there (largest tension 542 N); its lengths
    solved again under a t_min lower by 1e-5 N (2e-8 of the largest tension, but 2e-6 of
    t_min) give the same equilibrium, still the distribution with cable 6 held."""
    rob = dataclasses.replace(cogiro.robot, tension_limits=(5.0, 5000.0))
    eq = rob.equilibrium(pose=cogiro.pose, tension_reference=T_REF, tol=1e-12)
    assert eq.states[6].min_tension == pytest.approx(5.0, abs=1e-9)
    assert 500.0 < tensions(eq).max() < 600.0
    low = dataclasses.replace(rob, tension_limits=(5.0 - 1e-5, 5000.0))
    same = low.equilibrium(unstretched_lengths=eq.unstretched_lengths, tol=1e-12)
    np.testing.assert_allclose(tensions(same), tensions(eq), rtol=1e-10)
    lin = LinearisedEquilibrium(same, tension_reference=T_REF)
    assert lin.active.tolist() == [0, 0, 0, 0, 0, 0, -1, 0]
    assert lin.multipliers[6] > 0


def test_fixed_lengths_have_no_active_set_of_ints(cogiro):
    lin = LinearisedEquilibrium(cogiro.equilibrium(), hold="lengths")
    assert lin.active.dtype.kind == "i"
    assert lin.active.tolist() == [0] * 8
    np.testing.assert_array_equal(lin.multipliers, 0.0)


def test_another_distribution_is_refused_naming_the_default_reference(cogiro):
    eq = cogiro.robot.equilibrium(pose=cogiro.pose, tension_reference=400.0)
    with pytest.raises(InvalidParameterError,
                       match=r"^equilibrium: its tensions are not the distribution closest to "
                             r"the default reference at this pose \(optimality residual "):
        LinearisedEquilibrium(eq)
    with pytest.raises(InvalidParameterError, match=r"closest to tension_reference \[300\.0, "):
        LinearisedEquilibrium(eq, tension_reference=np.full(8, 300.0))
    LinearisedEquilibrium(eq, tension_reference=400.0)      # its own reference: accepted


def test_a_vertical_chord_is_refused_naming_the_cable():
    """Cable 0 hangs straight above the point mass (H = 0): no catenary sensitivities."""
    anchors = np.array([[0, 0, 5.0], [-4, 0, 5], [4, 0, 5], [0, -4, 5], [0, 4, 5]])
    rob = ds.Robot(anchors, np.zeros((5, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(20.0, free_dofs=("x", "y", "z")))
    eq = rob.equilibrium(pose=[0.0, 0.0, 1.0])
    assert eq.states[0].H == 0.0
    for hold in ("pose", "lengths"):
        with pytest.raises(InvalidParameterError, match=r"^equilibrium: cable 0 has a vertical "
                           r"chord \(H = 0\); its sensitivities are not available$"):
            LinearisedEquilibrium(eq, hold=hold)


def test_singular_statics_are_refused_with_their_reason():
    """The pendulum scene at a fixed pose: both cables held at t_min on one DOF (a
    degenerate active set); at fixed lengths its equations are regular."""
    eq = ds.load_scene("pendulum").equilibrium()
    with pytest.raises(InvalidParameterError, match=r"^equilibrium: the statics equations are "
                       r"singular at this equilibrium \(a degenerate active set or a singular "
                       r"configuration\)$"):
        LinearisedEquilibrium(eq)
    assert LinearisedEquilibrium(eq, hold="lengths").y.size == 5
