"""bench_vs_moordyn's rows for Wang's 2-DOF model and the model ladder's ``auto`` choice (issues 12, 13).

Both against the converged segmented reference of the case, their speed against MoorDyn at the smallest
N of the case (``md_small`` = (N, MoorDyn wall seconds)). The helpers of the main script are passed in
(``matched``, ``timed_run``, ``stats``, ``diff``, ``compiled_ctx``), as for ``_bench_slack``.
"""

from __future__ import annotations

import os
import time
import warnings

from cablesys.ladder import simulate_auto
from cablesys.ladder.rungs import RungCache
from cablesys.model import build_model
from cablesys.time_domain import simulate

AUTO_REPEATS = 3


def wang_row(wang_scene, period, ref_stats, md_small, *, matched, timed_run, stats, diff, compiled_ctx) -> dict:
    """Wang's 2-DOF model itself at matched accuracy against its own tight run (stepping and outputs
    timed, setup apart), compiled; ``error`` against the converged reference."""
    dur = wang_scene.numerics.duration
    wang_model = build_model(wang_scene)
    run = lambda meth, rtol: simulate(wang_scene, model=wang_model, method=meth, rtol=rtol, atol=rtol * 1e-3)
    try:
        with warnings.catch_warnings(), compiled_ctx(True):
            warnings.simplefilter("ignore")
            tight = run("cvodes", 1e-8)
            m = matched(run, stats(tight, period), period,
                        timed=lambda meth, rtol: timed_run(wang_scene, meth, rtol, rtol * 1e-3))
    except Exception as err:          # noqa: BLE001 - a failing rung is a result of the benchmark
        return {"failed": f"{type(err).__name__}: {err}"}
    if m is None:
        return {"failed": "no setting met matched accuracy", "error": diff(stats(tight, period), ref_stats)}
    res, wall, first, how = m
    return {"s_per_s": wall / dur, "build_s": first - wall, "compiled": True, "error": diff(stats(res, period), ref_stats),
            "settings": how, "steps": res.stats.get("nsteps"), "model": res.stats.get("model"),
            "speedup_vs_moordyn_n": md_small[0], "speedup": md_small[1] / wall}


def auto_row(scene, period, ref_stats, md_small, *, stats, diff, compiled_ctx) -> dict:
    """Model auto at the default tolerance as a user runs it: its own rung, element count and
    integrator settings (issue 12), one RungCache for the calls. The first call builds (models,
    compiled code, the describing-function solver); the best of AUTO_REPEATS further calls gives
    ``choose_s`` (steady state, describing function, estimates), ``check_s`` (a posteriori runs) and
    ``run_s`` (the chosen run with its integrator guard and start: stepping and outputs, as MoorDyn's
    time is). ``speedup`` counts the choice and the checks (choose_s + check_s + run_s),
    ``speedup_run_only`` the run alone; both against MoorDyn at the smallest N of the case. ``error``:
    against the converged reference. ``load_average``: the machine's 1-minute load when measured."""
    cache = RungCache()
    dur = scene.numerics.duration
    try:
        with warnings.catch_warnings(), compiled_ctx(True):    # auto compiles up to 20 elements, the VM above
            warnings.simplefilter("ignore")
            t0 = time.perf_counter()
            simulate_auto(scene, model="auto", cache=cache)
            cold = time.perf_counter() - t0
            runs = [simulate_auto(scene, model="auto", cache=cache) for _ in range(AUTO_REPEATS)]
    except Exception as err:          # noqa: BLE001 - a failing rung is a result of the benchmark
        return {"failed": f"{type(err).__name__}: {err}"}
    res = min(runs, key=lambda r: r.stats["ladder_timing"]["total_s"])
    t = res.stats["ladder_timing"]
    waited = t["choose_s"] + t["check_s"] + t["run_s"]
    return {"s_per_s": waited / dur, "run_s_per_s": t["run_s"] / dur, "choose_s": t["choose_s"], "check_s": t["check_s"],
            "run_s": t["run_s"], "build_s": cold - t["total_s"], "first_call_s": cold,
            "error": diff(stats(res, period), ref_stats) if res.success else None, "success": bool(res.success),
            "model": res.stats.get("model"), "method": res.stats.get("method"), "steps": res.stats.get("nsteps"),
            "compiled": res.stats.get("compiled"), "speedup_vs_moordyn_n": md_small[0],
            "speedup": md_small[1] / waited, "speedup_run_only": md_small[1] / t["run_s"],
            "load_average": os.getloadavg()[0]}
