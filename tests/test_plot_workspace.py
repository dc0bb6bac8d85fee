"""Figures of a workspace map (dynstiff/plot/workspace.py): the worst case over orientations
and parameter values, and the figures' content (cells, colour limits, counts in titles)."""

import warnings

import numpy as np
import pytest

xr = pytest.importorskip("xarray")
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from dynstiff.errors import InvalidParameterError
from dynstiff.plot.workspace import plot_workspace_3d, plot_workspace_slices, worst_case


def synthetic_map():
    """A 3 x 2 x 2 grid x 2 parameter values with known values: f1 = 1 + x + z + p."""
    x, y, z, p = np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0]), np.array([1.0, 2.0]), \
        np.array([0.0, 0.5])
    X, Y, Z, P = np.meshgrid(x, y, z, p, indexing="ij")
    f1 = 1.0 + X + Z + P
    feas = ~((X == 2.0) & (Y == 1.0))
    f1 = np.where(feas, f1, np.nan)
    dyn = feas & (f1 > 3.2)
    dims = ("x", "y", "z", "parameter")
    return xr.Dataset({"first_platform_hz": (dims, f1), "band_margin": (dims, f1 / 1.5 - 1),
                       "dynamic": (dims, dyn), "feasible": (dims, feas)},
                      coords={"x": x, "y": y, "z": z, "parameter": p},
                      attrs={"robot": "test", "margin": 0.05, "band_hz": [0.0, 1.5]})


def test_worst_case_is_the_least_frequency_and_the_all_pass_verdict():
    f1, _mg, dyn, feas = worst_case(synthetic_map())
    assert f1.dims == ("x", "y", "z")
    np.testing.assert_allclose(f1.sel(x=1.0, y=0.0, z=2.0), 1 + 1 + 2 + 0.0)
    assert np.isnan(f1.sel(x=2.0, y=1.0, z=1.0))
    # (0, 0, 2): f1 = 3 at p = 0 and 3.5 at p = 0.5 -> not dynamic everywhere
    assert not dyn.sel(x=0.0, y=0.0, z=2.0) and dyn.sel(x=1.0, y=0.0, z=2.0)
    assert int(feas.sum()) == 10


def test_slices_and_3d_view_draw_the_map():
    ds = synthetic_map()
    fig = plot_workspace_slices(ds, n_slices=4)
    axes = [a for a in fig.axes if a.get_label() != "<colorbar>"]
    assert len(axes) == 3 * 2 and len(fig.axes) == 3 * 2 + 3    # 3 rows x 2 heights, 3 bars
    assert "4 of 12 positions" in fig._suptitle.get_text()
    mesh = fig.axes[0].collections[0]
    assert mesh.get_clim() == pytest.approx((2.0, 5.0))   # least f1 over p: 1+x+z
    plt.close(fig)
    fig = plot_workspace_3d(ds)
    assert "4 of 12 positions" in fig.axes[0].get_title()
    plt.close(fig)


def test_a_list_of_poses_has_no_slices():
    ds = synthetic_map().stack(pose=("x", "y", "z")).reset_index("pose")
    with pytest.raises(InvalidParameterError, match="grid"):
        plot_workspace_slices(ds)


def five_level_map():
    x, y, z = np.array([0.0, 1.0]), np.array([0.0, 1.0]), np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    X, Y, Z = np.meshgrid(x, y, z, indexing="ij")
    f1 = 1.0 + X + Z
    dims = ("x", "y", "z")
    return xr.Dataset({"first_platform_hz": (dims, f1), "band_margin": (dims, f1 / 3 - 1),
                       "dynamic": (dims, f1 > 3), "feasible": (dims, np.ones_like(f1, bool))},
                      coords={"x": x, "y": y, "z": z},
                      attrs={"robot": "a robot with a rather long name for its title",
                             "margin": 0.05, "band_hz": [0.0, 1.5]})


def test_every_height_gets_its_panels_and_the_title_fits():
    ds = five_level_map()
    fig = ds.dynstiff.plot()
    heights = [a.get_title() for a in fig.axes if a.get_title().startswith("z = ")]
    assert heights == [f"z = {v:.3g} m" for v in ds["z"].values]     # z = 3 m included
    fig.canvas.draw()
    box = fig.get_window_extent()
    title = fig._suptitle.get_window_extent()
    assert box.x0 <= title.x0 and title.x1 <= box.x1 and title.y1 <= box.y1
    plt.close(fig)
    fig = plot_workspace_slices(ds, n_slices=3)                   # fewer asked: said so
    heights = [a.get_title() for a in fig.axes if a.get_title().startswith("z = ")]
    assert heights == ["z = 1 m", "z = 3 m", "z = 5 m"]
    assert "; 3 of 5 heights drawn (z = 1, 3, 5 m) forbidden band" in \
        fig._suptitle.get_text().replace("\n", " ")
    plt.close(fig)
    with pytest.raises(InvalidParameterError, match="n_slices"):
        plot_workspace_slices(ds, n_slices=0)


