"""The ``run`` and ``scene`` sub-commands: a scene through the model ladder's choice (:func:`cablesys.ladder.simulate`),
its series, summary, verdict and figure written to ``--out``."""

from __future__ import annotations

import dataclasses
import logging
import math
import sys
from pathlib import Path

import numpy as np

from .. import units as U
from ..examples import EXAMPLES
from ..ladder.metrics import forcing_period
from ..integration import METHODS
from ..ladder.rungs import MODEL_CHOICES, RUNGS, check_rung
from ..time_domain.integrators import IntegratorSettings
from ..results import unit_of
from ..statistics import half_range
from ..statistics import window_mask as st_window_mask

log = logging.getLogger(__name__)


_DEFAULT_STEPS = next(f.default for f in dataclasses.fields(IntegratorSettings) if f.name == "max_num_steps")


def register(sub) -> None:
    p = sub.add_parser("run", help="simulate a scene (default: the Dale et al. model at four frequencies)",
                       description="Simulate SCENE.toml and write time series (CSV, netCDF), summary.json and "
                                   "plots to --out. Without a scene: the built-in Dale et al. water-channel model "
                                   "(Wang 1971 Table 1) at omega/omega_n = 0.5, 1, 1.5, 2, and a table of "
                                   "lower-body amplitudes.")
    p.add_argument("scene", nargs="?", type=Path, help="scene TOML file (see `cablesys scene --example`)")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: cablesys-out)")
    p.add_argument("--method", default=None, help=" | ".join(METHODS) + " (default: the ladder's choice, or the scene's "
                                                 "numerics.integrator when it names one)")
    p.add_argument("--model", default=None, help=" | ".join(MODEL_CHOICES) + " (default: the scene's numerics.model): "
                                                "the model ladder's rung (cablesys.ladder)")
    p.add_argument("--duration", type=float, default=None, help="simulated time in s (overrides the scene)")
    p.add_argument("--window", type=float, nargs=2, default=None, metavar=("T0", "T1"),
                   help="statistics window in s for summary.json (default: the last 5 forcing periods in the run's "
                        "second half, after the smooth start)")
    p.add_argument("--jit", action="store_true", help="compile the model with the C compiler whatever its size "
                                                      "(compiled code is the default up to a size limit)")
    p.add_argument("--strict", action="store_true", help="exit with status 3 when a criterion of the scene's [limits] fails")
    p.add_argument("--units", default=None, choices=("SI", "fps"),
                   help="units of the console, CSV and figure (default: those of the scene file)")
    p.add_argument("--overwrite", action="store_true", help="replace results of another scene in --out")
    p.add_argument("--max-steps", type=int, default=None,
                   help=f"integrator step budget per output interval (default {_DEFAULT_STEPS}); a run that needs more "
                        "fails with a named message")
    p.add_argument("--time-budget", type=float, default=None, metavar="S",
                   help="wall seconds model = auto may plan for a run (numerics.time_budget_s; 0: none): a run predicted "
                        "past it (compile and steps) is refused before it is built, a slack scene's extrapolation "
                        "lowers N to fit first")
    p.set_defaults(func=_run)
    s = sub.add_parser("scene", help="print an annotated example scene, or check a scene file",
                       description="With --example: print an annotated scene (the Dale default). With a file: "
                                   "validate it and print it back in SI.")
    s.add_argument("file", nargs="?", type=Path)
    s.add_argument("--example", nargs="?", const="dale", default=None, choices=("dale",) + tuple(EXAMPLES),
                   help="print an annotated example scene: dale (default), rov-lift (irregular sea, limits, design), "
                        "light-lift (a light cage in a steep sea: slack and snap), clump-span (a system of lines "
                        "joined at points: a span with a clump weight hung from a junction) or dual-isolation (a "
                        "package below a damper plate and a soft insert: a chain of sections with a [design] table)")
    s.add_argument("--design", action="store_true", help="with --example: append a commented [design] template")
    s.add_argument("--units", default="SI", choices=("SI", "fps"), help="units to print in")
    s.set_defaults(func=_scene)


