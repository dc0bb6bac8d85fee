"""Exact elastic-catenary statics of one cable between a fixed anchor A and an end B.

Notation (theory.md §1.1; Irvine, *Cable Structures*, 1981, §2.2)
-----------------------------------------------------------------
=========  ==========================================================  ======
symbol     meaning                                                     unit
=========  ==========================================================  ======
s          unstretched arc length from A, 0 <= s <= L0                 m
w0         weight per unstretched length, m g                          N/m
W          total weight, w0 L0                                         N
H          horizontal tension component (constant along the cable)     N
V0         vertical tension component at A (> 0: cable rises from A)   N
Vb         vertical tension component at B, V0 + W                      N
l_h, h     horizontal and vertical offset of B from A                  m
=========  ==========================================================  ======

The profile in the vertical plane of the cable (x horizontal from A towards B, z up) is::

    x(s) = H s / EA + (H / w0) [asinh((V0 + w0 s)/H) - asinh(V0/H)]
    z(s) = (V0 s + w0 s^2 / 2) / EA + (1 / w0) [sqrt(H^2 + (V0 + w0 s)^2) - sqrt(H^2 + V0^2)]

and (H, V0) solve x(L0) = l_h, z(L0) = h. The differences of asinh and sqrt are evaluated
in a cancellation-free form (divided differences), so the formulas stay accurate for an
almost weightless cable (W << H) and for an almost vertical one (H << |V|).
"""

from dataclasses import dataclass
from numbers import Integral

import numpy as np

from dynstiff._validate import point, positive_scalar
from dynstiff._vec import cross
from dynstiff.cable.chord import chord_parameters
from dynstiff.constants import MAX_COORDINATE, STANDARD_GRAVITY
from dynstiff.errors import ConvergenceError, InvalidParameterError, SlackCableError
from dynstiff.params import Cable

__all__ = ["CatenaryState", "solve_catenary", "unstretched_length_for_tension",
           "divided_differences", "end_stiffnesses"]

_RTOL = 1e-12
_EZ = np.array([0.0, 0.0, 1.0])


# --------------------------------------------------------------------------- kernels
def divided_differences(a, b, delta):
    """Cancellation-free divided differences between t = a and t = b = a + delta >= a.

    Returns (D_asinh, D_f, D_g, D_sqrt), each (F(b) - F(a)) / delta for
    F = asinh(t), t / sqrt(1 + t^2), 1 / sqrt(1 + t^2), sqrt(1 + t^2), and the derivatives at
    a where delta = 0 (weightless cable). Scalars or arrays of one shape (n,), elementwise
    (also the batched statics, :mod:`dynstiff.catenary_batch`). Uses
    asinh(b) - asinh(a) = asinh(b sqrt(1+a^2) - a sqrt(1+b^2)) and rationalised differences
    so nothing cancels when delta << |a|.
    """
    sa, sb = np.hypot(1.0, a), np.hypot(1.0, b)
    same = a * b > 0
    zero = delta == 0
    d = np.where(zero, 1.0, delta)
    with np.errstate(divide="ignore", invalid="ignore"):
        # same sign: rationalise b sa - a sb = delta (a + b) / (b sa + a sb); else both
        # terms are >= 0 and nothing cancels
        iod_same = (a + b) / (b * sa + a * sb)
        inner_other = b * sa - a * sb
        iod = np.where(same, iod_same, inner_other / d)
    inner = np.where(same, d * iod_same, inner_other)
    d_asinh = np.where(zero, 1.0 / sa, np.arcsinh(inner) / d)
    d_f = np.where(zero, 1.0 / sa**3, iod / (sa * sb))
    d_g = np.where(zero, -a / sa**3, -(a + b) / ((sa + sb) * sa * sb))
    d_sqrt = np.where(zero, a / sa, (a + b) / (sa + sb))
    return d_asinh, d_f, d_g, d_sqrt


