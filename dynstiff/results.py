"""Result types of the analyses: plain data that can make a table and a figure.

Every result holds its numbers in public fields, with units in the docstrings; ``to_frame()``
gives a pandas DataFrame with units in the column names and ``plot(ax=None)`` draws it
(:mod:`dynstiff.plot`); pandas and matplotlib are imported only then.

Channels of an FRF: inputs ``LOAD_NAMES`` (forces [N] and moments [N m] on the platform about
P), outputs ``DOF_NAMES`` (translations [m] of a platform point, rotations [rad]).
"""

from dataclasses import dataclass

import numpy as np

from dynstiff.constants import DOF_NAMES, GLOBAL_SHARE, LOAD_NAMES, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError

__all__ = ["FRFResult", "ModalResult", "LumpedModalResult", "DampedModes", "INPUT_NAMES",
           "OUTPUT_NAMES", "RESPONSE_KINDS", "mode_kinds", "response_factor"]

_TWO_PI = 2.0 * np.pi

#: Load channels: forces [N] and moments [N m] on the platform about P.
INPUT_NAMES = LOAD_NAMES
#: Response channels: translations [m] of the chosen point and rotations [rad].
OUTPUT_NAMES = DOF_NAMES
#: FRF kinds and the power of (i omega) that turns a receptance into each.
RESPONSE_KINDS = {"receptance": 0, "mobility": 1, "accelerance": 2}


def response_factor(omega, kind):
    """(i omega)^k turning a receptance into ``kind`` (k = 0, 1, 2 for receptance, mobility,
    accelerance), shape of ``omega`` [rad/s] (theory.md §4).

    Raises
    ------
    InvalidParameterError
        ``kind`` unknown.
    """
    if kind not in RESPONSE_KINDS:
        raise InvalidParameterError(
            f"kind must be one of {tuple(RESPONSE_KINDS)}, got {kind!r}")
    return (1j * np.asarray(omega)) ** RESPONSE_KINDS[kind]


#: Column units of the platform mode shapes in the tables: the shapes are normalised to unit
#: platform kinetic energy x^T M_p x = 1, so translations are in m/sqrt(kg) and rotations in
#: rad/(m sqrt(kg)) (M_p in kg and kg m^2), not in metres.
SHAPE_UNITS = ("[m/kg^0.5, x'Mx=1]",) * 3 + ("[rad/(m kg^0.5), x'Mx=1]",) * 3


def _span(freq_hz):
    f = np.asarray(freq_hz)
    return f"{f.min():.4g}-{f.max():.4g} Hz" if f.size else "none"


