"""The frequency-optimal tension distribution (dynstiff/analyses/optimal_tensions.py,
theory.md §16.7): the optimum against its neighbours in the tension null space and against
a brute-force search over it, the limits along every cable, what binds, warm starts."""

import re
from collections import deque

import numpy as np
import pytest
from conftest import inverted_stewart

import dynstiff as ds
from dynstiff.analyses.optimal_tensions import optimal_tensions, tension_equilibrium
from dynstiff.analyses.platform_modes import find_platform_modes
from dynstiff.errors import InvalidParameterError


def first_platform_hz(robot, pose, reference):
    eq = robot.equilibrium(pose=pose, tension_reference=reference)
    return find_platform_modes(ds.FrequencyModel(eq, guard_rtol=None)).first_hz, eq


def null_basis(opt):
    import scipy.linalg
    eq = opt.default
    u = np.array([s.force_on_end / s.tension_at_end for s in eq.states])
    W = np.vstack([u.T, np.cross(eq.lever_arms, u).T])
    return scipy.linalg.null_space(W)


@pytest.mark.parametrize("position, binds", [([4.0, -2.5, 1.0], "at t_min"),
                                             ([2.0, 1.5, 1.5], "smooth maximum")])
def test_the_optimum_beats_its_neighbours_and_keeps_the_limits(cogiro, position, binds):
    """At a pose where two cables reach t_min (a vertex of the feasible polygon) and at one
    with a smooth interior maximum, no distribution 5 N away along the null space does
    better, the tensions stay within [t_min, t_max] all along every cable, and the first
    platform mode rises over the default distribution's (0.085 and 0.0057 Hz)."""
    rob = cogiro.robot
    opt = optimal_tensions(rob, position)
    t_min, t_max = rob.tension_limits
    assert opt.equilibrium.min_tensions.min() >= t_min - 1e-6
    assert opt.equilibrium.max_tensions.max() <= t_max
    assert opt.gain > 5e-3
    assert any(binds in b for b in opt.binds), opt.binds
    N = null_basis(opt)
    for d in (N[:, 0], -N[:, 0], N[:, 1], -N[:, 1]):
        f, eq = first_platform_hz(rob, position, opt.reference + 5.0 * d)
        assert f <= opt.value + 1e-5 * opt.value, (d, f, opt.value)


def test_band_margin_objective_and_warm_start(cogiro):
    """The band margin of a band just below the first platform mode rises with the
    tensions; a warm start from the optimum needs fewer equilibria and finds it again."""
    rob, pose = cogiro.robot, [4.0, -2.5, 1.0]
    opt = optimal_tensions(rob, pose, objective="band_margin", band_hz=(0.0, 2.0))
    assert opt.value > opt.default_value
    first = optimal_tensions(rob, pose)
    again = optimal_tensions(rob, pose, start=first)
    assert again.evaluations < first.evaluations
    assert again.value == pytest.approx(first.value, rel=1e-5)
    eq = tension_equilibrium(rob, pose, "max-frequency", start=first.equilibrium)
    np.testing.assert_allclose(eq.tensions, first.tensions, rtol=1e-3)
    np.testing.assert_allclose(tension_equilibrium(rob, pose).tensions,
                               rob.equilibrium(pose=pose).tensions)


def test_without_redundancy_the_distribution_is_the_default():
    rob = inverted_stewart()
    opt = optimal_tensions(rob, [0.0, 0.0, 1.5], rung="spring")
    assert opt.gain == 0.0 and "no redundancy" in opt.binds[0]


def test_bad_requests_are_refused(cogiro):
    rob = cogiro.robot
    with pytest.raises(InvalidParameterError, match="objective must be one of"):
        optimal_tensions(rob, [0, 0, 1], objective="stiffness")
    with pytest.raises(InvalidParameterError, match="needs band_hz"):
        optimal_tensions(rob, [0, 0, 1], objective="band_margin")
    for band in ((2.0, 1.0), (-1.0, 2.0), (1.0, 1.0)):     # not 0 <= lo < hi
        with pytest.raises(InvalidParameterError, match=r"^band_hz must be \(lo, hi\), "
                           r"0 <= lo < hi \[Hz\], got " + re.escape(repr(band)) + "$"):
            optimal_tensions(rob, [0, 0, 1], objective="band_margin", band_hz=band)
    with pytest.raises(InvalidParameterError, match="start must be"):
        optimal_tensions(rob, [0, 0, 1], start=[1.0, 2.0])
    with pytest.raises(InvalidParameterError, match="tensions must be one of"):
        tension_equilibrium(rob, [0, 0, 1], "stiff")


