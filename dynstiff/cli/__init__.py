"""Command-line interface: ``dynstiff`` (or ``python -m dynstiff``)."""

import argparse
import sys

from dynstiff.errors import DynstiffError


def _settings(scene, args):
    """The analysis settings of ``scene`` with the command line's overrides
    (:func:`dynstiff.analyses.settings.analysis_settings`, the one source of defaults)."""
    from dynstiff.analyses.settings import analysis_settings
    band = getattr(args, "band", None)
    fmax = getattr(args, "fmax", None)
    kw = {}
    if getattr(args, "command", None) == "check":
        kw = dict(forbidden_hz=tuple(band) if band else None, margin=args.margin,
                  model_rtol=args.rtol, participation=args.participation,
                  frf_limit=args.frf_limit)
        band = None
    elif band:
        kw["band_hz"] = tuple(band)
    elif fmax is not None and getattr(args, "command", None) in ("demo", "report", "frf"):
        from dynstiff.analyses.settings import DEFAULT_BAND_HZ
        lo = (scene.band_hz or DEFAULT_BAND_HZ)[0]
        kw["band_hz"] = (min(lo, 0.5 * fmax), fmax)
    if getattr(args, "model", None):
        kw["rung"] = args.model
    for name in ("segments", "n"):
        if getattr(args, name, None) is not None:
            kw["n_modes" if name == "n" else name] = getattr(args, name)
    return analysis_settings(scene, damping=getattr(args, "damping", None), **kw)


def _cmd_report(args):
    from dynstiff.report.robot import robot_report
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    settings = _settings(scene, args)
    text, files = robot_report(scene, args.out, settings=settings, n_points=args.points)
    _info(args).write(text)
    _info(args).write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


def _cmd_demo(args):
    if args.cable:
        from dynstiff.report.cable import cable_report, write_report
        rep = cable_report(fmax_hz=args.fmax or 12.0, n_points=args.points)
        files = write_report(rep, args.out)
        _info(args).write(rep.text())
    else:
        from dynstiff.report.robot import robot_report
        from dynstiff.scenes import load_scene
        scene = load_scene(args.scene)
        settings = _settings(scene, args)          # every input checked before any file
        text, files = robot_report(scene, args.out, settings=settings, n_points=args.points)
        _info(args).write(text)
    _info(args).write("\nwrote:\n" + "".join(f"  {f}\n" for f in files))
    return 0


class _ProgressBar:
    """A text progress bar on standard error: ``[#####.....] 5/10``."""

    def __init__(self, label, width=30, stream=None):
        self.label, self.width = label, width
        self.stream = stream or sys.stderr

    def __call__(self, done, total):
        n = int(round(self.width * done / total))
        self.stream.write(f"\r{self.label} [{'#' * n}{'.' * (self.width - n)}] {done}/{total}")
        if done == total:
            self.stream.write("\n")
        self.stream.flush()


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
    """The robot with one parameter changed: EA [N] of every cable, platform mass [kg], or
    the minimum tension t_min [N] of the tension distribution."""
    from dataclasses import replace

    from dynstiff.robot.robot import Robot
    cables, platform, limits = robot.cables, robot.platform, robot.tension_limits
    if name == "EA":
        cables = [replace(c, EA=value) for c in cables]
    elif name == "mass":
        platform = replace(platform, mass=value)
    elif name == "t_min":
        limits = (value, limits[1])
    return Robot(robot.anchors, robot.attachments, cables, platform, g=robot.g,
                 tension_limits=limits, name=robot.name)


