"""Inverted pendulum on two cables with excited ends (seed paper 004, Polach & Hajzman;
dynstiff.timedomain.pendulum and the built-in scene ``pendulum``)."""

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.timedomain import pendulum as pdl
from dynstiff.timedomain.pendulum.dynamics import excitation_at, segment_geometry

#: Paper, Sec. 3: l = 1 m, m = 9.864 kg, I_A = 3.288 kg m^2, a = 1.2 m, d = 0.75 m,
#: k = 8.264e4 N/m.
M, I_A, C, A, D, K = 9.864, 3.288, 0.5, 1.2, 0.75, 8.264e4
G = 9.81


def analytic_stiffness(P, h=0.0):
    """Upright pendulum on two straight cables from (-a, h), (a, h) to D = (0, d), written
    out here: V = sum k/2 (L_i - L0)^2 + m g c cos(phi), L_i^2 = a^2 + d^2 +- 2 a d sin(phi)
    + ... (h = 0), so V'' = 2 k (a d / L)^2 - 2 P (a d)^2 / L^3 - m g c at phi = 0."""
    assert h == 0.0
    L = np.hypot(A, D)
    return 2 * K * (A * D / L) ** 2 - 2 * P * (A * D) ** 2 / L ** 3 - M * G * C


def pendulum(**kw):
    args = dict(inertia=I_A, mass=M, com_distance=C, attach_distance=D, half_span=A,
                stiffness=K, damping=5e-4 * K, g=G)
    args.update(kw)
    return pdl.CablePendulum(**args)


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("pendulum")


# ------------------------------------------------------------------ scene and analytic limits
def test_scene_modes_match_the_analytic_natural_frequency(scene):
    eq = scene.equilibrium()
    P = scene.robot.tension_limits[0]
    # inverse statics: the least tension (at the lower end B, C) is the preload; at D it
    # carries the cable's weight on top: elastic catenary dT = w0 dz / (1 + T/EA), with w0
    # = m_c g / L0 per unstretched length: 0.0200 N
    np.testing.assert_allclose(eq.min_tensions, P, rtol=1e-12)
    EA = scene.robot.cables[0].EA
    np.testing.assert_allclose(eq.tensions - P, 3.846e-3 * G * D / eq.unstretched_lengths[0]
                               / (1 + P / EA), rtol=1e-5)
    f_analytic = np.sqrt(analytic_stiffness(P) / I_A) / (2 * np.pi)
    f1 = ds.modes(ds.FrequencyModel(eq), 2).freq_hz[0]
    assert abs(f1 / f_analytic - 1) < 1e-3            # 3.8 g cables shift it by 2e-4
    model = pdl.from_scene(scene)
    assert model.natural_frequency_hz() == pytest.approx(f_analytic, rel=1e-12)
    assert model.stiffness == pytest.approx(K, rel=1e-9)
    assert model.stiffness == pytest.approx(scene.robot.cables[0].EA / eq.unstretched_lengths[0],
                                            rel=1e-6)
    assert model.inertia == pytest.approx(I_A, rel=1e-12)
    assert model.damping == pytest.approx(5e-4 * K, rel=1e-9)
    assert model.cable_mass == pytest.approx(3.846e-3, rel=1e-9)


def test_free_vibration_has_the_analytic_frequency():
    m = pendulum(damping=0.0, preload=2066.0)
    r = pdl.simulate(m, 1.0, 0.0, 0.5, phi0=1e-5, rtol=1e-10, n_out=20001)
    up = np.flatnonzero((r.phi[:-1] < 0) & (r.phi[1:] >= 0))
    tc = r.t[up] - r.phi[up] * (r.t[up + 1] - r.t[up]) / (r.phi[up + 1] - r.phi[up])
    f_sim = (up.size - 1) / (tc[-1] - tc[0])
    f_an = np.sqrt(analytic_stiffness(2066.0) / I_A) / (2 * np.pi)
    assert abs(f_sim / f_an - 1) < 2e-4