@dataclass(frozen=True)
class FRFResult:
    """FRF matrix H[k, o, i] from input channel i to output channel o at freq_hz[k].

    Attributes
    ----------
    freq_hz : ndarray, shape (n,)
    H : ndarray, shape (n, n_out, n_in), complex
        Units: receptance [m/N, m/(N m), rad/N, rad/(N m)]; mobility per second; accelerance
        per second squared. inf at an exact pole.
    inputs, outputs : tuple of str
    kind : str
    damping : str
        The damping of the model the FRF comes from, in words ("undamped": every peak is
        the grid's value near a pole, not the structure's).
    """

    freq_hz: np.ndarray
    H: np.ndarray
    inputs: tuple
    outputs: tuple
    kind: str
    damping: str = "not stated"

    def unit(self, output, input):
        """Unit of H from ``input`` (fx .. mz) to ``output`` (x .. rz) for this ``kind``,
        e.g. ``"m/N"``, ``"rad/(N m)"``, ``"m/(N s)"`` (mobility), ``"m/(N s^2)"``
        (accelerance)."""
        if output not in OUTPUT_NAMES or input not in INPUT_NAMES:
            raise InvalidParameterError(
                f"unit needs an output among {OUTPUT_NAMES} and an input among "
                f"{INPUT_NAMES}, got {output!r}, {input!r}")
        num = "m" if output in OUTPUT_NAMES[:3] else "rad"
        den = ["N"] if input in INPUT_NAMES[:3] else ["N", "m"]
        den += [[], ["s"], ["s^2"]][RESPONSE_KINDS[self.kind]]
        return f"{num}/{den[0]}" if len(den) == 1 else f"{num}/({' '.join(den)})"

    def __repr__(self):
        return (f"FRFResult({self.kind}, {len(self.freq_hz)} frequencies {_span(self.freq_hz)}, "
                f"outputs {self.outputs}, inputs {self.inputs}, {self.damping})")

    def _repr_html_(self):
        """Jupyter display: the largest |H| of each channel and where it is."""
        from dynstiff._html import html_table
        f = np.asarray(self.freq_hz)
        rows = []
        for o, out in enumerate(self.outputs):
            for i, inp in enumerate(self.inputs):
                a = np.abs(np.asarray(self.H)[:, o, i])
                k = int(np.nanargmax(np.where(np.isfinite(a), a, -1.0))) if a.size else 0
                rows.append([out, inp, self.unit(out, inp), a[k] if a.size else np.nan,
                             f[k] if a.size else np.nan])
        return html_table(f"FRFResult: {self.kind}, {len(f)} frequencies {_span(f)}, "
                          f"{self.damping}", ["output", "input", "unit", "largest |H|",
                                              "at [Hz]"], rows)

    def plot(self, ax=None, modes=None, pairs=None, phase=False):
        """Magnitude (and phase) against frequency: :func:`dynstiff.plot.plot_frf`.
        Returns the matplotlib Figure."""
        from dynstiff.plot import plot_frf
        return plot_frf(self, modes=modes, pairs=pairs, ax=ax, phase=phase)

    def to_uff(self, path, node=1, entity="platform", point_node=None, binary=False,
               even=False):
        """Write every (output, input) pair as a UFF 58 record through pyuff (ASCII, or
        binary with exact doubles): :func:`dynstiff.io.exchange.write_uff58` (theory.md §15.3).
        ``even=True`` (the step of the grid's uniform part) or a step [Hz] resamples on an
        even grid (:func:`dynstiff.io.exchange.even_grid`), as the records then say.
        Returns the path."""
        from dynstiff.io.exchange import write_uff58
        return write_uff58(self, path, node=node, entity=entity, point_node=point_node,
                           binary=binary, even=even)

    def to_control(self, name=None):
        """python-control ``FrequencyResponseData`` (outputs x inputs x frequencies, omega
        [rad/s]), named with its channels, that ``control.bode_plot`` draws as it is; a
        channel below 1e-12 of the largest (zero by symmetry) is exact zeros:
        :func:`dynstiff.io.exchange.frf_to_control`."""
        from dynstiff.io.exchange import frf_to_control
        return frf_to_control(self, name=name)

    def to_frame(self):
        """Tidy pandas DataFrame: freq [Hz], input, output, magnitude |H|, phase [deg],
        real, imag (all in the row's ``unit``, see :meth:`unit`), kind."""
        import pandas as pd
        n, no, ni = self.H.shape
        f = np.repeat(self.freq_hz, no * ni)
        out = np.tile(np.repeat(self.outputs, ni), n)
        inp = np.tile(self.inputs, n * no)
        units = np.tile([self.unit(o, i) for o in self.outputs for i in self.inputs], n)
        h = self.H.reshape(-1)
        with np.errstate(invalid="ignore"):
            return pd.DataFrame({"freq [Hz]": f, "input": inp, "output": out,
                                 "magnitude": np.abs(h), "phase [deg]": np.degrees(np.angle(h)),
                                 "real": h.real, "imag": h.imag, "unit": units,
                                 "kind": self.kind})


def mode_kinds(platform_share):
    """The one labelling of modes (theory.md §12.1): "global" (platform share >=
    ``GLOBAL_SHARE``, the platform holds most of the kinetic energy), "mixed" (from
    ``PLATFORM_SHARE_THRESHOLD``: a cable mode that moves the platform) or "local" (the
    cables vibrate, the platform hardly), for each platform share [-].

    Examples
    --------
    >>> mode_kinds([0.99, 0.2, 0.01])
    ('global', 'mixed', 'local')
    """
    s = np.asarray(platform_share, dtype=float).ravel()
    return tuple("global" if v >= GLOBAL_SHARE else "mixed" if v >= PLATFORM_SHARE_THRESHOLD
                 else "local" for v in s)


