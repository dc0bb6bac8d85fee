"""Nonlinear time response of the pendulum and its cables (scipy ``solve_ivp``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import positive_scalar
from dynstiff.errors import ConvergenceError, InvalidParameterError
from dynstiff.timedomain.pendulum.dynamics import (
    evaluate_rhs,
    excitation_at,
    segment_geometry,
    start_state,
)
from dynstiff.timedomain.pendulum.model import CablePendulum, checked_integer

if TYPE_CHECKING:
    import pandas as pd
    from numpy.typing import NDArray


@dataclass(frozen=True)
class PendulumResponse:
    """Nonlinear time response of the pendulum and its cables.

    Attributes
    ----------
    model : CablePendulum
    freq_hz, amplitude, phase : float
        Excitation f [Hz], x0 [m], phase lag [rad].
    t : ndarray, shape (n_t,)
        Output times [s].
    y : ndarray, shape (n_t, 2 n_dof)
        States (q, dq/dt).
    method : str
        scipy ``solve_ivp`` method used.
    nfev, njev : int
        Right-hand side and Jacobian evaluations.
    wall_time : float
        Integration time [s].
    """

    model: CablePendulum
    freq_hz: float
    amplitude: float
    phase: float
    t: np.ndarray
    y: np.ndarray
    method: str
    nfev: int
    njev: int
    wall_time: float

    @property
    def phi(self) -> NDArray[np.float64]:
        """Pendulum angle [rad], shape (n_t,)."""
        return self.y[:, 0]

    def tensions(self):
        """Tension of the segment at D of cable 1 (end B) and 2 (end C) [N], (n_t, 2)."""
        exc = excitation_at(self.freq_hz, self.amplitude, self.phase).repeat(self.t.size)
        return segment_geometry(self.model, self.t, self.y, exc)[-1][:, :, -1]

    def amplitude_growth(self, periods: int = 2):
        """max |phi| over the last ``periods`` excitation periods / max |phi| over the first
        ones [-]: > 1 where a disturbance grows."""
        T = periods / self.freq_hz
        first = np.abs(self.phi[self.t <= self.t[0] + T]).max()
        last = np.abs(self.phi[self.t >= self.t[-1] - T]).max()
        return float(last / max(first, 1e-300))

    def to_frame(self) -> pd.DataFrame:
        """pandas DataFrame: time [s], phi [rad], the two tensions at D [N]."""
        import pandas as pd
        Tn = self.tensions()
        return pd.DataFrame({"t [s]": self.t, "phi [rad]": self.phi,
                             "T_B [N]": Tn[:, 0], "T_C [N]": Tn[:, 1]})


def simulate(model: CablePendulum, freq_hz: float, amplitude: float, t_end: float,
             phase: float = 0.0, phi0: float = 1e-4, method=None, rtol: float = 1e-8, max_step=None,
             n_out: int | None = None) -> PendulumResponse:
    """Nonlinear response from rest with the pendulum tilted by ``phi0``.

    The ends start moving at t = 0 (x(t) = x0 sin(2 pi f t)); the point masses start in
    static equilibrium with the velocity of the ends interpolated along each cable. Solved
    by scipy ``solve_ivp`` with the exact Jacobian for implicit methods.

    Parameters
    ----------
    model : CablePendulum
    freq_hz, amplitude, phase : float
        Excitation f [Hz] (> 0), x0 [m] (>= 0), phase lag of end C [rad].
    t_end : float
        Duration [s].
    phi0 : float
        Initial angle [rad].
    method : str, optional
        ``solve_ivp`` method. Default "DOP853" for massless cables (not stiff) and "LSODA"
        for point-mass cables (stiff with damping: eigenvalues to about -1e6 1/s; "Radau"
        and "BDF" also work but cost 2-4 times more; undamped cables are not stiff).
    rtol : float
        Relative tolerance; the absolute tolerances are rtol times (1 rad, L, omega, omega L).
    max_step : float, optional
        Largest step [s] (default one sixteenth of the excitation period).
    n_out : int, optional
        Output samples, evenly spaced (default 64 per period, at most 200001).

    Returns
    -------
    PendulumResponse

    Raises
    ------
    InvalidParameterError
        Bad arguments (named).
    ConvergenceError
        The integrator failed (its message is included) or the state became non-finite.
    """
    import time

    from scipy.integrate import solve_ivp
    exc = excitation_at(freq_hz, amplitude, phase)
    if exc.omega.size != 1:
        raise InvalidParameterError(
            f"simulate takes one excitation case, got {exc.omega.size} (freq_hz, amplitude, "
            f"phase broadcast to that many)")
    t_end = positive_scalar("t_end", t_end)
    rtol = positive_scalar("rtol", rtol)
    f = float(exc.freq_hz[0])
    if max_step is None:
        max_step = 1.0 / (16.0 * f)
    max_step = positive_scalar("max_step", max_step)
    if n_out is None:
        n_out = int(min(64 * t_end * f, 200000)) + 1
    n_out = checked_integer("n_out", n_out, 2)
    if method is None:
        method = "DOP853" if model.n_masses == 0 else "LSODA"
    y0 = start_state(model, exc)[0]
    y0[0] = float(phi0)
    if not np.isfinite(y0[0]):
        raise InvalidParameterError(f"phi0 must be finite [rad], got {phi0!r}")

    def fun(t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        return evaluate_rhs(model, np.array([t]), y[None], exc, False)[0][0]

    def jac(t, y):
        return evaluate_rhs(model, np.array([t]), y[None], exc, True)[1][0]

    kw = {} if method in ("RK23", "RK45", "DOP853") else {"jac": jac}
    t_eval = np.linspace(0.0, t_end, n_out)
    start = time.perf_counter()
    try:
        sol = solve_ivp(fun, (0.0, t_end), y0, method=method, t_eval=t_eval, rtol=rtol,
                        atol=rtol * model.state_scale(exc.omega)[0], max_step=max_step, **kw)
    except ValueError as exc_:
        raise InvalidParameterError(f"method {method!r}: {exc_}") from None
    wall = time.perf_counter() - start
    if not sol.success or not np.all(np.isfinite(sol.y)):
        raise ConvergenceError(
            f"simulate ({method}) failed at t = {sol.t[-1] if sol.t.size else 0.0:.6g} s of "
            f"{t_end:g} s: {sol.message}")
    return PendulumResponse(model=model, freq_hz=f, amplitude=float(exc.amplitude[0]),
                            phase=float(exc.phase[0]), t=sol.t, y=sol.y.T, method=method,
                            nfev=int(sol.nfev), njev=int(sol.njev), wall_time=wall)

