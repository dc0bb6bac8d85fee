"""Chord-frame parameters of the linear cable theory, from an elastic-catenary equilibrium.

One cable's equilibrium, seen from its chord A -> B: length, the tension the linear theory
uses, mass and weight per chord length, compliance length and the Irvine parameter
lambda^2 (docs/theory.md §1.2, §3.1). The closed-form dynamic stiffness
(:mod:`dynstiff.cable.dsm`) and the catenary's own ``lambda_sq`` both read these, so the
conventions (mean tension, mass per chord length, compliance length L0 (1 + 8 (d/L)^2)) live
here once; they are argued in the docstring of :mod:`dynstiff.cable.dsm`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.cable.catenary import CatenaryState

__all__ = ["ChordParameters", "chord_parameters", "irvine_lambda_sq", "stack_parameters"]


def irvine_lambda_sq(q: NDArray[np.float64] | float, L: NDArray[np.float64] | float,
                     T: NDArray[np.float64] | float, EA: NDArray[np.float64] | float,
                     L_e: NDArray[np.float64] | float) -> NDArray[np.float64] | float:
    """Irvine parameter lambda^2 = (q L / T)^2 L EA / (T L_e) [-] (theory.md §1.2).

    Elementwise over arrays; complex when EA is (hysteretic damping).
    """
    return (q * L / T) ** 2 * L * EA / (T * L_e)


@dataclass(frozen=True)
class ChordParameters:
    """Chord-frame parameters of the linear theory for one cable equilibrium.

    Attributes
    ----------
    L : float
        Chord length [m].
    T : float
        Tension used by the linear theory [N].
    m : float
        Mass per unit chord length [kg/m].
    c : float or complex
        Viscous damping per unit chord length [N s/m^2]. Complex, c / sqrt(1 + i eta),
        when :class:`dynstiff.FrequencyModel` evaluates the hysteretic damping of all
        stiffness forces by K(omega) = s K(omega / sqrt(s)) (theory.md §12.2); every kernel
        tests ``c != 0``, so a real c behaves as before.
    EA : complex or float
        Axial stiffness [N], EA (1 + i eta) with hysteretic damping.
    q : float
        Weight per chord length perpendicular to the chord [N/m].
    L_e : float
        Compliance length L0 (1 + 8 (d/L)^2) [m].
    cos_theta : float
        Cosine of the chord inclination [-].
    rotation : ndarray, shape (3, 3)
        R = [e_u e_v e_w] (columns): chord direction A -> B, sag direction, out of plane.
    """

    L: float
    T: float
    m: float
    c: float
    EA: complex
    q: float
    L_e: float
    cos_theta: float
    rotation: np.ndarray

    @property
    def sag(self) -> float:
        """Mid-span sag perpendicular to the chord, d = q L^2 / (8 T) [m]."""
        return self.q * self.L**2 / (8.0 * self.T)

    @property
    def K0(self) -> NDArray[np.float64] | float:
        """EA / L_e [N/m] (complex with hysteretic damping)."""
        return self.EA / self.L_e

    @property
    def alpha(self) -> NDArray[np.float64] | float:
        """Static end slope relative to the chord, q L / (2 T) [-]."""
        return self.q * self.L / (2.0 * self.T)

    @property
    def lambda_sq(self) -> NDArray[np.float64] | float:
        """Irvine parameter lambda^2 [-] (:func:`irvine_lambda_sq`; real part if damped),
        a float, or an array for stacked parameters."""
        lam2 = np.real(self.lambda_sq_complex)
        return float(lam2) if np.ndim(lam2) == 0 else lam2

    @property
    def lambda_sq_complex(self) -> NDArray[np.float64] | float:
        """lambda^2 with the complex EA of hysteretic damping [-]."""
        return irvine_lambda_sq(self.q, self.L, self.T, self.EA, self.L_e)

    def psi(self, omega: NDArray[Any]) -> NDArray[Any]:
        """psi = Omega / 2 = (L/2) sqrt((omega^2 m - i omega c) / T) [-], shape of ``omega``."""
        beta_sq = (omega**2 * self.m - 1j * omega * self.c) / self.T if np.any(self.c != 0) \
            else omega**2 * self.m / self.T
        return 0.5 * self.L * np.sqrt(beta_sq)


def chord_parameters(state: CatenaryState, tension: str = "mean") -> ChordParameters:
    """Chord-frame parameters of the linear theory from an elastic-catenary equilibrium.

    Parameters
    ----------
    state : CatenaryState
        Static equilibrium from :func:`dynstiff.solve_catenary`.
    tension : {"mean", "chord"}
        "mean": tension averaged over the cable (default); "chord": H / cos(theta)
        (Irvine's H*). A vertical chord always uses the mean tension.

    Returns
    -------
    ChordParameters

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> p = ds.chord_parameters(state)
    >>> print(f"lambda^2 = {p.lambda_sq:.4f}, T = {p.T:.1f} N")
    lambda^2 = 0.3867, T = 299.1 N
    """
    if tension not in ("mean", "chord"):
        raise InvalidParameterError(f"tension must be 'mean' or 'chord', got {tension!r}")
    cable, g = state.cable, state.g
    L = state.chord_length
    e_u = state.chord / L
    g_vec = np.array([0.0, 0.0, -g])
    g_perp = g_vec - (g_vec @ e_u) * e_u
    gp = np.linalg.norm(g_perp)
    if gp > 1e-12 * max(g, 1e-300):
        e_v = g_perp / gp
    else:                                 # vertical chord (or g = 0): any transverse pair
        e_v = state.horizontal_direction - (state.horizontal_direction @ e_u) * e_u
        e_v /= np.linalg.norm(e_v)
    e_w = cross(e_u, e_v)
    cos_theta = state.cos_theta
    if tension == "chord" and cos_theta > 1e-12:
        T = state.H / cos_theta
    else:
        T = state.mean_tension
    L0 = state.unstretched_length
    m = cable.mass_per_length * L0 / L
    c = cable.viscous_damping * L0 / L
    q = m * g * cos_theta
    d_over_L = q * L / (8.0 * T)
    L_e = L0 * (1.0 + 8.0 * d_over_L**2)
    EA = cable.EA * (1.0 + 1j * cable.loss_factor) if cable.loss_factor > 0 else cable.EA
    return ChordParameters(L=L, T=T, m=m, c=c, EA=EA, q=q, L_e=L_e, cos_theta=cos_theta,
                           rotation=np.column_stack([e_u, e_v, e_w]))


def stack_parameters(params: tuple[ChordParameters, ...]) -> ChordParameters:
    """ChordParameters of several cables stacked into one with (n_cables,) array fields, for
    evaluating all cables in one broadcast call (see :func:`dynstiff.cable.dsm.local_entries`)."""
    def arr(name: str) -> NDArray[np.float64]:
        return np.array([getattr(p, name) for p in params])
    return ChordParameters(L=arr("L"), T=arr("T"), m=arr("m"), c=arr("c"), EA=arr("EA"),
                           q=arr("q"), L_e=arr("L_e"), cos_theta=arr("cos_theta"),
                           rotation=None)
