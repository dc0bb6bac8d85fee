"""Plots (matplotlib is imported here only). Each function takes ``ax=`` and returns the
figure; none calls ``show()``."""

import numpy as np

__all__ = ["plot_frf"]

_COLORS = {"global": "tab:red", "local": "tab:blue"}


def figure_axes(ax=None, figsize=(8, 4.5)):
    """(figure, axes): a new figure when ``ax`` is None, else ``ax`` and its figure."""
    if ax is None:
        import matplotlib.pyplot as plt
        return plt.subplots(figsize=figsize)
    return ax.figure, ax


def plot_frf(result, modes=None, pairs=None, ax=None):
    """Magnitude of FRFs against frequency, with the natural frequencies marked.

    Parameters
    ----------
    result : FRFResult
    modes : ModalResult, optional
        Marks each mode by a vertical line, red for global and blue for local modes.
    pairs : list of (output, input), optional
        Channels to draw (default: the diagonal pairs present in ``result``).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Figure
    """
    fig, ax = figure_axes(ax)
    if pairs is None:
        pairs = [(o, i) for o, i in zip(result.outputs, result.inputs)]
    for o, i in pairs:
        h = result.H[:, result.outputs.index(o), result.inputs.index(i)]
        ax.semilogy(result.freq_hz, np.abs(h), lw=1.0, label=f"{o} / {i}")
    if modes is not None:
        f_lo, f_hi = result.freq_hz[0], result.freq_hz[-1]
        for f, kind in zip(modes.freq_hz, modes.kind):
            if f_lo <= f <= f_hi:
                ax.axvline(f, color=_COLORS[kind], lw=0.6, alpha=0.6, ls="--",
                           gid=f"mode-{kind}")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(f"|{result.kind}|")
    ax.set_title(f"FRF ({result.kind}); dashed: modes, red global, blue local")
    ax.legend(loc="upper right", fontsize=8)
    return fig
