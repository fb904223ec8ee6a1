"""Design of the ROV lift's line (AE, C_I) through the nonlinear time domain, against the frequency-domain design.

The ROV lift example (:mod:`cablesys.data` rov_lift.toml: its [design] bounds, [limits] and JONSWAP sea
Hs 2.5 m, Tp 10 s at the crane tip): :func:`cablesys.control.design.time_domain_design` minimizes the body
heave variance (mean over the seeds) with no slack, the peak tension under the working load, the body
excursion limit (each in every seed, by KS envelopes) and the static strain limit, on the model the ladder
chooses for the scene (as ``cablesys control --design`` does: the quasi-static cable of N = 4 elements, for
which the control runs the node model at that N) rolled out by RK4 (dt 0.5 s, the steps per interval from the
stiffest design in the bounds). Compared with the frequency-domain design of the same [design] table
(:func:`cablesys.isolation.design`, equivalent-linear RAOs), the latter evaluated by the same roll-out; both
re-run by the plain time domain (:func:`cablesys.time_domain.simulate`, the same model) in every seed: the
largest relative constraint violation and the agreement of the roll-out's constraint values with the re-run's.
Also the design gradient (forward sensitivities) against Richardson central differences at the optimum, and the
cost of one gradient over one evaluation (same run). Full mode also designs on Wang's 2-DOF model (the model of
the design before the ladder's, ``wang``): where the two models' optima differ.

A chain (both modes): the dual-isolation example (150 m rope, damper plate, 50 m soft insert, 300 kg package),
both ropes' AE and C_I and the plate's mass designed through the time domain and in the frequency domain
(:func:`dual_case`; ``time_domain_design_dual.png``).

A second case (full mode only), a sea in which the realised extremes come near their limits: the same lift in
Hs 7 m with a stiffer insert (strain_limit 0.03), seeds 1, 2, 300 s, one drag segment, on the same model. The
realised body excursion and least tension are constraints of the time-domain design only: the frequency-domain
design cannot state them as realised extremes, so its design is judged by the roll-out and re-run here (on Wang's
model the excursion was the active limit, which the frequency design exceeded; the JSON says whether the ladder's
model agrees).

Full: 600 s records, seeds 1, 2, 3, the scene's 10 drag segments. ``--quick``: 90 s, seeds 1, 2, one drag
segment, on Wang's 2-DOF model in place of the ladder's (a quick run in CasADi's virtual machine, where the node
model's sensitivities cost a minute; the JSON's ``model_why`` says so; tests/test_time_design.py designs on the
node model itself). Writes time_domain_design.json and time_domain_design.png.

Usage: python studies/time_domain_design.py --out DIR [--quick]
"""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, write_json

from cablesys.control import resolve_model
from cablesys.control.design import (design_functions, design_kernels, evaluate_design, resimulate_design,
                                     time_design_problem, time_domain_design)
from cablesys.control.design_figure import plot_time_design
from cablesys.examples import example_path
from cablesys.isolation import design as frequency_design, settings_from_dict
from cablesys.scene import load_scene


def gradient_check(problem, z, repeats: int = 5) -> dict:
    """The NLP's Jacobian (forward sensitivities) at z against Richardson central differences of (f, g)
    at the relative steps 1e-4 and 1e-5 of z (the better per entry), each error relative to the largest
    entry of its row (at an optimum a gradient entry is ~0: its own size is no scale), and the cost of the Jacobian over one evaluation of (f, g): least of ``repeats`` wall times each (after one call)."""
    fns = design_functions(problem)
    z = np.asarray(z, float)
    jf, jg = (np.array(v) for v in fns.jac(z))
    J = np.vstack([jf, jg])
    val = lambda zz: np.concatenate([np.array(v).ravel() for v in fns.fg(zz)])
    errs = []
    for rel in (1e-4, 1e-5):
        fd = np.zeros_like(J)
        for i in range(z.size):
            d = np.zeros(z.size)
            d[i] = rel * max(abs(z[i]), 0.05)
            D = lambda s: (val(z + s * d) - val(z - s * d)) / (2 * s * d[i])
            fd[:, i] = (4 * D(0.5) - D(1.0)) / 3
        scale = np.max(np.abs(J), axis=1, keepdims=True)
        errs.append(np.abs(fd - J) / scale)
    err = np.minimum(*errs)

    def timed(f, n=repeats):
        f(z)
        best = math.inf
        for _ in range(n):
            t0 = time.perf_counter()
            f(z)
            best = min(best, time.perf_counter() - t0)
        return best
    t_f, t_j = timed(fns.fg), timed(fns.jac)
    return {"rel_err": float(np.max(err)), "rel_err_per_row": np.max(err, axis=1).tolist(), "rows": ["objective", *fns.rows],
            "evaluation_s": t_f, "jacobian_s": t_j, "cost_ratio": t_j / t_f}


