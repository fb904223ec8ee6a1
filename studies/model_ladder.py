"""The model ladder: error against a converged segmented reference versus wall time, per rung and integrator.

Scenes (issue 12):
- the Dale et al. water-channel model (Wang 1971 Table 1) at omega = 2 omega_n, where the straight
  cable is worst (cable drag bows it);
- the 300 m steel wire with a 2 t sphere of issue 11 (``cablesys/data/heave_300m.toml``), 1 m heave
  at T = 10 s (taut) and T = 6 s (slack each cycle, snap loads);
- 1000 m of 16 mm steel wire rope with a 300 kg sphere (the cable weighs 4x the body), 1 m heave
  and 1 m surge at T = 10 s: forcing above the cable's first string mode.

Taut scenes: the reference is the segmented cable at N_ref elements (CVODES; its own convergence is
reported: the difference to N_ref / 2), errors those of :mod:`cablesys.ladder.metrics` (body
amplitudes, tension extremes over the last 5 forcing periods).

Slack scene (T = 6 s): the response has a transient of ~100-150 s (issue 11), so a short run times
the transient instead of comparing models. It runs 360 s and every figure is a mean over the forcing
cycles of 180-360 s (:func:`_cycles.ladder_statistics`, the code of studies/segmented_convergence.py:
maxima refined between samples, output every 0.01 s). The segmented cable converges at first order
there, so auto extrapolates the statistics from RK4 runs at N / 4, N / 2, N (:mod:`cablesys.ladder.extrapolation`)
and is measured on what it reports, against a reference finer than its runs: the first-order Richardson
limit of RK4 runs at N = 40, 80 (compiled, ``studies/_ladder_slack.py``; quick: 16, 32 in the VM, auto
capped at 16), in auto's own statistics (last 5 periods, maxima refined) for auto, in cycle means for
the table; its observed order (with the table's N = 20) and its own uncertainty (the remainder estimate
|L(20, 40) - L(40, 80)| / 3) are in the JSON.

Every rung (frequency-domain periodic orbit, quasi-static stretch, the quasi-static segmented cable
at a few N on the taut scenes when the library has it, Wang's 2-DOF, segmented at several N) runs
with every integrator: CVODES (BDF, Adams), IDAS, RK4 at the scene's step (10 per output; it fails
where that is above the stability limit, and the failure is marked) and RK4 at its stability step
(``rk-stable``, segmented rungs). Wall time is the integration alone (``stats["wall_s"]``) in
CasADi's virtual machine, build apart (``MODEL_LADDER_ONLY=dale,heavy1000`` reruns some scenes and
keeps the others' results; ``MODEL_LADDER_REESTIMATE=1`` keeps the runs of an existing
model_ladder.json and makes auto's run, the estimates and the checks again). A failed run is
an x at the top of the chart with its reason in the JSON.

Auto (the star) is measured on its own run (``studies/_ladder_auto.py``): ``simulate(scene)`` as a user
calls it, compiled in full mode (the VM in quick mode), with the integrator and rtol it picks, its a
posteriori checks and any switch of rung; its row's integrator says which (``auto (rk23 rtol 1e-04,
compiled)``). Its actual error is on the rows' statistics against the same reference, its stated estimate
the one it reports (``stats["model"]``, a posteriori where it checked), its wall time ``ladder_timing``
(choose, run, checks; the least of 10 calls on one cache, the first call's too) and on the chart choose +
run + checks. As the table's VM rows at the study's rtol are not auto's terms, "beaten" compares auto with
every other rung and N at or below its own on the ladder whose table row is within the tolerance, run forced
the same way (hollow circles; rule in the JSON's ``cheaper_rung_within_tolerance.rule``).

Findings (2026-11-30, full run on the shared 2-core machine; numbers in the JSON):
- slack scene: the Richardson limit of N = 40, 80 (RK4, planar) is 1.4032 m body heave amplitude and
  54.33 kN top maximum (issue 11: 1.403 m, 54.3 kN), observed order 0.97-1.13 (N = 20, 40, 80), own
  uncertainty 0.012 % (body) / 0.16 % (tension). No single run is within the 1 % / 2 % tolerance
  (segmented N = 40: 3.3-3.5 % body, 3-5 % tension); Wang's and the quasi-static rung miss by 27 % (body)
  and 78 % (tension). Auto extrapolates from N = 8, 16, 32 (N = 16 first: the runs 4, 8, 16 are not in
  the asymptotic range, observed order -0.9, so N doubled): actual 0.025 % body / 0.28 % tension against
  a stated 0.037 % / 0.059 % (both below the resolution, 0.1 % / 0.31 %), in 10-21 s of compiled runs; its
  N = 32 time series states 4.26 % / 3.84 % against an actual 4.28 % / 3.83 %. RK4 at its stable step vs
  half of it: < 1e-5 on every statistic at N = 8, 16, 32. CVODES and IDAS runs buckle sideways (x
  amplitude 7-13 mm) and their cycle maxima spread by up to 6 kN at N = 40; RK4 at 10 steps per output
  is past its stability step at N = 40 and runs on with 15 % tension error. The whole scene took 19 min
  (30 min in an earlier run on a busier machine); the two compiled reference runs are 150 s of it.
- taut scenes, auto's own run (compiled, least of 10 calls, 1-min load 0.6-0.9; each scene ~40 s, heavy1000
  86 s; 13:52-13:57 UTC): Dale: quasi-static N = 3, rk23 rtol 1e-4, actual 0.38 % body / 0.021 % tension,
  stated 0.37 % / 0.011 % (a priori; the tension below the resolution), 9.3 ms (choose 3.9, run 5.3; a first
  call on a fresh cache 214 ms, building included); not beaten (quasi-static N = 2, 0.88 %, runs in 4.0 ms,
  1.3x). 300 m, T = 10 s: the straight quasi-static rung, rk23 rtol 1e-5, actual 0.010 % / 0.16 %, stated
  0.020 % / 0.16 %, 5.7 ms; not beaten (Wang's model, the only rung at its level, runs 16 ms). 1000 m, run
  120 s (a 40 s window held the surge front still arriving: estimate.settling_time 45 s): settled errors of
  the segmented cable 0.94 / 0.49 / 1.13 / 0.77 / 0.17 % at N = 5 / 6 / 8 / 10 / 20 (not monotone: the drag
  rule's switch from 2 to 1 points per element at N = 7 flips the error's sign); auto takes the quasi-static
  segmented cable at N = 6 (choice.element_plan: estimated 0.95 %, within the tolerance but not half of it,
  so checked a posteriori against N = 3; cost 0.7 x 1.5 x 6 = 6.3 against the node model's sure N = 9),
  rk23 rtol 1e-4, actual 0.49 % / 0.11 %, stated (Richardson plus the stretch's part) 0.42 % / 0.12 %
  (ratios 0.85 / 1.10), run 11.0 ms + check 5.8 ms; not beaten: the quasi-static N = 5 (0.94 %) runs in
  9.4 ms (14.1 ms with its own check), the node model N = 5 in 14.8 ms. Until this change auto ran the node
  model at N = 10 (0.77 %, 22 ms) and was beaten 2x by both: the segmented estimate's floor (46.7 % x
  N^-2, whose evidence was a start-up transient) held N at 10, and the quasi-static segmented cable was
  admitted only where omega/omega_ax <= 1/30 (0.152 here).
  The actual errors equal the old table rows' of auto's rungs to 2 digits (study's rtol vs auto's).

Per scene the JSON holds issue 12's checks: ``cheaper_rung_within_tolerance`` (auto's run against the
forced runs, ``beaten``/``beaten_by``, and the table's cheapest VM run within the tolerance) and
``estimate_ratio`` (auto's stated estimate over its actual error, within 2x or not).

Usage: python studies/model_ladder.py --out DIR [--quick]
"""

