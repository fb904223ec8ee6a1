"""The model ladder: model no more than a scene needs, say which model ran, why, and its error.

Rungs, cheapest first (:mod:`.rungs`): ``frequency`` (periodic steady state), ``quasi-static``
(stretch following the tension), ``wang`` (2-DOF straight cable), ``segmented`` (N elements).
:func:`choose` decides from the scene's numbers (:mod:`.indicators`) and error estimates
(:mod:`.estimate`); :func:`simulate_auto` runs the choice and checks it a posteriori (:mod:`.auto`).
A :class:`RungCache` passed to many calls builds each rung's model and simulator once.
"""

from .auto import run_rung, simulate_auto
from .choice import Choice, choose, tolerances
from .rungs import MODEL_CHOICES, RUNGS, RungCache, build_rung

__all__ = ["MODEL_CHOICES", "RUNGS", "Choice", "RungCache", "build_rung", "choose", "run_rung", "simulate_auto",
           "tolerances"]
