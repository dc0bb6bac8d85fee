"""The speed-accuracy chart (dynstiff/plot/accuracy.py)."""

import matplotlib
import numpy as np
import pandas as pd
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.text import Annotation  # noqa: E402

from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_speed_accuracy  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def by_gid(ax, prefix):
    return [a for a in ax.get_children() if (a.get_gid() or "").startswith(prefix)]


# -------------------------------------------------------------------- speed-accuracy
def speed_table():
    """Synthetic run() output: 3 cases x 6 models; two massless models miss modes."""
    models = {"spring": (np.inf, 1e-3), "catenary": (np.inf, 2e-3), "dsm": (2e-6, 2e-2),
              "lumped N=5": (3e-2, 5e-3), "lumped N=10": (8e-3, 1.2e-2),
              "lumped N=20": (2e-3, 5e-2)}
    rows = [{"model": name, "err first 20": e * (1 + 0.1 * case),
             "40 modes [s]": c * (1 + 0.2 * case), "FRF [s]": 10 * c, "build [s]": 1e-3,
             "E [GPa]": 17.0, "pose": str(case)}
            for name, (e, c) in models.items() for case in range(3)]
    return pd.DataFrame(rows)


def test_speed_accuracy_annotations_and_pareto_front():
    df = speed_table()
    fig0, ax = plt.subplots()
    fig = plot_speed_accuracy(df, ax=ax)
    assert fig is ax.figure
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    notes = [t for t in ax.texts if isinstance(t, Annotation)]
    assert sorted(t.get_gid() for t in notes) == sorted(f"model-{m}" for m in
                                                        df["model"].unique())
    missing = {t.get_text() for t in notes if "misses modes" in t.get_text()}
    assert missing == {"spring (misses modes)", "catenary (misses modes)"}
    # worst error over the cases, median cost + median build
    g = df.groupby("model").agg({"err first 20": "max", "40 modes [s]": "median",
                                 "build [s]": "median"})
    cost = g["40 modes [s]"] + g["build [s]"]
    dsm = [a for a in ax.get_lines() if a.get_gid() == "model-dsm"][0]
    np.testing.assert_allclose([dsm.get_xdata()[0], dsm.get_ydata()[0]],
                               [cost["dsm"], g.loc["dsm", "err first 20"]])
    (front,) = by_gid(ax, "pareto")
    fx, fy = front.get_data()
    finite = np.isfinite(g["err first 20"].to_numpy())
    pts = np.column_stack([cost.to_numpy(), g["err first 20"].to_numpy()])[finite]

    def dominated(p):
        return np.any(np.all(pts <= p, axis=1) & np.any(pts < p, axis=1))

    on_front = [tuple(p) for p in np.column_stack([fx, fy])]
    assert len(on_front) == 3                      # lumped N=5, lumped N=10, dsm
    assert not any(dominated(np.array(p)) for p in on_front)
    for p in pts:                                   # every other model is dominated
        assert tuple(p) in on_front or dominated(p)
    assert np.all(np.diff(fx) > 0) and np.all(np.diff(fy) < 0)


def test_speed_accuracy_rejects_missing_column():
    with pytest.raises(InvalidParameterError, match="'FRF log error"):
        plot_speed_accuracy(speed_table(), error="FRF log error [dec]", cost="FRF [s]")
    with pytest.raises(InvalidParameterError, match="df must be a pandas DataFrame"):
        plot_speed_accuracy([1, 2, 3])


