"""The closed form's guard (theory.md §11.5, §11.6): the warnings a
:class:`~dynstiff.models.dsm.FrequencyModel` gives when its cables leave the closed form's
validity (slack, static stiffness error, axial and local modes in the band, the robot-level
bound), and the static error they rest on. Functions of the model, which calls them (its
build, :meth:`~dynstiff.models.dsm.FrequencyModel.guard_band`)."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, cast

import numpy as np

from dynstiff.cable.catenary import end_stiffnesses
from dynstiff.cable.dsm import static_block_coefficients
from dynstiff.cable.guard import ROBOT_ERROR_FACTOR, closed_form_local_error
from dynstiff.errors import ClosedFormWarning, user_stacklevel

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import NDArray

    from dynstiff.models.dsm import FrequencyModel
    from dynstiff.robot.equilibrium import Equilibrium

__all__ = ["ROBOT_BOUND_MESSAGE", "guard_band", "guard_static", "static_error"]

#: How the robot-level bound's warning begins (theory.md §11.6), for filters of it.
ROBOT_BOUND_MESSAGE = "the closed form's error of the coupled modes"


def static_error(model: FrequencyModel) -> tuple[float, int | None]:
    """:meth:`FrequencyModel.static_error`, computed: the modes x of (K_exact(0), M_p) and
    every cable's share of x^T dK x / (2 x^T K x), dK = K_dsm(0) - K_exact(0) (theory.md
    §11.5), K_dsm(0) the real part before the model's loss factor eta (both rungs multiply
    by the same s = 1 + i eta, §12.2, whose product with a cable's own complex EA shifts
    the real parts alike: no error of the closed form); (0, None) when no massless mode has
    a positive stiffness."""
    nf, n = model.n_free, len(model.params)
    J = model._lever_maps                                                   # (n, 3, nf)
    states = cast("Equilibrium", model.equilibrium).states
    Ke = np.swapaxes(J, 1, 2) @ end_stiffnesses(states) @ J
    K_ex = model._K_geo_free + Ke.sum(axis=0)
    K0 = np.real(static_block_coefficients(model.stacked_params)).reshape(n, 1, 5)
    Kd = np.matmul(K0, model._assembly.reshape(n, 5, nf * nf)).reshape(n, nf, nf)
    dK = Kd - Ke
    from scipy.linalg import eigh
    lam, X = eigh(0.5 * (K_ex + K_ex.T), model.platform_mass)
    ok = lam > 0
    if not np.any(ok):
        return 0.0, None
    X, lam = X[:, ok], lam[ok]
    per = np.einsum("ik,cij,jk->ck", X, dK, X) / (2 * lam)
    total = np.abs(per.sum(axis=0))
    k = int(np.argmax(total))
    return float(total[k]), int(np.argmax(np.abs(per[:, k])))


def guard_static(model: FrequencyModel) -> None:
    """Warn for slack cables and for a static error above ``guard_rtol``."""
    for i, v in enumerate(model._validity):
        if v.causes["slack"] > 0:
            warn_once(model, i, "slack", f"cable {i}: the closed form does not apply: "
                      + "; ".join(v.reasons(model.guard_rtol)))
    err, i = model.static_error()
    if err > model.guard_rtol:
        warn_once(model, i, "static", (
            f"cable {i}: the closed form's static stiffness shifts a global mode by "
            f"{err:.2g} (estimate, > guard_rtol {model.guard_rtol:g}; "
            + "; ".join(model._validity[i].reasons(0.1 * model.guard_rtol)) + ")"))


def guard_band(model: FrequencyModel, omega: NDArray[Any]) -> None:
    """:meth:`FrequencyModel.guard_band`."""
    if model.guard_rtol is None or not omega.size:
        return
    top = float(np.max(np.abs(omega)))
    if top <= model._guarded[0]:                 # this band was checked already
        return
    model._guarded[0] = top
    for i in np.flatnonzero(top >= model._axial_omega):
        f_ax = model._validity[i].values["axial_hz"]
        warn_once(model, int(i), "axial", (
            f"cable {i}: its axial modes from {f_ax:.4g} Hz lie in the band asked (up to "
            f"{top / 2 / np.pi:.4g} Hz); the closed form has none, so mode counts and "
            f"frequencies above are wrong"))
    for i in np.flatnonzero(top >= model._local_omega):
        v = model._validity[i]
        if (int(i), "local") in model._warned or not np.isfinite(v.error) \
                or v.error <= model.guard_rtol:
            continue
        # the envelope is conservative: measure against the exact cable before warning
        err = closed_form_local_error(cast("Equilibrium", model.equilibrium).states[i],
                                      min(top, model._axial_omega[i]), model.tension)
        if err <= model.guard_rtol:
            model._warned.add((int(i), "local"))       # checked, within tolerance
            continue
        warn_once(model, int(i), "local", (
            f"cable {i}: its local modes (from {model._local_omega[i] / 2 / np.pi:.4g} Hz) "
            f"are in the band asked and the closed form's are {err:.2g} off the exact "
            f"model's (> guard_rtol {model.guard_rtol:g}; "
            + "; ".join(v.reasons(0.1 * model.guard_rtol)) + ")"))
    guard_robot(model, top)


def guard_robot(model: FrequencyModel, top: float) -> None:
    """Warn once when the robot-level bound up to top [rad/s] exceeds guard_rtol and no
    cable's warning has pointed to the exact rung already."""
    if (None, "robot") in model._warned or model._issued:
        return
    bound, i = model.robot_error(top)
    if np.isfinite(bound) and bound > model.guard_rtol:
        warn_once(model, None, "robot", (
            f"{ROBOT_BOUND_MESSAGE} up to {top / 2 / np.pi:.4g} Hz "
            f"may reach {bound:.2g} (bound {ROBOT_ERROR_FACTOR:g} x (static + cable "
            f"{i}'s own error), > guard_rtol {model.guard_rtol:g})"))


def warn_once(model: FrequencyModel, cable: int | None, cause: str, message: str) -> None:
    """A ClosedFormWarning, once per cable and cause, pointing to the exact rung."""
    if (cable, cause) in model._warned:
        return
    model._warned.add((cable, cause))
    model._issued.append(cause)
    warnings.warn(ClosedFormWarning(message + ": use the 'exact' rung", cable=cable,
                                    cause=cause), stacklevel=user_stacklevel())
