"""The parsers of the commands of dynstiff/cli/exchange.py (dynstiff.cli.build_parser):
import-caspr and calibrate listed with their help, each option with its flags, metavar,
default, type and help as printed."""


# ------------------------------------------------------------------ the parsers' options
def _subparsers():
    import argparse

    from dynstiff.cli import build_parser
    return next(a for a in build_parser()._actions
                if isinstance(a, argparse._SubParsersAction))


def _options(command):
    """{dest: (flags, metavar, required, default, type, choices, nargs, help as printed)}
    of ``dynstiff COMMAND``."""
    import argparse
    fmt = argparse.HelpFormatter("x")
    return {a.dest: (tuple(a.option_strings), a.metavar, a.required, a.default, a.type,
                     a.choices, a.nargs, fmt._expand_help(a))
            for a in _subparsers().choices[command]._actions if a.dest != "help"}


def test_the_commands_are_listed_with_their_help():
    """`dynstiff -h` lists import-caspr and calibrate under these names, each with its
    one-line help."""
    sub = _subparsers()
    helps = {a.dest: a.help for a in sub._choices_actions}
    assert helps["import-caspr"] == ("write a scene file from CASPR's XML model files "
                                     "(single rigid body)")
    assert helps["calibrate"] == ("fit EA, platform mass ... to measured natural frequencies; "
                                  "estimates with confidence intervals")


def test_import_caspr_options_and_their_help():
    """Every option of `dynstiff import-caspr`: its flag, metavar, whether it is required,
    default, type, choices and the help a user reads."""
    from dynstiff.cli.options import MEANINGS, PARAMETERS
    beside = "(default: the file beside BODIES, if any)"
    assert _options("import-caspr") == {
        "bodies": ((), None, True, None, None, None, None, "CASPR *_bodies.xml"),
        "cables": ((), None, True, None, None, None, None, "CASPR *_cables.xml"),
        "mass_per_length": (("--mass-per-length",), None, True, None, float, None, None,
                            f"{PARAMETERS['mass_per_length']} (CASPR holds none)"),
        "EA": (("--EA",), None, True, None, float, None, None,
               f"{PARAMETERS['EA']} (CASPR holds none)"),
        "cable_set": (("--cable-set",), None, False, None, None, None, None,
                      "cable set id (default: the file's default_cable_set)"),
        "inertia_convention": (
            ("--inertia-convention",), None, False, "products", None, ["products", "tensor"],
            None, "printed Ixy, Ixz, Iyz are products of inertia (default; tensor entry = "
                  "-value) or tensor entries (CASPR's code)"),
        "min_tension": (("--min-tension",), None, False, 1.0, float, None, None,
                        "least t_min [N] where CASPR's force_min is lower (default 1.0)"),
        "trajectories": (("--trajectories",), "FILE", False, None, None, None, None,
                         "CASPR *_trajectories.xml: its joint trajectories become the "
                         f"scene's [[trajectories]] {beside}"),
        "operational_spaces": (("--operational-spaces",), "FILE", False, None, None, None,
                               None, "CASPR *_operational_spaces.xml: its markers are listed "
                                     f"in the scene's header {beside}"),
        "no_siblings": (("--no-siblings",), None, False, False, None, None, 0,
                        "do not read the trajectories and operational-space files beside "
                        "BODIES"),
        "name": (("--name",), None, False, None, None, None, None,
                 "scene name (default: the CASPR link's name)"),
        "out": (("--out",), "FILE", True, None, None, None, None,
                MEANINGS["--out"] + ": the scene file ('-': standard output); its cables are "
                                    "numbered from 0, as in every output"),
    }


def test_calibrate_options_and_their_help():
    """Every option of `dynstiff calibrate`: flag, metavar, required, default (dsm model,
    2000 modes at most, 95 % intervals), type and the help a user reads; no --lengths."""
    from dynstiff.cli.options import MEANINGS, MODELS, PARAMETERS
    opts = _options("calibrate")
    assert list(opts) == ["scene", "measured", "parameter", "pose", "model", "max_modes",
                          "confidence", "csv", "json", "plot", "quiet"]
    assert opts["scene"] == ((), None, True, None, None, None, None, MEANINGS["scene"])
    assert opts["measured"] == (("--measured",), "FILE", True, None, None, None, None,
                                "CSV of measured modes: 'freq [Hz]', optional 'sigma [Hz]' "
                                "and shape columns x y z rx ry rz")
    assert opts["parameter"] == (
        ("--parameter",), None, True, None, None, None, None,
        MEANINGS["--parameter"] + ": to fit (repeat for several): "
        f"EA ({PARAMETERS['EA']}), mass ({PARAMETERS['mass']}), t_min ({PARAMETERS['t_min']})"
        ", EA_<i> (cable i's, from 0), EA_* (each cable's), inertia, loss_factor, "
        "viscous_damping (the last two need a 'damping ratio [-]' column and a nonzero value "
        "in the scene)")
    assert opts["pose"] == (("--pose",), "X", False, None, float, None, "+",
                            MEANINGS["--pose"] + ": of the measurement (default: the scene's "
                                                 "pose)")
    assert opts["model"][:7] == (("--model",), None, False, "dsm", None, MODELS, None)
    assert opts["model"][7].startswith(MEANINGS["--model"] + ": ")
    assert opts["model"][7].endswith("; default dsm")
    assert opts["max_modes"][:7] == (("--max-modes",), "N", False, 2000, int, None, None)
    assert opts["max_modes"][7].endswith("(default 2000)")
    assert opts["confidence"] == (("--confidence",), None, False, 0.95, float, None, None,
                                  "level of the intervals (default 0.95)")
    assert opts["csv"] == (("--csv",), "FILE", False, None, None, None, None,
                           MEANINGS["--csv"] + ": the residual of every mode ('-': standard "
                                               "output)")
    assert opts["json"] == (("--json",), "FILE", False, None, None, None, None,
                            MEANINGS["--json"] + ": the residual of every mode ('-': standard "
                                                 "output)")
    assert opts["plot"][:7] == (("--plot",), "FILE", False, None, None, None, None)
    assert opts["plot"][7].startswith(MEANINGS["--plot"] + ": the relative error of every "
                                                           "mode before and after the fit")
    assert opts["quiet"][:4] == (("--quiet",), None, False, False)
