"""Closed-form dynamic stiffness matrix (DSM) of one inclined, sagging, elastic cable.

Linear theory of Irvine & Caughey (1974) for the in-plane motion and the taut string for the
out-of-plane motion, written as end-force / end-displacement relations (Starossek 1991;
theory.md §3). The weight component along the chord is neglected (Irvine's inclined-cable
approximation), as is the cable's chordwise inertia, which can be restored to first order
(``chordwise_inertia=True``, consistent axial mass m L/3, theory.md §3.6).

Notation (chord frame, theory.md §1.2, §3.1)
--------------------------------------------
==============  =====================================================  ========
symbol          meaning                                                unit
==============  =====================================================  ========
L               chord length |B - A|                                   m
T               tension used by the linear theory (see ``tension``)   N
m               mass per unit chord length, m0 L0 / L                  kg/m
q               load perpendicular to the chord, m g cos(theta)        N/m
d               mid-span sag, q L^2 / (8 T)                            m
L_e             compliance length, L0 (1 + 8 (d/L)^2)                  m
K0              EA / L_e                                               N/m
lambda_sq       Irvine parameter (q L / T)^2 L EA / (T L_e)            --
alpha           static end slope to the chord, q L / (2 T)             --
psi             half the nondimensional frequency, Omega / 2           --
Omega           beta L, beta^2 = (omega^2 m - i omega c) / T           --
==============  =====================================================  ========

Conventions chosen (and why)
----------------------------
* **Tension** ``tension="mean"`` (default): T is the tension averaged over the cable. With the
  chordwise weight neglected, T is uniform in the theory; the true tension varies linearly
  along the chord, and to first order a string's frequencies depend on the average of T
  (perturbation of the Rayleigh quotient with the even weight sin^2(n pi x/L)). The option
  ``tension="chord"`` uses Irvine's H* = H / cos(theta) (tension where the tangent is parallel
  to the chord); the two differ by O(q L / T)^2 and by the along-chord weight.
* **Mass** per unit *chord* length, m = m0 L0 / L (m0 per unstretched length), so the model
  carries the cable's true total mass m0 L0. Per stretched length would differ by O((d/L)^2).
* **Compliance** uses the unstretched length, L_e = L0 (1 + 8 (d/L)^2), because EA refers to
  the unstretched length: the chord stiffness of a straight weightless cable is then exactly
  EA / L0 and the transverse one T / L (the massless limit is exact). Irvine's L (1 + 8 (d/L)^2)
  differs by the static strain T/EA.

All matrices give the forces applied **to** the cable ends per unit end displacement.
"""

import functools
from dataclasses import dataclass
from numbers import Integral

import numpy as np

from dynstiff._validate import omega_array
from dynstiff.cable.chord import ChordParameters, chord_parameters, stack_parameters
from dynstiff.cable.exact import ExactCable
from dynstiff.errors import ClosedFormWarning, InvalidParameterError, user_stacklevel

__all__ = [
    "ChordParameters",
    "chord_parameters",
    "stack_parameters",
    "local_entries",
    "end_block_coefficients",
    "closed_form_validity",
    "closed_form_local_error",
    "ClosedFormValidity",
    "DEFAULT_GUARD_RTOL",
    "mode_count_nondimensional",
    "check_frequency_range",
    "MAX_OMEGA_ND",
    "cable_field",
    "cable_kinetic_energy",
    "local_end_stiffness",
    "local_two_end_stiffness",
    "cable_dynamic_stiffness",
    "cable_mode_count",
    "CableModes",
    "cable_natural_frequencies",
    "DEFAULT_CHORDWISE_INERTIA",
    "dyad_basis",
    "block_coefficients",
    "end_block_coefficients_and_count",
    "PSI_SERIES",
]

#: Default of ``chordwise_inertia`` (see validation/chordwise_inertia.py for the evidence).
DEFAULT_CHORDWISE_INERTIA = True

_SERIES_RADIUS = 1.0
_N_TERMS = 16

#: Largest nondimensional frequency |Omega| = |omega| L sqrt(m/T) at which the closed forms
#: are evaluated: there sin and cos of psi = Omega/2 still carry 9 correct digits (the phase
#: error is ulp(psi) ~ 1e-9) and the mode counts are exact integers; about 3 million clamped
#: modes of the cable lie below it.
MAX_OMEGA_ND = 1e7
#: Largest |Im psi| (damped or complex frequencies): sin and cos overflow near 710.
MAX_IMAG_PSI = 350.0
#: Estimated relative frequency error above which the closed form warns (theory.md §11.5).
DEFAULT_GUARD_RTOL = 1e-2


