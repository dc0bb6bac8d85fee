"""Platform kinematics (dynstiff/robot/platform.py): the lever map J = [I, -[r]x] moves a point of
the platform by dp + dtheta x r, and its transpose carries a force to a wrench about P
(theory.md §4)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.platform import rotation_matrix


def test_lever_map_moves_a_point_by_dp_plus_dtheta_cross_r():
    rng = np.random.default_rng(3)
    r, dp, dth = rng.normal(size=(3, 3))
    x = np.concatenate([dp, dth])
    np.testing.assert_allclose(ds.robot.platform.lever_map(r) @ x, dp + np.cross(dth, r),
                               rtol=1e-14, atol=1e-15)
    # J^T f is the wrench about P of a force f at r
    f = rng.normal(size=3)
    np.testing.assert_allclose(ds.robot.platform.lever_map(r).T @ f,
                               np.concatenate([f, np.cross(r, f)]), rtol=1e-14, atol=1e-15)
    fi = [0, 2, 5]
    np.testing.assert_array_equal(ds.robot.platform.lever_map(r, fi),
                                  ds.robot.platform.lever_map(r)[:, fi])


@pytest.mark.parametrize("angle", [0.0, 1e-9, 1e-4, 9.9e-4, 1.1e-3, 0.5, 2.0, np.pi - 1e-6])
def test_rotation_helpers_equal_scipy_rotation(angle):
    """rotation_matrix and the quaternion composition of Pose.moved against scipy's
    Rotation, on both sides of the series threshold (1e-3 rad) and near pi."""
    from scipy.spatial.transform import Rotation

    from dynstiff.robot.platform import (
        quaternion_product,
        quaternion_to_rotvec,
        rotvec_to_quaternion,
    )
    rng = np.random.default_rng(int(1e6 * angle) % 2**32)
    for _ in range(20):
        axis = rng.standard_normal(3)
        v = angle * axis / np.linalg.norm(axis)
        w = rng.uniform(-0.3, 0.3, 3)
        np.testing.assert_allclose(rotation_matrix(v), Rotation.from_rotvec(v).as_matrix(),
                                   rtol=0, atol=2e-15)
        np.testing.assert_allclose(rotvec_to_quaternion(v), Rotation.from_rotvec(v).as_quat(
            canonical=False), rtol=0, atol=2e-16)
        q = quaternion_product(rotvec_to_quaternion(w), rotvec_to_quaternion(v))
        ref = (Rotation.from_rotvec(w) * Rotation.from_rotvec(v)).as_rotvec()
        np.testing.assert_allclose(quaternion_to_rotvec(q), ref, rtol=0, atol=4e-15)


def test_lever_maps_stack_lever_map():
    """lever_maps of n arms is lever_map of each, all DOFs and a free subset."""
    from dynstiff.robot.platform import lever_map, lever_maps
    r = np.random.default_rng(2).normal(size=(5, 3))
    for fi in (None, np.array([0, 2, 3, 5])):
        np.testing.assert_array_equal(lever_maps(r, fi), [lever_map(x, fi) for x in r])
    whole = [[1, -2, 3], [0, 4, -1]]                # integer arms give the same float maps
    assert lever_maps(whole).dtype == np.float64
    np.testing.assert_array_equal(lever_maps(whole), lever_maps(np.array(whole, dtype=float)))


def test_platform_input_is_checked_to_rounding_and_named():
    """Mass, inertia shape, symmetry and definiteness are checked with tolerances relative
    to the inertia's size: a rounding-level asymmetry (1e-13 of |I|) or negative eigenvalue
    (1e-13 of |I|, translations only) is accepted; 1e-10 of |I| is not, and the messages name
    the argument and the value. The centre of mass and the inertia are stored as floats."""
    big = np.diag([1e4, 1e4, 1e4])
    skew = big.copy()
    skew[0, 1] += 1e-9
    ds.Platform(mass=2.0, inertia=skew)
    skew[0, 1] += 1e-6
    with pytest.raises(InvalidParameterError, match="^inertia must be symmetric, got"):
        ds.Platform(mass=2.0, inertia=skew)
    trans = ("x", "y", "z")
    ds.Platform(mass=2.0, inertia=np.diag([1e4, 1e4, -1e-9]), free_dofs=trans)
    with pytest.raises(InvalidParameterError) as err:
        ds.Platform(mass=2.0, inertia=np.diag([1e4, 1e4, -1e-6]), free_dofs=trans)
    assert str(err.value) == ("inertia must be positive semi-definite, eigenvalues "
                              "[-1e-06, 10000.0, 10000.0] [kg m^2]")
    with pytest.raises(InvalidParameterError) as err:
        ds.Platform(mass=-1.0)
    assert str(err.value) == "mass must be > 0, got -1.0"
    with pytest.raises(InvalidParameterError) as err:
        ds.Platform(mass=1.0, inertia=np.ones((2, 2)))
    assert str(err.value) == "inertia must be a finite 3x3 tensor [kg m^2], got shape (2, 2)"
    p = ds.Platform(mass=2, center_of_mass=[1, 2, 3], inertia=[[2, 0, 0], [0, 3, 0], [0, 0, 4]])
    assert p.center_of_mass.dtype == p.inertia.dtype == np.float64 and type(p.mass) is float


def test_any_free_rotation_needs_a_positive_definite_physical_inertia():
    """Each of rx, ry, rz alone makes the inertia matter: a singular one is refused (it is
    accepted when only translations are free). The principal moments of a body obey
    I3 <= I1 + I2, with equality for a thin plate: a plate whose I3 exceeds I1 + I2 by a
    rounding-level 5e-10 of I3 (and a rotated plate) is accepted, 5e-9 of I3 is not. A
    negative rounding-level eigenvalue is judged against the largest moment, not the middle
    one, and an asymmetry against the largest entry (1e-12 of it), not against the product
    of inertia itself (1e-10 on unit moments is refused). No free DOF is refused, and the
    free DOFs are kept in canonical order. The messages name the argument and the value."""
    singular = np.diag([0.0, 1.0, 4.0])
    for dof in ("rx", "ry", "rz"):
        with pytest.raises(InvalidParameterError,
                           match="^inertia must be positive definite when a rotation is free"):
            ds.Platform(mass=1.0, inertia=singular, free_dofs=("z", dof))
    ds.Platform(mass=1.0, inertia=singular, free_dofs=("x", "y", "z"))
    skew = np.array([[1e4, 100.0, 0.0], [100.0 + 1e-6, 1e4, 0.0], [0.0, 0.0, 1e4]])
    with pytest.raises(InvalidParameterError, match="^inertia must be symmetric"):
        ds.Platform(mass=1.0, inertia=skew)          # 1e-8 relative to the product 100
    ds.Platform(mass=1.0, inertia=np.diag([1.0, 1e4, -1e-10]), free_dofs=("x", "y", "z"))
    with pytest.raises(InvalidParameterError, match="positive semi-definite"):
        ds.Platform(mass=1.0, inertia=np.diag([1.0, 1e4, -1e-7]), free_dofs=("x", "y", "z"))
    ds.Platform(mass=1.0, inertia=np.diag([1000.0, 1000.0, 2000.0 + 1e-6]))
    R = rotation_matrix([0.3, -1.1, 0.7])
    ds.Platform(mass=1.0, inertia=R @ np.diag([300.0, 1700.0, 2000.0]) @ R.T)
    with pytest.raises(InvalidParameterError, match="triangle inequality"):
        ds.Platform(mass=1.0, inertia=np.diag([1.0, 10.0, 15.0]))     # 15 > 1 + 10
    with pytest.raises(InvalidParameterError, match="^inertia must be symmetric"):
        ds.Platform(mass=1.0, inertia=[[1.0, 0.0, 0.0], [1e-10, 1.0, 0.0], [0.0, 0.0, 1.0]])
    with pytest.raises(InvalidParameterError, match="^free_dofs must be distinct names"):
        ds.Platform(mass=1.0, free_dofs=())
    assert ds.Platform(1.0, inertia=np.eye(3), free_dofs=("rz", "z", "x")).free_dofs == (
        "x", "z", "rz")
    with pytest.raises(InvalidParameterError) as err:
        ds.Platform(mass=1.0, inertia=np.diag([1000.0, 1000.0, 2000.0 + 1e-5]))
    assert str(err.value).startswith("inertia violates the triangle inequality of principal "
                                     "moments [1000.0, 1000.0, 2000.00001] [kg m^2]")
    with pytest.raises(InvalidParameterError) as err:
        ds.Platform(mass=1.0, center_of_mass=[1.0, 2.0])
    assert str(err.value) == "center_of_mass must be 3 finite numbers [m], got [1.0, 2.0]"


@pytest.mark.parametrize("scale", [1e-6, 1.0, 1e6])
def test_inertia_checks_do_not_depend_on_units(scale):
    """The symmetry and semi-definiteness checks are relative to the tensor's size: the same
    body in other units (a tensor scaled by 1e-6 or 1e6) gets the same verdict."""
    skew = np.array([[1.0, 0.0, 0.0], [5e-10, 1.0, 0.0], [0.0, 0.0, 1.5]])
    with pytest.raises(InvalidParameterError, match="^inertia must be symmetric"):
        ds.Platform(mass=1.0, inertia=scale * skew)
    R = rotation_matrix([0.3, -1.1, 0.7])
    ds.Platform(mass=1.0, inertia=scale * (R @ np.diag([1.0, 1.0, 1.5]) @ R.T))  # rounding only
    held = ("x", "y", "z")
    with pytest.raises(InvalidParameterError, match="positive semi-definite"):
        ds.Platform(mass=1.0, inertia=scale * np.diag([1.0, 1.0, -1e-9]), free_dofs=held)
    ds.Platform(mass=1.0, inertia=scale * np.diag([1.0, 1.0, -1e-13]), free_dofs=held)
    # relative to the largest eigenvalue: -5e-11 is rounding next to 100
    ds.Platform(mass=1.0, inertia=scale * np.diag([1.0, 100.0, -5e-11]), free_dofs=held)
