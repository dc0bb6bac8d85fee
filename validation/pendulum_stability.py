"""Inverted pendulum on two cables with harmonically moved ends (seed paper 004, Polach &
Hajzman): where is the upright pendulum unstable, for massless and point-mass cables, as the
preload, the amplitude, the cable mass and the phase of the excitation change?

Model and choices: built-in scene ``pendulum`` and :mod:`dynstiff.timedomain.pendulum` (symmetric
outward excitation of B and C along BC, b = 5e-4 s x k, 10 point masses per cable). Method:
Floquet multipliers of the linearisation about the periodic response (|mu| > 1: unstable),
each unstable frequency interval checked by a nonlinear simulation from phi0 = 1e-6 rad at
its worst frequency (the angle must grow), and one stable frequency per case checked to
decay. The paper's qualitative conclusions are compared in ``table.attrs["comparison"]``.

Results of the full run (1894 s on one core; the tables below are its output):

* preload 0 (x0 = 0.02 m): unstable on 59 % of 0.1-200 Hz with massless cables (largest
  |mu| = 11.5 at 1.96 Hz; 11 of the 14 unstable intervals confirmed by simulation, the
  others narrow ones below 0.3 Hz), 73 % of the 5-120 Hz grid with point-mass cables;
  826 N: 37 % (16 of 16 confirmed); from 2066 N, above the slack preload k x0 a / L =
  1402 N, stable everywhere for both models (|mu| <= 0.975);
* amplitude 0.02 to 0.2 m at zero preload: 55-59 % unstable;
* cable mass (point-mass model, 3.8, 30, 269 g): 73, 86, 77 % of the grid unstable against
  59 % massless; 27-36 % of the grid is unstable only with point-mass cables (the paper
  says cable mass does not destabilise: the one disagreement, see ``attrs["comparison"]``);
  slack point-mass cables move aperiodically (27, 9 and 0 % of these responses are
  periodic), so there the multiplier is the finite-time growth per period along the
  aperiodic response (:func:`dynstiff.timedomain.pendulum.floquet`);
* 30 deg phase shift: unstable on 50 % with, 62 % without; 3 % only with it (agrees);
* taut cables (8264 N, x0 = 0.1 m): only the Mathieu tongue at twice the natural
  frequency is left, |mu| = 1.010 at 43.7 Hz undamped, 0.998 with b = 5e-5 s x k, 0.901
  with the scene's 5e-4 s x k.

Transient amplification: below the slack preload the Floquet multiplier can be small while
the pendulum is not stable in practice. At 0.11 Hz and zero preload |mu| = 0.005 per
period, yet the simulation from 1e-6 rad wobbles at 0.015-0.02 rad (the "stable check" of
those rows grows by 1e3-1e5, outcome "grows, bounded"): during the half period in which
both cables are slack the upright pendulum falls freely, exp(sqrt(m g c / I_A) T / 2) ~
e^17.4 at 0.11 Hz, until a cable catches it (the chord shortens by x0 a / L, a tilt
lengthens it by (a d / L) phi: at phi = x0 / d = 0.027 rad); the taut half period then
damps it by about as much. The linear multiplier is the product of the two;
any disturbance above ~1e-8 rad (the integrator's tolerance here) reaches the catch
amplitude. Above the slack preload the stable checks decay (growth 7e-4 to 0.16).

Run ``python validation/pendulum_stability.py`` for the tables and ``pendulum_stability.png``
(about 40 min on one core; ``run(quick=True)`` takes seconds).
"""

import time
from dataclasses import replace

import numpy as np
import pandas as pd

import dynstiff as ds
from dynstiff.timedomain import pendulum as pdl

#: An angle above this [rad] counts as "the pendulum falls" (5.7 deg; a falling pendulum in
#: these runs reaches 0.3 rad, the chaotic wobble of slack point-mass cables 0.003 rad).
FALL_ANGLE = 0.1
#: Initial disturbance of the confirming simulations [rad].
PHI0 = 1e-6