def check_frequency_range(params, omega, name="omega"):
    """Raise InvalidParameterError naming ``name`` unless every omega [rad/s] keeps
    |Omega| <= MAX_OMEGA_ND and |Im psi| <= MAX_IMAG_PSI for the cable(s) ``params``
    (ChordParameters, single or stacked); the message gives the admissible bound [rad/s]."""
    scale = np.max(np.atleast_1d(params.L * np.sqrt(params.m / params.T)))   # Omega per rad/s
    w = np.abs(np.asarray(omega))
    if w.size and w.max() * scale > MAX_OMEGA_ND:
        bad = np.asarray(omega).ravel()[int(np.argmax(w))]
        bad = complex(bad) if np.iscomplexobj(omega) else float(bad)
        raise InvalidParameterError(
            f"{name} must be <= {MAX_OMEGA_ND / scale:.6g} rad/s for this cable model "
            f"(omega L sqrt(m/T) <= {MAX_OMEGA_ND:g}, beyond which the closed form loses its "
            f"digits), got {bad:.6g}")
    if np.iscomplexobj(omega) and w.size:
        psi = np.abs(np.imag(params.psi(np.asarray(omega).reshape(-1, 1)
                                        if np.ndim(params.L) else np.asarray(omega))))
        if psi.max() > MAX_IMAG_PSI:
            raise InvalidParameterError(
                f"{name} has an imaginary part too large for the closed form (|Im psi| = "
                f"{psi.max():.4g} > {MAX_IMAG_PSI:g}: sin and cos overflow)")


# --------------------------------------------------------------------------- psi kernels
def _series_coefficients():
    """Taylor coefficients (in powers psi^(2k), k = 0..N-1) of E, P~ and Q~."""
    from math import factorial
    a = [(-1) ** k * 4**k / factorial(2 * k + 1) for k in range(_N_TERMS + 2)]  # sin2psi/2
    b = [(-1) ** k * 4**k / factorial(2 * k) for k in range(_N_TERMS + 2)]      # cos 2psi
    E = [(-1) ** n * 2 * n / factorial(2 * n + 1) for n in range(1, _N_TERMS + 1)]
    P = [a[k] + a[k - 1] for k in range(1, _N_TERMS + 1)]
    Q = [b[k] + a[k - 1] - a[k] for k in range(1, _N_TERMS + 1)]
    # numpy.polyval wants the highest power first
    return np.array(E[::-1]), np.array(P[::-1]), np.array(Q[::-1])


_E_COEF, _P_COEF, _Q_COEF = _series_coefficients()
#: (radius, E coefficients, P~ coefficients) of the series branch of :func:`_psi_functions`,
#: highest power of psi^2 first, for compiled kernels that evaluate the same functions.
PSI_SERIES = (_SERIES_RADIUS, _E_COEF, _P_COEF)


def _psi_functions(psi):
    """Cancellation-free functions of psi (real or complex array).

    Returns (c, s_over_psi, cos2, E, Pt, Qt) with
    E  = (psi cos psi - sin psi) / psi^3,
    Pt = ((1 + psi^2) sin(2 psi)/2 - psi) / psi^3,
    Qt = (psi cos 2psi + (psi^2 - 1) sin(2 psi)/2) / psi^3,
    each by its Taylor series for |psi| < 1 (no cancellation) and directly otherwise.
    """
    s, c = np.sin(psi), np.cos(psi)
    cos2 = c * c - s * s
    small = np.abs(psi) < _SERIES_RADIUS
    with np.errstate(divide="ignore", invalid="ignore"):
        s_over_psi = np.where(psi == 0, 1.0, s / np.where(psi == 0, 1.0, psi))
        p3 = psi**3
        E = (psi * c - s) / p3
        Pt = ((1 + psi * psi) * s * c - psi) / p3
        Qt = (psi * cos2 + (psi * psi - 1) * s * c) / p3
    if np.any(small):
        x = psi[small] ** 2
        E[small] = np.polyval(_E_COEF, x)
        Pt[small] = np.polyval(_P_COEF, x)
        Qt[small] = np.polyval(_Q_COEF, x)
    return c, s_over_psi, cos2, E, Pt, Qt


def local_entries(p, omega, chordwise_inertia):
    """Independent entries of the local two-end DSM, each shape (n_omega,).

    Elementwise: ``p`` may hold arrays of shape (n_cables,) with ``omega`` of shape
    (n_omega, 1), giving entries of shape (n_omega, n_cables) for all cables at once.

    Returns (k_uu, k_uv, k_vv, k_vv_AB, kw_s, kw_c, m_axial) where, with the two-end
    in-plane matrix written as (K0/D) g g^T + string terms, g = [1, a_t, -1, a_t]:
    k_uu = K0/D, k_uv = alpha tau K0/D, k_vv = k_s + (alpha tau)^2 K0/D,
    k_vv_AB = k_c + (alpha tau)^2 K0/D, kw_s / kw_c the out-of-plane string terms and
    m_axial = -omega^2 m~ L / 6 the consistent chordwise-mass unit (0 when not requested).
    Stable forms of theory.md §3.5, rewritten with the series functions above
    (den = 4 cos psi - lambda^2 E = Delta / psi^3).
    """
    psi = np.asarray(p.psi(omega))
    return _entries_from(p, omega, psi, _psi_functions(psi), chordwise_inertia)


