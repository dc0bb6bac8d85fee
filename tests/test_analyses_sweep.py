"""Sweeps of modes along paths and over parameters (dynstiff/analyses/sweep.py, theory.md §6):
tracking by MAC, veering, infeasible steps."""

import numpy as np
import pytest
import scipy.linalg

import dynstiff as ds
from dynstiff.analyses.platform_modes import find_platform_modes
from dynstiff.analyses.sweep import UNTRACKED, sweep
from dynstiff.errors import InvalidParameterError, SlackCableError


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def cogiro_with_E(scene, E):
    """CoGiRo with Young's modulus E [Pa] (as validation/cogiro_modes.py and
    tests/test_validation.py::test_cogiro_modes build it)."""
    rob = scene.robot
    return ds.Robot(rob.anchors, rob.attachments, ds.Cable(0.064, 8.2051e-6 * E), rob.platform,
                    tension_limits=rob.tension_limits)


def massless_frequencies(eq):
    """The 6 frequencies [Hz] of the massless-cable model K_0 (theory.md §6), ascending."""
    m = ds.FrequencyModel(eq)
    lam = scipy.linalg.eigh(m.massless_stiffness(), m.platform_mass, eigvals_only=True)
    return np.sqrt(lam) / (2 * np.pi)


def check_tracks_follow_massless_modes(res):
    """Independent check of the MAC tracking: on these sweeps the 6 massless-cable modes keep
    their order, so track t must be the continuation of massless mode t at every step."""
    for k, eq in enumerate(res.equilibria):
        f0 = massless_frequencies(eq)
        sel = (res.step == k) & (res.track != UNTRACKED)
        rank = np.argmin(np.abs(res.massless_freq_hz[sel][:, None] - f0[None, :]), axis=1)
        np.testing.assert_array_equal(rank, res.track[sel], err_msg=f"step {k}")


# ------------------------------------------------------------------ sweep along a path
@pytest.fixture(scope="module")
def path_sweep(scene):
    poses = [(0.0, 0.0, z) for z in np.linspace(0.8, 1.2, 5)]
    calls = []
    res = sweep(scene.robot, poses=poses, fmax_hz=5.5,
                progress=lambda done, n: calls.append((done, n)))
    return poses, res, calls


# ------------------------------------------------------------------ arguments and errors
def small_robot():
    ang = np.radians([90, 210, 330])
    anchors = np.column_stack([5 * np.cos(ang), 5 * np.sin(ang), [5.0, 5.2, 4.8]])
    return ds.Robot(anchors, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                    ds.Platform(20.0, free_dofs=("x", "y", "z")))


def test_path_sweep_global_tracks_are_continuous(path_sweep):
    """Each global track changes by less than 10 % between steps 0.1 m apart (measured at most
    1.95 %); 4 tracks span the whole path; tracks continue the massless-cable modes."""
    _, res, _ = path_sweep
    vt = res.veering_table()
    assert vt.shape == (5, res.n_tracks) and res.n_tracks >= 4          # measured: 5
    assert vt.notna().all().sum() >= 4                                  # measured: 4
    rel = (vt.diff().abs() / vt.shift()).to_numpy()
    assert np.nanmax(rel) < 0.1
    sel = res.track != UNTRACKED
    np.testing.assert_array_equal(vt.to_numpy()[res.step[sel], res.track[sel]],
                                  res.freq_hz[sel])
    check_tracks_follow_massless_modes(res)