def test_floquet_of_a_constant_coefficient_system_is_exp_of_eigenvalues():
    """x0 = 0: the system is autonomous, M = expm(J T), mu = exp(lambda T)."""
    m = pendulum(preload=2066.0)
    f = 10.0
    lam = np.linalg.eigvals(pdl.jacobian(m, 0.0, pdl.rest_state(m), f, 0.0)[0])
    exact = np.sort_complex(np.exp(lam / f))
    err = [np.abs(np.sort_complex(pdl.floquet(m, f, 0.0, steps_per_cycle=s).multipliers[0])
                  - exact).max() for s in (40, 80)]
    assert err[0] < 1e-3
    assert 6.0 < err[0] / err[1] < 20.0          # third-order Radau IIA: ratio 2^3
    # point-mass cables: the pendulum's multiplier is exp(lambda_pendulum T) of the
    # linearised chain model too (the faster cable modes are damped by the L-stable scheme)
    mp = replace(m, cable_mass=3.846e-3, n_masses=10)
    resp = pdl.floquet(mp, f, 0.0)
    assert resp.periodic[0] and resp.orbit_residual[0] < 1e-9
    lam_p = np.linalg.eigvals(pdl.jacobian(mp, 0.0, pdl.rest_state(mp), f, 0.0)[0])
    lam_pend = lam_p[np.argmin(np.abs(lam_p - lam[np.argmax(lam.imag)]))]
    assert abs(lam_pend / lam[np.argmax(lam.imag)] - 1) < 1e-3   # cable mass: small shift
    assert resp.pendulum_share[0] > 0.9
    assert abs(resp.pendulum_multiplier[0] - np.exp(lam_pend / f)) < 1e-3


def test_mathieu_principal_tongue_at_twice_the_natural_frequency():
    """Taut cables (P = 8264 N > k x0 a/L = 7008 N), no damping: the stiffness is modulated
    by eps ~ 1.3 % and the principal tongue spans 2 f_n (1 -+ eps/4) (Mathieu equation,
    first-order theory, e.g. Nayfeh & Mook 1979, Sec. 5.2)."""
    m = pendulum(damping=0.0, preload=8264.0)
    x0 = 0.1
    fn = m.natural_frequency_hz()
    f = 2 * fn * np.linspace(0.99, 1.01, 201)
    res = pdl.floquet(m, f, x0)
    tongues = pdl.unstable_intervals(f, res.stable)
    assert len(tongues) == 1
    lo, hi = tongues[0]
    assert abs(0.5 * (lo + hi) / (2 * fn) - 1) < 3e-3
    t = np.linspace(0.0, 1.0 / (2 * fn), 400, endpoint=False)
    Kt = -pdl.jacobian(m, t, pdl.rest_state(m), 2 * fn, x0)[:, 1, 0] * m.pin_inertia
    eps = (Kt.max() - Kt.min()) / (Kt.max() + Kt.min())
    assert 0.01 < eps < 0.02
    half_width = 0.5 * (hi - lo) / (2 * fn)
    assert abs(half_width / (eps / 4) - 1) < 0.15
    # the damping of the scene (zeta = 0.036 > eps / 4) removes it
    assert np.all(pdl.floquet(replace(m, damping=5e-4 * K), f[::20], x0).stable)


def test_slack_threshold_separates_stable_from_unstable_preloads():
    m = pendulum(preload=0.0)
    x0 = 0.02
    P_slack = K * x0 * A / np.hypot(A, D)
    assert replace(m, preload=P_slack).slack_amplitude() == pytest.approx(x0, rel=1e-12)
    f = np.geomspace(2.0, 100.0, 60)
    below = pdl.floquet(replace(m, preload=0.9 * P_slack), f, x0)
    above = pdl.floquet(replace(m, preload=1.1 * P_slack), f, x0)
    assert np.any(~below.stable) and np.all(above.stable)
    # zero preload: the cables slacken every period and the upright pendulum loses its
    # restoring stiffness; principal region around 2 f_n / sqrt(2) (half the time taut)
    zero = pdl.floquet(m, f, x0)
    lo, hi = max(pdl.unstable_intervals(f, zero.stable), key=lambda iv: iv[0])
    assert lo < np.sqrt(2) * m.natural_frequency_hz() < hi < 2 * m.natural_frequency_hz()


