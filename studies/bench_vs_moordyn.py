"""cablesys side by side with MoorDyn v2 (a lumped-mass peer), in one run, same inputs.

Cases (issue 11): the Dale scene (Wang 1971 Table 1, 10 and 40 elements) and the 300 m / 2 t
sphere heave scene at T = 10 s (taut) and T = 6 s (slack), 20 and 80 elements. Every scene is
started with the same smooth ramp on both sides (3 forcing periods), so the comparison is of
the forced motion, not of how each code rings after an abrupt start.

Per case and element count N:
- MoorDyn at its largest stable step (RK4, found by halving from the axial estimate);
- cablesys's segmented model at the same N, at the loosest tolerance whose body amplitudes are
  within 0.5 % and top-tension extremes within 1 % of its own tight-tolerance run (matched accuracy);
- Wang's 2-DOF model (``wang``) and the model ladder's ``auto`` choice, each against a converged
  segmented reference (2 x the largest N): ``wang_speedup``, ``auto_speedup``, ``auto_error``
  against MoorDyn at the smallest N of the case (issues 12 and 13).
Times are seconds of wall time per simulated second, measured on a second run (the first builds
and compiles; its build time is reported apart). A peer is a benchmark and a sanity check, not the
truth: where cablesys and MoorDyn differ by more than 2 % in a converged taut case we say why.

    python studies/bench_vs_moordyn.py --out DIR [--quick]
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import setup_matplotlib, write_json  # noqa: E402
from _moordyn import largest_stable_dt, run_moordyn  # noqa: E402

import cablesys  # noqa: E402
from cablesys.ladder import metrics as M  # noqa: E402
from cablesys.ladder import simulate_auto  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.scene import dale_scene, load_scene  # noqa: E402
from cablesys.time_domain import simulate  # noqa: E402

DATA = Path(cablesys.__file__).resolve().parent / "data"
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6)


def _ramped(scene, period, duration):
    top = dataclasses.replace(scene.top_motion, ramp_s=3 * period)
    return dataclasses.replace(scene, top_motion=top).with_numerics(duration=duration)


def cases(quick: bool):
    """(name, scene, period, element counts, taut?)"""
    dur = 20.0 if quick else 60.0
    w = dale_scene().top_motion.x[0].frequency
    out = [("dale", _ramped(dale_scene(duration=dur), 2 * math.pi / w, dur), 2 * math.pi / w, (10,) if quick else (10, 40), True)]
    if quick:
        return out
    heave = load_scene(DATA / "heave_300m.toml")
    for period, taut in ((10.0, True), (6.0, False)):
        sine = dataclasses.replace(heave.top_motion.y[0], frequency=2 * math.pi / period)
        sc = dataclasses.replace(heave, name=f"300 m / 2 t sphere, 1 m heave, T = {period:g} s",
                                 top_motion=dataclasses.replace(heave.top_motion, y=(sine,)))
        out.append((f"heave_T{period:g}", _ramped(sc, period, 60.0), period, (20, 80), taut))
    return out


COMPILE_MAX_ELEMENTS = 20     # gcc's time and memory grow faster than linearly with the segmented
# model's straight-line code (N = 80: minutes and >10 GB at -O1): larger models run in CasADi's VM


@contextlib.contextmanager
def _compiled(enabled: bool):
    """Run cablesys compiled (cached C, the default) or in CasADi's virtual machine."""
    old = os.environ.get("CABLESYS_COMPILE")
    os.environ["CABLESYS_COMPILE"] = "1" if enabled else "0"
    try:
        yield
    finally:
        if old is None:
            os.environ.pop("CABLESYS_COMPILE", None)
        else:
            os.environ["CABLESYS_COMPILE"] = old


def _segments(scene, n):
    return scene.replace_section(0, cable={"segments": n})


def _stats(result, period):
    s = M.statistics(result, period)
    w = M.window(np.asarray(result.time), period)
    tb = np.asarray(result["tension_bottom"])[w]
    s["slack_fraction_bottom"] = float(np.mean(tb <= 0.0))
    return s


def _timed(fn):
    """(result, wall of the second call, wall of the first call): the first builds and compiles."""
    t0 = time.perf_counter()
    fn()
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = fn()
    return r, time.perf_counter() - t0, first


def _moordyn_stats(r, period):
    class _R:                        # the metrics read a result by label and time
        time = r["time"]

        def __getitem__(self, k):
            return r[k]
    return _stats(_R(), period)


def _diff(a: dict, b: dict) -> dict:
    """Relative differences of a against b: body amplitudes and tension extremes."""
    return M.errors(a, b)


