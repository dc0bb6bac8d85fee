"""Workspace maps (dynstiff/maps/workspace.py, docs/theory.md §13): per-pose values against the
single-pose analyses, recorded failures in input order, the band margin's definition, the
cable-parameter dimension, independence of the chunking, argument checks, and (integration
tier) the same Dataset from local processes and from a real Dask cluster."""

import numpy as np
import pytest

import dynstiff as ds

xr = pytest.importorskip("xarray")
from dynstiff.analyses.checks import design_checks
from dynstiff.maps.workspace import CHECKS, box_grid, workspace

N_MODES = 6
BAND = (0.0, 1.5)
# two feasible poses around an infeasible one (outside the frame): input order is kept
POSES = [[0.0, 0.0, 1.0], [9.0, 0.0, 1.0], [1.0, -0.5, 1.5, 0.0, 0.0, 0.05]]


@pytest.fixture(scope="module")
def robot():
    return ds.load_scene("cogiro").robot


@pytest.fixture(scope="module")
def listed(robot):
    return workspace(robot, POSES, n_modes=N_MODES, band_hz=BAND, chunk_size=3)


def test_each_pose_equals_the_single_pose_analyses(robot, listed):
    """Tensions and lengths equal cold inverse statics (1e-9; the map warm-starts), the
    frequencies equal dynstiff.modes (1e-8), the platform share is 1 - the cable energy
    fraction, and the platform modes and the first of them are those of
    find_platform_modes at the pose."""
    from dynstiff.analyses.platform_modes import find_platform_modes
    for i in (0, 2):
        eq = robot.equilibrium(pose=POSES[i])
        m = ds.build_model(eq, "dsm")
        res = ds.modes(m, n_modes=N_MODES)
        pm = find_platform_modes(m)
        p = listed.isel(pose=i)
        np.testing.assert_allclose(p["tension"], eq.tensions, rtol=1e-9)
        np.testing.assert_allclose(p["unstretched_length"], eq.unstretched_lengths, rtol=1e-9)
        np.testing.assert_allclose(p["freq"], res.freq_hz, rtol=1e-8)
        np.testing.assert_allclose(p["platform_share"], res.platform_share, rtol=1e-6,
                                   atol=1e-9)
        assert p["is_platform"].values.tolist() == [k in pm.index for k in range(N_MODES)]
        assert float(p["first_platform_hz"]) == pytest.approx(pm.first_hz, rel=1e-8)


def test_band_margin_is_the_relative_distance_above_the_band(listed):
    """Band (0, 1.5) Hz: the margin is f1 / 1.5 - 1 (every mode held to it lies above, the
    lowest the first platform mode)."""
    f1 = listed["first_platform_hz"].values[[0, 2]]
    np.testing.assert_allclose(listed["band_margin"].values[[0, 2]], f1 / 1.5 - 1.0,
                               rtol=1e-14)


def test_infeasible_pose_is_recorded_in_place_with_its_reason(listed):
    assert listed["feasible"].values.tolist() == [True, False, True]
    assert str(listed["reason"].values[1]).startswith(          # why, and what to change
        "InfeasiblePoseError: pose [9.0, 0.0, 1.0, 0.0, 0.0, 0.0]: no positive cable "
        "tensions balance the platform")
    assert "outside the wrench-feasible workspace" in str(listed["reason"].values[1])
    assert listed["reason"].values[0] == ""
    assert np.all(np.isnan(listed["tension"].values[1]))
    assert not listed["passed"].values[1].any() and not listed["dynamic"].values[1]
    np.testing.assert_array_equal(listed["position"].values[1], POSES[1])
    np.testing.assert_array_equal(listed["rotation"].values[2], POSES[2][3:])


def test_verdicts_match_the_design_checks(robot, listed):
    """Every verdict, and the sag and tension values, as dynstiff.analyses.checks.
    design_checks at the same pose with the same arguments; every check is mapped."""
    for i in (0, 1, 2):
        res = design_checks(robot, POSES[i], band_hz=BAND)
        p = listed.isel(pose=i)
        for r in res.rows:
            assert bool(p["passed"].sel(check=r["check"])) == (r["verdict"] == "pass")
            assert bool(p["unknown"].sel(check=r["check"])) == (r["verdict"] == "unknown")
        assert bool(p["dynamic"]) == res.passed
    rows = {r["check"]: r for r in design_checks(robot, POSES[0], band_hz=BAND).rows}
    p = listed.isel(pose=0)
    assert float(p["sag_ratio"].max()) == pytest.approx(rows["sag / chord"]["value"],
                                                        rel=1e-9)
    assert float(p["max_tension"].max()) == pytest.approx(rows["tension limits"]["value"],
                                                          rel=1e-9)
    assert list(listed["check"].values) == list(CHECKS)


