"""Package layering and the command-line main job."""

import subprocess
import sys



def test_import_does_not_load_matplotlib_or_pandas():
    code = ("import sys, dynstiff; "
            "bad = [m for m in ('matplotlib', 'pandas', 'mpmath') if m in sys.modules]; "
            "print(','.join(bad))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_demo_writes_report(tmp_path):
    out = subprocess.run([sys.executable, "-m", "dynstiff", "demo", "--out", str(tmp_path),
                          "--points", "400"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "in-plane symmetric 1" in out.stdout
    for name in ["report.txt", "statics.csv", "modes.csv", "dynamic_stiffness.png"]:
        assert (tmp_path / name).stat().st_size > 0
    import pandas as pd
    modes = pd.read_csv(tmp_path / "modes.csv")
    assert list(modes.columns) == ["freq [Hz]", "Omega [-]", "family", "order"]
    assert modes["freq [Hz]"].is_monotonic_increasing


def test_report_figure_content():
    import matplotlib
    matplotlib.use("Agg")
    from dynstiff.report import cable_report
    rep = cable_report(fmax_hz=8.0, n_points=500)
    fig = rep.plot()
    ax = fig.axes[0]
    assert ax.get_xlabel() == "frequency [Hz]"
    assert "[N/m]" in ax.get_ylabel()
    assert len(ax.get_lines()) == 3 + sum(rep.modes.freq_hz <= 8.0)   # curves + pole markers


def test_cli_rejects_unknown_option():
    out = subprocess.run([sys.executable, "-m", "dynstiff", "demo", "--bogus"],
                         capture_output=True, text=True)
    assert out.returncode == 2
    assert "--bogus" in out.stderr


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "dynstiff", *args], capture_output=True,
                          text=True)


def test_cli_modes_table_and_csv(tmp_path):
    out = run_cli("modes", "cogiro", "-n", "6", "--csv", str(tmp_path / "m.csv"))
    assert out.returncode == 0, out.stderr
    assert "global" in out.stdout and "freq [Hz]" in out.stdout
    import pandas as pd
    df = pd.read_csv(tmp_path / "m.csv")
    assert len(df) == 6 and df["freq [Hz]"].is_monotonic_increasing
    assert df["kind"].isin(["global", "local"]).all()


def test_cli_errors_exit_nonzero_with_message(tmp_path):
    out = run_cli("modes", "nope")
    assert out.returncode == 2 and "unknown scene 'nope'" in out.stderr
    out = run_cli("modes", "cogiro", "--pose", "9", "0", "1")
    assert out.returncode == 2 and "pose [9.0" in out.stderr
    bad = tmp_path / "bad.toml"
    bad.write_text("[platform]\nmass = 1.0\nbogus_key = 3\n[[cables]]\nanchor=[0,0,1]\n"
                   "attachment=[0,0,0]\n")
    out = run_cli("modes", str(bad))
    assert out.returncode == 2 and "line 3" in out.stderr and "bogus_key" in out.stderr
    out = run_cli("modes", str(tmp_path / "missing.toml"))
    assert out.returncode == 2 and "missing.toml" in out.stderr


def test_cli_frf_writes_table_and_figure(tmp_path):
    out = run_cli("frf", "cogiro", "--from", "fz", "--to", "z", "--band", "1", "3", "--points",
                  "400", "--csv", str(tmp_path / "f.csv"), "--plot", str(tmp_path / "f.png"))
    assert out.returncode == 0, out.stderr
    import pandas as pd
    df = pd.read_csv(tmp_path / "f.csv")
    assert len(df) == 400 and set(df["output"]) == {"z"} and set(df["input"]) == {"fz"}
    # the largest response in 1-3 Hz is the first (vertical) global mode of CoGiRo
    import dynstiff as ds
    f1 = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()).eigenfrequencies(1)[0]
    peak = df.loc[df["magnitude"].idxmax(), "freq [Hz]"]
    assert abs(peak - f1) < 2.0 / 399 + 1e-9            # within one frequency step
    assert (tmp_path / "f.png").stat().st_size > 10_000
    bad = run_cli("frf", "cogiro", "--band", "5", "1")
    assert bad.returncode == 2 and "--band" in bad.stderr
    bad = run_cli("frf", "cogiro", "--from", "fq")
    assert bad.returncode == 2 and "fq" in bad.stderr
