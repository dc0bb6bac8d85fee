"""FRFs out (dynstiff/io/exchange.py, FRFResult.to_uff / to_control; theory.md §15.3): UFF 58
files read back through pyuff with the same values, function and data types, units and DOF
labels; python-control's FrequencyResponseData holds the same matrix."""

import sys

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.io.exchange import MissingDependencyError, require, uff58_records

# These tests check the algebra of undamped FRFs (symmetry, kinds, files, figures) across
# natural frequencies on purpose: the ResonanceWarning that says so is expected here.
pytestmark = pytest.mark.filterwarnings("ignore::dynstiff.errors.ResonanceWarning")

pyuff = pytest.importorskip("pyuff")
control = pytest.importorskip("control")


@pytest.fixture(scope="module")
def model():
    return ds.build_model(ds.load_scene("cogiro").equilibrium(), "dsm")


@pytest.fixture(scope="module")
def omega():
    return 2 * np.pi * np.linspace(0.3, 6.0, 37)


# (kind, UFF ordinate data type, numerator units of a translation and of a rotation)
KINDS = [("receptance", 8, "m", "rad"), ("mobility", 11, "m/s", "rad/s"),
         ("accelerance", 12, "m/s^2", "rad/s^2")]


@pytest.mark.parametrize("kind, dtype, trans, rot", KINDS)
def test_uff58_reads_back_with_values_types_and_units(tmp_path, model, omega, kind, dtype,
                                                      trans, rot):
    res = ds.frf(model, omega, inputs=["fy", "mx"], outputs=["x", "rz"], kind=kind)
    path = res.to_uff(tmp_path / "frf.uff")
    sets = pyuff.UFF(str(path)).read_sets()
    assert len(sets) == 4 and all(s["type"] == 58 for s in sets)
    expect = {(o, i): res.H[:, a, b] for a, o in enumerate(res.outputs)
              for b, i in enumerate(res.inputs)}
    for s in sets:
        out = ("x", "y", "z", "rx", "ry", "rz")[s["rsp_dir"] - 1]
        inp = ("fx", "fy", "fz", "mx", "my", "mz")[s["ref_dir"] - 1]
        assert s["func_type"] == 4                               # frequency response function
        assert s["ordinate_spec_data_type"] == dtype
        assert s["orddenom_spec_data_type"] == 13                # excitation force
        assert s["abscissa_spec_data_type"] == 18                # frequency
        assert s["abscissa_axis_units_lab"] == "Hz"
        num = rot if out.startswith("r") else trans
        den = "N m" if inp.startswith("m") else "N"
        assert s["ordinate_axis_units_lab"] == num and s["orddenom_axis_units_lab"] == den
        assert s["ordinate_len_unit_exp"] == (0 if out.startswith("r") else 1)
        assert s["orddenom_len_unit_exp"] == (1 if inp.startswith("m") else 0)
        assert s["orddenom_force_unit_exp"] == 1
        assert s["rsp_node"] == s["ref_node"] == 1
        # ASCII: 12 significant digits of H, 6 of the frequency (E13.5)
        np.testing.assert_allclose(s["data"], expect[(out, inp)], rtol=1e-11, atol=0)
        np.testing.assert_allclose(s["x"], res.freq_hz, rtol=5e-6)


def test_binary_uff58_is_exact(tmp_path, model, omega):
    res = ds.frf(model, omega, inputs="fz", outputs="z")
    path = res.to_uff(tmp_path / "frf.uff", binary=True, node=7, point_node=12)
    s = pyuff.UFF(str(path)).read_sets()                    # one set: a dict
    np.testing.assert_array_equal(s["data"], res.H[:, 0, 0])
    np.testing.assert_array_equal(s["x"], res.freq_hz)
    assert (s["ref_node"], s["rsp_node"], s["rsp_dir"], s["ref_dir"]) == (7, 12, 3, 3)


