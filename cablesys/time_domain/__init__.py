"""Time-domain simulation: an integrator registry behind one call.

``simulate(scene, method=...)`` takes a name in :data:`METHODS` or a user
:class:`IntegratorMethod` (the protocol of :mod:`cablesys.integration`).
"""

from ..integration import METHODS, IntegratorMethod
from .integrators import IntegratorSettings, make_integrator
from .record import RunInterrupted, RunRecord
from .run import Simulator, initial_state, simulate

__all__ = ["METHODS", "IntegratorMethod", "IntegratorSettings", "RunInterrupted", "RunRecord", "Simulator",
           "initial_state", "make_integrator", "simulate"]
