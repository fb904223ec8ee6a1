"""Issue 12's checks on the rows of studies/model_ladder.py: which run is the cheapest within the
tolerance against auto's, and whether a lower rung beats auto's choice. Pure functions of the rows
(dicts with ``rung``, ``segments``, ``integrator``, ``wall_s``, ``error_body``, ``error_tension``)."""

from __future__ import annotations

import math

from cablesys.ladder.choice import SAFETY

NOISE_FACTOR = 2.0        # a cheaper run "beats" auto's when its wall time is below 1/2 of auto's (shared machine)


def _same(r: dict, rung: str, n: int) -> bool:
    return r["rung"] == rung and (r["segments"] == n or rung not in ("segmented", "quasi-static"))


def find_row(rows, rung, n, integrators):
    return next((r for r in rows if _same(r, rung, n) and r["integrator"] in integrators
                 and r.get("error_body") is not None), None)


def _rank(rung: str, n: int) -> float:
    """Ladder order of cost: the straight-cable rungs, then the cable in N elements (quasi-static below
    the dynamic one at the same N)."""
    if rung in ("quasi-static", "wang") and n <= 1:
        return 1
    return 1 + n - (0.5 if rung == "quasi-static" else 0.0)


def run_name(r: dict) -> str:
    return r["rung"] + (f" N={r['segments']}" if r["rung"] == "segmented" or r["segments"] > 1 else "")


def cheaper_within(rows, choice, tol, integrators) -> list:
    """Rungs below auto's choice on the ladder (straight cables, fewer elements) whose actual errors are
    within half the tolerance (auto aims at half of it: choice.SAFETY); the frequency rung answers
    another question (a steady amplitude) and is left out."""
    mine = _rank(choice.name, choice.segments)
    return [run_name(r) for r in rows if r["integrator"] in integrators and r.get("error_body") is not None
            and r["rung"] != "frequency" and _rank(r["rung"], r["segments"]) < mine
            and r["error_body"] <= 0.5 * tol["body"] and r["error_tension"] <= 0.5 * tol["tension"]]


def estimate_check(act: dict, stated: dict, tol: dict, conv: dict, resolved_fraction: float) -> dict:
    """Per figure (body, tension): whether auto's stated estimate is within a factor 2 of its actual error
    where that is resolved (above ``resolved_fraction`` of the tolerance and twice the reference's own
    uncertainty ``conv``), else whether the estimate is within the tolerance too; and ``within_tolerance``."""
    check = {}
    for k in ("body", "tension"):
        a, e = act[k], stated[k]
        floor = max(resolved_fraction * tol[k], 2 * (conv.get(k) or 0.0))
        if a is None or e is None or not math.isfinite(e):
            check[k] = {"resolved": None, "ratio": None, "pass": None}
            continue
        resolved = a > floor
        ratio = e / a if a > 0 else math.inf
        ok = (0.5 <= ratio <= 2.0) if resolved else (e <= tol[k])
        check[k] = {"resolved": resolved, "resolution": floor, "ratio": ratio, "pass": bool(ok),
                    "strict_pass": bool(0.5 <= ratio <= 2.0)}
    check["within_tolerance"] = None if act["body"] is None else bool(act["body"] <= tol["body"] and act["tension"] <= tol["tension"])
    return check


def _brief(r: dict | None) -> dict | None:
    return None if r is None else {"run": run_name(r), "integrator": r["integrator"], "wall_s": r["wall_s"],
                                   "error_body": r.get("error_body"), "error_tension": r.get("error_tension")}


def verdicts(res: dict) -> dict:
    """Issue 12's two checks on this scene, from the rows and auto's choice.

    ``cheaper_rung_within_tolerance``: the run of least wall time whose actual errors are within the
    tolerance, over every time-domain rung and integrator (``cheapest``) and with auto's integrator
    (``cheapest_same_integrator``), against auto's run; auto is ``beaten`` when a run of another rung
    with its integrator is within the tolerance in less than 1 / NOISE_FACTOR of its wall time.
    ``estimate_ratio``: auto's stated estimate over its actual error, per figure, and whether it is
    within a factor 2 (``None`` where the actual error is not measured).
    """
    a = res["auto"]
    tol = a["tolerance"]
    integ = (a.get("integrator", "cvodes"), "periodic")
    within = [r for r in res["rows"] if r.get("error_body") is not None and r["rung"] != "frequency"
              and r["error_body"] <= tol["body"] and r["error_tension"] <= tol["tension"]]
    mine = find_row(res["rows"], a["name"], a["segments"], integ)
    cheapest = min(within, key=lambda r: r["wall_s"], default=None)
    same = min((r for r in within if r["integrator"] in integ), key=lambda r: r["wall_s"], default=None)
    beaten = (None if mine is None else bool(same is not None and not _same(same, a["name"], a["segments"])
                                                 and same["wall_s"] * NOISE_FACTOR < mine["wall_s"]))
    # auto aims at SAFETY x the tolerance (its estimate is trusted to a factor 2): the same check there
    aim = [r for r in within if r["integrator"] in integ and r["error_body"] <= SAFETY * tol["body"]
           and r["error_tension"] <= SAFETY * tol["tension"]]
    same_aim = min(aim, key=lambda r: r["wall_s"], default=None)
    beaten_aim = (None if mine is None else bool(same_aim is not None and not _same(same_aim, a["name"], a["segments"])
                                                     and same_aim["wall_s"] * NOISE_FACTOR < mine["wall_s"]))
    cheaper = {"auto": _brief(mine), "cheapest": _brief(cheapest), "cheapest_same_integrator": _brief(same),
               "beaten": beaten, "cheapest_within_safety_tolerance": _brief(same_aim),
               "beaten_at_safety_tolerance": beaten_aim, "safety": SAFETY,
               "rule": f"beaten: another rung within the tolerance (or within {SAFETY:g} x it, which auto aims at) "
                       f"with auto's integrator in < 1/{NOISE_FACTOR:g} of auto's wall time (frequency rung "
                       f"excluded: it answers the steady-amplitude question)"}
    ratio = {}
    for k in ("body", "tension"):
        act, st = a["actual_error"].get(k), a["stated_estimate"].get(k)
        r = st / act if act and st is not None and math.isfinite(st) else None
        ratio[k] = {"stated": st, "actual": act, "ratio": r, "within_2x": None if r is None else bool(0.5 <= r <= 2.0),
                    "resolved": a["check"][k].get("resolved")}
    return {"cheaper_rung_within_tolerance": cheaper, "estimate_ratio": ratio}
