"""``sweep``: modes along a path (a line, a file of poses, a trajectory of the scene) or over
a parameter, the platform modes tracked, the veering diagram."""

from dynstiff.cli.common import (
    ProgressBar,
    info,
    refuse_unused,
    save_figure,
    scene_settings,
    scene_trajectory,
    table_metadata,
    write_tables,
)
from dynstiff.cli.options import (
    PARAMETERS,
    add_band,
    add_model,
    add_n_modes,
    add_outputs,
    add_pose,
    add_quiet,
    add_scene,
    parameter_help,
)

__all__ = ["add_parsers"]


def _read_path(path, rotation):
    """Poses of a path file: one pose a line, ``x y z`` [m] (the scene's rotation) or
    ``x y z rx ry rz`` [m, rad], separated by spaces or commas; blank lines, lines starting
    with ``#`` and a first line that is not numeric (a header) are skipped."""
    import numpy as np

    from dynstiff.errors import InvalidParameterError
    poses, header = [], False
    with open(path) as fh:
        lines = fh.read().splitlines()
    for k, line in enumerate(lines, start=1):
        text = line.split("#", 1)[0].replace(",", " ").split()
        if not text:
            continue
        try:
            vals = [float(v) for v in text]
        except ValueError:
            if not poses and not header:                    # one header line, first
                header = True
                continue
            raise InvalidParameterError(
                f"--path {path}: line {k}: expected numbers, got {line.strip()!r}") from None
        if len(vals) not in (3, 6) or not np.all(np.isfinite(vals)):
            raise InvalidParameterError(
                f"--path {path}: line {k}: expected 3 (x y z [m]) or 6 (x y z rx ry rz) "
                f"finite numbers, got {line.strip()!r}")
        poses.append(np.concatenate([vals, rotation]) if len(vals) == 3 else np.array(vals))
    if len(poses) < 2:
        raise InvalidParameterError(f"--path {path}: needs at least 2 poses, got {len(poses)}")
    return poses


def _with_parameter(robot, name, value):
    """The robot with one parameter changed (:data:`dynstiff.cli.options.PARAMETERS`): EA [N]
    or mass_per_length [kg/m] of every cable, platform mass [kg], or the minimum tension
    t_min [N] of the tension distribution."""
    from dataclasses import replace

    from dynstiff.robot.robot import Robot
    cables, platform, limits = robot.cables, robot.platform, robot.tension_limits
    if name in ("EA", "mass_per_length"):
        cables = [replace(c, **{name: value}) for c in cables]
    elif name == "mass":
        platform = replace(platform, mass=value)
    elif name == "t_min":
        limits = (value, limits[1])
    return Robot(robot.anchors, robot.attachments, cables, platform, g=robot.g,
                 tension_limits=limits, name=robot.name)


