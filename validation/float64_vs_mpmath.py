"""Float64 cable dynamic stiffness against the mpmath reference of the naive forms.

Compares :func:`dynstiff.cable.dsm.local_end_stiffness` (3x3) and
:func:`dynstiff.cable.dsm.local_two_end_stiffness` (6x6), which use the stable closed forms
of theory.md §3.5 and a Taylor series for |psi| < 1, with
:mod:`dynstiff.cable.mpmath_reference`, which evaluates the textbook forms of theory.md §3.2-3.4
with enough digits to absorb their cancellation (>= 50 significant digits).

Grid (``run()``)
----------------
* lambda^2: 12 values log-spaced in [1e-6, 1e4], plus the first crossover 4 pi^2 where the
  first symmetric root meets the first antisymmetric pole Omega = 2 pi (theory.md §2.2).
* Omega = omega L sqrt(m/T): 40 values (15 log-spaced in [1e-6, 1], 25 linear in [1, 60]),
  plus, for each pole Omega_p < 60 (out-of-plane n pi, antisymmetric 2 n pi, Irvine
  symmetric roots of that lambda^2 from
  :func:`dynstiff.cable.mpmath_reference.irvine_symmetric_roots_mp`),
  the points Omega_p (1 +- 1e-8) and Omega_p (1 +- 1e-6).
* Damping cases: "undamped"; "loss_factor" (EA -> EA (1 + 0.02 i)); "viscous" (c chosen for
  a damping ratio c / (2 m omega_1) = 1 % at the first string frequency omega_1 = pi c_s / L,
  so zeta_n = 1 %/n).
* Chordwise inertia on (the package default). ``ChordParameters`` are built directly:
  L = 10 m, T = 300 N, m = 0.064 kg/m, EA = 1e5 T (so that lambda^2 = 1e4 keeps a moderate
  sag d/L = 0.04), q chosen to give the wanted lambda^2 with L_e = L (1 + 8 (d/L)^2).
  The Irvine roots use the lambda^2 of the rounded parameters, so the poles are exact.

Error measures (columns)
------------------------
* ``err_entry``: max over the entries that are not structurally zero (the u/v-w couplings
  are exactly 0 in both) of |K64_ij - Kmp_ij| / |Kmp_ij|, over the 3x3 and the 6x6 matrices.
  This is the strictest measure: every entry, however small (K_uv ~ alpha ~ 1e-6 K_vv at
  lambda^2 = 1e-6), must be right to that relative accuracy. Its weakness is at an isolated
  zero of one entry (e.g. K_ww at Omega = (n + 1/2) pi), where any method's relative error is
  eps times the entry's condition number; no grid point sits that close to such a zero.
* ``err_norm``: ||K64 - Kmp||_F / ||Kmp||_F, max over the two matrices (what an FRF sees).
* ``worst_entry``: the entry giving ``err_entry`` ("end:uv", "two:vAvB", ...).
* ``pole_dist``: relative distance |Omega - Omega_p| / Omega_p to the nearest *undamped* pole
  (for damped cases this is conservative: damping moves poles off the real axis, except the
  string poles n pi and 2 n pi under hysteretic damping, which does not act on them).
* ``near_pole``: pole_dist <= 1.5e-8 (the points placed at 1e-8, allowing for rounding).
  ``away``: pole_dist > 1e-6 * (1 + 1e-3), i.e. every sample except those placed at 1e-8 or
  1e-6 from a pole. Near a pole, float64 cannot do better than about eps / pole_dist in
  relative terms, because psi itself is rounded (1 ulp of psi moves the sample by 1e-16 of
  the pole distance scale).
"""

import sys
import time

import numpy as np
import pandas as pd

from dynstiff.cable.dsm import ChordParameters, local_end_stiffness, local_two_end_stiffness
from dynstiff.cable.mpmath_reference import (
    end_stiffness_mp,
    irvine_symmetric_roots_mp,
    params_to_mp_args,
    two_end_stiffness_mp,
)

L_CHORD = 10.0          # [m]
TENSION = 300.0         # [N]
MASS = 0.064            # [kg/m]
EA_OVER_T = 1e5         # [-]
LOSS_FACTOR = 0.02      # [-]
VISCOUS_ZETA_1 = 0.01   # [-] damping ratio of the first string mode
OMEGA_MAX = 60.0        # [-] largest nondimensional frequency
POLE_OFFSETS = (-1e-6, -1e-8, 1e-8, 1e-6)
NEAR_POLE = 1.5e-8
AWAY = 1e-6 * (1 + 1e-3)

