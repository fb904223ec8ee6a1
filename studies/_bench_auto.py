"""bench_vs_moordyn's rows for Wang's 2-DOF model and the model ladder's ``auto`` choice (issues 12, 13).

Both against the converged segmented reference of the case, their speed against MoorDyn at the smallest
N of the case (``md_small`` = (N, MoorDyn wall seconds)). The helpers of the main script are passed in
(``matched``, ``timed_run``, ``stats``, ``diff``, ``compiled_ctx``), as for ``_bench_slack``.

The slack case (heave at T = 6 s, 360 s; :func:`slack_auto_row`), run of 2026-11-30 12:18-12:31 UTC (load 1-3 on
2 cores, MoorDyn steps kept from the 09:22 probe): auto picked N = 16 (4, 8, 16 not asymptotic), doubled to
N = 32 and extrapolated from 8, 16, 32 (observed orders 0.98 / 0.97): 10.35 s in all (choice 3 ms, the N = 16
run 2.18 s, the checks 8.17 s: the runs at 4, 8 and the N = 32 run that gives the time series; code cached).
Error of its extrapolated statistics against the reference (Richardson limit of the tight RK4 runs at 40, 80;
its own uncertainty 0.004 % / 0.16 %): body 0.025 %, tension 0.28 % (stated 0.037 % / 0.059 %); its N = 32
time series 4.3 % / 3.8 % (stated 4.3 % / 3.8 %). MoorDyn N = 20 takes 3.27 s: auto is 0.32x its speed, but
MoorDyn N = 20 is 0.09 % / 8.2 % from its own limit (N = 20, 80, first order assumed), cablesys N = 20 6.8 % /
6.1 % and N = 80 1.7 % / 1.5 % from theirs. MoorDyn would need N ~ 590 for auto's accuracy (~5000 s at its
walls' N^2.17: auto ~480x faster, an extrapolation) and N ~ 83 for the default 1 % / 2 % (~72 s: ~7x).
"""

from __future__ import annotations

import math
import os
import warnings

import _ladder_auto as auto_run

from cablesys.ladder import richardson as R
from cablesys.ladder import metrics as M
from cablesys.ladder.choice import tolerances
from cablesys.model import build_model
from cablesys.time_domain import simulate

AUTO_REPEATS = 3


def wang_row(wang_scene, period, ref_stats, md_small, *, matched, timed_run, stats, diff, compiled_ctx,
             compiled: bool = True) -> dict:
    """Wang's 2-DOF model itself at matched accuracy against its own tight run (stepping and outputs
    timed, setup apart), compiled (``compiled=False``: in CasADi's virtual machine); ``error`` against the converged
    reference (null without one, ``ref_stats`` None)."""
    dur = wang_scene.numerics.duration
    wang_model = build_model(wang_scene)
    run = lambda meth, rtol: simulate(wang_scene, model=wang_model, method=meth, rtol=rtol, atol=rtol * 1e-3)
    error = lambda r: None if ref_stats is None else diff(stats(r, period), ref_stats)
    try:
        with warnings.catch_warnings(), compiled_ctx(compiled):
            warnings.simplefilter("ignore")
            tight = run("cvodes", 1e-8)
            m = matched(run, stats(tight, period), period,
                        timed=lambda meth, rtol: timed_run(wang_scene, meth, rtol, rtol * 1e-3))
    except Exception as err:          # noqa: BLE001 - a failing rung is a result of the benchmark
        return {"failed": f"{type(err).__name__}: {err}"}
    if m is None:
        return {"failed": "no setting met matched accuracy", "error": error(tight)}
    res, wall, first, how = m
    return {"s_per_s": wall / dur, "build_s": first - wall, "compiled": compiled, "error": error(res),
            "settings": how, "steps": res.stats.get("nsteps"), "model": res.stats.get("model"),
            "speedup_vs_moordyn_n": md_small[0], "speedup": md_small[1] / wall}


