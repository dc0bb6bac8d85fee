"""CoGiRo at its central pose: first 40 eigenfrequencies, global/local labels, kinetic-energy
fractions, shift from the massless-cable model, and FRFs (built-in scene ``cogiro``).

No published CoGiRo eigenfrequency could be confirmed (theory.md §8.2), so this study checks
the model against itself and against independent limits:
* the 6 global modes continue the massless-cable model (their shift from it is reported);
* the count of modes from Wittrick-Williams equals the number of roots found (none missed);
* the statics round trip (inverse then forward statics) returns the pose.

Run ``python validation/cogiro_modes.py`` for the table and ``cogiro_frf.png``.
"""

import numpy as np
import pandas as pd

import dynstiff as ds


def run(E=17e9, n_modes=40):
    """Modal table of CoGiRo at the central pose.

    Parameters
    ----------
    E : float
        Young's modulus [Pa] (the source gives 17-120 GPa).
    n_modes : int

    Returns
    -------
    pandas.DataFrame
        One row per mode (see :meth:`ModalResult.to_frame`) plus the W-W count just above
        each frequency and the round-trip pose error of the statics [m] (same in every row).
    """
    scene = ds.load_scene("cogiro")
    rob = scene.robot
    if E != 17e9:
        rob = ds.Robot(rob.anchors, rob.attachments, ds.Cable(0.064, 8.2051e-6 * E),
                       rob.platform, tension_limits=rob.tension_limits, name=rob.name)
    eq = rob.equilibrium(pose=scene.pose)
    fwd = rob.equilibrium(unstretched_lengths=eq.unstretched_lengths)
    model = ds.FrequencyModel(eq)
    modes = model.modes(n_modes)
    df = modes.to_frame()
    df.insert(2, "W-W count above", model.mode_count(2 * np.pi * modes.freq_hz * (1 + 1e-9)))
    df["statics round trip [m]"] = np.linalg.norm(fwd.pose.position - scene.pose.position)
    df["E [GPa]"] = E / 1e9
    return df


if __name__ == "__main__":
    import matplotlib
    matplotlib.use("Agg")
    from dynstiff.plot import plot_frf

    pd.set_option("display.width", 200)
    for E in (17e9, 120e9):
        df = run(E)
        print(f"\nE = {E / 1e9:g} GPa")
        print(df[["mode", "freq [Hz]", "kind", "cable energy fraction [-]",
                  "massless freq [Hz]", "shift from massless [-]"]].to_string(index=False))
    scene = ds.load_scene("cogiro")
    model = ds.FrequencyModel(scene.equilibrium())
    modes = model.modes(40)
    res = model.frf(2 * np.pi * np.linspace(0.5, 10.0, 20000), inputs=["fx", "fy", "fz", "mz"],
                    outputs=["x", "y", "z", "rz"])
    fig = plot_frf(res, modes)
    fig.tight_layout()
    fig.savefig("cogiro_frf.png", dpi=120)
    print("wrote cogiro_frf.png")
