"""Measurements in: measured natural frequencies (with optional platform mode shapes) and
measured FRFs, read from files and compared with a model (theory.md §15.5).

Measured modes come as a table, CSV with a header: a frequency column ``freq [Hz]`` (or
``freq_hz``), optionally ``sigma [Hz]`` (standard deviation of each frequency), ``damping
ratio [-]``, and platform shape columns among ``x y z rx ry rz`` (the units of
:class:`~dynstiff.ModalResult`: m, rad; empty where not measured). Measured FRFs come as UFF 58
records (function type 4, as :meth:`dynstiff.FRFResult.to_uff` writes them) or as the CSV of
:meth:`dynstiff.FRFResult.to_frame`.

Pairing a measured mode with a model mode (:func:`pair_modes`):

* ``"mac"`` (default when shapes are given): the assignment (Hungarian) that maximises the
  sum of MAC x platform share over the pairs, MAC on the measured platform DOFs,
  MAC = |a^T b|^2 / (|a|^2 |b|^2), platform share = 1 - cable energy fraction;
* ``"order"`` (default without shapes): the k-th measured frequency with the k-th global mode;
* ``"frequency"``: the assignment minimising the sum of |ln(f_model / f_measured)| over global
  modes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff._validate import real_array
from dynstiff.analyses.measured_frf import FRFComparison, compare_frf, read_measured_frf
from dynstiff.constants import DOF_NAMES
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from pathlib import Path

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray

    from dynstiff.models.base import PlatformModel
    from dynstiff.results import ModalResult

__all__ = ["MeasuredModes", "ModeComparison", "FRFComparison", "PAIRINGS", "compare_frf",
           "compare_modes", "mac_matrix", "massless_pairing", "pair_modes",
           "read_measured_frf", "read_measured_modes"]

#: Ways to pair measured and model modes (module notes).
PAIRINGS = ("mac", "order", "frequency")
_FREQ_COLUMNS = ("freq [Hz]", "freq_hz", "frequency [Hz]", "f [Hz]")


@dataclass(frozen=True)
class MeasuredModes:
    """Measured natural frequencies, optionally with platform shapes.

    Parameters
    ----------
    freq_hz : array_like, shape (n,)
        Natural frequencies [Hz], > 0.
    shapes : array_like, shape (n, 6), optional
        Platform motions (x, y, z [m], rx, ry, rz [rad]) about P, any scale; NaN where a DOF
        was not measured.
    sigma_hz : array_like, shape (n,), optional
        Standard deviation of each frequency [Hz], > 0 (weights of a calibration).
    damping_ratio : array_like, shape (n,), optional
        Measured modal damping ratios [-].

    Examples
    --------
    >>> import dynstiff as ds
    >>> measured = ds.MeasuredModes(freq_hz=[2.25, 2.40, 3.05], sigma_hz=[0.01, 0.01, 0.02])
    >>> list(measured.to_frame().columns)
    ['freq [Hz]', 'sigma [Hz]']
    """

    freq_hz: np.ndarray
    shapes: object = None
    sigma_hz: object = None
    damping_ratio: object = None

    def __post_init__(self) -> None:
        try:
            f = np.atleast_1d(real_array("freq_hz", self.freq_hz))
        except InvalidParameterError:
            f = np.empty(0)                     # text, complex, booleans, ragged: refused below
        if f.ndim != 1 or f.size == 0 or not np.all(np.isfinite(f)) or np.any(f <= 0):
            raise InvalidParameterError(
                f"freq_hz must be a non-empty list of finite frequencies > 0 [Hz], got "
                f"{self.freq_hz!r}")
        object.__setattr__(self, "freq_hz", f)
        if self.shapes is not None:
            S = _floats("shapes", self.shapes)
            if S.shape != (f.size, 6):
                raise InvalidParameterError(
                    f"shapes must have shape ({f.size}, 6) (x y z rx ry rz per mode, NaN where "
                    f"not measured), got {S.shape}")
            if not np.all(np.any(np.isfinite(S) & (S != 0), axis=1)):
                raise InvalidParameterError("shapes: every mode needs a nonzero measured DOF")
            object.__setattr__(self, "shapes", S)
        for name in ("sigma_hz", "damping_ratio"):
            v = getattr(self, name)
            if v is None:
                continue
            v = _floats(name, v)
            if v.shape not in ((), (1,), f.shape):
                raise InvalidParameterError(
                    f"{name} must be one number or one per mode ({f.size}), got shape {v.shape}")
            v = np.broadcast_to(v, f.shape).copy()
            if name == "damping_ratio" and not np.all((v >= 0) & (v < 1)):
                raise InvalidParameterError(
                    f"damping_ratio must be in [0, 1) (an underdamped mode), one per mode, "
                    f"got {getattr(self, name)!r}")
            if not np.all(np.isfinite(v)) or np.any(v < 0) or (name == "sigma_hz"
                                                               and np.any(v == 0)):
                raise InvalidParameterError(f"{name} must be finite and > 0, one per mode, "
                                            f"got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)

    def __len__(self) -> int:
        return self.freq_hz.size

    def __repr__(self) -> str:
        shapes = "yes" if self.shapes is not None else "no"
        return (f"MeasuredModes({counted(len(self), 'mode')} {self.freq_hz.min():.4g}-"
                f"{self.freq_hz.max():.4g} Hz, shapes {shapes})")

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame in the format :func:`read_measured_modes` reads.

        Examples
        --------
        >>> import dynstiff as ds
        >>> measured = ds.MeasuredModes(freq_hz=[2.25, 2.40, 3.05], sigma_hz=[0.01, 0.01, 0.02])
        >>> list(measured.to_frame().columns)
        ['freq [Hz]', 'sigma [Hz]']
        """
        import pandas as pd
        df = pd.DataFrame({"freq [Hz]": self.freq_hz})
        if self.sigma_hz is not None:
            df["sigma [Hz]"] = self.sigma_hz
        if self.damping_ratio is not None:
            df["damping ratio [-]"] = self.damping_ratio
        if self.shapes is not None:
            for k, name in enumerate(DOF_NAMES):
                df[name] = self.shapes[:, k]
        return df