def _cases(st, quick):
    """(study, preload [N], x0 [m], cable mass [kg], phase [deg], extra) of every case."""
    P, x0, mc = st["preload"], st["amplitude"], st["cable_mass"]
    out = [("preload", p, x0, mc, 0.0, {}) for p in st["preloads"]]
    out += [("amplitude", P, a, mc, 0.0, {}) for a in st["amplitudes"] if a != x0]
    out += [("cable mass", P, x0, m, 0.0, {}) for m in st["cable_masses"] if m != mc]
    out += [("phase", P, x0, mc, st["phase_deg"], {})]
    # sensitivity to the unreadable figure and the lost damping exponent (massless only)
    out += [("translation excitation", P, a, mc, 180.0, {}) for a in (x0, 0.2)]
    out += [("ends at D's height", P, x0, mc, 0.0,
             {"end_height": st["end_height_alternative"]})]
    # taut cables (P > k x0 a/L): only the small Mathieu modulation is left, on a fine grid
    # about twice the natural frequency
    out += [(f"damping b = {t:g} s x k", 8264.0, 0.1, mc, 0.0,
             {"damping_time": t, "fine": True}) for t in (st["damping_time"], 5e-5, 0.0)]
    if quick:
        keep = {("preload", 0.0), ("preload", 2066.0), ("amplitude", 0.2),
                ("phase", st["phase_deg"]), ("damping b = 0 s x k", 8264.0)}
        out = [c for c in out if (c[0], c[1]) in keep or (c[0], c[2]) in keep
               or (c[0], c[4]) in keep]
    return out


def _point_mass_wanted(case, quick, st):
    study, P, x0, mc, ph, extra = case
    if study not in ("preload", "amplitude", "cable mass", "phase"):
        return False
    if quick:
        return study == "preload" and P in (0.0, 2066.0)
    return True


def _grids(quick, n_masses, phase):
    if quick:
        if n_masses:
            return np.array([30.0, 50.0])
        return np.array([25.0, 30.0, 35.0, 50.0]) if phase else np.geomspace(2.0, 200.0, 48)
    if n_masses:
        return np.geomspace(5.0, 120.0, 14 if phase else 22)
    return np.geomspace(1.0, 200.0, 40) if phase else np.geomspace(0.1, 200.0, 241)


def _growth(model, f, x0, phase, mu, t_max):
    """Nonlinear check at one frequency, from phi0 = PHI0: the growth of the disturbance,
    max |phi| over the last period / PHI0 (for non-symmetric excitation, of the difference
    from the run without disturbance), the growth Floquet predicts for that time, the
    largest |phi| [rad] and the wall time [s]."""
    n_per = int(np.clip(np.ceil(np.log(1e6) / np.log(max(mu, 1.0 + 1e-3))), 8, 2000))
    t_end = max(min(n_per / f, t_max), 8.0 / f)
    start = time.perf_counter()
    r = pdl.simulate(model, f, x0, t_end, phase=phase, phi0=PHI0)
    phi = r.phi
    if phase != 0.0:
        phi = phi - pdl.simulate(model, f, x0, t_end, phase=phase, phi0=0.0).phi
    last = np.abs(phi[r.t >= r.t[-1] - 1.0 / f]).max()
    return (last / PHI0, mu ** (t_end * f), float(np.abs(r.phi).max()),
            time.perf_counter() - start)


def _confirmed(growth, predicted, max_phi):
    """The disturbance grew by at least the square root of the Floquet prediction, or left
    the linear range (|phi| >= 0.01 rad from 1e-6 rad)."""
    return growth > 1.0 and (np.log(growth) >= 0.5 * np.log(predicted) or max_phi >= 0.01)


def _outcome(growth, max_phi):
    if growth <= 1.0:
        return "decays"
    return "falls" if max_phi >= FALL_ANGLE else "grows, bounded"


