"""Issue 12's checks on the rows of studies/model_ladder.py: which run is the cheapest within the
tolerance against auto's, and whether a lower rung beats auto's choice. Pure functions of the rows
(dicts with ``rung``, ``segments``, ``integrator``, ``wall_s``, ``error_body``, ``error_tension``)."""

from __future__ import annotations

import math

from cablesys.ladder import metrics
from cablesys.ladder.choice import SAFETY

NOISE_FACTOR = 2.0        # a cheaper run "beats" auto's when its time is below 1/2 of auto's (shared machine)
QUANTITY_TOL = {"body": 0.01, "tension": 0.02}    # the ladder's default tolerance per group (choice.tolerances)
RESOLVED = 0.05      # an actual error below this fraction of its tolerance need not be resolved by the estimate


def quantity_rows(actual: dict, stated: dict, held=None, tol: dict = QUANTITY_TOL) -> list:
    """Issue 22's two verdicts per reported quantity, sorted by name: ``actual`` {quantity: relative error} of auto
    against a reference (:func:`cablesys.ladder.metrics.quantity_errors`), ``stated`` auto's
    ``model.estimated_error_per_quantity`` (missing or ``None`` where the run was not checked a posteriori),
    ``held`` the quantities auto was asked to hold (``None``: all). Each row: ``within_tolerance`` (actual <= its
    group's tolerance), ``stated_at_least_half`` (stated >= actual / 2, the issue's strict inequality; ``None``
    without a statement) and ``stated_honest`` (the same, or an actual error below RESOLVED x the tolerance, which
    no estimate need resolve)."""
    rows = []
    for k, e in sorted(actual.items()):
        s = (stated or {}).get(k)
        t = tol[metrics.group(k)]
        half = None if s is None else bool(s >= 0.5 * e)
        rows.append({"quantity": k, "actual": e, "stated": s, "tolerance": t, "within_tolerance": e <= t,
                     "held": held is None or k in held, "stated_at_least_half": half,
                     "stated_honest": None if s is None else bool(half or e <= RESOLVED * t)})
    return rows


def _same(r: dict, rung: str, n: int) -> bool:
    return r["rung"] == rung and (r["segments"] == n or rung not in ("segmented", "quasi-static"))


def find_row(rows, rung, n, integrators):
    return next((r for r in rows if _same(r, rung, n) and r["integrator"] in integrators
                 and r.get("error_body") is not None), None)


def ladder_rank(rung: str, n: int) -> float:
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
    mine = ladder_rank(choice.name, choice.segments)
    return [run_name(r) for r in rows if r["integrator"] in integrators and r.get("error_body") is not None
            and r["rung"] != "frequency" and ladder_rank(r["rung"], r["segments"]) < mine
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
    return None if r is None else {"run": r.get("run") or run_name(r), "integrator": r["integrator"], "wall_s": r["wall_s"],
                                   "error_body": r.get("error_body"), "error_tension": r.get("error_tension")}


def _costs(t: dict) -> tuple:
    """(the chosen run alone, the run and its a posteriori checks) of a ``ladder_timing``."""
    return t["run_s"], t["run_s"] + t["check_s"]


def beaten_by(auto: dict, cands: list, tol: dict, fraction: float = 1.0) -> list:
    """The forced runs (:func:`_ladder_auto.candidates`, run as auto runs its rung) within ``fraction`` x the
    tolerance by their own errors that cost less than 1 / NOISE_FACTOR of auto's, on the run alone or on
    the run with its a posteriori checks (either: the stricter test for auto)."""
    mine = _costs(auto["ladder_timing"])
    out = []
    for c in cands:
        if c.get("error_body") is None or c["error_body"] > fraction * tol["body"] or c["error_tension"] > fraction * tol["tension"]:
            continue
        theirs = _costs(c["ladder_timing"])
        if any(NOISE_FACTOR * t < m for t, m in zip(theirs, mine)):
            out.append(c)
    return out


def verdicts(res: dict) -> dict:
    """Issue 12's two checks on this scene, from the rows, auto's own run and the forced runs.

    ``cheaper_rung_within_tolerance``: auto's own run (compiled, as a user runs it) against every other
    rung and N at or below auto's on the ladder whose table row is within the tolerance, each run forced by the same code with the same
    integrator rule (``candidates``, compiled as auto): auto is ``beaten`` when one of them is within the
    tolerance by its own errors at under 1 / NOISE_FACTOR of auto's wall time, on the run alone or on the
    run with its a posteriori checks (both measured as ``ladder_timing``, least of a few calls); the same
    at SAFETY x the tolerance, which auto aims at. ``cheapest`` is the table's (CasADi VM, study's rtol:
    not auto's terms, for reference). ``estimate_ratio``: auto's stated estimate over its actual error,
    per figure, and whether it is within a factor 2 (``None`` where the actual error is not measured).
    """
    a = res["auto"]
    tol = a["tolerance"]
    within = [r for r in res["rows"] if r.get("error_body") is not None and r["rung"] != "frequency"
              and not r.get("auto") and r["integrator"] != a.get("integrator")
              and r["error_body"] <= tol["body"] and r["error_tension"] <= tol["tension"]]
    mine = next((r for r in res["rows"] if r["integrator"] == a.get("integrator") and _same(r, a["name"], a["segments"])), None)
    cands = a.get("candidates") or []
    measured = mine is not None and mine.get("error_body") is not None and "ladder_timing" in a
    beat = beaten_by(a, cands, tol) if measured else None
    beat_aim = beaten_by(a, cands, tol, SAFETY) if measured else None
    run_s, with_checks = _costs(a["ladder_timing"]) if "ladder_timing" in a else (None, None)
    cheaper = {"auto": None if mine is None else dict(_brief(mine), run_s=run_s, run_and_checks_s=with_checks),
               "cheapest": _brief(min(within, key=lambda r: r["wall_s"], default=None)),
               "candidates": [dict(_brief(c), run_s=_costs(c["ladder_timing"])[0],
                                   run_and_checks_s=_costs(c["ladder_timing"])[1]) for c in cands],
               "beaten": None if beat is None else bool(beat), "beaten_by": [c["run"] for c in beat or []],
               "beaten_at_safety_tolerance": None if beat_aim is None else bool(beat_aim),
               "beaten_at_safety_tolerance_by": [c["run"] for c in beat_aim or []], "safety": SAFETY,
               "noise_factor": NOISE_FACTOR,
               "rule": f"beaten: another rung (or N) within the tolerance (or within {SAFETY:g} x it, which auto aims "
                       f"at), run forced by simulate as auto runs its own rung (its integrator rule, rtol and a "
                       f"posteriori check; compiled like auto's), at or below auto's rung on the ladder, by its own errors, in < 1/{NOISE_FACTOR:g} of auto's "
                       f"time on the run alone or on the run with its a posteriori checks (least of a few calls each; "
                       f"choosing excluded, the same for both); the table's VM rows at the study's rtol are not "
                       f"compared (other integrator, other rtol, not compiled). Candidates: the (rung, N) whose table "
                       f"row is within the tolerance; frequency rung excluded (it answers the steady-amplitude question)"}
    ratio = {}
    for k in ("body", "tension"):
        act, st = a["actual_error"].get(k), a["stated_estimate"].get(k)
        r = st / act if act and st is not None and math.isfinite(st) else None
        ratio[k] = {"stated": st, "actual": act, "ratio": r, "within_2x": None if r is None else bool(0.5 <= r <= 2.0),
                    "resolved": a["check"][k].get("resolved")}
    return {"cheaper_rung_within_tolerance": cheaper, "estimate_ratio": ratio}
