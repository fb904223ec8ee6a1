"""Auto's row of studies/model_ladder.py: auto run as a user runs it, and the runs it is compared with.

:func:`run_auto` calls :func:`cablesys.ladder.simulate` itself (compiled in full mode, CasADi's
VM in quick mode), so auto's row is what a user gets: the rung and N it ends with after its a
posteriori checks, the integrator and rtol it picks (recorded from the simulators it builds,
:class:`RecordingCache`), its stated estimate (``stats["model"]["estimated_error"]``, a posteriori
where auto made its check) and its wall time (``stats["ladder_timing"]``). The first call is on a
fresh cache (``ladder_timing_first``, building included); every figure of ``ladder_timing`` is the
least over ``repeats`` calls, and ``wall_s`` the least choose + run + check (total less building).

The table rows run in the VM at the study's rtol, so their wall times are not auto's. The "beaten"
check compares like with like instead (:func:`candidates`): every other rung and N of the table
whose actual errors are within the tolerance runs forced (``simulate(scene, model=rung,
segments=N)``: the same code, integrator rule and a posteriori check as auto's rung, compiled as
auto), and its errors and timing come from that run.
"""

from __future__ import annotations

import contextlib
import os
import warnings

from _ladder_checks import ladder_rank, run_name

from cablesys.errors import NumericalWarning
from cablesys.ladder import RungCache, metrics, simulate

# calls per run on one cache, the least time of each figure: ms runs on a shared 2-core machine (heavy1000's
# N = 10 run: 21.5 ms as the least of 3 calls at load ~2, 8.7 ms of 10 at load 0.5; the forced N = 5: 6.2, 5.7 ms)
REPEATS = 10
TIMES = ("choose_s", "build_s", "run_s", "check_s", "total_s")


@contextlib.contextmanager
def compiling(on: bool):
    """CABLESYS_COMPILE=1 inside when ``on`` (the study runs its table in CasADi's VM)."""
    old = os.environ.get("CABLESYS_COMPILE")
    if on:
        os.environ["CABLESYS_COMPILE"] = "1"
    try:
        yield
    finally:
        if on:
            if old is None:
                os.environ.pop("CABLESYS_COMPILE", None)
            else:
                os.environ["CABLESYS_COMPILE"] = old


class RecordingCache(RungCache):
    """A RungCache that keeps the integrator settings of every simulator asked of it (auto's runs)."""

    def __init__(self):
        super().__init__()
        self.settings = []

    def simulator(self, model, times, settings):
        self.settings.append(settings)
        return super().simulator(model, times, settings)


def integrator_text(settings: list, compiled: bool) -> str:
    """'auto (rk23 rtol 1e-04, compiled)': the distinct methods and rtols (fixed steps: per output) of auto's runs."""
    step = lambda s: f"rk4 {s.steps_per_output} steps/output" if s.method == "rk" else f"{s.method} rtol {s.rtol:.0e}"
    what = "; ".join(dict.fromkeys(step(s) for s in settings)) or "not stepped: a periodic orbit or a steady state"
    return f"auto ({what}, {'compiled' if compiled else 'VM'})"


def kept_run_s(timing: dict) -> float:
    """Wall seconds of the run whose result auto reports, from one call's ``ladder_timing``: its plan's last candidate
    run (a grown N's, or the same N again at the check's rtol), which ``run_s`` (the first candidate's) is not where
    a check grew N or tightened the rtol; ``run_s`` where the plan logs no run (the extrapolation keeps its own)."""
    runs = [r for r in timing.get("runs", ()) if r["candidate"]]
    return float(runs[-1]["wall_s"]) if runs else float(timing["run_s"])


