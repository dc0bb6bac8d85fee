"""Geometry behind the 3-D robot views (dynstiff.report.geometry3d): the platform's hull on
hand-made point sets whose hull is known (cube, square, collinear points, a shallow roof), the
polygon chain of a square's edges, the cable profiles under ``sag_scale``, the quasi-static
cable motion t * dB_i with t in [0, 1], the default mode scale from its definition, and the
argument checks' messages, matched in full.
"""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.report.geometry3d import (
    _chain,
    _check_mode,
    _check_model,
    _default_scale,
    _geometry,
    _hull,
    nonnegative,
    positive_int,
    prepare,
)


def path_edges(path):
    """Edges (sorted index pairs) of a hull path: pieces of two indices separated by -1."""
    pieces = np.split(np.asarray(path), np.flatnonzero(np.asarray(path) == -1))
    edges = [tuple(sorted(int(v) for v in p if v != -1)) for p in pieces]
    assert all(len(e) == 2 for e in edges)
    return edges


def modal_result(shapes):
    """A ModalResult with the given platform shapes (n, 6), 1, 2, ... Hz, global modes."""
    shapes = np.asarray(shapes, dtype=float)
    n = len(shapes)
    return ds.ModalResult(np.arange(1.0, n + 1.0), shapes, np.zeros(n), np.zeros((n, 1)))


# ---------------------------------------------------------------------------------- hull
def test_hull_of_a_cube_is_its_twelve_edges_and_six_square_faces():
    """Coplanar facets (each face is two triangles) are one polygon: no face diagonal."""
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    path, faces = _hull(cube)
    edges = path_edges(path)
    assert len(edges) == len(set(edges)) == 12
    for a, b in edges:                                    # unit edges along an axis
        assert np.linalg.norm(cube[a] - cube[b]) == 1.0
    assert len(faces) == 6
    for f in faces:
        assert sorted(f) == sorted(set(f)) and len(f) == 4
        pts = cube[f]
        assert np.sum(np.ptp(pts, axis=0) == 0) == 1                  # in one axis plane
        steps = np.linalg.norm(pts - np.roll(pts, 1, axis=0), axis=1)
        assert np.all(steps == 1.0)                                   # a loop, not crossed
    assert {frozenset(f) for f in faces} == {
        frozenset(np.flatnonzero(cube[:, ax] == v)) for ax in range(3) for v in (0, 1)}


def test_hull_of_a_square_is_one_closed_polygon():
    sq = np.array([[1, 1, 2], [0, 0, 2], [0, 1, 2], [1, 0, 2]], dtype=float)
    path, faces = _hull(sq)
    assert len(faces) == 1 and sorted(faces[0]) == [0, 1, 2, 3]
    assert path == faces[0] + faces[0][:1]
    steps = np.linalg.norm(sq[path[1:]] - sq[path[:-1]], axis=1)
    assert np.all(steps == 1.0)                           # around the sides, no diagonal


def test_hull_of_collinear_points_is_the_segment_between_the_extremes():
    t = np.array([0.37, 0.0, 1.1, 2.9, 1.7])
    pts = np.array([0.1, 0.2, 0.3]) + np.outer(t, [0.3, -0.7, 1.1])
    path, faces = _hull(pts)
    assert sorted(path) == [int(np.argmin(t)), int(np.argmax(t))] == [1, 3]
    assert faces == []
    assert _hull(np.tile([1.0, 2.0, 3.0], (4, 1))) == ([], [])      # coincident: nothing


@pytest.mark.parametrize("angle_deg, n_faces", [(1.5, 7), (0.5, 6)])
def test_hull_keeps_a_roof_ridge_only_beyond_one_degree(angle_deg, n_faces):
    """A box 2 x 4 x 1 m with a ridge along y at x = 1: the two roof planes' normals are
    angle_deg apart. Beyond 1 degree the ridge is an edge and each roof plane a face; within
    it the roof is one face (its vertices all within 1 % of the size of one plane)."""
    h = 1.0 + np.tan(np.radians(angle_deg / 2))
    pts = np.array([[0, 0, 0], [2, 0, 0], [0, 4, 0], [2, 4, 0],
                    [0, 0, 1], [2, 0, 1], [0, 4, 1], [2, 4, 1],
                    [1, 0, h], [1, 4, h]], dtype=float)
    path, faces = _hull(pts)
    edges = set(path_edges(path))
    assert len(faces) == n_faces
    assert len(edges) == len(pts) + n_faces - 2                       # Euler: V - E + F = 2
    assert ((8, 9) in edges) == (n_faces == 7)
    roof = [set(f) for f in faces if set(f) & {8, 9}]
    if n_faces == 7:
        assert {4, 6, 8, 9} in roof and {5, 7, 8, 9} in roof
    else:
        assert {4, 5, 6, 7, 8, 9} in roof


