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

from __future__ import annotations

from dataclasses import dataclass

from dynstiff._validate import positive_scalar

__all__ = ["Cable", "Damping", "DEFAULT_DAMPING"]


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
        Hysteretic (structural) loss factor eta [-], in [0, 1) (steel and fibre ropes hold
        1e-3 to 0.1; eta >= 1 is no longer light damping); the dynamics use EA (1 + i eta).

    Raises
    ------
    InvalidParameterError
        If a value is not finite, or out of range; the message names the field.

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=8.2051e-6 * 200e9)   # 4 mm steel
    >>> print(f"{cable.EA / 1e6:.3f} MN")
    1.641 MN
    """

    mass_per_length: float
    EA: float
    viscous_damping: float = 0.0
    loss_factor: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass_per_length",
                           positive_scalar("mass_per_length", self.mass_per_length))
        object.__setattr__(self, "EA", positive_scalar("EA", self.EA))
        object.__setattr__(self, "viscous_damping",
                           positive_scalar("viscous_damping", self.viscous_damping,
                                           allow_zero=True))
        eta = positive_scalar("loss_factor", self.loss_factor, allow_zero=True)
        if not eta < 1:
            from dynstiff.errors import InvalidParameterError
            raise InvalidParameterError(f"loss_factor must be in [0, 1) [-], got {eta!r}")
        object.__setattr__(self, "loss_factor", eta)

    @property
    def is_damped(self) -> bool:
        """True when viscous or hysteretic damping is present."""
        return self.viscous_damping > 0 or self.loss_factor > 0

    def weight_per_length(self, g: float) -> float:
        """Weight per unstretched length w0 = m g [N/m] for gravity ``g`` [m/s^2]."""
        return self.mass_per_length * positive_scalar("g", g, allow_zero=True)


@dataclass(frozen=True)
class Damping:
    """Damping of an analysis, on top of the cables' own (theory.md §12.2).

    The defaults are chosen values, not measurements: a steel wire rope dissipates a few
    tenths of a percent of its strain energy per radian (loss factor 0.005-0.02), and the
    platform's winches, pulleys and frame add about one percent of critical damping to its
    rigid-body modes. A scene's ``[damping]`` section or ``--damping`` replaces them; zeros
    give the undamped model.

    Parameters
    ----------
    platform_ratio : float
        zeta_p, modal damping ratio of the platform modes [-], >= 0, < 1 (default 0.01).
    cable_loss_factor : float
        eta_c, hysteretic loss factor of all cable stiffness forces, transverse (dynamic
        tension) and axial (elastic) [-], >= 0, < 1 (default 0.01).
    cable_viscous_damping : float
        c, viscous damping per length of every cable [N s/m^2], >= 0, acting on every cable
        motion through the complex mass m - i c / omega (default 0); added to a cable's own
        ``viscous_damping``.

    Examples
    --------
    >>> import dynstiff as ds
    >>> d = ds.Damping(platform_ratio=0.02)
    >>> d.platform_ratio, d.cable_loss_factor
    (0.02, 0.01)
    """

    platform_ratio: float = 0.01
    cable_loss_factor: float = 0.01
    cable_viscous_damping: float = 0.0

    def __post_init__(self) -> None:
        for name in ("platform_ratio", "cable_loss_factor", "cable_viscous_damping"):
            v = positive_scalar(name, getattr(self, name), allow_zero=True)
            if name != "cable_viscous_damping" and not v < 1:
                from dynstiff.errors import InvalidParameterError
                raise InvalidParameterError(f"{name} must be < 1, got {v!r}")
            object.__setattr__(self, name, v)

    @property
    def is_zero(self) -> bool:
        """True when no damping is added."""
        return not (self.platform_ratio or self.cable_loss_factor or self.cable_viscous_damping)

    def text(self) -> str:
        """One line for a report: ``damping: platform zeta 0.01, cable eta 0.01, ...``."""
        return (f"damping: platform modal ratio {self.platform_ratio:g}, cable loss factor "
                f"{self.cable_loss_factor:g} (axial and transverse), cable viscous "
                f"{self.cable_viscous_damping:g} N s/m^2")


#: The damping an analysis uses when the scene gives no ``[damping]`` section.
DEFAULT_DAMPING = Damping()
