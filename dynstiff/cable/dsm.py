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

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import omega_array
from dynstiff.cable.chord import ChordParameters, chord_parameters, stack_parameters
from dynstiff.cable.exact import ExactCable
from dynstiff.cable.guard import DEFAULT_GUARD_RTOL, guard_cable
from dynstiff.cable.psi import PSI_SERIES, check_frequency_range, mode_count_psi, psi_functions
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.cable.catenary import CatenaryState

__all__ = [
    "ChordParameters", "chord_parameters", "stack_parameters", "local_entries",
    "end_block_coefficients", "local_end_stiffness", "local_two_end_stiffness",
    "cable_dynamic_stiffness", "DEFAULT_CHORDWISE_INERTIA",
    "dyad_basis", "block_coefficients", "end_block_coefficients_and_count",
    "static_block_coefficients"
]

#: Default of ``chordwise_inertia`` (see validation/chordwise_inertia.py for the evidence).
DEFAULT_CHORDWISE_INERTIA = True


def local_entries(p: ChordParameters, omega: NDArray[Any],
                  chordwise_inertia: bool) -> tuple[NDArray[Any], ...]:
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
    return _entries_from(p, omega, psi, psi_functions(psi), chordwise_inertia)


def _entries_from(
        p: ChordParameters, omega: NDArray[Any], psi: NDArray[Any],
        functions: tuple[NDArray[Any], NDArray[Any], NDArray[Any], NDArray[Any], NDArray[Any],
                         NDArray[Any]],
        chordwise_inertia: bool,
) -> tuple[NDArray[Any], ...]:
    """:func:`local_entries` from psi and its :func:`psi_functions`."""
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


def _real_if_undamped(p: ChordParameters, K: NDArray[Any], omega: NDArray[Any]) -> NDArray[Any]:
    """Drop the zero imaginary part for an undamped cable at real frequencies."""
    if p.c == 0 and np.isrealobj(p.EA) and np.isrealobj(omega):
        return np.real(K)
    return K


def local_end_stiffness(params: ChordParameters, omega: NDArray[Any],
                        chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA) -> NDArray[Any]:
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


def local_two_end_stiffness(params: ChordParameters, omega: NDArray[Any],
                            chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA) -> NDArray[Any]:
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


