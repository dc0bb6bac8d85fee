"""Compiled kernels of the time stepping (dynstiff/compiled/chain.py, theory.md §14.4,
§14.5) against the numpy path: the residual, the axial-dashpot force, the largest tension and
the extreme tension and strain of a displaced, moving CoGiRo configuration; the whole
compiled explicit run against the stepwise loop (records, nodes, ledger, warnings, failure)."""

import warnings

import numpy as np
import pytest

from dynstiff import compiled
from dynstiff.lumped import LumpedMassModel, TimeDamping
from dynstiff.timedomain import stepping as time_stepping

pytest.importorskip("numba")


def _both_paths(monkeypatch, run):
    """run() with the compiled kernels, then with the numpy path: [(result or exception,
    [(category, message) of the warnings])] * 2."""
    out = []
    for fast in (True, False):
        if not fast:
            monkeypatch.setattr(compiled, "load", lambda name: None)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                res = run()
            except Exception as exc:                    # compared below
                res = exc
        out.append((res, [(w.category, str(w.message)) for w in caught]))
    return out


def test_compiled_run_warns_as_the_stepwise_loop_when_cables_go_slack(robot_model, monkeypatch):
    """An upward kick of 0.6 m/s unloads the cables of the point-mass robot: both paths warn
    once, naming the same cable, segment and step, count the same slack steps and record the
    same motion."""
    from dynstiff.lumped import SlackSegmentWarning, explicit_step_limit, simulate
    m = robot_model(5)
    dt = 0.5 * explicit_step_limit(m.mass_model)
    (r1, w1), (r0, w0) = _both_paths(monkeypatch, lambda: simulate(
        m, 0.06, dt, scheme="explicit", initial=([0] * 6, [0, 0, 0.6, 0, 0, 0]),
        record_every=5))
    assert [c for c, _ in w1] == [SlackSegmentWarning] and w1 == w0
    assert r1.slack_steps == r0.slack_steps > 10
    np.testing.assert_allclose(r1.pose, r0.pose, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r1.energy.residual, r0.energy.residual, rtol=0,
                               atol=1e-9 * np.abs(r0.energy.gravity).max())


def test_compiled_run_fails_as_the_stepwise_loop(robot_model, monkeypatch):
    """At 1.5 times the stability limit both paths raise the same IntegrationError (same
    step, same message) after the same warnings."""
    from dynstiff.lumped import IntegrationError, explicit_step_limit, simulate
    m = robot_model(5)
    dt = 1.5 * explicit_step_limit(m.mass_model)
    (e1, w1), (e0, w0) = _both_paths(monkeypatch, lambda: simulate(
        m, 2000 * dt, dt, scheme="explicit", initial=[1e-3, 0, 0, 0, 0, 0]))
    assert isinstance(e1, IntegrationError) and isinstance(e0, IntegrationError)
    assert (e1.step, str(e1)) == (e0.step, str(e0)) and e1.step < 2000
    assert w1 == w0 and len(w1) >= 2                  # the dt warning, then the ledger's


def test_compiled_implicit_run_warns_and_fails_as_the_stepwise_loop(robot_model, monkeypatch):
    """A 0.6 m/s kick snaps the cables of the point-mass robot: at dt = 2 ms both implicit
    paths warn (slack segment, then the ledger) and stop with the same IntegrationError;
    at 1 ms both complete with the same motion, slack count and Newton work."""
    from dynstiff.lumped import IntegrationError, simulate
    m = robot_model(5)
    kick = ([0] * 6, [0, 0, 0.6, 0, 0, 0])
    (e1, w1), (e0, w0) = _both_paths(monkeypatch, lambda: simulate(m, 0.3, 0.002,
                                                                   initial=kick))
    assert isinstance(e1, IntegrationError) and isinstance(e0, IntegrationError)
    assert (e1.step, str(e1)) == (e0.step, str(e0)) and w1 == w0 and len(w1) == 2
    monkeypatch.undo()
    (r1, w1), (r0, w0) = _both_paths(monkeypatch, lambda: simulate(m, 0.3, 0.001,
                                                                   initial=kick,
                                                                   record_every=10))
    assert w1 == w0 and r1.slack_steps == r0.slack_steps > 50
    assert (r1.newton_iterations, r1.jacobian_updates) == \
        (r0.newton_iterations, r0.jacobian_updates)
    # the snaps amplify rounding: 2.3e-11 m measured (Newton stops at tol 1e-9 either way)
    np.testing.assert_allclose(r1.pose, r0.pose, rtol=0, atol=1e-10 * np.abs(r0.pose).max())


def test_compiled_implicit_run_reports_newton_failure_as_the_stepwise_loop(robot_model,
                                                                          monkeypatch):
    """Two Newton iterations cannot reach a relative residual of 1e-15: both paths raise the
    same ConvergenceError (step, residual, message)."""
    from dynstiff.errors import ConvergenceError
    from dynstiff.lumped import simulate
    m = robot_model(5)
    (e1, _), (e0, _) = _both_paths(monkeypatch, lambda: simulate(
        m, 0.01, 1e-3, initial=[1e-3, 0, 0, 0, 0, 0], tol=1e-15, max_iter=2))
    assert isinstance(e1, ConvergenceError) and isinstance(e0, ConvergenceError)
    assert str(e1) == str(e0) and "step 1 " in str(e1)


@pytest.mark.parametrize("viscous, beta, segments", [(0.0, 0.0, 6), (0.3, 0.0, 6),
                                                     (0.3, 1e-4, [2, 3, 4, 5, 6, 7, 3, 5])])
