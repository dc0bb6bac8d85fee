"""Tests of the time-domain simulation of the lumped-mass robot (dynstiff.timedomain.simulation).

References: theory.md §7.1 (lumped model), §7.3 (explicit limit dt < l0 / sqrt(EA / m), FFT
resolution 1 / T); the Newmark average-acceleration period error (omega dt)^2 / 12 and its
exact conservation of the energy of a linear system (Hughes, The Finite Element Method,
1987, §9.1); the large-amplitude pendulum period 4 sqrt(I / (m g d)) K(sin(theta_0 / 2))
(any mechanics text). Every number a tolerance rests on was measured with this code; the
comment next to it gives the measured value.
"""

import warnings

import numpy as np
import pytest
import scipy.special
from conftest import linearised, point_mass_robot

import dynstiff as ds
from dynstiff.errors import InvalidParameterError, SlackCableError
from dynstiff.lumped import (
    EnergyBalanceWarning,
    IntegrationError,
    LumpedMassModel,
    SlackSegmentWarning,
    TimeDamping,
    TimeResponse,
    TimeStepWarning,
    explicit_step_limit,
    simulate,
)

E17 = 8.2051e-6 * 17e9          # CoGiRo cable EA [N] (theory.md §8.1)


def pendulum(free_dofs):
    """A body pinned at P (cables attached at P carry no moment): a heavy pendulum / top."""
    anchors = np.array([[-2.0, -1.0, 3.0], [2.0, -1.0, 3.0], [0.0, 2.0, 3.0]])
    pl = ds.Platform(10.0, center_of_mass=[0.0, 0.0, -0.5], inertia=np.diag([0.8, 0.6, 0.3]),
                     free_dofs=free_dofs)
    rob = ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5), pl)
    m = linearised(rob, 0.999 * np.linalg.norm(anchors, axis=1), 2, initial_pose=np.zeros(6))
    return m


# ------------------------------------------------------------------ free vibration
def test_free_vibration_peaks_land_on_the_eigenfrequencies(robot_model):
    """Spectrum peaks of a free vibration (0.1 mm offset, zeta = 0.5 %) lie within the FFT
    resolution 1/T of the linearised lumped eigenfrequencies; the global modes are found and
    also match the closed-form dynamic-stiffness model."""
    m = robot_model(10)
    T, dt = 10.0, 0.005
    r = simulate(m, T, dt, initial=[1e-4, -0.5e-4, 0.75e-4, 0, 0, 0],
                 damping=TimeDamping.rayleigh(0.005, 3.0, 6.0))
    assert isinstance(r, TimeResponse) and r.slack_steps == 0
    modes = ds.modes(m, 40)
    f = modes.freq_hz
    global_f = f[np.array(modes.kind) == "global"]
    global_f = global_f[global_f < 7.0]                       # 4.950, 5.288, 6.288 Hz
    assert global_f.size == 3
    res = 1.0 / T
    found = []
    for ch in ("x", "y", "z"):
        sp = r.spectrum(ch, threshold=1e-2)
        assert sp.resolution_hz == pytest.approx(res, rel=1e-3)
        err = np.min(np.abs(sp.peaks_hz[:, None] - f[None, :]), axis=1)
        # measured: every peak within 0.035 Hz (Newmark period error (omega dt)^2/12 is
        # 0.02 Hz at 6.3 Hz), resolution 0.1 Hz
        assert np.all(err < res), (ch, sp.peaks_hz, err)
        found.append(sp.peaks_hz)
    found = np.concatenate(found)
    err_global = np.min(np.abs(global_f[:, None] - found[None, :]), axis=1)
    assert np.all(err_global < res)                         # measured <= 0.033 Hz
    closed = ds.eigenfrequencies(ds.FrequencyModel(point_mass_robot().equilibrium(
        unstretched_lengths=m.unstretched_lengths)), 12)
    err_closed = np.min(np.abs(global_f[:, None] - closed[None, :]), axis=1)
    assert np.all(err_closed < 0.1 * res)                   # the two models: <= 0.01 Hz


