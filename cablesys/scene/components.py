"""Immutable, validated scene components (SI units inside).

Every field documents its unit and meaning (Wang 1971 notation in brackets).
Validation runs in ``__post_init__`` and raises :class:`~cablesys.errors.ParameterError`
naming the field, its value and the allowed range, before any model is built.
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import (ParameterError, require_finite, require_nonnegative,
                      require_positive, require_range)
from ..integration import METHODS as INTEGRATION_METHODS
from .fields import quantity, spec
from .harmonics import MAX_AMPLITUDE_M, MAX_FREQUENCY_RAD_S, Sinusoid, Wave
from .sea import MotionRAO, SeaSpectrum, append_once, sea_sinusoids
from .track import Track
from .vessel import VesselRAO


def _check_all_finite(obj, prefix: str) -> None:
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            if f.name == "tension_floor" and v == -math.inf:
                continue  # -inf: the cable never goes slack (a rod)
            require_finite(f"{prefix}.{f.name}", v)
            if abs(v) > MAX_MAGNITUDE:
                raise ParameterError(f"{prefix}.{f.name}", v, f"must be within +-{MAX_MAGNITUDE:g} (SI units); larger "
                                     "values overflow the squares and products of the equations of motion")


# no cable or body number in SI comes near this (AE of the largest steel ropes ~1e10 N); a cable
# 1e300 m long passed the range checks and overflowed the steady-state solve (found by fuzzing)
MAX_MAGNITUDE = 1e15
MAX_SEGMENTS = 2000       # elements per section (the model's size grows linearly with it)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Cable:
    """One cable section, described at its reference tension (Wang 1971 eq. 1-7)."""

    length: float = quantity("length", "reference length l_r at the reference tension")
    tension_ref: float = spec("force", "reference tension T_r at which length/ae/diameter are given", 0.0)
    ae: float = quantity("ae", "reference spring coefficient (AE)_r; spring constant k = (AE)_r / l_r")
    diameter: float = quantity("diameter", "cable thickness d_r at the reference tension")
    mass_per_length: float = quantity("mass_per_length", "cable mass per unit length m_r at the reference tension")
    weight_per_length: float = quantity("weight_per_length", "cable weight in water per unit length (W_c = w l_r)")
    thinning_ratio: float = spec("none", "ratio p of lateral contraction to strain, d = d_0 (1 - p u / l_r) (eq. 3)", 0.0)
    added_mass_factor: float = quantity("added_mass_factor", "added-mass factor gamma of the cable (1 for a round cable, eq. 23)", 1.0)
    cd_normal: float = quantity("cd_normal", "normal drag coefficient C_D of the cable (eq. 42)", 1.5)
    ct_tangential: float = quantity("ct_tangential", "tangential friction coefficient C_t of the cable (eq. 44)", 0.01)
    internal_damping: float = spec("force_time", "Voigt internal damping constant C_I, force = (C_I/l_r) du/dt (eq. 46)", 0.0)
    tension_floor: float = spec("force", "least tension TENS the cable supports; 0 for a flexible cable, -inf for a rod (eq. 54)", 0.0)
    cable_mass_switch: float = spec("none", "the report's CBMAS: any negative value drops the cable mass and added-mass terms", 1.0)
    segments: int = spec("none", "number N of straight elements the section is divided into (node positions, "
                         "tension-only elements); 1 is Wang's 2-DOF straight cable", 1)

    def __post_init__(self):
        _check_all_finite(self, "cable")
        require_positive("cable.length", self.length, "m")
        require_positive("cable.ae", self.ae, "N")
        require_positive("cable.diameter", self.diameter, "m")
        require_nonnegative("cable.mass_per_length", self.mass_per_length, "kg/m")
        require_range("cable.thinning_ratio", self.thinning_ratio, 0.0, 1.0)
        for name in ("added_mass_factor", "cd_normal", "ct_tangential", "internal_damping"):
            require_nonnegative(f"cable.{name}", getattr(self, name))
        if self.tension_ref >= self.ae:
            raise ParameterError("cable.tension_ref", self.tension_ref,
                                 f"must be < cable.ae = {self.ae} so that the zero-tension length l_0 = l_r - T_r/k is positive (eq. 1)")
        if self.thinning_ratio * self.tension_ref / self.ae >= 1.0:
            raise ParameterError("cable.thinning_ratio", self.thinning_ratio, "must keep d_0 > 0 (eq. 4)")
        if self.tension_floor != -math.inf:
            require_finite("cable.tension_floor", self.tension_floor)
        if (not isinstance(self.segments, int) or isinstance(self.segments, bool)
                or not 1 <= self.segments <= MAX_SEGMENTS):
            raise ParameterError("cable.segments", self.segments, f"must be an integer in [1, {MAX_SEGMENTS}]")

    # zero-tension quantities, Wang (1971) eq. 1-7 (numeric twins of the symbolic ones in model/section.py)
    @property
    def spring_constant(self) -> float:
        """k = (AE)_r / l_r (Wang 1971, below eq. 1)."""
        return self.ae / self.length

    @property
    def length_zero(self) -> float:
        """l_0 = l_r - T_r / k (Wang 1971 eq. 1)."""
        return self.length - self.tension_ref / self.spring_constant

    @property
    def total_mass(self) -> float:
        """M_c = m_r l_r (Wang 1971 eq. 5); zero when CBMAS < 0."""
        return self.mass_per_length * self.length if self.cable_mass_switch >= 0 else 0.0

    @property
    def total_weight(self) -> float:
        """W_c, the cable weight in water (Wang 1971 eq. 12)."""
        return self.weight_per_length * self.length


#: The rigid body's fields of :class:`Body` (all at their defaults: Wang's point body).
RIGID_FIELDS = ("pitch_inertia", "pitch_added_inertia", "attachment_x", "attachment_y", "buoyancy", "buoyancy_x",
                "buoyancy_y", "pitch_damping", "pitch_drag", "drag_centre_x", "drag_centre_y")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Body:
    """The body at the lower end of a cable section: a point (Wang 1971 eq. 16, 32-35) or, with ``pitch_inertia``
    set, a rigid body that pitches in the x-y plane on an attachment point off its centre of gravity
    (Wang 1971 p. 32, "Extensions"; equations in :mod:`cablesys.model.rigid_body`). A rigid body's virtual masses
    ``mass_x``, ``mass_y`` and its drag axis ``axis_angle_deg`` are along its body axes, which are the scene's x and y
    at zero pitch; its drag acts at its centre of pressure (``drag_centre_x/y``; unset: the centre of gravity)."""

    weight: float = spec("force", "weight in water W_b (negative: buoyant)")
    mass_x: float = spec("mass", "virtual mass (mass plus added mass) for motion in x, M_bvx")
    mass_y: float = spec("mass", "virtual mass (mass plus added mass) for motion in y, M_bvy")
    drag_area_normal: float = spec("area", "CDABN: (C_D A_b)_n, or C_D A_b of a sphere (eq. 32-33)", 0.0)
    drag_area_tangential: float = spec("area", "CDABT: (C_D A_b)_t; equal to CDABN for a sphere (eq. 33b)", 0.0)
    axis_angle_deg: float = spec("angle_deg", "PHIBD: angle phi_b of the body's tangential axis with the vertical in degrees; |PHIBD| > 180 selects sphere drag (eq. 32)", 999.0)
    mass_z: float | None = spec("mass", "virtual mass for motion in z (out of the x-y plane), M_bvz; used by the 3-D "
                                "equations only; unset: mass_x (a body symmetric about the vertical)", None)
    # a rigid body that pitches in the x-y plane (Wang 1971 p. 32, "Extensions": "where the body is fairly large
    # and the cable is not attached to the center of mass"); body axes coincide with the scene's x, y (y down)
    # at theta_b = 0, theta_b turning +x towards +y (about +z); unset pitch_inertia: Wang's point body
    pitch_inertia: float | None = spec("inertia", "moment of inertia I of the body's mass about its centre of gravity for "
                                       "rotation in the x-y plane (pitch); set: the body is rigid and pitches (one more "
                                       "coordinate theta_b, segmented cable only); unset: a point body", None)
    pitch_added_inertia: float | None = spec("inertia", "added moment of inertia I_a of the fluid for pitch "
                                             "(rigid body; unset: 0)", None)
    attachment_x: float | None = spec("length", "x of the cable's attachment point from the centre of gravity, body "
                                      "axes (rigid body; unset: 0)", None)
    attachment_y: float | None = spec("length", "y (down) of the cable's attachment point from the centre of gravity, body "
                                      "axes; negative: above the CG (rigid body; unset: 0)", None)
    buoyancy: float | None = spec("force", "buoyant force B acting up at the centre of buoyancy (rigid body; unset: 0); the "
                                  "weight W_b + B acts down at the CG, so the weight in water stays W_b", None)
    buoyancy_x: float | None = spec("length", "x of the centre of buoyancy from the centre of gravity, body axes "
                                    "(rigid body; unset: 0)", None)
    buoyancy_y: float | None = spec("length", "y (down) of the centre of buoyancy from the centre of gravity, body axes "
                                    "(rigid body; unset: 0)", None)
    pitch_damping: float | None = spec("moment_time", "linear pitch damping c: moment -c theta_b' (rigid body; unset: 0)",
                                       None)
    pitch_drag: float | None = spec("moment_time2", "quadratic pitch drag d: moment -d |theta_b'| theta_b' (rigid body; "
                                    "unset: 0)", None)
    drag_centre_x: float | None = spec("length", "x of the point where the body's drag acts (centre of pressure) from the "
                                       "centre of gravity, body axes (rigid body; unset: 0, at the CG)", None)
    drag_centre_y: float | None = spec("length", "y (down) of the body's centre of pressure from the centre of gravity, "
                                       "body axes (rigid body; unset: 0)", None)

    def __post_init__(self):
        _check_all_finite(self, "body")
        require_positive("body.mass_x", self.mass_x, "kg")
        require_positive("body.mass_y", self.mass_y, "kg")
        if self.mass_z is not None:
            require_positive("body.mass_z", self.mass_z, "kg")
        self._check_rigid()
        require_nonnegative("body.drag_area_normal", self.drag_area_normal, "m^2")
        require_nonnegative("body.drag_area_tangential", self.drag_area_tangential, "m^2")
        if self.is_sphere and not math.isclose(self.drag_area_normal, self.drag_area_tangential, rel_tol=1e-12, abs_tol=0.0):
            raise ParameterError("body.drag_area_tangential", self.drag_area_tangential,
                                 f"must equal body.drag_area_normal = {self.drag_area_normal} for sphere drag "
                                 "(|axis_angle_deg| > 180, the report's PHIBD rule)")

    def _check_rigid(self) -> None:
        """A rigid body's fields: non-negative inertias, damping and buoyancy; on a point body every rigid field
        must be unset or 0 (an offset or inertia given without ``pitch_inertia`` would be dropped)."""
        if self.pitch_inertia is None:
            for name in RIGID_FIELDS[1:]:
                if getattr(self, name) not in (None, 0.0):
                    raise ParameterError(f"body.{name}", getattr(self, name), "needs body.pitch_inertia (a rigid body); "
                                         "a point body has no attachment offset, buoyancy centre or pitch")
            return
        for name in ("pitch_inertia", "pitch_added_inertia", "buoyancy", "pitch_damping", "pitch_drag"):
            require_nonnegative(f"body.{name}", self.rigid(name))
        if not self.pitch_inertia + self.rigid("pitch_added_inertia") > 0.0:
            raise ParameterError("body.pitch_inertia", self.pitch_inertia, "must make pitch_inertia + pitch_added_inertia "
                                 "> 0 kg m^2 (a rigid body without rotary inertia has no pitch equation)")

    def rigid(self, name: str) -> float:
        """The rigid-body field ``name`` (one of :data:`RIGID_FIELDS`) in SI, 0 when unset."""
        v = getattr(self, name)
        return 0.0 if v is None else float(v)

    @property
    def is_rigid(self) -> bool:
        """A body that pitches (``pitch_inertia`` set): one more coordinate theta_b in the segmented cable."""
        return self.pitch_inertia is not None

    @property
    def virtual_mass_z(self) -> float:
        """M_bvz (kg): ``mass_z``, or ``mass_x`` when unset."""
        return self.mass_x if self.mass_z is None else self.mass_z

    @property
    def is_sphere(self) -> bool:
        """The report's PHIBD rule: |PHIBD| > 180 means sphere drag, eq. 32."""
        return abs(self.axis_angle_deg) > 180.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class Section:
    """A cable section and the body at its lower end."""

    cable: Cable
    body: Body


