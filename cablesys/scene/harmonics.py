"""The sinusoidal terms of a scene: a deep-water surface wave component and a top-motion sinusoid.

Both the sea realisation (:mod:`.sea`, which turns a spectrum into these terms) and the scene
components (:mod:`.components`, whose ``Environment.waves`` and ``TopMotion.x``/``y`` hold them)
use them; they depend on neither.
"""

from __future__ import annotations

import dataclasses

from ..errors import require_finite, require_nonnegative, require_positive
from .fields import spec


@dataclasses.dataclass(frozen=True, kw_only=True)
class Wave:
    """A deep-water surface wave component (Wang 1971 eq. 26)."""

    amplitude: float = spec("length", "wave amplitude a")
    length: float = spec("length", "wave length lambda; n = 2 pi / lambda, sigma = sqrt(g n)")
    phase: float = spec("angle", "phase added to n x - sigma t", 0.0)
    heading_deg: float | None = spec("angle_deg", "direction the wave travels in the horizontal plane, degrees from +x "
                                     "towards +z (seen from above, counter-clockwise); the phase becomes "
                                     "n (x cos b + z sin b) - sigma t; unset: along +x, a planar scene", None)

    def __post_init__(self):
        require_nonnegative("waves.amplitude", self.amplitude, "m")
        require_positive("waves.length", self.length, "m")
        require_finite("waves.phase", self.phase)
        if self.heading_deg is not None:
            require_finite("waves.heading_deg", self.heading_deg)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Sinusoid:
    """One term amplitude * sin(frequency * t + phase) of the top motion."""

    amplitude: float = spec("length", "amplitude")
    frequency: float = spec("frequency", "circular frequency omega")
    phase: float = spec("angle", "phase", 0.0)

    def __post_init__(self):
        require_finite("top_motion.amplitude", self.amplitude)
        require_positive("top_motion.frequency", self.frequency, "rad/s")
        require_finite("top_motion.phase", self.phase)
