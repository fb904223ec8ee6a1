"""The ladder's cost weights, measured: each constant the choice prices rungs by, against the wall-time ratio it
stands for, on this machine, in one run.

The ladder (:mod:`cablesys.ladder.rung`) prices a run in units of the node model's element (the segmented rung at
N costs N) and of Wang's straight cable (cost 1). Where a weight is a constant rather than a count it stands for a
ratio of run times; this benchmark measures each ratio, runs compiled as users run (the VM in ``--quick``), each
run the least ``run_s`` (:func:`cablesys.simulate`'s ``stats["ladder_timing"]``: the run alone, no choice, no
build, no check) over ``repeats`` calls on one cache after a first call that builds and compiles, every run at
the same rtol (:data:`RTOL`, the ladder's at a 1 % tolerance; a rung's default rtol follows its own stated error,
which would compare integrator tolerances instead of models):

- ``Wang.straight_cost`` (1, the unit), ``QuasiStatic.straight_cost`` and ``Frequency.straight_cost``: the
  straight quasi-static cable's and the periodic orbit's time over Wang's on the same scene;
- ``quasistatic.STIFF_QS_COST``: the quasi-static segmented cable at N over the node model at N where its stretch
  is stiff (omega / omega_ax <= 1 / ``choice.STIFF_RATIO``: the Dale channel cable at 2 omega_n);
- ``quasistatic.EXPLICIT_COST`` and ``EXPLICIT_COST_MAX_ELEMENTS``: the quasi-static segmented cable stepped by
  the compiled rk23 pair over the node model at the same N where the stretch is not that stiff (the 1000 m heavy
  wire, omega / omega_ax = 0.15), N up to past the cap;
- ``segmented.CHECK_COST``: a run of N checked a posteriori, (t(N) + t(N / 2)) / t(N), for the node model.

``CHECK_ACCEPT`` is not a cost (it bounds the Richardson estimate's ratio to the actual error, from
studies/model_ladder.py) and is not measured here.

Writes ``rung_costs.json`` (the machine, its load, every run, each ratio beside its constant) and
``rung_costs.png`` to ``--out``; ``studies/results/rung_costs.json`` is the committed measurement the constants'
docstrings name.
"""

from __future__ import annotations

import os
import platform
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import casadi  # noqa: E402
import numpy as np  # noqa: E402
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402
from segmented_convergence import slack_scene  # noqa: E402

import cablesys  # noqa: E402
from cablesys.compiled import compiles  # noqa: E402
from cablesys.errors import NumericalWarning  # noqa: E402
from cablesys.ladder import RungCache  # noqa: E402
from cablesys.ladder.choice import STIFF_RATIO  # noqa: E402
from cablesys.ladder.indicators import scene_numbers  # noqa: E402
from cablesys.ladder.rung import quasistatic, segmented  # noqa: E402
from cablesys.ladder.rungs import get_rung  # noqa: E402
from cablesys.scene import dale_scene, heavy_wire_scene  # noqa: E402

RTOL = 1e-4
"""Every run's relative tolerance: the ladder's at its default 1 % body tolerance (a hundredth of it,
:func:`cablesys.ladder.run_settings.integrator_settings`), the same for the rungs compared."""


def scenes(quick: bool) -> dict:
    """The benchmark's scenes (short in quick mode)."""
    if quick:
        return {"dale": dale_scene(omega_ratio=2.0, duration=6.0),
                "heavy1000": heavy_wire_scene(period=10.0, duration=20.0)}
    return {"dale": dale_scene(omega_ratio=2.0, duration=40.0),
            "heavy1000": heavy_wire_scene(period=10.0, duration=120.0),
            "heave_300m": slack_scene(period=10.0, duration=120.0, output_step=0.05)}   # taut at T = 10 s


def timed(scene, rung: str, segments: int | None, method: str | None, repeats: int, cache: RungCache) -> dict:
    """The least run time of ``simulate(scene, model=rung, segments=..., method=...)`` over ``repeats`` calls after
    a first (building) one, with the model and integrator that ran."""
    kw = {"model": rung, "cache": cache, "rtol": RTOL}
    if segments is not None:
        kw["segments"] = segments
    if method is not None:
        kw["method"] = method
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumericalWarning)
        t0 = time.perf_counter()
        first = cablesys.simulate(scene, **kw)
        first_s = time.perf_counter() - t0
        runs = [cablesys.simulate(scene, **kw).stats["ladder_timing"]["run_s"] for _ in range(repeats)]
    if not first.success:
        raise RuntimeError(f"{rung} N = {segments} on {scene.name}: {first.message}: a failed run has no cost to compare")
    info = first.stats.get("model", {})
    return {"rung": rung, "asked_segments": segments, "asked_method": method,
            "ran": info.get("name"), "segments": info.get("segments"),
            "integrator": first.stats.get("method"), "rtol": RTOL,
            "success": bool(first.success), "nsteps": int(first.stats.get("nsteps", 0) or 0),
            "first_call_s": first_s, "run_s": float(min(runs)), "run_s_all": [float(r) for r in runs]}


