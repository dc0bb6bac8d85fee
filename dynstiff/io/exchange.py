"""FRFs out to the tools of experimental modal analysis and control design.

* Universal File Format, dataset 58 ("function at nodal DOF"), written through pyuff: one
  record per (output, input) pair, function type 4 (frequency response function), the kind in
  the ordinate's specific data type (8 displacement: receptance, 11 velocity: mobility,
  12 acceleration: accelerance) over the denominator's 13 (excitation force), abscissa 18
  (frequency, Hz), with SI unit exponents and labels, double-precision complex data on an
  uneven abscissa (every frequency listed). ASCII records carry 12 significant digits of H
  but only 6 of each frequency (the format's E13.5 field); binary records (``binary=True``)
  carry both exactly. Directions follow UFF's DOF codes:
  1, 2, 3 translation (force) along x, y, z; 4, 5, 6 rotation (moment) about x, y, z.
* python-control: a :class:`control.FrequencyResponseData`, response of shape
  (n_outputs, n_inputs, n_frequencies) over omega [rad/s].

Both take any FRF result with ``freq_hz``, ``H`` (n, n_out, n_in), ``inputs``, ``outputs``
and ``kind`` (:class:`dynstiff.FRFResult`); the libraries are imported only here, when asked
(``pip install "dynstiff[exchange]"``). See theory.md §15.3.
"""

import numpy as np

from dynstiff._validate import count, flag
from dynstiff.constants import DOF_NAMES, LOAD_NAMES
from dynstiff.errors import DynstiffError, InvalidParameterError

__all__ = ["MissingDependencyError", "UFF_DATA_TYPES", "ZERO_FLOOR", "even_grid",
           "frf_to_control", "require", "uff58_records", "write_uff58", "zero_below_floor"]

#: UFF specific data type of the response (numerator) for each FRF kind.
UFF_DATA_TYPES = {"receptance": 8, "mobility": 11, "accelerance": 12}
_UFF_FORCE = 13           # excitation force (a moment is a force on a rotational DOF)
_UFF_FREQUENCY = 18
_UFF_FRF = 4
_TIME = {"receptance": "", "mobility": "/s", "accelerance": "/s^2"}


class MissingDependencyError(DynstiffError, ImportError):
    """An optional library is not installed; the message names the extra that brings it."""

def require(module):
    """Import an optional library of the ``exchange`` extra, or raise
    :class:`MissingDependencyError` naming it."""
    import importlib
    try:
        return importlib.import_module(module)
    except ImportError:
        raise MissingDependencyError(
            f"{module} is needed for this: pip install \"dynstiff[exchange]\"") from None


def even_grid(freq_hz, H, even):
    """The FRF ``H`` (n, n_out, n_in) on an even frequency grid (theory.md §15.3).

    Parameters
    ----------
    freq_hz : ndarray, shape (n,)
        The result's grid, ascending [Hz] (e.g. uniform and refined at the modes, §12.3).
    H : ndarray, shape (n, n_out, n_in)
    even : True or float
        True: the step of the grid's uniform part (its most common spacing); a float: the
        step [Hz].

    Returns
    -------
    f : ndarray, shape (m,)
        f[0] + k step up to the grid's last frequency [Hz].
    He : ndarray, shape (m, n_out, n_in)
        Linear interpolation of the real and imaginary parts: exact where a point of the
        even grid is a point of the result's grid (the uniform part's points, with
        ``even=True``).
    step : float
        [Hz]

    Examples
    --------
    >>> f = np.array([0.0, 1.0, 2.0, 2.01, 2.1, 3.0, 4.0, 5.0])   # refined after 2 Hz
    >>> H = (f + 1j * f)[:, None, None]
    >>> fe, He, step = even_grid(f, H, True)
    >>> fe.tolist(), step, bool(np.all(He[:, 0, 0] == fe + 1j * fe))
    ([0.0, 1.0, 2.0, 3.0, 4.0, 5.0], 1.0, True)
    """
    f = np.asarray(freq_hz, dtype=float)
    span = f[-1] - f[0]
    if even is True:
        d = np.diff(f)
        key = np.round(d / span, 9)
        values, counts = np.unique(key, return_counts=True)
        step = float(d[key == values[np.argmax(counts)]].mean())
    elif isinstance(even, bool | np.bool_) or not isinstance(even, int | float | np.floating):
        raise InvalidParameterError(f"even must be True or a step in Hz, got {even!r}")
    else:
        step = float(even)
    if not (np.isfinite(step) and 0 < step <= span):
        raise InvalidParameterError(f"even: the step must be positive and at most the band "
                                    f"{span:g} Hz, got {step!r}")
    n = int(np.floor(span / step * (1 + 1e-12))) + 1
    fe = f[0] + step * np.arange(n)
    fe[-1] = min(fe[-1], f[-1])
    # snap the even points that are points of the grid (to rounding) onto them
    j = np.clip(np.searchsorted(f, fe), 0, f.size - 1)
    near = np.where(np.abs(f[j - 1] - fe) < np.abs(f[j] - fe), j - 1, j)
    on = np.abs(f[near] - fe) <= 1e-9 * max(span, 1e-300)
    Hf = np.asarray(H).reshape(f.size, -1)
    He = np.empty((n, Hf.shape[1]), dtype=complex)
    for c in range(Hf.shape[1]):
        He[:, c] = (np.interp(fe, f, Hf[:, c].real) + 1j * np.interp(fe, f, Hf[:, c].imag))
    He[on] = Hf[near[on]]
    return fe, He.reshape((n,) + np.asarray(H).shape[1:]), step


