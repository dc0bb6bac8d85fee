"""The platform modes of a robot (dynstiff/analyses/platform_modes.py, theory.md §12.4):
each free DOF's carrier is its largest participation below the frequency by which every DOF
is half found; the search grows until then, covers what it is asked to, and says when a
ceiling stops it."""

import re

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.platform_modes import (
    PLATFORM_FOUND,
    find_platform_modes,
    select_platform_modes,
)
from dynstiff.constants import DOF_NAMES
from dynstiff.errors import InvalidParameterError


@pytest.fixture(scope="module")
def model():
    return ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())


@pytest.fixture(scope="module")
def pm(model):
    return find_platform_modes(model)


def test_found_frequency_is_where_every_dof_is_half_found(model, pm):
    """found_hz is a mode's frequency; the participations of the modes up to it sum to at
    least one half for every free DOF, and up to the mode below it not for all of them."""
    f = np.asarray(pm.modes.freq_hz)
    p = np.nan_to_num(pm.modes.participation)[:, model.free_index]
    k = int(np.flatnonzero(f == pm.found_hz)[0])
    assert np.all(p[:k + 1].sum(axis=0) >= PLATFORM_FOUND)
    assert not np.all(p[:k].sum(axis=0) >= PLATFORM_FOUND)
    assert pm.complete and pm.reason == "" and pm.searched_hz >= pm.found_hz


def test_carriers_are_the_largest_participations_below_the_found_frequency(model, pm):
    f = np.asarray(pm.modes.freq_hz)
    p = np.nan_to_num(pm.modes.participation)
    below = f <= pm.found_hz
    expected = {DOF_NAMES[j]: int(np.flatnonzero(below)[np.argmax(p[below, j])])
                for j in model.free_index}
    assert pm.carriers == expected
    glob = np.flatnonzero(below & (np.asarray(pm.modes.kind) == "global"))
    assert list(pm.index) == sorted(set(glob) | set(expected.values()))
    assert pm.index.dtype.kind == "i"
    # CoGiRo: one global mode per DOF, 2.2061 Hz first
    assert len(pm.index) == 6 and pm.first_hz == pytest.approx(2.2061, abs=1e-4)
    np.testing.assert_array_equal(pm.freq_hz, f[pm.index])


def test_select_below_a_frequency_under_every_mode_finds_nothing(pm, model):
    index, carriers = select_platform_modes(pm.modes, model.free_index, 0.5)
    assert index.size == 0 and carriers == {}
    index, carriers = select_platform_modes(pm.modes, model.free_index, np.inf)
    assert set(carriers.values()) <= set(index)


def test_the_search_covers_what_it_is_asked_to(model, pm):
    """Every mode below cover_hz (1 + neighbours_rtol) is computed, whatever the platform
    modes need: the same lowest modes as a direct eigen-solution."""
    res = find_platform_modes(model, cover_hz=12.0, neighbours_rtol=0.1)
    assert res.searched_hz >= 12.0 and res.complete
    f = np.asarray(res.modes.freq_hz)
    assert f.max() >= 12.0 and f.max() <= 12.0 * 1.1 * 1.5
    direct = ds.eigenfrequencies(model, len(f))
    np.testing.assert_allclose(f, direct, rtol=1e-8)
    assert res.carriers == pm.carriers
    assert res.found_hz == pytest.approx(pm.found_hz, rel=1e-9)
    # without a cover the search stops at its first step past the found frequency
    assert pm.searched_hz < 12.0 and np.max(pm.modes.freq_hz) <= pm.searched_hz


