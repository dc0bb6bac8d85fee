"""Subcommands that talk to other tools: ``import-caspr`` and ``calibrate``.

Added to the ``dynstiff`` parser by :func:`add_parsers`; errors are DynstiffError and are
reported on one line by :func:`dynstiff.cli.main`.
"""

import sys
import warnings

from dynstiff._text import counted
from dynstiff.cli.common import save_figure, table_metadata, write_tables
from dynstiff.cli.options import (
    MEANINGS,
    PARAMETERS,
    add_max_modes,
    add_model,
    add_outputs,
    add_pose,
    add_quiet,
    add_scene,
)

__all__ = ["add_parsers"]


def _out(path, text):
    if path == "-":
        sys.stdout.write(text)
    else:
        from dynstiff.io.files import write_text
        write_text(path, text)


def cmd_import_caspr(args):
    """``dynstiff import-caspr BODIES CABLES --mass-per-length M --EA EA --out FILE``."""

    from dynstiff.io.caspr import InertiaConventionWarning
    from dynstiff.io.files import check_paths
    from dynstiff.params import Cable
    from dynstiff.scenes.caspr import caspr_comments, caspr_siblings, import_caspr
    from dynstiff.scenes.writer import scene_text
    cable = Cable(mass_per_length=args.mass_per_length, EA=args.EA)
    traj, ops = args.trajectories, args.operational_spaces
    if not args.no_siblings:                 # CASPR's other files beside the bodies file
        found = caspr_siblings(args.bodies)
        traj = traj or found[0]
        ops = ops or found[1]
    check_paths([("bodies", args.bodies), ("cables", args.cables), ("--trajectories", traj),
                 ("--operational-spaces", ops)], [("--out", args.out)])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", InertiaConventionWarning)
        scene = import_caspr(args.bodies, args.cables, cable, cable_set=args.cable_set,
                             inertia_convention=args.inertia_convention, name=args.name,
                             min_tension=args.min_tension, trajectories_xml=traj,
                             operational_spaces_xml=ops)
    for w in caught:
        sys.stderr.write(f"dynstiff: warning: {w.message}\n")
    kinds = scene.study.get("caspr_trajectory_kinds", {})
    text = scene_text(scene.robot, scene.pose, name=scene.name, description=scene.description,
                      comments=caspr_comments(scene, args.bodies, args.cables, traj, ops),
                      cable_names=[f"CASPR {n!r}" for n in scene.study["caspr_cable_names"]],
                      trajectories=scene.trajectories.values(),
                      workspace_box=scene.workspace_box,
                      trajectory_notes={k: f"CASPR {v}" for k, v in kinds.items()})
    _out(args.out, text)
    info = sys.stderr if args.out == "-" else sys.stdout
    r = scene.robot
    info.write(f"{scene.name}: {counted(r.n_cables, 'cable')}, platform "
               f"{r.platform.mass:g} kg, free {' '.join(r.platform.free_dofs)}, pose "
               f"{scene.pose.position.tolist()} m, "
               f"tensions {r.tension_limits[0]:g}-{r.tension_limits[1]:g} N, inertia "
               f"convention {args.inertia_convention!r}\n")
    if scene.workspace_box is not None:
        info.write(f"workspace box (q_min, q_max): {list(scene.workspace_box)} m\n")
    if traj is not None:
        info.write(f"trajectories from {traj}: " + (", ".join(
            f"{k} ({p.law}, {p.times.size} waypoints, {p.duration:g} s)"
            for k, p in scene.trajectories.items()) or "none") + "\n")
        for tid, why in scene.study["caspr_skipped_trajectories"]:
            info.write(f"trajectory {tid!r} not read: {why}\n")
    if ops is not None:
        sets = scene.study["caspr_operational_sets"]
        info.write(f"operational spaces from {ops}: " + (", ".join(
            f"{k} ({len(v)} marker{'s' if len(v) != 1 else ''})" for k, v in sets.items())
            or "no operational set") + " (markers, no bounds)\n")
    if args.out != "-":
        info.write(f"wrote {args.out}\n")
    return 0


