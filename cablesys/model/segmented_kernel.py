"""The segmented cable's right-hand side as an element kernel mapped over the elements.

:func:`cablesys.model.segmented.build_segmented_model` writes the right-hand side out element by
element: one straight-line SX expression whose size grows with N (the 300 m heave cable: ~300
operations per element, ~24k at N = 80, four copies in an RK4 step). Compiled, that is megabytes
of C: gcc needs its -O0 or -O1 past ~20 elements, and the code no longer fits the instruction
cache. The same equations are the same few functions of each element's two end nodes, so here:

- one SX function per section, the *element kernel* ``(r_a, r_b, v_a, v_b, t, p) -> (M_a, M_b,
  F_a, F_b)``: the 2 x 2 mass blocks and forces the element lumps at its two end nodes (tension
  and drag shares, half its weight, the inertial forces of its added mass: Wang 1971 eq. 5, 12,
  23-24, 42-46, 54), built from :func:`.segmented_element.element_terms` and :func:`.segmented_element.element_inertia`
  (the same physics, no copy);
- the kernel evaluated over all elements of a section with ``Function.map`` (a loop in the
  generated C), its node terms added column-shifted (node j gets F_a of element j and F_b of
  element j - 1), the body's mass, weight and drag (eq. 16, 32-35) added at its node;
- the 2 x 2 node solves M_j q''_j = f_j mapped over the nodes.

The generated C is a loop of constant size at any N (it compiles in seconds at -O3) and computes
the same numbers as the element-by-element expression to rounding (the sums are taken in another
order): ``tests/test_segmented_kernel.py``. It is the segmented model's ``kernel_ode``, an MX
function with the interface of ``ode``; compiled explicit loops use it at large N
(:attr:`.segmented.SegmentedModel.loop_ode`).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from .params import ParameterLayout, environment_symbols, section_prefix
from .section import SectionParameters
from .segmented_element import block_solve, body_drag, element_inertia, element_terms
from .top_motion import top_motion_function

__all__ = ["kernel_jacobian", "kernel_ode", "kernel_statics"]


def _element_kernel(P: SectionParameters, n_el: int, p, t, env, rho, depth0, n_points: int, name: str,
                    dim: int = 2) -> ca.Function:
    """``(r_a, r_b, v_a, v_b, t, p) -> (M_a, M_b, F_a, F_b)`` of one element of a section: its mass
    blocks (dim^2 entries, column-major) and the forces it lumps at its end nodes (virtual work of the
    tension, eq. 46/54, and drag, eq. 42-44; half its weight, eq. 12; inertial forces, eq. 8-9)."""
    ra, rb, va, vb = (ca.SX.sym(s, dim) for s in ("ra", "rb", "va", "vb"))
    cols = lambda v: tuple(v[c] for c in range(dim))
    el = element_terms(P, n_el, cols(ra), cols(va), cols(rb), cols(vb), rho=rho, t=t, env=env,
                       depth0=depth0, n_points=n_points)
    Ma, Mb, fa, fb = element_inertia(P, n_el, p, rho, t, env, depth0, n_points, dim)(ra, rb, va, vb, p)
    w2 = 0.5 * el["weight"]
    Fa = fa + ca.vertcat(*[el["tension"] * el["et"][c] + el["drag_a"][c] + (w2 if c == 1 else 0.0) for c in range(dim)])
    Fb = fb + ca.vertcat(*[-el["tension"] * el["et"][c] + el["drag_b"][c] + (w2 if c == 1 else 0.0) for c in range(dim)])
    # the inertia function repeats the element's length, unit vectors and thinned diameter: common
    # subexpressions merged (340 -> 256 operations per element on the 300 m heave cable, same arithmetic)
    d2 = dim * dim
    outs = ca.vertsplit(ca.cse(ca.vertcat(ca.vec(Ma), ca.vec(Mb), Fa, Fb)), [0, d2, 2 * d2, 2 * d2 + dim, 2 * d2 + 2 * dim])
    return ca.Function(name, [ra, rb, va, vb, t, p], outs,
                       ["ra", "rb", "va", "vb", "t", "p"], ["Ma", "Mb", "Fa", "Fb"])


def _body(P: SectionParameters, p, t, env, rho, depth0, name: str, dim: int = 2) -> ca.Function:
    """``(r, v, t, p) -> (M, F)``: the body's mass block (eq. 16; M_bvz in 3-D), weight in water and drag (eq. 32-35)."""
    r, v = ca.SX.sym("r", dim), ca.SX.sym("v", dim)
    D = body_drag(P, rho, tuple(r[c] for c in range(dim)), tuple(v[c] for c in range(dim)), t, env, depth0)
    M = (ca.vertcat(P.m_bx, 0.0, 0.0, P.m_by) if dim == 2 else
         ca.vertcat(P.m_bx, 0.0, 0.0, 0.0, P.m_by, 0.0, 0.0, 0.0, P.m_bz))
    return ca.Function(name, [r, v, t, p], [M, ca.vertcat(D[0], D[1] + P.w_b, *D[2:])], ["r", "v", "t", "p"], ["M", "F"])


