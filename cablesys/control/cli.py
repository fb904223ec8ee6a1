"""The ``cablesys control`` sub-command: heave compensation by the winch for a scene."""

from __future__ import annotations

import math
import sys

from ..errors import ParameterError
from .model_choice import CHOICES, ladder_note, resolve_model


def register(sub) -> None:
    """Add ``control SCENE.toml [--out DIR]`` to the cablesys parser."""
    p = sub.add_parser("control", help="optimal and MPC heave compensation by the winch (IPOPT)",
                       description="Compare no compensation, a passive compensator, a PI/feed-forward AHC, MPC "
                                   "with a wave preview and the open-loop optimal payout, every one on the same "
                                   "nonlinear winch model of the scene (the plant: the model ladder's choice, Wang's "
                                   "2-DOF cable or the segmented node model with a variable length; the controller: "
                                   "Wang's or a coarser node model), under winch speed, "
                                   "acceleration and power limits and the tension band. Writes control.json, "
                                   "control_heave_tension.png and control_winch.png. With --design instead: the "
                                   "time-domain design of the line's AE and C_I (each section's in a chain, and "
                                   "an intermediate body's mass: bounds from the scene's [design] "
                                   "table) that minimizes the body heave variance, mean over --seeds realisations "
                                   "of the sea, with no slack, peak tension <= working load and the body "
                                   "excursion limit in every seed (cablesys.control.design), on the same model as "
                                   "the plant (--model, --segments: the ladder's choice by default), compared with "
                                   "the frequency-domain design (cablesys design) and re-run by the plain time "
                                   "domain; writes time_design.json and time_design.png.")
    p.add_argument("scene", help="scene TOML file (one section; with --design also a chain of sections)")
    p.add_argument("--out", default="control_out", help="output directory (default: control_out)")
    p.add_argument("--duration", type=float, default=120.0, help="closed-loop run [s] (default 120)")
    p.add_argument("--horizon", type=float, default=20.0, help="MPC horizon and preview [s] (default 20)")
    p.add_argument("--dt", type=float, default=0.5, help="control interval [s] (default 0.5)")
    p.add_argument("--speed", type=float, default=1.0, help="payout speed limit [m/s] (default 1; inf: none)")
    p.add_argument("--acceleration", type=float, default=1.0, help="payout acceleration limit [m/s^2] (default 1)")
    p.add_argument("--power", type=float, default=math.inf, help="winch power limit [W] (default: none)")
    p.add_argument("--plant-segments", type=int, default=None,
                   help="drag segments of the plant's cable (default: the scene's numerics.drag_segments)")
    p.add_argument("--model", default="auto", choices=CHOICES,
                   help="the model every strategy plays on (the plant; with --design the design's model): Wang's "
                        "2-DOF winch, the segmented node model's winch (--segments N), or auto (default): the winch "
                        "form of the ladder's a priori choice for the scene (its [numerics] model; cablesys run "
                        "starts there and its a posteriori checks may grow N, which the control does not run), as the "
                        "Python API's model='auto'")
    p.add_argument("--segments", type=int, default=None,
                   help="elements N of a segmented plant (default: the ladder's N, else the scene's cable.segments; "
                        "with auto, in place of the ladder's N)")
    p.add_argument("--controller-model", default="wang", choices=("wang", "segmented"),
                   help="the MPC's and the open-loop optimum's model, not finer than the plant (default wang: the "
                        "model mismatch against a node-model plant)")
    p.add_argument("--controller-segments", type=int, default=None,
                   help="elements N of a segmented controller (at most the plant's)")
    p.add_argument("--strategies", default="none,passive,pi,mpc,mpc_no_preview,optimal",
                   help="comma-separated subset of none,passive,pi,mpc,mpc_no_preview,optimal "
                        "(mpc_no_preview: the top motion over the horizon predicted from its measured past)")
    p.add_argument("--mpc-scheme", default="gauss-newton", choices=("gauss-newton", "ipopt"),
                   help="how each MPC step solves its horizon: gauss-newton (real-time iteration, one QP per "
                        "step; default) or ipopt (the full NLP to convergence)")
    p.add_argument("--design", action="store_true",
                   help="design the line (AE, C_I per section, an intermediate body's mass) through the nonlinear "
                        "time domain instead of compensating")
    p.add_argument("--seeds", default="1,2,3", help="--design: comma-separated seeds of the sea (default 1,2,3)")
    p.add_argument("--design-dt", type=float, default=0.5,
                   help="--design: interval of the rolled-out series [s] (default 0.5; RK4 steps per interval from "
                        "the stiffest design in the bounds)")
    p.add_argument("--record", type=float, default=None,
                   help="--design: record length [s] (default: the scene's numerics.duration)")
    p.add_argument("--no-resimulate", action="store_true", help="--design: skip the plain time-domain re-run check")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.set_defaults(func=run)


