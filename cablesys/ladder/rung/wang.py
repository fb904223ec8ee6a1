"""The wang rung: Wang's (1971) 2-DOF straight cable per section, stretch and swing (:mod:`cablesys.model.build`);
in a 3-D scene the same cable with two swing angles (Wang 1971 p. 32)."""

from __future__ import annotations

from ...model import CableModel, build_model
from ...scene import Scene
from .. import estimate as est
from .base import NO_NODES, ROTATES, SYSTEM, TURNING, WINCHED, BuiltinRung, has_ends, rigid, system, turning, winched


class Wang(BuiltinRung):
    """Wang's straight cable: every scene but one with nodes to anchor or lay on a bed."""

    name = "wang"
    stays_taut = True          # one stretch per section: a slack run makes the whole cable slack at once
    straight_cost = 1.0        # the unit of the rungs' costs

    def valid(self, scene: Scene) -> str:
        """"" unless the scene has an anchor or a seabed (the straight cable has no nodes), a winch (its length is fixed
        here; :mod:`cablesys.model.winch` is the control door's), a rigid body or a turning track (its
        steady turn is the node model's), or is a system of lines that is not a chain."""
        if system(scene):
            return SYSTEM
        if has_ends(scene):
            return NO_NODES
        if winched(scene):
            return WINCHED
        if rigid(scene):
            return ROTATES
        return TURNING if turning(scene) else ""

    def build(self, scene: Scene, segments: int = 1, cache=None) -> CableModel:
        """Wang's model of ``scene`` with one element per section (:func:`cablesys.model.build_model`)."""
        return build_model(self.scene(scene))

    def estimate(self, scene: Scene, assessment, segments: int = 1) -> dict:
        """Wang's estimated errors against the converged segmented cable (:mod:`cablesys.ladder.estimate`)."""
        return est.rung_error(assessment.estimates, self.name)

    def alone(self, scene: Scene, requested: str, segments) -> tuple:
        """A massless cable (in the plane or in 3-D): Wang's straight cable, its error against the segmented cable not
        estimated (there is no other rung to estimate it by), and no a posteriori check."""
        return 1, ("a massless cable (cable.cable_mass_switch < 0, Wang 1971's CBMAS): Wang's straight cable, the model "
                   "that idealization belongs to (the element rungs' nodes would have no mass); its error against a "
                   "cable with mass is not estimated"), False


RUNG = Wang()
