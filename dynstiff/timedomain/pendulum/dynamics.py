"""Equations of motion of the pendulum and its cables, batched over excitation cases:
end motion, segment tensions, right-hand side and exact Jacobian, rest state."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.timedomain.pendulum.model import CablePendulum


@dataclass(frozen=True)
class _Excitation:
    """Batched excitation: frequency [Hz], amplitude [m], phase lag [rad], each shape (c,)."""

    freq_hz: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray

    @property
    def omega(self) -> NDArray[np.float64]:
        return 2 * np.pi * self.freq_hz

    def take(self, idx: NDArray[np.int64]) -> _Excitation:
        return _Excitation(self.freq_hz[idx], self.amplitude[idx], self.phase[idx])

    def repeat(self, r: int) -> _Excitation:
        return _Excitation(np.tile(self.freq_hz, r), np.tile(self.amplitude, r),
                           np.tile(self.phase, r))


def excitation_at(freq_hz: NDArray[np.float64] | float, amplitude: NDArray[np.float64] | float,
                  phase: NDArray[np.float64] | float) -> _Excitation:
    f, x0, ph = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, dtype=float))
                                      for v in (freq_hz, amplitude, phase)))
    for name, v, zero in (("freq_hz", f, False), ("amplitude", x0, True)):
        bad = ~np.isfinite(v) | (v < 0) | ((v == 0) & (not zero))
        if np.any(bad):
            raise InvalidParameterError(
                f"{name} must be finite and {'>= 0' if zero else '> 0'}, got "
                f"{v[bad][0]!r}")
    if not np.all(np.isfinite(ph)):
        raise InvalidParameterError(f"phase must be finite [rad], got {ph[~np.isfinite(ph)][0]!r}")
    return _Excitation(f.ravel().copy(), x0.ravel().copy(), ph.ravel().copy())


def _ends(model: CablePendulum, t: NDArray[np.float64],
          exc: _Excitation) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """End positions and velocities E, dE/dt, shape (c, 2, 2) [m, m/s]."""
    c = t.shape[0]
    a1, a2 = exc.omega * t, exc.omega * t - exc.phase
    E = np.empty((c, 2, 2))
    V = np.zeros((c, 2, 2))
    E[:, 0, 0] = -model.half_span - exc.amplitude * np.sin(a1)
    E[:, 1, 0] = model.half_span + exc.amplitude * np.sin(a2)
    E[:, :, 1] = model.end_height
    V[:, 0, 0] = -exc.amplitude * exc.omega * np.cos(a1)
    V[:, 1, 0] = exc.amplitude * exc.omega * np.cos(a2)
    return E, V


def segment_geometry(model: CablePendulum, t: NDArray[np.float64], y: NDArray[np.float64],
                     exc: _Excitation) -> tuple[NDArray[np.float64], ...]:
    """Geometry and tensions of all cable segments, batched over c cases.

    Returns D, tD = dD/dphi (c, 2); the segment vectors r, their rates w and unit vectors e
    (c, 2, n+1, 2); lengths (c, 2, n+1); the spring-damper force s and tension T = max(s, 0)
    (c, 2, n+1) [N].
    """
    n, nq = model.n_masses, model.n_dof
    c = y.shape[0]
    phi, dphi = y[:, 0], y[:, nq]
    d = model.attach_distance
    D = d * np.stack([np.sin(phi), np.cos(phi)], axis=1)
    tD = d * np.stack([np.cos(phi), -np.sin(phi)], axis=1)
    P = np.empty((c, 2, n + 2, 2))
    V = np.empty((c, 2, n + 2, 2))
    P[:, :, 0], V[:, :, 0] = _ends(model, t, exc)
    P[:, :, 1:n + 1] = y[:, 1:nq].reshape(c, 2, n, 2)
    V[:, :, 1:n + 1] = y[:, nq + 1:].reshape(c, 2, n, 2)
    P[:, :, n + 1] = D[:, None]
    V[:, :, n + 1] = (tD * dphi[:, None])[:, None]
    r = np.diff(P, axis=2)
    w = np.diff(V, axis=2)
    length = np.sqrt(np.sum(r * r, axis=-1))
    e = r / length[..., None]
    s = (n + 1) * (model.stiffness * (length - model.unstretched_length / (n + 1))
                   + model.damping * np.sum(e * w, axis=-1))
    return D, tD, r, w, e, length, s, np.maximum(s, 0.0)


def evaluate_rhs(model: CablePendulum, t: NDArray[np.float64], y: NDArray[np.float64],
                 exc: _Excitation, jac: bool) -> tuple[NDArray[np.float64], None]:
    """Right-hand side (and Jacobian) of the first-order system, batched over c cases.

    Returns
    -------
    ydot : ndarray, shape (c, 2 n_dof)
    J : ndarray, shape (c, 2 n_dof, 2 n_dof), or None
    """
    n, nq = model.n_masses, model.n_dof
    c = y.shape[0]
    ks = (n + 1) * model.stiffness
    bs = (n + 1) * model.damping
    dphi = y[:, nq]
    D, tD, r, w, e, length, s, T = segment_geometry(model, t, y, exc)
    sn, cs = D[:, 0] / model.attach_distance, D[:, 1] / model.attach_distance
    F = T[..., None] * e                                 # force on a segment's first point
    fD = -F[:, :, n].sum(axis=1)                         # on D, both cables
    Q = np.empty((c, nq))
    Q[:, 0] = np.sum(tD * fD, axis=1) + model.gravity_moment() * sn
    if n:
        fn = F[:, :, 1:] - F[:, :, :-1]
        fn[..., 1] -= model.node_mass * model.g
        Q[:, 1:] = fn.reshape(c, 4 * n)
    Minv = 1.0 / model.mass_diagonal()
    ydot = np.concatenate([y[:, nq:], Q * Minv], axis=1)
    if not jac:
        return ydot, None
    # segment blocks: Kr = d(T e)/dr, Cw = d(T e)/dw (zero while slack)
    taut = (s > 0.0)[..., None, None]
    ee = e[..., :, None] * e[..., None, :]
    Pr = np.eye(2) - ee
    wperp = np.einsum("...ij,...j->...i", Pr, w)
    Kr = taut * (ks * ee + bs * e[..., :, None] * wperp[..., None, :] / length[..., None, None]
                 + (T / length)[..., None, None] * Pr)
    Cw = taut * (bs * ee)
    npt = 4 * n + 2                                      # point space: nodes, then D
    Kp = np.zeros((c, npt, npt))
    Cp = np.zeros((c, npt, npt))
    two = np.arange(2)
    node = 2 * (np.arange(2)[:, None] * n + np.arange(n)[None, :])          # (2, n)
    nxt = np.concatenate([node[:, 1:], np.full((2, 1), 4 * n)], axis=1)[:, :n]
    for Mp, X in ((Kp, Kr), (Cp, Cw)):
        Mp[:, 4 * n:, 4 * n:] = -(X[:, 0, n] + X[:, 1, n])
        if n:
            rows = node[..., None, None] + two[:, None]
            cols = node[..., None, None] + two[None, :]
            Mp[:, rows, cols] = -(X[:, :, :-1] + X[:, :, 1:])
            rn = nxt[..., None, None] + two[:, None]
            cn = nxt[..., None, None] + two[None, :]
            Mp[:, rows, cn] = X[:, :, 1:]
            Mp[:, rn, cols] = X[:, :, 1:]
    # generalised coordinates: the nodes map to themselves, D moves by tD dphi and its
    # velocity by tD d(dphi) - D dphi dphi
    nn, dd = slice(0, 4 * n), slice(4 * n, npt)
    vD = -D * dphi[:, None]
    dQdq = np.empty((c, nq, nq))
    dQdv = np.empty((c, nq, nq))
    dQdq[:, 1:, 1:] = Kp[:, nn, nn]
    dQdv[:, 1:, 1:] = Cp[:, nn, nn]
    dQdq[:, 1:, 0] = (np.einsum("cij,cj->ci", Kp[:, nn, dd], tD)
                      + np.einsum("cij,cj->ci", Cp[:, nn, dd], vD))
    dQdv[:, 1:, 0] = np.einsum("cij,cj->ci", Cp[:, nn, dd], tD)
    dQdq[:, 0, 1:] = np.einsum("ci,cij->cj", tD, Kp[:, dd, nn])
    dQdv[:, 0, 1:] = np.einsum("ci,cij->cj", tD, Cp[:, dd, nn])
    dQdq[:, 0, 0] = (np.einsum("ci,cij,cj->c", tD, Kp[:, dd, dd], tD)
                     + np.einsum("ci,cij,cj->c", tD, Cp[:, dd, dd], vD)
                     - np.sum(D * fD, axis=1) + model.gravity_moment() * cs)
    dQdv[:, 0, 0] = np.einsum("ci,cij,cj->c", tD, Cp[:, dd, dd], tD)
    J = np.zeros((c, 2 * nq, 2 * nq))
    J[:, :nq, nq:] = np.eye(nq)
    J[:, nq:, :nq] = dQdq * Minv[:, None]
    J[:, nq:, nq:] = dQdv * Minv[:, None]
    return ydot, J


def _batch_args(model: CablePendulum, t: NDArray[np.float64] | float, y: NDArray[np.float64],
                freq_hz: float, amplitude: float,
                phase: float) -> tuple[NDArray[np.float64], NDArray[np.float64], _Excitation]:
    exc = excitation_at(freq_hz, amplitude, phase)
    y = np.atleast_2d(np.asarray(y, dtype=float))
    if y.shape[-1] != 2 * model.n_dof:
        raise InvalidParameterError(
            f"y must have {2 * model.n_dof} state components (2 (1 + 4 n_masses)), got shape "
            f"{y.shape}")
    t = np.atleast_1d(np.asarray(t, dtype=float))
    if t.ndim != 1 or not np.all(np.isfinite(t)):
        raise InvalidParameterError(f"t must be finite times [s], scalar or 1-D, got {t!r}")
    c = max(y.shape[0], exc.omega.size, t.size)
    try:
        t = np.broadcast_to(t, (c,)).copy()
        y = np.broadcast_to(y, (c, y.shape[1])).copy()
        f = np.broadcast_to(exc.freq_hz, (c,))
    except ValueError:
        raise InvalidParameterError(
            f"t, y and the excitation must broadcast to one number of cases, got {t.size}, "
            f"{y.shape[0]}, {exc.omega.size}") from None
    return t, y, excitation_at(f, np.broadcast_to(exc.amplitude, (c,)),
                             np.broadcast_to(exc.phase, (c,)))


def rhs(model: CablePendulum, t: float, y: NDArray[np.float64], freq_hz: float, amplitude: float,
        phase: float = 0.0) -> NDArray[np.float64]:
    """Nonlinear right-hand side dy/dt of the pendulum and its cables.

    Parameters
    ----------
    model : CablePendulum
    t : float or array_like, shape (c,)
        Time [s].
    y : array_like, shape (2 n_dof,) or (c, 2 n_dof)
        State (q, dq/dt), q = (phi [rad], node coordinates [m]).
    freq_hz, amplitude, phase : float or array_like, shape (c,)
        Excitation frequency f [Hz], amplitude x0 [m] and phase lag psi of end C [rad].

    Returns
    -------
    ndarray, shape (c, 2 n_dof)
    """
    t, y, exc = _batch_args(model, t, y, freq_hz, amplitude, phase)
    return evaluate_rhs(model, t, y, exc, False)[0]


def jacobian(model: CablePendulum, t: NDArray[np.float64] | float, y: NDArray[np.float64],
             freq_hz: float, amplitude: float, phase: float = 0.0) -> NDArray[np.float64]:
    """Jacobian d(dy/dt)/dy of :func:`rhs` (exact, piecewise: slack segments contribute 0).

    Parameters
    ----------
    model, t, y, freq_hz, amplitude, phase
        As for :func:`rhs`.

    Returns
    -------
    ndarray, shape (c, 2 n_dof, 2 n_dof)
    """
    t, y, exc = _batch_args(model, t, y, freq_hz, amplitude, phase)
    return evaluate_rhs(model, t, y, exc, True)[1]


def rest_state(model: CablePendulum, phi: float = 0.0) -> NDArray[np.float64]:
    """State at rest with the ends in their mean position, shape (2 n_dof,).

    The point masses hang in the static equilibrium of each cable between E and D (Newton,
    :func:`dynstiff.lumped.chain_equilibrium`, same lumping and gravity); ``phi`` [rad]
    tilts the pendulum without moving the nodes (an initial disturbance).
    """
    phi = float(phi)
    if not np.isfinite(phi):
        raise InvalidParameterError(f"phi must be finite [rad], got {phi!r}")
    y = np.zeros(2 * model.n_dof)
    y[0] = phi
    n = model.n_masses
    if n:
        from dynstiff.cable.lumped_chain import chain_equilibrium
        from dynstiff.params import Cable
        L0 = model.unstretched_length
        cable = Cable(model.cable_mass / L0, model.stiffness * L0)
        D = np.array([0.0, 0.0, model.attach_distance])
        for i, sign in enumerate((-1.0, 1.0)):
            E = np.array([sign * model.half_span, 0.0, model.end_height])
            st = chain_equilibrium(E, D, L0, cable, n + 1, model.g)
            y[1 + 2 * n * i:1 + 2 * n * (i + 1)] = st.nodes[1:-1][:, [0, 2]].ravel()
    return y



def start_state(model: CablePendulum, exc: _Excitation) -> NDArray[np.float64]:
    """Rest state whose point masses move with the ends as at t = 0 (velocity interpolated
    along each cable), so that a start from rest does not jolt the stiff cable, (c, n_y)."""
    c, n, nq = exc.omega.size, model.n_masses, model.n_dof
    y = np.broadcast_to(rest_state(model), (c, 2 * nq)).copy()
    if n:
        _, V = _ends(model, np.zeros(c), exc)
        w = 1.0 - np.arange(1, n + 1) / (n + 1)                     # share of the end motion
        y[:, nq + 1:] = (V[:, :, None, :] * w[None, None, :, None]).reshape(c, 4 * n)
    return y

