"""Workspace maps as data (dynstiff/maps/dataset.py): units and provenance, the netCDF
round trip (bool verdicts and the reasons of failures restored), the tidy tables."""

import numpy as np
import pytest

import dynstiff as ds

xr = pytest.importorskip("xarray")
from dynstiff.maps.dataset import VARIABLES, open_workspace

POSES = [[0.0, 0.0, 1.0], [9.0, 0.0, 1.0], [1.0, 1.0, 2.0]]


@pytest.fixture(scope="module")
def wmap():
    robot = ds.load_scene("cogiro").robot
    return ds.workspace(robot, POSES, n_modes=3, band_hz=(0.0, 1.5), parameter="EA",
                        values=[1.39487e5, 1.6e5])


def test_every_variable_has_units_and_the_map_its_provenance(wmap):
    for name in VARIABLES:
        assert "units" in wmap[name].attrs and wmap[name].attrs["long_name"]
    assert wmap["tension"].attrs["units"] == "N" and wmap["freq"].attrs["units"] == "Hz"
    assert wmap["parameter"].attrs["units"] == "N"
    assert wmap.attrs["robot"] == "cogiro" and "dynstiff" in wmap.attrs["source"]
    assert wmap.attrs["n_modes"] == 3 and wmap.attrs["engine"] == "serial"
    assert wmap["feasible"].dims == ("pose", "parameter")


def test_netcdf_round_trip_restores_the_map(wmap, tmp_path):
    path = tmp_path / "map.nc"
    wmap.to_netcdf(path)
    back = open_workspace(path)
    xr.testing.assert_identical(back.drop_attrs(), wmap.drop_attrs())
    assert back["feasible"].dtype == bool and back["passed"].dtype == bool
    assert str(back["reason"].values[1, 0]).startswith("InfeasiblePoseError: pose [9.0")
    assert back.attrs["robot"] == "cogiro"


def test_tables_have_one_row_per_pose_and_per_mode(wmap):
    df = wmap.dynstiff.to_frame()
    assert len(df) == 3 * 2
    assert df["feasible"].tolist() == [True, True, False, False, True, True]
    assert {"check: tension limits", "first_platform_hz", "reason",
            "largest tension [N]"} <= set(df.columns)
    row = df[(df["pose"] == 2) & (df["parameter"] == 1.6e5)].iloc[0]
    assert row["largest tension [N]"] == pytest.approx(
        float(wmap["max_tension"].isel(pose=2, parameter=1).max()))
    modes = wmap.dynstiff.modes_frame()
    assert len(modes) == 3 * 2 * 3
    np.testing.assert_allclose(modes["freq"].to_numpy(),
                               wmap["freq"].values.reshape(-1), equal_nan=True)


def test_the_coordinates_say_what_they_are(wmap):
    """Poses given as a list: pose, position and rotation with their units, the x/y/z
    components, the cables, modes and checks; a parameter's name and units; the reasons and
    the dynamic flag described; the title and provenance from the robot and the package."""
    from importlib.metadata import version
    c = wmap.coords
    assert {"pose", "mode", "cable", "check", "component", "parameter"} <= set(wmap.indexes)
    assert c["pose"].dims == ("pose",) and c["pose"].values.tolist() == [0, 1, 2]
    assert c["position"].dims == c["rotation"].dims == ("pose", "component")
    assert c["position"].attrs == {"units": "m"}
    assert c["rotation"].attrs == {"units": "rad", "long_name": "rotation vector"}
    assert c["component"].values.tolist() == ["x", "y", "z"]
    assert c["cable"].values.tolist() == list(range(8))
    assert c["mode"].values.tolist() == [1, 2, 3]
    assert c["check"].dtype.kind == "U" and "tension limits" in c["check"].values
    assert c["parameter"].attrs == {"long_name": "cable EA", "units": "N"}
    assert wmap["reason"].attrs == {"long_name": "why the pose is infeasible (empty when "
                                                 "feasible)"}
    assert wmap["dynamic"].attrs == {"units": "1", "long_name": "every check asked passes "
                                                                "(dynamic workspace)"}
    a = wmap.attrs
    assert a["title"] == "workspace map of cogiro"
    assert a["source"] == f"dynstiff {version('dynstiff')}, dynstiff.workspace"
    assert a["conventions"] == "SI units; frequencies in Hz; docs/theory.md §13"
    np.testing.assert_array_equal(a["tension_limits_N"], [100.0, 5000.0])
    assert a["tension_limits_N"].dtype == float