@dataclasses.dataclass(frozen=True, kw_only=True)
class Environment:
    """Fluid, gravity, current profile (the report's CUR) and waves."""

    density: float = quantity("density", "fluid density rho", 1025.0)
    gravity: float = quantity("gravity", "gravity g", 9.80665)
    current_depths: tuple = spec("length", "depths y (down) of the current-profile points, strictly increasing", (0.0,))
    current_speeds: tuple = spec("velocity", "actual current speed in +x at each depth; linearly interpolated, constant beyond the ends", (0.0,))
    system_speed: float = spec("velocity", "steady speed of the cable system in +x (ship speed); subtracted from the current: c(y) = current(y) - speed (eq. 27)", 0.0)
    top_depth: float = spec("length", "mean depth of the top of the cable below the still surface", 0.0)
    waves: tuple[Wave, ...] = spec("none", "deep-water wave components", ())
    current_headings_deg: tuple = spec("angle_deg", "direction of the current in the horizontal plane at each current "
                                       "depth, degrees from +x towards +z (seen from above, counter-clockwise); one value: "
                                       "every depth; the x and z components are interpolated in depth like the speeds; "
                                       "empty: along +x, a planar scene", ())

    def __post_init__(self):
        require_positive("environment.density", self.density, "kg/m^3")
        require_positive("environment.gravity", self.gravity, "m/s^2")
        require_finite("environment.system_speed", self.system_speed)
        require_finite("environment.top_depth", self.top_depth)
        d, s = tuple(self.current_depths), tuple(self.current_speeds)
        if len(d) == 0 or len(d) != len(s):
            raise ParameterError("environment.current_speeds", s,
                                 f"must have one speed per depth ({len(d)} depths given, at least one)")
        for i, (di, si) in enumerate(zip(d, s)):
            require_finite(f"environment.current_depths[{i}]", di)
            require_finite(f"environment.current_speeds[{i}]", si)
        for i in range(1, len(d)):
            if not d[i] > d[i - 1]:
                raise ParameterError("environment.current_depths", d,
                                     f"must be strictly increasing (entry {i} = {d[i]} <= {d[i - 1]})")
        object.__setattr__(self, "current_depths", tuple(float(v) for v in d))
        object.__setattr__(self, "current_speeds", tuple(float(v) for v in s))
        object.__setattr__(self, "waves", tuple(self.waves))
        h = tuple(self.current_headings_deg)
        if len(h) not in (0, 1, len(d)):
            raise ParameterError("environment.current_headings_deg", h,
                                 f"must be empty (along +x), one heading or one per current depth ({len(d)})")
        for i, hi in enumerate(h):
            require_finite(f"environment.current_headings_deg[{i}]", hi)
        object.__setattr__(self, "current_headings_deg", tuple(float(v) for v in h))

    @property
    def headings_per_depth_deg(self) -> tuple:
        """The current's heading (deg) at every current depth: 0 when unset, one value repeated."""
        h = self.current_headings_deg
        return (h[0],) * len(self.current_depths) if len(h) == 1 else (h or (0.0,) * len(self.current_depths))

    @property
    def is_planar(self) -> bool:
        """No current heading and no wave heading set: the flow lies in the x-y plane."""
        return not self.current_headings_deg and all(w.heading_deg is None for w in self.waves)


