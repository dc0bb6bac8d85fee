"""The speed-accuracy chart (dynstiff/plot/accuracy.py)."""

import re

import matplotlib
import numpy as np
import pandas as pd
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402
from matplotlib.legend import Legend  # noqa: E402
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



def lines_of(ax):
    """The model points, by model name (their gid is model-<name>)."""
    return {ln.get_gid()[len("model-"):]: ln for ln in ax.get_lines()
            if (ln.get_gid() or "").startswith("model-")}


def notes_of(ax):
    """The model labels, by model name."""
    return {t.get_gid()[len("model-"):]: t for t in ax.texts if isinstance(t, Annotation)}


def one_row_table(models, error="err first 20", cost="40 modes [s]"):
    """One case per model: {name: (error, cost)}, build time 0 (so the cost is the total)."""
    return pd.DataFrame([{"model": m, error: e, cost: c, "build [s]": 0.0}
                         for m, (e, c) in models.items()])


def test_models_alike_as_text_are_refused():
    """Model keys 1 and "1" are two groups but one label and one gid: refused, both named."""
    df = one_row_table({1: (0.1, 1.0), "1": (0.2, 2.0), "dsm": (0.01, 3.0)})
    with pytest.raises(InvalidParameterError, match=re.escape(
            "df: models [1, '1', 'dsm'] are not distinct as text (['1'] twice): their labels "
            "and gids would be one")):
        plot_speed_accuracy(df, error="err first 20", cost="40 modes [s]")


def worst_and_total(df, error="err first 20", cost="40 modes [s]"):
    g = df.groupby("model", sort=False).agg({error: "max", cost: "median", "build [s]": "median"})
    return g[error], g[cost] + g["build [s]"]


def test_pareto_flags_mark_the_non_dominated_points_as_bools():
    """The helper returns a bool array: the cheapest point, then each point whose error is
    below every cheaper one's; at equal cost only the lower error; never an infinite error."""
    from dynstiff.plot.accuracy import _pareto_flags
    cost = np.array([3.0, 1.0, 2.0, 2.0, 4.0, 0.5])
    err = np.array([0.1, 0.5, 0.4, 0.2, 0.3, np.inf])
    flags = _pareto_flags(cost, err)
    assert flags.dtype == np.bool_ and flags.shape == (6,)
    assert flags.tolist() == [True, True, False, True, False, False]


def test_label_offsets_follow_the_documented_stepping_rule():
    """Neighbours (|du| < 0.3 span(u), |dv| < 0.08 span(v), spans at least 1) get offsets
    4, -12, 20, ... in order of u; points farther apart in u or v keep 4."""
    from dynstiff.plot.accuracy import _label_offsets
    # u steps of 0.5 of a span 1: not neighbours (0.5 > 0.3 * 1)
    assert _label_offsets(np.array([0.0, 0.5, 1.0]), np.zeros(3)).tolist() == [4.0] * 3
    # v step 0.12 with span 1: not neighbours (0.12 > 0.08 * 1)
    assert _label_offsets(np.array([0.0, 0.1]), np.array([0.0, 0.12])).tolist() == [4.0] * 2
    # three mutual neighbours at the same (non-zero) v, given right to left: placed by u
    got = _label_offsets(np.array([-1.8, -1.9, -2.0]), np.full(3, -3.0))
    assert got.tolist() == [20.0, -12.0, 4.0]


def test_labels_of_neighbouring_points_do_not_overlap():
    """Two models of nearly equal cost and equal error, on axes spanning decades (a third
    model far away): their labels, drawn, do not overlap."""
    df = one_row_table({"lumped N=20 (long)": (1e-2, 1.0), "lumped N=40 (long)": (1e-2, 1.2),
                        "dsm": (1e-4, 1e3)})
    fig = plot_speed_accuracy(df)
    fig.canvas.draw()
    notes = notes_of(fig.axes[0])
    a, b = (notes[m].get_window_extent() for m in ("lumped N=20 (long)", "lumped N=40 (long)"))
    assert not a.overlaps(b)


