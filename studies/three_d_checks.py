"""Wang's straight cable in three dimensions (Wang 1971 p. 32, "Extensions"): the checks, as numbers.

Writes ``DIR/three_d_checks.json`` (each value the largest error over its cases) and
``DIR/three_d_conical_pendulum.png``:

- ``planar_equivalence_max_abs``: planar scenes run by the 3-D equations (``numerics.dimensions =
  3``) against today's planar equations: the largest difference of any planar output (m, rad, N,
  m/s) over a fixed-step run (the same steps in both: the difference is the equations', not the
  integrator's); ``planar_equivalence_max_rel`` the largest normwise relative difference
  max|a - b| / max(max|a|, 1) of the right-hand side and of the outputs at random states with the
  out-of-plane angle 0, and of the runs (the componentwise one is in the details: the solve of
  M q'' = f rounds differently for a 4x4 and a 3x3 system, cond(M) ~ 5e4 in the shared chain);
- ``rotation_invariance_max_abs``: a 3-D scene (current with a heading, waves with a heading, top
  surge + sway + heave) and the same scene turned by 35 degrees about the vertical: body position
  and velocity of one turned by the rotation, stretch, depth and tensions equal; at random states
  (the rotated state mapped through the angles) and over a run at tight tolerance;
- ``conical_pendulum_rel_err``: a stiff massless cable and a heavy sphere started on the cone of
  half-angle alpha with omega^2 = g / (L cos alpha): the measured |omega^2 L cos alpha / g - 1|, L and
  alpha measured over the run, and the radius' relative wander;
- ``energy_drift_rel``: no drag, no damping, the top at rest, a 3-D swing (cable mass, added mass,
  elastic stretch): max |E - E_0| over 100 pendulum periods relative to the energy of the motion
  (E_0 minus the energy at rest);
- ``out_of_plane_frequency_rel_err``: the linearization of the 3-D model of a symmetric scene
  (sphere, M_bvz = M_bvx): out-of-plane pendulum frequency against the in-plane one of the planar
  model; ``out_of_plane_rao_rel_err``: the RAO of z_b to the top's sway z_s against the planar
  model's x_b to x_s at five frequencies off resonance.

The quasi-static rungs (Wang's 3-D cable and the segmented cable in element coordinates, the stretches following the
tension: ``studies/_three_d_quasistatic.py``, numbers under ``details.quasi_static``) add their planar equivalence (states
absolute, outputs normwise), rotation invariance and conical pendulum to the first three keys.

The node model (segmented cable, N elements, nodes (x, y, z): ``studies/_three_d_nodes.py``) adds its
cases to the first keys, each the largest over Wang's and the node model's cases (the node model's numbers
are under ``details.node_model``): planar equivalence (its states absolute, its outputs normwise),
rotation invariance, energy drift; and

- ``chain_out_of_plane_mode_rel_err``: the hanging chain's out-of-plane modes (3-D node model, linearized)
  against its in-plane ones (planar node model), the three lowest, at every N; against the continuous
  chain's Bessel-J0 frequencies in ``chain_out_of_plane_vs_bessel_rel_err`` (finest N) with the observed
  order of convergence in the details.

The towed cable (``studies/towed_nonlinear.py``, :mod:`cablesys.towed.nodes`): 3-D node model of Kennedy &
Strahan's (1981) cable, towed in a current past a fixed tow point that sways:

- ``towed_linear_vs_theory_max_rel_err``: linearized about the straight tow (AD Jacobian, the theory's
  equivalent linear normal drag c_n* = A C_n, eq. 38-39), |H(1)| and c*(1) at omega L/U = 1, 3, 8 against
  ``towed/``'s exact solution of eq. 3 with the node model's coefficients (finest N; the difference of those
  from the report's coefficients is ``details.towed.linear_vs_theory.model_form_vs_report_coefficients_max_rel``);
- ``towed_sea_trials``: mean |model - measured| of |H| and c* over Table A-2 (quick: runs 1, 6, 20), the
  nonlinear node model in the time domain (quadratic normal drag, C_n = 0.16) and the linear theory.

Towing in a circle (``studies/_turning.py``, :mod:`cablesys.statics.turning`):
``turning_tow_steady_vs_time_domain_rel_err``, the body's distance from the steady turn (in the turning
frame) after a node-model run started at rest under the tow point (quick 1.5 turns, full 4), over the
line's length; figure ``three_d_turning_tow.png``.

``span_out_of_plane_vs_irvine_rel_err``: a span between two supports (Griffin & Rosenthal's Table 2 cable
with 1 - l/L = 4e-4, sag 2.6 % of the span) on the node model (``cablesys.slack``'s shared cable,
Richardson over N = 24, 48, 96): its four lowest sway modes against Irvine's string frequencies
(n pi / l) sqrt(H / m).

``rigid_body_momentum_drift_rel`` (``studies/_three_d_rigid.py``, :mod:`cablesys.model.rigid_body`): a free
asymmetric body tumbling about its intermediate axis, with and without added mass (quick: with), 100 s: the
largest relative drift of Kirchhoff's linear and angular impulse and of the kinetic energy.

The pitching rigid body is a case of ``planar_equivalence_max_abs`` and ``_max_rel`` (``_three_d_rigid.
planar_equivalence``): its planar scene against the 3-D equations at random states, the pitch mapped to its
quaternion (node accelerations, the quaternion's a'' against the planar theta'', outputs). Its run cannot take the
same fixed steps in both (theta and the quaternion are different coordinates, so RK4 discretizes them differently):
each model on its own CVODES-Adams steps at rtol 1e-12, the largest normwise difference of the pitch, the CG, the
attachment point and the tensions is ``planar_equivalence_rigid_run_max_rel``.

A towing ship's manoeuvres (``studies/_tracks.py``, :mod:`cablesys.scene.track`, :mod:`cablesys.statics.tow`):

- ``straight_track_vs_system_speed_max_rel``: a straight track at 2 m/s in still water against the same scene
  towed in the ship's frame (``environment.system_speed``), both released from the steady tow at 1 m/s, a cable
  without added mass: the body's position and velocity relative to the tow point and the tensions (the largest
  normwise difference, the same fixed RK4 steps; Galilean invariance); with the cable's added mass the frames'
  difference (the Munk couples) in the details (tests/test_tracks.py also runs CVODES on its own steps);
- ``straight_track_munk_couple_rel_err``: that difference of the forces at one shape against the closed form of
  the elements' Munk couples (Newman 1977 sec. 4.13);
- ``turn_settles_on_steady_turn_rel_err``: a turn to port from the steady straight tow (quick 450 deg, full 720)
  against the steady turn of the circle of the same radius and speed (:mod:`cablesys.statics.turning`): the
  body's distance from the steady turn's place relative to the tow point, over the line's length; figure
  ``three_d_tracks.png``;
- a zig-zag on base courses 0 and 35 deg (the same fixed RK4 steps) is a case of ``rotation_invariance_max_abs`` and
  ``_scalars_max_rel``.

Keys of the issue's list that these steps do not compute are ``null`` and named in ``not_built``.

Usage: python studies/three_d_checks.py --out DIR [--quick]
"""

