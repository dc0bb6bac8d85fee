"""The single-cable report (dynstiff/report/cable.py): its figure holds the stiffness curves and a
marker at every pole of the band."""

def test_report_figure_content():
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
    import pytest

    from dynstiff.errors import InvalidParameterError
    from dynstiff.report.cable import cable_report
    for kw, message in [(dict(fmax_hz=True), "^fmax_hz must be a real number, got True"),
                        (dict(n_points=4.7), r"^n_points must be an integer >= 2, got 4\.7"),
                        (dict(n_points=1), "^n_points must be an integer >= 2, got 1"),
                        (dict(chordwise_inertia="no"), "^chordwise_inertia must be True or")]:
        with pytest.raises(InvalidParameterError, match=message):
            cable_report(**kw)