def test_a_grid_with_orientations_and_a_mass_parameter(tmp_path):
    from dataclasses import replace
    robot = replace(ds.load_scene("cogiro").robot, name="")
    m = ds.workspace(robot, box=(0, 1, 0, 0, 1, 1), step=1.0,
                     orientations=[[0, 0, 0], [0, 0, 0.05]], n_modes=2,
                     parameter="mass_per_length", values=[0.064])
    assert m["feasible"].dims == ("x", "y", "z", "orientation", "parameter")
    assert m.coords["rotation"].dims == ("orientation", "component")
    assert m.coords["rotation"].attrs == {"units": "rad", "long_name": "rotation vector"}
    assert m.coords["component"].values.tolist() == ["x", "y", "z"]
    assert m.coords["parameter"].attrs == {"long_name": "cable mass_per_length",
                                           "units": "kg/m"}
    assert m.attrs["title"] == "workspace map of robot" and m.attrs["robot"] == ""
    from dynstiff.maps.dataset import _points
    assert _points(m) == ["x", "y", "z", "orientation", "parameter"]


def test_verdicts_stored_as_integers_are_read_back_as_booleans(wmap, tmp_path):
    """Another writer may store the boolean variables as integers: every one of them comes
    back boolean."""
    names = ("feasible", "is_platform", "passed", "unknown", "dynamic")
    other = wmap.copy()
    for n in names:
        other[n] = other[n].astype(np.int8)
    other.to_netcdf(tmp_path / "ints.nc")
    back = open_workspace(tmp_path / "ints.nc")
    for n in names:
        assert back[n].dtype == bool, n
        np.testing.assert_array_equal(back[n].values, wmap[n].values)


def test_a_zarr_name_is_written_as_zarr(wmap, tmp_path):
    from dynstiff.maps.dataset import write_workspace
    path = tmp_path / "map.zarr"
    try:
        import zarr  # noqa: F401
    except ImportError:
        with pytest.raises((ImportError, ModuleNotFoundError), match="zarr"):
            write_workspace(wmap, path)
        assert not path.exists()
        return
    write_workspace(wmap, path)
    assert path.is_dir()
    xr.testing.assert_identical(open_workspace(path).drop_attrs(), wmap.drop_attrs())


def test_the_table_of_a_map_has_its_tensions_and_uncertain_columns_when_mapped(wmap):
    from dynstiff.errors import InvalidParameterError
    df = wmap.dynstiff.to_frame()
    least = wmap["min_tension"].min("cable").values.ravel()        # pose outer
    np.testing.assert_array_equal(df["least tension [N]"].to_numpy(), least)
    assert "uncertain_probability" not in df
    older = wmap.drop_vars(["uncertain_probability", "uncertain_margin"])
    older.attrs.pop("uncertain")
    assert "uncertain_margin" not in older.dynstiff.to_frame()
    flagged = wmap.copy()
    flagged.attrs["uncertain"] = "mass 10%"
    cols = list(flagged.dynstiff.to_frame().columns)
    assert {"feasible", "reason", "uncertain_probability", "uncertain_margin"} <= set(cols)
    with pytest.raises(InvalidParameterError,
                       match=r"^to_frame needs a workspace map \(dynstiff.workspace\)$"):
        xr.Dataset({"a": ("p", [1.0])}).dynstiff.to_frame()


def test_the_3d_view_is_drawn_from_the_map(wmap):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = ds.workspace(ds.load_scene("cogiro").robot, box=(0, 1, 0, 1, 1, 1), step=1.0,
                       n_modes=2).dynstiff.plot_3d()
    assert fig.axes and fig.axes[0].name == "3d"
    plt.close(fig)


def test_one_worker_is_the_serial_run_without_a_process_pool(monkeypatch):
    import concurrent.futures

    def no_pool(*a, **k):
        raise AssertionError("a process pool for one worker")
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", no_pool)
    m = ds.workspace(ds.load_scene("cogiro").robot, [[0.0, 0.0, 1.0]], n_modes=2, workers=1)
    assert m.attrs["engine"] == "serial" and bool(m["feasible"].all())
