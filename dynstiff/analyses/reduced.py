"""A reduced modal model of the platform for control design, and its python-control form.

The receptance of any rung (theory.md §15.4) is expanded over its natural frequencies

    H(omega) = sum_r phi_r phi_r^T / (omega_r^2 - omega^2 + 2 i zeta_r omega_r omega) + R,

phi_r the platform shape of mode r (free DOFs) scaled by its *exact* modal mass

    mu_r = -x_r^T dK/d(omega^2)(omega_r) x_r,        phi_r = x_r / sqrt(mu_r),

the residue of K(omega)^-1 at omega_r^2, which counts the kinetic energy of the cables as well as
the platform's (for a discrete rung dK/d(omega^2) = -M, so mu_r is the usual generalized mass).
dK/domega is taken by a complex step, Im K(omega + i h) / h, exact to rounding for the analytic
K(omega) of every rung. The truncated modes enter through their static (residual) flexibility

    R = K(0)^-1 - sum_r phi_r phi_r^T / omega_r^2,

so that H is exact at omega = 0; what it leaves of a truncated mode t grows as
omega^2 / (omega_t^2 - omega^2), so the kept band must hold every mode with a large platform
share (all the platform modes of the massless-cable model, not only the band of interest).
Modes whose platform is at rest (a cable alone on its pole) have no residue and are left out.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff._validate import flag, positive_scalar, real_array
from dynstiff.analyses.eigen import eigenfrequencies
from dynstiff.analyses.frf import channel_maps
from dynstiff.errors import InvalidParameterError
from dynstiff.io.exchange import ZERO_FLOOR, require
from dynstiff.models.base import require_model

if TYPE_CHECKING:
    from collections.abc import Sequence
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.base import PlatformModel

__all__ = ["ModalModel", "modal_model", "to_statespace"]

_TWO_PI = 2.0 * np.pi


@dataclass(frozen=True)
class ModalModel:
    """Modal expansion of the platform receptance (module notes, theory.md §15.4).

    Attributes
    ----------
    omega : ndarray, shape (n,)
        Natural frequencies omega_r [rad/s] of the kept modes (platform moving).
    shapes : ndarray, shape (n, n_free)
        phi_r, platform shapes scaled to unit exact modal mass [1/sqrt(kg), ...].
    modal_mass : ndarray, shape (n,)
        mu_r of the shape x_r normalised to x_r^T M_p x_r = 1 [-] (1 for a platform alone;
        larger by the cables' share of the kinetic energy).
    damping : ndarray, shape (n,)
        Modal damping ratios zeta_r [-].
    residual : ndarray, shape (n_free, n_free) or None
        Residual flexibility R [m/N, ...] of the truncated modes (None: not corrected).
    free_dofs : tuple of str
    pose : Pose

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> mm = ds.modal_model(m, n_modes=6)
    >>> len(mm.freq_hz), mm.free_dofs
    (6, ('x', 'y', 'z', 'rx', 'ry', 'rz'))
    """

    omega: np.ndarray
    shapes: np.ndarray
    modal_mass: np.ndarray
    damping: np.ndarray
    residual: object
    free_dofs: tuple
    pose: object

    @property
    def freq_hz(self) -> NDArray[np.float64]:
        """Natural frequencies [Hz], shape (n,).

        Examples
        --------
        >>> import numpy as np
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> m = ds.FrequencyModel(eq)
        >>> print(f"{ds.modal_model(m, n_modes=6).freq_hz[0]:.4f} Hz")
        2.2061 Hz
        """
        return self.omega / _TWO_PI

    def __len__(self) -> int:
        return len(self.omega)

    def __repr__(self) -> str:
        f = self.freq_hz
        span = f"{f.min():.4g}-{f.max():.4g} Hz" if f.size else "none"
        return (f"ModalModel({counted(len(self), 'mode')} {span}, free {self.free_dofs}, residual "
                f"{'on' if self.residual is not None else 'off'})")

    def receptance(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """H(omega) on the free DOFs, shape (n_omega, n_free, n_free) [m/N, ...].

        Examples
        --------
        >>> import numpy as np
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> m = ds.FrequencyModel(eq)
        >>> mm = ds.modal_model(m, n_modes=6, damping=0.01)
        >>> mm.receptance(2 * np.pi * np.array([0.5, 1.0])).shape
        (2, 6, 6)
        """
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        den = (self.omega**2 - w[:, None]**2 + 2j * self.damping * self.omega * w[:, None])
        H = np.einsum("kr,ri,rj->kij", 1.0 / den, self.shapes, self.shapes)
        if self.residual is not None:
            H = H + self.residual
        return H


def _dK_domega2(m: PlatformModel, omega: float) -> NDArray[np.float64]:
    """dK/d(omega^2) at a real omega > 0 [kg, ...] by a complex step, (n_free, n_free)."""
    h = 1e-20 * omega
    dK = m.dynamic_stiffness(np.array([omega + 1j * h]))[0].imag / h
    return dK / (2.0 * omega)


def modal_model(model: PlatformModel, n_modes: int | None = None, fmax_hz: float | None = None,
                damping: float | ArrayLike = 0.0, residual: bool = True, cluster_rtol: float = 1e-8,
                null_rtol: float = 1e-6) -> ModalModel:
    """Modal expansion of a model's platform receptance (module notes, theory.md §15.4).

    Parameters
    ----------
    model : model of any rung (:mod:`dynstiff.models.base`); its damping is ignored
    n_modes, fmax_hz : as :func:`dynstiff.eigenfrequencies`
        Which natural frequencies to keep (those with the platform at rest drop out).
    damping : float or array_like, shape (n_kept,)
        Modal damping ratios zeta [-], >= 0 (one for all, or one per kept mode).
    residual : bool
        Add the residual flexibility of the truncated modes (default True).
    cluster_rtol : float
        Frequencies closer than this (relative) are one repeated root.
    null_rtol : float
        Eigenvalues of K(omega_r) below ``null_rtol`` times the largest of K(0) span the
        platform shapes of the root.

    Returns
    -------
    ModalModel

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> mm = ds.modal_model(m, n_modes=6, damping=0.01)
    >>> [f"{f:.3f}" for f in mm.freq_hz[:2]]
    ['2.206', '2.359']
    >>> H = mm.receptance([1.0]); H.shape
    (1, 6, 6)
    """
    m = require_model(model).undamped()
    residual = flag("residual", residual)
    cluster_rtol = positive_scalar("cluster_rtol", cluster_rtol)
    null_rtol = positive_scalar("null_rtol", null_rtol)
    zeta_in = real_array("damping", damping, "one ratio >= 0 or one per kept mode")
    if not np.all(np.isfinite(zeta_in)) or np.any(zeta_in < 0) or zeta_in.ndim > 1:
        raise InvalidParameterError(
            f"damping must be one ratio >= 0 or one per kept mode, got {damping!r}")
    f = eigenfrequencies(m, n_modes=n_modes, fmax_hz=fmax_hz)
    w_all = _TWO_PI * f
    if np.any(w_all <= 0):
        raise InvalidParameterError(
            f"the model has a zero or negative natural frequency ({f.min():.3g} Hz): an "
            f"unstable or free platform has no modal expansion")
    K0 = m.massless_stiffness()
    scale = np.abs(np.linalg.eigvalsh(0.5 * (K0 + K0.T))).max()
    omega, shapes, masses = [], [], []
    k = 0
    while k < len(w_all):
        j = k + 1
        while j < len(w_all) and w_all[j] - w_all[k] <= cluster_rtol * w_all[k]:
            j += 1
        w = float(np.mean(w_all[k:j]))
        K = m.dynamic_stiffness(np.array([w]))[0]
        k = j
        if not np.all(np.isfinite(K)):
            continue                                   # a cable pole: platform at rest
        ev, V = np.linalg.eigh(0.5 * (K + K.T))
        V = V[:, np.abs(ev) < null_rtol * scale]
        if V.shape[1] == 0:
            continue
        Mc = -V.T @ _dK_domega2(m, w) @ V
        mu, U = np.linalg.eigh(0.5 * (Mc + Mc.T))
        if np.any(mu <= 0):
            raise InvalidParameterError(
                f"non-positive modal mass {mu.min():.3g} at {w / _TWO_PI:.6g} Hz")
        X = V @ U
        Mp = m.platform_mass
        for i in range(X.shape[1]):
            x = X[:, i]
            omega.append(w)
            shapes.append(x / np.sqrt(mu[i]))
            masses.append(mu[i] / (x @ Mp @ x))
    omega = np.array(omega)
    shapes = np.array(shapes).reshape(len(omega), m.n_free)
    zeta = np.broadcast_to(zeta_in, omega.shape).copy() \
        if zeta_in.ndim == 0 or zeta_in.size == len(omega) else None
    if zeta is None:
        raise InvalidParameterError(
            f"damping must be one ratio >= 0 or one per kept mode ({len(omega)}), got "
            f"{damping!r}")
    R = None
    if residual:
        R = np.linalg.inv(K0) - np.einsum("r,ri,rj->ij", 1.0 / omega**2, shapes, shapes)
        R = 0.5 * (R + R.T)
    return ModalModel(omega=omega, shapes=shapes, modal_mass=np.array(masses), damping=zeta,
                      residual=R, free_dofs=m.free_dofs, pose=m.pose)


def to_statespace(model: PlatformModel | ModalModel, n_modes: int | None = None,
                  fmax_hz: float | None = None, damping: float = 0.0,
                  inputs: str | Sequence[str] | None = None,
                  outputs: str | Sequence[str] | None = None, point: ArrayLike | None = None,
                  residual: bool = True, name: str = "dynstiff modal model") -> Any:
    """python-control ``StateSpace`` of the platform from its modes (theory.md §15.4).

    States (q_1 .. q_n, dq_1/dt .. dq_n/dt), modal coordinates of the kept modes:

        A = [[0, I], [-Omega^2, -2 Z Omega]],  B = [[0], [Phi^T B_in]],
        C = [[C_out Phi, 0]],                   D = C_out R B_in,

    so that C (i omega - A)^-1 B + D is the receptance of :class:`ModalModel` between the
    named channels.

    Parameters
    ----------
    model : model of any rung, or a :class:`ModalModel`
    n_modes, fmax_hz, damping, residual : as :func:`modal_model` (ignored for a ModalModel,
        except that ``residual=False`` drops its residual)
    inputs, outputs, point : as :func:`dynstiff.frf`
        Loads on the platform (about P) and motions of a platform point (default P).
    name : str
        The system's name (``control.bode_plot`` titles its figure with it).

    Returns
    -------
    control.StateSpace
        Inputs, outputs and states named; 2 n states. Entries of B, C and D at most
        :data:`dynstiff.io.exchange.ZERO_FLOOR` (1e-12) times the largest of their matrix
        are exact zeros: a coupling that vanishes by symmetry holds only rounding.

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> sys = ds.to_statespace(m, n_modes=6, damping=0.01, inputs="fz", outputs="z")
    >>> sys.nstates, sys.ninputs, sys.noutputs
    (12, 1, 1)
    """
    ct = require("control")
    residual = flag("residual", residual)
    mm = model if isinstance(model, ModalModel) else modal_model(
        model, n_modes=n_modes, fmax_hz=fmax_hz, damping=damping, residual=residual)
    free_index = np.array([("x", "y", "z", "rx", "ry", "rz").index(d) for d in mm.free_dofs])
    B_in, C_out, in_names, out_names = channel_maps(free_index, mm.pose.matrix, inputs,
                                                    outputs, point)
    n = len(mm)
    Om = np.diag(mm.omega)
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-Om**2, -2.0 * np.diag(mm.damping) @ Om]])
    Phi = mm.shapes.T                                   # (n_free, n)
    B = np.vstack([np.zeros((n, B_in.shape[1])), Phi.T @ B_in])
    C = np.hstack([C_out @ Phi, np.zeros((C_out.shape[0], n))])
    D = C_out @ mm.residual @ B_in if (mm.residual is not None and residual) else \
        np.zeros((C_out.shape[0], B_in.shape[1]))
    B, C, D = (_floor(M) for M in (B, C, D))
    return ct.ss(A, B, C, D, inputs=list(in_names), outputs=list(out_names),
                 states=[f"q{r + 1}" for r in range(n)] + [f"dq{r + 1}" for r in range(n)],
                 name=name)


def _floor(M):
    """``M`` with the entries at most ZERO_FLOOR times its largest set to exact zeros."""
    M = np.array(M, dtype=float)
    top = np.abs(M).max() if M.size else 0.0
    M[np.abs(M) <= ZERO_FLOOR * top] = 0.0
    return M
