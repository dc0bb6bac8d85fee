"""The closed form's guard (theory.md §11.5): how far the closed-form cable theory can be trusted
for one cable (an envelope of its error from sag, chordwise weight, tension variation, slack
and axial modes), the measured error of its clamped frequencies against the exact cable, and
the warning raised when it is used outside its range.
"""

from dataclasses import dataclass

import numpy as np

from dynstiff.cable.chord import chord_parameters
from dynstiff.cable.exact import ExactCable
from dynstiff.cable.psi import closed_form_spectrum
from dynstiff.errors import ClosedFormWarning, InvalidParameterError, user_stacklevel

__all__ = [
    "ClosedFormValidity", "DEFAULT_GUARD_RTOL", "ROBOT_ERROR_FACTOR", "closed_form_local_error",
    "closed_form_validity"
]


#: Estimated relative frequency error above which the closed form warns (theory.md §11.5).
DEFAULT_GUARD_RTOL = 1e-2


#: Safety factor k of the robot-level bound k (e_static + max_c e_c) on the closed form's
#: error of the coupled modes (theory.md §11.6): the first-order bound (k = 1) was exceeded
#: by up to 2.11x on 800 random robots (cables 1-200 % of the platform's mass; near veerings
#: of a platform mode with cable modes); 2.5 bounds them all (validation/guard_bound.py).
ROBOT_ERROR_FACTOR = 2.5
#: Envelope above which a cable's own error is measured against the exact cable.
MEASURE_ABOVE = 1e-2


# --------------------------------------------------------------------------- guard
#: The closed form warns when the band reaches this fraction of a cable's first axial
#: frequency sqrt(EA/m) / (2 L0) (it has no axial modes).
AXIAL_MARGIN = 0.9
#: Lowest-to-highest tension ratio below which a cable is called slack.
SLACK_RATIO = 0.1


@dataclass(frozen=True)
class ClosedFormValidity:
    """The closed form's estimated relative error for one cable and its causes (theory.md
    §11.5): an envelope of the error of its clamped frequencies against the exact model,
    measured on 150 random cables (the largest ratio of measured to estimated error was
    0.83). It is not an envelope of the static end stiffness, whose error in the soft
    in-plane direction can exceed it 2.4x at 30-60 degrees; the robot model measures that
    part exactly (:meth:`dynstiff.models.dsm.FrequencyModel.static_error`).

    Attributes
    ----------
    error : float
        Estimated relative error [-]; inf when the closed form misses modes or does not
        apply (slack cable).
    causes : dict
        Cause -> its estimate [-]: "sag" 15 delta^2 (delta = d/L), "chordwise weight"
        2 delta eps (1 + 40 eps) (eps = W |sin theta| / T), "tension variation" 0.4 v^2
        (v = (T_max - T_min) / T_mean), "slack" (inf when T_min < 0.1 T_max), "axial" (inf
        when the band reaches 0.9 of the first axial frequency sqrt(EA/m) / (2 L0)).
    values : dict
        delta, eps, v, T_min / T_max and the first axial frequency [Hz].
    """

    error: float
    causes: dict
    values: dict

    def reasons(self, rtol):
        """Causes whose estimate exceeds ``rtol``, as readable text."""
        v = self.values
        text = {"sag": f"sag d/L = {v['sag_ratio']:.3g}",
                "chordwise weight": f"chordwise weight W sin(theta)/T = {v['weight_ratio']:.3g}",
                "tension variation": f"tension varies by {v['tension_variation']:.3g} of its "
                                     f"mean along the cable",
                "slack": f"slack (lowest tension {v['tension_ratio']:.3g} of the highest)",
                "axial": f"axial modes from {v['axial_hz']:.4g} Hz are in the band"}
        return [text[k] for k, e in self.causes.items() if e > rtol]