def run(quick=False):
    """Stability of the upright pendulum for every case of the paper's Tab. 1.

    Parameters
    ----------
    quick : bool
        Coarse grids, point-mass cables for two preloads at two frequencies, and fewer
        cases (for tests).

    Returns
    -------
    pandas.DataFrame
        One row per case and cable model: the case ("study", "preload [N]", "x0 [m]",
        "cable mass [kg]", "phase [deg]", "model"), the frequency grid, the unstable
        intervals [Hz] (a list of (first, last) unstable grid frequencies), the unstable
        fraction of the grid, the largest pendulum multiplier and its frequency, the share of
        periodic responses, the nonlinear checks at the worst frequency of each unstable
        interval (simulated growth max |phi(last period)| / phi0, the growth mu^n Floquet
        predicts for that run, largest |phi| [rad], outcome "falls" / "grows, bounded" /
        "decays", and how many intervals that confirms) and at the most stable frequency
        (its growth must stay below 1), and the wall times [s].
        ``attrs["maps"]``: all grid points (see :func:`dynstiff.timedomain.pendulum.stability_map`);
        ``attrs["comparison"]``: the paper's statements against dynstiff's findings;
        ``attrs["constants"]``: natural frequency, slack thresholds, damping ratio.
    """
    scene = ds.load_scene("pendulum")
    st = scene.study
    base = pdl.from_scene(scene, preload=st["preload"], cable_mass=st["cable_mass"])
    rows, maps = [], []
    for case in _cases(st, quick):
        study, P, x0, mc, ph_deg, extra = case
        for n in (0, st["n_point_masses"]):
            if n and not _point_mass_wanted(case, quick, st):
                continue
            model = replace(base, preload=P, cable_mass=mc, n_masses=n,
                            end_height=extra.get("end_height", base.end_height),
                            damping=extra.get("damping_time", st["damping_time"])
                            * base.stiffness)
            phase = np.radians(ph_deg)
            f = _grids(quick, n, ph_deg != 0.0)
            if extra.get("fine"):
                f = 2 * model.natural_frequency_hz() * np.linspace(0.99, 1.01, 41 if quick
                                                                    else 201)
            opts = {"transient_periods": 10, "average_periods": 10} if n or ph_deg else {}
            df = pdl.stability_map(model, f, [x0], phase=phase, **opts)
            if n:
                ref = pdl.floquet(replace(model, n_masses=0), f, x0, phase, **opts)
                df["massless |multiplier| [-]"] = ref.pendulum_abs
            df.insert(0, "study", study)
            df.insert(1, "model", "point-mass" if n else "massless")
            maps.append(df)
            mu = df["pendulum |multiplier| [-]"].to_numpy()
            stable = df["stable"].to_numpy()
            intervals = pdl.unstable_intervals(f, stable)
            t_sim = 0.3 if n else 3.0
            checks = []
            if not quick or (study == "preload" and P == 0.0 and not n):
                for lo, hi in intervals:
                    sel = (f >= lo) & (f <= hi)
                    k = np.flatnonzero(sel)[np.argmax(mu[sel])]
                    checks.append((f[k],) + _growth(model, f[k], x0, phase, mu[k], t_sim))
            stable_check = None
            if np.any(stable) and (not quick or (study == "preload" and P == 0.0 and not n)):
                k = np.flatnonzero(stable)[np.argmin(mu[stable])]
                stable_check = (f[k],) + _growth(model, f[k], x0, phase, mu[k], t_sim)
            k = int(np.argmax(mu))
            rows.append({
                "study": study, "preload [N]": P, "x0 [m]": x0, "cable mass [kg]": mc,
                "phase [deg]": ph_deg, "model": "point-mass" if n else "massless",
                "end height [m]": model.end_height, "damping b [N s/m]": model.damping,
                "natural freq [Hz]": model.natural_frequency_hz(),
                "f min [Hz]": f[0], "f max [Hz]": f[-1], "n freqs": f.size,
                "unstable intervals [Hz]": intervals,
                "unstable fraction [-]": float(np.mean(~stable)),
                "max pendulum |multiplier| [-]": float(mu[k]), "f at max [Hz]": float(f[k]),
                "periodic fraction [-]": float(df["periodic orbit"].mean()),
                "checked intervals": len(checks),
                "confirmed intervals": sum(_confirmed(g, q, p) for _, g, q, p, _ in checks),
                "sim growth [-]": [float(g) for _, g, _, _, _ in checks],
                "Floquet growth [-]": [float(q) for _, _, q, _, _ in checks],
                "sim max |phi| [rad]": [float(p) for _, _, _, p, _ in checks],
                "sim outcome": [_outcome(g, p) for _, g, _, p, _ in checks],
                "stable check f [Hz]": None if stable_check is None else stable_check[0],
                "stable check growth [-]": None if stable_check is None else stable_check[1],
                "stable check max |phi| [rad]": None if stable_check is None
                else stable_check[3],
                "stable check outcome": None if stable_check is None
                else _outcome(stable_check[1], stable_check[3]),
                "map wall time [s]": float(df["wall time [s]"].iloc[0]),
                "sim wall time [s]": float(sum(w for *_, w in checks)
                                           + (0.0 if stable_check is None else stable_check[4])),
            })
    table = pd.DataFrame(rows)
    table.attrs["maps"] = pd.concat(maps, ignore_index=True)
    table.attrs["comparison"] = _compare(table, base, st)
    zeta = base.damping * base.lever_factor ** 2 / (
        base.pin_inertia * 2 * np.pi * base.natural_frequency_hz())
    table.attrs["constants"] = {
        "natural freq P=0 [Hz]": base.natural_frequency_hz(),
        "natural freq P=8264 [Hz]": replace(base, preload=8264.0).natural_frequency_hz(),
        "natural freq, ends at D's height [Hz]": replace(
            base, end_height=st["end_height_alternative"]).natural_frequency_hz(),
        "slack preload at x0 = 0.02 m [N]": base.stiffness * st["amplitude"]
        * base.half_span / base.chord_length,
        "damping ratio [-]": zeta,
    }
    return table


