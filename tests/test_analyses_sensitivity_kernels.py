"""The complex-step-safe kernels of the sensitivities (theory.md §16.1-§16.3) against
independent references.

The rotation against scipy's ``Rotation.from_rotvec``, its Rodrigues coefficients
sin(theta)/theta and (1 - cos(theta))/theta^2 on both sides of the series switch
(theta^2 = 1e-6) and its complex step against central differences; the divided differences
against their definition evaluated in 40-digit arithmetic (mpmath), at coincident points
(the derivatives, without floating-point faults at t = 0) and nearly coincident ones; the
mean tension against quadrature of T = hypot(H, V) along the catenary, in and around the
Taylor branch (and its complex step there), and at zero weight; the pose kept by
``cable_quantities``.
"""

import mpmath
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.spatial.transform import Rotation

from dynstiff.analyses.sensitivity_kernels import (
    CS_STEP,
    cable_quantities,
    divided_differences,
    mean_tension,
    primitives,
    rotation,
)

RNG = np.random.default_rng(20240611)


def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


# --------------------------------------------------------------------------- rotation
def test_rotation_of_a_batch_matches_scipy():
    """A batch (k, 3) of rotation vectors of angles from 1e-2 to 3 rad, one call: every
    matrix is scipy's, each from its own vector."""
    angles = np.array([1e-2, 0.3, 0.9, 1.7, 2.4, 3.0])
    v = np.array([a * unit(RNG.normal(size=3)) for a in angles])
    R = rotation(v)
    assert R.shape == (len(angles), 3, 3)
    np.testing.assert_allclose(R, Rotation.from_rotvec(v).as_matrix(), rtol=0, atol=2e-15)


@pytest.mark.parametrize("th2", [1e-10, 3e-7, 9.9e-7, 1.01e-6, 4e-6, 1e-3, 0.04, 0.7, 2.5, 9.0])
def test_rodrigues_coefficients_on_both_sides_of_the_series_switch(th2):
    """For v = (x, y, 0), R[0, 2] = a y and R[0, 1] = b x y exactly (no sum with 1), so the
    coefficients a = sin(th)/th and b = (1 - cos th)/th^2 are read to rounding: the series
    (th^2 < 1e-6) and the closed form (whose 1 - cos th loses 2e-16 / th^2) both match
    the cancellation-free sinc(th) and sinc(th/2)^2 / 2."""
    x, y = np.sqrt(0.36 * th2), np.sqrt(0.64 * th2)
    R = rotation(np.array([x, y, 0.0]))
    th = np.sqrt(x * x + y * y)
    a_ref = np.sinc(th / np.pi)
    b_ref = 0.5 * np.sinc(th / (2 * np.pi)) ** 2
    rtol_b = 1e-14 if th2 < 1e-6 else 1e-14 + 4e-16 / th2
    assert R[0, 2] / y == pytest.approx(a_ref, rel=1e-14)
    assert R[0, 1] / (x * y) == pytest.approx(b_ref, rel=rtol_b)
    # and the whole matrix is a rotation: R R^T = I, det 1
    np.testing.assert_allclose(R @ R.T, np.eye(3), rtol=0, atol=1e-15)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("angle", [1e-4, 0.5, 2.0])
def test_rotation_complex_step_is_the_derivative(angle):
    """Im R(v + i h e_k) / h against central differences of scipy's matrices."""
    v = angle * unit([0.3, -0.8, 0.5])
    dv = 1e-6
    for k in range(3):
        e = np.eye(3)[k]
        cs = rotation(v + 1j * CS_STEP * e).imag / CS_STEP
        fd = (Rotation.from_rotvec(v + dv * e).as_matrix()
              - Rotation.from_rotvec(v - dv * e).as_matrix()) / (2 * dv)
        np.testing.assert_allclose(cs, fd, rtol=0, atol=1e-9)


# --------------------------------------------------------------------------- divided differences
_MP = {"asinh": mpmath.asinh, "f": lambda t: t / mpmath.sqrt(1 + t * t),
       "g": lambda t: 1 / mpmath.sqrt(1 + t * t), "sqrt": lambda t: mpmath.sqrt(1 + t * t)}