def test_a_ceiling_of_modes_makes_the_search_incomplete(model):
    res = find_platform_modes(model, max_modes=3)
    assert not res.complete and np.isnan(res.found_hz) and np.isnan(res.first_hz)
    assert res.index.size == 0 and res.carriers == {}
    # the first step searches up to 1.1 x the highest massless-cable platform frequency
    import scipy.linalg
    K0 = model.massless_stiffness()
    lam = scipy.linalg.eigh(0.5 * (K0 + K0.T), model.platform_mass, eigvals_only=True)
    first = 1.1 * np.sqrt(lam.max()) / (2 * np.pi)
    assert res.reason.startswith(f"more than 3 modes below {first:.4g} Hz")
    wider = find_platform_modes(model, neighbours_rtol=0.2, max_modes=3)
    assert wider.reason.startswith(f"more than 3 modes below {first * 1.2:.4g} Hz")
    assert res.reason.endswith("Hz, the ceiling of the search for the platform modes")
    assert repr(res) == f"PlatformModes(incomplete: {res.reason})"
    assert res.spread() == ""


def test_the_band_of_an_exact_model_ends_the_search():
    """An exact model built up to 3 Hz cannot hold CoGiRo's platform modes (found by
    5.9 Hz): the search stops at the model's band and names the option to change."""
    eq = ds.load_scene("cogiro").equilibrium()
    res = find_platform_modes(ds.build_model(eq, "exact", fmax_hz=3.0))
    assert not res.complete
    assert res.reason.startswith("the model's band ends at ")
    assert "build it with a larger fmax_hz" in res.reason
    assert re.search(r"found only in part \(x \d+%, y \d+%, z \d+%, rx \d+%, ry \d+%, "
                     r"rz \d+%\)", res.reason), res.reason
    assert res.modes is not None and res.searched_hz == pytest.approx(3.0, rel=1e-12)


@pytest.mark.parametrize("kw, name", [(dict(cover_hz=-1.0), "cover_hz"),
                                      (dict(cover_hz=np.nan), "cover_hz"),
                                      (dict(cover_hz=np.inf), "cover_hz"),
                                      (dict(neighbours_rtol=-0.1), "neighbours_rtol"),
                                      (dict(neighbours_rtol=np.inf), "neighbours_rtol")])
def test_bad_arguments_are_named(model, kw, name):
    with pytest.raises(InvalidParameterError, match=name):
        find_platform_modes(model, **kw)


def test_describe_and_repr_say_the_numbers(pm):
    k = int(pm.index[0])
    m = pm.modes
    dof = DOF_NAMES[int(np.argmax(np.nan_to_num(m.participation[k])))]
    assert pm.describe(k) == (f"{m.freq_hz[k]:.4g} Hz ({m.kind[k]}, platform share "
                              f"{100 * m.platform_share[k]:.0f} %, mostly {dof})")
    assert repr(pm) == (f"PlatformModes(6 of {len(m)} modes, first {pm.first_hz:.4g} Hz, "
                        f"found by {pm.found_hz:.4g} Hz)")


def test_describe_names_no_dof_for_a_mode_without_participation():
    """A mode that moves no DOF (participations zero or NaN) is "mostly -"; otherwise the
    DOF of its largest participation."""
    from types import SimpleNamespace

    from dynstiff.analyses.platform_modes import PlatformModes
    p = np.zeros((3, 6))
    p[1, 4] = 0.7
    p[1, 0] = 0.2
    p[2] = np.nan
    modes = SimpleNamespace(participation=p, freq_hz=np.array([1.0, 2.0, 3.0]),
                            kind=("local", "global", "local"),
                            platform_share=np.array([0.0, 0.9, 0.01]))
    pm = PlatformModes(modes=modes, index=np.array([1]), carriers={"ry": 1}, complete=True,
                       found_hz=2.0, searched_hz=3.0, reason="")
    assert pm.describe(0) == "1 Hz (local, platform share 0 %, mostly -)"
    assert pm.describe(1) == "2 Hz (global, platform share 90 %, mostly ry)"
    assert pm.describe(2) == "3 Hz (local, platform share 1 %, mostly -)"


