"""Every rung of the ladder (dynstiff/models/ladder.py) answers the same questions through the same
functions: frf, eigenfrequencies, modes, mode_count, damped_modes (the interface of
dynstiff/models/base.py, theory.md §4, §5)."""

import dataclasses
import re

import matplotlib
import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError, UnsupportedAnalysisError

# These tests check the algebra of undamped FRFs (symmetry, kinds, files, figures) across
# natural frequencies on purpose: the ResonanceWarning that says so is expected here.
pytestmark = pytest.mark.filterwarnings("ignore::dynstiff.errors.ResonanceWarning")

matplotlib.use("Agg")

RUNG_OPTIONS = {"spring": {}, "catenary": {}, "dsm": {}, "exact": {"fmax_hz": 10.0},
                "lumped": {"segments": 10}}


@pytest.fixture(scope="module")
def models(cogiro_eq):
    return {r: ds.build_model(cogiro_eq, r, **kw) for r, kw in RUNG_OPTIONS.items()}


@pytest.mark.parametrize("rung", ds.RUNGS)
def test_every_rung_answers_every_question(models, rung):
    m = models[rung]
    assert m.rung == rung and m.free_dofs == ("x", "y", "z", "rx", "ry", "rz")
    assert len(repr(m)) < 200
    n = min(8, getattr(m, "n_dof", 8))
    f = ds.eigenfrequencies(m, n_modes=n)
    assert f.shape == (n,) and np.all(np.diff(f) >= 0) and f[0] > 0
    # fmax_hz and n_modes select the same modes; mode_count counts them exactly
    below = ds.eigenfrequencies(m, fmax_hz=f[-1] * (1 + 1e-9))
    np.testing.assert_allclose(below, f, rtol=1e-10)
    assert ds.mode_count(m, 2 * np.pi * f[-1] * (1 + 1e-9))[0] == n
    md = ds.modes(m, n_modes=n)
    np.testing.assert_allclose(md.freq_hz, f, rtol=1e-10)
    x = md.platform_shapes[[k == "global" for k in md.kind]]
    np.testing.assert_allclose(np.einsum("ni,ij,nj->n", x, m.platform_mass, x), 1.0, rtol=1e-8)
    df = md.to_frame()
    assert "freq [Hz]" in df.columns and len(df) == n
    fig = md.plot()
    assert fig.axes[0].get_xlabel() == "frequency [Hz]"
    matplotlib.pyplot.close(fig)


@pytest.mark.parametrize("rung", ds.RUNGS)
def test_frf_kinds_are_powers_of_i_omega_and_receptance_is_reciprocal(models, rung):
    """mobility = i omega H and accelerance = -omega^2 H exactly, for every rung; the
    undamped receptance is real and symmetric (Maxwell reciprocity)."""
    m = models[rung]
    w = 2 * np.pi * np.array([0.3, 1.1, 2.7])
    H = ds.frf(m, w)
    assert np.abs(H.H.imag).max() == 0.0
    np.testing.assert_allclose(H.H, np.swapaxes(H.H, 1, 2), rtol=1e-9,
                               atol=1e-12 * np.abs(H.H).max())
    mob = ds.frf(m, w, kind="mobility").H
    acc = ds.frf(m, w, kind="accelerance").H
    np.testing.assert_allclose(mob, 1j * w[:, None, None] * H.H, rtol=1e-14)
    np.testing.assert_allclose(acc, -(w**2)[:, None, None] * H.H, rtol=1e-14)
    assert np.all(mob.real == 0) and np.all(mob.imag[np.abs(H.H) > 0] != 0)


@pytest.mark.parametrize("rung", ds.RUNGS)
def test_static_limit_of_the_receptance_is_the_massless_compliance(models, rung):
    """H(omega -> 0) = K_massless^-1: the dynamic stiffness of every rung tends to its own
    massless stiffness (theory.md §3.6 for the closed form)."""
    m = models[rung]
    K0 = m.massless_stiffness()
    np.testing.assert_allclose(m.dynamic_stiffness(0.0)[0].real, K0, rtol=1e-9,
                               atol=1e-12 * np.abs(K0).max())
    H = ds.frf(m, [1e-4]).H[0].real
    np.testing.assert_allclose(H, np.linalg.inv(K0), rtol=1e-6, atol=1e-9 * np.abs(H).max())


@pytest.mark.parametrize("rung", ["spring", "catenary", "lumped"])
def test_wittrick_williams_equals_the_matrix_eigenproblem(models, rung):
    """Two independent solvers on a discrete rung: W-W counting on the condensed K(omega)
    (with the held-platform poles as J0) and the finite eigenproblem K phi = omega^2 M phi."""
    m = models[rung]
    n = min(25, m.n_dof)
    a = ds.eigenfrequencies(m, n_modes=n, method="matrix")
    b = ds.eigenfrequencies(m, n_modes=n, method="wittrick-williams")
    np.testing.assert_allclose(b, a, rtol=1e-9)                  # measured 1.6e-12


