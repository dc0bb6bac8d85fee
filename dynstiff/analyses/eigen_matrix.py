"""Modes of a discrete rung: the finite eigenproblem K phi = omega^2 M phi.

For models with ``matrices()`` ("spring", "catenary", "lumped"; :mod:`dynstiff.models.base`):
dense ``eigh`` for small models, sparse shift-invert Lanczos otherwise (theory.md §7.1-§7.2).
Reached through :func:`dynstiff.analyses.eigen.eigenfrequencies` and
:func:`dynstiff.analyses.modes.modes`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.errors import ConvergenceError, InvalidParameterError
from dynstiff.results import LumpedModalResult, ModalResult

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.models.base import PlatformModel

__all__ = ["eig", "eigenfrequencies", "modes", "count_below", "massless_modes",
           "massless_pairing"]

_TWO_PI = 2.0 * np.pi
#: Above this many DOFs the eigenproblem is solved by sparse shift-invert Lanczos.
DENSE_LIMIT = 400
#: Up to this many DOFs an unstable equilibrium (negative eigenvalues, which the sparse
#: shift-invert solve misses) is solved densely; above, it is an error.
UNSTABLE_DENSE_LIMIT = 4000


def _dense(A: Any) -> NDArray[np.float64]:
    import scipy.sparse
    return A.toarray() if scipy.sparse.issparse(A) else np.asarray(A)


def eig(model: PlatformModel, n_modes: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest ``n_modes`` eigenpairs of K phi = omega^2 M phi (K symmetrised).

    Returns
    -------
    lam : ndarray, shape (n_modes,)
        Eigenvalues omega^2 [rad^2/s^2], ascending.
    V : ndarray, shape (n_dof, n_modes)
        Mass-normalised vectors, phi^T M phi = 1.
    """
    import scipy.linalg
    import scipy.sparse.linalg
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or \
            not 1 <= n_modes <= model.n_dof:
        raise InvalidParameterError(
            f"n_modes must be an integer in [1, {model.n_dof}] (the number of DOFs of the "
            f"{model.rung!r} model), got {n_modes!r}")
    K, M = model.matrices()
    K = 0.5 * (K + K.T)
    dense = model.n_dof <= DENSE_LIMIT or n_modes >= model.n_dof // 2
    if not dense:
        # an unstable equilibrium has negative eigenvalues, below the shift: the shift-invert
        # solve would miss them (the inertia of K says how many, M being positive)
        negative = _negative_count(K)
        if negative != 0:
            if model.n_dof > UNSTABLE_DENSE_LIMIT:
                raise ConvergenceError(
                    f"the {model.rung!r} model's stiffness has negative eigenvalues (an "
                    f"unstable equilibrium: {negative} counted, None where its inertia could "
                    f"not be read): the sparse solver would miss them, and {model.n_dof} DOFs "
                    f"are more than the dense solver's {UNSTABLE_DENSE_LIMIT}; use fewer "
                    f"segments")
            dense = True
    if dense:
        return scipy.linalg.eigh(_dense(K), _dense(M), subset_by_index=[0, n_modes - 1])
    # shift-invert about sigma < 0, below every eigenvalue of a stable equilibrium: the
    # eigenvalues nearest sigma are then the lowest ones. min K_kk / M_kk bounds the lowest
    # eigenvalue from above (Rayleigh quotient of a unit vector).
    d = K.diagonal() / M.diagonal()
    sigma = -0.1 * d[d > 0].min() if np.any(d > 0) else -1.0
    lam, V = scipy.sparse.linalg.eigsh(scipy.sparse.csc_matrix(K), k=n_modes,
                                       M=scipy.sparse.csc_matrix(M), sigma=sigma, which="LM")
    order = np.argsort(lam)
    lam, V = lam[order], V[:, order]
    return lam, V / np.sqrt(np.einsum("ij,ij->j", V, M @ V))


