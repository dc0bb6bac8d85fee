"""Designing CoGiRo for frequency: the first platform mode over the workspace with the
default and the frequency-optimal tensions, and the probability that a platform mode enters
a forbidden band when EA is known to +-10 % (theory.md §16.6, §16.7).

The workspace: a grid of positions of P at z = 1 m (x from -4 to 4 m, y from -3 to 3 m,
step 2 and 1.5 m) at zero rotation, built-in scene ``cogiro`` (17 GPa, t_min = 100 N).

* Tensions: :func:`dynstiff.workspace` with ``tensions="default"`` (closest to t_min) and
  ``"max-frequency"`` (:func:`dynstiff.optimal_tensions`); the reference of the optimum is
  a brute-force look around it: the first platform mode 5 N away along each direction of
  the tension null space (``neighbour excess`` > 0 would say a neighbour does better).
* Probability: EA uniform within +-10 % (EA of every cable together), the scene's forbidden
  band 0-1.5 Hz with the checks' 5 % margin (every mode with platform share >= 5 % held to
  it); the share of robots whose band check fails, by Monte Carlo (64 Latin-hypercube
  samples, seed 0) and by first order on the same samples: the difference is the first
  order's error (``P first order - P Monte Carlo``).

Run ``python validation/design_for_frequency.py`` for the table and
``design_for_frequency.png``.
"""

import numpy as np
import pandas as pd

import dynstiff as ds

BAND = (0.0, 1.5)
MARGIN = 0.05
X, Y, Z = np.arange(-4.0, 4.01, 2.0), np.arange(-3.0, 3.01, 1.5), 1.0


def _null_basis(eq):
    import scipy.linalg
    u = np.array([s.force_on_end / s.tension_at_end for s in eq.states])
    return scipy.linalg.null_space(np.vstack([u.T, np.cross(eq.lever_arms, u).T]))


def _neighbour_excess(robot, pose, opt, step=5.0):
    """Largest first platform mode 5 N away from the optimum along the null space, minus
    the optimum's [Hz] (<= 0 when none does better)."""
    from dynstiff.analyses.platform_modes import find_platform_modes
    N = _null_basis(opt.default)
    out = -np.inf
    for d in np.concatenate([N.T, -N.T]):
        try:
            eq = robot.equilibrium(pose=pose, tension_reference=opt.reference + step * d)
        except ds.DynstiffError:
            continue
        out = max(out, find_platform_modes(ds.FrequencyModel(eq)).first_hz - opt.value)
    return out


def run(quick=False, n_samples=64):
    """The table of the study, one row per pose.

    Returns
    -------
    pandas.DataFrame
        x, y [m]; first platform mode with the default and the optimal tensions [Hz], the
        gain [Hz] and what binds; ``neighbour excess`` [Hz] (the optimum against its
        neighbours); P(the band check fails) by Monte Carlo and first order [-] and their
        difference (the first order's error).
    """
    sc = ds.load_scene("cogiro")
    rob = sc.robot
    xs, ys = (X[[1, 3]], Y[[1, 3]]) if quick else (X, Y)
    poses = [[x, y, Z] for x in xs for y in ys]
    base = ds.workspace(rob, poses, n_modes=4)
    best = ds.workspace(rob, poses, n_modes=4, tensions="max-frequency")
    rows = []
    for i, p in enumerate(poses):
        opt = ds.optimal_tensions(rob, p)
        unc = ds.propagate_uncertainty(rob, p, {"EA": "10%:uniform"}, n_modes=1,
                                       band_hz=BAND, n_samples=n_samples, seed=0)
        p_mc = unc.probability_below("band_margin", MARGIN)
        p_fo = unc.probability_below("band_margin", MARGIN, "first-order")
        rows.append({
            "x [m]": p[0], "y [m]": p[1],
            "default first platform [Hz]": float(base["first_platform_hz"][i]),
            "optimal first platform [Hz]": float(best["first_platform_hz"][i]),
            "gain [Hz]": float(best["first_platform_hz"][i] - base["first_platform_hz"][i]),
            "optimum (single pose) [Hz]": opt.value,
            "neighbour excess [Hz]": _neighbour_excess(rob, p, opt),
            "binds": "; ".join(opt.binds), "equilibria": opt.evaluations,
            "P fail Monte Carlo [-]": p_mc, "P fail first order [-]": p_fo,
            "P first order - P Monte Carlo [-]": p_fo - p_mc,
            "margin at 95 % [-]": unc.quantile("band_margin", 0.05)})
    return pd.DataFrame(rows)


