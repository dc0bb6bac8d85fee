"""The energy-consistent time step of the lumped-mass robot and its step control (scheme
"energy", theory.md §7.3). Internal to :mod:`dynstiff.timedomain.simulation`.

One step from t_a to t_b = t_a + h: unknown the increment d (platform (dp, dtheta), nodes);
v_b = 2 d / h - v_a; the momentum balance at the mid-step,

    M_mid (v_b - v_a) / h = R_bar + (f_ext,a + f_ext,b) / 2 + (f_d,a + f_d,b) / 2
                            - (g_a + g_b) / 2,

with R_bar the discrete gradient of the elastic and gravity energy between q_a and q_b at
the mid-step unstretched lengths (:mod:`dynstiff.timedomain.discrete_gradient`), M_mid the
mid-step node masses and the mean of the platform's mass matrix at both poses, g the
centripetal and gyroscopic terms. For the cables and the translating platform
R_bar . d = -(V_b - V_a) exactly, so the energy is conserved to the Newton tolerance through
slack and snap: the scheme is stable on the compression-free segment law, which the
trapezoidal rule of the "implicit" scheme is not (its force at the end of a step that
crosses l = l0 misses the kink, and the snaps feed energy into the run).

Newton's method (modified: the LU factors of the secant Newton matrix, half of
K_sec + 4 M / dt^2 + 2 C / dt, kept while each iteration reduces the residual tenfold),
started from the constant-velocity guess d = h v_a. Step control: a step whose Newton
iteration fails (no convergence in ``max_iter``, a non-finite state, or a residual grown a
thousandfold) is retried as two half steps, down to dt / 2^``MAX_HALVINGS``; the records
stay on the dt grid.

The energy ledger (theory.md §7.3) is kept per sub-step: the external and damping work as
the trapezoidal rule of the forces over the increment (what the scheme applies), the winch
work as the change of V with the unstretched lengths at fixed configuration, L_a -> L_mid at
q_a and L_mid -> L_b at q_b (what the discrete gradient leaves out, exactly), the kinetic
energy carried in with the paid-out mass as 1/4 dmu (|v_a|^2 + |v_b|^2) (exact for the nodes
with the mid-step masses).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import ConvergenceError
from dynstiff.timedomain.discrete_gradient import discrete_gradient_force, secant_elements
from dynstiff.timedomain.dynamics import (
    advance,
    gyroscopic,
    interior_views,
    model_at,
    node_mass_vector,
    twist_of,
)
from dynstiff.timedomain.stepping import carried_energy

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.models.lumped_robot import LumpedMassModel
    from dynstiff.timedomain.dynamics import Dynamics, FastPose, Frame
    from dynstiff.timedomain.stepping import StepNewton

__all__ = ["EnergyStepper", "MAX_HALVINGS"]

#: Halvings of a step whose Newton iteration fails (theory.md §7.3).
MAX_HALVINGS = 10
#: Growth of the residual over its first value that ends a Newton iteration as failed.
_DIVERGED = 1e3


class _Failed(Exception):
    """A step's Newton iteration failed (the step is retried as two halves)."""

    def __init__(self, message: str, residual: float) -> None:
        super().__init__(message)
        self.residual = residual


