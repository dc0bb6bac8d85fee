"""Complete eigenfrequencies of the robot by Wittrick-Williams counting, and its modes.

K(omega) is transcendental with poles at every cable's clamped-clamped frequencies, so a sign
scan of det K finds poles as well as roots and misses close pairs. The Wittrick-Williams count
(Wittrick & Williams 1971; theory.md §5)

    J(omega) = J0(omega) + s{K(omega)}

(J0: clamped-cable frequencies below omega, s: negative eigenvalues of K) is the exact number
of natural frequencies below omega. The r-th frequency is bracketed by bisection on J, all
roots at once (one batched evaluation of K per step), until the bracket holds that root alone
and no cable pole; the eigenvalue of K that crosses zero there is then refined by a vectorised
Illinois (regula falsi) iteration to a relative bracket width of ``rtol``. Multiple roots and
roots on a cable pole are bisected to ``rtol``. This never misses a root, handles coincident
roots, and finds purely local cable modes, which are not zeros of det K.

Every function here takes a model of any rung (:mod:`dynstiff.models.base`). A discrete rung
(one with ``matrices()``: "spring", "catenary", "lumped") is solved by default as the finite
eigenproblem K phi = omega^2 M phi (:mod:`dynstiff.analyses.eigen_matrix`); the Wittrick-Williams
search works for every rung (``method="wittrick-williams"``), which is how the two are
checked against each other.
"""

from __future__ import annotations

from numbers import Integral, Real
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import compiled
from dynstiff._validate import MAX_OMEGA, omega_array
from dynstiff.analyses import eigen_matrix
from dynstiff.cable.psi import check_frequency_range
from dynstiff.errors import ConvergenceError, InvalidParameterError, UnsupportedAnalysisError
from dynstiff.models.base import require_model
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.dsm_compiled import compiled_arguments
from dynstiff.results import ModalResult

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.base import PlatformModel

__all__ = ["eigenfrequencies", "mode_count", "ModalResult", "METHODS"]

_TWO_PI = 2.0 * np.pi
#: Eigen solvers: "auto" (the matrix solver for discrete rungs, W-W otherwise), "matrix",
#: "wittrick-williams".
METHODS = ("auto", "matrix", "wittrick-williams")


def _real_symmetric(K: NDArray[np.float64]) -> NDArray[np.float64]:
    """Symmetric real part of a stack of K(omega), shape (n, nf, nf)."""
    K = K.real if np.iscomplexobj(K) else K
    return 0.5 * (K + np.swapaxes(K, -1, -2))


def validated_request(n_modes: int | None,
                      fmax_hz: float | None) -> tuple[int | None, float | None]:
    """Check ``n_modes`` (integer >= 1 or None) and ``fmax_hz`` (finite > 0 or None), one
    given at least; returns them as (int or None, float or None)."""
    if n_modes is None and fmax_hz is None:
        raise InvalidParameterError("give n_modes or fmax_hz (or both)")
    if n_modes is not None:
        if isinstance(n_modes, bool) or not isinstance(n_modes, Integral) or n_modes < 1:
            raise InvalidParameterError(f"n_modes must be an integer >= 1, got {n_modes!r}")
        n_modes = int(n_modes)
    if fmax_hz is not None:
        try:
            f = float(fmax_hz) if isinstance(fmax_hz, Real) and not isinstance(fmax_hz, bool) \
                else np.nan
        except OverflowError:                        # an integer beyond float range
            f = np.inf
        if not np.isfinite(f) or f <= 0:
            raise InvalidParameterError(f"fmax_hz must be finite and > 0 [Hz], got {fmax_hz!r}")
        if _TWO_PI * f > MAX_OMEGA:
            raise InvalidParameterError(
                f"fmax_hz must be <= {MAX_OMEGA / _TWO_PI:.6g} Hz (omega^2 times a mass must "
                f"stay finite), got {fmax_hz!r}")
        fmax_hz = f
    return n_modes, fmax_hz


def checked_method(model: PlatformModel, method: str) -> str:
    require_model(model)
    if method not in METHODS:
        raise InvalidParameterError(f"method must be one of {METHODS}, got {method!r}")
    discrete = hasattr(model, "matrices")
    if method == "matrix" and not discrete:
        raise UnsupportedAnalysisError(
            f"method='matrix' needs a discrete rung ('spring', 'catenary', 'lumped'); the "
            f"{model.rung!r} model has no finite matrices: use 'wittrick-williams'")
    if method == "auto":
        return "matrix" if discrete else "wittrick-williams"
    return method


