"""Time-domain figures (dynstiff/plot/time.py): spectra with the model's frequencies, tracking."""

from types import SimpleNamespace

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_spectrum, plot_tracking  # noqa: E402
from dynstiff.plot.common import COLORS  # noqa: E402
from dynstiff.timedomain.response import Spectrum  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def by_gid(ax, prefix):
    return [a for a in ax.get_children() if (a.get_gid() or "").startswith(prefix)]


# -------------------------------------------------------------------------- spectrum
def synthetic_spectrum(channel, f_peaks, amps):
    f = np.linspace(0.0, 10.0, 401)
    a = 1e-7 + sum(A * np.exp(-0.5 * ((f - fp) / 0.05) ** 2) for fp, A in zip(f_peaks, amps))
    return Spectrum(freq_hz=f, amplitude=a, peaks_hz=np.asarray(f_peaks, dtype=float),
                    peak_amplitudes=np.asarray(amps, dtype=float), channel=channel,
                    window="hann", resolution_hz=0.025)


def test_spectrum_log_amplitude_and_mode_markers():
    sz = synthetic_spectrum("z", [2.2, 3.0], [1e-3, 2e-4])
    srx = synthetic_spectrum("rx", [2.4], [5e-4])
    fig0, ax = plt.subplots()
    fig = plot_spectrum([sz, srx], ax=ax, channels=["z"], modes=[2.2, 3.0, 7.5, 12.0],
                        band_hz=(0.0, 8.0))
    assert fig is ax.figure
    assert ax.get_yscale() == "log" and ax.get_xlabel() == "frequency [Hz]"
    (curve,) = by_gid(ax, "spectrum-")
    assert curve.get_gid() == "spectrum-z"                     # channels= filters
    x, y = curve.get_data()
    assert x.min() > 0 and x.max() <= 8.0                      # the band, without 0 Hz
    np.testing.assert_allclose(y, sz.amplitude[(sz.freq_hz > 0) & (sz.freq_hz <= 8.0)])
    marks = by_gid(ax, "mode-marker")
    assert sorted(m.get_xdata()[0] for m in marks) == [2.2, 3.0, 7.5]   # 12 Hz is outside
    with pytest.raises(InvalidParameterError, match="channels: 'y'"):
        plot_spectrum(sz, channels=["y"])
    with pytest.raises(InvalidParameterError, match="band_hz"):
        plot_spectrum(sz, band_hz=(5.0, 1.0))


def test_spectrum_is_labelled_with_the_channels_unit():
    sz = synthetic_spectrum("z", [2.2], [1e-3])
    srx = synthetic_spectrum("rx", [2.4], [5e-4])
    ax = plot_spectrum(sz).axes[0]
    assert ax.get_ylabel() == "amplitude [m]"
    ax = plot_spectrum(srx).axes[0]
    assert ax.get_ylabel() == "amplitude [rad]"
    ax = plot_spectrum([sz, srx]).axes[0]                     # mixed: units per channel
    assert ax.get_ylabel() == "amplitude [units in the legend]"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["z [m]", "rx [rad]"]


def test_amplitude_of_a_sinusoid_is_its_amplitude():
    from types import SimpleNamespace

    from dynstiff.timedomain.response import TimeResponse
    t = np.arange(4000) * 0.01
    pose = np.zeros((t.size, 6))
    pose[:, 2] = 3e-3 * np.sin(2 * np.pi * 2.05 * t) + 0.5     # on a bin, with a mean
    r = SimpleNamespace(times=t, pose=pose, dt=0.01, record_every=1)
    s = TimeResponse.spectrum(r, "z")
    np.testing.assert_allclose(s.peaks_hz[0], 2.05, atol=1e-9)
    np.testing.assert_allclose(s.peak_amplitudes[0], 3e-3, rtol=1e-6)
    assert s.amplitude[0] < 1e-12                               # the mean removed


