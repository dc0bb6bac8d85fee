"""Wittrick-Williams eigenfrequencies, mode counts and cable fields (dynstiff/analyses/eigen.py,
theory.md §5).

W-W never misses a root: its count against an independent lumped-mass model (theory.md §7)
on a point-mass robot and as a property test on random 3-cable point-mass robots; coincident
and close roots of a symmetric robot; a dense determinant scan that does miss the coincident
roots of a symmetric robot. Cable displacement fields of a mode meet the platform."""

import warnings

import numpy as np
import pytest
from conftest import lumped_point_mass_frequencies, point_mass_robot
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff import compiled
from dynstiff.analyses.modes import cable_fields
from dynstiff.errors import InvalidParameterError, SlackCableError

N_SEG = 40                    # lumped segments per cable
M_CABLE = 0.064               # [kg/m], CoGiRo cable (theory.md §8.1)
AREA = 8.2051e-6              # [m^2]
N_COMPARED = 20               # lowest modes of the continuous model compared


# -------------------------------------------------------------- W-W against lumped mass
def test_wittrick_williams_count_equals_lumped_model_count():
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.2, -0.1, 1.0])
    m = ds.FrequencyModel(eq)
    f = ds.eigenfrequencies(m, 30)
    f_lumped = lumped_point_mass_frequencies(eq, 80, n_modes=30)
    # same number of modes below every probe frequency away from any mode
    probes = np.linspace(0.5, 0.97 * f[-1], 400)
    gap = np.min(np.abs(probes[:, None] / np.concatenate([f, f_lumped])[None, :] - 1), axis=1)
    probes = probes[gap > 0.004]
    J = ds.mode_count(m, 2 * np.pi * probes)
    J_lumped = np.searchsorted(f_lumped, probes)
    np.testing.assert_array_equal(J, J_lumped)
    np.testing.assert_allclose(f, f_lumped, rtol=3e-3)   # discretisation O((n pi/N)^2/24)


def test_close_and_coincident_roots_are_found():
    """A symmetric robot: three identical cables at 120 deg give double roots."""
    ang = np.radians([90, 210, 330])
    anchors = np.column_stack([5 * np.cos(ang), 5 * np.sin(ang), np.full(3, 5.0)])
    rob = ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(20.0, free_dofs=("x", "y", "z")))
    eq = rob.equilibrium(pose=[0, 0, 1.0])
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), 26)
    pairs = np.sum(np.abs(np.diff(f)) < 1e-6 * f[1:])
    assert pairs >= 3                                      # coincident roots resolved
    J = ds.mode_count(ds.FrequencyModel(eq), 2 * np.pi * f[:20] * (1 + 1e-7))
    np.testing.assert_array_equal(J, [np.sum(f <= fk * (1 + 1e-9)) for fk in f[:20]])


def test_close_pairs_are_found():
    """Break the symmetry slightly: each double root splits into a pair < 1e-4 apart
    (relative); W-W finds both members and the count steps by one at each."""
    ang = np.radians([90, 210, 330])
    anchors = np.column_stack([5 * np.cos(ang), 5 * np.sin(ang), np.full(3, 5.0)])
    anchors[0, 0] += 2e-5                                   # 20 micrometres
    rob = ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(20.0, free_dofs=("x", "y", "z")))
    m = ds.FrequencyModel(rob.equilibrium(pose=[0, 0, 1.0]))
    f = ds.eigenfrequencies(m, 32)
    gaps = np.diff(f) / f[1:]
    close = np.flatnonzero((gaps > 0) & (gaps < 1e-4))
    close = close[close + 2 < len(f)]                      # the next mode up is known
    assert len(close) >= 3
    for k in close:
        mid = 0.5 * (f[k] + f[k + 1])
        lo, hi = f[k] - 0.25 * (f[k + 1] - f[k]), f[k + 1] + 0.25 * (f[k + 1] - f[k])
        if hi >= f[k + 2] or (k > 0 and lo <= f[k - 1]):
            continue                                       # a third close root: tested below
        np.testing.assert_array_equal(ds.mode_count(m, 2 * np.pi * np.array([lo, mid, hi])),
                                      [k, k + 1, k + 2])
    # every computed root is a distinct step of the count, even in triplets 6e-7 apart
    between = 0.5 * (f[1:] + f[:-1])
    np.testing.assert_array_equal(ds.mode_count(m, 2 * np.pi * between), np.arange(1, len(f)))


