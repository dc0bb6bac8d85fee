"""The `dynstiff` command line, run in this process (conftest.run_cli): `scenes`, `modes`,
`frf` and `check` (dynstiff/cli/analysis.py)."""

import re

import numpy as np
import pytest
from conftest import cli_help, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


# ------------------------------------------------------------------------ helpers
def _metadata(path):
    """The ``# key: value`` header of a CSV table written by the command line, decoded."""
    import json
    return {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in
                                          path.read_text().splitlines()
                                          if line.startswith("# "))}


def _spy(monkeypatch, module, name, calls, limit=None):
    """Replace ``module.name`` by a wrapper that records (args, kwargs) of each call in
    ``calls`` and calls the real function (more than ``limit`` calls: an error, not a hang)."""
    real = getattr(module, name)

    def spy(*a, **kw):
        calls.append((a, kw))
        if limit is not None and len(calls) > limit:
            raise AssertionError(f"{name} called more than {limit} times")
        return real(*a, **kw)
    monkeypatch.setattr(module, name, spy)
    return real


def _scene_with_free_dofs(tmp_path, base, dofs, **replace):
    """A copy of the built-in scene ``base`` whose platform has only the DOFs ``dofs`` free."""
    from dynstiff.scenes.loader import SCENE_DIR
    text = (SCENE_DIR / f"{base}.toml").read_text()
    text, n = re.subn(r"(?m)^free_dofs = \[.*\]$", "free_dofs = " + str(list(dofs))
                      .replace("'", '"'), text)
    assert n == 1
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / f"{base}_{'_'.join(dofs)}.toml"
    path.write_text(text)
    return path


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


# ------------------------------------------------------------------------ frf
@pytest.mark.parametrize(("base", "dof", "load"), [("fourcable", "x", "fx"),
                                                    ("cogiro", "rz", "mz")])
def test_cli_frf_default_channels_of_the_first_free_dof(tmp_path, base, dof, load):
    """A scene whose only free DOF is x (rz): `frf` without --load/--response gives the FRF
    of that DOF's force (moment) to its motion."""
    scene = _scene_with_free_dofs(tmp_path, base, [dof])
    out = run_cli("frf", scene, "--points", "50", "--band", "1", "3")
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith(f"receptance {dof}/{load}: ")


def test_cli_frf_takes_every_load_and_response_channel(tmp_path):
    """`--load fx fy fz mx my mz --response x y z rx ry rz` on CoGiRo (all six DOFs free):
    the table holds all 36 channels."""
    import pandas as pd
    loads, responses = ["fx", "fy", "fz", "mx", "my", "mz"], ["x", "y", "z", "rx", "ry", "rz"]
    path = tmp_path / "f.csv"
    out = run_cli("frf", "cogiro", "--load", *loads, "--response", *responses, "--band",
                  "1", "1.5", "--points", "20", "--csv", path)
    assert out.returncode == 0, out.stderr
    df = pd.read_csv(path, comment="#")
    assert sorted(set(zip(df["output"], df["input"]))) == sorted(
        (o, i) for o in responses for i in loads)
    assert out.stdout.startswith("receptance x/fx: ")


def test_cli_frf_passes_kind_point_and_channels_to_the_analysis(monkeypatch, capsys):
    """`--kind mobility --point X Y Z --load fx --response x z`: the FRF is computed with
    those, and the report names the kind and the first channel."""
    import dynstiff.analyses.frf
    from dynstiff.cli import main
    calls = []
    _spy(monkeypatch, dynstiff.analyses.frf, "frf", calls)
    assert main(["frf", "planar2", "--kind", "mobility", "--point", "0.5", "0", "-0.25",
                 "--load", "fx", "--response", "x", "z", "--points", "30"]) == 0
    (args, kw), = calls
    assert kw == dict(inputs=["fx"], outputs=["x", "z"], point=[0.5, 0.0, -0.25],
                      kind="mobility")
    assert capsys.readouterr().out.startswith("mobility x/fx: ")