def _cmd_sweep(args):
    import numpy as np

    from dynstiff.analyses.interaction import sweep
    from dynstiff.errors import InvalidParameterError
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    st = _settings(scene, args)
    robot = scene.robot
    bar = None if args.quiet else _ProgressBar(f"sweep {scene.name}")
    n_modes = None if args.fmax and args.n is None else st.n_modes
    given = [name for name in ("line", "path", "parameter") if getattr(args, name) is not None]
    if len(given) != 1:
        raise InvalidParameterError(
            f"give exactly one of --line, --path or --parameter, got {given or 'none'}")
    rot = scene.pose.rotation if scene.pose is not None else np.zeros(3)
    if args.line is not None:
        if args.steps < 2:
            raise InvalidParameterError(f"--steps must be >= 2, got {args.steps}")
        pts = np.linspace(args.line[:3], args.line[3:], args.steps)
        res = sweep(robot, poses=[np.concatenate([p, rot]) for p in pts], n_modes=n_modes,
                    fmax_hz=args.fmax, progress=bar, on_error="record")
    elif args.path is not None:
        res = sweep(robot, poses=_read_path(args.path, rot), n_modes=n_modes,
                    fmax_hz=args.fmax, progress=bar, on_error="record")
    else:
        if not args.values:
            raise InvalidParameterError("--parameter needs --values V1 V2 ...")
        pose = scene.pose if scene.pose is not None else scene.equilibrium().pose
        units = {"EA": "N", "mass": "kg", "t_min": "N"}

        def build(v):
            return _with_parameter(robot, args.parameter, v).equilibrium(pose=pose)
        res = sweep(None, build=build, values=args.values, n_modes=n_modes,
                    fmax_hz=args.fmax, progress=bar, on_error="record",
                    parameter=f"{args.parameter} [{units[args.parameter]}]")
    df = res.to_frame()
    if args.csv:
        _write_table(df, args.csv, "csv", st.metadata(units="Hz; value in " + res.parameter))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        from dynstiff.plot import plot_veering
        fig = plot_veering(res)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
    vt = res.veering_table()
    vt.insert(0, res.parameter, res.values)
    vt.columns = [vt.columns[0]] + [f"global {c} [Hz]" for c in vt.columns[1:]]
    _info(args).write(f"{st.rung} model, undamped natural frequencies ({st.damping.text()} "
                     f"applies to FRFs)\n")
    _info(args).write(f"{res.n_steps} steps, {res.n_tracks} global-mode tracks, "
                     f"{int(np.sum(res.kind == 'local'))} local modes listed\n")
    _info(args).write(vt.to_string(index=False, float_format=lambda x: f"{x:.5g}") + "\n")
    for k, v, msg in res.failures:
        _info(args).write(f"step {k} ({res.parameter} = {v:g}): infeasible, skipped: "
                         f"{msg.splitlines()[0]}\n")
    for name in (args.csv, args.plot):
        if name and name != "-":
            _info(args).write(f"wrote {name}\n")
    return 0


