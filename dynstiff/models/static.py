"""The two massless rungs, "spring" and "catenary" (theory.md §4): every cable a static end
stiffness, (EA/L0) u u^T + (T/L)(I - u u^T) for a straight spring or the elastic catenary's
exact 3x3 end stiffness, assembled with the platform's mass; global modes only.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import omega_array
from dynstiff.errors import InvalidParameterError
from dynstiff.models.base import PlatformModel, require_equilibrium
from dynstiff.robot.platform import lever_map
from dynstiff.robot.robot import geometric_stiffness

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["StaticCableModel"]


class StaticCableModel(PlatformModel):
    """Robot with massless cables: constant stiffness K = sum J^T K_i J + K_geo and mass M_p.

    Parameters
    ----------
    equilibrium : Equilibrium
    stiffness : {"spring", "catenary"}
        "spring": straight elastic springs, K_i = (EA/L0) u u^T + (T/L)(I - u u^T) with u the
        chord direction and T the tension at B; "catenary": the exact elastic-catenary static
        end stiffness of each cable (:attr:`CatenaryState.end_stiffness`).

    Attributes
    ----------
    rung, robot, equilibrium, pose, free_dofs, free_index, n_free, platform_mass, damped
        As every model (:mod:`dynstiff.models.base`); massless cables carry no damping, so
        ``damped`` is False.
    K : ndarray, shape (n_free, n_free)
        Stiffness [N/m, N, N m/rad] (symmetric part).
    n_dof : int
        n_free: the platform is the only mass.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.StaticCableModel(eq)
    >>> [f"{f:.3f}" for f in ds.eigenfrequencies(m, n_modes=2)]     # massless cables [Hz]
    ['2.217', '2.398']
    """

    def __init__(self, equilibrium: Equilibrium, stiffness: str = "catenary") -> None:
        if stiffness not in ("spring", "catenary"):
            raise InvalidParameterError(
                f"stiffness must be 'spring' or 'catenary', got {stiffness!r}")
        robot, pose = require_equilibrium(equilibrium).robot, equilibrium.pose
        self._init_platform(robot, equilibrium, pose)
        self.rung = stiffness
        self.damped = False
        fi = self.free_index
        K = np.zeros((6, 6))
        for i, (s, r) in enumerate(zip(equilibrium.states, equilibrium.lever_arms)):
            if stiffness == "spring":
                L = s.chord_length
                u = s.chord / L
                Ki = (robot.cables[i].EA / s.unstretched_length * np.outer(u, u)
                      + s.tension_at_end / L * (np.eye(3) - np.outer(u, u)))
            else:
                Ki = s.end_stiffness
            J = lever_map(r)
            K += J.T @ Ki @ J
        K[3:, 3:] += geometric_stiffness(robot, pose, equilibrium.states)
        K = K[np.ix_(fi, fi)]
        self.K = 0.5 * (K + K.T)
        self.n_dof = self.n_free
        self._freeze()

    def matrices(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Stiffness and mass on the free DOFs, (K, M), each (n_free, n_free)."""
        return self.K, self.platform_mass

    def dynamic_stiffness(self, omega: NDArray[Any] | float) -> NDArray[Any]:
        """K - omega^2 M_p, shape (n_omega, n_free, n_free) [N/m, N, N m/rad]; omega [rad/s]
        real >= 0 or complex."""
        omega = omega_array(omega, complex_ok=True)
        return self.K[None] - (omega**2)[:, None, None] * self.platform_mass[None]

    def massless_stiffness(self) -> NDArray[np.float64]:
        """K itself (the cables are massless), shape (n_free, n_free)."""
        return self.K.copy()

    def cable_energies(self, V: NDArray[np.float64]) -> NDArray[np.float64]:
        """Massless cables hold no kinetic energy: zeros of shape (n_modes, n_cables)."""
        return np.zeros((np.shape(V)[1], self.robot.n_cables))
