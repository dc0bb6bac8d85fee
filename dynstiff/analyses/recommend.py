"""Model selection: the cheapest rung of the model ladder expected to meet a tolerance.

"Model no more than a scene needs": from cheap estimates (cable fixed-end frequencies
against the band, sag ratio, along-chord weight, a first-order perturbation of the
massless-cable modes by the cables' real dynamic stiffness) predict the frequency error of
each rung of :mod:`dynstiff.models.ladder` in the band, and return the cheapest one whose
prediction meets ``rtol``.

Error estimates (relative frequency error, all modes in the band)
-----------------------------------------------------------------
* "spring" / "catenary" have no cable modes: if any clamped-cable frequency lies below the
  band's top they miss modes (error inf). Otherwise the "catenary" error is the first-order
  shift of each massless mode x at omega by the cables' inertia,
  |x^T (K_dsm(omega) - K_cat) x| / (2 omega^2 x^T M x), with K_dsm the closed-form
  robot dynamic stiffness; "spring" adds its measured gap to "catenary" (the sag effect).
* "dsm": measured against the exact rung in the band (theory.md §11.5; the exact rung costs
  a few times the closed form); inf when a cable is slack or its axial modes reach the band
  (the closed form has none, :func:`dynstiff.cable.guard.closed_form_validity`).
* "exact": 1e-8, the rounding floor of its discretisation (theory.md §11.2).
* "lumped": the beaded-string error (n pi / N)^2 / 24 of the highest cable harmonic n in the
  band (theory.md §7.2), with N chosen so that it stays below rtol / 2.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import band
from dynstiff.analyses.eigen import eigenfrequencies
from dynstiff.cable.dsm import chord_parameters
from dynstiff.cable.guard import ROBOT_ERROR_FACTOR, closed_form_validity
from dynstiff.cable.psi import cable_mode_count
from dynstiff.errors import ClosedFormWarning, InvalidParameterError
from dynstiff.models.base import require_equilibrium
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.ladder import RUNGS
from dynstiff.models.static import StaticCableModel

if TYPE_CHECKING:

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from dynstiff.models.base import PlatformModel
    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["Recommendation", "estimated_error", "recommend_model", "predicted_errors"]

_COST_ORDER = {r: i for i, r in enumerate(RUNGS)}
#: Relative frequency error of the "exact" rung in its band: the rounding floor of its
#: discretisation, measured 1e-9 against Richardson-extrapolated lumped chains (theory.md §11.2).
EXACT_ERROR = 1e-8


@dataclass(frozen=True)
class Recommendation:
    """Cheapest adequate model.

    Attributes
    ----------
    rung : str
        One of :data:`dynstiff.models.ladder.RUNGS`.
    segments : int or None
        Segments per cable when ``rung == "lumped"``.
    predicted_error : float
        Predicted relative frequency error of that rung in the band [-].
    errors : dict
        Predicted error of every rung [-] (inf: misses modes).
    estimates : dict
        The quantities the choice relied on.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> rec = ds.recommend_model(eq, band_hz=(0.0, 5.0))
    >>> rec.rung, rec.predicted_error < 0.01
    ('dsm', True)
    """

    rung: str
    segments: object
    predicted_error: float
    errors: dict = field(default_factory=dict)
    estimates: dict = field(default_factory=dict)

    def __repr__(self) -> str:
        seg = f", {self.segments} segments" if self.segments else ""
        return f"Recommendation({self.rung!r}{seg}, predicted error {self.predicted_error:.2e})"

    def plot(self, ax: Axes | None = None, rtol: float | None = None) -> Figure:
        """Predicted error of every rung: :func:`dynstiff.plot.plot_model_errors`. Returns
        the matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> fig = ds.recommend_model(eq, band_hz=(0.0, 5.0)).plot()
        >>> type(fig).__name__
        'Figure'
        >>> import matplotlib.pyplot as plt; plt.close(fig)
        """
        from dynstiff.plot import plot_model_errors
        return plot_model_errors(self, ax=ax, rtol=rtol)

    def text(self) -> str:
        """One-paragraph explanation.

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> print(ds.recommend_model(eq, band_hz=(0.0, 5.0)).text().splitlines()[0])
        recommended model: dsm (predicted error 1.57e-04)
        """
        e = self.estimates
        seg = f" with N = {self.segments} segments per cable" if self.segments else ""
        lines = [f"recommended model: {self.rung}{seg} (predicted error "
                 f"{self.predicted_error:.2e})",
                 f"  lowest clamped-cable frequency {e['cable_f1_hz']:.4g} Hz; cable modes in "
                 f"band: {e['cable_modes_in_band']}",
                 f"  max sag/chord {e['sag_ratio_max']:.2e}, max lambda^2 "
                 f"{e['lambda_sq_max']:.3g}, max W sin(theta)/T {e['weight_ratio_max']:.3g}, "
                 f"cable/platform mass {e['mass_ratio']:.3g}",
                 "  predicted errors: " + ", ".join(
                     f"{k} {v:.2e}" for k, v in self.errors.items())]
        return "\n".join(lines) + "\n"

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per rung, cheapest first: "rung", "segments" (the
        lumped rung's count for the tolerance), "predicted error [-]" (inf: misses modes)
        and "recommended".

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> df = ds.recommend_model(eq, band_hz=(0.0, 5.0)).to_frame()
        >>> list(df["rung"])
        ['spring', 'catenary', 'dsm', 'exact', 'lumped']
        """
        import pandas as pd
        rungs = [r for r in RUNGS if r in self.errors]
        return pd.DataFrame({
            "rung": rungs,
            "segments": [self.estimates.get("lumped_segments") if r == "lumped" else None
                         for r in rungs],
            "predicted error [-]": [float(self.errors[r]) for r in rungs],
            "recommended": [r == self.rung for r in rungs],
        })