@pytest.mark.parametrize("band", [BAND, None, (3.0, 4.0)])
def test_a_small_box_map_is_the_design_checks_at_every_pose(robot, band):
    """A 4 x 3 x 2 box over the frame (edges and infeasible poses included), one chunk,
    with and without a forbidden band (and with one among the platform modes): at every
    pose the map's verdicts are design_checks' (the damped model of the receptance check
    derived from the map's model, the static error once per model), its first platform
    frequency and band margin are those of design_checks' platform modes (1e-9: the map's
    statics start from the neighbour), and a feasible pose has a reason only for an
    unknown verdict."""
    from dynstiff.maps.workspace import _band_margin
    kw = {"band_hz": band} if band else {}
    m = workspace(robot, box=(-6.0, 2.0, -3.0, 3.0, 0.5, 3.0), step=2.5,
                  n_modes=N_MODES, chunk_size=50, **kw)
    checks = list(m["check"].values)
    assert ("platform receptance in band" in checks) == (band is not None)
    P = np.stack(np.meshgrid(m["x"], m["y"], m["z"], indexing="ij"), -1).reshape(-1, 3)
    flat = m.stack(pose=("x", "y", "z"))
    assert 0 < int(m["feasible"].sum()) < len(P)
    for i, x in enumerate(P):
        res = design_checks(robot, x, **kw)
        p = flat.isel(pose=i)
        verdicts = res.verdicts
        assert [verdicts[c] == "pass" for c in checks] == p["passed"].values.tolist()
        assert [verdicts[c] == "unknown" for c in checks] == p["unknown"].values.tolist()
        assert bool(p["dynamic"]) == all(verdicts[c] == "pass" for c in checks)
        if res.platform is None:
            assert not bool(p["feasible"])
            continue
        assert float(p["first_platform_hz"]) == pytest.approx(res.platform.first_hz,
                                                              rel=1e-9)
        from dynstiff.analyses.checks import check_options
        margin = _band_margin(res.platform, check_options(band))
        if band is None:
            assert np.isnan(float(p["band_margin"])) and np.isnan(margin)
        else:
            assert float(p["band_margin"]) == pytest.approx(margin, rel=1e-9, abs=1e-12)
            # the definition (theory.md §13.2), written out: above f / f_hi - 1, below
            # 1 - f / f_lo (none below a band from 0 Hz), the least over the held modes
            md = res.platform.modes
            f = md.freq_hz[md.platform_share >= 0.05]
            lo, hi = band
            below = 1 - f / lo if lo > 0 else np.full(f.size, -np.inf)
            assert margin == pytest.approx(np.min(np.maximum(f / hi - 1, below)), rel=1e-12)
        sag = p["sag_ratio"].values
        assert np.all(np.isfinite(sag)) and np.all(sag > 0)
        local = np.asarray(res.platform.modes.kind) == "local"
        gap = float(p["proximity_gap"])       # stored within proximity_rtol, else NaN
        if res.platform.complete and local.any():
            f = res.platform.modes.freq_hz
            fp = f[res.platform.index]
            expect = np.min(np.abs(f[local][None] - fp[:, None]) / fp[:, None])
            if expect <= 0.03:
                assert gap == pytest.approx(expect, rel=1e-9)
            else:
                assert np.isnan(gap)


