"""Numerically exact dynamic stiffness of one cable linearised about its elastic catenary.

No shallow-cable approximation (theory.md §11): the tension varies along the arc, the whole
weight acts (its chordwise part included), axial and transverse motions are coupled through
the curvature, the cable is extensible and may be steep, sagging or slack. With s the
unstretched arc length, t(s) the unit tangent, T(s) the tension and u(s) the small motion,

    m u_tt = (D(s) u')',   D = EA t t^T + T / (1 + T/EA) (I - t t^T)        (theory.md §11.1)

(the weight is constant and drops out of the increment). The motion perpendicular to the
vertical cable plane decouples (a string of varying tension); the in-plane motion is a
coupled pair. Viscous damping c [N s/m^2] on all motions enters as m -> m - i c / omega,
hysteretic damping as EA -> EA (1 + i eta) on the axial strain (theory.md §11.4).

Discretisation (theory.md §11.2): spectral elements of order ``order`` with
Gauss-Lobatto-Legendre nodes (diagonal mass), graded towards low tension and sized to the
transverse wavelength at ``omega_max``. The interior (A and B clamped) is condensed exactly
through its clamped modes (lambda_j, phi_j), computed once:

    K(omega) = K_s - w^2 [M_bb + sum_j c_j c_j^T / (lambda_j (lambda_j - w^2))],
    w^2 = omega^2 - i omega c / m,   c_j = K_bi phi_j                    (theory.md §11.3)

with K_s the exact static two-end stiffness of the catenary (so omega -> 0 is exact). The
poles lambda_j are the clamped-cable frequencies: the exact J0 of Wittrick-Williams counting.
Local frame: x along the horizontal direction from A to B, y = z x x (out of plane), z up.
"""

import functools
from dataclasses import dataclass
from numbers import Integral, Real

import numpy as np

from dynstiff._validate import omega_array
from dynstiff._vec import cross
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError

__all__ = ["ExactCable", "DEFAULT_ORDER", "HALF_WAVES_PER_ELEMENT"]

#: Polynomial order of the spectral elements.
DEFAULT_ORDER = 12
#: Transverse half-wavelengths per element at ``omega_max`` (theory.md §11.2).
HALF_WAVES_PER_ELEMENT = 2.0
#: Elements per e-fold of the tension measure asinh(V/H) (grading towards low tension).
ELEMENTS_PER_EFOLD = 1.0
#: Largest relative difference allowed between the discretisation's static stiffness and the
#: exact one (theory.md §11.2); measured 1e-11 to 5e-8 on taut, sagging, steep and slack cables.
STATIC_CHECK_RTOL = 1e-6
_EZ = np.array([0.0, 0.0, 1.0])


@functools.lru_cache(maxsize=16)
def gll(order):
    """Gauss-Lobatto-Legendre nodes xi (p+1,) on [-1, 1], weights (p+1,) and the
    differentiation matrix Dm (p+1, p+1), Dm[q, a] = l_a'(xi_q)."""
    p = int(order)
    Pp = np.polynomial.legendre.Legendre.basis(p)
    xi = np.concatenate([[-1.0], np.sort(Pp.deriv().roots().real), [1.0]])
    P = Pp(xi)
    w = 2.0 / (p * (p + 1) * P**2)
    with np.errstate(divide="ignore"):
        Dm = P[:, None] / (P[None, :] * (xi[:, None] - xi[None, :]))
    np.fill_diagonal(Dm, 0.0)
    Dm[0, 0], Dm[p, p] = -p * (p + 1) / 4.0, p * (p + 1) / 4.0
    for a in (xi, w, Dm):
        a.flags.writeable = False
    return xi, w, Dm


@dataclass(frozen=True)
class _Static:
    """The static state along the cable at arc lengths s: tension T [N], tangent (tx, tz)
    in the cable plane, stretch factor 1 + T/EA."""

    T: np.ndarray
    tx: np.ndarray
    tz: np.ndarray


