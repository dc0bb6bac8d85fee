"""Robot dynamic stiffness K(omega): cable DSMs rotated, mapped to the platform and assembled.

    K(omega) = sum_i J_i^T K_B,i(omega) J_i + K_geo - omega^2 M_p        (theory.md §4)

J_i = [I, -[r_i]x] maps the platform motion x = (dp, dtheta) about P to the motion of the
attachment point B_i; K_B,i is the end-B dynamic stiffness of cable i (anchor clamped), in the
global frame; K_geo is the geometric stiffness of the static cable forces and gravity acting on
rotating lever arms; M_p the platform's rigid-body mass matrix. Only the free DOFs are kept.

Each K_B,i is a combination of five dyads of its chord frame, so the whole sum over cables is a
single (n_omega, 5 n) @ (5 n, n_free^2) product: no loop over frequencies.
"""

import numpy as np

from ._validate import omega_array
from .cable_dsm import (DEFAULT_CHORDWISE_INERTIA, _local_entries, _mode_count_Omega,
                        chord_parameters, dyad_basis, stack_parameters)
from .platform import DOF_NAMES, lever_map, platform_mass_matrix
from .robot import geometric_stiffness

__all__ = ["FrequencyModel"]


class FrequencyModel:
    """Frequency-domain model of a cable robot at a static equilibrium.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    tension : {"mean", "chord"}
        Tension of the cables' linear theory (see :func:`dynstiff.cable_dsm.chord_parameters`).
    chordwise_inertia : bool
        Include the consistent chordwise mass of the cables (theory.md §3.6).

    Attributes
    ----------
    free_dofs : tuple of str
        Names of the free DOFs, the order of every matrix this model returns.
    K_geo : ndarray, shape (6, 6)
        Geometric stiffness [N m/rad] (all DOFs).
    M_p : ndarray, shape (6, 6)
        Platform mass matrix about P (all DOFs).
    """

    def __init__(self, equilibrium, tension="mean", chordwise_inertia=DEFAULT_CHORDWISE_INERTIA):
        self.equilibrium = equilibrium
        self.tension = tension
        self.chordwise_inertia = bool(chordwise_inertia)
        robot = equilibrium.robot
        pose = equilibrium.pose
        self.free_dofs = robot.platform.free_dofs
        fi = robot.platform.free_index
        self._fi = fi
        self.params = [chord_parameters(s, tension) for s in equilibrium.states]
        self._stack = stack_parameters(self.params)
        self.lever_arms = equilibrium.lever_arms
        # (5 n, nf*nf) map from dyad coefficients of every cable to the free-DOF matrix
        blocks = []
        for p, r in zip(self.params, self.lever_arms):
            J = lever_map(r, fi)                                   # (3, nf)
            D = dyad_basis(p.rotation).reshape(5, 3, 3)
            blocks.append(np.einsum("ai,kab,bj->kij", J, D, J).reshape(5, -1))
        self._G = np.vstack(blocks)
        K_geo = np.zeros((6, 6))
        K_geo[3:, 3:] = geometric_stiffness(robot, pose, equilibrium.states)
        self.K_geo = K_geo
        self.M_p = platform_mass_matrix(robot.platform, pose.matrix)
        # With held rotations the reaction moment about a held axis makes the free block of
        # K_geo non-symmetric by 1/2 [M_reaction]x, an artefact of the non-commuting rotation
        # vector; the conservative (potential-energy Hessian) stiffness is its symmetric part.
        # At a full 6-DOF equilibrium the block is already symmetric.
        Kg = K_geo[np.ix_(fi, fi)]
        self._Kg = 0.5 * (Kg + Kg.T)
        self._M = self.M_p[np.ix_(fi, fi)]
        self.damped = any(c.is_damped for c in robot.cables)

    @property
    def n_free(self):
        """Number of free DOFs."""
        return len(self._fi)

    def cable_coefficients(self, omega):
        """Dyad coefficients (uu, uv, vu, vv, ww) of every cable's end-B DSM, all cables in one
        broadcast call, shape (n_omega, 5 n_cables), cable-major."""
        omega = np.asarray(omega)
        k_uu, k_uv, k_vv, _, kw_s, _, m_ax = _local_entries(self._stack, omega[:, None],
                                                             self.chordwise_inertia)
        C = np.stack([k_uu + 2.0 * m_ax, -k_uv, -k_uv, k_vv, kw_s + 0.0 * k_uu], axis=2)
        C = C.reshape(omega.size, -1)
        if not self.damped and np.isrealobj(omega):
            C = np.real(C)
        return C

    def dynamic_stiffness(self, omega):
        """K(omega) on the free DOFs, shape (n_omega, n_free, n_free).

        Parameters
        ----------
        omega : float or array_like, shape (n_omega,)
            Angular frequencies [rad/s], >= 0.

        Returns
        -------
        ndarray [N/m, N, N m/rad]; real when no cable is damped, complex otherwise.
        """
        omega = omega_array(omega)
        nf = self.n_free
        K = (self.cable_coefficients(omega) @ self._G).reshape(omega.size, nf, nf)
        return K + self._Kg - (omega**2)[:, None, None] * self._M

    def _dynamic_stiffness_complex(self, omega):
        """K(omega) for complex omega (no validation), shape (n, n_free, n_free)."""
        omega = np.atleast_1d(np.asarray(omega, dtype=complex))
        nf = self.n_free
        K = (self.cable_coefficients(omega) @ self._G).reshape(omega.size, nf, nf)
        return K + self._Kg - (omega**2)[:, None, None] * self._M

    def cable_mode_count(self, omega):
        """Sum over cables of the clamped-clamped mode counts J0 below omega, (n_omega,)."""
        omega = omega_array(omega)
        st = self._stack
        lam2 = np.real((st.q * st.L / st.T) ** 2 * st.L * st.EA / (st.T * st.L_e))
        Omega = omega[:, None] * st.L * np.sqrt(st.m / st.T)
        return _mode_count_Omega(Omega, lam2).sum(axis=1)

    def mode_count(self, omega):
        """Wittrick-Williams count J(omega) = J0 + s{K(omega)}: eigenfrequencies below omega.

        Requires undamped cables (real symmetric K). Shape (n_omega,).
        """
        K = self.dynamic_stiffness(omega)
        if np.iscomplexobj(K):
            K = K.real
        with np.errstate(invalid="ignore"):
            ev = np.linalg.eigvalsh(K)
        return self.cable_mode_count(omega) + np.sum(ev < 0, axis=1)

    def massless_stiffness(self):
        """Static stiffness of the massless-cable model (K_B(0) of every cable) + K_geo,
        shape (n_free, n_free)."""
        return self.dynamic_stiffness(0.0)[0].real

    def dof_names(self):
        """Names of the free DOFs."""
        return tuple(DOF_NAMES[i] for i in self._fi)

    # thin wrappers over the analysis modules
    def frf(self, omega, inputs=None, outputs=None, point=None, kind="receptance"):
        """Frequency response functions; see :func:`dynstiff.frf.frf`."""
        from .frf import frf
        return frf(self, omega, inputs=inputs, outputs=outputs, point=point, kind=kind)

    def eigenfrequencies(self, n_modes=None, fmax_hz=None):
        """Natural frequencies [Hz], ascending; see :func:`dynstiff.eigen.eigenfrequencies`."""
        from .eigen import eigenfrequencies
        return eigenfrequencies(self, n_modes=n_modes, fmax_hz=fmax_hz)

    def modes(self, n_modes=None, fmax_hz=None):
        """Modes with shapes, labels and energy fractions; see :func:`dynstiff.eigen.modes`."""
        from .eigen import modes
        return modes(self, n_modes=n_modes, fmax_hz=fmax_hz)
