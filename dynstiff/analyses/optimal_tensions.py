"""The tension distribution that maximises a frequency objective (theory.md §16.7).

A robot with more cables than free DOFs holds a pose with any tensions t = t_d + N lambda,
N an orthonormal basis of the null space of the structure matrix W at the default
distribution t_d: the distribution closest to the reference t_d + N lambda is that
equilibrium (with sag, W moves with t, and the statics find the exact equilibrium of the
reference). The objective is a minimum over modes (the first platform mode,
:attr:`dynstiff.analyses.platform_modes.PlatformModes.first_hz`, or the band margin of the
modes held to it, as the workspace maps), so it is not smooth where two modes cross; the
search is a sequential linear program with a trust region: at lambda, maximise s subject to

    s <= v_k + g_k^T d          every candidate mode k (value v_k, gradient g_k = dv_k/dlambda)
    min T_i + (grad min T_i)^T d >= t_min,   max T_i + (grad max T_i)^T d <= t_max
    |d_j| <= rho

(the gradients from the eigenfrequency sensitivities and the linearised statics of
:mod:`dynstiff.analyses.sensitivity_statics`); a step is kept when the objective rises by at
least a tenth of the predicted rise, rho grows after good steps and halves after bad ones,
down to ``xtol``. At the end the constraints within tolerance are what binds.
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral, Real
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import real_array
from dynstiff.analyses.participation import PLATFORM_SHARE_THRESHOLD
from dynstiff.analyses.platform_modes import find_platform_modes
from dynstiff.analyses.sensitivity import RUNGS, sensitivities_at, whole_clusters
from dynstiff.analyses.sensitivity_kernels import CS_STEP
from dynstiff.analyses.sensitivity_parameters import Parameter
from dynstiff.analyses.sensitivity_statics import LinearisedEquilibrium
from dynstiff.errors import ConvergenceError, DynstiffError, InvalidParameterError
from dynstiff.models.ladder import build_model
from dynstiff.robot.pose import as_pose
from dynstiff.robot.robot import Robot

if TYPE_CHECKING:
    from typing import Any

    import pandas as pd
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.analyses.platform_modes import PlatformModes
    from dynstiff.robot.equilibrium import Equilibrium
    from dynstiff.robot.pose import Pose

__all__ = ["OBJECTIVES", "TENSIONS", "OptimalTensions", "band_margin", "optimal_tensions",
           "tension_equilibrium"]

#: Objectives of :func:`optimal_tensions`.
OBJECTIVES = ("first_global_hz", "band_margin")
#: Tension distributions of a map (:func:`tension_equilibrium`).
TENSIONS = ("default", "max-frequency")
_WINDOW = 0.15            # candidate modes: within 15 % of the objective
_JUMP = 3.0               # a rise over 3 times the predicted one is a jump, not followed


@dataclass(frozen=True)
class OptimalTensions:
    """The frequency-optimal tension distribution at a pose.

    Attributes
    ----------
    equilibrium : Equilibrium
        The equilibrium of the optimal tensions (inverse statics, their reference).
    reference : ndarray, shape (n,)
        Its tension reference [N] (``Robot.equilibrium(pose, tension_reference=...)``).
    default : Equilibrium
        The default distribution (closest to t_min).
    objective : str
    value, default_value : float
        The objective at the optimum and at the default distribution ([Hz] for
        "first_global_hz": the first platform mode; [-] for "band_margin").
    binds : tuple of str
        What limits the optimum: tension limits reached, coincident modes, or none; and
        "max_iter: ..." when the search stopped before it converged.
    iterations, evaluations : int
        Steps of the search and equilibria solved.
    platform : PlatformModes
        The platform modes at the optimum.

    Examples
    --------
    >>> import dynstiff as ds
    >>> opt = ds.optimal_tensions(ds.load_scene("cogiro").robot, [4.0, -2.5, 1.0])
    >>> opt.objective, opt.equilibrium.robot.n_cables
    ('first_global_hz', 8)
    """

    equilibrium: object
    reference: np.ndarray
    default: object
    objective: str
    value: float
    default_value: float
    binds: tuple
    iterations: int
    evaluations: int
    platform: object

    @property
    def gain(self) -> float:
        """value - default_value [Hz or -].

        Examples
        --------
        >>> import dynstiff as ds
        >>> opt = ds.optimal_tensions(ds.load_scene("cogiro").robot, [4.0, -2.5, 1.0])
        >>> print(f"{opt.gain:+.3f} Hz")
        +0.085 Hz
        """
        return self.value - self.default_value

    @property
    def tensions(self) -> NDArray[np.float64]:
        """Optimal tensions at B [N], shape (n,).

        Examples
        --------
        >>> import dynstiff as ds
        >>> opt = ds.optimal_tensions(ds.load_scene("cogiro").robot, [4.0, -2.5, 1.0])
        >>> print(f"{opt.tensions.min():.1f} N")
        100.0 N
        """
        return self.equilibrium.tensions

    def __repr__(self) -> str:
        unit = " Hz" if self.objective == "first_global_hz" else ""
        return (f"OptimalTensions({self.objective} {self.value:.5g}{unit}, default "
                f"{self.default_value:.5g}{unit}, gain {self.gain:+.3g}{unit}; binds: "
                f"{'; '.join(self.binds) or 'nothing'}; {self.evaluations} equilibria)")

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per cable: default and optimal tension at B and their
        least and largest tension along the cable [N].

        Examples
        --------
        >>> import dynstiff as ds
        >>> opt = ds.optimal_tensions(ds.load_scene("cogiro").robot, [4.0, -2.5, 1.0])
        >>> len(opt.to_frame())
        8
        """
        import pandas as pd
        d, o = self.default, self.equilibrium
        return pd.DataFrame({"cable": np.arange(len(o.tensions)),
                             "default tension [N]": d.tensions,
                             "optimal tension [N]": o.tensions,
                             "optimal least tension [N]": o.min_tensions,
                             "optimal largest tension [N]": o.max_tensions})