def _floats(name: str, value: object) -> np.ndarray:
    """``value`` as a float array, or InvalidParameterError naming ``name`` (text, complex
    or ragged input)."""
    return real_array(name, value)


def read_measured_modes(path: str | Path) -> MeasuredModes:
    """Read a table of measured modes (CSV, module notes), strictly: every number is parsed
    on its own (a bad one is named with its line and column, a decimal comma refused), an
    empty shape cell is "not measured". Shape columns are named ``x .. rz``, with or
    without a unit in brackets, so dynstiff's own modes tables (``x [m/kg^0.5, x'Mx=1]``
    ...) read back with their shapes.

    Returns
    -------
    MeasuredModes

    Raises
    ------
    InvalidParameterError
        No frequency column, an empty file, or bad values (named with file, line and
        column).

    Examples
    --------
    >>> import dynstiff as ds
    >>> measured = ds.MeasuredModes(freq_hz=[2.25, 2.40, 3.05], sigma_hz=[0.01, 0.01, 0.02])
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "modes.csv")
    >>> measured.to_frame().to_csv(path, index=False)
    >>> ds.read_measured_modes(path).freq_hz.tolist()
    [2.25, 2.4, 3.05]
    """
    from dynstiff.io.table import read_table
    table = read_table(path)
    col = next((c for c in _FREQ_COLUMNS if c in table.columns), None)
    if col is None:
        raise InvalidParameterError(f"{path}: no frequency column; expected one of "
                                    f"{list(_FREQ_COLUMNS)}, found {list(table.columns)}")
    shape_cols = {}
    for c in table.columns:
        name = c.split(" [", 1)[0].strip()
        if name in DOF_NAMES and (c == name or c.endswith("]")):
            if name in shape_cols:
                raise InvalidParameterError(
                    f"{path}: two shape columns for {name!r}: {shape_cols[name]!r}, {c!r}")
            shape_cols[name] = c
    shapes = None
    if shape_cols:
        shapes = np.full((len(table), 6), np.nan)
        for name, c in shape_cols.items():
            shapes[:, DOF_NAMES.index(name)] = table.numbers(c, empty=np.nan)
    freq = table.numbers(col)
    sigma = table.numbers("sigma [Hz]") if "sigma [Hz]" in table.columns else None
    zeta = (table.numbers("damping ratio [-]") if "damping ratio [-]" in table.columns
            else None)
    try:
        return MeasuredModes(freq_hz=freq, shapes=shapes, sigma_hz=sigma, damping_ratio=zeta)
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"{path}: {exc}") from None