@dataclasses.dataclass(frozen=True, kw_only=True)
class TimeSeries:
    """Sampled, non-periodic top motion; interpolated by a cubic spline through the samples."""

    times: tuple = spec("time", "sample times, strictly increasing, at least 4")
    x: tuple = spec("length", "x_s at the sample times")
    y: tuple = spec("length", "y_s at the sample times")

    def __post_init__(self):
        t = tuple(float(v) for v in self.times)
        if len(t) < 4:
            raise ParameterError("top_motion.series.times", self.times, "needs at least 4 samples")
        for name in ("x", "y"):
            v = getattr(self, name)
            if len(v) != len(t):
                raise ParameterError(f"top_motion.series.{name}", f"{len(v)} values",
                                     f"must have one value per sample time ({len(t)})")
            for i, vi in enumerate(v):
                require_range(f"top_motion.series.{name}[{i}]", vi, -MAX_AMPLITUDE_M, MAX_AMPLITUDE_M, "m")
            object.__setattr__(self, name, tuple(float(a) for a in v))
        for i in range(1, len(t)):
            if not t[i] > t[i - 1]:
                raise ParameterError("top_motion.series.times", f"entry {i} = {t[i]}", "must be strictly increasing")
        object.__setattr__(self, "times", t)


#: Largest significant wave height of a sea (m): about five times the largest recorded (~ 19 m).
MAX_SEA_HS_M = 100.0
#: Range of a sea's peak period (s): from ripples to beyond the longest swell.
SEA_TP_RANGE_S = (0.1, 1000.0)

