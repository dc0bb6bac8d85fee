"""Numerically exact dynamic stiffness of one cable linearised about its elastic catenary.

No shallow-cable approximation (theory.md §11): the tension varies along the arc, the whole
weight acts (its chordwise part included), axial and transverse motions are coupled through
the curvature, the cable is extensible and may be steep, sagging or slack. With s the
unstretched arc length, t(s) the unit tangent, T(s) the tension and u(s) the small motion,

    m u_tt = (D(s) u')',   D = EA t t^T + T / (1 + T/EA) (I - t t^T)        (theory.md §11.1)

(the weight is constant and drops out of the increment). The motion perpendicular to the
vertical cable plane decouples (a string of varying tension); the in-plane motion is a
coupled pair. Viscous damping c [N s/m^2] on all motions enters as m -> m - i c / omega,
hysteretic damping as EA -> EA (1 + i eta) on the axial strain (theory.md §11.3).

Discretisation (theory.md §11.2): spectral elements of order ``order`` with
Gauss-Lobatto-Legendre nodes (diagonal mass), graded towards low tension and sized to the
transverse wavelength at ``omega_max`` (:mod:`dynstiff.cable.exact_mesh`); the in-plane
family in mixed form, the axial force increment an unknown, so that the transverse stiffness
of a slack cable is not lost to the rounding of EA (:mod:`dynstiff.cable.exact_condense`).
The interior (A and B clamped) is condensed exactly through its clamped modes
(lambda_j, phi_j), computed once:

    K(omega) = K_s - w^2 [M_bb + sum_j c_j c_j^T / (lambda_j (lambda_j - w^2))],
    w^2 = omega^2 - i omega c / m,   c_j = K_bi phi_j                    (theory.md §11.3)

with K_s the exact static two-end stiffness of the catenary (so omega -> 0 is exact). The
poles lambda_j are the clamped-cable frequencies: the exact J0 of Wittrick-Williams counting.
Local frame: x along the horizontal direction from A to B, y = z x x (out of plane), z up.

Supported: every catenary with T_min / T_max >= ``MIN_TENSION_RATIO`` (taut, sagging, steep,
U-shaped, near-vertical); a slacker cable is refused up front with one
:class:`~dynstiff.errors.SlackCableError`, whatever band or order is asked.
"""

from __future__ import annotations

from numbers import Integral, Real
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import omega_array
from dynstiff._vec import cross
from dynstiff.cable.exact_condense import axial_coupling, condense, quadrature_state, string_matrix
from dynstiff.cable.exact_mesh import gll, mesh, static_along, tangent_integrals
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.cable.catenary import CatenaryState
    from dynstiff.cable.exact_condense import Quadrature

__all__ = ["ExactCable", "DEFAULT_ORDER", "HALF_WAVES_PER_ELEMENT", "MIN_TENSION_RATIO",
           "STATIC_CHECK_RTOL"]

#: Polynomial order of the spectral elements.
DEFAULT_ORDER = 12
#: Transverse half-wavelengths per element at ``omega_max`` (theory.md §11.2).
HALF_WAVES_PER_ELEMENT = 2.0
#: Largest relative difference allowed between the discretisation's static stiffness and the
#: exact one, in the energy norm (theory.md §11.2); measured 1e-13 to 1e-11 on taut,
#: sagging, steep, U-shaped and near-vertical cables down to T_min / T_max = 1e-6.
STATIC_CHECK_RTOL = 1e-6
#: Least T_min / T_max of a cable the exact model accepts (theory.md §11.2). Down to it the
#: frequencies and end stiffness agree with graded lumped chains to 1e-8 and the static
#: self-check stays below 1e-8; further down the arc-length coordinate itself puts
#: eps / (T_min / T_max) of error into the tangent at the bottom of a U (static self-check
#: 4.5e-8 at 1e-10, 1e-5 at 1e-12).
MIN_TENSION_RATIO = 1e-8
_EZ = np.array([0.0, 0.0, 1.0])