def _scene(args) -> int:
    from ..scene import default_scene, dump_scene, load_scene
    if args.example in EXAMPLES:
        from ..examples import example_text
        print(example_text(args.example), end="")
        return 0
    if args.example or args.file is None:
        print(dump_scene(default_scene(), units=args.units, annotate=True), end="")
        if args.design:
            from ..isolation.example import design_template
            print(design_template(), end="")
        return 0
    print(dump_scene(load_scene(args.file), units=args.units, annotate=True), end="")
    return 0


RUN_FILES = ("timeseries.csv", "timeseries.nc", "timeseries.png", "plan_view.png")


class _Progress:
    """A progress line on stderr for runs longer than a few seconds (overwritten in place on a terminal)."""

    AFTER_S, EVERY_S = 3.0, 2.0

    def __init__(self, label: str = ""):
        self.label, self.next = label, self.AFTER_S
        self.tty = sys.stderr.isatty()
        self.shown = False

    def __call__(self, t: float, t_end: float, wall: float) -> None:
        if wall < self.next and t < t_end:
            return
        if not self.shown and t >= t_end:
            return                                  # a short run: no line at all
        self.next = wall + self.EVERY_S
        frac = t / t_end if t_end > 0 else 1.0
        left = f", about {wall * (1 - frac) / frac:.0f} s left" if 0 < frac < 1 else ""
        line = f"cablesys run{self.label}: t = {t:.6g} of {t_end:.6g} s ({100 * frac:.0f} %), {wall:.1f} s elapsed{left}"
        end = "\n" if (not self.tty or t >= t_end) else ""
        sys.stderr.write(("\r" if self.tty else "") + line + end)
        sys.stderr.flush()
        self.shown = True


def _print_plan(prediction) -> None:
    """The run's predicted cost on stderr before its model is built (:meth:`cablesys.ladder.plan_cost.Prediction.line`)."""
    print(f"cablesys run: {prediction.line()}", file=sys.stderr, flush=True)


def _check_options(args) -> None:
    """Option values refused before anything is built (named errors)."""
    from ..errors import ParameterError, require_positive
    if args.duration is not None:
        require_positive("--duration", args.duration, "s")
    if getattr(args, "model", None) is not None:
        check_rung(args.model)
    budget = getattr(args, "time_budget", None)
    if budget is not None and not (0 <= budget < float("inf")):
        raise ParameterError("--time-budget", budget, "must be a finite number of seconds >= 0 (0: no budget)")
    if args.max_steps is not None and not 100 <= args.max_steps <= 10**9:
        raise ParameterError("--max-steps", args.max_steps, "must be an integer in [100, 1e9] (steps per output interval)")


class _Streams:
    """``on_run`` of :func:`cablesys.ladder.simulate` for the ``run`` command: each candidate run of the plan streams
    its series to ``timeseries.partial.csv`` (a new stream replaces the last: the returned result is the last
    candidate's), every run shows a progress line naming it and its place in the plan."""

    def __init__(self, outdir, units: str, label: str = ""):
        self.outdir, self.units, self.label = outdir, units, label
        self.stream, self.count = None, 0

    def __call__(self, description: str, candidate: bool):
        from ..export import series_table
        from ..time_domain.record import RunRecord
        self.count += 1
        # the plan's own descriptions count its runs ("run 2 of 3"); others get the count of runs so far
        progress = _Progress(f"{self.label} [{description}]" if "(run " in description
                             else f"{self.label} [{description}, run {self.count}]")
        if not candidate:
            return None, progress
        if self.stream is not None:
            self.stream.discard()
        units = self.units
        self.stream = self.outdir.stream_csv("timeseries.csv", lambda t, d: series_table(RunRecord(time=t, data=d), units))
        return self.stream.append, progress

    def close(self) -> bool:
        """Close the last candidate's stream (complete: it is ``timeseries.csv``); False when nothing streamed."""
        if self.stream is None:
            return False
        self.stream.close()
        return True

    def discard(self) -> None:
        if self.stream is not None:
            self.stream.discard()