def test_spectrum_of_a_simulation_marks_model_modes():
    """A short lumped-mass run of the point-mass robot: its z spectrum peaks near a
    frequency-domain eigenfrequency, which the figure marks (coloured by kind)."""
    from conftest import point_mass_robot

    from dynstiff.lumped import LumpedMassModel
    from dynstiff.timedomain.simulation import simulate
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.0, 0.0, 1.0])
    m = LumpedMassModel(rob, eq.unstretched_lengths, segments=3)
    m.equilibrium()
    run = simulate(m, 2.0, 0.01, initial=[1e-3, 0.0, 2e-3, 0.0, 0.0, 0.0])
    modes = ds.modes(ds.FrequencyModel(eq), 4)
    fig = plot_spectrum(run, channels=["z"], modes=modes, band_hz=(0.0, 10.0))
    ax = fig.axes[0]
    assert [c.get_gid() for c in by_gid(ax, "spectrum-")] == ["spectrum-z"]
    marks = by_gid(ax, "mode-marker")
    assert len(marks) == np.sum(modes.freq_hz <= 10.0)
    colours = {matplotlib.colors.to_hex(m.get_color()) for m in marks}
    assert colours <= {matplotlib.colors.to_hex(c) for c in ("tab:red", "tab:purple", "tab:blue")}


def raised(spectrum, **kw):
    with pytest.raises(InvalidParameterError) as e:
        plot_spectrum(spectrum, **kw)
    return str(e.value)


def test_not_a_spectrum_is_an_error_naming_spectrum_and_what_is_expected():
    """An item without the Spectrum attributes: the message names the argument, the accepted
    inputs and the first missing attribute."""
    assert raised([object()]) == ("spectrum must be a Spectrum, a sequence of Spectrum or a "
                                  "TimeResponse, got object (no 'freq_hz')")


def test_empty_sequence_is_an_error_saying_so():
    """An empty list: nothing to draw, said in the message."""
    assert raised([]) == "spectrum: no spectrum to draw (empty sequence)"


def test_band_of_zero_width_is_refused():
    """band_hz = (2, 2) breaks 0 <= f_lo < f_hi."""
    sz = synthetic_spectrum("z", [2.2], [1e-3])
    assert raised(sz, band_hz=(2.0, 2.0)).startswith("band_hz must be (f_lo, f_hi) [Hz]")


def test_default_band_is_zero_to_the_highest_frequency():
    """Without band_hz the x range is 0 .. the highest frequency of all the spectra, and every
    positive frequency is drawn."""
    sz = synthetic_spectrum("z", [2.2], [1e-3])
    sx = synthetic_spectrum("x", [2.4], [5e-4])
    sx = Spectrum(freq_hz=sx.freq_hz * 1.5, amplitude=sx.amplitude, peaks_hz=sx.peaks_hz,
                  peak_amplitudes=sx.peak_amplitudes, channel="x", window="hann",
                  resolution_hz=0.0375)
    ax = plot_spectrum([sz, sx]).axes[0]
    assert ax.get_xlim() == (0.0, float(sx.freq_hz.max()))
    for s in (sz, sx):
        (curve,) = by_gid(ax, f"spectrum-{s.channel}")
        np.testing.assert_array_equal(curve.get_xdata(), s.freq_hz[1:])   # all but 0 Hz
        np.testing.assert_array_equal(curve.get_ydata(), s.amplitude[1:])


def test_spectrum_lines_are_1pt_and_labelled_by_channel_when_units_agree():
    """Channels all in m: each line 1 pt wide, the legend shows the bare channel names."""
    sz = synthetic_spectrum("z", [2.2], [1e-3])
    sx = synthetic_spectrum("x", [2.4], [5e-4])
    ax = plot_spectrum([sz, sx]).axes[0]
    assert [c.get_linewidth() for c in by_gid(ax, "spectrum-")] == [1.0, 1.0]
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["z", "x"]
    assert ax.get_ylabel() == "amplitude [m]"


def test_peaks_inside_the_band_are_5pt_triangles_of_the_line_colour():
    """Peaks at 2.2, 3.0 (the band's upper end, kept) and 6.0 Hz (outside, dropped) with band
    (1, 3): the peak line holds exactly the two inside, as 5 pt 'v' markers without a
    connecting line, in the colour of its spectrum; each channel has its own colour."""
    sz = synthetic_spectrum("z", [2.2, 3.0, 6.0], [1e-3, 2e-4, 3e-4])
    sx = synthetic_spectrum("x", [0.5, 2.5], [1e-4, 4e-4])
    ax = plot_spectrum([sz, sx], band_hz=(1.0, 3.0)).axes[0]
    colours = []
    for s, keep in ((sz, [0, 1]), (sx, [1])):
        (pk,) = by_gid(ax, f"peaks-{s.channel}")
        (curve,) = by_gid(ax, f"spectrum-{s.channel}")
        np.testing.assert_array_equal(pk.get_xdata(), s.peaks_hz[keep])
        np.testing.assert_array_equal(pk.get_ydata(), s.peak_amplitudes[keep])
        assert pk.get_marker() == "v" and pk.get_markersize() == 5
        assert pk.get_linestyle() == "None"
        assert to_rgba(pk.get_color()) == to_rgba(curve.get_color())
        colours.append(to_rgba(curve.get_color()))
    assert colours[0] != colours[1]


