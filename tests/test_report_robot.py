"""The main job of `dynstiff demo` (dynstiff/report/robot.py, robot_report), run in-process; the
command itself is run in test_cli.py."""

def test_demo_frf_marks_every_mode_of_its_band(tmp_path, monkeypatch):
    """The table holds the first 40 modes (to 9.6 Hz); the FRF runs to 12 Hz, and every mode
    below 12 Hz is marked on it (the W-W count up to 12 Hz), not only the table's."""
    import dynstiff as ds
    import dynstiff.plot
    from dynstiff.report.robot import robot_report
    seen = {}
    real = dynstiff.plot.plot_frf

    def spy(result, modes=None, **kw):
        seen["modes"] = modes
        return real(result, modes, **kw)

    monkeypatch.setattr(dynstiff.plot, "plot_frf", spy)
    scene = ds.load_scene("cogiro")
    robot_report(scene, tmp_path, n_points=200)
    model = ds.FrequencyModel(scene.equilibrium())
    n_band = ds.eigenfrequencies(model, fmax_hz=12.0).size
    assert n_band > 40
    assert len(seen["modes"].freq_hz) == n_band


def test_a_worded_html_flag_is_refused_and_nothing_is_written(tmp_path):
    import pytest

    import dynstiff as ds
    from dynstiff.report.robot import robot_report
    with pytest.raises(ds.InvalidParameterError, match="^html must be True or False, got 'no'"):
        robot_report(ds.load_scene("planar2"), tmp_path / "out", html="no")
    assert not (tmp_path / "out").exists()
