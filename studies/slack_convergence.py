"""The slack path's stated error against its actual one, per quantity, on slack scenes (issue 28, issue 22's checks).

    python studies/slack_convergence.py --out DIR [--quick] [--only NAMES] [--reuse-reference JSON ...]
    python studies/slack_convergence.py --out DIR --assemble JSON ...     (runs per scene group in one JSON and figure)

On a slack scene auto (``cablesys.simulate(scene)``, as a user runs it, compiled in full mode) runs the segmented cable
at N / 4, N / 2, N and reports statistics extrapolated in N (Richardson 1911, first order: the snap front is carried
by one element; :mod:`cablesys.ladder.extrapolation`, :mod:`cablesys.ladder.richardson`) with a stated error per group
(``model.estimated_error``: body, tension; :func:`cablesys.ladder.metrics.errors`) and, where the ladder gives one, per
quantity (``model.estimated_error_per_quantity``). Here that statement is tested against a reference finer than auto's
runs:

- the segmented cable at REFERENCE_N (full: 32, 64, 128 elements) stepped by RKC (:mod:`cablesys.time_domain.rkc`) at
  1 / REFINE of the axial travel time across one element (auto's runs step at the whole travel time,
  :func:`cablesys.ladder.extrapolation.element_travel_time`), sampled at 1 / REFINE of auto's statistics step
  (:func:`cablesys.ladder.extrapolation.statistics_step`) over the statistics window, maxima refined between samples
  as auto's (:func:`cablesys.ladder.richardson.statistics`): an independent route in time step and sampling; run in
  pieces started from the last state of the piece before at the same step, so that N = 128 on the fine grid fits the
  memory limit of one run (:func:`reference_run`; pieces of 11 or 2 give the same statistics to 5e-10 at N = 16);
- the reference statistics are the first-order Richardson limit of its last two N (the order auto assumes, checked:
  ``observed_order`` of the three reference N); its own uncertainty per quantity follows auto's rules for its own
  statement (:func:`score_reference`: the remainder estimate where the order is in range, the whole difference where
  not) and its raw convergence is the difference of its last two N (``convergence_last_two``); its time step is
  checked at the smallest reference N against half that step (``time_step_check``);
- actual error per quantity: :func:`cablesys.ladder.metrics.quantity_errors` of auto's extrapolated statistics
  against the reference (each relative to its own value, floors 1 cm and 1 % of the top tension); per group:
  :func:`cablesys.ladder.metrics.errors` (the normalisation of auto's stated body/tension numbers).

The claim (the criterion of ``studies/ladder_generated.py``, :func:`_ladder_checks.quantity_rows`): every quantity
within its group's tolerance (1 % body, 2 % tension) and its stated error at least half its actual one
(``stated_at_least_half``; ``stated_honest`` also passes an actual error below RESOLVED x the tolerance, or below twice
the reference's own uncertainty, which no statement can be checked on). Where the ladder states no per-quantity error
the group's number is the statement (``stated_source``).

Scenes (:func:`scenes`): ``light_lift``, the packaged light-cage lift (``cablesys scene --example light-lift``) run for
DURATION s (its current, its sea of seed 1 and its RAO); ``light_lift_harsh`` and ``light_lift_violent``, the same lift
in harsher seas (HARSH, VIOLENT; the example's text with Hs and Tp replaced), where the cage's line goes slack and snaps
(least tensions 0 N in the window).
Quick mode (for the test, in CasADi's VM): the light lift over QUICK_DURATION s, auto at a loose tolerance with its
smallest extrapolation N lowered to QUICK_MIN_SEGMENTS (runs at 2, 4, 8), the reference at the same N = 2, 4, 8 (the
finer step and sampling alone: no finer N), and ``own_pair``: auto's stated time-series error per quantity against the
difference of the study's own runs at N / 2 and N, which is the first-order estimate it states.

Writes ``slack_convergence.json`` (per scene: auto's plan, statements, statistics and wall time; the reference runs and
their convergence; one row per quantity; totals, load average) and ``slack_convergence.png`` (stated against actual per
quantity, log-log, the diagonal and the factor-2 band).
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
import tomllib
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402
from _ladder_checks import QUANTITY_TOL, RESOLVED, quantity_rows  # noqa: E402

import cablesys  # noqa: E402
from cablesys.errors import NumericalWarning, ParameterError  # noqa: E402
from cablesys.examples import example_text  # noqa: E402
from cablesys.ladder import RungCache, metrics  # noqa: E402
from cablesys.ladder import extrapolation as X  # noqa: E402
from cablesys.ladder import richardson as R  # noqa: E402
from cablesys.ladder.run_settings import start  # noqa: E402
from cablesys.ladder.rungs import rung_scene  # noqa: E402
from cablesys.scene import scene_from_dict  # noqa: E402

DURATION = {"light_lift": 120.0, "light_lift_harsh": 100.0, "light_lift_violent": 100.0}   # s of each full-mode run
QUICK_DURATION = 6.0
HARSH = {"hs": 7.0, "tp": 10.0}       # the light lift in Hs 7 m, Tp 10 s (DNV-RP-C205 Table 3-1: very rough)
VIOLENT = {"hs": 9.0, "tp": 11.0}     # and in Hs 9 m, Tp 11 s (high): slack and snapping at both ends
REFERENCE_N = {"full": (32, 64, 128), "quick": (2, 4, 8)}
QUICK_MIN_SEGMENTS = 8                # quick mode: auto's smallest extrapolation N (choice.EXTRAPOLATION_MIN_SEGMENTS)
REFINE = 2                            # reference step and sampling: 1 / REFINE of auto's
QUICK_TOLERANCE = 0.05                # quick mode: a loose tolerance, so that auto's N stays small
TIMESTEP_CHECK_REFINE = 2 * REFINE    # the reference's time-step check: the smallest N again at half its step
PRE_SUB = 20                          # the reference's samples before its statistics window: every PRE_SUB-th
PIECE_BYTES = 0.4 * 1024**3           # series per piece of a reference run (memory estimate of one run)
ALL = ("light_lift", "light_lift_harsh", "light_lift_violent")


@contextlib.contextmanager
def smallest_extrapolation(n: int | None):
    """Auto's smallest extrapolation N set to ``n`` inside (quick mode; None: unchanged)."""
    from cablesys.ladder import choice
    old = choice.EXTRAPOLATION_MIN_SEGMENTS
    choice.EXTRAPOLATION_MIN_SEGMENTS = n or old
    try:
        yield
    finally:
        choice.EXTRAPOLATION_MIN_SEGMENTS = old


