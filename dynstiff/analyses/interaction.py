"""Modal interaction of global platform modes and local cable modes; mode tracking in sweeps.

Each cable acts on the platform like a set of tuned vibration absorbers, one per
clamped-clamped cable frequency (theory.md §6): a global (platform) mode whose frequency is
close to a local (cable) mode exchanges energy with it, and the two veer apart when a pose or
parameter carries them through each other. This module

* flags global/local pairs of close frequencies (:func:`proximity_warnings`), and
* follows the modes along a path of poses or a parameter (:func:`sweep`), tracking the global
  modes by the modal assurance criterion (MAC) of their platform shapes so that veering
  diagrams can connect the points of one mode.

Notation
--------
==================  =====================================================  ========
symbol              meaning                                                unit
==================  =====================================================  ========
``f_g``, ``f_l``    frequency of a global / local mode                     Hz
``relative_gap``    |f_l - f_g| / f_g                                      --
``x``               platform shape (dp, dtheta) about P, shape (6,)        m, rad
``M_p``             platform mass matrix about P, shape (6, 6)             kg, kg m,
                                                                           kg m^2
``MAC``             (x_a^T M x_b)^2 / ((x_a^T M x_a)(x_b^T M x_b))         --
==================  =====================================================  ========

No plotting here; pandas is imported only by the ``to_frame`` helpers.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import flag, positive_scalar
from dynstiff.errors import DynstiffWarning, InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    import pandas as pd
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.results import ModalResult

__all__ = ["ProximityWarning", "proximity_warnings", "to_frame"]


# ------------------------------------------------------------------------ proximity
class ProximityWarning(DynstiffWarning, UserWarning):
    """A local (cable) mode close in frequency to a global (platform) mode.

    A real :class:`Warning` (``warnings.warn(w)`` issues it; ``proximity_warnings(...,
    warn=True)`` does so for every pair) that is also the record of the pair: equal when its
    fields are.

    Attributes
    ----------
    global_mode, local_mode : int
        Mode numbers, 1-based, as in the ``mode`` column of :meth:`ModalResult.to_frame`
        (index ``mode - 1`` into the arrays of the :class:`ModalResult`).
    freq_global_hz, freq_local_hz : float
        Their frequencies [Hz].
    relative_gap : float
        |freq_local_hz - freq_global_hz| / freq_global_hz [-].

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> w = ds.proximity_warnings(ds.modes(m, fmax_hz=4.0), rtol=0.15)[0]
    >>> print(f"{w.freq_global_hz:.3f} Hz near {w.freq_local_hz:.3f} Hz, gap {w.relative_gap:.3f}")
    2.991 Hz near 3.351 Hz, gap 0.120
    """

    _FIELDS = ("global_mode", "local_mode", "freq_global_hz", "freq_local_hz", "relative_gap")

    def __init__(self, global_mode: int, local_mode: int, freq_global_hz: float,
                 freq_local_hz: float, relative_gap: float) -> None:
        super().__init__(
            f"local mode {local_mode} ({freq_local_hz:.6g} Hz) is within "
            f"{100 * relative_gap:.3g} % of global mode {global_mode} ({freq_global_hz:.6g} Hz)")
        self.global_mode = int(global_mode)
        self.local_mode = int(local_mode)
        self.freq_global_hz = float(freq_global_hz)
        self.freq_local_hz = float(freq_local_hz)
        self.relative_gap = float(relative_gap)

    def _key(self) -> tuple[int, int, float, float, float]:
        return tuple(getattr(self, f) for f in self._FIELDS)

    def __eq__(self, other: tuple[int, int] | ProximityWarning) -> bool:
        return isinstance(other, ProximityWarning) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return ("ProximityWarning(" + ", ".join(f"{f}={getattr(self, f)!r}" for f in self._FIELDS)
                + ")")


def _check_modes(modes: Any) -> tuple[NDArray[np.float64], NDArray[Any]]:
    try:
        f = np.asarray(modes.freq_hz, dtype=float)
        kind = np.asarray(modes.kind)
    except AttributeError:
        raise InvalidParameterError(
            f"modes must be a ModalResult (with freq_hz and kind), got "
            f"{type(modes).__name__}") from None
    if f.ndim != 1 or kind.shape != f.shape:
        raise InvalidParameterError(
            f"modes: freq_hz and kind must be 1-D of equal length, got shapes {f.shape} and "
            f"{kind.shape}")
    return f, kind


def proximity_warnings(modes: ModalResult, rtol: float = 0.05, warn: bool = False,
                       platform: ArrayLike | None = None) -> list[ProximityWarning]:
    """Local modes within a relative frequency gap of a global (platform) mode.

    A local cable mode near a global platform mode acts as a tuned absorber on it
    (theory.md §6): the platform response splits into two peaks and the modes veer. Every
    pair (global g, local l) with

        |f_l - f_g| / f_g <= rtol

    is reported; one local mode may be listed against several global modes and vice versa.
    Only the modes in ``modes`` are compared: to see every partner of a global mode at f_g,
    compute the modes up to at least (1 + rtol) f_g.

    Parameters
    ----------
    modes : ModalResult
        From :func:`dynstiff.analyses.modes.modes`.
    rtol : float
        Largest relative gap [-], > 0 (default 0.05).
    warn : bool
        Also issue each pair as a :class:`ProximityWarning` (``warnings.warn``).
    platform : array_like of int, optional
        Indices (0-based) into ``modes`` of the platform modes to compare with (default:
        the global modes); for example ``PlatformModes.index``
        (:mod:`dynstiff.analyses.platform_modes`), which holds each DOF's carrier also
        when no mode is global. The local modes are those of kind "local".

    Returns
    -------
    list of ProximityWarning
        Sorted by global mode, then by gap (closest first). Empty when no pair is close.
        See :func:`to_frame` for a table.

    Raises
    ------
    InvalidParameterError
        ``rtol`` not finite and > 0, ``modes`` not a modal result, or ``platform`` not
        integer indices of its modes.

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> w = ds.proximity_warnings(ds.modes(m, fmax_hz=4.0), rtol=0.15)
    >>> len(w)
    15
    >>> print(w[0])
    local mode 7 (3.35055 Hz) is within 12 % of global mode 3 (2.99072 Hz)
    """
    rtol = positive_scalar("rtol", rtol)
    warn = flag("warn", warn)
    f, kind = _check_modes(modes)
    if platform is None:
        ig = np.flatnonzero(kind == "global")
    else:
        ig = np.unique(np.asarray(platform))
        if ig.size and (ig.dtype.kind not in "iu" or ig.min() < 0 or ig.max() >= f.size):
            raise InvalidParameterError(
                f"platform must be integer indices of the {f.size} modes, got "
                f"{np.asarray(platform).tolist()}")
    il = np.flatnonzero(kind == "local")
    if ig.size == 0 or il.size == 0:
        return []
    gap = np.abs(f[il][None, :] - f[ig][:, None]) / f[ig][:, None]     # (n_global, n_local)
    out = []
    for a, b in zip(*np.nonzero(gap <= rtol)):
        out.append(ProximityWarning(global_mode=int(ig[a]) + 1, local_mode=int(il[b]) + 1,
                                    freq_global_hz=float(f[ig[a]]),
                                    freq_local_hz=float(f[il[b]]),
                                    relative_gap=float(gap[a, b])))
    out.sort(key=lambda w: (w.global_mode, w.relative_gap, w.local_mode))
    if warn:
        import warnings
        for w in out:
            warnings.warn(w, stacklevel=2)
    return out


def to_frame(warnings: list[ProximityWarning]) -> pd.DataFrame:
    """pandas DataFrame of proximity warnings, one row per pair, units in the column names.

    Parameters
    ----------
    warnings : sequence of ProximityWarning
        From :func:`proximity_warnings`.

    Returns
    -------
    pandas.DataFrame
        Columns ``global mode``, ``local mode``, ``freq global [Hz]``, ``freq local [Hz]``,
        ``relative gap [-]`` (zero rows if ``warnings`` is empty).
    """
    import pandas as pd
    warnings = list(warnings)
    for w in warnings:
        if not isinstance(w, ProximityWarning):
            raise InvalidParameterError(
                f"warnings must hold ProximityWarning items, got {type(w).__name__}")
    return pd.DataFrame({
        "global mode": np.array([w.global_mode for w in warnings], dtype=int),
        "local mode": np.array([w.local_mode for w in warnings], dtype=int),
        "freq global [Hz]": np.array([w.freq_global_hz for w in warnings], dtype=float),
        "freq local [Hz]": np.array([w.freq_local_hz for w in warnings], dtype=float),
        "relative gap [-]": np.array([w.relative_gap for w in warnings], dtype=float),
    })


