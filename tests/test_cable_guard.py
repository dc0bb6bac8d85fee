"""The closed form's guard (dynstiff/cable/guard.py, theory.md §11.5): the envelope, the measured
local error and the warning."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable.dsm import chord_parameters
from dynstiff.errors import InvalidParameterError


def test_closed_form_guard_flags_slack_steep_and_axial_cables_and_not_cogiro():
    """closed_form_validity (theory.md §11.5): the estimate bounds the measured error of the
    clamped frequencies against the exact model on the hard cases, is inf for a slack U and
    for axial modes in the band, and stays below 1e-3 on CoGiRo's cables."""
    from dynstiff.cable.guard import closed_form_local_error, closed_form_validity
    slack = ds.solve_catenary([0, 0, 0], [1e-6, 0, 10], 10.1, ds.Cable(0.064, 1.4e5))
    v = closed_form_validity(slack)
    assert np.isinf(v.error) and any("slack" in r for r in v.reasons(1e-2))
    steep = ds.solve_catenary([0, 0, 0], [5.0, 0, 5 * np.sqrt(3)], 10.6, ds.Cable(1.0, 1e6))
    v = closed_form_validity(steep)
    measured = closed_form_local_error(steep, 0.0)
    assert measured > 1e-2 and v.error >= measured
    soft = ds.solve_catenary([0, 0, 0], [10.0, 0, -2.0], 9.8, ds.Cable(1.0, 2e3))
    f_ax = np.sqrt(2e3 / 1.0) / (2 * 9.8)
    assert np.isfinite(closed_form_validity(soft, 2 * np.pi * 0.8 * f_ax).error)
    v = closed_form_validity(soft, 2 * np.pi * f_ax)
    assert np.isinf(v.causes["axial"]) and "axial modes from" in v.reasons(1e-2)[-1]
    for s in ds.load_scene("cogiro").equilibrium().states:
        v = closed_form_validity(s, 2 * np.pi * 20.0)
        assert v.error < 1e-3
        assert closed_form_local_error(s, 2 * np.pi * 20.0) <= v.error
    # the cable-level functions warn too, and stay silent on CoGiRo
    import warnings

    from dynstiff.errors import ClosedFormWarning
    with pytest.warns(ClosedFormWarning, match="off the exact model's") as rec:
        ds.cable_natural_frequencies(steep, 5)
    assert rec[0].message.cause == "local" and rec[0].message.cable is None
    with pytest.warns(ClosedFormWarning) as rec:
        ds.cable_dynamic_stiffness(slack, [0.0, 1.0])
    assert rec[0].message.cause == "slack" and rec[0].message.cable is None
    # the message lists the validity's reasons above a tenth of guard_rtol (1e-2)
    reasons = "; ".join(closed_form_validity(slack, 1.0).reasons(1e-3))
    assert str(rec[0].message) == (f"it is outside the closed form's range ({reasons}): "
                                   f"use model='exact'")
    with pytest.warns(ClosedFormWarning) as rec:
        ds.cable_dynamic_stiffness(soft, 2 * np.pi * f_ax)
    assert rec[0].message.cause == "axial"
    reasons = closed_form_validity(soft, 2 * np.pi * f_ax).reasons(1e-3)
    assert len(reasons) > 1 and str(rec[0].message) == (
        f"it is outside the closed form's range ({'; '.join(reasons)}): use model='exact'")
    for bad in (0, 0.0, -1e-3, np.inf, True, "1e-2"):
        with pytest.raises(InvalidParameterError,
                           match=f"^guard_rtol must be a number > 0 or None, got {bad!r}$"):
            ds.cable_dynamic_stiffness(steep, 1.0, guard_rtol=bad)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ClosedFormWarning)
        ds.cable_natural_frequencies(s, 12)
        ds.cable_dynamic_stiffness(steep, 1.0, guard_rtol=None)


