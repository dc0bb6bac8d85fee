"""The command line's shared options (dynstiff.cli.options), each on a parser of its own:
what it parses (type, count, default, exclusivity) and the whole of its help, which is what a
user reads in ``dynstiff COMMAND --help`` and in the docs' command-line page."""

import argparse

import pytest

from dynstiff.cli import options as o
from dynstiff.errors import InvalidParameterError


class _Refused(Exception):
    """argparse's refusal, raised instead of exiting."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise _Refused(message)


def _parser(add, *args, **kw):
    p = _Parser(prog="dynstiff x")
    add(p, *args, **kw)
    return p


def _action(p, dest):
    return next(a for a in p._actions if a.dest == dest)


def _help(p, dest):
    """The help as printed (``%(default)s`` and ``%%`` expanded)."""
    a = _action(p, dest)
    return argparse.HelpFormatter("x")._expand_help(a)


def test_scene_positional_required_or_cogiro():
    p = _parser(o.add_scene)
    assert p.parse_args(["planar2"]).scene == "planar2"
    with pytest.raises(_Refused, match="scene"):
        p.parse_args([])
    assert _help(p, "scene") == "scene: a built-in scene name or the path of a TOML scene file"
    q = _parser(o.add_scene, optional=True)
    assert q.parse_args([]).scene == "cogiro" and q.parse_args(["x.toml"]).scene == "x.toml"
    assert _help(q, "scene") == ("scene: a built-in scene name or the path of a TOML scene "
                                 "file: default cogiro")


def test_pose_and_lengths_are_floats_and_exclusive():
    p = _parser(o.add_pose)
    a = p.parse_args(["--pose", "1", "2.5", "3"])
    assert a.pose == [1.0, 2.5, 3.0] and a.lengths is None
    assert p.parse_args(["--lengths", "4", "5"]).lengths == [4.0, 5.0]
    assert p.parse_args([]).pose is None
    for bad in (["--pose", "1", "--lengths", "2"], ["--pose"], ["--pose", "a"]):
        with pytest.raises(_Refused):
            p.parse_args(bad)
    assert _action(p, "pose").metavar == "X" and _action(p, "lengths").metavar == "L0"
    assert _help(p, "pose") == ("platform pose x y z [m] (and rx ry rz [rad]), by inverse "
                                "statics: default: the scene's pose")
    assert _help(p, "lengths") == ("unstretched cable lengths [m], by forward statics: "
                                   "instead of --pose")
    q = _parser(o.add_pose, lengths=False, what="the start")
    assert not any(a.dest == "lengths" for a in q._actions)
    assert _help(q, "pose").endswith("by inverse statics: the start")
    assert q.parse_args(["--pose", "1", "2", "3"]).pose == [1.0, 2.0, 3.0]


def test_band_and_fmax_exclusive():
    p = _parser(o.add_band)
    assert p.parse_args(["--band", "0.5", "20"]).band == [0.5, 20.0]
    assert p.parse_args(["--fmax", "12"]).fmax == 12.0
    a = p.parse_args([])
    assert a.band is None and a.fmax is None
    for bad in (["--band", "1"], ["--band", "1", "2", "--fmax", "3"], ["--fmax", "x"]):
        with pytest.raises(_Refused):
            p.parse_args(bad)
    assert _action(p, "band").metavar == ("LO", "HI") and _action(p, "fmax").metavar == "F"
    assert _help(p, "band") == "band of interest LO HI [Hz]: default: the scene's band_hz"
    assert _help(p, "fmax") == ("top of the band of interest [Hz]: --band with the scene's LO "
                                "(or F/2 if lower)")
    assert _help(_parser(o.add_band, what="from 0"), "band").endswith("[Hz]: from 0")


def test_forbidden_band():
    p = _parser(o.add_forbidden_band)
    assert p.parse_args(["--forbidden-band", "2", "5"]).forbidden_band == [2.0, 5.0]
    assert p.parse_args([]).forbidden_band is None
    with pytest.raises(_Refused):
        p.parse_args(["--forbidden-band", "2"])
    assert _action(p, "forbidden_band").metavar == ("LO", "HI")
    assert _help(p, "forbidden_band") == (
        "forbidden excitation band LO HI [Hz]: no platform mode may lie in it (default: the "
        "scene's forbidden_band_hz)")


def test_uncertain_repeatable_and_parsed():
    p = _parser(o.add_uncertain)
    a = p.parse_args(["--uncertain", "EA=10%", "--uncertain", "mass=2:uniform"])
    assert a.uncertain == ["EA=10%", "mass=2:uniform"]
    assert p.parse_args([]).uncertain is None
    assert _action(p, "uncertain").metavar == "NAME=VALUE[%]"
    assert _help(p, "uncertain") == (
        "a parameter's uncertainty NAME=VALUE, repeatable: EA=10% is a standard deviation of "
        "10 %, EA=10%:uniform +-10 %, mass=2 absolute; adds the probability that a platform "
        "mode enters the band and the margin at 95 % confidence (Monte Carlo, 200 samples)")
    from dynstiff.analyses.uncertainty import Uncertain
    got = o.uncertain_items([" EA =10%", "mass=2:uniform"])
    assert got == {"EA": Uncertain(0.1), "mass": Uncertain(2.0, "uniform", relative=False)}
    assert o.uncertain_items(None) == {} and o.uncertain_items([]) == {}


@pytest.mark.parametrize("item, message", [
    ("EA", r"^--uncertain EA: give NAME=VALUE\[%\], e\.g\. EA=10%$"),
    ("=10%", r"^--uncertain =10%: give NAME=VALUE"),
    (" =10%", r"^--uncertain  =10%: give NAME=VALUE"),
    ("EA=ten", r"^--uncertain EA=ten: uncertainty 'ten': give VALUE"),
    ("EA=-1%", r"^--uncertain EA=-1%: scale must be finite and > 0"),
])
def test_uncertain_items_refused_naming_the_option(item, message):
    with pytest.raises(InvalidParameterError, match=message) as info:
        o.uncertain_items(["EA=1%", item])
    e = info.value                              # one line: no chained traceback
    assert e.__cause__ is None and (e.__context__ is None or e.__suppress_context__)


def test_modes_options():
    p = _parser(o.add_n_modes)
    assert p.parse_args(["-n", "7"]).n == 7 and p.parse_args(["--n-modes", "3"]).n == 3
    assert p.parse_args([]).n is None
    with pytest.raises(_Refused):
        p.parse_args(["-n", "2.5"])
    assert _action(p, "n").metavar == "N"
    assert _help(p, "n") == "number of modes: default: the scene's n_modes"
    assert _help(_parser(o.add_n_modes, what="of the table"), "n") == \
        "number of modes: of the table"
    q = _parser(o.add_max_modes, 60)
    assert q.parse_args([]).max_modes == 60 and q.parse_args(["--max-modes", "9"]).max_modes == 9
    with pytest.raises(_Refused):
        q.parse_args(["--max-modes", "9.5"])
    assert _action(q, "max_modes").metavar == "N"
    assert _help(q, "max_modes") == ("most modes computed: beyond it the search stops with an "
                                      "error or an 'unknown' verdict (default 60)")


def test_model_choices_and_default():
    p = _parser(o.add_model)
    assert p.parse_args([]).model is None
    for m in ("dsm", "exact", "lumped", "catenary", "spring"):
        assert p.parse_args(["--model", m]).model == m
    with pytest.raises(_Refused, match="invalid choice"):
        p.parse_args(["--model", "taut"])
    detail = ("cable model: closed-form dynamic stiffness, the exact cable about its true "
              "catenary, lumped masses (--segments), or massless cables with the catenary's "
              "or the straight spring's stiffness (platform modes only); ")
    assert _help(p, "model") == detail + "default: the scene's, else dsm"
    q = _parser(o.add_model, default="exact")
    assert q.parse_args([]).model == "exact"
    assert _help(q, "model") == detail + "default exact"
    import dynstiff as ds
    assert set(o.MODELS) == set(ds.RUNGS)


def test_outputs_only_those_asked_for():
    p = _parser(o.add_outputs, csv="the modes", json="the checks", plot="the FRF")
    a = p.parse_args(["--csv", "a.csv", "--json", "-", "--plot", "f.png"])
    assert (a.csv, a.json, a.plot) == ("a.csv", "-", "f.png")
    a = p.parse_args([])
    assert (a.csv, a.json, a.plot) == (None, None, None)
    assert {_action(p, d).metavar for d in ("csv", "json", "plot")} == {"FILE"}
    assert _help(p, "csv") == "write the table as CSV: the modes ('-': standard output)"
    assert _help(p, "json") == "write the table as JSON: the checks ('-': standard output)"
    assert _help(p, "plot") == "write a figure: the FRF (PNG, PDF, SVG, ...)"
    for only in ("csv", "json", "plot"):
        q = _parser(o.add_outputs, **{only: "it"})
        dests = {a.dest for a in q._actions} - {"help"}
        assert dests == {only}


def test_quiet_flag():
    p = _parser(o.add_quiet)
    assert p.parse_args([]).quiet is False and p.parse_args(["--quiet"]).quiet is True
    assert _help(p, "quiet") == ("no progress bars: nor the first-run notice (bars are off too "
                                 "when standard error is not a terminal)")


def test_parameter_help_names_each_meaning():
    text = o.parameter_help(["EA", "t_min", "zeta"], "swept")
    assert text == ("model parameter by name: swept: EA (axial stiffness of every cable [N]), "
                    "t_min (minimum tension of the tension distribution [N]), zeta")
    assert o.parameter_help(["mass", "mass_per_length"], "fitted") == (
        "model parameter by name: fitted: mass (platform mass [kg]), mass_per_length (mass per "
        "unstretched length of every cable [kg/m])")


@pytest.mark.parametrize("command, argv, hint", [
    ("frf", ["planar2", "--from", "fx"], "--from was renamed: use --load"),
    ("frf", ["planar2", "--to", "x"], "--to was renamed: use --response"),
    ("simulate", ["--to", "0"], "--to was renamed: use --target"),
    ("check", ["--band", "1", "2"], "--band was renamed: use --forbidden-band"),
    ("workspace", ["--band", "1", "2"], "--band was renamed: use --forbidden-band"),
    ("demo", ["--scene", "x"], "--scene was renamed: use the scene as a positional argument "
                               "(dynstiff demo SCENE)"),
    ("frf", ["planar2", "--load", "fx"], None),
    ("modes", ["--band", "1", "2"], None),            # --band is the band of interest there
    ("simulate", ["--from", "0"], None),
])
def test_renamed_hint(command, argv, hint):
    assert o.renamed_hint(command, argv) == hint
