"""The platform modes of a robot: the modes every modal verdict is about (theory.md §12.4).

For each free DOF j the participations p_kj of all the modes sum to 1
(:attr:`dynstiff.ModalResult.participation`). The DOF's *carrier* is the mode with the
largest participation among the modes below ``found_hz``, the frequency by which every free
DOF has at least ``PLATFORM_FOUND`` (half) of its participation; the *platform modes* are
the carriers and every global mode below ``found_hz``. Both depend on the robot alone, not
on how many modes a user asked for: :func:`find_platform_modes` computes modes until every
DOF is half found (from 1.1 times the highest massless-cable platform frequency, growing by
1.5), up to a ceiling of modes; at the ceiling the search is *incomplete* and every verdict
that needs the platform modes is "unknown".

A light-cable robot's platform modes are its global modes (one per free DOF). When the
cables weigh as much as the platform, no mode may be global: each DOF's carrier is then the
cable-dominated mode that moves it most, and the search says how spread the DOF is.
"""

from dataclasses import dataclass

import numpy as np

from dynstiff.analyses.eigen_matrix import massless_modes
from dynstiff.analyses.participation import modal_data
from dynstiff.constants import DOF_NAMES
from dynstiff.errors import InvalidParameterError

__all__ = ["MAX_PLATFORM_MODES", "PLATFORM_FOUND", "PlatformModes", "find_platform_modes",
           "select_platform_modes"]

#: A free DOF counts as found when the participations of the modes below a frequency sum
#: to this [-].
PLATFORM_FOUND = 0.5
#: Most modes a search for the platform modes computes: beyond it the search is incomplete.
MAX_PLATFORM_MODES = 2000
_GROWTH = 1.5
_START = 1.1


@dataclass(frozen=True)
class PlatformModes:
    """The platform modes among the modes of a robot.

    Attributes
    ----------
    modes : ModalResult
        Every mode below ``searched_hz`` (1 + ``neighbours_rtol``) [Hz].
    index : ndarray of int
        Indices into ``modes`` of the platform modes, ascending.
    carriers : dict
        Free DOF name -> index of the mode with its largest participation.
    complete : bool
        Every free DOF was half found within the ceiling.
    found_hz : float
        Frequency by which every free DOF is half found [Hz] (NaN if incomplete).
    searched_hz : float
        Every mode below this frequency is in ``modes`` [Hz].
    reason : str
        Why the search is incomplete ("" when complete).
    """

    modes: object
    index: np.ndarray
    carriers: dict
    complete: bool
    found_hz: float
    searched_hz: float
    reason: str

    @property
    def freq_hz(self):
        """Frequencies of the platform modes [Hz]."""
        return np.asarray(self.modes.freq_hz)[self.index]

    @property
    def first_hz(self):
        """Frequency of the lowest platform mode [Hz] (NaN if the search is incomplete)."""
        return float(self.freq_hz[0]) if self.complete and self.index.size else np.nan

    def describe(self, k):
        """One mode in words: frequency, kind, share and the DOF it carries most."""
        m = self.modes
        r = np.nan_to_num(m.participation[k])        # ModalResult.dominant_dof of mode k
        dof = DOF_NAMES[int(np.argmax(r))] if np.nanmax(r, initial=0) > 0 else "-"
        return (f"{m.freq_hz[k]:.4g} Hz ({m.kind[k]}, platform share "
                f"{100 * m.platform_share[k]:.0f} %, mostly {dof})")

    def spread(self):
        """When a free DOF is carried by cable-dominated modes only (its carrier's platform
        share < 50 %, theory.md §12.4), the sentence saying which DOFs and over how many
        cable-dominated modes up to ``found_hz`` (where each free DOF is half found) their
        motion is spread; "" otherwise or when the search is incomplete."""
        m = self.modes
        if not self.complete or not len(m):
            return ""
        share = np.asarray(m.platform_share)
        dofs = [d for d, k in self.carriers.items() if share[k] < 0.5]
        if not dofs:
            return ""
        below = np.asarray(m.freq_hz) <= self.found_hz
        n = int(np.sum(below & (share < 0.5)))
        return (f"no mode is platform-dominated in {', '.join(dofs)}: the platform's motion "
                f"there is spread over {n} cable-dominated modes up to {self.found_hz:.4g} Hz "
                f"(largest platform share among them {100 * share[below & (share < 0.5)].max():.0f}"
                f" %); the platform modes are the carriers of each DOF by participation")

    def __repr__(self):
        if not self.complete:
            return f"PlatformModes(incomplete: {self.reason})"
        return (f"PlatformModes({self.index.size} of {len(self.modes)} modes, first "
                f"{self.first_hz:.4g} Hz, found by {self.found_hz:.4g} Hz)")


