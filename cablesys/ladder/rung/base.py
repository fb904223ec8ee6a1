"""What the built-in rungs share: the scene a rung runs, the scene kinds that limit which rungs can run a scene,
and the base of every built-in rung (:class:`BuiltinRung`).

A rung's validity (:meth:`BuiltinRung.valid`) is "" when it can run a scene, else the sentence saying why not. These
kinds of scene limit the rungs so far: a 3-D scene (Wang's straight cable, the node model and the quasi-static rungs
have three-dimensional equations, Wang 1971 p. 32; the frequency rung is planar), a massless cable (Wang's CBMAS < 0,
Wang 1971 program notes: an idealization of his straight cable; the element rungs' nodes would have no mass), an
anchored line or a seabed (they act on the nodes of the segmented cable, which the straight cable has none of), a
winch (a varying length, carried by the node model only) and a towing ship's track (its steady start, the turn or
the straight tow, is found for the node model only). A rigid body (``body.pitch_inertia``) limits them too: its
orientation (the pitch in the plane, a quaternion in 3-D) is a coordinate of the node model alone
(:mod:`cablesys.model.rigid_body`). So does a system of lines joined at points that is not a chain (``scene.system``):
only the node model builds a graph of lines (:mod:`cablesys.model.system`).
"""

from __future__ import annotations

import dataclasses
import math

from ...scene import Scene


def with_segments(scene: Scene, n: int) -> Scene:
    """``scene`` with every section divided into ``n`` elements (1: Wang's straight cable). Elements each have their
    own inclination: a chain whose sections share one swing angle (``angles = "shared"``, the dual-isolation model
    of Wang 1971 p. 33) is divided with every element's angle its own (``per_section``). A system of lines: every
    section of every line divided into ``n``."""
    if system(scene):
        return dataclasses.replace(scene, system=scene.system.with_segments(int(n)))
    secs = tuple(dataclasses.replace(s, cable=dataclasses.replace(s.cable, segments=int(n))) for s in scene.sections)
    angles = "per_section" if n > 1 else scene.angles
    return dataclasses.replace(scene, sections=secs, angles=angles)


def three_d(scene: Scene) -> bool:
    """True when Wang's 3-D equations run the scene (:attr:`cablesys.scene.Scene.three_d`)."""
    return bool(getattr(scene, "three_d", False))


def cables(scene: Scene) -> tuple:
    """Every cable of the scene: its sections' (a chain) or its lines' sections (a system)."""
    if getattr(scene, "system", None) is not None:
        return tuple(c for line in scene.system.line for c in line.section)
    return tuple(sec.cable for sec in scene.sections)


def massless(scene: Scene) -> bool:
    """True when a section's cable is massless (``cable.cable_mass_switch < 0``, Wang 1971's CBMAS)."""
    return any(c.cable_mass_switch < 0 for c in cables(scene))


def has_ends(scene: Scene) -> bool:
    """True when the scene has an ``[anchor]`` or a ``[seabed]``, which act on the segmented cable's nodes."""
    return getattr(scene, "anchor", None) is not None or getattr(scene, "seabed", None) is not None


def rigid(scene: Scene) -> bool:
    """True when a section's body, or a system's body point, is rigid and pitches (``body.pitch_inertia`` set): the
    node model's coordinate."""
    if system(scene):
        return any(p.body is not None and p.body.is_rigid for p in scene.system.point)
    return any(getattr(sec.body, "is_rigid", False) for sec in scene.sections)


def winched(scene: Scene) -> bool:
    """True when the scene has a ``[winch]``: the first section's length changes in time, which only the node model
    carries (:mod:`cablesys.model.segmented_winch`)."""
    return getattr(scene, "winch", None) is not None


def system(scene: Scene) -> bool:
    """True when the scene is a system of lines joined at points that is not a chain (``scene.system``): the node
    model of a graph of lines (:mod:`cablesys.model.system`) builds it."""
    return getattr(scene, "system", None) is not None


def scene_segments(scene: Scene) -> int:
    """The most elements a section of the scene has (a chain's sections, or a system's line sections)."""
    return max(c.segments for c in cables(scene))


def turning(scene: Scene) -> bool:
    """True when the tow point follows a track (``top_motion.track``: a circle, a straight, a turn, a zig-zag or a
    path): the run starts on the steady turn or the steady straight tow, which the statics find for the node model
    (:mod:`cablesys.statics.turning`, :mod:`cablesys.statics.tow`)."""
    return getattr(getattr(scene, "top_motion", None), "track", None) is not None


