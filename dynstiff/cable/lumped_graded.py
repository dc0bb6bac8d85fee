"""A lumped-mass chain with segments graded towards its point of lowest tension: the
independent reference of the exact cable on slack cables (theory.md §7.4).

A uniform chain (:mod:`dynstiff.cable.lumped_chain`) cannot follow a U-shaped cable whose
lowest tension H is far below the weight of one segment, w l0: its bottom segment carries
about w l0 / 2 instead of H, and the flexibility of the bottom, int ds / T, which grows as
log(T_max / H), is missed by O(1) however many segments there are (N >> T_max / H would be
needed). Here the segment boundaries are spread evenly in the measure

    Phi(s) = s / L0 + beta [asinh((s - s_low) / c) - asinh(-s_low / c)],

which puts half the segments in equal steps of asinh((s - s_low) / c) about the point s_low
(c the length of the low-tension core, H / w for a U; beta normalises the second term to 1);
s_low and c are only a mesh hint, the chain solves its own statics. Doubling N halves every
step of the same smooth map, so the error falls as N^-2 and Richardson's extrapolation
(4 f_2N - f_N) / 3 applies as for the uniform chain (theory.md §7.2).

Statics in force space: node equilibrium makes the segment forces f_k = f_0 + W_k e_z (W_k
the weight of nodes 1..k), a segment carrying f has the vector l0_k (1 + |f| / EA) f / |f|,
and f_0 solves the closure sum_k d_k = B - A by Newton's method on the strictly convex
complementary energy (three unknowns, a backtracking line search). No catenary formula is
used.

Linear dynamics in mixed form: the element tangent K_e = (EA / l0) n n^T + (T / l)(I - n n^T)
is written (T / l) I + kappa n n^T with kappa = EA / l0 - T / l, and the axial force
increment tau_e = kappa n . (u_k+1 - u_k) is kept as an unknown:

    [[K_T - omega^2 M, B^T], [B, -diag(1 / kappa)]] [u; tau] = [f; 0].

Eliminating tau gives back K exactly, but no entry of this matrix is of order EA / l0, so
the transverse stiffness T / l of a short segment at the bottom of a U is not lost to the
rounding of its axial stiffness (with l0 ~ 1e-7 m, eps EA / l0 exceeds T / l). The
matrix is banded (bandwidth 6 in the order u_1, tau_1, u_2, ...) and factorised by sparse
LU with partial pivoting.

Notation as :mod:`dynstiff.cable.lumped_chain`; l0_k, the unstretched length of segment k,
varies along the chain.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import omega_array, point, positive_scalar
from dynstiff.cable.lumped_chain import checked_integer
from dynstiff.constants import STANDARD_GRAVITY
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError
from dynstiff.params import Cable

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

__all__ = ["GradedChain", "graded_edges", "graded_chain"]

_EZ = np.array([0.0, 0.0, 1.0])


def graded_edges(unstretched_length: float, n_segments: int, s_low: float | None = None,
                 core: float | None = None) -> NDArray[np.float64]:
    """Segment boundaries [m], shape (N + 1,), evenly spread in Phi(s) (module notes).

    Parameters
    ----------
    unstretched_length : float
        L0 [m].
    n_segments : int
        N >= 1.
    s_low : float, optional
        Arc length of the lowest tension [m] (may lie outside [0, L0]); None: uniform.
    core : float, optional
        Length c > 0 [m] over which the tension is near its least (H / w for a U).
    """
    L0 = positive_scalar("unstretched_length", unstretched_length)
    n = checked_integer("n_segments", n_segments, 1)
    xi = np.linspace(0.0, 1.0, n + 1)
    if s_low is None:
        return L0 * xi
    c = positive_scalar("core", core)
    s = np.linspace(0.0, L0, 20001)
    s = np.unique(np.concatenate([s, np.clip(s_low + c * np.sinh(np.linspace(
        np.arcsinh(-s_low / c), np.arcsinh((L0 - s_low) / c), 20001)), 0.0, L0)]))
    a = np.arcsinh((s - s_low) / c) - np.arcsinh(-s_low / c)
    phi = s / L0 + a / a[-1]
    edges = np.interp(xi * phi[-1], phi, s)
    # refine the inverse map by Newton steps on the exact Phi (the table is only a start)
    span = np.arcsinh((L0 - s_low) / c) - np.arcsinh(-s_low / c)
    for _ in range(3):
        f = edges / L0 + (np.arcsinh((edges - s_low) / c) - np.arcsinh(-s_low / c)) / span \
            - xi * phi[-1]
        edges = edges - f / (1.0 / L0 + 1.0 / (span * np.hypot(c, edges - s_low)))
    edges[0], edges[-1] = 0.0, L0
    return edges


@dataclass(frozen=True, eq=False)
class GradedChain:
    """Static equilibrium of a graded chain (result of :func:`graded_chain`).

    Attributes
    ----------
    nodes : ndarray, shape (N + 1, 3)
        Node positions [m], A first, B last.
    tensions : ndarray, shape (N,)
        Segment tensions T_k [N].
    units : ndarray, shape (N, 3)
        Segment unit vectors n_k, from node k to node k + 1 [-].
    segment_lengths : ndarray, shape (N,)
        Unstretched segment lengths l0_k [m].
    node_masses : ndarray, shape (N + 1,)
        m (l0_k-1 + l0_k) / 2 [kg] (half a segment at each end).
    cable : Cable
    closure : float
        |sum_k d_k - (B - A)| at the solution [m].
    """

    nodes: np.ndarray
    tensions: np.ndarray
    units: np.ndarray
    segment_lengths: np.ndarray
    node_masses: np.ndarray
    cable: Cable
    closure: float

    @property
    def n_segments(self) -> int:
        """N."""
        return self.tensions.size

    @property
    def lengths(self) -> NDArray[np.float64]:
        """Stretched segment lengths l_k = l0_k (1 + T_k / EA) [m], shape (N,)."""
        return self.segment_lengths * (1.0 + self.tensions / self.cable.EA)

    def _saddle(self, omega: float,
                clamped: list[int]) -> tuple[Any, NDArray[np.int64], NDArray[np.int64]]:
        """The mixed matrix Z(omega) over (u_1, tau_1, ..., u_N-1, tau_N-1 and tau_0 first)
        restricted to the unknowns that are not ``clamped`` nodes, as sparse CSC, and the
        columns of the clamped nodes' coupling (module notes)."""
        import scipy.sparse
        N = self.n_segments
        EA = self.cable.EA
        l, T = self.lengths, self.tensions
        kt = T / l                                          # string stiffness [N/m]
        kappa = EA / self.segment_lengths - kt              # axial excess [N/m]
        sigma = kt                                          # scale of tau (balances rows)
        # unknown index: node k at 4k..4k+2, tau_k at 4k+3
        rows, cols, vals = [], [], []

        def add(i: NDArray[np.int64], j: NDArray[np.int64], v: NDArray[np.float64]) -> None:
            rows.append(i)
            cols.append(j)
            vals.append(v)
        eye = np.arange(3)
        for k in range(N):
            a, b = 4 * k + eye, 4 * (k + 1) + eye
            for i, j, sgn in ((a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)):
                add(i, j, np.full(3, sgn * kt[k]))
            t = 4 * k + 3
            bn = sigma[k] * self.units[k]
            for i, sgn in ((a, -1.0), (b, 1.0)):
                add(i, np.full(3, t), sgn * bn)
                add(np.full(3, t), i, sgn * bn)
            add(np.array([t]), np.array([t]), np.array([-sigma[k] ** 2 / kappa[k]]))
        n = 4 * N + 3
        w2 = np.asarray(omega) ** 2
        diag = np.zeros(n)
        diag[(4 * np.arange(N + 1)[:, None] + eye[None, :]).ravel()] = \
            np.repeat(self.node_masses, 3)
        Z = scipy.sparse.coo_matrix((np.concatenate(vals), (np.concatenate(rows),
                                     np.concatenate(cols))), shape=(n, n)).tocsc()
        Z = Z - w2 * scipy.sparse.diags(diag)
        fixed = np.concatenate([4 * k + eye for k in clamped]) if clamped else np.zeros(0, int)
        keep = np.setdiff1d(np.arange(n), fixed)
        return Z, keep, fixed

    def fixed_end_frequencies(self, n_modes: int) -> NDArray[np.float64]:
        """Lowest ``n_modes`` natural frequencies with both ends clamped [Hz], ascending:
        the largest eigenvalues mu = 1 / omega^2 of M^1/2 F M^1/2, F the interior
        flexibility applied through the LU factors of the mixed matrix (module notes)."""
        import scipy.sparse.linalg
        n_modes = checked_integer("n_modes", n_modes, 1)
        N = self.n_segments
        if n_modes > 3 * (N - 1) - 1:
            raise InvalidParameterError(
                f"n_modes must be < 3(N-1) = {3 * (N - 1)}, got {n_modes}")
        Z, keep, _ = self._saddle(0.0, [0, N])
        lu = scipy.sparse.linalg.splu(Z[keep][:, keep], permc_spec="NATURAL",
                                      diag_pivot_thresh=1.0)
        u_pos = np.flatnonzero(keep % 4 != 3)              # positions of u among keep
        r = np.sqrt(np.repeat(self.node_masses[1:-1], 3))
        rhs = np.zeros(keep.size)

        def apply(x: NDArray[np.float64]) -> NDArray[np.float64]:
            rhs[:] = 0.0
            rhs[u_pos] = r * x
            return r * lu.solve(rhs)[u_pos]
        op = scipy.sparse.linalg.LinearOperator((u_pos.size, u_pos.size), matvec=apply,
                                                dtype=float)
        mu = scipy.sparse.linalg.eigsh(op, k=n_modes, which="LA", tol=0.0,
                                       return_eigenvectors=False,
                                       ncv=min(u_pos.size, max(2 * n_modes + 1, 40)))
        return np.sort(1.0 / np.sqrt(mu)) / (2.0 * np.pi)

    def end_dynamic_stiffness(self, omega: ArrayLike) -> NDArray[np.float64]:
        """Dynamic stiffness of end B with A clamped, shape (n_omega, 3, 3) [N/m]: the mixed
        matrix condensed onto B, S = Z_bb - Z_br Z_rr^-1 Z_rb, one sparse LU per omega
        [rad/s] (>= 0); the half segment mass at B included (undamped)."""
        import scipy.sparse.linalg
        omega = omega_array(omega)
        N = self.n_segments
        out = np.empty((omega.size, 3, 3))
        for i, w in enumerate(omega):
            Z, keep, _ = self._saddle(w, [0])
            b = 4 * N + np.arange(3)
            r = np.setdiff1d(keep, b)
            lu = scipy.sparse.linalg.splu(Z[r][:, r], permc_spec="NATURAL",
                                          diag_pivot_thresh=1.0)
            Zrb = Z[r][:, b].toarray()
            out[i] = Z[b][:, b].toarray() - Zrb.T @ lu.solve(Zrb)
        return out