def _compile(on: bool):
    """CABLESYS_COMPILE for the runs that follow (read at each build: cablesys.compiled)."""
    os.environ["CABLESYS_COMPILE"] = "1" if on else "0"


def light_lift(duration: float, sea: dict | None = None):
    """The packaged light-cage lift (its current included), ``duration`` s, in the sea ``sea`` ({hs, tp}, m and s;
    default the example's Hs 5 m, Tp 9 s)."""
    text = example_text("light-lift")
    if sea is not None:
        for old, new in (("hs = 5.0 ", f"hs = {sea['hs']:g} "), ("tp = 9.0 ", f"tp = {sea['tp']:g} "),
                         ("Hs 5 m Tp 9 s", f"Hs {sea['hs']:g} m Tp {sea['tp']:g} s")):
            if old not in text:
                raise ValueError(f"light_lift: the packaged example no longer holds {old!r}")
            text = text.replace(old, new)
    return scene_from_dict(tomllib.loads(text)).with_numerics(duration=duration)


def scenes(quick: bool, only=None) -> list:
    """[(name, scene, description)] of the study."""
    if quick:
        return [("light_lift", light_lift(QUICK_DURATION), f"packaged light-lift example, {QUICK_DURATION:g} s")]
    make = {"light_lift": (lambda d: light_lift(d), "packaged light-lift example"),
            "light_lift_harsh": (lambda d: light_lift(d, HARSH),
                                 f"light-lift example in Hs {HARSH['hs']:g} m, Tp {HARSH['tp']:g} s (generated)"),
            "light_lift_violent": (lambda d: light_lift(d, VIOLENT),
                                   f"light-lift example in Hs {VIOLENT['hs']:g} m, Tp {VIOLENT['tp']:g} s (generated)")}
    names = ALL if not only else only
    return [(n, make[n][0](DURATION[n]), f"{make[n][1]}, {DURATION[n]:g} s") for n in names]


