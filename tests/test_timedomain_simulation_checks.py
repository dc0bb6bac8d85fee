"""Tests of the checks and bookkeeping of simulate() (dynstiff.timedomain.simulation): the
errors that name a bad argument, a start without a taut equilibrium, an over-stretched or
slack start; the explicit step limit of the run's damping (its warning and
TimeResponse.explicit_limit), the wall time, the compiled runs of fixed lengths and the
blow-up of the stepwise (numpy) loop.

References: theory.md §7.3 (explicit limit dt0 = l0 / sqrt(EA / m), reduced by the damping
ratio zeta of the highest axial chain mode to dt0 (sqrt(1 + zeta^2) - zeta), zeta =
c_ax / (l0 sqrt(EA m)) for axial dashpots); a straight weightless segment's strain is
chord / L0 - 1.
"""

import os
import re
import time
import warnings

import numpy as np
import pytest
from conftest import damped_explicit_limit

import dynstiff as ds
import dynstiff.compiled
from dynstiff.errors import InvalidParameterError, SlackCableError
from dynstiff.lumped import (
    IntegrationError,
    LumpedMassModel,
    TimeDamping,
    TimeStepWarning,
    simulate,
)

C_AX = 50.0                      # axial dashpot [N s]: zeta about 0.13 on the highest mode