def auto_row(scene, period, ref_stats, md_small, *, stats, diff, repeats=AUTO_REPEATS, more=None) -> dict:
    """Model auto at the default tolerance as a user runs it: its own rung, element count and
    integrator settings (issue 12), one RungCache for the calls, compiled (:func:`_ladder_auto.run_auto`, as the
    model-ladder study times it). The first call builds (models, compiled code, the describing-function solver);
    the least of each figure over it and ``repeats`` further calls gives ``choose_s`` (steady state, describing
    function, estimates), ``check_s`` (a posteriori runs, a grown N's runs among them) and ``run_s`` (the first run of
    the chosen rung and N with its integrator guard and start: stepping and outputs, as MoorDyn's time is);
    ``kept_run_s`` is the run whose result auto reports (:func:`_ladder_auto.kept_run_s`: the last candidate, at a
    grown N or the check's rtol). ``speedup`` counts the choice and the checks (choose_s + check_s + run_s),
    ``speedup_run_only`` the reported run alone (kept_run_s); both against MoorDyn at the smallest N of the case. ``error``: against the converged reference of ``stats(result, period)`` (what auto reports).
    ``load_average``: the machine's 1-minute load when measured. ``more(result)``: further entries of the row."""
    dur = scene.numerics.duration
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res, info = auto_run.run_auto(scene, True, repeats + 1, model="auto")
    except Exception as err:          # noqa: BLE001 - a failing rung is a result of the benchmark
        return {"failed": f"{type(err).__name__}: {err}"}
    t, cold = info["ladder_timing"], info["ladder_timing_first"]["total_s"]
    waited = t["choose_s"] + t["check_s"] + t["run_s"]
    return {"s_per_s": waited / dur, "run_s_per_s": info["kept_run_s"] / dur, "choose_s": t["choose_s"],
            "check_s": t["check_s"], "run_s": t["run_s"], "kept_run_s": info["kept_run_s"],
            "build_s": cold - t["total_s"], "first_call_s": cold,
            "error": diff(stats(res, period), ref_stats) if res.success else None, "success": bool(res.success),
            "model": res.stats.get("model"), "method": res.stats.get("method"), "steps": res.stats.get("nsteps"),
            "compiled": res.stats.get("compiled"), "speedup_vs_moordyn_n": md_small[0],
            "speedup": md_small[1] / waited, "speedup_run_only": md_small[1] / info["kept_run_s"],
            "load_average": os.getloadavg()[0], "repeats": repeats, **(more(res) if more and res.success else {})}


def worst_quantity(stats: dict, reference: dict, tol: dict) -> tuple:
    """(quantity, relative error, within) of ``stats`` against ``reference`` on auto's metric
    (:func:`cablesys.ladder.metrics.quantity_errors`; only the keys of :func:`cablesys.ladder.metrics.statistics`):
    the quantity furthest from its tolerance ``tol`` ({"body", "tension"}), and whether it is within it."""
    keys = [k for k in reference if k.endswith(("_amplitude", "_mean", "_max", "_min"))]
    q = M.quantity_errors({k: stats[k] for k in keys if k in stats}, {k: reference[k] for k in keys})
    k = max(q, key=lambda key: q[key] / tol[M.group(key)])
    return k, q[k], bool(q[k] <= tol[M.group(k)])


BOUND_NS = (2, 3, 4, 6, 8, 10, 12, 14, 16, 20, 24, 30, 36)   # the element counts searched, below the reference's
BOUND_RTOLS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)     # BDF(<= 2) settings, loosest first
BOUND_NEXT = 2                                               # N above the least one also timed (looser rtol)


