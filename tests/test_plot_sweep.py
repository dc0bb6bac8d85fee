"""The veering diagram (dynstiff/plot/sweep.py)."""

import warnings
from types import SimpleNamespace

import matplotlib
import numpy as np
import pandas as pd
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_veering  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def small_sweep(cogiro):
    return ds.sweep(cogiro.robot, poses=[[-1.5, 0.0, 1.0], [0.0, 0.0, 1.0], [1.5, 0.0, 1.0]],
                    n_modes=8)


def by_gid(ax, prefix):
    return [a for a in ax.get_children() if (a.get_gid() or "").startswith(prefix)]


# --------------------------------------------------------------------------- veering
def test_veering_one_line_per_track_and_local_dots(small_sweep):
    fig0, ax = plt.subplots()
    fig = plot_veering(small_sweep, ax=ax)
    assert fig is ax.figure
    assert ax.get_xlabel() == small_sweep.parameter == "arc length [m]"
    assert ax.get_ylabel() == "frequency [Hz]"
    tracks = by_gid(ax, "track-")
    assert small_sweep.n_tracks >= 1 and len(tracks) == small_sweep.n_tracks
    table = small_sweep.veering_table()
    for ln in tracks:
        t = int(ln.get_gid().split("-")[1])
        np.testing.assert_allclose(ln.get_xdata(), small_sweep.values)
        np.testing.assert_allclose(ln.get_ydata(), table[t].to_numpy())   # NaN where absent
    (dots,) = by_gid(ax, "local-modes")
    local = small_sweep.kind == "local"
    pts = dots.get_offsets()
    assert len(pts) == local.sum() > 0
    np.testing.assert_allclose(np.sort(pts[:, 1]), np.sort(small_sweep.freq_hz[local]))
    fig = plot_veering(small_sweep, show_local=False)
    assert by_gid(fig.axes[0], "local-modes") == []
    with pytest.raises(InvalidParameterError, match="sweep_result must be a SweepResult"):
        plot_veering(small_sweep.to_frame())


def test_veering_bridges_interior_gaps_only():
    """A track missing between two hits is bridged by a dotted line of its colour from the
    last hit to the next; a track that ends (or starts late) is not extended."""

    class Stub:
        parameter = "E [Pa]"
        values = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
        n_tracks = 2
        value = np.array([2.0, 3.0])
        freq_hz = np.array([3.0, 3.1])
        kind = np.array(["local", "local"])

        def veering_table(self):
            return pd.DataFrame({0: [2.0, np.nan, np.nan, 2.6, 2.8],
                                 1: [np.nan, 3.5, 3.6, np.nan, np.nan]})

    fig = plot_veering(Stub())
    ax = fig.axes[0]
    (gap,) = by_gid(ax, "gap-")
    assert gap.get_gid() == "gap-0"
    np.testing.assert_array_equal(gap.get_xdata()[:2], [1.0, 4.0])
    np.testing.assert_array_equal(gap.get_ydata()[:2], [2.0, 2.6])
    (track0,) = [ln for ln in by_gid(ax, "track-") if ln.get_gid() == "track-0"]
    assert gap.get_color() == track0.get_color()
    assert "dotted" in ax.get_title()




@pytest.mark.parametrize("values, scale", [([1e10, 3e10, 1e11], "log"),
                                           ([1e10, 2e10, 5e10], "linear"),
                                           ([-1.0, 0.0, 10.0], "linear")])
def test_a_decade_of_a_positive_parameter_is_drawn_on_a_log_axis(values, scale):
    class Stub:
        parameter = "EA [N]"
        n_tracks = 1
        value = np.array(values)
        freq_hz = np.array([3.0, 3.1, 3.2])
        kind = np.array(["local"] * 3)

        def veering_table(self):
            return pd.DataFrame({0: [2.0, 2.2, 2.5]})

    Stub.values = np.array(values)
    ax = plot_veering(Stub()).axes[0]
    assert ax.get_xscale() == scale
    lo, hi = ax.get_xlim()
    assert lo < min(values) and max(values) < hi
    (track,) = by_gid(ax, "track-")
    np.testing.assert_array_equal(track.get_xdata(), values)


def test_a_worded_show_local_flag_is_refused(small_sweep):
    with pytest.raises(InvalidParameterError, match="^show_local must be True or False"):
        plot_veering(small_sweep, show_local="no")


# --------------------------------------------------------------------------- style and stubs
def stub(values, table, kind, value, freq_hz, track=None, parameter="E [Pa]"):
    """A SweepResult-like object: ``table`` (n_steps, n_tracks) is the veering table; the
    rows ``kind``, ``value``, ``freq_hz`` (and ``track`` if given) list the modes."""
    table = np.asarray(table, dtype=float)
    s = SimpleNamespace(parameter=parameter, values=np.asarray(values, dtype=float),
                        n_tracks=table.shape[1], kind=np.asarray(kind),
                        value=np.asarray(value, dtype=float),
                        freq_hz=np.asarray(freq_hz, dtype=float),
                        veering_table=lambda: pd.DataFrame(table))
    if track is not None:
        s.track = np.asarray(track)
    return s


