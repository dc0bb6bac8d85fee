"""One source of the analysis defaults (dynstiff/analyses/settings.py)."""

import dataclasses

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.settings import DEFAULT_BAND_HZ, analysis_settings
from dynstiff.errors import InvalidParameterError


def test_scene_values_then_defaults_then_overrides():
    six = ds.load_scene("sixcable")
    st = analysis_settings(six)
    assert st.band_hz == (0.05, 2.0) and st.forbidden_hz is None and st.n_modes == 20
    assert st.rung == "dsm" and st.model_rtol == 0.01 and st.damping == ds.Damping()
    bare = dataclasses.replace(six, band_hz=None, n_modes=None)
    assert analysis_settings(bare).band_hz == DEFAULT_BAND_HZ
    st = analysis_settings(six, band_hz=(0.1, 1.0), forbidden_hz=(0.2, 0.3), rung="lumped",
                           segments=8, damping=[0.02])
    assert st.band_hz == (0.1, 1.0) and st.forbidden_hz == (0.2, 0.3)
    assert st.model_options() == {"segments": 8}
    assert st.damping == ds.Damping(0.02, 0.01, 0.0)         # the rest keeps the scene's
    opts = st.check_options()
    assert opts["band_hz"] == (0.2, 0.3) and opts["model_band_hz"] == (0.1, 1.0)
    assert opts["rung"] == "lumped" and opts["segments"] == 8
    assert any("damping" in line for line in st.lines())


def test_models_carry_the_damping():
    sc = ds.load_scene("cogiro")
    eq = sc.equilibrium()
    m = analysis_settings(sc).model(eq)
    assert m.damped and m.cable_loss_factor == 0.01 and m.platform_damping_ratio == 0.01
    assert not analysis_settings(sc, damping=[0, 0, 0]).model(eq).damped
    m = analysis_settings(sc, damping=[0, 0, 0.05]).model(eq)
    assert all(c.viscous_damping == 0.05 for c in m.robot.cables)


@pytest.mark.parametrize("kw, name", [(dict(band_hz=(2.0, 1.0)), "band_hz"),
                                      (dict(forbidden_hz=(-1.0, 1.0)), "forbidden_hz"),
                                      (dict(rung="fem"), "model"),
                                      (dict(n_modes=0), "n_modes"),
                                      (dict(damping=[0.1, 0.1, 0.1, 0.1]), "damping"),
                                      (dict(damping=[-0.1]), "platform_ratio"),
                                      (dict(model_rtol=-1.0), "model_rtol"),
                                      (dict(margin=-0.1), "margin")])
def test_bad_settings_are_named(kw, name):
    with pytest.raises(InvalidParameterError, match=name):
        analysis_settings(ds.load_scene("planar2"), **kw)


def test_metadata_names_scene_pose_model_damping_version():
    sc = ds.load_scene("cogiro")
    md = analysis_settings(sc).metadata(sc.pose, units="Hz")
    assert md["dynstiff"] == ds.__version__ and md["scene"] == "cogiro"
    assert md["model"] == "dsm" and md["units"] == "Hz"
    assert md["pose"]["position [m]"] == [0.0, 0.0, 1.0]
    assert md["damping"]["cable_loss_factor"] == 0.01
    # every table of the command line and of the report starts with the same keys
    assert list(md)[:5] == ["dynstiff", "scene", "pose", "model", "date"]


def test_the_settings_in_words_in_the_header_and_in_the_checks():
    """Every setting reaches the design checks' arguments, the printed lines and the
    tables' header: the receptance limit, the lumped segments, the viscous damping, the
    band; no forbidden band reads "none"; the undamped model has no damping at all."""
    sc = ds.load_scene("cogiro")
    st = analysis_settings(sc, rung="lumped", segments=5, frf_limit=4.0, band_hz=(0.2, 9.0),
                           damping=[0.02, 0.03, 0.04])
    assert st.check_options()["frf_limit"] == 4.0
    band, model = st.lines()
    assert band == ("band 0.2-9 Hz; forbidden band 0-1.5 Hz (margin 5%, modes with platform "
                    "share >= 5%, receptance <= 4 x static)")
    assert model.startswith("model lumped, 5 segments per cable, tolerance 0.01; ")
    md = st.metadata()
    assert md["band_hz"] == [0.2, 9.0] and md["segments"] == 5
    assert md["damping"] == {"platform_ratio": 0.02, "cable_loss_factor": 0.03,
                             "cable_viscous_damping [N s/m^2]": 0.04}
    dsm = analysis_settings(ds.load_scene("sixcable"))
    assert dsm.lines()[0] == "band 0.05-2 Hz; forbidden band none"
    assert "segments" not in dsm.metadata() and "segments" not in dsm.lines()[1]
    eq = sc.equilibrium()
    undamped = analysis_settings(sc, damping=[0.02, 0.03, 0.04]).model(eq, damped=False)
    assert not undamped.damped and undamped.cable_loss_factor == 0.0
    assert undamped.platform_damping_ratio == 0.0
    assert all(c.viscous_damping == 0.0 for c in undamped.robot.cables)


