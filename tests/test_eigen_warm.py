"""Natural frequencies started from a neighbouring pose (dynstiff/eigen_warm.py, docs/theory.md
§13.4): equal to the cold Wittrick-Williams search of dynstiff.eigenfrequencies (1e-11), with
and without a start, and a start that the counts do not certify is not used."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff import eigen_warm
from dynstiff.eigen_warm import eigenfrequencies_near


@pytest.fixture(scope="module")
def robot():
    return ds.load_scene("cogiro").robot


def model(robot, position):
    return ds.build_model(robot.equilibrium(pose=position), "dsm")


@pytest.mark.parametrize("position", [(0.0, 0.0, 1.0), (3.0, 2.0, 2.5), (5.0, 3.0, 1.0)])
def test_cold_equals_eigenfrequencies(robot, position):
    m = model(robot, position)
    np.testing.assert_allclose(eigenfrequencies_near(m, 25), ds.eigenfrequencies(m, 25),
                               rtol=1e-11)


def test_start_from_a_neighbouring_pose_gives_the_same_roots_without_rebracketing(
        robot, monkeypatch):
    """1 cm away, the previous pose's roots certify the brackets: no cold bracketing runs,
    and the roots equal the cold search."""
    prev = ds.eigenfrequencies(model(robot, (0.0, 0.0, 1.0)), 20)
    m = model(robot, (0.01, 0.005, 1.0))

    def no_cold(*args):
        raise AssertionError("cold bracketing ran")
    monkeypatch.setattr(eigen_warm, "_brackets", no_cold)
    np.testing.assert_allclose(eigenfrequencies_near(m, 20, prev), ds.eigenfrequencies(m, 20),
                               rtol=1e-11)


def test_a_start_the_counts_reject_falls_back_to_the_cold_search(robot):
    """Roots of a far pose (and a start with the wrong length or order) are not trusted."""
    m = model(robot, (0.0, 0.0, 1.0))
    ref = ds.eigenfrequencies(m, 12)
    far = ds.eigenfrequencies(model(robot, (4.0, -3.0, 3.0)), 12)
    for start in (far, far[:5], far[::-1], 0.5 * ref):
        np.testing.assert_allclose(eigenfrequencies_near(m, 12, start), ref, rtol=1e-11)
