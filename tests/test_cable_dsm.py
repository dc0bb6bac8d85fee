"""Closed-form cable dynamic stiffness (theory.md §3, §5.2): limits, symmetry, poles, counts."""

import numpy as np
import pytest
from conftest import A0, B0, cogiro_cable
from hypothesis import given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.cable.dsm import (
    chord_parameters,
    local_end_stiffness,
    local_two_end_stiffness,
)
from dynstiff.cable.psi import irvine_symmetric_roots
from dynstiff.errors import InvalidParameterError

TWO_PI = 2 * np.pi


def local(K, p):
    """Global (n, 3, 3) -> chord frame (u, v, w)."""
    R = p.rotation
    return R.T @ K @ R


# ----------------------------------------------------------------------------- limits
@pytest.mark.parametrize("omega", [0.0, 1e-9, 1e-4])
def test_zero_frequency_is_parabolic_static_stiffness(state300, omega):
    """omega -> 0: K_B = diag(K0/(1 + lambda^2/12), T/L, T/L) exactly (theory.md §3.6)."""
    p = chord_parameters(state300)
    K = local(ds.cable_dynamic_stiffness(state300, omega, chordwise_inertia=False), p)[0]
    expected = np.diag([p.K0 / (1 + p.lambda_sq / 12), p.T / p.L, p.T / p.L])
    rtol = 1e-13 if omega < 1e-6 else 1e-8   # at 1e-4 rad/s the O(omega^2) terms are 1e-9
    np.testing.assert_allclose(K, expected, rtol=rtol, atol=rtol * p.K0)


def shallow_error_bound(s):
    """Measured envelope of the shallow-cable (parabolic, no chordwise weight) error of the
    static end stiffness, with delta = d/L and eps = W sin(theta) / T (the tension change
    along the chord relative to T, which the linear theory neglects):
    15 delta^2 + 2 delta eps (1 + 40 eps). Fitted on the 30 cases of the test below; every
    case sits at least 1.4x inside it."""
    p = chord_parameters(s)
    sin_t = abs(s.chord[2]) / s.chord_length
    delta = p.sag / p.L
    eps = s.total_weight * sin_t / p.T
    return 15 * delta**2 + 2 * delta * eps * (1 + 40 * eps)


@pytest.mark.parametrize("E", [17e9, 120e9])
@pytest.mark.parametrize("T", [30.0, 100.0, 300.0, 1000.0, 3000.0])
@pytest.mark.parametrize("A,B", [(A0, B0), ((0, 0, 0), (10, 0, 0)), ((0, 0, 10), (3, 0, 0))],
                         ids=["cogiro", "horizontal", "steep"])
def test_zero_frequency_matches_exact_catenary_within_shallow_cable_error(E, T, A, B):
    s = ds.unstretched_length_for_tension(A, B, T, cogiro_cable(E))
    K0 = ds.cable_dynamic_stiffness(s, 0.0, chordwise_inertia=False)[0]
    Ks = s.end_stiffness
    err = np.linalg.norm(K0 - Ks, 2) / np.linalg.norm(Ks, 2)
    assert err <= shallow_error_bound(s)
    # no O(T/EA) term: tension strains up to 2 % leave the taut cases exact to 1e-5
    if T >= 1000:
        assert err < 1e-5


def test_massless_limit_is_straight_spring():
    """m -> 0: K = (EA/L0) u u^T + (T/L)(I - u u^T) at any frequency."""
    cable = ds.Cable(1e-12, 1.4e5)
    A, B = np.array([1.0, 2.0, 6.0]), np.array([-3.0, 0.5, 1.0])
    L = np.linalg.norm(B - A)
    s = ds.solve_catenary(A, B, 0.997 * L, cable)
    u = (B - A) / L
    T = s.tension_at_end
    K_ref = cable.EA / s.unstretched_length * np.outer(u, u) + T / L * (np.eye(3) - np.outer(u, u))
    K = ds.cable_dynamic_stiffness(s, [0.0, 10.0, 300.0])
    np.testing.assert_allclose(K, np.broadcast_to(K_ref, K.shape), rtol=1e-9, atol=1e-9 * T / L)


def test_rigid_translation_has_no_static_force(state300):
    K = ds.cable_dynamic_stiffness(state300, 0.0, ends="both")[0]
    for d in np.eye(3):
        np.testing.assert_allclose(K @ np.concatenate([d, d]), 0, atol=1e-9 * np.abs(K).max())


