"""The main job on a scene (``dynstiff demo``, ``dynstiff report``): statics, modal table with
platform participation, the model the scene needs, design checks, damped FRFs with the modes
marked and a 3-D view of the first platform mode, written as CSV tables, PNG figures and one
self-contained ``report.html``. Every setting comes from
:func:`dynstiff.analyses.settings.analysis_settings` (the same as ``dynstiff check``).

pandas and matplotlib are imported here, on demand.
"""

from pathlib import Path

import numpy as np

from dynstiff.io.files import atomic_path, write_text

__all__ = ["robot_report", "write_csv"]


def write_csv(df, path, metadata):
    """Write ``df`` as CSV to ``path`` (or return the text when ``path`` is None) under a
    header of ``# key: value`` lines (read back with ``pandas.read_csv(path,
    comment="#")``)."""
    import json
    head = "".join(f"# {k}: {json.dumps(v)}\n" for k, v in metadata.items())
    text = head + df.to_csv(index=False)
    if path is None:
        return text
    write_text(path, text)
    return None


def robot_report(scene, out, settings=None, n_points=3000, html=True):
    """Run the main analysis of ``scene`` and write its tables and figures into ``out``.

    Parameters
    ----------
    scene : Scene
        From :func:`dynstiff.load_scene`.
    out : str or Path
        Output folder (created).
    settings : AnalysisSettings, optional
        Default: :func:`dynstiff.analyses.settings.analysis_settings` of the scene.
    n_points : int
        Uniform frequencies of the FRFs (refined around every mode in the band).
    html : bool
        Also write ``report.html``.

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

    from dynstiff.analyses.checks import design_checks
    from dynstiff.analyses.freqgrid import refined_grid
    from dynstiff.analyses.frf import frf
    from dynstiff.analyses.modes import modes as modal
    from dynstiff.analyses.recommend import recommend_model
    from dynstiff.analyses.settings import analysis_settings
    from dynstiff.plot import plot_frf
    from dynstiff.report.html import figure_png, html_page
    from dynstiff.report.robot3d import plot_robot

    st = settings or analysis_settings(scene)
    eq = scene.equilibrium()              # statics first: an infeasible scene writes nothing
    model = st.model(eq)
    checks = design_checks(scene.robot, eq.pose, **st.check_options())
    pm = checks.platform                 # the modes the verdicts were taken from
    modes = pm.modes
    if modes is None or len(modes) < st.n_modes:     # at least the scene's number of modes
        modes = modal(model, n_modes=min(st.n_modes, getattr(model, "n_dof", st.n_modes)))
    marks = modal(model, fmax_hz=st.band_hz[1])
    rec = recommend_model(eq, band_hz=st.band_hz, rtol=st.model_rtol)
    f = refined_grid(st.band_hz, n_points, marks.freq_hz)
    inputs = [c for c in ("fx", "fz") if c[1] in eq.robot.platform.free_dofs]
    outputs = [c[1] for c in inputs]
    response = frf(model, 2 * np.pi * f, inputs=inputs or None, outputs=outputs or None)

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = []
    meta = st.metadata(eq.pose)

    def save_csv(df, name, units):
        write_csv(df, out / name, {**meta, "table": name, "units": units})
        files.append(out / name)

    statics = eq.to_frame()
    save_csv(statics, "statics.csv", "SI, in the column names")
    table = modes.to_frame()
    table.insert(3, "platform mode", np.isin(np.arange(len(modes)), pm.index))
    save_csv(table, "modes.csv", "Hz; mode shapes normalised to unit platform kinetic energy")
    save_csv(checks.to_frame(), "checks.csv", "as each row's value and limit")
    save_csv(response.to_frame(), "frf.csv", "in each row's unit column")
    figs = []
    fig = plot_frf(response, marks, phase=True)
    figs.append((fig, "frf.png", "Damped platform FRFs with the modes marked"))
    kk = list(pm.index)
    if kk:
        fig = plot_robot(eq, modes, kk[0], model=model if model.rung == "dsm" else None)
        figs.append((fig, "mode_shape.png", f"Mode {kk[0] + 1} (first platform mode, "
                                            f"{modes.kind[kk[0]]}, "
                                            f"{modes.freq_hz[kk[0]]:.4g} Hz)"))
    pngs = []
    for fig, name, caption in figs:
        with atomic_path(out / name) as tmp:
            fig.savefig(tmp, dpi=120, bbox_inches="tight")
        pngs.append((figure_png(fig), caption))
        plt.close(fig)
        files.append(out / name)

    fmt = {"float_format": lambda x: f"{x:.5g}", "index": False}
    cols = ["mode", "freq [Hz]", "kind", "platform mode", "platform share [-]", "dominant dof",
            "massless freq [Hz]"]
    head = [f"dynstiff: {scene.name}: {scene.description}",
            f"pose {np.round(eq.pose.position, 4).tolist()} m, rotation "
            f"{np.round(eq.pose.rotation, 4).tolist()} rad", *st.lines()]
    sections = [
        ("Statics (elastic catenaries)", statics.to_string(**fmt)),
        (f"First {len(modes)} modes, which hold the platform modes (Wittrick-Williams count: "
         f"none missed; undamped frequencies)",
         table[cols].to_string(**fmt)),
        ("Cable model", rec.text()),
        ("Design checks", checks.text()),
    ]
    text = "\n".join(head + [""] + [f"{t}\n{b}\n" for t, b in sections])
    if html:
        blocks = [("pre", "\n".join(head)), ("h2", "Design checks"),
                  ("checks", checks.rows), ("h2", "Cable model"), ("pre", rec.text()),
                  ("h2", "Statics"), ("table", statics), ("h2", "Modes"),
                  ("table", table[cols + [c for c in table.columns
                                         if c.startswith(("x", "y", "z", "r"))]]),
                  ("h2", "Figures")] + [("png", p) for p in pngs]
        write_text(out / "report.html", html_page(f"dynstiff report: {scene.name}", blocks))
        files.append(out / "report.html")
    return text + "\n", files
