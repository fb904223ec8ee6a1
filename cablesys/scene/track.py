"""A towing ship's track in the horizontal plane: towing in a circle.

Wang (1971) p. 32, "Extensions": "cases where the towing ship is executing maneuvers involving
motions in two horizontal directions, such as towing in a circle". The tow point moves on a
circle of radius R at speed U about the top's mean position (the circle's centre is the origin of
cablesys' x and z; y is down), starting at (x, z) = (0, -R) (counter-clockwise seen from above)
or (0, R) (clockwise), heading +x:

    x_s = R sin(Omega t),   z_s = -/+ R cos(Omega t),   |Omega| = U / R,

two sinusoids of ``top_motion.x`` and ``top_motion.z`` (the compiled path of any top motion). The
turn rate Omega is signed about the upward vertical (+: counter-clockwise seen from above). The
steady turn, the cable's shape that rotates rigidly with the tow point, is the run's initial state
(:func:`cablesys.statics.turning.turning_state`).
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import ParameterError, require_positive
from .fields import spec
from .harmonics import Sinusoid

TRACKS = ("circle",)
DIRECTIONS = ("counter-clockwise", "clockwise")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Track:
    """The tow point's path in the horizontal plane (``kind = "circle"``: towing in a circle)."""

    kind: str = spec("none", f"path: one of {TRACKS}", "circle")
    radius: float = spec("length", "radius of the circle the tow point runs on")
    speed: float = spec("velocity", "the tow point's speed along the circle")
    direction: str = spec("none", f"sense of the turn seen from above: one of {DIRECTIONS}", "counter-clockwise")

    def __post_init__(self):
        if self.kind not in TRACKS:
            raise ParameterError("top_motion.track.kind", self.kind, f"must be one of {TRACKS} (a straight tow is "
                                 "environment.system_speed)")
        require_positive("top_motion.track.radius", self.radius, "m")
        require_positive("top_motion.track.speed", self.speed, "m/s")
        if self.direction not in DIRECTIONS:
            raise ParameterError("top_motion.track.direction", self.direction, f"must be one of {DIRECTIONS}")

    @property
    def turn_rate(self) -> float:
        """Omega (rad/s) about the upward vertical: U / R, negative for a clockwise turn."""
        w = self.speed / self.radius
        return w if self.direction == "counter-clockwise" else -w

    def sinusoids(self) -> tuple[tuple, tuple]:
        """(x terms, z terms) of the tow point's motion (module docstring)."""
        w, r = abs(self.turn_rate), self.radius
        lag = -0.5 * math.pi if self.turn_rate > 0 else 0.5 * math.pi      # z = -R cos (ccw), +R cos (cw)
        return ((Sinusoid(amplitude=r, frequency=w, phase=0.0),),
                (Sinusoid(amplitude=r, frequency=w, phase=lag % (2 * math.pi)),))
