"""Robot statics (dynstiff/robot/statics.py, theory.md §4): inverse and forward statics, the
workspace edge, warm starts, and the batched statics against the scalar solver (the tension
distribution itself: tests/test_robot_distribution.py)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError, SlackCableError
from dynstiff.robot.statics import tension_distribution


# ---------------------------------------------------------- inverse and forward statics
def test_inverse_then_forward_statics_round_trip(cogiro, cogiro_eq):
    assert cogiro_eq.residual < 1e-10
    fwd = cogiro.robot.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    np.testing.assert_allclose(fwd.pose.position, cogiro.pose.position, atol=1e-9)
    np.testing.assert_allclose(fwd.pose.rotation, cogiro.pose.rotation, atol=1e-9)
    t_min, t_max = cogiro.robot.tension_limits
    assert np.all(cogiro_eq.tensions >= t_min - 1e-9) and np.all(cogiro_eq.tensions <= t_max)


def test_forward_statics_with_held_dofs_needs_initial_pose(cogiro, cogiro_eq):
    p = cogiro.robot.platform
    planar = ds.Platform(p.mass, p.center_of_mass, p.inertia, free_dofs=("x", "z", "ry"))
    rob = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments, cogiro.robot.cables, planar,
                   tension_limits=cogiro.robot.tension_limits)
    with pytest.raises(InvalidParameterError, match="initial_pose"):
        rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    eq = rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths,
                         initial_pose=cogiro.pose)
    np.testing.assert_allclose(eq.pose.position, cogiro.pose.position, atol=1e-9)
    m = ds.FrequencyModel(eq)
    K = m.dynamic_stiffness([0.0, 10.0])
    np.testing.assert_allclose(K, K.transpose(0, 2, 1), atol=1e-9 * np.abs(K).max())


def test_pose_outside_workspace_raises(cogiro):
    with pytest.raises(SlackCableError, match="pose"):
        cogiro.robot.equilibrium(pose=[9.0, 0.0, 1.0])


def test_cogiro_near_the_workspace_edge_converges():
    """(5, 3, 1) m: two cables at t_min; the fixed point of directions and tensions needs an
    exact distribution (an inexact one stalled the iteration at a 5e-6 wrench residual)."""
    eq = ds.load_scene("cogiro").robot.equilibrium(pose=[5.0, 3.0, 1.0])
    assert eq.residual < 1e-10
    assert eq.min_tensions.min() == pytest.approx(100.0, abs=1e-6)


def test_bad_tolerance_and_iteration_count_name_the_argument(cogiro):
    with pytest.raises(InvalidParameterError, match="tol must be finite"):
        cogiro.robot.equilibrium(pose=cogiro.pose, tol=float("nan"))
    with pytest.raises(InvalidParameterError, match="max_iter must be an integer >= 1"):
        cogiro.robot.equilibrium(pose=cogiro.pose, max_iter=0)
    with pytest.raises(InvalidParameterError, match="max_iter"):
        cogiro.robot.equilibrium(unstretched_lengths=[12.0] * 8, max_iter=2.5)


# ------------------------------------------- the batched statics against the scalar solver
def reference_inverse_statics(robot, pose, max_iter=500):
    """The fixed point with every cable solved alone by the bracketing (Brent) search of
    :func:`dynstiff.cable.catenary_solve.unstretched_length_for_tension`, as inverse statics did
    before
    the batched Newton on (H, V0, L0): the reference the batched solver must equal."""
    from dynstiff._vec import cross
    from dynstiff.cable.catenary_solve import unstretched_length_for_tension

    fi = robot.platform.free_index
    B, r = robot.attachment_points(pose)
    u = robot.anchors - B
    u /= np.linalg.norm(u, axis=1)[:, None]
    wg = robot.gravity_wrench(pose)
    t_min, t_max = robot.tension_limits
    lo = np.zeros(robot.n_cables)
    hi = np.zeros(robot.n_cables)
    best, since_best = np.inf, 0
    for _ in range(max_iter):
        W = np.vstack([u.T, cross(r, u).T])[fi]
        t = tension_distribution(W, -wg[fi], t_min + lo, t_max - hi)
        states = [unstretched_length_for_tension(robot.anchors[i], B[i], t[i],
                                                 robot.cables[i], robot.g)
                  for i in range(robot.n_cables)]
        u_new = np.array([s.force_on_end for s in states])
        u_new /= np.linalg.norm(u_new, axis=1)[:, None]
        lo_new = np.array([s.tension_at_end - s.min_tension for s in states])
        hi_new = np.array([s.max_tension - s.tension_at_end for s in states])
        change = max(np.abs(u_new - u).max(),
                     np.abs(np.concatenate([lo_new - lo, hi_new - hi])).max() / t.max())
        u, lo, hi = u_new, lo_new, hi_new
        best, since_best = (change, 0) if change < best else (best, since_best + 1)
        if change < 1e-15 or (best < 1e-9 and since_best >= 10):
            break
    return (np.array([s.unstretched_length for s in states]),
            np.array([s.tension_at_end for s in states]))


def assert_same_statics(eq, ref):
    L0, t = ref
    np.testing.assert_allclose(eq.unstretched_lengths, L0, rtol=1e-9, atol=0)
    np.testing.assert_allclose(eq.tensions, t, rtol=1e-9, atol=0)


@pytest.mark.parametrize("name", ["cogiro", "fourcable", "sixcable", "simulator", "planar2"])
def test_batched_statics_equal_the_scalar_solver_on_every_scene(name):
    sc = ds.load_scene(name)
    eq = sc.equilibrium()
    assert_same_statics(eq, reference_inverse_statics(sc.robot, eq.pose))


@pytest.mark.parametrize("position", [(5.0, 3.0, 1.0), (-4.0, 2.5, 0.5), (2.0, -3.0, 3.5)])
def test_batched_statics_equal_the_scalar_solver_across_the_cogiro_workspace(position):
    robot = ds.load_scene("cogiro").robot
    eq = robot.equilibrium(pose=position)
    assert_same_statics(eq, reference_inverse_statics(robot, eq.pose))


def test_warm_start_from_a_neighbouring_pose_reaches_the_same_equilibrium(cogiro, cogiro_eq):
    """Started from the central equilibrium, the fixed point at a pose 0.4 m away is the one
    reached from straight cables (to 1e-9), in fewer iterations' worth of work."""
    robot = cogiro.robot
    cold = robot.equilibrium(pose=[0.4, -0.2, 1.3])
    warm = robot.equilibrium(pose=[0.4, -0.2, 1.3], start=cogiro_eq)
    assert_same_statics(warm, (cold.unstretched_lengths, cold.tensions))
    assert warm.residual < 1e-10