def test_a_figure_or_axes_that_is_not_one_is_refused():
    """fig=5 and ax=5 came out as AttributeErrors; a 2-D Axes for the 3-D view too."""
    ds = synthetic_map()
    with pytest.raises(InvalidParameterError, match="^fig must be a matplotlib Figure, got int"):
        plot_workspace_slices(ds, fig=5)
    flat = plt.subplots()[1]
    for ax in (5, flat):
        with pytest.raises(InvalidParameterError, match=r"^ax must be a matplotlib 3-D Axes"):
            plot_workspace_3d(ds, ax=ax)
    plt.close("all")


# --- what the figures mean: cells, colour scales, colour bars, titles, layout --------------

from matplotlib.collections import QuadMesh  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402
from matplotlib.contour import ContourSet  # noqa: E402


@pytest.fixture
def close_figures():
    yield
    plt.close("all")


def grid_map(x, y, z, f1, feasible=None, **attrs):
    """A map on the grid x, y, z with first platform frequency f1 (array over x, y, z), band
    margin f1 / 1.5 - 1 (band 0-1.5 Hz), dynamic where the margin reaches attrs' margin."""
    f1 = np.asarray(f1, float)
    feasible = np.ones(f1.shape, bool) if feasible is None else np.asarray(feasible, bool)
    f1 = np.where(feasible, f1, np.nan)
    mg = f1 / 1.5 - 1.0
    dims = ("x", "y", "z")
    attrs = {"robot": "grid", "margin": 0.05, "band_hz": [0.0, 1.5], **attrs}
    return xr.Dataset({"first_platform_hz": (dims, f1), "band_margin": (dims, mg),
                       "dynamic": (dims, feasible & (mg >= attrs["margin"])),
                       "feasible": (dims, feasible)},
                      coords={"x": np.asarray(x, float), "y": np.asarray(y, float),
                              "z": np.asarray(z, float)}, attrs=attrs)


def panels(fig):
    """The panels of a slices figure, 3 rows (frequency, margin, state) x one column per
    height (fig.subplots makes them row by row)."""
    return np.array([a for a in fig.axes if a.get_label() != "<colorbar>"]).reshape(3, -1)


def colour_bars(fig):
    """The colour bars of a figure, in the order drawn."""
    return [a for a in fig.axes if a.get_label() == "<colorbar>"]


def bar_colours(bar):
    """The mesh of colours drawn in a colour bar (its cmap and norm map values to colours)."""
    (m,) = [c for c in bar.collections if isinstance(c, QuadMesh)]
    return m


def mesh(ax):
    """The (single) pcolormesh of a panel."""
    (m,) = [c for c in ax.collections if not isinstance(c, ContourSet)]
    return m


def cell_edges(centres):
    """Edges of cells centred on evenly spaced centres (spacing 1 for a single centre)."""
    h = np.diff(centres)[0] if centres.size > 1 else 1.0
    return np.append(centres - h / 2, centres[-1] + h / 2)


def test_worst_case_keeps_a_nan_at_any_parameter_value():
    """A NaN (modes not all found) at one parameter value makes the worst case NaN, even
    where the other value is finite; the band margin alike."""
    ds = synthetic_map()
    ds["first_platform_hz"][0, 0, 0, 1] = np.nan
    ds["band_margin"][0, 0, 0, 1] = np.nan
    f1, mg, _dyn, _feas = worst_case(ds)
    assert np.isfinite(ds["first_platform_hz"][0, 0, 0, 0])
    assert np.isnan(f1[0, 0, 0]) and np.isnan(mg[0, 0, 0])
    # elsewhere the least value over the parameter values
    np.testing.assert_array_equal(f1.values[1:], ds["first_platform_hz"].values[1:].min(-1))


def test_every_position_is_a_cell_centred_on_it(close_figures):
    """The cells of every panel have their edges halfway between grid positions, and the end
    cells as wide as the inner ones, so each cell is centred on its (x, y)."""
    ds = synthetic_map()
    fig = plot_workspace_slices(ds)
    for ax in panels(fig).ravel():
        xy = mesh(ax).get_coordinates()
        np.testing.assert_allclose(xy[0, :, 0], cell_edges(ds["x"].values))
        np.testing.assert_allclose(xy[:, 0, 1], cell_edges(ds["y"].values))


