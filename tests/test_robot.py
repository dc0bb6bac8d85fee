"""Robot-level analysis (theory.md §4-§6): statics, K(omega), FRFs, complete eigenfrequencies."""


import numpy as np
import pytest
import scipy.linalg

import dynstiff as ds
from dynstiff.errors import InvalidParameterError, PoleWarning, SlackCableError
from conftest import lumped_point_mass_frequencies, point_mass_robot


def skew(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def test_lever_map_moves_a_point_by_dp_plus_dtheta_cross_r():
    rng = np.random.default_rng(3)
    r, dp, dth = rng.normal(size=(3, 3))
    x = np.concatenate([dp, dth])
    np.testing.assert_allclose(ds.platform.lever_map(r) @ x, dp + np.cross(dth, r),
                               rtol=1e-14, atol=1e-15)
    # J^T f is the wrench about P of a force f at r
    f = rng.normal(size=3)
    np.testing.assert_allclose(ds.platform.lever_map(r).T @ f,
                               np.concatenate([f, np.cross(r, f)]), rtol=1e-14, atol=1e-15)
    fi = [0, 2, 5]
    np.testing.assert_array_equal(ds.platform.lever_map(r, fi),
                                  ds.platform.lever_map(r)[:, fi])


def straight_cable_frequencies(eq):
    """Independent massless straight-cable model: K = sum J^T (k u u^T + t/l (I - u u^T)) J
    + K_geo, with k = EA/L0, mass matrix of the rigid body written out here (Hz)."""
    rob, pose = eq.robot, eq.pose
    R = pose.matrix
    K = np.zeros((6, 6))
    Kgeo = np.zeros((3, 3))
    for i, s in enumerate(eq.states):
        r = R @ rob.attachments[i]
        B = pose.position + r
        d = rob.anchors[i] - B
        l = np.linalg.norm(d)
        u = d / l
        t = s.tension_at_end
        Kc = rob.cables[i].EA / eq.unstretched_lengths[i] * np.outer(u, u) + t / l * (
            np.eye(3) - np.outer(u, u))
        J = np.hstack([np.eye(3), -skew(r)])
        K += J.T @ Kc @ J
        f = t * u
        Kgeo += (r @ f) * np.eye(3) - np.outer(r, f)      # -[f]x[r]x = (f.r) I - r f^T
    m = rob.platform.mass
    rG = R @ rob.platform.center_of_mass
    fg = m * np.array([0, 0, -rob.g])
    Kgeo += (rG @ fg) * np.eye(3) - np.outer(rG, fg)
    K[3:, 3:] += Kgeo
    M = np.zeros((6, 6))
    M[:3, :3] = m * np.eye(3)
    M[:3, 3:] = -m * skew(rG)
    M[3:, :3] = m * skew(rG)
    M[3:, 3:] = R @ rob.platform.inertia @ R.T + m * (np.dot(rG, rG) * np.eye(3) - np.outer(rG, rG))
    fi = rob.platform.free_index
    lam = scipy.linalg.eigh(0.5 * (K + K.T)[np.ix_(fi, fi)], M[np.ix_(fi, fi)],
                            eigvals_only=True)
    return np.sqrt(lam) / (2 * np.pi)


def test_massless_limit_matches_straight_cable_model(cogiro):
    light = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments,
                     ds.Cable(1e-7, cogiro.robot.cables[0].EA), cogiro.robot.platform,
                     tension_limits=cogiro.robot.tension_limits)
    eq = light.equilibrium(pose=cogiro.pose)
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), 6)
    np.testing.assert_allclose(f, straight_cable_frequencies(eq), rtol=1e-6)


def test_geometric_stiffness_symmetric_at_equilibrium(cogiro_eq):
    Kg = ds.FrequencyModel(cogiro_eq).K_geo
    assert np.abs(Kg).max() > 10          # not trivially zero
    np.testing.assert_allclose(Kg, Kg.T, atol=1e-10 * np.abs(Kg).max())


def test_inverse_then_forward_statics_round_trip(cogiro, cogiro_eq):
    assert cogiro_eq.residual < 1e-10
    fwd = cogiro.robot.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    np.testing.assert_allclose(fwd.pose.position, cogiro.pose.position, atol=1e-9)
    np.testing.assert_allclose(fwd.pose.rotation, cogiro.pose.rotation, atol=1e-9)
    t_min, t_max = cogiro.robot.tension_limits
    assert np.all(cogiro_eq.tensions >= t_min - 1e-9) and np.all(cogiro_eq.tensions <= t_max)