def _entries_from(p, omega, psi, functions, chordwise_inertia):
    """:func:`local_entries` from psi and its :func:`_psi_functions`."""
    lam2 = p.lambda_sq_complex
    K0, T, L = p.K0, p.T, p.L
    c, s_over_psi, cos2, E, Pt, Qt = functions
    den = 4.0 * c - lam2 * E
    TL = T / L
    with np.errstate(divide="ignore", invalid="ignore"):
        k_uu = 4.0 * K0 * c / den
        k_uv = 4.0 * p.alpha * K0 * psi * psi * E / den
        k_vv = TL * (4.0 * cos2 + lam2 * Pt) / (s_over_psi * den)
        k_vv_AB = TL * (-4.0 + lam2 * Qt) / (s_over_psi * den)
        sinc2 = s_over_psi * c                       # sin(2 psi) / (2 psi)
        kw_s = TL * cos2 / sinc2
        kw_c = -TL / sinc2
    if chordwise_inertia:          # -omega^2 m~ L/6 with m~ = m - i c/omega
        inertia = omega**2 * p.m - 1j * omega * p.c if np.any(p.c != 0) else omega**2 * p.m
        m_axial = -inertia * L / 6.0
    else:
        m_axial = np.zeros_like(k_uu)
    return k_uu, k_uv, k_vv, k_vv_AB, kw_s, kw_c, m_axial


def _real_if_undamped(p, K, omega):
    """Drop the zero imaginary part for an undamped cable at real frequencies."""
    if p.c == 0 and np.isrealobj(p.EA) and np.isrealobj(omega):
        return np.real(K)
    return K


def local_end_stiffness(params, omega, chordwise_inertia=DEFAULT_CHORDWISE_INERTIA):
    """3x3 DSM of end B with A clamped, in the local chord frame (u, v, w).

    K_B = [[K0/D, -alpha tau K0/D, 0], [., k_s + (alpha tau)^2 K0/D, 0], [0, 0, k_s]]
    (theory.md §3.4), plus -omega^2 m L / 3 on K_uu with ``chordwise_inertia``.

    Parameters
    ----------
    params : ChordParameters
    omega : ndarray, shape (n_omega,)
        Angular frequencies [rad/s], >= 0.
    chordwise_inertia : bool

    Returns
    -------
    ndarray, shape (n_omega, 3, 3) [N/m]; real if undamped, complex otherwise.
    """
    k_uu, k_uv, k_vv, _, kw_s, _, m_ax = local_entries(params, omega, chordwise_inertia)
    K = np.zeros((omega.size, 3, 3), dtype=np.result_type(k_uu, k_vv, kw_s, m_ax))
    K[:, 0, 0] = k_uu + 2.0 * m_ax
    K[:, 0, 1] = K[:, 1, 0] = -k_uv
    K[:, 1, 1] = k_vv
    K[:, 2, 2] = kw_s
    return _real_if_undamped(params, K, omega)


def local_two_end_stiffness(params, omega, chordwise_inertia=DEFAULT_CHORDWISE_INERTIA):
    """6x6 DSM of both ends in the local chord frame, ordered (u_A, v_A, w_A, u_B, v_B, w_B).

    In-plane: (K0/D) g g^T + [[0,0,0,0],[0,k_s,0,k_c],[0,0,0,0],[0,k_c,0,k_s]],
    g = [1, alpha tau, -1, alpha tau] on (u_A, v_A, u_B, v_B); out-of-plane [[k_s, k_c],
    [k_c, k_s]] on (w_A, w_B) (theory.md §3.2-3.3); with ``chordwise_inertia`` the consistent
    axial mass -omega^2 (m L / 6) [[2, 1], [1, 2]] on (u_A, u_B).

    Returns
    -------
    ndarray, shape (n_omega, 6, 6) [N/m].
    """
    k_uu, k_uv, k_vv, k_vv_AB, kw_s, kw_c, m_ax = local_entries(
        params, omega, chordwise_inertia)
    K = np.zeros((omega.size, 6, 6), dtype=np.result_type(k_uu, k_vv, kw_s, m_ax))
    uA, vA, wA, uB, vB, wB = range(6)
    K[:, uA, uA] = K[:, uB, uB] = k_uu + 2.0 * m_ax
    K[:, uA, uB] = K[:, uB, uA] = -k_uu + m_ax
    K[:, uA, vA] = K[:, vA, uA] = k_uv
    K[:, uA, vB] = K[:, vB, uA] = k_uv
    K[:, uB, vA] = K[:, vA, uB] = -k_uv
    K[:, uB, vB] = K[:, vB, uB] = -k_uv
    K[:, vA, vA] = K[:, vB, vB] = k_vv
    K[:, vA, vB] = K[:, vB, vA] = k_vv_AB
    K[:, wA, wA] = K[:, wB, wB] = kw_s
    K[:, wA, wB] = K[:, wB, wA] = kw_c
    return _real_if_undamped(params, K, omega)


