"""The rigid body in space (cablesys/model/rigid_body.py): free of its cable, the conservation check of
``studies/three_d_checks.py``'s ``rigid_body_momentum_drift_rel``; on its cable in a planar scene run by the 3-D
equations, the rigid-body case of ``planar_equivalence_max_abs`` (:func:`planar_equivalence`).

A torque-free asymmetric body tumbles about its intermediate principal axis (the unstable one: Goldstein,
Classical Mechanics, 3rd ed., sec. 5.6; it flips over every half period of the separatrix motion), in a fluid
whose added mass per body axis couples its translation to its rotation (the Munk moment, Newman 1977 sec. 4.13).
Over 100 s (CVODES, rtol 1e-13) Kirchhoff's linear and angular impulse of body and fluid (Lamb 1932 sec. 119:
P = R M_bv w, L = r_cg x P + R (I + I_a) omega, a closed form of the state, not the Lagrangian's momenta) and the
kinetic energy must stay constant; the value is the largest relative drift of the three over the cases
(|dP| / |P_0|, |dL| / |L_0|, |dK| / K_0), the quaternion's norm error beside it.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from cablesys.model import build_model
from cablesys.model.rigid_body import free_body
from cablesys.scene import Body, Cable, Environment, Numerics, Sinusoid, TopMotion, single_section_scene
from cablesys.statics import steady_state
from cablesys.time_domain import simulate
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator

DURATION_S = 100.0


def free_scene(body: Body):
    """A 3-D scene holding ``body`` on a weightless rod-like cable (only its parameters are used: the free body
    has no cable)."""
    cable = Cable(length=10.0, ae=1e7, diameter=0.02, mass_per_length=1.0, weight_per_length=0.0,
                  added_mass_factor=0.0, cd_normal=0.0, ct_tangential=0.0, segments=2, tension_floor=-np.inf)
    return single_section_scene(cable=cable, body=body, environment=Environment(density=1e-9),
                                numerics=Numerics(dimensions=3))


def cases() -> dict:
    """Two tumbling bodies (weightless, no buoyancy, no drag): the rotation alone (no added mass, at rest as a
    whole) and the same body with added mass and inertia per axis, a product of inertia and a translation."""
    plain = Body(weight=0.0, mass_x=200.0, mass_y=200.0, mass_z=200.0, pitch_inertia=30.0, inertia_xx=10.0,
                 inertia_yy=20.0, attachment_y=-0.5)
    munk = Body(weight=0.0, mass_x=200.0, mass_y=320.0, mass_z=250.0, pitch_inertia=30.0, inertia_xx=10.0,
                inertia_yy=20.0, inertia_xy=1.0, added_inertia_x=2.0, added_inertia_y=1.0, pitch_added_inertia=3.0,
                attachment_x=0.3, attachment_y=-0.5, attachment_z=0.2)
    # omega (rad/s, body axes) near the intermediate axis y (I_yy = 20 between 10 and 30), CG velocity (m/s)
    return {"intermediate_axis": (plain, np.array([0.01, 2.0, 0.01]), np.zeros(3)),
            "intermediate_axis_with_added_mass": (munk, np.array([0.01, 2.0, 0.01]), np.array([0.1, 0.2, -0.3]))}


def tumble(body: Body, omega0, velocity0, duration: float = DURATION_S, n_out: int = 1001) -> dict:
    """Integrate the free body from the level attitude with body rates ``omega0`` and attachment-point velocity
    ``velocity0``; the drifts of the impulses and the energy (relative), the quaternion's norm error and whether
    the body flipped (omega_y changed sign)."""
    fb = free_body(free_scene(body))
    p = fb["p"]
    a0 = np.array([1.0, 0.0, 0.0, 0.0])
    ad0 = 0.5 * np.concatenate([[0.0], omega0])                 # a' = 1/2 a (x) (0, omega) at a = 1
    x0 = np.concatenate([np.zeros(3), a0, velocity0, ad0])
    x, t = ca.SX.sym("x", 14), ca.SX.sym("t")
    times = np.linspace(0.0, duration, n_out)
    integ = ca.integrator("free_body", "cvodes", {"x": x, "t": t, "ode": fb["ode"](x, t, p)}, 0.0, times,
                          {"abstol": 1e-15, "reltol": 1e-13, "max_num_steps": 10**6})
    X = np.array(integ(x0=x0)["xf"])
    X = np.column_stack([x0, X]) if X.shape[1] == n_out - 1 else X
    P0, L0 = (np.array(v).ravel() for v in fb["impulse"](x0, p))
    K0 = float(fb["energy"](x0, p)[0])
    dP = dL = dK = dn = 0.0
    om_y = []
    for k in range(X.shape[1]):
        P, L = (np.array(v).ravel() for v in fb["impulse"](X[:, k], p))
        K = float(fb["energy"](X[:, k], p)[0])
        dP = max(dP, float(np.linalg.norm(P - P0)) / max(float(np.linalg.norm(P0)), 1e-300))
        dL = max(dL, float(np.linalg.norm(L - L0) / np.linalg.norm(L0)))
        dK = max(dK, abs(K - K0) / K0)
        dn = max(dn, abs(float(np.linalg.norm(X[3:7, k])) - 1.0))
        om_y.append(float(np.array(fb["state"](X[:, k], p)[2]).ravel()[1]))
    moving = np.linalg.norm(P0) > 0.0
    return {"linear_impulse_drift_rel": dP if moving else None, "angular_impulse_drift_rel": dL,
            "energy_drift_rel": dK, "quaternion_norm_error": dn, "flipped": bool(min(om_y) < 0.0 < max(om_y)),
            "duration_s": duration}


def free_rotation(quick: bool) -> dict:
    """The conservation check over :func:`cases` (quick: the harder, added-mass case alone); ``max_drift_rel``
    the largest relative drift of P, L and K."""
    runs = {name: tumble(*spec) for name, spec in cases().items() if not quick or "added_mass" in name}
    worst = max(max(v for k, v in r.items() if k.endswith("_drift_rel") and v is not None) for r in runs.values())
    return {"max_drift_rel": worst, "cases": runs}


# ---------------------------------------------------------------------------------------- the plane as the special case
def planar_body(**kw) -> Body:
    """A pitching body with every planar rigid field: offsets, buoyancy centre, centre of pressure, added inertia,
    pitch damping and drag, a cylinder's drag axis and per-axis drag."""
    return Body(weight=900.0, mass_x=150.0, mass_y=210.0, drag_area_normal=0.5, drag_area_tangential=0.2,
                axis_angle_deg=20.0, pitch_inertia=35.0, pitch_added_inertia=5.0, attachment_x=0.2, attachment_y=-0.6,
                buoyancy=300.0, buoyancy_x=0.1, buoyancy_y=-0.2, drag_centre_x=-0.3, drag_centre_y=0.1,
                pitch_damping=4.0, pitch_drag=2.0, drag_area_x=0.3, drag_area_y=0.1, **kw)