def test_mode_markers_are_thin_translucent_dashed_lines_including_band_ends():
    """Plain frequencies at both ends of the band are marked; every marker is a grey, 0.7 pt,
    dashed line at 70 % opacity."""
    sz = synthetic_spectrum("z", [2.2], [1e-3])
    ax = plot_spectrum(sz, modes=[1.0, 2.0, 8.0, 8.5], band_hz=(1.0, 8.0)).axes[0]
    marks = by_gid(ax, "mode-marker")
    assert [m.get_xdata()[0] for m in marks] == [1.0, 2.0, 8.0]
    for m in marks:
        assert to_rgba(m.get_color()) == to_rgba("0.3")
        assert m.get_linewidth() == 0.7 and m.get_linestyle() == "--" and m.get_alpha() == 0.7


def test_mode_of_an_unknown_kind_is_marked_grey():
    """A ModalResult whose kind is none of global / mixed / local: its marker is grey, the
    global one red."""
    from dynstiff.results import ModalResult
    res = ModalResult(freq_hz=np.array([2.0, 4.0]), platform_shapes=np.zeros((2, 6)),
                      cable_energy_fraction=np.zeros(2), cable_energy=np.zeros((2, 1)),
                      kind=("global", "other"))
    ax = plot_spectrum(synthetic_spectrum("z", [2.2], [1e-3]), modes=res).axes[0]
    got = [(m.get_xdata()[0], to_rgba(m.get_color())) for m in by_gid(ax, "mode-marker")]
    assert got == [(2.0, to_rgba(COLORS["global"])), (4.0, to_rgba("0.3"))]


def test_title_names_window_finest_resolution_and_the_markers():
    """The title states the window and the smallest resolution of the spectra, and mentions
    the dashed model frequencies only when modes are given."""
    sz = synthetic_spectrum("z", [2.2], [1e-3])
    fine = Spectrum(freq_hz=sz.freq_hz, amplitude=sz.amplitude, peaks_hz=sz.peaks_hz,
                    peak_amplitudes=sz.peak_amplitudes, channel="x", window="hann",
                    resolution_hz=0.0125)
    base = f"Amplitude spectrum (hann window, resolution {fine.resolution_hz:.3g} Hz)"
    assert plot_spectrum([sz, fine]).axes[0].get_title() == base
    got = plot_spectrum([sz, fine], modes=[2.0]).axes[0].get_title()
    assert got == base + "; dashed: model frequencies"


def test_spectrum_legend_is_in_the_upper_right():
    """A spectrum rising across the band fills the upper right corner, where an automatic
    placement would not put the legend: the legend is still drawn in the upper right
    quadrant of the axes."""
    f = np.linspace(0.0, 10.0, 401)
    s = Spectrum(freq_hz=f, amplitude=10.0 ** (f - 12.0), peaks_hz=np.array([9.0]),
                 peak_amplitudes=np.array([1e-3]), channel="z", window="hann",
                 resolution_hz=0.025)
    fig = plot_spectrum(s)
    ax = fig.axes[0]
    fig.canvas.draw()
    leg = ax.get_legend().get_window_extent()
    box = ax.get_window_extent()
    assert leg.x0 > (box.x0 + box.x1) / 2 and leg.y0 > (box.y0 + box.y1) / 2


# -------------------------------------------------------------------------- tracking
def tracking_result():
    """A TrackingResult of 11 samples: P leaves the desired straight line by up to 2.5 mm."""
    from dynstiff.timedomain.trajectory import TrackingResult
    t = np.linspace(0.0, 1.0, 11)
    desired = np.zeros((t.size, 6))
    desired[:, 0] = 0.2 * t
    desired[:, 1] = -0.1 * t
    desired[:, 2] = 1.0 + 0.05 * t
    pose = desired.copy()
    pose[:, 0] += 1.5e-3 * np.sin(np.pi * t)
    pose[:, 2] -= 2.0e-3 * np.sin(np.pi * t)          # |(1.5, 2.0)| = 2.5 mm at t = 0.5
    response = SimpleNamespace(times=t, pose=pose)
    return TrackingResult(trajectory=None, lengths=np.zeros((2, 4)), tensions=np.zeros((2, 4)),
                          response=response, desired=desired, static_offset=0.0,
                          mean_cable_length=1.0)