def test_cli_frf_report_of_a_damped_and_of_an_undamped_model(tmp_path):
    """The report's lines: channel, grid and largest |H| (read back from the table), the
    model and its damping; an undamped model adds that its largest |H| is the grid's, a
    damped one does not. The CSV header says where the units are, `wrote` names the file."""
    import pandas as pd

    from dynstiff.params import Damping
    scene = ds.load_scene("pendulum")
    lo, hi = scene.band_hz
    for damping, extra in (([], []), (["--damping", "0", "0", "0"],
                                      ["undamped model: |H| is unbounded at every mode, the "
                                       "largest value is the grid's, not a peak"])):
        csv = tmp_path / "p.csv"
        out = run_cli("frf", "pendulum", "--points", "40", *damping, "--csv", csv)
        assert out.returncode == 0, out.stderr
        df = pd.read_csv(csv, comment="#")
        values = [float(v) for v in damping[1:]] or None
        model = ds.scene_model(scene, damping=values)
        marks = ds.modes(model, fmax_hz=hi)
        k = df["magnitude"].idxmax()
        assert out.stdout.splitlines() == [
            f"receptance ry/my: {len(df)} frequencies {lo:g}-{hi:g} Hz (40 uniform, refined "
            f"at {len(marks)} modes), largest |H| = {df['magnitude'][k]:.4g} at "
            f"{df['freq [Hz]'][k]:.5g} Hz",
            f"dsm model; {(Damping(*values) if values else scene.damping).text()}",
            *extra, f"wrote {csv}"]
        assert _metadata(csv)["units"] == "in the unit column"


def test_cli_frf_writes_uff_after_the_tables(tmp_path):
    """`--uff FILE` writes the FRF as UFF 58 records (one per channel), and the report says
    `wrote` for the table, then for the UFF file."""
    pyuff = pytest.importorskip("pyuff")
    csv, uff = tmp_path / "f.csv", tmp_path / "f.uff"
    out = run_cli("frf", "planar2", "--points", "30", "--response", "x", "z", "--csv", csv,
                  "--uff", uff)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-2:] == [f"wrote {csv}", f"wrote {uff}"]
    assert len(pyuff.UFF(str(uff)).read_sets()) == 2


def test_cli_frf_figure_marks_the_modes_of_the_band(monkeypatch, tmp_path):
    """`frf --plot`: the figure is drawn with the modes of the model up to the band's top
    (the dashed lines at the natural frequencies)."""
    import dynstiff.plot
    from dynstiff.cli import main
    calls = []
    _spy(monkeypatch, dynstiff.plot, "plot_frf", calls)
    assert main(["frf", "planar2", "--points", "50", "--quiet", "--plot",
                 str(tmp_path / "f.png")]) == 0
    (args, kw), = calls
    scene = ds.load_scene("planar2")
    expected = ds.modes(ds.scene_model(scene), fmax_hz=scene.band_hz[1]).freq_hz
    assert args[1] is not None
    np.testing.assert_allclose(args[1].freq_hz, expected, rtol=1e-12)
    assert kw == dict(pairs=[("z", "fz")], phase=True)


# ------------------------------------------------------------------------ check
def test_cli_check_passes_the_options_to_the_design_checks(monkeypatch, capsys):
    """Every option of `check` reaches the design checks: the forbidden band, margin,
    tolerance, participation, FRF limit, model, damping, proximity, sag limit, max modes and
    the uncertain parameters, with the scene's band of interest."""
    import dynstiff.analyses.checks
    from dynstiff.analyses.uncertainty import Uncertain
    from dynstiff.cli import main
    from dynstiff.params import Damping
    calls = []
    _spy(monkeypatch, dynstiff.analyses.checks, "design_checks", calls)
    code = main(["check", "planar2", "--forbidden-band", "0.5", "1.5", "--margin", "0.2",
                 "--rtol", "0.004", "--participation", "0.3", "--frf-limit", "7",
                 "--model", "catenary", "--damping", "0.02", "0.03", "--proximity", "0.07",
                 "--max-sag", "0.015", "--max-modes", "300", "--uncertain", "EA=10%"])
    assert code in (0, 1)
    capsys.readouterr()
    (args, kw), = calls
    scene = ds.load_scene("planar2")
    np.testing.assert_allclose(args[0].anchors, scene.robot.anchors)
    np.testing.assert_allclose(args[1].position, scene.pose.position)
    assert kw == dict(proximity_rtol=0.07, max_sag_ratio=0.015,
                      uncertain={"EA": Uncertain.parse("10%")}, max_modes=300,
                      band_hz=(0.5, 1.5), margin=0.2, model_rtol=0.004, rung="catenary",
                      participation=0.3, frf_limit=7.0,
                      damping=Damping(0.02, 0.03, scene.damping.cable_viscous_damping),
                      model_band_hz=scene.band_hz)


