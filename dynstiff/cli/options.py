"""The command line's vocabulary: every option that more than one command takes is added
here, once, so that a flag means one thing in every command (:data:`MEANINGS`; the help of
each option starts with its meaning). Defaults come from the scene (its ``[analysis]``,
``[damping]`` and ``[pose]``), else from :mod:`dynstiff.analyses.settings`.

Renamed options are refused with a one-line error that names the new one
(:data:`RENAMED`), so that an old command line never runs with another meaning.
"""

__all__ = ["MEANINGS", "PARAMETERS", "RENAMED", "add_band", "add_forbidden_band",
           "add_max_modes", "add_model", "add_n_modes", "add_outputs", "add_pose",
           "add_quiet", "add_scene", "add_uncertain", "parameter_help", "renamed_hint",
           "uncertain_items"]

#: The meaning of each shared option: the first words of its help in every command.
MEANINGS = {
    "scene": "scene: a built-in scene name or the path of a TOML scene file",
    "--pose": "platform pose x y z [m] (and rx ry rz [rad]), by inverse statics",
    "--lengths": "unstretched cable lengths [m], by forward statics",
    "--band": "band of interest LO HI [Hz]",
    "--fmax": "top of the band of interest [Hz]",
    "--forbidden-band": "forbidden excitation band LO HI [Hz]",
    "--n-modes": "number of modes",
    "--max-modes": "most modes computed",
    "--model": "cable model",
    "--segments": "segments per cable of the lumped model",
    "--damping": "damping ZETA_P [ETA_C [C]]",
    "--margin": "relative margin of the platform modes to the forbidden band [-]",
    "--points": "uniform frequencies of the FRFs",
    "--parameter": "model parameter by name",
    "--values": "values of --parameter",
    "--trajectory": "the scene's trajectory NAME",
    "--csv": "write the table as CSV",
    "--json": "write the table as JSON",
    "--plot": "write a figure",
    "--out": "write the main result to",
    "--quiet": "no progress bars",
    "--uncertain": "a parameter's uncertainty NAME=VALUE, repeatable",
}

#: Parameters by name, one meaning in every command that varies or fits them.
PARAMETERS = {
    "EA": "axial stiffness of every cable [N]",
    "mass_per_length": "mass per unstretched length of every cable [kg/m]",
    "mass": "platform mass [kg]",
    "t_min": "minimum tension of the tension distribution [N]",
}

#: Options renamed, by command: the old flag and its new name.
RENAMED = {
    "frf": {"--from": "--load", "--to": "--response"},
    "simulate": {"--to": "--target"},
    "check": {"--band": "--forbidden-band"},
    "workspace": {"--band": "--forbidden-band"},
    "demo": {"--scene": "the scene as a positional argument (dynstiff demo SCENE)"},
}

#: Cable models of the command line (dynstiff.RUNGS).
MODELS = ("dsm", "exact", "lumped", "catenary", "spring")


def _help(flag, detail=None):
    return MEANINGS[flag] + (f": {detail}" if detail else "")


def add_scene(p, optional=False):
    """The positional scene (``optional``: default cogiro)."""
    if optional:
        p.add_argument("scene", nargs="?", default="cogiro",
                       help=_help("scene", "default %(default)s"))
    else:
        p.add_argument("scene", help=MEANINGS["scene"])


def add_pose(p, lengths=True, what="default: the scene's pose"):
    """``--pose`` (and ``--lengths``, exclusive)."""
    grp = p.add_mutually_exclusive_group() if lengths else p
    grp.add_argument("--pose", type=float, nargs="+", metavar="X", help=_help("--pose", what))
    if lengths:
        grp.add_argument("--lengths", type=float, nargs="+", metavar="L0",
                         help=_help("--lengths", "instead of --pose"))


def add_band(p, what="default: the scene's band_hz"):
    """``--band LO HI`` and ``--fmax F`` (its top alone), exclusive."""
    grp = p.add_mutually_exclusive_group()
    grp.add_argument("--band", type=float, nargs=2, metavar=("LO", "HI"),
                     help=_help("--band", what))
    grp.add_argument("--fmax", type=float, metavar="F",
                     help=_help("--fmax", "--band with the scene's LO (or F/2 if lower)"))


def add_forbidden_band(p):
    p.add_argument("--forbidden-band", type=float, nargs=2, metavar=("LO", "HI"),
                   help=_help("--forbidden-band", "no platform mode may lie in it (default: "
                                                  "the scene's forbidden_band_hz)"))


def add_uncertain(p):
    p.add_argument("--uncertain", action="append", metavar="NAME=VALUE[%]",
                   help=_help("--uncertain", "EA=10%% is a standard deviation of 10 %%, "
                                             "EA=10%%:uniform +-10 %%, mass=2 absolute; adds "
                                             "the probability that a platform mode enters "
                                             "the band and the margin at 95 %% confidence "
                                             "(Monte Carlo, 200 samples)"))


def uncertain_items(items):
    """{name: Uncertain} of the ``--uncertain NAME=VALUE[%][:normal|:uniform]`` options."""
    from dynstiff.analyses.uncertainty import Uncertain
    from dynstiff.errors import InvalidParameterError
    out = {}
    for item in items or ():
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise InvalidParameterError(f"--uncertain {item}: give NAME=VALUE[%], e.g. EA=10%")
        try:
            out[name.strip()] = Uncertain.parse(value)
        except InvalidParameterError as exc:
            raise InvalidParameterError(f"--uncertain {item}: {exc}") from None
    return out


def add_n_modes(p, what="default: the scene's n_modes"):
    p.add_argument("-n", "--n-modes", dest="n", type=int, metavar="N", help=_help("--n-modes",
                                                                                  what))


def add_max_modes(p, default):
    p.add_argument("--max-modes", type=int, default=default, metavar="N",
                   help=_help("--max-modes", "beyond it the search stops with an error or an "
                                             "'unknown' verdict (default %(default)s)"))


def add_model(p, default=None):
    p.add_argument("--model", choices=MODELS, default=default,
                   help=_help("--model", (
                       "closed-form dynamic stiffness, the exact cable about its true "
                       "catenary, lumped masses (--segments), or massless cables with the "
                       "catenary's or the straight spring's stiffness (platform modes only); "
                       + ("default: the scene's, else dsm" if default is None
                          else "default %(default)s"))))


def add_outputs(p, csv=None, json=None, plot=None):
    """``--csv``, ``--json`` (``-``: standard output) and ``--plot`` with what each writes."""
    if csv:
        p.add_argument("--csv", metavar="FILE",
                       help=_help("--csv", csv + " ('-': standard output)"))
    if json:
        p.add_argument("--json", metavar="FILE",
                       help=_help("--json", json + " ('-': standard output)"))
    if plot:
        p.add_argument("--plot", metavar="FILE",
                       help=_help("--plot", plot + " (PNG, PDF, SVG, ...)"))


def add_quiet(p):
    p.add_argument("--quiet", action="store_true",
                   help=_help("--quiet", "nor the first-run notice (bars are off too when "
                                         "standard error is not a terminal)"))


def parameter_help(names, what):
    """Help of ``--parameter``: the names accepted, each with its one meaning."""
    return _help("--parameter", what + ": " + ", ".join(
        f"{n} ({PARAMETERS[n]})" if n in PARAMETERS else n for n in names))


def renamed_hint(command, argv):
    """The one-line hint for an old flag of ``command`` found in ``argv``, or None."""
    for old, new in RENAMED.get(command, {}).items():
        if old in argv:
            return f"{old} was renamed: use {new}"
    return None

