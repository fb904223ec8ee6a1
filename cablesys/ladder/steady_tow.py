"""The steady tow and the steady turn answered as a run: the node model's steady state, carried with the tow point to
the output times, and its stability.

A towing ship on a straight course, or on a circle (:class:`cablesys.scene.track.Track`; Wang 1971 p. 32, "towing in
a circle"), with nothing else moving the tow point or the water, starts every run on its steady state
(:func:`cablesys.time_domain.initial.initial_state`: :func:`cablesys.statics.tow.straight_tow_state`,
:func:`cablesys.statics.turning.turning_initial_state`, a system of lines' :func:`~cablesys.statics.turning.
system_turning_state`). The node model's ODE x' = f(x, t) (x = (q, q'), q the node positions over the ground, each
a d-vector, d = 2 in the plane, 3 in space) is then solved for all time by that state moved with the tow:

- straight tow at the velocity V: x(t) = y + c(t), c(t) = (V t on every node position, 0 on every velocity). The
  flow is still water (no current, waves or system speed: :meth:`cablesys.scene.Scene._check_track`) and the
  bed-free model is invariant under a horizontal translation, with the top moved as r_top(t) = r_top(0) + V t:
  f(y + c(t), t) = f(y, 0); so x' = y' + c' gives y' = f(y, 0) - (V, 0), whose equilibrium is the steady tow
  (:mod:`cablesys.statics.tow`: every node moving with V, none accelerating);
- steady turn at the rate Omega about the upward vertical through the circle's centre (the origin, y down):
  x(t) = R(t) y(t), R(t) = blockdiag(Q(Omega t), ...) acting alike on every 3-vector of the state (each node's
  position and velocity), Q(theta) the rotation by theta about the upward vertical,
  Q(theta) (x, y, z) = (x cos theta - z sin theta, y, x sin theta + z cos theta). The still water, the vertical
  gravity and the point bodies whose virtual masses and drag do not depend on the heading
  (:func:`cablesys.statics.turning.heading_dependent_bodies`) make f equivariant, f(R(t) y, t) = R(t) f(y, 0),
  with the top on the circle r_top(t) = Q(Omega t) r_top(0). Then x' = R' y + R y' = R f(y, 0) gives
  y' = f(y, 0) - R^T R' y = f(y, 0) - Omega_hat y, where R^T R' = Omega_hat = blockdiag(S, ..., S) with
  S w = omega x w, omega = Omega (0, -1, 0) (up is -y):

      S = [[0, 0, -Omega], [0, 0, 0], [Omega, 0, 0]],     S (x, y, z) = Omega (-z, 0, x)

  (the statics' v_j = Omega_up x r_j, :mod:`cablesys.statics.turning`). Its equilibrium y* (f(y*, 0) = Omega_hat y*)
  is the steady turn, a relative equilibrium of the model.

Stability: perturbed, y = y* + d, d' = A d with, linearizing y' = f(y, 0) - Omega_hat y,

      A = J(y*, 0) - Omega_hat     (turn),       A = J(y*, 0)     (straight tow: c(t) shifts no velocity),

J = df/dx the Jacobian of the model's ODE (CasADi AD, :func:`cablesys.time_domain.failures.ode_jacobian`). In the
earth frame d_x(t) = R(t) exp(A t) d(0): over one revolution T = 2 pi / |Omega| (R(T) = I) the periodic orbit's
monodromy matrix is exp(A T), its Floquet multipliers exp(lambda T) for the eigenvalues lambda of A (Hale,
*Ordinary Differential Equations*, 1969, ch. III.7; Marsden & Ratiu, *Introduction to Mechanics and Symmetry*, 2nd ed.
1999, sec. 4.4 on relative equilibria). The steady state is stable (asymptotically, in the model) when every eigenvalue
has Re lambda < 0; :func:`stability` asks Re lambda < -STABILITY_MARGIN x max |lambda|, a margin above the eigenvalue
solver's rounding, and reports the least-damped eigenvalue (its damping ratio -Re lambda / |lambda| and decay time
-1 / Re lambda). The top is prescribed, not a coordinate: the rotation or translation of the whole line is no symmetry
of the driven system and gives no zero eigenvalue.

Every output (tensions, body coordinates, profiles, the top's position) is the model's own output function on the
states x(t_k) at the output times (:func:`cablesys.time_domain.sampled.sampled_record`), so the run carries the
labels, statistics and result protocol of a time-domain run of the node model; nothing is stepped, and the states
hold the statics' tolerance on the scaled residual (:func:`cablesys.statics.tow.tolerance`) in place of an
integration error.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ..scene import Scene
from ..statics.tow import tolerance as statics_tolerance
from ..statics.turning import heading_dependent_bodies

STABILITY_MARGIN = 1e-8
"""Least decay rate a stable steady state's eigenvalues must show, relative to the largest |lambda| (the axial
modes'): LAPACK's eigenvalues carry an error of about eps ||A|| times their condition number, and ||A|| is about
max |lambda|^2 here (the node stiffness over the node mass), so 1e-8 max |lambda| stays above that rounding for
max |lambda| up to ~1e4 1/s and condition numbers up to ~1e4 while it is far below any physical damping (the
lightest, the axial modes of a wire damped by its tangential drag alone: ~2e-6 of |lambda|, tests/test_ladder_steady.py)."""


def steady_kind(scene: Scene) -> str:
    """"turn" for a towing ship on a circle, "tow" on a straight course (``kind = "straight"``, or a path of straight
    legs alone: its heading never changes), else "" (no track, or one whose heading changes: a turn, a zig-zag, a
    path with arcs)."""
    track = getattr(scene.top_motion, "track", None)
    if track is None:
        return ""
    if track.is_circle:
        return "turn"
    return "tow" if track.keeps_heading else ""


def unsteady_reason(scene: Scene) -> str:
    """"" when a run of ``scene`` is its steady tow or steady turn for all time (given the start on it, which every
    track scene has), else why not, a sentence; the caller has checked the rung's other limits (a massless cable, a
    system, a winch, a rigid body, a seabed)."""
    top, env = scene.top_motion, scene.environment
    track = getattr(top, "track", None)
    if track is None:
        return ("no towing ship's track (top_motion.track): the steady rung answers a steady straight tow or a steady "
                "turn only")
    kind = steady_kind(scene)
    if not kind:
        return (f"a {track.kind!r} track changes the tow's heading along its course, so the tow is not steady (a "
                "circle or a straight course is)")
    moved = [f"top_motion.{n}" for n in ("series", "spectrum", "rao", "vessel") if getattr(top, n, None) is not None]
    if moved:
        return f"{moved[0]} moves the tow point besides the track: the tow is not steady"
    if env.waves or env.system_speed != 0.0 or any(v != 0.0 for v in env.current_speeds):
        return ("waves, a current or a system speed: the steady state is found in still water (and a current "
                "breaks a turn's rotational symmetry)")
    if kind == "turn":
        odd = heading_dependent_bodies(scene)
        if odd:
            return ("a point body whose virtual masses or drag axis change with the heading (" + "; ".join(odd) +
                    ", fixed in the scene's axes: Wang 1971 eq. 16): no turn is steady")
    return ""


def _rotated(X: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """States ``X`` (2 nq, 1) of 3-vectors rotated by each of ``angles`` (rad) about the upward vertical: (2 nq, n)
    (the module docstring's Q(theta) on every position and velocity)."""
    v = X.reshape(-1, 3)
    c, s = np.cos(angles)[None, :], np.sin(angles)[None, :]
    x, y, z = v[:, 0:1], v[:, 1:2], v[:, 2:3]
    out = np.empty((v.shape[0], 3, angles.size))
    out[:, 0, :] = x * c - z * s
    out[:, 1, :] = np.repeat(y, angles.size, axis=1)
    out[:, 2, :] = x * s + z * c
    return out.reshape(-1, angles.size)


def carried(model, x0: np.ndarray, times, turn_rate: float, p) -> np.ndarray:
    """The steady state ``x0`` (at t = 0) carried to ``times``: turned by Omega t about the circle's centre
    (``turn_rate`` Omega, rad/s), or for a straight tow (``turn_rate`` 0) every node translated by V t, V the tow
    point's velocity (the module docstring's x(t)); (2 nq, n)."""
    T = np.asarray(times, float)
    x0 = np.asarray(x0, float).ravel()
    if turn_rate:
        return _rotated(x0, turn_rate * T)
    dim, nq = getattr(model, "dim", 2), model.nq
    e = np.array(model.top(0.0, p)).ravel()
    V = e[1 + dim:1 + 2 * dim]
    X = np.repeat(x0[:, None], T.size, axis=1)
    X[:nq, :] += np.tile(V, nq // dim)[:, None] * T[None, :]
    return X


def frame_matrix(model, x0: np.ndarray, p, turn_rate: float) -> np.ndarray:
    """A, the linearization about the steady state in the frame that turns (or moves) with the tow (module
    docstring): J(x0, 0) - Omega_hat, Omega_hat the block skew matrix of omega = Omega (0, -1, 0) on every 3-vector of
    the state; J itself for a straight tow."""
    from ..time_domain.failures import ode_jacobian
    J = np.array(ode_jacobian(model)(x0, 0.0, p))
    if not turn_rate:
        return J
    S = np.array([[0.0, 0.0, -turn_rate], [0.0, 0.0, 0.0], [turn_rate, 0.0, 0.0]])
    return J - np.kron(np.eye(J.shape[0] // 3), S)


def stability(model, x0: np.ndarray, p, turn_rate: float) -> dict:
    """The steady state's eigenvalues in the frame of the tow (:func:`frame_matrix`, numpy.linalg.eigvals) and the
    verdict: ``stable`` (every Re lambda < -STABILITY_MARGIN max |lambda|), the least-damped eigenvalue
    ``least_damped`` (re, im; 1/s), its ``damping_ratio`` -Re / |lambda| and ``decay_time_s`` -1 / Re (inf when it
    does not decay), ``floquet_modulus`` |exp(lambda T)| over one revolution T (a turn), ``margin`` (1/s) and
    ``eigenvalues`` (how many)."""
    lam = np.linalg.eigvals(frame_matrix(model, x0, p, turn_rate))
    worst = lam[int(np.argmax(lam.real))]
    margin = STABILITY_MARGIN * float(np.max(np.abs(lam)))
    out = {"stable": bool(worst.real < -margin), "least_damped": [float(worst.real), float(abs(worst.imag))],
           "damping_ratio": float(-worst.real / abs(worst)) if abs(worst) > 0 else 0.0,
           "decay_time_s": float(-1.0 / worst.real) if worst.real < 0 else math.inf,
           "margin": margin, "eigenvalues": int(lam.size)}
    if turn_rate:
        out["floquet_modulus"] = float(math.exp(worst.real * 2.0 * math.pi / abs(turn_rate)))
    return out


def describe_stability(st: dict) -> str:
    """The reason's words for :func:`stability`'s verdict."""
    re, im = st["least_damped"]
    lam = f"{re:.3g}" + (f" +- {im:.4g}i" if im else "")
    if not st["stable"]:
        return (f"NOT stable: its least-damped eigenvalue in the frame of the tow is {lam} 1/s (real part not below "
                f"-{st['margin']:.2g} 1/s)")
    text = (f"stable: every eigenvalue in the frame of the tow decays, the least damped {lam} 1/s (damping ratio "
            f"{st['damping_ratio']:.2g}, decay time {st['decay_time_s']:.3g} s")
    if "floquet_modulus" in st:
        text += f", Floquet multiplier {st['floquet_modulus']:.3g} per revolution"
    return text + ")"


def steady_run(scene: Scene, scene_run: Scene, model, x0, segments: int, times=None, cache=None):
    """The run of the steady rung: ``model``, the node model of ``scene_run`` (``scene`` with ``segments`` elements per
    section, the segmented rung's), from its steady start ``x0`` (at t = 0: the start of its time-domain run), carried
    to the output times (:func:`carried`), every output the model's own
    (:func:`~cablesys.time_domain.sampled.sampled_record`); ``cache`` (a :class:`~.rungs.RungCache`) keeps the stability
    verdict of a model and start it has seen.

    Returns
    -------
    RunRecord
        ``model_info`` {name "steady", segments}; ``stats["steady"]``: ``kind`` (turn, tow), ``turn_rate`` (rad/s),
        ``statics_tolerance`` (the scaled residual the state holds), ``residual`` (|f(y, 0) - Omega_hat y - (V, 0)|,
        max over the state, in its units: m/s and m/s^2) and :func:`stability`'s verdict.
    """
    from ..time_domain.failures import ode_jacobian
    from ..time_domain.sampled import sampled_record
    t_build = time.perf_counter()
    ode_jacobian(model)                       # built once per model (model.derive): the setup, not the run
    t0 = time.perf_counter()
    sc = scene_run
    p = np.asarray(model.parameters(sc), dtype=float)
    x0 = np.asarray(x0, dtype=float).ravel()
    kind = steady_kind(scene)
    rate = float(scene.top_motion.track.turn_rate) if kind == "turn" else 0.0
    T = sc.output_times if times is None else np.asarray(times, float)
    X = carried(model, x0, T, rate, p)
    f0 = np.array(model.ode(x0, 0.0, p)).ravel()
    # x' of the carried state at t = 0: Omega_hat y (turn), or (V, 0) (tow: the state carried over 1 s, less itself)
    drift = (np.kron(np.eye(x0.size // 3), [[0, 0, -rate], [0, 0, 0], [rate, 0, 0]]) @ x0 if rate
             else carried(model, x0, [1.0], 0.0, p)[:, 0] - x0)
    judge = lambda: stability(model, x0, p, rate)
    st = judge() if cache is None else cache.memo(model, "steady_stability", (p, x0), judge)
    gap = np.array(model.cable_force(x0, p)).ravel()
    modes = np.repeat((gap < 0).astype(float)[:, None], T.size, axis=1)
    info = {"kind": kind, "turn_rate": rate, "statics_tolerance": float(statics_tolerance(model, p)),
            "residual": float(np.max(np.abs(f0 - drift))), **st}
    record = sampled_record(scene, model, p, T, states=X, modes=modes, stats={"method": "steady state", "steady": info},
                            model_info={"name": "steady", "segments": int(segments)})
    wall = time.perf_counter() - t0
    return dataclasses.replace(record, stats={**record.stats, "wall_s": wall, "wall_time_s": wall, "run_s": wall,
                                              "build_s": t0 - t_build})