from __future__ import annotations

import dataclasses
import json
import os
import re
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _ladder_auto as auto_run
from _common import parse_args, write_json
from _cycles import ladder_statistics, settled_window_start
from _ladder_chart import plot_case
from _ladder_checks import cheaper_within, estimate_check, run_name, verdicts
from _ladder_slack import assess_slack_auto, slack_reference
from segmented_convergence import slack_scene, stable_steps_per_output

from cablesys.errors import NumericalWarning
from cablesys.ladder import RungCache, choose, metrics, run_rung
from cablesys.ladder import estimate as est
from cablesys.ladder.rungs import rung_scene
from cablesys.scene import (
    dale_scene,
    heavy_wire_scene,
)
from cablesys.time_domain.run import initial_state

INTEGRATORS = ("cvodes", "cvodes-adams", "idas", "rk", "rk-stable")
RESOLVED_FRACTION = 0.1   # the factor-2 check applies to actual errors above this fraction of the tolerance


def heave_300m(period: float, duration: float, output_step: float = 0.05) -> object:
    """The 300 m wire / 2 t sphere scene of issue 11 (``heave_300m.toml``), 1 m heave at ``period``."""
    sc = slack_scene(period, duration, output_step)
    return sc.replace(name=f"300 m wire, 2 t sphere, heave T = {period:g} s")


