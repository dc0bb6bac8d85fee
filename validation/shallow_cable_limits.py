"""Where the shallow-cable closed form breaks: fixed-end natural frequencies of one cable from
the closed-form theory (Irvine-Caughey, inclined-cable approximation, theory.md §2.3) against
an independent lumped-mass chain (N = 100 and 200, Richardson-extrapolated), as the sag/chord
ratio and the inclination grow.

The closed form neglects the weight component along the chord, so on steep heavy cables the
tension varies along the cable and the symmetric/antisymmetric families mix (Triantafyllou
1984); near the lambda^2 = 4 pi^2 crossover this is strongest.

Run ``python validation/shallow_cable_limits.py`` for the table.
"""

import numpy as np
import pandas as pd

import dynstiff as ds
from dynstiff.cable.dsm import chord_parameters
from dynstiff.lumped import chain_equilibrium, chain_fixed_end_frequencies

SPAN = 10.0


def case(sag_ratio, inclination_deg, E=17e9, n_modes=4, segments=(100, 200)):
    """One cable of chord 10 m at the given inclination, tension set for the wanted mid-span
    sag / chord (parabolic estimate); closed-form and extrapolated lumped frequencies."""
    th = np.radians(inclination_deg)
    A = np.zeros(3)
    B = SPAN * np.array([np.cos(th), 0.0, -np.sin(th)])
    cable = ds.Cable(0.064, 8.2051e-6 * E)
    g = ds.STANDARD_GRAVITY
    T = cable.mass_per_length * g * np.cos(th) * SPAN / (8 * sag_ratio)
    s = ds.unstretched_length_for_tension(A, B, T, cable, at="end")
    closed = ds.cable_natural_frequencies(s, n_modes, guard_rtol=None)   # its error is measured
    fs = []
    for N in segments:
        ch = chain_equilibrium(A, B, s.unstretched_length, cable, N)
        fs.append(chain_fixed_end_frequencies(ch, n_modes))
    r = (segments[1] / segments[0]) ** 2
    ref = fs[1] + (fs[1] - fs[0]) / (r - 1)
    p = chord_parameters(s)
    return [{"sag/chord": sag_ratio, "inclination [deg]": inclination_deg,
             "lambda^2": p.lambda_sq, "W sin(theta)/T": s.total_weight * np.sin(th) / p.T,
             "mode": k + 1, "label": closed.labels[k], "closed [Hz]": closed.freq_hz[k],
             "lumped [Hz]": ref[k], "rel error": closed.freq_hz[k] / ref[k] - 1}
            for k in range(n_modes)]


def run(quick=False):
    """Table over sag/chord in [0.002, 0.05] and inclinations 0-80 deg.

    Returns
    -------
    pandas.DataFrame
    """
    sags = (0.005, 0.03) if quick else (0.002, 0.005, 0.01, 0.02, 0.03, 0.05)
    incl = (0, 60) if quick else (0, 30, 60, 80)
    rows = []
    for d in sags:
        for a in incl:
            rows += case(d, a)
    return pd.DataFrame(rows)


if __name__ == "__main__":
    pd.set_option("display.width", 200)
    df = run()
    print(df.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    piv = df.groupby(["sag/chord", "inclination [deg]"])["rel error"].apply(
        lambda s: s.abs().max()).unstack()
    print("\nmax |relative error| of the first 4 fixed-end frequencies")
    print(piv.to_string(float_format=lambda x: f"{x:.2e}"))
