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
    z: float | None = spec("length", "sway position of the anchor from the top's mean position (+z; set: the scene "
                                     "runs in 3-D; unset: 0, in the plane)", None)

    def __post_init__(self):
        check_all_finite(self, "anchor")

    @property
    def position(self) -> tuple:
        """(x, y, z) of the anchor (m), z = 0 when unset."""
        return (self.x, self.y, 0.0 if self.z is None else self.z)


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
    slope_deg: float = spec("angle_deg", "slope of the seabed in degrees, + when it deepens towards +x (towards the "
                                         "heading in 3-D); in (-60, 60)", 0.0)
    heading_deg: float | None = spec("angle_deg", "horizontal direction in which the bed deepens, degrees from +x "
                                                  "towards +z (set: the scene runs in 3-D; unset: +x, in the plane)", None)
    stiffness: float = spec("stiffness_per_area", "normal stiffness per unit contact area k (MoorDyn kBot)", 3.0e6)
    damping: float = spec("damping_per_area", "normal damping per unit contact area c (MoorDyn cBot)", 3.0e5)
    friction_axial: float = spec("none", "Coulomb friction coefficient for sliding along the line", 0.0)
    friction_lateral: float = spec("none", "Coulomb friction coefficient for sliding across the line (acts in the 3-D "
                                           "model; the planar model's nodes slide along the line only)", 0.0)
    friction_speed: float = spec("velocity", "sliding speed v_s of the tanh regularisation of the friction (m/s)", 0.01)

    def __post_init__(self):
        check_all_finite(self, "seabed")
        require_range("seabed.slope_deg", self.slope_deg, -60.0, 60.0, "deg", lo_open=True, hi_open=True)
        require_positive("seabed.stiffness", self.stiffness, "Pa/m")
        for name in ("damping", "friction_axial", "friction_lateral"):
            require_nonnegative(f"seabed.{name}", getattr(self, name))
        require_positive("seabed.friction_speed", self.friction_speed, "m/s")

    @property
    def heading(self) -> float:
        """The heading of the slope (rad from +x towards +z), 0 when unset."""
        return math.radians(self.heading_deg or 0.0)

    def bed_y(self, x: float, top_depth: float, z: float = 0.0) -> float:
        """The bed's y (down from the top's mean depth, m) at horizontal position (x, z) (m):
        y_0 + tan(slope) (x cos(heading) + z sin(heading))."""
        along = x * math.cos(self.heading) + z * math.sin(self.heading)
        return self.depth - top_depth + along * math.tan(math.radians(self.slope_deg))


def _smoothstep(fmin, fmax):
    """(S, I, S') of the smoothstep S(x) = 3 x^2 - 2 x^3 on the clipped x in [0, 1]: I(x) = int_0^x S = x^3 - x^4 / 2
    (1/2 at x = 1), S'(x) = 6 x (1 - x); S(0) = S'(0) = S'(1) = 0, S(1) = 1."""
    clip = lambda x: fmin(fmax(x, 0.0), 1.0)
    return (clip, lambda x: x * x * (3.0 - 2.0 * x), lambda x: x ** 3 - 0.5 * x ** 4, lambda x: 6.0 * x * (1.0 - x))