METHODS = ("cvodes", "cvodes-bdf2")


def _matched(run, tight_stats, period):
    """The fastest (method, rtol) whose run is within 0.5 % (body amplitudes) and 1 % (top and
    body-end tension extremes) of ``tight_stats``: (result, wall of a second run, first-call wall,
    settings), or None."""
    best = None
    for method in METHODS:
        for rtol in RTOLS:
            try:
                res, wall, first = _timed(lambda: run(method, rtol))
            except Exception:                 # noqa: BLE001 - a failing setting is skipped
                continue
            if not res.success:
                continue
            e = _diff(_stats(res, period), tight_stats)
            if e["body"] <= 0.005 and e["tension"] <= 0.01:
                if best is None or wall < best[1]:
                    best = (res, wall, first, {"method": method, "rtol": rtol, "error_vs_own_tight": e})
                break                          # looser tolerances of this method failed already or are slower
    return best


def bench_case(name, scene, period, ns, taut, quick):
    dur = scene.numerics.duration
    row = {"case": name, "scene": scene.name, "duration_s": dur, "period_s": period, "taut": taut, "by_n": []}
    n_conv = 2 * max(ns) if taut else max(ns)   # partial slack: 2x the largest N is out of reach here
    with _compiled(False):
        ref = simulate(_segments(scene, n_conv), method="cvodes", rtol=1e-7, atol=1e-10)
    ref_stats = _stats(ref, period)
    row["reference"] = {"segments": n_conv, "stats": ref_stats, "success": ref.success}
    md_small = None
    for n in ns:
        sc = _segments(scene, n)
        dt = largest_stable_dt(sc, n, probe_s=min(dur, 10.0))
        md, _, _ = _timed(lambda: run_moordyn(sc, n, dt))
        md_stats = _moordyn_stats(md, period)
        with _compiled(n <= COMPILE_MAX_ELEMENTS):
            tight = simulate(sc, method="cvodes", rtol=1e-7, atol=1e-10)
            tight_stats = _stats(tight, period)
            m = _matched(lambda meth, rtol: simulate(sc, method=meth, rtol=rtol, atol=rtol * 1e-3), tight_stats, period)
        entry = {"segments": n, "cablesys_compiled": n <= COMPILE_MAX_ELEMENTS, "moordyn_dt_s": dt, "moordyn_s_per_s": md["wall_s"] / dur,
                 "moordyn_stable": md["stable"], "moordyn_stats": md_stats,
                 "moordyn_slack_fraction_per_segment": md["slack_fraction_per_segment"].tolist(),
                 "cablesys_stats": tight_stats,
                 "cablesys_vs_moordyn": _diff(tight_stats, md_stats),
                 "cablesys_error_vs_converged": _diff(tight_stats, ref_stats),
                 "moordyn_error_vs_converged": _diff(md_stats, ref_stats)}
        if m:
            res, wall, first, how = m
            entry.update(cablesys_s_per_s=wall / dur, speedup=md["wall_s"] / wall, cablesys_settings=how,
                         cablesys_build_s=first - wall, cablesys_steps=res.stats.get("nsteps"),
                         cablesys_timing={k: res.stats.get(k) for k in ("build_s", "load_s", "run_s")})
        else:
            entry.update(cablesys_s_per_s=None, speedup=None, note="no setting met matched accuracy")
        row["by_n"].append(entry)
        if md_small is None:
            md_small = (n, md["wall_s"])
    # Wang's 2-DOF model and the ladder's auto choice: matched accuracy against their own tight runs,
    # error against the converged segmented reference, speed against MoorDyn at the smallest N
    wang_model = build_model(scene)       # Wang's 2-DOF model itself (issue 13); auto includes its choosing (issue 12)
    for label in ("wang",):
        run = lambda meth, rtol: simulate(scene, model=wang_model, method=meth, rtol=rtol, atol=rtol * 1e-3)
        compiled = True
        try:
            with warnings.catch_warnings(), _compiled(compiled):
                warnings.simplefilter("ignore")
                tight = run("cvodes", 1e-8)
                m = _matched(run, _stats(tight, period), period)
        except Exception as err:          # noqa: BLE001 - a failing rung is a result of the benchmark
            row[label] = {"failed": f"{type(err).__name__}: {err}"}
            continue
        if m is None:
            row[label] = {"failed": "no setting met matched accuracy", "error": _diff(_stats(tight, period), ref_stats)}
            continue
        res, wall, first, how = m
        row[label] = {"s_per_s": wall / dur, "build_s": first - wall, "compiled": compiled, "error": _diff(_stats(res, period), ref_stats),
                      "settings": how, "steps": res.stats.get("nsteps"), "model": res.stats.get("model"),
                      "speedup_vs_moordyn_n": md_small[0], "speedup": md_small[1] / wall}
    row["auto"] = _auto(scene, period, ref_stats, md_small)
    row["wang_speedup"] = row["wang"].get("speedup")
    row["auto_speedup"] = row["auto"].get("speedup")            # with the choice (what the user waits for)
    row["auto_speedup_run_only"] = row["auto"].get("speedup_run_only")
    row["auto_choose_s"] = row["auto"].get("choose_s")
    row["auto_error"] = row["auto"].get("error")
    return row