def test_cogiro_six_dof_spectrum_matches_global_modes():
    """6-DOF platform with rotations (CoGiRo, N = 4): the translation and rotation spectra
    peak on the lumped eigenfrequencies within 1/T."""
    scene = ds.load_scene("cogiro")
    m = linearised(scene.robot, scene.equilibrium().unstretched_lengths, 4)
    T = 5.0
    r = simulate(m, T, 0.01, initial=[1e-4, -1e-4, 1e-4, 2e-4, -3e-4, 4e-4],
                 damping=TimeDamping.rayleigh(0.005, 2.0, 4.0))
    modes = ds.modes(m, 40)
    f = modes.freq_hz
    g = f[(np.array(modes.kind) == "global") & (f < 5.5)]   # 2.21 2.36 2.97 3.81 4.96 Hz
    peaks = np.concatenate([r.spectrum(c, threshold=0.05).peaks_hz
                            for c in ("x", "y", "z", "rx", "ry", "rz")])
    err = np.min(np.abs(peaks[:, None] - f[None, :]), axis=1)
    assert np.all(err[peaks < 5.5] < 1.0 / T)               # measured <= 0.12 Hz, 1/T 0.2
    err_g = np.min(np.abs(g[:, None] - peaks[None, :]), axis=1)
    assert np.all(err_g < 1.0 / T)                           # measured <= 0.06 Hz
    assert np.max(np.abs(r.energy.relative_residual)) < 1e-3  # measured 4.1e-5


# ---------------------------------------------------------------------- energy
def _energy_run(m, periods):
    f1 = ds.eigenfrequencies(m, 1)[0]
    T1 = 1.0 / f1
    return simulate(m, periods * T1, T1 / 20, initial=[1e-4, -0.5e-4, 0.75e-4, 0, 0, 0],
                    record_every=10)


@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_static_equilibrium_stays_at_rest(robot_model, scheme):
    m = robot_model(3)
    dt = 0.01 if scheme == "implicit" else 0.5 * explicit_step_limit(m)
    r = simulate(m, 100 * dt, dt, scheme=scheme, record_every=10)
    assert np.max(np.abs(r.displacement)) < 1e-9            # measured ~1e-13 m
    assert np.max(np.abs(r.energy.relative_residual)) < 1e-12


def _check_conserved(r, tol):
    rel = r.energy.relative_residual
    n = rel.size // 10
    assert r.energy.dissipated[-1] == 0.0 and r.energy.external_work[-1] == 0.0
    assert np.max(np.abs(rel)) < tol
    # bounded, no secular drift: the last tenth is no worse than the first tenth
    assert np.max(np.abs(rel[-n:])) < 2.0 * np.max(np.abs(rel[:n])) + 1e-6
    return np.max(np.abs(rel))


def test_implicit_scheme_conserves_energy_over_100_periods(robot_model):
    """Undamped, fixed lengths, 0.1 mm offset, 20 steps per period of the first mode
    (2.857 Hz, N = 3): E - E0 stays within 2e-3 of the vibration energy (measured 1.4e-3,
    bounded: the trapezoidal rule conserves a linear system's energy exactly; the residual is
    its quadrature error of the geometric nonlinearity, O((omega dt)^2 x amplitude))."""
    r = _energy_run(robot_model(3), 100)
    _check_conserved(r, 2e-3)


@pytest.mark.slow
def test_implicit_scheme_conserves_energy_over_1000_periods(robot_model):
    """As above over 1,000 periods (20,000 steps); measured 1.55e-3, no drift (first and
    last tenth 1.42e-3 and 1.43e-3)."""
    r = _energy_run(robot_model(3), 1000)
    _check_conserved(r, 2e-3)


def test_energy_balance_with_loads_and_damping(robot_model):
    """External work and dissipation (Rayleigh, axial dashpots, cable viscous damping) are
    booked: the balance residual stays at the trapezoidal error level."""
    m = robot_model(5)
    robot = m.robot
    damped = ds.Robot(robot.anchors, robot.attachments,
                      ds.Cable(0.064, E17, viscous_damping=0.05), robot.platform)
    md = linearised(damped, m.unstretched_lengths, 5)

    def push(t):
        return np.array([5.0 * np.sin(2 * np.pi * 3.0 * t), 0.0, 3.0 * np.cos(7.0 * t),
                         0.0, 0.0, 0.0])

    r = simulate(md, 2.0, 0.005, excitation=push,
                 damping=TimeDamping(alpha=0.2, beta=1e-4, axial=5.0))
    e = r.energy
    assert e.dissipated[-1] > 0 and np.all(np.diff(e.dissipated) >= -1e-15)
    assert abs(e.external_work[-1]) > 0
    assert np.max(np.abs(e.relative_residual)) < 1e-3      # measured 1.5e-5