def _dd_reference(a, b):
    """(F(b) - F(a)) / (b - a) of the float points a, b, in 40 digits."""
    with mpmath.workdps(40):
        A, B = mpmath.mpf(float(a)), mpmath.mpf(float(b))
        return [float((F(B) - F(A)) / (B - A)) for F in _MP.values()]


@pytest.mark.parametrize("a, delta", [
    (0.5, 0.25), (-3.0, 1.0), (-0.4, 1.1), (-2.0, 2.0), (0.0, 0.7), (2e3, 1e-3),
    (-50.0, 1e-9), (0.3, 1e-12), (1e-8, 3e-8), (-1e-3, 1e-3), (7.0, 40.0)])
def test_divided_differences_match_their_definition(a, delta):
    """Same signs, opposite signs, one end at t = 0, far apart and nearly coincident
    (where the float definition cancels): the kernel matches the 40-digit definition."""
    b = a + delta
    got = divided_differences(np.float64(a), np.float64(b), np.float64(b - a))
    np.testing.assert_allclose(np.array(got, float), _dd_reference(a, b), rtol=2e-14,
                               atol=1e-300)


@pytest.mark.parametrize("a", [0.5, -1.3, 1e-3, 40.0])
def test_divided_differences_at_coincident_points_are_the_derivatives(a):
    """delta = 0 (weightless cable): F'(a), with no floating-point fault; a nearly
    coincident pair gives the same within delta."""
    s = np.sqrt(1 + a * a)
    deriv = [1 / s, 1 / s**3, -a / s**3, a / s]
    with np.errstate(all="raise"):
        got = divided_differences(np.float64(a), np.float64(a), np.float64(0.0))
    np.testing.assert_allclose(np.array(got, float), deriv, rtol=1e-15, atol=1e-300)
    delta = 1e-9
    near = divided_differences(np.float64(a), np.float64(a + delta), np.float64(delta))
    np.testing.assert_allclose(np.array(near, float), deriv, rtol=0, atol=2e-9)


def test_divided_differences_at_t_zero_raise_no_floating_point_fault():
    """At a = b = 0, delta = 0 (V0 = 0 and W = 0: no gravity, a horizontal chord) the unused
    same-sign form (a + b) / (b sa + a sb) is 0/0: np.where evaluates it, and no floating-point
    fault may escape (the forms of dynstiff.cable.catenary.divided_differences alike)."""
    with np.errstate(all="raise"):
        got = divided_differences(np.float64(0.0), np.float64(0.0), np.float64(0.0))
    np.testing.assert_array_equal(np.array(got, float), [1.0, 1.0, 0.0, 0.0])


def test_divided_differences_complex_step_at_coincident_points():
    """Im D(a + ih, a + ih, 0) / h = F''(a), the derivative of the coincident branch."""
    a = 0.7
    s2 = 1 + a * a
    got = divided_differences(a + 1j * CS_STEP, a + 1j * CS_STEP, 0.0)
    second = [-a / s2**1.5, -3 * a / s2**2.5, (2 * a * a - 1) / s2**2.5, 1 / s2**1.5]
    np.testing.assert_allclose(np.array(got).imag / CS_STEP, second, rtol=1e-14)


# --------------------------------------------------------------------------- mean tension
def _mean_ref(H, V0, W):
    """Mean of T = hypot(H, V) over the unstretched length: V = V0 + W u, u in [0, 1]."""
    return quad(lambda u: np.hypot(H, V0 + W * u), 0.0, 1.0, epsabs=0.0, epsrel=2e-14)[0]