def test_uff_refuses_an_frf_with_a_pole_and_an_unknown_kind(model):
    res = ds.frf(model, [1.0, 2.0], inputs="fz", outputs="z")
    bad = ds.FRFResult(res.freq_hz, np.full_like(res.H, np.inf), res.inputs, res.outputs,
                       res.kind)
    with pytest.raises(ds.InvalidParameterError,
                       match=r"^the FRF holds inf or NaN \(an exact pole\): UFF 58 holds finite "
                             "numbers only; evaluate beside the pole$"):
        uff58_records(bad)
    one = ds.FRFResult(res.freq_hz[:1], res.H[:1], res.inputs, res.outputs, res.kind)
    with pytest.raises(ds.InvalidParameterError,
                       match="^a UFF 58 record needs at least 2 frequencies, got 1$"):
        uff58_records(one)
    bad = ds.FRFResult(res.freq_hz, res.H, res.inputs, res.outputs, "compliance")
    with pytest.raises(ds.InvalidParameterError, match="kind must be one of"):
        uff58_records(bad)


def test_to_control_is_outputs_by_inputs_by_frequencies(model, omega):
    res = ds.frf(model, omega, inputs=["fx", "fz", "my"], outputs=["y", "ry"])
    frd = res.to_control()
    assert isinstance(frd, control.FrequencyResponseData)
    assert frd.ninputs == 3 and frd.noutputs == 2
    np.testing.assert_allclose(frd.omega, omega)
    np.testing.assert_array_equal(np.asarray(frd.frdata), np.moveaxis(res.H, 0, -1))
    assert frd.input_labels == ["fx", "fz", "my"] and frd.output_labels == ["y", "ry"]
    # python-control evaluates it back at a stored frequency
    np.testing.assert_allclose(frd.eval(omega[5]), res.H[5])


def test_missing_library_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "pyuff", None)
    with pytest.raises(MissingDependencyError, match=r'dynstiff\[exchange\]'):
        require("pyuff")


def test_a_bad_frf_leaves_an_existing_uff_file_as_it_was(tmp_path, model, monkeypatch):
    """The data are checked before the file is touched; a writer failing half way through
    (a planted error in pyuff) leaves the old file byte for byte and no temporary."""
    res = ds.frf(model, [1.0, 2.0], inputs="fz", outputs="z")
    path = tmp_path / "old.uff"
    res.to_uff(path)
    before = (path.read_bytes(), path.stat().st_mtime_ns)
    H = res.H.copy()
    H[1, 0, 0] = np.nan
    bad = ds.FRFResult(res.freq_hz, H, res.inputs, res.outputs, res.kind)
    with pytest.raises(ds.InvalidParameterError, match="inf or NaN"):
        bad.to_uff(path)
    assert (path.read_bytes(), path.stat().st_mtime_ns) == before

    def broken(self, sets, mode="add"):
        with open(self._filename, "a") as fh:
            fh.write("    -1\n    58\n")
        raise OSError("disk full (planted)")
    monkeypatch.setattr(pyuff.UFF, "write_sets", broken)
    with pytest.raises(OSError, match="planted"):
        res.to_uff(path)
    assert (path.read_bytes(), path.stat().st_mtime_ns) == before
    assert [p.name for p in tmp_path.iterdir()] == ["old.uff"]


@pytest.fixture(scope="module")
def symmetric():
    """planar2 at x = 0: mirror symmetric about x = 0, so x/fz and z/fx vanish."""
    eq = ds.load_scene("planar2").equilibrium()
    return ds.build_model(eq, "dsm", platform_damping_ratio=0.02)


def test_to_control_is_named_and_bode_plots_it_as_it_is(symmetric):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = ds.frf(symmetric, 2 * np.pi * np.linspace(0.05, 3.0, 120), inputs=["fx", "fz"],
                 outputs=["x", "z"])
    top = np.abs(res.H).max()
    cross = np.abs(res.H[:, 0, 1]).max()
    assert 0 < cross < 1e-12 * top              # rounding only: zero by symmetry
    frd = res.to_control()
    assert frd.name == "dynstiff receptance"
    assert frd.input_labels == ["fx", "fz"] and frd.output_labels == ["x", "z"]
    data = np.asarray(frd.frdata)
    assert np.all(data[0, 1] == 0) and np.all(data[1, 0] == 0)
    np.testing.assert_array_equal(data[0, 0], res.H[:, 0, 0])       # the rest untouched
    cp = control.bode_plot(frd)
    assert "dynstiff receptance" in cp.figure._suptitle.get_text()
    # the direct channels' phases stay within one turn (no unwrapped rounding noise)
    for line in cp.lines[1, 0]:
        assert np.all(np.abs(line.get_ydata()) <= 360.0)
    plt.close(cp.figure)


