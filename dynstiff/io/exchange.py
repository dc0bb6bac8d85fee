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

from dynstiff.constants import DOF_NAMES, LOAD_NAMES
from dynstiff.errors import DynstiffError, InvalidParameterError

__all__ = ["MissingDependencyError", "UFF_DATA_TYPES", "frf_to_control", "require",
           "uff58_records", "write_uff58"]

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


def uff58_records(result, node=1, entity="platform", point_node=None, binary=False):
    """UFF 58 records (pyuff dictionaries) of every (output, input) pair of an FRF result.

    Parameters
    ----------
    result : FRFResult
    node : int
        Node number of the reference (the load point P).
    entity : str
        Entity name written for response and reference (at most 10 characters).
    point_node : int, optional
        Node number of the response point (default ``node``).
    binary : bool
        Binary records (exact doubles) instead of ASCII.

    Returns
    -------
    list of dict, one per (output, input) pair, outputs outer
    """
    if result.kind not in UFF_DATA_TYPES:
        raise InvalidParameterError(f"kind must be one of {tuple(UFF_DATA_TYPES)}, got "
                                    f"{result.kind!r}")
    f = np.asarray(result.freq_hz, dtype=float)
    H = np.asarray(result.H)
    if not np.all(np.isfinite(H)):
        raise InvalidParameterError("the FRF holds inf or NaN (an exact pole): UFF 58 holds "
                                    "finite numbers only; evaluate beside the pole")
    if f.size < 2:
        raise InvalidParameterError(f"a UFF 58 record needs at least 2 frequencies, got "
                                    f"{f.size}")
    point_node = node if point_node is None else point_node
    records = []
    for o, out in enumerate(result.outputs):
        rot_out = DOF_NAMES.index(out) >= 3
        for i, inp in enumerate(result.inputs):
            moment = LOAD_NAMES.index(inp) >= 3
            num = ("rad" if rot_out else "m") + _TIME[result.kind]
            den = "N m" if moment else "N"
            records.append({
                "type": 58, "binary": int(bool(binary)), "func_type": _UFF_FRF,
                "id1": f"dynstiff {result.kind} {out}/{inp}", "id2": f"{num}/{den}",
                "id3": "NONE", "id4": "NONE", "id5": "NONE",
                "rsp_ent_name": entity[:10], "rsp_node": int(point_node),
                "rsp_dir": DOF_NAMES.index(out) + 1,
                "ref_ent_name": entity[:10], "ref_node": int(node),
                "ref_dir": LOAD_NAMES.index(inp) + 1,
                "abscissa_spacing": 0, "abscissa_spec_data_type": _UFF_FREQUENCY,
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


def frf_to_control(result):
    """:class:`control.FrequencyResponseData` of an FRF result: response (n_out, n_in, n)
    over omega = 2 pi freq_hz [rad/s], inputs and outputs named after the channels."""
    ct = require("control")
    H = np.moveaxis(np.asarray(result.H), 0, -1)
    omega = 2 * np.pi * np.asarray(result.freq_hz, dtype=float)
    return ct.FrequencyResponseData(H, omega, inputs=list(result.inputs),
                                    outputs=list(result.outputs))
