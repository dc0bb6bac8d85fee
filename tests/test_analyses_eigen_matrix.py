"""Modes of the discrete rungs (dynstiff/analyses/eigen_matrix.py, theory.md §7.1-§7.2): sparse
shift-invert equals dense, platform shapes are mass-normalised with the held DOFs zero, and
the cable energies and node shapes of the lumped model."""

import numpy as np
from conftest import linearised, point_mass_robot

import dynstiff as ds
from dynstiff.analyses import eigen_matrix
from dynstiff.lumped import LumpedModalResult


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
    M_p = ds.robot.platform.platform_mass_matrix(cogiro.robot.platform, model.pose.matrix)
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


def test_band_request_counts_first_and_solves_once(lumped, cogiro_eq, monkeypatch):
    """The number of modes below fmax is the W-W count of the condensed K (exact for a
    discrete model): it equals the dense eigenvalue count at every probe, and a band request
    then takes one sparse solve of exactly that many modes."""
    import scipy.linalg
    model = lumped(20)
    K, M = model.matrices()
    K = 0.5 * (K + K.T)
    lam = scipy.linalg.eigh(K.toarray(), M.toarray(), eigvals_only=True)
    f_all = np.sqrt(np.abs(lam)) * np.sign(lam) / (2 * np.pi)
    for f_probe in (0.5, 2.3, 3.4, 6.0, 9.97):
        gap = np.abs(f_all / f_probe - 1).min()
        assert gap > 1e-6                                  # probe away from any mode
        assert eigen_matrix.count_below(model, 2 * np.pi * f_probe) == \
            np.sum(f_all < f_probe)
    spring = ds.build_model(cogiro_eq, "spring")
    Ks, Ms = spring.matrices()
    lam_s = scipy.linalg.eigh(0.5 * (Ks + Ks.T), Ms, eigvals_only=True)
    assert eigen_matrix.count_below(spring, 2 * np.pi * 3.0) == \
        np.sum(lam_s < (2 * np.pi * 3.0) ** 2) > 0
    calls = []
    eig = eigen_matrix.eig
    monkeypatch.setattr(eigen_matrix, "eig", lambda m, n: calls.append(n) or eig(m, n))
    f = ds.eigenfrequencies(model, fmax_hz=10.0)
    assert calls == [np.sum(f_all < 10.0)] == [len(f)]
    np.testing.assert_allclose(f, f_all[:len(f)], rtol=1e-9)
