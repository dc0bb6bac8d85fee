"""The saved chunks of a workspace map, so that an interrupted run resumes (docs/theory.md §13.8).

A checkpoint is a folder: ``run.json`` (a fingerprint of everything the numbers depend on:
the poses, the robots, the options, the model and the chunking) and one
``chunk-NNNNNN.npz`` per completed task (the arrays of
:func:`dynstiff.maps.workspace.evaluate_chunk`, written atomically as each task completes).
A task's numbers depend only on its own poses and settings, so the saved chunks joined to
the rest computed later give the map of an uninterrupted run, bit for bit.

Example
-------
>>> import tempfile, numpy as np
>>> from dynstiff.maps.store import Checkpoint
>>> cp = Checkpoint(tempfile.mkdtemp() + "/map.parts", fingerprint="abc", n_tasks=2)
>>> cp.save(1, {"freq": np.arange(3.0), "reason": ["", "x", ""]})
>>> sorted(cp.load())
[1]
"""

import hashlib
import json
import os
import pickle
import re
import shutil

import numpy as np

from dynstiff.errors import InvalidParameterError

__all__ = ["Checkpoint", "check_folder", "fingerprint", "remove_folder", "resumed"]

_OURS = re.compile(r"(run\.json|chunk-\d{6}\.npz)$|\.(run\.json|chunk-\d{6}\.npz)\.")


def _ours(name):
    """An entry a checkpoint writes: run.json, its chunks and their temporary folders
    (:func:`dynstiff.io.files.atomic_path`)."""
    return bool(_OURS.match(name))


def check_folder(path):
    """Refuse ``path`` as a checkpoint folder when it is a file or a folder holding anything a
    checkpoint does not write (its files would be mixed with, then removed as, the saved
    chunks); a missing folder or a checkpoint's own folder passes.

    Raises
    ------
    InvalidParameterError
        Naming the path and the first foreign entry.

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.mkdtemp()
    >>> check_folder(os.path.join(folder, "map.nc.parts"))     # missing: a checkpoint may go there
    >>> open(os.path.join(folder, "notes.txt"), "w").close()
    >>> try:
    ...     check_folder(folder)
    ... except ValueError as exc:
    ...     print(str(exc).split(": ")[0].split("holds ")[1])
    files a checkpoint does not write ('notes.txt')
    """
    path = os.fspath(path)
    if not os.path.lexists(path):
        return
    if os.path.islink(path) or not os.path.isdir(path):
        raise InvalidParameterError(
            f"checkpoint {path} exists and is not a checkpoint folder: move it away or give "
            f"another output name")
    foreign = sorted(n for n in os.listdir(path) if not _ours(n))
    if foreign:
        raise InvalidParameterError(
            f"checkpoint {path} holds files a checkpoint does not write ({foreign[0]!r}"
            f"{' ...' if len(foreign) > 1 else ''}): move them away or give another output name")


def remove_folder(path):
    """Delete a checkpoint's own files (run.json, the chunks, their temporary files) and the
    folder when that leaves it empty; anything else in it is left where it is.

    Examples
    --------
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "map.nc.parts")
    >>> Checkpoint(path, fingerprint="abc", n_tasks=1).save(0, {"f": [1.0], "reason": [""]})
    >>> remove_folder(path); os.path.exists(path)
    False
    """
    path = os.fspath(path)
    if not os.path.isdir(path) or os.path.islink(path):
        return
    for name in os.listdir(path):
        entry = os.path.join(path, name)
        if not _ours(name) or os.path.islink(entry):
            continue
        if os.path.isdir(entry):
            shutil.rmtree(entry, ignore_errors=True)
        else:
            os.remove(entry)
    try:
        os.rmdir(path)
    except OSError:
        pass


def fingerprint(tasks):
    """SHA-256 of the tasks' arguments (robots, poses, options, model, chunking): two runs
    with the same fingerprint compute the same numbers."""
    h = hashlib.sha256()
    for args in tasks:
        h.update(pickle.dumps(args, protocol=4))
    return h.hexdigest()


class Checkpoint:
    """The folder of saved chunks of one run (module notes).

    Parameters
    ----------
    path : str or path-like
        The folder (created when the first chunk is saved).
    fingerprint : str
        Of the run (:func:`fingerprint`).
    n_tasks : int
    """

    def __init__(self, path, fingerprint, n_tasks):
        self.path, self.fingerprint, self.n_tasks = os.fspath(path), fingerprint, n_tasks

    def _chunk(self, i):
        return os.path.join(self.path, f"chunk-{i:06d}.npz")

    def exists(self):
        """True when the folder holds a run."""
        return os.path.isfile(os.path.join(self.path, "run.json"))

    def _start(self):
        from dynstiff.io.files import write_text
        if not self.exists():
            os.makedirs(self.path, exist_ok=True)
            write_text(os.path.join(self.path, "run.json"), json.dumps(
                {"fingerprint": self.fingerprint, "n_tasks": self.n_tasks}) + "\n")

    def save(self, i, result):
        """Save the result of task ``i`` (a dict of arrays and the list ``reason``)."""
        from dynstiff.io.files import atomic_path
        self._start()
        arrays = {k: np.asarray(v) for k, v in result.items() if k != "reason"}
        arrays["reason"] = np.asarray(result["reason"], dtype=str)
        with atomic_path(self._chunk(i)) as tmp:
            np.savez(tmp, **arrays)

    def load(self):
        """The saved results, {task index: result}; refuses a folder of another run."""
        if not self.exists():
            return {}
        with open(os.path.join(self.path, "run.json"), encoding="utf-8") as fh:
            meta = json.load(fh)
        if meta.get("fingerprint") != self.fingerprint or meta.get("n_tasks") != self.n_tasks:
            raise InvalidParameterError(
                f"checkpoint {self.path} holds another run (other poses, robot, options or "
                f"chunk size): resume with the same settings, or remove the folder")
        out = {}
        for i in range(self.n_tasks):
            if os.path.isfile(self._chunk(i)):
                try:       # no pickled objects: a chunk holds plain arrays, nothing to run
                    with np.load(self._chunk(i), allow_pickle=False) as z:
                        res = {k: z[k] for k in z.files}
                    res["reason"] = [str(r) for r in res["reason"]]
                except (ValueError, OSError, KeyError) as exc:
                    raise InvalidParameterError(
                        f"checkpoint {self.path}: {os.path.basename(self._chunk(i))} is not a "
                        f"chunk a checkpoint writes ({exc}): remove the folder") from None
                out[i] = res
        return out

    def remove(self):
        """Delete the saved chunks (after the map is written): :func:`remove_folder`."""
        remove_folder(self.path)


def resumed(tasks, checkpoint, resume):
    """The results already saved in ``checkpoint`` (a list, None where a task is to be
    computed) and the function that saves a completed task."""
    results = [None] * len(tasks)
    if checkpoint is None:
        if resume:
            raise InvalidParameterError("resume=True needs checkpoint= (the folder of the "
                                        "saved chunks)")
        return results, lambda i: None
    check_folder(checkpoint)
    store = Checkpoint(checkpoint, fingerprint(tasks), len(tasks))
    if store.exists() and not resume:
        raise InvalidParameterError(
            f"checkpoint {checkpoint} holds a run already: give resume=True (--resume) to "
            f"continue it, or remove the folder")
    for i, res in store.load().items():
        results[i] = res
    return results, lambda i: store.save(i, results[i])
