"""Closed-form cable dynamic stiffness (theory.md §3, §5.2): limits, symmetry, poles, counts."""

import numpy as np
import pytest
from conftest import A0, B0, cogiro_cable

import dynstiff as ds
from dynstiff.cable.dsm import chord_parameters, local_end_stiffness, local_two_end_stiffness
from dynstiff.errors import InvalidParameterError

TWO_PI = 2 * np.pi


def local(K, p):
    """Global (n, 3, 3) -> chord frame (u, v, w)."""
    R = p.rotation
    return R.T @ K @ R


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


# ----------------------------------------------------------------------------- limits
@pytest.mark.parametrize("omega", [0.0, 1e-9, 1e-4])
def test_zero_frequency_is_parabolic_static_stiffness(state300, omega):
    """omega -> 0: K_B = diag(K0/(1 + lambda^2/12), T/L, T/L) exactly (theory.md §3.6)."""
    p = chord_parameters(state300)
    K = local(ds.cable_dynamic_stiffness(state300, omega, chordwise_inertia=False), p)[0]
    expected = np.diag([p.K0 / (1 + p.lambda_sq / 12), p.T / p.L, p.T / p.L])
    rtol = 1e-13 if omega < 1e-6 else 1e-8   # at 1e-4 rad/s the O(omega^2) terms are 1e-9
    np.testing.assert_allclose(K, expected, rtol=rtol, atol=rtol * p.K0)


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
    from dynstiff.cable.dsm import end_block_coefficients, end_block_coefficients_and_count
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




# ----------------------------------------------------------------------------- fields
@pytest.mark.parametrize("f_hz", [0.37, 1.9, 4.4])
def test_cable_field_solves_the_field_equations_with_its_end_motion(state300, f_hz):
    """cable_field (theory.md §2.1, §5.3): v'' + beta^2 v is one constant h q / T^2 along the
    chord (T v'' + h y'' = -m omega^2 v), w'' + beta^2 w = 0, the field meets the clamped end A
    and the end motion at B, and h satisfies the compatibility condition
    h L_e / EA = u_B + int y' v' dx = u_B - alpha v_B + (q / T) int v dx."""
    from dynstiff.cable.dsm_fields import cable_field
    p = chord_parameters(state300)
    omega = 2 * np.pi * f_hz
    d = np.array([2e-3, -3e-3, 1.5e-3])
    x = np.linspace(0.0, p.L, 4001)
    u, v, w = cable_field(p, omega, d, x).T
    np.testing.assert_allclose([u[0], v[0], w[0]], 0.0, atol=1e-15)
    np.testing.assert_allclose([u[-1], v[-1], w[-1]], d, rtol=1e-12, atol=1e-15)
    beta = omega * np.sqrt(p.m / p.T)
    dx = x[1] - x[0]
    lhs_v = (v[2:] - 2 * v[1:-1] + v[:-2]) / dx**2 + beta**2 * v[1:-1]
    lhs_w = (w[2:] - 2 * w[1:-1] + w[:-2]) / dx**2 + beta**2 * w[1:-1]
    scale = beta**2 * np.abs(v).max()
    assert np.ptp(lhs_v) < 1e-5 * scale                     # one constant along the chord
    assert np.abs(lhs_w).max() < 1e-5 * beta**2 * np.abs(w).max()
    h = np.mean(lhs_v) * p.T**2 / p.q                        # dynamic tension [N]
    int_v = np.sum((v[1:] + v[:-1]) / 2) * dx
    assert h / p.K0 == pytest.approx(d[0] - p.alpha * d[1] + p.q / p.T * int_v, rel=1e-6)


def test_cable_kinetic_energy_is_the_integral_of_its_field(state300):
    """cable_kinetic_energy: m int (|v|^2 + |w|^2) dx by an independent adaptive quadrature of
    cable_field, plus m L / 3 |u_B|^2 with the chordwise inertia (theory.md §3.6, §6)."""
    from scipy.integrate import quad

    from dynstiff.cable.dsm_fields import cable_field, cable_kinetic_energy
    p = chord_parameters(state300)
    omega, d = 2 * np.pi * 2.7, np.array([1e-3, 2e-3, -1e-3])

    def density(x):
        f = cable_field(p, omega, d, np.array([x]))[0]
        return p.m * (abs(f[1]) ** 2 + abs(f[2]) ** 2)
    ref = quad(density, 0.0, p.L, limit=200, epsabs=0, epsrel=1e-12)[0]
    assert cable_kinetic_energy(p, omega, d, False) == pytest.approx(ref, rel=1e-10)
    assert cable_kinetic_energy(p, omega, d, True) == pytest.approx(
        ref + p.m * p.L / 3 * d[0] ** 2, rel=1e-10)


def test_static_block_coefficients_are_the_kernel_at_zero_frequency():
    """Written out at psi = 0, the end-block coefficients equal the general kernel at
    omega = 0 to the last bit, for one cable and a stack, undamped, hysteretic (complex EA)
    and viscous, with and without the chordwise inertia; k_uu is Irvine's static chord
    stiffness K0 / (1 + lambda^2 / 12) and k_vv = k_ww = T/L (theory.md §3.5); a planted
    sign in lambda^2's term would move k_uu by 2 lambda^2 / 12 relative."""
    from dynstiff.cable.chord import stack_parameters
    from dynstiff.cable.dsm import end_block_coefficients, static_block_coefficients
    for cab in (ds.Cable(0.064, 139486.7), ds.Cable(0.064, 139486.7, loss_factor=0.05),
                ds.Cable(0.064, 139486.7, viscous_damping=0.3)):
        ps = [chord_parameters(ds.solve_catenary((0, 0, 0), B, L0, cab))
              for B, L0 in (((8.0, 3.0, -5.0), 9.9), ((4.0, -2.0, 6.0), 7.6))]
        for p in (*ps, stack_parameters(ps)):
            got = static_block_coefficients(p)
            for chordwise in (True, False):
                ref = end_block_coefficients(p, np.zeros(1), chordwise)[0]
                assert got.shape == ref.shape
                np.testing.assert_array_equal(got, ref)
            np.testing.assert_allclose(got[..., 0], p.K0 / (1 + p.lambda_sq_complex / 12),
                                       rtol=1e-14)
            np.testing.assert_allclose(got[..., 3], p.T / p.L, rtol=1e-14)
            np.testing.assert_array_equal(got[..., 4], p.T / p.L)
            assert np.all(got[..., 1:3] == 0)
    assert np.all(np.real(ps[0].lambda_sq_complex) > 0.1)    # lambda^2 matters here