def test_grid_with_a_cable_parameter_and_chunking_that_does_not_matter(robot):
    """A 2 x 1 x 2 grid x 2 orientations x 2 moduli: dimensions and coordinates in order; a
    stiffer cable raises every first platform frequency; chunks of 1 (cold statics at every
    pose) give the warm-started chunk of 8 to 1e-8."""
    kw = {"box": (-1.0, 1.0, 0.0, 0.0, 1.0, 3.0), "step": 2.0, "n_modes": 4,
              "orientations": [[0, 0, 0], [0, 0, 0.1]], "parameter": "EA",
              "values": [1.39487e5, 2.0e5], "band_hz": BAND}
    a = workspace(robot, chunk_size=8, **kw)
    b = workspace(robot, chunk_size=1, **kw)
    assert dict(a.sizes) == {"x": 2, "y": 1, "z": 2, "orientation": 2, "parameter": 2, "mode": 4,
                                 "cable": 8, "check": len(CHECKS), "component": 3}
    assert a["feasible"].dims == ("x", "y", "z", "orientation", "parameter")
    np.testing.assert_array_equal(a["x"], [-1.0, 1.0])
    f = a["first_platform_hz"]
    assert np.all(f.isel(parameter=1) > 1.05 * f.isel(parameter=0))
    xr.testing.assert_allclose(a[["freq", "tension"]], b[["freq", "tension"]], rtol=1e-8)


def test_box_grid_axes():
    x, y, z = box_grid((0.0, 1.0, -1.0, 1.0, 2.0, 2.0), 0.5)
    np.testing.assert_allclose(x, [0.0, 0.5, 1.0])
    np.testing.assert_allclose(y, [-1.0, -0.5, 0.0, 0.5, 1.0])
    np.testing.assert_allclose(z, [2.0])
    np.testing.assert_allclose(box_grid((0.0, 1.0, 0, 0, 0, 0), 0.3)[0], [0.0, 0.3, 0.6, 0.9])
    np.testing.assert_array_equal(box_grid(np.arange(6), 1.0)[2], [4.0, 5.0])   # integers
    for bad in (["0", "1", "0", "1", "0", "1"], [True, True, 0, 1, 0, 1], [0, 1, 0, 1, 0, None]):
        with pytest.raises(ds.InvalidParameterError, match="box must be 6 numbers"):
            box_grid(bad, 0.5)


@pytest.mark.parametrize("kw, match", [
    ({"poses": None}, "exactly one of poses"),
    ({"box": (0, 1, 0, 1, 1, 2)}, "step"),
    ({"box": (1, 0, 0, 1, 1, 2), "step": 0.5}, "box must be"),
    ({"box": (0, 1, 0, 1, 1, 2), "step": -1.0}, "step"),
    ({"poses": [[0, 0, 1]], "parameter": "E"}, "parameter and values|go together"),
    ({"poses": [[0, 0, 1]], "parameter": "E", "values": [1.0]}, "cable field"),
    ({"poses": [[0, 0, 1]], "parameter": "EA", "values": [-1.0]}, "EA"),
    ({"poses": [[0, 0, 1]], "n_modes": 0}, "n_modes"),
    ({"poses": [[0, 0, 1]], "chunk_size": 2.5}, "chunk_size"),
    ({"poses": [[0, 0, 1]], "band_hz": (2.0, 1.0)}, "band_hz"),
    ({"poses": [[0, 0, 1]], "rung": "beam"}, "rung"),
    ({"poses": [[0, 0, 1]], "workers": 0}, "workers"),
    ({"poses": [[0, 0, 1]], "progress": "no"}, "progress must be True or False, got 'no'"),
    ({"poses": [], }, "at least one pose"),
    # options checked before the first pose: never a map of "infeasible" poses
    ({"poses": [[0, 0, 1]], "rung": "exact", "fmax_hz": -1.0}, "fmax_hz must be > 0"),
    ({"poses": [[0, 0, 1]], "rung": "exact", "fmax_hz": float("nan")}, "fmax_hz must be fin"),
    ({"poses": [[0, 0, 1]], "rung": "exact", "fmax_hz": True}, "fmax_hz must be a number"),
    ({"poses": [[0, 0, 1]], "fmax_hz": 10.0}, r"\['fmax_hz'\] do not apply to rung 'dsm'"),
    ({"poses": [[0, 0, 1]], "cable_loss_factor": 1.5}, r"cable_loss_factor .*\[0, 1\)"),
    ({"poses": [[0, 0, 1]], "rung": "lumped", "segments": 0}, "segments must be an integer"),
    ({"poses": [[0, 0, 1]], "n_modes": 30000}, "n_modes must be at most max_modes=2000"),
    ({"poses": [[0, 0, 1]], "n_modes": True}, "n_modes must be an integer"),
    ({"box": (0, 1, 0, 1, 1, 2), "step": True}, "step must be a number > 0"),
    ({"box": (0, 1, 0, 1, 1, 2), "step": 0.5, "orientations": np.zeros((3, 2))},
     r"orientations .*shape \(n, 3\).*got shape \(3, 2\)"),
    ({"box": (0, 1, 0, 1, 1, 2), "step": 0.5, "orientations": np.zeros((2, 3, 1))},
     r"got shape \(2, 3, 1\)"),
    ({"poses": [[0, 0, 1]], "parameter": "EA", "values": [True]}, "values must be"),
    ({"box": (-6, 6, -4, 4, 0, 5), "step": 0.001}, r"more than 10000: raise step= \(--step\)"),
    ({"box": (-6, 6, -4, 4, 0, 5), "step": 0.05}, r"3,918,901 poses, more than max_poses="),
    ({"box": (-6, 6, -4, 4, 0, 5), "step": 0.002, "max_poses": None}, r"GiB of memory \(this"),
    # the uncertain row: its settings and parameters checked before the first pose
    ({"poses": [[0, 0, 1]], "uncertain": {"EA": "10%"}}, "uncertain= needs band_hz"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EB": "10%"}}, "EB"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EA": "ten"}}, "ten"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {}}, "non-empty dict"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EA": "10%"}, "n_samples": 0},
     "n_samples must be an integer >= 1"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EA": "10%"}, "seed": True},
     "seed must be an integer >= 0, got True"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EA": "10%"}, "seed": -1},
     "seed must be an integer >= 0, got -1"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EA": "10%"}, "confidence": 1.0},
     r"confidence must be a number in \(0, 1\)"),
    ({"poses": [[0, 0, 1]], "band_hz": BAND, "uncertain": {"EA": "10%"},
      "tensions": "max-frequency"}, "default tensions"),
])
def test_bad_arguments_are_named(robot, kw, match):
    with pytest.raises(ds.InvalidParameterError, match=match):
        workspace(robot, **kw)


