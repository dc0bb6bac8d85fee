"""Solving one elastic catenary (dynstiff/cable/catenary_solve.py, theory.md §1.1): forward solves
from the ends and the unstretched length, the unstretched length for a tension, hard cases."""

import numpy as np
import pytest
from conftest import A0, B0, cogiro_cable
from scipy.integrate import quad
from scipy.optimize import fsolve

import dynstiff as ds
from dynstiff.errors import InvalidParameterError, SlackCableError

G = ds.STANDARD_GRAVITY

# (anchor, end, L0 / chord) cases: taut, slack, steep, near-vertical, rising, horizontal
CASES = [
    ("taut CoGiRo", A0, B0, 0.998),
    ("slack", (0, 0, 5), (7, 0, 0), 1.15),
    ("very slack", (0, 0, 0), (10, 0, 0), 1.3),
    ("steep", (0, 0, 10), (0.5, 0, 0), 1.0),
    ("near vertical", (0, 0, 10), (1e-4, 0, 0), 0.999),
    ("rising", (0, 0, 0), (3, 2, 6), 0.9995),
    ("horizontal taut", (0, 0, 0), (10, 0, 0), 0.9999),
]


def quadrature_solution(A, B, L0, cable, g=G):
    """Independent solution: integrate dx/ds = (H/T)(1 + T/EA), dz/ds = (V/T)(1 + T/EA)
    by adaptive quadrature and shoot on (H, Vb) with fsolve. Returns the force on B."""
    d = np.asarray(B, float) - np.asarray(A, float)
    lh, h = np.hypot(d[0], d[1]), d[2]
    w0, EA = cable.mass_per_length * g, cable.EA

    def ends(x):
        H, Vb = x
        V = lambda s: Vb - w0 * (L0 - s)
        T = lambda s: np.hypot(H, V(s))
        xe = quad(lambda s: H / T(s) * (1 + T(s) / EA), 0, L0, epsabs=0, epsrel=1e-13, limit=200)[0]
        ze = quad(lambda s: V(s) / T(s) * (1 + T(s) / EA), 0, L0, epsabs=1e-14 * L0,
                  epsrel=1e-13, limit=200)[0]    # z_B may be ~0: absolute floor
        return [xe / lh - 1.0, (ze - h) / L0]

    s0 = ds.solve_catenary(A, B, L0, cable, g)      # start nearby, converge independently
    (H, Vb), info, *_ = fsolve(ends, [s0.H * 1.01, s0.Vb * 0.99 + 0.01 * s0.H], xtol=1e-12,
                               full_output=True)
    assert np.max(np.abs(info["fvec"])) < 1e-11      # the reference itself converged
    e_h = np.array([d[0], d[1], 0.0]) / lh
    return -(H * e_h + Vb * np.array([0, 0, 1.0]))


# MoorPy treats the near-vertical chord (l_h = 1e-4 m) as exactly vertical (H = 0, V off by
# 5e-8); the quadrature test above confirms H = 1.4e-3 N = lateral stiffness * l_h there.
MOORPY_CASES = [c for c in CASES if c[0] != "near vertical"]


@pytest.mark.parametrize("name,A,B,ratio", CASES, ids=[c[0] for c in CASES])
def test_matches_independent_quadrature_solution(name, A, B, ratio):
    cable = cogiro_cable(17e9)
    L0 = ratio * np.linalg.norm(np.subtract(B, A))
    s = ds.solve_catenary(A, B, L0, cable)
    assert s.residual <= 1e-12
    f_ref = quadrature_solution(A, B, L0, cable)
    np.testing.assert_allclose(s.force_on_end, f_ref, rtol=1e-8, atol=1e-8 * np.linalg.norm(f_ref))


@pytest.mark.parametrize("name,A,B,ratio", MOORPY_CASES, ids=[c[0] for c in MOORPY_CASES])
def test_matches_moorpy(name, A, B, ratio):
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    cable = cogiro_cable(17e9)
    L0 = ratio * np.linalg.norm(np.subtract(B, A))
    s = ds.solve_catenary(A, B, L0, cable)
    d = np.subtract(B, A)
    lh = np.hypot(d[0], d[1])
    fAH, fAV, fBH, fBV, info = catenary(lh, d[2], L0, cable.EA, cable.mass_per_length * G,
                                        CB=-1e3, Tol=1e-12, MaxIter=500)
    # MoorPy: (fAH, fAV) force on A, (fBH, fBV) force on B in its plane
    np.testing.assert_allclose([s.H, s.V0, -s.Vb], [fAH, fAV, fBV], rtol=1e-8)
    K = s.end_stiffness
    if True:
        e_h = s.horizontal_direction
    K2 = np.array([[e_h @ K @ e_h, e_h @ K[:, 2]], [K[2] @ e_h, K[2, 2]]])
    np.testing.assert_allclose(K2, info["stiffnessB"], rtol=1e-7,
                               atol=1e-9 * np.abs(info["stiffnessB"]).max())