def _jump(df):
    """Poses whose optimum lies next to a jump of the objective (what binds says so)."""
    return df["binds"].str.contains("jumps|drops")


def summary(df):
    """Headline numbers: gains (mean, largest), poses improved, the optimum's excess over
    its neighbours, the largest probability and the first order's largest error."""
    return pd.Series({
        "poses": len(df), "improved": int((df["gain [Hz]"] > 1e-4).sum()),
        "mean gain [Hz]": df["gain [Hz]"].mean(), "largest gain [Hz]": df["gain [Hz]"].max(),
        "mean relative gain [-]": (df["gain [Hz]"]
                                   / df["default first platform [Hz]"]).mean(),
        "largest neighbour excess [Hz]": df["neighbour excess [Hz]"].max(),
        "poses next to a jump of the objective": int(_jump(df).sum()),
        "largest neighbour excess away from jumps [Hz]":
            df.loc[~_jump(df), "neighbour excess [Hz]"].max(),
        "largest P fail [-]": df["P fail Monte Carlo [-]"].max(),
        "largest |P first order - P Monte Carlo| [-]":
            df["P first order - P Monte Carlo [-]"].abs().max()})


def figure(df):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 7.6), constrained_layout=True)
    nx, ny = df["x [m]"].nunique(), df["y [m]"].nunique()
    ext = [df["x [m]"].min() - 1, df["x [m]"].max() + 1, df["y [m]"].min() - 0.75,
           df["y [m]"].max() + 0.75]
    f_range = (df["default first platform [Hz]"].min(),
               df["optimal first platform [Hz]"].max())
    panels = (("default first platform [Hz]", "first platform mode, default tensions [Hz]",
               "viridis", f_range),
              ("optimal first platform [Hz]", "first platform mode, optimal tensions [Hz]",
               "viridis", f_range),
              ("gain [Hz]", "gain of the frequency-optimal tensions [Hz]", "viridis", None),
              ("P fail Monte Carlo [-]", f"P(a platform mode within {MARGIN:.0%} of "
               f"{BAND[0]:g}-{BAND[1]:g} Hz), EA +-10 %", "Reds", (0.0, 1.0)))
    for ax, (col, title, cmap, lim) in zip(axes.ravel(), panels):
        v = df[col].to_numpy()
        lo, hi = lim if lim is not None else (v.min(), v.max())
        im = ax.imshow(v.reshape(nx, ny).T, origin="lower", extent=ext, cmap=cmap,
                       aspect="auto", vmin=lo, vmax=hi)
        for x, y, val in zip(df["x [m]"], df["y [m]"], v):
            light = (val - lo) / (hi - lo if hi > lo else 1.0) > 0.6
            dark_text = light if cmap == "viridis" else not light
            ax.text(x, y, f"{val:.3g}", ha="center", va="center", fontsize=8,
                    color="k" if dark_text else "w")
        ax.set(title=title, xlabel="x [m]", ylabel="y [m] (z = 1 m)")
        fig.colorbar(im, ax=ax)
    return fig


if __name__ == "__main__":
    import matplotlib
    matplotlib.use("Agg")
    df = run()
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(df.drop(columns=["binds"]).to_string(index=False, float_format="%.4g"))
        print(df[["x [m]", "y [m]", "binds"]].to_string(index=False))
        print(summary(df).to_string())
    figure(df).savefig("design_for_frequency.png", dpi=130)
    print("wrote design_for_frequency.png")
