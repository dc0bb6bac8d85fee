"""Results of a time-domain run (dynstiff.timedomain.response): TimeResponse and its
Spectrum as tables and figures, the recorded history read-only."""

import re

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import simulate
from dynstiff.timedomain.response import EnergyBalance, Spectrum, TimeResponse


def _response(pose, dt=0.01, record_every=1, equilibrium=None, n_cables=2, **kw):
    """TimeResponse of a given pose history (records dt * record_every apart), with twist,
    tensions, lengths and energies set to distinct known values derived from the record index."""
    n = pose.shape[0]
    k = np.arange(n, dtype=float)
    energy = EnergyBalance(*(k + 100.0 * j for j in range(8)), static_energy=0.0)
    cable = k[:, None] + np.arange(n_cables)[None, :]
    return TimeResponse(
        times=k * dt * record_every, pose=pose, velocity=-pose, end_tensions=1000.0 + cable,
        anchor_tensions=2000.0 + cable, unstretched_lengths=3000.0 + cable, energy=energy,
        equilibrium_pose=np.zeros(6) if equilibrium is None else equilibrium, dt=dt,
        record_every=record_every, **kw)


def _tones(n, dt, channel, tones):
    """Pose history (n, 6) whose ``channel`` column is a sum of cosines (amplitude, frequency
    [Hz], phase [rad]); the other columns are 0."""
    t = np.arange(n) * dt
    pose = np.zeros((n, 6))
    pose[:, channel] = sum(a * np.cos(2 * np.pi * f * t + ph) for a, f, ph in tones)
    return pose


def test_results_convert_and_plot(robot_model):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    m = robot_model(3)
    r = simulate(m, 0.5, 0.01, initial=[1e-4, 0, 0, 0, 0, 0], record_nodes=True)
    n_t = r.times.size
    assert n_t == 51 and r.pose.shape == (n_t, 6) and r.velocity.shape == (n_t, 6)
    assert [a.shape for a in r.nodes] == [(n_t, 4, 3)] * 3
    np.testing.assert_allclose(r.nodes[0][:, -1], r.pose[:, :3], atol=1e-12)  # B = P
    df = r.to_frame()
    assert len(df) == n_t and "z [m]" in df and "residual [J]" in df and "T_B2 [N]" in df
    sp = r.spectrum("x")
    assert len(sp.to_frame()) == sp.freq_hz.size
    with pytest.raises(InvalidParameterError, match="channel"):
        r.spectrum("q")
    for fig in (r.plot(), sp.plot()):
        assert fig.axes
        plt.close(fig)
    with pytest.raises(ValueError):
        r.pose[0, 0] = 1.0                                    # read-only history


def test_to_frame_columns_units_and_time_index():
    """The frame holds pose, twist, per-cable tensions and lengths and the eight energy terms,
    in that order with their units, indexed by the record times [s]."""
    n = 5
    pose = np.arange(6 * n, dtype=float).reshape(n, 6) / 7.0
    r = _response(pose, dt=0.25, record_every=2)
    df = r.to_frame()
    assert list(df.columns) == [
        "x [m]", "y [m]", "z [m]", "rx [rad]", "ry [rad]", "rz [rad]",
        "vx [m/s]", "vy [m/s]", "vz [m/s]", "wx [rad/s]", "wy [rad/s]", "wz [rad/s]",
        "T_B0 [N]", "T_A0 [N]", "L0_0 [m]", "T_B1 [N]", "T_A1 [N]", "L0_1 [m]",
        "kinetic [J]", "gravity [J]", "elastic [J]", "external_work [J]", "winch_work [J]",
        "carried_kinetic [J]", "dissipated [J]", "residual [J]"]
    assert df.index.name == "t [s]"
    np.testing.assert_array_equal(df.index.to_numpy(), 0.5 * np.arange(n))   # 2 x 0.25 s
    np.testing.assert_array_equal(df.iloc[:, :6].to_numpy(), pose)
    np.testing.assert_array_equal(df.iloc[:, 6:12].to_numpy(), -pose)
    k = np.arange(n)
    for i in range(2):
        np.testing.assert_array_equal(df[f"T_B{i} [N]"], 1000.0 + k + i)
        np.testing.assert_array_equal(df[f"T_A{i} [N]"], 2000.0 + k + i)
        np.testing.assert_array_equal(df[f"L0_{i} [m]"], 3000.0 + k + i)
    np.testing.assert_array_equal(df["dissipated [J]"], 600.0 + k)
    np.testing.assert_array_equal(df["residual [J]"], 700.0 + k)


