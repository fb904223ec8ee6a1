"""Fluid velocities and quadratic drag laws, as CasADi expressions (Wang 1971 eq. 26-45).

One place for every drag law: the body and cable forces of the 2-DOF model, the
multi-section chain and the linearization all call these.
"""

from __future__ import annotations

import casadi as ca


def safe_norm(vx, vy, *more):
    """sqrt(vx^2 + vy^2 (+ vz^2 ...)) whose derivative is 0 (not NaN) at the origin.

    Quadratic drag |v| v has zero slope at zero relative velocity; a plain sqrt would give
    0/0 there and poison Jacobians taken about a state at rest.
    """
    s = vx**2 + vy**2
    for v in more:
        s = s + v**2
    pos = s > 0
    return ca.if_else(pos, ca.sqrt(ca.if_else(pos, s, 1.0)), 0.0, True)


def current_profile(depth, depths, speeds):
    """c(y): linear interpolation of the current points, constant beyond the ends (the report's CUR)."""
    c = speeds[0]
    for k in range(len(depths) - 1):
        slope = (speeds[k + 1] - speeds[k]) / (depths[k + 1] - depths[k])
        c = c + slope * (ca.fmin(ca.fmax(depth, depths[k]), depths[k + 1]) - depths[k])
    return c


def wave_velocity(x, depth, t, waves, gravity, z=None):
    """Deep-water wave particle velocity (x_W, y_W), y down (Wang 1971 eq. 26a-b, sign of 26b fixed).

    ``waves`` is a list of (amplitude a, length lambda, phase) expressions;
    n = 2 pi / lambda, sigma = sqrt(g n) (= sqrt(2 pi g / lambda)). The velocity derives from the
    potential (a sigma / n) e^{-n y} cos(n x - sigma t + phase) of the wave
    eta = a sin(n x - sigma t + phase) (elevation up). Eq. 26b as printed,
    -a sigma e^{-n y} cos(...), is the *upward* component (the report's source measures y up):
    with y down it breaks continuity (div v = 2 n a sigma e^{-n y} cos != 0). We use
    y_W = +a sigma e^{-n y} cos(...), which is divergence- and curl-free (tests/test_waves.py).

    In three dimensions (``z`` given) each wave is (a, lambda, phase, heading b): it travels along
    (cos b, 0, sin b), its phase is n (x cos b + z sin b) - sigma t + phase, and the velocity
    (x_W, y_W, z_W) has the horizontal part along the heading (the plane wave rotated about the
    vertical); the plane is b = 0.
    """
    vx, vy, vz = 0.0, 0.0, 0.0
    for wave in waves:
        a, lam, ph = wave[:3]
        n = 2 * ca.pi / lam
        sigma = ca.sqrt(gravity * n)
        if z is None:
            arg = n * x - sigma * t + ph
        else:
            cb, sb = ca.cos(wave[3]), ca.sin(wave[3])
            arg = n * (x * cb + z * sb) - sigma * t + ph
        amp = a * sigma * ca.exp(-n * depth)
        if z is None:
            vx = vx + amp * ca.sin(arg)
        else:
            vx, vz = vx + cb * amp * ca.sin(arg), vz + sb * amp * ca.sin(arg)
        vy = vy + amp * ca.cos(arg)          # y down: eq. 26b's sign reversed (see docstring)
    return (vx, vy) if z is None else (vx, vy, vz)


def fluid_velocity(x, depth, t, env):
    """Ocean velocity (xi', eta') at a point: current minus system speed plus waves (eq. 27-28)."""
    c = current_profile(depth, env["current_depths"], env["current_speeds"]) - env["system_speed"]
    wx, wy = wave_velocity(x, depth, t, env["waves"], env["gravity"])
    return c + wx, wy


def fluid_velocity_3d(x, depth, z, t, env):
    """Ocean velocity (xi', eta', zeta') at a point in 3-D: the current along its heading per depth
    minus the system speed (along +x), plus waves with their headings (eq. 27-28 rotated about the
    vertical). The current's x and z components are interpolated in depth like the report's CUR
    speeds (``env["current_headings"]``, rad from +x towards +z)."""
    speeds, heads = env["current_speeds"], env["current_headings"]
    cx = current_profile(depth, env["current_depths"], [c * ca.cos(h) for c, h in zip(speeds, heads)])
    cz = current_profile(depth, env["current_depths"], [c * ca.sin(h) for c, h in zip(speeds, heads)])
    wx, wy, wz = wave_velocity(x, depth, t, env["waves"], env["gravity"], z=z)
    return cx - env["system_speed"] + wx, wy, cz + wz


def crossflow_drag(rho, coef_area, components):
    """Normal drag 1/2 rho C A |v_n| v_n by the cross-flow principle, per component of v_n.

    ``components`` are the relative velocity's components on an orthonormal basis of the plane
    normal to a cable (or a body axis): one in the plane (Wang 1971 eq. 42, 33a: |v_n| v_n along
    e_n), two in space, where the size |v_n| is that of the whole normal velocity (so the law does
    not depend on the basis chosen).
    """
    if len(components) == 1:
        return [quadratic_drag(rho, coef_area, components[0])]
    size = safe_norm(*components)
    return [0.5 * rho * coef_area * size * c for c in components]


def quadratic_drag(rho, coef_area, v_rel):
    """1/2 rho C A |v| v along one direction (eq. 33a-b, 42, 44)."""
    return 0.5 * rho * coef_area * ca.fabs(v_rel) * v_rel


def sphere_drag(rho, cda, vrx, vry, *vrz):
    """Drag parallel to the relative flow, (D_bx, D_by) (Wang 1971 eq. 32a-d); (D_bx, D_by, D_bz) in 3-D."""
    vb = safe_norm(vrx, vry, *vrz)
    return (0.5 * rho * cda * vb * vrx, 0.5 * rho * cda * vb * vry) + tuple(0.5 * rho * cda * vb * v for v in vrz)


def axial_body_drag(rho, cda_n, cda_t, phi_b, vrx, vry):
    """Cylinder or disk: normal and tangential drag about the body axis phi_b (eq. 33-35)."""
    v_t = -vrx * ca.sin(phi_b) + vry * ca.cos(phi_b)            # eq. 34a
    v_n = -vrx * ca.cos(phi_b) - vry * ca.sin(phi_b)            # eq. 34b
    d_n = quadratic_drag(rho, cda_n, v_n)
    d_t = quadratic_drag(rho, cda_t, v_t)
    return -ca.sin(phi_b) * d_t - ca.cos(phi_b) * d_n, ca.cos(phi_b) * d_t - ca.sin(phi_b) * d_n   # eq. 35


def axial_body_drag_3d(rho, cda_n, cda_t, phi_b, vrx, vry, vrz):
    """Cylinder or disk whose axis (-sin phi_b, cos phi_b, 0) lies in the x-y plane, in 3-D (eq. 33-35).

    Tangential drag along the axis as in eq. 34a, 35; the normal drag by the cross-flow principle
    (:func:`crossflow_drag`) on the normal plane spanned by e_n = (-cos phi_b, -sin phi_b, 0) and z.
    With vrz = 0 it is :func:`axial_body_drag`.
    """
    s, c = ca.sin(phi_b), ca.cos(phi_b)
    v_t = -vrx * s + vry * c                                    # eq. 34a
    v_n = -vrx * c - vry * s                                    # eq. 34b
    d_t = quadratic_drag(rho, cda_t, v_t)
    d_n, d_z = crossflow_drag(rho, cda_n, [v_n, vrz])
    return -s * d_t - c * d_n, c * d_t - s * d_n, d_z