def agreement(rollout: dict, rerun: dict, seeds) -> float:
    """Largest |roll-out KS value - re-run sampled extreme| over the seeds and constraints, in the constraints'
    normalized units (peak / working load, least / mean tension, excursion / limit)."""
    out = 0.0
    for s in seeds:
        for name, (v, b) in rerun["per_seed"][s]["constraints"].items():
            out = max(out, abs(rollout[f"{name} (seed {s})"][0] - v))
    return out


def harsh_case(scene, model: dict) -> dict:
    """Both designs of the Hs 7 m, strain_limit 0.03 variant (module docstring) on the design's ``model``
    (``time_design_problem``'s model and segments), each evaluated by the roll-out and re-run by the plain time
    domain."""
    import dataclasses
    sea = dataclasses.replace(scene.top_motion.spectrum, hs=7.0)
    sc = scene.with_numerics(drag_segments=1).replace(top_motion=dataclasses.replace(scene.top_motion, spectrum=sea),
                                                      design={**scene.design, "strain_limit": [0.03]})
    problem = time_design_problem(sc, seeds=(1, 2), duration=300.0, dt=0.5, **model)
    res = time_domain_design(problem)
    fd = frequency_design(sc, settings_from_dict(sc.design))
    theta_f = [float(v) for v in fd.values]
    fd_td = evaluate_design(problem, theta_f)
    return {"hs_m": 7.0, "strain_limit": 0.03, "seeds": [1, 2], "record_s": 300.0, "model": problem.describe(),
            "time_domain": res.summary(),
            "frequency_domain": {"ae_n": theta_f[0], "internal_damping_n_s": theta_f[1], "active": list(fd.active),
                                 "in_the_time_domain": fd_td},
            "resimulated": {"design": resimulate_design(problem, res.theta),
                            "frequency_design": resimulate_design(problem, theta_f)}}


def dual_case(quick: bool, out) -> dict:
    """The dual-isolation example (a chain: 150 m rope, damper plate, 50 m soft insert, package; Wang 1971 p. 33):
    both ropes' AE and C_I and the plate's mass designed through the time domain and in the frequency domain (the
    same [design] table), each judged by the roll-out and re-run by the plain time domain; the design gradient in
    all five variables against central differences. Quick: 80 s (a 20 s window after the 60 s start-up), seed 1, one
    drag segment; full: 600 s, seeds 1, 2, 3, the scene's drag segments. Writes time_domain_design_dual.png."""
    scene = load_scene(example_path("dual-isolation"))
    seeds, record = ((1,), 80.0) if quick else ((1, 2, 3), 600.0)
    if quick:
        scene = scene.with_numerics(drag_segments=1)
    problem = time_design_problem(scene, seeds=seeds, duration=record, dt=0.5)
    res = time_domain_design(problem)
    fd = frequency_design(scene, settings_from_dict(scene.design))
    theta_f = [float(v) for v in fd.values]
    fd_td = evaluate_design(problem, theta_f)
    rerun, rerun_f = resimulate_design(problem, res.theta), resimulate_design(problem, theta_f)
    active = lambda c: [k for k, (v, b) in c.items() if v > b - 1e-4 * max(abs(b), 1e-3)]
    plot_time_design(res, out / "time_domain_design_dual.png", frequency_theta=theta_f,
                     title=f"{scene.name}: designed through the nonlinear time domain ({record:g} s, seeds {seeds})")
    return {"scene": scene.name, "record_s": record, "seeds": list(seeds), "model": problem.describe(),
            "model_why": problem.model_reason, "variables": list(problem.names),
            "time_domain": res.summary(), "time_domain_active": active(res.constraints),
            "frequency_domain": {"success": bool(fd.success), "design": dict(zip(problem.names, theta_f)),
                                 "active": list(fd.active), "in_the_time_domain": fd_td,
                                 "active_in_the_time_domain": active(fd_td["constraints"])},
            "frequency_over_time_heave_variance": fd_td["objective_heave_variance_m2"] / res.objective,
            "resimulated": {"design": rerun, "frequency_design": rerun_f},
            "resimulated_constraint_violation_rel": rerun["max_relative_violation"],
            "rollout_vs_rerun_heave_variance_rel": abs(res.objective - rerun["heave_variance_m2"]) / rerun["heave_variance_m2"],
            "design_gradient": gradient_check(problem, problem.z(res.theta))}


