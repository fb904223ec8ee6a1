"""A package lowered onto the seabed, as the model ladder runs it (``ends_checks.py``'s landing keys): the landed
state's convergence in N with and without the body's footprint (``body.bed_area``), and auto's stated error per
quantity against a fine reference (cablesys.ladder.landed: the landed tensions judged at their first order)."""

from __future__ import annotations

import dataclasses

import numpy as np

import cablesys
from cablesys.ladder import metrics
from cablesys.scene import Body, Cable, Environment, Numerics, Seabed, Winch, single_section_scene
from cablesys.time_domain import simulate

# a 500 N package on 8 N/m line (AE 1 MN) lowered at 0.5 m/s from 32 m to the bed 40 m down, where the winch stops
W_B, M_B, W_R, M_R, AE, D = 500.0, 100.0, 8.0, 1.0, 1e6, 0.02
DEPTH, L0, SPEED, RAMP, K_BED = 40.0, 32.0, 0.5, 2.0, 3e6


def scene(n: int = 4, bed_area: float | None = 1.0, settle: float = 8.0):
    """The lowering in still water (cross-flow drag on the line, Voigt damping C_I = 0.05 s AE), its package with the
    footprint ``bed_area`` (m^2; None: a point body)."""
    dur = (DEPTH - L0) / SPEED + RAMP
    return single_section_scene(
        cable=Cable(length=L0, ae=AE, diameter=D, mass_per_length=M_R, weight_per_length=W_R, cd_normal=1.2,
                    ct_tangential=0.0, internal_damping=0.05 * AE, segments=n),
        body=Body(weight=W_B, mass_x=M_B, mass_y=M_B, drag_area_normal=0.0, drag_area_tangential=0.0, bed_area=bed_area),
        environment=Environment(gravity=9.80665), seabed=Seabed(depth=DEPTH, stiffness=K_BED),
        numerics=Numerics(duration=dur + settle, output_step=0.5),
        winch=Winch(speed=SPEED, duration=dur, ramp=RAMP, max_length=60.0))


def landed_state(n: int, bed_area: float | None) -> dict:
    """The node model at N = ``n`` (as built, rtol 1e-8) at the end of the run, the package at rest on the bed: the top
    tension, the line's pull on the package (``tension_bottom``) and the package's depth (m)."""
    sc = scene(n, bed_area)
    r = simulate(dataclasses.replace(sc, numerics=dataclasses.replace(sc.numerics, model="as-built", rtol=1e-8,
                                                                      atol=1e-9)))
    return {"N": n, "tension_top_N": float(r["tension_top"][-1]), "tension_bottom_N": float(r["tension_bottom"][-1]),
            "depth_m": float(r["y_b"][-1]), "success": bool(r.success)}


def honesty(n_ref: int = 64) -> dict:
    """auto's run of the landing (package footprint 1 m^2): its N, the statistics it reports (the landed tensions
    extrapolated at first order, ``model.extrapolated``) and their stated errors per quantity, against a reference from
    runs at ``n_ref`` / 2 and ``n_ref`` (rtol 1e-8): the first-order limit 2 f(n_ref) - f(n_ref / 2) of the quantities
    auto extrapolated, f(n_ref) of the others; each error relative to its own value with the ladder's floors
    (:func:`cablesys.ladder.metrics.quantity_errors`). ``ratio`` is actual / stated per quantity (honest: <= 1). Also the
    taut check's statement for the same N, |f(N) - f(N / 2)| / 3 of the raw statistics, against their actual error
    (what auto said before the landed rule) and the closed forms of the landed tensions (w L and 0)."""
    sc = scene()
    run = cablesys.simulate(sc)
    model = run.stats["model"]
    n = model["segments"]
    block = model.get("extrapolated") or {}
    stats = block.get("statistics") or {}
    first = block.get("extrapolated_quantities", [])
    period, ramp = metrics.forcing_period(sc), sc.top_motion.effective_ramp_s
    ref_runs = {}
    for m in (n_ref // 2, n_ref, n // 2, n):
        s = scene(m)
        ref_runs[m] = metrics.statistics(simulate(dataclasses.replace(
            s, numerics=dataclasses.replace(s.numerics, model="as-built", rtol=1e-8, atol=1e-9))), period, ramp)
    f_half, f_ref = ref_runs[n_ref // 2], ref_runs[n_ref]
    ref = {k: (2 * f_ref[k] - f_half[k] if k in first else f_ref[k]) for k in f_ref}
    ref = {k: max(v, 0.0) if metrics.group(k) == "tension" else v for k, v in ref.items()}
    actual = metrics.quantity_errors(stats, ref)
    stated = model["estimated_error_per_quantity"]
    raw_actual = metrics.quantity_errors(ref_runs[n], ref)
    taut_stated = {k: v / 3.0 for k, v in metrics.quantity_errors(ref_runs[n], ref_runs[n // 2]).items()}
    return {"N": n, "checked": model["checked"], "extrapolated_quantities": first, "statistics": stats,
            "reference": ref, "reference_N": [n_ref // 2, n_ref], "stated": stated, "actual": actual,
            "ratio": {k: actual[k] / stated[k] for k in actual},
            "closed_form": {"tension_top_min": W_R * DEPTH, "tension_bottom_min": 0.0},
            "taut_rule": {"stated": taut_stated, "actual": raw_actual},
            "success": bool(run.success)}