def test_theory_example_tension():
    # theory.md §1.1: 7 m horizontal, 5 m drop, L0 = 8.5 m, m = 0.064, EA = 1.39e5: T ~ 1680 N
    s = ds.solve_catenary((0, 0, 5), (7, 0, 0), 8.5, ds.Cable(0.064, 1.39e5))
    assert s.tension_at_end == pytest.approx(1680, rel=0.01)


def test_mirror_symmetry():
    cable = cogiro_cable(120e9)
    A, B = np.array([3.0, 1.0, 5.0]), np.array([-2.0, 0.5, 1.0])
    M = np.diag([-1.0, 1.0, 1.0])
    L0 = 1.0005 * np.linalg.norm(B - A)
    s1 = ds.solve_catenary(A, B, L0, cable)
    s2 = ds.solve_catenary(M @ A, M @ B, L0, cable)
    np.testing.assert_allclose(s2.force_on_end, M @ s1.force_on_end, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(s2.end_stiffness, M @ s1.end_stiffness @ M, rtol=1e-10,
                               atol=1e-9)


@pytest.mark.parametrize("at", ["end", "anchor"])
def test_unstretched_length_for_tension_round_trip(at, cable17):
    s = ds.unstretched_length_for_tension(A0, B0, 437.0, cable17, at=at)
    T = s.tension_at_end if at == "end" else s.tension_at_anchor
    assert T == pytest.approx(437.0, rel=1e-12)
    s2 = ds.solve_catenary(A0, B0, s.unstretched_length, cable17)
    assert s2.H == pytest.approx(s.H, rel=1e-12)


@pytest.mark.parametrize("strain", [0.3, 2.0, 3.0])
def test_unstretched_length_for_tension_at_any_strain(strain):
    """The elastic catenary is linear-elastic at every strain: a target of 2 EA and above
    (bracket starts that a formula in 1 - T/EA would break) is found as well as 0.3 EA."""
    cable = ds.Cable(mass_per_length=0.064, EA=1.64e3)
    s = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], strain * cable.EA, cable)
    assert s.tension_at_end == pytest.approx(strain * cable.EA, rel=1e-12)
    # nearly straight: the chord is about L0 (1 + strain)
    assert s.unstretched_length * (1 + strain) == pytest.approx(5.0, rel=0.02)


def test_unreachable_tension_raises(cable17):
    with pytest.raises(SlackCableError, match="tension"):
        ds.unstretched_length_for_tension(A0, B0, 0.3, cable17)


def test_slack_vertical_cable_raises(cable17):
    with pytest.raises(SlackCableError, match="slack"):
        ds.solve_catenary((0, 0, 10), (0, 0, 0), 12.0, cable17)


@pytest.mark.parametrize("up", [True, False])
def test_vertical_cable_is_taut_exactly_beyond_its_stretched_length(up):
    """An exactly vertical cable is straight: |h| = L0 (1 + (T_low + W/2) / EA) with T_low
    its lowest tension (theory.md §1.1). Just beyond |h|_0 = L0 (1 + W / (2 EA)) it is taut,
    with T_low = EA (|h| / L0 - 1) - W/2 and T_high = T_low + W; just short of it, slack,
    and the error names the rise or drop."""
    cable = ds.Cable(0.5, 2e4)
    L0, W = 10.0, 0.5 * 9.81 * 10.0
    h0 = L0 * (1 + W / (2 * cable.EA))
    sign = 1.0 if up else -1.0
    h = h0 * (1 + 1e-6)
    st = ds.solve_catenary((0, 0, 0), (0, 0, sign * h), L0, cable)
    t_low = cable.EA * (h / L0 - 1) - W / 2
    lower, upper = (st.tension_at_anchor, st.tension_at_end) if up else \
        (st.tension_at_end, st.tension_at_anchor)
    assert st.H == 0.0
    assert lower == pytest.approx(t_low, rel=1e-9) and upper == pytest.approx(t_low + W, 1e-12)
    word = "rise" if up else "drop"
    with pytest.raises(SlackCableError, match=f"{word} {h0 * (1 - 1e-6)!r} m is not larger"):
        ds.solve_catenary((0, 0, 0), (0, 0, sign * h0 * (1 - 1e-6)), L0, cable)
    # a short rising cable (|h| < 1 m) on the same law
    st = ds.solve_catenary((0, 0, 0), (0, 0, sign * 0.5), 0.45, cable)
    t_low = cable.EA * (0.5 / 0.45 - 1) - 0.5 * 9.81 * 0.45 / 2
    assert min(st.tension_at_anchor, st.tension_at_end) == pytest.approx(t_low, rel=1e-12)


