"""dynstiff: frequency-domain vibration analysis of cable-driven parallel robots with
heavy, elastic, sagging cables.

Importing dynstiff loads numpy and scipy only; matplotlib and pandas are imported when a
plot or a table is asked for.
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
)
from .eigen import ModalResult
from .frf import FRFResult
from .ladder import RUNGS, build_model
from .lumped import LumpedMassModel
from .recommend import Recommendation, recommend_model
from .interaction import ProximityWarning, SweepResult, proximity_warnings, sweep
from .params import Cable
from .platform import Platform
from .robot import Equilibrium, Pose, Robot
from .scenes import Scene, SceneError, list_scenes, load_scene

__version__ = "0.1.0"

__all__ = [
    "Cable",
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
