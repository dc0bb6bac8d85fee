"""3-D views of a robot at equilibrium and of its mode shapes (matplotlib imported here).

:func:`plot_robot` draws the anchors, the sagging cable profiles (elastic catenaries of the
:class:`~dynstiff.robot.robot.Equilibrium`) and the platform as the hull of its attachment points,
with the point P marked; given a mode, also the exaggerated deformed shape. The platform moves
by the small motion x = scale * (dp, dtheta), so an attachment point moves by

    dB_i = scale * (dp + dtheta x r_i),      r_i = R_p b_i,

and, with the :class:`~dynstiff.models.dsm.FrequencyModel` given, each cable by its closed-form
displacement field (:func:`dynstiff.analyses.modes.cable_fields`, theory.md §5.3) times the same
scale.
:func:`animate_mode` writes the oscillation shape * sin(2 pi t / T) over one period as a GIF.

Artists carry a ``gid``: ``anchors``, ``P``, ``cable-<i>`` (static cable i), ``platform``
(platform edges), ``platform-faces``; with a mode ``cable-<i>-mode``, ``platform-mode``,
``platform-mode-faces`` and ``P-mode``. A platform smaller than a tenth of the robot gets a
close-up axes of its own (gid ``platform-inset``, lines ``inset-platform`` and
``inset-platform-mode``), where its motion is drawn at its own scale.

What the figure shows (line widths in points, marker sizes in points^2):

- static cables (``cable-<i>``): 1.2 wide, dark grey (0.15); under a mode shape 0.9 wide,
  light grey (0.65);
- the static platform: edges (``platform``) 1.5 wide, faces (``platform-faces``, alpha 0.25)
  filled without edge lines, both orange, light grey under a mode shape; P (``P``) a dot
  (``o``, 20), black, light grey under a mode shape;
- the mode shape, drawn at B_i + scale * dB_i and P + scale * dp (plus, not minus: the
  displacement the mode's ``platform_shapes`` give): each cable (``cable-<i>-mode``) 1.3 wide
  in a colour of its own, the platform's edges (``platform-mode``) 2.0 wide and faces
  (``platform-mode-faces``, alpha 0.35, no edge lines) in orange, P (``P-mode``) an orange
  diamond (``D``, 60) edged in black; arrows (``motion``, black, 1.0 wide) from B_i and P to
  their displaced points;
- cable numbers (``anchor-label-<i>``, 8 pt, in the colour of cable i's mode shape) at each
  anchor point, offset along z by 2.5 % of the robot's size (the longest side of the bounding
  box of the anchors and attachment points): above the anchor for even i, below for odd i;
- the close-up (``platform-inset``): a cube (box aspect 1:1:1) seen as the main view, at
  most 3 tick intervals per axis, the last stretch of each cable 1.0 wide in light grey, the
  platform's edges 1.8 wide (light grey static, orange at B_i + f dB_i) and P an orange
  diamond (30) at P + f dp, with f = 0.25 * platform size / largest motion of the B_i and P,
  titled ``platform close-up, motion x <f:.3g>``.
"""

from pathlib import Path

import numpy as np

from dynstiff.errors import InvalidParameterError
from dynstiff.report.geometry3d import nonnegative, path_points, positive_int, prepare

__all__ = ["plot_robot", "animate_mode"]

_STATIC = "0.15"           # cables without a mode
_GHOST = "0.65"            # static shape under a mode shape
_MODE = {"global": "tab:red", "local": "tab:blue"}
_PLATFORM = "tab:orange"


