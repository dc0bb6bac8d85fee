"""Damping of the time-domain model and the explicit step limit
(dynstiff/timedomain/damping.py, theory.md §7.3)."""

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import LumpedMassModel, TimeDamping, explicit_step_limit


def test_rayleigh_gives_its_ratio_at_both_frequencies():
    """zeta(omega) = alpha / (2 omega) + beta omega / 2 equals zeta at f1 and f2, and is
    smaller between them."""
    d = TimeDamping.rayleigh(0.02, 1.5, 6.0)
    for f in (1.5, 6.0):
        w = 2 * np.pi * f
        assert d.alpha / (2 * w) + d.beta * w / 2 == pytest.approx(0.02, rel=1e-14)
    w = 2 * np.pi * 3.0
    assert d.alpha / (2 * w) + d.beta * w / 2 < 0.02


def test_rayleigh_checks_its_arguments_by_name_and_takes_zeta_zero():
    """zeta may be 0 (no damping: alpha = beta = 0), not negative; each frequency must be
    > 0; every refusal names its argument and the value."""
    d = TimeDamping.rayleigh(0.0, 1.0, 2.0)
    assert (d.alpha, d.beta) == (0.0, 0.0)
    for args, name, value in (((-0.1, 1.0, 2.0), "zeta", "-0.1"),
                              ((np.nan, 1.0, 2.0), "zeta", "nan"),
                              ((0.01, 0.0, 2.0), "freq1_hz", "0.0"),
                              ((0.01, -1.0, 2.0), "freq1_hz", "-1.0"),
                              ((0.01, 1.0, 0.0), "freq2_hz", "0.0"),
                              ((0.01, 1.0, np.inf), "freq2_hz", "inf")):
        with pytest.raises(InvalidParameterError, match=rf"^{name} must be .*{value}"):
            TimeDamping.rayleigh(*args)


def test_axial_dashpots_per_cable_and_bad_values():
    assert np.array_equal(TimeDamping(axial=2.0).axial_per_cable(3), [2.0, 2.0, 2.0])
    assert np.array_equal(TimeDamping(axial=[1, 2, 3]).axial_per_cable(3), [1, 2, 3])
    with pytest.raises(InvalidParameterError, match="damping.axial"):
        TimeDamping(axial=[1, 2]).axial_per_cable(3)
    with pytest.raises(InvalidParameterError, match="axial"):
        TimeDamping(axial=-1.0)
    with pytest.raises(InvalidParameterError, match="beta"):
        TimeDamping(beta=np.nan)


def test_a_wrong_number_of_axial_dashpots_is_refused_with_both_counts():
    """axial_per_cable(n) refuses a sequence of another length than n, naming damping.axial,
    the n expected and the count given."""
    for axial, n, got in (([1.0, 2.0], 3, 2), ([1.0, 2.0, 3.0, 4.0], 8, 4)):
        with pytest.raises(InvalidParameterError,
                           match=rf"^damping\.axial must be one value or {n} values "
                                 rf"\(one per cable\), got {got}$"):
            TimeDamping(axial=axial).axial_per_cable(n)


@pytest.mark.parametrize("name, value, shown", [
    ("alpha", -1.0, "-1.0"), ("alpha", np.inf, "inf"), ("beta", -0.5, "-0.5"),
    ("beta", np.nan, "nan")])
def test_a_negative_or_infinite_rayleigh_coefficient_is_refused_by_name(name, value, shown):
    """alpha and beta must be finite and >= 0; the refusal names the coefficient and the
    value given."""
    with pytest.raises(InvalidParameterError, match=rf"^{name} must be .*{shown}"):
        TimeDamping(**{name: value})