def cable_dynamic_stiffness(state: CatenaryState, omega: ArrayLike, ends: str = "end",
                            tension: str = "mean",
                            chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA,
                            model: str = "closed-form",
                            guard_rtol: float | None = DEFAULT_GUARD_RTOL,
                            ) -> NDArray[np.complex128] | NDArray[np.float64]:
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
        The closed form's guard (theory.md §11.5): a
        :class:`~dynstiff.errors.ClosedFormWarning` when the cable is slack, its axial modes
        are in the band asked, or its clamped frequencies in the band are further than this
        from the exact model's. None: no check.

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

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> K = ds.cable_dynamic_stiffness(state, [0.0, 10.0])   # omega [rad/s]
    >>> K.shape
    (2, 3, 3)
    >>> print(f"{K[0, 0, 0]:.1f} N/m")
    203423.5 N/m
    """
    if ends not in ("end", "both"):
        raise InvalidParameterError(f"ends must be 'end' or 'both', got {ends!r}")
    omega = omega_array(omega)
    if checked_cable_model(model) == "exact":
        band = max(float(np.max(omega, initial=0.0)), lowest_string_omega(state))
        return ExactCable(state, band).dynamic_stiffness(omega, ends)
    p = chord_parameters(state, tension)
    check_frequency_range(p, omega)
    guard_cable(state, float(np.max(omega, initial=0.0)), tension, guard_rtol)
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


def dyad_basis(rotation: NDArray[np.float64]) -> NDArray[np.float64]:
    """Global dyads e_i e_j^T of the local pairs ``DYAD_PAIRS``, shape (5, 9).

    Every 3x3 block of the cable DSM is a combination of these five dyads, so R K R^T is
    one (n_omega, 5) @ (5, 9) product.
    """
    R = rotation
    return np.stack([np.outer(R[:, i], R[:, j]).ravel() for i, j in DYAD_PAIRS])


def _end_block(entries: tuple[NDArray[Any], ...], axis: int) -> NDArray[Any]:
    """Dyad coefficients (uu, uv, vu, vv, ww) of K_B from :func:`local_entries`, stacked
    on a new ``axis`` (theory.md §3.4): k_uu + 2 m_axial, -k_uv, -k_uv, k_vv, kw_s."""
    k_uu, k_uv, k_vv, _, kw_s, _, m_ax = entries
    return np.stack([k_uu + 2.0 * m_ax, -k_uv, -k_uv, k_vv, kw_s + 0.0 * k_uu], axis=axis)


def end_block_coefficients(params: ChordParameters, omega: NDArray[Any],
                           chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA) -> NDArray[Any]:
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


def static_block_coefficients(params: ChordParameters) -> NDArray[Any]:
    """:func:`end_block_coefficients` at omega = 0, written out: psi = 0, where
    :func:`psi_functions` give c = cos 2psi = s/psi = 1 and E, P~ their series' constant
    terms (-1/3 and 1/3), so k_uu = 4 K0 / (4 - lambda^2 E(0)) (Irvine's static chord
    stiffness, K0 / (1 + lambda^2 / 12)), k_uv = 0, k_vv = (T/L) (4 + lambda^2 P~(0)) /
    (4 - lambda^2 E(0)) = T/L and the out-of-plane T/L (theory.md §3.5); the chordwise mass
    is zero. The same operations as the general path at psi = 0, so the same numbers.

    Parameters
    ----------
    params : ChordParameters
        One cable, or several stacked by :func:`stack_parameters`.

    Returns
    -------
    ndarray, shape (5,) or (n_cables, 5) [N/m]
        (uu, uv, vu, vv, ww); complex where EA is.

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> p = chord_parameters(ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0],
    ...                                                       300.0, cable))
    >>> bool(np.all(static_block_coefficients(p) == end_block_coefficients(p, np.zeros(1))[0]))
    True
    """
    _, e_coef, p_coef = PSI_SERIES
    # numpy's (complex, where psi is: viscous damping) divisions, as the general path's
    lam2 = np.asarray(params.lambda_sq_complex,
                      dtype=complex if np.any(params.c != 0) else None)
    den = 4.0 - lam2 * e_coef[-1]
    TL = np.asarray(params.T / params.L)
    k_uu = 4.0 * np.asarray(params.K0) / den
    k_vv = TL * (4.0 + lam2 * p_coef[-1]) / den
    zero = 0.0 * k_uu
    return np.stack([k_uu, zero, zero, k_vv, TL + zero], axis=-1)


def end_block_coefficients_and_count(
        params: ChordParameters, omega: NDArray[Any],
        chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA,
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
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
    functions = psi_functions(psi)
    coef = _end_block(_entries_from(params, om, psi, functions, chordwise_inertia), axis=-1)
    return np.real(coef), mode_count_psi(psi, functions[0], functions[3], params.lambda_sq)


def block_coefficients(params: ChordParameters, omega: NDArray[np.float64],
                       chordwise_inertia: bool = DEFAULT_CHORDWISE_INERTIA,
                       blocks: str = "end") -> dict[str, NDArray[Any]]:
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


#: Cable models of the cable-level functions.
CABLE_MODELS = ("closed-form", "exact")


def checked_cable_model(model: str) -> str:
    if model not in CABLE_MODELS:
        raise InvalidParameterError(f"model must be one of {CABLE_MODELS}, got {model!r}")
    return model


def lowest_string_omega(state: CatenaryState) -> float:
    """pi sqrt(T_mean / m) / L0 [rad/s]: the first taut-string frequency, a floor for the band
    of an exact cable asked for low frequencies only."""
    return np.pi * np.sqrt(state.mean_tension / state.cable.mass_per_length) \
        / state.unstretched_length