def test_cli_check_advice_when_the_bound_fails_the_recommended_model(tmp_path):
    """planar2 at --rtol 1e-4: the cable-model row fails (its bound) though the recommended
    model is the one checked: the advice line follows the recommendation; with --csv - both go
    to standard error and standard output holds the table alone."""
    from dynstiff.analyses.settings import analysis_settings
    scene = ds.load_scene("planar2")
    rec = ds.recommend_model(scene.equilibrium(), scene.band_hz, 1e-4)
    assert rec.rung == analysis_settings(scene).rung
    out = run_cli("check", "planar2", "--rtol", "1e-4", "--csv", "-")
    assert out.returncode == 1
    assert "FAIL    cable model" in out.stderr
    lines = out.stderr.splitlines()
    i = lines.index(rec.text().splitlines()[0] + f" (over {scene.band_hz[0]:g}-"
                    f"{scene.band_hz[1]:g} Hz, the closed form measured against the exact "
                    f"rung)")
    assert lines[i + 1:] == [
        "  (advice, not a verdict: the measured error is within the tolerance, the "
        "cable-model row holds the model to its bound, computed without the exact rung "
        "(theory.md §11.6); --model exact passes the row)"]
    assert "advice" not in out.stdout and "recommended" not in out.stdout
    assert out.stdout.startswith("# dynstiff: ")


def test_cli_check_recommends_a_model_for_the_tolerance_given():
    """The recommendation under the verdicts is the cheapest model for --rtol: on the
    pendulum 1e-4 asks for another model than the default 1e-2."""
    scene = ds.load_scene("pendulum")
    eq = scene.equilibrium()
    rec = ds.recommend_model(eq, scene.band_hz, 1e-4)
    assert rec.rung != ds.recommend_model(eq, scene.band_hz).rung
    out = run_cli("check", "pendulum", "--rtol", "1e-4")
    assert out.returncode == 0, out.stdout + out.stderr
    assert (rec.text().splitlines()[0] + f" (over {scene.band_hz[0]:g}-{scene.band_hz[1]:g} "
            f"Hz, the closed form measured against the exact rung)") in out.stdout.splitlines()


def test_cli_check_has_no_lengths_option():
    """`check` takes a pose, not unstretched lengths: --lengths is refused, exit 2."""
    out = run_cli("check", "planar2", "--lengths", "20", "20")
    assert out.returncode == 2 and out.stdout == ""
    assert "unrecognized arguments: --lengths 20 20" in out.stderr


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


def test_cli_frf_writes_table_and_figure(tmp_path):
    out = run_cli("frf", "cogiro", "--load", "fz", "--response", "z", "--band", "1", "3",
                  "--points", "400", "--csv", str(tmp_path / "f.csv"), "--plot",
                  str(tmp_path / "f.png"))
    assert out.returncode == 0, out.stderr
    import pandas as pd
    df = pd.read_csv(tmp_path / "f.csv", comment="#")
    assert len(df) > 400 and set(df["output"]) == {"z"} and set(df["input"]) == {"fz"}
    # the largest response in 1-3 Hz is the first (vertical) global mode of CoGiRo
    import dynstiff as ds
    f1 = ds.eigenfrequencies(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), 1)[0]
    peak = df.loc[df["magnitude"].idxmax(), "freq [Hz]"]
    assert abs(peak / f1 - 1) < 1e-3              # the grid is refined at the mode
    assert (tmp_path / "f.png").stat().st_size > 10_000
    bad = run_cli("frf", "cogiro", "--band", "5", "1")
    assert bad.returncode == 2 and "--band" in bad.stderr
    bad = run_cli("frf", "cogiro", "--load", "fq")
    assert bad.returncode == 2 and "fq" in bad.stderr