def test_a_start_that_fails_gives_the_cold_result_or_the_cold_diagnosis(cogiro, cogiro_eq,
                                                                       monkeypatch):
    """A start from which the iteration fails (planted: its distributions fail) gives the
    equilibrium without a start; at an infeasible pose, the error and its diagnosis are
    those without a start, and the start's own failure is not diagnosed (one diagnosis)."""
    from dynstiff.robot import feasibility, statics
    robot = cogiro.robot
    pose = [0.4, -0.2, 1.3]
    real = statics._step_distribution

    def fails_warm(*a, **k):
        if not a[12]:                      # the steps from the start (not diagnosed)
            raise ds.SlackCableError("planted")
        return real(*a, **k)
    with monkeypatch.context() as m:
        m.setattr(statics, "_step_distribution", fails_warm)
        m.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)   # numpy loop
        warm = robot.equilibrium(pose=pose, start=cogiro_eq)
        cold = robot.equilibrium(pose=pose)
    np.testing.assert_array_equal(warm.tensions, cold.tensions)
    far = [7.4, 5.2, 0.5]
    with pytest.raises(ds.InfeasiblePoseError) as without:
        robot.equilibrium(pose=far)
    diagnosed = []
    real_diagnose = statics.diagnose_limits

    def counted(*a, **k):
        diagnosed.append(1)
        return real_diagnose(*a, **k)
    monkeypatch.setattr(statics, "diagnose_limits", counted)
    with pytest.raises(ds.InfeasiblePoseError) as with_start:
        robot.equilibrium(pose=far, start=cogiro_eq)
    assert str(with_start.value) == str(without.value)
    assert len(diagnosed) == 1
    assert feasibility.diagnose_limits is real_diagnose


