"""Time-domain simulation: an integrator registry behind one call."""

from .integrators import METHODS, IntegratorSettings, make_integrator
from .record import RunInterrupted, RunRecord
from .run import Simulator, initial_state, simulate

__all__ = ["METHODS", "IntegratorSettings", "RunInterrupted", "RunRecord", "Simulator", "initial_state",
           "make_integrator", "simulate"]
