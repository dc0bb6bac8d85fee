"""Results of the time-domain simulation (:mod:`dynstiff.timedomain.simulation`): the energy
ledger, the time response with its pandas and plot views, and its spectrum."""

from dataclasses import dataclass

import numpy as np

from dynstiff.constants import DOF_NAMES as OUTPUT_NAMES
from dynstiff.errors import InvalidParameterError

__all__ = ["EnergyBalance", "TimeResponse", "Spectrum"]


@dataclass(frozen=True, eq=False)
class EnergyBalance:
    """Energy bookkeeping of a simulation at the recorded times [J], each shape (n_t,).

    E - E(0) = external_work - dissipated + winch_work + carried_kinetic + residual, with
    E = kinetic + gravity + elastic (see the module notes).

    Attributes
    ----------
    kinetic, gravity, elastic : ndarray
        Kinetic energy; gravity potential (heights from the base origin); strain energy.
    external_work, winch_work, carried_kinetic, dissipated : ndarray
        Cumulated work of the platform loads and of the winches, kinetic energy carried in
        with paid-out mass, energy removed by damping (>= 0 for positive damping).
    residual : ndarray
        Balance residual (0 for an exact integrator).
    static_energy : float
        Potential energy of the starting static equilibrium [J] (reference of ``scale``).
    """

    kinetic: np.ndarray
    gravity: np.ndarray
    elastic: np.ndarray
    external_work: np.ndarray
    winch_work: np.ndarray
    carried_kinetic: np.ndarray
    dissipated: np.ndarray
    residual: np.ndarray
    static_energy: float

    @property
    def total(self):
        """kinetic + gravity + elastic [J], shape (n_t,)."""
        return self.kinetic + self.gravity + self.elastic

    @property
    def scale(self):
        """Energy scale of the run [J]: the initial energy above the static equilibrium
        plus the largest magnitudes of the external, winch, carried and dissipated terms."""
        return float(abs(self.total[0] - self.static_energy)
                     + np.abs(self.external_work).max() + np.abs(self.winch_work).max()
                     + np.abs(self.carried_kinetic).max() + np.abs(self.dissipated).max())

    @property
    def relative_residual(self):
        """residual / scale [-], shape (n_t,) (relative to max |total| for a run that stays
        at rest, whose scale is 0)."""
        scale = self.scale
        if scale == 0.0:
            scale = float(np.abs(self.total).max())
        return self.residual / max(scale, np.finfo(float).tiny)


