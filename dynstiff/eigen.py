"""Complete eigenfrequencies of the robot by Wittrick-Williams counting, and its modes.

K(omega) is transcendental with poles at every cable's clamped-clamped frequencies, so a sign
scan of det K finds poles as well as roots and misses close pairs. The Wittrick-Williams count
(Wittrick & Williams 1971; theory.md §5)

    J(omega) = J0(omega) + s{K(omega)}

(J0: clamped-cable frequencies below omega, s: negative eigenvalues of K) is the exact number
of natural frequencies below omega. The r-th frequency is bracketed by bisection on J, all
roots at once (one batched evaluation of K per step), until the bracket holds that root alone
and no cable pole; the eigenvalue of K that crosses zero there is then refined by a vectorised
Illinois (regula falsi) iteration to a relative bracket width of ``rtol``. Multiple roots and
roots on a cable pole are bisected to ``rtol``. This never misses a root, handles coincident
roots, and finds purely local cable modes, which are not zeros of det K.
"""

import functools
from dataclasses import dataclass

import numpy as np

from ._vec import cross
from .cable_dsm import _local_entries
from .errors import ConvergenceError, InvalidParameterError
from .platform import DOF_NAMES

__all__ = ["eigenfrequencies", "modes", "ModalResult", "cable_fields", "damped_modes",
           "DampedModes"]

_TWO_PI = 2.0 * np.pi


def _undamped(model):
    """The model itself, or an undamped copy (W-W needs a real symmetric K)."""
    if not model.damped:
        return model
    import copy
    from dataclasses import replace
    m = copy.copy(model)
    from .cable_dsm import stack_parameters
    m.params = [replace(p, c=0.0, EA=float(np.real(p.EA))) for p in model.params]
    m._stack = stack_parameters(m.params)
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
    J_lo, J_hi = np.zeros(N, dtype=int), np.full(N, N)
    # phase 1: bisection on the count until each bracket holds one simple root and no cable
    # pole (then the eigenvalue of K that crosses zero is smooth and decreasing in it)
    while True:
        width = hi - lo
        isolated = (J_lo == r - 1) & (J_hi == r) & (width < 1e-3 * hi)
        if np.all(isolated | (width <= rtol * hi)):
            break
        act = ~isolated & (width > rtol * hi)
        mid = 0.5 * (lo[act] + hi[act])
        u, inv = np.unique(mid, return_inverse=True)
        J = m.mode_count(u)[inv]
        above = J >= r[act]
        idx = np.flatnonzero(act)
        hi[idx[above]], J_hi[idx[above]] = mid[above], J[above]
        lo[idx[~above]], J_lo[idx[~above]] = mid[~above], J[~above]
    refine = isolated & (m.cable_mode_count(lo) == m.cable_mode_count(hi))
    # multiple roots and roots on a cable pole keep bisecting to rtol
    while True:
        act = ~refine & (hi - lo > rtol * hi)
        if not np.any(act):
            break
        mid = 0.5 * (lo[act] + hi[act])
        J = m.mode_count(mid)
        above = J >= r[act]
        idx = np.flatnonzero(act)
        hi[idx[above]] = mid[above]
        lo[idx[~above]] = mid[~above]
    out = 0.5 * (lo + hi)
    if np.any(refine):
        out[refine] = _illinois(m, lo[refine], hi[refine], J_lo[refine], rtol)
    return out / _TWO_PI


def _crossing_eigenvalue(m, omega, index):
    """Eigenvalue number ``index`` (ascending, minus the cable-count offset) of K(omega)."""
    K = m.dynamic_stiffness(omega)
    ev = np.linalg.eigvalsh(K.real if np.iscomplexobj(K) else K)
    return ev[np.arange(len(omega)), index]


def _illinois(m, lo, hi, J_lo, rtol, max_iter=100):
    """Vectorised Illinois regula falsi on the eigenvalue of K that crosses zero in [lo, hi].

    In an isolated bracket without cable poles, s{K} goes from s_lo = J_lo - J0 to s_lo + 1,
    so eigenvalue number s_lo (ascending) goes from >= 0 to < 0, decreasing (W-W monotonicity).
    Falls back to bisection where the update leaves the bracket. Returns roots [rad/s].
    """
    idx = J_lo - m.cable_mode_count(lo)
    f_lo = _crossing_eigenvalue(m, lo, idx)
    f_hi = _crossing_eigenvalue(m, hi, idx)
    side = np.zeros(len(lo), dtype=int)
    x = 0.5 * (lo + hi)
    for _ in range(max_iter):
        act = hi - lo > rtol * hi
        if not np.any(act):
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            x = np.where(act, (lo * f_hi - hi * f_lo) / (f_hi - f_lo), x)
        bad = ~np.isfinite(x) | (x <= lo) | (x >= hi)
        x = np.where(bad, 0.5 * (lo + hi), x)
        fx = _crossing_eigenvalue(m, x, idx)
        pos = fx >= 0
        # Illinois: halve the retained end's value when the same side is kept twice
        lo_new = np.where(act & pos, x, lo)
        hi_new = np.where(act & ~pos, x, hi)
        f_hi = np.where(act & pos & (side == 1), 0.5 * f_hi, f_hi)
        f_lo = np.where(act & ~pos & (side == -1), 0.5 * f_lo, f_lo)
        f_lo = np.where(act & pos, fx, f_lo)
        f_hi = np.where(act & ~pos, fx, f_hi)
        side = np.where(act, np.where(pos, 1, -1), side)
        converged = act & (np.abs(fx) == 0)
        lo, hi = np.where(converged, x, lo_new), np.where(converged, x, hi_new)
    return 0.5 * (lo + hi)


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