LABELS = ["deviation |P - P_d|", "x simulated", "x desired", "y simulated", "y desired",
          "z simulated", "z desired"]


def test_tracking_draws_the_deviation_in_mm_in_black():
    """The first axes: |P - P_d| [mm] against time, black, on an 8 x 4.5 in figure titled with
    the largest deviation."""
    tr = tracking_result()
    fig = plot_tracking(tr)
    assert tuple(fig.get_size_inches()) == (8.0, 4.5)
    ax = fig.axes[0]
    (dev,) = ax.get_lines()
    r = tr.response
    expected = 1e3 * np.linalg.norm(r.pose[:, :3] - tr.desired[:, :3], axis=1)
    np.testing.assert_array_equal(dev.get_xdata(), r.times)
    np.testing.assert_allclose(dev.get_ydata(), expected, rtol=1e-12)    # rounding only
    assert to_rgba(dev.get_color()) == to_rgba("k")
    assert ax.get_xlabel() == "t [s]" and ax.get_ylabel() == "deviation from the desired path [mm]"
    assert ax.get_title() == f"largest deviation {expected.max():.4g} mm"
    assert ax.get_title() == "largest deviation 2.5 mm"          # the 2.5 mm built in


def test_tracking_draws_simulated_and_desired_xyz_on_the_second_axis():
    """The twin axes: for each of x y z the simulated (solid) and desired (dashed) position,
    both in one colour, distinct per coordinate."""
    tr = tracking_result()
    fig = plot_tracking(tr)
    ax2 = fig.axes[1]
    assert ax2.get_ylabel() == "position of P [m]"
    lines = ax2.get_lines()
    assert [ln.get_label() for ln in lines] == LABELS[1:]
    colours = []
    for k in range(3):
        sim, des = lines[2 * k], lines[2 * k + 1]
        np.testing.assert_array_equal(sim.get_ydata(), tr.response.pose[:, k])
        np.testing.assert_array_equal(des.get_ydata(), tr.desired[:, k])
        assert sim.get_linestyle() == "-" and des.get_linestyle() == "--"
        assert to_rgba(sim.get_color()) == to_rgba(des.get_color())
        colours.append(to_rgba(sim.get_color()))
    assert len(set(colours)) == 3


def test_tracking_desired_path_shares_the_colour_of_its_coordinate_under_any_style():
    """With a colour cycle of the user's style (not matplotlib's default), each desired line
    still takes the colour of its simulated coordinate."""
    from cycler import cycler
    with plt.rc_context({"axes.prop_cycle": cycler(color=["k", "m", "c", "y", "0.5", "r"])}):
        lines = plot_tracking(tracking_result()).axes[1].get_lines()
    for k in range(3):
        assert to_rgba(lines[2 * k + 1].get_color()) == to_rgba(lines[2 * k].get_color())


def test_tracking_legend_lists_the_seven_lines_in_two_columns():
    """One legend on the first axes, its entries the deviation and the six position lines
    (their own handles), laid out in two columns in the upper left."""
    tr = tracking_result()
    fig, ax = plt.subplots()
    assert plot_tracking(tr, ax=ax) is fig
    leg = ax.get_legend()
    assert [t.get_text() for t in leg.get_texts()] == LABELS
    drawn = ax.get_lines() + fig.axes[1].get_lines()
    assert [to_rgba(h.get_color()) for h in leg.legend_handles] == [
        to_rgba(ln.get_color()) for ln in drawn]
    fig.canvas.draw()
    columns = {round(t.get_window_extent().x0, 1) for t in leg.get_texts()}
    assert len(columns) == 2
    box, where = ax.get_window_extent(), leg.get_window_extent()
    # upper left: its corner within a tenth of the axes' size of the axes' corner
    assert where.x0 - box.x0 < 0.1 * box.width and box.y1 - where.y1 < 0.1 * box.height
