"""The segmented cable in generalized coordinates per element: inclination(s) and stretch.

The same physics as the node model (:mod:`.segmented`), in other coordinates. Wang (1971, p. 33)
describes the segmented cable as "several segments ... each segment has two degrees of freedom":
element k has the inclination phi_k (from the vertical, clockwise positive) and the stretch
u_k = l_k - h_0 (h_0 = l_0 / N the element's zero-tension length, eq. 1). In three dimensions
(Wang 1971 p. 32, "allow the cable to swing out of the vertical plane") element k has a second
angle, phi_z_k out of the x-y plane, with the unit tangent of Wang's 3-D straight cable
(:func:`tangent`, the frame of :func:`.section._frame`):

    e_t = (-sin phi, cos phi)                                   (plane, eq. 10, y down)
    e_t = (-sin phi cos phi_z, cos phi cos phi_z, sin phi_z)    (space; phi_z = 0 is the plane)

so that one element (N = 1) has the coordinates (phi, u) or (phi, phi_z, u) of Wang's cable, in
his order. The node positions follow by forward kinematics from the top point z (the exogenous
input e):

    r_j = z + sum_{k < j} (h_0 + u_k) e_t(angles_k),          r = R(q_g, z)  (holonomic, invertible
                                                                 while |phi_z| < 90 deg)

so r' = Z z' + J q_g' and r'' = Z z'' + J q_g'' + J' q_g', with J = dR/dq_g (CasADi AD), Z the
column of identities (2 x 2 in the plane, 3 x 3 in space) and J' q_g' = d(J q_g')/dq_g q_g'. The
node model's equations M_n r'' = f_n (Lagrange's equations of the lumped cable, eq. 8-9 with
eq. 12, 15-16, 23-24, 32-35, 42-46, 54; in space with the sway and the 3-D drag of
:mod:`.segmented`) transform by virtual work (the generalized forces of q_g are J^T times the node
forces):

    (J^T M_n J) q_g'' = J^T (f_n - M_n (Z z'' + J' q_g'))

Tension, drag, weight and the inertial forces of the added mass all come with f_n; nothing is
written twice, and the plane and space are one code with the node dimension ``dim`` (a planar
scene builds the planar coordinates; ``numerics.dimensions = 3`` forces the 3-D ones). The model
is the building block of the quasi-static segmented rung (:mod:`.quasistatic`), whose split into
slow (the angles ``phi``, ``phi_z``) and fast (``u``) coordinates needs exactly these coordinates.
Its outputs are the node model's (the state mapped back to node positions and velocities). Runs
of it start from the node model's elastic catenary mapped by ``from_nodes``
(:func:`cablesys.time_domain.initial.initial_state`).
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from ..errors import ParameterError
from ..scene import Scene
from .cable_model import CableModel
from .params import ParameterLayout, section_prefix
from .section import SectionParameters


# an element's coordinates per node dimension, in Wang's order (build.py: (phi, u); (phi, phi_z, u) in 3-D)
COORDINATES = {2: ("phi", "u"), 3: ("phi", "phi_z", "u")}


@dataclasses.dataclass(frozen=True, eq=False)
class ElementModel(CableModel):
    """A :class:`CableModel` with coordinates ``phi[k]``, ``u[k]`` per element (k = 0.. top to bottom), in 3-D
    ``phi[k]``, ``phi_z[k]``, ``u[k]``.

    Besides the functions of :class:`CableModel`: ``to_nodes(x, e, p) -> x_n`` (the node model's state
    (r, r')) and ``from_nodes(x_n, e, p) -> x`` (its inverse), ``node_model`` the node model whose
    physics it carries, ``elements`` the elements per section. (Not ``segments``: that attribute marks a
    node-coordinates model for the statics and the initial state.)
    """

    elements: tuple = ()
    to_nodes: ca.Function | None = None
    from_nodes: ca.Function | None = None
    node_model: CableModel | None = None
    name: str = "element-coordinates"

    @property
    def n_elements(self) -> int:
        return int(sum(self.elements))


def _sections(scene: Scene, layout: ParameterLayout):
    """(SectionParameters, elements) of every section, top to bottom: the one loop over the sections
    that the per-element tables below share."""
    n_sec = len(scene.sections)
    return [(SectionParameters.from_layout(layout, section_prefix(n_sec, i), sec.body.is_sphere), sec.cable.segments)
            for i, sec in enumerate(scene.sections)]


def _per_element(scene: Scene, layout: ParameterLayout, value) -> list:
    """``value(P, n)`` of each section repeated for its n equal elements, top to bottom."""
    return [v for P, n in _sections(scene, layout) for v in [value(P, n)] * n]


def zero_tension_lengths(scene: Scene, layout: ParameterLayout) -> list:
    """h_0 = l_0 / N of every element, top to bottom (Wang 1971 eq. 1), SX of ``layout.symbol``."""
    return _per_element(scene, layout, lambda P, n: P.l_0 / n)


def hanging_stretch(scene: Scene, layout: ParameterLayout) -> ca.Function:
    """``(p) -> u``: every element's stretch hanging still and vertical, u_k = T_k h_r / (AE)_r with
    T_k the weight in water below the element's mid-point (eq. 12, 46): a starting point for Newton."""
    p = layout.symbol
    us, below = [], 0.0
    for P, n in reversed(_sections(scene, layout)):
        h_r, w_el = P.l_r / n, P.w_r * P.l_r / n
        below = below + P.w_b
        sec_u = []
        for _ in range(n):                       # bottom element first
            sec_u.append((below + 0.5 * w_el) * h_r / P.ae)
            below = below + w_el
        us = list(reversed(sec_u)) + us
    return ca.Function("hanging_stretch", [p], [ca.vertcat(*us)], ["p"], ["u"])


def element_stiffness(scene: Scene, layout: ParameterLayout) -> ca.Function:
    """``(p) -> k``: every element's axial stiffness k_e = (AE)_r / h_r, h_r = l_r / N (Wang 1971 eq. 46
    per element), top to bottom."""
    k = _per_element(scene, layout, lambda P, n: P.ae * n / P.l_r)
    return ca.Function("element_stiffness", [layout.symbol], [ca.vertcat(*k)], ["p"], ["k"])


def tangent(phi, theta=None):
    """Wang's unit tangent e_t down a straight element and its partial derivatives by the element's angles.

    Plane (``theta`` None; Wang 1971 eq. 10, y down): e_t = (-sin phi, cos phi), de_t/dphi = (-cos phi, -sin phi).
    Space (Wang 1971 p. 32; the frame of :func:`.section._frame`): e_t = (-sin phi cos theta, cos phi cos theta,
    sin theta), de_t/dphi = cos theta (-cos phi, -sin phi, 0), de_t/dtheta = (sin phi sin theta, -cos phi sin theta,
    cos theta). Returns (e_t, [de_t/dphi] or [de_t/dphi, de_t/dtheta]), tuples of SX."""
    s, c = ca.sin(phi), ca.cos(phi)
    if theta is None:
        return (-s, c), [(-c, -s)]
    st, ct = ca.sin(theta), ca.cos(theta)
    return (-s * ct, c * ct, st), [(-c * ct, -s * ct, 0.0), (s * st, -c * st, ct)]


def _element(q, k: int, dim: int):
    """(angles, stretch) of element k in q: (phi_k,) and u_k in the plane, (phi_k, phi_z_k) and u_k in space
    (``dim`` coordinates per element, Wang's order)."""
    return tuple(q[dim * k + a] for a in range(dim - 1)), q[dim * k + dim - 1]


def _kinematics(q, z, h0, dim: int):
    """Node positions r_1..r_N (stacked x, y[, z]) of the elements hung from z (Wang 1971 eq. 10)."""
    r, pos = [z[c] for c in range(dim)], []
    for k, h in enumerate(h0):
        angles, u = _element(q, k, dim)
        e_t, _ = tangent(*angles)
        length = h + u
        r = [r[c] + length * e_t[c] for c in range(dim)]
        pos += r
    return ca.vertcat(*pos)


def _block_diagonal(sp: ca.Sparsity, n: int, dim: int) -> bool:
    """Whether a (dim n x dim n) sparsity couples only the coordinates of each node."""
    rows, cols = sp.get_triplet()
    return sp.size1() == dim * n and all(r // dim == c // dim for r, c in zip(rows, cols))


def _chain_transform(q, h0, M_n, g, dim: int):
    """J^T M_n J and J^T g for a block-diagonal M_n (dim x dim per node), by the chain's structure: coordinate a of
    element k (an angle or the stretch) moves every node below element k by the same vector c_a (dR/dangle = l_k
    de_t/dangle, dR/du_k = e_t), so with the suffix sums S_k = sum_{j > k} M_j and G_k = sum_{j > k} g_j (nodes below
    element k), (J^T M_n J)_{ab} = c_a^T S_max(k_a, k_b) c_b and (J^T g)_a = c_a^T G_k: O(N^2) and O(N) operations
    where the dense product is O(N^3) (the same numbers, tests/test_quasistatic_segmented.py)."""
    n = len(h0)
    cols = []                                       # (element, vector) per coordinate, Wang's order per element
    for k, h in enumerate(h0):
        angles, u = _element(q, k, dim)
        e_t, partials = tangent(*angles)
        length = h + u
        cols += [(k, ca.vertcat(*[length * d[c] for c in range(dim)])) for d in partials] + [(k, ca.vertcat(*e_t))]
    S, G = [None] * n, [None] * n
    acc_S, acc_G = ca.SX.zeros(dim, dim), ca.SX.zeros(dim, 1)
    for k in reversed(range(n)):                    # node k + 1 is the first below element k
        acc_S = acc_S + M_n[dim * k:dim * k + dim, dim * k:dim * k + dim]
        acc_G = acc_G + g[dim * k:dim * k + dim]
        S[k], G[k] = acc_S, acc_G
    nq = dim * n
    M = ca.SX.zeros(nq, nq)
    f = ca.SX.zeros(nq, 1)
    for a in range(nq):
        ka, ca_ = cols[a]
        f[a] = ca.dot(ca_, G[ka])
        Sa = [ca.mtimes(S[m], ca_) for m in range(n)]   # S_m c_a
        for b in range(a + 1):
            kb, cb = cols[b]
            M[a, b] = ca.dot(cb, Sa[max(ka, kb)])
            M[b, a] = M[a, b]
    return M, f


def _from_nodes(xn, z, zd, h0, dim: int) -> list:
    """The element coordinates and their rates of node positions and velocities ``xn`` (the inverse of
    :func:`_kinematics`): element vectors d = r_b - r_a, phi = atan2(-d_x, d_y), phi_z = atan2(d_z, |d_xy|) (the chord
    angles of :mod:`.segmented`'s outputs), u = |d| - h_0, and their time derivatives."""
    n = len(h0)
    r, rd = xn[:dim * n], xn[dim * n:]
    back, back_d = [], []
    for k in range(n):
        a = [z[c] if k == 0 else r[dim * (k - 1) + c] for c in range(dim)]
        va = [zd[c] if k == 0 else rd[dim * (k - 1) + c] for c in range(dim)]
        d = [r[dim * k + c] - a[c] for c in range(dim)]
        dv = [rd[dim * k + c] - va[c] for c in range(dim)]
        lsq = sum((d[c] ** 2 for c in range(1, dim)), d[0] ** 2)
        length = ca.sqrt(lsq)
        lp2 = d[0] ** 2 + d[1] ** 2 if dim == 3 else lsq             # the element's square in the x-y plane
        angles = [ca.atan2(-d[0], d[1])]
        rates = [(d[0] * dv[1] - d[1] * dv[0]) / lp2]
        if dim == 3:
            lp = ca.sqrt(lp2)
            lpd = (d[0] * dv[0] + d[1] * dv[1]) / lp
            angles.append(ca.atan2(d[2], lp))
            rates.append((lp * dv[2] - d[2] * lpd) / lsq)
        back += angles + [length - h0[k]]
        back_d += rates + [sum((d[c] * dv[c] for c in range(1, dim)), d[0] * dv[0]) / length]
    return back + back_d


def build_element_model(scene: Scene, node: CableModel | None = None) -> ElementModel:
    """The segmented cable of ``scene`` in element coordinates (same ``p`` as the node model).

    Parameters
    ----------
    scene : Scene
        Any scene the node model accepts; ``cable.segments`` per section (1 allowed: one element).
    node : CableModel, optional
        The node model of the same scene (:func:`~cablesys.model.segmented.build_segmented_model`),
        if already built.

    Returns
    -------
    ElementModel
        ``q_labels`` ``phi[k]``, ``u[k]`` (rad, m), in 3-D ``phi[k]``, ``phi_z[k]``, ``u[k]`` (the node model's
        dimension: a planar scene's nodes are planar); ``outputs`` with the node model's labels; ``kind``
        ``"element-coordinates"`` (state scales: none, atol in SI).
    """
    for field, value, why in (("anchor", scene.anchor, "an anchored line's last node is fixed"),
                              ("winch", scene.winch, "a winch changes the element lengths in time"),
                              ("body.pitch_inertia", next((s.body.pitch_inertia for s in scene.sections
                                                           if s.body.is_rigid), None),
                               "a rigid body's orientation is a node-model coordinate")):
        if value is not None:
            raise ParameterError(field, value, f"must be unset for the element coordinates: {why}; the node model "
                                 "(segmented) runs such scenes")
    if node is None:
        from .segmented import build_segmented_model
        node = build_segmented_model(scene)
    dim = node.dim                                     # 2: (phi_k, u_k); 3: (phi_k, phi_z_k, u_k)
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    h0 = zero_tension_lengths(scene, layout)
    n = len(h0)
    nq = dim * n
    q, qd, e = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("e", node.top.size1_out(0))
    z, zd, zdd = e[1:1 + dim], e[1 + dim:1 + 2 * dim], e[1 + 2 * dim:1 + 3 * dim]
    R = _kinematics(q, z, h0, dim)
    J = ca.jacobian(R, q)
    Jqd = ca.mtimes(J, qd)
    v = Jqd + ca.repmat(zd, n, 1)                                  # r' = Z z' + J q'
    known = ca.jtimes(Jqd, q, qd) + ca.repmat(zdd, n, 1)           # r'' - J q'' = J' q' + Z z''
    M_n, f_n = node.dynamics(R, v, e, p)
    if _block_diagonal(node.dynamics.sparsity_out(0), n, dim):
        M, f = _chain_transform(q, h0, M_n, f_n - ca.mtimes(M_n, known), dim)
    else:                                                          # any node mass matrix: dense
        M = ca.mtimes([J.T, M_n, J])                               # virtual work: J^T M_n J
        f = ca.mtimes(J.T, f_n - ca.mtimes(M_n, known))
    x = ca.vertcat(q, qd)
    x_n = ca.vertcat(R, v)

    # inverse map: element vectors from consecutive nodes (chord angles and length, as segmented's outputs)
    xn = ca.SX.sym("x_n", 2 * nq)
    from_nodes = ca.Function("from_nodes", [xn, e, p], [ca.vertcat(*_from_nodes(xn, z, zd, h0, dim))],
                             ["x_n", "e", "p"], ["x"])
    to_nodes = ca.Function("to_nodes", [x, e, p], [x_n], ["x", "e", "p"], ["x_n"])

    dynamics = ca.Function("dynamics", [q, qd, e, p], [M, f], ["q", "qd", "e", "p"], ["M", "f"])
    outputs = ca.Function("outputs", [x, e, p], [node.outputs(x_n, e, p)], ["x", "e", "p"], ["y"])
    K, V = node.energy(x_n, e, p)
    energy = ca.Function("energy", [x, e, p], [K, V], ["x", "e", "p"], ["K", "V"])
    cable_force = ca.Function("cable_force", [x, p], [ca.SX(0, 1)], ["x", "p"], ["gap"])
    S = node.symbolic
    xs, ts, ps = S.sym("x", 2 * nq), S.sym("t"), S.sym("p", len(layout))
    M_t, f_t = dynamics(xs[:nq], xs[nq:], node.top(ts, ps), ps)
    ode = ca.Function("ode", [xs, ts, ps], [ca.vertcat(xs[nq:], ca.solve(M_t, f_t))], ["x", "t", "p"], ["xdot"])
    q_labels = tuple(f"{c}[{k}]" for k in range(n) for c in COORDINATES[dim])
    return ElementModel(layout=layout, n_sections=node.n_sections, angles=node.angles, q_labels=q_labels,
                        output_labels=node.output_labels, dynamics=dynamics, ode=ode, top=node.top,
                        outputs=outputs, energy=energy, cable_force=cable_force, slack_index=(),
                        symbolic=S, kind="element-coordinates",
                        elements=tuple(s.cable.segments for s in scene.sections),
                        to_nodes=to_nodes, from_nodes=from_nodes, node_model=node)

