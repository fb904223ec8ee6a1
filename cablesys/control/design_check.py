"""The time-domain design re-run by the plain time domain (:func:`cablesys.time_domain.simulate`): every limit
judged on the sampled extremes of an adaptive integrator's run, not on the design's RK4 roll-out."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..model.segmented import build_segmented_model
from ..model.segmented_winch_control import NodeWinchModel
from ..scene.labels import section_suffix
from .design_problem import TimeDesignProblem
from .design_rollout import section_row


def resimulate_design(problem: TimeDesignProblem, theta) -> dict:
    """The design ``theta`` re-run by the plain time domain (:func:`cablesys.time_domain.simulate`, the
    scene's integrator and tolerances, output every ``numerics.output_step``; the design's model without its winch:
    Wang's 2-DOF model, or the node model of its N elements per section) in every seed, judged over the same window
    by the sampled extremes: each section's peak ``tension_top`` / its working load, the least of the tension the
    no-slack floor bounds / its mean (the slack ratio: Wang's F_bc, ``tension_mid``; the node model's least element
    tension at each time), the lowest body's largest |y_b - mean| and |x_b - mean| / max excursion, and var(y_b).

    Returns
    -------
    dict
        per seed the values, ``max_relative_violation`` (largest (value - bound) / |bound|, 0 when all hold)
        and ``heave_variance_m2`` (mean over the seeds).
    """
    from ..time_domain import simulate
    scene = problem.designed_scene(theta)
    # the design's model without its winch: build_model's (the stored model), except a chain's node model at N = 1
    # per section, for which build_model would build Wang's chain; per seed, whose sea may realise other sinusoids
    node_n1 = isinstance(problem.model, NodeWinchModel) and problem.model.segments == 1
    k = problem.sections
    low = section_suffix(k, k - 1)
    per_seed, worst, variances = {}, 0.0, []
    for s in problem.seeds:
        sea = dataclasses.replace(scene.top_motion.spectrum, seed=int(s))
        seeded = scene.replace(top_motion=dataclasses.replace(scene.top_motion, spectrum=sea))
        run = simulate(seeded, model=build_segmented_model(seeded) if node_n1 else None)
        if not run.success:
            per_seed[s] = {"success": False, "message": run.message}
            worst = math.inf
            continue
        m = run.time >= problem.window_start * problem.dt - 1e-9
        d = {name: np.asarray(run.data[name + low])[m] for name in ("y_b", "x_b")}
        tops = [np.asarray(run.data["tension_top" + section_suffix(k, i)])[m] for i in range(k)]
        prof = run.profiles
        d["floor"] = (np.min(np.asarray(prof["element_tension"]), axis=1)[m] if "element_tension" in prof
                      else np.asarray(run.data["tension_mid" + section_suffix(k, 0)])[m])
        h, xb = d["y_b"] - d["y_b"].mean(), d["x_b"] - d["x_b"].mean()
        vals = {}
        for i, (top, wl) in enumerate(zip(tops, problem.working_load)):
            if math.isfinite(wl):
                vals[section_row("peak_tension", i)] = (float(top.max() / wl), 1.0)
        if problem.slack_fraction is not None:
            vals["slack"] = (float(-d["floor"].min() / d["floor"].mean()), -problem.slack_fraction)
        if problem.max_excursion is not None:
            vals["excursion"] = (float(max(np.abs(h).max(), np.abs(xb).max()) / problem.max_excursion), 1.0)
        viol = max([max(v - b, 0.0) / abs(b) for v, b in vals.values()] or [0.0])
        worst = max(worst, viol)
        variances.append(float(np.mean(h ** 2)))
        per_seed[s] = {"success": True, "constraints": vals, "max_relative_violation": viol,
                       "heave_variance_m2": variances[-1], "tension_top_max_n": float(tops[0].max()),
                       "tension_floor_min_n": float(d["floor"].min())}
    return {"theta": [float(v) for v in theta], "per_seed": per_seed, "max_relative_violation": worst,
            "heave_variance_m2": float(np.mean(variances)) if variances else math.nan,
            "integrator": scene.numerics.integrator, "drag_segments": scene.numerics.drag_segments,
            "segments": scene.sections[0].cable.segments, "sections": k}
