"""Damping of the lumped-mass time-domain model and the explicit scheme's stability limit
(theory.md §7.3)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import positive_scalar, real_array
from dynstiff._validate import unstretched_lengths as checked_lengths
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.models.lumped_robot import LumpedMassModel

__all__ = ["TimeDamping", "explicit_step_limit"]


@dataclass(frozen=True)
class TimeDamping:
    """Damping of the time-domain model (besides the cables' ``viscous_damping``).

    Parameters
    ----------
    alpha : float
        Mass-proportional Rayleigh coefficient [1/s], >= 0: force -alpha M(q) v.
    beta : float
        Stiffness-proportional Rayleigh coefficient [s], >= 0: force -beta K_0 v, K_0 the
        (symmetrised) tangent stiffness at the starting equilibrium, so the modal damping
        ratio of the linearised model is zeta = alpha / (2 omega) + beta omega / 2.
    axial : float or sequence of float
        Axial dashpot c_ax [N s] of every segment (one value or one per cable), >= 0: the
        force c_ax d(epsilon)/dt acts along a taut segment (none while it is slack), as
        MoorDyn's internal damping ``BA``. Its damping ratio on the highest axial chain
        mode is about c_ax / (l0 sqrt(EA m)).
    """

    alpha: float = 0.0
    beta: float = 0.0
    axial: object = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "alpha", positive_scalar("alpha", self.alpha, True))
        object.__setattr__(self, "beta", positive_scalar("beta", self.beta, True))
        c = np.atleast_1d(real_array("axial", self.axial, "a finite dashpot c_ax >= 0 [N s] or "
                                                          "one per cable"))
        if c.ndim != 1 or c.size == 0 or not np.all(np.isfinite(c)) or np.any(c < 0):
            raise InvalidParameterError(
                f"axial must be a finite dashpot c_ax >= 0 [N s] or one per cable, got "
                f"{self.axial!r}")
        object.__setattr__(self, "axial",
                           tuple(float(x) for x in c) if c.size > 1 else float(c[0]))

    @classmethod
    def rayleigh(cls, zeta: float, freq1_hz: float, freq2_hz: float) -> TimeDamping:
        """Rayleigh damping with ratio ``zeta`` [-] at the two frequencies [Hz]."""
        zeta = positive_scalar("zeta", zeta, True)
        w1 = 2 * np.pi * positive_scalar("freq1_hz", freq1_hz)
        w2 = 2 * np.pi * positive_scalar("freq2_hz", freq2_hz)
        return cls(alpha=2 * zeta * w1 * w2 / (w1 + w2), beta=2 * zeta / (w1 + w2))

    def axial_per_cable(self, n: int) -> NDArray[np.float64]:
        """c_ax of every cable [N s], shape (n,)."""
        if np.ndim(self.axial) == 0:
            return np.full(n, float(self.axial))
        if np.size(self.axial) != n:
            raise InvalidParameterError(
                f"damping.axial must be one value or {n} values (one per cable), got "
                f"{np.size(self.axial)}")
        return np.array(self.axial, dtype=float)


def explicit_step_limit(model: LumpedMassModel, unstretched_lengths=None,
                        damping: TimeDamping | None = None) -> float:
    """Predicted stability limit of the explicit scheme [s].

    Central differences are stable for omega_max dt < 2 (sqrt(1 + zeta^2) - zeta), with the
    highest axial chain mode omega_max ~ 2 sqrt(EA / m) / l0 and zeta its damping ratio
    (theory.md §7.3); undamped, dt < l0 / sqrt(EA / m). The exact chain value of omega_max
    is smaller by sin((N - 1) pi / 2N), so the true limit lies slightly above this one.

    Parameters
    ----------
    model : LumpedMassModel
    unstretched_lengths : array_like, shape (n_cables,), optional
        L0_i [m] (default the model's).
    damping : TimeDamping, optional
        Its axial dashpots and Rayleigh terms give zeta = c_ax / (l0 sqrt(EA m)) +
        beta omega_max / 2 + alpha / (2 omega_max) on the highest mode.

    Returns
    -------
    float
        min over the cables [s].
    """
    cables = model.robot.cables
    L0 = model.unstretched_lengths if unstretched_lengths is None else \
        checked_lengths(unstretched_lengths, len(cables))
    EA = np.array([cb.EA for cb in cables])
    mass = np.array([cb.mass_per_length for cb in cables])
    l0 = L0 / model.segments
    dt0 = l0 / np.sqrt(EA / mass)
    if damping is None:
        return float(dt0.min())
    w_max = 2.0 / dt0
    zeta = damping.axial_per_cable(len(cables)) / (l0 * np.sqrt(EA * mass)) \
        + 0.5 * damping.beta * w_max + 0.5 * damping.alpha / w_max
    return float(np.min(dt0 * (np.sqrt(1.0 + zeta ** 2) - zeta)))
