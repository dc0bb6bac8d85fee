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
    eq = _equilibrium(scene, args)
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


def _equilibrium(scene, args):
    if getattr(args, "pose", None) is not None:
        return scene.robot.equilibrium(pose=args.pose)
    if getattr(args, "lengths", None) is not None:
        return scene.robot.equilibrium(unstretched_lengths=args.lengths)
    return scene.equilibrium()


def _cmd_frf(args):
    import numpy as np

    from .assembly import FrequencyModel
    from .scenes import load_scene
    scene = load_scene(args.scene)
    model = FrequencyModel(_equilibrium(scene, args))
    lo, hi = args.band if args.band else (scene.band_hz or (0.1, 20.0))
    if not 0 <= lo < hi:
        from .errors import InvalidParameterError
        raise InvalidParameterError(f"--band must be LO HI with 0 <= LO < HI [Hz], got {lo} {hi}")
    f = np.linspace(lo, hi, args.points)
    res = model.frf(2 * np.pi * f, inputs=args.source, outputs=args.to, point=args.point,
                    kind=args.kind)
    df = res.to_frame()
    if args.csv:
        df.to_csv(args.csv, index=False)
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        from .plot import plot_frf
        modes = model.modes(fmax_hz=hi)
        fig = plot_frf(res, modes, pairs=[(o, i) for o in res.outputs for i in res.inputs])
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
    h = np.abs(res.H[:, 0, 0])
    k = int(np.argmax(h))
    sys.stdout.write(f"{res.kind} {res.outputs[0]}/{res.inputs[0]}: {len(f)} frequencies "
                     f"{lo:g}-{hi:g} Hz, largest |H| = {h[k]:.4g} at {f[k]:.5g} Hz\n")
    for name in (args.csv, args.plot):
        if name:
            sys.stdout.write(f"wrote {name}\n")
    return 0


def _cmd_check(args):
    from .checks import design_checks
    from .scenes import load_scene
    scene = load_scene(args.scene)
    pose = args.pose if args.pose is not None else scene.pose
    if pose is None:
        pose = scene.equilibrium().pose
    band = tuple(args.band) if args.band else scene.band_hz
    res = design_checks(scene.robot, pose, band_hz=band, margin=args.margin,
                        proximity_rtol=args.proximity, max_sag_ratio=args.max_sag)
    sys.stdout.write(res.text())
    if args.csv:
        res.to_frame().to_csv(args.csv, index=False)
    return 0 if res.passed else 1


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
    fr = sub.add_parser("frf", help="frequency response functions of the platform")
    fr.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    grp = fr.add_mutually_exclusive_group()
    grp.add_argument("--pose", type=float, nargs="+", metavar="X")
    grp.add_argument("--lengths", type=float, nargs="+", metavar="L0")
    fr.add_argument("--from", dest="source", nargs="+", default=["fz"],
                    choices=["fx", "fy", "fz", "mx", "my", "mz"], help="load channel(s)")
    fr.add_argument("--to", nargs="+", default=["z"], choices=["x", "y", "z", "rx", "ry", "rz"],
                    help="response channel(s)")
    fr.add_argument("--point", type=float, nargs=3, metavar=("X", "Y", "Z"),
                    help="platform point whose translation is output [m, platform frame]")
    fr.add_argument("--kind", default="receptance",
                    choices=["receptance", "mobility", "accelerance"])
    fr.add_argument("--band", type=float, nargs=2, metavar=("LO", "HI"),
                    help="frequency band [Hz] (default: the scene's band)")
    fr.add_argument("--points", type=int, default=4000, help="number of frequencies")
    fr.add_argument("--plot", help="write a figure (PNG) with the modes marked")
    fr.add_argument("--csv", help="write the tidy FRF table (CSV)")
    fr.set_defaults(func=_cmd_frf)
    ck = sub.add_parser("check", help="design checks with a pass/fail report; exit code 1 if "
                                      "any check fails")
    ck.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    ck.add_argument("--pose", type=float, nargs="+", metavar="X")
    ck.add_argument("--band", type=float, nargs=2, metavar=("LO", "HI"),
                    help="forbidden band for global modes [Hz] (default: the scene's band)")
    ck.add_argument("--margin", type=float, default=0.05,
                    help="relative margin of global modes to the band (default %(default)s)")
    ck.add_argument("--proximity", type=float, default=0.03,
                    help="relative distance local-global mode that fails (default %(default)s)")
    ck.add_argument("--max-sag", type=float, default=0.02,
                    help="largest admissible sag/chord (default %(default)s)")
    ck.add_argument("--csv", help="write the checks table (CSV)")
    ck.set_defaults(func=_cmd_check)
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
    except BrokenPipeError:             # output piped into e.g. `head`: stop quietly
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(main())
