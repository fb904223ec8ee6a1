"""Throughput of parameter sweeps: a plain loop vs ``cablesys.sweep`` serial, on all local cores, on Dask.

Two sweeps of the Dale et al. water-channel scene (Wang 1971 Table 1):

* time domain: ``cable.ae`` (log) x the top-motion frequency (x and y zipped), 1,000 cases of a
  20 s run (quick: 8 cases of 6 s);
* RAO: ``cable.ae`` x ``body.weight``, 10,000 linearizations with natural frequencies and RAOs on
  300 frequencies (quick: 100).

Each is timed four ways in this one process and run: the baseline loop a user writes by hand
(one model, one Simulator, edit ``p`` by label, call the integrator / linearize, no metrics, no
storage), ``sweep(workers=1)`` (the same work plus metrics, case records and the Dataset),
``sweep()`` on every local core (processes), and ``sweep(scheduler=LocalCluster)`` with one
single-threaded worker process per core. Reported: cases per second (model builds included, as a
user sees them), the per-case overhead of ``sweep`` over the bare loop with the models already
built (``sweep`` builds them once per process and keeps them: a second serial call is warm), and
the parallel efficiency (serial sweep time / (cores x parallel sweep time)). Worker start-up
(process fork, a model per worker, cluster start) is inside the parallel timings.

The machine load (``os.getloadavg``) is recorded before and after: on a shared machine the
parallel numbers measure the cores actually available, not the hardware.

Usage: python studies/bench_sweep.py --out DIR [--quick]
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

import cablesys
from cablesys import units as U
from cablesys.linear import linearize, modes, rao
from cablesys.model import build_model
from cablesys.plots import save_figure
from cablesys.scene import OMEGA_N_MEASURED, dale_scene
from cablesys.sweeps.backends import local_cores
from cablesys.time_domain import IntegratorSettings, Simulator, initial_state

FX, FY = "top_motion.x[0].frequency", "top_motion.y[0].frequency"


def td_case(n_ae: int, n_w: int, duration: float):
    scene = dale_scene(duration=duration)
    w = list(np.linspace(0.5, 2.0, n_w) * OMEGA_N_MEASURED)
    return scene, {"cable.ae": list(np.geomspace(5.0, 1000.0, n_ae) * U.LBF), FX: w, FY: w}, [(FX, FY)]


def rao_case(n_ae: int, n_wb: int):
    scene = dale_scene(duration=1.0)
    wb = scene.body.weight
    return scene, {"cable.ae": list(np.geomspace(5.0, 1000.0, n_ae) * U.LBF),
                   "body.weight": list(np.linspace(0.8, 1.5, n_wb) * wb)}, False


def loop_time_domain(scene, vary) -> tuple[float, float]:
    """The hand-written loop: one Simulator, values into p by label, the bare integrator call.
    Returns (wall with the model build, wall of the cases only)."""
    t_build = time.perf_counter()
    model = build_model(scene)
    num = scene.numerics
    sim = Simulator(model, scene.output_times, IntegratorSettings(method=num.integrator, rtol=num.rtol, atol=num.atol))
    lab = model.layout
    p0 = model.parameters(scene)
    t0 = time.perf_counter()
    for ae in vary["cable.ae"]:
        for w in vary[FX]:
            p = p0.copy()
            p[lab.index("cable.ae")] = ae
            p[lab.index(FX)] = w
            p[lab.index(FY)] = w
            sim.run(p, initial_state(scene, model, p))
    return time.perf_counter() - t_build, time.perf_counter() - t0


def loop_rao(scene, vary, n_omega=300) -> tuple[float, float]:
    t_build = time.perf_counter()
    model = build_model(scene)
    lab = model.layout
    p0 = model.parameters(scene)
    t0 = time.perf_counter()
    for ae in vary["cable.ae"]:
        for wb in vary["body.weight"]:
            p = p0.copy()
            p[lab.index("cable.ae")] = ae
            p[lab.index("body.weight")] = wb
            lin = linearize(model, p)
            md = modes(lin)
            rao(lin, (np.arange(n_omega) + 0.5) / n_omega * 3.0 * float(np.max(md.omega_undamped)))
    return time.perf_counter() - t_build, time.perf_counter() - t0


def timed_sweep(scene, vary, analysis, zip_, **kw) -> tuple[float, object]:
    t0 = time.perf_counter()
    ds = cablesys.sweep(scene, vary, analysis, zip=zip_, progress=False, **kw)
    wall = time.perf_counter() - t0
    bad = int((ds["status"] != "ok").sum())
    if bad:
        raise RuntimeError(f"{bad} cases not ok in the benchmark sweep: {ds['message'].values.ravel()[:3]}")
    return wall, ds


def bench(name, scene, vary, analysis, zip_, loop, cores, with_dask=True) -> dict:
    n = int(np.prod([len(v) for k, v in vary.items() if k != FY]))
    t_loop, t_loop_warm = loop(scene, vary)
    t_serial, ds1 = timed_sweep(scene, vary, analysis, zip_, workers=1)         # builds its model: cold
    t_serial_warm, _ = timed_sweep(scene, vary, analysis, zip_, workers=1)      # this process's cache: warm
    t_par, dsp = timed_sweep(scene, vary, analysis, zip_, workers=cores)
    same = all(np.array_equal(ds1[v].values, dsp[v].values, equal_nan=True)
               for v in ds1.data_vars if ds1[v].dtype.kind == "f" and not v.startswith(("stats_", "wall_")))
    row = {"cases": n, "loop_s": t_loop, "loop_cases_only_s": t_loop_warm, "sweep_serial_s": t_serial,
           "sweep_serial_warm_s": t_serial_warm, "sweep_parallel_s": t_par, "cores": cores,
           "parallel_equals_serial": bool(same),
           "throughput_cases_per_s": {"loop": n / t_loop, "sweep_serial": n / t_serial, "sweep_parallel": n / t_par},
           "overhead_per_case_s": (t_serial_warm - t_loop_warm) / n,
           "overhead_fraction": (t_serial_warm - t_loop_warm) / t_loop_warm,
           "parallel_efficiency": t_serial / (cores * t_par),
           "speedup_over_loop": t_loop / t_par}
    if with_dask:
        try:
            import distributed
        except ImportError:
            row["dask"] = "not installed (pip install cablesys[sweep])"
        else:
            t0 = time.perf_counter()
            with distributed.LocalCluster(n_workers=cores, threads_per_worker=1, processes=True,
                                          dashboard_address=None) as cluster, distributed.Client(cluster) as client:
                t_start = time.perf_counter() - t0
                t_dask, _ = timed_sweep(scene, vary, analysis, zip_, scheduler=client)
            row.update({"dask_s": t_dask, "dask_cluster_start_s": t_start,
                        "dask_efficiency": t_serial / (cores * t_dask)})
            row["throughput_cases_per_s"]["dask"] = n / t_dask
    print(f"{name}: {n} cases; cases/s " + ", ".join(f"{k} {v:.3g}" for k, v in row["throughput_cases_per_s"].items())
          + f"; overhead {row['overhead_fraction']:+.1%} per case; parallel efficiency {row['parallel_efficiency']:.0%}"
          + (f", Dask {row['dask_efficiency']:.0%}" if "dask_efficiency" in row else ""))
    return row


def plot(results, path):
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, len(results), figsize=(5.2 * len(results), 4.0), squeeze=False)
    for ax, (name, r) in zip(axes[0], results.items()):
        keys = list(r["throughput_cases_per_s"])
        vals = [r["throughput_cases_per_s"][k] for k in keys]
        bars = ax.bar(keys, vals, color=["0.6", "tab:blue", "tab:green", "tab:orange"][:len(keys)])
        ax.bar_label(bars, fmt="%.3g", fontsize=8)
        ax.set(ylabel="cases per second", title=f"{name}: {r['cases']} cases, {r['cores']} cores\n"
                                                 f"efficiency {r['parallel_efficiency']:.0%} (processes)"
                                                 + (f", {r['dask_efficiency']:.0%} (Dask)" if "dask_efficiency" in r else ""))
        ax.tick_params(axis="x", labelsize=8)
    return save_figure(fig, path)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    cores = local_cores()
    load0 = os.getloadavg()
    if args.quick:
        td, rr = td_case(2, 4, 6.0), rao_case(10, 10)
    else:
        td, rr = td_case(25, 40, 20.0), rao_case(100, 100)
    results = {"time_domain": bench("time domain", *td[:2], "run", td[2], loop_time_domain, cores),
               "rao": bench("RAO", *rr[:2], "rao", rr[2], loop_rao, cores)}
    doc = {"cores": cores, "load_average_before": load0, "load_average_after": os.getloadavg(),
           "quick": args.quick, "note": "cores shared with other processes: efficiency measures the cores actually "
                                        "available during the run (see load_average_*)", **results}
    write_json(args.out / "bench_sweep.json", doc)
    plot(results, args.out / "bench_sweep.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
