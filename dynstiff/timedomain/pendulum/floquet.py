"""Floquet multipliers of the pendulum linearised about its periodic response (Newton
shooting on the Radau period map, or growth per period along an aperiodic response)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.errors import ConvergenceError
from dynstiff.timedomain.pendulum.dynamics import evaluate_rhs, excitation_at, start_state
from dynstiff.timedomain.pendulum.model import checked_integer
from dynstiff.timedomain.pendulum.radau import (
    RADAU_C,
    mirror_bases,
    period_map,
    stage_matrix,
    steps_per_period_of,
)

if TYPE_CHECKING:
    from typing import Any

    import pandas as pd
    from numpy.typing import NDArray

    from dynstiff.timedomain.pendulum.model import CablePendulum


@dataclass(frozen=True)
class FloquetResult:
    """Floquet multipliers of the periodic response, c excitation cases.

    Attributes
    ----------
    freq_hz, amplitude, phase : ndarray, shape (c,)
        Excitation f [Hz], x0 [m], phase lag [rad].
    multipliers : ndarray, shape (c, n_y), complex
        Eigenvalues of the monodromy matrix, by decreasing modulus. Where no periodic
        response exists (``periodic`` False) they are the K-period averages
        (eigenvalues of the product of K period maps along the response)^(1/K).
    pendulum_multiplier : ndarray, shape (c,), complex
        The multiplier of the pendulum's motion: among the multipliers of the motions that
        can tilt it (for symmetric excitation those antisymmetric under the mirror
        x -> -x; the symmetric ones move the cables alone), the largest in modulus of those
        whose eigenvector holds at least half the largest pendulum share. The cable modes
        are left out: they have no damping of their own, so their |mu| is 1 up to the
        numerical damping of the scheme, and their own parametric resonances (a string
        driven at its ends) are not the pendulum's.
    pendulum_share : ndarray, shape (c,)
        Share of the pendulum angle in the energy norm sum m_i (|dv_i|^2 + omega_n^2
        |dq_i|^2) of that eigenvector [-] (1 for massless cables).
    periodic : ndarray, shape (c,), bool
        Whether Newton shooting found a periodic response.
    orbit_residual : ndarray, shape (c,)
        Scaled max |y(T_e) - y(0)| at the response used [-].
    steps_per_period : ndarray, shape (c,), int
    tol : float
        Stability tolerance on |mu| - 1.
    """

    freq_hz: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    multipliers: np.ndarray
    pendulum_multiplier: np.ndarray
    pendulum_share: np.ndarray
    periodic: np.ndarray
    orbit_residual: np.ndarray
    steps_per_period: np.ndarray
    tol: float

    @property
    def max_abs(self):
        """Largest |mu| of each case, shape (c,) [-]."""
        return np.abs(self.multipliers[:, 0])

    @property
    def pendulum_abs(self) -> NDArray[np.float64]:
        """|mu| of the pendulum's motion, shape (c,) [-]."""
        return np.abs(self.pendulum_multiplier)

    @property
    def stable(self) -> NDArray[np.bool_]:
        """The upright pendulum is stable: |pendulum mu| <= 1 + tol, shape (c,) bool."""
        return self.pendulum_abs <= 1.0 + self.tol

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per case, units in the column names."""
        import pandas as pd
        return pd.DataFrame({
            "f [Hz]": self.freq_hz,
            "x0 [m]": self.amplitude,
            "phase [deg]": np.degrees(self.phase),
            "max |multiplier| [-]": self.max_abs,
            "pendulum |multiplier| [-]": self.pendulum_abs,
            "pendulum share [-]": self.pendulum_share,
            "stable": self.stable,
            "periodic orbit": self.periodic,
            "orbit residual [-]": self.orbit_residual,
            "steps per period": self.steps_per_period,
        })



def floquet(model: CablePendulum, freq_hz: NDArray[np.float64] | float, amplitude: float,
            phase: float = 0.0, steps_min: int = 64, steps_per_cycle: int = 40,
            transient_periods=None, tol: float = 1e-6, orbit_tol: float = 1e-9,
            max_shooting: int = 12, average_periods: int = 20) -> FloquetResult:
    """Floquet multipliers of the pendulum linearised about its periodic response.

    The periodic response y_p(t) = y_p(t + T_e) is found by integrating
    ``transient_periods`` from rest, then by damped Newton shooting on y(T_e) - y(0) = 0
    with the monodromy matrix M. The multipliers mu are the eigenvalues of M at the orbit: a
    small perturbation is multiplied by mu every period, so |mu| > 1 means unstable. For
    symmetric excitation (phase 0) the response keeps phi = 0: it is integrated in the
    mirror-symmetric subspace and M splits into the motions that tilt the pendulum
    (antisymmetric) and those of the cables alone (symmetric). The pendulum's multiplier is
    picked by the share of the pendulum in its eigenvector (see :class:`FloquetResult`).

    Point-mass cables that go slack can move aperiodically (the cable snaps, its transverse
    modes have no damping of their own). Where shooting fails, the growth per period is
    measured along the response instead: the eigenvalues of the product P_K of ``average_
    periods`` = K period maps, |mu| = |eig(P_K)|^(1/K) (equal to the Floquet multipliers
    when the response is periodic: a finite-time Lyapunov exponent per period); ``periodic``
    is then False.

    Parameters
    ----------
    model : CablePendulum
    freq_hz, amplitude, phase : float or array_like, broadcast to shape (c,)
        Excitation frequency f [Hz] (> 0), amplitude x0 [m] (>= 0), phase lag psi of end C
        [rad]. A phase of exactly 0 everywhere selects the symmetric treatment.
    steps_min, steps_per_cycle : int
        Radau steps: at least ``steps_min`` per excitation period and ``steps_per_cycle`` per
        natural period of the pendulum (rounded up to a power of two).
    transient_periods : int, optional
        Periods integrated from rest before shooting. Default: none for massless cables
        under symmetric excitation (the orbit is phi = 0), else 20.
    tol : float
        Stability tolerance: stable when the pendulum's max |mu| <= 1 + tol.
    orbit_tol : float
        Convergence of the shooting, max |y(T_e) - y(0)| scaled by (1 rad, L, omega,
        omega L), omega = max(Omega, omega_n).
    max_shooting : int
        Period integrations spent on Newton shooting.
    average_periods : int
        K, periods averaged where no periodic response is found.

    Returns
    -------
    FloquetResult

    Raises
    ------
    InvalidParameterError
        Bad arguments (named).
    ConvergenceError
        A time step whose Newton iteration failed even after four halvings, or a
        non-finite monodromy matrix.
    """
    exc = excitation_at(freq_hz, amplitude, phase)
    steps_min = checked_integer("steps_min", steps_min, 4)
    steps_per_cycle = checked_integer("steps_per_cycle", steps_per_cycle, 4)
    max_shooting = checked_integer("max_shooting", max_shooting, 1)
    average_periods = checked_integer("average_periods", average_periods, 1)
    symmetric = bool(np.all(exc.phase == 0.0))
    if transient_periods is None:
        transient_periods = 0 if symmetric and model.n_masses == 0 else 20
    transient_periods = checked_integer("transient_periods", transient_periods, 0)
    tol = positive_scalar("tol", tol)
    orbit_tol = positive_scalar("orbit_tol", orbit_tol)
    n_steps = steps_per_period_of(model, exc, steps_min, steps_per_cycle)
    c, ny = exc.omega.size, 2 * model.n_dof
    mult = np.empty((c, ny), dtype=complex)
    pend = np.empty(c, dtype=complex)
    share = np.empty(c)
    resid = np.empty(c)
    periodic = np.empty(c, dtype=bool)
    for ns in np.unique(n_steps):
        idx = np.flatnonzero(n_steps == ns)
        mult[idx], pend[idx], share[idx], periodic[idx], resid[idx] = _floquet_group(
            model, exc.take(idx), int(ns), symmetric, transient_periods, orbit_tol,
            max_shooting, average_periods)
    return FloquetResult(freq_hz=exc.freq_hz, amplitude=exc.amplitude,
                         phase=exc.phase, multipliers=mult, pendulum_multiplier=pend,
                         pendulum_share=share, periodic=periodic, orbit_residual=resid,
                         steps_per_period=n_steps, tol=tol)


def _rest_monodromy(model: CablePendulum, exc: Any, n_steps: int,
                    block: int = 2048) -> NDArray[np.float64]:
    """Monodromy matrix about the orbit y = 0 of massless cables under symmetric excitation
    (phi = 0 is a solution), shape (c, 2, 2): the same Radau step derivatives as
    `_radau_step`, formed for all steps at once and multiplied by pairwise reduction."""
    c, ny = exc.omega.size, 2 * model.n_dof
    h = 2 * np.pi / exc.omega / n_steps
    M = np.broadcast_to(np.eye(ny), (c, ny, ny)).copy()
    for start in range(0, n_steps, block):
        k = np.arange(start, min(n_steps, start + block))
        nb = k.size
        t = ((k[None, :, None] + RADAU_C[None, None, :]) * h[:, None, None]).ravel()
        rep = np.repeat(np.arange(c), 2 * nb)
        J = evaluate_rhs(model, t, np.zeros((t.size, ny)), exc.take(rep), True)[1]
        Mat, rhs = stage_matrix(np.repeat(h, nb), J.reshape(c * nb, 2, ny, ny))
        S = (np.eye(ny) + np.linalg.solve(Mat, rhs)[:, ny:]).reshape(c, nb, ny, ny)
        while S.shape[1] > 1:                          # S_{nb-1} ... S_1 S_0, pairwise
            if S.shape[1] % 2:
                S = np.concatenate([S, np.broadcast_to(np.eye(ny), (c, 1, ny, ny))], axis=1)
            S = S[:, 1::2] @ S[:, 0::2]
        M = S[:, 0] @ M
    return M


def _by_modulus(mu: NDArray[np.complex128]) -> NDArray[np.complex128]:
    return np.take_along_axis(mu, np.argsort(-np.abs(mu), axis=1), axis=1)


def _shooting_step(
        model: CablePendulum, exc: Any, n_steps: int, scale: NDArray[np.float64],
        U: NDArray[np.float64], bases: tuple[NDArray[np.float64], NDArray[np.float64]],
        v: NDArray[np.float64],
) -> tuple[NDArray[np.float64], list[NDArray[np.float64]], NDArray[np.float64],
           NDArray[np.float64]]:
    """One period from v: y(T_e), the monodromy matrices, the scaled residual and the Newton
    step, limited so that no node moves by more than 5 % of the chord (phi by 0.05 rad)."""
    vT, M = period_map(model, v, exc, n_steps, scale, U, bases)
    r = vT - v
    W = bases[0]
    step = np.linalg.solve(M[0] - np.eye(W.shape[1]), -(r @ W)[..., None])[..., 0] @ W.T
    big = np.max(np.abs(step) / scale, axis=1)
    step *= np.minimum(1.0, 0.05 / np.maximum(big, 1e-300))[:, None]
    return vT, M, np.max(np.abs(r) / scale, axis=1), step


def _floquet_group(
        model: CablePendulum, exc: Any, n_steps: int, symmetric: bool, n_transient: int,
        orbit_tol: float, max_shooting: int, n_average: int,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.float64], NDArray[np.bool_],
           NDArray[np.float64]]:
    """Multipliers of c cases sharing the number of steps per period (see `floquet`)."""
    c = exc.omega.size
    if symmetric and model.n_masses == 0:
        mu = _by_modulus(np.linalg.eigvals(_rest_monodromy(model, exc, n_steps))
                         .astype(complex))
        return mu, mu[:, 0], np.ones(c), np.ones(c, dtype=bool), np.zeros(c)
    scale = model.state_scale(exc.omega)
    y = start_state(model, exc)
    if symmetric:
        U, Ua = mirror_bases(model)
        bases = (U, Ua)
        y = (y @ U) @ U.T
    else:
        U, bases = None, (np.eye(2 * model.n_dof),)
    for _ in range(n_transient):
        y = period_map(model, y, exc, n_steps, scale, U)[0]

    def evaluate(
            v: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], list[NDArray[np.float64]], NDArray[np.float64],
               NDArray[np.float64]]:
        return _shooting_step(model, exc, n_steps, scale, U, bases, v)

    def try_evaluate(v, fallback):
        """`evaluate`, case by case where the batch fails; a case whose integration fails
        gets an infinite residual (its candidate is rejected)."""
        try:
            return evaluate(v)
        except ConvergenceError:
            if c == 1:
                return fallback[0], fallback[1], np.full(1, np.inf), fallback[3]
        parts = []
        for k in range(c):
            try:
                parts.append(_shooting_step(model, exc.take([k]), n_steps, scale[k:k + 1], U,
                                            bases, v[k:k + 1]))
            except ConvergenceError:
                parts.append((fallback[0][k:k + 1], [m[k:k + 1] for m in fallback[1]],
                              np.full(1, np.inf), fallback[3][k:k + 1]))
        return (np.concatenate([p[0] for p in parts]),
                [np.concatenate([p[1][b] for p in parts]) for b in range(len(bases))],
                np.concatenate([p[2] for p in parts]), np.concatenate([p[3] for p in parts]))

    # damped Newton shooting: a step must lower the residual by (1 - lam/4); after two
    # halvings of lam the point moves on by one period of transient instead
    yT, M, err, step = evaluate(y)
    lam = np.ones(c)
    picard = np.zeros(c, dtype=bool)
    for _ in range(max_shooting - 1):
        done = err <= orbit_tol
        if np.all(done):
            break
        cand = np.where(picard[:, None], yT, y + lam[:, None] * step)
        cT, cM, cerr, cstep = try_evaluate(cand, (yT, M, err, step))
        accept = ~done & np.isfinite(cerr) & (picard | (cerr < (1 - 0.25 * lam) * err))
        y = np.where(accept[:, None], cand, y)
        yT = np.where(accept[:, None], cT, yT)
        step = np.where(accept[:, None], cstep, step)
        M = [np.where(accept[:, None, None], b, a) for a, b in zip(M, cM)]
        err = np.where(accept, cerr, err)
        lam = np.where(accept, 1.0, 0.5 * lam)
        picard = ~accept & (lam < 0.3)
    periodic = err <= orbit_tol
    mats = [m.copy() for m in M]
    logs = [np.zeros(c) for _ in bases]
    if not np.all(periodic):
        # growth per period along the (aperiodic) response: product of K period maps,
        # rescaled every period
        idx = np.flatnonzero(~periodic)
        v = yT[idx]
        prod = [np.broadcast_to(np.eye(B.shape[1]), (idx.size,) + (B.shape[1],) * 2).copy()
                for B in bases]
        for _ in range(n_average):
            v_prev = v
            v, Mk = period_map(model, v, exc.take(idx), n_steps, scale[idx], U, bases)
            for b in range(len(bases)):
                p = Mk[b] @ prod[b]
                nrm = np.linalg.norm(p, axis=(1, 2))
                prod[b] = p / nrm[:, None, None]
                logs[b][idx] += np.log(nrm)
        for b in range(len(bases)):
            mats[b][idx] = prod[b]
        err[idx] = np.max(np.abs(v - v_prev) / scale[idx], axis=1)
        periodic[idx] = err[idx] <= orbit_tol
    if not all(np.all(np.isfinite(m)) for m in mats):
        raise ConvergenceError(
            f"floquet: non-finite monodromy matrix at f = "
            f"{exc.freq_hz.max():.6g} Hz (integration blew up)")
    K = np.where(periodic, 1, n_average)[:, None]
    mus, vecs = [], None
    for b, m in enumerate(mats):
        lam, vec = np.linalg.eig(m)
        lam = lam.astype(complex)
        mod = np.exp((np.log(np.maximum(np.abs(lam), 1e-300)) + logs[b][:, None]) / K)
        mus.append(mod * np.exp(1j * np.angle(lam) / K))
        vecs = vec                                   # the last basis holds the pendulum
    share = _pendulum_share(model, bases[-1] @ vecs)
    pick = np.where(share >= 0.5 * share.max(axis=1, keepdims=True), np.abs(mus[-1]), -1.0)
    k = np.argmax(pick, axis=1)
    rows = np.arange(c)
    return (_by_modulus(np.concatenate(mus, axis=1)), mus[-1][rows, k], share[rows, k],
            periodic, err)


def _pendulum_share(model: CablePendulum, V: NDArray[np.complex128]) -> NDArray[np.float64]:
    """Share of the pendulum angle in the energy norm sum_i m_i (|dv_i|^2 + omega_n^2
    |dq_i|^2) of state vectors V, shape (c, n_y, k) -> (c, k)."""
    nq = model.n_dof
    w2 = (2 * np.pi * max(model.natural_frequency_hz(), 1.0)) ** 2
    m = model.mass_diagonal()[None, :, None]
    e = m * (np.abs(V[:, nq:]) ** 2 + w2 * np.abs(V[:, :nq]) ** 2)
    return e[:, 0] / np.sum(e, axis=1)

