"""Equilibrium of a cable system: lines joined at points (the node model of a graph of lines, model/system.py).

The static residual is the model's own force vector with every rate zero (:func:`.problem.static_residual`; waves
off, forces over the total weight), the prescribed points held at a given translation (their mean positions, or
where the top motion puts them at the start of a run). KINSOL solves it in node coordinates with a sparse direct solver, as the
anchored line's statics do (:mod:`.catenary`): first with every element elastic both ways (tension floor -(AE)_r, so
that an element of the guess shorter than its zero-tension length keeps its stiffness), then with the lines' own
law. The first guess:

- every body's and junction's position: the user's (``x``, ``y``, ``z`` of the point), else the minimum of the
  potential energy of the coarse system, each line one straight, tension-only elastic bar of its zero-tension length
  l_0 = sum of its sections' (Wang 1971 eq. 1) and axial compliance sum l_r / (AE)_r, its weight in water lumped half
  at each end, the bodies' weights at their points (IPOPT; a few variables);
- every line's nodes between its end points: the inextensible catenary of its length in the vertical plane through
  its chord (:func:`.closed_forms.suspended_catenary`, Irvine 1981, *Cable Structures*, ch. 1), stretched until no
  element is slack, or straight where the line is shorter than its chord or hangs vertically.

When KINSOL does not converge from that guess, the model's potential energy (weights, elastic strain; Wang 1971
eq. 14-15) is minimized from it by IPOPT (the equilibrium without flow is its minimum) and KINSOL restarts there; a
current or tow speed it still cannot reach is approached by continuation in the flow speed, as for the chain
(:func:`.catenary.segmented_equilibrium`). With a seabed the statics' own laws hold (elements elastic both ways, the
laid-down line's friction: :mod:`cablesys.model.segmented_seabed`), the guess lays the nodes it puts under the bed on
it, and a state with a compressed element is refused. A run's start (:func:`system_initial_state`) that fails from
this guess solves the system at COARSE_SEGMENTS elements per section first and refines it (:func:`refine`).
Forces in N, lengths in m.
"""

from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np

from ..errors import SolverError
from ..messages import casadi_warnings_captured, kinsol_flags
from .catenary import NODE_KINSOL, TOLERANCE, _pins, _taut_span, flow_continuation, flow_indices, released
from .problem import SteadyState, at_rest, residual_scales, static_parameters, static_zeroed

__all__ = ["system_equilibrium", "system_guess", "system_initial_state", "system_rest", "system_steady"]


def _sections(model, p) -> list:
    """Per line, its sections' (l_r, l_0, (AE)_r, w, N) (m, m, N, N/m, elements) from ``p``."""
    lab = model.layout.labels
    out = []
    for k, segs in enumerate(model.line_segments):
        secs = []
        for s, n in enumerate(segs):
            v = lambda name: float(p[lab.index(f"system.line[{k}].section[{s}].{name}")])
            l_r, ae = v("length"), v("ae")
            secs.append((l_r, l_r - v("tension_ref") * l_r / ae, ae, v("weight_per_length"), n))
        out.append(secs)
    return out


def _n_top(model) -> int:
    """Entries of the top input z0 of the statics: the prescribed point's translation (dim) and a vessel's rotation
    moving further prescribed points (:meth:`cablesys.model.system.SystemModel.top_input`)."""
    return model.dim + len(model.vessel_inputs)


def _bodies(model, p) -> dict:
    """{point index: weight in water (N)} of the bodies and junctions."""
    lab = model.layout.labels
    return {i: float(p[lab.index(f"system.point[{i}].body.weight")]) for i, kind in enumerate(model.point_kinds)
            if kind in ("body", "junction")}


def _held(model, p, top) -> dict:
    """{node: (x, y, z)} of the held nodes: the prescribed points translated by ``top`` (default 0: at their mean
    positions, the first at the origin), the fixed points at their positions (m)."""
    lab = model.layout.labels
    shift = np.zeros(3) if top is None else np.r_[np.asarray(top, float)[:model.dim], np.zeros(3 - model.dim)]
    out = {}
    for i, kind in enumerate(model.point_kinds):
        j = model.point_nodes[i]
        at = np.array([float(p[lab.index(f"system.point[{i}].{c}")]) if f"system.point[{i}].{c}" in lab else 0.0
                       for c in "xyz"])
        if kind == "prescribed":
            out[j] = at + shift
        elif kind == "fixed":
            out[j] = at
    return out