@pytest.mark.integration
def test_local_processes_and_a_dask_cluster_give_the_serial_dataset(robot):
    """Two worker processes (concurrent.futures) and a real dask.distributed LocalCluster
    with 2 worker processes return the serial Dataset (1e-12), recorded failures included."""
    distributed = pytest.importorskip("distributed")
    kw = {"box": (-6.0, 6.0, -4.0, 4.0, 1.0, 1.0), "step": 4.0, "n_modes": 4, "band_hz": BAND,
              "chunk_size": 4}
    serial = workspace(robot, **kw)
    assert not serial["feasible"].all() and serial["feasible"].any()
    procs = workspace(robot, workers=2, **kw)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = workspace(robot, client=client, **kw)
    for other in (procs, dask):
        xr.testing.assert_allclose(serial, other, rtol=1e-12, atol=0)
        np.testing.assert_array_equal(serial["reason"].values, other["reason"].values)
        np.testing.assert_array_equal(serial["feasible"].values, other["feasible"].values)
    assert dask.attrs["engine"] == "dask"


# the closed form's robot-level bound warns at CoGiRo's edge poses (theory.md §11.6)
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
def test_fast_statics_give_the_numbers_of_the_previous_path(robot, monkeypatch):
    """A 5 x 4 x 3 grid of CoGiRo poses over the frame (edges, infeasible poses and active
    tension limits included), warm-started along chunks, with the compiled fixed point
    (compiled Newton, warm active set, theory.md §13.6) against the numpy loop with the
    numpy Newton and LP-started tension distributions: the same feasibility, reasons and
    verdicts; tensions, lengths, sag,
    frequencies and margins to 1e-12; participation to 1e-7, the accuracy of its
    finite-difference derivative (§13.3), which magnifies round-off."""
    from dynstiff.analyses.checks import check_options
    from dynstiff.maps.workspace import evaluate_chunk
    from dynstiff.robot import statics
    options = check_options(BAND)
    grid = np.stack(np.meshgrid(np.linspace(-5.0, 5.0, 5), np.linspace(-3.5, 3.5, 4),
                                np.linspace(0.5, 3.0, 3), indexing="ij"), -1).reshape(-1, 3)
    X = np.hstack([grid, np.zeros_like(grid)])

    def run():
        parts = [evaluate_chunk(robot, X[s:s + 12], 12, options, "dsm", ds.Damping(), {},
                                CHECKS) for s in range(0, len(X), 12)]
        return {k: ([r for p in parts for r in p[k]] if k == "reason"
                    else np.concatenate([p[k] for p in parts])) for k in parts[0]}
    fast = run()
    batched, dist = statics.taut_catenaries, statics._distribution
    monkeypatch.setattr(statics, "taut_catenaries",
                        lambda *a, **k: batched(*a, **{**k, "compiled": False}))
    monkeypatch.setattr(statics, "_distribution",
                        lambda W, w, lo, hi, r=None, sides=None: dist(W, w, lo, hi, r,
                                                                      warm=False))
    monkeypatch.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)  # numpy loop
    ref = run()
    assert 0 < ref["feasible"].sum() < len(X)
    assert np.sum(np.isclose(ref["min_tension"], robot.tension_limits[0], rtol=1e-9)) > 5
    assert fast["reason"] == ref["reason"]
    for k in ("feasible", "is_platform", "passed", "unknown"):
        np.testing.assert_array_equal(fast[k], ref[k])
    for k in ("tension", "unstretched_length", "min_tension", "max_tension", "sag_ratio",
              "freq", "first_platform_hz"):
        np.testing.assert_allclose(fast[k], ref[k], rtol=1e-12, atol=0, err_msg=k)
    for k in ("band_margin", "proximity_gap"):
        np.testing.assert_allclose(fast[k], ref[k], rtol=0, atol=1e-12, err_msg=k)
    np.testing.assert_allclose(fast["platform_share"], ref["platform_share"], rtol=0,
                               atol=1e-7)


