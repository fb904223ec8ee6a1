"""The model ladder: model no more than a scene needs, say which model ran, why, and its error.

Rungs, cheapest first (:mod:`.rungs`; one module each in :mod:`.rung`: build, validity, estimate, cost):
``frequency`` (periodic steady state), ``quasi-static`` (stretch following the tension), ``wang`` (2-DOF
straight cable), ``segmented`` (N elements).
:func:`choose` decides from the scene's numbers (:mod:`.indicators`) and error estimates
(:mod:`.estimate`); :func:`simulate` runs the choice and checks it a posteriori (:mod:`.auto`).
A :class:`RungCache` passed to many calls builds each rung's model and simulator once.
"""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "run_rung": ".auto",
    "AS_BUILT": ".auto",
    "decide": ".auto",
    "linear_model": ".auto",
    "simulate": ".auto",
    "Choice": ".choice",
    "choose": ".choice",
    "tolerances": ".choice",
    "MODEL_CHOICES": ".rungs",
    "RUNGS": ".rungs",
    "RungCache": ".rungs",
    "Rung": ".rungs",
    "Assessment": ".rungs",
    "register_rung": ".rungs",
    "unregister_rung": ".rungs",
    "registered_rungs": ".rungs",
    "build_rung": ".rungs",
    "ladder_rungs": ".rungs",
    "validity": ".rungs",
}

__all__ = ["AS_BUILT", "MODEL_CHOICES", "RUNGS", "Assessment", "Choice", "Rung", "RungCache", "build_rung", "choose",
           "decide", "ladder_rungs", "linear_model", "register_rung", "registered_rungs", "run_rung", "simulate",
           "tolerances", "unregister_rung", "validity"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