def test_chain_of_a_squares_edges_runs_round_it_from_the_first_edge():
    """The loop visits each vertex once, consecutive vertices joined by an edge, starting
    with the first edge (edges[0][0], edges[0][1]), in the original indices uniq[v]."""
    edges = [(2, 0), (1, 3), (0, 1), (3, 2)]
    uniq = np.array([10, 11, 12, 13])
    loop = _chain(edges, uniq)
    assert loop == [12, 10, 11, 13]
    assert sorted(loop) == [10, 11, 12, 13]
    pairs = {frozenset((a, b)) for a, b in zip(loop, loop[1:] + loop[:1])}
    assert pairs == {frozenset((int(uniq[a]), int(uniq[b]))) for a, b in edges}


# ------------------------------------------------------------------------------ geometry
@pytest.mark.parametrize("sag_scale", [0.0, 2.0])
def test_sag_scale_scales_each_cables_deviation_from_its_chord(cogiro_eq, sag_scale):
    """Each profile point keeps its position along the chord; its offset from the chord is
    sag_scale times the catenary's (0: straight chords); the ends stay at A_i and B_i."""
    n = 21
    geo = _geometry(cogiro_eq, None, None, None, n, sag_scale)
    assert geo["cables"].shape == (8, n, 3)
    for i, s in enumerate(cogiro_eq.states):
        prof = s.profile(n)
        e = s.chord / s.chord_length
        along = s.anchor + np.outer((prof - s.anchor) @ e, e)
        c = geo["cables"][i]
        np.testing.assert_allclose(c, along + sag_scale * (prof - along), rtol=0, atol=1e-9)
        np.testing.assert_allclose(c[[0, -1]], [s.anchor, s.end], rtol=0, atol=1e-9)
        dev = np.linalg.norm(c - along, axis=1)
        assert dev.max() == pytest.approx(sag_scale * s.sag, rel=0.02, abs=1e-12)


def test_static_geometry_has_no_mode(cogiro_eq):
    geo = _geometry(cogiro_eq, None, None, None, 5, 1.0)
    assert geo["dynamic"] is False
    assert all(geo[key] is None for key in ("cable_disp", "dB", "dP", "kind", "freq_hz"))
    np.testing.assert_array_equal(geo["P"], cogiro_eq.pose.position)
    np.testing.assert_array_equal(geo["B"], [s.end for s in cogiro_eq.states])


def test_quasi_static_cable_motion_is_chordwise_position_in_0_1_times_dB():
    """A slack cable hanging steeply from A = (0, 0, 10) m to B = (1, 0, 0) m (12 m long)
    dips below B: those points lie beyond B along the chord, and move by dB (t = 1), not
    more; each point moves by clip(t, 0, 1) dB."""
    cable = ds.Cable(0.064, 8.2051e-6 * 17e9)
    A, B = np.array([0.0, 0.0, 10.0]), np.array([1.0, 0.0, 0.0])
    s = ds.solve_catenary(A, B, 12.0, cable)
    robot = ds.Robot(A[None, :], np.zeros((1, 3)), cable, ds.Platform(1.0, free_dofs=("z",)))
    eq = ds.Equilibrium(robot, ds.Pose(B), np.array([12.0]), (s,), 0.0)
    dz = 1e-3
    modes = modal_result([[0.0, 0.0, dz, 0.0, 0.0, 0.0]])
    n = 41
    geo = _geometry(eq, modes, 0, None, n, 1.0)
    prof = s.profile(n)
    t = (prof - A) @ (B - A) / np.dot(B - A, B - A)
    assert t.max() > 1.05                                  # the dip goes beyond B
    np.testing.assert_allclose(geo["cable_disp"][0], np.outer(np.clip(t, 0, 1), [0, 0, dz]),
                               rtol=0, atol=1e-15)
    assert np.linalg.norm(geo["cable_disp"][0], axis=1).max() <= dz
    np.testing.assert_array_equal(geo["dB"], [[0.0, 0.0, dz]])
    assert geo["dynamic"] is False and geo["kind"] == "global" and geo["freq_hz"] == 1.0


