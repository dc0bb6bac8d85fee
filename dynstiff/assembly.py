"""Robot dynamic stiffness K(omega): cable DSMs rotated, mapped to the platform and assembled.

    K(omega) = sum_i J_i^T K_B,i(omega) J_i + K_geo - omega^2 M_p        (theory.md §4)

J_i = [I, -[r_i]x] maps the platform motion x = (dp, dtheta) about P to the motion of the
attachment point B_i; K_B,i is the end-B dynamic stiffness of cable i (anchor clamped), in the
global frame; K_geo is the geometric stiffness of the static cable forces and gravity acting on
rotating lever arms; M_p the platform's rigid-body mass matrix. Only the free DOFs are kept.

Each K_B,i is a combination of five dyads of its chord frame, so the whole sum over cables is a
single (n_omega, 5 n) @ (5 n, n_free^2) product: no loop over frequencies.
"""

from dataclasses import replace

import numpy as np

from ._validate import omega_array
from ._vec import cross
from .cable_dsm import (DEFAULT_CHORDWISE_INERTIA, cable_field, cable_kinetic_energy,
                        check_frequency_range, chord_parameters, dyad_basis, end_block_coefficients,
                        end_block_coefficients_and_count, mode_count_nondimensional,
                        stack_parameters)
from .model_base import PlatformModel, require_equilibrium
from .platform import lever_map, platform_mass_matrix
from .robot import geometric_stiffness

__all__ = ["FrequencyModel"]


