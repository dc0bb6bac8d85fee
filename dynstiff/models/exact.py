"""The "exact" rung: every cable's numerically exact dynamic stiffness, assembled.

    K(omega) = sum_i J_i^T E_i K_BB,i(omega) E_i^T J_i + K_geo - omega^2 M_p     (theory.md §4)

with K_BB,i the end-B block of cable i's dynamic stiffness about its true elastic catenary
(:class:`dynstiff.cable.exact.ExactCable`, theory.md §11), E_i its local frame and J_i the
lever map. Each K_BB,i is K_s - w^2 M_psi - w^4 sum_j beta_j beta_j^T mu_j / (1 - w^2 mu_j),
so the whole sum over cables is one (n_omega, n_modes) @ (n_modes, n_free^2) product.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import flag, omega_array, positive_scalar
from dynstiff.cable.exact import DEFAULT_ORDER, HALF_WAVES_PER_ELEMENT, ExactCable
from dynstiff.errors import InvalidParameterError
from dynstiff.models.base import PlatformModel, require_equilibrium
from dynstiff.robot.platform import lever_map

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["ExactModel", "DEFAULT_FMAX_HZ"]

#: Default band of the exact rung [Hz]: the cables are discretised to resolve it.
DEFAULT_FMAX_HZ = 25.0
_BB = np.ix_([3, 4, 5], [3, 4, 5])
#: Frequencies x cable modes per block of :meth:`ExactModel.dynamic_stiffness` (2^16: ~1 MB
#: of complex temporaries).
BLOCK_ELEMENTS = 2**16


class ExactModel(PlatformModel):
    """The "exact" rung (theory.md §11): cables linearised about their true catenary.

    Immutable; the interface of every model is described in :mod:`dynstiff.models.base`.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    fmax_hz : float
        Band [Hz] the cable discretisations resolve (default 25 Hz); K(omega) above it is
        refused with an error that says so.
    order : int
        Polynomial order of the cables' spectral elements.
    half_waves : float
        Transverse half-wavelengths per element at ``fmax_hz``.
    damping : bool
        Keep the damping (default); False builds the undamped model (the cables' own damping
        and the two options below all removed).
    cable_loss_factor : float
        eta_c >= 0 [-]: hysteretic damping of all the cable's stiffness forces (D -> D (1 + i
        eta_c), axial and transverse), as the closed form's option (theory.md §12.2): exactly
        K_B(omega) = s K_B(omega / sqrt(s)), s = 1 + i eta_c, the viscous c / sqrt(s).
    platform_damping_ratio : float
        zeta_p >= 0 [-]: the hysteretic term i 2 zeta_p K_s on the massless-cable stiffness
        K_s (theory.md §12.2).

    Attributes
    ----------
    rung, robot, equilibrium, pose, free_dofs, free_index, n_free, platform_mass, damped
        As every model (:mod:`dynstiff.models.base`).
    cables : tuple of ExactCable
    fmax_hz, max_omega : float
        The band [Hz] and its angular frequency [rad/s].
    lever_arms : ndarray, shape (n_cables, 3)
        r_i = R_p b_i [m].
    K_geo, M_p : ndarray, shape (6, 6)
        Geometric stiffness and platform mass matrix (all DOFs).
    """

    rung = "exact"

    def __init__(self, equilibrium: Equilibrium, fmax_hz: float | str = DEFAULT_FMAX_HZ,
                 order: int = DEFAULT_ORDER, half_waves: float = HALF_WAVES_PER_ELEMENT,
                 damping: bool = True, cable_loss_factor: float = 0.0,
                 platform_damping_ratio: float = 0.0) -> None:
        robot, pose = require_equilibrium(equilibrium).robot, equilibrium.pose
        damping = flag("damping", damping)
        try:
            f = float(fmax_hz)
        except (TypeError, ValueError):
            f = np.nan
        if isinstance(fmax_hz, bool) or not np.isfinite(f) or f <= 0:
            raise InvalidParameterError(f"fmax_hz must be finite and > 0 [Hz], got {fmax_hz!r}")
        self._init_platform(robot, equilibrium, pose)
        self.fmax_hz = f
        self.max_omega = 2.0 * np.pi * f
        self.order, self.half_waves = order, half_waves
        self.cables = tuple(ExactCable(s, self.max_omega, order, damping, half_waves)
                            for s in equilibrium.states)
        self.cable_loss_factor = positive_scalar("cable_loss_factor", cable_loss_factor,
                                                 allow_zero=True) if damping else 0.0
        self.platform_damping_ratio = positive_scalar(
            "platform_damping_ratio", platform_damping_ratio, allow_zero=True) if damping else 0.0
        self.damped = (any(c.damped for c in self.cables) or self.cable_loss_factor > 0
                       or self.platform_damping_ratio > 0)
        self.lever_arms = np.array(equilibrium.lever_arms, dtype=float)
        self._init_geometric(robot, pose, equilibrium.states)
        self.M_p = self._platform_mass_all
        fi = self.free_index
        nf = self.n_free
        # map of each cable's local end-B 3x3 block (flattened) to the free-DOF matrix
        const = np.zeros(nf * nf, dtype=complex if any(c.damped for c in self.cables)
                         else float)
        mass_rows, mode_rows, mu, visc = [], [], [], []
        for cab, r in zip(self.cables, self.lever_arms):
            G = cab.frame.T @ lever_map(r, fi)                           # (3, nf)
            Q = np.einsum("ai,bj->abij", G, G).reshape(9, nf * nf)
            const = const + cab.static_stiffness[_BB].ravel() @ Q
            mass_rows.append(cab.mass_psi[_BB].ravel() @ Q)
            mode_rows.append(cab.beta_dyads(ends="end") @ Q)
            mu.append(cab.flexibilities)
            visc.append(np.full(cab.flexibilities.size, cab.c / cab.m))
        self._const = const                                             # cables' K_s
        self._K_platform_damping = None
        if self.platform_damping_ratio > 0:
            Ks = (const.real + self._K_geo_free.ravel()).reshape(nf, nf)
            self._K_platform_damping = (2j * self.platform_damping_ratio
                                        * 0.5 * (Ks + Ks.T)).ravel()
        self._mass = np.array(mass_rows)                                  # (n_cables, nf^2)
        self._modes = np.vstack(mode_rows)                                # (n_modes, nf^2)
        self._mu = np.concatenate(mu)
        self._visc_cable = np.array([c.c / c.m for c in self.cables])
        self._visc_mode = np.concatenate(visc)
        self._freeze()

    def dynamic_stiffness(self, omega: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """K(omega) on the free DOFs, shape (n_omega, n_free, n_free) (theory.md §4, §11.3).

        Parameters
        ----------
        omega : float or array_like, shape (n_omega,)
            [rad/s], real >= 0 or complex, |omega| <= ``max_omega``.

        Returns
        -------
        ndarray [N/m, N, N m/rad]; real when undamped and omega real. Infinite on a
        clamped-cable pole: at an omega exactly on one (w^2 mu = 1 in floats) the entries
        are not finite (inf, or NaN where a zero meets the infinity), without a warning.
        """
        omega = omega_array(omega, complex_ok=True)
        self._check(omega)
        nf = self.n_free
        complex_out = self.damped or np.iscomplexobj(omega)
        K = np.empty((omega.size, nf, nf), dtype=complex if complex_out else float)
        # frequencies in blocks: the (n_omega, n_modes) temporaries stay ~1 MB, in cache,
        # instead of ~70 MB each at 10,000 frequencies (page faults on every call)
        step = max(1, BLOCK_ELEMENTS // max(1, self._mu.size))
        for a in range(0, omega.size, step):
            K[a:a + step] = self._block(omega[a:a + step])
        return K

    def _block(self, omega: NDArray[np.float64]) -> NDArray[np.float64]:
        """K(omega) for one block of validated frequencies, (n, n_free, n_free)."""
        w = omega[:, None]
        # cable loss factor: K_B(omega) = s K_B(omega / sqrt(s)), i.e. w^2 -> w^2 / s
        s = 1.0 + 1j * self.cable_loss_factor
        w2_c = w**2 - 1j * w * self._visc_cable[None, :] if self.damped else w**2
        w2_m = w**2 - 1j * w * self._visc_mode[None, :] if self.damped else w**2
        if self.cable_loss_factor > 0:
            w2_c, w2_m = w2_c / s, w2_m / s
        # at an omega exactly on a clamped pole (w^2 mu = 1 in floats) g is infinite and K
        # not finite (inf, or NaN where a zero meets it): no floating-point warning
        with np.errstate(divide="ignore", invalid="ignore"):
            g = w2_m**2 * self._mu[None, :] / (1.0 - w2_m * self._mu[None, :])
            if self.damped:
                K = self._const[None, :] - w2_c @ self._mass - g @ self._modes
                if self.cable_loss_factor > 0:
                    K = s * K
                if self._K_platform_damping is not None:
                    K = K + self._K_platform_damping[None, :]
            else:
                K = (self._const[None, :] - w2_c * self._mass.sum(axis=0)[None, :]
                     - g @ self._modes)
        if not self.damped and np.isrealobj(omega):
            K = K.real
        nf = self.n_free
        return (K.reshape(-1, nf, nf) + self._K_geo_free
                - (omega**2)[:, None, None] * self.platform_mass)

    def _check(self, omega: NDArray[np.float64]) -> None:
        w = np.abs(omega)
        if w.size and w.max() > self.max_omega * (1 + 1e-12):
            bad = np.asarray(omega).ravel()[int(np.argmax(w))]
            raise InvalidParameterError(
                f"omega must be <= {self.max_omega:.6g} rad/s: the exact model was built for "
                f"fmax_hz = {self.fmax_hz:g} Hz, got {bad:.6g} rad/s "
                f"({abs(bad) / 2 / np.pi:.6g} Hz); build it with a larger fmax_hz")

    def cable_mode_count(self, omega: NDArray[np.float64] | float) -> NDArray[np.int64]:
        """J0: clamped-cable frequencies below omega of all cables, shape (n_omega,)
        (theory.md §11.3); the damping is ignored."""
        omega = omega_array(omega)
        self._check(omega)
        return sum(c.mode_count(omega) for c in self.cables)

    def massless_stiffness(self) -> NDArray[np.float64]:
        """Static stiffness K(0): the exact catenaries' end stiffness + K_geo, shape
        (n_free, n_free) [N/m, N, N m/rad]."""
        return self.dynamic_stiffness(0.0)[0].real

    def undamped(self) -> ExactModel:
        """The same model with the cables' damping removed (itself when undamped)."""
        if not self.damped:
            return self
        return ExactModel(self.equilibrium, self.fmax_hz, self.order, self.half_waves,
                          damping=False)

    def with_damping(self, cable_loss_factor: float = 0.0,
                     platform_damping_ratio: float = 0.0) -> ExactModel:
        """The same cables with the model-level damping options (theory.md §12.2)."""
        return ExactModel(self.equilibrium, self.fmax_hz, self.order, self.half_waves,
                          cable_loss_factor=cable_loss_factor,
                          platform_damping_ratio=platform_damping_ratio)

    def _end_motion(self, cab: ExactCable, r: NDArray[np.float64],
                    x: NDArray[np.float64]) -> NDArray[np.float64]:
        return cab.frame.T @ (x[:3] + np.cross(x[3:], r))

    def cable_kinetic_energies(self, omega: ArrayLike,
                               x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Kinetic energy of every cable per unit omega^2 / 2 [kg m^2 per unit amplitude^2],
        shape (n_cables,), for the platform motion x (6,) at omega [rad/s] (theory.md §11.3);
        for omega of shape (n,) and x of shape (n, 6), shape (n, n_cables)."""
        one = np.ndim(omega) == 0
        om = np.atleast_1d(np.asarray(omega, dtype=float))
        xs = np.asarray(x, dtype=float).reshape(om.size, 6)
        E = np.array([[c.kinetic_energy(w, self._end_motion(c, r, xk))
                       for c, r in zip(self.cables, self.lever_arms)]
                      for w, xk in zip(om, xs)]).reshape(om.size, len(self.cables))
        return E[0] if one else E

    def cable_displacements(self, omega: float, x: NDArray[np.float64],
                            n_points: int = 41) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Cable displacement fields for the platform motion x (6,) at omega [rad/s].

        Returns
        -------
        positions : ndarray, shape (n_cables, n_points, 3)
            Points of the static catenaries, equally spaced in unstretched arc length [m].
        displacements : ndarray, shape (n_cables, n_points, 3)
            Real part of the field [m], global frame (linear between the nodes).
        """
        pos = np.zeros((len(self.cables), n_points, 3))
        disp = np.zeros_like(pos)
        for i, (c, r) in enumerate(zip(self.cables, self.lever_arms)):
            s = np.linspace(0.0, c.state.unstretched_length, n_points)
            pos[i] = c.state.profile(n_points)
            if not np.any(x):
                continue
            u = np.real(c.end_response(omega, self._end_motion(c, r, x))) @ c.frame.T
            disp[i] = np.column_stack([np.interp(s, c.s, u[:, k]) for k in range(3)])
        return pos, disp
