"""UncertaintyResult (dynstiff/analyses/uncertainty_result.py) on a result built by hand:
its linear standard deviations, probabilities, quantiles, table and histograms against
numbers computed here (the propagation itself: test_analyses_uncertainty.py)."""

import warnings

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from dynstiff.analyses.uncertainty import Uncertain  # noqa: E402
from dynstiff.analyses.uncertainty_result import UncertaintyResult  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402


def result(monte_carlo=True):
    """Two parameters (EA sigma 10 %, mass +-2 kg uniform), two quantities, 6 samples; the
    Monte Carlo has one failed sample (NaN)."""
    rng = np.random.default_rng(7)
    first = np.column_stack([2.0 + 0.1 * rng.standard_normal(6),
                             3.0 + 0.2 * rng.standard_normal(6)])
    mc = first + 0.01
    mc[4, 0] = np.nan
    return UncertaintyResult(
        parameters=("EA", "mass"), nominal_values=np.array([1e6, 90.0]),
        uncertain=(Uncertain(0.1), Uncertain(2.0, "uniform", relative=False)),
        samples=np.zeros((6, 2)), quantities=("f1", "first_platform_hz"),
        nominal=np.array([2.0, 3.0]), gradient=np.array([[1e-7, -0.01], [2e-7, 0.03]]),
        first_order=first, monte_carlo=mc if monte_carlo else None,
        failed=1, seed=0)


def test_linear_standard_deviation_sums_the_parameters_in_quadrature():
    r = result()
    sig = np.array([0.1 * 1e6, 2.0 / np.sqrt(3.0)])       # relative normal; uniform half-width
    expected = np.sqrt(np.sum((r.gradient * sig) ** 2, axis=1))
    np.testing.assert_allclose(r.std_first_order, expected, rtol=1e-15)
    assert r.std_first_order[0] == pytest.approx(np.hypot(0.01, 0.02 / np.sqrt(3.0)), rel=1e-15)


def test_probability_and_quantile_count_a_failed_sample_as_below():
    r = result()
    x = r.monte_carlo[:, 0]
    assert r.probability_below("f1", 2.0) == pytest.approx(
        (np.sum(x[np.isfinite(x)] < 2.0) + 1) / 6)
    y = r.first_order[:, 1]
    assert r.probability_below("first_platform_hz", 3.0, method="first-order") == \
        pytest.approx(np.mean(y < 3.0))
    assert r.probability_below("first_platform_hz", y[2], method="first-order") == \
        pytest.approx(np.mean(y < y[2]))                    # a sample on it is not below
    assert r.quantile("first_platform_hz", 0.5, method="first-order") == np.median(y)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                      # -inf + inf is silenced
        assert r.quantile("f1", 0.0) == -np.inf             # the failed sample
        assert r.quantile("f1", 0.1) == -np.inf
    assert r.quantile("f1", 1.0) == np.nanmax(x)


@pytest.mark.parametrize("kw, match", [
    (dict(quantity="f9"), r"^quantity must be one of \('f1', 'first_platform_hz'\)"),
    (dict(method="exact"), r"^method must be 'first-order' or 'monte-carlo'"),
])
def test_a_bad_quantity_or_method_is_named(kw, match):
    args = dict(quantity="f1", method="monte-carlo") | kw
    with pytest.raises(InvalidParameterError, match=match):
        result().quantile(args["quantity"], 0.5, method=args["method"])
    with pytest.raises(InvalidParameterError, match=match):
        result().probability_below(args["quantity"], 1.0, method=args["method"])


def test_monte_carlo_not_computed_is_refused_by_name():
    with pytest.raises(InvalidParameterError, match="monte-carlo' \\(computed\\)"):
        result(monte_carlo=False).quantile("f1", 0.5)


def test_table_rows_are_the_statistics_of_each_method():
    r = result()
    df = r.to_frame()
    assert list(df["quantity"]) == ["f1", "first_platform_hz"]
    assert list(df.columns) == [
        "quantity", "nominal", "std first order (linear)",
        "mean first order", "std first order", "q05 first order", "q95 first order",
        "mean Monte Carlo", "std Monte Carlo", "q05 Monte Carlo", "q95 Monte Carlo"]
    for i in range(2):
        row = df.iloc[i]
        assert row["nominal"] == r.nominal[i]
        assert row["std first order (linear)"] == r.std_first_order[i]
        for name, data in (("first order", r.first_order), ("Monte Carlo", r.monte_carlo)):
            x = data[:, i]
            x = x[np.isfinite(x)]                           # the failed sample left out
            assert row[f"mean {name}"] == pytest.approx(np.mean(x), rel=1e-14)
            assert row[f"std {name}"] == pytest.approx(np.std(x, ddof=1), rel=1e-14)
            assert row[f"q05 {name}"] == pytest.approx(np.quantile(x, 0.05), rel=1e-14)
            assert row[f"q95 {name}"] == pytest.approx(np.quantile(x, 0.95), rel=1e-14)
    without = result(monte_carlo=False).to_frame()
    assert not any("Monte Carlo" in c for c in without.columns)
    assert "q95 first order" in without.columns


def test_histograms_of_both_methods_with_the_nominal_line():
    r = result()
    fig = r.plot("f1")
    ax = fig.axes[0]
    heights = [[p.get_height() for p in c] for c in ax.containers]
    assert [len(h) for h in heights] == [25, 25]
    assert [sum(h) for h in heights] == [6, 5]              # the failed sample left out
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["first order",
                                                                 "Monte Carlo"]
    assert {p.get_alpha() for c in ax.containers for p in c} == {0.55}   # see-through
    (line,) = ax.get_lines()
    assert list(line.get_xdata()) == [2.0, 2.0]
    assert matplotlib.colors.to_rgba(line.get_color()) == (0.0, 0.0, 0.0, 1.0)
    assert line.get_linewidth() == 0.8
    assert ax.get_xlabel() == "f1" and ax.get_ylabel() == "samples"
    assert ax.get_title() == "EA sigma 10 % (normal), mass +-2 (uniform)"
    assert tuple(fig.get_size_inches()) == (5.5, 3.5)
    plt.close(fig)
    fig = r.plot()                                          # the first platform mode
    assert fig.axes[0].get_lines()[0].get_xdata()[0] == 3.0
    plt.close(fig)
    fig, own = plt.subplots()
    assert result(monte_carlo=False).plot("first_platform_hz", ax=own) is fig
    assert len(own.containers) == 1 and own.get_lines()[0].get_xdata()[0] == 3.0
    plt.close(fig)
