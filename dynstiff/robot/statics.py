"""Robot statics with sagging cables: inverse statics (the tension distribution is
:mod:`dynstiff.robot.distribution`; forward statics :mod:`dynstiff.robot.forward_statics`).

Inverse statics (pose given, redundant robot): the tensions t at the platform ends solve the
wrench balance W t = -w_g on the free DOFs, W = [u_i; r_i x u_i] with u_i the unit force of
cable i on the platform at B_i. With sag, u_i depends on t_i through the elastic catenary, so
the distribution and the catenaries are iterated to a fixed point. Among the solutions of the
balance, the one closest (2-norm) to a reference tension within [t_min, t_max] is chosen; the
limits hold along the whole cable (a cable running down to its anchor is least tensioned
there, one whose lowest point lies between its ends has the tension H there).
"""

from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import compiled
from dynstiff._validate import tension_reference as checked_reference
from dynstiff._vec import cross
from dynstiff.cable.catenary import catenary_states
from dynstiff.cable.catenary_batch import catenary_arrays, taut_catenaries
from dynstiff.cable.catenary_solve import solve_catenary, unstretched_length_for_tension
from dynstiff.errors import ConvergenceError, DynstiffError, InvalidParameterError, SlackCableError
from dynstiff.robot.distribution import distribution_with_active_set as _distribution
from dynstiff.robot.distribution import tension_distribution
from dynstiff.robot.equilibrium import Equilibrium
from dynstiff.robot.feasibility import diagnose_limits, diagnose_unreachable, least_end_tension
from dynstiff.robot.pose import Pose

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.robot.robot import Robot

__all__ = ["tension_distribution", "inverse_statics"]


def _carried(u: NDArray[np.float64], c_old: NDArray[np.float64],
             c_new: NDArray[np.float64]) -> NDArray[np.float64]:
    """u (n, 3) turned with each chord from c_old to c_new (n, 3) by the least rotation
    (Rodrigues): a neighbouring equilibrium's cable-end directions keep their angle to the
    chord, which moves little with the pose, while the chord itself moves with it."""
    a = c_old / np.linalg.norm(c_old, axis=1)[:, None]
    b = c_new / np.linalg.norm(c_new, axis=1)[:, None]
    k = cross(a, b)
    cos = np.einsum("ij,ij->i", a, b)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.where(cos > -0.5, 1.0 / (1.0 + cos), 0.0)     # (1 - cos) / sin^2
    turned = (u * cos[:, None] + cross(k, u)
              + k * (np.einsum("ij,ij->i", k, u) * f)[:, None])
    keep = cos <= -0.5                            # a chord turned past 120 degrees: as given
    turned[keep] = u[keep]
    return turned / np.linalg.norm(turned, axis=1)[:, None]


