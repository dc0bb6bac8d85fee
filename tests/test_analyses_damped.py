"""Damped complex natural frequencies (dynstiff/analyses/damped.py, theory.md §5.4)."""

import numpy as np
import pytest
import scipy.linalg

import dynstiff as ds
from dynstiff.analyses.damped import damped_modes


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def skew(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def robot_with(scene, **cable_kw):
    r = scene.robot
    cable = ds.Cable(cable_kw.pop("mass_per_length", 0.064), r.cables[0].EA, **cable_kw)
    return ds.Robot(r.anchors, r.attachments, cable, r.platform, tension_limits=r.tension_limits)


def test_massless_hysteretic_matches_complex_eigenproblem(scene):
    """Massless cables with EA(1 + i eta): K_c = sum J^T (k (1 + i eta) u u^T + t/l (I - u u^T))
    J + K_geo is frequency independent, so omega^2 are the eigenvalues of (K_c, M)."""
    eta = 0.05
    rob = robot_with(scene, mass_per_length=1e-7, loss_factor=eta)
    eq = rob.equilibrium(pose=scene.pose)
    m = ds.FrequencyModel(eq)
    K = np.zeros((6, 6), dtype=complex)
    for i, s in enumerate(eq.states):
        r = eq.lever_arms[i]
        d = s.anchor - s.end
        l = np.linalg.norm(d)
        u = d / l
        t = s.tension_at_end
        Kc = rob.cables[i].EA * (1 + 1j * eta) / eq.unstretched_lengths[i] * np.outer(u, u) \
            + t / l * (np.eye(3) - np.outer(u, u))
        J = np.hstack([np.eye(3), -skew(r)])
        K += J.T @ Kc @ J
    K += m.K_geo
    lam = scipy.linalg.eigvals(K, m.M_p)
    w_ref = np.sort_complex(np.sqrt(lam))                 # principal root: Im > 0
    d = damped_modes(m, 6)
    np.testing.assert_allclose(np.sort_complex(d.omega), w_ref, rtol=1e-7)
    assert np.all(d.damping_ratio > 0) and np.all(d.damping_ratio < eta / 2 + 1e-6)


def test_damping_ratio_is_linear_in_loss_factor(scene):
    z = []
    for eta in (1e-3, 2e-3):
        m = ds.FrequencyModel(robot_with(scene, loss_factor=eta).equilibrium(pose=scene.pose))
        z.append(damped_modes(m, 3).damping_ratio)
    np.testing.assert_allclose(z[1] / z[0], 2.0, rtol=2e-3)


def test_viscous_damping_gives_decaying_modes(scene):
    m = ds.FrequencyModel(robot_with(scene, viscous_damping=0.02).equilibrium(pose=scene.pose))
    d = damped_modes(m, 24)
    ok = np.isfinite(d.omega)
    glob = np.array(ds.modes(m, 24).kind) == "global"
    assert glob.sum() == 6 and np.all(ok[glob])      # every global mode is found
    # overlapping local modes (spacing ~ their damping) are NaN, never a wrong root
    assert len(set(np.round(d.omega[ok], 9))) == ok.sum()
    assert np.all(d.damping_ratio[ok] > 0)
    assert np.all(d.residual[ok] < 1e-8)
    np.testing.assert_allclose(d.freq_hz[ok], d.undamped_freq_hz[ok], rtol=5e-3)


@pytest.mark.parametrize("kw, message", [
    (dict(tol=True), "^tol must be a real number, got True$"),
    (dict(tol="a"), "^tol must be a real number, got 'a'$"),
    (dict(tol=-1.0), r"^tol must be > 0, got -1\.0$"),
    (dict(max_iter=True), "^max_iter must be an integer >= 1, got True$"),
    (dict(max_iter=2.0), r"^max_iter must be an integer >= 1, got 2\.0$")])
def test_the_secant_options_are_checked_naming_them(scene, kw, message):
    """max_iter=True was one secant step, and tol text a TypeError in the loop."""
    m = ds.FrequencyModel(scene.equilibrium(), platform_damping_ratio=0.02)
    with pytest.raises(ds.InvalidParameterError, match=message):
        ds.damped_modes(m, n_modes=1, **kw)
