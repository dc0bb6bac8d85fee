"""Energy-consistent forces of a time step: the discrete gradient of the potential energy of
the lumped-mass robot between two configurations (theory.md §7.3, scheme "energy").

For a segment with potential phi(l) = EA / (2 l0) (l - l0)_+^2 between its vectors d_n and
d_n+1 (lengths l_n, l_n+1), the force

    f = T_sec (d_n + d_n+1) / (l_n + l_n+1),
    T_sec = [phi(l_n+1) - phi(l_n)] / (l_n+1 - l_n),

does exactly the work f . (d_n+1 - d_n) = phi(l_n+1) - phi(l_n) (Gonzalez's discrete
gradient of a central potential). T_sec is the mean tension over [l_n, l_n+1], written
without a division by l_n+1 - l_n: with a = l_n - l0, b = l_n+1 - l0 and k = EA / l0,

    T_sec = k (a + b) / 2                     both taut,
          = 0                                 both slack,
          = k max(a, b)^2 / (2 |b - a|)       slack at one end of the step, taut at the other.

It is continuous and once differentiable in the end state, so a Newton iteration crosses a
slack/taut switch without the kink of the tension law. The weights are linear in the
configuration and need no averaging. The platform moves by the increment (dp, dtheta),
R_n+1 = exp([dtheta]x) R_n, so a point r of it moves by dp + dtheta x r_bar with
r_bar = Phi(dtheta) r_n, Phi(theta) = int_0^1 exp(s [theta]x) ds: a force f at that point
(a segment's end force, a weight) enters the platform's generalised force as (f, r_bar x f),
whose work is exactly f . (B_n+1 - B_n). Altogether

    R_bar . d = -(V(q_n+1) - V(q_n))

for the elastic and gravity energy V of theory.md §7.3, whatever the step, slack segments and
snaps included: with the momentum balance written at the mid-step, the scheme conserves the
energy of the cables and the translating platform to the Newton tolerance.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.robot.platform import skew

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.models.lumped_robot import LumpedMassModel

__all__ = ["rotation_mean", "secant_tension", "discrete_gradient_force", "secant_elements"]


def rotation_mean(theta: NDArray[np.float64]) -> NDArray[np.float64]:
    """Phi(theta) = int_0^1 exp(s [theta]x) ds, shape (3, 3) [-], for a rotation vector
    theta (3,) [rad]: I + (1 - cos t) / t^2 [theta]x + (t - sin t) / t^3 [theta]x^2,
    t = |theta|; the first coefficient as 2 sin^2(t/2) / t^2 (no cancellation), the second
    by its series below t = 1e-2."""
    th = np.asarray(theta, dtype=float)
    t = float(np.linalg.norm(th))
    S = skew(th)
    a = 0.5 * np.sinc(t / (2.0 * np.pi)) ** 2
    if t < 1e-2:
        t2 = t * t
        b = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0 - t2**3 / 362880.0
    else:
        b = (t - np.sin(t)) / t**3
    return np.eye(3) + a * S + b * (S @ S)


def secant_tension(l_a: NDArray[np.float64], l_b: NDArray[np.float64],
                   l0: NDArray[np.float64] | float,
                   EA: NDArray[np.float64] | float) -> NDArray[np.float64]:
    """Mean tension T_sec [N] of segments whose length goes from ``l_a`` to ``l_b`` [m]
    (module notes); arrays broadcasting together with l0 [m] and EA [N]."""
    k = EA / l0
    a, b = l_a - l0, l_b - l0
    both = (a >= 0.0) & (b >= 0.0)
    hi = np.maximum(np.maximum(a, b), 0.0)
    gap = np.abs(b - a)
    with np.errstate(divide="ignore", invalid="ignore"):
        one = np.where(gap > 0.0, hi * hi / (2.0 * gap), 0.0)
    return k * np.where(both, 0.5 * (a + b), one)


def discrete_gradient_force(model: LumpedMassModel, nodes_a: list[NDArray[np.float64]],
                            nodes_b: list[NDArray[np.float64]], r_a: NDArray[np.float64],
                            theta: NDArray[np.float64], r_G: NDArray[np.float64],
                            g_vec: NDArray[np.float64], dashpot: NDArray[np.float64] | None = None,
                            h: float | None = None) -> tuple[NDArray[np.float64], float, float]:
    """Generalised force R_bar (n_dof,) [N, N m] with R_bar . d = -(V_b - V_a) - D.

    Parameters
    ----------
    model : LumpedMassModel
        Unstretched segment lengths, node masses and DOF layout of the step (the mid-step
        lengths when winches move).
    nodes_a, nodes_b : list of ndarray, shape (N_i + 1, 3)
        Node positions of every cable at the start and end of the step [m], anchor first,
        B_i last.
    r_a : ndarray, shape (n_cables, 3)
        Lever arms R_n b_i at the start [m].
    theta : ndarray, shape (3,)
        Rotation increment of the step [rad] (zero without free rotations).
    r_G : ndarray, shape (3,)
        Lever arm of the platform's centre of mass at the start [m].
    g_vec : ndarray, shape (3,)
        Gravity [m/s^2].
    dashpot : ndarray, shape (n_cables,), optional
        Axial dashpots c_ax [N s] per cable, with ``h`` the step [s]: the mean dashpot
        force over the step, c_ax theta (l_b - l_a) / (h l0), theta the fraction of
        [l_a, l_b] above l0, joins the secant tension (continuous where a segment goes
        taut or slack within the step; it dissipates D = sum c_ax theta (l_b - l_a)^2 /
        (h l0) >= 0).

    Returns
    -------
    R_bar : ndarray, shape (n_dof,)
    t_max : float
        Largest secant tension [N].
    dissipated : float
        D [J].
    """
    rob = model.robot
    Phi = rotation_mean(theta)
    EA = np.array([c.EA for c in rob.cables])
    W = np.zeros(6)
    if np.all(model.segments == model.segments[0]):          # all chains at once
        xa, xb = np.stack(nodes_a), np.stack(nodes_b)
        da, db = np.diff(xa, axis=1), np.diff(xb, axis=1)
        la, lb = np.sqrt(np.sum(da * da, axis=2)), np.sqrt(np.sum(db * db, axis=2))
        T = secant_tension(la, lb, model.segment_lengths[:, None], EA[:, None])
        T_d, dissipated = _mean_dashpot(la, lb, model.segment_lengths[:, None], dashpot, h)
        t_max = float(T.max())
        T = T + T_d
        f = (T / (la + lb))[..., None] * (da + db)             # pulls node j towards j+1
        w = model.node_masses[:, None] * g_vec
        inner = (f[:, 1:] - f[:, :-1] + w[:, None, :]).ravel()
        fB = -f[:, -1] + 0.5 * w                               # (n, 3)
        W[:3] += fB.sum(axis=0)
        W[3:] += cross(np.asarray(r_a) @ Phi.T, fB).sum(axis=0)
    else:
        parts, t_max, dissipated = [], 0.0, 0.0
        for i, (xa, xb) in enumerate(zip(nodes_a, nodes_b)):
            da, db = np.diff(xa, axis=0), np.diff(xb, axis=0)
            la, lb = np.linalg.norm(da, axis=1), np.linalg.norm(db, axis=1)
            T = secant_tension(la, lb, model.segment_lengths[i], EA[i])
            t_max = max(t_max, float(T.max()))
            T_d, D = _mean_dashpot(la, lb, model.segment_lengths[i],
                                   None if dashpot is None else dashpot[i:i + 1], h)
            dissipated += D
            T = T + T_d
            f = (T / (la + lb))[:, None] * (da + db)
            w = model.node_masses[i] * g_vec
            parts.append((f[1:] - f[:-1] + w).ravel())
            fB = -f[-1] + 0.5 * w
            W[:3] += fB
            W[3:] += cross(Phi @ r_a[i], fB)
        inner = np.concatenate(parts)
    fg = rob.platform.mass * g_vec
    W[:3] += fg
    W[3:] += cross(Phi @ r_G, fg)
    R = np.empty(model.n_dof)
    R[:model.n_free] = W[model.free_index]
    R[model.n_free:] = inner
    return R, t_max, dissipated


def _mean_dashpot(la: NDArray[np.float64], lb: NDArray[np.float64], l0: NDArray[np.float64],
                  dashpot: NDArray[np.float64] | None,
                  h: float | None) -> tuple[NDArray[np.float64] | float, float]:
    """Mean axial dashpot force over a step [N], shape of la, and its dissipation [J]
    (:func:`discrete_gradient_force`); dashpot (n,) or None."""
    if dashpot is None or not np.any(dashpot):
        return 0.0, 0.0
    c = np.asarray(dashpot, dtype=float).reshape((-1,) + (1,) * (np.ndim(la) - 1))
    if np.ndim(la) == 1:
        c = c.reshape(())
    hi = np.maximum(la, lb)
    gap = np.abs(lb - la)
    with np.errstate(divide="ignore", invalid="ignore"):
        theta = np.where(gap > 0.0, np.clip((hi - l0) / gap, 0.0, 1.0),
                         (hi > l0).astype(float))
    rate = (lb - la) / (h * l0)
    T_d = c * theta * rate
    return T_d, float(np.sum(T_d * (lb - la)))

def secant_elements(model: LumpedMassModel, nodes_a: list[NDArray[np.float64]],
                    nodes_b: list[NDArray[np.float64]], dashpot: NDArray[np.float64],
                    dt: float) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """Newton elements of the energy scheme: per cable (K_e (N_i, 3, 3) [N/m], force on the
    platform at B_i (3,) [N]), K_e = 2 [T_sec' m m^T + T_sec / (l_a + l_b) (I - m m^T)]
    + 2 c_ax / (dt l0) m m^T (taut), m the unit vector of d_a + d_b and T_sec' = dT_sec /
    dl_b, the derivative of the secant force with respect to the end state (twice: the
    Newton matrix of the energy scheme is half of K + 4 M / dt^2 + 2 C / dt); the axial
    dashpots ``dashpot`` [N s] per cable."""
    g_vec = model.robot.gravity_vector
    out = []
    for i, (xa, xb) in enumerate(zip(nodes_a, nodes_b)):
        da, db = np.diff(xa, axis=0), np.diff(xb, axis=0)
        la, lb = np.linalg.norm(da, axis=1), np.linalg.norm(db, axis=1)
        l0, EA = model.segment_lengths[i], model.robot.cables[i].EA
        k = EA / l0
        a, b = la - l0, lb - l0
        T = secant_tension(la, lb, l0, EA)
        with np.errstate(divide="ignore", invalid="ignore"):
            gap2 = 2.0 * (b - a) ** 2
            rising = np.where(gap2 > 0, k * b * (b - 2.0 * a) / gap2, 0.5 * k)
            falling = np.where(gap2 > 0, k * a * a / gap2, 0.5 * k)
        dT = np.where((a >= 0) & (b >= 0), 0.5 * k,
                      np.where((a < 0) & (b >= 0), rising,
                               np.where((b < 0) & (a >= 0), falling, 0.0)))
        s = da + db
        mm = s / np.linalg.norm(s, axis=1)[:, None]
        nn = mm[:, :, None] * mm[:, None, :]
        axial = 2.0 * dT + np.where(b > 0, 2.0 * dashpot[i] / (dt * l0), 0.0)
        ke = axial[:, None, None] * nn + (2.0 * T / (la + lb))[:, None, None] * (np.eye(3) - nn)
        f_end = T[-1] / (la[-1] + lb[-1]) * s[-1]
        out.append((ke, -f_end + 0.5 * model.node_masses[i] * g_vec))
    return out
