"""Figures of a workspace map (an ``xarray.Dataset`` of :func:`dynstiff.workspace`):
horizontal slices and a 3-D view of the first platform frequency, the band margin and the
dynamic workspace (docs/theory.md §13). matplotlib is imported when a figure is drawn.

Over an ``orientation`` or ``parameter`` dimension the figures show the worst case: the
least first platform frequency and band margin, and a pose belongs to the dynamic workspace
only when every check passes for every orientation and value.
"""

import numpy as np

from dynstiff.errors import InvalidParameterError

__all__ = ["MAX_SLICES", "plot_workspace_3d", "plot_workspace_slices", "slice_levels",
           "worst_case"]

_REDUCED = ("orientation", "parameter")


def worst_case(ds):
    """(first platform frequency [Hz], band margin [-], dynamic, feasible) over x, y, z: the
    least value and the all-pass verdict over the orientations and parameter values. A NaN
    (platform modes not all found) at any orientation or value makes the least value NaN."""
    if not all(d in ds.dims for d in ("x", "y", "z")):
        raise InvalidParameterError(
            "the workspace figures need a grid map (dimensions x, y, z): give box= to "
            "dynstiff.maps.workspace")
    red = [d for d in _REDUCED if d in ds.dims]
    f1 = ds["first_platform_hz"].min(red, skipna=False) if red else ds["first_platform_hz"]
    mg = ds["band_margin"].min(red, skipna=False) if red else ds["band_margin"]
    dyn = ds["dynamic"].all(red) if red else ds["dynamic"]
    feas = ds["feasible"].all(red) if red else ds["feasible"]
    return (f1.transpose("x", "y", "z"), mg.transpose("x", "y", "z"),
            dyn.transpose("x", "y", "z"), feas.transpose("x", "y", "z"))


def _edges(v):
    """Cell edges around the centres v (a single centre gets a unit-width cell)."""
    if v.size == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


#: Most heights the slices figure draws by default.
MAX_SLICES = 8


def slice_levels(n_z, n_slices=None):
    """Indices of the heights drawn: every one of the ``n_z`` levels when ``n_slices`` is
    None and ``n_z`` <= :data:`MAX_SLICES`, else ``n_slices`` (default MAX_SLICES) evenly
    spread from the lowest to the highest."""
    if n_slices is None:
        n_slices = MAX_SLICES
    if isinstance(n_slices, bool) or not isinstance(n_slices, int | np.integer) \
            or n_slices < 1:
        raise InvalidParameterError(f"n_slices must be an integer >= 1, got {n_slices!r}")
    if n_z <= n_slices:
        return np.arange(n_z)
    return np.unique(np.linspace(0, n_z - 1, n_slices).round().astype(int))