@pytest.mark.parametrize("tension", ["mean", "chord"])
def test_validity_and_exact_modes_use_the_tension_asked(state300, tension):
    """closed_form_validity's weight ratio is W |h| / (L T) with the T of the tension asked
    (theory.md §11.5), and the exact model's modes give Omega = omega L sqrt(m / T) with
    that T, like the closed form's."""
    from dynstiff.cable.guard import closed_form_validity
    s = state300
    p = chord_parameters(s, tension)
    v = closed_form_validity(s, tension=tension)
    assert v.values["weight_ratio"] == pytest.approx(
        s.total_weight * abs(s.chord[2]) / s.chord_length / p.T, rel=1e-14)
    # the envelope's terms (theory.md §11.5): 15 delta^2, 2 delta eps (1 + 40 eps), 0.4 v^2
    delta, eps = p.sag / p.L, v.values["weight_ratio"]
    var = (s.max_tension - s.min_tension) / s.mean_tension
    assert v.causes["sag"] == pytest.approx(15 * delta**2, rel=1e-14)
    assert v.causes["chordwise weight"] == pytest.approx(2 * delta * eps * (1 + 40 * eps),
                                                         rel=1e-14)
    assert v.causes["tension variation"] == pytest.approx(0.4 * var**2, rel=1e-14)
    assert v.error == pytest.approx(sum(v.causes[k] for k in ("sag", "chordwise weight",
                                                              "tension variation")), rel=1e-14)
    for model in ("closed-form", "exact"):
        cm = ds.cable_natural_frequencies(s, 4, tension=tension, model=model)
        np.testing.assert_allclose(cm.Omega, 2 * np.pi * cm.freq_hz * p.L * np.sqrt(p.m / p.T),
                                   rtol=1e-13)


def test_the_default_band_is_the_static_one():
    """Without omega_max the validity judges no band (omega_max = 0): no axial cause even
    for a cable whose axial modes start at 0.05 Hz (EA 1 N, 1 kg/m, 9 m), which any band
    reaching 0.9 of it (here 0.31 rad/s, so 1 rad/s) puts in."""
    from dynstiff.cable.guard import closed_form_validity
    s = ds.solve_catenary([0, 0, 0], [10.0, 0, 0.0], 9.0, ds.Cable(1.0, 1.0))
    f_ax = np.sqrt(1.0 / 1.0) / (2 * 9.0)
    assert closed_form_validity(s).values["axial_hz"] == pytest.approx(f_ax, rel=1e-14)
    assert closed_form_validity(s).causes["axial"] == 0.0
    assert np.isinf(closed_form_validity(s, 1.0).causes["axial"])


def test_the_measured_local_error_uses_the_tension_asked_for_its_band():
    """closed_form_local_error over the modes below 8 omega_1, omega_1 = pi sqrt(T / m) / L
    with the T asked (theory.md §11.5): on a steep sagging cable, whose chord tension is
    34 % below its mean, the chord-tension error is the largest |f_closed / f_exact - 1| of
    the exact cable's non-axial modes in that band, rebuilt here."""
    from dynstiff.cable.exact import ExactCable
    from dynstiff.cable.guard import closed_form_local_error
    s = ds.solve_catenary([0, 0, 0], [5.0, 0, 5 * np.sqrt(3)], 10.6, ds.Cable(1.0, 1e6))
    p = chord_parameters(s, "chord")
    band = 8 * np.pi * np.sqrt(p.T / p.m) / p.L
    ec = ExactCable(s, band)
    keep = (ec.eigenvalues <= band**2) & (np.array(ec.family) != "axial")
    f_ex = np.sqrt(ec.eigenvalues[keep]) / (2 * np.pi)
    f_cf = ds.cable_natural_frequencies(s, f_ex.size, "chord", guard_rtol=None).freq_hz
    want = np.max(np.abs(f_cf / f_ex - 1))
    assert closed_form_local_error(s, 0.0, "chord") == pytest.approx(want, rel=1e-12)
    assert closed_form_local_error(s, 0.0, "mean") != pytest.approx(want, rel=1e-3)


