"""Output paths checked against the inputs and written atomically (dynstiff/io/files.py):
the same file by name, through a symbolic link and through a hard link is refused naming
both arguments; a writer that fails leaves the old file byte for byte."""

import os
import re

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.io.files import OutputPathError, atomic_path, check_paths, input_file, write_text


@pytest.fixture
def scene(tmp_path):
    p = tmp_path / "scene.toml"
    p.write_text("name = 'x'\n")
    return p


@pytest.mark.parametrize("how", ["same", "relative", "symlink", "hardlink"])
def test_an_output_that_is_an_input_is_refused_naming_both(tmp_path, scene, how, monkeypatch):
    monkeypatch.chdir(tmp_path)
    other = {"same": str(scene), "relative": "./sub/../scene.toml",
             "symlink": tmp_path / "link.toml", "hardlink": tmp_path / "hard.toml"}[how]
    (tmp_path / "sub").mkdir()
    if how == "symlink":
        os.symlink(scene, other)
    elif how == "hardlink":
        os.link(scene, other)
    with pytest.raises(OutputPathError, match=r"--csv .* is the same file as scene .*"
                                              r"never replaces an input") as exc:
        check_paths([("scene", scene)], [("--csv", other)])
    assert isinstance(exc.value, InvalidParameterError) and str(scene) in str(exc.value)
    assert f"({os.path.realpath(other)})" in str(exc.value)   # the output file, resolved


def test_two_outputs_on_one_file_and_distinct_files(tmp_path, scene):
    with pytest.raises(OutputPathError, match="--csv .* same file as --out .* two outputs") \
            as exc:
        check_paths([("scene", scene)], [("--out", tmp_path / "x.nc"),
                                         ("--csv", tmp_path / "x.nc")])
    assert f"({os.path.realpath(tmp_path / 'x.nc')})" in str(exc.value)
    # distinct files, standard output twice and options not given pass
    check_paths([("scene", scene), ("--measured", None)],
                [("--out", tmp_path / "x.nc"), ("--csv", "-"), ("--json", "-"),
                 ("--plot", None), ("--uff", tmp_path / "x.uff")])


def test_atomic_path_replaces_on_success_and_keeps_the_old_file_on_failure(tmp_path):
    target = tmp_path / "table.csv"
    target.write_bytes(b"old,data\n1,2\n")
    before = target.stat()
    with pytest.raises(RuntimeError, match="planted"):
        with atomic_path(target) as tmp:
            with open(tmp, "w") as fh:
                fh.write("half a tab")
            raise RuntimeError("planted")
    assert target.read_bytes() == b"old,data\n1,2\n"
    assert target.stat().st_mtime_ns == before.st_mtime_ns
    assert sorted(os.listdir(tmp_path)) == ["table.csv"]            # no temporary left
    write_text(target, "new\n")
    assert target.read_text() == "new\n" and sorted(os.listdir(tmp_path)) == ["table.csv"]
    # mode of a fresh file follows the umask, as open() would give it
    umask = os.umask(0)
    os.umask(umask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~umask


def test_atomic_path_replaces_a_store_folder_and_keeps_its_suffix(tmp_path):
    store = tmp_path / "map.zarr"
    store.mkdir()
    (store / "old").write_text("old")
    with atomic_path(store) as tmp:
        assert tmp.endswith("map.zarr") and os.path.dirname(os.path.dirname(tmp)) == str(
            tmp_path)
        os.mkdir(tmp)
        np.save(os.path.join(tmp, "a.npy"), np.arange(3))
    assert sorted(os.listdir(store)) == ["a.npy"]
    assert sorted(os.listdir(tmp_path)) == ["map.zarr"]
    with pytest.raises(FileNotFoundError, match="wrote nothing"):
        with atomic_path(tmp_path / "none.csv"):
            pass
    assert sorted(os.listdir(tmp_path)) == ["map.zarr"]


def test_write_text_encodes_as_asked(tmp_path):
    """UTF-8 by default, whatever the locale; another encoding when given."""
    target = tmp_path / "note.txt"
    assert write_text(target, "\u00e9") == target
    assert target.read_bytes() == b"\xc3\xa9"
    write_text(target, "\u00e9", encoding="latin-1")
    assert target.read_bytes() == b"\xe9"


@pytest.mark.parametrize("reader", ["read_measured_modes", "read_measured_frf"])
def test_readers_say_what_is_wrong_with_the_path_before_reading(tmp_path, reader):
    """None was read as a file named 'None'; a folder or a missing file given to the UFF
    reader came out as pyuff's bare Exception, which the command line does not catch."""
    import dynstiff as ds
    read = getattr(ds, reader)
    with pytest.raises(ds.InvalidParameterError, match="^path must be a path"):
        read(None)
    with pytest.raises(IsADirectoryError):
        read(tmp_path)
    with pytest.raises(FileNotFoundError):
        read(tmp_path / "missing.uff")


def test_input_file_returns_the_path_as_str_or_says_why_not(tmp_path):
    """input_file: a str, a PathLike or a PathLike that gives bytes, of an existing file,
    comes back as its str; what is not a path (bytes itself included) is refused naming
    the argument and the value, a folder is an
    IsADirectoryError (errno 21) and a missing file a FileNotFoundError (errno 2), each
    naming the path."""
    f = tmp_path / "m.csv"
    f.write_text("x")
    class BytesPath:
        def __fspath__(self):
            return os.fsencode(str(f))
    for given in (str(f), f, BytesPath()):
        got = input_file(given)
        assert got == str(f) and type(got) is str
    for bad in (None, 5, 1.5, ["a"], os.fsencode(str(f))):
        with pytest.raises(InvalidParameterError,
                           match=rf"^measured must be a path \(str or os.PathLike\), got "
                                 rf"{re.escape(repr(bad))}$"):
            input_file(bad, "measured")
    with pytest.raises(InvalidParameterError, match="^path must be a path"):
        input_file(None)
    with pytest.raises(IsADirectoryError) as err:
        input_file(tmp_path)
    assert (err.value.errno, err.value.strerror, err.value.filename) == (
        21, "Is a directory", str(tmp_path))
    with pytest.raises(FileNotFoundError) as err:
        input_file(tmp_path / "missing.csv")
    assert (err.value.errno, err.value.strerror, err.value.filename) == (
        2, "No such file", str(tmp_path / "missing.csv"))
