"""The mpmath reference (dynstiff.cable.mpmath_reference) and the float64 kernel checked against it.

Tiers (STYLE.md §8): (a) analytic limits of the reference; (b) the equation-exact Irvine
table of theory.md §9.1; (f) cross-model agreement: stable float64 closed forms
(cable_dsm, theory.md §3.5) against the naive textbook forms (theory.md §3.2-3.4) evaluated
with 50+ digits.
"""

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest

from dynstiff.cable.dsm import ChordParameters, local_end_stiffness, local_two_end_stiffness
from dynstiff.cable.mpmath_reference import (
    end_stiffness_mp,
    irvine_symmetric_roots_mp,
    params_to_mp_args,
    two_end_stiffness_mp,
)
from dynstiff.cable.psi import irvine_symmetric_roots

EPS = np.finfo(float).eps
_FINDROOT = mpmath.findroot          # the real solver, for the stand-ins of the tests below
_VALIDATION = Path(__file__).resolve().parents[1] / "validation" / "float64_vs_mpmath.py"


def _load_validation():
    spec = importlib.util.spec_from_file_location("float64_vs_mpmath", _VALIDATION)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


V = _load_validation()


# --------------------------------------------------------------------------- Irvine roots
# theory.md §9.1: roots of the Irvine-Caughey symmetric equation (Irvine & Caughey 1974;
# theory.md §2.2) solved with Brent's method to 1e-15 and printed to 7 significant digits.
# Equation-exact values, not published ones. lambda^2 = None means infinity.
IRVINE_TABLE = [
    ("0.5", (3.205404, 9.427179, 15.708480), 1.02031),
    ("1", (3.267886, 9.429603, 15.708999), 1.04020),
    ("2", (3.389149, 9.434523, 15.710043), 1.07880),
    ("5", (3.727496, 9.449882, 15.713225), 1.18650),
    ("10", (4.225833, 9.477637, 15.718697), 1.34512),
    ("20", (5.056508, 9.542616, 15.730323), 1.60954),
    ("4pi2", (6.283185, 9.718273, 15.755961), 2.00000),
    ("50", (6.793920, 9.850046, 15.771746), 2.16257),
    ("100", (8.159296, 10.931722, 15.873408), 2.59718),
    ("16pi2", (8.600065, 12.566371, 16.091717), 2.73749),
    ("1000", (8.948084, 15.370464, 21.646868), 2.84826),
    ("inf", (8.986819, 15.450504, 21.808243), 2.86059),
]


def _lambda_sq_mp(label):
    special = {"4pi2": 4 * mpmath.pi**2, "16pi2": 16 * mpmath.pi**2, "inf": mpmath.inf}
    return special[label] if label in special else mpmath.mpf(label)


@pytest.mark.parametrize("label, omegas, omega1_over_pi", IRVINE_TABLE,
                         ids=[row[0] for row in IRVINE_TABLE])
def test_irvine_roots_mp_match_theory_table(label, omegas, omega1_over_pi):
    with mpmath.workdps(30):
        roots = irvine_symmetric_roots_mp(_lambda_sq_mp(label), 3)
        got = [float(r) for r in roots]
        ratio = float(roots[0] / mpmath.pi)
    # the table has 7 significant digits (6 decimals): half a unit of the last place is 5e-7
    np.testing.assert_allclose(got, omegas, rtol=0, atol=5e-7)
    assert abs(ratio - omega1_over_pi) <= 5e-6          # 5 decimals in the table


def test_irvine_roots_mp_exact_crossovers_and_limits():
    with mpmath.workdps(60):
        pi = mpmath.pi
        # crossover lambda^2 = 4 n^2 pi^2: the n-th symmetric root is 2 n pi (theory.md §2.2)
        assert abs(irvine_symmetric_roots_mp(4 * pi**2, 1)[0] - 2 * pi) < mpmath.mpf("1e-45")
        assert abs(irvine_symmetric_roots_mp(16 * pi**2, 2)[1] - 4 * pi) < mpmath.mpf("1e-45")
        # taut string lambda^2 = 0: (2k - 1) pi
        for k, r in enumerate(irvine_symmetric_roots_mp(0, 4), start=1):
            assert abs(r - (2 * k - 1) * pi) < mpmath.mpf("1e-45")
        # inextensible limit: twice the roots of tan x = x
        for r in irvine_symmetric_roots_mp(mpmath.inf, 4):
            assert abs(mpmath.tan(r / 2) - r / 2) < mpmath.mpf("1e-40")
        # residual of the published tan form itself, and the branch bracket
        lam2 = mpmath.mpf(10)
        for k, r in enumerate(irvine_symmetric_roots_mp(lam2, 5), start=1):
            psi = r / 2
            assert abs(mpmath.tan(psi) - psi + 4 * psi**3 / lam2) < mpmath.mpf("1e-40")
            assert (2 * k - 1) * pi < r < (2 * k + 1) * pi


