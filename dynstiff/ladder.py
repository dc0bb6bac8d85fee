"""A ladder of cable models behind one interface, from cheapest to richest.

==========  =================================================================  ==============
rung        cable model                                                        modes it has
==========  =================================================================  ==============
"spring"    (a) massless straight spring: (EA/L0) u u^T + (T/L)(I - u u^T)      global only
"catenary"  (b) massless elastic catenary: exact static 3x3 end stiffness       global only
"dsm"       (c) closed-form dynamic stiffness (Irvine-Caughey, theory.md §3)    global + local
"lumped"    (d) lumped-mass chains with N segments per cable (theory.md §7)     global + local
==========  =================================================================  ==============

Every model built by :func:`build_model` answers ``eigenfrequencies(n_modes=None,
fmax_hz=None)`` [Hz] and ``frf(omega, inputs, outputs)`` (a :class:`dynstiff.frf.FRFResult`),
and carries ``rung``. All share the platform, the geometric stiffness K_geo and gravity.
"""

import numpy as np
import scipy.linalg

from ._validate import omega_array
from .assembly import FrequencyModel
from .errors import InvalidParameterError
from .frf import FRFResult, channel_maps
from .platform import lever_map, platform_mass_matrix
from .robot import geometric_stiffness

__all__ = ["RUNGS", "StaticCableModel", "build_model"]

#: The rungs, cheapest first.
RUNGS = ("spring", "catenary", "dsm", "lumped")


class StaticCableModel:
    """Robot with massless cables: constant stiffness K = sum J^T K_i J + K_geo and mass M_p.

    Parameters
    ----------
    equilibrium : Equilibrium
    stiffness : {"spring", "catenary"}
        "spring": straight elastic springs, K_i = (EA/L0) u u^T + (T/L)(I - u u^T) with u the
        chord direction and T the tension at B; "catenary": the exact elastic-catenary static
        end stiffness of each cable (:attr:`CatenaryState.static_stiffness`).
    """

    def __init__(self, equilibrium, stiffness="catenary"):
        if stiffness not in ("spring", "catenary"):
            raise InvalidParameterError(
                f"stiffness must be 'spring' or 'catenary', got {stiffness!r}")
        self.rung = stiffness
        self.equilibrium = equilibrium
        robot, pose = equilibrium.robot, equilibrium.pose
        fi = robot.platform.free_index
        K = np.zeros((6, 6))
        for i, (s, r) in enumerate(zip(equilibrium.states, equilibrium.lever_arms)):
            if stiffness == "spring":
                L = s.chord_length
                u = s.chord / L
                Ki = (robot.cables[i].EA / s.unstretched_length * np.outer(u, u)
                      + s.tension_at_end / L * (np.eye(3) - np.outer(u, u)))
            else:
                Ki = s.static_stiffness
            J = lever_map(r)
            K += J.T @ Ki @ J
        K[3:, 3:] += geometric_stiffness(robot, pose, equilibrium.states)
        K = K[np.ix_(fi, fi)]
        self.K = 0.5 * (K + K.T)
        self.M = platform_mass_matrix(robot.platform, pose.matrix)[np.ix_(fi, fi)]
        self._fi = fi

    def eigenfrequencies(self, n_modes=None, fmax_hz=None):
        """Natural frequencies [Hz] (at most n_free), ascending."""
        lam = scipy.linalg.eigh(self.K, self.M, eigvals_only=True)
        f = np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi)
        if fmax_hz is not None:
            f = f[f < fmax_hz]
        return f if n_modes is None else f[:n_modes]

    def frf(self, omega, inputs=None, outputs=None, point=None):
        """Receptance of the platform (see :func:`dynstiff.frf.frf` for the channels),
        H of shape (n, n_out, n_in)."""
        omega = omega_array(omega)
        B, C, in_names, out_names = channel_maps(self._fi, self.equilibrium.pose.matrix,
                                                 inputs, outputs, point)
        D = self.K[None] - (omega**2)[:, None, None] * self.M[None]
        H = C @ np.linalg.solve(D.astype(complex), np.broadcast_to(B, (omega.size,) + B.shape))
        return FRFResult(freq_hz=omega / (2 * np.pi), H=H, inputs=in_names, outputs=out_names,
                         kind="receptance")


class _DSMRung(FrequencyModel):
    rung = "dsm"


def build_model(equilibrium, rung, segments=30):
    """The model of rung ``rung`` for this equilibrium.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    rung : {"spring", "catenary", "dsm", "lumped"}
    segments : int or sequence of int
        Segments per cable of the "lumped" rung.

    Returns
    -------
    StaticCableModel, FrequencyModel or LumpedMassModel (equilibrated), with ``.rung``.
    """
    if rung in ("spring", "catenary"):
        return StaticCableModel(equilibrium, rung)
    if rung == "dsm":
        return _DSMRung(equilibrium)
    if rung == "lumped":
        from .lumped import LumpedMassModel
        m = LumpedMassModel(equilibrium.robot, equilibrium.unstretched_lengths,
                            segments=segments)
        m.equilibrium(initial_pose=equilibrium.pose)
        m.rung = "lumped"
        return m
    raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
