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