# --------------------------------------------------------------------- explicit
def _blows_up(m, dt, steps):
    try:
        with warnings.catch_warnings():
            # a blow-up is what is probed: the step-limit, slack and energy-ledger warnings
            # that come with it are expected
            warnings.simplefilter("ignore", TimeStepWarning)
            warnings.simplefilter("ignore", SlackSegmentWarning)
            warnings.simplefilter("ignore", EnergyBalanceWarning)
            simulate(m, steps * dt, dt, scheme="explicit", initial=[1e-3, 0, 0, 0, 0, 0])
    except IntegrationError:
        return True
    return False


def test_explicit_stability_limit_matches_prediction(robot_model):
    """Bisection on dt for a blow-up within 600 steps: the measured limit is within 20 % of
    l0 / sqrt(EA / m) (theory.md §7.3). Measured 1.0125 x predicted for N = 10, the exact
    chain factor 1 / sin(9 pi / 20) = 1.0125."""
    m = robot_model(10)
    pred = explicit_step_limit(m)
    lo, hi = 0.5 * pred, 2.0 * pred
    assert not _blows_up(m, lo, 600) and _blows_up(m, hi, 600)
    for _ in range(9):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if _blows_up(m, mid, 600) else (mid, hi)
    measured = 0.5 * (lo + hi)
    assert abs(measured / pred - 1.0) < 0.2
    assert measured / pred == pytest.approx(1.0 / np.sin(9 * np.pi / 20), abs=0.01)


def test_explicit_and_implicit_agree_below_the_limit(robot_model):
    m = robot_model(5)
    dt = 0.5 * explicit_step_limit(m)
    kw = dict(initial=[1e-4, 0, 0, 0, 0, 0], record_every=50)
    ex = simulate(m, 0.2, dt, scheme="explicit", **kw)
    im = simulate(m, 0.2, dt, scheme="implicit", **kw)
    np.testing.assert_allclose(ex.displacement, im.displacement, atol=1e-7)  # 1e-4 m motion
    assert np.max(np.abs(ex.energy.relative_residual)) < 1e-4


def test_implicit_is_stable_far_beyond_the_explicit_limit(robot_model):
    """The implicit scheme is not bound by the segment CFL limit: at 20x the explicit limit
    (where central differences blow up within a few steps) it runs 400 steps with a bounded
    energy residual and the platform motion stays at the imposed amplitude."""
    m = robot_model(10)
    dt = 20 * explicit_step_limit(m)
    assert _blows_up(m, dt, 50)
    res = simulate(m, 400 * dt, dt, scheme="implicit", initial=[1e-4, 0, 0, 0, 0, 0])
    assert np.all(np.isfinite(res.displacement))
    assert np.max(np.abs(res.displacement)) < 2e-4
    assert np.max(np.abs(res.energy.relative_residual)) < 1e-2


def test_blow_up_raises_integration_error_not_nan(robot_model):
    m = robot_model(5)
    dt = 1.5 * explicit_step_limit(m)
    with pytest.warns(TimeStepWarning, match="stability limit"):
        with pytest.raises(IntegrationError, match=r"step \d+.*dt = ") as exc:
            with warnings.catch_warnings():        # the blow-up slackens cables and breaks
                warnings.simplefilter("ignore", SlackSegmentWarning)       # the energy ledger
                warnings.simplefilter("ignore", EnergyBalanceWarning)
                simulate(m, 2000 * dt, dt, scheme="explicit", initial=[1e-3, 0, 0, 0, 0, 0])
    assert exc.value.dt == dt and exc.value.step >= 1


def test_slack_segment_warns_and_snapping_is_caught(robot_model):
    """An upward kick of 0.6 m/s unloads the cables (the platform rises 22 mm, the static
    stretch is 4.6 mm) and they snap taut again. The first slack segment warns. At dt = 1 ms
    the run completes, finite, with the balance residual at 1 % (0.5 % at 0.5 ms, 0.12 % at
    0.2 ms: first order in dt, the trapezoidal rule meets the kinks of the tension-only law);
    at dt = 2 ms the snaps keep creating energy: the ledger warns first
    (EnergyBalanceWarning at 10 % of the scale), then IntegrationError stops the run when
    the residual passes 10 times the scale, never NaN."""
    m = robot_model(5)
    kick = ([0] * 6, [0, 0, 0.6, 0, 0, 0])
    with pytest.warns(SlackSegmentWarning, match="went slack"):
        r = simulate(m, 0.3, 0.001, initial=kick, record_every=10)
    assert r.slack_steps > 50
    assert r.pose[:, 2].max() - r.pose[0, 2] > 0.02
    assert np.all(np.isfinite(r.pose)) and np.all(np.isfinite(r.energy.residual))
    assert np.max(np.abs(r.energy.relative_residual)) < 0.02
    with pytest.warns(SlackSegmentWarning), pytest.warns(EnergyBalanceWarning):
        with pytest.raises(IntegrationError, match="energy balance residual.*reduce dt"):
            simulate(m, 0.3, 0.002, initial=kick)


