"""Benchmark: 2000-element cable with five masses, statics + 50 lowest modes, on two routes in one run.

    python studies/bench_slack.py --out DIR [--elements 2000] [--modes 50] [--repeat 3]

The lumped-mass chain of cablesys.slack: statics by the CasADi/IPOPT NLP (the first call also
builds the CasADi functions and the solver; that set-up is timed separately), modes by sparse
shift-invert (scipy.sparse.linalg.eigsh). The shared cable (cablesys.slack.shared): the same span
as a node-model scene, its statics by KINSOL on the node model's residual and its modes from the
model's mass matrix and the Jacobian of its forces (the model's element-kernel form), the same eigen
solver. Warm runs alternate between the routes so that both see the same machine load.

First calls, as a user's first ``cablesys slack``: each route's statics + modes timed in a fresh
Python process (imports done before the clock starts) with an empty CABLESYS_CACHE directory of its
own, the two processes run one after the other in this run.

Writes DIR/bench_slack.json with static_s, modes_s, total_s (best of --repeat warm runs, chain
route), shared_static_s, shared_modes_s, shared_total_s, shared_vs_chain_ratio (shared_total_s /
total_s), the in-process set-up times (first_call_setup_s: the chain's first statics, its NLP
built; shared_first_call_setup_s: the shared route's first statics + modes, after the chain's),
first_call_chain_s, first_call_shared_s (statics + modes, cold) and first_call_ratio (shared / chain), the load average and the frequency agreement of the routes.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cablesys.model import FunctionCache
from cablesys.slack import shared
from cablesys.slack.vibration import modes
from cablesys.slack.scene import SlackCable, PointMass, SlackScene
from cablesys.slack.statics import solve_equilibrium, solve_equilibrium_shooting


def bench_scene(n_elements: int) -> SlackScene:
    """Table 4 configuration (l/L = 0.962, HLHLH masses at the sixth points)."""
    L = 22.9 / 0.962
    masses = tuple(PointMass(position=L * (k + 1) / 6, mass=4.5 if c == "H" else 2.0)
                   for k, c in enumerate("HLHLH"))
    return SlackScene(cable=SlackCable(length=L, mass_per_length=1.14, ae=8.9e5),
                      span=22.9, masses=masses, n_elements=n_elements)


def first_call(route: str, n_elements: int, n_modes: int) -> dict:
    """Statics + modes of ``route`` ('chain' or 'shared') on :func:`bench_scene`, timed from after the imports, in
    this process (run by :func:`cold_first_call` in a fresh one)."""
    sc = bench_scene(n_elements)
    t0 = time.perf_counter()
    if route == "chain":
        eq = solve_equilibrium(sc)
        t1 = time.perf_counter()
        modes(eq, n_modes, solver="sparse")
    else:
        eq = shared.equilibrium(sc)
        t1 = time.perf_counter()
        shared.modes(eq, n_modes, solver="sparse")
    t2 = time.perf_counter()
    return {"static_s": t1 - t0, "modes_s": t2 - t1, "total_s": t2 - t0}


def cold_first_call(route: str, n_elements: int, n_modes: int) -> dict:
    """:func:`first_call` in a fresh Python process with an empty CABLESYS_CACHE directory (a user's first run)."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, CABLESYS_CACHE=cache)
        out = subprocess.run([sys.executable, __file__, "--first-call", route, "--elements", str(n_elements),
                              "--modes", str(n_modes), "--out", cache], env=env, check=True, capture_output=True,
                             text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--elements", type=int, default=2000)
    ap.add_argument("--modes", type=int, default=50)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--first-call", choices=("chain", "shared"), help=argparse.SUPPRESS)   # the cold child process
    a = ap.parse_args(argv)
    if a.first_call:
        print(json.dumps(first_call(a.first_call, a.elements, a.modes)))
        return 0
    cold = {route: cold_first_call(route, a.elements, a.modes) for route in ("chain", "shared")}
    sc = bench_scene(a.elements)
    cache = FunctionCache()            # the NLP is built on the first call and reused by the repeats
    t = time.perf_counter()
    solve_equilibrium(sc, cache=cache)
    setup_s = time.perf_counter() - t
    t = time.perf_counter()
    shared.modes(shared.equilibrium(sc), a.modes, solver="sparse")     # builds the model's kernel form
    shared_setup_s = time.perf_counter() - t
    runs, shared_runs = [], []
    for _ in range(a.repeat):
        t0 = time.perf_counter()
        eq = solve_equilibrium(sc, cache=cache)
        t1 = time.perf_counter()
        ms = modes(eq, a.modes, solver="sparse")
        t2 = time.perf_counter()
        runs.append((t1 - t0, t2 - t1, t2 - t0))
        t0 = time.perf_counter()
        eq_sh = shared.equilibrium(sc)
        t1 = time.perf_counter()
        ms_sh = shared.modes(eq_sh, a.modes, solver="sparse")
        t2 = time.perf_counter()
        shared_runs.append((t1 - t0, t2 - t1, t2 - t0))
    best = min(runs, key=lambda r: r[2])
    best_sh = min(shared_runs, key=lambda r: r[2])
    t = time.perf_counter()
    eqs = solve_equilibrium_shooting(sc)
    shoot_s = time.perf_counter() - t
    # cross-check sparse vs dense on the out-of-plane/in-plane lowest 10 at 2000 elements is costly;
    # compare with a 400-element dense solution instead (discretization error ~ (1/400)^2)
    eq4 = solve_equilibrium(sc.replace(n_elements=400))
    ref = modes(eq4, 10, solver="dense")
    doc = {"n_elements": a.elements, "n_modes": a.modes, "repeat": a.repeat,
           "static_s": best[0], "modes_s": best[1], "total_s": best[2],
           "first_call_setup_s": setup_s, "ipopt_iterations": eq.iterations,
           "shooting_static_s": shoot_s,
           "static_nlp_vs_shooting_max_dz_m": float(np.max(np.abs(eq.z - eqs.z))),
           "target_total_s": 1.0, "meets_target": best[2] < 1.0,
           "omega_first10": ms.omega[:10].tolist(),
           "rel_diff_first10_vs_400_dense": (ms.omega[:10] / ref.omega - 1).tolist(),
           "omega_50th": float(ms.omega[-1]), "mode_types": "".join(ms.mode_type),
           "shared_static_s": best_sh[0], "shared_modes_s": best_sh[1], "shared_total_s": best_sh[2],
           "shared_first_call_setup_s": shared_setup_s, "shared_vs_chain_ratio": best_sh[2] / best[2],
           "shared_within_2x": best_sh[2] < 2.0 * best[2], "load_average_1min": os.getloadavg()[0],
           "shared_vs_chain_max_rel_diff_omega": float(np.max(np.abs(ms_sh.omega / ms.omega - 1))),
           "shared_mode_types": "".join(ms_sh.mode_type),
           "first_call_chain_s": cold["chain"]["total_s"], "first_call_shared_s": cold["shared"]["total_s"],
           "first_call_ratio": cold["shared"]["total_s"] / cold["chain"]["total_s"],
           "first_call_within_2x": cold["shared"]["total_s"] < 2.0 * cold["chain"]["total_s"],
           "first_call_parts": cold}
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench_slack.json").write_text(json.dumps(doc, indent=1))
    print(f"statics {best[0]:.3f} s + modes {best[1]:.3f} s = {best[2]:.3f} s "
          f"(target < 1 s; first-call set-up {setup_s:.2f} s; shooting statics {shoot_s:.3f} s)")
    print(f"shared cable: statics {best_sh[0]:.3f} s + modes {best_sh[1]:.3f} s = {best_sh[2]:.3f} s, "
          f"{best_sh[2] / best[2]:.2f}x the chain (first-call set-up {shared_setup_s:.1f} s; "
          f"load {os.getloadavg()[0]:.1f})")
    print(f"first call, cold (fresh process and cache): chain {cold['chain']['total_s']:.2f} s, shared "
          f"{cold['shared']['total_s']:.2f} s ({cold['shared']['total_s'] / cold['chain']['total_s']:.2f}x)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
