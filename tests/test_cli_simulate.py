"""The `dynstiff` command line, run in this process (conftest.run_cli): the simulate commands
(dynstiff/cli/simulate.py)."""

import re

import pytest
from conftest import inverted_stewart_scene, run_cli

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




def test_cli_simulate_follows_a_trajectory_of_the_scene(tmp_path):
    """A CASPR cubic trajectory (1.5 s, ending at 0.1 m/s) commanded through quasi-static
    lengths: the platform follows it within 1 % of the cable length; the CSV holds the
    path's 1.5 s plus the 0.1 s settling, every 10 ms."""
    scene = inverted_stewart_scene(tmp_path / "s.toml")
    out = run_cli("simulate", str(scene), "--trajectory", "swing", "--segments", "1",
                  "--time", "0.1", "--dt", "1e-2", "--quiet", "--csv", str(tmp_path / "t.csv"))
    assert out.returncode == 0, out.stderr
    m = re.search(r"trajectory 'swing' \(1.5 s, 2 waypoints\).*deviation from the "
                  r"quasi-static path ([0-9.e-]+) m \(([0-9.e-]+) % of", out.stdout)
    assert m and 0 < float(m.group(2)) < 1.0
    import pandas as pd
    df = pd.read_csv(tmp_path / "t.csv", comment="#")
    assert len(df) == 161 and abs(df["x desired [m]"].iloc[-1] - 0.2) < 1e-12
    bad = run_cli("simulate", str(scene), "--trajectory", "swing", "--target", "0", "0", "1")
    assert bad.returncode == 2 and "--target or --trajectory, not both" in bad.stderr
    bad = run_cli("simulate", "fourcable", "--trajectory", "swing")
    assert bad.returncode == 2 and "no [[trajectories]]" in bad.stderr