def test_spectrum_default_channel_window_and_resolution():
    """Without arguments the spectrum is the Hann-windowed z channel: a 1 mm cosine on exactly
    bin 8 of z (64 records 2 x 0.01 s apart: 0.78125 Hz bins) gives one peak of 1 mm at
    6.25 Hz, while a larger x motion is ignored."""
    n, dt, every = 64, 0.01, 2
    df = 1.0 / (n * dt * every)
    pose = _tones(n, dt * every, 2, [(1e-3, 8 * df, 0.3)])
    pose[:, 0] = 0.1 * np.cos(2 * np.pi * 20 * df * np.arange(n) * dt * every)
    sp = _response(pose, dt, every).spectrum()
    assert (sp.channel, sp.window) == ("z", "hann")
    assert sp.resolution_hz == pytest.approx(0.78125, rel=1e-12)
    np.testing.assert_allclose(sp.freq_hz, df * np.arange(n // 2 + 1), rtol=1e-12)
    np.testing.assert_allclose(sp.peaks_hz, [6.25], rtol=1e-9)
    np.testing.assert_allclose(sp.peak_amplitudes, [1e-3], rtol=1e-9)


def test_spectrum_window_name_is_recorded():
    """The window given is kept, as text, on the spectrum."""
    pose = _tones(32, 0.01, 1, [(1.0, 25.0, 0.0)])
    assert _response(pose).spectrum("y", window="boxcar").window == "boxcar"
    assert _response(pose).spectrum("y", window=("tukey", 0.25)).window == "('tukey', 0.25)"


def test_spectrum_rejects_bad_channel_and_short_records():
    """An unknown channel and a t_start leaving fewer than 8 records are refused with messages
    naming the valid channels and the number of records left (10 records 0.1 s apart: t >= 0.65 s
    keeps 0.7, 0.8, 0.9 s)."""
    r = _response(np.zeros((10, 6)), dt=0.1)
    with pytest.raises(InvalidParameterError, match=re.escape(
            "channel must be one of ('x', 'y', 'z', 'rx', 'ry', 'rz'), got 'vz'")):
        r.spectrum("vz")
    with pytest.raises(InvalidParameterError,
                       match=r"^t_start = 0\.65 leaves 3 samples; at least 8 are needed$"):
        r.spectrum(t_start=0.65)


def test_spectrum_peaks_largest_first_and_four_bins_apart():
    """Bin-centred Hann tones give their amplitude at their bin and half of it at the two
    neighbours only: tones of 0.5 at bin 5, 1 at bin 12 and 0.25 at bin 15 (3 bins from the
    larger one, closer than the 4-bin minimum spacing) give the peaks 12 and 5 bins, largest
    first, with amplitudes 1 and 0.5."""
    n, dt = 64, 0.01
    df = 1.0 / (n * dt)
    pose = _tones(n, dt, 2, [(0.5, 5 * df, 0.0), (1.0, 12 * df, 1.0), (0.25, 15 * df, 2.0)])
    sp = _response(pose, dt).spectrum("z")
    np.testing.assert_allclose(sp.amplitude[13:17], [0.5, 0.125, 0.25, 0.125], rtol=1e-9)
    np.testing.assert_allclose(sp.peaks_hz, [12 * df, 5 * df], rtol=1e-9)
    np.testing.assert_allclose(sp.peak_amplitudes, [1.0, 0.5], rtol=1e-9)


def test_spectrum_peak_on_first_bin_sets_the_threshold():
    """A tone on bin 1 (phase pi/4, so that the mean-removed Hann spectrum is 0.5, 1, 0.5 on
    bins 0 to 2) is reported at 1 bin with amplitude 1, and, being the largest, sets the
    threshold: a 0.7e-3 tone is dropped at threshold 1e-3 and kept at 0.5e-3."""
    n, dt = 64, 0.01
    df = 1.0 / (n * dt)
    pose = _tones(n, dt, 5, [(1.0, df, np.pi / 4), (0.7e-3, 10 * df, 0.0)])
    r = _response(pose, dt)
    sp = r.spectrum("rz")
    np.testing.assert_allclose(sp.amplitude[:3], [0.5, 1.0, 0.5], rtol=1e-9)
    np.testing.assert_allclose(sp.peaks_hz, [df], rtol=1e-9)
    np.testing.assert_allclose(sp.peak_amplitudes, [1.0], rtol=1e-9)
    low = r.spectrum("rz", threshold=0.5e-3)
    np.testing.assert_allclose(low.peaks_hz, [df, 10 * df], rtol=1e-9)
    np.testing.assert_allclose(low.peak_amplitudes, [1.0, 0.7e-3], rtol=1e-9)


def test_spectrum_refines_peaks_between_bins():
    """A tone between bins is located by the parabola through the log amplitudes of its three
    bins: the peak frequency and amplitude equal the vertex computed here from the
    mean-removed, periodic-Hann-windowed FFT (amplitude 2 |X| / sum(w)), and lie within
    0.05 bin and 3 % of the 2 mm tone at 10.3 bins."""
    n, dt = 64, 0.01
    df = 1.0 / (n * dt)
    pose = _tones(n, dt, 2, [(2e-3, 10.3 * df, 0.4), (0.5e-3, 20.6 * df, -1.2)])
    sp = _response(pose, dt).spectrum("z")
    y = pose[:, 2] - pose[:, 2].mean()
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(n) / n)
    a = 2.0 * np.abs(np.fft.rfft(y * w)) / w.sum()
    expected_f, expected_a = [], []
    for k in (10, 21):
        lm, l0, lp = np.log(a[k - 1:k + 2])
        p = 0.5 * (lm - lp) / (lm - 2.0 * l0 + lp)
        expected_f.append((k + p) * df)
        expected_a.append(np.exp(l0 - 0.25 * (lm - lp) * p))
    np.testing.assert_allclose(sp.peaks_hz, expected_f, rtol=1e-9)
    np.testing.assert_allclose(sp.peak_amplitudes, expected_a, rtol=1e-9)
    assert abs(sp.peaks_hz[0] - 10.3 * df) < 0.05 * df
    assert sp.peak_amplitudes[0] == pytest.approx(2e-3, rel=0.03)


def _spectrum(peaks_hz, n=11, resolution=0.5):
    peaks_hz = np.asarray(peaks_hz, dtype=float)
    return Spectrum(freq_hz=resolution * np.arange(n), amplitude=1.0 + np.arange(n),
                    peaks_hz=peaks_hz, peak_amplitudes=np.linspace(1.0, 0.5, peaks_hz.size),
                    channel="ry", window="hann", resolution_hz=resolution)


def test_spectrum_repr_lists_the_four_largest_peaks():
    """The summary gives the channel, bin count and width, and at most four peaks [Hz], with
    an ellipsis when there are more."""
    assert repr(_spectrum([1.0, 2.0, 3.0, 4.0])) == (
        "Spectrum(ry, 11 bins of 0.5 Hz, peaks [1, 2, 3, 4] Hz)")
    assert repr(_spectrum([1.0, 2.0, 3.0, 4.0, 4.5])) == (
        "Spectrum(ry, 11 bins of 0.5 Hz, peaks [1, 2, 3, 4, ...] Hz)")


def test_spectrum_frame_flags_the_nearest_bins_of_peaks():
    """The frame has the frequency, amplitude and a boolean peak flag; each peak flags its
    nearest bin (0.2 Hz -> bin 0, 2.4 Hz -> bin 5 with 0.5 Hz bins) and peaks off the grid
    (5.5 Hz = bin 11 of 0..10, -0.6 Hz) flag nothing."""
    sp = _spectrum([2.4, 0.2, 5.5, -0.6])
    df = sp.to_frame()
    assert list(df.columns) == ["freq [Hz]", "amplitude", "peak"]
    assert df["peak"].dtype == bool
    np.testing.assert_array_equal(df["freq [Hz]"], 0.5 * np.arange(11))
    np.testing.assert_array_equal(df["amplitude"], 1.0 + np.arange(11))
    assert list(np.flatnonzero(df["peak"])) == [0, 5]


def test_spectrum_plot_draws_log_amplitude_and_peak_markers():
    """The figure shows the amplitude against frequency on a log scale, labelled with the
    channel, and the peaks as unjoined triangle markers labelled "peaks"."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sp = _spectrum([2.4, 1.0])
    fig = sp.plot()
    try:
        ax, = fig.axes
        line, marks = ax.lines
        np.testing.assert_array_equal(line.get_xdata(), sp.freq_hz)
        np.testing.assert_array_equal(line.get_ydata(), sp.amplitude)
        assert ax.get_yscale() == "log"
        np.testing.assert_array_equal(marks.get_xdata(), [2.4, 1.0])
        np.testing.assert_array_equal(marks.get_ydata(), sp.peak_amplitudes)
        assert (marks.get_marker(), marks.get_linestyle()) == ("v", "None")
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["ry", "peaks"]
        assert (ax.get_xlabel(), ax.get_ylabel()) == ("frequency [Hz]", "amplitude of ry")
    finally:
        plt.close(fig)


def test_time_plot_shows_displacement_in_mm_and_mrad_on_given_axes():
    """On given axes the figure of those axes is returned; each channel is drawn against time
    as 1e3 times its displacement from the equilibrium pose, labelled in mm (translations) or
    mrad (rotations); by default the free DOFs are drawn."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = 6
    pose = np.arange(6 * n, dtype=float).reshape(n, 6) * 1e-3
    eq = np.array([0.1, 0.2, 0.3, 0.01, 0.02, 0.03])
    r = _response(pose, dt=0.5, equilibrium=eq, free_dofs=("y", "ry"))
    fig, ax = plt.subplots()
    try:
        assert r.plot(ax=ax, channels=("x", "rx", "rz")) is fig
        assert [ln.get_label() for ln in ax.lines] == ["x [mm]", "rx [mrad]", "rz [mrad]"]
        for ln, k in zip(ax.lines, (0, 3, 5)):
            np.testing.assert_array_equal(ln.get_xdata(), 0.5 * np.arange(n))
            np.testing.assert_allclose(ln.get_ydata(), 1e3 * (pose[:, k] - eq[k]), rtol=1e-12)
        assert ax.get_xlabel() == "t [s]"
        assert ax.get_ylabel() == "displacement from equilibrium [mm, mrad]"
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["x [mm]", "rx [mrad]",
                                                                         "rz [mrad]"]
    finally:
        plt.close(fig)
    fig = r.plot()
    try:
        assert [ln.get_label() for ln in fig.axes[0].lines] == ["y [mm]", "ry [mrad]"]
    finally:
        plt.close(fig)
