"""The README's Python examples run as written, in order, in one namespace (the API they
show is the API there is). Blocks that simulate (trajectories, time domain, pendulum) would
take minutes and run in the slow tier; the longer examples live in the user guide
(docs/guide/, run by tests/test_docs_guide.py)."""

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"
SLOW_CALLS = ("track(", "simulate(", "floquet(", "stability_map(")


def blocks():
    return re.findall(r"```python\n(.*?)```", README.read_text(), re.S)


def run_blocks(selected, capsys):
    import matplotlib
    matplotlib.use("Agg")
    ns = {}
    for i, code in selected:
        exec(compile(code, f"README.md python block {i}", "exec"), ns)
    return ns, capsys.readouterr().out


def test_readme_has_examples():
    b = blocks()
    assert len(b) >= 3
    assert sum(not any(c in code for c in SLOW_CALLS) for code in b) >= 3


def test_readme_fast_examples_run(capsys):
    fast = [(i, c) for i, c in enumerate(blocks()) if not any(s in c for s in SLOW_CALLS)]
    ns, out = run_blocks(fast, capsys)
    # the ten-line example: 300 N at B, K over 10,000 frequencies, 3x3 and 6x6
    assert ns["state"].tension_at_end == pytest.approx(300.0, rel=1e-9)
    assert ns["K"].shape == (10_000, 3, 3) and ns["K6"].shape == (10_000, 6, 6)
    # the robot-level example: 40 CoGiRo modes, the fz -> z FRF on 5000 frequencies
    assert len(ns["modes"].to_frame()) == 40
    assert ns["H"].to_frame()["freq [Hz]"].nunique() == 5000
    assert "recommended model" in out


@pytest.mark.slow
def test_readme_all_examples_run(capsys):
    ns, _ = run_blocks(list(enumerate(blocks())), capsys)
    assert ns["model"] is not None
