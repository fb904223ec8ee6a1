"""Study: a run's cost predicted before its build (:mod:`cablesys.ladder.plan_cost`) against what the run cost.

    python studies/run_prediction.py --out DIR [--quick]

Issue 23 ("Work that is predicted before it is done") and 29 ("Compile time bounded and shown"). Six scenes of
different kinds, each run by ``cablesys.simulate`` (the model ladder's choice, as ``cablesys run`` runs it) compiled
(``CABLESYS_COMPILE=1``) on a cold cache: every scene in a fresh Python process (``--child``) with a private, empty
``CABLESYS_CACHE``, so nothing is shared between scenes or with the user's cache:

- ``dale``: the Dale et al. water-channel model at omega = omega_n (``cablesys.scene.default_scene``, the scene of
  ``cablesys run`` without a file), Wang (1971) Table 1;
- ``heave_300m``: 300 m of steel wire, a 2 t sphere, 1 m heave at T = 6 s (``cablesys/data/heave_300m.toml``);
- ``rov_lift``: an ROV lifted through an irregular sea (``cablesys/data/rov_lift.toml``), its first 120 s;
- ``heavy_wire``: 1000 m of wire and a 300 kg sphere (``cablesys.heavy_wire_scene``);
- ``slack_light_lift``: the 300 m wire of ``heave_300m`` holding a light 0.3 t package (weight in water 400 N):
  the heave's acceleration force exceeds the weight, the lower cable goes slack and snaps;
- ``sheared``: 150 m of wire in a current of 1.2 / 0.6 / 0.1 m/s over the depth, surged and heaved at T = 9 s
  (``studies/ladder_quantities.py``).

For each: the prediction the ladder hands to ``on_plan`` before the candidate run's model is built, and what that
run cost: integrator steps (``stats["nsteps"]``, for the extrapolation the sum over its runs), operations of the
built model (``ode`` plus ``outputs``, CasADi SX instructions), compile wall time (the sum of the compiles
:mod:`cablesys.compiled` logs between the prediction and the candidate run's end; the compiles of the model choice
before it and of a posteriori checks after it are reported apart), stepping wall time (``stats["wall_s"]``) and
the output memory (bytes of the result's arrays x the record's copies, ``record._COPIES``, which the prediction
counts). Each compile's own prediction from its C size (:func:`cablesys.compiled.predicted_compile_s`) is
recorded beside its actual time (``compiles``) and the rate of seconds per MB of C is fitted per flag.

Ratios actual / predicted, each within a factor 3 or not (``within_3x``). Wall times are of this machine under
its load (the load average before and after is recorded); steps, operations and memory do not depend on it.
``--quick``: the Dale scene over 20 s only, Wang's model named (the model choice's own cold compiles are skipped).

Writes DIR/run_prediction.json and DIR/run_prediction.png.
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

QUANTITIES = (("steps", "integrator steps"), ("operations", "operations"), ("compile_s", "compile (s)"),
              ("run_s", "stepping (s)"), ("memory_bytes", "output memory (bytes)"))
CPU = {"compile_s": "compile_cpu_s", "run_s": "run_cpu_s"}        # the same measured in CPU time
FACTOR = 3.0
SCENES = ("dale", "heave_300m", "rov_lift", "heavy_wire", "slack_light_lift", "sheared")


def make_scene(name: str, quick: bool = False):
    """The scene ``name`` of :data:`SCENES` (the module docstring)."""
    import cablesys
    from cablesys.scene import default_scene, load_scene
    data = Path(cablesys.__file__).parent / "data"
    if name == "dale":
        sc = default_scene()
        return sc.with_numerics(duration=20.0) if quick else sc
    if name == "heave_300m":
        return load_scene(data / "heave_300m.toml")
    if name == "rov_lift":
        return load_scene(data / "rov_lift.toml").with_numerics(duration=120.0)
    if name == "heavy_wire":
        return cablesys.heavy_wire_scene()
    if name == "slack_light_lift":
        heave = load_scene(data / "heave_300m.toml")
        # a light package: 300 kg dry, 400 N in water, virtual mass 300 + 0.5 x 1025 x 0.25 m^3 = 430 kg
        return heave.replace_section(0, body={"weight": 400.0, "mass_x": 430.0, "mass_y": 430.0},
                                     cable={"tension_ref": 400.0 + 0.5 * 19.6 * 300.0}).with_numerics(duration=40.0)
    if name == "sheared":
        from ladder_quantities import sheared_scene
        return sheared_scene(150.0, 90.0)
    raise ValueError(name)


def _compile_events(records) -> list:
    """(time, what, actual_s, predicted_s, MB of C) of every "compiled X in ..." line of :mod:`cablesys.compiled`."""
    import re
    out, flags = [], {}
    for t, msg in records:
        start = re.match(r"compiling (.*) \([0-9.]+ MB of C, (.*?)\) into", msg)
        if start:
            opts = [a for a in start.group(2).split() if a.startswith("-O")]
            flags[start.group(1)] = opts[-1] if opts else "?"
        m = re.match(r"compiled (.*) in ([0-9.e+-]+) s \(predicted about ([0-9.e+-]+) s, ([0-9.]+) MB of C\)", msg)
        if m:
            out.append({"t": t, "what": m.group(1), "actual_s": float(m.group(2)), "predicted_s": float(m.group(3)),
                        "c_mb": float(m.group(4)), "flag": flags.get(m.group(1), "?")})
    return out


def child(name: str, quick: bool) -> dict:
    """One scene's run, in this (fresh) process, on the cache ``CABLESYS_CACHE`` names (empty)."""
    import logging
    import resource

    import numpy as np

    import cablesys
    import cablesys.compiled as compiled
    import cablesys.time_domain as td
    from cablesys.ladder import RungCache
    from cablesys.time_domain import record

    records, compiler_runs, runs = [], [], []

    class Keep(logging.Handler):
        def emit(self, rec):
            records.append((time.perf_counter(), rec.getMessage()))
    logging.getLogger("cablesys.compiled").addHandler(Keep(level=logging.INFO))
    logging.getLogger("cablesys.compiled").setLevel(logging.INFO)

    real_cc, real_sim = compiled._run_compiler, td.simulate

    def timed_cc(argv, workdir):          # the compiler's CPU time (its process and children), load-independent
        c0, w0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        out = real_cc(argv, workdir)
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        compiler_runs.append({"t": time.perf_counter(), "wall_s": time.perf_counter() - w0,
                              "cpu_s": (c1.ru_utime + c1.ru_stime) - (c0.ru_utime + c0.ru_stime)})
        return out

    def timed_sim(*a, **k):               # every run the ladder makes (candidates, checks, the extrapolation's)
        c0 = time.process_time()
        r = real_sim(*a, **k)
        held = sum(np.asarray(v).nbytes for v in (r.time, r.states, r.modes)) + \
            sum(np.asarray(v).nbytes for v in (*r.data.values(), *r.profiles.values()))
        steps = int(r.stats.get("nsteps", 0))
        sim = k.get("simulator")
        if not steps and sim is not None and r.stats.get("method") in ("rk", "rkc", "collocation"):
            steps = int(sim.settings.steps_per_output) * (int(np.asarray(r.time).size) - 1)   # fixed step: what it took
        runs.append({"t": time.perf_counter(), "nsteps": steps,
                     "wall_s": float(r.stats.get("wall_s", 0.0)), "cpu_s": time.process_time() - c0,
                     "held_bytes": float(held), "outputs": int(np.asarray(r.time).size), "success": bool(r.success)})
        return r
    compiled._run_compiler, td.simulate = timed_cc, timed_sim
    scene = make_scene(name, quick)
    marks = {"plan": None, "runs": []}

    def on_plan(prediction):
        marks["plan"] = (time.perf_counter(), prediction.as_dict())

    def on_run(description, candidate):
        marks["runs"].append((time.perf_counter(), description, bool(candidate)))
        return None, None
    cache = RungCache()
    t0 = time.perf_counter()
    # quick: Wang's model named (the choice's own cold compiles, the describing function's, take 10-30 s)
    result = cablesys.simulate(scene, cache=cache, on_plan=on_plan, on_run=on_run, model="wang" if quick else None)
    t_end = time.perf_counter()
    info = result.stats["model"]
    t_plan, pred = marks["plan"]
    # what the prediction covers: the candidate run (it ends where the next run of the plan starts: a check, or a
    # rejected candidate's successor), or every run of the extrapolation's plan (N / 4, N / 2, N)
    extrapolated = "extrapolated" in info
    n_runs = int(pred.get("runs", 1))
    later = [t for t, _, _ in marks["runs"] if t > t_plan]
    t_cut = later[n_runs] if len(later) > n_runs else t_end
    covered = [r for r in runs if t_plan <= r["t"] <= t_cut][:n_runs]
    events = _compile_events(records)
    for e, c in zip(events, compiler_runs):           # one compiler run per "compiled" line, in order
        e.update(compiler_wall_s=c["wall_s"], compiler_cpu_s=c["cpu_s"])
    mine = [e for e in events if t_plan <= e["t"] <= t_cut]
    what = pred["what"].split(" (")[0]               # "segmented N = 16 (extrapolation)": the predicted model
    p_name, _, p_n = what.partition(" N = ")
    model = cache.model(scene, p_name, int(p_n or 1))
    sx = lambda f: f if f.is_a("SXFunction") else f.expand()      # SX operations, as the prediction counts them
    ops = float(sx(model.ode).n_instructions() + sx(model.outputs).n_instructions())
    actual = {"steps": sum(r["nsteps"] for r in covered), "operations": ops,
              "compile_s": sum(e["actual_s"] for e in mine),
              "compile_cpu_s": sum(e.get("compiler_cpu_s", 0.0) for e in mine),
              "run_s": sum(r["wall_s"] for r in covered), "run_cpu_s": sum(r["cpu_s"] for r in covered),
              "memory_bytes": max((r["held_bytes"] for r in covered), default=0.0) * record._COPIES}
    return {"scene": name, "scene_name": scene.name, "duration_s": scene.numerics.duration,
            "model": {"name": info["name"], "segments": info.get("segments"), "extrapolated": extrapolated,
                      "method": result.stats.get("method")},
            "predicted_model": {"name": p_name, "segments": int(p_n or 1), "method": pred["method"]},
            "success": bool(result.success), "prediction": pred, "actual": actual,
            "plan_runs": [{"description": d, "candidate": c} for _, d, c in marks["runs"]],
            "runs": [dict(r, t=r["t"] - t0, covered=r in covered) for r in runs],
            "compiles": [dict(e, t=e["t"] - t0, phase="choice" if e["t"] < t_plan else
                              ("predicted" if e["t"] <= t_cut else "after")) for e in events],
            "choice_compile_s": sum(e["actual_s"] for e in events if e["t"] < t_plan),
            "after_compile_s": sum(e["actual_s"] for e in events if e["t"] > t_cut),
            "total_s": t_end - t0}


