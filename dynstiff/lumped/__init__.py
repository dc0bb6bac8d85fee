"""Lumped-mass (bead-and-spring) cable models, the independent cross-check of the
closed-form dynamic stiffness (theory.md §7)."""

from .chain import ChainState, chain_equilibrium
from .chain_dynamics import (
    chain_end_dynamic_stiffness,
    chain_fixed_end_frequencies,
    chain_matrices,
)
from .compare import compare_modes
from .robot_model import LumpedEquilibrium, LumpedMassModel, LumpedModalResult
from .time_domain import (
    EnergyBalance,
    EnergyBalanceWarning,
    IntegrationError,
    SlackSegmentWarning,
    Spectrum,
    TimeDamping,
    TimeResponse,
    TimeStepWarning,
    explicit_step_limit,
    simulate,
)

__all__ = [
    "LumpedEquilibrium",
    "LumpedMassModel",
    "LumpedModalResult",
    "compare_modes",
    "ChainState",
    "chain_end_dynamic_stiffness",
    "chain_equilibrium",
    "chain_fixed_end_frequencies",
    "chain_matrices",
    "EnergyBalance",
    "EnergyBalanceWarning",
    "IntegrationError",
    "SlackSegmentWarning",
    "Spectrum",
    "TimeDamping",
    "TimeResponse",
    "TimeStepWarning",
    "explicit_step_limit",
    "simulate",
]
