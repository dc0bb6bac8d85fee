"""FRF figures (dynstiff/plot/frf.py): curves, mode lines by class, legend and phase."""

import warnings

import matplotlib
import numpy as np
import pytest

# These tests check the algebra of undamped FRFs (symmetry, kinds, files, figures) across
# natural frequencies on purpose: the ResonanceWarning that says so is expected here.
pytestmark = pytest.mark.filterwarnings("ignore::dynstiff.errors.ResonanceWarning")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import plot_frf  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


# ------------------------------------------------------------------------------- FRF
def test_frf_marks_band_modes_and_draws_phase(cogiro_model, cogiro_modes):
    band = (0.5, 3.3)
    res = ds.frf(cogiro_model, 2 * np.pi * np.linspace(*band, 600), inputs=["fz", "fx"],
                           outputs=["z", "x"])
    fig = plot_frf(res, cogiro_modes, phase=True)
    mag, ph = fig.axes
    in_band = (cogiro_modes.freq_hz >= band[0]) & (cogiro_modes.freq_hz <= band[1])
    assert 0 < in_band.sum() < len(cogiro_modes)          # the band cuts the mode list
    for ax in (mag, ph):
        marks = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("mode-")]
        assert len(marks) == in_band.sum()
        np.testing.assert_allclose(sorted(ln.get_xdata()[0] for ln in marks),
                                   cogiro_modes.freq_hz[in_band])
        n_global = sum(k == "global" for k, b in zip(cogiro_modes.kind, in_band) if b)
        assert sum(ln.get_gid() == "mode-global" for ln in marks) == n_global
    curves = [ln for ln in mag.get_lines() if ln.get_gid().startswith("frf-")]
    assert [c.get_label() for c in curves] == ["z / fz", "x / fx"]
    np.testing.assert_allclose(curves[0].get_ydata(), np.abs(res.H[:, 0, 0]))
    assert mag.get_yscale() == "log" and "receptance" in mag.get_ylabel()
    assert ph.get_xlabel() == "frequency [Hz]" and ph.get_ylabel() == "phase [deg]"
    phase = np.concatenate([ln.get_ydata() for ln in ph.get_lines()
                            if ln.get_gid().startswith("frf-")])
    np.testing.assert_allclose(phase[:5], np.degrees(np.angle(res.H[:5, 0, 0])))
    assert np.nanmax(np.abs(phase)) <= 180.0


def test_frf_honours_ax_and_rejects_bad_input(cogiro_model, cogiro_modes):
    res = ds.frf(cogiro_model, 2 * np.pi * np.linspace(1.0, 2.0, 50), inputs=["fz"],
                           outputs=["z"])
    fig0, ax = plt.subplots()
    fig = plot_frf(res, cogiro_modes, ax=ax)      # ax given: magnitude only
    assert fig is ax.figure and fig.axes == [ax]
    with pytest.raises(InvalidParameterError, match="phase=True draws its own figure"
                       r".*pass ax=None, or phase=False to draw the magnitude on ax"):
        plot_frf(res, cogiro_modes, ax=ax, phase=True)      # never silently dropped
    assert fig.axes == [ax]
    with pytest.raises(InvalidParameterError, match="result must be a FRFResult"):
        plot_frf(cogiro_modes)
    with pytest.raises(InvalidParameterError, match=r"pairs.*\('q', 'fz'\)"):
        plot_frf(res, pairs=[("q", "fz")])
    with pytest.raises(InvalidParameterError, match="modes must be a ModalResult"):
        plot_frf(res, modes=[1.0, 2.0])


def test_frf_units_on_axis_and_in_the_table():
    """One unit for all curves goes on the axis label; mixed units go into the legend; the
    tidy table carries the unit of every row."""
    from dynstiff.analyses.frf import FRFResult
    H = np.ones((3, 2, 2), dtype=complex)
    f = np.array([1.0, 2.0, 3.0])
    res = FRFResult(freq_hz=f, H=H, inputs=("fz", "mx"), outputs=("z", "rx"), kind="mobility")
    assert res.unit("z", "fz") == "m/(N s)" and res.unit("rx", "mx") == "rad/(N m s)"
    assert FRFResult(f, H, ("fx",), ("x",), "receptance").unit("x", "fx") == "m/N"
    assert FRFResult(f, H, ("fx",), ("x",), "accelerance").unit("ry", "fx") == "rad/(N s^2)"
    fig = plot_frf(res)                                    # pairs (z, fz), (rx, mx)
    ax = fig.axes[0]
    assert ax.get_ylabel() == "|mobility| [units in the legend]"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["z / fz [m/(N s)]", "rx / mx [rad/(N m s)]"]
    fig = plot_frf(res, pairs=[("z", "fz")])
    assert fig.axes[0].get_ylabel() == "|mobility| [m/(N s)]"
    df = res.to_frame()
    assert set(zip(df["output"], df["input"], df["unit"])) == {
        ("z", "fz", "m/(N s)"), ("z", "mx", "m/(N m s)"), ("rx", "fz", "rad/(N s)"),
        ("rx", "mx", "rad/(N m s)")}
    with pytest.raises(InvalidParameterError, match="unit needs"):
        res.unit("q", "fz")


