"""Complex-step-safe kernels of the sensitivities (theory.md §16.1-§16.3): the elastic
catenary's end offsets, flexibility and mean tension, rotations, the cables' geometry and
forces at a pose, the wrench balance, the geometric stiffness and the platform's mass matrix,
all analytic in their arguments (branches chosen on real parts, square roots of sums of
squares instead of norms), and the primitive parameters with their complex perturbations.

Primitive parameters (a dict of arrays, real or complex): ``EA`` (n,) [N], ``m0`` (n,)
[kg/m], ``mass`` () [kg], ``com`` (3,) [m], ``inertia`` (3, 3) [kg m^2], ``position`` (3,)
[m], ``rotvec`` (3,) [rad], ``anchors`` (n, 3) [m], ``attachments`` (n, 3) [m], ``t_min``,
``t_max`` () [N], ``t_ref`` (n,) [N] (with the default reference, a shift of it),
``L0`` (n,) [m] (at fixed lengths), ``axial`` (n,) [-] (a factor on the dynamic EA only,
1 at the base: the direction of a loss factor). A leading batch axis holds several
perturbed copies at once.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.robot.pose import Pose
    from dynstiff.robot.robot import Robot

__all__ = ["CS_STEP", "cable_quantities", "catenary_flexibility", "catenary_offsets",
           "divided_differences", "geometric_stiffness", "mean_tension",
           "perturbed_primitives", "platform_mass_forms", "primitives", "rotation", "skew3",
           "wrench"]

#: Step of the complex-step derivatives (relative to the unit of each direction).
CS_STEP = 1e-30
_EZ = np.array([0.0, 0.0, 1.0])


def skew3(a: NDArray[Any]) -> NDArray[Any]:
    """[a]x of vectors a (..., 3) -> (..., 3, 3), complex-safe.

    Examples
    --------
    >>> skew3(np.array([1.0, 2.0, 3.0])) @ np.array([0.0, 0.0, 1.0])     # a x e_z
    array([ 2., -1.,  0.])
    """
    z = np.zeros_like(a[..., 0])
    return np.stack([np.stack([z, -a[..., 2], a[..., 1]], -1),
                     np.stack([a[..., 2], z, -a[..., 0]], -1),
                     np.stack([-a[..., 1], a[..., 0], z], -1)], -2)


def rotation(v: NDArray[Any]) -> NDArray[Any]:
    """Rotation matrix of rotation vectors v (..., 3) [rad] -> (..., 3, 3), analytic in v
    (Rodrigues' formula, its series below theta^2 = 1e-6; the same matrix as
    :attr:`dynstiff.Pose.matrix` for real v).

    Examples
    --------
    >>> np.round(rotation(np.array([0.0, 0.0, np.pi / 2])) @ [1.0, 0.0, 0.0], 12)
    array([0., 1., 0.])
    """
    v = np.asarray(v)
    th2 = np.sum(v * v, axis=-1)
    small = np.abs(th2) < 1e-6
    th = np.sqrt(np.where(small, 1.0, th2))
    a = np.where(small, 1 - th2 / 6 + th2**2 / 120, np.sin(th) / th)
    b = np.where(small, 0.5 - th2 / 24 + th2**2 / 720, (1 - np.cos(th)) / th**2)
    S = skew3(v)
    return np.eye(3) + a[..., None, None] * S + b[..., None, None] * (S @ S)


def divided_differences(
        a: NDArray[Any], b: NDArray[Any], delta: NDArray[Any],
) -> tuple[NDArray[Any], NDArray[Any], NDArray[Any], NDArray[Any]]:
    """(F(b) - F(a)) / delta for F = asinh(t), t / sqrt(1 + t^2), 1 / sqrt(1 + t^2),
    sqrt(1 + t^2) and b = a + delta, without cancellation: the forms of
    :func:`dynstiff.cable.catenary.divided_differences`, analytic (branches chosen on the
    real parts), for the complex step.

    Examples
    --------
    >>> [round(float(v), 6) for v in divided_differences(0.5, 0.5, 0.0)]   # derivatives
    [0.894427, 0.715542, -0.357771, 0.447214]
    """
    sa, sb = np.sqrt(1 + a * a), np.sqrt(1 + b * b)
    same = np.real(a) * np.real(b) > 0
    zero = np.real(delta) == 0
    d = np.where(zero, 1.0, delta)
    with np.errstate(divide="ignore", invalid="ignore"):    # np.where evaluates both forms
        iod = np.where(same, (a + b) / (b * sa + a * sb), (b * sa - a * sb) / d)
    d_asinh = np.where(zero, 1.0 / sa, np.arcsinh(d * iod) / d)
    d_f = np.where(zero, 1.0 / sa**3, iod / (sa * sb))
    d_g = np.where(zero, -a / sa**3, -(a + b) / ((sa + sb) * sa * sb))
    d_sqrt = np.where(zero, a / sa, (a + b) / (sa + sb))
    return d_asinh, d_f, d_g, d_sqrt


def catenary_offsets(H: NDArray[Any], V0: NDArray[Any], L0: NDArray[Any], EA: NDArray[Any],
                     w0: NDArray[Any]) -> tuple[NDArray[Any], NDArray[Any]]:
    """End offsets (x, z) [m] of the elastic catenary from A (theory.md §1.1), analytic in
    every argument (arrays of one shape).

    Examples
    --------
    >>> x, z = catenary_offsets(1000.0, 0.0, 10.0, 1e6, 1e-9)   # weightless: straight
    >>> round(float(x), 9), round(float(z), 9)
    (10.01, 0.0)
    """
    W = w0 * L0
    d_asinh, _, _, d_sqrt = divided_differences(V0 / H, (V0 + W) / H, W / H)
    return L0 * (H / EA + d_asinh), L0 * ((V0 + 0.5 * W) / EA + d_sqrt)


def catenary_flexibility(H: NDArray[np.complex128], V0: NDArray[np.complex128],
                         L0: NDArray[np.complex128], EA: NDArray[np.complex128],
                         w0: NDArray[np.complex128]) -> tuple[NDArray[np.complex128], ...]:
    """In-plane flexibility d(x, z)/d(H, Vb) = int D^-1 ds of the catenary [m/N]
    (theory.md §1.1, §11.1), (f_xx, f_xz, f_zz), analytic.

    Examples
    --------
    >>> [round(float(v), 9) + 0.0 for v in catenary_flexibility(1000.0, 0.0, 10.0, 1e6, 1e-9)]
    [1e-05, 0.0, 0.01001]
    """
    W = w0 * L0
    d_asinh, d_f, d_g, _ = divided_differences(V0 / H, (V0 + W) / H, W / H)
    return (L0 / EA + (L0 / H) * (d_asinh - d_f), (L0 / H) * d_g, L0 / EA + (L0 / H) * d_f)


def mean_tension(H: NDArray[np.complex128], V0: NDArray[np.complex128], L0: NDArray[np.complex128],
                 w0: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Tension averaged over the unstretched length [N] (as the catenary's
    ``mean_tension``), analytic.

    Examples
    --------
    >>> round(float(mean_tension(300.0, -40.0, 10.0, 8.0)), 3)   # V from -40 to 40 N
    300.887
    """
    W = w0 * L0
    Vb = V0 + W

    def prim(V: NDArray[np.complex128]) -> NDArray[np.complex128]:
        return 0.5 * (V * np.sqrt(H * H + V * V) + H * H * np.arcsinh(V / H))

    Vm = V0 + 0.5 * W
    Tm = np.sqrt(H * H + Vm * Vm)
    taylor = np.abs(W) < 1e-6 * np.abs(np.sqrt(H * H + V0 * V0))
    Wd = np.where(taylor, 1.0, W)
    return np.where(taylor, Tm + (W**2 / 24.0) * H * H / Tm**3, (prim(Vb) - prim(V0)) / Wd)