def auto_bound(make, reference, n_ref: int, period, md_small, *, timed_run, compiled_ctx, compiled_max: int,
               ramp_s: float | None = None, moordyn_stats: dict | None = None,
               moordyn_reference: dict | None = None) -> dict:
    """The most auto can reach on a case: a bound of ``auto_speedup`` that no choice of rung settings can pass.

    Auto promises every quantity of its statistics (:func:`cablesys.ladder.metrics.quantity_errors`: each body
    amplitude and mean, each tension extreme, on its own scale or the floor) within its default tolerance
    (:func:`cablesys.ladder.choice.tolerances` of the scene) of the converged cable. The least element count N whose
    tight run (CVODES rtol 1e-7) keeps that promise against ``reference`` (the case's converged statistics at
    ``n_ref``, :func:`cablesys.ladder.metrics.statistics`) is the least any honest auto can run; that N and the next
    BOUND_NEXT of BOUND_NS are then timed at the loosest BDF(<= 2) rtol of BOUND_RTOLS still keeping the promise
    (stepping and outputs, a second run, setup apart, as MoorDyn's time: ``timed_run(scene, method, rtol, atol)``).
    The fastest of them, with no choice and no check counted, gives ``speedup_bound`` = MoorDyn's wall
    (``md_small`` = (N, s)) over it. The reference's own discretisation error makes the least N too small, so the
    bound is generous. ``make(n)``: the case's scene at n elements; ``compiled_ctx(bool)``: compiled code on or
    off (the tight runs in CasADi's virtual machine, the timed ones compiled up to ``compiled_max`` elements).
    ``moordyn_stats``: the statistics of MoorDyn's run at ``md_small[0]``, judged on the same metric
    (``moordyn_worst``: whether the peer's run the speed-up is taken against keeps auto's tolerance) against
    ``moordyn_reference``, the converged statistics in MoorDyn's definitions (its line tensions are the end
    segments', not the forces on the end points: ``bench_vs_moordyn._segment_stats``; default ``reference``)."""
    scene = make(n_ref)
    tol_body, tol_tension = tolerances(scene)
    tol = {"body": tol_body, "tension": tol_tension}
    worst = lambda stats: worst_quantity(stats, reference, tol)     # noqa: E731

    searched, least = [], None
    for n in (n for n in BOUND_NS if n < n_ref):
        try:
            with compiled_ctx(False):
                tight = simulate(make(n), method="cvodes", rtol=1e-7, atol=1e-10)
        except Exception as err:      # noqa: BLE001 - an N too coarse for the scene (its statics) is a result
            searched.append({"segments": n, "failed": f"{type(err).__name__}: {err}", "within": False})
            continue
        k, e, ok = worst(M.statistics(tight, period, ramp_s))
        searched.append({"segments": n, "worst_quantity": k, "error": e, "within": ok})
        if ok and least is None:
            least = n
        if least is not None and len([s for s in searched if s["segments"] >= least]) > BOUND_NEXT:
            break
    out = {"tolerance": tol, "reference_segments": n_ref, "searched": searched,
           "moordyn_segments": md_small[0], "moordyn_wall_s": md_small[1]}
    if moordyn_stats is not None:  # the peer's run the speed-up is taken against, on the same metric
        k, e, ok = worst_quantity(moordyn_stats, moordyn_reference or reference, tol)
        out["moordyn_worst"] = {"quantity": k, "error": e, "within": ok}
    if least is None:
        return {**out, "least_segments": None,
                "why": f"no N below the reference's {n_ref} keeps every quantity within the tolerance"}
    timed = []
    for s in (s for s in searched if s["segments"] >= least and s["within"]):
        n = s["segments"]
        for rtol in BOUND_RTOLS:
            with compiled_ctx(n <= compiled_max):
                res, wall = timed_run(make(n), "cvodes-bdf2", rtol, rtol * 1e-3)[:2]
            k, e, ok = worst(M.statistics(res, period, ramp_s))
            if res.success and ok:
                timed.append({"segments": n, "rtol": rtol, "wall_s": wall, "steps": res.stats.get("nsteps"),
                              "worst_quantity": k, "error": e})
                break
    if not timed:
        return {**out, "least_segments": least, "why": "no rtol of BOUND_RTOLS keeps the tolerance"}
    best = min(timed, key=lambda t: t["wall_s"])
    return {**out, "least_segments": least, "timed": timed, "fastest": best,
            "speedup_bound": md_small[1] / best["wall_s"]}


# -- the slack row (heave at T = 6 s, _bench_slack): auto reports extrapolated statistics -------------------

DEFAULT_TOLERANCE = {"body": 0.01, "tension": 0.02}     # auto's default model tolerance (issue 12)
SLACK_NOTE = ("Accuracy is each code's against its own converged answer, not against the other code: MoorDyn damps "
              "slack segments where cablesys keeps Wang's eq. 54 (the tension floor), so their converged answers "
              "differ by ~30 % on this scene (cablesys_vs_moordyn). auto_error: auto's reported (extrapolated) "
              "statistics against the reference, both in auto's definition (last 5 periods, maxima refined); "
              "auto_speedup: MoorDyn at the smallest N over auto's whole wait (choice, runs at N, N/2, N/4), "
              "whatever MoorDyn's accuracy there; auto_moordyn_equal_accuracy: the N (and wall) MoorDyn would need "
              "for auto's accuracy and for the default tolerance, from its own two runs assuming first order in N.")


def reported_statistics(result, period) -> dict:
    """What auto reports on a slack scene: the statistics extrapolated from its runs at N / 4, N / 2, N
    (:mod:`cablesys.ladder.extrapolation`), else its N run's (same definition: the last 5 periods,
    maxima refined between samples, :func:`cablesys.ladder.richardson.statistics`)."""
    block = (result.stats.get("model") or {}).get("extrapolated")
    return dict(block["statistics"]) if block else R.statistics(result, period)