def n_track_stub(n):
    """n straight tracks over three values, no other mode."""
    table = [[10.0 + t + 0.1 * k for t in range(n)] for k in range(3)]
    return stub([1.0, 2.0, 3.0], table, [], [], [])


def test_tracks_are_thin_lines_with_small_circles_and_bridges_thinner_dotted():
    """Tracks: 1.4 pt lines, 3.5 pt circles; a gap bridge: a 1 pt dotted line (docstring)."""
    s = stub([1.0, 2.0, 3.0], [[2.0], [np.nan], [2.4]], ["local"], [2.0], [5.0])
    ax = plot_veering(s).axes[0]
    (track,) = by_gid(ax, "track-")
    assert track.get_linewidth() == 1.4 and track.get_markersize() == 3.5
    assert track.get_marker() == "o" and track.get_linestyle() == "-"
    (gap,) = by_gid(ax, "gap-")
    assert gap.get_linestyle() == ":" and gap.get_linewidth() == 1.0
    assert gap.get_marker() in ("None", "", None)


def test_gap_bridge_data_are_float_pairs_separated_by_nan():
    """Each interior gap gives (last hit, next hit, NaN) in x and y, as float arrays."""
    from dynstiff.plot.sweep import _gap_bridges
    x = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    y = np.array([2.0, np.nan, 2.2, np.nan, np.nan, 2.5])
    gx, gy = _gap_bridges(x, y)
    assert gx.dtype == np.float64 and gy.dtype == np.float64
    np.testing.assert_array_equal(gx, [1.0, 3.0, np.nan, 3.0, 6.0, np.nan])
    np.testing.assert_array_equal(gy, [2.0, 2.2, np.nan, 2.2, 2.5, np.nan])
    gx, gy = _gap_bridges(x, np.full(6, 1.0))
    assert gx.size == gy.size == 0


@pytest.mark.parametrize("n", [3, 10])
def test_up_to_ten_tracks_take_the_tab10_colours(n):
    """With 3 or 10 tracks (10 the most for tab10), track t has the t-th tab10 colour (not
    tab10 spread end to end)."""
    ax = plot_veering(n_track_stub(n)).axes[0]
    tab10 = matplotlib.colormaps["tab10"]
    got = {int(ln.get_gid().split("-")[1]): to_rgba(ln.get_color())
           for ln in by_gid(ax, "track-")}
    assert got == {t: to_rgba(tab10(t)) for t in range(n)}


def test_more_than_ten_tracks_spread_over_turbo_from_end_to_end():
    """With 11 tracks, track t has turbo(t / 10): the first and last colours of turbo at the
    ends, every track a different colour."""
    n = 11
    ax = plot_veering(n_track_stub(n)).axes[0]
    turbo = matplotlib.colormaps["turbo"]
    got = {int(ln.get_gid().split("-")[1]): to_rgba(ln.get_color())
           for ln in by_gid(ax, "track-")}
    assert got == {t: to_rgba(turbo(t / (n - 1))) for t in range(n)}
    assert got[0] == to_rgba(turbo(0.0)) and got[n - 1] == to_rgba(turbo(1.0))
    assert len(set(got.values())) == n