def cable_dynamic_stiffness(state, omega, ends="end", tension="mean",
                            chordwise_inertia=DEFAULT_CHORDWISE_INERTIA, model="closed-form",
                            guard_rtol=DEFAULT_GUARD_RTOL):
    """Dynamic stiffness matrix of one sagging cable in the global frame.

    Parameters
    ----------
    state : CatenaryState
        Static equilibrium from :func:`dynstiff.solve_catenary`.
    omega : float or array_like, shape (n_omega,)
        Angular frequencies [rad/s], finite and >= 0.
    ends : {"end", "both"}
        "end": 3x3 matrix of end B with A clamped; "both": 6x6 ordered (A xyz, B xyz).
    tension : {"mean", "chord"}
        Tension of the linear theory (see :func:`chord_parameters`).
    chordwise_inertia : bool
        Add the consistent chordwise mass of the cable (theory.md §3.6).
    model : {"closed-form", "exact"}
        "closed-form": the shallow-cable theory above (``tension`` and ``chordwise_inertia``
        apply); "exact": linearised about the true catenary, no shallow-cable approximation
        (:class:`dynstiff.cable.exact.ExactCable`, theory.md §11), discretised for the
        largest |omega| asked.
    guard_rtol : float or None
        The closed form's guard (theory.md §11.5): a :class:`ClosedFormWarning` when the cable
        is slack, its axial modes are in the band asked, or its clamped frequencies in the
        band are further than this from the exact model's. None: no check.

    Returns
    -------
    ndarray, shape (n_omega, 3, 3) or (n_omega, 6, 6) [N/m]
        Force applied to the cable end(s) per unit displacement: K_glob = R K_loc R^T with
        R = [e_u e_v e_w]. Real when the cable is undamped, complex otherwise.
        Symmetric (complex-symmetric with damping). Entries grow without bound at the
        poles, the clamped-clamped natural frequencies of the cable.

    Raises
    ------
    InvalidParameterError
        ``omega`` negative or not finite, or ``ends`` / ``tension`` unknown.
    """
    if ends not in ("end", "both"):
        raise InvalidParameterError(f"ends must be 'end' or 'both', got {ends!r}")
    omega = omega_array(omega)
    if _cable_model(model) == "exact":
        band = max(float(np.max(omega, initial=0.0)), _lowest_string_omega(state))
        return ExactCable(state, band).dynamic_stiffness(omega, ends)
    p = chord_parameters(state, tension)
    check_frequency_range(p, omega)
    _guard_cable(state, float(np.max(omega, initial=0.0)), tension, guard_rtol)
    dyads = dyad_basis(p.rotation)
    n = omega.size
    coef = block_coefficients(p, omega, chordwise_inertia, blocks=ends)
    if ends == "end":
        return _real_if_undamped(p, (coef["BB"] @ dyads).reshape(n, 3, 3), omega)
    K_AB = (coef["AB"] @ dyads).reshape(n, 3, 3)
    K = np.empty((n, 6, 6), dtype=K_AB.dtype)
    K[:, :3, :3] = (coef["AA"] @ dyads).reshape(n, 3, 3)
    K[:, 3:, 3:] = (coef["BB"] @ dyads).reshape(n, 3, 3)
    K[:, :3, 3:] = K_AB
    K[:, 3:, :3] = K_AB.transpose(0, 2, 1)
    return _real_if_undamped(p, K, omega)


#: Local dyads (i, j) of the basis used by :func:`dyad_basis`: uu, uv, vu, vv, ww.
DYAD_PAIRS = ((0, 0), (0, 1), (1, 0), (1, 1), (2, 2))


def dyad_basis(rotation):
    """Global dyads e_i e_j^T of the local pairs ``DYAD_PAIRS``, shape (5, 9).

    Every 3x3 block of the cable DSM is a combination of these five dyads, so R K R^T is
    one (n_omega, 5) @ (5, 9) product.
    """
    R = rotation
    return np.stack([np.outer(R[:, i], R[:, j]).ravel() for i, j in DYAD_PAIRS])


def _end_block(entries, axis):
    """Dyad coefficients (uu, uv, vu, vv, ww) of K_B from :func:`local_entries`, stacked
    on a new ``axis`` (theory.md §3.4): k_uu + 2 m_axial, -k_uv, -k_uv, k_vv, kw_s."""
    k_uu, k_uv, k_vv, _, kw_s, _, m_ax = entries
    return np.stack([k_uu + 2.0 * m_ax, -k_uv, -k_uv, k_vv, kw_s + 0.0 * k_uu], axis=axis)


def end_block_coefficients(params, omega, chordwise_inertia=DEFAULT_CHORDWISE_INERTIA):
    """Dyad coefficients of the clamped-A end matrix K_B of one or several cables.

    Parameters
    ----------
    params : ChordParameters
        One cable, or several stacked by :func:`stack_parameters` ((n_cables,) fields).
    omega : ndarray, shape (n_omega,)
        [rad/s], validated; real or complex (the kernel is analytic in omega).
    chordwise_inertia : bool

    Returns
    -------
    ndarray, shape (n_omega, 5) for one cable or (n_omega, n_cables, 5) for a stack [N/m]
        Coefficients of the dyads :func:`dyad_basis` (``DYAD_PAIRS`` order); complex where
        a cable is damped or omega is complex.
    """
    om = omega if np.ndim(params.L) == 0 else omega[:, None]
    return _end_block(local_entries(params, om, chordwise_inertia), axis=-1)


