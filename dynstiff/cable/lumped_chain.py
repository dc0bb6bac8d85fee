"""Lumped-mass (bead-and-spring) model of one heavy elastic cable: statics (the linear
dynamics about the equilibrium are in :mod:`dynstiff.cable.lumped_chain_dynamics`).

This is the independent cross-check of the closed-form cable dynamic stiffness
(theory.md §7, §9.2). It uses no catenary closed form: the equilibrium is found by its own
Newton method on the interior node coordinates.

Notation (theory.md §7.1)
-------------------------
=================  ==============================================================  =======
symbol             meaning                                                         unit
=================  ==============================================================  =======
N                  number of segments; nodes 0..N, node 0 = anchor A, node N = B   --
L0                 unstretched cable length                                        m
l0                 unstretched segment length, L0 / N                              m
m                  mass per unstretched length                                     kg/m
EA                 axial stiffness, tension T = EA (l / l0 - 1) if l > l0 else 0    N
c, eta             viscous damping per length, hysteretic loss factor              N s/m^2, --
d_i                segment vector x_{i+1} - x_i, length l_i, unit vector n_i         m, m, --
T_i                tension of segment i                                            N
m l0, m l0 / 2     mass of an interior node, of an end node                        kg
K_e                element tangent stiffness (EA/l0) n n^T + (T/l)(I - n n^T)       N/m
=================  ==============================================================  =======

Gravity is (0, 0, -g) (z up). The interior nodes carry the weight m l0 g; the end nodes are
prescribed, so their half masses enter only the dynamic condensation.

Conventions: stiffness matrices give the force that must be *applied* to the nodes per unit
displacement (K u = f_applied); the degree-of-freedom order is node-major,
(x_0, y_0, z_0, x_1, ..., z_N).
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import point, positive_scalar
from dynstiff.cable.lumped_elements import (
    BANDWIDTH,
    element_stiffness,
    interior_banded,
    interior_forces,
    potential_energy,
    segments_from_vectors,
    update_segments,
)
from dynstiff.constants import STANDARD_GRAVITY
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError
from dynstiff.params import Cable

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["ChainState", "chain_equilibrium"]

_EZ = np.array([0.0, 0.0, 1.0])


# ------------------------------------------------------------------------ initial guess
def _tension_estimate(anchor: NDArray[np.float64], end: NDArray[np.float64],
                      unstretched_length: float, cable: Cable, g: float) -> float:
    """Rough chord tension [N] of a parabolic elastic cable, used to seed the statics.

    Solves L (1 + (8/3)(d/L)^2) = L0 (1 + T/EA) with d = q L^2 / (8 T) and
    q = m g cos(theta) (theory.md §1.2: sag d, parabolic arc length). Without a transverse
    load (vertical chord or g = 0) it returns EA (L/L0 - 1)_+ + m g L0.
    """
    import scipy.optimize
    chord = end - anchor
    length = np.linalg.norm(chord)
    cos_theta = np.hypot(chord[0], chord[1]) / length
    q = cable.mass_per_length * g * cos_theta
    EA, L0 = cable.EA, unstretched_length
    straight = EA * max(length / L0 - 1.0, 0.0)
    if q <= 0.0 or cos_theta < 1e-9:
        return straight + cable.mass_per_length * g * L0

    def mismatch(T: float) -> float:
        return length * (1.0 + (8.0 / 3.0) * (q * length / (8.0 * T)) ** 2) - L0 * (1.0 + T / EA)

    t_lo, t_hi = q * length, q * length + straight
    while mismatch(t_lo) <= 0.0:
        t_lo *= 0.5
    while mismatch(t_hi) >= 0.0:
        t_hi *= 2.0
    return scipy.optimize.brentq(mismatch, t_lo, t_hi, xtol=1e-12 * t_hi, rtol=1e-10)


def _force_space_start(anchor: NDArray[np.float64], end: NDArray[np.float64],
                       unstretched_length: float, cable: Cable, n_segments: int, g: float,
                       max_iter: int = 50) -> NDArray[np.float64]:
    """Starting nodes from the chain's equations written for the force in the first segment.

    Node equilibrium makes the segment forces f_i = f_0 + i m l0 g e_z (i = 0..N-1), and a
    segment carrying f has the vector d(f) = l0 (1 + |f|/EA) f / |f|. The chain closes,
    sum_i d(f_i) = B - A, at the minimum of the strictly convex complementary energy

        Phi(f_0) = sum_i l0 (|f_i| + |f_i|^2 / (2 EA)) - f_0 . (B - A),

    whose gradient is sum_i d_i - (B - A) and whose Hessian is the sum of the segment
    compliances. |f| is not smooth at f = 0 (a slack segment) and Newton's method can stall
    there, so |f| is replaced by sqrt(|f|^2 + delta^2) and delta is decreased geometrically
    to 0 (continuation), each stage a damped Newton solve in the three unknowns f_0,
    started from the parabolic tension estimate. This is only the starting point of the
    interior-node Newton of `chain_equilibrium`; it uses no catenary closed form.

    Returns
    -------
    ndarray, shape (N+1, 3)
        Node positions [m]; the last one is set to ``end`` (the closure error of an
        unconverged start is left in the last segment).
    """
    chord = end - anchor
    length = np.linalg.norm(chord)
    l0 = unstretched_length / n_segments
    EA = cable.EA
    w = cable.mass_per_length * l0 * g
    lift = (np.arange(n_segments) * w)[:, None] * _EZ
    T0 = _tension_estimate(anchor, end, unstretched_length, cable, g)
    scale = T0 + w * n_segments
    eye = np.eye(3)

    def phi(f0: NDArray[np.float64], delta: float) -> float:
        T2 = np.sum((f0 + lift) ** 2, axis=1)
        return l0 * np.sum(np.sqrt(T2 + delta * delta) + T2 / (2.0 * EA)) - np.dot(f0, chord)

    def newton(f0: NDArray[np.float64], delta: float, gtol: float) -> NDArray[np.float64]:
        value = phi(f0, delta)
        for _ in range(max_iter):
            f = f0 + lift
            r = np.sqrt(np.sum(f * f, axis=1) + delta * delta)
            if np.any(r == 0.0):
                break
            grad = l0 * np.sum(f / r[:, None] + f / EA, axis=0) - chord
            if np.linalg.norm(grad) <= gtol:
                break
            # segment compliance (|f|^2 + delta^2) I - f f^T over r^3, its diagonal written
            # without the cancellation 1/r - f_z^2/r^3 (for a nearly straight, nearly slack
            # segment along z that difference is below the rounding of 1/r and the 1/EA
            # term, the only one left, would be lost)
            sq = f * f
            other = np.stack([sq[:, 1] + sq[:, 2], sq[:, 0] + sq[:, 2],
                              sq[:, 0] + sq[:, 1]], axis=1) + delta * delta
            r3 = r ** 3
            hess = -np.einsum("i,ij,ik->jk", 1.0 / r3, f, f)
            hess[np.diag_indices(3)] = np.sum(other / r3[:, None], axis=0)
            hess = l0 * (n_segments / EA * eye + hess)
            try:
                step = -np.linalg.solve(hess, grad)
            except np.linalg.LinAlgError:
                break                      # only a starting point: the node Newton goes on
            slope = np.dot(grad, step)
            alpha = 1.0
            while alpha > 1e-10:
                trial = f0 + alpha * step
                trial_value = phi(trial, delta)
                if trial_value <= value + 1e-4 * alpha * slope:
                    break
                alpha *= 0.5
            else:
                break
            f0, value = trial, trial_value
        return f0

    f0 = T0 * chord / length - 0.5 * (n_segments - 1) * w * _EZ
    delta = scale
    while delta > 1e-10 * scale:
        f0 = newton(f0, delta, 1e-6 * unstretched_length)
        delta *= 0.1
    f0 = newton(f0, 0.0, 1e-14 * unstretched_length)
    f = f0 + lift
    T = np.linalg.norm(f, axis=1)
    units = np.divide(f, T[:, None], out=np.tile(chord / length, (n_segments, 1)),
                      where=T[:, None] > 0)
    d = (l0 * (1.0 + T / EA))[:, None] * units
    nodes = anchor + np.vstack((np.zeros(3), np.cumsum(d, axis=0)))
    nodes[-1] = end
    return nodes


def _slack_segment(chord: NDArray[np.float64], unstretched_length: float, cable: Cable,
                   n_segments: int, g: float):
    """Index of the segment that is slack at equilibrium, or None if the chain is taut.

    At equilibrium the segment forces are f_i = f_0 + i m l0 g e_z. A segment k with zero
    force therefore forces f_i = (i - k) m l0 g e_z on all the others: they hang vertically,
    down from A to node k and up from node k+1 to B, with tensions |i - k| m l0 g. Segment k
    must then bridge the remaining gap within its unstretched length l0. Because the
    complementary energy (see `_force_space_start`) is strictly convex, the equilibrium
    forces are unique, so this test is exact: the chain has a zero-tension segment if and
    only if min_k |B - A - s_k| <= l0, with s_k the vector sum of the hanging segments. For
    g = 0 all forces are equal and the chain is slack iff |B - A| <= L0.

    Returns
    -------
    int or None
        k, or None when every segment is stretched.
    """
    l0 = unstretched_length / n_segments
    w = cable.mass_per_length * l0 * g
    if w == 0.0:
        return 0 if np.linalg.norm(chord) <= unstretched_length else None
    k = np.arange(n_segments, dtype=float)
    up = n_segments - 1 - k                       # segments above node k+1, hanging up to B
    # s_k,z = sum_{j=1}^{up} l0 (1 + j w/EA) - sum_{j=1}^{k} l0 (1 + j w/EA)
    s_z = l0 * (up - k) + l0 * w / cable.EA * 0.5 * (up * (up + 1) - k * (k + 1))
    gap = np.hypot(np.hypot(chord[0], chord[1]), chord[2] - s_z)
    best = int(np.argmin(gap))
    return best if gap[best] <= l0 else None


# ---------------------------------------------------------------------------- result type
@dataclass(frozen=True, eq=False)
class ChainState:
    """Static equilibrium of the lumped-mass chain (result of `chain_equilibrium`).

    Attributes
    ----------
    nodes : ndarray, shape (N+1, 3)
        Node positions [m]; nodes[0] is the anchor A, nodes[-1] the end B.
    tensions : ndarray, shape (N,)
        Segment tensions T_i [N], segment i joining node i and node i+1.
    lengths : ndarray, shape (N,)
        Stretched segment lengths l_i [m].
    cable : Cable
        Cable properties.
    g : float
        Gravitational acceleration [m/s^2] used for the weights.
    n_segments : int
        N.
    unstretched_length : float
        L0 [m].
    residual : float
        Largest net force on an interior node at the solution [N].
    """

    nodes: np.ndarray
    tensions: np.ndarray
    lengths: np.ndarray
    cable: Cable
    g: float
    n_segments: int
    unstretched_length: float
    residual: float

    @property
    def segment_length(self) -> float:
        """Unstretched segment length l0 = L0 / N [m]."""
        return self.unstretched_length / self.n_segments

    @property
    def units(self) -> NDArray[np.float64]:
        """Unit vectors n_i of the segments, from node i to node i+1, shape (N, 3) [-]."""
        d = np.diff(self.nodes, axis=0)
        return d / np.linalg.norm(d, axis=1)[:, None]

    @property
    def force_on_end(self) -> NDArray[np.float64]:
        """Force the cable exerts on the end B, shape (3,) [N] (points towards node N-1)."""
        return -self.tensions[-1] * self.units[-1]

    @property
    def force_on_anchor(self) -> NDArray[np.float64]:
        """Force the cable exerts on the anchor A, shape (3,) [N] (points towards node 1)."""
        return self.tensions[0] * self.units[0]


# ------------------------------------------------------------------------------- analyses
def checked_integer(name: str, value: int, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise InvalidParameterError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if value < minimum:
        raise InvalidParameterError(f"{name} must be >= {minimum}, got {value!r}")
    return int(value)


def chain_equilibrium(anchor: ArrayLike, end: ArrayLike, unstretched_length: float, cable: Cable,
                      n_segments: int, g: float = STANDARD_GRAVITY, tol: float = 1e-12,
                      max_iter: int = 100) -> ChainState:
    """Static equilibrium of a lumped-mass cable hanging between a fixed anchor and an end.

    Newton's method on the 3(N-1) interior node coordinates with the analytic tangent
    stiffness (block tridiagonal, solved by a banded Cholesky factorisation), globalised by
    a backtracking line search on the total potential energy (convex for tension-only
    springs). The iterate is stored as segment strains and unit vectors, so the tensions
    are not polluted by the rounding of the coordinates (which would limit them to about
    EA x 1e-16). The start comes from a three-unknown Newton solve of the same chain
    equations written for the force in the first segment (see `_force_space_start`;
    seeded by a parabolic tension estimate), so that slack, steep and vertical chords
    converge as reliably as taut ones. No catenary closed form is used. Theory:
    theory.md §7.1.

    Parameters
    ----------
    anchor : array_like, shape (3,)
        Anchor point A [m] (node 0), clamped.
    end : array_like, shape (3,)
        End point B [m] (node N), prescribed.
    unstretched_length : float
        L0 [m], > 0.
    cable : Cable
        Mass per unstretched length m [kg/m] and axial stiffness EA [N].
    n_segments : int
        N >= 1.
    g : float, optional
        Gravitational acceleration [m/s^2], >= 0; gravity is (0, 0, -g).
    tol : float, optional
        Converged when max_i |F_i| <= tol (m g L0 + max_i T_i), F_i the net force on
        interior node i [N].
    max_iter : int, optional
        Maximum number of Newton iterations.

    Returns
    -------
    ChainState
        Node positions, tensions, lengths and the final residual.

    Raises
    ------
    InvalidParameterError
        For an invalid argument (named in the message), e.g. ``anchor`` equal to ``end``.
    ConvergenceError
        If Newton's method did not reach ``tol``; the message and ``.residual`` give the
        residual [N].
    SlackCableError
        If the converged chain has a segment with zero tension.
    """
    anchor = point("anchor", anchor)
    end = point("end", end)
    L0 = positive_scalar("unstretched_length", unstretched_length)
    if not isinstance(cable, Cable):
        raise InvalidParameterError(f"cable must be a Cable, got {type(cable).__name__}")
    n_segments = checked_integer("n_segments", n_segments, 1)
    g = positive_scalar("g", g, allow_zero=True)
    tol = positive_scalar("tol", tol)
    max_iter = checked_integer("max_iter", max_iter, 1)
    chord = np.linalg.norm(end - anchor)
    if chord == 0.0:
        raise InvalidParameterError(
            f"end must differ from anchor, both are {anchor.tolist()}")

    slack = _slack_segment(end - anchor, L0, cable, n_segments, g)
    if slack is not None:
        how = ("the chain hangs vertically from both ends and that segment is slack"
               if g > 0 else "without gravity every segment is slack when L0 >= chord")
        raise SlackCableError(
            f"chain_equilibrium: segment {slack} of {n_segments} has zero tension at "
            f"equilibrium: {how} (unstretched_length {L0:g} m, chord {chord:g} m, "
            f"g {g:g} m/s^2)")
    l0 = L0 / n_segments
    EA = cable.EA
    nodes = _force_space_start(anchor, end, L0, cable, n_segments, g)
    strain, units, res, iteration = _newton(
        nodes, l0, EA, cable.mass_per_length * L0 * g, cable.mass_per_length * l0 * g,
        tol, max_iter)
    if iteration > max_iter:
        raise ConvergenceError(
            f"chain_equilibrium did not converge in {max_iter} Newton iterations: "
            f"residual {res:.3e} N (tolerance {tol:g} x (weight + max tension))",
            residual=res)
    if iteration < 0:
        raise ConvergenceError(
            f"chain_equilibrium: no descent step found (line search failed or the tangent "
            f"stiffness is singular, e.g. all segments slack), residual {res:.3e} N",
            residual=res)

    tensions = EA * np.maximum(strain, 0.0)
    lengths = l0 * (1.0 + strain)
    slack = np.flatnonzero(tensions <= 0.0)
    if slack.size:
        raise SlackCableError(
            f"chain_equilibrium: segment(s) {slack[:5].tolist()} of {n_segments} have zero "
            f"tension at equilibrium (unstretched_length {L0:g} m, chord {chord:g} m)")
    nodes = anchor + np.vstack((np.zeros(3), np.cumsum(lengths[:, None] * units, axis=0)))
    nodes[-1] = end
    for arr in (nodes, tensions, lengths):
        arr.setflags(write=False)
    return ChainState(nodes=nodes, tensions=tensions, lengths=lengths, cable=cable, g=g,
                      n_segments=n_segments, unstretched_length=L0, residual=float(res))


def _newton(nodes: NDArray[np.float64], l0: float, EA: float, total_weight: float,
            node_weight: float, tol: float,
            max_iter: int) -> tuple[NDArray[np.float64], NDArray[np.float64], float, int]:
    """Damped Newton iteration on the interior nodes of a chain (kernel of `chain_equilibrium`).

    Parameters
    ----------
    nodes : ndarray, shape (N+1, 3)
        Starting node positions [m]; the end nodes are kept fixed.
    l0, EA, total_weight, node_weight : float
        Segment length [m], axial stiffness [N], weight of the cable and of an interior
        node [N].
    tol : float
        Relative tolerance on the largest net nodal force, scaled by weight + max tension.
    max_iter : int
        Maximum number of iterations.

    Returns
    -------
    strain : ndarray, shape (N,)
    units : ndarray, shape (N, 3)
    residual : float
        Largest net force on an interior node [N].
    iterations : int
        Iterations used; max_iter + 1 if not converged, -1 if no descent step was found.
    """
    seg = np.diff(nodes, axis=0)
    seg[-1] = (nodes[-1] - nodes[0]) - np.sum(seg[:-1], axis=0)   # exact closure
    strain, units = segments_from_vectors(seg, l0)

    def measure(eps: NDArray[np.float64],
                n: NDArray[np.float64]) -> tuple[NDArray[np.float64], float, bool]:
        forces = interior_forces(eps, n, EA, node_weight)
        res = np.max(np.linalg.norm(forces, axis=1)) if forces.size else 0.0
        return forces, res, res <= tol * (total_weight + EA * max(np.max(eps), 0.0))

    forces, res, done = measure(strain, units)
    energy = potential_energy(strain, units, l0, EA, node_weight)
    iteration = 0
    while not done:
        if iteration == max_iter:
            return strain, units, res, max_iter + 1
        iteration += 1
        ke = element_stiffness(units, l0 * (1.0 + strain), EA * np.maximum(strain, 0.0),
                                np.where(strain > 0, EA / l0, 0.0))
        step = _regularised_solve(interior_banded(ke), forces.ravel())
        if step is None:
            return strain, units, res, -1
        step = step.reshape(-1, 3)
        dseg = np.diff(np.vstack((np.zeros(3), step, np.zeros(3))), axis=0)
        slope = -np.dot(forces.ravel(), step.ravel())      # d(energy)/d(alpha) at 0, < 0
        alpha = 1.0
        for _ in range(60):
            trial = update_segments(strain, units, l0, alpha * dseg)
            trial_energy = potential_energy(*trial, l0, EA, node_weight)
            trial_forces, trial_res, trial_done = measure(*trial)
            if (trial_energy <= energy + 1e-4 * alpha * slope
                    or np.linalg.norm(trial_forces) < np.linalg.norm(forces)):
                break
            alpha *= 0.5
        else:
            return strain, units, res, -1
        (strain, units), energy = trial, trial_energy
        forces, res, done = trial_forces, trial_res, trial_done
    return strain, units, res, iteration


def _regularised_solve(ab: NDArray[np.float64],
                       rhs: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Solve K x = rhs for symmetric positive semi-definite banded K (upper form).

    A slack segment has no stiffness, so K may be singular during the iterations; then a
    small multiple of the largest diagonal entry is added (Levenberg-Marquardt), which keeps
    the step a descent direction of the energy. Returns None if even the shifted matrix
    cannot be factorised.
    """
    import scipy.linalg
    if ab.shape[1] == 0:
        return rhs
    shift = 0.0
    scale = np.max(np.abs(ab[BANDWIDTH]))
    for _ in range(20):
        shifted = ab.copy()
        shifted[BANDWIDTH] += shift
        try:
            return scipy.linalg.solveh_banded(shifted, rhs, check_finite=False)
        except np.linalg.LinAlgError:
            shift = 1e-10 * scale if shift == 0.0 else 100.0 * shift
    return None


def check_chain_state(state: str | ChainState) -> None:
    if not isinstance(state, ChainState):
        raise InvalidParameterError(
            f"state must be a ChainState, got {type(state).__name__}")
