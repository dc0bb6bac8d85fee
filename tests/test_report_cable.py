"""The single-cable report (dynstiff/report/cable.py): its figure holds the stiffness curves and a
marker at every pole of the band; its statics table, text and files are as documented."""

import numpy as np
import pytest


def test_report_figure_content():
    """The figure has the documented x label, a y label in N/m, and one line per curve plus
    one per pole inside the band."""
    import matplotlib
    matplotlib.use("Agg")
    from dynstiff.report.cable import cable_report
    rep = cable_report(fmax_hz=8.0, n_points=500)
    fig = rep.plot()
    ax = fig.axes[0]
    assert ax.get_xlabel() == "frequency [Hz]"
    assert "[N/m]" in ax.get_ylabel()
    assert len(ax.get_lines()) == 3 + sum(rep.modes.freq_hz <= 8.0)   # curves + pole markers


def test_report_options_are_checked_naming_them():
    """fmax_hz=True was a 1 Hz band, n_points=4.7 four points, n_points=1 a single
    frequency; a worded chordwise_inertia flag was true."""
    from dynstiff.errors import InvalidParameterError
    from dynstiff.report.cable import cable_report
    for kw, message in [(dict(fmax_hz=True), "^fmax_hz must be a real number, got True"),
                        (dict(n_points=4.7), r"^n_points must be an integer >= 2, got 4\.7"),
                        (dict(n_points=1), "^n_points must be an integer >= 2, got 1"),
                        (dict(chordwise_inertia="no"), "^chordwise_inertia must be True or")]:
        with pytest.raises(InvalidParameterError, match=message):
            cable_report(**kw)


_ROWS = [("chord length", "m"), ("unstretched length", "m"), ("tension at end B", "N"),
         ("tension at anchor A", "N"), ("mean tension", "N"), ("horizontal tension H", "N"),
         ("sag (max distance to chord)", "m"), ("chord inclination", "deg"),
         ("Irvine parameter lambda^2", "-"), ("chord stiffness K0/(1+lambda^2/12)", "N/m"),
         ("transverse stiffness T/L", "N/m"), ("force on end B, x", "N"),
         ("force on end B, y", "N"), ("force on end B, z", "N")]


def test_demo_cable_is_the_documented_cogiro_cable():
    """The demo scene is the one its docstring gives: anchor a_0, attachment b_0 on the
    platform at (0, 0, 1) m, 0.064 kg/m, EA = 8.2051e-6 m^2 * 17 GPa, 300 N."""
    from dynstiff.report.cable import demo_cable
    anchor, end, cable, tension = demo_cable()
    np.testing.assert_array_equal(anchor, [-7.1775, -5.4361, 5.3911])
    np.testing.assert_allclose(end, np.array([0.5032, -0.4928, 0.0]) + [0.0, 0.0, 1.0],
                               rtol=0, atol=1e-15)
    assert cable.mass_per_length == 0.064
    assert cable.EA == pytest.approx(8.2051e-6 * 17e9, rel=1e-14)
    assert tension == 300.0


def test_statics_frame_rows_units_and_values():
    """The statics table has the documented rows and units, in order, and its values agree
    with the catenary state: the requested end tension, |B - A|, the chord's angle to the
    horizontal, and the 0 Hz dynamic stiffness (chord K_uu, transverse K_ww)."""
    from dynstiff.cable.dsm import chord_parameters
    from dynstiff.report.cable import cable_report, demo_cable
    anchor, end, _, tension = demo_cable()
    rep = cable_report(fmax_hz=2.0, n_points=3)
    s = rep.state
    df = rep.statics_frame()
    assert list(df.columns) == ["quantity", "value", "unit"]
    assert list(zip(df["quantity"], df["unit"])) == _ROWS
    v = dict(zip(df["quantity"], df["value"].astype(float)))
    chord = np.asarray(end) - anchor
    rel = dict(rtol=1e-9)
    np.testing.assert_allclose(v["chord length"], np.linalg.norm(chord), **rel)
    np.testing.assert_allclose(v["unstretched length"], s.unstretched_length, **rel)
    np.testing.assert_allclose(v["tension at end B"], tension, rtol=1e-6)
    np.testing.assert_allclose(v["tension at anchor A"], np.hypot(s.H, s.V0), **rel)
    np.testing.assert_allclose(v["mean tension"], s.mean_tension, **rel)
    np.testing.assert_allclose(v["horizontal tension H"], s.H, **rel)
    np.testing.assert_allclose(v["sag (max distance to chord)"], s.sag, **rel)
    np.testing.assert_allclose(
        v["chord inclination"], np.degrees(np.arctan2(abs(chord[2]), np.hypot(*chord[:2]))),
        **rel)
    np.testing.assert_allclose(v["Irvine parameter lambda^2"],
                               chord_parameters(s).lambda_sq, **rel)
    np.testing.assert_allclose(v["chord stiffness K0/(1+lambda^2/12)"], rep.K[0, 0, 0],
                               rtol=1e-6)
    np.testing.assert_allclose(v["transverse stiffness T/L"], rep.K[0, 2, 2], rtol=1e-6)
    force = [v[f"force on end B, {c}"] for c in "xyz"]
    np.testing.assert_allclose(force, s.force_on_end, **rel)
    np.testing.assert_allclose(np.linalg.norm(force), tension, rtol=1e-6)