def stretched_pair(L0):
    """A weightless platform between two cables along x (anchors at x = -2 and 2 m, only x
    free), unstretched lengths L0 [m]; and its equilibrium at x = 0."""
    anchors = np.array([[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    rob = ds.Robot(anchors, np.zeros((2, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(5.0, free_dofs=("x",)), g=0.0)
    mm = LumpedMassModel(rob, [L0, L0], segments=2)
    return mm, mm.equilibrium(initial_pose=np.zeros(6))


# ------------------------------------------------------------------- arguments
def test_bad_arguments_are_named_with_the_type_or_value_given(robot_model):
    m = robot_model(3)
    with pytest.raises(InvalidParameterError,
                       match="^model must be a LumpedMassModel or LumpedLinearModel, got Robot$"):
        simulate(m.robot, 0.01, 1e-3)
    with pytest.raises(InvalidParameterError,
                       match=r"^start must be a LumpedEquilibrium \(.*\), got str$"):
        simulate(m, 0.01, 1e-3, start="equilibrium")
    for name in ("record_every", "max_iter"):
        for bad in (2.5, True, 0):          # a float, a bool (an Integral) and 0 are refused
            with pytest.raises(InvalidParameterError, match="^" + re.escape(
                    f"{name} must be an integer >= 1, got {bad!r}") + "$"):
                simulate(m, 0.01, 1e-3, **{name: bad})
    with pytest.raises(InvalidParameterError, match="^tol must be"):
        simulate(m, 0.01, 1e-3, tol=0.0)


def test_a_start_without_taut_equilibrium_names_where_its_lengths_came_from(robot_model,
                                                                            lengths0):
    m = robot_model(3)
    long = lengths0 + [20.0, 0.0, 0.0]
    with pytest.raises(SlackCableError, match=re.escape(
            f"no taut static equilibrium for lengths(0) = {long.tolist()} m")):
        simulate(m, 0.01, 1e-3, lengths=lambda t: long)
    weightless = ds.Robot(m.robot.anchors, m.robot.attachments, m.robot.cables,
                          m.robot.platform, g=0.0)
    chords = np.linalg.norm(m.robot.anchors - m.pose.position, axis=1)
    with pytest.raises(SlackCableError, match=re.escape(
            f"no taut static equilibrium for the model's unstretched_lengths = "
            f"{(1.01 * chords).tolist()} m")):
        simulate(LumpedMassModel(weightless, 1.01 * chords, segments=3), 0.01, 1e-3)


def test_an_over_stretched_start_without_offset_blames_the_lengths():
    """L0 = 0.9 m on a 2 m chord: strain 2 / 0.9 - 1 = 1.22 at the equilibrium itself, with
    the model's lengths or lengths(0); no offset was given, so none is blamed."""
    mm, eq = stretched_pair(0.9)
    for kw in ({}, {"lengths": lambda t: np.array([0.9, 0.9])}):
        with pytest.raises(InvalidParameterError, match=r"^simulate: the start stretches a "
                           r"segment to strain 1\.22 \(> 1\): lengths\(0\) is far outside"):
            simulate(mm, 0.01, 1e-3, start=eq, **kw)


def test_a_start_slack_by_rounding_names_the_initial_offset():
    """L0 = 1.5 m, offset x -> 0.5 m makes cable 1's chord 1.5 m: offsets a few ulps below
    0.5 leave it taut by a strain of 1e-16, which the node coordinates lose; the start is
    refused (no taut chain, or a segment slack at the start) and the error names the
    offset, the only cause."""
    mm, eq = stretched_pair(1.5)
    kinds = set()
    for k in range(12):
        x = 0.5 - k * 2.0 ** -53
        try:
            simulate(mm, 0.002, 1e-3, start=eq, initial=[x, 0, 0, 0, 0, 0])
        except SlackCableError as exc:
            msg = str(exc)
            assert f"initial offset {[x, 0.0, 0.0, 0.0, 0.0, 0.0]}" in msg, msg
            kinds.add("slack at the start" in msg)
    assert kinds == {False, True}           # measured: k <= 1 no taut chain, k = 2 slack


# ------------------------------------------------------- explicit limit, result
def test_explicit_limit_and_its_warning_use_the_runs_damping(robot_model):
    """Axial dashpots lower the explicit limit by 25 %: dt = 1.1 x the damped limit warns
    (pointing at the caller's line) although it is below the undamped limit, and the
    response reports the damped limit."""
    m = robot_model(3)
    lim = damped_explicit_limit(m.mass_model, C_AX)
    assert damped_explicit_limit(m.mass_model, 0.0) > 1.2 * lim
    dt = 1.1 * lim
    with pytest.warns(TimeStepWarning, match="exceeds the predicted stability limit") as rec:
        r = simulate(m, 10 * dt, dt, scheme="explicit", damping=TimeDamping(axial=C_AX))
    hits = [w for w in rec if issubclass(w.category, TimeStepWarning)]
    assert len(hits) == 1
    if "MUTANT_UNDER_TEST" not in os.environ:    # a mutation run's frames stand between
        assert hits[0].filename == __file__       # the caller and the package
    assert r.explicit_limit == pytest.approx(lim, rel=1e-5)
    assert np.max(np.abs(r.displacement)) < 1e-9           # 10 steps from rest: no blow-up
    with warnings.catch_warnings():
        warnings.simplefilter("error", TimeStepWarning)    # below the limit: no warning
        r = simulate(m, 10 * 0.9 * lim, 0.9 * lim, scheme="explicit",
                     damping=TimeDamping(axial=C_AX))
    assert r.explicit_limit == pytest.approx(lim, rel=1e-5)


def test_wall_time_is_the_time_simulate_took(robot_model):
    m = robot_model(3)
    t0 = time.perf_counter()
    r = simulate(m, 0.05, 0.01, initial=[1e-4, 0, 0, 0, 0, 0])
    outer = time.perf_counter() - t0
    assert 0.0 < r.wall_time <= outer
    assert r.speed_ratio == pytest.approx(0.05 / r.wall_time, rel=1e-12)   # simulated / wall


# ------------------------------------------------------------ compiled runs
def test_fixed_length_runs_use_the_compiled_kernels(robot_model, lengths0, monkeypatch):
    """The explicit and implicit schemes with fixed lengths run in the compiled kernels;
    a winch run and the energy scheme step in Python."""
    load = dynstiff.compiled.load
    if load("chain_run") is None:
        pytest.skip("no compiled kernels (numba missing)")
    calls = []

    class Spy:
        def __init__(self, mod):
            self.mod = mod

        def __getattr__(self, name):
            fn = getattr(self.mod, name)

            def wrapped(*args, **kw):
                calls.append(name)
                return fn(*args, **kw)
            return wrapped

    monkeypatch.setattr(dynstiff.compiled, "load",
                        lambda name: Spy(load(name)) if name == "chain_run" else load(name))
    m = robot_model(3)
    dt = 0.5 * damped_explicit_limit(m.mass_model, 0.0)
    kw = dict(initial=[1e-4, 0, 0, 0, 0, 0])
    for scheme in ("explicit", "implicit"):
        calls.clear()
        simulate(m, 20 * dt, dt, scheme=scheme, **kw)
        assert calls and set(calls) == {f"{scheme}_run"}, (scheme, calls)
    for extra in (dict(scheme="energy"), dict(lengths=lambda t: lengths0)):
        calls.clear()
        simulate(m, 5 * dt, dt, **kw, **extra)
        assert calls == []


# ------------------------------------------------------- numpy-loop blow-up
def test_stepwise_explicit_blow_up_names_its_step_and_the_damped_limit(robot_model,
                                                                       monkeypatch):
    """Without the compiled kernels, a 300 kN pull down (15,000 g on the 20 kg platform)
    stretches the cables past 2 l0 within 100 steps, between records and with no segment
    slack: the IntegrationError gives its step, time = step x dt, and names the stability
    limit of the run's axial dashpots."""
    load = dynstiff.compiled.load
    monkeypatch.setattr(dynstiff.compiled, "load",
                        lambda name: None if name == "chain_run" else load(name))
    m = robot_model(3)
    damping = TimeDamping(axial=C_AX)
    lim = damped_explicit_limit(m.mass_model, C_AX)
    dt = 0.5 * lim
    with pytest.raises(IntegrationError, match=r"blow-up at step \d+ .*stretched to") as err:
        simulate(m, 500 * dt, dt, scheme="explicit", damping=damping, record_every=1000,
                 excitation=lambda t: np.array([0.0, 0.0, -3e5, 0.0, 0.0, 0.0]))
    e = err.value
    assert isinstance(e.step, int) and 1 <= e.step < 500 and e.dt == dt
    assert e.time == pytest.approx(e.step * dt, rel=1e-12)
    assert f"blow-up at step {e.step} " in str(e)
    named = float(re.search(r"stability limit is dt < ([0-9.e+-]+) s", str(e)).group(1))
    assert named == pytest.approx(lim, rel=1e-5)
