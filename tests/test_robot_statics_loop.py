"""The numpy loop of inverse statics (dynstiff/robot/statics.py, ``_fixed_point``, theory.md
§4): the fixed point of cable directions and tension distribution run without the compiled
kernel (``dynstiff.compiled.load`` gives None for "statics", as without numba): its exit
rule (a linear contraction's remaining change below rounding) and the messages of a cable
that the scalar catenary solver cannot bring to the asked tension."""

import numpy as np
import pytest

import dynstiff as ds
import dynstiff.compiled
from dynstiff.errors import InfeasiblePoseError, SlackCableError
from dynstiff.robot import statics

UPPER = [[-4.0, -3.0, 5.0], [4.5, -2.0, 5.2], [0.3, 4.0, 4.8]]


@pytest.fixture
def numpy_loop(monkeypatch):
    """Inverse statics by the numpy loop from the start."""
    load = dynstiff.compiled.load
    monkeypatch.setattr(dynstiff.compiled, "load",
                        lambda name: None if name == "statics" else load(name))


def heavy_rising_cable():
    """Three upper cables and a heavy one (0.2 kg/m) rising 2 m from a low anchor to the
    point-mass platform at [0, 0, 2]: the distribution asks it less tension than any
    catenary between its ends has at the platform."""
    return ds.Robot(np.asarray(UPPER + [[3.0, 3.0, 0.0]], float), np.zeros((4, 3)),
                    ds.Cable(0.2, 1e6), ds.Platform(20.0, free_dofs=("x", "y", "z")),
                    tension_limits=(1.0, np.inf))


@pytest.mark.usefixtures("numpy_loop")
def test_unreachable_cable_is_diagnosed_at_its_pose():
    """The scalar solver's failure is diagnosed (cable 3, the cable's weight) and the
    message starts with the pose it was asked at."""
    pose = [0.0, 0.0, 2.0]
    with pytest.raises(InfeasiblePoseError) as err:
        heavy_rising_cable().equilibrium(pose=pose)
    assert err.value.cable == 3 and err.value.cause == "cable weight"
    assert str(err.value).startswith("pose [0.0, 0.0, 2.0, 0.0, 0.0, 0.0]: cable 3 (rising 2 m")


@pytest.mark.usefixtures("numpy_loop")
def test_undiagnosed_unreachable_cable_names_the_pose_and_the_solver(monkeypatch):
    """Without a diagnosis (another cause), the scalar solver's own SlackCableError is
    raised, prefixed by the pose."""
    monkeypatch.setattr(statics, "diagnose_unreachable", lambda *a: None)
    with pytest.raises(SlackCableError) as err:
        heavy_rising_cable().equilibrium(pose=[0.0, 0.0, 2.0])
    assert not isinstance(err.value, InfeasiblePoseError)
    assert str(err.value).startswith("pose [0.0, 0.0, 2.0, 0.0, 0.0, 0.0]: tension ")
    assert "not reachable" in str(err.value)


def fast_off_zenith():
    """The FAST scene 10 deg off its zenith: cables of 0.89 times the cabin's mass, tensions
    of 120-1200 kN."""
    t, r = np.deg2rad(10.0), 300.0 * (1 - 0.4611)      # focal surface radius [m]
    return ds.load_scene("fast").robot, [r * np.sin(t), 0.0, 300.0 - r * np.cos(t)]


@pytest.mark.usefixtures("numpy_loop")
@pytest.mark.parametrize("robot_pose", ["point mass, centre", "point mass, off centre",
                                        "FAST, 10 deg"])
