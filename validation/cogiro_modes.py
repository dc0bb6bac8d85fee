"""CoGiRo at its central pose: first 40 eigenfrequencies, global/local labels, kinetic-energy
fractions, shift from the massless-cable model, and FRFs (built-in scene ``cogiro``).

No published CoGiRo eigenfrequency could be confirmed (theory.md §8.2), so this study checks
the model against itself and against independent limits:
* the 6 global modes continue the massless-cable model (their shift from it is reported);
* the count of modes from Wittrick-Williams equals the number of roots found (none missed);
* the statics round trip (inverse then forward statics) returns the pose.

Across the workspace (:func:`poses_and_moduli`): at several poses and for E = 17 and 120 GPa
(the range the CoGiRo description gives), the first 20 frequencies of the closed-form model
against the independent lumped-mass model (N = 20 and 40 segments per cable,
Richardson-extrapolated), with the global/local labels and the local-global proximity
warnings; and (:func:`veering`) the global modes tracked along a path from the centre to a
corner of the workspace, the veering diagram.

Run ``python validation/cogiro_modes.py`` for the tables, ``cogiro_frf.png`` and
``cogiro_veering.png``.
"""

import numpy as np
import pandas as pd

import dynstiff as ds

POSES = ([0.0, 0.0, 1.0], [2.0, 1.0, 1.5], [-3.0, -2.0, 2.0], [4.0, -3.0, 1.0])
PATH = ([0.0, 0.0, 1.0], [5.0, 3.0, 1.0])            # veering path of P [m]


def robot_with_E(E):
    """CoGiRo with Young's modulus E [Pa] (area 8.2051e-6 m^2)."""
    r = ds.load_scene("cogiro").robot
    return ds.Robot(r.anchors, r.attachments, ds.Cable(0.064, 8.2051e-6 * E), r.platform,
                    tension_limits=r.tension_limits, name=f"cogiro E={E / 1e9:g} GPa")


def poses_and_moduli(quick=False, n_modes=20):
    """Closed-form model against the lumped-mass model across poses and E.

    Returns
    -------
    pandas.DataFrame
        One row per (E, pose): the first global frequencies [Hz], the largest relative
        difference to the lumped reference over all ``n_modes`` and over the global modes,
        the number of global modes, of proximity warnings (local within 3 % of global), the
        lowest clamped-cable frequency [Hz].
    """
    rows = []
    poses = POSES[:2] if quick else POSES
    for E in (17e9, 120e9):
        rob = robot_with_E(E)
        for p in poses:
            eq = rob.equilibrium(pose=p)
            modes = ds.modes(ds.FrequencyModel(eq), n_modes)
            fa = ds.build_model(eq, "lumped", segments=20)
            fb = ds.build_model(eq, "lumped", segments=40)
            a, b = ds.eigenfrequencies(fa, n_modes), ds.eigenfrequencies(fb, n_modes)
            ref = b + (b - a) / 3.0                      # O(1/N^2) Richardson
            err = np.abs(modes.freq_hz / ref - 1)
            glob = np.array(modes.kind) == "global"
            rows.append({
                "E [GPa]": E / 1e9, "pose [m]": str(p),
                "global freqs [Hz]": np.round(modes.freq_hz[glob], 4).tolist(),
                "n global": int(glob.sum()),
                "max rel. diff. to lumped, all [-]": float(err.max()),
                "max rel. diff. to lumped, global [-]": float(err[glob].max()) if glob.any()
                else np.nan,
                "lumped N=40 vs ref [-]": float(np.max(np.abs(b / ref - 1))),
                "proximity warnings": len(ds.proximity_warnings(modes, rtol=0.03)),
                "lowest cable mode [Hz]": float(min(
                    ds.cable_natural_frequencies(s, 1).freq_hz[0] for s in eq.states)),
            })
    return pd.DataFrame(rows)


def veering(steps=11, n_modes=24, E=17e9):
    """Global modes tracked along ``PATH`` (:func:`dynstiff.sweep`).

    Returns
    -------
    SweepResult
    """
    poses = np.linspace(PATH[0], PATH[1], steps)
    return ds.sweep(robot_with_E(E), poses=poses, n_modes=n_modes)


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
    rob = scene.robot if E == 17e9 else robot_with_E(E)
    eq = rob.equilibrium(pose=scene.pose)
    fwd = rob.equilibrium(unstretched_lengths=eq.unstretched_lengths)
    model = ds.FrequencyModel(eq)
    modes = ds.modes(model, n_modes)
    df = modes.to_frame()
    df.insert(2, "W-W count above", ds.mode_count(model, 2 * np.pi * modes.freq_hz * (1 + 1e-9)))
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
    model = ds.scene_model(scene)                # the scene's [damping]: finite peaks
    modes = ds.modes(model, 40)
    res = ds.frf(model, 2 * np.pi * np.linspace(0.5, 10.0, 20000), inputs=["fx", "fy", "fz", "mz"],
                    outputs=["x", "y", "z", "rz"])
    fig = plot_frf(res, modes)
    fig.tight_layout()
    fig.savefig("cogiro_frf.png", dpi=120)
    print("wrote cogiro_frf.png")
    print(poses_and_moduli().to_string(index=False))
    from dynstiff.plot import plot_veering
    sw = veering()
    print(sw.veering_table().to_string())
    fig = plot_veering(sw)
    fig.tight_layout()
    fig.savefig("cogiro_veering.png", dpi=120)
    print("wrote cogiro_veering.png")