# ------------------------------------------------------------------------- drawing
def _draw(ax, geo, factor):
    """Draw the static robot and, with a mode, its shape at ``factor`` * unit displacement.
    Returns the artists that move, for the animation."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    moving = {}
    with_mode = geo["dB"] is not None
    a = geo["anchors"]
    ax.scatter(a[:, 0], a[:, 1], a[:, 2], marker="s", s=22, color="k", depthshade=False,
               gid="anchors", label="anchors")
    for i, c in enumerate(geo["cables"]):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=_GHOST if with_mode else _STATIC,
                lw=0.9 if with_mode else 1.2, gid=f"cable-{i}",
                label="cables (static)" if i == 0 else None)
    B, P = geo["B"], geo["P"]
    color = _GHOST if with_mode else _PLATFORM
    if geo["faces"]:
        ax.add_collection3d(Poly3DCollection([B[f] for f in geo["faces"]], facecolor=color,
                                             alpha=0.25, edgecolor="none",
                                             gid="platform-faces"))
    if geo["path"]:
        pp = path_points(B, geo["path"])
        ax.plot(pp[:, 0], pp[:, 1], pp[:, 2], color=color, lw=1.5, gid="platform",
                label="platform" if not with_mode else "platform (static)")
    ax.scatter([P[0]], [P[1]], [P[2]], marker="o", s=20, color="k" if not with_mode
               else _GHOST, depthshade=False, gid="P", label="P")
    if not with_mode:
        return moving
    moving["cables"] = []
    for i, c in enumerate(geo["cables"] + factor * geo["cable_disp"]):
        (ln,) = ax.plot(c[:, 0], c[:, 1], c[:, 2], color=_cable_color(i), lw=1.3,
                        gid=f"cable-{i}-mode",
                        label="cables, mode shape (one colour each)" if i == 0 else None)
        moving["cables"].append(ln)
    Bd = B + factor * geo["dB"]
    if geo["faces"]:
        moving["faces"] = Poly3DCollection([Bd[f] for f in geo["faces"]],
                                           facecolor=_PLATFORM, alpha=0.35, edgecolor="none",
                                           gid="platform-mode-faces")
        ax.add_collection3d(moving["faces"])
    if geo["path"]:
        pp = path_points(Bd, geo["path"])
        (moving["platform"],) = ax.plot(pp[:, 0], pp[:, 1], pp[:, 2], color=_PLATFORM,
                                        lw=2.0, gid="platform-mode",
                                        label="platform, mode shape")
    Pd = P + factor * geo["dP"]
    # a marker of fixed size in points: the platform stays visible on a large frame
    moving["P"] = ax.scatter([Pd[0]], [Pd[1]], [Pd[2]], marker="D", s=60, color=_PLATFORM,
                             edgecolor="k", depthshade=False, gid="P-mode",
                             label="P, mode shape")
    return moving


#: Colours of the cables' mode shapes, cycled: neighbours in a pair differ, and none is the
#: platform's orange or the static grey.
_CABLE_COLORS = ("tab:blue", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink",
                 "tab:olive", "tab:cyan", "navy", "darkgreen", "maroon", "indigo")


def _cable_color(i):
    """Colour of cable i's mode shape."""
    return _CABLE_COLORS[i % len(_CABLE_COLORS)]


def _draw_annotations(ax, geo, factor):
    """Cable numbers at the anchors (one label per anchor point, listing every cable that
    leaves it) and arrows from the static to the displaced attachment points and P (the
    direction of motion at the drawn phase)."""
    a = geo["anchors"]
    span = np.ptp(np.vstack([a, geo["B"]]), axis=0).max()
    shared = np.linalg.norm(a[:, None, :] - a[None, :, :], axis=2) <= 1e-9 * max(1.0, span)
    for i, p in enumerate(a):
        first = int(np.argmax(shared[i]))
        if first < i:                       # a shared anchor point: labelled once, below
            continue
        off = 0.025 * span * (1 if i % 2 == 0 else -1)
        ax.text(p[0], p[1], p[2] + off, ",".join(str(j) for j in np.flatnonzero(shared[i])),
                color=_cable_color(i), fontsize=8, ha="center", va="center",
                gid=f"anchor-label-{i}")
    if geo["dB"] is None:
        return
    start = np.vstack([geo["B"], geo["P"][None, :]])
    d = factor * np.vstack([geo["dB"], geo["dP"][None, :]])
    keep = np.linalg.norm(d, axis=1) > 0
    if np.any(keep):
        ax.quiver(*start[keep].T, *d[keep].T, color="k", lw=1.0, arrow_length_ratio=0.3,
                  gid="motion", label="motion, static to displaced")