def mac_matrix(measured_shapes: NDArray[np.float64],
               model_shapes: NDArray[np.float64]) -> NDArray[np.float64]:
    """MAC between measured and model platform shapes on the measured DOFs.

    Parameters
    ----------
    measured_shapes : ndarray, shape (n_meas, 6), NaN where not measured
    model_shapes : ndarray, shape (n_model, 6)

    Returns
    -------
    ndarray, shape (n_meas, n_model), in [0, 1]
    """
    A = np.asarray(measured_shapes, dtype=float)
    B = np.asarray(model_shapes, dtype=float)
    mask = np.isfinite(A)
    A0 = np.where(mask, A, 0.0)
    num = (A0 @ B.T) ** 2
    nb = mask.astype(float) @ (B**2).T             # |b|^2 over each measured mode's DOFs
    na = np.sum(A0**2, axis=1)[:, None]
    with np.errstate(invalid="ignore", divide="ignore"):
        mac = num / (na * nb)
    return np.nan_to_num(mac, nan=0.0)


def massless_pairing(model_modes: ModalResult, model: PlatformModel, n: int) -> NDArray[np.int64]:
    """Indices of the modes of ``model_modes`` that continue the first ``n`` platform modes of
    the massless-cable model (K(0) phi = omega^2 M_p phi): for each, the mode with the largest
    mass-weighted MAC x platform share (Hungarian assignment), shape (n,).

    The massless modes keep their order when a parameter moves the whole spectrum, while the
    modes of a rung with cable mass split near cable frequencies; this pairing follows the
    platform motion through them (theory.md §15.5)."""
    from scipy.linalg import eigh
    M = model.platform_mass
    lam, X0 = eigh(model.massless_stiffness(), M)
    if n > X0.shape[1]:
        raise InvalidParameterError(f"{n} measured modes but the platform has only "
                                    f"{X0.shape[1]} free DOFs")
    X = np.asarray(model_modes.platform_shapes)[:, model.free_index]     # (n_modes, n_free)
    num = (X0[:, :n].T @ M @ X.T) ** 2
    den = np.einsum("ij,jk,ik->i", X, M, X)[None, :] * \
        np.einsum("ji,jk,ki->i", X0[:, :n], M, X0[:, :n])[:, None]
    with np.errstate(invalid="ignore", divide="ignore"):
        mac = np.nan_to_num(num / den)
    return _assign_by_platform_mac(mac, model_modes, n)


def _assign_by_platform_mac(mac: NDArray[np.float64], model_modes: ModalResult,
                            n: int) -> NDArray[np.int64]:
    """Model mode paired with each of ``n`` rows of ``mac`` (n, n_modes): the Hungarian
    assignment maximising MAC x platform share (1 - cable energy fraction), shape (n,)."""
    from scipy.optimize import linear_sum_assignment
    score = mac * (1.0 - np.asarray(model_modes.cable_energy_fraction))[None, :]
    if score.shape[1] < n:
        raise InvalidParameterError(f"{n} measured modes but only {score.shape[1]} model "
                                    f"modes computed: compute more (fmax_hz)")
    rows, cols = linear_sum_assignment(-score)
    idx = np.empty(n, dtype=int)
    idx[rows] = cols
    return idx


