"""Hostile input at every entry point, with one rule as the oracle: a call returns a result
whose numbers are finite (inf only at an exact pole, with a PoleWarning), or it raises a
typed dynstiff error that names the offending argument. Anything else (a raw ValueError,
TypeError, OverflowError, LinAlgError, a NaN in a result, a traceback from the command line)
is a failure.

Each fuzzer runs a few dozen examples in the default tier and thousands in the slow tier
(``-m slow``: 11,000 examples in all).
"""

import contextlib
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
                      ("unstretched_lengths", "slack", "converge", "residual"))
        obey_the_rule(lambda: rob.equilibrium(pose=scene.pose, tol=tol), ("tol",))
        obey_the_rule(lambda: design_checks(rob, scene.pose, margin=margin,
                                            max_sag_ratio=sag, model_band_hz=(0.0, 2.0)),
                      ("margin", "max_sag_ratio"))
    return check


test_statics_and_checks = _statics_fuzzer(FAST)
test_statics_and_checks_long = pytest.mark.slow(_statics_fuzzer(LONG))


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