def _run(args) -> int:
    from ..ladder import simulate
    from ..ladder.rungs import rung_scene
    from ..outputs import OutputDir
    from ..scene import load_scene
    from ..time_domain.record import RunInterrupted, check_scene_run_size
    _check_options(args)
    out = args.out or Path("cablesys-out")
    if args.scene is None:
        return _run_dale_table(args, out)
    scene = load_scene(args.scene)
    if args.duration is not None:
        scene = scene.with_numerics(duration=args.duration)
    if getattr(args, "time_budget", None) is not None:
        scene = scene.with_numerics(time_budget_s=args.time_budget)
    check_scene_run_size(scene)                       # limits, before anything is built
    outdir = OutputDir(out, "run", scene, overwrite=args.overwrite, owned=RUN_FILES)   # --out checked here
    from ..export import units_of_file
    units = args.units or units_of_file(args.scene)
    with outdir.start(scene=scene.name, scene_file=str(args.scene)):
        streams = _Streams(outdir, units)
        try:
            result = simulate(scene, model=args.model, method=args.method, max_num_steps=args.max_steps, jit=args.jit,
                              on_run=streams, on_plan=_print_plan)
        except RunInterrupted as err:
            # the stream holds whole rows: kept when they are exactly the interrupted record's series
            on_disk = streams.stream is not None and streams.stream.holds(err.result.time) and streams.close()
            if not on_disk:
                streams.discard()
            summary = write_run(scene, err.result, outdir, plot=False, units=units, series_on_disk=on_disk)
            outdir.finish("interrupted", **summary)
            print(f"interrupted: {err.result.message}; wrote {outdir.path}/ ({', '.join(outdir.files)})", file=sys.stderr)
            raise
        on_disk = streams.close()
        info = result.stats["model"]
        if getattr(args, "window", None):         # the statistics window of the summary groups, if asked
            result = dataclasses.replace(result, window_s=tuple(args.window))
        # the scene the model ran: as built, the scene itself (its model_info counts every element, not N per section)
        as_built = (args.model or scene.numerics.model) == "as-built"
        scene_run = rung_scene(scene, info["name"], info.get("segments") or 1) if info["name"] in RUNGS and not as_built \
            else scene
        summary = write_run(scene_run, result, outdir, series_on_disk=on_disk, units=units)
        if "run_s" in result.stats:     # a time-domain run: the ladder built its models and simulators besides
            summary["timing"]["build_s"] += float(result.stats.get("ladder_timing", {}).get("build_s", 0.0))
        summary["model"] = info
        outdir.finish("success" if result.success else "failed", **summary)
    sys.stdout.write("\n".join(summary_lines(summary, units)) + "\n")
    print(f"wrote {out}/ ({', '.join(outdir.files)}, summary.json)")
    if not result.success:
        print(f"error: {result.message}")
        return 1
    if getattr(args, "strict", False) and not all(v["pass"] for v in summary.get("verdict", {}).values()):
        return 3
    return 0


def _simulate_into(outdir, scene, label: str = "", units: str = "SI", **kw):
    """Run ``scene`` as built with its series streamed to ``outdir`` (CSV in ``units``); on an interrupt write
    what was computed (manifest status ``interrupted``) and re-raise."""
    from ..export import series_table
    from ..time_domain.record import RunInterrupted, RunRecord
    from ..time_domain.run import simulate
    stream = outdir.stream_csv("timeseries.csv", lambda t, d: series_table(RunRecord(time=t, data=d), units))
    try:
        result = simulate(scene, on_block=stream.append, progress=_Progress(label), **kw)
    except RunInterrupted as err:
        on_disk = stream.holds(err.result.time)       # whole rows, exactly the interrupted record's series
        stream.close() if on_disk else stream.discard()
        summary = write_run(scene, err.result, outdir, plot=False, units=units, series_on_disk=on_disk)
        outdir.finish("interrupted", **summary)
        print(f"interrupted: {err.result.message}; wrote {outdir.path}/ ({', '.join(outdir.files)})", file=sys.stderr)
        raise
    stream.close()
    return result


