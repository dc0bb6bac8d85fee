"""The cable pendulum's parameters and derived data, and its construction from a scene
(notation: :mod:`dynstiff.timedomain.pendulum`)."""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.constants import STANDARD_GRAVITY
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.scenes.loader import Scene


@dataclass(frozen=True)
class CablePendulum:
    """Inverted pendulum on two cables (seed paper 004).

    Parameters
    ----------
    inertia : float
        I_A, moment of inertia about the pin [kg m^2]; >= mass * com_distance^2 (checked to a
        relative 1e-12 for rounding: mass * com_distance^2 * (1 - 1e-12) is accepted).
    mass : float
        Pendulum mass m [kg].
    com_distance : float
        Distance c from the pin to the centre of mass [m] (l/2 for a uniform rod).
    attach_distance : float
        Distance d from the pin to the cable attachment D [m].
    half_span : float
        a, horizontal distance from the pin to each cable end [m].
    stiffness : float
        k, axial stiffness of a whole cable [N/m].
    damping : float
        b, axial damping coefficient of a whole cable [N s/m], >= 0.
    preload : float, optional
        P, cable tension at rest with the pendulum upright [N], >= 0.
    cable_mass : float, optional
        m_c, mass of one cable [kg]; > 0 when ``n_masses`` > 0, unused otherwise.
    n_masses : int, optional
        Point masses per cable; 0 is the massless cable (default).
    end_height : float, optional
        h, height of the cable ends above the pin [m] (default 0: the pin's level).
    g : float, optional
        Gravity [m/s^2].

    The real parameters are stored as Python floats, ``n_masses`` as an int.

    Raises
    ------
    InvalidParameterError
        A value out of range; the message names it.
    """

    inertia: float
    mass: float
    com_distance: float
    attach_distance: float
    half_span: float
    stiffness: float
    damping: float
    preload: float = 0.0
    cable_mass: float = 0.0
    n_masses: int = 0
    end_height: float = 0.0
    g: float = STANDARD_GRAVITY

    def __post_init__(self) -> None:
        for name in ("inertia", "mass", "attach_distance", "half_span", "stiffness"):
            object.__setattr__(self, name, positive_scalar(name, getattr(self, name)))
        for name in ("com_distance", "damping", "preload", "cable_mass", "g"):
            object.__setattr__(self, name, positive_scalar(name, getattr(self, name),
                                                           allow_zero=True))
        h = float(self.end_height)
        if not np.isfinite(h):
            raise InvalidParameterError(f"end_height must be finite [m], got {self.end_height!r}")
        object.__setattr__(self, "end_height", h)
        n = self.n_masses
        if isinstance(n, bool) or not isinstance(n, Integral) or n < 0:
            raise InvalidParameterError(f"n_masses must be an integer >= 0, got {n!r}")
        object.__setattr__(self, "n_masses", int(n))
        if n > 0 and self.cable_mass <= 0:
            raise InvalidParameterError(
                f"cable_mass must be > 0 [kg] for a point-mass cable (n_masses={n}), got "
                f"{self.cable_mass!r}")
        if self.inertia < self.mass * self.com_distance ** 2 * (1 - 1e-12):
            raise InvalidParameterError(
                f"inertia must be >= mass * com_distance^2 = "
                f"{self.mass * self.com_distance ** 2:g} kg m^2 (parallel-axis theorem), got "
                f"{self.inertia!r}")
        if self.preload / self.stiffness >= self.chord_length:
            raise InvalidParameterError(
                f"preload {self.preload:g} N needs a stretch P/k = "
                f"{self.preload / self.stiffness:g} m longer than the chord "
                f"{self.chord_length:g} m")

    # ------------------------------------------------------------------ derived data
    @property
    def chord_length(self) -> float:
        """L = |E_i - D| at rest [m]."""
        return float(np.hypot(self.half_span, self.attach_distance - self.end_height))

    @property
    def unstretched_length(self) -> float:
        """L0 = L - P / k [m]."""
        return self.chord_length - self.preload / self.stiffness

    @property
    def node_mass(self) -> float:
        """Mass of one interior point mass m_c / (n + 1) [kg] (0 for massless cables)."""
        return self.cable_mass / (self.n_masses + 1) if self.n_masses else 0.0

    @property
    def pin_inertia(self) -> float:
        """I_A plus the two end half masses at D [kg m^2]."""
        return self.inertia + self.node_mass * self.attach_distance ** 2

    @property
    def n_dof(self) -> int:
        """Degrees of freedom 1 + 4 n."""
        return 1 + 4 * self.n_masses

    @property
    def lever_factor(self) -> float:
        """dL/dphi at rest, a d / L [m/rad]."""
        return self.half_span * self.attach_distance / self.chord_length

    def linear_stiffness(self) -> float:
        """Rotational stiffness of the upright pendulum on straight cables at rest [N m/rad].

        K_phi = 2 [k (dL/dphi)^2 + P d^2L/dphi^2] - m g c with dL/dphi = a d / L and
        d^2L/dphi^2 = (d h - (a d / L)^2) / L (second derivative of |E - D(phi)| at phi = 0):
        the preload *lowers* the stiffness when the ends are below D (h < d), since it also
        compresses the pendulum. Cable masses are not included.
        """
        L, s = self.chord_length, self.lever_factor
        curv = (self.attach_distance * self.end_height - s ** 2) / L
        return 2.0 * (self.stiffness * s ** 2 + self.preload * curv) - (
            self.mass * self.g * self.com_distance)

    def natural_frequency_hz(self) -> float:
        """sqrt(K_phi / I_A) / (2 pi) [Hz] of the massless model at rest (0 if K_phi <= 0)."""
        return float(np.sqrt(max(self.linear_stiffness(), 0.0) / self.pin_inertia) / (2 * np.pi))

    def slack_amplitude(self) -> float:
        """Excitation amplitude [m] above which both cables go slack when the ends move
        inward (quasi-static, straight cables): x0 = P / (k dL/dx), dL/dx = a / L."""
        return self.preload * self.chord_length / (self.stiffness * self.half_span)

    # ------------------------------------------------------------------ kernels
    def gravity_moment(self) -> float:
        """Coefficient of sin(phi) in the gravity moment about A [N m]."""
        return (self.mass * self.com_distance + self.node_mass * self.attach_distance) * self.g

    def mass_diagonal(self) -> NDArray[np.float64]:
        """Diagonal of the mass matrix: pin inertia [kg m^2], then the node masses [kg]."""
        return np.concatenate([[self.pin_inertia], np.full(4 * self.n_masses, self.node_mass)])

    def state_scale(self, omega: NDArray[np.float64]) -> NDArray[np.float64]:
        """Per-component scale of the state (rad, m, rad/s, m/s), shape (c, 2 n_dof)."""
        w = np.maximum(np.asarray(omega, dtype=float), 2 * np.pi * self.natural_frequency_hz())
        q = np.concatenate([[1.0], np.full(4 * self.n_masses, self.chord_length)])
        return np.concatenate([np.broadcast_to(q, (w.size, q.size)),
                               w[:, None] * q[None, :]], axis=1)



