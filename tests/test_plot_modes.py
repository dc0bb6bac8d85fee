"""Figures of modes and statics (dynstiff/plot/modes.py): natural frequencies by class, damped
roots, cable modes by family, tensions and model errors."""

import re
import warnings
from types import SimpleNamespace

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import (  # noqa: E402
    plot_cable_modes,
    plot_damped_modes,
    plot_model_errors,
    plot_modes,
    plot_tensions,
)


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def by_gid(ax, prefix):
    return [a for a in ax.get_children() if (a.get_gid() or "").startswith(prefix)]


def test_cable_modes_and_damped_modes_plot(cogiro_eq):
    st = cogiro_eq.states[0]
    cm = ds.cable_natural_frequencies(st, 7)
    ax = cm.plot().axes[0]
    xs = np.concatenate([np.concatenate([s[:, 0] for s in c.get_segments()])
                         for c in by_gid(ax, "cable-")])
    np.testing.assert_allclose(np.unique(xs), np.unique(cm.freq_hz), rtol=1e-12)
    dm = ds.DampedModes(undamped_freq_hz=np.array([1.0, 2.0]),
                        omega=np.array([2 * np.pi * (1 + 0.01j), np.nan]),
                        residual=np.array([1e-12, np.nan]))
    pts = by_gid(dm.plot().axes[0], "damped-modes")[0]
    np.testing.assert_allclose(pts.get_xdata(), [1.0])
    np.testing.assert_allclose(pts.get_ydata(), [100 * 0.01 / np.hypot(1, 0.01)])
    with pytest.raises(InvalidParameterError, match="modes"):
        plot_modes(np.array([1.0]))


# ----------------------------------------------------------- results that draw themselves
def test_modal_result_plot_shows_each_mode_at_its_platform_share(cogiro_model):
    """One stem per mode, at its frequency, up to its platform share, in the colour of its
    kind (global, mixed, local: all three among CoGiRo's first 12 modes)."""
    md = ds.modes(cogiro_model, 12)
    ax = md.plot().axes[0]
    groups = {k: by_gid(ax, f"modes-{k}") for k in ("global", "mixed", "local")}
    assert all(len(g) == 1 for g in groups.values())
    segs = np.concatenate([g[0].get_segments() for g in groups.values()])
    assert len(segs) == len(md)
    got = sorted((s[0, 0], s[1, 1]) for s in segs)
    want = sorted(zip(md.freq_hz, md.platform_share))
    np.testing.assert_allclose(got, want, rtol=1e-12)
    for k, g in groups.items():
        xs = np.sort([s[0, 0] for s in g[0].get_segments()])
        np.testing.assert_allclose(xs, np.sort(md.freq_hz[np.array(md.kind) == k]))


def test_equilibrium_plot_bars_are_the_tensions_and_the_limits(cogiro_eq):
    ax = cogiro_eq.plot().axes[0]
    heights = [p.get_height() for p in by_gid(ax, "tension-B")]
    np.testing.assert_allclose(heights, cogiro_eq.tensions, rtol=1e-12)
    heights = [p.get_height() for p in by_gid(ax, "tension-A")]
    np.testing.assert_allclose(heights, cogiro_eq.anchor_tensions, rtol=1e-12)
    # CoGiRo: tensions 270-306 N, limits 100 and 5000 N: t_max is named, not drawn, and
    # the axis is scaled to the tensions
    limits = [line.get_ydata()[0] for line in by_gid(ax, "limit-")]
    assert limits == [100.0]
    assert "t_max = 5000 N" in ax.get_title()
    lo, hi = ax.get_ylim()
    top = max(cogiro_eq.tensions.max(), cogiro_eq.anchor_tensions.max())
    assert lo == 0 and top < hi < 1.3 * top
    # limits within reach are both drawn, and the axis holds them
    fig = ds.plot.plot_tensions(cogiro_eq, limits=(150.0, 400.0))
    ax = fig.axes[0]
    assert sorted(line.get_ydata()[0] for line in by_gid(ax, "limit-")) == [150.0, 400.0]
    assert ax.get_ylim()[1] > 400.0 and "off scale" not in ax.get_title()


