"""Which cable model a scene needs: the closed form, the lumped chain and the exact cable
against sag ratio and chord inclination.

One cable (chord 10 m, CoGiRo's cable: m = 0.064 kg/m, EA = 1.395e5 N, i.e. E = 17 GPa) at
inclinations 0-85 deg, its unstretched length solved for a sag ratio d/L from 1e-3 to 0.1
(d = `CatenaryState.sag`, the largest distance from the chord segment). Each model is
measured against the exact cable (theory.md §11):

- clamped-cable frequencies: the largest |f / f_exact - 1| over the first ``N_MODES``;
- static end stiffness (end B, A clamped): the largest relative error along any
  displacement, max |eig(K_ex^-1/2 (K - K_ex) K_ex^-1/2)| (the energy-norm error, which
  sees the soft transverse directions as well as the stiff axial one);

for (a) the closed form (Irvine-Caughey, theory.md §3, mean tension), with its own error
estimate `closed_form_validity(...).error` next to it (theory.md §11.5); (b) the lumped
chain (theory.md §7) at N = 10 and 40 segments. The exact model itself is checked against
the lumped chain at N = 400 and 800, Richardson-extrapolated ((4 f_800 - f_400) / 3,
theory.md §7.2).

Run ``python validation/exact_cable.py`` for the table and ``exact_cable.png``.
"""

from pathlib import Path

import numpy as np
import pandas as pd
from scipy.optimize import brentq

import dynstiff as ds
from dynstiff.cable.dsm import cable_dynamic_stiffness
from dynstiff.cable.guard import closed_form_validity
from dynstiff.cable.lumped_chain_dynamics import chain_end_dynamic_stiffness
from dynstiff.cable.modes import cable_natural_frequencies
from dynstiff.errors import DynstiffError
from dynstiff.lumped import chain_equilibrium, chain_fixed_end_frequencies

CHORD = 10.0                                   # [m]
CABLE = ds.Cable(0.064, 1.395e5)               # [kg/m], [N]
N_MODES = 10
LUMPED = (10, 40)                              # segments of the chains measured
REFERENCE = (400, 800)                         # chains of the Richardson check
TOLERANCES = (1e-2, 1e-4)
SAGS = (1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1)
INCLINATIONS = (0.0, 30.0, 60.0, 85.0)         # [deg]


def cable_for(sag_ratio, inclination_deg):
    """The catenary between A = 0 and B = CHORD (cos a, 0, -sin a) whose sag / chord is
    ``sag_ratio`` (unstretched length by Brent's method to 1e-12 m)."""
    th = np.radians(inclination_deg)
    A = np.zeros(3)
    B = CHORD * np.array([np.cos(th), 0.0, -np.sin(th)])

    def excess(L0):
        return ds.solve_catenary(A, B, L0, CABLE).sag / CHORD - sag_ratio

    hi = 1.05 * CHORD
    while excess(hi) < 0:
        hi *= 1.1
    L0 = brentq(excess, 0.95 * CHORD, hi, xtol=1e-12)
    return ds.solve_catenary(A, B, L0, CABLE)


def energy_error(K, K_ref):
    """max |eig(K_ref^-1/2 (K - K_ref) K_ref^-1/2)| [-] for symmetric K, K_ref (3, 3)."""
    from scipy.linalg import eigh
    if not np.all(np.isfinite(K)):
        return np.nan
    return float(np.max(np.abs(eigh(0.5 * (K + K.T) - K_ref, K_ref, eigvals_only=True))))


def _richardson(f_n, f_2n):
    return (4.0 * f_2n - f_n) / 3.0