@pytest.mark.parametrize("args,name", [
    (((0, 0, 0), (0, 0, 0), 1.0), "anchor and end"),
    (((0, 0, 0), (1, 0, 0), 0.0), "unstretched_length"),
    (((0, 0, 0), (1, 0, 0), -2.0), "unstretched_length"),
    (((0, 0, 0), (1, 0, 0), float("nan")), "unstretched_length"),
    (((0, 0, float("nan")), (1, 0, 0), 1.0), "anchor"),
    (((0, 0, 0), (1, 0, float("inf")), 1.0), "end"),
    (((0, 0), (1, 0, 0), 1.0), "anchor"),
])
def test_bad_statics_input_raises_naming_argument(args, name, cable17):
    with pytest.raises(InvalidParameterError, match=name):
        ds.solve_catenary(*args, cable17)


def test_bad_gravity_and_profile_count(cable17):
    with pytest.raises(InvalidParameterError, match="g must"):
        ds.solve_catenary((0, 0, 0), (1, 0, 0), 1.0, cable17, g=-9.81)
    s = ds.solve_catenary((0, 0, 1), (1, 0, 0), 1.4, cable17)
    with pytest.raises(InvalidParameterError, match="n must"):
        s.profile(1)


def test_bad_iteration_counts_and_absurd_coordinates_name_the_argument(cable17):
    with pytest.raises(InvalidParameterError, match="max_iter must be an integer >= 1"):
        ds.solve_catenary([0, 0, 0], [10, 0, 2], 10.3, cable17, max_iter=0)
    with pytest.raises(InvalidParameterError, match="within 1e\\+100 m of the origin"):
        ds.solve_catenary([0, 0, 0], [1e300, 0, 2], 10.3, cable17)


def test_a_slack_cable_in_a_u_is_not_reported_as_a_taut_string():
    """solve_catenary([0,0,0], [1e-6,0,10], 10.1, ...) hangs in a U below A: the distance from
    the chord *segment* is its true sag (the U reaches |V0|/w = 5 cm below A), and lambda^2 is
    then written with the measured sag (theory.md §11.5); a taut cable keeps the chord theory's
    lambda^2 and its sag is the profile's largest distance from the line."""
    s = ds.solve_catenary([0, 0, 0], [1e-6, 0, 10], 10.1, ds.Cable(0.064, 1.4e5))
    w0 = s.cable.weight_per_length(s.g)
    drop = -s.V0 / w0                                  # arc length from A down to the bottom
    assert s.sag == pytest.approx(drop, rel=2e-2) and s.sag > 0.04
    assert s.lambda_sq > 50                            # not a taut string (was 2e-9)
    taut = ds.solve_catenary(A0, B0, 1.0001 * np.linalg.norm(np.subtract(B0, A0)), cogiro_cable())
    from dynstiff.cable.chord import chord_parameters
    assert taut.lambda_sq == chord_parameters(taut).lambda_sq
    p = taut.profile(401) - taut.anchor
    e = taut.chord / taut.chord_length
    line = np.max(np.linalg.norm(p - np.outer(p @ e, e), axis=1))
    assert line <= taut.sag <= line * (1 + 1e-5)      # the profile's 401 points fall short
    from dynstiff.cable.catenary_batch import catenary_arrays, sag_ratios
    exact = sag_ratios(np.array([taut.anchor]), np.array([taut.end]),
                       *catenary_arrays([taut]), np.array([taut.cable.EA]),
                       np.array([taut.cable.weight_per_length(taut.g)]))[0]
    assert taut.sag == pytest.approx(exact * taut.chord_length, rel=1e-12)


