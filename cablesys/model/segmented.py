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

An ``[anchor]`` fixes the last section's lower node at (anchor.x, anchor.y) instead of a free body
(that node is then no coordinate, and the last section's body sits at the anchor: its weight and
drag load the anchor, not the line); a ``[seabed]`` acts on every free node with normal contact
and regularised Coulomb friction (:mod:`.segmented_seabed`, MoorDyn's seabed model). With a
seabed, ``static_force`` is the statics' own right-hand side at rest: elements elastic both ways
(a line laid unstretched on the bed has zero tension, not an undetermined slack length) and the
laid-down line's friction (:func:`.segmented_seabed.seabed_forces`); without one it is None and the
statics use ``dynamics``. Scenes with a seabed evaluate the element-by-element
``ode`` (no mapped kernel; an anchored line has it, its last node the anchor's parameters). A ``[winch]`` changes the first section's zero-tension length in time, its
elements sharing L(t) uniformly (:mod:`.segmented_winch`: material velocities for the element terms and the
seabed's contact, L a prescribed coordinate in Lagrange's equations; element-by-element ``ode`` too), with a free body
or an anchor at the line's lower end.

In three dimensions (``scene.three_d``: Wang 1971 p. 32, "allow the cable to swing out of the vertical
plane") the same elements and bodies are built with node positions r_j = (x_j, y_j, z_j), z the sway
(q labels ``x[j]``, ``y[j]``, ``z[j]``, e = :data:`.top_motion.EXO_LABELS_3D`): the normal drag by the
cross-flow principle on the part of the relative velocity normal to the element (eq. 42; in the plane
exactly eq. 42's (v . e_n) e_n), the added mass on the normal part of the node velocities, the current
and waves with their headings (:func:`.fluid.fluid_velocity_3d`), the body's virtual mass M_bvz and its
3-D drag (eq. 32-35, :func:`.fluid.axial_body_drag_3d`); 3 x 3 blocks per node. A planar scene builds the
planar equations (2 x 2 blocks); both have the mapped kernel (:mod:`.segmented_kernel`); in 3-D an
``[anchor]`` holds the node at (anchor.x, anchor.y, anchor.z) and the ``[seabed]`` is a plane sloping towards
``seabed.heading_deg`` with friction along and across the line (:mod:`.segmented_seabed`; output profiles add
``seabed_friction_lateral[j]``). Outputs add Wang's 3-D
``phi_z``, ``phi_z_rate``, ``z_b``, ``z_b_rate`` per section and the profile ``node_z[j]``.

A rigid body (``body.pitch_inertia`` set; Wang 1971 p. 32, body rotation "where the body is fairly large
and the cable is not attached to the center of mass") pitches in the plane and turns freely in space: its node
is the cable's attachment point and its orientation more coordinates after the nodes, the pitch ``theta_b`` in
the plane, a quaternion ``quat_w_b``, ``quat_x_b``, ``quat_y_b``, ``quat_z_b`` in space (``_<i>`` appended in a
chain), node and orientation sharing one mass block (3 x 3 in the plane, 7 x 7 in space); its kinetic and
potential energy, generalized forces and the quaternion's norm constraint are in :mod:`.rigid_body` (one
formulation: a planar scene run in space is the pitching body with the quaternion about z). Outputs add
``theta_b``, ``theta_b_rate``, ``x_cg``, ``x_cg_rate``, ``y_cg``, ``y_cg_rate`` per rigid body (``x_b``, ``y_b`` stay
the attachment point), in space also the roll and yaw (``theta_b`` then the pitch of the sequence of
:func:`.rigid_body.attitude`) and their rates, ``z_cg``, ``z_cg_rate``, the body-axis rates ``omega_x_b``,
``omega_y_b``, ``omega_z_b`` and the unit quaternion. Such scenes evaluate the element-by-element ``ode`` (no
mapped kernel).

The element's terms are in :mod:`.segmented_element` (shared with the mapped kernel of
:mod:`.segmented_kernel`). The inertia terms come from the Lagrangian by AD, element by element
(:func:`.segmented_element.element_inertia`), gravity from eq. 15; tension and drag are
generalized forces (virtual work). One right-hand side costs O(N) (2 x 2 solves per node) and
its Jacobian is banded, so CVODES/IDAS factor it sparse.
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from ..errors import ParameterError
from ..scene import Scene
from .cable_model import CableModel
from .params import ParameterLayout, environment_symbols, section_prefix
from .rigid_assembly import (RIGID_OUTPUTS, RIGID_OUTPUTS_3D, assemble, node_acceleration,  # noqa: F401 (re-exported)
                             orientation_names, rigid_block, rigid_outputs)
from .rigid_body import ORIENTATION_REST
from .section import SectionParameters
from .node_terms import NodeSums
from .segmented_element import block_solve, dot, lump_force, norm
from .segmented_kernel import kernel_jacobian, kernel_ode
from .segmented_seabed import seabed_forces
from .segmented_winch import WINCH_OUTPUTS, Payout, payout
from .signals import CHORD_NAMES, EXO_LABELS, OUTPUT_NAMES
from .top_motion import EXO_LABELS_3D, symbolic_type, top_motion_function

ELEMENT_PROFILES = ("element_tension", "element_tension_rate", "element_strain", "element_slack")
NODE_PROFILES = ("node_x", "node_y")
# a section's outputs in 3-D besides the planar ones: the chord's angle out of the x-y plane (rad) and its
# rate, the body's sway z_b (m, from the top's mean position) and its rate (the names of Wang's 3-D model)
OUTPUTS_3D = ("phi_z", "phi_z_rate", "z_b", "z_b_rate")


@dataclasses.dataclass(frozen=True, eq=False)
class SegmentedModel(CableModel):
    """A :class:`CableModel` whose coordinates are node positions (``x[j]``, ``y[j]``, j = 1..; ``z[j]`` too in 3-D).

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
    anchored: bool = False                    # the last section's lower node fixed at [anchor] (not in q)
    static_force: ca.Function | None = None   # (q, qd, e, p) -> f at rest with the seabed's static laws
                                              # (elements elastic both ways, laid-down friction); None: ``dynamics``
    kernel_ode: ca.Function | None = None     # the same ode from mapped element kernels (MX; .segmented_kernel)
    kernel_jacobian: ca.Function | None = None   # (x, t, p) -> d kernel_ode / d x, sparse, by the chain rule over
                                                 # the elements' AD (.segmented_kernel.kernel_jacobian)
    name: str = "segmented"
    kind: str = "segmented"                  # the model-ladder rung (integrators cap BDF at order 2 for it)
    dim: int = 2                              # coordinates per node: 2 (x, y) in the plane, 3 (x, y, z) in space
    n_rotations: int = 0                      # rigid bodies' orientation coordinates, after the node coordinates in q
    rotation_rest: tuple = ()                 # those coordinates at the level attitude (theta_b = 0; quaternion 1)

    @property
    def n_elements(self) -> int:
        return int(sum(self.segments))

    @property
    def loop_ode(self) -> ca.Function:
        """The ``ode`` a compiled explicit loop (RK4) should evaluate: the element kernel mapped over
        the elements (:mod:`.segmented_kernel`, MX: C of constant size) from
        :data:`KERNEL_MIN_ELEMENTS` elements, else the element-by-element SX ``ode``. A copy made with
        another ``ode`` (``dataclasses.replace``) must replace or clear ``kernel_ode`` (and ``kernel_jacobian``) too; one whose
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


def has_kernel(scene: Scene) -> bool:
    """Whether the segmented model of ``scene`` has its element-kernel form (:mod:`.segmented_kernel`; an ``[anchor]``
    its fixed last node): no seabed, no winch and no rigid body (such scenes evaluate the element-by-element ``ode``)."""
    return scene.seabed is None and scene.winch is None and not any(s.body.is_rigid for s in scene.sections)


def drag_points(scene: Scene, n_el: int) -> int:
    """Drag points per element: ``numerics.drag_segments`` shared among the section's elements (at
    least one, the element mid-point); N = 1 uses the 2-DOF model's points exactly."""
    return max(1, round(scene.numerics.drag_segments / n_el))


def mid_tension(els):
    """The section's tension at mid-length (N), s = l_0 / 2 in unstretched arc length, from its N element
    tensions T_k (k = 0.. top to bottom), each taken at its element's mid-point s_k = (k + 1/2) l_0 / N:
    linear interpolation in s between the two element mid-points around l_0 / 2, which for N even is the
    mean (T_{N/2-1} + T_{N/2}) / 2 of the elements meeting at the middle node and for N odd the middle
    element's tension T_{(N-1)/2}. Hanging at rest the element tensions are W_b + w (l_0 - s_k) with w the
    weight in water per unstretched length (Wang 1971 eq. 12, weight lumped half to each node), linear in
    s, so the interpolation is exact: W_b + W_c / 2."""
    n = len(els)
    if n % 2:
        return els[n // 2]["tension"]
    return 0.5 * (els[n // 2 - 1]["tension"] + els[n // 2]["tension"])


def build_segmented_model(scene: Scene, *, winch_input: ca.SX | None = None) -> SegmentedModel:
    """Build the segmented-cable functions for ``scene`` (elements per section: ``cable.segments``).

    Parameters
    ----------
    scene : Scene
        Any scene; every value enters through the parameter vector ``p`` as for the 2-DOF model.
    winch_input : casadi.SX, optional
        A 3-vector of symbols (L, w, alpha): the first section's zero-tension length (m), payout speed (m/s)
        and acceleration (m/s^2) as inputs instead of the ``[winch]`` profile (:mod:`.segmented_winch`, the
        same terms), for a controlled winch (:mod:`.segmented_winch_control`). ``dynamics``, ``accel``,
        ``ode``, ``outputs`` and ``energy`` then take it as their last input ``winch``; no kernel; ``outputs`` adds
        ``top_force_x``, ``top_force_y`` (N): the cable's force on the sheave, the first element's tension and the
        half element lumped there (what a heave compensator under the sheave carries).

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
    anchored = scene.anchor is not None
    n_free = n_nodes - int(anchored)                 # an anchored line's last node is fixed
    # a 3-D scene (scene.three_d) has nodes (x, y, z): the same elements and bodies in space, z the sway
    # (Wang 1971 p. 32, "allow the cable to swing out of the vertical plane"); the plane is dim = 2
    dim = 3 if scene.three_d else 2
    axes = ("x", "y", "z")[:dim]
    sfx = (lambda i: "") if n_sec == 1 else (lambda i: f"_{i + 1}")
    # a rigid body's orientation (model/rigid_body.py) after the nodes: its pitch theta_b in the plane, a quaternion
    # (quat_w_b, quat_x_b, quat_y_b, quat_z_b) in space
    rigid = [i for i, s in enumerate(scene.sections) if s.body.is_rigid]
    rest = ORIENTATION_REST[dim]
    rot_names = orientation_names(dim)
    n_rot = len(rigid) * len(rest)
    q_labels = tuple(f"{c}[{j}]" for j in range(1, n_free + 1) for c in axes) + tuple(
        f"{name}{sfx(i)}" for i in rigid for name in rot_names)
    q, qd = ca.SX.sym("q", dim * n_free + n_rot), ca.SX.sym("qd", dim * n_free + n_rot)
    e = ca.SX.sym("e", len(EXO_LABELS_3D if dim == 3 else EXO_LABELS))
    t, z, zd, zdd = e[0], e[1:1 + dim], e[1 + dim:1 + 2 * dim], e[1 + 2 * dim:1 + 3 * dim]
    env = environment_symbols(layout, scene)          # Wang 1971 eq. 26-28 inputs
    rho, depth0 = env["density"], env["top_depth"]
    node_r = [tuple(z[c] for c in range(dim))] + [tuple(q[dim * j + c] for c in range(dim)) for j in range(n_free)]
    node_v = [tuple(zd[c] for c in range(dim))] + [tuple(qd[dim * j + c] for c in range(dim)) for j in range(n_free)]
    if anchored:
        node_r.append(tuple(layout.sym(f"anchor.{c}") for c in axes))      # (x, y, z) in space
        node_v.append((0.0,) * dim)
    static_law = scene.seabed is not None            # the seabed's statics: elements elastic both ways (catenary.py)

    sums = NodeSums(n_nodes + 1, dim)         # the element and body terms per node (node 0: the top)
    sections, elements = [], []
    V_rigid, rigid_terms = 0.0, {}       # rigid bodies: energy; node -> its RigidBlock (rigid_assembly.py)
    j0 = 0
    for i, sec in enumerate(scene.sections):
        P = SectionParameters.from_layout(layout, section_prefix(n_sec, i), sec.body.is_sphere, dim == 3)
        n_el = segs[i]
        pay = payout(scene, layout, P, t) if i == 0 else None     # a [winch]: L(t) (segmented_winch.py)
        if i == 0 and winch_input is not None:                    # L, w, alpha as inputs (a control)
            pay = Payout(L=winch_input[0], w=winch_input[1], alpha=winch_input[2])
        els, P = sums.section(P, n_el, range(j0, j0 + n_el + 1), node_r, node_v, pay=pay, p=p, rho=rho, t=t, env=env,
                              depth0=depth0, n_points=drag_points(scene, n_el), static_law=static_law)
        jb = j0 + n_el                                         # the body's node
        rb, vb = node_r[jb], node_v[jb]
        if scene.seabed is not None:                           # the body's footprint on the bed (segmented_seabed.py)
            sums.area[jb] += layout.sym(f"{section_prefix(n_sec, i)}body.bed_area")
        sec_d = dict(P=P, top=j0, body=jb, elements=els, pay=pay)
        if i in rigid:                                         # a rigid body (rigid_body.py)
            k = range(dim * n_free + len(rest) * rigid.index(i), dim * n_free + len(rest) * (rigid.index(i) + 1))
            blk = rigid_block(P, layout, section_prefix(n_sec, i), [dim * (jb - 1) + c for c in range(dim)], k, rb, vb,
                              q, qd, rho=rho, t=t, env=env, depth0=depth0, dim=dim)
            sums.K, V_rigid = sums.K + blk.K, V_rigid + blk.V
            rigid_terms[jb] = blk
            sec_d.update(rigid=blk)
        else:
            sums.point_body(jb, P, rb, vb, rho=rho, t=t, env=env, depth0=depth0)
        sections.append(sec_d)
        elements += els
        j0 = jb
    V_grav = sums.gravity(node_r)                               # eq. 15 with y down
    V_contact, bed = 0.0, None
    if scene.seabed is not None:
        # the bed resists the cable's material, which a winch makes slide past the first section's nodes
        pay0 = sections[0]["pay"]
        slide = list(node_v) if pay0 is None else pay0.sliding(node_r, node_v, range(segs[0] + 1))
        bed = seabed_forces(layout, node_r, slide, sums.area, elements, depth0, range(1, n_free + 1))
        V_contact = bed["energy"]
        for j, (Fd, Fs) in bed["forces"].items():
            for c in range(dim):
                sums.Q[j][c] += Fd[c]
                sums.Q_static[j][c] += Fs[c]
    # Lagrange's equations node by node (element by element, see element_inertia): M q'' = f with
    # f = generalized forces + weights (-dV/dq, eq. 15) + inertial forces of the added mass (node_terms.py)
    blocks = sums.M[1:n_free + 1]
    f_nodes = [sums.force(j) for j in range(1, n_free + 1)]
    f_static = ca.vertcat(*[sums.force(j, static=True) for j in range(1, n_free + 1)])
    M, f = ca.diagcat(*blocks), ca.vertcat(*f_nodes)
    # a rigid body's node and its orientation share one block (3 x 3 in the plane, 7 x 7 in space)
    M, f, f_static = assemble(M, f, f_static, rigid_terms.values(), n_rot)

    # q'' node by node: M is block diagonal (dim x dim per node; a rigid body's node and orientation one block):
    # solve each node's block in closed form, a body's block by CasADi's QR (7 x 7 in space)
    acc_nodes = [tuple(zdd[c] for c in range(dim))]
    acc, acc_rot = [], [0.0] * n_rot
    for j in range(n_free):
        if j + 1 in rigid_terms:
            blk = rigid_terms[j + 1]
            a_j, a_rot = node_acceleration(blk, blocks[j], f_nodes[j], dim)
            for kk, a_k in zip(blk.k, a_rot):
                acc_rot[kk - dim * n_free] = a_k
        else:
            a_j = block_solve(blocks[j], f_nodes[j])
        acc += list(a_j)
        acc_nodes.append(a_j)
    acc = ca.vertcat(*acc, *acc_rot)
    if anchored:
        acc_nodes.append((0.0,) * dim)

    x = ca.vertcat(q, qd)
    xdot = ca.vertcat(qd, acc)
    out, labels = [], []
    for i, s in enumerate(sections):
        P, els = s["P"], s["elements"]
        rt, vt_, rb, vb = node_r[s["top"]], node_v[s["top"]], node_r[s["body"]], node_v[s["body"]]
        chord = tuple(rb[c] - rt[c] for c in range(dim))
        chord_v = tuple(vb[c] - vt_[c] for c in range(dim))
        lc = norm(chord)
        phi = ca.atan2(-chord[0], chord[1])                        # e_t = (-sin phi, cos phi), eq. 10
        lp2 = chord[0] ** 2 + chord[1] ** 2 if dim == 3 else lc**2  # the chord's square in the x-y plane
        phid = (chord[0] * chord_v[1] - chord[1] * chord_v[0]) / lp2
        # u: the stretch of the whole section beyond its zero-tension length, the sum of the element
        # elongations (Wang's u, eq. 1, when the elements are in line); chord_stretch: the chord
        # (top to body, the straight line phi measures) minus that length, negative when the cable sags
        u, ud = sum(el["length"] for el in els) - P.l_0, sum(el["rate"] for el in els)
        c_u, c_ud = lc - P.l_0, dot(chord, chord_v) / lc
        first, last = els[0], els[-1]
        # force of the cable on its top point and on its body: the end element's tension plus the
        # half element lumped at that node (weight, drag share, minus its inertia)
        acc_top = acc_nodes[s["top"]] if s["pay"] is None else s["pay"].top_acceleration(    # the material's, at the sheave
            len(els), rt, vt_, acc_nodes[s["top"]], node_r[s["top"] + 1], node_v[s["top"] + 1])
        lt = lump_force(first, "a", acc_top)
        top_force = tuple(first["tension"] * first["et"][c] + lt[c] for c in range(dim))
        s["top_force"] = top_force                 # a controlled winch reports it (below)
        lb = lump_force(last, "b", acc_nodes[s["body"]])
        bottom_force = tuple(-last["tension"] * last["et"][c] + lb[c] for c in range(dim))
        out += [phi, phid, u, ud, rb[0], vb[0], rb[1], vb[1], mid_tension(els), norm(bottom_force), norm(top_force),
                c_u, c_ud]
        labels += [f"{name}{sfx(i)}" for name in OUTPUT_NAMES + CHORD_NAMES]
        if dim == 3:
            # Wang's 3-D angles of the chord, e_t = (-sin phi cos phi_z, cos phi cos phi_z, sin phi_z)
            # (section._frame): phi_z = atan2(c_z, |c_xy|), its rate d/dt of that
            lp = ca.sqrt(lp2)
            lpd = (chord[0] * chord_v[0] + chord[1] * chord_v[1]) / lp
            out += [ca.atan2(chord[2], lp), (lp * chord_v[2] - chord[2] * lpd) / lc**2, rb[2], vb[2]]
            labels += [f"{name}{sfx(i)}" for name in OUTPUTS_3D]
        if "rigid" in s:      # the rigid body's pitch (rad, +x towards +y) and rate, its CG (m) and CG velocity; in
            values, names = rigid_outputs(s["rigid"], dim)     # space roll, yaw, omega and the quaternion
            out += values
            labels += [f"{name}{sfx(i)}" for name in names]
    if sections[0].get("pay") is not None:     # the winch: L, w, alpha and the power T_top w (segmented_winch.py)
        out += sections[0]["pay"].outputs(out[OUTPUT_NAMES.index("tension_top")])
        labels += list(WINCH_OUTPUTS)
    if winch_input is not None:      # a controlled winch: the cable's force on the sheave (N), for a compensator
        out += list(sections[0]["top_force"])
        labels += [f"top_force_{c}" for c in axes]
    # profiles (element k top to bottom over all sections; node j = 0 the top) and their arc lengths
    T = ca.vertcat(*[el["tension"] for el in elements])
    T_rate = ca.jtimes(T, x, xdot) + ca.jacobian(T, e) @ ca.vertcat(1.0, zd, zdd, ca.DM.zeros(dim))
    if winch_input is not None:      # L' = w, w' = alpha (alpha' not known to the model: held)
        T_rate += ca.jacobian(T, winch_input) @ ca.vertcat(winch_input[1], winch_input[2], 0.0)
    prof = {"element_tension": T, "element_tension_rate": T_rate,
            "element_strain": ca.vertcat(*[el["strain"] for el in elements]),
            "element_slack": ca.vertcat(*[el["slack"] for el in elements]),
            "node_x": ca.vertcat(*[r[0] for r in node_r]), "node_y": ca.vertcat(*[r[1] for r in node_r])}
    if dim == 3:
        prof["node_z"] = ca.vertcat(*[r[2] for r in node_r])
    if bed is not None:
        prof["seabed_normal"] = ca.vertcat(*bed["normal"])
        prof["seabed_friction"] = ca.vertcat(*bed["friction"])
        if dim == 3:
            prof["seabed_friction_lateral"] = ca.vertcat(*bed["lateral"])
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

    # a controlled winch: (L, w, alpha) the last input of every function (winch_input)
    zi, zn = ([winch_input], ["winch"]) if winch_input is not None else ([], [])
    dynamics = ca.Function("dynamics", [q, qd, e, p, *zi], [M, f], ["q", "qd", "e", "p", *zn], ["M", "f"])
    accel = ca.Function("accel", [q, qd, e, p, *zi], [acc], ["q", "qd", "e", "p", *zn], ["qdd"])
    top = top_motion_function(scene, layout)
    S = symbolic_type(scene)
    nq = dim * n_free + n_rot
    xs, ts, ps = S.sym("x", 2 * nq), S.sym("t"), S.sym("p", p.shape[0])
    zs = [S.sym("winch", 3)] if winch_input is not None else []
    ode = ca.Function("ode", [xs, ts, ps, *zs], [ca.vertcat(xs[nq:], accel(xs[:nq], xs[nq:], top(ts, ps), ps, *zs))],
                      ["x", "t", "p", *zn], ["xdot"])
    outputs = ca.Function("outputs", [x, e, p, *zi], [ca.vertcat(*out)], ["x", "e", "p", *zn], ["y"])
    energy = ca.Function("energy", [x, e, p, *zi], [sums.K, V_grav + sums.V_strain + V_contact + V_rigid], ["x", "e", "p", *zn],
                         ["K", "V"])
    cable_force = ca.Function("cable_force", [x, p], [ca.SX(0, 1)], ["x", "p"], ["gap"])
    static = (ca.Function("static_force", [q, qd, e, p, *zi], [f_static], ["q", "qd", "e", "p", *zn], ["f"])
              if scene.seabed is not None else None)
    # a sampled series is an MX node inside the SX physics: no kernel form of that model
    kernel = S is ca.SX and has_kernel(scene) and winch_input is None
    points = lambda n_el: drag_points(scene, n_el)  # noqa: E731
    return SegmentedModel(layout=layout, n_sections=n_sec, angles=scene.angles, q_labels=q_labels,
                          output_labels=tuple(labels), dynamics=dynamics, ode=ode, top=top, outputs=outputs,
                          energy=energy, cable_force=cable_force, slack_index=(), symbolic=S,
                          segments=segs, accel=accel, kernel_ode=kernel_ode(scene, points) if kernel else None,
                          kernel_jacobian=kernel_jacobian(scene, points) if kernel else None, anchored=anchored,
                          static_force=static, dim=dim, n_rotations=n_rot, rotation_rest=rest * len(rigid))
