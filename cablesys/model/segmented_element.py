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
    """a . b of two 2- or 3-vectors (tuples of SX or floats); the plane's a0 b0 + a1 b1 unchanged."""
    return sum((a[j] * b[j] for j in range(2, len(a))), a[0] * b[0] + a[1] * b[1])


def normal_part(v, et, en=None):
    """The part of v normal to the element of unit tangent ``et``: (v . e_n) e_n in the plane (eq. 17a, ``en``
    its unit normal), v - (v . e_t) e_t in space (the same vector when v lies in the plane)."""
    if len(v) == 2:
        vn = dot(v, en)
        return (vn * en[0], vn * en[1])
    vt = dot(v, et)
    return tuple(v[j] - vt * et[j] for j in range(3))


def normal_square(v, et, en=None):
    """|v_n|^2 of :func:`normal_part`: (v . e_n)^2 in the plane, |v|^2 - (v . e_t)^2 in space."""
    if len(v) == 2:
        return dot(v, en) ** 2
    return dot(v, v) - dot(v, et) ** 2


def flow_at(r, t, env, depth0):
    """The fluid velocity at node-frame point r (y down from the mean top depth): eq. 26-28 in the plane,
    the current and waves with their headings in space (:func:`.fluid.fluid_velocity_3d`)."""
    if len(r) == 2:
        return fluid.fluid_velocity(r[0], depth0 + r[1], t, env)
    return fluid.fluid_velocity_3d(r[0], depth0 + r[1], r[2], t, env)


def body_drag(P: SectionParameters, rho, r, v, t, env, depth0):
    """Drag of the body at node position r, velocity v (Wang 1971 eq. 32-35; in space the sphere's drag
    along the relative flow, eq. 32, or the cylinder's cross-flow drag, :func:`.fluid.axial_body_drag_3d`)."""
    u = flow_at(r, t, env, depth0)
    vr = tuple(u[j] - v[j] for j in range(len(r)))
    if P.sphere:
        return fluid.sphere_drag(rho, P.cda_n, *vr)
    if len(r) == 3:
        return fluid.axial_body_drag_3d(rho, P.cda_n, P.cda_t, P.phi_b, *vr)
    return fluid.axial_body_drag(rho, P.cda_n, P.cda_t, P.phi_b, *vr)


def element_terms(P: SectionParameters, n_el: int, ra, va, rb, vb, *, rho, t, env, depth0, n_points):
    """Length, tension, lumped masses and drag shares of one element (:mod:`.segmented` describes them).

    Node positions and velocities are 2-vectors in the plane, 3-vectors (x, y, z) in space; the
    element's laws do not depend on the dimension: the normal drag is the cross-flow law (Wang 1971
    eq. 42; :func:`.fluid.crossflow_drag`), 1/2 rho C_D d ds |v_n| v_n with v_n the part of the relative
    velocity normal to the element, in the plane (v . e_n) e_n as eq. 42 writes it; the added mass
    acts on the normal part of the velocity (eq. 23-24)."""
    dim = len(ra)
    h_r, h_0 = P.l_r / n_el, P.l_0 / n_el
    dr = tuple(rb[j] - ra[j] for j in range(dim))
    dx, dy = dr[0], dr[1]
    length = ca.sqrt(sum((dr[j] ** 2 for j in range(2, dim)), dx**2 + dy**2))
    et = tuple(dr[j] / length for j in range(dim))
    en = unit_normal(et) if dim == 2 else None
    rate = dot(tuple(vb[j] - va[j] for j in range(dim)), et)             # dl_e/dt
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
    fa, fb = [0.0] * dim, [0.0] * dim
    seg = length / n_points
    for k in range(n_points):                                              # eq. 30-31, 41-44
        s = (k + 0.5) / n_points
        r = tuple(ra[j] + s * dr[j] for j in range(dim))
        v = tuple(va[j] + s * (vb[j] - va[j]) for j in range(dim))
        u = flow_at(r, t, env, depth0)
        vq = tuple(u[j] - v[j] for j in range(dim))
        d_t = fluid.quadratic_drag(rho, P.ct * d * seg, dot(vq, et))       # eq. 44
        if dim == 2:
            d_n = fluid.quadratic_drag(rho, P.cd * d * seg, dot(vq, en))   # eq. 42
            F = (d_n * en[0] + d_t * et[0], d_n * en[1] + d_t * et[1])
        else:                                                              # eq. 42, cross-flow in space
            D_n = fluid.crossflow_drag(rho, P.cd * d * seg, list(normal_part(vq, et)))
            F = tuple(D_n[j] + d_t * et[j] for j in range(3))
        for i in range(dim):                                               # virtual work shares
            fa[i] = fa[i] + (1 - s) * F[i]
            fb[i] = fb[i] + s * F[i]
    return dict(length=length, et=et, en=en, rate=rate, strain=strain, tension=tension, mass=mass,
                slack=ca.if_else(law <= P.tens, 1.0, 0.0),
                added=added, weight=weight, strain_energy=strain_energy, drag_a=fa, drag_b=fb)


