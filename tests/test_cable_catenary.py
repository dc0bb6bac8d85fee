"""Elastic-catenary statics (theory.md §1.1): independent solutions, symmetry, stiffness."""

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


@pytest.mark.parametrize("name,A,B,ratio", CASES, ids=[c[0] for c in CASES])
def test_matches_independent_quadrature_solution(name, A, B, ratio):
    cable = cogiro_cable(17e9)
    L0 = ratio * np.linalg.norm(np.subtract(B, A))
    s = ds.solve_catenary(A, B, L0, cable)
    assert s.residual <= 1e-12
    f_ref = quadrature_solution(A, B, L0, cable)
    np.testing.assert_allclose(s.force_on_end, f_ref, rtol=1e-8, atol=1e-8 * np.linalg.norm(f_ref))


@pytest.mark.parametrize("name,A,B,ratio", CASES + [
    ("lowest point inside", (0, 0, 0), (10, 0, 0.5), 1.05),
    ("falling to B", (0, 0, 6), (3, 0, 0), 1.001)], ids=lambda c: c if isinstance(c, str) else "")
def test_least_and_largest_tension_along_the_cable(name, A, B, ratio):
    """min_tension / max_tension against T(s) sampled densely along the cable."""
    cable = cogiro_cable(17e9)
    st = ds.solve_catenary(A, B, ratio * np.linalg.norm(np.subtract(B, A)), cable)
    T = st.tension(np.linspace(0.0, st.unstretched_length, 200001))
    assert st.min_tension == pytest.approx(T.min(), rel=1e-9)
    assert st.max_tension == pytest.approx(T.max(), rel=1e-12)
    if name == "lowest point inside":
        assert st.V0 < 0 < st.Vb and st.min_tension == st.H < min(T[0], T[-1])


# MoorPy treats the near-vertical chord (l_h = 1e-4 m) as exactly vertical (H = 0, V off by
# 5e-8); the quadrature test above confirms H = 1.4e-3 N = lateral stiffness * l_h there.
MOORPY_CASES = [c for c in CASES if c[0] != "near vertical"]


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


def test_force_balance_and_profile_ends(state300):
    s = state300
    np.testing.assert_allclose(s.force_on_end + s.force_on_anchor, [0, 0, -s.total_weight],
                               atol=1e-10 * s.tension_at_end)
    prof = s.profile(7)
    np.testing.assert_allclose(prof[0], s.anchor, atol=1e-12)
    np.testing.assert_allclose(prof[-1], s.end, atol=1e-10)
    # tension along the cable: ends agree with the end forces
    assert s.tension(0.0) == pytest.approx(np.linalg.norm(s.force_on_anchor), rel=1e-14)
    assert s.tension(s.unstretched_length) == pytest.approx(np.linalg.norm(s.force_on_end),
                                                            rel=1e-14)


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


@pytest.mark.parametrize("name,A,B,ratio", CASES, ids=[c[0] for c in CASES])
def test_end_stiffness_is_derivative_of_end_force(name, A, B, ratio):
    cable = cogiro_cable(17e9)
    A, B = np.asarray(A, float), np.asarray(B, float)
    L0 = ratio * np.linalg.norm(B - A)
    s = ds.solve_catenary(A, B, L0, cable)
    K = s.end_stiffness
    assert np.allclose(K, K.T)
    assert np.all(np.linalg.eigvalsh(K) > 0)
    h = 1e-7 * np.linalg.norm(B - A)     # central differences, truncation error O(h^2)
    K_fd = np.empty((3, 3))
    for j in range(3):
        dB = np.zeros(3)
        dB[j] = h
        fp = ds.solve_catenary(A, B + dB, L0, cable).force_on_end
        fm = ds.solve_catenary(A, B - dB, L0, cable).force_on_end
        K_fd[:, j] = -(fp - fm) / (2 * h)
    np.testing.assert_allclose(K, K_fd, rtol=1e-5, atol=1e-6 * np.abs(K).max())


def test_vertical_limit_is_continuous():
    cable = cogiro_cable(17e9)
    for A, B in [((0, 0, 10), (0, 0, 0)), ((0, 0, 0), (0, 0, 10))]:
        A, B = np.asarray(A, float), np.asarray(B, float)
        L0 = 0.999 * 10
        sv = ds.solve_catenary(A, B, L0, cable)
        sn = ds.solve_catenary(A, B + [1e-7, 0, 0], L0, cable)
        assert sv.H == 0.0
        np.testing.assert_allclose(sn.end_stiffness, sv.end_stiffness, rtol=1e-6,
                                   atol=1e-6 * sv.end_stiffness.max())
        np.testing.assert_allclose(sn.force_on_end, sv.force_on_end, rtol=1e-6, atol=1e-3)
        # straight hanging cable: lateral stiffness 1 / int ds/T (exact), vertical EA/L0
        w0 = cable.mass_per_length * G
        Ts = np.linspace(sv.tension_at_anchor, sv.tension_at_end, 20001)
        lateral = 1.0 / (L0 / cable.EA + np.trapezoid(1.0 / Ts, Ts) / w0 * np.sign(
            sv.tension_at_end - sv.tension_at_anchor))
        assert sv.end_stiffness[0, 0] == pytest.approx(lateral, rel=1e-7)
        assert sv.end_stiffness[2, 2] == pytest.approx(cable.EA / L0, rel=1e-12)