# ----------------------------------------------------------------------------- symmetry
def test_symmetry_and_reciprocity(state300):
    w = np.linspace(0.1, 80.0, 301)
    K3 = ds.cable_dynamic_stiffness(state300, w)
    K6 = ds.cable_dynamic_stiffness(state300, w, ends="both")
    assert K3.dtype == np.float64 and K6.dtype == np.float64
    np.testing.assert_allclose(K3, K3.transpose(0, 2, 1), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(K6, K6.transpose(0, 2, 1), rtol=1e-12, atol=1e-9)
    # the end-B block of the two-end matrix is the clamped-A end matrix
    np.testing.assert_allclose(K6[:, 3:, 3:], K3, rtol=1e-12, atol=1e-9)
    # exchanging the ends of the chord: K_AA of one cable is K_BB of the reversed one? not in
    # general (sag side is the same); but the two-end matrix is symmetric about the centre:
    P = np.zeros((6, 6))
    p = chord_parameters(state300)
    Kl = local_two_end_stiffness(p, w)
    flip = np.diag([-1.0, 1.0, 1.0])      # u -> -u when A and B are exchanged
    P[:3, 3:] = P[3:, :3] = flip
    np.testing.assert_allclose(P @ Kl @ P.T, Kl, rtol=1e-12, atol=1e-9)


def test_damped_is_complex_symmetric(cable17):
    for kw in [dict(loss_factor=0.02), dict(viscous_damping=0.05)]:
        s = ds.unstretched_length_for_tension(A0, B0, 300.0, cogiro_cable(17e9, **kw))
        w = np.linspace(0.0, 60.0, 50)
        K = ds.cable_dynamic_stiffness(s, w, ends="both")
        assert np.iscomplexobj(K)
        np.testing.assert_allclose(K, K.transpose(0, 2, 1), rtol=1e-12, atol=1e-9)
        assert np.all(np.isfinite(K))
        # viscous damping removes every pole; hysteretic damping acts on EA only, so the
        # string families (out-of-plane, antisymmetric) keep their real poles
        modes = ds.cable_natural_frequencies(s, 4)
        Kp = np.abs(ds.cable_dynamic_stiffness(s, TWO_PI * modes.freq_hz)).max(axis=(1, 2))
        s0 = ds.solve_catenary(A0, B0, s.unstretched_length, cable17)
        K_undamped = np.abs(ds.cable_dynamic_stiffness(
            s0, TWO_PI * modes.freq_hz * (1 + 1e-9))).max(axis=(1, 2))
        bounded = Kp < 1e-3 * K_undamped
        if "viscous_damping" in kw:
            assert np.all(bounded)
        else:
            sym = np.array([f == "in-plane symmetric" for f in modes.family])
            np.testing.assert_array_equal(bounded, sym)


def test_light_damping_converges_to_undamped(state300):
    w = np.linspace(1.0, 50.0, 40)
    K = ds.cable_dynamic_stiffness(state300, w)
    for kw in [dict(loss_factor=1e-9), dict(viscous_damping=1e-10)]:
        s = ds.solve_catenary(A0, B0, state300.unstretched_length, cogiro_cable(17e9, **kw))
        Kd = ds.cable_dynamic_stiffness(s, w)
        np.testing.assert_allclose(Kd.real, K, rtol=1e-6, atol=1e-6 * np.abs(K).max())


# ----------------------------------------------------------------------------- poles & modes
@pytest.mark.parametrize("lam2", [0.5, 1, 2, 5, 10, 20, 50, 100, 1000])
def test_irvine_roots_reproduce_theory_table(lam2):
    """theory.md §9.1 (Brent roots of the Irvine-Caughey equation, 7 significant digits)."""
    table = {0.5: (3.205404, 9.427179, 15.708480), 1: (3.267886, 9.429603, 15.708999),
             2: (3.389149, 9.434523, 15.710043), 5: (3.727496, 9.449882, 15.713225),
             10: (4.225833, 9.477637, 15.718697), 20: (5.056508, 9.542616, 15.730323),
             50: (6.793920, 9.850046, 15.771746), 100: (8.159296, 10.931722, 15.873408),
             1000: (8.948084, 15.370464, 21.646868)}
    np.testing.assert_allclose(irvine_symmetric_roots(lam2, 3), table[lam2], atol=6e-7)


def test_irvine_crossovers_and_limits():
    """Exact: lambda^2 = 4 n^2 pi^2 puts the n-th symmetric root on 2 n pi (theory.md §2.2);
    lambda^2 -> 0 gives (2k-1) pi; lambda^2 -> inf gives 2 x roots of tan x = x."""
    for n in (1, 2, 3):
        roots = irvine_symmetric_roots(4 * n * n * np.pi**2, n)
        assert roots[n - 1] == pytest.approx(2 * n * np.pi, rel=1e-12)
    np.testing.assert_allclose(irvine_symmetric_roots(1e-12, 3), [np.pi, 3 * np.pi, 5 * np.pi],
                               rtol=1e-12)
    np.testing.assert_allclose(irvine_symmetric_roots(1e12, 3),
                               2 * np.array([4.493409457909064, 7.725251836937707,
                                             10.904121659428899]), rtol=1e-9)


def test_string_families_are_exact(state300):
    modes = ds.cable_natural_frequencies(state300, 12)
    p = chord_parameters(state300)
    for fam, mult in [("out-of-plane", np.pi), ("in-plane antisymmetric", TWO_PI)]:
        sel = np.array([f == fam for f in modes.family])
        np.testing.assert_allclose(modes.Omega[sel], mult * modes.order[sel], rtol=1e-15)
    np.testing.assert_allclose(modes.freq_hz, modes.Omega / (TWO_PI * p.L) * np.sqrt(p.T / p.m),
                               rtol=1e-15)
    assert np.all(np.diff(modes.freq_hz) >= 0)
    assert modes.labels[0] == "out-of-plane 1"


def test_poles_sit_at_fixed_end_frequencies(state300):
    """Each clamped-clamped frequency is a pole: the entry of its family flips sign and grows
    like 1/(relative distance) across it."""
    modes = ds.cable_natural_frequencies(state300, 8)
    p = chord_parameters(state300)
    entry = {"out-of-plane": (2, 2), "in-plane symmetric": (0, 0),
             "in-plane antisymmetric": (1, 1)}
    for f, fam in zip(modes.freq_hz, modes.family):
        i, j = entry[fam]
        w = TWO_PI * f * np.array([1 - 1e-7, 1 + 1e-7, 1 - 1e-5, 1 + 1e-5])
        K = local_end_stiffness(p, w, chordwise_inertia=False)[:, i, j]
        assert np.sign(K[0]) != np.sign(K[1]), fam
        assert abs(K[0]) > 50 * abs(K[2]) and abs(K[1]) > 50 * abs(K[3]), fam


def test_mode_count_steps_at_each_natural_frequency(state300):
    modes = ds.cable_natural_frequencies(state300, 40)
    f = modes.freq_hz[:30]
    w = TWO_PI * f
    # out-of-plane 2n and antisymmetric n coincide exactly (Omega = 2 n pi): count multiplicity
    below = ds.cable_mode_count(state300, w * (1 - 1e-9))
    above = ds.cable_mode_count(state300, w * (1 + 1e-9))
    np.testing.assert_array_equal(below, [np.sum(modes.freq_hz < fk * (1 - 1e-12)) for fk in f])
    np.testing.assert_array_equal(above, [np.sum(modes.freq_hz <= fk * (1 + 1e-12)) for fk in f])
    multiplicity = [np.sum(np.isclose(modes.freq_hz, fk, rtol=1e-12)) for fk in f]
    np.testing.assert_array_equal(above - below, multiplicity)
    assert max(multiplicity) == 2


@settings(max_examples=60, deadline=None)
@given(lam2=st.floats(1e-6, 1e4), ratio=st.one_of(st.floats(0.0, 40.0), st.integers(0, 40)))
def test_count_equals_number_of_roots_below(lam2, ratio):
    """J0 from the branch rule equals the number of roots strictly below Omega (any lambda^2,
    including Omega exactly on a string root or a branch end)."""
    Om = float(ratio) * np.pi
    sym = irvine_symmetric_roots(lam2, 25)
    n = np.arange(1, 60)
    expected = np.sum(n * np.pi < Om) + np.sum(2 * n * np.pi < Om) + np.sum(sym < Om)
    assert ds.cable.psi.mode_count_nondimensional(np.array([Om]), lam2)[0] == expected


def test_eigenvalues_decrease_between_poles(state300):
    """Wittrick-Williams needs dK/domega negative definite between poles (theory.md §5.1)."""
    w = np.linspace(0.5, 120.0, 4001)
    ev = np.linalg.eigvalsh(ds.cable_dynamic_stiffness(state300, w, ends="both"))
    count = ds.cable_mode_count(state300, w)
    same_interval = np.diff(count) == 0
    assert np.all(np.diff(ev, axis=0)[same_interval] < 1e-9 * np.abs(ev).max())


# ----------------------------------------------------------------------------- vertical, inputs
def test_vertical_chord_is_a_string(cable17):
    s = ds.solve_catenary((0, 0, 10), (0, 0, 0), 9.99, cable17)
    p = chord_parameters(s)
    assert p.lambda_sq == 0.0
    modes = ds.cable_natural_frequencies(s, 6)
    np.testing.assert_allclose(modes.Omega, np.pi * np.array([1, 1, 2, 2, 3, 3]), rtol=1e-12)
    K = ds.cable_dynamic_stiffness(s, [0.0, 20.0])
    assert np.all(np.isfinite(K))
    np.testing.assert_allclose(K[:, 0, 0], K[:, 1, 1], rtol=1e-12)   # isotropic transverse


@pytest.mark.parametrize("omega", [-1.0, float("nan"), float("inf"), [1.0, -2.0]])
def test_bad_omega_raises(state300, omega):
    with pytest.raises(InvalidParameterError, match="omega"):
        ds.cable_dynamic_stiffness(state300, omega)


def test_bad_options_raise(state300):
    with pytest.raises(InvalidParameterError, match="ends"):
        ds.cable_dynamic_stiffness(state300, 1.0, ends="B")
    with pytest.raises(InvalidParameterError, match="tension"):
        ds.cable_dynamic_stiffness(state300, 1.0, tension="max")
    with pytest.raises(InvalidParameterError, match="n_modes"):
        ds.cable_natural_frequencies(state300, 0)


def test_shapes(state300):
    assert ds.cable_dynamic_stiffness(state300, 3.0).shape == (1, 3, 3)
    assert ds.cable_dynamic_stiffness(state300, np.arange(7.0), ends="both").shape == (7, 6, 6)


def test_frequencies_beyond_the_closed_forms_range_are_refused(state300):
    """omega L sqrt(m/T) above 1e7 (sin and cos of psi lose their digits; mode counts leave
    exact integers) is an error naming omega and the admissible bound, never an overflowed
    count or a NaN matrix."""
    p = ds.cable.dsm.chord_parameters(state300)
    w_max = ds.cable.psi.MAX_OMEGA_ND / (p.L * np.sqrt(p.m / p.T))
    n = ds.cable_mode_count(state300, 0.999 * w_max)[0]
    assert 0 < n < 2**53
    for w in (1.001 * w_max, 1e20, 1e300):
        with pytest.raises(InvalidParameterError, match=r"omega must be <= .* rad/s"):
            ds.cable_mode_count(state300, w)
        with pytest.raises(InvalidParameterError, match="omega must be <="):
            ds.cable_dynamic_stiffness(state300, [1.0, w])


@pytest.mark.parametrize("lam2", [0.18, 5e3])
def test_high_irvine_roots_match_a_multiprecision_bisection(lam2):
    """Up to the 20000th symmetric root (where the root sits 1e-16 above its branch start and
    4 cos(psi) is below its own rounding), against a 40-digit bisection of
    4 cos(psi) - lambda^2 (psi cos psi - sin psi) / psi^3 = 0."""
    import mpmath
    roots = irvine_symmetric_roots(lam2, 20000)
    with mpmath.workdps(40):
        L2 = mpmath.mpf(lam2)

        def g(x):
            return 4 * mpmath.cos(x) - L2 * (x * mpmath.cos(x) - mpmath.sin(x)) / x**3
        for k in (1, 40, 2000, 20000):
            a = (2 * k - 1) * mpmath.pi / 2 + mpmath.mpf("1e-35")
            b = (2 * k + 1) * mpmath.pi / 2 - mpmath.mpf("1e-35")
            ga = g(a)
            for _ in range(170):
                c = (a + b) / 2
                gc = g(c)
                if ga * gc <= 0:
                    b = c
                else:
                    a, ga = c, gc
            assert abs(roots[k - 1] / float(a + b) - 1) < 4e-16


@pytest.mark.parametrize("n", [np.nan, np.inf, None, 2.0, "3", 0])
def test_cable_natural_frequencies_count_must_be_an_integer(state300, n):
    with pytest.raises(InvalidParameterError, match="n_modes must be an integer >= 1"):
        ds.cable_natural_frequencies(state300, n)


def test_ten_thousand_labelled_cable_modes(state300):
    """The high symmetric roots no longer fail in the root finder: 10000 modes come back
    ascending, each family in its order, the out-of-plane ones at n pi exactly."""
    cm = ds.cable_natural_frequencies(state300, 10000)
    assert len(cm) == 10000 and np.all(np.diff(cm.Omega) >= 0)
    oop = np.array(cm.family) == "out-of-plane"
    np.testing.assert_allclose(cm.Omega[oop], np.pi * cm.order[oop], rtol=1e-15)


def test_closed_form_guard_flags_slack_steep_and_axial_cables_and_not_cogiro():
    """closed_form_validity (theory.md §11.5): the estimate bounds the measured error of the
    clamped frequencies against the exact model on the hard cases, is inf for a slack U and
    for axial modes in the band, and stays below 1e-3 on CoGiRo's cables."""
    from dynstiff.cable.guard import closed_form_local_error, closed_form_validity
    slack = ds.solve_catenary([0, 0, 0], [1e-6, 0, 10], 10.1, ds.Cable(0.064, 1.4e5))
    v = closed_form_validity(slack)
    assert np.isinf(v.error) and any("slack" in r for r in v.reasons(1e-2))
    steep = ds.solve_catenary([0, 0, 0], [5.0, 0, 5 * np.sqrt(3)], 10.6, ds.Cable(1.0, 1e6))
    v = closed_form_validity(steep)
    measured = closed_form_local_error(steep, 0.0)
    assert measured > 1e-2 and v.error >= measured
    soft = ds.solve_catenary([0, 0, 0], [10.0, 0, -2.0], 9.8, ds.Cable(1.0, 2e3))
    f_ax = np.sqrt(2e3 / 1.0) / (2 * 9.8)
    assert np.isfinite(closed_form_validity(soft, 2 * np.pi * 0.8 * f_ax).error)
    v = closed_form_validity(soft, 2 * np.pi * f_ax)
    assert np.isinf(v.causes["axial"]) and "axial modes from" in v.reasons(1e-2)[-1]
    for s in ds.load_scene("cogiro").equilibrium().states:
        v = closed_form_validity(s, 2 * np.pi * 20.0)
        assert v.error < 1e-3
        assert closed_form_local_error(s, 2 * np.pi * 20.0) <= v.error
    # the cable-level functions warn too, and stay silent on CoGiRo
    import warnings

    from dynstiff.errors import ClosedFormWarning
    with pytest.warns(ClosedFormWarning, match="off the exact model's") as rec:
        ds.cable_natural_frequencies(steep, 5)
    assert rec[0].message.cause == "local" and rec[0].message.cable is None
    with pytest.warns(ClosedFormWarning) as rec:
        ds.cable_dynamic_stiffness(slack, [0.0, 1.0])
    assert rec[0].message.cause == "slack" and rec[0].message.cable is None
    # the message lists the validity's reasons above a tenth of guard_rtol (1e-2)
    reasons = "; ".join(closed_form_validity(slack, 1.0).reasons(1e-3))
    assert str(rec[0].message) == (f"it is outside the closed form's range ({reasons}): "
                                   f"use model='exact'")
    with pytest.warns(ClosedFormWarning) as rec:
        ds.cable_dynamic_stiffness(soft, 2 * np.pi * f_ax)
    assert rec[0].message.cause == "axial"
    reasons = closed_form_validity(soft, 2 * np.pi * f_ax).reasons(1e-3)
    assert len(reasons) > 1 and str(rec[0].message) == (
        f"it is outside the closed form's range ({'; '.join(reasons)}): use model='exact'")
    for bad in (0, 0.0, -1e-3, np.inf, True, "1e-2"):
        with pytest.raises(InvalidParameterError,
                           match=f"^guard_rtol must be a number > 0 or None, got {bad!r}$"):
            ds.cable_dynamic_stiffness(steep, 1.0, guard_rtol=bad)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ClosedFormWarning)
        ds.cable_natural_frequencies(s, 12)
        ds.cable_dynamic_stiffness(steep, 1.0, guard_rtol=None)


