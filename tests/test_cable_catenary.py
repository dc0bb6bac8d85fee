"""Elastic-catenary statics (theory.md §1.1): independent solutions, symmetry, stiffness."""

import numpy as np
import pytest
from conftest import A0, B0, cogiro_cable

import dynstiff as ds
from dynstiff.errors import InvalidParameterError


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




@pytest.mark.parametrize("mass, end, tension", [
    (0.5, (0.0, 0.0, 3.0), 20.0),     # rising: V0 = 5.3 N below half the weight, 7.4 N
    (0.01, (0.0, 0.0, -3.0), 0.5),    # hanging below its anchor, light: V0 = -0.79 N
    (0.5, (0.0, 0.0, -3.0), 20.0),    # hanging, heavy
])
def test_a_vertical_cable_profile_ends_at_its_end(mass, end, tension):
    """A vertical cable's profile: every point on the chord, the last one the end B, the
    heights (V0 s + w s^2 / 2) / EA +- s (theory.md §1.1), the sign that of the mean axial
    force over [0, s], V0 + w s / 2. The cases put V0 in (0, w L0 / 2) and, for a light
    cable, in (-L0 / (2 w), -w L0 / 2): a wrong weight of w in that sign turns it."""
    cab = ds.Cable(mass, 1e5)
    st = ds.unstretched_length_for_tension((0.0, 0.0, 0.0), end, tension, cab)
    assert st.H == 0.0
    p = st.profile(7)
    np.testing.assert_allclose(p[-1], end, rtol=0, atol=1e-9)
    s = np.linspace(0.0, st.unstretched_length, 7)
    w0 = cab.weight_per_length(st.g)
    direction = np.sign(end[2])
    np.testing.assert_allclose(p[:, 2], (st.V0 * s + 0.5 * w0 * s * s) / cab.EA
                               + direction * s, rtol=0, atol=1e-9)


def test_states_from_arrays_prime_the_same_numbers_as_one_state_computes():
    """catenary_states computes the chord, horizontal direction and force on B of many
    cables at once: each is bit for bit what a fresh state computes for itself, on random
    inclined cables, an exactly vertical one, one within rounding of vertical and a 10 m one
    5e-14 m off vertical (vertical for one state: 5e-14 <= 1e-14 |C|; those three are left
    to compute their own direction: the same numbers again)."""
    from dynstiff.cable.catenary import CatenaryState, catenary_states
    rng = np.random.default_rng(11)
    n = 60
    A = rng.uniform(-10, 10, size=(n, 3))
    B = A + rng.uniform(-8, 8, size=(n, 3))
    B[0, :2] = A[0, :2]                                      # vertical
    B[1, :2] = A[1, :2] + 1e-16 * np.array([3.0, -1.0])      # within rounding of vertical
    A[2], B[2] = 0.0, [0.0, 5e-14, 10.0]                     # vertical for one state
    L0 = np.linalg.norm(B - A, axis=1) * rng.uniform(0.98, 1.01, n)
    H, V0 = rng.uniform(1.0, 5e3, n), rng.uniform(-3e3, 3e3, n)
    res = rng.uniform(0, 1e-12, n)
    cables = [ds.Cable(mass_per_length=m, EA=1e6) for m in rng.uniform(0.01, 2.0, n)]
    states = catenary_states(A, B, L0, cables, 9.81, H, V0, res)
    primed = {"force_on_end", "horizontal_direction"}
    assert [primed <= set(vars(s)) for s in states[:3]] == [False, False, False]
    assert all(primed <= set(vars(s)) for s in states[3:])
    for i, s in enumerate(states):
        fresh = CatenaryState(anchor=A[i], end=B[i], unstretched_length=float(L0[i]),
                              cable=cables[i], g=9.81, H=float(H[i]), V0=float(V0[i]),
                              residual=float(res[i]))
        assert (s.H, s.V0, s.unstretched_length, s.residual, s.cable, s.g) == (
            fresh.H, fresh.V0, fresh.unstretched_length, fresh.residual, fresh.cable, fresh.g)
        assert np.array_equal(s.anchor, fresh.anchor) and np.array_equal(s.end, fresh.end)
        for name in ("chord", "horizontal_direction", "force_on_end"):
            got, ref = getattr(s, name), getattr(fresh, name)
            assert np.array_equal(got, ref) and not got.flags.writeable, (i, name)
        assert s.horizontal_span == fresh.horizontal_span
    assert states[0].horizontal_direction.tolist() == [1.0, 0.0, 0.0]
    assert states[2].horizontal_direction.tolist() == [1.0, 0.0, 0.0]
