"""Statics of the lumped-mass robot (dynstiff/models/lumped_statics.py, theory.md §7.1): Newton
from the catenary equilibrium, the record, segment forces."""
import dataclasses
import time

import numpy as np
import pytest

from dynstiff.errors import ConvergenceError, InvalidParameterError
from dynstiff.lumped import LumpedMassModel
from dynstiff.models.lumped_statics import LumpedEquilibrium, lumped_equilibrium


# ------------------------------------------------------------------------------ statics
def test_statics_agree_with_elastic_catenary_at_second_order(cogiro, cogiro_eq, lumped):
    """Forward statics of the lumped model vs the closed-form robot statics for the same
    lengths. The lumped nodes lie on the catenary (theory.md §1.1) but straight segments
    replace the curved arcs, an O(l0^2) error in each cable's end force: the poses differ by
    ~4e-7 m at N = 30, falling as N^-2 (measured ratio 30 -> 60: 4.0)."""
    fwd = cogiro.robot.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    L0 = cogiro_eq.unstretched_lengths
    dp, dr, dF = {}, {}, {}
    for N in (30, 60):
        st = lumped(N).equilibrium
        assert st.iterations <= 2 and st.residual <= 1e-10       # measured 1 iteration
        dp[N] = np.linalg.norm(st.pose.position - fwd.pose.position)
        dr[N] = np.linalg.norm(st.pose.rotation - fwd.pose.rotation)
        # the cause: end forces of lumped chains vs catenaries at the *same* pose
        F_cat = [s.force_on_end for s in cogiro.robot.cable_states(st.pose, L0)]
        dF[N] = np.abs(st.platform_forces - F_cat).max()
        K, _ = lumped(N).matrices()
        assert abs(K - K.T).max() < 1e-13 * abs(K).max()         # measured 5e-16
    assert dp[30] < 1e-6 and dr[30] < 1e-7                       # measured 4.4e-7 m, 4.0e-8 rad
    assert dF[30] < 5e-3                                         # measured 2.2e-3 N of ~290 N
    assert dp[30] / dp[60] == pytest.approx(4.0, rel=0.05)       # (60/30)^2
    assert dF[30] / dF[60] == pytest.approx(4.0, rel=0.05)


def test_cogiro_statics_fast(cogiro, cogiro_eq):
    """Issue 4: N = 50 per cable in well under a second (measured 0.05-0.07 s, 1 iteration)."""
    model = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=50)
    t = time.perf_counter()
    st = model.equilibrium()
    assert time.perf_counter() - t < 1.0
    assert st.iterations <= 2
    assert [len(x) for x in st.nodes] == [51] * 8 and [len(t) for t in st.tensions] == [50] * 8


def test_convergence_error_reports_residual(cogiro, cogiro_eq):
    """A tolerance below rounding stops at the rounding floor and reports the residual
    reached (it must stop, not loop); too few iterations raise with the residual."""
    model = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=10)
    st = model.equilibrium(tol=1e-22)
    assert 0 < st.residual <= 4 * model.rounding_floor(st.pose, st.end_tensions.max())
    assert st.residual < 1e-12
    stiff = dataclasses.replace(cogiro.robot,
                                cables=dataclasses.replace(cogiro.robot.cables[0], EA=1e9))
    eq = stiff.equilibrium(pose=cogiro.pose)
    with pytest.raises(ConvergenceError, match="residual") as exc:
        LumpedMassModel(stiff, eq.unstretched_lengths, 5).equilibrium(initial_pose=eq.pose,
                                                                       max_iter=1)
    assert exc.value.residual > 1e-9


def test_stiff_cables_converge_to_their_rounding_floor(cogiro):
    """EA = 1e9 N in 30 segments: a tension EA (l/l0 - 1) from 10 m coordinates carries
    about eps EA |x| / l0 = 6e-5 N of rounding, 2e-9 of the force scale, above the default
    tol of 1e-10. Newton stops there (it used to raise after stagnating), reports the
    residual it reached, and the pose still agrees with the elastic catenary to the
    beaded-cable error O(l0^2) of the soft cable (4.4e-7 m at N = 30)."""
    rob = dataclasses.replace(cogiro.robot,
                              cables=dataclasses.replace(cogiro.robot.cables[0], EA=1e9))
    eq = rob.equilibrium(pose=cogiro.pose)
    mm = LumpedMassModel(rob, eq.unstretched_lengths, segments=30)
    st = mm.equilibrium(initial_pose=eq.pose)
    floor = mm.rounding_floor(st.pose, st.end_tensions.max())
    assert 1e-10 < floor < 1e-7
    assert st.residual <= 4 * floor
    assert np.abs(st.pose.position - eq.pose.position).max() < 1e-6
    soft = LumpedMassModel(cogiro.robot, cogiro.robot.equilibrium(pose=cogiro.pose)
                           .unstretched_lengths, segments=30)
    assert soft.rounding_floor(cogiro.pose, 300.0) < 1e-10     # the default tol rules there


