"""Modes and statics at a glance: natural frequencies by class, damped roots, a cable's
clamped frequencies by family, the tensions at both ends of every cable, and the predicted
error of every cable model.
"""

import numpy as np

from dynstiff._validate import positive_scalar, real_array
from dynstiff.constants import GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError
from dynstiff.plot.common import COLORS, figure_axes, require

__all__ = [
    "plot_cable_modes", "plot_damped_modes", "plot_model_errors", "plot_modes", "plot_tensions"
]


# ----------------------------------------------------------------------------- modes
def plot_modes(modes, ax=None):
    """Natural frequencies against their platform share of the kinetic energy.

    Parameters
    ----------
    modes : ModalResult
        ``freq_hz`` (n,) [Hz], ``cable_energy_fraction`` (n,) [-], ``kind`` (n,).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Figure
        One stem per mode up to its platform share, coloured by kind: red (gid
        ``modes-global``), purple (``modes-mixed``), blue (``modes-local``); dashed 0.8 pt
        lines at the kinds' thresholds 0.5 and 0.05 (docs/theory.md §12.1). The share axis
        runs from 0 to 1.05.
    """
    require(modes, "modes", ("freq_hz", "cable_energy_fraction", "kind"), "ModalResult")
    fig, ax = figure_axes(ax)
    f = np.asarray(modes.freq_hz, dtype=float)
    share = np.clip(1.0 - np.asarray(modes.cable_energy_fraction, dtype=float), 0.0, 1.0)
    kind = np.asarray(modes.kind)
    for k in ("global", "mixed", "local"):
        sel = kind == k
        if np.any(sel):
            ax.vlines(f[sel], 0.0, share[sel], color=COLORS[k], lw=1.2, gid=f"modes-{k}",
                      label=f"{k} ({int(sel.sum())})")
            ax.plot(f[sel], share[sel], "o", color=COLORS[k], ms=3)
    for level in (GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD):
        ax.axhline(level, color="0.5", lw=0.8, ls="--")
    ax.set_ylim(0.0, 1.05)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("platform share of kinetic energy [-]")
    ax.set_title(f"{len(f)} modes by platform share: global, mixed and local")
    if len(f):
        ax.legend(loc="upper right", fontsize=8)
    return fig


def plot_damped_modes(damped, ax=None):
    """Damping ratio against damped natural frequency of the roots found.

    Parameters
    ----------
    damped : DampedModes
        ``freq_hz`` (n,) [Hz] and ``damping_ratio`` (n,) [-]; NaN entries (no root) are
        left out.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Figure
        Scatter of red circles with gid ``damped-modes``, over a light grid (alpha 0.3).
    """
    require(damped, "damped", ("freq_hz", "damping_ratio"), "DampedModes")
    fig, ax = figure_axes(ax)
    f = np.asarray(damped.freq_hz, dtype=float)
    z = np.asarray(damped.damping_ratio, dtype=float)
    ok = np.isfinite(f) & np.isfinite(z)
    ax.plot(f[ok], 100.0 * z[ok], "o", color="tab:red", gid="damped-modes")
    ax.set_xlabel("damped frequency [Hz]")
    ax.set_ylabel("damping ratio [%]")
    ax.set_title(f"damped roots: {int(ok.sum())} of {f.size} modes")
    ax.grid(True, alpha=0.3)
    return fig


def plot_cable_modes(cable_modes, ax=None):
    """Clamped-clamped natural frequencies of one cable, one row per family.

    Parameters
    ----------
    cable_modes : CableModes
        ``freq_hz`` (n,) [Hz], ``family`` (n,), ``order`` (n,).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Figure
        Stems per family (gid ``cable-<family>``, spaces as dashes), labelled by order.
        The figure is 8 x 4 in; stems are 1.5 pt wide, their order labels 7 pt; the legend
        (8 pt) sits at the upper center.
    """
    require(cable_modes, "cable_modes", ("freq_hz", "family", "order"), "CableModes")
    fig, ax = figure_axes(ax, figsize=(8, 4))
    f = np.asarray(cable_modes.freq_hz, dtype=float)
    fam = np.asarray(cable_modes.family)
    names = list(dict.fromkeys(fam.tolist()))
    for row, name in enumerate(names):
        sel = fam == name
        ax.vlines(f[sel], row, row + 0.8, lw=1.5, color=f"C{row}",
                  gid=f"cable-{name.replace(' ', '-')}", label=name)
        for x, k in zip(f[sel], np.asarray(cable_modes.order)[sel]):
            ax.annotate(str(k), (x, row + 0.82), ha="center", fontsize=7)
    ax.set_yticks([])
    ax.set_ylim(0.0, max(len(names), 1) + 0.9)
    ax.set_xlabel("frequency [Hz]")
    ax.set_title("clamped-clamped cable modes (the poles of its dynamic stiffness)")
    if names:
        ax.legend(loc="upper center", fontsize=8, ncol=len(names), framealpha=0.9)
    return fig