_END_NAMES = "uvw"
_TWO_NAMES = ("uA", "vA", "wA", "uB", "vB", "wB")


def chord_params_for(lambda_sq, damping="undamped"):
    """ChordParameters with the given Irvine parameter (see the module docstring).

    Parameters
    ----------
    lambda_sq : float
        Wanted lambda^2 [-], 0 <= lambda_sq < 8 EA/T.
    damping : {"undamped", "loss_factor", "viscous"}

    Returns
    -------
    ChordParameters
    """
    L, T, m = L_CHORD, TENSION, MASS
    EA = EA_OVER_T * T
    # lambda^2 = x EA / (T (1 + x/8)), x = (q L / T)^2, from L_e = L (1 + (q L / T)^2 / 8)
    r = lambda_sq * T / EA
    x = r / (1.0 - r / 8.0)
    q = np.sqrt(x) * T / L
    d = q * L**2 / (8.0 * T)
    L_e = L * (1.0 + 8.0 * (d / L) ** 2)
    c = 0.0
    if damping == "loss_factor":
        EA = EA * (1.0 + 1j * LOSS_FACTOR)
    elif damping == "viscous":
        omega_1 = np.pi * np.sqrt(T / m) / L
        c = 2.0 * VISCOUS_ZETA_1 * m * omega_1
    elif damping != "undamped":
        raise ValueError(f"damping must be 'undamped', 'loss_factor' or 'viscous', "
                         f"got {damping!r}")
    return ChordParameters(L=L, T=T, m=m, c=c, EA=EA, q=q, L_e=L_e, cos_theta=1.0,
                           rotation=np.eye(3))


def _lambda_sq_mp(params):
    """lambda^2 of the rounded parameters, as the float64 kernel sees it (real part)."""
    import mpmath
    with mpmath.workdps(40):
        L, T, _, _, EA, L_e, q = (mpmath.mpf(v) if not isinstance(v, complex)
                                  else mpmath.mpf(v.real)
                                  for v in params_to_mp_args(params))
        return (q * L / T) ** 2 * L * EA / (T * L_e)


def poles_below(params, omega_max):
    """Undamped clamped-clamped poles Omega_p < omega_max, sorted, float [-]."""
    out = [n * np.pi for n in range(1, int(omega_max / np.pi) + 1)]
    out += [2 * n * np.pi for n in range(1, int(omega_max / (2 * np.pi)) + 1)]
    n_sym = int(omega_max / (2 * np.pi)) + 2
    out += [float(r) for r in irvine_symmetric_roots_mp(_lambda_sq_mp(params), n_sym, dps=30)]
    return np.unique([p for p in out if p < omega_max])


def _entry_errors(K64, Kmp, names):
    """Entry-wise relative error over non-structural-zero entries, Frobenius-norm error."""
    nz = Kmp != 0
    rel = np.zeros(K64.shape)
    rel[nz] = np.abs(K64[nz] - Kmp[nz]) / np.abs(Kmp[nz])
    if np.any((K64 != 0) & ~nz):                 # a structural zero that is not zero
        rel[(K64 != 0) & ~nz] = np.inf
    i, j = np.unravel_index(np.argmax(rel), rel.shape)
    norm = np.linalg.norm(K64 - Kmp) / np.linalg.norm(Kmp)
    return rel[i, j], norm, f"{names[i]}{names[j]}"


