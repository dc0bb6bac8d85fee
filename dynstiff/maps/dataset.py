"""Workspace maps as labelled N-d data: the ``xarray.Dataset`` of :func:`dynstiff.workspace`,
its tidy tables, files and figures (docs/theory.md §13).

Importing this module imports xarray (the ``workspace`` extra) and registers the accessor
``dataset.dynstiff`` with ``.to_frame()``, ``.modes_frame()``, ``.plot()`` and ``.plot_3d()``.
"""

import datetime
import platform as _platform

import numpy as np

from dynstiff.errors import InvalidParameterError

try:
    import xarray as xr
except ImportError as exc:            # pragma: no cover - depends on the environment
    raise ImportError('workspace maps need xarray: pip install "dynstiff[workspace]"') from exc

__all__ = ["VARIABLES", "WorkspaceAccessor", "open_workspace", "to_dataset", "write_workspace"]

#: Variables of a workspace map: (extra dimensions, units, description).
VARIABLES = {
    "feasible": ((), "1", "inverse statics and modes succeeded"),
    "residual": ((), "1", "free-DOF wrench residual relative to the platform weight"),
    "tension": (("cable",), "N", "tension at the platform end B"),
    "unstretched_length": (("cable",), "m", "unstretched cable length L0"),
    "min_tension": (("cable",), "N", "least tension along the cable"),
    "max_tension": (("cable",), "N", "largest tension along the cable"),
    "sag_ratio": (("cable",), "1", "largest distance from the chord / chord length"),
    "freq": (("mode",), "Hz", "natural frequency"),
    "platform_share": (("mode",), "1", "platform share of the modal kinetic energy"),
    "is_platform": (("mode",), "1", ("platform mode: a DOF's largest participation, or "
                                     "global (platform share >= 0.5)")),
    "first_platform_hz": ((), "Hz", "lowest platform mode (NaN: not all found)"),
    "band_margin": ((), "1", ("smallest relative distance outside the forbidden band of the "
                              "modes held to the margin (negative inside)")),
    "proximity_gap": ((), "1", ("smallest relative gap between a local and a platform mode "
                                "within proximity_rtol (NaN if none)")),
    "uncertain_probability": ((), "1", ("probability that a mode held to the margin lies "
                                        "within it of the forbidden band, Monte Carlo (NaN "
                                        "without uncertain=)")),
    "uncertain_margin": ((), "1", ("band margin reached with probability confidence "
                                   "(NaN without uncertain=)")),
    "passed": (("check",), "1", "check verdict pass"),
    "unknown": (("check",), "1", ("check verdict unknown: what it needs was not computed "
                                  "(it fails the pose)")),
}


def _attr(v):
    """An attribute value netCDF can hold."""
    if v is None:
        return "none"
    if isinstance(v, (bool, np.bool_)):
        return int(v)
    if isinstance(v, (tuple, list)):
        return np.asarray(v, dtype=float)
    if isinstance(v, (int, float, str, np.integer, np.floating)):
        return v
    return str(v)