def _negative_count(K: Any) -> int | None:
    """Number of negative eigenvalues of the symmetric sparse K (Sylvester's law of inertia:
    the signs of the pivots of P K P^T = L D L^T, a sparse LU with diagonal pivots and a
    symmetric ordering), None where the factorisation is singular or pivots off the
    diagonal (then the caller solves densely)."""
    import scipy.sparse
    import scipy.sparse.linalg
    try:
        lu = scipy.sparse.linalg.splu(scipy.sparse.csc_matrix(K), permc_spec="MMD_AT_PLUS_A",
                                      diag_pivot_thresh=0.0,
                                      options={"SymmetricMode": True})
    except RuntimeError:                       # exactly singular
        return None
    if not np.array_equal(lu.perm_r, lu.perm_c):
        return None
    d = lu.U.diagonal()
    return int(np.sum(d < 0)) if np.all(np.isfinite(d)) and np.all(d != 0) else None


def _to_hz(lam: NDArray[np.float64] | float) -> NDArray[np.float64] | float:
    return np.sign(lam) * np.sqrt(np.abs(lam)) / _TWO_PI


def count_below(model: PlatformModel, omega: float) -> int | None:
    """Number of eigenvalues of (K, M) below omega^2, omega [rad/s], by the Wittrick-Williams
    count of the model's condensed K(omega) (exact for a discrete model: J0 from the chains
    with the platform held, theory.md §5.1, §14.3); None where K(omega) is not finite (omega
    on a held-platform frequency)."""
    w = np.array([float(omega)])
    K = np.real(model.dynamic_stiffness(w))[0]
    if not np.all(np.isfinite(K)):
        return None
    ev = np.linalg.eigvalsh(0.5 * (K + K.T))
    return int(model.cable_mode_count(w)[0] + np.sum(ev < 0))


def _lowest(model: PlatformModel, n_modes: int | None,
            fmax_hz: float | None) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """Eigenpairs (lam, V) of the request: the lowest ``n_modes``, or all below ``fmax_hz``
    (the first ``n_modes`` of them if both). For a band, the number of modes in it is counted
    first (:func:`count_below`) and one eigen solve asks for exactly that many; where the
    count is unavailable or disagrees, the solve is repeated with a doubled count."""
    if fmax_hz is None:
        return eig(model, n_modes)
    n = count_below(model, _TWO_PI * fmax_hz)
    if n is not None:
        n = n if n_modes is None else min(n, n_modes)
        if n == 0:
            return np.zeros(0), np.zeros((model.n_dof, 0))
        lam, V = eig(model, min(n, model.n_dof))
        if _to_hz(lam[-1]) < fmax_hz:
            return lam, V
    n = 12 if n_modes is None else n_modes
    while True:                      # grow the count until the band is covered
        lam, V = eig(model, min(n, model.n_dof))
        f = _to_hz(lam)
        if n >= model.n_dof or f[-1] >= fmax_hz:
            k = int(np.sum(f < fmax_hz))
            k = k if n_modes is None else min(k, n_modes)
            return lam[:k], V[:, :k]
        n *= 2


def eigenfrequencies(model: PlatformModel, n_modes: int | None = None,
                     fmax_hz: float | None = None) -> NDArray[np.float64]:
    """Lowest natural frequencies [Hz], ascending (validated request, see
    :func:`dynstiff.analyses.eigen.eigenfrequencies`); an unstable equilibrium's negative eigenvalue
    lambda is reported as -sqrt(-lambda) / 2 pi."""
    return _to_hz(_lowest(model, n_modes, fmax_hz)[0])