def test_default_scale_makes_the_largest_displacement_5_percent_of_the_diagonal():
    """The largest of |dB_i|, |dp| and the cable points' motion is 5 % of the diagonal of
    the bounding box of anchors, attachment points and P; 1.0 when nothing moves."""
    anchors = np.array([[0.0, 0.0, 3.0], [4.0, 0.0, 3.0]])
    B = np.array([[1.0, 1.0, 1.0], [2.0, 1.0, 1.0]])
    P = np.array([1.5, 1.0, 1.0])
    diag = np.linalg.norm([4.0, 1.0, 2.0])
    cable_disp = np.zeros((2, 5, 3))
    cable_disp[1, 2] = [0.0, 0.3, 0.4]                          # 0.5 m, the largest
    geo = dict(anchors=anchors, B=B, P=P, dB=np.zeros((2, 3)), dP=np.zeros(3),
               cable_disp=cable_disp)
    assert _default_scale(geo) == pytest.approx(0.05 * diag / 0.5, rel=1e-12)
    geo.update(dB=np.array([[0.0, 0.0, 0.1], [0.0, 0.0, 2.0]]))
    assert _default_scale(geo) == pytest.approx(0.05 * diag / 2.0, rel=1e-12)
    geo.update(dB=np.zeros((2, 3)), dP=np.array([0.0, 3.0, 0.0]))
    assert _default_scale(geo) == pytest.approx(0.05 * diag / 3.0, rel=1e-12)
    geo.update(dP=np.zeros(3), cable_disp=np.zeros((2, 5, 3)))
    assert _default_scale(geo) == 1.0


# ------------------------------------------------------------------------------- checks
def test_check_mode_messages():
    modes = modal_result(np.zeros((3, 6)))
    assert _check_mode(modes, np.int64(2)) == 2
    with pytest.raises(InvalidParameterError,
                       match=r"^mode must be a 0-based index in \[0, 2\] \(3 modes\), got 3$"):
        _check_mode(modes, 3)
    with pytest.raises(InvalidParameterError,
                       match=r"^mode must be a 0-based index in \[0, 2\] \(3 modes\), got -1$"):
        _check_mode(modes, -1)
    with pytest.raises(InvalidParameterError, match=r"^mode must be an integer index, got True$"):
        _check_mode(modes, True)
    with pytest.raises(InvalidParameterError,
                       match=r"^mode must be given with modes= \(0-based index below 3\), "
                             r"got None$"):
        _check_mode(modes, None)


def test_check_model_messages(cogiro, cogiro_eq, cogiro_model):
    with pytest.raises(InvalidParameterError,
                       match=r"^model must be the dynstiff\.FrequencyModel of the modes, "
                             r"got str$"):
        _check_model("model", cogiro_eq, None)
    other = cogiro.robot.equilibrium(pose=[0.5, 0.0, 1.0])
    with pytest.raises(InvalidParameterError,
                       match=r"^model must be built on the equilibrium eq \(FrequencyModel"
                             r"\(eq\)\); its cable ends differ from eq's$"):
        _check_model(cogiro_model, other, None)


def test_check_model_compares_cable_ends_to_1e_9_m(cogiro, cogiro_eq, cogiro_model):
    """The same pose re-solved passes; the pose 5e-9 m higher (ends 5e-9 m apart) does not."""
    pose = cogiro_eq.pose
    _check_model(cogiro_model, cogiro.robot.equilibrium(pose=pose), None)
    higher = ds.Pose(pose.position + [0.0, 0.0, 5e-9], pose.rotation)
    with pytest.raises(InvalidParameterError, match="its cable ends differ from eq's"):
        _check_model(cogiro_model, cogiro.robot.equilibrium(pose=higher), None)


def test_number_checks_messages():
    assert nonnegative("x", "2.5") == 2.5 and positive_int("n", np.int32(3), 2) == 3
    with pytest.raises(InvalidParameterError, match=r"^x must be a real number, got 'abc'$"):
        nonnegative("x", "abc")
    with pytest.raises(InvalidParameterError, match=r"^x must be a real number, got None$"):
        nonnegative("x", None)
    with pytest.raises(InvalidParameterError, match=r"^x must be finite and >= 0, got inf$"):
        nonnegative("x", np.inf)
    with pytest.raises(InvalidParameterError, match=r"^n must be an integer >= 2, got 1$"):
        positive_int("n", 1, 2)


def test_prepare_names_the_argument_it_refuses(cogiro_eq):
    with pytest.raises(InvalidParameterError, match=r"^n_points must be an integer >= 2, got 1$"):
        prepare(cogiro_eq, None, None, None, 1, None, 1.0)
    with pytest.raises(InvalidParameterError,
                       match=r"^sag_scale must be finite and >= 0, got -1\.0$"):
        prepare(cogiro_eq, None, None, None, 41, None, -1.0)
    with pytest.raises(InvalidParameterError,
                       match=r"^mode=0 needs modes= \(a ModalResult\), got None$"):
        prepare(cogiro_eq, None, 0, None, 41, None, 1.0)
