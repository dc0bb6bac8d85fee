"""Platform participation of the modes, and the platform's dynamic amplification in a band.

A mode's *platform share* s is the platform's part of its kinetic energy (theory.md §6);
its *participation* in free DOF j is its effective-mass fraction
p_j = (M_p x)_j^2 s / (M_p)_jj, x the shape at unit platform kinetic energy (theory.md
§12.1): over all the modes of a robot each DOF's participations sum to 1, so they say where
the platform's mass went even when no mode is platform-dominated (heavy cables). Modes are
labelled by share alone (:func:`dynstiff.results.mode_kinds`):

==========  ========================================  ===================================
kind        platform share s                           what it means
==========  ========================================  ===================================
"global"    s >= GLOBAL_SHARE (0.5)                   the platform holds most energy
"mixed"     PLATFORM_SHARE_THRESHOLD <= s < 0.5       a cable mode that moves the platform
"local"     s < PLATFORM_SHARE_THRESHOLD (0.05)       the cables vibrate, the platform not
==========  ========================================  ===================================

:func:`modal_data` gives the modes every verdict uses: :func:`dynstiff.modes` for every
rung, or for the undamped closed form the same frequencies with the shares from the
derivative of K(omega) (:func:`platform_shares`, docs/theory.md §13.3), which is faster.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.analyses.eigen import eigenfrequencies
from dynstiff.analyses.eigen_matrix import massless_modes, massless_pairing
from dynstiff.analyses.freqgrid import refined_grid
from dynstiff.analyses.frf import frf
from dynstiff.analyses.modes import modes as modal
from dynstiff.constants import DOF_NAMES, GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD
from dynstiff.models.dsm_compiled import stiffness_and_count
from dynstiff.results import ModalResult

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.base import PlatformModel
    from dynstiff.models.dsm import FrequencyModel

__all__ = ["GLOBAL_SHARE", "PLATFORM_SHARE_THRESHOLD", "FRF_AMPLIFICATION_LIMIT",
           "modal_data", "platform_shares", "receptance_amplification"]

#: Largest admissible ratio of a direct platform receptance in the forbidden band to its
#: static value [-] (theory.md §12.1).
FRF_AMPLIFICATION_LIMIT = 10.0

_FD_STEP = 1e-6        # relative frequency step of the derivative of K(omega) in omega^2


def _quadratic(x: NDArray[np.float64], A: NDArray[np.float64]) -> NDArray[np.float64]:
    """x_k^T A_k x_k for x (n, m) and A (n, m, m), as ``x[k] @ A[k] @ x[k]`` for each k
    (the same products in the same order, so the same rounding, as one mode at a time: the
    form is close to cancellation, and the order of its sums moves it by 1e-9), in one
    stacked matmul."""
    return (x[:, None, :] @ A @ x[:, :, None])[:, 0, 0]


def platform_shares(
        model: FrequencyModel, freq_hz: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Platform share of the kinetic energy [-] and platform shape of the modes of an
    undamped closed-form model at ``freq_hz``, without the cable fields.

    For an exact dynamic stiffness the total modal mass is -x^T dK/d(omega^2) x
    (docs/theory.md §13.3), so the share is x^T M_p x / (-x^T dK/d(omega^2) x), x the null
    vector of K(omega_r). The derivative is a central difference in omega^2 with steps
    1e-6 and 5e-7 (relative), Richardson-extrapolated: all modes in one call of
    ``dynamic_stiffness``. A mode with a cable pole within the steps takes the closed-form
    cable energies instead (``cable_kinetic_energies``, as :func:`dynstiff.modes`); a mode
    on a cable pole with the platform at rest has share 0. The modes' null vectors come
    from one batched ``eigh`` (docs/theory.md §13.6).

    Parameters
    ----------
    model : FrequencyModel (closed-form rung, undamped)
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz].

    Returns
    -------
    share : ndarray, shape (n,)
        [-]
    shapes : ndarray, shape (n, 6)
        Platform shapes at unit platform kinetic energy (held DOFs and local modes 0).
    """
    w = 2.0 * np.pi * np.asarray(freq_hz, dtype=float)
    n = w.size
    out, shapes = np.zeros(n), np.zeros((n, 6))
    if n == 0:
        return out, shapes
    h = _FD_STEP
    steps = np.array([1.0, 1 + h, 1 - h, 1 + h / 2, 1 - h / 2, 1 + 1e-9, 1 - 1e-9])
    # K at the steps 1 .. 1 -+ h/2; cable counts at 1 +- h (a pole within the steps) and
    # 1 +- 1e-9 (a pole at the root)
    K_all, J0_all = stiffness_and_count(model, np.outer(steps, w).ravel())
    K_all, J0_all = K_all.reshape(7, n, *K_all.shape[1:]), J0_all.reshape(7, n)
    K, Ks, J0 = K_all[0], K_all[1:5], J0_all[[1, 2, 5, 6]]
    Mp = model.platform_mass
    fin = np.flatnonzero(np.all(np.isfinite(K), axis=(1, 2)))
    if not fin.size:
        return out, shapes
    ev, V = np.linalg.eigh(K[fin])
    least = np.abs(ev).min(axis=1)
    pole = J0[2, fin] > J0[3, fin]             # a cable pole at the root
    if np.any(pole):
        scale = np.abs(np.linalg.eigvalsh(model.massless_stiffness())).max()
        keep = ~pole | (least <= 1e-6 * scale)
        fin, ev, V = fin[keep], ev[keep], V[keep]  # else local mode, platform at rest
    x = V[np.arange(len(V)), :, np.argmin(np.abs(ev), axis=1)].reshape(-1, Mp.shape[0])
    x = x / np.sqrt(np.einsum("ki,ij,kj->k", x, Mp, x))[:, None]    # unit platform energy
    wk = w[fin]
    d1 = (Ks[0, fin] - Ks[1, fin]) / (wk**2 * ((1 + h) ** 2 - (1 - h) ** 2))[:, None, None]
    d2 = (Ks[2, fin] - Ks[3, fin]) / (wk**2 * ((1 + h / 2) ** 2 - (1 - h / 2) ** 2))[:, None,
                                                                                    None]
    out[fin] = 1.0 / -_quadratic(x, (4.0 * d2 - d1) / 3.0)
    shapes[np.ix_(fin, model.free_index)] = x
    for j in np.flatnonzero(J0[0, fin] != J0[1, fin]):     # a cable pole within the steps
        out[fin[j]] = 1.0 / (1.0 + model.cable_kinetic_energies(w[fin[j]], shapes[fin[j]]).sum())
    return out, shapes


