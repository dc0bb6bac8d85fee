"""The result of :func:`dynstiff.frequency_sensitivities`: derivatives of the natural
frequencies, as a table, normalised and as tornado charts (theory.md §16).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted

if TYPE_CHECKING:

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray


__all__ = ["SensitivityResult"]


@dataclass(frozen=True)
class SensitivityResult:
    """Derivatives of the natural frequencies with respect to parameters.

    Attributes
    ----------
    freq_hz : ndarray, shape (m,)
        Natural frequencies of the undamped model [Hz].
    parameters : tuple of str
        Parameter names (:mod:`dynstiff.analyses.sensitivity_parameters`).
    values : ndarray, shape (p,)
        Their values at the model.
    units : tuple of str
        Their units.
    derivative : ndarray, shape (m, p)
        d f_k / d p_j [Hz per unit of p_j]; 0 for a loss factor; NaN for a mode whose
        platform is at rest on a cable pole (``note``). Within a cluster of coincident
        modes, the one-sided derivatives for an increase of p_j, ascending.
    damping_derivative : ndarray, shape (m, p)
        d zeta_k / d p_j [per unit] of the modal damping ratio, for the loss factors (first
        order about the undamped mode); NaN for the other parameters.
    cluster : ndarray of int, shape (m,)
        Modes with the same number are coincident (one subspace).
    platform_share : ndarray, shape (m,)
        Platform share of each mode's kinetic energy [-] (theory.md §13.3).
    rung, hold : str
    note : str

    Examples
    --------
    >>> import dynstiff as ds
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> s = ds.frequency_sensitivities(m, ["EA", "mass"], n_modes=2)
    >>> s.parameters, s.derivative.shape
    (('EA', 'mass'), (2, 2))
    """

    freq_hz: np.ndarray
    parameters: tuple
    values: np.ndarray
    units: tuple
    derivative: np.ndarray
    damping_derivative: np.ndarray
    cluster: np.ndarray
    platform_share: np.ndarray
    rung: str
    hold: str
    note: str = ""

    @property
    def relative(self) -> NDArray[np.float64]:
        """Change of each frequency per 1 % of each parameter, 0.01 p df/dp [Hz], (m, p).

        Examples
        --------
        >>> import dynstiff as ds
        >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
        >>> s = ds.frequency_sensitivities(m, ["EA", "mass"], n_modes=2)
        >>> [f"{v:+.4f}" for v in s.relative[0]]      # Hz per +1 % of EA, of the mass
        ['+0.0108', '-0.0102']
        """
        return 0.01 * self.derivative * self.values[None, :]

    @property
    def elasticity(self) -> NDArray[np.float64]:
        """(p / f) df/dp [-], (m, p): the relative change of f per relative change of p.

        Examples
        --------
        >>> import dynstiff as ds
        >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
        >>> s = ds.frequency_sensitivities(m, ["EA", "mass"], n_modes=2)
        >>> [f"{v:+.3f}" for v in s.elasticity[0]]
        ['+0.487', '-0.461']
        """
        return self.derivative * self.values[None, :] / self.freq_hz[:, None]

    def __repr__(self) -> str:
        return (f"SensitivityResult({counted(len(self.freq_hz), 'mode')} x "
                f"{counted(len(self.parameters), 'parameter')}, {self.rung} rung at fixed "
                f"{self.hold})")

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per mode and parameter: frequency, parameter, value,
        unit, df/dp, df per 1 %, elasticity, d zeta/dp.

        Examples
        --------
        >>> import dynstiff as ds
        >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
        >>> s = ds.frequency_sensitivities(m, ["EA", "mass"], n_modes=2)
        >>> len(s.to_frame())
        4
        """
        import pandas as pd
        m, p = self.derivative.shape
        return pd.DataFrame({
            "mode": np.repeat(np.arange(1, m + 1), p),
            "freq [Hz]": np.repeat(self.freq_hz, p),
            "cluster": np.repeat(self.cluster, p),
            "platform share [-]": np.repeat(self.platform_share, p),
            "parameter": np.tile(self.parameters, m),
            "value": np.tile(self.values, m), "unit": np.tile(self.units, m),
            "df/dp [Hz/unit]": self.derivative.ravel(),
            "df per 1 % [Hz]": self.relative.ravel(),
            "elasticity [-]": self.elasticity.ravel(),
            "dzeta/dp [1/unit]": self.damping_derivative.ravel()})

    def plot(self, modes: tuple[int, int] = (0,), n_parameters: int = 10,
             ax: Axes | None = None) -> Figure:
        """Tornado chart per mode: the change of the frequency per 1 % of each parameter
        (:attr:`relative`, NaN drawn as 0), the ``n_parameters`` largest in magnitude, the
        largest at the top, a rise in blue ("tab:blue", zero counted as a rise) and a fall in
        red ("tab:red"), the parameters' names on the bars, a zero line (grey 0.3, 0.8 pt).
        One panel per mode of ``modes``, side by side, 4.2 x 3.6 in each (or on ``ax``, the
        first mode only). Returns the matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
        >>> s = ds.frequency_sensitivities(m, ["EA", "mass"], n_modes=2)
        >>> import matplotlib.pyplot as plt
        >>> plt.close(s.plot())
        """
        import matplotlib.pyplot as plt
        modes = list(modes)
        if ax is None:
            fig, axes = plt.subplots(1, len(modes), figsize=(4.2 * len(modes), 3.6),
                                     squeeze=False)
            axes = axes[0]
        else:
            axes, fig = [ax], ax.figure
        for a, k in zip(axes, modes):
            r = np.nan_to_num(self.relative[k])
            order = np.argsort(np.abs(r))[::-1][:n_parameters][::-1]
            a.barh(np.arange(order.size), r[order],
                   color=np.where(r[order] >= 0, "tab:blue", "tab:red"))
            a.set_yticks(np.arange(order.size), [self.parameters[j] for j in order])
            a.axvline(0.0, color="0.3", lw=0.8)
            a.set(xlabel="change per +1 % of the parameter [Hz]",
                  title=f"mode {k + 1}: {self.freq_hz[k]:.4g} Hz")
        fig.tight_layout()
        return fig
