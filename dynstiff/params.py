"""Parameter types: frozen, validated dataclasses.

Notation
--------
=====================  ===========================================  ==========
symbol                 meaning                                      unit
=====================  ===========================================  ==========
``mass_per_length``    m, mass per *unstretched* length              kg/m
``EA``                 axial stiffness (referred to unstretched L0)  N
``viscous_damping``    c, transverse viscous damping per length      N s/m^2
``loss_factor``        eta, hysteretic loss factor, EA -> EA(1+i eta) --
=====================  ===========================================  ==========
"""

from dataclasses import dataclass

from ._validate import positive_scalar

__all__ = ["Cable"]


@dataclass(frozen=True)
class Cable:
    """Properties of one heavy elastic cable.

    Parameters
    ----------
    mass_per_length : float
        Mass per unit *unstretched* length m [kg/m], > 0.
    EA : float
        Axial stiffness [N], > 0. Strain is tension / EA, referred to the unstretched length.
    viscous_damping : float, optional
        Viscous damping c per unit length [N s/m^2], >= 0. Enters the linear dynamics as the
        complex mass m - i c / omega (Starossek 1994, eq. 1: H v'' + h y'' = m v_tt + c v_t).
    loss_factor : float, optional
        Hysteretic (structural) loss factor eta [-], >= 0; the dynamics use EA (1 + i eta).

    Raises
    ------
    InvalidParameterError
        If a value is not finite, or out of range; the message names the field.
    """

    mass_per_length: float
    EA: float
    viscous_damping: float = 0.0
    loss_factor: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "mass_per_length",
                           positive_scalar("mass_per_length", self.mass_per_length))
        object.__setattr__(self, "EA", positive_scalar("EA", self.EA))
        object.__setattr__(self, "viscous_damping",
                           positive_scalar("viscous_damping", self.viscous_damping,
                                           allow_zero=True))
        object.__setattr__(self, "loss_factor",
                           positive_scalar("loss_factor", self.loss_factor, allow_zero=True))

    @property
    def is_damped(self):
        """True when viscous or hysteretic damping is present."""
        return self.viscous_damping > 0 or self.loss_factor > 0

    def weight_per_length(self, g):
        """Weight per unstretched length w0 = m g [N/m] for gravity ``g`` [m/s^2]."""
        return self.mass_per_length * positive_scalar("g", g, allow_zero=True)