def _cmd_simulate(args):
    import warnings

    import numpy as np

    from dynstiff.analyses.eigen import eigenfrequencies
    from dynstiff.constants import DOF_NAMES
    from dynstiff.errors import InvalidParameterError
    from dynstiff.lumped import SlackSegmentWarning, simulate
    from dynstiff.models.ladder import build_model
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    eq = _equilibrium(scene, args)
    if args.to is not None:
        from dynstiff.timedomain.trajectory import line, track
        traj = line(eq.pose.position, args.to, args.speed, rotation=eq.pose.rotation,
                    ramp=args.ramp)
        bar = None if args.quiet else _ProgressBar("quasi-static lengths")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SlackSegmentWarning)
            tr = track(scene.robot, traj, segments=args.segments, dt=args.dt,
                       settle=args.time, progress=bar)
        resp = tr.response
        df = tr.to_frame()
        _info(args).write(
            f"line {np.round(traj.positions[0], 4).tolist()} -> {list(args.to)} m at "
            f"{args.speed:g} m/s (ramp {args.ramp:g} s), {args.segments} segments per "
            f"cable, dt = {args.dt:g} s: largest deviation from the quasi-static path "
            f"{tr.max_deviation:.4g} m ({100 * tr.relative_max_deviation:.3g} % of the mean "
            f"cable length)\n")
        if args.plot:
            import matplotlib
            matplotlib.use("Agg")
            from dynstiff.plot import plot_tracking
            fig = plot_tracking(tr)
            fig.tight_layout()
            fig.savefig(args.plot, dpi=120)
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
        resp = simulate(model, args.time, args.dt, initial=offset)
        df = resp.to_frame().reset_index()
        ch = args.channel or DOF_NAMES[fd[0]]
        sp = resp.spectrum(ch, prominence=_SPECTRUM_PROMINENCE)
        f_model = eigenfrequencies(model, fmax_hz=sp.freq_hz[-1] * 0.5)
        if args.band is not None:
            band = tuple(args.band)
            if not 0 <= band[0] < band[1]:
                raise InvalidParameterError(
                    f"--band must be LO HI with 0 <= LO < HI [Hz], got {list(args.band)}")
        else:
            band = scene.band_hz or (0.0, 1.5 * float(f_model[min(7, f_model.size - 1)]))
        _info(args).write(
            f"free vibration from offset {offset.tolist()}, {args.time:g} s, dt = "
            f"{args.dt:g} s, {args.segments} segments per cable (damping: the cables' own, "
            f"time domain): wall {resp.wall_time:.3g} s, "
            f"energy residual {np.abs(resp.energy.relative_residual).max():.2e}\n")
        peaks = np.sort(sp.peaks_hz[(sp.peaks_hz >= band[0]) & (sp.peaks_hz <= band[1])][:8])
        inband = f_model[(f_model >= band[0]) & (f_model <= band[1])]
        near = [f_model[int(np.argmin(np.abs(f_model - f)))] if f_model.size else np.nan
                for f in peaks]
        _info(args).write(
            f"spectrum peaks of {ch} in {band[0]:g}-{band[1]:g} Hz (Hann window, "
            f"resolution {sp.resolution_hz:.3g} Hz, prominence >= "
            f"{_SPECTRUM_PROMINENCE:.0%} of the largest), each with the nearest linearised "
            f"mode:\n" + "".join(f"  {f:.4g} Hz ~ mode {m:.4g} Hz ({f - m:+.3g} Hz)\n"
                                 for f, m in zip(peaks, near)))
        _info(args).write(f"linearised lumped-model frequencies in the band [Hz] "
                         f"({inband.size}): " + ", ".join(f"{f:.4g}" for f in inband[:8])
                         + (", ..." if inband.size > 8 else "") + "\n")
        if args.plot:
            import matplotlib
            matplotlib.use("Agg")
            from dynstiff.plot import plot_spectrum
            fig = plot_spectrum(sp, modes=f_model, band_hz=band)
            fig.tight_layout()
            fig.savefig(args.plot, dpi=120)
    if args.csv:
        from dynstiff._version import __version__
        _write_table(df, args.csv, "csv", {
            "dynstiff": __version__, "scene": scene.name, "model": "lumped",
            "segments": args.segments, "dt [s]": args.dt,
            "pose": {"position [m]": [float(v) for v in eq.pose.position],
                     "rotation [rad]": [float(v) for v in eq.pose.rotation]},
            "damping": "the cables' own (time domain)", "units": "SI, in the column names"})
    for name in (args.csv, args.plot):
        if name and name != "-":
            _info(args).write(f"wrote {name}\n")
    return 0


#: Smallest prominence of a reported spectrum peak, relative to the largest [-]: above the
#: Hann window's highest side lobe (2.7 % of the main lobe), so leakage is not reported.
_SPECTRUM_PROMINENCE = 0.03


def _cmd_scenes(args):
    from dynstiff.scenes import list_scenes, load_scene
    for name in list_scenes():
        _info(args).write(f"{name:<12s} {load_scene(name).description}\n")
    return 0


def _exact_model(eq, n_modes, fmax_hz):
    """The exact rung with a band that holds the request: 1.05 fmax_hz, or, for n_modes, a
    band doubled from 25 Hz until it holds them (theory.md §11)."""
    from dynstiff.analyses.eigen import mode_count
    from dynstiff.errors import InvalidParameterError
    from dynstiff.models.ladder import build_model
    if fmax_hz is not None:
        return build_model(eq, "exact", fmax_hz=1.05 * fmax_hz)
    band = 25.0
    while True:
        model = build_model(eq, "exact", fmax_hz=band)
        if mode_count(model, 2 * 3.141592653589793 * band)[0] >= n_modes:
            return model
        band *= 2.0
        if band > 1e4:
            raise InvalidParameterError(f"-n {n_modes}: more modes than the exact model holds "
                                        f"below 10 kHz")


