"""The ``cablesys design`` sub-command: the isolation-design NLP for a scene with a ``[design]`` table."""

from __future__ import annotations

import json
import math
import sys


def register(sub) -> None:
    """Add ``design SCENE.toml [--out DIR]`` to the cablesys parser."""
    p = sub.add_parser("design", help="tune AE and C_I of each cable section (dual-isolation NLP, IPOPT)",
                       description="Minimize the lower body's vertical significant amplitude (or its band RAO) "
                                   "in the sea state of the scene's [design] table, over AE and C_I per section "
                                   "within the given bounds, with no-slack, working-load and static-strain "
                                   "constraints (Wang 1971 p. 33, dual isolation). Writes design.json.")
    p.add_argument("scene", help="scene TOML file with a [design] table (keys of cablesys.isolation.DesignSettings)")
    p.add_argument("--out", default="design_out", help="output directory (default: design_out)")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.add_argument("--write-scene", default=None, metavar="FILE",
                   help="write the scene with the designed values (AE, C_I, ...) in the design sea on the buoy orbit, "
                        "model as-built, to FILE: `cablesys run FILE` is the run whose heave the design predicts")
    p.add_argument("--check", action="store_true",
                   help="run the baseline and the designed scene in the time domain in the design's sea on the "
                        "design's buoy orbit (the design's own model, as built) and compare their body heave "
                        "significant amplitude and its ratio with the design's prediction, each with its stated "
                        "error (linearization spread, sampling error of the record): design.json time_domain_check")
    p.set_defaults(func=run)


def load(path) -> tuple:
    """(scene, settings) from a scene TOML file with a ``[design]`` table."""
    from ..errors import ParameterError
    from ..reader import located, read_toml
    from ..scene import scene_from_dict
    from .problem import settings_from_dict

    data, source = read_toml(path, "scene file")
    table = data.pop("design", None)
    if table is None:
        raise located(ParameterError("design", "missing", "the scene file needs a [design] table with ae_bounds "
                                     "and damping_bounds"), source)
    scene = scene_from_dict(data, source)
    sea = scene.top_motion.spectrum
    if sea is not None:          # the scene's sea is the design sea unless [design] names another
        table = dict(table)
        for key, value in (("hs", sea.hs), ("tp", sea.tp), ("gamma", sea.gamma if sea.kind == "jonswap" else 1.0)):
            table.setdefault(key, value)
    return scene, settings_from_dict(table, source)


_WHY = {
    "Maximum_Iterations_Exceeded": "hit the iteration limit (raise [design] max_iter, or loosen tol)",
    "Infeasible_Problem_Detected": "found no point meeting the constraints from this start",
    "Restoration_Failed": "lost feasibility and could not restore it (a start too far from the feasible set)",
    "Search_Direction_Becomes_Too_Small": "stalled: the objective is flat along the bounds",
    "Invalid_Number_Detected": "met a non-finite objective or constraint (AE at or below the reference tension?)",
    "Error_In_Step_Computation": "could not compute a step (ill-conditioned near a bound)",
}


def failed_starts(result) -> list[dict]:
    """The IPOPT solves that did not converge: start, outer pass, status and why."""
    from .solve import OK_STATUS
    out = []
    for k, r in enumerate(result.runs):
        if r["status"] not in OK_STATUS:
            out.append({"solve": k + 1, "outer": r["outer"], "status": r["status"], "iterations": r["iterations"],
                        "objective": r["objective"], "max_violation": r["max_violation"],
                        "why": _WHY.get(r["status"], "IPOPT did not converge")})
    return out


def write_figures(scene, settings, result, outdir) -> list[str]:
    """design_rao.png (before/after), design_objective.png, design_margins.png."""
    from ..model import build_model
    from .plots import (
        plot_constraint_margins,
        plot_objective_history,
        plot_rao_before_after,
    )
    model = build_model(scene)
    written = []
    for name, fn in (("design_rao.png", lambda f: plot_rao_before_after(
                          model, model.parameters(scene), result.parameters, settings, f,
                          title=f"{scene.name}: RAOs before and after the design")),
                     ("design_objective.png", lambda f: plot_objective_history(result, f)),
                     ("design_margins.png", lambda f: plot_constraint_margins(result, f))):
        with outdir.writing(name) as tmp:
            fn(tmp)
        written.append(name)
    return written


def designed_scene(scene, settings, result):
    """``scene`` with the design's values: each variable's value times its factor at each of its parameter labels."""
    from ..model.design_variables import designed_scene as with_values
    from .problem import variables
    return with_values(scene, variables(scene, settings), result.values)


