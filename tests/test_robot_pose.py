"""Pose (dynstiff/robot/pose.py): value semantics, validation, small motions."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.pose import as_pose


def test_poses_compare_and_hash_by_value():
    a = ds.Pose([1.0, 2.0, 3.0], [0.0, 0.1, 0.0])
    b = ds.Pose(np.array([1, 2, 3]), (0.0, 0.1, 0.0))
    c = ds.Pose([1.0, 2.0, 3.0])
    assert a == b and hash(a) == hash(b)
    assert a != c and c == ds.Pose([1, 2, 3], [0, 0, 0])
    assert len({a, b, c}) == 2
    assert a != (1.0, 2.0, 3.0)                    # another type is never equal
    assert hash(a) != hash(c)              # by value: poses spread over a dict's slots
    assert repr(a) == "Pose(position=[1, 2, 3] m, rotation=[0, 0.1, 0] rad)"


def test_as_pose_accepts_the_documented_forms_and_names_the_rest():
    ref = ds.Pose([1.0, 2.0, 3.0], [0.1, 0.0, 0.0])
    assert as_pose(ref) is ref
    assert as_pose([1, 2, 3, 0.1, 0, 0]) == ref
    assert as_pose(([1, 2, 3], [0.1, 0, 0])) == ref
    assert as_pose([1, 2, 3]) == ds.Pose([1, 2, 3])
    with pytest.raises(InvalidParameterError, match="pose"):
        as_pose([1, 2])
    with pytest.raises(InvalidParameterError, match="position"):
        ds.Pose([1.0, np.nan, 0.0])


def test_moved_composes_rotations_in_the_base_frame():
    """A quarter turn about z then a quarter turn about x (base axes) maps the platform's
    x axis to the base z axis."""
    p = ds.Pose([0, 0, 0], [0, 0, np.pi / 2]).moved(np.array([0, 0, 0, np.pi / 2, 0, 0]))
    np.testing.assert_allclose(p.matrix @ [1, 0, 0], [0, 0, 1], atol=1e-12)


def test_a_pose_holds_copies_and_computes_its_rotation_once():
    """The pose copies what it is given (the caller's arrays stay the caller's); its
    rotation matrix is computed once and handed out as a new array each time, and is
    computed again when the rotation vector is changed in place."""
    from dynstiff.robot.platform import rotation_matrix
    x, r = np.array([1.0, 2.0, 3.0]), np.array([0.1, -0.2, 0.3])
    p = ds.Pose(x, r)
    x[0] = r[0] = 9.0                                     # the caller's arrays
    assert p.position[0] == 1.0 and p.rotation[0] == 0.1
    R = p.matrix
    np.testing.assert_array_equal(R, rotation_matrix(np.array([0.1, -0.2, 0.3])))
    R[:] = 0.0                                            # the caller's copy
    np.testing.assert_array_equal(p.matrix, rotation_matrix(np.array([0.1, -0.2, 0.3])))
    p.rotation[2] = -0.4
    np.testing.assert_array_equal(p.matrix, rotation_matrix(np.array([0.1, -0.2, -0.4])))


def test_a_pose_given_integers_holds_floats():
    """Coordinates given as integers are held as float arrays, so a pose's position [m] and
    rotation [rad] take a fraction written in place (an integer array would cut it off)."""
    p = ds.Pose([1, 2, 3], [0, 0, 0])
    assert p.position.dtype == np.float64 and p.rotation.dtype == np.float64
    p.position[0] = 1.5
    p.rotation[2] = 0.25
    assert p.position.tolist() == [1.5, 2.0, 3.0]
    np.testing.assert_allclose(p.matrix, [[np.cos(0.25), -np.sin(0.25), 0.0],
                                          [np.sin(0.25), np.cos(0.25), 0.0],
                                          [0.0, 0.0, 1.0]], rtol=0, atol=1e-15)


@pytest.mark.parametrize("position, rotation, name, shown", [
    (["a", "b", "c"], None, "position", "['a', 'b', 'c']"),
    ([1.0, 2.0, 3.0], [0.0, "x", 0.0], "rotation", "[0.0, 'x', 0.0]"),
    ([[1.0, 2.0], [3.0]], None, "position", "[[1.0, 2.0], [3.0]]"),
    ([1.0, 2.0, 3.0], [0.0, 0.0, 1j], "rotation", "[0.0, 0.0, 1j]"),
])
def test_text_ragged_or_complex_coordinates_are_refused_by_name(position, rotation, name,
                                                                shown):
    """Coordinates that are not numbers (text, a ragged list, a complex number) are refused
    with the one-line message naming the pose's field and the value given, as a wrong
    count is, never with numpy's own error."""
    kw = {} if rotation is None else {"rotation": rotation}
    with pytest.raises(InvalidParameterError) as err:
        ds.Pose(position, **kw)
    assert str(err.value) == (f"pose {name} must be 3 finite numbers within 1e+100, got "
                              f"{shown}")
