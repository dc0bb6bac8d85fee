"""Checks of a workspace map before its first pose (dynstiff/maps/guards.py): model options
named with their value (a bool is not a number), orientations checked and never reshaped,
the size refused beyond the limit or the machine's memory with the option to change, and
the estimate line."""

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.maps.guards import (
    MAX_POSES,
    check_model_options,
    check_orientations,
    check_size,
    estimate_text,
    map_bytes,
)


@pytest.mark.parametrize("rung, options", [
    ("dsm", {}), ("dsm", {"tension": "chord", "chordwise_inertia": False, "guard_rtol": None,
                          "cable_loss_factor": 0.0, "platform_damping_ratio": 0.99}),
    ("exact", {"fmax_hz": 12.5, "order": 3, "half_waves": 2}),
    ("lumped", {"tol": 1e-9, "max_iter": 50, "segments": [3, 4]}),
])
def test_good_model_options_pass(rung, options):
    check_model_options(rung, options)


@pytest.mark.parametrize("rung, options, match", [
    ("exact", {"fmax_hz": -1}, "fmax_hz must be > 0, got -1"),
    ("exact", {"fmax_hz": np.inf}, "fmax_hz must be finite"),
    ("exact", {"fmax_hz": "10"}, "fmax_hz must be a number > 0, got '10'"),
    ("exact", {"order": 2.0}, "order must be an integer >= 1, got 2.0"),
    ("exact", {"half_waves": np.bool_(True)}, "half_waves must be an integer"),
    ("dsm", {"guard_rtol": False}, "guard_rtol must be a number"),
    ("dsm", {"platform_damping_ratio": 1.0}, r"platform_damping_ratio must be .*\[0, 1\)"),
    ("dsm", {"cable_loss_factor": -0.01}, r"cable_loss_factor must be .*\[0, 1\)"),
    ("dsm", {"tension": "max"}, "tension must be 'mean' or 'chord'"),
    ("dsm", {"chordwise_inertia": 1}, "chordwise_inertia must be True or False"),
    ("lumped", {"segments": [3, 0]}, "segments must be an integer >= 1, got 0"),
    ("spring", {"tol": 1e-9}, r"\['tol'\] do not apply to rung 'spring' \(it takes none\)"),
])
def test_bad_model_options_are_named(rung, options, match):
    with pytest.raises(InvalidParameterError, match=match):
        check_model_options(rung, options)


def test_orientations_are_checked_not_reshaped():
    assert check_orientations([0, 0, 0.1]).shape == (1, 3)
    np.testing.assert_array_equal(check_orientations([[0, 0, 0], [0.1, 0, 0]])[1], [0.1, 0, 0])
    for bad, shape in ((np.zeros((3, 2)), r"\(3, 2\)"), (np.zeros((0, 3)), r"\(0, 3\)"),
                       (np.zeros(6), r"\(6,\)")):
        with pytest.raises(InvalidParameterError, match=shape):
            check_orientations(bad)
    with pytest.raises(InvalidParameterError, match="finite"):
        check_orientations([[0, np.nan, 0]])
    with pytest.raises(InvalidParameterError, match="rotation vectors"):
        check_orientations([["a", 0, 0]])


def test_size_guard_counts_memory_and_names_what_to_change():
    per_pose = map_bytes(1, 8, 20, 7)
    assert 1000 < per_pose < 3000                     # a pose's arrays, three copies
    assert check_size(MAX_POSES, 8, 20, 7) == MAX_POSES * per_pose
    with pytest.raises(InvalidParameterError, match=r"^box b with step 1 m gives 200,001 "
                                                    r"poses, more than max_poses=200,000.*"
                                                    r"raise step= \(--step\)"):
        check_size(MAX_POSES + 1, 8, 20, 7, what="box b with step 1 m")
    with pytest.raises(InvalidParameterError, match="give fewer poses.*--max-poses"):
        check_size(11, 8, 20, 7, max_poses=10, what="11 poses")
    with pytest.raises(InvalidParameterError, match=r"10,000,000,000 poses, which need about "
                                                    r"[0-9.e+]+ GiB of memory \(this machine"):
        check_size(10**10, 8, 20, 7, max_poses=None)      # never a MemoryError
    with pytest.raises(InvalidParameterError, match="max_poses must be an integer"):
        check_size(1, 8, 20, 7, max_poses=True)


