"""The segmented cable in generalized coordinates per element: inclination and stretch (phi_k, u_k).

The same physics as the node model (:mod:`.segmented`), in other coordinates. Wang (1971, p. 33)
describes the segmented cable as "several segments ... each segment has two degrees of freedom":
element k has the inclination phi_k (from the vertical, clockwise positive) and the stretch
u_k = l_k - h_0 (h_0 = l_0 / N the element's zero-tension length, eq. 1). The node positions follow
by forward kinematics from the top point z (the exogenous input e), with Wang's unit tangent
e_t = (-sin phi, cos phi) (eq. 10, y down):

    r_j = z + sum_{k < j} (h_0 + u_k) e_t(phi_k),          r = R(q_g, z)  (holonomic, invertible)

so r' = Z z' + J q_g' and r'' = Z z'' + J q_g'' + J' q_g', with J = dR/dq_g (CasADi AD), Z the
column of 2 x 2 identities and J' q_g' = d(J q_g')/dq_g q_g'. The node model's equations
M_n r'' = f_n (Lagrange's equations of the lumped cable, eq. 8-9 with eq. 12, 15-16, 23-24, 32-35,
42-46, 54) transform by virtual work (the generalized forces of q_g are J^T times the node forces):

    (J^T M_n J) q_g'' = J^T (f_n - M_n (Z z'' + J' q_g'))

Tension, drag, weight and the inertial forces of the added mass all come with f_n; nothing is
written twice. The model is the building block of the quasi-static segmented rung
(:mod:`.quasistatic`), whose split into slow (``phi``) and fast (``u``) coordinates needs exactly
these coordinates. Its outputs are the node model's (the state mapped back to node positions and
velocities). Runs of it start from the node model's elastic catenary mapped by ``from_nodes``
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


@dataclasses.dataclass(frozen=True, eq=False)
class ElementModel(CableModel):
    """A :class:`CableModel` with coordinates ``phi[k]``, ``u[k]`` per element (k = 0.. top to bottom).

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


def _kinematics(q, z, h0):
    """Node positions r_1..r_N (stacked x, y) of elements (phi_k, u_k) hung from z (Wang 1971 eq. 10)."""
    rx, ry, pos = z[0], z[1], []
    for k, h in enumerate(h0):
        length = h + q[2 * k + 1]
        rx, ry = rx - length * ca.sin(q[2 * k]), ry + length * ca.cos(q[2 * k])
        pos += [rx, ry]
    return ca.vertcat(*pos)


