"""Smoke test of the command line (dynstiff/cli/): every subcommand on every built-in scene
with its defaults, and every output option each subcommand offers, run in-process
(``dynstiff.cli.main``); each must exit 0 (``check``: 0 or 1, its verdict), write what it
announces in a form that reads back (CSV with its metadata header, JSON, PNG, UFF 58, netCDF,
a scene file, a report folder) and print no traceback and no raw Python warning.

The subcommands and their output options are read from ``build_parser()``: an option whose
help starts with "write" is an output, so a new command or output option fails here until
this file says how to run and read it."""

import argparse
import io
import json
import re
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import dynstiff as ds
from dynstiff.cli import build_parser, main
from dynstiff.errors import DynstiffWarning

CASPR = Path(__file__).parent / "data" / "caspr"
#: The head of every table's metadata, in this order (dynstiff.cli.common.table_metadata).
HEADER = ["dynstiff", "scene", "pose", "model", "date"]
#: The quickest scene that has every feature the commands use.
QUICK = "planar2"
#: Scenes whose report runs in the default tier, by command (the others are marked slow).
QUICK_REPORTS = {"report": ("planar2", "pendulum"), "demo": ("planar2",)}


def _commands():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices


COMMANDS = _commands()
SCENELESS = ("scenes", "import-caspr")
#: Runs that fail today, each with its cause (strict: they report when they start to pass).
KNOWN_DEFECTS: dict = {}        # (command, scene) -> reason, run as strict xfails


def _outputs(command):
    """The output options of ``command``: those whose help starts with "write"."""
    return [a.option_strings[-1] for a in COMMANDS[command]._actions
            if a.option_strings and (a.help or "").startswith("write")]


def _extra(command, scene, tmp):
    """The arguments ``command`` needs besides the scene (small sizes where it runs long)."""
    if command in ("demo", "report"):
        return ["--points", "200"]
    if command == "simulate":
        return ["--time", "0.2"]
    if command == "sweep":
        m = ds.load_scene(scene).robot.platform.mass
        return ["--parameter", "mass", "--values", str(m), str(1.2 * m), "-n", "4"]
    if command == "workspace":
        p = ds.load_scene(scene).equilibrium().pose.position
        return ["--box", *(f"{v:.17g}" for c in p for v in (c, c)), "--step", "1", "-n", "4"]
    if command == "calibrate":
        return ["--measured", str(_measured(scene, tmp)), "--parameter", "EA"]
    if command == "import-caspr":
        return [str(CASPR / "InvertedStewart_bodies.xml"),
                str(CASPR / "InvertedStewart_cables.xml"), "--mass-per-length", "0.01",
                "--EA", "1e5"]
    if command in ("modes", "frf", "check", "scenes"):
        return []
    raise AssertionError(f"tests/test_cli_smoke.py does not know how to run {command!r}")


def _measured(scene, tmp):
    """A measured-modes CSV: the scene's modes that move the platform most (up to 4), 2 %
    higher (EA has to move)."""
    sc = ds.load_scene(scene)
    with warnings.catch_warnings():
        # the closed form's guard may warn on the heavy-cable scenes; the synthetic table is
        # not its subject (the command's own run below shows its warnings)
        warnings.simplefilter("ignore", DynstiffWarning)
        res = ds.modes(ds.FrequencyModel(sc.equilibrium()), n_modes=sc.n_modes or 6)
    n = min(4, len(sc.robot.platform.free_dofs))
    f = np.sort(res.freq_hz[np.argsort(-res.platform_share)[:n]]) * 1.02
    path = tmp / f"measured-{scene}.csv"
    pd.DataFrame({"freq [Hz]": f}).to_csv(path, index=False)
    return path


#: Files of each output option, by command where it differs.
def _target(command, option, tmp):
    if option == "--out":
        return tmp / {"workspace": "map.nc", "import-caspr": "scene.toml"}.get(command, "out")
    return tmp / {"--csv": "t.csv", "--json": "t.json", "--plot": "f.png",
                  "--uff": "f.uff"}[option]


def _run(capsys, argv):
    """``dynstiff ARGV`` in-process: exit code, stdout, stderr."""
    with warnings.catch_warnings():
        # the package's warnings are errors in the tests; here they reach the command line,
        # which must print each as one line (checked below), not fail
        warnings.simplefilter("always", DynstiffWarning)
        code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err, err[-2000:]
    assert not re.search(r":\d+: \w+Warning: ", out + err), err    # no raw warning
    for line in err.splitlines():
        if "warning" in line.lower():
            assert line.startswith("dynstiff: warning: "), line
    return code, out, err


def _ok(command, code, err):
    assert code in ((0, 1) if command == "check" else (0,)), err