def test_weightless_cable_is_straight_spring():
    cable = cogiro_cable(17e9)
    A, B = np.zeros(3), np.array([3.0, 4.0, 0.0])
    s = ds.solve_catenary(A, B, 4.99, cable, g=0.0)
    T = cable.EA * (5.0 / 4.99 - 1)
    np.testing.assert_allclose(s.force_on_end, -T * B / 5.0, rtol=1e-13)
    u = B / 5
    np.testing.assert_allclose(
        s.end_stiffness, cable.EA / 4.99 * np.outer(u, u) + T / 5.0 * (np.eye(3) - np.outer(u, u)),
        rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("at", ["end", "anchor"])
def test_unstretched_length_for_tension_round_trip(at, cable17):
    s = ds.unstretched_length_for_tension(A0, B0, 437.0, cable17, at=at)
    T = s.tension_at_end if at == "end" else s.tension_at_anchor
    assert T == pytest.approx(437.0, rel=1e-12)
    s2 = ds.solve_catenary(A0, B0, s.unstretched_length, cable17)
    assert s2.H == pytest.approx(s.H, rel=1e-12)


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


def test_profile_table_runs_from_anchor_to_end():
    """to_frame: s from 0 to L0, the first point at A, the last at B, T(0) and T(L0) the
    anchor and end tensions, stretched arc length between the points >= the chord."""
    cable = ds.Cable(0.064, 8.2051e-6 * 17e9)
    A, B = np.array([-7.1775, -5.4361, 5.3911]), np.array([0.5032, -0.4928, 1.0])
    st = ds.unstretched_length_for_tension(A, B, 100.0, cable)
    df = st.to_frame(41)
    assert list(df.columns) == ["s [m]", "x [m]", "y [m]", "z [m]", "tension [N]"]
    xyz = df[["x [m]", "y [m]", "z [m]"]].to_numpy()
    np.testing.assert_allclose(xyz[0], A, atol=1e-12)
    np.testing.assert_allclose(xyz[-1], B, atol=1e-9)
    assert df["s [m]"].iloc[-1] == pytest.approx(st.unstretched_length, rel=1e-14)
    assert df["tension [N]"].iloc[0] == pytest.approx(st.tension_at_anchor, rel=1e-12)
    assert df["tension [N]"].iloc[-1] == pytest.approx(st.tension_at_end, rel=1e-12)
    arc = np.linalg.norm(np.diff(xyz, axis=0), axis=1).sum()
    assert np.linalg.norm(B - A) < arc < st.stretched_length + 1e-12
    assert len(st.to_frame()) == 50                       # the documented default


@pytest.mark.parametrize("mass, rtol", [(0.064, 1e-13), (5e-7, 4e-15)])
def test_mean_tension_is_the_arc_average_of_the_tension(mass, rtol):
    """mean_tension = (1/L0) int_0^L0 T(s) ds, against a 40-digit quadrature of
    T(s) = sqrt(H^2 + (V0 + w0 s)^2) with the state's own H and V0. The light cable
    (W/T = 5e-7) takes the small-weight Taylor branch, whose W^2/24 term is 1e-14 of T there:
    a 1/12 would miss by as much."""
    import mpmath
    cable = ds.Cable(mass, 1.4e5)
    st = ds.unstretched_length_for_tension([0, 0, 0], [10.0, 0.0, 2.0], 100.0, cable)
    W = cable.weight_per_length(st.g) * st.unstretched_length
    assert (W < 1e-6 * st.tension_at_anchor) == (mass < 1e-3)   # the branch under test
    with mpmath.workdps(40):
        H, V0 = mpmath.mpf(st.H), mpmath.mpf(st.V0)
        w0, L0 = mpmath.mpf(cable.weight_per_length(st.g)), mpmath.mpf(st.unstretched_length)
        ref = mpmath.quad(lambda s: mpmath.sqrt(H**2 + (V0 + w0 * s) ** 2), [0, L0]) / L0
    assert abs(st.mean_tension / float(ref) - 1) <= rtol
    # not the mean of the two end tensions (the tension varies non-linearly along the cable)
    if mass > 1e-3:
        ends = 0.5 * (st.tension_at_end + st.tension_at_anchor)
        assert abs(ends / float(ref) - 1) > 1e3 * rtol


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
    assert taut.sag == pytest.approx(line, rel=1e-12)


def test_end_stiffnesses_equal_each_cables_property():
    """The batched end stiffness (all cables at once, used by the closed form's static
    guard) equals CatenaryState.end_stiffness of every case above (slack, steep, near
    vertical and rising included) and of an exactly vertical cable (H = 0), in any
    horizontal direction of the chord."""
    cable = cogiro_cable(17e9)
    states = []
    for _, A, B, ratio in CASES:
        A, B = np.asarray(A, float), np.asarray(B, float)
        for phi in (0.0, 2.1):
            c, s = np.cos(phi), np.sin(phi)
            R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
            states.append(ds.solve_catenary(R @ A, R @ B, ratio * np.linalg.norm(B - A),
                                            cable))
    states.append(ds.solve_catenary([0.0, 0.0, 10.0], [0.0, 0.0, 0.0], 9.99, cable))
    assert states[-1].H == 0.0
    K = ds.cable.catenary.end_stiffnesses(states)
    for Ki, s in zip(K, states):
        ref = s.end_stiffness
        np.testing.assert_allclose(Ki, ref, rtol=0, atol=1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("V0, W", [(30.0, 50.0), (-80.0, 50.0), (-20.0, 50.0), (0.0, 50.0)])
def test_mean_tension_of_a_vertical_cable_is_the_average_of_its_axial_force(V0, W):
    """H = 0: T(s) = |V0 + w s|; its average over the length, in closed form, equals the
    quadrature of |V0 + w s| — rising, hanging, and through zero (tension then compression
    in magnitude, the kink at s = -V0 / w)."""
    from dynstiff.cable.catenary import _mean_tension
    L0 = 10.0
    w0 = W / L0
    s = np.linspace(0.0, L0, 200001)
    T = np.abs(V0 + w0 * s)
    ref = np.sum(0.5 * (T[1:] + T[:-1]) * np.diff(s)) / L0
    assert _mean_tension(0.0, V0, L0, w0) == pytest.approx(ref, rel=1e-9)


def test_profiles_of_two_points_and_of_a_vertical_cable():
    """profile(2) is the two ends; an exactly vertical cable's profile lies on its chord,
    its heights the stretched arc s + (V0 s + w s^2 / 2) / EA of §1.1 (theory.md §1.1);
    one Newton iteration is a valid (if insufficient) request, refused by its residual."""
    from dynstiff.errors import ConvergenceError
    cab = ds.Cable(0.5, 2e4)
    st = ds.solve_catenary((0, 0, 0), (0.0, 0, 10.0), 9.9, cab)
    np.testing.assert_array_equal(st.profile(2), [st.anchor, st.end])
    p = st.profile(5)
    s = np.linspace(0.0, 9.9, 5)
    w0 = cab.weight_per_length(st.g)
    np.testing.assert_allclose(p[:, 2], s + (st.V0 * s + 0.5 * w0 * s * s) / cab.EA,
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(p[:, :2], 0.0)
    with pytest.raises(ConvergenceError, match="relative residual"):
        ds.solve_catenary((0, 0, 0), (8.0, 0, 3.0), 8.7, cab, max_iter=1)


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


def test_profile_defaults_and_the_point_one_metre_along(cable17):
    """profile() gives 50 points by default, from A to B; profile_plane at s = 1 m exactly
    is the catenary's own point there (the offsets of a 1 m cable with the same H and V0),
    not the anchor; a bad g is named."""
    from dynstiff.cable.catenary import end_offsets_and_flexibility
    s = ds.solve_catenary(A0, B0, 8.5, cable17)
    pts = s.profile()
    assert pts.shape == (50, 3)
    np.testing.assert_allclose(pts[[0, -1]], [A0, B0], rtol=0, atol=1e-9)
    xz = s.profile_plane([0.0, 1.0, 2.0])
    ref = [end_offsets_and_flexibility(s.H, s.V0, sk, cable17.EA,
                                        cable17.weight_per_length(s.g))[0] for sk in (1.0, 2.0)]
    np.testing.assert_array_equal(xz, np.vstack([[0.0, 0.0], ref]))
    with pytest.raises(InvalidParameterError, match="^g must be"):
        ds.unstretched_length_for_tension(A0, B0, 437.0, cable17, g=-1.0)


def test_divided_differences_at_zero_width_are_the_derivatives():
    """delta = 0 (a weightless cable): the four divided differences are the derivatives of
    asinh t, t / sqrt(1 + t^2), 1 / sqrt(1 + t^2) and sqrt(1 + t^2) at a."""
    from dynstiff.cable.catenary import divided_differences
    a = np.array([-3.0, -0.2, 0.0, 0.7, 40.0])
    s = np.hypot(1.0, a)
    got = divided_differences(a, a, np.zeros_like(a))
    for g, want in zip(got, (1 / s, 1 / s**3, -a / s**3, a / s)):
        np.testing.assert_allclose(g, want, rtol=1e-15, atol=0)


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


def test_coincident_ends_are_judged_relative_to_their_coordinates():
    """Ends 5e-11 m apart 100 m from the origin are one point to rounding (1e-12 of the
    coordinates): refused, naming both."""
    with pytest.raises(InvalidParameterError, match="^anchor and end must be distinct points"):
        ds.solve_catenary([100.0, 0, 0], [100.0 + 5e-11, 0, 0], 1.0, ds.Cable(1.0, 1e6))