@pytest.mark.parametrize("chordwise", [True, False])
@pytest.mark.parametrize("damping", [{}, {"loss_factor": 0.02}, {"viscous_damping": 0.3}])
def test_block_coefficients_rebuild_the_two_end_matrix(chordwise, damping):
    """The five dyad coefficients (u u, u v, v u, v v, w w) of the blocks AA, AB and BB
    rebuild the local two-end DSM, with and without chordwise inertia, undamped or damped
    (theory.md §3.4); undamped they are real."""
    from dynstiff.cable.dsm import block_coefficients
    state = ds.solve_catenary((0, 0, 0), (8.0, 3.0, -5.0), 9.9,
                              ds.Cable(0.064, 139486.7, **damping))
    p = chord_parameters(state)
    w = np.array([0.5, 20.0, 55.0])
    c = block_coefficients(p, w, chordwise, blocks="both")
    assert set(c) == {"AA", "AB", "BB"}
    assert set(block_coefficients(p, w, chordwise)) == {"BB"}
    K = local_two_end_stiffness(p, w, chordwise)
    assert np.iscomplexobj(K) == bool(damping)
    for name, rows, cols in (("AA", slice(0, 3), slice(0, 3)), ("AB", slice(0, 3), slice(3, 6)),
                             ("BB", slice(3, 6), slice(3, 6))):
        a = c[name]
        assert a.dtype == K.dtype
        B = np.zeros((w.size, 3, 3), dtype=a.dtype)
        B[:, 0, 0], B[:, 0, 1], B[:, 1, 0], B[:, 1, 1], B[:, 2, 2] = a.T
        np.testing.assert_allclose(B, K[:, rows, cols], rtol=1e-13,
                                   atol=1e-13 * np.abs(K).max())