def mode_count(model: PlatformModel, omega: ArrayLike) -> NDArray[np.int64]:
    """Wittrick-Williams count J(omega) = J0(omega) + s{K(omega)}: the number of natural
    frequencies of the undamped model strictly below omega (theory.md §5.1).

    Parameters
    ----------
    model : model of any rung
    omega : float or array_like, shape (n_omega,)
        [rad/s], >= 0.

    Returns
    -------
    ndarray of int, shape (n_omega,)

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> f = ds.eigenfrequencies(m, n_modes=2)
    >>> ds.mode_count(m, 2 * np.pi * np.array([0.5, 1.01]) * f[1]).tolist()   # below and above f[1]
    [0, 2]
    """
    return _count(require_model(model).undamped(), omega)[0]


def _count(
        m: PlatformModel, omega: NDArray[np.float64] | float,
) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.int64]]:
    """W-W count of the undamped model ``m`` at omega (n,) [rad/s]: (J, ev, J0) with the
    ascending eigenvalues ev (n, n_free) of sym K(omega) and the cable count J0 (n,)."""
    return _counter(m)(omega)


def _counter(m: PlatformModel) -> Callable[..., Any]:
    """The function omega (n,) [rad/s] -> (J, ev, J0) of :func:`_count` for the undamped
    model ``m``, with the cable kernels evaluated once per frequency: the compiled kernel of
    the "dsm" rung when numba is installed, else ``dynamic_stiffness_and_count`` where the
    model has it, else K(omega) and the model's cable count (theory.md §14.2)."""
    fast = compiled.load("dsm")
    # exactly the closed-form class: a subclass may change the cable kernels
    if fast is not None and type(m) is FrequencyModel and not m.damped:
        args = compiled_arguments(m)

        def checked(omega: NDArray[np.float64] | float) -> NDArray[np.float64]:
            omega = omega_array(omega)
            check_frequency_range(m.stacked_params, omega)
            m.guard_band(omega)
            return omega

        def count(
                omega: NDArray[np.float64] | float,
        ) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.int64]] | None:
            ev, J0 = fast.dsm_count(checked(omega), *args)
            return J0 + np.sum(ev < 0, axis=1), ev, J0

        def search(grid: NDArray[np.float64], J: NDArray[np.int64], det: NDArray[np.float64],
                   J0: NDArray[np.int64], N: int, rtol: float,
                   max_iter: int = 200) -> NDArray[np.float64]:
            # every frequency of the search lies in [0, grid[-1]], checked by count(grid);
            # det: det K on the grid where :func:`counts` knew it (NaN elsewhere)
            J, J0 = J.copy(), J0.copy()
            J[0] = J0[0] = 0
            roots, failed, width = compiled.load("dsm_search").dsm_search(
                grid, J, J0, np.asarray(det, dtype=float), N, rtol, max_iter, *args)
            if failed >= 0:
                raise ConvergenceError(
                    f"the regula falsi left the bracket of root {failed + 1} wider than rtol = "
                    f"{rtol:g} after {max_iter} steps", residual=width)
            return roots

        def counts(omega: NDArray[np.float64]) -> tuple[NDArray[Any], ...]:
            # (J, J0, det K) without the eigenvalues (the search needs none): the pivots
            return compiled.load("dsm_search").dsm_counts(checked(omega), *args)
        count.search = search                       # type: ignore[attr-defined]
        count.counts = counts                       # type: ignore[attr-defined]
        return count

    def count(
            omega: NDArray[np.float64] | float,
    ) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.int64]]:
        if hasattr(m, "dynamic_stiffness_and_count"):
            K, J0 = m.dynamic_stiffness_and_count(omega)
        else:
            K, J0 = m.dynamic_stiffness(omega), m.cable_mode_count(omega)
        with np.errstate(invalid="ignore"):
            ev = np.linalg.eigvalsh(_real_symmetric(K))
        return J0 + np.sum(ev < 0, axis=1), ev, J0
    return count