def to_dataset(robot, X, layout, parameter, values, results, settings):
    """Assemble the chunk results of :func:`dynstiff.workspace` into a Dataset.

    Parameters
    ----------
    robot : Robot
    X : ndarray, shape (n_poses, 6)
        Poses [m, rad] in input order.
    layout : dict
        ``kind`` "grid" (with ``axes`` and ``orientations``) or "poses".
    parameter : str or None; values : ndarray or None
    results : list of dict
        :func:`dynstiff.maps.workspace.evaluate_chunk` outputs in task order (parameter value
        outer, poses inner).
    settings : dict
        Analysis settings, stored as attributes, and ``checks`` (the check names).

    Returns
    -------
    xarray.Dataset
    """
    from importlib.metadata import PackageNotFoundError, version
    try:
        __version__ = version("dynstiff")
    except PackageNotFoundError:        # pragma: no cover - run from a source tree
        __version__ = "unknown"
    checks = settings.pop("checks")
    flat = {k: np.concatenate([r[k] for r in results]) if k != "reason"
            else np.array([s for r in results for s in r[k]], dtype=str)
            for k in list(VARIABLES) + ["reason"]}
    n_v = 1 if parameter is None else len(values)
    if layout["kind"] == "grid":
        ax = layout["axes"]
        pdims = ["x", "y", "z"]
        pshape = [len(a) for a in ax]
        coords = {"x": ("x", ax[0], {"units": "m"}), "y": ("y", ax[1], {"units": "m"}),
                  "z": ("z", ax[2], {"units": "m"})}
        if layout["orientations"] is not None:
            rot = layout["orientations"]
            pdims.append("orientation")
            pshape.append(len(rot))
            coords["orientation"] = ("orientation", np.arange(len(rot)))
            coords["rotation"] = (("orientation", "component"), rot,
                                  {"units": "rad", "long_name": "rotation vector"})
    else:
        pdims, pshape = ["pose"], [len(X)]
        coords = {"pose": ("pose", np.arange(len(X))),
                  "position": (("pose", "component"), X[:, :3], {"units": "m"}),
                  "rotation": (("pose", "component"), X[:, 3:],
                               {"units": "rad", "long_name": "rotation vector"})}
    if parameter is not None:
        coords["parameter"] = ("parameter", np.asarray(values, dtype=float),
                               {"long_name": f"cable {parameter}",
                                "units": {"EA": "N", "mass_per_length": "kg/m"}.get(
                                    parameter, "SI")})
    n_modes = settings["n_modes"]
    coords["mode"] = ("mode", np.arange(1, n_modes + 1))
    coords["cable"] = ("cable", np.arange(robot.n_cables))
    coords["check"] = ("check", np.array(checks, dtype=str))
    if "component" in {d for c in coords.values() for d in np.atleast_1d(c[0])}:
        coords["component"] = ("component", np.array(["x", "y", "z"]))
    dims = pdims + (["parameter"] if parameter is not None else [])
    n_p = int(np.prod(pshape))

    def shaped(a, extra):
        a = a.reshape([n_v, n_p] + list(a.shape[1:]))
        a = np.moveaxis(a, 0, 1)                       # (n_p, n_v, ...)
        a = a.reshape(pshape + [n_v] + list(a.shape[2:]))
        return a if parameter is not None else a.reshape(pshape + list(a.shape[len(pshape)
                                                                              + 1:]))

    data = {}
    for name, (extra, units, text) in VARIABLES.items():
        data[name] = (dims + list(extra), shaped(flat[name], extra),
                      {"units": units, "long_name": text})
    data["reason"] = (dims, shaped(flat["reason"], ()),
                      {"long_name": "why the pose is infeasible (empty when feasible)"})
    dyn = data["feasible"][1] & np.all(data["passed"][1], axis=-1)
    data["dynamic"] = (dims, dyn, {"units": "1", "long_name": "every check asked passes "
                                                             "(dynamic workspace)"})
    attrs = {"title": f"workspace map of {robot.name or 'robot'}",
             "source": f"dynstiff {__version__}, dynstiff.workspace",
             "history": f"{datetime.datetime.now(datetime.UTC).isoformat(timespec='seconds')}"
                        f" computed with python {_platform.python_version()}, numpy "
                        f"{np.__version__}",
             "robot": robot.name or "",
             "tension_limits_N": np.asarray(robot.tension_limits, dtype=float),
             "cable_parameter": parameter or "none",
             "conventions": "SI units; frequencies in Hz; docs/theory.md §13"}
    attrs.update({k: _attr(v) for k, v in settings.items()})
    return xr.Dataset(data, coords=coords, attrs=attrs)


