"""Speed against accuracy of the model ladder on CoGiRo (the chart is the product).

For CoGiRo at several poses and E = 17 and 120 GPa, every model of the ladder (spring,
catenary, closed-form dsm, lumped with N = 5 ... 80 segments per cable) is timed, side by side
in one run, on two jobs: (1) the first 10 / 20 / 40 natural frequencies, (2) an FRF (fz -> z)
at 2000 frequencies. Its error is measured against a converged reference: the lumped model
at N = 40 and 80 Richardson-extrapolated (eigenfrequencies) and the N = 80 lumped FRF.

Errors: frequencies, the largest relative error over the first k modes (inf when the model
has fewer than k modes: the massless models only have the platform's 6), and over the global
(platform) modes alone, identified by the closed-form model's labels; FRF, the RMS of
log10|H| - log10|H_ref| in decades, over the band's frequencies more than 2 % away from every
mode of the reference (at an undamped peak any frequency shift gives an unbounded log error).

Run ``python validation/speed_accuracy.py`` for the table and ``speed_accuracy.png``.
"""

import time

import numpy as np
import pandas as pd

import dynstiff as ds
from dynstiff.models.ladder import build_model

LADDER = [("spring", None), ("catenary", None), ("dsm", None), ("lumped", 5), ("lumped", 10),
          ("lumped", 20), ("lumped", 40)]


def _timed(fn, repeat=3):
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return out, best


def cogiro_equilibria(quick=False):
    scene = ds.load_scene("cogiro")
    r0 = scene.robot
    poses = [[0, 0, 1.0]] if quick else [[0, 0, 1.0], [2.0, 1.0, 1.5], [-3.0, -2.0, 2.0]]
    out = []
    for E in (17e9, 120e9):
        rob = ds.Robot(r0.anchors, r0.attachments, ds.Cable(0.064, 8.2051e-6 * E), r0.platform,
                       tension_limits=r0.tension_limits)
        for p in poses:
            out.append((E, p, rob.equilibrium(pose=p)))
    return out


def run(quick=False, band_hz=(0.5, 8.0), n_freq=2000):
    """Table: one row per (E, pose, model) with wall times [s] and errors.

    Returns
    -------
    pandas.DataFrame
    """
    f = np.linspace(*band_hz, n_freq)
    w = 2 * np.pi * f
    ladder = LADDER[:5] if quick else LADDER
    import warnings
    # the rungs' undamped FRFs are compared away from their modes (``away``): the warning
    # that an undamped FRF crosses resonances is expected here
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.ResonanceWarning)
        return _rows(ladder, band_hz, f, w, quick)


def _rows(ladder, band_hz, f, w, quick):
    rows = []
    for E, pose, eq in cogiro_equilibria(quick):
        n_ref = (20, 40) if quick else (40, 80)
        fa = ds.eigenfrequencies(build_model(eq, "lumped", n_ref[0]), 40)
        fb = ds.eigenfrequencies(build_model(eq, "lumped", n_ref[1]), 40)
        ref = fb + (fb - fa) / 3.0
        H_ref = np.abs(ds.frf(build_model(eq, "lumped", n_ref[1]), w, "fz", "z").H[:, 0, 0])
        ref_all = ds.eigenfrequencies(build_model(eq, "lumped", n_ref[1]), fmax_hz=band_hz[1] * 1.1)
        away = np.min(np.abs(f[:, None] / ref_all[None, :] - 1), axis=1) > 0.02
        dsm_modes = ds.modes(ds.FrequencyModel(eq), 40)
        glob = np.array(dsm_modes.kind) == "global"
        # reference frequency of each global mode: the nearest reference root
        ref_glob = ref[np.argmin(np.abs(ref[None, :] - dsm_modes.freq_hz[glob][:, None]), axis=1)]
        for rung, N in ladder:
            m, t_build = _timed(lambda: build_model(eq, rung, N or 30), repeat=1)
            fr, t_eig = _timed(lambda: ds.eigenfrequencies(m, 40) if rung in ("dsm", "lumped")
                               else ds.eigenfrequencies(m, m.n_dof))
            res, t_frf = _timed(lambda: ds.frf(m, w, "fz", "z"))
            H = np.abs(res.H[:, 0, 0])[away]
            row = {"E [GPa]": E / 1e9, "pose": str(pose), "model": rung if N is None
                   else f"lumped N={N}", "rung": rung, "segments": N or 0,
                   "build [s]": t_build, "40 modes [s]": t_eig, "FRF [s]": t_frf,
                   "FRF log error [dec]": float(np.sqrt(np.mean(
                       np.log10(H / H_ref[away]) ** 2)))}
            if rung in ("spring", "catenary"):
                fg = np.sort(fr)[:len(ref_glob)]
            else:               # global modes of this model: nearest to the reference's
                fg = fr[np.argmin(np.abs(fr[None, :] - ref_glob[:, None]), axis=1)]
            row["err global modes"] = float(np.max(np.abs(fg / ref_glob - 1)))
            for k in (10, 20, 40):
                row[f"err first {k}"] = (float(np.max(np.abs(fr[:k] / ref[:k] - 1)))
                                         if len(fr) >= k else np.inf)
            rows.append(row)
    return pd.DataFrame(rows)


def pareto(df, error="err first 20", cost="40 modes [s]"):
    """Mean error and cost per model over the cases, with the Pareto-optimal ones flagged."""
    g = df.groupby("model").agg({error: "max", cost: "median", "build [s]": "median"})
    g["total [s]"] = g[cost] + g["build [s]"]
    g = g.sort_values("total [s]")
    best = np.inf
    flags = []
    for e in g[error]:
        flags.append(bool(e < best))
        best = min(best, e)
    g["pareto"] = flags
    return g


if __name__ == "__main__":
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pd.set_option("display.width", 200)
    df = run()
    print(df.to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    for k in ("global modes", "first 10", "first 20", "first 40"):
        print(f"\nPareto, {k}")
        print(pareto(df, f"err {k}").to_string(float_format=lambda x: f"{x:.3g}"))
    from dynstiff.plot import plot_speed_accuracy
    measures = [("err global modes", "40 modes [s]", "max relative error, global modes"),
                ("err first 10", "40 modes [s]", "max relative error, first 10 modes"),
                ("err first 20", "40 modes [s]", "max relative error, first 20 modes"),
                ("err first 40", "40 modes [s]", "max relative error, first 40 modes"),
                ("FRF log error [dec]", "FRF [s]", "FRF RMS log error [decades]")]
    fig, axes = plt.subplots(2, 3, figsize=(16, 9))
    for ax, (err, cost, label) in zip(axes.flat, measures):
        plot_speed_accuracy(df, error=err, cost=cost, ax=ax)
        ax.set_ylabel(label)
    for ax in axes.flat[len(measures):]:
        ax.remove()
    n_cases = df.groupby(["E [GPa]", "pose"]).ngroups
    fig.suptitle(f"CoGiRo, {n_cases} cases (poses x E in {{17, 120}} GPa): cost against "
                 "accuracy (worst case)")
    fig.tight_layout()
    fig.savefig("speed_accuracy.png", dpi=120)
    print("wrote speed_accuracy.png")
