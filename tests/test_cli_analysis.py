"""The `dynstiff` command line, run in this process (conftest.run_cli): the help of the
analysis commands, `scenes` and `modes` (dynstiff/cli/analysis.py)."""

import numpy as np
import pytest
from conftest import _metadata, _spy, cli_help, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


# ------------------------------------------------------------------------ help, scenes
def test_help_of_the_analysis_commands_names_each_option(monkeypatch):
    """`dynstiff -h` says what `scenes`, `modes` and `frf` do; `modes -h`, `frf -h` and
    `check -h` show each option with its metavar and its help, as written for the user."""
    top = cli_help(monkeypatch)
    assert "scenes list the built-in scenes" in top
    assert ("modes eigenfrequencies with global/local labels and energy fractions "
            "(Wittrick-Williams: none missed)") in top
    assert "frf frequency response functions of the platform" in top
    mo = cli_help(monkeypatch, "modes")
    assert ("--band LO HI band of interest LO HI [Hz]: every mode in it, both ends included "
            "(default: the first --n-modes)") in mo
    assert ("-n N, --n-modes N number of modes: the lowest N (default: the scene's n_modes; "
            "with --band or --fmax, all in the band)") in mo
    assert ("--json FILE write the table as JSON: the full modes table ('-': standard "
            "output)") in mo
    fr = cli_help(monkeypatch, "frf")
    assert ("load channel(s), the FRF's input (default: fz, else the force or moment of the "
            "first free DOF)") in fr
    assert "response channel(s), the FRF's output (default: z, else the first free DOF)" in fr
    assert "--point X Y Z platform point whose translation is output [m, platform frame]" in fr
    assert "--csv FILE write the table as CSV: the tidy FRF table ('-': standard output)" in fr
    assert "--uff FILE write the FRFs as UFF 58 records (needs dynstiff[exchange])" in fr
    ck = cli_help(monkeypatch, "check")
    assert ("--participation PARTICIPATION platform share of a mode's kinetic energy from "
            "which it is held to the margin (default 0.05)") in ck
    assert ("--frf-limit FRF_LIMIT largest admissible receptance / static value in the "
            "forbidden band (default 10)") in ck


def test_cli_scenes_lists_every_built_in_scene_with_its_description():
    """`dynstiff scenes`: one line per built-in scene, its name padded to 12 characters and
    its description, exit 0, nothing on standard error."""
    out = run_cli("scenes")
    assert out.returncode == 0 and out.stderr == ""
    assert out.stdout == "".join(f"{n:<12s} {ds.load_scene(n).description}\n"
                                 for n in ds.list_scenes())


# ------------------------------------------------------------------------ modes
def test_cli_modes_passes_n_fmax_and_max_modes_to_the_analysis(monkeypatch, capsys):
    """`modes -n N` asks the analysis for the lowest N modes with no top frequency; `--fmax F`
    for every mode below F and no count; `--max-modes` reaches it in both."""
    import dynstiff.analyses.modes
    from dynstiff.cli import main
    calls = []
    _spy(monkeypatch, dynstiff.analyses.modes, "modes", calls)
    assert main(["modes", "planar2", "-n", "3", "--max-modes", "50"]) == 0
    assert main(["modes", "planar2", "--fmax", "4", "--max-modes", "60"]) == 0
    assert [c[1] for c in calls] == [dict(n_modes=3, fmax_hz=None, max_modes=50),
                                     dict(n_modes=None, fmax_hz=4.0, max_modes=60)]
    capsys.readouterr()


def test_cli_modes_refuses_more_modes_than_max_modes():
    """`-n 5 --max-modes 3`: exit 2 with the one-line error naming both, nothing computed or
    printed on standard output."""
    out = run_cli("modes", "planar2", "-n", "5", "--max-modes", "3")
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr == ("dynstiff: error: -n 5 is more than --max-modes 3; raise --max-modes "
                          "to compute them\n")


def test_cli_modes_report_table_and_header(tmp_path):
    """`modes planar2 -n 4 --csv FILE`: the first line names the model and the scene's
    damping; the printed table is the CSV's columns of the summary, without an index, each
    float to 6 digits; the CSV header carries the units of the modes table."""
    import pandas as pd
    path = tmp_path / "m.csv"
    out = run_cli("modes", "planar2", "-n", "4", "--csv", path)
    assert out.returncode == 0, out.stderr
    damping = ds.load_scene("planar2").damping.text()
    lines = out.stdout.splitlines()
    assert lines[0] == f"dsm model (undamped natural frequencies; {damping}):"
    df = pd.read_csv(path, comment="#")
    cols = ["mode", "freq [Hz]", "kind", "platform share [-]", "dominant dof",
            "massless freq [Hz]", "shift from massless [-]"]
    table = df[cols].to_string(index=False, float_format=lambda x: f"{x:.6g}")
    assert "\n".join(lines[1:]) == table + f"\nwrote {path}"
    assert _metadata(path)["units"] == ("Hz; shapes normalised to unit platform kinetic "
                                        "energy")