@pytest.mark.parametrize("lambda_sq, n_roots, dps", [
    (0, 4, 30), ("1e-300", 4, 30), ("1e-40", 3, 50), ("1e-58", 3, 50), ("1e-61", 3, 50),
    ("1e-70", 3, 50), ("1e-40", 3, 15), ("1e-300", 3, 30), ("1e-66", 20, 50),
    ("1e-420", 3, 400), ("1e-425", 3, 400)])
def test_irvine_roots_mp_of_a_nearly_taut_cable(lambda_sq, n_roots, dps):
    """For small lambda^2 the k-th root lies above the string's (2k-1) pi by
    4 lambda^2 / ((2k-1)^3 pi^3) (first order of tan(psi) = psi - 4 psi^3 / lambda^2 about
    psi = (2k-1) pi / 2; the taut string at lambda^2 = 0): n_roots roots, each to dps digits,
    also where that offset is below the working precision (where the end values of the
    root's bracket, lambda^2 / (4 psi_k^3), are rounding noise: high modes, k up to 20, and
    dps = 400), and to 1e-7 of the offset itself where dps resolves it."""
    roots = irvine_symmetric_roots_mp(lambda_sq, n_roots, dps=dps)
    assert len(roots) == n_roots
    with mpmath.workdps(dps + 30):
        lam2 = mpmath.mpf(lambda_sq)
        for k, r in enumerate(roots, start=1):
            base = (2 * k - 1) * mpmath.pi
            offset = 4 * lam2 / ((2 * k - 1) ** 3 * mpmath.pi ** 3)
            assert abs(r - (base + offset)) < mpmath.mpf(10) ** (-dps) * base
            if offset > mpmath.mpf(10) ** (8 - dps) * base:
                assert abs((r - base) / offset - 1) < 1e-7


@pytest.mark.parametrize("lambda_sq, n_roots, message", [
    (1.0, 0, "n_roots must be >= 1, got 0"),
    (-1.0, 2, "lambda_sq must be >= 0, got -1.0"),
    (float("nan"), 2, "lambda_sq must be >= 0, got nan"),
])
def test_irvine_roots_mp_reject_invalid_arguments(lambda_sq, n_roots, message):
    """n_roots >= 1 and lambda^2 >= 0 (documented); NaN is not >= 0."""
    with pytest.raises(ValueError, match=rf"^{re.escape(message)}$"):
        irvine_symmetric_roots_mp(lambda_sq, n_roots)


def _irvine_g(lam2):
    """g(psi) of the irvine_symmetric_roots_mp docstring (zero at psi = Omega_k / 2)."""
    def g(x):
        return ((4 * x**3 * mpmath.cos(x) / lam2 - x * mpmath.cos(x) + mpmath.sin(x))
                / (4 * x**3 / lam2 + x))
    return g


def test_irvine_roots_mp_fall_back_to_bisection_when_anderson_stalls(monkeypatch):
    """Documented: Anderson-Bjorck, then bisection if that stalls. Anderson is cut to one step
    here (a stall: a point inside the branch with |g| of order one, far above 10^-dps); each
    root then comes from the bisection and still solves the published tan form to 40 digits,
    lies in its branch and matches theory.md §9.1 (lambda^2 = 10, 7 significant digits)."""
    calls = []

    def one_step_anderson(f, x0, solver, **kw):
        calls.append(solver)
        if solver == "anderson":
            kw["maxsteps"] = 1
        return _FINDROOT(f, x0, solver=solver, **kw)

    monkeypatch.setattr(mpmath, "findroot", one_step_anderson)
    roots = irvine_symmetric_roots_mp(10, 3, dps=50)
    assert calls == ["anderson", "bisect"] * 3
    np.testing.assert_allclose([float(r) for r in roots], (4.225833, 9.477637, 15.718697),
                               rtol=0, atol=5e-7)
    with mpmath.workdps(60):
        lam2 = mpmath.mpf(10)
        for k, r in enumerate(roots, start=1):
            psi = r / 2
            assert abs(mpmath.tan(psi) - psi + 4 * psi**3 / lam2) < mpmath.mpf("1e-40")
            assert (2 * k - 1) * mpmath.pi < r < (2 * k + 1) * mpmath.pi


