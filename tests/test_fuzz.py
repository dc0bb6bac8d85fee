"""Hostile input at every entry point of the library, with one rule as the oracle
(conftest.obey_the_rule): a call returns a result whose numbers are finite (inf only at an
exact pole, with a PoleWarning), or it raises a typed dynstiff error that names the offending
argument. Anything else (a raw ValueError, TypeError, OverflowError, LinAlgError, a NaN in a
result) is a failure. The command line and files: tests/test_fuzz_cli.py and
tests/test_fuzz_files.py.

Each fuzzer runs a few dozen examples in the default tier and thousands in the slow tier
(``-m slow``: 13,000 examples here, 25,500 over the three files). The workspace options and
the calibration add one more rule: on an error, no file is changed.
"""

import functools
import warnings

import numpy as np
import pytest
from conftest import FAST, LONG, _settings, obey_the_rule, weird_scalars, weird_vectors
from hypothesis import given
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.analyses.checks import design_checks


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)             # any file a command line writes stays here


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