class Series:
    """The series of one run the statistics read (body coordinates, end tensions) on its output times: a record
    assembled from the run's pieces (:func:`reference_run`), read as :func:`cablesys.ladder.richardson.statistics`
    reads a run."""

    def __init__(self, time, data: dict, ramp_s: float):
        self.time, self.data, self.ramp_s = np.asarray(time), data, ramp_s
        self.labels = list(data)

    def __getitem__(self, key):
        return self.data[key]


def _pieces(n_out: int, chunk: int) -> list:
    """[(first, last)] output indices of consecutive pieces of at most ``chunk`` outputs, sharing their ends."""
    out, i = [], 0
    while i < n_out - 1:
        j = min(i + chunk - 1, n_out - 1)
        out.append((i, j))
        i = j
    return out


def reference_run(scene, n: int, cache: RungCache, refine: int = REFINE) -> dict:
    """The segmented cable at ``n`` elements, RKC at 1 / ``refine`` of the element travel time, sampled at 1 /
    ``refine`` of auto's statistics step over the statistics window (before it every PRE_SUB-th sample, the same
    steps); its statistics (:func:`cablesys.ladder.richardson.statistics`).

    The run is made in pieces of at most PIECE_BYTES of series (:func:`cablesys.time_domain.record.run_memory_bytes`),
    each started from the last state of the one before at the same step (a fixed-step method: the same steps as one
    run), so that a fine reference fits the memory limit of one run; only the body and end-tension series are kept."""
    from dataclasses import replace

    from cablesys import statistics as stat
    from cablesys.time_domain import simulate
    from cablesys.time_domain.record import run_memory_bytes
    period, ramp = metrics.forcing_period(scene), scene.top_motion.effective_ramp_s
    fine = scene.with_numerics(output_step=X.statistics_step(scene) / refine)
    sc = rung_scene(fine, "segmented", n)
    model = cache.model(fine, "segmented", n)
    x = start(sc, model, cache)
    s = X.settings(sc, model, "rkc", x, base_step=scene.numerics.output_step,
                   max_step=X.element_travel_time(sc) / refine)
    t = np.asarray(sc.output_times)
    t0w = stat.window(t, period, ramp)[0]
    i0 = int(np.searchsorted(t, t0w - 1e-9 * max(1.0, t0w)))
    pre = (t[: i0 + 1:PRE_SUB] if i0 % PRE_SUB == 0 else np.append(t[: i0 + 1:PRE_SUB], t[i0])) if i0 > 0 else t[:1]
    per_output = 2 * model.nq + len(model.slack_index) + len(model.output_labels) + 2
    chunk = max(16, int(PIECE_BYTES / run_memory_bytes(1, 1, per_output)))
    grids = [(pre[a:b + 1], PRE_SUB) for a, b in _pieces(len(pre), chunk)] if len(pre) > 1 else []
    grids += [(t[i0 + a:i0 + b + 1], 1) for a, b in _pieces(len(t) - i0, chunk)]
    keep = [k for k in model.output_labels if metrics.base_label(k) in metrics.BODY + metrics.TENSIONS]
    times, data = [t[:1]], {k: [] for k in keep}
    load = os.getloadavg()[0]
    t_wall, c0 = time.perf_counter(), time.process_time()
    ok, message = True, ""
    for j, (g, sub) in enumerate(grids):
        settings = replace(s, steps_per_output=s.steps_per_output * sub)
        sim = cache.simulator(model, g, settings)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NumericalWarning)
            r = simulate(sc, model=model, simulator=sim, x0=x)
        if not r.success:
            ok, message = False, r.message
            break
        for k in keep:
            data[k].append(np.asarray(r[k])[(0 if j == 0 else 1):])
        times.append(np.asarray(r.time)[1:])
        x = np.asarray(r.states)[:, -1]
    row = {"segments": n, "method": s.method, "stages": s.stages, "steps_per_output": s.steps_per_output,
           "step_s": fine.numerics.output_step / s.steps_per_output, "output_step_s": fine.numerics.output_step,
           "window_start_s": float(t[i0]), "pieces": len(grids), "compiled": bool(s.compiled), "success": ok,
           "wall_s": time.perf_counter() - t_wall, "cpu_s": time.process_time() - c0, "load_1min": load}
    if ok:
        rec = Series(np.concatenate(times), {k: np.concatenate(v) for k, v in data.items()}, ramp)
        row["statistics"] = R.statistics(rec, period, ramp)
    else:
        row["message"] = message
    return row


