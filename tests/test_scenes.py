"""Built-in scenes and the TOML loader (dynstiff/scenes/): every seed-paper robot loads by
name and from its file and balances; TOML errors name the key and the line."""

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
    # a scene of lengths only (no [pose]) balances at those lengths; one of neither refuses
    import dataclasses
    lengths = own.unstretched_lengths * 1.001
    by_lengths = dataclasses.replace(scene, pose=None, unstretched_lengths=lengths)
    eq = by_lengths.equilibrium()
    np.testing.assert_array_equal(eq.unstretched_lengths, lengths)
    assert eq.pose == scene.robot.equilibrium(unstretched_lengths=lengths).pose
    assert eq.pose.position[2] < own.pose.position[2] - 1e-3        # longer cables: lower
    with pytest.raises(ds.scenes.SceneError, match="names neither a \\[pose\\] nor"):
        dataclasses.replace(scene, pose=None, unstretched_lengths=None).equilibrium()


def test_scene_gravity_and_dofs_default_to_the_package_constants(tmp_path):
    text = (ds.scenes.loader.SCENE_DIR / "simulator.toml").read_text()
    lines = [ln for ln in text.splitlines()
             if not ln.strip().startswith(("g =", "free_dofs"))]
    p = tmp_path / "nog.toml"
    p.write_text("\n".join(lines) + "\n")
    rob = ds.load_scene(p).robot
    assert rob.g == ds.STANDARD_GRAVITY
    assert rob.platform.free_dofs == ds.robot.platform.DOF_NAMES


