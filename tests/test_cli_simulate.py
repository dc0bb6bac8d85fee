"""The `dynstiff` command line, run in this process (conftest.run_cli): the simulate command
(dynstiff/cli/simulate.py), its free vibration, its help and the options it refuses."""

import json
import re
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from conftest import cli_help, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


def test_cli_simulate_free_vibration_and_line(tmp_path):
    out = run_cli("simulate", "fourcable", "--time", "2", "--segments", "1", "--csv",
                  str(tmp_path / "t.csv"), "--plot", str(tmp_path / "s.png"))
    assert out.returncode == 0, out.stderr
    import re
    pairs = re.findall(r"  ([0-9.]+) Hz ~ mode ([0-9.]+) Hz \(([-+0-9.e]+) Hz\)", out.stdout)
    peaks = [float(p) for p, _, _ in pairs]
    assert pairs and "prominence >= 3%" in out.stdout
    for p, m, d in pairs:                     # each peak named with its nearest mode
        assert abs(float(p) - float(m) - float(d)) < 2e-3 * max(1.0, float(p))
    f1 = ds.eigenfrequencies(ds.FrequencyModel(ds.load_scene("fourcable").equilibrium()), 1)[0]
    assert min(abs(p - f1) for p in peaks) < 0.5                       # resolution 0.5 Hz
    import pandas as pd
    assert len(pd.read_csv(tmp_path / "t.csv", comment="#")) == 1001
    out = run_cli("simulate", "planar2", "--target", "1", "0", "-10", "--speed", "1", "--ramp",
                  "0.5", "--time", "0.2", "--segments", "2", "--quiet", "--plot",
                  str(tmp_path / "line.png"))
    assert out.returncode == 0, out.stderr
    assert f"wrote {tmp_path / 'line.png'}" in out.stdout
    assert (tmp_path / "line.png").stat().st_size > 10_000      # announced and written
    dev = float(re.search(r"quasi-static path ([0-9.e-]+) m", out.stdout).group(1))
    assert 0 < dev < 0.01
    bad = run_cli("simulate", "cogiro", "--offset", "1", "2")
    assert bad.returncode == 2 and "--offset needs 6 values" in bad.stderr
    bad = run_cli("simulate", "cogiro", "--band", "5", "1")
    assert bad.returncode == 2 and "--band" in bad.stderr
    bad = run_cli("simulate", "cogiro", "--dt", "-1")
    assert bad.returncode == 2 and "dt" in bad.stderr


def test_cli_simulate_spectrum_reports_no_leakage():
    """CoGiRo free vibration from 1 mm in x: the spectrum named peaks at 0.55 and 1.55 Hz,
    leakage 1000 times below the real ones, inside the forbidden band. With the prominence
    rule every reported peak is within 2 resolution bins of a linearised mode."""
    out = run_cli("simulate", "cogiro", "--time", "5", "--segments", "4")
    assert out.returncode == 0, out.stderr
    pairs = re.findall(r"  ([0-9.]+) Hz ~ mode ([0-9.]+) Hz", out.stdout)
    assert pairs
    for p, m in pairs:
        assert float(p) > 1.6 and abs(float(p) - float(m)) < 0.4, out.stdout


# ---------------------------------------------------------------- spies of the library calls
# The commands' own work (the options they pass on, what they print and write) is checked
# against fakes of the expensive library calls: a simulation, its spectrum and the
# linearised frequencies (free vibration), or the tracking of a path.


class _FakeSpectrum:
    def __init__(self, channel, peaks_hz):
        self.channel = channel
        self.freq_hz = np.linspace(0.0, 125.0, 501)
        self.peaks_hz = np.asarray(peaks_hz, dtype=float)
        self.resolution_hz = 0.3125


class _FakeResponse:
    wall_time = 0.123456

    def __init__(self, spy):
        self.spy = spy
        self.energy = SimpleNamespace(relative_residual=np.array([2e-9, -3.25e-7, 1e-8]))

    def to_frame(self):
        return pd.DataFrame({"x [m]": [0.2, 0.2005, 0.1998], "T_B0 [N]": [10.0, 10.5, 9.5]},
                            index=pd.Index([0.0, 0.5, 1.0], name="t [s]"))

    def spectrum(self, channel, prominence=None):
        self.spy.spectra.append(dict(channel=channel, prominence=prominence))
        sp = _FakeSpectrum(channel, self.spy.peaks)
        self.spy.spectrum = sp
        return sp