def test_max_frequency_tensions_map_the_optimal_distribution(robot):
    """tensions="max-frequency": every pose's equilibrium is the frequency-optimal
    distribution (theory.md §16.7), warm-started along the chunk; its first platform mode
    is the optimum's and not below the default map's."""
    from dynstiff.analyses.optimal_tensions import optimal_tensions
    poses = [[4.0, -2.5, 1.0], [3.8, -2.5, 1.0]]
    opt = workspace(robot, poses, n_modes=4, tensions="max-frequency")
    base = workspace(robot, poses, n_modes=4)
    assert opt.attrs["tensions"] == "max-frequency"
    assert np.all(opt["first_platform_hz"].values >= base["first_platform_hz"].values - 1e-9)
    single = optimal_tensions(robot, poses[0])
    assert float(opt["first_platform_hz"][0]) == pytest.approx(single.value, rel=1e-6)
    assert opt["min_tension"].values.min() >= robot.tension_limits[0] - 1e-6
    with pytest.raises(ds.InvalidParameterError, match="tensions must be one of"):
        workspace(robot, poses, tensions="optimal")


def test_a_warm_start_that_fails_is_retried_cold_under_the_optimal_tensions(robot,
                                                                             monkeypatch):
    """Under the frequency-optimal tensions a pose whose warm start (the last feasible
    pose's equilibrium) fails is solved again from no start, and the map equals the one
    with every pose started cold (chunks of one pose); under the default tensions the
    failure is the pose's (their statics retry cold themselves)."""
    import dynstiff.maps.workspace as ws
    from dynstiff.errors import ConvergenceError
    real, starts = ws.tension_equilibrium, []

    def warm_fails(robot, pose, tensions, start, rung, **kw):
        starts.append(start is not None)
        models.append((rung, kw))
        if start is not None:
            raise ConvergenceError("planted: the warm start fails")
        return real(robot, pose, tensions, start, rung, **kw)

    poses, models = [[4.0, -2.5, 1.0], [3.8, -2.5, 1.0]], []
    opts = {"tensions": "max-frequency", "chordwise_inertia": False}
    cold = workspace(robot, poses, n_modes=4, chunk_size=1, **opts)
    monkeypatch.setattr(ws, "tension_equilibrium", warm_fails)
    opt = workspace(robot, poses, n_modes=4, chunk_size=2, **opts)
    assert starts == [False, True, False]
    assert models == [("dsm", {"chordwise_inertia": False})] * 3      # the map's own model
    assert opt["feasible"].values.all()
    for k in ("tension", "freq", "first_platform_hz", "passed"):
        np.testing.assert_array_equal(opt[k].values, cold[k].values, err_msg=k)
    starts.clear()
    base = workspace(robot, poses, n_modes=4, chunk_size=2, chordwise_inertia=False)
    assert starts == [False, True]
    assert list(base["feasible"].values) == [True, False]
    assert "planted: the warm start fails" in str(base["reason"].values[1])