def test_undamped_kernels_continue_analytically_to_complex_frequencies():
    """An undamped cable's DSM at complex omega (how damped modes are searched) is the
    analytic continuation: complex, K(conj w) = conj K(w), and at w (1 + i e) it equals the
    first-order Taylor step K(w) + i e w dK/domega to O(e^2) (theory.md §3.4)."""
    state = ds.solve_catenary((0, 0, 0), (8.0, 3.0, -5.0), 9.9, ds.Cable(0.064, 139486.7))
    p = chord_parameters(state)
    w, e, h = np.array([3.0, 21.0]), 1e-6, 1e-4
    for kernel in (local_end_stiffness, local_two_end_stiffness):
        Kc = kernel(p, w * (1 + 1j * e))
        assert np.iscomplexobj(Kc)
        np.testing.assert_allclose(kernel(p, w * (1 - 1j * e)), np.conj(Kc), rtol=1e-14,
                                   atol=1e-14 * np.abs(Kc).max())
        dK = (kernel(p, w * (1 + h)) - kernel(p, w * (1 - h))) / (2 * h)
        np.testing.assert_allclose(Kc.imag, e * dK, rtol=1e-5, atol=1e-9 * np.abs(dK).max())


def test_end_block_and_count_equal_their_separate_kernels_for_one_cable_and_a_stack():
    """One evaluation of the psi functions gives the end-block coefficients and J0 equal to
    :func:`end_block_coefficients` and :func:`cable_mode_count`, for one cable (shapes
    (n, 5), (n,)) and a stack ((n, n_cables, 5), (n, n_cables)); damped cables or complex
    omega are refused (theory.md §14.2)."""
    from dynstiff.cable.chord import stack_parameters
    from dynstiff.cable.dsm import (
        end_block_coefficients,
        end_block_coefficients_and_count,
    )
    from dynstiff.cable.psi import cable_mode_count
    states = [ds.solve_catenary((0, 0, 0), B, L0, ds.Cable(0.064, 139486.7))
              for B, L0 in (((8.0, 3.0, -5.0), 9.9), ((4.0, -2.0, 6.0), 7.6))]
    w = np.linspace(0.0, 120.0, 57)
    for chordwise in (True, False):
        for k, s in enumerate(states):
            p = chord_parameters(s)
            c, J0 = end_block_coefficients_and_count(p, w, chordwise)
            assert c.shape == (57, 5) and J0.shape == (57,) and c.dtype == np.float64
            np.testing.assert_allclose(c, end_block_coefficients(p, w, chordwise), rtol=1e-14,
                                       atol=1e-14 * np.abs(c).max())
            np.testing.assert_array_equal(J0, cable_mode_count(s, w))
            stack = stack_parameters([chord_parameters(t) for t in states])
            cs, Js = end_block_coefficients_and_count(stack, w, chordwise)
            assert cs.shape == (57, 2, 5) and Js.shape == (57, 2)
            np.testing.assert_allclose(cs[:, k], c, rtol=1e-14, atol=1e-14 * np.abs(c).max())
            np.testing.assert_array_equal(Js[:, k], J0)
    assert J0.max() > 3
    p = chord_parameters(states[0])
    msg = r"^end_block_coefficients_and_count needs undamped cables at real omega$"
    with pytest.raises(InvalidParameterError, match=msg):
        end_block_coefficients_and_count(p, w * (1 + 1e-3j))
    for cab in (ds.Cable(0.064, 139486.7, loss_factor=0.01),
                ds.Cable(0.064, 139486.7, viscous_damping=0.1)):
        damped = chord_parameters(ds.solve_catenary((0, 0, 0), (8.0, 3.0, -5.0), 9.9, cab))
        with pytest.raises(InvalidParameterError, match=msg):
            end_block_coefficients_and_count(damped, w)


