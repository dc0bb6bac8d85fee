"""Clamped-clamped natural frequencies of one cable, labelled by family: the closed form's
(theory.md §2.2) and the exact cable's about its true catenary (theory.md §11). They are the
poles of the cable's dynamic stiffness of the same model.
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import count
from dynstiff.cable.chord import chord_parameters
from dynstiff.cable.dsm import checked_cable_model, lowest_string_omega
from dynstiff.cable.exact import ExactCable
from dynstiff.cable.guard import DEFAULT_GUARD_RTOL, guard_cable
from dynstiff.cable.psi import closed_form_spectrum
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray

    from dynstiff.cable.catenary import CatenaryState

__all__ = ["CableModes", "cable_natural_frequencies"]


@dataclass(frozen=True)
class CableModes:
    """Clamped-clamped natural frequencies of one cable.

    Attributes
    ----------
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz], ascending.
    Omega : ndarray, shape (n,)
        Nondimensional frequencies omega L sqrt(m/T) [-].
    family : tuple of str
        "out-of-plane", "in-plane antisymmetric" or "in-plane symmetric" (closed form);
        "out-of-plane", "in-plane" or "axial" (exact model).
    order : ndarray of int, shape (n,)
        Index of the mode within its family, from 1.

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> m = ds.cable_natural_frequencies(state, 3)
    >>> [f"{f:.2f}" for f in m.freq_hz], m.family[0]
    (['6.84', '6.94', '13.67'], 'out-of-plane')
    """

    freq_hz: np.ndarray
    Omega: np.ndarray
    family: tuple
    order: np.ndarray

    @property
    def labels(self) -> tuple[str, ...]:
        """Labels such as "in-plane symmetric 1".

        Examples
        --------
        >>> import dynstiff as ds
        >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
        >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
        >>> ds.cable_natural_frequencies(state, 2).labels
        ('out-of-plane 1', 'in-plane symmetric 1')
        """
        return tuple(f"{f} {k}" for f, k in zip(self.family, self.order))

    def __len__(self) -> int:
        return len(self.freq_hz)

    def __repr__(self) -> str:
        f = self.freq_hz
        span = f"{f.min():.4g}-{f.max():.4g} Hz" if len(f) else "none"
        return f"CableModes({len(self)} modes {span}: {', '.join(self.labels[:3])}, ...)"

    def plot(self, ax: Axes | None = None) -> Figure:
        """The frequencies by family: :func:`dynstiff.plot.plot_cable_modes`. Returns the
        matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
        >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
        >>> fig = ds.cable_natural_frequencies(state, 3).plot()
        >>> type(fig).__name__
        'Figure'
        >>> import matplotlib.pyplot as plt; plt.close(fig)
        """
        from dynstiff.plot import plot_cable_modes
        return plot_cable_modes(self, ax=ax)

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame with columns freq [Hz], Omega [-], family, order.

        Examples
        --------
        >>> import dynstiff as ds
        >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
        >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
        >>> df = ds.cable_natural_frequencies(state, 3).to_frame()
        >>> list(df.columns), len(df)
        (['freq [Hz]', 'Omega [-]', 'family', 'order'], 3)
        """
        import pandas as pd
        return pd.DataFrame({"freq [Hz]": self.freq_hz, "Omega [-]": self.Omega,
                             "family": list(self.family), "order": self.order})


def _exact_modes(state: CatenaryState, n: int) -> tuple[NDArray[np.float64], tuple[Any, ...]]:
    """First n clamped modes of the exact cable (theory.md §11), band grown until it holds
    them; returns (omega_j [rad/s], family)."""
    w = 1.2 * (n + 1) * lowest_string_omega(state)
    for _ in range(60):
        cab = ExactCable(state, w)
        lam = cab.eigenvalues
        if np.count_nonzero(lam <= w * w) >= n:
            return np.sqrt(lam[:n]), cab.family[:n]
        w *= 1.5
    raise InvalidParameterError(f"n_modes = {n} is more than the exact cable resolves")


def cable_natural_frequencies(state: CatenaryState, n_modes: int,
                              tension: str = "mean", model: str = "closed-form",
                              guard_rtol: float | None = DEFAULT_GUARD_RTOL,
                              max_modes: int = 20000) -> CableModes:
    """First ``n_modes`` clamped-clamped natural frequencies of the cable, labelled.

    "closed-form": out-of-plane Omega = n pi, in-plane antisymmetric Omega = 2 n pi, in-plane
    symmetric the Irvine-Caughey roots (theory.md §2.2, inclined-cable approximation).
    "exact": the clamped spectrum about the true catenary (theory.md §11), families
    "out-of-plane", "in-plane" and "axial" (in-plane, most of its strain energy axial). These
    are the poles of :func:`cable_dynamic_stiffness` of the same ``model``.

    Parameters
    ----------
    state : CatenaryState
    n_modes : int
        Number of modes, >= 1.
    tension : {"mean", "chord"}
        Tension of the closed form; Omega is always omega L sqrt(m / T) with this T.
    model : {"closed-form", "exact"}
    guard_rtol : float or None
        As :func:`cable_dynamic_stiffness` (closed form only).
    max_modes : int
        Largest ``n_modes`` accepted; a larger one is refused before any work (the arrays of
        a count far beyond any physical use would exhaust the memory).

    Returns
    -------
    CableModes

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> m = ds.cable_natural_frequencies(state, 3)
    >>> print(f"{m.freq_hz[0]:.3f} Hz", m.labels[0])     # sqrt(T / m) / 2L, T = 299.1 N
    6.836 Hz out-of-plane 1
    """
    if isinstance(n_modes, bool) or not isinstance(n_modes, Integral) or n_modes < 1:
        raise InvalidParameterError(f"n_modes must be an integer >= 1, got {n_modes!r}")
    if n_modes > count("max_modes", max_modes):
        raise InvalidParameterError(f"n_modes = {n_modes} is more than max_modes = {max_modes}; "
                                    "raise max_modes to ask for more")
    n = int(n_modes)
    p = chord_parameters(state, tension)
    to_hz = np.sqrt(p.T / p.m) / (2 * np.pi * p.L)
    if checked_cable_model(model) == "exact":
        w, fam = _exact_modes(state, n)
        order = np.zeros(n, dtype=int)
        for name in set(fam):
            sel = np.array([f == name for f in fam])
            order[sel] = np.arange(1, sel.sum() + 1)
        f = w / (2 * np.pi)
        return CableModes(freq_hz=f, Omega=f / to_hz, family=tuple(str(x) for x in fam),
                          order=order)
    Om, family, order = closed_form_spectrum(p.lambda_sq, n)
    if guard_rtol is not None:
        guard_cable(state, Om[-1] * np.sqrt(p.T / p.m) / p.L, tension, guard_rtol)
    return CableModes(freq_hz=Om * to_hz, Omega=Om, family=family, order=order)
