"""Result types (dynstiff/results.py): units, tables and the FRF kinds."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.results import RESPONSE_KINDS, response_factor


def test_response_factor_is_i_omega_to_the_kind():
    w = np.array([0.0, 1.5, 20.0])
    np.testing.assert_array_equal(response_factor(w, "receptance"), np.ones(3))
    np.testing.assert_array_equal(response_factor(w, "mobility"), 1j * w)
    np.testing.assert_allclose(response_factor(w, "accelerance"), -w**2, rtol=1e-15)
    assert set(RESPONSE_KINDS) == {"receptance", "mobility", "accelerance"}
    with pytest.raises(InvalidParameterError, match="kind"):
        response_factor(w, "inertance")


@pytest.mark.parametrize("kind, unit_fx, unit_mz", [
    ("receptance", "m/N", "rad/(N m)"),
    ("mobility", "m/(N s)", "rad/(N m s)"),
    ("accelerance", "m/(N s^2)", "rad/(N m s^2)"),
])
def test_frf_units(kind, unit_fx, unit_mz):
    r = ds.FRFResult(freq_hz=np.array([1.0]), H=np.ones((1, 6, 6), complex),
                     inputs=ds.results.INPUT_NAMES, outputs=ds.results.OUTPUT_NAMES, kind=kind)
    assert r.unit("x", "fx") == unit_fx
    assert r.unit("rz", "mz") == unit_mz
    with pytest.raises(InvalidParameterError, match="unit"):
        r.unit("fx", "x")


def test_frf_table_is_tidy_and_repr_short():
    H = (np.arange(12) + 1j).reshape(2, 3, 2)
    r = ds.FRFResult(freq_hz=np.array([1.0, 2.0]), H=H, inputs=("fx", "fz"),
                     outputs=("x", "y", "z"), kind="receptance")
    df = r.to_frame()
    assert len(df) == 12
    row = df[(df["freq [Hz]"] == 2.0) & (df["output"] == "y") & (df["input"] == "fz")]
    assert row["real"].item() == H[1, 1, 1].real and row["imag"].item() == 1.0
    assert row["magnitude"].item() == pytest.approx(abs(H[1, 1, 1]), rel=1e-15)
    assert row["phase [deg]"].item() == pytest.approx(np.degrees(np.angle(H[1, 1, 1])))
    assert "2 frequencies" in repr(r) and len(repr(r)) < 150


def test_damped_modes_frequency_and_damping_ratio_from_the_complex_root():
    """e^{i omega t} with omega = omega_d + i sigma: f = omega_d / 2 pi,
    zeta = sigma / |omega|."""
    om = np.array([2 * np.pi * 3.0 * (1 + 0.02j), np.nan + 1j * np.nan])
    d = ds.DampedModes(undamped_freq_hz=np.array([3.0, 5.0]), omega=om,
                       residual=np.array([1e-12, np.nan]))
    assert d.freq_hz[0] == pytest.approx(3.0, rel=1e-15)
    assert d.damping_ratio[0] == pytest.approx(0.02 / np.hypot(1, 0.02), rel=1e-14)
    df = d.to_frame()
    assert list(df.columns) == ["undamped freq [Hz]", "damped freq [Hz]", "damping ratio [-]",
                                "residual [-]"]
    assert "1 damped root found" in repr(d)
    none = ds.DampedModes(undamped_freq_hz=np.array([3.0, 5.0]), omega=np.full(2, np.nan + 0j),
                          residual=np.full(2, np.nan))
    assert repr(none) == "DampedModes(2 modes, no damped root found)"


def test_modal_table_units_and_shift(cogiro_model):
    md = ds.modes(cogiro_model, 8)
    df = md.to_frame()
    for col in ("freq [Hz]", "cable energy fraction [-]", "x [m/kg^0.5, x'Mx=1]",
                "rz [rad/(m kg^0.5), x'Mx=1]"):
        assert col in df.columns
    assert "x [m]" not in df.columns and "rz [rad]" not in df.columns   # energy-normalised
    M = cogiro_model.platform_mass
    x = df[[c for c in df.columns if "x'Mx=1" in c]].to_numpy()[np.array(md.kind) == "global"]
    np.testing.assert_allclose(np.einsum("ki,ij,kj->k", x, M, x), 1.0, rtol=1e-10)
    paired = np.isfinite(md.massless_freq_hz)
    assert paired[np.array(md.kind) == "global"].all()     # every global mode continues one
    assert np.unique(md.massless_freq_hz[paired]).size == paired.sum()     # one-to-one
    np.testing.assert_allclose(md.shift_from_massless[paired],
                               md.freq_hz[paired] / md.massless_freq_hz[paired] - 1,
                               rtol=1e-15)
    assert np.all(np.isnan(md.shift_from_massless[~paired]))


def test_one_labelling_by_platform_share():
    """mode_kinds: "global" from a platform share of 0.5, "mixed" from 0.05, "local" below
    (theory.md §12.1); a ModalResult takes its kind from its cable fraction when none is
    given."""
    from dynstiff.constants import GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD
    from dynstiff.results import mode_kinds
    assert mode_kinds([0.0, 0.0499, 0.05, 0.4999, 0.5, 1.0]) == (
        "local", "local", "mixed", "mixed", "global", "global")
    assert (PLATFORM_SHARE_THRESHOLD, GLOBAL_SHARE) == (0.05, 0.5)
    res = ds.ModalResult(freq_hz=np.array([1.0, 2.0, 3.0]), platform_shapes=np.zeros((3, 6)),
                         cable_energy_fraction=np.array([0.01, 0.6, 0.97]),
                         cable_energy=np.zeros((3, 1)))
    assert res.kind == ("global", "mixed", "local")
    assert np.isnan(res.massless_freq_hz).all() and np.isnan(res.participation).all()


def test_rich_displays_hold_the_key_numbers(cogiro_model):
    from conftest import assert_valid_html
    md = ds.modes(cogiro_model, 30)
    text = assert_valid_html(md._repr_html_())
    assert f"{md.freq_hz[0]:.5g}" in text and f"{md.freq_hz[19]:.5g}" in text
    assert f"{md.freq_hz[20]:.5g}" not in text and "10 more rows" in text
    assert md.kind[0] in text and f"{md.platform_share[3]:.5g}" in text
    omega = 2 * np.pi * np.linspace(0.5, 3.0, 40)
    with pytest.warns(ds.ResonanceWarning):     # undamped across the modes, on purpose
        r = ds.frf(cogiro_model, omega, inputs=["fx", "mz"], outputs=["x"])
    text = assert_valid_html(r._repr_html_())
    a = np.abs(r.H[:, 0, 1])
    assert f"{a.max():.5g}" in text and f"{r.freq_hz[np.argmax(a)]:.5g}" in text
    assert "m/(N m)" in text and "receptance" in text


def _frf(H, freq_hz=None):
    H = np.asarray(H, dtype=complex).reshape(-1, 1, 1)
    f = np.arange(1.0, len(H) + 1) if freq_hz is None else np.asarray(freq_hz, dtype=float)
    return ds.FRFResult(freq_hz=f, H=H, inputs=("fx",), outputs=("x",), kind="receptance",
                        damping="undamped")


def test_empty_frf_displays_without_frequencies():
    from conftest import assert_valid_html
    r = _frf(np.zeros(0))
    assert repr(r) == ("FRFResult(receptance, 0 frequencies none, outputs ('x',), "
                       "inputs ('fx',), undamped)")
    text = assert_valid_html(r._repr_html_())
    assert "0 frequencies none" in text and "nan" in text


def test_frf_display_names_the_largest_finite_value_and_its_columns():
    """An exact pole (inf) is not the largest |H|: the largest finite value is, at its own
    frequency."""
    from conftest import assert_valid_html
    html = _frf([np.inf, 1e-3, 2e-3, 5e-4], [1.0, 2.0, 3.0, 4.0])._repr_html_()
    assert "<th>output</th><th>input</th><th>unit</th><th>largest |H|</th><th>at [Hz]</th>" \
        in html
    text = assert_valid_html(html)
    assert "0.002" in text and "m/N" in text and "3" in text.split("0.002")[1]


def test_modal_display_numbers_modes_from_one_and_names_its_class():
    res = ds.ModalResult(freq_hz=np.array([1.0, 2.0]), platform_shapes=np.zeros((2, 6)),
                         cable_energy_fraction=np.array([0.01, 0.97]),
                         cable_energy=np.zeros((2, 1)))
    assert repr(res) == "ModalResult(2 modes 1-2 Hz: 1 global, 0 mixed, 1 local)"
    html = res._repr_html_()
    assert ("<th>mode</th><th>freq [Hz]</th><th>kind</th><th>platform share [-]</th>"
            "<th>dominant dof</th>") in html
    assert "<tr><td>1</td><td>1</td><td>global</td>" in html
    assert "<td>0</td>" not in html.split("</th></tr>")[1].split("</tr>")[0]


def test_damped_modes_repr_with_a_root_at_zero_gives_no_warning():
    """omega = 0 is a finite root with an undefined damping ratio (0/0): the repr reads nan
    for it, with no RuntimeWarning (0/0, an all-NaN minimum), which this test turns into an
    error."""
    import warnings
    d = ds.DampedModes(undamped_freq_hz=np.array([1.0, 2.0]), omega=np.array([0j, 6 + 0.3j]),
                       residual=np.array([0.0, 0.0]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isnan(d.damping_ratio[0])
        assert repr(d) == "DampedModes(2 modes, 2 damped roots found, damping ratio 0.0499..0.0499)"
        at_zero = ds.DampedModes(undamped_freq_hz=np.array([1.0]), omega=np.array([0j]),
                                 residual=np.array([0.0]))
        assert repr(at_zero) == \
            "DampedModes(1 mode, 1 damped root found, damping ratio undefined)"


def test_result_plots_draw_into_the_axes_given(cogiro_model):
    import matplotlib.pyplot as plt
    omega = 2 * np.pi * np.array([0.5, 0.8])
    r = ds.frf(cogiro_model, omega, inputs=["fx", "fz"], outputs=["x", "z"])
    fig, ax = plt.subplots()
    assert r.plot(ax=ax, pairs=[("z", "fz")]) is fig
    assert len(ax.lines) == 1                       # the one pair asked, not the diagonal
    plt.close(fig)
    md = ds.modes(cogiro_model, 3)
    fig, ax = plt.subplots()
    assert md.plot(ax=ax) is fig and ax.has_data()
    plt.close(fig)
    d = ds.DampedModes(undamped_freq_hz=np.array([1.0]), omega=np.array([6.0 + 0.1j]),
                       residual=np.array([0.0]))
    fig, ax = plt.subplots()
    assert d.plot(ax=ax) is fig and ax.has_data()
    plt.close(fig)


def test_frf_to_uff_is_ascii_unless_binary_is_asked(tmp_path):
    r = _frf([1e-3, 2e-3])
    text = r.to_uff(tmp_path / "a.uff").read_bytes()
    text.decode("ascii")                            # ASCII records: no raw doubles
    assert b"58b" not in text.splitlines()[1]
    raw = r.to_uff(tmp_path / "b.uff", binary=True).read_bytes()
    assert b"58b" in raw.splitlines()[1]


def test_modal_table_carries_the_participations(cogiro_model):
    md = ds.modes(cogiro_model, 4)
    df = md.to_frame()
    cols = [f"participation {n} [-]" for n in ("x", "y", "z", "rx", "ry", "rz")]
    np.testing.assert_array_equal(df[cols].to_numpy(), md.participation)


def test_frf_to_uff_names_the_platform_entity_unless_told(tmp_path):
    pyuff = pytest.importorskip("pyuff")
    r = _frf([1e-3, 2e-3])
    rec = pyuff.UFF(str(r.to_uff(tmp_path / "a.uff"))).read_sets()
    assert rec["rsp_ent_name"].strip() == rec["ref_ent_name"].strip() == "platform"
    rec = pyuff.UFF(str(r.to_uff(tmp_path / "b.uff", entity="cabin"))).read_sets()
    assert rec["rsp_ent_name"].strip() == "cabin"


def test_modal_display_is_titled_with_its_repr():
    res = ds.ModalResult(freq_hz=np.array([1.0]), platform_shapes=np.zeros((1, 6)),
                         cable_energy_fraction=np.array([0.01]), cable_energy=np.zeros((1, 1)))
    assert res._repr_html_().startswith(f"<div><p><b>{repr(res)}</b></p>")


def test_frf_plot_draws_magnitude_only_unless_phase_is_asked():
    import matplotlib.pyplot as plt
    r = _frf([1e-3, 2e-3, 1.5e-3])
    fig = r.plot()
    assert len(fig.axes) == 1
    plt.close(fig)
    fig = r.plot(phase=True)
    assert len(fig.axes) == 2
    plt.close(fig)
