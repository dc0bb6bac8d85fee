"""The Floquet search of the cable pendulum (dynstiff.timedomain.pendulum.floquet): the
shooting step's limit, the pendulum's share of a mode, the damped Newton shooting and its
fallbacks case by case, each case's own pendulum multiplier, the options' messages."""

import numpy as np
import pytest
from test_timedomain_pendulum import pendulum

from dynstiff.errors import InvalidParameterError
from dynstiff.timedomain import pendulum as pdl
from dynstiff.timedomain.pendulum.dynamics import excitation_at


def test_shooting_step_is_limited_to_five_percent():
    """A Newton step of 0.2 rad (start tilted by 0.2 rad, orbit near phi = 0) is scaled
    down along its direction so that its largest scaled entry is 0.05."""
    from dynstiff.timedomain.pendulum.floquet import _shooting_step
    m = pendulum(preload=2066.0)
    exc = excitation_at(30.0, 0.01, 0.3)
    scale = m.state_scale(exc.omega)
    v = pdl.rest_state(m, 0.2)[None]
    vT, M_, _, step = _shooting_step(m, exc, 64, scale, None, (np.eye(2),), v)
    newton = np.linalg.solve(M_[0][0] - np.eye(2), -(vT - v)[0])
    assert np.max(np.abs(newton) / scale[0]) > 0.1
    assert np.max(np.abs(step[0]) / scale[0]) == pytest.approx(0.05, rel=1e-12)
    np.testing.assert_allclose(step[0], newton * 0.05 / np.max(np.abs(newton) / scale[0]),
                               rtol=1e-12)


def test_pendulum_share_is_the_energy_norm_share():
    """Share of phi in sum m_i (|dv_i|^2 + omega^2 |dq_i|^2), omega = 2 pi max(f_n, 1 Hz),
    for state vectors whose velocity entries are not 0 or 1 in modulus."""
    from dynstiff.timedomain.pendulum.floquet import _pendulum_share
    m = pendulum(preload=1000.0, cable_mass=0.01, n_masses=1)
    nq = m.n_dof
    rng = np.random.default_rng(5)
    V = rng.uniform(0.2, 0.9, (1, 2 * nq, 2)) * np.exp(1j * rng.uniform(0, 6, (1, 2 * nq, 2)))
    w2 = (2 * np.pi * m.natural_frequency_hz()) ** 2
    mi = m.mass_diagonal()
    e = mi[:, None] * (np.abs(V[0, nq:]) ** 2 + w2 * np.abs(V[0, :nq]) ** 2)
    np.testing.assert_allclose(_pendulum_share(m, V)[0], e[0] / e.sum(axis=0), rtol=1e-13)


def _failing_batches(monkeypatch, first_ok):
    """Make floquet's shooting fail (ConvergenceError) for candidate batches of more than
    one case, or for every candidate when first_ok only lets the first call through."""
    import importlib

    from dynstiff.errors import ConvergenceError
    fq = importlib.import_module("dynstiff.timedomain.pendulum.floquet")
    real, calls = fq._shooting_step, []

    def step(model, exc, n_steps, scale, U, bases, v):
        calls.append(v.shape[0])
        if len(calls) > 1 and (first_ok or v.shape[0] > 1):
            raise ConvergenceError("integration failed", residual=1.0)
        return real(model, exc, n_steps, scale, U, bases, v)
    monkeypatch.setattr(fq, "_shooting_step", step)
    return calls


def test_failing_batch_is_retried_case_by_case(monkeypatch):
    """When a batch of candidates fails, each case is integrated on its own: the result is
    that of the batch (the cases are independent)."""
    m = pendulum(preload=2066.0)
    f = [30.0, 31.0]
    ref = pdl.floquet(m, f, 0.01, phase=0.3, transient_periods=0)
    calls = _failing_batches(monkeypatch, first_ok=False)
    got = pdl.floquet(m, f, 0.01, phase=0.3, transient_periods=0)
    assert 1 in calls and np.all(got.periodic)
    np.testing.assert_allclose(got.multipliers, ref.multipliers, rtol=1e-8, atol=1e-10)


def test_single_case_whose_candidates_fail_keeps_its_start(monkeypatch):
    """One case whose every shooting candidate fails (infinite residual, rejected) ends as
    with no shooting at all (max_shooting = 1): growth averaged from the first period."""
    m = pendulum(preload=2066.0)
    kw = dict(phase=0.3, transient_periods=0, average_periods=2)
    ref = pdl.floquet(m, 30.0, 0.01, max_shooting=1, **kw)
    calls = _failing_batches(monkeypatch, first_ok=True)
    got = pdl.floquet(m, 30.0, 0.01, max_shooting=3, **kw)
    assert len(calls) == 3 and not ref.periodic[0]
    np.testing.assert_array_equal(got.multipliers, ref.multipliers)
    np.testing.assert_array_equal(got.orbit_residual, ref.orbit_residual)


