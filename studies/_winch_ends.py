"""The winch with the line's other ends, checks of ``ends_checks.py`` (node model, :mod:`cablesys.model.segmented_winch`):
a mooring line hauled in at its fairlead against the catenary of its current length, the mass of an anchored line in
the water, and the winch in space against the planar one (see that study's docstring for the keys)."""

from __future__ import annotations

import dataclasses

import numpy as np

from cablesys.model import build_model
from cablesys.scene import (Anchor, Body, Cable, Numerics, Seabed, Sinusoid, TopMotion, Winch,
                            single_section_scene)
from cablesys.statics.catenary import segmented_steady
from cablesys.statics.closed_forms import seabed_catenary, seabed_catenary_span
from cablesys.time_domain.run import simulate

# the chain of ends_checks.py, 150 m of its 300 m on the bed at the start
LENGTH, W, EA, DEPTH, DIAMETER, MASS = 300.0, 1300.0, 5e7, 100.0, 0.1, 150.0
LAID = 150.0


def span() -> float:
    """The fairlead's span (m) that lays ``LAID`` m of the 300 m chain on the bed (frictionless closed form)."""
    return seabed_catenary_span(length=LENGTH, weight_per_length=W, ea=EA, height=DEPTH, seabed_length=LAID)


def mooring(n: int, length: float = LENGTH, *, winch: Winch | None = None, friction: float = 0.0,
            duration: float = 10.0, rtol: float = 1e-8):
    """The chain from the fairlead (the top, at rest, where the winch is) to its anchor on the bed, MoorDyn's default
    bed, cross-flow drag (C_D 1.2) to damp the catenary's slow swing, Voigt damping C_I = 0.02 s EA; ``length`` the
    zero-tension length in the water at t = 0."""
    return single_section_scene(
        cable=Cable(length=length, ae=EA, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W, cd_normal=1.2,
                    ct_tangential=0.0, internal_damping=0.02 * EA, segments=n),
        body=Body(weight=0.0, mass_x=1.0, mass_y=1.0), anchor=Anchor(x=span(), y=DEPTH),
        seabed=Seabed(depth=DEPTH, stiffness=3e6, damping=3e5, friction_axial=friction), winch=winch,
        numerics=Numerics(duration=duration, output_step=1.0, model="as-built", rtol=rtol, atol=rtol))


def closed_form_tension(L: float, friction: float = 0.0) -> float:
    """The fairlead tension (N) of :func:`seabed_catenary` for the zero-tension length L (m) at the fixed span."""
    cf = seabed_catenary(length=L, weight_per_length=W, ea=EA, span=span(), height=DEPTH, friction=friction)
    return float(np.hypot(cf["H"], cf["V_F"]))


def static_tension(n: int, L: float, friction: float = 0.0) -> float:
    """The node model's static fairlead tension (N, ``tension_top``) of the line of zero-tension length L (m)."""
    sc = mooring(n, L, friction=friction)
    model = build_model(sc)
    return float(segmented_steady(model, model.parameters(sc)).outputs["tension_top"])