def graded_chain(anchor: ArrayLike, end: ArrayLike, unstretched_length: float, cable: str | Cable,
                 n_segments: int, g: float = STANDARD_GRAVITY, s_low: float | None = None,
                 core: float | None = None, f0: NDArray[np.float64] | None = None,
                 tol: float = 1e-14, max_iter: int = 200) -> GradedChain:
    """Static equilibrium of a lumped chain whose segments are graded towards s_low.

    Parameters
    ----------
    anchor, end : array_like, shape (3,)
        A (node 0) and B (node N) [m].
    unstretched_length : float
        L0 [m].
    cable : Cable
    n_segments : int
        N >= 2.
    g : float
        Gravitational acceleration [m/s^2], gravity (0, 0, -g).
    s_low, core : float, optional
        Mesh hint (:func:`graded_edges`); None: uniform segments.
    f0 : array_like, shape (3,), optional
        Starting force of the first segment [N] (default: the weight shared by the ends
        and a horizontal pull of the same size along A -> B).
    tol : float
        Closure tolerance relative to max(|B - A|, L0) [-] (>= 0; 0: until the line search
        can no longer lower the energy, the closure at rounding level).
    max_iter : int
        Newton iterations (>= 1).

    Returns
    -------
    GradedChain

    Raises
    ------
    SlackCableError
        A segment ends up with exactly zero force (no direction).
    ConvergenceError
        Newton did not close the chain (its residual given).
    """
    A, B = point("anchor", anchor), point("end", end)
    L0 = positive_scalar("unstretched_length", unstretched_length)
    if not isinstance(cable, Cable):
        raise InvalidParameterError(f"cable must be a Cable, got {type(cable).__name__}")
    N = checked_integer("n_segments", n_segments, 2)
    g = positive_scalar("g", g, allow_zero=True)
    tol = positive_scalar("tol", tol, allow_zero=True)
    max_iter = checked_integer("max_iter", max_iter, 1)
    l0 = np.diff(graded_edges(L0, N, s_low, core))
    m = cable.mass_per_length
    node_mass = np.concatenate([[0.5 * l0[0]], 0.5 * (l0[:-1] + l0[1:]), [0.5 * l0[-1]]]) * m
    lift = np.concatenate([[0.0], np.cumsum(node_mass[1:-1] * g)])[:, None] * _EZ   # (N, 3)
    EA = cable.EA
    chord = B - A
    scale = max(np.linalg.norm(chord), L0)
    if f0 is None:
        h = np.array([chord[0], chord[1], 0.0])
        hn = np.linalg.norm(h)
        W = float(node_mass[1:-1].sum() * g)
        f0 = -0.5 * W * _EZ + (W * h / hn if hn > 0 else 0.0)
    f0 = np.asarray(f0, dtype=float).copy()

    def parts(f0: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        f = f0 + lift
        T = np.linalg.norm(f, axis=1)
        return f, T

    def closure(f0: NDArray[np.float64]) -> float:
        f, T = parts(f0)
        d = (l0 * (1.0 + T / EA) / T)[:, None] * f
        return float(np.linalg.norm(d.sum(axis=0) - chord))

    def energy(f0: NDArray[np.float64]) -> float:
        _, T = parts(f0)
        return float(np.sum(l0 * (T + T * T / (2.0 * EA))) - f0 @ chord)

    for _ in range(max_iter):
        f, T = parts(f0)
        if np.any(T == 0.0):
            raise SlackCableError("graded_chain: a segment carries no force")
        n = f / T[:, None]
        gap = np.sum((l0 * (1.0 + T / EA))[:, None] * n, axis=0) - chord
        res = float(np.linalg.norm(gap))
        if res <= tol * scale:
            break
        J = np.einsum("k,kij->ij", l0 / T, np.eye(3)[None] - n[:, :, None] * n[:, None, :]) \
            + (l0.sum() / EA) * np.eye(3)
        step = -np.linalg.solve(J, gap)
        if closure(f0 + step) < res:        # near the solution: the full Newton step
            f0 = f0 + step
            continue
        e0, alpha = energy(f0), 0.5          # far from it: backtrack on the energy
        while alpha > 1e-12 and not energy(f0 + alpha * step) <= e0 + 1e-4 * alpha * (gap @ step):
            alpha *= 0.5
        if alpha <= 1e-12:
            break
        f0 = f0 + alpha * step
    else:
        raise ConvergenceError(
            f"graded_chain: the chain did not close in {max_iter} iterations (closure "
            f"{res:.3g} m)", residual=res)
    f, T = parts(f0)
    n = f / T[:, None]
    d = (l0 * (1.0 + T / EA))[:, None] * n
    nodes = A + np.vstack([np.zeros(3), np.cumsum(d, axis=0)])
    nodes[-1] = B
    return GradedChain(nodes=nodes, tensions=T, units=n, segment_lengths=l0,
                       node_masses=node_mass, cable=cable, closure=res)