def write_run(scene, result, out, *, plot: bool = True, series_on_disk: bool = False, units: str = "SI") -> dict:
    """Write time series (CSV, netCDF) and the figure for one run; return its summary.

    Parameters
    ----------
    scene : Scene
        The scene run.
    result : RunRecord or TimeResult
        Its result.
    out : OutputDir or path
        The folder. A plain path gets its own :class:`~cablesys.outputs.OutputDir` whose
        manifest ``summary.json`` is finished here; with an ``OutputDir`` the caller finishes it.
    plot : bool
        Also draw ``timeseries.png`` (and ``plan_view.png`` for a 3-D run or a track).
    series_on_disk : bool
        ``timeseries.csv`` was already streamed complete (do not write it again).
    units : str
        "SI" or "fps": units of the CSV columns and the figure (netCDF and summary.json stay SI).

    Returns
    -------
    dict
        The summary (``summary.json`` content without the manifest entries).
    """
    from ..outputs import OutputDir
    if not isinstance(out, OutputDir):
        with OutputDir(out, "run", scene, overwrite=True).start(scene=scene.name) as od:
            summary = write_run(scene, result, od, plot=plot)
            od.finish(getattr(result, "status", "success" if result.success else "failed"), **summary)
        return summary
    from ..export import write_csv, write_netcdf
    from ..scene import dump_scene
    if not series_on_disk:
        with out.writing("timeseries.csv") as tmp:
            write_csv(result, tmp, units)
    with out.writing("timeseries.nc") as tmp:       # SI, conventions and the scene to reproduce the run
        write_netcdf(result, tmp, scene_toml=dump_scene(scene), scene_units=units)
    start = getattr(scene.limits, "statistics_start", None)
    if start is not None and getattr(result, "window_s", None) is None:     # one window: the verdict's start
        result = dataclasses.replace(result, window_s=(float(start), float(result.time[-1])))
    summary = result.summary()
    summary.pop("status", None)
    system = getattr(scene, "system", None)
    if system is None:    # where the last section's tension_bottom acts: its body, or the anchor that holds its lower end
        summary["tension_bottom_at"] = "at the anchor" if scene.anchor is not None else "at the body"
    st = result.stats
    summary["timing"] = {k: float(st.get(k, 0.0)) for k in ("build_s", "load_s", "run_s")}
    if "ladder_timing" in st and "run_s" not in st:     # the frequency rung: no time-domain run, the ladder's times
        summary["timing"].update(build_s=float(st["ladder_timing"].get("build_s", 0.0)),
                                 run_s=float(st["ladder_timing"].get("run_s", 0.0)))
    period = forcing_period(scene)
    t0, t1 = (summary["window"]["start_s"], summary["window"]["end_s"]) if "window" in summary else (0.0, 0.0)
    if period and t1 - t0 >= period * (1 - 1e-9):   # None for an irregular sea: no periodic amplitudes
        # the amplitudes over the one statistics window (cablesys.statistics.window), which holds a whole period
        summary["amplitude_periods"] = (t1 - t0) / period
        mask = st_window_mask(result.time, t0, t1)
        free = tuple(f"point.{p.name}." for p in system.point if p.free) if system is not None else ()
        amps = {lbl: half_range(np.asarray(result[lbl])[mask])
                for lbl in result.labels if lbl.startswith(("x_b", "y_b", "z_b", "phi", "u", "tension", "line.") + free)
                and not lbl.endswith("rate")}
        for unit in ("m", "rad", "N"):      # grouped by quantity, the unit in the key
            summary[f"amplitudes_{unit}"] = {k: v for k, v in amps.items() if unit_of(k) == unit}
    from ..verdict import report
    summary.update(report(scene, result))
    if scene.top_motion.spectrum is not None:       # the linear frequency-domain statistics of the same sea
        from ..linear.sea_response import side_by_side
        td = {k: v for g, rows in summary["statistics"].items() if isinstance(rows, dict) for k, v in rows.items()}
        summary["statistics_time_vs_frequency_domain"] = side_by_side(scene, td, summary["statistics"]["exposure_s"])
    if plot and result.time.size > 1 and system is not None:     # lines joined at points: shape, paths, tensions
        from ..model.system import topology
        from ..plots.system import plot_system_series
        point_nodes, line_nodes, _ = topology(system)
        with out.writing("timeseries.png") as tmp:
            plot_system_series(result, tmp, units=units, limits=scene.limits,
                               window_start=summary["statistics"]["window_s"][0], towed=scene.top_motion.track is not None,
                               lines={ln.name: (nodes, ln.start, ln.end) for ln, nodes in zip(system.line, line_nodes)},
                               points={p.name: (p.kind, j) for p, j in zip(system.point, point_nodes)})
        if scene.three_d:                            # out of the plane or towed along a track: seen from above
            from ..plots.plan import plot_plan_view
            with out.writing("plan_view.png") as tmp:
                plot_plan_view(result, tmp, units=units, lines=line_nodes,
                               bodies={p.name: f"point.{p.name}." for p in system.point if p.free},
                               held={p.name: f"point.{p.name}." for p in system.point[1:] if p.kind == "prescribed"})
    elif plot and result.time.size > 1:
        from ..plots.time_domain import plot_time_series
        with out.writing("timeseries.png") as tmp:
            plot_time_series(result, tmp, units=units, limits=scene.limits, anchored=scene.anchor is not None,
                             window_start=summary["statistics"]["window_s"][0], towed=scene.top_motion.track is not None)
        if "z_b" in result.labels or any(lb.startswith("z_b_") for lb in result.labels) \
                or scene.top_motion.track is not None:      # out of the plane or towed along a track: seen from above
            from ..plots.plan import plot_plan_view
            with out.writing("plan_view.png") as tmp:
                plot_plan_view(result, tmp, units=units)
    return summary


