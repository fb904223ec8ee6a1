"""The ``run`` and ``scene`` sub-commands (Wang 1971 time domain)."""

from __future__ import annotations

import json
import logging
import math
from pathlib import Path

from .. import units as U
from ..results import unit_of

log = logging.getLogger(__name__)


def register(sub) -> None:
    p = sub.add_parser("run", help="simulate a scene (default: the Dale et al. model at four frequencies)",
                       description="Simulate SCENE.toml and write time series (CSV, netCDF), summary.json and "
                                   "plots to --out. Without a scene: the built-in Dale et al. water-channel model "
                                   "(Wang 1971 Table 1) at omega/omega_n = 0.5, 1, 1.5, 2, and a table of "
                                   "lower-body amplitudes.")
    p.add_argument("scene", nargs="?", type=Path, help="scene TOML file (see `cablesys scene --example`)")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: cablesys-out)")
    p.add_argument("--method", default=None, help="cvodes | cvodes-adams | idas | rk | collocation")
    p.add_argument("--duration", type=float, default=None, help="simulated time in s (overrides the scene)")
    p.add_argument("--jit", action="store_true", help="compile the model with the C compiler (faster long runs, ~2 s build)")
    p.add_argument("--strict", action="store_true", help="exit with status 3 when a criterion of the scene's [limits] fails")
    p.set_defaults(func=_run)
    s = sub.add_parser("scene", help="print an annotated example scene, or check a scene file",
                       description="With --example: print an annotated scene (the Dale default). With a file: "
                                   "validate it and print it back in SI.")
    s.add_argument("file", nargs="?", type=Path)
    s.add_argument("--example", nargs="?", const="dale", default=None, choices=("dale", "rov-lift"),
                   help="print an annotated example scene: dale (default) or rov-lift (irregular sea, limits, design)")
    s.add_argument("--design", action="store_true", help="with --example: append a commented [design] template")
    s.add_argument("--units", default="SI", choices=("SI", "fps"), help="units to print in")
    s.set_defaults(func=_scene)


def _scene(args) -> int:
    from ..scene import default_scene, dump_scene, load_scene
    if args.example == "rov-lift":
        from ..examples import example_text
        print(example_text("rov-lift"), end="")
        return 0
    if args.example or args.file is None:
        print(dump_scene(default_scene(), units=args.units, annotate=True), end="")
        if args.design:
            from ..design.example import design_template
            print(design_template(), end="")
        return 0
    print(dump_scene(load_scene(args.file), units=args.units, annotate=True), end="")
    return 0


def _forcing_period(scene) -> float | None:
    freqs = [s.frequency for s in scene.top_motion.x + scene.top_motion.y]
    return 2 * math.pi / min(freqs) if freqs else None


def _run(args) -> int:
    from ..scene import load_scene
    from . import simulate
    out = args.out or Path("cablesys-out")
    if args.scene is None:
        return _run_dale_table(args, out)
    scene = load_scene(args.scene)
    if args.duration:
        scene = scene.with_numerics(duration=args.duration)
    result = simulate(scene, method=args.method, jit=args.jit)
    summary = write_run(scene, result, out)
    _print_summary(summary)
    if not result.success:
        print(f"error: {result.message}")
        return 1
    if getattr(args, "strict", False) and not all(v["pass"] for v in summary.get("verdict", {}).values()):
        return 3
    return 0