def _end_offsets_and_flexibility(H, V0, L0, EA, w0):
    """End offset (x, z) of B from A and its Jacobian with respect to (H, V0).

    Parameters are floats [N, N, m, N, N/m], H > 0. Returns ``xz`` (2,) [m] and
    ``F`` (2, 2) [m/N], F = d(x, z)/d(H, V0). F is also the in-plane flexibility
    d(x, z)/d(H, Vb) of the end B, because Vb = V0 + W with W fixed.
    """
    W = w0 * L0
    a, b, delta = V0 / H, (V0 + W) / H, W / H
    d_asinh, d_f, d_g, d_sqrt = divided_differences(a, b, delta)
    x = L0 * (H / EA + d_asinh)
    z = L0 * ((V0 + 0.5 * W) / EA + d_sqrt)
    dx_dH = L0 / EA + (L0 / H) * (d_asinh - d_f)
    dx_dV = (L0 / H) * d_g
    dz_dV = L0 / EA + (L0 / H) * d_f
    return np.array([x, z]), np.array([[dx_dH, dx_dV], [dx_dV, dz_dV]])


def _mean_tension(H, V0, L0, w0):
    """Mean tension over the unstretched length, (1/L0) int_0^L0 T(s) ds [N]."""
    W = w0 * L0
    if H == 0.0:
        return abs(V0 + 0.5 * W) if V0 * (V0 + W) >= 0 else 0.5 * (V0**2 + (V0 + W) ** 2) / W

    def prim(V):  # int sqrt(H^2 + V^2) dV
        return 0.5 * (V * np.hypot(H, V) + H * H * np.arcsinh(V / H))

    if W < 1e-6 * np.hypot(H, V0):     # Taylor: mean of T over V in [V0, V0+W]
        Vm = V0 + 0.5 * W
        Tm = np.hypot(H, Vm)
        return Tm + (W**2 / 24.0) * H * H / Tm**3
    return (prim(V0 + W) - prim(V0)) / W