def band_margin(platform: PlatformModes, band_hz: tuple[float, float],
                participation: float = PLATFORM_SHARE_THRESHOLD) -> float:
    """Smallest relative distance outside the forbidden band of the modes with platform
    share >= ``participation`` [-], negative inside: f / f_hi - 1 above, 1 - f / f_lo below
    (the map's margin, theory.md §13.2); NaN without modes.

    Examples
    --------
    >>> import dynstiff as ds
    >>> from dynstiff.analyses.platform_modes import find_platform_modes
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> round(band_margin(find_platform_modes(m, 1.6), (0.0, 1.5)), 4)   # 2.2061 / 1.5 - 1
    0.4707
    """
    v = _margins(platform, band_hz, participation)[1]
    return float(v.min()) if v.size else np.nan


def _margins(pm: PlatformModes, band: tuple[float, float],
             participation: float) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """(indices, margins) of the modes the band margin holds."""
    if pm.modes is None:
        return np.zeros(0, int), np.zeros(0)
    m = pm.modes
    k = np.flatnonzero(m.platform_share >= participation)
    f = np.asarray(m.freq_hz)[k]
    lo, hi = band
    below = 1.0 - f / lo if lo > 0 else np.full(f.shape, -np.inf)
    return k, np.maximum(f / hi - 1.0, below)


def _structure(eq: Equilibrium) -> NDArray[np.float64]:
    """Structure matrix W (k, n) on the free DOFs at an equilibrium."""
    rob = eq.robot
    u = np.array([s.force_on_end / s.tension_at_end for s in eq.states])
    return np.vstack([u.T, np.cross(eq.lever_arms, u).T])[rob.platform.free_index]


