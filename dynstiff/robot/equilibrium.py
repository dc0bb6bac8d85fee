"""Static equilibrium of a robot: the record the statics solvers return.

It holds its robot and the exact elastic-catenary state of every cable (docs/theory.md §1.1);
the models of :mod:`dynstiff.models.ladder` are built on it.
"""

from dataclasses import dataclass

import numpy as np

from dynstiff.robot.pose import Pose

__all__ = ["Equilibrium"]


@dataclass(frozen=True)
class Equilibrium:
    """Static equilibrium of a robot.

    Attributes
    ----------
    robot : Robot
        The robot (its geometry gives the lever arms and the static stiffness).
    pose : Pose
    unstretched_lengths : ndarray, shape (n,) [m]
    states : tuple of CatenaryState
    residual : float
        Norm of the free-DOF wrench residual relative to the platform weight [-].
    """

    robot: object
    pose: Pose
    unstretched_lengths: np.ndarray
    states: tuple
    residual: float

    @property
    def tensions(self):
        """Tension at the platform end B of each cable [N], shape (n,)."""
        return np.array([s.tension_at_end for s in self.states])

    @property
    def anchor_tensions(self):
        """Tension at the anchor A of each cable [N], shape (n,)."""
        return np.array([s.tension_at_anchor for s in self.states])

    @property
    def min_tensions(self):
        """Least tension along each cable [N], shape (n,) (the lower end, or H where the
        cable's lowest point lies between its ends)."""
        return np.array([s.min_tension for s in self.states])

    @property
    def max_tensions(self):
        """Largest tension along each cable [N], shape (n,)."""
        return np.array([s.max_tension for s in self.states])

    @property
    def lever_arms(self):
        """r_i = R_p b_i [m], shape (n, 3)."""
        return self.robot.attachment_points(self.pose)[1]

    def platform_stiffness(self):
        """6x6 static stiffness about P (all DOFs) [N/m, N, N m/rad]."""
        return self.robot.platform_stiffness(self.pose, self.states)

    def __repr__(self):
        t = self.tensions
        return (f"Equilibrium({self.robot.n_cables} cables, {self.pose!r}, tensions "
                f"{t.min():.4g}..{t.max():.4g} N, residual {self.residual:.1e})")

    def _repr_html_(self):
        """Jupyter display: the pose and each cable's tensions, length and sag."""
        from dynstiff._html import html_table
        rows = [[i, s.tension_at_end, s.tension_at_anchor, L0, s.sag]
                for i, (s, L0) in enumerate(zip(self.states, self.unstretched_lengths))]
        return html_table(
            f"Equilibrium of {self.robot.n_cables} cables at P = "
            f"{np.round(self.pose.position, 4).tolist()} m, rotation "
            f"{np.round(self.pose.rotation, 4).tolist()} rad",
            ["cable", "tension at B [N]", "tension at A [N]", "unstretched length [m]",
             "sag [m]"], rows, notes=[f"statics residual {self.residual:.2g}"])

    def plot(self, ax=None):
        """Cable tensions at B and A with the robot's limits:
        :func:`dynstiff.plot.plot_tensions`. Returns the matplotlib Figure."""
        from dynstiff.plot import plot_tensions
        return plot_tensions(self, ax=ax)

    def to_frame(self):
        """pandas DataFrame, one row per cable: tensions [N], lengths [m], sag, lambda^2."""
        import pandas as pd
        return pd.DataFrame({
            "cable": np.arange(self.robot.n_cables),
            "tension at B [N]": self.tensions,
            "tension at A [N]": self.anchor_tensions,
            "unstretched length [m]": self.unstretched_lengths,
            "chord length [m]": [s.chord_length for s in self.states],
            "sag [m]": [s.sag for s in self.states],
            "lambda^2 [-]": [s.lambda_sq for s in self.states],
        })