def uff58_records(result, node=1, entity="platform", point_node=None, binary=False,
                  even=False):
    """UFF 58 records (pyuff dictionaries) of every (output, input) pair of an FRF result.

    Parameters
    ----------
    result : FRFResult
    node : int
        Node number of the reference (the load point P).
    entity : str
        Entity name written for response and reference (at most 10 characters, the field's
        width; a longer one is refused, not cut).
    point_node : int, optional
        Node number of the response point (default ``node``).
    binary : bool
        Binary records (exact doubles) instead of ASCII.
    even : bool or float
        False: the result's own grid (uneven where it was refined at the modes, §12.3);
        True or a step [Hz]: resampled on an even grid (:func:`even_grid`), which many
        modal-analysis tools need; the records say so (their third ID line).

    Returns
    -------
    list of dict, one per (output, input) pair, outputs outer
    """
    if result.kind not in UFF_DATA_TYPES:
        raise InvalidParameterError(f"kind must be one of {tuple(UFF_DATA_TYPES)}, got "
                                    f"{result.kind!r}")
    node = count("node", node)
    point_node = node if point_node is None else count("point_node", point_node)
    binary = flag("binary", binary)
    if not isinstance(entity, str) or len(entity) > 10:
        raise InvalidParameterError(f"entity must be a name of at most 10 characters (the "
                                    f"format's field), got {entity!r}")
    f = np.asarray(result.freq_hz, dtype=float)
    H = np.asarray(result.H)
    if not np.all(np.isfinite(H)):
        raise InvalidParameterError("the FRF holds inf or NaN (an exact pole): UFF 58 holds "
                                    "finite numbers only; evaluate beside the pole")
    if f.size < 2:
        raise InvalidParameterError(f"a UFF 58 record needs at least 2 frequencies, got "
                                    f"{f.size}")
    id3 = "NONE"
    if even is not False:
        f, H, step = even_grid(f, H, even)
        id3 = f"resampled on an even grid, step {step:.9g} Hz, linear interpolation"
    records = []
    for o, out in enumerate(result.outputs):
        rot_out = DOF_NAMES.index(out) >= 3
        for i, inp in enumerate(result.inputs):
            moment = LOAD_NAMES.index(inp) >= 3
            num = ("rad" if rot_out else "m") + _TIME[result.kind]
            den = "N m" if moment else "N"
            records.append({
                "type": 58, "binary": int(binary), "func_type": _UFF_FRF,
                "id1": f"dynstiff {result.kind} {out}/{inp}", "id2": f"{num}/{den}",
                "id3": id3, "id4": "NONE", "id5": "NONE",
                "rsp_ent_name": entity, "rsp_node": point_node,
                "rsp_dir": DOF_NAMES.index(out) + 1,
                "ref_ent_name": entity, "ref_node": node,
                "ref_dir": LOAD_NAMES.index(inp) + 1,
                "abscissa_spacing": int(even is not False),
                "abscissa_spec_data_type": _UFF_FREQUENCY,
                "abscissa_axis_lab": "Frequency", "abscissa_axis_units_lab": "Hz",
                "ordinate_spec_data_type": UFF_DATA_TYPES[result.kind],
                "ordinate_len_unit_exp": 0 if rot_out else 1, "ordinate_force_unit_exp": 0,
                "ordinate_axis_lab": out, "ordinate_axis_units_lab": num,
                "orddenom_spec_data_type": _UFF_FORCE,
                "orddenom_len_unit_exp": 1 if moment else 0, "orddenom_force_unit_exp": 1,
                "orddenom_axis_lab": inp, "orddenom_axis_units_lab": den,
                "data": np.ascontiguousarray(H[:, o, i], dtype=complex), "x": f.copy(),
            })
    return records


