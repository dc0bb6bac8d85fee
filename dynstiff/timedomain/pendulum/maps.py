"""Stability maps over excitation frequency, amplitude, preload and cable mass."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import ConvergenceError, InvalidParameterError
from dynstiff.timedomain.pendulum.floquet import FloquetResult, floquet

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray


def stability_map(model, freqs_hz, amplitudes, preloads=None, cable_masses=None, phase: float = 0.0,
                  **floquet_options: Any):
    """Floquet stability over a grid of excitation frequency, amplitude, preload and cable
    mass.

    Parameters
    ----------
    model : CablePendulum
        The base model; ``preloads`` and ``cable_masses`` replace its values.
    freqs_hz : array_like, shape (n_f,)
        Excitation frequencies [Hz].
    amplitudes : float or array_like, shape (n_x,)
        Excitation amplitudes x0 [m].
    preloads : array_like, optional
        Preloads P [N] (default: the model's).
    cable_masses : array_like, optional
        Mass of one cable [kg] (default: the model's; used by point-mass models only).
    phase : float
        Phase lag of end C [rad].
    **floquet_options
        Passed to :func:`floquet` (steps, tolerances).

    Returns
    -------
    pandas.DataFrame
        One row per grid point: "f [Hz]", "x0 [m]", "preload [N]", "cable mass [kg]",
        "phase [deg]", "n masses", "max |multiplier| [-]", "pendulum |multiplier| [-]",
        "stable", "periodic orbit", "orbit residual [-]", "steps per period",
        "natural freq [Hz]" (massless, at rest), "wall time [s]" of its group and "error"
        (the message where the integration failed: that point is reported unstable with
        infinite multipliers).
    """
    import time

    import pandas as pd
    f = np.atleast_1d(np.asarray(freqs_hz, dtype=float))
    x0 = np.atleast_1d(np.asarray(amplitudes, dtype=float))
    if f.ndim != 1 or f.size == 0 or x0.ndim != 1 or x0.size == 0:
        raise InvalidParameterError(
            f"freqs_hz and amplitudes must be non-empty 1-D, got shapes {f.shape}, {x0.shape}")
    pre = np.atleast_1d(np.asarray([model.preload] if preloads is None else preloads,
                                   dtype=float))
    mc = np.atleast_1d(np.asarray([model.cable_mass] if cable_masses is None
                                  else cable_masses, dtype=float))
    F, X = (v.ravel() for v in np.meshgrid(f, x0, indexing="ij"))
    frames = []
    for p in pre:
        for m_c in mc:
            m = replace(model, preload=float(p), cable_mass=float(m_c))
            start = time.perf_counter()
            df = _floquet_frame(m, F, X, phase, floquet_options)
            df.insert(2, "preload [N]", m.preload)
            df.insert(3, "cable mass [kg]", m.cable_mass)
            df.insert(5, "n masses", m.n_masses)
            df["natural freq [Hz]"] = m.natural_frequency_hz()
            df["wall time [s]"] = time.perf_counter() - start
            frames.append(df)
    return pd.concat(frames, ignore_index=True)


def _floquet_frame(model, F, X, phase, options):
    """`floquet` as a table; where the batch fails, case by case, and a case whose
    integration fails is reported unstable with infinite multipliers and its error."""
    try:
        df = floquet(model, F, X, phase, **options).to_frame()
        df["error"] = ""
        return df
    except ConvergenceError:
        if F.size == 1:
            raise
    frames = []
    for f, x in zip(F, X):
        try:
            frames.append(_floquet_frame(model, np.array([f]), np.array([x]), phase, options))
        except ConvergenceError as exc:
            frames.append(FloquetResult(
                freq_hz=np.array([f]), amplitude=np.array([x]),
                phase=np.atleast_1d(float(phase)), multipliers=np.full((1, 1), np.inf + 0j),
                pendulum_multiplier=np.full(1, np.inf + 0j), pendulum_share=np.zeros(1),
                periodic=np.zeros(1, dtype=bool), orbit_residual=np.full(1, np.inf),
                steps_per_period=np.zeros(1, dtype=int), tol=0.0).to_frame().assign(
                    error=str(exc)))
    import pandas as pd
    return pd.concat(frames, ignore_index=True)


def unstable_intervals(freqs_hz: NDArray[np.float64],
                       stable: NDArray[np.bool_]) -> list[tuple[float, float]]:
    """Runs of unstable grid frequencies as (first, last) pairs [Hz].

    Parameters
    ----------
    freqs_hz : array_like, shape (n,)
        Ascending frequencies [Hz].
    stable : array_like of bool, shape (n,)

    Returns
    -------
    list of (float, float)
    """
    f = np.asarray(freqs_hz, dtype=float)
    st = np.asarray(stable, dtype=bool)
    if f.shape != st.shape or f.ndim != 1:
        raise InvalidParameterError(
            f"freqs_hz and stable must be 1-D of one shape, got {f.shape} and {st.shape}")
    if np.any(np.diff(f) <= 0):
        raise InvalidParameterError("freqs_hz must be strictly ascending")
    out, start = [], None
    for k in range(f.size):
        if not st[k] and start is None:
            start = k
        if start is not None and (st[k] or k == f.size - 1):
            end = k if not st[k] else k - 1
            out.append((float(f[start]), float(f[end])))
            start = None
    return out

