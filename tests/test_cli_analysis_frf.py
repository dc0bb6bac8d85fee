"""The `dynstiff` command line, run in this process (conftest.run_cli): `frf`, its channels,
report, tables, UFF file and figure (dynstiff/cli/analysis.py)."""

import re

import numpy as np
import pytest
from conftest import _metadata, _spy, run_cli

import dynstiff as ds

pytestmark = pytest.mark.usefixtures("no_traceback")


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