def test_frf_legend_names_the_mode_markers():
    """The dashed mode lines have legend entries by platform share; CoGiRo at 50 kg has a
    mixed mode (2.216 Hz, 42 %) drawn purple, not blue as a cable mode."""
    import dataclasses
    sc = ds.load_scene("cogiro")
    r = sc.robot
    rob = ds.Robot(r.anchors, r.attachments, r.cables,
                   dataclasses.replace(r.platform, mass=50.0), tension_limits=r.tension_limits)
    m = ds.FrequencyModel(rob.equilibrium(pose=sc.pose))
    modes = ds.modes(m, fmax_hz=2.6)
    res = ds.frf(m, 2 * np.pi * np.linspace(2.0, 2.6, 50), inputs=["fy"], outputs=["y"])
    fig = plot_frf(res, modes)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[0] == "y / fy"
    assert any(lb.startswith("mixed mode (platform share 5%-50%)") for lb in labels)
    assert any(lb.startswith("local mode") for lb in labels)
    mixed = [ln for ln in ax.get_lines() if ln.get_gid() == "mode-mixed"]
    assert any(abs(ln.get_xdata()[0] - 2.216) < 1e-3 for ln in mixed)


def test_frf_curves_mode_lines_twins_and_legend_stay_apart(cogiro_model, cogiro_modes):
    """Curve colours are none of the mode classes'; x / fz and its reciprocal twin z / fx
    (equal) are both visible, the twin dashed and wider; the legend lies outside the
    axes, so no peak is under it."""
    from matplotlib.colors import to_rgba

    from dynstiff.plot.common import COLORS
    res = ds.frf(cogiro_model, 2 * np.pi * np.linspace(0.5, 3.3, 300), inputs=["fx", "fz"],
                 outputs=["x", "z"])
    pairs = [("x", "fx"), ("z", "fz"), ("x", "fz"), ("z", "fx")]
    fig = plot_frf(res, cogiro_modes, pairs=pairs, phase=True)
    mag = fig.axes[0]
    curves = {ln.get_gid(): ln for ln in mag.get_lines()
              if (ln.get_gid() or "").startswith("frf-")}
    assert sorted(curves) == sorted(f"frf-{o}-{i}" for o, i in pairs)
    curve_colours = {to_rgba(ln.get_color()) for ln in curves.values()}
    assert len(curve_colours) == 4                                   # one per channel
    assert not curve_colours & {to_rgba(c) for c in COLORS.values()}  # none a mode class's
    a, b = curves["frf-x-fz"], curves["frf-z-fx"]
    np.testing.assert_allclose(a.get_ydata(), b.get_ydata(), rtol=1e-6)   # reciprocity
    assert a.get_linestyle() == "-" and b.get_linestyle() != "-"
    assert b.get_linewidth() > a.get_linewidth()
    fig.canvas.draw()
    leg = mag.get_legend().get_window_extent()
    box = mag.get_window_extent()
    assert leg.x0 >= box.x1                                           # right of the axes
    # the axes' limits hold every curve
    lo, hi = mag.get_ylim()
    for ln in curves.values():
        assert lo <= np.min(ln.get_ydata()) and np.max(ln.get_ydata()) <= hi


@pytest.mark.parametrize("kw, message", [
    (dict(phase="no"), "^phase must be True or False, got 'no'$"),
    (dict(phase=1), "^phase must be True or False, got 1$"),
    (dict(pairs=True), r"^pairs must be a list of \(output, input\), got True$"),
    (dict(ax=5), "^ax must be a matplotlib Axes, got int$")])
