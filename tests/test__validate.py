"""Argument checks shared by the public functions (dynstiff/_validate.py): typed errors that
name the argument, the expectation and the value found."""

import numpy as np
import pytest

from dynstiff._validate import omega_array, point, positive_scalar, unstretched_lengths
from dynstiff.errors import DynstiffError, InvalidParameterError


def test_errors_are_typed_and_subclass_builtins():
    assert issubclass(InvalidParameterError, ValueError)
    assert issubclass(InvalidParameterError, DynstiffError)


@pytest.mark.parametrize("value, match", [
    ("abc", "g must be a real number"), (np.nan, "g must be finite"), (-1.0, "g must be > 0"),
    (0.0, "g must be > 0"), (True, "g must be a real number, got True"),
    (np.bool_(True), "g must be a real number")])
def test_positive_scalar(value, match):
    with pytest.raises(InvalidParameterError, match=match):
        positive_scalar("g", value)
    assert positive_scalar("g", 0.0, allow_zero=True) == 0.0


def test_omega_array_real_and_complex():
    np.testing.assert_array_equal(omega_array(2.0), [2.0])
    with pytest.raises(InvalidParameterError, match=r"omega must be finite and >= 0.*index 1"):
        omega_array([1.0, -1.0])
    with pytest.raises(InvalidParameterError, match="1-D"):
        omega_array(np.ones((2, 2)))
    z = omega_array([1.0 + 0.1j], complex_ok=True)
    assert z.dtype == complex and z[0] == 1.0 + 0.1j
    with pytest.raises(InvalidParameterError, match="finite"):
        omega_array([np.nan + 1j], complex_ok=True)
    assert omega_array([1.0], complex_ok=True).dtype == float     # real stays real


def test_point_and_lengths():
    with pytest.raises(InvalidParameterError, match=r"anchor must have shape \(3,\)"):
        point("anchor", [1, 2])
    with pytest.raises(InvalidParameterError, match="unstretched_lengths must be 2 finite"):
        unstretched_lengths([1.0, 0.0], 2)
    with pytest.raises(InvalidParameterError, match="unstretched_lengths"):
        unstretched_lengths("ab", 2)
    np.testing.assert_array_equal(unstretched_lengths((1, 2), 2), [1.0, 2.0])


def test_omega_is_bounded_so_that_omega_squared_stays_finite():
    from dynstiff._validate import MAX_OMEGA
    assert np.isfinite(MAX_OMEGA**2 * 1e6)
    omega_array([MAX_OMEGA])
    with pytest.raises(InvalidParameterError, match="omega must be <= 1e\\+150"):
        omega_array([1.0, 1e300])


def test_subnormal_scalars_are_refused():
    with pytest.raises(InvalidParameterError, match="EA must be 0 or at least"):
        positive_scalar("EA", 2.225073858507203e-309)
    assert positive_scalar("EA", 2.3e-308) == 2.3e-308
    with pytest.raises(InvalidParameterError, match="unstretched_lengths"):
        unstretched_lengths([1.0, 2.2e-311], 2)
