"""Modes of the discrete rungs (dynstiff/eigen_matrix.py, theory.md §7.1-§7.2): sparse
shift-invert equals dense, platform shapes are mass-normalised with the held DOFs zero, and
the cable energies and node shapes of the lumped model."""

import numpy as np

import dynstiff as ds
from dynstiff import eigen_matrix
from dynstiff.lumped import LumpedModalResult
from conftest import linearised, point_mass_robot


def test_sparse_shift_invert_equals_dense(lumped, monkeypatch):
    model = lumped(20)
    assert model.n_dof > eigen_matrix.DENSE_LIMIT
    f_sparse = ds.eigenfrequencies(model, 12)
    monkeypatch.setattr(eigen_matrix, "DENSE_LIMIT", 10**6)
    np.testing.assert_allclose(ds.eigenfrequencies(model, 12), f_sparse, rtol=1e-10)


def test_modes_normalisation_and_energy(cogiro, lumped):
    model = lumped(20)
    md = ds.modes(model, 12)
    assert isinstance(md, LumpedModalResult)
    M_p = ds.platform.platform_mass_matrix(cogiro.robot.platform, model.pose.matrix)
    x = md.platform_shapes
    np.testing.assert_allclose(np.einsum("ni,ij,nj->n", x, M_p, x), 1.0, rtol=1e-10)
    np.testing.assert_allclose(md.cable_energy.sum(axis=1), md.cable_energy_fraction,
                               rtol=1e-12)
    kinds = np.array(md.kind)
    assert np.all(md.cable_energy_fraction[kinds == "global"] < 0.5)
    assert np.all(md.cable_energy_fraction[kinds == "local"] >= 0.5)
    # node shapes: anchors at rest, the last node moves with the platform point B_i
    _, r = cogiro.robot.attachment_points(model.pose)
    k = int(np.flatnonzero(kinds == "global")[0])
    B_motion = np.array([ns[k, -1] for ns in md.node_shapes])
    scale = B_motion[0, 0] / (x[k, :3] + np.cross(x[k, 3:], r[0]))[0]
    np.testing.assert_allclose(B_motion, scale * (x[k, :3] + np.cross(x[k, 3:], r)),
                               atol=1e-12 * np.abs(B_motion).max())
    assert all(np.all(ns[:, 0] == 0) for ns in md.node_shapes)
    # massless-cable (condensed) frequencies lie above the global ones (cable inertia)
    g = kinds == "global"
    assert np.all(md.massless_freq_hz[g] > md.freq_hz[g])


def test_point_mass_held_rotations_are_zero():
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.2, -0.1, 1.0])
    md = ds.modes(linearised(rob, eq.unstretched_lengths, 8), 10)
    assert np.all(md.platform_shapes[:, 3:] == 0)
    np.testing.assert_allclose(np.sum(md.platform_shapes[:, :3] ** 2, axis=1) * 20.0, 1.0,
                               rtol=1e-12)
