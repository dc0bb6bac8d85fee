"""Where the cable models fail: a stability map of the slack regime (frequency domain).

One 10 m cable (CoGiRo's cable: m = 0.064 kg/m, EA = 1.4e5 N) whose span is shortened until
its least tension is a fraction T_min / T_max = 0.3 ... 1e-10 of its greatest, in two shapes:
a U between ends at equal height, and a U under a near-vertical 9.9 m chord. Each model is
measured against the converged reference, lumped chains graded towards the bottom of the U
(theory.md §7.4) Richardson-extrapolated from N = 800 and 1600 (its own convergence, the
extrapolation from 400 and 800 against it, is reported):

- clamped-cable frequencies: the largest |f / f_ref - 1| over the first ``N_MODES``;
- static end stiffness (end B, A clamped): the energy-norm error
  max |eig(K_ref^-1/2 (K - K_ref) K_ref^-1/2)|;

for the closed form (theory.md §3) with its guard's estimate (theory.md §11.5: inf, i.e.
refused, below T_min / T_max = 0.1), the exact rung (theory.md §11; refused below
``MIN_TENSION_RATIO`` = 1e-8) and uniform lumped chains of N = 10, 40 and 160 segments
(theory.md §7), with the wall time of each. The time-domain side of the map (the six-cable
circle against dt and N) is :func:`validation.sixcable_paths.convergence`.

Run ``python validation/slack_cables.py`` for the table and ``slack_cables.png``.
"""

import time
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.optimize import brentq

import dynstiff as ds
from dynstiff.cable.dsm import cable_dynamic_stiffness
from dynstiff.cable.exact import MIN_TENSION_RATIO, ExactCable
from dynstiff.cable.guard import SLACK_RATIO, closed_form_validity
from dynstiff.cable.lumped_chain_dynamics import (
    chain_end_dynamic_stiffness,
    chain_fixed_end_frequencies,
)
from dynstiff.cable.lumped_graded import graded_chain
from dynstiff.cable.modes import cable_natural_frequencies
from dynstiff.errors import DynstiffError
from dynstiff.lumped import chain_equilibrium

CABLE = ds.Cable(0.064, 1.4e5)                 # [kg/m], [N]
L0 = 10.0                                      # [m]
SHAPES = {"U, ends at equal height": 0.0, "U under a near-vertical chord": 9.9}   # height [m]
RATIOS = (0.3, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1.1e-8, 5e-9, 1e-10)
N_MODES = 10
LUMPED = (10, 40, 160)
REFERENCE = (800, 1600)
TWO_PI = 2 * np.pi
TOP = 1e2                                      # errors above are drawn at the top


def slack_state(height, ratio):
    """The cable from A = 0 to B = (x, 0, height) with T_min / T_max = ``ratio``, x by Brent's
    method on log x."""
    def excess(log_x):
        s = ds.solve_catenary((0, 0, 0), (np.exp(log_x), 0, height), L0, CABLE)
        return np.log(s.min_tension / s.max_tension) - np.log(ratio)
    top = np.log(np.sqrt(L0**2 * (1 - 1e-6) - height**2))
    x = np.exp(brentq(excess, np.log(1e-12), top, xtol=1e-15))
    return ds.solve_catenary((0, 0, 0), (x, 0, height), L0, CABLE)


def energy_error(K, K_ref):
    """max |eig(K_ref^-1/2 (K - K_ref) K_ref^-1/2)| [-] for symmetric K, K_ref (3, 3)."""
    from scipy.linalg import eigh
    if not np.all(np.isfinite(K)):
        return np.nan
    return float(np.max(np.abs(eigh(0.5 * (K + K.T) - K_ref, K_ref, eigvals_only=True))))


