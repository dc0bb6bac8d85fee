"""Chordwise cable inertia: closed-form DSM with and without the consistent axial mass,
against the dynamic condensation of an independent lumped-mass cable (theory.md §3.6).

The closed-form theory neglects the cable's inertia along the chord. The first-order fix adds
-omega^2 m L / 3 to the chordwise entry of the end matrix. This study measures both variants
against a lumped-mass chain (N = 200 and 400 segments, Richardson-extrapolated, O(N^-2)), on
CoGiRo cables (theory.md §9.2) at several tensions and both ends of the Young's modulus range,
at frequencies away from the cable's own poles, and reports the relative error of the chordwise
entry K_uu and of the whole matrix.

Run ``python validation/chordwise_inertia.py`` for the table and a figure.
"""

import numpy as np
import pandas as pd

import dynstiff as ds
from dynstiff.cable.dsm import chord_parameters
from dynstiff.lumped import chain_end_dynamic_stiffness, chain_equilibrium

ANCHOR = np.array([-7.1775, -5.4361, 5.3911])
END = np.array([0.5032, -0.4928, 1.0])
AREA, MASS = 8.2051e-6, 0.064


def lumped_reference(state, omega, segments=(200, 400)):
    """Richardson-extrapolated lumped-mass end stiffness (global frame), shape (n, 3, 3)."""
    Ks = []
    for n in segments:
        ch = chain_equilibrium(state.anchor, state.end, state.unstretched_length, state.cable,
                               n, state.g)
        Ks.append(chain_end_dynamic_stiffness(ch, omega))
    r = (segments[1] / segments[0]) ** 2
    return Ks[1] + (Ks[1] - Ks[0]) / (r - 1), Ks[1]


def run(quick=False):
    """Table of errors of the closed-form DSM against the lumped-mass reference.

    Returns
    -------
    pandas.DataFrame
        One row per (E, tension, frequency): K_uu relative error without / with the chordwise
        mass, whole-matrix relative error (2-norm) without / with, and the gap between the
        N = 400 chain and its extrapolation (the reference's own error).
    """
    cases = [(17e9, 300.0)] if quick else [(17e9, 100.0), (17e9, 300.0), (17e9, 1000.0),
                                           (120e9, 300.0), (120e9, 1000.0)]
    rows = []
    for E, T in cases:
        cable = ds.Cable(MASS, AREA * E)
        state = ds.unstretched_length_for_tension(ANCHOR, END, T, cable)
        p = chord_parameters(state)
        R = p.rotation
        poles = ds.cable_natural_frequencies(state, 12).freq_hz
        f = np.linspace(0.25, 8.0, 8 if quick else 32)
        f = f[np.min(np.abs(f[:, None] / poles[None, :] - 1), axis=1) > 0.03]
        w = 2 * np.pi * f
        K_ref, K_400 = lumped_reference(state, w)
        K_no = ds.cable_dynamic_stiffness(state, w, chordwise_inertia=False)
        K_yes = ds.cable_dynamic_stiffness(state, w, chordwise_inertia=True)
        loc = lambda K: R.T @ K @ R
        uu = lambda K: loc(K)[:, 0, 0]
        norm = lambda K: np.linalg.norm(K, 2, axis=(1, 2))
        for i in range(len(f)):
            rows.append({
                "E [GPa]": E / 1e9, "tension [N]": T, "lambda^2": p.lambda_sq, "freq [Hz]": f[i],
                "K_uu ref [N/m]": uu(K_ref)[i],
                "K_uu err without": uu(K_no)[i] / uu(K_ref)[i] - 1,
                "K_uu err with": uu(K_yes)[i] / uu(K_ref)[i] - 1,
                "matrix err without": norm(K_no - K_ref)[i] / norm(K_ref)[i],
                "matrix err with": norm(K_yes - K_ref)[i] / norm(K_ref)[i],
                "reference error": norm(K_400 - K_ref)[i] / norm(K_ref)[i],
            })
    return pd.DataFrame(rows)


def summary(df):
    """Max absolute errors per case, without / with the chordwise mass."""
    g = df.groupby(["E [GPa]", "tension [N]"])
    return pd.DataFrame({
        "max |K_uu err| without": g["K_uu err without"].apply(lambda s: s.abs().max()),
        "max |K_uu err| with": g["K_uu err with"].apply(lambda s: s.abs().max()),
        "max matrix err without": g["matrix err without"].max(),
        "max matrix err with": g["matrix err with"].max(),
        "max reference error": g["reference error"].max(),
    })


if __name__ == "__main__":
    import matplotlib.pyplot as plt

    df = run()
    pd.set_option("display.width", 160)
    print(summary(df).to_string(float_format=lambda x: f"{x:.2e}"))
    fig, ax = plt.subplots(figsize=(7, 4))
    for (E, T), d in df.groupby(["E [GPa]", "tension [N]"]):
        l, = ax.plot(d["freq [Hz]"], 100 * d["K_uu err without"], ls="--")
        ax.plot(d["freq [Hz]"], 100 * d["K_uu err with"], color=l.get_color(),
                label=f"E={E:g} GPa, T={T:g} N")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("K_uu error vs lumped mass [%]")
    ax.set_title("Chordwise entry: dashed without, solid with the consistent axial mass")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("chordwise_inertia.png", dpi=120)
    print("wrote chordwise_inertia.png")
