"""Operability of a lift over a sea-state scatter diagram (Hs x Tp) through the run verdict.

The shipped ROV-lift scene (``cablesys/data/rov_lift.toml``: 1 t cage on 500 m of 30 mm wire,
crane-tip motion RAO, JONSWAP sea, surface current, ``[limits]``) is run in the time domain for
every (Hs, Tp) of the grid with one compiled model (only the sea's sinusoid amplitudes and
frequencies change, through the parameter vector). Each case is judged by the verdict of
:mod:`cablesys.verdict` against the scene's limits (peak tension <= MBL / safety factor, least
tension >= 10 % of static (slack sling), DAF, cage excursion), with most probable extremes over a
3-hour exposure. Outputs:

* ``operability.csv``/``operability.json``: per sea state the verdict, the governing criterion
  (smallest margin) and every margin; the table of allowed sea states (rows Hs, columns Tp);
* ``operability.png``: the smallest margin over the scatter diagram, allowed cells marked, and
  seas steeper than 2 pi Hs / (g Tp^2) = 1/15 hatched (they break: not a design sea state;
  the 1/15 limit as commonly cited from DNV-RP-C205 sec. 3.5.5; the cells are computed anyway);
* ``sweep.nc``: the whole sweep (statistics, margins, status per case).

The same seed is used for every sea state (one realisation per cell, duration of the run);
a longer ``numerics.duration`` or several seeds narrow the scatter of the extremes.

Usage: python studies/operability.py --out DIR [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

import cablesys
from cablesys import units as U
from cablesys.examples import example_path
from cablesys.plots import save_figure
from cablesys.scene import load_scene

STEEPNESS_LIMIT = 1.0 / 15.0


def criteria_of(ds) -> list:
    return sorted({v[len("verdict_"):-len("_margin")] for v in ds.data_vars
                   if v.startswith("verdict_") and v.endswith("_margin")})


def table(ds, hs_dim: str, tp_dim: str) -> list:
    """One row per sea state: verdict, governing criterion, margins, steepness."""
    crit = criteria_of(ds)
    rows = []
    for i, hs in enumerate(ds[hs_dim].values):
        for j, tp in enumerate(ds[tp_dim].values):
            c = ds.isel({hs_dim: i, tp_dim: j})
            ok = str(c["status"].values) == "ok"
            margins = {k: float(c[f"verdict_{k}_margin"]) for k in crit}
            finite = {k: m for k, m in margins.items() if np.isfinite(m)}
            gov = min(finite, key=finite.get) if finite else ""
            rows.append({"hs_m": float(hs), "tp_s": float(tp), "status": str(c["status"].values),
                         "allowed": bool(ok and float(c["verdict_pass"]) == 1.0),
                         "governing": gov, "min_margin": finite.get(gov, float("nan")),
                         "steepness": 2 * np.pi * hs / (U.G_STANDARD * tp**2),
                         **{f"margin_{k}": m for k, m in margins.items()},
                         "message": str(c["message"].values)})
    return rows


def plot(rows, hs, tp, path, title):
    plt = setup_matplotlib()
    from matplotlib.colors import TwoSlopeNorm
    M = np.array([r["min_margin"] for r in rows]).reshape(len(hs), len(tp))
    A = np.array([r["allowed"] for r in rows]).reshape(len(hs), len(tp))
    S = np.array([r["steepness"] for r in rows]).reshape(len(hs), len(tp))
    G = np.array([r["governing"] for r in rows], dtype=object).reshape(len(hs), len(tp))
    fig, ax = plt.subplots(figsize=(max(7.5, 2.6 + 0.8 * len(tp)), max(4.2, 1.6 + 0.45 * len(hs))))
    # colours saturate at +-0.5 (50 % margin): the pass/fail boundary stays visible next to large slack margins
    lim = min(0.5, max(0.05, float(np.nanmax(np.abs(M))) if np.isfinite(M).any() else 0.5))
    cmap = plt.get_cmap("RdYlGn").with_extremes(bad="0.8")
    im = ax.pcolormesh(np.ma.masked_invalid(np.clip(M, -lim, lim)), cmap=cmap, norm=TwoSlopeNorm(0.0, -lim, lim))
    for (i, j), m in np.ndenumerate(M):
        txt = ("PASS" if A[i, j] else "FAIL") + (f"\n{G[i, j]}" if not A[i, j] and G[i, j] else "")
        ax.text(j + 0.5, i + 0.5, txt, ha="center", va="center", fontsize=6.5)
        if S[i, j] > STEEPNESS_LIMIT:
            ax.add_patch(plt.Rectangle((j, i), 1, 1, fill=False, hatch="///", edgecolor="0.35", lw=0))
    ax.set_xticks(np.arange(len(tp)) + 0.5, [f"{v:g}" for v in tp])
    ax.set_yticks(np.arange(len(hs)) + 0.5, [f"{v:g}" for v in hs])
    ax.set(xlabel="peak period Tp [s]", ylabel="significant wave height Hs [m]")
    ax.set_title(title, fontsize=9.5)
    fig.colorbar(im, ax=ax, label="smallest verdict margin (>= 0 passes)", extend="both")
    return save_figure(fig, path)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    scene = load_scene(example_path("rov-lift"))
    if args.quick:
        hs, tp = [2.0, 5.0, 8.0], [6.0, 9.0, 12.0, 15.0]
        scene = scene.with_numerics(duration=200.0)
    else:
        hs, tp = list(np.arange(1.0, 9.01, 1.0)), list(np.arange(5.0, 16.01, 1.0))
    t0 = time.perf_counter()
    ds = cablesys.sweep(scene, {"top_motion.spectrum.hs": hs, "top_motion.spectrum.tp": tp}, "run",
                        metrics=["verdict_*", "statistics_force_N_*", "statistics_length_m_*", "time_slack_s"],
                        out=args.out / "cases", progress=sys.stderr.isatty())
    wall = time.perf_counter() - t0
    hs_dim, tp_dim = "top_motion.spectrum.hs", "top_motion.spectrum.tp"
    rows = table(ds, hs_dim, tp_dim)
    ds.to_netcdf(args.out / "sweep.nc", engine="scipy")
    import csv
    with (args.out / "operability.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    grid = {f"Hs {h:g} m": {f"Tp {t:g} s": ("PASS" if r["allowed"] else f"FAIL ({r['governing']})")
                            for t, r in zip(tp, rows[i * len(tp):(i + 1) * len(tp)])} for i, h in enumerate(hs)}
    doc = {"scene": scene.name, "duration_s": scene.numerics.duration, "criteria": criteria_of(ds),
           "limits": {k: v for k, v in vars(scene.limits).items() if v is not None} if getattr(scene, "limits", None) else {},
           "n_cases": len(rows), "n_allowed": sum(r["allowed"] for r in rows),
           "n_not_ok": sum(r["status"] != "ok" for r in rows), "wall_s": wall, "backend": ds.attrs["backend"],
           "table": grid, "cases": rows}
    write_json(args.out / "operability.json", doc)
    plot(rows, hs, tp, args.out / "operability.png",
         f"{scene.name.split(',')[0]}: where the lift is allowed\n(verdict per sea state, {scene.numerics.duration:g} s run, "
         "MPM over 3 h; hatched: steeper than 1/15)")
    print(f"{len(rows)} sea states in {wall:.1f} s ({ds.attrs['backend']}): {doc['n_allowed']} allowed")
    width = max(len(k) for k in grid)
    print(" " * width + "".join(f"{f'Tp {t:g}':>10}" for t in tp))
    for k, row in grid.items():
        print(f"{k:<{width}}" + "".join(f"{('PASS' if v == 'PASS' else 'FAIL'):>10}" for v in row.values()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
