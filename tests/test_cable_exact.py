"""The exact cable (dynstiff/cable/exact.py, theory.md §11): static limit, weightless limit,
symmetries, spectral convergence, damping, and agreement with an independent model, the
lumped-mass chain (theory.md §7) extrapolated by Richardson, graded (theory.md §7.4) on slack
cables."""

import functools

import numpy as np
import pytest
from conftest import HARD

import dynstiff as ds
from dynstiff.cable.dsm import cable_dynamic_stiffness
from dynstiff.cable.exact import ExactCable
from dynstiff.cable.lumped_chain import chain_equilibrium
from dynstiff.cable.lumped_chain_dynamics import (
    chain_end_dynamic_stiffness,
    chain_fixed_end_frequencies,
)
from dynstiff.cable.modes import cable_natural_frequencies

TWO_PI = 2 * np.pi
# static-limit cases: taut, sagging up to d/L 0.3, steep to 85 deg, vertical limit, slack U
STATIC = {
    "taut (CoGiRo cable)": ((0, 0, 0), (8.0, 3.0, -5.0), 9.9, ds.Cable(0.064, 139486.7)),
    "sagging d/L 0.3": ((0, 0, 0), (10.0, 0, 0), 12.3, ds.Cable(1.0, 1e6)),
    "steep 85 deg": ((0, 0, 0), (10 * np.cos(np.radians(85)), 0, 10 * np.sin(np.radians(85))),
                     10.02, ds.Cable(0.5, 1e6)),
    "vertical limit": ((0, 0, 0), (1e-4, 0, 10.0), 9.99, ds.Cable(0.064, 1.4e5)),
    "slack U (T_min 0.04 T_max)": ((0, 0, 0), (2.0, 0, 9.0), 10.1, ds.Cable(0.064, 1.4e5)),
}


def state(case):
    A, B, L0, cab = case
    return ds.solve_catenary(A, B, L0, cab)


def richardson(f, Ns):
    """(4 f_2N - f_N) / 3 from the two finest of a sequence of O(N^-2) results."""
    return (4 * f[Ns[-1]] - f[Ns[-2]]) / 3


@pytest.mark.parametrize("name", STATIC)
def test_static_limit_is_the_catenary_end_stiffness(name):
    """omega -> 0 gives the exact elastic-catenary static stiffness (theory.md §11.1, §11.3):
    the discretisation's own static condensation converges to it (the self-check, measured
    1e-11 to 5e-8), and K(omega) tends to it continuously, as omega^2."""
    s = state(STATIC[name])
    cab = ExactCable(s, TWO_PI * 2.0)
    assert cab.static_mismatch <= 1e-6
    Kd = cab.discrete_static_stiffness()[3:, 3:]
    Ke = s.end_stiffness
    E = cab.frame
    np.testing.assert_allclose(E @ Kd @ E.T, Ke, rtol=0, atol=1e-6 * np.abs(Ke).max())
    w1 = np.sqrt(cab.eigenvalues[0])
    K = cab.dynamic_stiffness([0.0, 1e-4 * w1, 1e-3 * w1])
    np.testing.assert_allclose(K[0], Ke, rtol=0, atol=1e-12 * np.abs(Ke).max())
    d1, d2 = np.abs(K[1] - K[0]).max(), np.abs(K[2] - K[0]).max()
    assert d2 / d1 == pytest.approx(100.0, rel=1e-3)              # O(omega^2)
    # the slack cable is no taut string
    if name.startswith("slack"):
        assert s.lambda_sq > 10 and s.sag > 0.1


