"""The main job of `dynstiff demo` (dynstiff/report/robot.py, robot_report), run in-process; the
command itself is run in test_cli.py."""

import numpy as np
import pytest


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
    text, files = robot_report(scene, tmp_path, n_points=200)
    from dynstiff.analyses.settings import analysis_settings
    pm = ds.design_checks(scene.robot, scene.equilibrium().pose,
                          **analysis_settings(scene).check_options()).platform
    assert [f.name for f in files] == (
        ["statics.csv", "modes.csv", "checks.csv", "frf.csv", "frf.png"]
        + [f"mode_shape_{k + 1}.png" for k in pm.index] + ["report.html"])
    assert all(f.parent == tmp_path and f.stat().st_size > 0 for f in files)
    # the printed report as documented: the title line, then the four titled sections
    lines = text.splitlines()
    assert lines[0] == f"dynstiff: cogiro: {scene.description}"
    titles = ["Statics (elastic catenaries)",
              "First 40 modes, which hold the platform modes (Wittrick-Williams count: none "
              "missed; undamped frequencies)", "Cable model", "Design checks"]
    at = [lines.index(t) for t in titles]
    assert at == sorted(at) and all(lines[k - 1] == "" for k in at)
    assert lines[at[1] + 1].split()[:3] == ["mode", "freq", "[Hz]"]
    model = ds.FrequencyModel(scene.equilibrium())
    n_band = ds.eigenfrequencies(model, fmax_hz=12.0).size
    assert n_band > 40
    assert len(seen["modes"].freq_hz) == n_band
    # the CSV tables as documented: their own name and units lines, modes.csv's fourth
    # column, frf.csv's inputs and outputs
    import pandas as pd
    units = {"statics.csv": "SI, in the column names",
             "modes.csv": "Hz; mode shapes normalised to unit platform kinetic energy",
             "checks.csv": "as each row's value and limit",
             "frf.csv": "in each row's unit column"}
    for name, unit in units.items():
        head = [ln for ln in (tmp_path / name).read_text().splitlines() if ln.startswith("#")]
        assert f'# table: "{name}"' in head and f'# units: "{unit}"' in head
    table = pd.read_csv(tmp_path / "modes.csv", comment="#")
    assert list(table.columns[:4]) == ["mode", "freq [Hz]", "kind", "platform mode"]
    assert table["platform mode"].dtype == bool and 0 < table["platform mode"].sum() < len(table)
    frf_rows = pd.read_csv(tmp_path / "frf.csv", comment="#")
    assert set(frf_rows["input"]) == {"fx", "fz"} and set(frf_rows["output"]) == {"x", "z"}


def test_a_worded_html_flag_is_refused_and_nothing_is_written(tmp_path):
    import pytest

    import dynstiff as ds
    from dynstiff.report.robot import robot_report
    with pytest.raises(ds.InvalidParameterError, match="^html must be True or False, got 'no'"):
        robot_report(ds.load_scene("planar2"), tmp_path / "out", html="no")
    assert not (tmp_path / "out").exists()