# ------------------------------------------------------------------ sweep of a parameter
def test_sweep_over_E_global_frequencies_increase(scene):
    """E = 17, 60, 120 GPa, modes below 10 Hz: every global track rises with E (CoGiRo's
    platform modes are governed by the axial cable stiffness). The massless-cable frequencies
    rise by less than sqrt(120/17) = 2.66 (the tension terms T/L and K_geo do not scale with E;
    measured 2.52-2.53); the full model's may rise more (measured 2.47-2.82), because at 17 GPa
    the lowest platform modes sit below the first clamped-cable frequencies, where every cable
    is softer than statically and the n-th mode lies below the n-th massless mode (theory.md
    §6: absorbers tuned above a mode pull it down). The mode continuing the 4th
    massless mode is labelled local at 60 GPa (it shares its energy with a cable family) and is
    found again by shape at 120 GPa."""
    res = sweep(None, build=lambda E: cogiro_with_E(scene, E).equilibrium(pose=scene.pose),
                values=[17e9, 60e9, 120e9], parameter="E [Pa]", fmax_hz=10.0)
    assert res.parameter == "E [Pa]"
    vt = res.veering_table()
    assert vt.notna().all().sum() >= 3                                  # measured: 3
    for t in vt.columns:
        f = vt[t].dropna().to_numpy()
        assert np.all(np.diff(f) > 0), f"track {t}: {f}"
    ratio = (vt.iloc[-1] / vt.iloc[0]).dropna()
    assert len(ratio) >= 3 and (ratio > 1.5).all()                     # measured: 4 tracks
    f0 = np.array([massless_frequencies(eq) for eq in res.equilibria])    # (3, 6)
    r0 = f0[-1] / f0[0]
    assert (r0 > 1.5).all() and (r0 < np.sqrt(120 / 17)).all()
    # below the first clamped-cable frequency K_B(omega) <= K_B(0) (its eigenvalues decrease
    # with omega, the W-W premise), so the n-th mode lies below the n-th massless mode
    below = 0
    for eq, m, f0k in zip(res.equilibria, res.modal, f0):
        J0 = ds.FrequencyModel(eq).cable_mode_count(2 * np.pi * m.freq_hz)
        n = int(np.sum(J0 == 0))
        assert np.all(m.freq_hz[:n] < f0k[:n])
        below += n
    assert below >= 5                                     # measured: 4, 2, 1 at 17, 60, 120 GPa
    check_tracks_follow_massless_modes(res)


def test_sweep_over_E_tracks_through_local_families(scene):
    """15 values of E from 17 to 120 GPa: the platform modes climb through the first and
    second local cable families (3.2-3.7 Hz, 6.4-7.3 Hz, nearly independent of E). While
    inside a family a mode may be labelled local (a gap in its track); the MAC tracking picks
    it up again on the far side, always as the continuation of the same massless mode."""
    res = sweep(None, build=lambda E: cogiro_with_E(scene, E).equilibrium(pose=scene.pose),
                values=np.geomspace(17e9, 120e9, 15), parameter="E [Pa]", fmax_hz=10.0)
    vt = res.veering_table()
    assert res.n_tracks == 6
    gaps = vt.isna().to_numpy()
    inner = gaps[1:-1] & ~gaps[:-2] & ~gaps[2:]                # a track missing between two hits
    assert inner.sum() >= 3                                    # measured: 6
    for t in vt.columns:
        f = vt[t].dropna().to_numpy()
        assert np.all(np.diff(f) > 0), f"track {t}: {f}"
    check_tracks_follow_massless_modes(res)


def test_sweep_user_values_and_progress():
    rob = small_robot()
    calls = []
    res = sweep(rob, poses=[[0, 0, 1.0], ds.Pose([0.1, 0, 1.0]), [0.2, 0, 1.0, 0, 0, 0]],
                values=[10.0, 20.0, 30.0], parameter="x [cm]", n_modes=5,
                progress=lambda *a: calls.append(a))
    assert calls == [(1, 3), (2, 3), (3, 3)]
    assert res.parameter == "x [cm]"
    for k in range(3):          # the 5 lowest modes and the platform modes, at every step
        pm = find_platform_modes(ds.build_model(res.equilibria[k], "dsm"))
        assert np.sum(res.step == k) == len(set(range(5)) | set(pm.index.tolist()))
    unnamed = sweep(rob, poses=[[0, 0, 1.0], [0.1, 0, 1.0]], values=[1.0, 2.0], n_modes=2)
    assert unnamed.parameter == "value"             # user values without a name
    np.testing.assert_array_equal(np.unique(res.value), [10.0, 20.0, 30.0])
    np.testing.assert_allclose(res.equilibria[2].pose.position, [0.2, 0, 1.0])