def cable_quantities(P: dict[str, NDArray[Any]], H: NDArray[Any], V0: NDArray[Any],
                     L0: NDArray[Any], g: float, position: NDArray[Any] | None = None,
                     R: NDArray[Any] | None = None) -> dict[str, NDArray[Any]]:
    """Geometry and forces of every cable from primitives ``P`` and catenary unknowns.

    Parameters
    ----------
    P : dict of arrays
        Primitive parameters (module notes), with an optional leading batch axis.
    H, V0, L0 : arrays (..., n)
        Catenary unknowns [N, N, m].
    g : float
        Gravity [m/s^2].
    position, R : arrays (..., 3), (..., 3, 3), optional
        The platform's position and rotation (default from ``P``).

    Returns
    -------
    dict with r (lever arms, (..., n, 3)), B, d (chord B - A), lh, h, eh (horizontal
    direction), Vb, TB, TA (end tensions), f (force of each cable on the platform), R,
    position, w0.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> P = primitives(eq.robot, eq.pose)
    >>> H, V0 = (np.array([getattr(s, a) for s in eq.states]) for a in ("H", "V0"))
    >>> q = cable_quantities(P, H, V0, eq.unstretched_lengths, eq.robot.g)
    >>> bool(np.allclose(q["TB"], eq.tensions))
    True
    """
    if R is None:
        R = rotation(P["rotvec"])
    if position is None:
        position = P["position"]
    r = np.einsum("...ij,...nj->...ni", R, P["attachments"])
    B = position[..., None, :] + r
    d = B - P["anchors"]
    lh = np.sqrt(d[..., 0] ** 2 + d[..., 1] ** 2)
    eh = np.stack([d[..., 0] / lh, d[..., 1] / lh, np.zeros_like(lh)], -1)
    w0 = P["m0"] * g
    Vb = V0 + w0 * L0
    f = -(H[..., None] * eh + Vb[..., None] * _EZ)
    return dict(r=r, B=B, d=d, lh=lh, h=d[..., 2], eh=eh, Vb=Vb,
                TB=np.sqrt(H * H + Vb * Vb), TA=np.sqrt(H * H + V0 * V0), f=f, R=R,
                position=position, w0=w0)


