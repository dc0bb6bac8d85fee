"""The "lumped" rung: the lumped-mass robot linearised about its own equilibrium.

Built from a :class:`~dynstiff.lumped.LumpedMassModel` and one of its equilibria (the
equilibrium is part of how the model is built; nothing changes it afterwards). It answers
the interface of every model (:mod:`dynstiff.models.base`) from its finite matrices
(theory.md §7.1):

    K(omega) = D_pp(omega) - K_pi D_ii(omega)^-1 K_ip,   D = K - omega^2 M + i omega C

(the interior nodes condensed out; the mass and damping of the nodes are diagonal, so only K
couples them to the platform), and its poles are the natural frequencies of the chains with
the platform held, counted exactly from the eigenvalues of (K_ii, M_ii).

Notation as :mod:`dynstiff.models.lumped_robot`.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff._validate import flag, omega_array
from dynstiff.errors import InvalidParameterError
from dynstiff.models.base import PlatformModel
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.models.lumped_statics import LumpedEquilibrium
from dynstiff.robot.platform import lever_map

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

__all__ = ["LumpedLinearModel"]


class LumpedLinearModel(PlatformModel):
    """Lumped-mass robot linearised about an equilibrium of its own (immutable).

    Parameters
    ----------
    mass_model : LumpedMassModel
        The nonlinear lumped-mass robot (cables, lengths, segments).
    state : LumpedEquilibrium
        Its equilibrium, from ``mass_model.equilibrium(...)``.

    Attributes
    ----------
    rung, robot, equilibrium, pose, free_dofs, free_index, n_free, platform_mass, damped
        As every model (:mod:`dynstiff.models.base`); ``equilibrium`` is ``state``.
    mass_model : LumpedMassModel
    unstretched_lengths : ndarray, shape (n_cables,)
        L0_i [m] (those of ``mass_model``).
    segments : ndarray of int, shape (n_cables,)
        N_i (those of ``mass_model``).
    n_dof : int
        Free platform DOFs + 3 (N_i - 1) per cable.
    K, M : scipy.sparse.csr_matrix, shape (n_dof, n_dof)
        Tangent stiffness (undamped) [N/m, N, N m/rad] and mass [kg, kg m, kg m^2].
    K_damped : scipy.sparse.csr_matrix or None
        Tangent with EA (1 + i eta) in the axial terms (hysteretic damping), None if no
        cable has a loss factor.
    C : scipy.sparse.csr_matrix or None
        Viscous damping [N s/m], None if no cable has viscous damping.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.build_model(eq, "lumped", segments=4)
    >>> type(m).__name__, m.rung
    ('LumpedLinearModel', 'lumped')
    >>> print(f"{ds.eigenfrequencies(m, n_modes=1)[0]:.2f} Hz")
    2.21 Hz
    """

    rung = "lumped"

    def __init__(self, mass_model: LumpedMassModel, state: LumpedEquilibrium,
                 damping: bool = True) -> None:
        if not isinstance(mass_model, LumpedMassModel):
            raise InvalidParameterError(
                f"mass_model must be a LumpedMassModel, got {type(mass_model).__name__}")
        if not isinstance(state, LumpedEquilibrium):
            raise InvalidParameterError(
                f"state must be a LumpedEquilibrium (from mass_model.equilibrium()), got "
                f"{type(state).__name__}")
        damping = flag("damping", damping)
        rob = mass_model.robot
        self._init_platform(rob, state, state.pose)
        self.mass_model = mass_model
        self.unstretched_lengths = mass_model.unstretched_lengths
        self.segments = mass_model.segments
        self.n_dof = mass_model.n_dof
        self.K = mass_model.tangent_stiffness(state.pose, state.interior)
        self.M = mass_model.mass_matrix(state.pose)
        eta = [c.loss_factor for c in rob.cables]
        hysteretic = damping and any(e > 0 for e in eta)
        viscous = damping and any(c.viscous_damping > 0 for c in rob.cables)
        self.K_damped = (mass_model.tangent_stiffness(
            state.pose, state.interior, [1.0 + 1j * e if e > 0 else 1.0 for e in eta])
            if hysteretic else None)
        self.C = mass_model.damping_matrix(state.pose) if viscous else None
        self.damped = hysteretic or viscous
        self._damping = damping
        self._freeze()

    def __repr__(self) -> str:
        seg = self.segments
        seg = int(seg[0]) if np.all(seg == seg[0]) else seg.tolist()
        return (f"LumpedLinearModel(rung='lumped', {counted(self.robot.n_cables, 'cable')}, "
                f"segments "
                f"{seg}, n_dof {self.n_dof}, {self.pose!r})")

    # ---------------------------------------------------------------- the interface
    def matrices(self) -> tuple[Any, Any]:
        """Undamped tangent stiffness K and mass M, sparse, shape (n_dof, n_dof), the free
        platform DOFs first (then the interior nodes, cable by cable)."""
        return self.K, self.M

    def dynamic_stiffness(self, omega: ArrayLike) -> NDArray[Any]:
        """K(omega) on the free platform DOFs, interior nodes condensed out exactly, shape
        (n_omega, n_free, n_free) [N/m, N, N m/rad].

        Parameters
        ----------
        omega : float or array_like, shape (n_omega,)
            [rad/s], real >= 0 or complex.

        Returns
        -------
        ndarray; real when undamped at real omega. inf where D_ii(omega) is exactly
        singular (a natural frequency of a chain with the platform held).
        """
        import scipy.sparse.linalg
        omega = omega_array(omega, complex_ok=True)
        nf = self.n_free
        K = self.K_damped if self.K_damped is not None else self.K
        complex_out = self.damped or np.iscomplexobj(omega)
        out = np.empty((omega.size, nf, nf), dtype=complex if complex_out else float)
        Kpp = K[:nf, :nf].toarray()
        Mpp = self.M[:nf, :nf].toarray()
        Cpp = self.C[:nf, :nf].toarray() if self.C is not None else None
        if self.n_dof == nf:
            out[:] = Kpp[None] - (omega**2)[:, None, None] * Mpp
            if Cpp is not None:
                out += (1j * omega)[:, None, None] * Cpp
            return out
        Kii, Kip, Kpi = K[nf:, nf:], K[nf:, :nf].toarray(), K[:nf, nf:]
        Mii = self.M[nf:, nf:]
        Cii = self.C[nf:, nf:] if self.C is not None else None
        for k, w in enumerate(omega):
            Dii = Kii - (w * w) * Mii
            if Cii is not None:
                Dii = Dii + (1j * w) * Cii
            Dpp = Kpp - (w * w) * Mpp
            if Cpp is not None:
                Dpp = Dpp + (1j * w) * Cpp
            try:
                sol = scipy.sparse.linalg.splu(Dii.tocsc()).solve(Kip.astype(Dii.dtype))
            except RuntimeError:                       # exactly singular: a held-platform pole
                out[k] = np.inf
                continue
            out[k] = Dpp - Kpi @ sol
        return out

    def massless_stiffness(self) -> NDArray[np.float64]:
        """Static stiffness of the platform with the cable nodes condensed out (their
        massless limit), shape (n_free, n_free) [N/m, N, N m/rad]; comparable with
        ``Equilibrium.platform_stiffness()``."""
        import scipy.sparse.linalg
        nf = self.n_free
        Kpp = self.K[:nf, :nf].toarray()
        if self.n_dof == nf:
            return Kpp
        sol = scipy.sparse.linalg.splu(self.K[nf:, nf:].tocsc()).solve(
            self.K[nf:, :nf].toarray())
        return Kpp - self.K[:nf, nf:] @ sol

    def cable_mode_count(self, omega: NDArray[np.float64] | float) -> NDArray[np.int64]:
        """Natural frequencies of the chains with the platform held below omega [rad/s]
        (J0 of the Wittrick-Williams count), shape (n_omega,)."""
        omega = omega_array(omega)
        lam = self._held_platform_eigenvalues
        return np.searchsorted(lam, omega**2, side="left")

    @functools.cached_property
    def _held_platform_eigenvalues(self) -> NDArray[np.float64]:
        """Eigenvalues omega^2 [rad^2/s^2] of (K_ii, M_ii), ascending (one chain at a time:
        the chains couple only through the platform)."""
        import scipy.linalg
        K, M = self.K.tocsr(), self.M.tocsr()
        lam = []
        for o, size in zip(self.mass_model.offsets, 3 * (self.mass_model.segments - 1)):
            if size == 0:
                continue
            sl = slice(o, o + size)
            Kc = K[sl, sl].toarray()
            lam.append(scipy.linalg.eigh(0.5 * (Kc + Kc.T), M[sl, sl].toarray(),
                                         eigvals_only=True))
        return np.sort(np.concatenate(lam)) if lam else np.zeros(0)

    def undamped(self) -> LumpedLinearModel:
        """The same linearisation without damping (itself when undamped)."""
        if not self.damped:
            return self
        return LumpedLinearModel(self.mass_model, self.equilibrium, damping=False)

    # ------------------------------------------------------- modal energy of vectors
    def cable_energies(self, V: NDArray[np.float64]) -> NDArray[np.float64]:
        """Kinetic energy of every cable per unit omega^2 / 2 for mode vectors V, shape
        (n_modes, n_cables) [kg m^2 per unit amplitude^2]: sum of m l0 |phi_j|^2 over its
        interior nodes plus (m l0 / 2) |J_i x|^2 at B_i (theory.md §7.1).

        V : ndarray, shape (n_dof, n_modes)."""
        mm = self.mass_model
        fi = self.free_index
        X = V[:self.n_free]
        _, r = self.robot.attachment_points(self.pose)
        E = np.zeros((V.shape[1], self.robot.n_cables))
        for i in range(self.robot.n_cables):
            o, size = mm.offsets[i], 3 * (mm.segments[i] - 1)
            dB = lever_map(r[i], fi) @ X                       # (3, n)
            E[:, i] = mm.node_masses[i] * (np.sum(V[o:o + size] ** 2, axis=0)
                                           + 0.5 * np.sum(dB ** 2, axis=0))
        return E

    def node_shapes(self, V: NDArray[np.float64]) -> list[NDArray[np.float64]]:
        """Displacement of every node of cable i for mode vectors V (n_dof, n_modes), a list
        of arrays of shape (n_modes, N_i + 1, 3) [m]: the anchor 0, the last node moving
        with the platform."""
        mm = self.mass_model
        fi = self.free_index
        n = V.shape[1]
        X = V[:self.n_free]
        _, r = self.robot.attachment_points(self.pose)
        out = []
        for i in range(self.robot.n_cables):
            o, size = mm.offsets[i], 3 * (mm.segments[i] - 1)
            U = V[o:o + size].T.reshape(n, -1, 3)
            dB = (lever_map(r[i], fi) @ X).T
            out.append(np.concatenate([np.zeros((n, 1, 3)), U, dB[:, None, :]], axis=1))
        return out
