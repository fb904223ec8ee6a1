"""A towing ship's track in the horizontal plane: a circle, or a path of straight legs and arcs at a constant speed.

Wang (1971) p. 32, "Extensions": "cases where the towing ship is executing maneuvers involving motions in two
horizontal directions, such as towing in a circle". The tow point moves in the horizontal plane (x, z) of
cablesys' axes (y down); a heading psi is measured from +x towards +z, counter-clockwise seen from above, so that
a turn to port (the ship's left) is counter-clockwise and raises psi. The tow point runs at the speed U along

- ``kind = "circle"``: a circle of radius R about the origin, with heading psi_0 at t = 0 (at (x, z) =
  R (sin psi_0, -cos psi_0) counter-clockwise, -R (sin psi_0, -cos psi_0) clockwise):

      counter-clockwise:  x_s = R sin(w t + psi_0),  z_s = -R cos(w t + psi_0),
      clockwise:          x_s = R sin(w t - psi_0),  z_s =  R cos(w t - psi_0),     w = |Omega| = U / R,

  two sinusoids of ``top_motion.x`` and ``top_motion.z`` (the compiled path of any top motion); the run starts on
  the steady turn (:func:`cablesys.statics.turning.turning_state`);
- every other kind: a path from the origin at t = 0 with the initial heading psi_0, made of legs, each a straight
  of length l (curvature 0) or an arc of radius R through the heading change Delta psi (curvature +-1/R, length
  R |Delta psi|), followed at the arc length s = U t, and straight on at the last heading after the last leg
  (before t = 0, straight along psi_0: the ship towed straight up to the start):

  - ``"straight"``: no legs;
  - ``"turn"``: a straight ``lead_in``, an arc of ``radius`` through ``turn_angle_deg`` (any angle: 360 and more
    is a full circle and on), then straight on;
  - ``"zig-zag"``: the course swings +-``heading_change_deg`` (delta) about the base course psi_0, the turning
    points (waypoints) ``leg_length`` (L) apart along the legs, every turn an arc of ``radius`` R tangent to the
    legs it joins (a fillet, as a route is planned from waypoints): after the straight ``lead_in`` the first arc
    turns by delta (to ``direction``), the track then runs L/2 between its first two waypoints and L between the
    others, the arcs turn by 2 delta alternately back and forth, so that the waypoints lie on +- (L/2) sin delta
    about the base course. The straights are L/2 - R tan(delta/2) - R tan(delta), then L - 2 R tan(delta) long
    (each waypoint's tangent length R tan(turn/2) taken off both sides), which must not be negative. The path is
    periodic after its first arc and half leg: ``[arc -2 delta, straight, arc +2 delta, straight]`` repeated
    without end (:meth:`Track.pieces`);
  - ``"path"``: the ``[[top_motion.track.leg]]`` tables in order.

The tow point's position, velocity and acceleration are CasADi expressions of t (:mod:`cablesys.model.track_path`);
the position is C1 (continuous heading), the acceleration U^2 kappa steps where the curvature kappa does. The
run's initial state is the steady straight tow on psi_0 (the node model's equilibrium in the frame moving with the
tow point: :func:`cablesys.statics.catenary.straight_tow_state`), for the circle its steady turn.
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import ParameterError, require_finite, require_positive, require_range
from .fields import spec
from .harmonics import Sinusoid

TRACKS = ("circle", "straight", "turn", "zig-zag", "path")
#: the sense of a turn: counter-clockwise seen from above is a turn to port (+1), clockwise to starboard (-1)
DIRECTIONS = {"counter-clockwise": 1.0, "port": 1.0, "clockwise": -1.0, "starboard": -1.0}
LEG_KINDS = ("straight", "arc")
#: the fields each kind of track takes besides ``kind``, ``speed`` and ``heading_deg`` (required, optional)
_FIELDS = {"circle": (("radius",), ("direction",)), "straight": ((), ()),
           "turn": (("radius", "turn_angle_deg"), ("direction", "lead_in")),
           "zig-zag": (("radius", "heading_change_deg", "leg_length"), ("direction", "lead_in")),
           "path": (("leg",), ())}
_OWN = ("radius", "direction", "lead_in", "turn_angle_deg", "heading_change_deg", "leg_length", "leg")


def _sense(field: str, value) -> float:
    """+1 for a turn to port (counter-clockwise), -1 to starboard (clockwise)."""
    if value not in DIRECTIONS:
        raise ParameterError(field, value, f"must be one of {tuple(DIRECTIONS)}")
    return DIRECTIONS[value]


@dataclasses.dataclass(frozen=True, kw_only=True)
class TrackLeg:
    """One leg of a path (``[[top_motion.track.leg]]``): a straight of a length, or an arc of a radius through a
    heading change to port or starboard."""

    kind: str = spec("none", f"one of {LEG_KINDS}")
    length: float | None = spec("length", "length of a straight leg (m, >= 0)", None)
    radius: float | None = spec("length", "radius of an arc (m, > 0)", None)
    angle_deg: float | None = spec("angle_deg", "heading change along an arc (degrees, > 0; 360 is a full circle)",
                                   None)
    direction: str | None = spec("none", f"sense of an arc: one of {tuple(DIRECTIONS)} (port: counter-clockwise "
                                 "seen from above)", None)

    def __post_init__(self):
        name = "top_motion.track.leg"
        if self.kind not in LEG_KINDS:
            raise ParameterError(f"{name}.kind", self.kind, f"must be one of {LEG_KINDS}")
        need = ("length",) if self.kind == "straight" else ("radius", "angle_deg", "direction")
        for f in ("length", "radius", "angle_deg", "direction"):
            v = getattr(self, f)
            if f in need and v is None:
                raise ParameterError(f"{name}.{f}", "missing", f"is required for a {self.kind} leg")
            if f not in need and v is not None:
                raise ParameterError(f"{name}.{f}", v, f"must be unset for a {self.kind} leg (it takes {need})")
        if self.kind == "straight":
            require_finite(f"{name}.length", self.length)
            if self.length < 0.0:
                raise ParameterError(f"{name}.length", self.length, "must be >= 0 (m)")
        else:
            require_positive(f"{name}.radius", self.radius, "m")
            require_positive(f"{name}.angle_deg", self.angle_deg, "deg")
            _sense(f"{name}.direction", self.direction)

    def piece(self) -> tuple[float, float]:
        """(length along the path (m), signed curvature (1/m), + to port)."""
        if self.kind == "straight":
            return float(self.length), 0.0
        return self.radius * math.radians(self.angle_deg), DIRECTIONS[self.direction] / self.radius


@dataclasses.dataclass(frozen=True, kw_only=True)
class Track:
    """The tow point's path in the horizontal plane at a constant speed (module docstring for each ``kind``)."""

    kind: str = spec("none", f"path: one of {TRACKS}", "circle")
    speed: float = spec("velocity", "the tow point's speed along its path (m/s)")
    radius: float | None = spec("length", "radius of the circle, of the turn's arc or of the zig-zag's turns (m)", None)
    direction: str | None = spec("none", f"sense of the circle, the turn, or the zig-zag's first turn: one of "
                                 f"{tuple(DIRECTIONS)} (unset: counter-clockwise, to port)", None)
    heading_deg: float | None = spec("angle_deg", "initial heading psi_0, degrees from +x towards +z (counter-clockwise "
                                     "seen from above); the zig-zag's base course; unset: +x (a straight track then "
                                     "stays in the x-y plane)", None)
    lead_in: float | None = spec("length", "turn, zig-zag: the straight run before the first turn begins (m; unset: 0)",
                                 None)
    turn_angle_deg: float | None = spec("angle_deg", "turn: the heading change of its arc (degrees, > 0; 360 and more "
                                        "turns full circles)", None)
    heading_change_deg: float | None = spec("angle_deg", "zig-zag: the course's swing either side of the base course "
                                            "(degrees, in (0, 90))", None)
    leg_length: float | None = spec("length", "zig-zag: the distance between turning points (waypoints) along a leg (m)",
                                    None)
    leg: tuple[TrackLeg, ...] = spec("none", "path: its legs in order ([[top_motion.track.leg]] tables)", ())

    def __post_init__(self):
        if self.kind not in TRACKS:
            raise ParameterError("top_motion.track.kind", self.kind, f"must be one of {TRACKS} (a steady tow in the "
                                 "ship's frame, the tow point still and the water moving, is environment.system_speed)")
        require_positive("top_motion.track.speed", self.speed, "m/s")
        if self.heading_deg is not None:
            require_finite("top_motion.track.heading_deg", self.heading_deg)
        object.__setattr__(self, "leg", tuple(self.leg))
        need, may = _FIELDS[self.kind]
        for f in _OWN:
            v = getattr(self, f)
            unset = v is None or v == ()
            if f in need and unset:
                raise ParameterError(f"top_motion.track.{f}", "missing", f"is required for kind = {self.kind!r}")
            if f not in need + may and not unset:
                raise ParameterError(f"top_motion.track.{f}", v, f"must be unset for kind = {self.kind!r} (it takes "
                                     f"{need + may or 'speed and heading_deg only'})")
        if self.radius is not None:
            require_positive("top_motion.track.radius", self.radius, "m")
        if self.direction is not None:
            _sense("top_motion.track.direction", self.direction)
        if self.lead_in is not None:
            require_finite("top_motion.track.lead_in", self.lead_in)
            if self.lead_in < 0.0:
                raise ParameterError("top_motion.track.lead_in", self.lead_in, "must be >= 0 (m)")
        if self.turn_angle_deg is not None:
            require_positive("top_motion.track.turn_angle_deg", self.turn_angle_deg, "deg")
        for k, g in enumerate(self.leg):
            if not isinstance(g, TrackLeg):
                raise ParameterError(f"top_motion.track.leg[{k}]", g, "must be a TrackLeg (kind, length or radius, "
                                     "angle_deg, direction)")
        if self.kind == "zig-zag":
            require_range("top_motion.track.heading_change_deg", self.heading_change_deg, 0.0, 90.0, "deg",
                          lo_open=True, hi_open=True)
            require_positive("top_motion.track.leg_length", self.leg_length, "m")
            d, R = math.radians(self.heading_change_deg), self.radius
            shortest = 2.0 * R * (math.tan(d / 2) + math.tan(d))     # the first half leg's two tangent lengths
            if self.leg_length < shortest:
                raise ParameterError("top_motion.track.leg_length", self.leg_length, f"must be >= {shortest:.6g} m: "
                                     f"2 R (tan(delta/2) + tan(delta)) for radius {R:g} m and heading change "
                                     f"{self.heading_change_deg:g} deg, so that the straights between the turns (the "
                                     "first one half a leg) are not negative")

    # ------------------------------------------------------------------ derived
    @property
    def sense(self) -> float:
        """+1 when the circle, the turn or the zig-zag's first turn goes to port (counter-clockwise), else -1."""
        return DIRECTIONS[self.direction or "counter-clockwise"]

    @property
    def heading(self) -> float:
        """psi_0 (rad)."""
        return math.radians(self.heading_deg or 0.0)

    @property
    def is_circle(self) -> bool:
        return self.kind == "circle"

    @property
    def keeps_heading(self) -> bool:
        """True for a track whose heading never changes: a straight course, or a path of straight legs alone."""
        return self.kind == "straight" or (self.kind == "path" and all(g.kind == "straight" for g in self.leg))

    @property
    def in_plane(self) -> bool:
        """True for a straight track with no heading set: the tow point moves along +x, in the x-y plane."""
        return self.kind == "straight" and self.heading_deg is None

    @property
    def turn_rate(self) -> float:
        """The circle's Omega (rad/s) about the upward vertical: U / R, negative for a clockwise turn."""
        if not self.is_circle:
            raise ParameterError("top_motion.track.kind", self.kind, "has no single turn rate: only a circle has")
        return self.sense * self.speed / self.radius

    def pieces(self) -> tuple[tuple, tuple]:
        """(legs, cycle) of a path (not a circle): each a tuple of (length (m), signed curvature (1/m, + to port));
        the legs are followed once from t = 0, then the cycle repeats without end (a zig-zag), or with no cycle the
        path goes straight on after its legs. The number of pieces depends on the kind only (a leg of length 0 is
        kept), so that a sweep over the numbers keeps one model structure."""
        k = self.kind
        if k == "straight":
            return (), ()
        if k == "path":
            return tuple(g.piece() for g in self.leg), ()
        R, sense, lead = self.radius, self.sense, self.lead_in or 0.0
        if k == "turn":
            return ((lead, 0.0), (R * math.radians(self.turn_angle_deg), sense / R)), ()
        if k == "zig-zag":
            d, L = math.radians(self.heading_change_deg), self.leg_length
            first = 0.5 * L - R * (math.tan(d / 2) + math.tan(d))
            straight = L - 2.0 * R * math.tan(d)
            legs = ((lead, 0.0), (R * d, sense / R), (first, 0.0))
            cycle = ((2 * R * d, -sense / R), (straight, 0.0), (2 * R * d, sense / R), (straight, 0.0))
            return legs, cycle
        raise ParameterError("top_motion.track.kind", k, "a circle is two sinusoids, not pieces (Track.sinusoids)")

    def parameter_items(self) -> list[tuple[str, float]]:
        """(label, SI value) of a path's entries of the parameter vector (cablesys.model.params): speed, initial
        heading (rad; not for a straight track in the x-y plane, which has none) and every piece's length and
        curvature; the circle's are its sinusoids'."""
        if self.is_circle:
            return []
        legs, cycle = self.pieces()
        items = [("top_motion.track.speed", float(self.speed))]
        items += [] if self.in_plane else [("top_motion.track.heading", self.heading)]
        for name, ps in (("legs", legs), ("cycle", cycle)):
            for j, (length, kappa) in enumerate(ps):
                items += [(f"top_motion.track.{name}[{j}].length", float(length)),
                          (f"top_motion.track.{name}[{j}].curvature", float(kappa))]
        return items

    def structure(self) -> tuple | None:
        """What fixes the shape of the path's functions (the number of legs and cycle pieces); None for the circle,
        whose sinusoids count in the model's structure already."""
        if self.is_circle:
            return None
        legs, cycle = self.pieces()
        return ("track", len(legs), len(cycle), self.in_plane)

    def sinusoids(self) -> tuple[tuple, tuple]:
        """(x terms, z terms) of the circle's motion (module docstring): counter-clockwise x = R sin(w t + psi_0),
        z = -R cos(w t + psi_0); clockwise x = R sin(w t - psi_0), z = R cos(w t - psi_0) (w = |Omega|)."""
        w, r, psi = abs(self.turn_rate), self.radius, self.heading
        if self.turn_rate > 0:
            return ((Sinusoid(amplitude=r, frequency=w, phase=psi % (2 * math.pi)),),
                    (Sinusoid(amplitude=r, frequency=w, phase=(psi - 0.5 * math.pi) % (2 * math.pi)),))
        return ((Sinusoid(amplitude=r, frequency=w, phase=-psi % (2 * math.pi)),),
                (Sinusoid(amplitude=r, frequency=w, phase=(0.5 * math.pi - psi) % (2 * math.pi)),))