def test_loop_stops_once_the_contraction_leaves_rounding_to_go(monkeypatch, robot_pose):
    """Each iteration's change (of the directions, and of the margins relative to the
    largest tension) is recorded from the iterates; the loop goes on while the change is
    at least 1e-15 and, for a linear contraction rho = change / last < 0.5, the change
    still to go (rho / (1 - rho) change) is at least 2e-16, and stops at the first
    iteration where it is not (no wasted iteration). The point-mass robot contracts fast
    (rho ~ 1e-2), so this rule, not change < 1e-15, ends the loop. FAST's heavy cables
    contract slowly (rho ~ 0.4), their margins (~1e4 N) changing with the directions:
    relative to the largest tension (~1e6 N) that change is below the directions' (scaled
    by it instead, it would keep the loop going to its limit)."""
    from conftest import point_mass_robot
    robot, pose = {"point mass, centre": (point_mass_robot(), [0.0, 0.0, 1.0]),
                   "point mass, off centre": (point_mass_robot(), [0.5, 0.3, 1.2]),
                   "FAST, 10 deg": fast_off_zenith()}[robot_pose]
    calls = []
    step, ends = statics._step_distribution, statics._end_quantities

    def step_spy(*a, **k):
        out = step(*a, **k)
        calls.append([a[2].copy(), a[7].copy(), a[8].copy(), out[0].copy()])
        return out

    def ends_spy(*a, **k):
        out = ends(*a, **k)
        calls[-1].append(out)
        return out

    monkeypatch.setattr(statics, "_step_distribution", step_spy)
    monkeypatch.setattr(statics, "_end_quantities", ends_spy)
    eq = robot.equilibrium(pose=pose)
    assert eq.residual < 1e-10
    changes = [max(np.abs(u1 - u).max(),
                   np.abs(np.concatenate([lo1 - lo, hi1 - hi])).max() / t.max())
               for u, lo, hi, t, (u1, lo1, hi1) in calls]
    done = [c < 1e-15 or (0 < c / p < 0.5 and c * (c / p) / (1 - c / p) < 2e-16)
            for p, c in zip([np.inf] + changes[:-1], changes)]
    assert len(changes) >= 3
    assert done[-1] and not any(done[:-1])
    if robot_pose.startswith("point mass"):
        assert changes[-1] >= 1e-15              # the contraction rule ended it


@pytest.mark.usefixtures("numpy_loop")
def test_the_relaxed_first_distribution_is_a_start_only(cogiro):
    """Straight chords may get a first distribution down to 1e-3 t_min (theory.md §4); the
    catenaries' distributions keep t_min. CoGiRo moved 5.5 m along x needs a cable below
    t_min = 100 N: the pose is refused (as by the compiled loop), never returned with that
    tension."""
    pose = cogiro.pose.position + [5.5, 0.0, 0.0]
    with pytest.raises(InfeasiblePoseError):
        cogiro.robot.equilibrium(pose=pose)
    eq = cogiro.robot.equilibrium(pose=cogiro.pose.position + [5.25, 0.0, 0.0])
    assert min(s.tension_at_end for s in eq.states) >= 100.0 * (1 - 1e-9)


@pytest.mark.parametrize("loop", ["compiled", "numpy"])
def test_a_relaxed_start_below_any_catenary_is_a_start_not_the_refusal(monkeypatch, loop):
    """Three upper cables and one rising 2.87 m from a low anchor to a 37.39 kg point mass,
    limits [t_min, 18045.1] N. The straight chords fit no distribution; the relaxed start
    (lower limits 1e-3 t_min + lo) asks the rising cable 1.09 N, less than any catenary
    between its ends has at the platform (1.66 N): it starts from the catenary of least
    tension there, and the refusal is the limits', with a remedy that holds. The null space
    of the balance trades the rising cable's tension against cable 1's, so the pose holds
    for t_min up to about the stated value only: just below it the pose is solved with the
    rising cable at t_min and cable 1 within 1 % of it, 1 % above it is refused. (The
    start's tension was taken as the request: 'raise t_min to above about 76.47 N', which
    no t_min satisfies.) The same robot under g = 3.71 m/s^2, its masses scaled to the
    same weights, gets the same remedy."""
    if loop == "numpy":
        load = dynstiff.compiled.load
        monkeypatch.setattr(dynstiff.compiled, "load",
                            lambda name: None if name == "statics" else load(name))
    A = np.array([[0.24, 4.6, 6.31], [-3.94, -2.4, 6.31], [3.73, -2.72, 6.31],
                  [-2.34, -0.93, -2.08]])

    def robot(t_min, g=ds.STANDARD_GRAVITY):
        k = ds.STANDARD_GRAVITY / g                   # the same weights under gravity g
        return ds.Robot(A, np.zeros((4, 3)), ds.Cable(0.036 * k, 1e6),
                        ds.Platform(37.39 * k, free_dofs=("x", "y", "z")),
                        tension_limits=(t_min, 18045.1), g=g)
    pose = [0.58, 1.32, 0.79]
    with pytest.raises(InfeasiblePoseError, match=r"no tension distribution within "
                       r"\[75\.9, 18045\.1\] N balances the platform") as info:
        robot(75.9).equilibrium(pose=pose)
    bound = info.value.remedies["t_min"]
    assert 40.0 < bound < 75.9
    with pytest.raises(InfeasiblePoseError) as mars:    # statics see weights only
        robot(75.9, g=3.71).equilibrium(pose=pose)
    assert mars.value.remedies["t_min"] == pytest.approx(bound, rel=1e-9)
    t_min = bound * (1 - 1e-3)
    eq = robot(t_min).equilibrium(pose=pose)
    assert eq.min_tensions[3] == pytest.approx(t_min, rel=1e-8)    # the rising cable
    assert t_min < eq.min_tensions[1] < 1.01 * t_min                # cable 1, near its limit
    assert eq.min_tensions.min() >= t_min * (1 - 1e-9)
    with pytest.raises(InfeasiblePoseError, match="no tension distribution within"):
        robot(bound * (1 + 1e-2)).equilibrium(pose=pose)