from __future__ import annotations

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402
import _three_d_nodes as nodes  # noqa: E402
import _three_d_quasistatic as quasistatic  # noqa: E402
import _three_d_rigid as rigid  # noqa: E402
import _tracks as tracks  # noqa: E402
import _turning as turning  # noqa: E402
import slack_tables  # noqa: E402
import towed_nonlinear as towed  # noqa: E402

from cablesys.linear.frequency_response import rao  # noqa: E402
from cablesys.linear.linearization import linearize  # noqa: E402
from cablesys.linear.modal import modes  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.scene import (  # noqa: E402
    Body,
    Cable,
    Environment,
    Numerics,
    Section,
    Scene,
    Sinusoid,
    TopMotion,
    Wave,
    single_section_scene,
)
from cablesys.statics.steady import steady_state  # noqa: E402
from cablesys.time_domain.run import simulate  # noqa: E402

NOT_BUILT = ()
PLANAR_OUTPUTS = ("phi", "phi_rate", "u", "u_rate", "x_b", "x_b_rate", "y_b", "y_b_rate", "tension_mid",
                  "tension_bottom", "tension_top")


# ---------------------------------------------------------------------------------------- scenes
def wire(**kw) -> Cable:
    """A 60 m steel wire rope of 24 mm (in water 18 N/m)."""
    base = dict(length=60.0, ae=4.0e7, diameter=0.024, mass_per_length=2.4, weight_per_length=18.0,
                cd_normal=1.5, ct_tangential=0.01)
    return Cable(**{**base, **kw})


def planar_scenes() -> list:
    """Planar scenes of every kind of section the planar equations know: one section with a cylinder
    body, a sheared current and a wave; a chain of two with a sphere; the shared-angle chain."""
    cyl = Body(weight=8000.0, mass_x=1500.0, mass_y=1800.0, drag_area_normal=2.0, drag_area_tangential=0.8,
               axis_angle_deg=10.0)
    sph = Body(weight=4000.0, mass_x=700.0, mass_y=700.0, drag_area_normal=1.0, drag_area_tangential=1.0)
    env = Environment(current_depths=(0.0, 40.0, 100.0), current_speeds=(0.8, 0.5, 0.1),
                      waves=(Wave(amplitude=1.0, length=120.0, phase=0.3),))
    top = TopMotion(x=(Sinusoid(amplitude=1.2, frequency=0.6),), y=(Sinusoid(amplitude=0.9, frequency=0.6, phase=0.4),))
    num = Numerics(duration=20.0, output_step=0.1, model="as-built")
    one = single_section_scene(cable=wire(internal_damping=2e4), body=cyl, environment=env, top_motion=top,
                               numerics=num, name="one")
    two = Scene(sections=(Section(cable=wire(), body=sph), Section(cable=wire(length=30.0), body=cyl)),
                environment=env, top_motion=top, numerics=num, name="chain")
    shared = dataclasses.replace(two, angles="shared", name="shared")
    return [one, two, shared]


