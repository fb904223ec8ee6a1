"""One element of the segmented cable, and the body at a node: the physics both assemblies share.

:func:`element_terms` gives an element's length, tension (Voigt damping and the slack rule, Wang
1971 eq. 46, 54), lumped mass and added mass (eq. 5, 23-24, thinned diameter eq. 3), weight in
water (eq. 12), strain energy and the virtual-work shares of its drag (eq. 42, 44 with the fluid
velocity of eq. 26-28); :func:`element_inertia` the inertial terms of its lumped kinetic energy by
AD (Lagrange's equations, eq. 8-9); :func:`body_drag` the body's drag (eq. 32-35). The
element-by-element SX model (:mod:`.segmented`, where the element and its coordinates are
described) and the mapped element kernel (:mod:`.segmented_kernel`) are both assembled from these.
All lengths in m, forces in N, masses in kg, velocities in m/s (SI, like the parameter vector).
"""

from __future__ import annotations

import casadi as ca

from . import fluid
from .section import SectionParameters


def unit_normal(t):
    """e_n = (-t_y, t_x): for t = e_t = (-sin phi, cos phi) this is Wang's e_n (eq. 17)."""
    return (-t[1], t[0])


def dot(a, b):
    """a . b of two 2-vectors (tuples of SX or floats)."""
    return a[0] * b[0] + a[1] * b[1]


def body_drag(P: SectionParameters, rho, r, v, t, env, depth0):
    """Drag of the body at node position r, velocity v (Wang 1971 eq. 32-35)."""
    fx, fy = fluid.fluid_velocity(r[0], depth0 + r[1], t, env)
    vr = (fx - v[0], fy - v[1])
    if P.sphere:
        return fluid.sphere_drag(rho, P.cda_n, *vr)
    return fluid.axial_body_drag(rho, P.cda_n, P.cda_t, P.phi_b, *vr)


def element_terms(P: SectionParameters, n_el: int, ra, va, rb, vb, *, rho, t, env, depth0, n_points):
    """Length, tension, lumped masses and drag shares of one element (:mod:`.segmented` describes them)."""
    h_r, h_0 = P.l_r / n_el, P.l_0 / n_el
    dx, dy = rb[0] - ra[0], rb[1] - ra[1]
    length = ca.sqrt(dx**2 + dy**2)
    et = (dx / length, dy / length)
    en = unit_normal(et)
    rate = dot((vb[0] - va[0], vb[1] - va[1]), et)                       # dl_e/dt
    strain = (length - h_0) / h_r                                          # u / l_r per element
    law = P.ae * strain + P.c_i * rate / h_r                               # eq. 46 (k u + C_I u'/l_r)
    tension = ca.fmax(P.tens, law)                                         # eq. 54, per element
    d = P.d_0 * (1 - P.thinning * strain)                                  # eq. 3
    mass = P.m_r * h_r * P.mass_on                                         # eq. 5
    added = P.gamma * rho * ca.pi * d**2 / 4 * length * P.mass_on           # eq. 23-24
    weight = P.w_r * h_r                                                   # eq. 12
    # undamped strain energy: the integral of max(TENS, k_e (l - h_0)) dl (a constant dropped)
    k_e = P.ae / h_r
    l_sw = h_0 + P.tens / k_e
    strain_energy = 0.5 * k_e * (ca.fmax(length, l_sw) - h_0) ** 2 + P.tens * ca.fmin(length - l_sw, 0.0)
    fa, fb = [0.0, 0.0], [0.0, 0.0]
    seg = length / n_points
    for k in range(n_points):                                              # eq. 30-31, 41-44
        s = (k + 0.5) / n_points
        r = (ra[0] + s * dx, ra[1] + s * dy)
        v = (va[0] + s * (vb[0] - va[0]), va[1] + s * (vb[1] - va[1]))
        ux, uy = fluid.fluid_velocity(r[0], depth0 + r[1], t, env)
        vq = (ux - v[0], uy - v[1])
        d_n = fluid.quadratic_drag(rho, P.cd * d * seg, dot(vq, en))       # eq. 42
        d_t = fluid.quadratic_drag(rho, P.ct * d * seg, dot(vq, et))       # eq. 44
        F = (d_n * en[0] + d_t * et[0], d_n * en[1] + d_t * et[1])
        for i in range(2):                                                 # virtual work shares
            fa[i] = fa[i] + (1 - s) * F[i]
            fb[i] = fb[i] + s * F[i]
    return dict(length=length, et=et, en=en, rate=rate, strain=strain, tension=tension, mass=mass,
                slack=ca.if_else(law <= P.tens, 1.0, 0.0),
                added=added, weight=weight, strain_energy=strain_energy, drag_a=fa, drag_b=fb)