def test_scene_model_at_the_lengths_given():
    """scene_model at unstretched lengths: forward statics from those lengths, the same
    model as at the pose they came from."""
    sc = ds.load_scene("cogiro")
    eq = sc.robot.equilibrium(pose=[1.0, 0.5, 1.2])
    m = ds.scene_model(sc, lengths=eq.unstretched_lengths)
    np.testing.assert_allclose(m.pose.position, [1.0, 0.5, 1.2], atol=1e-6)
    with pytest.raises(InvalidParameterError, match="not both"):
        ds.scene_model(sc, [1.0, 0.5, 1.2], lengths=eq.unstretched_lengths)


@pytest.mark.integration
def test_the_documented_python_model_gives_the_command_lines_frf(tmp_path):
    """One set of defaults: ds.frf of ds.scene_model(scene) (the scene's [damping]) on the
    frequencies `dynstiff frf cogiro` wrote equals the command line's FRF to 1e-12, peak
    included (about 1.8e-3 m/N, not the undamped model's grid-dependent 1e-1)."""
    import pandas as pd
    from conftest import run_cli
    out = run_cli("frf", "cogiro", "--csv", str(tmp_path / "frf.csv"))
    assert out.returncode == 0, out.stderr
    cli = pd.read_csv(tmp_path / "frf.csv", comment="#")
    f = cli["freq [Hz]"].to_numpy()
    H = ds.frf(ds.scene_model(ds.load_scene("cogiro")), 2 * np.pi * f, "fz", "z").H[:, 0, 0]
    np.testing.assert_allclose(np.abs(H), cli["magnitude"], rtol=1e-12)
    assert 1.5e-3 < np.abs(H).max() < 2.5e-3
    assert "damped: platform modal ratio 0.01, cable loss factor 0.01" in repr(
        ds.scene_model(ds.load_scene("cogiro")))


def test_an_undamped_frf_across_resonances_warns_and_says_undamped():
    """frf of an undamped model whose band holds natural frequencies warns that its peaks
    are the grid's (counted by Wittrick-Williams: CoGiRo has 2 modes in 2.0-2.5 Hz) and
    the result, its repr and its figure's title say "undamped"; below the first mode, or
    damped, no warning."""
    import warnings
    sc = ds.load_scene("cogiro")
    m = ds.scene_model(sc, damping=(0, 0, 0))
    assert m.damping_text() == "undamped" and "undamped" in repr(m)
    with pytest.warns(ds.ResonanceWarning, match="crosses 2 natural frequencies"):
        H = ds.frf(m, 2 * np.pi * np.linspace(2.0, 2.5, 50), "fz", "z")
    assert H.damping == "undamped" and "undamped" in repr(H)
    import matplotlib
    matplotlib.use("Agg")
    assert "undamped" in H.plot().axes[0].get_title()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds.frf(m, 2 * np.pi * np.linspace(0.1, 2.0, 50), "fz", "z")
        ds.frf(ds.scene_model(sc), 2 * np.pi * np.linspace(2.0, 2.5, 50), "fz", "z")


def test_the_scenes_own_analysis_values_are_taken():
    """[analysis] model, segments, n_modes and model_rtol of a scene, each taken over the
    defaults; the smallest count (1) is accepted."""
    sc = dataclasses.replace(ds.load_scene("planar2"), model="lumped", segments=7, n_modes=1,
                             model_rtol=0.003)
    st = analysis_settings(sc)
    assert (st.rung, st.segments, st.n_modes, st.model_rtol) == ("lumped", 7, 1, 0.003)
    assert st.model_options() == {"segments": 7}


