"""The Python blocks of the documentation's pages (docs/getting_started.md and the user
guide, docs/guide/*.md) run as written, in order, one namespace per page: the API they
show is the API there is. Blocks that take long (the pendulum's point-mass Floquet
analysis) run in the slow tier. The CASPR examples read the CASPR files of tests/data."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "docs" / "getting_started.md", *sorted((ROOT / "docs" / "guide").glob("*.md"))]
CASPR_DATA = ROOT / "tests" / "data" / "caspr"
SLOW_CALLS = ("floquet(", "stability_map(")


def blocks(page):
    return re.findall(r"```python\n(.*?)```", page.read_text(), re.S)


def run_page(page, monkeypatch, fast_only):
    monkeypatch.chdir(CASPR_DATA)
    ns = {}
    try:
        for i, code in enumerate(blocks(page)):
            if fast_only and any(s in code for s in SLOW_CALLS):
                continue
            exec(compile(code, f"{page.relative_to(ROOT)} python block {i}", "exec"), ns)
    finally:
        plt.close("all")
    return ns


def test_the_guide_has_a_page_per_task():
    tasks = {"getting_started", "robots", "statics", "modes_frf", "cable_model",
             "design_checks", "workspace", "time_domain", "exchange", "calibration"}
    assert tasks <= {p.stem for p in PAGES}
    assert all(blocks(p) for p in PAGES if p.stem in tasks), "a task page without code"


@pytest.mark.parametrize("page", PAGES, ids=[p.stem for p in PAGES])
def test_page_examples_run(page, monkeypatch):
    ns = run_page(page, monkeypatch, fast_only=True)
    if page.stem == "getting_started":
        assert ns["state"].tension_at_end == pytest.approx(300.0, rel=1e-9)
        assert ns["K6"].shape == (10_000, 6, 6) and len(ns["modes"].to_frame()) == 40
    if page.stem == "workspace":
        assert set(ns["wmap"]["dynamic"].dims) == {"x", "y", "z"}


@pytest.mark.slow
@pytest.mark.parametrize("page", [p for p in PAGES if any(s in c for c in blocks(p)
                                                          for s in SLOW_CALLS)],
                         ids=lambda p: p.stem)
def test_page_all_examples_run(page, monkeypatch):
    ns = run_page(page, monkeypatch, fast_only=False)
    assert ns["fl"].stable.shape == (2,)
