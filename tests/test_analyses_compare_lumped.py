"""Closed-form against lumped modes (dynstiff.analyses.compare_lumped.compare_modes): matched by
frequency and platform-shape MAC, unmatched rows kept, bad inputs named."""

import warnings

import numpy as np
import pytest
from conftest import linearised, point_mass_robot

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import compare_modes

COLUMNS = ["closed-form mode", "lumped mode", "kind (closed form)", "kind (lumped)",
           "closed-form freq [Hz]", "lumped freq [Hz]", "relative difference [-]", "MAC [-]",
           "matched by", "match quality [-]"]


def _modes(freq_hz, kinds, shapes=None):
    """A ModalResult with the given frequencies, kinds and platform shapes (default zero)."""
    n = len(freq_hz)
    shapes = np.zeros((n, 6)) if shapes is None else np.asarray(shapes, dtype=float)
    return ds.ModalResult(freq_hz=np.asarray(freq_hz, dtype=float), platform_shapes=shapes,
                          cable_energy_fraction=np.zeros(n), cable_energy=np.zeros((n, 1)),
                          kind=tuple(kinds))


def _compare(a, b, mass_matrix=None):
    """compare_modes with every RuntimeWarning turned into an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        return compare_modes(a, b, mass_matrix)


def _quality(fa, fb):
    """Match quality of the single closed-form mode fa paired among lumped modes fb."""
    df = _compare(_modes([fa], ["local"]), _modes(fb, ["local"] * len(fb)))
    return df["match quality [-]"].iloc[0]


def test_compare_modes_keeps_unmatched_rows():
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.2, -0.1, 1.0])
    model = ds.FrequencyModel(eq)
    cf = ds.modes(model, 10)
    lm = ds.modes(linearised(rob, eq.unstretched_lengths, 40), 13)
    df = compare_modes(cf, lm)
    assert list(df.columns) == COLUMNS
    assert len(df) == 13 and df["closed-form freq [Hz]"].isna().sum() == 3
    matched = df.dropna(subset=["closed-form freq [Hz]"])
    assert list(matched["closed-form mode"]) == list(range(1, 11))
    # measured at N = 40: global -2e-4 ... -1.2e-4, local down to -1.1e-3 (6.2 Hz family)
    assert np.abs(matched["relative difference [-]"]).max() < 2e-3
    assert set(matched.loc[matched["kind (closed form)"] == "global", "matched by"]) == {"MAC"}
    assert set(matched.loc[matched["kind (closed form)"] == "local", "matched by"]) == {
        "frequency"}
    with pytest.raises(InvalidParameterError,
                       match=r"^lumped_modes must be a ModalResult, got ndarray$"):
        compare_modes(cf, lm.freq_hz)
    with pytest.raises(InvalidParameterError,
                       match=r"^closed_form_modes must be a ModalResult, got list$"):
        compare_modes([1.0], lm)
    with pytest.raises(InvalidParameterError, match="mass_matrix"):
        compare_modes(cf, lm, np.eye(3))


def test_compare_modes_mac_pairs_only_modes_global_in_both():
    """Only modes global in both results are MAC-paired (weighted MAC), the rest by frequency,
    each lumped mode used once; a global mode of zero weighted norm falls back to frequency."""
    s = np.array([[1.0, 0.3, -0.2, 0, 0, 0], [0.1, 1.0, 0.4, 0, 0, 0],
                  [0.9, -0.2, 0.1, 0, 0, 0], [-0.3, 1.1, 0.3, 0, 0, 0]])
    W = np.diag([20.0, 20.0, 20.0, 0.0, 0.0, 0.0])
    a = _modes([2.0, 3.0, 2.08], ["global", "mixed", "local"], [s[0], s[1], np.zeros(6)])
    b = _modes([2.05, 3.1, 2.6], ["global", "global", "local"], [s[2], s[3], np.zeros(6)])
    df = _compare(a, b, W)
    assert list(df["closed-form mode"]) == [1, 2, 3] and list(df["lumped mode"]) == [1, 2, 3]
    assert list(df["matched by"]) == ["MAC", "frequency", "frequency"]
    mac = [(x @ W @ y) ** 2 / ((x @ W @ x) * (y @ W @ y)) for x, y in ((s[0], s[2]), (s[1], s[3]))]
    np.testing.assert_allclose(df["MAC [-]"].iloc[:2], mac, rtol=1e-12)
    assert np.isnan(df["MAC [-]"].iloc[2])
    assert df["match quality [-]"].iloc[0] == pytest.approx(mac[0], rel=1e-12)
    np.testing.assert_allclose(df["relative difference [-]"],
                               np.array([2.05, 3.1, 2.6]) / np.array([2.0, 3.0, 2.08]) - 1,
                               rtol=1e-12)
    # a pure rotation is invisible to a translation-only weight: no MAC, paired by frequency
    rot = np.array([0, 0, 0, 1.0, 0, 0])
    a = _modes([2.0, 4.0], ["global", "global"], [s[0], rot])
    b = _modes([2.05, 4.1], ["global", "global"], [s[2], rot + [0, 0, 0.05, 0, 0, 0]])
    df = _compare(a, b, W)
    assert list(df["lumped mode"]) == [1, 2]
    assert list(df["matched by"]) == ["MAC", "frequency"]
    assert np.isnan(df["MAC [-]"].iloc[1]) and df["match quality [-]"].iloc[1] == 1.0


def test_compare_modes_rows_sorted_by_closed_form_mode():
    """A closed-form mode left without partner keeps its place in closed-form order."""
    df = _compare(_modes([2.0, 9.0, 3.0], ["local"] * 3), _modes([2.1, 3.1], ["local"] * 2))
    assert list(df["closed-form mode"]) == [1, 2, 3]
    assert list(df["lumped mode"].fillna(0)) == [1, 0, 2]
    assert list(df["matched by"])[::2] == ["frequency", "frequency"]
    assert np.isnan(df["match quality [-]"].iloc[1])


def test_compare_modes_frequency_match_quality():
    """Frequency-pair quality: 1 without rival, in (0, 1) falling as a rival nears, 0 when a
    rival is as close (mirror frequency on the log scale, or a repeated frequency)."""
    assert _quality(2.0, [2.2]) == 1.0
    far, near = _quality(2.0, [2.2, 3.0]), _quality(2.0, [2.2, 2.6])
    assert 0.0 < near < far < 1.0
    assert _quality(2.0, [2.2, 2.0 / 1.1]) == pytest.approx(0.0, abs=1e-9)
    assert _quality(2.0, [2.0, 2.0]) == 0.0        # identical cables: repeated local modes
    # the documented formula, 1 - ln^2(f_b / f_a) / ln^2(f_b' / f_a)
    assert _quality(2.0, [2.2, 2.5]) == pytest.approx(
        1 - np.log(1.1) ** 2 / np.log(1.25) ** 2, rel=1e-12)


def test_frequency_pairs_minimise_the_summed_squared_log_distance():
    """Unpaired modes go by the least sum of ln^2(f_b / f_a), as documented: a family of
    close modes all shifted down keeps its order (1.0, 1.01 -> 0.95, 0.96, where the sum
    of |ln| is the same for the crossed pairs: the beaded string's local modes of
    identical cables), and 3.07, 3.45 Hz pair with 2.52, 3.02 (0.057) rather than with
    3.02, 4.51 (0.072)."""
    df = _compare(_modes([1.0, 1.01], ["local"] * 2), _modes([0.96, 0.95], ["local"] * 2))
    assert df["lumped freq [Hz]"].tolist() == [0.95, 0.96]
    df = _compare(_modes([3.07, 3.45], ["local"] * 2),
                  _modes([2.52, 3.02, 4.51], ["local"] * 3))
    assert df["lumped freq [Hz]"].tolist()[:2] == [2.52, 3.02]


def test_compare_modes_nonpositive_lumped_frequencies():
    """Unstable (negative) and 0 Hz lumped modes are never preferred by frequency, without
    warnings; a mode left only such partners gets match quality 0."""
    df = _compare(_modes([2.0], ["local"]), _modes([-0.5, 0.0, 2.1], ["local"] * 3))
    assert df["lumped mode"].tolist() == [3, 1, 2]
    assert df["matched by"].iloc[0] == "frequency" and df["match quality [-]"].iloc[0] == 1.0
    assert df["relative difference [-]"].iloc[0] == pytest.approx(2.1 / 2.0 - 1, rel=1e-12)
    df = _compare(_modes([2.0], ["local"]), _modes([-0.5, 0.0], ["local"] * 2))
    assert df["lumped mode"].iloc[0] in (1, 2) and df["match quality [-]"].iloc[0] == 0.0


@pytest.mark.parametrize("W, reason", [
    (np.diag([1.0, 1.0, 1.0, 1.0, 1.0, -1.0]), "an indefinite weight"),
    (np.eye(6) + np.triu(np.ones((6, 6)), 1), "an unsymmetric weight"),
    (2 * np.eye(6) + np.diag([0.5] * 5, 1) + np.diag([0.5 + 4e-12] * 5, -1),
     "an asymmetry of 2e-12 of the largest entry"),
])
def test_a_mac_weight_that_is_not_a_mass_matrix_is_refused(W, reason):
    """The MAC's weight must be symmetric positive semi-definite (``reason`` names the case):
    with an indefinite one a shape's weighted norm can be negative and a 'MAC' leave
    [0, 1]; refused naming mass_matrix, as a boolean matrix is. A singular weight (no
    rotation) is accepted: a shape it does not see has no MAC."""
    a = _modes([2.0], ["global"], [[0.0, 0.0, 0.0, 0.0, 0.0, 1.0]])
    b = _modes([2.1], ["global"], [[1.0, 0.0, 0.0, 0.0, 0.0, 1.0]])
    with pytest.raises(InvalidParameterError, match=r"^mass_matrix must be symmetric positive "
                                                    r"semi-definite \(a mass matrix"):
        compare_modes(a, b, W)
    with pytest.raises(InvalidParameterError, match="^mass_matrix must be real numbers, not "
                                                    "booleans"):
        compare_modes(a, b, np.eye(6, dtype=bool))
    with pytest.raises(InvalidParameterError,
                       match=r"^mass_matrix must be a finite 6x6 matrix, got 'abc'$"):
        compare_modes(a, b, "abc")
    assert _compare(a, b, np.diag([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]))["MAC [-]"].isna().all()


def test_a_weight_symmetric_to_1e_12_is_accepted_and_its_eigenvalues_named_if_refused():
    """The weight's symmetry is checked to 1e-12 of its largest entry: 0.5e-12 is accepted
    (a shape it does not see, rz, gets no MAC and is paired by frequency, without a
    warning though W rz is not zero), 2e-12 refused; an indefinite weight is refused
    naming its eigenvalues to 4 significant digits."""
    a = _modes([2.0], ["global"], [[0.0, 0.0, 0.0, 0.0, 0.0, 1.0]])
    b = _modes([2.1], ["global"], [[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    W = np.diag([1.0, 1.0, 1.0, 1.0, 1.0, 0.0])
    W[5, 0] = 0.5e-12
    df = _compare(a, b, W)
    assert df["matched by"].tolist() == ["frequency"] and np.isnan(df["MAC [-]"].iloc[0])
    W[5, 0] = 2e-12
    with pytest.raises(InvalidParameterError, match=r"^mass_matrix must be symmetric"):
        compare_modes(a, b, W)
    with pytest.raises(InvalidParameterError,
                       match=r"got eigenvalues \[1\.0, 1\.0, 1\.0, 1\.0, 1\.0, -0\.001235\]$"):
        compare_modes(a, b, np.diag([1.0, 1.0, 1.0, 1.0, 1.0, -1.23456789e-3]))
    with pytest.raises(InvalidParameterError,     # a small eigenvalue is not rounded to 0
                       match=r"got eigenvalues \[1\.0, 1\.0, 1\.0, 1\.0, 1\.0, -4e-07\]$"):
        compare_modes(a, b, np.diag([1.0, 1.0, 1.0, 1.0, 1.0, -4e-7]))


def test_mac_pairs_across_indices_leave_the_others_to_frequency():
    """A MAC pair of closed-form mode 2 with lumped mode 1 leaves closed-form mode 1 and
    lumped mode 2 to be paired by frequency: each mode appears once."""
    s = [1.0, 0.3, -0.2, 0, 0, 0]
    a = _modes([1.0, 2.0], ["local", "global"], [np.zeros(6), s])
    b = _modes([2.05, 1.1], ["global", "local"], [s, np.zeros(6)])
    df = _compare(a, b)
    assert df["closed-form mode"].tolist() == [1, 2] and df["lumped mode"].tolist() == [2, 1]
    assert df["matched by"].tolist() == ["frequency", "MAC"]


def test_a_0_hz_closed_form_mode_and_an_empty_lumped_result():
    """A 0 Hz closed-form mode: relative difference inf against a positive lumped
    frequency, NaN against 0 Hz, without warnings. No lumped mode at all: a row per
    closed-form mode, the mode numbers still nullable integers (<NA> for the lumped)."""
    df = _compare(_modes([0.0], ["local"]), _modes([2.0], ["local"]))
    assert df["relative difference [-]"].tolist() == [np.inf]
    df = _compare(_modes([0.0], ["local"]), _modes([0.0], ["local"]))
    assert df["lumped mode"].tolist() == [1] and np.isnan(df["relative difference [-]"].iloc[0])
    df = _compare(_modes([2.0, 3.0], ["local"] * 2), _modes([], []))
    assert df["closed-form mode"].tolist() == [1, 2] and df["lumped mode"].isna().all()
    assert df["closed-form mode"].dtype == "Int64" and df["lumped mode"].dtype == "Int64"