def optimal_tensions(robot: Robot, pose: ArrayLike | Pose, objective: str = "first_global_hz",
                     band_hz: tuple[float, float] | None = None,
                     participation: float = PLATFORM_SHARE_THRESHOLD, rung: str = "dsm",
                     start: ArrayLike | OptimalTensions | Equilibrium | None = None,
                     max_iter: int = 40, xtol: float = 1.0,
                     **model_options: Any) -> OptimalTensions:
    """The equilibrium at ``pose`` whose tensions maximise a frequency objective (module
    notes, theory.md §16.7), tensions within the robot's limits all along every cable.

    Parameters
    ----------
    robot : Robot
    pose : Pose or array_like
    objective : {"first_global_hz", "band_margin"}
        "first_global_hz": the frequency of the first platform mode (the lowest of the
        modes every free DOF's verdict is about,
        :func:`~dynstiff.analyses.platform_modes.find_platform_modes`: the global modes and
        each DOF's carrier); "band_margin": the
        relative margin to ``band_hz`` of the modes with platform share >= ``participation``.
    band_hz : (float, float), optional
        Forbidden band [Hz] ("band_margin"), 0 <= lo < hi.
    participation : float
        Platform share from which a mode is held to the band [-].
    rung : str
        The model: "dsm", "exact", "lumped", "spring" or "catenary".
    start : Equilibrium, OptimalTensions or array_like, shape (n,), optional
        Warm start: a neighbouring pose's optimum (its tensions start the search).
    max_iter : int
        Most steps of the search.
    xtol : float
        Trust radius [N] below which the search stops.
    **model_options
        Passed to :func:`dynstiff.build_model`.

    Returns
    -------
    OptimalTensions

    Raises
    ------
    InvalidParameterError
        Bad arguments (named), before any work.
    InfeasiblePoseError, ConvergenceError
        No equilibrium at the pose, or no objective (the platform modes not found).

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> opt = ds.optimal_tensions(sc.robot, [4.0, -2.5, 1.0])
    >>> round(opt.default_value, 3), round(opt.value, 3), opt.binds  # first platform mode [Hz]
    (2.136, 2.22, ('cable 2 at t_min (100 N)', 'cable 3 at t_min (100 N)'))
    """
    if not isinstance(robot, Robot):
        raise InvalidParameterError(f"robot must be a dynstiff.Robot, got {type(robot).__name__}")
    if objective not in OBJECTIVES:
        raise InvalidParameterError(f"objective must be one of {OBJECTIVES}, got "
                                    f"{objective!r}")
    if objective == "band_margin":
        if band_hz is None:
            raise InvalidParameterError("objective 'band_margin' needs band_hz=(lo, hi)")
        lo, hi = (float(b) for b in band_hz)
        if not 0 <= lo < hi:
            raise InvalidParameterError(f"band_hz must be (lo, hi), 0 <= lo < hi [Hz], got "
                                        f"{band_hz!r}")
        band_hz = (lo, hi)
    if rung not in RUNGS:
        raise InvalidParameterError(f"rung must be one of {RUNGS}, got {rung!r}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, Integral) or max_iter < 1:
        raise InvalidParameterError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    if isinstance(xtol, (bool, np.bool_)) or not isinstance(xtol, Real) or \
            not (np.isfinite(xtol) and xtol > 0):
        raise InvalidParameterError(f"xtol must be finite and > 0 [N], got {xtol!r}")
    pose = as_pose(pose)
    t_start = None
    if start is not None:
        t_start = real_array("start", getattr(getattr(start, "equilibrium", start), "tensions",
                                              start), f"{robot.n_cables} tensions [N]")
        if t_start.shape != (robot.n_cables,):
            raise InvalidParameterError(
                f"start must be an Equilibrium, OptimalTensions or {robot.n_cables} tensions "
                f"[N], got shape {t_start.shape}")
    search = _Search(robot, pose, objective, band_hz, participation, rung, model_options)
    return search.run(t_start, max_iter, xtol)


class _Search:
    """The sequential linear programme of :func:`optimal_tensions`."""

    def __init__(self, robot: Robot, pose: Pose, objective: str, band: tuple[float, float] | None,
                 participation: float, rung: str, options: dict[Any, Any]) -> None:
        self.robot, self.pose, self.objective = robot, pose, objective
        self.band, self.participation = band, participation
        self.rung, self.options = rung, options
        self.search_options = dict(options)
        if rung == "dsm":                    # the guard speaks when the map builds its model
            self.search_options.setdefault("guard_rtol", None)
        self.cover = band[1] * 1.05 if band is not None else 0.0
        self.evaluations = self.jumps = self.cliffs = 0
        self.default = robot.equilibrium(pose=pose)
        import scipy.linalg
        self.N = scipy.linalg.null_space(_structure(self.default))
        self.t0 = self.default.tensions

    def evaluate(self, lam: NDArray[np.float64], prev: Equilibrium | None) -> dict[str, Any] | None:
        """Objective, candidates and constraints at lambda (None where no equilibrium)."""
        t_ref = self.t0 + self.N @ lam
        try:
            eq = self.robot.equilibrium(pose=self.pose, tension_reference=t_ref, start=prev)
        except DynstiffError:
            return None
        self.evaluations += 1
        model = build_model(eq, self.rung, **self.search_options).undamped()
        pm = find_platform_modes(model, self.cover)
        if self.objective == "first_global_hz":
            value = pm.first_hz
            k = pm.index[np.asarray(pm.modes.freq_hz)[pm.index] <= value * (1 + _WINDOW)] \
                if pm.complete else np.zeros(0, int)
            v = np.asarray(pm.modes.freq_hz)[k]
        else:
            k, v = _margins(pm, self.band, self.participation)
            value = float(v.min()) if v.size else np.nan
            sel = v <= value + _WINDOW
            k, v = k[sel], v[sel]
        if not np.isfinite(value):
            return None
        return dict(lam=lam, t_ref=t_ref, eq=eq, model=model, pm=pm, value=value, k=k, v=v,
                    shapes=np.asarray(pm.modes.platform_shapes)[k],
                    mass=np.asarray(pm.modes.platform_mass))

    @staticmethod
    def continues(old: dict[str, Any], new: dict[str, Any]) -> bool | None:
        """Whether the mode that set the objective at ``old`` is still a candidate at
        ``new`` (mass-weighted MAC >= 0.5 with one of them): else the objective jumped
        because that mode left the candidates (it turned local by veering with a cable
        mode), not because the robot got stiffer."""
        if not new["k"].size or not old["k"].size:
            return False
        x = old["shapes"][int(np.argmin(old["v"]))]
        M = new["mass"]
        num = (new["shapes"] @ M @ x) ** 2
        den = np.einsum("ki,ij,kj->k", new["shapes"], M, new["shapes"]) * (x @ M @ x)
        with np.errstate(invalid="ignore", divide="ignore"):
            return bool(np.nanmax(num / den) >= 0.5)

    def gradients(self, ev: dict[str, Any]) -> tuple[NDArray[np.float64], ...]:
        """d(candidate)/dlambda (n_k, r) and the tension limits' values and gradients."""
        r = self.N.shape[1]
        params = [Parameter(f"lambda_{j}", float(ev["lam"][j]), "N",
                            {"t_ref": self.N[:, j]}) for j in range(r)]
        lin = LinearisedEquilibrium(ev["eq"], "pose", ev["t_ref"])
        f = np.asarray(ev["pm"].modes.freq_hz)
        sens = sensitivities_at(ev["model"], f[:whole_clusters(f, int(ev["k"].max()) + 1)],
                                params, "pose", ev["t_ref"], lin)
        g = sens.derivative[ev["k"]]
        if self.objective == "band_margin":
            lo, hi = self.band
            above = f[ev["k"]] / hi - 1.0 >= (1.0 - f[ev["k"]] / lo if lo > 0 else -np.inf)
            g = np.where(above[:, None], g / hi, -g / lo if lo > 0 else 0.0)
        dy = lin.derivatives([p.direction for p in params])
        Y, P = lin.perturbed([p.direction for p in params], dy)
        lo_t, hi_t = lin.tension_extremes(Y, P)
        base_lo, base_hi = (np.real(a) for a in lin.tension_extremes(lin.y, lin.P))
        return g, base_lo, np.imag(lo_t).T / CS_STEP, base_hi, np.imag(hi_t).T / CS_STEP

    def step(self, ev: dict[str, Any],
             rho: float) -> tuple[NDArray[np.float64], float, tuple[NDArray[np.float64], ...]]:
        """The linear programme's step d and predicted objective."""
        from scipy.optimize import linprog
        g, lo, dlo, hi, dhi = self.gradients(ev)
        r = self.N.shape[1]
        t_min, t_max = self.robot.tension_limits
        rows, rhs = [np.c_[-g, np.ones(len(g))]], [ev["v"]]
        rows.append(np.c_[-dlo, np.zeros(len(lo))])
        rhs.append(lo - t_min)
        if np.isfinite(t_max):
            rows.append(np.c_[dhi, np.zeros(len(hi))])
            rhs.append(t_max - hi)
        lp = linprog(np.r_[np.zeros(r), -1.0], A_ub=np.vstack(rows),
                     b_ub=np.maximum(np.concatenate(rhs), 0.0),
                     bounds=[(-rho, rho)] * r + [(None, None)], method="highs")
        if lp.status != 0:
            return np.zeros(r), ev["value"], (g, lo, hi)
        return lp.x[:r], -lp.fun, (g, lo, hi)

    def run(self, t_start: NDArray[np.float64] | None, max_iter: int, xtol: float,
            ftol: float = 1e-6) -> OptimalTensions:
        self.xtol = xtol
        r = self.N.shape[1]
        first = self.evaluate(np.zeros(r), None)
        if first is None:
            raise ConvergenceError(
                f"optimal tensions: the platform modes were not all found at the default "
                f"distribution ({self.objective} undefined)")
        if r == 0:
            return self._result(first, first, ("no redundancy: the tension distribution is "
                                               "unique",), 0)
        best = first
        if t_start is not None:
            cand = self.evaluate(self.N.T @ (t_start - self.t0), first["eq"])
            if cand is not None and cand["value"] > best["value"]:
                best = cand
        rho = max(0.1 * float(np.mean(self.t0)), 4 * xtol)
        steps, at, converged = 0, None, False
        while steps < max_iter:
            steps += 1
            d, pred, lin = self.step(best, rho)
            at, gain = best, pred - best["value"]
            if gain <= ftol * max(abs(best["value"]), 1e-3) or rho < xtol:
                converged = True
                break
            new = self.evaluate(best["lam"] + d, best["eq"])
            ratio = -1.0 if new is None else (new["value"] - best["value"]) / gain
            if ratio > _JUMP or (ratio > 0.1 and not self.continues(best, new)):
                # far above the linear model: another mode became the minimum by a jump
                # (the first platform mode crossing a cable mode changes identity)
                self.jumps += 1
                rho *= 0.5
                continue
            if ratio > 0.1:
                best = new
                if ratio > 0.75 and np.abs(d).max() >= 0.99 * rho:
                    rho *= 2.0
                continue
            if ratio < -_JUMP:
                self.cliffs += 1        # a drop far beyond the linear model: a jump down
            rho *= 0.5
            # the linear model overshot: the parabola through the value, the predicted
            # slope and the value at d gives the best fraction of the step
            c = None if new is None else new["value"] - best["value"] - gain
            if c is not None and c < 0:
                alpha = float(np.clip(-gain / (2 * c), 0.05, 0.9))
                mid = self.evaluate(best["lam"] + alpha * d, best["eq"])
                if mid is not None and mid["value"] > best["value"] \
                        and self.continues(best, mid):
                    best = mid
                    rho = alpha * float(np.abs(d).max())
        if at is not best:
            lin = self.step(best, rho)[2]
        _, lo, hi = lin
        return self._result(first, best,
                            self._binds(best, lo, hi, None if converged else steps), steps)

    def _binds(self, ev: dict[str, Any], lo: NDArray[np.float64], hi: NDArray[np.float64],
               stopped: int | None = None) -> tuple[str, ...]:
        """What limits the optimum: tension limits reached, coincident candidate modes, the
        search stopped by ``max_iter`` after ``stopped`` steps before it converged."""
        t_min, t_max = self.robot.tension_limits
        tol = max(self.xtol, 1e-3 * t_min)         # the search stops within xtol of a limit
        out = [f"cable {i} at t_min ({t_min:g} N)" for i in np.flatnonzero(lo - t_min <= tol)]
        out += [f"cable {i} at t_max ({t_max:g} N)" for i in np.flatnonzero(t_max - hi <= tol)]
        near = ev["v"] <= ev["value"] + 1e-4 * max(abs(ev["value"]), 1e-3)
        if near.sum() >= 2:
            pm = ev["pm"]
            out.append("coincident modes at the minimum: "
                       + ", ".join(pm.describe(int(k)) for k in ev["k"][near]))
        if self.jumps:
            out.append(f"the objective jumps next to the optimum ({self.jumps} step(s) where "
                       f"the mode that sets it turns local by veering with a cable mode, or "
                       f"the rise exceeds {_JUMP:g} times the linear prediction); the jump is "
                       f"not followed")
        if self.cliffs:
            out.append(f"the objective drops next to the optimum ({self.cliffs} step(s) fell "
                       f"over {_JUMP:g} times the predicted rise: another mode becomes the "
                       f"first platform mode by veering with a cable mode)")
        if stopped is not None:
            out.append(f"max_iter: the search stopped after {stopped} step(s) before it "
                       f"converged (the objective may rise further)")
        if not out:
            out.append("nothing: a smooth maximum (the objective's gradient vanishes)")
        return tuple(out)

    def _result(self, first: dict[str, Any], best: dict[str, Any], binds: tuple[str, ...],
                iterations: int) -> OptimalTensions:
        return OptimalTensions(
            equilibrium=best["eq"], reference=best["t_ref"], default=self.default,
            objective=self.objective, value=float(best["value"]),
            default_value=float(first["value"]), binds=binds, iterations=iterations,
            evaluations=self.evaluations, platform=best["pm"])


def tension_equilibrium(robot: Robot, pose: list[float] | Pose, tensions: str = "default",
                        start: Equilibrium | None = None, rung: str = "dsm",
                        **model_options: Any) -> Equilibrium:
    """The equilibrium of a map's pose: the default distribution (warm-started from the
    neighbour ``start``), or the frequency-optimal one (:func:`optimal_tensions`, objective
    "first_global_hz", warm-started from the neighbour's tensions).

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> eq = tension_equilibrium(sc.robot, sc.pose, "max-frequency")
    >>> bool(eq.min_tensions.min() >= 100.0 - 1e-6)
    True
    """
    if tensions not in TENSIONS:
        raise InvalidParameterError(f"tensions must be one of {TENSIONS}, got {tensions!r}")
    if tensions == "default":
        return robot.equilibrium(pose=pose, start=start)
    return optimal_tensions(robot, pose, rung=rung, start=start, **model_options).equilibrium