@pytest.fixture
def free_spy(monkeypatch):
    """The lumped model, its simulation, spectrum and linearised frequencies replaced by
    spies: the peaks (largest first) and model frequencies are set by the test."""
    spy = SimpleNamespace(peaks=[], modes=[], build=[], simulate=[], spectra=[], eigen=[],
                          plots=[], spectrum=None)

    def build_model(eq, rung, segments=30, **kw):
        spy.build.append(dict(eq=eq, rung=rung, segments=segments, kw=kw))
        return "lumped model"

    def simulate(model, t_end, dt, **kw):
        spy.simulate.append(dict(model=model, t_end=t_end, dt=dt, kw=kw))
        return _FakeResponse(spy)

    def eigenfrequencies(model, n_modes=None, fmax_hz=None, **kw):
        spy.eigen.append(dict(model=model, n_modes=n_modes, fmax_hz=fmax_hz, kw=kw))
        return np.array(spy.modes, dtype=float)

    def plot_spectrum(sp, **kw):
        import matplotlib.pyplot as plt
        spy.plots.append(dict(sp=sp, kw=kw))
        return plt.figure(figsize=(1, 1))
    monkeypatch.setattr("dynstiff.models.ladder.build_model", build_model)
    monkeypatch.setattr("dynstiff.lumped.simulate", simulate)
    monkeypatch.setattr("dynstiff.analyses.eigen.eigenfrequencies", eigenfrequencies)
    monkeypatch.setattr("dynstiff.plot.plot_spectrum", plot_spectrum)
    return spy


def _free_report(spy, offset, time, dt, segments, ch, band):
    """The report of a free vibration run, from what the fakes returned."""
    sp, f_model = spy.spectrum, np.array(spy.modes, dtype=float)
    peaks = sorted(f for f in spy.peaks if band[0] <= f <= band[1])
    near = [f_model[np.argmin(abs(f_model - f))] for f in peaks]
    inband = [f for f in spy.modes if band[0] <= f <= band[1]]
    return (f"free vibration from offset {[float(v) for v in offset]}, {time:g} s, dt = {dt:g} s, "
            f"{segments} segments per cable (damping: the cables' own, time domain): wall "
            f"{_FakeResponse.wall_time:.3g} s, energy residual {3.25e-7:.2e}\n"
            f"spectrum peaks of {ch} in {band[0]:g}-{band[1]:g} Hz (Hann window, "
            f"resolution {sp.resolution_hz:.3g} Hz, prominence >= 3% of the largest), each "
            f"with the nearest linearised mode:\n"
            + "".join(f"  {f:.4g} Hz ~ mode {m:.4g} Hz ({f - m:+.3g} Hz)\n"
                      for f, m in zip(peaks, near))
            + f"linearised lumped-model frequencies in the band [Hz] ({len(inband)}): "
            + ", ".join(f"{f:.4g}" for f in inband[:8])
            + (", ..." if len(inband) > 8 else "") + "\n")