# ------------------------------------------------------------------------ random robots
def highest_harmonic(eq, f_hz):
    """Largest clamped-string harmonic number n = 2 f L sqrt(m/T) over the cables at f_hz."""
    return max(2 * f_hz * s.chord_length * np.sqrt(M_CABLE / s.mean_tension) for s in eq.states)


def probe_gap(eq, f_hz, n_seg):
    """Relative distance kept between probes and modes: 1 %, or twice the beaded-string error
    (n pi / N)^2 / 24 of the highest harmonic compared (theory.md §7.2) if larger."""
    n = np.ceil(highest_harmonic(eq, f_hz))
    return max(0.01, 2 * (n * np.pi / n_seg) ** 2 / 24)


def count_check(eq):
    """W-W count and lumped count at probes between the modes; returns the numbers."""
    model = ds.FrequencyModel(eq)
    f = ds.eigenfrequencies(model, N_COMPARED)
    fmax = f[-1]
    gap = probe_gap(eq, fmax, N_SEG)
    fl = lumped_point_mass_frequencies(eq, N_SEG, fmax_hz=1.5 * fmax)
    allf = np.sort(np.concatenate([f, fl]))
    # midpoints between neighbouring modes of both models, plus a uniform grid
    cand = np.concatenate([0.5 * (allf[1:] + allf[:-1]), np.linspace(0.02, 1.0, 200) * fmax])
    cand = cand[cand < fmax * (1 - gap)]
    dist = np.min(np.abs(cand[:, None] / allf[None, :] - 1.0), axis=1)
    probes = np.unique(cand[dist > gap])
    J = ds.mode_count(model, 2 * np.pi * probes)
    J_lumped = np.searchsorted(fl, probes)
    return dict(probes=probes, J=J, J_lumped=J_lumped, f=f, fl=fl, gap=gap)


#: Least cable tension [N] of the random robots. Irvine's linear theory gives each cable one
#: (mean) tension; the static tension varies along a cable by m g dz, and below ~15 N here
#: (m g dz / T above ~15 %) the DSM and the converged lumped model differ by 0.4-5 % (measured
#: by Richardson extrapolation from N = 80, 160 on 80 random robots), a model error larger
#: than the probe gap and no fault of the W-W count. From 20 N up they agree within 0.16 %.
T_MIN = 20.0


def random_robot(radius, angles, heights, mass, E):
    anchors = np.column_stack([radius * np.cos(angles), radius * np.sin(angles), heights])
    return ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(M_CABLE, AREA * E),
                    ds.Platform(mass, free_dofs=("x", "y", "z")), tension_limits=(T_MIN, np.inf))


@settings(max_examples=15, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(radius=st.floats(3.0, 6.0),
       turn=st.floats(0.0, 2 * np.pi),
       jitter=st.lists(st.floats(-0.5, 0.5), min_size=3, max_size=3),
       heights=st.lists(st.floats(4.0, 6.0), min_size=3, max_size=3),
       mass=st.floats(5.0, 50.0),
       E=st.floats(17e9, 120e9),
       xy=st.lists(st.floats(-0.5, 0.5), min_size=2, max_size=2),
       z=st.floats(1.0, 2.0))
def test_ww_count_equals_lumped_count_on_random_robots(radius, turn, jitter, heights, mass, E,
                                                       xy, z):
    """Random 3-cable point-mass robots (anchors 120 deg +- 29 deg apart on a circle of radius
    3-6 m at 4-6 m height, 5-50 kg, E 17-120 GPa, pose within 0.5 m of the axis at z = 1-2 m):
    W-W and the lumped model count the same number of modes below every probe frequency
    (probes kept away from every mode of both models) over the lowest 20 modes, so W-W misses
    no root and adds none."""
    angles = turn + np.radians([0.0, 120.0, 240.0]) + np.asarray(jitter)
    rob = random_robot(radius, angles, np.asarray(heights), mass, E)
    try:
        eq = rob.equilibrium(pose=[xy[0], xy[1], z])
    except SlackCableError:
        assume(False)                 # a cable below T_MIN (or slack): outside the workspace
    with warnings.catch_warnings():   # the counts are compared, not the closed form's
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)    # accuracy: its guard
        r = count_check(eq)                                             # may warn here
    np.testing.assert_array_equal(r["J"], r["J_lumped"])
    # the comparison is not vacuous: many probes, up to at least 3/4 of the band, counting at
    # least half the modes compared (the top modes may sit within the gap of the band's end)
    assert r["probes"].size >= 50
    assert r["probes"].max() >= 0.75 * r["f"][-1]
    assert r["J"].max() >= N_COMPARED // 2


