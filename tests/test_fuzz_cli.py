"""Hostile command lines (dynstiff.cli.main): bad option values, unknown options and
commands end with exit 0, 1 or 2, an exit 2 with one line `dynstiff: error: ...`, never a
traceback; output paths that clash with an input or with each other are refused
(dynstiff/cli/common.py, check_outputs) and no file is changed. Tiers as in
tests/test_fuzz.py (``-m slow``: 4,000 examples here).
"""

import contextlib
import io

import pytest
from conftest import FAST, _settings
from hypothesis import given
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.cli import main

# ---------------------------------------------------------------------- command line
OPTION_VALUES = st.one_of(st.sampled_from(["nan", "-1", "0", "1e9", "inf", "2", "x", "",
                                           "/", "-", "a.xyz", "0.5"]),
                          st.floats(-10, 10).map(repr))


def _cli_fuzzer(n):
    @_settings(n)
    @given(command=st.sampled_from(["modes", "frf", "check", "sweep", "simulate", "demo",
                                    "scenes", "nope"]),
           options=st.lists(st.tuples(st.sampled_from(
               ["-n", "--fmax", "--points", "--band", "--forbidden-band", "--margin",
                "--max-sag", "--pose", "--lengths", "--csv", "--plot", "--time", "--dt",
                "--segments", "--steps", "--bogus"]), OPTION_VALUES), max_size=3))
    def check(command, options):
        argv = [command] + (["planar2"] if command not in ("demo", "scenes", "nope") else [])
        for opt, val in options:
            argv += [opt, val]
            if opt in ("--band", "--forbidden-band", "--pose"):
                argv += ["0.0", "-10.0"] if opt == "--pose" else ["1.0"]
        if command in ("simulate", "demo") and "--time" not in argv:
            return                   # the long runs are exercised elsewhere
        err, out = io.StringIO(), io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            code = main(argv)
        assert code in (0, 1, 2), code
        if code == 2:
            lines = err.getvalue().splitlines()
            assert len(lines) == 1 and lines[0].startswith("dynstiff: error: "), err.getvalue()
    return check


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)             # any file a command line writes stays here


test_command_line = _cli_fuzzer(FAST)
test_command_line_long = pytest.mark.slow(_cli_fuzzer(1000))


# ---------------------------------------------------------------------- output paths
PATH_CHOICES = ["scene.toml", "m.csv", "link.csv", "sym.csv", "new.csv", "new.nc", "-",
                "sub/../m.csv", "./scene.toml", "other.png"]


def _paths_fuzzer(n):
    @_settings(n)
    @given(command=st.sampled_from(["workspace", "calibrate", "modes", "frf", "sweep"]),
           outputs=st.lists(st.tuples(st.sampled_from(["--csv", "--json", "--plot",
                                                       "--uff", "--out"]),
                                      st.sampled_from(PATH_CHOICES)), max_size=3,
                            unique_by=lambda t: t[0]))
    def check(tmp_path, command, outputs):
        import os

        from dynstiff.cli import build_parser
        from dynstiff.cli.common import check_outputs
        from dynstiff.io.files import OutputPathError
        for name in ("scene.toml", "m.csv"):
            if not (tmp_path / name).exists():
                (tmp_path / name).write_text("old")
        if not (tmp_path / "link.csv").exists():
            os.link(tmp_path / "m.csv", tmp_path / "link.csv")
            os.symlink(tmp_path / "scene.toml", tmp_path / "sym.csv")
            (tmp_path / "sub").mkdir()
        argv = [command, "scene.toml"]
        argv += {"workspace": ["--step", "1"], "calibrate": ["--measured", "m.csv",
                                                              "--parameter", "EA"]}.get(
                                                                  command, [])
        for opt, value in outputs:
            argv += [opt, value]
        try:
            args = build_parser().parse_args(argv)
        except BaseException:            # an option the command does not take
            return
        real = {}
        for opt, value in outputs:
            if value != "-" or opt in ("--plot", "--uff", "--out"):
                real.setdefault(os.path.realpath(value) if value != "sym.csv"
                                else str(tmp_path / "scene.toml"), []).append(opt)
        inputs = {str(tmp_path / "scene.toml")} | (
            {str(tmp_path / "m.csv")} if command == "calibrate" else set())
        hard = {str(tmp_path / "link.csv"): str(tmp_path / "m.csv")}
        merged = {}
        for k, v in real.items():
            merged.setdefault(hard.get(k, k), []).extend(v)
        real = merged
        clash = any(k in inputs or len(v) > 1 for k, v in real.items())
        try:
            check_outputs(args)
        except OutputPathError as exc:
            assert clash, str(exc)
            assert any(opt in str(exc) for opt, _ in outputs)
        except ds.InvalidParameterError:
            pass                         # another check of the same place (a suffix)
        else:
            assert not clash, argv
        assert (tmp_path / "scene.toml").read_text() == "old"
        assert (tmp_path / "m.csv").read_text() == "old"
    return check


test_output_paths = _paths_fuzzer(FAST)
test_output_paths_long = pytest.mark.slow(_paths_fuzzer(3000))
