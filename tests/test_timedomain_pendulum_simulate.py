"""Time response of the cable pendulum (dynstiff.timedomain.pendulum.simulate): ``simulate``
argument checks and the ``PendulumResponse`` views (tensions at D, amplitude growth, table)."""

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.timedomain import pendulum as pdl
from dynstiff.timedomain.pendulum.simulate import PendulumResponse

#: Paper 004, Sec. 3: m = 9.864 kg, I_A = 3.288 kg m^2, c = 0.5 m, a = 1.2 m, d = 0.75 m,
#: k = 8.264e4 N/m; cable damping b = 5e-4 k [N s/m].
M, I_A, C, A, D, K, G = 9.864, 3.288, 0.5, 1.2, 0.75, 8.264e4, 9.81
B = 5e-4 * K


def pendulum(**kw):
    """Massless-cable pendulum of the paper, ends at the pin's level."""
    args = dict(inertia=I_A, mass=M, com_distance=C, attach_distance=D, half_span=A,
                stiffness=K, damping=B, g=G)
    args.update(kw)
    return pdl.CablePendulum(**args)


def cable_tensions(P, t, y, f, x0, psi):
    """Tension at D of the massless cables [N], written out: T_i = max(k (L_i - L0) + b
    dL_i/dt, 0) with L0 = L - P / k, L_i = |D(phi) - E_i|, D = d (sin phi, cos phi), ends
    E_B = (-a - x0 sin(w t), 0) and E_C = (a + x0 sin(w t - psi), 0), w = 2 pi f."""
    w = 2 * np.pi * f
    phi, dphi = y[:, 0], y[:, 1]
    Dp = D * np.stack([np.sin(phi), np.cos(phi)], axis=1)
    dD = D * dphi[:, None] * np.stack([np.cos(phi), -np.sin(phi)], axis=1)
    L0 = np.hypot(A, D) - P / K
    out = []
    for sx, arg in ((-1.0, w * t), (1.0, w * t - psi)):
        E = np.stack([sx * (A + x0 * np.sin(arg)), np.zeros_like(t)], axis=1)
        dE = np.stack([sx * x0 * w * np.cos(arg), np.zeros_like(t)], axis=1)
        r = Dp - E
        L = np.linalg.norm(r, axis=1)
        dL = np.sum(r * (dD - dE), axis=1) / L
        out.append(np.maximum(K * (L - L0) + B * dL, 0.0))
    return np.stack(out, axis=1)


# ------------------------------------------------------------------ argument checks
@pytest.mark.parametrize("rtol, got", [(0.0, "0.0"), (-1e-8, "-1e-08")])
def test_relative_tolerance_must_be_positive(rtol, got):
    """rtol scales every absolute tolerance, so it must be > 0; the message names it."""
    with pytest.raises(InvalidParameterError, match=rf"^rtol must be > 0, got {got}$"):
        pdl.simulate(pendulum(preload=1000.0), 5.0, 0.0, 0.1, rtol=rtol)


# ------------------------------------------------------------------ tensions
def test_upright_pendulum_at_rest_carries_the_preload():
    """phi0 = 0 and ends at rest: the upright pose is an equilibrium (the two cables pull
    symmetrically), so both cables keep their preload P = 1500 N at D at every output."""
    r = pdl.simulate(pendulum(preload=1500.0), 5.0, 0.0, 0.2, phi0=0.0, n_out=11)
    np.testing.assert_array_equal(r.phi, 0.0)
    Tn = r.tensions()
    assert Tn.shape == (11, 2)
    np.testing.assert_allclose(Tn, 1500.0, rtol=1e-10)


def test_tensions_follow_the_moving_ends_and_the_swing():
    """Taut cables (P = 2066 N), ends moving 5 mm at 7 Hz with a phase lag 0.9 rad, tilted
    start: the tensions at D are the spring-damper forces of the two cables written out in
    ``cable_tensions`` from the simulated angle and rate and the prescribed end motion [N]."""
    f, x0, psi = 7.0, 0.005, 0.9
    r = pdl.simulate(pendulum(preload=2066.0), f, x0, 0.15, phase=psi, phi0=2e-3, n_out=61)
    Tn = r.tensions()
    expected = cable_tensions(2066.0, r.t, r.y, f, x0, psi)
    assert Tn.min() > 0.0                               # taut throughout: no clipping here
    np.testing.assert_allclose(Tn, expected, rtol=1e-9)
    # the two cables differ: the ends move out of phase and the pendulum swings
    assert np.abs(Tn[:, 0] - Tn[:, 1]).max() > 100.0


