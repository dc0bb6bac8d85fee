"""The energy-consistent time step and its step control (dynstiff/timedomain/energy_scheme.py,
theory.md §7.3): the energy ledger closes to the Newton tolerance through slack and snap,
where the trapezoidal "implicit" scheme fails; second order and equal to it on a taut run."""

import warnings

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import ConvergenceError
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.timedomain.simulation import SlackSegmentWarning, simulate
from dynstiff.timedomain.stepping import EnergyBalanceWarning, IntegrationError

POSE = [-2.0, 0.0, -10.0, 0.0, 0.0, 0.0]


@pytest.fixture(scope="module")
def planar():
    """The planar two-cable robot (100 kg, EA 1e7 N), 6 segments per cable, at rest."""
    rob = ds.load_scene("planar2").robot
    eq = rob.equilibrium(pose=POSE)
    m = LumpedMassModel(rob, [s.unstretched_length for s in eq.states], 6)
    return m, m.equilibrium(initial_pose=POSE)


def _run(planar, t_end, dt, scheme, velocity, **kw):
    m, start = planar
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SlackSegmentWarning)       # counted in slack_steps
        return simulate(m, t_end, dt, scheme=scheme, start=start,
                        initial=(np.zeros(6), velocity), **kw)


def test_slack_and_snap_keep_the_energy_where_the_trapezoidal_rule_fails(planar):
    """A 2 m/s upward kick: the cables go slack for the whole 0.6 s and snap taut again.
    The energy scheme closes the ledger to 1e-8 of the energy scale (measured 1e-10 to 5e-10
    at dt = 4 ... 0.0625 ms); the trapezoidal rule's Newton iteration fails at every one of
    those steps (at t = 0.26 s with dt = 4 ms)."""
    kick = [1.5, 0.0, 2.0, 0.0, 0.0, 0.0]
    r = _run(planar, 0.6, 2e-3, "energy", kick)
    assert r.slack_steps == r.n_steps == 300
    assert np.abs(r.energy.relative_residual).max() < 1e-8
    assert r.substeps == 0
    assert r.pose[:, 2].max() > POSE[2] + 0.05                      # it flew up
    with warnings.catch_warnings(), pytest.raises((ConvergenceError, IntegrationError)):
        # its ledger warns before it fails; the failure is the subject here
        warnings.simplefilter("ignore", EnergyBalanceWarning)
        _run(planar, 0.6, 4e-3, "implicit", kick)


def test_on_a_taut_run_it_is_the_trapezoidal_rule_and_second_order(planar):
    """A small kick (no slack): the platform path at dt = 1 ms equals the implicit scheme's
    to 1e-8 m (measured 1.1e-9: for a linear system the discrete gradient is the average of
    the forces), its error against dt = 0.25 ms falls by 4.0 and 4.2 at each halving from
    4 ms, and its ledger closes to 1e-8 where the trapezoidal rule's misses by 2e-6 to 3e-5
    (its quadrature of the nonlinear spring forces)."""
    kick = [0.02, 0.0, 0.01, 0.0, 0.0, 0.0]
    ref = _run(planar, 0.3, 2.5e-4, "energy", kick, record_every=16).pose[:, [0, 2]]
    err = []
    for dt in (4e-3, 2e-3, 1e-3):
        r = _run(planar, 0.3, dt, "energy", kick, record_every=int(round(4e-3 / dt)))
        assert r.slack_steps == 0
        assert np.abs(r.energy.relative_residual).max() < 1e-8
        err.append(np.abs(r.pose[:, [0, 2]] - ref).max())
    assert 3.6 < err[0] / err[1] < 4.4 and 3.6 < err[1] / err[2] < 4.4
    imp = _run(planar, 0.3, 1e-3, "implicit", kick, record_every=4)
    assert np.abs(imp.pose - r.pose).max() < 1e-8
    assert np.abs(imp.energy.relative_residual).max() > 1e-6


