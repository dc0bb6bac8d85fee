"""dynstiff: frequency-domain vibration analysis of cable-driven parallel robots with
heavy, elastic, sagging cables.

Importing dynstiff loads numpy and scipy only; matplotlib and pandas are imported when a
plot or a table is asked for.

The workflow: a :class:`Robot` (or a built-in scene, :func:`load_scene`), its static
:class:`Equilibrium` (``robot.equilibrium(pose=...)``), a model of one rung of the ladder
(:func:`build_model`: "spring", "catenary", "dsm", "lumped"), and the analyses, plain
functions of any model: :func:`frf`, :func:`eigenfrequencies`, :func:`modes`,
:func:`damped_modes`.
"""

from .assembly import FrequencyModel
from .cable_dsm import (
    CableModes,
    cable_dynamic_stiffness,
    cable_mode_count,
    cable_natural_frequencies,
    chord_parameters,
)
from .catenary import CatenaryState, solve_catenary, unstretched_length_for_tension
from .constants import STANDARD_GRAVITY
from .errors import (
    ConvergenceError,
    DynstiffError,
    InvalidParameterError,
    PoleWarning,
    SlackCableError,
    UnsupportedAnalysisError,
)
from .calibrate import CalibrationResult, calibrate
from .damped import DampedModes, damped_modes
from .eigen import ModalResult, cable_fields, eigenfrequencies, mode_count, modes
from .frf import FRFResult, frf
from .ladder import RUNGS, StaticCableModel, build_model
from .lumped import LumpedLinearModel, LumpedMassModel
from .measured import (
    MeasuredModes,
    compare_frf,
    compare_modes,
    read_measured_frf,
    read_measured_modes,
)
from .reduced import ModalModel, modal_model, to_statespace
from .results import LumpedModalResult
from .recommend import Recommendation, recommend_model
from .interaction import ProximityWarning, SweepResult, proximity_warnings, sweep
from .params import Cable, Damping
from .platform import Platform
from .robot import Equilibrium, Pose, Robot
from .scenes import Scene, SceneError, list_scenes, load_scene
from .workspace_map import box_grid, workspace

__version__ = "0.1.0"

__all__ = [
    "calibrate",
    "CalibrationResult",
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
    "cable_dynamic_stiffness",
    "cable_mode_count",
    "cable_natural_frequencies",
    "chord_parameters",
    "solve_catenary",
    "unstretched_length_for_tension",
]