def test_warm_start_must_be_an_equilibrium_of_the_same_robot(cogiro):
    other = ds.load_scene("sixcable").equilibrium()
    with pytest.raises(InvalidParameterError, match="start"):
        cogiro.robot.equilibrium(pose=cogiro.pose, start=other)
    with pytest.raises(InvalidParameterError, match="start"):
        cogiro.robot.equilibrium(pose=cogiro.pose, start="warm")


@pytest.mark.slow
def test_batched_statics_equal_the_scalar_solver_on_a_1000_pose_cogiro_grid():
    """10 x 10 x 10 positions over the CoGiRo workspace. Started from straight cables, the
    batched solver fails exactly where the scalar one does and otherwise equals it (1e-9).
    Warm-started from the previous pose (as a workspace map does) it equals it too; near
    the edge of the workspace it may also find an equilibrium that the iteration from
    straight cables misses (the straight-cable tensions left the limits at an early
    iteration), and so may the solver started cold, whose first iteration is relaxed: such
    an equilibrium must be a true one within the limits, the same from both starts."""
    robot = ds.load_scene("cogiro").robot
    t_min, t_max = robot.tension_limits
    grid = np.stack(np.meshgrid(np.linspace(-5.0, 5.0, 10), np.linspace(-3.5, 3.5, 10),
                                np.linspace(0.3, 3.6, 10), indexing="ij"), -1).reshape(-1, 3)
    prev, n_ok, n_extra = None, 0, 0
    for p in grid:
        try:
            warm = robot.equilibrium(pose=p, start=prev)
        except SlackCableError:
            warm = None
        try:
            ref = reference_inverse_statics(robot, ds.Pose(p))
        except SlackCableError:
            # the reference starts from straight cables and stops where their tensions leave
            # the limits; the solver relaxes its first iteration (theory.md §4) and may solve
            try:
                cold = robot.equilibrium(pose=p)
            except SlackCableError:
                cold = None
            found = [eq for eq in (cold, warm) if eq is not None]
            n_extra += bool(found)
            for eq in found:                # then a true equilibrium within the limits
                assert eq.residual < 1e-10
                assert np.all(eq.min_tensions >= t_min - 1e-6)
                assert np.all(eq.max_tensions <= t_max + 1e-6)
            if cold is not None and warm is not None:
                np.testing.assert_allclose(cold.tensions, warm.tensions, rtol=1e-8)
            if warm is not None:
                prev = warm
            continue
        assert_same_statics(robot.equilibrium(pose=p), ref)
        assert warm is not None
        assert_same_statics(warm, ref)
        prev, n_ok = warm, n_ok + 1
    assert n_ok > 500
    assert n_extra < 0.02 * len(grid)


