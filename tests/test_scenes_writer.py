"""Scene files written from a robot (dynstiff/scenes/writer.py): a written scene reads back
to the same robot and pose bit for bit; CASPR import gives a Scene at q_initial."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.io.caspr import InertiaConventionWarning
from dynstiff.scenes import import_caspr, write_scene

DATA = Path(__file__).parent / "data" / "caspr"


def assert_same_robot(a, b):
    for f in ("anchors", "attachments"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f))
    assert a.cables == b.cables and a.g == b.g and a.tension_limits == b.tension_limits
    for f in ("mass", "center_of_mass", "inertia"):
        np.testing.assert_array_equal(getattr(a.platform, f), getattr(b.platform, f))
    assert a.platform.free_dofs == b.platform.free_dofs


@pytest.mark.parametrize("name", ["cogiro", "planar2", "fourcable"])
def test_written_scene_reads_back_bit_for_bit(tmp_path, name):
    sc = ds.load_scene(name)
    pose = sc.pose or ds.Pose([0.1, -0.2, 1.0], [0.01, 0.02, 1 / 3])
    path = write_scene(tmp_path / "s.toml", sc.robot, pose, description="round trip",
                       comments=["a comment"])
    back = ds.load_scene(path)
    assert_same_robot(back.robot, sc.robot)
    assert back.pose == pose and back.description == "round trip"


def test_cables_that_differ_are_written_one_by_one(tmp_path):
    r = ds.load_scene("cogiro").robot
    cables = [replace(c, EA=c.EA * (1 + k / 10), loss_factor=0.01 * k)
              for k, c in enumerate(r.cables)]
    r2 = replace(r, cables=cables, tension_limits=(10.0, np.inf))
    back = ds.load_scene(write_scene(tmp_path / "s.toml", r2)).robot
    assert_same_robot(back, r2)


def test_import_caspr_scene_is_at_q_initial():
    cable = ds.load_scene("cogiro").robot.cables[0]
    with pytest.warns(InertiaConventionWarning):
        sc = import_caspr(DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml", cable)
    assert sc.pose == ds.Pose([0.0, 0.0, 2.0])
    assert "products" in sc.description and "original" in sc.description
    with pytest.raises(ds.InvalidParameterError, match="cable must be a dynstiff.Cable"):
        import_caspr(DATA / "CoGiRo_bodies.xml", DATA / "CoGiRo_cables.xml", 1e5)