def test_receptance_is_symmetric(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    H = ds.frf(m, 2 * np.pi * np.linspace(0.2, 10, 200)).H
    np.testing.assert_allclose(H, H.transpose(0, 2, 1), rtol=1e-8, atol=1e-12 * np.abs(H).max())


def rotated_robot(rob, pose, phi):
    """The robot turned by phi about the vertical (gravity unchanged)."""
    c, s = np.cos(phi), np.sin(phi)
    Q = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    from scipy.spatial.transform import Rotation
    rot = (Rotation.from_matrix(Q) * Rotation.from_rotvec(pose.rotation)).as_rotvec()
    return (ds.Robot(rob.anchors @ Q.T, rob.attachments, rob.cables, rob.platform,
                     tension_limits=rob.tension_limits), ds.Pose(Q @ pose.position, rot))


def test_rotating_robot_with_gravity_leaves_frequencies(cogiro, cogiro_eq):
    f = ds.eigenfrequencies(ds.FrequencyModel(cogiro_eq), 12)
    rob, pose = rotated_robot(cogiro.robot, cogiro.pose, 0.7)
    eq = rob.equilibrium(pose=pose)
    np.testing.assert_allclose(ds.eigenfrequencies(ds.FrequencyModel(eq), 12), f, rtol=1e-9)


def test_mirrored_robot_gives_mirrored_modes(cogiro, cogiro_eq):
    Mx = np.diag([-1.0, 1, 1])
    p = cogiro.robot.platform
    pm = ds.Platform(p.mass, Mx @ p.center_of_mass, Mx @ p.inertia @ Mx)
    rob = ds.Robot(cogiro.robot.anchors @ Mx, cogiro.robot.attachments @ Mx, cogiro.robot.cables,
                   pm, tension_limits=cogiro.robot.tension_limits)
    eq = rob.equilibrium(pose=Mx @ cogiro.pose.position)
    a = ds.modes(ds.FrequencyModel(cogiro_eq), 8)
    b = ds.modes(ds.FrequencyModel(eq), 8)
    np.testing.assert_allclose(b.freq_hz, a.freq_hz, rtol=1e-9)
    # translation mirrors with Mx, rotation (axial vector) with -Mx
    T = np.diag([-1.0, 1, 1, 1, -1, -1])
    for k in np.flatnonzero(np.array(a.kind) == "global"):
        ma, mb = T @ a.platform_shapes[k], b.platform_shapes[k]
        assert abs(ma @ mb) == pytest.approx(np.linalg.norm(ma) * np.linalg.norm(mb), rel=1e-6)


# ------------------------------------------------------------------ W-W against lumped mass
def test_wittrick_williams_count_equals_lumped_model_count():
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.2, -0.1, 1.0])
    m = ds.FrequencyModel(eq)
    f = ds.eigenfrequencies(m, 30)
    f_lumped = lumped_point_mass_frequencies(eq, 80, n_modes=30)
    # same number of modes below every probe frequency away from any mode
    probes = np.linspace(0.5, 0.97 * f[-1], 400)
    gap = np.min(np.abs(probes[:, None] / np.concatenate([f, f_lumped])[None, :] - 1), axis=1)
    probes = probes[gap > 0.004]
    J = ds.mode_count(m, 2 * np.pi * probes)
    J_lumped = np.searchsorted(f_lumped, probes)
    np.testing.assert_array_equal(J, J_lumped)
    np.testing.assert_allclose(f, f_lumped, rtol=3e-3)   # discretisation O((n pi/N)^2/24)


def test_close_and_coincident_roots_are_found():
    """A symmetric robot: three identical cables at 120 deg give double roots."""
    ang = np.radians([90, 210, 330])
    anchors = np.column_stack([5 * np.cos(ang), 5 * np.sin(ang), np.full(3, 5.0)])
    rob = ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(20.0, free_dofs=("x", "y", "z")))
    eq = rob.equilibrium(pose=[0, 0, 1.0])
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), 26)
    pairs = np.sum(np.abs(np.diff(f)) < 1e-6 * f[1:])
    assert pairs >= 3                                      # coincident roots resolved
    J = ds.mode_count(ds.FrequencyModel(eq), 2 * np.pi * f[:20] * (1 + 1e-7))
    np.testing.assert_array_equal(J, [np.sum(f <= fk * (1 + 1e-9)) for fk in f[:20]])