def pendulum_scene(*, length=20.0, ae=1e10, weight=9.80665e4, mass=1e4, drag=0.0, cable_mass=False, **kw) -> Scene:
    """A sphere on one straight cable, no current: the symmetric 3-D scene of the checks."""
    cable = wire(length=length, ae=ae, mass_per_length=2.4 if cable_mass else 0.0,
                 weight_per_length=18.0 if cable_mass else 0.0, cd_normal=1.5 if drag else 0.0,
                 ct_tangential=0.01 if drag else 0.0, cable_mass_switch=1.0 if cable_mass else -1.0)
    body = Body(weight=weight, mass_x=mass, mass_y=mass, mass_z=mass, drag_area_normal=drag, drag_area_tangential=drag)
    return single_section_scene(cable=cable, body=body, **kw)


# ------------------------------------------------------------------------------ planar equivalence
def _states(model, rng, n):
    """Random states of ``model`` (angles within 0.5 rad, stretches near the hanging one, rates O(0.3))."""
    out = []
    for _ in range(n):
        q = [rng.uniform(-0.5, 0.5) if lbl.startswith("phi") else rng.uniform(0.005, 0.02) for lbl in model.q_labels]
        out.append(np.concatenate([q, rng.normal(scale=0.3, size=model.nq)]))
    return out


def _as_3d(model2, model3, x2):
    """The 3-D state of a planar one: phi_z = 0 and its rate 0."""
    x3 = np.zeros(2 * model3.nq)
    for k, lbl in enumerate(model3.q_labels):
        if lbl in model2.q_labels:
            j = model2.q_labels.index(lbl)
            x3[k], x3[model3.nq + k] = x2[j], x2[model2.nq + j]
    return x3


def planar_equivalence(quick: bool) -> dict:
    """Largest differences between the planar equations and the 3-D ones forced on planar scenes."""
    rng = np.random.default_rng(7)
    worst_abs, worst_rel, cases = 0.0, 0.0, {}
    for sc in planar_scenes():
        sc3 = sc.with_numerics(dimensions=3)
        m2, m3 = build_model(sc), build_model(sc3)
        p2, p3 = m2.parameters(sc), m3.parameters(sc3)
        names = [m2.output_labels.index(lb) for lb in m2.output_labels]
        rows3 = [m3.output_labels.index(lb) for lb in m2.output_labels]
        d_abs = d_rel = d_comp = 0.0
        for x2 in _states(m2, rng, 4 if quick else 20):
            x3 = _as_3d(m2, m3, x2)
            for t in (0.0, 7.3, 30.0):
                f2 = np.array(m2.ode(x2, t, p2)).ravel()
                f3 = np.array(m3.ode(x3, t, p3)).ravel()
                f3p = _as_3d_inverse(m2, m3, f3)
                y2 = np.array(m2.outputs(x2, m2.top(t, p2), p2)).ravel()[names]
                y3 = np.array(m3.outputs(x3, m3.top(t, p3), p3)).ravel()[rows3]
                for a, b in ((f2, f3p), (y2, y3)):
                    d_abs = max(d_abs, float(np.max(np.abs(a - b))))
                    # normwise: the round-off of the solve M q'' = f (a 4x4 against a 3x3 system in the
                    # shared chain, cond(M) ~ 5e4) is bounded normwise, not for its smallest entries
                    d_rel = max(d_rel, float(np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1.0)))
                    d_comp = max(d_comp, float(np.max(np.abs(a - b) / np.maximum(np.abs(a), 1.0))))
                # out of the plane nothing moves: phi_z'' = 0 and z_b = 0
                d_abs = max(d_abs, float(np.max(np.abs(f3[[m3.nq + k for k, lb in enumerate(m3.q_labels)
                                                           if lb.startswith("phi_z")]]))))
        run = sc.with_numerics(duration=4.0 if quick else 20.0)
        r2 = simulate(run, model=m2, method="rk")
        r3 = simulate(run.with_numerics(dimensions=3), model=m3, method="rk")
        run_abs = max(float(np.max(np.abs(np.asarray(r2[lb]) - np.asarray(r3[lb])))) for lb in m2.output_labels)
        run_rel = max(float(np.max(np.abs(np.asarray(r2[lb]) - np.asarray(r3[lb]))
                                  / np.maximum(np.abs(np.asarray(r2[lb])), 1.0))) for lb in m2.output_labels)
        run_out = max(float(np.max(np.abs(np.asarray(r3[lb])))) for lb in m3.output_labels if lb.startswith(("z_b", "phi_z")))
        cases[sc.name] = {"equations_max_abs": d_abs, "equations_max_rel": d_rel,
                          "equations_max_rel_componentwise": d_comp, "run_max_abs": run_abs,
                          "run_max_rel": run_rel, "run_out_of_plane_max_abs": run_out,
                          "planar_q_labels": list(m2.q_labels), "three_d_q_labels": list(m3.q_labels)}
        worst_abs = max(worst_abs, run_abs, run_out)
        worst_rel = max(worst_rel, d_rel, run_rel)
    return {"run_max_abs": worst_abs, "max_rel": worst_rel, "cases": cases}


