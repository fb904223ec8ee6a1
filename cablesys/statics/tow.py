"""The steady straight tow: the node model's equilibrium in the frame moving with a tow point on a straight course.

A tow point moving at the constant velocity V = U e_psi (e_psi = (cos psi, 0, sin psi), psi the heading from +x
towards +z; (U, 0) in the plane) through still water carries the cable along unchanged in shape: every node moves
with V, none accelerates. The node model's equations of motion M(q) q'' = f(q, q', e, p) then read

    f(q, V, e_V, p) = 0,      e_V = (t_0, r_top, V, 0)     (no node accelerates),

the frame moving with the tow point being Galilean (Goldstein, Classical Mechanics, 3rd ed., sec. 1.1). Its force
terms are those of the statics in water streaming past at -V (Wang 1971 eq. 27's current minus the system speed),
drag, tension and weight, plus the inertial forces of the cable's added mass, which the node model writes in the
nodes' velocities over the ground (Wang 1971 eq. 23-24: K = 1/2 a |v_n|^2 per element, a = gamma rho pi d^2 / 4 l
proportional to the element's length l): at steady translation d/dt dK/dq' = 0 but dK/dr does not vanish, and
each element feels

    +- (1/2 (a / l) |V_n|^2 e_t - (a / l) (V . e_t) V_n)     on its lower (+) and upper (-) node,

the Munk couple of a slender body moving obliquely through still water, (m_n - m_t) V_t V_n with m_t = 0 (Newman,
Marine Hydrodynamics, 1977, sec. 4.13), and an axial pair from a's growth with l. A tow in the ship's frame
(``environment.system_speed``: the nodes still, the water moving) has no such term, so the two frames differ by it
(tests/test_tracks.py measures it); a point body's virtual masses are fixed in the scene's axes and feel none.

The steady tow is found from the statics in that streaming water (:func:`.catenary.segmented_steady`, a system of
lines joined at points :func:`.system.system_steady`, with its continuation in the flow speed and the pins of a rigid body's neutral rotations): in the plane the system speed
U cos psi (psi = 0 or pi), in space a current of speed U at every depth heading psi + pi; then KINSOL polishes it
on the residual above (scaled by the total weight, as the statics', with the statics' pins), from which it is
small. On the ground every node keeps its place relative to the tow point and moves with V, a rigid body at rest
(:func:`.catenary.segmented_initial_state`). This is the initial state of a run on a track that is not a circle
(:class:`cablesys.scene.track.Track`: the ship towed straight up to t = 0); the circle's is the steady turn
(:mod:`.turning`).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ..errors import SolverError
from ..messages import casadi_warnings_captured, kinsol_flags
from ..model.system import SystemModel
from .catenary import _pins, _rotations, segmented_initial_state, segmented_steady, static_tolerance
from .problem import residual_scales, static_parameters
from .system import static_tolerance as system_tolerance
from .system import system_rest, system_steady


def tow_parameters(model, p, speed: float, heading: float) -> np.ndarray:
    """A copy of ``p`` whose flow is still water seen from a tow point moving at ``speed`` (m/s) on ``heading`` (rad):
    the system speed U cos(heading) in the plane (the x axis), in space a current of speed U heading heading + pi at
    every current depth (the scene's own flow must be still water: :meth:`cablesys.scene.Scene._check_track`)."""
    p = np.array(p, dtype=float)
    lab = model.layout.labels
    if getattr(model, "dim", 2) == 3:
        for k, lb in enumerate(lab):
            if lb.startswith("environment.current_speeds["):
                p[k] = speed
            elif lb.startswith("environment.current_headings["):
                p[k] = heading + math.pi
    else:
        p[lab.index("environment.system_speed")] = speed * math.cos(heading)
    return p


def tow_velocity(model, speed: float, heading: float) -> np.ndarray:
    """V (m/s): (U cos psi, 0, U sin psi) in space, (U cos psi, 0) in the plane."""
    v = np.array([speed * math.cos(heading), 0.0, speed * math.sin(heading)])
    return v if getattr(model, "dim", 2) == 3 else v[:2]


def _tow_rootfinder(model):
    """``R(q; [p, V, pins]) = -f(q, q'_V, e_V, p) / W`` with the statics' pins on the rotation rows
    (:func:`.catenary._pinned_residual`), q relative to the tow point, and KINSOL on it (sparse, node coordinates)."""
    def build():
        nq, n_rot, dim, n_p = model.nq, _rotations(model), getattr(model, "dim", 2), len(model.layout)
        q, V = ca.SX.sym("q", nq), ca.SX.sym("V", dim)
        P = ca.SX.sym("P", n_p + dim + n_rot + n_rot * n_rot)
        p, V = P[:n_p], P[n_p:n_p + dim]
        qd = ca.vertcat(ca.repmat(V, (nq - n_rot) // dim, 1), ca.SX.zeros(n_rot))
        e = ca.vertcat(0.0, ca.SX.zeros(dim), V, ca.SX.zeros(dim))
        _, f = model.dynamics(q, qd, e, p)
        r = -f / residual_scales(model, p)
        if n_rot:
            ref = P[n_p + dim:n_p + dim + n_rot]
            U = ca.reshape(P[n_p + dim + n_rot:], n_rot, n_rot)
            r = ca.vertcat(r[:nq - n_rot], r[nq - n_rot:] + ca.mtimes(U, ref - q[nq - n_rot:]))
        F = ca.Function("tow_residual", [q, P], [r])
        opts = {"strategy": "linesearch", "abstol": 1e-13, "error_on_fail": False, "print_level": 0,
                "disable_internal_warnings": True, "max_iter": 100, "linear_solver_type": "user_defined",
                "linear_solver": "csparse"}
        return F, ca.rootfinder("straight_tow", "kinsol", F, opts)
    return model.derive("straight_tow_rootfinder", build)


def straight_tow(model, p, speed: float, heading: float, scene=None) -> np.ndarray:
    """q of the steady straight tow relative to the tow point (m; a rigid body's orientation coordinates after the
    nodes): the module docstring's residual, from the statics in the streaming water (a system of lines: of ``scene``,
    coarse to fine where its first guess fails, :func:`.system.system_rest`).

    Raises
    ------
    SolverError
        When KINSOL does not bring the residual below the statics' tolerance.
    """
    def flow(m, pp):             # still water streaming past the tow point, on every model the statics solve
        return static_parameters(m, tow_parameters(m, pp, speed, heading))
    p_flow = flow(model, p)
    q0 = hanging(model, p, scene, flow)
    p = static_parameters(model, p)
    P = np.concatenate([p, tow_velocity(model, speed, heading), _pins(model, q0, p_flow)])
    F, solve = _tow_rootfinder(model)
    tol = tolerance(model, p)
    resid = lambda q: float(np.max(np.abs(np.array(F(q, P))))) if np.all(np.isfinite(q)) else np.inf
    if resid(q0) < tol:
        return q0
    with casadi_warnings_captured() as kinsol:
        q = np.array(solve(q0, P)).ravel()
    if not resid(q) < tol:
        flags = kinsol_flags(kinsol)
        raise SolverError(f"steady straight tow at {speed:.4g} m/s not found: the residual stayed at "
                          f"{min(resid(q), resid(q0)):.3g} of the total weight (tolerance {tol:.3g})"
                          + (f" (KINSOL: {', '.join(flags)})" if flags else ""))
    return q


def hanging(model, p, scene=None, flow=None) -> np.ndarray:
    """q of the node model at rest (m, relative to the top at its mean position) at the parameters ``flow(model, p)``
    (default ``p``): the chain's statics (:func:`.catenary.segmented_steady`) or a system's of lines joined at points,
    its prescribed point the top (:func:`.system.system_rest` on ``scene``, coarse to fine where the first guess
    fails, or :func:`.system.system_steady` without one)."""
    at = flow or (lambda m, pp: pp)
    if not isinstance(model, SystemModel):
        return segmented_steady(model, at(model, p)).q
    return system_rest(scene, model, p, flow=flow) if scene is not None else system_steady(model, at(model, p)).q


def tolerance(model, p) -> float:
    """The statics' tolerance on the scaled residual: the chain's (:func:`.catenary.static_tolerance`) or a system's
    (:func:`.system.static_tolerance`)."""
    return (system_tolerance if isinstance(model, SystemModel) else static_tolerance)(model, p)


def moved_with_top(model, p, q, t0: float) -> np.ndarray:
    """x0 = (q, q') of a system of lines (:class:`~cablesys.model.system.SystemModel`) whose shape ``q`` (node
    positions relative to the prescribed point, then the rigid bodies' orientation coordinates) moves with the top:
    translated to the top's position at ``t0``, every free node with the top's velocity, the orientations at rest.
    (A system held by a fixed point cannot move with its top: a track refuses one, Scene._check_track.)"""
    e = np.array(model.top(t0, p)).ravel()
    dim, n_rot = model.dim, _rotations(model)
    q = np.asarray(q, float)
    nodes = q[:q.size - n_rot].reshape(-1, dim)
    return np.concatenate([(nodes + e[1:1 + dim]).ravel(), q[q.size - n_rot:],
                           np.tile(e[1 + dim:1 + 2 * dim], nodes.shape[0]), np.zeros(n_rot)])


def straight_tow_state(scene, model, p, t0: float = 0.0) -> np.ndarray:
    """x0 of a node model whose top follows ``scene.top_motion.track`` (not a circle): the steady straight tow at the
    track's speed along its initial heading (module docstring), at time ``t0`` (the track still straight there); a
    system of lines (``scene.system``) moved with its prescribed point as the chain with its top."""
    track = scene.top_motion.track
    q = straight_tow(model, p, track.speed, track.heading, scene)
    if isinstance(model, SystemModel):
        return moved_with_top(model, p, q, t0)
    return segmented_initial_state(scene, model, p, t0, q=q)