class FrequencyModel(PlatformModel):
    """The "dsm" rung: closed-form dynamic stiffness of every cable, assembled (theory.md §4).

    Immutable; the interface of every model is described in :mod:`dynstiff.model_base`.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    tension : {"mean", "chord"}
        Tension of the cables' linear theory (see :func:`dynstiff.chord.chord_parameters`).
    chordwise_inertia : bool
        Include the consistent chordwise mass of the cables (theory.md §3.6).
    damping : bool
        Keep the cables' damping (default); False builds the undamped model.

    Attributes
    ----------
    rung, robot, equilibrium, pose, free_dofs, free_index, n_free, platform_mass, damped
        As every model (:mod:`dynstiff.model_base`).
    params : tuple of ChordParameters
        Chord-frame parameters of every cable.
    lever_arms : ndarray, shape (n_cables, 3)
        r_i = R_p b_i [m].
    K_geo : ndarray, shape (6, 6)
        Geometric stiffness [N m/rad] (all DOFs; only the rotation block is non-zero).
    M_p : ndarray, shape (6, 6)
        Platform mass matrix about P (all DOFs).
    assembly_map : ndarray, shape (5 n_cables, n_free**2)
        Dyad coefficients of every cable (``cable_coefficients``) -> K on the free DOFs.
    K_geo_free : ndarray, shape (n_free, n_free)
        Symmetric part of K_geo on the free DOFs (the conservative stiffness).
    """

    rung = "dsm"

    def __init__(self, equilibrium, tension="mean", chordwise_inertia=DEFAULT_CHORDWISE_INERTIA,
                 damping=True):
        robot, pose = require_equilibrium(equilibrium).robot, equilibrium.pose
        self._init_platform(robot, equilibrium, pose)
        self.tension = tension
        self.chordwise_inertia = bool(chordwise_inertia)
        params = [chord_parameters(s, tension) for s in equilibrium.states]
        if not damping:
            params = [replace(p, c=0.0, EA=float(np.real(p.EA))) for p in params]
            self.damped = False
        self.params = tuple(params)
        self.stacked_params = stack_parameters(self.params)
        self.lever_arms = np.array(equilibrium.lever_arms, dtype=float)
        fi = self.free_index
        # (5 n, nf*nf) map from dyad coefficients of every cable to the free-DOF matrix
        blocks = []
        for p, r in zip(self.params, self.lever_arms):
            J = lever_map(r, fi)                                   # (3, nf)
            D = dyad_basis(p.rotation).reshape(5, 3, 3)
            blocks.append(np.einsum("ai,kab,bj->kij", J, D, J).reshape(5, -1))
        self._assembly = np.vstack(blocks)
        self.assembly_map = self._assembly
        K_geo = np.zeros((6, 6))
        K_geo[3:, 3:] = geometric_stiffness(robot, pose, equilibrium.states)
        self.K_geo = K_geo
        self.M_p = platform_mass_matrix(robot.platform, pose.matrix)
        # With held rotations the reaction moment about a held axis makes the free block of
        # K_geo non-symmetric by 1/2 [M_reaction]x, an artefact of the non-commuting rotation
        # vector; the conservative (potential-energy Hessian) stiffness is its symmetric part.
        # At a full 6-DOF equilibrium the block is already symmetric.
        Kg = K_geo[np.ix_(fi, fi)]
        self._K_geo_free = 0.5 * (Kg + Kg.T)
        self.K_geo_free = self._K_geo_free
        self._freeze()

    def cable_coefficients(self, omega):
        """Dyad coefficients (uu, uv, vu, vv, ww) of every cable's end-B DSM, all cables in one
        broadcast call, shape (n_omega, 5 n_cables), cable-major [N/m].

        ``omega`` [rad/s], shape (n_omega,), validated, real or complex."""
        C = end_block_coefficients(self.stacked_params, omega, self.chordwise_inertia)
        C = C.reshape(omega.size, 5 * len(self.params))
        if not self.damped and np.isrealobj(omega):
            C = np.real(C)
        return C

    def dynamic_stiffness(self, omega):
        """K(omega) on the free DOFs, shape (n_omega, n_free, n_free) (theory.md §4).

        Parameters
        ----------
        omega : float or array_like, shape (n_omega,)
            Angular frequencies [rad/s]: real >= 0, or complex (finite) for damped roots.

        Returns
        -------
        ndarray [N/m, N, N m/rad]; real when no cable is damped and omega is real, complex
        otherwise. Entries are inf/NaN exactly on a clamped-cable pole.
        """
        omega = omega_array(omega, complex_ok=True)
        check_frequency_range(self.stacked_params, omega)
        nf = self.n_free
        K = (self.cable_coefficients(omega) @ self._assembly).reshape(omega.size, nf, nf)
        return K + self._K_geo_free - (omega**2)[:, None, None] * self.platform_mass

    def dynamic_stiffness_and_count(self, omega):
        """K(omega) and J0(omega) of the undamped model at real omega, from one evaluation of
        the cable kernels (a Wittrick-Williams count needs both, theory.md §5, §14.2).

        Parameters
        ----------
        omega : float or array_like, shape (n_omega,)
            [rad/s], real >= 0.

        Returns
        -------
        K : ndarray, shape (n_omega, n_free, n_free), real
        J0 : ndarray of int, shape (n_omega,)
            As :meth:`cable_mode_count`.
        """
        if self.damped:
            return self.undamped().dynamic_stiffness_and_count(omega)
        if type(self) is not FrequencyModel:       # a subclass may change the cable kernels
            return self.dynamic_stiffness(omega), self.cable_mode_count(omega)
        omega = omega_array(omega)
        check_frequency_range(self.stacked_params, omega)
        C, J0 = end_block_coefficients_and_count(self.stacked_params, omega,
                                                 self.chordwise_inertia)
        nf = self.n_free
        K = (C.reshape(omega.size, -1) @ self._assembly).reshape(omega.size, nf, nf)
        K = K + self._K_geo_free - (omega**2)[:, None, None] * self.platform_mass
        return K, J0.sum(axis=1)

    def cable_mode_count(self, omega):
        """J0: sum over cables of the clamped-clamped mode counts below omega [rad/s],
        shape (n_omega,) (theory.md §5.2); the damping is ignored."""
        omega = omega_array(omega)
        st = self.stacked_params
        check_frequency_range(st, omega)
        Omega = omega[:, None] * st.L * np.sqrt(st.m / st.T)
        return mode_count_nondimensional(Omega, st.lambda_sq).sum(axis=1)

    def massless_stiffness(self):
        """Static stiffness of the massless-cable model (K_B(0) of every cable) + K_geo,
        shape (n_free, n_free) [N/m, N, N m/rad]."""
        return self.dynamic_stiffness(0.0)[0].real

    def undamped(self):
        """The same model with the cables' damping removed (itself when undamped)."""
        if not self.damped:
            return self
        return FrequencyModel(self.equilibrium, self.tension, self.chordwise_inertia,
                              damping=False)

    def cable_kinetic_energies(self, omega, x):
        """Kinetic energy of every cable per unit omega^2 / 2 [kg m^2 per unit amplitude^2],
        shape (n_cables,), for the platform motion x (6,) (dp [m], dtheta [rad]) at the
        natural frequency omega [rad/s] (closed-form fields, theory.md §5.3, §6)."""
        out = np.empty(len(self.params))
        for i, (p, r) in enumerate(zip(self.params, self.lever_arms)):
            dB = x[:3] + cross(x[3:], r)
            out[i] = cable_kinetic_energy(p, omega, p.rotation.T @ dB, self.chordwise_inertia)
        return out

    def cable_displacements(self, omega, x, n_points=41):
        """Cable displacement fields for the platform motion x (6,) at omega [rad/s].

        Returns
        -------
        positions : ndarray, shape (n_cables, n_points, 3)
            Points on the chords from anchor to attachment [m].
        displacements : ndarray, shape (n_cables, n_points, 3)
            Real part of the closed-form field (theory.md §5.3) [m], global frame; zero when
            x is zero.
        """
        pos = np.zeros((len(self.params), n_points, 3))
        disp = np.zeros_like(pos)
        for i, (p, r, s) in enumerate(zip(self.params, self.lever_arms,
                                          self.equilibrium.states)):
            xs = np.linspace(0.0, p.L, n_points)
            pos[i] = s.anchor + np.outer(xs / p.L, s.chord)
            if not np.any(x):
                continue
            dB = x[:3] + cross(x[3:], r)
            disp[i] = np.real(cable_field(p, omega, p.rotation.T @ dB, xs)) @ p.rotation.T
        return pos, disp
