"""The sinusoidal terms of a scene: a deep-water surface wave component and a top-motion sinusoid.

Both the sea realisation (:mod:`.sea`, which turns a spectrum into these terms) and the scene
components (:mod:`.components`, whose ``Environment.waves`` and ``TopMotion.x``/``y`` hold them)
use them; they depend on neither.
"""

from __future__ import annotations

import dataclasses

from ..errors import ParameterError, require_finite, require_positive, require_range
from .fields import spec

#: Largest amplitude of a wave or top-motion term (m): ten kilometres, beyond any sea state or
#: vessel motion; it also keeps ``amplitude * frequency**2`` and the ladder's trigonometric
#: arguments far from floating-point overflow.
MAX_AMPLITUDE_M = 1e4
#: Largest circular frequency of a top-motion term (rad/s): a period of 0.6 ms, far above any
#: wave or vessel motion (and any frequency a cable model resolves).
MAX_FREQUENCY_RAD_S = 1e4
#: Largest velocity amplitude |a| omega of a top-motion term (m/s): ten times a fast ship's
#: speed; with the two bounds above alone a term could move at 1e8 m/s, and the ladder's
#: linearised drag (damping proportional to |a| omega) then overflows its trigonometric terms.
MAX_VELOCITY_M_S = 100.0
#: Range of a deep-water wave length (m): from 1 cm (below it, capillary waves, not gravity
#: waves; sigma = sqrt(g 2 pi / lambda) ~ 78 rad/s) to 1000 km (beyond any ocean basin's swell).
WAVE_LENGTH_RANGE_M = (1e-2, 1e6)


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
        require_range("waves.amplitude", self.amplitude, 0.0, MAX_AMPLITUDE_M, "m")
        require_positive("waves.length", self.length, "m")
        require_range("waves.length", self.length, *WAVE_LENGTH_RANGE_M, "m")
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
        require_range("top_motion.amplitude", self.amplitude, -MAX_AMPLITUDE_M, MAX_AMPLITUDE_M, "m")
        require_positive("top_motion.frequency", self.frequency, "rad/s")
        require_range("top_motion.frequency", self.frequency, 0.0, MAX_FREQUENCY_RAD_S, "rad/s", lo_open=True)
        v = abs(self.amplitude) * self.frequency
        if not v <= MAX_VELOCITY_M_S:
            raise ParameterError("top_motion.amplitude * frequency", v,
                                 f"must be <= {MAX_VELOCITY_M_S:g} m/s (the term's velocity amplitude; amplitude = "
                                 f"{self.amplitude:g} m, frequency = {self.frequency:g} rad/s)")
        require_finite("top_motion.phase", self.phase)
