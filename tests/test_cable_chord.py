"""Chord-frame parameters of the linear cable theory (dynstiff/cable/chord.py, theory.md §1.2,
§3.1): conventions checked against the exact catenary they come from."""

import dataclasses

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.chord import chord_parameters, irvine_lambda_sq, stack_parameters
from dynstiff.errors import InvalidParameterError


@pytest.fixture
def inclined(cable17):
    """A 30-degree inclined CoGiRo cable, 300 N at B (theory.md §9.2 kind of case)."""
    return ds.unstretched_length_for_tension([0, 0, 0], [8.0, 3.0, 5.0], 300.0, cable17)


def test_chord_frame_is_right_handed_with_the_sag_direction_downward(inclined):
    p = chord_parameters(inclined)
    R = p.rotation
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-14)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-14)
    np.testing.assert_allclose(R[:, 0], inclined.chord / inclined.chord_length, atol=1e-15)
    assert R[2, 1] < 0                        # e_v: the component of gravity across the chord
    assert abs(R[2, 2]) < 1e-14               # e_w horizontal: out of the vertical plane
    cos_theta = np.hypot(8.0, 3.0) / np.linalg.norm([8.0, 3.0, 5.0])
    assert p.cos_theta == pytest.approx(cos_theta, rel=1e-14)
    assert p.q == pytest.approx(p.m * ds.STANDARD_GRAVITY * cos_theta, rel=1e-14)


def test_mass_per_chord_length_carries_the_whole_cable_mass(inclined, cable17):
    p = chord_parameters(inclined)
    assert p.m * p.L == pytest.approx(cable17.mass_per_length * inclined.unstretched_length,
                                      rel=1e-14)


def test_tension_conventions(inclined):
    """mean: the arc average of T(s) along the catenary; chord: H / cos(theta)."""
    mean = chord_parameters(inclined, "mean").T
    s = np.linspace(0.0, inclined.unstretched_length, 20001)
    T = inclined.tension(s)
    arc = np.sum(0.5 * (T[1:] + T[:-1]) * np.diff(s)) / s[-1]          # trapezoid, O(h^2)
    assert mean == pytest.approx(arc, rel=1e-8)
    chord = chord_parameters(inclined, "chord").T
    assert chord == pytest.approx(inclined.H / chord_parameters(inclined).cos_theta, rel=1e-14)
    assert abs(chord / mean - 1) < 0.02       # both within the weight along the chord
    with pytest.raises(InvalidParameterError, match="tension"):
        chord_parameters(inclined, "max")


def test_lambda_sq_limits_and_damping(inclined, cable17):
    """lambda^2 = (qL/T)^2 L EA/(T L_e): 0 without weight across the chord (vertical chord),
    proportional to EA at fixed geometry, and complex with ratio eta under hysteretic
    damping (EA (1 + i eta))."""
    p = chord_parameters(inclined)
    assert inclined.lambda_sq == p.lambda_sq == pytest.approx(
        irvine_lambda_sq(p.q, p.L, p.T, p.EA, p.L_e), rel=0)
    assert irvine_lambda_sq(0.0, p.L, p.T, p.EA, p.L_e) == 0.0
    assert irvine_lambda_sq(p.q, p.L, p.T, 2 * p.EA, p.L_e) == pytest.approx(2 * p.lambda_sq)
    lossy = dataclasses.replace(cable17, loss_factor=0.03)
    st = ds.solve_catenary(inclined.anchor, inclined.end, inclined.unstretched_length, lossy)
    lam = chord_parameters(st).lambda_sq_complex
    assert lam.imag / lam.real == pytest.approx(0.03, rel=1e-12)
    assert chord_parameters(st).lambda_sq == pytest.approx(p.lambda_sq, rel=1e-12)
    vertical = ds.solve_catenary([0, 0, 0], [0, 0, 5.0], 4.999, cable17)
    assert chord_parameters(vertical).lambda_sq == 0.0


def test_compliance_length_uses_the_unstretched_length(inclined):
    p = chord_parameters(inclined)
    d = p.q * p.L / (8 * p.T)                 # sag over chord
    assert p.L_e == pytest.approx(inclined.unstretched_length * (1 + 8 * d**2), rel=1e-14)
    assert p.sag == pytest.approx(d * p.L, rel=1e-14)


def test_stacked_parameters_are_elementwise_the_single_ones(cogiro_eq):
    params = [chord_parameters(s) for s in cogiro_eq.states]
    st = stack_parameters(params)
    for name in ("L", "T", "m", "c", "EA", "q", "L_e", "cos_theta"):
        np.testing.assert_array_equal(getattr(st, name), [getattr(p, name) for p in params])
    np.testing.assert_array_equal(st.lambda_sq, [p.lambda_sq for p in params])


def test_weightless_inclined_cable_still_has_an_orthonormal_chord_frame(cable17):
    """With g = 0 there is no sag direction: e_v is the horizontal direction made normal to
    the chord (and then normalised), so the frame stays orthonormal for inclined chords."""
    st = ds.solve_catenary([0, 0, 0], [8.0, 3.0, 5.0], 9.0, cable17, g=0.0)
    R = chord_parameters(st).rotation
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-14)
    assert abs(R[:, 0] @ R[:, 1]) < 1e-14
    assert chord_parameters(st).q == 0.0 and chord_parameters(st).lambda_sq == 0.0
