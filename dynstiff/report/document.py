"""The report page as a document a designer can sign: a title block (scene, dynstiff
version, date, input file and its SHA-256), the inputs, the design checks with their
verdicts and reasons, the platform modes (theory.md §12.4) and their shapes, the FRFs, the
cable model with its estimated error (theory.md §12.5), what was assumed, and the full modes
table to download. The blocks are those of :func:`dynstiff.report.html.html_page`.
"""

import datetime
import hashlib
from pathlib import Path

import numpy as np

__all__ = ["cable_frame", "input_rows", "platform_mode_table", "spread_note", "title_rows"]


def title_rows(scene, when=None):
    """(key, value) rows of the title block, in this order:

    - ``("scene", scene.name)``;
    - ``("description", scene.description)``, ``""`` for a scene without one;
    - ``("dynstiff version", dynstiff.__version__)``;
    - ``("date", "YYYY-MM-DD HH:MM:SS UTC")``: ``when`` (a UTC datetime, default now);
    - for a scene read from a file (``scene.path`` an existing file):
      ``("input file", str(scene.path))`` then ``("input file SHA-256", h)``, ``h`` the
      lower-case hexadecimal SHA-256 of the file's bytes; otherwise (a scene built in
      memory) the one row ``("input file", "none (scene built in memory)")``.
    """
    from dynstiff._version import __version__
    when = when or datetime.datetime.now(datetime.UTC)
    path = getattr(scene, "path", None)
    if path is not None and Path(path).is_file():
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
        source = [("input file", str(path)), ("input file SHA-256", digest)]
    else:
        source = [("input file", "none (scene built in memory)")]
    return [("scene", scene.name), ("description", scene.description or ""),
            ("dynstiff version", __version__),
            ("date", when.strftime("%Y-%m-%d %H:%M:%S UTC")), *source]


def _vec(v, nd=4):
    return "(" + ", ".join(f"{x:.{nd}g}" for x in np.ravel(v)) + ")"


def input_rows(eq, settings):
    """(key, value) rows of the robot and the analysis, in this order. A vector is written
    ``"(x, y, z)"``, its components to 4 significant digits (``:.4g``) unless said.

    - ``"platform mass [kg]"``: 6 significant digits;
    - ``"centre of mass, platform frame [m]"``: vector;
    - ``"inertia about G, platform axes [kg m^2]"``: the three rows of the tensor, each a
      vector to 5 significant digits, joined by ``"; "``;
    - ``"free DOFs"``: their names joined by ``", "`` (e.g. ``"x, y, z"``);
    - ``"pose: position of P [m]"``, ``"pose: rotation vector [rad]"``: vectors;
    - ``"gravity [m/s^2]"``: 6 significant digits;
    - ``"tension limits [N]"``: ``"t_min to t_max"`` (``:g``);
    - ``"cable model"``: the rung, for ``"lumped"`` followed by ``", N segments per
      cable"``, then ``", admissible frequency error E"`` (``:g``);
    - ``"band of interest [Hz]"``: ``"f0-f1"`` (``:g``);
    - ``"forbidden band"``: ``"f0-f1 Hz, margin M%, modes with platform share >= P%,
      receptance <= L x static"`` (frequencies and L ``:g``, percentages rounded), or
      ``"none (not checked)"`` when the settings give none;
    - ``"damping"``: :meth:`dynstiff.Damping.text` without its ``"damping: "`` prefix.
    """
    rob = eq.robot
    p = rob.platform
    t_min, t_max = rob.tension_limits
    st = settings
    fb = (f"{st.forbidden_hz[0]:g}-{st.forbidden_hz[1]:g} Hz, margin {st.margin:.0%}, "
          f"modes with platform share >= {st.participation:.0%}, receptance <= "
          f"{st.frf_limit:g} x static" if st.forbidden_hz else "none (not checked)")
    return [
        ("platform mass [kg]", f"{p.mass:.6g}"),
        ("centre of mass, platform frame [m]", _vec(p.center_of_mass)),
        ("inertia about G, platform axes [kg m^2]",
         "; ".join(_vec(r, 5) for r in np.asarray(p.inertia))),
        ("free DOFs", ", ".join(p.free_dofs)),
        ("pose: position of P [m]", _vec(eq.pose.position)),
        ("pose: rotation vector [rad]", _vec(eq.pose.rotation)),
        ("gravity [m/s^2]", f"{rob.g:.6g}"),
        ("tension limits [N]", f"{t_min:g} to {t_max:g}"),
        ("cable model", f"{st.rung}" + (f", {st.segments} segments per cable"
                                        if st.rung == "lumped" else "")
         + f", admissible frequency error {st.model_rtol:g}"),
        ("band of interest [Hz]", f"{st.band_hz[0]:g}-{st.band_hz[1]:g}"),
        ("forbidden band", fb),
        ("damping", st.damping.text().removeprefix("damping: ")),
    ]