def test_a_step_whose_newton_fails_is_halved(planar):
    """With 3 Newton iterations allowed, the kicked run splits 1112 of its steps (measured)
    and still closes the ledger; with 1 none converges and, after 10 halvings, the error
    says so with the residual."""
    kick = [1.5, 0.0, 2.0, 0.0, 0.0, 0.0]
    r = _run(planar, 0.6, 2e-3, "energy", kick, max_iter=3)
    assert r.substeps > 100
    assert np.abs(r.energy.relative_residual).max() < 1e-8
    assert r.times[-1] == pytest.approx(0.6) and r.times.size == 301     # records on the grid
    with pytest.raises(ConvergenceError, match="halved 10 times") as err:
        _run(planar, 0.1, 2e-3, "energy", kick, max_iter=1)
    assert err.value.residual > 1e-9


def test_with_winches_the_ledger_closes_and_the_path_is_the_implicit_one():
    """The planar robot tracking 2 m at 1 m/s through its winches (no slack): the same
    largest deviation as the implicit scheme (1.088e-3 m, to 1e-8 m) and the ledger closed to
    1e-8 (measured 2e-10; the implicit scheme's trapezoidal winch work misses by 2e-2 at
    dt = 2 ms)."""
    from dynstiff.timedomain.trajectory import line, track
    rob = ds.load_scene("planar2").robot
    rob = ds.Robot(rob.anchors, rob.attachments, ds.Cable(0.1, 1e7), rob.platform,
                   tension_limits=rob.tension_limits)
    path = line([-5.0, 0.0, -10.0], [-3.0, 0.0, -10.0], 1.0, ramp=0.5)
    res = {s: track(rob, path, segments=10, dt=2e-3, settle=1.0, scheme=s)
           for s in ("energy", "implicit")}
    assert res["energy"].max_deviation == pytest.approx(res["implicit"].max_deviation,
                                                        abs=1e-8)
    assert np.abs(res["energy"].response.energy.relative_residual).max() < 1e-8
    assert np.abs(res["implicit"].response.energy.relative_residual).max() > 1e-3
    assert res["energy"].response.energy.winch_work[-1] != 0.0


def test_axial_dashpots_from_the_first_step_keep_the_ledger_closed(planar):
    """Axial dashpots (c_ax = 200 N s) on a kicked run: the scheme applies their work by its
    own discrete gradient, so the start's damping force leaves them out; the ledger closes
    to 1e-8 of the energy scale from the first step on, and the dashpots dissipate energy
    (the dissipated work grows)."""
    from dynstiff.timedomain.damping import TimeDamping
    from dynstiff.timedomain.dynamics import Dynamics
    kick = [0.02, 0.0, 0.01, 0.0, 0.0, 0.0]
    real, flags = Dynamics.forces, []

    def forces(self, *args, **kw):
        flags.append(kw.get("dashpots", True))
        return real(self, *args, **kw)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Dynamics, "forces", forces)
        r = _run(planar, 0.02, 1e-3, "energy", kick, damping=TimeDamping(axial=200.0))
    assert np.abs(r.energy.relative_residual).max() < 1e-8
    assert r.energy.dissipated[-1] > 0.0
    # the run's start (for every scheme) with its dashpots, then the scheme's own forces
    # without them, the first step's start included
    assert flags[0] is True and len(flags) > 20 and not any(flags[1:])


def test_loads_and_rayleigh_damping_enter_as_in_the_implicit_scheme(planar):
    """A platform load (50 N and 30 N sines) and Rayleigh damping on a taut run: for a
    linear system the discrete gradient is the average of the forces, so the path equals the
    implicit scheme's to 1e-8 m (measured 5e-10); the ledger, whose external work and
    dissipation both move, closes to 1e-8 (measured 2e-9). Newton counts its iterations and
    its matrix updates."""
    from dynstiff.timedomain.damping import TimeDamping

    def load(t):
        return np.array([50 * np.sin(10 * np.pi * t), 0, 30 * np.sin(6 * np.pi * t), 0, 0, 0])
    kw = dict(excitation=load, damping=TimeDamping(alpha=0.5, beta=1e-4))
    kick = [0.02, 0.0, 0.01, 0.0, 0.0, 0.0]
    e = _run(planar, 0.1, 1e-3, "energy", kick, **kw)
    i = _run(planar, 0.1, 1e-3, "implicit", kick, **kw)
    assert np.abs(e.pose - i.pose).max() < 1e-8
    assert np.abs(e.energy.relative_residual).max() < 1e-8
    assert np.abs(e.energy.external_work).max() > 1e-3 and e.energy.dissipated[-1] > 1e-3
    assert e.newton_iterations >= e.n_steps and 1 <= e.jacobian_updates <= e.newton_iterations


