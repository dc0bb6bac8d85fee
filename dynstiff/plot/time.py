"""Time-domain figures: amplitude spectra with the model's frequencies marked, and the
tracking of a commanded path.
"""

import numpy as np

from dynstiff.errors import InvalidParameterError
from dynstiff.plot.common import COLORS, figure_axes, mode_frequencies, require

__all__ = ["plot_spectrum", "plot_tracking"]


# -------------------------------------------------------------------------- spectrum
def _spectra(spectrum, channels):
    """List of Spectrum from a Spectrum, a sequence of them, or a TimeResponse."""
    if hasattr(spectrum, "spectrum") and hasattr(spectrum, "times"):       # TimeResponse
        names = tuple(spectrum.free_dofs) if channels is None else tuple(channels)
        return [spectrum.spectrum(c) for c in names]
    items = [spectrum] if hasattr(spectrum, "amplitude") else list(spectrum)
    for s in items:
        require(s, "spectrum", ("freq_hz", "amplitude", "channel", "peaks_hz"),
                 "Spectrum, a sequence of Spectrum or a TimeResponse")
    if channels is not None:
        have = [s.channel for s in items]
        for c in channels:
            if c not in have:
                raise InvalidParameterError(
                    f"channels: {c!r} is not among the spectra's channels {tuple(have)}")
        items = [s for s in items if s.channel in tuple(channels)]
    return items


def plot_spectrum(spectrum, ax=None, channels=None, modes=None, band_hz=None):
    """Amplitude spectrum of a time-domain run on a log scale, frequencies marked.

    Parameters
    ----------
    spectrum : Spectrum, sequence of Spectrum, or TimeResponse
        From :meth:`~dynstiff.lumped.TimeResponse.spectrum`: ``amplitude`` [m or rad] at
        ``freq_hz`` [Hz], both shape (n_f,). A TimeResponse is analysed with the default
        window, one spectrum per channel.
    ax : matplotlib Axes, optional
    channels : sequence of str, optional
        Channels to draw, among ``("x", "y", "z", "rx", "ry", "rz")`` (default: every given
        spectrum; for a TimeResponse its free DOFs).
    modes : ModalResult or array_like of float, optional
        Frequencies [Hz] to mark by dashed vertical lines (gid ``mode-marker``), e.g. the
        natural frequencies of the frequency-domain model; a ModalResult colours them red
        (global), purple (mixed) or blue (local), any other kind and plain frequencies
        grey ("0.3"). Only those inside the drawn band (ends included) are marked, as
        0.7 pt lines at 70 % opacity.
    band_hz : (float, float), optional
        Frequency range drawn [Hz] (default: 0 to the highest frequency of the spectra);
        it is the x range of the axes.

    Returns
    -------
    matplotlib Figure
        One 1 pt line per channel (gid ``spectrum-<channel>``), labelled by its channel
        (with its unit, when the channels mix m and rad), and the identified peaks inside
        the band as 5 pt downward triangles of the line's colour (gid ``peaks-<channel>``).
        The title names the window and the finest resolution, and ends with "; dashed:
        model frequencies" when ``modes`` is given; the legend is in the upper right.

    Raises
    ------
    InvalidParameterError
        Not a spectrum, an unknown channel, non-finite ``modes`` or a bad ``band_hz``.
    """
    items = _spectra(spectrum, channels)
    if not items:
        raise InvalidParameterError("spectrum: no spectrum to draw (empty sequence)")
    if band_hz is None:
        band = (0.0, max(float(np.max(s.freq_hz)) for s in items))
    else:
        try:
            band = tuple(float(b) for b in band_hz)
        except (TypeError, ValueError):
            band = ()
        if len(band) != 2 or not all(np.isfinite(band)) or not 0 <= band[0] < band[1]:
            raise InvalidParameterError(
                f"band_hz must be (f_lo, f_hi) [Hz] with 0 <= f_lo < f_hi, got {band_hz!r}")
    mode_f, mode_kind = (None, None) if modes is None else mode_frequencies(modes)
    fig, ax = figure_axes(ax)
    units = {s.channel: "rad" if s.channel.startswith("r") else "m" for s in items}
    one = len(set(units.values())) == 1
    for s in items:
        unit = units[s.channel]
        f, a = np.asarray(s.freq_hz), np.asarray(s.amplitude)
        sel = (f > 0) & (f >= band[0]) & (f <= band[1])   # the mean (0 Hz) is removed
        (line,) = ax.semilogy(f[sel], a[sel], lw=1.0, gid=f"spectrum-{s.channel}",
                              label=s.channel if one else f"{s.channel} [{unit}]")
        pk = (s.peaks_hz >= band[0]) & (s.peaks_hz <= band[1])
        ax.plot(s.peaks_hz[pk], s.peak_amplitudes[pk], "v", ms=5, color=line.get_color(),
                gid=f"peaks-{s.channel}")
    if mode_f is not None:
        for k, fm in enumerate(mode_f):
            if band[0] <= fm <= band[1]:
                color = "0.3" if mode_kind is None else COLORS.get(mode_kind[k], "0.3")
                ax.axvline(fm, color=color, lw=0.7, ls="--", alpha=0.7, gid="mode-marker")
    ax.set_xlim(*band)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(f"amplitude [{next(iter(units.values()))}]" if one
                  else "amplitude [units in the legend]")
    res = min(s.resolution_hz for s in items)
    title = f"Amplitude spectrum ({items[0].window} window, resolution {res:.3g} Hz)"
    if mode_f is not None:
        title += "; dashed: model frequencies"
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, which="both", alpha=0.25)
    return fig


def plot_tracking(tracking, ax=None):
    """A commanded path (:class:`dynstiff.timedomain.trajectory.TrackingResult`): the deviation of P
    from the desired path against time [mm], with the simulated and desired x y z [m] on a
    second axis. Returns the Figure.

    The figure is 8 x 4.5 in. The deviation is drawn in black, each of x y z in its own
    colour, simulated solid and desired dashed; the legend (upper left, two columns) lists
    the seven lines, and the title gives the largest deviation [mm]."""
    fig, ax = figure_axes(ax, figsize=(8, 4.5))
    r = tracking.response
    ax.plot(r.times, 1e3 * tracking.deviation, color="k", label="deviation |P - P_d|")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("deviation from the desired path [mm]")
    ax2 = ax.twinx()
    for k, (n, c) in enumerate(zip("xyz", ("tab:blue", "tab:orange", "tab:green"))):
        ax2.plot(r.times, r.pose[:, k], color=c, lw=1.2, label=f"{n} simulated")
        ax2.plot(r.times, tracking.desired[:, k], color=c, lw=1.0, ls="--",
                 label=f"{n} desired")
    ax2.set_ylabel("position of P [m]")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, loc="upper left", fontsize=8, ncol=2)
    ax.set_title(f"largest deviation {1e3 * tracking.max_deviation:.4g} mm")
    return fig