def test_cable_dsm_options_reach_the_kernels(state300):
    """Each option of :func:`cable_dynamic_stiffness` reaches the kernel: chordwise inertia
    adds exactly -omega^2 m L / 3 u u^T to K_B (theory.md §3.4); the chord tension differs
    from the mean tension; complex omega is refused, not cast; an empty grid gives
    an empty stack for both models; the exact model honours ``ends``."""
    s = state300
    w = np.array([2.0, 9.0, 31.0])
    p = chord_parameters(s)
    u = (s.end - s.anchor) / np.linalg.norm(s.end - s.anchor)
    on = ds.cable_dynamic_stiffness(s, w, chordwise_inertia=True)
    off = ds.cable_dynamic_stiffness(s, w, chordwise_inertia=False)
    np.testing.assert_allclose(on - off, -(w**2 * p.m * p.L / 3)[:, None, None]
                               * np.outer(u, u), rtol=1e-9, atol=1e-9 * np.abs(on).max())
    chord = ds.cable_dynamic_stiffness(s, w, tension="chord")
    assert np.abs(chord - ds.cable_dynamic_stiffness(s, w)).max() > 1e-6 * np.abs(chord).max()
    with pytest.raises(InvalidParameterError, match="omega must be real .* got complex"):
        ds.cable_dynamic_stiffness(s, w * (1 + 1e-6j), ends="both")
    for model in ("closed-form", "exact"):
        assert ds.cable_dynamic_stiffness(s, [], model=model).shape == (0, 3, 3)
    assert ds.cable_dynamic_stiffness(s, w, ends="both", model="exact").shape == (3, 6, 6)


