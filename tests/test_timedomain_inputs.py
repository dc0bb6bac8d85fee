"""The tables of a time-domain run (dynstiff/timedomain/inputs.py): a table t -> values,
linear between its rows and held beyond them, checked before any step."""

import re

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.timedomain.inputs import interpolated_table


def table(times, values, finite=False):
    return interpolated_table(np.asarray(times, dtype=float), np.asarray(values, dtype=float),
                              2, "excitation", "loads", "N", finite=finite)


def test_values_are_linear_between_rows_and_held_beyond():
    """Rows (t, v) -> v(t) by linear interpolation per column, the end rows held outside."""
    fn = table([-1.0, 0.0, 2.0], [[0.0, 1.0], [2.0, 1.0], [6.0, -3.0]])
    np.testing.assert_array_equal(fn(-0.5), [1.0, 1.0])
    np.testing.assert_array_equal(fn(1.0), [4.0, -1.0])
    np.testing.assert_array_equal(fn(5.0), [6.0, -3.0])
    np.testing.assert_array_equal(fn(-9.0), [0.0, 1.0])


def test_one_row_is_a_constant():
    """A single row at t <= 0 is a valid table: its values at every time."""
    fn = table([0.0], [[3.0, -2.0]])
    np.testing.assert_array_equal(fn(0.0), [3.0, -2.0])
    np.testing.assert_array_equal(fn(7.5), [3.0, -2.0])


def message(times_shape, values_shape, finite):
    return re.escape(f"excitation table must be (times (k,) strictly increasing [s], loads "
                     f"(k, 2){' finite' if finite else ''} [N]), got shapes {times_shape} and "
                     f"{values_shape}")


@pytest.mark.parametrize("times, values, finite", [
    ([0.0, 0.0], [[1.0, 1.0], [2.0, 2.0]], False),          # not strictly increasing
    ([0.0, 1.0, 0.5], np.zeros((3, 2)), True),               # going back
    ([0.0, np.nan], np.zeros((2, 2)), False),                # a time not finite
    ([[0.0, 1.0]], np.zeros((1, 2)), False),                 # times not one-dimensional
    ([], np.zeros((0, 2)), False),                           # no row
    ([0.0, 1.0], np.zeros((2, 3)), True),                    # a column too many
    ([0.0, 1.0], [[0.0, np.inf], [1.0, 1.0]], True),         # a load not finite
])
def test_a_bad_table_is_refused_naming_it_and_its_shapes(times, values, finite):
    """Each bad table: the one message naming the table, what it must be (finite values
    only where asked) and the shapes given."""
    t, v = np.asarray(times, dtype=float), np.asarray(values, dtype=float)
    with pytest.raises(InvalidParameterError, match="^" + message(t.shape, v.shape, finite)
                       + "$"):
        table(t, v, finite=finite)


def test_values_not_finite_are_taken_unless_finite_is_asked():
    """Without ``finite`` a NaN value is a value (a length table may hold one)."""
    fn = table([0.0, 1.0], [[np.nan, 1.0], [2.0, 3.0]])
    assert np.isnan(fn(0.5)[0]) and fn(0.5)[1] == 2.0


def test_a_table_must_start_by_zero():
    """The first row's time is named when it is after t = 0."""
    with pytest.raises(InvalidParameterError,
                       match=r"^excitation table must start at t <= 0, starts at 0\.25 s$"):
        table([0.25, 1.0], np.zeros((2, 2)))