def test_frf_peaks_sit_at_eigenfrequencies(cogiro):
    light = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments,
                     ds.Cable(0.064, cogiro.robot.cables[0].EA, loss_factor=1e-4),
                     cogiro.robot.platform, tension_limits=cogiro.robot.tension_limits)
    eq = light.equilibrium(pose=cogiro.pose)
    m = ds.FrequencyModel(eq)
    modes = ds.modes(m, 3)
    f1 = modes.freq_hz[0]
    f = np.linspace(0.9 * f1, 1.1 * f1, 20001)
    H = ds.frf(m, 2 * np.pi * f).H
    amp = np.abs(H).max(axis=(1, 2))
    assert f[np.argmax(amp)] == pytest.approx(f1, rel=2e-4)


def test_frf_exact_pole_warns_and_returns_inf(cogiro_eq):
    class Singular:
        """The closed-form model with an exactly singular K at the first frequency."""

        def __init__(self, model):
            self.model = model

        def __getattr__(self, name):
            return getattr(self.model, name)

        def dynamic_stiffness(self, omega):
            K = self.model.dynamic_stiffness(omega)
            K[0] = 0.0
            return K

    with pytest.warns(PoleWarning):
        H = ds.frf(Singular(ds.FrequencyModel(cogiro_eq)), [1.0, 2.0]).H
    assert np.all(np.isinf(H[0])) and np.all(np.isfinite(H[1]))


# ------------------------------------------------------------------ bad inputs
def test_bad_robot_inputs_raise_naming_field(cogiro):
    r = cogiro.robot
    with pytest.raises(InvalidParameterError, match="anchors"):
        ds.Robot(r.anchors[:5], r.attachments[:5], r.cables[:5], r.platform)
    A = r.anchors.copy()
    A[3] = A[2]
    with pytest.raises(InvalidParameterError, match="anchors 2 and 3"):
        ds.Robot(A, r.attachments, r.cables, r.platform)
    with pytest.raises(InvalidParameterError, match="inertia"):
        ds.Platform(10.0, inertia=np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(InvalidParameterError, match="inertia"):
        ds.Platform(10.0, inertia=np.diag([1.0, 1.0, 5.0]))      # triangle inequality
    with pytest.raises(InvalidParameterError, match="free_dofs"):
        ds.Platform(10.0, free_dofs=("x", "q"))


def test_pose_outside_workspace_raises(cogiro):
    with pytest.raises(SlackCableError, match="pose"):
        cogiro.robot.equilibrium(pose=[9.0, 0.0, 1.0])


@pytest.mark.parametrize("edit,key,line", [
    (("mass = 91.058", "mas = 91.058"), "mas", 12),
    (("EA = 139486.7", "EA = -1.0"), "EA", None),
    (("[analysis]", "[analysys]"), "analysys", None),
    (("forbidden_band_hz = [0.0, 1.5]", "forbidden_band_hz = [1.5, 0.0]"), "forbidden_band_hz",
     None),
])
def test_toml_errors_name_key_and_line(tmp_path, edit, key, line):
    text = (ds.scenes.loader.SCENE_DIR / "cogiro.toml").read_text().replace(*edit)
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(ds.SceneError, match=key) as exc:
        ds.load_scene(p).robot
    if line is not None:
        assert f"line {line}" in str(exc.value)
    else:
        assert "line " in str(exc.value)


def test_scene_loads_by_name_and_path(cogiro):
    assert "cogiro" in ds.list_scenes()
    r = ds.load_scene(ds.scenes.loader.SCENE_DIR / "cogiro.toml").robot
    np.testing.assert_array_equal(r.anchors, cogiro.robot.anchors)
    with pytest.raises(ds.SceneError, match="unknown scene"):
        ds.load_scene("nope")


def test_close_pairs_are_found():
    """Break the symmetry slightly: each double root splits into a pair < 1e-4 apart
    (relative); W-W finds both members and the count steps by one at each."""
    ang = np.radians([90, 210, 330])
    anchors = np.column_stack([5 * np.cos(ang), 5 * np.sin(ang), np.full(3, 5.0)])
    anchors[0, 0] += 2e-5                                   # 20 micrometres
    rob = ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                   ds.Platform(20.0, free_dofs=("x", "y", "z")))
    m = ds.FrequencyModel(rob.equilibrium(pose=[0, 0, 1.0]))
    f = ds.eigenfrequencies(m, 32)
    gaps = np.diff(f) / f[1:]
    close = np.flatnonzero((gaps > 0) & (gaps < 1e-4))
    close = close[close + 2 < len(f)]                      # the next mode up is known
    assert len(close) >= 3
    for k in close:
        mid = 0.5 * (f[k] + f[k + 1])
        lo, hi = f[k] - 0.25 * (f[k + 1] - f[k]), f[k + 1] + 0.25 * (f[k + 1] - f[k])
        if hi >= f[k + 2] or (k > 0 and lo <= f[k - 1]):
            continue                                       # a third close root: tested below
        np.testing.assert_array_equal(ds.mode_count(m, 2 * np.pi * np.array([lo, mid, hi])),
                                      [k, k + 1, k + 2])
    # every computed root is a distinct step of the count, even in triplets 6e-7 apart
    between = 0.5 * (f[1:] + f[:-1])
    np.testing.assert_array_equal(ds.mode_count(m, 2 * np.pi * between), np.arange(1, len(f)))