def test_spread_counts_the_cable_dominated_modes_up_to_the_found_frequency():
    """Carriers x and y with platform shares below one half: the sentence names both and
    counts the cable-dominated modes up to found_hz (2 of the 3 below it; the 60 % mode
    and the mode above found_hz are not counted)."""
    from types import SimpleNamespace

    from dynstiff.analyses.platform_modes import PlatformModes

    class Modes(SimpleNamespace):
        def __len__(self):
            return 4
    modes = Modes(freq_hz=np.array([1.0, 2.0, 3.0, 4.0]),
                  platform_share=np.array([0.2, 0.6, 0.3, 0.1]))
    kw = dict(index=np.array([0, 1, 2]), found_hz=3.0, searched_hz=4.0, reason="")
    pm = PlatformModes(modes=modes, carriers={"x": 0, "y": 2, "z": 1}, complete=True, **kw)
    assert pm.spread() == (
        "no mode is platform-dominated in x, y: the platform's motion there is spread over "
        "2 cable-dominated modes up to 3 Hz (largest platform share among them 30 %); the "
        "platform modes are the carriers of each DOF by participation")
    assert PlatformModes(modes=modes, carriers={"z": 1}, complete=True, **kw).spread() == ""
    assert PlatformModes(modes=modes, carriers={"x": 0}, complete=False, **kw).spread() == ""


def test_a_dof_no_mode_below_moves_has_no_carrier():
    """Below 1.5 Hz only the first two modes: x moves in both (carrier: the larger), y in
    neither (no carrier, not the first mode by default); the global mode is kept."""
    from types import SimpleNamespace
    p = np.zeros((3, 6))
    p[:, 0] = [0.2, 0.5, 0.3]
    p[2, 1] = 1.0
    modes = SimpleNamespace(freq_hz=np.array([1.0, 1.2, 2.0]), participation=p,
                            kind=("global", "local", "global"))
    index, carriers = select_platform_modes(modes, [0, 1], 1.5)
    assert carriers == {"x": 1}
    assert list(index) == [0, 1] and index.dtype.kind == "i"
    index, carriers = select_platform_modes(modes, [0, 1], 2.0)
    assert carriers == {"x": 1, "y": 2} and list(index) == [0, 1, 2]


def test_found_frequency_counts_the_modes_at_the_top_and_needs_every_dof():
    """_found_frequency on three modes (1, 2, 3 Hz), DOFs x and y: x is half found by the
    first mode (0.6), y by the second (0.2 + 0.4); the mode at ``top`` counts ("at or below"),
    the found frequency is the last DOF's; below every mode nothing is found and each DOF's
    cumulative participation is 0."""
    from types import SimpleNamespace

    from dynstiff.analyses.platform_modes import _found_frequency
    p = np.zeros((3, 6))
    p[:, 0] = [0.6, 0.1, 0.3]
    p[:, 1] = [0.2, 0.4, 0.4]
    p[0, 2] = np.nan                                    # not a free DOF here
    modes = SimpleNamespace(freq_hz=np.array([1.0, 2.0, 3.0]), participation=p)
    found, cum = _found_frequency(modes, np.array([0, 1]), 2.0)
    assert found == 2.0
    np.testing.assert_allclose(cum, [0.7, 0.6], rtol=1e-15)
    found, cum = _found_frequency(modes, np.array([0, 1]), 1.5)   # y: 0.2 < 1/2
    assert found is None
    np.testing.assert_allclose(cum, [0.6, 0.2], rtol=1e-15)
    assert _found_frequency(modes, np.array([0, 1]))[0] == 2.0      # no top: every mode
    found, cum = _found_frequency(modes, np.array([0, 1]), 0.5)
    assert found is None and cum.shape == (2,) and not np.any(cum)


def _softened(cls, scale):
    """``cls`` with its massless-cable stiffness scaled by ``scale`` (only the search's
    start moves: the modes are the model's own)."""
    class Soft(cls):
        def massless_stiffness(self):
            return scale * super().massless_stiffness()
    return Soft


@pytest.fixture
def bounded_steps(monkeypatch):
    """At most 30 steps of the search (a search that never ends fails instead of hanging)."""
    import dynstiff.analyses.platform_modes as mod
    real, steps = mod.modal_data, []

    def counted(*args, **kw):
        steps.append(args[1])
        assert len(steps) <= 30, "the search does not end"
        return real(*args, **kw)
    monkeypatch.setattr(mod, "modal_data", counted)
    return steps