def test_irvine_roots_mp_raise_when_no_solver_converges(monkeypatch):
    """Both solvers cut to one step: ArithmeticError naming the root (1), lambda^2, the last
    psi and its residual; that psi lies in the first branch (pi/2, 3 pi/2) and the residual
    is |g(psi)| of the docstring (recomputed here), above 10^-dps."""
    def one_step(f, x0, solver, **kw):
        return _FINDROOT(f, x0, solver=solver, **{**kw, "maxsteps": 1})

    monkeypatch.setattr(mpmath, "findroot", one_step)
    number = r"([0-9.]+(?:e[-+]?[0-9]+)?)"
    message = (rf"^Irvine root 1 of lambda\^2 = 10\.0 not converged: psi = {number}, "
               rf"residual {number}$")
    with pytest.raises(ArithmeticError, match=message) as info:
        irvine_symmetric_roots_mp(10, 2, dps=30)
    psi_text, residual_text = re.match(message, str(info.value)).groups()
    with mpmath.workdps(60):
        psi, residual = mpmath.mpf(psi_text), mpmath.mpf(residual_text)
        assert mpmath.pi / 2 < psi < 3 * mpmath.pi / 2
        assert residual > mpmath.mpf("1e-30")
        assert abs(residual - abs(_irvine_g(mpmath.mpf(10))(psi))) < mpmath.mpf("1e-25")


@pytest.mark.parametrize("residual, bisected", [(1.2, True), (0.8, False), (-1.2, True),
                                                (-0.8, False)])
def test_irvine_roots_mp_accept_a_residual_below_ten_to_minus_dps(monkeypatch, residual,
                                                                  bisected):
    """The solver's answer is kept when |g| < 10^-dps (documented check), else the bisection
    runs. Anderson is replaced by a point placed next to the first root of lambda^2 = 1 (found
    here at 80 digits from g of the docstring) so that g = residual * 10^-30 there (first order
    in the offset, whose second-order term is ~1e-60), with dps = 30."""
    with mpmath.workdps(80):
        g = _irvine_g(mpmath.mpf(1))
        root = _FINDROOT(g, (mpmath.pi / 2, 3 * mpmath.pi / 2), solver="anderson")
        point = root + residual * mpmath.mpf("1e-30") / mpmath.diff(g, root)
        assert abs(g(point) / mpmath.mpf("1e-30") - residual) < 1e-20
    calls = []

    def placed_anderson(f, x0, solver, **kw):
        calls.append(solver)
        return +point if solver == "anderson" else _FINDROOT(f, x0, solver=solver, **kw)

    monkeypatch.setattr(mpmath, "findroot", placed_anderson)
    (Omega,) = irvine_symmetric_roots_mp(1, 1, dps=30)
    assert calls == (["anderson", "bisect"] if bisected else ["anderson"])
    with mpmath.workdps(80):
        # the kept point is returned (rounded to 30 digits); the bisection's is the root
        expected = 2 * root if bisected else 2 * point
        assert abs(Omega - expected) < mpmath.mpf("1e-29")
        assert abs(float(Omega) - 3.267886) < 5e-7           # theory.md §9.1


def test_irvine_roots_mp_keep_a_converged_branch_start(monkeypatch):
    """lambda^2 = 1e-55 at dps = 50: the first root lies 4 lambda^2 / pi^3 = 1.3e-56 above
    pi, so the branch start psi = pi/2 is the root to 50 digits (|g| ~ lambda^2 / (4 psi^3) =
    6.5e-57 < 10^-50) and an Anderson answer exactly there is kept: no bisection."""
    calls = []

    def anderson_at_branch_start(f, x0, solver, **kw):
        calls.append(solver)
        return x0[0] if solver == "anderson" else _FINDROOT(f, x0, solver=solver, **kw)

    monkeypatch.setattr(mpmath, "findroot", anderson_at_branch_start)
    (Omega,) = irvine_symmetric_roots_mp("1e-55", 1, dps=50)
    assert calls == ["anderson"]
    with mpmath.workdps(60):
        assert abs(Omega - mpmath.pi) < mpmath.mpf("1e-50")


