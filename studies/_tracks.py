"""A towing ship's manoeuvres (cablesys/scene/track.py, cablesys/model/track_path.py, cablesys/statics/tow.py): the
checks of ``studies/three_d_checks.py``'s track keys, shared with tests/test_tracks.py.

- :func:`galilean`: a straight track at the speed U through still water against the same scene towed in the ship's
  frame (``environment.system_speed = U``), started from the same shape off its steady state (the statics at a
  lower speed): the body's motion relative to the tow point and the tensions must agree (Galilean invariance,
  Goldstein 1980 sec. 1.1) to the integration's accuracy, for a cable without added mass; with the added mass they
  differ by the Munk couples of the elements (:mod:`cablesys.statics.tow`), :func:`munk`;
- :func:`munk`: that difference, f(q, V) on the ground minus f(q, 0) in the ship's frame at the same shape, against
  the closed form of the slender elements' Munk couple and axial pair (Newman 1977 sec. 4.13);
- :func:`turn_settles`: a turn through 360+ degrees from the steady straight tow settles on the steady turn of
  :mod:`cablesys.statics.turning` for the same radius and speed (the body's place relative to the tow point, in
  the frame of its heading, and the top tension);
- :func:`rotation`: a zig-zag whose base course is turned by alpha gives the first one's answer turned by alpha
  (the same fixed RK4 steps: the difference is rounding).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import tomllib

from cablesys.model import build_model
from cablesys.scene import scene_from_dict
from cablesys.statics.catenary import segmented_steady
from cablesys.statics.tow import tow_parameters, tow_velocity
from cablesys.statics.turning import turning_initial_state
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator, simulate

LENGTH_M = 60.0
BASE = """
name = "a towed body on 60 m of 20 mm wire{what}"
[cable]
length = 60.0
ae = 4.0e7
diameter = 0.02
mass_per_length = 1.5
weight_per_length = 12.0
cd_normal = 1.5
internal_damping = 2.0e4
added_mass_factor = {gamma}
segments = {n}
[body]
weight = 3000.0
mass_x = 500.0
mass_y = 600.0
drag_area_normal = 0.5
drag_area_tangential = 0.2
axis_angle_deg = 0.0
"""
ZIGZAG = """[top_motion.track]
kind = "zig-zag"
speed = 2.0
radius = 40.0
heading_change_deg = 20.0
leg_length = 200.0
lead_in = 20.0
heading_deg = {heading}
"""


def scene(track: str = "", *, gamma: float = 1.0, n: int = 4, what: str = "", **numerics):
    """The towed body's scene with ``track`` (TOML text after the cable and body) and numerics."""
    sc = scene_from_dict(tomllib.loads(BASE.format(gamma=gamma, n=n, what=what) + track))
    return dataclasses.replace(sc, numerics=dataclasses.replace(sc.numerics, **numerics)) if numerics else sc


def _run(sc, model, x0=None, *, method="cvodes", rtol=1e-10, compiled=False, steps=None):
    """One run of ``model`` (compiled or in CasADi's virtual machine), its output times the scene's."""
    kw = {} if steps is None else {"steps_per_output": steps}
    sim = Simulator(model, sc.output_times, IntegratorSettings(method=method, rtol=rtol, atol=rtol, compiled=compiled,
                                                              **kw))
    r = simulate(sc, model=model, x0=x0, simulator=sim)
    if not r.success:
        raise RuntimeError(f"{sc.name}: the run failed ({r.message})")
    return r


