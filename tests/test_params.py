"""Cable parameters (dynstiff/params.py): a bad value raises InvalidParameterError naming the
field."""

import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError


@pytest.mark.parametrize("kwargs,name", [
    (dict(mass_per_length=0.0, EA=1e5), "mass_per_length"),
    (dict(mass_per_length=-1.0, EA=1e5), "mass_per_length"),
    (dict(mass_per_length=0.1, EA=0.0), "EA"),
    (dict(mass_per_length=0.1, EA=-5.0), "EA"),
    (dict(mass_per_length=float("nan"), EA=1e5), "mass_per_length"),
    (dict(mass_per_length=0.1, EA=float("inf")), "EA"),
    (dict(mass_per_length=0.1, EA=1e5, loss_factor=-0.1), "loss_factor"),
    (dict(mass_per_length=0.1, EA=1e5, loss_factor=1.0), r"loss_factor must be in \[0, 1\)"),
    (dict(mass_per_length=0.1, EA=True), "EA must be a real number, got True"),
    (dict(mass_per_length=0.1, EA=1e5, viscous_damping=float("nan")), "viscous_damping"),
])
def test_bad_cable_raises_naming_field(kwargs, name):
    with pytest.raises(InvalidParameterError, match="^" + name):   # the message opens with it
        ds.Cable(**kwargs)


@pytest.mark.parametrize("kwargs, name", [
    (dict(platform_ratio=-0.01), "platform_ratio"),
    (dict(platform_ratio=1.0), "platform_ratio"),
    (dict(cable_loss_factor=float("nan")), "cable_loss_factor"),
    (dict(cable_viscous_damping=-1.0), "cable_viscous_damping"),
])
def test_bad_damping_raises_naming_field(kwargs, name):
    with pytest.raises(InvalidParameterError, match="^" + name):   # the message opens with it
        ds.Damping(**kwargs)


def test_damping_defaults_are_stated_and_printed():
    d = ds.Damping()
    assert (d.platform_ratio, d.cable_loss_factor, d.cable_viscous_damping) == (0.01, 0.01, 0)
    assert not d.is_zero and ds.Damping(0, 0, 0).is_zero
    assert "platform modal ratio 0.01" in d.text() and "cable loss factor 0.01" in d.text()


def test_cable_viscous_damping_has_no_upper_bound():
    """c is a damping per length [N s/m^2], not a ratio: 1 and above are valid (the two
    ratios stop below 1)."""
    for c in (1.0, 250.0):
        assert ds.Damping(cable_viscous_damping=c).cable_viscous_damping == c


def test_weight_per_length_is_m_g_and_checks_g():
    c = ds.Cable(mass_per_length=0.25, EA=1e5)
    assert c.weight_per_length(9.81) == 0.25 * 9.81 and c.weight_per_length(0.0) == 0.0
    with pytest.raises(InvalidParameterError, match="^g must be >= 0"):
        c.weight_per_length(-9.81)


def test_cable_values_are_stored_as_floats():
    """Numbers given as text, integers or numpy scalars are stored as Python floats."""
    import numpy as np
    c = ds.Cable(mass_per_length="0.5", EA=np.float32(1e5), loss_factor=0, viscous_damping=2)
    assert [type(v) for v in (c.mass_per_length, c.EA, c.loss_factor, c.viscous_damping)] \
        == [float] * 4
    assert (c.mass_per_length, c.EA) == (0.5, 1e5)