def _summary_page(monkeypatch, freq_hz, cable_fraction, index, complete=True, passed=True,
                  segments=0, forbidden_hz=None):
    """The page of _page (robot.py) for platform modes given by hand: the document's
    helpers (tested in test_report_document.py) replaced by stubs, the summary paragraph and
    the section headings returned."""
    import re
    from types import SimpleNamespace

    import pandas as pd

    import dynstiff.report.document as doc
    from dynstiff.analyses.platform_modes import PlatformModes
    from dynstiff.report.robot import _page
    for name in ("title_rows", "input_rows"):
        monkeypatch.setattr(doc, name, lambda *a: [("k", "v")])
    for name in ("cable_frame", "platform_mode_table"):
        monkeypatch.setattr(doc, name, lambda *a: pd.DataFrame({"c": [1]}))
    monkeypatch.setattr(doc, "spread_note", lambda pm: "")
    modes = SimpleNamespace(freq_hz=np.asarray(freq_hz, float),
                            cable_energy_fraction=np.asarray(cable_fraction, float))
    pm = PlatformModes(modes, np.asarray(index, int), {}, complete,
                       2.0 if complete else np.nan, 3.0, "" if complete else "ceiling")
    st = SimpleNamespace(check_options=lambda: {"participation": 0.05}, rung="dsm",
                         band_hz=(0.0, 10.0), model_rtol=0.01, forbidden_hz=forbidden_hz,
                         damping=SimpleNamespace(text=lambda: "damping none"))
    checks = SimpleNamespace(passed=passed, rows=[])
    rec = SimpleNamespace(rung="dsm" if not segments else "lumped", segments=segments,
                          predicted_error=1e-3,
                          to_frame=lambda: pd.DataFrame({"r": [1]}))
    png = (b"\x89PNG", "figure")
    page = _page(SimpleNamespace(name="s"), None, st, checks, pm, rec, (1e-3, "cause"),
                 pd.DataFrame({"x": [1]}), [png, png], "a,b\n", 3, 10)
    summary = page[page.index("Summary:"):].split("</p>")[0]
    return summary, re.findall(r"<h2>(.*?)</h2>", page), page


def test_the_page_has_the_documented_sections_in_order(monkeypatch):
    _, heads, _ = _summary_page(monkeypatch, [1.0, 2.0], [0.5, 0.5], [0])
    assert heads == ["Inputs", "Design checks", "Platform modes", "Frequency response",
                     "Cable model", "Assumptions", "Statics", "Downloads"]


def test_the_summary_verdict_is_worded_as_documented(monkeypatch):
    ok, _, _ = _summary_page(monkeypatch, [1.0, 2.0], [0.5, 0.5], [0], passed=True)
    bad, _, _ = _summary_page(monkeypatch, [1.0, 2.0], [0.5, 0.5], [0], passed=False)
    assert ok.startswith("Summary: all checks passed; 1 platform mode(s), the first at 1 Hz;")
    assert bad.startswith("Summary: some checks FAILED; 1 platform mode(s), the first at 1 Hz;")


def test_the_summary_names_the_lowest_mode_below_the_first_platform_mode_moving_it(monkeypatch):
    """Mode 1 (0.5 Hz) has a platform share 1 - 0.99 = 1 % < 5 %, mode 2 (0.7 Hz) 1 - 0.9 =
    10 %: mode 2 is named, below the first platform mode (mode 3, 1.25 Hz)."""
    s, _, _ = _summary_page(monkeypatch, [0.5, 0.7, 1.25, 2.0], [0.99, 0.9, 0.2, 0.3], [2, 3])
    assert ("2 platform mode(s), the first at 1.25 Hz (the lowest mode the platform moves in, "
            "with a share of 10%, is mode 2 at 0.7 Hz); cable model dsm") in s


@pytest.mark.parametrize("case", ["first is lowest", "incomplete", "none held"])
def test_the_summary_names_no_mode_when_none_below_the_first_platform_mode_moves_it(
        monkeypatch, case):
    """The lowest mode holding >= 5 % in the platform is the first platform mode itself (not
    below it), or the search is incomplete, or no mode reaches 5 %: nothing is added."""
    if case == "first is lowest":
        s, _, _ = _summary_page(monkeypatch, [0.5, 1.25], [0.99, 0.2], [1])
        assert "the first at 1.25 Hz; cable model" in s
    elif case == "incomplete":
        s, _, _ = _summary_page(monkeypatch, [0.5, 1.25], [0.5, 0.5], [], complete=False)
        assert "; the platform modes not all found; cable model" in s
    else:
        s, _, _ = _summary_page(monkeypatch, [0.5, 1.25], [0.99, 0.98], [1])
        assert "the first at 1.25 Hz; cable model" in s
    assert "lowest mode" not in s


