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

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._vec import cross
from dynstiff.cable.chord import chord_parameters
from dynstiff.errors import InvalidParameterError
from dynstiff.params import Cable

if TYPE_CHECKING:

    import pandas as pd
    from numpy.typing import ArrayLike, NDArray

__all__ = ["CatenaryState", "catenary_states", "divided_differences", "end_stiffnesses"]

_EZ = np.array([0.0, 0.0, 1.0])


# --------------------------------------------------------------------------- kernels
def divided_differences(a: NDArray[np.float64] | float, b: NDArray[np.float64] | float,
                        delta: NDArray[np.float64] | float) -> tuple[NDArray[np.float64], ...]:
    """Cancellation-free divided differences between t = a and t = b = a + delta >= a.

    Returns (D_asinh, D_f, D_g, D_sqrt), each (F(b) - F(a)) / delta for
    F = asinh(t), t / sqrt(1 + t^2), 1 / sqrt(1 + t^2), sqrt(1 + t^2), and the derivatives at
    a where delta = 0 (weightless cable). Scalars or arrays of one shape (n,), elementwise
    (also the batched statics, :mod:`dynstiff.cable.catenary_batch`). Uses
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


def end_offsets_and_flexibility(H: float, V0: float, L0: float, EA: float,
                                w0: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
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


def _mean_tension(H: float, V0: float, L0: float, w0: float) -> float:
    """Mean tension over the unstretched length, (1/L0) int_0^L0 T(s) ds [N]."""
    W = w0 * L0
    if H == 0.0:
        return abs(V0 + 0.5 * W) if V0 * (V0 + W) >= 0 else 0.5 * (V0**2 + (V0 + W) ** 2) / W

    def prim(V: float) -> float:  # int sqrt(H^2 + V^2) dV
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

    Examples
    --------
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> state = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> print(f"H = {state.H:.2f} N, V0 = {state.V0:.2f} N, chord {state.chord_length:.1f} m")
    H = 239.24 N, V0 = 177.87 N, chord 5.0 m
    """

    anchor: np.ndarray
    end: np.ndarray
    unstretched_length: float
    cable: Cable
    g: float
    H: float
    V0: float
    residual: float

    # ---- geometry of the cable plane (computed once: the state is immutable; the arrays
    # are read-only)
    @cached_property
    def chord(self) -> NDArray[np.float64]:
        """Chord vector B - A [m], shape (3,), read-only."""
        d = np.asarray(self.end, dtype=float) - self.anchor
        d.setflags(write=False)
        return d

    @cached_property
    def chord_length(self) -> float:
        """Chord length L = |B - A| [m]."""
        return float(np.linalg.norm(self.chord))

    @cached_property
    def horizontal_span(self) -> float:
        """Horizontal distance l_h between A and B [m]."""
        return float(np.hypot(self.chord[0], self.chord[1]))

    @cached_property
    def horizontal_direction(self) -> NDArray[np.float64]:
        """Unit horizontal vector from A towards B, shape (3,), read-only.

        For an exactly vertical chord it is an arbitrary (fixed) horizontal axis, x.
        """
        lh = self.horizontal_span
        e = (np.array([1.0, 0.0, 0.0]) if lh <= 1e-14 * self.chord_length
             else np.array([self.chord[0] / lh, self.chord[1] / lh, 0.0]))
        e.setflags(write=False)
        return e

    # ---- forces
    @property
    def total_weight(self) -> float:
        """W = m g L0 [N]."""
        return self.cable.mass_per_length * self.g * self.unstretched_length

    @property
    def Vb(self) -> float:
        """Vertical tension component at B, V0 + W [N]."""
        return self.V0 + self.total_weight

    @property
    def horizontal_tension(self) -> float:
        """Horizontal tension component H [N]."""
        return self.H

    @cached_property
    def force_on_end(self) -> NDArray[np.float64]:
        """Force of the cable on the end B [N], shape (3,), read-only: -(H e_h + Vb e_z)."""
        f = -(self.H * self.horizontal_direction + self.Vb * _EZ)
        f.setflags(write=False)
        return f

    @property
    def force_on_anchor(self) -> NDArray[np.float64]:
        """Force of the cable on the anchor A [N], shape (3,): H e_h + V0 e_z."""
        return self.H * self.horizontal_direction + self.V0 * _EZ

    @property
    def tension_at_end(self) -> float:
        """Tension at B [N]."""
        return float(np.hypot(self.H, self.Vb))

    @property
    def tension_at_anchor(self) -> float:
        """Tension at A [N]."""
        return float(np.hypot(self.H, self.V0))

    @property
    def min_tension(self) -> float:
        """Least tension along the cable [N]: H where the cable has its lowest point between
        A and B (V changes sign), else the smaller end tension (T = sqrt(H^2 + V^2), V
        linear in the arc length)."""
        if self.V0 < 0.0 < self.Vb:
            return float(self.H)
        return float(np.hypot(self.H, min(abs(self.V0), abs(self.Vb))))

    @property
    def max_tension(self) -> float:
        """Largest tension along the cable [N], at the higher-tension end."""
        return max(self.tension_at_end, self.tension_at_anchor)

    @cached_property
    def mean_tension(self) -> float:
        """Tension averaged over the unstretched length [N]."""
        return float(_mean_tension(self.H, self.V0, self.unstretched_length,
                                   self.cable.weight_per_length(self.g)))

    def tension(self, s: NDArray[np.float64] | float) -> NDArray[np.float64] | float:
        """Tension T(s) = sqrt(H^2 + (V0 + w0 s)^2) [N] at unstretched arc length s [m]."""
        s = np.asarray(s, dtype=float)
        return np.hypot(self.H, self.V0 + self.cable.weight_per_length(self.g) * s)

    @property
    def stretched_length(self) -> float:
        """Arc length of the stretched cable, L0 + int T/EA ds [m]."""
        L0 = self.unstretched_length
        return L0 * (1.0 + self.mean_tension / self.cable.EA)

    # ---- profile
    def profile_plane(self, s: ArrayLike) -> NDArray[np.float64]:
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
                out[k], _ = end_offsets_and_flexibility(self.H, self.V0, sk, EA, w0)
        return out

    def profile(self, n: int = 50) -> NDArray[np.float64]:
        """Points of the cable, shape (n, 3) [m], equally spaced in unstretched arc length."""
        n = int(n)
        if n < 2:
            raise InvalidParameterError(f"n must be an integer >= 2, got {n!r}")
        xz = self.profile_plane(np.linspace(0.0, self.unstretched_length, n))
        return (self.anchor + np.outer(xz[:, 0], self.horizontal_direction)
                + np.outer(xz[:, 1], _EZ))

    def to_frame(self, n: int = 50) -> pd.DataFrame:
        """pandas DataFrame of the profile: unstretched arc length s from A [m], the point
        (x, y, z) [m] in the base frame and the tension T(s) [N], ``n`` rows equally spaced
        in s (theory.md §1.1)."""
        import pandas as pd
        pts = self.profile(n)
        s = np.linspace(0.0, self.unstretched_length, pts.shape[0])
        return pd.DataFrame({"s [m]": s, "x [m]": pts[:, 0], "y [m]": pts[:, 1],
                             "z [m]": pts[:, 2], "tension [N]": self.tension(s)})

    @property
    def sag(self) -> float:
        """Largest distance of the cable from its chord *segment* AB [m]: over a 401-point
        profile and the point where the cable runs parallel to the chord, V(s) / H = h / l_h,
        which holds the largest distance from the chord's line (theory.md §1.1; a point
        beyond an end of the segment counts its distance to that end, so a slack cable
        hanging in a U below its lower end shows its true sag)."""
        s = np.linspace(0.0, self.unstretched_length, 401)
        w0, lh = self.cable.weight_per_length(self.g), self.horizontal_span
        if self.H > 0 and w0 > 0 and lh > 0:
            s_star = (self.H * self.chord[2] / lh - self.V0) / w0
            s = np.append(s, np.clip(s_star, 0.0, self.unstretched_length))
        xz = self.profile_plane(s)
        p = np.outer(xz[:, 0], self.horizontal_direction) + np.outer(xz[:, 1], _EZ)
        L = self.chord_length
        e = self.chord / L
        along = np.clip(p @ e, 0.0, L)
        return float(np.max(np.linalg.norm(p - np.outer(along, e), axis=1)))

    # ---- chord-frame (parabolic) parameters used by the linear dynamic theory
    @property
    def cos_theta(self) -> float:
        """cos of the chord inclination to the horizontal [-]."""
        return self.horizontal_span / self.chord_length

    @property
    def lambda_sq(self) -> float:
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
    def in_plane_flexibility(self) -> NDArray[np.float64]:
        """d(l_h, h)/d(H, Vb) [m/N], shape (2, 2): compliance of the end B in the cable plane."""
        if self.H == 0.0:
            L0, EA = self.unstretched_length, self.cable.EA
            return np.array([[1.0 / self._vertical_lateral_stiffness(), 0.0],
                             [0.0, L0 / EA]])
        _, F = end_offsets_and_flexibility(self.H, self.V0, self.unstretched_length,
                                            self.cable.EA, self.cable.weight_per_length(self.g))
        return F

    def _vertical_lateral_stiffness(self) -> float:
        """H / l_h in the limit H -> 0 (vertical chord) [N/m].

        From x = H L0/EA + (H/w0)[asinh(Vb/H) - asinh(V0/H)]:
        x / H -> L0/EA + |ln(Vb/V0)| / w0 = L0/EA + int_0^L0 ds / T(s).
        """
        L0, EA = self.unstretched_length, self.cable.EA
        w0 = self.cable.weight_per_length(self.g)
        return 1.0 / (L0 / EA + abs(np.log1p(w0 * L0 / self.V0)) / w0)

    @property
    def out_of_plane_stiffness(self) -> float:
        """Stiffness of B perpendicular to the vertical cable plane, H / l_h [N/m]."""
        if self.H == 0.0:
            return float(self._vertical_lateral_stiffness())
        return float(self.H / self.horizontal_span)

    @property
    def end_stiffness(self) -> NDArray[np.float64]:
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