def checked_integer(name: str, value: int, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, Integral) or value < minimum:
        raise InvalidParameterError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)



def from_scene(scene: Scene, preload=None, cable_mass=None, n_masses: int = 0, damping=None,
               end_height=None) -> CablePendulum:
    """The pendulum of a scene: a 1-DOF platform (free DOF "ry") on two cables.

    Reads the pin (platform frame origin), the centre of mass, I_A = I_G,yy + m |c_G|^2, the
    attachment D (both cables), the anchors B, C (symmetric about the pin) and the cables.
    The scene's static tension P_s = t_min (inverse statics at the upright pose) and its EA
    give the whole-cable stiffness k = (EA + P_s) / L (straight cable, EA / L0 = k).

    Parameters
    ----------
    scene : Scene
        E.g. ``dynstiff.load_scene("pendulum")``.
    preload : float, optional
        P [N] (default: the scene's static tension P_s).
    cable_mass : float, optional
        Mass of one cable [kg] (default: mass_per_length x the scene's unstretched length).
    n_masses : int
        Point masses per cable (0: massless cables).
    damping : float, optional
        b [N s/m] (default ``scene.study["damping_time"]`` x k, else 0).
    end_height : float, optional
        Height of B and C [m] (default: the scene's anchors).

    Returns
    -------
    CablePendulum

    Raises
    ------
    InvalidParameterError
        The scene is not such a pendulum (the message says what differs).
    """
    rob = scene.robot
    pl = rob.platform
    if pl.free_dofs != ("ry",) or rob.n_cables != 2:
        raise InvalidParameterError(
            f"scene {scene.name!r}: a cable pendulum has free_dofs ('ry',) and 2 cables, got "
            f"{pl.free_dofs} and {rob.n_cables}")
    b = rob.attachments
    A = rob.anchors
    if not (np.allclose(b[0], b[1]) and abs(b[0, 0]) + abs(b[0, 1]) < 1e-12 and b[0, 2] > 0):
        raise InvalidParameterError(
            f"scene {scene.name!r}: both cables must attach at one point (0, 0, d), d > 0, "
            f"got {b.tolist()}")
    if not (np.allclose(A[0] * [-1, 1, 1], A[1]) and A[0, 0] < 0 and A[0, 1] == 0):
        raise InvalidParameterError(
            f"scene {scene.name!r}: anchors must be (-a, 0, h) and (a, 0, h), got {A.tolist()}")
    cG = pl.center_of_mass
    if abs(cG[0]) + abs(cG[1]) > 1e-12:
        raise InvalidParameterError(
            f"scene {scene.name!r}: the centre of mass must lie on the pendulum axis (0, 0, c),"
            f" got {cG.tolist()}")
    d, a, h = float(b[0, 2]), float(-A[0, 0]), float(A[0, 2])
    L = float(np.hypot(a, d - h))
    P_s = rob.tension_limits[0]
    cab = rob.cables[0]
    k = (cab.EA + P_s) / L
    study = scene.study or {}
    if damping is None:
        damping = study.get("damping_time", 0.0) * k
    if cable_mass is None:
        cable_mass = cab.mass_per_length * cab.EA / k
    return CablePendulum(
        inertia=pl.inertia[1, 1] + pl.mass * float(cG @ cG), mass=pl.mass,
        com_distance=float(cG[2]), attach_distance=d, half_span=a, stiffness=k,
        damping=damping, preload=P_s if preload is None else preload,
        cable_mass=cable_mass, n_masses=n_masses,
        end_height=h if end_height is None else end_height, g=rob.g)
