"""Towing in a circle: the steady turn against a long run of the node model started off it (from rest under the
tow point), for studies/three_d_checks.py."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import tomllib

import cablesys
from cablesys.model import build_model
from cablesys.scene import scene_from_dict
from cablesys.statics.catenary import segmented_steady
from cablesys.statics.turning import turning_initial_state

TOW = """
name = "towing in a circle: 60 m of 20 mm wire and a 3 kN body, 80 m radius at 2 m/s"
[cable]
length = 60.0
ae = 4.0e7
diameter = 0.02
mass_per_length = 1.5
weight_per_length = 12.0
cd_normal = 1.5
segments = 6
[body]
weight = 3000.0
mass_x = 500.0
mass_y = 500.0
mass_z = 500.0
drag_area_normal = 0.5
drag_area_tangential = 0.5
axis_angle_deg = 999.0
[top_motion.track]
radius = 80.0
speed = 2.0
"""


def turning_check(revolutions: float = 3.0, segments: int = 6) -> dict:
    """The body's place in the turning frame after ``revolutions`` turns of a run started at rest under the tow
    point (the hanging shape, every node with the tow point's velocity), against the steady turn: the largest
    difference of (x, y, z) over the line's length."""
    sc = scene_from_dict(tomllib.loads(TOW.replace("segments = 6", f"segments = {segments}")))
    w = sc.top_motion.track.turn_rate
    duration = revolutions * 2 * math.pi / abs(w)
    sc = dataclasses.replace(sc, numerics=dataclasses.replace(sc.numerics, duration=duration, output_step=1.0,
                                                             rtol=1e-8, atol=1e-8))
    model = build_model(sc)
    p = model.parameters(sc)
    steady = turning_initial_state(sc, model, p)
    e = np.array(model.top(0.0, p)).ravel()
    hang = segmented_steady(model, p).q.reshape(-1, 3) + e[1:4]
    x0 = np.concatenate([hang.ravel(), np.tile(e[4:7], len(hang))])
    res = cablesys.simulate(sc, model="segmented", segments=segments, x0=x0)
    t = np.asarray(res.time)
    xb, yb, zb = (np.asarray(res[k]) for k in ("x_b", "y_b", "z_b"))
    c, s = np.cos(w * t), np.sin(w * t)
    back = np.column_stack([c * xb + s * zb, yb, -s * xb + c * zb])
    target = steady[:model.nq].reshape(-1, 3)[-1]
    dist = np.linalg.norm(back - target, axis=1)
    length = sc.sections[0].cable.length
    return {"scene": sc.name, "revolutions": revolutions, "segments": segments, "turn_rate_rad_s": w,
            "steady_body_m": target.tolist(), "run_body_end_m": back[-1].tolist(),
            "start_distance_m": float(dist[0]), "end_distance_m": float(dist[-1]),
            "rel_err": float(dist[-1] / length), "time_s": t.tolist(), "distance_m": dist.tolist()}


def steady_shape(segments: int = 6) -> dict:
    """The steady turn's node positions (m, from the circle's centre) and the tow circle, for the plan view."""
    sc = scene_from_dict(tomllib.loads(TOW.replace("segments = 6", f"segments = {segments}")))
    model = build_model(sc)
    p = model.parameters(sc)
    e = np.array(model.top(0.0, p)).ravel()
    q = turning_initial_state(sc, model, p)[:model.nq].reshape(-1, 3)
    return {"nodes_m": np.vstack([e[1:4], q]).tolist(), "radius_m": sc.top_motion.track.radius}


def figure(check: dict, shape: dict, path):
    """Plan view of the steady turn (tow circle, body circle, the line) and the run's distance from it."""
    import matplotlib.pyplot as plt
    nodes = np.array(shape["nodes_m"])
    R = shape["radius_m"]
    body = nodes[-1]
    rb = float(np.hypot(body[0], body[2]))
    th = np.linspace(0, 2 * np.pi, 400)
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(12, 5))
    a0.plot(R * np.cos(th), R * np.sin(th), color="0.6", lw=1, label=f"tow circle R = {R:g} m")
    a0.plot(rb * np.cos(th), rb * np.sin(th), color="C0", lw=1, ls="--", label=f"body's circle r = {rb:.1f} m")
    a0.plot(nodes[:, 0], nodes[:, 2], "o-", color="C3", ms=3, label="line in the steady turn (plan)")
    a0.annotate("tow point", nodes[0, [0, 2]], textcoords="offset points", xytext=(6, -12))
    a0.annotate("", xy=(R * 0.25, -R * 0.97), xytext=(0, -R), arrowprops=dict(arrowstyle="->", color="0.3"))
    a0.set_aspect("equal")
    a0.set_xlabel("x [m]")
    a0.set_ylabel("z [m] (seen from above)")
    a0.set_title(f"steady turn, plan view (body {body[1]:.1f} m deep, {-body[0]:.1f} m behind the tow point)", fontsize=9)
    a0.legend(fontsize=8, loc="upper right")
    a0.grid(alpha=0.3)
    t, d = np.array(check["time_s"]), np.array(check["distance_m"])
    a1.semilogy(t, np.maximum(d, 1e-12), color="C0")
    a1.set_xlabel("time [s]")
    a1.set_ylabel("body's distance from the steady turn [m]")
    a1.set_title(f"a run started at rest under the tow point: {check['start_distance_m']:.1f} m off, "
                 f"{check['end_distance_m']:.2g} m after {check['revolutions']:g} turns", fontsize=9)
    a1.grid(alpha=0.3, which="both")
    fig.suptitle(check["scene"], fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
