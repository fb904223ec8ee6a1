"""Convergence of the segmented cable with the number of elements N, and the 2-DOF model's error.

Scenes (the segmented-cable issue):
- Dale et al. (Wang 1971, Table 1) driven at omega = 2.28 rad/s (2 omega_n), where the straight
  2-DOF cable is 9 % off in sway against a lumped-mass code: the cable bows under its drag;
- the 300 m wire with a 2 t sphere (``cablesys/data/heave_300m.toml``), 1 m heave at T = 10 s
  (taut, 8 periods) and T = 6 s (slack and snapping); full mode only (long runs).

Dale and taut heave: for each N, body amplitudes (half peak-to-peak over the last 3 periods), top
tension extremes over the same window, wall time. Errors are against the finest N; the observed
order is log2(err(N) / err(2N)). The 2-DOF model (Wang's straight cable) is run on the same scene
and its error against the finest N is reported.

Slack heave (T = 6 s): the response has a transient of ~100 s (a period-2 bounce, then the body's
mean lifts by ~1.5 m and the motion settles on a periodic cycle), so a 60 s run measures *when*
that transition happens, which depends on N, tolerance and method in the 4th digit of the state:
runs of 60 s did not converge in N for that reason. Here each N runs ``--slack-duration`` (360 s)
with RK4 at a fixed step inside its stability limit (step halved once to show the integration
error is far below the discretisation's), and every figure is a mean over the forcing cycles of
the second half (``_cycles.cycle_statistics``: extremes refined between samples; the spread over
the cycles is 0 for a settled periodic response). The observed order needs no reference:
p = log2(|f(N) - f(2N)| / |f(2N) - f(4N)|). MoorDyn v2 (if installed) runs the same scene, same
ramp and N at its largest stable step, probed over the whole run (stability and agreement of the
settled statistics with the half step), with the same statistics and the same slack definition
(element strain <= 0, i.e. zero elastic tension).

Findings on the slack scene (2026-11-30; numbers in the JSON):
- cablesys converges at first order in N (observed p = 0.98-1.02 for body amplitude and top-tension
  maximum from N = 10, 20, 40, 80); the RK4 half-step changes them by < 2e-5, and CVODES (BDF <= 2)
  at rtol 1e-4, 1e-6, 1e-8 agrees to 1e-4 in amplitude: time integration is not the issue.
- The slack lower elements bunch: no compression, no damping while slack (Wang eq. 54), so their
  nodes close up (element strain -0.15, -0.29, -0.58, -1.0 at N = 10, 20, 40, 80: touching at 80).
  The planar response is unstable to a lateral perturbation (the bunched chain buckles: 1e-6 m at a
  middle node grows to 0.8 m); CVODES's round-off does that by itself, RK4 keeps x = 0 exactly. The
  buckled response differs by 0.4 % (amplitude) and 0.7 % (top maximum, with a 1-3 % spread over
  cycles) at N = 20: small against the discretisation error, and reported, not hidden.
- MoorDyn differs by its slack law, not by its numerics: its segment force is EA strain while
  stretched plus BA strain rate always (damping acts on slack segments and can push, -1.1 kN at the
  body end). With that law put into the cablesys element (a scratch experiment, not an option of the
  model), cablesys gives MoorDyn's body amplitude to 1e-4 at N = 10 and 20 and its top tension to
  0.7 % (the rest is the end-force read-out). Drag and added mass on the unstretched length of a
  bunched element (MoorDyn's choice) change nothing here (1e-5).

Usage: python studies/segmented_convergence.py --out DIR [--quick] [--slack-n 10 20 40 80]
"""

from __future__ import annotations

import itertools
import math
import pickle
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import setup_matplotlib, write_json
from _cycles import cycle_statistics

import cablesys
from cablesys.model import build_model
from cablesys.plots import save_figure
from cablesys.scene import OMEGA_N_MEASURED, dale_scene, load_scene
from cablesys.time_domain import simulate
from cablesys.time_domain.failures import largest_rate, rk4_steps_per_output
from cablesys.time_domain.integrators import IntegratorSettings
from cablesys.time_domain.run import Simulator, initial_state

HEAVE_SCENE = Path(cablesys.__file__).parent / "data" / "heave_300m.toml"
METRICS = ("x_amp", "y_amp", "top_max", "top_min")


def stable_steps_per_output(model, scene, x0, margin: float = 2.5) -> int:
    """RK4 steps per output interval that keep h |lambda|_max below 2.5 (RK4 is stable to 2.78): the
    undamped axial modes of a lumped cable make BDF resolve them anyway, so a fixed explicit step at
    the stability limit is the cheaper method for these scenes."""
    lam = largest_rate(model, x0, 0.0, model.parameters(scene))
    return rk4_steps_per_output(lam, scene.numerics.output_step, margin)


