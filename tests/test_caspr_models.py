"""Compatibility with CASPR's model library (theory.md §15.1, §15.7-15.8): the ten spatial
robots of CASPR (Lau et al., darwinlau/CASPR, GPL-3.0),
data/model_config/models/SCDM/spatial_manipulators/, each imported with its trajectories
and operational spaces, solved at its q_initial with the cable data of ``CABLE_DATA``, run
through its modes and the design checks; where CASPR's data make the pose infeasible, the
error names the cause and a remedy that works; a CASPR trajectory drives a sweep; planar and
multi-link models keep their one-line refusal.

CASPR's files are not part of this repository. The suite runs where they are: the folder
``spatial_manipulators`` given by the environment variable ``DYNSTIFF_CASPR_MODELS``, or
``../shared/caspr/`` beside the repository (that folder itself, or a CASPR checkout in it).
Elsewhere every test here is skipped, saying why. Expected values are read from the XML
files with ElementTree, independently of dynstiff's reader.
"""

import os
import warnings
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from conftest import inverted_stewart
from scipy.spatial.transform import Rotation

import dynstiff as ds
from dynstiff.analyses.checks import design_checks
from dynstiff.errors import InfeasiblePoseError
from dynstiff.io.caspr import CasprError, InertiaConventionWarning
from dynstiff.scenes.caspr import caspr_siblings, import_caspr

SUBDIR = Path("data", "model_config", "models", "SCDM", "spatial_manipulators")


def _models_folder():
    env = os.environ.get("DYNSTIFF_CASPR_MODELS")
    if env:
        return Path(env), f"DYNSTIFF_CASPR_MODELS={env}"
    shared = Path(__file__).resolve().parents[2] / "shared" / "caspr"
    return (shared / SUBDIR if (shared / SUBDIR).is_dir() else shared), str(shared)


FOLDER, WHERE = _models_folder()
pytestmark = pytest.mark.skipif(
    not FOLDER.is_dir(), reason=f"CASPR's model folder is not here ({WHERE} is not a folder): "
                                f"set DYNSTIFF_CASPR_MODELS to .../{SUBDIR.as_posix()}")

#: The light cable of every robot: 0.05 kg/m, EA 1e6 N (a 3-4 mm synthetic or steel rope).
LIGHT = ds.Cable(mass_per_length=0.05, EA=1e6)

#: Cable data at which each robot is solved, beyond LIGHT and CASPR's tension limits (t_min
#: raised to 1 N where CASPR gives 0, a slack sagging cable). Two need more, for reasons
#: the statics' own errors give (test_caspr_data_that_cannot_hold_the_pose_say_why):
CABLE_DATA = {
    # CASPR's force_min 120 kN is above the one tension distribution at q_initial (six cables,
    # six DOFs: 98.4 kN each), so t_min = 90 kN
    "FAST": dict(tension_limits=(9.0e4, 1.2e6)),
    # the light cables rising 2.75 m to the platform need t_min above about 1.1 N; at 2 N the
    # platform (its centre of mass 0.5 m above P) is at the edge of static stability (the
    # least eigenvalue of K(0) 0.016 N m/rad in the closed form), so t_min = 10 N
    "IPAnema_2": dict(min_tension=10.0),
}
#: Robots whose light cables sag 5-14 % of their chord at a few newtons: the closed form's
#: guard (ClosedFormWarning) sends them to the exact rung, which their modes and checks use.
EXACT = ("IPAnema_1", "MACARM", "SEGESTA")
ROBOTS = ["ACROBOT", "CAROCA", "CoGiRo", "FAST", "IPAnema_1", "IPAnema_2", "MACARM",
          "NIST_RoboCrane", "SEGESTA", "The_Cable_Robot_Simulator"]
#: Design checks in the default tier on two robots, on all ten in the slow tier (0.2-0.5 s a
#: robot with single-threaded BLAS, several seconds with threaded BLAS on loaded cores: the
#: checks build exact cable models).
QUICK_CHECKS = ("CAROCA", "FAST")


def files(robot):
    """(bodies, cables, trajectories, operational spaces) of ``robot``; folder names are
    matched without case (CASPR's list says NIST_RoboCrane, its folder NIST_ROBOCRANE)."""
    match = [p for p in FOLDER.iterdir() if p.name.lower() == robot.lower()]
    assert match, f"{robot} not in {FOLDER}"
    bodies = next(match[0].glob("*_bodies.xml"))
    return (bodies, next(match[0].glob("*_cables.xml")), *caspr_siblings(bodies))


