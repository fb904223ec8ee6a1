"""The numbers that decide the rung: what the scene and its linearization say about the cable.

All closed forms, cheap (no time integration): forcing frequencies, Wang's axial frequency
(a spring with the body and a third of the cable, Wang 1971 eq. 22-25), the first string mode of
the cable under its mean tension, cable-to-body mass and weight ratios, and the bowing of the cable
under current and under the drag of its own motion against its chord (a uniformly loaded string:
sag q L^2 / (8 T)).
"""

from __future__ import annotations

import cmath
import dataclasses
import math

import numpy as np

from ..model.quasistatic import axial_frequencies
from ..scene import Scene


@dataclasses.dataclass(frozen=True)
class SceneNumbers:
    """Deciding numbers of a scene (SI; ratios dimensionless)."""

    forcing: tuple                 # ((omega rad/s, amplitude m), ...) of the top motion and waves
    omega_forcing: float           # highest forcing frequency with a non-negligible amplitude
    single_frequency: bool         # sinusoids at one frequency only (a periodic steady state exists)
    omega_axial: float             # lowest stretch frequency of the sections (rad/s)
    axial_ratio: float             # omega_forcing / omega_axial
    omega_string: float            # first string mode of the longest section (rad/s)
    omega_swing: float             # compound-pendulum frequency of the (first) section (rad/s)
    string_ratio: float            # omega_forcing / omega_string
    mass_ratio: float              # cable mass (with added mass) / body virtual mass
    weight_ratio: float            # cable weight / body weight in water
    transverse_fraction: float     # part of the top motion normal to the (static) cable
    static_bow: float              # current-drag sag / chord
    dynamic_bow: float             # sag under the drag of the top's motion / chord
    tension_static: float          # body-end tension hanging at rest (N)
    tension_floor: float           # least tension the cable supports (N)

    def as_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["forcing"] = [list(f) for f in self.forcing]
        return d


def forcing_components(scene: Scene) -> list[tuple[float, float]]:
    """(omega, amplitude) of every sinusoid of the top motion (surge, heave and, in 3-D, sway), then every wave and
    the sampled series (:func:`other_components`)."""
    top = scene.top_motion
    comps = [(s.frequency, abs(s.amplitude)) for s in top.x + top.y + top.z if s.amplitude != 0.0]
    return comps + other_components(scene)


def other_components(scene: Scene) -> list[tuple[float, float]]:
    """(omega, amplitude) of every wave (sigma = sqrt(2 pi g / lambda), Wang 1971 eq. 26) and of the sampled series
    (its spectrum's components above 1 % of the largest): the forcing that is not a sinusoid of the top."""
    top = scene.top_motion
    g = scene.environment.gravity
    comps = [(math.sqrt(2 * math.pi * g / w.length), w.amplitude) for w in scene.environment.waves if w.amplitude > 0]
    if top.series is not None:
        t = np.asarray(top.series.times)
        dt = float(np.min(np.diff(t)))
        grid = np.arange(t[0], t[-1], dt)
        for y in (top.series.x, top.series.y):
            v = np.interp(grid, t, y)
            spec = np.abs(np.fft.rfft(v - v.mean())) * 2 / max(len(v), 1)
            om = 2 * np.pi * np.fft.rfftfreq(len(v), dt)
            if spec.size > 1 and spec.max() > 0:
                keep = spec > 0.01 * spec.max()
                comps += [(float(o), float(a)) for o, a in zip(om[keep], spec[keep]) if o > 0]
    return comps


def relative_flow(scene: Scene) -> tuple[float, float]:
    """(u, beta): the steady relative flow (the current minus the system speed along +x, Wang 1971 eq. 26-28) of
    largest size over the current's depths, m/s, and the heading beta of the vertical plane it lies in (rad from +x
    towards +z, the current headings' convention). In the plane beta = 0 and u is signed along +x, as the planar
    equations take it; in a 3-D scene the flow is the vector (U cos h - V_s, U sin h) per depth, u its size (the
    static cable lies in the plane of the flow: the estimates of :mod:`.continuum` turn the top motion into it)."""
    env = scene.environment
    if not getattr(scene, "three_d", False):
        return max((s - env.system_speed for s in env.current_speeds), key=abs), 0.0
    flows = [(s * math.cos(math.radians(h)) - env.system_speed, s * math.sin(math.radians(h)))
             for s, h in zip(env.current_speeds, env.headings_per_depth_deg)]
    vx, vz = max(flows, key=lambda v: math.hypot(*v))
    size = math.hypot(vx, vz)
    return size, (math.atan2(vz, vx) if size > 0.0 else 0.0)


def top_phasors(scene: Scene, beta: float = 0.0) -> list[tuple[float, complex, complex, complex]]:
    """(omega, X, Y, Z) per forcing frequency of the top's sinusoids: the complex amplitudes, a sin(wt + ph) =
    Re(-i a e^{i ph} e^{iwt}), summed per axis, with surge and sway turned by ``beta`` about the vertical into the
    axes along and across a heading (X cos beta + Z sin beta, -X sin beta + Z cos beta); Z = 0 in the plane."""
    comps: dict = {}
    axes = ("x", "y", "z")
    for axis in axes:
        for s in getattr(scene.top_motion, axis):
            if s.amplitude == 0.0:
                continue
            z = comps.setdefault(round(s.frequency, 12), [s.frequency, 0j, 0j, 0j])
            z[1 + axes.index(axis)] += -1j * s.amplitude * cmath.exp(1j * s.phase)
    if beta != 0.0:
        c, s_ = math.cos(beta), math.sin(beta)
        for z in comps.values():
            z[1], z[3] = z[1] * c + z[3] * s_, -z[1] * s_ + z[3] * c
    return [tuple(v) for v in comps.values()]


