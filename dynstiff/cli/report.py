"""The main job: ``demo`` (a built-in scene, or one cable) and ``report`` (any scene):
tables, figures and a self-contained HTML page."""

from dynstiff.cli.common import damping_option, info, scene_settings

__all__ = ["add_parsers"]


def _cmd_report(args):
    from dynstiff.report.robot import robot_report
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    settings = scene_settings(scene, args)
    text, files = robot_report(scene, args.out, settings=settings, n_points=args.points)
    info(args).write(text)
    info(args).write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


def _cmd_demo(args):
    if args.cable:
        from dynstiff.report.cable import cable_report, write_report
        rep = cable_report(fmax_hz=args.fmax or 12.0, n_points=args.points)
        files = write_report(rep, args.out)
        info(args).write(rep.text())
    else:
        from dynstiff.report.robot import robot_report
        from dynstiff.scenes import load_scene
        scene = load_scene(args.scene)
        settings = scene_settings(scene, args)          # every input checked before any file
        text, files = robot_report(scene, args.out, settings=settings, n_points=args.points)
        info(args).write(text)
    info(args).write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


def add_parsers(sub):
    """Add the ``demo``, ``report`` subcommands to the subparsers ``sub``."""
    demo = sub.add_parser(
        "demo", help="main job on a scene (default: CoGiRo): statics, modes, model choice, "
                     "design checks, FRF and mode-shape figures, CSV tables")
    demo.add_argument("--scene", default="cogiro", help="scene (default %(default)s)")
    demo.add_argument("--cable", action="store_true",
                      help="single-cable report instead (CoGiRo cable 0: statics, fixed-end "
                           "frequencies, dynamic stiffness plot)")
    demo.add_argument("--out", default="dynstiff-demo", help="output folder (default %(default)s)")
    demo.add_argument("--fmax", type=float,
                      help="band upper end [Hz] (default: the scene's band)")
    demo.add_argument("--points", type=int, default=3000,
                      help="uniform frequencies of the FRFs, refined around every mode")
    damping_option(demo)
    demo.set_defaults(func=_cmd_demo)
    rp = sub.add_parser("report", help="the demo's analysis of one scene: tables, figures and "
                                       "a self-contained report.html")
    rp.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    rp.add_argument("--out", default="dynstiff-report", help="output folder")
    rp.add_argument("--fmax", type=float, help="band upper end [Hz] (default: the scene's)")
    rp.add_argument("--points", type=int, default=3000,
                    help="uniform frequencies of the FRFs, refined around every mode")
    damping_option(rp)
    rp.set_defaults(func=_cmd_report)
