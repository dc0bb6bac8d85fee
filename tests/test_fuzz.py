"""Hostile input at every entry point, with one rule as the oracle: a call returns a result
whose numbers are finite (inf only at an exact pole, with a PoleWarning), or it raises a
typed dynstiff error that names the offending argument. Anything else (a raw ValueError,
TypeError, OverflowError, LinAlgError, a NaN in a result, a traceback from the command line)
is a failure.

Each fuzzer runs a few dozen examples in the default tier and thousands in the slow tier
(``-m slow``: 25,500 examples in all). The workspace options, the calibration, the readers
and writers of files and the output paths of the command line add one more rule: on an
error, no file is changed.
"""

import contextlib
import functools
import io
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.analyses.checks import design_checks
from dynstiff.cli import main
from dynstiff.errors import DynstiffError, PoleWarning

FAST, LONG = 25, 2500

# values a hostile user might pass where a number, a vector or a count is expected
weird_scalars = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-1e3, 1e3), st.integers(-10**20, 10**20), st.booleans(), st.none(),
    st.text(max_size=4), st.complex_numbers(allow_nan=True, allow_infinity=True),
    st.lists(st.floats(-10, 10), max_size=4))
weird_vectors = st.one_of(
    weird_scalars, st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=3,
                            max_size=3),
    st.lists(st.floats(-20, 20), min_size=3, max_size=3), st.lists(st.text(max_size=2),
                                                                  min_size=3, max_size=3))


def _settings(n):
    return settings(max_examples=n, deadline=None, derandomize=n == FAST,
                    suppress_health_check=[HealthCheck.too_slow,
                                           HealthCheck.function_scoped_fixture])


def _all_finite(result):
    """Every number reachable in ``result`` (arrays, dataclass fields, tuples) is finite."""
    if isinstance(result, (np.ndarray, float, int, complex, np.number)):
        arr = np.asarray(result)
        return arr.dtype.kind not in "fc" or bool(np.all(np.isfinite(arr)))
    if isinstance(result, (list, tuple)):
        return all(_all_finite(r) for r in result)
    fields = getattr(result, "__dataclass_fields__", None)
    if fields:
        return all(_all_finite(getattr(result, f)) for f in fields
                   if isinstance(getattr(result, f), (np.ndarray, float, int, complex, tuple)))
    return True