@pytest.mark.parametrize("complete", [True, False])
def test_the_platform_modes_section_opens_with_the_documented_paragraph(monkeypatch, complete):
    """found_hz = 2 Hz given: the paragraph ends with "(2 Hz)"; without it (an incomplete
    search) the note says why."""
    from html import unescape
    _, _, page = _summary_page(monkeypatch, [0.5, 1.25], [0.5, 0.5], [1] if complete else [],
                               complete=complete)
    sec = unescape(page[page.index("<h2>Platform modes</h2>"):])
    para = ("The modes every modal verdict is about (theory.md §12.4): the mode that moves "
            "each free DOF most and every global mode below the frequency by which every "
            "free DOF has half of its participation" + (" (2 Hz)" if complete else "")
            + "; undamped frequencies.")
    assert sec.startswith(f"<h2>Platform modes</h2>\n<p>{para}</p>")
    note = "The search for the platform modes is incomplete: ceiling"
    assert (note in sec) is not complete


@pytest.mark.parametrize("segments, forbidden", [(0, None), (12, (4.0, 6.5))])
def test_the_cable_model_and_assumptions_say_what_was_and_was_not_checked(monkeypatch,
                                                                          segments, forbidden):
    """The recommendation names its segments only for a lumped rung; the assumptions say
    the forbidden band's two checks are not asked when none is given, else give the band,
    and that no mode below the highest listed is missed (the Wittrick-Williams count)."""
    import html
    _, _, page = _summary_page(monkeypatch, [1.0, 2.0], [0.5, 0.5], [0], segments=segments,
                               forbidden_hz=forbidden)
    text = html.unescape(page)
    rec = "lumped with 12 segments (predicted" if segments else "dsm (predicted"
    assert f"Recommended for this band: {rec} error 0.001)." in text
    assert ("forbidden band 4-6.5 Hz" if forbidden else
            "forbidden band none given: its two checks are not asked") in text
    assert ("every mode below the highest listed found (Wittrick-Williams count)") in text


def test_the_download_is_the_modes_table_described_in_full(monkeypatch):
    """The one download: modes.csv, with the number of modes and what the file holds."""
    import html
    _, _, page = _summary_page(monkeypatch, [1.0, 2.0], [0.5, 0.5], [0])
    text = html.unescape(page)
    assert ("All 3 modes computed (modes.csv: frequencies, kinds, participations, platform "
            "shapes; also written beside this page)") in text
    assert 'download="modes.csv"' in text


def test_the_report_reuses_the_checks_modes_and_rounds_the_pose_to_four_decimals(tmp_path,
                                                                              monkeypatch):
    """planar2 at a pose rotated by 0.0123456 rad, the settings asking for exactly as many
    modes as the design checks searched: the report's pose line rounds to 4 decimals, the
    table holds the checks' modes without a second search (the only search is the band's
    marks, by fmax_hz), and the page says how many modes it holds and on how many
    frequencies (those of frf.csv) the FRFs are."""
    import html
    from dataclasses import replace

    import dynstiff as ds
    import dynstiff.analyses.modes
    from dynstiff.analyses.settings import analysis_settings
    from dynstiff.report.robot import robot_report
    from dynstiff.robot.pose import as_pose
    scene = ds.load_scene("planar2")
    scene = replace(scene, pose=as_pose([0.1, 0.0, -9.5, 0.0, 0.0123456, 0.0]),
                    unstretched_lengths=None)
    st = analysis_settings(scene)
    found = len(ds.design_checks(scene.robot, scene.pose, **st.check_options()).platform.modes)
    calls, real = [], dynstiff.analyses.modes.modes

    def spy(model, **kw):
        calls.append(kw)
        return real(model, **kw)

    monkeypatch.setattr(dynstiff.analyses.modes, "modes", spy)
    text, _ = robot_report(scene, tmp_path, settings=replace(st, n_modes=found), n_points=50)
    assert text.splitlines()[1] == "pose [0.1, 0.0, -9.5] m, rotation [0.0, 0.0123, 0.0] rad"
    assert [sorted(kw) for kw in calls] == [["fmax_hz"]]
    page = html.unescape((tmp_path / "report.html").read_text())
    assert f"All {found} modes computed (modes.csv:" in page
    import pandas as pd
    n_freq = pd.read_csv(tmp_path / "frf.csv", comment="#")["freq [Hz]"].nunique()
    assert n_freq > 50
    assert f"FRFs on {n_freq} frequencies, refined around every mode of the band" in page