def test_the_linearisation_reproduces_the_catenary_flexibility():
    """int D^-1 ds = d(l_h, h)/d(H, V_B) (theory.md §11.1): computed here by 2000-point
    Gauss quadrature of D^-1 along the arc, independently of the discretisation."""
    s = state(HARD["sagging 10x5 m, d/L 0.10"])
    x, w = np.polynomial.legendre.leggauss(200)
    L0, EA, w0 = s.unstretched_length, s.cable.EA, s.cable.weight_per_length(s.g)
    edges = np.linspace(0, L0, 11)
    F = np.zeros((2, 2))
    for a, b in zip(edges[:-1], edges[1:]):
        sq = 0.5 * (b - a) * (x + 1) + a
        V = s.V0 + w0 * sq
        T = np.hypot(s.H, V)
        t = np.stack([s.H / T, V / T])
        tt = np.einsum("iq,jq->qij", t, t)
        Dinv = tt / EA + ((1 + T / EA) / T)[:, None, None] * (np.eye(2) - tt)
        F += 0.5 * (b - a) * np.einsum("q,qij->ij", w, Dinv)
    np.testing.assert_allclose(F, s.in_plane_flexibility, rtol=1e-12)


def test_weightless_cable_is_a_taut_string_and_an_axial_rod():
    """g = 0 (theory.md §11.4): clamped modes n pi sqrt(D_t/m)/L0 (in and out of the plane)
    and n pi sqrt(EA/m)/L0 (axial); end stiffness EA k_a cot(k_a L0) along the cable and
    D_t k_t cot(k_t L0) across it."""
    cab, L0 = ds.Cable(0.5, 2e4), 9.98
    s = ds.solve_catenary((0, 0, 0), (10.0, 0, 0), L0, cab, g=0.0)
    T = s.H
    Dt = T / (1 + T / cab.EA)
    n = np.arange(1, 30)
    ct, ca = np.sqrt(Dt / cab.mass_per_length), np.sqrt(cab.EA / cab.mass_per_length)
    ref = np.sort(np.concatenate([n * np.pi * ct / L0, n * np.pi * ct / L0,
                                  n * np.pi * ca / L0]))[:24]
    ec = ExactCable(s, 1.05 * ref[-1])
    np.testing.assert_allclose(np.sqrt(ec.eigenvalues[:24]), ref, rtol=1e-9)
    fam = np.array(ec.family[:24])
    assert np.count_nonzero(fam == "axial") == np.count_nonzero(n * ca / L0 <= ref[-1] / np.pi)
    w = np.array([0.37, 1.9, 0.6 * ref[-1]])
    K = ec.dynamic_stiffness(w)
    ka, kt = w * np.sqrt(cab.mass_per_length / cab.EA), w * np.sqrt(cab.mass_per_length / Dt)
    np.testing.assert_allclose(K[:, 0, 0], cab.EA * ka / np.tan(ka * L0), rtol=1e-9)
    np.testing.assert_allclose(K[:, 1, 1], Dt * kt / np.tan(kt * L0), rtol=1e-9)
    np.testing.assert_allclose(K[:, 2, 2], Dt * kt / np.tan(kt * L0), rtol=1e-9)


def _rotz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def test_symmetry_reciprocity_rotation_mirror_and_reversal():
    A, B, L0, cab = (0, 0, 0), np.array([6.0, 2.0, 4.0]), 7.7, ds.Cable(0.8, 5e5)
    s = ds.solve_catenary(A, B, L0, cab)
    w = TWO_PI * np.array([0.13, 0.71, 1.37])
    band = TWO_PI * 1.5
    K = ExactCable(s, band).dynamic_stiffness(w, ends="both")
    assert np.isrealobj(K)
    np.testing.assert_allclose(K, np.swapaxes(K, 1, 2), rtol=0, atol=1e-12 * np.abs(K).max())
    # rigid rotation about the vertical
    R = _rotz(0.83)
    K_rot = ExactCable(ds.solve_catenary(A, R @ B, L0, cab), band).dynamic_stiffness(w, "both")
    R6 = np.kron(np.eye(2), R)
    np.testing.assert_allclose(K_rot, R6 @ K @ R6.T, rtol=0, atol=1e-9 * np.abs(K).max())
    # mirror y -> -y
    S = np.diag([1.0, -1.0, 1.0])
    K_mir = ExactCable(ds.solve_catenary(A, S @ B, L0, cab), band).dynamic_stiffness(w, "both")
    S6 = np.kron(np.eye(2), S)
    np.testing.assert_allclose(K_mir, S6 @ K @ S6, rtol=0, atol=1e-9 * np.abs(K).max())
    # the same cable seen from the other end: the two ends swap places
    K_rev = ExactCable(ds.solve_catenary(B, A, L0, cab), band).dynamic_stiffness(w, "both")
    P = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
    np.testing.assert_allclose(K_rev, P @ K @ P, rtol=0, atol=1e-8 * np.abs(K).max())


