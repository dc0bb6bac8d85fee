"""The ``dynstiff workspace`` command: a workspace map of a scene over a box grid (given, or
the scene's ``[workspace] box``; docs/theory.md §13), written to netCDF (or Zarr) with an
optional figure and table."""


from dynstiff.cli.common import save_figure, table_metadata, write_tables
from dynstiff.cli.options import (
    MEANINGS,
    add_forbidden_band,
    add_max_modes,
    add_n_modes,
    add_outputs,
    add_quiet,
    add_scene,
    add_uncertain,
    parameter_help,
    uncertain_items,
)

__all__ = ["add_parsers"]

#: Columns of the workspace table, named as in every table of the command line.
COLUMNS = {"x": "x [m]", "y": "y [m]", "z": "z [m]", "rx": "rx [rad]", "ry": "ry [rad]",
           "rz": "rz [rad]", "residual": "statics residual [N]",
           "first_platform_hz": "first platform freq [Hz]",
           "band_margin": "band margin [-]", "proximity_gap": "proximity gap [-]",
           "uncertain_probability": "probability of a platform mode in the band [-]",
           "uncertain_margin": "band margin at the confidence [-]"}


def add_parsers(sub):
    """Add the ``workspace`` subcommand to the subparsers ``sub`` of the dynstiff parser."""
    from dynstiff.maps.guards import MAX_POSES
    ws = sub.add_parser(
        "workspace", help="map statics, modes and design checks over a box grid of positions "
                          "(optionally x orientations x a cable parameter); netCDF output")
    add_scene(ws)
    ws.add_argument("--box", type=float, nargs=6,
                    metavar=("X0", "X1", "Y0", "Y1", "Z0", "Z1"),
                    help="grid box [m] (default: the scene's [workspace] box, e.g. a CASPR "
                         "joint's q_min / q_max)")
    ws.add_argument("--step", type=float,
                    help="grid spacing [m] (default: a quarter of the box's longest side)")
    ws.add_argument("--orientations", metavar="FILE",
                    help="rotation vectors rx ry rz [rad], one a line ('#' comments), "
                         "crossed with the positions (default: the scene's rotation)")
    ws.add_argument("--parameter", choices=["EA", "mass_per_length"],
                    help=parameter_help(["EA", "mass_per_length"], "set on every cable, "
                                        "crossed with the poses"))
    ws.add_argument("--values", type=float, nargs="+", metavar="V",
                    help="values of --parameter, in its unit")
    add_n_modes(ws, "per pose (default: the scene's n_modes)")
    add_max_modes(ws, _max_platform_modes())
    add_forbidden_band(ws)
    ws.add_argument("--margin", type=float,
                    help="relative margin of the platform modes to the forbidden band [-] "
                         "(default: the scene's, else 0.05)")
    add_uncertain(ws)
    ws.add_argument("--tensions", choices=["default", "max-frequency"], default="default",
                    help="tension distribution at every pose: the default (closest to t_min) "
                         "or the one that maximises the first platform mode")
    ws.add_argument("--chunk-size", type=int, default=25,
                    help="poses per task, warm-started along it (default %(default)s)")
    run = ws.add_mutually_exclusive_group()
    run.add_argument("--workers", type=int, help="local worker processes")
    run.add_argument("--scheduler", metavar="ADDRESS",
                     help="Dask scheduler address, e.g. tcp://10.0.0.5:8786")
    ws.add_argument("--out", required=True, metavar="FILE",
                    help=MEANINGS["--out"] + ": the map file, NAME.nc (netCDF) or NAME.zarr "
                                             "(Zarr folder)")
    add_outputs(ws, csv="one row per pose", json="one row per pose",
                plot="the slices of the map")
    add_quiet(ws)
    ws.add_argument("--resume", action="store_true",
                    help="continue an interrupted run (its chunks are saved in OUT.parts)")
    ws.add_argument("--max-poses", type=int, default=MAX_POSES,
                    help="refuse a map of more poses (default %(default)s)")
    ws.set_defaults(func=_cmd_workspace)
    return ws


def _max_platform_modes():
    from dynstiff.analyses.platform_modes import MAX_PLATFORM_MODES
    return MAX_PLATFORM_MODES


