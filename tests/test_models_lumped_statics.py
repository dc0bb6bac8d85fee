"""Statics of the lumped-mass robot (dynstiff/models/lumped_statics.py, theory.md §7.1): Newton
from the catenary equilibrium, the record, segment forces."""
import dataclasses
import time

import numpy as np
import pytest

from dynstiff.errors import ConvergenceError
from dynstiff.lumped import LumpedMassModel


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