def test_spectral_convergence_in_the_element_order():
    """At a fixed mesh, the error of the clamped frequencies falls exponentially with the
    polynomial order p (theory.md §11.2): measured 7e-4, 6e-6, 1.5e-8, 2e-11 at p = 6, 8, 10,
    12; each step of 2 in p must divide it by more than 20 until the rounding floor."""
    s = state(HARD["sagging 10x5 m, d/L 0.10"])
    band = TWO_PI * 2.0
    ref = np.sqrt(ExactCable(s, band, order=24, half_waves=4.0).eigenvalues[:10])
    errs = []
    for p in (6, 8, 10, 12):
        f = np.sqrt(ExactCable(s, band, order=p, half_waves=4.0).eigenvalues[:10])
        errs.append(np.max(np.abs(f / ref - 1)))
    assert errs[0] > 1e-4
    for a, b in zip(errs[:-1], errs[1:]):
        assert b < a / 20 or b < 1e-9


@pytest.fixture(scope="module")
def lumped_reference():
    """Clamped frequencies (first 12) and end stiffness at three omega between poles of the
    lumped chain, N = 200, 400, 800, for every hard case."""
    out = {}
    for name, (A, B, L0, cab) in HARD.items():
        f, K = {}, {}
        st = ds.solve_catenary(A, B, L0, cab)
        w1 = np.sqrt(ExactCable(st, 1.0).eigenvalues[0])
        w = w1 * np.array([0.31, 0.83, 1.27])
        for N in (200, 400, 800):
            ch = chain_equilibrium(A, B, L0, cab, N)
            f[N] = TWO_PI * chain_fixed_end_frequencies(ch, 12)
            K[N] = chain_end_dynamic_stiffness(ch, w)
        out[name] = (st, w, richardson(f, (400, 800)), richardson(K, (400, 800)),
                     richardson(f, (200, 400)))
    return out


@pytest.mark.parametrize("name", HARD)
def test_agrees_with_richardson_extrapolated_lumped_chains(lumped_reference, name):
    """Independent model (theory.md §7): clamped frequencies (axial included where they fall)
    and the end stiffness at three omega agree with the lumped chain extrapolated from N = 400
    and 800 to 1e-6 (measured 7e-10 to 3e-9 on the frequencies)."""
    st, w, f_ref, K_ref, f_ref_coarse = lumped_reference[name]
    assert np.max(np.abs(f_ref / f_ref_coarse - 1)) < 1e-7          # the reference converged
    ec = ExactCable(st, 1.1 * f_ref[-1])
    np.testing.assert_allclose(np.sqrt(ec.eigenvalues[:12]), f_ref, rtol=1e-6)
    K = ec.dynamic_stiffness(w)
    np.testing.assert_allclose(K, K_ref, rtol=0, atol=1e-6 * np.abs(K_ref).max())
    if name.startswith("soft"):
        assert "axial" in ec.family[:10]
        f_ax = np.sqrt(st.cable.EA / st.cable.mass_per_length) / (2 * st.unstretched_length)
        k = ec.family.index("axial")
        assert np.sqrt(ec.eigenvalues[k]) / TWO_PI == pytest.approx(f_ax, rel=0.05)


