"""The static state and mesh of the exact cable (dynstiff/cable/exact_mesh.py, theory.md
§11.2, §11.3): the Gauss-Lobatto-Legendre rule and the closed-form integrals of t t^T along
the arc, each against quadrature; the mesh's spacing against the measure Phi integrated by
adaptive quadrature."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.exact_mesh import gll, tangent_integrals


def test_gll_rule_integrates_polynomials_and_differentiates_exactly():
    xi, w, Dm = gll(7)
    assert w.sum() == pytest.approx(2.0, abs=1e-14)
    assert np.dot(w, xi**12) == pytest.approx(2 / 13, rel=1e-13)          # degree 2p - 2
    np.testing.assert_allclose(Dm @ xi**5, 5 * xi**4, atol=1e-12)


@pytest.mark.parametrize("case", ["sagging", "weightless", "vertical"])
def test_tangent_integrals_match_quadrature(case):
    """int t t^T ds over the arc in closed form (theory.md §11.3, damped static stiffness)
    against 2000-point Gauss quadrature of t(s) = (H, V0 + w s) / T(s)."""
    if case == "sagging":
        s = ds.solve_catenary((0, 0, 0), (10.0, 0, 5.0), 11.5, ds.Cable(1.0, 1e6))
    elif case == "weightless":
        s = ds.solve_catenary((0, 0, 0), (6.0, 0, 8.0), 9.99, ds.Cable(0.5, 2e4), g=0.0)
    else:
        s = ds.solve_catenary((0, 0, 0), (0.0, 0, 10.0), 9.9, ds.Cable(0.5, 2e4))
    x, w = np.polynomial.legendre.leggauss(2000)
    L0 = s.unstretched_length
    sq = 0.5 * L0 * (x + 1)
    V = s.V0 + s.cable.weight_per_length(s.g) * sq
    T = np.hypot(s.H, V)
    tx, tz = s.H / T, V / T
    ref = [0.5 * L0 * np.dot(w, f) for f in (tx * tx, tx * tz, tz * tz)]
    np.testing.assert_allclose(tangent_integrals(s), ref, rtol=1e-12, atol=1e-14 * L0)


@pytest.mark.parametrize("H", [1.0, 5.09, 0.0])
def test_tangent_integrals_are_the_quadrature_of_the_tangent(H):
    """int_0^L0 t t^T ds with the tangent's slope tan(theta) = (V0 + w s) / H, against
    adaptive quadrature (1e-12), for horizontal tensions of exactly 1 N, 5.09 N and 0 (a
    vertical cable: t = e_z everywhere, so (0, 0, L0))."""
    import dataclasses

    from scipy.integrate import quad
    cable = ds.Cable(0.064, 1.4e5)
    s = dataclasses.replace(ds.solve_catenary([0, 0, 0], [3.0, 0, 4.0], 5.01, cable), H=H)
    w, L0 = cable.mass_per_length * s.g, s.unstretched_length

    def part(x, k):
        V = s.V0 + w * x
        T2 = H * H + V * V
        return (H * H, H * V, V * V)[k] / T2
    want = [quad(part, 0.0, L0, args=(k,), epsabs=1e-14, epsrel=1e-13)[0] for k in range(3)]
    np.testing.assert_allclose(tangent_integrals(s), want, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("per_efold", [1.0, 3.0])
def test_mesh_puts_per_efold_elements_in_each_e_fold_of_the_tension(per_efold):
    """Without the band's waves (omega_max = 0), Phi(L0) = 1 + per_efold |asinh(V_B/H) -
    asinh(V0/H)| (asinh(V/H) grows monotonically along a hanging cable), so the mesh has
    ceil of that many elements: per_efold elements in each e-fold of the tension measure."""
    from dynstiff.cable.exact_mesh import mesh
    cable = ds.Cable(0.064, 1.4e5)
    s = ds.solve_catenary([0, 0, 0], [10.0, 0, 0.0], 10.6, cable)      # a sagging U
    span = abs(np.arcsinh(s.Vb / s.H) - np.arcsinh(s.V0 / s.H))
    assert span > 1.0
    edges = mesh(s, 0.0, 2.0, per_efold=per_efold)
    assert edges.size - 1 == int(np.ceil(1.0 + per_efold * span))


@pytest.mark.parametrize("name, half_waves", [
    ("sagging 10x5 m, d/L 0.10", 2.0), ("slack U (T_min 0.04 T_max)", 2.0),
    ("exactly vertical", 2.0), ("sagging 10x5 m, d/L 0.10", 0.3)])
def test_elements_are_spread_evenly_in_the_mesh_measure(name, half_waves):
    """theory.md §11.2: the element edges divide Phi(s) = s / L0 + |asinh(V/H) -
    asinh(V0/H)| + int_0^s k_t ds / (pi half_waves), k_t = omega_max sqrt(m (1 + T/EA) / T),
    into ceil(Phi(L0)) equal parts (ln T replaces asinh(V/H) when H = 0). Phi is evaluated
    here by adaptive quadrature, independently of the mesh's own 4001-point sums."""
    from scipy.integrate import quad

    from dynstiff.cable.exact_mesh import mesh
    A, B, L0, cable = {
        "sagging 10x5 m, d/L 0.10": ((0, 0, 0), (10.0, 0, 5.0), 11.5, ds.Cable(1.0, 1e6)),
        "slack U (T_min 0.04 T_max)": ((0, 0, 0), (2.0, 0, 9.0), 10.1, ds.Cable(0.064, 1.4e5)),
        "exactly vertical": ((0, 0, 0), (0.0, 0, 10.0), 9.9, ds.Cable(0.5, 2e4))}[name]
    s = ds.solve_catenary(A, B, L0, cable)
    w_max = 2 * np.pi * 12.0
    L0, EA, m = s.unstretched_length, s.cable.EA, s.cable.mass_per_length
    w0 = s.cable.weight_per_length(s.g)

    def T(x):
        return np.hypot(s.H, s.V0 + w0 * x)

    def psi(x):
        return np.arcsinh((s.V0 + w0 * x) / s.H) if s.H > 0 else np.log(T(x))

    def k(x):
        return w_max * np.sqrt(m * (1 + T(x) / EA) / T(x))

    def phi(x):
        wave = quad(k, 0.0, x, epsabs=0, epsrel=1e-12, limit=200)[0]
        return x / L0 + abs(psi(x) - psi(0.0)) + wave / (np.pi * half_waves)

    edges = mesh(s, w_max, half_waves)
    n_el = len(edges) - 1
    assert edges[0] == 0.0 and edges[-1] == L0
    assert n_el == int(np.ceil(phi(L0))) and n_el > 3
    # equal to the accuracy of the mesh's trapezoid sums on 4001+ points (measured <= 4e-7)
    np.testing.assert_allclose(np.diff([phi(x) for x in edges]), phi(L0) / n_el, rtol=1e-6)