def cable_frame(eq):
    """pandas DataFrame, one row per cable in the robot's order, with the columns
    ``"cable"`` (its index, from 0), ``"anchor A [m]"`` and ``"attachment b [m]"`` (each
    ``"(x, y, z)"``, 4 significant digits), ``"mass per length [kg/m]"``, ``"EA [N]"``,
    ``"loss factor [-]"`` and ``"viscous damping [N s/m^2]"`` (the cable's numbers)."""
    import pandas as pd
    rob = eq.robot
    return pd.DataFrame({
        "cable": np.arange(rob.n_cables),
        "anchor A [m]": [_vec(a) for a in rob.anchors],
        "attachment b [m]": [_vec(b) for b in rob.attachments],
        "mass per length [kg/m]": [c.mass_per_length for c in rob.cables],
        "EA [N]": [c.EA for c in rob.cables],
        "loss factor [-]": [c.loss_factor for c in rob.cables],
        "viscous damping [N s/m^2]": [c.viscous_damping for c in rob.cables],
    })


def platform_mode_table(pm):
    """pandas DataFrame of the platform modes of ``pm`` (PlatformModes), one row per mode
    of ``pm.index``, with the columns ``"mode"`` (its number, from 1), ``"freq [Hz]"``,
    ``"kind"``, ``"platform share [-]"``, ``"dominant dof"``, ``"carries"`` (the DOFs whose
    largest participation it holds, joined by ``", "``; ``"-"`` for none) and ``"massless
    freq [Hz]"`` (the massless-cable frequency it continues). The same columns, no row,
    when the search found no mode."""
    import pandas as pd
    m = pm.modes
    if m is None or not pm.index.size:
        return pd.DataFrame(columns=["mode", "freq [Hz]", "kind", "platform share [-]",
                                     "dominant dof", "carries", "massless freq [Hz]"])
    carries = {k: [d for d, j in pm.carriers.items() if j == k] for k in pm.index}
    return pd.DataFrame({
        "mode": [int(k) + 1 for k in pm.index],
        "freq [Hz]": np.asarray(m.freq_hz)[pm.index],
        "kind": [m.kind[k] for k in pm.index],
        "platform share [-]": m.platform_share[pm.index],
        "dominant dof": [m.dominant_dof[k] for k in pm.index],
        "carries": [", ".join(carries[k]) or "-" for k in pm.index],
        "massless freq [Hz]": np.asarray(m.massless_freq_hz)[pm.index],
    })


def spread_note(pm):
    """A sentence when no computed mode has more than half its kinetic energy in the
    platform (the platform's motion spread over many cable-dominated modes), else "":
    "No mode below F Hz has more than half of its kinetic energy in the platform (largest
    share S%): the platform's motion is spread over many cable-dominated modes. Each DOF
    (D) is listed with the mode that moves it most; the FRFs show the spread.", F
    ``pm.searched_hz`` to 4 significant digits, S the largest platform share (0 % without
    modes), D the DOFs of ``pm.carriers`` joined by ", " (or "the free DOFs")."""
    if pm.modes is None:
        return ""
    share = pm.modes.platform_share
    if share.size and share.max() > 0.5:
        return ""
    free = ", ".join(pm.carriers) or "the free DOFs"
    return (f"No mode below {pm.searched_hz:.4g} Hz has more than half of its kinetic energy "
            f"in the platform (largest share {share.max(initial=0):.0%}): the platform's "
            f"motion is spread over many cable-dominated modes. Each DOF ({free}) is "
            f"listed with the mode that moves it most; the FRFs show the spread.")
