"""The ends of a line that are not a ship's top or a free body: an anchor, the seabed, a winch (SI units inside).

Immutable and validated like :mod:`.components` (a :class:`~cablesys.errors.ParameterError` naming the field,
its value and the allowed range, before any model is built); the segmented node model carries them
(:mod:`cablesys.model.segmented`, :mod:`cablesys.model.segmented_seabed`, :mod:`cablesys.model.segmented_winch`).
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import ParameterError, require_nonnegative, require_positive, require_range
from .components import check_all_finite
from .fields import spec


@dataclasses.dataclass(frozen=True, kw_only=True)
class Anchor:
    """A fixed lower end: the last section's lower node held at (x, y) instead of a free body.

    Coordinates are the segmented model's node coordinates (cablesys.model.segmented): x
    horizontal from the top's mean position, y down from the top's mean depth. The last
    section's body sits at the anchor: its weight and drag act on the anchor, not on the line.
    """

    x: float = spec("length", "horizontal position of the anchor from the top's mean position (+x to the right)")
    y: float = spec("length", "depth of the anchor below the top's mean depth (y down)")

    def __post_init__(self):
        check_all_finite(self, "anchor")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Seabed:
    """A flat or sloped seabed acting on the nodes of a segmented cable.

    Contact follows MoorDyn's seabed model (Hall & Goupee 2015; MoorDyn v2 documentation,
    moordyn.readthedocs.io, kBot and cBot): a node of contact length l (half of each adjacent
    element's unstretched length) and diameter d penetrating the bed by delta feels the normal
    force F_n = max(0, (k delta + c delta') d l) while delta > 0. Coulomb friction along the
    bed opposes the node's sliding speed v_t: F_f = -mu F_n tanh(v_t / friction_speed), a smooth
    regularisation of sign(v_t) (so the integrator is not stalled by stick-slip; MoorDyn v2
    regularises with a linear damping instead, NREL/TP-5000-82033).
    """

    depth: float = spec("length", "depth of the seabed below the still surface at x = 0 (the top's mean horizontal position)")
    slope_deg: float = spec("angle_deg", "slope of the seabed in degrees, + when it deepens towards +x; in (-60, 60)", 0.0)
    stiffness: float = spec("stiffness_per_area", "normal stiffness per unit contact area k (MoorDyn kBot)", 3.0e6)
    damping: float = spec("damping_per_area", "normal damping per unit contact area c (MoorDyn cBot)", 3.0e5)
    friction_axial: float = spec("none", "Coulomb friction coefficient for sliding along the line", 0.0)
    friction_lateral: float = spec("none", "Coulomb friction coefficient for sliding across the line (out of the plane: "
                                           "acts in the 3-D model; the planar model's nodes slide along the line only)", 0.0)
    friction_speed: float = spec("velocity", "sliding speed v_s of the tanh regularisation of the friction (m/s)", 0.01)

    def __post_init__(self):
        check_all_finite(self, "seabed")
        require_range("seabed.slope_deg", self.slope_deg, -60.0, 60.0, "deg", lo_open=True, hi_open=True)
        require_positive("seabed.stiffness", self.stiffness, "Pa/m")
        for name in ("damping", "friction_axial", "friction_lateral"):
            require_nonnegative(f"seabed.{name}", getattr(self, name))
        require_positive("seabed.friction_speed", self.friction_speed, "m/s")

    def bed_y(self, x: float, top_depth: float) -> float:
        """The bed's y (down from the top's mean depth, m) at horizontal position x (m)."""
        return self.depth - top_depth + x * math.tan(math.radians(self.slope_deg))


def payout_profile(t, speed, start, duration, ramp, fmin=min, fmax=max):
    """The winch's payout profile at time t: (Delta L, w, alpha) = (length paid out since t = 0 (m), payout speed
    w = dL/dt (m/s, + pays out), acceleration alpha = dw/dt (m/s^2)).

    w rises from 0 to ``speed`` over ``ramp`` seconds from ``start``, holds, and falls back to 0 over the last
    ``ramp`` seconds of ``duration``; each ramp is the smoothstep S(x) = 3 x^2 - 2 x^3 (x = time into the ramp /
    ramp), so w and alpha = speed S'(x) / ramp are continuous. Integrating S (int_0^x S = x^3 - x^4 / 2, 1/2 at
    x = 1): Delta L = speed [ramp I(x_1) + max(t - start - ramp, 0) - ramp I(x_2) - max(t - start - duration, 0)]
    with x_1, x_2 the clipped times into the rising and the falling ramp; at the end Delta L = speed (duration - ramp).
    ``fmin``/``fmax`` are the elementwise min/max of the number type (``min``/``max`` for floats, CasADi's
    ``fmin``/``fmax`` for a symbolic t), so the model and the scene's check evaluate this one formula."""
    clip = lambda x: fmin(fmax(x, 0.0), 1.0)
    x1 = clip((t - start) / ramp)
    x2 = clip((t - start - duration + ramp) / ramp)
    S = lambda x: x * x * (3.0 - 2.0 * x)
    I = lambda x: x ** 3 - 0.5 * x ** 4
    dS = lambda x: 6.0 * x * (1.0 - x)
    dL = speed * (ramp * I(x1) + fmax(t - start - ramp, 0.0) - ramp * I(x2) - fmax(t - start - duration, 0.0))
    return dL, speed * (S(x1) - S(x2)), speed * (dS(x1) - dS(x2)) / ramp


@dataclasses.dataclass(frozen=True, kw_only=True)
class Winch:
    """A winch at the top of the first section: its unstretched length L(t) changes in time (segmented cable only).

    The first section's cable (its ``cable.length`` at ``cable.tension_ref``, zero-tension length l_0, Wang 1971
    eq. 1) is what is in the water at t = 0; from ``start`` the winch pays out (``speed`` > 0) or hauls in
    (``speed`` < 0) at the constant ``speed``, reached and left over smooth ramps of ``ramp`` seconds, for
    ``duration`` seconds in all (:func:`payout_profile`): L(t) = l_0 + Delta L(t), at the end
    l_0 + speed (duration - ramp). L must stay in (0, max_length] over the run (checked by the scene).
    """

    speed: float = spec("velocity", "payout speed at full speed (m/s, + pays out, - hauls in)")
    start: float = spec("time", "time the winch starts (s, >= 0: the run starts at rest with L = l_0)", 0.0)
    duration: float = spec("time", "time from start to stop, ramps included (s, > 0)")
    ramp: float = spec("time", "duration of each smooth speed ramp (s, > 0, 2 ramp <= duration)", 1.0)
    max_length: float = spec("length", "the most zero-tension cable the drum holds / the line may pay out to (m)")

    def __post_init__(self):
        check_all_finite(self, "winch")
        require_nonnegative("winch.start", self.start, "s")
        require_positive("winch.duration", self.duration, "s")
        require_positive("winch.ramp", self.ramp, "s")
        if 2.0 * self.ramp > self.duration:
            raise ParameterError("winch.ramp", self.ramp, f"must be <= duration / 2 = {self.duration / 2:g} s: the "
                                 "speed ramps up and down within the duration")
        require_positive("winch.max_length", self.max_length, "m")

    def profile(self, t: float) -> tuple:
        """(Delta L (m), w (m/s), alpha (m/s^2)) at time t (:func:`payout_profile`)."""
        return payout_profile(t, self.speed, self.start, self.duration, self.ramp)

    @property
    def paid_out(self) -> float:
        """Length paid out over the whole profile, speed (duration - ramp) (m; < 0 hauled in)."""
        return self.speed * (self.duration - self.ramp)
