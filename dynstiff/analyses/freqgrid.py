"""Frequency grids refined around the modes, so that a damped FRF's peaks are sampled.

A uniform grid of n points sees a resonance of damping ratio zeta only if its step is below
about zeta f_r; an undamped or lightly damped peak read from a uniform grid depends on the
grid. :func:`refined_grid` adds to the uniform grid, around every natural frequency f_r in
the band, points f_r (1 +- d) with d geometric from ``rel_min`` to ``rel_width``: the step
near the mode is then below rel_min f_r and grows by a constant ratio away from it, so a
peak of half-power width 2 zeta f_r >= 2e-3 f_r is sampled within 0.1 % of its top whatever
the uniform count (theory.md §12.3).
"""

from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import band, positive_scalar
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["refined_grid"]


def refined_grid(band_hz: str | tuple[float, float], n_points: int, modes_hz: ArrayLike = (),
                 rel_width: float = 0.03, rel_min: float = 1e-6,
                 per_side: int = 40) -> NDArray[np.float64]:
    """Uniform grid over ``band_hz`` plus points clustered at every mode inside it.

    Parameters
    ----------
    band_hz : (float, float)
        Band [Hz], 0 <= low < high.
    n_points : int
        Points of the uniform part, >= 2.
    modes_hz : array_like, shape (n_modes,)
        Natural frequencies [Hz]; those outside the band are ignored.
    rel_width : float
        Relative half-width of the refined neighbourhood of a mode [-].
    rel_min : float
        Smallest relative offset from a mode [-].
    per_side : int
        Points on each side of a mode (geometric in the offset), plus the mode itself.

    Returns
    -------
    ndarray, shape (n,)
        Sorted, unique frequencies [Hz] inside the band (both ends included).
    """
    lo, hi = band(band_hz)
    if int(n_points) != n_points or n_points < 2:
        raise InvalidParameterError(f"n_points must be an integer >= 2, got {n_points!r}")
    rel_width = positive_scalar("rel_width", rel_width)
    rel_min = positive_scalar("rel_min", rel_min)
    if not rel_min < rel_width:
        raise InvalidParameterError(
            f"rel_min must be < rel_width, got {rel_min!r} and {rel_width!r}")
    f = np.asarray(modes_hz, dtype=float).ravel()
    f = f[np.isfinite(f) & (f >= lo) & (f <= hi)]
    d = _offsets(rel_min, rel_width, int(per_side))
    extra = (f[:, None] * (1.0 + d[None, :])).ravel()
    grid = np.concatenate([np.linspace(lo, hi, int(n_points)), extra])
    return np.unique(grid[(grid >= lo) & (grid <= hi)])


@lru_cache(maxsize=16)
def _offsets(rel_min: float, rel_width: float, per_side: int) -> NDArray[np.float64]:
    """Relative offsets of the points at a mode: -d[::-1], 0, d with d geometric from
    rel_min to rel_width, shape (2 per_side + 1,), read-only (the same for every mode and
    every call with these settings: computed once)."""
    d = np.geomspace(rel_min, rel_width, per_side)
    d = np.concatenate([-d[::-1], [0.0], d])
    d.setflags(write=False)
    return d