def _cmd_modes(args):
    import numpy as np

    from dynstiff.analyses.eigen import modes
    from dynstiff.errors import InvalidParameterError
    from dynstiff.models.ladder import build_model
    from dynstiff.scenes import load_scene
    if args.segments is not None and args.segments < 1:
        raise InvalidParameterError(f"--segments must be >= 1, got {args.segments}")
    scene = load_scene(args.scene)
    st = _settings(scene, args)
    eq = _equilibrium(scene, args)
    n = None if args.fmax and args.n is None else st.n_modes
    args.model = st.rung
    args.segments = st.segments
    if st.rung == "exact":
        model = _exact_model(eq, n, args.fmax)
    else:
        model = build_model(eq, st.rung, segments=st.segments)
    note = ""
    if hasattr(model, "matrices") and n is not None and n > model.n_dof:
        note = f" (it has {model.n_dof} modes; {n} asked)"
        n = model.n_dof
    res = modes(model, n_modes=n, fmax_hz=args.fmax)
    if len(res) == 0:
        raise InvalidParameterError(f"no {args.model}-model mode below --fmax {args.fmax} Hz")
    from dynstiff.analyses.participation import platform_participation
    part = platform_participation(model, res, st.participation)
    df = res.to_frame()
    df.insert(3, "platform share [-]", part.platform_share)
    df.insert(4, "category", list(part.category))
    meta = st.metadata(eq.pose, units="Hz; shapes normalised to unit platform kinetic energy")
    _info(args).write(f"{args.model} model")
    _info(args).write(f", {args.segments} segments per cable" if args.model == "lumped"
                     else "")
    _info(args).write(f"{note} (undamped natural frequencies; {st.damping.text()}):\n")
    if args.csv:
        _write_table(df, args.csv, "csv", meta)
    if args.json:
        _write_table(df, args.json, "json", meta)
    cols = [c for c in ("mode", "freq [Hz]", "kind", "platform share [-]", "category",
                        "massless freq [Hz]", "shift from massless [-]") if c in df.columns]
    with np.printoptions(suppress=True):
        _info(args).write(df[cols].to_string(index=False, float_format=lambda x: f"{x:.6g}"))
    _info(args).write("\n")
    return 0


def _equilibrium(scene, args):
    if getattr(args, "pose", None) is not None:
        return scene.robot.equilibrium(pose=args.pose)
    if getattr(args, "lengths", None) is not None:
        # held DOFs keep the values of the start pose: the scene's, when it has one
        start = scene.pose
        if start is None and len(scene.robot.platform.free_dofs) < 6:
            from dynstiff.errors import InvalidParameterError
            raise InvalidParameterError(
                f"--lengths: scene {scene.name!r} holds DOFs but gives no [pose] to hold them "
                f"at; give --pose instead, or a [pose] position in the scene file")
        return scene.equilibrium(unstretched_lengths=args.lengths, initial_pose=start)
    return scene.equilibrium()


def _cmd_frf(args):
    import numpy as np

    from dynstiff.analyses.eigen import modes
    from dynstiff.analyses.freqgrid import refined_grid
    from dynstiff.analyses.frf import frf
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    st = _settings(scene, args)
    lo, hi = st.band_hz
    eq = _equilibrium(scene, args)
    model = st.model(eq)
    marks = modes(model, fmax_hz=hi)
    f = refined_grid((lo, hi), args.points, marks.freq_hz)
    res = frf(model, 2 * np.pi * f, inputs=args.source, outputs=args.to, point=args.point,
              kind=args.kind)
    df = res.to_frame()
    if args.csv:
        _write_table(df, args.csv, "csv", st.metadata(eq.pose, units="in the unit column"))
    if args.uff:
        res.to_uff(args.uff)
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        from dynstiff.plot import plot_frf
        fig = plot_frf(res, marks, pairs=[(o, i) for o in res.outputs for i in res.inputs])
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
    h = np.abs(res.H[:, 0, 0])
    k = int(np.argmax(h))
    _info(args).write(f"{res.kind} {res.outputs[0]}/{res.inputs[0]}: {len(f)} frequencies "
                     f"{lo:g}-{hi:g} Hz ({args.points} uniform, refined at {len(marks)} "
                     f"modes), largest |H| = {h[k]:.4g} at {f[k]:.5g} Hz\n"
                     f"{st.rung} model; {st.damping.text()}\n"
                     + ("" if model.damped else "undamped model: |H| is unbounded at every "
                        "mode, the largest value is the grid's, not a peak\n"))
    for name in (args.csv, args.plot, args.uff):
        if name and name != "-":
            _info(args).write(f"wrote {name}\n")
    return 0


