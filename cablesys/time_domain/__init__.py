"""Time-domain simulation: an integrator registry behind one call.

``simulate(scene, method=...)`` takes a name in :data:`METHODS` or a user
:class:`IntegratorMethod` (the protocol of :mod:`cablesys.integration`).
"""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "METHODS": "..integration",
    "IntegratorMethod": "..integration",
    "IntegratorSettings": ".integrators",
    "make_integrator": ".integrators",
    "RunInterrupted": ".record",
    "RunRecord": ".record",
    "Simulator": ".run",
    "initial_state": ".run",
    "simulate": ".run",
}

__all__ = ["METHODS", "IntegratorMethod", "IntegratorSettings", "RunInterrupted", "RunRecord", "Simulator",
           "initial_state", "make_integrator", "simulate"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
