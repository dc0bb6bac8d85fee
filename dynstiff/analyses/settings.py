"""One source of the analysis defaults of a scene.

Every command (``demo``, ``report``, ``check``, ``modes``, ``frf``, ``sweep``) and the demo
report take their band, forbidden band, cable model, tolerance and damping from
:func:`analysis_settings`: the scene's ``[analysis]`` and ``[damping]`` sections, the
defaults below where the scene is silent, and the user's overrides on top. So the same scene
gives the same verdicts and the same model recommendation whichever command prints them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from dynstiff._validate import band as checked_band
from dynstiff.analyses.checks import damped_model
from dynstiff.analyses.participation import FRF_AMPLIFICATION_LIMIT, PLATFORM_SHARE_THRESHOLD
from dynstiff.errors import InvalidParameterError
from dynstiff.models.exact import DEFAULT_FMAX_HZ
from dynstiff.models.ladder import RUNGS
from dynstiff.params import Damping

if TYPE_CHECKING:
    from typing import Any

    from numpy.typing import ArrayLike

    from dynstiff.models.base import PlatformModel
    from dynstiff.models.dsm import FrequencyModel
    from dynstiff.robot.equilibrium import Equilibrium
    from dynstiff.robot.pose import Pose
    from dynstiff.scenes.loader import Scene

__all__ = ["AnalysisSettings", "analysis_settings", "DEFAULT_BAND_HZ", "DEFAULT_MODEL_RTOL",
           "scene_equilibrium", "scene_model"]

#: Band of interest of a scene without ``band_hz`` [Hz].
DEFAULT_BAND_HZ = (0.1, 20.0)
#: Admissible relative frequency error of the cable model [-].
DEFAULT_MODEL_RTOL = 1e-2
#: Relative margin of the checked modes to the forbidden band [-].
DEFAULT_MARGIN = 0.05
#: Modes listed by default.
DEFAULT_N_MODES = 20
#: Segments per cable of the lumped rung.
DEFAULT_SEGMENTS = 30


@dataclass(frozen=True)
class AnalysisSettings:
    """The settings every analysis of a scene uses.

    Attributes
    ----------
    scene : str
        Scene name.
    band_hz : (float, float)
        Band of interest: FRFs, the model recommendation [Hz].
    forbidden_hz : (float, float) or None
        Band no platform mode may enter (design checks) [Hz]; None: not checked.
    n_modes : int
        Modes listed.
    rung : str
        Cable model (:data:`dynstiff.RUNGS`).
    segments : int
        Segments per cable of the lumped rung.
    model_rtol : float
        Admissible relative frequency error of the cable model [-].
    margin : float
        Relative frequency margin to the forbidden band [-].
    participation : float
        Platform share from which a mode is held to the margin [-].
    frf_limit : float
        Largest admissible receptance / static value in the forbidden band [-].
    damping : Damping
    """

    scene: str
    band_hz: tuple
    forbidden_hz: object
    n_modes: int
    rung: str
    segments: int
    model_rtol: float
    margin: float
    participation: float
    frf_limit: float
    damping: Damping

    def model_options(self) -> dict[str, int]:
        """Keyword options of :func:`dynstiff.build_model` for ``rung``."""
        if self.rung == "exact":            # the exact cables resolve 1.6 x the band's top
            return {"fmax_hz": max(DEFAULT_FMAX_HZ, 1.6 * float(self.band_hz[1]))}
        return {"segments": self.segments} if self.rung == "lumped" else {}

    def model(self, equilibrium: Equilibrium, damped: bool = True) -> FrequencyModel:
        """The model of ``rung`` with the settings' damping (``damped=False``: none)."""
        return damped_model(equilibrium, self.damping if damped else Damping(0, 0, 0),
                            self.rung, **self.model_options())

    def check_options(self) -> dict[str, ArrayLike | str | Damping]:
        """Keyword arguments of :func:`dynstiff.analyses.checks.design_checks`."""
        return dict(band_hz=self.forbidden_hz, margin=self.margin,
                    model_rtol=self.model_rtol, rung=self.rung,
                    participation=self.participation, frf_limit=self.frf_limit,
                    damping=self.damping, model_band_hz=self.band_hz,
                    **self.model_options())

    def lines(self) -> list[str]:
        """Lines stating the settings, for every printed report."""
        fb = (f"{self.forbidden_hz[0]:g}-{self.forbidden_hz[1]:g} Hz (margin "
              f"{self.margin:.0%}, modes with platform share >= {self.participation:.0%}, "
              f"receptance <= {self.frf_limit:g} x static)" if self.forbidden_hz else "none")
        seg = f", {self.segments} segments per cable" if self.rung == "lumped" else ""
        return [f"band {self.band_hz[0]:g}-{self.band_hz[1]:g} Hz; forbidden band {fb}",
                f"model {self.rung}{seg}, tolerance {self.model_rtol:g}; "
                + self.damping.text()]

    def metadata(self, pose: Pose | None = None,
                 units: str | None = None) -> dict[str, Any]:
        """Dict for the header of a CSV/JSON output, the same keys first in every table:
        dynstiff (version), scene, pose (position [m], rotation [rad]), model, date (UTC,
        ISO 8601); then band, damping, segments (lumped), units."""
        from datetime import UTC, datetime

        from dynstiff._version import __version__
        d = {"dynstiff": __version__, "scene": self.scene,
             "pose": None if pose is None else {
                 "position [m]": [float(v) for v in pose.position],
                 "rotation [rad]": [float(v) for v in pose.rotation]},
             "model": self.rung,
             "date": datetime.now(UTC).isoformat(timespec="seconds"),
             "band_hz": list(self.band_hz),
             "damping": {"platform_ratio": self.damping.platform_ratio,
                         "cable_loss_factor": self.damping.cable_loss_factor,
                         "cable_viscous_damping [N s/m^2]":
                             self.damping.cable_viscous_damping}}
        if self.rung == "lumped":
            d["segments"] = self.segments
        if units is not None:
            d["units"] = units
        return d


