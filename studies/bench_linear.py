"""Benchmark: steady state + linearization + RAOs at 1000 frequencies, and the periodic solve
against simulating to steady state at equal accuracy (1e-4 of the amplitude), Dale scene at
omega / omega_n = 1. Usage: python studies/bench_linear.py --out DIR
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from cablesys.linear.linearize import linearize
from cablesys.linear.periodic import periodic_steady_state, scene_input_amplitude
from cablesys.linear import rao
from cablesys.linear.steady import steady_state
from cablesys.model import build_model
from cablesys.scene import dale_scene
from cablesys.simulate import simulate

TARGET = 1e-4


def best_of(fn, n):
    ts = []
    for _ in range(n):
        t = time.perf_counter(); out = fn(); ts.append(time.perf_counter() - t)
    return min(ts), out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, type=Path)
    args = ap.parse_args(argv)
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
    t_per, sol = best_of(lambda: periodic_steady_state(model, p, w, input_amplitude=Z, n_harmonics=20), 5)
    amp = ref.amplitude("x_b")
    from cablesys.linear.periodic import trig_interpolate
    err_per = float(np.max(np.abs(trig_interpolate(sol.outputs["x_b"], 410) - trig_interpolate(ref.outputs["x_b"], 410))) / amp)
    # time domain: fewest whole periods from rest (the hanging steady state) reaching TARGET
    td = None
    for k in range(3, 60):
        times = np.concatenate([np.arange(0.0, (k - 1) * T - T / 16, T / 8), (k - 1) * T + ref.time])
        res = simulate(scene, times=times); t_td = res.stats["wall_s"]     # integration only, no build
        err = float(np.max(np.abs(res["x_b"][-ref.time.size:] - ref.outputs["x_b"])) / amp)
        if err < TARGET:
            td = {"periods": k, "simulated_s": k * T, "wall_s": t_td, "rel_err": err}
            break
    doc = {"rao_1000_ms": 1e3 * t_rao, "rao_1000_note": "steady state (KINSOL) + AD linearization + 1000-frequency batched solve, after the one-time build",
           "rao_only_1000_ms": 1e3 * t_rao_only,
           "periodic_ms": 1e3 * t_per, "periodic_rel_err_vs_H40": err_per,
           "time_domain_to_steady": td, "target_rel_err": TARGET,
           "periodic_speedup_vs_time_domain": (td["wall_s"] / t_per) if td else None}
    (args.out / "bench_linear.json").write_text(json.dumps(doc, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
