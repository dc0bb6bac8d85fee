"""Plots of results (matplotlib is imported here and in :mod:`dynstiff.report.robot3d` only).

Each function takes ``ax=`` (an existing Axes) and returns the matplotlib Figure; none calls
``show()``. Artists that tests and users may want to find again carry a ``gid``:

==================  ===========================================================
gid                 artist
==================  ===========================================================
``mode-global``     vertical line at a global (platform) mode, :func:`plot_frf`
``mode-local``      vertical line at a local (cable) mode, :func:`plot_frf`
``track-<id>``      frequency line of global track ``id``, :func:`plot_veering`
``local-modes``     scatter of the local modes, :func:`plot_veering`
``mode-marker``     vertical line at a given frequency, :func:`plot_spectrum`
``spectrum-<ch>``   amplitude of channel ``ch``, :func:`plot_spectrum`
``model-<name>``    point and annotation of a model, :func:`plot_speed_accuracy`
``pareto``          Pareto front (step line), :func:`plot_speed_accuracy`
``modes-<kind>``    stems of the global / local modes, :func:`plot_modes`
``damped-modes``    scatter of the damped roots, :func:`plot_damped_modes`
``cable-<family>``  stems of one family of cable modes, :func:`plot_cable_modes`
``tension-<end>``   bars of the tensions at B / A, :func:`plot_tensions`
``limit-<name>``    horizontal line at a limit, :func:`plot_tensions`,
                    :func:`plot_model_errors`
``rung-errors``     bars of the predicted errors, :func:`plot_model_errors`
==================  ===========================================================
"""

import numpy as np

from dynstiff.constants import GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError

__all__ = ["plot_frf", "plot_veering", "plot_spectrum", "plot_speed_accuracy", "plot_modes",
           "plot_damped_modes", "plot_cable_modes", "plot_tensions", "plot_model_errors"]

_COLORS = {"global": "tab:red", "mixed": "tab:purple", "local": "tab:blue"}
_CATEGORY_LABELS = {
    "global": f"global mode (platform share >= {GLOBAL_SHARE:.0%})",
    "mixed": f"mixed mode (platform share {PLATFORM_SHARE_THRESHOLD:.0%}-{GLOBAL_SHARE:.0%})",
    "local": f"local mode (platform share < {PLATFORM_SHARE_THRESHOLD:.0%})"}


def mode_categories(modes):
    """"global" / "mixed" / "local" of each mode of a ModalResult, from its platform share
    1 - cable energy fraction (docs/theory.md §12.1); its ``kind`` when it has no energy
    fractions."""
    frac = getattr(modes, "cable_energy_fraction", None)
    if frac is None:
        return tuple(modes.kind)
    share = 1.0 - np.asarray(frac, dtype=float)
    return tuple("global" if s >= GLOBAL_SHARE else "mixed" if s >= PLATFORM_SHARE_THRESHOLD
                 else "local" for s in share)


def figure_axes(ax=None, figsize=(8, 4.5)):
    """(figure, axes): a new figure when ``ax`` is None, else ``ax`` and its figure."""
    if ax is None:
        import matplotlib.pyplot as plt
        return plt.subplots(figsize=figsize)
    return ax.figure, ax


def _require(obj, name, attrs, expected):
    """Raise InvalidParameterError naming ``name`` unless ``obj`` has every attribute."""
    missing = [a for a in attrs if not hasattr(obj, a)]
    if missing:
        raise InvalidParameterError(
            f"{name} must be a {expected}, got {type(obj).__name__} (no {missing[0]!r})")


def _mode_frequencies(modes, name="modes"):
    """(freq_hz, kind) of a ModalResult-like object, or of an array of frequencies [Hz]
    (kind None)."""
    if hasattr(modes, "freq_hz"):
        f = np.asarray(modes.freq_hz, dtype=float).reshape(-1)
        kind = tuple(getattr(modes, "kind", ())) or None
        if kind is not None and len(kind) != f.size:
            raise InvalidParameterError(
                f"{name}: kind has {len(kind)} entries for {f.size} frequencies")
        return f, kind
    try:
        f = np.asarray(modes, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be a ModalResult or frequencies [Hz], got "
            f"{type(modes).__name__}") from None
    if not np.all(np.isfinite(f)):
        raise InvalidParameterError(f"{name} must be finite frequencies [Hz], got {f.tolist()}")
    return f, None