def closed_form_validity(state, omega_max=0.0, tension="mean", params=None):
    """How far the closed form can be trusted for this cable up to omega_max [rad/s]
    (theory.md §11.5); omega_max decides whether axial modes enter the band. ``params``:
    ``chord_parameters(state, tension)`` when the caller has it already.

    Returns
    -------
    ClosedFormValidity
    """
    p = chord_parameters(state, tension) if params is None else params
    delta = p.sag / p.L
    eps = state.total_weight * abs(state.chord[2]) / state.chord_length / p.T
    t_min, t_max = state.min_tension, state.max_tension
    v = (t_max - t_min) / state.mean_tension
    ratio = t_min / t_max
    cab = state.cable
    f_ax = np.sqrt(cab.EA / cab.mass_per_length) / (2.0 * state.unstretched_length)
    causes = {"sag": 15 * delta**2, "chordwise weight": 2 * delta * eps * (1 + 40 * eps),
              "tension variation": 0.4 * v**2,
              "slack": np.inf if ratio < SLACK_RATIO else 0.0,
              "axial": np.inf if omega_max >= AXIAL_MARGIN * 2 * np.pi * f_ax else 0.0}
    values = {"sag_ratio": delta, "weight_ratio": eps, "tension_variation": v,
              "tension_ratio": ratio, "axial_hz": f_ax}
    err = causes["sag"] + causes["chordwise weight"] + causes["tension variation"]
    err = max(err, causes["slack"], causes["axial"])
    return ClosedFormValidity(error=float(err), causes=causes, values=values)


def guard_cable(state, omega_max, tension, guard_rtol):
    """Warn (ClosedFormWarning) when the closed form is used outside its range for one cable
    up to omega_max [rad/s]: slack, axial modes in the band, or a measured error of its
    clamped frequencies above guard_rtol where the envelope exceeds it (theory.md §11.5)."""
    if guard_rtol is None:
        return
    if not (isinstance(guard_rtol, (int, float)) and not isinstance(guard_rtol, bool)
            and 0 < guard_rtol < np.inf):
        raise InvalidParameterError(f"guard_rtol must be a number > 0 or None, got "
                                    f"{guard_rtol!r}")
    v = closed_form_validity(state, omega_max, tension)
    if v.error <= guard_rtol:
        return
    if np.isfinite(v.error):
        err = closed_form_local_error(state, omega_max, tension)
        if err <= guard_rtol:
            return
        what = f"its clamped frequencies are {err:.2g} off the exact model's"
    else:
        what = "it is outside the closed form's range"
    import warnings
    cause = "slack" if np.isinf(v.causes["slack"]) else (
        "axial" if np.isinf(v.causes["axial"]) else "local")
    warnings.warn(ClosedFormWarning(
        f"{what} (" + "; ".join(v.reasons(0.1 * guard_rtol)) + "): use model='exact'",
        cable=None, cause=cause), stacklevel=user_stacklevel())


def closed_form_local_error(state, omega_max, tension="mean"):
    """Measured relative error of the closed form's clamped-cable frequencies against the
    exact model (theory.md §11.5), over the modes below max(omega_max, 8 omega_1) [rad/s]
    (omega_1 the first taut-string frequency); the exact model's axial modes are left out
    (the guard reports them as missing). Returns the largest |f_closed / f_exact - 1| [-]."""
    p = chord_parameters(state, tension)
    w1 = np.pi * np.sqrt(p.T / p.m) / p.L
    band = max(float(omega_max), 8.0 * w1)
    cab = ExactCable(state, band)
    sel = (cab.eigenvalues <= band**2) & (np.array(cab.family) != "axial")
    f_ex = np.sqrt(cab.eigenvalues[sel])
    n = f_ex.size
    if n == 0:
        return 0.0
    f_cf = closed_form_spectrum(p.lambda_sq, n)[0] * np.sqrt(p.T / p.m) / p.L
    return float(np.max(np.abs(f_cf / f_ex - 1.0)))