def _coarse_points(model, p, held: dict, start: dict) -> dict:
    """{node: (x, y, z)} of every point at the minimum of the coarse system's potential energy (module docstring),
    IPOPT from ``start`` ({node: position} of the free points)."""
    dim = model.dim
    secs, bodies = _sections(model, p), _bodies(model, p)
    free = sorted(start)
    X = ca.SX.sym("X", dim * len(free))
    pos = {j: X[dim * m:dim * m + dim] for m, j in enumerate(free)}
    pos.update({j: ca.DM(r[:dim]) for j, r in held.items()})
    weight = {model.point_nodes[i]: w for i, w in bodies.items()}
    lengths = []
    E = 0.0
    for k, seq in enumerate(model.line_nodes):
        L0 = sum(s[1] for s in secs[k])
        k_bar = 1.0 / sum(s[0] / s[2] for s in secs[k])
        W = sum(s[0] * s[3] for s in secs[k])
        a, b = seq[0], seq[-1]
        weight[a] = weight.get(a, 0.0) + 0.5 * W
        weight[b] = weight.get(b, 0.0) + 0.5 * W
        d = pos[b] - pos[a]
        ell = ca.sqrt(ca.sumsqr(d) + (1e-6 * L0) ** 2)
        E += 0.5 * k_bar * ca.fmax(ell - L0, 0.0) ** 2
        lengths.append(L0)
    E -= sum(w * pos[j][1] for j, w in weight.items() if j in start)     # Wang 1971 eq. 15, y down
    scale = max(sum(abs(w) for w in weight.values()), 1e-300) * max(np.mean(lengths), 1e-300)
    solver = ca.nlpsol("system_coarse", "ipopt", {"x": X, "f": E / scale},
                       {"print_time": False, "ipopt": {"print_level": 0, "sb": "yes", "max_iter": 3000, "tol": 1e-12}})
    x0 = np.concatenate([np.asarray(start[j][:dim], float) for j in free])
    with casadi_warnings_captured():
        sol = solver(x0=x0)
    x = np.array(sol["x"]).ravel()
    return {j: np.r_[x[dim * m:dim * m + dim], np.zeros(3 - dim)] for m, j in enumerate(free)}


def _first_positions(model, p, held: dict) -> dict:
    """A start for the coarse problem: every free point below (above, when the line or the point is buoyant) the
    point it is first reached from, walking the graph from the held points, by 0.7 of the joining line's length."""
    secs, bodies = _sections(model, p), _bodies(model, p)
    adj = {}
    for k, seq in enumerate(model.line_nodes):
        L0 = sum(s[1] for s in secs[k])
        W = sum(s[0] * s[3] for s in secs[k])
        adj.setdefault(seq[0], []).append((seq[-1], L0, W))
        adj.setdefault(seq[-1], []).append((seq[0], L0, W))
    weight = {model.point_nodes[i]: w for i, w in bodies.items()}
    pos, queue = dict(held), list(held)
    while queue:
        a = queue.pop(0)
        for b, L0, W in adj.get(a, []):
            if b in pos:
                continue
            sign = 1.0 if weight.get(b, 0.0) + 0.5 * W >= 0.0 else -1.0
            side = 0.05 * L0 * (1 + len(pos) % 3)          # a small sideways offset: no two points coincide
            pos[b] = pos[a] + np.array([side, sign * 0.7 * L0, 0.0])
            queue.append(b)
    return {j: r for j, r in pos.items() if j not in held}


