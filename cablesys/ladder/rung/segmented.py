"""The segmented rung: N straight tension-only elements per section, every element stretch stepped (the node model,
:mod:`cablesys.model.segmented`); the only rung with nodes to anchor and to lay on a seabed."""

from __future__ import annotations

from ...errors import ParameterError
from ...model import CableModel, build_model
from ...scene import Scene
from .. import estimate as est
from .base import WITH_MASS, BuiltinRung, has_ends, massless, rigid, scene_segments, system, winched

ENDS_SEGMENTS = 16
"""The first N of an anchored line or a seabed scene (the a posteriori check at N / 2 grows it)."""
CHECK_COST = 1.5
"""Cost of a run of N elements checked a posteriori against N / 2, in runs of N (either element rung; a wall-time ratio:
studies/bench_rung_costs.py, measured in studies/results/rung_costs.json)."""
CHECK_ACCEPT = 0.8
"""A checked N is kept when its Richardson estimate is within this fraction of the tolerance: those estimates were 0.82-0.98 x the actual error (studies/model_ladder.py: heavy1000 0.85, random current-4 / 9 / 10 0.98 / 0.92 / 0.82 against N = 32)."""


def alone_segments(scene: Scene, requested: str, segments, name: str = "segmented") -> int:
    """N of the node model where it is the only rung (or the steady rung in its place, ``name``): the caller's N, else
    the scene's when the rung ``name`` was named, else at least ENDS_SEGMENTS."""
    scene_n = scene_segments(scene)
    return int(segments or (scene_n if requested == name and scene_n > 1 else max(scene_n, ENDS_SEGMENTS)))


class Segmented(BuiltinRung):
    """The node model with N >= 2 elements per section."""

    name = "segmented"
    elements = True
    straight = False

    def valid(self, scene: Scene) -> str:
        """"" unless the scene's cable is massless (the nodes would have no mass); a 3-D scene runs the node model with
        nodes (x, y, z) (:mod:`cablesys.model.segmented`)."""
        return WITH_MASS if massless(scene) else ""

    def build(self, scene: Scene, segments: int = 2, cache=None) -> CableModel:
        """The node model with ``segments`` >= 2 elements per section (:func:`cablesys.model.build_model`)."""
        if segments < 2:
            raise ParameterError("segments", segments, "the segmented rung needs at least 2 elements per section")
        return build_model(self.scene(scene, segments))

    def estimate(self, scene: Scene, assessment, segments: int = 2) -> dict:
        """Estimated errors of N elements against the converged cable (:func:`cablesys.ladder.estimate.segmented_error`)."""
        return est.segmented_error(assessment.estimates, self.segments(segments))

    def alone(self, scene: Scene, requested: str, segments) -> tuple:
        """A system of lines, an anchored line or a seabed, a winch, a rigid body, or a towing ship's track: the node model with the caller's N, else the scene's
        (named segmented rung), else at least ENDS_SEGMENTS, checked a posteriori on every quantity when the ladder
        chose it."""
        n = alone_segments(scene, requested, segments, self.name)
        why = ("a system of lines joined at points ([[point]], [[line]]) that is not a chain: the node model with N = {n} "
               "elements per line section, the only rung that builds a graph of lines" if system(scene) else
               "an anchored line or a seabed: the node model with N = {n}, the only rung with nodes to anchor and to lay "
               "on the bed" if has_ends(scene) else "a winch ([winch]): the node model with N = {n}, the only rung whose "
               "cable length can change in time" if winched(scene) else "a rigid body: the node model with "
               "N = {n}, the only rung whose coordinates include its orientation (pitch in the plane, a quaternion in 3-D)" if rigid(scene) else "a towing ship's track "
               "(top_motion.track): the node model with N = {n}, the only rung whose steady turn or straight tow the "
               "statics find")
        if (has_ends(scene) or system(scene)) and winched(scene):
            why += " and whose cable length can change in time (the [winch])"
        if rigid(scene) and (has_ends(scene) or winched(scene) or system(scene)):
            why += " and whose coordinates include a rigid body's orientation (pitch in the plane, a quaternion in 3-D)"
        return n, why.format(n=n) + "; N checked a posteriori on every quantity", requested == "auto"


RUNG = Segmented()