def test_floquet_multiplier_predicts_the_simulated_growth():
    m = pendulum(preload=0.0)
    f, x0 = 30.0, 0.02
    mu = pdl.floquet(m, f, x0).pendulum_abs[0]
    assert mu > 2.0
    r = pdl.simulate(m, f, x0, 12 / f, phi0=1e-9, rtol=1e-10)
    peak = [np.abs(r.phi[(r.t >= k / f) & (r.t < (k + 1) / f)]).max() for k in range(12)]
    rate = (peak[11] / peak[5]) ** (1 / 6)
    assert abs(rate / mu - 1) < 0.02


# ------------------------------------------------------------------ model consistency
@pytest.mark.parametrize("n", [0, 10])
def test_jacobian_matches_finite_differences(n):
    m = pendulum(preload=300.0, cable_mass=0.05, n_masses=n)
    rng = np.random.default_rng(n)
    y = pdl.rest_state(m, 0.02)
    nq = m.n_dof
    y[nq:] = rng.normal(0.0, 0.3, nq)
    y[1:nq] += rng.normal(0.0, 2e-3, nq - 1)
    t, f, x0, ph = 0.013, 20.0, 0.03, 0.4
    J = pdl.jacobian(m, t, y, f, x0, ph)[0]
    Jfd = np.empty_like(J)
    for i in range(2 * nq):
        e = np.zeros(2 * nq)
        e[i] = 1e-7 * max(1.0, abs(y[i]))
        Jfd[:, i] = (pdl.rhs(m, t, y + e, f, x0, ph)[0] - pdl.rhs(m, t, y - e, f, x0, ph)[0]) / (
            2 * e[i])
    assert np.abs(J - Jfd).max() <= 1e-6 * np.abs(J).max()
    if n:   # the state has slack segments, so the piecewise Jacobian is exercised
        seg = segment_geometry(m, np.array([t]), y[None], excitation_at(f, x0, ph))[-1]
        assert np.any(seg == 0.0) and np.any(seg > 0.0)


def energy(m, y):
    """Mechanical energy [J] written out independently: kinetic energy of the pendulum
    (with the end half masses at D) and of the nodes, tension-only spring energy of every
    segment, gravity (ends at rest, x0 = 0)."""
    n = m.n_masses
    nq = m.n_dof
    phi, w = y[0], y[nq]
    Dp = D * np.array([np.sin(phi), np.cos(phi)])
    E = 0.5 * m.pin_inertia * w ** 2 + (M * C + m.node_mass * D) * G * np.cos(phi)
    ks, ls = (n + 1) * K, m.unstretched_length / (n + 1)
    for i, sx in enumerate((-1.0, 1.0)):
        nodes = y[1 + 2 * n * i:1 + 2 * n * (i + 1)].reshape(n, 2)
        vel = y[nq + 1 + 2 * n * i:nq + 1 + 2 * n * (i + 1)].reshape(n, 2)
        E += 0.5 * m.node_mass * np.sum(vel ** 2) + m.node_mass * G * nodes[:, 1].sum()
        pts = np.vstack([[sx * A, 0.0], nodes, Dp])
        ell = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        E += 0.5 * ks * np.sum(np.maximum(ell - ls, 0.0) ** 2)
    return E


@pytest.mark.parametrize("n, t_end, phi0, rtol", [(0, 0.5, 0.01, 1e-9), (0, 0.5, 0.03, 1e-11),
                                                 (10, 0.01, 1e-3, 1e-9)])
