"""One cable section with the body at its lower end: energies and forces (Wang 1971).

The section hangs from a top point whose position and velocity are given (the ship for
the first section, the body above for the others). Its coordinates are the angle phi with
the vertical (clockwise positive, y down) and the stretch u = l - l_0 at the lower end.
Unit vectors: tangent e_t = (-sin phi, cos phi) down the cable, normal
e_n = (-cos phi, -sin phi), so that v.e_n and v.e_t are eq. 17a and 17b. In three dimensions
(Wang 1971 p. 32) a second angle theta takes the cable out of the x-y plane (:func:`_frame`);
the same terms are written over the cable's normal directions, the plane being theta = 0.
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
    m_bz: ca.SX | None = None      # virtual mass in z, M_bvz: the 3-D equations only

    @classmethod
    def from_layout(cls, layout, prefix: str, sphere: bool, three_d: bool = False) -> "SectionParameters":
        """Section ``prefix``'s cable (``{prefix}cable.ae``, ...), body and slack switch of the parameter vector."""
        return cls.from_symbols(lambda n: layout.sym(f"{prefix}cable.{n}"), lambda n: layout.sym(f"{prefix}body.{n}"),
                                layout.sym(f"{prefix}slack"), sphere, three_d)

    @classmethod
    def for_cable(cls, layout, prefix: str) -> "SectionParameters":
        """A cable's parameters alone (``{prefix}ae``, ...: a line section of a system, model/system.py): no body at
        its lower end (its body entries 0) and no slack switch (the node model's elements have their own law)."""
        return cls.from_symbols(lambda n: layout.sym(f"{prefix}{n}"), lambda n: 0.0, 0.0, False, False)

    @classmethod
    def for_body(cls, layout, prefix: str, sphere: bool, three_d: bool) -> "SectionParameters":
        """A point body's parameters alone (``{prefix}weight``, ...: a body or junction of a system, model/system.py),
        its cable entries 0."""
        return cls.from_symbols(lambda n: 0.0, lambda n: layout.sym(f"{prefix}{n}"), 0.0, sphere, three_d)

    @classmethod
    def from_symbols(cls, c, b, slack, sphere: bool, three_d: bool) -> "SectionParameters":
        """From the lookups ``c(name)`` of the cable's and ``b(name)`` of the body's entries."""
        return cls(l_r=c("length"), T_r=c("tension_ref"), ae=c("ae"), d_r=c("diameter"),
                   m_r=c("mass_per_length"), w_r=c("weight_per_length"), thinning=c("thinning_ratio"),
                   gamma=c("added_mass_factor"), cd=c("cd_normal"), ct=c("ct_tangential"),
                   c_i=c("internal_damping"), tens=c("tension_floor"), cbmas=c("cable_mass_switch"),
                   w_b=b("weight"), m_bx=b("mass_x"), m_by=b("mass_y"), cda_n=b("drag_area_normal"),
                   cda_t=b("drag_area_tangential"), phi_b=b("axis_angle"), slack=slack, sphere=sphere,
                   m_bz=b("mass_z") if three_d else None)

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


def dot(a, b):
    """a . b of two tuples of 2 or 3 components (vectors of the plane or of space)."""
    return sum((a[j] * b[j] for j in range(1, len(a))), a[0] * b[0])


def _frame(phi, theta, phid, thetad):
    """Unit tangent e_t down the cable and its normal directions, each with its swing rate.

    Plane (``theta`` None): e_t = (-sin phi, cos phi), the one normal e_n = (-cos phi, -sin phi),
    de_t/dt = phi' e_n. Space (Wang 1971 p. 32, "allow the cable to swing out of the vertical
    plane"): e_t = (-sin phi cos theta, cos phi cos theta, sin theta), theta the angle out of the x-y
    plane; the orthonormal frame (e_t, e_n, e_b) with e_n = (-cos phi, -sin phi, 0) and
    e_b = de_t/dtheta = (sin phi sin theta, -cos phi sin theta, cos theta) gives
    de_t/dt = phi' cos theta e_n + theta' e_b. Returns e_t and [(normal n_k, rate de_t/dt . n_k)].
    """
    s, c = ca.sin(phi), ca.cos(phi)
    if theta is None:
        return (-s, c), [((-c, -s), phid)]
    st, ct = ca.sin(theta), ca.cos(theta)
    return (-s * ct, c * ct, st), [((-c, -s, 0.0), phid * ct), ((s * st, -c * st, ct), thetad)]


