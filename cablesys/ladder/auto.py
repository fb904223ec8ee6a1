"""``simulate(scene)``: run the rung the scene needs, check it afterwards, say which and why.

The choice (:func:`~cablesys.ladder.choice.choose`) is checked a posteriori:
- quasi-static: the stretch must stay taut (a quasi-static stretch cannot go slack); if the
  tension falls to the floor, the run is rejected and Wang's model (or the segmented cable) runs;
- wang: a run that goes slack is outside the straight cable's validity (one stretch makes the whole
  cable slack at once): rejected for the segmented cable;
- quasi-static segmented (N elements whose stretches follow the tension): rejected like the straight
  quasi-static rung when any element's tension reaches the floor; its N is checked as the segmented one's;
- segmented with N: N is chosen for SAFETY x the tolerance (:func:`~.choice.segments_for`); only
  when the estimate at N is not that far within the tolerance (N capped, or forced by the user) does
  a second run with N/2 give the Richardson estimate |y_N - y_N/2| / (2^p - 1), N doubling while it
  exceeds the tolerance (a second run costs as much as the first: it is not spent on a sure case); with an adaptive
  integrator the N / 2 run steps at a tenth of the candidate's rtol and the N that passes runs again at it, that run
  kept with its integration error in the stated one (:mod:`.checks`); from N = 8 on a third run at N / 4 tells
  whether the pair is in the asymptotic range (each quantity's observed order), and in an irregular sea the
  estimate is the whole difference (:func:`.checks.richardson_triple`);
- steady (a towing ship's steady turn or straight tow, :mod:`.steady_tow`): the steady state's stability, the eigenvalues
  of its linearization in the frame of the tow; one that does not decay sends auto to the node model's stepped run at
  the same N (:func:`steady_judged`); N is checked as the segmented one's, against steady states at N / 2 and N / 4,
  with no integration part (nothing is stepped);
- segmented under predicted partial slack (first order in N): RK4 runs at N, N/2, N/4 and the statistics
  are extrapolated (:mod:`.extrapolation`), N doubling while the runs are not asymptotic or miss the
  tolerance; ``estimated_error`` is then the extrapolated statistics' (``extrapolated`` holds them) and
  ``estimated_error_time_series`` the N run's own.
The result's ``stats["model"]`` holds ``{name, segments, reason, estimated_error}``, and
``stats["ladder_timing"]`` the wall time of choosing, building, the run and its checks.

Speed: models and simulators are built once per call, or once for many calls through a
:class:`~cablesys.ladder.rungs.RungCache`; without a method or tolerances from the caller or the
scene, the rung runs with :func:`.run_settings.integrator_settings` (BDF of order <= 2, rtol a hundredth of the
body tolerance, compiled C up to COMPILE_MAX_ELEMENTS elements; the quasi-static rungs by the compiled
explicit rk23 pair where its stiffness guard, :mod:`.stiffness`, accepts them, at an rtol also well below
their stated error).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
import warnings

import numpy as np

from ..errors import NumericalWarning, ParameterError, SolverError
from ..model import CableModel
from ..scene import Scene
from . import estimate as est
from . import checks, extrapolation, landed, metrics, plan_cost, static_check
from .choice import (
    CHECK_ACCEPT,
    EXPLICIT_COST_MAX_ELEMENTS,
    MAX_SEGMENTS,
    SAFETY,
    SLACK_MAX_SEGMENTS,
    Choice,
    check_scene,
    checkable,
    choose,
    forced,
    model_operations,
    quasistatic_max_segments,
    tolerances,
)
from .run_settings import (  # noqa: F401 - re-exported: the ladder's run settings, as before the split
    AUTO_METHOD,
    AUTO_RTOL,
    EXPLICIT_MAX_ELEMENTS,
    QUASI_STATIC_FALLBACK,
    QUASI_STATIC_METHOD,
    STATED_ROOM,
    integrator_settings,
    rung_settings,
    start,
)
from .hooks import checking, hooks
from .steady_tow import describe_stability, steady_run
from .rung.base import NOT_ESTIMATED, scene_segments
from .rung.segmented import ENDS_SEGMENTS  # noqa: F401 - re-exported: the first N of an anchored line
from .rungs import BUILTIN, RUNGS, RungCache, check_rung, get_rung, ladder_rungs, rung_scene, takes_elements, validity

log = logging.getLogger(__name__)

def run_rung(scene: Scene, name: str, segments: int = 1, *, cache: RungCache | None = None, **kw):
    """One time-domain run of rung ``name``.

    Parameters
    ----------
    scene : Scene
        The scene.
    name : str
        A rung; ``frequency`` gives the periodic orbit (Fourier collocation) sampled at the output times, ``steady``
        the steady tow or turn carried to them (:func:`.steady_tow.steady_run`).
    segments : int, optional
        Elements per section of the segmented rung.
    cache : RungCache, optional
        Built models to reuse (default: a new one).
    **kw
        Passed to :func:`cablesys.time_domain.simulate`.

    Returns
    -------
    TimeResult
        The run (``success`` False with the reason when the integrator failed).
    """
    from ..time_domain import simulate
    cache = cache if cache is not None else RungCache()
    if name == "frequency":
        return _periodic_run(scene, cache)
    if name == "steady":
        return _steady_run(scene, segments, cache, kw.get("times"))
    sc = rung_scene(scene, name, segments)
    return simulate(sc, model=cache.model(scene, name, segments), **kw)


def describe_run(choice: Choice) -> str:
    """A run's name for progress lines: the rung and its N."""
    return choice.name + (f" N = {choice.segments}" if choice.segments > 1 else "")