def test_a_heavy_vertical_cable_is_found_for_a_tension_below_its_weight():
    """A 0.5 kg/m cable (EA 2e4 N) hanging 4 m straight down to B, 5 N at B: its weight
    (about 19.6 N) exceeds the tension asked, so the first lengths tried are slack (a
    negative tension at B). The length is L = L0 + (T_B L0 + w0 L0^2 / 2) / EA, and the
    anchor carries T_B + w0 L0. Rising 4 m from the anchor, a tension at B below the
    cable's weight cannot be reached and is refused."""
    cab = ds.Cable(0.5, 2e4)
    w0, EA, L, T = 0.5 * 9.81, 2e4, 4.0, 5.0
    s = ds.unstretched_length_for_tension([0, 0, 5.0], [0, 0, 1.0], T, cab)
    a, b = w0 / (2 * EA), 1.0 + T / EA
    L0 = 2 * L / (b + np.sqrt(b * b + 4 * a * L))
    assert s.unstretched_length == pytest.approx(L0, rel=1e-13)
    assert s.tension_at_end == pytest.approx(T, rel=1e-12)
    assert s.tension_at_anchor == pytest.approx(T + w0 * L0, rel=1e-12)
    with pytest.raises(SlackCableError, match="5.0 N at the end is not reachable"):
        ds.unstretched_length_for_tension([0, 0, 0], [0, 0, 4.0], T, cab)
    # a short, very heavy one (50 kg/m over 0.5 m): the taut end of the bracket shrinks too
    cab, L = ds.Cable(50.0, 2e4), 0.5
    s = ds.unstretched_length_for_tension([0, 0, 5.0], [0, 0, 5.0 - L], T, cab)
    a, b = 50.0 * 9.81 / (2 * EA), 1.0 + T / EA
    assert s.unstretched_length == pytest.approx(2 * L / (b + np.sqrt(b * b + 4 * a * L)),
                                                 rel=1e-13)


def test_coincident_ends_are_judged_relative_to_their_coordinates():
    """Ends 5e-11 m apart 100 m from the origin are one point to rounding (1e-12 of the
    coordinates): refused, naming both."""
    with pytest.raises(InvalidParameterError, match="^anchor and end must be distinct points"):
        ds.solve_catenary([100.0, 0, 0], [100.0 + 5e-11, 0, 0], 1.0, ds.Cable(1.0, 1e6))


G = ds.STANDARD_GRAVITY

# (anchor, end, L0 / chord) cases: taut, slack, steep, near-vertical, rising, horizontal
CASES = [
    ("taut CoGiRo", A0, B0, 0.998),
    ("slack", (0, 0, 5), (7, 0, 0), 1.15),
    ("very slack", (0, 0, 0), (10, 0, 0), 1.3),
    ("steep", (0, 0, 10), (0.5, 0, 0), 1.0),
    ("near vertical", (0, 0, 10), (1e-4, 0, 0), 0.999),
    ("rising", (0, 0, 0), (3, 2, 6), 0.9995),
    ("horizontal taut", (0, 0, 0), (10, 0, 0), 0.9999),
]


def test_long_spans_converge_and_limits_are_exact():
    """2 km spans (1 kg/m, EA 1e8 N) converge to the relative residual 1e-12 of the smaller
    spans, and the residual reported is that relative one, max |offset error| / (l_h, max(L,
    L0)), not metres. A weightless cable exactly
    as long as its chord has no tension: slack, refused. A negative tension is named."""
    from dynstiff.cable.catenary import end_offsets_and_flexibility
    cab = ds.Cable(1.0, 1e8)
    for L0 in (2001.0, 2019.0, 2100.0):
        s = ds.solve_catenary((0, 0, 0), (2000.0, 0, 100.0), L0, cab)
        xz = end_offsets_and_flexibility(s.H, s.V0, L0, cab.EA, cab.weight_per_length(s.g))[0]
        rel = np.max(np.abs(xz - [2000.0, 100.0]) / [2000.0, L0])
        assert s.residual == pytest.approx(rel, rel=1e-12, abs=0) and s.residual < 1e-12
    with pytest.raises(SlackCableError, match="weightless cable is slack"):
        ds.solve_catenary((0, 0, 0), (3.0, 0, 4.0), 5.0, ds.Cable(1.0, 1e6), g=0.0)
    with pytest.raises(InvalidParameterError, match="^tension must be"):
        ds.unstretched_length_for_tension((0, 0, 0), (3.0, 0, 4.0), -5.0, ds.Cable(1.0, 1e6))




