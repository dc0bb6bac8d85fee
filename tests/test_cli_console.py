"""The console of the command line (dynstiff/cli/console.py): progress bars (tqdm) on a
terminal, silenced by --quiet and off where standard error is not a terminal; the first-run
notice of compiling the kernels and where it looks for their cache."""

import io
import sys

import pytest

from dynstiff.cli import main
from dynstiff.cli.console import ProgressBar, elapsed


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def _tty(monkeypatch):
    """Standard error as a terminal (set in the test itself: pytest sets its own capture
    at the start of each phase)."""
    err = _Terminal()
    monkeypatch.setattr(sys, "stderr", err)
    return err


def test_progress_bar_counts_to_the_end_on_a_terminal(monkeypatch):
    tty = _tty(monkeypatch)
    bar = ProgressBar("poses", unit="pose")
    for k in range(1, 5):
        bar(k, 4)
    text = tty.getvalue()
    assert "poses: 100%" in text and "4/4" in text
    assert bar.bar.n == 4


def test_progress_bar_follows_the_terminal_width(monkeypatch):
    """On a terminal the bar takes the terminal's width as it changes (tqdm's dynamic_ncols:
    a function reading the width), not the width it had when the bar started."""
    _tty(monkeypatch)
    bar = ProgressBar("poses")
    bar(1, 3)
    assert callable(bar.bar.dynamic_ncols)
    bar(3, 3)


def test_progress_is_off_when_quiet_or_not_a_terminal(monkeypatch):
    tty = _tty(monkeypatch)
    ProgressBar("poses", quiet=True)(2, 2)
    with elapsed("work", quiet=True):
        pass
    assert tty.getvalue() == ""
    pipe = io.StringIO()                        # not a tty: tqdm switches itself off
    monkeypatch.setattr(sys, "stderr", pipe)
    ProgressBar("poses")(2, 2)
    assert pipe.getvalue() == ""


def test_sweep_draws_its_bar_and_quiet_silences_it(monkeypatch):
    tty = _tty(monkeypatch)
    import dynstiff as ds
    m = ds.load_scene("planar2").robot.platform.mass
    argv = ["sweep", "planar2", "--parameter", "mass", "--values", str(m), str(1.1 * m), "-n",
            "2"]
    assert main(argv) == 0
    assert "sweep planar2: 100%" in tty.getvalue() and "2/2" in tty.getvalue()
    tty.seek(0)
    tty.truncate()
    assert main(argv + ["--quiet"]) == 0
    assert tty.getvalue() == ""


def test_elapsed_shows_the_label_and_the_time(monkeypatch):
    tty = _tty(monkeypatch)
    with elapsed("report planar2"):
        pass
    assert "report planar2: 00:00" in tty.getvalue()      # drawn, then cleared (leave=False)


@pytest.fixture
def cache_places(monkeypatch, tmp_path):
    """numba on; the package's own __pycache__ and NUMBA_CACHE_DIR pointed at empty folders
    of tmp_path (returned), so what the test writes there decides."""
    from pathlib import Path

    from dynstiff import compiled
    from dynstiff.cli import console
    if compiled.load("dsm") is None:
        pytest.skip("numba is not installed")
    pkg = tmp_path / "pkg"
    (pkg / "__pycache__").mkdir(parents=True)
    monkeypatch.setattr(compiled, "__file__", str(pkg / "__init__.py"))
    env = tmp_path / "numba-cache"
    env.mkdir()
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(env))
    assert not console._kernels_cached()
    return Path(pkg / "__pycache__"), env


@pytest.mark.parametrize("where", ["__pycache__", "NUMBA_CACHE_DIR"])
def test_kernels_count_as_cached_where_numba_keeps_them(cache_places, where):
    """The notice of a first compilation looks for the closed form's index file dsm.*.nbi in
    the package's __pycache__ and in NUMBA_CACHE_DIR (any depth), and nowhere else."""
    from dynstiff.cli import console
    folder = cache_places[0] if where == "__pycache__" else cache_places[1] / "a" / "b"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "statics.fixed_point-1.py311.nbi").write_text("")   # another kernel's
    (folder / "DSM.x.NBI").write_text("")
    assert not console._kernels_cached()
    (folder / "dsm.dsm_count-200.py311.nbi").write_text("")
    assert console._kernels_cached()


def test_without_numba_nothing_is_to_compile(monkeypatch):
    """numba absent or switched off: the kernels count as cached (no notice)."""
    from dynstiff import compiled
    from dynstiff.cli import console
    monkeypatch.setattr(compiled, "load", lambda name: None)
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    assert console._kernels_cached()


def test_compile_notice_only_on_a_terminal_with_nothing_cached(cache_places, monkeypatch):
    """With no kernel cached, the notice of a first compilation is written on a terminal
    (by default, and not with quiet), never into a pipe or a file."""
    from dynstiff.cli.console import compile_notice
    tty = _tty(monkeypatch)
    compile_notice()
    assert tty.getvalue() == ("dynstiff: first run: compiling the numerical kernels (once, "
                              "about 20 s; then cached on disk)\n")
    tty = _tty(monkeypatch)
    compile_notice(quiet=True)
    assert tty.getvalue() == ""
    pipe = io.StringIO()
    monkeypatch.setattr(sys, "stderr", pipe)
    compile_notice()
    assert pipe.getvalue() == ""
    (cache_places[0] / "dsm.dsm_count-200.py311.nbi").write_text("")     # now cached
    tty = _tty(monkeypatch)
    compile_notice()
    assert tty.getvalue() == ""