# ------------------------------------------------------------------- why not a det scan
def symmetric_robot():
    """Three identical cables at 120 deg, platform on the axis: double roots (x-y symmetry)
    and purely local cable modes (platform at rest) on the coinciding cable poles."""
    ang = np.radians([90, 210, 330])
    anchors = np.column_stack([5 * np.cos(ang), 5 * np.sin(ang), np.full(3, 5.0)])
    rob = ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(M_CABLE, 1.4e5),
                   ds.Platform(20.0, free_dofs=("x", "y", "z")))
    return rob.equilibrium(pose=[0, 0, 1.0])


def test_determinant_scan_misses_roots_that_ww_finds():
    """A dense scan of det K(omega) (2e5 points to 12 Hz, sign changes across cable poles
    discarded) finds only the odd-multiplicity roots off the poles: 4 of the 21 roots W-W
    counts. Missed: the double roots of the x-y symmetry (no sign change) and the purely local
    modes sitting on the poles (no zero of det K). This is why dynstiff uses W-W (theory.md
    §5)."""
    eq = symmetric_robot()
    model = ds.FrequencyModel(eq)
    fmax = 12.0
    f = ds.eigenfrequencies(model, fmax_hz=fmax)
    n_ww = f.size
    assert n_ww == ds.mode_count(model, 2 * np.pi * fmax)[0]
    # the scan
    fg = np.linspace(0.05, fmax, 200_000)
    w = 2 * np.pi * fg
    det = np.linalg.det(model.dynamic_stiffness(w))
    J0 = model.cable_mode_count(w)
    change = np.sign(det[1:]) * np.sign(det[:-1]) < 0
    no_pole = J0[1:] == J0[:-1]
    n_raw = int(change.sum())                      # poles included
    n_scan = int((change & no_pole).sum())         # poles excluded: candidate roots
    # what a sign scan can see: clusters of equal roots, off the poles, of odd multiplicity
    clusters = np.split(f, np.flatnonzero(np.diff(f) > 1e-6 * f[1:]) + 1)
    visible = 0
    for c in clusters:
        lo, hi = model.cable_mode_count(2 * np.pi * c[0] * np.array([1 - 1e-9, 1 + 1e-9]))
        visible += int(hi == lo and len(c) % 2 == 1)
    assert sum(len(c) > 1 for c in clusters) >= 6     # repeated roots present
    assert n_scan == visible
    assert n_scan < n_ww and n_raw < n_ww


# ------------------------------------------------------------------------- cable fields
@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def test_cable_fields_are_continuous_with_the_platform(scene):
    m = ds.FrequencyModel(scene.equilibrium())
    modes = ds.modes(m, 6)
    for k in np.flatnonzero(np.array(modes.kind) == "global")[:2]:
        pos, disp = cable_fields(m, modes, k)
        x6 = modes.platform_shapes[k]
        np.testing.assert_allclose(disp[:, 0], 0.0, atol=1e-12)       # anchors clamped
        for i, r in enumerate(m.lever_arms):
            np.testing.assert_allclose(disp[i, -1], x6[:3] + np.cross(x6[3:], r), rtol=1e-9,
                                       atol=1e-12)
        np.testing.assert_allclose(pos[:, -1], [s.end for s in m.equilibrium.states], atol=1e-12)


def test_cable_energy_fraction_is_the_frequency_derivative_of_the_dynamic_stiffness(cogiro_eq):
    """For a dynamic stiffness K(omega) = K_s(omega) - omega^2 M_p, the kinetic energy of a
    mode per unit omega^2 / 2 is -x^T dK/d(omega^2) x (Rayleigh; theory.md §6). With
    x^T M_p x = 1 the cable fraction is therefore 1 - 1 / (-x^T dK/d(omega^2) x), which the
    closed-form field integrals (chordwise term m L/3 |u_B|^2 included) must reproduce."""
    m = ds.FrequencyModel(cogiro_eq)
    md = ds.modes(m, 12)
    checked = 0
    for k in np.flatnonzero(np.array(md.kind) == "global"):
        w = 2 * np.pi * md.freq_hz[k]
        h = 1e-7 * w
        x = md.platform_shapes[k][m.free_index]
        dK = (m.dynamic_stiffness(w + h)[0] - m.dynamic_stiffness(w - h)[0]) / (2 * h)
        q = -(x @ (dK / (2 * w)) @ x)
        assert md.cable_energy_fraction[k] == pytest.approx(1 - 1 / q, abs=1e-8)  # measured 5e-10
        checked += 1
    assert checked >= 3