def measure(scene, period: float, n_periods: int = 3) -> dict:
    """Body amplitudes and top tension extremes over the last periods, and the wall time (RK4 at its
    stability limit, CasADi's virtual machine: no C compilation per N)."""
    t0 = time.perf_counter()
    model = build_model(scene)
    x0 = initial_state(scene, model, model.parameters(scene))
    spo = stable_steps_per_output(model, scene, x0)
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


SLACK_METRICS = ("y_amp", "y_min", "top_max", "bottom_max", "top_min", "slack_bottom", "slack_top")


def slack_scene(period: float = 6.0, duration: float = 360.0, output_step: float = 0.01):
    """The heave scene at ``period`` (default smooth start: 3 periods), run ``duration`` s."""
    heave = load_scene(HEAVE_SCENE)
    sc = heave.replace(top_motion=dataclasses_replace_top(heave, period))
    return sc.with_numerics(duration=duration, output_step=output_step)


COMPILE_MAX_SLACK = 80     # the RK4 loop has no Jacobian: it compiles at N = 80 in minutes (< 8 GB); larger N in the VM


def run_slack(scene, n: int, period: float, t0: float, *, refine: int = 1) -> dict:
    """cablesys at N elements: RK4 at its stability step / ``refine`` (compiled up to
    ``COMPILE_MAX_SLACK`` elements, else CasADi's VM); the settled statistics over [t0, end] and
    the series to plot. ``run_s_per_s`` times the stepping and outputs of the built simulator."""
    sc = scene.replace_section(0, cable={"segments": n})
    t_wall = time.perf_counter()
    model = build_model(sc)
    x0 = initial_state(sc, model, model.parameters(sc))
    spo = refine * stable_steps_per_output(model, sc, x0, margin=2.0)
    compiled = n <= COMPILE_MAX_SLACK
    settings = IntegratorSettings(method="rk", steps_per_output=spo, compiled=compiled)
    Simulator(model, sc.output_times[:3], settings).run(model.parameters(sc), x0)   # builds (compiles) the RK4 step loop
    sim = Simulator(model, sc.output_times, settings)
    t_run = time.perf_counter()
    r = simulate(sc, model=model, simulator=sim, x0=x0)
    row = {"n": n, "success": bool(r.success), "dt_s": sc.numerics.output_step / spo, "compiled": compiled,
           "run_s_per_s": (time.perf_counter() - t_run) / sc.numerics.duration,
           "wall_s": time.perf_counter() - t_wall}
    if not r.success:
        return {**row, "message": r.message}
    st = cycle_statistics(r.time, r.data, period, t0, strain=r.profiles["element_strain"],
                          law_slack=r.profiles["element_slack"])
    return {**row, **st, "min_strain": float(np.min(r.profiles["element_strain"][np.asarray(r.time) >= t0])),
            "series": {"time": np.asarray(r.time), "y_b": np.asarray(r["y_b"]), "tension_top": np.asarray(r["tension_top"])}}


def run_moordyn_slack(scene, n: int, period: float, t0: float) -> dict:
    """MoorDyn at N segments, its largest step whose whole run is stable and whose settled
    statistics agree with the half step's (0.5 % body amplitude, 1 % top tension)."""
    from _moordyn import largest_stable_dt
    sc = scene.replace_section(0, cable={"segments": n})
    stat = lambda r: cycle_statistics(r["time"], r, period, t0, strain=r["element_strain"])

    def agree(a, b):
        sa, sb = stat(a), stat(b)
        return (abs(sa["y_amp"] - sb["y_amp"]) <= 0.005 * sb["y_amp"]
                and abs(sa["top_max"] - sb["top_max"]) <= 0.01 * sb["top_max"])
    runs = {}
    dt = largest_stable_dt(sc, n, agree=agree, runs=runs)
    r = runs[dt]
    return {"n": n, "dt_s": dt, "run_s_per_s": r["wall_s"] / sc.numerics.duration, "stable": r["stable"],
            **stat(r), "min_strain": float(np.min(r["element_strain"][r["time"] >= t0])),
            "series": {"time": r["time"], "y_b": r["y_b"], "tension_top": r["tension_top"]}}


def _orders(rows: list, keys) -> None:
    """Reference-free observed order from three successive doublings, and the change to 2N."""
    for a, b, c in zip(rows, rows[1:], rows[2:]):
        a["observed_order"] = {k: math.log2(abs(a[k] - b[k]) / abs(b[k] - c[k]))
                               if abs(b[k] - c[k]) > 0 and abs(a[k] - b[k]) > 0 else None for k in keys}
    for a, b in itertools.pairwise(rows):
        a["change_to_2n"] = {k: abs(a[k] - b[k]) / max(abs(b[k]), 1e-300) for k in keys}