def planar_scenes(duration: float = 6.0) -> tuple:
    """The pitching body on a 3-element cable in a current of 0.6 m/s with surge and heave of the top, as a planar
    scene and forced through the 3-D equations (``numerics.dimensions = 3``)."""
    cable = Cable(length=10.0, tension_ref=0.0, ae=2e6, diameter=0.02, mass_per_length=2.0, weight_per_length=15.0,
                  added_mass_factor=1.0, cd_normal=1.2, ct_tangential=0.0, segments=3)
    top = TopMotion(x=(Sinusoid(amplitude=0.5, frequency=0.7),), y=(Sinusoid(amplitude=0.3, frequency=1.1),))
    return tuple(single_section_scene(cable=cable, body=planar_body(), top_motion=top,
                                      environment=Environment(gravity=9.80665, current_speeds=(0.6,)),
                                      numerics=Numerics(duration=duration, output_step=0.05, dimensions=d))
                 for d in (2, 3))


def to_3d(m2, m3, x2) -> np.ndarray:
    """The 3-D state of a planar one: z = 0, the quaternion (cos theta/2, 0, 0, sin theta/2) of the pitch about z and
    its rate."""
    n2, n3 = m2.nq, m3.nq
    x3 = np.zeros(2 * n3)
    for k, lbl in enumerate(m2.q_labels[:-1]):
        j = m3.q_labels.index(lbl)
        x3[j], x3[n3 + j] = x2[k], x2[n2 + k]
    th, thd = x2[n2 - 1], x2[-1]
    c, s = math.cos(th / 2), math.sin(th / 2)
    x3[n3 - 4:n3] = (c, 0.0, 0.0, s)
    x3[-4:] = 0.5 * thd * np.array([-s, 0.0, 0.0, c])
    return x3


RUN_OUTPUTS = ("theta_b", "theta_b_rate", "x_cg", "y_cg", "x_b", "y_b", "tension_top", "tension_bottom")