def test_forward_statics_with_held_dofs_needs_initial_pose(cogiro, cogiro_eq):
    p = cogiro.robot.platform
    planar = ds.Platform(p.mass, p.center_of_mass, p.inertia, free_dofs=("x", "z", "ry"))
    rob = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments, cogiro.robot.cables, planar,
                   tension_limits=cogiro.robot.tension_limits)
    with pytest.raises(InvalidParameterError, match="initial_pose"):
        rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths)
    eq = rob.equilibrium(unstretched_lengths=cogiro_eq.unstretched_lengths,
                         initial_pose=cogiro.pose)
    np.testing.assert_allclose(eq.pose.position, cogiro.pose.position, atol=1e-9)
    m = ds.FrequencyModel(eq)
    K = m.dynamic_stiffness([0.0, 10.0])
    np.testing.assert_allclose(K, K.transpose(0, 2, 1), atol=1e-9 * np.abs(K).max())


@pytest.mark.parametrize("name", ["cogiro", "planar2", "sixcable", "fourcable"])
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


def test_fourcable_needs_only_the_light_model():
    """Seed paper 002's small robot: the cable modes sit above 28 Hz, sag/chord ~1e-4 and the
    cables weigh 0.1 % of the platform, so straight massless springs meet 1 % up to 20 Hz."""
    eq = ds.load_scene("fourcable").equilibrium()
    rec = ds.recommend_model(eq, (0.1, 20.0), 1e-2)
    assert rec.rung == "spring"
    assert rec.estimates["cable_f1_hz"] > 20.0 and rec.estimates["mass_ratio"] < 0.01
    f_spring = ds.eigenfrequencies(ds.build_model(eq, "spring"), fmax_hz=20.0)
    f_dsm = ds.eigenfrequencies(ds.build_model(eq, "dsm"), fmax_hz=20.0)
    np.testing.assert_allclose(f_spring, f_dsm, rtol=1e-2)


SEED_SCENES = ("cogiro", "planar2", "sixcable", "fourcable", "pendulum", "simulator")


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


def test_each_stiffness_has_its_own_name(cogiro_eq):
    """One name per quantity: the 3x3 end stiffness of one cable (CatenaryState.end_stiffness),
    the 6x6 platform stiffness at a pose (Robot/Equilibrium.platform_stiffness) and a
    model's massless_stiffness on its free DOFs; the catenary rung assembles the first
    into the second."""
    s = cogiro_eq.states[0]
    assert s.end_stiffness.shape == (3, 3)
    K6 = cogiro_eq.platform_stiffness()
    np.testing.assert_allclose(
        K6, cogiro_eq.robot.platform_stiffness(cogiro_eq.pose, cogiro_eq.states), rtol=0)
    cat = ds.build_model(cogiro_eq, "catenary")
    np.testing.assert_allclose(cat.massless_stiffness(), 0.5 * (K6 + K6.T), rtol=1e-12)
    for obj in (s, cogiro_eq, cogiro_eq.robot, cat):
        assert not hasattr(obj, "static_stiffness") and not hasattr(obj, "dof_names")
