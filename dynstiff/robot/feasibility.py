"""Why a pose has no statics, and what would give it one: the diagnosis behind
:class:`dynstiff.errors.InfeasiblePoseError` (theory.md §15.7).

Inverse statics (:mod:`dynstiff.robot.statics`) fails at a pose in one of three ways, each
diagnosed here from what the iteration had when it stopped (the cable directions u_i at B
and the weight margins lo_i = T_B - min T, hi_i = max T - T_B of the last catenaries):

``"singular"``
    the cable directions span fewer than the free DOFs (no tension holds the platform);
``"tension limits"``
    no tensions t with W t = w_c, t_min + lo_i <= t_i <= t_max - hi_i: two linear programs
    give the largest t_min and the smallest t_max for which such tensions exist at these
    directions (the remedies); when lowering t_min to 0 and raising t_max without end do not
    help either, the pose is outside the wrench-feasible workspace of the arrangement
    (cause ``"wrench"``); when the limits would hold with weightless margins (lo = hi = 0),
    the cables' weight is the cause (``"cable weight"``);
``"cable weight"``
    the tension t_i asked at B of cable i is below the least tension T_B* any catenary
    between A_i and B_i has there (a heavy cable rising to the platform): t_min raised by
    T_B* - t_i, or the weight scaled by s = (t_i - lo_i) / (T_B* - lo_i) (T_B* and lo_i
    grow in proportion to the weight per length for an inextensible catenary, the rest of
    t_i does not), makes the requested tension reachable.

The numbers are estimates at the last iterate's directions (sag changes them with the
tensions); the messages say "about".
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.cable.catenary_solve import solve_catenary
from dynstiff.errors import DynstiffError, InfeasiblePoseError

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.params import Cable
    from dynstiff.robot.robot import Robot

__all__ = ["diagnose_limits", "diagnose_unreachable", "least_end_tension"]


def _lp(c: NDArray[np.float64], A_eq: NDArray[np.float64], b_eq: NDArray[np.float64],
        A_ub: NDArray[np.float64], b_ub: NDArray[np.float64],
        bounds: list[tuple[float | None, float | None]]) -> float:
    """Optimal value of min c x (inf when infeasible, -inf when unbounded)."""
    from scipy.optimize import linprog
    res = linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds,
                  method="highs")
    if res.status == 2:
        return np.inf
    if res.status == 3:
        return -np.inf
    return float(res.fun) if res.status == 0 else np.nan


def limit_bounds(W: NDArray[np.float64], w: NDArray[np.float64], t_min: float, t_max: float,
                 lo: NDArray[np.float64], hi: NDArray[np.float64]) -> tuple[float, float]:
    """Largest t_min and smallest t_max [N] for which tensions within the limits balance.

    Parameters
    ----------
    W : ndarray, shape (k, n)
        Structure matrix (unit wrenches of the cables at B).
    w : ndarray, shape (k,)
        Wrench the cables must supply [N, N m].
    t_min, t_max : float
        Tension limits [N] (t_max may be inf).
    lo, hi : ndarray, shape (n,)
        Weight margins of each cable [N]: its tension at B must lie in
        [t_min + lo_i, t_max - hi_i].

    Returns
    -------
    best_t_min : float
        max s such that W t = w, s + lo_i <= t_i <= t_max - hi_i has a solution [N]
        (-inf when none for any s, inf when unbounded).
    best_t_max : float
        min s such that W t = w, t_min + lo_i <= t_i <= s - hi_i has a solution [N]
        (inf when none).
    """
    k, n = W.shape
    A_eq = np.hstack([W, np.zeros((k, 1))])
    ub = t_max - hi
    # max s: -t_i + s <= -lo_i, t_i <= t_max - hi_i
    A1 = np.hstack([-np.eye(n), np.ones((n, 1))])
    bounds = [(None, u if np.isfinite(u) else None) for u in ub] + [(None, None)]
    best_min = -_lp(np.r_[np.zeros(n), -1.0], A_eq, w, A1, -lo, bounds)
    # min s: t_i >= t_min + lo_i, t_i + hi_i - s <= 0
    A2 = np.hstack([np.eye(n), -np.ones((n, 1))])
    bounds = [(t_min + lo_i, None) for lo_i in lo] + [(None, None)]
    best_max = _lp(np.r_[np.zeros(n), 1.0], A_eq, w, A2, -hi, bounds)
    return best_min, best_max


def diagnose_limits(W: NDArray[np.float64], w: NDArray[np.float64], t_min: float, t_max: float,
                    lo: NDArray[np.float64], hi: NDArray[np.float64],
                    where: str) -> InfeasiblePoseError:
    """The :class:`InfeasiblePoseError` of a failed tension distribution.

    Parameters
    ----------
    W, w, lo, hi : as :func:`limit_bounds`
    t_min, t_max : float
        The robot's tension limits [N].
    where : str
        Prefix of the message (the pose).

    Returns
    -------
    InfeasiblePoseError
        ``cause`` "singular", "wrench", "tension limits" or "cable weight"; ``remedies``
        with ``t_min`` (the largest that works) and/or ``t_max`` (the smallest) [N].
    """
    k, n = W.shape
    rank = np.linalg.matrix_rank(W)
    if rank < k:
        return InfeasiblePoseError(
            f"{where}: the cable directions span only {rank} of the {k} free DOFs (a "
            f"singular configuration): no tensions hold the platform; change the pose or the "
            f"anchors", cause="singular")
    best_min, best_max = limit_bounds(W, w, t_min, t_max, lo, hi)
    remedies = {}
    if np.isfinite(best_min) and 0.0 < best_min < t_min:
        remedies["t_min"] = best_min
    if np.isfinite(best_max) and best_max > t_max:
        remedies["t_max"] = best_max
    limits = f"[{t_min:g}, {t_max:g}] N"
    both = not remedies              # neither limit alone: both together, or none at all
    if both:
        s, _ = limit_bounds(W, w, t_min, np.inf, lo, hi)
        if np.isfinite(s) and s > 0.0:
            low = min(t_min, 0.5 * s)
            remedies = {"t_min": low, "t_max": limit_bounds(W, w, low, t_max, lo, hi)[1]}
    if not remedies or not np.isfinite(remedies.get("t_max", 0.0)):
        return InfeasiblePoseError(
            f"{where}: no positive cable tensions balance the platform here, whatever the "
            f"tension limits {limits}: the pose is outside the wrench-feasible workspace of "
            f"the cable arrangement; change the pose or the anchors", cause="wrench")
    weightless_min, weightless_max = limit_bounds(W, w, t_min, t_max, np.zeros(n),
                                                  np.zeros(n))
    weight = weightless_min >= t_min and weightless_max <= t_max
    parts = []
    if "t_min" in remedies:
        parts.append(f"t_min <= about {remedies['t_min']:.6g} N")
    if "t_max" in remedies:
        parts.append(f"t_max >= about {remedies['t_max']:.6g} N")
    what = (" and " if both else " or ").join(parts)
    cause = "cable weight" if weight else "tension limits"
    why = ("the cables' weight (the tension varies along each cable by up to "
           f"{max(np.max(lo), np.max(hi)):.4g} N) leaves no room within the limits"
           if weight else "the tensions that hold the platform here do not fit in the limits")
    remedy = (f"use lighter cables, or change the tension limits: {what}" if weight
              else f"change the tension limits: feasible with {what}")
    return InfeasiblePoseError(
        f"{where}: no tension distribution within {limits} balances the platform: {why}; "
        f"{remedy}", cause=cause, remedies=remedies)


def least_end_tension(anchor: NDArray[np.float64], end: NDArray[np.float64], cable: Cable,
                      g: float) -> tuple[float, float]:
    """Least tension [N] at the end B any elastic catenary between A and B has (the fold
    where a longer cable stops lowering T_B), and the unstretched length giving it [m]."""
    from scipy.optimize import minimize_scalar
    A, B = np.asarray(anchor, float), np.asarray(end, float)
    chord = float(np.linalg.norm(B - A))

    def T(L0: float) -> float | None:
        try:
            return solve_catenary(A, B, L0, cable, g).tension_at_end
        except DynstiffError:
            return np.inf
    grid = chord * (1.0 + np.geomspace(1e-7, 4.0, 60))
    vals = np.array([T(L0) for L0 in grid])
    j = int(np.argmin(vals))
    lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]
    res = minimize_scalar(T, bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-10 * chord})
    return (float(res.fun), float(res.x)) if res.fun < vals[j] else (float(vals[j]),
                                                                    float(grid[j]))


def diagnose_unreachable(robot: Robot, i: int, anchor: NDArray[np.float64],
                         end: NDArray[np.float64], tension: float, lo_i: float,
                         where: str) -> InfeasiblePoseError | None:
    """The :class:`InfeasiblePoseError` of a cable whose requested end tension no catenary
    reaches, or None when the least reachable tension is below it (another cause).

    Parameters
    ----------
    robot : Robot
    i : int
        The cable.
    anchor, end : ndarray, shape (3,)
        A_i and B_i [m].
    tension : float
        The tension asked at B [N].
    lo_i : float
        Its weight margin T_B - min T at the last iterate [N].
    where : str
        Prefix of the message (the pose).
    """
    cable = robot.cables[i]
    T_star, _ = least_end_tension(anchor, end, cable, robot.g)
    if not np.isfinite(T_star) or tension >= T_star:
        return None
    t_min = robot.tension_limits[0]
    need_t_min = t_min + (T_star - tension)
    scale = (tension - lo_i) / (T_star - lo_i) if T_star > lo_i else 0.0
    remedies = {"t_min": need_t_min}
    lighter = ""
    if 0.0 < scale < 1.0:
        remedies["mass_per_length"] = scale * cable.mass_per_length
        lighter = (f" or use a cable lighter than about {scale * cable.mass_per_length:.4g} "
                   f"kg/m")
    rise = end[2] - anchor[2]
    weight = cable.mass_per_length * robot.g * np.linalg.norm(end - anchor)
    return InfeasiblePoseError(
        f"{where}: cable {i} ({'rising' if rise > 0 else 'falling'} {abs(rise):.4g} m to the "
        f"platform, chord weight {weight:.4g} N) is asked {tension:.4g} N at the platform; "
        f"not reachable: no catenary between its ends has less than {T_star:.4g} N there "
        f"(the cable is too heavy for its tension); raise t_min to above about "
        f"{need_t_min:.4g} N (tension limits){lighter}", cause="cable weight",
        remedies=remedies, cable=i)
