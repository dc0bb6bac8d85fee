"""Measured FRFs in: read from UFF 58 records (function type 4, as
:meth:`dynstiff.FRFResult.to_uff` writes them) or from the CSV of
:meth:`dynstiff.FRFResult.to_frame`, and compared with a model's (theory.md §15.5).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff.constants import DOF_NAMES
from dynstiff.errors import InvalidParameterError
from dynstiff.results import FRFResult

if TYPE_CHECKING:
    from pathlib import Path

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike, NDArray

    from dynstiff.models.base import PlatformModel

__all__ = ["FRFComparison", "compare_frf", "read_measured_frf"]

def read_measured_frf(path: str | Path) -> FRFResult:
    """Read measured FRFs: UFF 58 records (``.uff``/``.unv``, through pyuff) or the CSV of
    :meth:`FRFResult.to_frame`.

    Returns
    -------
    FRFResult
        Channels from the UFF direction codes (1-6: x..rz for responses, fx..mz for loads;
        a negative code, a measurement along the negative axis, flips the sign of its data);
        kind from the ordinate data type (8, 11, 12). All records must share one frequency
        axis and one kind; any other dataset 58 function type (4 only), data type or
        abscissa (frequency) is refused naming its record.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> r = ds.frf(m, 2 * np.pi * np.array([0.5, 1.0]), inputs="fz", outputs="z")
    >>> path = os.path.join(tempfile.mkdtemp(), "frf.csv")
    >>> r.to_frame().to_csv(path, index=False)
    >>> back = ds.read_measured_frf(path)
    >>> back.inputs, back.outputs, bool(np.allclose(back.H, r.H))
    (('fz',), ('z',), True)
    """
    from pathlib import Path

    from dynstiff.io.files import input_file
    path = Path(input_file(path))
    if path.suffix.lower() == ".csv":
        return _frf_from_csv(path)
    from dynstiff.io.exchange import UFF_DATA_TYPES, require
    pyuff = require("pyuff")
    sets = pyuff.UFF(str(path)).read_sets()
    sets = [sets] if isinstance(sets, dict) else list(sets)
    sets = [(k, s) for k, s in enumerate(sets, start=1) if s.get("type") == 58]
    kinds = {v: k for k, v in UFF_DATA_TYPES.items()}
    loads = ("fx", "fy", "fz", "mx", "my", "mz")
    for k, s in sets:
        where = f"{path}: record {k} ({s.get('id1', '')!r})"
        for key, known, what in (("func_type", (4,), "function type"),
                                 ("ordinate_spec_data_type", tuple(kinds), "data type"),
                                 ("abscissa_spec_data_type", (0, 18), "abscissa type")):
            if s.get(key, 0 if key.startswith("abscissa") else None) not in known:
                raise InvalidParameterError(
                    f"{where}: {what} {s.get(key)!r} is not one dynstiff reads (one of "
                    f"{known}: an FRF of receptance, mobility or accelerance over frequency)")
        for key in ("rsp_dir", "ref_dir"):
            if not 1 <= abs(int(s[key])) <= 6:
                raise InvalidParameterError(f"{where}: direction {key}={s[key]} is not one "
                                            f"of the 6 platform DOFs (+-1 to +-6)")
    if not sets:
        raise InvalidParameterError(f"{path}: no UFF 58 frequency response record "
                                    f"(function type 4)")
    kind = {kinds[s["ordinate_spec_data_type"]] for _, s in sets}
    f = np.asarray(sets[0][1]["x"], dtype=float)
    if len(kind) > 1 or any(np.asarray(s["x"]).shape != f.shape
                            or not np.allclose(s["x"], f, rtol=1e-5) for _, s in sets):
        raise InvalidParameterError(f"{path}: the records mix kinds {sorted(kind)} or "
                                    f"frequency axes; give one kind on one axis")
    pair = [(DOF_NAMES[abs(int(s["rsp_dir"])) - 1], loads[abs(int(s["ref_dir"])) - 1])
            for _, s in sets]
    outs, ins = list(dict.fromkeys(o for o, _ in pair)), list(dict.fromkeys(i for _, i in pair))
    H = np.full((f.size, len(outs), len(ins)), np.nan + 0j)
    for n, ((k, s), (o, i)) in enumerate(zip(sets, pair)):
        if (o, i) in pair[:n]:
            raise InvalidParameterError(f"{path}: record {k} ({s.get('id1', '')!r}): a "
                                        f"second record of {o}/{i}")
        # a response or a load along a negative direction (-1..-6): the sign is honoured
        sign = np.sign(int(s["rsp_dir"])) * np.sign(int(s["ref_dir"]))
        H[:, outs.index(o), ins.index(i)] = sign * np.asarray(s["data"], dtype=complex)
    return FRFResult(freq_hz=f, H=H, inputs=tuple(ins), outputs=tuple(outs), kind=kind.pop())


def _frf_from_csv(path: Path) -> FRFResult:
    import pandas as pd
    df = pd.read_csv(path)
    need = {"freq [Hz]", "input", "output", "real", "imag"}
    if not need <= set(df.columns):
        raise InvalidParameterError(f"{path}: FRF CSV needs the columns {sorted(need)} (as "
                                    f"FRFResult.to_frame writes them), found {list(df.columns)}")
    f = np.unique(df["freq [Hz]"].to_numpy(float))
    outs = list(dict.fromkeys(df["output"]))
    ins = list(dict.fromkeys(df["input"]))
    H = np.full((f.size, len(outs), len(ins)), np.nan + 0j)
    k = np.searchsorted(f, df["freq [Hz]"].to_numpy(float))
    o = np.array([outs.index(v) for v in df["output"]])
    i = np.array([ins.index(v) for v in df["input"]])
    H[k, o, i] = df["real"].to_numpy(float) + 1j * df["imag"].to_numpy(float)
    kind = str(df["kind"].iloc[0]) if "kind" in df else "receptance"
    return FRFResult(freq_hz=f, H=H, inputs=tuple(ins), outputs=tuple(outs), kind=kind)


@dataclass(frozen=True)
class FRFComparison:
    """Measured and model FRFs on the measured frequencies and channels.

    Attributes
    ----------
    measured, model : FRFResult
    """

    measured: FRFResult
    model: FRFResult

    @property
    def log_magnitude_error(self) -> NDArray[np.float64]:
        """RMS over frequency of log10 |H_model / H_measured| per (output, input) [decades],
        shape (n_out, n_in)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.log10(np.abs(self.model.H) / np.abs(self.measured.H))
        return np.sqrt(np.nanmean(r**2, axis=0))

    def __repr__(self) -> str:
        return (f"FRFComparison({self.measured.kind}, {len(self.measured.freq_hz)} frequencies, "
                f"rms log10 magnitude error {np.nanmax(self.log_magnitude_error):.3g} decades)")

    def plot(self, ax: Axes | None = None) -> Figure:
        """Overlay of measured (dots) and model (line) magnitudes, every channel pair;
        returns the Figure."""
        import matplotlib.pyplot as plt
        if ax is None:
            fig, ax = plt.subplots(figsize=(7, 4))
        fig = ax.figure
        for o, out in enumerate(self.model.outputs):
            for i, inp in enumerate(self.model.inputs):
                c = f"C{(o * len(self.model.inputs) + i) % 10}"
                ax.semilogy(self.measured.freq_hz, np.abs(self.measured.H[:, o, i]), ".",
                            color=c, ms=3, label=f"{out}/{inp} measured")
                ax.semilogy(self.model.freq_hz, np.abs(self.model.H[:, o, i]), "-", color=c,
                            lw=1, label=f"{out}/{inp} model")
        ax.set(xlabel="frequency [Hz]", ylabel=f"|H| ({self.model.kind})")
        ax.legend(fontsize=7, ncol=2)
        return fig

    def to_frame(self) -> pd.DataFrame:
        """Measured and model values side by side (tidy, one row per frequency and pair)."""
        a, b = self.measured.to_frame(), self.model.to_frame()
        a["model magnitude"] = b["magnitude"].to_numpy()
        a["model phase [deg]"] = b["phase [deg]"].to_numpy()
        return a


