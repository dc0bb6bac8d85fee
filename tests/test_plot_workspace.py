"""Figures of a workspace map (dynstiff/plot/workspace.py): the worst case over orientations
and parameter values, and the figures' content (cells, colour limits, counts in titles)."""

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
    assert "3 of 5 heights drawn" in fig._suptitle.get_text().replace("\n", " ")
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
