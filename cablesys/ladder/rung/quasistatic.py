"""The quasi-static rung: the swing with the stretch following the tension (:mod:`cablesys.model.quasistatic`),
Wang's straight cable (``segments = 1``) or N elements whose stretches follow their tensions (``segments = N``:
the quasi-static segmented cable)."""

from __future__ import annotations

from ...model import CableModel
from ...model.quasistatic import build_quasistatic, default_iterations
from ...scene import Scene
from .. import estimate as est
from .base import BuiltinRung, three_d

STIFF_QS_COST = 0.25
"""Cost per element of the quasi-static segmented cable where its stretch is stiff (omega/omega_ax <= 1/STIFF_RATIO), relative to the node model's element stepped by BDF2, compiled, at one rtol (a wall-time ratio: studies/bench_rung_costs.py, its
measurement and machine in studies/results/rung_costs.json)."""
EXPLICIT_COST = 0.7
"""Cost per element of the quasi-static segmented cable stepped by the compiled rk23 pair where its stretch is not that stiff, relative to the node model's element at one rtol (a wall-time ratio: studies/bench_rung_costs.py, measured in
studies/results/rung_costs.json)."""
EXPLICIT_COST_MAX_ELEMENTS = 7
"""Most elements per section at which EXPLICIT_COST holds: past ~1.5 MB of functions the compiler runs at -O0 (cablesys.compiled.SIZE_FLAGS) and the 1000 m wire's N = 8 runs as slowly as the node model (studies/results/rung_costs.json)."""


class QuasiStatic(BuiltinRung):
    """The stretch quasi-static (following the tension), the swing dynamic; straight or with N elements."""

    name = "quasi-static"
    elements = True
    stays_taut = True          # a quasi-static stretch cannot go slack
    straight_cost = 0.5        # the straight quasi-static cable against Wang's (no stretch mode to step; studies/results/rung_costs.json)

    def build(self, scene: Scene, segments: int = 1, cache=None) -> CableModel:
        """The quasi-static model (:func:`cablesys.model.quasistatic.build_quasistatic`); the straight one reuses
        Wang's model from ``cache`` (a :class:`~cablesys.ladder.rungs.RungCache`) when given."""
        full = cache.model(scene, "wang") if cache is not None and self.segments(segments) == 1 else None
        return build_quasistatic(self.scene(scene, segments), full=full)

    def scene(self, scene: Scene, segments: int = 1) -> Scene:
        """The scene this rung runs; a 3-D scene keeps one element per section: the quasi-static reduction is planar
        (outside its validity, :func:`.base.straight_validity`), so it offers the ladder no elements there."""
        return super().scene(scene, 1 if three_d(scene) else segments)

    def structure(self, scene_run: Scene) -> tuple:
        """What besides the scene's structure sets the model: the stretch solve's Newton iterations."""
        return (default_iterations(scene_run),)

    def estimate(self, scene: Scene, assessment, segments: int = 1) -> dict:
        """Estimated errors against the converged segmented cable: the straight quasi-static cable's, or with N > 1
        the quasi-static segmented cable's (:func:`cablesys.ladder.estimate.quasistatic_segmented_error`)."""
        return est.rung_error(assessment.estimates, self.name, self.segments(segments))


RUNG = QuasiStatic()