@pytest.mark.parametrize("H, V0, L0, w0", [
    (300.0, -40.0, 10.0, 8.0),       # V from -40 to 40 N
    (300.0, 120.0, 1e-3, 1e-2),      # W = 1e-5: Taylor branch
    (1e3, 100.0, 1e-3, 1e-4),        # W = 1e-7: Taylor branch, far below its switch
    (1e3, 100.0, 1.0, 1.5e-4),       # W between 1e-6 sqrt(1 + V0^2) and 1e-6 T: Taylor
    (1e3, 100.0, 1.0, 3e-4),
    (1e3, 100.0, 1.0, 6e-4),
    (50.0, -200.0, 30.0, 12.0),      # steep, V of both signs
    (2.0, 5.0, 20.0, 3.0),           # slack-ish: H << V
])
def test_mean_tension_matches_quadrature_along_the_catenary(H, V0, L0, w0):
    W = w0 * L0
    assert float(mean_tension(H, V0, L0, w0)) == pytest.approx(_mean_ref(H, V0, W),
                                                                rel=1e-13)


@pytest.mark.parametrize("L0, w0", [(0.0, 8.0), (10.0, 0.0)])
def test_mean_tension_of_a_weightless_or_zero_length_cable_is_the_tension(L0, w0):
    """W = 0: the tension hypot(H, V0), without a division fault (the other branch's
    division by W is guarded)."""
    with np.errstate(all="raise"):
        T = mean_tension(np.float64(300.0), np.float64(-40.0), np.float64(L0),
                         np.float64(w0))
    assert float(T) == pytest.approx(np.hypot(300.0, -40.0), rel=1e-15)


@pytest.mark.parametrize("H", [50.0, 0.4])
def test_mean_tension_complex_step_in_the_taylor_branch(H):
    """At Vm = V0 + W/2 = 0 the mean tension's derivative in W comes from the Taylor
    branch's curvature term alone: d/dL0 = w0 int_0^1 u V / hypot(H, V) du, V = V0 + W u
    (quadrature), with W = 0.5e-6 H (the Taylor branch)."""
    W = 0.5e-6 * H
    L0 = 4.0
    w0 = W / L0
    V0 = -0.5 * (w0 * L0)
    cs = mean_tension(H, V0, L0 + 1j * CS_STEP, w0).imag / CS_STEP
    We = w0 * L0
    ref = w0 * quad(lambda u: u * (V0 + We * u) / np.hypot(H, V0 + We * u), 0.0, 1.0,
                    epsabs=0.0, epsrel=1e-13)[0]
    assert cs == pytest.approx(ref, rel=1e-8, abs=0)
    assert ref == pytest.approx(w0 * We / (12 * H), rel=1e-6, abs=0)     # the analytic limit
    assert mean_tension(H, V0, L0, w0) == pytest.approx(_mean_ref(H, V0, We), rel=1e-15)


# --------------------------------------------------------------------------- cable quantities
def test_cable_quantities_keep_the_pose_they_used(cogiro, cogiro_eq):
    """The returned position and R are those the geometry was built from (P's by
    default, else the given ones), and the end tensions are the equilibrium's."""
    eq = cogiro_eq
    P = primitives(eq.robot, eq.pose)
    H, V0 = (np.array([getattr(s, k) for s in eq.states]) for k in ("H", "V0"))
    L0 = np.asarray(eq.unstretched_lengths, float)
    q = cable_quantities(P, H, V0, L0, eq.robot.g)
    np.testing.assert_array_equal(q["position"], eq.pose.position)
    np.testing.assert_allclose(q["R"], Rotation.from_rotvec(eq.pose.rotation).as_matrix(),
                               rtol=0, atol=1e-15)
    np.testing.assert_allclose(q["TB"], eq.tensions, rtol=1e-9)
    np.testing.assert_allclose(q["B"], q["position"] + q["r"], rtol=0, atol=0)
    shift = np.array([0.1, -0.2, 0.05])
    R = rotation(np.array([0.0, 0.0, 0.3]))
    q2 = cable_quantities(P, H, V0, L0, eq.robot.g, position=P["position"] + shift, R=R)
    np.testing.assert_array_equal(q2["position"], P["position"] + shift)
    np.testing.assert_array_equal(q2["R"], R)
    np.testing.assert_allclose(q2["B"], P["position"] + shift + P["attachments"] @ R.T,
                               rtol=0, atol=1e-14)