def _end_quantities(anchors: NDArray[np.float64], ends: NDArray[np.float64], H: NDArray[np.float64],
                    V0: NDArray[np.float64], L0: NDArray[np.float64],
                    w0: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Unit force direction on B, shape (n, 3), and the tension margins lo = T_B - min T,
    hi = max T - T_B [N], shape (n,), of catenaries given by arrays (H, V0, L0)."""
    d = ends - anchors
    lh = np.hypot(d[:, 0], d[:, 1])
    vertical = lh <= 1e-14 * np.linalg.norm(d, axis=1)
    lh_safe = np.where(vertical, 1.0, lh)
    e_h = np.stack([np.where(vertical, 1.0, d[:, 0] / lh_safe),
                    np.where(vertical, 0.0, d[:, 1] / lh_safe), np.zeros(len(H))], axis=1)
    Vb = V0 + w0 * L0
    f = -(H[:, None] * e_h)
    f[:, 2] -= Vb
    T_B = np.hypot(H, Vb)
    T_A = np.hypot(H, V0)
    T_min = np.where((V0 < 0.0) & (Vb > 0.0), H,
                     np.hypot(H, np.minimum(np.abs(V0), np.abs(Vb))))
    return f / T_B[:, None], T_B - T_min, np.maximum(T_B, T_A) - T_B


def _step_distribution(pose: Pose, r: NDArray[np.float64], u: NDArray[np.float64],
                       fi: NDArray[np.int64], w: NDArray[np.float64],
                       t_min: NDArray[np.float64] | float, t_max: NDArray[np.float64] | float,
                       lo: NDArray[np.float64], hi: NDArray[np.float64],
                       tension_reference: NDArray[np.float64] | float | None,
                       sides: NDArray[np.int64] | None, straight: bool,
                       diagnose: bool = True) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The tension distribution (t, its active set) of one fixed-point iteration at cable-end
    directions u and margins lo, hi (``straight``: u are straight chords); raises the
    diagnosed InfeasiblePoseError when there is none (a plain SlackCableError when not
    ``diagnose``: a warm start, which a cold one follows)."""
    W = np.vstack([u.T, cross(r, u).T])[fi]
    try:
        return _distribution(W, w, t_min + lo, t_max - hi, tension_reference, sides)
    except SlackCableError:
        # straight chords of heavy cables leave the platform at other angles than their
        # catenaries, and their limits may not fit where the catenaries' do (theory.md
        # §4): a first distribution above 1e-3 t_min only gives the catenaries, whose
        # directions then meet the limits
        if straight:
            with contextlib.suppress(SlackCableError):
                return _distribution(W, w, 1e-3 * t_min + lo, t_max - hi, tension_reference,
                                     sides)
        where = f"pose {pose.as_vector().tolist()}"
        if not diagnose:
            raise SlackCableError(f"{where}: no tension distribution from the start") from None
        raise diagnose_limits(W, w, t_min, t_max, lo, hi, where) from None


def _start_or_request(robot: Robot, i: int, A_i: NDArray[np.float64], B_i: NDArray[np.float64],
                      t: NDArray[np.float64], relaxed: bool) -> Any:
    """Cable i's catenary at the platform-end tension t[i] [N] (scalar solver); where the
    distribution was the ``relaxed`` start and no catenary between A_i and B_i has so little
    tension at B_i, the catenary of least tension there (t[i] raised to it): that start only
    gives the next iteration its directions (theory.md §4), and an unreachable tension
    there is not the pose's refusal."""
    try:
        return unstretched_length_for_tension(A_i, B_i, t[i], robot.cables[i], robot.g)
    except SlackCableError:
        if not relaxed:
            raise
        least, L0 = least_end_tension(A_i, B_i, robot.cables[i], robot.g)
        if not (np.isfinite(least) and least > t[i]):       # no catenary found: diagnosed
            raise
        state = solve_catenary(A_i, B_i, L0, robot.cables[i], robot.g)
        t[i] = state.tension_at_end
        return state


def _fixed_point(robot: Robot, pose: Pose, A: NDArray[np.float64], B: NDArray[np.float64],
                 r: NDArray[np.float64], fi: NDArray[np.int64], wg: NDArray[np.float64],
                 EA: NDArray[np.float64], w0: NDArray[np.float64], t_min: NDArray[np.float64],
                 t_max: NDArray[np.float64], tension_reference: NDArray[np.float64] | float | None,
                 u: NDArray[np.float64], lo: NDArray[np.float64], hi: NDArray[np.float64],
                 warm: tuple[NDArray[np.float64], ...] | None, straight: bool,
                 max_iter: int, done: int = 0, diagnose: bool = True) -> tuple[Any, ...]:
    """The fixed point of cable directions and tension distribution of
    :func:`inverse_statics` from the directions u and margins lo, hi (``straight``: u are
    straight chords), after ``done`` of the ``max_iter`` iterations:
    (t, H, V0, L0, residual, {cable: CatenaryState of the scalar solver})."""
    best, since_best, last, change = np.inf, 0, np.inf, np.inf
    sides = None                          # the last distribution's active set
    for _ in range(max(max_iter - done, 1)):
        t, sides = _step_distribution(pose, r, u, fi, -wg[fi], t_min, t_max, lo, hi,
                                      tension_reference, sides, straight, diagnose)
        # the relaxed first distribution (below t_min + lo somewhere) is a start only
        relaxed = straight and bool(np.any(t < t_min + lo))
        straight = False
        H, V0, L0, res, pending = taut_catenaries(A, B, t, EA, w0, warm)
        scalar = {}
        for i in np.flatnonzero(pending):
            try:
                scalar[i] = _start_or_request(robot, i, A[i], B[i], t, relaxed)
            except SlackCableError as exc:
                where = f"pose {pose.as_vector().tolist()}"
                raise (diagnose_unreachable(robot, i, A[i], B[i], t[i], lo[i], where)
                       or SlackCableError(f"{where}: {exc}")) from None
            H[i], V0[i], L0[i] = scalar[i].H, scalar[i].V0, scalar[i].unstretched_length
            res[i] = scalar[i].residual
        warm = (H, V0, L0)
        u_new, lo_new, hi_new = _end_quantities(A, B, H, V0, L0, w0)
        change = max(np.abs(u_new - u).max(),
                     np.abs(np.concatenate([lo_new - lo, hi_new - hi])).max() / t.max())
        u, lo, hi = u_new, lo_new, hi_new
        # fixed point reached, or stalled at rounding level: below 1e-9 and no new smallest
        # change for 10 iterations (slow but steady contraction near slack keeps going; the
        # wrench residual below decides whether the result is good)
        best, since_best = (change, 0) if change < best else (best, since_best + 1)
        # a linear contraction rho = change / last leaves rho / (1 - rho) change to go: done
        # when that is below rounding (the next iteration would change nothing)
        rho = change / last if 0 < last < np.inf else 1.0
        last = change
        if change < 1e-15 or (rho < 0.5 and change * rho / (1 - rho) < 2e-16) \
                or (best < 1e-9 and since_best >= 10):
            break
    else:
        raise ConvergenceError(
            f"inverse statics: cable directions still change by {change:.2e} after "
            f"{max_iter} iterations (max_iter)", residual=change)
    return t, H, V0, L0, res, scalar


def _compiled_fixed_point(pose: Pose, A: NDArray[np.float64], B: NDArray[np.float64],
                          r: NDArray[np.float64], fi: NDArray[np.int64],
                          w: NDArray[np.float64], EA: NDArray[np.float64],
                          w0: NDArray[np.float64], t_min: NDArray[np.float64],
                          t_max: NDArray[np.float64],
                          tension_reference: NDArray[np.float64] | float | None,
                          u: NDArray[np.float64], lo: NDArray[np.float64],
                          hi: NDArray[np.float64], warm: tuple[NDArray[np.float64], ...] | None,
                          max_iter: int, diagnose: bool = True) -> tuple[Any, Any] | None:
    """:func:`_fixed_point` by the compiled loop (:func:`dynstiff.compiled.statics.fixed_point`)
    when numba is installed: None without it (the numpy loop runs from the start).

    The kernel takes the regular case (every distribution from an active set, every cable
    solved by the batched Newton). Where a distribution needs the LP's feasible point, the
    numpy loop's distribution finds the optimum's active set at the kernel's state (or
    raises the diagnosed error where there is none) and the kernel goes on from there, once.
    Whatever else happens (a singular configuration, a cable left to the scalar solver, no
    convergence), the numpy loop goes on from the state of the failing iteration: it is the
    reference, and says what went wrong.

    Returns
    -------
    (result, None) or (None, start)
        result as :func:`_fixed_point`'s; start (u, lo, hi, warm, iterations done) for the
        numpy loop.
    """
    kernels = compiled.load("statics")
    if kernels is None:
        return None
    n = len(EA)
    has_ref = tension_reference is not None
    ref = (np.broadcast_to(np.asarray(tension_reference, dtype=float), (n,)).copy() if has_ref
           else np.zeros(n))
    H, V0, L0 = warm if warm is not None else (np.full(n, np.nan),) * 3
    f = np.ascontiguousarray
    fixed = (f(A, dtype=float), f(B, dtype=float), f(r, dtype=float), f(fi, dtype=np.int64),
             f(w, dtype=float), f(EA, dtype=float), f(w0, dtype=float),
             f(np.broadcast_to(t_min, (n,)), dtype=float),
             f(np.broadcast_to(t_max, (n,)), dtype=float), ref, has_ref)
    sides = np.zeros(n, dtype=np.int64)
    is_warm, done = warm is not None, 0
    for attempt in range(2):
        status, it, t, H, V0, L0, res, u, lo, hi = kernels.fixed_point(
            *fixed, f(u, dtype=float), f(lo, dtype=float), f(hi, dtype=float),
            f(H, dtype=float), f(V0, dtype=float), f(L0, dtype=float), is_warm, sides,
            max_iter - done)
        done += it
        is_warm = is_warm or it > 0
        if status == kernels.CONVERGED:
            return (t, H, V0, L0, res, {}), None
        if status != kernels.NEEDS_LP or attempt or done >= max_iter:
            break
        # the numpy loop's distribution, which raises the diagnosed error where there is none
        sides = _step_distribution(pose, r, u, fi, w, t_min, t_max, lo, hi, tension_reference,
                                   None, not is_warm, diagnose)[1].astype(np.int64)
    return None, (u, lo, hi, (H, V0, L0) if is_warm else None, done)


def inverse_statics(robot: Robot, pose: Pose,
                    tension_reference: NDArray[np.float64] | float | None = None,
                    tol: float = 1e-10, max_iter: int = 50,
                    start: ArrayLike | None = None) -> Equilibrium:
    """Tensions and unstretched lengths that hold the platform at ``pose`` (sag included),
    with every cable's tension within the robot's limits all along its length.

    The fixed point of cable directions and tension distribution is iterated; each
    iteration solves all catenaries for their end tensions at once
    (:func:`dynstiff.cable.catenary_batch.taut_catenaries`, docs/theory.md §13.1), warm-started
    from the previous iteration.

    Parameters
    ----------
    robot : Robot
    pose : Pose
    tension_reference : float or ndarray, shape (n,), optional
        Reference tensions [N] of the distribution (default the lower limit).
    tol : float
        Admissible wrench residual relative to the platform weight [-].
    max_iter : int
        Fixed-point iterations.
    start : Equilibrium, optional
        A neighbouring equilibrium of the same robot: its cable directions, tension margins
        and catenaries start the iteration (the fixed point reached is the same). Where the
        iteration from it fails (a far neighbour), the pose is solved afresh: the result,
        or the error and its diagnosis, are those without a start.

    Returns
    -------
    Equilibrium
    """
    if tension_reference is not None:
        tension_reference = checked_reference(tension_reference, robot.n_cables)
    if start is not None:
        try:
            return _inverse_statics(robot, pose, tension_reference, tol, max_iter, start, False)
        except DynstiffError:       # a far neighbour: afresh, where a failure is diagnosed
            pass
    return _inverse_statics(robot, pose, tension_reference, tol, max_iter, None, True)


def _inverse_statics(robot: Robot, pose: Pose,
                     tension_reference: NDArray[np.float64] | float | None, tol: float,
                     max_iter: int, start: Any, diagnose: bool) -> Equilibrium:
    """:func:`inverse_statics` from ``start`` (None: cold), its failures diagnosed when
    ``diagnose``."""
    fi = robot.platform.free_index
    B, r = robot.attachment_points(pose)
    A = robot.anchors
    n = robot.n_cables
    w0 = np.array([c.mass_per_length for c in robot.cables]) * robot.g
    EA = np.array([c.EA for c in robot.cables])
    with np.errstate(over="ignore", invalid="ignore"):     # an overflow is refused below
        wg = robot.gravity_wrench(pose)
    if not np.all(np.isfinite(wg)):
        raise InvalidParameterError(
            f"platform: its weight's wrench at pose {pose.as_vector().tolist()} is not finite "
            f"({wg.tolist()}): mass {robot.platform.mass!r} kg times g {robot.g!r} m/s^2 "
            f"overflows")
    t_min, t_max = robot.tension_limits
    # the limits hold along the whole cable: the platform-end tension t_i is bounded by
    # [t_min + lo_i, t_max - hi_i], lo_i = T_B - min T, hi_i = max T - T_B of the last
    # catenaries (a cable going down to its anchor is least tensioned there)
    if start is not None:
        warm = catenary_arrays(start.states)
        A0 = np.array([s.anchor for s in start.states])
        B0 = np.array([s.end for s in start.states])
        u, lo, hi = _end_quantities(A0, B0, *warm, w0)
        u = _carried(u, A0 - B0, A - B)       # the start's sag angles on the new chords
    else:
        warm = None
        u = A - B
        u /= np.linalg.norm(u, axis=1)[:, None]
        # straight-cable lower margins (theory.md §4): along a catenary
        # dT = w0 dz / (1 + T/EA), so a cable rising to B has about w0 h less tension at A
        lo = np.maximum(0.0, w0 * (B[:, 2] - A[:, 2]))
        hi = np.zeros(n)
    fast = _compiled_fixed_point(pose, A, B, r, fi, -wg[fi], EA, w0, t_min, t_max,
                                 tension_reference, u, lo, hi, warm, max_iter, diagnose)
    if fast is not None and fast[0] is not None:
        t, H, V0, L0, res, scalar = fast[0]
    else:                    # the numpy loop, from the start or where the kernel stopped
        done = 0
        if fast is not None:
            u, lo, hi, warm, done = fast[1]
        t, H, V0, L0, res, scalar = _fixed_point(
            robot, pose, A, B, r, fi, wg, EA, w0, t_min, t_max, tension_reference, u, lo, hi,
            warm, start is None and done == 0, max_iter, done, diagnose)
    states = catenary_states(A, B, L0, robot.cables, robot.g, H, V0, res)
    for i, s in scalar.items():
        states[i] = s
    # final balance with these exact catenaries
    resid = robot.wrench(pose, states)[fi]
    scale = robot.platform.mass * max(robot.g, 1.0)
    res = np.linalg.norm(resid) / scale
    if res > tol:
        raise ConvergenceError(
            f"inverse statics: wrench residual {res:.3e} (relative to m g) > tol {tol:.0e} at pose "
            f"{pose.as_vector().tolist()}", residual=res)
    return Equilibrium(robot=robot, pose=pose, unstretched_lengths=L0.copy(),
                       states=tuple(states), residual=float(res))
