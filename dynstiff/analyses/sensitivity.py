"""Sensitivities of the natural frequencies to the robot's parameters (theory.md §16).

At a root of the transcendental problem K(omega) x = 0 (theory.md §5), with lambda = omega^2,

    d lambda / dp = -(x^T dK/dp x) / (x^T dK/dlambda x)

(the first-order change of the eigenvalue of K that crosses zero; -x^T dK/dlambda x is the
mode's total modal mass, theory.md §13.3). dK/dp is the total derivative along the
equilibrium that the parameter moves (:mod:`dynstiff.analyses.sensitivity_statics`) and the
rung's own dependence (:mod:`dynstiff.analyses.sensitivity_rungs`), both by the complex step
(exact to rounding); dK/domega by the complex step of the model's own ``dynamic_stiffness``.
A cluster of coincident roots (within 1e-8) is one subspace X: the derivatives of its
eigenvalues are the eigenvalues of (X^T dK/dp X, -X^T dK/dlambda X), ascending (the one-sided
derivatives for an increase of p; no basis of the subspace is preferred). The lumped rung
differentiates its finite eigenproblem (:mod:`dynstiff.analyses.sensitivity_lumped`).

A loss factor leaves the undamped frequencies alone; its sensitivity is that of the modal
damping ratio, d zeta / d eta = (1 / (2 lambda)) d lambda / d a with a the factor on the
dynamic (axial) EA the loss factor multiplies by (1 + i eta) (first order about the
undamped mode: the modal strain energy method).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import tension_reference as checked_reference
from dynstiff.analyses import eigen_matrix
from dynstiff.analyses.eigen import eigenfrequencies, validated_request
from dynstiff.analyses.sensitivity_kernels import CS_STEP, perturbed_primitives, primitives
from dynstiff.analyses.sensitivity_lumped import LumpedLinearisation
from dynstiff.analyses.sensitivity_parameters import expand_parameters
from dynstiff.analyses.sensitivity_result import SensitivityResult
from dynstiff.analyses.sensitivity_rungs import exact_fields, forms
from dynstiff.analyses.sensitivity_statics import LinearisedEquilibrium
from dynstiff.errors import InvalidParameterError, UnsupportedAnalysisError
from dynstiff.models.base import require_model
from dynstiff.models.dsm_compiled import stiffness_and_count

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike, NDArray

    from dynstiff.analyses.sensitivity_parameters import Parameter
    from dynstiff.models.base import PlatformModel
    from dynstiff.models.lumped import LumpedLinearModel
    from dynstiff.robot.pose import Pose
    from dynstiff.robot.robot import Robot

__all__ = ["SensitivityResult", "frequency_sensitivities", "sensitivities_at", "RUNGS",
           "whole_clusters"]

#: The rungs with sensitivities.
RUNGS = ("spring", "catenary", "dsm", "exact", "lumped")
_TWO_PI = 2.0 * np.pi
_CLUSTER_RTOL = 1e-8


def frequency_sensitivities(
        model: PlatformModel, parameters: str | Sequence[str], n_modes: int | None = None,
        fmax_hz: float | None = None, hold: str = "pose",
        tension_reference: ArrayLike | None = None,
) -> SensitivityResult:
    """Derivatives of the natural frequencies with respect to parameters (module notes).

    Parameters
    ----------
    model : model of the rung "dsm", "exact", "lumped", "spring" or "catenary"
        Its undamped frequencies are differentiated.
    parameters : str or sequence of str
        Names of :mod:`dynstiff.analyses.sensitivity_parameters` (``"EA"``, ``"EA_*"``,
        ``"mass"``, ``"pose_x"``, ``"anchor_3"``, ``"t_min"``, ...).
    n_modes, fmax_hz : as :func:`dynstiff.eigenfrequencies`
    hold : {"pose", "lengths"}
        What a parameter change keeps: the pose, with the tension distribution closest to
        ``tension_reference`` (the equilibrium of ``Robot.equilibrium(pose=...)``), or the
        unstretched lengths, with the pose following (``unstretched_lengths=...``).
    tension_reference : float or ndarray, shape (n_cables,), optional
        The reference [N] the model's equilibrium was computed with (default the robot's,
        t_min along each cable); needed by ``t_ref_i``.

    Returns
    -------
    SensitivityResult

    Raises
    ------
    InvalidParameterError
        Unknown parameter, bad request, or an equilibrium that is not the one ``hold``
        and ``tension_reference`` describe.
    UnsupportedAnalysisError
        A model without sensitivities.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> s = ds.frequency_sensitivities(ds.FrequencyModel(eq), ["EA", "mass"], n_modes=2)
    >>> [round(float(v), 4) for v in s.relative[0]]   # Hz per +1 % of EA, of the mass
    [0.0108, -0.0102]
    """
    require_model(model)
    if model.rung not in RUNGS:
        raise UnsupportedAnalysisError(
            f"frequency sensitivities need one of the rungs {RUNGS}, got {model.rung!r}")
    n_modes, fmax_hz = validated_request(n_modes, fmax_hz)
    tension_reference, _ = _checked_request(model, parameters, hold, tension_reference)
    m = model.undamped()
    f = eigenfrequencies(m, n_modes=n_modes, fmax_hz=fmax_hz)
    return sensitivities_at(m, f, parameters, hold, tension_reference)


def sensitivities_at(model: PlatformModel, freq_hz: NDArray[np.float64],
                     parameters: list[str | Parameter], hold: str = "pose",
                     tension_reference: NDArray[np.float64] | None = None,
                     linearisation: LinearisedEquilibrium | None = None) -> SensitivityResult:
    """:func:`frequency_sensitivities` at frequencies already computed (``freq_hz`` [Hz],
    ascending, the undamped model's: e.g. from a search done anyway); parameters as there,
    or a list of :class:`~dynstiff.analyses.sensitivity_parameters.Parameter`;
    ``linearisation``: the model's
    :class:`~dynstiff.analyses.sensitivity_statics.LinearisedEquilibrium` when one was built
    already (continuous rungs).

    Examples
    --------
    >>> import dynstiff as ds
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> f = ds.eigenfrequencies(m, n_modes=1)
    >>> round(float(sensitivities_at(m, f, ["mass"]).derivative[0, 0]), 5)  # Hz/kg
    -0.01118
    """
    tension_reference, params = _checked_request(model, parameters, hold, tension_reference)
    m = model.undamped()
    f = np.asarray(freq_hz, dtype=float)
    if m.rung == "lumped":
        return _lumped(m, f, parameters, hold, tension_reference)
    lin = linearisation or LinearisedEquilibrium(m.equilibrium, hold, tension_reference)
    dy = lin.derivatives([p.direction for p in params])
    groups, X, moving = _null_vectors(m, f)
    pairs = [(k, a, b) for k, g in enumerate(groups) for a in range(len(g))
             for b in range(len(g)) if moving[g[0]] and a <= b]
    out = _empty(f, params)
    if pairs:
        w = _TWO_PI * f
        kk = np.array([k for k, _, _ in pairs])
        Xa = np.array([X[k][:, a] for k, a, _ in pairs])
        Xb = np.array([X[k][:, b] for k, _, b in pairs])
        wp = w[[groups[k][0] for k in kk]]
        Bp = _modal_masses(m, wp, Xa, Xb)
        Y, P = lin.perturbed([p.direction for p in params], dy)
        fields = None
        if m.rung == "exact":
            fa = exact_fields(m, wp, Xa)
            fields = (fa, fa if np.array_equal(Xa, Xb) else exact_fields(m, wp, Xb))
        Ap = np.imag(forms(m, lin, Y, P, wp, Xa, Xb, fields)) / CS_STEP      # (p, n_pairs)
        fi, masses = m.free_index, np.full(len(f), np.nan)
        for k, g in enumerate(groups):                 # x^T M_p x of each mode's vector
            x = X[k][fi]
            masses[g] = np.einsum("ia,ij,ja->a", x, m.platform_mass, x)
        _assemble(out, groups, pairs, Ap, Bp, w, params, moving, masses)
    note = "" if all(moving[g[0]] for g in groups) else (
        "modes with the platform at rest on a cable pole (NaN): their sensitivities are "
        "those of the clamped cable")
    return _result(out, f, params, groups, m.rung, hold, note)


def _checked_request(
        model: PlatformModel, parameters: list[str | Parameter], hold: str,
        tension_reference: ArrayLike | None,
) -> tuple[NDArray[np.float64] | None, list[Parameter]]:
    """``hold``, ``tension_reference`` and the parameter names checked before any work (a
    typed error naming the argument); returns the reference as an array (or None) and the
    parameters expanded at the model's pose."""
    if hold not in ("pose", "lengths"):
        raise InvalidParameterError(f"hold must be 'pose' or 'lengths', got {hold!r}")
    if tension_reference is not None:
        tension_reference = checked_reference(tension_reference, model.robot.n_cables)
    L0 = (model.mass_model if model.rung == "lumped" else model.equilibrium).unstretched_lengths
    return tension_reference, _parameters(parameters, model.robot, model.pose, hold,
                                          tension_reference, L0)


def _parameters(parameters: list[str | Parameter], robot: Robot, pose: Pose, hold: str,
                t_ref: NDArray[np.float64] | None, L0: NDArray[np.float64]) -> list[Parameter]:
    if isinstance(parameters, (list, tuple)) and parameters and all(
            hasattr(p, "direction") for p in parameters):
        return list(parameters)
    return expand_parameters(parameters, robot, pose, hold, t_ref, L0)


def whole_clusters(f: NDArray[np.float64], top: int) -> int:
    """``top`` raised so that ``f[:top]`` ends with whole clusters of coincident roots
    (within 1e-8, as :func:`sensitivities_at` groups them): the sensitivities of a cluster
    cut by the list would come from part of its null space, not its eigenvalues.

    Examples
    --------
    >>> whole_clusters(np.array([1.0, 2.0, 2.0, 3.0]), 2)
    3
    """
    top = min(int(top), len(f))
    if top <= 0:
        return top
    return next(g[-1] + 1 for g in _clusters(f) if g[-1] + 1 >= top)


def _clusters(f: NDArray[np.float64]) -> list[list[int]]:
    groups = []
    for k in range(len(f)):
        if groups and f[k] - f[groups[-1][-1]] <= _CLUSTER_RTOL * max(abs(f[k]), 1e-300):
            groups[-1].append(k)
        else:
            groups.append([k])
    return groups


def _null_vectors(
        m: PlatformModel, f: NDArray[np.float64],
) -> tuple[list[list[int]], list[NDArray[np.float64]], NDArray[np.bool_]]:
    """Clusters of coincident roots, their null spaces X (6, c) of K(omega) (full
    platform vectors) and whether they move the platform (theory.md §5.3)."""
    groups = _clusters(f)
    X, moving = [], np.zeros(len(f), bool)
    if not groups:
        return groups, X, moving
    w = _TWO_PI * f
    scale = np.abs(np.linalg.eigvalsh(m.massless_stiffness())).max()
    ends = np.array([[g[0], g[-1]] for g in groups], dtype=int)
    w_ends = (w[ends] * np.array([1 - 1e-9, 1 + 1e-9])).ravel()
    # K at the roots and the cable counts beside them, from one call
    K, J0 = stiffness_and_count(m, np.concatenate([w[[g[0] for g in groups]], w_ends]))
    K, J0 = np.real(K[:len(groups)]), J0[len(groups):].reshape(-1, 2)
    finite = np.all(np.isfinite(K), axis=(1, 2))
    eigs = dict(zip(np.flatnonzero(finite),
                    zip(*np.linalg.eigh(0.5 * (K[finite] + K[finite].transpose(0, 2, 1))))))
    for j, g in enumerate(groups):
        x = np.zeros((6, len(g)))
        if finite[j]:
            ev, V = eigs[j]
            order = np.argsort(np.abs(ev))[:len(g)]
            small = np.abs(ev[order]) <= 1e-6 * scale
            if J0[j, 1] == J0[j, 0] or np.all(small):
                x[m.free_index] = V[:, order]
                moving[g] = True
        X.append(x)
    return groups, X, moving


def _modal_masses(m: PlatformModel, w: NDArray[np.float64], Xa: NDArray[np.float64],
                  Xb: NDArray[np.float64]) -> NDArray[np.float64]:
    """-x_a^T dK/dlambda x_b at omega (pairs), dK/domega by the complex step of the model's
    own K (theory.md §16.1)."""
    h = 1e-20 * np.maximum(w, 1.0)
    dK = np.imag(m.dynamic_stiffness(w + 1j * h)) / h[:, None, None]
    fi = m.free_index
    return -np.einsum("pi,pij,pj->p", Xa[:, fi], dK, Xb[:, fi]) / (2.0 * w)


def _empty(f: NDArray[np.float64], params: list[Parameter]) -> dict[str, NDArray[np.float64]]:
    n, p = len(f), len(params)
    return {"d": np.full((n, p), np.nan), "z": np.full((n, p), np.nan),
            "share": np.full(n, np.nan)}


def _assemble(out: dict[str, NDArray[np.float64]], groups: list[list[int]],
              pairs: list[tuple[int, int, int]], Ap: NDArray[np.float64], Bp: NDArray[np.float64],
              w: NDArray[np.float64], params: list[Parameter], moving: NDArray[np.bool_],
              masses: NDArray[np.float64]) -> None:
    """Per cluster: the eigenvalues of (A_j, B) for every parameter j (A_j / B for all the
    lone roots at once), into d f/dp and d zeta/dp (module notes); the platform share
    x^T M_p x / x^T B x of each mode from ``masses``, its vector's x^T M_p x."""
    import scipy.linalg
    damping = np.array([p.kind == "damping" for p in params])
    index = {}
    for i, (k, a, b) in enumerate(pairs):
        index[(k, a, b)] = index[(k, b, a)] = i
    one = [k for k, g in enumerate(groups) if len(g) == 1 and moving[g[0]]]
    if one:                                            # lone roots: mu = A / B, all at once
        i = np.array([index[(k, 0, 0)] for k in one])
        g1 = np.array([groups[k][0] for k in one])
        mu = Ap[:, i].T / Bp[i, None]                                  # (n_one, p)
        out["d"][g1] = np.where(damping, 0.0, mu / (2.0 * w[g1, None] * _TWO_PI))
        out["z"][g1[:, None], damping] = (mu / (2.0 * w[g1, None] ** 2))[:, damping]
        out["share"][g1] = masses[g1] / np.real(Bp[i])
    for k, g in enumerate(groups):
        if not moving[g[0]] or len(g) == 1:
            continue
        c = len(g)
        sel = np.array([[index[(k, a, b)] for b in range(c)] for a in range(c)])
        B = Bp[sel]
        lam = w[g[0]] ** 2
        for j in range(len(params)):
            A = Ap[j][sel]
            mu = np.sort(scipy.linalg.eigh(0.5 * (A + A.T), 0.5 * (B + B.T),
                                           eigvals_only=True))
            if damping[j]:
                out["d"][g, j] = 0.0
                out["z"][g, j] = mu / (2.0 * lam)
            else:
                out["d"][g, j] = mu / (2.0 * w[g[0]] * _TWO_PI)
        out["share"][g] = masses[g] / np.real(np.diag(B))


def _result(out: dict[str, NDArray[np.float64]], f: NDArray[np.float64], params: list[Parameter],
            groups: list[list[int]], rung: str, hold: str, note: str) -> SensitivityResult:
    cluster = np.zeros(len(f), dtype=int)
    for k, g in enumerate(groups):
        cluster[g] = k
    return SensitivityResult(
        freq_hz=f, parameters=tuple(p.name for p in params),
        values=np.array([p.value for p in params]), units=tuple(p.unit for p in params),
        derivative=out["d"], damping_derivative=out["z"], cluster=cluster,
        platform_share=out["share"], rung=rung, hold=hold, note=note)


def _lumped(m: LumpedLinearModel, f: NDArray[np.float64], parameters: list[str], hold: str,
            tension_reference: ArrayLike | None) -> SensitivityResult:
    """The lumped rung: its own equilibrium's derivative and the finite eigenproblem."""
    rob, st, mm = m.robot, m.equilibrium, m.mass_model
    n = rob.n_cables
    L0 = mm.unstretched_lengths
    if hold == "pose":
        cat = rob.equilibrium(pose=st.start_pose, tension_reference=tension_reference)
        if not np.allclose(cat.unstretched_lengths, L0, rtol=1e-8, atol=0):
            raise InvalidParameterError(
                "model: its unstretched lengths are not those of the tension distribution "
                "at its pose (closest to tension_reference); give the reference it was "
                "built with, or hold='lengths'")
        lin = LinearisedEquilibrium(cat, "pose", tension_reference)
        pose = st.start_pose
    else:
        lin, pose = None, st.pose
    params = _parameters(parameters, rob, pose, hold, tension_reference, L0)
    dirs = [dict(p.direction) for p in params]
    if lin is not None:
        dy = lin.derivatives(dirs)
        for d, row in zip(dirs, dy):
            d["L0"] = row[2 * n:3 * n]
    P0 = primitives(rob, pose, tension_reference, L0)
    LL = LumpedLinearisation(m, P0)
    Pb = perturbed_primitives(P0, dirs)
    Z = LL.z_base()[None, :] + 1j * CS_STEP * LL.equilibrium_derivatives(Pb)
    out = _empty(f, params)
    if not len(f):
        return _result(out, f, params, [], "lumped", hold, "")
    lam, V = eigen_matrix.eig(m, len(f))
    groups = _clusters(f)
    pairs = [(k, a, b) for k, g in enumerate(groups) for a in range(len(g))
             for b in range(len(g)) if a <= b]
    A = np.array([V[:, groups[k][a]] for k, a, _ in pairs])
    Bv = np.array([V[:, groups[k][b]] for k, _, b in pairs])
    lp = np.array([lam[groups[k][0]] for k, _, _ in pairs])
    Ap = np.imag(LL.forms(Z, Pb, lp, A, Bv)) / CS_STEP
    Bp = np.array([1.0 if a == b else 0.0 for _, a, b in pairs])
    Mp = m.platform_mass
    X = V[:m.n_free]
    share = np.einsum("in,ij,jn->n", X, Mp, X)
    _assemble(out, groups, pairs, Ap, Bp, _TWO_PI * f, params, np.ones(len(f), bool),
              masses=share)
    return _result(out, f, params, groups, "lumped", hold, "")
