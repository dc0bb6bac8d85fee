"""Exception and warning types of dynstiff.

Every error names the offending argument, what was expected and what was found.
The exceptions subclass built-ins so that generic handlers keep working.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from types import FrameType

__all__ = [
    "DynstiffError",
    "InvalidParameterError",
    "ConvergenceError",
    "SlackCableError",
    "InfeasiblePoseError",
    "UnsupportedAnalysisError",
    "DynstiffWarning",
    "PoleWarning",
    "ClosedFormWarning",
    "ResonanceWarning",
    "CalibrationWarning",
    "CalibrationError",
    "Interrupted",
]


class DynstiffError(Exception):
    """Base class of all dynstiff errors.

    Examples
    --------
    >>> import dynstiff as ds
    >>> try:
    ...     ds.Cable(mass_per_length=-1.0, EA=1e6)
    ... except ds.DynstiffError as exc:
    ...     print(type(exc).__name__)
    InvalidParameterError
    """


class DynstiffWarning(Warning):
    """Base class of all dynstiff warnings (each also subclasses the built-in warning of its
    kind: RuntimeWarning or UserWarning).

    Examples
    --------
    >>> import dynstiff as ds
    >>> issubclass(ds.PoleWarning, ds.DynstiffWarning), issubclass(ds.PoleWarning, RuntimeWarning)
    (True, True)
    """


class InvalidParameterError(DynstiffError, ValueError):
    """An argument has the wrong type, shape, sign or is not finite.

    Examples
    --------
    >>> import dynstiff as ds
    >>> try:
    ...     ds.Cable(mass_per_length=0.064, EA=-1.0)
    ... except ValueError as exc:                 # an InvalidParameterError is a ValueError
    ...     print(exc)
    EA must be > 0, got -1.0
    """


class ConvergenceError(DynstiffError, RuntimeError):
    """An iterative solver did not converge; the message gives its residual.

    Examples
    --------
    >>> from dynstiff.errors import ConvergenceError
    >>> err = ConvergenceError("Newton did not converge", residual=1e-3)
    >>> err.residual, isinstance(err, RuntimeError)
    (0.001, True)
    """

    def __init__(self, message: str, residual: float | None = None) -> None:
        super().__init__(message)
        self.residual = residual


class SlackCableError(DynstiffError, ValueError):
    """A cable has no tensile equilibrium (it would be slack or compressed).

    Examples
    --------
    >>> import dynstiff as ds
    >>> issubclass(ds.SlackCableError, ValueError)
    True
    """


class InfeasiblePoseError(SlackCableError):
    """No statics at a pose: no tensions within the limits hold the platform there. The
    message says why and what would change it; ``cause`` is one of "singular", "wrench",
    "tension limits", "cable weight"; ``remedies`` maps what to change to a value that
    would make the pose feasible (estimates at the last iterate): ``"t_min"`` (the largest
    lower limit [N] that works, or the least one a heavy cable needs), ``"t_max"`` (the
    smallest upper limit [N]), ``"mass_per_length"`` [kg/m]; ``cable`` the cable at fault
    (or None).

    Examples
    --------
    >>> import dynstiff as ds
    >>> robot = ds.load_scene("cogiro").robot
    >>> try:
    ...     robot.equilibrium(pose=[0.0, 0.0, 30.0])     # far above the anchors
    ... except ds.InfeasiblePoseError as exc:
    ...     print(type(exc).__name__, isinstance(exc, ds.SlackCableError))
    InfeasiblePoseError True
    """

    def __init__(self, message: str, cause: str | None = None,
                 remedies: dict[str, float] | None = None, cable: int | None = None) -> None:
        super().__init__(message)
        self.cause = cause
        self.remedies = dict(remedies or {})
        self.cable = cable


class UnsupportedAnalysisError(DynstiffError, TypeError):
    """The model's rung cannot answer this question (e.g. the cable displacement field of a
    massless-cable model); the message names the rung and one that can.

    Examples
    --------
    >>> import dynstiff as ds
    >>> m = ds.StaticCableModel(ds.load_scene("cogiro").equilibrium())
    >>> try:
    ...     ds.cable_fields(m, ds.modes(m, n_modes=1), 0)
    ... except ds.UnsupportedAnalysisError as exc:
    ...     print(type(exc).__name__, isinstance(exc, TypeError))
    UnsupportedAnalysisError True
    """


class PoleWarning(DynstiffWarning, RuntimeWarning):
    """A quantity was evaluated exactly on a pole; the value returned is inf.

    Examples
    --------
    >>> import dynstiff as ds
    >>> issubclass(ds.PoleWarning, RuntimeWarning)
    True
    """


class CalibrationWarning(DynstiffWarning, UserWarning):
    """A calibration whose result should not be trusted as it stands: ``cause`` is
    "pairing" (measured frequencies among the model's local modes, paired without shapes),
    "residual" (a residual far above the measurement uncertainty) or "bound" (an estimate
    on its search bound); the message names the mode or parameter and what to give.

    Examples
    --------
    >>> import warnings
    >>> import dynstiff as ds
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn(ds.CalibrationWarning("a bound is active", cause="bound"))
    >>> caught[0].message.cause
    'bound'
    """

    def __init__(self, message: str, cause: str | None = None) -> None:
        super().__init__(message)
        self.cause = cause


class CalibrationError(DynstiffError, RuntimeError):
    """A calibration failed its checks (``calibrate(..., strict=True)``); ``cause`` as
    :class:`CalibrationWarning`.

    Examples
    --------
    >>> import dynstiff as ds
    >>> err = ds.CalibrationError("the fit failed its checks", cause="residual")
    >>> err.cause, isinstance(err, RuntimeError)
    ('residual', True)
    """

    def __init__(self, message: str, cause: str | None = None) -> None:
        super().__init__(message)
        self.cause = cause


class ResonanceWarning(DynstiffWarning, UserWarning):
    """An FRF of an undamped model crosses natural frequencies: its peaks are the values of
    the frequency grid next to each pole (unbounded in the limit), not the structure's.

    Examples
    --------
    >>> import dynstiff as ds
    >>> issubclass(ds.ResonanceWarning, UserWarning)
    True
    """


class ClosedFormWarning(DynstiffWarning, UserWarning):
    """The closed-form (shallow-cable) theory is used outside its range for the question
    asked: the message names the cable, the cause and the estimated error, and points to the
    "exact" rung. ``cable`` (index) and ``cause`` are attributes."""

    def __init__(self, message: str, cable: int | None = None, cause: str | None = None) -> None:
        super().__init__(message)
        self.cable = cable
        self.cause = cause


def user_stacklevel() -> int:
    """``stacklevel`` for :func:`warnings.warn` called by the caller of this function that
    attributes the warning to the first frame outside the dynstiff package: the user's line,
    however deep in the package the warning arises (a model's guard runs from its
    construction, from K(omega) and from the eigen search)."""
    import os
    import sys
    package = os.path.dirname(os.path.abspath(__file__)) + os.sep
    frame: FrameType | None = sys._getframe(1)
    level = 1
    while frame is not None and frame.f_code.co_filename.startswith(package):
        frame, level = frame.f_back, level + 1
    return level


class Interrupted(KeyboardInterrupt):
    """A long run stopped by Ctrl-C (a KeyboardInterrupt) after saving what it had: the
    message says how much is saved and how to resume; ``saved`` and ``total`` count the
    items (e.g. poses)."""

    def __init__(self, message: str, saved: int = 0, total: int = 0) -> None:
        super().__init__(message)
        self.saved = saved
        self.total = total