PLANAR = ("a 3-D scene: the frequency rung is planar; Wang's straight cable, the quasi-static rungs and the node model "
          "(segmented) have three-dimensional equations")
WITH_MASS = ("a massless cable (cable.cable_mass_switch < 0, Wang 1971's CBMAS) belongs to Wang's straight cable: the "
             "element rungs' nodes would have no mass, and the ladder has no estimate of the other rungs against it")
NO_NODES = ("an anchored line or a seabed: only the node model (segmented) has nodes to anchor and to lay on the bed")
ROTATES = ("a rigid body (body.pitch_inertia): its orientation (pitch in the plane, a quaternion in 3-D) is a "
           "coordinate of the node model (segmented) only")
WINCHED = ("a winch ([winch]): only the node model (segmented) carries a varying cable length; the other rungs "
           "have a fixed one and would ignore the payout")
SYSTEM = ("a system of lines joined at points that is not a chain ([[point]], [[line]]): only the node model "
          "(segmented) builds a graph of lines")
TURNING = ("a towing ship's track (top_motion.track: a circle, a straight, a turn, a zig-zag or a path): the run starts "
           "on the steady turn or the steady straight tow, which the statics find for the node model (segmented) only")


def reduced_validity(scene: Scene) -> str:
    """The validity of a rung built on Wang's straight cable with mass, in the plane or in space, that the node model
    does not carry (the quasi-static rungs): "" or why not (see the module docstring)."""
    if system(scene):
        return SYSTEM
    if massless(scene):
        return WITH_MASS
    if rigid(scene):
        return ROTATES
    if winched(scene):
        return WINCHED
    if turning(scene):           # a straight track along x is planar: its straight tow is the node model's
        return TURNING
    return NO_NODES if has_ends(scene) else ""


def straight_validity(scene: Scene) -> str:
    """The validity of a rung built on Wang's planar straight cable with mass (the frequency rung's periodic orbit):
    "" or why not (see the module docstring)."""
    if system(scene):
        return SYSTEM
    return PLANAR if three_d(scene) else reduced_validity(scene)


NOT_ESTIMATED = {"body": math.nan, "tension": math.nan}


class BuiltinRung:
    """A rung of the ladder's own (a :class:`~cablesys.ladder.rungs.Rung` with elements).

    ``name`` is its model name (:data:`cablesys.scene.components.RUNGS`); ``elements`` whether it takes N elements per
    section (the scene it runs keeps ``segments``, :meth:`scene`); ``time_domain`` whether it steps in time (the
    frequency rung is a periodic orbit); ``stays_taut`` whether a run that goes slack is outside its validity (one
    stretch per section, or a quasi-static one: :func:`cablesys.ladder.auto.after_run`). ``straight_cost`` is its
    run's cost relative to Wang's straight cable with one element; with N > 1 elements a rung costs N (the node
    model's N, the unit of :meth:`~cablesys.ladder.rungs.Rung.cost`; the element plans weigh their own,
    :func:`~cablesys.ladder.choice.element_plan`).
    """

    name = ""
    elements = False
    straight = True            # it runs one element per section (the segmented rung needs two)
    time_domain = True
    stays_taut = False
    straight_cost = 1.0
    model_of = None            # another rung whose model this one runs (a RungCache builds it once for both)
    shortcut = False           # it answers model_of's run without stepping: under auto in that rung's place where valid

    def valid(self, scene: Scene) -> str:
        """"" when this rung can run ``scene``, else why not."""
        return straight_validity(scene)

    def segments(self, segments: int) -> int:
        """The elements per section this rung runs when asked for ``segments`` (1 unless it takes elements)."""
        return int(segments) if self.elements else 1

    def scene(self, scene: Scene, segments: int = 1) -> Scene:
        """The scene this rung runs: ``scene`` with :meth:`segments` elements per section."""
        return with_segments(scene, self.segments(segments))

    def structure(self, scene_run: Scene) -> tuple:
        """What sets this rung's model besides the structure of the scene it runs (a cache key's part)."""
        return ()

    def cost(self, scene: Scene, assessment=None, segments: int = 1) -> float:
        """The run's relative cost (see the class docstring)."""
        n = self.segments(segments)
        return self.straight_cost if n <= 1 else float(n)

    def alone(self, scene: Scene, requested: str, segments) -> tuple:
        """(segments, reason, checked a posteriori) where this rung is the only one valid for ``scene``."""
        raise NotImplementedError(f"the {self.name} rung is never the only valid one")

    def __repr__(self) -> str:
        return f"<rung {self.name}>"