def pair_modes(model_modes: ModalResult, measured: MeasuredModes,
               pairing: str | None = None) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Pair measured modes with modes of a :class:`~dynstiff.ModalResult` (module notes).

    Returns
    -------
    model_index : ndarray of int, shape (n_meas,)
        Index into ``model_modes`` of each measured mode's partner.
    mac : ndarray, shape (n_meas,)
        Their MAC (NaN without measured shapes).

    Raises
    ------
    InvalidParameterError
        Unknown ``pairing``, "mac" without shapes, or fewer candidate model modes than
        measured ones.
    """
    from scipy.optimize import linear_sum_assignment
    pairing = pairing or ("mac" if measured.shapes is not None else "order")
    if pairing not in PAIRINGS:
        raise InvalidParameterError(f"pairing must be one of {PAIRINGS}, got {pairing!r}")
    n = len(measured)
    glob = np.flatnonzero(np.array(model_modes.kind) == "global")
    if pairing == "mac":
        if measured.shapes is None:
            raise InvalidParameterError("pairing='mac' needs measured shapes")
        mac = mac_matrix(measured.shapes, model_modes.platform_shapes)
        idx = _assign_by_platform_mac(mac, model_modes, n)
        return idx, mac[np.arange(n), idx]
    if glob.size < n:
        raise InvalidParameterError(
            f"{n} measured modes but the model has {glob.size} global modes in "
            f"{len(model_modes)} computed: compute more (fmax_hz), or give shapes")
    if pairing == "order":
        idx = glob[np.argsort(np.argsort(measured.freq_hz))]
    else:
        cost = np.abs(np.log(model_modes.freq_hz[glob][None, :] / measured.freq_hz[:, None]))
        rows, cols = linear_sum_assignment(cost)
        idx = np.empty(n, dtype=int)
        idx[rows] = glob[cols]
    mac = (mac_matrix(measured.shapes, model_modes.platform_shapes)[np.arange(n), idx]
           if measured.shapes is not None else np.full(n, np.nan))
    return idx, mac


@dataclass(frozen=True)
class ModeComparison:
    """Measured and model frequencies, paired.

    Attributes
    ----------
    measured_hz, model_hz : ndarray, shape (n,)
        [Hz].
    model_index : ndarray of int, shape (n,)
        The model mode (0-based, in the model's ascending list) of each measured mode.
    mac : ndarray, shape (n,)
        NaN without measured shapes.
    kind : tuple of str
        "global"/"local" of the paired model modes.
    """

    measured_hz: np.ndarray
    model_hz: np.ndarray
    model_index: np.ndarray
    mac: np.ndarray
    kind: tuple

    @property
    def error(self) -> NDArray[np.float64]:
        """Relative error f_model / f_measured - 1 [-], shape (n,)."""
        return self.model_hz / self.measured_hz - 1.0

    def __len__(self) -> int:
        return self.measured_hz.size

    def __repr__(self) -> str:
        return (f"ModeComparison({len(self)} pairs, largest error "
                f"{np.abs(self.error).max():.3g}, rms {np.sqrt(np.mean(self.error**2)):.3g})")

    def to_frame(self) -> pd.DataFrame:
        """One row per measured mode, units in the column names."""
        import pandas as pd
        return pd.DataFrame({"measured [Hz]": self.measured_hz, "model [Hz]": self.model_hz,
                             "error [-]": self.error, "model mode": self.model_index + 1,
                             "kind": list(self.kind), "MAC [-]": self.mac})

    def plot(self, ax: Axes | None = None) -> Figure:
        """Model against measured frequency, with the line of equality; returns the Figure."""
        import matplotlib.pyplot as plt
        if ax is None:
            fig, ax = plt.subplots(figsize=(4.5, 4.2))
        fig = ax.figure
        lo = 0.9 * min(self.measured_hz.min(), self.model_hz.min())
        hi = 1.1 * max(self.measured_hz.max(), self.model_hz.max())
        ax.plot([lo, hi], [lo, hi], color="0.6", lw=1)
        ax.plot(self.measured_hz, self.model_hz, "o", color="C0")
        for k, (fm, fa) in enumerate(zip(self.measured_hz, self.model_hz)):
            ax.annotate(f"{100 * self.error[k]:+.1f} %", (fm, fa), textcoords="offset points",
                        xytext=(5, -10), fontsize=8)
        ax.set(xlabel="measured [Hz]", ylabel="model [Hz]", xlim=(lo, hi), ylim=(lo, hi))
        return fig


def compare_modes(model_or_modes: PlatformModel | ModalResult, measured: MeasuredModes,
                  pairing: str | None = None,
                  fmax_hz: float | None = None) -> ModeComparison:
    """Pair measured modes with a model's and tabulate the errors (theory.md §15.5).

    Parameters
    ----------
    model_or_modes : model of any rung, or its :class:`~dynstiff.ModalResult`
    measured : MeasuredModes, or array_like of frequencies [Hz]
    pairing : {"mac", "order", "frequency"}, optional
        Default "mac" with measured shapes, "order" without.
    fmax_hz : float, optional
        Band of the model's modes (default 1.5 x the highest measured frequency).

    Returns
    -------
    ModeComparison

    Examples
    --------
    >>> import dynstiff as ds
    >>> measured = ds.MeasuredModes(freq_hz=[2.25, 2.40, 3.05], sigma_hz=[0.01, 0.01, 0.02])
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> c = ds.compare_modes(m, measured)
    >>> print(c)
    ModeComparison(3 pairs, largest error 0.0195, rms 0.0187)
    """
    measured = measured if isinstance(measured, MeasuredModes) else MeasuredModes(measured)
    md = model_or_modes
    if not hasattr(md, "platform_shapes"):
        from dynstiff.analyses.modes import modes
        md = modes(model_or_modes, fmax_hz=fmax_hz or 1.5 * measured.freq_hz.max())
    idx, mac = pair_modes(md, measured, pairing)
    return ModeComparison(measured_hz=measured.freq_hz, model_hz=md.freq_hz[idx],
                          model_index=idx, mac=mac, kind=tuple(md.kind[k] for k in idx))