def test_recommendation_plot_marks_rungs_that_miss_modes(cogiro_eq):
    rec = ds.recommend_model(cogiro_eq, band_hz=(0.0, 12.0), rtol=1e-3)
    ax = rec.plot(rtol=1e-3).axes[0]
    bars = by_gid(ax, "rung-errors")
    assert [b.get_height() for b in bars][2] == pytest.approx(rec.errors["dsm"], rel=1e-12)
    misses = [t.get_text() for t in ax.texts]
    assert misses.count("misses modes") == sum(not np.isfinite(e) for e in rec.errors.values())
    assert by_gid(ax, "limit-rtol")[0].get_ydata()[0] == 1e-3




@pytest.mark.parametrize("call, message", [
    (lambda eq, rec: plot_tensions(eq, limits=True), "^limits must be real numbers, not "
                                                     "booleans"),
    (lambda eq, rec: plot_tensions(eq, limits="ab"), r"^limits must be \(t_min, t_max\) \[N\]"),
    (lambda eq, rec: plot_tensions(eq, limits=(1.0, 2.0, 3.0)), r"^limits must be \(t_min, "),
    (lambda eq, rec: plot_model_errors(rec, rtol=True), "^rtol must be a real number, got True"),
    (lambda eq, rec: plot_model_errors(rec, rtol="a"), "^rtol must be a real number, got 'a'")])
def test_limits_and_tolerances_of_the_plots_are_numbers(call, message):
    """limits=True and text came out as TypeErrors; rtol=True drew a line at 1."""
    eq = ds.load_scene("planar2").equilibrium()
    rec = ds.recommend_model(eq, band_hz=(0.0, 2.0))
    with pytest.raises(InvalidParameterError, match=message):
        call(eq, rec)


# ------------------------------------------------------------------ synthetic inputs
def legend_loc(ax):
    """The location the legend was asked for (matplotlib has no public getter)."""
    from matplotlib.legend import Legend
    return {code: name for name, code in Legend.codes.items()}[ax.get_legend()._loc]


def modal(freq_hz, cable_energy_fraction, kind):
    return SimpleNamespace(freq_hz=freq_hz, cable_energy_fraction=cable_energy_fraction,
                           kind=kind)


def test_mode_stems_rise_from_zero_in_the_documented_colours():
    """Each stem runs from share 0 up to 1 - cable energy fraction, red / purple / blue for
    global / mixed / local, and the share axis runs from 0 to 1.05 with the y label naming
    the platform share of kinetic energy."""
    frac = np.array([0.1, 0.7, 0.99])
    ax = plot_modes(modal([1.0, 2.0, 3.0], frac, ["global", "mixed", "local"])).axes[0]
    want = {"global": "tab:red", "mixed": "tab:purple", "local": "tab:blue"}
    for i, (k, colour) in enumerate(want.items()):
        (stems,) = by_gid(ax, f"modes-{k}")
        (seg,) = stems.get_segments()
        np.testing.assert_array_equal(seg, [[i + 1.0, 0.0], [i + 1.0, 1.0 - frac[i]]])
        assert [to_rgba(c) for c in stems.get_colors()] == [to_rgba(colour)]
    assert ax.get_ylim() == (0.0, 1.05)
    assert ax.get_ylabel() == "platform share of kinetic energy [-]"


def test_mode_share_is_computed_in_double_precision():
    """Single-precision cable energy fractions give stems at 1 - fraction evaluated in
    double precision (a float32 subtraction would round the share to ~1e-8)."""
    frac = np.array([0.1, 0.3], dtype=np.float32)
    ax = plot_modes(modal([1.0, 2.0], frac, ["global", "global"])).axes[0]
    tops = [s[1, 1] for s in by_gid(ax, "modes-global")[0].get_segments()]
    np.testing.assert_array_equal(tops, 1.0 - frac.astype(float))