@pytest.mark.parametrize("top, fmax", [(50.0, 80.0), (1.0, None)])
def test_the_exact_rung_resolves_1_6_times_the_band_top(top, fmax):
    """fmax_hz of the exact rung: 1.6 x the band's top, never below the exact model's own
    default."""
    from dynstiff.models.exact import DEFAULT_FMAX_HZ
    st = analysis_settings(ds.load_scene("planar2"), band_hz=(0.1, top), rung="exact")
    assert st.model_options() == {"fmax_hz": DEFAULT_FMAX_HZ if fmax is None else fmax}
    assert fmax is None or fmax > DEFAULT_FMAX_HZ


def test_a_damping_given_whole_is_taken_as_it_is():
    d = ds.Damping(0.03, 0.0, 0.2)
    assert analysis_settings(ds.load_scene("cogiro"), damping=d).damping is d


@pytest.mark.parametrize("name", ["participation", "frf_limit", "model_rtol"])
def test_zero_is_not_a_positive_setting(name):
    with pytest.raises(InvalidParameterError) as err:
        analysis_settings(ds.load_scene("planar2"), **{name: 0.0})
    assert str(err.value) == f"{name} must be finite and > 0, got 0.0"


def test_a_band_that_is_not_two_numbers_is_named():
    with pytest.raises(InvalidParameterError) as err:
        analysis_settings(ds.load_scene("planar2"), band_hz=("low", 2.0))
    assert str(err.value) == "band_hz must be (low, high) [Hz], got ('low', 2.0)"


def test_scene_model_names_a_setting_it_does_not_have():
    """A misspelt setting came out as Python's TypeError of analysis_settings."""
    with pytest.raises(InvalidParameterError, match=r"^settings \['band'\] are not settings of "
                                                    r"an analysis \(they are \['band_hz', "):
        ds.scene_model(ds.load_scene("planar2"), band=(0, 3))


def test_a_scene_that_is_not_one_is_refused():
    with pytest.raises(InvalidParameterError, match="^scene must be a dynstiff Scene"):
        ds.scene_model(None)


def test_a_band_of_booleans_is_refused():
    """(0, True) was the band up to 1 Hz; the settings check bands as every analysis does."""
    with pytest.raises(InvalidParameterError, match="^band_hz must be real numbers, not "
                                                    "booleans"):
        analysis_settings(ds.load_scene("planar2"), band_hz=(0.0, True))


def test_a_scene_without_an_attribute_names_the_first_one_missing():
    """Something that is not a Scene is refused naming the first of robot, pose, band_hz,
    damping it lacks: all four (None), or only the damping."""
    from types import SimpleNamespace
    with pytest.raises(InvalidParameterError) as err:
        analysis_settings(None)
    assert str(err.value).endswith("got NoneType without 'robot'")
    sc = ds.load_scene("planar2")
    partial = SimpleNamespace(robot=sc.robot, pose=sc.pose, band_hz=sc.band_hz)
    with pytest.raises(InvalidParameterError) as err:
        analysis_settings(partial)
    assert str(err.value).endswith("got SimpleNamespace without 'damping'")


def test_the_scenes_own_damping_is_the_base_of_the_values_given():
    """A scene's [damping] (not the defaults) is the damping, and the base of a partial
    override."""
    own = ds.Damping(0.03, 0.02, 0.1)
    assert own != ds.Damping()
    sc = dataclasses.replace(ds.load_scene("planar2"), damping=own)
    assert analysis_settings(sc).damping == own
    assert analysis_settings(sc, damping=[0.05]).damping == ds.Damping(0.05, 0.02, 0.1)


def test_scene_model_passes_the_further_settings_on():
    """segments given to scene_model reach the lumped model: 3 segments per cable, not the
    default 30."""
    m = ds.scene_model(ds.load_scene("planar2"), rung="lumped", segments=3)
    assert m.rung == "lumped" and list(m.segments) == [3] * m.robot.n_cables


def test_scene_model_lists_exactly_the_settings_it_takes_further():
    """The further settings are analysis_settings' keywords but scene, rung and damping
    (scene_model's own arguments)."""
    with pytest.raises(InvalidParameterError) as err:
        ds.scene_model(ds.load_scene("planar2"), band=(0, 3))
    assert str(err.value) == (
        "settings ['band'] are not settings of an analysis (they are ['band_hz', "
        "'forbidden_hz', 'frf_limit', 'margin', 'model_rtol', 'n_modes', 'participation', "
        "'segments'])")