def end_block_coefficients_and_count(params, omega,
                                     chordwise_inertia=DEFAULT_CHORDWISE_INERTIA):
    """:func:`end_block_coefficients` of undamped cables at real omega together with their
    clamped-clamped mode counts J0 (:func:`cable_mode_count`), from one evaluation of the psi
    functions (what a Wittrick-Williams count needs, theory.md §5, §14.2).

    Returns
    -------
    coefficients : ndarray, shape as :func:`end_block_coefficients`, real
    J0 : ndarray of int, shape (n_omega,) for one cable or (n_omega, n_cables) for a stack
    """
    if np.any(params.c > 0) or np.iscomplexobj(params.EA) or np.iscomplexobj(omega):
        raise InvalidParameterError("end_block_coefficients_and_count needs undamped cables "
                                    "at real omega")
    om = omega if np.ndim(params.L) == 0 else omega[:, None]
    psi = np.asarray(params.psi(om))
    functions = _psi_functions(psi)
    coef = _end_block(_entries_from(params, om, psi, functions, chordwise_inertia), axis=-1)
    return np.real(coef), _mode_count_psi(psi, functions[0], functions[3], params.lambda_sq)


def block_coefficients(params, omega, chordwise_inertia=DEFAULT_CHORDWISE_INERTIA,
                       blocks="end"):
    """Coefficients of the DSM blocks on the dyad basis, each shape (n_omega, 5).

    Parameters
    ----------
    params : ChordParameters
    omega : ndarray, shape (n_omega,)
        [rad/s], validated; may be complex (the kernel is analytic in omega), which is how
        damped natural frequencies are found.
    blocks : {"end", "both"}
        "end": only "BB" (the clamped-A end matrix); "both": "AA", "AB", "BB".

    Returns
    -------
    dict of str -> ndarray, shape (n_omega, 5), real if undamped
    """
    entries = local_entries(params, omega, chordwise_inertia)
    out = {"BB": _end_block(entries, axis=1)}
    if blocks == "both":
        k_uu, k_uv, k_vv, k_vv_AB, kw_s, kw_c, m_ax = entries
        zero = np.zeros_like(k_uu)
        k_axial = k_uu + 2.0 * m_ax
        out["AA"] = np.stack([k_axial, k_uv, k_uv, k_vv, kw_s + zero], axis=1)
        out["AB"] = np.stack([-k_uu + m_ax, k_uv, -k_uv, k_vv_AB, kw_c + zero], axis=1)
    return {k: _real_if_undamped(params, v, omega) for k, v in out.items()}


# --------------------------------------------------------------------------- fixed-end modes
def cable_mode_count(state, omega, tension="mean"):
    """Wittrick-Williams J0: number of clamped-clamped cable frequencies strictly below omega.

    J0 = #{n pi < Omega} + #{2 n pi < Omega} + N_sym, N_sym = 0 if k = 0, else
    (k - 1) + [g(psi) > 0], k = floor(psi/pi + 1/2), psi = Omega/2 (theory.md §5.2), where
    g(psi) = tan psi - psi + 4 psi^3/lambda^2 > 0 is evaluated without division as
    (4 cos psi - lambda^2 E(psi)) cos psi > 0 together with cos psi having the sign
    (-1)^k of branch k (at a branch end, where rounding may give cos psi the wrong sign,
    g -> -inf and the root of that branch is not yet passed). The chordwise-inertia
    correction adds no clamped-clamped mode.

    Parameters
    ----------
    state : CatenaryState
    omega : float or array_like, shape (n_omega,)
        Angular frequencies [rad/s].

    Returns
    -------
    ndarray of int, shape (n_omega,)
    """
    omega = omega_array(omega)
    p = chord_parameters(state, tension)
    check_frequency_range(p, omega)
    return mode_count_nondimensional(omega * p.L * np.sqrt(p.m / p.T), p.lambda_sq)


def mode_count_nondimensional(Omega, lambda_sq):
    """J0 as a function of the nondimensional frequency Omega >= 0 (see cable_mode_count)."""
    psi = 0.5 * Omega
    c, _, _, E, _, _ = _psi_functions(psi)
    return _mode_count_psi(psi, c, E, lambda_sq)


def _mode_count_psi(psi, c, E, lambda_sq):
    """J0 from psi = Omega / 2 and its cos psi and E(psi) (see cable_mode_count)."""
    Omega = 2.0 * psi
    k = np.floor(psi / np.pi + 0.5).astype(int)
    on_branch = c * np.where(k % 2 == 0, 1.0, -1.0) > 0
    upper = (((4.0 * c - lambda_sq * E) * c > 0) & on_branch).astype(int)
    n_sym = np.where(k == 0, 0, k - 1 + upper)
    return _count_multiples_below(Omega, np.pi) + _count_multiples_below(Omega, 2 * np.pi) + n_sym


def _count_multiples_below(x, step):
    """#{n >= 1 : n * step < x}, with ties decided in the same float arithmetic as n * step."""
    n = np.maximum(np.ceil(x / step).astype(int) - 1, 0)
    n = n - ((n >= 1) & (n * step >= x))    # x / step rounded up past an integer
    return n + ((n + 1) * step < x)         # x / step rounded down below one


