"""Convergence of the segmented cable with the number of elements N, and the 2-DOF model's error.

Scenes (the segmented-cable issue):
- Dale et al. (Wang 1971, Table 1) driven at omega = 2.28 rad/s (2 omega_n), where the straight
  2-DOF cable is 9 % off in sway against a lumped-mass code: the cable bows under its drag;
- the 300 m wire with a 2 t sphere (``cablesys/data/heave_300m.toml``), 1 m heave at T = 10 s
  (taut) and T = 6 s (slack and snapping); full mode only (long runs).

For each N: body amplitudes (half peak-to-peak over the last 3 periods), top tension extremes over
the same window, wall time. Errors are against the finest N; the observed order is
log2(err(N) / err(2N)). The 2-DOF model (Wang's straight cable) is run on the same scene and its
error against the finest N is reported.

Usage: python studies/segmented_convergence.py --out DIR [--quick]
"""

from __future__ import annotations

import itertools
import math
import sys
import time
from pathlib import Path

import casadi as ca
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json

import cablesys
from cablesys.model import build_model
from cablesys.plots import save_figure
from cablesys.scene import OMEGA_N_MEASURED, dale_scene, load_scene
from cablesys.time_domain import simulate
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator, initial_state

HEAVE_SCENE = Path(cablesys.__file__).parent / "data" / "heave_300m.toml"
METRICS = ("x_amp", "y_amp", "top_max", "top_min")


def _steps_per_output(model, scene, x0) -> int:
    """RK4 steps per output interval that keep h |lambda|_max below 2.5 (RK4 is stable to 2.78): the
    undamped axial modes of a lumped cable make BDF resolve them anyway, so a fixed explicit step at
    the stability limit is the cheaper method for these scenes."""
    p = model.parameters(scene)
    x, t = model.sym("x", 2 * model.nq), model.sym("t")
    jac = ca.Function("ode_jacobian", [x, t], [ca.jacobian(model.ode(x, t, p), x)])
    lam = float(np.max(np.abs(np.linalg.eigvals(np.array(jac(x0, 0.0))))))
    return max(1, math.ceil(scene.numerics.output_step * lam / 2.5))


def measure(scene, period: float, n_periods: int = 3) -> dict:
    """Body amplitudes and top tension extremes over the last periods, and the wall time (RK4 at its
    stability limit, CasADi's virtual machine: no C compilation per N)."""
    t0 = time.perf_counter()
    model = build_model(scene)
    x0 = initial_state(scene, model, model.parameters(scene))
    spo = _steps_per_output(model, scene, x0)
    sim = Simulator(model, scene.output_times, IntegratorSettings(method="rk", steps_per_output=spo, compiled=False))
    r = simulate(scene, model=model, simulator=sim, x0=x0)
    wall = time.perf_counter() - t0
    if not r.success:
        return {"success": False, "message": r.message, "wall_s": wall}
    mask = r.time >= r.time[-1] - n_periods * period - 1e-9
    top = r["tension_top"][mask]
    return {"success": True, "wall_s": wall, "x_amp": r.steady_amplitude("x_b", period, n_periods),
            "y_amp": r.steady_amplitude("y_b", period, n_periods), "top_max": float(top.max()),
            "top_min": float(top.min()), "steps_per_output": spo}


def converge(name: str, scene, period: float, ns: list) -> dict:
    """Rows per N (segmented), the 2-DOF row, errors against the finest N and observed orders."""
    rows = []
    for n in ns:
        sc = scene.replace_section(0, cable={"segments": n})
        rows.append({"n": n, **measure(sc, period)})
    wang = measure(scene.replace_section(0, cable={"segments": 1}), period)
    ref = rows[-1]
    rel = lambda row, k: abs(row[k] - ref[k]) / max(abs(ref[k]), 1e-300) if row.get("success") and ref.get("success") else None
    for row in rows[:-1]:
        row["rel_err"] = {k: rel(row, k) for k in METRICS}
    for a, b in itertools.pairwise(rows[:-1]):
        a["observed_order"] = {k: math.log2(a["rel_err"][k] / b["rel_err"][k])
                               if a["rel_err"][k] and b["rel_err"][k] else None for k in METRICS}
    wang["rel_err"] = {k: rel(wang, k) for k in METRICS}
    return {"scene": name, "period_s": period, "rows": rows, "two_dof": wang}


def plot(results: list, path: Path) -> Path:
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, len(results), figsize=(5.5 * len(results), 4.2), squeeze=False)
    for ax, res in zip(axes[0], results):
        rows = [r for r in res["rows"][:-1] if r.get("rel_err")]
        ns = [r["n"] for r in rows]
        for k, label in (("x_amp", "body x amplitude"), ("y_amp", "body y amplitude"),
                         ("top_max", "top tension max"), ("top_min", "top tension min")):
            err = [r["rel_err"][k] for r in rows]
            if any(e for e in err):
                ax.loglog(ns, [max(e, 1e-12) for e in err], "o-", label=label)
        for k, ls in (("x_amp", ":"), ("top_max", "--")):
            e = res["two_dof"]["rel_err"].get(k)
            if e:
                ax.axhline(e, color="k", ls=ls, lw=0.8, label=f"2-DOF model, {k.replace('_', ' ')}")
        if ns:
            ax.loglog(ns, [rows[0]["rel_err"]["x_amp"] * (ns[0] / n) ** 2 if rows[0]["rel_err"]["x_amp"] else np.nan
                           for n in ns], color="0.6", lw=0.8, label="slope -2")
        ax.set(xlabel="elements N", ylabel=f"relative error vs N = {res['rows'][-1]['n']}", title=res["scene"])
        ax.set_xticks(ns, [str(n) for n in ns])
        ax.minorticks_off()
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    return save_figure(fig, path)


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    w = 2.0 * OMEGA_N_MEASURED
    period = 2 * math.pi / w
    dale = dale_scene(omega_ratio=2.0, duration=(6 if args.quick else 12) * period)
    results = [converge("Dale et al., omega = 2.28 rad/s", dale, period, [2, 4, 8] if args.quick else [2, 4, 8, 16, 32])]
    if not args.quick:
        heave = load_scene(HEAVE_SCENE)
        for T in (10.0, 6.0):
            sc = heave.replace(top_motion=dataclasses_replace_top(heave, T)).with_numerics(duration=8 * T)
            results.append(converge(f"300 m wire, 2 t sphere, T = {T:g} s", sc, T, [5, 10, 20, 40]))
    write_json(args.out / "segmented_convergence.json", {"results": results})
    plot(results, args.out / "segmented_convergence.png")
    for res in results:
        print(res["scene"])
        for r in res["rows"]:
            print(f"  N = {r['n']:3d}  x_amp {r.get('x_amp', float('nan')):.6g}  top max {r.get('top_max', float('nan')):.6g} N"
                  f"  wall {r['wall_s']:.2f} s  err {r.get('rel_err')}")
        print(f"  2-DOF  err {res['two_dof']['rel_err']}")
    return 0


def dataclasses_replace_top(scene, period: float):
    """The scene's top motion with its heave at ``period``."""
    import dataclasses
    y = tuple(dataclasses.replace(s, frequency=2 * math.pi / period) for s in scene.top_motion.y)
    return dataclasses.replace(scene.top_motion, y=y)


if __name__ == "__main__":
    sys.exit(main())