def test_a_single_x_gets_a_unit_wide_cell_and_no_contour(close_figures):
    """A map one position wide in x: its cells are 1 m wide about that x, and no margin
    contour is attempted (a contour needs a 2 x 2 grid) though four margins are finite."""
    x, y, z = np.array([0.5]), np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.0])
    ds = grid_map(x, y, z, 1.0 + np.arange(4.0).reshape(1, 4, 1))
    fig = plot_workspace_slices(ds)
    top, middle, _bottom = panels(fig)[:, 0]
    np.testing.assert_allclose(mesh(top).get_coordinates()[0, :, 0], [0.0, 1.0])
    np.testing.assert_allclose(mesh(top).get_coordinates()[:, 0, 1], cell_edges(y))
    assert not [c for c in middle.collections if isinstance(c, ContourSet)]


def test_frequency_panels_share_one_colour_scale(close_figures):
    """Every frequency panel maps colours from the least to the greatest worst-case frequency
    of the whole map, not of its own height, so colours compare across heights."""
    ds = synthetic_map()
    f1 = ds["first_platform_hz"].min("parameter").values
    fig = plot_workspace_slices(ds)
    lims = [mesh(a).get_clim() for a in panels(fig)[0]]
    assert len(lims) == ds["z"].size
    assert lims == [(np.nanmin(f1), np.nanmax(f1))] * ds["z"].size
    # the upper height alone starts higher than the map's least frequency
    assert np.nanmin(f1[:, :, 1]) > np.nanmin(f1)


def test_margin_panels_are_red_below_zero_blue_above_on_a_symmetric_scale(close_figures):
    """The margin colour scale runs from -m to +m (m the largest absolute margin of the map)
    with 0 in the middle; cells with a negative margin are red, positive ones blue."""
    ds = five_level_map()
    mg = ds["band_margin"].values
    assert (mg < 0).any() and (mg > 0).any()
    lim = np.abs(mg).max()
    fig = plot_workspace_slices(ds)
    for ax in panels(fig)[1]:
        m = mesh(ax)
        assert m.get_clim() == pytest.approx((-lim, lim), rel=1e-12)
        assert m.norm(0.0) == pytest.approx(0.5)
        assert m.get_cmap().name == "RdBu"
        v = np.ravel(m.get_array())
        rgba = m.to_rgba(v)
        assert np.all(rgba[v < 0, 0] > rgba[v < 0, 2])
        assert np.all(rgba[v > 0, 2] > rgba[v > 0, 0])


def test_without_finite_margins_the_margin_scale_runs_from_minus_one_to_one(close_figures):
    """A map without a single finite margin (no band) gets the margin scale -1 to 1, and no
    contour; the title says there is no band. Without a finite frequency either (nothing
    feasible) the frequency scale runs from 0 to 1 Hz, without a warning."""
    ds = grid_map([0.0, 1.0], [0.0, 1.0], [1.0], np.full((2, 2, 1), 2.0))
    ds["band_margin"][:] = np.nan
    del ds.attrs["band_hz"]
    fig = plot_workspace_slices(ds)
    middle = panels(fig)[1, 0]
    assert mesh(middle).get_clim() == (-1.0, 1.0)
    assert not [c for c in middle.collections if isinstance(c, ContourSet)]
    assert fig.get_suptitle().replace("\n", " ").endswith(
        "dynamic workspace no band; grey: infeasible, or platform modes not all found")
    ds["first_platform_hz"][:] = np.nan
    ds["feasible"][:] = ds["dynamic"][:] = False
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig = plot_workspace_slices(ds)
    assert mesh(panels(fig)[0, 0]).get_clim() == (0.0, 1.0)


def test_margin_contours_mark_zero_and_the_required_margin(close_figures):
    """Each margin panel has black 0.8 pt contours at 0 and at the map's required margin."""
    ds = five_level_map()
    fig = plot_workspace_slices(ds)
    for ax in panels(fig)[1]:
        (cs,) = [c for c in ax.collections if isinstance(c, ContourSet)]
        np.testing.assert_array_equal(cs.levels, [0.0, ds.attrs["margin"]])
        np.testing.assert_array_equal(cs.get_linewidths(), [0.8, 0.8])
        assert [to_rgba(c) for c in cs.get_edgecolor()] == [to_rgba("k")] * 2


