"""Elastic catenaries of many cables at once, for prescribed end tensions (inverse statics).

For each cable the unknowns (H, V0, L0) solve the three equations (docs/theory.md §13.1)::

    x(H, V0, L0) = l_h,    z(H, V0, L0) = h,    T_B(H, V0, L0) = sqrt(H^2 + Vb^2) = t

with x, z the end offsets of the exact elastic catenary (docs/theory.md §1.1; notation of
:mod:`dynstiff.cable.catenary`: w0 weight per unstretched length, W = w0 L0, Vb = V0 + W). One
Newton iteration on all cables together costs a handful of array operations; the Jacobian is
analytic::

    dx/dL0 = H/EA + H/T_B,   dz/dL0 = Vb/EA + Vb/T_B,
    dT_B/dH = H/T_B,   dT_B/dV0 = Vb/T_B,   dT_B/dL0 = w0 Vb/T_B,

and d(x, z)/d(H, V0) is the in-plane flexibility of :mod:`dynstiff.cable.catenary`, its differences
of asinh and sqrt written without cancellation. Of the two lengths with the same end tension
(taut, and hanging deeper), the taut one is kept: the tension falls as L0 grows at fixed ends,
dT_B/dL0 (total) < 0. A cable that does not converge, lands on the other branch, is exactly
vertical or weightless is handed to the scalar bracketing solver
:func:`dynstiff.cable.catenary_solve.unstretched_length_for_tension`, which also says why a tension
cannot be reached.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff import compiled as compiled_kernels
from dynstiff.cable.catenary import CatenaryState, divided_differences
from dynstiff.cable.catenary_solve import unstretched_length_for_tension

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.params import Cable

__all__ = ["catenary_arrays", "sag_ratios", "states_for_tensions", "taut_catenaries"]

_RTOL = 1e-13          # relative residual of the three equations at convergence
_MAX_ITER = 40


def _equations(H: NDArray[np.float64], V0: NDArray[np.float64], L0: NDArray[np.float64],
               EA: NDArray[np.float64], w0: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """End offsets (x, z) [m], end tension T_B [N] and the 3x3 Jacobian with respect to
    (H, V0, L0), shape (n, 3, 3)."""
    W = w0 * L0
    Vb = V0 + W
    a, b, delta = V0 / H, Vb / H, W / H
    d_asinh, d_f, d_g, d_sqrt = divided_differences(a, b, delta)
    x = L0 * (H / EA + d_asinh)
    z = L0 * ((V0 + 0.5 * W) / EA + d_sqrt)
    T = np.hypot(H, Vb)
    J = np.empty(H.shape + (3, 3))
    J[:, 0, 0] = L0 / EA + (L0 / H) * (d_asinh - d_f)
    J[:, 0, 1] = J[:, 1, 0] = (L0 / H) * d_g
    J[:, 1, 1] = L0 / EA + (L0 / H) * d_f
    J[:, 0, 2] = H / EA + H / T
    J[:, 1, 2] = Vb / EA + Vb / T
    J[:, 2, 0] = H / T
    J[:, 2, 1] = Vb / T
    J[:, 2, 2] = w0 * Vb / T
    return x, z, T, J


def _straight_start(lh: NDArray[np.float64], h: NDArray[np.float64], L: NDArray[np.float64],
                    t: NDArray[np.float64], EA: NDArray[np.float64],
                    w0: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """(H, V0, L0) of a straight elastic cable with tension t along its chord (the weight
    taken off at A)."""
    L0 = L / (1.0 + t / EA)
    Vb = t * h / L
    return t * lh / L, Vb - w0 * L0, L0


def _newton(
        lh: NDArray[np.float64], h: NDArray[np.float64], L: NDArray[np.float64],
        t: NDArray[np.float64], EA: NDArray[np.float64], w0: NDArray[np.float64],
        H: NDArray[np.float64], V0: NDArray[np.float64], L0: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_],
           NDArray[np.float64]]:
    """Newton on (H, V0, L0) for all cables; returns them and a mask of the converged
    taut solutions."""
    scale = np.stack([lh, np.maximum(L, L0), t], axis=1)
    target = np.stack([lh, h, t], axis=1)
    ok = np.zeros(H.shape, dtype=bool)
    for _ in range(_MAX_ITER):
        x, z, T, J = _equations(H, V0, L0, EA, w0)
        r = np.stack([x, z, T], axis=1) - target
        res = np.max(np.abs(r) / scale, axis=1)
        ok = res <= _RTOL
        if np.all(ok | ~np.isfinite(res)):
            break
        try:
            step = np.linalg.solve(J, -r[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            break
        # keep H and L0 positive: at most a tenfold reduction per step
        H = np.where(ok, H, np.maximum(H + step[:, 0], 0.1 * H))
        V0 = np.where(ok, V0, V0 + step[:, 1])
        L0 = np.where(ok, L0, np.maximum(L0 + step[:, 2], 0.1 * L0))
    else:
        x, z, T, J = _equations(H, V0, L0, EA, w0)
        r = np.stack([x, z, T], axis=1) - target
        res = np.max(np.abs(r) / scale, axis=1)
        ok = res <= _RTOL
    # taut branch: dT/dL0 at fixed ends, T_L - [T_H, T_V] F^-1 [x_L, z_L], is negative
    F, c = J[:, :2, :2], J[:, :2, 2]
    det = F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0]
    y0 = (F[:, 1, 1] * c[:, 0] - F[:, 0, 1] * c[:, 1]) / det
    y1 = (F[:, 0, 0] * c[:, 1] - F[:, 1, 0] * c[:, 0]) / det
    dT_dL0 = J[:, 2, 2] - J[:, 2, 0] * y0 - J[:, 2, 1] * y1
    ok &= np.isfinite(res) & (dT_dL0 < 0) & (H > 0) & (L0 > 0)
    return H, V0, L0, ok, res


def _solve(compiled: Callable[..., Any], args: tuple[NDArray[np.float64], ...],
           guess: tuple[NDArray[np.float64], ...]) -> list[NDArray[Any]] | None:
    """(H, V0, L0, ok, residual) of Newton from ``guess``: compiled or numpy."""
    if compiled is not None:
        return list(compiled(*args, *guess, _RTOL, _MAX_ITER))
    with np.errstate(all="ignore"):       # a diverging cable shows as non-finite, not ok
        return list(_newton(*args, *guess))


def taut_catenaries(
        anchors: NDArray[np.float64], ends: NDArray[np.float64], tensions: NDArray[np.float64],
        EA: NDArray[np.float64], w0: NDArray[np.float64],
        start: tuple[NDArray[np.float64], ...] | None = None, compiled: bool = True,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
           NDArray[np.bool_]]:
    """(H, V0, L0) of every cable with tension ``tensions`` at its end B (taut branch).

    Inputs are taken as valid (finite, ends distinct from anchors, tensions > 0): the
    robot and its pose were checked once before.

    Parameters
    ----------
    anchors, ends : ndarray, shape (n, 3)
        A_i and B_i [m], z up.
    tensions : ndarray, shape (n,)
        Tension at B [N].
    EA : ndarray, shape (n,)
        Axial stiffness [N].
    w0 : ndarray, shape (n,)
        Weight per unstretched length [N/m].
    start : tuple of three ndarray, shape (n,), optional
        (H, V0, L0) to start Newton from (the previous outer iteration or a neighbouring
        pose); default the straight elastic cable with the prescribed tension.
    compiled : bool
        Use the compiled Newton (:mod:`dynstiff.compiled.catenary`, equal to round-off) when
        numba is installed; False: the numpy Newton (the reference).

    Returns
    -------
    H, V0, L0 : ndarray, shape (n,)
        [N, N, m]; the entries of ``pending`` are not solved (NaN).
    residual : ndarray, shape (n,)
        Largest relative residual of the three equations [-] (NaN where pending).
    pending : ndarray of bool, shape (n,)
        Cables left to the scalar solver: exactly vertical or weightless, or not converged
        to the taut branch from this start.
    """
    d = ends - anchors
    lh = np.hypot(d[:, 0], d[:, 1])
    h = d[:, 2]
    L = np.hypot(lh, h)
    t = np.asarray(tensions, dtype=float)
    out = [np.full(t.shape, np.nan) for _ in range(4)]
    batch = (lh > 1e-14 * L) & (w0 > 0)
    if not np.any(batch):
        return (*out, ~batch)
    idx = np.flatnonzero(batch)
    args = (lh[idx], h[idx], L[idx], t[idx], EA[idx], w0[idx])
    guess = None
    if start is not None:
        guess = tuple(np.asarray(s, dtype=float)[idx] for s in start)
        if not (all(np.all(np.isfinite(g)) for g in guess) and np.all(guess[0] > 0)
                and np.all(guess[2] > 0)):
            guess = None
    if guess is None:
        guess = _straight_start(*args)
    kernels = compiled_kernels.load("catenary") if compiled else None
    fast = kernels.newton_taut if kernels is not None else None
    sol = _solve(fast, args, guess)
    ok = sol[3]
    if start is not None and not np.all(ok):      # retry the others from the straight cable
        redo = np.flatnonzero(~ok)
        sub = tuple(a[redo] for a in args)
        again = _solve(fast, sub, _straight_start(*sub))
        for k, v in enumerate(again):
            sol[k][redo] = v
    H, V0, L0, ok, res = sol
    done = idx[ok]
    for k, v in enumerate((H, V0, L0, res)):
        out[k][done] = v[ok]
    pending = np.ones(t.shape, dtype=bool)
    pending[done] = False
    return (*out, pending)


def catenary_arrays(states: tuple[CatenaryState, ...]) -> tuple[NDArray[np.float64], ...]:
    """(H, V0, L0) arrays [N, N, m] of a sequence of CatenaryState (a warm start)."""
    return (np.array([s.H for s in states]), np.array([s.V0 for s in states]),
            np.array([s.unstretched_length for s in states]))


def states_for_tensions(anchors: NDArray[np.float64], ends: NDArray[np.float64],
                        tensions: NDArray[np.float64], cables: list[Cable], g: float,
                        start: ArrayLike | None = None) -> list[CatenaryState]:
    """CatenaryState of every cable for its tension at B: :func:`taut_catenaries`, the
    cables it leaves solved one by one by
    :func:`dynstiff.cable.catenary_solve.unstretched_length_for_tension` (which raises
    :class:`SlackCableError` for a tension that cannot be reached).

    Returns
    -------
    list of CatenaryState, length n
    """
    EA = np.array([c.EA for c in cables])
    w0 = np.array([c.mass_per_length for c in cables]) * g
    H, V0, L0, res, pending = taut_catenaries(anchors, ends, tensions, EA, w0, start)
    states = []
    for i in range(len(cables)):
        if pending[i]:
            states.append(unstretched_length_for_tension(anchors[i], ends[i], tensions[i],
                                                         cables[i], g))
            continue
        states.append(CatenaryState(anchor=anchors[i], end=ends[i],
                                    unstretched_length=float(L0[i]), cable=cables[i], g=g,
                                    H=float(H[i]), V0=float(V0[i]),
                                    residual=float(res[i])))
    return states


def sag_ratios(anchors: NDArray[np.float64], ends: NDArray[np.float64], H: NDArray[np.float64],
               V0: NDArray[np.float64], L0: NDArray[np.float64], EA: NDArray[np.float64],
               w0: NDArray[np.float64]) -> NDArray[np.float64]:
    """Largest distance of each cable from its chord over the chord length [-], shape (n,).

    Exact, at one point per cable (docs/theory.md §1.1): the signed distance from the chord,
    g(s) = (x(s) h - z(s) l_h) / L, is zero at both ends and concave in the unstretched arc
    length s (g' is proportional to H h - V(s) l_h, V(s) = V0 + w0 s increasing), so its
    largest value is where the cable runs parallel to the chord, V(s*) / H = h / l_h, and s*
    lies in [0, L0]. A cable with H = 0 (vertical chord) or without weight is straight: 0.

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.1, EA=1e9)                  # 0.981 N/m
    >>> st = ds.unstretched_length_for_tension([0, 0, 0], [10.0, 0, 0], 100.0, cable)
    >>> r = sag_ratios(np.zeros((1, 3)), np.array([[10.0, 0, 0]]), *catenary_arrays([st]),
    ...                np.array([1e9]), np.array([0.981]))
    >>> print(f"{r[0]:.5f}, parabola {0.981 * 10 / (8 * st.H):.5f}")     # w0 L / (8 H)
    0.01228, parabola 0.01228
    """
    d = ends - anchors
    lh = np.hypot(d[:, 0], d[:, 1])
    L = np.hypot(lh, d[:, 2])
    sloped = (H > 0) & (w0 > 0) & (lh > 0)
    Hc = np.where(sloped, H, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.clip((Hc * d[:, 2] / np.where(sloped, lh, 1.0) - V0) / np.where(sloped, w0, 1.0),
                    0.0, L0)
        a, b = V0 / Hc, (V0 + w0 * s) / Hc
        d_asinh, _, _, d_sqrt = divided_differences(a, b, b - a)
    x = s * (Hc / EA + d_asinh)
    z = s * ((V0 + 0.5 * w0 * s) / EA + d_sqrt)
    dist = np.abs(x * d[:, 2] - z * lh) / L
    return np.where(sloped, dist / L, 0.0)
