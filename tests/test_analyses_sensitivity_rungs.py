"""The continuous rungs' quadratic forms x^T K(omega) z (dynstiff/analyses/sensitivity_rungs.py,
theory.md §16.3) against independent references: at real inputs the model's own dynamic
stiffness (both tensions of the closed form, the exact rung down to omega = 0, where it is
the massless stiffness), the complex step in the dynamic EA factor against the imaginary part
of an exact model with a small loss factor, and the complex step in one primitive against
central differences of the forms at real inputs."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.sensitivity_kernels import CS_STEP, perturbed_primitives
from dynstiff.analyses.sensitivity_parameters import equilibrium_with
from dynstiff.analyses.sensitivity_rungs import exact_fields, forms
from dynstiff.analyses.sensitivity_statics import LinearisedEquilibrium


@pytest.fixture(scope="module")
def lin(cogiro_eq):
    return LinearisedEquilibrium(cogiro_eq)


@pytest.fixture(scope="module")
def motions():
    """Two unrelated platform motions per frequency, (3, 6) each."""
    rng = np.random.default_rng(7)
    return rng.standard_normal((3, 6)), rng.standard_normal((3, 6))


def at_base(lin):
    """The unperturbed unknowns and primitives as a batch of one, complex."""
    return lin.y[None].astype(complex), perturbed_primitives(lin.P, [{}])


def model_form(model, w, X, Z):
    """x_k^T K(omega_k) z_k from the model's own dynamic stiffness."""
    return np.einsum("mi,mij,mj->m", X, model.dynamic_stiffness(w), Z)


@pytest.mark.parametrize("tension", ["mean", "chord"])
def test_closed_form_at_real_inputs_is_the_models_dynamic_stiffness(cogiro_eq, lin, motions,
                                                                    tension):
    """The closed form rebuilt from each catenary with the model's tension choice (mean
    tension, or H / cos(theta) along the chord): the two differ by ~1e-6 relative."""
    X, Z = motions
    w = np.array([3.0, 7.0, 12.0])
    model = ds.FrequencyModel(cogiro_eq, tension=tension)
    Y, P = at_base(lin)
    f = forms(model, lin, Y, P, w, X, Z)
    assert f.shape == (1, 3)
    np.testing.assert_allclose(f[0].real, model_form(model, w, X, Z), rtol=1e-12)
    np.testing.assert_array_equal(f[0].imag, 0.0)


def test_exact_form_at_real_inputs_is_the_models_down_to_the_static_stiffness(cogiro_eq, lin,
                                                                             motions):
    """The exact rung at real inputs: the model's K(omega), and at omega = 0 (the dynamic
    part S(0) - S(0) vanishes) the massless stiffness K(0)."""
    X, Z = motions
    model = ds.build_model(cogiro_eq, "exact", fmax_hz=6.0)
    w = np.array([0.0, 7.0, 30.0])
    Y, P = at_base(lin)
    f = forms(model, lin, Y, P, w, X, Z, (exact_fields(model, w, X), exact_fields(model, w, Z)))
    np.testing.assert_allclose(f[0].real, model_form(model, w, X, Z), rtol=1e-12)
    K0 = model.massless_stiffness()
    np.testing.assert_allclose(f[0, 0].real, X[0] @ K0 @ Z[0], rtol=1e-12)


def test_exact_forms_derivative_in_the_dynamic_ea_is_that_of_a_loss_factor(cogiro, cogiro_eq,
                                                                          lin, motions):
    """A loss factor eta makes the cables' dynamic (axial) EA complex, EA (1 + i eta): the
    exact model built with a small eta has Im x^T K z / eta = d(x^T K z)/da + O(eta^2), a
    the factor on the dynamic EA, which the forms' complex step along ``axial`` gives (the
    static part's flexibility with the axial term scaled, and the cables' interior energy)."""
    X, Z = motions
    model = ds.build_model(cogiro_eq, "exact", fmax_hz=6.0)
    w = np.array([3.0, 12.0, 30.0])
    n = cogiro.robot.n_cables
    Y, P = lin.perturbed([{"axial": np.ones(n)}], np.zeros((1, lin.y.size)))
    fields = (exact_fields(model, w, X), exact_fields(model, w, Z))
    A = np.imag(forms(model, lin, Y, P, w, X, Z, fields)[0]) / CS_STEP
    eta = 1e-4
    lossy = ds.build_model(equilibrium_with(cogiro.robot, cogiro_eq.pose, ["loss_factor"],
                                            [eta]), "exact", fmax_hz=6.0)
    assert lossy.damped
    ref = model_form(lossy, w, X, Z).imag / eta
    np.testing.assert_allclose(A, ref, rtol=1e-9)
    assert np.all(np.abs(A) > 1e-2 * np.abs(model_form(model, w, X, Z)))


def test_a_complex_anchor_with_real_cable_primitives_keeps_its_derivative(cogiro_eq, lin,
                                                                         motions):
    """The forms are analytic in each primitive alone: with the unknowns and the cables' EA
    and mass real (real flexibilities) and only the anchors complex, the catenary rung's
    complex step is the central difference (Richardson) of the forms at real anchors."""
    X, Z = motions
    model = ds.build_model(cogiro_eq, "catenary")
    w = np.array([2.0, 7.0, 12.0])
    d = np.random.default_rng(3).standard_normal((cogiro_eq.robot.n_cables, 3))
    Y = lin.y[None]

    def form(s):
        P = {k: np.asarray(v)[None] for k, v in lin.P.items()}
        P["anchors"] = P["anchors"] + s * d
        return forms(model, lin, Y, P, w, X, Z)[0]

    A = np.imag(form(1j * CS_STEP)) / CS_STEP

    def cd(s):
        return np.real(form(s) - form(-s)) / (2 * s)
    fd = (4 * cd(5e-4) - cd(1e-3)) / 3
    np.testing.assert_allclose(A, fd, rtol=1e-8)
    assert np.all(np.abs(A) > 1e-3 * np.abs(form(0.0)))
