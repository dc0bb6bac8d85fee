"""The graded lumped chain (dynstiff/cable/lumped_graded.py, theory.md §7.4): with uniform
segments it is the lumped chain of theory.md §7.1; graded towards the bottom of a U it
converges as N^-2 to the elastic catenary where a uniform chain cannot."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.lumped_chain import chain_equilibrium
from dynstiff.cable.lumped_chain_dynamics import (
    chain_end_dynamic_stiffness,
    chain_fixed_end_frequencies,
)
from dynstiff.cable.lumped_graded import graded_chain, graded_edges
from dynstiff.errors import ConvergenceError, InvalidParameterError

SAGGING = ((0, 0, 0), (10.0, 0, 5.0), 11.5, ds.Cable(1.0, 1e6))
# a 10 m U between ends at equal height, T_min / T_max = 1e-6 (theory.md §11.2)
U = ((0, 0, 0), (1.451e-4, 0, 0.0), 10.0, ds.Cable(0.064, 1.4e5))


def test_uniform_segments_are_the_lumped_chain():
    """No grading: the same nodes (1e-14 m), clamped frequencies (1e-10) and end stiffness
    (1e-9) as chain_equilibrium and its dynamics, which solve the statics on the node
    coordinates and the dynamics in displacement form."""
    A, B, L0, cab = SAGGING
    for N in (20, 100):
        g = graded_chain(A, B, L0, cab, N)
        c = chain_equilibrium(A, B, L0, cab, N)
        np.testing.assert_allclose(g.nodes, c.nodes, rtol=0, atol=1e-13)
        np.testing.assert_allclose(g.tensions, c.tensions, rtol=1e-11)
        np.testing.assert_allclose(g.fixed_end_frequencies(8), chain_fixed_end_frequencies(c, 8),
                                   rtol=1e-10)
        w = [0.0, 1.3, 4.1]
        K = chain_end_dynamic_stiffness(c, w)
        np.testing.assert_allclose(g.end_dynamic_stiffness(w), K, rtol=0,
                                   atol=1e-9 * np.abs(K).max())


def test_every_node_is_in_equilibrium():
    """T_k n_k - T_k-1 n_k-1 = m_k g e_z at every interior node, to 1e-12 of the largest
    tension, on a U at T_min / T_max = 1e-6 graded to 1e-7 m segments."""
    A, B, L0, cab = U
    s = ds.solve_catenary(A, B, L0, cab)
    w0 = cab.weight_per_length(s.g)
    g = graded_chain(A, B, L0, cab, 200, s_low=-s.V0 / w0, core=s.H / w0)
    assert g.segment_lengths.min() < 2e-6
    f = g.tensions[:, None] * g.units
    net = f[1:] - f[:-1] - (g.node_masses[1:-1] * s.g)[:, None] * np.array([0, 0, 1.0])
    assert np.abs(net).max() < 1e-12 * g.tensions.max()
    seg = np.diff(g.nodes, axis=0)
    np.testing.assert_allclose(np.linalg.norm(seg, axis=1), g.lengths, rtol=1e-9)
    assert g.closure < 1e-13
    assert g.node_masses.sum() == pytest.approx(cab.mass_per_length * L0, rel=1e-14)


def test_graded_chains_converge_on_the_catenary_as_n_minus_2():
    """The U at 1e-6: the static end stiffness of the graded chain approaches the elastic
    catenary's (theory.md §1.1, no formula of which the chain uses) as N^-2: the error falls
    by 4.0 per doubling (measured 7.0e-3, 1.75e-3, 4.4e-4 at N = 200, 400, 800) and the
    Richardson extrapolation of 400 and 800 is within 1e-6 (measured 2.5e-6 -> 1.5e-7).
    A uniform chain of 800 segments is off by O(1) (1.7 times too stiff horizontally, 4e4
    times vertically): its bottom segment carries about w l0 / 2, not H."""
    A, B, L0, cab = U
    s = ds.solve_catenary(A, B, L0, cab)
    w0 = cab.weight_per_length(s.g)
    Ke = s.end_stiffness
    K = {N: graded_chain(A, B, L0, cab, N, s_low=-s.V0 / w0, core=s.H / w0)
         .end_dynamic_stiffness(0.0)[0] for N in (200, 400, 800)}
    err = {N: np.abs(K[N] - Ke).max() / np.abs(Ke).max() for N in K}
    assert err[200] / err[400] == pytest.approx(4.0, rel=0.02)
    assert err[400] / err[800] == pytest.approx(4.0, rel=0.02)
    rich = (4 * K[800] - K[400]) / 3
    assert np.abs(rich - Ke).max() < 1e-6 * np.abs(Ke).max()
    Ku = graded_chain(A, B, L0, cab, 800).end_dynamic_stiffness(0.0)[0]
    assert np.abs(Ku - Ke).max() > 0.1 * np.abs(Ke).max()


def test_graded_edges_divide_the_measure_evenly():
    """Phi(s) = s / L0 + beta [asinh((s - s_low) / c) - asinh(-s_low / c)], beta making the
    second term 1 at L0, takes equal steps 2 / N at the edges (evaluated here directly)."""
    L0, s_low, c = 10.0, 4.2, 1e-5
    e = graded_edges(L0, 64, s_low, c)
    assert e[0] == 0.0 and e[-1] == L0 and np.all(np.diff(e) > 0)
    span = np.arcsinh((L0 - s_low) / c) - np.arcsinh(-s_low / c)
    phi = e / L0 + (np.arcsinh((e - s_low) / c) - np.arcsinh(-s_low / c)) / span
    np.testing.assert_allclose(np.diff(phi), 2.0 / 64, rtol=1e-9)
    np.testing.assert_array_equal(graded_edges(L0, 4), [0.0, 2.5, 5.0, 7.5, 10.0])
    # a low point beyond the end grades towards that end
    e = graded_edges(L0, 32, 12.0, 0.5)
    assert np.diff(e)[-1] < np.diff(e)[0]


def test_bad_input_and_failure_are_reported():
    A, B, L0, cab = SAGGING
    for kw, word in (({"n_segments": 1}, "n_segments"), ({"cable": "steel"}, "cable"),
                     ({"unstretched_length": -1.0}, "unstretched_length")):
        args = {"anchor": A, "end": B, "unstretched_length": L0, "cable": cab, "n_segments": 8}
        with pytest.raises(InvalidParameterError, match=word):
            graded_chain(**(args | kw))
    with pytest.raises(InvalidParameterError, match="core"):
        graded_edges(L0, 8, 1.0, 0.0)
    with pytest.raises(ConvergenceError, match="closure"):
        graded_chain(A, B, L0, cab, 8, max_iter=1)
    with pytest.raises(InvalidParameterError, match="n_modes"):
        graded_chain(A, B, L0, cab, 4).fixed_end_frequencies(9)


def test_messages_name_the_argument_and_the_bound():
    A, B, L0, cab = SAGGING
    with pytest.raises(InvalidParameterError, match=r"^cable must be a Cable, got str$"):
        graded_chain(A, B, L0, "steel", 8)
    with pytest.raises(InvalidParameterError, match=r"^n_modes must be < 3\(N-1\) = 9, got 9$"):
        graded_chain(A, B, L0, cab, 4).fixed_end_frequencies(9)
    with pytest.raises(InvalidParameterError, match=r"^max_iter must be >= 1, got 0$"):
        graded_chain(A, B, L0, cab, 8, max_iter=0)
    with pytest.raises(InvalidParameterError, match=r"^tol must be >= 0, got -1\.0$"):
        graded_chain(A, B, L0, cab, 8, tol=-1.0)


def test_two_segments_hang_as_a_v():
    """N = 2 (the least allowed): one node of mass m L0 / 2 between the ends at equal
    height; by symmetry each segment carries T with 2 T sin(theta) = m L0 g / 2, and its
    stretched length l = (L0 / 2)(1 + T / EA) spans half the chord: cos(theta) = d / l."""
    cab = ds.Cable(2.0, 1e5)
    L0, d = 10.0, 4.0                                    # half-chord d [m]
    g = graded_chain((0, 0, 0), (2 * d, 0, 0), L0, cab, 2)
    T = g.tensions[0]
    theta = np.arccos(d / ((L0 / 2) * (1 + T / cab.EA)))
    W = cab.mass_per_length * L0 / 2 * ds.constants.STANDARD_GRAVITY
    np.testing.assert_allclose(g.tensions, [T, T], rtol=1e-12)
    assert 2 * T * np.sin(theta) == pytest.approx(W, rel=1e-12)
    assert g.nodes[1, 2] == pytest.approx(-d * np.tan(theta), rel=1e-10)


def test_default_start_is_the_shared_weight_and_an_equal_pull():
    """Without f0 the first segment starts at -W/2 e_z + W h / |h| (W the interior nodes'
    weight, h the chord's horizontal part), or -W/2 e_z for a vertical chord: the same chain,
    to the bit, as with that start given."""
    A, B, L0, cab = SAGGING
    for end in (B, (0.0, 0.0, -9.0)):
        ref = graded_chain(A, end, L0, cab, 8)
        W = ref.node_masses[1:-1].sum() * ds.constants.STANDARD_GRAVITY
        h = np.array([end[0] - A[0], end[1] - A[1], 0.0])
        f0 = -0.5 * W * np.array([0, 0, 1.0]) + (W * h / np.linalg.norm(h) if h.any() else 0)
        got = graded_chain(A, end, L0, cab, 8, f0=f0)
        np.testing.assert_array_equal(got.nodes, ref.nodes)
        np.testing.assert_array_equal(got.tensions, ref.tensions)


def test_a_segment_without_force_is_slack():
    """A start with no force in the first segment gives it no direction."""
    A, B, L0, cab = SAGGING
    with pytest.raises(ds.errors.SlackCableError, match="a segment carries no force"):
        graded_chain(A, B, L0, cab, 8, f0=np.zeros(3))


def test_zero_tolerance_closes_the_chain_to_rounding():
    """tol = 0 iterates until the energy can no longer be lowered: the chain closes to
    rounding (1e-14 of its length) and agrees with the default tolerance's chain."""
    A, B, L0, cab = SAGGING
    ref = graded_chain(A, B, L0, cab, 16)
    got = graded_chain(A, B, L0, cab, 16, tol=0.0)
    assert got.closure < 1e-14 * L0
    np.testing.assert_allclose(got.nodes, ref.nodes, rtol=0, atol=1e-13)