def test_cable_modes_table_repr_and_plot(state300):
    import matplotlib.pyplot as plt
    modes = ds.cable_natural_frequencies(state300, 5)
    df = modes.to_frame()
    assert list(df.columns) == ["freq [Hz]", "Omega [-]", "family", "order"]
    np.testing.assert_array_equal(df["freq [Hz]"], modes.freq_hz)
    assert list(df["family"]) == list(modes.family) and list(df["order"]) == list(modes.order)
    assert repr(modes) == (f"CableModes(5 modes {modes.freq_hz[0]:.4g}-{modes.freq_hz[-1]:.4g}"
                           f" Hz: {', '.join(modes.labels[:3])}, ...)")
    fig, ax = plt.subplots()
    assert modes.plot(ax=ax) is fig
    assert any(str(a.get_gid()).startswith("cable-") for a in ax.get_children())
    plt.close(fig)


def test_series_coefficients_are_the_taylor_series_of_the_psi_functions():
    """The series branch of the psi functions (|psi| < 1): its coefficients, recomputed
    here, evaluate E, P~ and Q~ to 1e-15 of their mpmath values at psi^2 = 0.0 .. 1."""
    import mpmath

    from dynstiff.cable.psi import _series_coefficients
    E, P, Q = _series_coefficients()
    for x in (0.0, 0.05, 0.3, 0.7, 1.0):
        with mpmath.workdps(60):
            p = mpmath.sqrt(x) if x else mpmath.mpf("1e-15")
            s, c = mpmath.sin(p), mpmath.cos(p)
            ref = [float(r) for r in ((p * c - s) / p**3, ((1 + p**2) * s * c - p) / p**3,
                                      (p * (c**2 - s**2) + (p**2 - 1) * s * c) / p**3)]
        for coef, r in zip((E, P, Q), ref):
            assert np.polyval(coef, x) == pytest.approx(r, rel=1e-15, abs=1e-16)