def test_no_contour_with_three_finite_margins_on_a_2x2_height(close_figures):
    """A 2 x 2 height with one infeasible position (3 finite margins) gets no contour; the
    same height with all four finite does."""
    f1 = np.array([[1.0, 2.0], [1.4, 1.8]])[:, :, None]
    feasible = np.array([[True, True], [True, False]])[:, :, None]
    for feas, n_contours in ((feasible, 0), (None, 1)):
        fig = plot_workspace_slices(grid_map([0.0, 1.0], [0.0, 1.0], [1.0], f1, feas))
        middle = panels(fig)[1, 0]
        assert len([c for c in middle.collections if isinstance(c, ContourSet)]) == n_contours
        plt.close(fig)


def state_colours(ds):
    """Expected colour of each position (x, y, z): grey 0.75 infeasible (at some parameter
    value), green when every check passes at every value, orange otherwise."""
    feas = ds["feasible"].all("parameter").values
    dyn = ds["dynamic"].all("parameter").values
    out = np.empty(feas.shape + (4,))
    out[:] = to_rgba("tab:orange")
    out[dyn] = to_rgba("tab:green")
    out[~feas] = to_rgba("0.75")
    return out


def test_dynamic_workspace_panels_colour_each_position_by_its_verdict(close_figures):
    """Bottom panels: green where every check passes, orange where one fails, grey where
    infeasible; the map has all three."""
    ds = synthetic_map()
    expected = state_colours(ds)
    fig = plot_workspace_slices(ds)
    fig.canvas.draw()
    for k, ax in enumerate(panels(fig)[2]):
        got = mesh(ax).get_facecolor()                       # cells row by row: y, then x
        want = expected[:, :, k].transpose(1, 0, 2).reshape(-1, 4)
        np.testing.assert_array_equal(got, want)
    assert {tuple(c) for c in expected.reshape(-1, 4)} == {
        to_rgba("0.75"), to_rgba("tab:orange"), to_rgba("tab:green")}


def test_state_colour_bar_names_the_three_colours(close_figures):
    """The dynamic workspace's colour bar has ticks 0, 1, 2 labelled infeasible / check
    fails / all pass, each in the colour the panels give that verdict."""
    fig = plot_workspace_slices(synthetic_map())
    fig.canvas.draw()
    bar = colour_bars(fig)[2]
    np.testing.assert_array_equal(bar.get_yticks(), [0, 1, 2])
    assert [t.get_text() for t in bar.get_yticklabels()] == [
        "infeasible", "check fails", "all pass"]
    solids = bar_colours(bar)
    np.testing.assert_array_equal(solids.to_rgba(np.array([0.0, 1.0, 2.0])), [
        to_rgba("0.75"), to_rgba("tab:orange"), to_rgba("tab:green")])


@pytest.mark.parametrize("n_slices", [None, 3])
def test_each_colour_bar_stands_beside_its_row(close_figures, n_slices):
    """The three colour bars (frequency, margin, verdict) stand in one column right of every
    panel, each centred on its row and 0.9 of the row's height; the panels of a column line
    up. Positions in figure fractions: 1e-9 allows for rounding in the layout arithmetic."""
    ds = synthetic_map() if n_slices is None else five_level_map()
    fig = plot_workspace_slices(ds, n_slices=n_slices)
    fig.canvas.draw()
    axs = panels(fig)
    bars = colour_bars(fig)
    assert [b.get_ylabel() for b in bars] == [
        "first platform frequency [Hz]", "band margin [-]", ""]
    for row, bar in zip(axs, bars, strict=True):                 # each bar its row's colours
        v = np.ravel(mesh(row[0]).get_array())
        np.testing.assert_array_equal(bar_colours(bar).to_rgba(v), mesh(row[0]).to_rgba(v))
    for col in axs.T:
        x0 = [a.get_position().x0 for a in col]
        assert x0 == pytest.approx([x0[0]] * 3, abs=1e-9)
    right = max(a.get_position().x1 for a in axs.ravel())
    assert bars[0].get_position().x0 > right
    for row, bar in zip(axs, bars, strict=True):
        box = row[0].get_position(original=True)            # the row's layout box
        pos = bar.get_position()
        assert bar.get_position().x0 == pytest.approx(bars[0].get_position().x0, abs=1e-9)
        assert (pos.y0 + pos.y1) / 2 == pytest.approx((box.y0 + box.y1) / 2, abs=1e-9)
        assert pos.height == pytest.approx(0.9 * box.height, abs=1e-9)


@pytest.mark.parametrize(("make", "n_slices", "n_drawn"),
                         [(synthetic_map, None, 2), (five_level_map, 3, 3)])
def test_slices_figure_size(close_figures, make, n_slices, n_drawn):
    """The figure is 9 in tall and max(3.4 n + 1.2, 8) in wide for n heights drawn."""
    fig = plot_workspace_slices(make(), n_slices=n_slices)
    assert panels(fig).shape == (3, n_drawn)
    np.testing.assert_allclose(fig.get_size_inches(), [max(3.4 * n_drawn + 1.2, 8.0), 9.0])


