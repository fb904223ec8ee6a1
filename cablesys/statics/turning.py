"""The steady turn: the node model's shape that rotates rigidly with a tow point on a circle.

Towing in a circle (Wang 1971 p. 32; :class:`cablesys.scene.track.Track`) has a steady state in the
frame that turns with the tow point at the rate Omega about the upward vertical through the
circle's centre: every node keeps its place in that frame. In the earth frame (cablesys' x, y down,
z, origin at the circle's centre) node j then moves with

    v_j = Omega_up x r_j = Omega (-z_j, 0, x_j),     a_j = Omega_up x v_j = -Omega^2 (x_j, 0, z_j),

and the equations of motion of the node model, M(q) q'' = f(q, q', e, p), hold with these: the
inertia of the turn balances tension, weight and the drag of the still water on the turning cable
(the relative velocity is -v_j). The residual M a(q) - f(q, v(q), e, p) = 0, scaled by the total
weight as the statics' is (and held to the same tolerance), is solved by KINSOL in element angles
and lengths (then polished in node positions), by continuation in the turn rate from the hanging
cable (each solution the next guess), as the catenary's statics continue in the flow speed
(:mod:`.catenary`). A system of lines joined at points (:mod:`cablesys.model.system`) has no chain of element
angles: its continuation steps in node positions alone, from its statics with the prescribed point as the top. The tow point's position, velocity and acceleration e are those of the rigid
turn at the start time, equal to the track's own (checked).
"""

from __future__ import annotations

import warnings

import casadi as ca
import numpy as np

from ..errors import NumericalWarning, SolverError
from ..messages import casadi_warnings_captured, kinsol_flags
from ..model.system import SystemModel
from ..scene.labels import section_prefix
from .catenary import polar_map, to_polar
from .problem import residual_scales, static_parameters
from .tow import hanging as hanging_shape
from .tow import tolerance



def _rigid(w, r):
    """(v, a) of points ``r`` (rows x, y, z; numbers or CasADi symbols) turning at ``w`` (rad/s) about the upward
    vertical (y is down): the module docstring's v_j and a_j."""
    x, z = r[:, 0], r[:, 2]
    cat = ca.horzcat if isinstance(r, (ca.SX, ca.MX)) else (lambda *cols: np.column_stack(cols))
    return cat(-w * z, 0 * x, w * x), cat(-w**2 * x, 0 * x, -w**2 * z)


