"""The static equilibrium of a robot as equations, and its derivative (theory.md §16.2).

The sensitivity of a natural frequency to a parameter needs the change of the equilibrium
the model is linearised about: the tensions, catenaries (and, at fixed lengths, the pose)
move with EA, the platform mass, the anchors... The equilibrium is written as residual
equations R(y, p) = 0 in explicit, complex-analytic form, so that their Jacobians come from
the complex step, exact to rounding (Squire & Trapp 1998; Martins et al. 2003):
dR/dy . d = Im R(y + i h d, p) / h with h = 1e-30. Then dy/dp = -R_y^-1 R_p.

Unknowns y (theory.md §16.2)
----------------------------
``hold="pose"`` (inverse statics at a fixed pose, the tension distribution of
:func:`dynstiff.robot.statics.tension_distribution`): per cable H, V0, L0 and the tension t
at B, plus the multipliers nu of the wrench balance; the equations are each catenary's end
offsets (2 n), T_B = t (n), the distribution's optimality (n: t - t_ref + (W^T nu)_i for a
free cable, min T_i = t_min or max T_i = t_max for a cable held at a limit) and the wrench
balance on the free DOFs (k). ``hold="lengths"`` (forward statics at fixed unstretched
lengths): per cable H, V0, and the motion of the free DOFs; the equations are the end
offsets (2 n) and the balance (k). The parameters are the primitives of
:mod:`dynstiff.analyses.sensitivity_kernels`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.analyses.sensitivity_kernels import (
    CS_STEP,
    cable_quantities,
    catenary_offsets,
    perturbed_primitives,
    primitives,
    rotation,
    wrench,
)
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["LinearisedEquilibrium"]


class LinearisedEquilibrium:
    """The equilibrium of a model as equations R(y, p) = 0 and the derivative dy/dp.

    Parameters
    ----------
    equilibrium : Equilibrium
        The model's static equilibrium.
    hold : {"pose", "lengths"}
        What a parameter change keeps: the pose (inverse statics and its tension
        distribution) or the unstretched lengths (forward statics).
    tension_reference : float or ndarray, shape (n,), optional
        The distribution's reference [N] (default: the robot's, t_min along each cable).

    Attributes
    ----------
    P : dict
        Base primitives (module notes).
    y : ndarray
        Base unknowns.
    active : ndarray of int, shape (n,)
        -1 / +1 where a cable's tension is held at t_min / t_max (pose hold), else 0.
    multipliers : ndarray, shape (n,)
        The distribution's multipliers of the held limits [N] (0 for the free cables): a
        tension at a limit binds the optimum while its multiplier is > 0.

    Raises
    ------
    InvalidParameterError
        The equilibrium is not the tension distribution closest to ``tension_reference``
        (at a fixed pose), or the equations are singular there.

        Examples
        --------
    >>> import dynstiff as ds
    >>> lin = LinearisedEquilibrium(ds.load_scene("cogiro").equilibrium())
    >>> lin.active.tolist(), lin.y.size          # no cable at a limit; 4 x 8 + 6 unknowns
    ([0, 0, 0, 0, 0, 0, 0, 0], 38)
        """

    def __init__(self, equilibrium: Equilibrium, hold: str = "pose",
                 tension_reference: NDArray[np.float64] | None = None) -> None:
        if hold not in ("pose", "lengths"):
            raise InvalidParameterError(f"hold must be 'pose' or 'lengths', got {hold!r}")
        eq = equilibrium
        rob = eq.robot
        self.robot, self.hold, self.g = rob, hold, rob.g
        self.n, self.fi = rob.n_cables, rob.platform.free_index
        self.k = len(self.fi)
        self.default_reference = tension_reference is None
        self.P = primitives(rob, eq.pose, tension_reference,
                            eq.unstretched_lengths if hold == "lengths" else None)
        H = np.array([s.H for s in eq.states])
        V0 = np.array([s.V0 for s in eq.states])
        L0 = np.array(eq.unstretched_lengths, dtype=float)
        if np.any(H <= 0):
            raise InvalidParameterError(
                f"equilibrium: cable {int(np.argmin(H))} has a vertical chord (H = 0); its "
                f"sensitivities are not available")
        self.R0 = rotation(self.P["rotvec"])
        self.scale_N = max(rob.platform.mass * max(rob.g, 1.0), 1.0)
        if hold == "lengths":
            self.y = np.concatenate([H, V0, np.zeros(self.k)])
            self.active = np.zeros(self.n, dtype=int)
            self.multipliers = np.zeros(self.n)
        else:
            q = cable_quantities(self.P, H, V0, L0, self.g)
            self.active = self._active_set(q, V0)
            t = q["TB"]
            self.y = np.concatenate([H, V0, L0, t, np.zeros(self.k)])
            nu, resid, self.multipliers = self._multipliers(self.y)
            self.y[4 * self.n:] = nu
            if resid > 1e-6 * max(1.0, np.abs(t).max()):
                ref = "the default reference" if self.default_reference \
                    else f"tension_reference {np.round(self.P['t_ref'], 6).tolist()} N"
                raise InvalidParameterError(
                    f"equilibrium: its tensions are not the distribution closest to {ref} "
                    f"at this pose (optimality residual {resid:.3g} N): give the "
                    f"tension_reference it was computed with, or hold='lengths'")
        Jy = self.jacobian_y()
        try:
            self._lu = self._factor(Jy)
        except np.linalg.LinAlgError:
            raise InvalidParameterError(
                "equilibrium: the statics equations are singular at this equilibrium (a "
                "degenerate active set or a singular configuration)") from None

    # ------------------------------------------------------------------ equations
    def _active_set(self, q: dict[str, NDArray[np.float64]],
                    V0: NDArray[np.float64]) -> NDArray[np.int64]:
        t_min, t_max = float(self.P["t_min"]), float(self.P["t_max"])
        lo = self._min_tension(q, V0)
        hi = np.maximum(q["TB"], q["TA"])
        tol = 1e-7 * max(1.0, t_min, float(np.max(q["TB"])))
        return np.where(np.abs(lo - t_min) <= tol, -1,
                        np.where(np.abs(hi - t_max) <= tol, 1, 0))

    @staticmethod
    def _min_tension(q: dict[str, NDArray[Any]], V0: NDArray[Any]) -> NDArray[Any]:
        """Least tension along each cable (as ``CatenaryState.min_tension``), analytic with
        the branch of the real values."""
        V0r, Vbr = np.real(V0), np.real(q["Vb"])
        H = np.sqrt(q["TA"] ** 2 - V0 ** 2)
        inner = (V0r < 0) & (Vbr > 0)
        return np.where(inner, H, np.where(np.abs(V0r) <= np.abs(Vbr), q["TA"], q["TB"]))

    def _split(
            self, y: NDArray[Any],
    ) -> tuple[NDArray[Any], NDArray[Any], NDArray[Any] | None, NDArray[Any] | None, NDArray[Any]]:
        n = self.n
        if self.hold == "lengths":
            return y[..., :n], y[..., n:2 * n], None, None, y[..., 2 * n:]
        return y[..., :n], y[..., n:2 * n], y[..., 2 * n:3 * n], y[..., 3 * n:4 * n], \
            y[..., 4 * n:]

    def pose_of(self, y: NDArray[Any],
                P: dict[str, NDArray[Any]]) -> tuple[NDArray[Any], NDArray[Any]]:
        """(position (..., 3), rotation (..., 3, 3)) of the platform for unknowns y."""
        if self.hold == "pose":
            return P["position"], rotation(P["rotvec"])
        d6 = np.zeros(np.shape(y)[:-1] + (6,), dtype=np.result_type(y, float))
        d6[..., self.fi] = self._split(y)[4]
        return (P["position"] + d6[..., :3],
                rotation(d6[..., 3:]) @ rotation(P["rotvec"]))

    def quantities(
            self, y: NDArray[Any], P: dict[str, NDArray[Any]],
    ) -> tuple[NDArray[Any], NDArray[Any], NDArray[Any], dict[str, NDArray[Any]]]:
        """(H, V0, L0, cable quantities) at unknowns y and primitives P (batch allowed)."""
        H, V0, L0, _, _ = self._split(y)
        if L0 is None:
            L0 = P["L0"]
        pos, R = self.pose_of(y, P)
        return H, V0, L0, cable_quantities(P, H, V0, L0, self.g, pos, R)

    def residual(self, y: NDArray[Any], P: dict[str, NDArray[Any]]) -> NDArray[Any]:
        """R(y, p), shape (..., n_y): offsets [m], tensions [N], optimality [N], balance
        [N, N m] (theory.md §16.2)."""
        H, V0, L0, q = self.quantities(y, P)
        x, z = catenary_offsets(H, V0, L0, P["EA"], q["w0"])
        parts = [x - q["lh"], z - q["h"]]
        bal = wrench(P, q, self.g)[..., self.fi]
        if self.hold == "pose":
            _, _, _, t, nu = self._split(y)
            W = np.concatenate([q["f"], cross(q["r"], q["f"])], -1) / q["TB"][..., None]
            Wt_nu = np.einsum("...nj,...j->...n", W[..., self.fi], nu)
            lo = self._min_tension(q, V0)
            t_ref = P["t_ref"] + (P["t_min"][..., None] + q["TB"] - lo
                                  if self.default_reference else 0.0)
            hi = np.where(np.real(q["TB"]) >= np.real(q["TA"]), q["TB"], q["TA"])
            opt = np.where(self.active < 0, lo - P["t_min"][..., None],
                           np.where(self.active > 0, hi - P["t_max"][..., None],
                                    t - t_ref + Wt_nu))
            parts += [q["TB"] - t, opt]
        return np.concatenate(parts + [bal], -1)

    def tension_extremes(self, y: NDArray[Any],
                         P: dict[str, NDArray[Any]]) -> tuple[NDArray[Any], NDArray[Any]]:
        """Least and largest tension along every cable [N], (..., n) each, analytic (the
        limits of the distribution hold all along the cables, theory.md §4)."""
        _, V0, _, q = self.quantities(y, P)
        hi = np.where(np.real(q["TB"]) >= np.real(q["TA"]), q["TB"], q["TA"])
        return self._min_tension(q, V0), hi

    def _multipliers(
            self, y: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], float, NDArray[np.float64]]:
        """Balance multipliers nu from the free cables' optimality, the residual of that
        fit [N], and the limit multipliers [N]."""
        R = self.residual(y, self.P)
        n, k = self.n, self.k
        opt = R[3 * n:4 * n]                       # with nu = 0: t - t_ref (free cables)
        H, V0, L0, q = self.quantities(y, self.P)
        W = (np.concatenate([q["f"], cross(q["r"], q["f"])], -1)
             / q["TB"][:, None])[:, self.fi]       # (n, k): W^T
        free = self.active == 0
        g = np.real(np.where(free, opt, 0.0))
        t = self._split(y)[3]
        lo = self._min_tension(q, V0)
        t_ref = self.P["t_ref"] + (self.P["t_min"] + q["TB"] - lo
                                   if self.default_reference else 0.0)
        g_all = np.real(t - t_ref)
        if np.any(free):
            nu = np.linalg.lstsq(W[free], -g[free], rcond=None)[0]
            resid = float(np.abs(W[free] @ nu + g[free]).max())
        else:
            nu, resid = np.zeros(k), 0.0
        mult = np.where(free, 0.0, -(g_all + W @ nu) * np.where(self.active < 0, -1.0, 1.0))
        return nu, resid, np.real(mult)

    # ------------------------------------------------------------------ derivatives
    def jacobian_y(self) -> NDArray[np.float64]:
        """dR/dy, square, by the complex step (all unit directions in one batch)."""
        ny = self.y.size
        Y = self.y[None, :] + 1j * CS_STEP * np.eye(ny)
        P = perturbed_primitives(self.P, [{}] * ny, 0.0)
        return (np.imag(self.residual(Y, P)) / CS_STEP).T

    @staticmethod
    def _factor(J: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int32]]:
        import warnings

        import scipy.linalg
        with warnings.catch_warnings():
            # an exactly singular J is refused below, by its pivots, with its reason
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
            lu = scipy.linalg.lu_factor(J)
        if np.min(np.abs(np.diag(lu[0]))) <= 1e-13 * np.abs(np.diag(lu[0])).max():
            raise np.linalg.LinAlgError("singular")
        return lu

    def derivatives(
            self, directions: list[dict[str, NDArray[np.float64] | float]],
    ) -> NDArray[np.float64]:
        """dy/dp along each direction (a list of dicts of primitive increments), shape
        (n_directions, n_y)."""
        import scipy.linalg
        if not directions:
            return np.zeros((0, self.y.size))
        Y = np.broadcast_to(self.y.astype(complex), (len(directions), self.y.size))
        P = perturbed_primitives(self.P, directions, CS_STEP)
        Rp = np.imag(self.residual(Y, P)) / CS_STEP
        return -scipy.linalg.lu_solve(self._lu, Rp.T, check_finite=False).T

    def perturbed(
            self, directions: list[dict[str, NDArray[np.float64] | float]], dy: NDArray[np.float64],
            step: float = CS_STEP,
    ) -> tuple[NDArray[np.complex128], dict[str, NDArray[np.complex128]]]:
        """(y + i step dy, P + i step d) for every direction: the complex inputs of the
        rungs' forms."""
        Y = self.y[None, :] + 1j * step * dy
        return Y, perturbed_primitives(self.P, directions, step)