def summary_lines(summary: dict, units: str = "SI") -> list[str]:
    """The console report of a run's ``summary`` (write_run's dict) in ``units``: the model and why, the integrator
    (or that nothing was stepped), amplitudes, tension extremes, the statistics window, statistics and verdicts."""
    lines = [f"scene: {summary['scene']}"]
    if "model" in summary:
        from ..ladder.auto import describe
        lines.append(describe(summary["model"]))
    st = summary["stats"]
    if st["method"] in ("steady state", "periodic collocation"):     # the steady and frequency rungs: nothing stepped
        lines.append(f"not stepped ({st['method']}, sampled at the output times): {st['wall_s'] * 1e3:.0f} ms "
                     f"(+ {st['build_s'] * 1e3:.0f} ms build)")
    else:
        lines.append(f"integrator {st['method']}: {st.get('nsteps', '-')} steps, "
                     f"{st.get('nfevals', st.get('nresevals', '-'))} rhs evaluations, {st['wall_s'] * 1e3:.0f} ms "
                     f"(+ {st['build_s'] * 1e3:.0f} ms build)"
                     + (f"; step budget {st['max_num_steps']} per output interval" if "max_num_steps" in st else ""))
    from ..units import output_unit
    for unit in ("m", "rad", "N"):
        f, name = output_unit(unit, units)
        for k, v in summary.get(f"amplitudes_{unit}", {}).items():
            lines.append(f"  amplitude {k:14s} {v * f:.6g} {name}")
    fn, name_n = output_unit("N", units)
    bottom = summary.get("tension_bottom_at", "at the body")
    for end, what in (("top", "at the top"), ("bottom", bottom)):   # the same meaning for every model
        lo, hi = summary.get(f"tension_{end}_min_N"), summary.get(f"tension_{end}_max_N")
        if lo is not None and hi is not None:
            lines.append(f"  tension {what} min/max {lo * fn:.4g} / {hi * fn:.4g} {name_n} (over the run)")
    lines.append(f"  time slack {summary['time_slack_s']:.3g} s")
    if "window" in summary:
        w = summary["window"]
        lines.append(f"  statistics window {w['start_s']:.4g} - {w['end_s']:.4g} s ({w['how']})")
    from ..verdict import format_statistics, format_table, steady_shape_lines
    unit = lambda u: output_unit(u, units)     # noqa: E731
    table = format_table(summary["verdict"], unit) if summary.get("verdict") else []
    stats = format_statistics(summary["statistics"], units) if "statistics" in summary else []
    lines += ["  " + line for line in stats + steady_shape_lines(summary, unit) + summary.get("warnings", []) + table]
    return lines