def _line_nodes(model, p, k: int, ra, rb) -> np.ndarray:
    """The interior nodes of line k between its end positions ra, rb (rows (x, y, z), m): the catenary of its
    zero-tension length in the vertical plane through the chord, stretched until no element is slack (sagging up for
    a buoyant line), or straight (module docstring)."""
    secs = _sections(model, p)[k]
    h0 = np.concatenate([[l0 / n] * n for _, l0, _, _, n in secs])
    arcs = np.cumsum(h0)
    L0 = arcs[-1]
    d = rb - ra
    horiz = np.array([d[0], 0.0, d[2]])
    span = float(np.linalg.norm(horiz))
    chord = float(np.linalg.norm(d))
    W = sum(l_r * w for l_r, _, _, w, _ in secs)
    if L0 > chord * (1 + 1e-9) and span > 1e-6 * L0 and W != 0.0:
        ea = min(s[2] for s in secs)
        flip = 1.0 if W > 0 else -1.0                 # a buoyant line sags upwards
        pts = _taut_span(L0, np.array([span, flip * d[1]]), arcs, min_strain=0.5 * abs(W) / ea)
        u = horiz / span
        return np.array([ra + X * u + np.array([0.0, flip * Y, 0.0]) for X, Y in pts])
    return np.array([ra + d * s / L0 for s in arcs[:-1]])


def system_guess(model, p, *, points: dict | None = None, top=None) -> np.ndarray:
    """The statics' first guess q (module docstring). ``points``: {point name: (x, y, z)} starting positions of
    bodies and junctions (the scene's guesses); ``top``: the prescribed point's position (default the origin)."""
    p = np.asarray(p, float)
    held = _held(model, p, top)
    given = {}
    for name, r in (points or {}).items():
        j = model.point_nodes[model.point_names.index(name)]
        given[j] = np.r_[np.asarray(r, float), np.zeros(3 - len(r))]
    start = {**_first_positions(model, p, held), **given}
    pos = {**held, **(start if len(given) == len(start) else {**_coarse_points(model, p, held, start), **given})}
    q = np.zeros(model.nq)
    dim = model.dim
    for k, seq in enumerate(model.line_nodes):
        inner = _line_nodes(model, p, k, pos[seq[0]], pos[seq[-1]])
        for j, r in zip(seq[1:-1], inner):
            pos[j] = r
    lab = model.layout.labels
    if "seabed.depth" in lab:        # nodes the catenaries put under the bed lie on it (in space: its heading)
        v = lambda name: float(p[lab.index(f"seabed.{name}")])
        y0 = v("depth") - float(p[lab.index("environment.top_depth")])
        beta = np.radians(v("heading_deg")) if "seabed.heading_deg" in lab else 0.0
        for j, r in pos.items():
            r[1] = min(r[1], y0 + (r[0] * np.cos(beta) + r[2] * np.sin(beta)) * np.tan(np.radians(v("slope_deg"))))
    for j, r in pos.items():
        if model.node_q[j] >= 0:
            q[model.node_q[j]:model.node_q[j] + dim] = r[:dim]
    return _level(model, q)


def _level(model, q) -> np.ndarray:
    """``q`` with the rigid bodies' orientation coordinates (after the nodes) at the level attitude (theta_b = 0, the
    unit quaternion: :data:`cablesys.model.rigid_body.ORIENTATION_REST`)."""
    n_rot = model.n_rotations
    if n_rot:
        q[model.nq - n_rot:] = model.rotation_rest
    return q


def _residual(model) -> ca.Function:
    """``(q, (p, z0, a_ref, U)) -> r``: the static residual (:func:`.problem.static_residual`) with the top input at
    z0 (the prescribed point's translation, dim entries, and a vessel's rotation moving further prescribed points,
    :meth:`cablesys.model.system.SystemModel.top_input`; e = (0, z0, 0, 0)) and the rigid bodies' neutral rotations
    pinned as the
    chain's statics pin them (:func:`.catenary._pinned_residual`: U (a_ref - a) added to the orientation rows, U by
    columns, n_rot x n_rot; U = 0 where no rotation is neutral, e.g. the yaw of a body hanging still in space)."""
    def build():
        q = ca.SX.sym("q", model.nq)
        n_p, dim, n_rot = len(model.layout), _n_top(model), model.n_rotations
        pz = ca.SX.sym("pz", n_p + dim + n_rot + n_rot * n_rot)
        p = pz[:n_p]
        zeroed = set(static_zeroed(model))
        ps = ca.vertcat(*[0.0 if i in zeroed else p[i] for i in range(n_p)])
        e = model.at_rest(pz[n_p:n_p + dim])
        forces = getattr(model, "static_force", None)   # a seabed's statics have their own laws (segmented_seabed.py)
        if forces is not None:
            f = forces(q, ca.SX.zeros(model.nq), e, ps)
        else:
            _, f = model.dynamics(q, ca.SX.zeros(model.nq), e, ps)
        r = f / residual_scales(model, p)
        if n_rot:
            ref, U = pz[n_p + dim:n_p + dim + n_rot], ca.reshape(pz[n_p + dim + n_rot:], n_rot, n_rot)
            r = ca.vertcat(r[:model.nq - n_rot], r[model.nq - n_rot:] + ca.mtimes(U, ref - q[model.nq - n_rot:]))
        return ca.Function("system_residual", [q, pz], [r], ["q", "p"], ["r"])
    return model.derive("system_static_residual", build)