def case(sag_ratio, inclination_deg, n_modes=N_MODES):
    """One row: every model's frequency and static stiffness error against the exact cable,
    and the closed form's error estimate. Returns a dict."""
    s = cable_for(sag_ratio, inclination_deg)
    ex = cable_natural_frequencies(s, n_modes, model="exact")
    f_ex = ex.freq_hz
    K_ex = cable_dynamic_stiffness(s, 0.0, model="exact")[0]
    f_cf = cable_natural_frequencies(s, n_modes, guard_rtol=None).freq_hz
    K_cf = cable_dynamic_stiffness(s, 0.0, guard_rtol=None)[0]
    guard = closed_form_validity(s, 2 * np.pi * f_ex[-1])
    row = {"sag/chord": sag_ratio, "inclination [deg]": inclination_deg,
           "L0 [m]": s.unstretched_length, "T_min/T_max": s.min_tension / s.max_tension,
           "lambda^2": s.lambda_sq, "f_1 exact [Hz]": f_ex[0],
           f"f_{n_modes} exact [Hz]": f_ex[-1],
           "axial among first": int(sum(f == "axial" for f in ex.family)),
           "closed form freq err": float(np.max(np.abs(f_cf / f_ex - 1))),
           "closed form static err": energy_error(K_cf, K_ex),
           "closed form guard": guard.error,
           "guard causes": ", ".join(k for k, e in guard.causes.items() if e > 1e-6)}
    A, B = s.anchor, s.end
    ref = {}
    for N in sorted(set(LUMPED) | set(REFERENCE)):
        try:
            ch = chain_equilibrium(A, B, s.unstretched_length, CABLE, N)
        except DynstiffError:          # a chain node at a slack U's bottom: no equilibrium
            f, K = np.full(n_modes, np.nan), np.full((3, 3), np.nan)
        else:
            f = chain_fixed_end_frequencies(ch, n_modes)
            K = chain_end_dynamic_stiffness(ch, 0.0)[0].real
        ref[N] = (f, K)
        if N in LUMPED:
            row[f"lumped N={N} freq err"] = float(np.max(np.abs(f / f_ex - 1)))
            row[f"lumped N={N} static err"] = energy_error(K, K_ex)
    (f1, K1), (f2, K2) = ref[REFERENCE[0]], ref[REFERENCE[1]]
    row["Richardson freq err"] = float(np.max(np.abs(_richardson(f1, f2) / f_ex - 1)))
    row["Richardson static err"] = energy_error(_richardson(K1, K2), K_ex)
    return row


def run(quick=False):
    """The grid of cables: sag ratios x inclinations (quick: 1e-3, 1e-2, 0.1 x 0, 60, 85 deg).

    Returns
    -------
    pandas.DataFrame
        One row per cable; the "... err" columns are relative errors [-] against the exact
        cable, "closed form guard" the closed form's own estimate [-] (inf: slack cable or
        axial modes in the band).
    """
    sags = (1e-3, 1e-2, 0.1) if quick else SAGS
    incl = (0.0, 60.0, 85.0) if quick else INCLINATIONS
    return pd.DataFrame([case(d, a) for a in incl for d in sags])


#: The approximate models, cheapest first, and their short names on the map.
APPROXIMATE = {"closed form": "CF", **{f"lumped N={N}": f"N{N}" for N in LUMPED}}


def sufficient(df, rtol):
    """Per cable, the approximate models within ``rtol`` on both the frequencies and the
    static stiffness, as a (inclination x sag) table of short names ("CF", "N10", "N40"
    joined by "+"; "exact" where none is)."""
    ok = {short: (df[f"{name} freq err"] <= rtol) & (df[f"{name} static err"] <= rtol)
          for name, short in APPROXIMATE.items()}
    names = [("+".join(k for k, v in ok.items() if v[i]) or "exact") for i in df.index]
    return df.assign(models=names).pivot(index="inclination [deg]", columns="sag/chord",
                                         values="models")