# --------------------------------------------------------------------------- result
@dataclass(frozen=True)
class CatenaryState:
    """Static equilibrium of one elastic catenary (all vectors in the global frame).

    Attributes
    ----------
    anchor, end : ndarray, shape (3,)
        Positions of A and B [m].
    unstretched_length : float
        L0 [m].
    cable : Cable
    g : float
        Gravity [m/s^2].
    H : float
        Horizontal tension component [N].
    V0 : float
        Vertical tension component at A [N], positive when the cable rises from A.
    residual : float
        Final relative residual of the end-offset equations [-].
    """

    anchor: np.ndarray
    end: np.ndarray
    unstretched_length: float
    cable: Cable
    g: float
    H: float
    V0: float
    residual: float

    # ---- geometry of the cable plane
    @property
    def chord(self):
        """Chord vector B - A [m], shape (3,)."""
        return self.end - self.anchor

    @property
    def chord_length(self):
        """Chord length L = |B - A| [m]."""
        return float(np.linalg.norm(self.chord))

    @property
    def horizontal_span(self):
        """Horizontal distance l_h between A and B [m]."""
        return float(np.hypot(self.chord[0], self.chord[1]))

    @property
    def horizontal_direction(self):
        """Unit horizontal vector from A towards B, shape (3,).

        For an exactly vertical chord it is an arbitrary (fixed) horizontal axis, x.
        """
        lh = self.horizontal_span
        if lh <= 1e-14 * self.chord_length:
            return np.array([1.0, 0.0, 0.0])
        return np.array([self.chord[0] / lh, self.chord[1] / lh, 0.0])

    # ---- forces
    @property
    def total_weight(self):
        """W = m g L0 [N]."""
        return self.cable.mass_per_length * self.g * self.unstretched_length

    @property
    def Vb(self):
        """Vertical tension component at B, V0 + W [N]."""
        return self.V0 + self.total_weight

    @property
    def horizontal_tension(self):
        """Horizontal tension component H [N]."""
        return self.H

    @property
    def force_on_end(self):
        """Force of the cable on the end B [N], shape (3,): -(H e_h + Vb e_z)."""
        return -(self.H * self.horizontal_direction + self.Vb * _EZ)

    @property
    def force_on_anchor(self):
        """Force of the cable on the anchor A [N], shape (3,): H e_h + V0 e_z."""
        return self.H * self.horizontal_direction + self.V0 * _EZ

    @property
    def tension_at_end(self):
        """Tension at B [N]."""
        return float(np.hypot(self.H, self.Vb))

    @property
    def tension_at_anchor(self):
        """Tension at A [N]."""
        return float(np.hypot(self.H, self.V0))

    @property
    def min_tension(self):
        """Least tension along the cable [N]: H where the cable has its lowest point between
        A and B (V changes sign), else the smaller end tension (T = sqrt(H^2 + V^2), V
        linear in the arc length)."""
        if self.V0 < 0.0 < self.Vb:
            return float(self.H)
        return float(np.hypot(self.H, min(abs(self.V0), abs(self.Vb))))

    @property
    def max_tension(self):
        """Largest tension along the cable [N], at the higher-tension end."""
        return max(self.tension_at_end, self.tension_at_anchor)

    @property
    def mean_tension(self):
        """Tension averaged over the unstretched length [N]."""
        return float(_mean_tension(self.H, self.V0, self.unstretched_length,
                                   self.cable.weight_per_length(self.g)))

    def tension(self, s):
        """Tension T(s) = sqrt(H^2 + (V0 + w0 s)^2) [N] at unstretched arc length s [m]."""
        s = np.asarray(s, dtype=float)
        return np.hypot(self.H, self.V0 + self.cable.weight_per_length(self.g) * s)

    @property
    def stretched_length(self):
        """Arc length of the stretched cable, L0 + int T/EA ds [m]."""
        L0 = self.unstretched_length
        return L0 * (1.0 + self.mean_tension / self.cable.EA)

    # ---- profile
    def profile_plane(self, s):
        """In-plane coordinates (x, z) [m] of the points at unstretched arc lengths ``s`` [m].

        Returns an array of shape (len(s), 2).
        """
        s = np.atleast_1d(np.asarray(s, dtype=float))
        EA, w0 = self.cable.EA, self.cable.weight_per_length(self.g)
        out = np.empty((s.size, 2))
        for k, sk in enumerate(s):
            if sk == 0.0:
                out[k] = 0.0
            elif self.H == 0.0:
                out[k] = (0.0, (self.V0 * sk + 0.5 * w0 * sk * sk) / EA
                          + np.sign(self.V0 + 0.5 * w0 * sk) * sk)
            else:
                out[k], _ = _end_offsets_and_flexibility(self.H, self.V0, sk, EA, w0)
        return out

    def profile(self, n=50):
        """Points of the cable, shape (n, 3) [m], equally spaced in unstretched arc length."""
        n = int(n)
        if n < 2:
            raise InvalidParameterError(f"n must be an integer >= 2, got {n!r}")
        xz = self.profile_plane(np.linspace(0.0, self.unstretched_length, n))
        return (self.anchor + np.outer(xz[:, 0], self.horizontal_direction)
                + np.outer(xz[:, 1], _EZ))

    def to_frame(self, n=50):
        """pandas DataFrame of the profile: unstretched arc length s from A [m], the point
        (x, y, z) [m] in the base frame and the tension T(s) [N], ``n`` rows equally spaced
        in s (theory.md §1.1)."""
        import pandas as pd
        pts = self.profile(n)
        s = np.linspace(0.0, self.unstretched_length, pts.shape[0])
        return pd.DataFrame({"s [m]": s, "x [m]": pts[:, 0], "y [m]": pts[:, 1],
                             "z [m]": pts[:, 2], "tension [N]": self.tension(s)})

    @property
    def sag(self):
        """Largest distance of the cable from its chord *segment* AB [m] (from a 401-point
        profile; a point beyond an end of the segment counts its distance to that end, so a
        slack cable hanging in a U below its lower end shows its true sag)."""
        p = self.profile(401) - self.anchor
        L = self.chord_length
        e = self.chord / L
        along = np.clip(p @ e, 0.0, L)
        return float(np.max(np.linalg.norm(p - np.outer(along, e), axis=1)))

    # ---- chord-frame (parabolic) parameters used by the linear dynamic theory
    @property
    def cos_theta(self):
        """cos of the chord inclination to the horizontal [-]."""
        return self.horizontal_span / self.chord_length

    @property
    def lambda_sq(self):
        """Irvine parameter lambda^2 [-] (see :func:`dynstiff.cable.chord.chord_parameters`).

        The chord theory's value (q L / T)^2 L EA / (T L_e) assumes the parabola of sag
        d = q L^2 / (8 T). Where the measured :attr:`sag` is more than twice that (a slack
        cable, e.g. hanging in a U under a near-vertical chord, whose q is ~0), the same
        parameter is reported with the measured sag, 64 (d/L)^2 L EA / (T L_e), so that a
        slack cable is never reported as a taut string (theory.md §11.5)."""
        p = chord_parameters(self)
        if self.sag > 2.0 * p.sag:
            return float(64.0 * (self.sag / p.L) ** 2 * p.L * self.cable.EA / (p.T * p.L_e))
        return p.lambda_sq

    # ---- stiffness
    @property
    def in_plane_flexibility(self):
        """d(l_h, h)/d(H, Vb) [m/N], shape (2, 2): compliance of the end B in the cable plane."""
        if self.H == 0.0:
            L0, EA = self.unstretched_length, self.cable.EA
            return np.array([[1.0 / self._vertical_lateral_stiffness(), 0.0],
                             [0.0, L0 / EA]])
        _, F = _end_offsets_and_flexibility(self.H, self.V0, self.unstretched_length,
                                            self.cable.EA, self.cable.weight_per_length(self.g))
        return F

    def _vertical_lateral_stiffness(self):
        """H / l_h in the limit H -> 0 (vertical chord) [N/m].

        From x = H L0/EA + (H/w0)[asinh(Vb/H) - asinh(V0/H)]:
        x / H -> L0/EA + |ln(Vb/V0)| / w0 = L0/EA + int_0^L0 ds / T(s).
        """
        L0, EA = self.unstretched_length, self.cable.EA
        w0 = self.cable.weight_per_length(self.g)
        return 1.0 / (L0 / EA + abs(np.log1p(w0 * L0 / self.V0)) / w0)

    @property
    def out_of_plane_stiffness(self):
        """Stiffness of B perpendicular to the vertical cable plane, H / l_h [N/m]."""
        if self.H == 0.0:
            return float(self._vertical_lateral_stiffness())
        return float(self.H / self.horizontal_span)

    @property
    def end_stiffness(self):
        """Static 3x3 stiffness of the end B [N/m] in the global frame, A fixed.

        K = -d f_B / d r_B: in-plane block from the inverse of the flexibility
        d(l_h, h)/d(H, Vb), out-of-plane term H / l_h (rotation of the cable plane).
        Symmetric positive definite for a taut cable.
        """
        e_h = self.horizontal_direction
        e_p = cross(_EZ, e_h)
        K2 = np.linalg.inv(self.in_plane_flexibility)
        B = np.column_stack([e_h, _EZ])
        K = B @ K2 @ B.T + self.out_of_plane_stiffness * np.outer(e_p, e_p)
        return 0.5 * (K + K.T)