def _timed(fn):
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def reference(s, Ns=REFERENCE, n_modes=N_MODES):
    """Graded-chain frequencies [Hz] and static end stiffness [N/m], Richardson from ``Ns``,
    and the relative change of the frequencies from the extrapolation one level coarser."""
    w0 = s.cable.weight_per_length(s.g)
    levels = (Ns[0] // 2,) + tuple(Ns)
    f, K = {}, {}
    for N in levels:
        ch = graded_chain(s.anchor, s.end, s.unstretched_length, s.cable, N,
                          s_low=-s.V0 / w0, core=s.H / w0, f0=s.force_on_anchor)
        f[N] = ch.fixed_end_frequencies(n_modes)
        K[N] = ch.end_dynamic_stiffness(0.0)[0]
    rich = {k: (4 * d[Ns[1]] - d[Ns[0]]) / 3 for k, d in (("f", f), ("K", K))}
    coarse = (4 * f[Ns[0]] - f[levels[0]]) / 3
    return rich["f"], rich["K"], float(np.max(np.abs(coarse / rich["f"] - 1)))


def case(shape, ratio, n_modes=N_MODES):
    """One row: every model's errors, wall time and verdict for one cable."""
    s = slack_state(SHAPES[shape], ratio)
    f_ref, K_ref, ref_change = reference(s, n_modes=n_modes)
    row = {"shape": shape, "T_min/T_max": s.min_tension / s.max_tension,
           "span [m]": s.horizontal_span, "f_1 [Hz]": f_ref[0],
           "reference convergence [-]": ref_change}
    # closed form, its guard
    (f_cf, K_cf), t = _timed(lambda: (
        cable_natural_frequencies(s, n_modes, guard_rtol=None).freq_hz,
        cable_dynamic_stiffness(s, 0.0, guard_rtol=None)[0]))
    guard = closed_form_validity(s, TWO_PI * f_ref[-1])
    row.update({"closed form freq err": float(np.max(np.abs(f_cf / f_ref - 1))),
                "closed form static err": energy_error(K_cf, K_ref),
                "closed form guard": guard.error, "closed form [s]": t,
                "guard refuses": bool(guard.causes["slack"] == np.inf)})
    # exact rung
    try:
        (f_ex, K_ex), t = _timed(lambda: _exact(s, f_ref, n_modes))
    except DynstiffError as exc:
        row.update({"exact freq err": np.nan, "exact static err": np.nan, "exact [s]": np.nan,
                    "exact": f"refused: {str(exc)[:60]}"})
    else:
        row.update({"exact freq err": float(np.max(np.abs(f_ex / f_ref - 1))),
                    "exact static err": energy_error(K_ex, K_ref), "exact [s]": t,
                    "exact": "accepted"})
    # uniform lumped chains
    for N in LUMPED:
        try:
            (f_n, K_n), t = _timed(lambda: _lumped(s, N, n_modes))
        except DynstiffError:          # no chain equilibrium with a node at the U's bottom
            f_n, K_n, t = np.full(n_modes, np.nan), np.full((3, 3), np.nan), np.nan
        row.update({f"lumped N={N} freq err": float(np.max(np.abs(f_n / f_ref - 1))),
                    f"lumped N={N} static err": energy_error(K_n, K_ref),
                    f"lumped N={N} [s]": t})
    return row


def _exact(s, f_ref, n_modes):
    ec = ExactCable(s, 1.1 * TWO_PI * f_ref[-1])
    return np.sqrt(ec.eigenvalues[:n_modes]) / TWO_PI, ec.dynamic_stiffness(0.0)[0]


def _lumped(s, N, n_modes):
    ch = chain_equilibrium(s.anchor, s.end, s.unstretched_length, s.cable, N)
    return (chain_fixed_end_frequencies(ch, n_modes),
            chain_end_dynamic_stiffness(ch, 0.0)[0].real)


def run(quick=False):
    """The map: one row per (shape, T_min / T_max).

    Returns
    -------
    pandas.DataFrame
        The "... err" columns are relative errors [-] against the graded-chain reference,
        "[s]" wall times, "closed form guard" the guard's estimate (inf: refused), "exact"
        the exact rung's verdict.
    """
    ratios = (0.3, 1e-4, 1.1e-8, 5e-9) if quick else RATIOS
    shapes = list(SHAPES)[:1] if quick else list(SHAPES)
    return pd.DataFrame([case(sh, r) for sh in shapes for r in ratios])


METHODS = {"closed form": ("C0", "-", "o"), "exact": ("C3", "-", "D"),
           **{f"lumped N={N}": (c, "--", m) for N, c, m in zip(LUMPED, ("C1", "C2", "C4"),
                                                                 ("s", "^", "v"))}}


def plot(df, fig=None):
    """Errors against T_min / T_max (one column per shape; frequencies, static stiffness) and
    error against wall time at T_min / T_max = 1e-4, with the guard's and the exact rung's
    refusals drawn. Returns the matplotlib Figure."""
    import matplotlib.pyplot as plt
    shapes = list(dict.fromkeys(df["shape"]))
    fig = fig or plt.figure(figsize=(4.2 * (len(shapes) + 1), 7.5), layout="constrained")
    grid = fig.add_gridspec(2, len(shapes) + 1)
    for j, sh in enumerate(shapes):
        d = df[df["shape"] == sh].sort_values("T_min/T_max", ascending=False)
        x = d["T_min/T_max"]
        for i, what in enumerate(("freq", "static")):
            ax = fig.add_subplot(grid[i, j])
            for name, (c, ls, mk) in METHODS.items():
                err = d[f"{name} {what} err"]
                ax.loglog(x, err.clip(lower=1e-13, upper=TOP), color=c, ls=ls, marker=mk,
                          ms=4, label=name)
                if name.startswith("lumped"):          # no chain equilibrium: drawn on top
                    failed = err.isna() & ~np.isnan(x)
                    ax.loglog(x[failed], np.full(failed.sum(), 2 * TOP), color=c, ls="none",
                              marker="x", ms=6, label="lumped: no chain equilibrium")
            if what == "freq":
                g = d["closed form guard"].where(np.isfinite(d["closed form guard"]))
                ax.loglog(x, g, color="C0", ls="none", marker="x", ms=8,
                          label="closed-form guard (estimate)")
                ax.set_title(sh, fontsize=10)
            ax.axvspan(x.min() / 3, SLACK_RATIO, color="C0", alpha=0.07,
                       label=f"guard refuses the closed form (< {SLACK_RATIO:g})")
            ax.axvspan(x.min() / 3, MIN_TENSION_RATIO, color="C3", alpha=0.15,
                       label=f"exact rung refuses (< {MIN_TENSION_RATIO:g})")
            ax.axhline(1e-6, color="k", lw=0.6, ls=(0, (1, 2)))
            ax.set_xlim(x.min() / 3, x.max() * 2)
            ax.invert_xaxis()
            ax.set_ylim(1e-13, 5 * TOP)
            ax.grid(True, which="major", alpha=0.3)
            ax.set_ylabel(f"rel. error, first {N_MODES} frequencies" if what == "freq"
                          else "rel. error, static end stiffness")
            if i == 1:
                ax.set_xlabel("T_min / T_max [-] (slacker to the right)")
    ax = fig.add_subplot(grid[:, -1])
    d = df[np.isclose(df["T_min/T_max"], 1e-4, rtol=1e-3) & (df["shape"] == shapes[0])]
    for name, (c, _, mk) in METHODS.items():
        ax.loglog(d[f"{name} [s]"], d[f"{name} freq err"].clip(lower=1e-13, upper=TOP), color=c,
                  ls="none", marker=mk, ms=7, label=name)
    ax.axhline(1e-6, color="k", lw=0.6, ls=(0, (1, 2)))
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel(f"rel. error, first {N_MODES} frequencies")
    ax.set_title(f"speed and accuracy at T_min / T_max = 1e-4\n({shapes[0]})", fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    handles = {}
    for a in fig.axes:
        for h, lab in zip(*a.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(handles.values(), handles.keys(), loc="outside upper center", ncol=4,
               fontsize=8)
    return fig


def main():
    pd.set_option("display.width", 250)
    df = run()
    cols = [c for c in df.columns if not c.endswith("[s]") and c != "exact"]
    print(df[cols].to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    import matplotlib
    matplotlib.use("Agg")
    fig = plot(df)
    out = Path(__file__).resolve().parent / "slack_cables.png"
    fig.savefig(out, dpi=120)
    print(f"\nwrote {out}")


if __name__ == "__main__":
    main()