def test_free_vibration_report_names_each_peak_with_its_nearest_mode(free_spy, tmp_path):
    """Free vibration of fourcable (scene band 0.1-50 Hz): the run's options reach the
    model and the simulation (1 mm along x, the first free DOF); the report lists the peaks
    in the band, ascending, each with the nearest model frequency (not the lowest) and the
    difference, and the model frequencies in the band, its top included, the first 8 then
    '...'; the CSV holds the time history under the metadata header."""
    free_spy.modes = [0.05, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 50.0, 60.0]
    free_spy.peaks = [3.1, 0.08, 7.9, 55.0, 1.05]
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", "fourcable", "--time", "2", "--dt", "0.004", "--segments", "3",
                  "--csv", csv)
    assert out.returncode == 0 and out.stderr == ""
    scene = ds.load_scene("fourcable")
    assert scene.band_hz == (0.1, 50.0)
    (b,), (s,), (e,) = free_spy.build, free_spy.simulate, free_spy.eigen
    assert b["rung"] == "lumped" and b["segments"] == 3 and type(b["segments"]) is int
    assert np.allclose(b["eq"].pose.position, scene.pose.position)
    assert s["model"] == "lumped model" and s["t_end"] == 2.0 and s["dt"] == 0.004
    assert s["kw"]["initial"].tolist() == [1e-3, 0, 0, 0, 0, 0]
    assert free_spy.spectra == [dict(channel="x", prominence=0.03)]
    assert e["model"] == "lumped model" and e["fmax_hz"] == 0.5 * 125.0
    expected = _free_report(free_spy, [1e-3, 0, 0, 0, 0, 0], 2, 0.004, 3, "x", (0.1, 50.0))
    assert "  1.05 Hz ~ mode 1 Hz (+0.05 Hz)\n" in expected            # the nearest mode
    assert "(10): 1, 2, 3, 4, 5, 6, 7, 8, ...\n" in expected           # 50 Hz is in the band
    assert out.stdout == expected + f"wrote {csv}\n"
    text = csv.read_text()
    head = [line for line in text.splitlines() if line.startswith("#")]
    meta = {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in head)}
    assert list(meta) == ["dynstiff", "scene", "pose", "model", "date", "segments", "dt [s]",
                          "damping", "units"]
    assert meta["scene"] == "fourcable" and meta["model"] == "lumped"
    assert np.allclose(meta["pose"]["position [m]"], scene.pose.position)
    assert meta["pose"]["rotation [rad]"] == [0.0, 0.0, 0.0]
    assert meta["segments"] == 3 and meta["dt [s]"] == 0.004
    assert meta["damping"] == "the cables' own (time domain)"
    assert meta["units"] == "SI, in the column names"
    df = pd.read_csv(csv, comment="#")
    assert list(df.columns) == ["t [s]", "x [m]", "T_B0 [N]"] and df["x [m]"].tolist() == [
        0.2, 0.2005, 0.1998]


def test_free_vibration_band_defaults_to_the_model_frequencies(free_spy, monkeypatch):
    """A scene without band_hz: the band is 0 to 1.5 times the 8th model frequency (the
    last one when there are fewer); no '...' when 8 or fewer frequencies are in it."""
    import dataclasses

    import dynstiff.scenes
    load = dynstiff.scenes.load_scene
    monkeypatch.setattr("dynstiff.scenes.load_scene",
                        lambda name: dataclasses.replace(load(name), band_hz=None))
    free_spy.modes = [1.0, 2.0, 4.0]
    free_spy.peaks = [2.1, 6.5, 5.9]
    out = run_cli("simulate", "fourcable", "--time", "1", "--segments", "2")
    assert out.returncode == 0, out.stderr
    assert out.stdout == _free_report(free_spy, [1e-3, 0, 0, 0, 0, 0], 1, 0.002, 2, "x",
                                      (0.0, 6.0))
    assert "spectrum peaks of x in 0-6 Hz" in out.stdout
    assert "(3): 1, 2, 4\n" in out.stdout


def test_free_vibration_without_band_nor_mode_is_refused_with_one_line(free_spy, monkeypatch,
                                                                        tmp_path):
    """A scene without band_hz and a lumped model with no mode below half the spectrum's
    top: one line naming --band and --dt, exit 2, and no table written; with --band the
    peaks are listed, with no nearest mode (nan)."""
    import dataclasses

    import dynstiff.scenes
    load = dynstiff.scenes.load_scene
    monkeypatch.setattr("dynstiff.scenes.load_scene",
                        lambda name: dataclasses.replace(load(name), band_hz=None))
    free_spy.modes = []
    free_spy.peaks = [2.1]
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", "fourcable", "--time", "1", "--dt", "0.004", "--csv", csv)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr == ("dynstiff: error: no band: the scene has no band_hz and the lumped model "
                          "has no mode below 62.5 Hz (half the spectrum's top at --dt 0.004 "
                          "s); give --band LO HI or a smaller --dt\n")
    assert not csv.exists()
    free_spy.modes = [70.0]                                   # one mode: the band 0-105 Hz
    assert run_cli("simulate", "fourcable", "--time", "1", "--dt", "0.004").returncode == 0
    free_spy.modes = []
    out = run_cli("simulate", "fourcable", "--time", "1", "--band", "1", "3")
    assert out.returncode == 0 and "\n  2.1 Hz ~ mode nan Hz (+nan Hz)\n" in out.stdout