def _rootfinder(model):
    return model.derive("system_rootfinder", lambda: ca.rootfinder("system_statics", "kinsol", _residual(model),
                                                                   NODE_KINSOL))


def _energy_minimum(model, p, q0, z0) -> np.ndarray:
    """q at the minimum of the model's potential energy V(q) (weights and strain, Wang 1971 eq. 14-15; no flow) by
    IPOPT from q0, the prescribed point at z0; V is divided by the total weight x the longest line (J)."""
    def build():
        q = ca.SX.sym("q", model.nq)
        n_p, dim = len(model.layout), _n_top(model)
        pz = ca.SX.sym("pz", n_p + dim + 1)
        e = model.at_rest(pz[n_p:n_p + dim])
        _, V = model.energy(ca.vertcat(q, ca.SX.zeros(model.nq)), e, pz[:n_p])
        return ca.nlpsol("system_energy", "ipopt", {"x": q, "p": pz, "f": V / pz[-1]},
                         {"print_time": False, "ipopt": {"print_level": 0, "sb": "yes", "max_iter": 3000,
                                                          "tol": 1e-12}})
    secs, bodies = _sections(model, p), _bodies(model, p)
    scale = (sum(abs(w) for w in bodies.values()) + sum(abs(w) * l_r for line in secs for l_r, _, _, w, _ in line)) * \
        max(sum(l_r for l_r, *_ in line) for line in secs)
    solver = model.derive("system_energy_minimum", build)
    with casadi_warnings_captured():
        sol = solver(x0=q0, p=np.concatenate([p, z0, [max(scale, 1e-300)]]))
    return np.array(sol["x"]).ravel()


def static_tolerance(model, p) -> float:
    """TOLERANCE, or the round-off floor of the scaled residual that stiff elements set: a node known to eps x the
    longest line gives an element force error k_e eps L (k_e = (AE)_r N / l_r)."""
    secs, bodies = _sections(model, p), _bodies(model, p)
    k_max = max(ae * n / l_r for line in secs for l_r, _, ae, _, n in line)
    total_l = max(sum(l_r for l_r, *_ in line) for line in secs)
    weight = sum(abs(w) for w in bodies.values()) + sum(abs(w) * l_r for line in secs for l_r, _, _, w, _ in line)
    return max(TOLERANCE, 1e3 * np.finfo(float).eps * k_max * total_l / weight)


