"""The quasi-static rungs (:mod:`cablesys.model.quasistatic`) in three dimensions: the checks of
``studies/three_d_checks.py`` for them, beside Wang's straight cable's and the node model's.

- :func:`planar_equivalence`: planar scenes (Wang's straight cable, N = 1, and the segmented cable in element
  coordinates, N = 3) run by the 3-D quasi-static equations (``numerics.dimensions = 3``: both angles of every element
  slow) against the planar quasi-static equations, from the same start over the same fixed RK4 steps: the states
  absolute, the outputs normwise;
- :func:`rotation_invariance`: a 3-D scene (a current turning with depth, a wave with a heading, surge + sway +
  heave) and the same scene turned about the vertical, the quasi-static segmented cable over the same fixed steps:
  the body's path turns, the tensions and the stretch are equal;
- :func:`conical_pendulum`: a sphere on a stiff massless cable started on the cone of half-angle theta with omega^2 =
  g / (L cos theta), on the quasi-static straight cable (Wang's 3-D cable with its stretch following the tension
  W / cos theta): the measured rate, length and cone angle against the closed form, the radius' wander, the body-end
  tension against W / cos theta.
"""

from __future__ import annotations

import math

import numpy as np

import _three_d_nodes as nodes
import three_d_checks as checks
from cablesys.model import build_model
from cablesys.model.quasistatic import build_quasistatic
from cablesys.scene import Numerics
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.run import simulate


def planar_equivalence(quick: bool, elements=(1, 3)) -> dict:
    """Largest differences between the planar quasi-static equations and the 3-D ones forced on a planar scene (a
    cylinder in a sheared current and a wave, surge and heave), started swinging (0.1 rad/s per angle)."""
    cases, worst_abs, worst_rel = {}, 0.0, 0.0
    for n in elements:
        run = nodes.divided(checks.planar_scenes()[0], n).with_numerics(duration=1.5 if quick else 10.0,
                                                                         steps_per_output=20)
        m2, m3 = build_quasistatic(run), build_quasistatic(run.with_numerics(dimensions=3))
        x0 = initial_state(run, m2, m2.parameters(run))
        x0[m2.nq:] += 0.1
        r2 = simulate(run, model=m2, method="rk", x0=x0)
        r3 = simulate(run.with_numerics(dimensions=3), model=m3, method="rk", x0=checks._as_3d(m2, m3, x0))
        # the states (angles rad, rates rad/s) absolute; every output normwise, max|a - b| / max(max|a|, 1): a tension
        # is the stretch's constraint force, the states' rounding (1e-14 rad) times the element stiffness
        labels = [lb for lb in m2.output_labels if lb in r2.data and "tension_rate" not in lb]
        idx = [m3.q_labels.index(lb) for lb in m2.q_labels]
        d_abs = float(np.max(np.abs(np.asarray(r2.states) - np.asarray(r3.states)[idx + [m3.nq + i for i in idx]])))
        d_rel = max(float(np.max(np.abs(np.asarray(r2[lb]) - np.asarray(r3[lb])))
                          / max(float(np.max(np.abs(np.asarray(r2[lb])))), 1.0)) for lb in labels)
        out = max(float(np.max(np.abs(np.asarray(r3[lb])))) for lb in ("z_b", "phi_z"))
        cases[f"N={n}"] = {"run_max_abs": d_abs, "run_max_rel": d_rel, "run_out_of_plane_max_abs": out,
                           "body_excursion_m": max(float(np.ptp(np.asarray(r2[k]))) for k in ("x_b", "y_b")),
                           "planar_q_labels": list(m2.q_labels[:3]), "three_d_q_labels": list(m3.q_labels[:3]),
                           "planar_exogenous": int(m2.top.size1_out(0))}
        worst_abs, worst_rel = max(worst_abs, d_abs, out), max(worst_rel, d_rel)
    return {"run_max_abs": worst_abs, "max_rel": worst_rel, "cases": cases}


def rotation_invariance(quick: bool, alpha: float = math.radians(50.0), n_el: int = 2) -> dict:
    """Largest difference between the quasi-static segmented cable's answer turned by ``alpha`` and the turned scene's."""
    sc = nodes.divided(checks.rotation_scene(), n_el).with_numerics(duration=2.0 if quick else 20.0, steps_per_output=20)
    sr = checks.rotated_scene(sc, alpha)
    r = simulate(sc, model=build_quasistatic(sc), method="rk")
    rr = simulate(sr, model=build_quasistatic(sr), method="rk")
    pos = np.vstack([np.asarray(r[k]) for k in ("x_b", "y_b", "z_b")])
    pos_r = np.vstack([np.asarray(rr[k]) for k in ("x_b", "y_b", "z_b")])
    turned = np.array([checks.rotate(alpha, c) for c in pos.T]).T
    scal = max(float(np.max(np.abs(np.asarray(r[k]) - np.asarray(rr[k]))) / np.max(np.abs(np.asarray(r[k]))))
               for k in ("tension_top", "tension_bottom", "u"))
    return {"run_position_max_abs_m": float(np.max(np.abs(turned - pos_r))), "run_scalars_max_rel": scal,
            "alpha_deg": math.degrees(alpha), "elements": n_el, "body_excursion_m": float(np.max(np.ptp(pos, axis=1))),
            "sway_excursion_m": float(np.ptp(pos[2]))}


def conical_pendulum(alpha_deg: float = 30.0, revolutions: int = 3) -> dict:
    """The conical pendulum on the quasi-static straight cable (module docstring)."""
    alpha = math.radians(alpha_deg)
    sc = checks.pendulum_scene(numerics=Numerics(duration=1.0, output_step=0.02, model="as-built", dimensions=3))
    qs = build_quasistatic(sc)
    x_full, omega, _ = checks.conical_initial_state(build_model(sc), sc, alpha)
    x0 = np.array([alpha, 0.0, 0.0, x_full[-2]])                  # (phi, phi_z, phi', phi_z')
    r = simulate(sc.with_numerics(duration=revolutions * 2 * math.pi / omega), model=qs, x0=x0, rtol=1e-11, atol=1e-11)
    x, y, z = (np.asarray(r[k]) for k in ("x_b", "y_b", "z_b"))
    rad, length = np.hypot(x, z), np.sqrt(x**2 + y**2 + z**2)
    cone = np.arctan2(rad, y)
    rate = np.polyfit(np.asarray(r.time), np.unwrap(np.arctan2(z, x)), 1)[0]
    g = sc.body.weight / sc.body.mass_x
    return {"q_labels": list(qs.q_labels), "rel_err_omega2": float(abs(rate**2 * np.mean(length) * math.cos(np.mean(cone)) / g - 1)),
            "radius_rel_wander": float(np.ptp(rad) / np.mean(rad)),
            "cone_angle_err_rad": float(abs(np.mean(cone) - alpha)),
            "tension_rel_err": float(np.max(np.abs(np.asarray(r["tension_bottom"]) * math.cos(alpha) / sc.body.weight - 1))),
            "alpha_deg": alpha_deg, "revolutions": revolutions}