def test_equilibrium_record_table_plot_and_text(cogiro, cogiro_eq):
    """The record of a robot with 3 to 6 segments per cable: one table row per cable with its
    segment count and end tensions, the interior nodes, the tension bars and the summary."""
    import matplotlib.pyplot as plt
    segs = [3, 4, 5, 6, 3, 4, 5, 6]
    st = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=segs).equilibrium()
    df = st.to_frame()
    assert list(df.columns) == ["cable", "segments", "tension at B [N]", "tension at A [N]"]
    assert df["cable"].tolist() == list(range(8)) and df["segments"].tolist() == segs
    np.testing.assert_array_equal(df["tension at B [N]"], [t[-1] for t in st.tensions])
    np.testing.assert_array_equal(df["tension at A [N]"], [t[0] for t in st.tensions])
    # a hanging cable pulls harder at its upper end: the anchors of CoGiRo are above B
    assert np.all(df["tension at A [N]"] > df["tension at B [N]"])
    assert [len(x) for x in st.interior] == [s - 1 for s in segs]
    for x, nodes in zip(st.interior, st.nodes):
        np.testing.assert_array_equal(x, nodes[1:-1])
    fig = st.plot()
    bars = [p.get_height() for p in fig.axes[0].patches if p.get_gid() == "tension-B"]
    np.testing.assert_array_equal(bars, st.end_tensions)
    plt.close(fig)
    t = st.end_tensions
    assert repr(st).startswith(f"LumpedEquilibrium(8 chains, {st.pose!r}, tensions at B "
                               f"{t.min():.4g}..{t.max():.4g} N, residual")


# ------------------------------------------------------- arguments, counts, stopping rule
def _small(cogiro, cogiro_eq, robot=None, segments=5):
    """CoGiRo (or ``robot``) with the lengths of its reference pose, 5 segments per cable."""
    return LumpedMassModel(cogiro.robot if robot is None else robot,
                           cogiro_eq.unstretched_lengths, segments=segments)


def test_arguments_are_checked_by_name(cogiro, cogiro_eq):
    """tol must be a positive number and max_iter an integer >= 1 (a bool or a float is no
    count); each refusal names its argument before any statics is solved."""
    model = _small(cogiro, cogiro_eq)
    for tol in (0.0, -1e-10, float("nan")):
        with pytest.raises(InvalidParameterError, match=r"^tol must be"):
            model.equilibrium(tol=tol)
    for max_iter in (True, 2.5, 0, -3):
        with pytest.raises(InvalidParameterError,
                           match=r"^max_iter must be an integer >= 1, got"):
            model.equilibrium(max_iter=max_iter)


def test_default_tolerance_of_the_function_is_the_methods(cogiro, cogiro_eq):
    """lumped_equilibrium(model) with its defaults is LumpedMassModel.equilibrium() (tol 1e-10,
    documented there): the same Newton steps and a residual below 1e-10, not the start."""
    model = _small(cogiro, cogiro_eq)
    st, ref = lumped_equilibrium(model), model.equilibrium()
    assert st.iterations == ref.iterations >= 1
    assert st.residual == ref.residual <= 1e-10
    np.testing.assert_array_equal(st.pose.as_vector(), ref.pose.as_vector())


def test_iterations_count_the_newton_steps(cogiro, cogiro_eq, monkeypatch):
    """``iterations`` is the number of tangent factorisations (Newton steps) taken, and
    max_iter equal to it is enough; one fewer raises with the residual then reached."""
    model = _small(cogiro, cogiro_eq)
    real, calls = model.tangent_unchecked, []
    monkeypatch.setattr(model, "tangent_unchecked", lambda *a: calls.append(1) or real(*a))
    st = model.equilibrium()
    assert st.iterations == len(calls) and st.residual <= 1e-10
    assert st.iterations == 2                                  # measured at N = 5
    assert model.equilibrium(max_iter=2).iterations == 2
    with pytest.raises(ConvergenceError,
                       match="did not converge in 1 Newton iterations") as exc:
        model.equilibrium(max_iter=1)
    assert exc.value.residual > 1e-10


def test_tolerance_is_inclusive_at_the_start(cogiro, cogiro_eq):
    """Converged when the residual is <= tol: a tol above the start's residual returns the
    start (the catenary pose, 0 iterations), and a tol equal to that residual does too."""
    model = _small(cogiro, cogiro_eq)
    start = model.equilibrium(tol=1.0)
    assert start.iterations == 0 and 1e-10 < start.residual < 1e-2
    np.testing.assert_array_equal(start.pose.as_vector(), start.start_pose.as_vector())
    same = model.equilibrium(tol=start.residual)
    assert same.iterations == 0 and same.residual == start.residual


