"""Tests of the lumped-mass chain statics (dynstiff.cable.lumped_chain): chain_equilibrium.

References: theory.md §7 (lumped-mass model), §1.1 (test cable). Every test asserts a number
that the physics fixes. The test cables are in conftest.py."""

import numpy as np
import pytest
from conftest import A_11, A_92, B_11, B_92, BEAD_L, CABLE_11, CABLE_92, L0_11, beaded_string
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError
from dynstiff.lumped import ChainState, chain_equilibrium
from dynstiff.params import Cable

G = 9.81
EZ = np.array([0.0, 0.0, 1.0])


def _node_forces(state):
    """Net force on each interior node recomputed from the returned state [N]."""
    f = state.tensions[:, None] * state.units
    w = state.cable.mass_per_length * state.segment_length * state.g
    return f[1:] - f[:-1] - w * EZ


def _force_scale(state):
    return state.cable.mass_per_length * state.unstretched_length * state.g + state.tensions.max()


# ------------------------------------------------------------------------------ statics
STATIC_CASES = {
    # name: (anchor, end, L0 / chord, N)
    "taut_11": (A_11, B_11, L0_11 / np.linalg.norm(B_11), 40),
    "slack_1.2": (np.zeros(3), np.array([10.0, 0, 0]), 1.2, 100),
    "slack_1.3_inclined": (A_92, B_92, 1.3, 60),
    "steep_85deg": (np.zeros(3), 10 * np.array([np.cos(np.radians(85)), 0,
                                                np.sin(np.radians(85))]), 1.05, 100),
    "steep_85deg_taut": (np.zeros(3), 10 * np.array([0, np.cos(np.radians(85)),
                                                     -np.sin(np.radians(85))]), 0.999, 50),
    "vertical_down": (np.array([0, 0, 10.0]), np.zeros(3), 0.999, 50),
    "vertical_up": (np.array([1.0, 2.0, 0.0]), np.array([1.0, 2.0, 10.0]), 0.999, 50),
}


@pytest.fixture(scope="module", params=sorted(STATIC_CASES))
def static_case(request):
    anchor, end, ratio, n_segments = STATIC_CASES[request.param]
    L0 = ratio * np.linalg.norm(end - anchor)
    return request.param, chain_equilibrium(anchor, end, L0, CABLE_11, n_segments)


def _dense_interior(ke):
    """K_II of a chain assembled element by element ([[k, -k], [-k, k]] at nodes i, i+1),
    the end nodes dropped."""
    n_el = ke.shape[0]
    K = np.zeros((3 * (n_el + 1),) * 2, dtype=ke.dtype)
    for i, k in enumerate(ke):
        s = slice(3 * i, 3 * i + 6)
        K[s, s] += np.block([[k, -k], [-k, k]])
    return K[3:-3, 3:-3]


# ---------------------------------------------------------------- beaded string (g = 0)
def test_beaded_string_statics_on_chord():
    state, tension = beaded_string(20)
    x = np.linspace(0, BEAD_L, 21)
    np.testing.assert_allclose(state.nodes[:, 0], x, rtol=0, atol=1e-13)
    assert np.all(state.nodes[:, 1:] == 0.0)
    np.testing.assert_allclose(state.tensions, tension, rtol=1e-12)


def test_interior_nodes_in_force_balance(static_case):
    name, state = static_case
    scale = _force_scale(state)
    assert state.residual <= 1e-12 * scale
    # recomputed from the returned nodes and tensions, not trusting state.residual
    assert np.max(np.linalg.norm(_node_forces(state), axis=1)) <= 1e-12 * scale
    # constitutive law on the returned lengths; all segments in tension
    np.testing.assert_allclose(
        state.tensions, CABLE_11.EA * (state.lengths / state.segment_length - 1), rtol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(np.diff(state.nodes, axis=0), axis=1),
                               state.lengths, rtol=1e-12)
    assert np.all(state.tensions > 0)