def compare_frf(model: PlatformModel, measured: FRFResult,
                point: ArrayLike | None = None) -> FRFComparison:
    """Model FRFs at the measured frequencies and channels, with the measured ones.

    Parameters
    ----------
    model : model of any rung
    measured : FRFResult (e.g. :func:`read_measured_frf`)
    point : array_like, shape (3,), optional
        Platform point of the measured translations [m, platform frame] (default P).

    Returns
    -------
    FRFComparison

    Examples
    --------
    >>> import numpy as np
    >>> import dynstiff as ds
    >>> m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    >>> r = ds.frf(m, 2 * np.pi * np.array([0.5, 1.0]), inputs="fz", outputs="z")
    >>> c = ds.compare_frf(m, r)                    # the model against its own FRF
    >>> print(c)
    FRFComparison(receptance, 2 frequencies, rms log10 magnitude error 0 decades)
    """
    from dynstiff.analyses.frf import frf
    if not isinstance(measured, FRFResult):
        raise InvalidParameterError(f"measured must be an FRFResult, got "
                                    f"{type(measured).__name__}")
    res = frf(model, 2 * np.pi * measured.freq_hz, inputs=list(measured.inputs),
              outputs=list(measured.outputs), point=point, kind=measured.kind)
    return FRFComparison(measured=measured, model=res)
