"""Platform participation of the modes, and the platform's dynamic amplification in a band.

A mode's *platform share* is the platform's part of its kinetic energy,
1 - (cable energy fraction) (theory.md §6); its *participation in DOF j* splits that share
over the platform DOFs in proportion to M_jj x_j^2 (x the platform shape, M_p the platform
mass matrix; the diagonal split is never negative and sums to the share). Modes are

==========  ========================================  ===================================
category    platform share s                           what it means
==========  ========================================  ===================================
"global"    s >= GLOBAL_SHARE (0.5)                   the platform holds most energy
"mixed"     PLATFORM_SHARE_THRESHOLD <= s < 0.5       a cable mode that moves the platform
"local"     s < PLATFORM_SHARE_THRESHOLD (0.05)       the cables vibrate, the platform not
==========  ========================================  ===================================

The design checks hold every global *and* mixed mode to the frequency margin
(theory.md §12.1 gives the evidence for 0.05).
"""

from dataclasses import dataclass

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.analyses.freqgrid import refined_grid
from dynstiff.analyses.frf import frf
from dynstiff.constants import DOF_NAMES, GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError

__all__ = ["GLOBAL_SHARE", "PLATFORM_SHARE_THRESHOLD", "FRF_AMPLIFICATION_LIMIT",
           "Participation", "platform_participation", "categories", "receptance_amplification"]

#: Largest admissible ratio of a direct platform receptance in the forbidden band to its
#: static value [-] (theory.md §12.1).
FRF_AMPLIFICATION_LIMIT = 10.0


def categories(share, threshold=PLATFORM_SHARE_THRESHOLD):
    """"global", "mixed" or "local" for each platform share [-] (module table)."""
    threshold = positive_scalar("threshold", threshold)
    if not threshold <= GLOBAL_SHARE:
        raise InvalidParameterError(
            f"threshold must be <= {GLOBAL_SHARE} (the global share), got {threshold!r}")
    s = np.asarray(share, dtype=float)
    return tuple("global" if v >= GLOBAL_SHARE else "mixed" if v >= threshold else "local"
                 for v in s.ravel())


@dataclass(frozen=True)
class Participation:
    """Platform participation of each mode.

    Attributes
    ----------
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz].
    platform_share : ndarray, shape (n,)
        Platform kinetic energy / total kinetic energy [-].
    dof_share : ndarray, shape (n, 6)
        The share split over x y z rx ry rz (held DOFs 0) [-]; rows sum to platform_share.
    category : tuple of str
        "global", "mixed" or "local" (module table).
    threshold : float
        Share from which a mode is "mixed" [-].
    """

    freq_hz: np.ndarray
    platform_share: np.ndarray
    dof_share: np.ndarray
    category: tuple
    threshold: float

    def __len__(self):
        return len(self.freq_hz)

    def __repr__(self):
        n = {c: sum(k == c for k in self.category) for c in ("global", "mixed", "local")}
        return (f"Participation({len(self)} modes: {n['global']} global, {n['mixed']} mixed, "
                f"{n['local']} local; mixed from platform share {self.threshold:g})")

    @property
    def checked(self):
        """Boolean mask of the modes held to the frequency margin (global and mixed)."""
        return self.platform_share >= self.threshold

    def dominant_dof(self):
        """Name of the DOF with the largest participation of each mode ("-" if none)."""
        return tuple(DOF_NAMES[int(np.argmax(r))] if r.max() > 0 else "-"
                     for r in self.dof_share)

    def to_frame(self):
        """pandas DataFrame, one row per mode: frequency, share, category, DOF shares."""
        import pandas as pd
        df = pd.DataFrame({"mode": np.arange(1, len(self) + 1), "freq [Hz]": self.freq_hz,
                           "platform share [-]": self.platform_share,
                           "category": list(self.category)})
        for k, name in enumerate(DOF_NAMES):
            df[f"share {name} [-]"] = self.dof_share[:, k]
        return df


def platform_participation(model, modes, threshold=PLATFORM_SHARE_THRESHOLD):
    """Platform share and per-DOF participation of the modes of ``model``.

    Parameters
    ----------
    model : model of any rung (:mod:`dynstiff.models.base`)
        Gives the platform mass matrix on the free DOFs.
    modes : ModalResult
        From :func:`dynstiff.modes` of the same model.
    threshold : float
        Platform share from which a mode is "mixed" [-].

    Returns
    -------
    Participation
    """
    share = np.clip(1.0 - np.asarray(modes.cable_energy_fraction, dtype=float), 0.0, 1.0)
    fi = model.free_index
    diag = np.diag(model.platform_mass)
    x = np.asarray(modes.platform_shapes)[:, fi]
    e = diag[None, :] * x**2
    tot = e.sum(axis=1, keepdims=True)
    dof = np.zeros((len(share), 6))
    with np.errstate(invalid="ignore", divide="ignore"):
        dof[:, fi] = np.where(tot > 0, e / np.where(tot > 0, tot, 1.0), 0.0) * share[:, None]
    return Participation(freq_hz=np.asarray(modes.freq_hz, dtype=float), platform_share=share,
                         dof_share=dof, category=categories(share, threshold),
                         threshold=float(threshold))


def receptance_amplification(model, band_hz, modes_hz=(), n_points=400):
    """Largest ratio of a direct platform receptance in ``band_hz`` to its static value.

    |H_jj(f)| / |H_jj(0)| over the free DOFs j and the frequencies of
    :func:`dynstiff.analyses.freqgrid.refined_grid` (uniform, plus clusters at ``modes_hz``), for
    the (damped) ``model``; an undamped model at a resonance gives inf.

    Parameters
    ----------
    model : model of any rung
    band_hz : (float, float)
        [Hz].
    modes_hz : array_like
        Natural frequencies in or near the band [Hz] (the grid is refined there).
    n_points : int
        Points of the uniform part of the grid.

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