def _solve2() -> ca.Function:
    """``(M, f) -> q''``: one node's 2 x 2 block (column-major) solved in closed form (Cramer)."""
    m, f = ca.SX.sym("M", 4), ca.SX.sym("f", 2)
    m11, m21, m12, m22 = m[0], m[1], m[2], m[3]
    det = m11 * m22 - m12 * m21
    return ca.Function("node_solve", [m, f], [ca.vertcat((m22 * f[0] - m12 * f[1]) / det, (m11 * f[1] - m21 * f[0]) / det)])


def _solve3() -> ca.Function:
    """``(M, f) -> q''``: one node's 3 x 3 block (column-major) solved in closed form (:func:`.segmented_element.block_solve`)."""
    m, f = ca.SX.sym("M", 9), ca.SX.sym("f", 3)
    return ca.Function("node_solve", [m, f], [ca.vertcat(*block_solve(ca.reshape(m, 3, 3), f))])


def _element_jacobian(kern: ca.Function, dim: int, name: str, static: bool = False) -> ca.Function:
    """``(r_a, r_b, v_a, v_b, t, p, a_a, a_b) -> (L_b, D_b, D_a, U_a)``: the derivatives of one element's end residuals
    g_a = F_a - M_a a_a and g_b = F_b - M_b a_b (the end accelerations a held fixed) with respect to its end nodes,
    each dim x 2 dim with the columns (d/dr, d/dv) of one node: L_b, D_b the b end's with respect to nodes a and b,
    D_a, U_a the a end's with respect to nodes a and b (CasADi's SX AD of the kernel).

    ``static``: at rest (v = a = 0 substituted before differentiating, so the terms quadratic in the velocities
    drop out of the expression), the derivatives of the end forces F_a, F_b with respect to the end positions only
    (each dim x dim); the velocity and acceleration inputs are kept and not used."""
    ra, rb, va, vb, aa, ab = (ca.SX.sym(s, dim) for s in ("ra", "rb", "va", "vb", "aa", "ab"))
    t, p = ca.SX.sym("t"), ca.SX.sym("p", kern.size1_in(5))
    if static:
        _, _, ga, gb = kern(ra, rb, ca.SX.zeros(dim), ca.SX.zeros(dim), t, p)
        node_a, node_b, w = ra, rb, dim
    else:
        Ma, Mb, Fa, Fb = kern(ra, rb, va, vb, t, p)
        ga = Fa - ca.mtimes(ca.reshape(Ma, dim, dim), aa)
        gb = Fb - ca.mtimes(ca.reshape(Mb, dim, dim), ab)
        node_a, node_b, w = ca.vertcat(ra, va), ca.vertcat(rb, vb), 2 * dim
    outs = [ca.densify(ca.jacobian(g, z)) for g, z in ((gb, node_a), (gb, node_b), (ga, node_a), (ga, node_b))]
    sizes = [0] + [o.numel() for o in outs]
    flat = ca.vertsplit(ca.cse(ca.vertcat(*[ca.vec(o) for o in outs])), list(np.cumsum(sizes)))
    return ca.Function(name, [ra, rb, va, vb, t, p, aa, ab], [ca.reshape(f, dim, w) for f in flat],
                       ["ra", "rb", "va", "vb", "t", "p", "aa", "ab"], ["Lb", "Db", "Da", "Ua"])


