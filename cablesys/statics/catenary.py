"""Equilibrium of the segmented cable: the elastic catenary under weight, current and tow.

The static residual is the segmented model's own right-hand side with every rate zero and the
top at rest (:func:`cablesys.statics.problem.static_residual`: waves off, forces scaled by the
total weight). KINSOL solves it with a sparse direct linear solver (the Jacobian is banded),
starting from the straight hanging cable stretched by the weight below each element (exact
without current: the lumped weights give each element the tension of its mid-point). A current
or tow speed that KINSOL cannot reach in one solve is approached by continuation in the flow
speed (each solution the next guess).

The closed forms it is checked against (and an anchored line's first guess) are in
:mod:`cablesys.statics.closed_forms`.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ..errors import SolverError
from ..messages import casadi_warnings_captured, kinsol_flags
from ..model.rigid_body import turned_orientation
from .closed_forms import seabed_catenary, suspended_catenary
from .problem import SteadyState, at_rest, static_parameters, static_residual

TOLERANCE = 1e-10     # largest static force residual over the total weight



def flow_indices(model) -> list[int]:
    """Entries of p that carry the flow: current speeds and the system (tow) speed."""
    return [i for i, lb in enumerate(model.layout.labels)
            if lb.startswith("environment.current_speeds[") or lb == "environment.system_speed"]


def hanging_guess(model, p) -> np.ndarray:
    """Node positions of the straight vertical cable stretched by the weight below each element.

    Parameters
    ----------
    model : SegmentedModel
    p : array
        Parameter vector.

    Returns
    -------
    numpy.ndarray
        q = (x_1, y_1, x_2, y_2, ...) in m (y down from the top); (x_1, y_1, z_1, ...) with z = 0 for a
        3-D model (``model.dim`` = 3).
    """
    lab = model.layout.labels
    val = lambda lbl: p[lab.index(lbl)]
    n = model.n_sections
    pre = (lambda i: "") if n == 1 else (lambda i: f"sections[{i}].")
    # tension at the bottom of each section: bodies and cables below
    bottom, below = [0.0] * n, 0.0
    for i in reversed(range(n)):
        below += val(f"{pre(i)}body.weight")
        bottom[i] = below
        below += val(f"{pre(i)}cable.weight_per_length") * val(f"{pre(i)}cable.length")
    ys, y = [], 0.0
    for i, n_el in enumerate(model.segments):
        l_r, ae = val(f"{pre(i)}cable.length"), val(f"{pre(i)}cable.ae")
        t_r, w = val(f"{pre(i)}cable.tension_ref"), val(f"{pre(i)}cable.weight_per_length")
        h_r, h_0 = l_r / n_el, (l_r - t_r * l_r / ae) / n_el
        for k in range(n_el):
            tension = bottom[i] + w * h_r * (n_el - k - 0.5)        # weight below the element mid-point
            y += h_0 + max(tension, 0.0) * h_r / ae                 # l = h_0 + T h_r / AE (eq. 1 per element)
            ys.append(y)
    cols = [np.zeros(len(ys)), ys] + [np.zeros(len(ys))] * (_dim(model) - 2)
    return np.concatenate([np.column_stack(cols).ravel(), _level(model)])   # rigid bodies level


def _dim(model) -> int:
    """Coordinates per node of a segmented model: 2 in the plane, 3 in space."""
    return getattr(model, "dim", 2)


def _rotations(model) -> int:
    """Rigid bodies' orientation coordinates at the end of a segmented model's q (model/rigid_body.py)."""
    return getattr(model, "n_rotations", 0)


def _level(model) -> np.ndarray:
    """Those coordinates at the level attitude: pitch theta_b = 0 in the plane, the unit quaternion in space."""
    return np.array(getattr(model, "rotation_rest", ()) or np.zeros(_rotations(model)), float)


def anchored_guess(model, p) -> np.ndarray:
    """Free node positions of an anchored line laid along a path of its zero-tension length.

    A heavy line without a seabed hangs free between its ends: the inextensible catenary of its length
    through the top and the anchor (:func:`.closed_forms.suspended_catenary`), pulled taut (:func:`_taut_span`).
    With a seabed it takes the closed-form catenary of its mean properties (:func:`seabed_catenary`, flat rigid bed
    at the anchor's depth); where that fails, the path runs from the anchor along the bed towards the top and rises
    straight to the top (its touchdown point found so that the path is as long as the line), or, when the bed path
    is shorter than the chord (and for a vertical chord without a bed), two straight legs meeting below the chord's
    mid-point. A line shorter than the chord is laid straight (it will be stretched).

    Parameters
    ----------
    model : SegmentedModel
        Anchored (``model.anchored``).
    p : array
        Parameter vector.

    In space the same path lies in the vertical plane through the top and the anchor (bearing psi = atan2(z, x) of
    the anchor), on the bed's slope along that plane, atan(tan(slope) cos(heading - psi)).

    Returns
    -------
    numpy.ndarray
        q = (x_1, y_1, ..., x_{n-1}, y_{n-1}) in m (the anchor node is not a coordinate); (x_j, y_j, z_j) in that
        plane for a 3-D model, and the rigid bodies' orientation coordinates at the level attitude after the nodes.
    """
    from scipy.optimize import brentq

    lab = model.layout.labels
    val = lambda lbl: float(p[lab.index(lbl)])
    A = np.array([val("anchor.x"), val("anchor.y")])
    psi = 0.0
    slope = np.radians(val("seabed.slope_deg")) if "seabed.slope_deg" in lab else 0.0
    if "anchor.z" in lab and val("anchor.z") != 0.0:     # in space, off the x-y plane: the plane through the anchor
        psi, A = np.arctan2(val("anchor.z"), A[0]), np.array([np.hypot(A[0], val("anchor.z")), A[1]])
    if "seabed.heading_deg" in lab:
        slope = np.arctan(np.tan(slope) * np.cos(np.radians(val("seabed.heading_deg")) - psi))
    arcs, s0 = [], 0.0                     # zero-tension arc length of every node from the top
    for i, n_el in enumerate(model.segments):
        l_0 = val(model.layout.labels[model.layout.section_index(i, "cable.length")]) * (
            1 - p[model.layout.section_index(i, "cable.tension_ref")] / p[model.layout.section_index(i, "cable.ae")])
        arcs += [s0 + (k + 1) * l_0 / n_el for k in range(n_el)]
        s0 += l_0
    L, chord = s0, float(np.hypot(*A))
    w = _total_weight(model, p) / L
    if w > 0 and L > chord and abs(A[0]) > 0 and "seabed.depth" not in lab:   # a span: hangs free between its ends
        ea = min(p[model.layout.section_index(i, "cable.ae")] for i in range(model.n_sections))
        taut = _taut_span(L, A, np.array(arcs), min_strain=0.5 * w * L / ea)
        shot = _shot_span(model, p, A, taut)
        return _in_space(model, taut if shot is None else shot, psi)
    if w > 0 and A[1] > 0 and L > chord:            # the closed-form catenary of the mean line (flat bed)
        ea = min(p[model.layout.section_index(i, "cable.ae")] for i in range(model.n_sections))
        mu = val("seabed.friction_axial") if "seabed.friction_axial" in lab else 0.0
        try:
            cat = seabed_catenary(length=L, weight_per_length=w, ea=ea, span=abs(A[0]), height=A[1], friction=mu)
        except SolverError:
            cat = None
        if cat is not None:
            x, z, _ = cat["shape"](L - np.array(arcs[:-1]))
            direction = -np.sign(A[0]) if A[0] != 0 else 1.0
            return _in_space(model, np.column_stack([A[0] + direction * x, A[1] - z]), psi)
    if L <= chord:
        corners = [np.zeros(2), A]
    else:
        corners = None
        if "seabed.depth" in lab:
            t = np.array([np.cos(slope), np.sin(slope)]) * (-np.sign(A[0]) if A[0] != 0 else 1.0)
            excess = lambda a: np.hypot(*(A + a * t)) + a - L      # path length - line length at touchdown a
            if excess(0.0) < 0 < excess(L):
                corners = [np.zeros(2), A + brentq(excess, 0.0, L) * t, A]
        if corners is None:
            mid, n = 0.5 * A, np.array([-A[1], A[0]]) / chord
            n = n if n[1] > 0 else -n                                  # below the chord (y down)
            drop = brentq(lambda h: 2 * np.hypot(0.5 * chord, h) - L, 0.0, L)
            corners = [np.zeros(2), mid + drop * n, A]
    legs = np.diff(np.array(corners), axis=0)
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(legs[:, 0], legs[:, 1]))])
    path = lambda s: np.array([np.interp(s, cum, [c[i] for c in corners]) for i in range(2)])
    q = [path(a / L * cum[-1]) for a in arcs[:-1]]
    return _in_space(model, np.array(q), psi)


#: AE / (line weight) at which :func:`_shot_span`'s continuation in the stiffness starts.
SHOOT_START_STIFFNESS = 1e3


def _shot_span(model, p, anchor, start) -> np.ndarray | None:
    """The free nodes of the lumped elastic catenary between the top and the anchor, by shooting on the first
    element's tension vector F_0 (two unknowns, SciPy's hybrid Powell): each free node's weight adds to it,
    F_{k+1} = F_k + (0, W_{k+1}) (y down; W the half elements' weights in water w h / 2 at each end and a body's
    weight at its node, as the node model lumps them), element k lies along -F_k / |F_k| with the length
    h_k (1 + |F_k| / (AE)_k) of the statics' elastic law (h_k the zero-tension length), and the last element must end
    at the anchor (Irvine 1981, *Cable Structures*, ch. 1, the elastic catenary, here for the lumped line). Without
    a current this is the node model's static state itself, so KINSOL starts on it; a stiff line (AE / w L ~ 1e7)
    stalls from a geometric guess, whose node errors of eps L are forces of AE eps. ``start`` (free nodes, rows
    (x, y)) gives F_0's first guess at AE / W = SHOOT_START_STIFFNESS (W the line's and bodies' weight), from where a
    continuation raises the stiffness a decade a step to the line's own; None when the shooting does not reach the
    anchor."""
    from scipy.optimize import root

    lay = model.layout
    val = lambda i, name: float(p[lay.section_index(i, name)])
    h, ae, we, body = [], [], [], []
    for i, n_el in enumerate(model.segments):
        h_i = val(i, "cable.length") * (1 - val(i, "cable.tension_ref") / val(i, "cable.ae")) / n_el
        h += [h_i] * n_el
        ae += [val(i, "cable.ae")] * n_el
        we += [val(i, "cable.weight_per_length") * h_i] * n_el
        body += [0.0] * (n_el - 1) + [val(i, "body.weight")]
    h, ae, we = np.array(h), np.array(ae), np.array(we)
    loads = 0.5 * (we[:-1] + we[1:]) + np.array(body[:-1])        # the free nodes 1 .. n-1

    def nodes(F0, stiff):
        F = np.asarray(F0, float)[None, :] + np.column_stack([np.zeros(len(h)), np.concatenate([[0.0], np.cumsum(loads)])])
        T = np.linalg.norm(F, axis=1)
        if not np.all(T > 0):
            return None
        return np.cumsum(-F / T[:, None] * (h * (1 + T / stiff))[:, None], axis=0)

    def miss(F0, stiff):
        r = nodes(F0, stiff)
        return np.full(2, 1e300) if r is None else r[-1] - anchor

    # continuation in the stiffness from AE / w L = 1e3 (a sagging line, where the geometric guess's tension
    # is near the solution's) up to the line's own, a decade a step, each from the last F_0
    d = np.asarray(start[0], float)
    scale = min(1.0, SHOOT_START_STIFFNESS * max(we.sum() + sum(body), np.finfo(float).tiny) / ae.min())
    F0 = -d / np.linalg.norm(d) * ae[0] * scale * max(np.linalg.norm(d) / h[0] - 1, 1e-9)
    for f in np.unique(np.r_[np.geomspace(scale, 1.0, max(int(np.ceil(-np.log10(scale))), 0) + 1), 1.0]):
        sol = root(miss, F0, args=(ae * f,), method="hybr", options={"xtol": 1e-14})
        if not np.all(np.isfinite(sol.x)):
            return None
        F0 = sol.x
    r = nodes(F0, ae)
    if r is None or not np.all(np.isfinite(r)) or np.linalg.norm(r[-1] - anchor) > 1e-9 * h.sum():
        return None
    return r[:-1]


def _taut_span(length: float, anchor, arcs, min_strain: float) -> np.ndarray:
    """The free nodes of :func:`.closed_forms.suspended_catenary` with every element stretched by about
    ``min_strain`` (the order of the line's static strain w L / 2 AE): a catenary through the ends of a length
    stretched until each element's chord exceeds its zero-tension length by that, so that no element of the guess is slack (a slack element has
    no stiffness and leaves Newton's matrix singular) and none is far stiffer than the solution."""
    h0 = np.diff(np.concatenate([[0.0], arcs]))
    stretch, target = 1.0, 1.0 + max(min_strain, 1e-9)
    for _ in range(30):
        pts = suspended_catenary(length * stretch, anchor, arcs * stretch)
        chords = np.linalg.norm(np.diff(np.vstack([[0.0, 0.0], pts]), axis=0), axis=1)
        short = float(np.min(chords / h0))
        if short >= target:
            break
        stretch *= target / short
    return pts[:-1]


def _in_space(model, xy, psi: float = 0.0) -> np.ndarray:
    """Planar node positions (rows (x, y)) as the model's q: for a 3-D model turned about the vertical into the plane
    of bearing ``psi`` (rad from +x towards +z; x -> x cos psi, z = x sin psi; z = 0 at psi = 0), and the rigid bodies'
    orientation coordinates at the level attitude (:func:`_level`) after the nodes."""
    if _dim(model) == 3 and psi != 0.0:
        xy = np.column_stack([xy[:, 0] * np.cos(psi), xy[:, 1], xy[:, 0] * np.sin(psi)])
    nodes = np.column_stack([xy] + [np.zeros(len(xy))] * (_dim(model) - xy.shape[1])).ravel()
    return np.concatenate([nodes, _level(model)])


def polar_map(model):
    """q as a function of element angles and lengths, v = (theta_1.., l_1..): r_j = sum_e l_e e_t(theta_e)
    with e_t = (-sin theta, cos theta) (Wang 1971 eq. 10). A rotation is linear in these variables,
    which is what Newton needs to swing a hanging cable into a current (in node coordinates it
    sees a sideways step as a stretch). The Jacobian is dense: the solution is polished in node
    coordinates (sparse). In space v = (theta_1.., psi_1.., l_1..) with Wang's 3-D tangent
    e_t = (-sin theta cos psi, cos theta cos psi, sin psi) (:func:`cablesys.model.section._frame`)."""
    def build():
        n, dim, n_rot = model.n_elements, _dim(model), _rotations(model)
        v = ca.SX.sym("v", dim * n + n_rot)          # the rigid bodies' angles pass through
        th, ln = v[:n], v[(dim - 1) * n:dim * n]
        if dim == 2:
            q = ca.vec(ca.horzcat(ca.cumsum(-ln * ca.sin(th)), ca.cumsum(ln * ca.cos(th))).T)
        else:
            ps = v[n:2 * n]
            q = ca.vec(ca.horzcat(ca.cumsum(-ln * ca.sin(th) * ca.cos(ps)), ca.cumsum(ln * ca.cos(th) * ca.cos(ps)),
                                  ca.cumsum(ln * ca.sin(ps))).T)
        return ca.Function("polar_to_nodes", [v], [ca.vertcat(q, v[dim * n:])])
    return model.derive("catenary_polar", build)


#: A direction of the static Jacobian is neutral below this fraction of its largest singular value.
NEUTRAL_SINGULAR = 1e-12


def _pinned_residual(model) -> ca.Function:
    """The static residual with the rigid bodies' neutral rotations pinned: (q, (p, a_ref, U)) -> r with
    U (a_ref - a) added to the rotation rows (a the orientation coordinates, U an n_rot x n_rot matrix by columns,
    :func:`_neutral_rotations`), which holds a neutral direction (any angle an equilibrium: a pitch about a body
    attached at its CG, the yaw of a body hanging still in space) at its reference value and leaves the others
    free (U = 0 without a neutral direction: the plain residual)."""
    def build():
        n_rot = _rotations(model)
        resid = static_residual(model)
        q = ca.SX.sym("q", model.nq)
        p = ca.SX.sym("p", len(model.layout) + n_rot + n_rot * n_rot)
        r = resid(q, p[:len(model.layout)])
        if n_rot:
            ref = p[len(model.layout):len(model.layout) + n_rot]
            U = ca.reshape(p[len(model.layout) + n_rot:], n_rot, n_rot)
            r = ca.vertcat(r[:model.nq - n_rot], r[model.nq - n_rot:] + ca.mtimes(U, ref - q[model.nq - n_rot:]))
        return ca.Function("pinned_residual", [q, p], [r])
    return model.derive("static_pinned_residual", build)


def _pins(model, q, p) -> np.ndarray:
    """The pins' parameters (a_ref, U by columns) at q (:func:`_pinned_residual`): the orientation coordinates held
    at their values in q along the neutral directions there; empty without rigid bodies."""
    n_rot = _rotations(model)
    if not n_rot:
        return np.zeros(0)
    return np.concatenate([q[len(q) - n_rot:], _neutral_rotations(model, q, p).ravel(order="F")])


def _neutral_rotations(model, q, p) -> np.ndarray:
    """U = sum_k u_k u_k^T over the neutral rotations at q: the combinations u of the orientation rows that feel no
    coordinate, u^T J[a, :] = 0 (J the static Jacobian, to NEUTRAL_SINGULAR of its largest entry; SVD of the n_rot
    rows). The orientation rows are the generalized forces conjugate to the orientation coordinates, so u is also
    the direction that row combination leaves undetermined. Such a direction turns a body whose static moment and
    its every derivative vanish along it: attached at the CG with the buoyancy centre there (any pitch), hanging
    still in space (any yaw about the vertical through its attachment, model/rigid_body.py). U pins it in
    :func:`_pinned_residual`, so that Newton's matrix is not singular; U = 0 where no rotation is neutral."""
    n_rot = _rotations(model)
    _, J = model.derive("static_residual_jacobian", lambda: _residual_jacobian(model))(q, p)
    rows = np.array(J)[-n_rot:, :].T                  # nq x n_rot: its right null space are the rows' combinations u
    _, sv, vt = np.linalg.svd(rows)
    tol = NEUTRAL_SINGULAR * max(float(np.max(np.abs(np.array(J)))), np.finfo(float).tiny)
    u = vt[np.concatenate([sv, np.zeros(n_rot - sv.size)]) <= tol].T
    return u @ u.T


def _rootfinders(model):
    """KINSOL in polar and in node coordinates on the static residual with the rigid bodies' pins
    (:func:`_pinned_residual`); their parameter vector is (p, a_ref, U)."""
    def build():
        n_rot = _rotations(model)
        to_q = polar_map(model)
        pinned = _pinned_residual(model)
        v = ca.SX.sym("v", _dim(model) * model.n_elements + n_rot)
        q = ca.SX.sym("q", model.nq)
        p = ca.SX.sym("p", len(model.layout) + n_rot + n_rot * n_rot)
        G = ca.Function("polar_residual", [v, p], [pinned(to_q(v), p)])
        opts = {"strategy": "linesearch", "abstol": 1e-13, "error_on_fail": False, "print_level": 0,
                "disable_internal_warnings": True, "max_iter": 200}
        polar = ca.rootfinder("catenary_polar", "kinsol", G, opts)
        nodes = ca.rootfinder("catenary_nodes", "kinsol", ca.Function("node_residual", [q, p], [pinned(q, p)]),
                              dict(opts, linear_solver_type="user_defined", linear_solver="csparse"))
        return polar, nodes
    return model.derive("catenary_rootfinders", build)


def static_tolerance(model, p) -> float:
    """TOLERANCE, or the round-off floor of the scaled residual when stiff elements set it: a node
    position known to eps x (cable length) gives an element force error k_e eps L."""
    def val(i, name):
        return p[model.layout.section_index(i, name)]
    total_l = sum(val(i, "cable.length") for i in range(model.n_sections))
    k_max = max(val(i, "cable.ae") * n / val(i, "cable.length") for i, n in enumerate(model.segments))
    if "seabed.stiffness" in model.layout.labels:       # a node's contact stiffness k d_0 l
        k_bed = p[model.layout.index("seabed.stiffness")]
        k_max = max(k_max, max(k_bed * val(i, "cable.diameter") * val(i, "cable.length") / n
                               for i, n in enumerate(model.segments)))
    weight = sum(abs(val(i, "body.weight")) + abs(val(i, "cable.weight_per_length")) * val(i, "cable.length")
                 for i in range(model.n_sections))
    return max(TOLERANCE, 1e3 * np.finfo(float).eps * k_max * total_l / weight)


def to_polar(q, dim: int = 2, rotations: int = 0):
    """The inverse of :func:`polar_map`: element angles and lengths of node positions q (the last
    ``rotations`` entries of q, rigid bodies' angles, pass through)."""
    q, rot = np.asarray(q, float), np.asarray(q, float)[len(q) - rotations:]
    d = np.diff(np.concatenate([np.zeros(dim), q[:len(q) - rotations]]).reshape(-1, dim), axis=0)
    theta, flat = np.arctan2(-d[:, 0], d[:, 1]), np.hypot(d[:, 0], d[:, 1])
    if dim == 2:
        return np.concatenate([theta, flat, rot])
    return np.concatenate([theta, np.arctan2(d[:, 2], flat), np.linalg.norm(d, axis=1), rot])


def segmented_equilibrium(model, p, *, guess=None):
    """Equilibrium node positions of a segmented model (waves off, top at rest).

    Parameters
    ----------
    model : SegmentedModel
    p : array
        Parameter vector (wave amplitudes are ignored).
    guess : array, optional
        Starting node positions; default the stretched vertical cable.

    Returns
    -------
    (numpy.ndarray, float)
        q and the largest scaled residual (forces over the total weight).

    Raises
    ------
    SolverError
        When neither the direct solve nor the continuation in flow speed converges.
    """
    p = static_parameters(model, p)
    if getattr(model, "anchored", False):
        return anchored_equilibrium(model, p, guess)
    polar, nodes = _rootfinders(model)
    resid, to_q = static_residual(model), polar_map(model)
    g0 = hanging_guess(model, p) if guess is None else np.asarray(guess, float)

    tol = static_tolerance(model, p)
    # a neutral rotation (any angle an equilibrium) is held at its guess (:func:`_pinned_residual`)
    pins = _pins(model, g0, p)
    pinned = lambda pp: np.concatenate([pp, pins])

    def residual(q, pp):
        return _max_residual(resid, q, pp)

    def solve(q0, pp):
        """Polar Newton from q0, then node-coordinate Newton to polish; (q, residual)."""
        r0 = residual(q0, pp)
        if r0 < tol:
            return q0, r0
        v = np.array(polar(to_polar(q0, _dim(model), _rotations(model)), pinned(pp))).ravel()
        q = np.array(to_q(v)).ravel() if np.all(np.isfinite(v)) else q0
        q_pol = np.array(nodes(q, pinned(pp))).ravel()
        return min(((q, residual(q, pp)), (q_pol, residual(q_pol, pp))), key=lambda a: a[1])

    # KINSOL's stalls on a guess are expected (the next guess or continuation step is tried): collected,
    # named in the error if every try fails, otherwise dropped
    with casadi_warnings_captured() as kinsol:
        q, r = solve(g0, p)
        if not r < tol:                   # continuation in flow speed, adaptive steps
            q, lam = flow_continuation(solve, hanging_guess(model, p), p, flow_indices(model), tol)
            r = residual(q, p) if lam >= 1.0 else np.inf
    if not r < tol:
        raise SolverError(f"segmented cable equilibrium not found (best scaled residual {r:.3g}): KINSOL failed from "
                          f"the hanging cable and along the flow-speed continuation{_flags(kinsol)}; a very strong "
                          "current or tow streams the cable horizontally: check weights and speeds, or give a guess")
    return q, r


def flow_continuation(solve, q, p, flow, tol, lam: float = 0.0) -> tuple:
    """(q, lambda reached): the equilibrium followed from ``q`` (solved with the flow entries ``flow`` of ``p`` scaled by
    ``lam``) as the flow speed grows to its full value in adaptive steps (a quarter first, doubled after a success,
    halved after a failure, given up below 1/1024); ``solve(q, p) -> (q, scaled residual)``, success below ``tol``."""
    step = 0.25
    while lam < 1.0 and step > 1.0 / 1024:
        pp = p.copy()
        pp[flow] *= min(1.0, lam + step)
        q_try, r = solve(q, pp)
        if r < tol:
            q, lam, step = q_try, min(1.0, lam + step), 2.0 * step
        else:
            step *= 0.5
    return q, lam


#: KINSOL in node coordinates: a line search, a sparse direct solve (the static Jacobian is banded per line).
NODE_KINSOL = {"strategy": "linesearch", "abstol": 1e-13, "error_on_fail": False, "print_level": 0,
               "disable_internal_warnings": True, "max_iter": 400, "linear_solver_type": "user_defined",
               "linear_solver": "csparse"}


def _residual_jacobian(model):
    resid = static_residual(model)
    q, p = ca.SX.sym("q", model.nq), ca.SX.sym("p", len(model.layout))
    r = resid(q, p)
    return ca.Function("static_residual_jacobian", [q, p], [r, ca.jacobian(r, q)])


def _flags(blocks) -> str:
    """`` (KINSOL: FLAG, ...)`` of the collected CasADi warnings, or nothing."""
    flags = kinsol_flags(blocks)
    return f" (KINSOL: {', '.join(flags)})" if flags else ""


def _max_residual(resid, q, p) -> float:
    return float(np.max(np.abs(np.array(resid(q, p))))) if np.all(np.isfinite(q)) else np.inf


def _node_rootfinder(model):
    def build():
        return ca.rootfinder("catenary_anchored", "kinsol", _pinned_residual(model), NODE_KINSOL)
    return model.derive("catenary_anchored_rootfinder", build)


def anchored_equilibrium(model, p, guess=None, functions=None):
    """The static state of an anchored line: KINSOL in node coordinates from ``guess`` (default
    :func:`anchored_guess`). With a seabed the statics' elements are elastic both ways (segmented_seabed.py) and a
    solution with a compressed element is refused; without one (a span) KINSOL first solves with the elements elastic
    both ways, then from there with the line's own law. ``functions``: (scaled static residual, its KINSOL
    rootfinder), default the model's (:func:`.problem.static_residual`); a span's element-kernel form
    (:class:`cablesys.statics.span.SpanKernel`) passes its own. Returns (q, scaled residual)."""
    resid, nodes = functions if functions is not None else (static_residual(model), _node_rootfinder(model))
    tol = static_tolerance(model, p)
    q = anchored_guess(model, p) if guess is None else np.asarray(guess, float)
    best = np.inf
    passes = [p]
    if "seabed.depth" not in model.layout.labels:
        # a span hanging free: first with every element elastic both ways (tension floor -(AE)_r), so that an
        # element Newton shortens past its zero-tension length keeps its stiffness, then with the line's own law
        both = p.copy()
        for i in range(model.n_sections):
            both[model.layout.section_index(i, "cable.tension_floor")] = -p[model.layout.section_index(i, "cable.ae")]
        passes = [both, p]
    with casadi_warnings_captured() as kinsol:
        for pp in passes:
            best = np.inf
            for _ in range(3):      # KINSOL restarted from its own last iterate, neutral rotations pinned there
                q_new = np.array(nodes(q, np.concatenate([pp, _pins(model, q, pp)]))).ravel()
                r = _max_residual(resid, q_new, pp)
                if r < best:
                    q, best = q_new, r
                if best < tol:
                    break
    if not best < tol:
        raise SolverError(f"anchored line equilibrium not found (best scaled residual {best:.3g} > {tol:.3g}): "
                          f"KINSOL failed from the line's first guess{_flags(kinsol)}; give a guess")
    if "seabed.depth" in model.layout.labels:
        T = _static_tensions(model, q, p)
        floor = -1e3 * np.finfo(float).eps * max(1.0, float(np.max(np.abs(T)))) - tol * _total_weight(model, p)
        if T.min() < floor:
            raise SolverError(f"the anchored line's static state has a compressed element (tension {T.min():.6g} N "
                              f"at element {int(T.argmin())}): the seabed statics hold only for a line in tension or "
                              "lying unstretched on the bed")
    return q, best


def _static_tensions(model, q, p) -> np.ndarray:
    """(AE)_r strain of every element at the node positions q (N): the statics' tension law."""
    x = np.concatenate([q, np.zeros_like(q)])
    y = dict(zip(model.output_labels, np.array(model.outputs(x, np.zeros(model.top.size1_out(0)), p)).ravel()))
    strain = np.array([y[f"element_strain[{k}]"] for k in range(model.n_elements)])
    ae = np.concatenate([[p[model.layout.section_index(i, "cable.ae")]] * n for i, n in enumerate(model.segments)])
    return ae * strain


def _total_weight(model, p) -> float:
    return sum(abs(p[model.layout.section_index(i, "body.weight")])
               + abs(p[model.layout.section_index(i, "cable.weight_per_length")]) * p[model.layout.section_index(i, "cable.length")]
               for i in range(model.n_sections))


def segmented_steady(model, p, *, guess=None) -> SteadyState:
    """The steady state of a segmented model: its elastic catenary (waves off, top at rest).

    Parameters
    ----------
    model : SegmentedModel
    p : array
        Parameter vector (wave amplitudes and slack switches are ignored).
    guess : array, optional
        Starting node positions (m); default the stretched vertical cable.

    Returns
    -------
    SteadyState
        Node positions ``q`` (m), labelled outputs and the scaled residual (forces over the total weight).

    Raises
    ------
    SolverError
        As :func:`segmented_equilibrium`.
    """
    p = static_parameters(model, p)
    q, r = segmented_equilibrium(model, p, guess=guess)
    return at_rest(model, q, p, r)


def segmented_initial_state(scene, model, p, t0: float = 0.0, q=None) -> np.ndarray:
    """x0 = (node positions, node velocities) of a segmented model at time ``t0``.

    As for the 2-DOF model (whose coordinates are relative to the top): ``scene.initial.phi`` and
    ``u`` unset give the equilibrium shape; set, every section is straight at angle phi with
    stretch u (Wang 1971 eq. 10), its elements equally long. The shape moves with the top: it is
    translated by the top position at t0 and every node starts with the top's velocity plus
    the rates ``phi_rate``/``u_rate`` (the analogue of phi' = u' = 0 relative to the top). A rigid body's
    orientation starts at rest, at its static attitude (``phi``, ``u`` unset) or level (theta_b = 0), turned about
    its attachment point to the ``body.initial_roll_deg``/``pitch``/``yaw`` it sets (a release from that attitude:
    the nodes keep their places).

    Parameters
    ----------
    scene : Scene
    model : SegmentedModel
    p : array
    t0 : float
        Start time (s).
    q : array, optional
        The shape (node positions relative to the top, then orientation coordinates) to start from instead of the
        equilibrium, with ``phi``, ``u`` unset (a tow's steady shape, :func:`.tow.straight_tow`).

    Returns
    -------
    numpy.ndarray
        The state vector (2 x number of free nodes positions, then velocities).
    """
    ini = scene.initial
    e = np.array(model.top(t0, p)).ravel()
    dim = _dim(model)                       # a 3-D scene starts from its equilibrium (initial.phi, u unset)
    z, zd = e[1:1 + dim], e[1 + dim:1 + 2 * dim]
    n_rot = _rotations(model)                # rigid bodies' angles: their static pitch, at rest
    rot = _level(model)
    if ini.phi is None and ini.u is None:
        q_all = segmented_steady(model, p).q if q is None else np.asarray(q, float)
        q, rot = q_all[:q_all.size - n_rot].reshape(-1, dim), q_all[q_all.size - n_rot:]
        v = np.zeros_like(q)
    else:
        if ini.phi is None or ini.u is None:
            y = segmented_steady(model, p).outputs
        pos, vel = [], []
        r0, v0 = np.zeros(2), np.zeros(2)
        for i, n_el in enumerate(model.segments):
            val = lambda name, i=i: p[model.layout.section_index(i, name)]
            l_0 = val("cable.length") * (1 - val("cable.tension_ref") / val("cable.ae"))
            phi = ini.phi if ini.phi is not None else y[model.label("phi", i)]
            u = ini.u if ini.u is not None else y[model.label("chord_stretch", i)]
            et, en = np.array([-np.sin(phi), np.cos(phi)]), np.array([-np.cos(phi), -np.sin(phi)])
            length = l_0 + u
            for k in range(1, n_el + 1):
                s = k / n_el
                pos.append(r0 + s * length * et)
                vel.append(v0 + s * (ini.u_rate * et + length * ini.phi_rate * en))
            r0, v0 = pos[-1], vel[-1]
        q, v = np.array(pos), np.array(vel)
    bodies = [s.body for s in scene.sections if s.body.is_rigid]
    return np.concatenate([(q + z).ravel(), released(bodies, rot), (v + zd).ravel(), np.zeros(n_rot)])


def released(bodies, rot) -> np.ndarray:
    """The rigid bodies' orientation coordinates ``rot`` with each body turned to its ``initial_*_deg`` attitude where
    set (:func:`cablesys.model.rigid_body.turned_orientation`, about its attachment point: the nodes keep their
    places); ``bodies`` (:class:`~cablesys.scene.body.Body`) in the order of their coordinates in q."""
    rot = np.array(rot, float)
    if not bodies:
        return rot
    n = rot.size // len(bodies)
    for k, body in enumerate(bodies):
        if any(a is not None for a in body.initial_attitude_deg):
            rot[k * n:(k + 1) * n] = turned_orientation(rot[k * n:(k + 1) * n], body.initial_attitude_deg)
    return rot


def anchored_line_forces(model, state: SteadyState, p) -> dict:
    """Fairlead and anchor forces of an anchored one-section line at rest, and its length on the bed (in the plane or
    in space, where H is the force's horizontal magnitude).

    The fairlead carries the top element's tension along its axis plus the half element lumped at
    the top; the anchor the bottom element's tension plus the half element lumped there
    (:mod:`cablesys.model.segmented`); when the line lies on the bed the anchor force is the line's
    tension at the anchor (the last element's less the friction of the half element lumped at the
    anchor). The length on the bed is the weight the seabed and the
    anchor carry vertically, (sum of the nodes' normal forces x cos(slope) + the anchor's downward
    load) / w: the supported length, what :func:`seabed_catenary` calls L_B (arc from the anchor).

    Parameters
    ----------
    model : SegmentedModel
        Anchored, one section.
    state : SteadyState
        Its static state.
    p : array
        Parameter vector.

    Returns
    -------
    dict
        ``H``, ``V_F`` at the fairlead (N; V up), ``H_A``, ``V_A`` at the anchor (N; the upward pull)
        and ``L_B`` (m).
    """
    y, idx = state.outputs, model.layout.section_index
    n = model.n_elements
    w, l_r = p[idx(0, "cable.weight_per_length")], p[idx(0, "cable.length")]
    half = 0.5 * w * l_r / n
    axes = "xyz"[:_dim(model)]
    r = np.array([[y[f"node_{c}[{j}]"] for c in axes] for j in range(n + 1)])
    T = np.array([y[f"element_tension[{k}]"] for k in range(n)])
    et = lambda k: (r[k + 1] - r[k]) / np.linalg.norm(r[k + 1] - r[k])
    top, bottom = T[0] * et(0), T[-1] * et(n - 1)
    horizontal = lambda f: float(np.hypot(f[0], f[2] if len(f) == 3 else 0.0))     # in space the x-z plane's
    anchor_down = half - bottom[1]
    L_B = 0.0
    if "seabed.depth" in model.layout.labels:
        cos_a = np.cos(np.radians(p[model.layout.index("seabed.slope_deg")]))
        L_B = (cos_a * sum(y[f"seabed_normal[{j}]"] for j in range(n + 1)) + anchor_down) / w
    H_A = horizontal(bottom)
    if "seabed.depth" in model.layout.labels and y["seabed_normal[%d]" % (n - 1)] > 0:
        # the line's tension at the anchor: the last element's (at its mid-point) less the laid-down
        # friction of the half element between (T(0) = max(T(h/2) - mu w h/2, 0), seabed_catenary)
        H_A = max(H_A - p[model.layout.index("seabed.friction_axial")] * half, 0.0)
    return dict(H=horizontal(top), V_F=top[1] + half, H_A=H_A, V_A=-anchor_down, L_B=L_B)