@dataclass(frozen=True)
class ModalResult:
    """Modes of the robot.

    Attributes
    ----------
    freq_hz : ndarray, shape (n,)
        Natural frequencies [Hz].
    platform_shapes : ndarray, shape (n, 6)
        Platform motion (dp [m], dtheta [rad]) about P, held DOFs 0, normalised to unit
        platform kinetic energy x^T M_p x = 1 (zero for a purely local mode).
    cable_energy_fraction : ndarray, shape (n,)
        Kinetic energy in the cables / total kinetic energy [-].
    cable_energy : ndarray, shape (n, n_cables)
        Kinetic-energy share of each cable [-] (sums to cable_energy_fraction).
    kind : tuple of str
        "global", "mixed" or "local" by the platform share (:func:`mode_kinds`); derived
        from ``cable_energy_fraction`` when not given.
    massless_freq_hz : ndarray, shape (n,)
        Frequency of the mode of the massless-cable model each mode continues (one-to-one,
        by participation: :func:`dynstiff.analyses.eigen_matrix.massless_pairing`; NaN for
        the other modes).
    platform_mass : ndarray, shape (6, 6), optional
        The platform block of the robot's mass matrix about P [kg, kg m, kg m^2] (held
        DOFs' rows and columns zero): the rigid platform, plus, for the lumped rung, the
        half masses of the cables' last segments; it gives the modes' participation.
    """

    freq_hz: np.ndarray
    platform_shapes: np.ndarray
    cable_energy_fraction: np.ndarray
    cable_energy: np.ndarray
    kind: tuple = None
    massless_freq_hz: np.ndarray = None
    platform_mass: np.ndarray = None

    def __post_init__(self):
        if self.kind is None:
            object.__setattr__(self, "kind", mode_kinds(self.platform_share))
        if self.massless_freq_hz is None:
            object.__setattr__(self, "massless_freq_hz", np.full(len(self.freq_hz), np.nan))

    @property
    def platform_share(self):
        """Platform kinetic energy / total kinetic energy of each mode [-], shape (n,)."""
        return np.clip(1.0 - np.asarray(self.cable_energy_fraction, dtype=float), 0.0, 1.0)

    @property
    def participation(self):
        """Effective-mass fraction of each free platform DOF in each mode [-], shape (n, 6):
        p_kj = (M x_k)_j^2 s_k / M_jj with x_k the shape at unit platform kinetic energy,
        s_k its platform share and M ``platform_mass`` (theory.md §12.1). Over all the modes
        of the robot each column sums to 1; held DOFs are 0 (NaN without
        ``platform_mass``)."""
        n = len(self.freq_hz)
        if self.platform_mass is None:
            return np.full((n, 6), np.nan)
        M = np.asarray(self.platform_mass, dtype=float)
        d = np.diag(M)
        g = np.asarray(self.platform_shapes, dtype=float) @ M
        with np.errstate(invalid="ignore", divide="ignore"):
            p = np.where(d > 0, g**2 * self.platform_share[:, None] / np.where(d > 0, d, 1.0),
                         0.0)
        return p

    @property
    def dominant_dof(self):
        """Name of the DOF each mode moves most, by participation ("-" for none)."""
        p = self.participation
        return tuple(DOF_NAMES[int(np.argmax(r))] if np.nanmax(r, initial=0) > 0 else "-"
                     for r in np.nan_to_num(p))

    @property
    def shift_from_massless(self):
        """Relative shift of each paired mode's frequency from its massless-cable mode [-]."""
        return self.freq_hz / self.massless_freq_hz - 1.0

    def __len__(self):
        return len(self.freq_hz)

    def __repr__(self):
        n = {c: sum(k == c for k in self.kind) for c in ("global", "mixed", "local")}
        return (f"{type(self).__name__}({len(self)} modes {_span(self.freq_hz)}: "
                f"{n['global']} global, {n['mixed']} mixed, {n['local']} local)")

    def _repr_html_(self):
        """Jupyter display: frequency, kind, platform share and dominant DOF of each mode."""
        from dynstiff._html import html_table
        rows = zip(range(1, len(self) + 1), self.freq_hz, self.kind, self.platform_share,
                   self.dominant_dof)
        return html_table(repr(self), ["mode", "freq [Hz]", "kind", "platform share [-]",
                                       "dominant dof"], rows)

    def plot(self, ax=None):
        """Frequencies against platform share, coloured by kind:
        :func:`dynstiff.plot.plot_modes`. Returns the matplotlib Figure."""
        from dynstiff.plot import plot_modes
        return plot_modes(self, ax=ax)

    def to_frame(self):
        """pandas DataFrame, one row per mode, units in the column names: frequency, kind,
        platform share, the participation of each DOF, the paired massless mode and the
        platform shape (labelled for its energy normalisation, ``SHAPE_UNITS``)."""
        import pandas as pd
        df = pd.DataFrame({
            "mode": np.arange(1, len(self) + 1),
            "freq [Hz]": self.freq_hz,
            "kind": list(self.kind),
            "platform share [-]": self.platform_share,
            "dominant dof": list(self.dominant_dof),
            "cable energy fraction [-]": self.cable_energy_fraction,
            "massless freq [Hz]": self.massless_freq_hz,
            "shift from massless [-]": self.shift_from_massless,
        })
        p = self.participation
        for k, name in enumerate(DOF_NAMES):
            df[f"participation {name} [-]"] = p[:, k]
        for k, name in enumerate(DOF_NAMES):
            df[f"{name} {SHAPE_UNITS[k]}"] = self.platform_shapes[:, k]
        return df