def heavy_cable(duration: float) -> object:
    """1000 m of 16 mm steel wire rope and a 300 kg sphere of 0.5 m (:func:`cablesys.scene.heavy_wire_scene`),
    surged and heaved 1 m at T = 10 s."""
    return heavy_wire_scene(period=10.0, duration=duration)


def _slack_case(duration: float, output_step: float, segments: tuple, integrators: tuple, reference: tuple,
                quick: bool) -> dict:
    """The slack scene; its reference the Richardson limit of RK4 runs at ``reference`` N, finer than auto's
    (compiled in full mode; quick: in the VM, auto's extrapolation capped at N = 16)."""
    sc = heave_300m(6.0, duration, output_step)
    t0 = settled_window_start(sc.top_motion.effective_ramp_s, 6.0, duration)
    return {"key": "wire300_T6", "scene": sc, "segments": segments, "reference": "richardson",
            "reference_integrator": "rk-stable", "reference_segments": reference, "compile_reference": not quick,
            "max_segments": 16 if quick else None, "window_t0": t0, "integrators": integrators}


def cases(quick: bool) -> list[dict]:
    """Scenes with their segment counts and reference (quick: short runs at coarse N, the same code paths)."""
    if quick:
        return [{"key": "dale", "scene": dale_scene(omega_ratio=2.0, duration=10.0), "segments": (2,), "n_ref": 6,
                 "qs_segments": (2,), "integrators": ("cvodes", "rk", "rk-stable")},
                _slack_case(30.0, 0.02, (2, 4, 8), ("cvodes", "rk-stable"), (16, 32), True)]
    # Dale's reference N = 32: N = 16 is 0.05 % from it in body amplitude, but 0.19 % from N = 8, which as the
    # reference's own convergence left auto's 0.1-0.3 % errors unresolved (settled: 40 and 80 s runs agree)
    full = {"compile_auto": True, "auto_repeats": auto_run.REPEATS}     # auto and its rivals compiled, as a user runs them
    return [
        {"key": "dale", "scene": dale_scene(omega_ratio=2.0, duration=40.0), "segments": (2, 4, 8), "n_ref": 32,
         "qs_segments": (2, 4, 8), "integrators": INTEGRATORS, **full},
        {"key": "wire300_T10", "scene": heave_300m(10.0, 40.0), "segments": (5, 10, 20), "n_ref": 40,
         "qs_segments": (5, 10, 20), "integrators": INTEGRATORS, **full},
        _slack_case(360.0, 0.01, (5, 10, 20, 40), INTEGRATORS, (40, 80), False),
        # 120 s: the last 5 periods start after estimate.settling_time (30 s ramp + 14.7 s for the surge to run down
        # the hanging string); a 40 s window measured the arriving front. N = 6, 8 sit on either side of the drag
        # rule's switch at N = 7 (2 -> 1 points per element), where the settled error changes sign
        {"key": "heavy1000", "scene": heavy_cable(120.0), "segments": (5, 6, 8, 10, 20), "n_ref": 40,
         "qs_segments": (5, 6, 8, 10, 20), "integrators": INTEGRATORS, **full},
    ]