@pytest.mark.parametrize("kwargs,message", [
    (dict(n_modes=5), "give poses= (a path of poses for robot) or build= (a callable value -> "
     "Equilibrium) with values=; got neither"),
    (dict(poses=[[0, 0, 1.0]], build=lambda v: None, values=[1.0], n_modes=5),
     "give poses= or build=, not both"),
    (dict(build=lambda v: None, n_modes=5), "build= needs values= (the parameter values to "
     "sweep)"),
    (dict(build=lambda v: None, values=[], n_modes=5),
     "values must be a non-empty 1-D sequence, got shape (0,)"),
    (dict(build=lambda v: None, values=["a"], n_modes=5), "values must be real numbers, got "
     "['a']"),
    (dict(build=lambda v: None, values=[np.nan], n_modes=5), "values must be finite, got [nan]"),
    (dict(build=3, values=[1.0], n_modes=5), "build must be a callable value -> Equilibrium, "
     "got 3"),
    (dict(poses=[], n_modes=5), "poses must hold at least one pose, got an empty sequence"),
    (dict(poses=3, n_modes=5), "poses must be a sequence of poses, got int"),
    (dict(poses=[[0, 0, 1.0]]), "give n_modes (number of modes per step) or fmax_hz (band top "
     "[Hz]), got neither"),
    (dict(poses=[[0, 0, 1.0]], n_modes=0), "n_modes must be an integer >= 1, got 0"),
    (dict(poses=[[0, 0, 1.0]], n_modes=2.0), "n_modes must be an integer >= 1, got 2.0"),
    (dict(poses=[[0, 0, 1.0]], fmax_hz=-1.0), "fmax_hz must be > 0, got -1.0"),
    (dict(poses=[[0, 0, 1.0]], n_modes=5, progress=3),
     "progress must be a callable (step, n_steps) or None, got 3"),
    (dict(poses=[[0, 0, 1.0], [0, 0, 1.1]], values=[1.0], n_modes=5),
     "values must give one value per pose (2), got 1"),
    (dict(build=lambda v: 1.0, values=[1.0], n_modes=5),
     "build must return an Equilibrium, got float for value np.float64(1.0)"),
    (dict(poses=[[0, 0, 1.0]], n_modes=5, mac_min=2.0), "mac_min must be in (0, 1], got 2.0"),
    (dict(poses=[[0, 0, 1.0]], n_modes=5, mac_min=-1.0), "mac_min must be > 0, got -1.0"),
    (dict(poses=[[0, 0, 1.0]], n_modes=5, parameter=3),
     "parameter must be a str (name [unit]), got 3"),
])
def test_sweep_bad_arguments_name_them(kwargs, message):
    with pytest.raises(InvalidParameterError) as err:
        sweep(small_robot(), **kwargs)
    assert str(err.value) == message


def test_sweep_limits_are_inclusive_and_the_robot_is_checked():
    """n_modes = 1 and mac_min = 1 are accepted; the default parameter name of a sweep over
    poses is the arc length and of a build sweep "value"; a non-robot is refused by type."""
    rob = small_robot()
    one = sweep(rob, poses=[[0, 0, 1.0]], n_modes=1)
    pm = find_platform_modes(ds.build_model(one.equilibria[0], "dsm"))
    assert len(one) == len({0} | set(pm.index.tolist())) and one.n_tracks == 3
    assert sweep(rob, poses=[[0, 0, 1.0], [0, 0, 1.05]], n_modes=2, mac_min=1.0).n_tracks >= 3
    built = sweep(None, build=lambda v: rob.equilibrium(pose=[0, 0, v]), values=[1.0],
                  n_modes=2)
    assert built.parameter == "value" == built.to_frame().attrs["parameter"]
    with pytest.raises(InvalidParameterError) as err:
        sweep("robot", poses=[[0, 0, 1.0]], n_modes=2)
    assert str(err.value) == "robot must be a dynstiff.Robot for a sweep of poses, got str"


def test_sweep_names_the_failing_step():
    with pytest.raises(SlackCableError) as exc:
        sweep(small_robot(), poses=[[0, 0, 1.0], [9.0, 0, 1.0]], n_modes=3)
    assert any("sweep step 1" in note for note in exc.value.__notes__)