def _body_jacobian(body: ca.Function, dim: int, name: str, static: bool = False) -> ca.Function:
    """``(r, v, t, p, a) -> D``: the derivative of the body's residual F - M a (a fixed) with respect to its node
    (dim x 2 dim, columns d/dr, d/dv); ``static``: of F at v = 0 with respect to r only (dim x dim)."""
    r, v, a, t, p = ca.SX.sym("r", dim), ca.SX.sym("v", dim), ca.SX.sym("a", dim), ca.SX.sym("t"), ca.SX.sym("p", body.size1_in(3))
    if static:
        D = ca.jacobian(body(r, ca.SX.zeros(dim), t, p)[1], r)
    else:
        M, F = body(r, v, t, p)
        D = ca.jacobian(F - ca.mtimes(ca.reshape(M, dim, dim), a), ca.vertcat(r, v))
    return ca.Function(name, [r, v, t, p, a], [ca.densify(D)], ["r", "v", "t", "p", "a"], ["D"])


def _solve_columns(dim: int, cols: int) -> ca.Function:
    """``(M, B) -> M^-1 B``: one node's mass block (column-major) applied inverted to ``cols`` columns, in closed form
    (:func:`.segmented_element.block_solve`, column by column)."""
    m, b = ca.SX.sym("M", dim * dim), ca.SX.sym("B", dim, cols)
    mm = ca.reshape(m, dim, dim)
    return ca.Function("node_solve_columns", [m, b], [ca.horzcat(*[ca.vertcat(*block_solve(mm, b[:, c])) for c in range(cols)])])


def _on_used_parameters(kern: ca.Function) -> tuple[ca.Function, list]:
    """(the element kernel with its parameter input ``p`` cut to the entries it depends on, their indices in ``p``).

    A map's shared input is copied once per element (CasADi repeats it into a column per call), so the mapped kernel
    takes only its section's and the environment's entries (``casadi.which_depends``), not the whole scene vector."""
    # harsh_sea ROV lift, planar, N = 46: 22 of p's 181 entries; copying all of p per element was ~1/3 of a
    # right-hand side (7.0 -> 5.2 us, bit-identical results)
    ins = [ca.SX.sym(kern.name_in(k), kern.sparsity_in(k)) for k in range(kern.n_in())]
    k_p = kern.name_in().index("p")
    outs = kern.call(ins)
    used = [k for k, d in enumerate(ca.which_depends(ca.vertcat(*[ca.vec(o) for o in outs]), ins[k_p], 1, False)) if d]
    pk = ca.SX.sym("p", len(used))
    full = ca.SX(ins[k_p].shape[0], 1)
    for j, k in enumerate(used):
        full[k] = pk[j]
    args = ins[:k_p] + [full] + ins[k_p + 1:]
    return ca.Function(kern.name(), ins[:k_p] + [pk] + ins[k_p + 1:], kern.call(args), kern.name_in(),
                       kern.name_out()), used


def _mapped(f: ca.Function, n: int, name: str, shared=()) -> ca.Function:
    """``f`` mapped serially over ``n`` columns (inputs ``shared`` repeated), or ``f`` itself when n = 1."""
    return f.map(name, "serial", n, list(shared), []) if n > 1 else f