# ----------------------------------------------------------------------- winches
def _ramp(x):
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def test_winch_pay_out_then_reel_in(robot_model):
    """All cables paid out by 2 cm over 1.5 s, held, reeled in: the platform lowers to the
    static equilibrium of the longer cables and comes back; the energy balance (winch work,
    carried kinetic energy, dissipation) closes to 1e-6 of the winch work (measured 6e-8)."""
    m = robot_model(5)
    L0 = m.unstretched_lengths.copy()

    def lengths(t):
        return L0 + 0.02 * (_ramp(t / 1.5) - _ramp((t - 3.0) / 1.5))

    r = simulate(m, 6.0, 0.005, lengths=lengths,
                 damping=TimeDamping.rayleigh(0.02, 2.9, 6.3))
    e = r.energy
    assert np.max(np.abs(e.relative_residual)) < 1e-6
    assert e.winch_work.min() < -5.0                         # paying out gives energy back
    assert e.winch_work[-1] == pytest.approx(e.dissipated[-1], rel=1e-3)
    z0 = m.pose.position[2]
    low = LumpedMassModel(m.robot, L0 + 0.02, segments=5).equilibrium().pose.position
    k = np.argmin(np.abs(r.times - 3.0))
    np.testing.assert_allclose(r.pose[k, :3], low, atol=1e-4)   # measured 6e-6 m
    assert low[2] < z0 - 0.03                                # 30.5 mm lower
    np.testing.assert_allclose(r.pose[-1, :3], m.pose.position, atol=1e-4)
    np.testing.assert_allclose(r.unstretched_lengths[k], L0 + 0.02, rtol=1e-12)
    # the winch work is, to O(l0), the anchor tension times the paid-out length plus the
    # weight of the paid-out mass at the anchor height (module notes): measured 0.6 % at N=5
    power = -r.anchor_tensions + 0.064 * m.robot.g * m.robot.anchors[:, 2]
    dL = np.diff(r.unstretched_lengths, axis=0)
    work = np.concatenate([[0.0], np.cumsum(np.sum(0.5 * (power[1:] + power[:-1]) * dL,
                                                   axis=1))])
    j = np.argmin(np.abs(r.times - 1.5))
    assert work[j] == pytest.approx(e.winch_work[j], rel=0.02)


def test_fast_winch_energy_balance_converges_at_second_order(robot_model):
    """A 0.3 s pay-out (undamped): the balance residual falls 4x per halving of dt
    (measured 4.4e-4, 1.1e-4, 2.8e-5 J for dt = 10, 5, 2.5 ms; winch work 4 J)."""
    m = robot_model(5)
    L0 = m.unstretched_lengths.copy()

    def lengths(t):
        return L0 + np.array([0.03, 0.0, 0.01]) * (_ramp(t / 0.3) - _ramp((t - 1.3) / 0.3))

    res = [np.max(np.abs(simulate(m, 1.6, dt, lengths=lengths).energy.residual))
           for dt in (0.01, 0.005)]
    assert 3.0 < res[0] / res[1] < 5.0
    assert res[1] < 2e-4


def test_lengths_table_equals_callable_and_sets_the_start(robot_model, lengths0):
    m = robot_model(3)
    start = lengths0 + np.array([0.0, 0.01, 0.0])
    times = np.array([0.0, 1.0])
    table = np.vstack([start, start + 0.005])
    a = simulate(m, 0.5, 0.01, lengths=(times, table), record_every=10)
    b = simulate(m, 0.5, 0.01, lengths=lambda t: start + 0.005 * t, record_every=10)
    np.testing.assert_allclose(a.pose, b.pose, atol=1e-12)
    eq = LumpedMassModel(m.robot, start, segments=3).equilibrium()
    np.testing.assert_allclose(a.equilibrium_pose[:3], eq.pose.position, atol=1e-12)


