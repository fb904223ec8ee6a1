"""The segmented cable: N straight, tension-only elements per section (node positions).

Wang (1971, p. 33) names the cure for a cable that bows or goes partly slack: "several
segments ... each segment has two degrees of freedom". We take as coordinates the positions
r_j = (x_j, y_j) of the free nodes (y down from the mean top depth), as lumped-mass line codes
do: node 0 of section 1 is the top (prescribed by the top motion), the last node of every
section carries that section's body (Wang's body: weight, virtual masses, drag), which is
also the top of the next section. Per element e of a section with N elements
(reference length h_r = l_r / N, zero-tension length h_0 = l_0 / N, Wang eq. 1):

- tension only, Voigt damping and the slack rule per element (Wang eq. 46, 54):
  T_e = max(TENS, (AE)_r (l_e - h_0) / h_r + C_I (dl_e/dt) / h_r); at N = 1 this is
  F_bc = k u + (C_I / l_r) u' bounded below by TENS;
- mass m_r h_r (eq. 5) and the added mass gamma rho pi d_e^2 / 4 l_e acting normal to the
  element (eq. 23-24), d_e the thinned diameter of eq. 3 with the element's own strain;
  both lumped half to each end node, so the mass matrix is block diagonal (2 x 2 per node);
- weight in water w_r h_r, constant as the element stretches (eq. 12), half to each node;
- normal and tangential quadratic drag (eq. 42, 44) at points along the element with the
  fluid velocity there (current profile, waves, system speed: eq. 26-28), shared between
  the end nodes by virtual work (a force at r = (1 - s) r_a + s r_b gives (1 - s) F and s F).

The inertia terms come from the Lagrangian by AD, element by element (:func:`_element_inertia`), gravity from eq. 15;
tension and drag are generalized forces (virtual work). One right-hand side costs O(N)
(2 x 2 solves per node) and its Jacobian is banded, so CVODES/IDAS factor it sparse.
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from ..errors import ParameterError
from ..scene import Scene
from . import fluid
from .build import EXO_LABELS, CableModel
from .params import ParameterLayout, environment_symbols, section_prefix
from .section import SectionParameters
from .segmented_kernel import kernel_ode
from .top_motion import symbolic_type, top_motion_function

SECTION_OUTPUTS = ("phi", "phi_rate", "u", "u_rate", "x_b", "x_b_rate", "y_b", "y_b_rate", "tension",
                   "tension_bottom", "tension_top")
ELEMENT_PROFILES = ("element_tension", "element_tension_rate", "element_strain", "element_slack")
NODE_PROFILES = ("node_x", "node_y")


@dataclasses.dataclass(frozen=True, eq=False)
class SegmentedModel(CableModel):
    """A :class:`CableModel` whose coordinates are node positions (``x[j]``, ``y[j]``, j = 1..).

    Same functions as the 2-DOF model; ``cable_force`` is empty (the tension law max(TENS, ...)
    is integrated directly, element by element: no switch is located, see :mod:`.segmented_post`).
    ``segments`` holds the elements per section; ``outputs`` adds the profiles
    ``element_tension[k]``, ``element_tension_rate[k]``, ``element_strain[k]``, ``element_slack[k]``
    (1 while the element's law is at or below its floor; k = 0.. over
    all elements, top to bottom), ``node_x[j]``, ``node_y[j]`` (j = 0 is the top) and their
    unstretched arc lengths ``element_s[k]`` (element mid-points) and ``node_s[j]``.
    """

    segments: tuple = ()
    accel: ca.Function | None = None          # (q, qd, e, p) -> q'' by 2 x 2 block solves
    kernel_ode: ca.Function | None = None     # the same ode from mapped element kernels (MX; .segmented_kernel)
    name: str = "segmented"
    kind: str = "segmented"                  # the model-ladder rung (integrators cap BDF at order 2 for it)

    @property
    def n_elements(self) -> int:
        return int(sum(self.segments))

    @property
    def loop_ode(self) -> ca.Function:
        """The ``ode`` a compiled explicit loop (RK4) should evaluate: the element kernel mapped over
        the elements (:mod:`.segmented_kernel`, MX: C of constant size) from
        :data:`KERNEL_MIN_ELEMENTS` elements, else the element-by-element SX ``ode``. A copy made with
        another ``ode`` (``dataclasses.replace``) must replace or clear ``kernel_ode`` too; one whose
        state size no longer matches falls back to its ``ode``."""
        if (self.kernel_ode is not None and self.n_elements >= KERNEL_MIN_ELEMENTS
                and self.kernel_ode.sparsity_in(0) == self.ode.sparsity_in(0)):
            return self.kernel_ode
        return self.ode


# From this many elements a compiled RK4 loop evaluates the element kernel (segmented_kernel): the 300 m
# heave cable, RK4 loop, us per right-hand side (gcc default flags by size): N = 20 unrolled SX 10.8 (-O0,
# 2.2 MB serialized), kernel 5.6 (-O2, compiled in 0.3 s); N = 80 unrolled 30.6 (-O0; -O1 15.0 after 13 s
# of gcc), kernel 8.5 (-O2, 0.3 s); unrolled at -O3: 4.9 (N = 20), 13.6 (N = 80, 21 s of gcc)
KERNEL_MIN_ELEMENTS = 10


def _unit_normal(t):
    """e_n = (-t_y, t_x): for t = e_t = (-sin phi, cos phi) this is Wang's e_n (eq. 17)."""
    return (-t[1], t[0])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def _body_drag(P: SectionParameters, rho, r, v, t, env, depth0):
    """Drag of the body at node position r, velocity v (Wang 1971 eq. 32-35)."""
    fx, fy = fluid.fluid_velocity(r[0], depth0 + r[1], t, env)
    vr = (fx - v[0], fy - v[1])
    if P.sphere:
        return fluid.sphere_drag(rho, P.cda_n, *vr)
    return fluid.axial_body_drag(rho, P.cda_n, P.cda_t, P.phi_b, *vr)