def end_stiffnesses(states):
    """:attr:`CatenaryState.end_stiffness` of many cables at once [N/m], shape (n, 3, 3).

    The same formulas on arrays (in-plane flexibility of §1.1 inverted, out-of-plane term
    H / l_h, symmetrised); a cable with H = 0 (vertical chord) takes its own property.
    Equal to the one-cable property to round-off."""
    n = len(states)
    H = np.array([s.H for s in states])
    V0 = np.array([s.V0 for s in states])
    L0 = np.array([s.unstretched_length for s in states])
    EA = np.array([s.cable.EA for s in states])
    w0 = np.array([s.cable.weight_per_length(s.g) for s in states])
    d = np.array([s.end - s.anchor for s in states]).reshape(n, 3)
    lh = np.hypot(d[:, 0], d[:, 1])
    taut = H != 0.0
    Hs = np.where(taut, H, 1.0)
    W = w0 * L0
    a, b = V0 / Hs, (V0 + W) / Hs
    d_asinh, d_f, d_g, _ = divided_differences(a, b, W / Hs)
    f11 = L0 / EA + (L0 / Hs) * (d_asinh - d_f)
    f12 = (L0 / Hs) * d_g
    f22 = L0 / EA + (L0 / Hs) * d_f
    det = f11 * f22 - f12 * f12
    k11, k12, k22 = f22 / det, -f12 / det, f11 / det          # inverse of the flexibility
    vertical = lh <= 1e-14 * np.linalg.norm(d, axis=1)
    lh_s = np.where(vertical, 1.0, lh)
    eh = np.stack([np.where(vertical, 1.0, d[:, 0] / lh_s),
                   np.where(vertical, 0.0, d[:, 1] / lh_s), np.zeros(n)], axis=1)
    ep = np.stack([-eh[:, 1], eh[:, 0], np.zeros(n)], axis=1)           # e_z x e_h
    ez = np.broadcast_to(_EZ, (n, 3))
    K = (k11[:, None, None] * eh[:, :, None] * eh[:, None, :]
         + k12[:, None, None] * (eh[:, :, None] * ez[:, None, :] + ez[:, :, None] * eh[:, None, :])
         + k22[:, None, None] * ez[:, :, None] * ez[:, None, :]
         + (Hs / lh_s)[:, None, None] * ep[:, :, None] * ep[:, None, :])
    K = 0.5 * (K + np.swapaxes(K, 1, 2))
    for i in np.flatnonzero(~taut):
        K[i] = states[i].end_stiffness
    return K