def _compare(table, base, st):
    """The paper's conclusions (Sec. 4) against this study. A factor "causes instability"
    in dynstiff's reading when it makes more than 5 % of the frequency grid unstable that is
    stable without it."""
    x0, P0 = st["amplitude"], st["preload"]
    slack = base.stiffness * x0 * base.half_span / base.chord_length
    out = []
    pre = table[(table["study"] == "preload") & (table["model"] == "massless")]
    below = pre[pre["preload [N]"] < slack]["unstable fraction [-]"]
    above = pre[pre["preload [N]"] > slack]["unstable fraction [-]"]
    found = bool(below.gt(0).any())
    out.append(("the preload can make the pendulum unstable", True, found,
                f"unstable fraction {below.max() if below.size else 0:.2f} for P below the "
                f"slack preload k x0 a/L = {slack:.0f} N, "
                f"{above.max() if above.size else 0:.2f} above it"))
    amp = table[table["study"].isin(["amplitude", "preload"]) & (table["model"] == "massless")
                & (table["preload [N]"] == P0)]
    found = bool(amp["unstable fraction [-]"].gt(0).any())
    out.append(("some amplitude-frequency combinations are unstable", True, found,
                "unstable fractions " + ", ".join(
                    f"x0 = {a:g} m: {u:.2f}" for a, u in
                    zip(amp["x0 [m]"], amp["unstable fraction [-]"]))))
    maps = table.attrs["maps"]
    tol = 1e-6
    sel = ((table["study"] == "preload") & (table["model"] == "massless")
           & (table["preload [N]"] == P0))
    base_row = table[sel].iloc[0]
    base_u = float(base_row["unstable fraction [-]"])
    band = f"{base_row['f min [Hz]']:g}-{base_row['f max [Hz]']:g} Hz"
    # new instability: frequencies where the point-mass model is unstable and the massless
    # one (same frequency, same case) is stable
    g = maps[(maps["model"] == "point-mass") & (maps["phase [deg]"] == 0.0)
             & (maps["preload [N]"] == P0) & (maps["x0 [m]"] == x0)]
    new = (g["pendulum |multiplier| [-]"] > 1 + tol) & (g["massless |multiplier| [-]"] <= 1 + tol)
    per_mass = g.assign(new=new).groupby("cable mass [kg]")["new"].mean()
    out.append(("adding cable mass causes instability", False, bool(new.mean() > 0.05),
                f"zero preload, x0 = {x0:g} m: the massless baseline is already unstable on "
                f"{base_u:.2f} of {band}; share of the point-mass grid unstable where the "
                f"massless model is stable: " + ", ".join(
                    f"{m * 1e3:g} g: {v:.2f}" for m, v in per_mass.items())))
    g = maps[(maps["model"] == "massless") & (maps["study"] == "phase")]
    if len(g):
        ref = pdl.floquet(replace(base, preload=P0, n_masses=0), g["f [Hz]"].to_numpy(), x0)
        new = (g["pendulum |multiplier| [-]"].to_numpy() > 1 + tol) & ref.stable
        detail = (f"massless, {len(g)} frequencies {g['f [Hz]'].min():g}-"
                  f"{g['f [Hz]'].max():g} Hz: unstable on {np.mean(~g['stable']):.2f} with the "
                  f"shift, {np.mean(~ref.stable):.2f} without; unstable only with the shift: "
                  f"{np.mean(new):.2f}")
        out.append(("the 30 deg phase shift causes instability", False,
                    bool(np.mean(new) > 0.05), detail))
    diffs = {}
    pm = maps[maps["model"] == "point-mass"]
    for study, g in pm.groupby("study"):
        diffs[study] = float(np.mean(np.abs(np.log(g["pendulum |multiplier| [-]"])
                                            - np.log(g["massless |multiplier| [-]"]))))
    largest = max(diffs, key=diffs.get) if diffs else "n/a"
    out.append(("massless and point-mass models differ most in the cable-mass study", True,
                largest == "cable mass",
                "mean |ln mu_point-mass - ln mu_massless| per study: " + ", ".join(
                    f"{k}: {v:.2f}" for k, v in diffs.items())))
    df = pd.DataFrame(out, columns=["statement", "paper", "dynstiff", "detail"])
    df.insert(3, "agrees", df["paper"] == df["dynstiff"])
    return df


