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

__all__ = ["kernel_jacobian", "kernel_ode"]


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


def _element_jacobian(kern: ca.Function, dim: int, name: str) -> ca.Function:
    """``(r_a, r_b, v_a, v_b, t, p, a_a, a_b) -> (L_b, D_b, D_a, U_a)``: the derivatives of one element's end residuals
    g_a = F_a - M_a a_a and g_b = F_b - M_b a_b (the end accelerations a held fixed) with respect to its end nodes,
    each dim x 2 dim with the columns (d/dr, d/dv) of one node: L_b, D_b the b end's with respect to nodes a and b,
    D_a, U_a the a end's with respect to nodes a and b (CasADi's SX AD of the kernel)."""
    ra, rb, va, vb, aa, ab = (ca.SX.sym(s, dim) for s in ("ra", "rb", "va", "vb", "aa", "ab"))
    t, p = ca.SX.sym("t"), ca.SX.sym("p", kern.size1_in(5))
    Ma, Mb, Fa, Fb = kern(ra, rb, va, vb, t, p)
    ga = Fa - ca.mtimes(ca.reshape(Ma, dim, dim), aa)
    gb = Fb - ca.mtimes(ca.reshape(Mb, dim, dim), ab)
    node_a, node_b = ca.vertcat(ra, va), ca.vertcat(rb, vb)
    outs = [ca.densify(ca.jacobian(g, z)) for g, z in ((gb, node_a), (gb, node_b), (ga, node_a), (ga, node_b))]
    sizes = [0] + [o.numel() for o in outs]
    flat = ca.vertsplit(ca.cse(ca.vertcat(*[ca.vec(o) for o in outs])), list(np.cumsum(sizes)))
    return ca.Function(name, [ra, rb, va, vb, t, p, aa, ab], [ca.reshape(f, dim, 2 * dim) for f in flat],
                       ["ra", "rb", "va", "vb", "t", "p", "aa", "ab"], ["Lb", "Db", "Da", "Ua"])


def _body_jacobian(body: ca.Function, dim: int, name: str) -> ca.Function:
    """``(r, v, t, p, a) -> D``: the derivative of the body's residual F - M a (a fixed) with respect to its node
    (dim x 2 dim, columns d/dr, d/dv)."""
    r, v, a, t, p = ca.SX.sym("r", dim), ca.SX.sym("v", dim), ca.SX.sym("a", dim), ca.SX.sym("t"), ca.SX.sym("p", body.size1_in(3))
    M, F = body(r, v, t, p)
    g = F - ca.mtimes(ca.reshape(M, dim, dim), a)
    return ca.Function(name, [r, v, t, p, a], [ca.densify(ca.jacobian(g, ca.vertcat(r, v)))], ["r", "v", "t", "p", "a"], ["D"])


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


