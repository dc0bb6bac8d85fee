"""Built-in scenes and the TOML loader (dynstiff/scenes/)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError


def test_scene_equilibrium_at_another_pose_or_lengths():
    """pose= and unstretched_lengths= given to Scene.equilibrium override the scene's own
    (they used to clash with it: "multiple values for keyword argument 'pose'")."""
    scene = ds.load_scene("cogiro")
    own = scene.equilibrium()
    moved = scene.equilibrium(pose=[0.5, 0.2, 1.2])
    np.testing.assert_allclose(moved.pose.position, [0.5, 0.2, 1.2])
    assert moved.pose == scene.robot.equilibrium(pose=[0.5, 0.2, 1.2]).pose
    fwd = scene.equilibrium(unstretched_lengths=own.unstretched_lengths)
    np.testing.assert_allclose(fwd.pose.position, own.pose.position, atol=1e-8)
    with pytest.raises(InvalidParameterError, match="at most one"):
        scene.equilibrium(pose=[0, 0, 1], unstretched_lengths=own.unstretched_lengths)


def test_scene_gravity_and_dofs_default_to_the_package_constants(tmp_path):
    text = (ds.scenes.loader.SCENE_DIR / "simulator.toml").read_text()
    lines = [ln for ln in text.splitlines()
             if not ln.strip().startswith(("g =", "free_dofs"))]
    p = tmp_path / "nog.toml"
    p.write_text("\n".join(lines) + "\n")
    rob = ds.load_scene(p).robot
    assert rob.g == ds.STANDARD_GRAVITY
    assert rob.platform.free_dofs == ds.platform.DOF_NAMES