def test_slack_cables_carry_no_compression():
    """No preload, ends moving 20 mm at 30 Hz: each cable goes slack for part of every
    period (the end moves inward further than the cable is stretched). A cable pushes
    nothing: the tension is exactly 0 N while slack, and otherwise the spring-damper force."""
    f, x0 = 30.0, 0.02
    r = pdl.simulate(pendulum(preload=0.0), f, x0, 2 / f, phi0=1e-4, n_out=129)
    Tn = r.tensions()
    expected = cable_tensions(0.0, r.t, r.y, f, x0, 0.0)
    assert Tn.min() == 0.0 and np.mean(Tn == 0.0) > 0.2        # slack a good part of the time
    assert Tn.max() > 1000.0                                   # and taut again in between
    np.testing.assert_allclose(Tn, expected, rtol=1e-9, atol=1e-9)


def test_table_has_the_time_angle_and_both_tensions():
    """to_frame: one row per output time, the columns named with their units, holding t,
    phi and the tensions at D of cable 1 (end B) and cable 2 (end C)."""
    f, x0 = 7.0, 0.005
    r = pdl.simulate(pendulum(preload=2066.0), f, x0, 0.05, phase=0.9, phi0=2e-3, n_out=21)
    df = r.to_frame()
    assert list(df.columns) == ["t [s]", "phi [rad]", "T_B [N]", "T_C [N]"]
    assert len(df) == 21
    np.testing.assert_array_equal(df["t [s]"], np.linspace(0.0, 0.05, 21))
    np.testing.assert_array_equal(df["phi [rad]"], r.phi)
    Tn = cable_tensions(2066.0, r.t, r.y, f, x0, 0.9)
    np.testing.assert_allclose(df["T_B [N]"], Tn[:, 0], rtol=1e-9)
    np.testing.assert_allclose(df["T_C [N]"], Tn[:, 1], rtol=1e-9)


# ------------------------------------------------------------------ amplitude growth
def exponential_response(sigma, f=2.0, periods=12, per_period=64):
    """A response whose angle is exp(sigma t) [rad], sampled at the dyadic times k / (64 f)
    (exact in binary, so the period boundaries are samples) over ``periods`` periods."""
    t = np.arange(periods * per_period + 1) / (per_period * f)
    y = np.column_stack([np.exp(sigma * t), sigma * np.exp(sigma * t)])
    return PendulumResponse(model=pendulum(), freq_hz=f, amplitude=0.0, phase=0.0, t=t, y=y,
                            method="DOP853", nfev=0, njev=0, wall_time=0.0)


@pytest.mark.parametrize("sigma", [0.7, -0.7])
@pytest.mark.parametrize("periods", [None, 1, 3])
def test_growth_of_an_exponential_is_exp_sigma_times_the_window_offset(sigma, periods):
    """phi = exp(sigma t) over t_end = 6 s at f = 2 Hz: the window of n periods is T = n / f
    (default n = 2: T = 1 s). Growing (sigma > 0), the largest |phi| of the first window
    [0, T] is at its end and that of the last window [t_end - T, t_end] at t_end; decaying,
    at 0 and at t_end - T. Either way the ratio is exp(sigma (t_end - T)) [-]."""
    r = exponential_response(sigma)
    T = (2 if periods is None else periods) / 2.0
    got = r.amplitude_growth() if periods is None else r.amplitude_growth(periods)
    assert isinstance(got, float)
    assert got == pytest.approx(np.exp(sigma * (6.0 - T)), rel=1e-13)


def test_damped_free_vibration_decays_at_the_analytic_rate():
    """Ends at rest, taut cables (P = 2066 N): the small free vibration from phi0 at rest is
    phi0 exp(-s t) (cos w t + s / w sin w t) with s = b (a d / L)^2 / I_A [1/s] (the two
    cable dampers) and w = sqrt(K_phi / I_A - s^2), K_phi = 2 k (a d / L)^2 - 2 P (a d)^2 /
    L^3 - m g c [N m/rad]. Its |phi| peaks at t = j pi / w with value phi0 exp(-s t): the
    first window (one period of the 5 Hz excitation, 0.2 s) peaks at t = 0, the last one
    [0.4 s, 0.6 s] at the first j pi / w >= 0.4 s."""
    P, f, t_end = 2066.0, 5.0, 0.6
    L = np.hypot(A, D)
    lever = A * D / L
    s = B * lever ** 2 / I_A
    K_phi = 2 * K * lever ** 2 - 2 * P * (A * D) ** 2 / L ** 3 - M * G * C
    w = np.sqrt(K_phi / I_A - s ** 2)
    t_peak = np.ceil(0.4 * w / np.pi) * np.pi / w
    r = pdl.simulate(pendulum(preload=P), f, 0.0, t_end, phi0=1e-6, rtol=1e-10, n_out=24001)
    assert r.amplitude_growth(1) == pytest.approx(np.exp(-s * t_peak), rel=5e-4)
    assert r.amplitude_growth(1) < 0.2                 # decays: s = 5.1 1/s, exp(-s 0.4 s) = 0.13
