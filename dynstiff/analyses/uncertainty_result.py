"""The result of an uncertainty propagation: the distributions of the frequencies by first order
and by Monte Carlo, side by side (theory.md §16.6).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray


__all__ = ["UncertaintyResult"]


@dataclass(frozen=True)
class UncertaintyResult:
    """Distributions of the frequencies by first order and by Monte Carlo, side by side.

    Attributes
    ----------
    parameters : tuple of str
    nominal_values : ndarray, shape (p,)
    uncertain : tuple of Uncertain
    samples : ndarray, shape (n_samples, p)
        Parameter values of the Latin-hypercube sample.
    quantities : tuple of str
        "f1", "f2", ... (modes by index) [Hz], "first_platform_hz" [Hz] and, with a band,
        "band_margin" [-].
    nominal : ndarray, shape (q,)
    gradient : ndarray, shape (q, p)
        d quantity / d p at the nominal values.
    first_order : ndarray, shape (n_samples, q)
        The linearised model at the samples.
    monte_carlo : ndarray, shape (n_samples, q) or None
        The full model at the samples (NaN where the statics failed).
    failed : int
        Samples whose statics or modes failed.
    seed : int

    Examples
    --------
    >>> import dynstiff as ds
    >>> res = ds.propagate_uncertainty(ds.load_scene("cogiro"), uncertain={"EA": "1%"}, n_modes=1,
    ...                            n_samples=16, method="first-order")
    >>> q = res.quantities[0]; print(q, f"{res.std_first_order[0]:.4f} Hz", len(res.to_frame()))
    f1 0.0108 Hz 2
    >>> print(f"{res.quantile(q, 0.5, method='first-order'):.4f}",
    ...       f"{res.probability_below(q, 2.2, method='first-order'):.3f}")
    2.2062 0.312
    """

    parameters: tuple
    nominal_values: np.ndarray
    uncertain: tuple
    samples: np.ndarray
    quantities: tuple
    nominal: np.ndarray
    gradient: np.ndarray
    first_order: np.ndarray
    monte_carlo: object
    failed: int
    seed: int

    @property
    def std_first_order(self) -> NDArray[np.float64]:
        """sqrt(sum_j (dq/dp_j sigma_j)^2) of every quantity, shape (q,)."""
        sig = np.array([u.std(v) for u, v in zip(self.uncertain, self.nominal_values)])
        return np.sqrt(np.sum((self.gradient * sig[None, :]) ** 2, axis=1))

    def _column(self, quantity: str, method: str) -> NDArray[np.float64]:
        if quantity not in self.quantities:
            raise InvalidParameterError(f"quantity must be one of {self.quantities}, got "
                                        f"{quantity!r}")
        data = {"first-order": self.first_order, "monte-carlo": self.monte_carlo}.get(method)
        if data is None:
            raise InvalidParameterError(f"method must be 'first-order' or 'monte-carlo' "
                                        f"(computed), got {method!r}")
        return data[:, self.quantities.index(quantity)]

    def probability_below(self, quantity: str, threshold: float,
                          method: str = "monte-carlo") -> float:
        """Share of the samples where ``quantity`` < ``threshold`` (a failed sample counts
        as below: its verdict fails) [-].

        Examples
        --------
        >>> import dynstiff as ds
        >>> res = ds.propagate_uncertainty(ds.load_scene("cogiro"), uncertain={"EA": "1%"},
        ...                            n_modes=1, n_samples=16)
        >>> q = res.quantities[0]
        >>> print(f"{res.probability_below(q, 2.20, method='first-order'):.3f}")
        0.312
        """
        x = self._column(quantity, method)
        return float(np.mean(~(x >= threshold)))

    def quantile(self, quantity: str, q: float, method: str = "monte-carlo") -> float:
        """The q-quantile of ``quantity`` (failed samples as -inf).

        Examples
        --------
        >>> import dynstiff as ds
        >>> res = ds.propagate_uncertainty(ds.load_scene("cogiro"), uncertain={"EA": "1%"},
        ...                            n_modes=1, n_samples=16)
        >>> q = res.quantities[0]
        >>> print(f"{res.quantile(q, 0.5, method='first-order'):.4f} Hz")
        2.2062 Hz
        """
        x = np.where(np.isnan(self._column(quantity, method)), -np.inf,
                     self._column(quantity, method))
        with np.errstate(invalid="ignore"):
            r = float(np.quantile(x, q))
        # numpy interpolates next to -inf as -inf + inf = NaN: the quantile is -inf there
        return -np.inf if np.isnan(r) else r

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per quantity: nominal, first-order and Monte Carlo mean,
        standard deviation and 5 / 95 % quantiles.

        Examples
        --------
        >>> import dynstiff as ds
        >>> res = ds.propagate_uncertainty(ds.load_scene("cogiro"), uncertain={"EA": "1%"},
        ...                            n_modes=1, n_samples=16)
        >>> len(res.to_frame())
        2
        """
        import pandas as pd
        rows = []
        for i, name in enumerate(self.quantities):
            row = {"quantity": name, "nominal": self.nominal[i],
                   "std first order (linear)": self.std_first_order[i]}
            for method, data in (("first order", self.first_order),
                                 ("Monte Carlo", self.monte_carlo)):
                if data is None:
                    continue
                x = data[:, i]
                row[f"mean {method}"] = np.nanmean(x)
                row[f"std {method}"] = np.nanstd(x, ddof=1)
                row[f"q05 {method}"], row[f"q95 {method}"] = np.nanquantile(x, [0.05, 0.95])
            rows.append(row)
        return pd.DataFrame(rows)

    def plot(self, quantity: str = "first_platform_hz", ax: Axes | None = None) -> Figure:
        """Histograms of ``quantity`` by first order and Monte Carlo. Returns the Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> res = ds.propagate_uncertainty(ds.load_scene("cogiro"), uncertain={"EA": "1%"},
        ...                            n_modes=1, n_samples=16)
        >>> import matplotlib.pyplot as plt
        >>> plt.close(res.plot(res.quantities[0]))
        """
        import matplotlib.pyplot as plt
        if ax is None:
            _, ax = plt.subplots(figsize=(5.5, 3.5))
        for method, data in (("first order", self.first_order),
                             ("Monte Carlo", self.monte_carlo)):
            if data is not None:
                x = data[:, self.quantities.index(quantity)]
                ax.hist(x[np.isfinite(x)], bins=25, alpha=0.55, label=method)
        ax.axvline(self.nominal[self.quantities.index(quantity)], color="k", lw=0.8)
        ax.set(xlabel=quantity, ylabel="samples",
               title=", ".join(f"{p} {u.text()}" for p, u in zip(self.parameters,
                                                                  self.uncertain)))
        ax.legend()
        return ax.figure
