"""Mode-by-mode comparison of two modal results (e.g. closed-form and lumped-mass models):
global modes paired by mass-weighted MAC of the platform shapes, the others by frequency."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import real_array
from dynstiff.errors import InvalidParameterError
from dynstiff.results import ModalResult

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.results import LumpedModalResult

__all__ = ["compare_modes"]


def compare_modes(closed_form_modes: ModalResult,
                  lumped_modes: NDArray[np.float64] | LumpedModalResult,
                  mass_matrix: NDArray[np.float64] | None = None) -> Any:
    """Mode-by-mode table of two modal results, matched by shape, not by index.

    Global modes (kind "global" in both results) are paired by the MAC of their platform
    shapes, MAC = (a^T W b)^2 / ((a^T W a)(b^T W b)), with an optimal one-to-one assignment
    (Hungarian algorithm, largest total MAC). The remaining modes (local cable modes, and
    global modes left unpaired) are paired by frequency, minimising the sum of ln^2(f_b/f_a)
    (squares: the sum of |ln| ties between crossed and uncrossed pairs of close modes, and
    the order-preserving pairing of a family of local modes is then left to chance);
    modes left over in either result get a row with the other side empty.

    Parameters
    ----------
    closed_form_modes : ModalResult
        E.g. ``modes(FrequencyModel(eq), n)``.
    lumped_modes : ModalResult
        E.g. ``modes(build_model(eq, "lumped"), n)``.
    mass_matrix : array_like, shape (6, 6), optional
        Weight W of the MAC, e.g. the platform mass matrix ``FrequencyModel.M_p``
        (default identity, which mixes metres and radians): symmetric positive
        semi-definite, so that every MAC lies in [0, 1]: symmetric to within 1e-12 of its
        largest entry, no eigenvalue below -1e-12 of it (else InvalidParameterError, naming
        the eigenvalues to 4 significant digits).

    Returns
    -------
    pandas.DataFrame
        One row per pair, sorted by closed-form mode: "closed-form mode", "lumped mode"
        (1-based), "kind (closed form)", "kind (lumped)", "closed-form freq [Hz]",
        "lumped freq [Hz]", "relative difference [-]" (f_lumped / f_closed - 1), "MAC [-]"
        (NaN where a platform shape is zero), "matched by" ("MAC" or "frequency"), and
        "match quality [-]": the MAC for MAC pairs; for frequency pairs
        1 - ln^2(f_b/f_a) / ln^2(f_b'/f_a), f_b' the nearest other unpaired lumped frequency
        (1: unambiguous, 0: another mode is as close). The mode numbers are pandas
        Int64, <NA> on the empty side; a 0 Hz closed-form mode has the relative difference
        inf (NaN against a 0 Hz lumped mode), without a warning.
    """
    import pandas as pd
    from scipy.optimize import linear_sum_assignment

    a, b = closed_form_modes, lumped_modes
    for name, m in (("closed_form_modes", a), ("lumped_modes", b)):
        if not isinstance(m, ModalResult):
            raise InvalidParameterError(
                f"{name} must be a ModalResult, got {type(m).__name__}")
    W = np.eye(6) if mass_matrix is None else real_array("mass_matrix", mass_matrix,
                                                        "a finite 6x6 matrix")
    if W.shape != (6, 6) or not np.all(np.isfinite(W)):
        raise InvalidParameterError(
            f"mass_matrix must be a finite 6x6 matrix, got shape {W.shape}")
    scale = np.abs(W).max()
    if not np.allclose(W, W.T, rtol=0.0, atol=1e-12 * scale) or \
            np.linalg.eigvalsh(0.5 * (W + W.T)).min() < -1e-12 * scale:
        raise InvalidParameterError(
            f"mass_matrix must be symmetric positive semi-definite (a mass matrix: the MAC's "
            f"weight), got eigenvalues "
            f"{[float(f'{v:.4g}') for v in np.linalg.eigvals(W).real]}")
    Xa, Xb = a.platform_shapes, b.platform_shapes
    na = np.einsum("ij,jk,ik->i", Xa, W, Xa)
    nb = np.einsum("ij,jk,ik->i", Xb, W, Xb)
    with np.errstate(divide="ignore", invalid="ignore"):
        mac = (Xa @ W @ Xb.T) ** 2 / np.outer(na, nb)
    mac[~np.isfinite(mac)] = np.nan
    ga = np.flatnonzero((np.array(a.kind) == "global") & (na > 0))
    gb = np.flatnonzero((np.array(b.kind) == "global") & (nb > 0))
    pairs = []                                      # (i, j, how, quality)
    if ga.size and gb.size:
        ri, ci = linear_sum_assignment(np.nan_to_num(mac[np.ix_(ga, gb)]), maximize=True)
        pairs += [(ga[p], gb[q], "MAC", mac[ga[p], gb[q]]) for p, q in zip(ri, ci)]
    rest_a = np.setdiff1d(np.arange(len(a)), [p[0] for p in pairs])
    rest_b = np.setdiff1d(np.arange(len(b)), [p[1] for p in pairs])
    if rest_a.size and rest_b.size:
        with np.errstate(divide="ignore", invalid="ignore"):
            cost = np.log(b.freq_hz[rest_b][None, :] / a.freq_hz[rest_a][:, None]) ** 2
        cost = np.nan_to_num(cost, nan=1e300, posinf=1e300)
        ri, ci = linear_sum_assignment(cost)
        for p, q in zip(ri, ci):
            others = np.delete(cost[p], q)
            if others.size == 0:
                quality = 1.0
            elif others.min() > 0:
                quality = float(np.clip(1.0 - cost[p, q] / others.min(), 0.0, 1.0))
            else:
                quality = 0.0
            pairs.append((rest_a[p], rest_b[q], "frequency", quality))
    done_a = {p[0] for p in pairs}
    done_b = {p[1] for p in pairs}
    pairs += [(i, None, None, np.nan) for i in range(len(a)) if i not in done_a]
    pairs += [(None, j, None, np.nan) for j in range(len(b)) if j not in done_b]
    pairs.sort(key=lambda p: (p[0] is None, p[0] if p[0] is not None else p[1]))
    fa = np.array([a.freq_hz[i] if i is not None else np.nan for i, *_ in pairs])
    fb = np.array([b.freq_hz[j] if j is not None else np.nan for _, j, *_ in pairs])
    with np.errstate(divide="ignore", invalid="ignore"):     # a 0 Hz mode: inf or NaN
        relative = fb / fa - 1.0
    return pd.DataFrame({
        "closed-form mode": pd.array([i + 1 if i is not None else None
                                      for i, *_ in pairs], dtype="Int64"),
        "lumped mode": pd.array([j + 1 if j is not None else None
                                 for _, j, *_ in pairs], dtype="Int64"),
        "kind (closed form)": [a.kind[i] if i is not None else None for i, *_ in pairs],
        "kind (lumped)": [b.kind[j] if j is not None else None for _, j, *_ in pairs],
        "closed-form freq [Hz]": fa,
        "lumped freq [Hz]": fb,
        "relative difference [-]": relative,
        "MAC [-]": [mac[i, j] if i is not None and j is not None else np.nan
                    for i, j, *_ in pairs],
        "matched by": [p[2] for p in pairs],
        "match quality [-]": [p[3] for p in pairs],
    })
