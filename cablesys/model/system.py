"""The node model of a cable system: lines joined at points (a graph of lines, :mod:`cablesys.scene.system`).

The chain's node model (:mod:`.segmented`) numbers its nodes top to bottom; here the lines meet at shared point
nodes, in any graph. The physics is the same and comes from the same functions: every line section of N elements
(reference length h_r = l_r / N, zero-tension length h_0 = l_0 / N, Wang 1971 eq. 1) has the element terms of
:func:`.segmented_element.element_terms` (tension-only law with Voigt damping and the slack rule, eq. 46, 54; mass and
added mass, eq. 5, 23-24; weight in water, eq. 12; normal and tangential drag in the current and waves, eq. 26-28,
42, 44) and the inertia of :func:`.segmented_element.element_inertia` (Lagrange's equations of the element's lumped
kinetic energy by AD), and every body or junction the point body's virtual masses, weight and drag (eq. 16, 32-35),
summed node by node in :class:`.node_terms.NodeSums`.

Nodes. The lines are walked in the scene's order; each line's start point gets a node when first met, then the
line's interior nodes from its start to its end (section joints included: a section's last node is the next
section's first), then its end point when first met. The prescribed point's node moves with the top motion e (the
origin of the node frame at its mean position), a further prescribed point's node (another point of the vessel) with
the same translation about its mean position (entries of p, ``system.point[i].x``, ...), and with a vessel's 6-DOF RAO
also turned by the vessel's small rotation theta at its lever arm: s_0 + theta x Delta, Delta its mean position (the
rotation theta, its rate and acceleration are entries of e after the translation's, ``vessel_inputs``; Faltinsen 1990
ch. 3 in the node frame, derived in :mod:`cablesys.scene.vessel`), and on a circular track swung round with the
ship's heading about the circle's centre (:mod:`.ship_points`); a fixed point's node is held
at its position (entries of p); every
other node is free: its coordinates (x, y) in the plane, (x, y, z) in space are q, labelled ``x[j]``, ``y[j]``,
``z[j]`` by node number j. A chain written from its top down is numbered as the chain's node model numbers it, so
the two models are the same functions (tests/test_system_model.py).

Outputs: ``point.NAME.x``, ``.y`` (``.z`` in space) of every point and their rates (m, m/s; y down from the
prescribed point's mean depth); ``line.NAME.tension_from`` and ``line.NAME.tension_to``, the size of the force of
the line on its start and end point (N): its end element's tension along the element plus the half element lumped
at that node (weight, drag share, minus its inertia), as the chain's ``tension_top``/``tension_bottom``; the
profiles ``element_tension[k]``, ``element_tension_rate[k]``, ``element_strain[k]``, ``element_slack[k]`` (elements
line by line, each from its start), ``element_s[k]`` (the element mid-point's unstretched arc length from its line's
start, m) and ``node_x[j]``, ``node_y[j]`` (``node_z[j]``) of every node. Units SI.

A body point whose body is rigid (``pitch_inertia`` set; Wang 1971 p. 32, body rotation) is the chain's rigid body
(:mod:`.rigid_body`, assembled by :mod:`.rigid_assembly` as the chain's): its node is the lines' attachment point, its
orientation more coordinates after every node's, point by point in the scene's order (``point.NAME.theta_b`` in the
plane, ``point.NAME.quat_w_b`` .. ``quat_z_b`` in space; ``n_rotations``, ``rotation_rest``), node and orientation one
block of Lagrange's equations (3 x 3 in the plane, 7 x 7 in space); its parameters ``system.point[i].body.*``, its
outputs ``point.NAME.theta_b``, ``theta_b_rate``, ``x_cg``, ``x_cg_rate``, ``y_cg``, ``y_cg_rate`` and in space
``roll_b``, ``yaw_b`` and rates, ``z_cg``, ``z_cg_rate``, ``omega_x_b`` .. ``omega_z_b``, ``quat_w_b`` .. ``quat_z_b``
(:data:`.rigid_assembly.RIGID_OUTPUTS`, :data:`.rigid_assembly.RIGID_OUTPUTS_3D`).

A ``[winch]`` pays out the one line that starts at the prescribed point (:func:`winch_line`; the scene refuses any
other), its first section exactly as the chain's first section (:mod:`.segmented_winch`: its elements share L(t),
their terms see the material velocities, L a prescribed coordinate in Lagrange's equations; the seabed resists the
sliding material, :meth:`.segmented_winch.Payout.sliding`; the line's ``tension_from`` lumps the sheave's half element
with the material's acceleration there) through the same :meth:`.node_terms.NodeSums.section`; outputs add
:data:`.segmented_winch.WINCH_OUTPUTS` (the power with that line's ``tension_from``).

A ``[seabed]`` acts on every free node as on the chain's (:mod:`.segmented_seabed`: normal contact, regularised
Coulomb friction, in space along and across the line on a bed sloping towards ``seabed.heading_deg``, the laid-down
line's friction in the statics, ``static_force``), a body's or junction's node with its footprint ``body.bed_area``
besides its lines' half elements (as the chain's body): a line is laid from its start towards its end, so a node's
fairlead side is the element of its line that ends at it (a point that no element ends at: the element leaving it),
its other side (the line's tangent in space) the element leaving it; write a mooring line from its fairlead to its
anchor. Profiles ``seabed_normal[j]`` and ``seabed_friction[j]`` per node (in space also
``seabed_friction_lateral[j]``).
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..scene import Scene
from .node_terms import NodeSums
from .params import ParameterLayout, environment_symbols
from .rigid_assembly import assemble, node_acceleration, orientation_names, rigid_block, rigid_outputs
from .rigid_body import ORIENTATION_REST
from .section import SectionParameters
from .segmented import SegmentedModel, drag_points
from .segmented_element import block_solve, lump_force, norm
from .segmented_seabed import seabed_forces
from .segmented_winch import WINCH_OUTPUTS, payout
from .ship_points import ship_point
from .signals import EXO_LABELS
from .top_motion import EXO_LABELS_3D, symbolic_type, top_motion_function, vessel_rotation_labels

__all__ = ["SystemModel", "build_system_model", "topology", "winch_line"]


@dataclasses.dataclass(frozen=True, eq=False)
class SystemModel(SegmentedModel):
    """The node model of a graph of lines (module docstring): a :class:`~.segmented.SegmentedModel` whose nodes are
    numbered line by line. ``point_names``, ``point_kinds`` and ``point_nodes`` (the node of each point, scene
    order); ``line_names``, ``line_nodes`` (each line's nodes from its start to its end) and ``line_segments`` (its
    sections' element counts); ``node_q`` the position of each node's first coordinate in q (-1 for the prescribed
    and fixed nodes); ``node_labels`` the parameter labels of a fixed node's position or a further prescribed node's
    mean position (() for the others)."""

    point_names: tuple = ()
    point_kinds: tuple = ()
    point_nodes: tuple = ()
    line_names: tuple = ()
    line_nodes: tuple = ()
    line_segments: tuple = ()
    node_q: tuple = ()
    node_labels: tuple = ()
    vessel_inputs: tuple = ()        # the vessel's rotation in e after (t, z, z', z''): ("rot_z_s",) or x, y, z

    @property
    def n_nodes(self) -> int:
        """Every node: free, fixed and the prescribed one."""
        return len(self.node_q)

    def top_input(self, e) -> list:
        """u = (z, theta): the top's translation (dim entries) and the vessel's rotation (``vessel_inputs``) of e."""
        n = len(self.vessel_inputs)
        return list(e[1:1 + self.dim]) + list(e[1 + 3 * self.dim:1 + 3 * self.dim + n])

    def at_rest(self, u):
        """e at rest with the top input u (:meth:`top_input`): (0, z, 0, 0, theta, 0, 0); SX for SX, else numbers."""
        dim, n = self.dim, len(self.vessel_inputs)
        if isinstance(u, ca.SX):
            return ca.vertcat(0.0, u[:dim], ca.SX.zeros(2 * dim), u[dim:dim + n], ca.SX.zeros(2 * n))
        u = np.asarray(u, float)
        return np.concatenate([[0.0], u[:dim], np.zeros(2 * dim), u[dim:dim + n], np.zeros(2 * n)])


def topology(system) -> tuple:
    """(point_nodes, line_nodes, n_nodes) of ``system`` (:class:`~cablesys.scene.system.System`): the node of every
    point and the nodes of every line from its start to its end, numbered as the module docstring says."""
    point_nodes, line_nodes, count = {}, [], 0

    def point(name):
        nonlocal count
        if name not in point_nodes:
            point_nodes[name] = count
            count += 1
        return point_nodes[name]

    for line in system.line:
        seq = [point(line.start)]
        n = sum(c.segments for c in line.section)
        seq += list(range(count, count + n - 1))
        count += n - 1
        seq.append(point(line.end))
        line_nodes.append(tuple(seq))
    return tuple(point_nodes[p.name] for p in system.point), tuple(line_nodes), count


def winch_line(scene: Scene) -> int | None:
    """The index of the line a ``[winch]`` pays out (the one line starting at the prescribed point, checked by the
    scene), None without a winch."""
    if getattr(scene, "winch", None) is None:
        return None
    top = scene.system.prescribed.name
    return next(k for k, ln in enumerate(scene.system.line) if ln.start == top)


def build_system_model(scene: Scene) -> SystemModel:
    """Build the node model of ``scene.system`` (module docstring); every value enters through ``p``.

    Parameters
    ----------
    scene : Scene
        A scene with a ``system`` that is not a chain (a chain is built by :mod:`.segmented`).

    Returns
    -------
    SystemModel
        ``dynamics``, ``accel``, ``ode``, ``top``, ``outputs``, ``energy`` and an empty ``cable_force``, as the chain's
        node model.
    """
    system = scene.system
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    dim = 3 if scene.three_d else 2
    axes = ("x", "y", "z")[:dim]
    point_nodes, line_nodes, n_nodes = topology(system)
    kind_of = {point_nodes[i]: pt for i, pt in enumerate(system.point)}
    point_index = {point_nodes[i]: i for i in range(len(system.point))}
    node_q, free = [-1] * n_nodes, []
    for j in range(n_nodes):
        if j not in kind_of or kind_of[j].free:
            node_q[j] = dim * len(free)
            free.append(j)
    # a rigid body's orientation (rigid_body.py) after the nodes, point by point: theta_b in the plane, a quaternion
    # in space, labelled point.NAME.theta_b, point.NAME.quat_w_b, ...
    rigid = [i for i, pt in enumerate(system.point) if pt.free and pt.body.is_rigid]
    rest = ORIENTATION_REST[dim]
    n_rot, n_nq = len(rigid) * len(rest), dim * len(free)
    q_labels = tuple(f"{c}[{j}]" for j in free for c in axes) + tuple(
        f"point.{system.point[i].name}.{name}" for i in rigid for name in orientation_names(dim))
    q, qd = ca.SX.sym("q", n_nq + n_rot), ca.SX.sym("qd", n_nq + n_rot)
    vessel = scene.vessel_rotation_axes                # the vessel's rotation moves the further prescribed points
    n_v = len(vessel)
    e = ca.SX.sym("e", len(EXO_LABELS_3D if dim == 3 else EXO_LABELS) + len(vessel_rotation_labels(vessel)))
    t, z, zd, zdd = e[0], e[1:1 + dim], e[1 + dim:1 + 2 * dim], e[1 + 2 * dim:1 + 3 * dim]
    theta = [e[1 + 3 * dim + n_v * m:1 + 3 * dim + n_v * (m + 1)] for m in range(3)]   # rotation, rate, acceleration
    top = top_motion_function(scene, layout)
    track = scene.top_motion.track
    z0 = top(0.0, p)[1:1 + dim] if track is not None and track.is_circle else None    # the tow point at the start
    env = environment_symbols(layout, scene)          # Wang 1971 eq. 26-28 inputs
    rho, depth0 = env["density"], env["top_depth"]

    node_r, node_v, node_a, node_labels = [], [], [], []
    for j in range(n_nodes):
        pt = kind_of.get(j)
        labels, a = (), None
        if node_q[j] >= 0:
            k = node_q[j]
            r, v = tuple(q[k + c] for c in range(dim)), tuple(qd[k + c] for c in range(dim))
        elif pt.kind == "prescribed" and pt is system.prescribed:     # the top: the scene's top motion
            r, v, a = tuple(z[c] for c in range(dim)), tuple(zd[c] for c in range(dim)), tuple(zdd[c] for c in range(dim))
        elif pt.kind == "prescribed":                  # another point of the vessel: the top's motion plus its arm
            labels = tuple(f"system.point[{point_index[j]}].{c}" for c in axes)
            arm = tuple(layout.sym(lb) for lb in labels)   # its mean position from the first prescribed point
            r, v, a = ship_point(arm, (z, zd, zdd), z0, theta if n_v else None, vessel)
        else:                                          # a fixed point, held at its position
            labels = tuple(f"system.point[{point_index[j]}].{c}" for c in axes)
            r, v = tuple(layout.sym(lb) for lb in labels), (0.0,) * dim
        node_r.append(r)
        node_v.append(v)
        node_a.append(a)
        node_labels.append(labels)

    static_law = scene.seabed is not None            # the seabed's statics: elements elastic both ways (catenary.py)
    sums = NodeSums(n_nodes, dim)
    elements, lines, s_el = [], [], []
    wound = winch_line(scene)                         # a [winch] pays out this line's first section (segmented_winch)
    pay = None
    for k, line in enumerate(system.line):
        seq, pos, els, s0 = line_nodes[k], 0, [], 0.0
        for s, cable in enumerate(line.section):
            P = SectionParameters.for_cable(layout, f"system.line[{k}].section[{s}].")
            n_el = cable.segments
            sec_pay = payout(scene, layout, P, t) if (k, s) == (wound, 0) else None
            pay = sec_pay or pay
            sec_els, P = sums.section(P, n_el, seq[pos:pos + n_el + 1], node_r, node_v, pay=sec_pay, p=p, rho=rho,
                                      t=t, env=env, depth0=depth0, n_points=drag_points(scene, n_el),
                                      static_law=static_law)
            els += sec_els
            s_el += [s0 + (m + 0.5) * P.l_0 / n_el for m in range(n_el)]
            pos += n_el
            s0 = s0 + P.l_0
        lines.append(els)
        elements += els
    V_rigid, rigid_terms = 0.0, {}                    # rigid bodies: energy; node -> its RigidBlock
    for i, pt in enumerate(system.point):
        if not pt.free:
            continue
        j = point_nodes[i]
        P = SectionParameters.for_body(layout, f"system.point[{i}].body.", pt.body.is_sphere, dim == 3)
        if i in rigid:                                 # a rigid body at its attachment node (rigid_assembly.py)
            m = rigid.index(i)
            blk = rigid_block(P, layout, f"system.point[{i}].", [node_q[j] + c for c in range(dim)],
                              range(n_nq + len(rest) * m, n_nq + len(rest) * (m + 1)), node_r[j], node_v[j], q, qd,
                              rho=rho, t=t, env=env, depth0=depth0, dim=dim)
            sums.K, V_rigid = sums.K + blk.K, V_rigid + blk.V
            rigid_terms[j] = blk
        else:                                          # Wang's point body: a body or a junction
            sums.point_body(j, P, node_r[j], node_v[j], rho=rho, t=t, env=env, depth0=depth0)

    V_contact, bed = 0.0, None
    if scene.seabed is not None:     # the seabed on every free node (segmented_seabed.py); a line is laid from its
        # start towards its end: a node's fairlead side is the element of its line ending at it
        for i, pt in enumerate(system.point):         # a body's or junction's footprint on the bed
            if pt.free:
                sums.area[point_nodes[i]] += layout.sym(f"system.point[{i}].body.bed_area")
        up, down = {}, {}
        for el in reversed(elements):
            up[el["a"]] = el                          # a point no element ends at: the element leaving it
        up.update({el["b"]: el for el in elements})
        for el in reversed(elements):                 # the other side (the line's tangent in space): an element
            if up[el["a"]] is not el:                 # leaving the node, its line's next one at an inner node
                down[el["a"]] = el
        # the bed resists the cable's material, which a winch makes slide past its line's nodes
        slide = node_v if pay is None else pay.sliding(
            node_r, node_v, line_nodes[wound][:system.line[wound].section[0].segments + 1])
        bed = seabed_forces(layout, node_r, slide, sums.area, elements, depth0, free, up, down)
        V_contact = bed["energy"]
        for j, (Fd, Fs) in bed["forces"].items():
            for c in range(dim):
                sums.Q[j][c] += Fd[c]
                sums.Q_static[j][c] += Fs[c]
    # Lagrange's equations node by node (node_terms.py): M_j q''_j = f_j, block diagonal; a rigid body's node and
    # its orientation one block (rigid_assembly.py)
    acc_nodes, acc, acc_rot = [None] * n_nodes, [], [0.0] * n_rot
    for j in range(n_nodes):
        if j in rigid_terms:
            blk = rigid_terms[j]
            a_j, a_rot = node_acceleration(blk, sums.M[j], sums.force(j), dim)
            acc += list(a_j)
            for kk, a_k in zip(blk.k, a_rot):
                acc_rot[kk - n_nq] = a_k
        elif node_q[j] >= 0:
            a_j = block_solve(sums.M[j], sums.force(j))
            acc += list(a_j)
        elif kind_of[j].kind == "prescribed":
            a_j = node_a[j]
        else:
            a_j = (0.0,) * dim
        acc_nodes[j] = a_j
    acc = ca.vertcat(*acc, *acc_rot)
    M, f, f_static = assemble(ca.diagcat(*[sums.M[j] for j in free]), ca.vertcat(*[sums.force(j) for j in free]),
                              ca.vertcat(*[sums.force(j, static=True) for j in free]), rigid_terms.values(), n_rot)

    x = ca.vertcat(q, qd)
    xdot = ca.vertcat(qd, acc)
    out, labels = [], []
    for i, pt in enumerate(system.point):
        j = point_nodes[i]
        out += [node_r[j][c] for c in range(dim)] + [node_v[j][c] for c in range(dim)]
        labels += [f"point.{pt.name}.{c}" for c in axes] + [f"point.{pt.name}.{c}_rate" for c in axes]
        if j in rigid_terms:                           # its attitude, CG and (in space) rates and quaternion
            values, names = rigid_outputs(rigid_terms[j], dim)
            out += values
            labels += [f"point.{pt.name}.{name}" for name in names]
    for k, line in enumerate(system.line):
        first, last = lines[k][0], lines[k][-1]
        a, b = line_nodes[k][0], line_nodes[k][-1]
        # force of the line on its end points: the end element's tension plus the half element lumped there
        acc_a = acc_nodes[a]
        if pay is not None and k == wound:           # the material's acceleration at the sheave (segmented_winch.py)
            seq = line_nodes[k]
            acc_a = pay.top_acceleration(system.line[k].section[0].segments, node_r[a], node_v[a], acc_a,
                                         node_r[seq[1]], node_v[seq[1]])
        lt, lb = lump_force(first, "a", acc_a), lump_force(last, "b", acc_nodes[b])
        start = tuple(first["tension"] * first["et"][c] + lt[c] for c in range(dim))
        end = tuple(-last["tension"] * last["et"][c] + lb[c] for c in range(dim))
        out += [norm(start), norm(end)]
        labels += [f"line.{line.name}.tension_from", f"line.{line.name}.tension_to"]
        if pay is not None and k == wound:           # the winch: L, w, alpha and the power T w at the sheave
            winch_out = pay.outputs(norm(start))
    if pay is not None:
        out += winch_out
        labels += list(WINCH_OUTPUTS)
    T = ca.vertcat(*[el["tension"] for el in elements])
    e_rate = ca.vertcat(1.0, zd, zdd, ca.DM.zeros(dim)) if not n_v else ca.vertcat(1.0, zd, zdd, ca.DM.zeros(dim),
                                                                                     theta[1], theta[2], ca.DM.zeros(n_v))
    T_rate = ca.jtimes(T, x, xdot) + ca.jacobian(T, e) @ e_rate
    prof = {"element_tension": T, "element_tension_rate": T_rate,
            "element_strain": ca.vertcat(*[el["strain"] for el in elements]),
            "element_slack": ca.vertcat(*[el["slack"] for el in elements]),
            "element_s": ca.vertcat(*s_el)}
    prof.update({f"node_{c}": ca.vertcat(*[r[n] for r in node_r]) for n, c in enumerate(axes)})
    if bed is not None:
        prof["seabed_normal"] = ca.vertcat(*bed["normal"])
        prof["seabed_friction"] = ca.vertcat(*bed["friction"])
        if dim == 3:
            prof["seabed_friction_lateral"] = ca.vertcat(*bed["lateral"])
    for name, v in prof.items():
        out += [v[k] for k in range(v.shape[0])]
        labels += [f"{name}[{k}]" for k in range(v.shape[0])]

    dynamics = ca.Function("dynamics", [q, qd, e, p], [M, f], ["q", "qd", "e", "p"], ["M", "f"])
    accel = ca.Function("accel", [q, qd, e, p], [acc], ["q", "qd", "e", "p"], ["qdd"])
    S = symbolic_type(scene)
    nq = len(q_labels)
    xs, ts, ps = S.sym("x", 2 * nq), S.sym("t"), S.sym("p", p.shape[0])
    ode = ca.Function("ode", [xs, ts, ps], [ca.vertcat(xs[nq:], accel(xs[:nq], xs[nq:], top(ts, ps), ps))],
                      ["x", "t", "p"], ["xdot"])
    outputs = ca.Function("outputs", [x, e, p], [ca.vertcat(*out)], ["x", "e", "p"], ["y"])
    energy = ca.Function("energy", [x, e, p], [sums.K, sums.gravity(node_r) + sums.V_strain + V_contact + V_rigid],
                         ["x", "e", "p"], ["K", "V"])
    static = (ca.Function("static_force", [q, qd, e, p], [f_static],
                          ["q", "qd", "e", "p"], ["f"]) if bed is not None else None)
    cable_force = ca.Function("cable_force", [x, p], [ca.SX(0, 1)], ["x", "p"], ["gap"])
    return SystemModel(layout=layout, n_sections=0, angles=scene.angles, q_labels=q_labels,
                       output_labels=tuple(labels), dynamics=dynamics, ode=ode, top=top, outputs=outputs,
                       energy=energy, cable_force=cable_force, slack_index=(), symbolic=S,
                       segments=tuple(c.segments for ln in system.line for c in ln.section), accel=accel,
                       static_force=static,
                       dim=dim, point_names=tuple(pt.name for pt in system.point),
                       point_kinds=tuple(pt.kind for pt in system.point), point_nodes=point_nodes,
                       line_names=tuple(ln.name for ln in system.line), line_nodes=line_nodes,
                       line_segments=tuple(tuple(c.segments for c in ln.section) for ln in system.line),
                       node_q=tuple(node_q), node_labels=tuple(node_labels), n_rotations=n_rot,
                       vessel_inputs=vessel_rotation_labels(vessel)[:n_v],
                       rotation_rest=rest * len(rigid))
