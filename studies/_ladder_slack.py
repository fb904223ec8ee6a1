"""The slack scene of studies/model_ladder.py: its reference and auto's assessment.

Auto on a slack scene (:mod:`cablesys.ladder.extrapolation`) reports statistics extrapolated from RK4
runs at N / 4, N / 2, N; its actual error is measured on those numbers, against a reference finer than
its runs (else the check is circular): the first-order Richardson limit of RK4 runs at the case's
``reference_segments`` (full: N = 40, 80; auto takes N = 32), compiled (the element kernel) in full
mode. The reference runs give both kinds of statistics: cycle means over the settled window (the
rows' figures, :func:`_cycles.ladder_statistics`) and auto's own (the last 5 periods, maxima refined
between samples, :func:`cablesys.ladder.richardson.statistics`), so auto is compared on its terms.
The reference's own uncertainty is the remainder estimate of the limits of the previous pair (the
table's rk-stable run at half the coarser reference N), |L(N/2) - L(N)| / 3, as auto states its own.
"""

from __future__ import annotations

import contextlib
import dataclasses
import time
import warnings

from _cycles import ladder_statistics
from _ladder_auto import auto_row, candidates, compiling, run_auto
from _ladder_checks import cheaper_within, estimate_check

from cablesys.errors import NumericalWarning
from cablesys.ladder import RungCache, metrics
from cablesys.ladder import extrapolation as X
from cablesys.ladder import richardson as R

AUTO_INTEGRATOR = "auto-extrapolated"     # auto's row: RK4 at N / 4, N / 2, N, statistics extrapolated


@contextlib.contextmanager
def capped(n: int | None):
    """The extrapolation's doubling stopped at ``n`` elements inside (quick mode: short runs in the VM)."""
    old = X.MAX_SEGMENTS
    X.MAX_SEGMENTS = n or old
    try:
        yield
    finally:
        X.MAX_SEGMENTS = old


def reference_run(case: dict, n: int, period: float, cache: RungCache) -> dict:
    """One reference run: RK4 at its stable step (:func:`cablesys.ladder.extrapolation.run`), both statistics."""
    with compiling(case.get("compile_reference", False)), warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        t0 = time.perf_counter()
        r = X.run(case["scene"], n, cache)
        total = time.perf_counter() - t0
    row = {"segments": n, "success": bool(r.success), "wall_s": float(r.stats.get("wall_s", total)), "total_s": total}
    if r.success:
        row.update(statistics=ladder_statistics(r, period, case["window_t0"]), auto_statistics=R.statistics(r, period))
    return row