def modal_data(model: PlatformModel, fmax_hz: float, max_modes: int = 20000) -> ModalResult:
    """Every mode of ``model`` below ``fmax_hz`` [Hz], with shapes, shares and participation:
    the modes every verdict is taken from (a design check, a map, a report).

    :func:`dynstiff.modes` for every rung but the undamped closed form, whose shares come
    from :func:`platform_shares` (faster; the same frequencies, shares within 1e-8,
    ``cable_energy`` NaN). Coincident roots of the closed form (closer than 1e-8 of the
    higher one, relative) go through :func:`dynstiff.modes` too (their shapes need the null
    space of K).

    Returns
    -------
    ModalResult
    """
    m = model.undamped()
    if m.rung != "dsm" or type(m).__name__ != "FrequencyModel":
        return modal(m, fmax_hz=fmax_hz, max_modes=max_modes)
    f = eigenfrequencies(m, fmax_hz=fmax_hz, max_modes=max_modes)
    if f.size > 1 and np.any(np.diff(f) <= 1e-8 * f[1:]):
        return modal(m, fmax_hz=fmax_hz, max_modes=max_modes)
    share, shapes = platform_shares(m, f)
    Mp = np.zeros((6, 6))
    Mp[np.ix_(m.free_index, m.free_index)] = m.platform_mass
    res = ModalResult(freq_hz=f, platform_shapes=shapes, cable_energy_fraction=1.0 - share,
                      cable_energy=np.full((f.size, m.robot.n_cables), np.nan),
                      platform_mass=Mp)
    return replace(res, massless_freq_hz=massless_pairing(res, m.massless_stiffness(),
                                                          m.platform_mass, m.free_index,
                                                          massless_modes(m)))


def receptance_amplification(model: PlatformModel, band_hz: tuple[float, float],
                             modes_hz: ArrayLike = (),
                             n_points: int = 100) -> tuple[float, float, str]:
    """Largest ratio of a direct platform receptance in ``band_hz`` to its static value.

    |H_jj(f)| / |H_jj(0)| over the free DOFs j and the frequencies of
    :func:`dynstiff.analyses.freqgrid.refined_grid` (uniform, plus clusters at
    ``modes_hz``), for the (damped) ``model``; an undamped model at a resonance gives inf.

    Parameters
    ----------
    model : model of any rung
    band_hz : (float, float)
        [Hz].
    modes_hz : array_like
        Natural frequencies in or near the band [Hz] (the grid is refined there).
    n_points : int
        Points of the uniform part of the grid. The peaks are read at the points clustered
        at the modes, so the uniform count does not set the result: on CoGiRo, in four
        bands from 0-1.5 to 0.5-10 Hz, 50, 100 and 400 points give the same ratio, within
        2e-4 of 4000 points' (theory.md §12.3).

    Returns
    -------
    ratio : float
        [-]
    freq_hz : float
        Where the ratio is largest [Hz].
    dof : str
        The DOF it occurs in.
    """
    import warnings

    from dynstiff.errors import PoleWarning
    f = refined_grid(band_hz, n_points, modes_hz)
    names = [DOF_NAMES[k] for k in model.free_index]
    loads = ["f" + n if len(n) == 1 else "m" + n[1] for n in names]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PoleWarning)
        H = frf(model, 2 * np.pi * np.concatenate([[0.0], f]), inputs=loads,
                outputs=names).H
    d = np.abs(np.diagonal(H, axis1=1, axis2=2))
    with np.errstate(invalid="ignore", divide="ignore"):
        r = d[1:] / d[0][None, :]
    r = np.where(np.isnan(r), np.inf, r)
    k, j = np.unravel_index(int(np.argmax(r)), r.shape)
    return float(r[k, j]), float(f[k]), names[j]
