"""Complete eigenfrequencies of the robot by Wittrick-Williams counting, and its modes.

K(omega) is transcendental with poles at every cable's clamped-clamped frequencies, so a sign
scan of det K finds poles as well as roots and misses close pairs. The Wittrick-Williams count
(Wittrick & Williams 1971; theory.md §5)

    J(omega) = J0(omega) + s{K(omega)}

(J0: clamped-cable frequencies below omega, s: negative eigenvalues of K) is the exact number
of natural frequencies below omega. The r-th frequency is found by bisection on J, all roots
at once (one batched evaluation of K per step), to a relative bracket width of ``rtol``; this
never misses a root, handles coincident roots, and finds purely local cable modes, which are
not zeros of det K.
"""

from dataclasses import dataclass

import numpy as np

from .cable_dsm import _local_entries
from .errors import ConvergenceError, InvalidParameterError
from .platform import DOF_NAMES

__all__ = ["eigenfrequencies", "modes", "ModalResult"]

_TWO_PI = 2.0 * np.pi


def _undamped(model):
    """The model itself, or an undamped copy (W-W needs a real symmetric K)."""
    if not model.damped:
        return model
    import copy
    from dataclasses import replace
    m = copy.copy(model)
    m.params = [replace(p, c=0.0, EA=float(np.real(p.EA))) for p in model.params]
    m.damped = False
    return m


def eigenfrequencies(model, n_modes=None, fmax_hz=None, rtol=1e-12):
    """Natural frequencies [Hz] of the undamped robot, ascending, none missed.

    Parameters
    ----------
    model : FrequencyModel
    n_modes : int, optional
        Number of lowest frequencies wanted.
    fmax_hz : float, optional
        All frequencies below this [Hz]. Give ``n_modes`` or ``fmax_hz`` (or both: the first
        ``n_modes`` below ``fmax_hz``).
    rtol : float
        Relative width of the final bisection bracket (default 1e-12).

    Returns
    -------
    ndarray, shape (n,) [Hz]
        With damped cables, the frequencies of the undamped system.
    """
    if n_modes is None and fmax_hz is None:
        raise InvalidParameterError("give n_modes or fmax_hz")
    m = _undamped(model)
    if fmax_hz is not None:
        if not np.isfinite(fmax_hz) or fmax_hz <= 0:
            raise InvalidParameterError(f"fmax_hz must be finite and > 0, got {fmax_hz!r}")
        w_hi = _TWO_PI * float(fmax_hz)
        N = int(m.mode_count(w_hi)[0])
        if n_modes is not None:
            N = min(N, int(n_modes))
    else:
        N = int(n_modes)
        if N < 1 or N != n_modes:
            raise InvalidParameterError(f"n_modes must be an integer >= 1, got {n_modes!r}")
        w_hi = _TWO_PI
        while m.mode_count(w_hi)[0] < N:
            w_hi *= 2.0
            if w_hi > 1e8:
                raise ConvergenceError(f"fewer than {N} modes below {w_hi:.3g} rad/s")
    if N == 0:
        return np.zeros(0)
    r = np.arange(1, N + 1)
    lo, hi = np.zeros(N), np.full(N, w_hi)
    while np.max(hi - lo) > rtol * np.min(hi):
        mid = 0.5 * (lo + hi)
        # evaluate each distinct midpoint once
        u, inv = np.unique(mid, return_inverse=True)
        J = m.mode_count(u)[inv]
        above = J >= r
        hi = np.where(above, mid, hi)
        lo = np.where(above, lo, mid)
    return 0.5 * (lo + hi) / _TWO_PI


# ------------------------------------------------------------------------- mode shapes
@dataclass(frozen=True)
class ModalResult:
    """Modes of the robot.

    Attributes
    ----------
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz].
    platform_shapes : ndarray, shape (n, 6)
        Platform motion (dp [m], dtheta [rad]) about P, held DOFs 0, normalised to unit
        platform kinetic energy x^T M_p x = 1 (zero for a purely local mode).
    cable_energy_fraction : ndarray, shape (n,)
        Kinetic energy in the cables / total kinetic energy [-].
    cable_energy : ndarray, shape (n, n_cables)
        Kinetic-energy share of each cable [-] (sums to cable_energy_fraction).
    kind : tuple of str
        "global" (platform holds most kinetic energy) or "local" (cables do).
    massless_freq_hz : ndarray, shape (n,)
        Frequency of the matching mode of the massless-cable model (NaN for local modes).
    """

    freq_hz: np.ndarray
    platform_shapes: np.ndarray
    cable_energy_fraction: np.ndarray
    cable_energy: np.ndarray
    kind: tuple
    massless_freq_hz: np.ndarray

    @property
    def shift_from_massless(self):
        """Relative shift of each global frequency from the massless-cable model [-]."""
        return self.freq_hz / self.massless_freq_hz - 1.0

    def __len__(self):
        return len(self.freq_hz)

    def to_frame(self):
        """pandas DataFrame, one row per mode, units in the column names."""
        import pandas as pd
        df = pd.DataFrame({
            "mode": np.arange(1, len(self) + 1),
            "freq [Hz]": self.freq_hz,
            "kind": list(self.kind),
            "cable energy fraction [-]": self.cable_energy_fraction,
            "massless freq [Hz]": self.massless_freq_hz,
            "shift from massless [-]": self.shift_from_massless,
        })
        for k, name in enumerate(DOF_NAMES):
            unit = "m" if k < 3 else "rad"
            df[f"{name} [{unit}]"] = self.platform_shapes[:, k]
        return df


