"""A ladder of cable models behind one interface, from cheapest to richest.

==========  =================================================================  ==============
rung        cable model                                                        modes it has
==========  =================================================================  ==============
"spring"    (a) massless straight spring: (EA/L0) u u^T + (T/L)(I - u u^T)      global only
"catenary"  (b) massless elastic catenary: exact static 3x3 end stiffness       global only
"dsm"       (c) closed-form dynamic stiffness (Irvine-Caughey, theory.md §3)    global + local
"exact"     (e) dynamic stiffness about the true catenary (theory.md §11)      global + local
"lumped"    (d) lumped-mass chains with N segments per cable (theory.md §7)     global + local
==========  =================================================================  ==============

:func:`build_model` returns the model of a rung: an immutable object with the fields and
methods of :mod:`dynstiff.models.base`. The analyses are plain functions of a model, the same
for every rung: :func:`dynstiff.analyses.frf.frf`, :func:`dynstiff.analyses.eigen.eigenfrequencies`,
:func:`dynstiff.analyses.eigen.modes`, :func:`dynstiff.analyses.damped.damped_modes`. All rungs share the
platform, the geometric stiffness K_geo and gravity.
"""

from numbers import Integral

import numpy as np

from dynstiff._validate import omega_array
from dynstiff.errors import InvalidParameterError
from dynstiff.models.base import PlatformModel, require_equilibrium
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.exact import ExactModel
from dynstiff.models.lumped import LumpedLinearModel
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.robot.platform import lever_map
from dynstiff.robot.robot import geometric_stiffness

__all__ = ["RUNGS", "StaticCableModel", "build_model"]

#: The rungs, cheapest first.
RUNGS = ("spring", "catenary", "dsm", "exact", "lumped")


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
    """

    def __init__(self, equilibrium, stiffness="catenary"):
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

    def matrices(self):
        """Stiffness and mass on the free DOFs, (K, M), each (n_free, n_free)."""
        return self.K, self.platform_mass

    def dynamic_stiffness(self, omega):
        """K - omega^2 M_p, shape (n_omega, n_free, n_free) [N/m, N, N m/rad]; omega [rad/s]
        real >= 0 or complex."""
        omega = omega_array(omega, complex_ok=True)
        return self.K[None] - (omega**2)[:, None, None] * self.platform_mass[None]

    def massless_stiffness(self):
        """K itself (the cables are massless), shape (n_free, n_free)."""
        return self.K.copy()

    def cable_energies(self, V):
        """Massless cables hold no kinetic energy: zeros of shape (n_modes, n_cables)."""
        return np.zeros((np.shape(V)[1], self.robot.n_cables))


def build_model(equilibrium, rung, segments=30, **options):
    """The model of rung ``rung`` for this equilibrium.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    rung : {"spring", "catenary", "dsm", "exact", "lumped"}
    segments : int or sequence of int
        Segments per cable of the "lumped" rung (ignored by the others).
    **options
        "dsm": ``tension``, ``chordwise_inertia``, ``cable_loss_factor``,
        ``platform_damping_ratio``, ``guard_rtol`` (:class:`FrequencyModel`); "exact":
        ``fmax_hz``, ``order``, ``half_waves``, ``cable_loss_factor``,
        ``platform_damping_ratio`` (:class:`ExactModel`); "lumped":
        ``tol``, ``max_iter`` of its equilibrium (:meth:`LumpedMassModel.equilibrium`).

    Returns
    -------
    StaticCableModel, FrequencyModel, ExactModel or LumpedLinearModel
        Immutable, with ``.rung``. The lumped model is linearised about its own
        equilibrium for the same unstretched lengths, started from ``equilibrium.pose``.
    """
    allowed = {"dsm": ("tension", "chordwise_inertia", "cable_loss_factor",
                       "platform_damping_ratio", "guard_rtol"),
               "exact": ("fmax_hz", "order", "half_waves", "cable_loss_factor",
                         "platform_damping_ratio"),
               "lumped": ("tol", "max_iter")}
    unknown = sorted(set(options) - set(allowed.get(rung, ())))
    if rung not in RUNGS:
        raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
    require_equilibrium(equilibrium)
    if unknown:
        raise InvalidParameterError(
            f"options {unknown} do not apply to rung {rung!r} (it takes "
            f"{list(allowed.get(rung, ())) or 'none'})")
    if rung in ("spring", "catenary"):
        return StaticCableModel(equilibrium, rung)
    if rung == "dsm":
        return FrequencyModel(equilibrium, **options)
    if rung == "exact":
        return ExactModel(equilibrium, **options)
    if isinstance(segments, Integral) and not isinstance(segments, bool) and segments < 1:
        raise InvalidParameterError(f"segments must be >= 1, got {segments!r}")
    mass_model = LumpedMassModel(equilibrium.robot, equilibrium.unstretched_lengths,
                                 segments=segments)
    state = mass_model.equilibrium(initial_pose=equilibrium.pose, **options)
    return LumpedLinearModel(mass_model, state)
