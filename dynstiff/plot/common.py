"""What every figure shares: the colours and legend labels of the mode classes (global,
mixed, local by platform share, docs/theory.md §12.1), a figure and axes, and argument
checks.
"""

import numpy as np

from dynstiff.constants import GLOBAL_SHARE, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError

COLORS = {"global": "tab:red", "mixed": "tab:purple", "local": "tab:blue"}
CATEGORY_LABELS = {
    "global": f"global mode (platform share >= {GLOBAL_SHARE:.0%})",
    "mixed": f"mixed mode (platform share {PLATFORM_SHARE_THRESHOLD:.0%}-{GLOBAL_SHARE:.0%})",
    "local": f"local mode (platform share < {PLATFORM_SHARE_THRESHOLD:.0%})"}


def mode_categories(modes):
    """"global" / "mixed" / "local" of each mode of a ModalResult: its ``kind``, the one
    labelling by platform share (docs/theory.md §12.1)."""
    return tuple(modes.kind)


def figure_axes(ax=None, figsize=(8, 4.5)):
    """(figure, axes): a new figure when ``ax`` is None, else ``ax`` and its figure."""
    if ax is None:
        import matplotlib.pyplot as plt
        return plt.subplots(figsize=figsize)
    from matplotlib.axes import Axes
    if not isinstance(ax, Axes):
        raise InvalidParameterError(f"ax must be a matplotlib Axes, got {type(ax).__name__}")
    return ax.figure, ax


def require(obj, name, attrs, expected):
    """Raise InvalidParameterError naming ``name`` unless ``obj`` has every attribute."""
    missing = [a for a in attrs if not hasattr(obj, a)]
    if missing:
        raise InvalidParameterError(
            f"{name} must be a {expected}, got {type(obj).__name__} (no {missing[0]!r})")


def mode_frequencies(modes, name="modes"):
    """(freq_hz, kind) of a ModalResult-like object, or of an array of frequencies [Hz]
    (kind None)."""
    if hasattr(modes, "freq_hz"):
        f = np.asarray(modes.freq_hz, dtype=float).reshape(-1)
        kind = tuple(getattr(modes, "kind", ())) or None
        if kind is not None and len(kind) != f.size:
            raise InvalidParameterError(
                f"{name}: kind has {len(kind)} entries for {f.size} frequencies")
        return f, kind
    try:
        f = np.asarray(modes, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"{name} must be a ModalResult or frequencies [Hz], got "
            f"{type(modes).__name__}") from None
    if not np.all(np.isfinite(f)):
        raise InvalidParameterError(f"{name} must be finite frequencies [Hz], got {f.tolist()}")
    return f, None