def analysis_settings(
        scene: Scene, band_hz: tuple[float, float] | None = None,
        forbidden_hz: tuple[float, float] | None = None, n_modes: int | None = None,
        rung: str | None = None, segments: int | None = None, model_rtol: float | None = None,
        margin: float | None = None, participation: float | None = None,
        frf_limit: float | None = None, damping: list[float] | tuple[int, int, int] | None = None,
) -> AnalysisSettings:
    """The settings of ``scene``: each argument given overrides the scene's value, which
    overrides the module default.

    Parameters
    ----------
    scene : Scene
    band_hz, forbidden_hz : (float, float), optional
        [Hz].
    n_modes, segments : int, optional
    rung : str, optional
    model_rtol, margin, participation, frf_limit : float, optional
    damping : Damping or sequence of up to 3 floats, optional
        (platform ratio, cable loss factor, cable viscous damping [N s/m^2]); values not
        given keep the scene's.

    Returns
    -------
    AnalysisSettings

    Raises
    ------
    InvalidParameterError
        A value out of range, naming it; also when ``scene`` is not a Scene (it lacks
        robot, pose, band_hz or damping): the message names the first of these it lacks.
    """
    missing = [a for a in ("robot", "pose", "band_hz", "damping") if not hasattr(scene, a)]
    if missing:
        raise InvalidParameterError(f"scene must be a dynstiff Scene (load_scene), got "
                                    f"{type(scene).__name__} without {missing[0]!r}")

    def pick(given: ArrayLike | str | None, scene_value: ArrayLike | None,
             default: ArrayLike | str | None) -> float | str | tuple[float, float]:
        return given if given is not None else (
            scene_value if scene_value is not None else default)

    band = checked_band(pick(band_hz, scene.band_hz, DEFAULT_BAND_HZ), "band_hz")
    fb = pick(forbidden_hz, scene.forbidden_band_hz, None)
    fb = None if fb is None else checked_band(fb, "forbidden_hz")
    rung = pick(rung, getattr(scene, "model", None), "dsm")
    if rung not in RUNGS:
        raise InvalidParameterError(f"model must be one of {RUNGS}, got {rung!r}")
    n = pick(n_modes, scene.n_modes, DEFAULT_N_MODES)
    seg = pick(segments, getattr(scene, "segments", None), DEFAULT_SEGMENTS)
    for name, v in (("n_modes", n), ("segments", seg)):
        if int(v) != v or v < 1:
            raise InvalidParameterError(f"{name} must be an integer >= 1, got {v!r}")
    base = getattr(scene, "damping", None) or Damping()
    if damping is None:
        damp = base
    elif isinstance(damping, Damping):
        damp = damping
    else:
        vals = list(damping)
        if not 1 <= len(vals) <= 3:
            raise InvalidParameterError(
                f"damping needs 1 to 3 values (platform ratio, cable loss factor, cable "
                f"viscous damping [N s/m^2]), got {vals!r}")
        full = [base.platform_ratio, base.cable_loss_factor, base.cable_viscous_damping]
        full[:len(vals)] = vals
        damp = Damping(*full)
    settings = AnalysisSettings(
        scene=scene.name, band_hz=band, forbidden_hz=fb, n_modes=int(n), rung=rung,
        segments=int(seg),
        model_rtol=float(pick(model_rtol, getattr(scene, "model_rtol", None),
                              DEFAULT_MODEL_RTOL)),
        margin=float(pick(margin, None, DEFAULT_MARGIN)),
        participation=float(pick(participation, None, PLATFORM_SHARE_THRESHOLD)),
        frf_limit=float(pick(frf_limit, None, FRF_AMPLIFICATION_LIMIT)), damping=damp)
    for name in ("model_rtol", "participation", "frf_limit"):
        v = getattr(settings, name)
        if not (np.isfinite(v) and v > 0):
            raise InvalidParameterError(f"{name} must be finite and > 0, got {v!r}")
    if not (np.isfinite(settings.margin) and settings.margin >= 0):
        raise InvalidParameterError(f"margin must be >= 0 (finite), got {settings.margin!r}")
    return settings