def cmd_calibrate(args):
    """``dynstiff calibrate SCENE --measured FILE --parameter EA [...]``."""
    from dynstiff.analyses.calibrate import calibrate
    from dynstiff.analyses.measured import read_measured_modes
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    measured = read_measured_modes(args.measured)
    from dynstiff.cli.common import info as report_stream
    from dynstiff.cli.console import elapsed
    from dynstiff.robot.pose import as_pose
    pose = as_pose(args.pose) if args.pose is not None else None
    with elapsed(f"calibrate {scene.name}", args.quiet):
        res = calibrate(scene, measured, parameters=tuple(args.parameter), pose=pose,
                        rung=args.model, confidence=args.confidence,
                        max_modes=args.max_modes)
    info = report_stream(args)
    info.write(f"{scene.name}: {len(measured)} measured modes, {args.model} model, "
               f"{res.n_evaluations} evaluations\n")
    info.write(res.text())
    where = pose if pose is not None else scene.pose
    write_tables(args, res.to_frame(), table_metadata(
        scene.name, where, args.model, measured=str(args.measured),
        parameters=list(args.parameter), confidence=args.confidence))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        save_figure(res.plot(), args.plot)
    for name in (args.csv, args.json, args.plot):
        if name and name != "-":
            info.write(f"wrote {name}\n")
    return 0


def add_parsers(sub):
    """Add ``import-caspr`` and ``calibrate`` to the subparsers ``sub``."""
    ic = sub.add_parser("import-caspr", help="write a scene file from CASPR's XML model files "
                                             "(single rigid body)")
    ic.add_argument("bodies", help="CASPR *_bodies.xml")
    ic.add_argument("cables", help="CASPR *_cables.xml")
    ic.add_argument("--mass-per-length", type=float, required=True,
                    help=f"{PARAMETERS['mass_per_length']} (CASPR holds none)")
    ic.add_argument("--EA", type=float, required=True,
                    help=f"{PARAMETERS['EA']} (CASPR holds none)")
    ic.add_argument("--cable-set", help="cable set id (default: the file's default_cable_set)")
    ic.add_argument("--inertia-convention", default="products", choices=["products", "tensor"],
                    help="printed Ixy, Ixz, Iyz are products of inertia (default; tensor entry "
                         "= -value) or tensor entries (CASPR's code)")
    ic.add_argument("--min-tension", type=float, default=1.0,
                    help="least t_min [N] where CASPR's force_min is lower (default "
                         "%(default)s)")
    ic.add_argument("--trajectories", metavar="FILE",
                    help="CASPR *_trajectories.xml: its joint trajectories become the scene's "
                         "[[trajectories]] (default: the file beside BODIES, if any)")
    ic.add_argument("--operational-spaces", metavar="FILE",
                    help="CASPR *_operational_spaces.xml: its markers are listed in the "
                         "scene's header (default: the file beside BODIES, if any)")
    ic.add_argument("--no-siblings", action="store_true",
                    help="do not read the trajectories and operational-space files beside "
                         "BODIES")
    ic.add_argument("--name", help="scene name (default: the CASPR link's name)")
    ic.add_argument("--out", required=True, metavar="FILE",
                    help=MEANINGS["--out"] + ": the scene file ('-': standard output); its "
                         "cables are numbered from 0, as in every output")
    ic.set_defaults(func=cmd_import_caspr)
    ca = sub.add_parser("calibrate", help="fit EA, platform mass ... to measured natural "
                                          "frequencies; estimates with confidence intervals")
    add_scene(ca)
    ca.add_argument("--measured", required=True, metavar="FILE",
                    help="CSV of measured modes: 'freq [Hz]', optional 'sigma [Hz]' and "
                         "shape columns x y z rx ry rz")
    ca.add_argument("--parameter", action="append", required=True,
                    help=MEANINGS["--parameter"] + ": to fit (repeat for several): " + ", ".join(
                        f"{n} ({PARAMETERS[n]})" for n in ("EA", "mass", "t_min"))
                    + ", EA_<i> (cable i's, from 0), EA_* (each cable's), inertia, "
                      "loss_factor, viscous_damping (the last two need a 'damping ratio "
                      "[-]' column and a nonzero value in the scene)")
    add_pose(ca, lengths=False, what="of the measurement (default: the scene's pose)")
    add_model(ca, default="dsm")
    add_max_modes(ca, 2000)
    ca.add_argument("--confidence", type=float, default=0.95,
                    help="level of the intervals (default %(default)s)")
    add_outputs(ca, csv="the residual of every mode", json="the residual of every mode",
                plot="the relative error of every mode before and after the fit")
    add_quiet(ca)
    ca.set_defaults(func=cmd_calibrate)
