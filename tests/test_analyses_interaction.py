"""Modal interaction (theory.md §6): global/local frequency proximity and mode tracking in
sweeps of pose and Young's modulus on CoGiRo (theory.md §8.1)."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.interaction import ProximityWarning, proximity_warnings, to_frame
from dynstiff.errors import InvalidParameterError


@pytest.fixture(scope="module")
def scene():
    return ds.load_scene("cogiro")


def cogiro_with_E(scene, E):
    """CoGiRo with Young's modulus E [Pa] (as validation/cogiro_modes.py and
    tests/test_validation.py::test_cogiro_modes build it)."""
    rob = scene.robot
    return ds.Robot(rob.anchors, rob.attachments, ds.Cable(0.064, 8.2051e-6 * E), rob.platform,
                    tension_limits=rob.tension_limits)


@pytest.fixture(scope="module")
def modes120(scene):
    rob = cogiro_with_E(scene, 120e9)
    return ds.modes(ds.FrequencyModel(rob.equilibrium(pose=scene.pose)), 40)


# ------------------------------------------------------------------ proximity
def test_proximity_pairs_match_brute_force(modes120):
    """CoGiRo at E = 120 GPa, first 40 modes: global modes at 6.48 and 9.57 Hz sit among the
    second and third local families (8 and 4 partners within 5 %, closest 0.66 %). Every
    reported pair is within rtol and no pair within rtol is missing."""
    f, kind = modes120.freq_hz, modes120.kind
    for rtol in (0.01, 0.05, 0.2):
        warn = proximity_warnings(modes120, rtol=rtol)
        brute = set()
        for i in range(len(f)):
            for j in range(len(f)):
                if kind[i] == "global" and kind[j] == "local" and \
                        abs(f[j] - f[i]) / f[i] <= rtol:
                    brute.add((i + 1, j + 1))
        assert {(w.global_mode, w.local_mode) for w in warn} == brute
        assert len(warn) == len(brute)                       # no duplicates
        for w in warn:
            assert isinstance(w, ProximityWarning)
            assert kind[w.global_mode - 1] == "global" and kind[w.local_mode - 1] == "local"
            assert w.freq_global_hz == f[w.global_mode - 1]
            assert w.freq_local_hz == f[w.local_mode - 1]
            assert w.relative_gap <= rtol
            assert w.relative_gap == pytest.approx(
                abs(w.freq_local_hz - w.freq_global_hz) / w.freq_global_hz, rel=1e-14)
        keys = [(w.global_mode, w.relative_gap) for w in warn]
        assert keys == sorted(keys)
    warn = proximity_warnings(modes120)                      # rtol = 0.05
    assert len({w.global_mode for w in warn}) >= 2            # measured: 2 (6.48, 9.57 Hz)
    assert min(w.relative_gap for w in warn) < 0.01           # measured: 0.0066
    assert len(warn) >= 10                                    # measured: 12
    df = to_frame(warn)
    assert list(df.columns) == ["global mode", "local mode", "freq global [Hz]",
                                "freq local [Hz]", "relative gap [-]"]
    assert len(df) == len(warn) and (df["relative gap [-]"] <= 0.05).all()
    assert len(to_frame([])) == 0


def test_proximity_bad_input_names_argument(modes120):
    with pytest.raises(InvalidParameterError, match="rtol"):
        proximity_warnings(modes120, rtol=-0.1)
    with pytest.raises(InvalidParameterError, match="rtol"):
        proximity_warnings(modes120, rtol=np.nan)
    with pytest.raises(InvalidParameterError, match="^rtol must be"):
        proximity_warnings(modes120, rtol=0.0)
    with pytest.raises(InvalidParameterError, match="ModalResult .*got list$"):
        proximity_warnings([1.0, 2.0])
    with pytest.raises(InvalidParameterError, match="^warn must be True or False, got 'yes'$"):
        proximity_warnings(modes120, warn="yes")
    with pytest.raises(InvalidParameterError, match="warnings"):
        to_frame([(1, 2)])

    class Ragged:
        freq_hz = np.array([1.0, 2.0, 3.0])
        kind = ("global", "local")

    with pytest.raises(InvalidParameterError) as err:
        proximity_warnings(Ragged())
    assert str(err.value) == ("modes: freq_hz and kind must be 1-D of equal length, got "
                              "shapes (3,) and (2,)")
    Ragged.freq_hz = np.ones((2, 1))
    with pytest.raises(InvalidParameterError, match="1-D of equal length"):
        proximity_warnings(Ragged())


def test_one_global_and_one_local_mode_make_one_pair():
    """The smallest case: one global and one local mode 0.3 % apart give one record, whose
    text states the pair; the default is to return the records without issuing them."""
    import warnings
    m = ds.ModalResult(freq_hz=np.array([6.48, 6.5]), platform_shapes=np.zeros((2, 6)),
                       cable_energy_fraction=np.array([0.1, 0.9]),
                       cable_energy=np.zeros((2, 3)), kind=("global", "local"),
                       massless_freq_hz=np.array([6.4, 6.4]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pairs = proximity_warnings(m, rtol=0.01)
    assert [(w.global_mode, w.local_mode, w.freq_global_hz, w.freq_local_hz)
            for w in pairs] == [(1, 2, 6.48, 6.5)]
    assert pairs[0].relative_gap == pytest.approx(0.02 / 6.48, rel=1e-13)
    assert proximity_warnings(m, rtol=0.01, platform=[0]) == pairs     # index 0 given
    assert str(pairs[0]) == ("local mode 2 (6.5 Hz) is within 0.309 % of global mode 1 "
                             "(6.48 Hz)")
    with pytest.warns(ProximityWarning) as record:
        proximity_warnings(m, rtol=0.01, warn=True)
    # issued at the caller, not inside the module
    assert not record[0].filename.replace("\\", "/").endswith("dynstiff/analyses/interaction.py")


def test_proximity_without_local_modes_is_empty():
    m = ds.ModalResult(freq_hz=np.array([1.0, 1.01]), platform_shapes=np.zeros((2, 6)),
                       cable_energy_fraction=np.zeros(2), cable_energy=np.zeros((2, 3)),
                       kind=("global", "global"), massless_freq_hz=np.array([1.0, 1.01]))
    assert proximity_warnings(m, rtol=0.5) == []


def test_proximity_warnings_are_real_warnings(modes120):
    """Each pair is a UserWarning (it can be issued, filtered, turned into an error) that
    still compares by value as a record."""
    import warnings
    pairs = proximity_warnings(modes120, rtol=0.01)
    assert pairs and all(isinstance(w, UserWarning) for w in pairs)
    again = proximity_warnings(modes120, rtol=0.01)
    assert pairs == again and len(set(pairs) | set(again)) == len(pairs)
    with pytest.warns(ProximityWarning, match="local mode") as record:
        proximity_warnings(modes120, rtol=0.01, warn=True)
    assert [r.message for r in record] == pairs
    with warnings.catch_warnings():
        warnings.simplefilter("error", ProximityWarning)
        with pytest.raises(ProximityWarning):
            proximity_warnings(modes120, rtol=0.01, warn=True)


def test_proximity_records_compare_by_value_and_tabulate_with_their_types(modes120):
    """Two records of the same pair are equal and hash alike; a record never equals a
    tuple; the table holds the records' values, integer mode columns even when empty."""
    warn = proximity_warnings(modes120)
    again = proximity_warnings(modes120)
    assert warn == again and len(set(warn) | set(again)) == len(warn)
    assert warn[0] != (warn[0].global_mode, warn[0].local_mode)
    assert warn[0] != warn[1]
    assert eval(repr(warn[2]), {"ProximityWarning": ProximityWarning}) == warn[2]
    df = to_frame(warn)
    for col, field in zip(df.columns, ProximityWarning._FIELDS):
        assert list(df[col]) == [getattr(w, field) for w in warn]
    empty = to_frame([])
    assert list(empty.dtypes) == [np.int64, np.int64, np.float64, np.float64, np.float64]
    with pytest.raises(InvalidParameterError, match="got tuple"):
        to_frame([warn[0], (1, 2)])




@pytest.mark.parametrize("platform", [[0, 40], [-1, 3], [0.0, 2.0], [2.5], [True, False]])
def test_platform_indices_outside_the_modes_or_not_integers_are_refused(modes120, platform):
    """platform indexes the modes: an index past the end or negative, or a number that is
    not an integer (2.5 would be truncated, True taken as 1), is an error naming it."""
    assert len(modes120) == 40
    with pytest.raises(InvalidParameterError) as err:
        proximity_warnings(modes120, platform=platform)
    assert str(err.value) == (f"platform must be integer indices of the 40 modes, got "
                              f"{np.asarray(platform).tolist()}")


def test_platform_indices_choose_the_modes_compared(modes120):
    """Given indices (numpy ints, repeated) compare exactly those modes: every pair's global
    mode is one of them, and the pairs are those of the default for the same modes."""
    glob = np.flatnonzero(np.array(modes120.kind) == "global")[:3]
    got = proximity_warnings(modes120, rtol=0.2, platform=np.r_[glob, glob[:1]])
    ref = [w for w in proximity_warnings(modes120, rtol=0.2) if w.global_mode - 1 in glob]
    assert got == ref and len(got) > 0
    assert proximity_warnings(modes120, platform=[]) == []