def _element(P: SectionParameters, n_el: int, ra, va, rb, vb, *, rho, t, env, depth0, n_points):
    """Length, tension, lumped masses and drag shares of one element (see the module docstring)."""
    h_r, h_0 = P.l_r / n_el, P.l_0 / n_el
    dx, dy = rb[0] - ra[0], rb[1] - ra[1]
    length = ca.sqrt(dx**2 + dy**2)
    et = (dx / length, dy / length)
    en = _unit_normal(et)
    rate = _dot((vb[0] - va[0], vb[1] - va[1]), et)                       # dl_e/dt
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
        d_n = fluid.quadratic_drag(rho, P.cd * d * seg, _dot(vq, en))       # eq. 42
        d_t = fluid.quadratic_drag(rho, P.ct * d * seg, _dot(vq, et))       # eq. 44
        F = (d_n * en[0] + d_t * et[0], d_n * en[1] + d_t * et[1])
        for i in range(2):                                                 # virtual work shares
            fa[i] = fa[i] + (1 - s) * F[i]
            fb[i] = fb[i] + s * F[i]
    return dict(length=length, et=et, en=en, rate=rate, strain=strain, tension=tension, mass=mass,
                slack=ca.if_else(law <= P.tens, 1.0, 0.0),
                added=added, weight=weight, strain_energy=strain_energy, drag_a=fa, drag_b=fb)


def _lump_kinetic(el, v_a, v_b):
    """Half the element's mass (all directions) and added mass (normal only) at each end node."""
    m, a, en = el["mass"], el["added"], el["en"]
    ke = lambda v: 0.25 * m * _dot(v, v) + 0.25 * a * _dot(v, en) ** 2
    return ke(v_a) + ke(v_b)