def test_plot_options_that_are_not_what_they_say_are_refused(kw, message):
    """phase="no" drew the phase (a non-empty string is true); pairs=True and ax=5 came out
    as numpy's TypeError and matplotlib's AttributeError."""
    m = ds.FrequencyModel(ds.load_scene("planar2").equilibrium())
    r = ds.frf(m, [1.0, 2.0], inputs="fz", outputs="z")
    with pytest.raises(ds.InvalidParameterError, match=message):
        r.plot(**kw)


def _toy_frf(**kw):
    """A 2 x 2 receptance on 20 frequencies (1-3 Hz) and three modes in the band, one of
    each class: no model to build."""
    from types import SimpleNamespace

    from dynstiff.results import FRFResult
    f = np.linspace(1.0, 3.0, 20)
    H = (1.0 + np.arange(4.0).reshape(1, 2, 2)) * np.exp(1j * f)[:, None, None]
    res = FRFResult(f, H, ("fx", "fz"), ("x", "z"), "receptance", **kw)
    modes = SimpleNamespace(freq_hz=np.array([1.5, 2.0, 2.5]), kind=("global", "mixed", "local"))
    return res, modes


def test_frf_phase_figure_size_and_axes_heights():
    """With the phase, a new figure is 10 x 6 in, the magnitude axes twice as tall as the
    phase axes."""
    res, modes = _toy_frf()
    fig = plot_frf(res, modes, phase=True)
    assert tuple(fig.get_size_inches()) == (10.0, 6.0)
    mag, ph = fig.axes
    assert mag.get_position().height == pytest.approx(2 * ph.get_position().height)


def test_frf_twin_dash_pattern_and_widths():
    """Curves are solid and 1.0 wide; the reciprocal twin drawn second (z / fx after
    x / fz) is dashed 4 on, 3 off (in line widths) and 2.0 wide, on both axes."""
    res, _ = _toy_frf()
    fig = plot_frf(res, pairs=[("x", "fz"), ("z", "fx")], phase=True)
    for ax in fig.axes:
        first, twin = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("frf-")]
        assert first.get_linestyle() == "-" and first.get_linewidth() == 1.0
        assert twin.get_linewidth() == 2.0
        # matplotlib has no public getter of a dash sequence: its unscaled pattern
        assert twin._unscaled_dash_pattern == (0, (4, 3))
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels == ["x / fz", "z / fx (= x / fz, reciprocity)"]


def test_frf_legend_font_place_and_handles():
    """The legend (8 pt) stands right of the axes, its top left corner at (1.01, 1.0); it
    shows each curve by its own line and each mode class by a dashed line 0.8 wide in the
    class's colour, after the curves."""
    from matplotlib.colors import to_rgba

    from dynstiff.plot.common import CATEGORY_LABELS, COLORS
    res, modes = _toy_frf()
    fig = plot_frf(res, modes)
    ax = fig.axes[0]
    leg = ax.get_legend()
    assert [t.get_fontsize() for t in leg.get_texts()] == [8.0] * 5
    fig.canvas.draw()
    box = leg.get_window_extent()                                     # its top left corner
    corner = ax.transAxes.inverted().transform((box.x0, box.y1))
    np.testing.assert_allclose(corner, [1.01, 1.0], atol=1e-9)
    assert [t.get_text() for t in leg.get_texts()] == [
        "x / fx", "z / fz", CATEGORY_LABELS["global"], CATEGORY_LABELS["mixed"],
        CATEGORY_LABELS["local"]]
    curves = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("frf-")]
    hs = leg.legend_handles
    assert [to_rgba(h.get_color()) for h in hs[:2]] == [to_rgba(c.get_color()) for c in curves]
    assert [h.get_linestyle() for h in hs[:2]] == ["-", "-"]
    for h, cat in zip(hs[2:], ("global", "mixed", "local")):
        assert to_rgba(h.get_color()) == to_rgba(COLORS[cat])
        assert h.get_linewidth() == 0.8 and h.get_linestyle() == "--"


def test_frf_title_states_the_damping():
    """The title (10 pt, whatever the default font size) reads "FRF (kind), natural
    frequencies dashed" and, below, the result's damping; only an "undamped" result adds
    the note on its peaks."""
    head = "FRF (receptance), natural frequencies dashed\n"
    res, _ = _toy_frf(damping="undamped")
    with plt.rc_context({"font.size": 12.0}):
        ax = plot_frf(res).axes[0]
    assert ax.get_title() == head + "undamped; each peak is the grid's value next to a pole"
    assert ax.title.get_fontsize() == 10.0
    res, _ = _toy_frf(damping="loss factor 0.002")
    assert plot_frf(res).axes[0].get_title() == head + "loss factor 0.002"