def _rootfinder(model):
    """KINSOL on ``(q; [t0, r_top, w, p]) -> (M a - f) / W`` for the model's 3-D nodes (W: the total weight,
    :func:`.problem.residual_scales`), and on the same residual in element angles and lengths v (q = r_top +
    the statics' polar map, :func:`.catenary.polar_map`), in which swinging the cable out is linear: node-coordinate
    Newton sees a swing of a stiff line as a stretch and stalls (as in the statics)."""
    def build():
        nq, n_p = model.nq, len(model.layout)
        q, t0, rt, w = ca.SX.sym("q", nq), ca.SX.sym("t0"), ca.SX.sym("r_top", 3), ca.SX.sym("w")
        p = ca.SX.sym("p", n_p)
        r = ca.reshape(q, 3, nq // 3).T
        v, a = _rigid(w, r)
        vt, at = _rigid(w, rt.T)
        e = ca.vertcat(t0, rt, vt.T, at.T)
        M, f = model.dynamics(q, ca.vec(v.T), e, p)
        res = (ca.mtimes(M, ca.vec(a.T)) - f) / residual_scales(model, p)
        F = ca.Function("turning_residual", [q, ca.vertcat(t0, rt, w, p)], [res])
        opts = {"strategy": "linesearch", "abstol": 1e-13, "error_on_fail": False, "print_level": 0,
                "disable_internal_warnings": True, "max_iter": 200}
        nodes = ca.rootfinder("turning", "kinsol", F, dict(opts, linear_solver_type="user_defined",
                                                            linear_solver="csparse"))
        if isinstance(model, SystemModel):    # a graph of lines has no chain of element angles: node coordinates
            return F, None, nodes
        v = ca.SX.sym("v", nq)
        P = ca.SX.sym("P", 5 + n_p)
        G = ca.Function("turning_polar_residual", [v, P], [F(ca.repmat(P[1:4], nq // 3, 1) + polar_map(model)(v), P)])
        return F, ca.rootfinder("turning_polar", "kinsol", G, opts), nodes
    return model.derive("turning_rootfinder", build)


def _continued(solve, state, rate: float, first_step: float, what: str, start: str):
    """The steady state at ``rate`` by continuation in the turn rate from 0: ``solve(state, w)`` gives the steady state
    at the rate w from the last one (or None), the step doubled after a success and halved after a failure, down to
    1/4096 of the rate. Raises SolverError naming the rate reached (``what``: the turn's owner, ``start``: where the
    continuation started, for the message)."""
    lam, step = 0.0, first_step
    with casadi_warnings_captured() as kinsol:
        while lam < 1.0 and step > 1.0 / 4096:
            tried = solve(state, rate * min(1.0, lam + step))
            if tried is not None:
                state, lam, step = tried, min(1.0, lam + step), 2.0 * step
            else:
                step *= 0.5
    if lam < 1.0:
        flags = kinsol_flags(kinsol)
        raise SolverError(f"steady turn {what}{' ' if what else ''}not found: the continuation in the turn rate "
                          f"{start}stopped at {lam * rate:.4g} of {rate:.4g} rad/s"
                          + (f" (KINSOL: {', '.join(flags)})" if flags else "")
                          + "; a tight, fast turn may have no steady state with the lines taut")
    return state


def heading_dependent_bodies(scene) -> list:
    """The fields of the point bodies of ``scene`` that a turn's heading changes: virtual masses unequal in x and z, or
    a drag axis tilted off the vertical (not sphere drag). A point body's virtual masses and drag axis are fixed in
    the scene's axes (Wang 1971 eq. 16, 32-35), so such a body meets the water differently as the tow turns and no
    turn is steady; a rigid body's are its own axes'."""
    if scene.system is not None:
        bodies = [(f"point[{i}].", pt.body) for i, pt in enumerate(scene.system.point) if pt.free]
    else:
        bodies = [(section_prefix(scene, i), s.body) for i, s in enumerate(scene.sections)]
    out = []
    for prefix, b in bodies:
        if b.is_rigid:
            continue
        if b.virtual_mass_z != b.mass_x:
            out.append(f"{prefix}body.mass_z = {b.virtual_mass_z:g} kg (mass_x = {b.mass_x:g} kg)")
        if not b.is_sphere and b.axis_angle_deg % 180.0 != 0.0:
            out.append(f"{prefix}body.axis_angle_deg = {b.axis_angle_deg:g}")
    return out


def turning_initial_state(scene, model, p, t0: float = 0.0) -> np.ndarray:
    """x0 of a segmented model towed in a circle (``scene.top_motion.track``): the steady turn, continued from the
    scene's hanging equilibrium (:func:`.catenary.segmented_steady`); a system of lines joined at points from its
    steady straight tow (:func:`system_turning_state`). Warns (NumericalWarning) when a point body's fields change
    with the heading (:func:`heading_dependent_bodies`): the turn found is the equilibrium at t0's heading, and the run
    moves about it."""
    odd = heading_dependent_bodies(scene)
    if odd:
        warnings.warn("the steady turn is steady only at the start's heading: " + "; ".join(odd) + " are fixed in the "
                      "scene's axes (a point body, Wang 1971 eq. 16, 32-35), so the run moves about it as the tow "
                      "turns (equal mass_x and mass_z, a vertical drag axis or sphere drag keep it steady)",
                      NumericalWarning, stacklevel=2)
    if isinstance(model, SystemModel):
        return system_turning_state(scene, model, p, t0)
    return turning_state(model, p, scene.top_motion.track.turn_rate, hanging_shape(model, p), t0)


def system_turning_state(scene, model, p, t0: float = 0.0) -> np.ndarray:
    """x0 = (node positions, node velocities) of the steady turn of a system of lines joined at points.

    A graph of lines has no chain of element angles to continue in (:func:`turning_state`), and Newton in node
    positions from the hanging system must swing stiff lines far out (it stalls). The straight tow at the track's speed
    along the turn's heading at ``t0`` (:func:`.tow.straight_tow`, from the statics in streaming water) is the turn of
    zero rate; the turn rate is then continued from 0 to Omega with the tow point held where the track puts it at t0,
    moving at the same speed along the same heading, about a centre at the distance U / omega on its inner side (at
    Omega: the circle's centre, the origin). Each step solves the module docstring's residual in node positions from
    the last shape relative to the tow point. Raises SolverError when the continuation stalls."""
    from .tow import straight_tow
    track = scene.top_motion.track
    rate, speed = track.turn_rate, track.speed
    p = static_parameters(model, p)
    e = np.array(model.top(t0, p)).ravel()
    r_top, v_top = e[1:4], e[4:7]
    heading = float(np.arctan2(v_top[2], v_top[0]))
    rel = straight_tow(model, p, speed, heading, scene).reshape(-1, 3)     # relative to the tow point
    radial = r_top / np.linalg.norm(r_top)                                  # from the centre out to the tow point
    F, _, nodes = _rootfinder(model)
    tol = tolerance(model, p)

    def solve(rel, w):
        """The shape relative to the tow point at the turn rate w about the centre U / |w| inwards, or None."""
        r_w = radial * speed / abs(w)                                      # the tow point seen from that centre
        P = np.concatenate([[t0], r_w, [w], p])
        q = np.array(nodes((rel + r_w).ravel(), P)).ravel()
        ok = np.all(np.isfinite(q)) and float(np.max(np.abs(np.array(F(q, P))))) < tol
        return q.reshape(-1, 3) - r_w if ok else None

    q = _continued(solve, rel, rate, 0.125, "of the system", "from the straight tow ") + r_top
    v, _ = _rigid(rate, q)
    return np.concatenate([q.ravel(), v.ravel()])


def turning_state(model, p, turn_rate: float, hanging, t0: float = 0.0) -> np.ndarray:
    """x0 = (node positions, node velocities) of the steady turn at time ``t0``.

    Parameters
    ----------
    model : SegmentedModel
        In 3-D (``model.dim`` = 3), its top on the circle (``top_motion.track``).
    p : array
        Parameter vector (waves and the slack switches are ignored, as in the statics).
    turn_rate : float
        Omega (rad/s) about the upward vertical, + counter-clockwise seen from above.
    hanging : array
        The hanging cable's node positions relative to the top (the statics' solution at rest), the
        continuation's start.
    t0 : float
        Start time (s).

    Returns
    -------
    numpy.ndarray
        (q, v) with q in m from the circle's centre and v = Omega_up x q in m/s.

    Raises
    ------
    SolverError
        When the continuation in the turn rate does not reach ``turn_rate``.
    """
    if getattr(model, "dim", 2) != 3:
        raise SolverError("the steady turn needs the node model in 3-D (a track moves the tow point in x and z)")
    p = static_parameters(model, p)
    e = np.array(model.top(t0, p)).ravel()
    r_top = e[1:4]
    v_top, a_top = _rigid(turn_rate, r_top[None, :])
    if not (np.allclose(e[4:7], v_top.ravel(), atol=1e-9 * max(1.0, abs(turn_rate) * np.linalg.norm(r_top)))
            and np.allclose(e[7:10], a_top.ravel(), atol=1e-9 * max(1.0, turn_rate**2 * np.linalg.norm(r_top)))):
        raise SolverError(f"the top motion at t = {t0:g} s is not a rigid turn at {turn_rate:.6g} rad/s about the "
                          "origin: the steady turn needs the track alone")
    F, polar, nodes = _rootfinder(model)
    tol = tolerance(model, p)
    q = (np.asarray(hanging, float).reshape(-1, 3) + r_top).ravel()
    resid = lambda qq, w: float(np.max(np.abs(np.array(F(qq, np.concatenate([[t0], r_top, [w], p]))))))
    def solve(q, w):
        """The nodes at the turn rate w from ``q`` (element angles and lengths, polished in node positions), or None."""
        P = np.concatenate([[t0], r_top, [w], p])
        v = np.array(polar(to_polar(q - np.tile(r_top, q.size // 3), 3), P)).ravel()
        q_try = np.tile(r_top, q.size // 3) + np.array(polar_map(model)(v)).ravel() if np.all(np.isfinite(v)) else q
        if not resid(q_try, w) < tol:                      # polished in node coordinates (sparse)
            q_try = np.array(nodes(q_try, P)).ravel()
        return q_try if np.all(np.isfinite(q_try)) and resid(q_try, w) < tol else None

    q = _continued(solve, q, turn_rate, 0.25, "", "")
    v, _ = _rigid(turn_rate, q.reshape(-1, 3))
    return np.concatenate([q, v.ravel()])