def test_mode_thresholds_are_thin_dashed_lines():
    """The two kind thresholds (0.5, 0.05) are dashed lines 0.8 pt wide."""
    ax = plot_modes(modal([1.0], [0.2], ["global"])).axes[0]
    lines = [ln for ln in ax.get_lines() if ln.get_linestyle() == "--"]
    assert sorted(ln.get_ydata()[0] for ln in lines) == [0.05, 0.5]
    assert [ln.get_linewidth() for ln in lines] == [0.8, 0.8]


def damped(freq_hz, damping_ratio):
    return SimpleNamespace(freq_hz=np.asarray(freq_hz), damping_ratio=np.asarray(damping_ratio))


def test_damped_roots_are_red_circles_over_a_light_grid():
    """The roots are drawn as red circles, not joined by a line, over a grid of alpha 0.3;
    drawing it raises no warning (matplotlib warns when told both grid off and grid style)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig = plot_damped_modes(damped([1.0, 2.0], [0.01, 0.02]))
    ax = fig.axes[0]
    (pts,) = by_gid(ax, "damped-modes")
    assert pts.get_marker() == "o" and pts.get_linestyle() == "None"
    assert to_rgba(pts.get_color()) == to_rgba("tab:red")
    fig.canvas.draw()
    grid = ax.xaxis.get_gridlines() + ax.yaxis.get_gridlines()
    assert grid and all(g.get_visible() and g.get_alpha() == 0.3 for g in grid)


@pytest.mark.parametrize("call, message", [
    (lambda: plot_damped_modes(np.array([1.0])), "^damped must be a DampedModes, got ndarray"),
    (lambda: plot_cable_modes(np.array([1.0])),
     "^cable_modes must be a CableModes, got ndarray"),
    (lambda: plot_model_errors(np.array([1.0])),
     "^recommendation must be a Recommendation, got ndarray"),
    (lambda: plot_tensions(SimpleNamespace(anchor_tensions=[1.0])),
     "^equilibrium must be an Equilibrium, got SimpleNamespace$")])
def test_wrong_objects_are_named_in_the_error(call, message):
    """An object of the wrong type is refused with a message naming the expected type."""
    with pytest.raises(InvalidParameterError, match=message):
        call()


def cable_modes():
    return SimpleNamespace(freq_hz=np.array([1.0, 2.0, 3.0]), order=np.array([1, 1, 2]),
                           family=("out-of-plane", "in-plane symmetric", "out-of-plane"))


def test_cable_mode_families_are_named_with_dashes_for_spaces():
    """A family name with spaces gives the gid with dashes; each family's stems take the
    next colour of the cycle and are 1.5 pt wide, labelled by order in 7 pt text."""
    ax = plot_cable_modes(cable_modes()).axes[0]
    assert [c.get_gid() for c in by_gid(ax, "cable-")] == ["cable-out-of-plane",
                                                           "cable-in-plane-symmetric"]
    for row, c in enumerate(by_gid(ax, "cable-")):
        assert [to_rgba(x) for x in c.get_colors()] == [to_rgba(f"C{row}")]
        assert list(c.get_linewidths()) == [1.5]
    assert sorted(t.get_text() for t in ax.texts) == ["1", "1", "2"]
    assert all(t.get_fontsize() == 7 for t in ax.texts)


def test_cable_modes_figure_title_and_legend():
    """The new figure is 8 x 4 in, titled as the clamped-clamped modes; the legend (8 pt)
    sits at the upper center, one column per family."""
    fig = plot_cable_modes(cable_modes())
    ax = fig.axes[0]
    assert tuple(fig.get_size_inches()) == (8.0, 4.0)
    assert ax.get_title() == "clamped-clamped cable modes (the poles of its dynamic stiffness)"
    leg = ax.get_legend()
    assert legend_loc(ax) == "upper center" and leg._ncols == 2
    assert [t.get_fontsize() for t in leg.get_texts()] == [8, 8]
    assert [t.get_text() for t in leg.get_texts()] == ["out-of-plane", "in-plane symmetric"]


def equilibrium(tB, tA):
    return SimpleNamespace(tensions=np.asarray(tB), anchor_tensions=np.asarray(tA))


def test_tension_bars_sit_side_by_side_in_their_colours():
    """For cable k the bar at B spans [k - 0.4, k] in red and the bar at A [k, k + 0.4] in
    blue, so the two never overlap; legend entries name both ends, at the upper right."""
    tB, tA = [300.0, 310.0, 320.0], [290.0, 305.0, 330.0]
    ax = plot_tensions(equilibrium(tB, tA)).axes[0]
    for gid, offset, colour, t in (("tension-B", -0.4, "tab:red", tB),
                                   ("tension-A", 0.0, "tab:blue", tA)):
        bars = by_gid(ax, gid)
        # edges are k -/+ 0.2 -/+ 0.4 / 2, rounded in floating point
        np.testing.assert_allclose([b.get_x() for b in bars], np.arange(3) + offset,
                                   atol=1e-15)
        np.testing.assert_allclose([b.get_width() for b in bars], 0.4, rtol=1e-15)
        assert [b.get_height() for b in bars] == t
        assert all(b.get_facecolor() == to_rgba(colour) for b in bars)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["at B (platform)",
                                                                  "at A (anchor)"]
    assert legend_loc(ax) == "upper right"
    assert ax.get_xlabel() == "cable" and ax.get_ylabel() == "tension [N]"
    assert ax.get_title() == "static cable tensions (dashed: admissible limits)"


def test_tension_limits_are_named_by_their_role():
    """A drawn t_min is a 0.8 pt line with gid limit-t_min; one off scale is named t_min in
    the title."""
    eq = equilibrium([300.0, 310.0], [290.0, 305.0])
    ax = plot_tensions(eq, limits=(100.0, 400.0)).axes[0]
    assert [ln.get_gid() for ln in by_gid(ax, "limit-")] == ["limit-t_min", "limit-t_max"]
    assert [ln.get_linewidth() for ln in by_gid(ax, "limit-")] == [0.8, 0.8]
    ax = plot_tensions(eq, limits=(1000.0, 5000.0)).axes[0]
    assert by_gid(ax, "limit-") == []
    assert ax.get_title() == ("static cable tensions (dashed: admissible limits)\n"
                              "off scale: t_min = 1000 N, t_max = 5000 N")


@pytest.mark.parametrize("tB, tA", [([300.0, np.nan], [290.0, 305.0]),
                                     ([300.0, 310.0], [np.inf, 305.0])])
def test_tensions_that_are_not_finite_are_refused(tB, tA):
    """A NaN or infinite tension would scale the axis to nothing: refused with both rows."""
    import matplotlib.pyplot as plt
    n = len(plt.get_fignums())
    with pytest.raises(InvalidParameterError,
                       match=rf"^equilibrium tensions must be finite \[N\], got "
                             rf"{re.escape(str(tB))} at B and {re.escape(str(tA))} at A$"):
        plot_tensions(equilibrium(tB, tA))
    assert len(plt.get_fignums()) == n                        # no figure left open


def recommendation(errors, rung):
    return SimpleNamespace(errors=errors, rung=rung)


def test_rung_that_misses_modes_is_grey_above_the_largest_error():
    """With finite errors below 1, a rung missing modes is a grey bar ten times the largest
    finite error, labelled "misses modes" (8 pt) just above its top; the others are blue,
    and the recommended rung is outlined in black."""
    errors = {"chord": 0.2, "dsm": 0.01, "lumped": np.inf, "exact": 0.0}
    fig = plot_model_errors(recommendation(errors, "dsm"), rtol=1e-2)
    ax = fig.axes[0]
    bars = by_gid(ax, "rung-errors")
    top = 10 * 0.2
    assert bars[2].get_height() == top
    assert [b.get_facecolor() for b in bars] == [to_rgba("tab:blue")] * 2 + [
        to_rgba("0.7"), to_rgba("tab:blue")]
    assert bars[1].get_edgecolor() == to_rgba("k") and bars[1].get_linewidth() == 2.0
    (label,) = ax.texts
    assert label.get_text() == "misses modes" and label.get_fontsize() == 8
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    bar_top = bars[2].get_window_extent(r).y1
    # the label's box starts at the bar's top (display pixels; 0.5 px for rounding)
    assert abs(label.get_window_extent(r).y0 - bar_top) < 0.5
    assert label.get_va() == "bottom"
    assert to_rgba(by_gid(ax, "limit-rtol")[0].get_color()) == to_rgba("tab:red")
    assert ax.get_ylabel() == "predicted relative frequency error [-]"


def test_rungs_without_finite_error_are_drawn_at_one():
    """When no rung has a finite positive error, the ones missing modes are drawn at 1."""
    ax = plot_model_errors(recommendation({"chord": np.inf, "dsm": np.inf}, "dsm")).axes[0]
    assert [b.get_height() for b in by_gid(ax, "rung-errors")] == [1.0, 1.0]


def test_tension_bars_keep_their_colours_on_axes_already_used():
    """On a caller's axes that already hold bars, the bars at A are still blue and those at
    B red (docstring), not the next colours of the axes' patch cycle."""
    fig, ax = plt.subplots()
    ax.bar([5.0], [1.0])                                 # takes the patch cycle's first colour
    plot_tensions(equilibrium([300.0, 310.0], [290.0, 305.0]), ax=ax)
    assert all(b.get_facecolor() == to_rgba("tab:blue") for b in by_gid(ax, "tension-A"))
    assert all(b.get_facecolor() == to_rgba("tab:red") for b in by_gid(ax, "tension-B"))