def load(robot):
    """The robot's scene with the cable data of CABLE_DATA."""
    b, c, t, o = files(robot)
    data = CABLE_DATA.get(robot, {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InertiaConventionWarning)     # CoGiRo's products
        sc = import_caspr(b, c, LIGHT, min_tension=data.get("min_tension", 1.0),
                          trajectories_xml=t, operational_spaces_xml=o)
    if "tension_limits" in data:
        sc = replace(sc, robot=replace(sc.robot, tension_limits=data["tension_limits"]))
    return sc


def xml(path):
    return ET.parse(path).getroot()


@pytest.mark.parametrize("robot", ROBOTS)
def test_every_spatial_robot_imports(robot):
    b, c, t, o = files(robot)
    sc = load(robot)
    link = xml(b).find(".//link_rigid")
    joint = link.find("joint")
    assert sc.robot.platform.mass == float(link.findtext("physical/mass"))
    cables = xml(c)
    default = cables.get("default_cable_set")
    n = len(cables.find(f"cable_set[@id='{default}']"))
    assert sc.robot.n_cables == n
    q0 = [float(v) for v in joint.get("q_initial").split()]
    np.testing.assert_allclose(sc.pose.position, q0[:3])
    lo = [float(v) for v in joint.get("q_min").split()][:3]
    hi = [float(v) for v in joint.get("q_max").split()][:3]
    assert sc.workspace_box == tuple(v for pair in zip(lo, hi) for v in pair)
    n_traj = len(xml(t).find("joint_trajectories"))
    assert len(sc.trajectories) == n_traj
    assert sc.study["caspr_operational_sets"] == {}       # the ten files hold no set


@pytest.mark.parametrize("robot", ROBOTS)
def test_every_spatial_robot_solves_at_q_initial(robot):
    """Statics within the limits all along every cable, to the solver's tolerance."""
    sc = load(robot)
    eq = sc.equilibrium()
    t_min, t_max = sc.robot.tension_limits
    assert eq.residual <= 1e-10
    assert eq.min_tensions.min() >= t_min * (1 - 1e-9) and eq.max_tensions.max() <= t_max


@pytest.mark.parametrize("robot", ROBOTS)
def test_every_spatial_robot_has_modes(robot):
    """Six modes whose Wittrick-Williams count agrees (none below the first, six below just
    above the sixth), of the closed form, or of the exact rung where the closed form's
    guard asks for it (its cables' own guard on the robots of EXACT, whose light cables sag
    5-14 % of the chord; the robot-level bound of theory.md §11.6 on some others)."""
    eq = load(robot).equilibrium()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ds.errors.ClosedFormWarning)
        f = ds.eigenfrequencies(ds.build_model(eq, "dsm"), n_modes=6)
    asks = any("use the 'exact' rung" in str(w.message) for w in caught)
    assert asks or robot not in EXACT
    model = ds.build_model(eq, "exact", fmax_hz=1.3 * f[-1]) if asks else ds.build_model(
        eq, "dsm")
    f = ds.eigenfrequencies(model, n_modes=6)
    assert np.all(f > 0) and np.all(np.diff(f) >= 0)
    w = 2 * np.pi * np.array([f[0] * (1 - 1e-6), f[5] * (1 + 1e-6)])
    np.testing.assert_array_equal(ds.mode_count(model, w), [0, 6])


@pytest.mark.parametrize("robot", [
    r if r in QUICK_CHECKS else pytest.param(r, marks=pytest.mark.slow) for r in ROBOTS])
def test_every_spatial_robot_runs_the_design_checks(robot):
    """The design checks (modes until the platform modes are found): the statics and
    tension rows pass (the pose was solved within the limits), every row has its detail."""
    sc = load(robot)
    rung = "exact" if robot in EXACT else "dsm"
    kw = {"fmax_hz": 4.0} if rung == "exact" else {}
    with warnings.catch_warnings():
        # the closed form's guard: the cable-model row reports what it would warn of
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
        res = design_checks(sc.robot, sc.pose, rung=rung, **kw)
    rows = {r["check"]: r for r in res.rows}
    assert rows["workspace (tension-feasible pose)"]["passed"]
    assert rows["tension limits"]["passed"]
    assert {"sag / chord", "cable model", "local modes near platform modes"} <= set(rows)
    assert all(r["detail"] for r in res.rows)


