"""Argument checks shared by the public functions (internal)."""

import numpy as np

from .errors import InvalidParameterError


def positive_scalar(name, value, allow_zero=False):
    """Return ``value`` as a float, or raise naming ``name`` if it is not finite and > 0."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be a real number, got {value!r}") from None
    if not np.isfinite(x):
        raise InvalidParameterError(f"{name} must be finite, got {x!r}")
    if x < 0 or (x == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise InvalidParameterError(f"{name} must be {bound}, got {x!r}")
    return x


def point(name, value, dim=3):
    """Return ``value`` as a finite float array of shape ``(dim,)``, or raise naming ``name``."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be a sequence of {dim} real numbers, got {value!r}") from None
    if arr.shape != (dim,):
        raise InvalidParameterError(
            f"{name} must have shape ({dim},), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(f"{name} must be finite, got {arr.tolist()}")
    return arr


def omega_array(value, name="omega"):
    """Return angular frequencies as a 1-D float array; raise if negative or not finite.

    A scalar becomes shape ``(1,)``.
    """
    try:
        arr = np.atleast_1d(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be real angular frequencies [rad/s], got {value!r}") from None
    if arr.ndim != 1:
        raise InvalidParameterError(
            f"{name} must be a scalar or 1-D array, got shape {arr.shape}")
    bad = ~np.isfinite(arr) | (arr < 0)
    if np.any(bad):
        raise InvalidParameterError(
            f"{name} must be finite and >= 0 [rad/s], got {arr[bad][0]!r} "
            f"at index {int(np.flatnonzero(bad)[0])}")
    return arr
