"""The closed form's guard (dynstiff/models/dsm_guard.py, dynstiff/cable/guard.py; theory.md
§11.5-11.6) as FrequencyModel runs it: each cable's static, local and axial error, estimated
or measured against the exact cable, the robot-level bound and its warning, the causes said
for cables whose closed form does not apply, and the ClosedFormWarnings that say them,
attributed to the caller's line."""

import dataclasses
import sys
import warnings

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.guard import ROBOT_ERROR_FACTOR
from dynstiff.errors import ClosedFormWarning, InvalidParameterError
from dynstiff.models.dsm import ROBOT_BOUND_MESSAGE


def _said(fn):
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        fn()
    return [w.message for w in rec if issubclass(w.category, ClosedFormWarning)]


def test_the_robot_bound_is_said_once_with_its_numbers():
    """CoGiRo at guard_rtol = 1e-4 up to 1 Hz: no cable's local modes are in the band and
    its static error (4.6e-5) is within tolerance, but the robot-level bound, 2.5 x (static
    + the largest cable error), exceeds it: one warning, cause 'robot', no cable, with the
    bound and the band top as robot_error gives them; a wider band does not say it again."""
    eq = ds.load_scene("cogiro").equilibrium()
    said = _said(lambda: ds.FrequencyModel(eq, guard_rtol=1e-4))
    assert said == []
    m = ds.FrequencyModel(eq, guard_rtol=1e-4)
    top = 2 * np.pi * 1.0
    said = _said(lambda: (m.dynamic_stiffness([top]), m.dynamic_stiffness([1.2 * top])))
    bound, i = m.robot_error(top)
    assert 1e-4 < bound < np.inf
    assert [(w.cause, w.cable) for w in said] == [("robot", None)]
    assert str(said[0]) == (
        f"{ROBOT_BOUND_MESSAGE} up to 1 Hz may reach {bound:.2g} (bound "
        f"{ROBOT_ERROR_FACTOR:g} x (static + cable {i}'s own error), > guard_rtol 0.0001): "
        f"use the 'exact' rung")


def test_cables_with_axial_modes_in_the_band_are_not_also_measured_for_local_error():
    """planar2 with soft heavy cables up to 40 Hz: both cables' axial modes are in the band
    (the closed form does not apply: error inf), and that is what is said of them, once
    each; their local error is not measured and said as well, nor the robot bound."""
    r = ds.load_scene("planar2").robot
    eq = dataclasses.replace(r, cables=(ds.Cable(1.0, 2.0e4),) * 2).equilibrium(
        ds.Pose([0, 0, -10]))
    m = ds.FrequencyModel(eq)
    said = _said(lambda: m.dynamic_stiffness(2 * np.pi * np.array([20.0, 40.0])))
    assert sorted((w.cable, w.cause) for w in said) == [(0, "axial"), (1, "axial")]


