"""The main job on a scene (``dynstiff demo``, ``dynstiff report``): statics, modal table with
platform participation, the model the scene needs, design checks, damped FRFs with the modes
marked and a 3-D view of every platform mode, written as CSV tables, PNG figures and one
self-contained ``report.html`` (:mod:`dynstiff.report.document`). Every setting comes from
:func:`dynstiff.analyses.settings.analysis_settings` (the same as ``dynstiff check``).

pandas and matplotlib are imported here, on demand.
"""

from pathlib import Path

import numpy as np

from dynstiff._validate import flag
from dynstiff.constants import PLATFORM_SHARE_THRESHOLD
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
        The printed report: a line ``dynstiff: NAME: DESCRIPTION``, the pose (``pose
        [x, y, z] m, rotation [rx, ry, rz] rad``, rounded to 4 decimals), the settings'
        lines, then four sections, each its title on one line followed by its table and a
        blank line: "Statics (elastic catenaries)" (the equilibrium's table), "First N
        modes, which hold the platform modes (Wittrick-Williams count: none missed; undamped
        frequencies)" (columns mode, freq [Hz], kind, platform mode, platform share [-],
        dominant dof, massless freq [Hz]; the modes the design checks searched, or, where
        they are fewer than the settings' ``n_modes``, that many searched again), "Cable
        model" (the recommendation) and "Design checks" (the checks' verdicts).
    files : list of Path
        Files written. The tables are CSV files (:func:`write_csv`), each
        headed by the run's metadata and the lines ``# table: "<file name>"`` and ``# units:
        "<where the units are>"``: ``statics.csv`` (units "SI, in the column names"),
        ``modes.csv`` (the modes with a fourth column ``platform mode``, True for the
        platform modes the verdicts are about; units "Hz; mode shapes normalised to unit
        platform kinetic energy"), ``checks.csv`` ("as each row's value and limit") and
        ``frf.csv`` ("in each row's unit column": the receptances from the forces fx, fz to
        the displacements x, z, those of them that are free DOFs). Then the figures, PNG:
        ``frf.png`` (the damped FRFs, magnitude and phase, every mode of the band marked) and
        ``mode_shape_K.png`` for each platform mode K (counted from 1); last ``report.html``
        when ``html``.
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from dynstiff.analyses.checks import design_checks
    from dynstiff.analyses.freqgrid import refined_grid
    from dynstiff.analyses.frf import frf
    from dynstiff.analyses.modes import modes as modal
    from dynstiff.analyses.recommend import estimated_error, recommend_model
    from dynstiff.analyses.settings import analysis_settings
    from dynstiff.plot import plot_frf
    from dynstiff.report.html import figure_png
    from dynstiff.report.robot3d import plot_robot

    html = flag("html", html)
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
    err, cause = estimated_error(model, st.band_hz)
    f = refined_grid(st.band_hz, n_points, marks.freq_hz)
    inputs = [c for c in ("fx", "fz") if c[1] in eq.robot.platform.free_dofs]
    outputs = [c[1] for c in inputs]
    response = frf(model, 2 * np.pi * f, inputs=inputs or None, outputs=outputs or None)

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = []
    meta = st.metadata(eq.pose)

    def save_csv(df, name, units):
        text = write_csv(df, None, {**meta, "table": name, "units": units})
        write_text(out / name, text)
        files.append(out / name)
        return text

    statics = eq.to_frame()
    save_csv(statics, "statics.csv", "SI, in the column names")
    table = modes.to_frame()
    table.insert(3, "platform mode", np.isin(np.arange(len(modes)), pm.index))
    modes_csv = save_csv(table, "modes.csv",
                         "Hz; mode shapes normalised to unit platform kinetic energy")
    save_csv(checks.to_frame(), "checks.csv", "as each row's value and limit")
    save_csv(response.to_frame(), "frf.csv", "in each row's unit column")
    figs = [(plot_frf(response, marks, phase=True), "frf.png",
             "Damped platform FRFs (magnitude and phase) with every mode of the band marked "
             "by class")]
    dsm = model if model.rung == "dsm" else None
    for k in pm.index:
        figs.append((plot_robot(eq, modes, int(k), model=dsm), f"mode_shape_{k + 1}.png",
                     f"Platform mode {k + 1}: {pm.describe(int(k))}"))
    pngs = []
    for n, (fig, name, caption) in enumerate(figs):
        # drawn once, for the file and the page; the mode shapes, shown side by side, at a
        # lower resolution
        png = figure_png(fig, dpi=110 if n == 0 else 90)
        with atomic_path(out / name) as tmp, open(tmp, "wb") as fh:
            fh.write(png)
        pngs.append((png, caption))
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
        page = _page(scene, eq, st, checks, pm, rec, (err, cause), statics, pngs, modes_csv,
                     len(modes), len(f))
        write_text(out / "report.html", page)
        files.append(out / "report.html")
    return text + "\n", files


def _page(scene, eq, st, checks, pm, rec, error, statics, pngs, modes_csv, n_modes, n_freq):
    """The HTML page (:mod:`dynstiff.report.document`).

    Below the title block, one paragraph ``Summary: V; F; cable model R with estimated error
    E up to B Hz.``: V is "all checks passed" or, when a check did not pass, "some checks
    FAILED"; F is "N platform mode(s), the first at F1 Hz" (or "the platform modes not all
    found" when the search is incomplete), followed, when a mode below the first platform
    mode holds at least the checks' ``participation`` share of its energy in the platform
    (share = 1 - cable energy fraction), by " (the lowest mode the platform moves in, with a
    share of S%, is mode K at FK Hz)" for the lowest such mode (K counted from 1). Then the
    sections, each an ``h2`` heading, in this order: "Inputs", "Design checks", "Platform
    modes", "Frequency response", "Cable model", "Assumptions", "Statics", "Downloads".
    "Platform modes" opens with the paragraph "The modes every modal verdict is about
    (theory.md §12.4): the mode that moves each free DOF most and every global mode below the
    frequency by which every free DOF has half of its participation (FOUND Hz); undamped
    frequencies." (FOUND: ``pm.found_hz``; the parenthesis left out when the search is
    incomplete, which a note then says with its reason).
    """
    from dynstiff.report.document import (
        cable_frame,
        input_rows,
        platform_mode_table,
        spread_note,
        title_rows,
    )
    from dynstiff.report.html import html_page
    err, cause = error
    verdict = "all checks passed" if checks.passed else "some checks FAILED"
    found = (f"{pm.index.size} platform mode(s), the first at {pm.first_hz:.4g} Hz"
             if pm.complete else "the platform modes not all found")
    share = 1.0 - np.asarray(pm.modes.cable_energy_fraction)
    held = np.flatnonzero(share >= st.check_options().get("participation",
                                                         PLATFORM_SHARE_THRESHOLD))
    if held.size and pm.complete and pm.modes.freq_hz[held[0]] < pm.first_hz:
        k = int(held[0])            # a mode below the first platform mode moves the platform
        found += (f" (the lowest mode the platform moves in, with a share of "
                  f"{share[k]:.0%}, is mode {k + 1} at {pm.modes.freq_hz[k]:.4g} Hz)")
    blocks = [("kv", title_rows(scene)), ("p", f"Summary: {verdict}; {found}; cable "
              f"model {st.rung} with estimated error {err:.2g} up to "
              f"{st.band_hz[1]:g} Hz."),
              ("h2", "Inputs"), ("kv", input_rows(eq, st)), ("table", cable_frame(eq)),
              ("h2", "Design checks"), ("checks", checks.rows),
              ("h2", "Platform modes"),
              ("p", "The modes every modal verdict is about (theory.md §12.4): the mode "
                    "that moves each free DOF most and every global mode below the "
                    "frequency by which every free DOF has half of its participation"
                    + (f" ({pm.found_hz:.4g} Hz)" if pm.complete else "")
                    + "; undamped frequencies.")]
    note = spread_note(pm)
    if note:
        blocks.append(("note", note))
    if not pm.complete:
        blocks.append(("note", f"The search for the platform modes is incomplete: {pm.reason}"))
    blocks += [("table", platform_mode_table(pm))]
    blocks += [("pngs", pngs[1:])]
    blocks += [("h2", "Frequency response"), ("png", pngs[0]),
               ("h2", "Cable model"),
               ("p", f"The analysis uses the {st.rung} model: estimated relative frequency "
                     f"error {err:.2g} up to {st.band_hz[1]:g} Hz ({cause}; theory.md "
                     f"§12.5), admissible {st.model_rtol:g}. Recommended for this band: "
                     f"{rec.rung}" + (f" with {rec.segments} segments" if rec.segments else "")
                     + f" (predicted error {rec.predicted_error:.2g})."),
               ("table", rec.to_frame()),
               ("h2", "Assumptions"),
               ("ul", [st.damping.text(),
                       f"band of interest {st.band_hz[0]:g}-{st.band_hz[1]:g} Hz: FRFs on "
                       f"{n_freq} frequencies, refined around every mode of the band",
                       "forbidden band " + (f"{st.forbidden_hz[0]:g}-{st.forbidden_hz[1]:g}"
                                            " Hz" if st.forbidden_hz else "none given: "
                                            "its two checks are not asked"),
                       "linear vibration about the static equilibrium (elastic catenaries); "
                       "natural frequencies undamped, every mode below the highest listed "
                       "found (Wittrick-Williams count)",
                       "mode shapes normalised to unit platform kinetic energy; figures "
                       "exaggerate the displacements"]),
               ("h2", "Statics"), ("table", statics),
               ("h2", "Downloads"),
               ("download", ("modes.csv", modes_csv.encode("utf-8"), "text/csv",
                             f"All {n_modes} modes computed (modes.csv: frequencies, kinds, "
                             "participations, platform shapes; also written beside this "
                             "page)"))]
    return html_page(f"dynstiff report: {scene.name}", blocks)