def slack_reference(case: dict, rows: list, period: float, cache: RungCache) -> dict:
    """The first-order Richardson limit of the reference runs (``case["reference_segments"]``), in the
    rows' and in auto's statistics, its observed order with the table's rk-stable run at half the coarser N,
    and its own uncertainty (the remainder estimate of the previous pair's limits)."""
    c, f = case["reference_segments"]
    runs = {n: reference_run(case, n, period, cache) for n in (c, f)}
    if not all(r["success"] for r in runs.values()):
        return {"kind": "richardson", "error": f"a reference run failed (N = {c}, {f})", "runs": runs}
    lim = R.limits(runs[c]["statistics"], runs[f]["statistics"], order=1.0, ratio=f / c)
    lim_auto = R.limits(runs[c]["auto_statistics"], runs[f]["auto_statistics"])
    floor = max(s.cable.tension_floor for s in case["scene"].sections)
    for d in (lim, lim_auto):           # a minimum's limit below the tension floor: the floor (as auto's)
        d.update({k: max(v, floor) for k, v in d.items() if k.endswith("_min")})
    half = next((r for r in rows if r["rung"] == "segmented" and r["segments"] == c // 2
                 and r["integrator"] == "rk-stable" and "statistics" in r), None)
    orders, unc = {}, None
    if half is not None:
        orders = R.observed_orders(half["statistics"], runs[c]["statistics"], runs[f]["statistics"])
        prev = R.limits(half["statistics"], runs[c]["statistics"], order=1.0)
        unc = {k: v / (2.0**R.REMAINDER_ORDER - 1.0) for k, v in metrics.errors(prev, lim).items()}
    return {"kind": "richardson", "segments": [c, f], "integrator": "rk-stable"
            + (" (compiled)" if case.get("compile_reference") else ""), "order_assumed": 1.0,
            "observed_order": orders, "observed_order_from": [c // 2, c, f], "statistics": lim,
            "auto_statistics": lim_auto, "uncertainty": unc, "convergence_vs_half": unc,
            "window_s": runs[f]["statistics"]["window_s"], "duration_s": case["scene"].numerics.duration,
            "spread_at_finest": runs[f]["statistics"]["spread"], "runs": runs,
            "wall_s": sum(r["wall_s"] for r in runs.values())}


def assess_slack_auto(case: dict, res: dict, choice, choose_s: float, resolved_fraction: float,
                      cache: RungCache | None = None) -> dict:
    """Auto's run of the slack scene (:func:`cablesys.ladder.simulate`, compiled as the reference
    in full mode), its stated errors against its actual ones on what it reports: the extrapolated
    statistics (headline) and the N run's time series (apart), against the reference in auto's terms.
    Auto's row (integrator AUTO_INTEGRATOR, wall time of its three or more runs) joins ``res["rows"]``."""
    scene, period, rows = case["scene"], res["period_s"], res["rows"]
    ref = res["reference"]["auto_statistics"]
    with capped(case.get("max_segments")):
        r, info = run_auto(scene, bool(case.get("compile_reference")))
    m, lt = r.stats["model"], info["ladder_timing"]
    x = m.get("extrapolated")
    got = x["statistics"] if x else R.statistics(r, period)
    act, act_ts = metrics.errors(got, ref), metrics.errors(R.statistics(r, period), ref)
    stated = dict(m["estimated_error"])
    tol = choice.numbers["tolerance"]
    settings, info["integrator"] = info["integrator"], AUTO_INTEGRATOR
    row = auto_row(scene, info, r, act, stated, runs=x["segments"] if x else [m["segments"]], statistics=got,
                   settings=settings)
    rows[:] = [q for q in rows if q["integrator"] != AUTO_INTEGRATOR and not q.get("auto")] + [row]
    conv = res["reference"].get("convergence_vs_half") or {}
    check = estimate_check(act, stated, tol, conv, resolved_fraction)
    check["time_series"] = estimate_check(act_ts, m.get("estimated_error_time_series", stated), tol, conv,
                                          resolved_fraction)
    check["lower_rungs_within_half_tolerance"] = cheaper_within(rows, dataclasses.replace(choice, segments=m["segments"]),
                                                                tol, ("rk-stable",))
    # the rungs within the tolerance run forced as auto runs them (none in the full run: no single run is)
    stats_of = lambda q: R.statistics(q, period)
    cands = candidates(scene, rows, ("segmented", m["segments"]), tol, stats_of, ref, bool(case.get("compile_reference")), 1)
    how = (f"a posteriori: statistics extrapolated from N = {', '.join(map(str, x['segments']))} (RK4), the "
           f"difference of the two limits x {x['remainder_factor']:.3g}" if x else "a priori")
    return {"name": m["name"], "segments": m["segments"], "integrator": AUTO_INTEGRATOR, "reason": m["reason"],
            "estimated_error": choice.estimated_error, "stated_estimate": stated, "stated_how": how,
            "stated_estimate_time_series": m.get("estimated_error_time_series"), "actual_error": act,
            "actual_error_time_series": act_ts, "extrapolated": x, "choose_s": choose_s, "candidates": cands,
            "ladder_timing": lt, "ladder_timing_first": info["ladder_timing_first"], "wall_s": info["wall_s"],
            "load_1min": info["load_1min"], "compiled": info["compiled"], "settings": settings, "estimates": choice.numbers["estimates"], "tolerance": tol, "check": check}
