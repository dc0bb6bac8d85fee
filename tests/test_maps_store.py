"""Resumable workspace maps (dynstiff/maps/store.py, docs/theory.md §13): a run interrupted
by Ctrl-C (a KeyboardInterrupt planted in the per-pose statics) stops with one line saying
how many poses are saved; resumed, serially or on a Dask cluster, it gives the map of an
uninterrupted run bit for bit; a checkpoint of another run is refused."""

import numpy as np
import pytest

import dynstiff as ds
import dynstiff.maps.workspace as wsmod

xr = pytest.importorskip("xarray")
from dynstiff.errors import Interrupted  # noqa: E402
from dynstiff.maps.store import Checkpoint  # noqa: E402

# 4 x 3 poses of CoGiRo (feasible and infeasible ones) in 4 tasks of 3
KW = {"box": (-6.0, 6.0, -4.0, 4.0, 1.0, 1.0), "step": 4.0, "n_modes": 4,
      "band_hz": (0.0, 1.5), "chunk_size": 3}
VOLATILE = ("wall_time_s", "history", "engine")     # differ between any two runs


@pytest.fixture(scope="module")
def robot():
    return ds.load_scene("cogiro").robot


@pytest.fixture(scope="module")
def whole(robot):
    return wsmod.workspace(robot, **KW)


def _interrupt_after(monkeypatch, n_calls):
    calls = [0]
    statics = wsmod.tension_equilibrium

    def planted(*a, **kw):
        calls[0] += 1
        if calls[0] > n_calls:
            raise KeyboardInterrupt
        return statics(*a, **kw)
    monkeypatch.setattr(wsmod, "tension_equilibrium", planted)


def assert_same_map(a, b):
    """Every variable, coordinate and attribute equal, bit for bit (NaN where NaN), but the
    run's wall time, date and engine."""
    a = a.copy()
    b = b.copy()
    for d in (a, b):
        for k in VOLATILE:
            d.attrs.pop(k, None)
    xr.testing.assert_identical(a, b)
    for name in a.data_vars:
        if a[name].dtype == object:                    # the reasons
            assert a[name].values.tolist() == b[name].values.tolist(), name
        else:
            assert a[name].values.tobytes() == b[name].values.tobytes(), name


def test_an_interrupted_run_resumes_to_the_uninterrupted_map(robot, whole, tmp_path,
                                                             monkeypatch):
    cp = tmp_path / "map.parts"
    _interrupt_after(monkeypatch, 7)           # tasks 0 and 1 (6 poses) done, then Ctrl-C
    with pytest.raises(Interrupted, match=r"^workspace interrupted: 6 of 12 poses saved "
                                             r"in .*map.parts; run again with resume=True"):
        wsmod.workspace(robot, checkpoint=cp, **KW)
    assert sorted(p.name for p in cp.iterdir()) == ["chunk-000000.npz", "chunk-000001.npz",
                                                    "run.json"]
    monkeypatch.undo()
    with pytest.raises(ds.InvalidParameterError, match="holds a run already.*resume=True"):
        wsmod.workspace(robot, checkpoint=cp, **KW)
    computed = []
    evaluate = wsmod.evaluate_chunk

    def counted(robot, poses, *a):
        computed.append(len(poses))
        return evaluate(robot, poses, *a)
    monkeypatch.setattr(wsmod, "evaluate_chunk", counted)
    resumed = wsmod.workspace(robot, checkpoint=cp, resume=True, **KW)
    assert computed == [3, 3]                   # only the two tasks not saved
    assert_same_map(resumed, whole)
    assert isinstance(Interrupted("x"), KeyboardInterrupt)


def test_an_interrupt_without_a_checkpoint_says_nothing_is_saved(robot, monkeypatch):
    _interrupt_after(monkeypatch, 1)
    with pytest.raises(Interrupted, match="0 of 12 poses not saved .*checkpoint=") as stop:
        wsmod.workspace(robot, **KW)
    assert (stop.value.saved, stop.value.total) == (0, 12)
    with pytest.raises(ds.InvalidParameterError, match=r"resume=True needs checkpoint= \(the "
                                                       r"folder of the saved chunks\)"):
        wsmod.workspace(robot, resume=True, **KW)


def test_a_checkpoint_of_another_run_is_refused(robot, tmp_path, monkeypatch):
    cp = tmp_path / "map.parts"
    _interrupt_after(monkeypatch, 4)
    with pytest.raises(Interrupted, match="3 of 12"):
        wsmod.workspace(robot, checkpoint=cp, **KW)
    monkeypatch.undo()
    for change in ({"n_modes": 5}, {"chunk_size": 4}, {"band_hz": (0.0, 1.4)},
                   {"step": 3.0}):
        with pytest.raises(ds.InvalidParameterError, match="holds another run"):
            wsmod.workspace(robot, checkpoint=cp, resume=True, **{**KW, **change})


def test_saved_chunks_read_back_exactly(tmp_path):
    cp = Checkpoint(tmp_path / "c", fingerprint="f", n_tasks=3)
    res = {"freq": np.array([1.0, np.nan, 1e-300]), "feasible": np.array([True, False, True]),
           "reason": ["", "InfeasiblePoseError: ünïcode, ; text", ""]}
    cp.save(2, res)
    back = cp.load()
    assert list(back) == [2] and back[2]["reason"] == res["reason"]
    assert back[2]["freq"].tobytes() == res["freq"].tobytes()
    assert back[2]["feasible"].dtype == bool
    cp.remove()
    assert not (tmp_path / "c").exists()


