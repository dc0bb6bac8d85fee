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
    return parser


def main(argv=None):
    """Entry point; returns the process exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except DynstiffError as exc:
        sys.stderr.write(f"dynstiff: error: {exc}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