def test_cli_modes_lumped_takes_the_segments_given(tmp_path):
    """`--model lumped --segments 4`: the model is built with 4 segments per cable (its modes
    are those of that model), the report and the table's header say so."""
    import pandas as pd
    path = tmp_path / "l.csv"
    out = run_cli("modes", "pendulum", "--model", "lumped", "--segments", "4", "-n", "3",
                  "--csv", path)
    assert out.returncode == 0, out.stderr
    scene = ds.load_scene("pendulum")
    assert out.stdout.splitlines()[0] == (f"lumped model, 4 segments per cable (undamped "
                                          f"natural frequencies; {scene.damping.text()}):")
    expected = ds.modes(ds.build_model(scene.equilibrium(), "lumped", segments=4),
                        n_modes=3).freq_hz
    got = pd.read_csv(path, comment="#")["freq [Hz]"].to_numpy()
    np.testing.assert_allclose(got, expected, rtol=1e-12)
    assert _metadata(path)["segments"] == 4


def test_cli_modes_of_a_model_with_fewer_modes_than_asked(monkeypatch, capsys):
    """The massless spring model of the pendulum has one mode per free DOF: `-n 5` lists
    those it has, asks the analysis for exactly that many and says so in the first line."""
    import dynstiff.analyses.modes
    from dynstiff.cli import main
    scene = ds.load_scene("pendulum")
    n_dof = ds.build_model(scene.equilibrium(), "spring").n_dof
    assert n_dof < 5
    calls = []
    _spy(monkeypatch, dynstiff.analyses.modes, "modes", calls)
    assert main(["modes", "pendulum", "--model", "spring", "-n", "5"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == (f"spring model (it has {n_dof} modes; 5 asked) (undamped natural "
                        f"frequencies; {scene.damping.text()}):")
    assert [c[1]["n_modes"] for c in calls] == [n_dof]
    assert len(lines) == 2 + n_dof                     # the line, the header, the modes


def test_cli_modes_exact_model_up_to_fmax(monkeypatch, tmp_path):
    """`--model exact --fmax 3`: the exact rung of the scene's equilibrium, resolved to
    1.05 x 3 Hz; the modes listed are every one of its modes below 3 Hz."""
    import pandas as pd

    import dynstiff.models.ladder
    calls = []
    _spy(monkeypatch, dynstiff.models.ladder, "build_model", calls)
    path = tmp_path / "e.csv"
    out = run_cli("modes", "planar2", "--model", "exact", "--fmax", "3", "--csv", path)
    assert out.returncode == 0, out.stderr
    eq = ds.load_scene("planar2").equilibrium()
    exact = [c for c in calls if c[0][1:2] == ("exact",)]
    assert len(exact) == 1 and exact[0][1] == {"fmax_hz": 1.05 * 3.0}
    np.testing.assert_allclose(exact[0][0][0].pose.position, eq.pose.position, atol=1e-12)
    model = ds.build_model(eq, "exact", fmax_hz=1.05 * 3.0)
    got = pd.read_csv(path, comment="#")["freq [Hz]"].to_numpy()
    np.testing.assert_allclose(got, ds.modes(model, fmax_hz=3.0).freq_hz, rtol=1e-9)


def test_cli_modes_exact_model_band_doubles_until_it_holds_n_modes(monkeypatch, capsys):
    """`--model exact -n 2` on the pendulum (one mode below 25 Hz): the exact rung is built
    for a band doubled from 25 Hz until it holds 2 modes, and its 2 lowest are listed."""
    import dynstiff.models.ladder
    from dynstiff.cli import main
    calls = []
    _spy(monkeypatch, dynstiff.models.ladder, "build_model", calls, limit=30)
    assert main(["modes", "pendulum", "--model", "exact", "-n", "2", "--quiet"]) == 0
    capsys.readouterr()
    bands = [c[1]["fmax_hz"] for c in calls]
    assert all(c[0][1] == "exact" for c in calls)
    assert len(bands) > 1 and bands == [25.0 * 2 ** k for k in range(len(bands))]
    eq = ds.load_scene("pendulum").equilibrium()
    for band in bands[-2:]:
        held = ds.analyses.eigen.mode_count(ds.build_model(eq, "exact", fmax_hz=band),
                                            2 * np.pi * band)[0]
        assert (held >= 2) == (band == bands[-1])


def test_cli_modes_exact_model_gives_up_at_10_khz(monkeypatch):
    """When no band up to 10 kHz holds the modes asked, `--model exact -n N` stops with the
    one-line error after doubling the band from 25 Hz to its last value below 10 kHz."""
    import dynstiff.analyses.eigen
    import dynstiff.models.ladder
    bands = []

    def build(eq, rung, **kw):
        bands.append(kw["fmax_hz"])
        if len(bands) > 30:
            raise AssertionError("the band does not grow")
        return object()
    monkeypatch.setattr(dynstiff.models.ladder, "build_model", build)
    monkeypatch.setattr(dynstiff.analyses.eigen, "mode_count", lambda m, w: np.array([0]))
    out = run_cli("modes", "planar2", "--model", "exact", "-n", "7")
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr == ("dynstiff: error: -n 7: more modes than the exact model holds below "
                          "10 kHz\n")
    expected, band = [], 25.0
    while band <= 1e4:
        expected.append(band)
        band *= 2.0
    assert bands == expected


def test_cli_modes_and_check_show_their_progress_label_on_a_terminal():
    """On a terminal, `modes` and `check` show a bar labelled with the command and the
    scene while they compute."""
    for argv, label in ((["modes", "planar2", "-n", "2"], "modes planar2: "),
                        (["check", "planar2"], "check planar2: ")):
        run = run_cli(*argv, terminal=True)
        assert run.returncode == 0 and label in run.stderr
        assert run_cli(*argv, "--quiet", terminal=True).stderr == ""      # --quiet: no bar


def test_cli_modes_table_and_csv(tmp_path):
    out = run_cli("modes", "cogiro", "-n", "6", "--csv", tmp_path / "m.csv", "--plot",
                  tmp_path / "m.png")
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "m.png").read_bytes().startswith(b"\x89PNG")
    assert "global" in out.stdout and "freq [Hz]" in out.stdout
    import pandas as pd
    df = pd.read_csv(tmp_path / "m.csv", comment="#")
    assert len(df) == 6 and df["freq [Hz]"].is_monotonic_increasing
    assert df["kind"].isin(["global", "mixed", "local"]).all()


def test_cli_modes_model_choice(tmp_path):
    """--model: the 30-segment lumped model lands within 1e-3 of the closed form on CoGiRo's
    first modes, the exact cable within 3e-4 (the closed form's error); the massless rungs
    give platform modes only, the straight spring stiffer than the catenary (sag softens the
    cable)."""
    import pandas as pd
    tables = {}
    for m in ("dsm", "exact", "lumped", "catenary", "spring"):
        out = run_cli("modes", "cogiro", "-n", "3", "--model", m, "--csv",
                      str(tmp_path / f"{m}.csv"))
        assert out.returncode == 0, out.stderr
        assert out.stdout.startswith(f"{m} model")
        tables[m] = pd.read_csv(tmp_path / f"{m}.csv", comment="#")["freq [Hz]"].to_numpy()
    assert abs(tables["lumped"] / tables["dsm"] - 1).max() < 1e-3
    assert 1e-6 < abs(tables["exact"] / tables["dsm"] - 1).max() < 3e-4   # theory.md §11.5
    assert (tables["spring"] > tables["catenary"]).all()
    assert (pd.read_csv(tmp_path / "spring.csv", comment="#")["kind"] == "global").all()
    bad = run_cli("modes", "cogiro", "--model", "lumped", "--segments", "0")
    assert bad.returncode == 2 and "--segments" in bad.stderr
    bad = run_cli("modes", "cogiro", "--model", "beam")
    assert bad.returncode == 2 and "beam" in bad.stderr


def test_lengths_on_a_scene_with_held_dofs_hold_them_at_the_scene_pose(capsys):
    """planar2 holds y and the rotations: forward statics from --lengths starts from (and
    keeps the held DOFs of) the scene's pose instead of asking for an option that does not
    exist; the lengths of the scene's own pose give back its frequencies."""
    from dynstiff.cli import main
    scene = ds.load_scene("planar2")
    L0 = scene.equilibrium().unstretched_lengths
    assert main(["modes", "planar2", "-n", "3", "--csv", "-", "--lengths",
                 *[repr(float(x)) for x in L0]]) == 0
    via_lengths = capsys.readouterr().out
    assert main(["modes", "planar2", "-n", "3", "--csv", "-"]) == 0
    at_pose = capsys.readouterr().out

    def rows(text):
        return [ln for ln in text.splitlines() if not ln.startswith("# ")][1:4]
    f1 = [float(r.split(",")[1]) for r in rows(via_lengths)]
    f2 = [float(r.split(",")[1]) for r in rows(at_pose)]
    np.testing.assert_allclose(f1, f2, rtol=1e-7)


@pytest.mark.parametrize("model", [None, "dsm", "exact", "spring"])
def test_cli_modes_segments_without_the_lumped_model_is_refused(model, tmp_path):
    """--segments sets the lumped model's cables: with any other model (the scene's dsm by
    default) it would be ignored, so it is refused with one line naming the model, exit 2,
    and no table written."""
    csv = tmp_path / "m.csv"
    extra = () if model is None else ("--model", model)
    out = run_cli("modes", "planar2", "--segments", "5", *extra, "--csv", csv)
    assert (out.returncode, out.stdout) == (2, "")
    assert out.stderr == (f"dynstiff: error: --segments applies to the lumped model only "
                          f"(--model lumped), not to the {model or 'dsm'!r} model\n")
    assert not csv.exists()


def test_modes_band_with_n_lists_the_lowest_n_in_the_band(tmp_path, capsys):
    """`modes --band 3 6 -n N` lists the lowest N modes in [3, 6] Hz, not the lowest N from
    0 Hz cut to the band (which left none); when the band holds fewer than N the first line
    says how many it holds."""
    import pandas as pd

    from dynstiff.cli import main
    eq = ds.load_scene("planar2").equilibrium()
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=6.0)
    inband = f[f >= 3.0]
    assert np.sum(f < 3.0) >= 2 and inband.size >= 3         # -n 2 from 0 Hz misses the band
    for n in (1, 2):
        path = tmp_path / f"n{n}.csv"
        assert main(["modes", "planar2", "--band", "3", "6", "-n", str(n), "--csv",
                     str(path)]) == 0
        got = pd.read_csv(path, comment="#")
        np.testing.assert_allclose(got["freq [Hz]"], inband[:n], rtol=1e-9)
        assert got["mode"].tolist() == [int(np.sum(f < 3.0)) + 1 + k for k in range(n)]
    capsys.readouterr()
    many = inband.size + 5
    assert main(["modes", "planar2", "--band", "3", "6", "-n", str(many)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith(f"dsm model ({inband.size} in the band; {many} asked) (")
    assert len(lines) == 2 + inband.size


def test_modes_band_lists_every_mode_in_it_and_frf_defaults_to_a_free_dof(tmp_path, capsys):
    """--band LO HI is the band of interest in every command: `modes --band 3 6` lists the
    eigenfrequencies in [3, 6] Hz (Wittrick-Williams, none missed), `--fmax 6` all below;
    `frf` without --load/--response takes the scene's first free DOF (the pendulum's ry)."""
    import pandas as pd

    from dynstiff.cli import main
    eq = ds.load_scene("planar2").equilibrium()
    f = ds.eigenfrequencies(ds.FrequencyModel(eq), fmax_hz=6.0)
    assert main(["modes", "planar2", "--band", "3", "6", "--csv", str(tmp_path / "b.csv")]) == 0
    got = pd.read_csv(tmp_path / "b.csv", comment="#")["freq [Hz]"].to_numpy()
    np.testing.assert_allclose(got, f[f >= 3.0], rtol=1e-9)
    assert main(["modes", "planar2", "--fmax", "6", "--csv", str(tmp_path / "f.csv")]) == 0
    got = pd.read_csv(tmp_path / "f.csv", comment="#")["freq [Hz]"].to_numpy()
    np.testing.assert_allclose(got, f, rtol=1e-9)
    lo, e = float(got[1]), tmp_path / "e.csv"               # LO on a mode: in [LO, HI]
    assert main(["modes", "planar2", "--band", repr(lo), "6", "--csv", str(e)]) == 0
    assert pd.read_csv(e, comment="#")["freq [Hz]"].iloc[0] == lo
    assert 0 < np.sum(f < 3.0) < f.size                     # the band cut something
    capsys.readouterr()
    assert main(["frf", "pendulum", "--points", "50"]) == 0
    assert capsys.readouterr().out.startswith("receptance ry/my:")
