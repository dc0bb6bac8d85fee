"""``simulate``: the lumped-mass time domain (free vibration from an offset and its
spectrum, or a line or a trajectory of the scene commanded through quasi-static cable
lengths).

A free vibration prints the spectrum's peaks in the band, each with the nearest frequency of
the linearised model: ``F Hz ~ mode M Hz (F - M Hz)``, M nan where the model has no mode in
the band.
"""

from dynstiff.cli.common import (
    ProgressBar,
    equilibrium,
    info,
    refuse_unused,
    save_figure,
    scene_trajectory,
    table_metadata,
    write_tables,
)
from dynstiff.cli.console import elapsed
from dynstiff.cli.options import add_outputs, add_pose, add_quiet, add_scene

__all__ = ["add_parsers"]


def _cmd_simulate(args):
    import warnings

    import numpy as np

    from dynstiff.analyses.eigen import eigenfrequencies
    from dynstiff.constants import DOF_NAMES
    from dynstiff.errors import InvalidParameterError
    from dynstiff.lumped import SlackSegmentWarning, simulate
    from dynstiff.models.ladder import build_model
    from dynstiff.scenes import load_scene
    if args.trajectory is not None and args.target is not None:
        raise InvalidParameterError("give --target or --trajectory, not both")
    if args.trajectory is not None:
        refuse_unused(args, ("--pose", "--lengths", "--offset", "--band", "--channel",
                              "--speed", "--ramp"),
                       "with --trajectory (the trajectory sets the start and the motion)")
    elif args.target is not None:
        refuse_unused(args, ("--offset", "--band", "--channel"),
                       "with --target (options of the free vibration)")
    else:
        refuse_unused(args, ("--speed", "--ramp"), "without --target (options of the line)")
    speed = 0.5 if args.speed is None else args.speed
    ramp = 1.0 if args.ramp is None else args.ramp
    scene = load_scene(args.scene)
    path = None if args.trajectory is None else scene_trajectory(scene, args.trajectory)
    eq = equilibrium(scene, args) if path is None else None
    start = None if eq is None else (eq.pose.position, eq.pose.rotation)
    if args.target is not None or args.trajectory is not None:
        from dynstiff.timedomain.trajectory import following, line, track
        if args.trajectory is not None:
            traj = following(path)
            what = (f"trajectory {args.trajectory!r} ({traj.duration:g} s, "
                    f"{path.times.size} waypoints)")
        else:
            traj = line(eq.pose.position, args.target, speed, rotation=eq.pose.rotation,
                        ramp=ramp)
            what = (f"line {np.round(traj.positions[0], 4).tolist()} -> {list(args.target)} m at "
                    f"{speed:g} m/s (ramp {ramp:g} s)")
        bar = _Stages(ProgressBar("quasi-static lengths", args.quiet, unit="pose"),
                      elapsed("time stepping", args.quiet))
        with warnings.catch_warnings(), bar:
            warnings.simplefilter("ignore", SlackSegmentWarning)
            tr = track(scene.robot, traj, segments=args.segments, dt=args.dt,
                       settle=args.time, progress=bar)
        resp = tr.response
        df = tr.to_frame()
        start = traj.positions[0], traj.rotations[0]
        info(args).write(
            f"{what}, {args.segments} segments per "
            f"cable, dt = {args.dt:g} s: largest deviation from the quasi-static path "
            f"{tr.max_deviation:.4g} m ({100 * tr.relative_max_deviation:.3g} % of the mean "
            f"cable length)\n")
        if args.plot:
            import matplotlib
            matplotlib.use("Agg")
            from dynstiff.plot import plot_tracking
            save_figure(plot_tracking(tr), args.plot)
    else:
        offset = np.zeros(6)
        fd = [k for k, n in enumerate(DOF_NAMES) if n in scene.robot.platform.free_dofs]
        if args.offset is not None:
            if len(args.offset) != 6:
                raise InvalidParameterError(
                    f"--offset needs 6 values dx dy dz [m] drx dry drz [rad], got "
                    f"{len(args.offset)}")
            offset = np.array(args.offset)
        else:
            offset[fd[0]] = 1e-3
        model = build_model(eq, "lumped", segments=args.segments)
        with elapsed(f"simulate {scene.name}", args.quiet):
            resp = simulate(model, args.time, args.dt, initial=offset)
        df = resp.to_frame().reset_index()
        ch = args.channel or DOF_NAMES[fd[0]]
        sp = resp.spectrum(ch, prominence=_SPECTRUM_PROMINENCE)
        f_model = eigenfrequencies(model, fmax_hz=sp.freq_hz[-1] * 0.5)
        if args.band is not None:
            band = tuple(args.band)
        elif scene.band_hz is not None:
            band = scene.band_hz
        elif f_model.size:
            band = (0.0, 1.5 * float(f_model[min(7, f_model.size - 1)]))
        else:
            raise InvalidParameterError(
                f"no band: the scene has no band_hz and the lumped model has no mode below "
                f"{sp.freq_hz[-1] * 0.5:.4g} Hz (half the spectrum's top at --dt "
                f"{args.dt:g} s); give --band LO HI or a smaller --dt")
        info(args).write(
            f"free vibration from offset {offset.tolist()}, {args.time:g} s, dt = "
            f"{args.dt:g} s, {args.segments} segments per cable (damping: the cables' own, "
            f"time domain): wall {resp.wall_time:.3g} s, "
            f"energy residual {np.abs(resp.energy.relative_residual).max():.2e}\n")
        peaks = np.sort(sp.peaks_hz[(sp.peaks_hz >= band[0]) & (sp.peaks_hz <= band[1])][:8])
        inband = f_model[(f_model >= band[0]) & (f_model <= band[1])]
        near = [f_model[int(np.argmin(np.abs(f_model - f)))] if f_model.size else np.nan
                for f in peaks]
        info(args).write(
            f"spectrum peaks of {ch} in {band[0]:g}-{band[1]:g} Hz (Hann window, "
            f"resolution {sp.resolution_hz:.3g} Hz, prominence >= "
            f"{_SPECTRUM_PROMINENCE:.0%} of the largest), each with the nearest linearised "
            f"mode:\n" + "".join(f"  {f:.4g} Hz ~ mode {m:.4g} Hz ({f - m:+.3g} Hz)\n"
                                 for f, m in zip(peaks, near)))
        info(args).write(f"linearised lumped-model frequencies in the band [Hz] "
                         f"({inband.size}): " + ", ".join(f"{f:.4g}" for f in inband[:8])
                         + (", ..." if inband.size > 8 else "") + "\n")
        if args.plot:
            import matplotlib
            matplotlib.use("Agg")
            from dynstiff.plot import plot_spectrum
            save_figure(plot_spectrum(sp, modes=f_model, band_hz=band), args.plot)
    from dynstiff.robot.pose import Pose
    write_tables(args, df, table_metadata(
        scene.name, Pose(start[0], start[1]), "lumped", segments=args.segments,
        **{"dt [s]": args.dt}, damping="the cables' own (time domain)",
        units="SI, in the column names"))
    for name in (args.csv, args.json, args.plot):
        if name and name != "-":
            info(args).write(f"wrote {name}\n")
    return 0


