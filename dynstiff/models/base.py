"""What every model of the ladder is: the one interface the analyses use.

A model is an immutable linearisation of a cable robot about a static equilibrium. The
analyses (:mod:`dynstiff.frf`, :mod:`dynstiff.analyses.eigen`,
:mod:`dynstiff.analyses.interaction`, ...) are
plain functions of a model and use only what this page lists, so every rung answers every
question it can, and says so in an :class:`~dynstiff.errors.UnsupportedAnalysisError` where
it cannot.

Fields (all rungs)
------------------
=====================  ==========================================================  ============
field                  meaning                                                     unit
=====================  ==========================================================  ============
``rung``               "spring", "catenary", "dsm" or "lumped"                     --
``robot``              the :class:`~dynstiff.Robot`                                --
``equilibrium``        the static equilibrium the model was linearised about       --
``pose``               the platform pose of that equilibrium                       --
``free_dofs``          names of the free platform DOFs, the order of every matrix  --
``free_index``         their indices in ``DOF_NAMES``, shape (n_free,)              --
``n_free``             number of free platform DOFs                                --
``platform_mass``      rigid-platform mass matrix M_p on the free DOFs, about P    kg, kg m, kg m^2
``damped``             whether any cable carries damping                           --
=====================  ==========================================================  ============

Methods (all rungs)
-------------------
``dynamic_stiffness(omega)``
    K(omega) on the free DOFs, shape (n_omega, n_free, n_free) [N/m, N, N m/rad]; omega may
    be complex (damped roots). The only method an FRF needs (theory.md §4).
``massless_stiffness()``
    The static stiffness of the same robot with massless cables, (n_free, n_free).
``cable_mode_count(omega)``
    J0: the number of natural frequencies below omega with the platform held (the poles of
    K(omega)); zero for massless cables. With it, the Wittrick-Williams count
    J0 + s{K(omega)} is exact (theory.md §5.1).
``undamped()``
    The same model without damping (the model itself when it has none).

What a rung can say about its own poles (one of)
------------------------------------------------
* ``matrices()`` -> (K, M): a discrete rung's finite stiffness and mass matrices, the free
  platform DOFs first (``n_dof`` in all), and ``cable_energies(V)`` -> (n_modes, n_cables)
  kinetic energy of each cable for mode vectors V (n_dof, n_modes);
* ``cable_kinetic_energies(omega, x)`` -> (n_cables,): a continuous rung's cable kinetic
  energy per unit omega^2 / 2 at a natural frequency omega for the platform motion x (6,),
  its clamped-cable poles being counted by ``cable_mode_count``; for omega (n,) and x
  (n, 6), all n at once, (n, n_cables).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff.errors import InvalidParameterError
from dynstiff.robot.platform import platform_mass_matrix
from dynstiff.robot.robot import geometric_stiffness

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.cable.catenary import CatenaryState
    from dynstiff.models.lumped_statics import LumpedEquilibrium
    from dynstiff.robot.equilibrium import Equilibrium
    from dynstiff.robot.pose import Pose
    from dynstiff.robot.robot import Robot

__all__ = ["PlatformModel", "require_model", "require_equilibrium"]


def require_equilibrium(equilibrium: Equilibrium, name: str = "equilibrium") -> Equilibrium:
    """Raise InvalidParameterError naming ``name`` unless it is a static equilibrium of a
    robot (``Robot.equilibrium(...)``): it needs ``robot``, ``pose``, ``states`` and
    ``unstretched_lengths``."""
    missing = [a for a in ("robot", "pose", "states", "unstretched_lengths")
               if not hasattr(equilibrium, a)]
    if missing:
        raise InvalidParameterError(
            f"{name} must be an Equilibrium (from Robot.equilibrium or Scene.equilibrium), got "
            f"{type(equilibrium).__name__} without {missing[0]!r}")
    return equilibrium


def require_model(model: PlatformModel, name: str = "model") -> PlatformModel:
    """Raise InvalidParameterError naming ``name`` unless ``model`` has the interface of a
    model of the ladder (``dynamic_stiffness``, ``free_index``, ``pose``, ...)."""
    needed = ("dynamic_stiffness", "cable_mode_count", "massless_stiffness", "undamped",
              "free_index", "platform_mass", "pose", "rung")
    missing = [a for a in needed if not hasattr(model, a)]
    if missing:
        hint = (": linearise it first, LumpedLinearModel(m, m.equilibrium()) or "
                "build_model(eq, 'lumped')" if type(model).__name__ == "LumpedMassModel"
                else " (build one with build_model(equilibrium, rung))")
        raise InvalidParameterError(
            f"{name} must be a model of the ladder, got {type(model).__name__} without "
            f"{missing[0]!r}{hint}")
    return model


class PlatformModel:
    """Base of the models: the common fields, immutability and a short ``repr``.

    Subclasses call :meth:`_init_platform` in their constructor, set their own fields, then
    :meth:`_freeze`; afterwards every attribute is read-only and every array field is a
    read-only array.
    """

    rung: str | None = None

    def _init_platform(self, robot: Robot, equilibrium: LumpedEquilibrium | Equilibrium,
                       pose: Pose) -> None:
        fi = robot.platform.free_index
        self.robot = robot
        self.equilibrium = equilibrium
        self.pose = pose
        self.free_dofs = tuple(robot.platform.free_dofs)
        self.free_index = fi
        self.n_free = len(fi)
        self._platform_mass_all = platform_mass_matrix(robot.platform, pose.matrix)
        self.platform_mass = self._platform_mass_all[np.ix_(fi, fi)]
        self.damped = any(c.is_damped for c in robot.cables)

    def _init_geometric(self, robot: Robot, pose: Pose, states: tuple[CatenaryState, ...]) -> None:
        """K_geo (6, 6) (theory.md §4) and its conservative free block.

        With held rotations the reaction moment about a held axis makes the free block of
        K_geo non-symmetric by 1/2 [M_reaction]x, an artefact of the non-commuting rotation
        vector; the conservative (potential-energy Hessian) stiffness is its symmetric part.
        At a full 6-DOF equilibrium the block is already symmetric."""
        K_geo = np.zeros((6, 6))
        K_geo[3:, 3:] = geometric_stiffness(robot, pose, states)
        self.K_geo = K_geo
        Kg = K_geo[np.ix_(self.free_index, self.free_index)]
        self._K_geo_free = 0.5 * (Kg + Kg.T)

    def _freeze(self) -> None:
        for value in vars(self).values():
            if isinstance(value, np.ndarray):
                value.setflags(write=False)
        object.__setattr__(self, "_frozen", True)

    def __setattr__(self, name: str, value: Any | None) -> None:
        if getattr(self, "_frozen", False):
            raise AttributeError(
                f"{type(self).__name__} is immutable: build a new model instead of setting "
                f"{name!r}")
        object.__setattr__(self, name, value)

    def __repr__(self) -> str:
        return (f"{type(self).__name__}(rung={self.rung!r}, "
                f"{counted(self.robot.n_cables, 'cable')}, free {self.free_dofs}, "
                f"{self.pose!r}, {self.damping_text()})")

    def damping_text(self) -> str:
        """The model's damping in words: "undamped", or its parts (cables' own viscous and
        hysteretic damping, the analysis' cable loss factor and platform modal ratio)."""
        if not self.damped:
            return "undamped"
        parts = []
        zeta = getattr(self, "platform_damping_ratio", 0.0)
        eta = getattr(self, "cable_loss_factor", 0.0)
        if zeta:
            parts.append(f"platform modal ratio {zeta:g}")
        if eta:
            parts.append(f"cable loss factor {eta:g}")
        c = max((cb.viscous_damping for cb in self.robot.cables), default=0.0)
        e = max((cb.loss_factor for cb in self.robot.cables), default=0.0)
        if c:
            parts.append(f"cable viscous damping up to {c:g} N s/m^2")
        if e:
            parts.append(f"cables' own loss factor up to {e:g}")
        return "damped: " + ", ".join(parts)

    def cable_mode_count(self, omega: ArrayLike) -> NDArray[np.int64]:
        """J0(omega): natural frequencies below omega with the platform held, shape
        (n_omega,); none for massless cables."""
        return np.zeros(np.size(omega), dtype=int)

    def undamped(self) -> Any:
        """This model without damping (itself when undamped)."""
        return self