def _orientations(path):
    import numpy as np

    from dynstiff.errors import InvalidParameterError
    try:
        rot = np.loadtxt(path, comments="#", ndmin=2, dtype=float)
    except ValueError as exc:
        raise InvalidParameterError(f"--orientations {path}: {exc}") from None
    if rot.shape[1] != 3 or rot.shape[0] == 0:
        raise InvalidParameterError(f"--orientations {path}: need 3 numbers a line "
                                    f"(rx ry rz [rad]), got shape {rot.shape}")
    return rot


def _cmd_workspace(args):
    from pathlib import Path

    import numpy as np

    from dynstiff.errors import InvalidParameterError
    from dynstiff.maps.workspace import workspace
    from dynstiff.scenes import load_scene
    out = Path(args.out)
    if out.suffix not in (".nc", ".zarr") or not out.parent.is_dir():
        raise InvalidParameterError(f"--out {args.out}: give NAME.nc or NAME.zarr in an "
                                    f"existing folder")
    if out.suffix == ".zarr":
        try:
            import zarr  # noqa: F401
        except ImportError:
            raise InvalidParameterError(
                f"--out {args.out}: Zarr output needs the zarr package (pip install zarr); "
                f"or give NAME.nc") from None
    if (args.parameter is None) != (args.values is None):
        raise InvalidParameterError("--parameter and --values go together")
    if args.workers is not None and args.workers < 1:
        raise InvalidParameterError(f"--workers must be >= 1, got {args.workers}")
    from dynstiff.maps.store import check_folder, remove_folder
    check_folder(f"{out}.parts")
    scene = load_scene(args.scene)
    box = args.box if args.box is not None else scene.workspace_box
    if box is None:
        raise InvalidParameterError(f"--box X0 X1 Y0 Y1 Z0 Z1 is needed: scene {scene.name!r} "
                                    f"has no [workspace] box")
    rot = (_orientations(args.orientations) if args.orientations else
           None if scene.pose is None or not np.any(scene.pose.rotation)
           else scene.pose.rotation[None, :])
    from dynstiff.cli.common import info as report_stream
    from dynstiff.cli.common import scene_settings
    st = scene_settings(scene, args)
    step = args.step if args.step is not None else max(
        box[1] - box[0], box[3] - box[2], box[5] - box[4]) / 4 or 1.0
    kw = dict(box=box, step=step, orientations=rot, parameter=args.parameter,
              values=args.values, n_modes=st.n_modes, band_hz=st.forbidden_hz,
              margin=st.margin, max_modes=args.max_modes, model_band_hz=st.band_hz,
              model_rtol=st.model_rtol, participation=st.participation,
              frf_limit=st.frf_limit, damping=st.damping, chunk_size=args.chunk_size,
              workers=args.workers, progress=not args.quiet, tensions=args.tensions,
              rung=st.rung, max_poses=args.max_poses, checkpoint=f"{out}.parts",
              resume=args.resume, uncertain=uncertain_items(args.uncertain) or None,
              **st.model_options())
    info = report_stream(args)
    if args.scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise InvalidParameterError(
                '--scheduler needs Dask: pip install "dynstiff[workspace]"') from None
        with Client(args.scheduler) as client:
            ds = workspace(scene.robot, client=client, **kw)
    else:
        ds = workspace(scene.robot, **kw)
    from dynstiff.maps.dataset import write_workspace
    write_workspace(ds, out)
    remove_folder(f"{out}.parts")                   # the saved chunks: in the map now
    f1 = ds["first_platform_hz"].values
    info.write(f"{int(ds['feasible'].size)} poses in {ds.attrs['wall_time_s']:.1f} s "
               f"({ds.attrs['engine']}): {int(ds['feasible'].sum())} feasible, "
               f"{int(ds['dynamic'].sum())} pass every check; first platform frequency "
               + (f"{np.nanmin(f1):.3f}-{np.nanmax(f1):.3f} Hz\n" if np.isfinite(f1).any()
                  else "not found\n"))
    if args.csv or args.json:
        df = ds.dynstiff.to_frame().rename(columns=COLUMNS)
        write_tables(args, df, table_metadata(
            scene.name, "the grid of the map (the pose columns)", st.rung,
            box=[float(v) for v in box], **{"step [m]": step}, map=str(args.out),
            forbidden_band_hz=list(st.forbidden_hz) if st.forbidden_hz else None,
            margin=st.margin, n_modes=st.n_modes))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        save_figure(ds.dynstiff.plot(), args.plot)
    for name in (args.out, args.plot, args.csv, args.json):
        if name and name != "-":
            info.write(f"wrote {name}\n")
    return 0
