"""Linear analysis of the lumped-mass robot about its equilibrium (theory.md §7.1-§7.2):
eigenfrequencies, modes with cable energy fractions and global/local labels, the static
stiffness with the cable nodes condensed out, and FRFs by direct sparse solves.

The functions take a :class:`~dynstiff.lumped.LumpedMassModel` and are its methods of the
same names; notation as :mod:`dynstiff.lumped.robot_model`.
"""

import warnings
from dataclasses import dataclass
from numbers import Integral

import numpy as np
import scipy.linalg
import scipy.sparse.linalg

from .._validate import omega_array
from ..eigen import ModalResult
from ..errors import InvalidParameterError, PoleWarning
from ..frf import _KINDS, FRFResult, channel_maps
from ..platform import lever_map, platform_mass_matrix

__all__ = ["LumpedModalResult", "eigenfrequencies", "modes", "static_stiffness", "frf"]

_TWO_PI = 2.0 * np.pi
#: Above this many DOFs the eigenproblem is solved by sparse shift-invert Lanczos.
_DENSE_LIMIT = 400


@dataclass(frozen=True)
class LumpedModalResult(ModalResult):
    """Modes of the lumped-mass robot: a :class:`~dynstiff.ModalResult` plus node motions.

    Attributes
    ----------
    node_shapes : list of ndarray, shape (n_modes, N_i + 1, 3)
        Displacement of every node of cable i [m] (anchor 0, the last node moves with the
        platform), for the mode vector normalised to unit total kinetic energy
        phi^T M phi = 1 (not the platform normalisation of ``platform_shapes``).

    Notes
    -----
    ``platform_shapes`` are normalised to x^T M_p x = 1 with M_p the rigid platform alone,
    like the closed-form model; ``massless_freq_hz`` comes from the lumped cables condensed
    statically onto the platform (their massless limit).
    """

    node_shapes: list = None


def eig(model, n_modes):
    """Lowest n_modes eigenpairs of K phi = omega^2 M phi at the model's equilibrium:
    (lambda [rad^2/s^2] ascending, mass-normalised vectors (n_dof, n_modes), K symmetrised,
    M), both sparse; dense ``eigh`` for small models, shift-invert Lanczos otherwise."""
    if isinstance(n_modes, bool) or not isinstance(n_modes, Integral) or \
            not 1 <= n_modes <= model.n_dof:
        raise InvalidParameterError(
            f"n_modes must be an integer in [1, {model.n_dof}] (the number of DOFs), got "
            f"{n_modes!r}")
    K, M = model.matrices()
    K = 0.5 * (K + K.T)
    if model.n_dof <= _DENSE_LIMIT or n_modes >= model.n_dof // 2:
        lam, V = scipy.linalg.eigh(K.toarray(), M.toarray(),
                                   subset_by_index=[0, n_modes - 1])
    else:
        # shift-invert about sigma < 0, below every eigenvalue of a stable equilibrium:
        # the eigenvalues nearest sigma are then the lowest ones. min K_kk / M_kk bounds
        # the lowest eigenvalue from above (Rayleigh quotient of a unit vector).
        d = K.diagonal() / M.diagonal()
        sigma = -0.1 * d[d > 0].min() if np.any(d > 0) else -1.0
        lam, V = scipy.sparse.linalg.eigsh(K.tocsc(), k=n_modes, M=M.tocsc(),
                                           sigma=sigma, which="LM")
        order = np.argsort(lam)
        lam, V = lam[order], V[:, order]
        V = V / np.sqrt(np.einsum("ij,ij->j", V, M @ V))
    return lam, V, K, M