def _seeds(text: str) -> tuple:
    try:
        seeds = tuple(int(s) for s in text.split(",") if s.strip())
    except ValueError:
        raise ParameterError("--seeds", text, "comma-separated integers >= 0") from None
    if not seeds:
        raise ParameterError("--seeds", text, "at least one seed")
    return seeds


def run_design(args) -> int:
    """``cablesys control SCENE --design``: the time-domain design against the frequency-domain one."""
    from ..isolation import design as frequency_design, settings_from_dict
    from ..outputs import OutputDir
    from ..scene import load_scene
    from .design import evaluate_design, resimulate_design, time_design_problem, time_domain_design
    from .design_problem import describe_theta
    from .design_figure import plot_time_design

    seeds = _seeds(args.seeds)
    scene = load_scene(args.scene)
    settings = {"seeds": seeds, "dt": args.design_dt, "record": args.record, "resimulate": not args.no_resimulate,
                "model": args.model, "segments": args.segments}
    problem = time_design_problem(scene, seeds=seeds, duration=args.record, dt=args.design_dt, model=args.model,
                                  segments=args.segments)
    outdir = OutputDir(args.out, "control", {"scene": scene, "time_design": settings},
                       overwrite=args.overwrite, owned=("time_design.json",))
    with outdir.start(scene=scene.name):
        res = time_domain_design(problem)
        doc = {"scene": scene.name, "settings": settings,
               "models": {"design": f"{problem.describe()}: the design's model ({problem.model_reason}), re-run by "
                                    "the plain time domain on the same model",
                          "design_choice": {k: v for k, v in problem.model_choice.as_dict().items() if k != "ladder"},
                          **ladder_note(scene, problem.model_choice)},
               "time_domain": res.summary()}
        fd = frequency_design(scene, settings_from_dict(scene.design))
        theta_f = [float(v) for v in fd.values]
        doc["frequency_domain"] = {"success": bool(fd.success), "design": dict(zip(problem.names, theta_f)),
                                   "described": describe_theta(problem.names, theta_f),
                                   "objective": float(fd.objective), "objective_kind": fd.objective_kind,
                                   "active": list(fd.active),
                                   "in_the_time_domain": evaluate_design(problem, theta_f)}
        if not args.no_resimulate:
            doc["resimulated"] = {"design": resimulate_design(problem, res.theta),
                                  "frequency_design": resimulate_design(problem, theta_f)}
        outdir.write_json("time_design.json", doc)
        with outdir.writing("time_design.png") as tmp:
            plot_time_design(res, tmp, frequency_theta=theta_f,
                             title=f"{scene.name}: line designed through the nonlinear time domain, seeds {seeds}")
        outdir.finish("success" if res.success else "failed", message=res.message)
    w = sys.stdout.write
    s = res.summary()
    w(f"{scene.name}\n{'' if res.success else 'WARNING: ' + res.message + chr(10)}")
    w(f"model: {doc['models']['design']}\n" + _ladder_line(doc["models"]))
    w(f"time-domain design:      {describe_theta(res.names, res.theta)}; heave std "
      f"{s['baseline_heave_std_m']:.3f} -> {s['heave_std_m']:.3f} m ({s['heave_reduction_db']:+.1f} dB), "
      f"mean over seeds {seeds}; {res.stats['iterations']} IPOPT iterations "
      f"over {res.stats.get('starts', 1)} start(s) in {res.stats['solve_s']:.1f} s\n")
    if len(res.names) > 2:
        w("  (AE_i, C_I,i: section i's AE and Voigt damping, top first; m_1: the intermediate body's heave mass, its "
          "weight and surge mass in proportion)\n")
    fdt = doc["frequency_domain"]["in_the_time_domain"]
    w(f"frequency-domain design: {describe_theta(res.names, theta_f)}; in the time domain heave std "
      f"{fdt['objective_heave_variance_m2'] ** 0.5:.3f} m\n")
    for row, (v, b) in res.constraints.items():
        fv = fdt["constraints"][row][0]
        w(f"  {row:<28s} design {v:+.4f}  frequency design {fv:+.4f}  (<= {b:+.4g})\n")
    w("  (peak_tension: the top tension's peak over the working load (peak_tension_2, ...: a chain's lower sections' "
      "tops); slack: minus the least floor tension over its mean, so <= -f keeps that least tension above f x the "
      "mean; excursion: the lowest body's largest heave or surge from its mean over the limit; static_strain "
      "(_2, ...): each section's static strain; peaks as smooth KS envelopes)\n")
    if "resimulated" in doc:
        w(f"re-run by the plain time domain: largest relative violation {doc['resimulated']['design']['max_relative_violation']:.3g} "
          f"(design), {doc['resimulated']['frequency_design']['max_relative_violation']:.3g} (frequency design)\n")
    w(f"wrote {outdir.path / 'time_design.json'}, time_design.png\n")
    return 0 if res.success else 1


def _ladder_line(models: dict) -> str:
    """The console's line on the ladder's own choice for the uncompensated scene, where it is not the model that ran
    (the model's line gives the ladder's reason otherwise; control.json keeps ``ladder`` always)."""
    return "" if models.get("ladder_agrees", False) else f"ladder: {models['ladder']}\n"