def qs_segmented_available() -> bool:
    """Whether the library's quasi-static rung takes elements (``build_rung(scene, "quasi-static",
    segments=N)``, the quasi-static segmented cable): its rung scene then keeps N."""
    try:
        return rung_scene(dale_scene(), "quasi-static", 3).sections[0].cable.segments == 3
    except Exception:       # noqa: BLE001 -- any failure means: not available in this tree
        return False


def plan(case: dict) -> list[tuple]:
    """(rung, N, integrator) of every run: straight rungs with every integrator but the stable-step
    RK4 (their step is stable at the scene's), elements with every one but Adams (non-stiff)."""
    straight = [m for m in case["integrators"] if m != "rk-stable"]
    elements = [m for m in case["integrators"] if m != "cvodes-adams"]
    runs = [("frequency", 1, None)] + [(rung, 1, m) for rung in ("quasi-static", "wang") for m in straight]
    if case.get("qs_segments") and qs_segmented_available():
        runs += [("quasi-static", n, m) for n in case["qs_segments"] for m in straight]
    return runs + [("segmented", n, m) for n in case["segments"] for m in elements]


def _statistics(case: dict, result, period) -> dict:
    """The compared figures: cycle means over the settled window, or the last 5 periods."""
    if case.get("reference") == "richardson":
        return ladder_statistics(result, period, case["window_t0"])
    return metrics.statistics(result, period)


def _run(scene, rung: str, n: int, method: str | None, cache: RungCache) -> tuple:
    """(result or None, row) with wall time, steps and failure; ``rk-stable`` is RK4 at its
    stability step (h |lambda|_max = 2, issue 11's choice), computed at the initial state."""
    row = {"rung": rung, "segments": n, "integrator": method or "periodic"}
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NumericalWarning)
            if method == "rk-stable":
                model, sc = cache.model(scene, rung, n), rung_scene(scene, rung, n)
                spo = stable_steps_per_output(model, sc, initial_state(sc, model, model.parameters(sc)), margin=2.0)
                row["steps_per_output"] = spo = max(spo, scene.numerics.steps_per_output)
                scene, method = scene.with_numerics(steps_per_output=spo), "rk"
            t0 = time.perf_counter()
            r = (run_rung(scene, rung, n, cache=cache) if rung == "frequency"
                 else run_rung(scene, rung, n, cache=cache, method=method))
    except (RuntimeError, ValueError, FloatingPointError) as err:   # rejected model / solver failure: marked
        row.update(success=False, failure=f"{type(err).__name__}: {str(err)[:300]}", wall_s=time.perf_counter() - t0)
        return None, row
    row.update(success=bool(r.success), failure="" if r.success else r.message[:300],
               wall_s=float(r.stats.get("wall_s", r.stats.get("wall_time_s", time.perf_counter() - t0))),
               total_s=time.perf_counter() - t0, nsteps=int(r.stats.get("nsteps", 0) or 0))
    return r, row


def _measured(case, scene, rung, n, method, period, cache) -> dict:
    """One run's row with its statistics (or marked failed)."""
    r, row = _run(scene, rung, n, method, cache)
    if r is not None and r.success and r.time[-1] >= scene.output_times[-1] - 1e-9:
        row["statistics"] = _statistics(case, r, period)
    else:
        row["success"] = False
        row["failure"] = row.get("failure") or "did not reach the end"
    return row


def _with_errors(row: dict, ref_stats: dict) -> dict:
    if "statistics" in row and ref_stats is not None:
        e = metrics.errors(row["statistics"], ref_stats)
        row["error_body"], row["error_tension"] = e["body"], e["tension"]
    return row