def _static_along(state, s):
    """T(s), t(s) of the elastic catenary at unstretched arc lengths s [m] (theory.md §1.1)."""
    w0 = state.cable.weight_per_length(state.g)
    V = state.V0 + w0 * np.asarray(s, dtype=float)
    T = np.hypot(state.H, V)
    return _Static(T=T, tx=state.H / T, tz=V / T)


def _mesh(state, omega_max, half_waves, per_efold=ELEMENTS_PER_EFOLD):
    """Element boundaries in s [m], shape (n_el + 1,) (theory.md §11.2).

    Elements are spread evenly in the measure
        Phi(s) = s / L0 + (asinh(V/H) - asinh(V0/H)) / per_efold + int k_t ds / (pi half_waves)
    where k_t = omega_max sqrt(m (1 + T/EA) / T) is the transverse wavenumber: the second term
    grades the mesh geometrically towards a point of low tension (a slack cable's U), the third
    resolves the waves of the band.
    """
    L0, EA, m = state.unstretched_length, state.cable.EA, state.cable.mass_per_length
    w0 = state.cable.weight_per_length(state.g)
    s = np.linspace(0.0, L0, 4001)
    if state.H > 0 and w0 > 0:
        a0, a1 = np.arcsinh(state.V0 / state.H), np.arcsinh(state.Vb / state.H)
        s_psi = (state.H * np.sinh(np.linspace(a0, a1, 4001)) - state.V0) / w0
        s = np.unique(np.clip(np.concatenate([s, s_psi]), 0.0, L0))
    st = _static_along(state, s)
    if state.H > 0:
        psi = np.arcsinh((state.V0 + w0 * s) / state.H)
    else:
        psi = np.log(np.maximum(st.T, 1e-300))
    k = omega_max * np.sqrt(m * (1.0 + st.T / EA) / np.maximum(st.T, 1e-300))
    wave = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(s))])
    phi = s / L0 + np.abs(psi - psi[0]) / per_efold + wave / (np.pi * half_waves)
    phi = np.maximum.accumulate(phi)
    n_el = max(1, int(np.ceil(phi[-1])))
    edges = np.interp(np.linspace(0.0, phi[-1], n_el + 1), phi, s)
    edges[0], edges[-1] = 0.0, L0
    return edges


