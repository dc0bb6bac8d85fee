"""Result types of the analyses: plain data that can make a table and a figure.

Every result holds its numbers in public fields, with units in the docstrings; ``to_frame()``
gives a pandas DataFrame with units in the column names and ``plot(ax=None)`` draws it
(:mod:`dynstiff.plot`); pandas and matplotlib are imported only then.

Channels of an FRF: inputs ``LOAD_NAMES`` (forces [N] and moments [N m] on the platform about
P), outputs ``DOF_NAMES`` (translations [m] of a platform point, rotations [rad]).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._text import counted
from dynstiff.constants import DOF_NAMES, GLOBAL_SHARE, LOAD_NAMES, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError

if TYPE_CHECKING:
    from pathlib import Path
    from typing import Any

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray

__all__ = ["FRFResult", "ModalResult", "LumpedModalResult", "DampedModes", "INPUT_NAMES",
           "OUTPUT_NAMES", "RESPONSE_KINDS", "mode_kinds", "response_factor"]

_TWO_PI = 2.0 * np.pi

#: Load channels: forces [N] and moments [N m] on the platform about P.
INPUT_NAMES = LOAD_NAMES
#: Response channels: translations [m] of the chosen point and rotations [rad].
OUTPUT_NAMES = DOF_NAMES
#: FRF kinds and the power of (i omega) that turns a receptance into each.
RESPONSE_KINDS = {"receptance": 0, "mobility": 1, "accelerance": 2}


def response_factor(omega: NDArray[np.float64], kind: str) -> NDArray[np.complex128]:
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


def _span(freq_hz: NDArray[np.float64]) -> str:
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

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> m = ds.FrequencyModel(eq)
    >>> r = ds.frf(m, 2 * np.pi * np.array([0.5, 1.0]), inputs=["fx", "fz"], outputs="z")
    >>> r.inputs, r.outputs, r.H.shape
    (('fx', 'fz'), ('z',), (2, 1, 2))
    """

    freq_hz: np.ndarray
    H: np.ndarray
    inputs: tuple
    outputs: tuple
    kind: str
    damping: str = "not stated"

    def unit(self, output: str, input: str) -> str:
        """Unit of H from ``input`` (fx .. mz) to ``output`` (x .. rz) for this ``kind``,
        e.g. ``"m/N"``, ``"rad/(N m)"``, ``"m/(N s)"`` (mobility), ``"m/(N s^2)"``
        (accelerance).

        Examples
        --------
        >>> import dynstiff as ds
        >>> r = ds.frf(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), [3.0, 6.0],
        ...            inputs=["fx", "fz"], outputs="z")                  # omega [rad/s]
        >>> r.unit("z", "fz"), r.unit("rz", "mz")
        ('m/N', 'rad/(N m)')
        """
        if output not in OUTPUT_NAMES or input not in INPUT_NAMES:
            raise InvalidParameterError(
                f"unit needs an output among {OUTPUT_NAMES} and an input among "
                f"{INPUT_NAMES}, got {output!r}, {input!r}")
        num = "m" if output in OUTPUT_NAMES[:3] else "rad"
        den = ["N"] if input in INPUT_NAMES[:3] else ["N", "m"]
        den += [[], ["s"], ["s^2"]][RESPONSE_KINDS[self.kind]]
        return f"{num}/{den[0]}" if len(den) == 1 else f"{num}/({' '.join(den)})"

    def __repr__(self) -> str:
        return (f"FRFResult({self.kind}, {len(self.freq_hz)} frequencies {_span(self.freq_hz)}, "
                f"outputs {self.outputs}, inputs {self.inputs}, {self.damping})")

    def _repr_html_(self) -> str:
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

    def plot(self, ax: Axes | None = None, modes=None, pairs=None, phase: bool = False) -> Figure:
        """Magnitude (and phase) against frequency: :func:`dynstiff.plot.plot_frf`.
        Returns the matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> r = ds.frf(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), [3.0, 6.0],
        ...            inputs=["fx", "fz"], outputs="z")                  # omega [rad/s]
        >>> import matplotlib.pyplot as plt
        >>> plt.close(r.plot())
        """
        from dynstiff.plot import plot_frf
        return plot_frf(self, modes=modes, pairs=pairs, ax=ax, phase=phase)

    def to_uff(self, path: Path, node: int = 1, entity: str = "platform",
               point_node: int | None = None, binary: bool = False,
               even: bool | float = False) -> Path:
        """Write every (output, input) pair as a UFF 58 record (ASCII, or binary with exact
        doubles; ``even=True`` or a step [Hz]: on an even grid, as the records say) and
        return the path: :func:`dynstiff.io.exchange.write_uff58` (theory.md §15.3).

        Examples
        --------
        >>> import dynstiff as ds
        >>> r = ds.frf(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), [3.0, 6.0],
        ...            inputs=["fx", "fz"], outputs="z")                  # omega [rad/s]
        >>> import os, tempfile
        >>> path = os.path.join(tempfile.mkdtemp(), "frf.uff")
        >>> _ = r.to_uff(path)
        >>> ds.read_measured_frf(path).H.shape
        (2, 1, 2)
        """
        from dynstiff.io.exchange import write_uff58
        return write_uff58(self, path, node=node, entity=entity, point_node=point_node,
                           binary=binary, even=even)

    def to_control(self, name: str | None = None) -> Any:
        """python-control ``FrequencyResponseData`` (outputs x inputs x frequencies, omega
        [rad/s]), named with its channels, that ``control.bode_plot`` draws as it is; a
        channel below 1e-12 of the largest (zero by symmetry) is exact zeros:
        :func:`dynstiff.io.exchange.frf_to_control`.

        Examples
        --------
        >>> import dynstiff as ds
        >>> r = ds.frf(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), [3.0, 6.0],
        ...            inputs=["fx", "fz"], outputs="z")                  # omega [rad/s]
        >>> type(r.to_control()).__name__
        'FrequencyResponseData'
        """
        from dynstiff.io.exchange import frf_to_control
        return frf_to_control(self, name=name)

    def to_frame(self) -> pd.DataFrame:
        """Tidy pandas DataFrame: freq [Hz], input, output, magnitude |H|, phase [deg],
        real, imag (all in the row's ``unit``, see :meth:`unit`), kind.

        Examples
        --------
        >>> import dynstiff as ds
        >>> r = ds.frf(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), [3.0, 6.0],
        ...            inputs=["fx", "fz"], outputs="z")                  # omega [rad/s]
        >>> df = r.to_frame(); len(df), list(df.columns)[:3]
        (4, ['freq [Hz]', 'input', 'output'])
        """
        import pandas as pd
        n, no, ni = self.H.shape
        f = np.repeat(self.freq_hz, no * ni)
        out = np.tile(np.repeat(self.outputs, ni), n)
        inp = np.tile(self.inputs, n * no)
        units = np.tile([self.unit(o, i) for o in self.outputs for i in self.inputs], n)
        h = self.H.reshape(-1)
        return pd.DataFrame({"freq [Hz]": f, "input": inp, "output": out,
                             "magnitude": np.abs(h), "phase [deg]": np.degrees(np.angle(h)),
                             "real": h.real, "imag": h.imag, "unit": units, "kind": self.kind})