@pytest.mark.parametrize("lambda_sq", [1e-6, 1e-3, 0.1692, 1.0, 10.0, 4 * np.pi**2, 39.5,
                                       100.0, 16 * np.pi**2, 1e3, 1e4, 1e6])
def test_irvine_roots_float64_match_mp(lambda_sq):
    ref = np.array([float(r) for r in irvine_symmetric_roots_mp(lambda_sq, 8)])
    got = irvine_symmetric_roots(lambda_sq, 8)
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=0)


# --------------------------------------------------------------------------- the reference
ARGS = (10.0, 300.0, 0.064, 0.0, 1.39e5, 10.01, 0.565)      # L, T, m, c, EA, L_e, q
ARGS_DAMPED = (10.0, 300.0, 0.064, 0.3, 1.39e5 * (1 + 0.02j), 10.01, 0.565)
S = np.sqrt(300.0 / 0.064) / 10.0                          # omega = Omega * S


@pytest.mark.parametrize("args", [ARGS, ARGS_DAMPED], ids=["undamped", "damped"])
@pytest.mark.parametrize("Omega", [1e-30, 1e-6, 1.0, np.pi * (1 + 1e-12), 2 * np.pi * (1 - 1e-14),
                                   8.986818916, 33.3])
def test_reference_is_converged_symmetric_and_consistent(args, Omega):
    """dps = 50 agrees with dps = 100 to 50 digits, also where the naive forms cancel
    (psi -> 0, Omega -> (2k+1) pi); K is (complex-)symmetric; the one-end matrix is the B
    block of the two-end one."""
    omega = Omega * S
    lo = two_end_stiffness_mp(*args, omega, dps=50, as_mpmath=True)
    hi = two_end_stiffness_mp(*args, omega, dps=100, as_mpmath=True)
    with mpmath.workdps(110):
        rel = max(abs(lo[i, j] - hi[i, j]) / abs(hi[i, j])
                  for i in range(6) for j in range(6) if hi[i, j] != 0)
    assert rel < mpmath.mpf("1e-48")
    K6 = two_end_stiffness_mp(*args, omega)
    K3 = end_stiffness_mp(*args, omega)
    assert np.array_equal(K6, K6.T)
    assert np.array_equal(K3, K6[3:, 3:])
    assert np.all(K6[np.ix_([0, 1, 3, 4], [2, 5])] == 0)


def test_reference_static_limit():
    """theory.md §3.6: K_B(0) = diag(K0 / (1 + lambda^2/12), T/L, T/L), reached continuously."""
    L, T, m, c, EA, L_e, q = ARGS
    lam2 = (q * L / T) ** 2 * L * EA / (T * L_e)
    expected = np.diag([EA / L_e / (1 + lam2 / 12), T / L, T / L])
    K = end_stiffness_mp(*ARGS, 0.0)
    np.testing.assert_allclose(K.real, expected, rtol=1e-15, atol=0)
    # at Omega = 1e-6 the correction is O(Omega^2) = 1e-12 relative (O(Omega) with viscous c)
    np.testing.assert_allclose(end_stiffness_mp(*ARGS, 1e-6 * S).real, expected,
                               rtol=1e-11, atol=1e-11 * T / L)
    Kd = end_stiffness_mp(*ARGS_DAMPED, 1e-9 * S)
    np.testing.assert_allclose(Kd, end_stiffness_mp(*ARGS_DAMPED, 0.0), rtol=1e-8,
                               atol=1e-7 * T / L)   # K_uv(0) = 0; here |K_uv| = 7e-9 N/m