@pytest.mark.parametrize("tension", ["mean", "chord"])
def test_validity_and_exact_modes_use_the_tension_asked(state300, tension):
    """closed_form_validity's weight ratio is W |h| / (L T) with the T of the tension asked
    (theory.md §11.5), and the exact model's modes give Omega = omega L sqrt(m / T) with
    that T, like the closed form's."""
    from dynstiff.cable.guard import closed_form_validity
    s = state300
    p = chord_parameters(s, tension)
    v = closed_form_validity(s, tension=tension)
    assert v.values["weight_ratio"] == pytest.approx(
        s.total_weight * abs(s.chord[2]) / s.chord_length / p.T, rel=1e-14)
    for model in ("closed-form", "exact"):
        cm = ds.cable_natural_frequencies(s, 4, tension=tension, model=model)
        np.testing.assert_allclose(cm.Omega, 2 * np.pi * cm.freq_hz * p.L * np.sqrt(p.m / p.T),
                                   rtol=1e-13)


@pytest.mark.parametrize("step", [np.pi, 2 * np.pi])
def test_multiples_below_count_ties_and_roundings_as_the_products_do(step):
    """#{n >= 1 : n step < x} at x = m step (m - 1 of them) and at the next float above it
    (m), for m up to 3000, including the ~10 % of those where x / step rounds back down onto
    m; brute force compares the float products n step themselves."""
    from dynstiff.cable.psi import _count_multiples_below
    m = np.arange(1, 3001)
    on = m * step
    above = np.nextafter(on, np.inf)
    assert np.count_nonzero(above / step == m) > 100
    for x, want in ((on, m - 1), (above, m)):
        brute = np.array([np.count_nonzero(np.arange(1, k + 2) * step < v)
                          for k, v in zip(m, x)])
        np.testing.assert_array_equal(brute, want)
        np.testing.assert_array_equal(_count_multiples_below(x, step), want)