def eigenfrequencies(model, n_modes=None, fmax_hz=None):
    """Lowest natural frequencies of K phi = omega^2 M phi [Hz], ascending.

    Sparse shift-invert Lanczos (dense ``eigh`` for small models). An unstable
    equilibrium (negative eigenvalue lambda) is reported as -sqrt(-lambda) / 2 pi.

    Parameters
    ----------
    model : LumpedMassModel
    n_modes : int, optional
        Number of frequencies, 1 <= n_modes <= n_dof.
    fmax_hz : float, optional
        All frequencies below this [Hz] (the first ``n_modes`` of them if both are given).

    Returns
    -------
    ndarray, shape (n,) [Hz]
    """
    if fmax_hz is None:
        if n_modes is None:
            raise InvalidParameterError("give n_modes or fmax_hz")
        lam = eig(model, n_modes)[0]
        return np.sign(lam) * np.sqrt(np.abs(lam)) / _TWO_PI
    n = 12 if n_modes is None else int(n_modes)
    while True:                      # grow the count until the band is covered
        f = eigenfrequencies(model, min(n, model.n_dof))
        if n >= model.n_dof or f[-1] >= fmax_hz:
            f = f[f < fmax_hz]
            return f if n_modes is None else f[:n_modes]
        n *= 2


def modes(model, n_modes):
    """Modes with platform shapes, cable kinetic-energy fractions and labels.

    Kinetic energies per unit omega^2 / 2: platform x^T M_p x (rigid body alone), cable i
    sum of m l0 |phi_j|^2 over its interior nodes plus (m l0 / 2) |J_i x|^2 at B_i. A
    mode is "global" when the cables hold less than half of the kinetic energy (as in
    :func:`dynstiff.eigen.modes`). ``massless_freq_hz`` of a global mode is the frequency
    of the mode of the statically condensed (massless-cable) lumped model with the
    largest mass-weighted MAC.

    Parameters
    ----------
    model : LumpedMassModel
    n_modes : int
        Number of lowest modes.

    Returns
    -------
    LumpedModalResult
        Platform shapes (n, 6), held DOFs 0, normalised to x^T M_p x = 1 (0 if the
        platform does not move at all).
    """
    lam, V, K, _ = eig(model, n_modes)
    freq = np.sign(lam) * np.sqrt(np.abs(lam)) / _TWO_PI
    s = model.state
    nf, fi = model.n_free, model._fi
    rob = model.robot
    Mp = platform_mass_matrix(rob.platform, s.pose.matrix)[np.ix_(fi, fi)]
    X = V[:nf]                                               # (nf, n)
    E_p = np.einsum("in,ij,jn->n", X, Mp, X)
    _, r = rob.attachment_points(s.pose)
    E_cab = np.zeros((n_modes, rob.n_cables))
    node_shapes = []
    for i in range(rob.n_cables):
        o, size = model._offsets[i], 3 * (model.segments[i] - 1)
        U = V[o:o + size].T.reshape(n_modes, -1, 3)
        dB = (lever_map(r[i], fi) @ X).T                    # (n, 3)
        E_cab[:, i] = model._node_mass[i] * (np.sum(U ** 2, axis=(1, 2))
                                            + 0.5 * np.sum(dB ** 2, axis=1))
        node_shapes.append(np.concatenate(
            [np.zeros((n_modes, 1, 3)), U, dB[:, None, :]], axis=1))
    total = E_p + E_cab.sum(axis=1)
    frac = E_cab.sum(axis=1) / total
    moving = E_p > 1e-24 * total
    shapes = np.zeros((n_modes, 6))
    shapes[np.ix_(moving, fi)] = (X[:, moving] / np.sqrt(E_p[moving])).T
    kinds = tuple("global" if f < 0.5 else "local" for f in frac)
    # massless-cable (statically condensed) lumped model, for the shift of global modes
    Kc = condensed(model, K)
    lam0, X0 = scipy.linalg.eigh(Kc, Mp)
    f0 = np.sign(lam0) * np.sqrt(np.abs(lam0)) / _TWO_PI
    f_massless = np.full(n_modes, np.nan)
    for k in np.flatnonzero(np.array(kinds) == "global"):
        x = shapes[k, fi]
        f_massless[k] = f0[int(np.argmax((X0.T @ Mp @ x) ** 2))]
    for a in node_shapes:
        a.setflags(write=False)
    return LumpedModalResult(freq_hz=freq, platform_shapes=shapes,
                             cable_energy_fraction=frac,
                             cable_energy=E_cab / total[:, None], kind=kinds,
                             massless_freq_hz=f_massless, node_shapes=node_shapes)