def test_undamped_motion_conserves_energy(n, t_end, phi0, rtol):
    """No damping, ends at rest: the energy written out above is constant (the forces of the
    model derive from that potential). Undamped, the chain is not stiff: DOP853.

    At phi0 = 0.03 a cable goes slack (stretch a d / L phi0 = 0.019 m > P / k = 0.012 m):
    the tension-only force has a kink there, which the error estimator of DOP853 does not
    see, so that case needs a tighter rtol for the same energy error (1.2e-5 at 1e-9,
    3.4e-8 at 1e-11); the drift is the integrator's, and it falls with rtol."""
    m = pendulum(damping=0.0, preload=1000.0, cable_mass=0.01, n_masses=n)

    def drift(tol):
        r = pdl.simulate(m, 1.0, 0.0, t_end, phi0=phi0, rtol=tol, method="DOP853", n_out=50)
        E = np.array([energy(m, y) for y in r.y]) - energy(m, pdl.rest_state(m))
        assert E[0] > 0
        assert abs(r.phi).max() > 0.5 * phi0 and abs(r.phi).min() < 0.5 * phi0   # it moved
        return np.ptp(E) / E[0], r

    rel, r = drift(rtol)
    assert rel < 1e-6
    if phi0 == 0.03:
        seg = segment_geometry(m, r.t, r.y, excitation_at(1.0, 0.0, 0.0).repeat(r.t.size))[-2]
        assert seg.min() < 0.0                                  # the slack case indeed
        assert drift(100 * rtol)[0] > 30 * rel                  # integrator error, converging


def test_point_mass_cables_tend_to_massless_cables():
    """Taut cables, 30 Hz: the pendulum multiplier of the point-mass model approaches the
    massless one linearly in the cable mass."""
    m0 = pendulum(preload=2066.0)
    f, x0 = 30.0, 0.02
    mu0 = pdl.floquet(m0, f, x0).pendulum_multiplier[0]
    diffs = []
    for mc in (3.846e-3, 3.846e-4):
        r = pdl.floquet(replace(m0, cable_mass=mc, n_masses=10), f, x0, transient_periods=2)
        assert r.periodic[0]
        diffs.append(abs(r.pendulum_abs[0] - abs(mu0)))
    assert diffs[0] < 0.02
    assert 5.0 < diffs[0] / diffs[1] < 20.0


def test_point_mass_multiplier_converges_with_the_step():
    """The scheme damps the unresolved cable modes; the pendulum multiplier still converges
    at third order as the step is halved (taut cables, 30 Hz)."""
    m = pendulum(preload=2066.0, cable_mass=3.846e-3, n_masses=10)
    mu = [pdl.floquet(m, 30.0, 0.02, steps_min=s, transient_periods=2).pendulum_abs[0]
          for s in (64, 128, 256)]
    d1, d2 = abs(mu[0] - mu[1]), abs(mu[1] - mu[2])
    assert d1 < 5e-3 and 4.0 < d1 / d2 < 20.0


# ------------------------------------------------------------------ API
def test_stability_map_is_a_tidy_table():
    m = pendulum(preload=0.0)
    df = pdl.stability_map(m, [20.0, 30.0, 60.0], [0.02, 0.05], preloads=[0.0, 2066.0])
    assert len(df) == 12
    for col in ("f [Hz]", "x0 [m]", "preload [N]", "cable mass [kg]", "phase [deg]",
                "max |multiplier| [-]", "pendulum |multiplier| [-]", "stable"):
        assert col in df.columns
    assert df["stable"].dtype == bool and np.all(np.isfinite(df["max |multiplier| [-]"]))
    row = df[(df["f [Hz]"] == 30.0) & (df["preload [N]"] == 0.0) & (df["x0 [m]"] == 0.02)]
    assert not row["stable"].iloc[0]
    taut = (df["preload [N]"] == 2066.0) & (df["x0 [m]"] == 0.02)     # x0 < P L / (k a)
    assert df[taut]["stable"].all()
    assert pdl.unstable_intervals([1, 2, 3, 4, 5], [True, False, False, True, False]) == [
        (2.0, 3.0), (5.0, 5.0)]


