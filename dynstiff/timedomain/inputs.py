"""The inputs of a time-domain run, checked before it starts: winch lengths (a function of
time or a table interpolated in time), the platform excitation, the initial offset and
velocity, and the number of steps.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import real_array
from dynstiff.constants import DOF_NAMES as OUTPUT_NAMES
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.models.lumped_robot import LumpedMassModel

__all__ = ["excitation_function", "initial_state", "interpolated_table", "lengths_function",
           "step_count"]


# -------------------------------------------------------------------------- inputs
def lengths_function(lengths: Callable[..., Any] | None, n: int) -> Callable[..., Any] | None:
    if lengths is None:
        return None
    if callable(lengths):
        fn = lengths
    else:
        try:
            times, table = lengths
            times = real_array("lengths", times)
            table = real_array("lengths", table)
        except (TypeError, ValueError):
            raise InvalidParameterError(
                "lengths must be a callable t -> (n_cables,) unstretched lengths [m] or a "
                f"table (times (k,) [s], lengths (k, {n}) [m]), got {lengths!r}") from None
        fn = interpolated_table(times, table, n, "lengths", "lengths", "m")

    def checked(t: float) -> NDArray[np.float64]:
        L = np.asarray(fn(t), dtype=float)
        if L.shape != (n,) or not np.all(np.isfinite(L)) or np.any(L <= 0):
            raise InvalidParameterError(
                f"lengths(t) must give {n} finite positive unstretched lengths [m], got "
                f"{L!r} at t = {t:g} s")
        return L
    return checked


def excitation_function(
        excitation: Callable[..., Any] | None,
) -> tuple[Callable[..., Any] | None, None]:
    """(callable t -> (6,) or None, the table (times, loads) or None) from ``excitation``."""
    if excitation is None or callable(excitation):
        return excitation, None
    try:
        times, loads = excitation
        times = real_array("excitation", times)
        loads = real_array("excitation", loads)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"excitation must be a callable t -> (6,) load, a table (times (k,) [s], loads "
            f"(k, 6) [N, N m]) or None, got {excitation!r}") from None
    fn = interpolated_table(times, loads, 6, "excitation", "loads", "N, N m", finite=True)
    return fn, (times, loads)


def interpolated_table(times, values, n, name, column, unit, finite: bool = False):
    """t -> values interpolated linearly in a table (times (k,) [s], values (k, n)), checked:
    times finite, strictly increasing, starting at t <= 0 (and the values finite with
    ``finite``); the error names ``name``."""
    if times.ndim != 1 or times.size < 1 or values.shape != (times.size, n) or \
            not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0) or \
            (finite and not np.all(np.isfinite(values))):
        raise InvalidParameterError(
            f"{name} table must be (times (k,) strictly increasing [s], {column} (k, {n})"
            f"{' finite' if finite else ''} [{unit}]), got shapes {times.shape} and "
            f"{values.shape}")
    if times[0] > 0:
        raise InvalidParameterError(
            f"{name} table must start at t <= 0, starts at {times[0]:g} s")

    def fn(t):
        return np.array([np.interp(t, times, values[:, j]) for j in range(n)])
    return fn


def initial_state(
        initial: list[float] | tuple[NDArray[np.float64] | list[float], list[float]] | None,
        model: LumpedMassModel,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(offset (6,), velocity (6,)) from ``initial``."""
    zero = np.zeros(6)
    if initial is None:
        return zero, zero
    if isinstance(initial, (tuple, list)) and len(initial) == 2 and \
            not np.isscalar(initial[0]):
        parts = [zero if p is None else p for p in initial]
    else:
        parts = [initial, zero]
    out = []
    for name, p in zip(("initial offset", "initial velocity"), parts):
        try:
            p = np.asarray(p, dtype=float)
        except (TypeError, ValueError):
            p = None
        if p is None or p.shape != (6,) or not np.all(np.isfinite(p)):
            raise InvalidParameterError(
                f"initial must be a platform offset (6,) [m, rad] or (offset, velocity) with "
                f"velocity (6,) [m/s, rad/s]; the {name} is {parts[len(out)]!r}")
        held = [k for k in range(6) if k not in model.free_index and p[k] != 0]
        if held:
            raise InvalidParameterError(
                f"initial: the {name} is nonzero on held DOF(s) "
                f"{[OUTPUT_NAMES[k] for k in held]}; only {model.free_dofs} are free")
        out.append(p)
    return out[0], out[1]


def step_count(t_end: float, dt: float) -> int:
    return max(1, int(np.ceil(t_end / dt - 1e-9)))