def reference(scene, ns: tuple, cache: RungCache) -> dict:
    """The reference runs at ``ns`` (:func:`reference_run`), scored by :func:`score_reference`; ``time_step_check``:
    the smallest N again at half the step, the change of each quantity (:func:`cablesys.ladder.metrics.quantity_errors`)."""
    runs = [reference_run(scene, n, cache) for n in ns]
    out = {"segments": list(ns), "refine": REFINE, "runs": runs}
    if not all(r["success"] for r in runs):
        return dict(out, error="a reference run failed: " + "; ".join(r.get("message", "") for r in runs
                                                                      if not r["success"]))
    score_reference(out, _floor(scene))
    half = reference_run(scene, ns[0], cache, refine=TIMESTEP_CHECK_REFINE)
    if half["success"]:
        change = metrics.quantity_errors(runs[0]["statistics"], half["statistics"])
        out["time_step_check"] = {"segments": ns[0], "refine": [REFINE, TIMESTEP_CHECK_REFINE],
                                  "wall_s": half["wall_s"], "largest": max(change.values()), "per_quantity": change}
    return out


def _floor(scene) -> float:
    return max(s.cable.tension_floor for s in scene.sections)


def score_reference(ref: dict, floor: float) -> dict:
    """The reference statistics and their uncertainty from its runs (``ref["runs"]``, coarsest first), in place.

    Three N or more: the first-order Richardson limit L of the last two (minima at least the tension ``floor``, N),
    per quantity its observed order p over the last three (:func:`cablesys.ladder.richardson.observed_orders`) and
    its uncertainty by auto's own rules (:mod:`cablesys.ladder.richardson`): p within ORDER_RANGE, the remainder
    estimate |L_prev - L| / (2^2 - 1); p above it with differences of one sign (converging faster than first order),
    the last correction |L - f_finest|; otherwise (not asymptotic) the larger of the whole |L_prev - L| and that
    correction (``uncertainty_rule``). Two N: the finer run as it is, uncertainty its difference to the coarser one."""
    st = [r["statistics"] for r in ref["runs"]]
    ns = [r["segments"] for r in ref["runs"]]
    ref["convergence_last_two"] = metrics.quantity_errors(st[-2], st[-1])
    ref["convergence_last_two_group"] = metrics.errors(st[-2], st[-1])
    if len(st) < 3:
        ref.update(kind="finest run", statistics=st[-1], uncertainty=ref["convergence_last_two"],
                   uncertainty_group=ref["convergence_last_two_group"], observed_order=None)
        return ref
    lim = R.limits(st[-2], st[-1], ratio=ns[-1] / ns[-2])
    prev = R.limits(st[-3], st[-2], ratio=ns[-2] / ns[-3])
    for d in (lim, prev):            # a minimum's limit below the tension floor: the floor (as auto's)
        d.update({k: max(v, floor) for k, v in d.items() if k.endswith("_min")})
    orders = R.observed_orders(*st[-3:])
    d_lim, corr = metrics.quantity_errors(prev, lim), metrics.quantity_errors(st[-1], lim)
    q = 2.0 ** R.REMAINDER_ORDER - 1.0
    unc, rule = {}, {}
    for k in d_lim:
        p = orders.get(k)
        one_sign = (st[-3][k] - st[-2][k]) * (st[-2][k] - st[-1][k]) > 0
        if p is not None and R.ORDER_RANGE[0] <= p <= R.ORDER_RANGE[1]:
            unc[k], rule[k] = d_lim[k] / q, "remainder"
        elif p is not None and p > R.ORDER_RANGE[1] and one_sign:
            unc[k], rule[k] = corr[k], "faster than first order: the last correction"
        else:
            unc[k], rule[k] = max(d_lim[k], corr[k]), "not asymptotic: the whole difference, at least the correction"
    g_lim, g_corr = metrics.errors(prev, lim), metrics.errors(st[-1], lim)
    ref.update(kind="richardson", statistics=lim, observed_order=orders, uncertainty=unc, uncertainty_rule=rule,
               uncertainty_group={k: max(g_lim[k], g_corr[k]) for k in g_lim})
    return ref