def test_damping_agrees_with_the_damped_lumped_chain():
    """Hysteretic (EA (1 + i eta) on the axial strain) and viscous (m - i c / omega on all
    motions) damping (theory.md §11.3) against the lumped chain, which models both the same
    way, extrapolated from N = 200, 400."""
    A, B, L0 = (0, 0, 0), (10.0, 0, -2.0), 9.8
    cab = ds.Cable(1.0, 2e3, viscous_damping=0.3, loss_factor=0.02)
    st = ds.solve_catenary(A, B, L0, cab)
    w = TWO_PI * np.array([0.2, 0.9, 1.7])
    K = {N: chain_end_dynamic_stiffness(chain_equilibrium(A, B, L0, cab, N), w)
         for N in (200, 400)}
    K_ref = richardson(K, (200, 400))
    ec = ExactCable(st, TWO_PI * 2.0)
    assert ec.damped
    Ke = ec.dynamic_stiffness(w)
    np.testing.assert_allclose(Ke, K_ref, rtol=0, atol=1e-5 * np.abs(K_ref).max())
    np.testing.assert_allclose(Ke, np.swapaxes(Ke, 1, 2), atol=1e-12 * np.abs(Ke).max())
    und = ExactCable(st, TWO_PI * 2.0, damping=False)
    assert not und.damped and np.isrealobj(und.dynamic_stiffness(w))
    np.testing.assert_array_equal(und.eigenvalues, ec.eigenvalues)


def test_kinetic_energy_is_the_derivative_of_the_stiffness():
    """sum m |u|^2 of the response to an end motion u equals -u^T dK/d(omega^2) u
    (theory.md §11.3), central difference of step 1e-6 omega."""
    s = state(HARD["steep 60 deg sagging"])
    ec = ExactCable(s, TWO_PI * 1.5)
    u = np.array([0.3, -0.5, 0.8])
    E = ec.frame
    for w in (0.4 * np.sqrt(ec.eigenvalues[0]), 0.5 * np.sqrt(ec.eigenvalues[3]
                                                             + ec.eigenvalues[4])):
        h = 1e-6 * w
        K = ec.dynamic_stiffness([w - h, w + h])
        dK = (K[1] - K[0]) / (2 * w * 2 * h)                   # d/d(omega^2)
        ug = E @ u
        assert ec.kinetic_energy(w, u) == pytest.approx(-ug @ dK @ ug, rel=1e-6)
        resp = ec.end_response(w, u)
        np.testing.assert_allclose(resp[0], 0.0)
        np.testing.assert_allclose(resp[-1], u)


def test_viscous_damping_is_the_undamped_cable_at_a_complex_frequency():
    """Viscous damping c on all motions is the complex mass m - i c / omega (theory.md
    §11.3): the damped cable's K(omega) is the undamped cable's at the complex frequency
    sqrt(omega^2 - i omega c / m), through the same exact condensation."""
    A, B, L0 = (0, 0, 0), (8.0, 0, 3.0), 8.7
    damped = ds.solve_catenary(A, B, L0, ds.Cable(0.7, 3e5, viscous_damping=0.4))
    plain = ds.solve_catenary(A, B, L0, ds.Cable(0.7, 3e5))
    band = TWO_PI * 2.0
    w = TWO_PI * np.array([0.11, 0.63, 1.41])
    Kd = ExactCable(damped, band).dynamic_stiffness(w, ends="both")
    wc = np.sqrt(w**2 - 1j * w * 0.4 / 0.7)
    Ku = ExactCable(plain, band).dynamic_stiffness(wc, ends="both")
    np.testing.assert_allclose(Kd, Ku, rtol=0, atol=1e-12 * np.abs(Kd).max())
    assert np.abs(Kd.imag).max() > 1e-3 * np.abs(Kd.real).max()


def test_a_long_cable_keeps_modes_below_one_radian_per_second():
    """A 100 m sagging span: the clamped frequencies, the lowest below 1 rad/s, equal the
    Richardson-extrapolated lumped chain's to 1e-6; the arrays are read-only."""
    A, B, L0, cab = (0, 0, 0), (100.0, 0, 10.0), 106.0, ds.Cable(1.0, 1e7)
    f = {N: TWO_PI * chain_fixed_end_frequencies(chain_equilibrium(A, B, L0, cab, N), 4)
         for N in (200, 400)}
    ref = richardson(f, (200, 400))
    assert ref[0] < 1.0
    ec = ExactCable(ds.solve_catenary(A, B, L0, cab), 1.2 * ref[-1])
    np.testing.assert_allclose(np.sqrt(ec.eigenvalues[:4]), ref, rtol=1e-6)
    with pytest.raises(ValueError, match="read-only"):
        ec.eigenvalues[0] = 1.0


