"""Benchmark of heave compensation by the winch (cablesys.control) on the ROV lift.

Measured in one run:

- the open-loop optimal payout for the ROV lift's JONSWAP sea (Hs 2.5 m, Tp 10 s; ``--quick``:
  the first 60 s, else 600 s) on the 2-DOF winch model (one drag segment), dt = 0.5 s, speed
  1 m/s, acceleration 1 m/s^2: IPOPT wall time, iterations, status, and the body heave
  against the uncompensated run (dB, negative = reduced); with compiled kernels (the default) also the
  same NLP in CasADi's virtual machine (objective difference, IPOPT CPU time ratio) and the kernels' build
  time (a cold cache: code generation and compile; a warm one: hashing and loading);
- that optimum re-simulated by CVODES on a 4x finer output grid: the largest relative
  constraint violation;
- closed loop on a finer plant (Wang's 2-DOF winch, asked for by name, with the scene's 10 drag segments;
  ``--quick``: 4), 120 s (``--quick``: 20 s): PI/feed-forward
  AHC, MPC with a 20 s horizon (``--quick``: 10 s) and preview, and MPC without preview (the top
  motion predicted by an AR model of its measured past), both by the Gauss-Newton real-time
  iteration: heave in dB against the uncompensated plant run, mean time per MPC step and the
  real-time factor dt / step time; and the preview MPC by IPOPT on the full NLP per step (heave,
  step time, iterations per step: the reference the real-time iteration is measured against);
- the open-loop optimum on the segmented node model (N = 4 elements of the ROV lift's line, compiled per-RK4-step
  kernels, dt = 0.5 s) over a 60 s record (``--quick``: 4 s), its RK4 steps per interval (set by the stiffest
  axial mode at rest, :func:`cablesys.control.payout.fastest_mode`), and Wang's 2-DOF optimum on the same record
  in the same run: wall and IPOPT CPU times and their ratio, iterations, status, heave in dB, IPOPT's time split
  (the Lagrangian Hessian's share); IPOPT with the objective's Gauss-Newton Hessian (the default) and with the
  exact AD Hessian on the node model, interleaved (exact, Gauss-Newton, twice; ``--quick``: the exact once, the
  Gauss-Newton being the node row's own solve of the same NLP): IPOPT CPU and iterations of each and the difference
  of their optima; ``--only node`` runs this row alone;
- the closed loop on the node-model plant (N = 4, the ladder's model of the ROV lift) with the Gauss-Newton MPC on
  Wang's 2-DOF controller (the model mismatch of ``cablesys control``'s default), 120 s with a 20 s horizon
  (``--quick``: 30 s, 10 s): heave in dB against the uncompensated node plant, time per MPC step and the
  real-time factor;
- the LQ check: the multiple-shooting optimum of a spring-mass plant against the discrete
  Riccati law (relative error);
- a time-domain design gradient: d(mean square heave of the uncompensated 2-DOF run)/d(AE, C_I)
  by forward sensitivities of the RK4 roll-out, against central finite differences (relative
  error per parameter at the best of three steps, the largest of the two), and its cost over
  one roll-out;
- the time-domain design's own gradient on the node model (N = 4, :mod:`cablesys.control.design`: the objective's
  and every constraint's Jacobian by forward sensitivities, one seed, 600 s; ``--quick``: 70 s) against
  Richardson central differences, and its cost over one evaluation of the objective and constraints.

Writes bench_control.json. Usage: python studies/bench_control.py --out DIR [--quick] [--only node]
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import time
from pathlib import Path

import casadi as ca
import numpy as np
from scipy.linalg import expm, solve_discrete_are

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, write_json

from cablesys.control import WinchLimits, heave_problem, optimal_payout, resimulate
from cablesys.control.mpc import compare_compensation
from cablesys.control.prediction import ARPredictor
from cablesys.control.rti import GaussNewtonMPC
from cablesys.control.kernels import interval_kernels
from cablesys.control.payout import fastest_mode
from cablesys.control.shooting import solve_shooting
from cablesys.examples import example_path
from cablesys.scene import load_scene


@contextlib.contextmanager
def _compile_off():
    """CABLESYS_COMPILE=0 inside the block (CasADi's virtual machine)."""
    before = os.environ.get("CABLESYS_COMPILE")
    os.environ["CABLESYS_COMPILE"] = "0"
    try:
        yield
    finally:
        if before is None:
            del os.environ["CABLESYS_COMPILE"]
        else:
            os.environ["CABLESYS_COMPILE"] = before


def lq_error() -> float:
    """max |u_shooting - u_Riccati| / max |u_Riccati| for a spring-mass plant (tests/test_control_lq.py)."""
    dt, m, k, c = 0.1, 2.0, 8.0, 0.3
    Ac, Bc = np.array([[0.0, 1.0], [-k / m, -c / m]]), np.array([[0.0], [1.0 / m]])
    E = expm(np.block([[Ac, Bc], [np.zeros((1, 3))]]) * dt)
    A, B = E[:2, :2], E[:2, 2:]
    Q, R = np.diag([1.0, 0.1]), np.array([[0.05]])
    P = solve_discrete_are(A, B, Q, R)
    K = np.linalg.solve(R + B.T @ P @ B, B.T @ P @ A)
    x, u, r = ca.SX.sym("x", 2), ca.SX.sym("u"), ca.SX.sym("r")
    step = ca.Function("step", [x, u, r], [ca.mtimes(ca.DM(A), x) + ca.mtimes(ca.DM(B), u)])
    stage = ca.Function("stage", [x, u, r], [ca.bilin(ca.DM(Q), x, x) + ca.bilin(ca.DM(R), u, u), u])
    sol = solve_shooting(step, stage, [1.0, -0.5], 60, terminal=ca.Function("t", [x], [ca.bilin(ca.DM(P), x, x)]),
                         ipopt={"tol": 1e-12})
    u_lqr = -(K @ sol.X[:-1].T).ravel()
    return float(np.max(np.abs(sol.U.ravel() - u_lqr)) / np.max(np.abs(u_lqr)))


def design_gradient(problem, duration: float) -> dict:
    """Gradient of the uncompensated mean square body heave over [0, duration] w.r.t. theta = (AE, C_I) by
    forward sensitivities of the RK4 roll-out (:func:`cablesys.control.gradient.rollout_gradient`), against
    Richardson-extrapolated central differences (:func:`cablesys.control.gradient.central_differences`), for
    the 2-DOF model (the problem's scene, RK4 step dt / substeps) and the segmented cable (4 elements,
    h = 0.05 s, 30 s). Both at the soft insert AE = 2e5 N inside the scene's [design] bounds (the region
    of both design optima): at the steel line's AE the segmented model's C_I derivative changes J by
    ~1e-11 of itself per 1e-4 step, below what differences resolve. cost_ratio: the least of 5 wall
    times of the gradient sweep over that of the plain roll-out, measured here."""
    from cablesys.control.gradient import central_differences, rollout_gradient
    soft = problem.scene.replace_section(0, cable={"ae": 2e5})
    cases = {"wang": (soft, duration, problem.dt / problem.substeps),
             "segmented": (soft.replace_section(0, cable={"segments": 4}), min(duration, 30.0), 0.05)}
    out = {}
    for name, (scene, dur, h) in cases.items():
        rg = rollout_gradient(scene, dur, h)
        th0 = rg.theta0

        def timed(f, n=5):
            """The least of n wall times of f(th0) (after one call), and its value."""
            val, best = f(th0), math.inf
            for _ in range(n):
                t0 = time.perf_counter()
                val = f(th0)
                best = min(best, time.perf_counter() - t0)
            return best, val
        t_sim, _ = timed(rg.objective)
        t_grad, (_, g) = timed(rg.gradient)
        g = np.array(g).ravel()
        steps = (1e-4, 1e-5)
        fd = central_differences(rg.objective, th0, steps)
        errs = np.abs(fd - g) / np.abs(g)
        best = np.argmin(errs, axis=0)
        out[name] = {"gradient_ad": g.tolist(), "gradient_fd": fd[best, [0, 1]].tolist(), "fd_steps_rel": list(steps),
                     "fd_rel_err_by_step": errs.tolist(), "rel_err": float(np.max(errs[best, [0, 1]])),
                     "cost_ratio": t_grad / t_sim, "simulation_s": t_sim, "gradient_s": t_grad, "theta": th0.tolist(),
                     "steps": rg.steps, "h_s": rg.h, "compiled": rg.compiled}
    w = out["wang"]
    return {**w, "rel_err": max(o["rel_err"] for o in out.values()),
            "cost_ratio": max(o["cost_ratio"] for o in out.values()), "models": out}


def gauss_newton_breakdown(scene, limits, t0: float, horizon: float, repeats: int = 50) -> dict:
    """Least mean time (ms, of 5 rounds of ``repeats``) of the parts of one Gauss-Newton MPC step on the 2-DOF
    controller model at the rest state, horizon starting at t0: the kernels mapped over the horizon (roll-out
    and linearization), the whole linearization with the condensing, and the QP."""
    prob = heave_problem(scene.with_numerics(drag_segments=1), limits, dt=0.5, model="wang")
    n_h = int(round(horizon / prob.dt))
    gn = GaussNewtonMPC(prob, n_h)
    E, U, x = prob.exogenous(t0 + prob.dt * np.arange(n_h + 1)), np.zeros(n_h), prob.x_rest
    H, g, A, lba, uba, _ = gn.linearization(x, E, U)
    a = gn.a_max

    def least(f):
        f()
        best = math.inf
        for _ in range(5):
            t = time.perf_counter()
            for _ in range(repeats):
                f()
            best = min(best, (time.perf_counter() - t) / repeats)
        return 1e3 * best
    return {"kernels_over_horizon": least(lambda: gn.horizon(x, U[None, :], E.T)),
            "linearization_and_condensing": least(lambda: gn.linearization(x, E, U)),
            "qp": least(lambda: gn.qp(h=H, g=g, a=A, lba=lba, uba=uba, lbx=-a - U, ubx=a - U)),
            "qp_rows": int(A.shape[0]), "qp_variables": n_h}


def prediction_error(scene, limits, duration: float, horizon: float, leads=(1.0, 5.0, 10.0, 20.0)) -> dict:
    """The no-preview MPC's top-motion prediction (``ARPredictor``, as in the closed loop: samples at
    dt = 0.5 s from t = 0) against the record: rms error of y_s (m) at each lead time (s) over the steps
    from duration / 4 on, and the rms of y_s itself over the same steps."""
    prob = heave_problem(scene.with_numerics(drag_segments=1), limits, dt=0.5, model="wang")
    n_h = int(round(horizon / prob.dt))
    pred, errs, ys = ARPredictor(prob), {lead: [] for lead in leads}, []
    for k in range(int(round(duration / prob.dt))):
        pred.measure(k * prob.dt)
        E = pred.exogenous(k, n_h)
        if k * prob.dt < duration / 4:
            continue
        true = prob.exogenous(prob.dt * (k + np.arange(n_h + 1)))
        ys.append(true[0, 2])
        for lead in leads:
            j = int(round(lead / prob.dt))
            if j <= n_h:
                errs[lead].append(E[j, 2] - true[j, 2])
    return {"lead_s": [lead for lead in leads if errs[lead]],
            "rms_error_m": [float(np.sqrt(np.mean(np.square(errs[lead])))) for lead in leads if errs[lead]],
            "rms_y_s_m": float(np.sqrt(np.mean(np.square(ys))))}


def closed_loop_mpc(scene, limits, quick: bool) -> dict:
    """The closed-loop runs on the finer plant: PI AHC, MPC with preview and MPC without preview (the
    top motion predicted from its measured past, ``ARPredictor``) by the Gauss-Newton real-time
    iteration (``GaussNewtonMPC``), and MPC with preview by IPOPT on the full NLP per step (exact
    Hessian, to convergence) as the reference of quality and speed in the same run."""
    duration, horizon = (20.0, 10.0) if quick else (120.0, 20.0)
    loop_scene = scene.with_numerics(duration=duration + horizon)
    kw = dict(duration=duration, horizon=horizon, dt=0.5, plant_segments=4 if quick else None, plant_model="wang")
    load0 = os.getloadavg()[0]
    cmp = compare_compensation(loop_scene, limits, strategies=("none", "pi", "mpc", "mpc_no_preview"), **kw)
    load1 = os.getloadavg()[0]
    ref = compare_compensation(loop_scene, limits, strategies=("none", "mpc"), mpc_scheme="ipopt", **kw)
    m, r = cmp.metrics, ref.metrics["mpc"]
    compiled = interval_kernels(heave_problem(scene.with_numerics(drag_segments=1), limits, dt=0.5,
                                              model="wang").interval)
    compiled = bool(compiled is not None and compiled.compiled)
    return dict(
        mpc_step_breakdown_ms=gauss_newton_breakdown(loop_scene, limits, duration, horizon, repeats=5 if quick else 50),
        mpc_no_preview_prediction=prediction_error(loop_scene, limits, duration, horizon),
        mpc_heave_reduction_db=m["mpc"]["heave_reduction_db"], pi_heave_reduction_db=m["pi"]["heave_reduction_db"],
        mpc_no_preview_heave_reduction_db=m["mpc_no_preview"]["heave_reduction_db"],
        mpc_step_ms=1e3 * m["mpc"]["compute_per_step_s"], mpc_realtime_factor=m["mpc"]["realtime_factor"],
        mpc_step_max_ms=1e3 * m["mpc"]["compute_max_step_s"],
        mpc_no_preview_step_ms=1e3 * m["mpc_no_preview"]["compute_per_step_s"],
        mpc_no_preview_realtime_factor=m["mpc_no_preview"]["realtime_factor"],
        mpc_scheme="gauss-newton real-time iteration (one condensed QP per step, DAQP)",
        mpc_ipopt_heave_reduction_db=r["heave_reduction_db"], mpc_ipopt_step_ms=1e3 * r["compute_per_step_s"],
        mpc_ipopt_iterations_per_step=r["iterations_per_step_mean"],
        mpc_heave_db_vs_ipopt=m["mpc"]["heave_reduction_db"] - r["heave_reduction_db"],
        mpc_speedup_vs_ipopt=r["compute_per_step_s"] / m["mpc"]["compute_per_step_s"],
        mpc_horizon_s=horizon, mpc_closed_loop_s=duration, mpc_plant_segments=cmp.stats["plant_segments"],
        mpc_success=cmp.success and ref.success, mpc_message="; ".join(x for x in (cmp.message, ref.message) if x),
        mpc_load_average_1min=[load0, load1], closed_loop=m, closed_loop_ipopt_mpc=r,
        mpc_note=("compiled per-interval kernels" if compiled else "CasADi virtual machine (no compiled code)")
        + "; target >= 50x real time compiled; mpc_ipopt_*: the same MPC with IPOPT on the full NLP per step "
          "(run after the others; load averages before and after the Gauss-Newton runs in mpc_load_average_1min)")


def node_hessians(problem, horizon: float, rounds: int, gauss_newton=None) -> dict:
    """IPOPT on the node-model OCP with the exact AD Hessian and with the objective's Gauss-Newton matrix,
    interleaved (exact, Gauss-Newton, ``rounds`` times) in one run under the same load: IPOPT CPU (least of the
    rounds), iterations, and the difference of the two optima (objective, relative; controls but the last, m/s^2:
    the last interval's alpha moves only the terminal node, a nearly flat direction). ``gauss_newton``: an optimum
    of this same problem already solved with the Gauss-Newton Hessian (``--quick``: the node row's own), taken as
    that Hessian's only round instead of solving the same NLP again (``rounds`` must then be 1)."""
    if gauss_newton is not None and rounds != 1:
        raise ValueError("gauss_newton: only with rounds = 1")
    runs = {"exact": [], "gauss-newton": []}
    for _ in range(rounds):
        for h in runs:
            if h == "gauss-newton" and gauss_newton is not None:
                runs[h].append(gauss_newton)
                continue
            runs[h].append(optimal_payout(problem, horizon, max_iter=300, hessian=h))
    best = {h: min(r, key=lambda x: x.stats["ipopt_timing_s"]["t_proc_total"]) for h, r in runs.items()}
    e, g = best["exact"], best["gauss-newton"]
    cpu = {h: [r.stats["ipopt_timing_s"]["t_proc_total"] for r in rs] for h, rs in runs.items()}
    return dict(node_ocp_exact_ipopt_proc_s=min(cpu["exact"]), node_ocp_gn_ipopt_proc_s=min(cpu["gauss-newton"]),
                node_ocp_exact_iterations=e.stats["iterations"], node_ocp_gn_iterations=g.stats["iterations"],
                node_ocp_hessian_speedup=min(cpu["exact"]) / min(cpu["gauss-newton"]),
                node_ocp_gn_vs_exact_objective_rel=abs(g.objective - e.objective) / abs(e.objective),
                node_ocp_gn_vs_exact_control_max=float(np.max(np.abs(g.acceleration[:-1] - e.acceleration[:-1]))),
                node_ocp_hessians={h: {"ipopt_proc_s": cpu[h], "status": best[h].status,
                                       "hessian_proc_s": best[h].stats["ipopt_timing_s"].get("t_proc_nlp_hess_l"),
                                       "jacobian_proc_s": best[h].stats["ipopt_timing_s"].get("t_proc_nlp_jac_g")}
                                   for h in runs},
                node_ocp_hessian_note=(f"the same NLP, IPOPT tol 1e-8; interleaved exact, gauss-newton x {rounds} "
                                       "in one run; ipopt_proc_s per round, speedup from the least of each")
                if gauss_newton is None else
                "the same NLP, IPOPT tol 1e-8; exact solved here, gauss-newton the node row's own solve of the same "
                "NLP earlier in the run (--quick: not interleaved); ipopt_proc_s per round")


def node_plant_mpc(scene, limits, quick: bool, segments: int = 4) -> dict:
    """The Gauss-Newton MPC (Wang's 2-DOF controller) in closed loop on the node-model plant of ``segments`` elements
    (CVODES), against the uncompensated node plant."""
    duration, horizon = (30.0, 10.0) if quick else (120.0, 20.0)
    cmp = compare_compensation(scene.with_numerics(duration=duration + horizon), limits, duration=duration,
                               horizon=horizon, dt=0.5, strategies=("none", "mpc"), plant_model="segmented",
                               plant_elements=segments)
    m = cmp.metrics["mpc"]
    return dict(node_plant_mpc_heave_reduction_db=m["heave_reduction_db"],
                node_plant_mpc_step_ms=1e3 * m["compute_per_step_s"],
                node_plant_mpc_realtime_factor=m["realtime_factor"], node_plant_mpc_success=cmp.success,
                node_plant_mpc_message=cmp.message, node_plant_mpc_segments=segments,
                node_plant_mpc_closed_loop_s=duration, node_plant_mpc_horizon_s=horizon,
                node_plant_mpc_models={"plant": cmp.stats["plant_model"], "controller": cmp.stats["controller_model"],
                                       "plant_reason": cmp.stats["plant_model_reason"],
                                       "controller_reason": cmp.stats["controller_model_reason"]},
                node_plant_mpc_metrics=cmp.metrics)


def node_design_gradient(scene, quick: bool, segments: int = 4) -> dict:
    """The time-domain design's Jacobian on the node model (one seed) against Richardson central differences
    (``time_domain_design.gradient_check``: relative to each row's largest entry) at z = (0.3, 0.5), and its cost
    over one evaluation of (f, g) (the least of 5 wall times each; ``--quick``: one)."""
    from time_domain_design import gradient_check
    from cablesys.control.design import time_design_problem
    problem = time_design_problem(scene.with_numerics(drag_segments=1), seeds=(1,), duration=70.0 if quick else 600.0,
                                  model="segmented", segments=segments)
    check = gradient_check(problem, np.array([0.3, 0.5]), repeats=1 if quick else 5)
    return dict(node_design_gradient_cost_ratio=check["cost_ratio"], node_design_gradient_fd_rel_err=check["rel_err"],
                node_design_gradient={**check, "model": problem.describe(), "record_s": problem.duration,
                                      "rk4_steps_per_interval": problem.heave.substeps})


def node_ocp(scene, limits, horizon: float, segments: int = 4, rounds: int = 2) -> dict:
    """The open-loop optimum over ``horizon`` s on the segmented node model (``segments`` elements, dt = 0.5 s,
    the RK4 steps per interval from the stiffest mode at rest) and on Wang's 2-DOF winch over the same record,
    in this order in one run: solve wall time (IPOPT with its derivative set-up), IPOPT's own CPU and wall
    times and their split, iterations, status, heave reduction against each model's uncompensated run (dB),
    the kernels' set-up (a cold cache: code generation and compile) and the load averages around the runs."""
    sc = scene.with_numerics(drag_segments=1, duration=horizon)
    load0 = os.getloadavg()[0]
    out = {}
    for name, kw in (("node", dict(model="segmented", segments=segments)), ("wang", dict(model="wang"))):
        pr = heave_problem(sc, limits, dt=0.5, **kw)
        t0 = time.perf_counter()
        compiled = pr.nlp_functions()[2]             # builds (or loads) the kernels of this structure
        setup_s = time.perf_counter() - t0
        res = optimal_payout(pr, horizon, max_iter=300)
        if name == "node":
            gn_result = res
        timing = res.stats["ipopt_timing_s"]
        out[name] = dict(wall_s=res.stats["solve_s"], iterations=res.stats["iterations"], status=res.status,
                         heave_reduction_db=res.heave_reduction_db, rk4_steps_per_interval=pr.substeps,
                         fastest_mode_rad_s=fastest_mode(pr.model, pr.x_rest, pr.p, pr.c), nx=pr.model.nx,
                         ipopt_proc_s=timing.get("t_proc_total"), ipopt_wall_s=timing.get("t_wall_total"),
                         hessian_share_proc=timing.get("t_proc_nlp_hess_l", 0.0) / timing["t_proc_total"],
                         ipopt_timing_s=timing, kernels_compiled=compiled, kernels_setup_s=setup_s)
    n, w = out["node"], out["wang"]
    # one round (--quick): the node row's optimum above is the Gauss-Newton round (the same NLP), not solved twice
    hessians = node_hessians(heave_problem(sc, limits, dt=0.5, model="segmented", segments=segments), horizon, rounds,
                             gauss_newton=gn_result if rounds == 1 else None)
    return dict(**hessians, node_ocp_wall_s=n["wall_s"], node_ocp_iterations=n["iterations"], node_ocp_status=n["status"],
                node_ocp_heave_reduction_db=n["heave_reduction_db"],
                node_ocp_rk4_steps_per_interval=n["rk4_steps_per_interval"],
                node_ocp_wang_wall_s=w["wall_s"], node_ocp_wang_heave_reduction_db=w["heave_reduction_db"],
                node_ocp_wall_ratio_vs_wang=n["wall_s"] / w["wall_s"],
                node_ocp_ipopt_proc_ratio_vs_wang=n["ipopt_proc_s"] / w["ipopt_proc_s"],
                node_ocp_heave_db_vs_wang=n["heave_reduction_db"] - w["heave_reduction_db"],
                node_ocp_horizon_s=horizon, node_ocp_segments=segments,
                node_ocp_load_average_1min=[load0, os.getloadavg()[0]], node_ocp=out,
                node_ocp_note="node: the segmented node model's winch (cablesys.model.segmented_winch_control), "
                              "wang: Wang's 2-DOF winch, the same scene, limits, dt = 0.5 s and record; wall_s: "
                              "optimal_payout's solve (IPOPT and its derivative set-up), ipopt_*: IPOPT's own "
                              "timer; ratios node over wang in this run")


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv, extra=lambda ap: ap.add_argument(
        "--only", choices=("node",), help="run one row alone: node, the node-model OCP and its Wang reference"))
    quick = args.quick
    scene = load_scene(example_path("rov-lift"))
    limits = WinchLimits(speed=1.0, acceleration=1.0)
    node_horizon = 4.0 if quick else 60.0
    if args.only == "node":
        doc = {"quick": quick, "scene": scene.name, **node_ocp(scene, limits, node_horizon, rounds=1 if quick else 2),
               "cpu_count": os.cpu_count()}
        write_json(args.out / "bench_control.json", doc)
        print({k: v for k, v in doc.items() if k.startswith("node_ocp_") and not isinstance(v, (dict, str))})
        return 0
    record = 60.0 if quick else 600.0
    ctrl = scene.with_numerics(drag_segments=1, duration=record)
    doc: dict = {"quick": quick, "scene": scene.name, "record_s": record, "limits": {"speed_m_s": 1.0,
                                                                                     "acceleration_m_s2": 1.0}}

    problem = heave_problem(ctrl, limits, dt=0.5, model="wang")
    t0 = time.perf_counter()
    kernels = interval_kernels(problem.interval)       # compiled once per structure (a cold cache: the build)
    doc.update(kernels_compiled=bool(kernels is not None and kernels.compiled),
               kernels_cached=bool(kernels is not None and kernels.cached),
               kernels_build_s=None if kernels is None else kernels.build_s,
               kernels_setup_s=time.perf_counter() - t0,
               kernels_note="per-interval step/stage kernels and their (x, u) derivatives, one library per "
                            "structure (cablesys.control.kernels.interval_kernels); build_s is the code generation and "
                            "compile time when not cached")
    ocp = optimal_payout(problem, record, max_iter=300)
    if doc["kernels_compiled"]:     # the same NLP in CasADi's virtual machine (inlined SX, full AD): an independent route
        with _compile_off():
            vm = optimal_payout(problem, record, max_iter=300)
        doc.update(ocp_objective=ocp.objective, ocp_vm_objective=vm.objective,
                   ocp_vm_objective_rel_diff=abs(ocp.objective - vm.objective) / abs(vm.objective),
                   ocp_vm_iterations=vm.stats["iterations"], ocp_vm_wall_s=vm.stats["solve_s"],
                   ocp_vm_ipopt_proc_s=vm.stats["ipopt_timing_s"].get("t_proc_total"),
                   ocp_speedup_ipopt_proc=vm.stats["ipopt_timing_s"].get("t_proc_total")
                   / ocp.stats["ipopt_timing_s"].get("t_proc_total"))
    doc.update(ocp_wall_s=ocp.stats["solve_s"], ocp_iterations=ocp.stats["iterations"], ocp_status=ocp.status,
               ocp_hessian=ocp.stats["hessian"],
               ocp_heave_reduction_db=ocp.heave_reduction_db, ocp_intervals=ocp.stats["intervals"],
               ocp_heave_rms_m=ocp.heave_rms_m, ocp_uncompensated_heave_rms_m=ocp.uncompensated_heave_rms_m,
               ocp_target="600 s record, 2-DOF model: at most 10 s of IPOPT wall time",
               ocp_ipopt_timing_s=ocp.stats["ipopt_timing_s"],
               ocp_ipopt_proc_s=ocp.stats["ipopt_timing_s"].get("t_proc_total"),
               ocp_ipopt_wall_s=ocp.stats["ipopt_timing_s"].get("t_wall_total"),
               load_average_1min=os.getloadavg()[0], cpu_count=os.cpu_count())
    check = resimulate(problem, ocp, per_interval=4)
    doc["resimulated_constraint_violation_rel"] = check["max_relative_violation"]
    doc["resimulated"] = check

    doc.update(closed_loop_mpc(scene, limits, quick))

    grad = design_gradient(problem, 30.0 if quick else 120.0)
    doc.update(gradient_fd_rel_err=grad["rel_err"], design_gradient_cost_ratio=grad["cost_ratio"],
               design_gradient=grad,
               design_gradient_note="forward sensitivities (2 directions) of the RK4 roll-out of the uncompensated run, "
                                    "parameters (AE, C_I) at AE = 2e5 N; objective mean square body heave; the largest "
                                    "error and cost ratio of the 2-DOF and the segmented (4 elements) model "
                                    "(cablesys.control.gradient); the design built on it: cablesys.control.design")
    doc.update(node_ocp(scene, limits, node_horizon, rounds=1 if quick else 2))
    doc.update(node_plant_mpc(scene, limits, quick))
    doc.update(node_design_gradient(scene, quick))
    doc["lq_rel_err"] = lq_error()
    write_json(args.out / "bench_control.json", doc)
    print({k: doc[k] for k in ("ocp_wall_s", "ocp_iterations", "ocp_status", "ocp_heave_reduction_db",
                               "mpc_heave_reduction_db", "pi_heave_reduction_db", "mpc_step_ms", "mpc_realtime_factor",
                               "mpc_no_preview_heave_reduction_db", "mpc_ipopt_heave_reduction_db", "mpc_speedup_vs_ipopt",
                               "design_gradient_cost_ratio", "lq_rel_err", "gradient_fd_rel_err",
                               "resimulated_constraint_violation_rel", "node_ocp_wall_s", "node_ocp_iterations",
                               "node_ocp_status", "node_ocp_heave_reduction_db", "node_ocp_rk4_steps_per_interval",
                               "node_ocp_wall_ratio_vs_wang", "node_ocp_exact_ipopt_proc_s", "node_ocp_gn_ipopt_proc_s",
                               "node_ocp_hessian_speedup", "node_plant_mpc_heave_reduction_db",
                               "node_plant_mpc_realtime_factor", "node_design_gradient_cost_ratio",
                               "node_design_gradient_fd_rel_err")})
    return 0


if __name__ == "__main__":
    sys.exit(main())
