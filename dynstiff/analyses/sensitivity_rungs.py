"""The quadratic forms x^T K(omega) z of the continuous rungs as analytic functions of the
equilibrium and the parameters, for the complex-step derivative dK/dp (theory.md §16.3).

Each function takes the unknowns Y and primitives P of a
:class:`~dynstiff.analyses.sensitivity_statics.LinearisedEquilibrium` (with a leading batch
axis: one perturbed copy per parameter direction), the natural frequencies omega (m,) and
pairs of platform motions X, Z (m, 6), and returns the bilinear forms x_k^T K(omega_k) z_k,
shape (batch, m): at real inputs the model's own K(omega) (tested to 1e-12), at complex ones
analytic, so that Im(form) / h is the derivative along the direction.

* "dsm": the closed form of every cable (theory.md §3-§4) rebuilt from its catenary;
* "spring", "catenary": the massless rungs' static end stiffnesses (theory.md §4);
* "exact": the exact cable (theory.md §11). Its dynamic part is the discretised cable's
  condensed stiffness S(omega) - S(0); by the stationarity of the interior field, the
  derivative of a condensed form is the derivative of the full energy u^T (K - omega^2 M) v
  at the interior fields held fixed (Rayleigh's principle, theory.md §16.3), which is what
  the complex step of :func:`exact_forms` gives; the static part is the catenary's exact
  K_s = F^-1.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.analyses.sensitivity_kernels import (
    catenary_flexibility,
    geometric_stiffness,
    mean_tension,
    platform_mass_forms,
)
from dynstiff.cable.chord import ChordParameters
from dynstiff.cable.dsm import end_block_coefficients
from dynstiff.cable.exact import gll

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from dynstiff.analyses.sensitivity_statics import LinearisedEquilibrium
    from dynstiff.cable.exact import ExactCable
    from dynstiff.models.base import PlatformModel
    from dynstiff.models.dsm import FrequencyModel
    from dynstiff.models.exact import ExactModel
    from dynstiff.models.static import StaticCableModel

__all__ = ["FORMS", "exact_fields", "forms"]

_EZ = np.array([0.0, 0.0, 1.0])


def _motions(x: NDArray[np.float64], r: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Motion of every attachment, J_i x = dp + dtheta x r_i: x (m, 6), r (B, n, 3) ->
    (B, m, n, 3)."""
    return x[None, :, None, :3] + cross(x[None, :, None, 3:], r[:, None, :, :])


def _platform_terms(lin: LinearisedEquilibrium, Y: NDArray[np.complex128],
                    P: dict[str, NDArray[np.complex128]], q: dict[str, NDArray[np.complex128]],
                    omega: NDArray[np.float64], X: NDArray[np.float64],
                    Z: NDArray[np.float64]) -> NDArray[np.complex128]:
    """x^T (K_geo - omega^2 M_p) z [N m...], (B, m): the symmetric geometric stiffness of
    the cable forces and gravity on rotating lever arms and the rigid platform's mass."""
    _, R = lin.pose_of(Y, P)
    m = np.asarray(P["mass"])
    rG = np.einsum("bij,bj->bi", R, P["com"])
    fg = m[:, None] * np.array([0.0, 0.0, -lin.g])
    G = geometric_stiffness(q["f"], q["r"], fg, rG)
    Gs = 0.5 * (G + np.swapaxes(G, 1, 2))
    geo = np.einsum("mi,bij,mj->bm", X[:, 3:], Gs, Z[:, 3:])
    M = platform_mass_forms(P, R)
    return geo - omega[None, :] ** 2 * np.einsum("mi,bij,mj->bm", X, M, Z)


def _chord_frames(q: dict[str, NDArray[np.complex128]],
                  g: float) -> tuple[NDArray[np.complex128], ...]:
    """Unit chord e_u, sag direction e_v, e_w, chord length L and cos(theta), (B, n, ...)."""
    L = np.sqrt(np.sum(q["d"] ** 2, -1))
    eu = q["d"] / L[..., None]
    gv = np.array([0.0, 0.0, -g])
    gp = gv - (eu @ gv)[..., None] * eu
    ev = gp / np.sqrt(np.sum(gp * gp, -1))[..., None]
    return eu, ev, cross(eu, ev), L, q["lh"] / L


