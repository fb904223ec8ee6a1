"""Richardson extrapolation of the segmented cable's statistics where it converges at first order.

Under partial slack the snap front is resolved to one element and the segmented cable converges at
first order in N (300 m wire, 2 t sphere, T = 6 s: observed 0.98-1.03 from N = 10, 20, 40, 80), so
the tolerance would need hundreds of elements. The statistics the tolerance speaks of (body
amplitudes, tension extremes, :mod:`.metrics`) are extrapolated instead (Richardson 1911), from
three runs at N / 4, N / 2 and N (RK4 at its stable step: :func:`settings`).

The extrapolation itself (the limits, the observed orders, the stated error and when N doubles) is
:mod:`.richardson`'s.

The time series the user gets is the N run's: its own first-order Richardson estimate
|f(N) - L(N)| is stated apart (``time_series_error``), so nothing is hidden.

Time step: RK4 at h |lambda|_max = RK4_MARGIN (on snap loads the fast and accurate method; the
compiled element kernel makes it cheap). Against half that step the statistics of the 300 m slack
scene (360 s, output 0.01 s) move by < 1e-5 relative at N = 8, 16, 32 (body amplitude 7e-6, top
maximum 4e-6, bottom maximum 5e-6): far below the extrapolated values' errors (3e-4 to 3e-3).
The step is at most the scene's output step / ``steps_per_output`` (not the finer statistics step's):
light-cage lift (60 m of 30 mm wire, 200 kg in water, Hs 5 m, 40 s, statistics step 0.0029 s), at N = 4,
8, 16 (1, 2, 10 steps per output) the statistics move against half the step by body < 2e-10, tension
< 1e-5. The statistics runs at N / 2 and N / 4 step no longer than the N run (``max_step``): at their own, coarser
RKC steps the light lift's (200 s) N = 4 and 8 top-tension maxima were 1.1 N and 0.8 N (2e-4, 1.5e-4) off their
values at a tenth of the step, as large as the differences in N the extrapolation reads (1.4 N); at the N = 16
run's step 0.1 N and 0.3 N.

Where the internal damping C_I makes the element modes overdamped, the fastest eigenvalue is real,
about -4 C_I / (m l_e^2), and grows as N^2 (that wire: -6.7e3, -2.9e4, -1.2e5 1/s at N = 16, 32, 64, the
largest imaginary part 435 1/s at each), so RK4's step falls as N^-2 and a run costs N^3 (at N = 64,
1.7e-5 s: 35 M steps for 600 s). There the runs step with second-order Runge-Kutta-Chebyshev
(:mod:`cablesys.time_domain.rkc`) at the axial travel time across one element, with the fewest stages
stable on the static state's whole spectrum, when that takes fewer right-hand sides per output than RK4
(RKC_GAIN). The light-cage lift, 20 s: N = 16, 4 stages x 3 steps per output against RK4's 10 steps; N =
32, 6 x 6 against 43; statistics against RK4's body <= 1.1e-9, tension <= 2.1e-6, and against RKC at half
its step body <= 8e-10, tension <= 1.9e-6 (the extrapolated errors there: body 3.8e-5).

The plan (:func:`plan`) is made and checked before the first run: each run's output count and memory
against the limits of one run (:mod:`cablesys.time_domain.record`; a statistics grid past them is made
coarser and said, a run that cannot fit refuses the plan as the plan's, :class:`PlanRefused`, never as the
user's input), its cost predicted as steps x the measured cost of one compiled step, and with
``numerics.time_budget_s`` N halves until the plan fits or it is refused; a doubling of N is made only when
its runs fit the limits and the budget left. The candidate runs on the statistics grid and the caller gets
the scene's grid from it (:func:`every`), so the N run is not repeated for its statistics.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np

from ..errors import CablesysError, NumericalWarning
from ..scene import Scene
from . import estimate as est
from . import metrics
from .choice import within
from .hooks import checking, hooks
from .rungs import RungCache, rung_scene
from .richardson import NOISE_FRACTION, ORDER_RANGE, extrapolate, needs_doubling, statistics
from .run_settings import integrator_settings, start

MAX_SEGMENTS = 80           # doubling stops here (RK4, compiled kernel: 0.14 s per simulated s at N = 80)
RKC_GAIN = 0.8              # RKC replaces RK4 when its right-hand sides per output are below this fraction of RK4's
RK4_MARGIN = 2.0            # h |lambda|_max of the stable step (RK4's boundary is 2.78)
SAMPLES_PER_SNAP = 6        # output samples per axial travel time in the statistics runs (see statistics_step)
MIN_SEGMENTS = 8            # the smallest plan a time budget may shrink to (runs at N = 2, 4, 8)
TIMING_S = 0.05             # wall time spent measuring one run's cost per RK4 step before the plan starts


def applies(choice, auto: bool) -> bool:
    """True when auto chose the segmented cable in its first-order regime (partial slack predicted:
    the segmented estimate's ``order`` below :data:`estimate.ORDER`)."""
    order = choice.numbers.get("estimates", {}).get("segmented_1", {}).get("order", est.ORDER)
    return bool(auto and choice.name == "segmented" and order < est.ORDER)


def settings(scene_run: Scene, model, method: str | None = None, x0=None, base_step: float | None = None,
             max_step: float | None = None, **kw):
    """Integrator settings of one extrapolation run: RK4 at its stable step (h |lambda|_max <= RK4_MARGIN
    at the static state, and no longer than ``base_step`` / the scene's steps per output), compiled (the element
    kernel), unless the caller names another method (then :func:`.auto.integrator_settings`).

    Parameters
    ----------
    scene_run : Scene
        The segmented rung's scene.
    model : CableModel
        Its model.
    method : str, optional
        The caller's method: "rk" (RK4 at its stable step), "rkc" (RKC; RK4 with a warning where no stage count is
        stable), another (:func:`.auto.integrator_settings`); default: RKC where it costs less than RK4, else RK4.
    x0 : array_like, optional
        The static start whose fastest rate sets the stable step (default: computed here).
    base_step : float, optional
        The output step (s) the scene's ``steps_per_output`` refers to (the scene's own, when ``scene_run`` has the
        finer statistics step): the step is at most base_step / steps_per_output (default: ``scene_run``'s step).
    max_step : float, optional
        The longest step (s) allowed: the plan's statistics runs at N / 2, N / 4 step as finely as its N run
        (:func:`_runs`), so their time error is below the N run's and does not pollute the observed order in N.
    **kw
        ``rtol``, ``atol``, ``max_num_steps`` for another method.

    Returns
    -------
    IntegratorSettings
    """
    from ..time_domain import IntegratorSettings
    from ..time_domain.failures import rk4_steps_per_output, spectrum
    from ..time_domain.integrators import compiled_by_default
    from ..time_domain.rkc import stages_for
    if method not in (None, "rk", "rkc"):
        # the caller's method and tolerances (the model tolerance only sets rtol without a method)
        return integrator_settings(scene_run, (1.0, 1.0), int(getattr(model, "n_elements", 1)), method=method, **kw)
    p = model.parameters(scene_run)
    eig = spectrum(model, start(scene_run, model) if x0 is None else x0, 0.0, p)
    num = scene_run.numerics
    h = num.output_step
    floor = math.ceil(num.steps_per_output * h / (base_step or h) - 1e-9)
    if max_step:
        floor = max(floor, math.ceil(h / max_step - 1e-9))
    spo = max(floor, rk4_steps_per_output(float(np.max(np.abs(eig))), h, RK4_MARGIN))
    extra = {} if kw.get("max_num_steps") is None else {"max_num_steps": int(kw["max_num_steps"])}
    if method != "rk":          # RKC where its stages cost less than RK4's 4 per step (the overdamped element modes)
        spo_c = max(floor, math.ceil(h / element_travel_time(scene_run) - 1e-9))
        stages = stages_for(h / spo_c, eig)
        if stages is not None and (method == "rkc" or stages * spo_c < RKC_GAIN * 4 * spo):
            return IntegratorSettings(method="rkc", steps_per_output=spo_c, stages=stages,
                                      compiled=compiled_by_default(model, "rkc"), **extra)
        if method == "rkc":
            warnings.warn(f"method rkc: no stage count up to the maximum is stable on the spectrum at the step "
                          f"{h / spo_c:.3g} s (an oscillatory mode too far up the imaginary axis): RK4 runs instead",
                          NumericalWarning, stacklevel=3)
    return IntegratorSettings(method="rk", steps_per_output=spo, compiled=compiled_by_default(model, "rk"), **extra)


def element_travel_time(scene_run: Scene) -> float:
    """The shortest time (s) an axial wave takes to cross one element, min over sections of (L / N) sqrt(m / AE):
    the step of the RKC runs, which resolves a snap front in time as finely as the elements do in space (RK4's
    stable step on the same wire without internal damping is 1.4 of it)."""
    return min(s.cable.length / s.cable.segments * math.sqrt(s.cable.mass_per_length / s.cable.ae)
               for s in scene_run.sections)


def run(scene: Scene, n: int, cache: RungCache, kw: dict | None = None, candidate: bool = True):
    """One run of the segmented cable at ``n`` elements with :func:`settings` (models and simulators
    from ``cache``). ``kw``: ``method``, ``rtol``, ``atol``, ``max_num_steps``, ``times``, ``x0``,
    ``on_block``, ``progress``, ``on_run`` as :func:`.auto.simulate` takes them, and ``extrapolation_plan``
    (a :class:`Plan`: the run is counted and timed in it, and its description says its place, "segmented
    N = 32 (run 2 of 3)"); ``candidate``: the run whose series is returned (:mod:`.hooks`)."""
    from ..time_domain import simulate
    kw = dict(kw or {})
    plan = kw.get("extrapolation_plan")
    # the candidate on the statistics grid (the plan's ``shared``): its statistics come from it, the caller gets
    # every ``sub``-th output (the scene's grid), and the N run is not repeated at the finer step
    sub = plan.sub if plan is not None and candidate and plan.shared else 1
    grid_scene = scene if sub == 1 else scene.with_numerics(output_step=plan.statistics_step)
    sc = rung_scene(grid_scene, "segmented", n)
    model = cache.model(scene, "segmented", n)
    if kw.get("x0") is None:                   # once: the stable step is probed there and the run starts there
        kw["x0"] = start(sc, model, cache)
    s = settings(sc, model, kw.get("method"), kw["x0"], base_step=None if plan is None else plan.base_step,
                 max_step=None if plan is None or candidate else plan.max_step(),
                 **{k: kw.get(k) for k in ("rtol", "atol", "max_num_steps")})
    times = kw.get("times")
    sim = cache.simulator(model, sc.output_times if times is None else times, s)
    what = f"segmented N = {n}" + ("" if candidate else " (extrapolation)")
    if plan is not None:         # its place in the plan: "segmented N = 32 (run 2 of 3)"
        what = f"segmented N = {n} (run {plan.begin(n, candidate)} of {len(plan.runs)}" + \
               ("" if candidate else ", extrapolation") + ")"
    opts = hooks(kw, what, candidate)
    if sub > 1 and opts.get("on_block") is not None:
        opts["on_block"] = _every_block(opts["on_block"], sub)
    result = simulate(rung_scene(scene, "segmented", n), model=model, simulator=sim, x0=kw["x0"], **opts)
    if plan is not None:
        plan.finished(n, candidate, result)
    if sub > 1:
        if result.success:
            plan.statistics[n] = statistics(result, metrics.forcing_period(scene), scene.top_motion.effective_ramp_s)
        result = every(result, sub)
    return result


def _every_block(on_block, sub: int):
    """``on_block`` fed every ``sub``-th output time of the blocks it is given (counted across blocks)."""
    seen = [0]

    def fed(T, data):
        keep = (np.arange(seen[0], seen[0] + len(T)) % sub) == 0
        seen[0] += len(T)
        if keep.any():
            on_block(np.asarray(T)[keep], {k: np.asarray(v)[keep] for k, v in data.items()})
    return fed


def every(result, sub: int):
    """``result`` (a :class:`~cablesys.time_domain.RunRecord`) at every ``sub``-th output time: its series, profiles
    (time x element arrays), states and modes; events and snap loads, located in time, are kept whole."""
    n = int(np.asarray(result.time).size)
    pick = lambda v: np.asarray(v)[::sub] if np.ndim(v) >= 1 and np.shape(v)[0] == n else v
    return dataclasses.replace(result, time=np.asarray(result.time)[::sub],
                               data={k: pick(v) for k, v in result.data.items()},
                               profiles={k: pick(v) for k, v in result.profiles.items()},
                               states=np.asarray(result.states)[:, ::sub], modes=np.asarray(result.modes)[:, ::sub])


class PlanRefused(CablesysError):
    """The extrapolation's plan (runs the tool chose) cannot fit its limits (output count, memory, time budget):
    refused before any run, with the reason and what would fit. Not a bad input: the scene itself is valid, and the
    ``cablesys`` command exits with :attr:`exit_code` 1 (what the tool planned does not fit), not 2 (bad input)."""

    exit_code = 1


@dataclasses.dataclass
class PlannedRun:
    """One run of the extrapolation's plan, predicted before the first starts.

    ``segments`` N; ``output_step`` (s) and ``outputs`` (count) of its grid; ``steps_per_output`` RK4 steps per
    output interval (:func:`settings`); ``method`` ``rk`` (RK4) or ``rkc`` with ``stages``; ``step_s`` the wall time
    of one compiled step of its model and method, measured on its compiled interval from the static start (s); ``memory_bytes`` the series' estimate
    (:func:`cablesys.time_domain.record.run_memory_bytes`); ``candidate``: the run whose series is returned.
    After the run: ``wall_s``, ``cpu_s`` (this process's CPU time, with the series' labelling) and ``status``.
    """

    segments: int
    output_step: float
    outputs: int
    steps_per_output: int
    step_s: float | None
    memory_bytes: float
    candidate: bool
    method: str = "rk"
    stages: int = 0
    wall_s: float | None = None
    cpu_s: float | None = None
    status: str = "planned"

    @property
    def steps(self) -> int:
        """RK4 steps of the run: steps per output x output intervals."""
        return int(self.steps_per_output) * (int(self.outputs) - 1)

    @property
    def predicted_s(self) -> float | None:
        """Predicted wall time (s): steps x measured cost per step (None when not measured)."""
        return None if self.step_s is None else self.steps * self.step_s

    def as_dict(self) -> dict:
        """JSON-able numbers: N, grid, steps, per-step cost (us), predicted and measured wall time (s)."""
        return {"segments": self.segments, "candidate": self.candidate, "method": self.method,
                "stages": self.stages or 4, "output_step_s": self.output_step,
                "outputs": self.outputs, "steps": self.steps, "step_us": None if self.step_s is None else 1e6 * self.step_s,
                "predicted_s": self.predicted_s, "wall_s": self.wall_s, "cpu_s": self.cpu_s, "status": self.status,
                "wall_per_step_us": (None if self.wall_s is None or not self.steps else 1e6 * self.wall_s / self.steps),
                "cpu_per_step_us": (None if self.cpu_s is None or not self.steps else 1e6 * self.cpu_s / self.steps)}


@dataclasses.dataclass
class Plan:
    """The runs the extrapolation plans (candidate N first, then the statistics runs at N, N / 2, N / 4), checked
    against the limits of :mod:`cablesys.time_domain.record` and the scene's ``numerics.time_budget_s`` before the
    first starts (:func:`plan`); it counts the runs as they start (for the progress description) and keeps their
    wall times. ``statistics_step``: the statistics runs' output step (s); ``budget_s``: 0 for none; ``notes``:
    what the plan changed and why; ``t_start``: wall clock at planning (s, ``time.perf_counter``); ``base_step``: the
    scene's output step (s); ``shared``: the candidate runs on the statistics grid and its statistics are taken
    from it (no second run at N), the caller getting the scene's grid (:func:`every`)."""

    runs: list
    statistics_step: float
    base_step: float
    shared: bool = False
    budget_s: float = 0.0
    notes: list = dataclasses.field(default_factory=list)
    t_start: float = 0.0
    started: int = 0
    statistics: dict = dataclasses.field(default_factory=dict)     # {N: statistics} of shared candidate runs

    def max_step(self) -> float | None:
        """The step (s) of the plan's statistics run at its largest N: the longest step of its runs at N / 2, N / 4
        (:func:`settings` ``max_step``), so that their time error stays below the N run's."""
        on_grid = [r for r in self.runs if abs(r.output_step - self.statistics_step) <= 1e-12 * r.output_step]
        top = max((r.segments for r in on_grid), default=None)
        steps = [r.output_step / r.steps_per_output for r in on_grid if r.segments == top]
        return min(steps) if steps else None

    @property
    def sub(self) -> int:
        """Statistics output steps per scene output step (the candidate keeps every sub-th when ``shared``)."""
        return max(1, int(round(self.base_step / self.statistics_step)))

    def begin(self, n: int, candidate: bool) -> int:
        """Count the start of the run (n, candidate) and return its number in the plan (1-based)."""
        self.started += 1
        run_ = self._find(n, candidate)
        if run_ is not None:
            run_.status, run_.cpu_s = "running", time.process_time()
        return self.started

    def finished(self, n: int, candidate: bool, result) -> None:
        """Record the wall time and status of the run (n, candidate)."""
        run_ = self._find(n, candidate)
        if run_ is not None:
            run_.wall_s = float(result.stats.get("wall_s", math.nan))
            run_.cpu_s = time.process_time() - run_.cpu_s
            run_.status = "success" if result.success else "failed"

    def _find(self, n: int, candidate: bool):
        return next((r for r in self.runs if r.segments == n and r.candidate == candidate and r.status in
                     ("planned", "running")), None)

    @property
    def predicted_s(self) -> float:
        """Predicted wall time of the runs not yet made (s)."""
        return float(sum(r.predicted_s or 0.0 for r in self.runs if r.status == "planned"))

    def remaining_budget_s(self) -> float:
        """The budget left now (s; infinite without a budget)."""
        return math.inf if not self.budget_s else self.budget_s - (time.perf_counter() - self.t_start)

    def as_dict(self) -> dict:
        """The plan for summary.json: each run (:meth:`PlannedRun.as_dict`), the statistics step, budget and notes."""
        return {"runs": [r.as_dict() for r in self.runs], "statistics_step_s": self.statistics_step,
                "time_budget_s": self.budget_s or None, "notes": list(self.notes)}


def _planned_run(scene: Scene, n: int, cache: RungCache, kw: dict, output_step: float, outputs: int,
                 candidate: bool, measure: bool, max_step: float | None = None) -> PlannedRun:
    """The :class:`PlannedRun` of ``n`` elements on a grid of ``outputs`` times ``output_step`` apart: its steps
    from :func:`settings` at the static start (no longer than ``max_step``, s) and, when ``measure``, its compiled
    RK4 step timed (:data:`TIMING_S`)."""
    from ..time_domain.record import run_memory_bytes
    sc = rung_scene(scene.with_numerics(output_step=output_step), "segmented", n)
    model = cache.model(scene, "segmented", n)
    x0 = start(sc, model, cache) if kw.get("x0") is None else np.asarray(kw["x0"], dtype=float)
    s = settings(sc, model, kw.get("method"), x0, base_step=scene.numerics.output_step, max_step=max_step,
                 **{k: kw.get(k) for k in ("rtol", "atol", "max_num_steps")})
    per_output = 2 * model.nq + len(model.slack_index) + len(model.output_labels) + 2
    step_s = None
    if measure and s.method in ("rk", "rkc"):
        step_s = cache.memo(model, "step_s", (s.method, s.stages, bool(s.compiled)),     # one cost per model and method
                            lambda: _step_seconds(model, s, x0, output_step, model.parameters(sc)))
    return PlannedRun(n, output_step, int(outputs), int(s.steps_per_output), step_s,
                      run_memory_bytes(outputs, 1, per_output), candidate, s.method, int(s.stages))


def _step_seconds(model, s, x0, output_step: float, p) -> float:
    """Wall time (s) of one step of ``s`` (``rk`` or ``rkc``) on ``model``: whole compiled output intervals from the
    static start ``x0`` for :data:`TIMING_S` (at least 3 calls), the median call (under the machine's present load:
    the budget is of wall time) over its steps."""
    from ..time_domain.integrators import rk4_interval
    f = rk4_interval(model, int(s.steps_per_output), s.compiled, s.stages if s.method == "rkc" else 0
                     ).functions["cablesys_rk4_interval"]
    p = np.concatenate([np.asarray(p, dtype=float), [0.0, 1.0]])
    x, calls, t0 = x0, [], time.perf_counter()
    while len(calls) < 3 or (time.perf_counter() - t0 < TIMING_S and len(calls) < 1000):
        t1 = time.perf_counter()
        x = f(x, 0.0, output_step, p)
        calls.append(time.perf_counter() - t1)
    return float(np.median(calls)) / s.steps_per_output


def _fits(r: PlannedRun) -> bool:
    """Whether ``r`` is within the output and memory limits of :mod:`cablesys.time_domain.record`."""
    from ..time_domain.record import MAX_MEMORY_BYTES, MAX_OUTPUTS
    return r.outputs <= MAX_OUTPUTS and r.memory_bytes <= MAX_MEMORY_BYTES


def _runs(scene: Scene, n: int, cache: RungCache, kw: dict, measure: bool) -> tuple:
    """(runs, statistics step, shared, notes) of the plan at ``n``: the candidate, then the statistics runs at N / 2
    and N / 4 on the :func:`statistics_step` grid, made coarser (an integer fraction of the scene's step) where a grid
    would pass the output or memory limits. On the scene's grid (no ``times`` of the caller's) the candidate runs on
    the statistics grid (``shared``), otherwise on the caller's grid with a statistics run at N besides."""
    from ..time_domain.record import MAX_MEMORY_BYTES, MAX_OUTPUTS
    times = kw.get("times")
    h, duration = scene.numerics.output_step, scene.numerics.duration
    cand = None
    if times is not None:
        t = np.asarray(times, dtype=float)
        cand = _planned_run(scene, n, cache, kw, float(np.min(np.diff(t))), t.size, True, measure)
        if not _fits(cand):
            raise PlanRefused(f"the extrapolation's candidate run at N = {n} on the caller's {cand.outputs} output "
                              f"times needs about {cand.memory_bytes / 1024 ** 3:.3g} GiB, past the limit of one run "
                              f"({MAX_MEMORY_BYTES / 1024 ** 3:.3g} GiB); nothing was run: pass fewer times")
    best = int(round(h / statistics_step(scene)))
    sub, notes = best, []
    while True:
        step = h / sub
        outs = int(math.floor(duration / step + 1e-9)) + 1
        runs = ([_planned_run(scene, n, cache, kw, step, outs, True, measure)] if cand is None else
                [cand, _planned_run(scene, n, cache, checking(kw), step, outs, False, measure)])
        finest = runs[-1].output_step / runs[-1].steps_per_output      # the N run's step on the statistics grid
        runs += [_planned_run(scene, m, cache, checking(kw), step, outs, False, measure, finest)
                 for m in (n // 2, n // 4)]
        if all(_fits(r) for r in runs) or sub == 1:
            break
        worst = max(max(r.outputs / MAX_OUTPUTS, r.memory_bytes / MAX_MEMORY_BYTES) for r in runs)
        sub = max(1, min(sub - 1, int(sub / worst)))
    if not all(_fits(r) for r in runs):
        raise PlanRefused(f"the extrapolation's runs at N = {n}, {n // 2}, {n // 4} pass the limits of one run "
                          f"({MAX_OUTPUTS:.0e} outputs, {MAX_MEMORY_BYTES / 1024 ** 3:.3g} GiB) even at the scene's "
                          "output step; nothing was run: raise numerics.output_step or shorten numerics.duration")
    if sub < best:
        notes.append(f"statistics runs at output step {h / sub:.3g} s, not the {h / best:.3g} s of {SAMPLES_PER_SNAP} "
                     f"samples per axial travel time: the finer grid would pass the limits of one run "
                     f"({MAX_OUTPUTS:.0e} outputs, {MAX_MEMORY_BYTES / 1024 ** 3:.3g} GiB); maxima refined between "
                     "samples (refined_maximum)")
    return runs, h / sub, cand is None, notes


def plan(scene: Scene, choice, cache: RungCache, kw: dict | None = None, measure: bool = True) -> tuple:
    """The extrapolation's plan for ``choice`` (:func:`applies`), checked before any run: (choice, kw).

    Every run (the candidate at N, the statistics runs at N, N / 2, N / 4) is checked against the output and
    memory limits of one run (a statistics grid that would pass them is made coarser, said in ``notes``; a
    candidate that would pass them refuses the plan, :class:`PlanRefused`), its cost predicted (steps x the
    measured per-step cost), and with ``numerics.time_budget_s`` > 0 N halves (down to :data:`MIN_SEGMENTS`)
    until the plan's predicted cost fits the budget, the reason saying what the tolerance's N would cost and
    the a priori error at the N kept (the stated error after the runs is the extrapolation's own); a plan that
    does not fit at MIN_SEGMENTS is refused.

    Parameters
    ----------
    scene : Scene
        The scene.
    choice : Choice
        The segmented choice under partial slack.
    cache : RungCache
        Models (and their compiled code) of the runs.
    kw : dict, optional
        The run options (:func:`run`).
    measure : bool, optional
        Time each run's compiled RK4 step (False: no cost prediction, no budget).

    Returns
    -------
    (Choice, dict)
        The choice (its N and reason changed when the budget shrank the plan) and ``kw`` with
        ``extrapolation_plan`` (a :class:`Plan`; its runs reach summary.json as ``model.extrapolated.plan``).

    Raises
    ------
    PlanRefused
        When no plan fits, before any run.
    """
    kw = dict(kw or {})
    t0 = time.perf_counter()
    budget = float(getattr(scene.numerics, "time_budget_s", 0.0) or 0.0)
    n = choice.segments
    runs, step, shared, notes = _runs(scene, n, cache, kw, measure)
    total = lambda rs: sum(r.predicted_s or 0.0 for r in rs)
    if budget and measure:
        asked, asked_s = n, total(runs)
        while total(runs) > budget - (time.perf_counter() - t0) and n // 2 >= MIN_SEGMENTS:
            n //= 2
            runs, step, shared, notes = _runs(scene, n, cache, kw, measure)
        if total(runs) > budget - (time.perf_counter() - t0):
            raise PlanRefused(f"time budget {budget:g} s: the extrapolation at N = {n // 4}, {n // 2}, {n} is predicted "
                              f"to take {total(runs):.3g} s (the tolerance's N = {asked}: {asked_s:.3g} s); nothing was "
                              "run: raise numerics.time_budget_s (--time-budget) or loosen numerics.model_tolerance")
        if n != asked:
            e = est.segmented_error(choice.numbers["estimates"], n)
            note = (f"time budget {budget:g} s: the tolerance's N = {asked} is predicted to take {asked_s:.3g} s; "
                    f"planned N = {n} instead ({total(runs):.3g} s predicted; a priori first-order error at N = {n} "
                    f"body {e['body']:.2g}, tension {e['tension']:.2g}; the stated error is the extrapolation's)")
            notes.append(note)
            choice = dataclasses.replace(choice, segments=n, reason=f"{choice.reason}; {note}",
                                         estimated_error={"body": e["body"], "tension": e["tension"]})
    kw["extrapolation_plan"] = Plan(runs, step, scene.numerics.output_step, shared, budget, notes, t0)
    return choice, kw


def _admits(scene: Scene, plan_: Plan, n2: int, cache: RungCache, kw: dict, known: dict) -> str:
    """"" when the plan may double to ``n2`` (its runs fit the limits and the budget left), else the reason it may not.
    Admitted, its runs are added to ``plan_``: the run at ``n2`` or, when the limits need a coarser statistics grid
    at ``n2``, all three on that grid (the statistics made on the finer one, ``known``, are dropped, said in
    ``plan_.notes``)."""
    try:
        runs, step, _, notes = _runs(scene, n2, cache, kw, True)
    except PlanRefused as err:
        return f"N would double to {n2}, but {err}"
    regrid = abs(step - plan_.statistics_step) > 1e-12 * step
    new = runs if regrid else [r for r in runs if r.segments == n2]
    need = sum(r.predicted_s or 0.0 for r in new)
    left = plan_.remaining_budget_s()
    if need > left:
        return (f"N would double to {n2} (predicted {need:.3g} s), beyond the {max(left, 0.0):.3g} s left of the time "
                f"budget {plan_.budget_s:g} s")
    if regrid:
        known.clear()
        plan_.statistics.clear()
        plan_.statistics_step = step
        plan_.notes.extend(f"from N = {n2}: {note}" for note in notes)
    plan_.runs.extend(new)
    return ""


def statistics_step(scene: Scene) -> float:
    """Output step (s) of the runs whose statistics are extrapolated: the scene's, or the largest integer
    fraction of it within the axial travel time / SAMPLES_PER_SNAP. A snap load lasts about the axial
    wave's travel time along the cable, sum L sqrt(m / AE) (300 m of steel wire: 0.075 s); a sampled
    maximum of a coarser series depends on where the samples fall (at the scene file's 0.05 s the
    extrapolated top maximum was 15 % low and not convergent), and the parabola through the largest of
    6 samples per pulse and its neighbours (:func:`refined_maximum`) gives its peak."""
    travel = sum(s.cable.length * math.sqrt(s.cable.mass_per_length / s.cable.ae) for s in scene.sections)
    h = scene.numerics.output_step
    return h / max(1, math.ceil(h * SAMPLES_PER_SNAP / travel - 1e-9))


def until_done(scene: Scene, choice, tol, result, cache: RungCache, kw: dict | None = None) -> tuple:
    """(result, choice) after the coarse runs and the extrapolation (:func:`complete`) of ``result``, the
    run at ``choice.segments`` (by :func:`run`), N doubling (one more run each) while :func:`complete` asks."""
    known: dict = {}
    before = None                # (result, choice) of the last N that extrapolated: kept if a doubled run fails
    while True:
        if before is not None and not result.success:
            r0, c0 = before
            c0, _, _ = complete(scene, c0, r0, tol, cache, kw, known, double=False)
            note = (f"; N = {choice.segments} failed ({result.message}): the N = {c0.segments} run and the "
                    f"extrapolation of N = {c0.segments // 4}, {c0.segments // 2}, {c0.segments} are kept")
            return r0, dataclasses.replace(c0, reason=c0.reason + note)
        new, _, again = complete(scene, choice, result, tol, cache, kw, known)
        if not again:
            return result, new
        before = (result, choice)
        choice = new
        result = run(scene, choice.segments, cache, kw)


def describe(choice_dict: dict, fmt, seg: str) -> str:
    """The console line of an extrapolated result (:func:`.auto.describe`): the extrapolated statistics'
    estimated error first, the N run's time series' own next, then the reason."""
    e, ts = choice_dict.get("estimated_error", {}), choice_dict.get("estimated_error_time_series", {})
    ns = ", ".join(str(n) for n in choice_dict["extrapolated"]["segments"])
    return (f"model {choice_dict.get('name')}{seg}, statistics extrapolated from N = {ns}: estimated error of the "
            f"extrapolated statistics body {fmt(e.get('body'))}, tension {fmt(e.get('tension'))} (the N = "
            f"{choice_dict['segments']} time series: body {fmt(ts.get('body'))}, tension {fmt(ts.get('tension'))}); "
            f"{choice_dict.get('reason', '')}")


def model_dict(choice) -> dict:
    """``choice.as_dict()`` with, after an extrapolation, ``extrapolated`` (the block of :func:`extrapolate`),
    ``estimated_error_time_series`` (the N run's own estimated error), ``estimated_error_per_quantity`` (each
    extrapolated number's) and ``estimated_error_refers_to``."""
    d = choice.as_dict()
    per = choice.numbers.get("per_quantity")
    d["checked"] = ("a posteriori: N = {0} against N = {1}".format(choice.numbers["checked_n"], choice.numbers["checked_n"] // 2)
                    if per is not None and choice.numbers.get("checked_n") == choice.segments
                    else "extrapolated" if choice.numbers.get("extrapolated") is not None
                    else "a priori only: unchecked")
    if per is not None and d["checked"].startswith("a posteriori"):
        d["estimated_error_per_quantity"] = {k: float(v) for k, v in per.items()}
        if "integration" in choice.numbers:      # the integration part of those, and its rtol pair (:mod:`.checks`)
            d["integration_check"] = choice.numbers["integration"]
    static = choice.numbers.get("static_errors")
    if static is not None:      # the mean shape checked before the run (:mod:`.static_check`)
        d["static_shape_error"] = {"segments": static["segments"], "reference_segments": static["reference_segments"],
                                   **{k: float(v) for k, v in static["errors"].items()}}
    block = choice.numbers.get("extrapolated")
    if block is not None:
        d.update(estimated_error_refers_to="the extrapolated statistics (model.extrapolated.statistics)",
                 estimated_error_time_series=dict(block["time_series_error"]), extrapolated=block)
        if "estimated_error_per_quantity" in block:     # each extrapolated number's own (richardson.extrapolate)
            d["estimated_error_per_quantity"] = {k: float(v) for k, v in block["estimated_error_per_quantity"].items()}
    return d


def complete(scene: Scene, choice, result, tol, cache: RungCache, kw: dict | None = None,
             known: dict | None = None, double: bool = True) -> tuple:
    """After the run at ``choice.segments``: the coarse runs, the extrapolated block, and whether N must double.

    Parameters
    ----------
    scene : Scene
        The scene.
    choice : Choice
        The segmented choice (:func:`applies`).
    result : TimeResult
        Its run at N (by :func:`run`, or streamed with :func:`stream_options`).
    tol : (float, float)
        Body and tension tolerances.
    cache : RungCache
        Models and simulators of the coarse runs.
    kw : dict, optional
        Run options (see :func:`run`; ``on_block`` and ``progress`` are not passed to the coarse runs).
    known : dict, optional
        {N: statistics} of runs already made (updated in place).
    double : bool, optional
        False: never ask for 2 N (the result at N is final).

    Returns
    -------
    (Choice, dict or None, bool)
        The updated choice (``estimated_error``: the extrapolated statistics'; ``numbers["extrapolated"]``:
        the block, see :func:`extrapolate`, with ``window_s`` and ``wall_s`` of the coarse runs), the
        block (None when a run failed: the choice is returned with its first-order a-priori estimate),
        and True when the runs are not in the asymptotic range or miss the tolerance and N can double
        (the caller runs 2 N and calls again with ``known``).
    """
    known = {} if known is None else known
    period, ramp = metrics.forcing_period(scene), scene.top_motion.effective_ramp_s
    n = choice.segments
    if not result.success:
        return choice, None, False
    plan_ = (kw or {}).get("extrapolation_plan")
    fine = scene.with_numerics(output_step=statistics_step(scene) if plan_ is None else plan_.statistics_step)
    coarse_kw = checking(kw or {})
    if plan_ is not None:
        known.update({m: v for m, v in plan_.statistics.items() if m not in known})
    if n not in known and fine.numerics.output_step == scene.numerics.output_step and (kw or {}).get("times") is None:
        known[n] = statistics(result, period, ramp)
    for m in (n, n // 2, n // 4):       # the N run again only when its output step does not resolve the snaps
        if m not in known:
            r = run(fine, m, cache, coarse_kw, candidate=False)
            if not r.success:
                reason = choice.reason + f"; extrapolation failed: the run at N = {m} failed ({r.message})"
                return dataclasses.replace(choice, reason=reason), None, False
            known[m] = statistics(r, period, ramp)
    block = extrapolate(known, n, max(s.cable.tension_floor for s in scene.sections))
    w = metrics.window(np.asarray(result.time), period, ramp)
    block["window_s"] = [float(np.asarray(result.time)[w][0]), float(result.time[-1])]
    e = block["estimated_error"]
    stop = ""
    again = needs_doubling(block, tol)             # sets block["settled_in_noise"]
    if double and again and 2 * n <= MAX_SEGMENTS:
        stop = "" if plan_ is None else _admits(scene, plan_, 2 * n, cache, checking(kw or {}), known)
        if not stop:
            return dataclasses.replace(choice, segments=2 * n), block, True
    if plan_ is not None:
        block["plan"] = plan_.as_dict()
    reason = (choice.reason + f"; statistics extrapolated (Richardson, order 1) from N = {n // 4}, {n // 2}, {n}: "
              f"estimated error of the extrapolated statistics body {e['body']:.2g}, tension {e['tension']:.2g} "
              f"(their difference to the limits of N = {n // 4}, {n // 2} x {block['remainder_factor']:.3g}); the time "
              f"series is the N = {n} run's, estimated error body {block['time_series_error']['body']:.2g}, "
              f"tension {block['time_series_error']['tension']:.2g}")
    if stop:
        reason += f"; {stop}"
    orders = ", ".join(f"{k} {v:.2g}" if v is not None else f"{k} n/a" for k, v in block["leading_orders"].items())
    if block["kept_converging"]:
        reason += (f"; observed orders {orders} above {ORDER_RANGE}, the differences of one sign: converging faster than "
                   "first order, the stated error is the conservative one (the whole difference of the two limits, at "
                   "least the extrapolation's correction) and N was not doubled")
    elif block["settled_in_noise"]:
        reason += (f"; observed orders {orders} outside {ORDER_RANGE}, but the whole differences of the runs are below "
                   f"{NOISE_FRACTION:g} x the tolerance, where their order is that of the time-step and sampling errors: "
                   "the stated error is the conservative one (the whole difference of the two limits, at least the "
                   "extrapolation's correction) and N was not doubled")
    elif not block["asymptotic"]:
        reason += (f"; NOT in the asymptotic range (observed orders {orders}): the stated error is the larger of the "
                   "whole difference of the two limits and the extrapolation's correction; a statistics window that "
                   "still holds the start-up transient does not converge smoothly in N (slack scenes settle slowly): "
                   "a longer duration helps")
        warnings.warn(f"model auto: {reason}", NumericalWarning, stacklevel=3)
    elif not within(e, tol):
        warnings.warn(f"model auto: tolerance not reached at N = {n}: {reason}", NumericalWarning, stacklevel=3)
    numbers = dict(choice.numbers, extrapolated=block)
    return dataclasses.replace(choice, reason=reason, estimated_error=dict(e), numbers=numbers), block, False