def scene_equilibrium(scene: Scene, pose: ArrayLike | Pose | None = None,
                      lengths: ArrayLike | None = None) -> Equilibrium:
    """The equilibrium of ``scene`` every command uses: inverse statics at ``pose``, forward
    statics from unstretched ``lengths`` [m] (held DOFs kept at the scene's pose), or the
    scene's own equilibrium (its pose or lengths).

    Raises
    ------
    InvalidParameterError
        Both ``pose`` and ``lengths``, or ``lengths`` for a scene that holds DOFs without a
        pose to hold them at.

    Examples
    --------
    >>> import dynstiff as ds
    >>> eq = ds.scene_equilibrium(ds.load_scene("cogiro"), pose=[0.0, 0.0, 1.2])
    >>> eq.pose.position.tolist()
    [0.0, 0.0, 1.2]
    """
    if pose is not None and lengths is not None:
        raise InvalidParameterError("give pose or lengths, not both")
    if pose is not None:
        return scene.robot.equilibrium(pose=pose)
    if lengths is not None:
        start = scene.pose               # held DOFs keep the values of the scene's pose
        if start is None and len(scene.robot.platform.free_dofs) < 6:
            raise InvalidParameterError(
                f"lengths: scene {scene.name!r} holds DOFs but gives no [pose] to hold them "
                f"at; give a pose instead, or a [pose] position in the scene file")
        return scene.equilibrium(unstretched_lengths=lengths, initial_pose=start)
    return scene.equilibrium()


def scene_model(scene: Scene, pose: ArrayLike | Pose | None = None, *,
                lengths: ArrayLike | None = None,
                rung: str | None = None, damping: Damping | None = None,
                **settings: Any) -> PlatformModel:
    """The model the command line builds for ``scene``: its ``[analysis]`` cable model (or
    ``rung``) with the options the settings give it, and its ``[damping]`` (or ``damping``;
    ``Damping(0, 0, 0)`` for none), at ``pose``, at unstretched ``lengths`` or at the scene's
    own equilibrium (:func:`scene_equilibrium`). One set of defaults: an FRF of this model
    equals ``dynstiff frf`` on the scene.

    Parameters
    ----------
    scene : Scene
    pose : Pose or array_like, optional
    lengths : array_like, optional
        Unstretched cable lengths [m] (forward statics).
    rung : str, optional
    damping : Damping or sequence of up to 3 floats, optional
        As :func:`analysis_settings`.
    **settings
        Further overrides of :func:`analysis_settings` (``band_hz``, ``segments``, ...).

    Returns
    -------
    model of the rung (damped unless the damping is zero)

    Raises
    ------
    InvalidParameterError
        A setting that is not a keyword of :func:`analysis_settings` other than scene, rung
        and damping; the message lists the settings it takes.

    Examples
    --------
    >>> import dynstiff as ds
    >>> model = ds.scene_model(ds.load_scene("cogiro"))
    >>> model.rung, model.damping_text()
    ('dsm', 'damped: platform modal ratio 0.01, cable loss factor 0.01')
    """
    import inspect
    known = set(inspect.signature(analysis_settings).parameters) - {"scene", "rung", "damping"}
    unknown = sorted(set(settings) - known)
    if unknown:
        raise InvalidParameterError(f"settings {unknown} are not settings of an analysis (they "
                                    f"are {sorted(known)})")
    st = analysis_settings(scene, rung=rung, damping=damping, **settings)
    return st.model(scene_equilibrium(scene, pose, lengths))