def dsm_forms(model: FrequencyModel, lin: LinearisedEquilibrium, Y: NDArray[np.complex128],
              P: dict[str, NDArray[np.complex128]], omega: NDArray[np.float64],
              X: NDArray[np.float64], Z: NDArray[np.float64]) -> NDArray[np.complex128]:
    """Closed-form rung (:class:`dynstiff.FrequencyModel`, theory.md §3-§4)."""
    H, V0, L0, q = lin.quantities(Y, P)
    eu, ev, ew, L, cos_t = _chord_frames(q, lin.g)
    if model.tension == "chord":
        T = H / cos_t
    else:
        T = mean_tension(H, V0, L0, q["w0"])
    m = P["m0"] * L0 / L
    qn = m * lin.g * cos_t
    dL = qn * L / (8.0 * T)
    params = ChordParameters(L=L, T=T, m=m, c=0.0, EA=P["EA"] * P["axial"], q=qn,
                             L_e=L0 * (1.0 + 8.0 * dL**2), cos_theta=cos_t, rotation=None)
    with np.errstate(divide="ignore", invalid="ignore"):
        C = end_block_coefficients(params, omega[:, None], model.chordwise_inertia)
    C = np.moveaxis(C, 0, 1)                                     # (B, m, n, 5)
    a, b = _motions(X, q["r"]), _motions(Z, q["r"])
    au, av, aw = (np.einsum("bmnj,bnj->bmn", a, e) for e in (eu, ev, ew))
    bu, bv, bw = (np.einsum("bmnj,bnj->bmn", b, e) for e in (eu, ev, ew))
    cab = (C[..., 0] * au * bu + C[..., 1] * au * bv + C[..., 2] * av * bu
           + C[..., 3] * av * bv + C[..., 4] * aw * bw).sum(-1)
    return cab + _platform_terms(lin, Y, P, q, omega, X, Z)


def _flexibility(H: NDArray[np.complex128], V0: NDArray[np.complex128], L0: NDArray[np.complex128],
                 EA: NDArray[np.complex128], w0: NDArray[np.complex128],
                 axial: NDArray[np.complex128]) -> tuple[NDArray[np.complex128], ...]:
    """In-plane flexibility (f_xx, f_xz, f_zz) of the catenary with the axial part of EA
    times ``axial`` (closed-form integrals of t t^T, theory.md §11.3), analytic."""
    fxx, fxz, fzz = catenary_flexibility(H, V0, L0, EA, w0)
    if np.all(axial == 1):
        return fxx, fxz, fzz
    W = w0 * L0
    Vb = V0 + W
    ang = np.arctan(H * W / (H * H + V0 * Vb))
    ang = np.where(np.real(H * H + V0 * Vb) < 0, ang + np.pi, ang)
    Ixx = H * L0 * ang / W
    Ixz = 0.5 * H * L0 * np.log1p(W * (V0 + Vb) / (H * H + V0 * V0)) / W
    c = (1.0 / axial - 1.0) / EA
    return fxx + c * Ixx, fxz + c * Ixz, fzz + c * (L0 - Ixx)


def _static_local(q: dict[str, NDArray[np.complex128]], H: NDArray[np.complex128],
                  V0: NDArray[np.complex128], L0: NDArray[np.complex128],
                  P: dict[str, NDArray[np.complex128]],
                  axial: NDArray[np.complex128] | None = None) -> NDArray[np.complex128]:
    """The catenary's exact static end stiffness in its local frame (x along e_h, y = e_z x
    e_h, z up), (B, n, 3, 3)."""
    axial = P["axial"] if axial is None else axial
    fxx, fxz, fzz = _flexibility(H, V0, L0, P["EA"], q["w0"], axial)
    F = np.zeros(np.shape(H) + (3, 3), dtype=np.result_type(fxx, complex))
    F[..., 0, 0], F[..., 0, 2], F[..., 2, 0], F[..., 2, 2] = fxx, fxz, fxz, fzz
    F[..., 1, 1] = q["lh"] / H
    K = np.linalg.inv(F)
    return 0.5 * (K + np.swapaxes(K, -1, -2))


def _frames(q: dict[str, NDArray[np.complex128]]) -> NDArray[np.complex128]:
    """Local frames E = [e_h, e_z x e_h, e_z] of every cable, (B, n, 3, 3)."""
    eh = q["eh"]
    ep = cross(np.broadcast_to(_EZ, eh.shape), eh)
    return np.stack([eh, ep, np.broadcast_to(_EZ, eh.shape)], -1)


