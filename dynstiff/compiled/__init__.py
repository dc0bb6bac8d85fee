"""Compiled (numba) kernels: arrays in, arrays out.

Nothing in this package imports the rest of dynstiff; every kernel has a numpy counterpart
beside the physics it computes, which stays the reference the kernel is tested against.
Callers ask :func:`load` for a kernel module and take the numpy path when it returns None
(numba not installed, ``pip install "dynstiff[fast]"``, or switched off with the
environment variable ``DYNSTIFF_DISABLE_NUMBA=1``). Kernels compile on first use and are
cached on disk.

========== ==============================================================================
module     kernels
========== ==============================================================================
dsm        the "dsm" rung's K(omega) fused with an FRF solve (undamped or hysteretic) or a
           Wittrick-Williams count
dsm_search the "dsm" rung's whole Wittrick-Williams search after its seed grid
catenary   Newton on many taut elastic catenaries at once (inverse statics)
statics    the inverse statics' fixed point of directions and tension distribution
chain      forces, energies and small solves of the lumped-mass chains (time domain)
chain_run  whole explicit and implicit time-domain runs of the lumped-mass robot
========== ==============================================================================
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

__all__ = ["KERNELS", "load"]

#: The kernel modules of this package.
KERNELS = ("dsm", "dsm_search", "catenary", "statics", "chain", "chain_run")


@functools.cache
def load(name: str) -> Any | None:
    """The compiled kernel module ``name`` (one of :data:`KERNELS`), or None without numba.

    Examples
    --------
    >>> from dynstiff import compiled
    >>> kernels = compiled.load("dsm")      # None when numba is not installed
    >>> kernels is None or hasattr(kernels, "dsm_receptance")
    True
    """
    if name not in KERNELS:
        raise ValueError(f"name must be one of {KERNELS}, got {name!r}")
    if os.environ.get("DYNSTIFF_DISABLE_NUMBA", "") not in ("", "0"):
        return None
    if importlib.util.find_spec("numba") is None:
        return None
    return importlib.import_module(f"dynstiff.compiled.{name}")