def write_uff58(result, path, **kw):
    """Write an FRF result to a UFF file (dataset 58; keywords: :func:`uff58_records`).

    The records are built (and the data checked) first; then they are written to a
    temporary file beside ``path`` that replaces it in one step
    (:func:`dynstiff.io.files.atomic_path`), so an error leaves an existing file as it was.
    Returns the path.
    """
    pyuff = require("pyuff")
    from pathlib import Path

    from dynstiff.io.files import atomic_path
    path = Path(path)
    records = uff58_records(result, **kw)
    with atomic_path(path) as tmp:
        pyuff.UFF(tmp).write_sets(records, mode="add")
    return path


#: Relative floor of the python-control hand-offs: an FRF channel whose largest magnitude is
#: below this times the largest of all channels is written as exact zeros (a cross term that
#: vanishes by symmetry and holds only rounding, e.g. 1e-25 m/N beside 1e-3 m/N).
ZERO_FLOOR = 1e-12


def zero_below_floor(H, floor=ZERO_FLOOR):
    """``H`` (n, n_out, n_in) with every channel (o, i) whose largest |H| over frequency is
    at most ``floor`` times the largest |H| of all channels set to exact zeros (a copy)."""
    H = np.array(H, dtype=complex)
    peak = np.abs(H).max(axis=0) if H.size else np.zeros(H.shape[1:])
    top = float(peak.max()) if peak.size else 0.0
    H[:, peak <= floor * top] = 0.0
    return H


def frf_to_control(result, name=None):
    """:class:`control.FrequencyResponseData` of an FRF result: response (n_out, n_in, n)
    over omega = 2 pi freq_hz [rad/s], inputs and outputs named after the channels, the
    system named (``name``, default "dynstiff <kind>"), so that ``control.bode_plot`` draws
    it as it is (theory.md §15.3).

    A channel whose largest magnitude is at most :data:`ZERO_FLOOR` (1e-12) times the
    largest of all channels is written as exact zeros: at a symmetric pose the cross terms
    that vanish by symmetry hold only rounding, whose phase is noise.

    Examples
    --------
    >>> import numpy as np
    >>> from dynstiff.results import FRFResult
    >>> H = np.zeros((3, 2, 2), complex); H[:, 0, 0] = 1e-3; H[:, 1, 1] = 2e-3
    >>> H[:, 0, 1] = 1e-25
    >>> r = FRFResult(np.array([1.0, 2.0, 3.0]), H, ("fx", "fz"), ("x", "z"), "receptance")
    >>> sys = frf_to_control(r)
    >>> sys.name, sys.input_labels, complex(sys.frdata[0, 1, 0])
    ('dynstiff receptance', ['fx', 'fz'], 0j)
    """
    if name is not None and not isinstance(name, str):
        raise InvalidParameterError(f"name must be a str or None, got {name!r}")
    ct = require("control")
    H = np.moveaxis(zero_below_floor(result.H), 0, -1)
    omega = 2 * np.pi * np.asarray(result.freq_hz, dtype=float)
    return ct.FrequencyResponseData(H, omega, inputs=list(result.inputs),
                                    outputs=list(result.outputs),
                                    name=name or f"dynstiff {result.kind}")
