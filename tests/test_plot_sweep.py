"""The veering diagram (dynstiff/plot/sweep.py)."""

import matplotlib
import numpy as np
import pandas as pd
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_veering  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def small_sweep(cogiro):
    return ds.sweep(cogiro.robot, poses=[[-1.5, 0.0, 1.0], [0.0, 0.0, 1.0], [1.5, 0.0, 1.0]],
                    n_modes=8)


def by_gid(ax, prefix):
    return [a for a in ax.get_children() if (a.get_gid() or "").startswith(prefix)]


# --------------------------------------------------------------------------- veering
def test_veering_one_line_per_track_and_local_dots(small_sweep):
    fig0, ax = plt.subplots()
    fig = plot_veering(small_sweep, ax=ax)
    assert fig is ax.figure
    assert ax.get_xlabel() == small_sweep.parameter == "arc length [m]"
    assert ax.get_ylabel() == "frequency [Hz]"
    tracks = by_gid(ax, "track-")
    assert small_sweep.n_tracks >= 1 and len(tracks) == small_sweep.n_tracks
    table = small_sweep.veering_table()
    for ln in tracks:
        t = int(ln.get_gid().split("-")[1])
        np.testing.assert_allclose(ln.get_xdata(), small_sweep.values)
        np.testing.assert_allclose(ln.get_ydata(), table[t].to_numpy())   # NaN where absent
    (dots,) = by_gid(ax, "local-modes")
    local = small_sweep.kind == "local"
    pts = dots.get_offsets()
    assert len(pts) == local.sum() > 0
    np.testing.assert_allclose(np.sort(pts[:, 1]), np.sort(small_sweep.freq_hz[local]))
    fig = plot_veering(small_sweep, show_local=False)
    assert by_gid(fig.axes[0], "local-modes") == []
    with pytest.raises(InvalidParameterError, match="sweep_result must be a SweepResult"):
        plot_veering(small_sweep.to_frame())


def test_veering_bridges_interior_gaps_only():
    """A track missing between two hits is bridged by a dotted line of its colour from the
    last hit to the next; a track that ends (or starts late) is not extended."""

    class Stub:
        parameter = "E [Pa]"
        values = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
        n_tracks = 2
        value = np.array([2.0, 3.0])
        freq_hz = np.array([3.0, 3.1])
        kind = np.array(["local", "local"])

        def veering_table(self):
            return pd.DataFrame({0: [2.0, np.nan, np.nan, 2.6, 2.8],
                                 1: [np.nan, 3.5, 3.6, np.nan, np.nan]})

    fig = plot_veering(Stub())
    ax = fig.axes[0]
    (gap,) = by_gid(ax, "gap-")
    assert gap.get_gid() == "gap-0"
    np.testing.assert_array_equal(gap.get_xdata()[:2], [1.0, 4.0])
    np.testing.assert_array_equal(gap.get_ydata()[:2], [2.0, 2.6])
    (track0,) = [ln for ln in by_gid(ax, "track-") if ln.get_gid() == "track-0"]
    assert gap.get_color() == track0.get_color()
    assert "dotted" in ax.get_title()




@pytest.mark.parametrize("values, scale", [([1e10, 3e10, 1e11], "log"),
                                           ([1e10, 2e10, 5e10], "linear"),
                                           ([-1.0, 0.0, 10.0], "linear")])
def test_a_decade_of_a_positive_parameter_is_drawn_on_a_log_axis(values, scale):
    class Stub:
        parameter = "EA [N]"
        n_tracks = 1
        value = np.array(values)
        freq_hz = np.array([3.0, 3.1, 3.2])
        kind = np.array(["local"] * 3)

        def veering_table(self):
            return pd.DataFrame({0: [2.0, 2.2, 2.5]})

    Stub.values = np.array(values)
    ax = plot_veering(Stub()).axes[0]
    assert ax.get_xscale() == scale
    lo, hi = ax.get_xlim()
    assert lo < min(values) and max(values) < hi
    (track,) = by_gid(ax, "track-")
    np.testing.assert_array_equal(track.get_xdata(), values)


def test_a_worded_show_local_flag_is_refused(small_sweep):
    with pytest.raises(InvalidParameterError, match="^show_local must be True or False"):
        plot_veering(small_sweep, show_local="no")
