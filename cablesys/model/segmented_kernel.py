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

from .params import ParameterLayout, environment_symbols, section_prefix
from .section import SectionParameters
from .segmented_element import block_solve, body_drag, element_inertia, element_terms
from .top_motion import top_motion_function

__all__ = ["kernel_ode"]


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
    j0 = 0
    for i, sec in enumerate(scene.sections):
        P = SectionParameters.from_layout(layout, section_prefix(n_sec, i), sec.body.is_sphere, dim == 3)
        n_el = segs[i]
        kern = _element_kernel(P, n_el, p, t, env, rho, depth0, n_points(n_el), f"element_{i}", dim)
        mapped = kern.map(f"elements_{i}", "serial", n_el, [4, 5], []) if n_el > 1 else kern
        terms = mapped(R[:, j0:j0 + n_el], R[:, j0 + 1:j0 + n_el + 1], V[:, j0:j0 + n_el], V[:, j0 + 1:j0 + n_el + 1], tm, pm)
        jb = j0 + n_el
        parts.append((terms, _body(P, p, t, env, rho, depth0, f"body_{i}", dim)(R[:, jb], V[:, jb], tm, pm)))
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
    M_all, F_all = ca.horzcat(*M_cols), ca.horzcat(*F_cols)
    solve = _solve3() if dim == 3 else _solve2()
    acc = (solve.map("node_solves", "serial", n_nodes, [], []) if n_nodes > 1 else solve)(M_all, F_all)
    return ca.Function("ode", [xm, tm, pm], [ca.vertcat(xm[dim * n_nodes:], ca.vec(acc))], ["x", "t", "p"], ["xdot"])