def write_run(scene, result, out: Path) -> dict:
    """Write time series (CSV, netCDF), summary.json and the figure for one run."""
    from ..plots.time_domain import plot_time_series
    out.mkdir(parents=True, exist_ok=True)
    result.to_csv(out / "timeseries.csv")
    result.to_netcdf(out / "timeseries.nc")
    summary = result.summary()
    period = _forcing_period(scene)
    if period and scene.top_motion.spectrum is None and result.time[-1] - result.time[0] >= 6 * period:
        summary["amplitude_periods"] = 3
        amps = {lbl: result.steady_amplitude(lbl, period, 3)
                for lbl in result.labels if lbl.startswith(("x_b", "y_b", "phi", "u", "tension"))
                and not lbl.endswith("rate")}
        for unit in ("m", "rad", "N"):      # grouped by quantity, the unit in the key
            summary[f"amplitudes_{unit}"] = {k: v for k, v in amps.items() if unit_of(k) == unit}
    from ..verdict import report
    summary.update(report(scene, result))
    (out / "summary.json").write_text(json.dumps(summary, indent=2, default=float))
    plot_time_series(result, out / "timeseries.png")
    return summary


def _print_summary(summary: dict) -> None:
    print(f"scene: {summary['scene']}")
    st = summary["stats"]
    print(f"integrator {st['method']}: {st.get('nsteps', '-')} steps, {st.get('nfevals', st.get('nresevals', '-'))} "
          f"rhs evaluations, {st['wall_s'] * 1e3:.0f} ms (+ {st['build_s'] * 1e3:.0f} ms build)")
    for unit in ("m", "rad", "N"):
        for k, v in summary.get(f"amplitudes_{unit}", {}).items():
            print(f"  amplitude {k:14s} {v:.6g} {unit}")
    print(f"  tension min/max {summary.get('tension_min_N', float('nan')):.4g} / {summary.get('tension_max_N', float('nan')):.4g} N,"
          f" time slack {summary['time_slack_s']:.3g} s")
    from ..verdict import format_statistics, format_table
    for line in (format_statistics(summary["statistics"]) if "statistics" in summary else []) + \
            summary.get("warnings", []) + (format_table(summary["verdict"]) if summary.get("verdict") else []):
        print("  " + line)


def _run_dale_table(args, out: Path) -> int:
    from ..scene import OMEGA_N_MEASURED, dale_scene
    from . import simulate
    print("Dale et al. water-channel model (Wang 1971, Table 1): 9 ft cable, 1 in sphere, circular top motion 5 in p-p")
    print("steady-state amplitudes of the lower body (half peak-to-peak over the last 3 periods)")
    print(f"{'omega/omega_n':>14} {'omega rad/s':>12} {'x_bA ft':>9} {'y_bA ft':>9} {'x_bA m':>9} {'y_bA m':>9} {'ms':>6}")
    from .integrators import IntegratorSettings
    from .run import Simulator
    from ..model import build_model
    rows, ok, sim = [], True, None
    for ratio in (0.5, 1.0, 1.5, 2.0):
        scene = dale_scene(omega_ratio=ratio, duration=args.duration or 150.0)
        if sim is None:      # one model and one set of integrators: only parameter values change
            num = scene.numerics
            sim = Simulator(build_model(scene), scene.output_times, IntegratorSettings(
                method=args.method or num.integrator, rtol=num.rtol, atol=num.atol, jit=args.jit))
        r = simulate(scene, simulator=sim)
        ok &= r.success
        T = 2 * math.pi / (ratio * OMEGA_N_MEASURED)
        xa, ya = r.steady_amplitude("x_b", T, 3), r.steady_amplitude("y_b", T, 3)
        rows.append({"omega_over_omega_n": ratio, "xbA_ft": xa / U.FT, "ybA_ft": ya / U.FT, "xbA_m": xa, "ybA_m": ya})
        print(f"{ratio:14.2f} {ratio * OMEGA_N_MEASURED:12.3f} {xa / U.FT:9.4f} {ya / U.FT:9.4f} {xa:9.4f} {ya:9.4f} "
              f"{r.stats['wall_s'] * 1e3:6.0f}")
        if ratio == 1.0:
            write_run(scene, r, out)
    (out / "dale_amplitudes.json").write_text(json.dumps(rows, indent=2))
    print(f"wrote {out}/ (time series, summary.json and plots of the omega = omega_n run; dale_amplitudes.json)")
    return 0 if ok else 1