def _dsm_error(equilibrium: Equilibrium,
               band_hz: tuple[float, float]) -> tuple[float, float, list[str]]:
    """The closed form's error in the band, measured against the exact rung (theory.md
    §11.5): the largest relative difference of their frequencies in the band, paired in
    order from the band's bottom (the top mode straddling the band's edge is compared too);
    inf for a slack cable or axial modes in the band (the closed form has none), or when
    the closed form has fewer modes than the exact rung there. Returns (error, largest
    chordwise weight ratio, causes of the cables the guard flags)."""
    import warnings

    from dynstiff.models.exact import ExactModel
    lo, hi = band_hz
    w_hi = 2 * np.pi * hi
    val = [closed_form_validity(s, w_hi) for s in equilibrium.states]
    eps_max = max(v.values["weight_ratio"] for v in val)
    causes = sorted({r for v in val for r in v.reasons(1e-2)})
    if not all(np.isfinite(v.error) for v in val):
        return np.inf, float(eps_max), causes
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)
        f_d = eigenfrequencies(FrequencyModel(equilibrium), fmax_hz=1.2 * hi)
    f_x = eigenfrequencies(ExactModel(equilibrium, fmax_hz=1.25 * hi), fmax_hz=1.2 * hi)
    b = f_x[(f_x >= lo) & (f_x < hi)]
    a = f_d[f_d >= lo][:b.size]           # paired in order: a mode straddling hi is compared
    if a.size < b.size:
        return np.inf, float(eps_max), causes
    err = float(np.max(np.abs(a / b - 1))) if b.size else 0.0
    return err, float(eps_max), causes