def test_even_uff_of_a_grid_refined_at_the_modes_is_its_uniform_part(tmp_path):
    """An FRF on the grid refined at the modes (theory.md §12.3) written with even=True:
    the records read back on an even abscissa (spacing code 1) at the uniform part's
    step, with exactly the result's values at those points (binary), and say so."""
    from dynstiff.analyses.freqgrid import refined_grid
    model = ds.scene_model(ds.load_scene("cogiro"))
    modes = ds.eigenfrequencies(model, 6)
    f = refined_grid((0.5, 6.0), 111, modes)
    assert f.size > 400                                  # 111 uniform + refinement
    res = ds.frf(model, 2 * np.pi * f, inputs="fz", outputs="z")
    s = pyuff.UFF(str(res.to_uff(tmp_path / "even.uff", binary=True, even=True))).read_sets()
    uniform = np.linspace(0.5, 6.0, 111)
    assert s["abscissa_spacing"] == 1 and "even grid, step 0.05 Hz" in s["id3"]
    np.testing.assert_allclose(s["x"], uniform, rtol=1e-12, atol=1e-12)
    on = np.searchsorted(f, uniform)
    assert np.abs(f[on] - uniform).max() < 1e-12
    np.testing.assert_array_equal(s["data"], res.H[on, 0, 0])


def test_even_uff_at_a_step_interpolates_and_refuses_bad_steps(tmp_path, model):
    """even=step [Hz]: linear interpolation of the real and imaginary parts between the
    result's points (checked on a straight-line FRF, which it reproduces); steps that are
    not positive numbers up to the band, and booleans as numbers, are refused naming
    'even', before the file is touched."""
    f = np.linspace(1.0, 2.0, 11)
    H = ((2.0 + 3.0j) * f - 1j)[:, None, None]
    res = ds.FRFResult(f, H, ("fz",), ("z",), "receptance")
    s = pyuff.UFF(str(res.to_uff(tmp_path / "a.uff", binary=True, even=0.03))).read_sets()
    np.testing.assert_allclose(s["x"], 1.0 + 0.03 * np.arange(34), rtol=1e-12)
    np.testing.assert_allclose(s["data"], (2.0 + 3.0j) * s["x"] - 1j, rtol=1e-12)
    whole = uff58_records(res, even=1.0)[0]              # a step of the whole band: its ends
    np.testing.assert_array_equal(whole["x"], [1.0, 2.0])
    target = tmp_path / "keep.uff"
    target.write_text("old")
    for bad in (0.0, -0.1, 2.0, np.nan, "0.1", np.True_):
        with pytest.raises(ds.InvalidParameterError, match="even"):
            res.to_uff(target, even=bad)
    assert target.read_text() == "old"


def test_uff58_records_read_back_with_their_ids_and_axis_labels(tmp_path, model, omega):
    res = ds.frf(model, omega, inputs=["fy", "mx"], outputs=["x", "rz"])
    sets = pyuff.UFF(str(res.to_uff(tmp_path / "ids.uff"))).read_sets()
    labels = [(s["id1"].strip(), s["id2"].strip(), s["id4"].strip(), s["id5"].strip(),
               s["abscissa_axis_lab"].strip(), s["ordinate_axis_lab"].strip(),
               s["orddenom_axis_lab"].strip()) for s in sets]
    assert [s["id3"].strip() for s in sets] == ["NONE"] * 4        # the result's own grid
    assert labels == [
        ("dynstiff receptance x/fy", "m/N", "NONE", "NONE", "Frequency", "x", "fy"),
        ("dynstiff receptance x/mx", "m/N m", "NONE", "NONE", "Frequency", "x", "mx"),
        ("dynstiff receptance rz/fy", "rad/N", "NONE", "NONE", "Frequency", "rz", "fy"),
        ("dynstiff receptance rz/mx", "rad/N m", "NONE", "NONE", "Frequency", "rz", "mx")]