def static_forms(model: StaticCableModel, lin: LinearisedEquilibrium, Y: NDArray[np.complex128],
                 P: dict[str, NDArray[np.complex128]], omega: NDArray[np.float64],
                 X: NDArray[np.float64], Z: NDArray[np.float64]) -> NDArray[np.complex128]:
    """The massless rungs (:class:`dynstiff.StaticCableModel`, theory.md §4)."""
    H, V0, L0, q = lin.quantities(Y, P)
    a, b = _motions(X, q["r"]), _motions(Z, q["r"])
    if model.rung == "spring":
        eu, _, _, L, _ = _chord_frames(q, lin.g)
        ka, kt = P["EA"] / L0, q["TB"] / L
        au, bu = np.einsum("bmnj,bnj->bmn", a, eu), np.einsum("bmnj,bnj->bmn", b, eu)
        cab = ((ka - kt)[:, None] * au * bu + kt[:, None] * np.sum(a * b, -1)).sum(-1)
    else:
        E = _frames(q)
        Ks = _static_local(q, H, V0, L0, P, axial=np.ones_like(P["axial"]))
        al, bl = np.einsum("bnji,bmnj->bmni", E, a), np.einsum("bnji,bmnj->bmni", E, b)
        cab = np.einsum("bmni,bnij,bmnj->bm", al, Ks, bl)
    return cab + _platform_terms(lin, Y, P, q, omega, X, Z)


def exact_fields(model: ExactModel, omega: NDArray[np.float64],
                 X: NDArray[np.float64]) -> list[NDArray[np.float64]]:
    """Interior fields of every cable of an :class:`dynstiff.models.exact.ExactModel` for
    the platform motions X (m, 6) at omega (m,) and at 0: a list (per cable) of arrays
    (2, m, n_nodes, 3), local frame (theory.md §11.3), real.

    Examples
    --------
    >>> import dynstiff as ds
    >>> m = ds.build_model(ds.load_scene("cogiro").equilibrium(), "exact", fmax_hz=6.0)
    >>> u = exact_fields(m, np.array([10.0]), np.eye(6)[[2]])
    >>> len(u), u[0].shape[0], u[0].shape[-1]          # cables; (omega, 0); xyz
    (8, 2, 3)
    """
    out = []
    for cab, r in zip(model.cables, model.lever_arms):
        loc = (X[:, :3] + cross(X[:, 3:], r)) @ cab.frame
        static = np.array([np.real(cab.end_response(0.0, e)) for e in np.eye(3)])
        dyn = np.array([np.real(cab.end_response(w, d)) for w, d in zip(omega, loc)])
        out.append(np.array([dyn.reshape(len(omega), -1, 3),
                             np.einsum("knc,mk->mnc", static, loc)]))
    return out


def _cable_energy(cab: ExactCable, fields: tuple[NDArray[np.float64], NDArray[np.float64]],
                  dB: tuple[NDArray[np.complex128], NDArray[np.complex128]],
                  H: NDArray[np.complex128], V0: NDArray[np.complex128], L0: NDArray[np.complex128],
                  EA: NDArray[np.complex128], m0: NDArray[np.complex128],
                  axial: NDArray[np.complex128], w0: NDArray[np.complex128],
                  omega: NDArray[np.float64], base: dict[str, float]) -> NDArray[np.complex128]:
    """u^T (K - omega^2 M) v of one discretised cable (theory.md §11.2) for fields (u, v)
    (each (2, m, n_nodes, 3): at omega and at 0, interior fixed, end B = dB (2 of (B, m, 3)))
    with the catenary (H, V0, L0, EA, m0, axial, w0) of shape (B,); the mesh is held in
    s / L0. Returns the dynamic part E(omega) - E(0), (B, m)."""
    xi, wq, Dm = gll(cab.order)
    p = cab.order
    n_el = len(cab.edges) - 1
    scale = L0 / base["L0"]
    h0 = np.diff(cab.edges)
    sq0 = cab.edges[:-1, None] + 0.5 * (xi[None, :] + 1.0) * h0[:, None]     # (n_el, p+1)
    s = scale[:, None, None] * sq0[None]                                       # (B, e, q)
    V = V0[:, None, None] + w0[:, None, None] * s
    T = np.sqrt(H[:, None, None] ** 2 + V * V)
    tx, tz = H[:, None, None] / T, V / T
    EAs = EA[:, None, None]
    Dt = T / (1.0 + T / EAs)
    EAd = EAs * axial[:, None, None]
    Dxx, Dxz, Dzz = EAd * tx**2 + Dt * tz**2, (EAd - Dt) * tx * tz, EAd * tz**2 + Dt * tx**2
    c = (2.0 / (scale[:, None] * h0[None]))[..., None] * wq                  # (B, e, q)
    idx = np.arange(n_el)[:, None] * p + np.arange(p + 1)[None, :]
    mass = (m0 * L0 / (base["m0"] * base["L0"]))[:, None] * cab.node_mass[None, :]
    out = []
    for j, w in ((0, omega), (1, 0.0 * omega)):
        grads, nodes = [], []
        for f, d in zip(fields, dB):
            u = f[j].copy()                                   # (m, n_nodes, 3), real
            u[:, 0], u[:, -1] = 0.0, 0.0
            g0 = np.matmul(Dm, u[:, idx, :])                  # (m, e, q, 3): interior part
            # end B (the last element's last node) moves with the complex platform motion
            g = np.broadcast_to(g0, (len(H),) + g0.shape).astype(complex)
            g[:, :, -1] += Dm[None, None, :, p, None] * d[:, :, None, :]
            grads.append(g)
            nodes.append((u, d))
        gu, gv = grads
        e = (Dt[:, None] * gu[..., 1] * gv[..., 1] + Dxx[:, None] * gu[..., 0] * gv[..., 0]
             + Dxz[:, None] * (gu[..., 0] * gv[..., 2] + gu[..., 2] * gv[..., 0])
             + Dzz[:, None] * gu[..., 2] * gv[..., 2])
        E = np.einsum("beq,bmeq->bm", c, e)
        (u, du), (v, dv) = nodes
        kin = (mass[:, :-1] @ np.einsum("mkc,mkc->km", u[:, :-1], v[:, :-1])
               + mass[:, -1, None] * np.sum(du * dv, -1))
        out.append(E - w[None, :] ** 2 * kin)
    return out[0] - out[1]


