"""Single-cable report: statics, fixed-end frequencies and the dynamic stiffness over a band.

The numbers come from :mod:`dynstiff.cable.catenary` and :mod:`dynstiff.cable.dsm`; this module only
formats them and writes files (pandas and matplotlib are imported here, on demand).
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from dynstiff._validate import count, flag, positive_scalar
from dynstiff.cable.catenary_solve import unstretched_length_for_tension
from dynstiff.cable.dsm import DEFAULT_CHORDWISE_INERTIA, cable_dynamic_stiffness, chord_parameters
from dynstiff.cable.modes import cable_natural_frequencies
from dynstiff.constants import STANDARD_GRAVITY
from dynstiff.params import Cable

__all__ = ["CableReport", "cable_report", "demo_cable"]


def demo_cable():
    """Built-in single-cable scene: CoGiRo cable 0 (theory.md §8.1, Table I) at about 300 N.

    Anchor a_0 = (-7.1775, -5.4361, 5.3911) m; attachment b_0 = (0.5032, -0.4928, 0) m on the
    platform placed at (0, 0, 1) m; 4 mm steel cable, 0.064 kg/m, E = 17 GPa (lower end of
    the range the CoGiRo description gives), area 8.2051e-6 m^2.

    Returns
    -------
    anchor (3,), end (3,), cable, tension [N]
    """
    anchor = np.array([-7.1775, -5.4361, 5.3911])
    end = np.array([0.5032, -0.4928, 1.0])
    return anchor, end, Cable(0.064, 8.2051e-6 * 17e9), 300.0


@dataclass(frozen=True)
class CableReport:
    """Everything the single-cable report shows.

    Attributes
    ----------
    state : CatenaryState
    modes : CableModes
    freq_hz : ndarray, shape (n,)
        Frequency grid [Hz].
    K : ndarray, shape (n, 3, 3)
        End-B dynamic stiffness in the chord frame (u, v, w) [N/m].
    """

    state: object
    modes: object
    freq_hz: np.ndarray
    K: np.ndarray

    def statics_frame(self):
        """pandas DataFrame of the static quantities, one row per quantity, with units.

        Columns "quantity", "value", "unit"; the rows, in this order (unit in brackets):
        "chord length" [m], "unstretched length" [m], "tension at end B" [N],
        "tension at anchor A" [N], "mean tension" [N], "horizontal tension H" [N],
        "sag (max distance to chord)" [m], "chord inclination" [deg] (to the horizontal),
        "Irvine parameter lambda^2" [-], "chord stiffness K0/(1+lambda^2/12)" [N/m],
        "transverse stiffness T/L" [N/m], then "force on end B, x", "..., y", "..., z" [N]
        (the force of the cable on B, global frame).
        """
        import pandas as pd
        s = self.state
        p = chord_parameters(s)
        rows = [
            ("chord length", s.chord_length, "m"),
            ("unstretched length", s.unstretched_length, "m"),
            ("tension at end B", s.tension_at_end, "N"),
            ("tension at anchor A", s.tension_at_anchor, "N"),
            ("mean tension", s.mean_tension, "N"),
            ("horizontal tension H", s.H, "N"),
            ("sag (max distance to chord)", s.sag, "m"),
            ("chord inclination", np.degrees(np.arccos(s.cos_theta)), "deg"),
            ("Irvine parameter lambda^2", p.lambda_sq, "-"),
            ("chord stiffness K0/(1+lambda^2/12)", p.K0 / (1 + p.lambda_sq / 12), "N/m"),
            ("transverse stiffness T/L", p.T / p.L, "N/m"),
        ]
        df = pd.DataFrame(rows, columns=["quantity", "value", "unit"])
        for i, comp in enumerate("xyz"):
            df.loc[len(df)] = (f"force on end B, {comp}", s.force_on_end[i], "N")
        return df

    def text(self):
        """Plain-text report.

        Its first line is "dynstiff single-cable report"; then a blank line, the heading
        "Statics (exact elastic catenary)" and one line per row of :meth:`statics_frame`
        (quantity, value, unit); then a blank line, the heading "Clamped-clamped natural
        frequencies (poles of the dynamic stiffness)" and one line per mode ("<f> Hz   <label>").
        """
        lines = ["dynstiff single-cable report", "", "Statics (exact elastic catenary)"]
        for _, r in self.statics_frame().iterrows():
            lines.append(f"  {r['quantity']:<38s} {r['value']:>14.6g} {r['unit']}")
        lines += ["", "Clamped-clamped natural frequencies (poles of the dynamic stiffness)"]
        for f, lab in zip(self.modes.freq_hz, self.modes.labels):
            lines.append(f"  {f:10.5f} Hz   {lab}")
        return "\n".join(lines) + "\n"

    def plot(self, ax=None):
        """Plot |K_uu|, |K_vv|, |K_ww| [N/m] against frequency with the poles marked.

        A new figure is 8 x 4.5 inches. The three curves (log y axis, line width 1.2 pt) are
        labelled "K_uu (chord)", "K_vv (in-plane)" and "K_ww (out-of-plane)" in a legend at
        the lower left; each natural frequency up to the end of the band is a dotted grey
        ("0.6") vertical line of width 0.6 pt. Axis labels "frequency [Hz]" and
        "|dynamic stiffness| [N/m]"; title "End-B dynamic stiffness of one sagging cable
        (dotted: fixed-end modes)".

        Parameters
        ----------
        ax : matplotlib Axes, optional

        Returns
        -------
        matplotlib Figure
        """
        from dynstiff.plot import figure_axes
        fig, ax = figure_axes(ax)
        names = {(0, 0): "K_uu (chord)", (1, 1): "K_vv (in-plane)", (2, 2): "K_ww (out-of-plane)"}
        for (i, j), name in names.items():
            ax.semilogy(self.freq_hz, np.abs(self.K[:, i, j]), label=name, lw=1.2)
        for f in self.modes.freq_hz:
            if f <= self.freq_hz[-1]:
                ax.axvline(f, color="0.6", lw=0.6, ls=":")
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("|dynamic stiffness| [N/m]")
        ax.set_title("End-B dynamic stiffness of one sagging cable (dotted: fixed-end modes)")
        ax.legend(loc="lower left")
        return fig


def cable_report(anchor=None, end=None, cable=None, tension=None, fmax_hz=12.0, n_points=4000,
                 n_modes=8, g=STANDARD_GRAVITY, chordwise_inertia=DEFAULT_CHORDWISE_INERTIA):
    """Compute the single-cable report (defaults: :func:`demo_cable`).

    Parameters
    ----------
    anchor, end : array_like, shape (3,), optional
        A and B [m].
    cable : Cable, optional
    tension : float, optional
        Tension at B [N]; the unstretched length is solved for it.
    fmax_hz : float
        Upper end of the frequency band [Hz].
    n_points : int
        Number of frequencies, evenly spaced from 0 to ``fmax_hz``.
    n_modes : int
        Number of fixed-end natural frequencies listed.

    Returns
    -------
    CableReport
    """
    fmax_hz = positive_scalar("fmax_hz", fmax_hz)
    n_points = count("n_points", n_points, least=2)
    chordwise_inertia = flag("chordwise_inertia", chordwise_inertia)
    d = demo_cable()
    anchor = d[0] if anchor is None else anchor
    end = d[1] if end is None else end
    cable = d[2] if cable is None else cable
    tension = d[3] if tension is None else tension
    state = unstretched_length_for_tension(anchor, end, tension, cable, g)
    freq = np.linspace(0.0, fmax_hz, n_points)
    p = chord_parameters(state)
    R = p.rotation
    K = R.T @ cable_dynamic_stiffness(state, 2 * np.pi * freq,
                                      chordwise_inertia=chordwise_inertia) @ R
    return CableReport(state=state, modes=cable_natural_frequencies(state, n_modes),
                       freq_hz=freq, K=K)


def write_report(report, out_dir):
    """Write ``report.txt``, ``statics.csv``, ``modes.csv`` and ``dynamic_stiffness.png``.

    ``out_dir`` is created with its missing parents. The CSV files have no index column;
    the PNG is saved at 120 dpi (960 x 540 pixels for the 8 x 4.5 in figure).

    Returns
    -------
    list of Path
        The files written.
    """
    import matplotlib
    matplotlib.use("Agg")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files = [out / "report.txt", out / "statics.csv", out / "modes.csv",
             out / "dynamic_stiffness.png"]
    from dynstiff.io.files import atomic_path, write_text
    write_text(files[0], report.text())
    write_text(files[1], report.statics_frame().to_csv(index=False))
    write_text(files[2], report.modes.to_frame().to_csv(index=False))
    fig = report.plot()
    fig.tight_layout()
    with atomic_path(files[3]) as tmp:
        fig.savefig(tmp, dpi=120)
    import matplotlib.pyplot as plt
    plt.close(fig)
    return files