@pytest.mark.parametrize("edit,key,line", [
    (("mass = 91.058", "mas = 91.058"), "mas", 12),
    (("EA = 139486.7", "EA = -1.0"), "EA", None),
    (("[analysis]", "[analysys]"), "analysys", None),
    (("forbidden_band_hz = [0.0, 1.5]", "forbidden_band_hz = [1.5, 0.0]"), "forbidden_band_hz",
     None),
    (("mass = 91.058", 'mass = "91.058"'),
     r"bad.toml: line 12: mass in \[platform\] must be a number, got '91.058'$", 12),
    (('name = "cogiro"', "name = 7"), r"bad.toml: line 7: name in \[scene\] must be a string, "
                                      r"got 7$", 7),
    (("center_of_mass = [-0.034, -0.013, 0.264]", "center_of_mass = [-0.034, -0.013]"),
     r"center_of_mass in \[platform\] must be 3 numbers, got \[-0.034, -0.013\]$", 13),
    (('free_dofs = ["x", "y", "z", "rx", "ry", "rz"]', 'free_dofs = "xyz"'),
     r"free_dofs in \[platform\] must be a list of names, got 'xyz'$", 21),
    (("mass = 91.058", "mass = -1.0"),
     r"bad.toml: line 12: \[platform\] platform: mass must be > 0, got -1.0$", 12),
    (("mass = 91.058", "mass = 1" + "0" * 400),         # beyond a float: not a number
     r"bad.toml: line 12: mass in \[platform\] must be a number, got 10000.*0000$", 12),
])
def test_toml_errors_name_key_and_line(tmp_path, edit, key, line):
    text = (ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text().replace(*edit)
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(ds.SceneError, match=key) as exc:
        _ = ds.load_scene(p).robot
    if line is not None:
        assert f"line {line}" in str(exc.value)
    else:
        assert "line " in str(exc.value)


def test_inertia_of_another_type_and_a_missing_file_are_named(tmp_path):
    """An inertia that is text is named with the three forms it may take and its line; a
    missing file ending in .toml is a missing file, not an unknown built-in scene."""
    import re
    text = (ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text()
    p = tmp_path / "bad.toml"
    p.write_text(re.sub(r"inertia = \[\[.*?\]\]\n", 'inertia = "big"\n', text, flags=re.S))
    with pytest.raises(ds.SceneError, match=r"bad.toml: line 18: inertia in \[platform\] must "
                       r"be a number, 3 numbers or 3 rows of 3 numbers, got 'big'$"):
        ds.load_scene(p)
    with pytest.raises(FileNotFoundError, match="missing.toml"):
        ds.load_scene(tmp_path / "missing.toml")


def test_pose_section_of_lengths_only_or_absent(tmp_path):
    """[pose] may give unstretched_lengths instead of a position (forward statics at them);
    a file with no [pose] loads with neither, and its equilibrium asks for one."""
    import re
    text = (ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text()
    L0 = ds.load_scene("cogiro").equilibrium().unstretched_lengths * 1.001
    lengths = "[pose]\nunstretched_lengths = [" + ", ".join(repr(float(x)) for x in L0) + "]\n\n"
    p = tmp_path / "lengths.toml"
    p.write_text(re.sub(r"\[pose\].*?\n\n", lengths, text, flags=re.S))
    scene = ds.load_scene(p)
    assert scene.pose is None
    np.testing.assert_array_equal(scene.unstretched_lengths, L0)
    np.testing.assert_array_equal(scene.equilibrium().unstretched_lengths, L0)
    p = tmp_path / "none.toml"
    p.write_text(re.sub(r"\[pose\].*?\n\n", "", text, flags=re.S))
    scene = ds.load_scene(p)
    assert scene.pose is None and scene.unstretched_lengths is None
    with pytest.raises(ds.SceneError, match="names neither a \\[pose\\] nor"):
        scene.equilibrium()


def test_analysis_damping_and_trajectory_errors_name_their_line(tmp_path):
    """A count of zero in [analysis], a damping ratio of 2 and two trajectories of one name:
    each error names the key, the section and the line of the key."""
    text = (ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text()
    traj = ('[[trajectories]]\nname = "pick"\nlaw = "quintic"\ntimes = [0.0, 2.0]\n'
            "positions = [[0.0, 0.0, 1.0], [0.5, 0.0, 1.0]]\n")
    cases = [(text.replace("n_modes = 40", "n_modes = 0"), "n_modes = 0",
              "n_modes in [analysis] must be > 0, got 0"),
             (text + "\n[damping]\nplatform_ratio = 2.0\n", "[damping]",
              "[damping] damping: platform_ratio must be < 1, got 2.0"),
             (text + "\n" + traj + "\n" + traj, 'name = "pick"',
              "two trajectories named 'pick'")]
    for k, (bad, key_line, message) in enumerate(cases):
        p = tmp_path / f"bad{k}.toml"
        p.write_text(bad)
        lines = bad.splitlines()
        line = len(lines) - lines[::-1].index(key_line)          # its last occurrence
        with pytest.raises(ds.SceneError) as exc:
            ds.load_scene(p)
        assert str(exc.value) == f"{p}: line {line}: {message}"


def test_scene_name_and_description_default_to_the_file(tmp_path):
    """Without name and description in [scene], the name is the file's stem and the
    description empty."""
    text = (ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text()
    lines = [ln for ln in text.splitlines() if not ln.startswith(("name =", "description ="))]
    p = tmp_path / "my_robot.toml"
    p.write_text("\n".join(lines) + "\n")
    scene = ds.load_scene(p)
    assert (scene.name, scene.description) == ("my_robot", "")


def test_scene_loads_by_name_and_path(cogiro):
    assert "cogiro" in ds.list_scenes()
    r = ds.load_scene(ds.scenes.loader.SCENE_DIR / "cogiro.toml").robot
    np.testing.assert_array_equal(r.anchors, cogiro.robot.anchors)
    with pytest.raises(ds.SceneError, match="unknown scene"):
        ds.load_scene("nope")


# the closed form's robot-level bound warns on sixcable and fast (theory.md §11.6): not the subject
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
@pytest.mark.parametrize("name", ["cogiro", "planar2", "sixcable", "fourcable", "fast"])
def test_builtin_scenes_load_and_equilibrate(name):
    scene = ds.load_scene(name)
    same = ds.load_scene(ds.scenes.loader.SCENE_DIR / f"{name}.toml").robot
    np.testing.assert_array_equal(same.anchors, scene.robot.anchors)
    eq = scene.equilibrium()
    assert eq.residual < 1e-9
    lo, hi = scene.band_hz
    assert np.all(eq.tensions >= scene.robot.tension_limits[0])
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=hi)
    assert len(f) >= 1 and np.all(np.diff(f) >= 0)


SEED_SCENES = ("cogiro", "planar2", "sixcable", "fourcable", "pendulum", "simulator")


# the closed form's robot-level bound warns on sixcable and fast (theory.md §11.6): not the subject
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
@pytest.mark.parametrize("name", SEED_SCENES)
def test_every_seed_scene_loads_by_name_and_path_and_balances(name):
    """Every robot of the seed papers is a built-in scene: by name and from its TOML file
    it gives the same robot, and its pose is a static equilibrium with sane tensions."""
    assert name in ds.list_scenes()
    by_name = ds.load_scene(name)
    by_path = ds.load_scene(str(ds.scenes.loader.SCENE_DIR / f"{name}.toml"))
    np.testing.assert_array_equal(by_name.robot.anchors, by_path.robot.anchors)
    eq = by_name.equilibrium()
    assert eq.residual < 1e-8
    lo, hi = by_name.robot.tension_limits
    # the limits hold along each whole cable (sampled)
    s = np.linspace(0.0, 1.0, 2001)
    T = np.array([st.tension(s * st.unstretched_length) for st in eq.states])
    assert T.min() >= lo * (1 - 1e-9) and T.max() <= hi * (1 + 1e-9)
    if name == "simulator":
        # its lower cables run down to their anchors: the least tension is there, on t_min
        # (not at the platform end, which carries t_min + the hanging weight)
        assert eq.min_tensions.min() == pytest.approx(lo, rel=1e-9)
        assert eq.tensions.min() > lo + 10.0
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), 2)
    assert np.all(np.isfinite(f)) and np.all(f > 0)


@pytest.mark.parametrize("old, new, key", [
    ("anchor = [-15.0, 0.0, 0.0]", 'anchor = ["-15", "0", "12"]', "anchor"),
    ("anchor = [-15.0, 0.0, 0.0]", "anchor = [true, false, true]", "anchor"),
    ("anchor = [-15.0, 0.0, 0.0]", "anchor = [-15.0, 0.0]", "anchor"),
    ('free_dofs = ["x", "z"]', 'free_dofs = "xz"', "free_dofs"),
    ("mass = ", "mass = true #", "mass"),
    ("position = [0.0, 0.0, -10.0]",
     "position = [0.0, 0.0, -10.0]\nunstretched_lengths = [18.0, 18.0]",
     "unstretched_lengths"),
])
def test_toml_values_are_not_coerced(tmp_path, old, new, key):
    """Strings are not numbers, booleans are not numbers, a string is not a list of DOF
    names, and a pose is a position or lengths, not both: each is refused naming the key."""
    text = (ds.scenes.loader.SCENE_DIR / "planar2.toml").read_text()
    assert old in text
    p = tmp_path / "bad.toml"
    p.write_text(text.replace(old, new, 1))
    with pytest.raises(ds.SceneError, match=key) as exc:
        ds.load_scene(p)
    assert "line" in str(exc.value)


def test_folders_and_binary_files_are_not_scenes(tmp_path):
    with pytest.raises(ds.SceneError, match="is a folder"):
        ds.load_scene(tmp_path)
    p = tmp_path / "latin.toml"
    p.write_bytes('[scene]\nname = "grün"\n'.encode("latin-1"))
    with pytest.raises(ds.SceneError, match="not a UTF-8"):
        ds.load_scene(p)
    b = tmp_path / "blob.toml"
    b.write_bytes(bytes(range(256)))
    with pytest.raises(ds.SceneError):
        ds.load_scene(b)


def test_scene_damping_and_analysis_settings_are_read(tmp_path):
    """[damping] and the new [analysis] keys reach the Scene; absent, the stated defaults;
    a bad value names the key and its line."""
    from dynstiff.scenes.loader import SCENE_DIR
    text = (SCENE_DIR / "planar2.toml").read_text()
    assert ds.load_scene("planar2").damping == ds.Damping()
    p = tmp_path / "d.toml"
    p.write_text(text + '\n[damping]\nplatform_ratio = 0.03\ncable_loss_factor = 0.0\n')
    sc = ds.load_scene(p)
    assert sc.damping == ds.Damping(0.03, 0.0, 0.0)
    p.write_text(text.replace("[analysis]", '[analysis]\nmodel = "lumped"\nsegments = 12\n'
                                            'model_rtol = 0.02'))
    sc = ds.load_scene(p)
    assert (sc.model, sc.segments, sc.model_rtol) == ("lumped", 12, 0.02)
    p.write_text(text + '\n[damping]\nplatform_ratio = -1.0\n')
    with pytest.raises(ds.SceneError, match="platform_ratio"):
        ds.load_scene(p)
    p.write_text(text + '\n[damping]\nstiffness = 1.0\n')
    with pytest.raises(ds.SceneError, match="unknown key 'stiffness'"):
        ds.load_scene(p)


TRAJECTORY = """
[workspace]
box = [-2.0, 2.0, -2.0, 2.0, 0.5, 3.0]

[[trajectories]]
name = "up"
law = "quintic"
times = [0.0, 2.0]
positions = [[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]]
"""


def test_workspace_box_and_trajectories_are_read(tmp_path):
    p = tmp_path / "t.toml"
    p.write_text((ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text() + TRAJECTORY)
    sc = ds.load_scene(p)
    assert sc.workspace_box == (-2.0, 2.0, -2.0, 2.0, 0.5, 3.0)
    up = sc.trajectories["up"]
    assert isinstance(up, ds.WaypointPath) and up.law == "quintic"
    np.testing.assert_array_equal(up.rotations, 0.0)                 # default: no rotation
    np.testing.assert_allclose(up.at(1.0)[0], [[0.0, 0.0, 1.5]])      # half way at mid-time
    assert ds.load_scene("cogiro").trajectories == {}


@pytest.mark.parametrize("edit, match", [
    (('box = [-2.0, 2.0, -2.0, 2.0, 0.5, 3.0]', 'box = [2.0, -2.0, -2.0, 2.0, 0.5, 3.0]'),
     r"line \d+: box must be 6 numbers"),
    (('law = "quintic"', 'law = "spline"'), r"line \d+: \[trajectories\] trajectory 'up': "
                                            r"law must be one of"),
    (('times = [0.0, 2.0]', 'times = [0.0, 2.0, 3.0]'),
     r"positions must be finite, shape \(3, 3\)"),
    (('law = "quintic"\n', ''), r"line \d+: missing key 'law' in \[trajectories\]"),
    (('positions = [[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]]', 'positions = [1.0, 2.0]'),
     "positions in \\[trajectories\\] must be a list of points"),
    (('name = "up"', 'name = "up"\nspeed = 1.0'), "unknown key 'speed' in \\[trajectories\\]"),
])
def test_bad_trajectories_and_boxes_name_key_and_line(tmp_path, edit, match):
    p = tmp_path / "t.toml"
    p.write_text((ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text()
                 + TRAJECTORY.replace(*edit))
    with pytest.raises(ds.SceneError, match=match):
        ds.load_scene(p)


@pytest.mark.parametrize("name", [5, None, ["cogiro"]])
def test_a_scene_name_that_is_no_name_is_refused(name):
    with pytest.raises(ds.InvalidParameterError,
                       match="^name must be a built-in scene's name or a path to a TOML file"):
        ds.load_scene(name)