def test_end_forces_carry_the_interior_weight(static_case):
    name, state = static_case
    weight = (state.n_segments - 1) * state.cable.mass_per_length * state.segment_length * G
    total = state.force_on_anchor + state.force_on_end
    np.testing.assert_allclose(total, -weight * EZ, rtol=0, atol=1e-11 * _force_scale(state))
    # the cable pulls each support along its end segment with the end tension
    np.testing.assert_allclose(np.linalg.norm(state.force_on_end), state.tensions[-1],
                               rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(state.force_on_anchor), state.tensions[0],
                               rtol=1e-14)


def test_chain_lies_in_the_vertical_plane_of_the_chord(static_case):
    name, state = static_case
    chord = state.nodes[-1] - state.nodes[0]
    horizontal = np.hypot(chord[0], chord[1])
    rel = state.nodes - state.nodes[0]
    if horizontal < 1e-12:                                  # vertical chord: on the line
        assert np.max(np.hypot(rel[:, 0], rel[:, 1])) <= 1e-12
        # tensions grow by exactly one node weight per node going up
        w = state.cable.mass_per_length * state.segment_length * G
        step = np.diff(state.tensions) * np.sign(chord[2])
        np.testing.assert_allclose(step, w, rtol=1e-8)
    else:
        normal = np.cross(chord, EZ) / horizontal
        assert np.max(np.abs(rel @ normal)) <= 1e-12 * np.linalg.norm(chord)
        # constant horizontal force component along the chain, H > 0
        f_h = (state.tensions[:, None] * state.units)[:, :2]
        np.testing.assert_allclose(f_h, np.broadcast_to(f_h[0], f_h.shape),
                                   rtol=0, atol=1e-11 * _force_scale(state))
        assert f_h[0] @ chord[:2] > 0


def test_mirror_symmetry_and_reversal():
    anchor, end = np.array([0.3, -1.0, 2.0]), np.array([6.5, 1.5, -3.0])
    L0 = 1.02 * np.linalg.norm(end - anchor)
    state = chain_equilibrium(anchor, end, L0, CABLE_11, 30)
    mirror = np.diag([-1.0, 1.0, 1.0])
    mirrored = chain_equilibrium(mirror @ anchor, mirror @ end, L0, CABLE_11, 30)
    scale = _force_scale(state)
    np.testing.assert_allclose(mirrored.force_on_end, mirror @ state.force_on_end,
                               rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(mirrored.nodes, state.nodes @ mirror, rtol=0, atol=1e-12)
    # swapping the ends renumbers the same chain backwards
    reverse = chain_equilibrium(end, anchor, L0, CABLE_11, 30)
    np.testing.assert_allclose(reverse.force_on_end, state.force_on_anchor,
                               rtol=0, atol=1e-11 * scale)
    np.testing.assert_allclose(reverse.nodes[::-1], state.nodes, rtol=0, atol=1e-12)


def test_theory_11_test_cable():
    # theory.md §1.1: T ~ 1680 N; lumped nodes of 20..320 segments lie on one curve to 1e-10 m
    s20, s40, s80 = (chain_equilibrium(A_11, B_11, L0_11, CABLE_11, n) for n in (20, 40, 80))
    assert abs(s40.tensions[-1] / 1680 - 1) < 0.015
    # straight-chord estimate EA (L/L0 - 1) = 1673.3 N brackets it from above at B (lower)
    assert 1665 < s40.tensions[-1] < s40.tensions[0] < 1680
    d_20_40 = np.max(np.abs(s20.nodes - s40.nodes[::2]))
    d_40_80 = np.max(np.abs(s40.nodes - s80.nodes[::2]))
    assert d_20_40 < 1e-6
    # the nodes converge at second order (error ratio 4 when N doubles)
    assert 3.5 < d_20_40 / d_40_80 < 4.5


@settings(max_examples=40, deadline=None)
# a single vertical segment just shorter than its chord: tension ~1e-12 N, where the start's
# Hessian lost its 1/EA term to the cancellation 1/r - f_z^2/r^3 (LinAlgError, now fixed)
@example(direction=(0.0, 0.0, 1.0), chord=1.5, ratio=0.9999999999999999, n_segments=1,
         log_ea=4.0, log_m=0.0)
@given(direction=st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.1),
       chord=st.floats(0.5, 30.0), ratio=st.floats(0.98, 1.4),
       n_segments=st.integers(1, 120), log_ea=st.floats(3.5, 8.5), log_m=st.floats(-2, 1))