def _as_3d_inverse(model2, model3, v3):
    """The planar entries of a 3-D state (or state rate) vector, in the planar model's order."""
    idx = [model3.q_labels.index(lbl) for lbl in model2.q_labels]
    return np.concatenate([v3[idx], v3[[model3.nq + k for k in idx]]])


# ------------------------------------------------------------------------------ rotation about y
def rotate(alpha: float, v):
    """A vector (x, y, z) turned by ``alpha`` (rad) about the vertical y, from +x towards +z."""
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([c * v[0] - s * v[2], v[1], s * v[0] + c * v[2]])


def _rotated_motion(top: TopMotion, alpha: float) -> TopMotion:
    """The top motion turned by ``alpha``: x' = x cos a - z sin a, z' = x sin a + z cos a (sinusoid terms)."""
    c, s = math.cos(alpha), math.sin(alpha)
    scale = lambda terms, f: tuple(dataclasses.replace(t, amplitude=f * t.amplitude) for t in terms)
    return dataclasses.replace(top, x=scale(top.x, c) + scale(top.z, -s), z=scale(top.x, s) + scale(top.z, c))


def rotated_scene(sc: Scene, alpha: float) -> Scene:
    """``sc`` turned by ``alpha`` (rad) about the vertical: current, wave headings and the top motion."""
    env = sc.environment
    deg = math.degrees(alpha)
    env = dataclasses.replace(env, current_headings_deg=tuple(h + deg for h in env.headings_per_depth_deg),
                              waves=tuple(dataclasses.replace(w, heading_deg=(w.heading_deg or 0.0) + deg)
                                          for w in env.waves))
    return dataclasses.replace(sc, environment=env, top_motion=_rotated_motion(sc.top_motion, alpha))


def rotation_scene() -> Scene:
    """A 3-D scene: a sheared current turning with depth, a wave at 20 degrees, surge + sway + heave."""
    env = Environment(current_depths=(0.0, 30.0, 80.0), current_speeds=(0.9, 0.6, 0.3),
                      current_headings_deg=(10.0, 40.0, 80.0), waves=(Wave(amplitude=0.8, length=100.0, heading_deg=20.0),))
    top = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=0.7),), y=(Sinusoid(amplitude=0.8, frequency=0.7, phase=0.5),),
                    z=(Sinusoid(amplitude=0.6, frequency=0.5, phase=1.0),))
    body = Body(weight=6000.0, mass_x=900.0, mass_y=1100.0, mass_z=900.0, drag_area_normal=1.5,
                drag_area_tangential=0.6, axis_angle_deg=0.0)        # a vertical cylinder: symmetric about y
    top = dataclasses.replace(top, ramp_s=2.0)
    return single_section_scene(cable=wire(internal_damping=1e4), body=body, environment=env, top_motion=top,
                                numerics=Numerics(duration=20.0, output_step=0.1, model="as-built"), name="turned")


def _angles_of(e_t, de_t):
    """(phi, phi_z) and their rates of the cable tangent e_t and its rate (the 3-D frame of model/section.py)."""
    th = math.asin(e_t[2])
    ph = math.atan2(-e_t[0], e_t[1])
    e_n = np.array([-math.cos(ph), -math.sin(ph), 0.0])
    e_b = np.array([math.sin(ph) * math.sin(th), -math.cos(ph) * math.sin(th), math.cos(th)])
    return ph, th, float(de_t @ e_n) / math.cos(th), float(de_t @ e_b)


def _tangent(ph, th, phd, thd):
    e_t = np.array([-math.sin(ph) * math.cos(th), math.cos(ph) * math.cos(th), math.sin(th)])
    de = phd * np.array([-math.cos(ph) * math.cos(th), -math.sin(ph) * math.cos(th), 0.0]) + thd * np.array(
        [math.sin(ph) * math.sin(th), -math.cos(ph) * math.sin(th), math.cos(th)])
    return e_t, de


def _rotate_exo(e, alpha):
    """e = (t, r, v, a) of the top turned by alpha."""
    return np.concatenate([[e[0]], rotate(alpha, e[1:4]), rotate(alpha, e[4:7]), rotate(alpha, e[7:10])])