# --------------------------------------------------------------------------- statics
def plot_tensions(equilibrium, ax=None, limits=None):
    """Tension of every cable at the platform end B and at the anchor A.

    Parameters
    ----------
    equilibrium : Equilibrium or LumpedEquilibrium
        ``tensions`` or ``end_tensions`` (n,) and ``anchor_tensions`` (n,) [N].
    ax : matplotlib Axes, optional
    limits : (float, float), optional
        Admissible [t_min, t_max] [N] (default: the robot's ``tension_limits`` when the
        equilibrium carries its robot). A limit is drawn as a dashed line when it lies
        below twice the largest tension; otherwise it is named in the title, so that the
        axis stays scaled to the tensions (from 0 to 1.25 times the largest value drawn;
        from 0 to 1 N when no value drawn is positive, e.g. all tensions zero).

    Returns
    -------
    matplotlib Figure
        Grouped bars (gids ``tension-B``, ``tension-A``), limits ``limit-t_min``,
        ``limit-t_max``. The bars are 0.4 wide, red at B left of the cable's tick and blue
        at A right of it; the limits are 0.8 pt lines; the title is 10 pt; the legend, at the
        upper right, has two columns of 8 pt text on a frame of alpha 0.9.
    """
    tB = getattr(equilibrium, "end_tensions", None)
    if tB is None:
        tB = getattr(equilibrium, "tensions", None)
    require(equilibrium, "equilibrium", ("anchor_tensions",), "Equilibrium")
    if tB is None:
        raise InvalidParameterError(
            f"equilibrium must be an Equilibrium, got {type(equilibrium).__name__}")
    tB = np.asarray(tB, dtype=float)
    tA = np.asarray(equilibrium.anchor_tensions, dtype=float)
    if not (np.all(np.isfinite(tB)) and np.all(np.isfinite(tA))):
        raise InvalidParameterError(
            f"equilibrium tensions must be finite [N], got {tB.tolist()} at B and "
            f"{tA.tolist()} at A")
    if limits is None and hasattr(equilibrium, "robot"):
        limits = equilibrium.robot.tension_limits
    if limits is not None:
        lim = real_array("limits", limits, "(t_min, t_max) [N]")
        if lim.shape != (2,) or np.isnan(lim).any():
            raise InvalidParameterError(f"limits must be (t_min, t_max) [N], got {limits!r}")
        limits = lim
    fig, ax = figure_axes(ax)
    k = np.arange(tB.size)
    ax.bar(k - 0.2, tB, 0.4, label="at B (platform)", gid="tension-B", color="tab:red")
    ax.bar(k + 0.2, tA, 0.4, label="at A (anchor)", gid="tension-A", color="tab:blue")
    top = float(max(tB.max(initial=0.0), tA.max(initial=0.0)))
    drawn, off = [top], []
    if limits is not None:
        for name, value in zip(("t_min", "t_max"), limits):
            if not np.isfinite(value):
                continue
            if value <= 2.0 * top:
                ax.axhline(value, color="0.3", ls="--", lw=0.8, gid=f"limit-{name}")
                drawn.append(float(value))
            else:
                off.append(f"{name} = {value:.4g} N")
    ax.set_ylim(0.0, 1.25 * max(drawn) if max(drawn) > 0 else 1.0)
    ax.set_xticks(k)
    ax.set_xlabel("cable")
    ax.set_ylabel("tension [N]")
    ax.set_title("static cable tensions (dashed: admissible limits)"
                 + (f"\noff scale: {', '.join(off)}" if off else ""), fontsize=10)
    ax.legend(loc="upper right", ncol=2, fontsize=8, framealpha=0.9)
    return fig


def plot_model_errors(recommendation, ax=None, rtol=None):
    """Predicted relative frequency error of every rung of the ladder, cheapest first.

    Parameters
    ----------
    recommendation : Recommendation
        ``errors`` (rung -> error [-], inf where a rung misses modes) and ``rung``.
    ax : matplotlib Axes, optional
    rtol : float, optional
        Admissible error [-], drawn as a dashed line.

    Returns
    -------
    matplotlib Figure
        Bars (gid ``rung-errors``) on a log scale; a rung that misses modes is drawn at the
        top with the label "misses modes"; the recommended rung is outlined. The bars are
        blue; one that misses modes is grey, ten times as high as the largest finite positive
        error (1 if there is none), with its 8 pt label just above it; the outline is black,
        2 pt; ``rtol`` is a red line.
    """
    require(recommendation, "recommendation", ("errors", "rung"), "Recommendation")
    rtol = None if rtol is None else positive_scalar("rtol", rtol)
    names = list(recommendation.errors)
    err = np.array([float(recommendation.errors[r]) for r in names])
    finite = np.isfinite(err) & (err > 0)
    top = 10 * err[finite].max() if np.any(finite) else 1.0
    shown = np.where(np.isfinite(err), np.maximum(err, 1e-16), top)
    fig, ax = figure_axes(ax)
    bars = ax.bar(names, shown, color=["0.7" if not np.isfinite(e) else "tab:blue" for e in err],
                  gid="rung-errors")
    for b, r, e in zip(bars, names, err):
        if r == recommendation.rung:
            b.set_edgecolor("k")
            b.set_linewidth(2.0)
        if not np.isfinite(e):
            ax.annotate("misses modes", (b.get_x() + b.get_width() / 2, top), ha="center",
                        va="bottom", fontsize=8)
    if rtol is not None:
        ax.axhline(rtol, color="tab:red", ls="--", lw=0.8, gid="limit-rtol")
    ax.set_yscale("log")
    ax.set_ylabel("predicted relative frequency error [-]")
    ax.set_title(f"cable models, cheapest first; recommended: {recommendation.rung}")
    return fig
