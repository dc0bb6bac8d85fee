"""Modes of any model: natural frequencies with platform shapes, cable kinetic energies,
labels by platform share and the pairing with the massless-cable modes (theory.md §5.3, §6),
coincident roots resolved into an energy-orthogonal basis; the cables' displacement fields of
a mode.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import count, index
from dynstiff.analyses import eigen_matrix
from dynstiff.analyses.eigen import checked_method, eigenfrequencies, validated_request
from dynstiff.errors import UnsupportedAnalysisError
from dynstiff.models.base import require_model
from dynstiff.results import ModalResult

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.models.base import PlatformModel
    from dynstiff.models.dsm import FrequencyModel

__all__ = ["cable_fields", "modes"]

_TWO_PI = 2.0 * np.pi


# ------------------------------------------------------------------------- mode shapes
def cable_fields(model: PlatformModel, modes: ModalResult, k: int,
                 n_points: int = 41) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Cable displacement fields of mode ``k`` (platform-moving modes), global frame.

    Parameters
    ----------
    model : model with closed-form cable fields (the "dsm" rung)
    modes : ModalResult
        From :func:`modes` of the same model.
    k : int
        Mode index (0-based).
    n_points : int
        Points per cable, from anchor to attachment.

    Returns
    -------
    positions : ndarray, shape (n_cables, n_points, 3)
        Points on the chords [m].
    displacements : ndarray, shape (n_cables, n_points, 3)
        Mode displacement [m] for the platform shape ``modes.platform_shapes[k]``; zero for a
        purely local mode (platform at rest), whose cable shape is the clamped-clamped one.

    Raises
    ------
    UnsupportedAnalysisError
        The rung has no continuous cable field (massless cables; the lumped rung gives its
        node motions in ``modes(...).node_shapes``).

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> res = ds.modes(m, n_modes=1)
    >>> points, u = ds.cable_fields(m, res, 0, n_points=5)
    >>> points.shape, u.shape
    ((8, 5, 3), (8, 5, 3))
    """
    require_model(model)
    if not hasattr(model, "cable_displacements"):
        raise UnsupportedAnalysisError(
            f"cable_fields needs closed-form cable fields (rung 'dsm'); the {model.rung!r} "
            f"model has none" + (": its node motions are modes(model, ...).node_shapes"
                                 if model.rung == "lumped" else " (massless cables)"))
    k = index("k", k, len(modes.freq_hz))
    return model.cable_displacements(_TWO_PI * modes.freq_hz[k], modes.platform_shapes[k],
                                     count("n_points", n_points, least=2))