def eigenfrequencies(model: PlatformModel, n_modes: int | None = None, fmax_hz: float | None = None,
                     rtol: float = 1e-12, method: str = "auto",
                     max_modes: int = 20000) -> NDArray[np.float64]:
    """Natural frequencies [Hz] of the undamped robot, ascending, none missed.

    Parameters
    ----------
    model : model of any rung (:mod:`dynstiff.models.base`)
    n_modes : int, optional
        Number of lowest frequencies wanted (>= 1).
    fmax_hz : float, optional
        All frequencies below this [Hz]. Give ``n_modes`` or ``fmax_hz`` (or both: the first
        ``n_modes`` below ``fmax_hz``).
    rtol : float
        Relative width of the final Wittrick-Williams bracket, in (0, 1e-2) (default 1e-12).
    method : {"auto", "matrix", "wittrick-williams"}
        "auto": the finite eigenproblem for discrete rungs, W-W otherwise.
    max_modes : int
        Largest number of frequencies computed (a guard on the time and memory that a large
        ``fmax_hz`` or ``n_modes`` would ask for); the error says how many were asked.

    Returns
    -------
    ndarray, shape (n,) [Hz]
        With damped cables, the frequencies of the undamped system. A discrete rung at an
        unstable equilibrium reports a negative eigenvalue lambda as -sqrt(-lambda) / 2 pi.

    Raises
    ------
    InvalidParameterError
        Bad ``n_modes``, ``fmax_hz``, ``rtol`` or ``method``; ``n_modes`` larger than a
        discrete rung's number of DOFs (by either method); ``n_modes`` more than a model's
        band holds (``max_omega``, the exact rung), also when that band ends at the
        search's cap of 1e8 rad/s.

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> [f"{f:.4f}" for f in ds.eigenfrequencies(m, n_modes=3)]
    ['2.2061', '2.3592', '2.9907']
    """
    n_modes, fmax_hz = validated_request(n_modes, fmax_hz)
    if not (isinstance(rtol, Real) and 0 < rtol < 1e-2):
        raise InvalidParameterError(f"rtol must be a number in (0, 1e-2), got {rtol!r}")
    if isinstance(max_modes, bool) or not isinstance(max_modes, Integral) or max_modes < 1:
        raise InvalidParameterError(f"max_modes must be an integer >= 1, got {max_modes!r}")
    if n_modes is not None and n_modes > max_modes:
        raise InvalidParameterError(
            f"n_modes = {n_modes} is more than max_modes = {max_modes}; raise max_modes to "
            f"compute them")
    if checked_method(model, method) == "matrix":
        f = eigen_matrix.eigenfrequencies(model.undamped(), n_modes, fmax_hz)
        if f.size > max_modes:
            raise InvalidParameterError(
                f"fmax_hz = {fmax_hz:g} Hz holds {f.size} modes, more than max_modes = "
                f"{max_modes}; lower fmax_hz or raise max_modes")
        return f
    m = model.undamped()
    n_dof = getattr(m, "n_dof", None)              # a discrete rung holds n_dof modes
    if n_modes is not None and fmax_hz is None and n_dof is not None and n_modes > n_dof:
        raise InvalidParameterError(
            f"n_modes must be an integer in [1, {n_dof}] (the number of DOFs of the "
            f"{m.rung!r} model), got {n_modes!r}")
    count = _counter(m)
    search = getattr(count, "search", None)         # the compiled search ("dsm" rung)
    counts = getattr(count, "counts", None)          # its counts, without the eigenvalues

    def at(omega: NDArray[np.float64] | float) -> tuple[Any, ...]:
        """(J, ev, J0) at omega; for the compiled search det K in place of ev (it needs no
        eigenvalue, and starts its regula falsi from det K where the counts knew it)."""
        if counts is None:
            return count(omega)
        J, J0, det = counts(omega)
        return J, det, J0
    if fmax_hz is not None:
        w_hi = _TWO_PI * fmax_hz
        try:
            grid = _seed_grid(m, w_hi)
            J, ev, J0 = at(grid)
        except InvalidParameterError as exc:
            raise InvalidParameterError(
                f"fmax_hz = {fmax_hz:g} Hz is out of the {m.rung!r} model's range: {exc}"
            ) from None
        N = int(J[-1])
        if N > max_modes and (n_modes is None or n_modes > max_modes):
            raise InvalidParameterError(
                f"fmax_hz = {fmax_hz:g} Hz holds {N} modes, more than max_modes = "
                f"{max_modes}; lower fmax_hz or raise max_modes")
        if n_modes is not None:
            N = min(N, n_modes)
    else:
        N = n_modes
        w_top = getattr(m, "max_omega", np.inf)           # a model's band (exact rung)
        w_hi = min(_TWO_PI, w_top)
        while at(w_hi)[0][0] < N:
            if w_hi >= w_top:
                raise InvalidParameterError(
                    f"n_modes = {N} asks for more than the {m.rung!r} model's band holds "
                    f"({int(at(w_top)[0][0])} modes below {w_top / _TWO_PI:g} Hz); "
                    f"build it with a larger fmax_hz")
            w_hi = min(2.0 * w_hi, w_top)
            if w_hi > 1e8:
                raise ConvergenceError(f"fewer than {N} modes below {w_hi:.3g} rad/s")
        grid = _seed_grid(m, w_hi)
        J, ev, J0 = at(grid)
    if N == 0:
        return np.zeros(0)
    if search is not None:
        return search(grid, J, ev, J0, N, rtol) / _TWO_PI
    return _search(count, N, grid, J, ev, J0, rtol) / _TWO_PI