def _tangent_integrals(state):
    """int_0^L0 t t^T ds in the cable plane, (I_xx, I_xz, I_zz) [m], closed form."""
    H, V0, Vb, L0 = state.H, state.V0, state.Vb, state.unstretched_length
    W = Vb - V0
    T0sq = H * H + V0 * V0
    if H == 0.0:
        return 0.0, 0.0, L0
    if W == 0.0:
        Ixx, Ixz = L0 * H * H / T0sq, L0 * H * V0 / T0sq
    else:
        Ixx = H * L0 * np.arctan2(H * W, H * H + V0 * Vb) / W
        Ixz = 0.5 * H * L0 * np.log1p(W * (V0 + Vb) / T0sq) / W
    return Ixx, Ixz, L0 - Ixx


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
        [-] (a self-check; the constructor raises ConvergenceError above 1e-6).
    eigenvalues : ndarray, shape (n_modes,)
        Undamped clamped-cable eigenvalues omega_j^2 [rad^2/s^2], ascending.
    family : tuple of str
        "out-of-plane", "in-plane" or "axial" (in-plane with most of its kinetic energy in
        motion along the cable).
    axial_share : ndarray, shape (n_modes,)
        That share of the kinetic energy [-].
    """

    def __init__(self, state, omega_max, order=DEFAULT_ORDER, damping=True,
                 half_waves=HALF_WAVES_PER_ELEMENT):
        if not (isinstance(omega_max, Real) and np.isfinite(omega_max) and omega_max > 0):
            raise InvalidParameterError(
                f"omega_max must be finite and > 0 [rad/s], got {omega_max!r}")
        if isinstance(order, bool) or not isinstance(order, Integral) or not 4 <= order <= 40:
            raise InvalidParameterError(f"order must be an integer in [4, 40], got {order!r}")
        if not all(hasattr(state, a) for a in ("H", "V0", "cable", "unstretched_length")):
            raise InvalidParameterError(
                f"state must be a CatenaryState (dynstiff.solve_catenary), got "
                f"{type(state).__name__}")
        cab = state.cable
        self.state, self.omega_max, self.order = state, float(omega_max), int(order)
        self.damped = bool(damping) and cab.is_damped
        self.m = cab.mass_per_length
        self.c = cab.viscous_damping if self.damped else 0.0
        eta = cab.loss_factor if self.damped else 0.0
        e_x = state.horizontal_direction
        self.frame = np.column_stack([e_x, cross(_EZ, e_x), _EZ])
        if not (isinstance(half_waves, Real) and 0 < half_waves <= 8):
            raise InvalidParameterError(
                f"half_waves must be a number in (0, 8], got {half_waves!r}")
        self.edges = _mesh(state, self.omega_max, float(half_waves))
        xi, wq, Dm = gll(self.order)
        p, n_el = self.order, len(self.edges) - 1
        h = np.diff(self.edges)
        s = (self.edges[:-1, None] + 0.5 * (xi[None, :] + 1.0) * h[:, None])   # (n_el, p+1)
        n = n_el * p + 1
        self.s = np.concatenate([s[:, :-1].ravel(), [self.edges[-1]]])
        st = _static_along(state, s)
        EA = cab.EA
        Dt = st.T / (1.0 + st.T / EA)                       # transverse coefficient [N]
        Dxx = EA * st.tx**2 + Dt * st.tz**2
        Dxz = (EA - Dt) * st.tx * st.tz
        Dzz = EA * st.tz**2 + Dt * st.tx**2
        # element matrices: Ke[a, b] = (2/h) sum_q w_q Dm[q, a] Dm[q, b] D(s_q)
        G = np.einsum("q,qa,qb->qab", wq, Dm, Dm)           # (p+1, p+1, p+1)
        scale = 2.0 / h
        k_out = np.einsum("e,eq,qab->eab", scale, Dt, G)
        k_xx = np.einsum("e,eq,qab->eab", scale, Dxx, G)
        k_xz = np.einsum("e,eq,qab->eab", scale, Dxz, G)
        k_zz = np.einsum("e,eq,qab->eab", scale, Dzz, G)
        idx = np.arange(n_el)[:, None] * p + np.arange(p + 1)[None, :]
        K1 = np.zeros((n, n))
        K2 = np.zeros((2 * n, 2 * n))
        # axial-only stiffness (for the labels and hysteretic damping): EA t t^T
        Ka = np.zeros((2 * n, 2 * n))
        a_xx = np.einsum("e,eq,qab->eab", scale, EA * st.tx**2, G)
        a_xz = np.einsum("e,eq,qab->eab", scale, EA * st.tx * st.tz, G)
        a_zz = np.einsum("e,eq,qab->eab", scale, EA * st.tz**2, G)
        for e in range(n_el):
            ix = np.ix_(idx[e], idx[e])
            K1[ix] += k_out[e]
            i2x, i2z = 2 * idx[e], 2 * idx[e] + 1
            K2[np.ix_(i2x, i2x)] += k_xx[e]
            K2[np.ix_(i2x, i2z)] += k_xz[e]
            K2[np.ix_(i2z, i2x)] += k_xz[e].T
            K2[np.ix_(i2z, i2z)] += k_zz[e]
            Ka[np.ix_(i2x, i2x)] += a_xx[e]
            Ka[np.ix_(i2x, i2z)] += a_xz[e]
            Ka[np.ix_(i2z, i2x)] += a_xz[e].T
            Ka[np.ix_(i2z, i2z)] += a_zz[e]
        mass = np.zeros(n)
        np.add.at(mass, idx, self.m * 0.5 * h[:, None] * wq[None, :])
        self.node_mass = mass                                 # [kg] per component
        K_bb = np.zeros((6, 6), dtype=complex if eta > 0 else float)
        for node, off in ((0, 0), (n - 1, 3)):
            K_bb[off + 1, off + 1] = K1[node, node]
        K_bb[1, 4] = K_bb[4, 1] = K1[0, n - 1]
        K2c = K2 + 1j * eta * Ka if eta > 0 else K2
        b2 = [0, 1, 2 * n - 2, 2 * n - 1]
        loc = [0, 2, 3, 5]
        K_bb[np.ix_(loc, loc)] = K2c[np.ix_(b2, b2)]
        self._K_bb = K_bb
        t_nodes = _static_along(state, self.s)
        try:
            self._build_modes(K1, K2, Ka, mass, eta, np.stack([t_nodes.tx, t_nodes.tz],
                                                              axis=1))
        except np.linalg.LinAlgError:
            ratio = state.min_tension / state.max_tension
            raise SlackCableError(
                f"the cable is too slack for the exact model in double precision (lowest "
                f"tension {state.min_tension:.3g} N, {ratio:.3g} of the highest: its stiffness "
                f"matrix is not positive definite after rounding)") from None
        self._K_s = self._static_two_end(eta)
        self.static_mismatch = self._self_check()

    # ------------------------------------------------------------------ construction
    def _build_modes(self, K1, K2, Ka, mass, eta, tangent):
        """Clamped modes of the interior, in flexibility form, and the static constraint
        modes (local 6-vector ordering A x y z, B x y z) (theory.md §11.3)."""
        n = mass.size
        inner = np.arange(1, n - 1)
        inner2 = np.stack([2 * inner, 2 * inner + 1], axis=1).ravel()
        fam_out = _condense(K1, mass[inner], inner, [0, n - 1], [1, 4])
        fam_in = _condense(K2, np.repeat(mass[inner], 2), inner2,
                           [0, 1, 2 * n - 2, 2 * n - 1], [0, 2, 3, 5])
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
        self._fam = (fam_out, fam_in if eta == 0 else
                     _condense(K2 + 1j * eta * Ka, np.repeat(mass[inner], 2), inner2,
                               [0, 1, 2 * n - 2, 2 * n - 1], [0, 2, 3, 5]))
        self._mu = np.concatenate([f.mu for f in self._fam])
        self._beta = np.concatenate([f.beta for f in self._fam])
        self._BB = np.einsum("ja,jb->jab", self._beta, self._beta).reshape(self._mu.size, 36)
        self._M_psi = sum(f.M_psi for f in self._fam)
        self._M_psi[[0, 1, 2], [0, 1, 2]] += mass[0]
        self._M_psi[[3, 4, 5], [3, 4, 5]] += mass[-1]
        for a in (self.eigenvalues, self.axial_share, self.s, self.edges, self.frame,
                  self.node_mass):
            a.flags.writeable = False

    def _self_check(self):
        """Relative difference of the discretisation's own static stiffness from the exact one
        (theory.md §11.2); raises ConvergenceError above STATIC_CHECK_RTOL (a cable too slack
        or too stiff for double precision) instead of returning a wrong model."""
        Kd = self.discrete_static_stiffness()
        Ks = self._K_s
        err = float(np.abs(Kd - Ks).max() / np.abs(Ks).max())
        if not err <= STATIC_CHECK_RTOL:
            st = self.state
            raise ConvergenceError(
                f"the exact cable model does not reproduce the catenary's static stiffness "
                f"(relative error {err:.2g} > {STATIC_CHECK_RTOL:g}); lowest tension "
                f"{st.min_tension:.3g} N is {st.min_tension / st.max_tension:.3g} of the "
                f"highest, EA / T_min = {st.cable.EA / st.min_tension:.3g}: the cable is too "
                f"slack (or too stiff) for double precision", residual=err)
        return err

    def _static_two_end(self, eta):
        """Exact static two-end stiffness of the catenary, local frame, (6, 6) [N/m]:
        [[K_s, -K_s], [-K_s, K_s]], K_s = (int D^-1 ds)^-1 (theory.md §11.3)."""
        st = self.state
        F = np.zeros((3, 3), dtype=complex if eta > 0 else float)
        F2 = st.in_plane_flexibility                    # d(l_h, h)/d(H, Vb) = int D^-1 ds
        F[np.ix_([0, 2], [0, 2])] = F2
        F[1, 1] = 1.0 / st.out_of_plane_stiffness
        if eta > 0:
            Ixx, Ixz, Izz = _tangent_integrals(st)
            d = (1.0 / (1.0 + 1j * eta) - 1.0) / st.cable.EA
            F[np.ix_([0, 2], [0, 2])] += d * np.array([[Ixx, Ixz], [Ixz, Izz]])
        Ks = np.linalg.inv(F)
        Ks = 0.5 * (Ks + Ks.T)
        return np.block([[Ks, -Ks], [-Ks, Ks]])

    # ------------------------------------------------------------------ parts
    @property
    def static_stiffness(self):
        """Exact static two-end stiffness K_s, local frame, (6, 6) [N/m] (theory.md §11.3)."""
        return self._K_s

    @property
    def mass_psi(self):
        """M_psi = M_bb + Psi^T M_ii Psi, local frame, (6, 6) [kg] (theory.md §11.3)."""
        return self._M_psi

    @property
    def flexibilities(self):
        """mu_j = 1 / lambda_j of every interior mode (damped if the cable is), shape
        (n_modes,) [s^2/rad^2], in the order of :meth:`beta_dyads`."""
        return self._mu

    def beta_dyads(self, ends="end"):
        """beta_j beta_j^T of every interior mode, flattened, local frame: (n_modes, 9) for
        the end-B block (``ends="end"``) or (n_modes, 36) (``"both"``) [kg]."""
        if ends == "both":
            return self._BB
        b = self._beta[:, 3:]
        return np.einsum("ja,jb->jab", b, b).reshape(b.shape[0], 9)

    # ------------------------------------------------------------------ queries
    def _check(self, omega):
        w = np.abs(omega)
        if w.size and w.max() > self.omega_max * (1 + 1e-12):
            bad = np.asarray(omega).ravel()[int(np.argmax(w))]
            raise InvalidParameterError(
                f"omega must be <= {self.omega_max:.6g} rad/s ({self.omega_max / 2 / np.pi:.6g}"
                f" Hz), the band this exact cable model was built for, got {bad:.6g}; build "
                f"it with a larger omega_max (fmax_hz)")

    def omega_eff_sq(self, omega):
        """w^2 = omega^2 - i omega c / m [rad^2/s^2] (viscous damping as complex mass)."""
        w2 = omega**2
        if self.c > 0:
            w2 = w2 - 1j * omega * self.c / self.m
        return w2

    def local_coefficients(self, omega):
        """Two-end dynamic stiffness in the local frame, flattened, shape (n_omega, 36)
        [N/m], ordering (A x y z, B x y z) x (A x y z, B x y z) (theory.md §11.3).
        ``omega`` [rad/s], validated array (real or complex)."""
        self._check(omega)
        w2 = self.omega_eff_sq(omega)[:, None]
        mu = self._mu[None, :]
        with np.errstate(divide="ignore", invalid="ignore"):
            g = mu / (1.0 - w2 * mu)
        K = self._K_s.ravel()[None, :] - w2 * (self._M_psi.ravel()[None, :]
                                               + w2 * (g @ self._BB))
        if not self.damped and np.isrealobj(omega):
            K = K.real
        return K

    def dynamic_stiffness(self, omega, ends="end"):
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

    def mode_count(self, omega):
        """J0: clamped-cable eigenvalues strictly below omega^2, shape (n_omega,) (damping
        ignored); ``omega`` [rad/s] validated array."""
        self._check(omega)
        return np.searchsorted(self.eigenvalues, np.asarray(omega) ** 2, side="left")

    def end_response(self, omega, u_end):
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

    def discrete_static_stiffness(self):
        """Static two-end stiffness of the discretisation itself, local frame, (6, 6) [N/m]:
        the Schur complement K_bb - K_bi K_ii^-1 K_ib; converges to the exact one
        (theory.md §11.2)."""
        K = self._K_bb.copy()
        for f in self._fam:
            K[np.ix_(f.local, f.local)] -= f.schur
        return K

    def kinetic_energy(self, omega, u_end):
        """sum m_k |u_k|^2 [kg m^2] of the response to ``u_end`` at omega: the cable's kinetic
        energy per unit omega^2 / 2 (theory.md §11.3)."""
        u = self.end_response(omega, u_end)
        return float(np.sum(self.node_mass[:, None] * np.abs(u) ** 2))


@dataclass(frozen=True)
class _Family:
    """One decoupled family (out-of-plane or in-plane) of the clamped interior.

    mu: flexibility eigenvalues 1/lambda_j [s^2/rad^2]; shapes: phi_j (n_i, n_modes),
    M-orthonormal; psi: static constraint modes -K_ii^-1 K_ib (n_i, n_b); beta: (n_modes, 6)
    couplings phi_j^T M Psi placed in the local 6-vector; M_psi: (6, 6) Psi^T M Psi; local:
    the family's positions in the 6-vector; schur: K_bi K_ii^-1 K_ib (n_b, n_b)."""

    mu: np.ndarray
    shapes: np.ndarray
    psi: np.ndarray
    beta: np.ndarray
    M_psi: np.ndarray
    local: list
    schur: np.ndarray


