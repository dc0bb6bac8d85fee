"""The closed form's way to the compiled kernels (dynstiff/models/dsm_compiled.py): which path
``stiffness_and_count`` takes for each model (the compiled kernel for the undamped closed form,
the model's own ``dynamic_stiffness_and_count`` where it has one, else ``dynamic_stiffness``
and ``cable_mode_count``), each checked against the numpy path; and the reduced symmetric
assembly map, which rebuilds K from the cables' coefficients as the full map does."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff import compiled
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.dsm_compiled import stiffness_and_count, symmetric_assembly

needs_numba = pytest.mark.skipif(compiled.load("dsm") is None, reason="numba not installed")
OMEGA = np.linspace(0.5, 60.0, 7)                    # [rad/s], across several cable modes


def _refuse(*args, **kwargs):
    raise AssertionError("the numpy path was taken")


@needs_numba
def test_the_undamped_closed_form_takes_the_compiled_kernel(cogiro_eq, monkeypatch):
    """One call of the kernel, not the model's numpy methods; its K agrees with theirs to
    tens of eps of the largest entry and its count exactly."""
    m = ds.FrequencyModel(cogiro_eq)
    K_ref, J_ref = m.dynamic_stiffness_and_count(OMEGA)
    assert J_ref[-1] > J_ref[0]                      # the band crosses cable modes
    for name in ("dynamic_stiffness_and_count", "dynamic_stiffness", "cable_mode_count"):
        monkeypatch.setattr(FrequencyModel, name, _refuse)
    K, J = stiffness_and_count(m, OMEGA)
    np.testing.assert_array_equal(J, J_ref)
    np.testing.assert_allclose(K, K_ref, rtol=0, atol=50 * np.finfo(float).eps
                               * np.abs(K_ref).max())


def test_a_damped_closed_form_gives_the_undamped_stiffness_and_count(cogiro_eq):
    """A damped model goes to its own ``dynamic_stiffness_and_count``: the undamped model's
    real K and count (what the Wittrick-Williams count needs), not the damped complex K."""
    damped = ds.FrequencyModel(cogiro_eq, cable_loss_factor=0.02)
    assert np.iscomplexobj(damped.dynamic_stiffness(OMEGA[:1]))
    K, J = stiffness_and_count(damped, OMEGA)
    K_ref, J_ref = ds.FrequencyModel(cogiro_eq).dynamic_stiffness_and_count(OMEGA)
    assert not np.iscomplexobj(K)
    np.testing.assert_array_equal(K, K_ref)
    np.testing.assert_array_equal(J, J_ref)


def test_a_model_without_the_joint_method_gives_its_stiffness_and_count(cogiro_eq):
    """The massless catenary rung has no ``dynamic_stiffness_and_count``: its own K(omega)
    and cable count."""
    m = ds.build_model(cogiro_eq, "catenary")
    assert not hasattr(m, "dynamic_stiffness_and_count")
    K, J = stiffness_and_count(m, OMEGA)
    np.testing.assert_array_equal(K, m.dynamic_stiffness(OMEGA))
    np.testing.assert_array_equal(J, m.cable_mode_count(OMEGA))


def test_the_symmetric_map_rebuilds_the_stiffness_of_the_full_map(cogiro_model):
    """K = sum of coefficient x dyad with the full map (5 dyads per cable, every entry), and
    the same K's upper triangle with the reduced map (uv + vu summed, 4 dyads)."""
    m = cogiro_model
    n, nf = m.robot.n_cables, m.n_free
    rng = np.random.default_rng(5)
    c = rng.standard_normal((n, 4))                   # uu, uv (= vu), vv, ww coefficients
    full = np.stack([c[:, 0], c[:, 1], c[:, 1], c[:, 2], c[:, 3]], axis=1).ravel()
    K = (full @ m.assembly_map).reshape(nf, nf)
    red = symmetric_assembly(m.assembly_map, nf)
    assert red.shape == (4 * n, nf * (nf + 1) // 2) and red.flags.c_contiguous
    iu = np.triu_indices(nf)
    np.testing.assert_allclose(c.ravel() @ red, K[iu], rtol=1e-14, atol=1e-14 * np.abs(K).max())


def test_the_symmetric_map_is_computed_once_and_shared_with_damped_copies(cogiro_eq):
    """The map is geometry only: one read-only array per model, the same object for the
    damped copies that share the model's cables (``_with_model_damping``, a map's check)."""
    from dynstiff.models.dsm_compiled import _symmetric_assembly_of
    m = ds.FrequencyModel(cogiro_eq)
    first = _symmetric_assembly_of(m)
    assert _symmetric_assembly_of(m) is first and not first.flags.writeable
    assert _symmetric_assembly_of(m._with_model_damping(0.01, 0.0)) is first


def test_the_kernel_arguments_are_computed_once_per_model(cogiro_eq):
    """The model is immutable: its kernels' arguments are built once (the same tuple again),
    real contiguous arrays of one value per cable."""
    from dynstiff.models.dsm_compiled import compiled_arguments
    m = ds.FrequencyModel(cogiro_eq)
    args = compiled_arguments(m)
    assert compiled_arguments(m) is args
    n = m.robot.n_cables
    for a in args[:6]:                                     # L, m, T, lambda^2, alpha, K0
        assert a.shape == (n,) and a.dtype == np.float64 and a.flags.c_contiguous