def brute_force(robot, pose, opt, step, continuity=0.02):
    """The first platform mode on a grid of the tension null space (step [N]) around the
    default distribution, and its best value on the default's branch: the grid cells
    reached from the default through neighbours whose objective differs by less than
    ``continuity`` (relative); a larger difference is a jump (a platform mode crossing a
    cable mode changes which mode is the first platform mode, theory.md §16.7)."""
    N = null_basis(opt)
    t0 = opt.default.tensions
    g = np.arange(-600.0, 600.0 + step, step)
    F = np.full((g.size, g.size), np.nan)
    t_min, t_max = robot.tension_limits
    for i, a in enumerate(g):
        for j, b in enumerate(g):
            t = t0 + N @ [a, b]
            if t.min() < t_min - 50 or t.max() > t_max:
                continue
            try:
                f, eq = first_platform_hz(robot, pose, t)
            except ds.DynstiffError:
                continue
            if np.abs(eq.tensions - t).max() <= 1.0:       # not clipped to a limit
                F[i, j] = f
    i0 = int(np.argmin(np.abs(g)))
    seen = np.zeros(F.shape, bool)
    seen[i0, i0] = True
    todo = deque([(i0, i0)])
    while todo:
        i, j = todo.popleft()
        for a, b in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
            if 0 <= a < g.size and 0 <= b < g.size and not seen[a, b] \
                    and abs(F[a, b] - F[i, j]) <= continuity * F[i, j]:
                seen[a, b] = True
                todo.append((a, b))
    k = np.unravel_index(np.nanargmax(np.where(seen, F, np.nan)), F.shape)
    return F[k], np.array([g[k[0]], g[k[1]]]), N.T @ (opt.reference - t0)


@pytest.mark.slow
@pytest.mark.parametrize("position", [[2.0, 1.5, 1.5], [4.0, -2.5, 1.0],
                                      [-4.5, -3.0, 0.8], [3.0, 3.0, 2.0]])
def test_the_optimum_matches_a_brute_force_search(cogiro, position):
    """At 4 CoGiRo poses the search finds at least the best first platform mode of a 12.5 N
    grid of the null space on the default's branch, within one grid step of its cell (a
    vertex of the feasible polygon, where tension limits bind, may lie further from the
    grid's cells: the grid keeps only distributions within the limits)."""
    rob = cogiro.robot
    opt = optimal_tensions(rob, position)
    step = 12.5
    best, cell, lam = brute_force(rob, position, opt, step)
    assert opt.value >= best - 1e-5 * best
    at_limit = any("at t_min" in b or "at t_max" in b for b in opt.binds)
    assert np.linalg.norm(lam - cell) <= np.sqrt(2) * step or at_limit, (lam, cell)
    assert opt.gain > 1e-3
    assert opt.equilibrium.min_tensions.min() >= rob.tension_limits[0] - 1e-6


def test_the_result_in_words_and_as_a_table(cogiro):
    """The summary names the objective with its unit and what binds ("nothing" when
    nothing does); the table gives each cable's default and optimal tensions; a max_iter
    that is not an integer is refused by name."""
    from dataclasses import replace
    opt = optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])
    assert opt.binds == ("nothing: a smooth maximum (the objective's gradient vanishes)",)
    text = repr(opt)
    assert text.startswith(f"OptimalTensions(first_global_hz {opt.value:.5g} Hz, default "
                           f"{opt.default_value:.5g} Hz, gain {opt.gain:+.3g} Hz; binds: "
                           f"nothing: a smooth maximum")
    assert repr(replace(opt, binds=())).endswith(f"binds: nothing; {opt.evaluations} "
                                                 f"equilibria)")
    df = opt.to_frame()
    assert list(df.columns) == ["cable", "default tension [N]", "optimal tension [N]",
                                "optimal least tension [N]", "optimal largest tension [N]"]
    np.testing.assert_array_equal(df["optimal least tension [N]"],
                                  opt.equilibrium.min_tensions)
    np.testing.assert_array_equal(df["default tension [N]"], opt.default.tensions)
    for bad in ("5", 0, True):
        with pytest.raises(InvalidParameterError, match="^max_iter must be an integer >= 1"):
            optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5], max_iter=bad)


