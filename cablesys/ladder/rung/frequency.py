"""The frequency rung: the periodic steady state of Wang's straight cable under one forcing frequency (Fourier
collocation, :func:`cablesys.linear.periodic_steady_state`), for a steady amplitude only (no start-up transient)."""

from __future__ import annotations

from ...model import CableModel, build_model
from ...scene import Scene
from .. import estimate as est
from .base import BuiltinRung


class Frequency(BuiltinRung):
    """The periodic orbit of Wang's model (Wang 1971's equations, solved by collocation instead of stepping)."""

    name = "frequency"
    time_domain = False
    straight_cost = 0.2      # the periodic orbit's cost against Wang's time-domain run (a collocation solve, no steps;
    #                          scene-dependent: studies/results/rung_costs.json)

    model_of = "wang"        # the rung whose model it solves (a RungCache builds it once for both)

    def build(self, scene: Scene, segments: int = 1, cache=None) -> CableModel:
        """Wang's straight-cable model (:func:`cablesys.model.build_model`), the orbit's equations."""
        return build_model(self.scene(scene))

    def estimate(self, scene: Scene, assessment, segments: int = 1) -> dict:
        """The periodic orbit's estimated errors against the converged segmented cable (:mod:`cablesys.ladder.estimate`)."""
        return est.rung_error(assessment.estimates, self.name)


RUNG = Frequency()