def wang_case(scene, seeds, record: float, res) -> dict:
    """The same design on Wang's 2-DOF model (the straight cable, one uniform stretch: the model of the design
    before the ladder's), and the ladder's optimum ``res`` evaluated by Wang's roll-out: where the models differ."""
    problem = time_design_problem(scene, seeds=seeds, duration=record, dt=0.5, model="wang")
    wang = time_domain_design(problem)
    return {"model": problem.describe(), "time_domain": wang.summary(),
            "ae_ratio_ladder_over_wang": res.theta[0] / wang.theta[0],
            "damping_ratio_ladder_over_wang": res.theta[1] / wang.theta[1],
            "ladder_design_in_wang_rollout": evaluate_design(problem, res.theta),
            "resimulated": resimulate_design(problem, wang.theta)}


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    quick = args.quick
    scene = load_scene(example_path("rov-lift"))
    if quick:
        scene = scene.with_numerics(drag_segments=1)
    seeds, record = ((1, 2), 90.0) if quick else ((1, 2, 3), 600.0)
    # the ladder's model for the scene with the record's duration, as time_design_problem's default and
    # cablesys control --design take it
    choice = resolve_model(scene.with_numerics(duration=record))
    model, why = {"model": choice}, choice.reason
    if quick:             # the quick run (the test's, in CasADi's virtual machine) on Wang's model
        model, why = {"model": "wang"}, f"quick: Wang's 2-DOF model in place of the ladder's ({why})"
    load0 = os.getloadavg()[0]
    t0 = time.perf_counter()
    problem = time_design_problem(scene, seeds=seeds, duration=record, dt=0.5, **model)
    compiled = design_kernels(problem)[2]
    setup_s = time.perf_counter() - t0
    res = time_domain_design(problem)
    fd = frequency_design(scene, settings_from_dict(scene.design))
    theta_f = [float(v) for v in fd.values]
    fd_td = evaluate_design(problem, theta_f)
    rerun = resimulate_design(problem, res.theta)
    rerun_f = resimulate_design(problem, theta_f)
    grad = gradient_check(problem, problem.z(res.theta))
    active_t = [k for k, (v, b) in res.constraints.items() if v > b - 1e-4 * max(abs(b), 1e-3)]
    doc = {"quick": quick, "scene": scene.name, "record_s": record, "seeds": list(seeds), "dt_s": problem.dt,
           "model": problem.describe(), "model_why": why,
           "rk4_steps_per_interval": problem.heave.substeps,
           "drag_segments": scene.numerics.drag_segments, "kernels_compiled": compiled, "setup_s": setup_s,
           "time_domain": res.summary(), "time_domain_active": active_t,
           "frequency_domain": {"success": bool(fd.success), "ae_n": theta_f[0], "internal_damping_n_s": theta_f[1],
                                "objective": float(fd.objective), "objective_kind": fd.objective_kind,
                                "active": list(fd.active), "in_the_time_domain": fd_td},
           "resimulated": {"design": rerun, "frequency_design": rerun_f},
           "resimulated_constraint_violation_rel": rerun["max_relative_violation"],
           "rollout_vs_rerun_constraint_diff_rel": agreement(res.constraints, rerun, seeds),
           "rollout_vs_rerun_heave_variance_rel": abs(res.objective - rerun["heave_variance_m2"]) / rerun["heave_variance_m2"],
           "design_gradient": grad, "design_gradient_fd_rel_err": grad["rel_err"],
           "design_gradient_cost_ratio": grad["cost_ratio"],
           "ipopt_iterations": res.stats["iterations"], "ipopt_solve_s": res.stats["solve_s"],
           "frequency_over_time_heave_variance": fd_td["objective_heave_variance_m2"] / res.objective,
           "ae_ratio_time_over_frequency": res.theta[0] / theta_f[0],
           "damping_ratio_time_over_frequency": res.theta[1] / theta_f[1]}
    doc["dual"] = dual_case(quick, args.out)
    if not quick:
        doc["harsh"] = harsh_case(scene, model)
        doc["wang"] = wang_case(scene, seeds, record, res)
    # the wall times (setup_s, ipopt_solve_s, the gradient's cost ratio) are as loaded as the machine was
    doc["load_average_1min"] = [load0, os.getloadavg()[0]]
    write_json(args.out / "time_domain_design.json", doc)
    plot_time_design(res, args.out / "time_domain_design.png", frequency_theta=theta_f,
                     title=f"{scene.name}: line designed through the nonlinear time domain ({record:g} s, seeds {seeds})")
    keys = ("resimulated_constraint_violation_rel", "rollout_vs_rerun_constraint_diff_rel",
            "rollout_vs_rerun_heave_variance_rel", "design_gradient_fd_rel_err", "design_gradient_cost_ratio",
            "ipopt_iterations", "ipopt_solve_s", "frequency_over_time_heave_variance", "ae_ratio_time_over_frequency",
            "damping_ratio_time_over_frequency", "time_domain_active")
    print({k: doc[k] for k in keys})
    print({k: doc["time_domain"][k] for k in ("ae_n", "internal_damping_n_s", "heave_std_m", "baseline_heave_std_m", "success")})
    print({k: doc["frequency_domain"][k] for k in ("ae_n", "internal_damping_n_s", "active")})
    return 0 if res.success else 1


if __name__ == "__main__":
    sys.exit(main())