def _run(scene: Scene, choice: Choice, tol, cache: RungCache, kw: dict, candidate: bool = True):
    """The run of ``choice`` with the ladder's integrator settings and the cache's simulator (``candidate``: its result
    may be returned, so it gets the caller's ``on_block`` and ``progress``; a check run does not)."""
    from ..time_domain import simulate
    if choice.name == "frequency":
        return _periodic_run(scene, cache)
    if choice.name == "steady":
        t0, c0 = time.perf_counter(), time.process_time()
        result = _steady_run(scene, choice.segments, cache, kw.get("times"))
        log_steady(kw, choice, candidate, result, time.perf_counter() - t0, time.process_time() - c0)
        return result
    sc = rung_scene(scene, choice.name, choice.segments)
    model = cache.model(scene, choice.name, choice.segments)
    settings, x0 = rung_settings(sc, tol, choice, model, cache=cache, x0=kw.get("x0"), method=kw.get("method"),
                                 rtol=kw.get("rtol"), atol=kw.get("atol"), max_num_steps=kw.get("max_num_steps"),
                                 jit=kw.get("jit", False))
    times = kw.get("times")
    # a run the plan has made already, by the run's scene (compared by value) and settings: the N / 4 run of one check
    # is the N / 2 run of the one before, a rejected N's run at the check's rtol the N / 2 run of the next N's check.
    # A check takes it; a candidate always runs (its caller's on_block and progress see it)
    memo = kw.get("check_runs") if times is None else None
    key = (sc, choice.name, choice.segments, str(settings.method), settings.rtol, settings.atol)
    if memo is not None and not candidate and key in memo:
        return memo[key]
    opts = {**({"x0": x0} if x0 is not None else {}),   # the quasi-static rungs: the start their guard probed, once
            **hooks(kw, describe_run(choice), candidate)}
    sim = cache.simulator(model, sc.output_times if times is None else times, settings)
    t0, c0 = time.perf_counter(), time.process_time()
    result = simulate(sc, model=model, simulator=sim, **opts)
    log_run(kw, choice, candidate, settings, result, time.perf_counter() - t0, time.process_time() - c0)
    if memo is not None:
        memo[key] = result
    return result


def log_run(kw: dict, choice: Choice, candidate: bool, settings, result, wall_s: float, cpu_s: float) -> None:
    """One entry in ``kw["run_log"]`` (when the caller keeps one, :func:`simulate` does) for a run of the plan: the
    rung and N, candidate or check, integrator (method, rtol, atol), steps taken (the integrator's count), wall and
    process CPU time (s) of the run with its outputs, and both per step (us)."""
    runs = kw.get("run_log")
    if runs is None:
        return
    steps = int((getattr(result, "stats", None) or {}).get("nsteps") or 0)
    runs.append({"rung": choice.name, "segments": choice.segments, "candidate": bool(candidate),
                 "method": str(settings.method), "rtol": float(settings.rtol), "atol": float(settings.atol),
                 "compiled": bool(settings.compiled), "steps": steps, "success": bool(getattr(result, "success", False)),
                 "wall_s": wall_s, "cpu_s": cpu_s,
                 "wall_per_step_us": 1e6 * wall_s / steps if steps else None,
                 "cpu_per_step_us": 1e6 * cpu_s / steps if steps else None})


def log_steady(kw: dict, choice: Choice, candidate: bool, result, wall_s: float, cpu_s: float) -> None:
    """One entry in ``kw["run_log"]`` (as :func:`log_run`) for a steady state of the plan: method "steady state", no
    integrator tolerances, no steps."""
    runs = kw.get("run_log")
    if runs is not None:
        runs.append({"rung": choice.name, "segments": choice.segments, "candidate": bool(candidate),
                     "method": "steady state", "rtol": None, "atol": None, "compiled": False, "steps": 0,
                     "success": bool(getattr(result, "success", False)), "wall_s": wall_s, "cpu_s": cpu_s,
                     "wall_per_step_us": None, "cpu_per_step_us": None})


def _steady_run(scene: Scene, segments: int, cache: RungCache, times=None):
    """The steady rung's run (:func:`.steady_tow.steady_run`) at N = ``segments``: the node model from ``cache`` and its
    start, the one its time-domain run takes (:func:`.run_settings.start`)."""
    sc = rung_scene(scene, "steady", segments)
    model = cache.model(scene, "steady", segments)
    return steady_run(scene, sc, model, start(sc, model, cache), segments, times, cache)


