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
:func:`dynstiff.analyses.modes.modes`, :func:`dynstiff.analyses.damped.damped_modes`. All rungs
share the platform, the geometric stiffness K_geo and gravity.
"""

from __future__ import annotations

from numbers import Integral
from typing import TYPE_CHECKING

from dynstiff.errors import InvalidParameterError
from dynstiff.models.base import require_equilibrium
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.exact import ExactModel
from dynstiff.models.lumped import LumpedLinearModel
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.models.static import StaticCableModel

if TYPE_CHECKING:
    from typing import Any

    from dynstiff.models.base import PlatformModel
    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["RUNGS", "build_model"]

#: The rungs, cheapest first.
RUNGS = ("spring", "catenary", "dsm", "exact", "lumped")


def build_model(equilibrium: Equilibrium, rung: str, segments: int = 30,
                **options: Any) -> PlatformModel:
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

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> for rung in ("spring", "dsm"):
    ...     m = ds.build_model(eq, rung)
    ...     print(rung, f"{ds.eigenfrequencies(m, n_modes=1)[0]:.4f} Hz")
    spring 2.2336 Hz
    dsm 2.2061 Hz
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
