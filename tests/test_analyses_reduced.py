"""Reduced modal model and its python-control StateSpace (dynstiff/analyses/reduced.py, theory.md
§15.4): exact modal masses against the closed-form cable kinetic energies, the expansion's
FRF against the full closed-form FRF below the highest kept mode, the residual flexibility,
and the state-space realisation against the expansion."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.reduced import ModalModel, modal_model, to_statespace

# These tests check the algebra of undamped FRFs (symmetry, kinds, files, figures) across
# natural frequencies on purpose: the ResonanceWarning that says so is expected here.
pytestmark = pytest.mark.filterwarnings("ignore::dynstiff.errors.ResonanceWarning")

FMAX = 8.0            # [Hz]: CoGiRo's modes below it, 38 with the platform moving


@pytest.fixture(scope="module")
def dsm():
    return ds.build_model(ds.load_scene("cogiro").equilibrium(), "dsm")


@pytest.fixture(scope="module")
def mm(dsm):
    return modal_model(dsm, fmax_hz=FMAX)


def test_complex_step_derivative_matches_finite_differences(dsm):
    from dynstiff.analyses.reduced import _dK_domega2
    w = 2 * np.pi * 2.0
    h = 1e-5 * w
    fd = (dsm.dynamic_stiffness([w + h])[0] - dsm.dynamic_stiffness([w - h])[0]) / (4 * w * h)
    np.testing.assert_allclose(_dK_domega2(dsm, w), fd, atol=1e-9 * np.abs(fd).max())


def test_modal_masses_equal_the_kinetic_energy_of_platform_and_cables(dsm, mm):
    """mu_r (from dK/d omega^2) = 1 + E_cables / E_platform = 1 / (1 - cable energy fraction)
    of ds.modes, whose cable energies come from the closed-form cable fields."""
    md = ds.modes(dsm, fmax_hz=FMAX)
    moving = np.abs(md.platform_shapes).max(axis=1) > 0
    np.testing.assert_allclose(mm.freq_hz, md.freq_hz[moving], rtol=1e-12)
    np.testing.assert_allclose(mm.modal_mass, 1.0 / (1.0 - md.cable_energy_fraction[moving]),
                               rtol=1e-6)


def test_massless_cables_have_unit_modal_mass():
    m = ds.build_model(ds.load_scene("cogiro").equilibrium(), "spring")
    np.testing.assert_allclose(modal_model(m, n_modes=6).modal_mass, 1.0, rtol=1e-9)


def test_expansion_matches_the_full_frf_below_the_highest_kept_mode(dsm, mm):
    """Stated tolerance: relative Frobenius error <= 1e-3 from 0.05 Hz to 0.98 of the
    highest kept frequency (measured 4.8e-4, at 7.0 Hz); without the residual flexibility
    the error is ten times larger over most of the band."""
    f = np.linspace(0.05, 0.98 * mm.freq_hz.max(), 1500)
    H = ds.frf(dsm, 2 * np.pi * f).H
    norm = np.linalg.norm(H, axis=(1, 2))
    err = np.linalg.norm(mm.receptance(2 * np.pi * f) - H, axis=(1, 2)) / norm
    assert err.max() < 1e-3
    bare = modal_model(dsm, fmax_hz=FMAX, residual=False)
    err0 = np.linalg.norm(bare.receptance(2 * np.pi * f) - H, axis=(1, 2)) / norm
    assert np.median(err0) > 10 * np.median(err)
    # exact at omega = 0: the residual restores the static flexibility K(0)^-1
    np.testing.assert_allclose(mm.receptance([0.0])[0], np.linalg.inv(dsm.massless_stiffness()),
                               rtol=1e-9, atol=1e-12 * np.abs(mm.residual).max())


def test_statespace_frf_equals_the_expansion_and_the_full_frf(dsm, mm):
    control = pytest.importorskip("control")
    sys = to_statespace(dsm, fmax_hz=FMAX, inputs=["fx", "mz"], outputs=["x", "y", "rz"],
                        point=[0.5, 0.5, 0.0])
    assert isinstance(sys, control.StateSpace)
    assert sys.nstates == 2 * len(mm) and sys.input_labels == ["fx", "mz"]
    f = np.linspace(0.1, 0.98 * mm.freq_hz.max(), 400)
    Hss = np.moveaxis(sys.frequency_response(2 * np.pi * f).complex, -1, 0)
    H = ds.frf(dsm, 2 * np.pi * f, inputs=["fx", "mz"], outputs=["x", "y", "rz"],
               point=[0.5, 0.5, 0.0]).H
    err = np.linalg.norm(Hss - H, axis=(1, 2)) / np.linalg.norm(H, axis=(1, 2))
    assert err.max() < 1e-3
    # poles: the kept natural frequencies
    poles = np.sort(np.abs(sys.poles().imag))[::2]
    np.testing.assert_allclose(poles, np.sort(mm.omega), rtol=1e-9)


def test_damping_sets_the_pole_ratios(dsm):
    pytest.importorskip("control")
    sys = to_statespace(dsm, n_modes=3, damping=0.02)
    p = sys.poles()
    np.testing.assert_allclose(-p.real / np.abs(p), 0.02, rtol=1e-9)


def test_bad_damping_is_named(dsm):
    with pytest.raises(ds.InvalidParameterError, match="damping must be"):
        modal_model(dsm, n_modes=3, damping=[0.1, 0.2])
    with pytest.raises(ds.InvalidParameterError, match="damping must be"):
        modal_model(dsm, n_modes=3, damping=-0.1)


def test_repeated_roots_keep_both_shapes():
    """A point mass under 4 cables from the corners of a square has a double root (x and y
    swing alike): both platform shapes are kept, mass-orthonormal, at the same frequency."""
    anchors = np.array([[3.0, 3.0, 4.0], [-3.0, 3.0, 4.0], [-3.0, -3.0, 4.0], [3.0, -3.0, 4.0]])
    robot = ds.Robot(anchors, np.zeros((4, 3)), ds.Cable(0.05, 2e5),
                     ds.Platform(20.0, free_dofs=("x", "y", "z")))
    m = ds.build_model(robot.equilibrium([0.0, 0.0, 1.0]), "dsm")
    f = ds.eigenfrequencies(m, n_modes=2)
    assert abs(f[1] / f[0] - 1) < 1e-9                      # the double root
    mm = modal_model(m, n_modes=3)
    assert len(mm) == 3
    np.testing.assert_allclose(mm.freq_hz[:2], f, rtol=1e-9)
    G = mm.shapes @ m.platform_mass @ mm.shapes.T * mm.modal_mass[:, None]
    np.testing.assert_allclose(G, np.eye(3), atol=1e-9)
    fz = ds.eigenfrequencies(m, n_modes=3)
    span = f"{fz.min():.4g}-{fz.max():.4g} Hz"
    assert isinstance(mm, ModalModel)
    assert repr(mm) == f"ModalModel(3 modes {span}, free ('x', 'y', 'z'), residual on)"
    assert repr(modal_model(m, n_modes=3, residual=False)) == \
        f"ModalModel(3 modes {span}, free ('x', 'y', 'z'), residual off)"


def test_truncation_error_grows_as_omega_squared(dsm, mm):
    """With the static residual, the first neglected term of each truncated mode is
    omega^2 phi phi^T / omega_t^4: at low frequency the error quadruples when omega doubles
    (theory.md §15.4)."""
    f = np.array([0.1, 0.2, 0.4])
    H = ds.frf(dsm, 2 * np.pi * f).H
    e = np.linalg.norm(mm.receptance(2 * np.pi * f) - H, axis=(1, 2)) / \
        np.linalg.norm(H, axis=(1, 2))
    np.testing.assert_allclose(e[1:] / e[:-1], 4.0, rtol=0.05)


def test_statespace_is_named_floored_and_bode_plots():
    control = pytest.importorskip("control")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # planar2 at x = 0 is mirror symmetric: its x and z modes do not couple
    dsm = ds.build_model(ds.load_scene("planar2").equilibrium(), "dsm")
    sys = to_statespace(dsm, n_modes=4, damping=0.02, inputs=["fx", "fz"],
                        outputs=["x", "z"])
    assert sys.name == "dynstiff modal model"
    n = sys.nstates // 2
    B = np.asarray(sys.B)[n:]                    # modal forces of fx, fz
    assert n >= 2 and np.count_nonzero(B) == n   # each mode driven by one input only
    assert np.all(np.count_nonzero(B, axis=1) == 1)
    cp = control.bode_plot(sys, 2 * np.pi * np.linspace(0.05, 3.0, 50))
    assert "dynstiff modal model" in cp.figure._suptitle.get_text()
    plt.close(cp.figure)


@pytest.mark.parametrize("kw, message", [
    (dict(damping=[True, 0.1, 0.1]), "^damping must be real numbers, not booleans"),
    (dict(damping="a"), "^damping must be one ratio >= 0 or one per kept mode, got 'a'"),
    (dict(damping=-0.1), "^damping must be one ratio >= 0 or one per kept mode, got -0.1"),
    (dict(cluster_rtol=True), "^cluster_rtol must be a real number, got True"),
    (dict(null_rtol=np.nan), "^null_rtol must be finite, got nan"),
    (dict(residual="no"), "^residual must be True or False, got 'no'")])
def test_modal_model_options_are_checked_before_the_modes_are_computed(dsm, kw, message,
                                                                       monkeypatch):
    """A worded flag ("no" is true in Python) or a boolean ratio is refused naming it, before
    any root is searched (the search is made to fail here)."""
    import dynstiff.analyses.reduced as red
    monkeypatch.setattr(red, "eigenfrequencies", lambda *a, **k: 1 / 0)
    with pytest.raises(ds.InvalidParameterError, match=message):
        modal_model(dsm, n_modes=3, **kw)


def test_to_statespace_refuses_a_worded_residual_flag_of_a_modal_model(mm):
    with pytest.raises(ds.InvalidParameterError, match="^residual must be True or False"):
        to_statespace(mm, residual="no")


def test_null_rtol_is_the_threshold_on_the_eigenvalues_at_the_root(dsm):
    """A root is kept iff |eig K(omega_r)| < null_rtol max|eig K(0)|; none kept: H = K(0)^-1."""
    w = 2 * np.pi * ds.eigenfrequencies(dsm, n_modes=1)[0]
    K = dsm.dynamic_stiffness([w])[0]
    K0 = dsm.massless_stiffness()
    e0 = np.abs(np.linalg.eigvalsh(0.5 * (K + K.T))).min()
    scale = np.abs(np.linalg.eigvalsh(0.5 * (K0 + K0.T))).max()
    kept = modal_model(dsm, n_modes=1, null_rtol=2.0 * e0 / scale)
    assert len(kept) == 1 and kept.omega[0] == w
    none = modal_model(dsm, n_modes=1, null_rtol=0.5 * e0 / scale)
    assert len(none) == 0 and none.shapes.shape == (0, 6)
    assert repr(none) == ("ModalModel(0 modes none, free ('x', 'y', 'z', 'rx', 'ry', 'rz'), "
                          "residual on)")
    np.testing.assert_allclose(none.receptance([0.0, w])[1], np.linalg.inv(K0), rtol=1e-12,
                               atol=1e-12 * np.abs(np.linalg.inv(K0)).max())


def test_non_positive_modal_mass_is_refused_naming_it_and_its_frequency(monkeypatch):
    """mu_r = -x^T M_p x (dK/d omega^2 negated here) is refused naming its value and Hz."""
    import re

    import dynstiff.analyses.reduced as red
    m = ds.build_model(ds.load_scene("cogiro").equilibrium(), "spring")
    f1 = ds.eigenfrequencies(m, n_modes=1)[0]
    K = m.dynamic_stiffness([2 * np.pi * f1])[0]
    x = np.linalg.eigh(0.5 * (K + K.T))[1][:, 0]           # unit shape of the root
    mu = -(x @ m.platform_mass @ x)
    dK = red._dK_domega2
    monkeypatch.setattr(red, "_dK_domega2", lambda model, w: -dK(model, w))
    with pytest.raises(ds.InvalidParameterError,
                       match=f"^{re.escape(f'non-positive modal mass {mu:.3g} at {f1:.6g} Hz')}$"):
        modal_model(m, n_modes=1)


def _two_modes(pose, residual):
    """A ModalModel written by hand: modes at 2 and 5 rad/s on the free DOFs (x, y, z)."""
    return ModalModel(omega=np.array([2.0, 5.0]),
                      shapes=np.array([[1.0, 1e-12, -1e-12], [-0.5, 1.5e-12, 0.25]]),
                      modal_mass=np.ones(2), damping=np.array([0.1, 0.0]), residual=residual,
                      free_dofs=("x", "y", "z"), pose=pose)


def test_receptance_is_the_modal_sum_also_for_integer_frequencies(dsm):
    """H = sum phi phi^T / (w_r^2 - w^2 + 2i zeta_r w_r w) + R, also at int32 w (46341^2 > 2^31)"""
    R = np.diag([4e-3, 1e-3, 2e-3])
    mm = _two_modes(dsm.pose, R)
    w = np.array([0.0, 3.0, 46341.0])
    den = mm.omega**2 - w[:, None]**2 + 2j * mm.damping * mm.omega * w[:, None]
    Hm = sum(np.multiply.outer(1 / den[:, r], np.outer(mm.shapes[r], mm.shapes[r]))
             for r in range(2))
    tol = dict(rtol=1e-14, atol=1e-14 * np.abs(Hm).max())
    np.testing.assert_allclose(mm.receptance(w), Hm + R, **tol)
    np.testing.assert_allclose(mm.receptance(w.astype(np.int32)), Hm + R, **tol)
    np.testing.assert_allclose(_two_modes(dsm.pose, None).receptance(w), Hm, **tol)


@pytest.mark.parametrize("with_residual, residual_flag", [(True, True), (True, False),
                                                          (False, True)])
def test_statespace_of_a_modal_model_is_its_realisation(dsm, with_residual, residual_flag):
    """A ModalModel's own A, B, C (floored at <= 1e-12 of their largest), D, names and FRF."""
    control = pytest.importorskip("control")
    R = np.array([[4e-3, 1e-4, 0.0], [1e-4, 1e-3, 2e-4], [0.0, 2e-4, 2e-3]])
    mm = _two_modes(dsm.pose, R if with_residual else None)
    # n_modes and damping are ignored for a ModalModel: its own modes and ratios are realised
    sys = to_statespace(mm, n_modes=1, damping=0.3, inputs=["fx", "fy"], outputs=["x", "z"],
                        residual=residual_flag)
    assert isinstance(sys, control.StateSpace) and sys.name == "dynstiff modal model"
    assert sys.state_labels == ["q1", "q2", "dq1", "dq2"]
    assert sys.input_labels == ["fx", "fy"] and sys.output_labels == ["x", "z"]
    A = np.zeros((4, 4))
    A[:2, 2:] = np.eye(2)
    A[2:, :2] = -np.diag([2.0, 5.0])**2
    A[2:, 2:] = -2.0 * np.diag([0.1 * 2.0, 0.0])
    np.testing.assert_array_equal(sys.A, A)
    # modal forces of fx, fy: phi_r[x], phi_r[y]; 1e-12 = ZERO_FLOOR x 1.0 is zeroed
    np.testing.assert_array_equal(sys.B, [[0, 0], [0, 0], [1.0, 0.0], [-0.5, 1.5e-12]])
    np.testing.assert_array_equal(sys.C, [[1.0, -0.5, 0, 0], [0.0, 0.25, 0, 0]])
    D = R[np.ix_([0, 2], [0, 1])] if with_residual and residual_flag else np.zeros((2, 2))
    np.testing.assert_array_equal(sys.D, D)
    w = np.array([1.0, 3.0, 7.0])
    Hss = np.moveaxis(sys.frequency_response(w).complex, -1, 0)
    H = _two_modes(dsm.pose, None).receptance(w)[:, [0, 2]][:, :, [0, 1]] + D
    np.testing.assert_allclose(Hss, H, rtol=1e-9, atol=1e-9 * np.abs(H).max())
