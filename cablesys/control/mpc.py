"""Closed-loop heave compensation against the nonlinear plant: MPC and the strategies it replaces.

The plant is a winch model of the scene (``plant_model``: by default the winch form of the model ``cablesys run``
runs for the scene, :mod:`.model_choice`; Wang's 2-DOF winch or the node model's winch on ``plant_elements``
elements as asked) with ``plant_segments`` drag segments on the cable (Wang 1971 eq. 38-45),
integrated by CVODES (:class:`.plant.Plant`); the controller's model (``controller_model``, not finer:
Wang's 2-DOF or a node model of fewer elements, with ``controller_segments`` drag segments) has its own RK4
transcription, and sees the plant's state in its coordinates (:func:`state_map`): the model mismatch. Every
strategy plays on that one plant (the passive compensator on the plant's model with its piston coordinate,
``compensator=True`` of either winch model), so every dB is against the same uncompensated run.
Strategies, each run from rest over the same sea:

- ``none``: winch still (alpha = 0);
- ``passive``: no payout, the sheave on a passive heave compensator (piston mass m_p, gas
  spring k_p, damper c_p; precharge carrying the static load), tuned to
  omega_n = omega_p / ``passive_ratio`` of the body + cable mass, damping ratio 0.3;
- ``pi``: a vendor-style active heave compensation: feed-forward of the measured tip heave
  rate plus a PI on the payout error, w_cmd = -y_s' + K_p e + K_i int e with e = L_0 - y_s - L
  (the length that cancels the tip's heave), through the speed limit and the power limit at
  the measured tension (|w| <= P_max / T_top), and a servo
  alpha = (w_cmd - w) / tau within the acceleration limit;
- ``mpc``: the optimal payout over a receding horizon of ``horizon`` s with a preview of the
  tip motion over it (the scene's record), re-solved every control interval from the measured
  plant state, warm-started from the previous solution shifted by one interval; the first
  interval's alpha is applied (a step that does not converge applies the previous plan,
  shifted; the path constraints start at the second node, the first being the measured
  state). Each step is one Gauss-Newton QP (the real-time iteration, :class:`.rti.GaussNewtonMPC`;
  ``mpc_scheme="ipopt"``: IPOPT with exact Hessians to convergence on the same NLP). The plant's
  and the controller's rest states differ (the drag
  of the current on a differently discretized cable sets another angle and stretch): the
  controller sees the measured state minus that difference (a constant-offset estimate, so the
  mismatch does not read as a pendulum swing or a heave error to be corrected);
- ``mpc_no_preview``: the same MPC with the tip motion over the horizon predicted from the
  samples of it measured up to the step only (an autoregressive model, :class:`.prediction.ARPredictor`);
- ``optimal``: the open-loop optimum of the whole record on the controller's model, played
  open-loop on the plant (the physical limit for these winch limits, up to the mismatch).

Reported per strategy: residual body heave (rms over the statistics window, m, and in dB
against ``none``), peak top tension and the least tension the no-slack floor bounds (N: Wang's spring force
F_bc, the node model's least element tension), time with it below the cable's tension floor (s: slack by
Wang's rule, eq. 54; Wang's plant keeps the spring law there, so a slack run's later response is not that of
a slack cable; the node model's elements go slack by max(TENS, ...)), largest |winch power| (W), and
the controller's compute time per step (s).
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import ClassVar

import numpy as np

from ..errors import ParameterError, require_positive
from ..model.segmented_winch_control import NodeWinchModel
from ..model.winch import WINCH_OUTPUTS
from ..results import ResultBase, timed
from .limits import WinchLimits
from .model_choice import MODELS, resolve_model
from .payout import check_window, describe_model, heave_problem, payout_nlp
from .payout_result import heave_reduction_db, statistics_window
from .plant import Plant
from .prediction import ARPredictor
from .rti import GaussNewtonMPC

STRATEGIES = ("none", "passive", "pi", "mpc", "mpc_no_preview", "optimal")
# how an MPC step solves its horizon problem
MPC_SCHEMES = ("gauss-newton", "ipopt")


@dataclasses.dataclass(frozen=True)
class Comparison(ResultBase):
    """Closed-loop runs of every strategy on the plant (module docstring), on one time grid.

    ``heave`` / ``tension_top`` / ``tension_mid`` (the spring force F_bc, the mid-length tension) / ``speed`` /
    ``power`` map a strategy to its series (m, N, N, m/s, W) at ``times`` (s); ``metrics`` a strategy to its headline numbers.
    """

    times: np.ndarray
    heave: dict
    tension_top: dict
    tension_mid: dict
    speed: dict
    power: dict
    length: dict
    metrics: dict
    limits: dict
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)

    VARIABLES: ClassVar[dict] = {"heave": ("m", "body heave from rest (down +)"),
                                 "tension_top": ("N", "tension at the sheave"),
                                 "tension_mid": ("N", "tension at mid-length: the spring force F_bc (Wang 1971 eq. 54)"),
                                 "speed": ("m/s", "payout rate"), "power": ("W", "winch power T_top w"),
                                 "length": ("m", "unstretched length in the water"), "strategy": ("1", "strategy")}

    def summary(self) -> dict:
        return {**super().summary(), "metrics": self.metrics, "limits": self.limits}

    def to_xarray(self):
        import xarray as xr
        names = [s for s in STRATEGIES if s in self.heave]
        data = {k: (("strategy", "time"), np.array([getattr(self, k)[s] for s in names]))
                for k in ("heave", "tension_top", "tension_mid", "speed", "power", "length")}
        return xr.Dataset(data, coords={"strategy": names, "time": self.times})


def plant_scene(scene, plant_segments: int | None = None):
    """The plant's scene: ``scene`` with ``plant_segments`` drag segments on its cable (None: the scene's own)."""
    return scene if plant_segments is None else scene.with_numerics(drag_segments=plant_segments)


def _metrics(problem, T, Y, heave0, mask, tens_floor):
    oi = problem.output_labels.index
    h = Y[:, oi("heave")] - problem.heave_rest
    dt = np.diff(T, prepend=T[0])
    return {"heave_rms_m": float(np.sqrt(np.mean(h[mask] ** 2))),
            "heave_reduction_db": heave_reduction_db(h, heave0, mask),
            "tension_max_n": float(np.max(Y[:, oi("tension_top")])),
            "tension_min_n": float(np.min(Y[:, oi(problem.floor_output)])),
            "slack_time_s": float(np.sum(dt[Y[:, oi(problem.floor_output)] < tens_floor])),
            "power_max_w": float(np.max(np.abs(Y[:, oi("power")]))),
            "speed_max_m_s": float(np.max(np.abs(Y[:, oi("speed")])))}


def _run(plant, problem_plant, controller, N: int, x0):
    """Closed loop: ``controller(k, x) -> alpha``; returns (T, X, alpha per node, step times)."""
    dt = problem_plant.dt
    X, A, S = [np.asarray(x0, float)], [], []
    for k in range(N):
        t0 = time.perf_counter()
        a = float(controller(k, X[-1]))
        S.append(time.perf_counter() - t0)
        A.append(a)
        X.append(plant.advance(X[-1], a, k * dt)[-1])
    A.append(0.0)
    return dt * np.arange(N + 1), np.array(X), np.array(A), np.array(S)


def _pi_controller(problem, limits: WinchLimits, kp: float, ki: float, tau: float):
    """The vendor-style AHC (module docstring) as ``controller(k, x) -> alpha``."""
    m, p, dt = problem.model, problem.p, problem.dt
    L0 = problem.x_rest[-2]
    state = {"int": 0.0}

    i_top = WINCH_OUTPUTS.index("tension_top")

    def control(k, x):
        e = np.array(m.top(k * dt, p)).ravel()
        err = (L0 - e[2]) - x[-2]
        state["int"] += err * dt
        # the drive's speed limit, and the power limit at the measured line tension
        tension = abs(float(np.array(m.outputs(x, [0.0, 0.0], k * dt, p, problem.c)).ravel()[i_top]))
        w_lim = min(limits.speed, limits.power / max(tension, 1.0))
        w_cmd = float(np.clip(-e[4] + kp * err + ki * state["int"], -w_lim, w_lim))
        return float(np.clip((w_cmd - x[-1]) / tau, -limits.acceleration, limits.acceleration))
    return control


@timed
def compare_compensation(scene, limits: WinchLimits, *, duration: float, horizon: float = 20.0, dt: float = 0.5,
                         plant_segments: int | None = None, controller_segments: int = 1,
                         tension_weight: float = 0.0, control_weight: float = 1e-3,
                         passive_ratio: float = 3.0, pi_gains=(0.5, 0.05), servo_tau: float | None = None,
                         strategies=STRATEGIES, stats_start: float | None = None, max_iter: int = 100,
                         mpc_scheme: str = "gauss-newton", mpc_iterations: int = 1, ar_order: int = 24,
                         plant_model="auto", plant_elements: int | None = None,
                         controller_model: str = "wang", controller_elements: int | None = None) -> Comparison:
    """Run the strategies of the module docstring on the plant and compare them.

    Parameters
    ----------
    scene : Scene
        One section; its top motion is the sea (and the MPC's preview).
    limits : WinchLimits
    duration : float
        Closed-loop run (s); with the MPC's horizon within the record.
    horizon : float
        MPC horizon = preview (s).
    dt : float
        Control interval (s), of the controller and the plant's zero-order hold.
    plant_segments, controller_segments : int
        Drag segments of the plant (default: the scene's) and of the controller's model.
    tension_weight, control_weight : float
        Objective weights (:func:`.payout.heave_problem`).
    passive_ratio : float
        omega_p / omega_n of the passive compensator (omega_p from the scene's sea, else its
        slowest sinusoid).
    pi_gains : (float, float)
        K_p (1/s) and K_i (1/s^2) of the PI AHC; ``servo_tau`` (s) its speed servo (default dt).
    strategies : sequence of str
        A subset of :data:`STRATEGIES`.
    stats_start : float, optional
        Start of the statistics window (s; default the window of every run's summary, :func:`cablesys.statistics.window`).
    max_iter : int
        IPOPT iterations per MPC step (``mpc_scheme`` "ipopt").
    mpc_scheme : str
        How each MPC step solves its horizon problem: "gauss-newton" (:class:`GaussNewtonMPC`) or "ipopt"
        (the full NLP with exact Hessians to convergence, :func:`.payout.payout_nlp`).
    mpc_iterations : int
        Gauss-Newton QPs per MPC step (1: the real-time iteration; "gauss-newton" only).
    ar_order : int
        Order of the autoregressive top-motion predictor of ``mpc_no_preview`` (:class:`ARPredictor`).
    plant_model : str or ModelChoice
        The plant's model: "auto" (default), the winch form of the ladder's a priori choice for the plant's scene
        (the scene with ``plant_segments``; where ``cablesys run`` starts, before its checks may grow N; :func:`.model_choice.resolve_model`, as
        ``cablesys control``), "wang" (Wang's 2-DOF winch), "segmented" (the node model's winch,
        :mod:`cablesys.model.segmented_winch_control`) or a resolved :class:`.model_choice.ModelChoice`.
    controller_model : str
        "wang" (default, as ``cablesys control``: the model mismatch against a node-model plant) or "segmented":
        the controller's (the MPC's and the open-loop optimum's) model, not finer than the plant's (a node plant
        with a Wang or a coarser node controller is the model mismatch). The controller sees the plant's state
        mapped to its coordinates (:func:`state_map`).
    plant_elements, controller_elements : int, optional
        N of a segmented plant / controller (default: the ladder's N for an "auto" plant, else the scene's
        ``cable.segments``).

    Returns
    -------
    Comparison
        ``success`` False (with the reason) when an MPC step or the open-loop optimum did not
        converge; the runs computed are kept. ``stats`` names the plant's and the controller's models and says
        why each ran (``plant_model_reason``, ``plant_model_choice``, ``controller_model_reason``).
    """
    unknown = [s for s in strategies if s not in STRATEGIES]
    if unknown:
        raise ParameterError("strategies", unknown, f"allowed: {STRATEGIES}")
    if mpc_scheme not in MPC_SCHEMES:
        raise ParameterError("mpc_scheme", mpc_scheme, f"allowed: {MPC_SCHEMES}")
    if not (isinstance(mpc_iterations, int) and mpc_iterations >= 1):
        raise ParameterError("mpc_iterations", mpc_iterations, "must be an integer >= 1")
    if mpc_scheme == "ipopt" and mpc_iterations != 1:
        raise ParameterError("mpc_iterations", mpc_iterations, "is the Gauss-Newton scheme's; IPOPT iterates to "
                                                               "convergence (max_iter)")
    if not (isinstance(ar_order, int) and ar_order >= 1):
        raise ParameterError("ar_order", ar_order, "must be an integer >= 1")
    if len(scene.sections) != 1:      # the controller's state map (state_map) interpolates one section's nodes
        raise ParameterError("sections", len(scene.sections), "must be 1: the compensation strategies run one "
                             "section (a chain is designed through the time domain: cablesys control --design)")
    plant_sc = plant_scene(scene, plant_segments)
    ctrl_scene = scene.with_numerics(drag_segments=controller_segments)
    kw = dict(dt=dt, tension_weight=tension_weight, control_weight=control_weight)
    if controller_model not in MODELS:
        raise ParameterError("controller_model", controller_model, f"allowed: {', '.join(MODELS)}")
    plant_choice = resolve_model(plant_sc, plant_model, plant_elements, names=("plant_model", "plant_elements"))
    ctrl_choice = resolve_model(ctrl_scene, controller_model, controller_elements,
                                names=("controller_model", "controller_elements"))
    prob_p = heave_problem(plant_sc, limits, model=plant_choice, **kw)
    prob_c = heave_problem(ctrl_scene, limits, model=ctrl_choice, **kw)
    observe = state_map(prob_p, prob_c)
    N = check_window(prob_c, 0.0, duration)
    mpcs = [s for s in ("mpc", "mpc_no_preview") if s in strategies]
    if "mpc" in strategies:           # the preview reads the record up to duration + horizon
        n_h = check_window(prob_c, duration, horizon)
    elif mpcs:                        # the prediction reads nothing beyond the measured past
        require_positive("horizon", horizon, "s")
        n_h = int(round(horizon / dt))
        if n_h < 2:
            raise ParameterError("horizon", horizon, f"must span at least 2 control intervals of {dt:g} s")
    else:
        n_h = 0
    plant = Plant(prob_p.model, prob_p.p, prob_p.c, dt)
    runs, step_s, messages, mpc_stats = {}, {}, [], {}

    runs["none"] = _run(plant, prob_p, lambda k, x: 0.0, N, prob_p.x_rest)     # the reference of every dB
    if "pi" in strategies:
        ctl = _pi_controller(prob_p, limits, pi_gains[0], pi_gains[1], servo_tau or dt)
        runs["pi"] = _run(plant, prob_p, ctl, N, prob_p.x_rest)
        step_s["pi"] = runs["pi"][3]
    if "optimal" in strategies:
        nlp = payout_nlp(prob_c, N, max_iter=max(max_iter, 300), hessian="gauss-newton")   # as optimal_payout
        sol = nlp.solve(prob_c.x_rest, prob_c.exogenous(dt * np.arange(N + 1)),
                        (prob_c.rollout(prob_c.x_rest, np.zeros(N)), np.zeros((N, 1))))
        if not sol.success:
            messages.append(f"open-loop optimum: {sol.status} {sol.worst}".strip())
        U = sol.U.ravel()
        runs["optimal"] = _run(plant, prob_p, lambda k, x: U[k], N, prob_p.x_rest)
        step_s["optimal"] = np.array([sol.solve_s])
    # the models' rest states differ (drag in the current, the node model's bowed line)
    offset = observe(prob_p.x_rest, 0.0) - prob_c.x_rest
    measure = lambda k, x: observe(x, k * dt) - offset
    for name in ("mpc", "mpc_no_preview"):
        if name not in strategies:
            continue
        predictor = ARPredictor(prob_c, ar_order) if name == "mpc_no_preview" else None
        ctl, memo = _mpc_controller(prob_c, N, n_h, measure, mpc_scheme, mpc_iterations, max_iter, predictor)
        runs[name] = _run(plant, prob_p, ctl, N, prob_p.x_rest)
        step_s[name] = runs[name][3]
        mpc_stats[name] = {"scheme": mpc_scheme, "failed_steps": memo["fail"],
                           "iterations_per_step_mean": float(np.mean(memo["iterations"]))}
        if memo["fail"]:
            messages.append(f"{name}: {memo['fail']} of {N} steps did not converge (the previous plan, shifted, "
                            "was applied)")
    if "passive" in strategies:     # the plant's model with the compensator's piston coordinate
        runs["passive"] = _passive_run(scene, plant_sc, limits, dict(kw, model=plant_choice), passive_ratio, N)

    T = dt * np.arange(N + 1)
    mask = statistics_window(T, stats_start, prob_c.scene.top_motion)
    out = {name: {} for name in ("heave", "tension_top", "tension_mid", "speed", "power", "length")}
    metrics = {}
    oi = WINCH_OUTPUTS.index
    Y0 = prob_p.outputs(runs["none"][1], runs["none"][2], T)
    h0 = Y0[:, oi("heave")] - prob_p.heave_rest
    floor = float(prob_p.p[prob_p.model.layout.index("cable.tension_floor")])
    for name in [s for s in STRATEGIES if s in runs]:
        prob, (_, X, A, _) = (runs[name][4], runs[name][:4]) if name == "passive" else (prob_p, runs[name])
        Y = prob.outputs(X, A, T)
        for k in out:
            out[k][name] = Y[:, oi(k)] - (prob.heave_rest if k == "heave" else 0.0)
        metrics[name] = _metrics(prob, T, Y, h0, mask, floor)
        if name in step_s:
            metrics[name]["compute_per_step_s"] = float(np.mean(step_s[name]))
            metrics[name]["compute_max_step_s"] = float(np.max(step_s[name]))
    for name in mpc_stats:
        metrics[name]["realtime_factor"] = dt / metrics[name]["compute_per_step_s"]
        metrics[name].update(mpc_stats[name])
    lim = {"speed_m_s": limits.speed, "acceleration_m_s2": limits.acceleration, "power_w": limits.power,
           "working_load_n": prob_p.working_load, "tension_floor_n": prob_p.floor,
           "static_tension_n": prob_p.static_tension}
    return Comparison(times=T, metrics=metrics, limits=lim, success=not messages, message="; ".join(messages),
                      stats={"steps": N, "horizon_intervals": n_h, "dt_s": dt,
                             "plant_segments": plant_sc.numerics.drag_segments,
                             "controller_segments": controller_segments, "mpc_scheme": mpc_scheme,
                             "plant_model": describe_model(prob_p.model), "controller_model": describe_model(prob_c.model),
                             "plant_model_reason": prob_p.model_reason, "plant_model_choice": plant_choice.as_dict(),
                             "controller_model_reason": prob_c.model_reason,
                             "same_plant": "every strategy on the plant (passive: its model with the compensator)",
                             "controller_substeps": prob_c.substeps,
                             "mpc_iterations": mpc_iterations, "ar_order": ar_order}, **out)


def _mpc_controller(prob_c, N, n_h, measure, scheme, iterations, max_iter, predictor=None):
    """The MPC of the module docstring over N steps as ``controller(k, x) -> alpha`` and its record (failed
    steps, iterations per step): the top motion over the horizon previewed (the scene's record, tabulated
    once at the intervals' stage times before the run: the preview is data the controller receives), or
    predicted by ``predictor`` (:class:`ARPredictor`) from the samples measured up to the step."""
    dt = prob_c.dt
    preview = prob_c.exogenous(dt * np.arange(N + n_h + 1)) if predictor is None else None
    if scheme == "ipopt":      # built once, solved N times; no path constraint on the measured state itself
        nlp = payout_nlp(prob_c, n_h, max_iter=max_iter, expand=True, constrain_first=False)
    else:
        gn = GaussNewtonMPC(prob_c, n_h, iterations=iterations)
    roll = prob_c.step.mapaccum(n_h)
    memo = {"U": np.zeros(n_h), "fail": 0, "iterations": []}

    def mpc(k, x):
        x = measure(k, x)                               # the measured state in the controller's coordinates
        U = np.append(memo["U"][1:], memo["U"][-1])       # warm start: shifted by one interval
        if predictor is None:
            E = preview[k: k + n_h + 1]
        else:
            predictor.measure(k * dt)
            E = predictor.exogenous(k, n_h)
        if scheme == "ipopt":
            Xg = np.vstack([x, np.array(roll(x, U[None, :], E[:n_h].T)).T])
            sol = nlp.solve(x, E, (Xg, U[:, None]))
            Unew, ok = sol.U.ravel(), sol.success
            memo["iterations"].append(sol.iterations)
        else:
            Unew, ok = gn.step(x, E, U)
            memo["iterations"].append(iterations)
        memo["fail"] += not ok
        memo["U"] = Unew if ok else U      # a failed step keeps the previous plan
        return memo["U"][0]
    return mpc, memo


def state_map(prob_p, prob_c):
    """``observe(x, t) -> x_c``: the plant's state in the controller's coordinates (L and w as they are).

    Same model: x itself. Node plant, Wang controller: the chord from the top (x_s, y_s)(t) (the measured tip) to
    the body node gives Wang's phi = atan2(-c_x, c_y) and l = |c| (Wang 1971 eq. 10: the body at top + l e_t,
    e_t = (-sin phi, cos phi)), their rates from the body node's velocity. Node plant of N_p elements, node
    controller of N_c: the controller's node j at the fraction j / N_c of the line from the top, linearly
    interpolated between the plant's nodes (node 0 the tip) in positions and velocities. A controller finer than
    its plant is refused."""
    mp, mc = prob_p.model, prob_c.model
    node_p, node_c = isinstance(mp, NodeWinchModel), isinstance(mc, NodeWinchModel)
    if not node_p:
        if node_c:
            raise ParameterError("controller_model", "segmented", "must not be finer than the plant's (Wang's 2-DOF)")
        if mp.nx != mc.nx:
            raise ParameterError("controller_model", describe_model(mc), f"has no state map from the plant "
                                                                         f"({describe_model(mp)})")
        return lambda x, t: np.asarray(x, float)
    if node_c and mc.segments > mp.segments:
        raise ParameterError("controller_elements", mc.segments, f"must be at most the plant's {mp.segments}")
    n_p = mp.segments
    top, pp = mp.top, prob_p.p

    def nodes(x, t):
        e = np.array(top(t, pp)).ravel()
        q, qd = np.asarray(x[:mp.nq], float).reshape(n_p, 2), np.asarray(x[mp.nq:2 * mp.nq], float).reshape(n_p, 2)
        return np.vstack([e[1:3], q]), np.vstack([e[3:5], qd])

    if not node_c:
        def observe(x, t):
            r, v = nodes(x, t)
            c, cv = r[-1] - r[0], v[-1] - v[0]
            l2 = c @ c
            phi, l = math.atan2(-c[0], c[1]), math.sqrt(l2)
            return np.array([phi, l, (c[0] * cv[1] - c[1] * cv[0]) / l2, c @ cv / l, x[-2], x[-1]])
        return observe
    f_p, f_c = np.arange(n_p + 1) / n_p, np.arange(1, mc.segments + 1) / mc.segments

    def observe(x, t):
        r, v = nodes(x, t)
        at = lambda a: np.column_stack([np.interp(f_c, f_p, a[:, i]) for i in range(2)]).ravel()
        return np.concatenate([at(r), at(v), [x[-2], x[-1]]])
    return observe


def _passive_run(scene, plant_scene, limits, kw, ratio, N):
    """The passive compensator on the plant: (T, X, alpha, step times, its problem)."""
    sea = scene.top_motion.spectrum
    omega_p = 2 * math.pi / sea.tp if sea is not None else min(s.frequency for s in scene.top_motion.y)
    body, cable = scene.sections[0].body, scene.sections[0].cable
    m = body.mass_y + cable.mass_per_length * cable.length
    wn = omega_p / ratio
    comp = {"mass": 200.0, "stiffness": m * wn ** 2, "damping": 2 * 0.3 * m * wn}
    prob = heave_problem(plant_scene, limits, compensator=comp, **kw)
    plant = Plant(prob.model, prob.p, prob.c, prob.dt)
    T, X, A, S = _run(plant, prob, lambda k, x: 0.0, N, prob.x_rest)
    return T, X, A, S, prob
