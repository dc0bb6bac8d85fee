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

from ._validate import omega_array, positive_scalar
from ._vec import cross
from .cable_dsm import (DEFAULT_CHORDWISE_INERTIA, cable_field, cable_kinetic_energy,
                        check_frequency_range, chord_parameters, dyad_basis, end_block_coefficients,
                        mode_count_nondimensional, stack_parameters)
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
        Keep the damping (default); False builds the undamped model (the cables' own
        damping and the two options below all removed).
    cable_loss_factor : float
        eta_c >= 0 [-]: hysteretic damping of *all* the cable's stiffness forces, the dynamic
        tension (transverse motions) and the elastic stretching (axial), both times
        (1 + i eta_c), the static geometry real; K_B(omega) = s K_B(omega / sqrt(s)) with
        s = 1 + i eta_c and the viscous c / sqrt(s) (theory.md §12.2). Acts on top of a
        cable's own ``loss_factor`` (EA only).
    platform_damping_ratio : float
        zeta_p >= 0 [-]: modal damping ratio of the platform modes (winches, frame,
        joints): the hysteretic term i 2 zeta_p K_s with K_s the massless-cable stiffness,
        which gives every massless-cable mode the damping ratio zeta_p at its resonance
        (theory.md §12.2).

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
    """

    rung = "dsm"

    def __init__(self, equilibrium, tension="mean", chordwise_inertia=DEFAULT_CHORDWISE_INERTIA,
                 damping=True, cable_loss_factor=0.0, platform_damping_ratio=0.0):
        robot, pose = require_equilibrium(equilibrium).robot, equilibrium.pose
        self._init_platform(robot, equilibrium, pose)
        self.tension = tension
        self.chordwise_inertia = bool(chordwise_inertia)
        self.cable_loss_factor = positive_scalar("cable_loss_factor", cable_loss_factor,
                                                 allow_zero=True)
        self.platform_damping_ratio = positive_scalar(
            "platform_damping_ratio", platform_damping_ratio, allow_zero=True)
        params = [chord_parameters(s, tension) for s in equilibrium.states]
        if not damping:
            params = [replace(p, c=0.0, EA=float(np.real(p.EA))) for p in params]
            self.damped = False
            self.cable_loss_factor = self.platform_damping_ratio = 0.0
        elif self.cable_loss_factor > 0 or self.platform_damping_ratio > 0:
            self.damped = True
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
        self._K_platform_damping = None
        if self.platform_damping_ratio > 0:
            Ks = self._stiffness(np.zeros(1)).real[0]
            self._K_platform_damping = 2j * self.platform_damping_ratio * 0.5 * (Ks + Ks.T)
        self._freeze()

    def cable_coefficients(self, omega):
        """Dyad coefficients (uu, uv, vu, vv, ww) of every cable's end-B DSM, all cables in one
        broadcast call, shape (n_omega, 5 n_cables), cable-major [N/m].

        ``omega`` [rad/s], shape (n_omega,), validated, real or complex."""
        eta = self.cable_loss_factor
        if eta > 0:                   # K_B(omega) = s K_B(omega / sqrt(s)), c -> c / sqrt(s)
            s = 1.0 + 1j * eta
            st = replace(self.stacked_params, c=self.stacked_params.c / np.sqrt(s))
            C = s * end_block_coefficients(st, omega / np.sqrt(s), self.chordwise_inertia)
        else:
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
        K = self._stiffness(omega)
        if self._K_platform_damping is not None:
            K = K + self._K_platform_damping
        return K - (omega**2)[:, None, None] * self.platform_mass

    def _stiffness(self, omega):
        nf = self.n_free
        K = (self.cable_coefficients(omega) @ self._assembly).reshape(omega.size, nf, nf)
        return K + self._K_geo_free

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

    def with_damping(self, cable_loss_factor=0.0, platform_damping_ratio=0.0):
        """The same cables with the model-level damping of :class:`FrequencyModel`."""
        return FrequencyModel(self.equilibrium, self.tension, self.chordwise_inertia,
                              cable_loss_factor=cable_loss_factor,
                              platform_damping_ratio=platform_damping_ratio)

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
