"""Checks of a workspace map made before its first pose (docs/theory.md §13.8): the options of
the model (a bad one is an error naming it, never a map of "infeasible" poses), the shape
of the orientations (checked, never reshaped), and the size of the run (poses, memory and
time estimated, refused beyond a stated limit with the option to change).

Example
-------
>>> from dynstiff.maps.guards import check_size
>>> check_size(1_000_000, n_cables=8, n_modes=20, n_checks=9,
...            max_poses=200_000)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
dynstiff.errors.InvalidParameterError: the map gives 1,000,000 poses, more than ...
"""

import os
from numbers import Integral, Real

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.errors import InvalidParameterError

__all__ = ["MAX_POSES", "check_model_options", "check_orientations", "check_size",
           "estimate_text", "map_bytes"]

#: Poses a map computes unless ``max_poses`` says more: about half an hour on one core at
#: the closed-form rung's 8 ms a CoGiRo pose (docs/theory.md §13.5), and about 0.5 GiB.
MAX_POSES = 200_000

# The options of each rung (dynstiff.models.ladder.build_model) and what each must be.
_RUNG_OPTIONS = {"dsm": ("tension", "chordwise_inertia", "cable_loss_factor",
                         "platform_damping_ratio", "guard_rtol"),
                 "exact": ("fmax_hz", "order", "half_waves", "cable_loss_factor",
                           "platform_damping_ratio"),
                 "lumped": ("tol", "max_iter", "segments")}
_POSITIVE = ("fmax_hz", "guard_rtol", "tol")
_COUNTS = ("order", "half_waves", "max_iter", "segments")
_FRACTIONS = ("cable_loss_factor", "platform_damping_ratio")


def _count(name, v):
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, Integral) or v < 1:
        raise InvalidParameterError(f"{name} must be an integer >= 1, got {v!r}")


def check_model_options(rung, model_options):
    """Refuse, before any pose, a model option the rung does not take or a bad value.

    Parameters
    ----------
    rung : str
    model_options : dict
        Keywords of :func:`dynstiff.models.ladder.build_model`: ``fmax_hz`` [Hz],
        ``guard_rtol``, ``tol`` (> 0); ``order``, ``half_waves``, ``max_iter``,
        ``segments`` (integers >= 1; ``segments`` also one per cable);
        ``cable_loss_factor`` [-] and ``platform_damping_ratio`` [-] in [0, 1);
        ``tension`` "mean" or "chord"; ``chordwise_inertia`` a bool.

    Raises
    ------
    InvalidParameterError
        Naming the option and its value (a bool is not a number).
    """
    allowed = _RUNG_OPTIONS.get(rung, ())
    unknown = sorted(set(model_options) - set(allowed))
    if unknown:
        raise InvalidParameterError(f"options {unknown} do not apply to rung {rung!r} (it "
                                    f"takes {list(allowed) or 'none'})")
    for name, v in model_options.items():
        if name in _POSITIVE and not (name == "guard_rtol" and v is None):
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, Real):
                raise InvalidParameterError(f"{name} must be a number > 0, got {v!r}")
            positive_scalar(name, v)
        elif name in _COUNTS:
            for k in (v if name == "segments" and np.ndim(v) == 1 else [v]):
                _count(name, k)
        elif name in _FRACTIONS:
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, Real) or not 0 <= v < 1:
                raise InvalidParameterError(f"{name} must be a number in [0, 1), got {v!r}")
        elif name == "tension" and v not in ("mean", "chord"):
            raise InvalidParameterError(f"tension must be 'mean' or 'chord', got {v!r}")
        elif name == "chordwise_inertia" and not isinstance(v, (bool, np.bool_)):
            raise InvalidParameterError(f"chordwise_inertia must be True or False, got {v!r}")