def score(c: dict, floor: float) -> dict:
    """Rows, groups and verdicts of case ``c`` from its auto row and its reference runs (in place)."""
    score_reference(c["reference"], floor)
    c["rows"] = rows_for(c["auto"], c["reference"])
    c["groups"] = group_rows(c["auto"], c["reference"])
    rows = c["rows"]
    c.update(all_within_tolerance=all(r["within_tolerance"] for r in rows),
             all_stated_at_least_half=all(r["stated_at_least_half"] is True for r in rows),
             all_stated_honest=all(r["stated_honest"] is True for r in rows),
             resolved_stated_at_least_half=all(r["stated_at_least_half"] is True for r in rows
                                               if r["reference_resolved"]))
    return c


def auto_run(scene, compiled: bool, tolerance=None) -> tuple:
    """(result, row) of auto as a user runs it (``cablesys.simulate``), its wall and CPU time and load."""
    _compile(compiled)
    load = os.getloadavg()[0]
    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = cablesys.simulate(scene, **({} if tolerance is None else {"tolerance": tolerance}))
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    m = r.stats["model"]
    x = m.get("extrapolated") or {}
    plan = (x.get("plan") or {}).get("runs", [])
    keys = ("segments", "candidate", "method", "stages", "steps", "step_us", "wall_s", "cpu_s", "status")
    row = {"success": bool(r.success), "compiled": compiled, "tolerance": tolerance, "wall_s": wall, "cpu_s": cpu,
           "load_1min": load, "model": m.get("name"), "segments": m.get("segments"), "checked": m.get("checked"),
           "extrapolated_segments": x.get("segments"), "asymptotic": x.get("asymptotic"),
           "leading_orders": x.get("leading_orders"), "settled_in_noise": x.get("settled_in_noise"),
           "kept_converging": x.get("kept_converging"), "remainder_factor": x.get("remainder_factor"),
           "stated_group": m.get("estimated_error"), "stated_time_series_group": m.get("estimated_error_time_series"),
           "stated_per_quantity": m.get("estimated_error_per_quantity"),
           "stated_time_series_per_quantity": x.get("time_series_error_per_quantity"),
           "statistics": x.get("statistics"), "statistics_coarse": x.get("statistics_coarse"),
           "plan": [{k: p.get(k) for k in keys} for p in plan], "reason": m.get("reason")}
    return r, row