def test_zero_below_floor_is_relative_to_the_largest_channel_and_keeps_shapes():
    from dynstiff.io.exchange import zero_below_floor
    H = np.zeros((3, 2, 1))
    H[:, 0, 0] = [1e3, 2e3, 0.5e3]                         # the largest channel: 2e3
    H[:, 1, 0] = 1e-10                                     # 5e-14 of it: below 1e-12
    out = zero_below_floor(H)
    assert out.dtype == complex and np.all(out[:, 1, 0] == 0)
    np.testing.assert_array_equal(out[:, 0, 0], H[:, 0, 0])
    H[:, 1, 0] = 1e-8                                      # 5e-12 of it: kept
    np.testing.assert_array_equal(zero_below_floor(H)[:, 1, 0], 1e-8)
    assert zero_below_floor(np.zeros((0, 2, 3))).shape == (0, 2, 3)


def test_even_grid_of_several_channels_scales_with_the_frequencies():
    """The even step is found among the grid's spacings whatever their scale (mHz to MHz),
    and every channel is resampled."""
    from dynstiff.io.exchange import even_grid
    f = np.array([0.0, 1.0, 2.0, 2.01, 2.1, 3.0, 4.0, 5.0])
    H = (f[:, None, None] + 1j) * np.arange(1, 5).reshape(1, 2, 2)
    for s in (1e-6, 1.0, 1e6):
        fe, He, step = even_grid(s * f, H, True)
        assert step == pytest.approx(s, rel=1e-12)
        np.testing.assert_allclose(fe, s * np.arange(6.0), rtol=1e-12)
        np.testing.assert_allclose(He, (fe[:, None, None] / s + 1j)
                                   * np.arange(1, 5).reshape(1, 2, 2), rtol=1e-9)


@pytest.mark.parametrize("kw, message", [
    (dict(node=True), "^node must be an integer >= 1, got True$"),
    (dict(node=1.5), r"^node must be an integer >= 1, got 1\.5$"),
    (dict(node=0), "^node must be an integer >= 1, got 0$"),
    (dict(point_node=True), "^point_node must be an integer >= 1, got True$"),
    (dict(binary="no"), "^binary must be True or False, got 'no'$"),
    (dict(entity=5), "^entity must be a name of at most 10 characters"),
    (dict(entity="platform_top"), "^entity must be a name of at most 10 characters .*"
                                  "got 'platform_top'$")])
def test_uff_options_are_checked_and_no_file_is_written(tmp_path, model, omega, kw, message):
    """binary="no" wrote binary records, node 1.5 was node 1, True node 1, and an entity
    name of 12 characters was cut to 10 without a word."""
    r = ds.frf(model, omega, inputs="fz", outputs="z")
    path = tmp_path / "frf.uff"
    with pytest.raises(ds.InvalidParameterError, match=message):
        r.to_uff(path, **kw)
    assert not path.exists()
    r.to_uff(path, node=np.int64(3), point_node=2, entity="p" * 10)
    rec = uff58_records(r, node=np.int64(3), point_node=2, entity="p" * 10)[0]
    assert (rec["ref_node"], rec["rsp_node"], rec["ref_ent_name"]) == (3, 2, "p" * 10)
    assert type(rec["ref_node"]) is int


def test_a_control_system_name_is_text(model, omega):
    with pytest.raises(ds.InvalidParameterError, match="^name must be a str or None, got 5$"):
        ds.frf(model, omega, inputs="fz", outputs="z").to_control(name=5)


def test_uff_data_are_complex_even_for_a_real_frf():
    """A real H (an undamped receptance away from its poles) is written as complex data, the
    data type the records declare; as float, pyuff would write another record type."""
    res = ds.FRFResult(np.array([1.0, 2.0]), np.ones((2, 1, 1)), ("fz",), ("z",),
                       "receptance")
    rec = uff58_records(res)[0]
    assert rec["data"].dtype == complex and rec["data"].flags["C_CONTIGUOUS"]
