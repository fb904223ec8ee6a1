"""The seabed under the segmented cable: normal contact and Coulomb friction at the nodes.

The bed is a plane. In the plane of the planar model it is the line y = y_0 + x tan(alpha) (node coordinates: y down
from the top's mean depth, y_0 = seabed.depth - environment.top_depth, alpha = seabed.slope_deg), with the unit normal
into the bed n = (-sin alpha, cos alpha) and the tangent along it t = (cos alpha, sin alpha). In space (nodes (x, y, z),
z the sway) it deepens towards the horizontal heading beta = seabed.heading_deg (from +x towards +z, as the current's
headings): y = y_0 + tan(alpha) (x cos beta + z sin beta), n = (-sin alpha cos beta, cos alpha, -sin alpha sin beta),
its down-slope tangent t = (cos alpha cos beta, sin alpha, cos alpha sin beta) and the level tangent across the slope
(-sin beta, 0, cos beta); at beta = 0 and z = 0 these are the plane's. A node at r penetrates by
delta = n . r - y_0 cos alpha. Its contact area is A = d_0 l, l half of each adjacent element's unstretched length
(MoorDyn's seabed model, Hall & Goupee 2015, with kBot = k and cBot = c per unit area):

- normal force F_n = max(0, k A delta + c A delta') while delta > 0, acting along -n; its elastic
  part derives from the potential V = k A max(delta, 0)^2 / 2 (in the model's energy, so that with
  c = 0 the contact neither creates nor destroys energy);
- Coulomb friction in the bed's plane on the sliding velocity v of the cable's material at the node (the node's
  velocity, or with a ``[winch]`` the material's, which slides past the node: :mod:`.segmented_winch`), each
  direction's sign(.) replaced by a tanh over the sliding speed v_s so that stick-slip does not stall the integrator:
  in the plane F_f = -mu_a F_n tanh(v_t / v_s) along t, v_t = v . t (mu_a = seabed.friction_axial: a node there slides
  along the bed, which is along the line lying on it); in space, with the axial and lateral coefficients of an
  anisotropic Coulomb law (MoorDyn v2's mu_kA and mu_kT, Hall 2020, NREL/TP-5000-82033), the axial direction
  e_a = p / sqrt(p . p + eps^2) from the line's tangent at the node projected on the bed, p = (I - n n^T) tau (tau the
  sum of the unit axes of the node's elements), and the lateral part of the velocity v_l = (I - n n^T - e_a e_a^T) v:
  F_f = -F_n [mu_a tanh(v . e_a / v_s) e_a + mu_l tanh(|v_l| / v_s) v_l / |v_l|] (|v_l| regularised as
  sqrt(v_l . v_l + (eta v_s)^2), :data:`LATERAL_SPEED_EPS`). A line lying on the bed has |p| ~ 2 and e_a its unit
  direction; where the line stands normal to the bed (|p| below eps, :data:`TANGENT_EPS`, e.g. a package landed under
  a vertical line) there is no axial direction, e_a -> 0 and the friction is the lateral coefficient's in every
  direction of the bed, as MoorDyn's (whose axial velocity is along the unprojected tangent). A planar scene run
  in space has p along t and v_l = 0: the plane's law, to the relative eps^2 ~ 1e-13;
- at rest (the statics) the friction of the line laid down by pulling its fairlead away from the
  anchor: at a node on the bed the friction points towards the anchor with the magnitude
  min(mu F_n, T_up |e_up . t|), T_up and e_up the tension and axis of the element on the fairlead
  side, so that the tension decreases by mu w per unit length along the bed towards the anchor
  and stops at zero (the classic mooring-line catenary with seabed friction, Jonkman 2007, NREL/TP-
  500-41958; its closed form is :func:`cablesys.statics.closed_forms.seabed_catenary`). In space the same along the
  up element's axis projected on the bed, e = (I - n n^T) e_up: min(mu_a F_n, T_up |e|) e / |e|. The statics hold no
  lateral friction: a load across a laid line at rest (a current across it, a bed sloping across it) is carried by
  the line's tension and curvature, as by a line laid with no lateral load and then loaded slowly; the lateral
  friction acts in the time domain (the static state of a stick is history, not geometry).

Forces in N, lengths in m, k in Pa/m, c in Pa s/m, v_s in m/s.
"""

from __future__ import annotations

import casadi as ca

from .segmented_element import dot

__all__ = ["seabed_forces", "bed_frame"]

TANGENT_EPS = 1e-6
"""eps of the axial direction e_a = p / sqrt(p . p + eps^2) (dimensionless: |p| is up to 2), below which a line standing
normal to the bed has no axial direction; a laid line's e_a is its unit direction to a relative 1e-13."""
LATERAL_SPEED_EPS = 1e-6
"""eta of the lateral speed's regularisation sqrt(v_l . v_l + (eta v_s)^2) (dimensionless), so that the lateral
friction's direction v_l / |v_l| is smooth at v_l = 0; it changes the law by a relative eta^2."""


def bed_frame(alpha, beta, dim: int):
    """(n, t, c) of the bed: the unit normal into it, the down-slope tangent and (in space) the level tangent across
    the slope (module docstring; alpha the slope, beta its heading, rad). In the plane c is None and beta unused."""
    if dim == 2:
        return (-ca.sin(alpha), ca.cos(alpha)), (ca.cos(alpha), ca.sin(alpha)), None
    return ((-ca.sin(alpha) * ca.cos(beta), ca.cos(alpha), -ca.sin(alpha) * ca.sin(beta)),
            (ca.cos(alpha) * ca.cos(beta), ca.sin(alpha), ca.cos(alpha) * ca.sin(beta)),
            (-ca.sin(beta), 0.0, ca.cos(beta)))


