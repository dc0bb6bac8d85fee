"""Lumped-mass (bead-and-spring) cable models, the independent cross-check of the
closed-form dynamic stiffness (theory.md §7): one chain, the nonlinear robot
(:class:`LumpedMassModel`), its linearisation (:class:`LumpedLinearModel`, the "lumped" rung)
and its time-domain simulation."""

from dynstiff.analyses.compare_lumped import compare_modes
from dynstiff.cable.lumped_chain import ChainState, chain_equilibrium
from dynstiff.cable.lumped_chain_dynamics import (
    chain_end_dynamic_stiffness,
    chain_fixed_end_frequencies,
    chain_matrices,
)
from dynstiff.models.lumped import LumpedLinearModel
from dynstiff.models.lumped_robot import LumpedMassModel
from dynstiff.models.lumped_statics import LumpedEquilibrium
from dynstiff.results import LumpedModalResult
from dynstiff.timedomain.simulation import (
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
    "LumpedLinearModel",
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