def lump_kinetic(el, v_a, v_b):
    """Half the element's mass (all directions) and added mass (normal only) at each end node."""
    m, a, en = el["mass"], el["added"], el["en"]
    ke = lambda v: 0.25 * m * dot(v, v) + 0.25 * a * dot(v, en) ** 2
    return ke(v_a) + ke(v_b)


def element_inertia(P: SectionParameters, n_el: int, p, rho, t, env, depth0, n_points) -> ca.Function:
    """Lagrange's equations (Wang 1971 eq. 8-9) of one element's lumped kinetic energy alone, in its
    own end coordinates r = (r_a, r_b), v = (v_a, v_b): ``(r_a, r_b, v_a, v_b, p) -> (M_a, M_b, f_a, f_b)``,
    with M_e = d2K_e/dv2 (block diagonal: no kinetic term couples v_a and v_b) and
    f_e = dK_e/dr - (d2K_e/dv dr) v, the inertial forces of the element-normal added mass whose
    direction and size follow the nodes. The whole cable's K is the sum of these, so summing them
    node by node gives the equations :func:`lagrange.lagrange_equations` gives for the whole cable
    (tests/test_segmented_scales.py), with a smaller expression: K_e depends on the positions through
    the chord u = r_b - r_a alone, so the AD is over u and the four velocities (the right-hand side
    of the 300 m heave cable at 20 elements: 6009 operations instead of 8736)."""
    ra, rb, va, vb = (ca.SX.sym(name, 2) for name in ("ra", "rb", "va", "vb"))
    # K_e depends on the positions through the chord u = r_b - r_a only: differentiate with respect
    # to u (dK/dr_b = dK/du = -dK/dr_a, d p/dt = (dp/du) u' + (dp/dv) v')
    u = ca.SX.sym("u", 2)
    el = element_terms(P, n_el, (0.0, 0.0), (va[0], va[1]), (u[0], u[1]), (vb[0], vb[1]), rho=rho, t=t, env=env,
                       depth0=depth0, n_points=n_points)
    K = lump_kinetic(el, (va[0], va[1]), (vb[0], vb[1]))
    v = ca.vertcat(va, vb)
    mom = ca.gradient(K, v)
    M = ca.jacobian(mom, v)
    dK = ca.gradient(K, u)
    f = ca.vertcat(-dK, dK) - ca.jtimes(mom, u, vb - va)
    f = ca.substitute(f, u, rb - ra)
    M = ca.substitute(M, u, rb - ra)
    return ca.Function("element_inertia", [ra, rb, va, vb, p], [M[:2, :2], M[2:, 2:], f[:2], f[2:]])


def lump_force(el, end: str, acc):
    """Weight, drag share and minus the inertia of the element's half lumped at one end (a 2-vector)."""
    m, a, en = el["mass"], el["added"], el["en"]
    an = dot(acc, en)
    drag = el["drag_a"] if end == "a" else el["drag_b"]
    return tuple(drag[i] + (0.5 * el["weight"] if i == 1 else 0.0) - 0.5 * (m * acc[i] + a * an * en[i])
                 for i in range(2))


def norm(v):
    """|v| of a 2-vector."""
    return ca.sqrt(v[0] ** 2 + v[1] ** 2)