def lump_kinetic(el, v_a, v_b):
    """Half the element's mass (all directions) and added mass (normal only) at each end node."""
    m, a = el["mass"], el["added"]
    ke = lambda v: 0.25 * m * dot(v, v) + 0.25 * a * normal_square(v, el["et"], el["en"])
    return ke(v_a) + ke(v_b)


def element_inertia(P: SectionParameters, n_el: int, p, rho, t, env, depth0, n_points, dim: int = 2) -> ca.Function:
    """Lagrange's equations (Wang 1971 eq. 8-9) of one element's lumped kinetic energy alone, in its
    own end coordinates r = (r_a, r_b), v = (v_a, v_b): ``(r_a, r_b, v_a, v_b, p) -> (M_a, M_b, f_a, f_b)``,
    with M_e = d2K_e/dv2 (block diagonal: no kinetic term couples v_a and v_b) and
    f_e = dK_e/dr - (d2K_e/dv dr) v, the inertial forces of the element-normal added mass whose
    direction and size follow the nodes. The whole cable's K is the sum of these, so summing them
    node by node gives the equations :func:`lagrange.lagrange_equations` gives for the whole cable
    (tests/test_segmented_scales.py), with a smaller expression: K_e depends on the positions through
    the chord u = r_b - r_a alone, so the AD is over u and the four velocities (the right-hand side
    of the 300 m heave cable at 20 elements: 6009 operations instead of 8736). The velocities are the nodes' over
    the ground, as Wang's eq. 23-24 write the cable's normal kinetic energy with the ship's velocity in it: a cable
    moving obliquely through still water feels each element's Munk couple, one at rest in a current does not
    (:mod:`cablesys.statics.tow`; tests/test_tracks.py measures the two frames' difference)."""
    ra, rb, va, vb = (ca.SX.sym(name, dim) for name in ("ra", "rb", "va", "vb"))
    # K_e depends on the positions through the chord u = r_b - r_a only: differentiate with respect
    # to u (dK/dr_b = dK/du = -dK/dr_a, d p/dt = (dp/du) u' + (dp/dv) v')
    u = ca.SX.sym("u", dim)
    cols = lambda s: tuple(s[j] for j in range(dim))
    el = element_terms(P, n_el, (0.0,) * dim, cols(va), cols(u), cols(vb), rho=rho, t=t, env=env,
                       depth0=depth0, n_points=n_points)
    K = lump_kinetic(el, cols(va), cols(vb))
    v = ca.vertcat(va, vb)
    mom = ca.gradient(K, v)
    M = ca.jacobian(mom, v)
    dK = ca.gradient(K, u)
    f = ca.vertcat(-dK, dK) - ca.jtimes(mom, u, vb - va)
    f = ca.substitute(f, u, rb - ra)
    M = ca.substitute(M, u, rb - ra)
    return ca.Function("element_inertia", [ra, rb, va, vb, p], [M[:dim, :dim], M[dim:, dim:], f[:dim], f[dim:]])


def block_solve(m, f) -> tuple:
    """x with m x = f for one node's 2 x 2 or 3 x 3 mass block, in closed form (Cramer's rule)."""
    if m.shape[0] == 2:
        m11, m12, m21, m22 = m[0, 0], m[0, 1], m[1, 0], m[1, 1]
        f1, f2 = f[0], f[1]
        det = m11 * m22 - m12 * m21
        return (m22 * f1 - m12 * f2) / det, (m11 * f2 - m21 * f1) / det
    cof = [[m[(r + 1) % 3, (c + 1) % 3] * m[(r + 2) % 3, (c + 2) % 3] - m[(r + 1) % 3, (c + 2) % 3] * m[(r + 2) % 3, (c + 1) % 3]
            for c in range(3)] for r in range(3)]                  # cofactors C_rc
    det = m[0, 0] * cof[0][0] + m[0, 1] * cof[0][1] + m[0, 2] * cof[0][2]
    return tuple((cof[0][c] * f[0] + cof[1][c] * f[1] + cof[2][c] * f[2]) / det for c in range(3))   # adj = C^T


def lump_force(el, end: str, acc):
    """Weight, drag share and minus the inertia of the element's half lumped at one end (a 2- or 3-vector)."""
    m, a = el["mass"], el["added"]
    drag = el["drag_a"] if end == "a" else el["drag_b"]
    if len(acc) == 2:
        an, en = dot(acc, el["en"]), el["en"]
        return tuple(drag[i] + (0.5 * el["weight"] if i == 1 else 0.0) - 0.5 * (m * acc[i] + a * an * en[i])
                     for i in range(2))
    an = normal_part(acc, el["et"], el["en"])
    return tuple(drag[i] + (0.5 * el["weight"] if i == 1 else 0.0) - 0.5 * (m * acc[i] + a * an[i])
                 for i in range(3))


def norm(v):
    """|v| of a 2- or 3-vector."""
    return ca.sqrt(sum((v[j] ** 2 for j in range(2, len(v))), v[0] ** 2 + v[1] ** 2))