def test_labels_sit_5_points_right_of_their_point_in_8_pt():
    """Each label points at its model's point and is offset (5, dy) points, dy the stepped
    offset of the points in log coordinates; its font is 8 pt."""
    from dynstiff.plot.accuracy import _label_offsets
    fig = plot_speed_accuracy(speed_table())
    ax = fig.axes[0]
    pts, notes = lines_of(ax), notes_of(ax)
    names = list(pts)
    x = np.array([pts[m].get_xdata()[0] for m in names])
    y = np.array([pts[m].get_ydata()[0] for m in names])
    dy = _label_offsets(np.log10(x), np.log10(y))
    for k, m in enumerate(names):
        t = notes[m]
        assert t.anncoords == "offset points"
        assert tuple(t.xy) == (x[k], y[k])
        assert tuple(t.xyann) == (5, dy[k])
        assert t.get_fontsize() == 8


def test_front_points_are_larger_and_edged_in_black():
    """Models on the front: 8 pt circles edged in black; the others 6 pt, edged in their
    own colour."""
    df = speed_table()
    ax = plot_speed_accuracy(df).axes[0]
    err, total = worst_and_total(df)
    finite = np.isfinite(err)
    # on the front: no other finite model is at most as costly and as wrong, once strictly
    on_front = {m for m in err.index[finite]
                if not np.any((total[finite] <= total[m]) & (err[finite] <= err[m])
                              & ((total[finite] < total[m]) | (err[finite] < err[m])))}
    assert 0 < len(on_front) < finite.sum()
    for m, ln in lines_of(ax).items():
        if not np.isfinite(err[m]):
            continue
        assert ln.get_marker() == "o"
        if m in on_front:
            assert ln.get_markersize() == 8
            assert to_rgba(ln.get_markeredgecolor()) == to_rgba("k")
        else:
            assert ln.get_markersize() == 6
            assert to_rgba(ln.get_markeredgecolor()) == to_rgba(ln.get_color())


def test_model_k_takes_tab10_colour_k_mod_10():
    """Eleven models (the first missing modes): model k is drawn in tab10 colour k mod 10,
    so the eleventh reuses the first colour."""
    models = {f"m{k}": (np.inf if k == 0 else 1.0 / k, float(k + 1)) for k in range(11)}
    ax = plot_speed_accuracy(one_row_table(models)).axes[0]
    pts = lines_of(ax)
    tab10 = plt.get_cmap("tab10").colors
    for k in range(11):
        assert to_rgba(pts[f"m{k}"].get_color()) == to_rgba(tab10[k % 10])


def test_models_missing_modes_are_open_triangles_a_decade_above():
    """An infinite error is an open 7 pt triangle at the model's cost, a decade above the
    largest positive error (errors in decades may exceed 1), above every finite point."""
    err = "FRF log error [dec]"
    df = one_row_table({"spring": (np.inf, 1e-3), "dsm": (0.2, 1e-1), "lumped": (5.0, 1e-2)},
                       error=err, cost="FRF [s]")
    ax = plot_speed_accuracy(df, error=err, cost="FRF [s]").axes[0]
    pts = lines_of(ax)
    tri = pts["spring"]
    assert tri.get_marker() == "^" and tri.get_markersize() == 7
    assert tri.get_markerfacecolor() == "none"
    assert tri.get_xdata().tolist() == [1e-3]
    assert tri.get_ydata().tolist() == [10.0 * 5.0]
    assert all(tri.get_ydata()[0] > pts[m].get_ydata()[0] for m in ("dsm", "lumped"))