def _condense(K, m_inner, inner, bnd, local):
    """Flexibility-form modal condensation of one family (theory.md §11.3).

    The eigenvalues of M^1/2 K_ii^-1 M^1/2 are 1/lambda_j: the low modes, which carry the
    dynamics, keep their relative accuracy however stiff the axial part is (a dense
    eigensolver on K_ii would lose them to the largest eigenvalue's rounding)."""
    from scipy.linalg import cho_factor, cho_solve, eig, eigh, lu_factor, lu_solve
    Kii = K[np.ix_(inner, inner)]
    Kib = K[np.ix_(inner, bnd)]
    complex_ = np.iscomplexobj(K)
    n_i = len(inner)
    if complex_:
        fac = lu_factor(Kii)
        F = lu_solve(fac, np.eye(n_i))
        psi = -lu_solve(fac, Kib)
    else:
        fac = cho_factor(Kii)
        F = cho_solve(fac, np.eye(n_i))
        psi = -cho_solve(fac, Kib)
    r = np.sqrt(m_inner)
    A = r[:, None] * F * r[None, :]
    A = 0.5 * (A + A.T)
    if complex_:
        mu, V = eig(A)
        V = V / np.sqrt(np.einsum("ij,ij->j", V, V))[None, :]
    else:
        mu, V = eigh(A)
    shapes = V / r[:, None]
    b = (V.T * r[None, :]) @ psi                              # (n_modes, n_b)
    beta = np.zeros((mu.size, 6), dtype=b.dtype)
    beta[:, local] = b
    M_psi = np.zeros((6, 6), dtype=b.dtype)
    M_psi[np.ix_(local, local)] = psi.T @ (m_inner[:, None] * psi)
    schur = -(Kib.T @ psi)
    return _Family(mu=mu, shapes=shapes, psi=psi, beta=beta, M_psi=M_psi, local=local,
                   schur=schur)