def test_random_geometry_converges_in_balance(direction, chord, ratio, n_segments, log_ea,
                                              log_m):
    # taut, slack, steep and vertical chords alike: converged, or a genuinely slack chain
    end = chord * np.array(direction) / np.linalg.norm(direction)
    cable = Cable(10 ** log_m, 10 ** log_ea)
    try:
        state = chain_equilibrium([0, 0, 0], end, ratio * chord, cable, n_segments)
    except SlackCableError:
        assume(False)
    scale = _force_scale(state)
    if n_segments > 1:
        assert np.max(np.linalg.norm(_node_forces(state), axis=1)) <= 1e-12 * scale
    weight = (n_segments - 1) * cable.mass_per_length * state.segment_length * G
    np.testing.assert_allclose(state.force_on_anchor + state.force_on_end, -weight * EZ,
                               rtol=0, atol=1e-10 * scale)
    assert np.all(state.tensions > 0)


def test_slack_and_degenerate_cables_raise():
    with pytest.raises(SlackCableError):      # no gravity: slack whenever L0 >= chord
        chain_equilibrium([0, 0, 0], [10, 0, 0], 11.0, CABLE_11, 20, g=0)
    with pytest.raises(SlackCableError):      # vertical, L0 = chord: the weight compresses
        chain_equilibrium([0, 0, 0], [0, 0, 10], 10.0, CABLE_11, 20)


def test_convergence_error_reports_residual():
    with pytest.raises(ConvergenceError, match="residual") as info:
        chain_equilibrium(A_92, B_92, 12.0, CABLE_92, 50, tol=1e-300, max_iter=3)
    assert info.value.residual is not None and info.value.residual >= 0


def test_state_is_immutable():
    state = chain_equilibrium(A_11, B_11, L0_11, CABLE_11, 10)
    assert isinstance(state, ChainState)
    with pytest.raises(ValueError):
        state.nodes[1, 0] = 0.0
    with pytest.raises(AttributeError):
        state.g = 1.0


# --------------------------------------------------------------------------- bad inputs
@pytest.mark.parametrize("kwargs, name", [
    (dict(n_segments=0), "n_segments"),
    (dict(n_segments=2.5), "n_segments"),
    (dict(n_segments=True), "n_segments"),
    (dict(unstretched_length=0.0), "unstretched_length"),
    (dict(unstretched_length=-1.0), "unstretched_length"),
    (dict(end=[0.0, 0.0, 0.0]), "end"),
    (dict(anchor=[0.0, 0.0]), "anchor"),
    (dict(g=-9.81), "g"),
    (dict(cable=None), "cable"),
])
def test_chain_equilibrium_rejects_bad_input(kwargs, name):
    args = dict(anchor=[0.0, 0.0, 0.0], end=[7.0, 0.0, -5.0], unstretched_length=8.5,
                cable=CABLE_11, n_segments=10)
    args.update(kwargs)
    with pytest.raises(InvalidParameterError, match=name):
        chain_equilibrium(**args)


def test_chain_functions_refuse_what_is_not_a_chain_state():
    from dynstiff.cable.lumped_chain import check_chain_state
    with pytest.raises(InvalidParameterError) as err:
        check_chain_state("chain")
    assert str(err.value) == "state must be a ChainState, got str"