def system_equilibrium(model, p, *, guess=None, points: dict | None = None, top=None) -> tuple:
    """Node positions q (m) of the system at rest (waves off, the prescribed point held at ``top``, default its mean
    position) and the largest scaled residual reached.

    Parameters
    ----------
    model : SystemModel
    p : array
        Parameter vector.
    guess : array, optional
        Starting q; default :func:`system_guess`.
    points : dict, optional
        {point name: (x, y, z)} starting positions of bodies and junctions.
    top : array, optional
        Position of the prescribed point (m, dim entries).

    Raises
    ------
    SolverError
        When KINSOL does not converge from the guess, from the energy minimum, or along the flow continuation.
    """
    p = static_parameters(model, p)
    z0 = np.zeros(_n_top(model))        # the top input: its translation, a vessel's rotation (unset: 0)
    if top is not None:
        given = np.asarray(top, float)[:z0.size]
        z0[:given.size] = given
    resid, nodes = _residual(model), _rootfinder(model)
    tol = static_tolerance(model, p)
    both = p.copy()
    for k, segs in enumerate(model.line_segments):
        for s in range(len(segs)):
            lb = f"system.line[{k}].section[{s}]."
            both[model.layout.index(lb + "tension_floor")] = -p[model.layout.index(lb + "ae")]

    q0 = system_guess(model, p, points=points, top=z0) if guess is None else np.asarray(guess, float)
    n_rot = model.n_rotations
    unpinned = np.zeros(n_rot + n_rot * n_rot)

    def residual(q, pp):
        return (float(np.max(np.abs(np.array(resid(q, np.concatenate([pp, z0, unpinned]))))))
                if np.all(np.isfinite(q)) else np.inf)

    def solve(q, pp):
        """KINSOL with the elements elastic both ways, then with the line's own law (restarted from its iterate), a
        neutral rotation pinned where it is (:func:`_residual`)."""
        for law in (_both_ways(model, pp, both, p), pp):
            for _ in range(2):
                q_new = np.array(nodes(q, np.concatenate([law, z0, _pins(model, q, law)]))).ravel()
                if np.all(np.isfinite(q_new)):
                    q = q_new
        return q, residual(q, pp)

    with casadi_warnings_captured() as kinsol:
        q, r = solve(q0, p)
        if not r < tol:                    # from the energy minimum (no flow), then along the flow speed
            flow = flow_indices(model)
            still = p.copy()
            still[flow] = 0.0
            q_c, r_c = solve(_energy_minimum(model, still, q0, z0), still)
            if r_c < tol:
                q_c, lam = flow_continuation(solve, q_c, p, flow, tol, 0.0 if np.any(p[flow]) else 1.0)
                if lam >= 1.0:
                    q, r = q_c, residual(q_c, p)
    if r < tol and "seabed.depth" in model.layout.labels:
        _no_compression(model, q, p, z0, tol)
    if not r < tol:
        flags = kinsol_flags(kinsol)
        raise SolverError(f"cable system equilibrium not found (best scaled residual {r:.3g} > {tol:.3g}): KINSOL "
                          "failed from the lines' catenaries, from the potential energy's minimum and along the flow "
                          "speed" + (f" (KINSOL: {', '.join(flags)})" if flags else "") + "; give the bodies' and "
                          "junctions' positions (x, y, z of their [[point]] tables) as a guess")
    return q, r


def _no_compression(model, q, p, z0, tol) -> None:
    """A seabed's statics hold for lines in tension or lying unstretched on the bed (the elements elastic both ways,
    :mod:`cablesys.model.segmented_seabed`): a static state with a compressed element is refused (SolverError)."""
    e = model.at_rest(z0)
    y = dict(zip(model.output_labels, np.array(model.outputs(np.concatenate([q, np.zeros_like(q)]), e, p)).ravel()))
    secs = _sections(model, p)
    ae = np.concatenate([[s_[2]] * s_[4] for line in secs for s_ in line])
    T = ae * np.array([y[f"element_strain[{k}]"] for k in range(ae.size)])
    weight = sum(abs(w) for w in _bodies(model, p).values()) + sum(abs(w) * l_r for line in secs
                                                                   for l_r, _, _, w, _ in line)
    if T.min() < -1e3 * np.finfo(float).eps * max(1.0, float(np.max(np.abs(T)))) - tol * weight:
        raise SolverError(f"the system's static state has a compressed element (tension {T.min():.6g} N at element "
                          f"{int(T.argmin())}): the seabed statics hold only for lines in tension or lying unstretched "
                          "on the bed")


def _both_ways(model, pp, both, p):
    """``pp`` with every line section's tension floor -(AE)_r (elastic both ways), its other entries kept."""
    out = pp.copy()
    for k, segs in enumerate(model.line_segments):
        for s in range(len(segs)):
            i = model.layout.index(f"system.line[{k}].section[{s}].tension_floor")
            out[i] = both[i]
    return out


def system_steady(model, p, *, guess=None, points: dict | None = None) -> SteadyState:
    """The system's static state (:func:`system_equilibrium`) with its outputs: a :class:`.problem.SteadyState`."""
    p = static_parameters(model, p)
    q, r = system_equilibrium(model, p, guess=guess, points=points)
    return at_rest(model, q, p, r)


