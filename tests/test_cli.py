"""The command line (dynstiff/cli/__init__.py, `python -m dynstiff`), run in this process
(conftest.run_cli; the entry point in a subprocess): demo, modes, frf, sweep, simulate and
check; their tables and figures are read back and compared
with the library, and bad arguments exit with status 2 and a message naming them."""

import os
import re
import sys
from pathlib import Path

import pytest
from conftest import run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


# ---------------------------------------------------------- modes, frf, sweep, simulate
def test_cli_rejects_unknown_option():
    out = run_cli("demo", "--bogus")
    assert out.returncode == 2
    assert "--bogus" in out.stderr



def test_cli_errors_exit_nonzero_with_message(tmp_path):
    out = run_cli("modes", "nope")
    assert out.returncode == 2 and "unknown scene 'nope'" in out.stderr
    out = run_cli("modes", "cogiro", "--pose", "9", "0", "1")
    assert out.returncode == 2 and "pose [9.0" in out.stderr
    bad = tmp_path / "bad.toml"
    bad.write_text("[platform]\nmass = 1.0\nbogus_key = 3\n[[cables]]\nanchor=[0,0,1]\n"
                   "attachment=[0,0,0]\n")
    out = run_cli("modes", str(bad))
    assert out.returncode == 2 and "line 3" in out.stderr and "bogus_key" in out.stderr
    out = run_cli("modes", str(tmp_path / "missing.toml"))
    assert out.returncode == 2 and "missing.toml" in out.stderr


def test_cli_malformed_toml_and_unknown_options(tmp_path):
    bad = tmp_path / "broken.toml"
    bad.write_text("[platform\nmass = 1\n")
    for cmd in ("modes", "check", "sweep", "simulate", "frf"):
        out = run_cli(cmd, str(bad))
        assert out.returncode == 2, cmd
        assert "TOML syntax error" in out.stderr and "broken.toml" in out.stderr, cmd
        out = run_cli(cmd, "cogiro", "--no-such-option")
        assert out.returncode == 2 and "--no-such-option" in out.stderr, cmd


@pytest.mark.integration
def test_cli_version_and_metadata_in_json(tmp_path):
    import json
    out = run_cli("--version", in_subprocess=True)         # the entry point itself
    assert out.returncode == 0 and out.stdout.strip() == f"dynstiff {ds.__version__}"
    out = run_cli("modes", "planar2", "-n", "4", "--json", tmp_path / "m.json")
    assert out.returncode == 0, out.stderr
    d = json.loads((tmp_path / "m.json").read_text())
    meta = d["metadata"]
    assert meta["dynstiff"] == ds.__version__ and meta["scene"] == "planar2"
    assert meta["model"] == "dsm" and "pose" in meta and "units" in meta
    assert set(meta["damping"]) >= {"platform_ratio", "cable_loss_factor"}
    assert len(d["data"]) == 4 and "platform share [-]" in d["data"][0]