def test_frf_of_a_held_dof_is_refused_not_zero():
    """The pendulum has one free DOF (ry): naming fx or the output y would give an FRF that
    is identically 0; that is an error naming the channel, and x of D = (0, 0, d) is not."""
    import dynstiff as ds
    from dynstiff.errors import InvalidParameterError
    model = ds.FrequencyModel(ds.load_scene("pendulum").equilibrium())
    with pytest.raises(InvalidParameterError, match=r"inputs \['fx'\].*\('ry',\)"):
        ds.frf(model, [1.0], inputs="fx", outputs="x")
    with pytest.raises(InvalidParameterError, match=r"outputs \['y'\]"):
        ds.frf(model, [1.0], inputs="my", outputs=["x", "y"], point=[0, 0, 0.75])
    # x of D moves by d dphi: H_x,my = d H_ry,my
    h = ds.frf(model, [1.0], inputs="my", outputs=["x", "ry"], point=[0, 0, 0.75]).H[0, :, 0]
    assert h[0] == pytest.approx(0.75 * h[1], rel=1e-12) and abs(h[1]) > 0
    assert ds.frf(model, [1.0]).H.shape == (1, 6, 6)           # the default keeps zero channels
    bad = run_cli("frf", "pendulum", "--load", "fx", "--response", "x")
    assert bad.returncode == 2 and "held DOFs only" in bad.stderr and "fx" in bad.stderr


# -------------------------------------------------------------------------------- check
def test_cli_check_exit_codes():
    def run(*a):
        return run_cli("check", *a)
    assert run("cogiro", "--forbidden-band", "1", "2").returncode == 0
    out = run("cogiro", "--forbidden-band", "4", "5")
    assert out.returncode == 1 and "FAIL    platform modes outside band" in out.stdout
    out = run("cogiro", "--pose", "9", "0", "1")
    assert out.returncode == 1 and "FAIL    workspace" in out.stdout


def test_cli_check_fails_a_mixed_platform_mode_in_band(tmp_path):
    """CoGiRo with a 50 kg platform, band 2.0-2.3 Hz: exit 1, naming the 2.216 Hz mode and
    its 42 % platform share (it passed when only > 50 % shares counted)."""
    from dynstiff.scenes.loader import SCENE_DIR
    text = (SCENE_DIR / "cogiro.toml").read_text().replace("mass = 91.058", "mass = 50.0")
    (tmp_path / "m50.toml").write_text(text)
    out = run_cli("check", tmp_path / "m50.toml", "--forbidden-band", "2.0", "2.3")
    assert out.returncode == 1, out.stdout + out.stderr
    line = [ln for ln in out.stdout.splitlines() if "platform modes outside band" in ln][0]
    assert line.startswith("FAIL") and "2.216 Hz" in line and "platform share 42 %" in line
    assert "FAIL    platform receptance in band" in out.stdout
    # --participation above the share and --frf-limit above the amplification: passes
    out = run_cli("check", tmp_path / "m50.toml", "--forbidden-band", "2.0", "2.3",
                  "--participation", "0.45", "--frf-limit", "100")
    assert "PASS    platform modes outside band" in out.stdout
    assert "PASS    platform receptance in band" in out.stdout


def test_cli_frf_peak_does_not_depend_on_points():
    """The damped CoGiRo z/fz receptance: the largest |H| from 300 and from 4000 uniform
    points differ by < 1 % (the grid is refined at every mode); --damping 0 0 0 gives the
    undamped model, whose peak is far higher."""
    def peak(*a):
        out = run_cli("frf", "cogiro", "--band", "0.5", "6", *a)
        assert out.returncode == 0, out.stderr
        assert "damping: platform modal ratio" in out.stdout
        return float(re.search(r"largest \|H\| = ([0-9.e+-]+)", out.stdout).group(1))
    p300, p4000 = peak("--points", "300"), peak("--points", "4000")
    assert abs(p300 / p4000 - 1) < 0.01
    assert peak("--points", "300", "--damping", "0.03") < 0.6 * p300
    assert peak("--points", "300", "--damping", "0", "0", "0") > 10 * p300


def test_cli_check_defaults_to_the_scenes_forbidden_band():
    def run(*a):
        return run_cli("check", *a)
    out = run("cogiro")                                    # forbidden_band_hz = [0, 1.5]
    assert out.returncode == 0 and "[0, 1.5] Hz" in out.stdout, out.stdout + out.stderr
    out = run("sixcable")                                  # no forbidden band in the scene
    assert out.returncode == 1 and "no forbidden band" in out.stdout
    # the closed form's error on sixcable, measured against the exact rung, is 4e-3 < 1e-2,
    # but its robot-level bound (theory.md §11.6) is 2.5e-2: the cable-model row fails
    assert "FAIL    cable model" in out.stdout and "FAIL    local modes near" in out.stdout
    assert "recommended model: dsm" in out.stdout
    assert "n/a     platform modes outside band       no forbidden band given" in out.stdout


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