# ----------------------------------------------------------------------- slack cables
# A 10 m cable (CoGiRo's 0.064 kg/m, EA 1.4e5 N) whose span is shortened until its least
# tension is a given fraction of its greatest: hanging in a U between ends at equal height,
# or in a U under a near-vertical 9.9 m chord (theory.md §11.2).
SLACK_CABLE = ds.Cable(0.064, 1.4e5)
SLACK_SHAPES = {"U, ends at equal height": 0.0, "U under a near-vertical chord": 9.9}
RATIOS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1.1e-8)


@functools.cache
def slack_state(height, ratio):
    """The 10 m cable from A = 0 to B = (x, 0, height) with T_min / T_max = ratio, x by
    Brent's method on log x."""
    from scipy.optimize import brentq

    def excess(log_x):
        s = ds.solve_catenary((0, 0, 0), (np.exp(log_x), 0, height), 10.0, SLACK_CABLE)
        return np.log(s.min_tension / s.max_tension) - np.log(ratio)
    top = np.log(np.sqrt(10.0**2 * (1 - 1e-6) - height**2))
    x = np.exp(brentq(excess, np.log(1e-12), top, xtol=1e-15))
    return ds.solve_catenary((0, 0, 0), (x, 0, height), 10.0, SLACK_CABLE)


def graded_reference(s, omega, n_modes=12, Ns=(400, 800, 1600)):
    """Clamped frequencies [rad/s] and end stiffness at ``omega`` of lumped chains graded
    towards the lowest tension (theory.md §7.4), Richardson-extrapolated from the two finest
    N, and the same from the two coarsest (its convergence)."""
    from dynstiff.cable.lumped_graded import graded_chain
    w0 = s.cable.weight_per_length(s.g)
    f, K = {}, {}
    for N in Ns:
        ch = graded_chain(s.anchor, s.end, s.unstretched_length, s.cable, N,
                          s_low=-s.V0 / w0, core=s.H / w0, f0=s.force_on_anchor)
        f[N] = TWO_PI * ch.fixed_end_frequencies(n_modes)
        K[N] = ch.end_dynamic_stiffness(omega)
    return richardson(f, Ns[1:]), richardson(K, Ns[1:]), richardson(f, Ns[:2])


@pytest.mark.parametrize("ratio", RATIOS)
@pytest.mark.parametrize("shape", SLACK_SHAPES)
def test_slack_cables_agree_with_graded_lumped_chains(shape, ratio):
    """Down to T_min / T_max = 1e-8 (theory.md §11.2): the first 12 clamped frequencies and
    the end stiffness, static (energy norm) and at two frequencies in the widest gaps of the
    spectrum, agree with lumped chains graded towards the bottom of the U (theory.md §7.4),
    Richardson-extrapolated from N = 800 and 1600, to 1e-6 (measured 3e-11 to 3e-9 on the
    frequencies, 5e-9 to 5e-8 on the stiffness). The reference has converged: its
    extrapolation from N = 400, 800 differs by less than 1e-7. Before the mixed form
    (theory.md §11.2) this cable was refused below T_min / T_max ~ 1e-3."""
    s = slack_state(SLACK_SHAPES[shape], ratio)
    assert s.min_tension / s.max_tension == pytest.approx(ratio, rel=1e-6)
    ec = ExactCable(s, TWO_PI * 4.0)
    w = np.sqrt(ec.eigenvalues[:13])
    gaps = np.argsort(np.diff(w[:12]))[-2:]
    omega = np.concatenate([[0.0], 0.5 * (w[gaps] + w[gaps + 1])])
    f_ref, K_ref, f_coarse = graded_reference(s, omega)
    assert np.max(np.abs(f_coarse / f_ref - 1)) < 1e-7
    np.testing.assert_allclose(w[:12], f_ref, rtol=1e-6)
    K = ec.dynamic_stiffness(omega)
    from scipy.linalg import eigh
    static = eigh(K[0] - K_ref[0], K_ref[0], eigvals_only=True)
    assert np.max(np.abs(static)) < 1e-6
    for k in (1, 2):
        assert np.abs(K[k] - K_ref[k]).max() < 1e-6 * np.abs(K_ref[k]).max()
    assert ec.static_mismatch < 1e-8