RAMP_PERIODS = 3   # default smooth start: this many of the longest forcing periods


@dataclasses.dataclass(frozen=True, kw_only=True)
class TopMotion:
    """Prescribed motion of the top of the cable (ship motion): sinusoids and/or a time series."""

    x: tuple[Sinusoid, ...] = spec("none", "sinusoids in x (horizontal, + to the right)", ())
    y: tuple[Sinusoid, ...] = spec("none", "sinusoids in y (vertical, + downwards)", ())
    z: tuple[Sinusoid, ...] = spec("none", "sinusoids in z (sway: horizontal, out of the x-y plane; (x, y, z) is "
                                   "right-handed with y down, so seen from above z is 90 degrees counter-clockwise "
                                   "from x); any term makes the scene 3-D", ())
    series: TimeSeries | None = spec("none", "sampled motion added to the sinusoids", None)
    spectrum: SeaSpectrum | None = spec("none", "an irregular sea (scene/sea.py SeaSpectrum), realised as sinusoids appended to x and y", None)
    rao: MotionRAO | None = spec("none", "vessel / crane-tip motion RAO turning the sea into top motion (scene/sea.py MotionRAO); "
                               "none: the top heaves with the surface", None)
    vessel: VesselRAO | None = spec("none", "a vessel's 6-DOF motion RAO and the lever arm of the cable's point on it (scene/vessel.py "
                                    "VesselRAO): the sea moves the top in x, y and z (sway makes the scene 3-D); instead of rao",
                                    None)
    track: Track | None = spec("none", "the tow point's path in the horizontal plane (scene/track.py Track: towing in a "
                               "circle), realised as sinusoids in x and z; the run starts on the steady turn", None)
    ramp_s: float | None = spec("time", "smooth start: every top-motion amplitude rises from 0 to full over 0 <= t <= "
                                        "ramp_s with a cosine-rate ramp u - sin(2 pi u)/(2 pi), u = t/ramp_s (no jump in top "
                                        "velocity or acceleration); unset: 3 periods of the longest forcing period (a sea: "
                                        "3 T_p; a series alone: 0); 0: abrupt start, as in Wang (1971)", None)

    def __post_init__(self):
        object.__setattr__(self, "x", tuple(self.x))
        object.__setattr__(self, "y", tuple(self.y))
        object.__setattr__(self, "z", tuple(self.z))
        if self.ramp_s is not None:
            require_finite("top_motion.ramp_s", self.ramp_s)
            require_nonnegative("top_motion.ramp_s", self.ramp_s, "s")
        if self.spectrum is not None:          # the sea as sinusoids: the compiled SX path (scene/sea.py)
            # its realised terms are Sinusoids (bounded); name the sea's own fields first
            require_range("top_motion.spectrum.hs", self.spectrum.hs, 0.0, MAX_SEA_HS_M, "m", lo_open=True)
            require_range("top_motion.spectrum.tp", self.spectrum.tp, *SEA_TP_RANGE_S, "s")
            require_range("top_motion.spectrum.omega_max", self.spectrum.omega_max, 0.0, MAX_FREQUENCY_RAD_S, "rad/s")
            if self.rao is not None and self.vessel is not None:
                raise ParameterError("top_motion.vessel", "given with top_motion.rao",
                                     "give one motion RAO: [top_motion.rao] (surge and heave) or [top_motion.vessel] (6-DOF)")
            realised = dict(zip("xyz", sea_sinusoids(self.spectrum, self.vessel or self.rao)))
            counts = {}
            for axis, terms in realised.items():
                n = len(getattr(self, axis))
                object.__setattr__(self, axis, append_once(getattr(self, axis), terms))
                counts[axis] = len(getattr(self, axis)) - len(terms) if len(getattr(self, axis)) == n else n
            object.__setattr__(self, "_user_count", counts)
        elif self.rao is not None or self.vessel is not None:
            name = "top_motion.rao" if self.rao is not None else "top_motion.vessel"
            raise ParameterError(name, "given", "needs a [top_motion.spectrum] sea to act on")
        if self.track is not None:             # the circle as sinusoids; alone: the run starts on its steady turn
            others = [n for n in ("spectrum", "series") if getattr(self, n) is not None]
            sx, sz = self.track.sinusoids()
            x, z = append_once(self.x, sx), append_once(self.z, sz)
            others += [f"{a}[0]" for a, mine, got in (("x", sx, x), ("z", sz, z)) if len(got) != len(mine)]
            others += ["y[0]"] if self.y else []
            if others:
                raise ParameterError(f"top_motion.{others[0]}", "given with top_motion.track",
                                     "must be unset: the run starts on the steady turn, which other top motion "
                                     "would not leave steady")
            if self.ramp_s not in (None, 0.0):
                raise ParameterError("top_motion.ramp_s", self.ramp_s, "must be 0 or unset with top_motion.track: "
                                     "the run starts on the steady turn, not from rest")
            object.__setattr__(self, "x", x)
            object.__setattr__(self, "z", z)
            object.__setattr__(self, "_user_count", {"x": 0, "y": 0, "z": 0})

    @property
    def effective_ramp_s(self) -> float:
        """The smooth start's duration (s): ``ramp_s``, or when unset RAMP_PERIODS periods of the longest
        forcing period (of the user's sinusoids and a sea's T_p, not of the sea's realised components,
        whose low-frequency tail has arbitrarily long periods); 0 without sinusoids (a recorded series
        plays as recorded) and with a track (the run starts on the steady turn)."""
        if self.ramp_s is not None:
            return float(self.ramp_s)
        if self.track is not None:       # the run starts on the steady turn
            return 0.0
        n = getattr(self, "_user_count", {"x": len(self.x), "y": len(self.y)})
        n = {"z": len(self.z), **n}
        periods = [2.0 * math.pi / s.frequency for axis in ("x", "y", "z") for s in getattr(self, axis)[: n[axis]]]
        if self.spectrum is not None:
            periods.append(self.spectrum.tp)
        return RAMP_PERIODS * max(periods) if periods else 0.0

    @property
    def forcing_period_s(self) -> float | None:
        """The longest period (s) of the top-motion sinusoids with a non-zero amplitude, a realised sea's
        components included; None without sinusoids."""
        freqs = [s.frequency for axis in (self.x, self.y, self.z) for s in axis if s.amplitude != 0.0]
        return 2.0 * math.pi / min(freqs) if freqs else None

    @property
    def window_period_s(self) -> float | None:
        """The period that sets the statistics window (:func:`cablesys.statistics.window`): the forcing period
        of a motion of sinusoids; None for an irregular sea or a recorded series, whose statistics (std, MPM,
        significant amplitude) need the longest settled record, the run's second half, not 5 periods of its
        longest component."""
        return None if (self.spectrum is not None or self.series is not None) else self.forcing_period_s