def _load() -> list:
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:                   # pragma: no cover
        return []


def run_scene(name: str, quick: bool) -> dict:
    """:func:`child` of ``name`` in a fresh process on a private cold cache."""
    with tempfile.TemporaryDirectory(prefix="cablesys-predict-") as cache:
        env = dict(os.environ, CABLESYS_CACHE=cache, CABLESYS_COMPILE="1", MPLBACKEND="Agg")
        for k in ("CABLESYS_CACHE_DIR", "CABLESYS_CFLAGS"):
            env.pop(k, None)
        argv = [sys.executable, __file__, "--out", cache, "--child", name] + (["--quick"] if quick else [])
        proc = subprocess.run(argv, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"{name} failed:\n{proc.stderr[-4000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def ratios(row: dict) -> dict:
    """actual / predicted of every quantity of :data:`QUANTITIES` (None where the prediction is 0)."""
    out = {}
    for key, _ in QUANTITIES:
        p, a = float(row["prediction"].get(key) or 0.0), float(row["actual"][key])
        out[key] = a / p if p > 0 else None
        if key in CPU:
            out[CPU[key]] = float(row["actual"][CPU[key]]) / p if p > 0 else None
    return out


def fit_compile_rates(rows: list) -> dict:
    """Per optimization flag: least-squares seconds per MB of C through the compiles' (MB, time - COMPILE_START_S),
    of their wall time and of the compiler's CPU time (its processes', which the machine's load affects less), and
    each compile's ratio actual / predicted (:func:`cablesys.compiled.predicted_compile_s`)."""
    from cablesys.compiled import COMPILE_START_S
    flags = {}
    for r in rows:
        for c in r["compiles"]:
            flags.setdefault(c["flag"], []).append(c)
    out = {}
    for flag, cs in flags.items():
        den = sum(c["c_mb"] ** 2 for c in cs)
        fit = lambda key: (sum(c["c_mb"] * (c[key] - COMPILE_START_S) for c in cs if key in c) / den) if den else None
        out[flag] = {"s_per_mb_wall": fit("actual_s"), "s_per_mb_cpu": fit("compiler_cpu_s"), "compiles": len(cs),
                     "ratio_actual_predicted": [c["actual_s"] / c["predicted_s"] for c in cs if c["predicted_s"] > 0]}
    return out


def plot(rows: list, path: Path) -> None:
    """Predicted (x) against actual (y), log-log, the 1:1 line and the factor-3 band; one colour per scene; wall
    times filled, the same measured in CPU time (compiler, stepping) open."""
    from _common import setup_matplotlib
    plt = setup_matplotlib()
    colours = {r["scene"]: f"C{i}" for i, r in enumerate(rows)}
    fig, axes = plt.subplots(2, 3, figsize=(14, 8.6))
    order = ("steps", "operations", "memory_bytes", "compile_s", "run_s")
    labels = dict(QUANTITIES)
    for ax, key in zip(axes.flat, order):
        label = labels[key]
        pts = []
        for r in rows:
            p = float(r["prediction"].get(key) or 0.0)
            pts.append((p, float(r["actual"][key]), r["scene"], True))
            if key in CPU:
                pts.append((p, float(r["actual"][CPU[key]]), r["scene"], False))
        pts = [q for q in pts if q[0] > 0 and q[1] > 0]
        if not pts:
            ax.set_title(f"{label}: nothing to compare")
            continue
        lo = min(min(p, a) for p, a, _, _ in pts) / 4
        hi = max(max(p, a) for p, a, _, _ in pts) * 4
        line = [lo, hi]
        ax.fill_between(line, [v / FACTOR for v in line], [v * FACTOR for v in line], color="0.9")
        ax.plot(line, line, "k-", lw=1)
        for p, a, name, wall in pts:
            ax.plot(p, a, "o", ms=7, color=colours[name], mfc=colours[name] if wall else "none")
            if wall:
                k = list(colours).index(name)
                ax.annotate(name, (p, a), textcoords="offset points", xytext=(5, -3 + 7 * (k % 3 - 1)), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
        ax.set_xlabel(f"predicted {label}")
        ax.set_ylabel(f"actual {label}")
        ax.set_title(label + (" (filled: wall, open: CPU)" if key in CPU else ""))
    key_ax = axes.flat[-1]
    key_ax.axis("off")
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    handles = [Patch(color="0.9", label=f"within {FACTOR:g}x"), Line2D([], [], color="k", lw=1, label="actual = predicted"),
               Line2D([], [], marker="o", ls="", color="0.3", label="wall time"),
               Line2D([], [], marker="o", ls="", color="0.3", mfc="none", label="CPU time (compiler, stepping)")]
    handles += [Line2D([], [], marker="o", ls="", color=colours[r["scene"]],
                       label=f"{r['scene']}: {r['prediction']['what']}") for r in rows]
    key_ax.legend(handles=handles, loc="center", fontsize=8, frameon=False)
    fig.suptitle("cablesys.ladder.plan_cost: the run's cost predicted before its build vs actual (cold cache, compiled)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None) -> int:
    from _common import parse_args, write_json

    def extra(ap):
        ap.add_argument("--child", default=None, help=argparse_hidden())
    args = parse_args(__doc__.splitlines()[0], argv, extra)
    if args.child:
        print(json.dumps(child(args.child, args.quick)))
        return 0
    names = ("dale",) if args.quick else SCENES
    load0, date = _load(), time.strftime("%Y-%m-%d %H:%M:%S %Z")
    rows = []
    for name in names:
        row = run_scene(name, args.quick)
        row["ratio"] = ratios(row)
        row["within_3x"] = {k: (v is not None and 1 / FACTOR <= v <= FACTOR) for k, v in row["ratio"].items()}
        rows.append(row)
        print(f"{name}: {row['model']['name']} N = {row['model']['segments']}, ratios actual / predicted "
              + ", ".join(f"{k} {v:.3g}" if v is not None else f"{k} -" for k, v in row["ratio"].items()), flush=True)
    res = {"machine": platform.machine(), "platform": platform.platform(), "cpus": os.cpu_count(),
           "load_before": load0, "load_after": _load(), "date": date, "quick": bool(args.quick),
           "factor": FACTOR, "rows": rows, "compile_rates": fit_compile_rates(rows)}
    write_json(args.out / "run_prediction.json", res)
    plot(rows, args.out / "run_prediction.png")
    print(f"wrote {args.out}/run_prediction.json, run_prediction.png")
    return 0


def argparse_hidden():
    import argparse
    return argparse.SUPPRESS


if __name__ == "__main__":
    raise SystemExit(main())