def _assembled(scene, n_points, static: bool = False):
    """The pieces :func:`kernel_ode`, :func:`kernel_jacobian` and :func:`kernel_statics` are made of: the symbols
    (x, t, p), the node positions R and velocities V (dim x (n + 1), column 0 the prescribed top; with an
    ``[anchor]`` a last column, the anchor's parameters (anchor.x, anchor.y[, anchor.z]) at rest: the line's last node
    is fixed there and is no coordinate, as in :mod:`.segmented`), each section's (element kernel, element-terms inputs,
    body function, first node, elements) and the node sums M, F (mass blocks column-major, forces; one column per free
    node: the anchor's column, where the last section's body sits and loads the support only, is dropped).

    ``static``: the state is the free node positions q alone, every velocity zero, the top at rest at its mean
    position and t = 0 (the statics' f(q, q' = 0, e = 0, p) of :func:`cablesys.statics.problem.static_residual`)."""
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    t = ca.SX.sym("t")
    env = environment_symbols(layout, scene)          # Wang 1971 eq. 26-28 inputs
    rho, depth0 = env["density"], env["top_depth"]
    n_sec = len(scene.sections)
    segs = [s.cable.segments for s in scene.sections]
    anchored = scene.anchor is not None
    n_nodes = sum(segs) - int(anchored)               # free nodes

    dim = 3 if scene.three_d else 2                   # nodes (x, y) in the plane, (x, y, z) in space
    axes = ("x", "y", "z")[:dim]
    pm = ca.MX.sym("p", p.shape[0])
    if static:
        xm, tm = ca.MX.sym("q", dim * n_nodes), ca.MX(0.0)
        top_r = top_v = ca.MX.zeros(dim, 1)
        v_free = ca.MX.zeros(dim, n_nodes)
    else:
        xm, tm = ca.MX.sym("x", 2 * dim * n_nodes), ca.MX.sym("t")
        e = top_motion_function(scene, layout)(tm, pm)
        top_r, top_v = e[1:1 + dim], e[1 + dim:1 + 2 * dim]
        v_free = ca.reshape(xm[dim * n_nodes:], dim, n_nodes)
    fixed_r = [ca.vertcat(*[pm[layout.index(f"anchor.{c}")] for c in axes])] if anchored else []
    R = ca.horzcat(top_r, ca.reshape(xm[: dim * n_nodes], dim, n_nodes), *fixed_r)   # node 0 (the top) prescribed
    V = ca.horzcat(top_v, v_free, *([ca.MX.zeros(dim, 1)] if anchored else []))
    parts = []                           # per section: element terms (M_a, M_b, F_a, F_b) and body (M, F)
    sections = []
    j0 = 0
    for i, sec in enumerate(scene.sections):
        P = SectionParameters.from_layout(layout, section_prefix(n_sec, i), sec.body.is_sphere, dim == 3)
        n_el = segs[i]
        kern, used = _on_used_parameters(_element_kernel(P, n_el, p, t, env, rho, depth0, n_points(n_el), f"element_{i}", dim))
        args = (R[:, j0:j0 + n_el], R[:, j0 + 1:j0 + n_el + 1], V[:, j0:j0 + n_el], V[:, j0 + 1:j0 + n_el + 1], tm, pm[used])
        terms = _mapped(kern, n_el, f"elements_{i}", (4, 5))(*args)
        jb = j0 + n_el
        body = _body(P, p, t, env, rho, depth0, f"body_{i}", dim)
        parts.append((terms, body(R[:, jb], V[:, jb], tm, pm)))
        sections.append((kern, args, body, j0, n_el))
        j0 = jb
    # node sums, nodes 1..: the b ends of a section's elements (nodes j0 + 1 .. jb) plus the a ends of
    # its elements 1.. (nodes j0 + 1 .. jb - 1), the body at jb and the next section's first a end
    M_cols, F_cols = [], []
    for i, ((Ma, Mb, Fa, Fb), (M_body, F_body)) in enumerate(parts):
        nxt = parts[i + 1][0] if i + 1 < len(parts) else None
        M_end = M_body + (nxt[0][:, 0] if nxt else 0)
        F_end = F_body + (nxt[2][:, 0] if nxt else 0)
        M_cols.append(Mb + ca.horzcat(Ma[:, 1:], M_end))
        F_cols.append(Fb + ca.horzcat(Fa[:, 1:], F_end))
    return dict(x=xm, t=tm, p=pm, R=R, V=V, dim=dim, n_nodes=n_nodes, sections=sections,
                M=ca.horzcat(*M_cols)[:, :n_nodes], F=ca.horzcat(*F_cols)[:, :n_nodes])


def kernel_ode(scene, n_points) -> ca.Function:
    """The segmented model's ``ode(x, t, p) -> xdot`` assembled from mapped element kernels (MX).

    Parameters
    ----------
    scene : Scene
        A scene whose sections have ``cable.segments`` elements.
    n_points : callable
        ``n_points(n_el)``: drag points per element (:func:`.segmented.drag_points` of the scene).

    Returns
    -------
    casadi.Function
        ``ode(x, t, p) -> xdot`` (MX), x = (q, q') with q = (x_1, y_1, x_2, y_2, ...) the free nodes
        ((x_1, y_1, z_1, ...) in a 3-D scene).
    """
    a = _assembled(scene, n_points)
    acc = _accelerations(a)
    xm, n, dim = a["x"], a["n_nodes"], a["dim"]
    return ca.Function("ode", [xm, a["t"], a["p"]], [ca.vertcat(xm[dim * n:], ca.vec(acc))], ["x", "t", "p"], ["xdot"])


def _accelerations(a: dict) -> ca.MX:
    """The node accelerations (dim x n): the 2 x 2 (3 x 3) node solves M_j q''_j = f_j mapped over the nodes."""
    solve = _solve3() if a["dim"] == 3 else _solve2()
    return _mapped(solve, a["n_nodes"], "node_solves")(a["M"], a["F"])