def _seed_grid(m: PlatformModel, w_hi: float, n_uniform: int = 64) -> NDArray[np.float64]:
    """Frequencies [rad/s] at which the count is first evaluated, ascending from 0 to w_hi:
    a uniform grid and the massless-cable frequencies (near which the global modes lie),
    each with a neighbour 1e-3 above (theory.md §14.2)."""
    try:
        lam = eigen_matrix.massless_modes(m)[0]
    except (np.linalg.LinAlgError, ValueError):
        lam = np.zeros(0)
    w0 = np.sqrt(lam[(lam > 0) & (lam < w_hi**2)])
    pts = np.concatenate([np.linspace(0.0, w_hi, n_uniform + 1)[1:], w0, w0 * (1 + 1e-3)])
    return np.unique([0.0] + pts[(pts > 0) & (pts < w_hi)].tolist() + [w_hi])


def _search(count: Callable[..., Any], N: int, grid: NDArray[np.float64], J_grid: NDArray[np.int64],
            ev_grid: NDArray[np.float64], J0_grid: NDArray[np.int64],
            rtol: float) -> NDArray[np.float64]:
    """The N lowest roots [rad/s] from the counts (``count``, :func:`_counter`) on ``grid``
    (theory.md §5, §14.2).

    Each root r gets the tightest grid bracket with J(lo) < r <= J(hi). Brackets are bisected
    on the count, all at once (one batched evaluation per step), until each holds one simple
    root and no cable pole; those go to the Illinois iteration on the eigenvalue of K that
    crosses zero, started from the end values the count already gave. Multiple roots and
    roots on a cable pole keep bisecting to ``rtol``.
    """
    r = np.arange(1, N + 1)
    # grid[0] = 0, where J = 0: a stable equilibrium has no root at or below 0
    J_grid, J0_grid = J_grid.copy(), J0_grid.copy()
    J_grid[0] = J0_grid[0] = 0
    i_hi = np.searchsorted(J_grid, r, side="left")          # first point with J >= r
    i_lo = i_hi - 1
    lo, hi = grid[i_lo], grid[i_hi]
    J_lo, J_hi = J_grid[i_lo], J_grid[i_hi]
    J0_lo, J0_hi = J0_grid[i_lo], J0_grid[i_hi]
    ev_lo, ev_hi = ev_grid[i_lo], ev_grid[i_hi]
    while True:
        isolated = (J_lo == r - 1) & (J_hi == r) & (J0_lo == J0_hi)
        act = ~isolated & (hi - lo > rtol * hi)
        if not np.any(act):
            break
        mid = 0.5 * (lo[act] + hi[act])
        u, inv = np.unique(mid, return_inverse=True)
        Ju, evu, J0u = count(u)
        J, ev, J0 = Ju[inv], evu[inv], J0u[inv]
        above = J >= r[act]
        idx = np.flatnonzero(act)
        up, dn = idx[above], idx[~above]
        hi[up], J_hi[up], J0_hi[up], ev_hi[up] = mid[above], J[above], J0[above], ev[above]
        lo[dn], J_lo[dn], J0_lo[dn], ev_lo[dn] = mid[~above], J[~above], J0[~above], ev[~above]
    out = 0.5 * (lo + hi)
    if np.any(isolated):
        k = np.flatnonzero(isolated)
        idx = J_lo[k] - J0_lo[k]
        f_lo = ev_lo[k, idx]
        f_hi = ev_hi[k, idx]
        out[k] = _illinois(count, lo[k], hi[k], idx, f_lo, f_hi, rtol)
    return out