def rotation_invariance(quick: bool, alpha: float = math.radians(35.0)) -> dict:
    """Largest difference between a scene's answer turned by ``alpha`` and the turned scene's answer."""
    sc = rotation_scene()
    sr = rotated_scene(sc, alpha)
    m, mt = build_model(sc), build_model(sr)       # the turned top motion has more sinusoid terms
    p, pr = m.parameters(sc), mt.parameters(sr)
    lab = m.output_labels
    vec = lambda y, name: np.array([y[lab.index(f"{ax}{name}")] for ax in ("x_b", "y_b", "z_b")])
    scalars = [lab.index(n) for n in ("u", "u_rate", "tension_mid", "tension_bottom", "tension_top")]
    rng = np.random.default_rng(3)
    worst = worst_rel = 0.0          # vectors (m, m/s, top e): absolute; scalars (u, tensions, u''): relative
    for _ in range(4 if quick else 20):
        ph, th, u = rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6), rng.uniform(0.005, 0.02)
        phd, thd, ud = rng.normal(scale=0.3, size=3)
        e_t, de = _tangent(ph, th, phd, thd)
        ph2, th2, phd2, thd2 = _angles_of(rotate(alpha, e_t), rotate(alpha, de))
        x, xr = np.array([ph, th, u, phd, thd, ud]), np.array([ph2, th2, u, phd2, thd2, ud])
        for t in (0.0, 5.1, 23.0):
            e = np.array(m.top(t, p)).ravel()
            er = np.array(mt.top(t, pr)).ravel()
            worst = max(worst, float(np.max(np.abs(_rotate_exo(e, alpha) - er))))
            y, yr = np.array(m.outputs(x, e, p)).ravel(), np.array(mt.outputs(xr, er, pr)).ravel()
            worst_rel = max(worst_rel, float(np.max(np.abs(y[scalars] - yr[scalars]) / np.maximum(np.abs(y[scalars]), 1.0))))
            for name in ("", "_rate"):
                worst = max(worst, float(np.max(np.abs(rotate(alpha, vec(y, name)) - vec(yr, name)))))
            # the stretch acceleration u'' is the same (the tensions above hold the other accelerations)
            f, fr = np.array(m.ode(x, t, p)).ravel(), np.array(mt.ode(xr, t, pr)).ravel()
            worst_rel = max(worst_rel, abs(f[5] - fr[5]) / max(abs(f[5]), 1.0))
    # over a run: the first scene's positions turned against the turned scene's
    dur = 8.0 if quick else 30.0
    r = simulate(sc.with_numerics(duration=dur), model=m, rtol=1e-12, atol=1e-12)
    rr = simulate(sr.with_numerics(duration=dur), model=mt, rtol=1e-12, atol=1e-12)
    pos = np.vstack([np.asarray(r[n]) for n in ("x_b", "y_b", "z_b")])
    pos_r = np.vstack([np.asarray(rr[n]) for n in ("x_b", "y_b", "z_b")])
    run_pos = float(np.max(np.abs(np.array([rotate(alpha, c) for c in pos.T]).T - pos_r)))
    run_t = max(float(np.max(np.abs(np.asarray(r[n]) - np.asarray(rr[n])) / np.max(np.abs(np.asarray(r[n])))))
                for n in ("tension_mid", "tension_top", "tension_bottom"))
    return {"equations_max_abs": worst, "equations_scalars_max_rel": worst_rel, "run_position_max_abs_m": run_pos, "run_tension_max_rel": run_t,
            "alpha_deg": math.degrees(alpha), "run_rtol": 1e-12,
            "body_excursion_m": float(np.max(np.ptp(pos, axis=1)))}


# ------------------------------------------------------------------------------ conical pendulum
def conical_initial_state(model, sc: Scene, alpha: float):
    """x0 on the cone of half-angle ``alpha``: phi = alpha, phi_z = 0, the stretch of the cone's tension
    T = W_b / cos alpha, and the body moving in +z at omega L sin alpha, omega^2 = (W_b / M_b) / (L cos alpha)."""
    c, b = sc.cable, sc.body
    u = b.weight / math.cos(alpha) / c.spring_constant
    L = c.length_zero + u
    omega = math.sqrt(b.weight / b.mass_x / (L * math.cos(alpha)))
    x0 = np.zeros(2 * model.nq)
    x0[model.q_labels.index("phi")] = alpha
    x0[model.q_labels.index("u")] = u
    x0[model.nq + model.q_labels.index("phi_z")] = omega * math.sin(alpha)
    return x0, omega, L


def conical_pendulum(quick: bool, alpha_deg=(15.0, 30.0, 50.0), omega_factor: float = 1.0) -> dict:
    """Relative error of omega^2 L cos(alpha) / g measured on steady conical motion, per cone angle.

    ``omega_factor`` scales the initial rate (1: the closed form; another value starts off the cone's
    steady state, which the radius' wander shows)."""
    out, worst, runs = {}, 0.0, {}
    for a in (alpha_deg[1:2] if quick else alpha_deg):
        alpha = math.radians(a)
        sc = pendulum_scene(numerics=Numerics(duration=1.0, output_step=0.02, model="as-built", dimensions=3))
        m = build_model(sc)
        x0, omega, L0 = conical_initial_state(m, sc, alpha)
        x0[m.nq:] *= omega_factor
        period = 2 * math.pi / omega
        n_rev = 3 if quick else 10
        r = simulate(sc.with_numerics(duration=n_rev * period), model=m, x0=x0, rtol=1e-11, atol=1e-11)
        x, y, z = (np.asarray(r[n]) for n in ("x_b", "y_b", "z_b"))
        t = np.asarray(r.time)
        rad = np.hypot(x, z)
        L = np.sqrt(x**2 + y**2 + z**2)
        cone = np.arctan2(rad, y)
        az = np.unwrap(np.arctan2(z, x))
        w_meas = np.polyfit(t, az, 1)[0]
        g = sc.body.weight / sc.body.mass_x
        err = abs(w_meas**2 * np.mean(L) * math.cos(np.mean(cone)) / g - 1.0)
        wander = float(np.ptp(rad) / np.mean(rad))
        # the cone's tension, T = W_b / cos(alpha) at both ends of the massless cable and as k u
        t_cone = sc.body.weight / math.cos(alpha)
        t_err = max(float(np.max(np.abs(np.asarray(r[n]) / t_cone - 1.0))) for n in ("tension_mid", "tension_top", "tension_bottom"))
        out[f"{a:g}"] = {"omega_closed_form": omega, "omega_measured": float(abs(w_meas)), "rel_err_omega2": float(err),
                         "radius_rel_wander": wander, "tension_rel_err": t_err, "cone_angle_deg_mean": math.degrees(float(np.mean(cone))),
                         "revolutions": n_rev}
        worst = max(worst, float(err), wander, t_err)
        runs[a] = (t, x, y, z)
    return {"max_rel_err": worst, "cases": out, "_runs": runs}