@dataclasses.dataclass(frozen=True, kw_only=True)
class Initial:
    """Initial state; ``None`` entries start from the steady state of the scene."""

    phi: float | None = spec("angle", "initial angle phi of every section (rad)", None)
    u: float | None = spec("length", "initial stretch u of every section (m)", None)
    phi_rate: float = spec("frequency", "initial d phi/dt", 0.0)
    u_rate: float = spec("velocity", "initial du/dt", 0.0)

    def __post_init__(self):
        # the section lengths l_0 + u > 0 are checked by the Scene, which knows l_0
        if self.phi is not None:
            require_range("initial.phi", self.phi, -math.pi, math.pi, "rad")
        if self.u is not None:
            require_finite("initial.u", self.u)
        require_finite("initial.phi_rate", self.phi_rate)
        require_finite("initial.u_rate", self.u_rate)


# the model ladder's rungs, cheapest first (cablesys.ladder.rungs builds them), and what numerics.model may name:
# "auto" (the ladder's choice) or "as-built" (the scene's own model: its sections' segments, no choice)
RUNGS = ("frequency", "quasi-static", "wang", "segmented")
MODEL_CHOICES = ("auto", "as-built") + RUNGS
INTEGRATORS = tuple(INTEGRATION_METHODS)      # the names of the one registry (cablesys.integration)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Numerics:
    """How to integrate."""

    drag_segments: int = spec("none", "number N of cable segments for drag (eq. 30-45)", 10)
    integrator: str = spec("none", f"one of {INTEGRATORS}", "cvodes")
    rtol: float = spec("none", "relative tolerance (the report used 1e-3)", 1e-7)
    atol: float = spec("none", "absolute tolerance, a fraction of each state's natural scale (cablesys.model.scales)", 1e-9)
    duration: float = spec("time", "simulated time", 60.0)
    output_step: float = spec("time", "spacing of output times", 0.05)
    steps_per_output: int = spec("none", "fixed-step methods (rk, collocation): steps per output interval", 10)
    model: str = spec("none", "model ladder rung: auto (the cheapest within model_tolerance) | as-built (the scene's own "
                              "model: segments per [cable]) | frequency | quasi-static | wang | segmented (cablesys.ladder)",
                      "auto")
    model_tolerance: float = spec("none", "relative error allowed on body motion for model = auto; tension extremes "
                                          "get twice it", 0.01)
    time_budget_s: float = spec("time", "wall time model = auto may plan for a slack scene's extrapolation runs (their "
                                        "predicted cost, steps x per-step cost); 0: no budget", 0.0)
    dimensions: int | None = spec("none", "3: Wang's cable in three dimensions (stretch and two swing angles) even for a "
                                  "planar scene; 2: the planar equations (refused when the scene sets a 3-D field); "
                                  "unset: 3 when the scene sets a 3-D field (top_motion.z, a current or wave heading, "
                                  "body.mass_z), else 2", None)

    def __post_init__(self):
        if not isinstance(self.drag_segments, int) or isinstance(self.drag_segments, bool) or not 1 <= self.drag_segments <= 1000:
            raise ParameterError("numerics.drag_segments", self.drag_segments, "must be an integer in [1, 1000]")
        if self.integrator not in INTEGRATORS or self.integrator == "rkc":
            raise ParameterError("numerics.integrator", self.integrator,
                                 f"must be one of {tuple(m for m in INTEGRATORS if m != 'rkc')} (rkc needs a stage count "
                                 "chosen from the model's spectrum: the ladder's slack runs choose it)")
        require_range("numerics.rtol", self.rtol, 1e-14, 1e-1)
        require_range("numerics.atol", self.atol, 1e-16, 1.0)
        require_positive("numerics.duration", self.duration, "s")
        require_positive("numerics.output_step", self.output_step, "s")
        if self.output_step > self.duration:
            raise ParameterError("numerics.output_step", self.output_step, f"must be <= numerics.duration = {self.duration}")
        if not isinstance(self.steps_per_output, int) or not 1 <= self.steps_per_output <= 100000:
            raise ParameterError("numerics.steps_per_output", self.steps_per_output, "must be an integer in [1, 100000]")
        if self.model not in MODEL_CHOICES:
            raise ParameterError("numerics.model", self.model, f"must be one of {MODEL_CHOICES}")
        require_range("numerics.model_tolerance", self.model_tolerance, 1e-6, 0.5)
        if isinstance(self.time_budget_s, bool) or not (isinstance(self.time_budget_s, (int, float)) and 0.0 <= self.time_budget_s < float("inf")):
            raise ParameterError("numerics.time_budget_s", self.time_budget_s, "must be a finite number of seconds >= 0 "
                                                                                 "(0: no budget)")
        if self.dimensions is not None and (isinstance(self.dimensions, bool) or self.dimensions not in (2, 3)):
            raise ParameterError("numerics.dimensions", self.dimensions, "must be 2 or 3 (or unset)")


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
        _check_all_finite(self, "anchor")


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
        _check_all_finite(self, "seabed")
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
        _check_all_finite(self, "winch")
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