class ExactCable:
    """Exact dynamic stiffness of one cable about its catenary (theory.md §11).

    Parameters
    ----------
    state : CatenaryState
        Static equilibrium (:func:`dynstiff.solve_catenary`).
    omega_max : float
        Highest angular frequency [rad/s] the discretisation must resolve; larger omega are
        refused (the clamped spectrum above it is not converged).
    order : int
        Polynomial order of the spectral elements (>= 4).
    damping : bool
        Keep the cable's viscous and hysteretic damping (default); False gives the undamped
        cable.

    Attributes
    ----------
    state, omega_max, order, damped
    frame : ndarray, shape (3, 3)
        Columns e_x (horizontal, A towards B), e_y = e_z x e_x, e_z [-].
    edges : ndarray
        Element boundaries in unstretched arc length [m].
    s : ndarray, shape (n_nodes,)
        Node positions [m].
    static_mismatch : float
        Relative difference of the discretisation's own static stiffness from the exact one
        in the energy norm [-] (a self-check; the constructor raises ConvergenceError above
        ``STATIC_CHECK_RTOL``).
    static_floor : float
        Bound of the rounding error of that difference, same norm [-].
    eigenvalues : ndarray, shape (n_modes,)
        Undamped clamped-cable eigenvalues omega_j^2 [rad^2/s^2], ascending.
    family : tuple of str
        "out-of-plane", "in-plane" or "axial" (in-plane with most of its kinetic energy in
        motion along the cable).
    axial_share : ndarray, shape (n_modes,)
        That share of the kinetic energy [-].
    """

    def __init__(self, state: str | CatenaryState, omega_max: float, order: float = DEFAULT_ORDER,
                 damping: bool = True, half_waves: float = HALF_WAVES_PER_ELEMENT) -> None:
        if not (isinstance(omega_max, Real) and np.isfinite(omega_max) and omega_max > 0):
            raise InvalidParameterError(
                f"omega_max must be finite and > 0 [rad/s], got {omega_max!r}")
        if isinstance(order, bool) or not isinstance(order, Integral) or not 4 <= order <= 40:
            raise InvalidParameterError(f"order must be an integer in [4, 40], got {order!r}")
        if not all(hasattr(state, a) for a in ("H", "V0", "cable", "unstretched_length")):
            raise InvalidParameterError(
                f"state must be a CatenaryState (dynstiff.solve_catenary), got "
                f"{type(state).__name__}")
        if not (isinstance(half_waves, Real) and 0 < half_waves <= 8):
            raise InvalidParameterError(
                f"half_waves must be a number in (0, 8], got {half_waves!r}")
        ratio = state.min_tension / state.max_tension
        if not ratio >= MIN_TENSION_RATIO:
            raise SlackCableError(
                f"the cable is too slack for the exact model: T_min / T_max = {ratio:.3g} "
                f"(lowest tension {state.min_tension:.3g} N, highest "
                f"{state.max_tension:.3g} N) is below the supported {MIN_TENSION_RATIO:g} "
                f"(theory.md §11.2)")
        cab = state.cable
        self.state, self.omega_max, self.order = state, float(omega_max), int(order)
        self.damped = bool(damping) and cab.is_damped
        self.m = cab.mass_per_length
        self.c = cab.viscous_damping if self.damped else 0.0
        eta = cab.loss_factor if self.damped else 0.0
        e_x = state.horizontal_direction
        self.frame = np.column_stack([e_x, cross(_EZ, e_x), _EZ])
        self.edges = mesh(state, self.omega_max, float(half_waves))
        _, wq, _ = gll(self.order)
        q = quadrature_state(static_along, state, self.edges, self.order)
        n = q.n
        xi = gll(self.order)[0]
        s = self.edges[:-1, None] + 0.5 * (xi[None, :] + 1.0) * q.h[:, None]
        self.s = np.concatenate([s[:, :-1].ravel(), [self.edges[-1]]])
        mass = np.zeros(n)
        np.add.at(mass, q.idx, self.m * 0.5 * q.h[:, None] * wq[None, :])
        self.node_mass = mass                                 # [kg] per component
        t_nodes = static_along(state, self.s)
        self._build_modes(q, mass, eta, np.stack([t_nodes.tx, t_nodes.tz], axis=1))
        self._K_s = self._static_two_end(eta)
        self.static_mismatch, self.static_floor = self._self_check()

    # ------------------------------------------------------------------ construction
    def _build_modes(self, q: Quadrature, mass: NDArray[np.float64], eta: float,
                     tangent: NDArray[np.float64]) -> None:
        """Clamped modes of the interior, in flexibility form, and the static constraint
        modes (local 6-vector ordering A x y z, B x y z) (theory.md §11.3): the out-of-plane
        family a string, the in-plane family in mixed form (theory.md §11.2)."""
        n = mass.size
        EA = self.state.cable.EA
        inner = np.arange(1, n - 1)
        inner2 = np.stack([2 * inner, 2 * inner + 1], axis=1).ravel()
        K1 = string_matrix(q, self.order)
        K2 = np.kron(K1, np.eye(2))                      # D_t I on (x, z), interleaved
        bnd2, loc2 = [0, 1, 2 * n - 2, 2 * n - 1], [0, 2, 3, 5]
        m2 = np.repeat(mass[inner], 2)
        fam_out = condense(K1, mass[inner], inner, [0, n - 1], [1, 4])
        fam_in = condense(K2, m2, inner2, bnd2, loc2, *axial_coupling(q, self.order, EA))
        # share of the kinetic energy in motion along the tangent (axial waves)
        phi = fam_in.shapes.reshape(inner.size, 2, -1)
        along = np.einsum("ia,iaj->ij", tangent[inner], phi)
        axial_share = np.einsum("i,ij->j", mass[inner], along**2)
        lam = np.concatenate([1.0 / fam_out.mu, 1.0 / fam_in.mu])
        fam = np.array(["out-of-plane"] * fam_out.mu.size
                       + ["axial" if a > 0.5 else "in-plane" for a in axial_share])
        share = np.concatenate([np.zeros(fam_out.mu.size), axial_share])
        keep = lam > 0                      # flexibility eigenvalues lost to rounding
        order = np.argsort(lam[keep], kind="stable")
        self.eigenvalues = lam[keep][order]
        self.family = tuple(fam[keep][order])
        self.axial_share = share[keep][order]
        self._fam = (fam_out, fam_in if eta == 0 else condense(
            K2, m2, inner2, bnd2, loc2, *axial_coupling(q, self.order, EA * (1.0 + 1j * eta))))
        self._mu = np.concatenate([f.mu for f in self._fam])
        self._beta = np.concatenate([f.beta for f in self._fam])
        self._BB = np.einsum("ja,jb->jab", self._beta, self._beta).reshape(self._mu.size, 36)
        self._M_psi = sum(f.M_psi for f in self._fam)
        self._M_psi[[0, 1, 2], [0, 1, 2]] += mass[0]
        self._M_psi[[3, 4, 5], [3, 4, 5]] += mass[-1]
        for a in (self.eigenvalues, self.axial_share, self.s, self.edges, self.frame,
                  self.node_mass):
            a.flags.writeable = False

    def _self_check(self) -> tuple[float, float]:
        """Difference of the discretisation's own static stiffness from the exact one and the
        bound of its rounding, in the energy norm of the exact end stiffness K:
        max over the four 3 x 3 blocks of ||K^-1/2 (K_d,blk -+ K) K^-1/2||_2 (theory.md
        §11.2). Raises ConvergenceError above STATIC_CHECK_RTOL instead of returning a wrong
        model. Returns (mismatch, floor) [-]."""
        Kd, Ks, fl = self.discrete_static_stiffness(), self._K_s, self._static_floor()
        K = Ks[3:, 3:].real
        lam, V = np.linalg.eigh(0.5 * (K + K.T))
        W = V / np.sqrt(lam)[None, :]                        # K^-1/2 in K's eigenbasis
        err = floor = 0.0
        for a in (slice(0, 3), slice(3, 6)):
            for b in (slice(0, 3), slice(3, 6)):
                err = max(err, float(np.linalg.norm(W.T @ (Kd[a, b] - Ks[a, b]) @ W, 2)))
                floor = max(floor, float(np.linalg.norm(np.abs(W.T) @ fl[a, b] @ np.abs(W),
                                                        2)))
        if not err <= STATIC_CHECK_RTOL:
            st = self.state
            why = (f"at its rounding floor {floor:.2g}: the cable is too slack or too stiff "
                   f"for double precision" if floor >= 0.1 * err else
                   f"far above its rounding floor {floor:.2g}: refine the discretisation "
                   f"(order, half_waves)")
            raise ConvergenceError(
                f"the exact cable model does not reproduce the catenary's static stiffness "
                f"(relative error {err:.2g} in the energy norm > {STATIC_CHECK_RTOL:g}, "
                f"{why}); T_min / T_max = {st.min_tension / st.max_tension:.3g}, order "
                f"{self.order}, {len(self.edges) - 1} elements", residual=err)
        return err, floor

    def _static_two_end(self, eta: float) -> NDArray[Any]:
        """Exact static two-end stiffness of the catenary, local frame, (6, 6) [N/m]:
        [[K_s, -K_s], [-K_s, K_s]], K_s = (int D^-1 ds)^-1 (theory.md §11.3)."""
        st = self.state
        F = np.zeros((3, 3), dtype=complex if eta > 0 else float)
        F2 = st.in_plane_flexibility                    # d(l_h, h)/d(H, Vb) = int D^-1 ds
        F[np.ix_([0, 2], [0, 2])] = F2
        F[1, 1] = 1.0 / st.out_of_plane_stiffness
        if eta > 0:
            Ixx, Ixz, Izz = tangent_integrals(st)
            d = (1.0 / (1.0 + 1j * eta) - 1.0) / st.cable.EA
            F[np.ix_([0, 2], [0, 2])] += d * np.array([[Ixx, Ixz], [Ixz, Izz]])
        Ks = np.linalg.inv(F)
        Ks = 0.5 * (Ks + Ks.T)
        return np.block([[Ks, -Ks], [-Ks, Ks]])

    # ------------------------------------------------------------------ parts
    @property
    def static_stiffness(self) -> NDArray[Any]:
        """Exact static two-end stiffness K_s, local frame, (6, 6) [N/m] (theory.md §11.3)."""
        return self._K_s

    @property
    def mass_psi(self) -> NDArray[Any]:
        """M_psi = M_bb + Psi^T M_ii Psi, local frame, (6, 6) [kg] (theory.md §11.3)."""
        return self._M_psi

    @property
    def flexibilities(self) -> NDArray[Any]:
        """mu_j = 1 / lambda_j of every interior mode (damped if the cable is), shape
        (n_modes,) [s^2/rad^2], in the order of :meth:`beta_dyads`."""
        return self._mu

    def beta_dyads(self, ends: str = "end") -> NDArray[Any]:
        """beta_j beta_j^T of every interior mode, flattened, local frame: (n_modes, 9) for
        the end-B block (``ends="end"``) or (n_modes, 36) (``"both"``) [kg]."""
        if ends == "both":
            return self._BB
        b = self._beta[:, 3:]
        return np.einsum("ja,jb->jab", b, b).reshape(b.shape[0], 9)

    # ------------------------------------------------------------------ queries
    def _check(self, omega: NDArray[np.float64]) -> None:
        w = np.abs(omega)
        if w.size and w.max() > self.omega_max * (1 + 1e-12):
            bad = np.asarray(omega).ravel()[int(np.argmax(w))]
            raise InvalidParameterError(
                f"omega must be <= {self.omega_max:.6g} rad/s ({self.omega_max / 2 / np.pi:.6g}"
                f" Hz), the band this exact cable model was built for, got {bad:.6g}; build "
                f"it with a larger omega_max (fmax_hz)")

    def omega_eff_sq(self, omega: NDArray[Any] | float) -> NDArray[Any] | float:
        """w^2 = omega^2 - i omega c / m [rad^2/s^2] (viscous damping as complex mass)."""
        w2 = omega**2
        if self.c > 0:
            w2 = w2 - 1j * omega * self.c / self.m
        return w2

    def local_coefficients(self, omega: NDArray[Any]) -> NDArray[Any]:
        """Two-end dynamic stiffness in the local frame, flattened, shape (n_omega, 36)
        [N/m], ordering (A x y z, B x y z) x (A x y z, B x y z) (theory.md §11.3).
        ``omega`` [rad/s], validated array (real or complex). At an omega exactly on a
        clamped pole (w^2 mu_j = 1 in floats) the stiffness is infinite: its entries there
        are not finite (inf, or NaN where a zero meets the infinity), without a warning."""
        self._check(omega)
        w2 = self.omega_eff_sq(omega)[:, None]
        mu = self._mu[None, :]
        with np.errstate(divide="ignore", invalid="ignore"):   # at a pole: inf, 0 x inf
            g = mu / (1.0 - w2 * mu)
            K = self._K_s.ravel()[None, :] - w2 * (self._M_psi.ravel()[None, :]
                                                   + w2 * (g @ self._BB))
        if not self.damped and np.isrealobj(omega):
            K = K.real
        return K

    def dynamic_stiffness(self, omega: ArrayLike, ends: str = "end") -> NDArray[Any]:
        """Dynamic stiffness in the global frame [N/m]: (n_omega, 3, 3) for end B with A
        clamped (``ends="end"``) or (n_omega, 6, 6) ordered (A xyz, B xyz) (``"both"``).
        Force applied to the cable end(s) per unit displacement; infinite at the poles."""
        if ends not in ("end", "both"):
            raise InvalidParameterError(f"ends must be 'end' or 'both', got {ends!r}")
        omega = omega_array(omega, complex_ok=True)
        K = self.local_coefficients(omega).reshape(-1, 6, 6)
        E6 = np.zeros((6, 6))
        E6[:3, :3] = E6[3:, 3:] = self.frame
        K = E6[None] @ K @ E6.T[None]
        return K[:, 3:, 3:] if ends == "end" else K

    def mode_count(self, omega: NDArray[np.float64]) -> NDArray[np.int64]:
        """J0: clamped-cable eigenvalues strictly below omega^2, shape (n_omega,) (damping
        ignored); ``omega`` [rad/s] validated array."""
        self._check(omega)
        return np.searchsorted(self.eigenvalues, np.asarray(omega) ** 2, side="left")

    def end_response(self, omega: float, u_end: NDArray[Any]) -> NDArray[np.complex128]:
        """Node displacements (n_nodes, 3) [m], local frame, for the end-B displacement
        ``u_end`` (3,) [m, local frame] with A clamped, at one omega [rad/s]:
        u_i = Psi u_b + w^2 (K_ii - w^2 M_ii)^-1 M_ii Psi u_b (theory.md §11.3)."""
        self._check(np.atleast_1d(omega))
        w2 = self.omega_eff_sq(complex(omega) if np.iscomplexobj(omega) else float(omega))
        ub = np.zeros(6, dtype=complex)
        ub[3:] = u_end
        n = self.s.size
        u = np.zeros((n, 3), dtype=complex)
        parts = []
        for f in self._fam:
            with np.errstate(divide="ignore", invalid="ignore"):
                q = w2 * f.mu / (1.0 - w2 * f.mu) * (f.beta @ ub)
            q = np.where(np.isfinite(q), q, 0.0)
            parts.append(f.psi @ ub[f.local] + f.shapes @ q)
        u[1:-1, 1] = parts[0]
        u[1:-1, 0], u[1:-1, 2] = parts[1][0::2], parts[1][1::2]
        u[-1] = u_end
        return u

    def discrete_static_stiffness(self) -> NDArray[Any]:
        """Static two-end stiffness of the discretisation itself, local frame, (6, 6) [N/m]:
        the Schur complement K_bb - K_bi K_ii^-1 K_ib, computed in mixed form (no entry of
        order EA / h, theory.md §11.2); converges to the exact one."""
        K = np.zeros((6, 6), dtype=np.result_type(*(f.static for f in self._fam)))
        for f in self._fam:
            K[np.ix_(f.local, f.local)] += f.static
        return K

    def _static_floor(self) -> NDArray[np.float64]:
        """Bound of the rounding error of :meth:`discrete_static_stiffness`, (6, 6) [N/m]."""
        K = np.zeros((6, 6))
        for f in self._fam:
            K[np.ix_(f.local, f.local)] += f.floor
        return K

    def kinetic_energy(self, omega: float, u_end: NDArray[np.float64]) -> float:
        """sum m_k |u_k|^2 [kg m^2] of the response to ``u_end`` at omega: the cable's kinetic
        energy per unit omega^2 / 2 (theory.md §11.3)."""
        u = self.end_response(omega, u_end)
        return float(np.sum(self.node_mass[:, None] * np.abs(u) ** 2))