def test_band_margin_with_modes_on_both_sides_of_the_band(cogiro):
    """Band (2.2, 2.4) Hz at a pose whose platform modes straddle it (2.136 Hz below it,
    inside it 2.316 Hz and more): the margin's gradient takes the mode below over -f_lo and
    the mode above over f_hi. The optimum lifts the margin from -0.035 to above 0 (no
    platform mode in the band), with the two sides' modes coincident at the minimum; no
    distribution 5 N away along the null space does better, and the limits hold."""
    from dynstiff.analyses.optimal_tensions import band_margin
    rob, pose, band = cogiro.robot, [4.0, -2.5, 1.0], (2.2, 2.4)
    opt = optimal_tensions(rob, pose, objective="band_margin", band_hz=band)
    assert opt.default_value < -0.03 and opt.value > 0.01
    assert any("coincident modes at the minimum" in b for b in opt.binds), opt.binds
    assert opt.equilibrium.min_tensions.min() >= rob.tension_limits[0] - 1e-6
    N = null_basis(opt)
    for d in (N[:, 0], -N[:, 0], N[:, 1], -N[:, 1]):
        eq = rob.equilibrium(pose=pose, tension_reference=opt.reference + 5.0 * d)
        pm = find_platform_modes(ds.FrequencyModel(eq, guard_rtol=None), band[1] * 1.05)
        assert band_margin(pm, band, 0.05) <= opt.value + 1e-6, d


def test_the_map_equilibrium_passes_the_model_on(cogiro, monkeypatch):
    """tension_equilibrium hands the rung and the model options to optimal_tensions (the
    map's optimum is that of its own model); the closed form's search builds without its
    guard (the map's own build warns), other rungs with their options only."""
    import dynstiff.analyses.optimal_tensions as ot
    seen = []
    real = ot.build_model

    def spy(eq, rung, **kw):
        seen.append((rung, kw))
        return real(eq, rung, **kw)

    monkeypatch.setattr(ot, "build_model", spy)
    pose = [2.0, 1.5, 1.5]
    a = tension_equilibrium(cogiro.robot, pose, "max-frequency", rung="dsm",
                            chordwise_inertia=False)
    assert seen and all(s == ("dsm", {"chordwise_inertia": False, "guard_rtol": None})
                        for s in seen)
    b = optimal_tensions(cogiro.robot, pose, chordwise_inertia=False).equilibrium
    np.testing.assert_array_equal(a.tensions, b.tensions)
    seen.clear()
    tension_equilibrium(cogiro.robot, pose, "max-frequency", rung="spring")
    assert seen and all(s == ("spring", {}) for s in seen)


@pytest.mark.parametrize("objective, band", [("band_margin", (2.2, 2.4)),
                                             ("band_margin", (0.0, 2.0)),
                                             ("first_global_hz", None)])