def test_a_spinning_platform_follows_the_implicit_path(cogiro):
    """CoGiRo (2 segments a cable) kicked into a spin about three axes, where the gyroscopic
    term w x (I w) acts: the energy scheme's path equals the implicit scheme's to 1e-9 m
    over 10 ms (measured 2.5e-11) and its ledger closes to 1e-8."""
    eq = cogiro.equilibrium()
    m = LumpedMassModel(cogiro.robot, eq.unstretched_lengths, 2)
    kw = dict(start=m.equilibrium(initial_pose=eq.pose),
              initial=(np.zeros(6), [0.0, 0.0, 0.0, 0.05, -0.04, 0.03]))
    e = simulate(m, 0.01, 1e-3, scheme="energy", **kw)
    i = simulate(m, 0.01, 1e-3, scheme="implicit", **kw)
    assert np.abs(e.pose - i.pose).max() < 1e-9
    assert np.abs(e.energy.relative_residual).max() < 1e-8


def test_halved_steps_tile_the_time_and_the_failure_names_its_time(planar, monkeypatch):
    """The sub-steps that succeed in a run with halvings follow each other without gap or
    overlap from 0 to t_end; a step that fails even when halved 10 times is reported at the
    end time of the sub-step that failed, t_a + dt / 2^10."""
    from dynstiff.timedomain.energy_scheme import EnergyStepper
    real, done, tried = EnergyStepper._single, [], []

    def single(self, state, t_a, h, *args):
        tried.append((t_a, h))
        out = real(self, state, t_a, h, *args)
        done.append((t_a, h))
        return out
    monkeypatch.setattr(EnergyStepper, "_single", single)
    kick = [1.5, 0.0, 2.0, 0.0, 0.0, 0.0]
    r = _run(planar, 0.02, 2e-3, "energy", kick, max_iter=3)
    assert r.substeps > 0 and len(done) > r.n_steps
    t = np.array(done)
    assert t[0, 0] == 0.0
    np.testing.assert_allclose(t[1:, 0], t[:-1, 0] + t[:-1, 1], rtol=0, atol=1e-15)
    assert t[-1, 0] + t[-1, 1] == pytest.approx(0.02, abs=1e-15)
    tried.clear()
    with pytest.raises(ConvergenceError, match="even with the step halved 10 times") as err:
        _run(planar, 0.02, 2e-3, "energy", kick, max_iter=1)
    t_a, h = tried[-1]
    assert h == 2e-3 / 2 ** 10
    assert f"at step 1 (t = {t_a + h:g} s) even with the step halved 10 times (to {h:g} s)" \
        in str(err.value)


def test_a_state_that_overflows_fails_with_an_infinite_residual(planar):
    """A load of 1e300 N from t = 1.5 ms drives the state to overflow: the step fails even
    when halved, and the error says the state is not finite, with an infinite residual.
    numpy warns of the overflow on the way (RuntimeWarning, ignored here: the failure is the
    subject)."""
    def load(t):
        return np.array([1e300 if t > 1.5e-3 else 0.0, 0, 0, 0, 0, 0])
    with warnings.catch_warnings(), pytest.raises(ConvergenceError,
                                                  match="non-finite state") as err:
        warnings.simplefilter("ignore", RuntimeWarning)
        _run(planar, 0.01, 1e-3, "energy", np.zeros(6), excitation=load)
    assert err.value.residual == np.inf


def test_winding_through_halved_steps_keeps_the_ledger_closed(planar):
    """Cable 0 reeled in and cable 1 paid out at 0.5 m/s for 0.1 s, Newton allowed 3
    iterations: steps are halved (measured 215 times) while the winches carry kinetic energy
    in and out with the cable, and every sub-step's share enters the ledger, which closes to
    1e-9 (measured 3e-11). Cable 1 goes slack (SlackSegmentWarning, counted, ignored here)."""
    m, start = planar
    L0 = m.unstretched_lengths.copy()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SlackSegmentWarning)
        r = simulate(m, 0.1, 2e-3, lengths=lambda t: L0 + np.array([-0.5, 0.5]) * t,
                     scheme="energy", start=start, max_iter=3)
    assert r.substeps > 100 and r.energy.carried_kinetic[-1] > 1e-5
    assert np.abs(r.energy.relative_residual).max() < 1e-9