@dataclass(frozen=True, eq=False)
class TimeResponse:
    """Time history of a lumped-mass simulation.

    Attributes
    ----------
    times : ndarray, shape (n_t,)
        Recorded times [s].
    pose : ndarray, shape (n_t, 6)
        Platform position of P [m] and rotation vector [rad] (base frame).
    velocity : ndarray, shape (n_t, 6)
        Platform twist: velocity of P [m/s], angular velocity [rad/s] (base frame).
    end_tensions, anchor_tensions : ndarray, shape (n_t, n_cables)
        Tension of the last (at B) and first (at A) segment of every cable [N].
    unstretched_lengths : ndarray, shape (n_t, n_cables)
        L0_i(t) [m].
    energy : EnergyBalance
    nodes : tuple of ndarray, shape (n_t, N_i + 1, 3), or None
        Node positions [m] when recorded (anchor first, B_i last).
    free_dofs : tuple of str
    equilibrium_pose : ndarray, shape (6,)
        Starting static equilibrium pose [m, rad].
    scheme : str
    dt : float
        Time step [s]; the records are ``record_every`` steps apart.
    n_steps, newton_iterations, jacobian_updates, slack_steps, record_every : int
    substeps : int
        Steps of the "energy" scheme that were split in two because Newton failed.
    explicit_limit : float
        Predicted explicit stability limit at the start [s].
    wall_time : float
        Wall-clock time of the run [s].
    """

    times: np.ndarray
    pose: np.ndarray
    velocity: np.ndarray
    end_tensions: np.ndarray
    anchor_tensions: np.ndarray
    unstretched_lengths: np.ndarray
    energy: EnergyBalance
    nodes: tuple = None
    free_dofs: tuple = ()
    equilibrium_pose: np.ndarray = None
    scheme: str = "implicit"
    dt: float = 0.0
    n_steps: int = 0
    newton_iterations: int = 0
    jacobian_updates: int = 0
    slack_steps: int = 0
    record_every: int = 1
    explicit_limit: float = 0.0
    wall_time: float = 0.0
    substeps: int = 0

    def __repr__(self):
        return (f"TimeResponse({self.scheme}, {self.times[-1]:.4g} s in {self.n_steps} steps of "
                f"{self.dt:.3g} s, {self.times.size} records, free {self.free_dofs})")

    @property
    def displacement(self):
        """Pose minus the starting equilibrium pose [m, rad], shape (n_t, 6)."""
        return self.pose - self.equilibrium_pose

    @property
    def speed_ratio(self):
        """Simulated seconds per wall-clock second [-]."""
        return self.times[-1] / self.wall_time if self.wall_time > 0 else np.inf

    def to_frame(self):
        """pandas DataFrame indexed by time [s]: pose, twist, tensions, lengths, energies."""
        import pandas as pd
        cols = {}
        units = ("m", "m", "m", "rad", "rad", "rad")
        for k, (name, u) in enumerate(zip(OUTPUT_NAMES, units)):
            cols[f"{name} [{u}]"] = self.pose[:, k]
        for k, name in enumerate(("vx [m/s]", "vy [m/s]", "vz [m/s]", "wx [rad/s]",
                                  "wy [rad/s]", "wz [rad/s]")):
            cols[name] = self.velocity[:, k]
        for i in range(self.end_tensions.shape[1]):
            cols[f"T_B{i} [N]"] = self.end_tensions[:, i]
            cols[f"T_A{i} [N]"] = self.anchor_tensions[:, i]
            cols[f"L0_{i} [m]"] = self.unstretched_lengths[:, i]
        e = self.energy
        for name in ("kinetic", "gravity", "elastic", "external_work", "winch_work",
                     "carried_kinetic", "dissipated", "residual"):
            cols[f"{name} [J]"] = getattr(e, name)
        return pd.DataFrame(cols, index=pd.Index(self.times, name="t [s]"))

    def spectrum(self, channel="z", window="hann", t_start=0.0, threshold=1e-3,
                 prominence=None):
        """Windowed amplitude spectrum of a platform channel, with identified peaks.

        The mean is removed, the window applied and the one-sided amplitude scaled by the
        window sum (:func:`scipy.signal.periodogram`, ``scaling="spectrum"``, whose power
        A^2 / 2 of a sinusoid gives back its amplitude A), so that a sinusoid of amplitude A
        gives a peak of about A. Peaks are
        local maxima (:func:`scipy.signal.find_peaks`) above ``threshold`` times the
        largest one and at least 4 bins apart (the Hann main lobe width, so its side lobes
        are not reported; closer modes are not separated); each is refined by a parabola
        through the log amplitude of its three bins.

        Parameters
        ----------
        channel : str
            Among ``("x", "y", "z", "rx", "ry", "rz")`` (rotation-vector components).
        window : str or tuple
            Any :func:`scipy.signal.get_window` window.
        t_start : float
            Skip the records before this time [s] (transients).
        threshold : float
            Smallest peak kept, relative to the largest [-].
        prominence : float, optional
            Smallest prominence of a peak (its height above the higher of the two minima
            that separate it from higher peaks, :func:`scipy.signal.find_peaks`), relative
            to the largest peak [-]. 0.03 keeps only peaks above the Hann window's highest
            side lobe (2.7 % of its main lobe): leakage is not reported as a mode.

        Returns
        -------
        Spectrum
        """
        import scipy.signal
        if channel not in OUTPUT_NAMES:
            raise InvalidParameterError(
                f"channel must be one of {OUTPUT_NAMES}, got {channel!r}")
        y = self.pose[self.times >= t_start, OUTPUT_NAMES.index(channel)]
        if y.size < 8:
            raise InvalidParameterError(
                f"t_start = {t_start!r} leaves {y.size} samples; at least 8 are needed")
        fs = 1.0 / (self.dt * self.record_every)
        freq, power = scipy.signal.periodogram(y, fs=fs, window=window, detrend="constant",
                                               scaling="spectrum")
        amp = np.sqrt(2.0 * power)              # a sinusoid's power A^2 / 2 -> amplitude A
        top = amp[1:].max(initial=0.0)
        idx, _ = scipy.signal.find_peaks(
            amp, height=threshold * top, distance=4,
            prominence=None if prominence is None else prominence * top)
        idx = idx[(idx > 0) & (idx < amp.size - 1)]
        df = freq[1] - freq[0]
        la = np.log(np.maximum(amp, np.finfo(float).tiny))
        den = la[idx - 1] - 2 * la[idx] + la[idx + 1]
        shift = np.where(den < 0, 0.5 * (la[idx - 1] - la[idx + 1]) / np.where(
            den < 0, den, 1.0), 0.0)
        peaks = freq[idx] + shift * df
        peak_amp = np.exp(la[idx] - 0.25 * (la[idx - 1] - la[idx + 1]) * shift)
        order = np.argsort(peak_amp)[::-1]
        return Spectrum(freq_hz=freq, amplitude=amp, peaks_hz=peaks[order],
                        peak_amplitudes=peak_amp[order], channel=channel,
                        window=str(window), resolution_hz=fs / y.size)

    def plot(self, ax=None, channels=None):
        """Platform displacement from the equilibrium against time; returns the figure.

        Parameters
        ----------
        ax : matplotlib Axes, optional
        channels : sequence of str, optional
            Default: the free DOFs. Translations in mm, rotations in mrad.
        """
        import matplotlib.pyplot as plt
        if ax is None:
            fig, ax = plt.subplots()
        else:
            fig = ax.figure
        channels = self.free_dofs if channels is None else channels
        for c in channels:
            if c not in OUTPUT_NAMES:
                raise InvalidParameterError(
                    f"channels must be among {OUTPUT_NAMES}, got {c!r}")
            k = OUTPUT_NAMES.index(c)
            unit = "mm" if k < 3 else "mrad"
            ax.plot(self.times, 1e3 * self.displacement[:, k], label=f"{c} [{unit}]")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("displacement from equilibrium [mm, mrad]")
        ax.legend()
        return fig


