"""Fluid velocities and quadratic drag laws, as CasADi expressions (Wang 1971 eq. 26-45).

One place for every drag law: the body and cable forces of the 2-DOF model, the
multi-section chain and the linearization all call these.
"""

from __future__ import annotations

import casadi as ca


def safe_norm(vx, vy):
    """sqrt(vx^2 + vy^2) whose derivative is 0 (not NaN) at the origin.

    Quadratic drag |v| v has zero slope at zero relative velocity; a plain sqrt would give
    0/0 there and poison Jacobians taken about a state at rest.
    """
    s = vx**2 + vy**2
    pos = s > 0
    return ca.if_else(pos, ca.sqrt(ca.if_else(pos, s, 1.0)), 0.0, True)


def current_profile(depth, depths, speeds):
    """c(y): linear interpolation of the current points, constant beyond the ends (the report's CUR)."""
    c = speeds[0]
    for k in range(len(depths) - 1):
        slope = (speeds[k + 1] - speeds[k]) / (depths[k + 1] - depths[k])
        c = c + slope * (ca.fmin(ca.fmax(depth, depths[k]), depths[k + 1]) - depths[k])
    return c


def wave_velocity(x, depth, t, waves, gravity):
    """Deep-water wave particle velocity (x_W, y_W), y down (Wang 1971 eq. 26a-b, sign of 26b fixed).

    ``waves`` is a list of (amplitude a, length lambda, phase) expressions;
    n = 2 pi / lambda, sigma = sqrt(g n) (= sqrt(2 pi g / lambda)). The velocity derives from the
    potential (a sigma / n) e^{-n y} cos(n x - sigma t + phase) of the wave
    eta = a sin(n x - sigma t + phase) (elevation up). Eq. 26b as printed,
    -a sigma e^{-n y} cos(...), is the *upward* component (the report's source measures y up):
    with y down it breaks continuity (div v = 2 n a sigma e^{-n y} cos != 0). We use
    y_W = +a sigma e^{-n y} cos(...), which is divergence- and curl-free (tests/test_waves.py).
    """
    vx, vy = 0.0, 0.0
    for a, lam, ph in waves:
        n = 2 * ca.pi / lam
        sigma = ca.sqrt(gravity * n)
        arg = n * x - sigma * t + ph
        amp = a * sigma * ca.exp(-n * depth)
        vx = vx + amp * ca.sin(arg)
        vy = vy + amp * ca.cos(arg)          # y down: eq. 26b's sign reversed (see docstring)
    return vx, vy


def fluid_velocity(x, depth, t, env):
    """Ocean velocity (xi', eta') at a point: current minus system speed plus waves (eq. 27-28)."""
    c = current_profile(depth, env["current_depths"], env["current_speeds"]) - env["system_speed"]
    wx, wy = wave_velocity(x, depth, t, env["waves"], env["gravity"])
    return c + wx, wy


def quadratic_drag(rho, coef_area, v_rel):
    """1/2 rho C A |v| v along one direction (eq. 33a-b, 42, 44)."""
    return 0.5 * rho * coef_area * ca.fabs(v_rel) * v_rel


def sphere_drag(rho, cda, vrx, vry):
    """Drag parallel to the relative flow, (D_bx, D_by) (Wang 1971 eq. 32a-d)."""
    vb = safe_norm(vrx, vry)
    return 0.5 * rho * cda * vb * vrx, 0.5 * rho * cda * vb * vry


def axial_body_drag(rho, cda_n, cda_t, phi_b, vrx, vry):
    """Cylinder or disk: normal and tangential drag about the body axis phi_b (eq. 33-35)."""
    v_t = -vrx * ca.sin(phi_b) + vry * ca.cos(phi_b)            # eq. 34a
    v_n = -vrx * ca.cos(phi_b) - vry * ca.sin(phi_b)            # eq. 34b
    d_n = quadratic_drag(rho, cda_n, v_n)
    d_t = quadratic_drag(rho, cda_t, v_t)
    return -ca.sin(phi_b) * d_t - ca.cos(phi_b) * d_n, ca.cos(phi_b) * d_t - ca.sin(phi_b) * d_n   # eq. 35