def test_sweep_runs_on_any_rung(cogiro):
    """The sweep takes the model of every step from the ladder: massless cables give the six
    platform modes only, all global and tracked; the lumped rung tracks the same global modes
    as the closed form (its first global frequency within the N = 6 discretisation error)."""
    poses = [[-0.5, 0.0, 1.0], [0.0, 0.0, 1.0], [0.5, 0.0, 1.0]]
    cat = ds.sweep(cogiro.robot, poses=poses, n_modes=6, rung="catenary")
    assert set(cat.kind) == {"global"} and cat.n_tracks == 6
    dsm = ds.sweep(cogiro.robot, poses=poses, n_modes=8)
    lum = ds.sweep(cogiro.robot, poses=poses, n_modes=8, rung="lumped", segments=6)
    f_dsm = dsm.veering_table().iloc[:, 0].to_numpy()
    f_lum = lum.veering_table().iloc[:, 0].to_numpy()
    np.testing.assert_allclose(f_lum, f_dsm, rtol=(np.pi / 6) ** 2 / 24)
    with pytest.raises(InvalidParameterError, match="tol"):
        ds.sweep(cogiro.robot, poses=poses, n_modes=6, rung="dsm", tol=1e-9)


def test_sweep_records_an_infeasible_pose_and_goes_on():
    """on_error="record": the infeasible middle pose is one row of kind "infeasible" with the
    error's message; the poses before and after it give the same modes as alone."""
    rob = small_robot()
    calls = []
    res = sweep(rob, poses=[[0, 0, 1.0], [9.0, 0, 1.0], [0.1, 0, 1.0]], n_modes=3,
                on_error="record", progress=lambda done, n: calls.append((done, n)))
    assert calls == [(1, 3), (2, 3), (3, 3)]
    assert [k for k, _, _ in res.failures] == [1]
    assert res.failures[0][2].startswith("InfeasiblePoseError: pose [9.0, 0.0, 1.0")
    assert "outside the wrench-feasible workspace" in res.failures[0][2]   # why, what to do
    df = res.to_frame()
    bad = df[df["step"] == 1]
    assert list(bad["kind"]) == ["infeasible"] and bad["freq [Hz]"].isna().all()
    assert res.modal[1] is None and res.equilibria[1] is None
    alone = sweep(rob, poses=[[0.1, 0, 1.0]], n_modes=3)
    np.testing.assert_allclose(df[df["step"] == 2]["freq [Hz]"], alone.freq_hz, rtol=1e-12)
    table = res.veering_table()
    assert table.shape[0] == 3 and table.index.name == "step"
    assert table.columns.name == "track" and list(table.columns) == list(range(res.n_tracks))
    assert list(table.index) == [0, 1, 2] and table.loc[1].isna().all()
    assert int(bad["mode"].iloc[0]) == 0 and bad["track"].isna().all()
    assert df["freq [Hz]"].dtype == np.float64 and df["mode"].dtype == np.int64
    assert repr(res).startswith("SweepResult(") and ", 3 steps, " in repr(res)
    assert f", {len(alone)} modes, " in repr(alone) and ", 1 step, " in repr(alone)
    assert repr(alone).endswith(f", {alone.n_tracks} platform-mode tracks)")
    for k in (0, 2):
        np.testing.assert_array_equal(df[df["step"] == k]["cable energy fraction [-]"],
                                      res.modal[k].cable_energy_fraction)
    with pytest.raises(InvalidParameterError, match="on_error"):
        sweep(rob, poses=[[0, 0, 1.0]], n_modes=3, on_error="skip")


def test_veering_plot_draws_into_the_given_axes_with_or_without_local_modes(path_sweep):
    import matplotlib.pyplot as plt
    res = path_sweep[1]
    fig, ax = plt.subplots()
    assert res.plot(ax=ax) is fig
    gids = {a.get_gid() for a in ax.get_children()}
    assert "local-modes" in gids and {f"track-{t}" for t in range(res.n_tracks)} <= gids
    fig2, ax2 = plt.subplots()
    res.plot(ax=ax2, show_local=False)
    assert "local-modes" not in {a.get_gid() for a in ax2.get_children()}
    plt.close(fig)
    plt.close(fig2)