@dataclass(frozen=True, eq=False)
class Spectrum:
    """One-sided amplitude spectrum of a simulated channel.

    Attributes
    ----------
    freq_hz : ndarray, shape (n_f,)
        Frequencies [Hz], spacing ``resolution_hz``.
    amplitude : ndarray, shape (n_f,)
        Amplitude [m or rad] (window-sum scaled).
    peaks_hz, peak_amplitudes : ndarray, shape (n_peaks,)
        Identified peaks, largest first, refined between bins [Hz], [m or rad].
    channel, window : str
    resolution_hz : float
        1 / T of the analysed record [Hz].
    """

    freq_hz: np.ndarray
    amplitude: np.ndarray
    peaks_hz: np.ndarray
    peak_amplitudes: np.ndarray
    channel: str
    window: str
    resolution_hz: float

    def __repr__(self):
        peaks = ", ".join(f"{f:.4g}" for f in self.peaks_hz[:4])
        return (f"Spectrum({self.channel}, {self.freq_hz.size} bins of {self.resolution_hz:.3g} "
                f"Hz, peaks [{peaks}{', ...' if self.peaks_hz.size > 4 else ''}] Hz)")

    def to_frame(self):
        """pandas DataFrame: freq [Hz], amplitude, and a ``peak`` flag."""
        import pandas as pd
        peak = np.zeros(self.freq_hz.size, dtype=bool)
        near = np.rint(self.peaks_hz / self.resolution_hz).astype(int)
        peak[near[(near >= 0) & (near < peak.size)]] = True
        return pd.DataFrame({"freq [Hz]": self.freq_hz, "amplitude": self.amplitude,
                             "peak": peak})

    def plot(self, ax=None):
        """Amplitude (log scale) with the peaks marked; returns the figure."""
        import matplotlib.pyplot as plt
        if ax is None:
            fig, ax = plt.subplots()
        else:
            fig = ax.figure
        ax.semilogy(self.freq_hz, self.amplitude, label=self.channel)
        ax.plot(self.peaks_hz, self.peak_amplitudes, "v", label="peaks")
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel(f"amplitude of {self.channel}")
        ax.legend()
        return fig