def _run_dale_table(args, out: Path) -> int:
    from ..model import build_model
    from ..outputs import OutputDir
    from ..scene import OMEGA_N_MEASURED, dale_scene
    from ..time_domain.integrators import IntegratorSettings
    from ..time_domain.record import check_scene_run_size
    from ..ladder.auto import windowed
    from ..statistics import half_range
    from ..time_domain.run import Simulator, simulate
    ratios = (0.5, 1.0, 1.5, 2.0)
    shortest = 3 * 2 * math.pi / (min(ratios) * OMEGA_N_MEASURED)     # the amplitudes need 3 periods
    if args.duration is not None and args.duration < shortest:
        from ..errors import ParameterError
        raise ParameterError("--duration", args.duration, f"must be >= {shortest:.4g} s for the Dale table "
                             "(3 periods at omega/omega_n = 0.5)")
    scenes = [dale_scene(omega_ratio=r, duration=args.duration or 150.0) for r in ratios]
    check_scene_run_size(scenes[0])
    outdir = OutputDir(out, "run", {"dale_table": scenes}, overwrite=args.overwrite,
                       owned=RUN_FILES + ("dale_amplitudes.json",))
    print("Dale et al. water-channel model (Wang 1971, Table 1): 9 ft cable, 1 in sphere, circular top motion 5 in p-p")
    print("steady-state amplitudes of the lower body (half peak-to-peak over each run's statistics window: "
          "its second half, or its last 5 periods if they start later)")
    print(f"{'omega/omega_n':>14} {'omega rad/s':>12} {'x_bA ft':>9} {'y_bA ft':>9} {'x_bA m':>9} {'y_bA m':>9} {'ms':>6}")
    rows, ok, sim, summary = [], True, None, {}
    with outdir.start(scene="Dale et al. water-channel model, omega/omega_n = 0.5, 1, 1.5, 2"):
        try:
            for ratio, scene in zip(ratios, scenes):
                if sim is None:      # one model and one set of integrators: only parameter values change
                    num = scene.numerics
                    extra = {} if args.max_steps is None else {"max_num_steps": args.max_steps}
                    sim = Simulator(build_model(scene), scene.output_times, IntegratorSettings(
                        method=args.method or num.integrator, rtol=num.rtol, atol=num.atol, jit=args.jit, **extra))
                tag = f" (omega/omega_n = {ratio:g})"
                if ratio == 1.0:     # the run whose series, summary and plot go to --out
                    r = windowed(scene, _simulate_into(outdir, scene, tag, simulator=sim))
                    summary = write_run(scene, r, outdir, series_on_disk=True)
                    summary["model"] = _dale_model(scene)
                    outdir.manifest.update(summary)
                else:
                    r = windowed(scene, simulate(scene, simulator=sim, progress=_Progress(tag)))
                ok &= r.success
                # the amplitudes over the run's one statistics window, the window of summary.json
                mask = r.window_mask()
                xa, ya = half_range(r["x_b"][mask]), half_range(r["y_b"][mask])
                rows.append({"omega_over_omega_n": ratio, "xbA_ft": xa / U.FT, "ybA_ft": ya / U.FT, "xbA_m": xa, "ybA_m": ya})
                print(f"{ratio:14.2f} {ratio * OMEGA_N_MEASURED:12.3f} {xa / U.FT:9.4f} {ya / U.FT:9.4f} {xa:9.4f} {ya:9.4f} "
                      f"{r.stats['wall_s'] * 1e3:6.0f}")
        finally:                     # the rows computed so far, also when interrupted
            outdir.write_json("dale_amplitudes.json", rows)
        outdir.finish("success" if ok else "failed", **summary)
    if summary.get("model"):
        from ..ladder.auto import describe
        print(describe(summary["model"]))
    print(f"wrote {out}/ (time series, summary.json and plots of the omega = omega_n run; dale_amplitudes.json)")
    return 0 if ok else 1


def _dale_model(scene) -> dict:
    """summary.json's ``model`` of the Dale table: Wang's 2-DOF model on purpose (the table reproduces the
    report's model against the experiment), with the ladder's estimate of its error for this scene and
    what the ladder would run instead (every result says which model ran, why, and its error)."""
    from ..ladder.choice import choose, forced
    from ..ladder.rungs import RungCache
    cache = RungCache()          # one Wang model and describing-function solver for both questions
    wang, auto = forced(scene, "wang", cache=cache), choose(scene, cache=cache)
    d = wang.as_dict()
    d["reason"] = (f"Wang's 2-DOF model, as Wang (1971) Table 2 compares it with the experiment; the model ladder "
                   f"would run {auto.name}" + (f" N = {auto.segments}" if auto.segments > 1 else "")
                   + " for a scene file with model = auto")
    return d
