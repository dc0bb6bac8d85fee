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