def test_warm_active_set_gives_the_lp_started_distribution_bitwise(monkeypatch):
    """The fixed point starts each tension distribution from the previous iteration's active
    set instead of the LP's feasible point: on CoGiRo grid poses where the limits are
    active, the equilibria equal (bitwise) those of the LP-started distribution."""
    from dynstiff.robot import statics

    robot = ds.load_scene("cogiro").robot
    poses = [ds.Pose([x, y, z]) for x in (-5.0, -3.9, 3.9) for y in (-3.5, 0.4)
             for z in (0.5, 1.6, 3.0)]
    warm, used = [], []
    plain = statics._distribution
    monkeypatch.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)  # numpy loop

    def spy(W, w, t_min, t_max, t_ref=None, sides=None):
        used.append(sides is not None and bool(np.any(sides)))
        return plain(W, w, t_min, t_max, t_ref, sides)
    monkeypatch.setattr(statics, "_distribution", spy)
    for p in poses:
        try:
            warm.append(robot.equilibrium(pose=p))
        except SlackCableError:
            warm.append(None)
    assert sum(used) >= 20                  # the warm start was tried
    monkeypatch.setattr(statics, "_distribution",
                        lambda W, w, lo, hi, r=None, sides=None: plain(W, w, lo, hi, r,
                                                                       warm=False))
    for p, eq in zip(poses, warm):
        if eq is None:
            with pytest.raises(SlackCableError):
                robot.equilibrium(pose=p)
            continue
        cold = robot.equilibrium(pose=p)
        np.testing.assert_array_equal(eq.tensions, cold.tensions)
        np.testing.assert_array_equal(eq.unstretched_lengths, cold.unstretched_lengths)


def test_forward_statics_with_its_defaults_inverts_inverse_statics():
    """statics.forward_statics called with its own defaults (tol 1e-10) returns the pose
    whose inverse statics gave the lengths, to 1e-9 m, and the same tensions."""
    import dynstiff as ds
    from dynstiff.robot.forward_statics import forward_statics
    rob = ds.load_scene("cogiro").robot
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.1, 0.02, -0.01, 0.03])
    fe = forward_statics(rob, eq.unstretched_lengths)
    assert type(fe.residual) is float and fe.residual <= 1e-10
    np.testing.assert_allclose(fe.pose.position, eq.pose.position, rtol=0, atol=1e-9)
    np.testing.assert_allclose(fe.tensions, eq.tensions, rtol=1e-9)


def test_vertical_cable_on_the_moon_has_the_analytic_length_and_no_warning():
    """A platform (10 kg, only z free) on one vertical cable (0.5 kg/m, EA 2e4 N) at
    g = 1.62 m/s^2, chord 4 m: T_B = m g, and the unstretched length solves
    L = L0 + (T_B L0 + w0 L0^2 / 2) / EA with w0 = m_c g (the tension grows linearly up a
    vertical cable). The vertical cable is left to the scalar solver, which must get the
    robot's g; no floating-point warning is raised on the way, and forward statics from
    those lengths returns the pose."""
    import warnings
    g, m, mc, EA, L = 1.62, 10.0, 0.5, 2.0e4, 4.0
    rob = ds.Robot([[0.0, 0.0, 5.0]], [[0.0, 0.0, 0.0]], [ds.Cable(mc, EA)],
                   ds.Platform(mass=m, free_dofs=("z",)), g=g)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        eq = rob.equilibrium(pose=[0.0, 0.0, 1.0])
        fe = rob.equilibrium(unstretched_lengths=eq.unstretched_lengths,
                             initial_pose=[0.0, 0.0, 0.5])
    a, b = mc * g / (2 * EA), 1.0 + m * g / EA
    L0 = 2 * L / (b + np.sqrt(b * b + 4 * a * L))        # the root without cancellation
    assert eq.tensions[0] == pytest.approx(m * g, rel=1e-14)
    assert eq.unstretched_lengths[0] == pytest.approx(L0, rel=1e-13)
    assert eq.states[0].H == 0.0
    np.testing.assert_allclose(fe.pose.position, [0.0, 0.0, 1.0], rtol=0, atol=1e-12)


@pytest.mark.parametrize("free, com, at_p", [(("x", "z", "rx", "ry", "rz"), None, False),
                                             (("x", "y", "z", "ry", "rz"), None, False),
                                             (("x", "y", "z", "rx", "ry"), None, False),
                                             (("x", "y", "z", "rx", "ry"), (0, 0, 0), False),
                                             (("x", "y", "z", "rx", "ry"), (0, 0, -0.3), True)])
