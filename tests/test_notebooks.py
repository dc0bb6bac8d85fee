"""Notebooks are stored without outputs, execute without error and show their figures."""

from pathlib import Path

import pytest

pytestmark = pytest.mark.integration

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_executes(path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(path, as_version=4)
    assert all(not c.get("outputs") for c in nb.cells if c.cell_type == "code"), \
        f"{path.name} is stored with outputs"
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}}).execute()
    if "plt.show()" in "".join(c.source for c in nb.cells):
        # figures shown inline reach the reader as images, not only as files
        assert any("image/png" in o.get("data", {}) for c in nb.cells
                   if c.cell_type == "code" for o in c.outputs), f"{path.name} shows no figure"
    # every cell that makes a figure shows it: an image/png output (not an Agg backend
    # that draws off screen, nor a figure assigned and never displayed)
    for cell in nb.cells:
        if cell.cell_type == "code" and "fig = " in cell.source:
            kinds = [k for o in cell.get("outputs", []) for k in o.get("data", {})]
            assert "image/png" in kinds, f"{path.name}: no figure shown by\n{cell.source}"


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 1
