"""The lumped rung's sensitivities (dynstiff/analyses/sensitivity_lumped.py, theory.md §16.3):
the platform's weight in the derivative of the geometric stiffness, and the loss factor's
damping derivative against the closed form's."""

import numpy as np
from test_analyses_sensitivity import assert_matches, central_difference

import dynstiff as ds
from dynstiff.analyses.sensitivity import frequency_sensitivities


def test_the_platforms_mass_centre_and_rotation_match_central_differences(cogiro):
    """The platform's mass, its centre of mass and a rotation of the pose move its weight's
    share of the geometric stiffness (a gravity vector with a horizontal component changed
    these by 4 to 7 %); against central differences of lumped models built at the perturbed
    parameters, to 1e-5 of each parameter's largest effect."""
    rob = cogiro.robot
    eq = rob.equilibrium(pose=cogiro.pose, tol=1e-12)
    model = ds.build_model(eq, "lumped", segments=4, tol=1e-13)
    s = frequency_sensitivities(model, ["mass", "com_z", "pose_rx"], n_modes=4)
    for j, name in enumerate(s.parameters):
        fd = central_difference(rob, eq.pose, name, "lumped", 4, segments=4, tol=1e-13)
        assert_matches(s, fd, j, rtol=1e-5)


def test_the_loss_factor_raises_the_damping_as_on_the_closed_form(cogiro):
    """d zeta / d eta of CoGiRo's first three modes on the lumped rung: positive, and
    converging to the closed form's as the chains are refined (4 and 8 segments: within 14 %
    and 3 %, the error falling); a sign error in the loss factor's direction (EA / (1 + i h)
    for EA (1 + i h)) turns them negative."""
    eq = cogiro.robot.equilibrium(pose=cogiro.pose, tol=1e-12)
    ref = frequency_sensitivities(ds.FrequencyModel(eq), ["loss_factor"],
                                  n_modes=3).damping_derivative[:, 0]
    err = []
    for n in (4, 8):
        model = ds.build_model(eq, "lumped", segments=n, tol=1e-13)
        z = frequency_sensitivities(model, ["loss_factor"], n_modes=3).damping_derivative[:, 0]
        assert np.all(z > 0)
        err.append(np.abs(z / ref - 1).max())
    assert err[0] < 0.14 and err[1] < 0.03 and err[1] < err[0] / 3
