"""Eigenvalue derivatives of the lumped rung (theory.md §16.3): the finite eigenproblem
K phi = lambda M phi about the lumped model's own equilibrium, whose nodes and pose move
with the parameters.

The lumped equilibrium z (free platform DOFs, interior nodes) solves R(z; L0, p) = 0
(:meth:`dynstiff.models.lumped_robot.LumpedMassModel.residual`), with the unstretched
lengths L0 from the catenary statics at the pose
(:mod:`dynstiff.analyses.sensitivity_statics`) or given (fixed lengths). With K = -dR/dz
its tangent,

    dz = K^-1 (dR/dp) dp,     d lambda = phi^T (dK - lambda dM) phi   (phi^T M phi = 1),

dR/dp and the forms phi^T (K - lambda M) phi along (dz, dp) by the complex step of the
analytic functions below (the element tangents (EA/l0) n n^T + (T/l)(I - n n^T), the
geometric stiffness of the platform's lever arms and the lumped masses, theory.md §7.1).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.analyses.sensitivity_kernels import (
    CS_STEP,
    geometric_stiffness,
    platform_mass_forms,
    rotation,
)

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.models.lumped import LumpedLinearModel

__all__ = ["LumpedLinearisation"]


class LumpedLinearisation:
    """The lumped model's equilibrium as analytic equations and its bilinear forms.

    Parameters
    ----------
    model : LumpedLinearModel
    P0 : dict
        Base primitives (:func:`dynstiff.analyses.sensitivity_kernels.primitives`) with
        ``L0`` the mass model's unstretched lengths.

        Examples
        --------
    >>> import dynstiff as ds
    >>> from dynstiff.analyses.sensitivity_kernels import primitives
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.build_model(eq, "lumped", segments=4)
    >>> LL = LumpedLinearisation(m, primitives(eq.robot, eq.pose, None,
    ...                                        m.mass_model.unstretched_lengths))
    >>> LL.z_base().size == m.n_dof
    True
        """

    def __init__(self, model: LumpedLinearModel, P0: dict[str, NDArray[np.float64]]) -> None:
        self.model, self.mm = model, model.mass_model
        self.P0 = P0
        self.robot = model.robot
        self.g = self.robot.g
        self.fi, self.nf = model.free_index, model.n_free
        st = model.equilibrium
        self.pos_L = st.pose.position
        self.R_L = st.pose.matrix
        self.interior = [np.asarray(x, float) for x in st.interior]
        self.z0 = np.zeros(model.n_dof)
        for x, o in zip(self.interior, self.mm.offsets):
            self.z0[o:o + x.size] = x.ravel()

    def _config(
            self, Z: NDArray[np.complex128], P: dict[str, NDArray[np.complex128]],
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128],
               list[NDArray[np.complex128]]]:
        """Platform pose and the nodes of every cable for DOF vectors Z (B, n_dof) (the
        platform part an increment from the lumped equilibrium)."""
        B = Z.shape[0]
        d6 = np.zeros((B, 6), dtype=complex)
        d6[:, self.fi] = Z[:, :self.nf]
        R = (rotation(d6[:, 3:]) @ rotation(P["rotvec"])
             @ rotation(self.P0["rotvec"]).T @ self.R_L)
        pos = self.pos_L + (P["position"] - self.P0["position"]) + d6[:, :3]
        r = np.einsum("bij,bnj->bni", R, P["attachments"])
        Bpt = pos[:, None, :] + r
        nodes = []
        for i, (o, N) in enumerate(zip(self.mm.offsets, self.mm.segments)):
            inner = Z[:, o:o + 3 * (N - 1)].reshape(B, N - 1, 3)
            nodes.append(np.concatenate([np.broadcast_to(P["anchors"][:, None, i, :],
                                                         (B, 1, 3)), inner,
                                         Bpt[:, None, i, :]], 1))
        return pos, R, r, nodes

    def _segments(self, nodes: NDArray[np.complex128], P: dict[str, NDArray[np.complex128]],
                  i: int) -> tuple[NDArray[np.complex128], ...]:
        N = self.mm.segments[i]
        l0 = P["L0"][:, i] / N
        d = np.diff(nodes, axis=1)
        ln = np.sqrt(np.sum(d * d, -1))
        T = P["EA"][:, i, None] * (ln / l0[:, None] - 1.0)
        return d / ln[..., None], ln, T, l0

    def residual(self, Z: NDArray[np.complex128],
                 P: dict[str, NDArray[np.complex128]]) -> NDArray[np.complex128]:
        """Net applied force on the free platform DOFs and the interior nodes, (B, n_dof)
        (as :meth:`~dynstiff.models.lumped_robot.LumpedMassModel.residual`), analytic."""
        pos, R, r, nodes = self._config(Z, P)
        gv = np.array([0.0, 0.0, -self.g])
        out = np.zeros(Z.shape, dtype=complex)
        F = []
        for i, x in enumerate(nodes):
            u, _, T, l0 = self._segments(x, P, i)
            f = T[..., None] * u
            mg = (P["m0"][:, i] * l0)[:, None] * gv
            o, N = self.mm.offsets[i], self.mm.segments[i]
            out[:, o:o + 3 * (N - 1)] = (f[:, 1:] - f[:, :-1] + mg[:, None, :]).reshape(
                len(Z), -1)
            F.append(-f[:, -1] + 0.5 * mg)
        F = np.stack(F, 1)
        m = np.asarray(P["mass"])
        fg = m[:, None] * gv
        rG = np.einsum("bij,bj->bi", R, P["com"])
        W = np.concatenate([F.sum(1) + fg,
                            cross(r, F).sum(1) + cross(rG, fg)], -1)
        out[:, :self.nf] = W[:, self.fi]
        return out

    def forms(self, Z: NDArray[np.complex128], P: dict[str, NDArray[np.complex128]],
              lam: NDArray[np.float64], A: NDArray[np.float64],
              Bv: NDArray[np.float64]) -> NDArray[np.complex128]:
        """a_k^T (K(z, p) - lam_k M(z, p)) b_k for mode vectors A, Bv (m, n_dof), (B, m),
        K the (symmetric part of the) tangent stiffness, M the lumped mass."""
        pos, R, r, nodes = self._config(Z, P)
        gv = np.array([0.0, 0.0, -self.g])
        fi, nf = self.fi, self.nf

        def platform(v: NDArray[np.float64]) -> NDArray[np.float64]:
            v6 = np.zeros((len(v), 6))
            v6[:, fi] = v[:, :nf]
            return v6

        a6, b6 = platform(A), platform(Bv)
        nb = Z.shape[0]
        Kf = np.zeros((nb, len(lam)), dtype=complex)
        Mf = np.zeros_like(Kf)
        F = []
        for i, x in enumerate(nodes):
            u, ln, T, l0 = self._segments(x, P, i)
            o, N = self.mm.offsets[i], self.mm.segments[i]

            def chain(
                    v: NDArray[np.float64], v6: NDArray[np.float64],
            ) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
                """Node motions of cable i (anchor 0, interior, B = J_i x), (B, m, N+1, 3)."""
                inner = v[:, o:o + 3 * (N - 1)].reshape(len(v), N - 1, 3)
                end = v6[None, :, :3] + cross(v6[None, :, 3:], r[:, None, i, :])
                nodes = [np.zeros((nb, len(v), 1, 3)),
                         np.broadcast_to(inner, (nb,) + inner.shape), end[:, :, None]]
                return np.concatenate(nodes, 2), inner

            ca, ia = chain(A, a6)
            cb, ib = chain(Bv, b6)
            da, db = np.diff(ca, axis=2), np.diff(cb, axis=2)            # (B, m, N, 3)
            ka = (P["EA"][:, i] * P["axial"][:, i] / l0)[:, None, None]
            kt = (T / ln)[:, None, :]
            ua = np.einsum("bmsj,bsj->bms", da, u)
            ub = np.einsum("bmsj,bsj->bms", db, u)
            Kf += ((ka - kt) * ua * ub + kt * np.sum(da * db, -1)).sum(-1)
            mi = P["m0"][:, i] * l0
            Mf += mi[:, None] * (np.einsum("msj,msj->m", ia, ib)[None, :]
                                 + 0.5 * np.sum(ca[:, :, -1] * cb[:, :, -1], -1))
            F.append(-T[:, -1, None] * u[:, -1] + 0.5 * (mi[:, None] * gv))
        m = np.asarray(P["mass"])
        rG = np.einsum("bij,bj->bi", R, P["com"])
        G = geometric_stiffness(np.stack(F, 1), r, m[:, None] * gv, rG)
        Gs = 0.5 * (G + np.swapaxes(G, 1, 2))
        Kf += np.einsum("mi,bij,mj->bm", a6[:, 3:], Gs, b6[:, 3:])
        Mp = platform_mass_forms(P, R)
        Mf += np.einsum("mi,bij,mj->bm", a6, Mp, b6)
        return Kf - lam[None, :] * Mf

    def equilibrium_derivatives(self,
                                P_batch: dict[str, NDArray[np.complex128]]) -> NDArray[np.float64]:
        """dz for the primitive increments in ``P_batch`` (complex-step batch, as
        :meth:`LinearisedEquilibrium.perturbed`), (B, n_dof): K dz = dR/dp dp."""
        import scipy.sparse.linalg
        Z = np.broadcast_to(self.z_base(), (len(P_batch["mass"]), self.model.n_dof)
                            ).astype(complex)
        Rp = np.imag(self.residual(Z, P_batch)) / CS_STEP
        lu = scipy.sparse.linalg.splu(self.model.K.tocsc())
        return lu.solve(np.ascontiguousarray(Rp.T)).T

    def z_base(self) -> NDArray[np.float64]:
        """The base DOF vector: platform increments 0, interior nodes at equilibrium."""
        return self.z0