def test_mac_is_one_for_a_mode_with_itself_and_zero_for_m_orthogonal_modes():
    """MAC(x, y) = (x^T M y)^2 / ((x^T M x)(y^T M y)) with M the mean of the two mass
    matrices: 1 on the diagonal for M-orthogonal modes, 0 off it, invariant to scaling."""
    from dynstiff.analyses.sweep import _mac
    rng = np.random.default_rng(3)
    A = rng.normal(size=(4, 4))
    M = A @ A.T + 4 * np.eye(4)
    X = np.linalg.inv(np.linalg.cholesky(M))             # rows M-orthonormal: X M X^T = I
    mac = _mac(X, M, 3.0 * X, M)
    np.testing.assert_allclose(mac, np.eye(4), atol=1e-12)
    y = X[0] + 0.5 * X[1]
    expected = (X[0] @ M @ y) ** 2 / ((X[0] @ M @ X[0]) * (y @ M @ y))
    assert _mac(X[:1], 0.5 * M, y[None], 1.5 * M)[0, 0] == pytest.approx(expected, rel=1e-12)
    assert expected == pytest.approx(0.8, rel=1e-12)


COLUMNS = ["step", "value", "mode", "track", "freq [Hz]", "kind", "cable energy fraction [-]",
           "massless freq [Hz]"]


def test_path_sweep_table(scene, path_sweep):
    """5 poses z = 0.8 .. 1.2 m, all modes below 5.5 Hz (21 per step) and the platform modes
    above (the rz carrier near 5.8 Hz): tidy table, arc length as value, frequencies
    identical to a direct FrequencyModel at each pose."""
    poses, res, calls = path_sweep
    df = res.to_frame()
    assert list(df.columns) == COLUMNS
    assert res.parameter == "arc length [m]" == df.attrs["parameter"]
    counts = df.groupby("step").size()
    assert list(counts.index) == [0, 1, 2, 3, 4]
    assert df.shape == (counts.sum(), 8) and counts.min() >= 15        # measured: 21 each
    np.testing.assert_allclose(res.values, [0.0, 0.1, 0.2, 0.3, 0.4], atol=1e-12)
    assert calls == [(k, 5) for k in range(1, 6)]
    for k, pose in enumerate(poses):
        rows = df[df["step"] == k]
        assert (rows["value"] == res.values[k]).all()
        assert list(rows["mode"]) == list(range(1, len(rows) + 1))
        eq = scene.robot.equilibrium(pose=pose)
        m = ds.FrequencyModel(eq)
        pm = find_platform_modes(m)
        f = ds.eigenfrequencies(m, fmax_hz=5.5)
        extra = [g for g in pm.freq_hz if np.min(np.abs(f / g - 1)) > 1e-9]
        f = np.sort(np.concatenate([f, extra]))
        np.testing.assert_allclose(rows["freq [Hz]"].to_numpy(), f, rtol=1e-12)
        np.testing.assert_array_equal(res.modal[k].freq_hz, rows["freq [Hz]"].to_numpy())
    # local modes carry no track, global ones do, one mode per track and step
    assert df.loc[df["kind"] == "local", "track"].isna().all()
    glob = df[df["kind"] == "global"]
    assert glob["track"].notna().all()
    assert not glob.duplicated(["step", "track"]).any()




def test_tracks_are_numbered_by_frequency_at_their_first_step():
    """Track ids 0, 1, ... in the order of the track's frequency at the first step it
    appears in (ties by id): the renumbering the result promises, independent of the order
    the tracks were found in."""
    from dynstiff.analyses.sweep import UNTRACKED
    rob = small_robot()
    res = sweep(rob, poses=[[0, 0, 1.0], [0.1, 0, 1.0], [0.2, 0, 1.0]], n_modes=5)
    tracked = res.track != UNTRACKED
    ids = np.unique(res.track[tracked])
    np.testing.assert_array_equal(ids, np.arange(ids.size))
    first = [res.freq_hz[tracked & (res.track == t)][np.argmin(res.step[tracked
                                                                        & (res.track == t)])]
             for t in ids]
    assert np.all(np.diff(first) >= 0) and ids.size >= 2


def test_swept_values_of_booleans_are_refused():
    sc = ds.load_scene("cogiro")
    with pytest.raises(ds.InvalidParameterError, match="^values must be real numbers, not "
                                                       "booleans"):
        ds.sweep(sc.robot, parameter="EA", values=[True, 2e6], poses=[sc.pose, sc.pose],
                 n_modes=2)