def galilean(gamma: float = 0.0, *, speed: float = 2.0, start_speed: float = 1.0, duration: float = 30.0,
             method: str = "rk", rtol: float = 1e-10) -> dict:
    """The straight track at ``speed`` against ``environment.system_speed = speed``, both from the shape of the
    steady tow at ``start_speed`` (released: the cable swings back), the track's nodes moving with the tow point.
    The largest difference of the body's position (m) and velocity relative to the tow point and of the tensions,
    each over the ship-frame run's largest value; ``start_max_abs_m`` the two scenes' own initial states (their
    steady tows) apart, relative to the tow point (0 without added mass; the Munk couples' offset with it).

    ``method = "rk"``: the same fixed RK4 steps (0.0025 s) in both runs, which a Runge-Kutta method takes alike in the
    two frames (it integrates the shift (U t, U) exactly: Butcher, Numerical Methods for Ordinary Differential
    Equations, 2016, sec. 31, affine covariance), so the difference is the equations' and rounding; ``"cvodes"`` at
    ``rtol``: each run's own steps, the difference the integration's error."""
    num = dict(duration=duration, output_step=0.5)
    sc_t = scene(f'[top_motion.track]\nkind = "straight"\nspeed = {speed}\n', gamma=gamma,
                 what=": towed straight along x", **num)
    sc_s = scene(f"[environment]\nsystem_speed = {speed}\n", gamma=gamma, what=": in the ship's frame", **num)
    mt, ms = build_model(sc_t), build_model(sc_s)
    pt, ps = mt.parameters(sc_t), ms.parameters(sc_s)
    from cablesys.time_domain.initial import initial_state
    x_t0, x_s0 = initial_state(sc_t, mt, pt), initial_state(sc_s, ms, ps)
    nq = mt.nq
    shift = np.concatenate([np.zeros(nq), np.tile([speed, 0.0], nq // 2)])        # the nodes move with the tow point
    start = float(np.max(np.abs(x_t0 - x_s0 - shift)))
    q1 = segmented_steady(ms, tow_parameters(ms, ps, start_speed, 0.0)).q
    x_s = np.concatenate([q1, np.zeros(nq)])
    kw = dict(method="rk", steps=200) if method == "rk" else dict(method=method, rtol=rtol)
    r_t, r_s = _run(sc_t, mt, x_s + shift, **kw), _run(sc_s, ms, x_s, **kw)
    t = np.asarray(r_t.time)
    rel = {"x_b": speed * t, "x_b_rate": speed}
    diff = {k: float(np.max(np.abs(np.asarray(r_t[k]) - rel.get(k, 0.0) - np.asarray(r_s[k])))
                     / np.max(np.abs(np.asarray(r_s[k]))))
            for k in ("x_b", "y_b", "x_b_rate", "y_b_rate", "tension_top", "tension_bottom")}
    return {"added_mass_factor": gamma, "speed_m_s": speed, "method": method, "rtol": rtol if method != "rk" else None,
            "duration_s": duration,
            "position_max_rel": max(diff["x_b"], diff["y_b"]), "velocity_max_rel": max(diff["x_b_rate"], diff["y_b_rate"]),
            "tension_max_rel": max(diff["tension_top"], diff["tension_bottom"]), "max_rel": max(diff.values()),
            "per_output": diff, "start_max_abs_m": start,
            "body_swing_m": float(np.ptp(np.asarray(r_s["x_b"])))}


def munk(speed: float = 2.0) -> dict:
    """At the ship frame's steady tow q (system speed U): the node model's forces on the ground, nodes moving at
    V = (U, 0), minus the ship frame's, nodes still (the drag, tension and weight are the same), against the
    closed form of each element's K = 1/2 a |V_n|^2, a = gamma rho pi d^2 / 4 l (Wang 1971 eq. 23-24): dK/dr_b =
    -dK/dr_a = 1/2 (a / l) |V_n|^2 e_t - (a / l) (V . e_t) V_n, the Munk couple (a V_t V_n, Newman 1977 sec. 4.13)
    and an axial pair; the largest difference over the largest term."""
    sc_t = scene(f'[top_motion.track]\nkind = "straight"\nspeed = {speed}\n')
    sc_s = scene(f"[environment]\nsystem_speed = {speed}\n")
    mt, ms = build_model(sc_t), build_model(sc_s)
    pt, ps = mt.parameters(sc_t), ms.parameters(sc_s)
    q = segmented_steady(ms, ps).q
    V = tow_velocity(mt, speed, 0.0)
    n = mt.nq // 2
    e_t = np.concatenate([[0.0, 0.0, 0.0], V, [0.0, 0.0]])      # (t, x_s, y_s, velocity, acceleration)
    f_t = np.array(mt.dynamics(q, np.tile(V, n), e_t, pt)[1]).ravel()
    f_s = np.array(ms.dynamics(q, np.zeros(mt.nq), np.zeros(7), ps)[1]).ravel()
    c = sc_t.cable
    a_per_l = c.added_mass_factor * sc_t.environment.density * math.pi * c.diameter**2 / 4
    nodes = np.vstack([[0.0, 0.0], q.reshape(-1, 2)])
    closed, couples = np.zeros((n + 1, 2)), []
    for k in range(n):
        d = nodes[k + 1] - nodes[k]
        et = d / np.linalg.norm(d)
        vt = V @ et
        vn = V - vt * et
        force = 0.5 * a_per_l * (vn @ vn) * et - a_per_l * vt * vn
        closed[k + 1] += force
        closed[k] -= force
        couples.append(float(a_per_l * np.linalg.norm(d) * vt * np.linalg.norm(vn)))     # (m_n - m_t) V_t V_n
    err = np.abs(f_t - f_s - closed[1:].ravel())
    return {"rel_err": float(np.max(err) / np.max(np.abs(closed[1:]))), "largest_term_N": float(np.max(np.abs(closed))),
            "munk_couples_N_m": couples}


def turn_settles(turn_deg: float = 450.0, *, radius: float = 40.0, speed: float = 2.0, n: int = 4,
                 rtol: float = 1e-8) -> dict:
    """A turn to port through ``turn_deg`` from the steady straight tow (no lead-in) against the steady turn of a
    circle of the same radius and speed (:func:`cablesys.statics.turning.turning_state`): the body relative to the
    tow point in the frame of its heading (ahead, down, to port), and the top tension, over the run; ``rel_err`` the
    body's distance from the steady turn's place at the end of the arc over the cable's length."""
    arc = radius * math.radians(turn_deg)
    num = dict(duration=arc / speed, output_step=1.0)
    track = f'[top_motion.track]\nkind = "turn"\nspeed = {speed}\nradius = {radius}\nturn_angle_deg = {turn_deg}\n'
    sc = scene(track, n=n, what=f": a {turn_deg:g} deg turn of radius {radius:g} m at {speed:g} m/s", **num)
    model = build_model(sc)
    r = _run(sc, model, rtol=rtol)
    circle = scene(f"[top_motion.track]\nradius = {radius}\nspeed = {speed}\n", n=n)
    mc = build_model(circle)
    pc = mc.parameters(circle)
    x0 = turning_initial_state(circle, mc, pc)
    start = np.array([0.0, 0.0, -radius])                      # the circle's tow point at t = 0, heading +x
    steady = x0[:mc.nq].reshape(-1, 3)[-1] - start
    e = np.array(mc.top(0.0, pc)).ravel()
    steady_tension = float(np.array(mc.outputs(x0, e, pc)).ravel()[mc.output_labels.index("tension_top")])
    t = np.asarray(r.time)
    psi = speed * t / radius                                   # the heading along the arc (from +x, to port)
    rel = np.column_stack([np.asarray(r["x_b"]) - np.asarray(r["x_s"]), np.asarray(r["y_b"]),
                           np.asarray(r["z_b"]) - np.asarray(r["z_s"])])
    c, s = np.cos(psi), np.sin(psi)
    own = np.column_stack([c * rel[:, 0] + s * rel[:, 2], rel[:, 1], -s * rel[:, 0] + c * rel[:, 2]])
    dist = np.linalg.norm(own - steady, axis=1)
    tension = np.asarray(r["tension_top"])
    return {"turn_deg": turn_deg, "radius_m": radius, "speed_m_s": speed, "elements": n, "rtol": rtol,
            "rel_err": float(dist[-1] / LENGTH_M), "start_distance_m": float(dist[0]),
            "tension_top_rel_err": float(abs(tension[-1] / steady_tension - 1.0)),
            "steady_body_from_tow_point_m": steady.tolist(), "end_body_from_tow_point_m": own[-1].tolist(),
            "steady_tension_top_N": steady_tension, "time_s": t.tolist(), "distance_m": dist.tolist(),
            "track_x_m": np.asarray(r["x_s"]).tolist(), "track_z_m": np.asarray(r["z_s"]).tolist(),
            "body_x_m": np.asarray(r["x_b"]).tolist(), "body_z_m": np.asarray(r["z_b"]).tolist()}


def rotate(alpha: float, v):
    """(x, y, z) turned by ``alpha`` (rad) about the vertical y, from +x towards +z."""
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([c * v[0] - s * v[2], v[1], s * v[0] + c * v[2]])


def rotation(alpha_deg: float = 35.0, *, duration: float = 60.0, n: int = 3) -> dict:
    """The zig-zag on base course 0 and on ``alpha_deg``, the same fixed RK4 steps (0.0025 s): the node positions of
    the first turned by alpha against the second's (m), the tensions (relative)."""
    alpha = math.radians(alpha_deg)
    runs = []
    for heading in (0.0, alpha_deg):
        sc = scene(ZIGZAG.format(heading=heading), n=n, duration=duration, output_step=0.5)
        runs.append(_run(sc, build_model(sc), method="rk", steps=200))
    pos = [np.stack([np.asarray(r.profiles[f"node_{ax}"]) for ax in "xyz"], axis=-1) for r in runs]
    turned = np.einsum("ij,tnj->tni", np.array([rotate(alpha, e) for e in np.eye(3)]).T, pos[0])
    ten = lambda r: [np.asarray(r["tension_top"]), np.asarray(r["tension_bottom"]), np.asarray(r.profiles["element_tension"])]
    return {"alpha_deg": alpha_deg, "duration_s": duration, "elements": n,
            "position_max_abs_m": float(np.max(np.abs(turned - pos[1]))),
            "tension_max_rel": max(float(np.max(np.abs(a - b)) / np.max(np.abs(a))) for a, b in zip(ten(runs[0]), ten(runs[1]))),
            "excursion_m": float(np.max(np.ptp(pos[0], axis=0)))}


def figure(turn: dict, path):
    """Plan view of the turn (tow point and body) and the body's distance from the steady turn."""
    import matplotlib.pyplot as plt
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(12, 5))
    a0.plot(turn["track_x_m"], turn["track_z_m"], "k-", lw=1.3, label="tow point (track)")
    a0.plot(turn["body_x_m"], turn["body_z_m"], "-", color="C0", lw=1.2, label="body")
    a0.plot([turn["track_x_m"][0]], [turn["track_z_m"][0]], "ks", ms=6, label="tow point at t = 0")
    a0.set_aspect("equal", adjustable="datalim")
    a0.set(xlabel="x (m)", ylabel="z (m, seen from above)",
           title=f"a {turn['turn_deg']:g} deg turn to port, R = {turn['radius_m']:g} m at {turn['speed_m_s']:g} m/s")
    a0.grid(alpha=0.3)
    a0.legend(fontsize=8, loc="best")
    t, d = np.array(turn["time_s"]), np.array(turn["distance_m"])
    a1.semilogy(t, np.maximum(d, 1e-12), color="C0")
    a1.set(xlabel="time (s)", ylabel="body's distance from the steady turn's place (m)",
           title=f"from the straight tow ({turn['start_distance_m']:.1f} m off) to the steady turn\n"
                 f"({turn['rel_err']:.1e} of the line's length at the end)")
    a1.title.set_fontsize(10)
    a1.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
