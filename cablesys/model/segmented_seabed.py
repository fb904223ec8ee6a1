"""The seabed under the segmented cable: normal contact and Coulomb friction at the nodes.

The bed is the line y = y_0 + x tan(alpha) (node coordinates: y down from the top's mean depth,
y_0 = seabed.depth - environment.top_depth, alpha = seabed.slope_deg), with the unit normal into
the bed n = (-sin alpha, cos alpha) and the tangent along it t = (cos alpha, sin alpha). A node at
r penetrates by delta = n . r - y_0 cos alpha. Its contact area is A = d_0 l, l half of each
adjacent element's unstretched length (MoorDyn's seabed model, Hall & Goupee 2015, with kBot =
k and cBot = c per unit area):

- normal force F_n = max(0, k A delta + c A delta') while delta > 0, acting along -n; its elastic
  part derives from the potential V = k A max(delta, 0)^2 / 2 (in the model's energy, so that with
  c = 0 the contact neither creates nor destroys energy);
- friction along the bed F_f = -mu F_n tanh(v_t / v_s), v_t = v . t (mu = seabed.friction_axial:
  in the plane a node slides along the bed, i.e. along the line lying on it); the tanh replaces
  sign(v_t) so that stick-slip does not stall the integrator;
- at rest (the statics) the friction of the line laid down by pulling its fairlead away from the
  anchor: at a node on the bed the friction points towards the anchor with the magnitude
  min(mu F_n, T_up |e_up . t|), T_up and e_up the tension and axis of the element on the fairlead
  side, so that the tension decreases by mu w per unit length along the bed towards the anchor
  and stops at zero (the classic mooring-line catenary with seabed friction, Jonkman 2007, NREL/TP-
  500-41958; its closed form is :func:`cablesys.statics.closed_forms.seabed_catenary`).

Forces in N, lengths in m, k in Pa/m, c in Pa s/m, v_s in m/s.
"""

from __future__ import annotations

import casadi as ca

__all__ = ["seabed_forces"]


def seabed_forces(layout, node_r, node_v, area, elements, depth0, nodes, up: dict | None = None) -> dict:
    """Contact and friction forces of the seabed on the free ``nodes`` (indices into ``node_r``).

    Parameters
    ----------
    layout : ParameterLayout
        With the ``seabed.*`` entries.
    node_r, node_v : list of (SX, SX)
        Node positions and velocities (m, m/s), node 0 the top.
    area : list
        Contact area d_0 l per node (m^2).
    elements : list of dict
        The elements (:func:`.segmented_element.element_terms` with ``a``, ``b``, ``static_tension``).
    depth0 : SX
        The top's mean depth below the still surface (m).
    nodes : iterable of int
        The free nodes.
    up : dict, optional
        {node: the element on its fairlead side} (the laid-down friction's direction and tension); default the element
        ending at the node (``el["b"]``), the chain's numbering from its top.

    Returns
    -------
    dict
        ``forces``: {j: (dynamic force, static force)} as 2-tuples (N); ``energy``: the contact
        potential (J); ``normal`` and ``friction``: per node of ``node_r`` the normal force and the
        signed friction force along t (N; 0 at the top and an anchor).
    """
    sym = lambda name: layout.sym(f"seabed.{name}")
    k, c, mu, v_s = sym("stiffness"), sym("damping"), sym("friction_axial"), sym("friction_speed")
    alpha = sym("slope_deg") * ca.pi / 180.0
    n_in, t_b = (-ca.sin(alpha), ca.cos(alpha)), (ca.cos(alpha), ca.sin(alpha))
    y0 = sym("depth") - depth0
    up = up if up is not None else {el["b"]: el for el in elements}   # the element on the fairlead side of each node
    dot = lambda a, b: a[0] * b[0] + a[1] * b[1]
    forces, energy = {}, 0.0
    normal, friction = [0.0] * len(node_r), [0.0] * len(node_r)
    for j in nodes:
        r, v, A = node_r[j], node_v[j], area[j]
        delta = dot(n_in, r) - y0 * ca.cos(alpha)
        touch = delta > 0
        F_el = k * A * ca.fmax(delta, 0.0)
        F_n = ca.if_else(touch, ca.fmax(F_el + c * A * dot(n_in, v), 0.0), 0.0)
        F_f = -mu * F_n * ca.tanh(dot(v, t_b) / v_s)
        el = up[j]
        along = dot(el["et"], t_b)
        F_fs = ca.fmin(mu * F_el, ca.fmax(el["static_tension"], 0.0) * ca.fabs(along)) * ca.sign(along)
        forces[j] = (tuple(-F_n * n_in[i] + F_f * t_b[i] for i in range(2)),
                     tuple(-F_el * n_in[i] + F_fs * t_b[i] for i in range(2)))
        energy += 0.5 * k * A * ca.fmax(delta, 0.0) ** 2
        normal[j], friction[j] = F_n, F_f
    return dict(forces=forces, energy=energy, normal=normal, friction=friction)