def _kept(folder: Path | None, name: str, fn):
    """``fn()``, kept in ``folder/name.pkl`` (a long study that is stopped resumes from its runs)."""
    if folder is None:
        return fn()
    path = folder / f"{name}.pkl"
    if path.is_file():
        return pickle.loads(path.read_bytes())
    out = fn()
    folder.mkdir(parents=True, exist_ok=True)
    path.write_bytes(pickle.dumps(out))
    return out


def converge_slack(ns: list, duration: float, period: float = 6.0, moordyn: bool = True, keep: Path | None = None) -> dict:
    """The slack scene at each N: cablesys (and a half-step run at the second N), MoorDyn. Runs are
    kept in ``keep`` (if given) and reused from there."""
    sc = slack_scene(period, duration)
    t0 = sc.top_motion.effective_ramp_s + math.floor((duration / 2 - sc.top_motion.effective_ramp_s) / period) * period
    tag = f"T{period:g}_{duration:g}s"
    rows = [_kept(keep, f"cablesys_{tag}_n{n}", lambda n=n: run_slack(sc, n, period, t0)) for n in ns]
    n_check = ns[min(1, len(ns) - 1)]
    check = _kept(keep, f"cablesys_{tag}_n{n_check}_half_step", lambda: run_slack(sc, n_check, period, t0, refine=2))
    ok = [r for r in rows if r["success"]]
    _orders(ok, SLACK_METRICS[:5])
    out = {"scene": f"300 m wire, 2 t sphere, T = {period:g} s (slack)", "period_s": period, "duration_s": duration,
           "window_s": [t0, duration], "rows": rows,
           "time_step_check": {"n": check["n"], "dt_s": check.get("dt_s"),
                               "change": {k: abs(check[k] - rows[min(1, len(ns) - 1)][k]) / abs(check[k])
                                          for k in SLACK_METRICS[:5]} if check["success"] else None}}
    if moordyn:
        try:
            import moordyn as _  # noqa: F401
        except ImportError:
            return out
        md = [_kept(keep, f"moordyn_{tag}_n{n}", lambda n=n: run_moordyn_slack(sc, n, period, t0)) for n in ns]
        _orders(md, SLACK_METRICS[:5])
        out["moordyn"] = md
        out["cablesys_vs_moordyn"] = [{"n": a["n"], **{k: (a[k] - b[k]) / abs(b[k]) for k in SLACK_METRICS[:5]}}
                                      for a, b in zip(ok, md)]
    return out


