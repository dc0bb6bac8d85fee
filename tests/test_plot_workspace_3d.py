"""The 3-D view of a workspace map (dynstiff/plot/workspace.py, plot_workspace_3d): each
position in its group, the markers' colours from the colour bar, labels, title, legend and
size. The maps and figure helpers are those of tests/test_plot_workspace.py."""

import numpy as np
import pytest

pytest.importorskip("xarray")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from test_plot_workspace import bar_colours, colour_bars, grid_map, synthetic_map  # noqa: E402

from dynstiff.plot.workspace import plot_workspace_3d  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def markers_3d(ax):
    """The four scatters of the 3-D view, by their legend labels."""
    handles, labels = ax.get_legend_handles_labels()
    return dict(zip(labels, handles, strict=True))


def test_3d_view_puts_each_position_in_its_group():
    """Filled markers at the positions passing every check (at every parameter value),
    hollow ones at the feasible rest and grey dots at the infeasible positions, at their
    (x, y, z); the legend names the groups in that order (the fourth, empty here: positions
    whose modes were not all found)."""
    ds = synthetic_map()
    f1 = ds["first_platform_hz"].min("parameter").values
    dyn = ds["dynamic"].all("parameter").values
    feas = ds["feasible"].all("parameter").values
    X, Y, Z = np.meshgrid(ds["x"], ds["y"], ds["z"], indexing="ij")
    fig = plot_workspace_3d(ds)
    ax = fig.axes[0]
    groups = markers_3d(ax)
    assert list(groups) == ["dynamic workspace", "a check fails", "infeasible",
                            "modes not all found"]
    for label, where in (("dynamic workspace", dyn & feas), ("a check fails", feas & ~dyn),
                         ("infeasible", ~feas)):
        assert where.any()
        got = np.column_stack([np.ravel(v) for v in groups[label]._offsets3d])
        np.testing.assert_array_equal(got, np.column_stack([X[where], Y[where], Z[where]]))
    np.testing.assert_array_equal(groups["dynamic workspace"].get_array(), f1[dyn & feas])


def rows(colours):
    """Colours as a sorted list of RGBA tuples (a 3-D scatter draws in depth order)."""
    return sorted(map(tuple, np.asarray(colours)))


def test_3d_markers_take_the_colour_bars_colour_of_their_frequency():
    """Filled markers' faces and hollow markers' edges are the colour bar's colour of their
    position's frequency, without depth shading (alpha 1) -- also when the user's default
    colormap is another one."""
    ds = synthetic_map()
    f1 = ds["first_platform_hz"].min("parameter").values
    dyn = ds["dynamic"].all("parameter").values
    feas = ds["feasible"].all("parameter").values
    with matplotlib.rc_context({"image.cmap": "plasma"}):
        fig = plot_workspace_3d(ds)
        fig.canvas.draw()
    ax = fig.axes[0]
    groups = markers_3d(ax)
    (bar,) = colour_bars(fig)
    scale = bar_colours(bar)
    assert scale.get_clim() == (np.nanmin(f1), np.nanmax(f1))
    filled, hollow = groups["dynamic workspace"], groups["a check fails"]
    np.testing.assert_array_equal(rows(filled.get_facecolor()),
                                  rows(scale.to_rgba(f1[dyn & feas])))
    np.testing.assert_allclose(rows(hollow.get_edgecolor()),
                               rows(scale.to_rgba(f1[feas & ~dyn])), atol=1e-12)
    assert np.all(np.asarray(hollow.get_facecolor())[:, 3] == 0)      # hollow


def test_3d_view_labels_title_legend_and_size():
    """Axis labels in m, the colour bar labelled with the frequency, the title with the robot
    and the count passing every check, the legend in the upper left, a 7.5 x 6 in figure."""
    ds = synthetic_map()
    n_dyn = int(ds["dynamic"].all("parameter").sum())
    fig = plot_workspace_3d(ds)
    fig.canvas.draw()
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x [m]", "y [m]", "z [m]")
    assert [b.get_ylabel() for b in colour_bars(fig)] == ["first platform frequency [Hz]"]
    assert ax.get_title() == f"test: {n_dyn} of 12 positions pass every check"
    np.testing.assert_allclose(fig.get_size_inches(), [7.5, 6.0])
    r = fig.canvas.get_renderer()
    leg, box = ax.get_legend().get_window_extent(r), ax.get_window_extent(r)
    pad = 2 * fig.dpi * 10 / 72          # within 2 font sizes (10 pt) of the corner
    assert leg.x0 - box.x0 < pad and box.y1 - leg.y1 < pad
    assert leg.x1 < (box.x0 + box.x1) / 2                # left half, not the centre/right


def test_3d_view_draws_a_feasible_position_whose_modes_were_not_all_found():
    """A feasible position with a NaN first platform frequency (its platform modes not all
    found) was drawn in no group while the title counted it: it is a black cross, and the
    four groups hold every position once."""
    f1 = np.array([[[2.0], [3.0]], [[np.nan], [4.0]]])
    ds = grid_map([0.0, 1.0], [0.0, 1.0], [1.0], f1)
    ds["first_platform_hz"][1, 0, 0] = np.nan
    fig = plot_workspace_3d(ds)
    groups = markers_3d(fig.axes[0])
    lost = np.column_stack([np.ravel(v) for v in groups["modes not all found"]._offsets3d])
    np.testing.assert_array_equal(lost, [[1.0, 0.0, 1.0]])
    assert sum(len(np.ravel(g._offsets3d[0])) for g in groups.values()) == 4
    assert groups["modes not all found"].get_facecolor()[0].tolist() == [0.0, 0.0, 0.0, 1.0]