# --------------------------------------------------------------------------- solver
def _validate_ends(anchor, end):
    A = point("anchor", anchor)
    B = point("end", end)
    if max(np.abs(A).max(), np.abs(B).max()) > MAX_COORDINATE:
        raise InvalidParameterError(
            f"anchor and end must lie within {MAX_COORDINATE:g} m of the origin (the "
            f"catenary's squares and products must stay finite), got anchor={A.tolist()} "
            f"end={B.tolist()}")
    L = float(np.linalg.norm(B - A))
    if L <= 1e-12 * max(1.0, float(np.max(np.abs(A)))):
        raise InvalidParameterError(
            f"anchor and end must be distinct points, got anchor={A.tolist()} end={B.tolist()}")
    return A, B, L


def _vertical_solution(lh, h, L0, EA, w0):
    """Exactly vertical chord: straight cable, H = 0; returns V0 [N]."""
    W = w0 * L0
    # h = L0 (V0 + W/2)/EA + sign * L0 for a cable in tension throughout
    if h < 0:       # B below A: V0 + W < 0 everywhere
        V0 = EA * (h + L0) / L0 - 0.5 * W
        if V0 + W >= 0:
            raise SlackCableError(
                f"vertical cable with end below anchor is slack: drop {-h!r} m is not larger "
                f"than the hanging length of the unstretched_length {L0!r} m")
    else:           # B above A: V0 > 0
        V0 = EA * (h - L0) / L0 - 0.5 * W
        if V0 <= 0:
            raise SlackCableError(
                f"vertical cable rising from the anchor is slack: rise {h!r} m is not larger than "
                f"unstretched_length {L0!r} m stretched by its own weight")
    return V0


def _initial_guesses(lh, h, L0, EA, w0):
    """Candidate (H, V0) starting points [N]: elastic straight cable, and Peyrot-Goulois."""
    W = w0 * L0
    L = np.hypot(lh, h)
    guesses = []
    if L > L0:          # taut: straight elastic cable, tension from strain, plus weight
        T = EA * (L / L0 - 1.0)
        T = max(T, 0.5 * W)
        H = T * lh / L
        guesses.append((H, T * h / L - 0.5 * W))
    # Peyrot & Goulois (1979) catenary starting value
    if L0 * L0 <= L * L:
        lam = 0.2
    elif lh <= 1e-6 * L:
        lam = 1e6
    else:
        lam = np.sqrt(3.0 * ((L0 * L0 - h * h) / (lh * lh) - 1.0))
    H = max(abs(0.5 * w0 * lh / lam), 1e-8 * (W + EA * 1e-9))
    V0 = 0.5 * w0 * (h / np.tanh(lam) - L0) if lam < 700 else 0.5 * w0 * (h - L0)
    guesses.append((H, V0))
    return guesses