def _massless_errors(equilibrium: Equilibrium, w_hi: float, n_cable: int) -> tuple[float, float]:
    """(catenary, spring) predicted errors up to w_hi [rad/s]: inf with cable modes below
    it (they miss them), else the first-order shift of the massless modes by the cables'
    inertia, the spring adding its measured gap to the catenary (module docstring)."""
    if n_cable > 0:
        return np.inf, np.inf
    cat = StaticCableModel(equilibrium, "catenary")
    spr = StaticCableModel(equilibrium, "spring")
    import scipy.linalg
    lam, X = scipy.linalg.eigh(cat.K, cat.platform_mass)
    w = np.sqrt(np.maximum(lam, 0.0))
    # first-order shift of every massless mode below 1.5 x the band top; a mode counts if
    # its shifted frequency lies in the band (heavy cables can pull one into it)
    sel = w <= w_hi * 1.5
    if not np.any(sel):
        return 0.0, 0.0
    import warnings
    with warnings.catch_warnings():       # a prediction: the guard speaks where it is used
        warnings.simplefilter("ignore", ClosedFormWarning)
        dsm = FrequencyModel(equilibrium)
        # cable part of the DSM robot matrix (it includes -omega^2 M_p) minus the static one
        Kd = dsm.dynamic_stiffness(w[sel]).real + (w[sel] ** 2)[:, None, None] * cat.platform_mass
    dK = Kd - cat.K[None]
    Xs = X[:, sel]
    shift = (np.einsum("ik,kij,jk->k", Xs, dK, Xs)
             / (2 * w[sel] ** 2 * np.einsum("ik,ij,jk->k", Xs, cat.platform_mass, Xs)))
    inband = w[sel] * (1 + np.minimum(shift, 0.0)) <= w_hi
    if not np.any(inband):
        return 0.0, 0.0
    catenary = float(np.abs(shift[inband]).max())
    fs = eigenfrequencies(spr, n_modes=spr.n_free)[sel][inband]
    fc = (w[sel] / (2 * np.pi))[inband]
    return catenary, float(np.max(np.abs(fs / fc - 1))) + catenary


def estimated_error(model: PlatformModel, band_hz: tuple[float, float]) -> tuple[float, str]:
    """The relative frequency error of ``model``'s cable theory up to the top of ``band_hz``,
    estimated without a richer model (the cable-model verdict of the design checks and
    maps, theory.md §12.5): the massless rungs and the lumped rung as
    :func:`predicted_errors`; the closed form as its robot-level bound (theory.md §11.6,
    :meth:`dynstiff.FrequencyModel.robot_error`): 2.5 x (its static error + the largest
    cable's own error, measured against the exact cable where its envelope exceeds 1e-2;
    inf for a slack cable or axial modes in the band), which bounded the measured error of
    the coupled modes on 800 random heavy-cable robots (validation/guard_bound.py); the
    exact rung its discretisation floor.

    Parameters
    ----------
    model : model of any rung
    band_hz : (float, float)
        [Hz]

    Returns
    -------
    error : float
        [-] (inf: the model misses modes in the band or does not apply).
    cause : str
        What dominates it, in words.
    """
    eq = model.equilibrium
    w_hi = 2 * np.pi * float(band_hz[1])
    if model.rung == "exact":
        return EXACT_ERROR, "the exact cables' discretisation"
    if model.rung == "lumped":
        harm = max(2 * float(band_hz[1]) * np.linalg.norm(x[-1] - x[0])
                   * np.sqrt(c.mass_per_length / t)                 # Omega / pi at the top
                   for x, c, t in zip(eq.nodes, model.robot.cables, eq.end_tensions))
        n_seg = int(np.min(model.segments))
        return (float((max(1.0, harm) * np.pi / n_seg) ** 2 / 24),
                f"{n_seg} segments per cable against the highest cable harmonic in the band")
    if model.rung in ("spring", "catenary"):
        n_cable = int(sum(cable_mode_count(s, w_hi)[0] for s in eq.states))
        err = _massless_errors(eq, w_hi, n_cable)[0 if model.rung == "catenary" else 1]
        return err, (f"{n_cable} cable modes in the band, which the massless cables miss"
                     if n_cable else "the cables' inertia shifts the platform modes")
    err, i = model.robot_error(w_hi)
    if not np.isfinite(err):
        v = closed_form_validity(eq.states[i], w_hi)
        return np.inf, f"cable {i}: " + "; ".join(v.reasons(1e-2))
    return err, (f"{ROBOT_ERROR_FACTOR:g} x (the closed form's static stiffness + cable "
                 f"{i}'s own error)")


