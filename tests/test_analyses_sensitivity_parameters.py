"""Parameter names and their expansion (dynstiff/analyses/sensitivity_parameters.py,
theory.md §16.2): every name of the module table, the wildcards and the per-cable groups,
the unit, value and kind ("frequency" / "damping") of each parameter, the default hold, the
tension reference broadcast, and the refusals (no modes are computed)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.sensitivity_parameters import expand_parameters, parameter_names
from dynstiff.errors import InvalidParameterError


def names(parameters, scene, **options):
    return [p.name for p in expand_parameters(parameters, scene.robot, scene.pose, **options)]


def test_parameter_names_follow_the_table():
    """Every row of the module table, wildcards expanded, for two cables."""
    assert parameter_names(2) == (
        "EA", "mass_per_length", "loss_factor",
        "EA_0", "EA_1", "mass_per_length_0", "mass_per_length_1",
        "loss_factor_0", "loss_factor_1",
        "mass", "inertia",
        "inertia_xx", "inertia_yy", "inertia_zz", "inertia_xy", "inertia_xz", "inertia_yz",
        "com_x", "com_y", "com_z",
        "pose_x", "pose_y", "pose_z", "pose_rx", "pose_ry", "pose_rz",
        "anchor_0_x", "anchor_0_y", "anchor_0_z", "anchor_1_x", "anchor_1_y", "anchor_1_z",
        "attachment_0_x", "attachment_0_y", "attachment_0_z",
        "attachment_1_x", "attachment_1_y", "attachment_1_z",
        "t_min", "t_max", "t_ref_0", "t_ref_1", "L0_0", "L0_1")


def test_every_name_expands_to_itself(cogiro):
    """Each listed name is accepted at a fixed pose (the fixed-lengths ones at fixed
    lengths), in the order given."""
    n = cogiro.robot.n_cables
    all_names = parameter_names(n)
    at_pose = [p for p in all_names if not p.startswith("L0_")]
    assert names(at_pose, cogiro, tension_reference=500.0) == at_pose
    at_lengths = [p for p in all_names
                  if not p.startswith(("pose_", "t_min", "t_max", "t_ref_"))]
    assert names(at_lengths, cogiro, hold="lengths") == at_lengths


def test_cable_wildcard_appends_one_name_per_cable(cogiro):
    """``EA_*`` gives EA_0 ... EA_7 in place: after the names before it, before those after
    it."""
    ea = [f"EA_{i}" for i in range(8)]
    assert names(["mass", "EA_*"], cogiro) == ["mass"] + ea
    assert names(["EA_*", "com_x"], cogiro) == ea + ["com_x"]


def test_anchor_groups(cogiro):
    """``anchor_*`` gives the three coordinates of every anchor, ``attachment_i`` those of
    cable i; the names after a group are kept."""
    assert names(["anchor_*"], cogiro) == [f"anchor_{i}_{a}" for i in range(8) for a in "xyz"]
    assert names(["attachment_1", "mass"], cogiro) == [
        "attachment_1_x", "attachment_1_y", "attachment_1_z", "mass"]


def test_single_string_is_one_parameter(cogiro):
    assert names("mass", cogiro) == ["mass"]
    assert names("EA_*", cogiro) == [f"EA_{i}" for i in range(8)]


def test_units_values_and_kinds(cogiro):
    """The unit column of the table; the loss factor (all or one cable) moves the damping
    ratios, every other parameter the frequencies."""
    rob = cogiro.robot
    got = {p.name: p for p in expand_parameters(
        ["EA", "mass_per_length", "loss_factor", "EA_2", "mass_per_length_1",
         "loss_factor_3", "mass", "inertia", "inertia_xy", "com_z", "pose_y", "pose_ry",
         "anchor_4_z", "attachment_5_x", "t_min", "t_max"], rob, cogiro.pose)}
    units = {"EA": "N", "mass_per_length": "kg/m", "loss_factor": "-", "EA_2": "N",
             "mass_per_length_1": "kg/m", "loss_factor_3": "-", "mass": "kg",
             "inertia": "-", "inertia_xy": "kg m^2", "com_z": "m", "pose_y": "m",
             "pose_ry": "rad", "anchor_4_z": "m", "attachment_5_x": "m", "t_min": "N",
             "t_max": "N"}
    assert {k: p.unit for k, p in got.items()} == units
    assert {k for k, p in got.items() if p.kind == "damping"} == {"loss_factor",
                                                                   "loss_factor_3"}
    assert {p.kind for k, p in got.items() if k not in ("loss_factor", "loss_factor_3")} \
        == {"frequency"}
    assert got["inertia_xy"].value == rob.platform.inertia[0, 1]
    assert got["com_z"].value == rob.platform.center_of_mass[2]
    assert got["anchor_4_z"].value == rob.anchors[4, 2]
    assert (got["t_min"].value, got["t_max"].value) == tuple(rob.tension_limits)
    np.testing.assert_array_equal(got["pose_ry"].direction["rotvec"], [0.0, 1.0, 0.0])
    np.testing.assert_array_equal(got["pose_y"].direction["position"], [0.0, 1.0, 0.0])
    d = np.zeros((8, 3))
    d[4, 2] = 1.0
    np.testing.assert_array_equal(got["anchor_4_z"].direction["anchors"], d)


def test_default_hold_is_the_pose(cogiro):
    """Without ``hold`` the pose is fixed: a pose coordinate is a parameter, an unstretched
    length is refused (it needs hold="lengths")."""
    assert names(["pose_x"], cogiro) == ["pose_x"]
    with pytest.raises(InvalidParameterError, match="'L0_0' applies at fixed lengths"):
        names(["L0_0"], cogiro)
    L0 = np.arange(1.0, 9.0)
    p, = expand_parameters(["L0_3"], cogiro.robot, cogiro.pose, hold="lengths",
                           unstretched_lengths=L0)
    assert (p.name, p.value, p.unit) == ("L0_3", 4.0, "m")


def test_names_must_be_strings(cogiro):
    with pytest.raises(InvalidParameterError, match=r"parameters must be names \(str\), got 3"):
        names(["mass", 3], cogiro)


def test_tension_reference_broadcast(cogiro):
    """A scalar reference is every cable's; t_ref_i is cable i's reference in N."""
    p, = expand_parameters(["t_ref_5"], cogiro.robot, cogiro.pose, tension_reference=500)
    assert (p.value, p.unit) == (500.0, "N")
    t_ref = np.arange(8) * 100.0 + 300.0
    p, = expand_parameters(["t_ref_5"], cogiro.robot, cogiro.pose, tension_reference=t_ref)
    assert p.value == 800.0


def test_bad_requests_are_refused_before_the_search(cogiro, monkeypatch):
    """A bad tension_reference (complex, text, NaN, wrong length), hold or parameter name is a
    typed error naming the argument, raised before any eigenfrequency is searched."""
    import dynstiff.analyses.sensitivity as sens
    model = ds.FrequencyModel(cogiro.equilibrium())

    def no_search(*args, **kw):
        raise AssertionError("the search ran before the request was checked")
    monkeypatch.setattr(sens, "eigenfrequencies", no_search)
    for ref in ([1 + 1j] * 8, "abc", [np.nan] * 8, [100.0] * 3):
        with pytest.raises(InvalidParameterError, match="^tension_reference must be"):
            ds.frequency_sensitivities(model, ["t_ref_0"], n_modes=2, tension_reference=ref)
    with pytest.raises(InvalidParameterError, match="^hold must be 'pose' or 'lengths'"):
        ds.frequency_sensitivities(model, ["mass"], n_modes=2, hold="length")
    with pytest.raises(InvalidParameterError, match="'bogus' is not a parameter"):
        ds.frequency_sensitivities(model, ["bogus"], n_modes=2)
    with pytest.raises(InvalidParameterError, match="^tension_reference must be"):
        sens.sensitivities_at(model, np.array([1.0]), ["t_ref_0"], tension_reference="abc")