def _newton(lh, h, L0, EA, w0, H, V0, max_iter):
    """Damped Newton on (H, V0) keeping H > 0. Returns (H, V0, relative residual)."""
    target = np.array([lh, h])
    # each offset relative to its own size: x is resolved to 1e-12 of l_h even for
    # an almost vertical chord (H / l_h is the out-of-plane stiffness)
    scale = np.array([lh, max(np.hypot(lh, h), L0)])
    xz, F = _end_offsets_and_flexibility(H, V0, L0, EA, w0)
    r = xz - target
    res = np.max(np.abs(r) / scale)
    for _ in range(max_iter):
        if res <= _RTOL:
            return H, V0, res
        try:
            step = np.linalg.solve(F, -r)
        except np.linalg.LinAlgError:
            break
        t = 1.0
        while True:
            H_new = H + t * step[0]
            if H_new > 0.1 * H:       # keep H positive: at most a 10x reduction per step
                V_new = V0 + t * step[1]
                xz_new, F_new = _end_offsets_and_flexibility(H_new, V_new, L0, EA, w0)
                r_new = xz_new - target
                res_new = np.max(np.abs(r_new) / scale)
                if res_new < res or t < 1e-3 or res_new <= _RTOL:
                    break
            t *= 0.5
            if t < 1e-6:
                return H, V0, res
        H, V0, xz, F, r, res = H_new, V_new, xz_new, F_new, r_new, res_new
    return H, V0, res


def solve_catenary(anchor, end, unstretched_length, cable, g=STANDARD_GRAVITY, max_iter=100):
    """Static equilibrium of an elastic catenary between anchor A and end B.

    Solves x(L0) = l_h, z(L0) = h of the exact elastic catenary (theory.md §1.1, Irvine 1981)
    for (H, V0) by Newton's method with the analytic Jacobian, to relative residuals
    |x - l_h| / l_h <= 1e-12 and |z - h| / max(|B - A|, L0) <= 1e-12. Exactly vertical chords use the closed
    form of a straight hanging cable.

    Parameters
    ----------
    anchor, end : array_like, shape (3,)
        Positions of A (fixed) and B [m]; z is up, gravity is (0, 0, -g).
    unstretched_length : float
        L0 [m], > 0.
    cable : Cable
    g : float, optional
        Gravity [m/s^2], >= 0 (default :data:`STANDARD_GRAVITY`). With g = 0 the cable is a
        straight elastic spring.
    max_iter : int, optional
        Newton iterations per starting guess.

    Returns
    -------
    CatenaryState

    Raises
    ------
    InvalidParameterError
        Bad argument (named in the message).
    SlackCableError
        A vertical or weightless cable shorter than its chord would need compression.
    ConvergenceError
        Newton failed from every starting guess; the message gives the residual.
    """
    A, B, L = _validate_ends(anchor, end)
    L0 = positive_scalar("unstretched_length", unstretched_length)
    if isinstance(max_iter, bool) or not isinstance(max_iter, Integral) or max_iter < 1:
        raise InvalidParameterError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    if not isinstance(cable, Cable):
        raise InvalidParameterError(f"cable must be a dynstiff.Cable, got {type(cable).__name__}")
    g = positive_scalar("g", g, allow_zero=True)
    EA, w0 = cable.EA, cable.mass_per_length * g
    d = B - A
    lh, h = float(np.hypot(d[0], d[1])), float(d[2])

    def make(H, V0, res):
        return CatenaryState(anchor=A, end=B, unstretched_length=L0, cable=cable, g=g,
                             H=float(H), V0=float(V0), residual=float(res))

    if w0 == 0.0:      # straight spring
        if L <= L0:
            raise SlackCableError(
                f"weightless cable is slack: chord {L!r} m <= unstretched_length {L0!r} m")
        T = EA * (L / L0 - 1.0)
        return make(T * lh / L, T * h / L, 0.0)
    if lh <= 1e-14 * L:
        return make(0.0, _vertical_solution(lh, h, L0, EA, w0), 0.0)

    best = (None, None, np.inf)
    for H0, V00 in _initial_guesses(lh, h, L0, EA, w0):
        H, V0, res = _newton(lh, h, L0, EA, w0, H0, V00, max_iter)
        if res <= _RTOL:
            return make(H, V0, res)
        if res < best[2]:
            best = (H, V0, res)
    raise ConvergenceError(
        f"elastic catenary did not converge: relative residual {best[2]:.3e} > {_RTOL:.0e} "
        f"(anchor={A.tolist()}, end={B.tolist()}, unstretched_length={L0!r})",
        residual=best[2])