def select_platform_modes(modes, free_index, upto_hz):
    """Indices of the platform modes among ``modes`` below ``upto_hz`` [Hz]: the carrier of
    each free DOF (largest participation) and every global mode; returns (index,
    carriers)."""
    f = np.asarray(modes.freq_hz)
    below = f <= upto_hz
    p = np.nan_to_num(modes.participation)
    carriers = {}
    for j in free_index:
        if np.any(below) and p[below, j].max() > 0:
            carriers[DOF_NAMES[j]] = int(np.argmax(np.where(below, p[:, j], -1.0)))
    glob = np.flatnonzero(below & (np.asarray(modes.kind) == "global"))
    return np.union1d(glob, list(carriers.values())).astype(int), carriers


def _found_frequency(modes, free_index, top=np.inf):
    """Frequency [Hz] at which every free DOF's cumulative participation over the modes at
    or below ``top`` [Hz] reaches PLATFORM_FOUND, or None; and the cumulative participation
    of each free DOF."""
    f = np.asarray(modes.freq_hz)
    keep = f <= top
    if not np.any(keep):
        return None, np.zeros(len(free_index))
    p = np.nan_to_num(modes.participation[keep][:, free_index])
    cum = np.cumsum(p, axis=0)
    reached = cum >= PLATFORM_FOUND
    if not np.all(reached[-1]):
        return None, cum[-1]
    first = np.argmax(reached, axis=0)             # first mode at which each DOF is found
    return float(f[keep][int(first.max())]), cum[-1]


def find_platform_modes(model, cover_hz=0.0, neighbours_rtol=0.0,
                        max_modes=MAX_PLATFORM_MODES):
    """Compute modes until they hold the platform modes of ``model`` (module docstring).

    Parameters
    ----------
    model : model of any rung
    cover_hz : float
        Compute every mode below this frequency too [Hz] (e.g. the top of a forbidden band
        with its margin).
    neighbours_rtol : float
        Also every mode within this relative distance above the last frequency searched
        (the local neighbours of the platform modes, for a proximity check) [-].
    max_modes : int
        The ceiling: most modes computed. A search stopped by it is incomplete and keeps the
        modes of its last completed step.

    Returns
    -------
    PlatformModes

    Notes
    -----
    Without a positive massless-cable frequency the search starts at 1.1 Hz. For a model
    with a band (``max_omega``, the exact rung) the search stops at max_omega / 2 pi /
    (1 + neighbours_rtol), so that the neighbours it reads stay in the band; a search
    stopped there is incomplete.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> pm = find_platform_modes(ds.FrequencyModel(eq))
    >>> pm.complete, len(pm.index), round(pm.first_hz, 4)
    (True, 6, 2.2061)
    """
    if not (np.isfinite(cover_hz) and cover_hz >= 0):
        raise InvalidParameterError(f"cover_hz must be finite and >= 0 [Hz], got {cover_hz!r}")
    if not (np.isfinite(neighbours_rtol) and neighbours_rtol >= 0):
        raise InvalidParameterError(
            f"neighbours_rtol must be finite and >= 0, got {neighbours_rtol!r}")
    fi = np.asarray(model.free_index)
    lam = massless_modes(model)[0]
    f0 = np.sqrt(lam[lam > 0]) / (2 * np.pi)
    base = float(f0.max()) if f0.size else 1.0
    top = max(_START * base, cover_hz)
    ceiling_hz = np.inf
    if hasattr(model, "max_omega"):                 # a rung with a band (the exact cables)
        ceiling_hz = model.max_omega / (2 * np.pi) / (1 + neighbours_rtol)
        top = min(top, ceiling_hz)
    last = None                               # (modes, top) of the last search done
    while True:
        try:
            res = modal_data(model, top * (1 + neighbours_rtol), max_modes=max_modes)
        except InvalidParameterError as exc:
            if "max_modes" not in str(exc):
                raise
            return _incomplete(last, f"more than {max_modes} modes below "
                                     f"{top * (1 + neighbours_rtol):.4g} Hz, the ceiling of the "
                                     f"search for the platform modes")
        found, cum = _found_frequency(res, fi, top)
        if found is not None and top >= cover_hz:
            index, carriers = select_platform_modes(res, fi, found)
            return PlatformModes(modes=res, index=index, carriers=carriers, complete=True,
                                 found_hz=found, searched_hz=top, reason="")
        last = (res, top)
        if top >= ceiling_hz:
            spread = ", ".join(f"{DOF_NAMES[j]} {c:.0%}" for j, c in zip(fi, cum))
            return _incomplete(last, f"the model's band ends at {top:.4g} Hz with the "
                                     f"platform's participation found only in part ({spread}); "
                                     f"build it with a larger fmax_hz")
        top = min(_GROWTH * top, ceiling_hz)


def _incomplete(last, reason):
    """An incomplete search: the modes of its last completed step (None if none)."""
    res, top = last if last is not None else (None, 0.0)
    return PlatformModes(modes=res, index=np.zeros(0, int), carriers={}, complete=False,
                         found_hz=np.nan, searched_hz=top if res is not None else 0.0,
                         reason=reason)