def test_a_slack_cable_is_said_slack_only_across_its_local_modes():
    """A 1 kg point mass on three heavy cables and a fourth straight down, held at 0.01 N
    (slack: t_min / t_max < 0.1, error inf). Up to 30 rad/s, past the local modes of every
    cable: the slack cable is said once, as slack, and not measured for a local error too;
    the three others are said for their local modes."""
    ang = np.radians([90, 210, 330])
    A = np.vstack([np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)]),
                   [0.3, -0.2, -4.0]])
    rob = ds.Robot(A, np.zeros((4, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6))
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    m = None

    def build():
        nonlocal m
        m = ds.FrequencyModel(eq, guard_rtol=1e-2)
    built = _said(build)
    assert [(w.cable, w.cause) for w in built if w.cable == 3] == [(3, "slack")]
    said = _said(lambda: m.dynamic_stiffness([30.0]))
    assert all(w.cable != 3 for w in said)
    assert np.pi * np.sqrt(m.params[3].T / m.params[3].m) / m.params[3].L < 30.0


def test_a_damped_copy_guards_its_band_afresh_like_a_new_build():
    """The damped copy a map's receptance check takes (_with_model_damping) shares the
    cables but not the band guard: after the undamped model said its robot bound (CoGiRo,
    guard_rtol 1e-4, 1 Hz), the copy says it too, as a model built with that damping
    does."""
    eq = ds.load_scene("cogiro").equilibrium()
    top = [2 * np.pi * 1.0]
    m = ds.FrequencyModel(eq, guard_rtol=1e-4)
    first = _said(lambda: m.dynamic_stiffness(top))
    copy = m._with_model_damping(0.01, 0.02)
    again = _said(lambda: copy.dynamic_stiffness(top))
    new = ds.FrequencyModel(eq, guard_rtol=1e-4, cable_loss_factor=0.01,
                            platform_damping_ratio=0.02)
    fresh = _said(lambda: new.dynamic_stiffness(top))
    assert [(w.cause, w.cable) for w in first] == [("robot", None)]
    assert [str(w) for w in again] == [str(w) for w in fresh] != []


def test_the_model_loss_factor_does_not_count_as_a_static_error_of_the_closed_form():
    """Cables with their own loss factor (EA (1 + 0.02 i)) and the model's eta = 0.5: both
    rungs multiply by s = 1 + i eta, whose product with the complex EA lowers the real
    stiffness by eta 0.02 = 1 % alike (theory.md §11.5, §12.2). The static error is the
    closed form's, the same with and without eta (4e-5 on CoGiRo; counted, it read 5e-3
    and the robot bound warned at any frequency)."""
    eq0 = ds.load_scene("cogiro").equilibrium()
    rob = eq0.robot
    lossy = dataclasses.replace(rob, cables=[dataclasses.replace(c, loss_factor=0.02)
                                             for c in rob.cables]).equilibrium(pose=eq0.pose)
    plain = ds.FrequencyModel(lossy)
    damped = ds.FrequencyModel(lossy, cable_loss_factor=0.5)
    e = plain.static_error()
    assert 1e-5 < e[0] < 1e-4
    assert damped.static_error() == e
    assert _said(lambda: damped.dynamic_stiffness([1e-6])) == []


@pytest.mark.parametrize("heavy", [2, 5])
def test_the_static_error_is_the_first_order_shift_of_the_massless_modes(cogiro, heavy):
    """CoGiRo with one cable 30 times heavier (its sag dominates the closed form's static
    error): the estimate equals the largest relative shift of the massless-cable
    frequencies between the closed form's K(0) and the exact catenaries' stiffness (the
    generalized eigenproblems with M_p, solved here; agreement to first order, measured
    0.2 %), and names the heavy cable."""
    from dataclasses import replace

    from scipy.linalg import eigh
    cables = list(cogiro.robot.cables)
    cables[heavy] = replace(cables[heavy], mass_per_length=30 * cables[heavy].mass_per_length)
    eq = replace(cogiro.robot, cables=cables).equilibrium(pose=cogiro.pose)
    m = ds.FrequencyModel(eq, guard_rtol=None)
    err, cable = m.static_error()
    Kd = np.real(m.dynamic_stiffness(0.0)[0])
    Ke = ds.build_model(eq, "catenary").K
    lam_d = eigh(0.5 * (Kd + Kd.T), m.platform_mass, eigvals_only=True)
    lam_e = eigh(0.5 * (Ke + Ke.T), m.platform_mass, eigvals_only=True)
    assert err == pytest.approx(np.abs(np.sqrt(lam_d / lam_e) - 1).max(), rel=5e-3)
    assert cable == heavy


def _place(filename, line):
    """A warning's place (file, line), compared with the caller's. A mutation-testing run
    (MUTANT_UNDER_TEST set) puts the tool's own frames between caller and library, so
    there the place is not compared (the normal run compares it)."""
    import os
    return (None, None) if "MUTANT_UNDER_TEST" in os.environ else (filename, line)


def _three_cable_point_mass(g=9.81, lower=False):
    """A 1 kg point mass on three heavy cables from 8 m around and 6 m up (0.064 kg/m,
    EA 1.4e5 N), optionally a fourth straight down to a floor anchor, at (0.3, -0.2, 1)."""
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    if lower:
        A = np.vstack([A, [0.3, -0.2, -4.0]])
    rob = ds.Robot(A, np.zeros((len(A), 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6),
                   g=g)
    return rob.equilibrium(pose=[0.3, -0.2, 1.0])


def test_the_guard_warns_on_slack_static_and_local_errors_and_is_silent_on_cogiro(cogiro_eq):
    """FrequencyModel's guard (theory.md §11.5): silent on CoGiRo up to 20 Hz at its default
    tolerance; a ClosedFormWarning names the cable and the cause on a heavy sagging robot, and
    guard_rtol=None turns it off."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    with warnings.catch_warnings():
        warnings.simplefilter("error", ClosedFormWarning)
        m = ds.FrequencyModel(cogiro_eq)
        ds.eigenfrequencies(m, fmax_hz=20.0)
        assert m.static_error()[0] < 1e-4
    # a three-cable point mass on heavy, sagging, steep cables
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    rob = ds.Robot(A, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6))
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    with pytest.warns(ClosedFormWarning) as rec:
        m = ds.FrequencyModel(eq)
        ds.eigenfrequencies(m, fmax_hz=1.5)
    causes = {(w.message.cable, w.message.cause) for w in rec}
    assert (0, "static") in causes and {c for c, k in causes if k == "local"} == {0, 1, 2}
    assert all(str(w.message).endswith(": use the 'exact' rung") for w in rec)
    assert len(rec) == len(causes)                         # once per cable and cause
    with warnings.catch_warnings():
        warnings.simplefilter("error", ClosedFormWarning)
        ds.eigenfrequencies(ds.FrequencyModel(eq, guard_rtol=None), fmax_hz=1.5)
    for bad in (-1.0, 0.0, np.inf):
        with pytest.raises(InvalidParameterError, match="guard_rtol"):
            ds.FrequencyModel(eq, guard_rtol=bad)


def test_static_error_equals_the_cable_by_cable_sum(cogiro_eq):
    """The guard's static check (all cables at once) against the sum written cable by
    cable with each state's own end stiffness and the general kernel at omega = 0: error
    and cable equal on CoGiRo and on a heavy sagging three-cable robot where it warns, with
    and without damping."""
    from scipy.linalg import eigh

    from dynstiff.robot.platform import lever_map

    def by_cable(m):
        fi, nf = m.free_index, m.n_free
        K_ex, dK = m.K_geo_free.copy(), []
        K0 = m.cable_coefficients(np.zeros(1)).real.reshape(len(m.params), 5)
        for i, (s, r) in enumerate(zip(m.equilibrium.states, m.lever_arms)):
            J = lever_map(r, fi)
            Ke = J.T @ s.end_stiffness @ J
            K_ex += Ke
            dK.append((K0[i] @ m.assembly_map[5 * i:5 * i + 5]).reshape(nf, nf) - Ke)
        lam, X = eigh(0.5 * (K_ex + K_ex.T), m.platform_mass)
        X, lam = X[:, lam > 0], lam[lam > 0]
        per = np.array([np.einsum("ik,ij,jk->k", X, d, X) for d in dK]) / (2 * lam)
        k = int(np.argmax(np.abs(per.sum(axis=0))))
        return abs(per.sum(axis=0)[k]), int(np.argmax(np.abs(per[:, k])))

    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    rob = ds.Robot(A, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6))
    heavy = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    slow = _three_cable_point_mass(g=0.3)          # global modes below 1 rad/s
    for eq, kw in ((cogiro_eq, {}), (heavy, {}), (slow, {}),
                   (cogiro_eq, {"cable_loss_factor": 0.02}), (heavy, {"damping": False})):
        m = ds.FrequencyModel(eq, guard_rtol=None, **kw)
        err, i = m.static_error()
        ref, i_ref = by_cable(m)
        assert i == i_ref
        np.testing.assert_allclose(err, ref, rtol=1e-8)
    assert ds.FrequencyModel(heavy, guard_rtol=None).static_error()[0] > 1e-2


def test_guard_warnings_point_at_the_callers_line_and_name_the_slack_cable():
    """The lower cable of the four-cable robot is held at 0.01 N at its anchor and carries
    its weight (3.1 N) at B: t_min / t_max < 0.1, the closed form does not apply (cause
    'slack', cable 3), said once when the model is built. The warning is attributed to the
    line of the user's call, not to the library."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    eq = _three_cable_point_mass(lower=True)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        ds.FrequencyModel(eq)
    got = [(w.message.cable, w.message.cause) + _place(w.filename, w.lineno) for w in rec
           if issubclass(w.category, ClosedFormWarning)]
    assert got == [(3, "slack") + _place(__file__, line)]
    from dynstiff.cable.guard import DEFAULT_GUARD_RTOL, closed_form_validity
    reasons = closed_form_validity(eq.states[3]).reasons(DEFAULT_GUARD_RTOL)
    slack = [str(w.message) for w in rec if issubclass(w.category, ClosedFormWarning)][0]
    assert slack == ("cable 3: the closed form does not apply: " + "; ".join(reasons)
                     + ": use the 'exact' rung")


def test_the_guard_checks_bands_below_one_radian_per_second():
    """At g = 0.3 m/s^2 the three heavy cables' local modes start at 0.76-0.84 rad/s; K at
    0.99 rad/s reaches them, and the closed form's error there is above guard_rtol: a
    'local' warning for each cable, from the evaluation's line."""
    import warnings

    from dynstiff.errors import ClosedFormWarning
    with pytest.warns(ClosedFormWarning, match="static stiffness shifts a global mode"):
        m = ds.FrequencyModel(_three_cable_point_mass(g=0.3), guard_rtol=1e-2)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        m.dynamic_stiffness([0.99])
        m.dynamic_stiffness([1.2])                 # a wider band: said once per cable only
    got = {(w.message.cable, w.message.cause) + _place(w.filename, w.lineno) for w in rec
           if issubclass(w.category, ClosedFormWarning)}
    assert got == {(i, "local") + _place(__file__, line) for i in range(3)}
    assert len(rec) == 3
    for w in rec:
        i = w.message.cable
        p = m.params[i]                      # lowest taut-string frequency, model tension
        f_loc = np.sqrt(p.T / p.m) / (2 * p.L)
        assert f_loc < 0.99 / (2 * np.pi)
        assert str(w.message).startswith(f"cable {i}: its local modes (from {f_loc:.4g} Hz) are "
                                         f"in the band asked and the closed form's are ")


def test_a_cable_error_below_one_radian_per_second_is_measured():
    """The three heavy cables' envelope (0.34-0.47) is above 1e-2, so their error is measured
    against the exact cable, also for a band below 1 rad/s (0.5 rad/s here): the number of
    closed_form_local_error, kept with its band of 8 times the first local frequency."""
    from dynstiff.cable.guard import closed_form_local_error
    eq = _three_cable_point_mass(g=0.3)
    m = ds.FrequencyModel(eq, guard_rtol=None)
    for i, state in enumerate(eq.states):
        assert m._validity[i].error > 0.3
        err = closed_form_local_error(state, 0.5, m.tension)
        assert m.cable_error(i, 0.5) == err > 0.01
        assert m._measured[i] == (8 * m._local_omega[i], err)


def test_a_cable_error_ends_at_axial_modes_below_one_radian_per_second():
    """A soft cable (EA 0.01 N, g = 0.02 m/s^2) has its first axial mode at 0.15 Hz: below
    AXIAL_MARGIN of it (0.85 rad/s) its error is its envelope, from there on inf."""
    from dynstiff.cable.guard import AXIAL_MARGIN, closed_form_validity
    one = ds.Robot(np.array([[1.0, 0.0, 5.0]]), np.zeros((1, 3)), ds.Cable(0.064, 0.01),
                   ds.Platform(1.0, free_dofs=("z",)), tension_limits=(1e-6, 1e6), g=0.02)
    s = one.equilibrium(pose=[0.0, 0.0, 1.0]).states[0]
    w_ax = AXIAL_MARGIN * np.pi * np.sqrt(0.01 / 0.064) / s.unstretched_length
    m = ds.FrequencyModel(one.equilibrium(pose=[0.0, 0.0, 1.0]), guard_rtol=None)
    assert 0.8 < w_ax < 0.9
    assert m.cable_error(0, 0.5) == closed_form_validity(s).error < 1e-2
    assert m.cable_error(0, w_ax) == np.inf


def test_the_static_warning_lists_every_cause_above_a_tenth_of_guard_rtol(cogiro_eq):
    """CoGiRo's closed-form static error is 4.6e-5 (cable 1); at guard_rtol = 3e-5 it warns,
    and the message lists the validity's reasons above 3e-6: the sag (9e-5), the chordwise
    weight (5e-5) and the tension variation (2.3e-5, below guard_rtol itself)."""
    from dynstiff.cable.guard import closed_form_validity
    from dynstiff.errors import ClosedFormWarning
    err, i = ds.FrequencyModel(cogiro_eq, guard_rtol=None).static_error()
    with pytest.warns(ClosedFormWarning) as rec:
        ds.FrequencyModel(cogiro_eq, guard_rtol=3e-5)
    reasons = closed_form_validity(cogiro_eq.states[i]).reasons(3e-6)
    assert len(reasons) == 3 and "tension varies" in reasons[-1]
    assert [str(w.message) for w in rec] == [
        f"cable {i}: the closed form's static stiffness shifts a global mode by {err:.2g} "
        f"(estimate, > guard_rtol 3e-05; {'; '.join(reasons)}): use the 'exact' rung"]


def test_guard_warnings_from_deep_calls_point_at_the_callers_line_too():
    """The guard also runs inside the eigen search and the cable-level functions: their
    warnings are attributed to the user's line as well, not to a line of the package."""
    import dataclasses
    import warnings

    from dynstiff.errors import ClosedFormWarning
    r = ds.load_scene("planar2").robot
    eq = dataclasses.replace(r, cables=(ds.Cable(1.0, 2.0e4),) * 2).equilibrium(
        ds.Pose([0, 0, -10]))
    m = ds.FrequencyModel(eq)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        ds.eigenfrequencies(m, fmax_hz=40.0)
        ds.cable_natural_frequencies(eq.states[0], 40)
    places = {_place(w.filename, w.lineno) for w in rec
              if issubclass(w.category, ClosedFormWarning)}
    assert places == {_place(__file__, line), _place(__file__, line + 1)}
    f_ax = np.sqrt(2.0e4 / 1.0) / (2 * eq.states[0].unstretched_length)
    axial = [str(w.message) for w in rec if getattr(w.message, "cause", "") == "axial"]
    assert axial[0] == (f"cable 0: its axial modes from {f_ax:.4g} Hz lie in the band asked "
                        f"(up to 40 Hz); the closed form has none, so mode counts and "
                        f"frequencies above are wrong: use the 'exact' rung")


@pytest.mark.parametrize("tension", ["mean", "chord"])
def test_a_cable_within_tolerance_does_not_stop_the_check_of_the_others(tension):
    """At g = 0.3 m/s^2 a light taut cable (estimated error 1e-5) comes first, two heavy ones
    after it: K at 30 rad/s reaches all their local modes, and the two heavy cables are
    each said once, in full: the error measured against the exact cable with the model's
    tension up to min(omega, axial), and every cause above a tenth of guard_rtol."""
    import warnings

    from dynstiff.cable.guard import closed_form_local_error, closed_form_validity
    from dynstiff.errors import ClosedFormWarning
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    heavy = ds.Cable(0.064, 1.4e5)
    rob = ds.Robot(A, np.zeros((3, 3)), (ds.Cable(0.0005, 1.4e5), heavy, heavy),
                   ds.Platform(1.0, free_dofs=("x", "y", "z")), tension_limits=(0.01, 1e6),
                   g=0.3)
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    with pytest.warns(ClosedFormWarning, match="static stiffness"):
        m = ds.FrequencyModel(eq, tension=tension, guard_rtol=1e-2)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        m.dynamic_stiffness([30.0])
    assert [w.message.cable for w in rec] == [1, 2]
    for w in rec:
        i = w.message.cable
        s = eq.states[i]
        f_ax = np.sqrt(s.cable.EA / s.cable.mass_per_length) / (2 * s.unstretched_length)
        err = closed_form_local_error(s, min(30.0, 2 * np.pi * f_ax), tension)
        reasons = "; ".join(closed_form_validity(s, tension=tension).reasons(1e-3))
        p = m.params[i]                      # lowest taut-string frequency, model tension
        f_loc = np.sqrt(p.T / p.m) / (2 * p.L)
        assert str(w.message) == (
            f"cable {i}: its local modes (from {f_loc:.4g} Hz) are in the band asked and the "
            f"closed form's are {err:.2g} off the exact model's (> guard_rtol 0.01; "
            f"{reasons}): use the 'exact' rung")


def test_cables_measured_within_tolerance_are_passed_over_and_the_rest_said(cogiro_eq):
    """CoGiRo at guard_rtol = 3e-5 up to 20 Hz: every cable's estimate exceeds it, so each is
    measured against the exact cable; cables 2 and 5 measure within it and are passed over,
    the other six are said in full, each with every cause above a tenth of guard_rtol."""
    import warnings

    from dynstiff.cable.guard import closed_form_local_error, closed_form_validity
    from dynstiff.errors import ClosedFormWarning
    with pytest.warns(ClosedFormWarning, match="static stiffness"):
        m = ds.FrequencyModel(cogiro_eq, guard_rtol=3e-5)
    top = 2 * np.pi * 20.0
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        m.dynamic_stiffness([top])
    said = [w.message.cable for w in rec]
    assert said == [0, 1, 3, 4, 6, 7]
    for i in (2, 5):
        assert closed_form_local_error(cogiro_eq.states[i], top) <= 3e-5
    for w, i in zip(rec, said):
        s = cogiro_eq.states[i]
        err = closed_form_local_error(s, top)
        p = m.params[i]                      # lowest taut-string frequency, model tension
        f_loc = np.sqrt(p.T / p.m) / (2 * p.L)
        assert str(w.message) == (
            f"cable {i}: its local modes (from {f_loc:.4g} Hz) are in the band asked and the "
            f"closed form's are {err:.2g} off the exact model's (> guard_rtol 3e-05; "
            + "; ".join(closed_form_validity(s).reasons(3e-6)) + "): use the 'exact' rung")


def test_on_fast_the_guard_warns_or_the_closed_form_is_within_guard_rtol_mode_by_mode():
    # the FAST feed support at the bottom of its focal surface: cables ~0.9 x the cabin's mass
    eq = ds.load_scene("fast").equilibrium()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ds.errors.ClosedFormWarning)
        m = ds.FrequencyModel(eq)
        f_d = ds.eigenfrequencies(m, fmax_hz=0.4)
    warned = any(isinstance(w.message, ds.errors.ClosedFormWarning) for w in caught)
    f_x = ds.eigenfrequencies(ds.build_model(eq, "exact", fmax_hz=0.45), fmax_hz=0.4)
    assert f_d.size == f_x.size > 20
    err = np.abs(f_d / f_x - 1)
    assert warned or err.max() <= m.guard_rtol
    # the robot-level bound holds here: measured 5.1e-3, bound 2.5 x (static + own) >= it
    bound = m.robot_error(2 * np.pi * 0.4)[0]
    assert err.max() <= bound
    assert warned == (bound > m.guard_rtol)


def test_robot_error_is_the_factor_times_static_plus_largest_cable_error(cogiro_eq):
    from dynstiff.cable.guard import ROBOT_ERROR_FACTOR
    m = ds.FrequencyModel(cogiro_eq)
    w = 2 * np.pi * 12.0
    own = [m.cable_error(i, w) for i in range(8)]
    bound, i = m.robot_error(w)
    assert bound == pytest.approx(ROBOT_ERROR_FACTOR * (m.static_error()[0] + max(own)))
    assert own[i] == max(own)