def unstretched_length_for_tension(anchor, end, tension, cable, g=STANDARD_GRAVITY, at="end"):
    """Unstretched length L0 [m] that gives a prescribed tension at B (or at A).

    Parameters
    ----------
    anchor, end : array_like, shape (3,)
        Positions of A and B [m].
    tension : float
        Prescribed tension [N], > 0, at ``at``.
    cable : Cable
    g : float, optional
        Gravity [m/s^2].
    at : {"end", "anchor"}
        Where the tension is prescribed.

    Returns
    -------
    CatenaryState
        The equilibrium; its ``unstretched_length`` is the answer.

    Notes
    -----
    Brent's method on log(T(L0) / T) in L0, bracketed by growing L0 from below the chord
    until the tension first drops under the target. The tension first decreases as L0
    grows, reaches a minimum, then rises again as the cable hangs deeper; the solution
    returned is the shorter, taut one. Raises :class:`SlackCableError` when the target is
    below the minimum tension any cable between these points can have.
    """
    from scipy.optimize import brentq

    A, B, L = _validate_ends(anchor, end)
    T_target = positive_scalar("tension", tension)
    if at not in ("end", "anchor"):
        raise InvalidParameterError(f"at must be 'end' or 'anchor', got {at!r}")
    g = positive_scalar("g", g, allow_zero=True)

    def tension_of(state):
        return state.tension_at_end if at == "end" else state.tension_at_anchor

    def f(L0):
        return np.log(tension_of(solve_catenary(A, B, L0, cable, g)) / T_target)

    # Upper bracket: a short cable is stiff, so tension is high; lower tension needs longer L0.
    L_hi_tension = L / (1.0 + 2.0 * T_target / cable.EA)

    def too_long(L0):                  # tension under the target, or slack (vertical cable)
        try:
            return f(L0) < 0
        except SlackCableError:
            return True

    while too_long(L_hi_tension):
        L_hi_tension *= 1.0 - 0.5 * min(0.5, 1.0 / np.log10(cable.EA))
    # Lower bracket: grow L0 until the tension drops under the target; a straight (vertical)
    # cable that goes slack first, at a length where the tension would be negative, is
    # bisected back between the last length too tensioned and the first slack one.
    L_lo_tension = L / (1.0 + 0.5 * T_target / cable.EA)
    taut, slack = L_hi_tension, np.inf
    k = 0
    while True:
        try:
            val = f(L_lo_tension)
        except SlackCableError:
            val, slack = None, L_lo_tension
        except ConvergenceError:
            val = None
        if val is not None and val < 0:
            break
        if val is not None:
            taut = L_lo_tension
        L_lo_tension = 1.05 * L_lo_tension if np.isinf(slack) else 0.5 * (taut + slack)
        k += 1
        if k > 200:
            raise SlackCableError(
                f"tension {T_target!r} N at the {at} is not reachable between anchor "
                f"{A.tolist()} and end {B.tolist()}: no unstretched length gives a tension this low")
    L0 = brentq(f, L_hi_tension, L_lo_tension, xtol=1e-15 * L, rtol=1e-15, maxiter=200)
    return solve_catenary(A, B, L0, cable, g)