def _element_inertia(P: SectionParameters, n_el: int, p, rho, t, env, depth0, n_points) -> ca.Function:
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
    el = _element(P, n_el, (0.0, 0.0), (va[0], va[1]), (u[0], u[1]), (vb[0], vb[1]), rho=rho, t=t, env=env,
                  depth0=depth0, n_points=n_points)
    K = _lump_kinetic(el, (va[0], va[1]), (vb[0], vb[1]))
    v = ca.vertcat(va, vb)
    mom = ca.gradient(K, v)
    M = ca.jacobian(mom, v)
    dK = ca.gradient(K, u)
    f = ca.vertcat(-dK, dK) - ca.jtimes(mom, u, vb - va)
    f = ca.substitute(f, u, rb - ra)
    M = ca.substitute(M, u, rb - ra)
    return ca.Function("element_inertia", [ra, rb, va, vb, p], [M[:2, :2], M[2:, 2:], f[:2], f[2:]])


def _lump_force(el, end: str, acc):
    """Weight, drag share and minus the inertia of the element's half lumped at one end (a 2-vector)."""
    m, a, en = el["mass"], el["added"], el["en"]
    an = _dot(acc, en)
    drag = el["drag_a"] if end == "a" else el["drag_b"]
    return tuple(drag[i] + (0.5 * el["weight"] if i == 1 else 0.0) - 0.5 * (m * acc[i] + a * an * en[i])
                 for i in range(2))


def _norm(v):
    return ca.sqrt(v[0] ** 2 + v[1] ** 2)


def drag_points(scene: Scene, n_el: int) -> int:
    """Drag points per element: ``numerics.drag_segments`` shared among the section's elements (at
    least one, the element mid-point); N = 1 uses the 2-DOF model's points exactly."""
    return max(1, round(scene.numerics.drag_segments / n_el))


