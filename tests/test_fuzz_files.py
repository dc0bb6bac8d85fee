"""Hostile files, with the oracle of tests/test_fuzz.py (conftest.obey_the_rule): scene files
with bad values of each key (dynstiff/scenes), measured tables with bad cells and headers
(dynstiff/analyses/measured.py), atomic writes that fail at each step (dynstiff/io/files.py)
and UFF files of non-finite FRFs (FRFResult.to_uff). The readers and writers add one more
rule: on an error, no file is changed. Tiers as in tests/test_fuzz.py (``-m slow``: 8,500
examples here).
"""

import numpy as np
import pytest
from conftest import FAST, LONG, _settings, obey_the_rule, weird_vectors
from hypothesis import example, given
from hypothesis import strategies as st

import dynstiff as ds


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)             # any file a command line writes stays here


# ---------------------------------------------------------------------- scene files
KEYS = ["mass", "EA", "mass_per_length", "anchor", "attachment", "free_dofs", "g",
        "position", "band_hz", "n_modes", "min", "inertia"]


def _toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "").replace('"', "") + '"'
    if isinstance(v, float) and not np.isfinite(v):
        return "nan" if np.isnan(v) else ("inf" if v > 0 else "-inf")
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if v is None or isinstance(v, complex):
        return '"none"'
    return repr(v)


def _scene_fuzzer(n):
    @_settings(n)
    @given(key=st.sampled_from(KEYS), value=weird_vectors)
    @example(key="EA", value=7.930652811838276e-308)  # a strain beyond the float range
    def check(tmp_path_factory, key, value):
        text = (ds.scenes.loader.SCENE_DIR / "planar2.toml").read_text()
        lines = text.splitlines()
        for i, line in enumerate(lines):
            if line.split("=")[0].strip() == key:
                lines[i] = f"{key} = {_toml_value(value)}"
                break
        else:
            lines.append(f"{key} = {_toml_value(value)}")
        p = tmp_path_factory.mktemp("scene") / "fuzz.toml"
        p.write_text("\n".join(lines) + "\n")
        scene = obey_the_rule(lambda: ds.load_scene(p), (str(p),))
        if scene is not None and scene.pose is not None:
            obey_the_rule(scene.equilibrium, ("pose", "slack", "tension", "converge",
                                              "workspace"))
    return check


test_scene_files = _scene_fuzzer(FAST)
test_scene_files_long = pytest.mark.slow(_scene_fuzzer(LONG))


# ------------------------------------------------------------------ readers and writers
CELLS = st.one_of(st.sampled_from(["4.2", "0,5", "", "nan", "inf", "-1", "1e400", "x",
                                   "\"1,2\"", " 3 ", "#", "1.0.0", "0x10", "½"]),
                  st.floats(allow_nan=True).map(repr), st.text(max_size=5))
HEADERS = st.lists(st.sampled_from(["freq [Hz]", "frequency [Hz]", "x", "z [m]", "rz",
                                    "sigma [Hz]", "damping ratio [-]", "note", "x"]),
                   max_size=4)


def _reader_fuzzer(n):
    @_settings(n)
    @given(header=HEADERS, rows=st.lists(st.lists(CELLS, max_size=5), max_size=4),
           comment=st.booleans())
    def check(tmp_path, header, rows, comment):
        path = tmp_path / "measured.csv"
        text = ("# scene: \"x\"\n" if comment else "") + "\n".join(
            ",".join(r) for r in [header, *rows])
        path.write_bytes(text.encode("utf-8", "surrogatepass"))
        from dynstiff.analyses.measured import read_measured_modes
        # NaN in a shape is "not measured": the frequencies, sigma and damping are finite
        def numbers():
            r = read_measured_modes(path)
            return [r.freq_hz] + [v for v in (r.sigma_hz, r.damping_ratio) if v is not None]
        m = obey_the_rule(numbers, [str(path)])
        if m is not None:
            assert np.all(m[0] > 0)
        assert path.read_bytes() == text.encode("utf-8", "surrogatepass")
    return check


test_measured_tables = _reader_fuzzer(FAST)
test_measured_tables_long = pytest.mark.slow(_reader_fuzzer(4000))


def _writer_fuzzer(n):
    @_settings(n)
    @given(text=st.text(max_size=50), fail_at=st.one_of(st.none(), st.integers(0, 3)),
           store=st.booleans())
    def check(tmp_path, text, fail_at, store):
        from dynstiff.io.files import atomic_path, write_text
        target = tmp_path / ("old.zarr" if store else "old.csv")
        if store:
            target.mkdir(exist_ok=True)
            (target / "a").write_text("old")
        else:
            target.write_text("old")
        before = sorted(p.name for p in tmp_path.iterdir())
        try:
            with atomic_path(target) as tmp:
                for step in range(4):
                    if step == fail_at:
                        raise OSError("planted")
                    if step == 1:
                        if store:
                            import os
                            os.mkdir(tmp)
                            write_text(os.path.join(tmp, "a"), text)
                        else:
                            write_text(tmp, text)
        except OSError as exc:
            assert "planted" in str(exc) or "wrote nothing" in str(exc)
            assert (target / "a" if store else target).read_text() == "old"
        else:
            with open(target / "a" if store else target, encoding="utf-8", newline="") as fh:
                assert fh.read() == text
        assert sorted(p.name for p in tmp_path.iterdir()) == before
    return check


test_atomic_writes = _writer_fuzzer(FAST)
test_atomic_writes_long = pytest.mark.slow(_writer_fuzzer(1500))


def _uff_fuzzer(n):
    @_settings(n)
    @given(bad=st.lists(st.sampled_from([np.nan, np.inf, -np.inf, 1.0, 1e308]), min_size=1,
                        max_size=3), kind=st.sampled_from(["receptance", "mobility",
                                                            "compliance"]))
    def check(tmp_path, bad, kind):
        pytest.importorskip("pyuff")
        path = tmp_path / "old.uff"
        path.write_bytes(b"an old file")
        H = np.ones((len(bad) + 1, 1, 1), complex)
        H[1:, 0, 0] = bad
        res = ds.FRFResult(np.arange(1.0, len(bad) + 2), H, ("fz",), ("z",), kind)
        got = obey_the_rule(lambda: res.to_uff(path), ["inf or NaN", "kind"])
        if got is None:
            assert path.read_bytes() == b"an old file"
        else:
            assert np.all(np.isfinite(H)) and kind != "compliance"
        assert [p.name for p in tmp_path.iterdir()] == ["old.uff"]
    return check


test_uff_writer = _uff_fuzzer(FAST)
test_uff_writer_long = pytest.mark.slow(_uff_fuzzer(500))