def test_slices_are_laid_out_without_overlaps_or_blank_margins(close_figures):
    """No panel or colour bar overlaps another, the figure title lies above every panel's
    title, and the panels and bars fill the figure: less than 3 % of its width is left blank
    on either side and of its height below (constrained layout; a fixed subplot layout of
    the same figure leaves 7 % left, 13 % right and 6 % below)."""
    fig = plot_workspace_slices(five_level_map(), n_slices=3)
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    boxes = [a.get_tightbbox(r) for a in fig.axes]
    for i, b in enumerate(boxes):
        for c in boxes[i + 1:]:
            assert not b.overlaps(c)
    top = fig._suptitle.get_window_extent(r)
    assert all(top.y0 >= a.title.get_window_extent(r).y1 for a in panels(fig)[0])
    w, h = fig.bbox.width, fig.bbox.height
    assert min(b.x0 for b in boxes) < 0.03 * w
    assert max(b.x1 for b in boxes) > 0.97 * w
    assert min(b.y0 for b in boxes) < 0.03 * h


def test_all_panels_share_their_x_and_y_axes(close_figures):
    """Zooming one panel zooms every panel alike, in x and in y; the bottom panels are
    labelled x [m], the left panels y [m]."""
    axs = panels(plot_workspace_slices(five_level_map(), n_slices=3))
    assert [a.get_xlabel() for a in axs[2]] + [a.get_ylabel() for a in axs[:, 0]] == [
        "x [m]"] * 3 + ["y [m]"] * 3
    axs = axs.ravel()
    axs[4].set_xlim(0.2, 0.7)
    axs[8].set_ylim(0.1, 0.6)
    assert {a.get_xlim() for a in axs} == {(0.2, 0.7)}
    assert {a.get_ylim() for a in axs} == {(0.1, 0.6)}


def test_slices_title_names_robot_worst_case_count_and_band(close_figures):
    """The figure title: robot, the dimension reduced to its worst case, the positions in the
    dynamic workspace (all-pass over the parameter values), the band and the margin."""
    ds = synthetic_map()
    n_dyn = int(ds["dynamic"].all("parameter").sum())
    fig = plot_workspace_slices(ds)
    assert fig.get_suptitle().replace("\n", " ") == (
        f"test workspace map (worst case over parameter): {n_dyn} of 12 positions in the "
        "dynamic workspace forbidden band [0.0, 1.5] Hz, margin 5%; grey: infeasible, or "
        "platform modes not all found")
    title = plot_workspace_slices(ds.expand_dims(orientation=[0, 1])).get_suptitle()
    assert "map (worst case over orientation, parameter): " in title.replace("\n", " ")


@pytest.mark.parametrize("margin, text", [(0.004, "margin 0.4%"), (0.125, "margin 12.5%"),
                                          (0.0, "margin 0%")])
def test_slices_title_gives_a_small_margin_as_it_is(close_figures, margin, text):
    """A margin below half a percent is written as it is, not rounded to 0 %."""
    ds = synthetic_map()
    ds.attrs["margin"] = margin
    title = plot_workspace_slices(ds).get_suptitle().replace("\n", " ")
    assert f"Hz, {text}; grey" in title


def test_slices_title_without_reduced_dimensions_says_no_worst_case(close_figures):
    """A map without orientation or parameter dimensions has no "worst case" in its title."""
    ds = five_level_map()
    fig = plot_workspace_slices(ds)
    text = fig.get_suptitle().replace("\n", " ")
    assert text.startswith(f"{ds.attrs['robot']} workspace map: {int(ds['dynamic'].sum())} of "
                           f"{ds['dynamic'].size} positions")
    assert "worst case" not in text


def test_a_long_title_word_is_broken_to_fit_the_figure(close_figures):
    """A robot name of 200 letters s (0.521 em in DejaVu Sans, 6.25 pt at 12 pt) is broken
    to fit the 8 in figure: 88 letters a line (11 per inch) are 7.6 in; 96 would be 8.3 in."""
    ds = five_level_map()
    ds.attrs["robot"] = "s" * 200
    with matplotlib.rc_context({"font.family": "DejaVu Sans", "figure.titlesize": 12.0}):
        fig = plot_workspace_slices(ds, n_slices=1)
        fig.canvas.draw()
    box, title = fig.get_window_extent(), fig._suptitle.get_window_extent()
    assert fig.get_figwidth() == 8.0 and box.x0 <= title.x0 and title.x1 <= box.x1