def section_terms(P: SectionParameters, top_r, top_v, phi, u, phid, ud, *, t, env, rho, n_segments,
                  theta=None, thetad=None):
    """Kinetic and potential energy, point forces and direct generalized forces of one section.

    ``top_r`` is (x, depth) of the section top (depth = y + top depth, y down); ``top_v`` its
    velocity. Returns a dict with K, V, point_forces [(velocity, force)], Q_u (acting on u
    only), r_b, v_b and F_bc, and for the end forces of the chain (Newton's second law on the
    virtual masses of eq. 16, 22-25): ``momentum`` and ``external_force`` of the section (cable
    and body: weights in water and drag, N), ``body_momentum`` and ``body_external_force`` of the
    body alone (its weight W_b and drag, eq. 15, 32-35). The body's balance also needs the pull
    of the section hanging below it, which this section does not know: the chain adds it
    (:func:`cablesys.model.build._end_forces`).

    In three dimensions (Wang 1971 p. 32, "Extensions") ``theta``/``thetad`` are the angle out of
    the x-y plane and its rate, ``top_r`` is (x, depth, z) and every vector has three components
    (:func:`_frame`). The same energies and forces hold with the plane's single normal replaced by
    the two normals of the cable: the velocity along the straight cable is linear in the arc
    length, so each normal direction n_k with end rate w_k = l (de_t/dt . n_k) adds
    1/2 M_cv (v_sk^2 + v_sk w_k + w_k^2 / 3) to the kinetic energy (eq. 22-25 for each), the body
    has a virtual mass M_bvz in z, and the normal drag takes the size of the whole normal relative
    velocity (:func:`fluid.crossflow_drag`). theta = 0 is the plane.
    """
    space = theta is not None
    e_t, frame = _frame(phi, theta, phid, thetad)
    normals = [n for n, _ in frame]
    dim = len(e_t)
    l = P.l_0 + u
    r_b = tuple(top_r[j] + l * e_t[j] for j in range(dim))                                   # eq. 10b, 10d
    swing = [tuple(l * w * n[j] for j in range(dim)) for n, w in frame]                     # l de_t/dt per normal
    rel = tuple(sum((sw[j] for sw in swing[1:]), ud * e_t[j] + swing[0][j]) for j in range(dim))
    v_b = tuple(sum((sw[j] for sw in swing[1:]), top_v[j] + ud * e_t[j] + swing[0][j]) for j in range(dim))  # eq. 11a-b

    # kinetic energy, eq. 16, 22, 24 (eq. 25 summed), one normal term per normal direction
    v_st = dot(top_v, e_t)                                                                   # eq. 17b
    m_cv = P.m_c + P.added_mass(u, rho)                                                       # M_cv below eq. 25
    masses = (P.m_bx, P.m_by) + ((P.m_bz,) if space else ())
    K = (0.5 * sum((masses[j] * v_b[j] ** 2 for j in range(1, dim)), masses[0] * v_b[0] ** 2)
         + 0.5 * P.m_c * (v_st ** 2 + v_st * ud + ud ** 2 / 3))
    for n, w in frame:
        v_sn = dot(top_v, n)                                                                 # eq. 17a
        K = K + 0.5 * m_cv * (v_sn ** 2 + v_sn * l * w + l ** 2 * w ** 2 / 3)
    # potential energy, eq. 15: gravity of body and cable mid-point, strain energy k u^2 / 2 (eq. 14)
    V = -P.w_b * r_b[1] - P.w_c * (top_r[1] + 0.5 * l * e_t[1]) + 0.5 * P.k * u ** 2

    def flow(r):
        return fluid.fluid_velocity_3d(r[0], r[1], r[2], t, env) if space else fluid.fluid_velocity(r[0], r[1], t, env)

    # body drag, eq. 32 (sphere) or 33-35 (cylinder/disk); generalized forces eq. 37 by virtual work
    vr = tuple(a - b for a, b in zip(flow(r_b), v_b))
    if P.sphere:
        d_b = fluid.sphere_drag(rho, P.cda_n, *vr)
    elif space:
        d_b = fluid.axial_body_drag_3d(rho, P.cda_n, P.cda_t, P.phi_b, *vr)
    else:
        d_b = fluid.axial_body_drag(rho, P.cda_n, P.cda_t, P.phi_b, *vr)
    point_forces = [(v_b, d_b)]

    # cable drag on N segments, fluid taken at segment midpoints (eq. 30-31, 38-45)
    d = P.diameter(u)
    seg = l / n_segments
    d_t_sum = 0.0
    for i in range(1, n_segments + 1):
        frac = (i - 0.5) / n_segments
        r_ci = tuple(top_r[j] + frac * l * e_t[j] for j in range(dim))                      # eq. 30a-b
        v_ci = tuple(top_v[j] + frac * rel[j] for j in range(dim))                          # eq. 38a-b
        vq = tuple(a - b for a, b in zip(flow(r_ci), v_ci))                                 # eq. 41
        d_n = fluid.crossflow_drag(rho, P.cd * d * seg, [dot(vq, n) for n in normals])   # eq. 42
        d_t_sum = d_t_sum + fluid.quadratic_drag(rho, P.ct * d * seg, dot(vq, e_t))  # eq. 44
        point_forces.append((v_ci, tuple(sum((dk * n[j] for dk, n in zip(d_n[1:], normals[1:])),
                                             d_n[0] * normals[0][j]) for j in range(dim))))  # moment arm: eq. 43
    # eq. 45 adds the whole tangential drag to Q_u: the same as applying it at the lower end
    point_forces.append((v_b, tuple(d_t_sum * e_t[j] for j in range(dim))))

    # Voigt internal damping (eq. 46) and the slack rule F_bc >= TENS (eq. 54): while the
    # section is slack (P.slack = 1) spring and damper are replaced by the constant TENS.
    F_bc = P.cable_force(u, ud)
    Q_u = -P.c_i / P.l_r * ud + P.slack * (F_bc - P.tens)

    # Momentum and external force of the section (cable + its body), for the top tension.
    # Cable: the velocity field is linear along the cable (eq. 38 with frac = s/l), so its
    # momentum is that of the mid-point velocity, with the mass M_c along e_t and the virtual
    # mass M_cv = M_c + added mass along the normals (the same split as the kinetic energy, eq. 22-25).
    # Body: virtual masses M_bvx, M_bvy (M_bvz) (eq. 16). External: weights in water (eq. 12, 15) and
    # every drag force of this section (body eq. 32-35, cable eq. 42, 44).
    v_m = tuple(0.5 * (top_v[j] + v_b[j]) for j in range(dim))
    vm_t, vm_n = dot(v_m, e_t), [dot(v_m, n) for n in normals]
    body_momentum = tuple(masses[j] * v_b[j] for j in range(dim))
    momentum = tuple(P.m_c * vm_t * e_t[j]
                     + sum((m_cv * c * n[j] for c, n in zip(vm_n[1:], normals[1:])), m_cv * vm_n[0] * normals[0][j])
                     + body_momentum[j] for j in range(dim))
    ext = [sum((F[j] for _, F in point_forces), 0.0) for j in range(dim)]
    ext[1] = ext[1] + P.w_b + P.w_c
    body_ext = tuple(d_b[j] + P.w_b if j == 1 else d_b[j] for j in range(dim))
    return dict(K=K, V=V, point_forces=point_forces, Q_u=Q_u, r_b=r_b, v_b=v_b, F_bc=F_bc,
                tension=F_bc + P.slack * (P.tens - F_bc), l=l, m_cv=m_cv,
                momentum=momentum, external_force=tuple(ext),
                body_momentum=body_momentum, body_external_force=body_ext, e_t=e_t)