def test_the_uncertain_row_of_a_map_is_the_design_checks_at_every_pose(robot):
    """The platform mass known to 10 %: at each pose the map's probability, margin at 95 %
    and verdict are those of design_checks with the same uncertainties, sample and seed
    (two poses whose nominal margin passes fail the uncertain row, one passes it), and the
    dynamic workspace holds the row."""
    from dynstiff.analyses.uncertainty import UNCERTAIN_CHECK
    poses = [[4.0, -3.0, 1.0], [-2.0, -1.0, 1.0], [-4.0, -3.0, 1.5]]
    kw = {"band_hz": BAND, "uncertain": {"mass": "10%"}, "n_samples": 24, "seed": 3}
    m = workspace(robot, poses, n_modes=3, chunk_size=2, **kw)
    assert m["check"].values.tolist()[-1] == UNCERTAIN_CHECK
    assert m.attrs["uncertain"] == "mass sigma 10 % (normal)" and m.attrs["n_samples"] == 24
    verdicts = []
    for k, pose in enumerate(poses):
        res = design_checks(robot, pose, **kw)
        row = res.rows[-1]
        assert row["check"] == UNCERTAIN_CHECK
        assert m["uncertain_probability"].values[k] == row["value"]
        q = res.uncertainty.quantile("band_margin", 1.0 - 0.95)
        assert m["uncertain_margin"].values[k] == q
        assert bool(m["passed"].values[k, -1]) == (row["verdict"] == "pass")
        assert bool(m["dynamic"].values[k]) == res.passed
        verdicts.append((row["verdict"], res.verdicts["platform modes outside band"]))
    assert verdicts == [("fail", "pass"), ("pass", "pass"), ("fail", "pass")]
    frame = m.dynstiff.to_frame()
    assert {"uncertain_probability", f"check: {UNCERTAIN_CHECK}"} <= set(frame.columns)


def test_the_maps_settings_are_its_attributes(robot):
    m = workspace(robot, [[0.0, 0.0, 1.0]], n_modes=2, band_hz=BAND)
    a = m.attrs
    for key, value in (("n_modes", 2), ("max_sag_ratio", 0.02), ("participation", 0.05),
                       ("frf_limit", 10.0), ("max_modes", 2000), ("rung", "dsm"),
                       ("n_samples", 0), ("model_rtol", 0.01), ("margin", 0.05),
                       ("proximity_rtol", 0.03), ("seed", 0)):
        assert a[key] == value, key
    np.testing.assert_array_equal(a["band_hz"], BAND)
    np.testing.assert_array_equal(a["model_band_hz"], [0.0, 20.0])
    from dynstiff.analyses.verdicts import equilibrium_sag_ratios
    eq = robot.equilibrium(pose=[0.0, 0.0, 1.0])
    np.testing.assert_allclose(m["sag_ratio"].values[0], equilibrium_sag_ratios(robot, eq),
                               rtol=1e-9)


def test_the_estimate_is_one_line_on_stderr(robot, capsys):
    workspace(robot, [[0.0, 0.0, 1.0], [0.5, 0.0, 1.0]], n_modes=2, progress=True)
    err = capsys.readouterr().err
    line = err.split("\n")[0]
    assert line.startswith("workspace: 2 poses, about ") and line.endswith("in a sample)")
    from dynstiff.maps.guards import _gib, map_bytes  # the 5 checks without a band
    assert f"about {_gib(map_bytes(2, 8, 2, 5))}, about " in line


def test_the_model_band_given_is_the_maps(robot):
    """model_band_hz reaches the checks (the cable-model row's band) and the attributes."""
    m = workspace(robot, [[0.0, 0.0, 1.0]], n_modes=2, model_band_hz=(0.0, 8.0))
    np.testing.assert_array_equal(m.attrs["model_band_hz"], [0.0, 8.0])
    res = design_checks(robot, [0.0, 0.0, 1.0], model_band_hz=(0.0, 8.0))
    row = next(r for r in res.rows if r["check"] == "cable model")
    assert "8 Hz" in row["detail"]