def rows_for(auto: dict, ref: dict) -> list:
    """One row per quantity of auto's extrapolated statistics against the reference (:func:`quantity_rows`), with the
    group's statement beside the per-quantity one and the reference's own uncertainty; ``stated_honest`` also passes
    an actual error below twice that uncertainty (not resolved by the reference)."""
    actual = metrics.quantity_errors(auto["statistics"], ref["statistics"])
    per = auto["stated_per_quantity"]
    group = {k: (auto["stated_group"] or {}).get(metrics.group(k)) for k in actual}
    stated, source = (per, "per quantity") if per else (group, "group")
    rows = quantity_rows(actual, stated)
    for r in rows:
        k = r["quantity"]
        u = (ref.get("uncertainty") or {}).get(k) or 0.0
        r.update(stated_source=source, stated_group=group[k], reference_uncertainty=u,
                 reference_resolved=bool(r["actual"] > 2 * u),
                 ratio=None if r["stated"] is None or r["actual"] <= 0 else r["stated"] / r["actual"],
                 group_at_least_half=None if group[k] is None else bool(group[k] >= 0.5 * r["actual"]))
        if r["stated_honest"] is False and not r["reference_resolved"]:
            r["stated_honest"] = True
    return rows


def group_rows(auto: dict, ref: dict) -> dict:
    """The group numbers (body, tension; :func:`cablesys.ladder.metrics.errors`): actual, stated, their ratio."""
    act = metrics.errors(auto["statistics"], ref["statistics"])
    st = auto["stated_group"] or {}
    return {k: {"actual": v, "stated": st.get(k), "ratio": None if not v or st.get(k) is None else st[k] / v,
                "tolerance": QUANTITY_TOL[k], "within_tolerance": v <= QUANTITY_TOL[k],
                "stated_at_least_half": None if st.get(k) is None else bool(st[k] >= 0.5 * v),
                "reference_uncertainty": (ref.get("uncertainty_group") or {}).get(k)} for k, v in act.items()}