def test_a_complex_frequency_beyond_the_range_is_named_as_given(state300):
    """check_frequency_range names the largest |omega| as given, complex included."""
    from dynstiff.cable.psi import check_frequency_range
    p = chord_parameters(state300)
    with pytest.raises(InvalidParameterError, match=r"got 1e\+09\+2j$"):
        check_frequency_range(p, np.array([3.0 + 0.1j, 1e9 + 2j]))
    with pytest.raises(InvalidParameterError, match=r"^w must be <= .*got 1e\+09$"):
        check_frequency_range(p, np.array([3.0, 1e9]), name="w")


def test_the_measured_local_error_uses_the_tension_asked_for_its_band():
    """closed_form_local_error over the modes below 8 omega_1, omega_1 = pi sqrt(T / m) / L
    with the T asked (theory.md §11.5): on a steep sagging cable, whose chord tension is
    34 % below its mean, the chord-tension error is the largest |f_closed / f_exact - 1| of
    the exact cable's non-axial modes in that band, rebuilt here."""
    from dynstiff.cable.exact import ExactCable
    from dynstiff.cable.guard import closed_form_local_error
    s = ds.solve_catenary([0, 0, 0], [5.0, 0, 5 * np.sqrt(3)], 10.6, ds.Cable(1.0, 1e6))
    p = chord_parameters(s, "chord")
    band = 8 * np.pi * np.sqrt(p.T / p.m) / p.L
    ec = ExactCable(s, band)
    keep = (ec.eigenvalues <= band**2) & (np.array(ec.family) != "axial")
    f_ex = np.sqrt(ec.eigenvalues[keep]) / (2 * np.pi)
    f_cf = ds.cable_natural_frequencies(s, f_ex.size, "chord", guard_rtol=None).freq_hz
    want = np.max(np.abs(f_cf / f_ex - 1))
    assert closed_form_local_error(s, 0.0, "chord") == pytest.approx(want, rel=1e-12)
    assert closed_form_local_error(s, 0.0, "mean") != pytest.approx(want, rel=1e-3)


def test_exact_modes_are_numbered_within_their_family():
    """The exact model's labels on a soft cable whose axial mode is among its first 12: in
    each of the three families the orders are 1, 2, 3, ... by frequency."""
    soft = ds.solve_catenary([0, 0, 0], [10.0, 0, -2.0], 9.8, ds.Cable(1.0, 2e3))
    cm = ds.cable_natural_frequencies(soft, 12, model="exact")
    fam = np.array(cm.family)
    assert set(cm.family) == {"out-of-plane", "in-plane", "axial"}
    for name in set(cm.family):
        sel = fam == name
        np.testing.assert_array_equal(cm.order[sel], np.arange(1, sel.sum() + 1))
        assert np.all(np.diff(cm.freq_hz[sel]) > 0)


def test_coincident_closed_form_modes_are_listed_in_family_order(state300):
    """Out-of-plane k pi and in-plane antisymmetric 2 j pi coincide for k = 2 j: such pairs
    keep the documented family order, out-of-plane first, every one of them."""
    cm = ds.cable_natural_frequencies(state300, 60, guard_rtol=None)
    fam = np.array(cm.family)
    ties = np.flatnonzero(np.diff(cm.Omega) == 0)
    assert len(ties) >= 10
    assert np.all(fam[ties] == "out-of-plane")
    assert np.all(fam[ties + 1] == "in-plane antisymmetric")
    np.testing.assert_array_equal(cm.order[ties + 1] * 2, cm.order[ties])