def test_bad_inputs_name_the_argument(scene):
    m = pendulum()
    with pytest.raises(InvalidParameterError, match="freq_hz"):
        pdl.floquet(m, 0.0, 0.02)
    with pytest.raises(InvalidParameterError, match="amplitude"):
        pdl.floquet(m, 10.0, -0.02)
    with pytest.raises(InvalidParameterError, match="n_masses"):
        pendulum(n_masses=-1)
    with pytest.raises(InvalidParameterError, match="cable_mass"):
        pendulum(n_masses=10)
    with pytest.raises(InvalidParameterError, match="preload"):
        pendulum(preload=K * 2.0)
    with pytest.raises(InvalidParameterError, match="damping"):
        pendulum(damping=np.nan)
    with pytest.raises(InvalidParameterError, match="y must have"):
        pdl.rhs(m, 0.0, np.zeros(5), 10.0, 0.02)
    with pytest.raises(InvalidParameterError, match="t_end"):
        pdl.simulate(m, 10.0, 0.02, -1.0)
    with pytest.raises(InvalidParameterError, match="free_dofs"):
        pdl.from_scene(ds.load_scene("cogiro"))
    with pytest.raises(InvalidParameterError, match="ascending"):
        pdl.unstable_intervals([2.0, 1.0], [True, False])



def test_counts_and_angles_are_checked_with_exact_messages():
    """Integer arguments and the initial tilt are validated; the message names the argument,
    its bound and the value."""
    m = pendulum()
    with pytest.raises(InvalidParameterError, match=r"^n_out must be an integer >= 2, got 1$"):
        pdl.simulate(m, 10.0, 0.02, 0.1, n_out=1)
    with pytest.raises(InvalidParameterError,
                       match=r"^steps_min must be an integer >= 4, got 2\.5$"):
        pdl.floquet(m, 10.0, 0.02, steps_min=2.5)
    with pytest.raises(InvalidParameterError, match=r"^phi must be finite \[rad\], got inf$"):
        pdl.rest_state(m, np.inf)


def test_natural_frequency_is_zero_when_gravity_outweighs_the_cables():
    """Soft cables, no preload: K_phi = 2 k (a d / L)^2 - m g c < 0, the upright pendulum
    has no restoring stiffness and natural_frequency_hz() is 0 (as documented)."""
    k = 10.0
    m = pendulum(stiffness=k, damping=0.0)
    K_phi = 2 * k * (A * D / np.hypot(A, D)) ** 2 - M * G * C
    assert K_phi < -40.0
    assert m.linear_stiffness() == pytest.approx(K_phi, rel=1e-12)
    assert m.natural_frequency_hz() == 0.0


def test_rhs_and_jacobian_evaluate_each_case_on_its_own():
    """A batch of cases (t, y, f, x0, phase per case) gives row by row the single-case
    results; one state and scalar arguments give one case, shape (1, 2 n_dof)."""
    m = pendulum(preload=300.0)
    rng = np.random.default_rng(3)
    t = np.array([0.0, 0.011, 0.037])
    y = rng.normal(0.0, 0.05, (3, 2))
    f, x0, ph = np.array([10.0, 20.0, 35.0]), np.array([0.01, 0.03, 0.02]), np.array([0, .4, 1])
    F = pdl.rhs(m, t, y, f, x0, ph)
    J = pdl.jacobian(m, t, y, f, x0, ph)
    assert F.shape == (3, 2) and J.shape == (3, 2, 2)
    for i in range(3):
        Fi = pdl.rhs(m, t[i], y[i], f[i], x0[i], ph[i])
        assert Fi.shape == (1, 2)
        np.testing.assert_allclose(F[i], Fi[0], rtol=1e-14, atol=0)
        np.testing.assert_allclose(J[i], pdl.jacobian(m, t[i], y[i], f[i], x0[i], ph[i])[0],
                                   rtol=1e-14, atol=0)
    assert pdl.jacobian(m, 0.0, y[0], 10.0, 0.01).shape == (1, 2, 2)