@pytest.mark.parametrize("kw, match", [
    ({"n_modes": 2.5, "fmax_hz": 5.0}, "n_modes must be an integer"),
    ({"n_modes": 0, "fmax_hz": 5.0}, "n_modes must be an integer"),
    ({"n_modes": np.nan}, "n_modes must be an integer"),
    ({"n_modes": "3"}, "n_modes must be an integer"),
    ({"fmax_hz": np.nan}, "fmax_hz must be finite"),
    ({"fmax_hz": "5"}, "fmax_hz must be finite"),
    ({"fmax_hz": [5.0]}, "fmax_hz must be finite"),
    ({"fmax_hz": 5.0 + 1j}, "fmax_hz must be finite"),
    ({}, "give n_modes or fmax_hz"),
    ({"fmax_hz": 1e9}, r"fmax_hz = 1e\+09 Hz is out of the 'dsm' model's range"),
    ({"fmax_hz": 3000.0, "max_modes": 100}, "holds .* modes, more than max_modes = 100"),
    ({"n_modes": 101, "max_modes": 100}, "more than max_modes"),
    ({"n_modes": 2, "max_modes": 2.5}, r"^max_modes must be an integer >= 1, got 2\.5$"),
    ({"n_modes": 2, "max_modes": True}, "^max_modes must be an integer >= 1, got True$"),
    ({"n_modes": 2, "max_modes": 0}, "^max_modes must be an integer >= 1, got 0$"),
    ({"n_modes": 2, "rtol": 0}, r"^rtol must be a number in \(0, 1e-2\), got 0$"),
])
def test_bad_mode_requests_name_the_argument(cogiro_eq, kw, match):
    m = ds.FrequencyModel(cogiro_eq, guard_rtol=None)       # the request's errors alone
    with pytest.raises(InvalidParameterError, match=match):
        ds.eigenfrequencies(m, **kw)


def test_mode_count_at_an_absurd_frequency_is_refused_by_every_rung(cogiro_eq):
    for rung in ("catenary", "dsm"):
        with pytest.raises(InvalidParameterError, match="omega must be <="):
            ds.mode_count(ds.build_model(cogiro_eq, rung), 1e300)


def test_every_rung_validates_its_mode_request(cogiro_eq):
    for rung in ds.RUNGS:
        m = ds.build_model(cogiro_eq, rung, segments=4)
        for kw in ({"fmax_hz": np.nan}, {"n_modes": 2.5, "fmax_hz": 5.0},
                   {"n_modes": 0, "fmax_hz": 5.0}):
            with pytest.raises(InvalidParameterError, match="n_modes|fmax_hz"):
                ds.eigenfrequencies(m, **kw)
    for method in ("matrix", "wittrick-williams"):     # the spring model's 6 DOFs: no 7th
        with pytest.raises(InvalidParameterError, match=r"^n_modes must be an integer in \[1, 6"):
            ds.eigenfrequencies(ds.build_model(cogiro_eq, "spring"), 7, method=method)