def predicted_errors(
        equilibrium: Equilibrium, band_hz: tuple[float, float], rtol: float = 1e-2,
) -> tuple[dict[str, float], dict[str, float | list[str]], int]:
    """Predicted relative frequency error of each rung in the band, and the estimates.

    Parameters
    ----------
    equilibrium : Equilibrium
    band_hz : (float, float)
        Frequency band of interest [Hz].
    rtol : float
        Tolerance used to choose the lumped rung's segment count.

    Returns
    -------
    errors : dict rung -> float
    estimates : dict
        The estimates behind the errors; among them ``closed_form_causes``, the causes
        (sorted) that the closed form's guard (:func:`dynstiff.cable.guard.closed_form_validity`)
        names above 1e-2 for the cables at the band's top.
    segments : int
        Segments per cable for the lumped rung.
    """
    require_equilibrium(equilibrium)
    lo, hi = band(band_hz)
    if not (np.isfinite(rtol) and rtol > 0):
        raise InvalidParameterError(f"rtol must be finite and > 0, got {rtol!r}")
    states = equilibrium.states
    w_hi = 2 * np.pi * hi
    n_cable = int(sum(cable_mode_count(s, w_hi)[0] for s in states))
    f1 = []
    harm = []
    for s in states:
        p = chord_parameters(s)
        f1.append(np.sqrt(p.T / p.m) / (2 * p.L))
        harm.append(2 * hi * p.L * np.sqrt(p.m / p.T))          # Omega / pi at the band top
    dsm_error, eps_max, dsm_causes = _dsm_error(equilibrium, (lo, hi))
    cable_mass = sum(s.cable.mass_per_length * s.unstretched_length for s in states)
    estimates = dict(
        cable_f1_hz=float(min(f1)), cable_modes_in_band=n_cable,
        sag_ratio_max=float(max(chord_parameters(s).sag / s.chord_length for s in states)),
        lambda_sq_max=float(max(s.lambda_sq for s in states)),
        weight_ratio_max=float(eps_max), closed_form_causes=dsm_causes,
        mass_ratio=float(cable_mass / equilibrium.robot.platform.mass),
        highest_harmonic=float(max(harm)))
    errors = {}
    errors["catenary"], errors["spring"] = _massless_errors(equilibrium, w_hi, n_cable)
    errors["dsm"] = float(dsm_error)
    errors["exact"] = EXACT_ERROR
    n_harm = max(1.0, estimates["highest_harmonic"])
    segments = int(np.ceil(n_harm * np.pi / np.sqrt(12.0 * rtol)))
    segments = max(segments, 4)
    errors["lumped"] = float((n_harm * np.pi / segments) ** 2 / 24)
    estimates["lumped_segments"] = segments
    return errors, estimates, segments


def recommend_model(equilibrium: Equilibrium, band_hz: tuple[float, float],
                    rtol: float = 1e-2) -> Recommendation:
    """The cheapest model on the ladder expected to meet ``rtol`` in the band.

    Parameters
    ----------
    equilibrium : Equilibrium
        From :meth:`Robot.equilibrium`.
    band_hz : (float, float)
        Frequency band of interest [Hz]; every mode in it counts.
    rtol : float
        Admissible relative error of the natural frequencies [-].

    Returns
    -------
    Recommendation

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> rec = ds.recommend_model(eq, band_hz=(0.0, 5.0))
    >>> rec.rung
    'dsm'
    """
    errors, estimates, segments = predicted_errors(equilibrium, band_hz, rtol)
    for rung in RUNGS:
        if errors[rung] <= rtol:
            break
    return Recommendation(rung=rung, segments=segments if rung == "lumped" else None,
                          predicted_error=errors[rung], errors=errors, estimates=estimates)
