"""The main job: ``demo`` (a built-in scene, or one cable) and ``report`` (any scene):
tables, figures and a self-contained HTML page."""

from dynstiff.cli.common import damping_option, info, refuse_unused, scene_settings
from dynstiff.cli.console import elapsed
from dynstiff.cli.options import add_band, add_model, add_n_modes, add_pose, add_quiet, add_scene

__all__ = ["add_parsers"]


def _scene_at_pose(args):
    """The scene, moved to ``--pose`` if given (the report analyses the scene's pose)."""
    from dataclasses import replace

    from dynstiff.robot.pose import as_pose
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    if args.pose is not None:
        pose = as_pose(args.pose)
        scene.robot.equilibrium(pose=pose)          # an infeasible pose fails before any file
        scene = replace(scene, pose=pose, unstretched_lengths=None)
    return scene


def _cmd_report(args):
    from dynstiff.report.robot import robot_report
    scene = _scene_at_pose(args)
    settings = scene_settings(scene, args)          # every input checked before any file
    with elapsed(f"{args.command} {scene.name}", args.quiet):
        text, files = robot_report(scene, args.out, settings=settings, n_points=args.points)
    info(args).write(text)
    info(args).write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


def _cmd_demo(args):
    if not args.cable:
        return _cmd_report(args)
    from dynstiff.errors import InvalidParameterError
    if args.scene != "cogiro":
        raise InvalidParameterError(f"demo --cable reports CoGiRo's cable 0, not a scene's: "
                                    f"drop {args.scene!r} (or --cable)")
    refuse_unused(args, ("--pose", "-n", "--model", "--damping"),
                  "with --cable (the single-cable report of CoGiRo's cable 0)")
    from dynstiff.report.cable import cable_report, write_report
    band = args.band[1] if args.band else args.fmax
    with elapsed("demo --cable", args.quiet):
        rep = cable_report(fmax_hz=band or 12.0, n_points=args.points)
        files = write_report(rep, args.out)
    info(args).write(rep.text())
    info(args).write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


def _common(p, out):
    add_pose(p, lengths=False, what="default: the scene's pose")
    add_band(p)
    add_n_modes(p, "in the modes table (default: the scene's n_modes)")
    add_model(p)
    p.add_argument("--points", type=int, default=3000,
                   help="uniform frequencies of the FRFs: refined around every mode "
                        "(default %(default)s)")
    damping_option(p)
    p.add_argument("--out", default=out, metavar="FOLDER",
                   help="write the main result to: the output folder, created (default "
                        "%(default)s)")
    add_quiet(p)


def add_parsers(sub):
    """Add the ``demo``, ``report`` subcommands to the subparsers ``sub``."""
    demo = sub.add_parser(
        "demo", help="main job on a scene (default: CoGiRo): statics, modes, model choice, "
                     "design checks, FRF and mode-shape figures, CSV tables")
    add_scene(demo, optional=True)
    demo.add_argument("--cable", action="store_true",
                      help="single-cable report instead (CoGiRo cable 0: statics, fixed-end "
                           "frequencies, dynamic stiffness plot; the top of --band or --fmax, "
                           "default 12 Hz)")
    _common(demo, "dynstiff-demo")
    demo.set_defaults(func=_cmd_demo)
    rp = sub.add_parser("report", help="the demo's analysis of one scene: tables, figures and "
                                       "a self-contained report.html")
    add_scene(rp)
    _common(rp, "dynstiff-report")
    rp.set_defaults(func=_cmd_report)