def test_an_integer_beyond_the_float_range_is_named(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    for f in (10**20, 10**400):
        with pytest.raises(InvalidParameterError, match="fmax_hz"):
            ds.eigenfrequencies(m, fmax_hz=f)


def test_numpy_count_path_finds_the_same_frequencies(cogiro_eq, monkeypatch):
    """Without numba the count is K(omega) (cable kernels shared with J0) and a batched
    eigvalsh: the same frequencies as the compiled count, to the bracket width."""
    pytest.importorskip("numba")
    m = ds.build_model(cogiro_eq, "dsm")
    f = ds.eigenfrequencies(m, fmax_hz=10.0)
    monkeypatch.setattr(compiled, "load", lambda name: None)
    f0 = ds.eigenfrequencies(m, fmax_hz=10.0)
    assert len(f) == len(f0) == ds.mode_count(m, 2 * np.pi * 10.0)[0]
    np.testing.assert_allclose(f, f0, rtol=2e-12)


def _run_illinois(fs, lo, hi, rtol=1e-12):
    from dynstiff.analyses.eigen import _illinois
    calls = []

    def count(x):
        calls.append(x.size)
        return None, np.stack([f(x) for f in fs], axis=1)

    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    f_lo = np.array([f(a) for f, a in zip(fs, lo)])
    f_hi = np.array([f(b) for f, b in zip(fs, hi)])
    return _illinois(count, lo, hi, np.arange(len(fs)), f_lo, f_hi, rtol), calls


def test_illinois_converges_superlinearly_and_stops_on_an_exact_zero():
    """The bracketed search of theory.md §14.2 on four decreasing functions with known roots
    (2, 3, the root of cos x = 0.3 x, 1.7): every root to 1e-12 in at most 10 batched
    evaluations (bisection would need about 40), and the linear one exactly (its first
    secant point is the root, where the bracket closes at once)."""
    from scipy.optimize import brentq
    fs = [lambda x: 4.0 - x**2, lambda x: 3.0 - x, lambda x: np.cos(x) - 0.3 * x,
          lambda x: np.tanh(5 * (1.7 - x))]
    roots, calls = _run_illinois(fs, [0.5, 1.0, 0.0, 0.3], [3.0, 5.0, 2.0, 3.1])
    ref = [2.0, 3.0, brentq(fs[2], 0.0, 2.0, xtol=1e-15), 1.7]
    np.testing.assert_allclose(roots, ref, rtol=1e-12)
    assert roots[1] == 3.0
    assert len(calls) <= 10                                # measured: 6
    assert calls[0] == 8 and calls[-1] <= 4                # converged brackets drop out


def test_illinois_takes_a_root_on_the_brackets_lower_end_quietly():
    """The search's contract allows f_lo = 0 (f_lo >= 0 > f_hi): for 2 - x on [2, 4] the root
    is the lower end itself. The Anderson-Bjorck factor 1 - f_new / f_lo divides by that zero
    (the factor is then replaced by 1/2); it must do so under its errstate, with no
    RuntimeWarning (an error in this suite), and the root 2 is found to rtol."""
    roots, _ = _run_illinois([lambda x: 2.0 - x], [2.0], [4.0])
    assert roots[0] == pytest.approx(2.0, rel=1e-12)


def test_illinois_on_a_strongly_curved_function_halves_its_bracket_and_converges():
    """exp(8 (1 - x)) - 1 on [0.1, 3] (values 1300 and -1): plain regula falsi creeps from
    the flat end (0.2 % per step; 100 steps left [0.1, 2.96]). A bracket that has not halved
    in three steps is bisected, so the root 1 is found to 1e-12 in at most 4 log2(2.9 / 1e-12)
    steps (measured: 16), and a search that cannot finish says so with its width."""
    from dynstiff.analyses.eigen import _illinois
    from dynstiff.errors import ConvergenceError
    f = [lambda x: np.exp(8.0 * (1.0 - x)) - 1.0]
    roots, calls = _run_illinois(f, [0.1], [3.0])
    assert roots[0] == pytest.approx(1.0, rel=1e-12)
    assert len(calls) <= 25
    with pytest.raises(ConvergenceError, match="wider than rtol = 1e-12 after 5 steps") as err:
        _illinois(lambda x: (None, f[0](x)[:, None]), np.array([0.1]), np.array([3.0]),
                  np.array([0]), f[0](np.array([0.1])), f[0](np.array([3.0])), 1e-12,
                  max_iter=5)
    assert err.value.residual > 1e-3


def test_purely_local_modes_sit_on_the_cable_poles_with_the_platform_at_rest():
    """planar2 moves in x and z only: each cable's out-of-plane (y) modes leave the platform
    at rest. They are found on the cables' clamped out-of-plane frequencies n pi sqrt(T/m)
    / L (both cables, a double root), with a zero platform shape and all of the kinetic
    energy in the cables (fraction exactly 1)."""
    eq = ds.load_scene("planar2").equilibrium()
    m = ds.FrequencyModel(eq)
    r = ds.modes(m, 12)
    p = m.params[0]
    at_rest = np.flatnonzero(np.abs(r.platform_shapes).max(axis=1) == 0.0)
    assert len(at_rest) == 6
    np.testing.assert_array_equal(r.cable_energy_fraction[at_rest], 1.0)
    assert all(r.kind[k] == "local" for k in at_rest)
    f_oop = np.arange(1, 4) * np.sqrt(p.T / p.m) / (2 * p.L)
    np.testing.assert_allclose(r.freq_hz[at_rest], np.repeat(f_oop, 2), rtol=1e-9)
    moving = np.setdiff1d(np.arange(12), at_rest)
    assert np.all(r.cable_energy_fraction[moving] < 1.0)


def test_cable_fields_follow_the_mode_and_name_what_other_rungs_offer(cogiro_eq):
    """``cable_fields`` is the model's cable displacement at the mode's own frequency and
    platform shape, on ``n_points`` points; rungs without a continuous field say so."""
    from dynstiff.errors import UnsupportedAnalysisError
    m = ds.FrequencyModel(cogiro_eq)
    r = ds.modes(m, 3)
    pos, disp = ds.cable_fields(m, r, 2, n_points=11)
    ref = m.cable_displacements(2 * np.pi * r.freq_hz[2], r.platform_shapes[2], 11)
    assert pos.shape == disp.shape == (8, 11, 3)
    np.testing.assert_array_equal(pos, ref[0])
    np.testing.assert_array_equal(disp, ref[1])
    for rung, tail in (("spring", " (massless cables)"),
                       ("lumped", ": its node motions are modes(model, ...).node_shapes")):
        other = ds.build_model(cogiro_eq, rung, **({"segments": 4} if rung == "lumped" else {}))
        with pytest.raises(UnsupportedAnalysisError) as err:
            ds.cable_fields(other, ds.modes(other, 2), 0)
        assert str(err.value).endswith("model has none" + tail)


def test_mode_requests_at_the_limits_of_max_modes_and_of_the_exact_band(cogiro_eq, soft_exact):
    """n_modes equal to max_modes is allowed even when fmax_hz holds more modes (the first
    n_modes are returned); asking the exact rung for more modes than its band holds names
    the band, not the cable's refusal of a frequency; Wittrick-Williams mode shapes of a
    discrete rung name the method to use."""
    from dynstiff.errors import UnsupportedAnalysisError
    m, eq = soft_exact
    dsm = ds.FrequencyModel(cogiro_eq)
    assert ds.mode_count(dsm, 2 * np.pi * 15.0)[0] > 6
    f = ds.eigenfrequencies(dsm, n_modes=6, fmax_hz=15.0, max_modes=6)
    np.testing.assert_allclose(f, ds.eigenfrequencies(dsm, n_modes=6), rtol=1e-12)
    with pytest.raises(InvalidParameterError,
                       match=r"^n_modes = 10000 asks for more than the 'exact' model's band "
                             r"holds \(\d+ modes below 3 Hz\); build it with a larger fmax_hz"):
        ds.eigenfrequencies(m, n_modes=10000)
    spring = ds.build_model(eq, "spring")
    with pytest.raises(UnsupportedAnalysisError) as err:
        ds.modes(spring, 2, method="wittrick-williams")
    assert str(err.value) == ("modes by Wittrick-Williams need the cables' kinetic energy of "
                              "a continuous rung; use method='matrix' for the 'spring' model")


@pytest.fixture(scope="module")
def soft_exact():
    """planar2 with soft heavy cables (1 kg/m, EA 2e4 N), 10 m below the anchors, and its
    exact model up to 3 Hz."""
    import dataclasses
    r = ds.load_scene("planar2").robot
    rob = dataclasses.replace(r, cables=(ds.Cable(1.0, 2.0e4),) * 2)
    eq = rob.equilibrium(ds.Pose([0, 0, -10]))
    return ds.build_model(eq, "exact", fmax_hz=3.0), eq


# the closed form's robot-level bound warns on sixcable and fast (theory.md §11.6): not the subject
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
@pytest.mark.parametrize("name, fmax_hz", [("planar2", 200.0), ("sixcable", 50.0)])
def test_the_roots_do_not_depend_on_the_band_asked(name, fmax_hz):
    """The lowest roots are the same whether 5 Hz or a wide band is asked, though in the
    wide one the first mode lies below the first point of the count's grid (fmax / 64)."""
    m = ds.FrequencyModel(ds.load_scene(name).equilibrium())
    low = ds.eigenfrequencies(m, fmax_hz=5.0)
    wide = ds.eigenfrequencies(m, fmax_hz=fmax_hz)
    assert low[0] < fmax_hz / 64 and len(wide) > len(low) > 0
    np.testing.assert_allclose(wide[:len(low)], low, rtol=1e-11)


@pytest.mark.parametrize("rung", ["spring", "dsm", "lumped"])
@pytest.mark.parametrize("fmax_hz", [1e152, 1e160, 1e300])
def test_a_band_beyond_every_frequency_names_fmax_hz(cogiro_eq, rung, fmax_hz):
    """fmax_hz whose omega^2 overflows (omega = 2 pi fmax_hz > 1e150 rad/s) is refused naming
    fmax_hz, by the finite eigenproblem and by Wittrick-Williams alike (it named the internal
    omega, or overflowed in the seed grid)."""
    m = ds.build_model(cogiro_eq, rung, **({"segments": 4} if rung == "lumped" else {}))
    with pytest.raises(InvalidParameterError, match=r"^fmax_hz must be <= 1\.59155e\+149 Hz"):
        ds.eigenfrequencies(m, fmax_hz=fmax_hz)
    with pytest.raises(InvalidParameterError, match=r"^fmax_hz must be <= "):
        ds.modes(m, fmax_hz=fmax_hz)


@pytest.mark.parametrize("f, lo, hi, root, most", [
    (lambda x: np.exp(-8 * x) - np.exp(-8 * 1.3), 0.05, 3.0, 1.3, 16),   # strongly convex
    (lambda x: (1.7 - x)**3 + 0.01 * (1.7 - x), 0.1, 4.0, 1.7, 26),      # flat at its root
    (lambda x: np.tan(1.5 - 0.5 * x), 0.2, 5.5, 3.0, 13)])
def test_the_regula_falsi_closes_its_bracket_in_few_evaluations(f, lo, hi, root, most):
    """The root to rtol = 1e-12 in 11-23 batched evaluations (measured: 14, 23, 11; each
    iterate with its second point), where bisection needs 41: the Illinois steps, the
    Anderson-Bjorck scaling and the closing pair each count (theory.md §14.2). A step rule
    that falls back to bisection, or a pair that no longer closes the bracket, passes the
    bound; the root stays exact."""
    roots, calls = _run_illinois([f], [lo], [hi])
    assert roots[0] == pytest.approx(root, rel=1e-12)
    assert len(calls) <= most


def test_the_compiled_search_that_cannot_finish_names_its_root_and_width():
    """The compiled search of the closed form, stopped after one step: the first root's
    bracket is still wide, and the error says which root, the tolerance and the steps."""
    from dynstiff import compiled
    from dynstiff.analyses.eigen import _counter
    from dynstiff.errors import ConvergenceError
    if compiled.load("dsm") is None:
        pytest.skip("numba is not installed: no compiled search")
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    count = _counter(m)
    grid = np.linspace(0.0, 2 * np.pi * 3.0, 9)
    J, J0, det = count.counts(grid)
    with pytest.raises(ConvergenceError, match=r"^the regula falsi left the bracket of root 1 "
                                               r"wider than rtol = 1e-12 after 1 steps") as err:
        count.search(grid, J, det, J0, int(J[-1]), 1e-12, max_iter=1)
    assert err.value.residual > 1e-12


def test_seed_grid_and_max_modes_reached_exactly(cogiro_eq):
    """Seed grid (§14.2; spring: K = K0), max_modes reached exactly."""
    m = ds.StaticCableModel(cogiro_eq, "spring")
    w0 = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(m.platform_mass, m.K)).real))
    ref = np.sort(np.r_[np.linspace(0.0, 27.0, 65), w0[:4], 1.001 * w0[:4]])  # w0[3:5]: 23, 31
    np.testing.assert_allclose(ds.analyses.eigen._seed_grid(m, 27.0), ref, rtol=1e-12)
    for kw in ({"fmax_hz": w0[-1], "max_modes": 6}, {"n_modes": 6, "method": "wittrick-williams"}):
        np.testing.assert_allclose(ds.eigenfrequencies(m, **kw), w0 / (2 * np.pi), rtol=1e-10)