@pytest.mark.integration
def test_a_run_resumed_on_a_dask_cluster_equals_the_serial_map(robot, whole, tmp_path,
                                                               monkeypatch):
    """Interrupted serially, resumed on a real dask.distributed LocalCluster (2 worker
    processes): the same map, bit for bit."""
    distributed = pytest.importorskip("distributed", reason="needs dask.distributed")
    cp = tmp_path / "map.parts"
    _interrupt_after(monkeypatch, 4)
    with pytest.raises(Interrupted, match="3 of 12"):
        wsmod.workspace(robot, checkpoint=cp, **KW)
    monkeypatch.undo()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        resumed = wsmod.workspace(robot, checkpoint=cp, resume=True, client=client, **KW)
    assert_same_map(resumed, whole)
    assert len(list(cp.glob("chunk-*.npz"))) == 4


def test_a_folder_or_file_that_is_not_a_checkpoint_is_refused_and_kept(robot, tmp_path):
    """A user's folder (or file) at the checkpoint's path is refused before any pose, and
    nothing in it is touched; removing a checkpoint leaves foreign files where they are."""
    from dynstiff.maps.store import remove_folder
    user = tmp_path / "map.parts"
    user.mkdir()
    (user / "notes.txt").write_text("mine")
    with pytest.raises(ds.InvalidParameterError, match="notes.txt"):
        wsmod.workspace(robot, checkpoint=user, **KW)
    assert sorted(p.name for p in user.iterdir()) == ["notes.txt"]
    plain = tmp_path / "file.parts"
    plain.write_text("x")
    with pytest.raises(ds.InvalidParameterError, match="not a checkpoint folder"):
        wsmod.workspace(robot, checkpoint=plain, **KW)
    assert plain.read_text() == "x"
    cp = Checkpoint(user, fingerprint="f", n_tasks=1)
    (user / "notes.txt").unlink()
    cp.save(0, {"freq": np.ones(2), "reason": ["", ""]})
    (user / ".chunk-000001.npz.tmp").mkdir()          # the temporary folder of a killed run
    (user / "notes.txt").write_text("mine")           # added by hand after the run began
    remove_folder(user)
    assert sorted(p.name for p in user.iterdir()) == ["notes.txt"]


def test_a_chunk_that_a_checkpoint_does_not_write_is_refused_by_name(tmp_path):
    """A chunk holding a pickled object (which loading would run) or lacking the reasons is
    refused, naming the file; nothing is unpickled."""
    cp = Checkpoint(tmp_path / "c", fingerprint="f", n_tasks=2)
    cp.save(0, {"freq": np.array([1.0]), "reason": [""]})
    np.savez(tmp_path / "c" / "chunk-000001.npz", freq=np.array([{"a": 1}], dtype=object),
             reason=np.array([""]))
    with pytest.raises(ds.InvalidParameterError,
                       match=r"chunk-000001.npz is not a chunk a checkpoint writes"):
        cp.load()
    np.savez(tmp_path / "c" / "chunk-000001.npz", freq=np.array([1.0]))
    with pytest.raises(ds.InvalidParameterError, match="chunk-000001.npz is not a chunk"):
        cp.load()


def test_the_refusal_names_the_first_foreign_file_and_says_when_there_are_more(tmp_path):
    from dynstiff.maps.store import check_folder
    folder = tmp_path / "parts"
    folder.mkdir()
    (folder / "b.txt").write_text("x")
    with pytest.raises(ds.InvalidParameterError, match=r"\('b.txt'\): move them away"):
        check_folder(folder)
    (folder / "a.txt").write_text("x")
    with pytest.raises(ds.InvalidParameterError, match=r"\('a.txt' \.\.\.\): move them away"):
        check_folder(folder)


def test_removing_a_checkpoint_skips_what_is_not_a_folder_and_what_it_cannot_remove(
        tmp_path, monkeypatch):
    """A missing path and a link to a folder are left alone (the linked folder's chunk
    stays); a temporary folder that cannot be removed does not stop the removal of the
    chunks."""
    import shutil

    from dynstiff.maps.store import remove_folder
    remove_folder(tmp_path / "missing")
    real = tmp_path / "real"
    Checkpoint(real, fingerprint="f", n_tasks=1).save(0, {"f": [1.0], "reason": [""]})
    (tmp_path / "link").symlink_to(real, target_is_directory=True)
    remove_folder(tmp_path / "link")
    assert (real / "chunk-000000.npz").is_file()
    (real / ".chunk-000001.npz.tmp").mkdir()          # an interrupted write's folder

    def stubborn(path, ignore_errors=False):
        if not ignore_errors:
            raise PermissionError(f"planted: {path}")
    monkeypatch.setattr(shutil, "rmtree", stubborn)
    remove_folder(real)
    assert not (real / "chunk-000000.npz").exists() and not (real / "run.json").exists()


def test_the_fingerprint_pins_the_pickle_protocol():
    """A run's fingerprint is the SHA-256 of its tasks pickled with protocol 4, whatever the
    Python's default protocol: a checkpoint saved by one Python resumes under another."""
    import hashlib
    import pickle

    from dynstiff.maps.store import fingerprint
    tasks = [(np.arange(3.0), {"n_modes": 4}), ("cogiro", 1.5)]
    h = hashlib.sha256()
    for t in tasks:
        h.update(pickle.dumps(t, protocol=4))
    assert fingerprint(tasks) == h.hexdigest()
    assert pickle.dumps(tasks[0], protocol=4) != pickle.dumps(tasks[0], protocol=5)