# the closed form's robot-level bound warns on sixcable and fast (theory.md §11.6); the
# table's "cable model" row says it too
@pytest.mark.filterwarnings("ignore::dynstiff.errors.ClosedFormWarning")
@pytest.mark.parametrize("scene", ds.list_scenes())
def test_check_writes_its_table_on_every_built_in_scene(tmp_path, scene, capsys):
    """`dynstiff check SCENE --csv FILE` at the scene's own pose: exit 0 or 1 (a verdict), a
    table with one row per check whose verdicts are the printed ones, and the pose in its
    metadata (the command crashed without --pose)."""
    import json

    import pandas as pd

    from dynstiff.cli import main
    out = tmp_path / "checks.csv"
    code = main(["check", scene, "--csv", str(out)])
    text = capsys.readouterr().out
    assert code in (0, 1)
    df = pd.read_csv(out, comment="#")
    assert len(df) == 7 and set(df["passed"]) <= {True, False}
    assert (code == 0) == bool(df["passed"].all())
    flags = {"pass": "PASS", "fail": "FAIL", "unknown": "UNKNOWN", "not asked": "n/a"}
    for row in df.itertuples():
        assert f"{flags[row.verdict]:<7s} {row.check}" in text
        assert row.passed == (row.verdict in ("pass", "not asked"))
    meta = dict(line[2:].split(": ", 1) for line in out.read_text().splitlines()
                if line.startswith("# "))
    pose = json.loads(meta["pose"])
    scn = ds.load_scene(scene)
    expected = scn.pose if scn.pose is not None else scn.equilibrium().pose
    np.testing.assert_allclose(pose["position [m]"], expected.position, atol=1e-12)


def test_cli_check_with_uncertain_parameters():
    """``--uncertain EA=10%``: the uncertain row (EA's sigma 10 %: about 16 % of the robots
    put a platform mode within 5 % of a 0-2 Hz band) and the exit code of a failing row."""
    def run(*a):
        return run_cli("check", *a)
    out = run("cogiro", "--forbidden-band", "0", "2", "--uncertain", "EA=10%")
    assert out.returncode == 1
    assert re.search(r"FAIL    platform modes outside band, uncertain P\(.*\) = 1\d\.\d%",
                     out.stdout)
    bad = run("cogiro", "--uncertain", "EA")
    assert bad.returncode == 2 and "--uncertain EA: give NAME=VALUE" in bad.stderr


@pytest.mark.parametrize("pose", [["0", "0", "nan"], ["0", "0", "1", "0", "inf", "0"], ["1", "2"]])
def test_check_of_a_bad_pose_is_an_error_not_a_verdict(pose):
    """A pose that is not a pose is bad input, exit 2 with one line naming it, not a FAIL
    verdict with exit 1 (as if the robot had failed)."""
    out = run_cli("check", "cogiro", "--pose", *pose)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and "pose" in out.stderr


def test_cli_frf_figure_has_a_phase_panel(tmp_path, monkeypatch):
    """The command's figure is the demo's: magnitude over phase, read back from the Figure."""
    import dynstiff.plot
    from dynstiff.cli import main
    seen = {}
    real = dynstiff.plot.plot_frf

    def spy(*a, **kw):
        seen["fig"] = real(*a, **kw)
        return seen["fig"]

    monkeypatch.setattr(dynstiff.plot, "plot_frf", spy)
    assert main(["frf", "planar2", "--points", "200", "--plot", str(tmp_path / "f.png")]) == 0
    mag, ph = seen["fig"].axes
    assert mag.get_yscale() == "log" and ph.get_ylabel() == "phase [deg]"
    curves = [ln for ln in ph.get_lines() if ln.get_gid().startswith("frf-")]
    assert curves and all(np.nanmax(np.abs(ln.get_ydata())) <= 180 for ln in curves)
    assert (tmp_path / "f.png").stat().st_size > 10_000


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
