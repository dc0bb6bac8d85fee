"""Workspace maps: statics, modes and design checks over a grid of poses, orientations and a
cable parameter (serial, on local processes or on Dask), and the map as data (an
xarray.Dataset with units, its netCDF file and its tables). The entry point is
:func:`dynstiff.workspace`."""