def own_pair(scene, auto: dict, cache: RungCache) -> dict:
    """Quick mode's check: the study's own runs at auto's N / 2 and N (:func:`reference_run`: finer step and
    sampling than auto's), their difference per quantity (the first-order estimate of the N run's error,
    |f(N) - L(N)| = |f(N) - f(N / 2)|), against auto's stated time-series error per quantity."""
    n = auto["segments"]
    a, b = reference_run(scene, n // 2, cache), reference_run(scene, n, cache)
    diff = metrics.quantity_errors(a["statistics"], b["statistics"])
    stated = auto["stated_time_series_per_quantity"] or {}
    return {"segments": [n // 2, n], "difference": diff, "stated_time_series": stated,
            "wall_s": a["wall_s"] + b["wall_s"],
            "covered": {k: bool(stated.get(k, -1.0) >= 0.5 * v) for k, v in diff.items()}}


def _reusable(old: dict | None, scene, quick: bool) -> dict | None:
    """The reference of a case of an earlier JSON (``--reuse-reference``) for ``scene``: the same scene name,
    duration, reference N and refinement, its runs all successful; else None."""
    if not old or old.get("scene") != scene.name or old.get("duration_s") != scene.numerics.duration:
        return None
    ref = old.get("reference") or {}
    ok = (ref.get("segments") == list(REFERENCE_N["quick" if quick else "full"]) and ref.get("refine") == REFINE
          and "error" not in ref and all(r.get("success") for r in ref.get("runs", [])))
    return ref if ok else None


def case(name: str, scene, description: str, quick: bool, reuse: dict | None = None) -> dict:
    """Auto and its reference on one scene (module docstring); ``reuse``: the same case of an earlier JSON whose
    reference runs are taken as they are when they match (:func:`_reusable`; auto runs again)."""
    compiled = not quick
    with smallest_extrapolation(QUICK_MIN_SEGMENTS if quick else None):
        _, auto = auto_run(scene, compiled, QUICK_TOLERANCE if quick else None)
    out = {"case": name, "scene": scene.name, "description": description, "duration_s": scene.numerics.duration,
           "output_step_s": scene.numerics.output_step, "statistics_step_s": X.statistics_step(scene), "auto": auto}
    if not auto["success"] or auto["statistics"] is None:
        return dict(out, error="auto did not extrapolate (not a slack plan, or a run failed)", rows=[])
    cache = RungCache()
    _compile(compiled)
    ref = _reusable(reuse, scene, quick)
    if ref is not None:
        out["reference_reused"] = "the reference runs of an earlier run of the study (--reuse-reference)"
    else:
        ref = reference(scene, REFERENCE_N["quick" if quick else "full"], cache)
    out["reference"] = ref
    if "error" in ref:
        return dict(out, rows=[])
    score(out, _floor(scene))
    if quick:
        out["own_pair"] = own_pair(scene, auto, cache)
    return out


def totals(cases: list) -> dict:
    rows = [(c["case"], r) for c in cases for r in c.get("rows", [])]
    brief = lambda c, r: {"case": c, "quantity": r["quantity"], "actual": r["actual"], "stated": r["stated"],  # noqa: E731
                          "tolerance": r["tolerance"], "reference_uncertainty": r["reference_uncertainty"]}
    return {"scenes": len(cases), "quantities": len(rows),
            "within_tolerance": sum(r["within_tolerance"] for _, r in rows),
            "stated_at_least_half": sum(r["stated_at_least_half"] is True for _, r in rows),
            "stated_honest": sum(r["stated_honest"] is True for _, r in rows),
            "group_at_least_half": sum(r["group_at_least_half"] is True for _, r in rows),
            "outside_tolerance": [brief(c, r) for c, r in rows if not r["within_tolerance"]],
            "stated_below_half": [brief(c, r) for c, r in rows if r["stated_at_least_half"] is False]}


def plot(cases: list, path: Path) -> None:
    plt = setup_matplotlib()
    fig, ax = plt.subplots(figsize=(8.5, 7.0))
    lo, hi = 1e-5, 1.0
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:purple"]
    for c, col in zip(cases, colours):
        for grp, mk in (("body", "o"), ("tension", "s")):
            pts = [(r["actual"], r["stated"], r["reference_uncertainty"]) for r in c.get("rows", [])
                   if metrics.group(r["quantity"]) == grp and r["stated"] is not None]
            if pts:
                a, s, u = np.array(pts).T
                a, s = np.clip(a, lo, hi), np.clip(s, lo, hi)
                left = np.clip(a - 2 * u, lo, hi)          # the reference's own uncertainty x 2 (resolution)
                ax.hlines(s, left, np.clip(a + 2 * u, lo, hi), color=col, lw=0.8, alpha=0.6)
                ax.loglog(a, s, mk, color=col, mfc=col if grp == "body" else "none", ms=7, alpha=0.8,
                          label=f"{c['case']} (N = {', '.join(map(str, c['auto']['extrapolated_segments']))}): "
                                f"{grp} ({len(pts)})")
        for r in c.get("rows", []):
            if r["stated"] is not None and max(r["actual"], r["stated"]) > 2e-3:
                ax.annotate(r["quantity"].replace("tension_", "T_").replace("_amplitude", " amp"),
                            (np.clip(r["actual"], lo, hi), np.clip(r["stated"], lo, hi)), fontsize=6.5,
                            xytext=(5, 4 if r["quantity"].endswith("_max") else -9), textcoords="offset points",
                            color=col)
    x = np.array([lo, hi])
    ax.plot(x, x, "k-", lw=0.9, label="stated = actual")
    ax.fill_between(x, x / 2, x * 2, color="grey", alpha=0.15, label="within a factor 2")
    ax.plot(x, x / 2, "k--", lw=0.9, label="stated = actual / 2 (below: dishonest)")
    for grp, ls in (("body", ":"), ("tension", "-.")):
        ax.axvline(QUANTITY_TOL[grp], color="tab:red", lw=0.9, ls=ls, label=f"{grp} tolerance {100 * QUANTITY_TOL[grp]:g} %")
    ns = cases[0].get("reference", {}).get("segments", "?") if cases else "?"
    ax.set(xlim=(lo, hi), ylim=(lo, hi), xlabel=f"actual relative error against the reference (segmented, Richardson limit of N = {ns})\n"
           f"bars: +-2x the reference's own uncertainty; values clipped to [{lo:g}, 1]",
           ylabel="stated relative error of auto's extrapolated statistics (per quantity)",
           title="Slack scenes: auto's stated error vs the actual one, per quantity")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7, loc="upper left", framealpha=0.9)
    from cablesys.plots import save_figure
    save_figure(fig, path)


def assemble(paths: list, out: Path) -> int:
    """The cases of several JSON files of the study (``--only`` runs per scene group) in one JSON and figure, each
    scored again from its stored runs (:func:`score`)."""
    import json
    docs = [json.loads(Path(p).read_text()) for p in paths]
    floors = {n: _floor(sc) for n, sc, _ in scenes(False)}
    cases = [c for d in docs for c in d["cases"]]
    for c in cases:
        if c.get("reference") and "error" not in c["reference"] and c["case"] in floors:
            score(c, floors[c["case"]])
    doc = dict(docs[0], cases=cases, totals=totals(cases), wall_s=[d["wall_s"] for d in docs],
               load_1min_start=[d["load_1min_start"] for d in docs], load_1min_end=[d["load_1min_end"] for d in docs],
               assembled_from=[str(p) for p in paths])
    write_json(out / "slack_convergence.json", doc)
    plot(cases, out / "slack_convergence.png")
    t = doc["totals"]
    print(f"{t['quantities']} quantities on {t['scenes']} scenes: {t['within_tolerance']} within tolerance, "
          f"{t['stated_at_least_half']} stated >= actual/2, {t['stated_honest']} honest")
    return 0


def _options(ap) -> None:
    ap.add_argument("--only", default=None, help=f"comma-separated scenes among {', '.join(ALL)} (full mode)")
    ap.add_argument("--reuse-reference", action="append", default=[], type=Path, metavar="JSON",
                    help="an earlier slack_convergence.json whose reference runs are reused for the same scenes "
                         "(same name, duration, N, refinement): auto runs again, the reference does not (repeatable)")
    ap.add_argument("--assemble", nargs="+", type=Path, default=None, metavar="JSON",
                    help="no runs: the cases of these slack_convergence.json files (runs per scene group) scored again "
                         "and written together, with the figure")


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv, extra=_options)
    only = None
    if args.only is not None:
        only = [w.strip() for w in args.only.split(",") if w.strip()]
        if not only or set(only) - set(ALL):
            raise ParameterError("--only", args.only, f"names among {list(ALL)}")
    import json
    if args.assemble:
        return assemble(args.assemble, args.out)
    earlier = {c["case"]: c for p in args.reuse_reference for c in json.loads(Path(p).read_text())["cases"]}
    t0, load0 = time.perf_counter(), os.getloadavg()
    cases = []
    for name, scene, description in scenes(args.quick, only):
        c = case(name, scene, description, args.quick, earlier.get(name))
        cases.append(c)
        a = c["auto"]
        print(f"{name}: auto N = {a['extrapolated_segments']} ({a['wall_s']:.1f} s), stated {a['stated_group']}; "
              + (f"error: {c['error']}" if "error" in c else
                 f"within tolerance {c['all_within_tolerance']}, stated >= actual/2 {c['all_stated_at_least_half']}, "
                 f"groups {({k: (round(v['actual'], 6), v['stated']) for k, v in c['groups'].items()})}"), flush=True)
        write_json(args.out / "slack_convergence.json", {
            "quick": args.quick, "tolerance": QUANTITY_TOL, "resolved_fraction": RESOLVED, "refine": REFINE,
            "reference_segments": REFERENCE_N["quick" if args.quick else "full"], "cases": cases,
            "totals": totals(cases), "wall_s": time.perf_counter() - t0, "load_1min_start": load0[0],
            "load_1min_end": os.getloadavg()[0], "cpus": os.cpu_count()})
    plot(cases, args.out / "slack_convergence.png")
    t = totals(cases)
    print(f"{t['quantities']} quantities on {t['scenes']} scenes: {t['within_tolerance']} within tolerance, "
          f"{t['stated_at_least_half']} stated >= actual/2, {t['stated_honest']} honest; {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
