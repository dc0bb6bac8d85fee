"""The console of the ``dynstiff`` command: the package's warnings as one line each, and
progress bars (tqdm) on standard error, off with ``--quiet`` or when standard error is not a
terminal."""

import contextlib
import sys

__all__ = ["ProgressBar", "compile_notice", "elapsed", "one_line_warnings"]


@contextlib.contextmanager
def one_line_warnings(stream=None):
    """Within the block, show each :class:`dynstiff.errors.DynstiffWarning` as one line
    ``dynstiff: warning: MESSAGE`` on standard error (no file path, no source line); another
    library's warning as ``dynstiff: warning: CATEGORY: MESSAGE``."""
    import warnings

    from dynstiff.errors import DynstiffWarning
    previous = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        text = " ".join(str(message).split())
        if not issubclass(category, DynstiffWarning):
            text = f"{category.__name__}: {text}"
        out = stream or sys.stderr
        try:
            from tqdm import tqdm
            tqdm.write(f"dynstiff: warning: {text}", file=out)   # not through a live bar
        except ImportError:                                      # pragma: no cover
            out.write(f"dynstiff: warning: {text}\n")
    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = previous


def _tqdm(quiet, **kw):
    from tqdm import tqdm
    # disable=None: tqdm switches itself off when standard error is not a terminal
    return tqdm(file=sys.stderr, disable=True if quiet else None, dynamic_ncols=True, **kw)


class ProgressBar:
    """A ``progress(done, total)`` callable drawing a tqdm bar on standard error."""

    def __init__(self, label, quiet=False, unit="step"):
        self.label, self.quiet, self.unit = label, quiet, unit
        self.bar = None

    def __call__(self, done, total):
        if self.bar is None:
            self.bar = _tqdm(self.quiet, total=total, desc=self.label, unit=self.unit)
        self.bar.update(done - self.bar.n)
        if done >= total:
            self.close()

    def close(self):
        if self.bar is not None:
            self.bar.close()


@contextlib.contextmanager
def elapsed(label, quiet=False):
    """A bar that shows ``label`` and the time elapsed while the block runs (work that
    reports no steps); it is cleared at the end."""
    import threading
    bar = _tqdm(quiet, total=None, desc=label, bar_format="{desc}: {elapsed}", leave=False)
    stop = threading.Event()

    def tick():
        while not stop.wait(0.5):
            bar.refresh()
    thread = threading.Thread(target=tick, daemon=True)
    if not bar.disable:
        thread.start()
    try:
        yield bar
    finally:
        stop.set()
        if thread.is_alive():
            thread.join()
        bar.close()


def _kernels_cached():
    """Whether numba's on-disk cache holds the compiled kernels (True without numba)."""
    import os
    from pathlib import Path

    from dynstiff import compiled
    if compiled.load("dsm") is None:                 # numba absent or switched off
        return True
    folders = [Path(compiled.__file__).parent / "__pycache__"]
    if os.environ.get("NUMBA_CACHE_DIR"):
        folders.append(Path(os.environ["NUMBA_CACHE_DIR"]))
    return any(any(f.rglob("dsm.*.nbi")) for f in folders if f.is_dir())


def compile_notice(quiet=False):
    """On the first run (numba installed, no compiled kernel cached on disk), say on standard
    error that the kernels are being compiled, so that the wait is not taken for a hang."""
    if quiet or not sys.stderr.isatty() or _kernels_cached():
        return
    sys.stderr.write("dynstiff: first run: compiling the numerical kernels (once, about "
                     "20 s; then cached on disk)\n")