@pytest.mark.parametrize("argv, message", [
    (["modes", "{tmp}"], "is a folder, not a scene file"),
    (["modes", "{latin}"], "not a UTF-8"),
    (["modes", "{blob}"], "not a UTF-8"),
    (["check", "planar2", "--max-sag", "nan"], "--max-sag must be finite and > 0"),
    (["check", "planar2", "--margin", "-1"], "margin must be >= 0"),
    (["frf", "planar2", "--points", "0"], "--points must be >= 2"),
    (["frf", "planar2", "--points", "-3"], "--points must be >= 2"),
    (["frf", "planar2", "--plot", "{tmp}/f.xyz"], "the file name must end in one of"),
    (["frf", "planar2", "--plot", "{tmp}"], "is a folder"),
    (["modes", "planar2", "--csv", "{tmp}"], "is a folder"),
    (["modes", "planar2", "--json", "{tmp}/missing/t.json"], "does not exist"),
    (["sweep", "planar2", "--path", "{tmp}"], "Is a directory"),
    (["sweep", "planar2", "--path", "{blob}"], "UnicodeDecodeError"),
    (["modes", "cogiro", "--fmax", "1e9"], "fmax_hz = 1e\\+09 Hz is out of"),
    (["modes", "planar2", "--pose", "0", "0"], "--pose needs 3 numbers .* got 2: \\[0.0, 0.0\\]"),
    (["modes", "planar2", "--bogus"], "unrecognized arguments: --bogus"),
    (["modes", "planar2", "-n", "30", "--max-modes", "20"], "-n 30 is more than --max-modes 20"),
    (["check", "planar2", "--forbidden-band", "3", "1"], "--forbidden-band must be LO HI"),
    (["frf", "planar2", "--band", "1", "2", "--fmax", "3"], "not allowed with argument"),
    ([], "required: command"),
])
def test_bad_command_lines_give_one_line_and_exit_2(tmp_path, capsys, argv, message):
    """Every error is one line on standard error with exit code 2, and nothing is written
    (no traceback unless --debug)."""
    from dynstiff.cli import main
    latin, blob = tmp_path / "latin.toml", tmp_path / "blob.toml"
    latin.write_bytes('[scene]\nname = "grün"\n'.encode("latin-1"))
    blob.write_bytes(bytes(range(256)))
    argv = [a.format(tmp=tmp_path, latin=latin, blob=blob) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("dynstiff: error: ")
    assert re.search(message, err), err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["blob.toml", "latin.toml"]


def test_debug_shows_the_traceback_and_dash_writes_to_stdout(capsys):
    from dynstiff.cli import main
    with pytest.raises(ds.InvalidParameterError):
        main(["--debug", "modes", "planar2", "--pose", "0", "0"])
    assert main(["modes", "planar2", "-n", "2", "--csv", "-"]) == 0
    cap = capsys.readouterr()
    data = [ln for ln in cap.out.splitlines() if not ln.startswith("# ")]
    assert cap.out.startswith("# dynstiff: ")                     # the metadata header
    assert data[0].startswith("mode,freq [Hz],kind,") and len(data) == 3
    assert "dsm model" in cap.err                 # the report moves out of the data's way




# ---------------------------------------------------------- outputs never replace inputs
def _files(*paths):
    return [(p.read_bytes(), p.stat().st_mtime_ns) for p in paths]


def test_no_command_writes_over_its_inputs_or_one_output_over_another(tmp_path):
    """Each command refuses, before any work, an output that is one of its inputs (also
    through a link) or another output: exit 2, one line naming both, the files unchanged."""
    from pathlib import Path
    scene = tmp_path / "scene.toml"
    scene.write_text((Path(ds.__file__).parent / "scenes" / "fourcable.toml").read_text())
    measured = tmp_path / "m.csv"
    measured.write_text("freq [Hz]\n4.2\n")
    link = tmp_path / "link.csv"
    os.link(measured, link)
    old_map = tmp_path / "x.nc"
    old_map.write_bytes(b"an old map")
    caspr = Path(__file__).parent / "data" / "caspr"
    bodies = tmp_path / "bodies.xml"
    bodies.write_text((caspr / "CoGiRo_bodies.xml").read_text())
    keep = [scene, measured, old_map, bodies]
    before = _files(*keep)
    cases = [
        (("workspace", scene, "--step", 0.5, "--out", tmp_path / "w.nc", "--csv", scene),
         "--csv .*scene.toml is the same file as scene"),
        (("calibrate", scene, "--measured", measured, "--parameter", "EA", "--csv", measured),
         "--csv .*m.csv is the same file as --measured"),
        (("calibrate", "cogiro", "--measured", measured, "--parameter", "EA", "--csv", link),
         "--csv .*link.csv is the same file as --measured"),          # a hard link
        (("import-caspr", bodies, caspr / "CoGiRo_cables.xml", "--mass-per-length", 0.01,
          "--EA", 1e5, "--out", bodies), "--out .*bodies.xml is the same file as bodies"),
        (("workspace", scene, "--step", 0.5, "--out", old_map, "--csv", old_map),
         "--csv .*x.nc is the same file as --out .*two outputs"),
        (("frf", scene, "--uff", scene), "--uff .* is the same file as scene"),
        (("modes", scene, "--csv", tmp_path / "t.csv", "--json", tmp_path / "t.csv"),
         "--json .* is the same file as --csv"),
    ]
    for args, message in cases:
        out = run_cli(*map(str, args))
        assert out.returncode == 2, (args, out.stderr)
        assert out.stderr.count("\n") == 1 and re.search(message, out.stderr), out.stderr
    assert _files(*keep) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["scene.toml", "m.csv", "link.csv", "x.nc", "bodies.xml"])


# ------------------------------------------------------------------- one vocabulary
#: The one meaning of every flag more than one command takes: the first words of its help.
FLAG_MEANINGS = {
    "scene": ("scene", "scene: a built-in scene name or the path of a TOML scene file"),
    "--pose": ("pose", "platform pose x y z [m] (and rx ry rz [rad]), by inverse statics"),
    "--lengths": ("lengths", "unstretched cable lengths [m], by forward statics"),
    "--band": ("band", "band of interest LO HI [Hz]"),
    "--fmax": ("fmax", "top of the band of interest [Hz]"),
    "--forbidden-band": ("forbidden_band", "forbidden excitation band LO HI [Hz]"),
    "--n-modes": ("n", "number of modes"),
    "--max-modes": ("max_modes", "most modes computed"),
    "--model": ("model", "cable model"),
    "--segments": ("segments", "segments per cable of the lumped model"),
    "--damping": ("damping", "damping ZETA_P [ETA_C [C]]"),
    "--margin": ("margin", "relative margin of the platform modes to the forbidden band [-]"),
    "--points": ("points", "uniform frequencies of the FRFs"),
    "--parameter": ("parameter", "model parameter by name"),
    "--values": ("values", "values of --parameter"),
    "--trajectory": ("trajectory", "the scene's trajectory NAME"),
    "--csv": ("csv", "write the table as CSV"),
    "--json": ("json", "write the table as JSON"),
    "--plot": ("plot", "write a figure"),
    "--out": ("out", "write the main result to"),
    "--quiet": ("quiet", "no progress bars"),
    "--uncertain": ("uncertain", "a parameter's uncertainty NAME=VALUE, repeatable"),
}