# ------------------------------------------------------------- large rotations
def test_large_amplitude_pendulum_period():
    """Pinned body, one free rotation, 1 rad amplitude: the period matches the elliptic-
    integral period within 5e-4 (measured 3.3e-4 = the Newmark error (2 pi / 100)^2 / 12)."""
    m = pendulum(("ry",))
    I, mass, d, g = 0.6 + 10.0 * 0.25, 10.0, 0.5, m.robot.g
    exact = 4 * np.sqrt(I / (mass * g * d)) * scipy.special.ellipk(np.sin(0.5) ** 2)
    r = simulate(m, 2.2 * exact, exact / 100, initial=[0, 0, 0, 0, 1.0, 0])
    th = r.pose[:, 4]
    i = np.flatnonzero((th[:-1] < 0) & (th[1:] >= 0))
    tc = r.times[i] - th[i] * (r.times[i + 1] - r.times[i]) / (th[i + 1] - th[i])
    assert np.diff(tc)[0] / exact - 1 == pytest.approx(0.0, abs=5e-4)
    assert np.max(np.abs(r.energy.relative_residual)) < 5e-4  # measured 1.7e-4


def test_heavy_top_conserves_vertical_angular_momentum():
    """Pinned asymmetric body spun about the vertical with a 0.85 rad tilt (rotation vector
    up to pi): gravity has no vertical moment about P, so H_z = (I_P w)_z is conserved; the
    rotation is composed exactly, so drift and energy residual are O(dt^2) (measured 1.0e-4
    and 1.1e-4 at dt = 5 ms)."""
    from scipy.spatial.transform import Rotation
    m = pendulum(("rx", "ry", "rz"))
    r = simulate(m, 1.5, 0.005, initial=([0, 0, 0, 0.8, 0.3, 0.0], [0, 0, 0, 0, 0, 4.0]))
    assert np.max(np.linalg.norm(r.pose[:, 3:], axis=1)) > 3.0
    I_G, c, mass = np.diag([0.8, 0.6, 0.3]), np.array([0.0, 0.0, -0.5]), 10.0
    Hz = []
    for R, w in zip(Rotation.from_rotvec(np.array(r.pose[:, 3:])).as_matrix(),
                    r.velocity[:, 3:]):
        rG = R @ c
        I_P = R @ I_G @ R.T + mass * (rG @ rG * np.eye(3) - np.outer(rG, rG))
        Hz.append((I_P @ w)[2])
    Hz = np.array(Hz)
    assert np.max(np.abs(Hz / Hz[0] - 1)) < 3e-4
    assert np.max(np.abs(r.energy.relative_residual)) < 3e-4


# ---------------------------------------------------------------- inputs, output
def test_bad_inputs_raise_typed_errors_naming_the_argument(robot_model, lengths0):
    m = robot_model(3)
    with pytest.raises(InvalidParameterError, match="dt"):
        simulate(m, 1.0, 0.0)
    with pytest.raises(InvalidParameterError, match="dt"):
        simulate(m, 1.0, -1e-3)
    with pytest.raises(InvalidParameterError, match="t_end"):
        simulate(m, 0.0, 1e-3)
    with pytest.raises(InvalidParameterError, match="dt must be <= t_end"):
        simulate(m, 1e-3, 1e-2)
    with pytest.raises(InvalidParameterError, match="scheme"):
        simulate(m, 1.0, 1e-3, scheme="rk4")
    with pytest.raises(InvalidParameterError, match="record_every"):
        simulate(m, 1.0, 1e-3, record_every=0)
    with pytest.raises(InvalidParameterError, match="excitation"):
        simulate(m, 1.0, 1e-3, excitation=lambda t: np.zeros(3))
    with pytest.raises(InvalidParameterError, match="initial"):
        simulate(m, 1.0, 1e-3, initial=[0, 0, 0, 0.1, 0, 0])      # rx is held
    with pytest.raises(InvalidParameterError, match="damping"):
        simulate(m, 1.0, 1e-3, damping=0.01)
    with pytest.raises(InvalidParameterError, match="lengths"):
        simulate(m, 1.0, 1e-3, lengths=([0.0, 1.0], np.ones((2, 2))))
    with pytest.raises(InvalidParameterError, match="lengths"):
        simulate(m, 1.0, 1e-2, lengths=lambda t: lengths0 * (1.0 if t < 0.05 else -1.0))
    with pytest.raises(SlackCableError, match="lengths"):         # no taut equilibrium
        simulate(m, 1.0, 1e-3, lengths=lambda t: lengths0 + [20.0, 0.0, 0.0])
    weightless = ds.Robot(m.robot.anchors, m.robot.attachments, m.robot.cables,
                          m.robot.platform, g=0.0)
    chords = np.linalg.norm(m.robot.anchors - m.pose.position, axis=1)
    with pytest.raises(SlackCableError, match="lengths"):         # longer than the chord
        simulate(LumpedMassModel(weightless, 0.99 * chords, segments=3), 1.0, 1e-3,
                 lengths=lambda t: 1.01 * chords)
    with pytest.raises(InvalidParameterError, match="segments"):
        LumpedMassModel(m.robot, lengths0, segments=0)
    with pytest.raises(InvalidParameterError, match="model"):
        simulate(m.robot, 1.0, 1e-3)