def plot_slack(res: dict, path: Path) -> Path:
    """Settled figures vs N (both codes), the change to 2N (order), the transient at one N."""
    plt = setup_matplotlib()
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.6))
    rows = [r for r in res["rows"] if r["success"]]
    md = res.get("moordyn", [])
    ns = [r["n"] for r in rows]
    for k, lab, c in (("y_amp", "body heave amplitude (m)", "C0"), ("top_max", "top tension max / 25 kN", "C1")):
        sc = 1.0 if k == "y_amp" else 2.5e4
        ax[0].semilogx(ns, [r[k] / sc for r in rows], "o-", color=c, label=f"cablesys, {lab}")
        if md:
            ax[0].semilogx([r["n"] for r in md], [r[k] / sc for r in md], "s--", color=c, label=f"MoorDyn v2, {lab}")
    ax[0].semilogx(ns, [r["slack_bottom"] for r in rows], "o-", color="C2", label="cablesys, bottom element slack fraction")
    if md:
        ax[0].semilogx([r["n"] for r in md], [r["slack_bottom"] for r in md], "s--", color="C2", label="MoorDyn, bottom slack fraction")
    ax[0].set(xlabel="elements N", title=f"settled cycle means, window {res['window_s'][0]:g}-{res['window_s'][1]:g} s")
    ax[0].set_xticks(ns, [str(n) for n in ns])
    ax[0].minorticks_off()
    ax[0].legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, 0.86))
    for k, lab in (("y_amp", "body amplitude"), ("y_min", "body's highest point"), ("top_max", "top tension max"),
                   ("bottom_max", "body-end tension max")):
        pts = [(r["n"], r["change_to_2n"][k]) for r in rows if "change_to_2n" in r and r["change_to_2n"][k] > 0]
        if pts:
            ax[1].loglog(*zip(*pts), "o-", label=f"cablesys {lab}")
    if len(rows) > 1 and rows[0]["change_to_2n"]["y_amp"] > 0:
        e0 = rows[0]["change_to_2n"]["y_amp"]
        ax[1].loglog(ns[:-1], [e0 * ns[0] / n for n in ns[:-1]], color="0.6", lw=0.8, label="slope -1")
    ax[1].set(xlabel="elements N", ylabel="|f(N) - f(2N)| / |f(2N)|", title="change on doubling N (slack, T = 6 s)")
    ax[1].set_xticks(ns[:-1], [str(n) for n in ns[:-1]])
    ax[1].minorticks_off()
    ax[1].grid(alpha=0.3, which="both")
    ax[1].legend(fontsize=7)
    r = rows[min(1, len(rows) - 1)]
    ax[2].plot(r["series"]["time"], r["series"]["y_b"], lw=0.6, label=f"cablesys N = {r['n']}")
    m = next((x for x in md if x["n"] == r["n"]), None)
    if m:
        ax[2].plot(m["series"]["time"], m["series"]["y_b"], lw=0.6, label=f"MoorDyn N = {r['n']}")
    ax[2].axvspan(*res["window_s"], color="0.9", label="statistics window")
    ax[2].invert_yaxis()
    ax[2].set(xlabel="time (s)", ylabel="body depth below mean top (m)", title="transient, then a settled cycle")
    ax[2].legend(fontsize=7)
    return save_figure(fig, path)


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path, help="output directory (created if missing)")
    ap.add_argument("--quick", action="store_true", help="Dale at N = 2, 4, 8 only (for tests)")
    ap.add_argument("--slack-n", type=int, nargs="+", default=[10, 20, 40, 80], help="N for the slack scene")
    ap.add_argument("--slack-duration", type=float, default=360.0, help="slack run length (s)")
    ap.add_argument("--no-moordyn", action="store_true", help="skip MoorDyn on the slack scene")
    ap.add_argument("--skip-taut", action="store_true", help="full mode: only the slack scene")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    w = 2.0 * OMEGA_N_MEASURED
    period = 2 * math.pi / w
    results = []
    if not args.skip_taut:
        dale = dale_scene(omega_ratio=2.0, duration=(6 if args.quick else 12) * period)
        results.append(converge("Dale et al., omega = 2.28 rad/s", dale, period, [2, 4, 8] if args.quick else [2, 4, 8, 16, 32]))
    slack = None
    if not args.quick:
        if not args.skip_taut:
            heave = load_scene(HEAVE_SCENE)
            sc = heave.replace(top_motion=dataclasses_replace_top(heave, 10.0)).with_numerics(duration=80.0)
            results.append(converge("300 m wire, 2 t sphere, T = 10 s", sc, 10.0, [5, 10, 20, 40]))
        slack = converge_slack(args.slack_n, args.slack_duration, moordyn=not args.no_moordyn, keep=args.out / "runs")
        plot_slack(slack, args.out / "segmented_convergence_slack.png")
    doc = {"results": results}
    if slack:
        strip = lambda rows: [{k: v for k, v in r.items() if k != "series"} for r in rows]
        doc["slack"] = {**slack, "rows": strip(slack["rows"]), "moordyn": strip(slack.get("moordyn", []))}
    write_json(args.out / "segmented_convergence.json", doc)
    if results:
        plot(results, args.out / "segmented_convergence.png")
    for res in results:
        print(res["scene"])
        for r in res["rows"]:
            print(f"  N = {r['n']:3d}  x_amp {r.get('x_amp', float('nan')):.6g}  top max {r.get('top_max', float('nan')):.6g} N"
                  f"  wall {r['wall_s']:.2f} s  err {r.get('rel_err')}")
        print(f"  2-DOF  err {res['two_dof']['rel_err']}")
    if slack:
        print(slack["scene"], "window", slack["window_s"])
        for code, rows in (("cablesys", slack["rows"]), ("MoorDyn", slack.get("moordyn", []))):
            for r in rows:
                print(f"  {code:8s} N = {r['n']:3d}  y_amp {r.get('y_amp', float('nan')):.4f} m  top max {r.get('top_max', float('nan')):.0f} N"
                      f"  top min {r.get('top_min', float('nan')):.0f} N  slack bottom {r.get('slack_bottom', float('nan')):.3f}"
                      f"  top {r.get('slack_top', float('nan')):.3f}  dt {r.get('dt_s', float('nan')):.3g} s"
                      f"  {r.get('run_s_per_s', float('nan')):.3g} s/s  order {r.get('observed_order')}")
        print("  time-step check", slack["time_step_check"])
    return 0


def dataclasses_replace_top(scene, period: float):
    """The scene's top motion with its heave at ``period``."""
    import dataclasses
    y = tuple(dataclasses.replace(s, frequency=2 * math.pi / period) for s in scene.top_motion.y)
    return dataclasses.replace(scene.top_motion, y=y)


if __name__ == "__main__":
    sys.exit(main())