def geometric_stiffness(f: NDArray[np.complex128], r: NDArray[np.complex128],
                        fg: NDArray[np.complex128],
                        rG: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Rotation block of K_geo, -sum_i [f_i]x [r_i]x - [f_g]x [r_G]x (theory.md §4), for
    forces f (B, n, 3) at lever arms r (B, n, 3) and the weight f_g (B, 3) at r_G (B, 3):
    (B, 3, 3), analytic ([a]x [b]x = b a^T - (a . b) I).

    Examples
    --------
    >>> f, r = np.array([[[0.0, 0.0, 10.0]]]), np.array([[[0.0, 0.0, 1.0]]])
    >>> geometric_stiffness(f, r, np.zeros((1, 3)), np.zeros((1, 3)))[0].diagonal()
    array([10., 10.,  0.])
    """
    eye = np.eye(3)
    G = (np.einsum("bn,ij->bij", np.sum(f * r, -1), eye)
         - np.einsum("bni,bnj->bij", r, f))
    return G + np.sum(fg * rG, -1)[:, None, None] * eye - rG[:, :, None] * fg[:, None, :]


def platform_mass_forms(P: dict[str, NDArray[np.complex128]],
                        R: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """Platform mass matrix about P, base axes, (..., 6, 6) [kg, kg m, kg m^2]
    (theory.md §4), analytic in the mass, centre of mass, inertia and rotation.

    Examples
    --------
    >>> P = {"mass": 2.0, "com": np.zeros(3), "inertia": np.eye(3)}
    >>> platform_mass_forms(P, np.eye(3)).diagonal()
    array([2., 2., 2., 1., 1., 1.])
    """
    m = np.asarray(P["mass"])
    rG = np.einsum("...ij,...j->...i", R, P["com"])
    S = skew3(rG)
    SS = rG[..., :, None] * rG[..., None, :] - np.sum(rG * rG, -1)[..., None, None] * np.eye(3)
    IG = R @ P["inertia"] @ np.swapaxes(R, -1, -2)
    mI = m[..., None, None] * np.eye(3)
    top = np.concatenate([mI, -m[..., None, None] * S], -1)
    bot = np.concatenate([m[..., None, None] * S, IG - m[..., None, None] * SS], -1)
    return np.concatenate([top, bot], -2)


def wrench(P: dict[str, NDArray[Any]], q: dict[str, NDArray[Any]], g: float) -> NDArray[Any]:
    """Total wrench of the cables and gravity on the platform about P, (..., 6) [N, N m]."""
    m = np.asarray(P["mass"])
    fg = m[..., None] * np.array([0.0, 0.0, -g])
    rG = np.einsum("...ij,...j->...i", q["R"], P["com"])
    F = q["f"].sum(-2) + fg
    M = cross(q["r"], q["f"]).sum(-2) + cross(rG, fg)
    return np.concatenate([F, M], -1)


def primitives(
        robot: Robot, pose: Pose, tension_reference: NDArray[np.float64] | None = None,
        unstretched_lengths: NDArray[np.float64] | None = None,
) -> dict[str, NDArray[np.float64]]:
    """The primitive parameters of ``robot`` at ``pose`` (module notes), real arrays.

    ``tension_reference`` None: the default reference of the distribution (``t_ref`` holds
    its shift, 0); else the reference [N], scalar or (n,). ``unstretched_lengths`` [m]
    (at fixed lengths).

    Examples
    --------
    >>> import dynstiff as ds
    >>> sc = ds.load_scene("cogiro")
    >>> float(primitives(sc.robot, sc.pose)["mass"])
    91.058
    """
    n = robot.n_cables
    pl = robot.platform
    P = dict(EA=np.array([c.EA for c in robot.cables], dtype=float),
             m0=np.array([c.mass_per_length for c in robot.cables], dtype=float),
             mass=np.array(pl.mass, dtype=float), com=np.array(pl.center_of_mass, float),
             inertia=np.array(pl.inertia, float), position=np.array(pose.position, float),
             rotvec=np.array(pose.rotation, float), anchors=np.array(robot.anchors, float),
             attachments=np.array(robot.attachments, float),
             t_min=np.array(robot.tension_limits[0], float),
             t_max=np.array(robot.tension_limits[1], float),
             t_ref=np.zeros(n) if tension_reference is None
             else np.broadcast_to(np.asarray(tension_reference, float), (n,)).copy(),
             L0=np.zeros(n) if unstretched_lengths is None
             else np.asarray(unstretched_lengths, float).copy(),
             axial=np.ones(n))
    return P


def perturbed_primitives(P: dict[str, NDArray[np.float64]],
                         directions: list[dict[str, NDArray[np.float64] | float]],
                         step: float = CS_STEP) -> dict[str, NDArray[np.complex128]]:
    """P + i step d for every direction (a list of dicts of primitive increments): a batch
    (n_directions, ...) of complex arrays, the complex-step inputs.

    Examples
    --------
    >>> P = perturbed_primitives({"mass": np.array(2.0)}, [{}, {"mass": 1.0}], 1e-30)
    >>> P["mass"].imag / 1e-30
    array([0., 1.])
    """
    out = {}
    nd = len(directions)
    for key, v in P.items():
        a = np.empty((nd,) + np.shape(v), dtype=complex)
        a[...] = v
        for j, d in enumerate(directions):
            if key in d:
                a[j] += 1j * step * np.asarray(d[key])
        out[key] = a
    return out