def condensed(model, K):
    """Static condensation onto the free platform DOFs, K_pp - K_pi K_ii^-1 K_ip."""
    nf = model.n_free
    Kpp = K[:nf, :nf].toarray()
    if model.n_dof == nf:
        return Kpp
    Kip = K[nf:, :nf].toarray()
    sol = scipy.sparse.linalg.splu(K[nf:, nf:].tocsc()).solve(Kip)
    return Kpp - K[:nf, nf:] @ sol


def static_stiffness(model):
    """Static stiffness of the platform (free DOFs), interior nodes condensed out.

    Returns
    -------
    ndarray, shape (n_free, n_free) [N/m, N, N m/rad]
        Comparable with the elastic-catenary ``Equilibrium.static_stiffness()``.
    """
    return condensed(model, model.matrices()[0])


def frf(model, omega, inputs=None, outputs=None, point=None, kind="receptance"):
    """Platform FRFs by a direct sparse solve of (K - omega^2 M + i omega C) X = F.

    Same channels and result as :func:`dynstiff.frf.frf`. Damping as in
    :func:`~dynstiff.lumped.chain_end_dynamic_stiffness`: EA (1 + i eta) in the axial
    term of K, viscous c l0 at every node (c l0 / 2 at B_i), none on the platform.

    Parameters
    ----------
    model : LumpedMassModel
    omega : array_like, shape (n,)
        Angular frequencies [rad/s], >= 0.
    inputs : str or list of str, optional
        Among ``INPUT_NAMES`` (default all six). Loads on held DOFs give no response: in
        the default they are zero columns, named explicitly they raise (as
        :func:`dynstiff.frf.frf`).
    outputs : str or list of str, optional
        Among ``OUTPUT_NAMES`` (default all six).
    point : array_like, shape (3,), optional
        Platform point [m, platform frame] whose translation is output (default P).
    kind : {"receptance", "mobility", "accelerance"}

    Returns
    -------
    FRFResult
        H of shape (n, n_out, n_in).

    Warns
    -----
    PoleWarning
        At a frequency where the dynamic stiffness is exactly singular (entries inf).
    """
    omega = omega_array(omega)
    if kind not in _KINDS:
        raise InvalidParameterError(f"kind must be one of {tuple(_KINDS)}, got {kind!r}")
    s = model.state
    B, out_map, in_names, out_names = channel_maps(model._fi, s.pose.matrix, inputs,
                                                   outputs, point)
    nf = model.n_free
    rob = model.robot
    eta = [cb.loss_factor for cb in rob.cables]
    K = model._tangent(s.pose, s.interior,
                      lambda i: 1.0 + 1j * eta[i] if eta[i] > 0 else 1.0)
    M = model.mass_matrix(s.pose)
    damped = any(cb.viscous_damping > 0 for cb in rob.cables)
    C = model._damping_matrix(s.pose) if damped else None
    F = np.zeros((model.n_dof, B.shape[1]))
    F[:nf] = B
    H = np.empty((omega.size, out_map.shape[0], B.shape[1]), dtype=complex)
    singular = []
    for k, w in enumerate(omega):
        D = K - w * w * M
        if damped:
            D = D + 1j * w * C
        try:
            X = scipy.sparse.linalg.splu(D.tocsc()).solve(F.astype(D.dtype))
        except RuntimeError:
            H[k] = np.inf
            singular.append(k)
            continue
        H[k] = out_map @ X[:nf]
    if singular:
        warnings.warn(
            f"LumpedMassModel.frf: the dynamic stiffness is exactly singular at "
            f"{len(singular)} frequencies (eigenfrequencies, e.g. "
            f"{omega[singular[0]] / _TWO_PI:.9g} Hz): FRF set to inf",
            PoleWarning, stacklevel=2)
    if kind != "receptance":
        H = H * ((1j * omega) ** _KINDS[kind])[:, None, None]
    return FRFResult(freq_hz=omega / _TWO_PI, H=H, inputs=in_names, outputs=out_names,
                     kind=kind)