def test_front_is_a_dashed_black_step_line_with_its_legend_at_lower_left():
    """The front: black, dashed, 1 pt, alpha 0.7, steps after each point; the legend (lower
    left) names it "Pareto front (black-edged points)"."""
    ax = plot_speed_accuracy(speed_table()).axes[0]
    (front,) = by_gid(ax, "pareto")
    assert to_rgba(front.get_color()) == to_rgba("k")
    assert front.get_linestyle() == "--" and front.get_linewidth() == 1.0
    assert front.get_alpha() == 0.7 and front.get_drawstyle() == "steps-post"
    leg = ax.get_legend()
    assert [t.get_text() for t in leg.get_texts()] == ["Pareto front (black-edged points)"]
    assert leg._loc == Legend.codes["lower left"]       # private, but the only record of loc


def test_axis_labels_name_the_cost_column_without_its_unit():
    """The x label is "wall time: <cost without ' [s]'> + build [s]", the y label
    "<error> (worst case)"."""
    ax = plot_speed_accuracy(speed_table()).axes[0]
    assert ax.get_xlabel() == "wall time: 40 modes + build [s]"
    assert ax.get_ylabel() == "err first 20 (worst case)"
    ax = plot_speed_accuracy(speed_table(), cost="FRF [s]").axes[0]
    assert ax.get_xlabel() == "wall time: FRF + build [s]"


def test_new_figure_size_and_margins():
    """Without ax: a new 6.5 x 4.5 in figure; margins 25 % in x and 20 % in y."""
    fig = plot_speed_accuracy(speed_table())
    assert tuple(fig.get_size_inches()) == (6.5, 4.5)
    assert fig.axes[0].margins() == (0.25, 0.2)


def test_object_columns_are_read_as_floats():
    """Errors and times held as Python objects give the same points as float columns."""
    df = speed_table()
    cols = ["err first 20", "40 modes [s]", "build [s]"]
    ref = lines_of(plot_speed_accuracy(df).axes[0])
    got = lines_of(plot_speed_accuracy(df.astype({c: object for c in cols})).axes[0])
    assert list(got) == list(ref)
    for m in ref:
        assert np.asarray(got[m].get_xydata(), dtype=float).tolist() == \
            ref[m].get_xydata().tolist()


@pytest.mark.parametrize("bad", [{"b": 0.0}, {"b": 0.0, "c": np.nan}, {"b": -1.0}])
def test_a_cost_not_finite_and_positive_names_the_first_such_model(bad):
    """A model whose cost + build is 0, negative or NaN is rejected; the message names the
    first such model (in table order) and its total."""
    models = {"a": (1e-2, 1.0), "b": (1e-3, 2.0), "c": (1e-4, 3.0)}
    df = one_row_table(models)
    for m, c in bad.items():
        df.loc[df["model"] == m, "40 modes [s]"] = c
    with pytest.raises(InvalidParameterError) as e:
        plot_speed_accuracy(df)
    msg = str(e.value)
    assert msg.startswith("df: '40 modes [s]' + 'build [s]' must be finite and > 0 [s]; "
                          "model 'b' has ")
    assert msg.endswith(repr(np.float64(bad["b"])))


@pytest.mark.parametrize("bad", [np.nan, -1e-3])
def test_a_nan_or_negative_error_of_one_case_is_refused_naming_its_model(bad):
    """The worst error of a model is the largest over its cases; a case whose error is NaN
    (a failed run) would be skipped by that maximum and the model drawn better than it is:
    refused, naming the value, the model and the row."""
    df = speed_table()
    k = int(np.flatnonzero(df["model"] == "lumped N=10")[1])
    df.loc[k, "err first 20"] = bad
    with pytest.raises(InvalidParameterError) as e:
        plot_speed_accuracy(df)
    assert str(e.value) == (f"df: 'err first 20' must be >= 0 or inf, got {bad!r} "
                            f"(model 'lumped N=10', row {k})")


def test_a_table_without_rows_is_refused_and_one_row_is_a_chart():
    df = one_row_table({"dsm": (1e-3, 1.0)})
    with pytest.raises(InvalidParameterError, match="^df has no rows$"):
        plot_speed_accuracy(df.iloc[:0])
    assert lines_of(plot_speed_accuracy(df).axes[0])["dsm"].get_ydata().tolist() == [1e-3]