# ------------------------------------------------------------------------------- FRF
def plot_frf(result, modes=None, pairs=None, ax=None, phase=False):
    """Magnitude (and phase) of FRFs against frequency, with the natural frequencies marked.

    Parameters
    ----------
    result : FRFResult
        ``H`` of shape (n_freq, n_out, n_in) at ``freq_hz``, shape (n_freq,) [Hz].
    modes : ModalResult, optional
        Marks each mode inside the band by a dashed vertical line coloured by its platform
        share (:func:`mode_categories`): red (gid ``mode-global``), purple (``mode-mixed``),
        blue (``mode-local``); the legend names the three.
    pairs : list of (output, input), optional
        Channels to draw, e.g. ``[("z", "fz")]`` (default: the pairs ``(outputs[k],
        inputs[k])`` present in ``result``).
    ax : matplotlib Axes, optional
        Axes for the magnitude. When given, only the magnitude is drawn (``phase`` ignored).
    phase : bool
        With ``ax`` None, add a second axes below for the phase [deg] (default False).

    Returns
    -------
    matplotlib Figure
        Its first axes holds the magnitude, on a log scale, in the units of ``result.kind``.

    Raises
    ------
    InvalidParameterError
        ``result`` not an FRF result, ``modes`` not a modal result, or a channel of
        ``pairs`` not in ``result``.
    """
    _require(result, "result", ("freq_hz", "H", "inputs", "outputs", "kind"), "FRFResult")
    if modes is not None:
        _require(modes, "modes", ("freq_hz", "kind"), "ModalResult")
    if pairs is None:
        pairs = list(zip(result.outputs, result.inputs))
    idx = []
    for pair in pairs:
        try:
            o, i = pair
            idx.append((o, i, result.outputs.index(o), result.inputs.index(i)))
        except (TypeError, ValueError):
            raise InvalidParameterError(
                f"pairs must hold (output, input) with outputs among {tuple(result.outputs)} "
                f"and inputs among {tuple(result.inputs)}, got {pair!r}") from None
    if ax is None and phase:
        import matplotlib.pyplot as plt
        fig, (ax, ax_ph) = plt.subplots(2, 1, sharex=True, figsize=(8, 6),
                                        height_ratios=(2, 1))
    else:
        fig, ax = figure_axes(ax)
        ax_ph = None
    f = np.asarray(result.freq_hz)
    unit = getattr(result, "unit", None)
    units = {(o, i): unit(o, i) for o, i, _, _ in idx} if callable(unit) else {}
    one_unit = len(set(units.values())) == 1
    for o, i, ko, ki in idx:
        h = result.H[:, ko, ki]
        tag = "" if one_unit or not units else f" [{units[(o, i)]}]"
        ax.semilogy(f, np.abs(h), lw=1.0, label=f"{o} / {i}{tag}")
        if ax_ph is not None:
            with np.errstate(invalid="ignore"):
                ax_ph.plot(f, np.degrees(np.angle(h)), lw=1.0)
    shown = []
    if modes is not None:
        cats = mode_categories(modes)
        for a in (ax, ax_ph):
            if a is None:
                continue
            for fm, cat in zip(modes.freq_hz, cats):
                if f[0] <= fm <= f[-1]:
                    a.axvline(fm, color=_COLORS[cat], lw=0.6, alpha=0.6, ls="--",
                              gid=f"mode-{cat}")
                    if cat not in shown:
                        shown.append(cat)
    ax.set_ylabel(f"|{result.kind}|" + (f" [{next(iter(units.values()))}]" if one_unit
                                         else " [units in the legend]" if units else ""))
    ax.set_title(f"FRF ({result.kind}), natural frequencies dashed")
    from matplotlib.lines import Line2D
    handles, labels = ax.get_legend_handles_labels()
    for cat in ("global", "mixed", "local"):
        if cat in shown:
            handles.append(Line2D([], [], color=_COLORS[cat], lw=0.8, ls="--"))
            labels.append(_CATEGORY_LABELS[cat])
    ax.legend(handles, labels, loc="upper right", fontsize=8)
    ax.set_xlim(f[0], f[-1])
    if ax_ph is None:
        ax.set_xlabel("frequency [Hz]")
    else:
        ax_ph.set_xlabel("frequency [Hz]")
        ax_ph.set_ylabel("phase [deg]")
        ax_ph.set_ylim(-190.0, 190.0)
        ax_ph.set_yticks([-180, -90, 0, 90, 180])
        ax_ph.grid(True, alpha=0.3)
        fig.tight_layout()
    return fig