@pytest.mark.usefixtures("numpy_loop")
@pytest.mark.parametrize("delta", [1e-13, 1e-7])
def test_a_stalled_loop_stops_only_below_1e_9(monkeypatch, delta):
    """A planted toggle of +-delta on one direction component at every iteration keeps the
    change at about 1.99 delta for good (the contraction takes back a little of the 2
    delta; rounding makes it wander among a few values, some repeated exactly). At 2e-13
    (below 1e-9) the loop stops 10 iterations after its smallest change (an equal one is
    not a new smallest), well before max_iter, and the platform is balanced; at 2e-7 it
    never stalls: ConvergenceError naming the change after max_iter iterations, not a
    wrench residual."""
    from conftest import point_mass_robot
    ends, step, count, seen = statics._end_quantities, statics._step_distribution, [], []

    def toggled(*a, **k):
        u, lo, hi = ends(*a, **k)
        count.append(1)
        u = u.copy()
        u[0, 0] += delta * (-1) ** len(count)
        seen[-1].append((u, lo, hi))
        return u, lo, hi

    def step_spy(*a, **k):
        out = step(*a, **k)
        seen.append([a[2].copy(), a[7].copy(), a[8].copy(), out[0].copy()])
        return out
    monkeypatch.setattr(statics, "_end_quantities", toggled)
    monkeypatch.setattr(statics, "_step_distribution", step_spy)
    robot, pose = point_mass_robot(), ds.Pose([0.5, 0.3, 1.2])
    if delta < 1e-9:
        eq = statics.inverse_statics(robot, pose, max_iter=200)
        assert eq.residual < 1e-10
        changes = [max(np.abs(u1 - u).max(),
                       np.abs(np.concatenate([lo1 - lo, hi1 - hi])).max() / t.max())
                   for u, lo, hi, t, (u1, lo1, hi1) in seen]
        best, since, last, stop = np.inf, 0, np.inf, None
        for k, c in enumerate(changes):           # the documented exit rule, from the iterates
            best, since = (c, 0) if c < best else (best, since + 1)
            rho, last = (c / last if 0 < last < np.inf else 1.0), c
            if c < 1e-15 or (rho < 0.5 and c * rho / (1 - rho) < 2e-16) or \
                    (best < 1e-9 and since >= 10):
                stop = k
                break
        assert stop is not None and len(count) == stop + 1 < 60
        assert since == 10 and changes[stop] >= 1e-15              # the stall ended it
    else:
        with pytest.raises(ds.ConvergenceError,
                           match=r"cable directions still change by 1\.99e-07 after 60 "):
            statics.inverse_statics(robot, pose, max_iter=60)
        assert len(count) == 60


def test_a_relaxed_start_whose_least_tension_is_not_found_is_diagnosed(monkeypatch):
    """Where no catenary between the cable's ends could be solved (the least end tension
    inf), the relaxed start is not moved: the cable's unreachable tension is diagnosed as the
    refusal, with the pose and the cable's weight."""
    monkeypatch.setattr(statics, "least_end_tension", lambda *a: (np.inf, 5.0))
    A = np.array([[0.24, 4.6, 6.31], [-3.94, -2.4, 6.31], [3.73, -2.72, 6.31],
                  [-2.34, -0.93, -2.08]])
    robot = ds.Robot(A, np.zeros((4, 3)), ds.Cable(0.036, 1e6),
                     ds.Platform(37.39, free_dofs=("x", "y", "z")), tension_limits=(75.9, 18045.1))
    with pytest.raises(InfeasiblePoseError, match=r"^pose \[0\.58, 1\.32, 0\.79, 0\.0, 0\.0, "
                       r"0\.0\]: cable 3 \(rising 2\.87 m to the platform") as err:
        robot.equilibrium(pose=[0.58, 1.32, 0.79])
    assert err.value.cause == "cable weight"
