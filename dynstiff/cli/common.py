"""What every command shares: the analysis settings of a scene with the command line's
overrides, the equilibrium asked for, the checks of output paths and options made before any
work, the report stream, the tables (one metadata header, one column naming) and figures."""

import sys

from dynstiff.cli.console import ProgressBar

__all__ = ["FIGURE_SUFFIXES", "INPUT_ARGS", "OUTPUT_ARGS", "ProgressBar", "check_outputs",
           "damping_option", "equilibrium", "file_arguments", "info", "pose_metadata",
           "refuse_unused", "save_figure", "scene_settings", "scene_trajectory", "table_metadata",
           "write_table", "write_tables"]


def scene_settings(scene, args):
    """The analysis settings of ``scene`` with the command line's overrides
    (:func:`dynstiff.analyses.settings.analysis_settings`, the one source of defaults)."""
    from dynstiff.analyses.settings import analysis_settings
    band = getattr(args, "band", None)
    fmax = getattr(args, "fmax", None)
    kw = {}
    forbidden = getattr(args, "forbidden_band", None)
    if forbidden:
        kw["forbidden_hz"] = tuple(forbidden)
    for name in ("margin", "participation", "frf_limit"):
        if getattr(args, name, None) is not None:
            kw[name] = getattr(args, name)
    if getattr(args, "rtol", None) is not None:
        kw["model_rtol"] = args.rtol
    if band:
        kw["band_hz"] = tuple(band)
    elif fmax is not None:
        from dynstiff.analyses.settings import DEFAULT_BAND_HZ
        lo = (scene.band_hz or DEFAULT_BAND_HZ)[0]
        kw["band_hz"] = (min(lo, 0.5 * fmax), fmax)
    if getattr(args, "model", None):
        kw["rung"] = args.model
    for name in ("segments", "n"):
        if getattr(args, name, None) is not None:
            kw["n_modes" if name == "n" else name] = getattr(args, name)
    st = analysis_settings(scene, damping=getattr(args, "damping", None), **kw)
    if getattr(args, "segments", None) is not None and st.rung != "lumped":
        from dynstiff.errors import InvalidParameterError
        raise InvalidParameterError(f"--segments applies to the lumped model only (--model "
                                    f"lumped), not to the {st.rung!r} model")
    return st


def refuse_unused(args, options, why):
    """One line naming the options given (not left at None) that ``why`` leaves unused:
    an option given is never silently ignored. Each option is looked up under argparse's
    name for it (leading dashes dropped, inner dashes as underscores)."""
    from dynstiff.errors import InvalidParameterError
    given = [o for o in options if getattr(args, o.lstrip("-").replace("-", "_"), None)
             is not None]
    if given:
        raise InvalidParameterError(f"{', '.join(given)} {'does' if len(given) == 1 else 'do'}"
                                    f" not apply {why}")


def equilibrium(scene, args):
    """The equilibrium of ``--pose`` or ``--lengths`` (or the scene's own):
    :func:`dynstiff.analyses.settings.scene_equilibrium`."""
    from dynstiff.analyses.settings import scene_equilibrium
    return scene_equilibrium(scene, getattr(args, "pose", None), getattr(args, "lengths", None))


def damping_option(p):
    p.add_argument("--damping", type=float, nargs="+", metavar="V",
                   help="damping ZETA_P [ETA_C [C]]: platform modal damping ratio, cable loss "
                        "factor "
                        "(all cable motions), cable viscous damping [N s/m^2]; values not "
                        "given keep the scene's [damping] (defaults 0.01 0.01 0); "
                        "--damping 0 0 0: undamped")


#: Figure formats accepted by ``--plot`` (matplotlib's raster and vector writers).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff",
                    ".webp")


#: The parsed arguments (attribute names) that name files a command reads ...
INPUT_ARGS = ("scene", "measured", "bodies", "cables", "trajectories", "operational_spaces",
              "orientations", "path")
#: ... and those that name files (or folders) it writes.
OUTPUT_ARGS = ("out", "csv", "json", "plot", "uff")


def file_arguments(args):
    """The (option, path) pairs of the files a command reads and of those it writes, from
    the parsed arguments named in :data:`INPUT_ARGS` and :data:`OUTPUT_ARGS` (a scene given
    by a built-in name is no file and is left out)."""
    import os

    def pairs(names):
        found = []
        for name in names:
            value = getattr(args, name, None)
            if isinstance(value, str) and value != "-":
                if name == "scene" and not os.path.exists(value):
                    continue
                found.append((name if name in ("scene", "bodies", "cables")
                              else "--" + name.replace("_", "-"), value))
        return found
    return pairs(INPUT_ARGS), pairs(OUTPUT_ARGS)