def check_orientations(orientations):
    """Rotation vectors [rad] as an array of shape (n, 3), n >= 1 (one vector of shape (3,)
    is one orientation); any other shape is refused, never reshaped."""
    try:
        rot = np.asarray(orientations, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"orientations must be rotation vectors, shape (n, 3) "
                                    f"[rad], got {orientations!r}") from None
    if rot.shape == (3,):
        rot = rot[None, :]
    if rot.ndim != 2 or rot.shape[1] != 3 or rot.shape[0] == 0:
        raise InvalidParameterError(f"orientations must be rotation vectors, shape (n, 3) "
                                    f"[rad], got shape {rot.shape}")
    if not np.all(np.isfinite(rot)):
        raise InvalidParameterError(f"orientations must be finite rotation vectors [rad], "
                                    f"got {orientations!r}")
    return rot


def map_bytes(n_poses, n_cables, n_modes, n_checks):
    """Memory a map of ``n_poses`` holds while it is computed and assembled [bytes]: the
    pose vectors, every variable of :data:`dynstiff.maps.dataset.VARIABLES` and a reason
    string per pose, three times (chunk results, the joined arrays, the Dataset).

    Per pose: 6 floats of the pose; the residual, 5 per cable (tension, unstretched length,
    least and largest tension, sag ratio), 2 per mode (frequency, platform share) and 5
    scalars (first platform frequency, band margin, proximity gap, uncertain probability
    and margin) as floats; as booleans feasible, dynamic, 1 per mode (is_platform) and 2
    per check (passed, unknown); about 120 bytes of reason."""
    floats = 6 + 1 + 5 * n_cables + 2 * n_modes + 5
    booleans = 2 + n_modes + 2 * n_checks
    return 3 * n_poses * (8 * floats + booleans + 120)


def _physical_memory():
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):       # pragma: no cover - not POSIX
        return None


def _gib(b):
    return f"{b / 2**30:.3g} GiB"


def check_size(n_poses, n_cables, n_modes, n_checks, max_poses=MAX_POSES, what="the map"):
    """Refuse a map over ``max_poses`` poses, or one whose arrays would not fit in this
    machine's memory, with one line naming the count and what to change.

    Parameters
    ----------
    n_poses : int
        Poses times parameter values.
    n_cables, n_modes, n_checks : int
    max_poses : int or None
        The limit (None: no limit but memory's).
    what : str
        How the poses came about, e.g. "box [...] with step 0.01 m".

    Returns
    -------
    int
        The estimated memory [bytes] (:func:`map_bytes`).
    """
    if max_poses is not None:
        _count("max_poses", max_poses)
    need = map_bytes(n_poses, n_cables, n_modes, n_checks)
    have = _physical_memory()
    change = ("raise step= (--step) or shrink the box (--box)" if "step" in what
              else "give fewer poses or parameter values")
    if have is not None and need > 0.5 * have:
        raise InvalidParameterError(
            f"{what} gives {n_poses:,} poses, which need about {_gib(need)} of memory "
            f"(this machine has {_gib(have)}): {change}")
    if max_poses is not None and n_poses > max_poses:
        raise InvalidParameterError(
            f"{what} gives {n_poses:,} poses, more than max_poses={max_poses:,} (about "
            f"{_gib(need)} of memory): {change}, or raise max_poses= (--max-poses)")
    return need


def estimate_text(n_poses, seconds_per_pose, n_bytes, workers=1):
    """One line: ``workspace: 12,000 poses, about 0.02 GiB, about 3.1 min (first pose
    15 ms a pose in a sample)``; the time divided among ``workers`` parallel workers."""
    t = n_poses * seconds_per_pose / max(1, workers)
    span = (f"{t:.0f} s" if t < 120 else f"{t / 60:.1f} min" if t < 7200
            else f"{t / 3600:.1f} h")
    return (f"workspace: {n_poses:,} poses, about {_gib(n_bytes)}, about {span}"
            + (f" on {workers} workers" if workers > 1 else "")
            + f" ({1e3 * seconds_per_pose:.0f} ms a pose in a sample)")