def exact_forms(
        model: ExactModel, lin: LinearisedEquilibrium, Y: NDArray[np.complex128],
        P: dict[str, NDArray[np.complex128]], omega: NDArray[np.float64], X: NDArray[np.float64],
        Z: NDArray[np.float64], fields: tuple[list[NDArray[np.float64]], list[NDArray[np.float64]]],
) -> NDArray[np.complex128]:
    """Exact rung (:class:`dynstiff.models.exact.ExactModel`, theory.md §11); ``fields``
    from :func:`exact_fields` of (X, Z) as a pair."""
    H, V0, L0, q = lin.quantities(Y, P)
    a, b = _motions(X, q["r"]), _motions(Z, q["r"])
    E = _frames(q)
    al, bl = np.einsum("bnji,bmnj->bmni", E, a), np.einsum("bnji,bmnj->bmni", E, b)
    Ks = _static_local(q, H, V0, L0, P)
    total = np.einsum("bmni,bnij,bmnj->bm", al, Ks, bl)
    base_L0 = np.real(lin.quantities(lin.y, lin.P)[2])
    for i, cab in enumerate(model.cables):
        base = {"L0": base_L0[i], "m0": lin.P["m0"][i]}
        total = total + _cable_energy(
            cab, (fields[0][i], fields[1][i]), (al[:, :, i], bl[:, :, i]), H[:, i], V0[:, i],
            L0[:, i], P["EA"][:, i], P["m0"][:, i], P["axial"][:, i], q["w0"][:, i], omega,
            base)
    return total + _platform_terms(lin, Y, P, q, omega, X, Z)


#: The forms of each continuous rung.
FORMS = {"dsm": dsm_forms, "spring": static_forms, "catenary": static_forms}


def forms(
        model: PlatformModel, lin: LinearisedEquilibrium, Y: NDArray[np.complex128],
        P: dict[str, NDArray[np.complex128]], omega: NDArray[np.float64], X: NDArray[np.float64],
        Z: NDArray[np.float64],
        fields: tuple[list[NDArray[np.float64]], list[NDArray[np.float64]]] | None = None,
) -> NDArray[np.complex128]:
    """x_k^T K(omega_k) z_k of ``model``'s rung, (batch, m) (module notes).

    Examples
    --------
    >>> import dynstiff as ds
    >>> from dynstiff.analyses.sensitivity_statics import LinearisedEquilibrium
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m, lin = ds.FrequencyModel(eq), LinearisedEquilibrium(eq)
    >>> Y, P = lin.perturbed([{}], np.zeros((1, lin.y.size)), 0.0)
    >>> x, w = np.eye(6)[[2]], np.array([5.0])
    >>> bool(np.isclose(forms(m, lin, Y, P, w, x, x)[0, 0].real,
    ...                 m.dynamic_stiffness(w)[0, 2, 2]))
    True
    """
    if model.rung == "exact":
        return exact_forms(model, lin, Y, P, omega, X, Z, fields)
    return FORMS[model.rung](model, lin, Y, P, omega, X, Z)