def build_segmented_model(scene: Scene) -> SegmentedModel:
    """Build the segmented-cable functions for ``scene`` (elements per section: ``cable.segments``).

    Parameters
    ----------
    scene : Scene
        Any scene; every value enters through the parameter vector ``p`` as for the 2-DOF model.

    Returns
    -------
    SegmentedModel
        Functions with the interface of :class:`CableModel` (``dynamics``, ``ode``, ``top``,
        ``outputs``, ``energy``, ``cable_force``) plus ``accel``.
    """
    n_sec = len(scene.sections)
    if scene.angles == "shared" and n_sec > 1:
        raise ParameterError("angles", scene.angles, "must be 'per_section' for a segmented cable (cable.segments > 1): "
                             "every element has its own inclination")
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    segs = tuple(s.cable.segments for s in scene.sections)
    n_nodes = sum(segs)
    q_labels = tuple(f"{c}[{j}]" for j in range(1, n_nodes + 1) for c in ("x", "y"))
    q, qd = ca.SX.sym("q", 2 * n_nodes), ca.SX.sym("qd", 2 * n_nodes)
    e = ca.SX.sym("e", len(EXO_LABELS))
    t, z, zd, zdd = e[0], e[1:3], e[3:5], e[5:7]
    env = environment_symbols(layout, scene)          # Wang 1971 eq. 26-28 inputs
    rho, depth0 = env["density"], env["top_depth"]
    node_r = [(z[0], z[1])] + [(q[2 * j], q[2 * j + 1]) for j in range(n_nodes)]
    node_v = [(zd[0], zd[1])] + [(qd[2 * j], qd[2 * j + 1]) for j in range(n_nodes)]

    K, V_grav, V_strain = 0.0, 0.0, 0.0
    Q = [[0.0, 0.0] for _ in range(n_nodes + 1)]            # generalized forces per node (node 0: top)
    M_nodes = [ca.SX.zeros(2, 2) for _ in range(n_nodes + 1)]     # 2 x 2 mass block per node
    F_inertia = [ca.SX.zeros(2, 1) for _ in range(n_nodes + 1)]   # inertial forces of the added mass
    weights = [0.0] * (n_nodes + 1)
    sections, elements = [], []
    j0 = 0
    for i, sec in enumerate(scene.sections):
        P = SectionParameters.from_layout(layout, section_prefix(n_sec, i), sec.body.is_sphere)
        n_el = segs[i]
        els = []
        inertia = _element_inertia(P, n_el, p, rho, t, env, depth0, drag_points(scene, n_el))
        for k in range(n_el):
            a, b = j0 + k, j0 + k + 1
            el = _element(P, n_el, node_r[a], node_v[a], node_r[b], node_v[b], rho=rho, t=t, env=env,
                          depth0=depth0, n_points=drag_points(scene, n_el))
            el.update(a=a, b=b)
            K += _lump_kinetic(el, node_v[a], node_v[b])
            Ma, Mb, fa, fb = inertia(ca.vertcat(*node_r[a]), ca.vertcat(*node_r[b]), ca.vertcat(*node_v[a]),
                                     ca.vertcat(*node_v[b]), p)
            M_nodes[a], M_nodes[b] = M_nodes[a] + Ma, M_nodes[b] + Mb
            F_inertia[a], F_inertia[b] = F_inertia[a] + fa, F_inertia[b] + fb
            weights[a] += 0.5 * el["weight"]
            weights[b] += 0.5 * el["weight"]
            V_strain += el["strain_energy"]
            for c in range(2):     # tension -T dl/dr (virtual work of eq. 46/54), drag shares
                Q[a][c] += el["tension"] * el["et"][c] + el["drag_a"][c]
                Q[b][c] += -el["tension"] * el["et"][c] + el["drag_b"][c]
            els.append(el)
        jb = j0 + n_el                                         # the body's node
        rb, vb = node_r[jb], node_v[jb]
        K += 0.5 * (P.m_bx * vb[0] ** 2 + P.m_by * vb[1] ** 2)  # eq. 16
        M_nodes[jb] = M_nodes[jb] + ca.diag(ca.vertcat(P.m_bx, P.m_by))
        weights[jb] += P.w_b
        D_b = _body_drag(P, rho, rb, vb, t, env, depth0)        # eq. 32-35
        Q[jb][0] += D_b[0]
        Q[jb][1] += D_b[1]
        sections.append(dict(P=P, top=j0, body=jb, elements=els, body_drag=D_b))
        elements += els
        j0 = jb
    V_grav = -sum(w * r[1] for w, r in zip(weights, node_r))   # eq. 15 with y down
    # Lagrange's equations node by node (element by element, see _element_inertia): M q'' = f with
    # f = generalized forces + weights (-dV/dq, eq. 15) + inertial forces of the added mass
    blocks = M_nodes[1:]
    f_nodes = [F_inertia[j] + ca.vertcat(Q[j][0], Q[j][1] + weights[j]) for j in range(1, n_nodes + 1)]
    M, f = ca.diagcat(*blocks), ca.vertcat(*f_nodes)

    # q'' node by node: M is block diagonal (2 x 2 per node); solve each block in closed form
    acc_nodes = [(zdd[0], zdd[1])]
    acc = []
    for j in range(n_nodes):
        m11, m12, m21, m22 = blocks[j][0, 0], blocks[j][0, 1], blocks[j][1, 0], blocks[j][1, 1]
        f1, f2 = f_nodes[j][0], f_nodes[j][1]
        det = m11 * m22 - m12 * m21
        ax, ay = (m22 * f1 - m12 * f2) / det, (m11 * f2 - m21 * f1) / det
        acc += [ax, ay]
        acc_nodes.append((ax, ay))
    acc = ca.vertcat(*acc)

    x = ca.vertcat(q, qd)
    xdot = ca.vertcat(qd, acc)
    out, labels = [], []
    sfx = (lambda i: "") if n_sec == 1 else (lambda i: f"_{i + 1}")
    for i, s in enumerate(sections):
        P, els = s["P"], s["elements"]
        rt, vt_, rb, vb = node_r[s["top"]], node_v[s["top"]], node_r[s["body"]], node_v[s["body"]]
        chord = (rb[0] - rt[0], rb[1] - rt[1])
        chord_v = (vb[0] - vt_[0], vb[1] - vt_[1])
        lc = _norm(chord)
        phi = ca.atan2(-chord[0], chord[1])                        # e_t = (-sin phi, cos phi), eq. 10
        phid = (chord[0] * chord_v[1] - chord[1] * chord_v[0]) / lc**2
        u, ud = lc - P.l_0, _dot(chord, chord_v) / lc
        first, last = els[0], els[-1]
        # force of the cable on its top point and on its body: the end element's tension plus the
        # half element lumped at that node (weight, drag share, minus its inertia)
        lt = _lump_force(first, "a", acc_nodes[s["top"]])
        top_force = tuple(first["tension"] * first["et"][c] + lt[c] for c in range(2))
        lb = _lump_force(last, "b", acc_nodes[s["body"]])
        bottom_force = tuple(-last["tension"] * last["et"][c] + lb[c] for c in range(2))
        out += [phi, phid, u, ud, rb[0], vb[0], rb[1], vb[1], last["tension"], _norm(bottom_force), _norm(top_force)]
        labels += [f"{name}{sfx(i)}" for name in SECTION_OUTPUTS]
    # profiles (element k top to bottom over all sections; node j = 0 the top) and their arc lengths
    T = ca.vertcat(*[el["tension"] for el in elements])
    T_rate = ca.jtimes(T, x, xdot) + ca.jacobian(T, e) @ ca.vertcat(1.0, zd, zdd, 0.0, 0.0)
    prof = {"element_tension": T, "element_tension_rate": T_rate,
            "element_strain": ca.vertcat(*[el["strain"] for el in elements]),
            "element_slack": ca.vertcat(*[el["slack"] for el in elements]),
            "node_x": ca.vertcat(*[r[0] for r in node_r]), "node_y": ca.vertcat(*[r[1] for r in node_r])}
    s_el, s_node, s0 = [], [0.0], 0.0
    for s in sections:
        P, n_el = s["P"], len(s["elements"])
        for k in range(n_el):
            s_el.append(s0 + (k + 0.5) * P.l_0 / n_el)
            s_node.append(s0 + (k + 1) * P.l_0 / n_el)
        s0 = s0 + P.l_0
    prof["element_s"], prof["node_s"] = ca.vertcat(*s_el), ca.vertcat(*s_node)
    for name, v in prof.items():
        out += [v[k] for k in range(v.shape[0])]
        labels += [f"{name}[{k}]" for k in range(v.shape[0])]

    dynamics = ca.Function("dynamics", [q, qd, e, p], [M, f], ["q", "qd", "e", "p"], ["M", "f"])
    accel = ca.Function("accel", [q, qd, e, p], [acc], ["q", "qd", "e", "p"], ["qdd"])
    top = top_motion_function(scene, layout)
    S = symbolic_type(scene)
    nq = 2 * n_nodes
    xs, ts, ps = S.sym("x", 2 * nq), S.sym("t"), S.sym("p", p.shape[0])
    ode = ca.Function("ode", [xs, ts, ps], [ca.vertcat(xs[nq:], accel(xs[:nq], xs[nq:], top(ts, ps), ps))],
                      ["x", "t", "p"], ["xdot"])
    outputs = ca.Function("outputs", [x, e, p], [ca.vertcat(*out)], ["x", "e", "p"], ["y"])
    energy = ca.Function("energy", [x, e, p], [K, V_grav + V_strain], ["x", "e", "p"], ["K", "V"])
    cable_force = ca.Function("cable_force", [x, p], [ca.SX(0, 1)], ["x", "p"], ["gap"])
    # a sampled series is an MX node inside the SX physics: no kernel form of that model
    kernel = kernel_ode(scene, lambda n_el: drag_points(scene, n_el)) if S is ca.SX else None
    return SegmentedModel(layout=layout, n_sections=n_sec, angles=scene.angles, q_labels=q_labels,
                          output_labels=tuple(labels), dynamics=dynamics, ode=ode, top=top, outputs=outputs,
                          energy=energy, cable_force=cable_force, slack_index=(), symbolic=S,
                          segments=segs, accel=accel, kernel_ode=kernel)