def test_a_zero_error_is_drawn_at_a_tenth_of_the_smallest_positive_one():
    df = one_row_table({"exact": (0.0, 3.0), "a": (1e-3, 1.0), "b": (5e-2, 0.5)})
    pts = lines_of(plot_speed_accuracy(df).axes[0])
    assert pts["exact"].get_ydata()[0] == pytest.approx(1e-4, rel=1e-14)
    assert pts["a"].get_ydata().tolist() == [1e-3] and pts["b"].get_ydata().tolist() == [5e-2]


def test_without_a_positive_error_zero_is_drawn_at_1e_12_and_missing_modes_at_1():
    """No positive error to scale from: a zero error sits at 1e-12, an infinite one at 1 (and
    the dotted line at 1)."""
    df = one_row_table({"exact": (0.0, 1.0), "spring": (np.inf, 0.1)})
    ax = plot_speed_accuracy(df).axes[0]
    pts = lines_of(ax)
    assert pts["exact"].get_ydata().tolist() == [1e-12]
    assert pts["spring"].get_ydata().tolist() == [1.0]
    (line,) = [ln for ln in ax.get_lines() if not ln.get_gid()]
    assert list(line.get_ydata()) == [1.0, 1.0]


def test_a_dotted_grey_line_marks_the_height_of_the_models_missing_modes():
    """With a model missing modes: a dotted line, grey 0.6, 0.6 pt, across the axes at the
    triangles' height (a decade above the largest positive error); none without."""
    df = speed_table()
    ax = plot_speed_accuracy(df).axes[0]
    err, _ = worst_and_total(df)
    (line,) = [ln for ln in ax.get_lines() if not ln.get_gid()]
    ceiling = 10.0 * err[np.isfinite(err)].max()
    assert list(line.get_ydata()) == [ceiling, ceiling]
    assert lines_of(ax)["spring"].get_ydata().tolist() == [ceiling]
    assert list(line.get_xdata()) == [0, 1]                   # axes coordinates: across
    assert line.get_transform() == ax.get_yaxis_transform()
    assert line.get_linestyle() == ":" and line.get_linewidth() == 0.6
    assert to_rgba(line.get_color()) == to_rgba("0.6")
    finite = df[np.isfinite(df["err first 20"])]
    ax = plot_speed_accuracy(finite).axes[0]
    assert not [ln for ln in ax.get_lines() if not ln.get_gid()]


def test_a_missing_modes_triangle_takes_its_tab10_colour_whatever_the_style():
    """Under a style whose colour cycle is not tab10, model k (finite or missing modes) is
    still drawn in tab10 colour k."""
    tab10 = plt.get_cmap("tab10").colors
    df = one_row_table({"dsm": (1e-3, 1.0), "spring": (np.inf, 0.1), "rod": (np.inf, 0.2)})
    with plt.rc_context({"axes.prop_cycle": matplotlib.cycler(color=["r", "g", "b"])}):
        pts = lines_of(plot_speed_accuracy(df).axes[0])
    for k, m in enumerate(("dsm", "spring", "rod")):
        assert to_rgba(pts[m].get_color()) == to_rgba(tab10[k]), m
    for m in ("spring", "rod"):                       # open triangles: edged in it too
        assert to_rgba(pts[m].get_markeredgecolor()) == to_rgba(pts[m].get_color()), m


def test_a_grid_at_major_and_minor_ticks_with_alpha_0_3():
    """Grid lines at the major and minor ticks of both log axes, alpha 0.3; drawing the
    chart warns of nothing (e.g. matplotlib's "grid() is false, but line properties")."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig = plot_speed_accuracy(speed_table())
    fig.canvas.draw()
    ax = fig.axes[0]
    for axis in (ax.xaxis, ax.yaxis):
        ticks = axis.get_major_ticks() + axis.get_minor_ticks()
        assert len(axis.get_minor_ticks()) > 0
        assert all(t.gridline.get_visible() and t.gridline.get_alpha() == 0.3 for t in ticks)