def baseline(scene, settings) -> float:
    """The design objective's significant amplitude 2 sigma of the lowest body's heave (m) at the scene's own values:
    the Gaussian equivalent linearization in the design sea (:func:`.solve.equivalent_jacobian_shift`)."""
    from ..model import build_model
    from .solve import equivalent_jacobian_shift
    model = build_model(scene)
    _, st = equivalent_jacobian_shift(model, model.parameters(scene), settings)
    return float(st.significant_amplitude(model.label("y_b", model.n_sections - 1)))


def check_lines(c: dict) -> str:
    """The console report of ``--check``: prediction +- its linearization error, the time domain +- its
    sampling error, and whether they agree, for each scene and for the ratio."""
    def pm(value, rel):
        return f"{value:.4g} +- {value * rel:.2g}"
    lines = [f"time-domain check ({c['designed']['model']}, the design sea on the buoy orbit, window {c['designed']['window_s'][0]:.0f}-"
             f"{c['designed']['window_s'][1]:.0f} s; predicted +- linearization error, time domain +- sampling error; "
             "allowed: both plus the realised sea's offset):"]
    for name, key in (("baseline", "baseline"), ("designed", "designed"), ("ratio designed/baseline", "ratio")):
        e = c[key]
        unit = " m" if key != "ratio" else ""
        pred, td = (e["predicted_m"], e["time_domain_m"]) if key != "ratio" else (e["predicted"], e["time_domain"])
        verdict = "agree" if e["agree"] else "DISAGREE"
        lines.append(f"  {name + (' heave 2 sigma' if key != 'ratio' else ''):<30s} predicted {pm(pred, e['linearization_error_rel'])}{unit}, "
                     f"time domain {pm(td, e['sampling_error_rel'])}{unit}: differ by {100 * e['difference_rel']:+.1f} %, "
                     f"allowed {100 * e['allowed_rel']:.1f} %: {verdict}")
    return "\n".join(lines) + "\n"


def infeasible_doc(scene, err, before: float) -> dict:
    """design.json of an infeasible design: the violated constraint, the best point and its margins."""
    return {"scene": scene.name, "success": False, "status": "infeasible", "message": str(err),
            "violated_constraint": err.constraint, "violation": err.violation, "best_point": err.best,
            "constraint_margins": err.margins,
            "baseline": {"significant_heave_m": before, "what": "the scene's own values, the same equivalent "
                         "linearization in the same sea"}}


def infeasible_lines(scene, err, before: float, path) -> str:
    """The console report of an infeasible design (the best point, every margin, the culprit)."""
    lines = [f"{scene.name}\nINFEASIBLE: constraint '{err.constraint}' violated by {err.violation:.3g} "
             "(normalized; 0 = just met)",
             f"body heave significant amplitude, baseline (the scene's values): {before:.4g} m",
             "best point found:"]
    lines += [f"  {name:<20s} {v:12.5g}" for name, v in err.best.items()]
    lines += ["constraint margins there (>= 0 met): " + ", ".join(f"{k} {v:+.3g}" for k, v in err.margins.items()),
              f"wrote {path}"]
    return "\n".join(lines) + "\n"


WRITTEN_HEADER = ("# written by `cablesys design --write-scene`: the scene with the designed values, in the design sea on\n"
                  "# the design's buoy orbit (the scene's own top motion replaced), run by the design's own model\n"
                  "# (model = \"as-built\"): `cablesys run` of this file is the time-domain run whose body heave the\n"
                  "# design predicts (design.json significant_y_b_stochastic_m, and --check's designed run)\n")


def design_model(scene) -> dict:
    """design.json's ``model``: the model the design linearizes (the scene's own, as built: Wang's section chain, or
    the node model where the scene's sections have elements) with the model ladder's estimate of that model's error
    for the scene's time domain, and what the ladder would run instead (every result says which model ran, why,
    and its error)."""
    from ..ladder.choice import choose, forced
    from ..ladder.rungs import RungCache
    n = max(s.cable.segments for s in scene.sections)
    rung = "wang" if n == 1 else "segmented"
    cache = RungCache()
    own, auto = forced(scene, rung, segments=None if n == 1 else n, cache=cache), choose(scene, cache=cache)
    d = own.as_dict()
    d["reason"] = ("the design optimizes the equivalent linearization of the scene's own model, as built "
                   f"({'Wang' + chr(39) + 's section chain' if n == 1 else f'the node model, N = {n} per section'}); "
                   f"the model ladder would run {auto.name}" + (f" N = {auto.segments}" if auto.segments > 1 else "")
                   + " for this scene's time domain")
    return d


