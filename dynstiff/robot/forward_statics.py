"""Forward statics of a robot: the platform pose at which given unstretched cable lengths
hold it in equilibrium (theory.md §4), by Newton's method on the free-DOF wrench."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.cable.catenary import CatenaryState
from dynstiff.errors import ConvergenceError, DynstiffError, InvalidParameterError
from dynstiff.robot.equilibrium import Equilibrium
from dynstiff.robot.pose import Pose

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.robot.robot import Robot

__all__ = ["forward_statics"]


def _kinematic_guess(robot: Robot, L0: NDArray[np.float64]) -> Pose:
    """Pose guess: free DOFs fitted so that straight chords match L0 (least squares)."""
    from scipy.optimize import least_squares

    fi = robot.platform.free_index
    x0 = np.zeros(6)
    x0[:3] = robot.anchors.mean(axis=0) - [0.0, 0.0, 0.5 * np.ptp(robot.anchors[:, 2]) + 1.0]

    def resid(xf: NDArray[np.float64]) -> NDArray[np.float64]:
        x = x0.copy()
        x[fi] = xf
        B, _ = robot.attachment_points(Pose(x[:3], x[3:]))
        return np.linalg.norm(robot.anchors - B, axis=1) - L0 * 0.999

    sol = least_squares(resid, x0[fi])
    x = x0.copy()
    x[fi] = sol.x
    return Pose(x[:3], x[3:])


def forward_statics(robot: Robot, L0: NDArray[np.float64], initial_pose: Pose | None = None,
                    tol: float = 1e-10, max_iter: int = 50) -> Equilibrium:
    """Pose of the free DOFs at which the platform is in equilibrium for lengths ``L0``.

    Newton's method on the free-DOF wrench W(x) = 0 with the analytic stiffness K = -dW/dx,
    with backtracking on |W|. Converged when |W_free| <= tol * m g.

    Returns
    -------
    Equilibrium

    Raises
    ------
    ConvergenceError
        With the final residual, if Newton fails; :class:`SlackCableError` if a cable cannot
        be in tension.
    """
    fi = robot.platform.free_index
    held = set(range(6)) - set(fi.tolist())
    rotations_matter = (np.any(robot.attachments != 0)
                        or np.any(robot.platform.center_of_mass != 0))
    if initial_pose is None and (held & {0, 1, 2} or (held & {3, 4, 5} and rotations_matter)):
        raise InvalidParameterError(
            f"initial_pose is required when DOFs are held (free_dofs="
            f"{robot.platform.free_dofs}): it fixes the held coordinates")
    pose = initial_pose if initial_pose is not None else _kinematic_guess(robot, L0)
    scale = robot.platform.mass * max(robot.g, 1.0)

    def evaluate(p: Pose) -> tuple[list[CatenaryState], NDArray[np.float64]]:
        st = robot.cable_states(p, L0)
        return st, robot.wrench(p, st)[fi]

    states, w = evaluate(pose)
    res = np.linalg.norm(w) / scale
    for _ in range(max_iter):
        if res <= tol:
            return Equilibrium(robot=robot, pose=pose, unstretched_lengths=L0,
                               states=tuple(states), residual=float(res))
        K = robot.platform_stiffness(pose, states)[np.ix_(fi, fi)]
        try:
            dxf = np.linalg.solve(K, w)
        except np.linalg.LinAlgError:
            break
        step = 1.0
        while step > 1e-4:
            dx = np.zeros(6)
            dx[fi] = step * dxf
            try:                            # a step to a non-finite pose counts as a failure
                trial = pose.moved(dx)
                st_t, w_t = evaluate(trial)
                res_t = np.linalg.norm(w_t) / scale
            except DynstiffError:
                res_t = np.inf
            if res_t < res:
                break
            step *= 0.5
        else:
            break
        pose, states, w, res = trial, st_t, w_t, res_t
    raise ConvergenceError(
        f"forward statics did not converge: wrench residual {res:.3e} (relative to m g) > "
        f"tol {tol:.0e} at pose {pose.as_vector().tolist()}", residual=res)