class EnergyStepper:
    """Energy-consistent steps with step control for one run (module notes).

    Parameters
    ----------
    dyn : Dynamics
        Forces, mass and Newton matrix; its model is switched to the model at the end of
        every (sub-)step.
    model : LumpedMassModel
        The model at the run's start lengths (segments, robot).
    length_fn : callable or None
        t [s] -> unstretched lengths (n_cables,) [m] (winches), or None (fixed lengths).
    newton : StepNewton
        Tolerance, iteration limit, kept LU factors and counters.

    Attributes
    ----------
    substeps : int
        Steps that were split (each halving counts once).
    """

    def __init__(self, dyn: Dynamics, model: LumpedMassModel, length_fn: Callable[..., Any] | None,
                 newton: StepNewton) -> None:
        self.dyn, self.model, self.length_fn, self.newton = dyn, model, length_fn, newton
        self.substeps = 0

    def _model(self, t: float) -> LumpedMassModel:
        if self.length_fn is None:
            return self.model
        return model_at(self.model, self.length_fn(t))

    def step(
            self, pose: FastPose, X: NDArray[np.float64], v: NDArray[np.float64],
            fe: NDArray[np.float64], fd: NDArray[np.float64], frame: Frame, t_a: float, dt: float,
            k: int,
    ) -> tuple[tuple[NDArray[np.float64] | FastPose | Frame, ...], NDArray[np.float64]]:
        """One step of ``dt`` [s] from t_a [s] (step k of the run; ``frame`` the platform
        terms at the start), halved where Newton fails. Returns (pose, X, v, a, fe, fd,
        frame) at t_a + dt and the ledger increments (external work, dissipated, winch
        work, carried energy) [J]."""
        m_a = self._model(t_a)
        if k == 1:           # the start's damping force without the axial dashpots
            self.dyn.set_model(m_a)
            fd = self.dyn.forces(pose, X, v, t_a, dashpots=False)[2]
        state = (pose, X, v, fe, fd, frame)
        work = np.zeros(4)
        out = self._interval(state, t_a, dt, m_a, k, 0, work)
        return out, work

    def _interval(
            self,
            state: tuple[FastPose, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
                         NDArray[np.float64], Frame],
            t_a: float, h: float, m_a: LumpedMassModel, k: int, depth: int,
            work: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64] | FastPose | Frame, ...]:
        m_b = self._model(t_a + h)
        try:
            return self._single(state, t_a, h, m_a, m_b, k, work)
        except _Failed as fail:
            if depth >= MAX_HALVINGS:
                raise ConvergenceError(
                    f"simulate: the energy scheme's Newton iteration did not converge at step "
                    f"{k} (t = {t_a + h:g} s) even with the step halved {MAX_HALVINGS} times "
                    f"(to {h:g} s): {fail}", residual=fail.residual) from None
        self.substeps += 1
        m_h = self._model(t_a + 0.5 * h)
        first = self._interval(state, t_a, 0.5 * h, m_a, k, depth + 1, work)
        pose, X, v, _, fe, fd, frame = first
        return self._interval((pose, X, v, fe, fd, frame), t_a + 0.5 * h, 0.5 * h, m_h, k,
                              depth + 1, work)

    def _single(
            self,
            state: tuple[FastPose, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
                         NDArray[np.float64], Frame],
            t_a: float, h: float, m_a: LumpedMassModel, m_b: LumpedMassModel, k: int,
            work: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64] | FastPose | Frame, ...]:
        """One step without step control; raises _Failed. Adds its ledger increments to
        ``work`` only when it succeeds."""
        import scipy.sparse.linalg
        pose, X, v, fe, fd, frame_a = state
        dyn, newton = self.dyn, self.newton
        mid = m_a if m_b is m_a else model_at(
            self.model, 0.5 * (m_a.unstretched_lengths + m_b.unstretched_lengths))
        dyn.set_model(m_b)
        nf = m_b.n_free
        g_vec = m_b.robot.gravity_vector
        nodes_a, _ = mid.full_nodes(pose, interior_views(mid, X))
        g_a = gyroscopic(m_a, frame_a, twist_of(m_a, v))
        mu = node_mass_vector(mid)
        t_b = t_a + h
        if getattr(newton, "h", None) != h:
            newton.lu, newton.h = None, h         # factors of another step size
        d = h * v
        first, prev = None, np.inf
        for it in range(newton.max_iter + 1):
            pose_b, X_b = advance(m_b, pose, X, d)
            v_b = 2.0 * d / h - v
            F_b, fe_b, fd_b, _, frame_b = dyn.forces(pose_b, X_b, v_b, t_b, dashpots=False)
            theta = np.zeros(6)
            theta[m_b.free_index] = d[:nf]
            nodes_b, _ = mid.full_nodes(pose_b, interior_views(mid, X_b))
            R, t_max, D = discrete_gradient_force(mid, nodes_a, nodes_b, frame_a.r,
                                                  theta[3:], frame_a.rG, g_vec, dyn.c_ax, h)
            rate = (v_b - v) / h
            G = np.concatenate([0.5 * (frame_a.Mff + frame_b.Mff) @ rate[:nf], mu * rate[nf:]])
            G -= R + 0.5 * (fe + fe_b + fd + fd_b)
            G[:nf] += 0.5 * (g_a + gyroscopic(m_b, frame_b, twist_of(m_b, v_b)))
            if not (np.all(np.isfinite(G)) and np.all(np.isfinite(d))):
                raise _Failed("non-finite state", np.inf)
            res = m_b.relative_residual(G, t_max)
            first = res if first is None else first
            if res <= newton.tol:
                break
            if it == newton.max_iter or res > _DIVERGED * max(first, newton.tol):
                newton.lu = None
                raise _Failed(f"relative residual {res:.3e} > tol {newton.tol:g} after {it} "
                              f"iterations", res)
            if newton.lu is None or res > 0.1 * prev:
                elements = secant_elements(mid, nodes_a, nodes_b, dyn.c_ax, h)
                newton.lu = scipy.sparse.linalg.splu(
                    0.5 * dyn.newton_matrix(pose_b, X_b, h, elements))
                newton.updates += 1
            prev = res
            d = d - newton.lu.solve(G)
        newton.iterations += it
        work[0] += 0.5 * d @ (fe + fe_b)
        work[1] += D - 0.5 * d @ (fd + fd_b)
        if m_b is not m_a:
            geo_a, geo_b = _geometry(nodes_a), _geometry(nodes_b)
            work[2] += (_stored(mid, geo_a) - _stored(m_a, geo_a)
                        + _stored(m_b, geo_b) - _stored(mid, geo_b))
            dmu = node_mass_vector(m_b) - node_mass_vector(m_a)
            work[3] += 0.25 * (carried_energy(m_b, m_a, frame_a, v, dmu)
                               + carried_energy(m_b, m_a, frame_b, v_b, dmu))
        a_b = dyn.accelerations(frame_b, F_b)
        return pose_b, X_b, v_b, a_b, fe_b, fd_b, frame_b


def _geometry(nodes: list[NDArray[np.float64]]) -> list[tuple[NDArray[np.float64], float]]:
    """Per cable: segment lengths (N_i,) [m] and sum of the interior node heights plus half
    the height of B_i [m] (what the energy depends on at fixed configuration)."""
    return [(np.sqrt(np.sum(np.diff(x, axis=0) ** 2, axis=1)),
             x[1:-1, 2].sum() + 0.5 * x[-1, 2]) for x in nodes]


def _stored(model: LumpedMassModel, geometry: list[tuple[NDArray[np.float64], float]]) -> float:
    """Elastic energy and the cables' gravity energy [J] of ``model``'s unstretched lengths
    and node masses at the configuration ``geometry`` (:func:`_geometry`); the platform's
    own weight is left out (it does not depend on the lengths)."""
    g = model.robot.g
    total = 0.0
    for i, (lengths, zsum) in enumerate(geometry):
        l0, EA = model.segment_lengths[i], model.robot.cables[i].EA
        stretch = np.maximum(lengths - l0, 0.0)
        total += 0.5 * EA / l0 * float(stretch @ stretch) + model.node_masses[i] * g * zsum
    return total