def haulin(n: int = 10, speed: float = 0.1, haul: float = 10.0, ramp: float = 10.0, friction: float = 0.0,
           points: int = 6, series: bool = False) -> dict:
    """Haul ``haul`` m of the mooring line in at its fairlead at ``speed`` m/s (ramps of ``ramp`` s) and compare the
    fairlead tension at ``points`` lengths L from l_0 to l_0 - haul with the catenary of that length: the closed form
    (:func:`closed_form_tension`; rigid flat bed, the continuum) and the node model's own statics at that L and N
    (:func:`static_tension`, the same discretisation): their difference is the haul-in's dynamics, which vanish as the
    speed does; the static's against the closed form is the discretisation, second order in 1/N. With friction, the
    laid part's friction during the haul (``seabed_friction`` on the bed's nodes, + towards the anchor at +x: the
    cable's material is pulled towards the fairlead, while the nodes, which are not material points under a winch,
    slide towards the anchor) and the statics of the friction-free and of the laid-down line of that length, between
    which the fairlead's tension must lie (the friction of the haul builds from the laid-down state's). ``series``: also
    the run's (L, T) and the lengths with the statics' and the closed form's tensions."""
    dur = haul / speed + ramp
    sc = mooring(n, winch=Winch(speed=-speed, duration=dur, ramp=ramp, max_length=LENGTH + 1.0), friction=friction,
                 duration=dur + 5.0)
    rec = simulate(sc)
    L, T = rec["winch_length"], rec["tension_top"]
    Ls = np.linspace(LENGTH, LENGTH - haul, points)
    run = np.interp(Ls[::-1], L[::-1], T[::-1])[::-1]           # the run's tension as L passes each length
    cf = np.array([closed_form_tension(x) for x in Ls])
    st = np.array([static_tension(n, x) for x in Ls])
    out = {"N": n, "speed_m_s": speed, "haul_m": haul, "lengths_m": Ls.tolist(), "success": bool(rec.success),
           "vs_closed_form_max_rel": float(np.max(np.abs(run / cf - 1))),
           "vs_statics_max_rel": float(np.max(np.abs(run / st - 1))),
           "statics_vs_closed_form_max_rel": float(np.max(np.abs(st / cf - 1))),
           "length_end_m": float(L[-1])}
    if series:
        out["series"] = (L, T, Ls, st, cf)
    if friction > 0:
        laid = np.array([static_tension(n, x, friction) for x in Ls])
        lo, hi = np.minimum(st, laid), np.maximum(st, laid)
        out.update(friction=friction,
                   outside_band_max_rel=float(np.max(np.maximum(lo - run, run - hi) / st)),
                   band_width_max_rel=float(np.max((hi - lo) / st)),
                   friction_min_N=float(np.min(rec.profiles["seabed_friction"])),
                   friction_max_N=float(np.max(rec.profiles["seabed_friction"])))
    return out


def anchored_mass(n: int = 5) -> float:
    """The free nodes' mass (the x blocks' trace, no added mass) of a mooring line hauled in, held and paid back out,
    against m_r L (1 - 1 / N): the cable in the water less the half elements lumped at the sheave and at the anchor,
    which are not coordinates (largest relative error over nine times)."""
    cab = Cable(length=LENGTH, ae=EA, diameter=DIAMETER, mass_per_length=MASS, weight_per_length=W,
                added_mass_factor=0.0, segments=n)
    from cablesys.scene import Leg
    winch = Winch(leg=(Leg(speed=-2.0, duration=10.0), Leg(speed=0.0, duration=3.0), Leg(speed=2.0, duration=10.0)),
                  start=1.0, ramp=2.0, max_length=LENGTH + 10.0)
    sc = single_section_scene(cable=cab, body=Body(weight=0.0, mass_x=1.0, mass_y=1.0), anchor=Anchor(x=span(), y=DEPTH),
                              seabed=Seabed(depth=DEPTH), winch=winch, numerics=Numerics(duration=30.0))
    model = build_model(sc)
    p = model.parameters(sc)
    q = np.concatenate([[span() * (j + 1) / n, DEPTH * (j + 1) / n] for j in range(n - 1)])
    errs = []
    for t in (0.0, 2.0, 5.0, 9.0, 12.0, 14.0, 18.0, 22.0, 30.0):
        e = np.zeros(7)
        e[0] = t
        M = np.array(model.dynamics(q, np.zeros_like(q), e, p)[0])
        L = LENGTH + winch.profile(t)[0]
        errs.append(abs(np.trace(M[0::2, 0::2]) / (MASS * L * (1 - 1 / n)) - 1))
    return float(max(errs))