def test_the_damping_holds_plain_floats_whatever_real_numbers_are_given():
    """alpha and beta are held as floats and axial as a float or a tuple of floats (one per
    cable), whatever real numbers they were given as (numpy scalars, ints, an array): a
    TimeDamping then equals, hashes and prints as the one built from those floats."""
    d = TimeDamping(alpha=np.float32(0.25), beta=np.int64(2), axial=np.array([1, 2]))
    ref = TimeDamping(alpha=0.25, beta=2.0, axial=(1.0, 2.0))
    assert type(d.alpha) is float and type(d.beta) is float
    assert d.axial == (1.0, 2.0) and all(type(c) is float for c in d.axial)
    assert d == ref and hash(d) == hash(ref)
    assert repr(d) == "TimeDamping(alpha=0.25, beta=2.0, axial=(1.0, 2.0))"
    one = TimeDamping(axial=[3])
    assert type(one.axial) is float and one.axial == 3.0
    assert TimeDamping(axial=[1, 2, 3]) == TimeDamping(axial=(1.0, 2.0, 3.0))


def test_explicit_limit_is_the_axial_wave_transit_time_of_a_segment(cogiro, cogiro_eq):
    """Undamped: dt < l0 / sqrt(EA / m) (theory.md §7.3); damping lowers it by
    sqrt(1 + zeta^2) - zeta."""
    N = 10
    mm = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=N)
    cab = cogiro.robot.cables[0]
    dt0 = (cogiro_eq.unstretched_lengths / N).min() / np.sqrt(cab.EA / cab.mass_per_length)
    assert explicit_step_limit(mm) == pytest.approx(dt0, rel=1e-14)
    l0 = cogiro_eq.unstretched_lengths.min() / N
    c = 0.1 * l0 * np.sqrt(cab.EA * cab.mass_per_length)      # zeta = 0.1 on the top mode
    damped = explicit_step_limit(mm, damping=TimeDamping(axial=c))
    assert damped == pytest.approx(dt0 * (np.sqrt(1.01) - 0.1), rel=1e-12)


def test_explicit_limit_takes_rayleigh_terms_and_the_lengths_given(cogiro, cogiro_eq):
    """Each Rayleigh term adds its share to zeta on the highest mode, alpha / (2 omega_max)
    and beta omega_max / 2 with omega_max = 2 / dt0; lengths given instead of the model's
    scale the limit with the shortest segment; lengths that are not one positive length
    per cable are refused by name."""
    N = 10
    mm = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=N)
    cab = cogiro.robot.cables[0]
    dt0 = (cogiro_eq.unstretched_lengths / N).min() / np.sqrt(cab.EA / cab.mass_per_length)
    w_max = 2.0 / dt0
    for alpha, beta in ((0.2 * w_max, 0.0), (0.0, 0.2 / w_max), (0.1 * w_max, 0.1 / w_max)):
        zeta = 0.5 * alpha / w_max + 0.5 * beta * w_max
        got = explicit_step_limit(mm, damping=TimeDamping(alpha=alpha, beta=beta))
        assert zeta == pytest.approx(0.1, rel=1e-12)
        assert got == pytest.approx(dt0 * (np.sqrt(1.01) - 0.1), rel=1e-12)
    L0 = 2 * cogiro_eq.unstretched_lengths
    assert explicit_step_limit(mm, L0.tolist()) == pytest.approx(2 * dt0, rel=1e-14)
    assert explicit_step_limit(mm, [int(x) + 1 for x in L0]) > 2 * dt0
    for bad in (L0[:3], np.full(8, -1.0), ["a"] * 8):
        with pytest.raises(InvalidParameterError, match="^unstretched_lengths must be 8 finite "
                                                        "positive lengths"):
            explicit_step_limit(mm, bad)


@pytest.mark.parametrize("axial, message", [
    (True, "^axial must be real numbers, not booleans, got True"),
    ([0.5, True], "^axial must be real numbers, not booleans"),
    ("a", r"^axial must be a finite dashpot c_ax >= 0 \[N s\] or one per cable, got 'a'"),
    (1j, r"^axial must be a finite dashpot c_ax >= 0 \[N s\] or one per cable, got 1j"),
    ([], r"^axial must be a finite dashpot c_ax >= 0 \[N s\] or one per cable, got \[\]")])
def test_an_axial_dashpot_of_booleans_text_or_complex_numbers_is_refused(axial, message):
    with pytest.raises(InvalidParameterError, match=message):
        TimeDamping(axial=axial)
