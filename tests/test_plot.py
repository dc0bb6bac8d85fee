"""Plotting layer (dynstiff.plot): the figures hold the data they claim to; the 3-D view
(dynstiff.report.robot3d) is tested in test_report_robot3d.py.

Every test reads the artists back (axis labels, line data, gids) and compares them with the
results that were plotted; none only checks that a figure exists.
"""

import matplotlib
import numpy as np
import pandas as pd
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.text import Annotation  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.errors import InvalidParameterError  # noqa: E402
from dynstiff.plot import (  # noqa: E402
    plot_frf,
    plot_modes,
    plot_spectrum,
    plot_speed_accuracy,
    plot_veering,
)
from dynstiff.timedomain.response import Spectrum  # noqa: E402


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
    curves = [ln for ln in mag.get_lines() if ln.get_gid() is None]
    assert [c.get_label() for c in curves] == ["z / fz", "x / fx"]
    np.testing.assert_allclose(curves[0].get_ydata(), np.abs(res.H[:, 0, 0]))
    assert mag.get_yscale() == "log" and "receptance" in mag.get_ylabel()
    assert ph.get_xlabel() == "frequency [Hz]" and ph.get_ylabel() == "phase [deg]"
    phase = np.concatenate([ln.get_ydata() for ln in ph.get_lines() if ln.get_gid() is None])
    np.testing.assert_allclose(phase[:5], np.degrees(np.angle(res.H[:5, 0, 0])))
    assert np.nanmax(np.abs(phase)) <= 180.0


def test_frf_honours_ax_and_rejects_bad_input(cogiro_model, cogiro_modes):
    res = ds.frf(cogiro_model, 2 * np.pi * np.linspace(1.0, 2.0, 50), inputs=["fz"],
                           outputs=["z"])
    fig0, ax = plt.subplots()
    fig = plot_frf(res, cogiro_modes, ax=ax, phase=True)      # ax given: magnitude only
    assert fig is ax.figure and fig.axes == [ax]
    with pytest.raises(InvalidParameterError, match="result must be a FRFResult"):
        plot_frf(cogiro_modes)
    with pytest.raises(InvalidParameterError, match=r"pairs.*\('q', 'fz'\)"):
        plot_frf(res, pairs=[("q", "fz")])
    with pytest.raises(InvalidParameterError, match="modes must be a ModalResult"):
        plot_frf(res, modes=[1.0, 2.0])


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
    import pandas as pd

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


# -------------------------------------------------------------------------- spectrum
def synthetic_spectrum(channel, f_peaks, amps):
    f = np.linspace(0.0, 10.0, 401)
    a = 1e-7 + sum(A * np.exp(-0.5 * ((f - fp) / 0.05) ** 2) for fp, A in zip(f_peaks, amps))
    return Spectrum(freq_hz=f, amplitude=a, peaks_hz=np.asarray(f_peaks, dtype=float),
                    peak_amplitudes=np.asarray(amps, dtype=float), channel=channel,
                    window="hann", resolution_hz=0.025)


def test_spectrum_log_amplitude_and_mode_markers():
    sz = synthetic_spectrum("z", [2.2, 3.0], [1e-3, 2e-4])
    srx = synthetic_spectrum("rx", [2.4], [5e-4])
    fig0, ax = plt.subplots()
    fig = plot_spectrum([sz, srx], ax=ax, channels=["z"], modes=[2.2, 3.0, 7.5, 12.0],
                        band_hz=(0.0, 8.0))
    assert fig is ax.figure
    assert ax.get_yscale() == "log" and ax.get_xlabel() == "frequency [Hz]"
    (curve,) = by_gid(ax, "spectrum-")
    assert curve.get_gid() == "spectrum-z"                     # channels= filters
    x, y = curve.get_data()
    assert x.min() > 0 and x.max() <= 8.0                      # the band, without 0 Hz
    np.testing.assert_allclose(y, sz.amplitude[(sz.freq_hz > 0) & (sz.freq_hz <= 8.0)])
    marks = by_gid(ax, "mode-marker")
    assert sorted(m.get_xdata()[0] for m in marks) == [2.2, 3.0, 7.5]   # 12 Hz is outside
    with pytest.raises(InvalidParameterError, match="channels: 'y'"):
        plot_spectrum(sz, channels=["y"])
    with pytest.raises(InvalidParameterError, match="band_hz"):
        plot_spectrum(sz, band_hz=(5.0, 1.0))


