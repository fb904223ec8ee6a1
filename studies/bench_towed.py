"""Benchmark: exact complex-order H(xi, omega) of Kennedy & Strahan (1981) on a 200 x 200 grid.

    python studies/bench_towed.py --out DIR [--full-baseline]

Times the vectorized 0F1 series route (cablesys.towed.bessel.exact_solution) and, in the
same run, the baselines it replaces: mpmath.hyp0f1 point by point (on a sub-grid, scaled
to 40 000 points unless --full-baseline) and the collocation BVP (one solve per omega,
on a subset of omegas, scaled to 200).  Writes bench_towed.json.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from cablesys.towed.bessel import exact_solution, mpmath_solution
from cablesys.towed.bvp import bvp_solution
from cablesys.towed.equation import REPORT_SEA_TRIAL, TowedCable
from cablesys.towed.transfer import transfer_grid


def best_of(fn, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--full-baseline", action="store_true", help="mpmath on all 40 000 points (~6 s)")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)

    cable = TowedCable(length=1190.0, speed=5.0, **REPORT_SEA_TRIAL)
    coef = cable.coefficients()
    xi = np.linspace(0.0, 1.0, 200)
    omega = np.linspace(0.1, 40.0, 200)

    t_grid, H = best_of(lambda: exact_solution(coef, xi[:, None], omega[None, :]))
    t_grid_cs, _ = best_of(lambda: transfer_grid(coef, xi, omega))

    # baseline 1: mpmath point by point
    if args.full_baseline:
        sub_i, sub_j = np.arange(200), np.arange(200)
    else:
        sub_i, sub_j = np.arange(0, 200, 10), np.arange(0, 200, 10)
    t0 = time.perf_counter()
    Hm = mpmath_solution(coef, xi[sub_i][:, None], omega[sub_j][None, :])
    t_mp = time.perf_counter() - t0
    n_mp = Hm.size
    t_mp_grid = t_mp / n_mp * 40000
    err_mp = float(np.max(np.abs(H[np.ix_(sub_i, sub_j)] - Hm)))

    # baseline 2: collocation BVP, one solve per omega (all 200 xi at once)
    om_sub = omega[::20]
    t0 = time.perf_counter()
    Hb = bvp_solution(coef, xi[:, None], om_sub[None, :])
    t_bvp = time.perf_counter() - t0
    t_bvp_grid = t_bvp / om_sub.size * omega.size
    err_bvp = float(np.max(np.abs(H[:, ::20] - Hb)))

    result = {
        "grid": "200 x 200, xi in [0, 1], omega in [0.1, 40]",
        "cable": {"length_m": cable.length, "speed_mps": cable.speed, **REPORT_SEA_TRIAL},
        "grid_200x200_s": t_grid,
        "grid_200x200_with_c_star_s": t_grid_cs,
        "target_s": 0.5,
        "meets_target": bool(t_grid < 0.5),
        "mpmath_points_timed": int(n_mp),
        "mpmath_per_point_s": t_mp / n_mp,
        "mpmath_grid_s" + ("" if args.full_baseline else "_extrapolated"): t_mp_grid,
        "speedup_vs_mpmath": t_mp_grid / t_grid,
        "max_abs_diff_vs_mpmath": err_mp,
        "bvp_omegas_timed": int(om_sub.size),
        "bvp_grid_s_extrapolated": t_bvp_grid,
        "speedup_vs_bvp": t_bvp_grid / t_grid,
        "max_abs_diff_vs_bvp": err_bvp,
    }
    (args.out / "bench_towed.json").write_text(json.dumps(result, indent=2))
    print(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
