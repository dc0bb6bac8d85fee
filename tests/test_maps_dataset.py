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
