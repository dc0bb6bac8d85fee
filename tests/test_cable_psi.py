"""The closed form's functions of psi (dynstiff/cable/psi.py, theory.md §3.2, §5.2): series
branches, the frequency range, the clamped count J0 and the Irvine-Caughey spectrum."""

import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.cable.dsm import chord_parameters
from dynstiff.cable.psi import irvine_symmetric_roots
from dynstiff.errors import InvalidParameterError

TWO_PI = 2 * np.pi


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


def test_mode_count_steps_at_each_natural_frequency(state300):
    modes = ds.cable_natural_frequencies(state300, 40, guard_rtol=None)  # the closed form alone
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


def test_mode_count_follows_the_tension_asked(state300):
    """With tension="chord" (H / cos theta, not the mean tension) the count steps at the
    chord tension's frequencies, which differ from the mean tension's on this inclined
    cable by about 1e-5 (1e4 times the steps of 1e-9 about each frequency)."""
    f = {t: ds.cable_natural_frequencies(state300, 6, tension=t, guard_rtol=None).freq_hz
         for t in ("mean", "chord")}
    assert np.min(np.abs(f["chord"] / f["mean"] - 1)) > 1e-6
    for t in ("mean", "chord"):
        w = TWO_PI * f[t]
        below = ds.cable_mode_count(state300, w * (1 - 1e-9), tension=t)
        above = ds.cable_mode_count(state300, w * (1 + 1e-9), tension=t)
        assert np.all(above > below)


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


def test_frequencies_beyond_the_closed_forms_range_are_refused(state300):
    """omega L sqrt(m/T) above 1e7 (sin and cos of psi lose their digits; mode counts leave
    exact integers) is an error naming omega and the admissible bound, never an overflowed
    count or a NaN matrix."""
    p = ds.cable.dsm.chord_parameters(state300)
    w_max = ds.cable.psi.MAX_OMEGA_ND / (p.L * np.sqrt(p.m / p.T))
    n = ds.cable_mode_count(state300, 0.999 * w_max)[0]
    assert 0 < n < 2**53
    bound = re.escape(f"omega must be <= {w_max:.6g} rad/s")   # 1e300: omega^2 m overflows
    for w in (1.001 * w_max, 1e20, 1e300):
        with pytest.raises(InvalidParameterError,
                           match=bound if w < 1e150 else r"omega must be <= .* rad/s"):
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




def test_series_coefficients_are_the_first_n_terms_exactly():
    """The series' coefficients are the first _N_TERMS Taylor coefficients (in psi^2) of E,
    P~ and Q~, computed here in exact rationals from the sine and cosine series by
    polynomial products (an independent derivation): none missing, none extra."""
    from fractions import Fraction
    from math import factorial

    from dynstiff.cable.psi import _N_TERMS, _series_coefficients
    D = 2 * _N_TERMS + 6                                   # degree kept in psi

    def poly(f):
        return [f(k) for k in range(D)]

    def mul(p, q):
        out = [Fraction(0)] * D
        for i, a in enumerate(p):
            for j, b in enumerate(q[:D - i]):
                out[i + j] += a * b
        return out

    sin = poly(lambda k: Fraction((-1) ** (k // 2), factorial(k)) if k % 2 else Fraction(0))
    cos = poly(lambda k: Fraction(0) if k % 2 else Fraction((-1) ** (k // 2), factorial(k)))
    x = poly(lambda k: Fraction(k == 1))                   # psi
    one = poly(lambda k: Fraction(k == 0))
    sc = mul(sin, cos)
    x2 = mul(x, x)
    numerators = (                                         # each over psi^3
        [a - b for a, b in zip(mul(x, cos), sin)],
        [a - b for a, b in zip(mul([u + v for u, v in zip(one, x2)], sc), x)],
        [a + b for a, b in zip(mul(x, [c - s for c, s in zip(mul(cos, cos), mul(sin, sin))]),
                               mul([v - u for u, v in zip(one, x2)], sc))])
    for coef, num in zip(_series_coefficients(), numerators):
        assert num[:3] == [0, 0, 0] and all(c == 0 for c in num[4::2])  # even in psi
        exact = [float(num[3 + 2 * k]) for k in range(_N_TERMS)]
        assert len(coef) == _N_TERMS
        np.testing.assert_allclose(coef[::-1], exact, rtol=1e-15, atol=0)


def test_heavy_viscous_damping_at_a_real_frequency_is_refused_not_nan():
    """With viscous damping c, psi is complex at a real omega too: Im psi tends to
    L c / (4 sqrt(m T)) as omega grows (theory.md §12.2), and above 350 sin and cos
    overflow. A real omega there is an error naming omega, never a NaN matrix; below, the
    same cable's stiffness is finite."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    cable = ds.Cable(mass_per_length=0.064, EA=1.64e6, viscous_damping=5000.0)
    st = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    p = chord_parameters(st)
    assert p.L * p.c / (4 * np.sqrt(p.m * p.T)) > ds.cable.psi.MAX_IMAG_PSI
    w = 3000.0
    im_psi = abs(np.imag(0.5 * p.L * np.sqrt((w**2 * p.m - 1j * w * p.c) / p.T)))
    assert im_psi > ds.cable.psi.MAX_IMAG_PSI
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)      # far outside its range
        with pytest.raises(InvalidParameterError, match=re.escape(
                f"omega is too large for the closed form with the cables' viscous damping "
                f"(|Im psi| = {im_psi:.4g} > 350: sin and cos overflow), got |omega| up to "
                f"3000 rad/s")):
            ds.cable_dynamic_stiffness(st, [10.0, w])
        assert np.all(np.isfinite(ds.cable_dynamic_stiffness(st, [10.0, 1000.0])))