def end_stiffnesses(states: tuple[CatenaryState, ...]) -> NDArray[np.float64]:
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
    ex = np.where(vertical, 1.0, d[:, 0] / lh_s)          # e_h = (ex, ey, 0)
    ey = np.where(vertical, 0.0, d[:, 1] / lh_s)
    kp = Hs / lh_s                                        # along e_p = e_z x e_h = (-ey, ex, 0)
    # k11 e_h e_h' + k12 (e_h e_z' + e_z e_h') + k22 e_z e_z' + kp e_p e_p', entry by entry
    K = np.empty((n, 3, 3))
    K[:, 0, 0] = k11 * ex * ex + kp * ey * ey
    K[:, 1, 1] = k11 * ey * ey + kp * ex * ex
    K[:, 0, 1] = K[:, 1, 0] = (k11 - kp) * ex * ey
    K[:, 0, 2] = K[:, 2, 0] = k12 * ex
    K[:, 1, 2] = K[:, 2, 1] = k12 * ey
    K[:, 2, 2] = k22
    for i in np.flatnonzero(~taut):
        K[i] = states[i].end_stiffness
    return K


def catenary_states(anchors: NDArray[np.float64], ends: NDArray[np.float64],
                    unstretched_lengths: NDArray[np.float64], cables: list[Cable], g: float,
                    H: NDArray[np.float64], V0: NDArray[np.float64],
                    residuals: NDArray[np.float64]) -> list[CatenaryState]:
    """The states of many cables from their arrays (shapes (n, 3) and (n,)), with the chord
    and, for every cable not within rounding of vertical, the horizontal direction and the
    force on B computed for all at once: the same operations, element by element, as the
    properties of one state, so the same numbers (the batched statics builds its
    equilibria so, and the model reads those properties of every cable).

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> cable = ds.Cable(mass_per_length=0.064, EA=1.64e6)
    >>> s = ds.unstretched_length_for_tension([0, 0, 0], [4.0, 0, 3.0], 300.0, cable)
    >>> (t,) = catenary_states(np.array([s.anchor]), np.array([s.end]),
    ...                        np.array([s.unstretched_length]), [cable], s.g,
    ...                        np.array([s.H]), np.array([s.V0]), np.array([s.residual]))
    >>> bool(np.array_equal(t.force_on_end, s.force_on_end))
    True
    """
    A = np.asarray(anchors, dtype=float)
    B = np.asarray(ends, dtype=float)
    C = B - A
    C.setflags(write=False)
    lh = np.hypot(C[:, 0], C[:, 1])
    # the vertical test of one state compares lh with 1e-14 |C|: here only cables well
    # clear of it (whatever the rounding of |C|) are primed, the others compute their own
    clear = lh > 1e-13 * np.linalg.norm(C, axis=1)
    safe = np.where(clear, lh, 1.0)
    E = np.stack([C[:, 0] / safe, C[:, 1] / safe, np.zeros(len(C))], axis=1)
    W = np.array([c.mass_per_length for c in cables]) * g * np.asarray(unstretched_lengths)
    Vb = np.asarray(V0, dtype=float) + W
    F = -(np.asarray(H, dtype=float)[:, None] * E + Vb[:, None] * _EZ)
    E.setflags(write=False)
    F.setflags(write=False)
    out = []
    for i, cable in enumerate(cables):
        s = CatenaryState(anchor=A[i], end=B[i], unstretched_length=float(unstretched_lengths[i]),
                          cable=cable, g=g, H=float(H[i]), V0=float(V0[i]),
                          residual=float(residuals[i]))
        object.__setattr__(s, "chord", C[i])                 # the cached properties
        object.__setattr__(s, "horizontal_span", float(lh[i]))
        if clear[i]:
            object.__setattr__(s, "horizontal_direction", E[i])
            object.__setattr__(s, "force_on_end", F[i])
        out.append(s)
    return out