@pytest.mark.parametrize("limits, largest", [(None, 330.0), ((100.0, 400.0), 400.0),
                                             ((100.0, 5000.0), 330.0)])
def test_tension_axis_runs_from_zero_to_1_25_times_the_largest_value_drawn(limits, largest):
    """Largest bar 330 N; a t_max of 400 N is drawn (below 2 x 330), one of 5000 N is not."""
    eq = equilibrium([300.0, 310.0, 320.0], [290.0, 305.0, 330.0])
    ax = plot_tensions(eq, limits=limits).axes[0]
    assert ax.get_ylim() == (0.0, 1.25 * largest)


def test_zero_tensions_keep_a_unit_axis_without_warning():
    """All tensions 0 (slack cables) and no limit: nothing positive to scale to, so the axis
    runs from 0 to 1 N rather than collapsing (matplotlib would warn on identical limits)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ax = plot_tensions(equilibrium([0.0, 0.0], [0.0, 0.0])).axes[0]
    assert ax.get_ylim() == (0.0, 1.0)


def test_tension_title_and_legend_text_sizes():
    """The title is 10 pt and the legend has two columns of 8 pt text on a 0.9 alpha frame,
    whatever the default font size (here 14 pt)."""
    with matplotlib.rc_context({"font.size": 14.0}):
        ax = plot_tensions(equilibrium([300.0, 310.0], [290.0, 305.0])).axes[0]
    assert ax.title.get_fontsize() == 10
    leg = ax.get_legend()
    assert leg._ncols == 2
    assert [t.get_fontsize() for t in leg.get_texts()] == [8, 8]
    assert leg.get_frame().get_alpha() == 0.9