def test_the_search_gradients_are_the_derivatives(cogiro, objective, band):
    """The linear programme's gradients at the default distribution against central
    differences (step 0.05 N along each null-space direction; their error falls as the
    step squared, 1e-5 relative here): of each candidate's
    objective (a margin below the band over -f_lo, above it over f_hi; the frequency) and
    of every cable's least and largest tension along its length."""
    from dynstiff.analyses.optimal_tensions import _Search
    from dynstiff.robot.pose import as_pose
    pose = as_pose([4.0, -2.5, 1.0])
    s = _Search(cogiro.robot, pose, objective, band, 0.05, "dsm", {})
    r = s.N.shape[1]
    ev = s.evaluate(np.zeros(r), None)
    g, lo, dlo, hi, dhi = s.gradients(ev)
    np.testing.assert_allclose(lo, ev["eq"].min_tensions, rtol=1e-9)
    np.testing.assert_allclose(hi, ev["eq"].max_tensions, rtol=1e-9)
    if band is not None and band[0] > 0:
        f = np.asarray(ev["pm"].modes.freq_hz)[ev["k"]]
        assert f.min() < band[0] and f.max() > band[1]         # both sides are candidates
    assert np.all(np.abs(g).max(axis=1) > 0)
    h = 0.05
    for j in range(r):
        e = np.zeros(r)
        e[j] = h
        p, m = s.evaluate(e, ev["eq"]), s.evaluate(-e, ev["eq"])
        np.testing.assert_array_equal(p["k"], ev["k"])
        np.testing.assert_array_equal(m["k"], ev["k"])
        np.testing.assert_allclose(g[:, j], (p["v"] - m["v"]) / (2 * h), rtol=1e-4,
                                   atol=1e-9)
        np.testing.assert_allclose(
            dlo[:, j], (p["eq"].min_tensions - m["eq"].min_tensions) / (2 * h), rtol=1e-4,
            atol=1e-6)
        np.testing.assert_allclose(
            dhi[:, j], (p["eq"].max_tensions - m["eq"].max_tensions) / (2 * h), rtol=1e-4,
            atol=1e-6)


def test_a_search_stopped_by_max_iter_says_so(cogiro):
    """One step of the search (max_iter=1) at the smooth-maximum pose: the distribution
    after it is an equilibrium within the limits, better than the default but short of
    the optimum, and what binds says the search stopped, not that a maximum was reached;
    the full search converges well within its 40 steps and claims the maximum."""
    rob, pose = cogiro.robot, [2.0, 1.5, 1.5]
    full = optimal_tensions(rob, pose)
    one = optimal_tensions(rob, pose, max_iter=1)
    assert one.iterations == 1
    assert one.default_value < one.value < full.value - 1e-4
    assert one.equilibrium.min_tensions.min() >= rob.tension_limits[0] - 1e-6
    assert one.binds == ("max_iter: the search stopped after 1 step(s) before it converged "
                         "(the objective may rise further)",)
    assert full.iterations < 20 and not any("max_iter" in b for b in full.binds)
    assert full.binds == ("nothing: a smooth maximum (the objective's gradient vanishes)",)
    two = optimal_tensions(rob, [4.0, -2.5, 1.0])
    assert "; binds: cable 2 at t_min (100 N); cable 3 at t_min (100 N); " in repr(two)


def test_no_objective_where_the_platform_modes_are_not_all_found(cogiro, monkeypatch):
    """An incomplete search for the platform modes (planted) leaves the first global mode
    undefined: at the default distribution that is a ConvergenceError naming it."""
    from dataclasses import replace

    import dynstiff.analyses.optimal_tensions as ot
    from dynstiff.errors import ConvergenceError
    real = ot.find_platform_modes
    monkeypatch.setattr(ot, "find_platform_modes",
                        lambda *a, **kw: replace(real(*a, **kw), complete=False))
    with pytest.raises(ConvergenceError, match="^optimal tensions: the platform modes were "
                       r"not all found at the default distribution \(first_global_hz "
                       r"undefined\)$"):
        optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])


def test_a_step_without_equilibrium_shortens_the_next(cogiro, monkeypatch):
    """A trial distribution with no equilibrium (planted at the first step) is a rejected
    step: the radius halves and the search goes on to the same optimum."""
    from dynstiff.analyses.optimal_tensions import _Search
    real, calls = _Search.evaluate, []

    def first_step_fails(self, lam, prev):
        calls.append(lam)
        return None if len(calls) == 2 else real(self, lam, prev)

    ref = optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])
    monkeypatch.setattr(_Search, "evaluate", first_step_fails)
    opt = optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])
    assert np.abs(calls[2]).max() == pytest.approx(0.5 * np.abs(calls[1]).max(), rel=1e-6)
    assert opt.value == pytest.approx(ref.value, rel=1e-5)


