"""The compiled fixed point of inverse statics (dynstiff/compiled/statics.py, theory.md §13.6)
against the numpy loop of dynstiff/robot/statics.py: over grids of poses of every built-in
scene, warm-started along chunks as a map does, the same feasibility and the same equilibria
to 1e-12; the regular case is compiled, everything else goes to the numpy loop."""

import warnings

import numpy as np
import pytest

import dynstiff as ds
from dynstiff import compiled
from dynstiff.robot import statics

pytestmark = pytest.mark.skipif(compiled.load("statics") is None,
                                reason="numba not installed or switched off")


def _grid(scene, k=4):
    box = scene.workspace_box
    if box is None:
        c = scene.pose.position if scene.pose is not None else scene.robot.anchors.mean(0)
        box = [c[0] - 1, c[0] + 1, c[1] - 1, c[1] + 1, c[2] - 0.5, c[2] + 0.5]
    axes = [np.linspace(box[2 * i], box[2 * i + 1], k) for i in range(3)]
    g = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    rot = scene.pose.rotation if scene.pose is not None else np.zeros(3)
    return np.hstack([g, np.tile(rot, (len(g), 1))])


def _run(robot, X, chunk=16):
    out, prev = [], None
    for i, x in enumerate(X):
        if i % chunk == 0:
            prev = None
        try:
            try:
                eq = robot.equilibrium(pose=x, start=prev)
            except ds.DynstiffError:
                if prev is None:
                    raise
                eq = robot.equilibrium(pose=x)
            prev = eq
            out.append(np.r_[eq.tensions, eq.unstretched_lengths,
                             [s.H for s in eq.states]])
        except ds.DynstiffError:
            prev = None
            out.append(np.full(3 * robot.n_cables, np.nan))
    return np.array(out)


@pytest.mark.parametrize("name", ds.list_scenes())
def test_the_compiled_fixed_point_is_the_numpy_loop(name, monkeypatch):
    scene = ds.load_scene(name)
    X = _grid(scene)
    used = []
    fixed = statics._compiled_fixed_point

    def counted(*a, **k):
        out = fixed(*a, **k)
        used.append(out is not None)
        return out
    monkeypatch.setattr(statics, "_compiled_fixed_point", counted)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.DynstiffWarning)   # edge poses of some scenes
        fast = _run(scene.robot, X)
        monkeypatch.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)
        ref = _run(scene.robot, X)
    np.testing.assert_array_equal(np.isnan(fast[:, 0]), np.isnan(ref[:, 0]))
    np.testing.assert_allclose(fast, ref, rtol=1e-12, atol=0)
    if name in ("cogiro", "sixcable", "planar2", "pendulum"):    # the regular case there
        assert np.mean(used) > 0.95
    assert np.isfinite(ref[:, 0]).any()


def test_a_distribution_that_needs_the_lp_is_found_by_it_and_the_kernel_goes_on(monkeypatch):
    """The motion simulator at its pose: its first distribution needs the LP's feasible point
    (no active set from the limits gives a feasible start). The numpy distribution finds the
    optimum's active set, the kernel goes on from it, and the equilibrium is the numpy
    loop's."""
    scene = ds.load_scene("simulator")
    result, start = statics._compiled_fixed_point(*_arguments(scene.robot, scene.pose))
    assert start is None
    eq = scene.robot.equilibrium(pose=scene.pose)
    monkeypatch.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)
    ref = scene.robot.equilibrium(pose=scene.pose)
    np.testing.assert_allclose(eq.tensions, ref.tensions, rtol=1e-12)
    np.testing.assert_allclose(eq.unstretched_lengths, ref.unstretched_lengths, rtol=1e-12)
    np.testing.assert_allclose(result[0], ref.tensions, rtol=1e-12)


def test_the_numpy_loop_goes_on_from_the_kernels_state(monkeypatch):
    """A kernel stopped after 3 iterations (planted: as if it had not converged) hands its
    state to the numpy loop, which ends at the same equilibrium as from the start."""
    kernels = compiled.load("statics")
    real, seen = kernels.fixed_point, []

    def three_then_stop(*a):
        out = real(*a[:-1], 3)
        seen.append(out[1])
        return (kernels._NUMPY,) + out[1:]
    robot = ds.load_scene("cogiro").robot
    x = [1.0, -0.5, 2.0, 0.0, 0.0, 0.1]
    monkeypatch.setattr(kernels, "fixed_point", three_then_stop)
    eq = robot.equilibrium(pose=x)
    monkeypatch.undo()
    assert seen == [3]
    monkeypatch.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)
    ref = robot.equilibrium(pose=x)
    np.testing.assert_allclose(eq.tensions, ref.tensions, rtol=1e-12)
    np.testing.assert_allclose(eq.unstretched_lengths, ref.unstretched_lengths, rtol=1e-12)


def test_the_numpy_loop_goes_on_from_where_the_kernel_stopped(monkeypatch):
    """Infeasible CoGiRo poses (outside the frame's wrench-feasible set): the kernel stops at
    the distribution with no feasible point, and the numpy loop, from the kernel's state,
    raises the same error as from the start."""
    robot = ds.load_scene("cogiro").robot
    for x in ([7.4, 5.2, 0.5, 0, 0, 0], [-7.2, 0.0, 5.5, 0, 0, 0]):
        with pytest.raises(ds.DynstiffError) as fast:
            robot.equilibrium(pose=x)
        with monkeypatch.context() as m:
            m.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)
            with pytest.raises(ds.DynstiffError) as ref:
                robot.equilibrium(pose=x)
        assert type(fast.value) is type(ref.value)
        assert str(fast.value) == str(ref.value)


def _arguments(robot, pose):
    """The arguments of _compiled_fixed_point for a cold start at ``pose``."""
    fi = robot.platform.free_index
    B, r = robot.attachment_points(pose)
    A = robot.anchors
    w0 = np.array([c.mass_per_length for c in robot.cables]) * robot.g
    EA = np.array([c.EA for c in robot.cables])
    u = (A - B) / np.linalg.norm(A - B, axis=1)[:, None]
    t_min, t_max = robot.tension_limits
    lo = np.maximum(0.0, w0 * (B[:, 2] - A[:, 2]))
    return (pose, A, B, r, fi, -robot.gravity_wrench(pose)[fi], EA, w0, t_min, t_max, None, u, lo,
            np.zeros(len(EA)), None, 50)