def test_reference_two_end_static_limit():
    """theory.md §3.6 at omega = 0: K0 / (1 + lambda^2/12) [[1, -1], [-1, 1]] on (u_A, u_B)
    (g = [1, alpha tau, -1, alpha tau] with tau = 0), the string T/L [[1, -1], [-1, 1]] on
    (v_A, v_B) and on (w_A, w_B), no chordwise mass, nothing else."""
    L, T, m, c, EA, L_e, q = ARGS
    lam2 = (q * L / T) ** 2 * L * EA / (T * L_e)
    axial, string = EA / L_e / (1 + lam2 / 12), T / L
    expected = np.zeros((6, 6))
    for (a, b), k in (((0, 3), axial), ((1, 4), string), ((2, 5), string)):
        expected[np.ix_([a, b], [a, b])] = [[k, -k], [-k, k]]
    K = two_end_stiffness_mp(*ARGS, 0.0)
    np.testing.assert_allclose(K.real, expected, rtol=1e-15, atol=0)
    assert np.all(K.imag == 0)


@pytest.mark.parametrize("args", [ARGS, ARGS_DAMPED], ids=["undamped", "damped"])
def test_reference_at_a_vanishing_frequency(args):
    """Omega = 1e-200: tau = 1 - tan(psi)/psi ~ -psi^2/3 cancels ~400 digits, which the
    working precision (under the 4000-digit limit) covers; K_B is the static limit
    diag(K0 / (1 + lambda^2/12), T/L, T/L) of theory.md §3.6 (complex K0 and lambda^2 with
    hysteretic damping), the corrections being O(Omega) <= 1e-200 relative."""
    L, T, m, c, EA, L_e, q = args
    lam2 = (q * L / T) ** 2 * L * EA / (T * L_e)
    expected = np.diag([EA / L_e / (1 + lam2 / 12), T / L, T / L])
    K = end_stiffness_mp(*args, 1e-200 * S)
    np.testing.assert_allclose(K, expected, rtol=1e-15, atol=1e-150 * T / L)


def test_reference_of_a_massless_chord_with_viscous_damping():
    """m = 0, c = 0.3 N s/m^2: beta^2 = -i omega c / T, so psi^2 = -i omega c L^2 / (4 T)
    = -1e-80 i at omega = 4e-79 rad/s, and tau = 1 - tan(psi)/psi ~ -psi^2/3 cancels ~80
    digits (with m = 0 the precision is not raised for psi beforehand). K_B is the static limit
    diag(K0 / (1 + lambda^2/12), T/L, T/L) up to O(|psi|^2) = 1e-80 relative, plus the
    chordwise term -omega^2 m~ L/3 = i omega c L/3 = 4e-79 i N/m on K_uu."""
    L, T, m, c, EA, L_e, q = 10.0, 300.0, 0.0, 0.3, 1.39e5, 10.01, 0.565
    omega = 4e-79
    lam2 = (q * L / T) ** 2 * L * EA / (T * L_e)
    expected = np.diag([EA / L_e / (1 + lam2 / 12) + 1j * omega * c * L / 3, T / L, T / L])
    K = end_stiffness_mp(L, T, m, c, EA, L_e, q, omega)
    np.testing.assert_allclose(K, expected, rtol=1e-15, atol=1e-60 * T / L)


def test_reference_chordwise_stiffness_cancelling_31_digits():
    """q = 0 (lambda^2 = 0, D = 1) and dyadic inputs L = m = 1, L_e = 3, EA = 1 + 2^-51,
    omega = 1 + 2^-52: K_uu = EA / L_e - omega^2 m L / 3 = ((1 + 2^-51) - (1 + 2^-52)^2) / 3
    = -2^-104 / 3 exactly, its two terms cancelling 31 digits. The mpmath matrix
    (as_mpmath=True) holds it to dps = 50 digits, and k_s = T beta cot(beta L) with
    beta = omega sqrt(m / T) (K_ww) as well; K_uv = 0 (alpha = 0)."""
    L, T, m, EA, L_e, omega = 1.0, 300.0, 1.0, 1 + 2.0**-51, 3.0, 1 + 2.0**-52
    K = end_stiffness_mp(L, T, m, 0.0, EA, L_e, 0.0, omega, dps=50, as_mpmath=True)
    assert isinstance(K, mpmath.matrix) and (K.rows, K.cols) == (3, 3)
    with mpmath.workdps(120):
        K_uu = -mpmath.mpf(2) ** -104 / 3
        assert abs(K[0, 0] - K_uu) < mpmath.mpf("1e-48") * abs(K_uu)
        beta = mpmath.mpf(omega) * mpmath.sqrt(mpmath.mpf(m) / T)
        k_s = T * beta * mpmath.cot(beta * L)
        assert abs(K[2, 2] - k_s) < mpmath.mpf("1e-48") * abs(k_s)
        assert K[0, 1] == 0 and K[1, 0] == 0