def test_estimate_line():
    assert estimate_text(1_000_000, 0.012, 2**31) == (
        "workspace: 1,000,000 poses, about 2 GiB, about 3.3 h (12 ms a pose in a sample)")
    assert "about 50 s on 4 workers" in estimate_text(1000, 0.2, 1, workers=4)


def test_the_memory_estimate_is_a_maps_own_arrays_three_times():
    """map_bytes per pose, less its 120 bytes of reason, is the bytes a pose takes in a real
    map (every numeric and boolean variable, and the 6 floats of its pose vector), for two
    sizes of cables, modes and checks; three copies of it."""
    import dynstiff as ds
    xr = pytest.importorskip("xarray")
    for scene, n_modes in (("cogiro", 4), ("planar2", 3)):
        robot = ds.load_scene(scene).robot
        c = robot.anchors.mean(axis=0)
        box = (c[0] - 1, c[0] + 1, c[1], c[1], c[2] - 8, c[2] - 8)
        m = ds.workspace(robot, box=box, step=1.0, n_modes=n_modes)
        assert isinstance(m, xr.Dataset)
        n = int(m["feasible"].size)
        arrays = sum(v.nbytes for v in m.data_vars.values() if v.dtype.kind in "fb")
        per_pose = arrays / n + 6 * 8
        assert map_bytes(n, robot.n_cables, n_modes, m.sizes["check"]) == \
            3 * n * (per_pose + 120)


def test_counts_start_at_one_and_fractions_are_numbers():
    check_model_options("lumped", {"max_iter": 1, "segments": 1})
    with pytest.raises(InvalidParameterError, match="max_iter must be an integer >= 1, got 0"):
        check_model_options("lumped", {"max_iter": 0})
    with pytest.raises(InvalidParameterError, match=r"must be a number in \[0, 1\), got '0.1'"):
        check_model_options("dsm", {"platform_damping_ratio": "0.1"})


def test_the_size_refusal_says_what_it_counted():
    with pytest.raises(InvalidParameterError, match="^the map gives 11 poses, more than "
                                                    "max_poses=10 .*: give fewer poses or "
                                                    "parameter values, or raise max_poses="):
        check_size(11, 8, 20, 7, max_poses=10)


@pytest.mark.parametrize("seconds, span", [(119.0, "119 s"), (120.0, "2.0 min"),
                                           (7199.0, "120.0 min"), (7200.0, "2.0 h")])
def test_the_estimate_changes_unit_at_two_minutes_and_two_hours(seconds, span):
    assert estimate_text(1000, seconds / 1000, 2**30) == (
        f"workspace: 1,000 poses, about 1 GiB, about {span} ({seconds:.0f} ms a pose in a "
        f"sample)")
    assert "on 2 workers" in estimate_text(1000, seconds / 500, 1, workers=2)
    assert " on " not in estimate_text(1000, seconds / 1000, 1, workers=1)


def test_memory_beyond_half_the_machine_is_refused(monkeypatch):
    from dynstiff.maps import guards
    per = map_bytes(1, 8, 20, 7)
    monkeypatch.setattr(guards, "_physical_memory", lambda: 1000 * per)
    assert check_size(500, 8, 20, 7, max_poses=None) == 500 * per
    with pytest.raises(InvalidParameterError, match="501 poses, which need about"):
        check_size(501, 8, 20, 7, max_poses=None)
    assert estimate_text(10, 3600.0, 1).split("about ")[2].startswith("10.0 h")
    # hours of 3600 s: 1000 h would read 999.7 h with one second more to the hour
    assert estimate_text(1000, 3600.0, 1).split("about ")[2].startswith("1000.0 h")
