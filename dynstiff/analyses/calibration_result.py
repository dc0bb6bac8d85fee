"""The result of a calibration: fitted parameters, their confidence intervals and the residual
of every mode (theory.md §15.6).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:

    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray


__all__ = ["CalibrationResult"]


@dataclass(frozen=True)
class CalibrationResult:
    """Fitted parameters, their confidence intervals and the residual of every mode.

    Attributes
    ----------
    parameters : tuple of str
    initial, estimate : ndarray, shape (n_par,)
        Values in the units of the module notes.
    ci_low, ci_high : ndarray, shape (n_par,)
        Confidence interval at ``confidence`` (NaN when the residuals cannot tell).
    confidence : float
    measured_hz, initial_hz, fitted_hz : ndarray, shape (n_modes,)
        Measured frequencies and the paired model frequencies at the start and the estimate.
    mac : ndarray, shape (n_modes,)
        MAC of each pair at the estimate (NaN without shapes to compare).
    cable_fraction : ndarray, shape (n_modes,)
        Cable share of the kinetic energy of each paired model mode at the estimate [-]: a
        mode near a cable frequency (large share) pairs ambiguously and weighs little.
    robot : Robot
        The calibrated robot.
    n_evaluations : int
        Evaluations of the model (statics, modes) the fit made.
    jacobian : ndarray, shape (n_residuals, n_par)
        d(residual)/d ln(p) at the estimate.
    jacobian_kind : str
        "analytic" (the sensitivities of theory.md §16) or "differences".
    measured_damping, fitted_damping : ndarray, shape (n_modes,) or None
        Damping ratios [-], when a damping parameter was fitted to them.
    frf_log_error : float or None
        RMS of ln |H_model / H_measured| at the estimate, when FRFs were fitted.

    Examples
    --------
    >>> import dynstiff as ds
    >>> cal = ds.calibrate(ds.load_scene("cogiro"), [2.25, 2.40])    # measured [Hz]
    >>> print(cal.text().splitlines()[0]); len(cal.to_frame()), [f"{r:+.4f}" for r in cal.residual]
    parameter       initial     estimate       ci low      ci high
    (2, ['-0.0006', '+0.0007'])
    """

    parameters: tuple
    initial: np.ndarray
    estimate: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    confidence: float
    measured_hz: np.ndarray
    initial_hz: np.ndarray
    fitted_hz: np.ndarray
    mac: np.ndarray
    cable_fraction: np.ndarray
    robot: object
    n_evaluations: int
    jacobian: np.ndarray
    measured_damping: object = None
    fitted_damping: object = None
    frf_log_error: object = None
    jacobian_kind: str = "differences"

    @property
    def residual(self) -> NDArray[np.float64]:
        """Relative residual f_fitted / f_measured - 1 of every mode [-]."""
        return self.fitted_hz / self.measured_hz - 1.0

    def __repr__(self) -> str:
        est = ", ".join(f"{p} = {v:.5g} [{lo:.5g}, {hi:.5g}]" for p, v, lo, hi in
                        zip(self.parameters, self.estimate, self.ci_low, self.ci_high))
        fit = (f"rms frequency residual {np.sqrt(np.mean(self.residual**2)):.3g}"
               if self.measured_hz.size else "")
        if self.frf_log_error is not None:
            fit += (", " if fit else "") + f"rms ln|H| residual {self.frf_log_error:.3g}"
        return (f"CalibrationResult({est} ({100 * self.confidence:g} %), {fit}, "
                f"{self.n_evaluations} evaluations)")

    def _repr_html_(self) -> str:
        """Jupyter display: each parameter's estimate and interval, each mode's residual."""
        from dynstiff._html import html_table
        pars = html_table(repr(self), ["parameter", "initial", "estimate", "ci low",
                                       "ci high"],
                          zip(self.parameters, self.initial, self.estimate, self.ci_low,
                              self.ci_high))
        return pars + html_table("modes", ["mode", "measured [Hz]", "fitted [Hz]",
                                           "residual [-]", "MAC"],
                                 zip(range(1, self.measured_hz.size + 1), self.measured_hz,
                                     self.fitted_hz, self.residual, self.mac))

    def text(self) -> str:
        """A short report: estimates with intervals, then the residual per mode.

        Examples
        --------
        >>> import dataclasses
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> stiffer = dataclasses.replace(scene.robot, cables=tuple(
        ...     dataclasses.replace(c, EA=1.1 * c.EA) for c in scene.robot.cables))
        >>> f = ds.eigenfrequencies(ds.FrequencyModel(stiffer.equilibrium(scene.pose)), n_modes=2)
        >>> cal = ds.calibrate(scene, f)                  # "measured": the cables 10 % stiffer
        >>> print(cal.text().splitlines()[0])
        parameter       initial     estimate       ci low      ci high
        """
        lines = [f"{'parameter':<10} {'initial':>12} {'estimate':>12} "
                 f"{'ci low':>12} {'ci high':>12}"]
        for p, a, v, lo, hi in zip(self.parameters, self.initial, self.estimate, self.ci_low,
                                   self.ci_high):
            lines.append(f"{p:<10} {a:12.6g} {v:12.6g} {lo:12.6g} {hi:12.6g}")
        lines.append(f"({100 * self.confidence:g} % confidence)")
        lines.append(self.to_frame().to_string(index=False))
        return "\n".join(lines) + "\n"

    def to_frame(self) -> pd.DataFrame:
        """One row per measured mode: measured, initial and fitted frequency, residual, MAC.

        Examples
        --------
        >>> import dataclasses
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> stiffer = dataclasses.replace(scene.robot, cables=tuple(
        ...     dataclasses.replace(c, EA=1.1 * c.EA) for c in scene.robot.cables))
        >>> f = ds.eigenfrequencies(ds.FrequencyModel(stiffer.equilibrium(scene.pose)), n_modes=2)
        >>> cal = ds.calibrate(scene, f)                  # "measured": the cables 10 % stiffer
        >>> len(cal.to_frame())
        2
        """
        import pandas as pd
        df = pd.DataFrame({"mode": np.arange(1, self.measured_hz.size + 1),
                           "measured [Hz]": self.measured_hz,
                           "initial [Hz]": self.initial_hz,
                           "fitted [Hz]": self.fitted_hz,
                           "residual [-]": self.residual, "MAC [-]": self.mac,
                           "cable energy fraction [-]": self.cable_fraction})
        if self.fitted_damping is not None:
            df["measured damping ratio [-]"] = self.measured_damping
            df["fitted damping ratio [-]"] = self.fitted_damping
        return df

    def plot(self, ax: Axes | None = None) -> Figure:
        """Relative error of every mode before and after the fit; returns the Figure.

        Examples
        --------
        >>> import dataclasses
        >>> import dynstiff as ds
        >>> scene = ds.load_scene("cogiro")
        >>> stiffer = dataclasses.replace(scene.robot, cables=tuple(
        ...     dataclasses.replace(c, EA=1.1 * c.EA) for c in scene.robot.cables))
        >>> f = ds.eigenfrequencies(ds.FrequencyModel(stiffer.equilibrium(scene.pose)), n_modes=2)
        >>> cal = ds.calibrate(scene, f)                  # "measured": the cables 10 % stiffer
        >>> import matplotlib.pyplot as plt
        >>> plt.close(cal.plot())
        """
        import matplotlib.pyplot as plt
        if ax is None:
            fig, ax = plt.subplots(figsize=(6, 3.5))
        fig = ax.figure
        k = np.arange(1, self.measured_hz.size + 1)
        ax.bar(k - 0.2, 100 * (self.initial_hz / self.measured_hz - 1), 0.4, label="initial")
        ax.bar(k + 0.2, 100 * self.residual, 0.4, label="fitted")
        ax.axhline(0, color="0.4", lw=0.8)
        ax.set(xlabel="measured mode", ylabel="model / measured - 1 [%]", xticks=k)
        ax.legend()
        return fig
