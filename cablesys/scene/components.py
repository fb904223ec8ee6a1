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
from .body import RIGID_FIELDS, Body  # noqa: F401  (re-exported: the scene's components)
from .fields import check_all_finite, quantity, spec  # noqa: F401  (check_all_finite re-exported)
from .harmonics import MAX_AMPLITUDE_M, MAX_FREQUENCY_RAD_S, Sinusoid, Wave
from .sea import MotionRAO, SeaSpectrum, append_once, rotation_sinusoids, sea_sinusoids
from .track import Track
from .vessel import VesselRAO


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
        check_all_finite(self, "cable")
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
    track: Track | None = spec("none", "the tow point's path in the horizontal plane at a speed (scene/track.py Track: "
                               "a circle, realised as sinusoids in x and z, the run starting on its steady turn; a "
                               "straight, a turn, a zig-zag or a path of legs, the run starting on the steady straight "
                               "tow)", None)
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
            if self.vessel is not None:     # its rotation too, for further points of the vessel (scene/vessel.py)
                object.__setattr__(self, "_rotation", dict(zip("xyz", rotation_sinusoids(self.spectrum, self.vessel))))
            counts = {}
            for axis, terms in realised.items():
                n = len(getattr(self, axis))
                object.__setattr__(self, axis, append_once(getattr(self, axis), terms))
                counts[axis] = len(getattr(self, axis)) - len(terms) if len(getattr(self, axis)) == n else n
            object.__setattr__(self, "_user_count", counts)
        elif self.rao is not None or self.vessel is not None:
            name = "top_motion.rao" if self.rao is not None else "top_motion.vessel"
            raise ParameterError(name, "given", "needs a [top_motion.spectrum] sea to act on")
        if self.track is not None:     # alone: the run starts on the circle's steady turn or the path's straight tow
            others = [n for n in ("spectrum", "series") if getattr(self, n) is not None]
            sx, sz = self.track.sinusoids() if self.track.is_circle else ((), ())   # the circle as sinusoids
            x, z = append_once(self.x, sx), append_once(self.z, sz)
            others += [f"{a}[0]" for a, mine, got in (("x", sx, x), ("z", sz, z)) if len(got) != len(mine)]
            others += ["y[0]"] if self.y else []
            start = "the steady turn" if self.track.is_circle else "the steady straight tow"
            if others:
                raise ParameterError(f"top_motion.{others[0]}", "given with top_motion.track",
                                     f"must be unset: the run starts on {start}, which other top motion "
                                     "would not leave steady")
            if self.ramp_s not in (None, 0.0):
                raise ParameterError("top_motion.ramp_s", self.ramp_s, "must be 0 or unset with top_motion.track: "
                                     f"the run starts on {start}, not from rest")
            object.__setattr__(self, "x", x)
            object.__setattr__(self, "z", z)
            object.__setattr__(self, "_user_count", {"x": 0, "y": 0, "z": 0})

    @property
    def vessel_rotation(self) -> dict:
        """{axis: sinusoids} of the vessel's small rotation about cablesys' axes x, y, z (rad; the sea realised through
        :meth:`.vessel.VesselRAO.rotation_transfer`, the same components and phases as its translation in x, y, z);
        {} without [top_motion.vessel]. It moves a system's further prescribed points, each by its own lever arm
        (s_0 + theta x Delta, scene/vessel.py)."""
        return getattr(self, "_rotation", {})

    @property
    def effective_ramp_s(self) -> float:
        """The smooth start's duration (s): ``ramp_s``, or when unset RAMP_PERIODS periods of the longest
        forcing period (of the user's sinusoids and a sea's T_p, not of the sea's realised components,
        whose low-frequency tail has arbitrarily long periods); 0 without sinusoids (a recorded series
        plays as recorded) and with a track (the run starts on its steady turn or straight tow)."""
        if self.ramp_s is not None:
            return float(self.ramp_s)
        if self.track is not None:       # the run starts on the steady turn or the steady straight tow
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
RUNGS = ("frequency", "quasi-static", "wang", "steady", "segmented")
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
                              "model: segments per [cable]) | frequency | quasi-static | wang | steady | segmented (cablesys.ladder)",
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