def _models(scene, res, choice) -> dict:
    """Which models ran and why, and what the model ladder runs for the uncompensated scene: the plant (Wang's 2-DOF
    winch, :mod:`cablesys.model.winch`, or the node model's, :mod:`cablesys.model.segmented_winch_control`) on which
    every strategy plays, its :class:`.model_choice.ModelChoice` ``choice``, and the controller (the MPC's and the
    open-loop optimum's model)."""
    st = res.stats
    out = {"controller": f"{st['controller_model']}, {st.get('controller_segments', 1)} drag segment(s), RK4 "
                         f"{st['controller_substeps']} steps per interval: the open-loop optimum's and the MPC's model, "
                         f"{st['controller_model_reason']}",
           "plant": f"{st['plant_model']}, {st.get('plant_segments')} drag segments, CVODES: the nonlinear plant of "
                    f"every strategy, the passive compensator's with its piston coordinate ({choice.reason})",
           "plant_choice": {k: v for k, v in choice.as_dict().items() if k != "ladder"},
           "same_plant": True}
    return {**out, **ladder_note(scene, choice)}


def run(args) -> int:
    if args.design:
        return run_design(args)
    from ..outputs import OutputDir
    from ..scene import load_scene
    from .limits import WinchLimits
    from .mpc import STRATEGIES, compare_compensation, plant_scene
    from .plots import plot_heave_tension, plot_winch

    strategies = tuple(s.strip() for s in args.strategies.split(",") if s.strip())
    bad = [s for s in strategies if s not in STRATEGIES]
    if bad:
        raise ParameterError("--strategies", bad, f"allowed: {', '.join(STRATEGIES)}")
    scene = load_scene(args.scene)
    limits = WinchLimits(speed=args.speed, acceleration=args.acceleration, power=args.power)
    settings = {"duration": args.duration, "horizon": args.horizon, "dt": args.dt, "speed": args.speed,
                "acceleration": args.acceleration, "power": args.power, "strategies": strategies,
                "plant_segments": args.plant_segments, "mpc_scheme": args.mpc_scheme, "model": args.model,
                "segments": args.segments, "controller_model": args.controller_model,
                "controller_segments": args.controller_segments}
    plant = resolve_model(plant_scene(scene, args.plant_segments), args.model, args.segments)   # before any work
    outdir = OutputDir(args.out, "control", {"scene": scene, "control": settings},
                       overwrite=args.overwrite, owned=("control.json",))
    with outdir.start(scene=scene.name):
        res = compare_compensation(scene, limits, duration=args.duration, horizon=args.horizon, dt=args.dt,
                                   plant_segments=args.plant_segments, strategies=strategies,
                                   mpc_scheme=args.mpc_scheme, plant_model=plant,
                                   controller_model=args.controller_model,
                                   controller_elements=args.controller_segments)
        models = _models(scene, res, plant)
        outdir.write_json("control.json", {"scene": scene.name, "settings": settings, "models": models,
                                           **res.summary()})
        title = f"{scene.name}: heave compensation, |w| <= {args.speed:g} m/s, |w'| <= {args.acceleration:g} m/s^2"
        for name, fn in (("control_heave_tension.png", plot_heave_tension), ("control_winch.png", plot_winch)):
            with outdir.writing(name) as tmp:
                fn(res, tmp, title=title)
        outdir.finish("success" if res.success else "failed", message=res.message)
    w = sys.stdout.write
    w(f"{scene.name}\n{'' if res.success else 'WARNING: ' + res.message + chr(10)}")
    w(f"controller: {models['controller']}\nplant: {models['plant']}\n" + _ladder_line(models))
    w(f"{'strategy':<14s} {'rms heave':>10s} {'dB':>7s} {'T top max':>10s} {'T min':>9s} {'slack':>6s} "
      f"{'|P| max':>9s} {'step':>9s}\n")
    for name, m in res.metrics.items():
        step = m.get("compute_per_step_s")
        w(f"{name:<14s} {m['heave_rms_m']:9.3f}m {m['heave_reduction_db']:7.1f} {m['tension_max_n'] / 1e3:8.1f}k "
          f" {m['tension_min_n'] / 1e3:8.1f}k {m['slack_time_s']:5.1f}s {m['power_max_w'] / 1e3:8.1f}k "
          f"{'' if step is None else f'{step * 1e3:7.1f}ms'}\n")
    w("rms heave: the body's heave from rest; dB: its rms against no compensation's; T top max: the peak tension at "
      "the sheave [kN]; T min: the least tension along the line [kN] (Wang's F_bc, the node model's least element "
      "tension), which the no-slack floor bounds; slack: time below that floor; |P| max: the winch's peak power [kW]; "
      "step: compute time per control step\n")
    w(f"wrote {outdir.path / 'control.json'}, control_heave_tension.png, control_winch.png\n")
    return 0 if res.success else 1