def _positions(model, p, q, top) -> dict:
    """{node: (x, y, z)} of every node of ``model`` at q (the held ones from ``p`` and the prescribed point at top)."""
    pos = _held(model, p, top)
    for j, k in enumerate(model.node_q):
        if k >= 0:
            pos[j] = np.r_[q[k:k + model.dim], np.zeros(3 - model.dim)]
    return pos


def refine(coarse, p_coarse, q_coarse, fine, p_fine, top=None) -> np.ndarray:
    """A guess for the ``fine`` model (more elements per section) from the static state ``q_coarse`` of the ``coarse``
    model of the same system: every line's nodes interpolated linearly in unstretched arc length between the coarse
    line's nodes, the points where they are."""
    pos_c = _positions(coarse, p_coarse, q_coarse, top)
    q = np.zeros(fine.nq)
    for k, seq in enumerate(fine.line_nodes):
        arcs = lambda model, pp: np.concatenate([[0.0], np.cumsum(np.concatenate(
            [[l0 / n] * n for _, l0, _, _, n in _sections(model, pp)[k]]))])
        s_c, s_f = arcs(coarse, p_coarse), arcs(fine, p_fine)
        s_f = s_f * s_c[-1] / s_f[-1]
        pts = np.array([pos_c[j] for j in coarse.line_nodes[k]])
        for j, s_ in zip(seq, s_f):
            if fine.node_q[j] >= 0:
                q[fine.node_q[j]:fine.node_q[j] + fine.dim] = [np.interp(s_, s_c, pts[:, c]) for c in range(fine.dim)]
    if fine.n_rotations:                     # the rigid bodies' orientations as the coarse model found them
        q[fine.nq - fine.n_rotations:] = q_coarse[coarse.nq - coarse.n_rotations:]
    return q


#: The elements per line section of the first model of :func:`system_initial_state`'s coarse-to-fine statics.
COARSE_SEGMENTS = 4


def system_rest(scene, model, p, *, top=None, flow=None) -> np.ndarray:
    """q (m) of the system at rest in its static state (:func:`system_equilibrium`) with the prescribed point at ``top``
    (default its mean position, the origin), the bodies' and junctions' positions given in the scene as the statics'
    guess. When the statics do not converge from the first guess, they are solved for the same system with
    COARSE_SEGMENTS elements per line section, then twice as many, ..., each state interpolated along the lines into the
    next one's guess (:func:`refine`): a mooring line lying on the seabed, whose touchdown the coarse guess misplaces by
    tens of metres, is found so. ``flow(model, p)``, when given, gives the parameters each model is solved at (the
    water streaming past a towed system, :mod:`.tow`)."""
    at = flow or (lambda m, pp: pp)
    points = {pt.name: tuple(v for v in (pt.x, pt.y, pt.z or 0.0)) for pt in scene.system.point
              if pt.free and pt.x is not None and pt.y is not None}
    try:
        return system_equilibrium(model, at(model, p), points=points, top=top)[0]
    except SolverError:
        from ..model import build_model
        n_fine, n = max(model.segments), COARSE_SEGMENTS
        if n_fine <= n:
            raise
        prev = None
        while n < n_fine:
            sc = dataclasses.replace(scene, system=scene.system.with_segments(n))
            m = build_model(sc)
            p_c = at(m, m.parameters(sc))
            guess = None if prev is None else refine(*prev, m, p_c, top)
            prev = (m, p_c, system_equilibrium(m, p_c, guess=guess, points=points, top=top)[0])
            n *= 2
        return system_equilibrium(model, at(model, p), guess=refine(*prev, model, at(model, p), top), top=top)[0]


def system_initial_state(scene, model, p, t0: float = 0.0) -> np.ndarray:
    """x0 = (q, q') of a run: the system at rest in its static state (:func:`system_rest`) with the prescribed point
    where the top motion puts it at t0 (the origin after a smooth start), a rigid body turned to its
    ``initial_*_deg`` attitude where set, about its attachment point."""
    e = np.array(model.top(t0, p)).ravel()
    q = system_rest(scene, model, p, top=model.top_input(e))
    n_rot = model.n_rotations
    if n_rot:
        q[model.nq - n_rot:] = released([pt.body for pt in scene.system.point if pt.free and pt.body.is_rigid],
                                        q[model.nq - n_rot:])
    return np.concatenate([q, np.zeros_like(q)])