def winch_3d(heading_deg: float = 40.0, n: int = 6, duration: float = 20.0, rtol: float = 1e-10) -> dict:
    """The lift of ``_lift.py`` (a 2 kN package on 30 mm wire) lowered, held and hauled back in under a top moving in
    surge and heave, in a 0.5 m/s current: planar, forced through the 3-D equations, and in space with the current and
    the top's surge turned to ``heading_deg`` (the top's motion as x and z sinusoids). Returns the 3-D right-hand side
    at the planar run's states against the planar one (largest relative difference), the runs' largest differences
    (m, after turning back; and N of the top tension), and the winch's length at the end. The right-hand sides'
    difference is relative to the largest node acceleration of the run."""
    import _lift
    g = np.radians(heading_deg)
    base = _lift.lift_scene(_lift.round_trip_winch(out=10.0, hold=3.0), duration, n, rtol=rtol, atol=rtol)

    def scene(h, dims):
        c = np.radians(h)
        top = TopMotion(x=(Sinusoid(amplitude=np.cos(c), frequency=0.8),), y=(Sinusoid(amplitude=0.5, frequency=0.8),),
                        z=() if dims is None else (Sinusoid(amplitude=np.sin(c), frequency=0.8),))
        env = dataclasses.replace(base.environment, current_speeds=(0.5,),
                                  current_headings_deg=() if dims is None else (h,))
        return dataclasses.replace(base, top_motion=top, environment=env,
                                   numerics=dataclasses.replace(base.numerics, dimensions=dims))

    scenes = {"plane": scene(0.0, None), "forced": scene(0.0, 3), "turned": scene(heading_deg, 3)}
    models = {k: build_model(s) for k, s in scenes.items()}
    runs = {k: simulate(s, model=models[k]) for k, s in scenes.items()}
    X2, t = np.asarray(runs["plane"].states), np.asarray(runs["plane"].time)
    k = X2.shape[0] // 4
    p2, p3 = models["plane"].parameters(scenes["plane"]), models["forced"].parameters(scenes["forced"])
    diff, scale = 0.0, 0.0
    for i in range(0, len(t), 4):
        q, v = X2[:2 * k, i].reshape(k, 2), X2[2 * k:, i].reshape(k, 2)
        x3 = np.concatenate([np.column_stack([q, np.zeros(k)]).ravel(), np.column_stack([v, np.zeros(k)]).ravel()])
        a2 = np.array(models["plane"].ode(X2[:, i], t[i], p2)).ravel()[2 * k:].reshape(k, 2)
        a3 = np.array(models["forced"].ode(x3, t[i], p3)).ravel()[3 * k:].reshape(k, 3)
        diff = max(diff, float(np.max(np.abs(a3 - np.column_stack([a2, np.zeros(k)])))))
        scale = max(scale, float(np.max(np.abs(a2))))
    rhs = diff / scale
    nodes = lambda r: np.asarray(r.states)[:3 * k].reshape(k, 3, -1)
    q2 = np.asarray(runs["plane"].states)[:2 * k].reshape(k, 2, -1)
    turn = np.array([[np.cos(g), 0.0, np.sin(g)], [0.0, 1.0, 0.0], [-np.sin(g), 0.0, np.cos(g)]])   # turns back
    back = np.einsum("ij,njt->nit", turn, nodes(runs["turned"]))
    return {"rhs_max_rel": rhs,
            "forced_max_abs_m": float(np.max(np.abs(nodes(runs["forced"])[:, :2] - q2))),
            "turned_max_abs_m": float(np.max(np.abs(back[:, :2] - q2))),
            "turned_sway_back_max_abs_m": float(np.max(np.abs(back[:, 2]))),
            "tension_top_max_abs_N": float(max(np.max(np.abs(runs[r]["tension_top"] - runs["plane"]["tension_top"]))
                                               for r in ("forced", "turned"))),
            "length_m": [float(runs["plane"]["winch_length"][0]), float(np.max(runs["plane"]["winch_length"])),
                         float(runs["turned"]["winch_length"][-1])],
            "heading_deg": heading_deg, "N": n, "success": all(r.success for r in runs.values())}