AUTO_REPEATS = 3


def _auto(scene, period, ref_stats, md_small):
    """Model auto at the default tolerance as a user runs it: its own rung, element count and
    integrator settings (issue 12), one RungCache for the calls. The first call builds (models,
    compiled code, the describing-function solver); the best of AUTO_REPEATS further calls gives
    ``choose_s`` (steady state, describing function, estimates), ``check_s`` (a posteriori runs) and
    ``run_s`` (the chosen run: stepping and outputs, as MoorDyn's time is). ``speedup`` counts the
    choice and the checks (choose_s + check_s + run_s), ``speedup_run_only`` the run alone; both
    against MoorDyn at the smallest N of the case. ``error``: against the converged reference."""
    from cablesys.ladder.rungs import RungCache
    cache = RungCache()
    dur = scene.numerics.duration
    try:
        with warnings.catch_warnings(), _compiled(True):    # auto compiles up to 20 elements, the VM above
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
            "error": _diff(_stats(res, period), ref_stats) if res.success else None, "success": bool(res.success),
            "model": res.stats.get("model"), "method": res.stats.get("method"), "steps": res.stats.get("nsteps"),
            "compiled": res.stats.get("compiled"), "speedup_vs_moordyn_n": md_small[0],
            "speedup": md_small[1] / waited, "speedup_run_only": md_small[1] / t["run_s"]}


def plot(rows, path):
    plt = setup_matplotlib()
    fig, ax = plt.subplots(figsize=(8, 4.8))
    labels, md, cs = [], [], []
    for r in rows:
        for e in r["by_n"]:
            labels.append(f"{r['case']}\nN = {e['segments']}")
            md.append(e["moordyn_s_per_s"])
            cs.append(e["cablesys_s_per_s"] or np.nan)
        for k in ("wang", "auto"):
            if "s_per_s" in r.get(k, {}):
                labels.append(f"{r['case']}\n{k}")
                md.append(np.nan)
                cs.append(r[k]["s_per_s"])
    x = np.arange(len(labels))
    ax.bar(x - 0.2, md, 0.4, label="MoorDyn v2 (largest stable RK4 step)")
    ax.bar(x + 0.2, cs, 0.4, label="cablesys (matched accuracy)")
    ax.set_yscale("log")
    ax.set_xticks(x, labels, fontsize=8)
    ax.set_ylabel("wall time per simulated second (s/s)")
    ax.set_title("cablesys vs MoorDyn, same scenes, same run")
    ax.legend(fontsize=8)
    from cablesys.plots import save_figure
    save_figure(fig, path)


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path, help="output directory (created if missing)")
    ap.add_argument("--quick", action="store_true", help="Dale, 10 elements, 20 s (for tests)")
    ap.add_argument("--case", action="append", default=None,
                    help="run only these cases (dale, heave_T10, heave_T6); repeatable")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    for c in cases(args.quick):
        if args.case and c[0] not in args.case:
            continue
        rows.append(bench_case(*c, args.quick))
        # written after every case: a long benchmark that is stopped keeps what it measured
        write_json(args.out / "bench_vs_moordyn.json", {"cases": rows, "quick": args.quick})
    plot(rows, args.out / "bench_vs_moordyn.png")
    for r in rows:
        for e in r["by_n"]:
            print(f"{r['case']:10s} N={e['segments']:3d}  MoorDyn {e['moordyn_s_per_s']:.4g} s/s (dt {e['moordyn_dt_s']:.3g})  "
                  f"cablesys {e['cablesys_s_per_s'] or float('nan'):.4g} s/s  speedup {e['speedup'] or float('nan'):.3g}  "
                  f"vs MoorDyn {e['cablesys_vs_moordyn']}")
        print(f"{r['case']:10s} wang speedup {r['wang_speedup']}, auto speedup {r['auto_speedup']} (run only "
              f"{r.get('auto_speedup_run_only')}, choosing {r.get('auto_choose_s')} s), auto error {r['auto_error']}")


if __name__ == "__main__":
    main()
