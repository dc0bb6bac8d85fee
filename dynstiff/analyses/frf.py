"""Frequency response functions of the robot platform, batched over frequency.

Receptance H(omega) = K(omega)^-1 on the free DOFs (theory.md §4), between forces/moments on
the platform (about P, base axes) and the motion of a platform point c (platform frame):
d_c = dp + dtheta x R_p c. Mobility = i omega H, accelerance = -omega^2 H.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np

from dynstiff import compiled
from dynstiff._validate import omega_array
from dynstiff._validate import point as validated_point
from dynstiff.cable.psi import check_frequency_range
from dynstiff.errors import InvalidParameterError, PoleWarning, ResonanceWarning, user_stacklevel
from dynstiff.models.base import require_model
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.dsm_compiled import compiled_arguments, damped_compiled_arguments
from dynstiff.results import INPUT_NAMES, OUTPUT_NAMES, FRFResult, response_factor
from dynstiff.robot.platform import skew

if TYPE_CHECKING:
    from collections.abc import Sequence
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.base import PlatformModel

__all__ = ["frf", "FRFResult", "INPUT_NAMES", "OUTPUT_NAMES", "channel_maps"]

#: Relative distance from a cable pole within which H is taken as the mean of both sides.
_POLE_STEP = 1e-9


def _channels(names: int | str | list[str] | None, allowed: tuple[str, str, str, str, str, str],
              arg: str) -> list[int]:
    if names is None:
        return list(range(6))
    if isinstance(names, str):
        names = [names]
    try:
        names = list(names)
    except TypeError:
        raise InvalidParameterError(
            f"{arg} must be a name or a list of names among {allowed}, got {names!r}") from None
    if not names:
        raise InvalidParameterError(f"{arg} must name at least one channel among {allowed}, "
                                    f"got an empty list")
    idx = []
    for n in names:
        if n not in allowed:
            raise InvalidParameterError(f"{arg} must be among {allowed}, got {n!r}")
        if allowed.index(n) in idx:
            raise InvalidParameterError(f"{arg} names {n!r} twice: {names!r}")
        idx.append(allowed.index(n))
    return idx


def channel_maps(
        free_index: NDArray[np.int64], rotation: NDArray[np.float64],
        inputs: int | str | list[str] | None = None, outputs: str | list[str] | None = None,
        point: ArrayLike | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], tuple[str, ...], tuple[str, ...]]:
    """Maps between named channels and the free DOFs.

    Parameters
    ----------
    free_index : ndarray of int, shape (n_free,)
        Free DOFs among (x, y, z, rx, ry, rz).
    rotation : ndarray, shape (3, 3)
        Platform rotation R_p.
    inputs, outputs : str or list of str, optional
        Among ``INPUT_NAMES`` / ``OUTPUT_NAMES`` (default all six).
    point : array_like, shape (3,), optional
        Platform point [m, platform frame] whose translation is output (default P).

    Returns
    -------
    B : ndarray, shape (n_free, n_in)
        Loads (about P) -> generalized forces on the free DOFs.
    C : ndarray, shape (n_out, n_free)
        Free-DOF motion -> output channels, d_c = dp - [R_p c]x dtheta.
    input_names, output_names : tuple of str
    """
    ii = _channels(inputs, INPUT_NAMES, "inputs")
    oo = _channels(outputs, OUTPUT_NAMES, "outputs")
    c = np.zeros(3) if point is None else validated_point("point", point)
    C6 = np.eye(6)
    C6[:3, 3:] = -skew(rotation @ c)
    B = np.ascontiguousarray(np.eye(6)[np.ix_(free_index, ii)])
    C = np.ascontiguousarray(C6[np.ix_(oo, free_index)])
    # a channel named explicitly that touches no free DOF would give an FRF identically 0
    free = tuple(OUTPUT_NAMES[k] for k in free_index)
    for names, allowed, mat, axis, arg in ((inputs, INPUT_NAMES, B, 0, "inputs"),
                                           (outputs, OUTPUT_NAMES, C, 1, "outputs")):
        if names is None:
            continue
        alive = np.any(mat != 0, axis=axis)           # per input column / output row
        dead = [allowed[k] for k, a in zip(ii if axis == 0 else oo, alive) if not a]
        if dead:
            raise InvalidParameterError(
                f"{arg} {dead} {'act on' if arg == 'inputs' else 'move with'} held DOFs only "
                f"(free DOFs: {free}{'' if arg == 'inputs' else f', point {c.tolist()}'}): "
                f"their FRFs are identically 0")
    return (B, C, tuple(INPUT_NAMES[i] for i in ii), tuple(OUTPUT_NAMES[o] for o in oo))


def frf(model: PlatformModel, omega: ArrayLike, inputs: str | Sequence[str] | None = None,
        outputs: str | Sequence[str] | None = None, point: ArrayLike | None = None,
        kind: str = "receptance", max_frequencies: int = 1_000_000) -> FRFResult:
    """FRFs of the robot platform, for a model of any rung.

    H(omega) = C K(omega)^-1 B with K(omega) = ``model.dynamic_stiffness(omega)`` on the free
    DOFs (theory.md §4), batched over frequency.

    Parameters
    ----------
    model : model of any rung (:mod:`dynstiff.models.base`)
    omega : array_like, shape (n,)
        Angular frequencies [rad/s], >= 0.
    inputs : str or list of str, optional
        Among ``INPUT_NAMES`` (default all six). Loads on held DOFs give no response: in
        the default they are zero columns, named explicitly they raise.
    outputs : str or list of str, optional
        Among ``OUTPUT_NAMES`` (default all six).
    point : array_like, shape (3,), optional
        Platform point [m, platform frame] whose translation is output (default P).
    kind : {"receptance", "mobility", "accelerance"}
        Mobility = i omega H, accelerance = -omega^2 H.
    max_frequencies : int
        Largest number of frequencies (a guard on memory: K(omega) takes n_free^2 complex
        numbers per frequency); raise it for longer grids.

    Returns
    -------
    FRFResult

    Warns
    -----
    PoleWarning
        At a frequency where K(omega) is exactly singular: those entries are inf, never a
        silently wrong finite number.

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> r = ds.frf(m, 2 * np.pi * np.array([0.5, 1.0]), inputs="fz", outputs="z")
    >>> r.H.shape
    (2, 1, 1)
    >>> print(f"{abs(r.H[0, 0, 0]):.3e} m/N")
    5.925e-05 m/N
    """
    require_model(model)
    omega = omega_array(omega)
    if omega.size > max_frequencies:
        raise InvalidParameterError(
            f"omega has {omega.size} frequencies, more than max_frequencies = "
            f"{max_frequencies}; raise max_frequencies or evaluate in pieces")
    factor = response_factor(omega, kind)
    B, C, in_names, out_names = channel_maps(model.free_index, model.pose.matrix,
                                             inputs, outputs, point)
    H, kmax, singular = _receptance(model, omega, B, C)
    if np.any(singular):
        H[singular] = np.inf
        warnings.warn(
            f"K(omega) is exactly singular at {singular.sum()} frequencies (eigenfrequencies, "
            f"e.g. {omega[singular][0] / (2 * np.pi):.9g} Hz): FRF set to inf",
            PoleWarning, stacklevel=2)
    # a pole of a cable's K_B is not a pole of H (an anti-resonance), but within about 1e-9
    # of it K has entries ~1e16 next to ~1e3 and its LU loses ~13 digits (1e-3 in H at a
    # CoGiRo cable pole): there H is the mean of its values at omega (1 -+ 1e-9), which
    # cancels the O(1/K) term antisymmetric about the pole (its error is O(1e-9)). Only
    # frequencies where K is 1e6 times its regular size are examined (kmax > 1e6 regular
    # implies kmax > 1e6 inertia; omega = 0, the static stiffness, is no cable's pole).
    inertia = omega**2 * np.abs(model.platform_mass).max()
    cand = np.flatnonzero((kmax > 1e6 * inertia) & (omega != 0))
    if cand.size:
        regular = np.abs(model.massless_stiffness()).max() + inertia[cand]
        cand = cand[kmax[cand] > 1e6 * regular]
    if cand.size:
        w = omega[cand]
        near = model.cable_mode_count(w * (1 - _POLE_STEP)) != \
            model.cable_mode_count(w * (1 + _POLE_STEP))
        if np.any(near):
            w = w[near]
            H[cand[near]] = 0.5 * (_receptance(model, w * (1 - _POLE_STEP), B, C)[0]
                                   + _receptance(model, w * (1 + _POLE_STEP), B, C)[0])
    if kind != "receptance":
        H = H * factor[:, None, None]
    if not model.damped:
        crossed = _modes_between(model, omega)
        if crossed:
            warnings.warn(ResonanceWarning(
                f"the FRF of this undamped model crosses {crossed} natural frequencies "
                f"between {omega.min() / (2 * np.pi):.4g} and {omega.max() / (2 * np.pi):.4g} "
                f"Hz: its peaks are the grid's values next to the poles, not the "
                f"structure's; give the model damping (dynstiff.scene_model applies a "
                f"scene's [damping])"), stacklevel=user_stacklevel())
    return FRFResult(freq_hz=omega / (2 * np.pi), H=H, inputs=in_names, outputs=out_names,
                     kind=kind, damping=model.damping_text())


def _modes_between(model: Any, omega: NDArray[np.float64]) -> int:
    """Number of natural frequencies of an undamped ``model`` strictly inside the range of
    ``omega`` [rad/s]: the Wittrick-Williams count J = J0 + s{K} at its ends (theory.md
    §5.1; the finite eigenproblem's count for the discrete rungs, its massless part for the
    massless ones)."""
    if omega.size < 2 or not omega.max() > omega.min():
        return 0
    w = np.array([omega.min(), omega.max()])
    with np.errstate(all="ignore"):
        K = model.dynamic_stiffness(w)
    if not np.all(np.isfinite(K)):
        return 0                              # an end on a pole: not judged here
    neg = np.sum(np.linalg.eigvalsh(0.5 * (K + np.swapaxes(K, 1, 2)).real) < 0, axis=1)
    J = model.cable_mode_count(w) + neg
    return int(J[1] - J[0])


def _receptance(
        model: Any, omega: NDArray[np.float64], B: NDArray[np.float64], C: NDArray[np.float64],
) -> tuple[NDArray[np.complex128], NDArray[np.float64], NDArray[np.bool_]]:
    """C K(omega)^-1 B of ``model`` at omega (n,) [rad/s], shape (n, n_out, n_in), complex.

    Returns (H, kmax, singular): kmax (n,) the largest |K_ij| per frequency, singular (n,)
    where K is exactly singular (H undefined there). "dsm" models take a fused compiled
    kernel when numba is installed (real for undamped cables, complex for hysteretic
    damping: loss factors and the platform's modal damping); every other model (viscous
    cable damping, other rungs) solves its K(omega) batched over frequency, in real
    arithmetic when K is real (theory.md §14.1).
    """
    fast = compiled.load("dsm")
    # exactly the closed-form class: a subclass may change the cable kernels
    if fast is not None and type(model) is FrequencyModel and not model.damped:
        check_frequency_range(model.stacked_params, omega)
        model.guard_band(omega)
        H, kmax, singular = fast.dsm_receptance(np.ascontiguousarray(omega, dtype=float),
                                                *compiled_arguments(model), B, C)
        return H, kmax, singular
    if fast is not None and type(model) is FrequencyModel and np.isrealobj(omega):
        args = damped_compiled_arguments(model)       # None with viscous cable damping
        if args is not None:
            check_frequency_range(model.stacked_params, omega)
            model.guard_band(omega)
            return fast.dsm_receptance_damped(np.ascontiguousarray(omega, dtype=float), *args,
                                              np.ascontiguousarray(B, dtype=float),
                                              np.ascontiguousarray(C, dtype=float))
    K = model.dynamic_stiffness(omega)
    H, singular = _solve(K, B, C, fast)
    return H, np.abs(K).max(axis=(1, 2)), singular


def _solve(K: NDArray[Any], B: NDArray[np.float64], C: NDArray[np.float64],
           fast: Any | None = None) -> tuple[NDArray[np.complex128], NDArray[np.bool_]]:
    """C K^-1 B for a stack K (n, nf, nf), shape (n, n_out, n_in), complex, and where K is
    exactly singular (n,) bool; a real K is solved in real arithmetic and cast once."""
    n = K.shape[0]
    if fast is not None and not np.iscomplexobj(K):
        H, singular = fast.real_receptance(np.ascontiguousarray(K, dtype=float), B, C)
        return H.astype(complex), singular
    singular = np.zeros(n, dtype=bool)
    rhs = np.broadcast_to(B, (n,) + B.shape)
    try:                                    # LU: raises only on an exactly singular K
        return (C @ np.linalg.solve(K, rhs)).astype(complex), singular
    except np.linalg.LinAlgError:
        pass
    H = np.empty((n, C.shape[0], B.shape[1]), dtype=complex)
    for k in range(n):
        try:
            H[k] = C @ np.linalg.solve(K[k], B)
        except np.linalg.LinAlgError:
            singular[k] = True
    return H, singular