def test_start_state_moves_the_point_masses_with_the_ends():
    """At t = 0 the nodes sit at rest_state and their velocities interpolate linearly
    between the end velocity dE/dt = (-+ x0 omega cos(0 / -psi), 0) and D at rest: node j of
    n has the share 1 - j / (n + 1)."""
    from dynstiff.timedomain.pendulum.dynamics import start_state
    n = 3
    m = pendulum(preload=1000.0, cable_mass=0.01, n_masses=n)
    f, x0, ph = 20.0, 0.02, 0.4
    y = start_state(m, excitation_at(f, x0, ph))
    nq = m.n_dof
    assert y.shape == (1, 2 * nq)
    np.testing.assert_array_equal(y[0, :nq + 1], pdl.rest_state(m)[:nq + 1])
    w = 2 * np.pi * f
    vend = np.array([-x0 * w, x0 * w * np.cos(ph)])
    share = 1.0 - np.arange(1, n + 1) / (n + 1)
    v = y[0, nq + 1:].reshape(2, n, 2)
    np.testing.assert_allclose(v[:, :, 0], vend[:, None] * share[None, :], rtol=1e-14)
    np.testing.assert_array_equal(v[:, :, 1], 0.0)


def test_radau_step_reports_a_newton_failure_with_its_residual():
    """A Radau step whose Newton iteration does not reach the tolerance in max_iter
    iterations raises ConvergenceError naming the time and the iteration count, with the
    scaled correction (as printed) as its residual."""
    from dynstiff.errors import ConvergenceError
    from dynstiff.timedomain.pendulum.radau import _radau_step
    m = pendulum(preload=300.0)
    exc = excitation_at(20.0, 0.03, 0.0)
    y = pdl.rest_state(m, 0.02)[None]
    with pytest.raises(ConvergenceError, match=r"t = 0\.01 s: Newton did not converge in 1 "
                                               r"iterations") as err:
        _radau_step(m, np.array([0.01]), y, np.array([2e-3]), exc, m.state_scale(exc.omega),
                    max_iter=1)
    res = err.value.residual
    assert isinstance(res, float) and res > 1e-10
    assert f"scaled correction {res:.2e}" in str(err.value)


def test_robust_step_halves_a_failing_step_up_to_four_times(monkeypatch):
    """Where Newton fails, the step is split in halves, at most four times: the result is
    that of the 2^k sub-steps taken in turn (same subspace U, scale and bases), the step
    derivative their product; a step failing even at h / 16 raises ConvergenceError."""
    from dynstiff.errors import ConvergenceError
    from dynstiff.timedomain.pendulum import radau
    m = pendulum(preload=1000.0, cable_mass=0.01, n_masses=1)
    U_sym, U_anti = radau.mirror_bases(m)
    exc = excitation_at(20.0, 0.02, 0.0)
    scale = m.state_scale(exc.omega)
    y0 = pdl.rest_state(m, 0.01)[None]   # tilted: increments restricted to U_sym differ
    h, t0 = 2e-3, 0.004
    real = radau._radau_step
    ok = {}

    def failing(model, t, y, hh, *args):
        if hh.max() > ok["h"] * (1 + 1e-9):
            raise ConvergenceError("Newton cycles", residual=1.0)
        return real(model, t, y, hh, *args)

    monkeypatch.setattr(radau, "_radau_step", failing)
    ok["h"] = h / 16
    y, S = radau._robust_step(m, np.array([t0]), y0, np.array([h]), exc, scale, U_sym,
                              (U_sym, U_anti))
    y_ref, S_ref = y0, [np.eye(4)[None], np.eye(6)[None]]
    for k in range(16):
        y_ref, Sk = real(m, np.array([t0 + k * h / 16]), y_ref, np.array([h / 16]), exc,
                         scale, U_sym, (U_sym, U_anti))
        S_ref = [b @ a for a, b in zip(S_ref, Sk)]
    np.testing.assert_allclose(y, y_ref, rtol=1e-13, atol=1e-15)
    assert y[0, 0] == y0[0, 0]           # phi is not in U_sym: untouched
    for a, b in zip(S, S_ref):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-14)
    ok["h"] = h / 32
    with pytest.raises(ConvergenceError, match="Newton cycles"):
        radau._robust_step(m, np.array([t0]), y0, np.array([h]), exc, scale, U_sym,
                           (U_sym, U_anti))


# ------------------------------------------------------------------ validation study
@pytest.fixture(scope="module")
def quick_validation():
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))
    import pendulum_stability
    return pendulum_stability.run(quick=True)


