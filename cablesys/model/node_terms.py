"""The node model's sums per node: element and body terms added node by node, Lagrange's equations per node.

Both node models assemble their equations here: the chain of sections (:mod:`.segmented`: nodes numbered top to
bottom) and the graph of lines joined at points (:mod:`.system`: nodes numbered line by line). Each element
(:func:`.segmented_element.element_terms`) lumps at its two end nodes half its mass and added mass (its kinetic
energy, Wang 1971 eq. 5, 23-24; the inertia blocks and the inertial forces of the added mass by AD,
:func:`.segmented_element.element_inertia`), half its weight in water (eq. 12), the virtual work of its tension (eq.
46, 54: -T dl/dr) and its drag shares (eq. 42, 44); a point body (Wang's body, eq. 16, 32-35) adds its virtual
masses, weight and drag at its node. Lagrange's equations are then, node by node (Wang 1971 eq. 8-9 with eq. 15's
gravity, y down), M_j q''_j = f_j with f_j = Q_j + (0, W_j, 0) + F_inertia_j: M is block diagonal (dim x dim per
node) and each block is solved in closed form (:func:`.segmented_element.block_solve`). Units SI.
"""

from __future__ import annotations

import casadi as ca

from .segmented_element import body_drag, element_inertia, element_terms, lump_kinetic

__all__ = ["NodeSums"]


class NodeSums:
    """The sums of the element and body terms at ``n`` nodes of ``dim`` coordinates (2 in the plane, 3 in space).

    ``K`` the kinetic energy (J), ``V_strain`` the elements' strain energy (J), ``Q[j]`` the generalized forces
    (tension and drag, N), ``Q_static[j]`` the same with the statics' tension law, ``M[j]`` the mass block (kg),
    ``F[j]`` the inertial forces of the added mass (N), ``weights[j]`` the weight in water lumped at node j (N, down),
    ``area[j]`` its seabed contact area d_0 l (m^2).
    """

    def __init__(self, n: int, dim: int):
        self.n, self.dim = n, dim
        self.K, self.V_strain = 0.0, 0.0
        self.Q = [[0.0] * dim for _ in range(n)]
        self.Q_static = [[0.0] * dim for _ in range(n)]
        self.area = [0.0] * n
        self.M = [ca.SX.zeros(dim, dim) for _ in range(n)]
        self.F = [ca.SX.zeros(dim, 1) for _ in range(n)]
        self.weights = [0.0] * n

    def element(self, el: dict, va, vb, inertia, P, n_el: int, static_law: bool) -> None:
        """Add one element (``el`` from :func:`.segmented_element.element_terms` with its end nodes ``el["a"]``,
        ``el["b"]``; ``va``, ``vb`` the velocities its terms see; ``inertia`` the (M_a, M_b, f_a, f_b) of
        :func:`.segmented_element.element_inertia`; ``P`` its section's parameters, ``n_el`` the section's element
        count). ``static_law``: the statics' tension is (AE)_r strain, elastic both ways (a seabed's statics),
        else the element's own law. Sets ``el["static_tension"]``."""
        a, b, dim = el["a"], el["b"], self.dim
        self.K += lump_kinetic(el, va, vb)
        Ma, Mb, fa, fb = inertia
        self.M[a], self.M[b] = self.M[a] + Ma, self.M[b] + Mb
        self.F[a], self.F[b] = self.F[a] + fa, self.F[b] + fb
        self.weights[a] += 0.5 * el["weight"]
        self.weights[b] += 0.5 * el["weight"]
        self.V_strain += el["strain_energy"]
        el["static_tension"] = P.ae * el["strain"] if static_law else el["tension"]
        for c in range(dim):     # tension -T dl/dr (virtual work of eq. 46/54), drag shares
            self.Q[a][c] += el["tension"] * el["et"][c] + el["drag_a"][c]
            self.Q[b][c] += -el["tension"] * el["et"][c] + el["drag_b"][c]
            self.Q_static[a][c] += el["static_tension"] * el["et"][c] + el["drag_a"][c]
            self.Q_static[b][c] += -el["static_tension"] * el["et"][c] + el["drag_b"][c]
        self.area[a] += 0.5 * P.l_r / n_el * P.d_0
        self.area[b] += 0.5 * P.l_r / n_el * P.d_0

    def section(self, P, n_el: int, seq, node_r, node_v, *, pay=None, p, rho, t, env, depth0, n_points: int,
                static_law: bool) -> tuple:
        """Add the ``n_el`` elements of one line section from node ``seq[0]`` to ``seq[n_el]`` (its nodes in order;
        ``P`` its parameters at its reference length, ``n_points`` drag points per element); ``pay`` a winch's
        :class:`.segmented_winch.Payout` paying the section out at ``seq[0]`` (its elements at L(t), material end
        velocities and the payout's inertia terms) or None. Returns (the elements' terms, the section's parameters as
        its elements see them: at L(t) under a winch)."""
        dim = self.dim
        inertia = (pay.inertia if pay else element_inertia)(P, n_el, p, rho, t, env, depth0, n_points, dim)
        P = pay.section(P) if pay else P
        els = []
        for k in range(n_el):
            a, b = seq[k], seq[k + 1]
            va, vb = pay.velocities(k, n_el, node_r[a], node_v[a], node_r[b], node_v[b]) if pay else (node_v[a], node_v[b])
            el = element_terms(P, n_el, node_r[a], va, node_r[b], vb, rho=rho, t=t, env=env, depth0=depth0,
                               n_points=n_points)
            el.update(a=a, b=b)
            self.element(el, va, vb, inertia(ca.vertcat(*node_r[a]), ca.vertcat(*node_r[b]), ca.vertcat(*node_v[a]),
                                             ca.vertcat(*node_v[b]), p, *((pay.z(k, n_el),) if pay else ())),
                         P, n_el, static_law)
            els.append(el)
        return els, P

    def point_body(self, j: int, P, r, v, *, rho, t, env, depth0) -> None:
        """Add Wang's point body at node j (position r, velocity v): virtual masses M_bvx, M_bvy (M_bvz in space) in
        the kinetic energy and the mass block (eq. 16), its weight in water W_b, its drag (eq. 32-35). ``P`` has
        ``m_bx``, ``m_by``, ``m_bz``, ``w_b`` and the drag fields of :func:`.segmented_element.body_drag`."""
        dim = self.dim
        masses = (P.m_bx, P.m_by) + ((P.m_bz,) if dim == 3 else ())   # eq. 16; M_bvz in space
        self.K += 0.5 * sum((masses[c] * v[c] ** 2 for c in range(2, dim)), P.m_bx * v[0] ** 2 + P.m_by * v[1] ** 2)
        self.M[j] = self.M[j] + ca.diag(ca.vertcat(*masses))
        self.weights[j] += P.w_b
        D_b = body_drag(P, rho, r, v, t, env, depth0)        # eq. 32-35
        for c in range(dim):
            self.Q[j][c] += D_b[c]

    def gravity(self, node_r) -> ca.SX:
        """The potential of the weights in water, V = -sum_j W_j y_j (Wang 1971 eq. 15 with y down; J)."""
        return -sum(w * r[1] for w, r in zip(self.weights, node_r))

    def force(self, j: int, static: bool = False) -> ca.SX:
        """f_j: the generalized forces at node j plus its weight (down, +y) and the added mass's inertial forces."""
        Q = self.Q_static[j] if static else self.Q[j]
        return self.F[j] + ca.vertcat(Q[0], Q[1] + self.weights[j], *Q[2:])
