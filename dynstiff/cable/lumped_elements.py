"""Elements of a lumped-mass chain (theory.md §7.1): segment vectors, lengths and tensions of
tension-only springs, the forces on the interior nodes, the potential energy, the element
tangent stiffness and the block-tridiagonal assembly of the interior stiffness (banded
storage for LAPACK).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

__all__ = [
    "BANDWIDTH", "block_tridiagonal_entries", "element_stiffness", "interior_banded",
    "interior_forces", "potential_energy", "segments_from_vectors", "update_segments",
]

_EZ = np.array([0.0, 0.0, 1.0])
BANDWIDTH = 5          # half bandwidth of a node-major 3-DOF block-tridiagonal matrix


# ------------------------------------------------------------------------------ kernels
def segments_from_vectors(seg: NDArray[np.float64],
                          l0: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Split segment vectors into strains and unit vectors.

    Parameters
    ----------
    seg : ndarray, shape (N, 3)
        Segment vectors d_i = x_{i+1} - x_i [m].
    l0 : float
        Unstretched segment length [m].

    Returns
    -------
    strain : ndarray, shape (N,)
        epsilon_i = l_i / l0 - 1 [-] (negative for a slack segment).
    units : ndarray, shape (N, 3)
        n_i = d_i / l_i [-].
    """
    lengths = np.linalg.norm(seg, axis=1)
    return lengths / l0 - 1.0, seg / lengths[:, None]