def _cmd_check(args):
    from dynstiff.analyses.checks import design_checks
    from dynstiff.scenes import load_scene
    scene = load_scene(args.scene)
    st = _settings(scene, args)
    pose = args.pose if args.pose is not None else scene.pose
    if pose is None:
        pose = scene.equilibrium().pose
    band = st.forbidden_hz
    res = design_checks(scene.robot, pose, proximity_rtol=args.proximity,
                        max_sag_ratio=args.max_sag, **st.check_options())
    _info(args).write("\n".join(st.lines()) + "\n")
    if band is None:
        _info(args).write("(no forbidden band: give --band LO HI or forbidden_band_hz in the "
                         "scene's [analysis])\n")
    _info(args).write(res.text())
    if args.csv:
        from dynstiff.robot.robot import Pose
        _write_table(res.to_frame(), args.csv, "csv",
                     st.metadata(Pose(pose[:3], pose[3:]) if len(pose) == 6 else
                                 (pose if hasattr(pose, "position") else None)))
    return 0 if res.passed else 1


def build_parser():
    """The argument parser of the ``dynstiff`` command."""
    parser = _Parser(
        prog="dynstiff",
        description="Vibration analysis of cable-driven parallel robots with sagging cables.")
    parser.add_argument("--debug", action="store_true",
                        help="show the full traceback of an error")
    from dynstiff._version import __version__
    parser.add_argument("--version", action="version", version=f"dynstiff {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
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
    _damping_option(demo)
    demo.set_defaults(func=_cmd_demo)
    rp = sub.add_parser("report", help="the demo's analysis of one scene: tables, figures and "
                                       "a self-contained report.html")
    rp.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    rp.add_argument("--out", default="dynstiff-report", help="output folder")
    rp.add_argument("--fmax", type=float, help="band upper end [Hz] (default: the scene's)")
    rp.add_argument("--points", type=int, default=3000,
                    help="uniform frequencies of the FRFs, refined around every mode")
    _damping_option(rp)
    rp.set_defaults(func=_cmd_report)
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
    mo.add_argument("--model", choices=["dsm", "exact", "lumped", "catenary", "spring"],
                    help="cable model (default: the scene's, else dsm): closed-form dynamic "
                         "stiffness, the exact cable about its true catenary, lumped masses "
                         "(--segments), or massless cables with the catenary's or the "
                         "straight spring's stiffness (platform modes only)")
    mo.add_argument("--segments", type=int,
                    help="segments per cable of the lumped model (default: the scene's, "
                         "else 30)")
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
    fr.add_argument("--points", type=int, default=4000,
                    help="uniform frequencies, refined around every mode in the band")
    _damping_option(fr)
    fr.add_argument("--plot", help="write a figure (PNG) with the modes marked")
    fr.add_argument("--csv", help="write the tidy FRF table (CSV)")
    fr.add_argument("--uff", help="write the FRFs as UFF 58 records (needs dynstiff[exchange])")
    fr.set_defaults(func=_cmd_frf)
    ck = sub.add_parser("check", help="design checks with a pass/fail report; exit code 1 if "
                                      "any check fails")
    ck.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    ck.add_argument("--pose", type=float, nargs="+", metavar="X")
    ck.add_argument("--band", type=float, nargs=2, metavar=("LO", "HI"),
                    help="forbidden band for global modes [Hz] (default: the scene's "
                         "forbidden_band_hz)")
    ck.add_argument("--rtol", type=float,
                    help="admissible frequency error of the cable model (default: the "
                         "scene's model_rtol, else 0.01)")
    ck.add_argument("--margin", type=float,
                    help="relative margin of the platform modes to the band (default 0.05)")
    ck.add_argument("--participation", type=float,
                    help="platform share of a mode's kinetic energy from which it is held to "
                         "the margin (default 0.05)")
    ck.add_argument("--frf-limit", type=float,
                    help="largest admissible receptance / static value in the band "
                         "(default 10)")
    _damping_option(ck)
    ck.add_argument("--proximity", type=float, default=0.03,
                    help="relative distance local-global mode that fails (default %(default)s)")
    ck.add_argument("--max-sag", type=float, default=0.02,
                    help="largest admissible sag/chord (default %(default)s)")
    ck.add_argument("--csv", help="write the checks table (CSV)")
    ck.set_defaults(func=_cmd_check)
    sw = sub.add_parser("sweep", help="modes along a straight path or over a parameter, global "
                                      "modes tracked; table and veering diagram")
    sw.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    sw.add_argument("--line", type=float, nargs=6, metavar=("X0", "Y0", "Z0", "X1", "Y1", "Z1"),
                    help="path of P from (X0, Y0, Z0) to (X1, Y1, Z1) [m], the scene's rotation")
    sw.add_argument("--steps", type=int, default=11,
                    help="poses along --line (default %(default)s)")
    sw.add_argument("--path", metavar="FILE",
                    help="poses from a text/CSV file, one a line: x y z [m] (the scene's "
                         "rotation) or x y z rx ry rz [m, rad]; '#' comments, a header line")
    sw.add_argument("--parameter", choices=["EA", "mass", "t_min"],
                    help="sweep a parameter at the scene's pose: EA of every cable [N], "
                         "platform mass [kg], minimum tension [N]")
    sw.add_argument("--values", type=float, nargs="+", metavar="V", help="parameter values")
    sw.add_argument("-n", type=int, help="modes per step (default: the scene's n_modes)")
    sw.add_argument("--fmax", type=float, help="all modes below this frequency [Hz]")
    sw.add_argument("--csv", help="write the tidy table (one row per mode and step)")
    sw.add_argument("--plot", help="write the veering diagram (PNG)")
    sw.add_argument("--quiet", action="store_true", help="no progress bar")
    sw.set_defaults(func=_cmd_sweep)
    si = sub.add_parser("simulate", help="time domain (lumped-mass cables): free vibration "
                                         "from an offset, or a line commanded through "
                                         "quasi-static cable lengths")
    si.add_argument("scene", help="built-in scene name or path to a TOML scene file")
    grp = si.add_mutually_exclusive_group()
    grp.add_argument("--pose", type=float, nargs="+", metavar="X")
    grp.add_argument("--lengths", type=float, nargs="+", metavar="L0")
    si.add_argument("--time", type=float, default=5.0,
                    help="duration [s] (after the path's end with --to; default %(default)s)")
    si.add_argument("--dt", type=float, default=2e-3, help="time step [s] (default %(default)s)")
    si.add_argument("--segments", type=int, default=10, help="segments per cable")
    si.add_argument("--offset", type=float, nargs="+", metavar="D",
                    help="initial platform offset dx dy dz [m] drx dry drz [rad] (default "
                         "1 mm along the first free DOF)")
    si.add_argument("--band", type=float, nargs=2, metavar=("LO", "HI"),
                    help="band of the spectrum [Hz] (default: the scene's band)")
    si.add_argument("--channel", choices=["x", "y", "z", "rx", "ry", "rz"],
                    help="channel of the spectrum (default: the first free DOF)")
    si.add_argument("--to", type=float, nargs=3, metavar=("X", "Y", "Z"),
                    help="move P in a straight line to this point [m] instead")
    si.add_argument("--speed", type=float, default=0.5, help="path speed [m/s]")
    si.add_argument("--ramp", type=float, default=1.0, help="speed ramp duration [s]")
    si.add_argument("--csv", help="write the time history (CSV)")
    si.add_argument("--plot", help="write the spectrum with the model's frequencies (PNG)")
    si.add_argument("--quiet", action="store_true", help="no progress bar")
    si.set_defaults(func=_cmd_simulate)
    from dynstiff.cli.exchange import add_commands
    add_commands(sub)
    from dynstiff.cli.workspace import add_workspace_parser
    add_workspace_parser(sub)
    return parser


def _damping_option(p):
    p.add_argument("--damping", type=float, nargs="+", metavar="V",
                   help="ZETA_P [ETA_C [C]]: platform modal damping ratio, cable loss factor "
                        "(all cable motions), cable viscous damping [N s/m^2]; values not "
                        "given keep the scene's [damping] (defaults 0.01 0.01 0); "
                        "--damping 0 0 0: undamped")


def main(argv=None):
    """Entry point; returns the process exit code: 0 done (``check``: all passed), 1 a check
    failed, 2 an error, reported on one line (``--debug`` shows the traceback)."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except _UsageError as exc:
        sys.stderr.write(f"dynstiff: error: {exc} (dynstiff -h, or dynstiff COMMAND -h)\n")
        return 2
    try:
        _check_outputs(args)
        return args.func(args)
    except BrokenPipeError:             # output piped into e.g. `head`: stop quietly
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except (DynstiffError, OSError, UnicodeDecodeError, MemoryError) as exc:
        if args.debug:
            raise
        what = f"{type(exc).__name__}: " if isinstance(exc, (UnicodeDecodeError,
                                                             MemoryError)) else ""
        sys.stderr.write(f"dynstiff: error: {what}{exc}\n")
        return 2


class _UsageError(Exception):
    """A command line argparse rejects (one line instead of the usage block)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise _UsageError(f"{self.prog}: {message}")


#: Figure formats accepted by ``--plot`` (matplotlib's raster and vector writers).
_FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff",
                    ".webp")


