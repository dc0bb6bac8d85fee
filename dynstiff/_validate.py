"""Argument checks shared by the public functions (internal)."""

from __future__ import annotations

import math
import reprlib
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

#: The least normal float: below it a float has lost digits (subnormal).
_TINY = float(np.finfo(float).tiny)


def holds_bool(value: object) -> bool:
    """True when ``value`` is a bool or an array or (nested) sequence holding one."""
    if isinstance(value, (bool, np.bool_)):
        return True
    if isinstance(value, np.ndarray):
        return value.dtype == np.bool_ or (value.dtype == object and
                                           any(holds_bool(v) for v in value.flat))
    if isinstance(value, (list, tuple)):
        return any(holds_bool(v) for v in value)
    return False


def refuse_bools(name: str, value: object) -> None:
    """Raise naming ``name`` when ``value`` is or holds a bool: ``True`` is not the number 1
    (numpy would read it so), in an array no more than alone.

    >>> refuse_bools("end", [0, True])
    Traceback (most recent call last):
    ...
    dynstiff.errors.InvalidParameterError: end must be real numbers, not booleans, got [0, True]
    """
    if holds_bool(value):
        raise InvalidParameterError(
            f"{name} must be real numbers, not booleans, got {reprlib.repr(value)}")


def real_array(name: str, value: Any, what: str = "real numbers") -> NDArray[np.float64]:
    """``value`` as a float array of its own shape, or raise naming ``name`` (and ``what``
    it must be) when it holds a bool or anything that is not a number; shape and range are
    the caller's to check."""
    refuse_bools(name, value)
    try:
        if not np.iscomplexobj(value):               # never drop an imaginary part
            return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        pass
    raise InvalidParameterError(f"{name} must be {what}, got {reprlib.repr(value)}")


def flag(name: str, value: object) -> bool:
    """``value`` if it is a bool, else raise naming ``name``: a string such as "no" is not
    False (Python would take it as True)."""
    if not isinstance(value, (bool, np.bool_)):
        raise InvalidParameterError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def count(name: str, value: object, least: int = 1) -> int:
    """``value`` as an int >= ``least``, or raise naming ``name`` (a bool or a float is not
    a count)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or \
            value < least:
        raise InvalidParameterError(f"{name} must be an integer >= {least}, got {value!r}")
    return int(value)


def band(value: object, name: str = "band_hz") -> tuple[float, float]:
    """A frequency band (low, high) [Hz] as two floats, 0 <= low < high, both finite, or
    raise naming ``name``."""
    refuse_bools(name, value)
    try:
        lo, hi = (float(b) for b in value)  # type: ignore[attr-defined]
    except (TypeError, ValueError):
        raise InvalidParameterError(f"{name} must be (low, high) [Hz], got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi):
        raise InvalidParameterError(
            f"{name} must be (low, high) with 0 <= low < high [Hz], got {value!r}")
    return lo, hi


def index(name: str, value: object, n: int) -> int:
    """``value`` as an index into ``n`` items, 0 <= value < n, or raise naming ``name``
    (a bool or a float is not an index)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or \
            not 0 <= value < n:
        raise InvalidParameterError(f"{name} must be an integer in [0, {n}), got {value!r}")
    return int(value)


def finite_scalar(name: str, value: object) -> float:
    """``value`` as a finite float of any sign, or raise naming ``name`` (a bool is not a
    number)."""
    if isinstance(value, (bool, np.bool_)):
        raise InvalidParameterError(f"{name} must be a real number, got {value!r}")
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InvalidParameterError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(x):
        raise InvalidParameterError(f"{name} must be finite, got {x!r}")
    return x