def kernel_jacobian(scene, n_points) -> ca.Function:
    """``jac(x, t, p) -> d xdot / d x`` of :func:`kernel_ode`, sparse (each node's acceleration depends on its own
    and its two neighbours' positions and velocities), from the elements' derivatives by the chain rule (MX).

    The node accelerations solve M_j(x) a_j = F_j(x), so d a_j = M_j^-1 d(F_j - M_j a_j) with a_j held at its value;
    F_j - M_j a_j is a sum over the node's two elements (and its body) of end residuals whose derivatives with respect
    to the element's two end nodes come from CasADi's AD of the element kernel (:func:`_element_jacobian`), mapped
    over the elements like the kernel itself, then summed per node and solved column by column. This is the
    Jacobian AD of the whole mapped ``ode`` gives (to rounding: ``tests/test_segmented_kernel.py``) at a fraction of
    its cost: AD of the assembled function seeds a direction per colour of the block-tridiagonal pattern (12 in the
    plane) through every element and copies the result's nonzeros out of them, where here each element is
    differentiated once with respect to its own 4 dim inputs (the costs: :func:`cablesys.time_domain.integrators.
    kernel_dae_functions`).

    Parameters
    ----------
    scene, n_points
        As :func:`kernel_ode`.

    Returns
    -------
    casadi.Function
        ``jac(x, t, p) -> J`` (MX), J = d xdot / d x with the sparsity of that block-tridiagonal pattern
        (q' rows: the identity on the velocities; q'' rows: 3 nodes x 2 dim columns, fewer at the ends).
    """
    a = _assembled(scene, n_points)
    dim, n = a["dim"], a["n_nodes"]
    w = 2 * dim                                        # one node's columns (d/dr, d/dv)
    L, D, U = _node_blocks(a, _accelerations(a))
    # node j's block row [L_j D_j U_j] (dim x 3 w), solved with its mass block
    B = ca.reshape(ca.vertcat(*[ca.reshape(X, dim * w, n) for X in (L, D, U)]), dim, 3 * w * n)
    sol = _mapped(_solve_columns(dim, 3 * w), n, "node_solves_columns")(a["M"], B)   # dim x (3 w n)
    rows, cols, src = _jacobian_pattern(dim, n)
    values = ca.vertcat(ca.vec(sol), ca.MX.ones(dim * n))
    sp = ca.Sparsity.triplet(2 * dim * n, 2 * dim * n, list(rows), list(cols))
    return ca.Function("ode_jacobian", [a["x"], a["t"], a["p"]], [ca.MX(sp, values[list(src)])], ["x", "t", "p"], ["jac"])


def _node_blocks(a: dict, acc, static: bool = False) -> tuple:
    """(L, D, U), each dim x (w n): node j's derivatives of F_j - M_j a_j (the accelerations ``acc``, dim x n,
    held fixed) with respect to the nodes j - 1, j and j + 1, columns (d/dr, d/dv) per node, w = 2 dim (zero past the
    ends; the top's and an anchor's columns are not coordinates and are dropped by :func:`_jacobian_pattern`): the
    elements' end derivatives (:func:`_element_jacobian`) and the bodies' (:func:`_body_jacobian`), summed per node.
    ``static``: of F_j at rest with respect to the positions only (w = dim)."""
    dim, n = a["dim"], a["n_nodes"]
    w = dim if static else 2 * dim
    fixed = a["R"].shape[1] - n - 1                    # an anchor's column after the free nodes (its a = 0)
    A = ca.horzcat(ca.MX.zeros(dim, 1), acc, ca.MX.zeros(dim, fixed))   # node 0 (the top): its row is not in the state
    pieces = []
    for i, (kern, args, body, j0, n_el) in enumerate(a["sections"]):
        jac = _mapped(_element_jacobian(kern, dim, f"element_jacobian_{i}", static), n_el, f"element_jacobians_{i}",
                      (4, 5))
        Lb, Db, Da, Ua = jac(*args, A[:, j0:j0 + n_el], A[:, j0 + 1:j0 + n_el + 1])
        jb = j0 + n_el
        D_body = _body_jacobian(body, dim, f"body_jacobian_{i}", static)(a["R"][:, jb], a["V"][:, jb], a["t"], a["p"],
                                                                          A[:, jb])
        pieces.append((Lb, Db, Da, Ua, D_body))
    L_cols, D_cols, U_cols = [], [], []
    for i, (Lb, Db, Da, Ua, D_body) in enumerate(pieces):
        nxt = pieces[i + 1] if i + 1 < len(pieces) else None
        D_end = D_body + (nxt[2][:, :w] if nxt else 0)
        U_end = nxt[3][:, :w] if nxt else ca.MX.zeros(dim, w)
        L_cols.append(Lb)
        D_cols.append(Db + ca.horzcat(Da[:, w:], D_end))
        U_cols.append(ca.horzcat(Ua[:, w:], U_end))
    return tuple(ca.horzcat(*X)[:, :w * n] for X in (L_cols, D_cols, U_cols))    # an anchor's row dropped