def _update(moving, geo, factor):
    """Move the mode-shape artists to ``factor`` * unit displacement."""
    for ln, c in zip(moving["cables"], geo["cables"] + factor * geo["cable_disp"]):
        ln.set_data_3d(c[:, 0], c[:, 1], c[:, 2])
    Bd = geo["B"] + factor * geo["dB"]
    if "faces" in moving:
        moving["faces"].set_verts([Bd[f] for f in geo["faces"]])
    if "platform" in moving:
        pp = path_points(Bd, geo["path"])
        moving["platform"].set_data_3d(pp[:, 0], pp[:, 1], pp[:, 2])
    Pd = geo["P"] + factor * geo["dP"]
    moving["P"]._offsets3d = ([Pd[0]], [Pd[1]], [Pd[2]])


def _set_limits(ax, geo, factors):
    """Equal-aspect limits enclosing the robot at every factor of the mode shape."""
    pts = [geo["anchors"], geo["B"], geo["P"][None, :], geo["cables"].reshape(-1, 3)]
    if geo["dB"] is not None:
        for f in factors:
            pts += [geo["B"] + f * geo["dB"], geo["P"][None, :] + f * geo["dP"][None, :],
                    (geo["cables"] + f * geo["cable_disp"]).reshape(-1, 3)]
    pts = np.vstack(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = hi - lo
    span = np.maximum(span, 0.15 * span.max()) * 1.06
    mid = 0.5 * (lo + hi)
    ax.set_xlim(mid[0] - span[0] / 2, mid[0] + span[0] / 2)
    ax.set_ylim(mid[1] - span[1] / 2, mid[1] + span[1] / 2)
    ax.set_zlim(mid[2] - span[2] / 2, mid[2] + span[2] / 2)
    ax.set_box_aspect(span, zoom=1.0)
    from matplotlib.ticker import MaxNLocator
    for axis, length in zip((ax.xaxis, ax.yaxis, ax.zaxis), span):
        axis.set_major_locator(MaxNLocator(int(np.clip(round(8 * length / span.max()), 3, 8))))


#: A platform smaller than this fraction of the robot's size gets a close-up beside it.
_INSET_BELOW = 0.1


def _platform_inset(fig, geo):
    """A close-up of the platform when it is small beside the robot (gid
    ``platform-inset``): the static platform in grey, the mode's platform motion in orange at
    its own scale (the largest attachment-point motion 25 % of the platform's size) and the
    last stretch of every cable. Returns the inset Axes or None."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    B, P = geo["B"], geo["P"]
    pts = np.vstack([geo["anchors"], B])
    size = float(np.ptp(pts, axis=0).max())
    plat = float(np.ptp(B, axis=0).max())
    if geo["dB"] is None or not 0 < plat < _INSET_BELOW * size:
        return None
    motion = max(float(np.linalg.norm(geo["dB"], axis=1).max()), float(np.linalg.norm(geo["dP"])))
    f = 0.25 * plat / motion if motion > 0 else 0.0
    ax = fig.add_axes((0.72, 0.02, 0.27, 0.5), projection="3d")
    ax.set_gid("platform-inset")
    reach = 0.9 * plat
    for i, c in enumerate(geo["cables"]):
        near = np.linalg.norm(c - B[i], axis=1) <= reach
        ax.plot(*c[near].T, color=_GHOST, lw=1.0)
    for pts_, color, gid in ((B, _GHOST, "inset-platform"),
                             (B + f * geo["dB"], _PLATFORM, "inset-platform-mode")):
        if geo["faces"]:
            ax.add_collection3d(Poly3DCollection([pts_[fc] for fc in geo["faces"]],
                                                 facecolor=color, alpha=0.35,
                                                 edgecolor="none"))
        if geo["path"]:
            pp = path_points(pts_, geo["path"])
            ax.plot(pp[:, 0], pp[:, 1], pp[:, 2], color=color, lw=1.8, gid=gid)
    Pd = P + f * geo["dP"]
    ax.scatter([Pd[0]], [Pd[1]], [Pd[2]], marker="D", s=30, color=_PLATFORM, edgecolor="k",
               depthshade=False)
    allp = np.vstack([B, B + f * geo["dB"], Pd[None, :]])
    mid = 0.5 * (allp.min(axis=0) + allp.max(axis=0))
    half = 0.5 * max(float(np.ptp(allp, axis=0).max()), 1e-9) * 1.5
    for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
        setter(m - half, m + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=22, azim=-60)
    from matplotlib.ticker import MaxNLocator
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(3))
    ax.tick_params(labelsize=6, pad=0)
    ax.set_title(f"platform close-up, motion x {f:.3g}", fontsize=8)
    return ax


def _title(eq, geo, k, n_modes, scale, sag_scale):
    name = getattr(eq.robot, "name", "") or "robot"
    if geo["dB"] is None:
        t = f"{name} at equilibrium, P = {np.round(geo['P'], 3).tolist()} m"
    else:
        t = f"{name}: mode {k + 1} of {n_modes}, {geo['freq_hz']:.4g} Hz, {geo['kind']}"
        if not np.any(geo["dB"]) and not np.any(geo["cable_disp"]):
            t += "\nplatform at rest (purely local cable mode; shape not drawn)"
        else:
            t += f"\ndisplacements x {scale:.3g}"
            if not geo["dynamic"]:
                t += ", cables quasi-static (give model= for their fields)"
    if sag_scale != 1.0:
        t += f"; sag x {sag_scale:g}"
    return t


def _flatness(geo):
    """1 - height / width of the robot's bounding box, in [0, 1]."""
    pts = np.vstack([geo["anchors"], geo["B"]])
    span = np.maximum(np.ptp(pts, axis=0), 1e-9)
    return float(np.clip(1.0 - span[2] / max(span[0], span[1]), 0.0, 1.0))


def _figsize(geo):
    """Figure size fitted to the robot's proportions (a flat robot gets a flat figure, so no
    blank band is left below the axes box) [in]."""
    return 10.0, float(10.0 * (0.24 + 0.5 * (1.0 - _flatness(geo))))


def _axes3d(ax, figsize=(8.0, 6.0)):
    if ax is None:
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=figsize)
        # the robot on the left, the legend and the platform's close-up on the right
        ax = fig.add_axes((-0.03, -0.07, 0.74, 0.98), projection="3d")
        return fig, ax
    if getattr(ax, "name", "") != "3d":
        raise InvalidParameterError(
            f"ax must be a 3-D Axes (add_subplot(projection='3d')), got "
            f"{type(ax).__name__}")
    return ax.figure, ax