@pytest.mark.parametrize("drop, k", [(0.0, 5), (2.0, 6), (-4.0, 3)])
def test_a_chain_hanging_from_both_ends_names_its_slack_segment_anywhere_in_space(drop, k):
    """Two ends 0.3 m apart, B `drop` below A, 11 segments of 1 m: the chain hangs
    vertically from both ends and segment k carries no force, where the hanging lengths k
    and 10 - k [m] differ by the height of B over A (10 - 2k = -drop); the error names it,
    wherever the anchor is."""
    A = np.array([1.0, 2.0, 3.0])
    B = A + np.array([0.3, 0.0, -drop])
    with pytest.raises(SlackCableError, match=f"segment {k} of 11 has zero tension"):
        chain_equilibrium(A, B, 11.0, Cable(0.5, 2e5), 11)


def test_chain_input_and_weightless_slack_chains_are_named():
    with pytest.raises(InvalidParameterError, match=r"^end must be finite, got \[1.0, 0.0, nan\]"):
        chain_equilibrium((0, 0, 0), (1, 0, np.nan), 2.0, Cable(0.5, 2e5), 4)
    with pytest.raises(SlackCableError, match="without gravity every segment is slack when "
                                              r"L0 >= chord \(unstretched_length 2 m"):
        chain_equilibrium((0, 0, 0), (1, 0, 0), 2.0, Cable(0.5, 2e5), 4, g=0.0)


def test_a_singular_chain_stiffness_is_solved_with_a_small_positive_shift():
    """A straight chain at zero tension has only axial stiffness (k u u^T): K_II is
    singular. The regularised solve shifts its diagonal by 1e-10 of its largest entry (and
    grows the shift only if that fails): an axial load, in the range of K, is met to 1e-9
    and the transverse motion stays 0."""
    from dynstiff.cable.lumped_chain import _regularised_solve
    from dynstiff.cable.lumped_elements import interior_banded
    u = np.array([0.6, 0.0, 0.8])
    ke = np.broadcast_to(1e4 * np.outer(u, u), (6, 3, 3)).copy()
    rhs = np.outer(np.linspace(1.0, 2.0, 5), u).ravel()
    x = _regularised_solve(interior_banded(ke), rhs)
    assert x is not None
    np.testing.assert_allclose(_dense_interior(ke) @ x, rhs, rtol=0, atol=1e-9 * np.abs(rhs).max())
    np.testing.assert_allclose(x.reshape(5, 3)[:, 1], 0.0, atol=0)


def test_a_newton_without_descent_step_says_so_with_its_residual(monkeypatch):
    """When the tangent stiffness cannot be factorised even shifted, chain_equilibrium
    raises ConvergenceError naming the failure and carrying the residual of its start
    (nonzero: the start is not the equilibrium), instead of returning that start; a bad
    tolerance is named."""
    import dynstiff.cable.lumped_chain as chain
    good = chain_equilibrium(A_11, B_11, L0_11, CABLE_11, 20)
    monkeypatch.setattr(chain, "_regularised_solve", lambda ab, rhs: None)
    with pytest.raises(ConvergenceError, match="no descent step found") as err:
        chain_equilibrium(A_11, B_11, L0_11, CABLE_11, 20)
    assert isinstance(err.value.residual, float) and err.value.residual > good.residual
    with pytest.raises(InvalidParameterError, match="^tol must be"):
        chain_equilibrium(A_11, B_11, L0_11, CABLE_11, 20, tol=-1.0)
    with pytest.raises(InvalidParameterError, match="^anchor must be"):
        chain_equilibrium([np.nan, 0, 0], B_11, L0_11, CABLE_11, 20)


@pytest.mark.parametrize("stretch, turn", [(1.0, 0.0), (1.05, 0.0), (1.05, 0.7)])
def test_force_space_start_is_already_the_equilibrium(stretch, turn):
    """The start solves the chain's own equations in force space (node equilibrium with the
    weight m l0 g per node, segments closing the chord): for the theory.md §1.1 cable, taut
    and 5 % longer (sagging), its chord also turned by 0.7 rad about the vertical, its nodes
    are those of the equilibrium to 1e-12 m."""
    from dynstiff.cable.lumped_chain import _force_space_start
    c, s_ = np.cos(turn), np.sin(turn)
    Rz = np.array([[c, -s_, 0.0], [s_, c, 0.0], [0.0, 0.0, 1.0]])
    A, B = Rz @ np.asarray(A_11, float), Rz @ np.asarray(B_11, float)
    L0 = L0_11 * stretch
    state = chain_equilibrium(A, B, L0, CABLE_11, 20)
    nodes = _force_space_start(A, B, L0, CABLE_11, 20, G)
    np.testing.assert_allclose(nodes, state.nodes, rtol=0, atol=1e-12)