def test_reference_chordwise_coupling_cancelling_21_digits():
    """K_uAuB = -K0/D - omega^2 m L / 6 (theory.md §3.2-3.3) vanishes where D < 0, between
    the string pole Omega = pi and the first symmetric root (Omega_1 = 3.1627 here): with
    K0/D = EA / (L_e (1 - EA kappa s)), kappa = (q L / T)^2 L / (T L_e) and
    s = tau / (4 psi^2), the zero is at EA = a L_e / (1 + a L_e kappa s), a = -omega^2 m L / 6.
    At omega = 21.509528057423708 rad/s (Omega = pi (1 + 2.4e-5)) the float nearest that EA
    makes the two terms cancel 21 digits (checked here). The reference's entry (as_mpmath,
    dps = 50) matches those forms evaluated here with 200 digits to 48 digits."""
    L, T, m, L_e, q, omega = 10.0, 300.0, 0.064, 10.01, 0.565, 21.509528057423708
    with mpmath.workdps(200):
        L_, T_, m_, L_e_, q_, w = (mpmath.mpf(v) for v in (L, T, m, L_e, q, omega))
        psi = w * mpmath.sqrt(m_ / T_) * L_ / 2
        s = (1 - mpmath.tan(psi) / psi) / (4 * psi**2)
        kappa = (q_ * L_ / T_) ** 2 * L_ / (T_ * L_e_)
        a = -w**2 * m_ * L_ / 6
        EA = float(a * L_e_ / (1 + a * L_e_ * kappa * s))
        K_uAuB = -EA / (L_e_ * (1 - EA * kappa * s)) + a
        assert abs(K_uAuB) < mpmath.mpf("1e-20") * abs(a)
    K = two_end_stiffness_mp(L, T, m, 0.0, EA, L_e, q, omega, dps=50, as_mpmath=True)
    with mpmath.workdps(200):
        assert abs(K[0, 3] - K_uAuB) < mpmath.mpf("1e-48") * abs(K_uAuB)
        assert K[3, 0] == K[0, 3]


def test_reference_small_frequency_string_series():
    """theory.md §3.5: k_s = T/L - m omega^2 L/3 + O(omega^4), k_c = -T/L - m omega^2 L/6."""
    L, T, m = ARGS[:3]
    omega = 1e-3 * S                                      # Omega = 1e-3
    K = two_end_stiffness_mp(*ARGS, omega)
    k_s, k_c = K[2, 2].real, K[2, 5].real
    # next terms are O(Omega^4) T/L = 1e-12 T/L
    assert abs(k_s - (T / L - m * omega**2 * L / 3)) < 1e-11 * T / L
    assert abs(k_c - (-T / L - m * omega**2 * L / 6)) < 1e-11 * T / L


def test_params_to_mp_args_round_trip():
    p = V.chord_params_for(10.0, "loss_factor")
    args = params_to_mp_args(p)
    assert args == (p.L, p.T, p.m, p.c, complex(p.EA), p.L_e, p.q)
    assert isinstance(params_to_mp_args(V.chord_params_for(10.0))[4], float)


@pytest.mark.integration
def test_dynstiff_does_not_import_mpmath_reference():
    code = "import sys, dynstiff; print('dynstiff.cable.mpmath_reference' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=Path(__file__).resolve().parents[1], check=True)
    assert out.stdout.strip() == "False"


# --------------------------------------------------------------------------- float64 vs mp
@pytest.fixture(scope="module")
def grid():
    return V.run(quick=True)


def test_grid_covers_the_cases(grid):
    assert set(grid.damping) == {"undamped", "loss_factor", "viscous"}
    assert grid.near_pole.sum() >= 100 and grid.away.sum() >= 250
    assert grid.lambda_sq.min() <= 1e-6 and grid.lambda_sq.max() >= 1e4


def test_float64_matches_mp_away_from_poles(grid):
    """Required: <= 1e-9 entry-wise where the nearest pole is > 1e-6 away (relative).

    Measured (quick grid): 3.4e-14 entry-wise, 3.1e-14 Frobenius; full grid 1.8e-13. The
    worst samples sit 1e-3..1e-2 from a pole, i.e. they are still eps / distance.
    """
    away = grid[grid.away]
    assert away.err_entry.max() <= 1e-9
    assert away.err_entry.max() <= 1e-12          # regression guard, 30x the measured value
    assert away.err_norm.max() <= 1e-12


