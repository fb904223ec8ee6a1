"""The quasi-static rung: the swing with the stretch following the tension (:mod:`cablesys.model.quasistatic`),
Wang's straight cable (``segments = 1``) or N elements whose stretches follow their tensions (``segments = N``:
the quasi-static segmented cable), in the plane or in 3-D (both angles slow, the stretches fast)."""

from __future__ import annotations

from ...model import CableModel
from ...model.quasistatic import build_quasistatic, default_iterations
from ...scene import Scene
from .. import estimate as est
from .base import BuiltinRung, reduced_validity

STIFF_QS_COST = 0.25
"""Cost per element of the quasi-static segmented cable where its stretch is stiff (omega/omega_ax <= 1/STIFF_RATIO), relative to the node model's element stepped by BDF2, compiled, at one rtol (a wall-time ratio: studies/bench_rung_costs.py, its
measurement and machine in studies/results/rung_costs.json)."""
EXPLICIT_COST = 0.7
"""Cost per element of the quasi-static segmented cable stepped by the compiled rk23 pair where its stretch is not that stiff, relative to the node model's element at one rtol (a wall-time ratio: studies/bench_rung_costs.py, measured in
studies/results/rung_costs.json)."""
EXPLICIT_COST_MAX_ELEMENTS = 7
"""Most elements per section at which EXPLICIT_COST holds: past ~1.5 MB of functions the compiler runs at -O0 (cablesys.compiled.SIZE_FLAGS) and the 1000 m wire's N = 8 runs as slowly as the node model (studies/results/rung_costs.json)."""
SPACE_COST_FACTOR = 2.0
"""The quasi-static segmented cable's weights (STIFF_QS_COST, EXPLICIT_COST) in a 3-D scene over the plane's, both against
the node model of the scene's dimension: each element has two angles, and the functions grow with the angles as the
plane's grow with the elements (:func:`cablesys.ladder.choice.model_operations`; the eliminated mass matrix is twice as
wide), to 2.5 / 3.8 x the plane's operations at N = 4 / 8, where the node model's grow 1.7 x (3 x 3 node blocks): 1.5 x
to 2.2 x the plane's weight (tests/test_quasistatic_3d.py counts them). At it the explicit pair's run is no cheaper than
the node model's in 3-D (EXPLICIT_COST x 2 > 1): there only a stiff stretch makes the quasi-static segmented cable the
cheaper rung."""


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

    def valid(self, scene: Scene) -> str:
        """"" for any scene with a cable with mass and no anchor, seabed, winch, rigid body or turning track, in the
        plane or in 3-D (Wang's 3-D cable and the node model in element coordinates (phi_k, phi_z_k, u_k),
        :mod:`cablesys.model.element_coordinates`), else why not."""
        return reduced_validity(scene)

    def structure(self, scene_run: Scene) -> tuple:
        """What besides the scene's structure sets the model: the stretch solve's Newton iterations."""
        return (default_iterations(scene_run),)

    def estimate(self, scene: Scene, assessment, segments: int = 1) -> dict:
        """Estimated errors against the converged segmented cable: the straight quasi-static cable's, or with N > 1
        the quasi-static segmented cable's (:func:`cablesys.ladder.estimate.quasistatic_segmented_error`)."""
        return est.rung_error(assessment.estimates, self.name, self.segments(segments))


RUNG = QuasiStatic()