def _assembled(scene, n_points):
    """The pieces both :func:`kernel_ode` and :func:`kernel_jacobian` are made of: the symbols (x, t, p), the node
    positions R and velocities V (dim x (n + 1), column 0 the prescribed top), each section's (element kernel,
    element-terms inputs, mapped terms, body function, body terms) and the node sums M_all, F_all (mass blocks
    column-major, forces; one column per free node)."""
    layout = ParameterLayout.from_scene(scene)
    p = layout.symbol
    t = ca.SX.sym("t")
    env = environment_symbols(layout, scene)          # Wang 1971 eq. 26-28 inputs
    rho, depth0 = env["density"], env["top_depth"]
    n_sec = len(scene.sections)
    segs = [s.cable.segments for s in scene.sections]
    n_nodes = sum(segs)

    dim = 3 if scene.three_d else 2                   # nodes (x, y) in the plane, (x, y, z) in space
    xm, tm, pm = ca.MX.sym("x", 2 * dim * n_nodes), ca.MX.sym("t"), ca.MX.sym("p", p.shape[0])
    e = top_motion_function(scene, layout)(tm, pm)
    R = ca.horzcat(e[1:1 + dim], ca.reshape(xm[: dim * n_nodes], dim, n_nodes))       # node 0 (the top) prescribed
    V = ca.horzcat(e[1 + dim:1 + 2 * dim], ca.reshape(xm[dim * n_nodes:], dim, n_nodes))
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
                M=ca.horzcat(*M_cols), F=ca.horzcat(*F_cols))


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
    acc = _accelerations(a)
    A = ca.horzcat(ca.MX.zeros(dim, 1), acc)          # node 0 (the top): its row is not in the state
    L_cols, D_cols, U_cols = [], [], []
    pieces = []
    for i, (kern, args, body, j0, n_el) in enumerate(a["sections"]):
        jac = _mapped(_element_jacobian(kern, dim, f"element_jacobian_{i}"), n_el, f"element_jacobians_{i}", (4, 5))
        Lb, Db, Da, Ua = jac(*args, A[:, j0:j0 + n_el], A[:, j0 + 1:j0 + n_el + 1])
        jb = j0 + n_el
        D_body = _body_jacobian(body, dim, f"body_jacobian_{i}")(a["R"][:, jb], a["V"][:, jb], a["t"], a["p"], A[:, jb])
        pieces.append((Lb, Db, Da, Ua, D_body))
    w = 2 * dim                                        # one node's columns (d/dr, d/dv)
    for i, (Lb, Db, Da, Ua, D_body) in enumerate(pieces):
        nxt = pieces[i + 1] if i + 1 < len(pieces) else None
        D_end = D_body + (nxt[2][:, :w] if nxt else 0)
        U_end = nxt[3][:, :w] if nxt else ca.MX.zeros(dim, w)
        L_cols.append(Lb)
        D_cols.append(Db + ca.horzcat(Da[:, w:], D_end))
        U_cols.append(ca.horzcat(Ua[:, w:], U_end))
    L, D, U = ca.horzcat(*L_cols), ca.horzcat(*D_cols), ca.horzcat(*U_cols)
    # node j's block row [L_j D_j U_j] (dim x 3 w), solved with its mass block
    B = ca.reshape(ca.vertcat(*[ca.reshape(X, dim * w, n) for X in (L, D, U)]), dim, 3 * w * n)
    sol = _mapped(_solve_columns(dim, 3 * w), n, "node_solves_columns")(a["M"], B)   # dim x (3 w n)
    rows, cols, src = _jacobian_pattern(dim, n)
    values = ca.vertcat(ca.vec(sol), ca.MX.ones(dim * n))
    sp = ca.Sparsity.triplet(2 * dim * n, 2 * dim * n, list(rows), list(cols))
    return ca.Function("ode_jacobian", [a["x"], a["t"], a["p"]], [ca.MX(sp, values[list(src)])], ["x", "t", "p"], ["jac"])


def _jacobian_pattern(dim: int, n: int):
    """(rows, cols, source) of the nonzeros of :func:`kernel_jacobian`'s result in column-major order: ``source``
    indexes the vector (vec of the solved node blocks, dim x 3 (2 dim) per node, then dim n ones of the q' rows)."""
    w = 2 * dim
    entries = []
    for j in range(n):                                 # free node j + 1; block k = 0, 1, 2: nodes j, j + 1, j + 2
        for k in range(3):
            node = j + k - 1                           # free-node index of the column node (-1: the top, n: none)
            if node < 0 or node >= n:
                continue
            for c in range(w):                         # d/dr_0.., d/dv_0..
                col = (node * dim + c) if c < dim else (dim * n + node * dim + c - dim)
                for r in range(dim):
                    entries.append((col, dim * n + j * dim + r, (j * 3 * w + k * w + c) * dim + r))
    off = dim * 3 * w * n
    entries += [(dim * n + i, i, off + i) for i in range(dim * n)]
    entries.sort()
    cols, rows, src = zip(*entries)
    return rows, cols, src