def test_forward_statics_needs_initial_pose_for_any_held_coordinate(cogiro, cogiro_eq, free,
                                                                     com, at_p):
    """One held translation (y) or one held rotation (rx or rz) alone makes the initial pose
    necessary, when rotations matter: attachment points off the reference point (whatever
    the centre of mass), or all cables at P and the centre of mass off it."""
    p = cogiro.robot.platform
    com = p.center_of_mass if com is None else com
    attach = np.zeros_like(cogiro.robot.attachments) if at_p else cogiro.robot.attachments
    rob = ds.Robot(cogiro.robot.anchors, attach, cogiro.robot.cables,
                   ds.Platform(p.mass, com, p.inertia, free_dofs=free),
                   tension_limits=cogiro.robot.tension_limits)
    with pytest.raises(InvalidParameterError, match="^initial_pose is required when DOFs are"):
        rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)


def test_equilibrium_states_carry_their_catenary_residuals_and_failures_theirs():
    """Every cable state of inverse statics keeps the residual of its catenary solution
    (a float at the solver's tolerance). A wrench residual above tol is refused with it, and
    a fixed point cut short by max_iter says how much the cable directions still change."""
    from dynstiff.errors import ConvergenceError
    rob = ds.load_scene("cogiro").robot
    eq = rob.equilibrium(pose=[0.5, -0.3, 1.5])
    res = [s.residual for s in eq.states]
    assert all(type(r) is float for r in res) and max(res) < 1e-10
    assert eq.residual > 1e-15                # rounding of the 8-cable wrench sum
    with pytest.raises(ConvergenceError, match=r"^inverse statics: wrench residual \S+ "
                                               r"\(relative to m g\) > tol 1e-15 at pose") as err:
        rob.equilibrium(pose=[0.5, -0.3, 1.5], tol=1e-15)
    assert err.value.residual == eq.residual
    with pytest.raises(ConvergenceError, match=r"^inverse statics: cable directions still "
                                               r"change by \S+ after 1 iterations \(max_iter\)"
                       ) as err:
        rob.equilibrium(pose=[0.5, -0.3, 1.5], max_iter=1)
    assert isinstance(err.value.residual, float) and 1e-15 < err.value.residual < 1.0


def test_straight_chord_guess_is_near_the_sagging_equilibrium():
    """The start of forward statics (straight chords of 0.999 L0 fitted to the lengths)
    lands within 0.15 m and 0.02 rad of the CoGiRo equilibrium, rotation included."""
    from dynstiff.robot.forward_statics import _kinematic_guess
    rob = ds.load_scene("cogiro").robot
    for pose in ([0.3, -0.2, 1.1, 0.02, -0.01, 0.03], [1.0, 0.5, 2.0, 0.1, -0.05, 0.25]):
        eq = rob.equilibrium(pose=pose)
        guess = _kinematic_guess(rob, eq.unstretched_lengths).as_vector()
        assert np.abs(guess[:3] - pose[:3]).max() < 0.15
        assert np.abs(guess[3:] - pose[3:]).max() < 0.02


def test_a_vertical_cable_rising_from_a_floor_anchor_is_held_at_t_min_at_its_anchor():
    """Three cables from above and one straight down to a floor anchor 5 m below a 1 kg
    point mass: the distribution drives the lower cable to its least tension, which is at
    its anchor, T_A = t_min (to the fixed point's 1e-8); at B it carries its whole weight on
    top, T_B = T_A + w0 L0 (vertical cable). The first iteration must not ask it for t_min
    at B, below its own weight, which no catenary can have."""
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    A = np.vstack([A, [0.3, -0.2, -4.0]])
    cab = ds.Cable(0.064, 1.4e5)
    rob = ds.Robot(A, np.zeros((4, 3)), cab, ds.Platform(1.0, free_dofs=("x", "y", "z")),
                   tension_limits=(0.01, 1e6))
    eq = rob.equilibrium(pose=[0.3, -0.2, 1.0])
    low = eq.states[3]
    w0 = cab.mass_per_length * rob.g
    assert low.tension_at_anchor == pytest.approx(0.01, rel=1e-8)
    assert low.tension_at_end == pytest.approx(low.tension_at_anchor
                                               + w0 * low.unstretched_length, rel=1e-14)
    assert eq.residual < 1e-10
    assert all(s.min_tension >= 0.01 * (1 - 1e-8) for s in eq.states)