def test_caspr_data_that_cannot_hold_the_pose_say_why():
    """With CASPR's own tension limits and the light cable: FAST's six cables have one
    distribution, m g L / (6 h) = 98.4 kN each (m = 30091.8 kg, chord 340 m, height 170 m:
    from the files), below CASPR's force_min; IPAnema 2's lower cables rise 2.75 m to the
    platform and cannot carry as little as the limits ask. Each error names its cause and
    a remedy; the remedies, applied, make the pose solve."""
    b, c, _, _ = files("FAST")
    sc = import_caspr(b, c, LIGHT)
    with pytest.raises(InfeasiblePoseError, match="t_min <= about") as err:
        sc.equilibrium()
    A = np.array([float(v) for v in xml(c).find(".//attachment/location").text.split()])
    B = np.array([float(v) for v in xml(c).findall(".//attachment/location")[1].text.split()])
    B[2] += sc.pose.position[2]
    T = sc.robot.platform.mass * sc.robot.g * np.linalg.norm(A - B) / (6 * (A[2] - B[2]))
    assert err.value.cause == "tension limits"
    np.testing.assert_allclose(err.value.remedies["t_min"], T, rtol=5e-3)
    replace(sc.robot, tension_limits=(0.99 * err.value.remedies["t_min"], 1.2e6)).equilibrium(
        pose=sc.pose)
    b, c, _, _ = files("IPAnema_2")
    sc = import_caspr(b, c, LIGHT)
    with pytest.raises(InfeasiblePoseError, match="not reachable") as err:
        sc.equilibrium()
    e = err.value
    assert e.cause == "cable weight" and e.cable in (4, 5, 6, 7)
    assert 1.0 < e.remedies["t_min"] < 2.0 and 0.03 < e.remedies["mass_per_length"] < 0.05
    replace(sc.robot, tension_limits=(1.05 * e.remedies["t_min"], 200.0)).equilibrium(
        pose=sc.pose)
    lighter = ds.Cable(0.9 * e.remedies["mass_per_length"], LIGHT.EA)
    replace(sc.robot, cables=(lighter,) * 8).equilibrium(pose=sc.pose)


def test_nist_robocrane_solves_like_its_published_geometry():
    """CASPR's RoboCrane (three shared exit points, refused before cables could share one)
    against the octahedron built from the RoboCrane's geometry (tests/conftest.py): same
    tensions, to the 4 decimals of CASPR's coordinates."""
    sc = load("NIST_RoboCrane")
    assert len(np.unique(sc.robot.anchors, axis=0)) == 3
    ref = inverted_stewart(mass=1.0, mass_per_length=LIGHT.mass_per_length, EA=LIGHT.EA,
                           inertia=(1.0, 1.0, 1.0))
    ref = replace(ref, tension_limits=sc.robot.tension_limits)
    t = sc.equilibrium().tensions
    t_ref = ref.equilibrium(pose=sc.pose).tensions
    np.testing.assert_allclose(np.sort(t), np.sort(t_ref), rtol=1e-3)


def test_a_caspr_trajectory_drives_a_sweep():
    """CoGiRo's general_1 (quintic, three waypoints 2 s apart, the platform turning): its
    waypoint poses are CASPR's q (x y z, then R_x R_y R_z), and the sweep along it solves
    every step, the first one's modes those of the robot at the first waypoint."""
    _, _, t, _ = files("CoGiRo")
    path = load("CoGiRo").trajectories["general_1"]
    el = xml(t).find(".//quintic_spline_trajectory[@id='general_1']")
    q = np.array([[float(v) for v in p.findtext("q").split()] for p in el.iter("point")])
    np.testing.assert_allclose(path.positions, q[:, :3])
    np.testing.assert_allclose(Rotation.from_rotvec(path.rotations).as_matrix(),
                               Rotation.from_euler("XYZ", q[:, 3:]).as_matrix(), atol=1e-12)
    robot = load("CoGiRo").robot
    poses, times = path.poses(5)
    res = ds.sweep(robot, poses=poses, values=times, n_modes=6, on_error="record",
                   parameter="time along general_1 [s]")
    assert res.failures == () and res.n_steps == 5
    f0 = ds.eigenfrequencies(ds.build_model(robot.equilibrium(pose=poses[0]), "dsm"), 6)
    # the sweep lists at least the modes asked (more where the platform modes lie higher)
    np.testing.assert_allclose(res.freq_hz[res.step == 0][:6], f0, rtol=1e-9)


@pytest.mark.parametrize("family, match", [
    (("..", "planar_manipulators"), "joint type '.*' is not supported"),
    (("..", "..", "MCDM"), "links; dynstiff models one rigid platform"),
])
def test_planar_and_multi_link_models_keep_their_one_line_refusal(family, match):
    where = FOLDER.joinpath(*family).resolve()
    if not where.is_dir():
        pytest.skip(f"{where} is not here")
    folder = sorted(p for p in where.iterdir() if p.is_dir())[0]
    b, c = next(folder.glob("*_bodies.xml")), next(folder.glob("*_cables.xml"))
    with pytest.raises(CasprError, match=match) as err:
        import_caspr(b, c, LIGHT)
    assert "\n" not in str(err.value)