def _options():
    """{flag: [(command, dest, help)]} of every subcommand, from build_parser()."""
    import argparse

    from dynstiff.cli import build_parser
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction))
    found = {}
    for command, parser in sub.choices.items():
        for a in parser._actions:
            if isinstance(a, argparse._HelpAction):
                continue
            flag = (a.option_strings[-1] if a.option_strings else a.dest)
            found.setdefault(flag, []).append((command, a.dest, a.help))
    return found


def test_one_flag_one_meaning():
    """Every option has help; a flag that several commands take has one dest and one meaning
    (its help starts with the meaning of FLAG_MEANINGS) in all of them; the renamed flags are
    gone (frf --from/--to, simulate --to, check/workspace --band as a forbidden band, demo
    --scene)."""
    found = _options()
    for flag, uses in found.items():
        for command, _, text in uses:
            assert text and text.strip(), f"{command} {flag} has no help"
        if len(uses) > 1:
            assert flag in FLAG_MEANINGS, f"{flag} is in {[u[0] for u in uses]}: add its meaning"
        if flag in FLAG_MEANINGS:
            dest, meaning = FLAG_MEANINGS[flag]
            for command, d, text in uses:
                assert d == dest, (flag, command, d)
                assert text.startswith(meaning), (flag, command, text)
    assert "--from" not in found and "--to" not in found and "--scene" not in found
    assert {c for c, _, _ in found["--band"]}.isdisjoint({"check", "workspace"})
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    table = readme.split("its one meaning", 1)[1].split("\n\n", 1)[0]
    for flag in FLAG_MEANINGS:
        if flag != "scene":
            assert f"`{flag}" in table or f"`-n`, `{flag}" in table, flag


def test_renamed_flags_are_refused_with_their_new_name(capsys):
    from dynstiff.cli import main
    for argv, new in ((["frf", "planar2", "--from", "fx"], "--load"),
                      (["simulate", "planar2", "--to", "0", "0", "1"], "--target"),
                      (["check", "planar2", "--band", "1", "2"], "--forbidden-band"),
                      (["demo", "--scene", "planar2"], "positional")):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and new in err, err


