"""Static equilibrium of a robot: the record the statics solvers return.

It holds its robot and the exact elastic-catenary state of every cable (docs/theory.md §1.1);
the models of :mod:`dynstiff.models.ladder` are built on it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff.robot.pose import Pose

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray

    from dynstiff.robot.robot import Robot

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

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> eq.robot.n_cables, f"{eq.residual:.0e}"
    (8, '9e-14')
    """

    robot: Robot
    pose: Pose
    unstretched_lengths: np.ndarray
    states: tuple
    residual: float

    def _per_cable(self, name: str) -> NDArray[np.float64]:
        """Each state's ``name``, shape (n,): computed once (the states are immutable), a
        copy returned."""
        cache = self.__dict__.setdefault("_per_cable_cache", {})
        if name not in cache:
            cache[name] = np.array([getattr(s, name) for s in self.states])
        return cache[name].copy()

    @property
    def tensions(self) -> NDArray[np.float64]:
        """Tension at the platform end B of each cable [N], shape (n,).

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> print(f"{eq.tensions.min():.1f} .. {eq.tensions.max():.1f} N")
        270.3 .. 304.1 N
        """
        return self._per_cable("tension_at_end")

    @property
    def anchor_tensions(self) -> NDArray[np.float64]:
        """Tension at the anchor A of each cable [N], shape (n,).

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> print(f"{eq.anchor_tensions[0]:.2f} N at A, {eq.tensions[0]:.2f} N at B")
        295.18 N at A, 292.43 N at B
        """
        return self._per_cable("tension_at_anchor")

    @property
    def min_tensions(self) -> NDArray[np.float64]:
        """Least tension along each cable [N], shape (n,) (the lower end, or H where the
        cable's lowest point lies between its ends).

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> print(f"{eq.min_tensions[0]:.2f} N")
        292.43 N
        """
        return self._per_cable("min_tension")

    @property
    def max_tensions(self) -> NDArray[np.float64]:
        """Largest tension along each cable [N], shape (n,).

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> print(f"{eq.max_tensions[0]:.2f} N")
        295.18 N
        """
        return self._per_cable("max_tension")

    @property
    def lever_arms(self) -> NDArray[np.float64]:
        """r_i = R_p b_i [m], shape (n, 3).

        Examples
        --------
        >>> import dynstiff as ds
        >>> ds.load_scene("cogiro").equilibrium().lever_arms.shape
        (8, 3)
        """
        return self.robot.attachment_points(self.pose)[1]

    def platform_stiffness(self) -> NDArray[np.float64]:
        """6x6 static stiffness about P (all DOFs) [N/m, N, N m/rad].

        Examples
        --------
        >>> import numpy as np
        >>> import dynstiff as ds
        >>> K = ds.load_scene("cogiro").equilibrium().platform_stiffness()
        >>> print(K.shape, f"k_z = {K[2, 2] / 1e3:.1f} kN/m")
        (6, 6) k_z = 17.9 kN/m
        """
        return self.robot.platform_stiffness(self.pose, self.states)

    def __repr__(self) -> str:
        t = self.tensions
        return (f"Equilibrium({counted(self.robot.n_cables, 'cable')}, {self.pose!r}, tensions "
                f"{t.min():.4g}..{t.max():.4g} N, residual {self.residual:.1e})")

    def _repr_html_(self) -> str:
        """Jupyter display: the pose and each cable's tensions, length and sag."""
        from dynstiff._html import html_table
        rows = [[i, s.tension_at_end, s.tension_at_anchor, L0, s.sag]
                for i, (s, L0) in enumerate(zip(self.states, self.unstretched_lengths))]
        return html_table(
            f"Equilibrium of {counted(self.robot.n_cables, 'cable')} at P = "
            f"{np.round(self.pose.position, 4).tolist()} m, rotation "
            f"{np.round(self.pose.rotation, 4).tolist()} rad",
            ["cable", "tension at B [N]", "tension at A [N]", "unstretched length [m]",
             "sag [m]"], rows, notes=[f"statics residual {self.residual:.2g}"])

    def plot(self, ax: Axes | None = None) -> Figure:
        """Cable tensions at B and A with the robot's limits:
        :func:`dynstiff.plot.plot_tensions`. Returns the matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> fig = ds.load_scene("cogiro").equilibrium().plot()
        >>> type(fig).__name__
        'Figure'
        >>> import matplotlib.pyplot as plt; plt.close(fig)
        """
        from dynstiff.plot import plot_tensions
        return plot_tensions(self, ax=ax)

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per cable: tensions [N], lengths [m], sag, lambda^2.

        Examples
        --------
        >>> import dynstiff as ds
        >>> df = ds.load_scene("cogiro").equilibrium().to_frame()
        >>> len(df), list(df.columns)[:2]
        (8, ['cable', 'tension at B [N]'])
        """
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