def test_other_modes_are_the_untracked_ones_grey_local_purple_mixed():
    """Dots mark the modes with track -1 only: a mixed mode on track 0 and a local one on
    track 1 (a track through a cable mode) are not dots; local dots grey 0.55, mixed dots
    tab:purple, 6 pt², at zorder 1 beneath the tracks; the legend names them."""
    s = stub([1.0, 2.0],
             [[3.0, 4.0], [3.1, 4.1]],
             kind=["mixed", "local", "local", "mixed", "mixed", "local", "global"],
             value=[1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
             freq_hz=[3.0, 4.0, 5.0, 6.0, 6.1, 5.1, 4.1],
             track=[0, 1, -1, -1, -1, -1, 1])
    ax = plot_veering(s).axes[0]
    (local,) = by_gid(ax, "local-modes")
    (mixed,) = by_gid(ax, "mixed-modes")
    np.testing.assert_array_equal(local.get_offsets(), [[1.0, 5.0], [2.0, 5.1]])
    np.testing.assert_array_equal(mixed.get_offsets(), [[1.0, 6.0], [2.0, 6.1]])
    assert [to_rgba(c) for c in local.get_facecolor()] == [to_rgba("0.55")]
    assert [to_rgba(c) for c in mixed.get_facecolor()] == [to_rgba("tab:purple")]
    tracks = by_gid(ax, "track-")
    for dots in (local, mixed):
        assert list(dots.get_sizes()) == [6.0]
        assert dots.get_zorder() == 1
        assert all(dots.get_zorder() < ln.get_zorder() for ln in tracks)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["track 0", "track 1", "local modes", "mixed modes"]
    assert ax.get_title() == ("Modes along the sweep: 2 platform-mode tracks, grey dots "
                              "local modes, purple dots mixed modes")


def test_without_a_track_attribute_every_local_mode_is_a_dot():
    """A result with no ``track`` has no tracked mode: all its local modes are dots."""
    s = stub([1.0, 2.0], [[3.0], [3.1]], kind=["local", "local", "local"],
             value=[1.0, 2.0, 2.0], freq_hz=[5.0, 5.1, 7.0])
    ax = plot_veering(s).axes[0]
    (local,) = by_gid(ax, "local-modes")
    np.testing.assert_array_equal(local.get_offsets(), [[1.0, 5.0], [2.0, 5.1], [2.0, 7.0]])
    assert by_gid(ax, "mixed-modes") == []


def test_title_counts_tracks_and_mentions_local_dots_and_bridges_only_when_drawn():
    """The title names the number of tracks; ", grey dots local modes" only with show_local;
    the note on dotted bridges only when a track has an interior gap."""
    s = stub([1.0, 2.0, 3.0], [[2.0, 3.0], [2.1, 3.1], [2.2, 3.2]], ["local"], [2.0], [5.0])
    title = plot_veering(s).axes[0].get_title()
    assert title == "Modes along the sweep: 2 platform-mode tracks, grey dots local modes"
    title = plot_veering(s, show_local=False).axes[0].get_title()
    assert title == "Modes along the sweep: 2 platform-mode tracks"
    g = stub([1.0, 2.0, 3.0], [[2.0], [np.nan], [2.2]], ["local"], [2.0], [5.0])
    title = plot_veering(g, show_local=False).axes[0].get_title()
    assert title.startswith("Modes along the sweep: 1 platform-mode tracks\ndotted: ")
    assert "grey dots" not in title


def test_legend_sits_right_of_the_axes_with_its_top_left_corner_at_the_anchor():
    """The legend's top left corner is at (1.01, 1.0) in axes coordinates (no padding), so it
    lies outside the axes on the right, level with their top."""
    # one falling track, no dot in the upper right of the axes: a legend placed "best"
    # would go there, inside the axes
    s = stub([1.0, 2.0, 3.0], [[3.0], [2.0], [1.0]], ["local"], [1.0], [1.5])
    fig = plot_veering(s)
    ax = fig.axes[0]
    fig.canvas.draw()
    box = ax.get_legend().get_window_extent().transformed(ax.transAxes.inverted())
    # the corner is placed exactly; 1e-6 allows for rounding in the transforms
    assert box.x0 == pytest.approx(1.01, abs=1e-6)
    assert box.y1 == pytest.approx(1.0, abs=1e-6)


def test_grid_is_drawn_light():
    """The grid is on, with alpha 0.3 (docstring)."""
    ax = plot_veering(n_track_stub(2)).axes[0]
    for axis in (ax.xaxis, ax.yaxis):
        lines = axis.get_gridlines()
        assert lines and all(ln.get_visible() and ln.get_alpha() == 0.3 for ln in lines)


@pytest.mark.parametrize("values", [[1e10, 3e10, 1e11], [1e10, 2e10, 5e10], [-1.0, 0.0, 10.0]])
def test_x_limits_leave_two_percent_of_the_span_either_side(values):
    """Linear axis: limits min - 2 % and max + 2 % of max - min; log axis: the same in log10."""
    s = stub(values, [[2.0], [2.2], [2.5]], ["local"], [values[0]], [3.0])
    ax = plot_veering(s).axes[0]
    lo, hi = ax.get_xlim()
    f = np.log10 if ax.get_xscale() == "log" else (lambda v: v)
    span = f(max(values)) - f(min(values))
    # limits are computed by one multiplication / division: equal to rounding
    assert f(min(values)) - f(lo) == pytest.approx(0.02 * span, rel=1e-9)
    assert f(hi) - f(max(values)) == pytest.approx(0.02 * span, rel=1e-9)


@pytest.mark.parametrize("v", [0.0, 5.0])
def test_a_single_step_keeps_automatic_limits_without_warning(v):
    """One step (a one-pose sweep starts at arc length 0): no singular-limit warning, the x
    axis left to autoscaling and holding the value."""
    s = stub([v], [[2.0]], ["local"], [v], [3.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ax = plot_veering(s).axes[0]
    assert ax.get_autoscalex_on() and ax.get_xscale() == "linear"
    lo, hi = ax.get_xlim()
    assert lo < v < hi


def test_local_dots_are_drawn_and_named_even_when_there_is_none():
    """With show_local the local-mode dots are drawn (an empty set here) and the title names
    them; mixed dots, of which there are none, are not."""
    ax = plot_veering(n_track_stub(2)).axes[0]
    (local,) = by_gid(ax, "local-modes")
    assert len(local.get_offsets()) == 0
    assert by_gid(ax, "mixed-modes") == []
    assert ax.get_title() == "Modes along the sweep: 2 platform-mode tracks, grey dots local modes"
