"""Platform kinematics (dynstiff/platform.py): the lever map J = [I, -[r]x] moves a point of
the platform by dp + dtheta x r, and its transpose carries a force to a wrench about P
(theory.md §4)."""

import numpy as np

import dynstiff as ds


def test_lever_map_moves_a_point_by_dp_plus_dtheta_cross_r():
    rng = np.random.default_rng(3)
    r, dp, dth = rng.normal(size=(3, 3))
    x = np.concatenate([dp, dth])
    np.testing.assert_allclose(ds.platform.lever_map(r) @ x, dp + np.cross(dth, r),
                               rtol=1e-14, atol=1e-15)
    # J^T f is the wrench about P of a force f at r
    f = rng.normal(size=3)
    np.testing.assert_allclose(ds.platform.lever_map(r).T @ f,
                               np.concatenate([f, np.cross(r, f)]), rtol=1e-14, atol=1e-15)
    fi = [0, 2, 5]
    np.testing.assert_array_equal(ds.platform.lever_map(r, fi),
                                  ds.platform.lever_map(r)[:, fi])
