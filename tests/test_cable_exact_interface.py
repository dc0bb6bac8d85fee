"""The exact cable's interface (dynstiff/cable/exact.py, theory.md §11.3): its poles are the
clamped frequencies and its mode count is exact, the band edge and the documented ranges
are inclusive, bad input is refused by name, the undamped stiffness is real and the
responses linear, one element equals many, and a response on a pole is finite."""

import numpy as np
import pytest
from conftest import HARD, exact_float_poles

import dynstiff as ds
from dynstiff.cable.dsm import cable_dynamic_stiffness
from dynstiff.cable.exact import ExactCable
from dynstiff.cable.modes import cable_natural_frequencies
from dynstiff.errors import DynstiffError, InvalidParameterError

TWO_PI = 2 * np.pi


def state(case):
    A, B, L0, cab = case
    return ds.solve_catenary(A, B, L0, cab)


def test_poles_are_the_clamped_frequencies_and_the_count_is_exact():
    s = state(HARD["soft, axial mode among the first ten"])
    ec = ExactCable(s, TWO_PI * 4.0)
    w = np.sqrt(ec.eigenvalues[:15])
    assert w[-1] < TWO_PI * 4.0
    np.testing.assert_array_equal(ec.mode_count(w * (1 + 1e-9)), np.arange(1, 16))
    np.testing.assert_array_equal(ec.mode_count(w * (1 - 1e-9)), np.arange(0, 15))
    K = ec.dynamic_stiffness(w[:3] * (1 + 1e-9))
    assert np.all(np.abs(K).max(axis=(1, 2)) > 1e4 * np.abs(ec.dynamic_stiffness(0.0)).max())
    modes = cable_natural_frequencies(s, 12, model="exact")
    np.testing.assert_allclose(TWO_PI * modes.freq_hz, w[:12], rtol=1e-12)
    assert "axial" in modes.family and modes.labels[0] == "out-of-plane 1"
    K2 = cable_dynamic_stiffness(s, [0.0, 1.0], model="exact")
    np.testing.assert_allclose(K2[0], s.end_stiffness, rtol=0,
                               atol=1e-12 * np.abs(s.end_stiffness).max())


def test_bad_input_and_too_slack_cables_are_refused():
    s = state(HARD["sagging 10x5 m, d/L 0.10"])
    ec = ExactCable(s, 5.0)
    with pytest.raises(InvalidParameterError, match="omega must be <= 5"):
        ec.dynamic_stiffness([1.0, 6.0])
    with pytest.raises(InvalidParameterError, match="ends"):
        ec.dynamic_stiffness(1.0, ends="A")
    for kw, word in (({"omega_max": -1.0}, "omega_max"), ({"omega_max": np.inf}, "omega_max"),
                     ({"omega_max": 1.0, "order": 2}, "order"),
                     ({"omega_max": 1.0, "half_waves": 0}, "half_waves")):
        with pytest.raises(InvalidParameterError, match=word):
            ExactCable(s, **kw)
    with pytest.raises(InvalidParameterError, match="model"):
        cable_dynamic_stiffness(s, 1.0, model="fem")
    with pytest.raises(InvalidParameterError, match="CatenaryState"):
        ExactCable("state", 1.0)
    # hanging in a U under a near-vertical chord (T_min / T_max = 3e-9): refused, not wrong
    slack = ds.solve_catenary((0, 0, 0), (1e-6, 0, 10), 10.1, ds.Cable(0.064, 1.4e5))
    with pytest.raises(DynstiffError, match="too slack"):
        ExactCable(slack, TWO_PI * 3)


def test_the_band_edge_is_inclusive():
    s = state(HARD["sagging 10x5 m, d/L 0.10"])
    ec = ExactCable(s, 5.0)
    assert np.all(np.isfinite(ec.dynamic_stiffness([0.0, 5.0])))
    assert ec.mode_count([5.0])[0] == np.count_nonzero(ec.eigenvalues < 25.0)
    for bad in (5.0 * (1 + 1e-9), -5.0 * (1 + 1e-9)):
        with pytest.raises(InvalidParameterError, match="omega must be <= 5 rad/s"):
            ec.mode_count([bad])


def test_end_block_dyads_are_the_end_block_of_the_two_end_dyads():
    s = state(HARD["steep 60 deg sagging"])
    ec = ExactCable(s, TWO_PI * 1.0)
    both = ec.beta_dyads("both").reshape(-1, 6, 6)
    end = ec.beta_dyads().reshape(-1, 3, 3)
    np.testing.assert_array_equal(end, both[:, 3:, 3:])
    assert both.shape[0] == ec.flexibilities.size
    with pytest.raises(InvalidParameterError, match=r"\(0.795775 Hz\)"):
        ExactCable(s, 5.0).dynamic_stiffness(6.0)