def update_segments(strain: NDArray[np.float64], units: NDArray[np.float64], l0: float,
                    dseg: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Add ``dseg`` to the segment vectors l0 (1 + epsilon) n, keeping epsilon accurate.

    The length change is formed as (2 d.dd + |dd|^2) / (|d + dd| + |d|), so the strain
    keeps its full relative precision even when it is far below the rounding of the
    segment vectors (a slack, stiff cable has epsilon ~ 1e-5). Recomputing it as
    |d|/l0 - 1 would limit the tension accuracy to about EA x 1e-16.

    Returns
    -------
    strain : ndarray, shape (N,)
    units : ndarray, shape (N, 3)
    """
    lengths = l0 * (1.0 + strain)
    seg = lengths[:, None] * units
    new = seg + dseg
    new_lengths = np.linalg.norm(new, axis=1)
    dl = (2.0 * np.sum(seg * dseg, axis=1) + np.sum(dseg * dseg, axis=1)) / (
        new_lengths + lengths)
    return strain + dl / l0, new / new_lengths[:, None]


def interior_forces(strain: NDArray[np.float64], units: NDArray[np.float64], EA: float,
                    node_weight: float) -> NDArray[np.float64]:
    """Net force on each interior node (the Newton residual).

    F_i = T_i n_i - T_{i-1} n_{i-1} - (0, 0, m l0 g) for i = 1..N-1, T = EA max(epsilon, 0):
    the segment on the right pulls towards node i+1, the one on the left towards node i-1.

    Returns
    -------
    ndarray, shape (N-1, 3)
        Net force [N]; zero at equilibrium.
    """
    f = (EA * np.maximum(strain, 0.0))[:, None] * units
    return f[1:] - f[:-1] - node_weight * _EZ


def potential_energy(strain: NDArray[np.float64], units: NDArray[np.float64], l0: float, EA: float,
                     node_weight: float) -> float:
    """Total potential energy [J] (strain + gravity of interior nodes, heights from A).

    Pi = sum_i EA l0 / 2 (epsilon_i)_+^2 + m l0 g sum_{j=1}^{N-1} z_j. It is convex in the
    node positions (a tension-only spring energy is a convex, non-decreasing function of the
    convex length |d_i|); its gradient is minus the residual of `interior_forces` and its
    Hessian is the tangent stiffness.
    """
    stretch = np.maximum(strain, 0.0)
    heights = np.cumsum(l0 * (1.0 + strain[:-1]) * units[:-1, 2])
    return 0.5 * EA * l0 * np.dot(stretch, stretch) + node_weight * np.sum(heights)


def element_stiffness(units: NDArray[np.float64], lengths: NDArray[np.float64],
                      tensions: NDArray[np.float64],
                      axial: NDArray[np.float64] | float) -> NDArray[np.float64]:
    """Element tangent stiffness K_e = k_a n n^T + (T / l)(I - n n^T) (theory.md §7.1).

    This is the exact derivative of the element force T n with respect to the segment
    vector when T = EA (l / l0 - 1): d(T n)/dd = (EA / l0) n n^T + (T / l)(I - n n^T).

    Parameters
    ----------
    units, lengths, tensions : ndarray, shapes (N, 3), (N,), (N,)
        n_i [-], l_i [m], T_i [N].
    axial : ndarray or complex, shape (N,) or scalar
        Axial stiffness k_a [N/m]: EA / l0 (possibly EA (1 + i eta) / l0) where the segment
        is stretched, 0 where it is slack.

    Returns
    -------
    ndarray, shape (N, 3, 3)
        K_e [N/m], real or complex as ``axial``.
    """
    nn = units[:, :, None] * units[:, None, :]
    geometric = (tensions / lengths)[:, None, None]
    axial = np.broadcast_to(np.asarray(axial), tensions.shape)[:, None, None]
    return axial * nn + geometric * (np.eye(3) - nn)


def block_tridiagonal_entries(
        ke: NDArray[np.float64],
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64]]:
    """Row, column and value arrays of the assembled stiffness of a chain of elements.

    Parameters
    ----------
    ke : ndarray, shape (N, 3, 3)
        Element stiffnesses; element i joins node i and node i+1 as [[K, -K], [-K, K]].

    Returns
    -------
    rows, cols, vals : ndarray
        Coordinates of the (N+1)*3 square matrix (duplicates to be summed).
    """
    n_el = ke.shape[0]
    a, b = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")
    i = np.arange(n_el)[:, None, None]
    rows, cols, vals = [], [], []
    for (p, q, sign) in ((0, 0, 1.0), (1, 1, 1.0), (0, 1, -1.0), (1, 0, -1.0)):
        rows.append((3 * (i + p) + a).ravel())
        cols.append((3 * (i + q) + b).ravel())
        vals.append((sign * ke).ravel())
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)


def interior_banded(ke: NDArray[Any], diag_extra: float = 0.0,
                    symmetric: bool = True) -> NDArray[Any]:
    """Banded storage of the interior block K_II (nodes 1..N-1) of the chain stiffness.

    Parameters
    ----------
    ke : ndarray, shape (N, 3, 3)
        Element stiffnesses [N/m].
    diag_extra : float or complex
        Added to every diagonal entry (e.g. -omega^2 m l0 + i omega c l0) [N/m].
    symmetric : bool
        True: upper form for `scipy.linalg.solveh_banded` / `eig_banded`, shape (6, n).
        False: general form for `scipy.linalg.solve_banded` with (l, u) = (5, 5),
        shape (11, n).

    Returns
    -------
    ndarray
        Banded matrix, n = 3 (N - 1).
    """
    n_el = ke.shape[0]
    n = 3 * (n_el - 1)
    rows, cols, vals = block_tridiagonal_entries(ke)
    # drop the end nodes 0 and N, shift to interior numbering
    keep = (rows >= 3) & (rows < 3 * n_el) & (cols >= 3) & (cols < 3 * n_el)
    rows, cols, vals = rows[keep] - 3, cols[keep] - 3, vals[keep]
    if symmetric:
        upper = rows <= cols
        ab = np.zeros((BANDWIDTH + 1, n), dtype=np.result_type(ke, diag_extra))
        np.add.at(ab, (BANDWIDTH + rows[upper] - cols[upper], cols[upper]), vals[upper])
        ab[BANDWIDTH] += diag_extra
    else:
        ab = np.zeros((2 * BANDWIDTH + 1, n), dtype=np.result_type(ke, diag_extra))
        np.add.at(ab, (BANDWIDTH + rows - cols, cols), vals)
        ab[BANDWIDTH] += diag_extra
    return ab