def mode_kinds(platform_share: NDArray[np.float64]) -> tuple[str, ...]:
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

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> res = ds.modes(ds.FrequencyModel(eq), n_modes=3)
    >>> [f"{f:.4f}" for f in res.freq_hz], res.kind
    (['2.2061', '2.3592', '2.9907'], ('global', 'global', 'global'))
    >>> [f"{s:.3f}" for s in res.platform_share], res.dominant_dof    # properties
    (['0.989', '0.944', '0.650'], ('z', 'y', 'x'))
    >>> print(res.participation.shape, [f"{s:+.4f}" for s in res.shift_from_massless])
    (3, 6) ['-0.0050', '-0.0163', '-0.0503']
    """

    freq_hz: np.ndarray
    platform_shapes: np.ndarray
    cable_energy_fraction: np.ndarray
    cable_energy: np.ndarray
    kind: tuple = None
    massless_freq_hz: np.ndarray = None
    platform_mass: np.ndarray = None

    def __post_init__(self) -> None:
        if self.kind is None:
            object.__setattr__(self, "kind", mode_kinds(self.platform_share))
        if self.massless_freq_hz is None:
            object.__setattr__(self, "massless_freq_hz", np.full(len(self.freq_hz), np.nan))

    @property
    def platform_share(self) -> NDArray[np.float64]:
        """Platform kinetic energy / total kinetic energy of each mode [-], shape (n,)."""
        return np.clip(1.0 - np.asarray(self.cable_energy_fraction, dtype=float), 0.0, 1.0)

    @cached_property
    def participation(self) -> NDArray[np.float64]:
        """Effective-mass fraction of each free platform DOF in each mode [-], shape (n, 6):
        p_kj = (M x_k)_j^2 s_k / M_jj with x_k the shape at unit platform kinetic energy,
        s_k its platform share and M ``platform_mass`` (theory.md §12.1). Over all the modes
        of the robot each column sums to 1; held DOFs are 0 (NaN without
        ``platform_mass``). Computed once (the result is immutable), read-only.
        """
        p = np.full((len(self.freq_hz), 6), np.nan)
        if self.platform_mass is not None:
            M = np.asarray(self.platform_mass, dtype=float)
            d, g = np.diag(M), np.asarray(self.platform_shapes, dtype=float) @ M
            with np.errstate(invalid="ignore", divide="ignore"):
                p = np.where(d > 0, g**2 * self.platform_share[:, None]
                             / np.where(d > 0, d, 1.0), 0.0)
        p.setflags(write=False)
        return p

    @property
    def dominant_dof(self) -> tuple[str, ...]:
        """Name of the DOF each mode moves most, by participation ("-" for none)."""
        p = self.participation
        return tuple(DOF_NAMES[int(np.argmax(r))] if np.nanmax(r, initial=0) > 0 else "-"
                     for r in np.nan_to_num(p))

    @property
    def shift_from_massless(self) -> NDArray[np.float64]:
        """Relative shift of each paired mode's frequency from its massless-cable mode [-]."""
        return self.freq_hz / self.massless_freq_hz - 1.0

    def __len__(self) -> int:
        return len(self.freq_hz)

    def __repr__(self) -> str:
        n = {c: sum(k == c for k in self.kind) for c in ("global", "mixed", "local")}
        return (f"{type(self).__name__}({counted(len(self), 'mode')} {_span(self.freq_hz)}: "
                f"{n['global']} global, {n['mixed']} mixed, {n['local']} local)")

    def _repr_html_(self) -> str:
        """Jupyter display: frequency, kind, platform share and dominant DOF of each mode."""
        from dynstiff._html import html_table
        rows = zip(range(1, len(self) + 1), self.freq_hz, self.kind, self.platform_share,
                   self.dominant_dof)
        return html_table(repr(self), ["mode", "freq [Hz]", "kind", "platform share [-]",
                                       "dominant dof"], rows)

    def plot(self, ax: Axes | None = None) -> Figure:
        """Frequencies against platform share, coloured by kind:
        :func:`dynstiff.plot.plot_modes`. Returns the matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> res = ds.modes(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), n_modes=3)
        >>> import matplotlib.pyplot as plt
        >>> plt.close(res.plot())
        """
        from dynstiff.plot import plot_modes
        return plot_modes(self, ax=ax)

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame, one row per mode, units in the column names: frequency, kind,
        platform share, the participation of each DOF, the paired massless mode and the
        platform shape (labelled for its energy normalisation, ``SHAPE_UNITS``).

        Examples
        --------
        >>> import dynstiff as ds
        >>> res = ds.modes(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()), n_modes=3)
        >>> df = res.to_frame(); len(df), list(df.columns)[:2]
        (3, ['mode', 'freq [Hz]'])
        """
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

    Examples
    --------
    >>> import dynstiff as ds
    >>> res = ds.modes(ds.build_model(ds.load_scene("cogiro").equilibrium(), "lumped", 4), 2)
    >>> type(res).__name__, len(res.node_shapes)
    ('LumpedModalResult', 8)
    >>> print(f"{res.freq_hz[0]:.2f} Hz")
    2.21 Hz
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

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.load_scene("cogiro").equilibrium()
    >>> d = ds.damped_modes(ds.FrequencyModel(eq, platform_damping_ratio=0.02), n_modes=2)
    >>> print([f"{w:.3f}" for w in d.omega])
    ['13.864+0.277j', '14.827+0.289j']
    >>> [f"{f:.4f}" for f in d.freq_hz], [f"{z:.4f}" for z in d.damping_ratio]
    (['2.2065', '2.3597'], ['0.0200', '0.0195'])
    """

    undamped_freq_hz: np.ndarray
    omega: np.ndarray
    residual: np.ndarray

    @property
    def freq_hz(self) -> NDArray[np.float64]:
        """Damped natural frequency Re(omega) / 2 pi [Hz]."""
        return self.omega.real / _TWO_PI

    @property
    def damping_ratio(self) -> NDArray[np.float64]:
        """zeta = Im(omega) / |omega| [-]; NaN where undefined (omega NaN or 0)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.omega.imag / np.abs(self.omega)

    def __len__(self) -> int:
        return len(self.omega)

    def __repr__(self) -> str:
        ok, z = np.isfinite(self.omega), self.damping_ratio[np.isfinite(self.damping_ratio)]
        n, found = counted(len(self), "mode"), counted(int(ok.sum()), "damped root")
        span = f"{z.min():.3g}..{z.max():.3g}" if z.size else "undefined"
        return (f"DampedModes({n}, {found} found, damping ratio {span})" if ok.any() else
                f"DampedModes({n}, no damped root found)")

    def plot(self, ax: Axes | None = None) -> Figure:
        """Damping ratio against damped frequency: :func:`dynstiff.plot.plot_damped_modes`.
        Returns the matplotlib Figure.

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> d = ds.damped_modes(ds.FrequencyModel(eq, platform_damping_ratio=0.02), n_modes=2)
        >>> import matplotlib.pyplot as plt
        >>> plt.close(d.plot())
        """
        from dynstiff.plot import plot_damped_modes
        return plot_damped_modes(self, ax=ax)

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame with units in column names.

        Examples
        --------
        >>> import dynstiff as ds
        >>> eq = ds.load_scene("cogiro").equilibrium()
        >>> d = ds.damped_modes(ds.FrequencyModel(eq, platform_damping_ratio=0.02), n_modes=2)
        >>> list(d.to_frame().columns)
        ['undamped freq [Hz]', 'damped freq [Hz]', 'damping ratio [-]', 'residual [-]']
        """
        import pandas as pd
        return pd.DataFrame({"undamped freq [Hz]": self.undamped_freq_hz,
                             "damped freq [Hz]": self.freq_hz,
                             "damping ratio [-]": self.damping_ratio,
                             "residual [-]": self.residual})