def modes(model: PlatformModel, n_modes: int | None = None, fmax_hz: float | None = None,
          method: str = "auto", max_modes: int = 20000) -> ModalResult:
    """Natural frequencies with platform shapes, energy fractions and labels.

    For a discrete rung (``method`` "auto" or "matrix"), the mode vectors of the finite
    eigenproblem (:func:`dynstiff.analyses.eigen_matrix.modes`). Otherwise the platform
    shape at omega_r is the eigenvector of K(omega_r) with the smallest |eigenvalue|; at a
    root that sits on a cable pole with the platform at rest (a purely local mode, counted by
    J0), the platform shape is zero and the mode is all cable. Coincident roots (a symmetric
    robot's double modes, within 1e-8 relative) share the null space of K: their shapes are
    a basis of it, M_p-orthonormal and orthogonal in cable kinetic energy too (so each
    mode's energy and participation is its own, not an arbitrary basis's). Kinetic energies:
    platform x^T M_p x, cables from the rung's ``cable_kinetic_energies`` (closed-form
    fields, theory.md §6). Modes are labelled by platform share
    (:func:`dynstiff.results.mode_kinds`); global modes are paired one-to-one with the
    massless-cable modes by mass-weighted MAC.

    Parameters
    ----------
    model : model of any rung
    n_modes, fmax_hz, max_modes : as :func:`dynstiff.eigenfrequencies`
    method : {"auto", "matrix", "wittrick-williams"}

    Returns
    -------
    ModalResult (LumpedModalResult for the lumped rung, with node motions)

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> res = ds.modes(ds.FrequencyModel(eq), n_modes=3)
    >>> [round(f, 4) for f in res.freq_hz], res.kind
    ([2.2061, 2.3592, 2.9907], ('global', 'global', 'global'))
    """
    n_modes, fmax_hz = validated_request(n_modes, fmax_hz)
    if checked_method(model, method) == "matrix":
        if getattr(model, "n_dof", 0) > max_modes:       # the request fits the limit
            eigenfrequencies(model, n_modes, fmax_hz, method="matrix", max_modes=max_modes)
        return eigen_matrix.modes(model.undamped(), n_modes, fmax_hz)
    if not hasattr(model, "cable_kinetic_energies"):
        raise UnsupportedAnalysisError(
            f"modes by Wittrick-Williams need the cables' kinetic energy of a continuous rung; "
            f"use method='matrix' for the {model.rung!r} model")
    m = model.undamped()
    f = eigenfrequencies(m, n_modes=n_modes, fmax_hz=fmax_hz, method="wittrick-williams",
                         max_modes=max_modes)
    w = _TWO_PI * f
    fi = m.free_index
    nf = m.n_free
    Mf = m.platform_mass
    shapes = np.zeros((len(f), 6))
    E_cab = np.zeros((len(f), m.robot.n_cables))
    K = m.dynamic_stiffness(w) if len(w) else np.zeros((0, nf, nf))
    J0_lo = m.cable_mode_count(w * (1 - 1e-9)) if len(w) else []
    J0_hi = m.cable_mode_count(w * (1 + 1e-9)) if len(w) else []
    scale = np.abs(np.linalg.eigvalsh(m.massless_stiffness())).max()
    # on a cable pole (K not finite) a root is purely local, the platform at rest
    heads = [ks for ks in _clusters(f) if np.all(np.isfinite(K[ks[0]]))]
    eigs = np.linalg.eigh(K[[ks[0] for ks in heads]]) if heads else ((), ())
    for ks, ev, V in zip(heads, *eigs):
        order = np.argsort(np.abs(ev))
        on_pole = J0_hi[ks[-1]] > J0_lo[ks[0]]
        n_move = len(ks)
        if on_pole:                      # only the null directions of K move the platform
            n_move = min(n_move, int(np.sum(np.abs(ev) <= 1e-6 * scale)))
        if n_move == 0:
            continue
        X = _energy_basis(m, w[ks[0]], V[:, order[:n_move]], Mf, fi)
        shapes[np.ix_(ks[:n_move], fi)] = X.T
    moving = np.any(shapes != 0, axis=1)
    if np.any(moving):
        E_cab[moving] = m.cable_kinetic_energies(w[moving], shapes[moving])
    total = 1.0 + E_cab.sum(axis=1)
    frac = np.where(moving, E_cab.sum(axis=1) / total, 1.0)
    E_cab = np.where(moving[:, None], E_cab / total[:, None], 0.0)
    Mp = np.zeros((6, 6))
    Mp[np.ix_(fi, fi)] = Mf
    res = ModalResult(freq_hz=f, platform_shapes=shapes, cable_energy_fraction=frac,
                      cable_energy=E_cab, platform_mass=Mp)
    f0 = eigen_matrix.massless_pairing(res, m.massless_stiffness(), Mf, fi)
    return replace(res, massless_freq_hz=f0)


def _clusters(f: NDArray[np.float64], rtol: float = 1e-8) -> list[list[int]]:
    """Index groups of consecutive coincident frequencies (within ``rtol`` relative)."""
    groups: list[list[int]] = []
    for k in range(len(f)):
        if groups and f[k] - f[groups[-1][-1]] <= rtol * max(abs(f[k]), 1e-300):
            groups[-1].append(k)
        else:
            groups.append([k])
    return groups


def _energy_basis(m: FrequencyModel, omega: float, V: NDArray[np.float64], Mf: NDArray[np.float64],
                  fi: NDArray[np.int64]) -> NDArray[np.float64]:
    """A basis of span(V) (free DOFs, shape (nf, c)), M_p-orthonormal and diagonal in the
    cables' kinetic energy at omega (polarisation of the quadratic form): the shapes of c
    coincident modes, unique up to sign where their energies differ."""
    B = V.T @ Mf @ V
    c = V.shape[1]
    if c == 1:                           # what eigh gives for 1 x 1: lam = B, U = 1
        return V * (1.0 / np.sqrt(B[0, 0]))
    lam, U = np.linalg.eigh(0.5 * (B + B.T))
    X = V @ (U / np.sqrt(lam))
    full = np.zeros((c, 6))
    full[:, fi] = X.T
    a, b = np.triu_indices(c, 1)
    both = np.concatenate([full, full[a] + full[b]])
    E = m.cable_kinetic_energies(np.full(len(both), omega), both).sum(axis=1)
    e = E[:c]
    Q = np.diag(e)
    Q[a, b] = Q[b, a] = 0.5 * (E[c:] - e[a] - e[b])
    _, R = np.linalg.eigh(Q)
    return X @ R