def top_amplitudes(scene: Scene) -> tuple[float, float, float]:
    """(a_parallel, a_y, a_perpendicular): the top's motion amplitudes (m) along the flow's heading beta
    (:func:`relative_flow`), vertical, and across it (horizontal). In the plane the sums of the sinusoids' amplitudes
    per axis (a bound over frequencies), (a_x, a_y, 0); in a 3-D scene the sums over the forcing frequencies of the
    sizes of the complex amplitudes turned into the flow's axes (:func:`top_phasors`), so that a scene turned about
    the vertical has the same amplitudes."""
    top = scene.top_motion
    if not getattr(scene, "three_d", False):
        return (sum(abs(s.amplitude) for s in top.x), sum(abs(s.amplitude) for s in top.y), 0.0)
    comps = top_phasors(scene, relative_flow(scene)[1])
    return tuple(float(sum(abs(c[k]) for c in comps)) for k in (1, 2, 3))


def static_angle(scene: Scene) -> float:
    """Angle of the top section from the vertical in a current (rad), in the vertical plane of the flow
    (:func:`relative_flow`): drag of the body and half the cable's against the weights below the cable's middle
    (the straight-cable balance, eq. 47-48)."""
    env = scene.environment
    u = relative_flow(scene)[0]
    drag, weight = 0.0, 0.0
    for k, sec in enumerate(scene.sections):
        c, b = sec.cable, sec.body
        drag += 0.5 * env.density * (b.drag_area_normal * u * abs(u) + c.cd_normal * c.diameter * c.length * u * abs(u))
        weight += b.weight + c.total_weight
    c0 = scene.sections[0].cable
    drag0 = drag - 0.25 * env.density * c0.cd_normal * c0.diameter * c0.length * u * abs(u)
    return math.atan2(drag0, max(weight - 0.5 * c0.total_weight, 1e-300))


def below_mass(scene: Scene, section) -> float:
    """Mass of the sections and bodies hanging below ``section`` (kg)."""
    secs = list(scene.sections)
    i = next(k for k, s in enumerate(secs) if s is section)
    return sum(s.body.mass_x + s.cable.total_mass for s in secs[i + 1:])


def scene_numbers(scene: Scene) -> SceneNumbers:
    """The deciding numbers of ``scene`` (see the module docstring)."""
    comps = forcing_components(scene)
    amp_max = max((a for _, a in comps), default=0.0)
    significant = [w for w, a in comps if a >= 0.01 * amp_max]
    w_f = max(significant, default=0.0)
    single = scene.top_motion.series is None and len({round(w, 12) for w, _ in comps}) == 1
    env = scene.environment
    rho = env.density
    w_ax = min(axial_frequencies(scene))
    w_str, mass_r, weight_r, bow_s, bow_d, w_sw = math.inf, 0.0, 0.0, 0.0, 0.0, 0.0
    a_x, a_y, a_z = top_amplitudes(scene)          # along the flow's plane, vertical, across it (3-D)
    a_top = math.hypot(math.hypot(a_x, a_y), a_z)
    phi0 = static_angle(scene)
    # the top motion normal to the cable, e_n = (-cos phi, -sin phi) (Wang 1971 eq. 17), and in 3-D the sway
    # across the flow's plane (normal to the static cable): only it bows the cable and excites its string
    # modes; motion along the cable stretches it
    a_normal = math.hypot(math.hypot(a_x * math.cos(phi0), a_y * math.sin(phi0)), a_z)
    below = 0.0
    t_static = None
    u_rel = abs(relative_flow(scene)[0])
    for sec in reversed(scene.sections):
        c, b = sec.cable, sec.body
        t_mean = below + b.weight + 0.5 * c.total_weight
        if t_static is None:
            t_static = b.weight
        m_v = c.mass_per_length + c.added_mass_factor * rho * math.pi * c.diameter**2 / 4
        if t_mean > 0 and m_v > 0:
            w_str = min(w_str, math.pi / c.length * math.sqrt(t_mean / m_v))
        mass_r = max(mass_r, m_v * c.length / b.mass_x)
        # compound pendulum, omega^2 = (W_b + W_c/2) / (L (M_bvx + M_cv/3)) (Wang 1971 eq. 22-25)
        w_sw = math.sqrt(max(t_mean, 0.0) / (c.length * (b.mass_x + below_mass(scene, sec) + m_v * c.length / 3)))
        weight_r = max(weight_r, c.total_weight / max(abs(b.weight), 1e-300))
        q_s = 0.5 * rho * c.cd_normal * c.diameter * u_rel**2
        q_d = 0.5 * rho * c.cd_normal * c.diameter * (w_f * a_normal) ** 2
        if t_mean > 0:
            bow_s = max(bow_s, q_s * c.length / (8 * t_mean))
            bow_d = max(bow_d, q_d * c.length / (8 * t_mean))
        below += b.weight + c.total_weight
    floor = max(s.cable.tension_floor for s in scene.sections)
    return SceneNumbers(forcing=tuple(comps), omega_forcing=w_f, single_frequency=single, omega_axial=w_ax,
                        axial_ratio=w_f / w_ax, omega_string=w_str, omega_swing=w_sw, string_ratio=w_f / w_str if w_str > 0 else math.inf,
                        mass_ratio=mass_r, weight_ratio=weight_r, static_bow=bow_s, dynamic_bow=bow_d,
                        transverse_fraction=a_normal / a_top if a_top > 0 else 0.0,
                        tension_static=float(t_static), tension_floor=float(floor if math.isfinite(floor) else -1e300))
