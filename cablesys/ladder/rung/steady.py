"""The steady rung: a towing ship's steady straight tow or steady turn, the node model's steady state carried with the
tow to the output times instead of stepped (:mod:`cablesys.ladder.steady_tow`), where the run is that steady state
for all time: a straight course or a circle and nothing else moving the tow point or the water, point bodies whose
fluid forces do not change with the heading, the start on the steady state."""

from __future__ import annotations

from ...model import CableModel
from ...scene import Scene
from .. import estimate as est
from ..steady_tow import steady_kind, unsteady_reason
from .base import WITH_MASS, BuiltinRung, has_ends, massless, rigid, winched
from .segmented import RUNG as SEGMENTED
from .segmented import alone_segments

STEADY_COST = 0.05
"""Cost of the steady state at N elements per section in runs of the node model at N (whose cost is N): a few
statics solves (the steady state at N, one KINSOL solve continued in the turn rate or polished from the statics), the
eigenvalues of its linearization and the outputs at the output times, where the node model's run steps every element
over the whole duration; any weight below 1 makes the ladder take it where it is valid (the ratio falls with the
run's duration and is not measured by studies/bench_rung_costs.py)."""


class Steady(BuiltinRung):
    """The node model's steady tow or turn at N elements per section (not stepped)."""

    name = "steady"
    elements = True
    straight = False
    time_domain = False
    model_of = "segmented"     # the node model at the same N (a RungCache builds it once for both)
    shortcut = True            # answers the node model's run without stepping: under auto in its place where valid

    def valid(self, scene: Scene) -> str:
        """"" where the run is the steady tow or turn for all time (:func:`~cablesys.ladder.steady_tow.unsteady_reason`),
        else why not: besides an unsteady track or flow, a massless cable (the nodes would have no mass), a winch (the
        length changes), a rigid body (its orientation's statics are not held in the turn), an anchor or a seabed
        (fixed in the ground, they neither turn nor move with the tow)."""
        if massless(scene):
            return WITH_MASS
        if winched(scene):
            return "a winch ([winch]): the cable length changes in time, so the tow is not steady"
        if rigid(scene):
            return ("a rigid body (body.pitch_inertia): its orientation is not a point's, and the steady rung holds the "
                    "nodes' steady state alone")
        if has_ends(scene):
            return ("an anchor or a seabed: fixed in the ground, it neither turns nor moves with the tow, so the tow is "
                    "not steady")
        return unsteady_reason(scene)

    def build(self, scene: Scene, segments: int = 2, cache=None) -> CableModel:
        """The node model with ``segments`` elements per section (the segmented rung's)."""
        return SEGMENTED.build(scene, segments, cache)

    def cost(self, scene: Scene, assessment=None, segments: int = 2) -> float:
        """STEADY_COST x N: a fraction of the node model's run at the same N."""
        return STEADY_COST * float(self.segments(segments))

    def estimate(self, scene: Scene, assessment, segments: int = 2) -> dict:
        """The node model's discretization error at N (:func:`cablesys.ladder.estimate.segmented_error`): the steady
        state is that model's, with no integration error."""
        return est.segmented_error(assessment.estimates, self.segments(segments))

    def alone(self, scene: Scene, requested: str, segments) -> tuple:
        """(N, reason, checked a posteriori) in place of the node model's run: N as the segmented rung takes it
        (:func:`~.segmented.alone_segments`), checked a posteriori against N / 2 (and N / 4) of steady states."""
        n = alone_segments(scene, requested, segments, self.name)
        track = scene.top_motion.track
        what = (f"a steady turn (top_motion.track: a circle of {track.radius:g} m at {track.speed:g} m/s, "
                f"{abs(track.turn_rate):.4g} rad/s)" if steady_kind(scene) == "turn" else
                f"a steady straight tow (top_motion.track: {track.speed:g} m/s on a straight course)")
        why = (f"{what}, nothing else moving the tow point or the water, started on its steady state: the node model's "
               f"steady state with N = {n} elements per section, carried with the tow to the output times, not stepped")
        return n, why + "; N checked a posteriori on every quantity", requested == "auto"


RUNG = Steady()