@dataclass(frozen=True, repr=False)
class LumpedModalResult(ModalResult):
    """Modes of the lumped-mass robot: a :class:`~dynstiff.ModalResult` plus node motions.

    Attributes
    ----------
    node_shapes : list of ndarray, shape (n_modes, N_i + 1, 3)
        Displacement of every node of cable i [m] (anchor 0, the last node moves with the
        platform), for the mode vector normalised to unit total kinetic energy
        phi^T M phi = 1 (not the platform normalisation of ``platform_shapes``).

    Notes
    -----
    ``platform_shapes`` are normalised to x^T M_p x = 1 with M_p the rigid platform alone,
    like the closed-form model; ``massless_freq_hz`` comes from the lumped cables condensed
    statically onto the platform (their massless limit).
    """

    node_shapes: list = None


@dataclass(frozen=True)
class DampedModes:
    """Complex natural frequencies of the damped robot (convention e^{i omega t}).

    Attributes
    ----------
    undamped_freq_hz : ndarray, shape (n,)
        Seeds: undamped natural frequencies [Hz].
    omega : ndarray, shape (n,), complex
        Roots of det K(omega) = 0 [rad/s]; Im(omega) > 0 for a decaying mode. NaN where the
        iteration did not converge (see ``residual``) or for purely local modes.
    residual : ndarray, shape (n,)
        |smallest eigenvalue of K(omega)| / ||K|| at the returned root [-].
    """

    undamped_freq_hz: np.ndarray
    omega: np.ndarray
    residual: np.ndarray

    @property
    def freq_hz(self):
        """Damped natural frequency Re(omega) / 2 pi [Hz]."""
        return self.omega.real / _TWO_PI

    @property
    def damping_ratio(self):
        """zeta = Im(omega) / |omega| [-]."""
        return self.omega.imag / np.abs(self.omega)

    def __len__(self):
        return len(self.omega)

    def __repr__(self):
        ok = np.isfinite(self.omega)
        return (f"DampedModes({len(self)} modes, {int(ok.sum())} damped roots found, "
                f"damping ratio {np.nanmin(self.damping_ratio, initial=np.nan):.3g}.."
                f"{np.nanmax(self.damping_ratio, initial=np.nan):.3g})" if ok.any()
                else f"DampedModes({len(self)} modes, no damped root found)")

    def plot(self, ax=None):
        """Damping ratio against damped frequency: :func:`dynstiff.plot.plot_damped_modes`.
        Returns the matplotlib Figure."""
        from dynstiff.plot import plot_damped_modes
        return plot_damped_modes(self, ax=ax)

    def to_frame(self):
        """pandas DataFrame with units in column names."""
        import pandas as pd
        return pd.DataFrame({"undamped freq [Hz]": self.undamped_freq_hz,
                             "damped freq [Hz]": self.freq_hz,
                             "damping ratio [-]": self.damping_ratio,
                             "residual [-]": self.residual})