def test_case_failing_alone_in_a_failed_batch_keeps_its_start(monkeypatch):
    """A batch fails, and then one of its cases fails on its own too: that case gets an
    infinite residual for the candidate (rejected, it keeps its start, as with no shooting),
    while the other case converges as it does alone."""
    import importlib

    from dynstiff.errors import ConvergenceError
    m = pendulum(preload=2066.0)
    kw = dict(phase=0.3, transient_periods=0, average_periods=2)
    ref0 = pdl.floquet(m, 30.0, 0.01, **kw)
    ref1 = pdl.floquet(m, 31.0, 0.01, max_shooting=1, **kw)
    fq = importlib.import_module("dynstiff.timedomain.pendulum.floquet")
    real, calls = fq._shooting_step, []

    def step(model, exc, n_steps, scale, U, bases, v):
        calls.append(v.shape[0])
        if len(calls) > 1 and (v.shape[0] > 1 or exc.freq_hz[0] == 31.0):
            raise ConvergenceError("integration failed", residual=1.0)
        return real(model, exc, n_steps, scale, U, bases, v)
    monkeypatch.setattr(fq, "_shooting_step", step)
    got = pdl.floquet(m, [30.0, 31.0], 0.01, **kw)
    assert calls[0] == 2 and 1 in calls
    assert got.periodic.tolist() == [True, False]
    np.testing.assert_allclose(got.multipliers[0], ref0.multipliers[0], rtol=1e-8,
                               atol=1e-10)
    np.testing.assert_array_equal(got.multipliers[1], ref1.multipliers[0])
    np.testing.assert_array_equal(got.orbit_residual[1], ref1.orbit_residual[0])


def test_damped_newton_accepts_rejects_and_moves_on_by_one_period(monkeypatch):
    """The shooting's damping, on a scripted residual: a candidate is accepted when its
    residual is below (1 - lam/4) times the current one (then lam = 1), else lam halves;
    below lam = 0.3 the next candidate is the current point's image y(T_e) (one period of
    transient), accepted whatever its residual."""
    import importlib
    fq = importlib.import_module("dynstiff.timedomain.pendulum.floquet")
    m = pendulum(preload=2066.0)
    ny = 2 * m.n_dof
    errs = iter([1.0, 0.5, 0.45, 0.45, 0.45])     # start, accept, reject, reject, period
    seen = []

    def step(model, exc, n_steps, scale, U, bases, v):
        k = len(seen)
        seen.append(v.copy())
        vT = v + 1e-4 * (k + 1)                     # a distinct image for each call
        s = np.full((1, ny), 1e-3 * (k + 1))       # a distinct step for each call
        return vT, [0.5 * np.eye(ny)[None]], np.array([next(errs)]), s
    monkeypatch.setattr(fq, "_shooting_step", step)
    pdl.floquet(m, 30.0, 0.01, phase=0.3, transient_periods=0, max_shooting=5,
                average_periods=1)
    y0 = seen[0]
    s = [np.full((1, ny), 1e-3 * (k + 1)) for k in range(5)]
    c1 = y0 + s[0]                                  # full step: 0.5 < 0.75 accepted
    expected = [y0, c1, c1 + s[1],                  # 0.45 >= 0.75 * 0.5: rejected
                c1 + 0.5 * s[1],                    # 0.45 >= 0.875 * 0.5: rejected
                c1 + 1e-4 * 2]                      # lam = 0.25: y(T_e) of c1
    assert len(seen) == 5
    for got, want in zip(seen, expected):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-15)


def test_cases_of_a_batch_pick_their_pendulum_multiplier_on_their_own():
    """The pendulum's multiplier of each case is picked by that case's own largest pendulum
    share: two cases computed together equal each computed alone, here with shares that
    differ by more than a factor of two between the cases (heavy cables: the larger
    amplitude's orbit mixes the pendulum into the cables' motions, its largest share 0.21
    against 0.91; its pick, 0.19, is not its largest share)."""
    m = pendulum(preload=1000.0, cable_mass=2.0, n_masses=2)
    x0 = [0.001, 0.05]
    both = pdl.floquet(m, 20.0, x0, phase=0.3)
    alone = [pdl.floquet(m, 20.0, x, phase=0.3) for x in x0]
    assert both.pendulum_share[1] < 0.5 * both.pendulum_share[0]
    for k in range(2):
        assert both.pendulum_share[k] == pytest.approx(alone[k].pendulum_share[0], rel=1e-6)
        assert both.pendulum_multiplier[k] == pytest.approx(
            alone[k].pendulum_multiplier[0], rel=1e-6)


@pytest.mark.parametrize("name, value, message", [
    ("tol", 0.0, r"^tol must be > 0, got 0\.0$"),
    ("orbit_tol", -1.0, r"^orbit_tol must be > 0, got -1\.0$"),
    ("max_shooting", 0, r"^max_shooting must be an integer >= 1, got 0$"),
    ("average_periods", 0, r"^average_periods must be an integer >= 1, got 0$"),
    ("steps_per_cycle", 3, r"^steps_per_cycle must be an integer >= 4, got 3$"),
    ("transient_periods", -1, r"^transient_periods must be an integer >= 0, got -1$"),
])
def test_floquet_options_are_checked_with_exact_messages(name, value, message):
    with pytest.raises(InvalidParameterError, match=message):
        pdl.floquet(pendulum(), 10.0, 0.02, **{name: value})
