"""CASPR model import (dynstiff/io/caspr.py, Robot.from_caspr; theory.md §15.1-15.2): CASPR's own
CoGiRo files (tests/data/caspr/, copied unchanged, SOURCE.md) give the built-in scene's robot
and frequencies; IPAnema 1 (8 cables, not suspended) imports and solves in both of its cable
sets; the two file layouts, the joint types, the inertia conventions and malformed files;
shared anchor points (a test robot in CASPR's format, InvertedStewart_*.xml), the joint's
bounds as the workspace box, and pulley attachments refused."""

import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import dynstiff as ds
from dynstiff.io.caspr import CasprError, InertiaConventionWarning, read_caspr

DATA = Path(__file__).parent / "data" / "caspr"
COG = (DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml")
IPA = (DATA / "IPAnema_1_bodies.xml", DATA / "IPAnema_1_cables.xml")


def cogiro_from_caspr(**kw):
    scene = ds.load_scene("cogiro")
    with pytest.warns(InertiaConventionWarning, match="products of inertia"):
        robot = ds.Robot.from_caspr(*COG, cable=scene.robot.cables[0], **kw)
    return scene, robot


def _place(filename):
    """A warning's file, compared with the caller's. A mutation-testing run
    (MUTANT_UNDER_TEST set) puts the tool's own frames between caller and library, so
    there the file is not compared (the normal run compares it)."""
    import os
    return None if "MUTANT_UNDER_TEST" in os.environ else filename


def test_cogiro_from_caspr_equals_the_built_in_scene():
    scene, robot = cogiro_from_caspr()
    ref = scene.robot
    np.testing.assert_array_equal(robot.anchors, ref.anchors)
    np.testing.assert_array_equal(robot.attachments, ref.attachments)
    assert robot.platform.mass == ref.platform.mass
    np.testing.assert_array_equal(robot.platform.center_of_mass, ref.platform.center_of_mass)
    np.testing.assert_array_equal(robot.platform.inertia, ref.platform.inertia)
    assert robot.tension_limits == ref.tension_limits == (100.0, 5000.0)
    assert robot.cables == ref.cables and robot.g == ref.g


def test_cogiro_from_caspr_has_the_scene_frequencies():
    scene, robot = cogiro_from_caspr()
    f_ref = ds.eigenfrequencies(ds.build_model(scene.equilibrium(), "dsm"), n_modes=8)
    f = ds.eigenfrequencies(ds.build_model(robot.equilibrium(scene.pose), "dsm"), n_modes=8)
    np.testing.assert_allclose(f, f_ref, rtol=1e-12)


def test_inertia_convention_tensor_flips_the_products_and_moves_frequencies():
    """'tensor' (CASPR's code) gives the off-diagonals the other sign; at an off-centre,
    tilted pose the frequencies move by up to about 2 % (theory.md §15.2)."""
    scene, prod = cogiro_from_caspr()
    with pytest.warns(InertiaConventionWarning, match="tensor entries"):
        tens = ds.Robot.from_caspr(*COG, cable=scene.robot.cables[0],
                                   inertia_convention="tensor")
    off = ~np.eye(3, dtype=bool)
    np.testing.assert_array_equal(tens.platform.inertia[off], -prod.platform.inertia[off])
    np.testing.assert_array_equal(np.diag(tens.platform.inertia),
                                  np.diag(prod.platform.inertia))
    pose = ds.Pose([2.0, 1.5, 1.5], [0.0, 0.0, 0.3])
    f = [ds.eigenfrequencies(ds.build_model(r.equilibrium(pose), "spring"), n_modes=6)
         for r in (prod, tens)]
    shift = np.abs(f[1] / f[0] - 1).max()
    assert 1e-3 < shift < 0.05


def test_min_tension_raises_caspr_floor_and_is_checked():
    """t_min = max(CASPR's force_min, min_tension): CoGiRo's file states 100 N."""
    assert cogiro_from_caspr(min_tension=150.0)[1].tension_limits == (150.0, 5000.0)
    assert cogiro_from_caspr(min_tension=50.0)[1].tension_limits == (100.0, 5000.0)
    with pytest.raises(ds.errors.InvalidParameterError, match="^min_tension must be > 0"):
        cogiro_from_caspr(min_tension=-1.0)


def test_caspr_parallel_axis_check_favours_products_of_inertia():
    """The CoGiRo description prints the inertia at G (eq. 1, CASPR's numbers) and at P
    (eq. 2: off-diagonals -0.414, 2.205, -1.849; theory.md §8.1). The transfer G -> P matches
    them only when the printed values are products of inertia (theory.md §15.2)."""
    scene, robot = cogiro_from_caspr()
    m, c = robot.platform.mass, robot.platform.center_of_mass
    printed_P = np.array([-0.414, 2.205, -1.849])                  # xy, xz, yz at P
    pairs = [(0, 1), (0, 2), (1, 2)]
    # the imported tensor (products reading) transferred by the parallel-axis rule
    I_P = robot.platform.inertia + m * (c @ c * np.eye(3) - np.outer(c, c))
    np.testing.assert_allclose([-I_P[i, j] for i, j in pairs], printed_P, atol=0.011)
    # the tensor reading (CASPR's code) misses the printed values by 0.08 to 1.6 kg m^2
    with pytest.warns(InertiaConventionWarning):
        tens = ds.Robot.from_caspr(*COG, cable=scene.robot.cables[0],
                                   inertia_convention="tensor")
    I_P = tens.platform.inertia + m * (c @ c * np.eye(3) - np.outer(c, c))
    assert np.abs(np.array([I_P[i, j] for i, j in pairs]) - printed_P).min() > 0.07


def test_ipanema_imports_and_solves_in_both_cable_sets():
    cable = ds.Cable(mass_per_length=0.02, EA=2e5)
    for cable_set, n_expected in (("original", 8), ("IROS_CASPR_2016", 8)):
        scene = ds.scenes.import_caspr(*IPA, cable=cable, cable_set=cable_set)
        r = scene.robot
        assert r.n_cables == n_expected and r.platform.mass == 25.0
        B, _ = r.attachment_points(scene.pose)
        assert np.sum(r.anchors[:, 2] < B[:, 2]) == 4                # 4 cables pull down
        assert r.tension_limits[0] == 1.0                         # CASPR's 0 N raised
        eq = scene.equilibrium()
        assert np.all(eq.tensions >= 1.0 - 1e-9)
        # the light cables sag (cable 4: 5 %): the closed form's guard warns there
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
            f = ds.eigenfrequencies(ds.build_model(eq, "dsm"), n_modes=6)
        assert np.all(np.isfinite(f)) and np.all(f > 0)
    # the IROS set has one cable limited to 200 N: the robot keeps the tightest pair
    assert scene.robot.tension_limits[1] == 200.0


def test_default_cable_set_and_named_set():
    m0 = read_caspr(*IPA)
    m1 = read_caspr(*IPA, cable_set="IROS_CASPR_2016")
    assert m0.cable_set == "original" and m1.cable_set == "IROS_CASPR_2016"
    assert m1.anchors[0].tolist() == [-2.0, 3.0, 5.0]
    with pytest.raises(CasprError, match="'nope' not found.*IROS_CASPR_2016"):
        read_caspr(*IPA, cable_set="nope")


def test_bare_links_layout_reads_like_bodies_system():
    a = read_caspr(DATA / "IPAnema1_bodies.xml", IPA[1])
    b = read_caspr(*IPA)
    assert a.mass == b.mass and a.name == b.name
    np.testing.assert_array_equal(a.inertia, b.inertia)
    np.testing.assert_array_equal(a.position, b.position)


BODY = """<links><link_rigid num="1" name="box">
  <joint type="{jtype}" q_initial="{q}"/>
  <physical><mass>10</mass><com_location>0.1 0 0.2</com_location>
    <inertia ref="com"><Ixx>1</Ixx><Iyy>2</Iyy><Izz>3</Izz><Ixy>0</Ixy><Ixz>0</Ixz>
    <Iyz>0</Iyz></inertia></physical>
  <parent><num>0</num><location>0.5 0 0</location></parent></link_rigid>{extra}</links>"""
CABLES = """<cables default_cable_set="s"><cable_set id="s">
  <cable_ideal name="c1" attachment_reference="{ref}"><properties><force_min>5</force_min>
  <force_max>50</force_max></properties><attachments>
  <attachment><link>0</link><location>1 2 3</location></attachment>
  <attachment><link>1</link><location>0.1 0.2 0.3</location></attachment>
  </attachments></cable_ideal></cable_set></cables>"""

def write(tmp_path, jtype="SPATIAL_EULER_XYZ", q="1 2 3 0.1 0.2 0.3", extra="", ref="joint"):
    b, c = tmp_path / "b.xml", tmp_path / "c.xml"
    b.write_text(BODY.format(jtype=jtype, q=q, extra=extra))
    c.write_text(CABLES.format(ref=ref))
    return b, c


@pytest.mark.parametrize("jtype, q, position, R, free", [
    ("SPATIAL_EULER_XYZ", "1 2 3 0.1 0.2 0.3", [1.5, 2, 3],
     Rotation.from_euler("XYZ", [0.1, 0.2, 0.3]), 6),
    ("SPATIAL", "1 2 3 0.9238795 0 0.3826834 0", [1.5, 2, 3],
     Rotation.from_rotvec([0, np.pi / 4, 0]), 6),
    ("T_XYZ", "1 2 3", [1.5, 2, 3], Rotation.identity(), 3),
    ("S_FIXED_XYZ", "0.1 0.2 0.3", [0.5, 0, 0], Rotation.from_euler("xyz", [0.1, 0.2, 0.3]),
     3),
    ("S_EULER_XYZ", "0.1 0.2 0.3", [0.5, 0, 0], Rotation.from_euler("XYZ", [0.1, 0.2, 0.3]),
     3),
    ("SPATIAL_QUATERNION", "1 2 3 0.9238795 0 0.3826834 0", [1.5, 2, 3],
     Rotation.from_rotvec([0, np.pi / 4, 0]), 6),
    ("SPHERICAL", "0.9238795 0 0.3826834 0", [0.5, 0, 0],
     Rotation.from_rotvec([0, np.pi / 4, 0]), 3),
])
def test_joint_types_give_pose_and_free_dofs(tmp_path, jtype, q, position, R, free):
    m = read_caspr(*write(tmp_path, jtype, q))
    assert m.name == "box" and m.joint_type == jtype
    np.testing.assert_allclose(m.position, position, atol=1e-12)
    np.testing.assert_allclose(Rotation.from_rotvec(m.rotation).as_matrix(), R.as_matrix(),
                               atol=1e-6)
    assert len(m.free_dofs) == free


@pytest.mark.parametrize("jtype", ["SPATIAL_EULER_XYZ", "SPATIAL", "SPATIAL_QUATERNION",
                                   "T_XYZ", "S_EULER_XYZ", "S_FIXED_XYZ", "SPHERICAL"])
def test_joint_without_q_initial_sits_at_its_parent_location_unrotated(tmp_path, jtype):
    """No q_initial: P at the parent location (0.5 0 0), identity orientation (unit quaternion)."""
    b, c = write(tmp_path, jtype)
    b.write_text(b.read_text().replace(' q_initial="1 2 3 0.1 0.2 0.3"', ""))
    m = read_caspr(b, c)
    np.testing.assert_array_equal(m.position, [0.5, 0.0, 0.0])
    np.testing.assert_array_equal(m.rotation, [0.0, 0.0, 0.0])


def test_euler_xyz_is_rx_ry_rz():
    """CASPR's SphericalEulerXYZ: R = R_x(alpha) R_y(beta) R_z(gamma)."""
    a, b, g = 0.3, -0.2, 0.5
    R = (Rotation.from_rotvec([a, 0, 0]) * Rotation.from_rotvec([0, b, 0])
         * Rotation.from_rotvec([0, 0, g])).as_matrix()
    np.testing.assert_allclose(Rotation.from_euler("XYZ", [a, b, g]).as_matrix(), R,
                               atol=1e-14)


def test_attachment_reference_com_adds_the_centre_of_mass(tmp_path):
    joint = read_caspr(*write(tmp_path, ref="joint"))
    com = read_caspr(*write(tmp_path, ref="com"))
    np.testing.assert_allclose(com.attachments - joint.attachments, [[0.1, 0.0, 0.2]])
    assert joint.tension_limits == (5.0, 50.0)


LINK2 = """<link_rigid num="2" name="arm"><joint type="R_X" q_initial="0"/></link_rigid>"""


@pytest.mark.parametrize("kind, match", [
    ("multi", "2 links.*multi-link robots are not supported"),
    ("planar", "joint type 'PLANAR_XY' is not supported"),
    ("xml", "not well-formed XML"),
    ("mass", "<mass> must be 1 finite number, got 'ten'"),
    ("q", "q_initial of the SPATIAL_EULER_XYZ joint must be 6"),
    ("swap", "root element <cables>"),
])
def test_unsupported_and_malformed_files_fail_with_one_clear_error(tmp_path, kind, match):
    b, c = write(tmp_path, extra=LINK2 if kind == "multi" else "",
                 jtype="PLANAR_XY" if kind == "planar" else "SPATIAL_EULER_XYZ",
                 q="1 2 3" if kind == "q" else "1 2 3 0 0 0")
    if kind == "xml":
        b.write_text(b.read_text()[:-20])
    if kind == "mass":
        b.write_text(b.read_text().replace("<mass>10</mass>", "<mass>ten</mass>"))
    if kind == "swap":
        b = c
    with pytest.raises(CasprError, match=match) as exc:
        read_caspr(b, c)
    assert "\n" not in str(exc.value) and str(b) in str(exc.value)
    assert isinstance(exc.value, ds.DynstiffError)


@pytest.mark.parametrize("file, old, new, message", [
    ("b", "<Ixx>1</Ixx>", "<Ixx>1 2</Ixx>", "<inertia><Ixx> must be 1 finite number, got '1 2'"),
    ("b", "<location>0.5 0 0</location>", "<location>0.5 0</location>",
     "<parent><location> must be 3 finite numbers, got '0.5 0'"),
    ("b", "physical>", "physics>", "link 'box' has no <physical>"),
    ("b", 'q_initial="1 2 3 0.1 0.2 0.3"', 'q_initial="1 2 3 0.1 0.2 0.3" q_min="0 0 0" '
     'q_max="1 1 1 1 1 1"', "q_min of the SPATIAL_EULER_XYZ joint must be 6 finite numbers, "
     "got '0 0 0'"),
    ("b", 'q_initial="1 2 3 0.1 0.2 0.3"', 'q_initial="1 2 3 0.1 0.2 0.3" q_min="0 0 0 0 0 0" '
     'q_max="1 -1 1 1 1 1"', "q_min [0.0, 0.0, 0.0, 0.0, 0.0, 0.0] exceeds q_max "
     "[1.0, -1.0, 1.0, 1.0, 1.0, 1.0] of the SPATIAL_EULER_XYZ joint"),
    ("c", "<force_min>5</force_min>", "", "missing cable 'c1' <force_min>"),
    ("c", "<link>1</link>", "<link>0</link>", "cable 'c1' runs through links ['0', '0']; "
     "dynstiff needs one attachment on the base (link 0) and one on the platform (link 1)"),
])
def test_malformed_element_is_refused_naming_file_element_and_value(tmp_path, file, old, new,
                                                                    message):
    """A malformed element raises one CasprError: '<file>: <element> ... <value>'."""
    b, c = write(tmp_path)
    target = b if file == "b" else c
    assert old in target.read_text()
    target.write_text(target.read_text().replace(old, new))
    with pytest.raises(CasprError) as exc:
        read_caspr(b, c)
    assert str(exc.value) == f"{target}: {message}"


TWO_SETS = """<cables{default}><cable_set id="s">
  <cable_ideal name="c1"><properties><force_min>5</force_min><force_max>50</force_max>
  </properties><attachments><attachment><link>0</link><location>1 2 3</location></attachment>
  <attachment><link>1</link><location>0.1 0.2 0.3</location></attachment></attachments>
  </cable_ideal>
  <cable_ideal><properties><force_min>6</force_min><force_max>60</force_max></properties>
  <attachments><attachment><link>0</link><location>-1 -2 3</location></attachment>
  <attachment><link>1</link><location>-0.1 -0.2 0.3</location></attachment></attachments>
  </cable_ideal></cable_set>{other}</cables>"""
OTHER_SET = """<cable_set id="t"><cable_ideal name="t1"><properties><force_min>1</force_min>
  <force_max>2</force_max></properties><attachments>
  <attachment><link>0</link><location>4 5 6</location></attachment>
  <attachment><link>1</link><location>0 0 0</location></attachment></attachments>
  </cable_ideal></cable_set>"""


def test_cable_set_without_default_is_the_only_set_or_must_be_named(tmp_path):
    """No default_cable_set: a lone set is read; with two, cable_set must name one."""
    b, c = write(tmp_path)
    c.write_text(TWO_SETS.format(default="", other=""))
    m = read_caspr(b, c)
    assert m.cable_set == "s"
    np.testing.assert_array_equal(m.anchors, [[1, 2, 3], [-1, -2, 3]])
    np.testing.assert_array_equal(m.attachments, [[0.1, 0.2, 0.3], [-0.1, -0.2, 0.3]])
    np.testing.assert_array_equal(m.force_min, [5, 6])
    np.testing.assert_array_equal(m.force_max, [50, 60])
    c.write_text(TWO_SETS.format(default="", other=OTHER_SET))
    with pytest.raises(CasprError) as exc:
        read_caspr(b, c)
    assert str(exc.value) == f"{c}: no default_cable_set; give cable_set, one of ['s', 't']"
    m = read_caspr(b, c, cable_set="t")
    assert m.cable_set == "t" and m.cable_names == ("t1",)
    np.testing.assert_array_equal(m.anchors, [[4, 5, 6]])


def test_cable_names_are_read_and_an_unnamed_cable_is_numbered(tmp_path):
    """cable_names: each cable's name attribute, else 'cable k' (k: its 0-based index)."""
    b, c = write(tmp_path)
    c.write_text(TWO_SETS.format(default=' default_cable_set="s"', other=""))
    assert read_caspr(b, c).cable_names == ("c1", "cable 1")


def test_off_diagonal_inertia_sign_follows_the_convention_and_warns(tmp_path):
    """Printed Ixy, Ixz, Iyz: tensor entries -value ('products') or +value ('tensor'), warned."""
    b, c = write(tmp_path)
    b.write_text(b.read_text().replace("<Ixy>0</Ixy>", "<Ixy>0.5</Ixy>")
                 .replace("<Ixz>0</Ixz>", "<Ixz>-0.25</Ixz>")
                 .replace("<Iyz>0</Iyz>", "<Iyz>0.125</Iyz>"))
    tensor = np.array([[1.0, 0.5, -0.25], [0.5, 2.0, 0.125], [-0.25, 0.125, 3.0]])
    off = ~np.eye(3, dtype=bool)
    for convention, sign, what in (
            ("products", -1.0, "products of inertia (tensor entry = -printed value)"),
            ("tensor", 1.0, "tensor entries (CASPR's code; products of inertia would change "
                            "sign)")):
        with pytest.warns(InertiaConventionWarning) as rec:
            m = read_caspr(b, c, inertia_convention=convention)
        assert [str(w.message) for w in rec] == [
            f"{b}: Ixy, Ixz, Iyz read as {what}: inertia_convention='{convention}'"]
        assert _place(rec[0].filename) == _place(__file__)     # the caller's line
        np.testing.assert_array_equal(m.inertia[off], sign * tensor[off])
        np.testing.assert_array_equal(np.diag(m.inertia), [1.0, 2.0, 3.0])
        assert m.convention == convention


def test_unknown_convention_is_named(tmp_path):
    with pytest.raises(CasprError, match="inertia_convention must be one of"):
        read_caspr(*write(tmp_path), inertia_convention="cad")


def test_no_warning_without_products_of_inertia():
    with warnings.catch_warnings():
        warnings.simplefilter("error", InertiaConventionWarning)
        read_caspr(*IPA)


INV = (DATA / "InvertedStewart_bodies.xml", DATA / "InvertedStewart_cables.xml")


def test_shared_anchor_points_import_and_solve():
    """A test robot in CASPR's format (tests/data/caspr/InvertedStewart_*.xml, written for
    dynstiff): six cables from three exit points, the NIST RoboCrane's arrangement. It
    imports, and at the centre its six tensions are equal (the octahedron's symmetry, to the
    4 decimals of the file's coordinates) and near m g L / (6 h) = 226.55 N; the cables'
    weight (0.05 kg/m, 3.46 m: 1.7 N each, about half of it carried at the platform) adds
    L / h = 2.31 times half of it, about 2 N."""
    m = read_caspr(*INV)
    assert len(np.unique(m.anchors, axis=0)) == 3 and len(m.anchors) == 6
    scene = ds.scenes.import_caspr(*INV, cable=ds.Cable(0.05, 1e6))
    eq = scene.equilibrium()
    np.testing.assert_allclose(eq.tensions, eq.tensions.mean(), rtol=1e-4)
    T0 = 60.0 * scene.robot.g * np.sqrt(12.0) / (6 * 1.5)
    assert abs(T0 - 226.55) < 0.01
    assert 1.5 < eq.tensions.mean() - T0 < 2.5


def test_joint_bounds_give_the_workspace_box():
    m = read_caspr(*INV)
    np.testing.assert_array_equal(m.q_min, [-1.0, -1.0, 0.5, -0.5, -0.5, -0.5])
    assert m.workspace_box == (-1.0, 1.0, -1.0, 1.0, 0.5, 2.5)
    np.testing.assert_array_equal(m.origin, [0.0, 0.0, 0.0])
    assert read_caspr(*IPA).workspace_box == (-4.5, 4.5, -3.5, 3.5, 0.0, 3.5)   # CASPR's
    with pytest.warns(InertiaConventionWarning):          # an older CoGiRo file: no bounds
        assert read_caspr(*COG).workspace_box is None


def test_workspace_box_is_moved_by_the_parent_location(tmp_path):
    b, c = write(tmp_path)
    b.write_text(b.read_text().replace('q_initial="1 2 3 0.1 0.2 0.3"',
                                       'q_initial="1 2 3 0.1 0.2 0.3" q_min="0 0 0 -1 -1 -1" '
                                       'q_max="2 3 4 1 1 1"'))
    assert read_caspr(b, c).workspace_box == (0.5, 2.5, 0.0, 3.0, 0.0, 4.0)
    b.write_text(b.read_text().replace('q_max="2 3 4 1 1 1"', 'q_max="2 -3 4 1 1 1"'))
    with pytest.raises(CasprError, match="q_min .* exceeds q_max"):
        read_caspr(b, c)
    assert read_caspr(*write(tmp_path, "S_EULER_XYZ", "0.1 0.2 0.3")).workspace_box is None


def test_joint_pose_is_the_reader_pose():
    from dynstiff.io.caspr import joint_pose
    p, r = joint_pose("SPATIAL_EULER_XYZ", [0.5, 0.0, 0.0], [1, 2, 3, 0.1, 0.2, 0.3])
    np.testing.assert_allclose(p, [1.5, 2.0, 3.0])
    np.testing.assert_allclose(Rotation.from_rotvec(r).as_matrix(),
                               Rotation.from_euler("XYZ", [0.1, 0.2, 0.3]).as_matrix(),
                               atol=1e-14)


PULLEY = """<attachments><base_rotating_pulley><fixed_location>1 2 3</fixed_location>
  <pulley_radius>0.045</pulley_radius><cable_entry_vector>0 0 1</cable_entry_vector>
  </base_rotating_pulley><attachment><link>1</link><location>0.1 0.2 0.3</location>
  </attachment></attachments>"""


def test_pulley_attachments_are_refused_with_the_sets_to_choose(tmp_path):
    """CAROCA's set 'with_rotating_pulleys' routes each cable over a base pulley whose exit
    point moves with the pose; dynstiff clamps a cable at a fixed point."""
    b, c = write(tmp_path)
    text = c.read_text()
    start, end = text.index("<attachments>"), text.index("</attachments>") + 14
    c.write_text(text[:start] + PULLEY + text[end:])
    with pytest.raises(CasprError, match="<base_rotating_pulley>.*choose a set of plain "
                                         r"<attachment>s \(this file has none\)") as err:
        read_caspr(b, c)
    assert "\n" not in str(err.value)
    text = c.read_text().replace("</cables>", CABLES.format(ref="joint").replace(
        '<cables default_cable_set="s"><cable_set id="s">', '<cable_set id="plain">'))
    c.write_text(text)
    with pytest.raises(CasprError, match=r"plain <attachment>s, one of \['plain'\]"):
        read_caspr(b, c)


def test_the_inertia_warning_points_at_the_callers_line():
    """Robot.from_caspr and import_caspr warn at the line that called them, as read_caspr."""
    from dynstiff.scenes.caspr import import_caspr
    cable = ds.load_scene("cogiro").robot.cables[0]         # CoGiRo's file has products
    with pytest.warns(InertiaConventionWarning) as rec:
        ds.Robot.from_caspr(*COG, cable)
    assert _place(rec[0].filename) == _place(__file__)
    with pytest.warns(InertiaConventionWarning) as rec:
        import_caspr(*COG, cable)
    assert _place(rec[0].filename) == _place(__file__)