@pytest.mark.parametrize("EA", [1.0, 1e-3, 1e-300])
def test_a_very_soft_cable_reaches_its_tension_with_the_weightless_length(EA):
    """A cable far softer than its tension (T / EA from 300 to 3e302) hangs straight, its
    weight negligible: L0 = L / (1 + T / EA) (Hooke along the chord), and the tension at B
    is the one asked to 1e-9 (at EA = 1e-300 the step tolerance, absolute on the chord's
    scale, stopped at a bracket end: 600 N for 300)."""
    T, L = 300.0, 5.0
    st = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], T, ds.Cable(0.064, EA))
    assert st.tension_at_end == pytest.approx(T, rel=1e-9)
    assert st.unstretched_length == pytest.approx(L / (1 + T / EA), rel=1e-4)


def test_a_strain_beyond_the_float_range_is_refused_naming_the_tension():
    """EA = 7.9e-308 N (found by the scene-file fuzzer): T / EA overflows and no unstretched
    length above 0 gives the tension; the error names the tension, the strain and EA (it
    was 'unstretched_length must be > 0, got 0.0', a value the caller never gave)."""
    with pytest.raises(ds.InvalidParameterError,
                       match=r"^tension 300\.0 N at the end: its strain tension / EA = inf "
                             r"\(EA 7\.9e-308 N\) leaves no unstretched length above 0"):
        ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0,
                                          ds.Cable(0.064, 7.9e-308))


def test_a_root_that_misses_the_tension_is_refused_with_its_residual(monkeypatch):
    """A planted root finder that returns its bracket's short end: the tension there is
    above the target, and the solver says so with the relative residual, never returning
    that state."""
    import scipy.optimize
    monkeypatch.setattr(scipy.optimize, "brentq", lambda f, a, b, **kw: a)
    with pytest.raises(ds.ConvergenceError, match=r"^unstretched length for tension 300\.0 N "
                       r"at the end: the tension found is .* N \(relative residual") as err:
        ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0,
                                          ds.Cable(0.064, 1.64e6))
    assert err.value.residual > 1e-9


def _sagging_root(T=100.0, w=1.0 * G, L=10.0):
    """The taut root of an inextensible catenary between two points 10 m apart at one
    height with end tension T: H cosh(w L / 2H) = T on the branch of large H, its length
    S = (2H / w) sinh(w L / 2H) [m]."""
    from scipy.optimize import brentq
    H = brentq(lambda H: H * np.cosh(w * L / (2 * H)) - T, 41.0, 10 * T)
    return 2 * H / w * np.sinh(w * L / (2 * H))


def test_a_sagging_root_beyond_the_chord_is_bracketed_by_growing_the_length():
    """1 kg/m over a 10 m level span at 100 N: the root lies beyond the chord (L0 = 10.556
    m), so the lower bracket, started at L / (1 + T / 2EA) where the tension is too high,
    grows to it. The root is the inextensible catenary's length over 1 + T / EA (to 1e-5,
    the mean tension being below T), the taut one (the tension still falls beyond it)."""
    cable = ds.Cable(1.0, 1e6)
    st = ds.unstretched_length_for_tension([0, 0, 0], [10.0, 0, 0], 100.0, cable)
    assert st.tension_at_end == pytest.approx(100.0, rel=1e-9)
    assert st.unstretched_length == pytest.approx(_sagging_root() / (1 + 100.0 / 1e6),
                                                  rel=1e-5)
    longer = ds.solve_catenary([0, 0, 0], [10.0, 0, 0], st.unstretched_length * (1 + 1e-6),
                               cable)
    assert longer.tension_at_end < 100.0


def test_a_trial_length_whose_catenary_does_not_converge_is_passed_over(monkeypatch):
    """A catenary solve that raises ConvergenceError at the lower bracket's first trial
    length: that length is passed over (the bracket grows past it) and the same root is
    found as without the failure."""
    from dynstiff.cable import catenary_solve
    cable = ds.Cable(1.0, 1e6)
    want = ds.unstretched_length_for_tension([0, 0, 0], [10.0, 0, 0], 100.0, cable)
    first, real = 10.0 / (1.0 + 0.5 * 100.0 / 1e6), catenary_solve.solve_catenary
    failed = []

    def flaky(A, B, L0, *args, **kw):
        if L0 == first:
            failed.append(L0)
            raise ds.ConvergenceError("planted", residual=1.0)
        return real(A, B, L0, *args, **kw)
    monkeypatch.setattr(catenary_solve, "solve_catenary", flaky)
    got = ds.unstretched_length_for_tension([0, 0, 0], [10.0, 0, 0], 100.0, cable)
    assert failed == [first]
    assert got.unstretched_length == pytest.approx(want.unstretched_length, rel=1e-14)
