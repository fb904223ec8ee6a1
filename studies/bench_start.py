"""Benchmark: how long a run takes to start, cold (empty cache) and warm (second start), against 50 ms.

    python studies/bench_start.py --out DIR [--quick]

Issue 13: "Second start of a cached compiled model under 50 ms (build included)". Every
measurement is a fresh Python process (``--child``) on a private, initially empty cache folder
(``CABLESYS_CACHE``), compilation on (``CABLESYS_COMPILE=1``), so nothing is shared with the
benchmark's own process or the user's cache:

- ``cold``: the first start of a structure: symbolic build, C generation and compilation;
- ``warm``: the same structure started again in a new process (median and best of a few):
  ``model_s`` (``build_model``: the stored functions, :mod:`cablesys.model.store`, each
  deserialized on its first use, so part of that cost shows in the next two),
  ``simulator_s`` (``Simulator``: integrators, the compiled DAE loaded from the structure index
  of :class:`cablesys.compiled.DerivedStore`), ``initial_s`` (initial state from the static
  equilibrium), ``start_s`` their sum, the "start" the target is about; ``load_s`` of it is
  ``casadi.external``; ``import_s`` (``import casadi`` and the cablesys modules a run needs) is
  reported apart; ``run_s`` the integration itself;
- ``recompiled``: whether the warm process compiled anything (new or rewritten library files in
  the cache) and ``cache_hits``, the compiled functions it took from the structure index.

Models: Wang's 2-DOF model on the Dale scene (Wang 1971 Table 1) and, without ``--quick``, the
segmented cable with N = 20 elements on the same scene.

Also the cost of a sampled top motion (issue 13: "Sampled series on the SX path ... compilable,
within 2x of the sinusoid cost"): the Dale scene's top motion (two sinusoids, omega = 1.14 rad/s)
given instead as a series sampled every 0.25 s (22 samples per period), same abrupt start,
same model; the ratio of best-of-3 compiled run times, with both runs' step counts, the ODE's
instruction count and the largest difference of the body motion (how well the spline reproduces
the sinusoid). The spline finds its piece by binary search in a constant table
(:mod:`cablesys.model.top_motion`), so its cost should not grow with the record: measured for a
10 s run (10 s record, 42 samples) and, without ``--quick``, a 60 s run with a 60 s record (242
samples) and with a 500 s record (2002 samples; the run uses its first 60 s). Before that
change the piece was selected by a telescoping sum over the samples (~26 operations per sample
and axis) and the samples were entries of ``p``: 1.14x at 42 samples, 5.95x at 242 (the ODE's top motion
~52 instructions per sample: ~100k at 2002, not measured); after it, on a loaded 2-core machine:
0.92x, 1.39x and 1.42x. ``per_step_ratio`` divides out the step counts (the series run takes
~30 % more steps over 60 s; not investigated: the spline's third derivative jumps at every
sample, a likely cause).

The machine may be shared: the load average at the start and end is recorded, and
``model_build_vs_load`` compares, in the same run, the cold process's symbolic build with the
warm process's stored model.

Writes DIR/bench_start.json and DIR/bench_start.png.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))     # _common, imported by the parent only:
# a child measures its imports from scratch (numpy included, as ``import casadi`` brings it)

TARGET_MS = 50.0
SERIES_TARGET = 2.0
SAMPLE_DT = 0.25


# -- the child: one fresh process -------------------------------------------------------------
def _scene(case: str, duration: float):
    from cablesys.scene import dale_scene
    scene = dale_scene().with_numerics(duration=duration)
    if case == "segmented20":
        from cablesys.ladder.rungs import with_segments
        scene = with_segments(scene, 20)
    return scene


def _series_scene(scene, record_s: float | None = None):
    """The scene's sinusoidal top motion as a sampled series (no sinusoids), both abrupt starts;
    the record lasts ``record_s`` (default: the run's duration)."""
    import dataclasses

    import numpy as np

    from cablesys.scene.components import TimeSeries
    top = scene.top_motion
    t = np.arange(0.0, max(scene.numerics.duration, record_s or 0.0) + 2 * SAMPLE_DT, SAMPLE_DT)
    xs = sum(s.amplitude * np.sin(s.frequency * t + s.phase) for s in top.x)
    ys = sum(s.amplitude * np.sin(s.frequency * t + s.phase) for s in top.y)
    sine = dataclasses.replace(scene, top_motion=dataclasses.replace(top, ramp_s=0.0))
    series = dataclasses.replace(scene, top_motion=dataclasses.replace(
        top, x=(), y=(), ramp_s=0.0, series=TimeSeries(times=tuple(t), x=tuple(xs), y=tuple(ys))))
    return sine, series, t.size


def _settings(scene):
    from cablesys.time_domain.integrators import IntegratorSettings
    num = scene.numerics
    return IntegratorSettings(method=num.integrator, rtol=num.rtol, atol=num.atol)


def child_start(case: str, duration: float) -> dict:
    """One start of ``case``: import, build, simulator, initial state, run (seconds)."""
    T = time.perf_counter
    t0 = T()
    import casadi  # noqa: F401  (and numpy)
    t1 = T()
    from cablesys.model import build_model
    from cablesys.time_domain import Simulator
    from cablesys.time_domain.initial import initial_state
    t2 = T()
    scene = _scene(case, duration)
    t3 = T()
    model = build_model(scene)
    t4 = T()
    sim = Simulator(model, scene.output_times, _settings(scene))
    t5 = T()
    p = model.parameters(scene)
    x0 = initial_state(scene, model, p)
    t6 = T()
    rec = sim.run(p, x0)
    t7 = T()
    return {"import_casadi_s": t1 - t0, "import_cablesys_s": t2 - t1, "import_s": t2 - t0,
            "model_s": t4 - t3, "simulator_s": t5 - t4, "initial_s": t6 - t5, "start_s": t6 - t3,
            "load_s": sim.compiled.load_s, "run_s": t7 - t6, "success": bool(rec.success),
            "compiled": bool(sim.compiled.compiled), "dae_from_cache": bool(sim.compiled.cached),
            "model_stored": bool(model.build_info.get("stored")), "cache_hits": int(model.cache.hits),
            "structure_key": model.build_info.get("structure_key"),     # changes when the model's sources do
            "nq": int(model.nq)}


def child_series(duration: float, repeats: int, record_s: float) -> dict:
    """Compiled run time of the sinusoidal and the sampled top motion (best of ``repeats``)."""
    import numpy as np

    from cablesys.model import build_model
    from cablesys.time_domain import Simulator
    from cablesys.time_domain.initial import initial_state
    sine, series, n_samples = _series_scene(_scene("wang", duration), record_s)
    out, body = {"samples": n_samples, "sample_dt_s": SAMPLE_DT, "duration_s": duration,
                 "record_s": max(duration, record_s)}, {}
    for name, scene in (("sinusoid", sine), ("series", series)):
        model = build_model(scene)
        sim = Simulator(model, scene.output_times, _settings(scene))
        p = model.parameters(scene)
        x0 = initial_state(scene, model, p)
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            rec = sim.run(p, x0)
            times.append(time.perf_counter() - t0)
        body[name] = np.array(rec["x_b"])
        out[name] = {"run_s": min(times), "nsteps": int(rec.stats.get("nsteps", 0)), "success": bool(rec.success),
                     "compiled": bool(sim.compiled.compiled), "ode_instructions": int(model.ode.n_instructions())}
    out["ratio"] = out["series"]["run_s"] / out["sinusoid"]["run_s"]
    # the series run takes more steps (see the module docstring): the cost per step is what the
    # record length could change
    out["per_step_ratio"] = out["ratio"] * out["sinusoid"]["nsteps"] / max(out["series"]["nsteps"], 1)
    out["body_x_max_difference_m"] = float(np.max(np.abs(body["series"] - body["sinusoid"])))
    out["body_x_amplitude_m"] = float(np.max(np.abs(body["sinusoid"])))
    return out


# -- the parent: fresh processes on a private cache -------------------------------------------
def _libraries(cache: Path) -> dict:
    """Library files and their inodes (a rebuilt library is a new file renamed into place; a use
    only refreshes the modification time, the LRU order)."""
    return {str(p): p.stat().st_ino for p in cache.rglob("*.so")}


def _spawn(cache: Path, *args) -> dict:
    env = dict(os.environ, CABLESYS_CACHE=str(cache), CABLESYS_COMPILE="1", MPLBACKEND="Agg")
    env.pop("CABLESYS_CACHE_DIR", None)
    proc = subprocess.run([sys.executable, __file__, "--out", "-", "--child", *map(str, args)],
                          capture_output=True, text=True, env=env, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"child {args} failed:\n{proc.stderr[-3000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def measure_case(case: str, duration: float, n_warm: int) -> dict:
    """Cold start on an empty cache, then ``n_warm`` warm starts, each in a new process."""
    with tempfile.TemporaryDirectory(prefix="cablesys-bench-start-") as tmp:
        cache = Path(tmp) / "cache"
        t0 = time.perf_counter()
        cold = _spawn(cache, "start", case, duration)
        cold["process_s"] = time.perf_counter() - t0
        before = _libraries(cache)
        warm = []
        for _ in range(n_warm):
            t0 = time.perf_counter()
            w = _spawn(cache, "start", case, duration)
            w["process_s"] = time.perf_counter() - t0
            warm.append(w)
        after = _libraries(cache)
        size = sum(p.stat().st_size for p in cache.rglob("*") if p.is_file())
    keys = [k for k in warm[0] if k.endswith("_s")]
    med = {k: statistics.median(w[k] for w in warm) for k in keys}
    best = {k: min(w[k] for w in warm) for k in keys}
    return {"cold": cold, "warm_runs": warm, "warm_median": med, "warm_best": best,
            "recompiled": after != before, "new_libraries": sorted(set(after) - set(before)),
            "cache_hits": min(w["cache_hits"] for w in warm),
            "model_stored": all(w["model_stored"] for w in warm),
            "dae_from_cache": all(w["dae_from_cache"] for w in warm),
            "cache_bytes": size,
            "warm_start_ms": 1e3 * med["start_s"], "warm_start_best_ms": 1e3 * best["start_s"],
            "cold_start_ms": 1e3 * cold["start_s"],
            "import_ms": 1e3 * med["import_s"],
            # same-run baseline: the cold process's symbolic model build vs the warm one's stored model
            "model_build_vs_load": cold["model_s"] / med["model_s"],
            "target_ms": TARGET_MS, "target_met": 1e3 * med["start_s"] < TARGET_MS}


def measure_series(duration: float, repeats: int, record_s: float = 0.0) -> dict:
    with tempfile.TemporaryDirectory(prefix="cablesys-bench-series-") as tmp:
        cache = Path(tmp) / "cache"
        _spawn(cache, "series", duration, 1, record_s)                 # compiles both structures
        out = _spawn(cache, "series", duration, repeats, record_s)      # times them warm
    out["target_ratio"] = SERIES_TARGET
    out["target_met"] = out["ratio"] <= SERIES_TARGET
    return out


def plot(res: dict, path: Path) -> None:
    from _common import setup_matplotlib
    plt = setup_matplotlib()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5.4), gridspec_kw={"width_ratios": [1.7, 1]})
    cases = list(res["cases"])
    parts = (("model_s", "model (stored, deserialized on use)", "tab:blue"), ("simulator_s", "simulator (+ compiled DAE loaded)", "tab:orange"),
             ("initial_s", "initial state", "tab:green"))
    rows, labels = [], []
    for case in cases:
        c = res["cases"][case]
        rows.append(("warm", dict(c["warm_median"], best_s=c["warm_best"]["start_s"])))
        labels.append(f"{case}: second start")
        rows.append(("import", c["warm_median"]))
        labels.append(f"{case}: imports")
        rows.append(("cold", c["cold"]))
        labels.append(f"{case}: cold start")
    y = list(range(len(rows)))[::-1]
    for yi, (kind, d) in zip(y, rows):
        if kind == "warm":
            left = 0.0
            for key, name, color in parts:
                ax.barh(yi, 1e3 * d[key], left=left, color=color, label=name if yi == y[0] else None)
                left += 1e3 * d[key]
            ax.text(left * 1.08, yi, f"{left:.0f} ms\n(best {1e3 * d['best_s']:.0f})", va="center", fontsize=9)
        elif kind == "import":
            ax.barh(yi, 1e3 * d["import_s"], color="0.6", label="imports (casadi + cablesys)" if yi == y[1] else None)
            ax.text(1e3 * d["import_s"] * 1.08, yi, f"{1e3 * d['import_s']:.0f} ms", va="center", fontsize=9)
        else:
            ax.barh(yi, 1e3 * d["start_s"], color="tab:red", label="cold start (compiles)" if yi == y[2] else None)
            ax.text(1e3 * d["start_s"] * 1.08, yi, f"{1e3 * d['start_s']:.0f} ms", va="center", fontsize=9)
    ax.axvline(TARGET_MS, color="k", ls="--", lw=1)
    ax.text(TARGET_MS * 1.05, y[0] + 0.45, "target 50 ms", fontsize=9)
    ax.set_xscale("log")
    ax.set_xlim(1, 10 ** (1.2 + max(3.0, float(__import__("math").log10(max(1e3 * r[1]["start_s"] for r in rows))))))
    ax.set_yticks(y, labels)
    ax.set_xlabel("time [ms] (fresh process; warm: median of the repeats)")
    ax.set_title("Start of a compiled model: cold vs second start")
    ax.legend(loc="upper center", bbox_to_anchor=(0.45, -0.16), ncol=3, fontsize=8, frameon=False)
    ticks, names = [], []
    for k, s in enumerate(res["series_runs"]):
        x0 = 3 * k
        sine, series = s["sinusoid"]["run_s"] / s["sinusoid"]["run_s"], s["series"]["run_s"] / s["sinusoid"]["run_s"]
        bx.bar(x0, sine, color="tab:blue", label=None if k else "two sinusoids")
        bx.bar(x0 + 1, series, color="tab:purple", label=None if k else "the same motion as a sampled series")
        bx.text(x0 + 1, series * 1.02, f"{series:.2f}x", ha="center", va="bottom", fontsize=9)
        bx.text(x0, sine * 1.02, f"{1e3 * s['sinusoid']['run_s']:.0f} ms", ha="center", va="bottom", fontsize=8)
        ticks.append(x0 + 0.5)
        record = s.get("record_s", s["duration_s"])
        names.append(f"{s['duration_s']:g} s run\n{s['samples']} samples"
                     + (f"\n({record:g} s record)" if record > s["duration_s"] else ""))
    bx.axhline(SERIES_TARGET, color="k", ls="--", lw=1)
    bx.text(-0.4, SERIES_TARGET * 1.02, f"target {SERIES_TARGET:g}x", fontsize=9)
    bx.set_xticks(ticks, names)
    bx.set_ylabel("compiled run time / sinusoid run time")
    bx.set_ylim(0, max(SERIES_TARGET, max(s["ratio"] for s in res["series_runs"])) * 1.25)
    bx.legend(loc="upper right", fontsize=8)
    bx.set_title(f"Sampled top motion (every {SAMPLE_DT} s)\nvs sinusoids: run-time ratio, best of repeats", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--child" in argv:
        rest = argv[argv.index("--child") + 1:]
        out = (child_start(rest[1], float(rest[2])) if rest[0] == "start"
               else child_series(float(rest[1]), int(rest[2]), float(rest[3])))
        print(json.dumps(out))
        return 0
    from _common import parse_args, write_json
    args = parse_args(__doc__.splitlines()[0], argv)
    cases = ("wang",) if args.quick else ("wang", "segmented20")
    duration = 2.0 if args.quick else 10.0
    n_warm = 2 if args.quick else 7
    res = {"target_ms": TARGET_MS, "quick": args.quick, "duration_s": duration, "warm_repeats": n_warm,
           "python": sys.version.split()[0], "load_average_start": os.getloadavg(), "cases": {}}
    for case in cases:
        res["cases"][case] = measure_case(case, duration, n_warm)
    runs = ((10.0, 0.0),) if args.quick else ((10.0, 0.0), (60.0, 0.0), (60.0, 500.0))     # (run, record) [s]
    res["series_runs"] = [measure_series(d, 1 if args.quick else 3, r) for d, r in runs]
    res["series"] = res["series_runs"][-1]          # the longest record
    res["summary"] = {case: {k: c[k] for k in ("cold_start_ms", "warm_start_ms", "warm_start_best_ms", "import_ms",
                                                "target_met", "recompiled", "cache_hits")}
                      for case, c in res["cases"].items()}
    res["summary"]["series_vs_sinusoid_ratio"] = {f"{s['duration_s']:g}s_{s['samples']}_samples": s["ratio"]
                                                  for s in res["series_runs"]}
    res["load_average_end"] = os.getloadavg()
    write_json(args.out / "bench_start.json", res)
    plot(res, args.out / "bench_start.png")
    for case, s in res["summary"].items():
        print(case, s)
    return 0


if __name__ == "__main__":
    sys.exit(main())
