"""Assembly and condensation of the exact cable (dynstiff/cable/exact_condense.py, theory.md
§11.2, §11.3): the mixed form is the displacement form rewritten, and its rounding floor is
what lets a slack cable through."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.exact_condense import axial_coupling, condense, quadrature_state, string_matrix
from dynstiff.cable.exact_mesh import gll, mesh, static_along

ORDER = 10


def in_plane(state, band=2 * np.pi * 2.0):
    """(K_T, B, C, node masses, interior DOFs, boundary DOFs) of the in-plane family."""
    edges = mesh(state, band, 2.0)
    q = quadrature_state(static_along, state, edges, ORDER)
    _, wq, _ = gll(ORDER)
    mass = np.zeros(q.n)
    np.add.at(mass, q.idx, state.cable.mass_per_length * 0.5 * q.h[:, None] * wq[None, :])
    K2 = np.kron(string_matrix(q, ORDER), np.eye(2))
    B, C = axial_coupling(q, ORDER, state.cable.EA)
    inner = np.arange(1, q.n - 1)
    inner2 = np.stack([2 * inner, 2 * inner + 1], axis=1).ravel()
    bnd2 = [0, 1, 2 * q.n - 2, 2 * q.n - 1]
    return K2, B, C, np.repeat(mass[inner], 2), inner2, bnd2, q


def displacement_form(q, EA):
    """The stiffness assembled from D = EA t t^T + D_t (I - t t^T) directly (theory.md
    §11.1), in-plane, interleaved: the form before the mixed one."""
    _, wq, Dm = gll(ORDER)
    n = q.n
    K = np.zeros((2 * n, 2 * n))
    G = np.einsum("q,qa,qb->qab", wq, Dm, Dm)
    D = {(0, 0): EA * q.tx**2 + q.Dt * q.tz**2, (0, 1): (EA - q.Dt) * q.tx * q.tz,
         (1, 1): EA * q.tz**2 + q.Dt * q.tx**2}
    D[(1, 0)] = D[(0, 1)]
    for e in range(q.h.size):
        for (a, b), d in D.items():
            K[np.ix_(2 * q.idx[e] + a, 2 * q.idx[e] + b)] += (2.0 / q.h[e]) * np.einsum(
                "q,qab->ab", d[e], G)
    return K


def test_eliminating_the_axial_force_gives_the_displacement_form():
    """K_T + B^T C^-1 B equals the displacement form's stiffness (same quadrature) to the
    rounding of its EA / h entries."""
    s = ds.solve_catenary((0, 0, 0), (10.0, 0, 5.0), 11.5, ds.Cable(1.0, 1e6))
    K2, B, C, *_, q = in_plane(s)
    K = K2 + B.T @ (B / C[:, None])
    Kd = displacement_form(q, s.cable.EA)
    np.testing.assert_allclose(K, Kd, rtol=0, atol=1e-13 * np.abs(Kd).max())


def test_mixed_and_displacement_condensations_agree_on_a_taut_cable():
    """Where the displacement form is accurate (a taut cable, EA / T = 100): the same clamped
    modes (1e-10) and the same static condensation (1e-10) from both forms."""
    s = ds.solve_catenary((0, 0, 0), (8.0, 0, 3.0), 8.5, ds.Cable(0.7, 3e5))
    assert s.cable.EA / s.min_tension < 200
    K2, B, C, m, inner, bnd, q = in_plane(s)
    loc = [0, 2, 3, 5]
    mixed = condense(K2, m, inner, bnd, loc, B, C)
    disp = condense(displacement_form(q, s.cable.EA), m, inner, bnd, loc)
    lam_m, lam_d = np.sort(1 / mixed.mu)[:12], np.sort(1 / disp.mu)[:12]
    np.testing.assert_allclose(lam_m, lam_d, rtol=1e-10)
    np.testing.assert_allclose(mixed.static, disp.static, rtol=0,
                               atol=1e-10 * np.abs(disp.static).max())
    np.testing.assert_allclose(mixed.psi, disp.psi, rtol=0, atol=1e-10)


@pytest.mark.parametrize("ratio_span", [(1e-4, 9.9e-3), (1e-6, 1.451e-4)])
def test_the_rounding_floor_shows_why_the_mixed_form(ratio_span):
    """A 10 m U between ends at equal height, T_min / T_max ~ 1e-4 and 1e-6 (theory.md
    §11.2): the displacement form's static condensation is 7.5e-6 and 5.8e-4 off the
    catenary's exact stiffness, under its rounding-floor estimate (6e-3 and 0.6: entries
    EA / h with h ~ 1e-6 m at the bottom); the mixed form's floor is 3e-10 and its error
    (discretisation at order 10) 2e-10 to 7e-10."""
    ratio, span = ratio_span
    s = ds.solve_catenary((0, 0, 0), (span, 0, 0.0), 10.0, ds.Cable(0.064, 1.4e5))
    assert s.min_tension / s.max_tension == pytest.approx(ratio, rel=0.05)
    K2, B, C, m, inner, bnd, q = in_plane(s)
    loc = [0, 2, 3, 5]
    K_exact = np.linalg.inv(s.in_plane_flexibility)           # end B, (x, z), A clamped
    scale = np.abs(K_exact).max()
    errors = {}
    for name, fam in (("mixed", condense(K2, m, inner, bnd, loc, B, C)),
                      ("displacement", condense(displacement_form(q, s.cable.EA), m, inner,
                                                bnd, loc))):
        errors[name] = (np.abs(fam.static[2:, 2:] - K_exact).max() / scale,
                        fam.floor[2:, 2:].max() / scale)
    err, floor = errors["displacement"]
    assert 1e-6 < err <= floor and floor > 1e-3
    err, floor = errors["mixed"]
    assert err < 1e-8 and floor < 1e-8
