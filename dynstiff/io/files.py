"""Output files that never destroy inputs: the paths checked before any work, and written
atomically.

* :func:`check_paths` refuses an output path that is one of the inputs, or another output,
  of the same call: the same file by name, through a symbolic link or a hard link
  (``os.path.realpath`` and the file's device and inode). ``-`` (standard output) and
  ``None`` (not asked) are skipped.
* :func:`atomic_path` gives a writer a path in a fresh hidden folder beside the target,
  with the target's own name (so that a writer that reads the format from the suffix, as
  matplotlib and xarray do, sees it); when the writer returns, the file (or a folder, e.g.
  a Zarr store) replaces the target in one ``os.replace``; when it raises, the temporary
  is removed and the target is left as it was. :func:`write_text` writes a string that way.

Example
-------
>>> import os, tempfile
>>> from dynstiff.io.files import check_paths, write_text
>>> d = tempfile.mkdtemp()
>>> scene = os.path.join(d, "scene.toml")
>>> _ = write_text(scene, "name = 'x'\\n")
>>> check_paths(inputs=[("scene", scene)], outputs=[("--csv", scene)])
Traceback (most recent call last):
...
dynstiff.io.files.OutputPathError: --csv ... is the same file as scene ...
"""

import contextlib
import os
import shutil
import tempfile

from dynstiff.errors import InvalidParameterError

__all__ = ["OutputPathError", "atomic_path", "check_paths", "write_text"]


class OutputPathError(InvalidParameterError):
    """An output path is an input (or another output) of the same call; the message names
    both arguments and the file."""


def input_file(path, name="path"):
    """``path`` as a str, checked to be an existing file before anything reads it: a value
    that is not a path is an InvalidParameterError naming ``name``, a missing file a
    FileNotFoundError and a folder an IsADirectoryError (an OSError each, as ``open`` gives,
    whatever the reader behind it, pyuff included).

    >>> input_file(5)
    Traceback (most recent call last):
    ...
    dynstiff.errors.InvalidParameterError: path must be a path (str or os.PathLike), got 5
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InvalidParameterError(f"{name} must be a path (str or os.PathLike), got {path!r}")
    path = os.fspath(path)
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if os.path.isdir(path):
        raise IsADirectoryError(21, "Is a directory", path)
    if not os.path.isfile(path):
        raise FileNotFoundError(2, "No such file", path)
    return path


def _identity(path):
    """(real path, (device, inode) or None) of ``path``."""
    real = os.path.realpath(os.fspath(path))
    try:
        st = os.stat(real)
    except OSError:
        return real, None
    return real, (st.st_dev, st.st_ino)


def _same(a, b):
    return a[0] == b[0] or (a[1] is not None and a[1] == b[1])


def check_paths(inputs=(), outputs=()):
    """Refuse an output that would overwrite an input or another output.

    Parameters
    ----------
    inputs, outputs : sequence of (str, path or None)
        (argument name, path) pairs; a path of None or ``"-"`` (standard output) is not a
        file and is skipped.

    Raises
    ------
    OutputPathError
        Naming the two arguments and the file, e.g. ``--csv m.csv is the same file as
        --measured m.csv (/data/m.csv): an output never replaces an input``.
    """
    def files(pairs):
        return [(name, p, _identity(p)) for name, p in pairs
                if p is not None and os.fspath(p) != "-"]
    ins, outs = files(inputs), files(outputs)
    for k, (name, p, ident) in enumerate(outs):
        for other, q, ident_q in ins:
            if _same(ident, ident_q):
                raise OutputPathError(
                    f"{name} {os.fspath(p)} is the same file as {other} {os.fspath(q)} "
                    f"({ident[0]}): an output never replaces an input; give another name")
        for other, q, ident_q in outs[:k]:
            if _same(ident, ident_q):
                raise OutputPathError(
                    f"{name} {os.fspath(p)} is the same file as {other} {os.fspath(q)} "
                    f"({ident[0]}): two outputs cannot share one file; give another name")


@contextlib.contextmanager
def atomic_path(path):
    """A temporary path for a writer; the target ``path`` is replaced only when the
    ``with`` block ends without an error (module notes).

    Parameters
    ----------
    path : str or path-like
        The target file (or folder, for a store such as Zarr); its folder must exist.

    Yields
    ------
    str
        Where to write: ``<folder>/.<name>.<random>/<name>``.
    """
    target = os.fspath(path)
    folder, name = os.path.split(os.path.abspath(target))
    tmpdir = tempfile.mkdtemp(prefix=f".{name}.", dir=folder)
    tmp = os.path.join(tmpdir, name)
    try:
        yield tmp
        if not os.path.lexists(tmp):
            raise FileNotFoundError(f"{target}: the writer wrote nothing")
        if os.path.isdir(tmp) and os.path.isdir(target) and not os.path.islink(target):
            os.replace(target, os.path.join(tmpdir, ".old"))   # a store: set the old aside
        os.replace(tmp, target)
    finally:
        shutil.rmtree(tmpdir, ignore_errors=True)


def write_text(path, text, encoding="utf-8"):
    """Write ``text`` to ``path`` atomically (:func:`atomic_path`); returns ``path``."""
    with atomic_path(path) as tmp, open(tmp, "w", encoding=encoding) as fh:
        fh.write(text)
    return path