def run_auto(scene, compiled: bool, repeats: int = 1, **kw) -> tuple:
    """(first result, info) of ``simulate(scene, **kw)`` called ``repeats`` times on one cache.

    ``info``: ``integrator`` (:func:`integrator_text` of the first call), ``method``/``rtol`` lists,
    ``ladder_timing_first`` (fresh cache), ``ladder_timing`` (least of each figure over the calls),
    ``wall_s`` (least total less building: choose + run + check), ``kept_run_s`` (least :func:`kept_run_s`),
    ``compiled``."""
    cache = RecordingCache()
    with compiling(compiled), warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        result = simulate(scene, cache=cache, **kw)
        used = list(cache.settings)
        timings = [dict(result.stats["ladder_timing"])]
        for _ in range(repeats - 1):
            timings.append(dict(simulate(scene, cache=cache, **kw).stats["ladder_timing"]))
    best = {k: min(t[k] for t in timings) for k in TIMES}
    kept = [kept_run_s(t) for t in timings]
    compiled = bool(result.stats.get("compiled", compiled))        # as it ran (a failed compilation runs in the VM)
    return result, {"integrator": integrator_text(used, compiled), "methods": [s.method for s in used],
                    "rtols": [s.rtol for s in used], "ladder_timing_first": timings[0], "ladder_timing": best,
                    "wall_s": min(t["total_s"] - t["build_s"] for t in timings), "calls": len(timings),
                    "kept_run_s": min(kept),
                    "compiled": compiled, "load_1min": os.getloadavg()[0]}


def _errors(result, statistics, ref_stats) -> dict:
    if not result.success or ref_stats is None:
        return {"body": None, "tension": None}
    return metrics.errors(statistics(result), ref_stats)


def auto_row(scene, info: dict, result, act: dict, stated: dict, **extra) -> dict:
    """Auto's row of the table (integrator: :func:`integrator_text`; wall time: ``info["wall_s"]``)."""
    m = result.stats["model"]
    return {"rung": m["name"], "segments": m["segments"], "integrator": info["integrator"],
            "success": bool(result.success), "failure": "" if result.success else result.message[:300],
            "wall_s": info["wall_s"], "total_s": info["ladder_timing"]["total_s"],
            "nsteps": int(result.stats.get("nsteps", 0) or 0), "error_body": act["body"],
            "error_tension": act["tension"], "estimate_body": stated.get("body"),
            "estimate_tension": stated.get("tension"), "auto": True, **extra}


def candidates(scene, rows: list, mine: tuple, tol: dict, statistics, ref_stats, compiled: bool,
               repeats: int) -> list:
    """Every other (rung, N) at or below auto's on the ladder (:func:`_ladder_checks.ladder_rank`: the cheaper
    rungs of issue 12's check) with a table row within the tolerance, forced and run as auto runs its rung.
    Rungs above auto's ran 1.5-30x slower than auto's in every full run that had them (12:30 UTC, 2026-11-30),
    and compiling the quasi-static segmented N = 20 model makes cc1 grow past 22 GB (killed: the shared
    machine's memory), so they are not run.

    Each entry: ``run``, ``integrator``, its own actual errors (``error_body``, ``error_tension``: the
    forced run's, which may differ from the table row's at the study's rtol), the table row's, its
    stated estimate and ``ladder_timing`` / ``wall_s`` as :func:`run_auto`."""
    seen = {}
    for r in rows:
        if r.get("error_body") is None or r["rung"] == "frequency" or r.get("auto"):
            continue
        key = (r["rung"], r["segments"] if r["rung"] in ("segmented", "quasi-static") else 1)
        if (key != mine and key not in seen and ladder_rank(*key) <= ladder_rank(*mine)
                and r["error_body"] <= tol["body"] and r["error_tension"] <= tol["tension"]):
            seen[key] = r
    out = []
    for (rung, n), r in seen.items():
        res, info = run_auto(scene, compiled, repeats, model=rung, segments=n if rung != "wang" else None)
        e = _errors(res, statistics, ref_stats)
        out.append({"run": run_name(r), "rung": rung, "segments": n, "integrator": info["integrator"],
                    "error_body": e["body"], "error_tension": e["tension"], "table_error_body": r["error_body"],
                    "table_error_tension": r["error_tension"], "stated": res.stats["model"]["estimated_error"],
                    "ladder_timing": info["ladder_timing"], "wall_s": info["wall_s"], "nsteps": res.stats.get("nsteps")})
    return out


def assess(scene, statistics, ref_stats, compiled: bool, repeats: int) -> tuple:
    """(result, info, its statistics, actual errors against ``ref_stats``, stated estimate) of auto's own run."""
    result, info = run_auto(scene, compiled, repeats)
    got = statistics(result) if result.success else None
    act = metrics.errors(got, ref_stats) if got is not None and ref_stats is not None else {"body": None, "tension": None}
    return result, info, got, act, dict(result.stats["model"]["estimated_error"])
