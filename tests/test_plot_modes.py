"""Figures of modes and statics (dynstiff/plot/modes.py): natural frequencies by class, damped
roots, cable modes by family, tensions and model errors."""

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_model_errors, plot_modes, plot_tensions  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def by_gid(ax, prefix):
    return [a for a in ax.get_children() if (a.get_gid() or "").startswith(prefix)]


def test_cable_modes_and_damped_modes_plot(cogiro_eq):
    st = cogiro_eq.states[0]
    cm = ds.cable_natural_frequencies(st, 7)
    ax = cm.plot().axes[0]
    xs = np.concatenate([np.concatenate([s[:, 0] for s in c.get_segments()])
                         for c in by_gid(ax, "cable-")])
    np.testing.assert_allclose(np.unique(xs), np.unique(cm.freq_hz), rtol=1e-12)
    dm = ds.DampedModes(undamped_freq_hz=np.array([1.0, 2.0]),
                        omega=np.array([2 * np.pi * (1 + 0.01j), np.nan]),
                        residual=np.array([1e-12, np.nan]))
    pts = by_gid(dm.plot().axes[0], "damped-modes")[0]
    np.testing.assert_allclose(pts.get_xdata(), [1.0])
    np.testing.assert_allclose(pts.get_ydata(), [100 * 0.01 / np.hypot(1, 0.01)])
    with pytest.raises(InvalidParameterError, match="modes"):
        plot_modes(np.array([1.0]))


# ----------------------------------------------------------- results that draw themselves
def test_modal_result_plot_shows_each_mode_at_its_platform_share(cogiro_model):
    """One stem per mode, at its frequency, up to its platform share, in the colour of its
    kind (global, mixed, local: all three among CoGiRo's first 12 modes)."""
    md = ds.modes(cogiro_model, 12)
    ax = md.plot().axes[0]
    groups = {k: by_gid(ax, f"modes-{k}") for k in ("global", "mixed", "local")}
    assert all(len(g) == 1 for g in groups.values())
    segs = np.concatenate([g[0].get_segments() for g in groups.values()])
    assert len(segs) == len(md)
    got = sorted((s[0, 0], s[1, 1]) for s in segs)
    want = sorted(zip(md.freq_hz, md.platform_share))
    np.testing.assert_allclose(got, want, rtol=1e-12)
    for k, g in groups.items():
        xs = np.sort([s[0, 0] for s in g[0].get_segments()])
        np.testing.assert_allclose(xs, np.sort(md.freq_hz[np.array(md.kind) == k]))


def test_equilibrium_plot_bars_are_the_tensions_and_the_limits(cogiro_eq):
    ax = cogiro_eq.plot().axes[0]
    heights = [p.get_height() for p in by_gid(ax, "tension-B")]
    np.testing.assert_allclose(heights, cogiro_eq.tensions, rtol=1e-12)
    heights = [p.get_height() for p in by_gid(ax, "tension-A")]
    np.testing.assert_allclose(heights, cogiro_eq.anchor_tensions, rtol=1e-12)
    # CoGiRo: tensions 270-306 N, limits 100 and 5000 N: t_max is named, not drawn, and
    # the axis is scaled to the tensions
    limits = [line.get_ydata()[0] for line in by_gid(ax, "limit-")]
    assert limits == [100.0]
    assert "t_max = 5000 N" in ax.get_title()
    lo, hi = ax.get_ylim()
    top = max(cogiro_eq.tensions.max(), cogiro_eq.anchor_tensions.max())
    assert lo == 0 and top < hi < 1.3 * top
    # limits within reach are both drawn, and the axis holds them
    fig = ds.plot.plot_tensions(cogiro_eq, limits=(150.0, 400.0))
    ax = fig.axes[0]
    assert sorted(line.get_ydata()[0] for line in by_gid(ax, "limit-")) == [150.0, 400.0]
    assert ax.get_ylim()[1] > 400.0 and "off scale" not in ax.get_title()


def test_recommendation_plot_marks_rungs_that_miss_modes(cogiro_eq):
    rec = ds.recommend_model(cogiro_eq, band_hz=(0.0, 12.0), rtol=1e-3)
    ax = rec.plot(rtol=1e-3).axes[0]
    bars = by_gid(ax, "rung-errors")
    assert [b.get_height() for b in bars][2] == pytest.approx(rec.errors["dsm"], rel=1e-12)
    misses = [t.get_text() for t in ax.texts]
    assert misses.count("misses modes") == sum(not np.isfinite(e) for e in rec.errors.values())
    assert by_gid(ax, "limit-rtol")[0].get_ydata()[0] == 1e-3




@pytest.mark.parametrize("call, message", [
    (lambda eq, rec: plot_tensions(eq, limits=True), "^limits must be real numbers, not "
                                                     "booleans"),
    (lambda eq, rec: plot_tensions(eq, limits="ab"), r"^limits must be \(t_min, t_max\) \[N\]"),
    (lambda eq, rec: plot_tensions(eq, limits=(1.0, 2.0, 3.0)), r"^limits must be \(t_min, "),
    (lambda eq, rec: plot_model_errors(rec, rtol=True), "^rtol must be a real number, got True"),
    (lambda eq, rec: plot_model_errors(rec, rtol="a"), "^rtol must be a real number, got 'a'")])
def test_limits_and_tolerances_of_the_plots_are_numbers(call, message):
    """limits=True and text came out as TypeErrors; rtol=True drew a line at 1."""
    eq = ds.load_scene("planar2").equilibrium()
    rec = ds.recommend_model(eq, band_hz=(0.0, 2.0))
    with pytest.raises(InvalidParameterError, match=message):
        call(eq, rec)