def planar_equivalence(quick: bool) -> dict:
    """The pitching body's planar scene against the same scene run by the 3-D equations. At random states (the pitch
    mapped to its quaternion): the node accelerations, the quaternion's a'' against d2/dt2 of (cos theta/2, 0, 0,
    sin theta/2) with the planar theta'', and the outputs (absolute: m/s^2, rad/s^2, m, N; normwise relative), the
    motion out of the plane (z'' and roll, yaw, z_cg: 0), the body rate about z against theta'. Over a run from the static state pitched by 0.4 rad with
    sideways node velocities, each model at CVODES-Adams rtol 1e-12 on its own steps (the plane's theta and the
    quaternion are different coordinates: fixed RK steps are not the same discretization in both, so the run differs
    by the integration's error, not by rounding): the largest normwise difference of RUN_OUTPUTS."""
    s2, s3 = planar_scenes(3.0 if quick else 6.0)
    m2, m3 = build_model(s2), build_model(s3)
    p2, p3 = m2.parameters(s2), m3.parameters(s3)
    n2, n3 = m2.nq, m3.nq
    rng = np.random.default_rng(11)
    st = steady_state(m2, p2)
    z_rows = [n3 + k for k, lbl in enumerate(m3.q_labels) if lbl.startswith("z[")]
    rows = [m3.output_labels.index(lbl) for lbl in m2.output_labels]
    flat = [m3.output_labels.index(n) for n in ("roll_b", "yaw_b", "z_cg", "omega_x_b", "omega_y_b")]
    d_abs = d_rel = out_of_plane = 0.0
    for _ in range(3 if quick else 10):
        x2 = np.concatenate([st.q + rng.normal(0, 0.05, n2), rng.normal(0, 0.5, n2)])
        x2[n2 - 1] = rng.uniform(-1.2, 1.2)
        x3 = to_3d(m2, m3, x2)
        t = rng.uniform(0, 10)
        f2, f3 = (np.array(m.ode(x, t, p)).ravel() for m, x, p in ((m2, x2, p2), (m3, x3, p3)))
        th, thd, thdd = x2[n2 - 1], x2[-1], f2[-1]
        c, s = math.cos(th / 2), math.sin(th / 2)
        quat = 0.5 * thdd * np.array([-s, 0, 0, c]) - 0.25 * thd**2 * np.array([c, 0, 0, s])
        acc2 = np.concatenate([to_3d(m2, m3, np.concatenate([x2[:n2], f2[n2:]]))[n3:2 * n3 - 4], quat])
        y2 = np.array(m2.outputs(x2, m2.top(t, p2), p2)).ravel()
        y3 = np.array(m3.outputs(x3, m3.top(t, p3), p3)).ravel()
        y2 = np.append(y2, thd)                                        # the body rate about z is theta'
        for a, b in ((acc2, f3[n3:]), (y2, np.append(y3[rows], y3[m3.output_labels.index("omega_z_b")]))):
            d_abs = max(d_abs, float(np.max(np.abs(a - b))))
            d_rel = max(d_rel, float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(a))), 1.0)))
        out_of_plane = max(out_of_plane, float(np.max(np.abs(f3[z_rows]))), float(np.max(np.abs(y3[flat]))))
    x0 = np.concatenate([st.q, np.zeros(n2)])
    x0[n2 - 1] += 0.4
    x0[n2:n2 + 2 * (n2 // 2):2] = 0.3                                 # sideways node velocities
    runs = {}
    for m, sc, x in ((m2, s2, x0), (m3, s3, to_3d(m2, m3, x0))):
        sim = Simulator(m, sc.output_times, IntegratorSettings(method="cvodes-adams", rtol=1e-12, atol=1e-14,
                                                              compiled=False))
        runs[m.dim] = simulate(sc, model=m, x0=x, simulator=sim)
    per = {lbl: float(np.max(np.abs(np.asarray(runs[2][lbl]) - np.asarray(runs[3][lbl])))
                      / max(float(np.max(np.abs(np.asarray(runs[2][lbl])))), 1.0)) for lbl in RUN_OUTPUTS}
    return {"equations_max_abs": d_abs, "equations_max_rel": d_rel, "equations_out_of_plane_max_abs": out_of_plane,
            "three_d_orientation_labels": list(m3.q_labels[-4:]),
            "run_max_rel": max(per.values()), "run_per_output_rel": per, "run_rtol": 1e-12,
            "run_pitch_range_rad": float(np.ptp(np.asarray(runs[2]["theta_b"]))),
            "run_out_of_plane_max_abs": max(float(np.max(np.abs(np.asarray(runs[3][k])))) for k in ("roll_b", "z_b"))}