def _first_top(model):
    """1.1 x the highest massless-cable platform frequency (1 Hz without one) [Hz]."""
    import scipy.linalg
    K0 = model.massless_stiffness()
    lam = scipy.linalg.eigh(0.5 * (K0 + K0.T), model.platform_mass, eigvals_only=True)
    return 1.1 * (np.sqrt(lam.max()) / (2 * np.pi) if lam.max() > 0 else 1.0)


@pytest.mark.parametrize("scale", [1e-3, 0.0])
def test_the_band_grows_by_one_and_a_half_until_every_dof_is_found(pm, scale, bounded_steps):
    """CoGiRo with its massless stiffness scaled by 1e-3 (first band 0.2 Hz, below every
    mode) or by 0 (no massless frequency: the search starts at 1.1 Hz): the band grows by
    1.5 to the first step at or above the found frequency (5.85 Hz), and the platform modes
    are those of the plain search (the start sets only the cost)."""
    eq = ds.load_scene("cogiro").equilibrium()
    soft = _softened(ds.FrequencyModel, scale)(eq)
    top = _first_top(soft)
    assert top < pm.found_hz / 1.5 ** 3
    while top < pm.found_hz:
        top *= 1.5
    res = find_platform_modes(soft)
    assert res.complete and res.searched_hz == pytest.approx(top, rel=1e-12)
    assert bounded_steps[-1] == res.searched_hz
    assert res.found_hz == pytest.approx(pm.found_hz, rel=1e-9)
    assert res.carriers == pm.carriers and list(res.index) == list(pm.index)
    f = np.asarray(res.modes.freq_hz)
    direct = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=top)
    np.testing.assert_allclose(f, direct, rtol=1e-8)


def test_a_ceiling_of_modes_met_while_growing_keeps_the_last_step(bounded_steps):
    """The softened CoGiRo (first band 0.2 Hz) with at most 5 modes: the search grows by 1.5
    until a band holds more than 5 modes; the incomplete result keeps the modes of the step
    before it, and says the band it could not compute."""
    eq = ds.load_scene("cogiro").equilibrium()
    soft = _softened(ds.FrequencyModel, 1e-3)(eq)
    direct = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=8.0)
    tops = [_first_top(soft)]
    while np.sum(direct <= tops[-1]) <= 5:
        tops.append(1.5 * tops[-1])
    assert np.sum(direct <= tops[-2]) >= 1                # a step found modes first
    res = find_platform_modes(soft, max_modes=5)
    assert not res.complete and res.index.size == 0 and np.isnan(res.found_hz)
    assert res.reason.startswith(f"more than 5 modes below {tops[-1]:.4g} Hz")
    assert res.searched_hz == pytest.approx(tops[-2], rel=1e-12)
    np.testing.assert_allclose(res.modes.freq_hz, direct[direct <= tops[-2]], rtol=1e-8)


def test_the_search_grows_up_to_an_exact_models_band_less_its_neighbours(bounded_steps):
    """An exact model built up to 3 Hz, its first band 1 Hz (massless stiffness scaled): the
    band grows by 1.5 (1, 1.5, 2.25 Hz) and then stops at the model's band over
    (1 + neighbours_rtol), so that the neighbours searched stay in the band."""
    from dynstiff.models.exact import ExactModel
    eq = ds.load_scene("cogiro").equilibrium()
    plain = ExactModel(eq, fmax_hz=3.0)
    scale = (1.0 / _first_top(plain)) ** 2
    model = _softened(ExactModel, scale)(eq, fmax_hz=3.0)
    assert _first_top(model) == pytest.approx(1.0, rel=1e-9)
    res = find_platform_modes(model, neighbours_rtol=0.1)
    ceiling = model.max_omega / (2 * np.pi) / 1.1
    assert ceiling == pytest.approx(3.0 / 1.1, rel=1e-12) and 2.25 < ceiling < 3.375
    assert not res.complete and res.reason.startswith("the model's band ends at ")
    assert res.searched_hz == pytest.approx(ceiling, rel=1e-12)
    f = np.asarray(res.modes.freq_hz)
    assert f.size >= 1 and f.max() <= 3.0