# ------------------------------------------------------------------------------ energy
def chain_scene(angles: str = "per_section") -> Scene:
    """Two sections (a 20 m and a 10 m cable, each with a body), no drag or damping, forced 3-D."""
    one = pendulum_scene(ae=2e6, weight=2e4, mass=3000.0, cable_mass=True)
    low = Section(cable=dataclasses.replace(one.cable, length=10.0),
                  body=dataclasses.replace(one.body, weight=8e3, mass_x=1000.0, mass_y=1000.0, mass_z=1000.0))
    return Scene(sections=(one.sections[0], low), angles=angles,
                 numerics=Numerics(duration=1.0, output_step=0.05, model="as-built", dimensions=3), name=f"chain-{angles}")


def energy_drift(quick: bool, n_periods: int | None = None, scene: Scene | None = None) -> dict:
    """max |E - E_0| / (E_0 - E_rest) over 100 pendulum periods of a 3-D swing with drag and damping off
    (``scene``: another scene without drag, damping or top motion; default one section)."""
    sc = scene or pendulum_scene(ae=2e7, weight=2e4, mass=3000.0, cable_mass=True,
                                 numerics=Numerics(duration=1.0, output_step=0.05, model="as-built", dimensions=3))
    m = build_model(sc)
    p = m.parameters(sc)
    q_rest = steady_state(m, p).q
    x0 = np.concatenate([q_rest, np.zeros(m.nq)])
    lab = m.q_labels
    x0[lab.index(m.label("phi", 0) if m.label("phi", 0) in lab else "phi")] = 0.4
    x0[m.nq + lab.index(m.label("phi_z", 0) if m.label("phi_z", 0) in lab else "phi_z")] = 0.25
    x0[m.nq + lab.index(m.label("u", 0))] = 0.002
    period = 2 * math.pi * math.sqrt(sum(s.cable.length for s in sc.sections) / 9.80665)
    n_per = n_periods or (10 if quick else 100)
    r = simulate(sc.with_numerics(duration=n_per * period, output_step=period / 8), model=m, x0=x0,
                 rtol=1e-10, atol=1e-10)
    states = np.asarray(r.states).T
    e0 = np.zeros(len(m.top(0.0, p).full().ravel()))

    def energy(x):
        K, V = m.energy(x, e0, p)
        return float(K) + float(V)
    E = np.array([energy(x) for x in states])
    E_rest = energy(np.concatenate([q_rest, np.zeros(m.nq)]))
    drift = float(np.max(np.abs(E - E[0])) / (E[0] - E_rest))
    return {"drift_rel": drift, "periods": n_per, "motion_energy_J": E[0] - E_rest,
            "z_b_amplitude_m": float(np.max(np.abs(np.asarray(r[m.label("z_b", m.n_sections - 1)]))))}


# ------------------------------------------------------------------------------ linear modes
def out_of_plane_frequency(mass_z_factor: float = 1.0) -> dict:
    """Out-of-plane pendulum frequency of the 3-D linearization against the in-plane one of the planar model
    (``mass_z_factor`` scales M_bvz: 1 is the symmetric scene; another value breaks the symmetry)."""
    base = pendulum_scene(ae=2e7, weight=2e4, mass=3000.0, cable_mass=True, drag=0.5,
                          numerics=Numerics(model="as-built"))
    base = base.replace_section(0, body={"mass_z": 3000.0 * mass_z_factor})
    sc2 = dataclasses.replace(base, sections=(Section(cable=base.cable,
                                                      body=dataclasses.replace(base.body, mass_z=None)),))
    m2, m3 = build_model(sc2), build_model(base)
    l2, l3 = linearize(m2, m2.parameters(sc2)), linearize(m3, m3.parameters(base))
    md2, md3 = modes(l2), modes(l3)
    w_in = float(md2.omega_undamped[list(md2.dominant).index("phi")])
    w_out = float(md3.omega_undamped[list(md3.dominant).index("phi_z")])
    w_in3 = float(md3.omega_undamped[list(md3.dominant).index("phi")])
    # the RAO of the sway z_b to the top's sway z_s is the planar one of x_b to x_s (off resonance)
    omega = np.array([0.2, 0.4, 0.8, 1.5, 3.0])
    ra2, ra3 = rao(l2, omega), rao(l3, omega)
    rao_err = float(np.max(np.abs(ra3("z_b", "z_s") - ra2("x_b", "x_s")) / np.abs(ra2("x_b", "x_s"))))
    cross = float(np.max(np.abs(ra3("tension_top", "z_s")) / np.abs(ra2("tension_top", "y_s"))))
    return {"omega_in_plane_planar": w_in, "omega_in_plane_3d": w_in3, "omega_out_of_plane_3d": w_out,
            "rel_err": max(abs(w_out / w_in - 1.0), abs(w_in3 / w_in - 1.0)),
            "rao_sway_vs_planar_surge_rel_err": rao_err, "rao_tension_per_sway_over_per_heave": cross,
            "rao_omega": omega, "input_labels": list(l3.input_labels)}