def test_frf_result_without_damping_or_unit():
    """A result with no ``damping`` says "not stated" in the title; with no ``unit`` the
    y label is "|kind|" alone."""
    from types import SimpleNamespace
    res, _ = _toy_frf()
    bare = SimpleNamespace(freq_hz=res.freq_hz, H=res.H, inputs=res.inputs,
                           outputs=res.outputs, kind="mobility")
    ax = plot_frf(bare).axes[0]
    assert ax.get_title() == "FRF (mobility), natural frequencies dashed\nnot stated"
    assert ax.get_ylabel() == "|mobility|"


def test_frf_layout_new_figure_tight_given_ax_kept():
    """A new figure is laid out tight, its legend (right of the axes) inside it; a given
    ``ax`` keeps its place (its figure is not laid out again)."""
    res, modes = _toy_frf()
    for phase in (False, True):
        fig = plot_frf(res, modes, phase=phase)
        fig.canvas.draw()
        leg = fig.axes[0].get_legend().get_window_extent()
        assert 0 <= leg.x0 and leg.x1 <= fig.bbox.x1 and leg.y1 <= fig.bbox.y1
    fig0, ax = plt.subplots(figsize=(8, 4.5))
    before = ax.get_position().bounds
    fig = plot_frf(res, modes, ax=ax)
    assert fig is ax.figure and ax.get_position().bounds == before


def test_frf_axes_span_the_frequencies_and_the_phase_axes_its_half_turns():
    """Both axes span exactly the result's frequencies; the frequency label is under the
    lowest axes (the magnitude's without the phase); the phase axes span -190 to 190 deg
    with ticks every 90 deg from -180 and a grid; all drawn without a warning."""
    res, modes = _toy_frf()
    f = res.freq_hz
    ax = plot_frf(res, modes).axes[0]
    assert ax.get_xlim() == (f[0], f[-1]) and ax.get_xlabel() == "frequency [Hz]"
    with warnings.catch_warnings():
        warnings.simplefilter("error")                 # drawn without any warning
        mag, ph = plot_frf(res, modes, phase=True).axes
    assert mag.get_xlim() == ph.get_xlim() == (f[0], f[-1])
    assert mag.get_xlabel() == "" and ph.get_xlabel() == "frequency [Hz]"
    assert ph.get_ylabel() == "phase [deg]" and ph.get_ylim() == (-190.0, 190.0)
    assert list(ph.get_yticks()) == [-180, -90, 0, 90, 180]
    assert all(line.get_visible() for line in ph.get_ygridlines())


def test_frf_legend_corner_where_the_axes_top_right_is_empty():
    """The legend's top left corner is at (1.01, 1.0) even where the axes' top right corner
    is empty (one falling curve, no modes), where a "best" placement would move it."""
    from dynstiff.results import FRFResult
    f = np.linspace(1.0, 3.0, 20)
    res = FRFResult(f, (f ** -4.0)[:, None, None].astype(complex), ("fz",), ("z",),
                    "receptance")
    fig = plot_frf(res)
    ax = fig.axes[0]
    fig.canvas.draw()
    box = ax.get_legend().get_window_extent()
    corner = ax.transAxes.inverted().transform((box.x0, box.y1))
    np.testing.assert_allclose(corner, [1.01, 1.0], atol=1e-9)


def test_frf_marks_every_mode_of_the_band_and_no_other():
    """A mode between the last two frequencies of the grid is inside the band and marked,
    on both axes; modes below the first or above the last frequency are not. The mode
    lines are dashed, 0.6 wide and translucent (alpha 0.6)."""
    res, _ = _toy_frf()
    from types import SimpleNamespace
    f = res.freq_hz
    inside = 0.5 * (f[-2] + f[-1])
    modes = SimpleNamespace(freq_hz=np.array([0.95, 1.5, inside, 3.05]),
                            kind=("global", "mixed", "local", "global"))
    fig = plot_frf(res, modes, phase=True)
    for ax in fig.axes:
        marks = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("mode-")]
        assert [ln.get_xdata()[0] for ln in marks] == [1.5, inside]
        assert [ln.get_gid() for ln in marks] == ["mode-mixed", "mode-local"]
        for ln in marks:
            assert ln.get_linestyle() == "--" and ln.get_linewidth() == 0.6
            assert ln.get_alpha() == 0.6
