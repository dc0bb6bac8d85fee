"""Tests of the stepping of the lumped-mass time-domain model (dynstiff.timedomain.stepping):
the Newmark and velocity-Verlet steps' blow-up checks and the IntegrationError they raise,
the explicit stability limit named in its messages, the energy ledger's scale, the
recorder's result, the excitation loads of the compiled runs and the compiled implicit run
against the stepwise (numpy) loop.

References: theory.md §7.3 (explicit limit dt < l0 / sqrt(EA / m), reduced by the damping
ratio zeta of the highest axial chain mode to dt0 (sqrt(1 + zeta^2) - zeta), zeta =
c_ax / (l0 sqrt(EA m)) for axial dashpots; central differences, any text on explicit
dynamics, e.g. Hughes, The Finite Element Method, 1987, §9.3).
"""

import re
import warnings

import numpy as np
import pytest
from conftest import damped_explicit_limit

import dynstiff.compiled
from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import (
    EnergyBalanceWarning,
    IntegrationError,
    SlackSegmentWarning,
    TimeDamping,
    TimeStepWarning,
    simulate,
)
from dynstiff.timedomain.dynamics import Dynamics, FastPose
from dynstiff.timedomain.stepping import (
    Ledger,
    StepNewton,
    check_blow_up,
    excitation_loads,
    explicit_step,
    implicit_step,
)

C_AX = 50.0                      # axial dashpot [N s]: zeta about 0.13 on the highest mode




def limit_in(message, pattern):
    """The step limit [s] a message names after ``pattern``."""
    return float(re.search(pattern + r" ([0-9.e+-]+) s", message).group(1))


def start_state(lm, damping):
    """Dynamics, pose and interior nodes of the model at its equilibrium."""
    mm, eq = lm.mass_model, lm.equilibrium
    dyn = Dynamics(mm, damping, None, None)
    pose = FastPose(eq.pose.position, eq.pose.rotation)
    X = np.concatenate([x.ravel() for x in eq.interior])
    return mm, dyn, pose, X


# ------------------------------------------------------------- non-finite steps
def test_implicit_step_overflowing_forces_raise_integration_error(robot_model):
    """A state so fast that the forces overflow while the Newmark increment d = dt v stays
    finite (1e148 m): the residual alone is non-finite and the step stops at once with an
    IntegrationError locating the step (not a singular factorisation of the Newton matrix)."""
    mm, dyn, pose, X = start_state(robot_model(3), TimeDamping())
    dt, k = 0.01, 7
    v, a = np.full(mm.n_dof, 1e150), np.zeros(mm.n_dof)
    assert np.all(np.isfinite(dt * v + 0.5 * dt ** 2 * a))         # d is finite
    newton = StepNewton(1e-9, 25)
    with pytest.raises(IntegrationError, match="non-finite state at step 7") as err:
        implicit_step(dyn, pose, X, v, a, k * dt, dt, k, newton)
    assert (err.value.step, err.value.time, err.value.dt) == (k, k * dt, dt)
    assert newton.updates == 0                     # no Newton matrix was factorised


def test_explicit_step_non_finite_names_the_damped_stability_limit(robot_model):
    """A non-finite velocity-Verlet step names the predicted stability limit of the run's
    damping (axial dashpots lower it by 25 %), and its step, time and dt."""
    mm, dyn, pose, X = start_state(robot_model(3), TimeDamping(axial=C_AX))
    dt, k = 0.004, 3
    v, a = np.full(mm.n_dof, 1e150), np.zeros(mm.n_dof)
    with pytest.raises(IntegrationError, match="explicit dt") as err:
        explicit_step(dyn, pose, X, v, a, k * dt, dt, k, StepNewton(1e-9, 25))
    named = limit_in(str(err.value), "stability limit is")
    assert named == pytest.approx(damped_explicit_limit(mm, C_AX), rel=1e-5)
    assert damped_explicit_limit(mm, 0.0) > 1.2 * named                     # the damping matters
    assert (err.value.step, err.value.time, err.value.dt) == (k, k * dt, dt)