def test_tension_estimate_is_the_parabolic_cable():
    """Inclined chord: L (1 + (8/3)(d/L)^2) = L0 (1 + T/EA), d = q L^2 / (8 T), q = m g
    cos(theta) (theory.md §1.2), checked on the returned T; vertical chord: EA (L/L0 - 1)_+
    + m g L0."""
    from dynstiff.cable.lumped_chain import _tension_estimate
    cab = Cable(0.5, 2e5)
    A, B, L0 = np.zeros(3), np.array([6.0, 0.0, 8.0]), 10.02
    T = _tension_estimate(A, B, L0, cab, G)
    L, q = 10.0, 0.5 * G * 0.6
    assert L * (1 + 8 / 3 * (q * L / (8 * T)) ** 2) == pytest.approx(L0 * (1 + T / 2e5),
                                                                      rel=1e-10)
    V = np.array([0.0, 0.0, 8.0])
    assert _tension_estimate(A, V, 7.99, cab, G) == pytest.approx(
        2e5 * (8.0 / 7.99 - 1) + 0.5 * G * 7.99, rel=1e-14)
    assert _tension_estimate(A, V, 8.01, cab, G) == pytest.approx(0.5 * G * 8.01, rel=1e-14)


def test_the_slack_test_counts_the_stretch_of_the_hanging_segments():
    """Three 1 m segments of a cable with m = 1 kg/m, EA = 100 N under g = 10 m/s^2 (node
    weight w = 10 N, w / EA = 0.1). If the middle segment is slack, segments 0 and 2 hang
    straight down from A and B with tension w, each 1.1 m long, so nodes 1 and 2 lie 1.1 m
    below A and B: the middle segment must bridge B - A itself. B 0.999 m beside A (at the
    same height) is within its 1 m: slack, named in full. B also 0.1 m higher puts the
    gap at hypot(0.999, 0.1) = 1.004 m > 1 m: the chain is taut, in balance, with a small
    middle tension and the end segments carrying about one node weight."""
    cable = Cable(1.0, 100.0)
    with pytest.raises(SlackCableError, match=(
            r"^chain_equilibrium: segment 1 of 3 has zero tension at equilibrium: the chain "
            r"hangs vertically from both ends and that segment is slack \(unstretched_length "
            r"3 m, chord 0\.999 m, g 10 m/s\^2\)$")):
        chain_equilibrium([0.0, 0.0, 0.0], [0.999, 0.0, 0.0], 3.0, cable, 3, g=10.0)
    state = chain_equilibrium([0.0, 0.0, 0.0], [0.999, 0.0, 0.1], 3.0, cable, 3, g=10.0)
    scale = _force_scale(state)
    assert np.max(np.linalg.norm(_node_forces(state), axis=1)) <= 1e-12 * scale
    # middle segment stretched by less than the 4 mm excess of the gap over 1 m
    assert 0.0 < state.tensions[1] < 100.0 * 0.004
    np.testing.assert_allclose(state.tensions[[0, 2]], 10.0, rtol=1e-2)


def test_a_wrong_cable_or_gravity_is_named_in_full():
    """A cable that is not a Cable is refused naming the type given; a gravity below zero is
    refused naming g and its bound (g = 0 is allowed)."""
    with pytest.raises(InvalidParameterError, match=r"^cable must be a Cable, got str$"):
        chain_equilibrium([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.2, "chain", 3)
    with pytest.raises(InvalidParameterError, match=r"^g must be >= 0, got -9\.81$"):
        chain_equilibrium([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.2, Cable(0.5, 2e5), 3, g=-9.81)