def open_workspace(path, **kw):
    """Read a workspace map written by ``dataset.to_netcdf`` (or ``.to_zarr`` for a
    directory ending in ``.zarr``) and restore its types (bool verdicts)."""
    path = str(path)
    ds = xr.open_zarr(path, **kw) if path.endswith(".zarr") else xr.open_dataset(path, **kw)
    ds = ds.load()
    for name in ("feasible", "is_platform", "passed", "unknown", "dynamic"):
        if name in ds and ds[name].dtype != bool:
            ds[name] = ds[name].astype(bool)
    return ds


def write_workspace(ds, path):
    """Write a workspace map to ``path``: netCDF, or Zarr for a name ending in ``.zarr``,
    atomically (a temporary beside ``path`` that replaces it when complete:
    :func:`dynstiff.io.files.atomic_path`), so a failure leaves an existing file as it was.
    Returns ``path``; :func:`open_workspace` reads it back."""
    from dynstiff.io.files import atomic_path
    with atomic_path(path) as tmp:
        if str(path).endswith(".zarr"):
            ds.to_zarr(tmp, mode="w")
        else:
            ds.to_netcdf(tmp)
    return path


def _points(ds):
    """The pose dimensions of a map (all dims except mode, cable, check, component)."""
    return [d for d in ds.dims if d not in ("mode", "cable", "check", "component")]


@xr.register_dataset_accessor("dynstiff")
class WorkspaceAccessor:
    """``dataset.dynstiff``: tables and figures of a workspace map."""

    def __init__(self, ds):
        self._ds = ds

    def to_frame(self):
        """pandas DataFrame, one row per pose (and parameter value): the pose coordinates,
        ``feasible``, ``reason``, ``first_platform_hz``, ``band_margin``,
        ``proximity_gap``, ``dynamic`` (and ``uncertain_probability``,
        ``uncertain_margin`` in a map with uncertainties), the verdict of each check
        ("pass", "fail", "unknown") and the least and largest tension [N]."""
        ds = self._ds
        if "check" not in ds.dims or "feasible" not in ds:
            raise InvalidParameterError("to_frame needs a workspace map (dynstiff.workspace)")
        keep = ["feasible", "reason", "residual", "first_platform_hz", "band_margin",
                "proximity_gap", "dynamic"]
        if str(ds.attrs.get("uncertain", "none")) != "none":
            keep += ["uncertain_probability", "uncertain_margin"]
        base = ds[keep].copy()
        for c in ds["check"].values:
            passed = ds["passed"].sel(check=c, drop=True)
            unknown = ds["unknown"].sel(check=c, drop=True)
            base[f"check: {c}"] = xr.where(unknown, "unknown", xr.where(passed, "pass", "fail"))
        base["least tension [N]"] = ds["min_tension"].min("cable")
        base["largest tension [N]"] = ds["max_tension"].max("cable")
        drop = [v for v in base.coords if v not in base.dims]
        return base.drop_vars(drop).to_dataframe().reset_index()

    def modes_frame(self):
        """pandas DataFrame, one row per pose and mode: ``freq``, ``platform_share``,
        ``is_platform``."""
        ds = self._ds[["freq", "platform_share", "is_platform"]]
        drop = [v for v in ds.coords if v not in ds.dims]
        return ds.drop_vars(drop).to_dataframe().reset_index()

    def plot(self, n_slices=None, fig=None):
        """Slices of the first platform frequency, the band margin and the dynamic workspace:
        :func:`dynstiff.plot.workspace.plot_workspace_slices`. Returns the Figure."""
        from dynstiff.plot.workspace import plot_workspace_slices
        return plot_workspace_slices(self._ds, n_slices=n_slices, fig=fig)

    def plot_3d(self, ax=None):
        """3-D view of the first platform frequency and the dynamic workspace:
        :func:`dynstiff.plot.workspace.plot_workspace_3d`. Returns the Figure."""
        from dynstiff.plot.workspace import plot_workspace_3d
        return plot_workspace_3d(self._ds, ax=ax)