def moordyn_for(md: dict, targets: dict, auto_wall: float) -> dict:
    """The MoorDyn N (and wall time) for a given accuracy, from its own runs at two N.

    MoorDyn's converged answer is taken as the first-order Richardson limit of its two runs
    (f + (f - f_c) / (r - 1), r the ratio of the N; first order as the segmented cable's on this scene,
    an assumption: two runs cannot verify an order), so its error is C / N with C from the finer run;
    the N for an error e is N_fine e_fine / e (body and tension, the larger), its wall time
    w_fine (N / N_fine)^k with k the exponent the two runs' walls give (about 2: the stable step
    ~ 1 / N, the cost of a step ~ N).

    Parameters
    ----------
    md : dict
        {N: {"stats", "cycle_means", "wall_s"}} of MoorDyn's runs (auto's statistics definition,
        the cycle means in the ladder's names, the best wall in s).
    targets : dict
        {name: {"body", "tension"}}: the accuracies to meet.
    auto_wall : float
        Auto's wall (s) to compare with.

    Returns
    -------
    dict
        Per statistics definition its error at each N against its own limit and, per target, ``segments``,
        ``wall_s`` (extrapolated) and ``auto_speedup`` at that accuracy.
    """
    ns = sorted(md)
    if len(ns) < 2:
        return {"estimated": False, "why": "MoorDyn ran at one N only: its convergence in N is unknown"}
    lo, hi = ns[0], ns[-1]
    ratio = hi / lo
    k = math.log(md[hi]["wall_s"] / md[lo]["wall_s"]) / math.log(ratio)
    out = {"estimated": True, "segments_used": [lo, hi], "order_assumed": 1.0, "wall_exponent": k,
           "assumption": "MoorDyn's converged answer = first-order Richardson limit of its two runs; error ~ 1/N"}
    for name in ("stats", "cycle_means"):
        lim = R.limits(md[lo][name], md[hi][name], order=1.0, ratio=ratio)
        e_hi = M.errors(md[hi][name], lim)
        d = {"error_at_n": {lo: M.errors(md[lo][name], lim), hi: e_hi}}
        for tname, t in targets.items():
            n = max(math.ceil(hi * e_hi[q] / max(t[q], 1e-9) * (1 - 1e-12)) for q in ("body", "tension"))  # round-off
            wall = md[hi]["wall_s"] * (n / hi) ** k
            d[tname] = {"segments": n, "wall_s": wall, "auto_speedup": wall / auto_wall}
        out[name] = d
    return out


def slack_auto_row(scene, period, ref: dict, md: dict, *, cycle_means) -> dict:
    """Auto's row on the slack scene: timed as :func:`auto_row` (one warm call after the cold one: 10-20 s
    each), its ``error`` on what it reports (:func:`reported_statistics`) against ``ref["stats"]`` (the
    bench's converged reference in the same definition), the N run's own time-series errors (auto's
    definition and the cycle means, ``cycle_means(result)``, against ``ref["cycle_means"]``), and
    the MoorDyn N for auto's accuracy and for the default tolerance (:func:`moordyn_for`).
    ``md``: {N: MoorDyn's runs as :func:`moordyn_for` takes them}, the speedup against the smallest N."""
    def more(res):
        m = res.stats.get("model") or {}
        block = m.get("extrapolated") or {}
        return {"reported": "extrapolated statistics" if block else "the N run's statistics",
                "segments": m.get("segments"), "extrapolated_from": block.get("segments"),
                "asymptotic": block.get("asymptotic"), "observed_order": block.get("leading_orders"),
                "estimated_error": m.get("estimated_error"),
                "estimated_error_time_series": m.get("estimated_error_time_series"),
                "error_time_series": M.errors(R.statistics(res, period), ref["stats"]),
                "error_time_series_cycle_means": M.errors(cycle_means(res), ref["cycle_means"])}
    n0 = min(md)
    row = auto_row(scene, period, ref["stats"], (n0, md[n0]["wall_s"]), stats=reported_statistics, diff=M.errors,
                   repeats=1, more=more)
    if row.get("error"):
        waited = row["s_per_s"] * scene.numerics.duration
        row["moordyn_equal_accuracy"] = moordyn_for(md, {"auto_error": row["error"], "default_tolerance": DEFAULT_TOLERANCE},
                                                    waited)
    return row
