"""Frequency response functions: magnitude (and phase) against frequency, the modes marked
and named by class.
"""

import numpy as np

from dynstiff._validate import flag
from dynstiff.constants import DOF_NAMES, LOAD_NAMES
from dynstiff.errors import InvalidParameterError
from dynstiff.plot.common import CATEGORY_LABELS, COLORS, figure_axes, mode_categories, require

__all__ = ["CHANNEL_COLORS", "plot_frf"]

#: Colours of the FRF curves, cycled: none is a mode class's colour (red, purple, blue).
CHANNEL_COLORS = ("black", "tab:orange", "tab:green", "tab:brown", "tab:olive", "tab:cyan",
                  "tab:pink", "tab:gray")


def _reciprocal(o, i):
    """The channel (output, input) reciprocal to (o, i): the input's DOF over the output's
    load."""
    return DOF_NAMES[LOAD_NAMES.index(i)], LOAD_NAMES[DOF_NAMES.index(o)]


# ------------------------------------------------------------------------------- FRF
def plot_frf(result, modes=None, pairs=None, ax=None, phase=False):
    """Magnitude (and phase) of FRFs against frequency, with the natural frequencies marked.

    Parameters
    ----------
    result : FRFResult
        ``H`` of shape (n_freq, n_out, n_in) at ``freq_hz``, shape (n_freq,) [Hz].
    modes : ModalResult, optional
        Marks each mode inside the band by a dashed vertical line, 0.6 wide with alpha 0.6
        so that the curves show through, coloured by its platform share
        (:func:`mode_categories`): red (gid ``mode-global``), purple (``mode-mixed``),
        blue (``mode-local``); the legend names the three, each by a dashed line 0.8 wide
        in its class's colour. The curves take other colours (:data:`CHANNEL_COLORS`) and
        are solid, 1.0 wide; a channel drawn after its reciprocal twin (``z / fx`` after
        ``x / fz``, equal by reciprocity) is dashed (4 on, 3 off, in line widths) and
        2.0 wide so both stay visible. The legend (8 pt) stands right of the axes, its top
        left corner at (1.01, 1.0), clear of the peaks.
    pairs : list of (output, input), optional
        Channels to draw, e.g. ``[("z", "fz")]`` (default: the pairs ``(outputs[k],
        inputs[k])`` present in ``result``).
    ax : matplotlib Axes, optional
        Axes for the magnitude. When given, only the magnitude is drawn (``phase`` must be
        False: one axes cannot hold both) and its figure is not laid out again: ``ax`` keeps
        its place. A new figure is laid out tight, the legend inside it.
    phase : bool
        With ``ax`` None, add a second axes below for the phase [deg] (default False); the
        new figure is then 10 x 6 in, the magnitude axes twice as tall as the phase axes.
        The phase axes span -190 to 190 deg, ticks every 90 deg from -180, with a light
        grid; the frequency label goes under the lowest axes. Both span exactly the
        frequencies of ``result``.

    Returns
    -------
    matplotlib Figure
        Its first axes holds the magnitude, on a log scale, in the units of ``result.kind``:
        the y label is ``|kind|`` and the unit when all curves share one, "[units in the
        legend]" when they differ, no unit when ``result`` has no ``unit`` method. The title
        (10 pt) reads "FRF (kind), natural frequencies dashed" and, on a second line,
        ``result.damping`` ("not stated" when ``result`` has none), followed for an
        "undamped" result by "; each peak is the grid's value next to a pole".

    Raises
    ------
    InvalidParameterError
        ``result`` not an FRF result, ``modes`` not a modal result, a channel of ``pairs``
        not in ``result``, or ``phase`` True with ``ax`` given.
    """
    require(result, "result", ("freq_hz", "H", "inputs", "outputs", "kind"), "FRFResult")
    if modes is not None:
        require(modes, "modes", ("freq_hz", "kind"), "ModalResult")
    phase = flag("phase", phase)
    if phase and ax is not None:
        raise InvalidParameterError(
            "phase=True draws its own figure (magnitude and phase axes): pass ax=None, or "
            "phase=False to draw the magnitude on ax")
    if pairs is None:
        pairs = list(zip(result.outputs, result.inputs))
    if isinstance(pairs, (str, bytes)) or not hasattr(pairs, "__iter__"):
        raise InvalidParameterError(f"pairs must be a list of (output, input), got {pairs!r}")
    idx = []
    for pair in pairs:
        try:
            o, i = pair
            idx.append((o, i, result.outputs.index(o), result.inputs.index(i)))
        except (TypeError, ValueError):
            raise InvalidParameterError(
                f"pairs must hold (output, input) with outputs among {tuple(result.outputs)} "
                f"and inputs among {tuple(result.inputs)}, got {pair!r}") from None
    own = ax is None
    if ax is None and phase:
        import matplotlib.pyplot as plt
        fig, (ax, ax_ph) = plt.subplots(2, 1, sharex=True, figsize=(10, 6),
                                        height_ratios=(2, 1))
    else:
        fig, ax = figure_axes(ax)
        ax_ph = None
    f = np.asarray(result.freq_hz)
    unit = getattr(result, "unit", None)
    units = {(o, i): unit(o, i) for o, i, _, _ in idx} if callable(unit) else {}
    one_unit = len(set(units.values())) == 1
    drawn = set()
    for n, (o, i, ko, ki) in enumerate(idx):
        h = result.H[:, ko, ki]
        tag = "" if one_unit or not units else f" [{units[(o, i)]}]"
        twin = _reciprocal(o, i)
        style = dict(color=CHANNEL_COLORS[n % len(CHANNEL_COLORS)], lw=1.0, ls="-",
                     gid=f"frf-{o}-{i}")
        label = f"{o} / {i}{tag}"
        if twin in drawn and twin != (o, i):
            style.update(ls=(0, (4, 3)), lw=2.0)
            label += f" (= {twin[0]} / {twin[1]}, reciprocity)"
        drawn.add((o, i))
        ax.semilogy(f, np.abs(h), label=label, **style)
        if ax_ph is not None:
            with np.errstate(invalid="ignore"):
                ax_ph.plot(f, np.degrees(np.angle(h)), **style)
    shown = []
    if modes is not None:
        cats = mode_categories(modes)
        for a in (ax, ax_ph):
            if a is None:
                continue
            for fm, cat in zip(modes.freq_hz, cats):
                if f[0] <= fm <= f[-1]:
                    a.axvline(fm, color=COLORS[cat], lw=0.6, alpha=0.6, ls="--",
                              gid=f"mode-{cat}")
                    if cat not in shown:
                        shown.append(cat)
    ax.set_ylabel(f"|{result.kind}|" + (f" [{next(iter(units.values()))}]" if one_unit
                                         else " [units in the legend]" if units else ""))
    damping = getattr(result, "damping", "not stated")
    ax.set_title(f"FRF ({result.kind}), natural frequencies dashed\n{damping}"
                 + ("; each peak is the grid's value next to a pole"
                    if damping == "undamped" else ""), fontsize=10)
    from matplotlib.lines import Line2D
    handles, labels = ax.get_legend_handles_labels()
    for cat in ("global", "mixed", "local"):
        if cat in shown:
            handles.append(Line2D([], [], color=COLORS[cat], lw=0.8, ls="--"))
            labels.append(CATEGORY_LABELS[cat])
    ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8,
              borderaxespad=0.0)
    ax.set_xlim(f[0], f[-1])
    if ax_ph is None:
        ax.set_xlabel("frequency [Hz]")
    else:
        ax_ph.set_xlabel("frequency [Hz]")
        ax_ph.set_ylabel("phase [deg]")
        ax_ph.set_ylim(-190.0, 190.0)
        ax_ph.set_yticks([-180, -90, 0, 90, 180])
        ax_ph.grid(True, alpha=0.3)
    if own:
        fig.tight_layout()
    return fig
