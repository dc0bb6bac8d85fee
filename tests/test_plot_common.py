"""Shared plot helpers (dynstiff/plot/common.py): the frequencies marked on a figure, read
from a ModalResult-like object or an array, and the errors naming the bad argument."""

from types import SimpleNamespace

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402

from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import figure_axes, mode_categories, plot_modes, plot_spectrum  # noqa: E402
from dynstiff.plot.common import COLORS, mode_frequencies  # noqa: E402
from dynstiff.results import DampedModes, ModalResult  # noqa: E402
from dynstiff.timedomain.response import Spectrum  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def spectrum():
    f = np.linspace(0.0, 10.0, 401)
    return Spectrum(freq_hz=f, amplitude=1e-7 + np.exp(-0.5 * ((f - 3.0) / 0.05) ** 2),
                    peaks_hz=np.array([3.0]), peak_amplitudes=np.array([1.0]), channel="z",
                    window="hann", resolution_hz=0.025)


def modal_result(freq_hz, platform_share, kind=None):
    n = len(freq_hz)
    return ModalResult(freq_hz=np.asarray(freq_hz, dtype=float), platform_shapes=np.zeros((n, 6)),
                       cable_energy_fraction=1.0 - np.asarray(platform_share, dtype=float),
                       cable_energy=np.zeros((n, 1)), kind=kind)


def markers(fig):
    return [ln for ln in fig.axes[0].get_lines() if ln.get_gid() == "mode-marker"]


def raised_message(modes):
    with pytest.raises(InvalidParameterError) as e:
        plot_spectrum(spectrum(), modes=modes)
    return str(e.value)


def test_modal_result_markers_take_the_colour_of_their_class():
    """Shares 0.9 / 0.3 / 0.01 mark global, mixed and local modes in the palette's colours."""
    fig = plot_spectrum(spectrum(), modes=modal_result([2.0, 4.0, 6.0], [0.9, 0.3, 0.01]))
    got = [(ln.get_xdata()[0], to_rgba(ln.get_color())) for ln in markers(fig)]
    assert got == [(2.0, to_rgba(COLORS["global"])), (4.0, to_rgba(COLORS["mixed"])),
                   (6.0, to_rgba(COLORS["local"]))]


def test_modes_without_kind_are_marked_grey():
    """DampedModes (freq_hz, no kind) mark their damped frequencies in neutral grey."""
    f = np.array([2.0, 5.0])
    damped = DampedModes(undamped_freq_hz=f, omega=2 * np.pi * f * (1 + 0.01j),
                         residual=np.zeros(2))
    got = markers(plot_spectrum(spectrum(), modes=damped))
    np.testing.assert_allclose([ln.get_xdata()[0] for ln in got], f, rtol=1e-12)
    assert all(to_rgba(ln.get_color()) == to_rgba("0.3") for ln in got)


def test_freq_hz_attribute_is_read_as_flat_float_hz():
    """A freq_hz attribute of integers, shape (2, 1), gives float frequencies shape (2,)."""
    f, kind = mode_frequencies(SimpleNamespace(freq_hz=np.array([[2], [3]])))
    assert f.dtype == np.float64 and f.shape == (2,) and f.tolist() == [2.0, 3.0]
    assert kind is None


def test_plain_frequencies_are_read_as_flat_float_hz():
    """A scalar integer is one float frequency; a nested list is flattened in order."""
    f, kind = mode_frequencies(5)
    assert f.dtype == np.float64 and f.shape == (1,) and f[0] == 5.0 and kind is None
    f, _ = mode_frequencies([[1, 2], [3, 4]])
    assert f.dtype == np.float64 and f.tolist() == [1.0, 2.0, 3.0, 4.0]


def test_single_float_marks_one_frequency():
    """modes=4.5 draws one grey marker at 4.5 Hz."""
    got = markers(plot_spectrum(spectrum(), modes=4.5))
    assert [ln.get_xdata()[0] for ln in got] == [4.5]


def test_kind_of_wrong_length_is_an_error_naming_modes():
    """A ModalResult with 2 kinds for 3 frequencies is refused, counts in the message."""
    res = modal_result([2.0, 4.0, 6.0], [0.9, 0.3, 0.01], kind=("global", "local"))
    assert raised_message(res) == "modes: kind has 2 entries for 3 frequencies"


def test_non_numeric_modes_are_an_error_naming_modes_and_type():
    """Text or a dict as modes: the message names modes and the type given."""
    assert raised_message("abc") == "modes must be a ModalResult or frequencies [Hz], got str"
    assert raised_message({"f": 2.0}) == ("modes must be a ModalResult or frequencies [Hz], "
                                          "got dict")


def test_non_finite_modes_are_an_error_listing_them():
    """A NaN among the frequencies: the message names modes and lists the values."""
    assert raised_message([2.0, np.nan]) == "modes must be finite frequencies [Hz], got [2.0, nan]"


def test_error_names_the_argument_given():
    """With name="damped" the messages name damped, not modes."""
    with pytest.raises(InvalidParameterError) as e:
        mode_frequencies([np.inf], name="damped")
    assert str(e.value) == "damped must be finite frequencies [Hz], got [inf]"


def test_new_figure_is_8_by_4_5_inches_or_the_size_given():
    """Without ax: a new 8 x 4.5 in figure (or figsize) holding the returned axes."""
    fig, ax = figure_axes()
    assert tuple(fig.get_size_inches()) == (8.0, 4.5) and ax.figure is fig
    fig, _ = figure_axes(figsize=(3, 2))
    assert tuple(fig.get_size_inches()) == (3.0, 2.0)


def test_given_axes_are_drawn_into():
    """With ax: that axes and its figure, no new figure."""
    fig0, ax0 = plt.subplots()
    n = len(plt.get_fignums())
    assert figure_axes(ax0) == (fig0, ax0) and len(plt.get_fignums()) == n


def test_non_axes_is_an_error_naming_ax():
    """ax=5: the message names ax and the type given."""
    with pytest.raises(InvalidParameterError) as e:
        figure_axes(5)
    assert str(e.value) == "ax must be a matplotlib Axes, got int"


def test_mode_categories_follow_the_platform_share():
    """Shares 0.9 / 0.3 / 0.01 are global, mixed, local (theory.md 12.1)."""
    res = modal_result([2.0, 4.0, 6.0], [0.9, 0.3, 0.01])
    assert mode_categories(res) == ("global", "mixed", "local")


def test_missing_attribute_is_an_error_naming_argument_type_and_first_missing():
    """plot_modes of an object with freq_hz only names modes, its type and the first gap."""
    with pytest.raises(InvalidParameterError) as e:
        plot_modes(SimpleNamespace(freq_hz=[2.0]))
    assert str(e.value) == ("modes must be a ModalResult, got SimpleNamespace "
                            "(no 'cable_energy_fraction')")