def legs_profile(t, speeds, durations, start, ramp, fmin=min, fmax=max):
    """The winch's payout profile of legs at time t: (Delta L, w, alpha) = (length paid out since t = 0 (m), payout
    speed w = dL/dt (m/s, + pays out), acceleration alpha = dw/dt (m/s^2)).

    Leg k holds the speed v_k for d_k seconds; legs follow each other from ``start``, leg k beginning at
    tau_k = start + d_0 + ... + d_(k-1). The speed passes from v_(k-1) to v_k (v_(-1) = 0: from rest) over the first
    ``ramp`` seconds of leg k, and back to rest over ``ramp`` seconds after the last leg (tau_n = the end of the last
    leg, v_n = 0), each by the smoothstep S(x) (x = (t - tau_k) / ramp clipped to [0, 1]), so w and alpha are
    continuous and |alpha| <= 1.5 |v_k - v_(k-1)| / ramp. Superposing the n + 1 transitions:
    w = sum_k (v_k - v_(k-1)) S(x_k), alpha = sum_k (v_k - v_(k-1)) S'(x_k) / ramp, and, integrating each
    (int S = ramp I(x) while ramping, ramp / 2 + (t - tau_k - ramp) after),
    Delta L = sum_k (v_k - v_(k-1)) [ramp I(x_k) + max(t - tau_k - ramp, 0)].
    After the run (t >= tau_n + ramp) Delta L = sum_k v_k d_k: each ramp is an instantaneous change of speed
    delayed by ramp / 2 (S(x) + S(1 - x) = 1), so every leg pays out exactly its v_k d_k.
    ``fmin``/``fmax`` are the elementwise min/max of the number type (``min``/``max`` for floats, CasADi's
    ``fmin``/``fmax`` for a symbolic t or symbolic legs), so the model and the scene's check evaluate this one
    formula."""
    clip, S, I, dS = _smoothstep(fmin, fmax)
    dL = w = alpha = 0.0
    tau, prev = start, 0.0
    for v, d in list(zip(speeds, durations)) + [(0.0, None)]:
        dv, x = v - prev, clip((t - tau) / ramp)
        dL = dL + dv * (ramp * I(x) + fmax(t - tau - ramp, 0.0))
        w = w + dv * S(x)
        alpha = alpha + dv * dS(x) / ramp
        if d is not None:
            tau, prev = tau + d, v
    return dL, w, alpha