def irvine_symmetric_roots(lambda_sq, n_roots):
    """First ``n_roots`` roots Omega of the Irvine-Caughey symmetric equation.

    tan(Omega/2) = Omega/2 - (4/lambda^2)(Omega/2)^3, solved as 4 cos psi - lambda^2 E(psi) = 0,
    psi = Omega/2, with exactly one root in each ((2k-1) pi/2, (2k+1) pi/2) (theory.md §2.2),
    by Brent's method to machine precision. lambda_sq = 0 gives the taut string (2k-1) pi.

    Returns
    -------
    ndarray, shape (n_roots,)
    """
    from scipy.optimize import brentq

    lam2 = float(lambda_sq)
    if not np.isfinite(lam2) or lam2 < 0:
        raise InvalidParameterError(f"lambda_sq must be finite and >= 0, got {lambda_sq!r}")
    out = np.empty(int(n_roots))
    for k in range(1, int(n_roots) + 1):
        lo, hi = (2 * k - 1) * np.pi / 2, (2 * k + 1) * np.pi / 2
        if lam2 == 0.0:
            out[k - 1] = 2 * lo
            continue
        # high branches: the root sits delta ~ lambda^2 / (4 psi^3) above the branch start,
        # where 4 cos(psi) is below its own rounding (ulp(psi)); tan(lo + delta) = -1/delta
        # + O(delta) then gives delta to O(delta^2), below the ulp of psi
        delta = lam2 / (4.0 * lo**3)
        if delta < 1e-8:
            out[k - 1] = 2.0 * (lo + delta)
            continue

        def f(x):
            c, _, _, E, _, _ = _psi_functions(np.array([x]))
            return float(4.0 * c[0] - lam2 * E[0])

        out[k - 1] = 2.0 * brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=500)
    return out


@dataclass(frozen=True)
class CableModes:
    """Clamped-clamped natural frequencies of one cable.

    Attributes
    ----------
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz], ascending.
    Omega : ndarray, shape (n,)
        Nondimensional frequencies omega L sqrt(m/T) [-].
    family : tuple of str
        "out-of-plane", "in-plane antisymmetric" or "in-plane symmetric" (closed form);
        "out-of-plane", "in-plane" or "axial" (exact model).
    order : ndarray of int, shape (n,)
        Index of the mode within its family, from 1.
    """

    freq_hz: np.ndarray
    Omega: np.ndarray
    family: tuple
    order: np.ndarray

    @property
    def labels(self):
        """Labels such as "in-plane symmetric 1"."""
        return tuple(f"{f} {k}" for f, k in zip(self.family, self.order))

    def __len__(self):
        return len(self.freq_hz)

    def __repr__(self):
        f = self.freq_hz
        span = f"{f.min():.4g}-{f.max():.4g} Hz" if len(f) else "none"
        return f"CableModes({len(self)} modes {span}: {', '.join(self.labels[:3])}, ...)"

    def plot(self, ax=None):
        """The frequencies by family: :func:`dynstiff.plot.plot_cable_modes`. Returns the
        matplotlib Figure."""
        from dynstiff.plot import plot_cable_modes
        return plot_cable_modes(self, ax=ax)

    def to_frame(self):
        """pandas DataFrame with columns freq [Hz], Omega [-], family, order."""
        import pandas as pd
        return pd.DataFrame({"freq [Hz]": self.freq_hz, "Omega [-]": self.Omega,
                             "family": list(self.family), "order": self.order})


#: Cable models of the cable-level functions.
CABLE_MODELS = ("closed-form", "exact")


def _cable_model(model):
    if model not in CABLE_MODELS:
        raise InvalidParameterError(f"model must be one of {CABLE_MODELS}, got {model!r}")
    return model


def _lowest_string_omega(state):
    """pi sqrt(T_mean / m) / L0 [rad/s]: the first taut-string frequency, a floor for the band
    of an exact cable asked for low frequencies only."""
    return np.pi * np.sqrt(state.mean_tension / state.cable.mass_per_length) \
        / state.unstretched_length


def _exact_modes(state, n):
    """First n clamped modes of the exact cable (theory.md §11), band grown until it holds
    them; returns (omega_j [rad/s], family)."""
    w = 1.2 * (n + 1) * _lowest_string_omega(state)
    for _ in range(60):
        cab = ExactCable(state, w)
        lam = cab.eigenvalues
        if np.count_nonzero(lam <= w * w) >= n:
            return np.sqrt(lam[:n]), cab.family[:n]
        w *= 1.5
    raise InvalidParameterError(f"n_modes = {n} is more than the exact cable resolves")


