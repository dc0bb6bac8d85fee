"""Natural frequencies of a closed-form model started from those of a neighbouring pose
(a workspace map or a sweep moves the platform in steps): Wittrick-Williams counts certify
every bracket, so no mode is missed (docs/theory.md §5.1, §13.4).

The neighbour's lowest frequencies omega'_1 < ... < omega'_n give seed points
b_r = sqrt(omega'_r omega'_{r+1}) between them, b_0 = omega'_1 / (1 + delta) and
b_n = omega'_n (1 + delta). One vectorised count J(b) brackets every root r between the
highest seed with J <= r - 1 and the lowest with J >= r; near the neighbour these brackets
hold one root each at once, farther away the count bisection of
:func:`dynstiff.eigen.eigenfrequencies` goes on from them (from [0, omega_hi] without
seeds). A bracket that also holds a cable pole is bisected on the count only until the pole
is out (down to ``rtol`` for a root on the pole); every root is then polished by Illinois
regula falsi on the eigenvalue of K(omega) that crosses zero.
"""

import numpy as np

from .eigen import mode_count
from .errors import ConvergenceError

__all__ = ["eigenfrequencies_near"]

_TWO_PI = 2.0 * np.pi
_DELTA = 0.05         # relative room below the first and above the last previous frequency


def _crossing(m, omega, index):
    """Eigenvalue number ``index`` (ascending) of the real symmetric K(omega), shape (n,)."""
    K = np.real(m.dynamic_stiffness(omega))
    ev = np.linalg.eigvalsh(0.5 * (K + np.swapaxes(K, 1, 2)))
    return ev[np.arange(len(omega)), index]


def _illinois(m, lo, hi, index, rtol, max_iter=100):
    """Illinois regula falsi on the decreasing crossing eigenvalue in pole-free isolated
    brackets [lo, hi] [rad/s], each estimate x evaluated at x -/+ 0.45 rtol hi: once the
    two straddle the root, the bracket is below rtol (regula falsi alone keeps one end
    and closes the other slowly). Bisection where an update leaves the bracket."""
    n = len(lo)
    f_lo = _crossing(m, lo, index)
    f_hi = _crossing(m, hi, index)
    side = np.zeros(n, dtype=int)
    for _ in range(max_iter):
        act = hi - lo > rtol * hi
        if not np.any(act):
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        bad = ~np.isfinite(x) | (x <= lo) | (x >= hi)
        x = np.where(bad, 0.5 * (lo + hi), x)
        d = 0.45 * rtol * hi
        a = np.clip(x - d, lo, hi)
        b = np.clip(x + d, lo, hi)
        fa, fb = np.split(_crossing(m, np.concatenate([a, b]), np.tile(index, 2)), 2)
        # the new bracket: the highest point with f >= 0 and the lowest with f < 0
        new_lo = np.where(fb >= 0, b, np.where(fa >= 0, a, lo))
        nf_lo = np.where(fb >= 0, fb, np.where(fa >= 0, fa, f_lo))
        new_hi = np.where(fa < 0, a, np.where(fb < 0, b, hi))
        nf_hi = np.where(fa < 0, fa, np.where(fb < 0, fb, f_hi))
        moved_lo, moved_hi = new_lo != lo, new_hi != hi
        # Illinois: halve the kept end's value when the same end moved twice running
        nf_hi = np.where(moved_lo & ~moved_hi & (side == 1), 0.5 * nf_hi, nf_hi)
        nf_lo = np.where(moved_hi & ~moved_lo & (side == -1), 0.5 * nf_lo, nf_lo)
        side = np.where(moved_lo & ~moved_hi, 1, np.where(moved_hi & ~moved_lo, -1, 0))
        zero = (fa == 0) | (fb == 0)
        root = np.where(fa == 0, a, b)
        lo = np.where(act, np.where(zero, root, new_lo), lo)
        hi = np.where(act, np.where(zero, root, new_hi), hi)
        f_lo = np.where(act, nf_lo, f_lo)
        f_hi = np.where(act, nf_hi, f_hi)
    return 0.5 * (lo + hi)