# ------------------------------------------------------------------------------ figure
def figure(runs: dict, cases: dict, path: Path) -> Path:
    """Plan view (x_b, z_b) and elevation (x_b, depth y_b) of the conical-pendulum runs, with the cable
    drawn at four instants of the first revolution."""
    plt = setup_matplotlib()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5.6))
    for k, (a, (t, x, y, z)) in enumerate(sorted(runs.items())):
        col = f"C{k}"
        c = cases[f"{a:g}"]
        lab = f"cone {a:g} deg: omega^2 L cos(a) / g - 1 = {c['rel_err_omega2']:.1e}"
        ax1.plot(x, z, color=col, lw=1.4, label=lab)
        ax1.plot([x[0]], [z[0]], "o", color=col, ms=5)
        ax2.plot(x, y, color=col, lw=1.4, label=f"cone {a:g} deg: body path (constant depth)")
        n_rev = int(np.searchsorted(t, 2 * math.pi / c["omega_measured"]))
        for j in np.linspace(0, n_rev, 4, endpoint=False).astype(int):
            ax1.plot([0.0, x[j]], [0.0, z[j]], color=col, lw=0.6, alpha=0.6)
            ax2.plot([0.0, x[j]], [0.0, y[j]], color=col, lw=0.6, alpha=0.6)
    ax1.plot([0.0], [0.0], "k+", ms=12, mew=2, label="top (fixed)")
    ax1.set(xlabel="x_b (m)", ylabel="z_b (m, sway)", title="Plan view from above: body path, cable at 4 instants")
    ax2.plot([0.0], [0.0], "k+", ms=12, mew=2)
    ax2.set(xlabel="x_b (m)", ylabel="y_b (m, down)", title="Elevation (x-y plane): cable at 4 instants")
    ax2.invert_yaxis()
    for ax in (ax1, ax2):
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1, frameon=False)
    fig.suptitle("Wang's cable in 3-D: a heavy sphere in steady conical motion (stiff massless cable, no drag)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def span_out_of_plane(levels=(24, 48, 96), n_modes: int = 4, slack: float = 4e-4) -> dict:
    """The sway (out-of-plane) modes of a span between two supports on the node model (Griffin & Rosenthal's
    Table 2 cable, 1 - l/L = ``slack``) against Irvine's (1981, ch. 3) taut-string frequencies of a shallow
    span, omega_n = (n pi / l) sqrt(H / m), which the sag leaves unchanged to first order."""
    from cablesys.slack import irvine
    from cablesys.slack.statics import solve_equilibrium
    from cablesys.slack.vibration import converge
    sc = slack_tables.scene6(1.0 - slack)
    eq = solve_equilibrium(sc.replace(n_elements=levels[-1]))
    conv = converge(sc, 2 * n_modes, levels=levels)
    out_of_plane = [i for i, t in enumerate(conv.mode_type) if t == "O"][:n_modes]
    num = np.sort(np.asarray(conv.richardson)[out_of_plane])
    theory = irvine.string_omega(np.arange(1, num.size + 1), span=slack_tables.SPAN6, H=eq.horizontal_tension,
                                 m=slack_tables.M6)
    err = num / theory - 1
    return {"max_rel_err": float(np.max(np.abs(err))), "rel_err": err.tolist(), "omega_rad_s": num.tolist(),
            "sag_to_span": float(eq.sag / slack_tables.SPAN6), "levels": list(levels),
            "observed_order": np.asarray(conv.order)[out_of_plane].tolist()}


def main(argv=None) -> dict:
    args = parse_args("Checks of Wang's cable in three dimensions", argv)
    planar = planar_equivalence(args.quick)
    rot = rotation_invariance(args.quick)
    cone = conical_pendulum(args.quick)
    energy = energy_drift(args.quick)
    freq = out_of_plane_frequency()
    node = {"planar_equivalence": nodes.planar_equivalence([s for s in planar_scenes() if s.angles != "shared"],
                                                            args.quick),
            "rotation_invariance": nodes.rotation_invariance(rotation_scene(), rotated_scene, rotate, args.quick),
            "energy": nodes.energy_drift(args.quick), "chain_modes": nodes.chain_modes(args.quick)}
    n_pl, n_rot = node["planar_equivalence"], node["rotation_invariance"]
    qs = {"planar_equivalence": quasistatic.planar_equivalence(args.quick),
          "rotation_invariance": quasistatic.rotation_invariance(args.quick), "conical_pendulum": quasistatic.conical_pendulum()}
    q_pl, q_rot = qs["planar_equivalence"], qs["rotation_invariance"]
    tow_lin, tow_sea = towed.linear_vs_theory(args.quick), towed.sea_trials(args.quick)
    tow_sea.pop("_profiles")
    fig = figure(cone.pop("_runs"), cone["cases"], args.out / "three_d_conical_pendulum.png")
    towed.figure(tow_lin, tow_sea, args.out / "three_d_towed_nonlinear.png")
    turn = turning.turning_check(1.5 if args.quick else 4.0)
    span = span_out_of_plane()
    body = rigid.free_rotation(args.quick)
    turning.figure(turn, turning.steady_shape(), args.out / "three_d_turning_tow.png")
    r_pl = rigid.planar_equivalence(args.quick)
    track = {"galilean": tracks.galilean(0.0), "galilean_with_added_mass": tracks.galilean(1.0), "munk": tracks.munk(),
             "turn": tracks.turn_settles(450.0 if args.quick else 720.0),
             "zigzag_rotation": tracks.rotation(35.0, duration=30.0 if args.quick else 120.0)}
    tracks.figure(track["turn"], args.out / "three_d_tracks.png")
    z_rot = track["zigzag_rotation"]
    doc = {
        "planar_equivalence_max_abs": max(planar["run_max_abs"], n_pl["run_max_abs"], q_pl["run_max_abs"],
                                          r_pl["equations_max_abs"]),
        "planar_equivalence_max_rel": max(planar["max_rel"], n_pl["max_rel"], q_pl["max_rel"], r_pl["equations_max_rel"]),
        "planar_equivalence_rigid_run_max_rel": r_pl["run_max_rel"],
        "rotation_invariance_max_abs": max(rot["equations_max_abs"], rot["run_position_max_abs_m"],
                                           n_rot["equations_max_abs"], n_rot["run_position_max_abs_m"],
                                           q_rot["run_position_max_abs_m"], z_rot["position_max_abs_m"]),
        "rotation_invariance_scalars_max_rel": max(rot["equations_scalars_max_rel"], rot["run_tension_max_rel"],
                                                   n_rot["equations_max_rel"], n_rot["run_tension_max_rel"],
                                                   q_rot["run_scalars_max_rel"], z_rot["tension_max_rel"]),
        "straight_track_vs_system_speed_max_rel": track["galilean"]["max_rel"],
        "straight_track_munk_couple_rel_err": track["munk"]["rel_err"],
        "turn_settles_on_steady_turn_rel_err": track["turn"]["rel_err"],
        "conical_pendulum_rel_err": max(cone["max_rel_err"], qs["conical_pendulum"]["rel_err_omega2"],
                                        qs["conical_pendulum"]["radius_rel_wander"]),
        "energy_drift_rel": max(energy["drift_rel"], node["energy"]["drift_rel"]),
        "chain_out_of_plane_mode_rel_err": node["chain_modes"]["out_of_plane_vs_in_plane_max_rel"],
        "chain_out_of_plane_vs_bessel_rel_err": node["chain_modes"]["vs_bessel_rel_err_finest"],
        "out_of_plane_frequency_rel_err": freq["rel_err"],
        "out_of_plane_rao_rel_err": freq["rao_sway_vs_planar_surge_rel_err"],
        "towed_linear_vs_theory_max_rel_err": tow_lin["max_rel_err"],
        "towed_sea_trials": {k: tow_sea[k] for k in ("mean_abs_dH_nonlinear", "mean_abs_dH_linear_theory",
                                                     "mean_abs_dcstar_nonlinear", "mean_abs_dcstar_linear_theory")},
        "turning_tow_steady_vs_time_domain_rel_err": turn["rel_err"],
        "span_out_of_plane_vs_irvine_rel_err": span["max_rel_err"],
        "rigid_body_momentum_drift_rel": body["max_drift_rel"],
        **{k: None for k in NOT_BUILT},
        "not_built": list(NOT_BUILT),
        "details": {"planar_equivalence": planar, "rotation_invariance": rot, "conical_pendulum": cone,
                    "energy": energy, "out_of_plane_frequency": freq, "node_model": node, "quasi_static": qs,
                    "towed": {"linear_vs_theory": tow_lin, "sea_trials": tow_sea}, "span_out_of_plane": span,
                    "turning_tow": {k: v for k, v in turn.items() if k not in ("time_s", "distance_m")},
                    "rigid_body": body, "rigid_body_planar_equivalence": r_pl,
                    "tracks": {k: ({n: x for n, x in v.items() if not isinstance(x, list) or n.startswith("munk")}
                                   if isinstance(v, dict) else v) for k, v in track.items()}},
        "quick": args.quick,
        "figure": fig.name,
    }
    write_json(args.out / "three_d_checks.json", doc)
    return doc


if __name__ == "__main__":
    main()