# ------------------------------------------------------------------------ the console
def test_package_warnings_print_as_one_line_each(capsys):
    """A ClosedFormWarning (the pendulum's closed form asked up to 3 kHz, above its cables'
    axial modes at 2318 Hz) prints as one line `dynstiff: warning: MESSAGE`, without the
    file, line or class name Python's format shows; Python's own display is back after."""
    import warnings

    from dynstiff.cli import main
    from dynstiff.errors import ClosedFormWarning
    before = warnings.showwarning
    with warnings.catch_warnings():
        warnings.simplefilter("always", ClosedFormWarning)     # the warning is the subject
        assert main(["modes", "pendulum", "--fmax", "3000"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2, err
    for k, line in enumerate(err):
        assert line.startswith(f"dynstiff: warning: cable {k}: its axial modes from 2318 Hz")
        assert "up to 3000 Hz" in line
        assert "ClosedFormWarning" not in line and ".py" not in line
    assert warnings.showwarning is before


def test_check_of_the_pendulum_judges_its_own_band(capsys):
    """`check pendulum`: the cable model judged up to the scene's 200 Hz, no warning (the
    search for the platform modes once asked 40 modes whatever the band, up to 4096 Hz,
    beyond the cables' axial modes at 2318 Hz; a warning here is an error under pytest)."""
    from dynstiff.cli import main
    assert main(["check", "pendulum"]) == 0
    cap = capsys.readouterr()
    assert cap.err == ""
    line = next(ln for ln in cap.out.splitlines() if ln.startswith("PASS    cable model"))
    assert "up to 200 Hz" in line


# ------------------------------------------------------------- main: what it reads, returns
def test_main_reads_sys_argv_after_the_program_name(monkeypatch, capsys):
    """main() without arguments takes the command line from sys.argv[1:]."""
    from dynstiff.cli import main
    monkeypatch.setattr(sys, "argv", ["dynstiff", "scenes"])
    assert main() == 0
    assert capsys.readouterr().out.split()[0] in ds.list_scenes()


def test_usage_errors_are_one_exact_line_with_the_hint_where_a_flag_was_renamed(capsys):
    """argparse's refusal is one line: the program, its message, the renamed flag's hint
    only where there is one, and where to find help."""
    from dynstiff.cli import main
    assert main(["demo", "--bogus"]) == 2
    assert capsys.readouterr().err == ("dynstiff: error: dynstiff: unrecognized arguments: "
                                       "--bogus (dynstiff -h, or dynstiff COMMAND -h)\n")
    assert main(["frf", "planar2", "--from", "fx"]) == 2
    assert capsys.readouterr().err == (
        "dynstiff: error: dynstiff: unrecognized arguments: --from fx; --from was renamed: "
        "use --load (dynstiff -h, or dynstiff COMMAND -h)\n")


def test_the_compile_notice_is_asked_for_every_command_but_scenes(monkeypatch, capsys,
                                                                  tmp_path):
    """Every command that computes may compile the kernels first and asks for the notice,
    quiet with --quiet (not quiet for a command without it); `scenes` computes nothing and
    does not ask."""
    import dynstiff.cli
    seen = []
    monkeypatch.setattr(dynstiff.cli, "compile_notice", seen.append)
    assert dynstiff.cli.main(["scenes"]) == 0
    assert seen == []
    assert dynstiff.cli.main(["modes", "planar2", "-n", "1"]) == 0
    assert dynstiff.cli.main(["sweep", "planar2", "--line", "0", "0", "1", "0", "0", "1.1",
                              "--steps", "2", "-n", "1", "--quiet"]) == 0
    data = Path(__file__).parent / "data" / "caspr"
    assert dynstiff.cli.main(["import-caspr", str(data / "CoGiRo_bodies.xml"),
                              str(data / "CoGiRo_cables.xml"), "--mass-per-length", "0.064",
                              "--EA", "139486.7", "--out", str(tmp_path / "c.toml")]) == 0
    assert seen == [False, True, False]          # import-caspr has no --quiet: not quiet
    capsys.readouterr()


def _failing_scenes(monkeypatch, exc):
    """`dynstiff scenes` made to raise ``exc``."""
    import dynstiff.cli.analysis

    def fail(args):
        raise exc
    monkeypatch.setattr(dynstiff.cli.analysis, "_cmd_scenes", fail)


@pytest.mark.parametrize("exc, line, code", [
    (KeyboardInterrupt(), "\ndynstiff: interrupted\n", 130),
    (KeyboardInterrupt("3 poses saved"), "\ndynstiff: 3 poses saved\n", 130),
    (MemoryError("932 GiB"), "dynstiff: error: MemoryError: 932 GiB\n", 2),
    (UnicodeDecodeError("utf-8", b"\xff", 0, 1, "invalid start byte"),
     "dynstiff: error: UnicodeDecodeError: 'utf-8' codec can't decode byte 0xff in position "
     "0: invalid start byte\n", 2),
    (ds.InvalidParameterError("n_modes must be > 0"), "dynstiff: error: n_modes must be > 0\n",
     2),
    (FileNotFoundError(2, "No such file or directory", "x.toml"),
     "dynstiff: error: [Errno 2] No such file or directory: 'x.toml'\n", 2),
])
def test_errors_and_interrupts_are_one_line_with_their_exit_code(monkeypatch, capsys, exc,
                                                                  line, code):
    """Ctrl-C: exit 130 and what was saved (or "interrupted"); MemoryError and
    UnicodeDecodeError name their type (their messages alone do not say what happened); a
    dynstiff or OS error is its message alone; all exit 2."""
    from dynstiff.cli import main
    _failing_scenes(monkeypatch, exc)
    assert main(["scenes"]) == code
    assert capsys.readouterr().err == line


def test_a_closed_pipe_ends_quietly_with_its_output_to_devnull(monkeypatch, tmp_path):
    """Output piped into a reader that stops (BrokenPipeError): exit 0, nothing on stderr,
    and standard output's descriptor now leads to the null device (what Python flushes at
    exit is dropped, not a second error)."""
    from dynstiff.cli import main
    _failing_scenes(monkeypatch, BrokenPipeError())
    with open(tmp_path / "out", "w") as out, open(tmp_path / "err", "w") as err:
        monkeypatch.setattr(sys, "stdout", out)
        monkeypatch.setattr(sys, "stderr", err)
        assert main(["scenes"]) == 0
        os.write(out.fileno(), b"after")
    assert (tmp_path / "out").read_bytes() == b"" and (tmp_path / "err").read_bytes() == b""
