"""The main job on a scene (``dynstiff demo``): statics, complete modal table, the model the
scene needs, design checks, FRFs with the modes marked and a 3-D view of the first global
mode, written as CSV tables and PNG figures.

pandas and matplotlib are imported here, on demand.
"""

from pathlib import Path

import numpy as np

__all__ = ["robot_report"]


def robot_report(scene, out, n_modes=None, band_hz=None, forbidden_hz=None,
                 n_points=3000):
    """Run the main analysis of ``scene`` and write its tables and figures into ``out``.

    Parameters
    ----------
    scene : Scene
        From :func:`dynstiff.load_scene`.
    out : str or Path
        Output folder (created).
    n_modes : int, optional
        Modes in the table (default: the scene's ``n_modes`` or 20).
    band_hz : (float, float), optional
        Band of the FRFs, the checks and the model recommendation [Hz] (default: the
        scene's band or 0.1-12 Hz).
    forbidden_hz : (float, float), optional
        Band no global mode may enter (design check) [Hz]; default the scene's
        ``forbidden_band_hz``, else below 1.5 Hz.
    n_points : int
        Frequencies of the FRFs.

    Returns
    -------
    text : str
        The printed report.
    files : list of Path
        Files written.
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .assembly import FrequencyModel
    from .checks import design_checks
    from .eigen import modes as modal
    from .frf import frf
    from .plot import plot_frf
    from .plot3d import plot_robot
    from .recommend import recommend_model

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    n_modes = n_modes or scene.n_modes or 20
    band = tuple(band_hz or scene.band_hz or (0.1, 12.0))
    forbidden_hz = tuple(forbidden_hz or scene.forbidden_band_hz or (0.0, 1.5))
    eq = scene.equilibrium()
    model = FrequencyModel(eq)
    modes = modal(model, n_modes=n_modes)
    files = []

    def save_csv(df, name):
        df.to_csv(out / name, index=False)
        files.append(out / name)

    statics = eq.to_frame()
    save_csv(statics, "statics.csv")
    table = modes.to_frame()
    save_csv(table, "modes.csv")
    checks = design_checks(scene.robot, eq.pose, band_hz=tuple(forbidden_hz))
    save_csv(checks.to_frame(), "checks.csv")
    rec = recommend_model(eq, band_hz=band, rtol=1e-2)

    f = np.linspace(band[0], band[1], n_points)
    inputs = [c for c in ("fx", "fz") if c[1] in eq.robot.platform.free_dofs]
    outputs = [c[1] for c in inputs]
    response = frf(model, 2 * np.pi * f, inputs=inputs or None, outputs=outputs or None)
    save_csv(response.to_frame(), "frf.csv")
    # mark every mode of the FRF band, also those beyond the table's n_modes
    marks = modes if modes.freq_hz[-1] >= band[1] else modal(model, fmax_hz=band[1])
    fig = plot_frf(response, marks, phase=True)
    fig.savefig(out / "frf.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    files.append(out / "frf.png")
    glob = [k for k, kind in enumerate(modes.kind) if kind == "global"]
    if glob:
        fig = plot_robot(eq, modes, glob[0], model=model)
        fig.savefig(out / "mode_shape.png", dpi=120, bbox_inches="tight")
        plt.close(fig)
        files.append(out / "mode_shape.png")

    fmt = {"float_format": lambda x: f"{x:.5g}", "index": False}
    cols = ["mode", "freq [Hz]", "kind", "cable energy fraction [-]", "massless freq [Hz]"]
    text = "\n".join([
        f"dynstiff: {scene.name}: {scene.description}",
        f"pose {np.round(eq.pose.position, 4).tolist()} m, rotation "
        f"{np.round(eq.pose.rotation, 4).tolist()} rad",
        "",
        "Statics (elastic catenaries)",
        statics.to_string(**fmt),
        "",
        f"First {len(modes)} modes (Wittrick-Williams count: none missed)",
        table[cols].to_string(**fmt),
        "",
        rec.text(),
        "",
        f"Design checks (forbidden band for global modes {forbidden_hz[0]:g}-"
        f"{forbidden_hz[1]:g} Hz)",
        checks.text(),
    ])
    return text + "\n", files
