"""The rigid body in space (cablesys/model/rigid_body.py), free of its cable: the conservation check of
``studies/three_d_checks.py``'s ``rigid_body_momentum_drift_rel``.

A torque-free asymmetric body tumbles about its intermediate principal axis (the unstable one: Goldstein,
Classical Mechanics, 3rd ed., sec. 5.6; it flips over every half period of the separatrix motion), in a fluid
whose added mass per body axis couples its translation to its rotation (the Munk moment, Newman 1977 sec. 4.13).
Over 100 s (CVODES, rtol 1e-13) Kirchhoff's linear and angular impulse of body and fluid (Lamb 1932 sec. 119:
P = R M_bv w, L = r_cg x P + R (I + I_a) omega, a closed form of the state, not the Lagrangian's momenta) and the
kinetic energy must stay constant; the value is the largest relative drift of the three over the cases
(|dP| / |P_0|, |dL| / |L_0|, |dK| / K_0), the quaternion's norm error beside it.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from cablesys.model.rigid_body import free_body
from cablesys.scene import Body, Cable, Environment, Numerics, single_section_scene

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