def _cmd_sweep(args):
    import numpy as np

    from dynstiff.analyses.sweep import sweep
    from dynstiff.errors import InvalidParameterError
    from dynstiff.scenes import load_scene
    if args.parameter is None:
        refuse_unused(args, ("--pose", "--values"), "without --parameter (the poses are the "
                                                     "path's)")
    if args.line is None and args.trajectory is None:
        refuse_unused(args, ("--steps",), "without --line or --trajectory")
    steps = 11 if args.steps is None else args.steps
    scene = load_scene(args.scene)
    st = scene_settings(scene, args)
    robot = scene.robot
    bar = ProgressBar(f"sweep {scene.name}", args.quiet)
    banded = args.band is not None or args.fmax is not None
    fmax = st.band_hz[1] if banded else None
    n_modes = None if banded and args.n is None else st.n_modes
    opts = dict(rung=st.rung, on_error="record", progress=bar, n_modes=n_modes, fmax_hz=fmax,
                **st.model_options())
    given = [name for name in ("line", "path", "trajectory", "parameter")
             if getattr(args, name) is not None]
    if len(given) != 1:
        raise InvalidParameterError(
            f"give exactly one of --line, --path, --trajectory or --parameter, got "
            f"{given or 'none'}")
    if steps < 2:
        raise InvalidParameterError(f"--steps must be >= 2, got {steps}")
    rot = scene.pose.rotation if scene.pose is not None else np.zeros(3)
    if args.trajectory is not None:
        poses, times = scene_trajectory(scene, args.trajectory).poses(steps)
        res = sweep(robot, poses=poses, values=times,
                    parameter=f"time along trajectory {args.trajectory} [s]", **opts)
    elif args.line is not None:
        pts = np.linspace(args.line[:3], args.line[3:], steps)
        res = sweep(robot, poses=[np.concatenate([p, rot]) for p in pts], **opts)
    elif args.path is not None:
        res = sweep(robot, poses=_read_path(args.path, rot), **opts)
    else:
        if not args.values:
            raise InvalidParameterError("--parameter needs --values V1 V2 ...")
        from dynstiff.robot.pose import as_pose
        pose = (as_pose(args.pose) if args.pose is not None else scene.pose
                if scene.pose is not None else scene.equilibrium().pose)
        units = {"EA": "N", "mass_per_length": "kg/m", "mass": "kg", "t_min": "N"}

        def build(v):
            return _with_parameter(robot, args.parameter, v).equilibrium(pose=pose)
        res = sweep(None, build=build, values=args.values,
                    parameter=f"{args.parameter} [{units[args.parameter]}]", **opts)
    bar.close()
    df = res.to_frame()
    where = (pose if args.parameter is not None else
             f"along {res.parameter} (the pose columns of each step)")
    write_tables(args, df, table_metadata(scene.name, where, st.rung, **{
        k: v for k, v in st.metadata().items() if k in ("band_hz", "segments")},
        units="Hz; value in " + res.parameter))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        from dynstiff.plot import plot_veering
        fig = plot_veering(res)
        if args.trajectory is not None:       # the waypoints, where the platform may rest
            ax = fig.axes[0]
            for k, t in enumerate(scene.trajectories[args.trajectory].times):
                ax.axvline(t, color="0.55", ls=":", lw=1.0, zorder=0, gid=f"waypoint-{k}",
                           label="waypoints" if k == 0 else None)
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, borderaxespad=0)
        save_figure(fig, args.plot)
    vt = res.veering_table()
    vt.insert(0, res.parameter, res.values)
    vt.columns = [vt.columns[0]] + [f"track {c} [Hz]" for c in vt.columns[1:]]
    info(args).write(f"{st.rung} model, undamped natural frequencies ({st.damping.text()} "
                     f"applies to FRFs)\n")
    info(args).write(f"{res.n_steps} steps, {res.n_tracks} platform-mode tracks, "
                     f"{int(np.sum(res.kind == 'local'))} local modes listed\n")
    info(args).write(vt.to_string(index=False, float_format=lambda x: f"{x:.5g}") + "\n")
    for k, v, msg in res.failures:
        info(args).write(f"step {k} ({res.parameter} = {v:g}): infeasible, skipped: "
                         f"{msg.splitlines()[0]}\n")
    for name in (args.csv, args.json, args.plot):
        if name and name != "-":
            info(args).write(f"wrote {name}\n")
    return 0


def add_parsers(sub):
    """Add the ``sweep`` subcommands to the subparsers ``sub``."""
    sw = sub.add_parser("sweep", help="modes along a straight path or over a parameter, platform "
                                      "modes tracked; table and veering diagram")
    add_scene(sw)
    sw.add_argument("--line", type=float, nargs=6, metavar=("X0", "Y0", "Z0", "X1", "Y1", "Z1"),
                    help="path of P from (X0, Y0, Z0) to (X1, Y1, Z1) [m], the scene's rotation")
    sw.add_argument("--steps", type=int,
                    help="poses along --line or --trajectory (default 11)")
    sw.add_argument("--path", metavar="FILE",
                    help="poses from a text/CSV file, one a line: x y z [m] (the scene's "
                         "rotation) or x y z rx ry rz [m, rad]; '#' comments, a header line")
    sw.add_argument("--trajectory", metavar="NAME",
                    help="the scene's trajectory NAME: poses along it ([[trajectories]], e.g. "
                         "from dynstiff import-caspr), --steps of them equally spaced in time")
    sw.add_argument("--parameter", choices=list(PARAMETERS),
                    help=parameter_help(PARAMETERS, "swept at the scene's pose (or --pose)"))
    sw.add_argument("--values", type=float, nargs="+", metavar="V",
                    help="values of --parameter, in its unit")
    add_pose(sw, lengths=False, what="of the --parameter sweep (default: the scene's pose)")
    add_n_modes(sw, "per step (default: the scene's n_modes; with --band or --fmax, all in "
                    "the band)")
    add_band(sw, "every mode up to its top at every step (default: the first --n-modes)")
    add_model(sw)
    sw.add_argument("--segments", type=int,
                    help="segments per cable of the lumped model (default: the scene's, "
                         "else 30)")
    add_outputs(sw, csv="one row per mode and step", json="one row per mode and step",
                plot="the veering diagram")
    add_quiet(sw)
    sw.set_defaults(func=_cmd_sweep)
