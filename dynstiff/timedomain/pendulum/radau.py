"""Fixed-step two-stage Radau IIA integration of the pendulum over excitation periods, with
the exact derivative of the discrete period map (the monodromy matrix)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import ConvergenceError
from dynstiff.timedomain.pendulum.dynamics import evaluate_rhs

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.timedomain.pendulum.model import CablePendulum

# two-stage Radau IIA (order 3, stiffly accurate)
RADAU_C = np.array([1.0 / 3.0, 1.0])
_RADAU_A = np.array([[5.0 / 12.0, -1.0 / 12.0], [3.0 / 4.0, 1.0 / 4.0]])


def _project(J: NDArray[np.float64], U: NDArray[np.float64]) -> NDArray[np.float64]:
    """U^T J U for a batch of square matrices (U None: J itself)."""
    return J if U is None else U.T @ J @ U


def stage_matrix(h: NDArray[np.float64],
                 Js: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """I - h (A kron J) for stage Jacobians Js of shape (c, 2, m, m) -> (c, 2m, 2m), and
    h sum_j a_ij J_j stacked over i, shape (c, 2m, m)."""
    c, _, m, _ = Js.shape
    hAJ = h[:, None, None, None, None] * _RADAU_A[None, :, :, None, None] * Js[:, None]
    Mat = np.eye(2 * m) - hAJ.transpose(0, 1, 3, 2, 4).reshape(c, 2 * m, 2 * m)
    return Mat, hAJ.sum(axis=2).reshape(c, 2 * m, m)


def _radau_step(model: CablePendulum, t: NDArray[np.float64], y: NDArray[np.float64],
                h: NDArray[np.float64], exc: Any, scale: NDArray[np.float64],
                U: NDArray[np.float64] | None = None, derivative: tuple[Any, ...] = (),
                tol: float = 1e-10, max_iter: int = 25) -> tuple[NDArray[np.float64], list[Any]]:
    """One two-stage Radau IIA step for c cases.

    The stage increments live in the span of the orthonormal columns of ``U`` (None: the whole
    state space), an invariant subspace such as the mirror-symmetric states. Returns the new
    state, shape (c, n_y), and for each basis W in ``derivative`` the step derivative in that
    basis, W^T (dy_new/dy) W, from the Newton matrix at the converged stages.
    """
    c, ny = y.shape
    tt = np.concatenate([t + RADAU_C[0] * h, t + RADAU_C[1] * h])
    exc2 = exc.repeat(2)
    f0 = evaluate_rhs(model, t, y, exc, False)[0]
    if U is not None:
        f0 = f0 @ U
    Z = RADAU_C[None, :, None] * h[:, None, None] * f0[:, None, :]
    m = Z.shape[2]
    err = np.inf
    for _ in range(max_iter):
        dY = Z if U is None else Z @ U.T
        Y = (y[:, None, :] + dY).transpose(1, 0, 2).reshape(2 * c, ny)
        F, J = evaluate_rhs(model, tt, Y, exc2, True)
        F = F.reshape(2, c, ny).transpose(1, 0, 2)
        J = J.reshape(2, c, ny, ny).transpose(1, 0, 2, 3)
        if U is not None:
            F = F @ U
        G = Z - h[:, None, None] * np.einsum("ij,cjn->cin", _RADAU_A, F)
        Mat, _ = stage_matrix(h, _project(J, U))
        dZ = np.linalg.solve(Mat, -G.reshape(c, 2 * m, 1))[..., 0].reshape(c, 2, m)
        Z += dZ
        err = np.max(np.abs(dZ if U is None else dZ @ U.T) / scale[:, None, :])
        if not np.isfinite(err) or err <= tol:
            break
    if not np.isfinite(err):
        raise ConvergenceError(f"Radau step at t = {t.max():.6g} s: non-finite state")
    if err > tol:
        raise ConvergenceError(
            f"Radau step at t = {t.max():.6g} s: Newton did not converge in {max_iter} "
            f"iterations, scaled correction {err:.2e}", residual=float(err))
    y_new = y + (Z[:, 1] if U is None else Z[:, 1] @ U.T)
    out = []
    for W in derivative:
        Mw, rw = stage_matrix(h, _project(J, W))
        k = rw.shape[2]
        out.append(np.eye(k) + np.linalg.solve(Mw, rw)[:, k:])
    return y_new, out


def _robust_step(model: CablePendulum, t: NDArray[np.float64], y: NDArray[np.float64],
                 h: NDArray[np.float64], exc: Any, scale: NDArray[np.float64],
                 U: NDArray[np.float64], derivative: tuple[Any, ...],
                 depth: int = 0) -> tuple[NDArray[np.float64], list[Any]]:
    """A Radau step, split in halves (up to 4 times) where Newton fails: a tension switching
    between slack and taut inside the step can make Newton cycle."""
    try:
        return _radau_step(model, t, y, h, exc, scale, U, derivative)
    except ConvergenceError:
        if depth >= 4:
            raise
    y1, S1 = _robust_step(model, t, y, 0.5 * h, exc, scale, U, derivative, depth + 1)
    y2, S2 = _robust_step(model, t + 0.5 * h, y1, 0.5 * h, exc, scale, U, derivative,
                          depth + 1)
    return y2, [b @ a for a, b in zip(S1, S2)]


def steps_per_period_of(model: CablePendulum, exc: Any, steps_min: int,
                        steps_per_cycle: int) -> NDArray[np.int64]:
    f = exc.freq_hz
    fn = max(model.natural_frequency_hz(), 1.0)
    n = np.maximum(steps_min, np.ceil(steps_per_cycle * fn / f))
    return (2 ** np.ceil(np.log2(n))).astype(int)       # powers of two: few distinct groups


def period_map(model: CablePendulum, y: NDArray[np.float64], exc: Any, n_steps: int,
               scale: NDArray[np.float64], U: NDArray[np.float64] | None = None,
               derivative: tuple[NDArray[np.float64], ...] = (),
               t0: float = 0.0) -> tuple[NDArray[np.float64], list[NDArray[np.float64]]]:
    """Integrate one excitation period from t0: y(T_e), and the monodromy matrix in each basis
    of ``derivative``."""
    c, ny = y.shape
    h = 2 * np.pi / exc.omega / n_steps
    t = np.full(c, float(t0))
    M = [np.broadcast_to(np.eye(W.shape[1]), (c, W.shape[1], W.shape[1])).copy()
         for W in derivative]
    for k in range(n_steps):
        y, S = _robust_step(model, t + k * h, y, h, exc, scale, U, derivative)
        M = [s @ m for s, m in zip(S, M)]
    return y, M


def mirror_bases(model: CablePendulum) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Orthonormal bases (U_sym, U_anti) of the states that the mirror x -> -x keeps,
    resp. reverses; shapes (n_y, 4 n) and (n_y, 4 n + 2)."""
    n, nq = model.n_masses, model.n_dof
    S = np.zeros((nq, nq))
    S[0, 0] = -1.0
    for j in range(n):
        for k, sgn in ((0, -1.0), (1, 1.0)):
            i1, i2 = 1 + 2 * j + k, 1 + 2 * n + 2 * j + k
            S[i1, i2] = S[i2, i1] = sgn
    w, U = np.linalg.eigh(np.kron(np.eye(2), S))
    return U[:, w > 0], U[:, w < 0]