def seabed_forces(layout, node_r, node_v, area, elements, depth0, nodes, up: dict | None = None,
                  down: dict | None = None) -> dict:
    """Contact and friction forces of the seabed on the free ``nodes`` (indices into ``node_r``).

    Parameters
    ----------
    layout : ParameterLayout
        With the ``seabed.*`` entries (and ``seabed.heading_deg`` in space).
    node_r, node_v : list of tuples
        Node positions (m), node 0 the top, and the velocities the bed resists (m/s): the material's at the node
        (module docstring); 2-tuples in the plane, 3-tuples in space.
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
    down : dict, optional
        {node: the element on its other side} (in space the line's tangent at the node is the sum of the two elements'
        unit axes); default the element starting at the node (``el["a"]``); a node missing from it (a free lower end)
        takes its ``up`` element's axis alone.

    Returns
    -------
    dict
        ``forces``: {j: (dynamic force, static force)} as 2- or 3-tuples (N); ``energy``: the contact
        potential (J); ``normal`` and ``friction``: per node of ``node_r`` the normal force and the
        signed friction force along t in the plane, along the line in space (along e_a, + towards the line's lower
        end); in space also ``lateral``, the friction across the line (along e_a x n) (N; 0 at the top and an anchor).
    """
    sym = lambda name: layout.sym(f"seabed.{name}")
    dim = len(node_r[0])
    k, c, mu, v_s = sym("stiffness"), sym("damping"), sym("friction_axial"), sym("friction_speed")
    alpha = sym("slope_deg") * ca.pi / 180.0
    beta = sym("heading_deg") * ca.pi / 180.0 if dim == 3 else None
    n_in, t_b, _ = bed_frame(alpha, beta, dim)
    y0 = sym("depth") - depth0
    up = up if up is not None else {el["b"]: el for el in elements}   # the element on the fairlead side of each node
    down = down if down is not None else {el["a"]: el for el in elements}   # and on the other side (none at a free end)
    on_bed = lambda v: tuple(v[i] - dot(v, n_in) * n_in[i] for i in range(dim))      # (I - n n^T) v
    forces, energy = {}, 0.0
    normal, friction, lateral = [0.0] * len(node_r), [0.0] * len(node_r), [0.0] * len(node_r)
    for j in nodes:
        r, v, A = node_r[j], node_v[j], area[j]
        delta = dot(n_in, r) - y0 * ca.cos(alpha)
        touch = delta > 0
        F_el = k * A * ca.fmax(delta, 0.0)
        F_n = ca.if_else(touch, ca.fmax(F_el + c * A * dot(n_in, v), 0.0), 0.0)
        el = up[j]
        if dim == 2:
            F_f = -mu * F_n * ca.tanh(dot(v, t_b) / v_s)
            along = dot(el["et"], t_b)
            F_fs = ca.fmin(mu * F_el, ca.fmax(el["static_tension"], 0.0) * ca.fabs(along)) * ca.sign(along)
            dyn = tuple(-F_n * n_in[i] + F_f * t_b[i] for i in range(2))
            sta = tuple(-F_el * n_in[i] + F_fs * t_b[i] for i in range(2))
        else:
            tau = tuple(el["et"][i] + (down[j]["et"][i] if j in down else 0.0) for i in range(3))
            p = on_bed(tau)
            e_a = tuple(p[i] / ca.sqrt(dot(p, p) + TANGENT_EPS ** 2) for i in range(3))
            v_a = dot(v, e_a)
            v_l = tuple(vb - v_a * e_a[i] for i, vb in enumerate(on_bed(v)))
            s_l = ca.sqrt(dot(v_l, v_l) + (LATERAL_SPEED_EPS * v_s) ** 2)
            F_a = -mu * F_n * ca.tanh(v_a / v_s)
            g_l = -sym("friction_lateral") * F_n * ca.tanh(s_l / v_s) / s_l
            e_up = on_bed(el["et"])
            size = ca.sqrt(dot(e_up, e_up) + TANGENT_EPS ** 2)
            g_s = ca.fmin(mu * F_el, ca.fmax(el["static_tension"], 0.0) * size) / size
            dyn = tuple(-F_n * n_in[i] + F_a * e_a[i] + g_l * v_l[i] for i in range(3))
            sta = tuple(-F_el * n_in[i] + g_s * e_up[i] for i in range(3))
            F_f = F_a * ca.sqrt(dot(e_a, e_a))
            across = (e_a[1] * n_in[2] - e_a[2] * n_in[1], e_a[2] * n_in[0] - e_a[0] * n_in[2],
                      e_a[0] * n_in[1] - e_a[1] * n_in[0])                       # e_a x n
            lateral[j] = g_l * dot(v_l, across)
        forces[j] = (dyn, sta)
        energy += 0.5 * k * A * ca.fmax(delta, 0.0) ** 2
        normal[j], friction[j] = F_n, F_f
    out = dict(forces=forces, energy=energy, normal=normal, friction=friction)
    if dim == 3:
        out["lateral"] = lateral
    return out