def check_outputs(args):
    """Refuse an output path before any work: one that is an input of the command or another
    of its outputs (the same file, also through links:
    :func:`dynstiff.io.files.check_paths`), a folder, a missing folder, or a figure format
    matplotlib does not write. ``-`` (``--csv``, ``--json``) is standard output."""
    from pathlib import Path

    from dynstiff.errors import InvalidParameterError
    from dynstiff.io.files import check_paths
    inputs, outputs = file_arguments(args)
    check_paths(inputs, outputs)
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
        if opt == "plot" and p.suffix.lower() not in FIGURE_SUFFIXES:
            raise InvalidParameterError(
                f"--plot {value}: the file name must end in one of {FIGURE_SUFFIXES}")
    for opt in ("points", "steps", "segments", "n", "max_modes"):
        value = getattr(args, opt, None)
        least = 2 if opt in ("points", "steps") else 1
        if value is not None and value < least:
            raise InvalidParameterError(f"{'-n' if opt == 'n' else '--' + opt.replace('_', '-')} "
                                        f"must be >= {least}, "
                                        f"got {value}")
    for opt in ("fmax", "time", "dt", "speed", "rtol", "proximity", "max_sag",
                "participation", "frf_limit"):
        value = getattr(args, opt, None)
        if value is not None and not (value > 0 and value < float("inf")):
            raise InvalidParameterError(
                f"--{opt.replace('_', '-')} must be finite and > 0, got {value}")
    for opt in ("band", "forbidden_band"):
        band = getattr(args, opt, None)
        if band is not None and not (0 <= band[0] < band[1] < float("inf")):
            raise InvalidParameterError(f"--{opt.replace('_', '-')} must be LO HI with 0 <= LO "
                                        f"< HI [Hz], got {band[0]} {band[1]}")
    pose = getattr(args, "pose", None)
    if pose is not None and len(pose) not in (3, 6):
        raise InvalidParameterError(
            f"--pose needs 3 numbers (x y z [m]) or 6 (and rx ry rz [rad]), got {len(pose)}: "
            f"{pose}")


def info(args):
    """Stream of a command's report: standard output, or standard error when a table goes
    to standard output (``--csv -`` / ``--json -``), so that the data stays clean."""
    to_stdout = "-" in (getattr(args, "csv", None), getattr(args, "json", None))
    return sys.stderr if to_stdout else sys.stdout


def pose_metadata(pose):
    """The pose of a table's header: position [m] and rotation [rad] (None: not one pose)."""
    if pose is None:
        return None
    return {"position [m]": [float(v) for v in pose.position],
            "rotation [rad]": [float(v) for v in pose.rotation]}


def table_metadata(scene, pose, model, **extra):
    """The header every table of the command line carries, in this order: ``dynstiff``
    (version), ``scene``, ``pose`` (position [m], rotation [rad]; a text where the table
    spans many poses), ``model``, ``date`` (UTC, ISO 8601), then ``extra``."""
    from dynstiff._version import __version__
    if pose is not None and not isinstance(pose, (str, dict)):
        pose = pose_metadata(pose)
    return {"dynstiff": __version__, "scene": scene, "pose": pose, "model": model,
            "date": _now(), **extra}


def _now():
    from datetime import UTC, datetime
    return datetime.now(UTC).isoformat(timespec="seconds")


def write_table(df, path, kind, metadata=None):
    """Write ``df`` as CSV or JSON to ``path`` (``-``: standard output). ``metadata`` (a dict;
    :func:`table_metadata` or :meth:`dynstiff.analyses.settings.AnalysisSettings.metadata`)
    gets the keys of :func:`table_metadata` first: CSV gets a header of ``# key: value``
    lines (``pandas.read_csv(path, comment="#")``), JSON is
    ``{"metadata": {...}, "data": [records]}``. Columns are named ``name [unit]``."""
    import json
    if metadata is not None:
        head = table_metadata(metadata.get("scene"), metadata.get("pose"),
                              metadata.get("model"))        # the pose as numbers, now's date
        metadata = {**head, **{k: v for k, v in metadata.items() if k not in head}}
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
        from dynstiff.io.files import write_text
        write_text(path, text)                   # atomic: a failure leaves the old file


def write_tables(args, df, metadata):
    """``--csv`` and ``--json`` of a command (each if asked), with the one metadata header."""
    for kind in ("csv", "json"):
        path = getattr(args, kind, None)
        if path:
            write_table(df, path, kind, metadata)


def save_figure(fig, path):
    """Save a figure of ``--plot`` (laid out, 120 dpi), atomically
    (:func:`dynstiff.io.files.atomic_path`), and close it."""
    import matplotlib.pyplot as plt

    from dynstiff.io.files import atomic_path
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=120, bbox_inches="tight")
    plt.close(fig)


def scene_trajectory(scene, name):
    """The scene's trajectory ``name`` (a :class:`dynstiff.WaypointPath`), or an error that
    lists the ones it has."""
    from dynstiff.errors import InvalidParameterError
    if name not in scene.trajectories:
        raise InvalidParameterError(
            f"--trajectory {name!r}: the scene has "
            + (f"the trajectories {list(scene.trajectories)}" if scene.trajectories
               else "no [[trajectories]] (dynstiff import-caspr reads CASPR's)"))
    return scene.trajectories[name]
