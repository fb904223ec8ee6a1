"""The model ladder: error against a converged segmented reference versus wall time, per rung and integrator.

Scenes (issue 12):
- the Dale et al. water-channel model (Wang 1971 Table 1) at omega = 2 omega_n, where the straight
  cable is worst (cable drag bows it);
- 300 m steel wire (25 mm, AE 4e7 N, 2.5 kg/m) with a 2 t sphere (virtual mass 3100 kg), 1 m heave
  at T = 10 s (taut) and T = 6 s (slack each cycle, snap loads);
- 1000 m of 16 mm steel wire rope with a 300 kg sphere (the cable weighs 4x the body), 1 m heave
  and 1 m surge at T = 10 s: forcing above the cable's first string mode.

For each scene the reference is the segmented cable at N_ref elements (its own convergence is
reported: the difference to N_ref / 2). Every rung (frequency-domain periodic orbit, quasi-static
stretch, Wang's 2-DOF, segmented at several N) runs with every integrator; errors are those of
:mod:`cablesys.ladder.metrics` (body amplitudes, tension extremes over the last 5 forcing periods).
Wall time is the integration alone (``stats["wall_s"]``) in CasADi's virtual machine, build apart
(``MODEL_LADDER_ONLY=dale,heavy1000`` reruns some scenes and keeps the others' results;
``MODEL_LADDER_REESTIMATE=1`` keeps the runs of an existing model_ladder.json and makes auto's choice,
the estimates and the checks again). A run that
fails (step budget, unstable fixed step, non-finite state) is marked with an x at the top of the
chart with its reason in the JSON. Auto's choice (:func:`cablesys.ladder.choose`) is marked by a
star, with its estimated error next to the actual one.

Usage: python studies/model_ladder.py --out DIR [--quick]
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

from cablesys import units as U
from cablesys.errors import NumericalWarning
from cablesys.ladder import choose, metrics, run_rung
from cablesys.ladder import estimate as est
from cablesys.scene import (
    Body,
    Cable,
    Environment,
    Numerics,
    Sinusoid,
    TopMotion,
    dale_scene,
)
from cablesys.scene.scene import single_section_scene

INTEGRATORS = ("cvodes", "cvodes-adams", "idas", "rk")
RUNG_COLOURS = {"frequency": "tab:purple", "quasi-static": "tab:green", "wang": "tab:blue", "segmented": "tab:orange"}
RESOLVED_FRACTION = 0.1   # the factor-2 check applies to actual errors above this fraction of the tolerance
MARKERS = {"cvodes": "o", "cvodes-adams": "s", "idas": "D", "rk": "^", "collocation": "v", "periodic": "P"}


def wire_300m(period: float, duration: float) -> object:
    """300 m steel wire, 2 t sphere, 1 m heave at ``period`` (the scene of issue 11)."""
    cable = Cable(length=300.0, tension_ref=4877.0, ae=4.0e7, diameter=0.025, mass_per_length=2.5,
                  weight_per_length=19.6, cd_normal=1.2, ct_tangential=0.01, tension_floor=0.0)
    body = Body(weight=1937.0, mass_x=3100.0, mass_y=3100.0, drag_area_normal=1.0, drag_area_tangential=1.0)
    top = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=2 * math.pi / period),))
    return single_section_scene(cable=cable, body=body, name=f"300 m wire, 2 t sphere, heave T = {period:g} s",
                                environment=Environment(density=1025.0), top_motion=top,
                                numerics=Numerics(duration=duration, output_step=0.05, rtol=1e-7, atol=1e-9))


def heavy_cable(duration: float) -> object:
    """1000 m of 16 mm steel wire rope (9.4 N/m in water, AE 1.2e7 N) and a 300 kg sphere of 0.5 m."""
    rho, g = U.RHO_SEA, U.G_STANDARD
    vol = math.pi / 6 * 0.5**3
    w_b = 300.0 * g - rho * g * vol
    cable = Cable(length=1000.0, tension_ref=w_b + 0.5 * 9.4 * 1000.0, ae=1.2e7, diameter=0.016,
                  mass_per_length=1.1, weight_per_length=9.4, cd_normal=1.2, ct_tangential=0.01)
    body = Body(weight=w_b, mass_x=300.0 + 0.5 * rho * vol, mass_y=300.0 + 0.5 * rho * vol,
                drag_area_normal=0.5 * math.pi / 4 * 0.25, drag_area_tangential=0.5 * math.pi / 4 * 0.25)
    w = 2 * math.pi / 10.0
    top = TopMotion(x=(Sinusoid(amplitude=1.0, frequency=w, phase=math.pi / 2),), y=(Sinusoid(amplitude=1.0, frequency=w),))
    return single_section_scene(cable=cable, body=body, name="1000 m steel wire, 300 kg sphere, T = 10 s",
                                environment=Environment(density=rho, gravity=g), top_motion=top,
                                numerics=Numerics(duration=duration, output_step=0.1, rtol=1e-7, atol=1e-9))


def cases(quick: bool) -> list[dict]:
    """Scenes with their segment counts and reference N (quick: one short Dale run, coarse N)."""
    if quick:
        return [{"key": "dale", "scene": dale_scene(omega_ratio=2.0, duration=10.0), "segments": (2,), "n_ref": 6,
                 "integrators": ("cvodes", "rk")}]
    return [
        {"key": "dale", "scene": dale_scene(omega_ratio=2.0, duration=40.0), "segments": (2, 4, 8), "n_ref": 16,
         "integrators": INTEGRATORS},
        {"key": "wire300_T10", "scene": wire_300m(10.0, 40.0), "segments": (5, 10, 20), "n_ref": 40,
         "integrators": INTEGRATORS},
        {"key": "wire300_T6", "scene": wire_300m(6.0, 30.0), "segments": (5, 10, 20), "n_ref": 40,
         "integrators": INTEGRATORS},
        {"key": "heavy1000", "scene": heavy_cable(40.0), "segments": (5, 10, 20), "n_ref": 40,
         "integrators": INTEGRATORS},
    ]


def _run(scene, rung: str, n: int, method: str | None) -> tuple:
    """(result or None, row) with wall time, steps and failure."""
    row = {"rung": rung, "segments": n, "integrator": method or "periodic"}
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NumericalWarning)
            r = run_rung(scene, rung, n) if rung == "frequency" else run_rung(scene, rung, n, method=method)
    except (RuntimeError, ValueError, FloatingPointError) as err:   # rejected model / solver failure: marked
        row.update(success=False, failure=f"{type(err).__name__}: {str(err)[:300]}", wall_s=time.perf_counter() - t0)
        return None, row
    row.update(success=bool(r.success), failure="" if r.success else r.message[:300],
               wall_s=float(r.stats.get("wall_s", r.stats.get("wall_time_s", time.perf_counter() - t0))),
               total_s=time.perf_counter() - t0, nsteps=int(r.stats.get("nsteps", 0) or 0))
    return r, row


def study_case(case: dict) -> dict:
    scene = case["scene"]
    period = metrics.forcing_period(scene)
    ref, ref_row = _run(scene, "segmented", case["n_ref"], "cvodes")
    half, _ = _run(scene, "segmented", case["n_ref"] // 2, "cvodes")
    if ref is None or not ref.success:
        return {"scene": scene.name, "reference": ref_row, "rows": [], "error": "reference run failed"}
    ref_stats = metrics.statistics(ref, period)
    ref_conv = metrics.errors(metrics.statistics(half, period), ref_stats) if half is not None and half.success else None
    rows = []
    plan = [("frequency", 1, None)] + [(rung, 1, m) for rung in ("quasi-static", "wang") for m in case["integrators"]]
    plan += [("segmented", n, m) for n in case["segments"] for m in case["integrators"] if m != "cvodes-adams"]
    for rung, n, method in plan:
        r, row = _run(scene, rung, n, method)
        if r is not None and r.success and r.time[-1] >= scene.output_times[-1] - 1e-9:
            row["statistics"] = metrics.statistics(r, period)
            row.update(metrics.errors(row["statistics"], ref_stats))
            row["error_body"], row["error_tension"] = row.pop("body"), row.pop("tension")
        else:
            row["success"] = False
            row.setdefault("failure", "did not reach the end")
        rows.append(row)
    res = {"scene": scene.name, "period_s": period, "reference": dict(ref_row, convergence_vs_half=ref_conv),
           "reference_statistics": ref_stats, "rows": rows}
    res["auto"] = assess_auto(case, res, ref_stats)
    return res


def _error_row(scene, rung: str, n: int, method, period, ref_stats) -> dict:
    r, row = _run(scene, rung, n, method)
    if r is not None and r.success:
        row["statistics"] = metrics.statistics(r, period)
        row.update(metrics.errors(row["statistics"], ref_stats))
        row["error_body"], row["error_tension"] = row.pop("body"), row.pop("tension")
    return row


def _find(rows, rung, n, integrators):
    return next((r for r in rows if r["rung"] == rung and (rung != "segmented" or r["segments"] == n)
                 and r["integrator"] in integrators and r.get("error_body") is not None), None)


def assess_auto(case: dict, res: dict, ref_stats: dict | None) -> dict:
    """Auto's choice, its a-priori estimate, the estimate it states and the verdicts of issue 12's checks.

    Every row gets the a-priori estimate of its rung (``estimate_body``, ``estimate_tension``). The
    stated estimate is the a-priori one, except for a segmented choice with N >= 4, for which auto
    states the Richardson estimate |y_N - y_N/2| / (2^p - 1) of its run at N/2 (:mod:`cablesys.ladder.auto`).
    The factor-2 check applies where the actual error is resolved: above RESOLVED_FRACTION of the
    tolerance and above twice the reference's own convergence (N_ref vs N_ref / 2); below that the
    estimate must only be within the tolerance too. Rows that are not run again come from ``res``.
    """
    scene, period, rows = case["scene"], res.get("period_s"), res["rows"]
    t0 = time.perf_counter()
    choice = choose(scene)
    choose_s = time.perf_counter() - t0
    errs = choice.numbers["estimates"]
    for r in rows:
        e = (est.segmented_error(errs, r["segments"]) if r["rung"] == "segmented" else errs.get(r["rung"])) or {}
        r["estimate_body"], r["estimate_tension"] = e.get("body"), e.get("tension")
    integ = (scene.numerics.integrator, "periodic")
    actual = _find(rows, choice.name, choice.segments, integ)
    at_reference = choice.name == "segmented" and choice.segments >= case["n_ref"]
    if at_reference:          # auto wants the reference's own N: no converged reference to measure it against
        ref_stats = None
    if actual is None and ref_stats is not None:
        actual = _error_row(scene, choice.name, choice.segments, scene.numerics.integrator, period, ref_stats)
        actual.update(estimate_body=choice.estimated_error["body"], estimate_tension=choice.estimated_error["tension"])
        rows.append(actual)
    stated, how = dict(choice.estimated_error), "a priori"
    if choice.name == "segmented" and choice.segments >= 4 and ref_stats is not None:
        half = _find(rows, "segmented", choice.segments // 2, integ)
        if half is None:
            half = _error_row(scene, "segmented", choice.segments // 2, scene.numerics.integrator, period, ref_stats)
            rows.append(half)
        if actual and actual.get("error_body") is not None and half.get("error_body") is not None:
            p = errs["segmented_1"].get("order", est.ORDER)
            # auto's a-posteriori estimate from the two runs' statistics (rows of an older JSON without them:
            # |e_N/2 - e_N|, a lower bound of the same difference)
            if "statistics" in half and "statistics" in actual:
                diff = metrics.errors(half["statistics"], actual["statistics"])
            else:
                diff = {k: abs(half[f"error_{k}"] - actual[f"error_{k}"]) for k in ("body", "tension")}
            stated = {k: v / (2**p - 1) for k, v in diff.items()}
            how = f"a posteriori (N = {choice.segments} vs {choice.segments // 2}, order {p:g})"
    tol = choice.numbers["tolerance"]
    if at_reference:
        actual = None
    act = {"body": (actual or {}).get("error_body"), "tension": (actual or {}).get("error_tension")}
    conv = res.get("reference", {}).get("convergence_vs_half") or {}
    check = {}
    for k in ("body", "tension"):
        a, e = act[k], stated[k]
        floor = max(RESOLVED_FRACTION * tol[k], 2 * (conv.get(k) or 0.0))
        if a is None or e is None or not math.isfinite(e):
            check[k] = {"resolved": None, "ratio": None, "pass": None}
            continue
        resolved = a > floor
        ratio = e / a if a > 0 else math.inf
        ok = (0.5 <= ratio <= 2.0) if resolved else (e <= tol[k])
        check[k] = {"resolved": resolved, "resolution": floor, "ratio": ratio, "pass": bool(ok),
                    "strict_pass": bool(0.5 <= ratio <= 2.0)}
    check["within_tolerance"] = None if act["body"] is None else bool(act["body"] <= tol["body"] and act["tension"] <= tol["tension"])
    check["cheaper_rung_within_tolerance"] = cheaper_within(rows, choice, tol, integ)
    return {"name": choice.name, "segments": choice.segments, "reason": choice.reason,
            "estimated_error": choice.estimated_error, "stated_estimate": stated, "stated_how": how,
            "choose_s": choose_s, "actual_error": act, "estimates": errs, "tolerance": tol, "check": check}


def _rank(rung: str, n: int) -> int:
    """Ladder order of cost: the straight-cable rungs, then the segmented cable by N."""
    return 1 if rung in ("quasi-static", "wang") else 1 + n


def cheaper_within(rows, choice, tol, integrators) -> list:
    """Rungs below auto's choice on the ladder (straight cables, fewer elements) whose actual errors are
    within half the tolerance (auto aims at half of it: choice.SAFETY); the frequency rung answers
    another question (a steady amplitude) and is left out. Wall times are not compared: on a shared
    machine they are noise at these sizes."""
    mine = _rank(choice.name, choice.segments)
    return [f"{r['rung']}" + (f" N={r['segments']}" if r["rung"] == "segmented" else "")
            for r in rows if r["integrator"] in integrators and r.get("error_body") is not None
            and r["rung"] != "frequency" and _rank(r["rung"], r["segments"]) < mine
            and r["error_body"] <= 0.5 * tol["body"] and r["error_tension"] <= 0.5 * tol["tension"]]


def plot_case(res: dict, path: Path):
    plt = setup_matplotlib()
    from matplotlib.ticker import NullFormatter

    from cablesys.plots import save_figure
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.5), sharex=True, layout="constrained")
    ok = [r for r in res["rows"] if r.get("success") and r.get("error_body") is not None]
    bad = [r for r in res["rows"] if not r.get("success")]
    tol = res["auto"]["tolerance"]
    floor = 1e-7
    for ax, key, tl, title in ((axes[0], "error_body", tol["body"], "body amplitude error"),
                               (axes[1], "error_tension", tol["tension"], "tension-extremes error")):
        for r in ok:
            lab = r["rung"] + (f" N={r['segments']}" if r["rung"] == "segmented" else "")
            ax.loglog(max(r["wall_s"], 1e-4), max(r[key], floor), MARKERS.get(r["integrator"], "o"),
                      color=RUNG_COLOURS[r["rung"]], ms=8, alpha=0.85)
            if r["integrator"] in ("cvodes", "periodic"):      # one label per rung, staggered vertically
                dy = {"frequency": 14, "quasi-static": 4, "wang": -8, "segmented": 4}[r["rung"]]
                ax.annotate(lab, (max(r["wall_s"], 1e-4), max(r[key], floor)), textcoords="offset points",
                            xytext=(6, dy), fontsize=7, color=RUNG_COLOURS[r["rung"]])
        for r in bad:
            ax.plot(max(r["wall_s"], 1e-4), 1.0, "x", color=RUNG_COLOURS[r["rung"]], ms=10, mew=2)
        a = res["auto"]
        hit = [r for r in ok if r["rung"] == a["name"] and (a["name"] != "segmented" or r["segments"] == a["segments"])]
        if hit:
            ax.loglog(max(hit[0]["wall_s"], 1e-4), max(hit[0][key], floor), "*", color="k", ms=18, mfc="none", mew=1.5)
            stated = (a.get("stated_estimate") or {}).get(key.removeprefix("error_"))
            if stated is not None and math.isfinite(stated):   # auto's stated estimate: a bar at the star's wall time
                ax.loglog(max(hit[0]["wall_s"], 1e-4), max(stated, floor), "_", color="k", ms=22, mew=2.5)
        ax.axhline(tl, ls="--", color="grey", lw=1)
        ax.text(ax.get_xlim()[0] if ok else 1e-3, tl * 1.1, f"tolerance {tl:.0%}", fontsize=8, color="grey")
        ax.axhline(1.0, ls=":", color="red", lw=0.8)
        ax.set_title(title)
        ax.set_xlabel("wall time of the integration [s]")
        ax.set_ylabel("relative error vs converged segmented")
        ax.grid(True, which="both", alpha=0.3)
        ax.xaxis.set_minor_formatter(NullFormatter())
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color=c, marker="o", ls="", label=k) for k, c in RUNG_COLOURS.items()]
    handles += [Line2D([], [], color="k", marker=m, ls="", label=k) for k, m in MARKERS.items()
                if any(r["integrator"] == k for r in res["rows"])]
    handles += [Line2D([], [], color="k", marker="*", mfc="none", ls="", ms=12, label="auto's choice"),
                Line2D([], [], color="k", marker="_", ls="", ms=14, mew=2.5, label="auto's stated estimate"),
                Line2D([], [], color="k", marker="x", ls="", label="failed (at error = 1)")]
    fig.legend(handles=handles, fontsize=8, loc="outside lower center", ncol=math.ceil(len(handles) / 2))
    fig.suptitle(f"{res['scene']}: model ladder work-precision (reference: segmented N = {res['reference']['segments']})")
    return save_figure(fig, path, dpi=110)


def _fmt(d) -> str:
    f = lambda v: "-" if v is None else f"{v:.2g}"
    return "{" + ", ".join(f"{k} {f(v)}" for k, v in (d or {}).items()) + "}"


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
        if reestimate and case["key"] in out and out[case["key"]].get("rows"):
            # the runs are kept; auto's choice, the estimates and the checks are made again (estimate changes)
            res = out[case["key"]]
            res["auto"] = assess_auto(case, res, res.get("reference_statistics"))
        else:
            res = study_case(case)
        out[case["key"]] = res
        if res["rows"]:
            plot_case(res, args.out / f"model_ladder_{case['key']}.png")
        a = res.get("auto", {})
        print(f"{case['key']}: auto -> {a.get('name')} N={a.get('segments')}; stated ({a.get('stated_how')}) "
              f"{_fmt(a.get('stated_estimate'))} vs actual {_fmt(a.get('actual_error'))}; check {a.get('check')}", flush=True)
        for r in res["rows"]:
            if r["integrator"] in ("cvodes", "periodic"):
                name = r["rung"] + (f" N={r['segments']}" if r["rung"] == "segmented" else "")
                print(f"    {name:16s} estimated {_fmt({'b': r.get('estimate_body'), 't': r.get('estimate_tension')})} "
                      f"actual {_fmt({'b': r.get('error_body'), 't': r.get('error_tension')})}", flush=True)
        write_json(path, out)           # after every scene: a long study keeps what it has
    return 0


if __name__ == "__main__":
    sys.exit(main())