# -------------------------------------------------------------------- blow-up
@pytest.mark.parametrize("scheme", ["explicit", "implicit"])
def test_check_blow_up_names_the_strain_and_the_hint_of_the_scheme(robot_model, scheme):
    """A strain of 1.5 (a segment at 2.5 l0) is a blow-up; the explicit scheme's message
    names its damped stability limit, the implicit one's asks for a smaller dt."""
    mm = robot_model(3).mass_model
    ledger = Ledger(1.0, 1.0, 1.0)
    with pytest.raises(IntegrationError, match=r"stretched to 2\.5 l0") as err:
        check_blow_up(1.5, 0.0, ledger, scheme, 0.002, 4, 0.008, mm,
                      TimeDamping(axial=C_AX))
    msg = str(err.value)
    assert (err.value.step, err.value.time, err.value.dt) == (4, 0.008, 0.002)
    if scheme == "explicit":
        assert limit_in(msg, "stability limit is dt <") == pytest.approx(
            damped_explicit_limit(mm, C_AX), rel=1e-5)
        assert "reduce dt" not in msg
    else:
        assert msg.endswith("; reduce dt") and "stability limit" not in msg
    # within the limits nothing happens
    check_blow_up(0.5, 0.0, ledger, scheme, 0.002, 4, 0.008, mm, TimeDamping())


def test_compiled_explicit_blow_up_names_the_damped_limit(robot_model):
    """dt at 3 times the damped limit (compiled explicit run): the energy residual check
    stops the run and names the limit with the run's axial dashpots, not the undamped one;
    the error's time is its step times dt."""
    m = robot_model(3)
    mm = m.mass_model
    lim = damped_explicit_limit(mm, C_AX)
    dt = 3.0 * lim
    with pytest.warns(TimeStepWarning), warnings.catch_warnings():
        # the blow-up is what is probed: its ledger and slack warnings are expected
        warnings.simplefilter("ignore", EnergyBalanceWarning)
        warnings.simplefilter("ignore", SlackSegmentWarning)
        with pytest.raises(IntegrationError, match="blow-up at step") as err:
            simulate(m, 100 * dt, dt, scheme="explicit", damping=TimeDamping(axial=C_AX),
                     initial=[1e-3, 0, 0, 0, 0, 0])
    assert limit_in(str(err.value), "stability limit is dt <") == pytest.approx(lim, rel=1e-5)
    assert damped_explicit_limit(mm, 0.0) > 1.2 * lim
    e = err.value
    assert e.dt == dt and 1 <= e.step < 100 and e.time == pytest.approx(e.step * dt)


# --------------------------------------------------------------------- ledger
def test_ledger_scale_is_the_excess_plus_the_peak_work_terms():
    """The energy scale is |E0 - V_eq| plus the largest magnitude each work term reached
    (external, winch, carried, dissipated), as EnergyBalance.scale."""
    led = Ledger(5.0, 3.0, 100.0)
    ext = [2.0, -7.0, 1.0]
    winch = [0.5, -0.25, 0.0]
    carried = [0.0, 0.125, -0.0625]
    diss = [0.25, 1.0, 3.0]
    for e, w, c, d in zip(ext, winch, carried, diss):
        led.ext, led.winch, led.carried, led.diss = e, w, c, d
        led.track()
    peaks = [max(np.abs(x)) for x in (ext, winch, carried, diss)]
    np.testing.assert_array_equal(led.peaks, peaks)
    assert led.scale() == pytest.approx(2.0 + sum(peaks), rel=1e-15)
    assert led.limit() == pytest.approx(2.0 + sum(peaks) + 0.1, rel=1e-15)