def plot_workspace_slices(ds, n_slices=None, fig=None):
    """Horizontal slices (x, y) at the heights z: first platform frequency [Hz] (top), band
    margin [-] (middle, 0 and the required margin as contours) and the dynamic workspace
    (bottom: every check passes / a check fails / infeasible).

    Each position is a cell centred on it (1 m wide along an axis with a single value); all
    panels share their x and y axes, the bottom panels labelled x [m] and the left panels
    y [m]. The frequency panels share one colour scale, from the least to the greatest
    frequency of the map (0 to 1 Hz when none is finite). The margin scale is red below 0 and blue
    above, symmetric about 0 (to the largest absolute margin, or 1 when none is finite); its
    contours are 0.8 pt black lines, drawn where the grid is at least 2 x 2 and the height
    has more than three finite margins. The dynamic workspace is green where every check
    passes, orange where one fails and grey (0.75) where infeasible. Each row's colour bar
    stands beside it, 0.9 of its height. The figure is 9 in tall and max(3.4 n + 1.2, 8) in
    wide for n heights drawn, laid out without overlaps or blank margins (constrained
    layout).

    Parameters
    ----------
    ds : xarray.Dataset
        A grid map of :func:`dynstiff.workspace`.
    n_slices : int, optional
        Most heights drawn (:func:`slice_levels`); default every height of the grid up to
        :data:`MAX_SLICES`. When fewer heights than the grid's are drawn, the title says
        which: ``; n of N heights drawn (z = z1, z2, ... m)``.
    fig : matplotlib Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        One column of three panels per height drawn, each titled ``z = ... m``. The figure's
        title gives the robot, the dimensions reduced to their worst case, how many positions
        are in the dynamic workspace, and the forbidden band [Hz] and margin (or "no band");
        it is wrapped to fit the figure's width.
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap, TwoSlopeNorm
    from matplotlib.figure import Figure

    if fig is not None and not isinstance(fig, Figure):
        raise InvalidParameterError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
    f1, mg, dyn, feas = worst_case(ds)
    x, y, z = (ds[c].values for c in ("x", "y", "z"))
    ks = slice_levels(z.size, n_slices)
    width = max(3.4 * ks.size + 1.2, 8.0)
    if fig is None:
        fig = plt.figure(figsize=(width, 9.0), layout="constrained")
    axs = np.asarray(fig.subplots(3, ks.size, squeeze=False, sharex=True, sharey=True))
    xe, ye = _edges(x), _edges(y)
    finite = np.isfinite(f1.values)
    fmin, fmax = ((np.nanmin(f1.values), np.nanmax(f1.values)) if finite.any() else (0, 1))
    m = mg.values[np.isfinite(mg.values)]
    lim = max(np.abs(m).max() if m.size else 1.0, 1e-3)
    need = float(ds.attrs.get("margin", 0.0))
    state = np.where(~feas.values, 0, np.where(dyn.values, 2, 1))
    cmap_state = ListedColormap(["0.75", "tab:orange", "tab:green"])
    for j, k in enumerate(ks):
        a0, a1, a2 = axs[:, j]
        im0 = a0.pcolormesh(xe, ye, f1.values[:, :, k].T, cmap="viridis", vmin=fmin,
                            vmax=fmax)
        im1 = a1.pcolormesh(xe, ye, mg.values[:, :, k].T, cmap="RdBu",
                            norm=TwoSlopeNorm(0.0, -lim, lim))
        if x.size > 1 and y.size > 1 and np.isfinite(mg.values[:, :, k]).sum() > 3:
            a1.contour(x, y, mg.values[:, :, k].T, levels=sorted({0.0, need}), colors="k",
                       linewidths=0.8)
        im2 = a2.pcolormesh(xe, ye, state[:, :, k].T, cmap=cmap_state, vmin=-0.5, vmax=2.5)
        for a in (a0, a1, a2):
            a.set_facecolor("0.75")
            a.set_aspect("equal")
        a0.set_title(f"z = {z[k]:.3g} m")
        a2.set_xlabel("x [m]")
    for a in axs[:, 0]:
        a.set_ylabel("y [m]")
    fig.colorbar(im0, ax=axs[0, :], label="first platform frequency [Hz]", shrink=0.9)
    fig.colorbar(im1, ax=axs[1, :], label="band margin [-]", shrink=0.9)
    cb = fig.colorbar(im2, ax=axs[2, :], ticks=[0, 1, 2], shrink=0.9)
    cb.ax.set_yticklabels(["infeasible", "check fails", "all pass"])
    band = ds.attrs.get("band_hz", None)
    band = (f"forbidden band {np.round(np.asarray(band, float), 3).tolist()} Hz, margin "
            f"{100 * need:.3g}%" if not isinstance(band, str) and band is not None
            else "no band")
    worst = " (worst case over " + ", ".join(d for d in _REDUCED if d in ds.dims) + ")" \
        if any(d in ds.dims for d in _REDUCED) else ""
    shown = ("" if ks.size == z.size else
             f"; {ks.size} of {z.size} heights drawn (z = "
             + ", ".join(f"{z[k]:.3g}" for k in ks) + " m)")
    import textwrap
    lines = [f"{ds.attrs.get('robot', '')} workspace map{worst}: {int(dyn.sum())} of "
             f"{dyn.size} positions in the dynamic workspace{shown}",
             f"{band}; grey: infeasible, or platform modes not all found"]
    chars = int(fig.get_figwidth() * 11)          # about 11 characters per inch at 12 pt
    fig.suptitle("\n".join(textwrap.fill(t, chars) for t in lines))
    return fig


def plot_workspace_3d(ds, ax=None):
    """3-D view: feasible positions coloured by their first platform frequency [Hz], the
    dynamic workspace as filled markers, the rest hollow; infeasible positions as grey
    dots; feasible positions whose platform modes were not all found (frequency NaN) as
    black crosses, so every position is drawn. Filled and hollow markers take the colour
    bar's colour of their frequency, without depth shading; the legend is in the upper
    left. The title gives the robot and how many positions pass every check. A new figure
    is 7.5 x 6 in.

    Parameters
    ----------
    ds : xarray.Dataset
        A grid map of :func:`dynstiff.workspace`.
    ax : matplotlib 3-D Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt
    from matplotlib.axes import Axes

    if ax is not None and not (isinstance(ax, Axes) and ax.name == "3d"):
        raise InvalidParameterError(f"ax must be a matplotlib 3-D Axes (projection='3d'), got "
                                    f"{type(ax).__name__}")
    f1, _, dyn, feas = worst_case(ds)
    X, Y, Z = np.meshgrid(ds["x"].values, ds["y"].values, ds["z"].values, indexing="ij")
    if ax is None:
        fig = plt.figure(figsize=(7.5, 6.0), layout="constrained")
        ax = fig.add_subplot(projection="3d")
    fig = ax.figure
    f, d, ok = f1.values, dyn.values, feas.values & np.isfinite(f1.values)
    vmin, vmax = (np.nanmin(f), np.nanmax(f)) if ok.any() else (0.0, 1.0)
    sc = ax.scatter(X[d & ok], Y[d & ok], Z[d & ok], c=f[d & ok], cmap="viridis", vmin=vmin,
                    vmax=vmax, s=28, depthshade=False, label="dynamic workspace")
    nd = ok & ~d
    ax.scatter(X[nd], Y[nd], Z[nd], facecolors="none", edgecolors=plt.get_cmap("viridis")(
        (f[nd] - vmin) / max(vmax - vmin, 1e-12)), s=22, depthshade=False,
        label="a check fails")
    ax.scatter(X[~feas.values], Y[~feas.values], Z[~feas.values], c="0.6", s=4,
               label="infeasible")
    lost = feas.values & ~np.isfinite(f)        # feasible, platform modes not all found
    ax.scatter(X[lost], Y[lost], Z[lost], c="k", marker="x", s=22, depthshade=False,
               label="modes not all found")
    fig.colorbar(sc, ax=ax, shrink=0.7, label="first platform frequency [Hz]")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.legend(loc="upper left", fontsize="small")
    ax.set_title(f"{ds.attrs.get('robot', '')}: {int(d.sum())} of {d.size} positions pass "
                 f"every check")
    return fig
