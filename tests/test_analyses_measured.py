"""Measurements in (dynstiff/analyses/measured.py, theory.md §15.5): measured-mode tables and
FRF files read back, MAC pairing finds a shuffled set of modes, comparisons tabulate and
plot."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.measured import (
    MeasuredModes,
    compare_frf,
    compare_modes,
    mac_matrix,
    massless_pairing,
    pair_modes,
    read_measured_frf,
    read_measured_modes,
)

# These tests check the algebra of undamped FRFs (symmetry, kinds, files, figures) across
# natural frequencies on purpose: the ResonanceWarning that says so is expected here.
pytestmark = pytest.mark.filterwarnings("ignore::dynstiff.errors.ResonanceWarning")


@pytest.fixture(scope="module")
def model():
    return ds.build_model(ds.load_scene("cogiro").equilibrium(), "dsm")


@pytest.fixture(scope="module")
def md(model):
    return ds.modes(model, fmax_hz=7.0)


def test_mac_is_one_for_scaled_shapes_and_ignores_unmeasured_dofs():
    a = np.array([[1.0, 2.0, np.nan, 0.5, np.nan, 0.0]])
    b = np.array([[-3.0, -6.0, 100.0, -1.5, 7.0, 0.0], [2.0, -1.0, 0.0, 0.0, 0.0, 0.0]])
    mac = mac_matrix(a, b)
    np.testing.assert_allclose(mac, [[1.0, 0.0]], atol=1e-15)


def test_mac_pairing_finds_shuffled_noisy_modes(md):
    glob = np.flatnonzero(np.array(md.kind) == "global")[:5]
    order = glob[[3, 0, 4, 2, 1]]
    rng = np.random.default_rng(0)
    shapes = md.platform_shapes[order] * (1 + 0.05 * rng.standard_normal((5, 6)))
    shapes[:, 5] = np.nan                                    # rz not measured
    meas = MeasuredModes(md.freq_hz[order] * 1.02, shapes=shapes)
    idx, mac = pair_modes(md, meas)
    np.testing.assert_array_equal(idx, order)
    assert np.all(mac > 0.95)
    cmp = compare_modes(md, meas)
    np.testing.assert_allclose(cmp.error, 1 / 1.02 - 1, rtol=1e-12)
    df = cmp.to_frame()
    assert list(df.columns)[:3] == ["measured [Hz]", "model [Hz]", "error [-]"]
    assert cmp.plot().axes[0].get_xlabel() == "measured [Hz]"


def test_order_and_frequency_pairing_without_shapes(md):
    glob = np.flatnonzero(np.array(md.kind) == "global")
    f = md.freq_hz[glob[:3]] * np.array([1.01, 0.99, 1.0])
    idx, mac = pair_modes(md, MeasuredModes(f[::-1]))          # order: by rank
    np.testing.assert_array_equal(idx, glob[:3][::-1])
    assert np.all(np.isnan(mac))
    idx, _ = pair_modes(md, MeasuredModes(f), "frequency")
    np.testing.assert_array_equal(idx, glob[:3])
    with pytest.raises(ds.InvalidParameterError, match="needs measured shapes"):
        pair_modes(md, MeasuredModes(f), "mac")


def test_massless_pairing_continues_the_platform_modes(model, md):
    """Below the first cable family the closed-form platform modes are the massless ones."""
    idx = massless_pairing(md, model, 3)
    np.testing.assert_allclose(md.freq_hz[idx], md.freq_hz[:3])


def test_measured_modes_csv_round_trip(tmp_path, md):
    meas = MeasuredModes(md.freq_hz[:3], shapes=md.platform_shapes[:3],
                         sigma_hz=[0.01, 0.02, 0.03])
    path = tmp_path / "modes.csv"
    meas.to_frame().to_csv(path, index=False)
    back = read_measured_modes(path)
    np.testing.assert_array_equal(back.freq_hz, meas.freq_hz)
    np.testing.assert_allclose(back.shapes, meas.shapes, rtol=1e-15)
    np.testing.assert_array_equal(back.sigma_hz, meas.sigma_hz)
    (tmp_path / "bad.csv").write_text("f\n1.0\n")
    with pytest.raises(ds.InvalidParameterError, match="no frequency column"):
        read_measured_modes(tmp_path / "bad.csv")
    (tmp_path / "neg.csv").write_text("freq [Hz]\n1.0\n-2.0\n")
    with pytest.raises(ds.InvalidParameterError, match="neg.csv: freq_hz must be"):
        read_measured_modes(tmp_path / "neg.csv")


@pytest.mark.parametrize("suffix", [".uff", ".csv"])
def test_measured_frf_files_read_back(tmp_path, model, suffix):
    if suffix == ".uff":
        pytest.importorskip("pyuff")
    res = ds.frf(model, 2 * np.pi * np.linspace(0.5, 4.0, 30), inputs=["fx", "mz"],
                 outputs=["y", "rz"], kind="mobility")
    path = tmp_path / f"frf{suffix}"
    if suffix == ".uff":
        res.to_uff(path, binary=True)
    else:
        res.to_frame().to_csv(path, index=False)
    back = read_measured_frf(path)
    assert back.inputs == res.inputs and back.outputs == res.outputs and back.kind == "mobility"
    np.testing.assert_allclose(back.H, res.H, rtol=1e-14)
    np.testing.assert_allclose(back.freq_hz, res.freq_hz, rtol=1e-14)


def test_uff_direction_signs_are_honoured_and_unknown_types_refused(tmp_path, model):
    """A response along -z (direction code -3) is the +z response with its sign flipped, as
    is a force along -fz; a second record of the same pair, another function type (time
    response), an unknown data type or a time abscissa is refused naming the record (its
    number and id1); a file without a frequency response record is refused."""
    pyuff = pytest.importorskip("pyuff")
    from dynstiff.io.exchange import uff58_records
    res = ds.frf(model, 2 * np.pi * np.linspace(0.5, 4.0, 12), inputs=["fz", "mx"],
                 outputs=["z"])
    recs = uff58_records(res, binary=True)

    def read(records, name):
        path = tmp_path / name
        pyuff.UFF(str(path)).write_sets(records, mode="add")
        return read_measured_frf(path)
    flipped = [dict(recs[0], rsp_dir=-3), dict(recs[1], ref_dir=-4)]
    back = read(flipped, "neg.uff")
    assert back.outputs == ("z",) and back.inputs == ("fz", "mx")
    np.testing.assert_array_equal(back.H, -res.H)
    both = [dict(recs[0], rsp_dir=-3, ref_dir=-3)]
    np.testing.assert_array_equal(read(both, "both.uff").H[:, 0, 0], res.H[:, 0, 0])
    for k, (change, match) in enumerate([
            ({"rsp_dir": -3}, "record 2 .*: a second record of z/fz"),
            ({"func_type": 1}, r"record 2 \('[^']+'\): function type 1 is not one dynstiff "
                               "reads"),
            ({"ordinate_spec_data_type": 9}, "record 2 .*data type 9 is not one"),
            ({"abscissa_spec_data_type": 17}, "record 2 .*abscissa type 17"),
            ({"rsp_dir": 7}, "record 2 .*direction rsp_dir=7")]):
        with pytest.raises(ds.InvalidParameterError, match=match):
            read([recs[0], dict(recs[0], **change)], f"bad{k}.uff")
    nodes = pyuff.prepare_15(node_nums=[1], def_cs=[0], disp_cs=[0], color=[1], x=[0.0],
                             y=[0.0], z=[0.0], return_full_dict=True)
    with pytest.raises(ds.InvalidParameterError, match=r"nodes\.uff: no UFF 58 frequency "
                                                       r"response record \(function type 4\)$"):
        read([nodes], "nodes.uff")                  # a file of nodes only


def test_compare_frf_overlays_and_scores(model):
    f = np.linspace(0.5, 4.0, 40)
    truth = ds.frf(model, 2 * np.pi * f, inputs="fz", outputs=["z", "rx"])
    meas = ds.FRFResult(truth.freq_hz, truth.H * 1.1, truth.inputs, truth.outputs, truth.kind)
    cmp = compare_frf(model, meas)
    np.testing.assert_allclose(cmp.log_magnitude_error, np.log10(1.1), rtol=1e-9)
    fig = cmp.plot()
    assert len(fig.axes[0].lines) == 4
    assert "model magnitude" in cmp.to_frame()


def test_order_pairing_of_a_three_cycle(md):
    """Pairing by order with a permutation that is not its own inverse (a 3-cycle): the k-th
    measured frequency goes to the global mode of its rank (a single argsort would give the
    inverse permutation, which a swap or a reversal cannot tell apart)."""
    glob = np.flatnonzero(np.array(md.kind) == "global")[:3]
    cycle = [1, 2, 0]
    idx, _ = pair_modes(md, MeasuredModes(md.freq_hz[glob[cycle]]), "order")
    np.testing.assert_array_equal(idx, glob[cycle])
    idx, _ = pair_modes(md, MeasuredModes(md.freq_hz[glob[cycle]] * 1.01), "frequency")
    np.testing.assert_array_equal(idx, glob[cycle])


@pytest.mark.parametrize(("kw", "named"), [
    ({"shapes": "abc"}, "shapes"),
    ({"shapes": [[1j] * 6] * 2}, "shapes"),
    ({"sigma_hz": "x"}, "sigma_hz"),
    ({"sigma_hz": [0.1, 0.1, 0.1]}, "sigma_hz"),
    ({"damping_ratio": [[0.01]]}, "damping_ratio"),
])
def test_measured_modes_refuse_text_complex_and_misshapen_arrays_by_name(kw, named):
    with pytest.raises(ds.InvalidParameterError, match=named):
        ds.MeasuredModes(freq_hz=[1.0, 2.0], **kw)
    # one number for every mode is still taken as such
    assert ds.MeasuredModes(freq_hz=[1.0, 2.0], sigma_hz=[0.1]).sigma_hz.tolist() == [0.1, 0.1]


def test_measured_modes_refuse_zero_and_negative_values_and_empty_shape_rows():
    """A frequency of 0, a sigma of 0 or below, and a mode whose shape row is all NaN or all
    zero are refused by name; a sigma of exactly 1 Hz is taken."""
    with pytest.raises(ds.InvalidParameterError, match="freq_hz must be a non-empty list"):
        MeasuredModes(freq_hz=[0.0, 2.0])
    for bad in ([-0.1, 0.1], [0.0, 0.1]):
        with pytest.raises(ds.InvalidParameterError, match="sigma_hz must be finite and > 0"):
            MeasuredModes(freq_hz=[1.0, 2.0], sigma_hz=bad)
    assert MeasuredModes(freq_hz=[1.0, 2.0], sigma_hz=[1.0, 1.0]).sigma_hz.tolist() == [1, 1]
    for bad in (1.0, 1.5, -0.01):                  # a damping ratio in [0, 1): 0 is taken
        with pytest.raises(ds.InvalidParameterError,
                           match=r"^damping_ratio must be in \[0, 1\) \(an underdamped mode\)"):
            MeasuredModes(freq_hz=[1.0, 2.0], damping_ratio=[0.01, bad])
    assert MeasuredModes(freq_hz=[1.0], damping_ratio=0.0).damping_ratio.tolist() == [0.0]
    row = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    for empty in ([np.nan] * 6, [0.0] * 6, [0.0, np.nan, 0.0, np.nan, 0.0, 0.0]):
        with pytest.raises(ds.InvalidParameterError,
                           match="shapes: every mode needs a nonzero measured DOF"):
            MeasuredModes(freq_hz=[1.0, 2.0], shapes=[row, empty])


def test_measured_modes_repr_and_table_name_what_they_hold(tmp_path):
    with_shapes = MeasuredModes(freq_hz=[1.0, 2.0], shapes=np.eye(6)[:2],
                                damping_ratio=[0.01, 0.02])
    assert repr(with_shapes) == "MeasuredModes(2 modes 1-2 Hz, shapes yes)"
    assert repr(MeasuredModes(freq_hz=[1.5])) == "MeasuredModes(1 mode 1.5-1.5 Hz, shapes no)"
    df = with_shapes.to_frame()
    assert list(df.columns) == ["freq [Hz]", "damping ratio [-]", "x", "y", "z", "rx", "ry",
                                "rz"]
    df.to_csv(tmp_path / "m.csv", index=False)
    np.testing.assert_array_equal(read_measured_modes(tmp_path / "m.csv").damping_ratio,
                                  [0.01, 0.02])


def test_shapes_choose_mac_pairing_and_order_pairing_still_reports_their_mac(md):
    """With shapes and no pairing named, the shapes decide (MAC), not the frequencies: two
    global modes measured with their shapes but each other's frequencies pair by shape.
    Paired by order, the same measurement reports the MAC of the pairs it made."""
    g = np.flatnonzero(np.array(md.kind) == "global")[:2]
    meas = MeasuredModes(md.freq_hz[g[::-1]], shapes=md.platform_shapes[g])
    idx, mac = pair_modes(md, meas)
    np.testing.assert_array_equal(idx, g)
    np.testing.assert_allclose(mac, 1.0, rtol=1e-12)
    idx, mac = pair_modes(md, meas, "order")
    np.testing.assert_array_equal(idx, g[::-1])
    full = mac_matrix(meas.shapes, md.platform_shapes)
    np.testing.assert_allclose(mac, full[[0, 1], g[::-1]], rtol=1e-15)
    assert np.all(mac < 0.5)


def test_mac_pairing_with_fewer_model_modes_than_measured_says_so(md):
    few = ds.modes(ds.build_model(ds.load_scene("cogiro").equilibrium(), "dsm"), n_modes=2)
    meas = MeasuredModes(md.freq_hz[:3], shapes=md.platform_shapes[:3])
    with pytest.raises(ds.InvalidParameterError,
                       match="3 measured modes but only 2 model modes computed"):
        pair_modes(few, meas)


def test_massless_pairing_is_the_mass_weighted_mac_assignment(model):
    """Against an independent assignment: for each massless mode x0, the mode maximising
    (x0' M x)^2 / ((x0' M x0)(x' M x)) times its platform share, over a band holding many
    cable modes (the six massless modes of CoGiRo among 60 modes)."""
    from scipy.linalg import eigh
    from scipy.optimize import linear_sum_assignment
    many = ds.modes(model, n_modes=60)
    M = model.platform_mass
    _, X0 = eigh(model.massless_stiffness(), M)
    X = np.asarray(many.platform_shapes)[:, model.free_index]
    score = np.zeros((6, len(many)))
    for i in range(6):
        for k in range(len(many)):
            a, b = X0[:, i], X[k]
            score[i, k] = (a @ M @ b) ** 2 / ((a @ M @ a) * (b @ M @ b)) * (
                1 - many.cable_energy_fraction[k])
    ref = linear_sum_assignment(-score)[1]
    np.testing.assert_array_equal(massless_pairing(many, model, 6), ref)
    assert score[np.arange(6), ref].min() > 0.5
    # the MAC does not depend on the shapes' scale: the other modes 100 times larger
    from dataclasses import replace
    scale = np.full(len(many), 100.0)
    scale[ref] = 1.0
    scaled = replace(many, platform_shapes=many.platform_shapes * scale[:, None])
    np.testing.assert_array_equal(massless_pairing(scaled, model, 6), ref)


def test_the_comparison_plot_shows_every_error_on_equal_axes(md):
    g = np.flatnonzero(np.array(md.kind) == "global")[:3]
    cmp = compare_modes(md, MeasuredModes(md.freq_hz[g] * np.array([1.02, 0.99, 1.0])))
    fig = cmp.plot()
    ax = fig.axes[0]
    assert tuple(fig.get_size_inches()) == (4.5, 4.2)
    assert ax.get_ylabel() == "model [Hz]"
    assert ax.get_xlim() == ax.get_ylim()
    lo = 0.9 * min(cmp.measured_hz.min(), cmp.model_hz.min())
    assert ax.get_ylim()[0] == pytest.approx(lo, rel=1e-12)
    texts = [t.get_text() for t in ax.texts]
    assert texts == [f"{100 * e:+.1f} %" for e in cmp.error]
    assert {t.get_anncoords() for t in ax.texts} == {"offset points"}


def test_a_csv_with_the_five_columns_only_is_a_receptance(tmp_path, model):
    res = ds.frf(model, 2 * np.pi * np.linspace(0.5, 1.5, 4), inputs="fz", outputs="z")
    df = res.to_frame()[["freq [Hz]", "input", "output", "real", "imag"]]
    df.to_csv(tmp_path / "five.csv", index=False)
    back = read_measured_frf(tmp_path / "five.csv")
    assert back.kind == "receptance"
    np.testing.assert_allclose(back.H, res.H, rtol=1e-14)


def test_uff_records_of_two_kinds_are_refused_naming_them(tmp_path, model):
    pyuff = pytest.importorskip("pyuff")
    from dynstiff.io.exchange import uff58_records
    w = 2 * np.pi * np.linspace(0.5, 1.5, 4)
    recs = uff58_records(ds.frf(model, w, inputs="fz", outputs="z"), binary=True) + \
        uff58_records(ds.frf(model, w, inputs="fx", outputs="z", kind="mobility"), binary=True)
    pyuff.UFF(str(tmp_path / "mix.uff")).write_sets(recs, mode="add")
    with pytest.raises(ds.InvalidParameterError,
                       match=r"the records mix kinds \['mobility', 'receptance'\] or "
                             r"frequency axes"):
        read_measured_frf(tmp_path / "mix.uff")


def test_compare_frf_takes_the_measured_kind_and_point(model):
    f = np.linspace(0.5, 1.5, 5)
    meas = ds.frf(model, 2 * np.pi * f, inputs="fz", outputs=["x", "z"], kind="mobility",
                  point=[0.4, 0.0, 0.0])
    cmp = compare_frf(model, meas, point=[0.4, 0.0, 0.0])
    assert cmp.model.kind == "mobility"
    np.testing.assert_allclose(cmp.model.H, meas.H, rtol=1e-12)
    at_p = compare_frf(model, meas)
    assert not np.allclose(at_p.model.H, meas.H, rtol=1e-6)
    with pytest.raises(ds.InvalidParameterError, match="^measured must be an FRFResult, got "
                                                       "list$"):
        compare_frf(model, [1.0, 2.0])


def test_the_frf_overlay_draws_each_channel_measured_and_model_in_one_colour(model):
    f = np.linspace(0.5, 1.5, 6)
    truth = ds.frf(model, 2 * np.pi * f, inputs=["fz", "mx"], outputs=["z", "rx"])
    meas = ds.FRFResult(truth.freq_hz, truth.H * 1.1, truth.inputs, truth.outputs, truth.kind)
    fig = compare_frf(model, meas).plot()
    ax = fig.axes[0]
    assert tuple(fig.get_size_inches()) == (7, 4)
    assert ax.get_xlabel() == "frequency [Hz]" and ax.get_ylabel() == "|H| (receptance)"
    lines = ax.get_lines()
    assert [ln.get_label() for ln in lines] == [
        f"{o}/{i} {w}" for o in ("z", "rx") for i in ("fz", "mx") for w in ("measured",
                                                                               "model")]
    for k, (m, d) in enumerate(zip(lines[::2], lines[1::2])):
        o, i = divmod(k, 2)
        assert m.get_color() == d.get_color() == f"C{k}"
        assert m.get_linestyle() == "None" and m.get_marker() == "." and m.get_markersize() == 3
        assert d.get_linestyle() == "-" and d.get_linewidth() == 1
        np.testing.assert_array_equal(m.get_xdata(), f)
        np.testing.assert_allclose(m.get_ydata(), np.abs(meas.H[:, o, i]), rtol=1e-15)
        np.testing.assert_allclose(d.get_ydata(), np.abs(truth.H[:, o, i]), rtol=1e-12)
    legend = ax.get_legend()
    assert legend._ncols == 2 and legend.get_texts()[0].get_fontsize() == 7


@pytest.mark.parametrize("kw, message", [
    (dict(freq_hz=[True, 2.0]), "^freq_hz must be a non-empty list of finite frequencies"),
    (dict(freq_hz=[1 + 1j, 2.0]), "^freq_hz must be a non-empty list of finite frequencies"),
    (dict(freq_hz=[1.0, 2.0], sigma_hz=[True, 0.1]), "^sigma_hz must be real numbers, not "
                                                      "booleans"),
    (dict(freq_hz=[1.0, 2.0], shapes=np.ones((2, 6), bool)), "^shapes must be real numbers, "
                                                             "not booleans"),
    (dict(freq_hz=[1.0, 2.0], sigma_hz=[0.1j, 0.1]), "^sigma_hz must be real numbers, got")])
def test_measured_modes_of_booleans_or_complex_numbers_are_refused(kw, message):
    """[True, 2.0] Hz was a mode at 1 Hz; a boolean shape a motion of 1 m in every DOF."""
    with pytest.raises(ds.InvalidParameterError, match=message):
        MeasuredModes(**kw)