def _illinois(count: Callable[..., Any], lo: NDArray[np.float64], hi: NDArray[np.float64],
              idx: NDArray[np.int64], f_lo: NDArray[np.float64], f_hi: NDArray[np.float64],
              rtol: float, max_iter: int = 200) -> NDArray[np.float64]:
    """Vectorised Illinois regula falsi on the eigenvalue of K that crosses zero in [lo, hi].

    In an isolated bracket without cable poles, s{K} goes from s_lo = J_lo - J0 to s_lo + 1,
    so eigenvalue number idx = s_lo (ascending) goes from f_lo >= 0 to f_hi < 0, decreasing
    (W-W monotonicity). Falls back to bisection where the update leaves the bracket, and
    where the bracket has not halved in three steps (a strongly curved function keeps regula
    falsi creeping from one end), so that the width halves at least every fourth step. Each
    iterate x comes with a second point 0.45 rtol hi from it towards the far end of the
    bracket, in the same batched evaluation: once x is within that distance of the root the
    pair brackets it and the bracket closes to rtol at once. When the same end moves twice,
    the retained end's value is scaled by the Anderson-Bjorck factor (theory.md §14.2). Only
    the brackets still wider than rtol are evaluated. Returns roots [rad/s].

    Raises
    ------
    ConvergenceError
        A bracket still wider than rtol after ``max_iter`` steps (with its width).
    """
    lo, hi, f_lo, f_hi = (np.array(v, dtype=float) for v in (lo, hi, f_lo, f_hi))
    side = np.zeros(len(lo), dtype=int)
    stall = np.zeros(len(lo), dtype=int)          # steps since the bracket last halved
    for _ in range(max_iter):
        act = np.flatnonzero(hi - lo > rtol * hi)
        if not act.size:
            break
        L, H, FL, FH, S = lo[act], hi[act], f_lo[act], f_hi[act], side[act]
        width = H - L
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (L * FH - H * FL) / (FH - FL)
        bad = ~np.isfinite(x) | (x <= L) | (x >= H) | (stall[act] >= 3)
        x = np.where(bad, 0.5 * (L + H), x)
        step = np.where(H - x > x - L, 1.0, -1.0) * 0.45 * rtol * H
        x2 = np.clip(x + step, np.nextafter(L, H), np.nextafter(H, L))
        ev = count(np.concatenate([x, x2]))[1]
        k = np.concatenate([idx[act], idx[act]])
        fx, fx2 = np.split(ev[np.arange(k.size), k], 2)
        a, b = np.minimum(x, x2), np.maximum(x, x2)
        fa, fb = np.where(x <= x2, fx, fx2), np.where(x <= x2, fx2, fx)
        up = fb >= 0                            # both points below the root: lo moves
        dn = fa < 0                             # both above: hi moves
        mid = ~up & ~dn                         # the pair brackets the root
        # Anderson-Bjorck: when the same end moves twice, scale the retained end's value
        # by 1 - f_new / f_replaced (by 1/2 where that is not in (0, 1))
        with np.errstate(divide="ignore", invalid="ignore"):
            g_up, g_dn = 1.0 - fb / FL, 1.0 - fa / FH
        g_up = np.where((g_up > 0) & (g_up < 1), g_up, 0.5)
        g_dn = np.where((g_dn > 0) & (g_dn < 1), g_dn, 0.5)
        FH = np.where(up & (S == 1), g_up * FH, FH)
        FL = np.where(dn & (S == -1), g_dn * FL, FL)
        L, FL = np.where(up, b, L), np.where(up, fb, FL)
        H, FH = np.where(dn, a, H), np.where(dn, fa, FH)
        L, FL = np.where(mid, a, L), np.where(mid, fa, FL)
        H, FH = np.where(mid, b, H), np.where(mid, fb, FH)
        S = np.where(up, 1, np.where(dn, -1, 0))
        zero = (fa == 0) | (fb == 0)
        xz = np.where(fa == 0, a, b)
        L, H = np.where(zero, xz, L), np.where(zero, xz, H)
        lo[act], hi[act], f_lo[act], f_hi[act], side[act] = L, H, FL, FH, S
        stall[act] = np.where(H - L <= 0.5 * width, 0, stall[act] + 1)
    else:
        wide = hi - lo > rtol * hi
        if np.any(wide):
            k = int(np.flatnonzero(wide)[0])
            raise ConvergenceError(
                f"the regula falsi left the bracket [{lo[k]:.12g}, {hi[k]:.12g}] rad/s wider "
                f"than rtol = {rtol:g} after {max_iter} steps", residual=(hi[k] - lo[k]) / hi[k])
    return 0.5 * (lo + hi)