def test_the_estimate_times_five_poses_and_the_bar_counts_every_pose(robot, monkeypatch):
    """With progress: one pose warms up, five poses spread over the list (first, last and
    evenly between) are timed for the estimate, then every chunk runs; the bar is a
    'workspace' bar in poses whose count reaches the total."""
    import tqdm

    import dynstiff.maps.workspace as ws
    calls, bars = [], []
    real = ws.evaluate_chunk

    def spy(robot, poses, *args, **kw):
        calls.append(np.array(poses))
        return real(robot, poses, *args, **kw)

    class Bar:
        def __init__(self, **kw):
            self.kw, self.n, self.total, self.closed = kw, 0, kw["total"], False
            bars.append(self)

        def update(self, n):
            self.n += n

        def close(self):
            self.closed = True

    monkeypatch.setattr(ws, "evaluate_chunk", spy)
    monkeypatch.setattr(tqdm, "tqdm", Bar)
    poses = [[x, 0.0, 1.0] for x in np.linspace(-1.0, 1.0, 12)]
    workspace(robot, poses, n_modes=2, chunk_size=5, progress=True)
    X = np.array(poses)
    assert [len(c) for c in calls] == [1, 5, 5, 5, 2]
    np.testing.assert_array_equal(calls[1][:, :3], X[[0, 3, 6, 8, 11]])
    (bar,) = bars
    assert bar.kw["desc"] == "workspace" and bar.kw["unit"] == "pose"
    assert bar.total == 12 and bar.n == 12 and bar.closed


def test_a_failure_of_the_modes_is_the_poses_reason(robot, monkeypatch):
    """A model or mode search that fails at a pose (planted) leaves that pose out of the
    dynamic workspace with the failure as its reason and its checks unknown; the other
    poses keep their verdicts."""
    import dynstiff.maps.workspace as ws
    from dynstiff.errors import ConvergenceError
    real = ws.build_model

    def fails_high(eq, rung, **kw):
        if eq.pose.position[2] > 1.2:
            raise ConvergenceError("planted: no modes here")
        return real(eq, rung, **kw)

    monkeypatch.setattr(ws, "build_model", fails_high)
    m = workspace(robot, [[0.0, 0.0, 1.0], [0.0, 0.0, 1.5]], n_modes=2, band_hz=BAND)
    assert list(m["feasible"].values) == [True, False]
    assert str(m["reason"].values[1]).endswith("planted: no modes here")
    assert m["unknown"].values[1].any() and not m["passed"].values[1].any()
    assert m["passed"].values[0].all()


def test_an_interrupted_map_resumes_to_the_whole_map(robot, tmp_path, monkeypatch):
    """Ctrl-C (planted in task 2) stops the map counting the poses saved of the total;
    resume=True reads the saved task, computes only the other and gives the whole map."""
    import dynstiff.maps.workspace as ws
    kw = {"poses": [[0, 0, 1.0], [0.5, 0, 1.0], [1.0, 0, 1.0]], "n_modes": 2, "chunk_size": 2}
    whole, real, calls = workspace(robot, **kw), ws.evaluate_chunk, []

    def planted(rob, X, *a):
        calls.append(len(X))
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(rob, X, *a)
    monkeypatch.setattr(ws, "evaluate_chunk", planted)
    with pytest.raises(ds.errors.Interrupted, match="2 of 3 poses saved") as stop:
        workspace(robot, checkpoint=tmp_path / "m.parts", **kw)
    assert (stop.value.saved, stop.value.total) == (2, 3)
    m = workspace(robot, checkpoint=tmp_path / "m.parts", resume=True, **kw)
    assert calls == [2, 1, 1]
    xr.testing.assert_equal(m, whole)            # every variable (not the run's attributes)


def test_the_tasks_are_submitted_to_the_client_given(robot):
    """client=: each task goes to client.submit (a stub that refuses it: no cluster)."""
    pytest.importorskip("distributed")

    class Client:
        def submit(self, fn, rob, X, *a, pure=True):
            raise RuntimeError(f"planted: {fn.__name__} of {len(X)} poses, pure={pure}")
    with pytest.raises(RuntimeError, match="planted: evaluate_chunk of 1 poses, pure=False"):
        workspace(robot, [[0.0, 0.0, 1.0]], n_modes=2, client=Client())
