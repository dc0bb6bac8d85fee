"""Workspace maps: statics, modes and design checks over a grid of poses, orientations and a
cable parameter (serial, on local processes or on Dask), and the map as data (an
xarray.Dataset with units, its netCDF file and its tables). The entry point is
:func:`dynstiff.workspace`."""

import importlib
import importlib.abc
import importlib.util
import sys

__all__ = ["register_accessor"]


def register_accessor():
    """Register the ``dataset.dynstiff`` accessor now if xarray is imported, else as soon as
    it is: ``import dynstiff`` calls this, so ``xr.open_dataset("map.nc").dynstiff`` works
    in either import order, and ``import dynstiff`` itself never imports xarray (nor the
    pandas it brings, about 0.2 s)."""
    if "xarray" in sys.modules:
        importlib.import_module("dynstiff.maps.dataset")
    elif not any(isinstance(f, _XarrayHook) for f in sys.meta_path):
        sys.meta_path.insert(0, _XarrayHook())


class _XarrayHook(importlib.abc.MetaPathFinder):
    """Finds nothing itself: on the first import of xarray it lets the other finders find
    it, then registers the accessor once xarray's own module has run."""

    def find_spec(self, name, path=None, target=None):
        if name != "xarray":
            return None
        sys.meta_path.remove(self)                 # once, and not for the search below
        spec = importlib.util.find_spec(name)
        if spec is None or spec.loader is None or not hasattr(spec.loader, "exec_module"):
            return spec
        run = spec.loader.exec_module

        def exec_module(module):
            run(module)
            importlib.import_module("dynstiff.maps.dataset")

        spec.loader.exec_module = exec_module
        return spec
