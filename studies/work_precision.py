"""Speed against accuracy: work-precision diagrams and the explicit-method stability limit.

    python studies/work_precision.py --out DIR [--quick]

1. For the Dale scene (AE = 1000 lb) and a stiff steel-like variant (AE a thousand times
   larger), every integrator of ``cablesys.time_domain`` is run over a sweep of tolerances
   (adaptive 'cvodes', 'cvodes-adams', 'idas': rtol 1e-3 ... 1e-10 with atol = 1e-3 rtol) or
   of steps per output interval (fixed-step 'rk' and 'collocation'). The error is the largest
   distance of the lower body from its position in a CVODES run at rtol 1e-12 (atol 1e-14),
   over all output times; the work is the wall time of ``Simulator.run`` (build excluded,
   best of two). -> DIR/work_precision.json, DIR/work_precision.png
2. The largest stable fixed step of the explicit method 'rk' (classical RK4) against AE,
   found by bisection (a run of ``N_STABILITY_STEPS`` steps is stable if it stays finite and
   its stretch stays below ten times that of a run at a tenth of the step), compared with the
   RK4 limits h omega_max = 2.785 (negative real axis) and 2 sqrt(2) = 2.828 (imaginary axis,
   an undamped oscillation), where omega_max = sqrt(k / (M_by + M_c/3)) is the stretch
   frequency. -> DIR/rk_stability.json, DIR/rk_stability.png
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import parse_args, setup_matplotlib, write_json  # noqa: E402

from cablesys import units as U  # noqa: E402
from cablesys.integration import METHODS  # noqa: E402
from cablesys.linear import modes  # noqa: E402
from cablesys.linear.linearization import linearize  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.plots import save_figure  # noqa: E402
from cablesys.scene import dale_scene  # noqa: E402
from cablesys.time_domain import IntegratorSettings, Simulator  # noqa: E402
from cablesys.time_domain.run import initial_state  # noqa: E402

ADAPTIVE = tuple(name for name, m in METHODS.items() if m.adaptive)       # the one registry
FIXED = tuple(name for name, m in METHODS.items() if not m.adaptive and name != "rkc")   # rkc: stages from the model (the extrapolation picks them)
RK4_REAL_LIMIT = 2.785293563405282      # |1 + z + z^2/2 + z^3/6 + z^4/24| = 1 on the negative real axis
RK4_IMAG_LIMIT = 2.0 * math.sqrt(2.0)   # ... on the imaginary axis
N_STABILITY_STEPS = 2000
OUTPUT_STEP = 0.05


def stretch_frequency(scene) -> float:
    """omega_max = sqrt(k / (M_by + M_c/3)), the stretch (spring-mass) frequency of the section."""
    c, b = scene.cable, scene.body
    return math.sqrt(c.spring_constant / (b.mass_y + c.total_mass / 3.0))


def run_case(model, scene, times, settings, repeat=2):
    """(best wall time in s, RunRecord) for one method/tolerance, build excluded."""
    sim = Simulator(model, times, settings)
    p = model.parameters(scene)
    x0 = initial_state(scene, model, p)
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = sim.run(p, x0)
        best = min(best, time.perf_counter() - t0)
        if not out.success or best > 1.0:      # failed, or long enough to time once
            break
    return best, out


def work_precision(model, scene, name, span, rtols, spos, log, repeat, quick=False) -> dict:
    times = np.arange(int(round(span / OUTPUT_STEP)) + 1) * OUTPUT_STEP
    ref_wall, ref = run_case(
        model, scene, times, IntegratorSettings(method="cvodes", rtol=1e-12, atol=1e-14, max_num_steps=10_000_000),
        repeat=1)
    if not ref.success:
        raise RuntimeError(f"reference run failed: {ref.message}")
    ref_stats = ref.stats
    xr, yr = ref["x_b"], ref["y_b"]
    res = {"scene": name, "ae_lb": scene.cable.ae / U.LBF, "span_s": span, "output_step_s": OUTPUT_STEP,
           "omega_max_rad_s": stretch_frequency(scene),
           "reference": {"method": "cvodes", "rtol": 1e-12, "atol": 1e-14, "wall_s": ref_wall,
                         "steps": int(ref_stats.get("nsteps", 0))},
           "methods": {}}
    for method in ADAPTIVE + FIXED:
        rows = []
        sweep = rtols if method in ADAPTIVE else spos
        for v in sweep:
            if method in ADAPTIVE:
                st = IntegratorSettings(method=method, rtol=v, atol=1e-3 * v, max_num_steps=1_000_000)
            else:
                st = IntegratorSettings(method=method, steps_per_output=int(v))
            if method == "collocation" and v > (100 if name == "stiff" else 20):
                continue                  # minutes of Newton solves for nothing new
            if method == "cvodes-bdf2" and quick and v < 1e-7:
                continue                  # quick: BDF(<= 2) at rtol 1e-9 on the stiff wire is a third of the run
            wall, r = run_case(model, scene, times, st, repeat)
            stats, msg = r.stats, r.message
            row = {"rtol" if method in ADAPTIVE else "steps_per_output": v, "wall_s": wall,
                   "steps": int(stats.get("nsteps", 0)) if method in ADAPTIVE else int(v) * (times.size - 1),
                   "success": bool(r.success and r.n_outputs == times.size), "slack_events": stats["n_events"]}
            if row["success"] and stats["n_events"] > ref_stats["n_events"]:
                # the Dale scenes stay taut; an unstable explicit run makes the stretch oscillation grow
                # until the cable "goes slack", and the slack logic then hides the blow-up
                row["success"] = False
                msg = f"spurious taut/slack switching ({stats['n_events']} events): unstable"
            if method not in ADAPTIVE:
                row["h_s"] = OUTPUT_STEP / v
                row["h_omega_max"] = OUTPUT_STEP / v * res["omega_max_rad_s"]
            if row["success"]:
                xb, yb = r["x_b"], r["y_b"]
                row["error_m"] = float(np.max(np.hypot(xb - xr, yb - yr)))
                row["success"] = bool(np.isfinite(row["error_m"]))
            else:
                row["error_m"] = None
                row["message"] = msg[:300]
            rows.append(row)
            log(f"  {name:6s} {method:12s} {('rtol %.0e' % v) if method in ADAPTIVE else ('spo %4d' % v)}: "
                + (f"error {row['error_m']:.2e} m, {1e3 * wall:8.1f} ms" if row["success"] else "FAILED (unstable)"))
        res["methods"][method] = rows
    return res


def rk_stable(model, scene, h, n_steps) -> bool:
    """True if 'rk' with step h stays bounded over ``n_steps`` steps.

    The scene's cable is made a rod (tension_floor = -inf): otherwise a growing stretch
    oscillation makes the cable "go slack" and the slack logic bounds (hides) the blow-up.
    """
    scene = scene.replace_section(0, cable={"tension_floor": -math.inf})

    def max_stretch(step):
        times = np.arange(n_steps + 1) * step
        sim = Simulator(model, times, IntegratorSettings(method="rk", steps_per_output=1))
        p = model.parameters(scene)
        r = sim.run(p, initial_state(scene, model, p))
        if not r.success or r.events or r.n_outputs < times.size or not np.all(np.isfinite(r.states)):
            return math.inf
        return float(np.max(np.abs(r["u"])))
    bound = max_stretch(h / 10.0)          # a tenth of the step (shorter span): well inside the limit
    return max_stretch(h) < 10.0 * bound


def stability_limit(model, scene, n_steps, rel=2e-3) -> float:
    """Largest stable RK4 step by bisection, starting from a bracket around the theory."""
    w = stretch_frequency(scene)
    lo, hi = 1.5 / w, 4.0 / w
    if not rk_stable(model, scene, lo, n_steps):
        lo = 0.2 / w
    if rk_stable(model, scene, hi, n_steps):
        return hi
    while hi - lo > rel * lo:
        mid = 0.5 * (lo + hi)
        if rk_stable(model, scene, mid, n_steps):
            lo = mid
        else:
            hi = mid
    return lo


def linear_stretch_frequency(model, scene) -> float:
    """Largest undamped frequency of the model linearized at rest (cablesys.linear), rad/s."""
    return float(np.max(modes(linearize(model, model.parameters(scene))).omega_undamped))


def main(argv=None) -> int:
    args = parse_args(__doc__.splitlines()[0], argv)
    log = print
    span = 1.0 if args.quick else 10.0
    rtols = (1e-3, 1e-5, 1e-7, 1e-9) if args.quick else (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
    base = dale_scene()
    model = build_model(base)                          # one model: AE is a parameter
    scenes = {"dale": base, "stiff": dale_scene(ae_lb=1000.0 * 1000.0)}
    spos = {"dale": (2, 5, 10, 20, 50) if args.quick else (1, 2, 5, 10, 20, 50, 100, 200),
            "stiff": (20, 200, 500) if args.quick else (5, 20, 100, 200, 500, 1000, 2000)}
    t0 = time.perf_counter()
    repeat = 1 if args.quick else 2
    wp = {name: work_precision(model, sc, name, span, rtols, spos[name], log, repeat, args.quick)
          for name, sc in scenes.items()}
    wp_json = {"what": "error = max over output times of |r_b - r_b,ref| (m); work = wall time of Simulator.run (s)",
               "quick": bool(args.quick), "scenes": wp, "wall_s": time.perf_counter() - t0}
    write_json(args.out / "work_precision.json", wp_json)
    plot_wp(args.out / "work_precision.png", wp)

    # largest stable RK4 step against AE
    ae_list = (5.0, 1000.0, 1e6) if args.quick else (5.0, 20.0, 100.0, 1000.0, 1e4, 1e5, 1e6)
    n_steps = 1000 if args.quick else N_STABILITY_STEPS
    rows = []
    for ae in ae_list:
        sc = dale_scene(ae_lb=ae)
        h = stability_limit(model, sc, n_steps, rel=1e-2 if args.quick else 2e-3)
        w = stretch_frequency(sc)
        w_lin = linear_stretch_frequency(model, sc)
        rows.append({"ae_lb": ae, "h_max_s": h, "omega_max_rad_s": w, "omega_linearized_rad_s": w_lin,
                     "h_omega_max": h * w, "ratio_to_real_axis_limit": h * w / RK4_REAL_LIMIT,
                     "ratio_to_imag_axis_limit": h * w / RK4_IMAG_LIMIT})
        log(f"  rk: AE {ae:8.0f} lb: h_max = {h:.3e} s, h omega_max = {h * w:.3f}")
    stab = {"method": "rk", "criterion": f"finite and stretch < 10x that at h/10 over {n_steps} steps "
                                         "(cable made a rod, tension_floor = -inf, so slack cannot mask a blow-up)",
            "rk4_real_axis_limit": RK4_REAL_LIMIT, "rk4_imag_axis_limit": RK4_IMAG_LIMIT, "rows": rows,
            "max_rel_dev_from_real_axis_limit": max(abs(r["ratio_to_real_axis_limit"] - 1) for r in rows),
            "max_rel_dev_from_imag_axis_limit": max(abs(r["ratio_to_imag_axis_limit"] - 1) for r in rows)}
    write_json(args.out / "rk_stability.json", stab)
    plot_stability(args.out / "rk_stability.png", stab)
    return 0


STYLE = {"cvodes": ("tab:blue", "o"), "cvodes-bdf2": ("tab:cyan", "P"), "cvodes-adams": ("tab:orange", "s"),
         "idas": ("tab:green", "^"),
         "rk": ("tab:red", "D"), "collocation": ("tab:purple", "v"), "dopri5": ("tab:brown", "X"),
         "rk23": ("tab:olive", "*")}
DEFAULT_STYLE = ("tab:gray", ".")      # a registered method without its own style still plots


def plot_wp(path, wp):
    plt = setup_matplotlib()
    fig, axes = plt.subplots(1, len(wp), figsize=(6.5 * len(wp), 5.5))
    for ax, (name, res) in zip(np.atleast_1d(axes), wp.items()):
        for method, rows in res["methods"].items():
            ok = [r for r in rows if r["success"]]
            if not ok:
                continue
            c, mk = STYLE.get(method, DEFAULT_STYLE)
            failed = [r for r in rows if not r["success"]]
            lbl = method + (" (rtol sweep)" if method in ADAPTIVE else " (steps/output sweep)")
            if failed:
                key = "rtol" if method in ADAPTIVE else "steps_per_output"
                lbl += "; failed at " + ", ".join(f"{r[key]:g}" for r in failed)
            ax.loglog([r["wall_s"] for r in ok], [max(r["error_m"], 1e-16) for r in ok], color=c, marker=mk, label=lbl)
            if method in ADAPTIVE:
                for r in (ok[0], ok[-1]):           # loosest and tightest rtol
                    ax.annotate(f"{r['rtol']:.0e}", (r["wall_s"], max(r["error_m"], 1e-16)), fontsize=7,
                                color=c, xytext=(3, 3), textcoords="offset points")
        ax.set_xlabel("wall time of the run (s)")
        ax.set_ylabel("max body-position error vs rtol-1e-12 reference (m)")
        ax.set_title(f"{name}: AE = {res['ae_lb']:g} lb, {res['span_s']:g} s, omega_max = {res['omega_max_rad_s']:.0f} rad/s",
                     fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    save_figure(fig, path, dpi=110)


def plot_stability(path, stab):
    plt = setup_matplotlib()
    rows = stab["rows"]
    ae = np.array([r["ae_lb"] for r in rows])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    ax1.loglog(ae, [r["h_max_s"] for r in rows], "o", color="tab:red", label="largest stable RK4 step (measured)")
    w = np.array([r["omega_max_rad_s"] for r in rows])
    ax1.loglog(ae, RK4_REAL_LIMIT / w, "-", color="k", lw=1, label="2.785 / omega_max (real-axis limit)")
    ax1.loglog(ae, RK4_IMAG_LIMIT / w, "--", color="0.4", lw=1, label="2.828 / omega_max (imaginary-axis limit)")
    ax1.set_xlabel("cable AE (lb)")
    ax1.set_ylabel("largest stable step h (s)")
    ax1.set_title("explicit RK4 ('rk'): step limit set by the stretch mode")
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=8)
    ax2.semilogx(ae, [r["h_omega_max"] for r in rows], "o-", color="tab:red", label="measured h_max * omega_max")
    ax2.axhline(RK4_REAL_LIMIT, color="k", lw=1, label="2.785")
    ax2.axhline(RK4_IMAG_LIMIT, color="0.4", ls="--", lw=1, label="2 sqrt(2) = 2.828")
    ax2.set_ylim(2.0, 3.5)
    ax2.set_xlabel("cable AE (lb)")
    ax2.set_ylabel("h_max * omega_max (-)")
    ax2.set_title("omega_max = sqrt(k / (M_by + M_c/3))")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    save_figure(fig, path, dpi=110)


if __name__ == "__main__":
    raise SystemExit(main())