def _read_table(source, kind):
    """A table written by the command line: its metadata and rows."""
    if kind == "csv":
        text = source if isinstance(source, str) else source.read_text()
        head = [ln[2:].split(":", 1)[0] for ln in text.splitlines() if ln.startswith("# ")]
        df = pd.read_csv(io.StringIO(text), comment="#")
        assert head[:5] == HEADER, head
    else:
        d = json.loads(source if isinstance(source, str) else source.read_text())
        assert list(d["metadata"])[:5] == HEADER, d["metadata"]
        df = pd.DataFrame(d["data"])
    assert len(df) > 0 and len(df.columns) > 0
    return df


def _check_written(command, option, path):
    if option in ("--csv", "--json"):
        _read_table(path, option[2:])
    elif option == "--plot":
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    elif option == "--uff":
        pyuff = pytest.importorskip("pyuff")
        sets = pyuff.UFF(str(path)).read_sets()
        sets = sets if isinstance(sets, list) else [sets]
        assert len(sets) >= 1 and all(s["type"] == 58 for s in sets)
    elif option == "--out" and command == "workspace":
        from dynstiff.maps.dataset import open_workspace
        assert open_workspace(path)["feasible"].size >= 1
    elif option == "--out" and command == "import-caspr":
        assert ds.load_scene(path).robot.n_cables == 6
        labels = re.findall(r"^\[\[cables\]\]\s+# cable (\d+)", path.read_text(), re.M)
        assert labels == [str(k) for k in range(6)]          # numbered from 0, as outputs
    elif option == "--out":
        assert (path / "report.html").stat().st_size > 1000
        assert len(list(path.glob("*.csv"))) >= 3
        for csv in path.glob("*.csv"):
            _read_table(csv, "csv")                     # the same header as every table
    else:
        raise AssertionError(f"tests/test_cli_smoke.py does not know how to read {option}")


def _cases_defaults():
    for command in COMMANDS:
        for scene in ((None,) if command in SCENELESS else ds.list_scenes()):
            slow = command in QUICK_REPORTS and scene not in QUICK_REPORTS[command]
            marks = [pytest.mark.slow] if slow else []
            if (command, scene) in KNOWN_DEFECTS:
                marks.append(pytest.mark.xfail(strict=True,
                                               reason=KNOWN_DEFECTS[command, scene]))
            yield pytest.param(command, scene, id=f"{command}-{scene}", marks=marks)


def _cases_outputs():
    for command in COMMANDS:
        for option in _outputs(command):
            yield pytest.param(command, option, False, id=f"{command}{option}")
            if option in ("--csv", "--json") or (option == "--out"
                                                 and command == "import-caspr"):
                yield pytest.param(command, option, True, id=f"{command}{option}-stdout")


@pytest.mark.parametrize("command, scene", list(_cases_defaults()))
def test_every_command_on_every_scene(command, scene, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)                  # default output folders land here
    argv = [command] + ([] if scene is None else [scene]) + _extra(command, scene or QUICK,
                                                                   tmp_path)
    if "--out" in _outputs(command) and any(a.required and "--out" in a.option_strings
                                            for a in COMMANDS[command]._actions):
        argv += ["--out", _target(command, "--out", tmp_path)]
    code, out, err = _run(capsys, argv)
    _ok(command, code, err)
    assert out.strip(), err                          # every command reports something


@pytest.mark.parametrize("command, option, stdout", list(_cases_outputs()))
def test_every_output_option(command, option, stdout, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene = [] if command in SCENELESS else [QUICK]
    argv = [command, *scene, *_extra(command, QUICK, tmp_path)]
    path = _target(command, option, tmp_path)
    if option != "--out" and "--out" in _outputs(command) and any(
            a.required and "--out" in a.option_strings for a in COMMANDS[command]._actions):
        argv += ["--out", _target(command, "--out", tmp_path)]
    code, out, err = _run(capsys, argv + [option, "-" if stdout else path])
    _ok(command, code, err)
    if not stdout:
        assert path.exists(), (option, out, err)
        assert f"{path.name}" in out + err                    # announced
        _check_written(command, option, path)
    elif option == "--out":
        (tmp_path / "s.toml").write_text(out)
        _check_written(command, option, tmp_path / "s.toml")
    else:
        _read_table(out, option[2:])             # standard output holds the data only


def test_every_command_and_output_is_covered():
    """The lists above come from the parser; each command has a way to run here and each
    output option a reader (a new one fails until it is added)."""
    assert set(COMMANDS) >= {"demo", "report", "scenes", "modes", "frf", "check", "sweep",
                             "simulate", "import-caspr", "calibrate", "workspace"}
    for command in COMMANDS:
        if command != "calibrate":                            # it writes a measured table
            _extra(command, QUICK, Path("."))
        assert set(_outputs(command)) <= {"--csv", "--json", "--plot", "--uff", "--out"}, \
            command
    assert {o for c in COMMANDS for o in _outputs(c)} == {"--csv", "--json", "--plot",
                                                          "--uff", "--out"}