def test_validation_headline_numbers(quick_validation):
    tab = quick_validation
    const = tab.attrs["constants"]
    assert const["natural freq P=0 [Hz]"] == pytest.approx(22.686, abs=1e-3)
    assert const["slack preload at x0 = 0.02 m [N]"] == pytest.approx(1401.6, abs=0.1)
    assert const["damping ratio [-]"] == pytest.approx(0.0357, abs=1e-4)

    def row(study, P, model):
        sel = (tab["study"] == study) & (tab["preload [N]"] == P) & (tab["model"] == model)
        return tab[sel].iloc[0]

    base = row("preload", 0.0, "massless")
    # zero preload: principal unstable interval around 23-38 Hz, confirmed by simulation
    assert any(lo < 25.0 and 35.0 < hi < 45.0 for lo, hi in base["unstable intervals [Hz]"])
    assert base["confirmed intervals"] == base["checked intervals"] >= 3
    assert base["stable check growth [-]"] < 1.0
    assert 0.5 < base["unstable fraction [-]"] < 0.7
    # preloads above the slack preload: no instability, massless or point-mass
    for model in ("massless", "point-mass"):
        assert row("preload", 2066.0, model)["unstable fraction [-]"] == 0.0
    assert row("preload", 0.0, "point-mass")["unstable fraction [-]"] == 1.0
    taut = row("damping b = 0 s x k", 8264.0, "massless")
    assert len(taut["unstable intervals [Hz]"]) == 1
    cmp = tab.attrs["comparison"].set_index("statement")
    assert cmp.loc["the preload can make the pendulum unstable", "agrees"]
    assert cmp.loc["some amplitude-frequency combinations are unstable", "agrees"]
    assert not cmp.loc["adding cable mass causes instability", "agrees"]


# ------------------------------------------------------------------ mutation-derived checks
def test_model_parameters_are_checked_with_exact_messages():
    """Each out-of-range parameter raises with a message naming it, its bound and the value;
    the preload message gives the stretch P/k that the chord cannot hold."""
    cases = [
        (dict(inertia=-1.0), r"^inertia must be > 0, got -1\.0$"),
        (dict(end_height=np.inf), r"^end_height must be finite \[m\], got inf$"),
        (dict(n_masses=2.5, cable_mass=0.01), r"^n_masses must be an integer >= 0, got 2\.5$"),
        (dict(n_masses=True, cable_mass=0.01), r"^n_masses must be an integer >= 0, got True$"),
        (dict(inertia=0.99 * M * C ** 2),
         r"^inertia must be >= mass \* com_distance\^2 = 2\.466 kg m\^2 \(parallel-axis "
         r"theorem\), got 2\.44134"),
        # P / k = 2 m, chord sqrt(1.2^2 + 0.75^2) = 1.4151 m
        (dict(preload=2 * K), r"^preload 165280 N needs a stretch P/k = 2 m longer than the "
                              r"chord 1\.4151 m$"),
    ]
    for kw, msg in cases:
        with pytest.raises(InvalidParameterError, match=msg):
            pendulum(**kw)


def test_model_stores_floats_and_accepts_a_point_mass_inertia_up_to_rounding():
    """end_height is stored as a float; I_A = m c^2 (1 - 1e-12) is within the documented
    rounding allowance of the parallel-axis bound."""
    m = pendulum(end_height=1)
    assert type(m.end_height) is float and m.end_height == 1.0
    assert pendulum(inertia=M * C ** 2 * (1 - 1e-12)).inertia == M * C ** 2 * (1 - 1e-12)


def test_steps_per_period_are_integer_powers_of_two():
    """n = max(steps_min, ceil(steps_per_cycle f_n / f)) rounded up to a power of two:
    f_n = 22.485 Hz, 10 Hz -> ceil(89.9) = 90 -> 128; 100 Hz -> max(64, 9) -> 64."""
    m = pendulum(preload=2066.0)
    r = pdl.floquet(m, [10.0, 100.0], 0.0)
    assert r.steps_per_period.dtype.kind == "i"
    np.testing.assert_array_equal(r.steps_per_period, [128, 64])