def modes(model: PlatformModel, n_modes: int | None = None,
          fmax_hz: float | None = None) -> ModalResult:
    """Modes with platform shapes, cable kinetic-energy fractions and labels.

    Kinetic energies per unit omega^2 / 2: platform x^T M_p x (rigid body alone), cables
    ``model.cable_energies(V)`` (for the lumped rung: m l0 |phi_j|^2 over the interior nodes
    plus (m l0 / 2) |J_i x|^2 at B_i). A mode is "global" when the cables hold less than
    half of the kinetic energy. ``massless_freq_hz`` of a global mode is the frequency of
    the mode of the massless-cable stiffness (``model.massless_stiffness()``, the cable
    nodes condensed statically) with the largest mass-weighted MAC.

    Returns
    -------
    ModalResult, or LumpedModalResult (with ``node_shapes``) where the model has nodes.
        Platform shapes (n, 6), held DOFs 0, normalised to x^T M_p x = 1 (0 if the
        platform does not move at all).
    """
    lam, V = _lowest(model, n_modes, fmax_hz)
    n = lam.size
    nf, fi = model.n_free, model.free_index
    freq = _to_hz(lam)
    Mp = model.platform_mass
    X = V[:nf]                                               # (nf, n)
    E_p = np.einsum("in,ij,jn->n", X, Mp, X)
    E_cab = model.cable_energies(V)
    total = E_p + E_cab.sum(axis=1)
    frac = E_cab.sum(axis=1) / total
    moving = E_p > 1e-24 * total
    shapes = np.zeros((n, 6))
    shapes[np.ix_(moving, fi)] = (X[:, moving] / np.sqrt(E_p[moving])).T
    M6 = np.zeros((6, 6))            # the platform block of the model's mass (participation)
    M6[np.ix_(fi, fi)] = _dense(model.matrices()[1][:nf, :nf])
    fields = dict(freq_hz=freq, platform_shapes=shapes, cable_energy_fraction=frac,
                  cable_energy=E_cab / total[:, None], platform_mass=M6)
    fields["massless_freq_hz"] = massless_pairing(ModalResult(**fields),
                                                  model.massless_stiffness(), Mp, fi)
    if not hasattr(model, "node_shapes"):
        return ModalResult(**fields)
    node_shapes = model.node_shapes(V)
    for a in node_shapes:
        a.setflags(write=False)
    return LumpedModalResult(**fields, node_shapes=node_shapes)


def massless_modes(model: PlatformModel) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The modes of the massless-cable model on the free DOFs: (lam, X) of the generalized
    problem (K0, M_p) (:func:`scipy.linalg.eigh`, K0 = ``model.massless_stiffness()``
    symmetrised, M_p = ``model.platform_mass``), eigenvalues lam = omega^2 [1/s^2] ascending
    and M_p-orthonormal shapes X (n_free, n_free), read-only. Computed once per model where
    the model keeps a memo (the closed form), since the platform-mode search, its seed grid
    and the massless pairing all ask for them.

    Examples
    --------
    >>> import dynstiff as ds
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> lam, X = massless_modes(m)
    >>> print(f"{lam[0] ** 0.5 / (2 * 3.141592653589793):.4f} Hz", X.shape)
    2.2172 Hz (6, 6)
    """
    import scipy.linalg
    memo = getattr(model, "_memo", None)
    if memo is not None and "massless_modes" in memo:
        return memo["massless_modes"]
    K0 = model.massless_stiffness()
    lam, X = scipy.linalg.eigh(0.5 * (K0 + K0.T), model.platform_mass)
    lam.setflags(write=False)
    X.setflags(write=False)
    if memo is not None:
        memo["massless_modes"] = (lam, X)
    return lam, X


def massless_pairing(modes: ModalResult, K0: NDArray[np.float64], Mp: NDArray[np.float64],
                     free_index: NDArray[np.int64],
                     massless: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
                     ) -> NDArray[np.float64]:
    """The frequency [Hz] of the massless-cable mode each mode of ``modes`` continues, NaN
    for the modes that continue none: a one-to-one assignment (Hungarian) that maximises the
    summed participation of the pairs, the participation of mode k in massless mode j being
    its effective-mass fraction MAC_kj s_k = (x_k^T M_p X0_j)^2 s_k (unit-energy shapes, s
    the platform share; over all modes it sums to 1 for each j); a pair is kept from 0.1.

    Parameters
    ----------
    modes : ModalResult
    K0 : ndarray, shape (nf, nf)
        The massless-cable stiffness on the free DOFs [N/m, N, N m].
    Mp : ndarray, shape (nf, nf)
        The platform mass on the free DOFs.
    free_index : ndarray of int
    massless : (lam, X), optional
        The massless modes of (K0, Mp) where already computed (:func:`massless_modes`).
    """
    import scipy.linalg
    from scipy.optimize import linear_sum_assignment
    out = np.full(len(modes), np.nan)
    if not len(modes):
        return out
    lam0, X0 = (scipy.linalg.eigh(0.5 * (K0 + K0.T), Mp) if massless is None
                else massless)
    X = np.asarray(modes.platform_shapes)[:, free_index]
    score = (X @ Mp @ X0) ** 2 * np.asarray(modes.platform_share)[:, None]
    rows, cols = linear_sum_assignment(-score)
    keep = score[rows, cols] >= 0.1
    out[rows[keep]] = _to_hz(lam0)[cols[keep]]
    return out