def positive_scalar(name: str, value: float | str, allow_zero: bool = False) -> float:
    """Return ``value`` as a float, or raise naming ``name`` if it is not finite and > 0
    (a bool is not a number: ``True`` is refused, never read as 1)."""
    x = finite_scalar(name, value)
    if x < 0 or (x == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise InvalidParameterError(f"{name} must be {bound}, got {x!r}")
    if 0 < x < _TINY:
        raise InvalidParameterError(
            f"{name} must be 0 or at least {_TINY:.3g} (a subnormal float has lost its "
            f"digits), got {x!r}")
    return x


def point(name: str, value: ArrayLike, dim: int = 3) -> NDArray[np.float64]:
    """Return ``value`` as a finite float array of shape ``(dim,)``, or raise naming ``name``."""
    arr = real_array(name, value, f"a sequence of {dim} real numbers")
    if arr.shape != (dim,):
        raise InvalidParameterError(
            f"{name} must have shape ({dim},), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(f"{name} must be finite, got {arr.tolist()}")
    return arr


#: Largest angular frequency [rad/s] any function accepts: omega^2 M stays finite.
MAX_OMEGA = 1e150


def omega_array(value: ArrayLike, name: str = "omega", complex_ok: bool = False) -> NDArray[Any]:
    """Return angular frequencies as a 1-D array; raise if negative or not finite.

    A scalar becomes shape ``(1,)``. With ``complex_ok`` a complex input stays complex (any
    finite value: the damped roots lie off the real axis); otherwise the array is float and
    must be >= 0.
    """
    refuse_bools(name, value)
    dtype = complex if complex_ok and np.iscomplexobj(value) else float
    if dtype is float and np.iscomplexobj(value):        # never drop an imaginary part
        raise InvalidParameterError(
            f"{name} must be real angular frequencies [rad/s], got complex values")
    try:
        arr = np.atleast_1d(np.asarray(value, dtype=dtype))
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be real angular frequencies [rad/s], got {value!r}") from None
    if arr.ndim != 1:
        raise InvalidParameterError(
            f"{name} must be a scalar or 1-D array, got shape {arr.shape}")
    bad = ~np.isfinite(arr) if dtype is complex else ~np.isfinite(arr) | (arr < 0)
    if np.any(bad):
        raise InvalidParameterError(
            f"{name} must be finite{'' if dtype is complex else ' and >= 0'} [rad/s], got "
            f"{arr[bad][0]!r} at index {int(np.flatnonzero(bad)[0])}")
    if arr.size and np.abs(arr).max() > MAX_OMEGA:
        raise InvalidParameterError(
            f"{name} must be <= {MAX_OMEGA:g} rad/s (omega^2 times a mass must stay finite), "
            f"got {np.abs(arr).max():.6g}")
    return arr


def unstretched_lengths(value: ArrayLike | str, n: int) -> NDArray[np.float64]:
    """Return ``n`` unstretched cable lengths [m] as a float array of shape (n,), or raise
    naming ``unstretched_lengths`` if they are not n finite positive numbers."""
    refuse_bools("unstretched_lengths", value)
    try:
        L0 = real_array("unstretched_lengths", value)
    except InvalidParameterError:
        L0 = None
    if L0 is None or L0.shape != (n,) or not np.all(np.isfinite(L0)) or \
            np.any(L0 < np.finfo(float).tiny):
        raise InvalidParameterError(
            f"unstretched_lengths must be {n} finite positive lengths [m] (one per cable), "
            f"got {value!r}")
    return L0


def tension_reference(value: ArrayLike, n: int) -> NDArray[np.float64]:
    """Return a reference tension [N] as a float array of shape () (every cable's) or (n,)
    (one per cable), or raise naming ``tension_reference`` if it is neither, or not finite.

    Examples
    --------
    >>> tension_reference(500, 8).shape, tension_reference([1.0, 2.0], 2).tolist()
    ((), [1.0, 2.0])
    """
    refuse_bools("tension_reference", value)
    ref = real_array("tension_reference", value, f"one tension or {n} [N]")
    if ref.shape not in ((), (n,)) or not np.all(np.isfinite(ref)):
        raise InvalidParameterError(f"tension_reference must be one tension or {n} finite "
                                    f"tensions [N], got {value!r}")
    return ref
