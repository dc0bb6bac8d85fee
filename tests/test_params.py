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
    (dict(mass_per_length=0.1, EA=1e5, viscous_damping=float("nan")), "viscous_damping"),
])
def test_bad_cable_raises_naming_field(kwargs, name):
    with pytest.raises(InvalidParameterError, match=name):
        ds.Cable(**kwargs)