def test_nonstandard_gravity_starts_on_its_own_catenaries(cogiro, cogiro_eq):
    """On the Moon (g = 1.62 m/s^2) the start chains hang on the catenaries of that g, so one
    or two Newton steps suffice as under standard gravity (chains of the standard g would be
    30 % of the force scale off and take 6); the start is the robot's elastic-catenary
    forward statics."""
    import dataclasses
    moon = dataclasses.replace(cogiro.robot, g=1.62)
    st = _small(cogiro, cogiro_eq, robot=moon).equilibrium()
    assert st.iterations <= 2 and st.residual <= 1e-10            # measured 2
    fwd = moon.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    np.testing.assert_allclose(st.start_pose.as_vector(), fwd.pose.as_vector(), atol=1e-9)
    assert np.abs(st.pose.position - fwd.pose.position).max() < 1e-4


def test_singular_tangent_raises_with_the_residual(cogiro, cogiro_eq, monkeypatch):
    """A tangent with a zero-stiffness DOF (a mechanism) cannot be factorised: a
    ConvergenceError naming the singular tangent, with the residual of the start."""
    import scipy.sparse
    model = _small(cogiro, cogiro_eq)
    res0 = model.equilibrium(tol=1.0).residual
    real = model.tangent_unchecked

    def mechanism(*args):
        K = real(*args)
        d = np.ones(K.shape[0])
        d[0] = 0.0
        return scipy.sparse.diags(d) @ K @ scipy.sparse.diags(d)
    monkeypatch.setattr(model, "tangent_unchecked", mechanism)
    with pytest.raises(ConvergenceError, match=r"^LumpedMassModel.equilibrium: singular "
                       r"tangent stiffness .* relative residual") as exc:
        model.equilibrium()
    assert exc.value.residual == res0
    assert f"{res0:.3e}" in str(exc.value)


def _stall(monkeypatch, model, floor_at_start):
    """Make every Newton step of ``model`` lost in rounding (the configuration does not move)
    and rescale its rounding floor to ``floor_at_start`` at the start configuration (it still
    depends on the pose and the tension as the real one)."""
    real, first = model.rounding_floor, []

    def floor(pose, t_max):
        f = real(pose, t_max)
        first.append(f)
        return floor_at_start * (f / first[0])
    monkeypatch.setattr(model, "rounding_floor", floor)
    monkeypatch.setattr(model, "displaced", lambda pose, interior, dx: (pose, interior))


@pytest.mark.parametrize("ratio", [2.0, 4.0])
def test_stagnation_within_four_rounding_floors_is_convergence(cogiro, cogiro_eq,
                                                                monkeypatch, ratio):
    """No step reduces the residual but it is within 4 times the rounding floor (inclusive):
    converged there, the record of that configuration with its residual, 1 iteration."""
    model = _small(cogiro, cogiro_eq)
    res0 = model.equilibrium(tol=1.0).residual
    _stall(monkeypatch, model, res0 / ratio)
    st = model.equilibrium(tol=1e-22)
    assert isinstance(st, LumpedEquilibrium)
    assert st.iterations == 1 and st.residual == res0
    np.testing.assert_array_equal(st.pose.as_vector(), st.start_pose.as_vector())


def test_stagnation_above_the_rounding_level_raises(cogiro, cogiro_eq, monkeypatch):
    """No step reduces the residual, which is 4.5 rounding floors (above the 4 accepted):
    ConvergenceError saying so, with the residual reached and the tolerance."""
    model = _small(cogiro, cogiro_eq)
    res0 = model.equilibrium(tol=1.0).residual
    _stall(monkeypatch, model, res0 / 4.5)
    with pytest.raises(ConvergenceError, match=r"^LumpedMassModel.equilibrium: no step "
                       r"reduces the residual .* > tol 1e-10$") as exc:
        model.equilibrium()
    assert exc.value.residual == res0
    assert f"relative residual {res0:.3e}" in str(exc.value)


def test_record_is_read_only_and_slack_segments_are_refused(cogiro, cogiro_eq, monkeypatch):
    """The record's arrays cannot be written (a result is not changed behind its residual);
    a cable with a zero-tension segment at equilibrium raises SlackCableError naming it."""
    from dynstiff.errors import SlackCableError
    from dynstiff.models import lumped_statics
    model = _small(cogiro, cogiro_eq)
    st = model.equilibrium()
    for a in st.nodes + st.tensions + [st.platform_forces]:
        with pytest.raises(ValueError, match="read-only"):
            a[0] = 0.0
    real, calls = lumped_statics.segment_forces, []

    def one_slack(x, l0, EA):           # called once per cable: segment 2 of cable 3 slack
        u, lengths, T = real(x, l0, EA)
        calls.append(1)
        return u, lengths, np.where(np.arange(T.size) == 2, 0.0, T) if len(calls) == 4 else T
    monkeypatch.setattr(lumped_statics, "segment_forces", one_slack)
    with pytest.raises(SlackCableError, match=r"cable\(s\) \[3\] have zero-tension segments"):
        model.equilibrium()
