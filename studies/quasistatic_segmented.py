"""The quasi-static segmented cable against the node model at the same N: wall time, steps, error.

Issue 12 asks the Dale scene's 60 s under ~10 ms (300x MoorDyn with 10 elements) at the model
tolerance (1 % body amplitude, 2 % tension extremes). The segmented node model steps its stiff,
undamped axial element modes; the quasi-static reduction (:mod:`cablesys.model.quasistatic` on
:mod:`cablesys.model.element_coordinates`) keeps the bowing and drops them.

Cases (as ``bench_vs_moordyn`` builds them, with its smooth start of 3 forcing periods): the Dale scene
(Wang 1971 Table 1, 60 s) and the 300 m / 2 t sphere heave at T = 10 s (60 s). For N = 2, 3, 4, 6, 8,
both models compiled, every integrator setting of :data:`SETTINGS`: wall time of ``Simulator.run``
after a first run (stepping and outputs; build apart; the best of :data:`REPEATS`), CVODES steps, and the errors of body amplitudes
and tension extremes (:mod:`cablesys.ladder.metrics`, last 5 periods) against the converged node-model
reference of the benchmark (Dale N = 80; heave N = 40, the ladder study's), computed once in CasADi's
VM at rtol 1e-7 and kept in ``DIR/reference_<case>.json``. ``tight``: each model's own run at rtol 1e-7
(its discretisation error at N). ``best`` per (case, model, N): the cheapest setting within the
tolerance whose integration error is within half of it (:func:`_best`).

    python studies/quasistatic_segmented.py --out DIR [--quick]
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

import cablesys
from cablesys.ladder import metrics as M
from cablesys.ladder.rungs import build_rung
from cablesys.model import build_model
from cablesys.model.quasistatic import least_tension_margin
from cablesys.scene import dale_scene, load_scene
from cablesys.time_domain import simulate
from cablesys.time_domain.initial import initial_state
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator

DATA = Path(cablesys.__file__).resolve().parent / "data"
REPEATS = 3
TOLERANCE = (0.01, 0.02)                      # body, tension: the ladder's default model tolerance
MATCHED = (0.005, 0.01)                       # integration error allowed (bench_vs_moordyn's matched accuracy)
# quasi-static: no stiff mode left, so Adams and BDF of any order are candidates; atol = rtol / 10 of
# each state's scale (the integrators scale the states)
SETTINGS = {"quasi-static": [(m, r, 0.1 * r) for m in ("cvodes", "cvodes-adams", "cvodes-bdf2")
                             for r in (1e-2, 3e-3, 1e-3, 1e-4)],
            # the node model's BDF is capped at order 2 (integrators.make_integrator): the bench's settings
            "segmented": [("cvodes-bdf2", r, 1e-3 * r) for r in (1e-3, 3e-4, 1e-4)]}


def _ramped(scene, period, duration):
    top = dataclasses.replace(scene.top_motion, ramp_s=3 * period)
    return dataclasses.replace(scene, top_motion=top).with_numerics(duration=duration)


def cases(quick: bool) -> list[dict]:
    """[{key, scene, period, segments, n_ref}] as bench_vs_moordyn builds the scenes."""
    w = dale_scene().top_motion.x[0].frequency
    period = 2 * math.pi / w
    if quick:
        return [{"key": "dale", "scene": _ramped(dale_scene(duration=12.0), period, 12.0), "period": period,
                 "segments": (2, 3), "n_ref": 6}]
    heave = load_scene(DATA / "heave_300m.toml")
    sine = dataclasses.replace(heave.top_motion.y[0], frequency=2 * math.pi / 10.0)
    heave = dataclasses.replace(heave, name="300 m / 2 t sphere, 1 m heave, T = 10 s",
                                top_motion=dataclasses.replace(heave.top_motion, y=(sine,)))
    return [{"key": "dale", "scene": _ramped(dale_scene(duration=60.0), period, 60.0), "period": period,
             "segments": (2, 3, 4, 6, 8), "n_ref": 80},
            {"key": "heave_T10", "scene": _ramped(heave, 10.0, 60.0), "period": 10.0,
             "segments": (2, 3, 4, 6, 8), "n_ref": 40}]


def _segments(scene, n):
    return scene.replace_section(0, cable={"segments": n})


def reference(case: dict, out: Path) -> dict:
    """Statistics of the converged node model (VM, cvodes rtol 1e-7), computed once per output dir."""
    path = out / f"reference_{case['key']}.json"
    sc = _segments(case["scene"], case["n_ref"])
    tag = {"segments": case["n_ref"], "duration_s": sc.numerics.duration}
    if path.exists():
        doc = json.loads(path.read_text())
        if doc.get("tag") == tag:
            return doc
    old = os.environ.get("CABLESYS_COMPILE")
    os.environ["CABLESYS_COMPILE"] = "0"          # N = 80 compiles for minutes; the VM run is the bench's
    try:
        t0 = time.perf_counter()
        r = simulate(sc, method="cvodes", rtol=1e-7, atol=1e-10)
        wall = time.perf_counter() - t0
    finally:
        os.environ["CABLESYS_COMPILE"] = old if old is not None else "1"
    doc = {"tag": tag, "stats": M.statistics(r, case["period"]), "success": bool(r.success),
           "nsteps": r.stats.get("nsteps"), "wall_s": wall}
    write_json(path, doc)
    return doc


def _runs(model, sc, period, ref_stats, settings, tight_stats) -> list[dict]:
    p = model.parameters(sc)
    x0 = initial_state(sc, model, p)
    rows = []
    for method, rtol, atol in settings:
        row = {"method": method, "rtol": rtol, "atol_scaled": atol}
        try:
            sim = Simulator(model, sc.output_times, IntegratorSettings(method=method, rtol=rtol, atol=atol))
            t0 = time.perf_counter()
            sim.run(p, x0)
            first = time.perf_counter() - t0
            wall = math.inf
            for _ in range(REPEATS):              # the machine is shared: the best of a few runs
                t0 = time.perf_counter()
                r = sim.run(p, x0)
                wall = min(wall, time.perf_counter() - t0)
        except Exception as err:            # noqa: BLE001 - a failing setting is a result
            row.update(success=False, failure=f"{type(err).__name__}: {str(err)[:200]}")
            rows.append(row)
            continue
        row.update(success=bool(r.success), wall_s=wall, first_run_s=first, nsteps=r.stats.get("nsteps"),
                   error=M.errors(M.statistics(r, period), ref_stats) if r.success else None,
                   error_vs_own_tight=M.errors(M.statistics(r, period), tight_stats) if r.success else None)
        if model.kind == "quasi-static" and r.success:
            row["least_tension_margin_N"] = least_tension_margin(r, sc)
        rows.append(row)
    return rows


def _best(rows):
    """The fastest run within tolerance of the reference whose integration error (against its own tight
    run) is within half the tolerance, the benchmark's matched accuracy: a loose run whose integration
    error happens to cancel the discretisation error does not count."""
    ok = [r for r in rows if r.get("success") and r["error"]["body"] <= TOLERANCE[0] and r["error"]["tension"] <= TOLERANCE[1]
          and r["error_vs_own_tight"]["body"] <= MATCHED[0] and r["error_vs_own_tight"]["tension"] <= MATCHED[1]]
    return min(ok, key=lambda r: r["wall_s"]) if ok else None


def study_case(case: dict, out: Path) -> dict:
    ref = reference(case, out)
    res = {"key": case["key"], "scene": case["scene"].name, "period_s": case["period"],
           "duration_s": case["scene"].numerics.duration, "reference": ref, "by_n": []}
    for n in case["segments"]:
        sc = _segments(case["scene"], n)
        entry = {"segments": n}
        for kind in ("quasi-static", "segmented"):
            t0 = time.perf_counter()
            model = build_rung(sc, kind, segments=n) if kind == "quasi-static" else build_model(sc)
            build = time.perf_counter() - t0
            tight = simulate(sc, model=model, method="cvodes", rtol=1e-7, atol=1e-8)
            tight_stats = M.statistics(tight, case["period"])
            rows = _runs(model, sc, case["period"], ref["stats"], SETTINGS[kind], tight_stats)
            entry[kind] = {"build_s": build, "tight": {"nsteps": tight.stats.get("nsteps"), "success": bool(tight.success),
                                                       "error": M.errors(tight_stats, ref["stats"])},
                           "rhs_instructions": model.ode.n_instructions(),
                           "outputs_instructions": model.outputs.n_instructions(), "runs": rows, "best": _best(rows)}
        res["by_n"].append(entry)
    return res


def plot_case(res: dict, path: Path) -> None:
    """Per N, the fastest setting within tolerance of each model: wall time, steps, error / tolerance."""
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    how = "compiled C" if res.get("compiled") else "CasADi VM"
    for kind, color, marker in (("quasi-static", "tab:blue", "o"), ("segmented", "tab:red", "s")):
        pts = [(e["segments"], e[kind]["best"]) for e in res["by_n"] if e[kind]["best"]]
        if not pts:
            continue
        ns = [n for n, _ in pts]
        label = "quasi-static segmented" if kind == "quasi-static" else "segmented (node model)"
        axes[0].plot(ns, [1e3 * b["wall_s"] for _, b in pts], marker=marker, color=color, label=label)
        for i, (n, b) in enumerate(pts):      # labels alternate above / below: neighbours at N, N + 1 overlap otherwise
            axes[0].annotate(f"{b['method']}\nrtol {b['rtol']:g}", (n, 1e3 * b["wall_s"]), textcoords="offset points",
                             xytext=(4, 4 if i % 2 == 0 else -20), fontsize=7, color=color)
        axes[1].plot(ns, [b["nsteps"] for _, b in pts], marker=marker, color=color, label=label)
        axes[2].plot(ns, [b["error"]["body"] / TOLERANCE[0] for _, b in pts], marker=marker, color=color,
                     label=f"{label}: body amplitude / 1 %")
        axes[2].plot(ns, [b["error"]["tension"] / TOLERANCE[1] for _, b in pts], marker=marker, color=color, ls="--",
                     mfc="none", label=f"{label}: tension extremes / 2 %")
    axes[0].set_ylabel(f"wall time of the {res['duration_s']:g} s run (ms, {how}, build apart)")
    axes[1].set_ylabel("CVODES steps")
    axes[2].set_ylabel("error vs converged node model / tolerance")
    axes[2].axhline(1.0, color="gray", ls=":", lw=1)
    for ax, title in zip(axes, ("fastest setting within tolerance", "its steps", "its error")):
        ax.set_xlabel("elements N")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=7)
    fig.suptitle(res["scene"], fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)       # quick: Dale 12 s, N = 2, 3, reference N = 6, VM
    os.environ["CABLESYS_COMPILE"] = "0" if args.quick else "1"     # quick: no gcc
    doc = {"tolerance": {"body": TOLERANCE[0], "tension": TOLERANCE[1]}, "compiled": not args.quick, "cases": []}
    for case in cases(args.quick):
        res = study_case(case, args.out)
        res["compiled"] = not args.quick
        doc["cases"].append(res)
        plot_case(res, args.out / f"quasistatic_segmented_{case['key']}.png")
        for e in res["by_n"]:
            line = [f"{case['key']} N={e['segments']}"]
            for kind in ("quasi-static", "segmented"):
                b = e[kind]["best"]
                line.append(f"{kind}: " + (f"{1e3 * b['wall_s']:.1f} ms {b['nsteps']} steps {b['method']} rtol {b['rtol']:g} "
                                           f"body {100 * b['error']['body']:.2f} % tension {100 * b['error']['tension']:.2f} %"
                                           if b else "none within tolerance"))
            print(" | ".join(line))
    write_json(args.out / "quasistatic_segmented.json", doc)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