# ------------------------------------------------------------------- recorder
def test_response_names_the_free_dofs(robot_model):
    m = robot_model(3)
    r = simulate(m, 0.05, 0.01, initial=[1e-4, 0, 0, 0, 0, 0])
    assert r.free_dofs == tuple(m.mass_model.free_dofs) == ("x", "y", "z")
    assert r.pose.shape == (6, 6) and not r.pose.flags.writeable


# ------------------------------------------------------------ excitation loads
def test_excitation_loads_of_a_bad_callable_name_the_time():
    """A callable that returns 3 loads from t = 0.02 s on is refused with the time named,
    as a load of the stepwise loop; a complex load is refused, not cut to its real part."""
    def short(t):
        return np.zeros(6) if t < 0.015 else np.zeros(3)

    free = np.ones(6, dtype=bool)
    with pytest.raises(InvalidParameterError, match=r"6 real finite loads .* at t = 0\.02 s"):
        excitation_loads(short, None, free, 0.01, 0, 5)

    def complex_load(t):
        return [1.0 + 1j] * 6

    with pytest.raises(InvalidParameterError, match=r"6 real finite loads .* at t = 0\.01 s"):
        excitation_loads(complex_load, None, free, 0.01, 0, 5)
    with pytest.raises(InvalidParameterError, match=r"got array\(\[1\.\+1\.j"):
        excitation_loads(lambda t: np.full(6, 1 + 1j), None, free, 0.01, 0, 5)
    with pytest.raises(InvalidParameterError, match=r"got \['a'"):
        excitation_loads(lambda t: ["a"] * 6, None, free, 0.01, 0, 5)


def test_excitation_loads_of_a_callable_are_its_values_on_the_free_dofs():
    free = np.array([True, False, True, False, False, True])

    def fn(t):
        return np.arange(6) + 10.0 * t
    out = excitation_loads(fn, None, free, 0.5, 2, 5)            # t = 1.5, 2.0, 2.5
    expected = np.array([[15.0, 0, 17, 0, 0, 20], [20, 0, 22, 0, 0, 25],
                         [25, 0, 27, 0, 0, 30]])
    np.testing.assert_array_equal(out, expected)
    assert excitation_loads(None, None, free, 0.5, 2, 5).shape == (0, 6)


# ----------------------------------------------------- compiled implicit run
def test_compiled_implicit_run_with_a_load_table_equals_the_stepwise_loop(robot_model,
                                                                          monkeypatch):
    """A load table that ramps up and reverses (30 steps; a segment goes slack, so the LU
    factors are refreshed at many steps): the compiled implicit run resumes each refreshed
    step with that step's load and matches the stepwise numpy loop (measured 9e-16 m apart
    on 2 cm of motion)."""
    m = robot_model(3)
    times = np.array([0.0, 0.1, 0.2, 0.3])
    loads = np.zeros((4, 6))
    loads[:, 0] = [0.0, 100.0, -100.0, 50.0]
    loads[:, 2] = [0.0, -80.0, 60.0, 0.0]
    with pytest.warns(SlackSegmentWarning, match="went slack at step 20"):
        fast = simulate(m, 0.3, 0.01, excitation=(times, loads))
    assert fast.jacobian_updates > 5 and fast.slack_steps > 0
    assert np.abs(fast.displacement).max() > 0.01
    load = dynstiff.compiled.load
    monkeypatch.setattr(dynstiff.compiled, "load",
                        lambda name: None if name == "chain_run" else load(name))
    with pytest.warns(SlackSegmentWarning, match="went slack at step 20"):
        slow = simulate(m, 0.3, 0.01, excitation=(times, loads))
    assert (slow.jacobian_updates, slow.slack_steps) == (fast.jacobian_updates,
                                                         fast.slack_steps)
    np.testing.assert_allclose(fast.pose, slow.pose, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.energy.external_work, slow.energy.external_work,
                               rtol=1e-9, atol=1e-12)
