"""Complex natural frequencies of the damped robot (convention e^{i omega t}, theory.md §5.4).

Seeded by the undamped modes of :func:`dynstiff.analyses.modes.modes`, for a model of any rung whose
``dynamic_stiffness`` accepts complex omega (:mod:`dynstiff.models.base`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import count, positive_scalar
from dynstiff.analyses.modes import modes
from dynstiff.results import DampedModes

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.models.base import PlatformModel
    from dynstiff.results import ModalResult

__all__ = ["damped_modes", "DampedModes"]

_TWO_PI = 2.0 * np.pi


def _nearest_zero_eigenvalue(K: NDArray[np.complex128]) -> tuple[complex, float]:
    """The eigenvalue of K nearest zero and ||K||_2 ((inf, 1) where K is not finite)."""
    if not np.all(np.isfinite(K)):
        return np.inf, 1.0
    mu = np.linalg.eigvals(K)
    return mu[np.argmin(np.abs(mu))], np.linalg.norm(K, 2)


def _shape_owner(K: NDArray[np.complex128], M: NDArray[np.float64],
                 shapes: NDArray[np.float64], candidates: NDArray[np.bool_]) -> int | None:
    """The undamped mode whose platform shape the root's null vector matches without
    ambiguity, or None: the mass-weighted MAC_j = |x_j^T M v|^2 / (x_j^T M x_j v^H M v) of
    the null vector v of K (finite, at the root; its least singular vector), M the platform
    mass, is above 0.9 for that mode and below 0.5 for every other candidate (theory.md
    §5.4). ``shapes`` (n, n_free), real."""
    v = np.linalg.svd(K)[2][-1].conj()
    den = np.einsum("ki,ij,kj->k", shapes, M, shapes) * np.real(v.conj() @ M @ v)
    with np.errstate(all="ignore"):
        mac = np.where(candidates, np.abs(shapes @ M @ v) ** 2 / den, 0.0)
    mac = np.nan_to_num(mac)
    j = int(np.argmax(mac))
    if mac[j] > 0.9 and np.all(np.delete(mac, j) < 0.5):
        return j
    return None


def _perturbation_estimates(model: PlatformModel, und: ModalResult) -> NDArray[np.complex128]:
    """First-order damped roots omega_r + d_omega, d_omega = -x^T (K_d - K_u) x / x^T K_u' x
    (x: undamped platform mode, K_u' = dK_u/domega by central differences)."""
    mu = model.undamped()
    fi = model.free_index
    est = np.full(len(und), np.nan + 0j)
    for k, f in enumerate(und.freq_hz):
        x = und.platform_shapes[k][fi]
        if not np.any(x):
            continue
        w = _TWO_PI * f
        h = 1e-6 * w
        dK = (mu.dynamic_stiffness([w + h])[0] - mu.dynamic_stiffness([w - h])[0]) / (2 * h)
        delta = model.dynamic_stiffness(w)[0] - mu.dynamic_stiffness([w])[0]
        est[k] = w - (x @ delta @ x) / (x @ dK @ x)
    return est


def damped_modes(model: PlatformModel, n_modes: int | None = None, fmax_hz: float | None = None,
                 tol: float = 1e-12, max_iter: int = 80) -> DampedModes:
    """Complex natural frequencies of the damped robot, seeded from the undamped ones.

    Each undamped mode omega_r with platform motion x gives a first-order estimate
    omega_r + d_omega, d_omega = -x^T (K_d - K_u) x / x^T dK_u/domega x (perturbation of the
    real root by the damping part of K). From there a secant iteration in the complex plane
    on det K(omega), deflated by the roots already found, converges to the damped root
    (theory.md §5.4). It is confined to the disc |omega - estimate| <= 0.2 |estimate|: an
    iterate outside it, or where K is not finite, gives the mode up (NaN), and the model's
    floating-point warnings at the complex iterates (an exact rung's hyperbolic functions far
    from the real axis) are silenced. A root is accepted only if the eigenvalue of K nearest
    zero is below 1e-8 ||K||, and given to the undamped mode whose platform shape its null
    vector matches without ambiguity (mass-weighted MAC above 0.9 with it, below 0.5 with
    every other), else to the mode whose estimate it is closer to than to any other mode's
    (clusters of close modes of similar shapes; a copy of its own multiple mode is not a
    rival); never to a mode that has a root already, so heavy damping, where
    first-order estimates pass a neighbour's root, gives NaN rather than that root. Both
    tests compare the modes asked for only: a lone mode (``n_modes=1``) keeps any root its
    secant converges to in its disc, so where damping is heavy ask for its neighbours too.
    A multiple root (the double modes of a symmetric robot) is found again by the searches
    of the other copies of its undamped mode (det K deflated by it still vanishes there),
    and each time goes to a copy that has none: the copy whose search found it, else the
    first; when every search converges, every copy has it. Otherwise, and for purely local
    modes (platform at rest, not zeros of det K), it is NaN with its ``residual`` recorded.

    Parameters
    ----------
    model : model of any rung (:mod:`dynstiff.models.base`); its ``dynamic_stiffness``
        must accept complex omega.
    n_modes, fmax_hz : as :func:`dynstiff.analyses.eigen.eigenfrequencies`
    tol : float
        Relative step at which the secant iteration stops.
    max_iter : int
        Secant iterations per mode.

    Returns
    -------
    DampedModes

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq, platform_damping_ratio=0.02)
    >>> d = ds.damped_modes(m, n_modes=1)
    >>> print(f"{d.freq_hz[0]:.3f} Hz, zeta = {d.damping_ratio[0]:.4f}")
    2.207 Hz, zeta = 0.0200
    """
    tol = positive_scalar("tol", tol)
    max_iter = count("max_iter", max_iter)
    und = modes(model, n_modes=n_modes, fmax_hz=fmax_hz)
    est = _perturbation_estimates(model, und)
    shapes = np.asarray(und.platform_shapes)[:, model.free_index]
    out = np.full(len(und), np.nan + 1j * np.nan)
    resid = np.full(len(und), np.nan)
    found, owners = [], []                   # accepted roots and their modes
    for k in np.flatnonzero(np.isfinite(est)):
        def g(w: complex) -> complex:
            if not np.isfinite(w) or abs(w - est[k]) > 0.2 * abs(est[k]):   # left: give up
                return np.nan
            with np.errstate(all="ignore"):
                K = model.dynamic_stiffness(w)[0]
            if not np.all(np.isfinite(K)):
                return np.nan
            d = np.linalg.det(K)
            for wj in found:
                d = d / (w - wj)
            return d

        w0 = est[k]
        w1 = w0 * (1 + 1e-6 * (1 + 1j))
        g0, g1 = g(w0), g(w1)
        for _ in range(max_iter):
            if g1 == g0 or not np.isfinite(g1) or not np.isfinite(g0):
                break
            w2 = w1 - g1 * (w1 - w0) / (g1 - g0)
            w0, g0, w1 = w1, g1, w2
            g1 = g(w1)
            if abs(w1 - w0) <= tol * abs(w1):
                break
        if not np.isfinite(g1):
            continue
        with np.errstate(all="ignore"):
            K = model.dynamic_stiffness(w1)[0]
        mu, nK = _nearest_zero_eigenvalue(K)
        resid[k] = abs(mu) / nK
        if not resid[k] < 1e-8:
            continue
        same = [j for j, wj in enumerate(found) if abs(w1 - wj) <= 1e-8 * abs(w1)]
        if same:
            # found already, yet a zero of the deflated det K: a multiple root (symmetric
            # robots), the root of every copy of the multiple undamped mode, deflated as
            # many times
            f = und.freq_hz
            j = owners[same[0]]
            copies = [c for c in np.flatnonzero(np.isnan(out) & np.isfinite(est))
                      if abs(f[c] - f[j]) <= 1e-9 * f[j]]
            if copies:
                c = k if k in copies else copies[0]
                out[c], resid[c] = w1, resid[k]
                found.append(w1)
                owners.append(c)
            continue
        # whose root: the mode its shape matches without ambiguity, else the nearest
        # estimate (close modes of similar shapes); a root is never given to a mode that
        # has one, so a wrong attribution leaves NaN, not another mode's root
        owner = _shape_owner(K, model.platform_mass, shapes, np.isfinite(est))
        if owner is None:
            f = und.freq_hz              # the other modes' estimates, not k's own copies
            others = est[np.isfinite(est) & (np.abs(f - f[k]) > 1e-9 * f[k])]
            owner = k if abs(w1 - est[k]) < np.min(np.abs(w1 - others), initial=np.inf) \
                else None
        if owner is not None and np.isnan(out[owner]):
            out[owner], resid[owner] = w1, resid[k]
            found.append(w1)
            owners.append(owner)
    return DampedModes(undamped_freq_hz=und.freq_hz, omega=out, residual=resid)