@pytest.mark.parametrize("drop", [0.01, 1.0])
def test_an_overshooting_step_is_followed_by_the_parabolas_fraction(cogiro, monkeypatch,
                                                                    drop):
    """A trial step whose objective falls (planted: 0.01 Hz, or 1 Hz, below the start) is
    cut back to the parabola's best fraction alpha of it (at least 0.05: the 1 Hz fall's
    parabola asks for 0.002); where that is better it is taken and the radius becomes alpha
    times the step, so the next step stays within it, and the search still ends at the
    optimum."""
    from dynstiff.analyses.optimal_tensions import _Search
    real, calls = _Search.evaluate, []

    def first_step_drops(self, lam, prev):
        calls.append(np.array(lam))
        ev = real(self, lam, prev)
        if len(calls) == 2 and ev is not None:
            ev = {**ev, "value": self.first_value - drop}
        if len(calls) == 1:
            self.first_value = ev["value"]
        return ev

    ref = optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])
    monkeypatch.setattr(_Search, "evaluate", first_step_drops)
    opt = optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])
    step, cut = np.abs(calls[1]).max(), np.abs(calls[2]).max()
    assert 0.05 * step * (1 - 1e-9) <= cut < 0.5 * step
    if drop == 1.0:
        assert cut == pytest.approx(0.05 * step, rel=1e-9)
    assert len(calls) > 3 and np.abs(calls[3] - calls[2]).max() <= cut * (1 + 1e-9)
    assert opt.value == pytest.approx(ref.value, rel=1e-5)


def test_the_mode_that_set_the_objective_continues_by_its_mass_weighted_mac():
    """continues(old, new): the candidate of least objective at ``old`` (the second one
    here) is compared with every candidate at ``new`` by the mass-weighted MAC (the shapes'
    scales do not matter); at least 0.5 with one of them continues it, none (or no
    candidates on either side) does not."""
    from dynstiff.analyses.optimal_tensions import _Search
    M = np.diag([2.0, 1.0, 1.0])
    old = {"k": np.array([0, 1]), "v": np.array([2.0, 1.5]),
           "shapes": np.array([[0.0, 0.0, 1.0], [2.0, 0.0, 0.0]])}       # least v: x = e1

    def new(*shapes):
        return {"k": np.arange(len(shapes)), "mass": M, "shapes": 3.0 * np.array(shapes)}

    assert _Search.continues(old, new([0.0, 1.0, 0.0], [1.0, 0.5, 0.0]))   # MAC 8/9
    assert not _Search.continues(old, new([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]))
    # MAC of (1, 1.5, 0) with e1 under M: 2^2 / (2 * (2 + 2.25)) = 0.47 < 0.5
    assert not _Search.continues(old, new([1.0, 1.5, 0.0]))
    assert not _Search.continues(old, {"k": np.zeros(0, int), "mass": M,
                                       "shapes": np.zeros((0, 3))})
    assert not _Search.continues({**old, "k": np.zeros(0, int)}, new([2.0, 0.0, 0.0]))


def test_the_trial_equilibria_start_from_the_current_one(cogiro, monkeypatch):
    """Each trial distribution's statics is warm-started from the equilibrium the step
    leaves (the first from none)."""
    import dynstiff.robot.robot as rr
    real, starts = rr.Robot.equilibrium, []

    def spy(self, *a, start=None, **kw):
        starts.append(start)
        return real(self, *a, start=start, **kw)

    monkeypatch.setattr(rr.Robot, "equilibrium", spy)
    optimal_tensions(cogiro.robot, [2.0, 1.5, 1.5])
    assert starts[0] is None and len(starts) > 3
    assert all(s is not None for s in starts[2:])


@pytest.mark.parametrize("kw, message", [
    (dict(start=[True] * 8), "^start must be real numbers, not booleans"),
    (dict(start="abc"), "^start must be 8 tensions \\[N\\], got 'abc'"),
    (dict(xtol=True), "^xtol must be finite and > 0 \\[N\\], got True"),
    (dict(xtol="1"), "^xtol must be finite and > 0 \\[N\\], got '1'")])
def test_a_boolean_start_or_tolerance_is_refused(cogiro, kw, message):
    with pytest.raises(InvalidParameterError, match=message):
        optimal_tensions(cogiro.robot, cogiro.pose, **kw)


def test_a_robot_that_is_not_one_is_refused():
    with pytest.raises(InvalidParameterError, match="^robot must be a dynstiff.Robot, got "
                                                    "NoneType$"):
        optimal_tensions(None, [0.0, 0.0, 1.0])