#: Smallest prominence of a reported spectrum peak, relative to the largest [-]: above the
#: Hann window's highest side lobe (2.7 % of the main lobe), so leakage is not reported.
_SPECTRUM_PROMINENCE = 0.03


class _Stages:
    """The progress of ``track``: a bar over the quasi-static poses, then the time elapsed
    while the motion is stepped."""

    def __init__(self, bar, stepping):
        self.bar, self.stepping, self.started = bar, stepping, False

    def __call__(self, done, total):
        self.bar(done, total)
        if done >= total and not self.started:
            self.started = True
            self.stepping.__enter__()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.bar.close()
        if self.started:
            self.stepping.__exit__(*exc)
        return False


def add_parsers(sub):
    """Add the ``simulate`` subcommands to the subparsers ``sub``."""
    si = sub.add_parser("simulate", help="time domain (lumped-mass cables): free vibration "
                                         "from an offset, or a line commanded through "
                                         "quasi-static cable lengths")
    add_scene(si)
    add_pose(si, what="the start (default: the scene's pose)")
    si.add_argument("--time", type=float, default=5.0,
                    help="duration [s] (after the path's end with --target or --trajectory; "
                         "default %(default)s)")
    si.add_argument("--dt", type=float, default=2e-3, help="time step [s] (default %(default)s)")
    si.add_argument("--segments", type=int, default=10,
                    help="segments per cable of the lumped model (default %(default)s)")
    si.add_argument("--offset", type=float, nargs="+", metavar="D",
                    help="initial platform offset dx dy dz [m] drx dry drz [rad] (default "
                         "1 mm along the first free DOF)")
    si.add_argument("--band", type=float, nargs=2, metavar=("LO", "HI"),
                    help="band of interest LO HI [Hz]: the spectrum's peaks and the model's "
                         "frequencies in it are listed (default: the scene's band_hz)")
    si.add_argument("--channel", choices=["x", "y", "z", "rx", "ry", "rz"],
                    help="channel of the spectrum (default: the first free DOF)")
    si.add_argument("--target", type=float, nargs=3, metavar=("X", "Y", "Z"),
                    help="target point: move P in a straight line to it [m] instead")
    si.add_argument("--trajectory", metavar="NAME",
                    help="the scene's trajectory NAME: follow it ([[trajectories]], e.g. from "
                         "dynstiff import-caspr) through quasi-static cable lengths instead")
    si.add_argument("--speed", type=float,
                    help="path speed of --target [m/s] (default 0.5)")
    si.add_argument("--ramp", type=float,
                    help="speed ramp duration of --target [s] (default 1.0)")
    add_outputs(si, csv="the time history", json="the time history",
                plot="the spectrum with the model's frequencies, or the path followed")
    add_quiet(si)
    si.set_defaults(func=_cmd_simulate)