def payout_profile(t, speed, start, duration, ramp, fmin=min, fmax=max):
    """The single-speed payout profile at time t: (Delta L (m), w (m/s), alpha (m/s^2)), :func:`legs_profile` of one
    leg at ``speed`` for ``duration - ramp`` seconds from ``start``.

    w rises from 0 to ``speed`` over ``ramp`` seconds from ``start``, holds, and falls back to 0 over the last
    ``ramp`` seconds of ``duration`` (smoothstep ramps); at the end Delta L = speed (duration - ramp)."""
    return legs_profile(t, (speed,), (duration - ramp,), start, ramp, fmin=fmin, fmax=fmax)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Leg:
    """One leg of a winch's payout profile (``[[winch.leg]]``): a speed held for a duration, the ramp into it from
    the previous leg's speed included (:func:`legs_profile`); the leg pays out speed x duration."""

    speed: float = spec("velocity", "payout speed of the leg (m/s, + pays out, - hauls in, 0 holds)")
    duration: float = spec("time", "duration of the leg (s, >= winch.ramp: the ramp into its speed starts the leg)")

    def __post_init__(self):
        check_all_finite(self, "leg")
        require_positive("leg.duration", self.duration, "s")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Winch:
    """A winch at the top of the first section: its unstretched length L(t) changes in time (segmented cable only).

    The first section's cable (its ``cable.length`` at ``cable.tension_ref``, zero-tension length l_0, Wang 1971
    eq. 1) is what is in the water at t = 0; L(t) = l_0 + Delta L(t). The profile is either one constant
    ``speed`` (> 0 pays out, < 0 hauls in) for ``duration`` seconds from ``start``, ramps included
    (:func:`payout_profile`: at the end l_0 + speed (duration - ramp)), or a sequence of legs ``leg`` (payout,
    hold, haul-in, ...) from ``start``, each ramped into from the previous speed and the last ramped to rest
    after it (:func:`legs_profile`: at the end l_0 + sum speed x duration). L must stay in (0, max_length] over
    the run (:meth:`check_length`, called by the scene).
    """

    speed: float | None = spec("velocity", "payout speed at full speed (m/s, + pays out, - hauls in); unset with "
                                           "[[winch.leg]]", None)
    start: float = spec("time", "time the winch starts (s, >= 0: the run starts at rest with L = l_0)", 0.0)
    duration: float | None = spec("time", "time from start to stop, ramps included (s, > 0); unset with "
                                          "[[winch.leg]]", None)
    ramp: float = spec("time", "duration of each smooth speed ramp (s, > 0; 2 ramp <= duration, ramp <= each "
                               "leg's duration)", 1.0)
    max_length: float = spec("length", "the most zero-tension cable the drum holds / the line may pay out to (m)")
    leg: tuple[Leg, ...] = spec("none", "the profile's legs in time order (payout, hold, haul-in): each a speed "
                                        "and a duration; unset for the single-speed form", ())

    def __post_init__(self):
        check_all_finite(self, "winch")
        require_nonnegative("winch.start", self.start, "s")
        require_positive("winch.ramp", self.ramp, "s")
        require_positive("winch.max_length", self.max_length, "m")
        if self.leg:
            for name in ("speed", "duration"):
                if getattr(self, name) is not None:
                    raise ParameterError(f"winch.{name}", getattr(self, name), "must be unset with [[winch.leg]]: "
                                         "the legs give the speeds and durations")
            for k, g in enumerate(self.leg):
                if not isinstance(g, Leg):
                    raise ParameterError(f"winch.leg[{k}]", g, "must be a Leg (speed, duration)")
                if g.duration < self.ramp:
                    raise ParameterError(f"winch.leg[{k}].duration", g.duration, f"must be >= winch.ramp = "
                                         f"{self.ramp:g} s: the ramp into the leg's speed lies within the leg")
            return
        for name in ("speed", "duration"):
            if getattr(self, name) is None:
                raise ParameterError(f"winch.{name}", "missing", "is required (or give the profile as "
                                     "[[winch.leg]] tables of speed and duration)")
        require_positive("winch.duration", self.duration, "s")
        if 2.0 * self.ramp > self.duration:
            raise ParameterError("winch.ramp", self.ramp, f"must be <= duration / 2 = {self.duration / 2:g} s: the "
                                 "speed ramps up and down within the duration")

    @property
    def legs(self) -> tuple:
        """The profile as legs ((v_k (m/s), d_k (s)), ...): the single-speed form is one leg of duration - ramp."""
        if self.leg:
            return tuple((g.speed, g.duration) for g in self.leg)
        return ((self.speed, self.duration - self.ramp),)

    def _field(self, k: int) -> str:
        """The field that sets leg k's speed."""
        return f"winch.leg[{k}].speed" if self.leg else "winch.speed"

    def parameter_items(self) -> list:
        """(label, SI value) of the profile's numbers in the model's parameter vector (:mod:`cablesys.model.params`)."""
        if not self.leg:
            return [(f"winch.{a}", float(getattr(self, a))) for a in ("speed", "start", "duration", "ramp")]
        return [("winch.start", float(self.start)), ("winch.ramp", float(self.ramp))] + [
            (f"winch.leg[{k}].{a}", float(getattr(g, a))) for k, g in enumerate(self.leg) for a in ("speed", "duration")]

    def structure(self) -> tuple:
        """What fixes the shape of the model's profile: the number of legs (the single-speed form keeps ("winch",))."""
        return ("winch",) if not self.leg else ("winch", len(self.leg))

    def profile_at(self, t, value=None, fmin=min, fmax=max) -> tuple:
        """(Delta L, w, alpha) at t with each number read as ``value(label)`` (labels of :meth:`parameter_items`;
        the model passes its parameter symbols) or, by default, the winch's own values."""
        own = dict(self.parameter_items())
        get = value or own.__getitem__
        if not self.leg:
            return payout_profile(t, get("winch.speed"), get("winch.start"), get("winch.duration"), get("winch.ramp"),
                                  fmin=fmin, fmax=fmax)
        n = len(self.leg)
        return legs_profile(t, [get(f"winch.leg[{k}].speed") for k in range(n)],
                            [get(f"winch.leg[{k}].duration") for k in range(n)], get("winch.start"), get("winch.ramp"),
                            fmin=fmin, fmax=fmax)

    def profile(self, t: float) -> tuple:
        """(Delta L (m), w (m/s), alpha (m/s^2)) at time t (:func:`legs_profile`)."""
        return self.profile_at(t)

    @property
    def paid_out(self) -> float:
        """Length paid out over the whole profile, sum of speed x duration over the legs (m; < 0 hauled in)."""
        return sum(v * d for v, d in self.legs)

    @property
    def end(self) -> float:
        """Time the winch comes to rest: start + the legs' durations + the last ramp (s)."""
        return self.start + sum(d for _, d in self.legs) + self.ramp

    def turning_points(self) -> list:
        """The times (s, increasing) between which Delta L is monotone, with Delta L (m) there: t = 0, the start
        and end of each ramp, and inside a ramp between speeds of opposite signs the time where w = 0. In
        ramp k, w = v_(k-1) + (v_k - v_(k-1)) S(x) = 0 at S(x) = s = v_(k-1) / (v_(k-1) - v_k), inverted in
        closed form: x = 1/2 - sin(asin(1 - 2 s) / 3) (4 u^3 - 3 u = -sin 3 theta with x = 1/2 - u, u = sin theta)."""
        times, tau, prev = [0.0], self.start, 0.0
        for v, d in list(self.legs) + [(0.0, None)]:
            times += [tau, tau + self.ramp]
            if prev * v < 0.0:
                s = prev / (prev - v)
                times.append(tau + self.ramp * (0.5 - math.sin(math.asin(1.0 - 2.0 * s) / 3.0)))
            if d is not None:
                tau, prev = tau + d, v
        return [(t, self.profile(t)[0]) for t in sorted(set(times))]

    def leg_at(self, t: float, sign: float) -> int:
        """The last leg begun by time t whose speed has the sign of ``sign`` (the leg that drove L there; 0 if none)."""
        tau, found = self.start, 0
        for k, (v, d) in enumerate(self.legs):
            if tau <= t + 1e-12 and v * sign > 0.0:
                found = k
            tau += d
        return found

    def check_length(self, l0: float, source: str) -> None:
        """L(t) = l_0 + Delta L(t) must stay in (0, max_length] over the run, l_0 (m) the zero-tension length in the
        water at t = 0 (``source``, the field it comes from, for the message; Wang 1971 eq. 1). Delta L is
        monotone between :meth:`turning_points`, so L is checked there; the error names the speed field of the
        leg that drove L out of range, the time and the length reached."""
        if l0 > self.max_length:
            raise ParameterError("winch.max_length", self.max_length, f"must be >= the {l0:.6g} m of zero-tension "
                                 f"cable in the water at the start ({source} at its tension_ref)")
        points = self.turning_points()
        for (t_a, dL_a), (t, dL) in zip(points, points[1:]):
            L = l0 + dL
            if 0.0 < L <= self.max_length:
                continue
            from scipy.optimize import brentq      # only to word the error (the scene module needs no SciPy)
            bound = 0.0 if L <= 0.0 else self.max_length      # L monotone on [t_a, t]: where it crosses the bound
            t_x = brentq(lambda s: l0 + self.profile(s)[0] - bound, t_a, t) if l0 + dL_a != bound else t_a
            k = self.leg_at(t_x, -1.0 if L <= 0.0 else 1.0)
            v = self.legs[k][0]
            what = "hauls in" if v < 0 else "pays out"
            leg = f" in leg {k}" if self.leg else ""
            t_w, dL_w = (min if L <= 0.0 else max)(points, key=lambda p: p[1])      # the extreme over the run
            raise ParameterError(self._field(k), v, f"{what} the first section's zero-tension length from {l0:.6g} m "
                                 f"to {bound:.6g} m at t = {t_x:.6g} s{leg} (and to {l0 + dL_w:.6g} m at t = "
                                 f"{t_w:.6g} s): it must stay in (0, max_length = {self.max_length:.6g} m]")
