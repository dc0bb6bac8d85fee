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
offsets (2 n) and the balance (k).

Primitive parameters (a dict of arrays, real or complex): ``EA`` (n,) [N], ``m0`` (n,)
[kg/m], ``mass`` () [kg], ``com`` (3,) [m], ``inertia`` (3, 3) [kg m^2], ``position`` (3,)
[m], ``rotvec`` (3,) [rad], ``anchors`` (n, 3) [m], ``attachments`` (n, 3) [m], ``t_min``,
``t_max`` () [N], ``t_ref`` (n,) [N] (with the default reference, a shift of it),
``L0`` (n,) [m] (at fixed lengths), ``axial`` (n,) [-] (a factor on the dynamic EA only,
1 at the base: the direction of a loss factor). A leading batch axis holds several
perturbed copies at once.
"""

import numpy as np

from dynstiff.errors import InvalidParameterError

__all__ = ["CS_STEP", "LinearisedEquilibrium", "cable_quantities", "catenary_flexibility",
           "catenary_offsets", "divided_differences", "geometric_stiffness", "mean_tension",
           "perturbed_primitives", "platform_mass_forms", "primitives", "rotation", "skew3"]

#: Step of the complex-step derivatives (relative to the unit of each direction).
CS_STEP = 1e-30
_EZ = np.array([0.0, 0.0, 1.0])


# ------------------------------------------------------------------ complex-safe kernels
def skew3(a):
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


def rotation(v):
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


def divided_differences(a, b, delta):
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
    iod = np.where(same, (a + b) / (b * sa + a * sb), (b * sa - a * sb) / d)
    d_asinh = np.where(zero, 1.0 / sa, np.arcsinh(d * iod) / d)
    d_f = np.where(zero, 1.0 / sa**3, iod / (sa * sb))
    d_g = np.where(zero, -a / sa**3, -(a + b) / ((sa + sb) * sa * sb))
    d_sqrt = np.where(zero, a / sa, (a + b) / (sa + sb))
    return d_asinh, d_f, d_g, d_sqrt


def catenary_offsets(H, V0, L0, EA, w0):
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


def catenary_flexibility(H, V0, L0, EA, w0):
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


def mean_tension(H, V0, L0, w0):
    """Tension averaged over the unstretched length [N] (as the catenary's
    ``mean_tension``), analytic.

    Examples
    --------
    >>> round(float(mean_tension(300.0, -40.0, 10.0, 8.0)), 3)   # V from -40 to 40 N
    300.887
    """
    W = w0 * L0
    Vb = V0 + W

    def prim(V):
        return 0.5 * (V * np.sqrt(H * H + V * V) + H * H * np.arcsinh(V / H))

    Vm = V0 + 0.5 * W
    Tm = np.sqrt(H * H + Vm * Vm)
    taylor = np.abs(W) < 1e-6 * np.abs(np.sqrt(H * H + V0 * V0))
    Wd = np.where(taylor, 1.0, W)
    return np.where(taylor, Tm + (W**2 / 24.0) * H * H / Tm**3, (prim(Vb) - prim(V0)) / Wd)


def cable_quantities(P, H, V0, L0, g, position=None, R=None):
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
    >>> lin = LinearisedEquilibrium(eq)
    >>> q = lin.quantities(lin.y, lin.P)[3]
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


def geometric_stiffness(f, r, fg, rG):
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


def platform_mass_forms(P, R):
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


def _wrench(P, q, g):
    """Total wrench of the cables and gravity on the platform about P, (..., 6) [N, N m]."""
    m = np.asarray(P["mass"])
    fg = m[..., None] * np.array([0.0, 0.0, -g])
    rG = np.einsum("...ij,...j->...i", q["R"], P["com"])
    F = q["f"].sum(-2) + fg
    M = np.cross(q["r"], q["f"]).sum(-2) + np.cross(rG, fg)
    return np.concatenate([F, M], -1)


def primitives(robot, pose, tension_reference=None, unstretched_lengths=None):
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


def perturbed_primitives(P, directions, step=CS_STEP):
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

    def __init__(self, equilibrium, hold="pose", tension_reference=None):
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
    def _active_set(self, q, V0):
        t_min, t_max = float(self.P["t_min"]), float(self.P["t_max"])
        lo = self._min_tension(q, V0)
        hi = np.maximum(q["TB"], q["TA"])
        tol = 1e-7 * max(1.0, t_min, float(np.max(q["TB"])))
        return np.where(np.abs(lo - t_min) <= tol, -1,
                        np.where(np.abs(hi - t_max) <= tol, 1, 0))

    @staticmethod
    def _min_tension(q, V0):
        """Least tension along each cable (as ``CatenaryState.min_tension``), analytic with
        the branch of the real values."""
        V0r, Vbr = np.real(V0), np.real(q["Vb"])
        H = np.sqrt(q["TA"] ** 2 - V0 ** 2)
        inner = (V0r < 0) & (Vbr > 0)
        return np.where(inner, H, np.where(np.abs(V0r) <= np.abs(Vbr), q["TA"], q["TB"]))

    def _split(self, y):
        n = self.n
        if self.hold == "lengths":
            return y[..., :n], y[..., n:2 * n], None, None, y[..., 2 * n:]
        return y[..., :n], y[..., n:2 * n], y[..., 2 * n:3 * n], y[..., 3 * n:4 * n], \
            y[..., 4 * n:]

    def pose_of(self, y, P):
        """(position (..., 3), rotation (..., 3, 3)) of the platform for unknowns y."""
        if self.hold == "pose":
            return P["position"], rotation(P["rotvec"])
        d6 = np.zeros(np.shape(y)[:-1] + (6,), dtype=np.result_type(y, float))
        d6[..., self.fi] = self._split(y)[4]
        return (P["position"] + d6[..., :3],
                rotation(d6[..., 3:]) @ rotation(P["rotvec"]))

    def quantities(self, y, P):
        """(H, V0, L0, cable quantities) at unknowns y and primitives P (batch allowed)."""
        H, V0, L0, _, _ = self._split(y)
        if L0 is None:
            L0 = P["L0"]
        pos, R = self.pose_of(y, P)
        return H, V0, L0, cable_quantities(P, H, V0, L0, self.g, pos, R)

    def residual(self, y, P):
        """R(y, p), shape (..., n_y): offsets [m], tensions [N], optimality [N], balance
        [N, N m] (theory.md §16.2)."""
        H, V0, L0, q = self.quantities(y, P)
        x, z = catenary_offsets(H, V0, L0, P["EA"], q["w0"])
        parts = [x - q["lh"], z - q["h"]]
        bal = _wrench(P, q, self.g)[..., self.fi]
        if self.hold == "pose":
            _, _, _, t, nu = self._split(y)
            W = np.concatenate([q["f"], np.cross(q["r"], q["f"])], -1) / q["TB"][..., None]
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

    def tension_extremes(self, y, P):
        """Least and largest tension along every cable [N], (..., n) each, analytic (the
        limits of the distribution hold all along the cables, theory.md §4)."""
        _, V0, _, q = self.quantities(y, P)
        hi = np.where(np.real(q["TB"]) >= np.real(q["TA"]), q["TB"], q["TA"])
        return self._min_tension(q, V0), hi

    def _multipliers(self, y):
        """Balance multipliers nu from the free cables' optimality, the residual of that
        fit [N], and the limit multipliers [N]."""
        R = self.residual(y, self.P)
        n, k = self.n, self.k
        opt = R[3 * n:4 * n]                       # with nu = 0: t - t_ref (free cables)
        H, V0, L0, q = self.quantities(y, self.P)
        W = (np.concatenate([q["f"], np.cross(q["r"], q["f"])], -1)
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
    def jacobian_y(self):
        """dR/dy, square, by the complex step (all unit directions in one batch)."""
        ny = self.y.size
        Y = self.y[None, :] + 1j * CS_STEP * np.eye(ny)
        P = perturbed_primitives(self.P, [{}] * ny, 0.0)
        return (np.imag(self.residual(Y, P)) / CS_STEP).T

    @staticmethod
    def _factor(J):
        import scipy.linalg
        lu = scipy.linalg.lu_factor(J)
        if np.min(np.abs(np.diag(lu[0]))) <= 1e-13 * np.abs(np.diag(lu[0])).max():
            raise np.linalg.LinAlgError("singular")
        return lu

    def derivatives(self, directions):
        """dy/dp along each direction (a list of dicts of primitive increments), shape
        (n_directions, n_y)."""
        import scipy.linalg
        if not directions:
            return np.zeros((0, self.y.size))
        Y = np.broadcast_to(self.y.astype(complex), (len(directions), self.y.size))
        P = perturbed_primitives(self.P, directions, CS_STEP)
        Rp = np.imag(self.residual(Y, P)) / CS_STEP
        return -scipy.linalg.lu_solve(self._lu, Rp.T, check_finite=False).T

    def perturbed(self, directions, dy, step=CS_STEP):
        """(y + i step dy, P + i step d) for every direction: the complex inputs of the
        rungs' forms."""
        Y = self.y[None, :] + 1j * step * dy
        return Y, perturbed_primitives(self.P, directions, step)