def cable_natural_frequencies(state, n_modes, tension="mean", model="closed-form",
                              guard_rtol=DEFAULT_GUARD_RTOL):
    """First ``n_modes`` clamped-clamped natural frequencies of the cable, labelled.

    "closed-form": out-of-plane Omega = n pi, in-plane antisymmetric Omega = 2 n pi, in-plane
    symmetric the Irvine-Caughey roots (theory.md §2.2, inclined-cable approximation).
    "exact": the clamped spectrum about the true catenary (theory.md §11), families
    "out-of-plane", "in-plane" and "axial" (in-plane, most of its strain energy axial). These
    are the poles of :func:`cable_dynamic_stiffness` of the same ``model``.

    Parameters
    ----------
    state : CatenaryState
    n_modes : int
        Number of modes, >= 1.
    tension : {"mean", "chord"}
        Tension of the closed form; Omega is always omega L sqrt(m / T) with this T.
    model : {"closed-form", "exact"}
    guard_rtol : float or None
        As :func:`cable_dynamic_stiffness` (closed form only).

    Returns
    -------
    CableModes
    """
    if isinstance(n_modes, bool) or not isinstance(n_modes, Integral) or n_modes < 1:
        raise InvalidParameterError(f"n_modes must be an integer >= 1, got {n_modes!r}")
    n = int(n_modes)
    p = chord_parameters(state, tension)
    to_hz = np.sqrt(p.T / p.m) / (2 * np.pi * p.L)
    if _cable_model(model) == "exact":
        w, fam = _exact_modes(state, n)
        order = np.zeros(n, dtype=int)
        for name in set(fam):
            sel = np.array([f == name for f in fam])
            order[sel] = np.arange(1, sel.sum() + 1)
        f = w / (2 * np.pi)
        return CableModes(freq_hz=f, Omega=f / to_hz, family=tuple(str(x) for x in fam),
                          order=order)
    k = np.arange(1, n + 1)
    Om = np.concatenate([k * np.pi, 2 * k * np.pi, irvine_symmetric_roots(p.lambda_sq, n)])
    if guard_rtol is not None:
        top = np.sort(Om)[n - 1] * np.sqrt(p.T / p.m) / p.L
        _guard_cable(state, top, tension, guard_rtol)
    fam = (["out-of-plane"] * n + ["in-plane antisymmetric"] * n
           + ["in-plane symmetric"] * n)
    order = np.concatenate([k, k, k])
    idx = np.argsort(Om, kind="stable")[:n]
    return CableModes(freq_hz=Om[idx] * to_hz, Omega=Om[idx],
                      family=tuple(fam[i] for i in idx), order=order[idx])


# --------------------------------------------------------------------------- guard
#: The closed form warns when the band reaches this fraction of a cable's first axial
#: frequency sqrt(EA/m) / (2 L0) (it has no axial modes).
AXIAL_MARGIN = 0.9
#: Lowest-to-highest tension ratio below which a cable is called slack.
SLACK_RATIO = 0.1


@dataclass(frozen=True)
class ClosedFormValidity:
    """The closed form's estimated relative error for one cable and its causes (theory.md
    §11.5): an envelope of the error of its clamped frequencies against the exact model,
    measured on 150 random cables (the largest ratio of measured to estimated error was
    0.83). It is not an envelope of the static end stiffness, whose error in the soft
    in-plane direction can exceed it 2.4x at 30-60 degrees; the robot model measures that
    part exactly (:meth:`dynstiff.models.dsm.FrequencyModel.static_error`).

    Attributes
    ----------
    error : float
        Estimated relative error [-]; inf when the closed form misses modes or does not
        apply (slack cable).
    causes : dict
        Cause -> its estimate [-]: "sag" 15 delta^2 (delta = d/L), "chordwise weight"
        2 delta eps (1 + 40 eps) (eps = W |sin theta| / T), "tension variation" 0.4 v^2
        (v = (T_max - T_min) / T_mean), "slack" (inf when T_min < 0.1 T_max), "axial" (inf
        when the band reaches 0.9 of the first axial frequency sqrt(EA/m) / (2 L0)).
    values : dict
        delta, eps, v, T_min / T_max and the first axial frequency [Hz].
    """

    error: float
    causes: dict
    values: dict

    def reasons(self, rtol):
        """Causes whose estimate exceeds ``rtol``, as readable text."""
        v = self.values
        text = {"sag": f"sag d/L = {v['sag_ratio']:.3g}",
                "chordwise weight": f"chordwise weight W sin(theta)/T = {v['weight_ratio']:.3g}",
                "tension variation": f"tension varies by {v['tension_variation']:.3g} of its "
                                     f"mean along the cable",
                "slack": f"slack (lowest tension {v['tension_ratio']:.3g} of the highest)",
                "axial": f"axial modes from {v['axial_hz']:.4g} Hz are in the band"}
        return [text[k] for k, e in self.causes.items() if e > rtol]


def closed_form_validity(state, omega_max=0.0, tension="mean", params=None):
    """How far the closed form can be trusted for this cable up to omega_max [rad/s]
    (theory.md §11.5); omega_max decides whether axial modes enter the band. ``params``:
    ``chord_parameters(state, tension)`` when the caller has it already.

    Returns
    -------
    ClosedFormValidity
    """
    p = chord_parameters(state, tension) if params is None else params
    delta = p.sag / p.L
    eps = state.total_weight * abs(state.chord[2]) / state.chord_length / p.T
    t_min, t_max = state.min_tension, state.max_tension
    v = (t_max - t_min) / state.mean_tension
    ratio = t_min / t_max
    cab = state.cable
    f_ax = np.sqrt(cab.EA / cab.mass_per_length) / (2.0 * state.unstretched_length)
    causes = {"sag": 15 * delta**2, "chordwise weight": 2 * delta * eps * (1 + 40 * eps),
              "tension variation": 0.4 * v**2,
              "slack": np.inf if ratio < SLACK_RATIO else 0.0,
              "axial": np.inf if omega_max >= AXIAL_MARGIN * 2 * np.pi * f_ax else 0.0}
    values = {"sag_ratio": delta, "weight_ratio": eps, "tension_variation": v,
              "tension_ratio": ratio, "axial_hz": f_ax}
    err = causes["sag"] + causes["chordwise weight"] + causes["tension variation"]
    err = max(err, causes["slack"], causes["axial"])
    return ClosedFormValidity(error=float(err), causes=causes, values=values)


