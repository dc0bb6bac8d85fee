"""The massless rungs "spring" and "catenary" (dynstiff/models/static.py, theory.md §4)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.platform import lever_map


def test_default_rung_is_the_catenary(cogiro_eq):
    m = ds.StaticCableModel(cogiro_eq)
    cat = ds.StaticCableModel(cogiro_eq, stiffness="catenary")
    assert m.rung == "catenary" and m.damped is False
    np.testing.assert_array_equal(m.K, cat.K)
    assert ds.StaticCableModel(cogiro_eq, stiffness="spring").damped is False


def test_bad_stiffness_is_named():
    with pytest.raises(InvalidParameterError,
                       match=r"^stiffness must be 'spring' or 'catenary', got 'lumped'$"):
        ds.StaticCableModel(None, stiffness="lumped")


def test_spring_stiffness_is_the_straight_springs(cogiro_eq):
    """K = sum J^T ((EA/L0) u u^T + (T/L)(I - u u^T)) J + K_geo, written out here from the
    states; the catenary rung differs from it by the cables' sag only (CoGiRo's cables are
    taut: within 2 %)."""
    robot = cogiro_eq.robot
    K = np.zeros((6, 6))
    for cable, s, r in zip(robot.cables, cogiro_eq.states, cogiro_eq.lever_arms):
        L = np.linalg.norm(s.chord)
        u = s.chord / L
        Ki = cable.EA / s.unstretched_length * np.outer(u, u) + s.tension_at_end / L * (
            np.eye(3) - np.outer(u, u))
        J = lever_map(r)
        K += J.T @ Ki @ J
    spring = ds.StaticCableModel(cogiro_eq, stiffness="spring")
    geo = spring.K - 0.5 * (K + K.T)
    cat = ds.StaticCableModel(cogiro_eq)
    np.testing.assert_allclose(geo[:3], 0.0, atol=1e-9 * np.abs(K).max())
    np.testing.assert_allclose(spring.K, spring.K.T, rtol=0, atol=0)
    np.testing.assert_allclose(cat.K, spring.K, rtol=0.02, atol=0.02 * np.abs(K).max())
    assert not np.array_equal(cat.K, spring.K)


def test_dynamic_stiffness_and_matrices(cogiro_eq):
    m = ds.StaticCableModel(cogiro_eq)
    K, M = m.matrices()
    assert K is m.K and M is m.platform_mass and m.n_dof == m.n_free == 6
    w = np.array([0.0, 3.0, 2.0 + 0.5j])
    D = m.dynamic_stiffness(w)
    assert D.shape == (3, 6, 6)
    for k in range(3):
        np.testing.assert_allclose(D[k], K - w[k] ** 2 * M, rtol=1e-15, atol=0)
    K0 = m.massless_stiffness()
    np.testing.assert_array_equal(K0, K)
    K0[0, 0] = -1.0                                          # a copy: the model is unchanged
    assert m.K[0, 0] > 0
    E = m.cable_energies(np.ones((6, 4)))
    assert E.shape == (4, cogiro_eq.robot.n_cables) and not E.any()

