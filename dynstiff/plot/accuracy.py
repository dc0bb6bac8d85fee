"""The speed-accuracy chart of the model ladder: cost against error, the Pareto front.
"""

import numpy as np

from dynstiff.errors import InvalidParameterError
from dynstiff.plot.common import figure_axes, require

__all__ = ["plot_speed_accuracy"]


# -------------------------------------------------------------------- speed-accuracy
def _pareto_flags(cost, err):
    """Non-dominated points (lowest cost for their error): after sorting by cost (ties by
    error), a point is on the front when its error is below every cheaper point's. Infinite
    errors are never on it. Returns a bool array, shape (n,)."""
    order = np.lexsort((err, cost))
    flags = np.zeros(cost.size, dtype=bool)
    best = np.inf
    for j in order:
        if err[j] < best:
            flags[j] = True
            best = err[j]
    return flags


def _label_offsets(u, v):
    """Vertical offsets [points] of the labels of points (u, v) (log coordinates), stepped
    so that labels of neighbouring points do not overlap. Points are placed in order of u;
    two are neighbours when |du| < 0.3 and |dv| < 0.08 times the span of u and of v (each
    span at least 1). A label starts at 4 and steps 4, -12, 20, -28, ... until its offset
    differs from those of its already placed neighbours."""
    span_u = max(np.ptp(u), 1.0)
    span_v = max(np.ptp(v), 1.0)
    dy = np.full(u.size, 4.0)
    placed = []
    for j in np.argsort(u):
        near = [dy[i] for i in placed
                if abs(u[j] - u[i]) < 0.3 * span_u and abs(v[j] - v[i]) < 0.08 * span_v]
        while dy[j] in near:
            dy[j] = -dy[j] - 8.0 if dy[j] > 0 else -dy[j] + 8.0
        placed.append(j)
    return dy


def plot_speed_accuracy(df, error="err first 20", cost="40 modes [s]", ax=None):
    """Speed against accuracy of several models: one annotated point per model, log-log,
    with the Pareto front as a step line.

    Per model (rows grouped by ``"model"``), the error is the worst over the cases (rows)
    and the cost the median of ``cost`` plus the median of ``"build [s]"``. A model whose
    error is infinite (it misses modes, e.g. a massless-cable model asked for cable modes)
    is drawn as an open 7 pt triangle a decade above the largest positive error and
    annotated "(misses modes)", a dotted grey line (colour 0.6, 0.6 pt) across the axes at
    its height. A zero error is drawn at a tenth of the smallest positive one; without a
    positive error, a zero error is drawn at 1e-12 and an infinite one at 1.

    Model k takes colour k mod 10 of the tab10 palette whatever the matplotlib style
    (triangles included); models on the front are drawn as 8 pt circles edged in black, the
    others as 6 pt. Labels (8 pt) sit 5 points right of their point, stepped up or down so
    that labels of neighbouring points do not overlap.
    The front is a dashed black step line, 1 pt wide with alpha 0.7, named "Pareto front
    (black-edged points)" in a legend at lower left. The x axis is labelled "wall time:
    <cost without ' [s]'> + build [s]"; the margins are 25 % in x and 20 % in y; a grid is
    drawn at the major and minor ticks of both axes, with alpha 0.3. A new figure is 6.5 x
    4.5 in.

    Parameters
    ----------
    df : pandas.DataFrame
        One row per case and model, as returned by ``validation/speed_accuracy.py``'s
        ``run()``: columns ``"model"``, ``error``, ``cost`` and ``"build [s]"``. Numbers
        held in object columns are read as floats.
    error : str
        Error column [-] (or [decades] for the FRF log error).
    cost : str
        Wall-time column [s] of the job, e.g. ``"40 modes [s]"`` or ``"FRF [s]"``.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Figure
        Points and annotations have gid ``model-<name>``; the front has gid ``pareto``.

    Raises
    ------
    InvalidParameterError
        A column is missing, there are no rows, an error is NaN or below 0 (a case whose
        error is NaN would drop out of the worst over the cases), a cost is not finite
        and > 0, or two models have the same text (1 and "1").
    """
    require(df, "df", ("groupby", "columns"), "pandas DataFrame")
    for col in ("model", error, cost, "build [s]"):
        if col not in df.columns:
            raise InvalidParameterError(
                f"df has no column {col!r} (columns: {list(df.columns)})")
    if len(df) == 0:
        raise InvalidParameterError("df has no rows")
    rows = df[error].to_numpy(dtype=float)   # per row: the aggregation would skip NaN
    if np.any(np.isnan(rows) | (rows < 0)):
        k = int(np.flatnonzero(np.isnan(rows) | (rows < 0))[0])
        raise InvalidParameterError(f"df: {error!r} must be >= 0 or inf, got {float(rows[k])!r} "
                                    f"(model {str(df['model'].iloc[k])!r}, row {k})")
    g = df.groupby("model", sort=False).agg({error: "max", cost: "median",
                                              "build [s]": "median"})
    names = [str(n) for n in g.index]
    if len(set(names)) < len(names):
        twice = sorted({n for n in names if names.count(n) > 1})
        raise InvalidParameterError(f"df: models {list(g.index)} are not distinct as text "
                                    f"({twice} twice): their labels and gids would be one")
    err = g[error].to_numpy(dtype=float)
    total = (g[cost] + g["build [s]"]).to_numpy(dtype=float)
    if not np.all(np.isfinite(total) & (total > 0)):
        bad = names[int(np.flatnonzero(~(np.isfinite(total) & (total > 0)))[0])]
        raise InvalidParameterError(
            f"df: {cost!r} + 'build [s]' must be finite and > 0 [s]; model {bad!r} has "
            f"{total[names.index(bad)]!r}")
    finite = np.isfinite(err)
    positive = err[finite & (err > 0)]
    floor = 0.1 * positive.min() if positive.size else 1e-12
    ceiling = 10.0 * positive.max() if positive.size else 1.0
    y = np.where(finite, np.maximum(err, floor), ceiling)
    on_front = _pareto_flags(total, err)
    fig, ax = figure_axes(ax, figsize=(6.5, 4.5))
    import matplotlib.pyplot as plt
    cmap = plt.get_cmap("tab10")
    dy = _label_offsets(np.log10(total), np.log10(y))
    for k, name in enumerate(names):
        color = cmap(k % 10)
        if finite[k]:
            ax.loglog(total[k], y[k], "o", ms=8 if on_front[k] else 6, color=color,
                      mec="k" if on_front[k] else color, gid=f"model-{name}")
            text = name
        else:
            ax.loglog(total[k], y[k], "^", ms=7, mfc="none", color=color,
                      gid=f"model-{name}")
            text = f"{name} (misses modes)"
        ax.annotate(text, (total[k], y[k]), fontsize=8, xytext=(5, dy[k]),
                    textcoords="offset points", gid=f"model-{name}")
    front = np.flatnonzero(on_front)
    front = front[np.argsort(total[front])]
    if front.size:
        ax.step(total[front], y[front], where="post", color="k", lw=1.0, ls="--",
                alpha=0.7, gid="pareto",
                label="Pareto front (black-edged points)")
        ax.legend(loc="lower left", fontsize=8)
    if not np.all(finite):
        ax.axhline(ceiling, color="0.6", lw=0.6, ls=":")
    ax.set_xlabel(f"wall time: {cost.replace(' [s]', '')} + build [s]")
    ax.set_ylabel(f"{error} (worst case)")
    ax.grid(True, which="both", alpha=0.3)
    ax.margins(x=0.25, y=0.2)
    return fig
