"""Registering the ``dataset.dynstiff`` accessor in either import order (dynstiff/maps/__init__.py):
register_accessor() and the one-shot meta-path hook _XarrayHook, in process (the fresh-interpreter
import-order checks are the integration tests)."""

import importlib.machinery
import importlib.util
import sys

import pytest

import dynstiff.maps as maps
from dynstiff.maps import _XarrayHook, register_accessor

DATASET = "dynstiff.maps.dataset"


@pytest.fixture
def meta_path(monkeypatch):
    """A private sys.meta_path without any _XarrayHook (the real one is restored afterwards)."""
    path = [f for f in sys.meta_path if not isinstance(f, _XarrayHook)]
    monkeypatch.setattr(sys, "meta_path", path)
    return path


@pytest.fixture
def fresh_dataset(monkeypatch):
    """Hide dynstiff.maps.dataset and its accessor: a new import of it is visible and quiet."""
    xr = pytest.importorskip("xarray")
    old = importlib.import_module(DATASET)
    monkeypatch.delitem(sys.modules, DATASET)
    monkeypatch.setattr(maps, "dataset", old)          # the re-import rebinds the attribute
    monkeypatch.delattr(xr.Dataset, "dynstiff")        # else xarray warns of an override

    def check():
        new = sys.modules[DATASET]
        assert new is not old
        assert xr.Dataset.dynstiff is new.WorkspaceAccessor
    return check


class _Loader:
    """A loader that records the modules it runs and whether the accessor was imported then."""

    def __init__(self):
        self.ran = []

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        self.ran.append((module, DATASET in sys.modules))
        module.ran = True


def _fake_find_spec(monkeypatch, spec):
    """Make importlib.util.find_spec return ``spec``, recording each name and sys.meta_path."""
    calls = []

    def find_spec(name, package=None):
        calls.append((name, list(sys.meta_path)))
        return spec
    monkeypatch.setattr(importlib.util, "find_spec", find_spec)
    return calls


def test_without_xarray_one_hook_is_inserted_first_and_only_once(monkeypatch, meta_path):
    """Without xarray imported, a first call puts one hook at meta_path[0], a second none."""
    monkeypatch.delitem(sys.modules, "xarray", raising=False)
    before = list(meta_path)
    register_accessor()
    assert isinstance(sys.meta_path[0], _XarrayHook) and sys.meta_path[1:] == before
    hook = sys.meta_path[0]
    register_accessor()
    assert sys.meta_path[0] is hook and sys.meta_path[1:] == before


def test_with_xarray_the_accessor_is_imported_now_and_no_hook(meta_path, fresh_dataset):
    """With xarray imported, the call imports dynstiff.maps.dataset and inserts no hook."""
    before = list(meta_path)
    register_accessor()
    fresh_dataset()
    assert sys.meta_path == before


def test_hook_ignores_other_modules(meta_path):
    """For a name other than xarray the hook finds nothing and stays in sys.meta_path."""
    hook = _XarrayHook()
    meta_path.insert(0, hook)
    assert hook.find_spec("numpy") is None
    assert hook.find_spec("xarray.core", ["somewhere"]) is None
    assert sys.meta_path[0] is hook


def test_hook_removes_itself_then_wraps_the_real_xarray_spec(monkeypatch, meta_path):
    """For xarray the hook leaves sys.meta_path, returns xarray's own spec, its loader wrapped."""
    xr = pytest.importorskip("xarray")
    monkeypatch.delitem(sys.modules, "xarray")       # a fresh search, a fresh loader
    hook = _XarrayHook()
    meta_path.insert(0, hook)
    spec = hook.find_spec("xarray")
    assert hook not in sys.meta_path
    assert spec.name == "xarray" and spec.origin == xr.__spec__.origin
    assert spec.loader is not xr.__spec__.loader
    assert "exec_module" in vars(spec.loader)          # wrapped on this fresh loader only


def test_wrapped_exec_module_runs_xarray_then_imports_the_accessor(monkeypatch, meta_path,
                                                                   fresh_dataset):
    """The wrapped exec_module runs the module first, then imports dynstiff.maps.dataset."""
    loader = _Loader()
    spec = importlib.machinery.ModuleSpec("xarray", loader)
    calls = _fake_find_spec(monkeypatch, spec)
    hook = _XarrayHook()
    meta_path.insert(0, hook)
    assert hook.find_spec("xarray") is spec and spec.loader is loader
    assert [name for name, _ in calls] == ["xarray"]
    assert all(not isinstance(f, _XarrayHook) for f in calls[0][1])   # removed before the search
    assert hook not in sys.meta_path
    module = importlib.util.module_from_spec(spec)
    assert loader.ran == []
    loader.exec_module(module)
    assert loader.ran == [(module, False)] and module.ran
    fresh_dataset()


@pytest.mark.parametrize("spec", [
    None,
    importlib.machinery.ModuleSpec("xarray", None),
    importlib.machinery.ModuleSpec("xarray", object()),
], ids=["no spec", "no loader", "loader without exec_module"])
def test_hook_returns_a_spec_it_cannot_wrap_unchanged(monkeypatch, meta_path, spec):
    """No spec, a spec without loader or a loader without exec_module comes back as it is."""
    loader = None if spec is None else spec.loader
    _fake_find_spec(monkeypatch, spec)
    hook = _XarrayHook()
    meta_path.insert(0, hook)
    assert hook.find_spec("xarray") is spec
    assert hook not in sys.meta_path
    if spec is not None:
        assert spec.loader is loader and not hasattr(spec.loader, "exec_module")