def measure(quick: bool, repeats: int) -> dict:
    """Every run and the ratios the constants stand for."""
    sc = scenes(quick)
    rows, ratios = [], {}

    def run(key, rung, n=None, method=None, cache=None):
        r = timed(sc[key], rung, n, method, repeats, cache or RungCache())
        r["scene"] = key
        rows.append(r)
        return r["run_s"]

    straight_keys = ("dale",) if quick else ("dale", "heave_300m")
    for key in straight_keys:
        wang = run(key, "wang")
        ratios.setdefault("quasi-static straight_cost", []).append(
            {"scene": key, "measured": run(key, "quasi-static", 1) / wang, "constant": get_rung("quasi-static").straight_cost})
        ratios.setdefault("frequency straight_cost", []).append(
            {"scene": key, "measured": run(key, "frequency") / wang, "constant": get_rung("frequency").straight_cost})

    stiff_ns = (2, 3) if quick else (3, 4, 6)
    for n in stiff_ns:
        ratios.setdefault("STIFF_QS_COST", []).append(
            {"scene": "dale", "segments": n, "constant": quasistatic.STIFF_QS_COST,
             "measured": run("dale", "quasi-static", n) / run("dale", "segmented", n)})

    explicit_ns = (4, 5) if quick else (4, 5, 6, 7, 8, 10)
    for n in explicit_ns:
        ratios.setdefault("EXPLICIT_COST", []).append(
            {"scene": "heavy1000", "segments": n, "constant": quasistatic.EXPLICIT_COST,
             "within_cap": n <= quasistatic.EXPLICIT_COST_MAX_ELEMENTS,
             "measured": run("heavy1000", "quasi-static", n, "rk23") / run("heavy1000", "segmented", n)})

    check_ns = (4,) if quick else (8, 16)
    for n in check_ns:
        cache = RungCache()
        ratios.setdefault("CHECK_COST", []).append(
            {"scene": "heavy1000", "segments": n, "constant": segmented.CHECK_COST,
             "measured": (run("heavy1000", "segmented", n, cache=cache) + run("heavy1000", "segmented", n // 2, cache=cache))
             / run("heavy1000", "segmented", n, cache=cache)})
    return {"rows": rows, "ratios": ratios,
            "scenes": {k: {"omega_over_omega_axial": scene_numbers(s).axial_ratio,
                           "omega_over_omega_string": scene_numbers(s).string_ratio, "duration_s": s.numerics.duration}
                       for k, s in sc.items()},
            "stiff_ratio": STIFF_RATIO}


def machine() -> dict:
    """Where the ratios were measured."""
    return {"platform": platform.platform(), "processor": platform.processor() or platform.machine(),
            "cpu_count": os.cpu_count(), "python": platform.python_version(), "casadi": casadi.__version__,
            "compiled": compiles(), "load_average": list(os.getloadavg()),
            "date_utc": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}


def plot(doc: dict, path: Path) -> Path:
    """Each constant (a bar) against its measured ratios (points, labelled by N or scene), on a log scale."""
    plt = setup_matplotlib()
    names = list(doc["ratios"])
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    for i, name in enumerate(names):
        entries = doc["ratios"][name]
        ax.hlines(entries[0]["constant"], i - 0.4, i + 0.4, color="k", lw=2.5,
                  label="constant in the ladder" if i == 0 else None)
        for j, e in enumerate(entries):
            x = i - 0.3 + 0.6 * (j + 0.5) / len(entries)
            ok = e.get("within_cap", True)
            ax.plot(x, e["measured"], "o" if ok else "x", color="C0" if ok else "C3", ms=7, mew=2,
                    label=("measured" if i == 0 and j == 0 else None))
            tag = f"N={e['segments']}" if "segments" in e else e["scene"]
            ax.annotate(tag, (x, e["measured"]), textcoords="offset points", xytext=(0, 7), ha="center", fontsize=7)
    if any(not e.get("within_cap", True) for es in doc["ratios"].values() for e in es):
        ax.plot([], [], "x", color="C3", mew=2, label="past EXPLICIT_COST_MAX_ELEMENTS")
    scenes = [sorted({e["scene"] for e in doc["ratios"][n]}) for n in names]
    ax.set_xticks(range(len(names)), [f"{n}\n({', '.join(sc)})" for n, sc in zip(names, scenes)], fontsize=8)
    ax.set_yscale("log")
    values = [e["measured"] for es in doc["ratios"].values() for e in es] + [es[0]["constant"] for es in doc["ratios"].values()]
    ax.set_ylim(0.5 * min(values), 3.0 * max(values))
    ax.set_xlim(-0.6, len(names) - 0.4)
    ax.set_ylabel("run-time ratio (-)")
    m = doc["machine"]
    ax.set_title(f"ladder cost weights: constant vs measured ({'compiled' if m['compiled'] else 'VM'}, rtol {RTOL:g}, "
                 f"{m['cpu_count']} cores, load {m['load_average'][0]:.1f})", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(True, which="major", axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv,
                      extra=lambda ap: ap.add_argument("--repeats", type=int, default=None,
                                                       help="calls per run after the building one (least taken)"))
    repeats = args.repeats or (1 if args.quick else 5)
    doc = {"what": __doc__.splitlines()[0], "quick": bool(args.quick), "repeats": repeats, "machine": machine()}
    if not args.quick and not compiles():
        sys.stderr.write("bench_rung_costs: no C compiler (or CABLESYS_COMPILE=0): the ratios are the VM's\n")
    doc.update(measure(args.quick, repeats))
    doc["machine"]["load_average_end"] = list(os.getloadavg())
    write_json(args.out / "rung_costs.json", doc)
    plot(doc, args.out / "rung_costs.png")
    for name, entries in doc["ratios"].items():
        got = ", ".join(f"{e['scene']}{' N=' + str(e['segments']) if 'segments' in e else ''} {e['measured']:.3g}"
                        for e in entries)
        print(f"{name:<28s} constant {entries[0]['constant']:<5g} measured {got}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
