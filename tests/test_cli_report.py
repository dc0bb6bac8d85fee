"""The `dynstiff` command line, run in this process (conftest.run_cli): the main job `demo`
and `report` (dynstiff/cli/report.py)."""

import re

import pytest
from conftest import run_cli

import dynstiff as ds

pytestmark = [pytest.mark.integration, pytest.mark.usefixtures("no_traceback")]


# --------------------------------------------------------------------------------- demo
def test_demo_main_job_on_cogiro(tmp_path):
    out = run_cli("demo", "--out", tmp_path, "--points", "400")
    assert out.returncode == 0, out.stderr
    import pandas as pd

    import dynstiff as ds
    modes = pd.read_csv(tmp_path / "modes.csv", comment="#")
    ref = ds.eigenfrequencies(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), 40)
    assert len(modes) == 40
    assert abs(modes["freq [Hz]"] / ref - 1).max() < 1e-9
    statics = pd.read_csv(tmp_path / "statics.csv", comment="#")
    assert len(statics) == 8 and (statics["tension at B [N]"] >= 100 - 1e-6).all()
    checks = pd.read_csv(tmp_path / "checks.csv", comment="#")
    assert len(checks) == 7 and checks["passed"].all()
    frf = pd.read_csv(tmp_path / "frf.csv", comment="#")
    # 400 uniform frequencies plus the clusters at the modes of the 0.1-12 Hz band
    assert set(frf["input"]) == {"fx", "fz"} and frf["freq [Hz]"].nunique() > 400
    shapes = sorted(tmp_path.glob("mode_shape_*.png"))      # one per platform mode
    assert len(shapes) == (modes["platform mode"]).sum() >= 6
    for path in [tmp_path / "frf.png", *shapes]:
        assert path.stat().st_size > 10_000
    assert "recommended model: dsm" in out.stdout
    assert "cheapest adequate" not in out.stdout
    head = (tmp_path / "modes.csv").read_text().splitlines()[:12]
    for key in ("dynstiff", "scene", "model", "damping", "pose", "units"):
        assert any(h.startswith(f"# {key}:") for h in head), (key, head)
    assert "platform modal ratio 0.01, cable loss factor 0.01" in out.stdout


def test_demo_and_report_write_one_self_contained_html(tmp_path):
    """report.html: parsed with html.parser, it has the check table, the modes table and
    every figure as a base64 PNG data URI, and no external asset (no src/href to a file
    or a URL, no script)."""
    import base64
    from html.parser import HTMLParser

    class Collect(HTMLParser):
        def __init__(self):
            super().__init__()
            self.tags, self.srcs, self.links, self.text = [], [], [], []

        def handle_starttag(self, tag, attrs):
            self.tags.append(tag)
            a = dict(attrs)
            if "src" in a:
                self.srcs.append(a["src"])
            if "href" in a:
                self.links.append(a["href"])

        def handle_data(self, data):
            self.text.append(data)
    for argv in (["demo", "fourcable"], ["report", "fourcable"]):
        out_dir = tmp_path / argv[0]
        out = run_cli(*argv, "--out", out_dir, "--points", "200")
        assert out.returncode == 0, out.stderr
        p = Collect()
        p.feed((out_dir / "report.html").read_text())
        text = " ".join(p.text)
        assert "script" not in p.tags and "link" not in p.tags
        assert [ln.split(",")[0] for ln in p.links] == ["data:text/csv;base64"]  # modes.csv
        assert base64.b64decode(p.links[0].split(",", 1)[1]).decode() == \
            (out_dir / "modes.csv").read_text()
        shapes = list(out_dir.glob("mode_shape_*.png"))
        assert p.tags.count("table") >= 3 and len(p.srcs) == 1 + len(shapes) > 1
        for src in p.srcs:
            assert src.startswith("data:image/png;base64,")
            assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
        assert "PASS" in text and "Recommended for this band" in text and "damping" in text


def test_demo_and_check_agree_on_every_scene(tmp_path):
    """One source of defaults: on every built-in scene `demo` and `check` print the same
    PASS/FAIL verdicts and the same recommended model (segments included)."""
    def verdicts(text):
        return [ln[:40] for ln in text.splitlines()
                if ln.startswith(("PASS", "FAIL", "UNKNOWN", "n/a"))]

    def recommendation(text):
        m = re.findall(r"recommended model: (\w+)(?: with N = (\d+)| \((\d+) segments)?",
                       text)
        return {(r, n or k) for r, n, k in m}
    for name in ds.list_scenes():
        demo = run_cli("demo", name, "--out", tmp_path / name, "--points", "100")
        check = run_cli("check", name)
        assert demo.returncode == 0 and check.returncode in (0, 1), demo.stderr + check.stderr
        assert verdicts(demo.stdout) == verdicts(check.stdout) != [], name
        rd, rc = recommendation(demo.stdout), recommendation(check.stdout)
        assert len(rd) == 1 and rd == rc, (name, rd, rc)
        assert "band 0.1-12 Hz; forbidden band none" not in demo.stdout


def test_demo_cable_report(tmp_path):
    out = run_cli("demo", "--cable", "--out", tmp_path, "--points", "400")
    assert out.returncode == 0, out.stderr
    assert "in-plane symmetric 1" in out.stdout
    for name in ["report.txt", "statics.csv", "modes.csv", "dynamic_stiffness.png"]:
        assert (tmp_path / name).stat().st_size > 0
    import pandas as pd
    modes = pd.read_csv(tmp_path / "modes.csv", comment="#")
    assert list(modes.columns) == ["freq [Hz]", "Omega [-]", "family", "order"]
    assert modes["freq [Hz]"].is_monotonic_increasing


@pytest.mark.parametrize("argv", [["demo", "--fmax", "-1"],
                                  ["demo", "--damping", "0.01", "0.01", "0", "1"],
                                  ["demo", "--damping", "-0.1"],
                                  ["report", "cogiro", "--damping", "0.01", "2"]])
def test_demo_validates_every_input_before_writing(tmp_path, argv):
    out = run_cli(*argv, "--out", tmp_path / "o")
    assert out.returncode == 2 and "error" in out.stderr
    assert not (tmp_path / "o").exists()


