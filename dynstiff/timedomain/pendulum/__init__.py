"""Inverted pendulum held by two cables whose ends are excited harmonically: nonlinear
equations of motion (massless or point-mass cables), simulation and Floquet stability.

Reference system: Polach & Hajzman, seed paper 004 (built-in scene ``pendulum``). The
pendulum obeys (paper, eq. 1)

    I_A phi'' = (F_1 sin alpha_1 - F_2 sin alpha_2) d + m g (l/2) sin phi,

the cable forces F_i acting at D, at distance d from the pin A, alpha_i the angles between
pendulum and cables. The cable ends B, C are moved harmonically, x(t) = x0 sin(2 pi f t).

Geometry (planar, x-z plane, gravity (0, -g)): pin A at the origin, the pendulum upright
along +z and rotated by phi about y, so D = d (sin phi, cos phi); the ends move outward along
the line BC, E_1 = (-a - x_1(t), h), E_2 = (a + x_2(t), h), x_1 = x0 sin(Omega t),
x_2 = x0 sin(Omega t - psi). With psi = 0 (symmetric excitation) both tensions oscillate in
phase and phi = 0 stays a solution: the excitation is parametric (a Mathieu/Meissner-type
modulation of the pendulum's stiffness), and its stability is read from Floquet multipliers.

Cable model: cable i is n point masses joined by n + 1 tension-only spring-dampers of
stiffness (n + 1) k, damping (n + 1) b and unstretched length L0 / (n + 1), so that the whole
cable keeps the stiffness k, the damping b and the unstretched length L0 = L - P / k of the
massless model (the paper's rule). Segment tension T = max(0, k_s (l - l_s) + b_s dl/dt): it
never pushes and is continuous in the state, so the linearisation needs no saltation matrix.
Interior masses m_c / (n + 1), plus half masses at the ends (the lumping of
:mod:`dynstiff.cable.lumped_chain`): the one at D rides on the pendulum, the one at E is prescribed.
n = 0 is the massless cable (the paper's force model); the cable mass is then ignored.

Notation
--------
=============  ============================================================  ==========
symbol         meaning                                                       unit
=============  ============================================================  ==========
I_A            moment of inertia of the pendulum about the pin A             kg m^2
m, c           pendulum mass, distance A-G (l/2 for a uniform rod)           kg, m
d              distance A-D of the cable attachment                          m
a, h           half distance B-C, height of B and C above A                  m, m
k, b           stiffness and damping coefficient of a whole cable            N/m, N s/m
P              preload: tension at rest with the pendulum upright            N
L, L0          chord |E_i - D| at rest, unstretched length L - P/k           m
m_c, n         mass of one cable, number of its point masses                 kg, --
x0, f, psi     amplitude, frequency and phase lag of the end excitation      m, Hz, rad
Omega, T_e     2 pi f, excitation period 1/f                                 rad/s, s
y              state (q, dq/dt), q = (phi, x_11, z_11, ..., x_2n, z_2n)      rad, m, ...
M              monodromy matrix dy(T_e)/dy(0) along the periodic response    --
mu             Floquet multipliers, eigenvalues of M                         --
=============  ============================================================  ==========

Numerics: the point-mass cable is stiff (segments of stiffness (n + 1) k on masses of a few
tenths of a gram, with dampers (n + 1) b: eigenvalues to about -1e6 1/s), so the periodic
response and its monodromy matrix come from a fixed-step two-stage Radau IIA scheme (order 3,
L-stable), with the step derivative dy_{k+1}/dy_k taken from the converged Newton matrix: the
monodromy is the exact derivative of the discrete period map, and Newton shooting on it
converges quadratically. The step is T_e / N with N >= ``steps_min`` and >= ``steps_per_cycle``
steps per natural period of the pendulum. Faster motions that this step does not resolve (the
transverse cable modes above a few hundred Hz, which have no damping of their own in this
model) are damped numerically by the L-stable scheme, so their multipliers come out < 1; the
pendulum's multiplier converges at third order in the step (tests/test_pendulum.py).
Massless cables under symmetric excitation need no orbit (phi = 0): their 2 x 2 monodromy is
formed for all steps at once. Point-mass cables that go slack may move aperiodically (the
cables snap and flap); there the growth per period is measured along the response
(see :func:`floquet`).
"""

from dynstiff.timedomain.pendulum.dynamics import jacobian, rest_state, rhs
from dynstiff.timedomain.pendulum.floquet import FloquetResult, floquet
from dynstiff.timedomain.pendulum.maps import stability_map, unstable_intervals
from dynstiff.timedomain.pendulum.model import CablePendulum, from_scene
from dynstiff.timedomain.pendulum.simulate import PendulumResponse, simulate

__all__ = [
    "CablePendulum",
    "from_scene",
    "rest_state",
    "rhs",
    "jacobian",
    "simulate",
    "PendulumResponse",
    "floquet",
    "FloquetResult",
    "stability_map",
    "unstable_intervals",
]