def _cable_field(p, omega, d_local, x):
    """Closed-form displacement (u, v, w) [m] along cable chord at positions x [m], shape
    (len(x), 3), for end-B motion d_local = (u_B, v_B, w_B) with A clamped (theory.md §5.3):
    v = C1 cos(beta x) + C2 sin(beta x) + q h / (T beta)^2, w = w_B sin(beta x)/sin(beta L),
    u = u_B x / L (quasi-static stretching)."""
    uB, vB, wB = d_local
    k_uu, k_uv, *_ = _local_entries(p, np.array([omega]), False)
    h = k_uu[0] * uB - k_uv[0] * vB                   # dynamic tension [N]
    beta = 2.0 * p.psi(np.array([omega]))[0] / p.L
    Om = beta * p.L
    vp = h * p.q / (p.T * beta) ** 2
    C2 = (vB - vp + vp * np.cos(Om)) / np.sin(Om)
    v = -vp * np.cos(beta * x) + C2 * np.sin(beta * x) + vp
    w = wB * np.sin(beta * x) / np.sin(Om)
    return np.column_stack([uB * x / p.L, v, w])


@functools.lru_cache(maxsize=8)
def _gauss(n):
    """Gauss-Legendre nodes and weights on [-1, 1] (cached)."""
    return np.polynomial.legendre.leggauss(n)


def _cable_kinetic(p, omega, d_local, chordwise_inertia, n_gauss=64):
    """int m (|v|^2 + |w|^2) dx (+ m L/3 |u_B|^2) [kg m^2 per unit amplitude^2] of the
    closed-form field (Gauss-Legendre quadrature)."""
    x, wts = _gauss(n_gauss)
    x = 0.5 * p.L * (x + 1.0)
    wts = 0.5 * p.L * wts
    f = _cable_field(p, omega, d_local, x)
    E = p.m * np.sum(wts * (np.abs(f[:, 1]) ** 2 + np.abs(f[:, 2]) ** 2))
    if chordwise_inertia:
        E += p.m * p.L / 3.0 * abs(d_local[0]) ** 2
    return float(E)


def cable_fields(model, modes, k, n_points=41):
    """Cable displacement fields of mode ``k`` (platform-moving modes), global frame.

    Parameters
    ----------
    model : FrequencyModel
    modes : ModalResult
        From ``model.modes()``.
    k : int
        Mode index (0-based).
    n_points : int
        Points per cable, from anchor to attachment.

    Returns
    -------
    positions : ndarray, shape (n_cables, n_points, 3)
        Points on the chords [m].
    displacements : ndarray, shape (n_cables, n_points, 3)
        Mode displacement [m] for the platform shape ``modes.platform_shapes[k]``; zero for a
        purely local mode (platform at rest), whose cable shape is the clamped-clamped one.
    """
    x6 = modes.platform_shapes[k]
    w = _TWO_PI * modes.freq_hz[k]
    eq = model.equilibrium
    pos = np.zeros((len(model.params), n_points, 3))
    disp = np.zeros_like(pos)
    for i, (p, r, s) in enumerate(zip(model.params, model.lever_arms, eq.states)):
        x = np.linspace(0.0, p.L, n_points)
        pos[i] = s.anchor + np.outer(x / p.L, s.chord)
        if not np.any(x6):
            continue
        dB = x6[:3] + cross(x6[3:], r)
        disp[i] = np.real(_cable_field(p, w, p.rotation.T @ dB, x)) @ p.rotation.T
    return pos, disp


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
    lam0, X0 = eigh(m.massless_stiffness(), Mf)       # massless-cable model
    f0 = np.sqrt(np.maximum(lam0, 0.0)) / _TWO_PI
    shapes = np.zeros((len(f), 6))
    E_cab = np.zeros((len(f), len(m.params)))
    frac = np.zeros(len(f))
    kinds, f_massless = [], np.full(len(f), np.nan)
    K = m.dynamic_stiffness(w) if len(w) else np.zeros((0, nf, nf))
    J0_lo = m.cable_mode_count(w * (1 - 1e-9)) if len(w) else []
    J0_hi = m.cable_mode_count(w * (1 + 1e-9)) if len(w) else []
    K_static = m.massless_stiffness()
    scale = np.abs(np.linalg.eigvalsh(K_static)).max()
    for k in range(len(f)):
        Kk = K[k]
        finite = np.all(np.isfinite(Kk))
        ev, V = np.linalg.eigh(Kk) if finite else (None, None)
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
            dB = full[:3] + cross(full[3:], r)
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