def test_undamped_stiffness_is_real_and_responses_are_linear_in_the_end_motion():
    """Undamped (c = 0, eta = 0): K(omega) and the static stiffnesses (exact and of the
    discretisation) are real, float64, at both ends; a damped cable's K(omega) is complex.
    The interior response is linear in the (complex) end displacement, and a refusal names
    the offending frequency, not the first one."""
    s = state(HARD["sagging 10x5 m, d/L 0.10"])
    ec = ExactCable(s, 5.0)
    assert ec.dynamic_stiffness([1.0, 2.0]).dtype == np.float64
    assert ec.dynamic_stiffness(1.0, ends="both").dtype == np.float64
    assert ec.static_stiffness.dtype == ec.discrete_static_stiffness().dtype == np.float64
    A, B, L0 = (0, 0, 0), (10.0, 0, 5.0), 11.5
    for cab in (ds.Cable(1.0, 1e6, loss_factor=0.01), ds.Cable(1.0, 1e6, viscous_damping=0.2)):
        K = ExactCable(ds.solve_catenary(A, B, L0, cab), 5.0).dynamic_stiffness(1.0)
        assert np.iscomplexobj(K) and np.abs(K.imag).max() > 1e-6 * np.abs(K.real).max()
    u = np.array([0.01, -0.02, 0.005])
    for w in (1.3, 3.9):
        U = ec.end_response(w, u)
        np.testing.assert_allclose(ec.end_response(w, (0.3 - 2j) * u), (0.3 - 2j) * U,
                                   rtol=1e-13, atol=1e-16)
        np.testing.assert_allclose(U[-1], u, rtol=0, atol=0)
    with pytest.raises(InvalidParameterError, match=r"got 6; build"):
        ec.dynamic_stiffness([1.0, 6.0, 2.0])


def test_a_single_element_cable_equals_a_refined_one():
    """A weightless cable with a band near zero is one element (Phi(L0) rounds to 1): its
    discrete statics must still reproduce the exact ones, and its K(omega) in the band
    equal the multi-element cable's (the end-to-end coupling entries of the one element)."""
    s = ds.solve_catenary((0, 0, 0), (6.0, 2.0, 8.0), 10.0, ds.Cable(0.5, 2e4), g=0.0)
    one = ExactCable(s, 1e-20)
    assert len(one.edges) == 2
    many = ExactCable(s, TWO_PI * 5.0)
    assert len(many.edges) > 3
    for K1, K2 in ((one.discrete_static_stiffness(), many.discrete_static_stiffness()),
                   (one.dynamic_stiffness(1e-20, ends="both"),
                    many.dynamic_stiffness(1e-20, ends="both"))):
        np.testing.assert_allclose(K1, K2, rtol=1e-9, atol=1e-9 * np.abs(K2).max())


def test_the_documented_ranges_are_inclusive_and_damping_can_be_switched_off():
    """order in [4, 40] (integers only), half_waves in (0, 8], omega_max > 0, a CatenaryState;
    damping=False gives the undamped cable of a damped one; the nodes run from 0 to L0."""
    s = state(HARD["sagging 10x5 m, d/L 0.10"])
    for kw in ({"order": 4, "half_waves": 0.5}, {"order": 40}, {"half_waves": 8.0}):
        assert ExactCable(s, 20.0, **kw).static_mismatch < 1e-6
    for kw, word in (({"order": 3}, "order"), ({"order": 41}, "order"),
                     ({"order": True}, "order"), ({"order": 12.0}, "order"),
                     ({"half_waves": 8.5}, "half_waves"), ({"half_waves": -1.0}, "half_waves")):
        with pytest.raises(InvalidParameterError, match=word):
            ExactCable(s, 2.0, **kw)
    with pytest.raises(InvalidParameterError, match="omega_max"):
        ExactCable(s, 0.0)
    with pytest.raises(InvalidParameterError, match="CatenaryState .*, got str$"):
        ExactCable("state", 1.0)
    ec = ExactCable(s, 5.0)
    assert ec.s[0] == 0.0 and ec.s[-1] == s.unstretched_length and np.all(np.diff(ec.s) > 0)
    A, B, L0 = (0, 0, 0), (10.0, 0, 5.0), 11.5
    for cab in (ds.Cable(1.0, 1e6, loss_factor=0.05), ds.Cable(1.0, 1e6, viscous_damping=0.5)):
        off = ExactCable(ds.solve_catenary(A, B, L0, cab), 5.0, damping=False)
        assert not off.damped
        np.testing.assert_array_equal(off.dynamic_stiffness([1.0, 3.0]),
                                      ec.dynamic_stiffness([1.0, 3.0]))


def test_a_response_exactly_on_a_clamped_pole_is_finite_and_silent():
    """At an omega where w^2 mu_j = 1 exactly (a clamped mode's pole, as a mode shape at a
    root on a cable pole asks), the undetermined resonant amplitude is dropped: the nodes are
    finite and the end node is u_end; the stiffness there is not finite (documented); no
    floating-point warning escapes (the package's RuntimeWarnings are errors in the tests)."""
    s = state(HARD["soft, axial mode among the first ten"])
    ec = ExactCable(s, TWO_PI * 4.0)
    poles = exact_float_poles(ec._mu, ec.omega_max)
    assert len(poles) >= 3
    u_end = np.array([0.1, 0.2, 0.3])
    for w in poles[:3]:
        u = ec.end_response(float(w), u_end)
        assert np.all(np.isfinite(u))
        np.testing.assert_array_equal(u[-1], u_end)
        # the stiffness itself is infinite there: entries not finite, as documented
        K = ec.local_coefficients(np.array([float(w)]))
        assert not np.all(np.isfinite(K)) and np.all(np.isfinite(
            ec.local_coefficients(np.array([float(w) * (1 - 1e-9)]))))