def _check_outputs(args):
    """Refuse an output path before any work: a folder, a missing folder, or a figure format
    matplotlib does not write. ``-`` (``--csv``, ``--json``) is standard output."""
    from pathlib import Path

    from dynstiff.errors import InvalidParameterError
    for opt in ("csv", "json", "plot", "uff"):
        value = getattr(args, opt, None)
        if value is None or (value == "-" and opt not in ("plot", "uff")):
            continue
        p = Path(value)
        if p.is_dir():
            raise InvalidParameterError(f"--{opt} {value}: is a folder; give a file name")
        if not p.parent.is_dir():
            raise InvalidParameterError(f"--{opt} {value}: folder {str(p.parent)!r} does not "
                                        f"exist")
        if opt == "plot" and p.suffix.lower() not in _FIGURE_SUFFIXES:
            raise InvalidParameterError(
                f"--plot {value}: the file name must end in one of {_FIGURE_SUFFIXES}")
    for opt in ("points", "steps", "segments", "n"):
        value = getattr(args, opt, None)
        least = 2 if opt in ("points", "steps") else 1
        if value is not None and value < least:
            raise InvalidParameterError(f"{'-n' if opt == 'n' else '--' + opt} must be >= {least}, "
                                        f"got {value}")
    for opt in ("fmax", "time", "dt", "speed", "rtol", "proximity", "max_sag",
                "participation", "frf_limit"):
        value = getattr(args, opt, None)
        if value is not None and not (value > 0 and value < float("inf")):
            raise InvalidParameterError(
                f"--{opt.replace('_', '-')} must be finite and > 0, got {value}")
    band = getattr(args, "band", None)
    if band is not None and not (0 <= band[0] < band[1] < float("inf")):
        raise InvalidParameterError(f"--band must be LO HI with 0 <= LO < HI [Hz], got "
                                    f"{band[0]} {band[1]}")
    pose = getattr(args, "pose", None)
    if pose is not None and len(pose) not in (3, 6):
        raise InvalidParameterError(
            f"--pose needs 3 numbers (x y z [m]) or 6 (and rx ry rz [rad]), got {len(pose)}: "
            f"{pose}")


def _info(args):
    """Stream of a command's report: standard output, or standard error when a table goes
    to standard output (``--csv -`` / ``--json -``), so that the data stays clean."""
    to_stdout = "-" in (getattr(args, "csv", None), getattr(args, "json", None))
    return sys.stderr if to_stdout else sys.stdout


def _write_table(df, path, kind, metadata=None):
    """Write ``df`` as CSV or JSON to ``path`` (``-``: standard output). With
    ``metadata`` (a dict: scene, pose, model, damping, units, version): CSV gets a header of
    ``# key: value`` lines (``pandas.read_csv(path, comment="#")``), JSON is
    ``{"metadata": {...}, "data": [records]}``."""
    import json
    if kind == "csv":
        text = df.to_csv(index=False)
        if metadata:
            text = "".join(f"# {k}: {json.dumps(v)}\n" for k, v in metadata.items()) + text
    else:
        text = df.to_json(orient="records", indent=1)
        if metadata:
            text = json.dumps({"metadata": metadata, "data": json.loads(text)}, indent=1)
    if path == "-":
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
    else:
        with open(path, "w") as fh:
            fh.write(text)


if __name__ == "__main__":
    sys.exit(main())