def test_the_upper_limit_holds_along_the_whole_cable():
    """CoGiRo at (0.3, -0.2, 1.1) with t_max 5 % above the default solution's largest
    tension and a reference tension far above it: the distribution presses the tensions up
    to the limit, which binds where the tension is largest, at the upper anchor. Two cables
    reach exactly t_max there, their platform ends t_max minus the weight of their drop h,
    w0 h / (1 + T/EA) from dT = w0 dz / (1 + T/EA) (theory.md §4), and no cable exceeds
    t_max anywhere."""
    import dataclasses
    rob = ds.load_scene("cogiro").robot
    pose = [0.3, -0.2, 1.1]
    t_max = 1.05 * max(s.max_tension for s in rob.equilibrium(pose=pose).states)
    eq = dataclasses.replace(rob, tension_limits=(100.0, t_max)).equilibrium(
        pose=pose, tension_reference=1e4)
    top = np.array([s.max_tension for s in eq.states])
    assert np.all(top <= t_max * (1 + 1e-9))
    at_limit = np.flatnonzero(top > t_max * (1 - 1e-9))
    assert len(at_limit) == 2
    for i in at_limit:
        s = eq.states[i]
        assert s.tension_at_anchor == pytest.approx(t_max, rel=1e-9)
        drop = s.cable.weight_per_length(s.g) * (s.anchor[2] - s.end[2])
        assert t_max - eq.tensions[i] == pytest.approx(drop / (1 + t_max / s.cable.EA),
                                                       rel=1e-4)


def test_forward_statics_whose_newton_cannot_descend_says_so(monkeypatch):
    """With the platform stiffness of the wrong sign, no step of the line search lowers the
    wrench residual: ConvergenceError with that residual, not a pose."""
    from dynstiff.errors import ConvergenceError
    from dynstiff.robot.forward_statics import forward_statics
    rob = ds.load_scene("cogiro").robot
    L0 = rob.equilibrium(pose=[0.3, -0.2, 1.1]).unstretched_lengths
    orig = ds.Robot.platform_stiffness
    monkeypatch.setattr(ds.Robot, "platform_stiffness", lambda self, *a: -orig(self, *a))
    with pytest.raises(ConvergenceError, match="^forward statics did not converge") as err:
        forward_statics(rob, L0)
    assert isinstance(err.value.residual, float) and err.value.residual > 1e-10


def test_heavy_cables_whose_straight_chords_miss_the_limits_are_solved():
    """The FAST scene 10 deg off its zenith (cables of 0.89 times the cabin's mass): the
    straight chords' limits [120, 1200] kN have no distribution, the catenaries' have one
    (theory.md §4; with the lower limit relaxed to 1 N the least tension is above 120 kN
    anyway): the pose is solved, within the limits along every cable, and balanced."""
    import dataclasses
    robot = ds.load_scene("fast").robot
    t = np.deg2rad(10.0)
    r = 300.0 * (1 - 0.4611)                              # focal surface radius [m]
    pose = [r * np.sin(t), 0.0, 300.0 - r * np.cos(t)]
    eq = robot.equilibrium(pose=pose)
    lo, hi = robot.tension_limits
    assert np.min(eq.min_tensions) >= lo * (1 - 1e-9) and np.max(eq.max_tensions) <= hi
    assert np.abs(robot.wrench(eq.pose, eq.states)[robot.platform.free_index]).max() < 1e-6
    relaxed = dataclasses.replace(robot, tension_limits=(1.0, hi)).equilibrium(pose=pose)
    assert np.min(relaxed.min_tensions) > lo