def study_case(case: dict) -> dict:
    scene = case["scene"]
    period = metrics.forcing_period(scene)
    cache = RungCache()
    rows = []
    for rung, n, method in plan(case):
        rows.append(_measured(case, scene, rung, n, method, period, cache))
        print(f"    ran {rung} N={n} {method}: wall {rows[-1]['wall_s']:.3g} s {'' if rows[-1]['success'] else 'FAILED'}",
              flush=True)
    if case.get("reference") == "richardson":
        reference = slack_reference(case, rows, period, cache)
    else:
        ref = _measured(case, scene, "segmented", case["n_ref"], "cvodes", period, cache)
        half = _measured(case, scene, "segmented", case["n_ref"] // 2, "cvodes", period, cache)
        ok = lambda r: "statistics" in r
        reference = dict(ref, kind="segmented", convergence_vs_half=metrics.errors(half["statistics"], ref["statistics"])
                         if ok(ref) and ok(half) else None)
        if not ok(ref):
            reference["error"] = "reference run failed"
    ref_stats = reference.get("statistics")
    if ref_stats is None:
        return {"scene": scene.name, "reference": reference, "rows": rows, "error": reference.get("error")}
    for r in rows:
        _with_errors(r, ref_stats)
    res = {"scene": scene.name, "period_s": period, "reference": reference, "reference_statistics": ref_stats, "rows": rows}
    res["auto"] = assess_auto(case, res, ref_stats, cache)
    res.update(verdicts(res))
    return res


def rerun_reference(case: dict, res: dict) -> None:
    """The slack case's reference runs again, and every kept row's errors against it."""
    res["reference"] = slack_reference(case, res["rows"], res["period_s"], RungCache())
    res["reference_statistics"] = res["reference"].get("statistics")
    for r in res["rows"]:
        _with_errors(r, res["reference_statistics"])


def _row_estimate(errs: dict, r: dict) -> dict:
    if r["rung"] == "segmented":
        return est.segmented_error(errs, r["segments"])
    if r["rung"] == "quasi-static" and r["segments"] > 1:
        qs = getattr(est, "quasistatic_segmented_error", None)
        return qs(errs, r["segments"]) if qs else {}
    return errs.get(r["rung"]) or {}


def assess_auto(case: dict, res: dict, ref_stats: dict | None, cache: RungCache | None = None) -> dict:
    """Auto's choice, the estimate it states, its actual error and the verdicts of issue 12's checks.

    Every row gets the a-priori estimate of its rung (``estimate_body``, ``estimate_tension``). Auto is
    measured on its own run (:mod:`_ladder_auto`: ``simulate`` as a user calls it, with its integrator,
    rtol and a posteriori checks, compiled in full mode), on the rows' statistics against the same reference;
    its stated estimate is what it reports (a posteriori where it checked). The factor-2 check applies where
    the actual error is resolved: above RESOLVED_FRACTION of the tolerance and above twice the reference's
    own uncertainty; below that the estimate must only be within the tolerance too. The rungs it is
    compared with for "beaten" run forced, the same way (:func:`_ladder_auto.candidates`).
    """
    scene, period, rows = case["scene"], res.get("period_s"), res["rows"]
    cache = cache if cache is not None else RungCache()
    t0 = time.perf_counter()
    choice = choose(scene)
    choose_s = time.perf_counter() - t0
    errs = choice.numbers["estimates"]
    for r in rows:
        e = _row_estimate(errs, r)
        r["estimate_body"], r["estimate_tension"] = e.get("body"), e.get("tension")
    if case.get("reference") == "richardson":       # auto extrapolates: measured on what it reports
        return assess_slack_auto(case, res, choice, choose_s, RESOLVED_FRACTION, cache)
    # auto's own run, as a user runs it (compiled in full mode), on the table's statistics and reference;
    # a choice at the reference's own N is not measured
    compiled, repeats = case.get("compile_auto", False), case.get("auto_repeats", 1)
    stats_of = lambda r: _statistics(case, r, period)
    result, info, got, act, stated = auto_run.assess(scene, stats_of, ref_stats, compiled, repeats)
    m = result.stats["model"]
    if m["name"] == "segmented" and m["segments"] >= case["n_ref"]:
        act = {"body": None, "tension": None}
    rows[:] = [r for r in rows if not r.get("auto")] + [auto_run.auto_row(scene, info, result, act, stated, statistics=got)]
    mine = (m["name"], m["segments"] if m["name"] in ("segmented", "quasi-static") else 1)
    tol = choice.numbers["tolerance"]
    cands = auto_run.candidates(scene, rows, mine, tol, stats_of, ref_stats, compiled, repeats)
    conv = res.get("reference", {}).get("convergence_vs_half") or {}
    check = estimate_check(act, stated, tol, conv, RESOLVED_FRACTION)
    final = dataclasses.replace(choice, name=m["name"], segments=m["segments"])
    check["lower_rungs_within_half_tolerance"] = cheaper_within(rows, final, tol, (scene.numerics.integrator,))
    how = re.search(r"a posteriori \([^)]*\)", m["reason"])
    how = how.group(0) if how else "a priori"
    return {"name": m["name"], "segments": m["segments"], "integrator": info["integrator"], "reason": m["reason"],
            "estimated_error": choice.estimated_error, "stated_estimate": stated, "stated_how": how,
            "choose_s": choose_s, "actual_error": act, "estimates": errs, "tolerance": tol, "check": check,
            "candidates": cands, **{k: info[k] for k in ("ladder_timing", "ladder_timing_first", "wall_s", "compiled",
                                                          "methods", "rtols", "calls", "load_1min")}}


def _fmt(d) -> str:
    f = lambda v: "-" if v is None else f"{v:.2g}"
    return "{" + ", ".join(f"{k} {f(v)}" for k, v in (d or {}).items()) + "}"


def _report(key: str, res: dict) -> None:
    a = res.get("auto", {})
    print(f"{key}: auto -> {a.get('name')} N={a.get('segments')}; stated ({a.get('stated_how')}) "
          f"{_fmt(a.get('stated_estimate'))} vs actual {_fmt(a.get('actual_error'))}", flush=True)
    print(f"    cheaper within tolerance: {res.get('cheaper_rung_within_tolerance')}", flush=True)
    print(f"    estimate ratio: {res.get('estimate_ratio')}", flush=True)
    ref = res.get("reference", {})
    if ref.get("kind") == "richardson":
        print(f"    reference: Richardson limit of N = {ref.get('segments')}: y_amp {ref['statistics']['y_b_amplitude']:.4f} m, "
              f"top max {ref['statistics']['tension_top_max']:.0f} N, observed order {ref.get('observed_order')}", flush=True)
    for r in res["rows"]:
        print(f"    {run_name(r):18s} {r['integrator']:12s} wall {r['wall_s']:8.3g} s  estimated "
              f"{_fmt({'b': r.get('estimate_body'), 't': r.get('estimate_tension')})} actual "
              f"{_fmt({'b': r.get('error_body'), 't': r.get('error_tension')})} {r.get('failure', '')[:60]}", flush=True)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    # Freshly built models run in CasADi's VM: compiling each (rung, N, integrator) to C costs 30-60 s,
    # far more than these runs; compiled code is about 3x faster for every rung alike.
    os.environ.setdefault("CABLESYS_COMPILE", "0")
    only = os.environ.get("MODEL_LADDER_ONLY", "").split(",") if os.environ.get("MODEL_LADDER_ONLY") else None
    path = args.out / "model_ladder.json"
    reestimate = bool(os.environ.get("MODEL_LADDER_REESTIMATE"))
    out = json.loads(path.read_text()) if (only or reestimate) and path.exists() else {}
    for case in cases(args.quick):
        if only and case["key"] not in only:
            continue
        t0 = time.perf_counter()
        if reestimate and case["key"] in out and out[case["key"]].get("rows"):
            # the runs are kept; auto's choice, the estimates and the checks are made again (estimate changes)
            res = out[case["key"]]
            if case.get("reference") == "richardson" and res.get("reference", {}).get("segments") != list(case["reference_segments"]):
                rerun_reference(case, res)      # the reference runs are new (finer than auto's): the rows' errors again
            res["auto"] = assess_auto(case, res, res.get("reference_statistics"))
            res.update(verdicts(res))
        else:
            res = study_case(case)
            res["study_s"] = time.perf_counter() - t0        # the whole scene: every run, build included
        out[case["key"]] = res
        if res["rows"] and "auto" in res:
            plot_case(res, args.out / f"model_ladder_{case['key']}.png")
        _report(case["key"], res)
        write_json(path, out)           # after every scene: a long study keeps what it has
    return 0


if __name__ == "__main__":
    sys.exit(main())