def obey_the_rule(fn, names):
    """Call ``fn``; a dynstiff error must name one of ``names``; a result must be finite
    unless a PoleWarning said why."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = fn()
        except DynstiffError as exc:
            text = str(exc)
            assert any(n in text for n in names), f"error does not name {names}: {text}"
            assert isinstance(exc, (ValueError, RuntimeError, TypeError)), type(exc)
            return None
    if not any(issubclass(w.category, PoleWarning) for w in caught):
        assert _all_finite(result), f"non-finite result without a PoleWarning: {result!r}"
    return result


# --------------------------------------------------------------------------- one cable
def _cable_fuzzer(n):
    @_settings(n)
    @given(mass=weird_scalars, EA=weird_scalars, anchor=weird_vectors, end=weird_vectors,
           L0=weird_scalars, omega=st.one_of(weird_scalars, st.floats(0, 1e9)),
           n_modes=weird_scalars)
    def check(mass, EA, anchor, end, L0, omega, n_modes):
        cable = obey_the_rule(lambda: ds.Cable(mass, EA), ("mass_per_length", "EA"))
        if cable is None:
            return
        state = obey_the_rule(lambda: ds.solve_catenary(anchor, end, L0, cable),
                              ("anchor", "end", "unstretched_length", "slack", "converge"))
        if state is None:
            return
        obey_the_rule(lambda: ds.cable_dynamic_stiffness(state, omega), ("omega",))
        obey_the_rule(lambda: ds.cable_mode_count(state, omega), ("omega",))
        obey_the_rule(lambda: ds.cable_natural_frequencies(state, n_modes), ("n_modes",))
    return check


test_cable_entry_points = _cable_fuzzer(FAST)
test_cable_entry_points_long = pytest.mark.slow(_cable_fuzzer(LONG))


# ------------------------------------------------------------------------- the robot
@pytest.fixture(scope="module")
def planar():
    scene = ds.load_scene("planar2")
    eq = scene.equilibrium()
    return scene, eq, {r: ds.build_model(eq, r, **({"segments": 4} if r == "lumped" else {}))
                       for r in ds.RUNGS}


def _model_fuzzer(n):
    @_settings(n)
    @given(rung=st.sampled_from(ds.RUNGS), n_modes=weird_scalars, fmax_hz=weird_scalars,
           omega=st.one_of(weird_scalars, st.lists(st.floats(0, 1e3), max_size=3)),
           inputs=st.one_of(st.none(), st.sampled_from(["fx", "fz", "mz", "q"]),
                            st.lists(st.sampled_from(["fx", "fz", "fq"]), max_size=3)),
           kind=st.sampled_from(["receptance", "mobility", "accelerance", "inertance"]),
           point=st.one_of(st.none(), weird_vectors))
    def check(planar, rung, n_modes, fmax_hz, omega, inputs, kind, point):
        model = planar[2][rung]
        obey_the_rule(lambda: ds.eigenfrequencies(model, n_modes=n_modes, fmax_hz=fmax_hz),
                      ("n_modes", "fmax_hz"))
        obey_the_rule(lambda: ds.frf(model, omega, inputs=inputs, kind=kind, point=point),
                      ("omega", "inputs", "kind", "point"))
        obey_the_rule(lambda: ds.mode_count(model, omega), ("omega",))
    return check


test_model_entry_points = _model_fuzzer(FAST)
test_model_entry_points_long = pytest.mark.slow(_model_fuzzer(LONG))


def _statics_fuzzer(n):
    @_settings(n)
    @given(pose=weird_vectors, lengths=st.one_of(weird_vectors, st.lists(
        st.floats(0, 40), min_size=2, max_size=2)), tol=weird_scalars, margin=weird_scalars,
        sag=weird_scalars)
    def check(planar, pose, lengths, tol, margin, sag):
        scene, eq, _ = planar
        rob = scene.robot
        obey_the_rule(lambda: rob.equilibrium(pose=pose), ("pose", "slack", "tension",
                                                            "workspace", "converge"))
        obey_the_rule(lambda: rob.equilibrium(unstretched_lengths=lengths,
                                              initial_pose=scene.pose),
                      ("unstretched_length", "slack", "converge", "residual"))
        obey_the_rule(lambda: rob.equilibrium(pose=scene.pose, tol=tol), ("tol",))
        obey_the_rule(lambda: design_checks(rob, scene.pose, margin=margin,
                                            max_sag_ratio=sag, model_band_hz=(0.0, 2.0)),
                      ("margin", "max_sag_ratio"))
    return check


test_statics_and_checks = _statics_fuzzer(FAST)
test_statics_and_checks_long = pytest.mark.slow(_statics_fuzzer(LONG))


def _robot_fuzzer(n):
    three = st.lists(weird_vectors, min_size=3, max_size=3)
    @_settings(n)
    @given(anchors=st.one_of(weird_vectors, three), attachments=st.one_of(weird_vectors, three),
           limits=weird_vectors, mass=weird_scalars, com=weird_vectors,
           inertia=st.one_of(weird_vectors, st.lists(weird_vectors, min_size=3, max_size=3)),
           dofs=st.one_of(st.text(max_size=3), st.lists(
               st.sampled_from(["x", "y", "z", "rx", "q", ""]), max_size=4)))
    def check(anchors, attachments, limits, mass, com, inertia, dofs):
        platform = obey_the_rule(
            lambda: ds.Platform(mass, center_of_mass=com, inertia=inertia, free_dofs=dofs),
            ("mass", "center_of_mass", "inertia", "free_dofs"))
        platform = platform or ds.Platform(10.0, free_dofs=("x", "y", "z"))
        obey_the_rule(lambda: ds.Robot(anchors, attachments, ds.Cable(0.1, 1e5), platform,
                                       tension_limits=limits) and None,
                      ("anchors", "attachments", "tension_limits", "cables"))
    return check


test_robot_and_platform = _robot_fuzzer(FAST)
test_robot_and_platform_long = pytest.mark.slow(_robot_fuzzer(LONG))


@pytest.fixture(scope="module")
def cogiro_model():
    return ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())


def _options_fuzzer(n):
    from dynstiff.io.exchange import uff58_records
    from dynstiff.lumped import TimeDamping
    from dynstiff.timedomain.trajectory import circle
    calls = {
        "relative": lambda m, v: ds.Uncertain(0.1, relative=v),
        "scale": lambda m, v: ds.Uncertain(v),
        "axial": lambda m, v: TimeDamping(axial=v),
        "sigma_hz": lambda m, v: ds.MeasuredModes([1.0, 2.0], sigma_hz=v),
        "chordwise_inertia": lambda m, v: ds.FrequencyModel(m.equilibrium,
                                                            chordwise_inertia=v),
        "binary": lambda m, v: uff58_records(_FRF(m), binary=v),
        "node": lambda m, v: uff58_records(_FRF(m), node=v),
        "entity": lambda m, v: uff58_records(_FRF(m), entity=v),
        "residual": lambda m, v: ds.modal_model(m, n_modes=2, residual=v),
        "tol": lambda m, v: ds.damped_modes(m, n_modes=1, tol=v),
        "k": lambda m, v: ds.cable_fields(m, _MODES(m), v),
        "band_hz": lambda m, v: ds.recommend_model(m.equilibrium, band_hz=v),
        "t": lambda m, v: ds.WaypointPath([0, 1.0], [[0, 0, 1], [0, 0, 1.1]],
                                          np.zeros((2, 3))).at(v),
        "start_angle": lambda m, v: circle([0, 0, 1], 1.0, 0.5, start_angle=v),
    }

    @_settings(n)
    @given(which=st.sampled_from(sorted(calls)), value=st.one_of(weird_scalars, weird_vectors))
    def check(cogiro_model, which, value):
        # the option named as the subject of the error ("t must ..."), not a letter of it
        obey_the_rule(lambda: calls[which](cogiro_model, value), (f"{which} must",))
    return check


@functools.cache
def _FRF(m):
    return ds.frf(m, [1.0, 2.0], inputs="fz", outputs="z")


@functools.cache
def _MODES(m):
    return ds.modes(m, n_modes=3)


test_options_of_the_analyses = _options_fuzzer(FAST)
test_options_of_the_analyses_long = pytest.mark.slow(_options_fuzzer(1000))


# ---------------------------------------------------------------------- scene files
KEYS = ["mass", "EA", "mass_per_length", "anchor", "attachment", "free_dofs", "g",
        "position", "band_hz", "n_modes", "min", "inertia"]


def _toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "").replace('"', "") + '"'
    if isinstance(v, float) and not np.isfinite(v):
        return "nan" if np.isnan(v) else ("inf" if v > 0 else "-inf")
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if v is None or isinstance(v, complex):
        return '"none"'
    return repr(v)


def _scene_fuzzer(n):
    @_settings(n)
    @given(key=st.sampled_from(KEYS), value=weird_vectors)
    def check(tmp_path_factory, key, value):
        text = (ds.scenes.loader.SCENE_DIR / "planar2.toml").read_text()
        lines = text.splitlines()
        for i, line in enumerate(lines):
            if line.split("=")[0].strip() == key:
                lines[i] = f"{key} = {_toml_value(value)}"
                break
        else:
            lines.append(f"{key} = {_toml_value(value)}")
        p = tmp_path_factory.mktemp("scene") / "fuzz.toml"
        p.write_text("\n".join(lines) + "\n")
        scene = obey_the_rule(lambda: ds.load_scene(p), (str(p),))
        if scene is not None and scene.pose is not None:
            obey_the_rule(scene.equilibrium, ("pose", "slack", "tension", "converge",
                                              "workspace"))
    return check


test_scene_files = _scene_fuzzer(FAST)
test_scene_files_long = pytest.mark.slow(_scene_fuzzer(LONG))


# ---------------------------------------------------------------------- command line
OPTION_VALUES = st.one_of(st.sampled_from(["nan", "-1", "0", "1e9", "inf", "2", "x", "",
                                           "/", "-", "a.xyz", "0.5"]),
                          st.floats(-10, 10).map(repr))


def _cli_fuzzer(n):
    @_settings(n)
    @given(command=st.sampled_from(["modes", "frf", "check", "sweep", "simulate", "demo",
                                    "scenes", "nope"]),
           options=st.lists(st.tuples(st.sampled_from(
               ["-n", "--fmax", "--points", "--band", "--forbidden-band", "--margin",
                "--max-sag", "--pose", "--lengths", "--csv", "--plot", "--time", "--dt",
                "--segments", "--steps", "--bogus"]), OPTION_VALUES), max_size=3))
    def check(command, options):
        argv = [command] + (["planar2"] if command not in ("demo", "scenes", "nope") else [])
        for opt, val in options:
            argv += [opt, val]
            if opt in ("--band", "--forbidden-band", "--pose"):
                argv += ["0.0", "-10.0"] if opt == "--pose" else ["1.0"]
        if command in ("simulate", "demo") and "--time" not in argv:
            return                   # the long runs are exercised elsewhere
        err, out = io.StringIO(), io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            code = main(argv)
        assert code in (0, 1, 2), code
        if code == 2:
            lines = err.getvalue().splitlines()
            assert len(lines) == 1 and lines[0].startswith("dynstiff: error: "), err.getvalue()
    return check


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)             # any file a command line writes stays here


test_command_line = _cli_fuzzer(FAST)
test_command_line_long = pytest.mark.slow(_cli_fuzzer(1000))



# ------------------------------------------------------------- workspace and calibration
counts = st.one_of(weird_scalars, st.integers(-2, 5))
orientation_arrays = st.one_of(
    st.none(), weird_vectors, st.sampled_from([np.zeros((3, 2)), np.zeros((2, 3)),
                                               np.zeros((1, 3, 1)), np.zeros((0, 3)),
                                               np.array([[0, 0, 0.1]]), [[0, 0, np.nan]]]))


def _workspace_fuzzer(n):
    @_settings(n)
    @given(step=weird_scalars, n_modes=counts, chunk_size=counts, max_poses=counts,
           orientations=orientation_arrays, rung=st.sampled_from(["dsm", "spring", "exact"]),
           option=st.sampled_from(["fmax_hz", "guard_rtol", "cable_loss_factor", "tension",
                                   "order", None]), value=weird_scalars,
           values=st.one_of(st.none(), weird_vectors))
    def check(robot, step, n_modes, chunk_size, max_poses, orientations, rung, option, value,
              values):
        kw = {} if option is None else {option: value}
        if rung == "exact" and option not in (None, "fmax_hz"):
            return                          # the exact rung's poses are mapped elsewhere
        if rung == "exact":
            kw["fmax_hz"] = -1.0 if option is None else value   # refused, or mapped quickly
        names = ["step", "n_modes", "chunk_size", "max_poses", "orientations", "values",
                 "box", "poses", "EA", *kw]
        ds_ = obey_the_rule(lambda: ds.workspace(
            robot, box=(0.0, 0.0, 0.0, 0.0, -10.0, -10.0), step=step, n_modes=n_modes,
            chunk_size=chunk_size, max_poses=max_poses, orientations=orientations,
            parameter=None if values is None else "EA", values=values, max_modes=5,
            rung=rung, **kw), names)
        if ds_ is not None:
            feasible = ds_["feasible"].values
            assert np.all(np.isfinite(ds_["tension"].values[feasible]))
            assert ds_["feasible"].size <= (max_poses if isinstance(max_poses, int) else 1e9)
    return check


@pytest.fixture(scope="module")
def robot():
    return ds.load_scene("planar2").robot


test_workspace_options = _workspace_fuzzer(FAST)
test_workspace_options_long = pytest.mark.slow(_workspace_fuzzer(1500))


def _calibration_fuzzer(n):
    @_settings(n)
    # frequencies up to 8 Hz: a measured mode at kHz asks the model for thousands of
    # modes (refused beyond max_modes, but only after they are counted)
    @given(freq=st.one_of(weird_vectors.filter(lambda v: not isinstance(v, (int, float))
                                               or isinstance(v, bool) or not abs(v) > 8),
                          st.lists(st.floats(0.5, 5.0), min_size=1, max_size=3)),
           parameters=st.one_of(st.sampled_from(["EA", "mass_per_length", "platform_mass",
                                                 ("EA", "EA"), "stiffness", ()]),
                                weird_scalars),
           confidence=st.one_of(st.just(0.95), weird_scalars),
           bounds=st.one_of(st.just((1e-2, 1e2)), weird_vectors))
    def check(planar2, freq, parameters, confidence, bounds):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ds.CalibrationWarning)   # the oracle's subject
            def fit():          # the numbers that must be finite (an interval may be NaN
                r = ds.calibrate(planar2, freq, parameters=parameters,  # when the fit has
                                 confidence=confidence, bounds=bounds,  # no residual left)
                                 max_nfev=5)
                return r.estimate, r.initial, r.fitted_hz, r.measured_hz
            # max_nfev=5 keeps the examples short: a search it stops is a ConvergenceError
            res = obey_the_rule(fit, ["measured", "freq", "parameter", "confidence",
                                      "bounds", "damping", "EA", "mass", "fmax_hz",
                                      "did not converge"])
        if res is not None:
            assert np.all(res[0] > 0)
    return check


@pytest.fixture(scope="module")
def planar2():
    return ds.load_scene("planar2")


test_calibration = _calibration_fuzzer(FAST)
test_calibration_long = pytest.mark.slow(_calibration_fuzzer(500))


# ------------------------------------------------------------------ readers and writers
CELLS = st.one_of(st.sampled_from(["4.2", "0,5", "", "nan", "inf", "-1", "1e400", "x",
                                   "\"1,2\"", " 3 ", "#", "1.0.0", "0x10", "½"]),
                  st.floats(allow_nan=True).map(repr), st.text(max_size=5))
HEADERS = st.lists(st.sampled_from(["freq [Hz]", "frequency [Hz]", "x", "z [m]", "rz",
                                    "sigma [Hz]", "damping ratio [-]", "note", "x"]),
                   max_size=4)


def _reader_fuzzer(n):
    @_settings(n)
    @given(header=HEADERS, rows=st.lists(st.lists(CELLS, max_size=5), max_size=4),
           comment=st.booleans())
    def check(tmp_path, header, rows, comment):
        path = tmp_path / "measured.csv"
        text = ("# scene: \"x\"\n" if comment else "") + "\n".join(
            ",".join(r) for r in [header, *rows])
        path.write_bytes(text.encode("utf-8", "surrogatepass"))
        from dynstiff.analyses.measured import read_measured_modes
        # NaN in a shape is "not measured": the frequencies, sigma and damping are finite
        def numbers():
            r = read_measured_modes(path)
            return [r.freq_hz] + [v for v in (r.sigma_hz, r.damping_ratio) if v is not None]
        m = obey_the_rule(numbers, [str(path)])
        if m is not None:
            assert np.all(m[0] > 0)
        assert path.read_bytes() == text.encode("utf-8", "surrogatepass")
    return check


test_measured_tables = _reader_fuzzer(FAST)
test_measured_tables_long = pytest.mark.slow(_reader_fuzzer(4000))


def _writer_fuzzer(n):
    @_settings(n)
    @given(text=st.text(max_size=50), fail_at=st.one_of(st.none(), st.integers(0, 3)),
           store=st.booleans())
    def check(tmp_path, text, fail_at, store):
        from dynstiff.io.files import atomic_path, write_text
        target = tmp_path / ("old.zarr" if store else "old.csv")
        if store:
            target.mkdir(exist_ok=True)
            (target / "a").write_text("old")
        else:
            target.write_text("old")
        before = sorted(p.name for p in tmp_path.iterdir())
        try:
            with atomic_path(target) as tmp:
                for step in range(4):
                    if step == fail_at:
                        raise OSError("planted")
                    if step == 1:
                        if store:
                            import os
                            os.mkdir(tmp)
                            write_text(os.path.join(tmp, "a"), text)
                        else:
                            write_text(tmp, text)
        except OSError as exc:
            assert "planted" in str(exc) or "wrote nothing" in str(exc)
            assert (target / "a" if store else target).read_text() == "old"
        else:
            with open(target / "a" if store else target, encoding="utf-8", newline="") as fh:
                assert fh.read() == text
        assert sorted(p.name for p in tmp_path.iterdir()) == before
    return check


test_atomic_writes = _writer_fuzzer(FAST)
test_atomic_writes_long = pytest.mark.slow(_writer_fuzzer(1500))


def _uff_fuzzer(n):
    @_settings(n)
    @given(bad=st.lists(st.sampled_from([np.nan, np.inf, -np.inf, 1.0, 1e308]), min_size=1,
                        max_size=3), kind=st.sampled_from(["receptance", "mobility",
                                                            "compliance"]))
    def check(tmp_path, bad, kind):
        pytest.importorskip("pyuff")
        path = tmp_path / "old.uff"
        path.write_bytes(b"an old file")
        H = np.ones((len(bad) + 1, 1, 1), complex)
        H[1:, 0, 0] = bad
        res = ds.FRFResult(np.arange(1.0, len(bad) + 2), H, ("fz",), ("z",), kind)
        got = obey_the_rule(lambda: res.to_uff(path), ["inf or NaN", "kind"])
        if got is None:
            assert path.read_bytes() == b"an old file"
        else:
            assert np.all(np.isfinite(H)) and kind != "compliance"
        assert [p.name for p in tmp_path.iterdir()] == ["old.uff"]
    return check


test_uff_writer = _uff_fuzzer(FAST)
test_uff_writer_long = pytest.mark.slow(_uff_fuzzer(500))


# ---------------------------------------------------------------------- output paths
PATH_CHOICES = ["scene.toml", "m.csv", "link.csv", "sym.csv", "new.csv", "new.nc", "-",
                "sub/../m.csv", "./scene.toml", "other.png"]


def _paths_fuzzer(n):
    @_settings(n)
    @given(command=st.sampled_from(["workspace", "calibrate", "modes", "frf", "sweep"]),
           outputs=st.lists(st.tuples(st.sampled_from(["--csv", "--json", "--plot",
                                                       "--uff", "--out"]),
                                      st.sampled_from(PATH_CHOICES)), max_size=3,
                            unique_by=lambda t: t[0]))
    def check(tmp_path, command, outputs):
        import os

        from dynstiff.cli import build_parser
        from dynstiff.cli.common import check_outputs
        from dynstiff.io.files import OutputPathError
        for name in ("scene.toml", "m.csv"):
            if not (tmp_path / name).exists():
                (tmp_path / name).write_text("old")
        if not (tmp_path / "link.csv").exists():
            os.link(tmp_path / "m.csv", tmp_path / "link.csv")
            os.symlink(tmp_path / "scene.toml", tmp_path / "sym.csv")
            (tmp_path / "sub").mkdir()
        argv = [command, "scene.toml"]
        argv += {"workspace": ["--step", "1"], "calibrate": ["--measured", "m.csv",
                                                              "--parameter", "EA"]}.get(
                                                                  command, [])
        for opt, value in outputs:
            argv += [opt, value]
        try:
            args = build_parser().parse_args(argv)
        except BaseException:            # an option the command does not take
            return
        real = {}
        for opt, value in outputs:
            if value != "-" or opt in ("--plot", "--uff", "--out"):
                real.setdefault(os.path.realpath(value) if value != "sym.csv"
                                else str(tmp_path / "scene.toml"), []).append(opt)
        inputs = {str(tmp_path / "scene.toml")} | (
            {str(tmp_path / "m.csv")} if command == "calibrate" else set())
        hard = {str(tmp_path / "link.csv"): str(tmp_path / "m.csv")}
        merged = {}
        for k, v in real.items():
            merged.setdefault(hard.get(k, k), []).extend(v)
        real = merged
        clash = any(k in inputs or len(v) > 1 for k, v in real.items())
        try:
            check_outputs(args)
        except OutputPathError as exc:
            assert clash, str(exc)
            assert any(opt in str(exc) for opt, _ in outputs)
        except ds.InvalidParameterError:
            pass                         # another check of the same place (a suffix)
        else:
            assert not clash, argv
        assert (tmp_path / "scene.toml").read_text() == "old"
        assert (tmp_path / "m.csv").read_text() == "old"
    return check


test_output_paths = _paths_fuzzer(FAST)
test_output_paths_long = pytest.mark.slow(_paths_fuzzer(3000))
