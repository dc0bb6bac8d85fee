"""Statics of the lumped-mass robot (theory.md §7.1): Newton on the interior nodes and the free
platform DOFs from the elastic-catenary equilibrium, the equilibrium record, and the
segment forces of a chain.
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.cable.lumped_chain import chain_equilibrium
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError
from dynstiff.robot.pose import Pose, as_pose

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.lumped_robot import LumpedMassModel

__all__ = ["LumpedEquilibrium", "lumped_equilibrium", "segment_forces"]


# ------------------------------------------------------------------------------ kernels
def segment_forces(nodes: NDArray[np.float64], l0: NDArray[np.float64] | float,
                   EA: NDArray[np.float64] | float) -> tuple[NDArray[np.float64], ...]:
    """Segment geometry and tensions of one chain, or of a stack of chains.

    Parameters
    ----------
    nodes : ndarray, shape (..., N+1, 3)
        Node positions [m], anchor first.
    l0, EA : float or ndarray broadcasting against shape (..., N)
        Unstretched segment length [m], axial stiffness [N].

    Returns
    -------
    units : ndarray, shape (..., N, 3)
        n_i [-].
    lengths : ndarray, shape (..., N)
        l_i [m].
    tensions : ndarray, shape (..., N)
        T_i = EA (l_i / l0 - 1)_+ [N].
    """
    d = np.diff(nodes, axis=-2)
    lengths = np.sqrt(np.sum(d * d, axis=-1))
    return d / lengths[..., None], lengths, EA * np.maximum(lengths / l0 - 1.0, 0.0)


# ----------------------------------------------------------------------- result types
@dataclass(frozen=True)
class LumpedEquilibrium:
    """Static equilibrium of the lumped-mass robot.

    Attributes
    ----------
    pose : Pose
        Platform pose.
    nodes : list of ndarray, shape (N_i + 1, 3)
        Node positions of every cable [m], anchor A_i first, attachment point B_i last.
    tensions : list of ndarray, shape (N_i,)
        Segment tensions [N], from the anchor to the platform.
    residual : float
        Largest unbalanced force on a node or the platform (moments divided by the platform
        size), relative to the force scale m_p g + sum m L0 g + max T [-].
    iterations : int
        Newton iterations taken from the start.
    start_pose : Pose
        Elastic-catenary equilibrium pose the iteration started from.
    platform_forces : ndarray, shape (n, 3)
        Force F_i of every cable on the platform at B_i [N]: the last segment's pull plus
        the weight of the half node mass carried by the platform (comparable with the
        elastic catenary's ``force_on_end``).
    """

    pose: Pose
    nodes: list
    tensions: list
    residual: float
    iterations: int
    start_pose: Pose
    platform_forces: np.ndarray

    def __repr__(self) -> str:
        t = self.end_tensions
        return (f"LumpedEquilibrium({len(self.nodes)} chains, {self.pose!r}, tensions at B "
                f"{t.min():.4g}..{t.max():.4g} N, residual {self.residual:.1e})")

    def plot(self, ax: Axes | None = None) -> Figure:
        """Tensions of the end segments at B and A: :func:`dynstiff.plot.plot_tensions`.
        Returns the matplotlib Figure."""
        from dynstiff.plot import plot_tensions
        return plot_tensions(self, ax=ax)

    @property
    def interior(self) -> list[NDArray[np.float64]]:
        """Interior nodes of every cable, list of (N_i - 1, 3) arrays [m]."""
        return [x[1:-1] for x in self.nodes]

    @property
    def end_tensions(self) -> NDArray[np.float64]:
        """Tension of the last segment of every cable (at the platform) [N], shape (n,)."""
        return np.array([t[-1] for t in self.tensions])

    @property
    def anchor_tensions(self):
        """Tension of the first segment of every cable (at the anchor) [N], shape (n,)."""
        return np.array([t[0] for t in self.tensions])

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per cable: segments and end tensions [N]."""
        import pandas as pd
        return pd.DataFrame({
            "cable": np.arange(len(self.nodes)),
            "segments": [len(t) for t in self.tensions],
            "tension at B [N]": self.end_tensions,
            "tension at A [N]": self.anchor_tensions,
        })


def lumped_equilibrium(model: LumpedMassModel, initial_pose: ArrayLike | Pose | None = None,
                       tol: float = 1e-10, max_iter: int = 50) -> LumpedEquilibrium:
    """Static equilibrium of a :class:`~dynstiff.models.lumped_robot.LumpedMassModel`: the
    work of its :meth:`~dynstiff.models.lumped_robot.LumpedMassModel.equilibrium` (see there
    for the parameters, the start and the stopping rule).

    Returns
    -------
    LumpedEquilibrium
    """
    import scipy.sparse.linalg
    tol = positive_scalar("tol", tol)
    if isinstance(max_iter, bool) or not isinstance(max_iter, Integral) or max_iter < 1:
        raise InvalidParameterError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    rob = model.robot
    start = rob.equilibrium(unstretched_lengths=model.unstretched_lengths,
                            initial_pose=None if initial_pose is None
                            else as_pose(initial_pose))
    pose = start.pose
    B, _ = rob.attachment_points(pose)
    interior = [chain_equilibrium(rob.anchors[i], B[i], model.unstretched_lengths[i],
                                  rob.cables[i], int(model.segments[i]), rob.g
                                  ).nodes[1:-1].copy()
                for i in range(rob.n_cables)]
    R, t_max = model.residual_unchecked(pose, interior)
    res = model.relative_residual(R, t_max)
    iteration = 0
    while res > max(tol, model.rounding_floor(pose, t_max)):
        if iteration == max_iter:
            raise ConvergenceError(
                f"LumpedMassModel.equilibrium did not converge in {max_iter} Newton "
                f"iterations: relative residual {res:.3e} > tol {tol:g}", residual=res)
        iteration += 1
        K = model.tangent_unchecked(pose, interior, lambda i: 1.0)
        try:
            with np.errstate(all="raise"):
                dx = scipy.sparse.linalg.splu(K.tocsc()).solve(R)
        except (RuntimeError, FloatingPointError):
            raise ConvergenceError(
                f"LumpedMassModel.equilibrium: singular tangent stiffness (slack "
                f"segments or an unstable pose), relative residual {res:.3e}",
                residual=res) from None
        alpha = 1.0
        while True:
            trial = model.displaced(pose, interior, alpha * dx)
            R_t, t_t = model.residual_unchecked(*trial)
            res_t = model.relative_residual(R_t, t_t)
            if res_t < res or alpha < 1e-6:
                break
            alpha *= 0.5
        if not res_t < res:
            if res <= 4 * model.rounding_floor(pose, t_max):
                break                      # stagnation at the rounding level: converged
            raise ConvergenceError(
                f"LumpedMassModel.equilibrium: no step reduces the residual (stagnation "
                f"at rounding level or a wrong tangent), relative residual {res:.3e} > "
                f"tol {tol:g}", residual=res)
        (pose, interior), R, t_max, res = trial, R_t, t_t, res_t
    nodes, _ = model.full_nodes(pose, interior)
    seg = [segment_forces(x, l0, c.EA) for x, l0, c in zip(nodes, model.segment_lengths,
                                                      rob.cables)]
    tensions = [T for _, _, T in seg]
    forces = np.array([-T[-1] * n[-1] + 0.5 * mi * rob.gravity_vector
                       for (n, _, T), mi in zip(seg, model.node_masses)])
    slack = [i for i, t in enumerate(tensions) if np.any(t <= 0.0)]
    if slack:
        raise SlackCableError(
            f"LumpedMassModel.equilibrium: cable(s) {slack} have zero-tension segments at "
            f"equilibrium (pose {pose.as_vector().tolist()})")
    for a in nodes + tensions + [forces]:
        a.setflags(write=False)
    return LumpedEquilibrium(pose=pose, nodes=nodes, tensions=tensions, residual=res,
                             iterations=iteration, start_pose=start.pose,
                             platform_forces=forces)