# ----------------------------------------------------------------------------- modes
def plot_modes(modes, ax=None):
    """Natural frequencies against the cables' share of the kinetic energy.

    Parameters
    ----------
    modes : ModalResult
        ``freq_hz`` (n,) [Hz], ``cable_energy_fraction`` (n,) [-], ``kind`` (n,).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Figure
        One stem per mode, red (gid ``modes-global``) for global and blue (``modes-local``)
        for local modes; the dashed line at 0.5 is the global/local threshold.
    """
    _require(modes, "modes", ("freq_hz", "cable_energy_fraction", "kind"), "ModalResult")
    fig, ax = figure_axes(ax)
    f = np.asarray(modes.freq_hz, dtype=float)
    frac = np.asarray(modes.cable_energy_fraction, dtype=float)
    kind = np.asarray(modes.kind)
    for k in ("global", "local"):
        sel = kind == k
        if np.any(sel):
            ax.vlines(f[sel], 0.0, frac[sel], color=_COLORS[k], lw=1.2, gid=f"modes-{k}",
                      label=f"{k} ({int(sel.sum())})")
            ax.plot(f[sel], frac[sel], "o", color=_COLORS[k], ms=3)
    ax.axhline(0.5, color="0.5", lw=0.8, ls="--")
    ax.set_ylim(0.0, 1.05)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("cable share of kinetic energy [-]")
    ax.set_title(f"{len(f)} modes: global (platform holds most energy) and local")
    if len(f):
        ax.legend(loc="center right", fontsize=8)
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
        Scatter with gid ``damped-modes``.
    """
    _require(damped, "damped", ("freq_hz", "damping_ratio"), "DampedModes")
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
    """
    _require(cable_modes, "cable_modes", ("freq_hz", "family", "order"), "CableModes")
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
        Admissible [t_min, t_max] [N], drawn as dashed lines (default: the robot's
        ``tension_limits`` when the equilibrium carries its robot).

    Returns
    -------
    matplotlib Figure
        Grouped bars (gids ``tension-B``, ``tension-A``), limits ``limit-t_min``,
        ``limit-t_max``.
    """
    tB = getattr(equilibrium, "end_tensions", None)
    if tB is None:
        tB = getattr(equilibrium, "tensions", None)
    _require(equilibrium, "equilibrium", ("anchor_tensions",), "Equilibrium")
    if tB is None:
        raise InvalidParameterError(
            f"equilibrium must be an Equilibrium, got {type(equilibrium).__name__}")
    tB = np.asarray(tB, dtype=float)
    tA = np.asarray(equilibrium.anchor_tensions, dtype=float)
    if limits is None and hasattr(equilibrium, "robot"):
        limits = equilibrium.robot.tension_limits
    fig, ax = figure_axes(ax)
    k = np.arange(tB.size)
    ax.bar(k - 0.2, tB, 0.4, label="at B (platform)", gid="tension-B", color="tab:red")
    ax.bar(k + 0.2, tA, 0.4, label="at A (anchor)", gid="tension-A", color="tab:blue")
    if limits is not None:
        for name, value in zip(("t_min", "t_max"), limits):
            if np.isfinite(value):
                ax.axhline(value, color="0.3", ls="--", lw=0.8, gid=f"limit-{name}")
    ax.set_xticks(k)
    ax.set_xlabel("cable")
    ax.set_ylabel("tension [N]")
    ax.set_title("static cable tensions (dashed: admissible limits)")
    ax.legend(loc="best", fontsize=8, framealpha=0.9)
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
        top with the label "misses modes"; the recommended rung is outlined.
    """
    _require(recommendation, "recommendation", ("errors", "rung"), "Recommendation")
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

    Each global track (a platform mode followed by MAC, :meth:`SweepResult.veering_table`)
    is one coloured line with markers (gid ``track-<id>``, broken where the track has no
    global mode); where the track is found again after such a gap (its mode shared its
    energy with cable modes and was labelled local in between), a dotted line of its colour
    bridges the gap (gid ``gap-<id>``); the local (cable) modes are small grey dots (gid
    ``local-modes``).

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
        x label ``sweep_result.parameter``, y label ``"frequency [Hz]"``.

    Raises
    ------
    InvalidParameterError
        ``sweep_result`` not a sweep result.
    """
    _require(sweep_result, "sweep_result",
             ("parameter", "values", "veering_table", "value", "freq_hz", "kind", "n_tracks"),
             "SweepResult")
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
    if show_local:
        loc = np.asarray(sweep_result.kind) == "local"
        ax.scatter(np.asarray(sweep_result.value)[loc], np.asarray(sweep_result.freq_hz)[loc],
                   s=6, color="0.55", zorder=1, gid="local-modes", label="local modes")
    ax.set_xlabel(sweep_result.parameter)
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(f"Modes along the sweep: {n} global tracks"
                 + (", grey dots local modes" if show_local else "")
                 + ("\ndotted: a track through cable modes (its mode labelled local there)"
                    if any_gap else ""))
    if n <= 12:
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, borderaxespad=0)
    ax.grid(True, alpha=0.3)
    if x.size > 1:
        pad = 0.02 * (x.max() - x.min())
        ax.set_xlim(x.min() - pad, x.max() + pad)
    return fig


# -------------------------------------------------------------------------- spectrum
def _spectra(spectrum, channels):
    """List of Spectrum from a Spectrum, a sequence of them, or a TimeResponse."""
    if hasattr(spectrum, "spectrum") and hasattr(spectrum, "times"):       # TimeResponse
        names = tuple(spectrum.free_dofs) if channels is None else tuple(channels)
        return [spectrum.spectrum(c) for c in names]
    items = [spectrum] if hasattr(spectrum, "amplitude") else list(spectrum)
    for s in items:
        _require(s, "spectrum", ("freq_hz", "amplitude", "channel", "peaks_hz"),
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
        From :meth:`TimeResponse.spectrum`: ``amplitude`` [m or rad] at ``freq_hz`` [Hz],
        both shape (n_f,). A TimeResponse is analysed with the default window, one spectrum
        per channel.
    ax : matplotlib Axes, optional
    channels : sequence of str, optional
        Channels to draw, among ``("x", "y", "z", "rx", "ry", "rz")`` (default: every given
        spectrum; for a TimeResponse its free DOFs).
    modes : ModalResult or array_like of float, optional
        Frequencies [Hz] to mark by dashed vertical lines (gid ``mode-marker``), e.g. the
        natural frequencies of the frequency-domain model; a ModalResult colours them red
        (global) or blue (local). Only those inside the drawn band are marked.
    band_hz : (float, float), optional
        Frequency range drawn [Hz] (default: 0 to the highest frequency of the spectra).

    Returns
    -------
    matplotlib Figure
        One line per channel (gid ``spectrum-<channel>``), identified peaks as triangles.

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
    mode_f, mode_kind = (None, None) if modes is None else _mode_frequencies(modes)
    fig, ax = figure_axes(ax)
    for s in items:
        unit = "rad" if s.channel.startswith("r") else "m"
        f, a = np.asarray(s.freq_hz), np.asarray(s.amplitude)
        sel = (f > 0) & (f >= band[0]) & (f <= band[1])   # the mean (0 Hz) is removed
        (line,) = ax.semilogy(f[sel], a[sel], lw=1.0, gid=f"spectrum-{s.channel}",
                              label=f"{s.channel} [{unit}]")
        pk = (s.peaks_hz >= band[0]) & (s.peaks_hz <= band[1])
        ax.plot(s.peaks_hz[pk], s.peak_amplitudes[pk], "v", ms=5, color=line.get_color(),
                gid=f"peaks-{s.channel}")
    if mode_f is not None:
        for k, fm in enumerate(mode_f):
            if band[0] <= fm <= band[1]:
                color = "0.3" if mode_kind is None else _COLORS.get(mode_kind[k], "0.3")
                ax.axvline(fm, color=color, lw=0.7, ls="--", alpha=0.7, gid="mode-marker")
    ax.set_xlim(*band)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude [m or rad]")
    res = min(s.resolution_hz for s in items)
    title = f"Amplitude spectrum ({items[0].window} window, resolution {res:.3g} Hz)"
    if mode_f is not None:
        title += "; dashed: model frequencies"
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, which="both", alpha=0.25)
    return fig


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
    so that labels of neighbouring points do not overlap."""
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
    is drawn as an open triangle above the finite points and annotated "(misses modes)".
    A zero error is drawn at a tenth of the smallest positive one.

    Parameters
    ----------
    df : pandas.DataFrame
        One row per case and model, as returned by ``validation/speed_accuracy.py``'s
        ``run()``: columns ``"model"``, ``error``, ``cost`` and ``"build [s]"``.
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
        A column is missing, there are no rows, or a cost is not finite and > 0.
    """
    _require(df, "df", ("groupby", "columns"), "pandas DataFrame")
    for col in ("model", error, cost, "build [s]"):
        if col not in df.columns:
            raise InvalidParameterError(
                f"df has no column {col!r} (columns: {list(df.columns)})")
    if len(df) == 0:
        raise InvalidParameterError("df has no rows")
    g = df.groupby("model", sort=False).agg({error: "max", cost: "median",
                                              "build [s]": "median"})
    names = [str(n) for n in g.index]
    err = g[error].to_numpy(dtype=float)
    total = (g[cost] + g["build [s]"]).to_numpy(dtype=float)
    if not np.all(np.isfinite(total) & (total > 0)):
        bad = names[int(np.flatnonzero(~(np.isfinite(total) & (total > 0)))[0])]
        raise InvalidParameterError(
            f"df: {cost!r} + 'build [s]' must be finite and > 0 [s]; model {bad!r} has "
            f"{total[names.index(bad)]!r}")
    if np.any(np.isnan(err) | (err < 0)):
        raise InvalidParameterError(f"df: {error!r} must be >= 0 or inf, got {err.tolist()}")
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


def plot_tracking(tracking, ax=None):
    """A commanded path (:class:`dynstiff.timedomain.trajectory.TrackingResult`): the deviation of P
    from the desired path against time [mm], with the simulated and desired x y z [m] on a
    second axis. Returns the Figure."""
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