def _block_diagonal(sp: ca.Sparsity, n: int) -> bool:
    """Whether a (2n x 2n) sparsity couples only the two coordinates of each node."""
    rows, cols = sp.get_triplet()
    return sp.size1() == 2 * n and all(r // 2 == c // 2 for r, c in zip(rows, cols))


def _chain_transform(q, h0, M_n, g):
    """J^T M_n J and J^T g for a 2 x 2 block-diagonal M_n, by the chain's structure: coordinate k (phi_k or
    u_k) moves every node below element k by the same vector c (dR/dphi_k = l_k de_t/dphi, dR/du_k = e_t),
    so with the suffix sums S_k = sum_{j > k} M_j and G_k = sum_{j > k} g_j (nodes below element k),
    (J^T M_n J)_{ab} = c_a^T S_max(k_a, k_b) c_b and (J^T g)_a = c_a^T G_k: O(N^2) and O(N) operations
    where the dense product is O(N^3) (the same numbers, tests/test_quasistatic_segmented.py)."""
    n = len(h0)
    cols = []                                       # (element, 2-vector) per coordinate, phi_k then u_k
    for k, h in enumerate(h0):
        c, s_ = ca.cos(q[2 * k]), ca.sin(q[2 * k])
        cols += [(k, ca.vertcat(-(h + q[2 * k + 1]) * c, -(h + q[2 * k + 1]) * s_)), (k, ca.vertcat(-s_, c))]
    S, G = [None] * n, [None] * n
    acc_S, acc_G = ca.SX.zeros(2, 2), ca.SX.zeros(2, 1)
    for k in reversed(range(n)):                    # node k + 1 is the first below element k
        acc_S = acc_S + M_n[2 * k:2 * k + 2, 2 * k:2 * k + 2]
        acc_G = acc_G + g[2 * k:2 * k + 2]
        S[k], G[k] = acc_S, acc_G
    nq = 2 * n
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
        ``q_labels`` ``phi[k]``, ``u[k]`` (rad, m); ``outputs`` with the node model's labels;
        ``kind`` ``"element-coordinates"`` (state scales: none, atol in SI).
    """
    if scene.three_d:
        raise ParameterError("numerics.dimensions", 3, "must be 2 or unset for the element coordinates (phi_k, u_k): "
                             "they are planar (one inclination per element); the node model runs 3-D scenes")
    if node is None:
        from .segmented import build_segmented_model
        node = build_segmented_model(scene)
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    h0 = zero_tension_lengths(scene, layout)
    n = len(h0)
    nq = 2 * n
    q, qd, e = ca.SX.sym("q", nq), ca.SX.sym("qd", nq), ca.SX.sym("e", 7)
    z, zd, zdd = e[1:3], e[3:5], e[5:7]
    R = _kinematics(q, z, h0)
    J = ca.jacobian(R, q)
    Jqd = ca.mtimes(J, qd)
    v = Jqd + ca.repmat(zd, n, 1)                                  # r' = Z z' + J q'
    known = ca.jtimes(Jqd, q, qd) + ca.repmat(zdd, n, 1)           # r'' - J q'' = J' q' + Z z''
    M_n, f_n = node.dynamics(R, v, e, p)
    if _block_diagonal(node.dynamics.sparsity_out(0), n):
        M, f = _chain_transform(q, h0, M_n, f_n - ca.mtimes(M_n, known))
    else:                                                          # any node mass matrix: dense
        M = ca.mtimes([J.T, M_n, J])                               # virtual work: J^T M_n J
        f = ca.mtimes(J.T, f_n - ca.mtimes(M_n, known))
    x = ca.vertcat(q, qd)
    x_n = ca.vertcat(R, v)

    # inverse map: element vectors from consecutive nodes (chord angle and length, as segmented's outputs)
    xn = ca.SX.sym("x_n", 2 * nq)
    r, rd = xn[:nq], xn[nq:]
    back, back_d = [], []
    for k in range(n):
        a = (z[0], z[1]) if k == 0 else (r[2 * k - 2], r[2 * k - 1])
        va = (zd[0], zd[1]) if k == 0 else (rd[2 * k - 2], rd[2 * k - 1])
        dx, dy = r[2 * k] - a[0], r[2 * k + 1] - a[1]
        dvx, dvy = rd[2 * k] - va[0], rd[2 * k + 1] - va[1]
        lsq = dx**2 + dy**2
        length = ca.sqrt(lsq)
        back += [ca.atan2(-dx, dy), length - h0[k]]
        back_d += [(dx * dvy - dy * dvx) / lsq, (dx * dvx + dy * dvy) / length]
    from_nodes = ca.Function("from_nodes", [xn, e, p], [ca.vertcat(*back, *back_d)], ["x_n", "e", "p"], ["x"])
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
    q_labels = tuple(f"{c}[{k}]" for k in range(n) for c in ("phi", "u"))
    return ElementModel(layout=layout, n_sections=node.n_sections, angles=node.angles, q_labels=q_labels,
                        output_labels=node.output_labels, dynamics=dynamics, ode=ode, top=node.top,
                        outputs=outputs, energy=energy, cable_force=cable_force, slack_index=(),
                        symbolic=S, kind="element-coordinates",
                        elements=tuple(s.cable.segments for s in scene.sections),
                        to_nodes=to_nodes, from_nodes=from_nodes, node_model=node)