def test_compiled_explicit_run_equals_the_stepwise_loop(cogiro, cogiro_eq, monkeypatch,
                                                        viscous, beta, segments):
    """The compiled velocity-Verlet run, taken in blocks of 37 steps, gives the stepwise
    numpy run: a spinning, driven CoGiRo with Rayleigh (mass- and stiffness-proportional),
    axial and cable viscous damping, chains of equal and of different N, records every 7
    steps."""
    import dataclasses

    import dynstiff as ds
    from dynstiff.lumped import explicit_step_limit, simulate
    rob = cogiro.robot
    cable = dataclasses.replace(rob.cables[0], viscous_damping=viscous)
    robot = ds.Robot(rob.anchors, rob.attachments, cable, rob.platform)
    mm = LumpedMassModel(robot, cogiro_eq.unstretched_lengths, segments=segments)
    damping = TimeDamping(alpha=0.3, beta=beta, axial=np.linspace(0.0, 20.0, 8))
    dt = 0.8 * explicit_step_limit(mm, damping=damping)
    kw = {"scheme": "explicit", "damping": damping, "record_every": 7,
          "start": mm.equilibrium(),
          "initial": ([1e-3, -1e-3, 1e-3, 2e-3, -1e-3, 1e-3],
                      [0.01, 0.0, -0.01, 0.02, 0.01, -0.03]),
          "excitation": lambda t: np.array([1.0, -2.0, 3.0 * np.sin(10 * t), 0.5, -0.2, 0.1]),
          "record_nodes": True}
    monkeypatch.setattr(time_stepping, "_BLOCK", 37)          # the run in 9 calls
    r1 = simulate(mm, 300 * dt, dt, **kw)
    monkeypatch.setattr(compiled, "load", lambda name: None)
    r0 = simulate(mm, 300 * dt, dt, **kw)
    assert np.abs(r0.pose[-1] - r0.pose[0]).max() > 1e-4               # it moved
    pairs = [(name, getattr(r1, name), getattr(r0, name))
             for name in ("times", "pose", "velocity", "end_tensions", "anchor_tensions",
                          "unstretched_lengths")]
    pairs += [(f"nodes {i}", a, b) for i, (a, b) in enumerate(zip(r1.nodes, r0.nodes))]
    for name, a, b in pairs:
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-10 * np.abs(b).max(), err_msg=name)
    scale = np.abs(r0.energy.gravity).max()          # the residual is a difference of these
    for name in ("kinetic", "elastic", "gravity", "external_work", "dissipated", "residual"):
        a, b = getattr(r1.energy, name), getattr(r0.energy, name)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * scale, err_msg=name)


@pytest.mark.parametrize("dt, segments", [(1e-3, 6), (4e-3, [2, 3, 4, 5, 6, 7, 3, 5])])
def test_compiled_implicit_run_equals_the_stepwise_loop(cogiro, cogiro_eq, monkeypatch, dt,
                                                        segments):
    """The compiled Newmark run (Newton in the kernel, factors from scipy) gives the stepwise
    numpy run: a spinning, driven CoGiRo with all the damping terms, the same Newton
    iterations and factorisations, records every 7 steps, taken in blocks of 37 steps."""
    import dataclasses

    import dynstiff as ds
    from dynstiff.lumped import simulate
    rob = cogiro.robot
    cable = dataclasses.replace(rob.cables[0], viscous_damping=0.3)
    robot = ds.Robot(rob.anchors, rob.attachments, cable, rob.platform)
    mm = LumpedMassModel(robot, cogiro_eq.unstretched_lengths, segments=segments)
    damping = TimeDamping(alpha=0.3, beta=1e-4, axial=np.linspace(0.0, 20.0, 8))
    kw = {"scheme": "implicit", "damping": damping, "record_every": 7,
          "start": mm.equilibrium(), "record_nodes": True,
          "initial": ([1e-3, -1e-3, 1e-3, 2e-3, -1e-3, 1e-3],
                      [0.01, 0.0, -0.01, 0.02, 0.01, -0.03]),
          "excitation": lambda t: np.array([1.0, -2.0, 3.0 * np.sin(10 * t), 0.5, -0.2, 0.1])}
    monkeypatch.setattr(time_stepping, "_BLOCK", 37)
    r1 = simulate(mm, 100 * dt, dt, **kw)
    monkeypatch.setattr(compiled, "load", lambda name: None)
    r0 = simulate(mm, 100 * dt, dt, **kw)
    assert np.abs(r0.pose[-1] - r0.pose[0]).max() > 1e-4               # it moved
    assert (r1.newton_iterations, r1.jacobian_updates) == \
        (r0.newton_iterations, r0.jacobian_updates)
    assert r0.newton_iterations > 100                                  # Newton worked
    pairs = [(name, getattr(r1, name), getattr(r0, name))
             for name in ("times", "pose", "velocity", "end_tensions", "anchor_tensions")]
    pairs += [(f"nodes {i}", a, b) for i, (a, b) in enumerate(zip(r1.nodes, r0.nodes))]
    for name, a, b in pairs:
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-10 * np.abs(b).max(), err_msg=name)
    scale = np.abs(r0.energy.gravity).max()
    for name in ("kinetic", "elastic", "gravity", "external_work", "dissipated", "residual"):
        a, b = getattr(r1.energy, name), getattr(r0.energy, name)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * scale, err_msg=name)