def plot(df, fig=None):
    """Errors against sag ratio, one column per inclination (top: frequencies, middle:
    static stiffness), and the approximate models within each tolerance (bottom).
    Returns the matplotlib Figure."""
    import matplotlib.pyplot as plt
    incl = sorted(df["inclination [deg]"].unique())
    fig = fig or plt.figure(figsize=(3.4 * len(incl), 10.5), layout="constrained")
    grid = fig.add_gridspec(3, len(incl))
    styles = {"closed form": ("C0", "-", "o"), f"lumped N={LUMPED[0]}": ("C1", "--", "s"),
              f"lumped N={LUMPED[1]}": ("C2", "--", "^"), "Richardson": ("0.5", ":", ".")}
    labels = {"Richardson": f"lumped N={REFERENCE[0]},{REFERENCE[1]} Richardson"}
    top = None
    for j, a in enumerate(incl):
        d = df[df["inclination [deg]"] == a].sort_values("sag/chord")
        for i, what in enumerate(("freq", "static")):
            ax = fig.add_subplot(grid[i, j], sharey=top)
            top = top or ax
            for name, (c, ls, mk) in styles.items():
                ax.loglog(d["sag/chord"], d[f"{name} {what} err"].clip(lower=1e-12), color=c,
                          ls=ls, marker=mk, ms=4, label=labels.get(name, name))
            if what == "freq":
                guard = d["closed form guard"].where(np.isfinite(d["closed form guard"]))
                ax.loglog(d["sag/chord"], guard, color="C0", ls="none", marker="x", ms=7,
                          label="closed-form guard (estimate)")
                slack = d.loc[~np.isfinite(d["closed form guard"]), "sag/chord"]
                for x in slack:
                    ax.axvline(x, color="C3", lw=0.8, alpha=0.5,
                               label="slack: guard = inf" if x == slack.iloc[0] else None)
                ax.set_title(f"inclination {a:g} deg", fontsize=10)
            for t in TOLERANCES:
                ax.axhline(t, color="k", lw=0.6, ls=(0, (1, 2)))
            ax.set_ylim(1e-10, 3.0)
            ax.grid(True, which="major", alpha=0.3)
            if j == 0:
                ax.set_ylabel(f"rel. error, first {N_MODES} frequencies" if what == "freq"
                              else "rel. error, static end stiffness")
            else:
                ax.tick_params(labelleft=False)
            if i == 1:
                ax.set_xlabel("sag / chord d/L [-]")
    handles = {}
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(handles.values(), handles.keys(), loc="outside upper center", ncol=6,
               fontsize=8)
    colours = {"CF": "#9ecae1", "N": "#a1d99b", "exact": "#fdd0a2"}
    half = len(incl) // 2
    for k, rtol in enumerate(TOLERANCES):
        ax = fig.add_subplot(grid[2, k * half:(k + 1) * half])
        tab = sufficient(df, rtol)
        ax.imshow(np.ones(tab.shape + (3,)), aspect="auto", origin="lower")
        for (r, c), v in np.ndenumerate(tab.to_numpy()):
            key = "CF" if v.startswith("CF") else ("exact" if v == "exact" else "N")
            ax.add_patch(plt.Rectangle((c - 0.5, r - 0.5), 1, 1, color=colours[key]))
            ax.text(c, r, v.replace("+", "\n"), ha="center", va="center", fontsize=7)
        ax.set_xticks(range(tab.shape[1]), [f"{x:g}" for x in tab.columns], fontsize=8)
        ax.set_yticks(range(tab.shape[0]), [f"{y:g}" for y in tab.index])
        ax.set_xlabel("sag / chord d/L [-]")
        ax.set_ylabel("inclination [deg]")
        ax.set_title(f"approximate models within {rtol:g} of the exact cable (frequencies and "
                     f"static stiffness)\nCF closed form, N10 / N40 lumped chain; exact: none "
                     f"of them", fontsize=9)
    return fig


def main():
    pd.set_option("display.width", 250)
    df = run()
    cols = [c for c in df.columns if c != "guard causes"]
    print(df[cols].to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    for rtol in TOLERANCES:
        print(f"\napproximate models within {rtol:g} of the exact cable")
        print(sufficient(df, rtol).to_string())
    import matplotlib
    matplotlib.use("Agg")
    fig = plot(df)
    out = Path(__file__).resolve().parent / "exact_cable.png"
    fig.savefig(out, dpi=120)
    print(f"\nwrote {out}")


if __name__ == "__main__":
    main()
