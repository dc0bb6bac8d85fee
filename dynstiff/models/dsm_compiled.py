"""The closed-form model's arrays for the compiled kernels (:mod:`dynstiff.compiled.dsm`;
theory.md §14.1-§14.2): the cables' chord parameters as contiguous arrays, the psi series,
and the assembly map reduced to a symmetric K."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff.cable.psi import PSI_SERIES

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.dsm import FrequencyModel

__all__ = ["compiled_arguments", "damped_compiled_arguments", "stiffness_and_count",
           "symmetric_assembly"]


def compiled_arguments(model: FrequencyModel) -> tuple[ArrayLike, ...]:
    """The arguments L .. M of the compiled kernels ``dsm_receptance`` and ``dsm_count``
    (:mod:`dynstiff.compiled.dsm`) for an undamped :class:`FrequencyModel`: contiguous float
    arrays, the psi series and the symmetric assembly map."""
    memo = getattr(model, "_memo", None)         # the model is immutable: computed once
    if memo is not None and "compiled_arguments" in memo:
        return memo["compiled_arguments"]
    p = model.stacked_params

    def real(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.ascontiguousarray(np.real(np.broadcast_to(x, p.L.shape)), dtype=float)

    args = (real(p.L), real(p.m), real(p.T), real(p.lambda_sq), real(p.alpha), real(p.K0),
            bool(model.chordwise_inertia), PSI_SERIES, _symmetric_assembly_of(model),
            np.ascontiguousarray(model.K_geo_free, dtype=float),
            np.ascontiguousarray(model.platform_mass, dtype=float))
    if memo is not None:
        memo["compiled_arguments"] = args
    return args


def damped_compiled_arguments(model: FrequencyModel) -> tuple[ArrayLike, ...] | None:
    """The arguments scale .. M of ``dsm_receptance_damped`` (:mod:`dynstiff.compiled.dsm`)
    for a damped :class:`FrequencyModel` whose damping is hysteretic (the model's cable loss
    factor, the cables' own complex EA, the platform's modal damping); None where a cable has
    viscous damping (its mass is complex and frequency-dependent: the numpy path)."""
    p = model.stacked_params
    if np.any(np.asarray(p.c) != 0):
        return None

    def arr(x: NDArray[Any], kind: type) -> NDArray[Any]:
        return np.ascontiguousarray(np.broadcast_to(x, p.L.shape), dtype=kind)

    K_static = model.K_geo_free.astype(complex)
    if model._K_platform_damping is not None:
        K_static = K_static + model._K_platform_damping
    return (complex(1.0 + 1j * model.cable_loss_factor), arr(np.real(p.L), float),
            arr(np.real(p.m), float), arr(np.real(p.T), float),
            arr(p.lambda_sq_complex, complex), arr(p.alpha, complex), arr(p.K0, complex),
            bool(model.chordwise_inertia), PSI_SERIES,
            _symmetric_assembly_of(model).astype(complex),
            np.ascontiguousarray(K_static), np.ascontiguousarray(model.platform_mass, dtype=float))


def stiffness_and_count(model: FrequencyModel, omega: NDArray[np.float64],
                        ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """K(omega) and the cable count J0(omega) of an undamped model at real omega [rad/s]:
    for the closed form one call of the compiled kernel
    :func:`dynstiff.compiled.dsm.dsm_stiffness`, whose entries agree with the numpy path's
    to tens of eps of the largest; without numba, or for another model, the model's
    ``dynamic_stiffness_and_count`` where it has one, else ``dynamic_stiffness`` and
    ``cable_mode_count``."""
    from dynstiff import compiled
    from dynstiff.cable.psi import check_frequency_range
    from dynstiff.models.dsm import FrequencyModel
    fast = compiled.load("dsm")
    if fast is None or type(model) is not FrequencyModel or model.damped:
        if hasattr(model, "dynamic_stiffness_and_count"):
            return model.dynamic_stiffness_and_count(omega)
        return model.dynamic_stiffness(omega), model.cable_mode_count(omega)
    omega = np.ascontiguousarray(omega, dtype=float)
    check_frequency_range(model.stacked_params, omega)
    model.guard_band(omega)
    return fast.dsm_stiffness(omega, *compiled_arguments(model))


def _symmetric_assembly_of(model: FrequencyModel) -> NDArray[np.float64]:
    """:func:`symmetric_assembly` of the model's assembly map, computed once per model (and
    shared with its damped copies: the map is geometry only)."""
    memo = getattr(model, "_memo", None)
    if memo is not None and "symmetric_assembly" in memo:
        return memo["symmetric_assembly"]
    out = symmetric_assembly(model.assembly_map, model.n_free)
    out.setflags(write=False)
    if memo is not None:
        memo["symmetric_assembly"] = out
    return out


def symmetric_assembly(assembly_map: NDArray[np.float64], n_free: int) -> NDArray[np.float64]:
    """The dyad -> K map reduced to what a symmetric K needs: the uv and vu dyads (which
    share the coefficient -k_uv) summed, and the upper triangle of K kept.

    assembly_map : ndarray, shape (5 n_cables, n_free**2), dyads (uu, uv, vu, vv, ww).
    Returns ndarray, shape (4 n_cables, n_free (n_free + 1) / 2), dyads (uu, uv + vu, vv, ww).
    """
    A = assembly_map.reshape(-1, 5, n_free, n_free)
    A = np.stack([A[:, 0], A[:, 1] + A[:, 2], A[:, 3], A[:, 4]], axis=1)
    iu, ju = np.triu_indices(n_free)
    return np.ascontiguousarray(A[:, :, iu, ju].reshape(-1, iu.size))