def _jacobian_pattern(dim: int, n: int, velocities: bool = True):
    """(rows, cols, source) of the nonzeros of a block-tridiagonal node Jacobian in column-major order.

    ``velocities`` (:func:`kernel_jacobian`): d xdot / d x, ``source`` indexing the vector (vec of the solved node
    blocks, dim x 3 (2 dim) per node, then the dim n ones of the q' rows); else (:func:`kernel_statics`) d f / d q,
    ``source`` indexing vec of the node blocks dim x 3 dim (position columns only)."""
    w = 2 * dim if velocities else dim
    grid = np.meshgrid(np.arange(n), np.arange(3), np.arange(w), np.arange(dim), indexing="ij")
    j, k, c, r = (g.ravel() for g in grid)
    node = j + k - 1                                   # free-node index of the column node (-1: the top, n: none)
    keep = (node >= 0) & (node < n)
    j, k, c, r, node = j[keep], k[keep], c[keep], r[keep], node[keep]
    src = (j * 3 * w + k * w + c) * dim + r
    col = np.where(c < dim, node * dim + c, dim * n + node * dim + c - dim)
    row = dim * n + j * dim + r if velocities else j * dim + r
    if velocities:
        off = dim * 3 * w * n
        ident = np.arange(dim * n)
        row, col = np.concatenate([row, ident]), np.concatenate([col, dim * n + ident])
        src = np.concatenate([src, off + ident])
    order = np.lexsort((row, col))
    return row[order].tolist(), col[order].tolist(), src[order].tolist()


def kernel_statics(scene, n_points) -> tuple[ca.Function, ca.Function]:
    """``forces(q, p) -> (M, f)`` and ``stiffness(q, p) -> K`` of a segmented scene at rest, from the mapped element
    kernels (MX): the free nodes' mass blocks M (dim^2 x n, column-major per node), forces f (dim n: f(q, q' = 0,
    e = 0, p) of the element-by-element ``dynamics``, the statics' residual before scaling) and their stiffness
    K = -d f / d q (dim n x dim n, sparse block-tridiagonal), every velocity zero, the top at rest at its mean
    position, t = 0. Two functions, so that the statics' residual does not evaluate K.

    K is the chain rule over the elements' AD as in :func:`kernel_jacobian`, at rest and without the node solves:
    d f_j / d r_k summed from the end derivatives of node j's two elements and its body (:func:`_node_blocks`; the
    Jacobian CasADi's AD of the element-by-element f gives, to rounding: ``tests/test_span_kernel.py``). About an
    equilibrium (f = 0) M q'' + K q = 0 are the linearized equations of motion (Lagrange's equations of the node
    model, Wang 1971 eq. 8-9, with the lumped element terms of eq. 5, 12, 23-24, 46). No function of size N is built:
    the graph is the element kernel and its Jacobian mapped over the elements.

    Parameters
    ----------
    scene, n_points
        As :func:`kernel_ode` (an ``[anchor]`` fixes the last node: :func:`_assembled`).
    """
    a = _assembled(scene, n_points, static=True)
    dim, n = a["dim"], a["n_nodes"]
    L, D, U = _node_blocks(a, ca.MX.zeros(dim, n), static=True)
    B = ca.reshape(ca.vertcat(*[ca.reshape(X, dim * dim, n) for X in (L, D, U)]), dim, 3 * dim * n)
    rows, cols, src = _jacobian_pattern(dim, n, velocities=False)
    K = -ca.MX(ca.Sparsity.triplet(dim * n, dim * n, rows, cols), ca.vec(B)[src])
    return (ca.Function("kernel_forces", [a["x"], a["p"]], [a["M"], ca.vec(a["F"])], ["q", "p"], ["M", "f"]),
            ca.Function("kernel_stiffness", [a["x"], a["p"]], [K], ["q", "p"], ["K"]))