@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_excitation_table_equals_its_interpolating_callable(robot_model, scheme):
    """A load table (times, loads) is the callable that interpolates it linearly and holds its
    last row (the explicit scheme evaluates the table at all steps at once)."""
    m = robot_model(3)
    rng = np.random.default_rng(3)
    times = np.r_[-0.01, np.sort(rng.uniform(0.0, 0.05, 9))]
    loads = rng.uniform(-20.0, 20.0, (times.size, 6))

    def fn(t):
        return np.array([np.interp(t, times, loads[:, j]) for j in range(6)])
    dt = 0.5 * explicit_step_limit(m.mass_model)
    r_tab = simulate(m, 0.08, dt, excitation=(times, loads), scheme=scheme, record_every=3)
    r_fn = simulate(m, 0.08, dt, excitation=fn, scheme=scheme, record_every=3)
    assert np.abs(r_fn.displacement).max() > 1e-6                       # it moved
    np.testing.assert_array_equal(r_tab.pose, r_fn.pose)
    np.testing.assert_array_equal(r_tab.energy.external_work, r_fn.energy.external_work)
    for bad in ((times, loads[:, :3]), (times[::-1], loads), (times + 1.0, loads),
                (times, np.where(loads > 15, np.nan, loads)), "table"):
        with pytest.raises(InvalidParameterError, match="excitation"):
            simulate(m, 0.01, dt, excitation=bad, scheme=scheme)


def test_absurd_starts_and_run_lengths_are_refused_before_any_step():
    """A 1000 m offset stretches a segment 567 times its length: the error names the offset
    (it used to blame dt after a blown-up step). A 1e9 s run at 1 ms would ask for 1e12
    records (7 TiB): refused naming t_end, dt and the max_records guard."""
    eq = ds.load_scene("fourcable").equilibrium()
    m = ds.build_model(eq, "lumped", segments=2)
    with pytest.raises(ds.InvalidParameterError, match="strain 567 .* initial offset"):
        simulate(m, 0.05, 1e-3, initial=[1000.0, 0, 0, 0, 0, 0])
    with pytest.raises(ds.InvalidParameterError, match="t_end = 1e\\+09 s .* max_records"):
        simulate(m, 1e9, 1e-3)
    r = simulate(m, 1.0, 1e-3, record_every=10, max_records=101)
    assert r.times.size == 101


def test_a_worded_record_nodes_flag_is_refused():
    """record_nodes="no" recorded every node (a non-empty string is true)."""
    lm = ds.build_model(ds.load_scene("planar2").equilibrium(), "lumped", segments=3)
    with pytest.raises(InvalidParameterError, match="^record_nodes must be True or False"):
        simulate(lm, 0.01, 1e-3, record_nodes="no")


@pytest.mark.parametrize("kw, name", [
    (dict(excitation=([0, 1], [[True, 0, 0, 0, 0, 0], [0] * 6])), "excitation"),
    (dict(lengths=([0, 1], [[True, 5.0], [5.0, 5.0]])), "lengths")])
def test_tables_of_booleans_are_refused_naming_them(kw, name):
    """A load of True was 1 N; a length of True was 1 m, said as a strain of 4."""
    lm = ds.build_model(ds.load_scene("planar2").equilibrium(), "lumped", segments=3)
    with pytest.raises(InvalidParameterError, match=f"^{name} must be a callable"):
        simulate(lm, 0.01, 1e-3, **kw)