def test_the_rungs_agree_where_their_physics_does(models):
    """The lowest global mode of CoGiRo: massless rungs bracket nothing (they miss the
    cable inertia), the closed form and the lumped model agree to their discretisation
    error (theory.md §7.2: 10 segments, (pi/10)^2/24 = 4e-3 at the first harmonic)."""
    f = {r: ds.eigenfrequencies(m, n_modes=1)[0] for r, m in models.items()}
    assert abs(f["lumped"] / f["dsm"] - 1) < 4e-3
    assert abs(f["exact"] / f["dsm"] - 1) < 1e-3          # shallow taut cables: 1e-4 apart
    assert abs(f["catenary"] / f["dsm"] - 1) < 1e-2
    assert abs(f["spring"] / f["catenary"] - 1) < 2e-2


def test_local_modes_of_massless_cables_are_refused_with_a_typed_error(models, cogiro_eq):
    modes = ds.modes(models["dsm"], n_modes=3)
    pos, disp = ds.cable_fields(models["dsm"], modes, 0)
    assert pos.shape == disp.shape == (8, 41, 3)
    for rung in ("spring", "catenary", "lumped"):
        with pytest.raises(UnsupportedAnalysisError, match=rung):
            ds.cable_fields(models[rung], ds.modes(models[rung], n_modes=3), 0)
    with pytest.raises(UnsupportedAnalysisError, match="discrete rung"):
        ds.eigenfrequencies(models["dsm"], 3, method="matrix")
    with pytest.raises(InvalidParameterError, match="LumpedLinearModel"):
        ds.modes(ds.LumpedMassModel(cogiro_eq.robot, cogiro_eq.unstretched_lengths, 4), 3)


@pytest.mark.parametrize("rung", ds.RUNGS)
def test_models_are_immutable(models, rung):
    m = models[rung]
    with pytest.raises(AttributeError, match="immutable"):
        m.pose = None
    with pytest.raises(ValueError, match="read-only"):
        m.platform_mass[0, 0] = 1.0


def test_damped_roots_for_any_rung_that_takes_complex_omega(cogiro):
    """Hysteretic damping: the lumped rung's damped roots are found by the same function as
    the closed form's, and the first one agrees to the rungs' frequency gap."""
    rob = dataclasses.replace(cogiro.robot, cables=dataclasses.replace(cogiro.robot.cables[0],
                                                                        loss_factor=0.02))
    eq = rob.equilibrium(pose=cogiro.pose)
    a = ds.damped_modes(ds.build_model(eq, "dsm"), 1)
    b = ds.damped_modes(ds.build_model(eq, "lumped", segments=10), 1)
    assert np.isfinite(a.omega[0]) and np.isfinite(b.omega[0])
    assert a.damping_ratio[0] > 0 and b.damping_ratio[0] > 0
    assert abs(b.omega[0] / a.omega[0] - 1) < 4e-3
    np.testing.assert_allclose(b.damping_ratio, a.damping_ratio, rtol=2e-2)


def test_build_model_rejects_options_of_other_rungs(cogiro_eq):
    with pytest.raises(InvalidParameterError, match="tension"):
        ds.build_model(cogiro_eq, "spring", tension="chord")
    with pytest.raises(InvalidParameterError, match="rung"):
        ds.build_model(cogiro_eq, "fem")
    with pytest.raises(InvalidParameterError, match="fmax_hz"):
        ds.build_model(cogiro_eq, "exact", tol=1e-9)


def test_options_each_rung_takes_are_listed_exactly(cogiro_eq):
    """The refusal lists the options the rung does take, in their order."""
    with pytest.raises(InvalidParameterError, match=re.escape(
            "options ['tol'] do not apply to rung 'exact' (it takes ['fmax_hz', 'order', "
            "'half_waves', 'cable_loss_factor', 'platform_damping_ratio'])")):
        ds.build_model(cogiro_eq, "exact", tol=1e-9)
    with pytest.raises(InvalidParameterError, match=re.escape(
            "options ['order'] do not apply to rung 'spring' (it takes none)")):
        ds.build_model(cogiro_eq, "spring", order=2)


def test_lumped_rung_has_30_segments_a_cable_by_default():
    """planar2 (2 cables, 2 free DOFs): 2 + 2 x 29 interior nodes x 3 = 176 DOFs."""
    m = ds.build_model(ds.load_scene("planar2").equilibrium(), "lumped")
    assert (m.n_free, m.n_dof) == (2, 2 + 2 * 29 * 3)
    np.testing.assert_array_equal(m.segments, [30, 30])


def test_lumped_rung_passes_its_equilibrium_options_and_checks_segments():
    """tol and max_iter reach the lumped equilibrium (one iteration to an unreachable tolerance
    fails, naming both); segments = 0 is refused by the ladder with its own message."""
    eq = ds.load_scene("planar2").equilibrium()
    with pytest.raises(ds.errors.ConvergenceError,
                       match=r"did not converge in 1 Newton iterations: .* > tol 1e-300$"):
        ds.build_model(eq, "lumped", segments=4, max_iter=1, tol=1e-300)
    with pytest.raises(InvalidParameterError, match=r"^segments must be >= 1, got 0$"):
        ds.build_model(eq, "lumped", segments=0)
