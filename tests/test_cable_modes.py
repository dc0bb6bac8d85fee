"""Clamped natural frequencies of one cable (dynstiff/cable/modes.py, theory.md §2.2, §11):
families, ordering and the exact cable's spectrum."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.dsm import chord_parameters
from dynstiff.errors import InvalidParameterError

TWO_PI = 2 * np.pi


def test_string_families_are_exact(state300):
    modes = ds.cable_natural_frequencies(state300, 12)
    p = chord_parameters(state300)
    for fam, mult in [("out-of-plane", np.pi), ("in-plane antisymmetric", TWO_PI)]:
        sel = np.array([f == fam for f in modes.family])
        np.testing.assert_allclose(modes.Omega[sel], mult * modes.order[sel], rtol=1e-15)
    np.testing.assert_allclose(modes.freq_hz, modes.Omega / (TWO_PI * p.L) * np.sqrt(p.T / p.m),
                               rtol=1e-15)
    assert np.all(np.diff(modes.freq_hz) >= 0)
    assert modes.labels[0] == "out-of-plane 1"


@pytest.mark.parametrize("n", [np.nan, np.inf, None, 2.0, "3", 0])
def test_cable_natural_frequencies_count_must_be_an_integer(state300, n):
    with pytest.raises(InvalidParameterError, match="n_modes must be an integer >= 1"):
        ds.cable_natural_frequencies(state300, n)


@pytest.mark.parametrize("n, limit, message", [
    (10**9, 20000, "^n_modes = 1000000000 is more than max_modes = 20000; raise max_modes"),
    (5, 4, "^n_modes = 5 is more than max_modes = 4;"),
    (3, 0, r"^max_modes must be an integer >= 1, got 0$"),
    (3, True, r"^max_modes must be an integer >= 1, got True$"),
    (3, 2.0, r"^max_modes must be an integer >= 1, got 2\.0$")])
def test_a_count_beyond_max_modes_is_refused_before_any_work(state300, n, limit, message):
    """A billion modes would take the memory of the machine (a fuzzed count once did):
    refused, naming the count and the limit; the limit itself is checked like a count."""
    with pytest.raises(InvalidParameterError, match=message):
        ds.cable_natural_frequencies(state300, n, max_modes=limit)


def test_the_limit_admits_its_own_count_and_defaults_to_twenty_thousand(state300):
    assert len(ds.cable_natural_frequencies(state300, 4, max_modes=4)) == 4
    with pytest.raises(InvalidParameterError,
                       match="^n_modes = 20001 is more than max_modes = 20000;"):
        ds.cable_natural_frequencies(state300, 20001)


def test_ten_thousand_labelled_cable_modes(state300):
    """The high symmetric roots no longer fail in the root finder: 10000 modes come back
    ascending, each family in its order, the out-of-plane ones at n pi exactly."""
    with pytest.warns(ds.errors.ClosedFormWarning, match=r"axial modes from 72\.99 Hz"):
        cm = ds.cable_natural_frequencies(state300, 10000)
    assert len(cm) == 10000 and np.all(np.diff(cm.Omega) >= 0)
    oop = np.array(cm.family) == "out-of-plane"
    np.testing.assert_allclose(cm.Omega[oop], np.pi * cm.order[oop], rtol=1e-15)


def test_cable_modes_table_repr_and_plot(state300):
    import matplotlib.pyplot as plt
    modes = ds.cable_natural_frequencies(state300, 5)
    df = modes.to_frame()
    assert list(df.columns) == ["freq [Hz]", "Omega [-]", "family", "order"]
    np.testing.assert_array_equal(df["freq [Hz]"], modes.freq_hz)
    assert list(df["family"]) == list(modes.family) and list(df["order"]) == list(modes.order)
    assert repr(modes) == (f"CableModes(5 modes {modes.freq_hz[0]:.4g}-{modes.freq_hz[-1]:.4g}"
                           f" Hz: {', '.join(modes.labels[:3])}, ...)")
    fig, ax = plt.subplots()
    assert modes.plot(ax=ax) is fig
    assert any(str(a.get_gid()).startswith("cable-") for a in ax.get_children())
    plt.close(fig)


def test_exact_modes_are_numbered_within_their_family():
    """The exact model's labels on a soft cable whose axial mode is among its first 12: in
    each of the three families the orders are 1, 2, 3, ... by frequency."""
    soft = ds.solve_catenary([0, 0, 0], [10.0, 0, -2.0], 9.8, ds.Cable(1.0, 2e3))
    cm = ds.cable_natural_frequencies(soft, 12, model="exact")
    fam = np.array(cm.family)
    assert set(cm.family) == {"out-of-plane", "in-plane", "axial"}
    for name in set(cm.family):
        sel = fam == name
        np.testing.assert_array_equal(cm.order[sel], np.arange(1, sel.sum() + 1))
        assert np.all(np.diff(cm.freq_hz[sel]) > 0)


def test_coincident_closed_form_modes_are_listed_in_family_order(state300):
    """Out-of-plane k pi and in-plane antisymmetric 2 j pi coincide for k = 2 j: such pairs
    keep the documented family order, out-of-plane first, every one of them."""
    cm = ds.cable_natural_frequencies(state300, 60, guard_rtol=None)
    fam = np.array(cm.family)
    ties = np.flatnonzero(np.diff(cm.Omega) == 0)
    assert len(ties) >= 10
    assert np.all(fam[ties] == "out-of-plane")
    assert np.all(fam[ties + 1] == "in-plane antisymmetric")
    np.testing.assert_array_equal(cm.order[ties + 1] * 2, cm.order[ties])


def test_empty_cable_modes_repr_says_none():
    empty = ds.CableModes(freq_hz=np.zeros(0), Omega=np.zeros(0), family=(), order=np.zeros(0))
    assert repr(empty) == "CableModes(0 modes none: , ...)"


def test_exact_band_grows_by_half_until_it_holds_the_modes(state300, monkeypatch):
    """The exact cable's band starts at 1.2 (n + 1) times the first string frequency and
    grows by a factor 1.5 until it holds n modes: started a thousand times too low, it takes
    the bands w0 1.5^k, and the modes equal those of the normal start; never holding them in
    60 bands is an error naming n_modes."""
    import importlib
    cm = importlib.import_module("dynstiff.cable.modes")
    ref = ds.cable_natural_frequencies(state300, 4, model="exact")
    real_cable, real_lowest, bands = cm.ExactCable, cm.lowest_string_omega, []

    class Spy(real_cable):
        def __init__(self, state, w):
            bands.append(w)
            super().__init__(state, w)
    monkeypatch.setattr(cm, "ExactCable", Spy)
    monkeypatch.setattr(cm, "lowest_string_omega", lambda s: 1e-3 * real_lowest(s))
    got = ds.cable_natural_frequencies(state300, 4, model="exact")
    w0 = 1.2 * 5 * 1e-3 * real_lowest(state300)
    assert len(bands) > 10
    np.testing.assert_allclose(bands, w0 * 1.5 ** np.arange(len(bands)), rtol=1e-12)
    assert bands[-2] ** 2 < (TWO_PI * got.freq_hz[-1]) ** 2 <= bands[-1] ** 2 * (1 + 1e-12)
    np.testing.assert_allclose(got.freq_hz, ref.freq_hz, rtol=1e-6)
    assert got.family == ref.family
    monkeypatch.setattr(cm, "lowest_string_omega", lambda s: 1e-30 * real_lowest(s))
    with pytest.raises(InvalidParameterError,
                       match=r"^n_modes = 4 is more than the exact cable resolves$"):
        ds.cable_natural_frequencies(state300, 4, model="exact")
