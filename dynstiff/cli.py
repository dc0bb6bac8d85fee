"""Command-line interface: ``dynstiff`` (or ``python -m dynstiff``)."""

import argparse
import sys

from .errors import DynstiffError


def _cmd_demo(args):
    from .report import cable_report, write_report
    rep = cable_report(fmax_hz=args.fmax, n_points=args.points)
    files = write_report(rep, args.out)
    sys.stdout.write(rep.text())
    sys.stdout.write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


def _cmd_scenes(args):
    from .scenes import list_scenes, load_scene
    for name in list_scenes():
        sys.stdout.write(f"{name:<12s} {load_scene(name).description}\n")
    return 0


def _cmd_modes(args):
    import numpy as np

    from .assembly import FrequencyModel
    from .scenes import load_scene
    scene = load_scene(args.scene)
    if args.pose is not None:
        eq = scene.robot.equilibrium(pose=args.pose)
    elif args.lengths is not None:
        eq = scene.robot.equilibrium(unstretched_lengths=args.lengths)
    else:
        eq = scene.equilibrium()
    n = args.n if args.n is not None else (None if args.fmax else (scene.n_modes or 20))
    df = FrequencyModel(eq).modes(n_modes=n, fmax_hz=args.fmax).to_frame()
    if args.csv:
        df.to_csv(args.csv, index=False)
    if args.json:
        df.to_json(args.json, orient="records", indent=1)
    cols = ["mode", "freq [Hz]", "kind", "cable energy fraction [-]", "massless freq [Hz]",
            "shift from massless [-]"]
    with np.printoptions(suppress=True):
        sys.stdout.write(df[cols].to_string(index=False, float_format=lambda x: f"{x:.6g}"))
    sys.stdout.write("\n")
    return 0


def build_parser():
    """The argument parser of the ``dynstiff`` command."""
    parser = argparse.ArgumentParser(
        prog="dynstiff",
        description="Vibration analysis of cable-driven parallel robots with sagging cables.")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser(
        "demo", help="single-cable report on the built-in CoGiRo cable: statics, fixed-end "
                     "frequencies, dynamic stiffness plot")
    demo.add_argument("--out", default="dynstiff-demo", help="output folder (default %(default)s)")
    demo.add_argument("--fmax", type=float, default=12.0, help="band upper end [Hz]")
    demo.add_argument("--points", type=int, default=4000, help="number of frequencies")
    demo.set_defaults(func=_cmd_demo)
    sc = sub.add_parser("scenes", help="list the built-in scenes")
    sc.set_defaults(func=_cmd_scenes)
    mo = sub.add_parser("modes", help="eigenfrequencies with global/local labels and energy "
                                      "fractions (Wittrick-Williams: none missed)")
    mo.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    grp = mo.add_mutually_exclusive_group()
    grp.add_argument("--pose", type=float, nargs="+", metavar="X",
                     help="platform pose: x y z [m] (and rx ry rz [rad]); inverse statics")
    grp.add_argument("--lengths", type=float, nargs="+", metavar="L0",
                     help="unstretched cable lengths [m]; forward statics")
    mo.add_argument("--fmax", type=float, help="all modes below this frequency [Hz]")
    mo.add_argument("-n", type=int, help="number of modes (default: the scene's n_modes)")
    mo.add_argument("--csv", help="write the full table (shapes included) to this CSV file")
    mo.add_argument("--json", help="write the full table to this JSON file")
    mo.set_defaults(func=_cmd_modes)
    return parser


def main(argv=None):
    """Entry point; returns the process exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except (DynstiffError, FileNotFoundError) as exc:
        sys.stderr.write(f"dynstiff: error: {exc}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
