"""The veering diagram of a sweep: tracked platform modes and the other modes along a path or
over a parameter.
"""

import numpy as np

from dynstiff._validate import flag
from dynstiff.plot.common import figure_axes, require

__all__ = ["LOG_SPAN", "plot_veering"]

#: A positive swept quantity whose largest value is this many times its least is drawn on a
#: logarithmic axis.
LOG_SPAN = 10.0


# --------------------------------------------------------------------------- veering
def _gap_bridges(x, y):
    """Segments bridging each interior run of NaN in y between its finite neighbours, as
    one polyline with NaN separators: (xs, ys), empty when there is no such gap."""
    ok = np.flatnonzero(np.isfinite(y))
    xs, ys = [], []
    for a, b in zip(ok[:-1], ok[1:]):
        if b > a + 1:
            xs += [x[a], x[b], np.nan]
            ys += [y[a], y[b], np.nan]
    return np.array(xs, dtype=float), np.array(ys, dtype=float)


def plot_veering(sweep_result, ax=None, show_local=True):
    """Veering diagram: natural frequencies against the swept quantity.

    Each track (a platform mode followed by MAC, :meth:`SweepResult.veering_table`) is one
    coloured line with markers (gid ``track-<id>``, broken where the track has no mode);
    where the track is found again after such a gap, a dotted line of its colour bridges
    the gap (gid ``gap-<id>``); the other modes are small dots, grey for local and purple
    for mixed ones (gid ``local-modes``, ``mixed-modes``).

    Tracks are 1.4 pt lines with 3.5 pt circles, in the ``tab10`` colours for up to 10
    tracks, else spread evenly over ``turbo`` from its first colour to its last; bridges
    are 1 pt dotted lines. The other modes are those with ``track`` -1 (all of them when the
    result has no ``track``): dots of area 6 pt², ``"0.55"`` grey and ``"tab:purple"``, at
    zorder 1, beneath the tracks. With at most 12 tracks a legend names each track and dot
    class, its top left corner at (1.01, 1.0) in axes coordinates. The grid has alpha 0.3.

    Parameters
    ----------
    sweep_result : SweepResult
        From :func:`dynstiff.sweep`; ``values`` of shape (n_steps,) in the unit named by
        ``parameter``, frequencies [Hz].
    ax : matplotlib Axes, optional
    show_local : bool
        Draw the local modes (default True).

    Returns
    -------
    matplotlib Figure
        x label ``sweep_result.parameter``, y label ``"frequency [Hz]"``; the x axis is
        logarithmic when the values are positive and span :data:`LOG_SPAN` (a decade) or
        more, and its limits hold every value, with a margin of 2 % of their span (of
        their log span on a log axis) either side; a single value keeps matplotlib's
        automatic limits. The title gives the number of tracks, adds ``", grey dots local
        modes"`` when they are drawn (and ``", purple dots mixed modes"`` when there are
        any), and a line on the dotted bridges when there is one.

    Raises
    ------
    InvalidParameterError
        ``sweep_result`` not a sweep result.
    """
    require(sweep_result, "sweep_result",
             ("parameter", "values", "veering_table", "value", "freq_hz", "kind", "n_tracks"),
             "SweepResult")
    show_local = flag("show_local", show_local)
    fig, ax = figure_axes(ax)
    x = np.asarray(sweep_result.values, dtype=float)
    table = sweep_result.veering_table()
    n = sweep_result.n_tracks
    import matplotlib.pyplot as plt
    cmap = plt.get_cmap("tab10" if n <= 10 else "turbo")
    any_gap = False
    for t in range(n):
        color = cmap(t % 10) if n <= 10 else cmap(t / max(n - 1, 1))
        y = table[t].to_numpy()
        ax.plot(x, y, "-o", ms=3.5, lw=1.4, color=color, gid=f"track-{t}",
                label=f"track {t}")
        gx, gy = _gap_bridges(x, y)
        if gx.size:
            any_gap = True
            ax.plot(gx, gy, ":", lw=1.0, color=color, gid=f"gap-{t}")
    dots = ""
    if show_local:
        kinds = np.asarray(sweep_result.kind)
        untracked = np.asarray(getattr(sweep_result, "track", np.full(kinds.shape, -1))) < 0
        for kind, color in (("local", "0.55"), ("mixed", "tab:purple")):
            sel = (kinds == kind) & untracked
            if kind == "local" or np.any(sel):
                ax.scatter(np.asarray(sweep_result.value)[sel],
                           np.asarray(sweep_result.freq_hz)[sel], s=6, color=color,
                           zorder=1, gid=f"{kind}-modes", label=f"{kind} modes")
                dots += (", grey dots local modes" if kind == "local"
                         else ", purple dots mixed modes")
    ax.set_xlabel(sweep_result.parameter)
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(f"Modes along the sweep: {n} platform-mode tracks" + dots
                 + ("\ndotted: a track through cable modes (its mode labelled local there)"
                    if any_gap else ""))
    if n <= 12:
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, borderaxespad=0)
    ax.grid(True, alpha=0.3)
    if x.size > 1 and x.min() > 0 and x.max() >= LOG_SPAN * x.min():
        ax.set_xscale("log")                  # a decade or more of a positive parameter
        pad = (x.max() / x.min()) ** 0.02
        ax.set_xlim(x.min() / pad, x.max() * pad)
    elif x.size > 1:
        pad = 0.02 * (x.max() - x.min())
        ax.set_xlim(x.min() - pad, x.max() + pad)
    return fig
