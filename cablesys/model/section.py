"""One cable section with the body at its lower end: energies and forces (Wang 1971).

The section hangs from a top point whose position and velocity are given (the ship for
the first section, the body above for the others). Its coordinates are the angle phi with
the vertical (clockwise positive, y down) and the stretch u = l - l_0 at the lower end.
Unit vectors: tangent e_t = (-sin phi, cos phi) down the cable, normal
e_n = (-cos phi, -sin phi), so that v.e_n and v.e_t are eq. 17a and 17b.
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from . import fluid


@dataclasses.dataclass(frozen=True)
class SectionParameters:
    """Symbolic parameters of one section and the zero-tension quantities (eq. 1-7)."""

    l_r: ca.SX
    T_r: ca.SX
    ae: ca.SX
    d_r: ca.SX
    m_r: ca.SX
    w_r: ca.SX
    thinning: ca.SX
    gamma: ca.SX
    cd: ca.SX
    ct: ca.SX
    c_i: ca.SX
    tens: ca.SX
    cbmas: ca.SX
    w_b: ca.SX
    m_bx: ca.SX
    m_by: ca.SX
    cda_n: ca.SX
    cda_t: ca.SX
    phi_b: ca.SX
    slack: ca.SX
    sphere: bool

    @classmethod
    def from_layout(cls, layout, prefix: str, sphere: bool) -> "SectionParameters":
        c = lambda n: layout.sym(f"{prefix}cable.{n}")
        b = lambda n: layout.sym(f"{prefix}body.{n}")
        return cls(l_r=c("length"), T_r=c("tension_ref"), ae=c("ae"), d_r=c("diameter"),
                   m_r=c("mass_per_length"), w_r=c("weight_per_length"), thinning=c("thinning_ratio"),
                   gamma=c("added_mass_factor"), cd=c("cd_normal"), ct=c("ct_tangential"),
                   c_i=c("internal_damping"), tens=c("tension_floor"), cbmas=c("cable_mass_switch"),
                   w_b=b("weight"), m_bx=b("mass_x"), m_by=b("mass_y"), cda_n=b("drag_area_normal"),
                   cda_t=b("drag_area_tangential"), phi_b=b("axis_angle"),
                   slack=layout.sym(f"{prefix}slack"), sphere=sphere)

    @property
    def k(self):
        """Spring constant k = (AE)_r / l_r (Wang 1971, below eq. 1)."""
        return self.ae / self.l_r

    @property
    def l_0(self):
        """Zero-tension length l_0 = l_r - T_r / k (eq. 1)."""
        return self.l_r - self.T_r / self.k

    @property
    def d_0(self):
        """Zero-tension thickness d_0 = d_r (1 - p T_r / (k l_r)) (eq. 4)."""
        return self.d_r * (1 - self.thinning * self.T_r / (self.k * self.l_r))

    @property
    def mass_on(self):
        """The report's CBMAS switch: 0 drops cable mass and added mass when CBMAS < 0."""
        return ca.if_else(self.cbmas >= 0, 1.0, 0.0)

    @property
    def m_c(self):
        """Cable mass M_c = m_0 l_0 = m_r l_r (eq. 5, 7)."""
        return self.m_r * self.l_r * self.mass_on

    @property
    def w_c(self):
        """Cable weight in water W_c, held constant as the cable stretches (eq. 12)."""
        return self.w_r * self.l_r

    def diameter(self, u):
        """Thickness d = d_0 (1 - p u / l_r) (eq. 3)."""
        return self.d_0 * (1 - self.thinning * u / self.l_r)

    def added_mass(self, u, rho):
        """Added mass of the whole cable, gamma rho pi d^2/4 (l_0 + u) (eq. 23-24)."""
        return self.gamma * rho * ca.pi * self.diameter(u) ** 2 / 4 * (self.l_0 + u) * self.mass_on

    def cable_force(self, u, ud):
        """F_bc = k u + (C_I / l_r) du/dt, the pull of the body on the cable (eq. 54)."""
        return self.k * u + self.c_i / self.l_r * ud


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def section_terms(P: SectionParameters, top_r, top_v, phi, u, phid, ud, *, t, env, rho, n_segments):
    """Kinetic and potential energy, point forces and direct generalized forces of one section.

    ``top_r`` is (x, depth) of the section top (depth = y + top depth, y down); ``top_v`` its
    velocity. Returns a dict with K, V, point_forces [(velocity, force)], Q_u (acting on u
    only), r_b, v_b and F_bc, and for the end forces of the chain (Newton's second law on the
    virtual masses of eq. 16, 22-25): ``momentum`` and ``external_force`` of the section (cable
    and body: weights in water and drag, N), ``body_momentum`` and ``body_external_force`` of the
    body alone (its weight W_b and drag, eq. 15, 32-35). The body's balance also needs the pull
    of the section hanging below it, which this section does not know: the chain adds it
    (:func:`cablesys.model.build._end_forces`).
    """
    s, c = ca.sin(phi), ca.cos(phi)
    e_t, e_n = (-s, c), (-c, -s)
    l = P.l_0 + u
    r_b = (top_r[0] + l * e_t[0], top_r[1] + l * e_t[1])                        # eq. 10b, 10d
    v_b = (top_v[0] + ud * e_t[0] + l * phid * e_n[0],
           top_v[1] + ud * e_t[1] + l * phid * e_n[1])                          # eq. 11a-b

    # kinetic energy, eq. 16, 22, 24 (eq. 25 summed)
    v_st, v_sn = _dot(top_v, e_t), _dot(top_v, e_n)                            # eq. 17a-b
    m_cv = P.m_c + P.added_mass(u, rho)                                         # M_cv below eq. 25
    K = (0.5 * (P.m_bx * v_b[0] ** 2 + P.m_by * v_b[1] ** 2)
         + 0.5 * P.m_c * (v_st ** 2 + v_st * ud + ud ** 2 / 3)
         + 0.5 * m_cv * (v_sn ** 2 + v_sn * l * phid + l ** 2 * phid ** 2 / 3))
    # potential energy, eq. 15: gravity of body and cable mid-point, strain energy k u^2 / 2 (eq. 14)
    V = -P.w_b * r_b[1] - P.w_c * (top_r[1] + 0.5 * l * c) + 0.5 * P.k * u ** 2

    # body drag, eq. 32 (sphere) or 33-35 (cylinder/disk); generalized forces eq. 37 by virtual work
    fx, fy = fluid.fluid_velocity(r_b[0], r_b[1], t, env)
    vr = (fx - v_b[0], fy - v_b[1])
    if P.sphere:
        d_b = fluid.sphere_drag(rho, P.cda_n, *vr)
    else:
        d_b = fluid.axial_body_drag(rho, P.cda_n, P.cda_t, P.phi_b, *vr)
    point_forces = [(v_b, d_b)]

    # cable drag on N segments, fluid taken at segment midpoints (eq. 30-31, 38-45)
    d = P.diameter(u)
    seg = l / n_segments
    d_t_sum = 0.0
    for i in range(1, n_segments + 1):
        frac = (i - 0.5) / n_segments
        r_ci = (top_r[0] + frac * l * e_t[0], top_r[1] + frac * l * e_t[1])          # eq. 30a-b
        v_ci = (top_v[0] + frac * (ud * e_t[0] + l * phid * e_n[0]),
                top_v[1] + frac * (ud * e_t[1] + l * phid * e_n[1]))               # eq. 38a-b
        fx, fy = fluid.fluid_velocity(r_ci[0], r_ci[1], t, env)
        vq = (fx - v_ci[0], fy - v_ci[1])                                           # eq. 41
        d_n = fluid.quadratic_drag(rho, P.cd * d * seg, _dot(vq, e_n))             # eq. 42
        d_t_sum = d_t_sum + fluid.quadratic_drag(rho, P.ct * d * seg, _dot(vq, e_t))  # eq. 44
        point_forces.append((v_ci, (d_n * e_n[0], d_n * e_n[1])))                  # moment arm: eq. 43
    # eq. 45 adds the whole tangential drag to Q_u: the same as applying it at the lower end
    point_forces.append((v_b, (d_t_sum * e_t[0], d_t_sum * e_t[1])))

    # Voigt internal damping (eq. 46) and the slack rule F_bc >= TENS (eq. 54): while the
    # section is slack (P.slack = 1) spring and damper are replaced by the constant TENS.
    F_bc = P.cable_force(u, ud)
    Q_u = -P.c_i / P.l_r * ud + P.slack * (F_bc - P.tens)

    # Momentum and external force of the section (cable + its body), for the top tension.
    # Cable: the velocity field is linear along the cable (eq. 38 with frac = s/l), so its
    # momentum is that of the mid-point velocity, with the mass M_c along e_t and the virtual
    # mass M_cv = M_c + added mass along e_n (the same split as the kinetic energy, eq. 22-25).
    # Body: virtual masses M_bvx, M_bvy (eq. 16). External: weights in water (eq. 12, 15) and
    # every drag force of this section (body eq. 32-35, cable eq. 42, 44).
    v_m = (0.5 * (top_v[0] + v_b[0]), 0.5 * (top_v[1] + v_b[1]))
    vm_t, vm_n = _dot(v_m, e_t), _dot(v_m, e_n)
    body_momentum = (P.m_bx * v_b[0], P.m_by * v_b[1])
    momentum = (P.m_c * vm_t * e_t[0] + m_cv * vm_n * e_n[0] + body_momentum[0],
                P.m_c * vm_t * e_t[1] + m_cv * vm_n * e_n[1] + body_momentum[1])
    fx_ext = sum((F[0] for _, F in point_forces), 0.0)
    fy_ext = sum((F[1] for _, F in point_forces), 0.0) + P.w_b + P.w_c
    return dict(K=K, V=V, point_forces=point_forces, Q_u=Q_u, r_b=r_b, v_b=v_b, F_bc=F_bc,
                tension=F_bc + P.slack * (P.tens - F_bc), l=l, m_cv=m_cv,
                momentum=momentum, external_force=(fx_ext, fy_ext),
                body_momentum=body_momentum, body_external_force=(d_b[0], d_b[1] + P.w_b), e_t=e_t)