def plot(table):
    """Figure: pendulum |multiplier| against frequency, one panel per study (lines: massless
    cables, dots: point-mass cables, one colour per value; above 1: unstable)."""
    import matplotlib.pyplot as plt
    maps = table.attrs["maps"]
    keys = {"preload": "preload [N]", "amplitude": "x0 [m]", "cable mass": "cable mass [kg]",
            "phase": "phase [deg]"}
    baseline = (maps["study"] == "preload") & (maps["preload [N]"] == 0.0)
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True, sharey=True)
    for ax, (study, key) in zip(axes.ravel(), keys.items()):
        g = maps[(maps["study"] == study) | (baseline if study != "preload" else False)]
        for i, (val, h) in enumerate(g.groupby(key)):
            colour = f"C{i}"
            for model, hm in h.groupby("model"):
                hm = hm.sort_values("f [Hz]")
                mu = np.clip(hm["pendulum |multiplier| [-]"], 1e-2, None)
                if model == "massless":
                    ax.loglog(hm["f [Hz]"], mu, color=colour, lw=1, label=f"{val:g} massless")
                else:
                    ax.loglog(hm["f [Hz]"], mu, "o", color=colour, ms=4,
                              label=f"{val:g} point-mass")
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_ylim(1e-2, 30.0)
        ax.set_title(f"{study} ({key})")
        ax.legend(fontsize=7, loc="lower right")
    for ax in axes[:, 0]:
        ax.set_ylabel("pendulum |multiplier| [-]")
    for ax in axes[1]:
        ax.set_xlabel("excitation frequency [Hz]")
    return fig


if __name__ == "__main__":
    import matplotlib
    matplotlib.use("Agg")
    pd.set_option("display.width", 250)
    pd.set_option("display.max_colwidth", 90)
    start = time.perf_counter()
    tab = run()
    print(tab.drop(columns=["end height [m]", "damping b [N s/m]"]).to_string(index=False))
    print()
    print(tab.attrs["comparison"].to_string(index=False))
    print()
    for k, v in tab.attrs["constants"].items():
        print(f"{k}: {v:.6g}")
    print(f"total wall time {time.perf_counter() - start:.0f} s")
    fig = plot(tab)
    fig.tight_layout()
    fig.savefig("pendulum_stability.png", dpi=120)
    print("wrote pendulum_stability.png")
