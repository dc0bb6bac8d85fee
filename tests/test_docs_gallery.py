"""The gallery's scripts (docs/examples/plot_*.py) run as written and each draws a figure
with data in it; the documentation build runs them again to show their figures."""

import runpy
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples"
SCRIPTS = sorted(EXAMPLES.glob("plot_*.py"))


def _drawn_data(ax):
    """Number of finite points of the lines, of collection items, patches and images that
    ``ax`` draws."""
    n = 0
    for line in ax.lines:
        points = (np.column_stack(line.get_data_3d()) if hasattr(line, "get_data_3d")
                  else line.get_xydata())
        n += int(np.isfinite(np.asarray(points, dtype=float)).all(axis=1).sum())
    for coll in ax.collections:
        n += len(coll.get_offsets()) + len(coll.get_paths())
    n += len(ax.patches) + len(ax.images)
    return n


def test_there_are_at_least_eight_scripts():
    assert len(SCRIPTS) >= 8, [p.name for p in SCRIPTS]


@pytest.mark.parametrize("path", SCRIPTS, ids=[p.stem for p in SCRIPTS])
def test_script_draws_a_figure_with_data(path, monkeypatch):
    text = path.read_text()
    # sphinx-gallery needs a docstring that opens with a title and its underline
    head = text.split('"""')[1].strip().splitlines()
    assert len(head) >= 3 and set(head[1]) == {"="} and len(head[1]) >= len(head[0]), head[:2]
    plt.close("all")
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    runpy.run_path(str(path), run_name="__main__")
    figures = [plt.figure(n) for n in plt.get_fignums()]
    try:
        assert figures, f"{path.name} draws no figure"
        for fig in figures:
            fig.canvas.draw()
            counts = [_drawn_data(ax) for ax in fig.axes]
            assert sum(counts) >= 3, f"{path.name}: figure {fig.number} draws {counts}"
    finally:
        plt.close("all")


def test_the_data_check_can_fail():
    fig, ax = plt.subplots()
    assert _drawn_data(ax) == 0
    ax.plot([0.0, 1.0, np.nan], [1.0, 2.0, 3.0])
    assert _drawn_data(ax) == 2
    plt.close(fig)
