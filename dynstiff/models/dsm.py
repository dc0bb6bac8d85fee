"""Robot dynamic stiffness K(omega): cable DSMs rotated, mapped to the platform and assembled.

    K(omega) = sum_i J_i^T K_B,i(omega) J_i + K_geo - omega^2 M_p        (theory.md §4)

J_i = [I, -[r_i]x] maps the platform motion x = (dp, dtheta) about P to the motion of the
attachment point B_i; K_B,i is the end-B dynamic stiffness of cable i (anchor clamped), in the
global frame; K_geo is the geometric stiffness of the static cable forces and gravity acting on
rotating lever arms; M_p the platform's rigid-body mass matrix. Only the free DOFs are kept.

Each K_B,i is a combination of five dyads of its chord frame, so the whole sum over cables is a
single (n_omega, 5 n) @ (5 n, n_free^2) product: no loop over frequencies.
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import flag, omega_array, positive_scalar
from dynstiff._vec import cross
from dynstiff.cable.dsm import (
    DEFAULT_CHORDWISE_INERTIA,
    DYAD_PAIRS,
    chord_parameters,
    end_block_coefficients,
    end_block_coefficients_and_count,
    stack_parameters,
    static_block_coefficients,
)
from dynstiff.cable.dsm_fields import cable_field, field_kinetic_energies
from dynstiff.cable.guard import (
    AXIAL_MARGIN,
    DEFAULT_GUARD_RTOL,
    MEASURE_ABOVE,
    ROBOT_ERROR_FACTOR,
    closed_form_local_error,
    closed_form_validity,
)
from dynstiff.cable.psi import check_frequency_range, mode_count_nondimensional
from dynstiff.errors import ClosedFormWarning, InvalidParameterError
from dynstiff.models import dsm_guard as guard
from dynstiff.models.base import PlatformModel, require_equilibrium
from dynstiff.models.dsm_guard import ROBOT_BOUND_MESSAGE
from dynstiff.robot.platform import lever_maps

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["FrequencyModel", "ROBOT_BOUND_MESSAGE"]


class FrequencyModel(PlatformModel):
    """The "dsm" rung: closed-form dynamic stiffness of every cable, assembled (theory.md §4).

    Immutable; the interface of every model is described in :mod:`dynstiff.models.base`.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    tension : {"mean", "chord"}
        Tension of the cables' linear theory (see :func:`dynstiff.cable.chord.chord_parameters`).
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
    guard_rtol : float or None
        The closed form's guard (theory.md §11.5): a :class:`ClosedFormWarning` names every
        slack cable and every cable whose static error shifts a global mode by more than this
        (at build), and every cable whose axial modes, or local modes measured further than
        this from the exact cable's, the asked omega reaches (:meth:`guard_band`); where no
        cable has warned, the robot once its bound on the coupled modes' error up to the
        asked omega exceeds this (:meth:`robot_error`, theory.md §11.6). None: no warnings.

    Attributes
    ----------
    rung, robot, equilibrium, pose, free_dofs, free_index, n_free, platform_mass, damped
        As every model (:mod:`dynstiff.models.base`).
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

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> m.rung, m.n_free
    ('dsm', 6)
    >>> K = m.dynamic_stiffness([0.0, 10.0])          # K(omega), omega [rad/s]
    >>> K.shape
    (2, 6, 6)
    """

    rung = "dsm"

    def __init__(self, equilibrium: Equilibrium, tension: str = "mean",
                 chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA, damping: bool = True,
                 cable_loss_factor: float = 0.0, platform_damping_ratio: float = 0.0,
                 guard_rtol: float = DEFAULT_GUARD_RTOL) -> None:
        robot, pose = require_equilibrium(equilibrium).robot, equilibrium.pose
        if guard_rtol is not None and not (isinstance(guard_rtol, (int, float))
                                           and not isinstance(guard_rtol, bool)
                                           and 0 < guard_rtol < np.inf):
            raise InvalidParameterError(
                f"guard_rtol must be a number > 0 or None, got {guard_rtol!r}")
        self.guard_rtol = guard_rtol
        self._init_platform(robot, equilibrium, pose)
        self.tension = tension
        self.chordwise_inertia = flag("chordwise_inertia", chordwise_inertia)
        damping = flag("damping", damping)
        self.cable_loss_factor = positive_scalar("cable_loss_factor", cable_loss_factor,
                                                 allow_zero=True)
        self.platform_damping_ratio = positive_scalar(
            "platform_damping_ratio", platform_damping_ratio, allow_zero=True)
        params = [chord_parameters(s, tension) for s in equilibrium.states]
        own = params                         # before damping=False changes them
        if not damping:
            params = [replace(p, c=0.0, EA=float(np.real(p.EA))) for p in params]
            self.damped = False
            self.cable_loss_factor = self.platform_damping_ratio = 0.0
        elif self.cable_loss_factor > 0 or self.platform_damping_ratio > 0:
            self.damped = True
        self._own_params = bool(damping)     # params are the cables' own
        self.params = tuple(params)
        self.stacked_params = stack_parameters(self.params)
        validity = [closed_form_validity(s, 0.0, tension, p)
                    for s, p in zip(equilibrium.states, own)]
        self._validity = tuple(validity)
        self._axial_omega = np.array([AXIAL_MARGIN * 2 * np.pi * v.values["axial_hz"]
                                      for v in validity])
        self._local_omega = np.array([np.pi * np.sqrt(p.T / p.m) / p.L for p in params])
        self._warned = set()                 # (cable, cause) already reported
        self._guarded = [0.0]                # highest omega the guard has checked [rad/s]
        self._memo = {}                      # static_error, massless_stiffness (immutable)
        self._measured = {}                  # cable -> (band [rad/s], measured local error)
        self._issued = []                    # causes warned of (a cable's warning says it)
        self.lever_arms = np.array(equilibrium.lever_arms, dtype=float)
        fi = self.free_index
        # (5 n, nf*nf) map from dyad coefficients of every cable to the free-DOF matrix:
        # J^T (e_a e_b^T) J = (J^T e_a)(J^T e_b)^T for the dyads (a, b) of DYAD_PAIRS
        self._lever_maps = lever_maps(self.lever_arms, fi)                 # (n, 3, nf)
        self._rotations = np.array([p.rotation for p in self.params])      # (n, 3, 3)
        G = np.einsum("cai,cam->cim", self._lever_maps, self._rotations)   # (n, nf, 3)
        a, b = np.array(DYAD_PAIRS).T
        self._assembly = np.einsum("cik,cjk->ckij", G[:, :, a], G[:, :, b]).reshape(
            5 * len(self.params), -1)
        self.assembly_map = self._assembly
        self._init_geometric(robot, pose, equilibrium.states)
        self.K_geo_free = self._K_geo_free
        self.M_p = self._platform_mass_all
        self._K_platform_damping = None
        if self.platform_damping_ratio > 0:
            Ks = self._static_stiffness()
            self._K_platform_damping = 2j * self.platform_damping_ratio * 0.5 * (Ks + Ks.T)
        self._freeze()
        if guard_rtol is not None:
            guard.guard_static(self)

    def cable_coefficients(self, omega: NDArray[Any]) -> NDArray[Any]:
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

    def dynamic_stiffness(self, omega: ArrayLike) -> NDArray[Any]:
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
        self.guard_band(omega)
        K = self._stiffness(omega)
        if self._K_platform_damping is not None:
            K = K + self._K_platform_damping
        return K - (omega**2)[:, None, None] * self.platform_mass

    def _stiffness(self, omega: NDArray[Any]) -> NDArray[Any]:
        nf = self.n_free
        K = (self.cable_coefficients(omega) @ self._assembly).reshape(omega.size, nf, nf)
        return K + self._K_geo_free

    def _zero_coefficients(self) -> NDArray[np.float64]:
        """Re :meth:`cable_coefficients` at omega = 0, shape (n_cables, 5) [N/m], written out
        at psi = 0 (:func:`static_block_coefficients`, times s = 1 + i eta as there; equal
        to the kernel's to rounding); computed once per model."""
        if "zero" not in self._memo:
            C = static_block_coefficients(self.stacked_params)
            if self.cable_loss_factor > 0:
                C = (1.0 + 1j * self.cable_loss_factor) * C
            self._memo["zero"] = np.real(C).reshape(len(self.params), 5)
        return self._memo["zero"]

    def _static_stiffness(self) -> NDArray[np.float64]:
        """Re K(0) without the platform damping: the cables' static stiffness + K_geo on the
        free DOFs, (n_free, n_free)."""
        nf = self.n_free
        return (self._zero_coefficients().reshape(1, -1) @ self._assembly).reshape(nf, nf) \
            + self._K_geo_free

    def static_error(self) -> tuple[float, int]:
        """First-order relative frequency error of the massless-cable modes caused by the
        closed form's static stiffness, against the exact catenaries (theory.md §11.5).

        Returns (error [-], cable): the largest |x^T dK x| / (2 x^T K x) over the modes x of
        (K_exact(0), M_p), dK = K_dsm(0) - K_exact(0), and the cable with the largest share of
        it. All cables at once (:func:`dynstiff.cable.catenary.end_stiffnesses`); computed
        once per model (the guard at build, the cable-model check)."""
        if "static_error" not in self._memo:
            self._memo["static_error"] = guard.static_error(self)
        return self._memo["static_error"]

    def guard_band(self, omega: NDArray[Any]) -> None:
        """The closed form's guard for a request up to max |omega| [rad/s] (theory.md §11.5):
        a ClosedFormWarning, once per cable and cause, when omega reaches the cable's axial
        modes, or its local modes while their error, measured against the exact cable,
        exceeds ``guard_rtol``. Called by every evaluation of K(omega), compiled ones
        included."""
        guard.guard_band(self, omega)

    def cable_error(self, i: int, omega_max: float) -> float:
        """Cable i's own closed-form error up to omega_max [rad/s] (theory.md §11.6): its
        envelope (:func:`dynstiff.cable.guard.closed_form_validity`), or, where that
        exceeds 1e-2, the measured error of its clamped frequencies against the exact cable
        (kept for later calls up to the same band); inf when the closed form does not apply
        (slack, axial modes below omega_max)."""
        v = self._validity[i]
        if not np.isfinite(v.error) or omega_max >= self._axial_omega[i]:
            return np.inf
        if v.error <= MEASURE_ABOVE:
            return float(v.error)
        band, err = self._measured.get(i, (-1.0, None))
        if omega_max > band:
            band = float(max(omega_max, 8 * self._local_omega[i]))
            err = closed_form_local_error(self.equilibrium.states[i], omega_max, self.tension)
            self._measured[i] = (band, err)
        return err

    def robot_error(self, omega_max: float) -> tuple[float, int]:
        """The bound on the closed form's relative frequency error of the robot's coupled
        modes up to omega_max [rad/s] (theory.md §11.6): ROBOT_ERROR_FACTOR (e_static +
        max_c e_c), e_static the static error (:meth:`static_error`), e_c every cable's own
        error (:meth:`cable_error`). Returns (bound [-], the cable of the largest e_c).

        Examples
        --------
        >>> import dynstiff as ds
        >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
        >>> bool(m.robot_error(2 * 3.1416 * 12.0)[0] < 1e-2)
        True
        """
        own = [self.cable_error(i, float(omega_max)) for i in range(len(self.params))]
        i = int(np.argmax(own))
        return float(ROBOT_ERROR_FACTOR * (self.static_error()[0] + own[i])), i

    def dynamic_stiffness_and_count(
            self, omega: NDArray[np.float64] | float,
    ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
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
        self.guard_band(omega)
        C, J0 = end_block_coefficients_and_count(self.stacked_params, omega,
                                                 self.chordwise_inertia)
        nf = self.n_free
        K = (C.reshape(omega.size, -1) @ self._assembly).reshape(omega.size, nf, nf)
        K = K + self._K_geo_free - (omega**2)[:, None, None] * self.platform_mass
        return K, J0.sum(axis=1)

    def cable_mode_count(self, omega: NDArray[np.float64]) -> NDArray[np.int64]:
        """J0: sum over cables of the clamped-clamped mode counts below omega [rad/s],
        shape (n_omega,) (theory.md §5.2); the damping is ignored."""
        omega = omega_array(omega)
        st = self.stacked_params
        check_frequency_range(st, omega)
        Omega = omega[:, None] * st.L * np.sqrt(st.m / st.T)
        return mode_count_nondimensional(Omega, st.lambda_sq).sum(axis=1)

    def massless_stiffness(self) -> NDArray[np.float64]:
        """Static stiffness of the massless-cable model (K_B(0) of every cable) + K_geo,
        shape (n_free, n_free) [N/m, N, N m/rad]; computed once per model, a copy returned."""
        if "massless" not in self._memo:
            self._memo["massless"] = self._static_stiffness()
        return self._memo["massless"].copy()

    def undamped(self) -> FrequencyModel:
        """The same model with the cables' damping removed (itself when undamped)."""
        if not self.damped:
            return self
        with warnings.catch_warnings():          # the static causes were reported already
            warnings.simplefilter("ignore", ClosedFormWarning)
            return FrequencyModel(self.equilibrium, self.tension, self.chordwise_inertia,
                                  damping=False, guard_rtol=self.guard_rtol)

    def with_damping(self, cable_loss_factor: float = 0.0,
                     platform_damping_ratio: float = 0.0) -> FrequencyModel:
        """The same cables with the model-level damping of :class:`FrequencyModel`."""
        return FrequencyModel(self.equilibrium, self.tension, self.chordwise_inertia,
                              cable_loss_factor=cable_loss_factor,
                              platform_damping_ratio=platform_damping_ratio)

    def _with_model_damping(self, cable_loss_factor: float,
                            platform_damping_ratio: float) -> FrequencyModel | None:
        """``FrequencyModel(self.equilibrium, self.tension, self.chordwise_inertia,
        cable_loss_factor=..., platform_damping_ratio=..., guard_rtol=self.guard_rtol)``,
        sharing this model's cable parameters, assembly map and platform terms (read-only,
        the same numbers a new build computes) instead of recomputing them, and its static
        error where computed (from the real parts at omega = 0, which the damping leaves as
        they are); None unless this model is an undamped build of the
        cables' own parameters. The build's static guard is not repeated (this model ran it
        on the same cables); the band guard starts afresh, as for a new build. A map's
        receptance check takes it (theory.md §13.7)."""
        if type(self) is not FrequencyModel or self.damped or not self._own_params:
            return None
        new = object.__new__(FrequencyModel)
        d = dict(vars(self))
        del d["_frozen"]
        d.update(cable_loss_factor=positive_scalar("cable_loss_factor", cable_loss_factor,
                                                   allow_zero=True),
                 platform_damping_ratio=positive_scalar(
                     "platform_damping_ratio", platform_damping_ratio, allow_zero=True),
                 _warned=set(), _guarded=[0.0], _K_platform_damping=None,
                 _measured=dict(self._measured), _issued=[],
                 # the static error is that of the real parts at omega = 0, which the
                 # damping does not change; the symmetric assembly map is geometry only
                 _memo={k: self._memo[k] for k in ("static_error", "symmetric_assembly")
                        if k in self._memo})
        d["damped"] = d["cable_loss_factor"] > 0 or d["platform_damping_ratio"] > 0
        for k, v in d.items():
            object.__setattr__(new, k, v)
        if new.platform_damping_ratio > 0:
            Ks = new._static_stiffness()
            object.__setattr__(new, "_K_platform_damping",
                               2j * new.platform_damping_ratio * 0.5 * (Ks + Ks.T))
        new._freeze()
        return new

    def cable_kinetic_energies(self, omega: ArrayLike,
                               x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Kinetic energy of every cable per unit omega^2 / 2 [kg m^2 per unit amplitude^2],
        shape (n_cables,), for the platform motion x (6,) (dp [m], dtheta [rad]) at the
        natural frequency omega [rad/s] (closed-form fields, theory.md §5.3, §6); for omega of
        shape (n,) and x of shape (n, 6), all n in one broadcast call, shape (n, n_cables)."""
        one = np.ndim(omega) == 0
        om = np.atleast_1d(np.asarray(omega, dtype=float))
        xs = np.asarray(x, dtype=float).reshape(om.size, 6)
        dB = xs[:, None, :3] + cross(xs[:, None, 3:], self.lever_arms[None])   # (n, c, 3)
        d_local = np.einsum("cji,ncj->nci", self._rotations, dB)
        E = field_kinetic_energies(self.stacked_params, om, d_local, self.chordwise_inertia)
        return E[0] if one else E

    def cable_displacements(self, omega: float, x: NDArray[np.float64],
                            n_points: int = 41) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
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
