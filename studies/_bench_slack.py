"""The slack row of ``bench_vs_moordyn`` (300 m / 2 t sphere, 1 m heave at T = 6 s), measured by cycle means.

The slack-and-snap response settles only after ~100-150 s (a period-2 bounce grows, then the body's
mean lifts by ~1.5 m), and the extremes of any 5 settled periods still scatter 3-14 % from cycle to
cycle (the bunched slack part can buckle sideways). So every figure here is the mean over the
forcing cycles of the second half of a 360 s run (:func:`_cycles.cycle_statistics`, maxima refined
between samples), for both codes, and matched accuracy is judged on those means:

- cablesys's own tight run at the same N: classical RK4 (the compiled fixed-step loop) at half its
  largest stable step (the segmented-convergence study: halving the step changes the cycle means by
  < 2e-5, so half the step is converged in time to ~1e-6);
- cablesys's candidates, fastest first: RK4 at its largest stable step (h |lambda|_max = 2.78 at the
  initial state), then at 3/4 of it; CVODES BDF(<= 2) at rtol 1e-3, 1e-4 where the model is compiled
  (N <= COMPILE_MAX_ELEMENTS: in CasADi's VM its Jacobians make it slower than RK4 by far). The
  fastest one whose body amplitudes are within 0.5 % and tension extremes within 1 % of the tight
  run (:func:`cablesys.ladder.metrics.errors` on the cycle means) is timed;
- MoorDyn v2 at its largest stable step, probed over the whole run (a probe inside the smooth start
  sees no snap): the first step, halving, whose run is bounded and whose cycle means agree with the
  half step's within 0.5 % / 1 %.

Both codes are then timed alternately TIMING_ROUNDS more times and the best wall of each is compared
(a shared machine's load drifts within a run: one timing each gave 0.9x or 1.7x at N = 80 depending on
the moment). Steps found by the probes can be kept in ``keep`` (a JSON file): a second run of the benchmark
times MoorDyn at the kept step in the same run as cablesys (the ratio is what counts) without
probing again.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import numpy as np
from _bench_auto import SLACK_NOTE, slack_auto_row
from _cycles import (
    cycle_statistics,
    ladder_statistics,
)
from _moordyn import largest_stable_dt, run_moordyn

from cablesys.ladder import extrapolation as X
from cablesys.ladder import richardson as R
from cablesys.ladder import metrics as M
from cablesys.time_domain.failures import largest_rate, rk4_steps_per_output
from cablesys.time_domain.integrators import COMPILE_MAX_ELEMENTS

BODY_TOL, TENSION_TOL = 0.005, 0.01        # matched accuracy (issue 11)
RK_FRACTIONS = (1.0, 0.75)                 # RK4 candidates: these fractions of the largest stable step
BDF_RTOLS = (1e-3, 1e-4)                   # CVODES BDF(<= 2) candidates (compiled models only)


def window_start(scene, period: float) -> float:
    """The last cycle start at or before half the run, cycles counted from the end of the ramp (the
    ramp's end in a run shorter than twice the ramp)."""
    ramp, dur = scene.top_motion.effective_ramp_s, scene.numerics.duration
    return ramp + max(0, math.floor((dur / 2 - ramp) / period)) * period


def cablesys_cycles(result, period: float, t0: float) -> dict:
    """Cycle means of a cablesys run over [t0, end] (with per-element strain and law slack)."""
    return cycle_statistics(result.time, result.data, period, t0, strain=result.profiles["element_strain"],
                            law_slack=result.profiles["element_slack"])


def moordyn_cycles(run: dict, period: float, t0: float) -> dict:
    """Cycle means of a MoorDyn run (:func:`_moordyn.run_moordyn`) over [t0, end]."""
    return cycle_statistics(run["time"], run, period, t0, strain=run["element_strain"])


def as_metrics(c: dict) -> dict:
    """Cycle means in the keys of :func:`cablesys.ladder.metrics.statistics` (amplitudes, tension extremes)."""
    return {"x_b_amplitude": c["x_amp"], "y_b_amplitude": c["y_amp"], "tension_top_max": c["top_max"],
            "tension_top_min": c["top_min"], "tension_bottom_max": c["bottom_max"], "tension_bottom_min": c["bottom_min"]}


def errors(a: dict, b: dict) -> dict:
    """Relative differences of cycle means a against b: {"body", "tension"} as the taut rows
    (:func:`cablesys.ladder.metrics.errors`: body amplitudes over the largest amplitude, tension
    extremes over the largest maximum), plus each figure's own relative difference."""
    e = M.errors(as_metrics(a), as_metrics(b))
    keys = ("y_amp", "x_amp", "y_min", "y_max", "top_max", "top_min", "bottom_max", "bottom_min", "slack_bottom", "slack_top")
    e["each"] = {k: (a[k] - b[k]) / abs(b[k]) if abs(b[k]) > 1e-12 else a[k] - b[k] for k in keys if k in a and k in b}
    return e


class _Run:
    """A MoorDyn run (:func:`_moordyn.run_moordyn`) read as a cablesys result by label and time."""
    labels = ("x_b", "y_b", "tension_top", "tension_bottom")

    def __init__(self, run: dict):
        self.time, self._run = run["time"], run

    def __getitem__(self, key):
        return self._run[key]


def _both(result, period: float, t0: float) -> dict:
    """A run's statistics in auto's definition (last 5 periods, maxima refined:
    :func:`cablesys.ladder.richardson.statistics`) and its cycle means over [t0, end] in the same names."""
    return {"stats": R.statistics(result, period), "cycle_means": ladder_statistics(result, period, t0)}


def _tight_run(sc, prepared):
    """(result, RK4 steps per output at the stable step, lambda_max, wall) of cablesys's tight run at the
    scene's N: RK4 at half its largest stable step, run once (a reference: not timed against MoorDyn)."""
    spo, lam = _stable_spo(sc, prepared)
    t = time.perf_counter()
    sim, p, x0, _ = prepared(sc.with_numerics(steps_per_output=2 * spo), "rk", 1e-6, 1e-9)
    tight = sim.run(p, x0)
    return tight, spo, lam, time.perf_counter() - t


def reference(scene, tights: dict, ns) -> dict:
    """The case's converged reference: the first-order Richardson limit of cablesys's tight runs at the
    largest N and half of it (the segmented cable converges at first order on this scene: observed
    0.98-1.03, :mod:`cablesys.ladder.extrapolation`), minima at least the tension floor, in auto's
    statistics (``stats``) and in cycle means (``cycle_means``); with a third N (a quarter) the observed
    order and the limit's own uncertainty (the previous pair's limit against it, / 3 for a remainder ~ N^-2);
    ``error_at_n``: each tight run's error against the limit."""
    hi = max(ns)
    lo = hi // 2
    floor = max(s.cable.tension_floor for s in scene.sections)
    out = {"kind": "richardson", "segments": [lo, hi], "order_assumed": 1.0, "integrator": "rk, half the stable step"}
    for name in ("stats", "cycle_means"):
        lim = R.limits(tights[lo][name], tights[hi][name], order=1.0)
        lim.update({k: max(v, floor) for k, v in lim.items() if k.endswith("_min")})
        out[name] = lim
        # each tight run's own error against the limit (as MoorDyn's against its own: _bench_auto.moordyn_for)
        out.setdefault("error_at_n", {})[name] = {n: M.errors(t[name], lim) for n, t in sorted(tights.items())}
        if lo // 2 in tights:
            prev = R.limits(tights[lo // 2][name], tights[lo][name], order=1.0)
            out.setdefault("observed_order", {})[name] = R.observed_orders(tights[lo // 2][name], tights[lo][name],
                                                                        tights[hi][name])
            out.setdefault("uncertainty", {})[name] = {k: v / 3.0 for k, v in M.errors(prev, lim).items()}
    return out


def _auto(row, scene, period, t0, ns, tights, mds, prepared, compiled_ctx, segments):
    """Model auto's row of the slack case (:func:`_bench_auto.slack_auto_row`) and the case's converged
    reference (:func:`reference`; the tight runs it needs besides the case's N are run here, compiled)."""
    hi = max(ns)
    for n in (hi // 2, hi // 4):
        if n >= 2 and n not in tights:
            with compiled_ctx(True):
                tight = _tight_run(segments(scene, n), prepared)[0]
            if tight.success:
                tights[n] = _both(tight, period, t0)
    if hi // 2 not in tights or hi not in tights:
        row["auto"] = {"failed": "no converged reference: a tight run failed"}
        return
    ref = reference(scene, tights, ns)
    row["reference"] = ref
    row["auto"] = slack_auto_row(scene, period, ref, mds, cycle_means=lambda r: ladder_statistics(r, period, t0))
    for key in ("speedup", "speedup_run_only", "choose_s", "error"):
        row[f"auto_{key}"] = row["auto"].get(key)
    row["auto_moordyn_equal_accuracy"] = row["auto"].get("moordyn_equal_accuracy")
    row["auto_note"] = SLACK_NOTE


def _strip(c: dict) -> dict:
    return {k: v for k, v in c.items() if k != "slack_per_element"}


def _stable_spo(sc, timed_run_prepared) -> tuple[int, float]:
    """RK4 steps per output interval at the largest stable step (h |lambda|_max = RK4_LIMIT at the
    initial state, the largest eigenvalue of the ODE Jacobian) and lambda_max."""
    sim, p, x0, _ = timed_run_prepared(sc, "rk", 1e-6, 1e-9)
    lam = largest_rate(sim.model, x0, sc.output_times[0], p)
    return rk4_steps_per_output(lam, sc.numerics.output_step), lam


def _moordyn_step(sc, n, period, t0, keep: Path | None, key: str) -> tuple[float, str]:
    """MoorDyn's largest stable step (probed over the whole run, cycle means agreeing with the half
    step's), or the step kept in ``keep`` by an earlier run of the same case."""
    kept = json.loads(keep.read_text()) if keep and keep.is_file() else {}
    if key in kept:
        return float(kept[key]), "kept from an earlier probe"

    def agree(a, b):
        if not (a["stable"] and b["stable"]):
            return False
        e = errors(moordyn_cycles(a, period, t0), moordyn_cycles(b, period, t0))
        return e["body"] <= BODY_TOL and e["tension"] <= TENSION_TOL
    dt = largest_stable_dt(sc, n, agree=agree)
    if keep:
        keep.parent.mkdir(parents=True, exist_ok=True)
        keep.write_text(json.dumps({**kept, key: dt}, indent=1))
    return dt, "probed in this run"


def _us_per_rhs(F, x0, pp, n_sub: int, intervals: int) -> float:
    """Microseconds per right-hand side of an RK4 interval function ``F(x, s0, ds, p)``, evaluated as
    the simulator does (a ``mapaccum`` over ``intervals`` output intervals in one call: no Python
    call per interval, whose ~30 us would be a large part of a 2-step interval); best of 3."""
    over = F.mapaccum("intervals", intervals, [0], [0])
    args = (x0, np.arange(intervals, dtype=float)[None, :], np.ones((1, intervals)), np.tile(pp[:, None], (1, intervals)))
    over(*args)
    best = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        over(*args)
        best = min(best, time.perf_counter() - t0)
    return 1e6 * best / (4 * n_sub * intervals)


def rhs_profile(sc, n_sub: int, prepared, flags=()) -> dict:
    """Where an RK4 run's time goes: microseconds per right-hand side of the RK4 interval (``n_sub``
    steps of one output interval) with the element kernel (the model's ``loop_ode``) and with the
    element-by-element SX ``ode``, compiled with the library's default flags (and the build time of
    that library, compile included when not cached), with each of ``flags`` (``CABLESYS_CFLAGS``,
    e.g. "-O3"), and in CasADi's VM (the SX ode: the VM loop never steps the kernel, whose map
    calls cost more there, 72 vs 53 us per right-hand side at N = 80)."""
    import dataclasses

    from cablesys.time_domain.integrators import rk4_interval
    sim, p, x0, _ = prepared(sc, "rk", 1e-6, 1e-9)
    model = sim.model
    pp = np.concatenate([p, [0.0, sc.numerics.output_step]])
    out = {"steps_per_output": n_sub}
    intervals = 256                      # the simulator's first chunk (Simulator.CHUNKS)
    old = os.environ.get("CABLESYS_CFLAGS")
    try:
        for flag in (None, "vm", *flags):
            if flag not in (None, "vm"):
                os.environ["CABLESYS_CFLAGS"] = flag
            for name in (("sx",) if flag == "vm" else ("kernel", "sx")):     # the VM always steps the SX ode
                # a fresh copy: its own cache of derived functions (a library per flag)
                m = dataclasses.replace(model, kernel_ode=model.kernel_ode if name == "kernel" else None)
                t0 = time.perf_counter()
                comp = rk4_interval(m, n_sub, flag != "vm")
                key = f"{name}_{'compiled' if flag is None else flag}"
                out[f"{key}_build_s"] = time.perf_counter() - t0
                out[f"{key}_cached"] = comp.cached
                out[f"{key}_us_per_rhs"] = _us_per_rhs(comp.functions["cablesys_rk4_interval"], x0, pp, n_sub,
                                                       16 if flag == "vm" else intervals)
    finally:
        if old is None:
            os.environ.pop("CABLESYS_CFLAGS", None)
        else:
            os.environ["CABLESYS_CFLAGS"] = old
    return out


TIMING_ROUNDS = 2          # further timings of each code, alternating (the machine's load drifts during a run)


def _interleaved(sc, n, dt, md, best, prepared):
    """Walls of MoorDyn and of cablesys's chosen setting (its simulator built once), timed alternately
    TIMING_ROUNDS more times after the first timings: ([MoorDyn walls], [MoorDyn step walls],
    [cablesys walls]). A shared machine's load changes within minutes; the best of each (the least
    disturbed) is the fair comparison, the lists show the spread."""
    _, wall, how = best
    rtol = how["rtol"] or 1e-6
    cand = sc.with_numerics(steps_per_output=how["steps_per_output"]) if how["steps_per_output"] else sc
    sim, p, x0, _ = prepared(cand, how["method"], rtol, rtol * 1e-3)
    sim.run(p, x0)
    md_walls, md_steps, cs_walls = [md["wall_s"]], [md["step_wall_s"]], [wall]
    for _ in range(TIMING_ROUNDS):
        again = run_moordyn(sc, n, dt)
        md_walls.append(again["wall_s"])
        md_steps.append(again["step_wall_s"])
        t0 = time.perf_counter()
        sim.run(p, x0)
        cs_walls.append(time.perf_counter() - t0)
    return md_walls, md_steps, cs_walls


def bench_slack_case(name, scene, period, ns, *, timed_run, prepared, compiled_ctx, segments, keep: Path | None = None,
                     flags=(), auto=True):
    """The slack row: per N, MoorDyn and cablesys timed in this run, both measured by cycle means.

    Parameters
    ----------
    name, scene, period, ns
        The case (scene with its ramp and duration), forcing period (s), element counts.
    timed_run, prepared, compiled_ctx, segments
        ``bench_vs_moordyn``'s timed cablesys run, its simulator setup, its compiled-or-VM context and
        its ``segments(scene, n)``.
    keep : Path, optional
        JSON file of MoorDyn steps found by earlier probes (read, and written when a probe runs).
    flags : sequence of str, optional
        Compiler flags to profile the RK4 loop with too (:func:`rhs_profile`).
    auto : bool, optional
        Add model auto's row (:func:`_auto`: ``reference``, ``auto``, ``auto_speedup``, ``auto_error``).

    Returns
    -------
    dict
        The case row: ``by_n`` entries with ``cablesys_s_per_s``, ``moordyn_s_per_s``, ``speedup``, the
        settings and their errors against the tight run, both codes' cycle means, their differences,
        and per-segment slack fractions.
    """
    dur = scene.numerics.duration
    t0 = window_start(scene, period)
    row = {"case": name, "scene": scene.name, "duration_s": dur, "period_s": period, "taut": False,
           "window_s": [t0, dur], "measured_by": "cycle means over the window (_cycles.cycle_statistics)", "by_n": []}
    tights, mds = {}, {}          # {N: both statistics} of cablesys's tight runs and MoorDyn's runs (auto's row)
    for n in ns:
        sc = segments(scene, n)
        dt, how_dt = _moordyn_step(sc, n, period, t0, keep, f"{name}:{n}:{dur:g}:{sc.numerics.output_step:g}")
        md = run_moordyn(sc, n, dt)
        md_c = moordyn_cycles(md, period, t0) if md["stable"] else None
        if md_c:
            mds[n] = {**_both(_Run(md), period, t0), "wall_s": md["wall_s"]}
        compiled = True                       # RK4's loop is the RHS alone (no Jacobian): compiled at any N
        entry = {"segments": n, "moordyn_dt_s": dt, "moordyn_dt_from": how_dt, "moordyn_s_per_s": md["wall_s"] / dur,
                 "moordyn_step_s_per_s": md["step_wall_s"] / dur, "moordyn_stable": md["stable"],
                 "moordyn_steps_per_s": dur / dt / md["step_wall_s"], "moordyn_us_per_step": 1e6 * md["step_wall_s"] * dt / dur,
                 "moordyn_cycles": _strip(md_c) if md_c else None,
                 "moordyn_slack_fraction_per_segment": md_c["slack_per_element"] if md_c else None}
        with compiled_ctx(compiled):
            tight, spo, lam, t_tight = _tight_run(sc, prepared)
            if not tight.success:
                entry.update(note=f"cablesys's tight run failed: {tight.message}")
                row["by_n"].append(entry)
                continue
            ref = cablesys_cycles(tight, period, t0)
            tights[n] = _both(tight, period, t0)
            entry.update(cablesys_tight={"method": "rk", "steps_per_output": 2 * spo, "step_s": sc.numerics.output_step / (2 * spo),
                                         "lambda_max": lam, "wall_s": t_tight},
                         cablesys_cycles=_strip(ref), cablesys_slack_fraction_per_element=ref["slack_per_element"])
            tried, best, rk_matched = [], None, False
            candidates = [("rk", math.ceil(spo / f), None) for f in RK_FRACTIONS]
            if n <= COMPILE_MAX_ELEMENTS:
                candidates += [("cvodes-bdf2", None, rtol) for rtol in BDF_RTOLS]
            for meth, n_sub, rtol in candidates:
                if meth == "rk" and rk_matched:          # a smaller step is slower
                    continue
                cand = sc if n_sub is None else sc.with_numerics(steps_per_output=n_sub)
                try:
                    res, wall, _, setup = timed_run(cand, meth, rtol or 1e-6, (rtol or 1e-6) * 1e-3)
                except Exception as err:  # noqa: BLE001 - a failing setting is a result
                    tried.append({"method": meth, "steps_per_output": n_sub, "rtol": rtol, "failed": f"{type(err).__name__}: {err}"})
                    continue
                # setup_s: model, integrators (compiled code: built when the cache is cold) and statics
                t = {"method": meth, "steps_per_output": n_sub, "rtol": rtol, "s_per_s": wall / dur, "success": bool(res.success),
                     "setup_s": setup}
                if res.success:
                    t["error_vs_own_tight"] = errors(cablesys_cycles(res, period, t0), ref)
                    t["matched"] = t["error_vs_own_tight"]["body"] <= BODY_TOL and t["error_vs_own_tight"]["tension"] <= TENSION_TOL
                    if t["matched"] and (best is None or wall < best[1]):
                        best = (res, wall, t)
                tried.append(t)
                rk_matched = rk_matched or (meth == "rk" and bool(t.get("matched")))
            if best:
                best = (*best, _interleaved(sc, n, dt, md, best, prepared))
            if best and best[2]["method"] == "rk":
                entry["cablesys_rhs_profile"] = rhs_profile(sc.with_numerics(steps_per_output=best[2]["steps_per_output"]),
                                                            best[2]["steps_per_output"], prepared, flags)
        entry["cablesys_tried"] = tried
        entry["cablesys_vs_moordyn"] = errors(ref, md_c) if md_c else None
        if best:
            res, _, how, (md_walls, md_steps, cs_walls) = best
            wall, md_wall = min(cs_walls), min(md_walls)        # best of the interleaved rounds: load drifts
            entry.update(moordyn_walls_s=md_walls, cablesys_walls_s=cs_walls, moordyn_s_per_s=md_wall / dur,
                         moordyn_step_s_per_s=min(md_steps) / dur, moordyn_steps_per_s=dur / dt / min(md_steps),
                         moordyn_us_per_step=1e6 * min(md_steps) * dt / dur)
            if how["method"] == "rk":
                steps = dur / sc.numerics.output_step * how["steps_per_output"]
                entry.update(cablesys_steps_per_s=steps / wall, cablesys_us_per_step=1e6 * wall / steps)
            entry.update(cablesys_s_per_s=wall / dur, speedup=md_wall / wall, cablesys_settings=how,
                         cablesys_compiled=compiled, cablesys_setup_s=how["setup_s"],
                         cablesys_total_s_per_s=(how["setup_s"] + wall) / dur,
                         speedup_total=md_wall / (how["setup_s"] + wall))
        else:
            entry.update(cablesys_s_per_s=None, speedup=None, note="no setting met matched accuracy on the cycle means")
        row["by_n"].append(entry)
        if n in mds and "moordyn_walls_s" in entry:           # the best of the interleaved timings
            mds[n]["wall_s"] = min(entry["moordyn_walls_s"])
    if auto:
        _auto(row, scene, period, t0, ns, tights, mds, prepared, compiled_ctx, segments)
    return row


# -- the plan cases (issue 28): light_lift and harsh_sea, irregular seas, auto's whole plan timed --------------------

PLAN_NS = (20, 40)               # MoorDyn's own convergence: N = 20 against N = 40
# MoorDyn's step search on a probe: the smooth start and four peak periods of the sea after it (the snaps of the light
# lift begin there), each trial step against its half on the probe's statistics (errors_md), then one geometric
# bisection round between the accepted step and the rejected one above it; the whole run at the step found (halved
# while that run is not stable). A probe over the whole 600 s at the light lift's ~1e-4 s steps did not finish in 40 min.
PROBE_AFTER_RAMP_S, PROBE_REFINE = 36.0, 1
HARSH_SEA = {"hs": 6.0, "tp": 9.0}   # the ROV lift in a harsh sea: Hs 6 m, Tp 9 s (DNV-RP-C205 Table 3-1: rough-very rough)


def plan_scene(name: str, duration: float | None = None):
    """The scene of plan case ``name``: ``light_lift`` (the packaged example ``light-lift``) or ``harsh_sea`` (the
    packaged ROV lift in :data:`HARSH_SEA`), both without the current (the MoorDyn peer, ``_moordyn``, has none: the
    same inputs on both sides), ``duration`` s (default the scene's 600 s)."""
    import tomllib

    from cablesys.examples import example_text
    from cablesys.scene import scene_from_dict
    text = example_text("light-lift" if name == "light_lift" else "rov-lift")
    subs = [("current_speeds = [1.0, 0.6, 0.2]", "current_speeds = [0.0, 0.0, 0.0]")]
    if name == "harsh_sea":
        subs += [("hs = 2.5 ", f"hs = {HARSH_SEA['hs']:g} "), ("tp = 10.0 ", f"tp = {HARSH_SEA['tp']:g} "),
                 ('Hs 2.5 m Tp 10 s"', f'Hs {HARSH_SEA["hs"]:g} m Tp {HARSH_SEA["tp"]:g} s (harsh sea)"')]
    for old, new in subs:
        if old not in text:
            raise ValueError(f"plan_scene({name!r}): the packaged example no longer holds {old!r}")
        text = text.replace(old, new)
    sc = scene_from_dict(tomllib.loads(text))
    return sc if duration is None else sc.with_numerics(duration=duration)


def _plan_runs(result) -> list:
    """Each run of auto's plan: N, method, steps, wall and per-step cost; on a slack scene the extrapolation's
    (``model.extrapolated.plan.runs``), on a taut one the candidate and check runs of ``ladder_timing.runs``
    (:func:`cablesys.ladder.auto.log_run`, with the rung and rtol)."""
    block = (result.stats.get("model") or {}).get("extrapolated") or {}
    keys = ("segments", "candidate", "method", "stages", "steps", "step_us", "predicted_s", "wall_s", "cpu_s",
            "wall_per_step_us", "status")
    runs = [{k: r.get(k) for k in keys} for r in (block.get("plan") or {}).get("runs", [])]
    if runs:
        return runs
    taut = ("rung", "segments", "candidate", "method", "rtol", "steps", "wall_s", "cpu_s", "wall_per_step_us",
            "cpu_per_step_us")
    return [{**{k: r.get(k) for k in taut}, "status": "success" if r.get("success") else "failed"}
            for r in (result.stats.get("ladder_timing") or {}).get("runs", [])]


def _auto_timed(scene, tolerance: float | None, period) -> dict:
    """Auto as a user runs it (``cablesys.simulate``, model auto, compiled), its second call on one cache timed whole
    (the first builds and compiles); its stated error, model, N and the runs of its plan, with the load average."""
    import warnings

    from cablesys.ladder import RungCache
    from cablesys.ladder import simulate as ladder_simulate
    cache = RungCache()
    kw = {} if tolerance is None else {"tolerance": tolerance}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        ladder_simulate(scene, cache=cache, **kw)
        first = time.perf_counter() - t0
        load = os.getloadavg()[0]
        t0, c0 = time.perf_counter(), time.process_time()
        r = ladder_simulate(scene, cache=cache, **kw)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    m = r.stats.get("model") or {}
    return {"tolerance": tolerance, "wall_s": wall, "cpu_s": cpu, "first_call_s": first, "load_1min": load,
            "success": bool(r.success),
            "model": m.get("name"), "segments": m.get("segments"), "estimated_error": m.get("estimated_error"),
            "plan_runs": _plan_runs(r), "statistics": reported_statistics(r, period) if r.success else None}


def _segmented_timed(scene, n: int) -> dict:
    """The segmented cable at ``n`` elements as the extrapolation steps it (:func:`cablesys.ladder.extrapolation.run`:
    RKC or RK4 at its stable step, compiled) on the scene's output grid, its second run timed (the first compiles)."""
    import warnings

    from cablesys.ladder import RungCache
    from cablesys.ladder.rungs import rung_scene
    from cablesys.ladder.run_settings import start
    cache = RungCache()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        X.run(scene, n, cache)
        load = os.getloadavg()[0]
        t0, c0 = time.perf_counter(), time.process_time()
        r = X.run(scene, n, cache)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        model = cache.model(scene, "segmented", n)
        s = X.settings(rung_scene(scene, "segmented", n), model, x0=start(rung_scene(scene, "segmented", n), model, cache))
    steps = s.steps_per_output * (len(scene.output_times) - 1)
    return {"segments": n, "wall_s": wall, "cpu_s": cpu, "load_1min": load, "method": s.method, "stages": s.stages,
            "steps": steps, "success": bool(r.success), "wall_per_step_us": 1e6 * wall / steps,
            "cpu_per_step_us": 1e6 * cpu / steps,
            "statistics": M.statistics(r, M.forcing_period(scene), scene.top_motion.effective_ramp_s)}


def reported_statistics(result, period) -> dict:
    """auto's reported statistics (extrapolated on a slack scene, else its run's: :mod:`_bench_auto`)."""
    from _bench_auto import reported_statistics as rs
    return rs(result, period)


def bench_plan_case(name: str, scene, *, quick: bool = False, ns=PLAN_NS, moordyn: bool = True, bdf_equal_n=None) -> dict:
    """One plan case: MoorDyn at ``ns`` (its largest stable step each, searched on a probe: PROBE_AFTER_RAMP_S) and its own
    convergence (its statistics at the smaller N against the larger, :func:`cablesys.ladder.metrics.errors`); cablesys
    auto at its default tolerance and at the peer's convergence (body; tension twice it, as the ladder's tolerance
    reads); ``auto_speedup`` = MoorDyn's wall at the larger N / auto's (default tolerance), ``auto_speedup_matched`` the
    same at the peer's convergence, given MoorDyn's wall at the larger N as its time budget (``numerics.time_budget_s``:
    auto plans a slack scene's runs to fit it and states the error it reaches; a taut candidate predicted past it is
    refused at once, ``auto_matched["refused"]`` says why and ``auto_speedup_matched`` is None);
    ``speedup`` = MoorDyn's wall / the segmented cable's at equal N (the larger): as the extrapolation steps it (RK4 or
    RKC at its stable step), and BDF(<= 2) at the loosest rtol that meets matched accuracy against its own tight run
    (``bdf_equal_n(scene, n) -> dict`` of the main script: ``segmented_equal_n_bdf``), the faster of the two; on a slack
    scene the BDF run counts only where it is also within matched accuracy of the extrapolation's RK run at that N
    (``error_vs_rk``: an independent route through the snaps). Every
    wall with the machine's 1-minute load; the ratios are of walls measured in this run. ``moordyn=False`` (quick
    mode, tests): cablesys only, no ratios."""
    period, ramp = M.forcing_period(scene), scene.top_motion.effective_ramp_s
    dur = scene.numerics.duration
    row = {"case": name, "scene": scene.name, "duration_s": dur, "quick": quick, "segments": list(ns),
           "note": "no current on either side (the MoorDyn peer has none); times are wall seconds under the stated "
                   "1-minute load average of a shared 2-core machine: compare the ratios, measured in one run"}
    md = {}
    if moordyn:
        for n in ns:
            sc = scene.replace_section(0, cable={"segments": n})
            trials, t0 = [], time.perf_counter()
            probe = min(dur, ramp + PROBE_AFTER_RAMP_S)
            dt = largest_stable_dt(sc, n, probe_s=probe, agree=lambda a, b: errors_md(a, b, period, ramp),
                                   refine=PROBE_REFINE, trials=trials)
            search_s = time.perf_counter() - t0
            while True:        # the probe's step over the whole run; halved if the whole run is not stable
                load, c0 = os.getloadavg()[0], time.process_time()
                r = run_moordyn(sc, n, dt)
                if r["stable"] or dt / 2 < 1e-7:
                    break
                trials.append({"dt_s": dt, "stable": False, "agrees": None, "probe_s": dur, "wall_s": r["wall_s"]})
                dt /= 2
            md[n] = {"dt_s": dt, "wall_s": r["wall_s"], "cpu_s": time.process_time() - c0, "s_per_s": r["wall_s"] / dur,
                     "load_1min": load,
                     "stable": r["stable"], "steps": int(round(dur / dt)),
                     "wall_per_step_us": 1e6 * r["wall_s"] / max(1, round(dur / dt)), "stats": _md_stats(r, period, ramp),
                     "step_search": {"probe_s": probe, "refine_rounds": PROBE_REFINE, "wall_s": search_s,
                                     "trials": trials}}
        lo, hi = ns
        conv = M.errors(md[lo]["stats"], md[hi]["stats"])
        row["moordyn"] = {str(n): v for n, v in md.items()}
        row["moordyn_convergence"] = conv           # |f(N/2) - f(N)|: the peer's own error estimate at its smaller N
    row["auto_default"] = _auto_timed(scene, None, period)
    if moordyn:
        tol = max(row["moordyn_convergence"]["body"], 1e-4)
        budget = md[max(ns)]["wall_s"]
        try:
            row["auto_matched"] = dict(_auto_timed(scene.with_numerics(time_budget_s=budget), tol, period),
                                       time_budget_s=budget)
        except X.PlanRefused as err:   # the peer's accuracy does not fit in the peer's time: auto says so at once
            row["auto_matched"] = {"tolerance": tol, "time_budget_s": budget, "wall_s": None, "refused": str(err)}
    row["segmented_equal_n"] = _segmented_timed(scene, max(ns))
    fastest = row["segmented_equal_n"]
    if bdf_equal_n is not None:
        bdf = row["segmented_equal_n_bdf"] = bdf_equal_n(scene, max(ns))
        counts = bool(bdf.get("wall_s"))
        if counts and bdf.get("statistics") and fastest.get("statistics"):
            bdf["error_vs_rk"] = M.errors(bdf["statistics"], fastest["statistics"])
            bdf["error_vs_rk_per_quantity"] = M.quantity_errors(bdf["statistics"], fastest["statistics"])
            counts = bdf["error_vs_rk"]["body"] <= MATCHED["body"] and bdf["error_vs_rk"]["tension"] <= MATCHED["tension"]
        if counts and bdf["wall_s"] < fastest["wall_s"]:
            fastest = bdf
    if moordyn:
        big, big_cpu = md[max(ns)]["wall_s"], md[max(ns)]["cpu_s"]
        row["auto_speedup"] = big / row["auto_default"]["wall_s"]
        matched = row["auto_matched"].get("wall_s")
        row["auto_speedup_matched"] = big / matched if matched else None
        row["speedup"] = big / fastest["wall_s"]
        row["speedup_of"] = "segmented_equal_n_bdf" if fastest is not row["segmented_equal_n"] else "segmented_equal_n"
        # the same ratios of process CPU time: on a loaded machine the walls also count the other processes' share
        row["auto_speedup_cpu"] = big_cpu / row["auto_default"]["cpu_s"]
        row["auto_speedup_matched_cpu"] = big_cpu / row["auto_matched"]["cpu_s"] if matched else None
        row["speedup_cpu"] = big_cpu / fastest["cpu_s"] if fastest.get("cpu_s") else None
    return row


MATCHED = {"body": 0.005, "tension": 0.01}   # matched accuracy: the main script's _matched (body amplitudes, tension extremes)


def _md_stats(r: dict, period, ramp_s: float = 0.0) -> dict:
    """MoorDyn's run in the ladder's statistics (:func:`cablesys.ladder.metrics.statistics`, over its window after
    the smooth start ``ramp_s``, s)."""
    class _R:
        time = r["time"]
        labels = ("x_b", "y_b", "tension_top", "tension_bottom")
        profiles: dict = {}

        def __getitem__(self, k):
            return r[k]
    return M.statistics(_R(), period, ramp_s)


def errors_md(a: dict, b: dict, period, ramp_s: float) -> bool:
    """MoorDyn's step probe on an irregular sea: statistics of the runs at a step and half of it within 0.5 % (body)
    and 1 % (tension), as ``bench_vs_moordyn``'s slack probe."""
    e = M.errors(_md_stats(a, period, ramp_s), _md_stats(b, period, ramp_s))
    return e["body"] <= 0.005 and e["tension"] <= 0.01