def test_float64_near_poles_is_pole_conditioning(grid):
    """Within 1e-8 of a pole the relative error is the pole's conditioning, not a defect.

    psi = (L/2) sqrt(omega^2 m / T) is rounded to ~1 ulp in float64 (while the reference uses
    the exact float omega), and an entry ~ 1/(Omega - Omega_p) then has relative error
    ~ eps / dist. Measured: err_entry * dist / eps <= 2.04 on the full grid (1.9 quick), max
    err_entry 5.6e-8 at dist = 1e-8 (4.2e-8 quick). Asserted with a margin of 5.
    """
    close = grid[grid.pole_dist < 1e-3]
    assert (close.err_entry * close.pole_dist / EPS).max() <= 10.0
    near = grid[grid.near_pole]
    assert near.err_entry.max() <= 5e-7
    assert near.err_norm.max() <= 5e-7


def test_float64_matches_mp_damped(grid):
    """Damped cases away from the undamped poles: <= 1e-9 required, 3.4e-14 measured.

    Viscous damping (zeta_1 = 1 %) moves every pole off the real axis, so even the samples
    at 1e-8 of an undamped pole are well conditioned (measured 1.7e-13 quick, 3.9e-13 full).
    Hysteretic damping leaves the string poles n pi, 2 n pi real: there the near-pole bound
    of the undamped case applies.
    """
    damped = grid[grid.damping != "undamped"]
    assert damped[damped.away].err_entry.max() <= 1e-9
    assert damped[damped.away].err_entry.max() <= 1e-12
    viscous = grid[grid.damping == "viscous"]
    assert viscous.err_entry.max() <= 1e-11


SERIES_OMEGAS = [1e-6, 1e-3, 0.5, 1.99, 2.01]


@pytest.mark.parametrize("damping", ["undamped", "loss_factor", "viscous"])
@pytest.mark.parametrize("lambda_sq", [1e-6, 1.0, 4 * np.pi**2, 100.0, 1e4])
@pytest.mark.parametrize("chordwise_inertia", [True, False])
def test_small_omega_series_branch_matches_mp(damping, lambda_sq, chordwise_inertia):
    """float64 uses a Taylor series for |psi| < 1 (Omega < 2) and the direct stable form
    above: both sides of the switch agree with the reference to 1e-12 (measured 2.8e-15)."""
    p = V.chord_params_for(lambda_sq, damping)
    args = params_to_mp_args(p)
    Omega = np.array(SERIES_OMEGAS)
    omega = Omega / (p.L * np.sqrt(p.m / p.T))
    K3 = local_end_stiffness(p, omega, chordwise_inertia)
    K6 = local_two_end_stiffness(p, omega, chordwise_inertia)
    for k in range(omega.size):
        K3mp = end_stiffness_mp(*args, float(omega[k]), chordwise_inertia)
        K6mp = two_end_stiffness_mp(*args, float(omega[k]), chordwise_inertia)
        e3, _, w3 = V._entry_errors(K3[k], K3mp, V._END_NAMES)
        e6, _, w6 = V._entry_errors(K6[k], K6mp, V._TWO_NAMES)
        assert e3 <= 1e-12, (Omega[k], w3, e3)
        assert e6 <= 1e-12, (Omega[k], w6, e6)


def test_float64_and_reference_agree_on_chord_parameters():
    """Same ChordParameters both ways: a hand-built cable (CoGiRo-like, theory.md §9.2)."""
    p = ChordParameters(L=10.1346, T=300.0, m=0.064, c=0.0, EA=8.2051e-6 * 17e9,
                        q=0.064 * 9.81 * 0.9013, L_e=10.1346 * 1.0005, cos_theta=0.9013,
                        rotation=np.eye(3))
    omega = 2 * np.pi * np.array([0.5, 2.0, 5.0, 8.0])           # [rad/s]
    K = local_end_stiffness(p, omega)
    for k in range(omega.size):
        Kmp = end_stiffness_mp(*params_to_mp_args(p), float(omega[k]))
        np.testing.assert_allclose(K[k], Kmp.real, rtol=1e-13, atol=0)
        assert np.all(Kmp.imag == 0)