def test_free_vibration_options_reach_the_run_and_the_plot(free_spy, tmp_path):
    """--offset, --channel, --band and the defaults --time 5, --dt 0.002, --segments 10
    reach the model, the simulation and the spectrum; --plot draws the spectrum with the
    model's frequencies and the band given, and is announced."""
    free_spy.modes = [1.0, 3.0, 5.0]
    free_spy.peaks = [3.2, 0.5]
    png = tmp_path / "s.png"
    offset = [0.0, 0.002, 0.0, 0.0, 0.0, 0.0]
    out = run_cli("simulate", "fourcable", "--offset", *offset, "--channel", "rx", "--band",
                  "2", "20", "--plot", png)
    assert out.returncode == 0, out.stderr
    (b,), (s,) = free_spy.build, free_spy.simulate
    assert b["segments"] == 10 and s["t_end"] == 5.0 and s["dt"] == 0.002
    assert s["kw"]["initial"].tolist() == offset
    assert free_spy.spectra == [dict(channel="rx", prominence=0.03)]
    (p,) = free_spy.plots
    assert p["sp"] is free_spy.spectrum and p["kw"]["band_hz"] == (2.0, 20.0)
    assert p["kw"]["modes"].tolist() == free_spy.modes
    assert out.stdout == _free_report(free_spy, offset, 5, 0.002, 10, "rx",
                                      (2.0, 20.0)) + f"wrote {png}\n"
    assert png.stat().st_size > 0


def test_free_vibration_table_on_stdout_keeps_the_report_on_stderr(free_spy, tmp_path):
    """--csv -: standard output holds the table alone; the report and the 'wrote' line of
    --plot go to standard error. The header's pose is the start given by --pose, its
    rotation included."""
    free_spy.modes = [1.0]
    free_spy.peaks = [1.1]
    png = tmp_path / "s.png"
    out = run_cli("simulate", "cogiro", "--pose", "0", "0", "1", "0", "0", "0.05",
                  "--segments", "1", "--csv", "-", "--plot", png)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("# dynstiff: ") and "wrote" not in out.stdout
    assert "free vibration" not in out.stdout
    assert out.stderr.startswith("free vibration from offset ")
    assert out.stderr.endswith(f"\nwrote {png}\n")
    meta = {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in
                                          out.stdout.splitlines() if line.startswith("#"))}
    assert meta["scene"] == "cogiro"
    assert meta["pose"]["position [m]"] == pytest.approx([0.0, 0.0, 1.0])
    assert meta["pose"]["rotation [rad]"] == pytest.approx([0.0, 0.0, 0.05])
    assert free_spy.build[0]["eq"].pose.rotation == pytest.approx([0.0, 0.0, 0.05])


def test_free_vibration_shows_the_time_elapsed_on_a_terminal(free_spy):
    """On a terminal the simulation shows a bar labelled 'simulate SCENE' with the time
    elapsed; --quiet: nothing on standard error."""
    free_spy.modes = [1.0]
    free_spy.peaks = [1.1]
    run = run_cli("simulate", "fourcable", "--segments", "1", terminal=True)
    code, err = run.returncode, run.stderr
    assert code == 0
    assert re.search(r"\rsimulate fourcable: \d\d:\d\d\r", err), err
    run = run_cli("simulate", "fourcable", "--segments", "1", "--quiet", terminal=True)
    code, err = run.returncode, run.stderr
    assert code == 0 and err == ""