# ------------------------------------------------------------------------- damped roots
@dataclass(frozen=True)
class DampedModes:
    """Complex natural frequencies of the damped robot (convention e^{i omega t}).

    Attributes
    ----------
    undamped_freq_hz : ndarray, shape (n,)
        Seeds: undamped natural frequencies [Hz].
    omega : ndarray, shape (n,), complex
        Roots of det K(omega) = 0 [rad/s]; Im(omega) > 0 for a decaying mode. NaN where the
        iteration did not converge (see ``residual``) or for purely local modes.
    residual : ndarray, shape (n,)
        |smallest eigenvalue of K(omega)| / ||K|| at the returned root [-].
    """

    undamped_freq_hz: np.ndarray
    omega: np.ndarray
    residual: np.ndarray

    @property
    def freq_hz(self):
        """Damped natural frequency Re(omega) / 2 pi [Hz]."""
        return self.omega.real / _TWO_PI

    @property
    def damping_ratio(self):
        """zeta = Im(omega) / |omega| [-]."""
        return self.omega.imag / np.abs(self.omega)

    def to_frame(self):
        """pandas DataFrame with units in column names."""
        import pandas as pd
        return pd.DataFrame({"undamped freq [Hz]": self.undamped_freq_hz,
                             "damped freq [Hz]": self.freq_hz,
                             "damping ratio [-]": self.damping_ratio,
                             "residual [-]": self.residual})


def _nearest_zero_eigenvalue(model, w):
    with np.errstate(all="ignore"):
        K = model._dynamic_stiffness_complex(w)[0]
    if not np.all(np.isfinite(K)):
        return np.inf, 1.0
    mu = np.linalg.eigvals(K)
    return mu[np.argmin(np.abs(mu))], np.linalg.norm(K, 2)


def _perturbation_estimates(model, und):
    """First-order damped roots omega_r + d_omega, d_omega = -x^T (K_d - K_u) x / x^T K_u' x
    (x: undamped platform mode, K_u' = dK_u/domega by central differences)."""
    mu = _undamped(model)
    fi = model._fi
    est = np.full(len(und), np.nan + 0j)
    for k, f in enumerate(und.freq_hz):
        x = und.platform_shapes[k][fi]
        if not np.any(x):
            continue
        w = _TWO_PI * f
        h = 1e-6 * w
        dK = (mu.dynamic_stiffness([w + h])[0] - mu.dynamic_stiffness([w - h])[0]) / (2 * h)
        delta = model._dynamic_stiffness_complex(w)[0] - mu.dynamic_stiffness([w])[0]
        est[k] = w - (x @ delta @ x) / (x @ dK @ x)
    return est


def damped_modes(model, n_modes=None, fmax_hz=None, tol=1e-12, max_iter=80):
    """Complex natural frequencies of the damped robot, seeded from the undamped ones.

    Each undamped mode omega_r with platform motion x gives a first-order estimate
    omega_r + d_omega, d_omega = -x^T (K_d - K_u) x / x^T dK_u/domega x (perturbation of the
    real root by the damping part of K). From there a secant iteration in the complex plane
    on det K(omega), deflated by the roots already found, converges to the damped root
    (theory.md §5.4). The root is accepted only if the eigenvalue of K nearest zero is below
    1e-8 ||K|| and the root is closer to its own estimate than to any other mode's (so a
    root is never attributed to the wrong mode in a cluster of close local modes); otherwise,
    and for purely local modes (platform at rest, not zeros of det K), it is NaN with its
    ``residual`` recorded.

    Returns
    -------
    DampedModes
    """
    und = modes(model, n_modes=n_modes, fmax_hz=fmax_hz)
    est = _perturbation_estimates(model, und)
    out = np.full(len(und), np.nan + 1j * np.nan)
    resid = np.full(len(und), np.nan)
    found = []
    for k in np.flatnonzero(np.isfinite(est)):
        def g(w):
            if abs(w - est[k]) > 0.2 * abs(est[k]):      # left the neighbourhood: give up
                return np.nan
            with np.errstate(all="ignore"):
                K = model._dynamic_stiffness_complex(w)[0]
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
        mu, nK = _nearest_zero_eigenvalue(model, w1)
        resid[k] = abs(mu) / nK
        others = np.delete(est, k)
        others = others[np.isfinite(others)]
        own = abs(w1 - est[k]) < np.min(np.abs(w1 - others), initial=np.inf)
        distinct = all(abs(w1 - wj) > 1e-8 * abs(w1) for wj in found)
        if resid[k] < 1e-8 and own and distinct:
            out[k] = w1
            found.append(w1)
    return DampedModes(undamped_freq_hz=und.freq_hz, omega=out, residual=resid)