def plot_robot(eq, modes=None, mode=None, scale=None, ax=None, n_points=41, model=None,
               sag_scale=1.0):
    """3-D view of the robot at equilibrium, optionally with an exaggerated mode shape.

    Draws the anchors A_i (squares), the sagging cables (elastic-catenary profiles of
    ``eq.states``, anchor to attachment point), the platform as the convex hull of its
    attachment points B_i (a polygon when they are coplanar, nothing when they coincide, as
    for a point mass) and P (dot). With a mode, the static shape is drawn in grey and the
    deformed one in colour: attachment points at B_i + scale (dp + dtheta x r_i), P at
    P + scale dp, cables at their profile + scale * their displacement field.

    Parameters
    ----------
    eq : Equilibrium
        Static equilibrium of the robot (``robot.equilibrium(...)``).
    modes : ModalResult, optional
        From ``dynstiff.modes(FrequencyModel(eq), ...)``; ``platform_shapes`` shape (n_modes, 6)
        [m, rad].
    mode : int, optional
        0-based index of the mode to draw (required with ``modes``); the title numbers modes
        from 1, as :meth:`ModalResult.to_frame` does.
    scale : float, optional
        Displacement magnification [-], >= 0. Default: the largest displacement drawn is
        5 % of the diagonal of the bounding box of the anchors and attachment points.
    ax : mpl_toolkits.mplot3d.Axes3D, optional
    n_points : int
        Points per cable profile (>= 2, default 41).
    model : FrequencyModel, optional
        The model that computed ``modes``. When given, the cables move by their closed-form
        fields (:func:`dynstiff.analyses.modes.cable_fields`); otherwise each cable point moves by
        the straight-line (quasi-static) interpolation t * dB_i, t the chordwise position in
        [0, 1].
    sag_scale : float
        Magnification of each cable's deviation from its chord, for display only (>= 0,
        default 1: true geometry). Cable ends are unchanged.

    Returns
    -------
    matplotlib Figure
        Axes with equal scales, labels ``x [m]``, ``y [m]``, ``z [m]``; gids ``anchors``,
        ``P``, ``cable-<i>``, ``platform``, ``platform-faces`` and, with a mode,
        ``cable-<i>-mode``, ``platform-mode``, ``platform-mode-faces``, ``P-mode``
        (their styles: see the module's docstring).

        Layout: seen from elevation 22 deg, azimuth -60 deg. Limits: the bounding box of
        everything drawn (static and displaced), each side raised to at least 15 % of the
        longest one, then widened by 6 %, about its centre; box aspect the sides' lengths;
        on each axis at most round(8 * side / longest side), clipped to [3, 8], tick
        intervals (:class:`~matplotlib.ticker.MaxNLocator`). A new figure is 10 in wide and
        10 * (0.24 + 0.5 * min(1, h / w)) in high, h the height and w the longest horizontal
        side of the bounding box of anchors and attachment points (sides below 1e-9 m count
        as 1e-9 m); its 3-D axes fill the rectangle (-0.03, -0.07, 0.74, 0.98) of the figure
        and the figure's legend (7 pt) has its upper left corner at (0.71, 0.97) (figure
        fraction). Given ``ax``, the legend stands at the axes' right, its centre left point
        at (1.17, 0.5) (axes fraction).

        Title (10 pt, at y = 0.98 of a new figure, 0.9 of a given ``ax``, to which Axes3D
        applies its own factor 0.92): ``<name> at equilibrium, P = [x, y, z] m`` (P rounded
        to 1 mm) without a mode; with one, ``<name>: mode <mode + 1> of <n_modes>, <f:.4g>
        Hz, <kind>`` and a second line ``displacements x <scale:.3g>`` (followed by
        ``, cables quasi-static (give model= for their fields)`` without ``model``), or
        ``platform at rest (purely local cable mode; shape not drawn)`` when nothing drawn
        moves; ``; sag x <sag_scale:g>`` is appended when ``sag_scale`` != 1. ``<name>`` is
        the robot's name, or ``robot`` when it has none.

    Raises
    ------
    InvalidParameterError
        ``eq`` not an equilibrium, ``modes`` not a ModalResult, ``mode`` missing or out of
        range, ``scale`` or ``sag_scale`` negative, ``n_points`` < 2, ``model`` not the
        FrequencyModel of ``eq``, ``ax`` not 3-D.
    """
    geo, k, scale, sag_scale = prepare(eq, modes, mode, scale, n_points, model, sag_scale)
    new = ax is None
    fig, ax = _axes3d(ax, figsize=_figsize(geo))
    _draw(ax, geo, scale if modes is not None else 0.0)
    _draw_annotations(ax, geo, scale if modes is not None else 0.0)
    _set_limits(ax, geo, [scale] if modes is not None else [])
    ax.view_init(elev=22, azim=-60)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.set_title(_title(eq, geo, k, None if modes is None else len(modes), scale, sag_scale),
                 fontsize=10, y=0.98 if new else 0.9)
    if new:
        fig.legend(*ax.get_legend_handles_labels(), loc="upper left",
                   bbox_to_anchor=(0.71, 0.97), fontsize=7, framealpha=0.8)
        _platform_inset(fig, geo)
    else:
        ax.legend(loc="center left", bbox_to_anchor=(1.17, 0.5), fontsize=7, framealpha=0.8)
    return fig