def run(args) -> int:
    from ..outputs import OutputDir
    from .solve import DesignInfeasible, design

    scene, settings = load(args.scene)
    # --out checked before any work; summary.json says running / success / failed / interrupted
    outdir = OutputDir(args.out, "design", {"scene": scene, "design": settings},
                       overwrite=getattr(args, "overwrite", False), owned=("design.json",))
    with outdir.start(scene=scene.name):
        before = baseline(scene, settings)
        try:
            result = design(scene, settings)
        except DesignInfeasible as err:
            # a failed computation (exit 1): the best point found and the violated constraint are kept
            outdir.write_text("design.json", json.dumps(infeasible_doc(scene, err, before), indent=2, default=float) + "\n")
            outdir.finish("failed", message=str(err))
            sys.stdout.write(infeasible_lines(scene, err, before, outdir.path / "design.json"))
            return 1
        out = outdir.path
        failed = failed_starts(result)
        doc = {"scene": scene.name, **result.to_dict(), "failed_starts": failed,
               "baseline": {"significant_heave_m": before, "what": "the scene's own values, the same equivalent "
                            "linearization in the same sea"}}
        doc["model"] = model = design_model(scene)
        from .check import linearization_errors
        new_scene = designed_scene(scene, settings, result)
        doc["prediction_error"] = errors = linearization_errors(scene, new_scene, settings)
        if args.write_scene:
            from ..atomic import atomic_path
            from ..scene import dump_scene
            from .check import check_scene
            from .problem import settings_to_toml
            # the scene whose response the design predicts: the designed values in the design sea on the buoy
            # orbit, run by the design's own model; `cablesys run` of it is the check's designed run
            written = check_scene(new_scene, settings).with_numerics(model="as-built")
            with atomic_path(args.write_scene) as tmp:
                tmp.write_text(WRITTEN_HEADER + dump_scene(written) + settings_to_toml(settings))
        if args.check:
            from ..ladder import simulate
            from .check import time_domain_check
            # the design's own model (as built): what is checked is its equivalent linearization
            doc["time_domain_check"] = time_domain_check(scene, new_scene, settings,
                                                         lambda sc: simulate(sc, model="as-built"))
        outdir.write_text("design.json", json.dumps(doc, indent=2, default=float) + "\n")
        figures = write_figures(scene, settings, result, outdir)
        outdir.finish("success" if result.converged else "failed", message=str(result.status))
    w = sys.stdout.write
    w(f"{scene.name}\n{'converged' if result.converged else 'NOT converged'} (best solve: {result.status}); "
      f"{result.nlp_iterations} IPOPT iterations in {result.nlp_wall_s:.2f} s (total {result.total_wall_s:.2f} s)\n")
    w(f"sea: JONSWAP Hs {settings.hs:g} m, Tp {settings.tp:g} s, gamma {settings.gamma:g}\n")
    est = model["estimated_error"]
    w(f"model: {model['name']}" + (f" N = {model['segments']}" if model.get("segments", 1) > 1 else "")
      + f", the scene's own (the ladder's estimate of its time-domain error: body "
      f"{100 * est['body']:.2g} %, tension {100 * est['tension']:.2g} %)\n")
    gain = 20 * math.log10(max(result.stochastic_sig_y_b, 1e-300) / max(before, 1e-300))
    w(f"body heave significant amplitude: baseline (the scene's values) {before:.4g} m -> designed "
      f"{result.stochastic_sig_y_b:.4g} m ({gain:+.1f} dB)\n")
    w(f"  linearization error (least-squares vs equal-mean-square criterion): baseline "
      f"{100 * errors['baseline_error_rel']:.1f} %, designed {100 * errors['designed_error_rel']:.1f} %, ratio "
      f"{errors['ratio']:.3g} +- {100 * errors['ratio_error_rel']:.1f} %\n")
    if scene.top_motion.rao is not None:
        w("note: the design's objective moves the top with the surface orbit (Wang 1971 eq. 26 at x = 0); "
          "the scene's [top_motion.rao] is used by run and rao, not by the design\n")
    if failed:
        w(f"{len(failed)} of {len(result.runs)} solves failed:\n")
        for f in failed:
            w(f"  solve {f['solve']} (outer pass {f['outer'] + 1}): {f['status']} after {f['iterations']} "
              f"iterations, objective {f['objective']:.5g}: {f['why']}\n")
    w(f"objective ({result.objective_kind}): {result.objective:.6g}\n")
    for name, v, lo, hi in zip(result.variable_names, result.values, result.lower, result.upper):
        w(f"  {name:<20s} {v:12.5g}   [{lo:.4g}, {hi:.4g}]\n")
    w("constraint margins (>= 0 met): " + ", ".join(f"{k} {v:+.3g}" for k, v in result.margins.items()) + "\n")
    w(f"active: {', '.join(result.active) or 'none'}\nwrote {out / 'design.json'} and {', '.join(figures)}\n")
    if args.write_scene:
        w(f"wrote the designed scene in the design sea (buoy orbit, the scene's own top motion replaced; model "
          f"as-built) to {args.write_scene}: `cablesys run {args.write_scene}` is the run whose heave the design "
          f"predicts\n")
    if args.check:
        w(check_lines(doc["time_domain_check"]))
    return 0 if result.converged else 1