def run(quick=False, dps=50):
    """Compare float64 and mpmath on the grid of the module docstring.

    Parameters
    ----------
    quick : bool
        Coarser grid for the test suite: 6 log-spaced lambda^2 values plus 4 pi^2, 13 Omega
        values up to 30 and the points next to the poles below 30 (1437 samples, ~2 s).
    dps : int
        Digits of the mpmath reference.

    Returns
    -------
    pandas.DataFrame
        One row per (lambda_sq, Omega, damping) sample, columns ``lambda_sq``, ``Omega``,
        ``omega`` [rad/s], ``damping``, ``pole_offset`` (nominal offset used to place the
        sample, 0 for the regular grid), ``pole_dist``, ``near_pole``, ``away``,
        ``err_entry``, ``err_norm``, ``worst_entry``, ``K_scale`` (|K_uu| of the 3x3,
        [N/m]).
    """
    if quick:
        lambdas = np.concatenate([np.geomspace(1e-6, 1e4, 6), [4 * np.pi**2]])
        om_max = 30.0
        grid = np.concatenate([np.geomspace(1e-6, 1.0, 5), np.linspace(1.5, om_max, 8)])
    else:
        lambdas = np.concatenate([np.geomspace(1e-6, 1e4, 12), [4 * np.pi**2]])
        om_max = OMEGA_MAX
        grid = np.concatenate([np.geomspace(1e-6, 1.0, 15), np.linspace(1.0, om_max, 26)[1:]])
    rows = []
    for lam2 in lambdas:
        p0 = chord_params_for(lam2)
        poles = poles_below(p0, om_max)
        samples = [(Om, 0.0) for Om in grid]
        samples += [(Op * (1 + off), off) for Op in poles for off in POLE_OFFSETS]
        Om = np.array([s[0] for s in samples])
        offsets = np.array([s[1] for s in samples])
        dist = np.min(np.abs(Om[:, None] - poles[None, :]) / poles[None, :], axis=1)
        for damping in ("undamped", "loss_factor", "viscous"):
            p = chord_params_for(lam2, damping)
            args = params_to_mp_args(p)
            omega = Om / (p.L * np.sqrt(p.m / p.T))
            K3 = local_end_stiffness(p, omega, chordwise_inertia=True)
            K6 = local_two_end_stiffness(p, omega, chordwise_inertia=True)
            for k in range(omega.size):
                K3mp = end_stiffness_mp(*args, float(omega[k]), True, dps)
                K6mp = two_end_stiffness_mp(*args, float(omega[k]), True, dps)
                e3, n3, w3 = _entry_errors(K3[k], K3mp, _END_NAMES)
                e6, n6, w6 = _entry_errors(K6[k], K6mp, _TWO_NAMES)
                rows.append(dict(
                    lambda_sq=lam2, Omega=Om[k], omega=omega[k], damping=damping,
                    pole_offset=offsets[k], pole_dist=dist[k],
                    near_pole=bool(dist[k] <= NEAR_POLE), away=bool(dist[k] > AWAY),
                    err_entry=max(e3, e6), err_norm=max(n3, n6),
                    worst_entry=("end:" + w3) if e3 >= e6 else ("two:" + w6),
                    K_scale=abs(K3mp[0, 0])))
    return pd.DataFrame(rows)


def summary(df):
    """Headline numbers of :func:`run`: max errors away from / near poles, per damping."""
    out = {}
    for damping, g in df.groupby("damping"):
        out[damping] = {
            "n": len(g),
            "max_err_entry_away": g.loc[g.away, "err_entry"].max(),
            "max_err_norm_away": g.loc[g.away, "err_norm"].max(),
            "max_err_entry_at_1e-6": g.loc[~g.away & ~g.near_pole, "err_entry"].max(),
            "max_err_entry_near": g.loc[g.near_pole, "err_entry"].max(),
            "max_err_norm_near": g.loc[g.near_pole, "err_norm"].max(),
        }
    return pd.DataFrame(out).T


if __name__ == "__main__":
    t0 = time.perf_counter()
    df = run(quick="--quick" in sys.argv)
    elapsed = time.perf_counter() - t0
    pd.set_option("display.width", 160)
    print(f"{len(df)} samples in {elapsed:.1f} s")
    print(summary(df).to_string(float_format=lambda v: f"{v:.3g}"))
    worst = df[df.away].sort_values("err_entry", ascending=False).head(8)
    print("\nworst samples away from poles:")
    print(worst[["lambda_sq", "Omega", "damping", "pole_dist", "err_entry", "err_norm",
                 "worst_entry"]].to_string(float_format=lambda v: f"{v:.4g}"))
    near = df[df.near_pole]
    print("\nnear poles: err_entry * pole_dist / eps (conditioning-scaled), max:",
          f"{(near.err_entry * near.pole_dist / np.finfo(float).eps).max():.3g}")
    if "--plot" in sys.argv:
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 4.5))
        for damping, g in df.groupby("damping"):
            ax.loglog(g.pole_dist, g.err_entry, ".", ms=3, label=damping)
        d = np.geomspace(1e-9, 10, 50)
        ax.loglog(d, np.finfo(float).eps / d, "k--", lw=1, label="eps / pole distance")
        ax.set_xlabel("relative distance to nearest undamped pole")
        ax.set_ylabel("max entry-wise relative error, float64 vs mpmath")
        ax.legend()
        fig.tight_layout()
        fig.savefig("float64_vs_mpmath.png", dpi=150)
        print("saved float64_vs_mpmath.png")