def animate_mode(eq, modes, mode, path, model=None, frames=24, scale=None, fps=12,
                 sag_scale=1.0, dpi=80):
    """Write a GIF of a mode oscillating over one period: shape * sin(2 pi j / frames).

    Parameters
    ----------
    eq : Equilibrium
    modes : ModalResult
        From ``dynstiff.modes(FrequencyModel(eq), ...)``.
    mode : int
        0-based index of the mode.
    path : str or path-like
        Output file, ending in ``.gif``.
    model : FrequencyModel, optional
        The model of ``modes``, for the cable displacement fields (see :func:`plot_robot`).
    frames : int
        Frames per period (>= 2, default 24); frame j shows the shape times
        sin(2 pi j / frames).
    scale : float, optional
        Displacement magnification [-] at the peak (default as in :func:`plot_robot`).
    fps : float
        Frames per second of the file (> 0, default 12).
    sag_scale : float
        Display magnification of the cable sag (default 1).
    dpi : float
        Resolution of the frames [dots per inch] (default 80: 600 x 480 pixels).

    Returns
    -------
    pathlib.Path
        ``path``. The frames are 8 x 6 in, drawn as :func:`plot_robot` draws (same styles
        and gids, axes labels ``x [m]``, ``y [m]``, ``z [m]``), with limits enclosing the
        shape at +scale and -scale; frame j's mode shape is at B_i + scale * sin(2 pi j /
        frames) * dB_i (and likewise P and the cables).

    Raises
    ------
    InvalidParameterError
        Bad argument (as :func:`plot_robot`), ``path`` not ending in ``.gif``,
        ``frames`` < 2, ``fps`` not > 0, or pillow not installed.
    """
    import importlib.util
    if importlib.util.find_spec("PIL") is None:        # matplotlib's PillowWriter needs it
        raise InvalidParameterError(
            "animate_mode writes GIFs with matplotlib's PillowWriter, which needs the "
            "'pillow' package; install it (pip install pillow)")
    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise InvalidParameterError(f"path must end in .gif, got {str(path)!r}")
    frames = positive_int("frames", frames, 2)
    fps = nonnegative("fps", fps)
    if fps == 0:
        raise InvalidParameterError(f"fps must be > 0, got {fps!r}")
    if modes is None:
        raise InvalidParameterError("modes must be a dynstiff.ModalResult, got None")
    geo, k, scale, sag_scale = prepare(eq, modes, mode, scale, 41, model, sag_scale)
    from matplotlib.animation import PillowWriter
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8.0, 6.0), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.04, top=0.92)
    moving = _draw(ax, geo, 0.0)
    _set_limits(ax, geo, [scale, -scale])
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(_title(eq, geo, k, len(modes), scale, sag_scale), fontsize=10)
    clock = fig.text(0.02, 0.03, "", fontsize=10)
    writer = PillowWriter(fps=fps)
    path.parent.mkdir(parents=True, exist_ok=True)
    with writer.saving(fig, str(path), dpi):
        for j in range(frames):
            _update(moving, geo, scale * np.sin(2.0 * np.pi * j / frames))
            clock.set_text(f"t = {j}/{frames} T")       # also keeps every frame distinct
            writer.grab_frame()
    return path