def test_text_headings_and_lines():
    """The text starts with the documented title and headings; one line per statics row
    (quantity then unit) and one line per mode (frequency in Hz, label)."""
    from dynstiff.report.cable import cable_report
    rep = cable_report(fmax_hz=2.0, n_points=3, n_modes=4)
    lines = rep.text().splitlines()
    assert lines[:3] == ["dynstiff single-cable report", "", "Statics (exact elastic catenary)"]
    for line, (q, unit) in zip(lines[3:3 + len(_ROWS)], _ROWS):
        assert line.split()[0] == q.split()[0] and line.endswith(" " + unit)
        assert q in line
    k = 3 + len(_ROWS)
    assert lines[k:k + 2] == [
        "", "Clamped-clamped natural frequencies (poles of the dynamic stiffness)"]
    modes = lines[k + 2:]
    assert len(modes) == 4
    for line, f, lab in zip(modes, rep.modes.freq_hz, rep.modes.labels):
        assert float(line.split()[0]) == round(f, 5) and line.endswith("Hz   " + lab)


def test_report_grid_and_given_scene():
    """The frequency grid runs from 0 to fmax_hz in n_points points; a given end and tension
    are used (the state ends at that point with that tension)."""
    from dynstiff.report.cable import cable_report, demo_cable
    anchor, _, cable, _ = demo_cable()
    end = np.array([0.5, -0.5, 2.0])
    rep = cable_report(end=end, tension=450.0, fmax_hz=3.0, n_points=7)
    np.testing.assert_allclose(rep.freq_hz, [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0], atol=1e-15)
    assert rep.K.shape == (7, 3, 3)
    np.testing.assert_array_equal(rep.state.end, end)
    np.testing.assert_array_equal(rep.state.anchor, anchor)
    np.testing.assert_allclose(rep.state.tension_at_end, 450.0, rtol=1e-6)


def test_report_chordwise_inertia_flag_is_used():
    """chordwise_inertia adds the consistent axial mass -omega^2 (m L0) / 3 to K_uu alone
    (cable_dynamic_stiffness docstring); both values of the flag are honoured."""
    from dynstiff.report.cable import cable_report
    on = cable_report(fmax_hz=6.0, n_points=4, chordwise_inertia=True)
    off = cable_report(fmax_hz=6.0, n_points=4, chordwise_inertia=False)
    mass = on.state.cable.mass_per_length * on.state.unstretched_length
    omega = 2 * np.pi * on.freq_hz
    np.testing.assert_allclose(on.K[:, 0, 0] - off.K[:, 0, 0], -omega**2 * mass / 3,
                               rtol=1e-6, atol=1e-9)
    d = on.K - off.K
    d[:, 0, 0] = 0.0
    assert np.abs(d).max() < 1e-8 * np.abs(on.K).max()


def test_report_figure_documented_style():
    """The figure is 8 x 4.5 in; the curves |K_uu|, |K_vv|, |K_ww| have width 1.2 and the
    documented labels (in a lower-left legend); the pole markers are dotted grey "0.6"
    lines of width 0.6; labels and title as documented."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgba

    from dynstiff.report.cable import cable_report
    rep = cable_report(fmax_hz=8.0, n_points=50)
    fig = rep.plot()
    try:
        np.testing.assert_allclose(fig.get_size_inches(), [8.0, 4.5])
        ax = fig.axes[0]
        assert ax.get_yscale() == "log"
        lines = ax.get_lines()
        labels = ["K_uu (chord)", "K_vv (in-plane)", "K_ww (out-of-plane)"]
        for k, (line, lab) in enumerate(zip(lines[:3], labels)):
            assert line.get_label() == lab
            assert line.get_linewidth() == 1.2
            np.testing.assert_allclose(line.get_xdata(), rep.freq_hz)
            np.testing.assert_allclose(line.get_ydata(), np.abs(rep.K[:, k, k]))
        poles = lines[3:]
        assert len(poles) == sum(rep.modes.freq_hz <= 8.0) > 0
        for line in poles:
            assert line.get_linestyle() == ":"
            assert line.get_linewidth() == 0.6
            assert to_rgba(line.get_color()) == to_rgba("0.6")
        assert ax.get_ylabel() == "|dynamic stiffness| [N/m]"
        assert ax.get_title() == ("End-B dynamic stiffness of one sagging cable "
                                  "(dotted: fixed-end modes)")
        legend = ax.get_legend()
        assert [t.get_text() for t in legend.get_texts()] == labels
        assert legend._loc == 3          # "lower left"
    finally:
        plt.close(fig)


def test_write_report_files(tmp_path):
    """write_report creates the missing folders, writes the four files (the text, the two
    CSV tables without index column) and a PNG of 960 x 540 pixels (120 dpi)."""
    import struct

    import pandas as pd

    from dynstiff.report.cable import cable_report, write_report
    rep = cable_report(fmax_hz=2.0, n_points=20, n_modes=3)
    out = tmp_path / "a" / "b"
    files = write_report(rep, out)
    assert [f.name for f in files] == ["report.txt", "statics.csv", "modes.csv",
                                       "dynamic_stiffness.png"]
    assert all(f.parent == out and f.is_file() for f in files)
    assert files[0].read_text(encoding="utf-8") == rep.text()
    statics = pd.read_csv(files[1])
    assert list(statics.columns) == ["quantity", "value", "unit"]
    assert list(zip(statics["quantity"], statics["unit"])) == _ROWS
    modes = pd.read_csv(files[2])
    assert list(modes.columns) == list(rep.modes.to_frame().columns)
    assert len(modes) == 3
    head = files[3].read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", head[16:24]) == (960, 540)
