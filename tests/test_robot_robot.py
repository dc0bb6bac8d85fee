"""The robot (dynstiff/robot/robot.py): bad inputs raise naming the field, each stiffness of a
robot at a pose has its own name (theory.md §4), and cables may share an anchor or an
attachment point (an inverted Stewart platform of the NIST RoboCrane type, theory.md §15.1)
but not both ends."""

import numpy as np
import pytest
from conftest import inverted_stewart

import dynstiff as ds
from dynstiff.errors import InvalidParameterError


def test_bad_robot_inputs_raise_naming_field(cogiro):
    r = cogiro.robot
    with pytest.raises(InvalidParameterError, match="anchors"):
        ds.Robot(r.anchors[:5], r.attachments[:5], r.cables[:5], r.platform)
    A, b = r.anchors.copy(), r.attachments.copy()
    A[3], b[3] = A[2], b[2]
    with pytest.raises(InvalidParameterError, match="cables 2 and 3 have both ends in common"
                                                    ".*merge them into one cable"):
        ds.Robot(A, b, r.cables, r.platform)
    b[3] += [0.0, 1e-3, 0.0]                  # 1 mm apart: two cables, a shared anchor only
    assert ds.Robot(A, b, r.cables, r.platform).n_cables == 8
    A[3] += [0.0, 0.0, 1e-3]
    b[3] = b[2]                               # a shared attachment point only
    assert ds.Robot(A, b, r.cables, r.platform).n_cables == 8
    with pytest.raises(InvalidParameterError, match="inertia"):
        ds.Platform(10.0, inertia=np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(InvalidParameterError, match="inertia"):
        ds.Platform(10.0, inertia=np.diag([1.0, 1.0, 5.0]))      # triangle inequality
    with pytest.raises(InvalidParameterError, match="free_dofs"):
        ds.Platform(10.0, free_dofs=("x", "q"))
    with pytest.raises(InvalidParameterError,
                       match="^platform must be a dynstiff.Platform, got dict"):
        ds.Robot(r.anchors, r.attachments, r.cables, {"mass": 10.0})
    assert ds.Robot(r.anchors, r.attachments, r.cables, r.platform,
                    tension_limits=(0.0, 5000.0)).tension_limits == (0.0, 5000.0)  # t_min >= 0
    with pytest.raises(InvalidParameterError, match=r"^tension_limits must satisfy 0 <= t_min "
                                                    r"< t_max \[N\], got \(500.0, 500.0\)"):
        ds.Robot(r.anchors, r.attachments, r.cables, r.platform, tension_limits=(500.0, 500.0))


def test_each_stiffness_has_its_own_name(cogiro_eq):
    """One name per quantity: the 3x3 end stiffness of one cable (CatenaryState.end_stiffness),
    the 6x6 platform stiffness at a pose (Robot/Equilibrium.platform_stiffness) and a
    model's massless_stiffness on its free DOFs; the catenary rung assembles the first
    into the second."""
    s = cogiro_eq.states[0]
    assert s.end_stiffness.shape == (3, 3)
    K6 = cogiro_eq.platform_stiffness()
    np.testing.assert_allclose(
        K6, cogiro_eq.robot.platform_stiffness(cogiro_eq.pose, cogiro_eq.states), rtol=0)
    cat = ds.build_model(cogiro_eq, "catenary")
    np.testing.assert_allclose(cat.massless_stiffness(), 0.5 * (K6 + K6.T), rtol=1e-12)
    for obj in (s, cogiro_eq, cogiro_eq.robot, cat):
        assert not hasattr(obj, "static_stiffness") and not hasattr(obj, "dof_names")


def test_coordinates_beyond_1e100_m_are_named(cogiro):
    r = cogiro.robot
    far = r.attachments.copy()
    far[0, 0] = 1.0000000000000002e100
    with pytest.raises(InvalidParameterError, match="attachments must lie within"):
        ds.Robot(r.anchors, far, r.cables, r.platform)
    with pytest.raises(InvalidParameterError, match=r"^anchors must lie within 1e\+100 m of "):
        ds.Robot(far, r.attachments, r.cables, r.platform)
    far[0, 0] = 1e100                                       # within: the bound included
    assert ds.Robot(far, r.attachments, r.cables, r.platform).anchors[0, 0] == 1e100
    with pytest.raises(InvalidParameterError, match="pose position"):
        ds.Pose([1e101, 0.0, 0.0])


def test_shared_anchor_points_solve_with_the_analytic_tension():
    """Three anchor points, two cables each: at the centre every cable carries
    T = m g L / (6 h) (six equal vertical shares; L the chord, h its height), up to the
    weight of the nearly massless cables (1e-4 kg/m: w0 L / T ~ 1e-5)."""
    robot = inverted_stewart()
    assert len(np.unique(robot.anchors, axis=0)) == 3
    eq = robot.equilibrium(pose=[0.0, 0.0, 1.5, 0.0, 0.0, 0.0])
    L, h = np.sqrt(12.0), 1.5                   # chord (3, 0.866, -1.5) m of every cable
    np.testing.assert_allclose(eq.tensions, 100.0 * robot.g * L / (6 * h), rtol=2e-5)
    np.testing.assert_allclose(eq.tensions, eq.tensions[0], rtol=1e-9)   # C3v symmetry


def test_shared_anchors_give_symmetric_modes_in_every_rung():
    """The octahedron's symmetry (C3v) pairs its platform modes: two degenerate pairs
    (sway with tilt) and two single modes (heave, twist) in every rung (the chains of the
    lumped rung and the exact cables leave from shared anchor nodes too); with light cables
    every rung agrees with the massless spring model to the cables' small mass."""
    eq = inverted_stewart().equilibrium(pose=[0.0, 0.0, 1.5, 0.0, 0.0, 0.0])
    f0 = ds.eigenfrequencies(ds.build_model(eq, "spring"), n_modes=6)
    for rung, kw in (("spring", {}), ("catenary", {}), ("dsm", {}),
                     ("lumped", {"segments": 4}), ("exact", {"fmax_hz": 200.0})):
        f = ds.eigenfrequencies(ds.build_model(eq, rung, **kw), n_modes=6)
        np.testing.assert_allclose(f[[1, 3]], f[[2, 4]], rtol=1e-8, err_msg=rung)
        assert np.all(np.diff(f[[0, 1, 3, 5]]) / f[[1, 3, 5]] > 0.1), rung
        np.testing.assert_allclose(f, f0, rtol=5e-5, err_msg=rung)


def test_shared_attachment_points_solve_with_the_analytic_tension():
    """Six anchors, three platform points with two cables each (the arrangement of FAST's
    feed cabin): each point is held by the anchors 30 deg either side of it, and at the
    centre every cable carries m g L / (6 h)."""
    ang_a = np.radians(np.arange(0.0, 360.0, 60.0))
    ang_b = np.radians([30.0, 30.0, 150.0, 150.0, 270.0, 270.0])
    A = np.c_[3.5 * np.cos(ang_a), 3.5 * np.sin(ang_a), np.full(6, 3.0)]
    b = np.c_[0.9 * np.cos(ang_b), 0.9 * np.sin(ang_b), np.zeros(6)]
    rob = ds.Robot(A, b, ds.Cable(1e-4, 1e7),
                   ds.Platform(100.0, inertia=np.diag([10.0, 10.0, 15.0])))
    eq = rob.equilibrium(pose=[0.0, 0.0, 1.5, 0.0, 0.0, 0.0])
    L = np.linalg.norm(A[0] - (b[0] + [0.0, 0.0, 1.5]))
    np.testing.assert_allclose(eq.tensions, 100.0 * rob.g * L / (6 * 1.5), rtol=2e-5)


@pytest.mark.parametrize("kw, message", [
    (dict(anchors="a"), r"anchors must be a finite \(n, 3\) array \[m\], got 'a'"),
    (dict(anchors=[[0, 0, 0], [1, 0, 0], [1, 1]]),
     r"anchors must be a finite \(n, 3\) array \[m\], got \[\[0, 0, 0\], \[1, 0, 0\], \[1, 1\]\]"),
    (dict(cables=["EA"]), r"cables must be one Cable or a sequence of 2 Cables, got \['EA'\]"),
    (dict(cables=[ds.Cable(0.1, 1e7), "EA"]),
     r"cables must be one Cable or a sequence of 2 Cables, got \[Cable\(.*\), 'EA'\]"),
    (dict(g="x"), r"g must be a real number, got 'x'"),
    (dict(g=-1.0), r"g must be >= 0, got -1\.0"),
    (dict(attachments="a"), r"attachments must be a finite \(n, 3\) array \[m\], got 'a'"),
    (dict(anchors=[[0, 0], [1, 1]]), r"anchors must be a finite \(n, 3\) array \[m\], got "
                                     r"shape \(2, 2\)"),
    (dict(attachments=[[0, 0, 0]]), r"attachments must be a finite array of shape \(2, 3\) "
                                    r"like anchors, got shape \(1, 3\)"),
    (dict(anchors=np.zeros((0, 3)), attachments=np.zeros((0, 3)), cables=[],
          platform=ds.Platform(1.0, free_dofs=("z",))),
     r"anchors: 0 cables cannot hold a platform with 1 free DOF \('z',\); at least 1 is "
     r"needed"),
    (dict(tension_limits="a"), r"tension_limits must be \(t_min, t_max\) \[N\], got 'a'"),
    (dict(tension_limits=(1, 2, 3)), r"tension_limits must be \(t_min, t_max\) \[N\], got "
                                     r"\(1, 2, 3\)"),
    (dict(platform=ds.Platform(2.0, free_dofs=("x", "y", "z"))),
     r"anchors: 2 cables cannot hold a platform with 3 free DOFs \('x', 'y', 'z'\); at least "
     r"3 are needed"),
    (dict(anchors=[[0, 0, 5.0]], attachments=[[0, 0, 0.0]], cables=ds.Cable(0.1, 1e7)),
     r"anchors: 1 cable cannot hold a platform with 2 free DOFs \('x', 'z'\); at least 2 are "
     r"needed")])
def test_a_bad_robot_is_refused_with_the_whole_message(kw, message):
    """planar2's robot (2 cables, x and z free) with one field changed: the message names the
    field, what it must be and the value given; a right-length list with a text in it is
    refused as a wrong-length one is; one cable and two free DOFs is said in the singular."""
    r = ds.load_scene("planar2").robot
    args = dict(anchors=r.anchors, attachments=r.attachments, cables=r.cables,
                platform=r.platform, g=r.g, tension_limits=r.tension_limits)
    args.update(kw)
    with pytest.raises(InvalidParameterError, match=f"^{message}$"):
        ds.Robot(**args)


def test_the_robot_holds_its_checked_arrays():
    """Lists in, float arrays out: the anchors, attachments and limits are the checked ones."""
    r = ds.Robot([[0, 0, 5]], [[0, 0, 0]], ds.Cable(0.1, 1e6),
                 ds.Platform(1.0, free_dofs=("z",)), tension_limits=[1, 100])
    for got, want in ((r.anchors, [[0.0, 0.0, 5.0]]), (r.attachments, [[0.0, 0.0, 0.0]])):
        assert isinstance(got, np.ndarray) and got.dtype == np.float64
        np.testing.assert_array_equal(got, want)
    assert r.tension_limits == (1.0, 100.0)