def test_spectrum_of_a_simulation_marks_model_modes():
    """A short lumped-mass run of the point-mass robot: its z spectrum peaks near a
    frequency-domain eigenfrequency, which the figure marks (coloured by kind)."""
    from conftest import point_mass_robot

    from dynstiff.lumped import LumpedMassModel
    from dynstiff.timedomain.simulation import simulate
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.0, 0.0, 1.0])
    m = LumpedMassModel(rob, eq.unstretched_lengths, segments=3)
    m.equilibrium()
    run = simulate(m, 2.0, 0.01, initial=[1e-3, 0.0, 2e-3, 0.0, 0.0, 0.0])
    modes = ds.modes(ds.FrequencyModel(eq), 4)
    fig = plot_spectrum(run, channels=["z"], modes=modes, band_hz=(0.0, 10.0))
    ax = fig.axes[0]
    assert [c.get_gid() for c in by_gid(ax, "spectrum-")] == ["spectrum-z"]
    marks = by_gid(ax, "mode-marker")
    assert len(marks) == np.sum(modes.freq_hz <= 10.0)
    colours = {matplotlib.colors.to_hex(m.get_color()) for m in marks}
    assert colours <= {matplotlib.colors.to_hex(c) for c in ("tab:red", "tab:blue")}


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


# ----------------------------------------------------------- results that draw themselves
def test_modal_result_plot_shows_each_mode_at_its_cable_share(cogiro_model):
    md = ds.modes(cogiro_model, 12)
    ax = md.plot().axes[0]
    glob, loc = by_gid(ax, "modes-global"), by_gid(ax, "modes-local")
    assert len(glob) == 1 and len(loc) == 1
    segs = np.concatenate([glob[0].get_segments(), loc[0].get_segments()])
    assert len(segs) == len(md)
    # each stem stands at its mode's frequency and rises to its cable energy fraction
    got = sorted((s[0, 0], s[1, 1]) for s in segs)
    want = sorted(zip(md.freq_hz, md.cable_energy_fraction))
    np.testing.assert_allclose(got, want, rtol=1e-12)


def test_equilibrium_plot_bars_are_the_tensions_and_the_limits(cogiro_eq):
    ax = cogiro_eq.plot().axes[0]
    heights = [p.get_height() for p in by_gid(ax, "tension-B")]
    np.testing.assert_allclose(heights, cogiro_eq.tensions, rtol=1e-12)
    heights = [p.get_height() for p in by_gid(ax, "tension-A")]
    np.testing.assert_allclose(heights, cogiro_eq.anchor_tensions, rtol=1e-12)
    limits = sorted(line.get_ydata()[0] for line in by_gid(ax, "limit-"))
    assert limits == sorted(v for v in cogiro_eq.robot.tension_limits if np.isfinite(v))


def test_recommendation_plot_marks_rungs_that_miss_modes(cogiro_eq):
    rec = ds.recommend_model(cogiro_eq, band_hz=(0.0, 12.0), rtol=1e-3)
    ax = rec.plot(rtol=1e-3).axes[0]
    bars = by_gid(ax, "rung-errors")
    assert [b.get_height() for b in bars][2] == pytest.approx(rec.errors["dsm"], rel=1e-12)
    misses = [t.get_text() for t in ax.texts]
    assert misses.count("misses modes") == sum(not np.isfinite(e) for e in rec.errors.values())
    assert by_gid(ax, "limit-rtol")[0].get_ydata()[0] == 1e-3


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