def _cable_kinetic(p, omega, d_local, chordwise_inertia, n_gauss=64):
    """int m (|v|^2 + |w|^2) dx (+ m L/3 |u_B|^2) for end-B motion d_local (u, v, w) with A
    clamped, from the closed-form fields (theory.md §5.3) [kg m^2 per unit amplitude^2]."""
    uB, vB, wB = d_local
    k_uu, k_uv, *_ = _local_entries(p, np.array([omega]), False)
    h = k_uu[0] * uB - k_uv[0] * vB                   # dynamic tension [N]
    beta = 2.0 * p.psi(np.array([omega]))[0] / p.L
    Om = beta * p.L
    x, wts = np.polynomial.legendre.leggauss(n_gauss)
    x = 0.5 * p.L * (x + 1.0)
    wts = 0.5 * p.L * wts
    vp = h * p.q / (p.T * beta) ** 2 if beta != 0 else 0.0
    C2 = (vB - vp + vp * np.cos(Om)) / np.sin(Om)
    v = -vp * np.cos(beta * x) + C2 * np.sin(beta * x) + vp
    w = wB * np.sin(beta * x) / np.sin(Om)
    E = p.m * np.sum(wts * (np.abs(v) ** 2 + np.abs(w) ** 2))
    if chordwise_inertia:
        E += p.m * p.L / 3.0 * abs(uB) ** 2
    return float(E)


def modes(model, n_modes=None, fmax_hz=None):
    """Natural frequencies with platform shapes, energy fractions and global/local labels.

    The platform shape at omega_r is the eigenvector of K(omega_r) with the smallest
    |eigenvalue|; at a root that sits on a cable pole with the platform at rest (a purely local
    mode, counted by J0), the platform shape is zero and the mode is all cable. Kinetic
    energies: platform x^T M_p x, cable m int (|v|^2 + |w|^2) dx from the closed-form fields
    (theory.md §6). Global modes are matched to the massless-cable model by mass-weighted MAC.

    Returns
    -------
    ModalResult
    """
    m = _undamped(model)
    f = eigenfrequencies(m, n_modes=n_modes, fmax_hz=fmax_hz)
    w = _TWO_PI * f
    fi = m._fi
    nf = m.n_free
    Mf = m._M
    # massless model: generalized eigenproblem
    from scipy.linalg import eigh
    lam0, X0 = eigh(m.massless_stiffness(), Mf)
    f0 = np.sqrt(np.maximum(lam0, 0.0)) / _TWO_PI
    shapes = np.zeros((len(f), 6))
    E_cab = np.zeros((len(f), len(m.params)))
    frac = np.zeros(len(f))
    kinds, f_massless = [], np.full(len(f), np.nan)
    K = m.dynamic_stiffness(w) if len(w) else np.zeros((0, nf, nf))
    J0_lo = m.cable_mode_count(w * (1 - 1e-9)) if len(w) else []
    J0_hi = m.cable_mode_count(w * (1 + 1e-9)) if len(w) else []
    for k in range(len(f)):
        Kk = K[k]
        finite = np.all(np.isfinite(Kk))
        ev, V = np.linalg.eigh(Kk) if finite else (None, None)
        scale = np.abs(np.linalg.eigvalsh(m.massless_stiffness())).max()
        on_pole = J0_hi[k] > J0_lo[k]
        if on_pole and (not finite or np.abs(ev).min() > 1e-6 * scale):
            x = np.zeros(nf)             # purely local cable mode, platform at rest
            frac[k] = 1.0
            kinds.append("local")
            continue
        x = V[:, np.argmin(np.abs(ev))]
        x = x / np.sqrt(x @ Mf @ x)
        full = np.zeros(6)
        full[fi] = x
        shapes[k] = full
        for i, (p, r) in enumerate(zip(m.params, m.lever_arms)):
            dB = full[:3] + np.cross(full[3:], r)
            E_cab[k, i] = _cable_kinetic(p, w[k], p.rotation.T @ dB, m.chordwise_inertia)
        total = 1.0 + E_cab[k].sum()
        frac[k] = E_cab[k].sum() / total
        E_cab[k] /= total
        if frac[k] < 0.5:
            kinds.append("global")
            mac = (X0.T @ Mf @ x) ** 2
            f_massless[k] = f0[int(np.argmax(mac))]
        else:
            kinds.append("local")
    return ModalResult(freq_hz=f, platform_shapes=shapes, cable_energy_fraction=frac,
                       cable_energy=E_cab, kind=tuple(kinds), massless_freq_hz=f_massless)
