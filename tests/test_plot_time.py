"""Time-domain figures (dynstiff/plot/time.py): spectra with the model's frequencies, tracking."""

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_spectrum  # noqa: E402
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