def _periodic_run(scene: Scene, cache: RungCache):
    from ..linear import periodic_steady_state
    from ..linear.periodic import scene_input_amplitude
    from ..time_domain.sampled import sampled_record
    sc = rung_scene(scene, "wang")
    model = cache.model(scene, "wang")
    p = model.parameters(sc)
    omega, Z = scene_input_amplitude(sc)
    per = periodic_steady_state(model, p, omega, input_amplitude=Z)
    times = sc.output_times
    data = {}
    n = len(per.time)
    k = np.fft.rfftfreq(n, 1.0 / n)
    for lbl, y in per.outputs.items():
        c = np.fft.rfft(np.asarray(y, float)) / n
        ph = 2 * np.pi * (times[:, None] - per.time[0]) / per.period * k[None, :]
        w = np.where((k == 0) | ((n % 2 == 0) & (k == n // 2)), 1.0, 2.0)
        data[lbl] = np.real(np.exp(1j * ph) @ (w * c))
    stats = dict(per.stats, method="periodic collocation", wall_s=float(per.stats.get("wall_time_s", 0.0)), build_s=0.0)
    return sampled_record(scene, model, p, times, data=data, success=per.success, message=per.message, stats=stats,
                          model_info={"name": "frequency", "segments": 1})


def _went_slack(result, scene: Scene) -> bool:
    """True when the run's least tension (ends, Wang's F_bc, and every element of a segmented cable)
    reached the floor, or the run located a slack event."""
    floor = max(s.cable.tension_floor for s in scene.sections)
    low = min(float(np.min(result[k])) for k in result.labels if metrics.base_label(k) in ("tension_bottom", "tension_mid"))
    profiles = getattr(result, "profiles", {}) or {}
    if "element_tension" in profiles:         # a segmented cable: an element can slacken between the ends
        low = min(low, float(np.min(profiles["element_tension"])))
    return bool(result.events) or result.time_slack() > 0 or low <= floor


def _alone(scene: Scene, name: str, segments, tol):
    """The decision where one built-in rung alone is valid for the scene (each rung's ``valid``,
    :mod:`cablesys.ladder.rung`), else None; a rung named for a scene it cannot run is a
    :class:`~cablesys.errors.ParameterError` saying why, before any work.

    The sole rung states its N, its reason and whether N is checked a posteriori (:meth:`~.rung.base.BuiltinRung.alone`:
    a 3-D scene or a massless cable runs Wang's straight cable, an anchored line or a seabed the node model, N
    checked on every quantity); its error has no a priori estimate against the converged cable (NaN): the check's,
    or for Wang's cable none. Registered rungs are not considered for such a scene.

    A rung that answers the sole rung's model without stepping (``shortcut``: the steady rung for the node model), is
    valid and costs less (its ``cost`` at the sole rung's N) takes its place under auto, and may be named; the sole rung
    may still be named."""
    why = {r.name: r.valid(scene) for r in BUILTIN}
    runnable = [r for r in BUILTIN if not why[r.name]]
    stepped = [r for r in runnable if r.time_domain]
    sole = stepped[0] if len(stepped) == 1 and len(runnable) - 1 <= sum(r.shortcut for r in runnable) else None
    shortcut = next((r for r in runnable if r.shortcut and sole is not None and r.model_of == sole.name), None)
    requested = None if name == "auto" else get_rung(name)
    refused = validity(requested, scene) if requested is not None else ""
    if not runnable or (requested is not None and (refused or (sole is not None and requested not in (sole, shortcut)))):
        able = " or ".join([r.name for r in (shortcut, sole) if r is not None] if sole else
                           [r.name for r in ladder_rungs() if not validity(r, scene)])
        allowed = f"must be auto, as-built or {able} for this scene" if able else "no rung can run this scene"
        raise ParameterError("numerics.model", name, f"{allowed}: " + (refused or "; ".join(dict.fromkeys(
            w for w in why.values() if w))))
    if sole is None:
        return None
    if shortcut is not None and requested is None:      # under auto where it costs less than the stepped run
        n = sole.alone(scene, name, segments)[0]
        shortcut = shortcut if shortcut.cost(scene, None, n) < sole.cost(scene, None, n) else None
    taken = shortcut if shortcut is not None and requested in (None, shortcut) else sole
    n, reason, checked = taken.alone(scene, name, segments)
    return Choice(taken.name, n, reason, dict(NOT_ESTIMATED), {"valid": True}), tol, checked


def decide(scene: Scene, model, tolerance, segments, cache: RungCache | None = None):
    """The ladder's decision for a model request, before any run.

    Parameters
    ----------
    scene : Scene
        The scene.
    model : str or None
        "auto", a rung name or a registered rung (default ``numerics.model``).
    tolerance : float or (float, float) or None
        See :func:`~.choice.tolerances`.
    segments : int or None
        Elements per section of a named segmented or quasi-static rung.
    cache : RungCache, optional
        Built models to reuse.

    Returns
    -------
    (Choice, (float, float), bool)
        The choice, the (body, tension) tolerances, and whether the ladder chose (auto). A rung named outside
        its validity warns (:class:`~cablesys.errors.NumericalWarning`) with the reason.
    """
    if (model or getattr(scene.numerics, "model", "auto")) == AS_BUILT:
        raise ParameterError("model", AS_BUILT, "runs the scene's own model with no choice: call simulate")
    name = check_rung(model or getattr(scene.numerics, "model", "auto"))
    tol = tolerances(scene, tolerance)
    only = _alone(scene, name, segments, tol)
    if only is not None:
        return only
    if name == "auto":
        return choose(scene, tol, cache=cache), tol, True
    choice = forced(scene, name, segments, tol, cache=cache)
    if not choice.numbers.get("valid", True):
        warnings.warn(f"model '{name}': {choice.reason}", NumericalWarning, stacklevel=3)
    return choice, tol, False


AS_BUILT = "as-built"      # the scene's own model (its sections' ``segments``), no choice, no estimate


def _as_built(scene: Scene, model, simulator, kw: dict, cache: RungCache | None):
    """Run ``scene``'s own model (or the caller's ``model`` / ``simulator``) with no ladder choice."""
    from ..time_domain import simulate as run_model
    given = model is not None or simulator is not None
    if not given and cache is not None:       # the scene's own structure, built once per cache
        n = scene_segments(scene)
        model = cache.model(scene, "segmented" if n > 1 else "wang", n)
    extra = hooks(kw, "as built", True)
    opts = {k: kw[k] for k in ("method", "rtol", "atol", "max_num_steps", "times", "x0") if kw.get(k) is not None}
    r = run_model(scene, model=model, simulator=simulator, jit=kw.get("jit", False), **opts, **extra)
    info = dict(r.model_info)
    info.update(reason=("the caller's model, as built" if given
                        else "numerics.model = 'as-built': the scene's own model, as built") +
                "; no ladder choice, its error not estimated", estimated_error={"body": None, "tension": None})
    return windowed(scene, dataclasses.replace(r, model_info=info, stats={**r.stats, "model": info}))


def windowed(scene: Scene, result):
    """``result`` with the scene's forcing period and smooth start, which set its statistics window
    (:func:`cablesys.statistics.window`): one window for every door's summary and table."""
    return dataclasses.replace(result, forcing_period_s=metrics.forcing_period(scene),
                               ramp_s=float(scene.top_motion.effective_ramp_s))


def simulate(scene: Scene, *, model=None, tolerance=None, segments: int | None = None, method: str | None = None,
             rtol: float | None = None, atol: float | None = None, max_num_steps: int | None = None, jit: bool = False,
             times=None, x0=None, on_block=None, progress=None, on_run=None, simulator=None, quantities=None,
             cache: RungCache | None = None, on_plan=None):
    """Simulate ``scene`` with the model the ladder chooses for it, or the one named; say which ran, why, and its error.

    Every door runs this: the Python API (``cablesys.simulate``), ``cablesys run`` and ``sweep``.

    Parameters
    ----------
    scene : Scene
        The scene.
    model : str or CableModel, optional
        "auto" (the ladder's choice), a rung name (:data:`~cablesys.ladder.rungs.MODEL_CHOICES`), "as-built" (the
        scene's own model, its sections' ``segments``, no choice), or a built :class:`~cablesys.model.CableModel`
        (run as built). Default: ``scene.numerics.model``.
    tolerance : float or (float, float), optional
        Body-motion (and tension) tolerance; default ``numerics.model_tolerance`` or 1 % / 2 %.
    segments : int, optional
        Elements per section for a named segmented or quasi-static rung (default: chosen for the tolerance).
    method, rtol, atol, max_num_steps, jit : optional
        Integrator settings (:func:`.run_settings.integrator_settings`: the ladder's by default).
    times, x0 : array_like, optional
        Output times (s) and initial state of the run (default: the scene's, and the static start).
    on_block, progress : callable, optional
        Passed to every candidate run (a run whose result may be returned), see
        :meth:`cablesys.time_domain.Simulator.run`.
    on_run : callable, optional
        ``on_run(description, candidate) -> (on_block, progress)`` before each run of the plan (the candidates and
        the a posteriori check runs, ``candidate`` False): a streaming caller starts a new stream there.
    simulator : Simulator, optional
        A built simulator: its model runs as built.
    quantities : sequence of str, optional
        The quantities of interest the a posteriori check holds to the tolerance (keys of
        :func:`.metrics.statistics`: ``x_b_amplitude``, ``y_b_mean``, ``tension_top_max``, ...; default all of them;
        an empty sequence: only the body and tension groups, each body amplitude over the largest and each tension
        extreme over the largest top tension).
    cache : RungCache, optional
        Built models and simulators to reuse; pass one cache to many calls on scenes of one
        structure (default: a new one, so nothing is built twice within this call).
    on_plan : callable, optional
        ``on_plan(prediction)`` with the candidate run's :class:`~.plan_cost.Prediction` (elements, operations, steps,
        compile, memory, wall time), before its model is built; a run predicted past ``numerics.time_budget_s`` is
        refused then (:class:`~.extrapolation.PlanRefused`).

    Returns
    -------
    RunRecord
        ``stats["model"]`` and ``model_info``: ``{name, segments, reason, estimated_error, checked}`` and, after an
        a posteriori check, ``estimated_error_per_quantity`` (every quantity of :func:`.metrics.statistics`, each
        relative to its own value with an absolute floor: :func:`.metrics.quantity_errors`);
        ``stats["ladder_timing"]``: wall seconds ``choose_s`` (steady state, linearization, describing function,
        estimates), ``build_s`` (models and simulators, incl. loading compiled code), ``run_s`` (the first run of the chosen
        rung and N), ``check_s`` (a posteriori runs: a grown N's and the reported run at the check's rtol among them),
        ``total_s``, and ``runs``: each time-domain run of the plan but the
        extrapolation's (which ``model.extrapolated.plan`` lists), in order (:func:`log_run`). A rung named outside its validity warns
        (:class:`~cablesys.errors.NumericalWarning`) with the reason.
    """
    kw = {k: v for k, v in dict(method=method, rtol=rtol, atol=atol, max_num_steps=max_num_steps, jit=jit, times=times,
                                  x0=x0, on_block=on_block, progress=progress, on_run=on_run, on_plan=on_plan,
                                  quantities=None if quantities is None else tuple(quantities)).items() if v is not None}
    if simulator is not None or isinstance(model, CableModel) or \
            (model or getattr(scene.numerics, "model", "auto")) == AS_BUILT:
        return _as_built(scene, model if isinstance(model, CableModel) else None, simulator, kw, cache)
    cache = cache if cache is not None else RungCache()
    kw["run_log"] = []          # every run of the taut path's plan (log_run); the extrapolation keeps its own plan
    kw["check_runs"] = {}       # the plan's runs by scene, rung, N and integrator settings, for its checks (_run)
    t0, b0 = time.perf_counter(), cache.build_s
    choice, tol, auto = decide(scene, model, tolerance, segments, cache)
    if choice.name == "steady" and kw.get("x0") is not None:     # the caller starts the run off the steady state
        if not auto:
            raise ParameterError("x0", "given", "must be unset for the steady rung: it answers the run started on the "
                                 "steady tow or turn (name model 'segmented' to step from another start)")
        choice = dataclasses.replace(choice, name="segmented", reason=f"{choice.reason}; the caller's x0 starts the run "
                                     f"off the steady state: the node model's time-domain run with N = "
                                     f"{choice.segments} instead")
    if auto:                                     # the mean shape in the current, from the statics, before any run
        choice = static_check.check(scene, choice, tol, cache)
        choice = checked_upward(choice)
    choice = explicit_or_node(scene, choice, tol, cache, kw)     # the stiffness guard at the N that will run
    t1, b1 = time.perf_counter(), cache.build_s
    if extrapolation.applies(choice, auto):      # first order in N: RK4 runs at N, N / 2, N / 4 (extrapolation)
        choice, kw = extrapolation.plan(scene, choice, cache, kw)      # every run checked before the first starts
        prediction = plan_cost.from_plan(scene, choice, kw["extrapolation_plan"])
        plan_cost.announce(prediction, kw)
        result = extrapolation.run(scene, choice.segments, cache, kw)
    else:
        prediction = plan_cost.for_run(scene, choice, tol, kw)     # before the run's model is built
        if prediction is not None:
            plan_cost.check_budget(scene, prediction)
        plan_cost.announce(prediction, kw)
        result = _run(scene, choice, tol, cache, kw)
    t2, b2 = time.perf_counter(), cache.build_s
    result, choice = _check(scene, choice, tol, result, cache, kw, auto=auto)
    choice = static_check.refresh(scene, choice, cache)        # the static shape's error at the N that ran
    choice = settled_check(scene, choice, result)
    t3, b3 = time.perf_counter(), cache.build_s
    info = extrapolation.model_dict(choice)
    if prediction is not None:            # the candidate run's prediction, made before its build
        info["prediction"] = prediction.as_dict()
    timing = {"choose_s": (t1 - t0) - (b1 - b0), "build_s": b3 - b0, "run_s": (t2 - t1) - (b2 - b1),
              "check_s": (t3 - t2) - (b3 - b2), "total_s": t3 - t0, "runs": kw["run_log"]}
    log.info("model %s (N = %d): %s", choice.name, choice.segments, choice.reason)
    return windowed(scene, dataclasses.replace(result, model_info=info,
                                                stats={**result.stats, "model": info, "ladder_timing": timing}))


def checked_upward(choice: Choice) -> Choice:
    """``choice``, or under auto an element rung with 2 or 3 elements per section doubled to 4 or 6: such an N has no
    coarser run of its own model to be checked against, so the ladder runs 2N and checks it against N, a run that
    costs less than the one kept (a 300 m line from a crane tip moved in x, y, z, chosen a priori at N = 3 and left
    unchecked, stated 0.26 % on the body and was 0.61 % off; in the plane 1.19 %, outside the tolerance). Slack
    scenes are extrapolated instead (:mod:`.extrapolation`)."""
    n = choice.segments
    if not takes_elements(choice.name) or not 2 <= n < checks.CHECKED_MIN_SEGMENTS or extrapolation.applies(choice, True):
        return choice
    e = (est.rung_error(choice.numbers["estimates"], choice.name, 2 * n) if "estimates" in choice.numbers
         else choice.estimated_error)
    return Choice(choice.name, 2 * n, f"{choice.reason}; N = {n} has no coarser run of its model to check it "
                                      f"against: N = {2 * n}, checked against N = {n}",
                  {"body": e["body"], "tension": e["tension"]}, choice.numbers)


def _explicit_only(choice: Choice) -> bool:
    return choice.name == "quasi-static" and choice.numbers.get("plan", {}).get("explicit_only", False)


def explicit_or_node(scene: Scene, choice: Choice, tol, cache: RungCache, kw: dict | None = None) -> Choice:
    """``choice``, or the node model at the same N when ``choice`` is the quasi-static segmented cable taken for
    its cost with the explicit pair (:func:`~.choice.element_plan`, ``explicit_only``) and the pair's stiffness
    guard (:mod:`.stiffness`) refuses it, or the caller names the method: stepped by CVODES it costs more than
    the node model (its stretch Newton solve at every evaluation). The guard's verdict and the start it probed are kept on
    ``cache`` for the run (:func:`.run_settings.rung_settings`)."""
    kw = kw or {}
    if not _explicit_only(choice):
        return choice
    sc = rung_scene(scene, choice.name, choice.segments)
    s, _ = rung_settings(sc, tol, choice, cache.model(scene, choice.name, choice.segments), cache=cache,
                         x0=kw.get("x0"), method=kw.get("method"), rtol=kw.get("rtol"), atol=kw.get("atol"))
    if s.method == QUASI_STATIC_METHOD:
        return choice
    return node_model(choice, f"the quasi-static segmented cable would step with {s.method}, not the explicit pair")


def node_model(choice: Choice, why: str, segments: int | None = None) -> Choice:
    """The node model (``segmented``) at ``segments`` (default: ``choice``'s N) in place of ``choice``, with its
    own estimate and ``why`` in the reason."""
    n = segments or choice.segments
    e = est.segmented_error(choice.numbers["estimates"], n)
    plan = dict(choice.numbers.get("plan", {}), name="segmented", segments=n, explicit_only=False)
    return Choice("segmented", n, f"{choice.reason}; {why}: the node model with N = {n} instead",
                  {"body": e["body"], "tension": e["tension"]}, dict(choice.numbers, plan=plan))


def _check(scene: Scene, choice: Choice, tol, result, cache: RungCache, kw: dict, *, auto: bool):
    """A posteriori checks of ``result`` (see the module docstring): (result, choice) to keep."""
    if extrapolation.applies(choice, auto):
        return extrapolation.until_done(scene, choice, tol, result, cache, kw)
    while True:
        choice, again = after_run(scene, choice, result, auto=auto)
        if not again:
            break
        log.info("rejected a posteriori; running %s with N = %d", choice.name, choice.segments)
        result = _run(scene, choice, tol, cache, kw)
    while needs_richardson(choice, tol):        # N / 2 checks, on every quantity
        choice, again, result = richardson_step(scene, choice, tol, result, cache, kw, auto=auto)
        if not again:
            break
        result = _run(scene, choice, tol, cache, kw)
        if choice.name == "steady":             # the grown N's steady state: its own stability
            choice, declined = steady_judged(choice, result, auto=auto, again=True)
            if declined:
                result = _run(scene, choice, tol, cache, kw)
    return result, choice


def settled_check(scene: Scene, choice: Choice, result) -> Choice:
    """``choice`` with a note in its reason when the run had not settled: the body amplitudes changed between
    the halves of the statistics window (:func:`.metrics.window_change`) by more than the stated body error.
    The estimates speak of the settled response; a build-up (a cable forced at its first string mode over 7
    periods: 11 %, the segmented estimates 2x short of the window's errors, within 1.2x over 25 periods) or a
    front still arriving is the run's, not the model's (extrapolated runs: :mod:`.extrapolation` has its own). Not for
    an irregular sea or a recorded motion, whose halves differ by sampling, nor for a winch scene, whose cable length
    changes by design (a lowering or a recovery has no settled response to approach)."""
    stepped = getattr(get_rung(choice.name), "time_domain", True)     # a periodic orbit or a steady state: settled
    if not getattr(result, "success", False) or "extrapolated" in choice.numbers or not stepped:
        return choice
    if scene.top_motion.spectrum is not None or scene.top_motion.series is not None:
        return choice      # an irregular sea: half the peak-to-peak of each half is a sample, not a build-up
    if scene.winch is not None:
        return choice      # the length L(t) is prescribed: the halves differ because the system does
    change = metrics.window_change(result, metrics.forcing_period(scene), scene.top_motion.effective_ramp_s)
    stated = choice.estimated_error.get("body", math.inf)
    if not (change > max(stated, est.RESOLUTION)):
        return choice
    note = (f"the run has not settled: the body amplitude changed by {change:.2g} between the halves of the statistics "
            f"window, more than the estimated error, which is the settled response's (run longer)")
    return dataclasses.replace(choice, reason=f"{choice.reason}; {note}", numbers=dict(choice.numbers, unsettled=change))


def needs_richardson(choice: Choice, tol) -> bool:
    """Whether a run of ``choice`` gets the a posteriori check at N / 2 (:func:`richardson_step`): every run of N >= 4
    elements not checked yet. The a priori estimates see the body and tension groups through a linear response;
    the check sees every reported quantity (each body coordinate's amplitude and mean, each tension extreme): in a
    sheared current the a priori body error of the quasi-static segmented N = 4 was 0.15 % while its surge
    amplitude was 2x the converged one. An N whose half lies across the drag rule's switch is checked against a
    run with one drag point per element (:func:`~.choice.check_scene`); auto runs no fewer elements
    (:func:`checked_upward`), a named rung's 2 or 3 is reported unchecked with its a priori estimate."""
    return checks.checked(choice.name, choice.segments) and choice.numbers.get("checked_n") != choice.segments


def richardson_step(scene: Scene, choice: Choice, tol, result, cache: RungCache, kw: dict, *, auto: bool):
    """One a posteriori check of ``result`` (N elements) against a run at N / 2: (Choice with the Richardson
    estimate |y_N - y_N/2| / (2^p - 1), False, the run to keep), or under auto while it misses CHECK_ACCEPT x the
    tolerance (Choice, True, ``result``): the plan's sure option for a checked N (:func:`~.choice.element_plan`), else
    2N. The estimate is at least est.RESOLUTION, and for the quasi-static segmented cable it adds the stretch's part
    (:func:`~.estimate.quasistatic_segmented_error`), which both runs share and their difference cannot see
    (heavy1000 N = 6 vs 3: 0.31 + 0.11 % body against an actual 0.49 %, 0.006 + 0.11 % tension against 0.11 %).

    With an adaptive integrator the N / 2 run steps at the candidate's rtol / checks.TIGHTEN, and an N that passes is
    run again at that rtol: that run is kept, its stated error the tight pair's Richardson estimate plus its
    integration error from its difference with the candidate (:mod:`.checks`: the integration error of one rtol
    does not cancel between N and N / 2). From N = checks.THIRD_MIN_SEGMENTS on, an N that passes is also checked
    against N / 4 (at the tight rtol): each quantity's estimate then takes its observed order, or the whole last
    difference where the three runs are not in the asymptotic range (:func:`~.checks.richardson_triple`), and under
    auto an N whose estimate that lifts past CHECK_ACCEPT x the tolerance grows as a missed check does. In an
    irregular sea or a recorded motion the estimates are the whole differences (:func:`~.checks.richardson`)."""
    period, n = metrics.forcing_period(scene), choice.segments
    sc = rung_scene(scene, choice.name, n)
    stepped = getattr(get_rung(choice.name), "time_domain", True)    # a steady state (the steady rung) has no integration error
    settings, _ = rung_settings(sc, tol, choice, cache.model(scene, choice.name, n), cache=cache, x0=kw.get("x0"),
                                method=kw.get("method"), rtol=kw.get("rtol"), atol=kw.get("atol"),
                                max_num_steps=kw.get("max_num_steps"), jit=kw.get("jit", False)) if stepped else (None, None)
    adaptive = stepped and checks.adaptive(settings.method)
    tight_kw = checks.tightened(kw, settings) if adaptive else kw
    coarse = _run(check_scene(scene, n), dataclasses.replace(choice, segments=n // 2), tol, cache, checking(tight_kw),
                  candidate=False)
    if not (coarse.success and result.success):
        return choice, False, result
    ramp = scene.top_motion.effective_ramp_s
    fine_st, coarse_st = (metrics.statistics(r, period, ramp) for r in (result, coarse))
    rough = checks.irregular(scene)
    e, per = checks.richardson(fine_st, coarse_st, choice, rough)
    order = choice.numbers.get("estimates", {}).get("segmented_1", {}).get("order", est.ORDER)
    # a body resting on the seabed: its tensions converge at first order, judged at that order (:mod:`.landed`)
    quarter_st, on_bed, block = None, landed.landed_sections(sc, result, period, ramp), None
    quarter_note = ""
    if on_bed and n >= checks.THIRD_MIN_SEGMENTS:
        quarter_st, quarter_note = _quarter(scene, choice, tol, cache, tight_kw, period, ramp)
        if quarter_st is not None:
            block = landed.extrapolate(quarter_st, coarse_st, fine_st, n)
            if block["extrapolated_quantities"]:
                e, per = block["estimated_error"], block["estimated_error_per_quantity"]
            else:                      # nothing first order: the taut check as for any run
                block = None
    limit = {"body": tol[0], "tension": tol[1]}
    asked = kw.get("quantities")
    judged = {k: v for k, v in per.items() if asked is None or k in asked}
    worst = max(judged, key=lambda k: judged[k] / limit[metrics.group(k)], default=None)
    cap = MAX_SEGMENTS if order >= est.ORDER else SLACK_MAX_SEGMENTS
    same_rule = "" if checkable(scene, n) else ", one drag point per element in both"
    how = "an irregular sea: the whole difference" if rough else f"order {order:g}"
    said = (f"a posteriori (N = {n} vs {n // 2}{same_rule}, {how}): body {e['body']:.2g}, tension {e['tension']:.2g}"
            + (f", the quantity furthest from its tolerance {worst} {judged[worst]:.2g}" if worst else ""))
    if on_bed:
        said = landed.note(sc, on_bed, block) + said
    ok = (e["body"] <= CHECK_ACCEPT * tol[0] and e["tension"] <= CHECK_ACCEPT * tol[1]
          and all(v <= CHECK_ACCEPT * limit[metrics.group(k)] for k, v in judged.items()))
    numbers = dict(choice.numbers, checked_n=n, per_quantity=per)
    if not auto or ok or 2 * n > cap:
        kept_st, e_i, per_i = fine_st, None, None
        if adaptive:       # the same N at the check's rtol, kept: its stated error has both parts (.checks)
            tight = _run(scene, choice, tol, cache, tight_kw)
            if tight.success:
                kept_st = metrics.statistics(tight, period, ramp)
                if block is not None:
                    block = landed.extrapolate(quarter_st, coarse_st, kept_st, n)
                    e, per = block["estimated_error"], block["estimated_error_per_quantity"]
                else:
                    e, per = checks.richardson(kept_st, coarse_st, choice, rough)
                e_i, per_i = checks.integration_errors(kept_st, fine_st, settings.method)
                result = tight
        if n >= checks.THIRD_MIN_SEGMENTS and block is None:   # N / 4 too: is N / 2 in the asymptotic range?
            if quarter_st is None and not quarter_note:   # (a landed body's check has run it already)
                quarter_st, quarter_note = _quarter(scene, choice, tol, cache, tight_kw, period, ramp)
            said += quarter_note
            if quarter_st is not None:
                e, per, observed = checks.richardson_triple(kept_st, coarse_st, quarter_st, choice, rough)
                slow = sorted(k for k in per if k in judged and (observed.get(k) or 0.0) < order)
                said += (f"; N = {n // 4} too" + ("" if rough else
                         f" (observed order below {order:g}: {', '.join(slow)})" if slow else " (asymptotic)"))
                numbers["observed_order"] = observed
                judged = {k: v for k, v in per.items() if asked is None or k in asked}
                ok_triple = (e["body"] <= CHECK_ACCEPT * tol[0] and e["tension"] <= CHECK_ACCEPT * tol[1]
                             and all(v <= CHECK_ACCEPT * limit[metrics.group(k)] for k, v in judged.items()))
                if auto and ok and not ok_triple and 2 * n <= cap:   # not yet asymptotic, and that matters: grow N
                    ratio = max([e["body"] / (CHECK_ACCEPT * tol[0]), e["tension"] / (CHECK_ACCEPT * tol[1])]
                                + [v / (CHECK_ACCEPT * limit[metrics.group(k)]) for k, v in judged.items()])
                    n_next = next_segments(scene, n, ratio, order, cap)
                    return dataclasses.replace(choice, segments=n_next, reason=f"{choice.reason}; {said}: N = {n_next}"), \
                        True, result
                ok = ok and ok_triple
        if auto and not ok:
            said += f"; NOT within {CHECK_ACCEPT:g} x the tolerance at the cap N = {n}"
        if per_i is not None:
            e, per = checks.total(e, e_i), checks.total(per, per_i)
            said += "; " + checks.summary(per_i, tight_kw["rtol"], settings.method)
            numbers["integration"] = {"method": str(settings.method), "rtol": tight_kw["rtol"], "atol": tight_kw["atol"],
                                      "rtol_compared": settings.rtol, "error": e_i, "per_quantity": per_i}
        numbers["per_quantity"] = per
        # stated: the larger of the check's and the a priori estimate at this N (a check against a coarse N / 2 can
        # understate, random heavy-4: 4 vs 2 gave 0.24 % body against an actual 0.50 %, the a priori 0.47 %); not the
        # estimate of the N the plan started from, which a grown N carries (random heavy-3: N = 5's 0.97 % stated at
        # N = 14, whose a priori estimate is 0.07 %)
        prior = (est.rung_error(choice.numbers["estimates"], choice.name, n) if "estimates" in choice.numbers
                 else choice.estimated_error)
        stated = {k: max(v, prior.get(k, 0.0)) for k, v in e.items()}
        if block is not None:        # the extrapolated statistics and their errors (extrapolation.model_dict shows them)
            block.update(estimated_error=dict(stated), estimated_error_per_quantity=dict(per))
            numbers.update(extrapolated=block)
        return Choice(choice.name, n, f"{choice.reason}; {said}", stated, numbers), False, result
    plan = choice.numbers.get("plan") or {}
    sure = plan.get("fallback")
    if sure and plan.get("checked") and (plan.get("name"), plan.get("segments")) == (choice.name, n):
        # the checked N missed CHECK_ACCEPT x the tolerance: the plan's sure option, with its a priori estimate
        e_sure = est.rung_error(choice.numbers["estimates"], sure["name"], sure["segments"])
        new = Choice(sure["name"], sure["segments"],
                     f"{choice.reason}; {said}, not within {CHECK_ACCEPT:g} x the tolerance: {sure['name']} with "
                     f"N = {sure['segments']}, its estimate within {SAFETY:g} x the tolerance",
                     {"body": e_sure["body"], "tension": e_sure["tension"]},
                     dict(choice.numbers, plan=dict(plan, **sure, checked=False, fallback=None)))
        return explicit_or_node(scene, new, tol, cache, kw), True, result
    ratio = max([e["body"] / (CHECK_ACCEPT * tol[0]), e["tension"] / (CHECK_ACCEPT * tol[1])]
                + [v / (CHECK_ACCEPT * limit[metrics.group(k)]) for k, v in judged.items()])
    n_next = next_segments(scene, n, ratio, order, cap)
    if _explicit_only(choice) and n_next > EXPLICIT_COST_MAX_ELEMENTS:      # past where it pays (choice.element_plan)
        return node_model(choice, f"a posteriori (N = {n} vs {n // 2}): body {e['body']:.2g}, tension "
                                  f"{e['tension']:.2g}, N grows past {EXPLICIT_COST_MAX_ELEMENTS}", n_next), True, result
    top = quasistatic_max_segments(scene)
    if choice.name == "quasi-static" and n_next > top:    # past its size cap (choice.MAX_MODEL_OPERATIONS): not built
        return node_model(choice, f"{said}; N grows to {n_next}, past the quasi-static segmented cable's size cap "
                                  f"N = {top}", n_next), True, result
    ratio_ops = model_operations(scene, "quasi-static", n_next) / model_operations(scene, "segmented", n_next)
    if choice.name == "quasi-static" and ratio_ops > QS_NODE_SIZE_RATIO:     # it no longer pays
        return node_model(choice, f"{said}; N grows to {n_next}, where the quasi-static segmented cable's functions "
                                  f"are {ratio_ops:.0f}x the node model's", n_next), True, result
    return dataclasses.replace(choice, segments=n_next, reason=f"{choice.reason}; {said}: N = {n_next}"), True, result


def _quarter(scene: Scene, choice: Choice, tol, cache: RungCache, tight_kw: dict, period, ramp) -> tuple:
    """(statistics of the check run at N / 4, "") or (None, the clause saying why there are none): a run that fails,
    or a static state that does not exist at N / 4 (an anchored line of few elements with a compressed one), leaves
    the pair's estimate standing."""
    n = choice.segments
    try:
        quarter = _run(check_scene(scene, n, n // 4), dataclasses.replace(choice, segments=n // 4), tol, cache,
                       checking(tight_kw), candidate=False)
    except SolverError as err:
        return None, f"; N = {n // 4} not run ({err}): the pair's estimate stands"
    if not quarter.success:
        return None, f"; N = {n // 4} failed ({quarter.message}): the pair's estimate stands"
    return metrics.statistics(quarter, period, ramp), ""


QS_NODE_SIZE_RATIO = 16.0
"""Largest ratio of the quasi-static segmented cable's operations to the node model's (:func:`~.choice.model_operations`)
at which a grown N keeps the quasi-static rung: it is chosen where it costs a quarter of the node model at small N
(rung.quasistatic.STIFF_QS_COST) with about 4x the node model's operations per step, so it takes some 16x fewer
steps; past 16x the operations, a step costs what those steps save, and the build grows as N^2.75 (the 3-D
heave line at N = 16: 571 k operations, minutes of C compile, against the node model's 10 k)."""


JUMP_MARGIN = 1.25    # the next N aims at the tolerance with this margin on the observed error's N^-p law


def next_segments(scene: Scene, n: int, ratio: float, order: float, cap: int) -> int:
    """N after a check at ``n`` whose worst quantity is ``ratio`` x its accepted error: the N where an error ~ N^-p
    (``order``) meets it, JUMP_MARGIN over, at least 2 n, at most ``cap``, and checkable against its half on the
    scene's own drag rule (:func:`~.choice.checkable`: both on one side of the drag rule's switch), as the plans
    prefer."""
    grow = min(4.0, max(2.0, JUMP_MARGIN * max(ratio, 1.0) ** (1.0 / max(order, 1.0))))
    m = min(cap, math.ceil(n * grow))
    while m < cap and not checkable(scene, m):
        m += 1
    return m


def after_run(scene: Scene, choice: Choice, result, *, auto: bool) -> tuple[Choice, bool]:
    """A posteriori check of one run: (updated Choice, whether to run again with it).

    A straight-cable run (quasi-static or wang) or a quasi-static segmented run that went slack is
    outside its validity: under "auto" the segmented cable is chosen instead (run again); a forced rung
    keeps its result with a warning and an infinite estimated error. A steady state (the steady rung) is judged by its
    stability (:func:`steady_judged`)."""
    if choice.name == "steady":
        return steady_judged(choice, result, auto=auto)
    if not getattr(get_rung(choice.name), "stays_taut", False) or not _went_slack(result, scene):
        return choice, False
    note = (f"the {choice.name} run went slack: " + ("a quasi-static stretch cannot go slack" if choice.segments > 1
                                                     else "a straight cable with one stretch cannot be partly slack"))
    if not auto:
        warnings.warn(f"model '{choice.name}': {note}", NumericalWarning, stacklevel=2)
        return Choice(choice.name, 1, choice.reason + "; " + note, {"body": math.inf, "tension": math.inf},
                      choice.numbers), False
    n = max(choice.segments, 10)
    return Choice("segmented", n, f"{choice.name} rejected a posteriori: {note}; segmented with N = {n}",
                  est.segmented_error(choice.numbers["estimates"], n), choice.numbers), True


def steady_judged(choice: Choice, result, *, auto: bool, again: bool = False) -> tuple[Choice, bool]:
    """The steady rung's run judged by its stability (:func:`.steady_tow.stability`): (``choice`` with the verdict in
    its first clause, or after a grown N (``again``) in a clause of its own, False) when stable; else under auto the
    node model's time-domain run at the same N, its reason naming the least-damped eigenvalue (True: run it), and for a
    named steady rung the result kept with a warning."""
    st = (getattr(result, "stats", None) or {}).get("steady")
    if st is None:
        return choice, False
    verdict = describe_stability(st)
    statics = (f"no integration error: the state holds the statics' tolerance {st['statics_tolerance']:.2g} on the "
               f"residual scaled by the total weight")
    head, _, rest = choice.reason.partition("; ")
    said = (f"{choice.reason}; at N = {choice.segments} {verdict}" if again else
            f"{head}, {verdict}; {statics}" + (f"; {rest}" if rest else ""))
    if st["stable"]:
        return dataclasses.replace(choice, reason=said), False
    if not auto:
        warnings.warn(f"model 'steady': the steady {st['kind']} is {verdict}", NumericalWarning, stacklevel=3)
        return dataclasses.replace(choice, reason=said), False
    n = choice.segments
    e = est.segmented_error(choice.numbers["estimates"], n) if "estimates" in choice.numbers else choice.estimated_error
    return Choice("segmented", n, f"{head}; the steady {st['kind']} is {verdict}: the node model's time-domain run "
                                  f"with N = {n} instead; N checked a posteriori on every quantity",
                  dict(e), dict(choice.numbers)), True


def short_reason(reason: str, segments: int) -> str:
    """The console's reason: its first clause (the first choice) and, where a later step changed the model (a
    rung replaced, N grown by the static or a posteriori check), the last clause that did, so that the line never
    names another model than the one that ran."""
    clauses = reason.split("; ")
    changed = [c for c in clauses[1:] if " instead" in c or f"with N = {segments}" in c or " rejected " in c]
    text = clauses[0] + (f"; then {changed[-1]}" if changed and changed[-1] != clauses[0] else "")
    return text + (" (the whole reason in summary.json)" if len(clauses) > 1 + bool(changed) else "")


def describe(choice_dict: dict, full: bool = False) -> str:
    """The console lines (at most three): which model ran and its estimated error, whether that error was checked
    (and the quantity furthest from the tolerance), and why, the reason's first clause (``full``: the whole reason,
    which summary.json always holds)."""
    e = choice_dict.get("estimated_error", {})
    fmt = lambda v: "n/a" if v is None else f"{100 * v:.2g} %"
    seg = f", N = {choice_dict['segments']}" if (choice_dict.get("segments") or 1) > 1 else ""
    reason = choice_dict.get("reason", "")
    why = reason if full else short_reason(reason, choice_dict.get("segments") or 1)
    if choice_dict.get("extrapolated"):      # the extrapolated statistics' error first, the time series' too
        return extrapolation.describe(dict(choice_dict, reason=why), fmt, seg)
    head = f"model {choice_dict.get('name')}{seg}: estimated error body {fmt(e.get('body'))}, tension {fmt(e.get('tension'))}"
    per = choice_dict.get("estimated_error_per_quantity") or {}
    check = choice_dict.get("checked")
    if per:
        worst = max(per, key=per.get)
        check = f"{check}; largest per quantity: {worst} {fmt(per[worst])}"
    notes = [] if full else [c for c in reason.split("; ")[1:] if c.startswith("the run has not settled") or "NOT " in c]
    return "\n".join(line for line in (head, f"  {check}" if check else "", f"  why: {why}",
                                        *(f"  note: {c}" for c in notes)) if line)


def require_at_rest(scene: Scene, what: str) -> None:
    """Refuse a towing ship's track for ``what`` (a linear or periodic analysis): those linearize or expand about the
    static state at rest (:mod:`cablesys.statics`), and a tow along a track is not at rest (its steady states are the
    straight tow and the steady turn, :mod:`cablesys.statics.tow`, :mod:`cablesys.statics.turning`)."""
    track = getattr(scene.top_motion, "track", None)
    if track is not None:
        raise ParameterError("top_motion.track", track.kind, f"must be unset for {what}: it works about the static "
                             "state at rest, and a tow along a track is not at rest (the linear analysis of a straight "
                             "tow is that of the ship-frame scene: environment.system_speed = the tow speed)")


def linear_model(scene: Scene, tolerance=None, cache: RungCache | None = None):
    """The model the linear analyses (``cablesys rao``, modes, RAOs) linearize for ``scene``, and why.

    The ladder's choice for the scene's time-domain run (``numerics.model``), as a model with states to linearize:
    Wang's straight cable where the ladder runs a straight rung (frequency, quasi-static, wang), the node model
    (segmented) at the ladder's N where it runs elements (the quasi-static segmented cable's stretch modes are
    eliminated, the node model keeps them: the same bending and swing). "as-built" linearizes the scene's own model.

    Parameters
    ----------
    scene : Scene
        The scene.
    tolerance : float or (float, float), optional
        See :func:`~.choice.tolerances`.
    cache : RungCache, optional
        Built models to reuse.

    Returns
    -------
    (Scene, CableModel, dict)
        The scene the model is built for, the model, and ``{name, segments, reason, estimated_error}`` (the error of
        the model's response against the converged cable, estimated by the ladder; the linearization's own error
        about the steady state is not part of it).

    Raises
    ------
    ParameterError
        For a scene towed along a track (:func:`require_at_rest`).
    """
    require_at_rest(scene, "the linear analyses")
    cache = cache if cache is not None else RungCache()
    if getattr(scene.numerics, "model", "auto") == AS_BUILT:
        n = scene_segments(scene)
        name = "segmented" if n > 1 else "wang"
        return scene, cache.model(scene, name, n), {
            "name": name, "segments": n, "reason": "numerics.model = 'as-built': the scene's own model, as built; "
            "its error not estimated", "estimated_error": {"body": None, "tension": None}}
    choice, tol, _ = decide(scene, None, tolerance, None, cache)
    if choice.name not in RUNGS:
        raise ParameterError("numerics.model", choice.name, "a registered rung has no linear model: name a built-in "
                                                            "rung or as-built for the linear analyses")
    name, n = ("segmented", choice.segments) if choice.segments > 1 else ("wang", 1)
    e = (est.rung_error(choice.numbers["estimates"], name, n) if "estimates" in choice.numbers
         else choice.estimated_error)           # a scene one rung alone can run: its own statement
    seg = f" N = {n}" if n > 1 else ""
    why = (f"the time-domain model is {choice.name}" + (f" N = {choice.segments}" if choice.segments > 1 else "")
           + f" ({choice.reason}); linearized: {name}{seg}")
    info = {"name": name, "segments": n, "reason": why,
            "estimated_error": {"body": e["body"] if math.isfinite(e["body"]) else None,
                                "tension": e["tension"] if math.isfinite(e["tension"]) else None}}
    return rung_scene(scene, name, n), cache.model(scene, name, n), info