@pytest.mark.parametrize("given, message", [
    (("--trajectory", "t", "--pose", "0", "0", "1"),
     "--pose does not apply with --trajectory (the trajectory sets the start and the motion)"),
    (("--trajectory", "t", "--lengths", "1", "2", "--offset", "0.001", "0", "0", "0", "0", "0",
      "--speed", "1", "--ramp", "2"),
     "--lengths, --offset, --speed, --ramp do not apply with --trajectory (the trajectory sets "
     "the start and the motion)"),
    (("--trajectory", "t", "--band", "1", "2", "--channel", "z"),
     "--band, --channel do not apply with --trajectory (the trajectory sets the start and the "
     "motion)"),
    (("--target", "0", "0", "1", "--offset", "0", "0", "0.001", "0", "0", "0"),
     "--offset does not apply with --target (options of the free vibration)"),
    (("--target", "0", "0", "1", "--band", "1", "2", "--channel", "z"),
     "--band, --channel do not apply with --target (options of the free vibration)"),
    (("--speed", "0.2",), "--speed does not apply without --target (options of the line)"),
    (("--ramp", "0", "--speed", "1"),
     "--speed, --ramp do not apply without --target (options of the line)"),
])
def test_options_that_do_not_apply_are_refused_before_any_work(given, message, tmp_path,
                                                               monkeypatch):
    """An option the chosen run would ignore is refused with one line naming it (exit 2),
    before the scene is read and before any table is written."""
    import dynstiff.scenes
    monkeypatch.setattr(dynstiff.scenes, "load_scene",
                        lambda name: pytest.fail("the scene was read"))
    csv = tmp_path / "t.csv"
    out = run_cli("simulate", "fourcable", *given, "--csv", csv)
    assert (out.returncode, out.stdout) == (2, "")
    assert out.stderr == f"dynstiff: error: {message}\n"
    assert not csv.exists()


def test_simulate_help(monkeypatch):
    """`dynstiff simulate -h`: the usage line and every option with its metavar, choices,
    default and help; `dynstiff -h` names the command with its help."""
    from dynstiff.cli.options import MEANINGS
    assert (" simulate time domain (lumped-mass cables): free vibration from an offset, or a "
            "line commanded through quasi-static cable lengths ") in cli_help(monkeypatch)
    h = cli_help(monkeypatch, "simulate")
    assert h == " ".join((
        "usage: dynstiff simulate [-h] [--pose X [X ...] | --lengths L0 [L0 ...]] "
        "[--time TIME] [--dt DT] [--segments SEGMENTS] [--offset D [D ...]] [--band LO HI] "
        "[--channel {x,y,z,rx,ry,rz}] [--target X Y Z] [--trajectory NAME] [--speed SPEED] "
        "[--ramp RAMP] [--csv FILE] [--json FILE] [--plot FILE] [--quiet] scene",
        f"positional arguments: scene {MEANINGS['scene']}",
        "options: -h, --help show this help message and exit",
        f"--pose X [X ...] {MEANINGS['--pose']}: the start (default: the scene's pose)",
        f"--lengths L0 [L0 ...] {MEANINGS['--lengths']}: instead of --pose",
        "--time TIME duration [s] (after the path's end with --target or --trajectory; "
        "default 5.0)",
        "--dt DT time step [s] (default 0.002)",
        f"--segments SEGMENTS {MEANINGS['--segments']} (default 10)",
        "--offset D [D ...] initial platform offset dx dy dz [m] drx dry drz [rad] (default "
        "1 mm along the first free DOF)",
        f"--band LO HI {MEANINGS['--band']}: the spectrum's peaks and the model's frequencies "
        "in it are listed (default: the scene's band_hz)",
        "--channel {x,y,z,rx,ry,rz} channel of the spectrum (default: the first free DOF)",
        "--target X Y Z target point: move P in a straight line to it [m] instead",
        f"--trajectory NAME {MEANINGS['--trajectory']}: follow it ([[trajectories]], e.g. "
        "from dynstiff import-caspr) through quasi-static cable lengths instead",
        "--speed SPEED path speed of --target [m/s] (default 0.5)",
        "--ramp RAMP speed ramp duration of --target [s] (default 1.0)",
        f"--csv FILE {MEANINGS['--csv']}: the time history ('-': standard output)",
        f"--json FILE {MEANINGS['--json']}: the time history ('-': standard output)",
        f"--plot FILE {MEANINGS['--plot']}: the spectrum with the model's frequencies, or the "
        "path followed (PNG, PDF, SVG, ...)",
        f"--quiet {MEANINGS['--quiet']}: nor the first-run notice (bars are off too when "
        "standard error is not a terminal)"))


@pytest.mark.parametrize("channel", ["x", "y", "z", "rx", "ry", "rz"])
def test_every_channel_reaches_the_spectrum(free_spy, channel):
    """--channel: each of the six platform channels is accepted and analysed."""
    free_spy.modes = [1.0]
    free_spy.peaks = [1.1]
    out = run_cli("simulate", "fourcable", "--segments", "1", "--channel", channel)
    assert out.returncode == 0, out.stderr
    assert free_spy.spectra == [dict(channel=channel, prominence=0.03)]
