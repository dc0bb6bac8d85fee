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
    kick = [0.02, 0.0, 0.01, 0.0, 0.0, 0.0]
    from dynstiff.timedomain.dynamics import Dynamics
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