def test_a_weight_that_overflows_is_refused_by_name():
    """A platform mass whose weight overflows float64 (1.8e307 kg, found by the scene-file
    fuzzer) is refused naming the platform, not passed to the tension distribution's linear
    program as inf."""
    import dataclasses
    scene = ds.load_scene("cogiro")
    robot = dataclasses.replace(scene.robot, platform=dataclasses.replace(
        scene.robot.platform, mass=1.8325108408382424e307))
    with pytest.raises(ds.InvalidParameterError, match="platform: its weight"):
        robot.equilibrium(pose=scene.pose)


def test_forward_statics_with_lengths_that_cannot_reach_says_it_did_not_converge():
    """planar2 with unstretched lengths of 1e-300 m (found by the statics fuzzer): the
    straight cable's strain to its chord overflows float64; the error names the unstretched
    length, never a non-finite pose reached by a Newton step (a step to a non-finite pose
    counts as a failed step), and no overflow warning is raised on the way."""
    scene = ds.load_scene("planar2")
    with pytest.raises(ds.InvalidParameterError, match="unstretched_length 1e-300 m"):
        scene.robot.equilibrium(unstretched_lengths=[1e-300, 1e-300], initial_pose=scene.pose)


def test_a_neighbours_cable_directions_turn_with_their_chords():
    """The warm start's directions keep their angle to the chord while the chord turns to
    the new pose; the same chord leaves them as they are, and so does a chord turned past
    120 degrees (no neighbour)."""
    from dynstiff.robot.statics import _carried
    rng = np.random.default_rng(3)
    c_old = rng.normal(size=(50, 3))
    c_new = c_old + 0.5 * rng.normal(size=(50, 3))
    u = c_old / np.linalg.norm(c_old, axis=1)[:, None] + 0.05 * rng.normal(size=(50, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    v = _carried(u, c_old, c_new)
    unit = lambda x: x / np.linalg.norm(x, axis=1)[:, None]   # noqa: E731
    cos_old = np.einsum("ij,ij->i", u, unit(c_old))
    cos_new = np.einsum("ij,ij->i", v, unit(c_new))
    near = np.einsum("ij,ij->i", unit(c_old), unit(c_new)) > -0.5
    assert 0 < np.sum(~near) < 10
    np.testing.assert_allclose(cos_new[near], cos_old[near], atol=1e-12)
    np.testing.assert_allclose(v[~near], u[~near], atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(v, axis=1), 1.0, atol=1e-15)
    np.testing.assert_allclose(_carried(u, c_old, 2.0 * c_old), u, atol=1e-15)


@pytest.mark.parametrize("ref, message", [
    ([True] * 8, "^tension_reference must be real numbers, not booleans"),
    ("a", r"^tension_reference must be one tension or 8 \[N\], got 'a'$"),
    ([np.nan] * 8, r"^tension_reference must be one tension or 8 finite tensions \[N\]"),
    ([1.0, 2.0, 3.0], r"^tension_reference must be one tension or 8 finite tensions \[N\]")])
def test_a_tension_reference_that_is_not_one_is_refused(ref, message):
    """A NaN reference came out as scipy's LinAlgError, text as numpy's ValueError, and
    booleans were a reference of 1 N."""
    sc = ds.load_scene("cogiro")
    with pytest.raises(InvalidParameterError, match=message):
        sc.robot.equilibrium(pose=sc.pose, tension_reference=ref)


def test_one_reference_tension_is_the_same_for_every_cable():
    sc = ds.load_scene("cogiro")
    one = sc.robot.equilibrium(pose=sc.pose, tension_reference=500.0).tensions
    each = sc.robot.equilibrium(pose=sc.pose, tension_reference=[500.0] * 8).tensions
    np.testing.assert_array_equal(one, each)