def _guard_cable(state, omega_max, tension, guard_rtol):
    """Warn (ClosedFormWarning) when the closed form is used outside its range for one cable
    up to omega_max [rad/s]: slack, axial modes in the band, or a measured error of its
    clamped frequencies above guard_rtol where the envelope exceeds it (theory.md §11.5)."""
    if guard_rtol is None:
        return
    if not (isinstance(guard_rtol, (int, float)) and not isinstance(guard_rtol, bool)
            and 0 < guard_rtol < np.inf):
        raise InvalidParameterError(f"guard_rtol must be a number > 0 or None, got "
                                    f"{guard_rtol!r}")
    v = closed_form_validity(state, omega_max, tension)
    if v.error <= guard_rtol:
        return
    if np.isfinite(v.error):
        err = closed_form_local_error(state, omega_max, tension)
        if err <= guard_rtol:
            return
        what = f"its clamped frequencies are {err:.2g} off the exact model's"
    else:
        what = "it is outside the closed form's range"
    import warnings
    cause = "slack" if np.isinf(v.causes["slack"]) else (
        "axial" if np.isinf(v.causes["axial"]) else "local")
    warnings.warn(ClosedFormWarning(
        f"{what} (" + "; ".join(v.reasons(0.1 * guard_rtol)) + "): use model='exact'",
        cable=None, cause=cause), stacklevel=user_stacklevel())


def closed_form_local_error(state, omega_max, tension="mean"):
    """Measured relative error of the closed form's clamped-cable frequencies against the
    exact model (theory.md §11.5), over the modes below max(omega_max, 8 omega_1) [rad/s]
    (omega_1 the first taut-string frequency); the exact model's axial modes are left out
    (the guard reports them as missing). Returns the largest |f_closed / f_exact - 1| [-]."""
    p = chord_parameters(state, tension)
    w1 = np.pi * np.sqrt(p.T / p.m) / p.L
    band = max(float(omega_max), 8.0 * w1)
    cab = ExactCable(state, band)
    sel = (cab.eigenvalues <= band**2) & (np.array(cab.family) != "axial")
    f_ex = np.sqrt(cab.eigenvalues[sel])
    n = f_ex.size
    if n == 0:
        return 0.0
    f_cf = 2 * np.pi * cable_natural_frequencies(state, n, tension, guard_rtol=None).freq_hz
    return float(np.max(np.abs(f_cf / f_ex - 1.0)))


# --------------------------------------------------------------------------- fields
def cable_field(p, omega, d_local, x):
    """Closed-form displacement (u, v, w) [m] along the chord at positions x [m], shape
    (len(x), 3), for the end-B motion d_local = (u_B, v_B, w_B) [m, chord frame] at omega
    [rad/s] with A clamped (theory.md §5.3); ``p`` the cable's :class:`ChordParameters`:
    v = C1 cos(beta x) + C2 sin(beta x) + q h / (T beta)^2, w = w_B sin(beta x)/sin(beta L),
    u = u_B x / L (quasi-static stretching)."""
    uB, vB, wB = d_local
    k_uu, k_uv, *_ = local_entries(p, np.array([omega]), False)
    h = k_uu[0] * uB - k_uv[0] * vB                   # dynamic tension [N]
    beta = 2.0 * p.psi(np.array([omega]))[0] / p.L
    Om = beta * p.L
    vp = h * p.q / (p.T * beta) ** 2
    C2 = (vB - vp + vp * np.cos(Om)) / np.sin(Om)
    v = -vp * np.cos(beta * x) + C2 * np.sin(beta * x) + vp
    w = wB * np.sin(beta * x) / np.sin(Om)
    return np.column_stack([uB * x / p.L, v, w])


@functools.lru_cache(maxsize=8)
def _gauss(n):
    """Gauss-Legendre nodes and weights on [-1, 1] (cached)."""
    return np.polynomial.legendre.leggauss(n)


def cable_kinetic_energy(p, omega, d_local, chordwise_inertia, n_gauss=64):
    """Kinetic energy per unit omega^2 / 2 of the closed-form field, int m (|v|^2 + |w|^2) dx
    (+ m L/3 |u_B|^2 with ``chordwise_inertia``) [kg m^2 per unit amplitude^2], by
    ``n_gauss``-point Gauss-Legendre quadrature (theory.md §6)."""
    x, wts = _gauss(n_gauss)
    x = 0.5 * p.L * (x + 1.0)
    wts = 0.5 * p.L * wts
    f = cable_field(p, omega, d_local, x)
    E = p.m * np.sum(wts * (np.abs(f[:, 1]) ** 2 + np.abs(f[:, 2]) ** 2))
    if chordwise_inertia:
        E += p.m * p.L / 3.0 * abs(d_local[0]) ** 2
    return float(E)
