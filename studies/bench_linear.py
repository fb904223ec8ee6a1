"""Benchmark: steady state + linearization + RAOs at 1000 frequencies, and the periodic solve
against simulating to steady state at equal accuracy (1e-4 of the amplitude), Dale scene at
omega / omega_n = 1. Usage: python studies/bench_linear.py --out DIR [--quick]

The periodic solve is timed cold (starting from the linear response, ``periodic_ms``) and along
a frequency sweep by continuation (``periodic_sweep_ms_per_frequency``: each orbit starts from
its neighbour's). The time domain to steady state is the shipped ``simulate`` (compiled, cached
model code), integration only (``wall_s``), from rest at the hanging steady state.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from cablesys.linear import rao
from cablesys.linear.linearization import linearize
from cablesys.linear.periodic import (
    periodic_steady_state,
    periodic_sweep,
    scene_input_amplitude,
)
from cablesys.linear.steady import steady_state
from cablesys.model import build_model
from cablesys.scene import dale_scene
from cablesys.time_domain import simulate

TARGET = 1e-4


def best_of(fn, n):
    ts = []
    for _ in range(n):
        t = time.perf_counter(); out = fn(); ts.append(time.perf_counter() - t)
    return min(ts), out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true", help="fewer repeats")
    args = ap.parse_args(argv)
    reps = 1 if args.quick else 5
    args.out.mkdir(parents=True, exist_ok=True)
    scene = dale_scene()
    model = build_model(scene)
    p = model.parameters(scene)
    omega = np.linspace(0.05, 5.0, 1000)
    rao(linearize(model, p), omega)                                   # one-time build of the AD functions
    t_rao, _ = best_of(lambda: rao(linearize(model, p, steady=steady_state(model, p)), omega), 20)
    lin = linearize(model, p)
    t_rao_only, _ = best_of(lambda: rao(lin, omega), 50)

    w, Z = scene_input_amplitude(scene)
    T = 2 * np.pi / w
    ref = periodic_steady_state(model, p, w, input_amplitude=Z, n_harmonics=40)      # reference orbit
    periodic_steady_state(model, p, w, input_amplitude=Z, n_harmonics=20)            # build
    t_per, sol = best_of(lambda: periodic_steady_state(model, p, w, input_amplitude=Z, n_harmonics=20), reps)
    sweep_w = w * np.linspace(0.5, 2.0, 31)
    periodic_sweep(model, p, sweep_w[:2], Z, n_harmonics=20)
    t_sweep, sweep = best_of(lambda: periodic_sweep(model, p, sweep_w, Z, n_harmonics=20), 1 if args.quick else 3)
    amp = ref.amplitude("x_b")
    from cablesys.linear.periodic import trig_interpolate
    err_per = float(np.max(np.abs(trig_interpolate(sol.outputs["x_b"], 410) - trig_interpolate(ref.outputs["x_b"], 410))) / amp)
    # time domain: fewest whole periods from rest (the hanging steady state) reaching TARGET
    td = None
    for k in range(3, 60):
        times = np.concatenate([np.arange(0.0, (k - 1) * T - T / 16, T / 8), (k - 1) * T + ref.time])
        simulate(scene, times=times)                                      # build (and cache) first
        t_td = min(simulate(scene, times=times).stats["wall_s"] for _ in range(1 if args.quick else 3))
        res = simulate(scene, times=times)     # integration only (wall_s), no build
        err = float(np.max(np.abs(res["x_b"][-ref.time.size:] - ref.outputs["x_b"])) / amp)
        if err < TARGET:
            td = {"periods": k, "simulated_s": k * T, "wall_s": t_td, "rel_err": err}
            break
    doc = {"rao_1000_ms": 1e3 * t_rao, "rao_1000_note": "steady state (KINSOL) + AD linearization + 1000-frequency batched solve, after the one-time build",
           "rao_only_1000_ms": 1e3 * t_rao_only,
           "periodic_ms": 1e3 * t_per, "periodic_rel_err_vs_H40": err_per,
           "periodic_newton_iterations": sol.stats["newton_iterations"],
           "periodic_sweep_frequencies": int(sweep_w.size), "periodic_sweep_converged": int(sum(x.success for x in sweep)),
           "periodic_sweep_ms_per_frequency": 1e3 * t_sweep / sweep_w.size,
           "periodic_sweep_newton_iterations": [x.stats["newton_iterations"] for x in sweep],
           "time_domain_to_steady": td, "target_rel_err": TARGET,
           "periodic_speedup_vs_time_domain": (td["wall_s"] / t_per) if td else None,
           "periodic_sweep_speedup_vs_time_domain": (td["wall_s"] * sweep_w.size / t_sweep) if td else None,
           "target_speedup": 20.0}
    (args.out / "bench_linear.json").write_text(json.dumps(doc, indent=1))
    print(json.dumps({k: v for k, v in doc.items() if "iterations" not in k}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