@pytest.mark.parametrize("ratio", [1e-2, 1e-6, 1.1e-8])
def test_a_slack_cable_gives_the_same_answer_whatever_is_asked(ratio):
    """The number of modes, the band (which sizes the mesh) and the element order do not
    change the answer (bands of 2, 1.3 and 6 Hz, orders 12, 16 and 10; 1, 4, 6 or 8 modes
    asked): frequencies to 1e-9 (measured 4e-11), the static and dynamic end
    stiffness to 1e-7 (measured 6e-9 next to a pair of nearly equal poles, 6e-12 on the
    U at 1e-2); before, near the refusal boundary, the verdict itself changed with these
    (theory.md §11.2)."""
    s = slack_state(0.0, ratio)
    base = ExactCable(s, TWO_PI * 2.0)
    f0 = np.sqrt(base.eigenvalues[:8])
    omega = np.array([0.0, 0.5 * f0[0], 0.5 * (f0[1] + f0[2])])
    K0 = base.dynamic_stiffness(omega)
    for band, order in ((1.3, 16), (6.0, 10)):
        ec = ExactCable(s, TWO_PI * band, order=order)
        np.testing.assert_allclose(np.sqrt(ec.eigenvalues[:8]), f0, rtol=1e-9)
        K = ec.dynamic_stiffness(omega)
        assert np.all(np.abs(K - K0).max(axis=(1, 2)) < 1e-7 * np.abs(K0).max(axis=(1, 2)))
    for n in (1, 4, 6, 8):
        modes = cable_natural_frequencies(s, n, model="exact")
        np.testing.assert_allclose(TWO_PI * modes.freq_hz, f0[:n], rtol=1e-9)


def test_below_the_supported_ratio_one_refusal_whatever_is_asked():
    """T_min / T_max = 5e-9 < 1e-8: the same SlackCableError, naming the ratio and the limit,
    for every band, order, number of modes and entry point (theory.md §11.2)."""
    from dynstiff.cable.exact import MIN_TENSION_RATIO
    from dynstiff.errors import SlackCableError
    s = slack_state(9.9, 5e-9)
    calls = [lambda: ExactCable(s, TWO_PI * 1.0), lambda: ExactCable(s, TWO_PI * 30.0),
             lambda: ExactCable(s, TWO_PI * 3.0, order=8),
             lambda: ExactCable(s, TWO_PI * 3.0, order=20, half_waves=0.5),
             lambda: cable_natural_frequencies(s, 6, model="exact"),
             lambda: cable_natural_frequencies(s, 8, model="exact"),
             lambda: cable_dynamic_stiffness(s, [0.0, 1.0], model="exact")]
    messages = set()
    for call in calls:
        with pytest.raises(SlackCableError) as err:
            call()
        messages.add(str(err.value))
    assert len(messages) == 1
    assert MIN_TENSION_RATIO == 1e-8
    assert "T_min / T_max = 5e-09" in messages.pop()
    ExactCable(slack_state(9.9, 1.01e-8), TWO_PI * 1.0)             # just above: accepted


def test_the_self_check_refuses_a_discretisation_that_misses_the_statics():
    """Order 4 with long elements on a U at T_min / T_max = 1e-4: its static condensation is
    2e-3 off the exact static stiffness in the energy norm, far above its rounding floor
    (1e-9), and the constructor says so with the residual instead of returning the model;
    the default order reproduces the statics to 1e-11 (theory.md §11.2)."""
    from dynstiff.errors import ConvergenceError
    s = slack_state(0.0, 1e-4)
    with pytest.raises(ConvergenceError, match=r"far above its rounding floor .*T_min / T_max "
                                               r"= 0.0001, order 4") as err:
        ExactCable(s, 0.1, order=4, half_waves=8.0)
    assert 1e-3 < err.value.residual < 1e-2
    ec = ExactCable(s, 0.1)
    assert ec.static_mismatch < 1e-10 and ec.static_floor < 1e-6
