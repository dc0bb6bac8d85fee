"""dynstiff: frequency-domain vibration analysis of cable-driven parallel robots with
heavy, elastic, sagging cables.

Importing dynstiff loads numpy and scipy only; matplotlib and pandas are imported when a
plot or a table is asked for.

The workflow: a :class:`Robot` (or a built-in scene, :func:`load_scene`), its static
:class:`Equilibrium` (``robot.equilibrium(pose=...)``), a model of one rung of the ladder
(:func:`build_model`: "spring", "catenary", "dsm", "lumped"), and the analyses, plain
functions of any model: :func:`frf`, :func:`eigenfrequencies`, :func:`modes`,
:func:`damped_modes`; designing for frequency: :func:`frequency_sensitivities`,
:func:`propagate_uncertainty`, :func:`optimal_tensions`.
"""

from dynstiff._version import __version__ as __version__
from dynstiff.analyses.calibrate import CalibrationResult, calibrate
from dynstiff.analyses.checks import CheckResult, design_checks
from dynstiff.analyses.damped import DampedModes, damped_modes
from dynstiff.analyses.eigen import ModalResult, eigenfrequencies, mode_count
from dynstiff.analyses.frf import FRFResult, frf
from dynstiff.analyses.interaction import ProximityWarning, proximity_warnings
from dynstiff.analyses.measured import (
    MeasuredModes,
    compare_frf,
    compare_modes,
    read_measured_frf,
    read_measured_modes,
)
from dynstiff.analyses.modes import cable_fields, modes
from dynstiff.analyses.optimal_tensions import OptimalTensions, optimal_tensions
from dynstiff.analyses.recommend import Recommendation, recommend_model
from dynstiff.analyses.reduced import ModalModel, modal_model, to_statespace
from dynstiff.analyses.sensitivity import SensitivityResult, frequency_sensitivities
from dynstiff.analyses.settings import scene_equilibrium, scene_model
from dynstiff.analyses.sweep import SweepResult, sweep
from dynstiff.analyses.uncertainty import Uncertain, UncertaintyResult, propagate_uncertainty
from dynstiff.cable.catenary import CatenaryState
from dynstiff.cable.catenary_solve import solve_catenary, unstretched_length_for_tension
from dynstiff.cable.dsm import cable_dynamic_stiffness, chord_parameters
from dynstiff.cable.modes import CableModes, cable_natural_frequencies
from dynstiff.cable.psi import cable_mode_count
from dynstiff.constants import STANDARD_GRAVITY
from dynstiff.errors import (
    CalibrationError,
    CalibrationWarning,
    ConvergenceError,
    DynstiffError,
    DynstiffWarning,
    InfeasiblePoseError,
    InvalidParameterError,
    PoleWarning,
    ResonanceWarning,
    SlackCableError,
    UnsupportedAnalysisError,
)
from dynstiff.lumped import LumpedLinearModel, LumpedMassModel
from dynstiff.maps import register_accessor as _register_accessor
from dynstiff.maps.workspace import box_grid, workspace
from dynstiff.models.dsm import FrequencyModel
from dynstiff.models.ladder import RUNGS, build_model
from dynstiff.models.static import StaticCableModel
from dynstiff.params import Cable, Damping
from dynstiff.results import LumpedModalResult
from dynstiff.robot.platform import Platform
from dynstiff.robot.robot import Equilibrium, Pose, Robot
from dynstiff.robot.waypoints import WaypointPath
from dynstiff.scenes import Scene, SceneError, list_scenes, load_scene

__all__ = [
    "scene_model",
    "scene_equilibrium",
    "design_checks",
    "CheckResult",
    "ResonanceWarning",
    "CalibrationWarning",
    "CalibrationError",
    "DynstiffWarning",
    "calibrate",
    "CalibrationResult",
    "frequency_sensitivities",
    "SensitivityResult",
    "propagate_uncertainty",
    "Uncertain",
    "UncertaintyResult",
    "optimal_tensions",
    "OptimalTensions",
    "MeasuredModes",
    "compare_frf",
    "compare_modes",
    "read_measured_frf",
    "read_measured_modes",
    "ModalModel",
    "modal_model",
    "to_statespace",
    "workspace",
    "box_grid",
    "frf",
    "eigenfrequencies",
    "modes",
    "mode_count",
    "damped_modes",
    "cable_fields",
    "DampedModes",
    "LumpedLinearModel",
    "LumpedModalResult",
    "StaticCableModel",
    "UnsupportedAnalysisError",
    "Cable",
    "Damping",
    "CableModes",
    "Equilibrium",
    "FRFResult",
    "FrequencyModel",
    "LumpedMassModel",
    "RUNGS",
    "Recommendation",
    "build_model",
    "recommend_model",
    "ModalResult",
    "ProximityWarning",
    "SweepResult",
    "proximity_warnings",
    "sweep",
    "Platform",
    "Pose",
    "Robot",
    "WaypointPath",
    "Scene",
    "SceneError",
    "list_scenes",
    "load_scene",
    "CatenaryState",
    "ConvergenceError",
    "DynstiffError",
    "InvalidParameterError",
    "PoleWarning",
    "STANDARD_GRAVITY",
    "SlackCableError",
    "InfeasiblePoseError",
    "cable_dynamic_stiffness",
    "cable_mode_count",
    "cable_natural_frequencies",
    "chord_parameters",
    "solve_catenary",
    "unstretched_length_for_tension",
]

_register_accessor()           # dataset.dynstiff, once xarray is imported (dynstiff.maps)
