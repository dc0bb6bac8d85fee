"""Natural frequencies started from a neighbouring pose (dynstiff/eigen_warm.py, docs/theory.md
§13.4): equal to the cold Wittrick-Williams search of dynstiff.eigenfrequencies (1e-11), with
and without a start, with fewer counts from a near start and every root from a poor one."""

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


def test_start_from_a_neighbouring_pose_gives_the_same_roots_with_fewer_counts(
        robot, monkeypatch):
    """10 cm away, the previous pose's roots seed the brackets: the roots equal the cold
    search (1e-11) and the count is evaluated fewer times (each count call is one K(omega)
    stack, eigenvalues and cable-mode counts)."""
    prev = ds.eigenfrequencies(model(robot, (0.0, 0.0, 1.0)), 20)
    m = model(robot, (0.1, 0.05, 1.0))
    calls = []

    def counting(model_, omega):
        calls.append(np.size(omega))
        return ds.mode_count(model_, omega)
    monkeypatch.setattr(eigen_warm, "mode_count", counting)
    cold = eigenfrequencies_near(m, 20)
    n_cold = len(calls)
    calls.clear()
    warm = eigenfrequencies_near(m, 20, prev)
    np.testing.assert_allclose(warm, ds.eigenfrequencies(m, 20), rtol=1e-11)
    np.testing.assert_allclose(cold, warm, rtol=1e-11)
    assert len(calls) < 0.7 * n_cold


def test_poor_seeds_still_give_every_root(robot):
    """Seeds from a far pose, too few, in reverse order or half the true roots only seed
    brackets that the counts then refine: the roots are still the cold search's."""
    m = model(robot, (0.0, 0.0, 1.0))
    ref = ds.eigenfrequencies(m, 12)
    far = ds.eigenfrequencies(model(robot, (4.0, -3.0, 3.0)), 12)
    for start in (far, far[:5], far[::-1], 0.5 * ref):
        np.testing.assert_allclose(eigenfrequencies_near(m, 12, start), ref, rtol=1e-11)