def _brackets(m, n, rtol, seeds=None):
    """Wittrick-Williams bracketing of the lowest n roots [rad/s]: counts at the ``seeds``
    (if any) give the first brackets, then bisection on the count until each bracket holds
    exactly one root (or is narrower than rtol: a multiple root). Returns lo, hi and the
    isolated mask."""
    r = np.arange(1, n + 1)
    lo, hi = np.zeros(n), np.zeros(n)
    J_lo, J_hi = np.zeros(n, dtype=int), np.zeros(n, dtype=int)
    todo = np.ones(n, dtype=bool)                 # roots without an upper seed
    w_hi = _TWO_PI
    if seeds is not None and seeds.size:
        J = mode_count(m, seeds)
        for k in range(n):
            below = np.flatnonzero(J <= k)
            if below.size:
                lo[k], J_lo[k] = seeds[below[-1]], J[below[-1]]
            above = np.flatnonzero(J >= k + 1)
            if above.size:
                hi[k], J_hi[k] = seeds[above[0]], J[above[0]]
                todo[k] = False
        w_hi = seeds[-1]
    if np.any(todo):
        while (J_top := mode_count(m, w_hi)[0]) < n:
            w_hi *= 2.0
            if w_hi > 1e8:
                raise ConvergenceError(f"fewer than {n} modes below {w_hi:.3g} rad/s")
        hi[todo], J_hi[todo] = w_hi, J_top
    while True:
        isolated = (J_lo == r - 1) & (J_hi == r)
        width = hi - lo
        if np.all(isolated | (width <= rtol * hi)):
            return lo, hi, isolated
        act = ~isolated & (width > rtol * hi)
        mid = 0.5 * (lo[act] + hi[act])
        u, inv = np.unique(mid, return_inverse=True)
        J = mode_count(m, u)[inv]
        above = J >= r[act]
        idx = np.flatnonzero(act)
        hi[idx[above]], J_hi[idx[above]] = mid[above], J[above]
        lo[idx[~above]], J_lo[idx[~above]] = mid[~above], J[~above]


def _polish(m, lo, hi, isolated, rtol):
    """Roots [rad/s] in isolated brackets: bisection on the count while a cable pole shares
    the bracket (to rtol for a root on the pole), then Illinois on the crossing eigenvalue;
    other brackets (multiple roots, already narrower than rtol) give their midpoint."""
    r = np.arange(1, lo.size + 1)
    lo, hi = lo.copy(), hi.copy()
    while True:
        poled = isolated & (m.cable_mode_count(lo) != m.cable_mode_count(hi))
        act = poled & (hi - lo > rtol * hi)
        if not np.any(act):
            break
        mid = 0.5 * (lo[act] + hi[act])
        above = mode_count(m, mid) >= r[act]
        idx = np.flatnonzero(act)
        hi[idx[above]] = mid[above]
        lo[idx[~above]] = mid[~above]
    out = 0.5 * (lo + hi)
    free = isolated & ~poled & (hi - lo > rtol * hi)
    if np.any(free):
        index = (r[free] - 1) - m.cable_mode_count(lo[free])
        out[free] = _illinois(m, lo[free], hi[free], index, rtol)
    return out


def eigenfrequencies_near(model, n_modes, previous_hz=None, rtol=1e-12):
    """The lowest ``n_modes`` natural frequencies [Hz] of a closed-form model, none missed.

    Parameters
    ----------
    model : model with ``dynamic_stiffness`` and ``cable_mode_count`` (the "dsm" rung)
    n_modes : int
    previous_hz : array_like, shape (n_modes,), optional
        The lowest frequencies [Hz] of a neighbouring pose (or of the same robot with a
        nearby parameter), ascending: candidate brackets, kept only if the counts certify
        them.
    rtol : float
        Relative width of the final bracket (as :func:`dynstiff.eigen.eigenfrequencies`).

    Returns
    -------
    ndarray, shape (n_modes,) [Hz]
    """
    m = model.undamped()
    n = int(n_modes)
    seeds = None
    f = None if previous_hz is None else np.asarray(previous_hz, dtype=float).ravel()
    if f is not None and f.size and np.all(np.isfinite(f)) and np.all(f > 0):
        w = np.unique(_TWO_PI * f)
        seeds = np.concatenate([[w[0] / (1 + _DELTA)], np.sqrt(w[:-1] * w[1:]),
                                [w[-1] * (1 + _DELTA)]])
    lo, hi, isolated = _brackets(m, n, rtol, seeds)
    return _polish(m, lo, hi, isolated, rtol) / _TWO_PI
