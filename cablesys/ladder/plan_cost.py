"""The cost of a ladder run predicted before its model is built: elements, operations, steps, compile time,
memory of the outputs and wall time; and the time budget's limit on it.

Every time-domain run the ladder plans gets a :class:`Prediction` (:func:`predict`) after the choice and before
anything of the run is built; ``numerics.time_budget_s`` (``--time-budget``) > 0 refuses a run predicted past it
(:func:`check_budget`, :class:`~.extrapolation.PlanRefused`: the tool's plan, not the user's input), naming the
prediction and what would fit. The slack extrapolation plans its runs itself (:func:`.extrapolation.plan`: steps at
the stable step x a measured per-step cost); its prediction is read from that plan (:func:`from_plan`), not made
twice.

Operations (:func:`run_operations`): the ODE's plus the outputs' SX operations of the built model. The structural
part is :func:`.choice.model_operations` (the large-N fits the size limit uses); the run's count adds what that
fit leaves out at small N, each per section, counted on built models (``studies/run_prediction.py``, Dale scene,
heave_300m, the heavy wire, rov_lift, the sheared current): the quasi-static segmented cable QS_OPERATIONS_PER_ELEMENT
x N (its outputs, linear in N: 7.3 k, 18.4 k, 73 k actual at N = 4, 8, 16 against 1.4 k, 9.2 k, 62 k of the
N^2.75 fit) and never below QS_OPERATIONS_FLOOR (its straight cable, N = 1: 7.1-7.3 k); Wang's straight cable
STRAIGHT_OPERATIONS (2.1-2.2 k); the node model NODE_OPERATIONS_BASE besides 600 per element (3.2 k at N = 4,
10.8 k at N = 16); and TOP_OPERATIONS_PER_COMPONENT per harmonic of the top motion (rov_lift's 58-component sea
added 1.6 k to Wang's 2.2 k).

Steps. Fixed-step methods (``rk``, ``rkc``, ``collocation``): exactly steps_per_output x output intervals, i.e.
duration / step. Adaptive methods: from the tolerance and the forcing period, a fit to counted steps (Dale scene,
120 s, 21.8 forcing periods, ``studies/results/run_prediction_calibration.json``):

    steps = periods x STEPS_PER_PERIOD[method] x (rtol / 1e-4)^(-RTOL_EXPONENT) x (elements / 4)^ELEMENT_EXPONENT

BDF2 at rtol 1e-4: 320, 484, 705, 962 steps per period at N = 4, 8, 16, 32 (x N^0.55); 1e-4 -> 1e-5 multiplied
the steps by 1.55-2.0 (an accuracy-limited p = 2 method would give 10^(1/3) = 2.15: part of the steps are set by
the element modes, not by the tolerance), hence the exponent 1/4. rk23 (quasi-static rung): 142, 186 steps per
period at N = 4, 8 (x N^0.39). Its accuracy is O((h omega)^p) per step (:mod:`.stiffness`), so steps scale with
the number of forcing periods; a scene without a period (a sea state) takes its peak period.

The quasi-static segmented cable's method is known only once its model is built: its stiffness guard
(:mod:`.stiffness`) accepts the explicit pair or hands the run to CVODES, whose dense Jacobian costs more per step
and far more C (QS_IMPLICIT_STEPS, IMPLICIT_STEP_S_PER_MB, measured on the heavy wire and the sheared current,
where the guard refused rk23). Unless the caller named the method, its prediction is the middle of the two
(geometric for steps and stepping time, arithmetic for the compile), each of which was within 3x of the middle on
the six scenes; the line names both methods. How good it is: ``studies/run_prediction.py`` reports the ratio
actual / predicted on six scenes.

Wall time per step: STEP_OVERHEAD_S + operations x SECONDS_PER_OPERATION (compiled C or CasADi's VM), fitted to
the same Dale runs (BDF2 compiled N = 4, 8, 16, the VM at N = 32, rk23 compiled N = 4, 8; the measured times are in
``studies/results/run_prediction_calibration.json``).

Compile time (a model compiled and not yet in the cache, :func:`compile_plan`): a run compiles two libraries, its
integrator's (the DAE; with its state Jacobian for an implicit method) and its outputs', and the quasi-static
segmented cable stepped by the explicit pair a third, its stiffness guard's probe; the C of each is predicted from
the operations (bytes of C per operation, measured on the same cold-cache builds: outputs 14-21, an explicit DAE
7-10, the guard's probe 40, an implicit node-model DAE with its banded Jacobian 80 (past COMPILE_MAX_ELEMENTS the
DAE and Jacobian from the element kernel: 7, the harsh-sea ROV lift at N = 46), the quasi-static cable's dense
one 290 at N = 14, i.e. about 20 N), its flags chosen by size as :func:`cablesys.compiled.compiler_command` does,
and its time is :func:`cablesys.compiled.predicted_compile_s` (the same prediction the compile's own progress
lines give). The slack extrapolation compiles, per run of its plan, the outputs and an RK4 interval of its N.
Whether a library is already cached is known only once the functions are built (their hash): the line says "if
not cached". Not counted: what the model choice itself compiles before the prediction is made (the linearization
and the describing function's harmonic balance on a cold cache, reported apart by the study).

Memory: :func:`cablesys.time_domain.record.run_memory_bytes` of the output grid, with 2 nq + outputs numbers per
output time (nq = 2 per node-model element, 1 per quasi-static element, 2 for Wang's cable, per section).
"""

from __future__ import annotations

import dataclasses
import logging
import math

from ..compiled import SIZE_FLAGS, compiles, predicted_compile_s
from ..model.segmented import has_kernel
from ..scene import Scene
from ..time_domain.integrators import COMPILE_MAX_ELEMENTS, FIXED_LOOPS, kernel_method
from .choice import model_operations
from .rung.base import cables
from .rungs import rung_scene

log = logging.getLogger(__name__)

FIXED_STEP = ("rk", "rkc", "collocation")
# adaptive methods: steps per forcing period at rtol 1e-4 and 4 elements, and their N exponent (Dale fits, above)
STEPS_PER_PERIOD = {"cvodes-bdf2": (320.0, 0.55), "cvodes": (320.0, 0.55), "idas": (320.0, 0.55),
                    "cvodes-adams": (320.0, 0.55), "rk23": (142.0, 0.39), "dopri5": (92.0, 0.39)}
# the quasi-static segmented cable stepped by CVODES (BDF2) once its guard refuses the explicit pair: 52 steps per
# period on the heavy wire (N = 6, rtol 1e-4), 137 in the sheared current (N = 14, rtol 1e-5), i.e. 40 at N = 4
QS_IMPLICIT_STEPS = (40.0, 0.55)
# its wall time per step over the MB of its implicit DAE's C (the dense Jacobian; studies/results/run_prediction.json)
IMPLICIT_STEP_S_PER_MB = 2e-5
RTOL_EXPONENT = 0.25
STEP_OVERHEAD_S = 5e-6                                  # per step, compiled (CVODES's own work, the call)
SECONDS_PER_OPERATION = {True: 3.5e-10, False: 3.0e-9}  # per step and operation: compiled C, CasADi VM
# operations besides choice.model_operations, per section (the module docstring)
QS_OPERATIONS_PER_ELEMENT = 1500.0
QS_OPERATIONS_FLOOR = 7200.0
STRAIGHT_OPERATIONS = 2100.0
NODE_OPERATIONS_BASE = 800.0
TOP_OPERATIONS_PER_COMPONENT = 30.0
# bytes of generated C per operation of each library (the module docstring), and bytes of C per byte of the
# functions' serialized form, by which compiler_command chooses the flags (SIZE_FLAGS): the outputs and the explicit
# integrators' functions serialize long for their C (0.13 MB of outputs' C compiled at -O1: serialized > 0.4 MB),
# an implicit DAE's Jacobian generates much C (0.46 MB at -O2, 18.5 MB at -O0)
OUTPUT_BYTES_PER_OP = {"quasi-static": 20.0, "other": 13.0}
EXPLICIT_BYTES_PER_OP = 10.0
PROBE_BYTES_PER_OP = 40.0
IMPLICIT_BYTES_PER_OP = 80.0
KERNEL_DAE_BYTES_PER_OP = 7.0       # the node model's DAE and Jacobian from its element kernel (kernel_compiled)
QS_IMPLICIT_BYTES_PER_ELEMENT = 20.0
RK4_INTERVAL_BYTES = 30_000.0                           # the extrapolation's compiled RK4 interval (0.03 MB seen)
C_PER_SERIALIZED = {"outputs": 0.3, "explicit": 0.3, "implicit": 1.6, "rk4": 1.0}
EXPLICIT = ("rk", "rkc", "rk23", "dopri5")
OUTPUT_LABELS = 24                                      # series per output time besides the states (about)


@dataclasses.dataclass(frozen=True)
class Prediction:
    """A run's cost predicted before it is built.

    ``what`` the run ("segmented N = 64"); ``elements`` over all sections; ``operations`` of the generated functions;
    ``method``; ``steps`` (integrator steps; ``steps_from`` says how they were predicted); ``compiled`` whether the
    model runs as compiled C; ``compile_s`` the compile's predicted wall time if not cached (s; 0 for the VM);
    ``memory_bytes`` of the output series; ``run_s`` the stepping's predicted wall time (s); ``runs`` how many runs
    the plan holds (the extrapolation: 3 or 4; their sum is ``run_s``).
    """

    what: str
    elements: int
    operations: float
    method: str
    steps: int
    steps_from: str
    compiled: bool
    compile_s: float
    memory_bytes: float
    run_s: float
    runs: int = 1

    @property
    def wall_s(self) -> float:
        """Predicted wall time of build and run (s), the compile counted as not cached."""
        return self.compile_s + self.run_s

    def line(self) -> str:
        """The console line before the build: "building segmented N = 64: about 38 k operations, compile about 12 s
        if not cached; run about 20 k steps (rk, duration / step), about 6 s; outputs 3.1 MB"."""
        comp = f"compile about {self.compile_s:.2g} s if not cached" if self.compiled else "no compile (CasADi VM)"
        runs = f" over {self.runs} runs" if self.runs > 1 else ""
        return (f"building {self.what}: about {_k(self.operations)} operations, {comp}; run about {_k(self.steps)} "
                f"steps{runs} ({self.method}, {self.steps_from}), about {self.run_s:.2g} s; outputs "
                f"{self.memory_bytes / 1e6:.2g} MB")

    def as_dict(self) -> dict:
        """JSON-able numbers for summary.json's model block (``prediction``)."""
        d = dataclasses.asdict(self)
        d["wall_s"] = self.wall_s
        return d


def _k(x: float) -> str:
    return f"{x / 1e3:.3g} k" if x >= 1e3 else f"{x:.3g}"


def predicted_steps(scene_run: Scene, method: str, rtol: float, elements: int, steps_per_output: int) -> tuple:
    """(steps, how) of a run of ``scene_run`` with ``method``: fixed-step methods steps_per_output x output intervals
    (duration / step, exact); adaptive ones from the forcing periods and rtol (the module docstring's fit)."""
    outputs = len(scene_run.output_times)
    if method in FIXED_STEP:
        return int(steps_per_output) * (outputs - 1), "duration / step"
    k, alpha = STEPS_PER_PERIOD.get(method, STEPS_PER_PERIOD["cvodes"])
    period = scene_run.top_motion.forcing_period_s or scene_run.numerics.duration
    periods = scene_run.numerics.duration / period
    steps = periods * k * (max(rtol, 1e-14) / 1e-4) ** (-RTOL_EXPONENT) * (max(elements, 1) / 4.0) ** alpha
    return int(math.ceil(steps)), f"from rtol {rtol:.2g} and {periods:.3g} forcing periods"


def step_seconds(operations: float, compiled: bool) -> float:
    """Predicted wall time (s) of one integrator step of a model of ``operations`` operations."""
    return STEP_OVERHEAD_S + operations * SECONDS_PER_OPERATION[bool(compiled)]


def run_operations(scene_run: Scene, name: str, segments: int) -> float:
    """Predicted SX operations of the ODE plus the outputs of rung ``name`` at ``segments`` elements per section
    (the module docstring)."""
    n, sections = max(int(segments), 1), len(cables(scene_run))
    base = model_operations(scene_run, name, n)
    if name == "quasi-static":
        base = max(base + sections * QS_OPERATIONS_PER_ELEMENT * n, sections * QS_OPERATIONS_FLOOR)
    elif n == 1:
        base = sections * STRAIGHT_OPERATIONS
    else:
        base += sections * NODE_OPERATIONS_BASE
    tm = scene_run.top_motion
    components = sum(len(getattr(tm, axis, ()) or ()) for axis in ("x", "y", "z"))
    return base + TOP_OPERATIONS_PER_COMPONENT * components


def _flags(c_bytes: float, kind: str) -> list:
    """The optimization flag :func:`cablesys.compiled.compiler_command` would choose for ``c_bytes`` of C of a library
    of ``kind`` (a key of C_PER_SERIALIZED)."""
    serialized = c_bytes / C_PER_SERIALIZED[kind]
    return [next(flag for limit, flag in SIZE_FLAGS if serialized < limit)]


def compile_seconds(libraries) -> float:
    """Predicted wall time (s) of compiling ``libraries`` ((kind, bytes of C) each) on a cold cache:
    :func:`cablesys.compiled.predicted_compile_s` of each with the flags its size gets."""
    return float(sum(predicted_compile_s(b, _flags(b, kind)) for kind, b in libraries))


def compile_plan(operations: float, name: str, method: str, segments: int, kernel: bool = False) -> tuple:
    """The libraries ((kind, predicted bytes of C) each) a run of ``name`` at ``segments`` stepped by ``method``
    compiles (the module docstring; ``kernel``: its DAE is the element kernel's, :func:`kernel_compiled`)."""
    libs = [("outputs", OUTPUT_BYTES_PER_OP["quasi-static" if name == "quasi-static" else "other"] * operations)]
    if kernel and method not in FIXED_LOOPS:
        libs.append(("implicit", KERNEL_DAE_BYTES_PER_OP * operations))
    elif method in EXPLICIT:
        libs.append(("explicit", EXPLICIT_BYTES_PER_OP * operations))
        if name == "quasi-static" and segments > 1:
            libs.append(("explicit", PROBE_BYTES_PER_OP * operations))
    else:
        per = max(IMPLICIT_BYTES_PER_OP, QS_IMPLICIT_BYTES_PER_ELEMENT * segments) if name == "quasi-static" \
            else IMPLICIT_BYTES_PER_OP
        libs.append(("implicit", per * operations))
    return tuple(libs)


def compile_guess(operations: float, name: str, method: str, segments: int) -> float:
    """Predicted compile time (s, cold cache) of a run of ``name`` with ``method``. The quasi-static segmented cable
    given the explicit pair before its stiffness guard has seen the built model (:func:`for_run`) may yet be stepped
    by CVODES, whose dense Jacobian is the larger library (18.5 MB of C at N = 14 in a sheared current, against
    2 MB for the explicit pair's): the mean of the two, each measured to be within 3x of it."""
    explicit = compile_seconds(compile_plan(operations, name, method, segments))
    if name != "quasi-static" or method not in EXPLICIT or segments < 2:
        return explicit
    return 0.5 * (explicit + compile_seconds(compile_plan(operations, name, "cvodes", segments)))


def state_count(scene_run: Scene, name: str, segments: int) -> int:
    """2 nq of a rung's model before it is built (the module docstring): per section the node model's dim N node
    coordinates, the quasi-static segmented cable's (dim - 1) N angles, a straight cable's dim (angles and stretch;
    dim = 3 in a 3-D scene, else 2)."""
    dim = 3 if getattr(scene_run, "three_d", False) else 2
    per = {"segmented": dim * segments, "quasi-static": (dim - 1) * segments}.get(name, dim)
    return 2 * per * len(cables(scene_run))


def predict(scene: Scene, choice, settings, guard_decides: bool = False) -> Prediction:
    """The :class:`Prediction` of the run of ``choice`` (a ladder :class:`~.choice.Choice`) with ``settings`` (its
    :class:`~cablesys.time_domain.IntegratorSettings`, from :func:`.run_settings.integrator_settings`), before its
    model is built. ``guard_decides``: the quasi-static segmented cable's explicit method is a guess its stiffness
    guard may overturn once the model is built (the module docstring: the middle of the two paths)."""
    from ..time_domain.record import run_memory_bytes
    n = max(int(choice.segments), 1)
    sc = rung_scene(scene, choice.name, n)
    elements = n * len(cables(sc))
    ops = run_operations(sc, choice.name, n)
    method = str(settings.method)
    steps, how = predicted_steps(sc, method, float(settings.rtol), elements, int(settings.steps_per_output))
    compiled = bool(settings.compiled)
    outputs = len(sc.output_times)
    memory = run_memory_bytes(outputs, len(cables(sc)), state_count(sc, choice.name, n) + OUTPUT_LABELS)
    what = choice.name + (f" N = {n}" if n > 1 else "")
    run_s = steps * step_seconds(ops, compiled)
    compile_s = compile_guess(ops, choice.name, method, n) if compiled else 0.0
    if guard_decides and choice.name == "quasi-static" and n > 1 and method in EXPLICIT:
        k, alpha = QS_IMPLICIT_STEPS
        period = sc.top_motion.forcing_period_s or sc.numerics.duration
        steps_i = (sc.numerics.duration / period) * k * (max(float(settings.rtol), 1e-14) / 1e-4) ** (-RTOL_EXPONENT) \
            * (max(elements, 1) / 4.0) ** alpha
        [(_, jac_bytes)] = [lib for lib in compile_plan(ops, choice.name, "cvodes", n) if lib[0] == "implicit"]
        run_i = steps_i * (step_seconds(ops, compiled) + IMPLICIT_STEP_S_PER_MB * jac_bytes / 1e6)
        steps, run_s = int(math.ceil(math.sqrt(steps * steps_i))), math.sqrt(run_s * run_i)
        method, how = f"{method} or cvodes-bdf2", f"{how}; the middle of both methods, the stiffness guard decides"
    else:
        kernel = elements > COMPILE_MAX_ELEMENTS and kernel_compiled(sc, choice.name, method)
        compile_s = compile_seconds(compile_plan(ops, choice.name, method, n, kernel)) if compiled else 0.0
    return Prediction(what, elements, ops, method, steps, how, compiled, compile_s, memory, run_s)


def from_plan(scene: Scene, choice, plan) -> Prediction:
    """The :class:`Prediction` of the slack extrapolation's plan (:class:`.extrapolation.Plan`): its runs' steps and
    predicted times (stable step x measured per-step cost), the candidate's operations and memory. The element
    kernel is compiled while planning (the per-step cost is measured on it); each run then compiles its outputs and
    its RK4 interval (the module docstring)."""
    n = int(choice.segments)
    sc = rung_scene(scene, "segmented", n)
    runs = plan.runs
    compiled = compiles()
    libs = [("outputs", OUTPUT_BYTES_PER_OP["other"] * run_operations(sc, "segmented", r.segments)) for r in runs]
    libs.append(("rk4", RK4_INTERVAL_BYTES))          # the candidate's interval on its grid (the others: planning's)
    return Prediction(f"segmented N = {n} (extrapolation)", n * len(cables(sc)),
                      run_operations(sc, "segmented", n), runs[0].method,
                      sum(r.steps for r in runs), "duration / stable step", compiled,
                      compile_seconds(libs) if compiled else 0.0,
                      max(r.memory_bytes for r in runs), float(sum(r.predicted_s or 0.0 for r in runs)), len(runs))


def check_budget(scene: Scene, prediction: Prediction, budget_s: float | None = None) -> None:
    """Refuse (:class:`~.extrapolation.PlanRefused`) before any build a run predicted past ``budget_s`` (default the
    scene's ``numerics.time_budget_s``; 0: none), naming the prediction and what would fit."""
    from .extrapolation import PlanRefused
    budget = float(getattr(scene.numerics, "time_budget_s", 0.0) or 0.0) if budget_s is None else float(budget_s)
    if not budget or prediction.wall_s <= budget:
        return
    cheaper = []
    if prediction.compile_s > 0 and prediction.run_s <= budget:
        cheaper.append("a second run once the model is in the cache (no compile)")
    if prediction.method not in FIXED_STEP:
        cheaper.append("a looser numerics.model_tolerance (fewer elements, a looser rtol)")
    else:
        cheaper.append("a looser numerics.model_tolerance (fewer elements) or a shorter numerics.duration")
    raise PlanRefused(
        f"time budget {budget:g} s: {prediction.what} is predicted to take about {prediction.wall_s:.3g} s (compile "
        f"{prediction.compile_s:.2g} s if not cached, {prediction.steps} steps of {prediction.method} "
        f"{prediction.run_s:.2g} s); nothing was built: raise numerics.time_budget_s (--time-budget), or what "
        f"would fit: {'; '.join(cheaper)}")


def kernel_compiled(scene_run: Scene, name: str, method: str) -> bool:
    """Whether a run of rung ``name`` on ``scene_run`` past COMPILE_MAX_ELEMENTS elements is compiled all the same,
    known before its model is built: the node model ("segmented") of a scene with its element-kernel form
    (:func:`cablesys.model.segmented.has_kernel`) stepped by a method that steps that kernel compiled
    (:func:`cablesys.time_domain.integrators.kernel_method`), as
    :func:`cablesys.time_domain.integrators.compiled_by_default` decides once it is built."""
    return (name == "segmented" and getattr(scene_run, "system", None) is None and has_kernel(scene_run)
            and kernel_method(method))


def for_run(scene: Scene, choice, tol, kw: dict) -> Prediction | None:
    """The :class:`Prediction` of the ladder's run of ``choice`` with the caller's options ``kw`` (``method``,
    ``rtol``, ``atol``, ``times``): the settings :func:`.run_settings.integrator_settings` gives it, the quasi-static
    rungs with QUASI_STATIC_METHOD (the method their guard, which needs the built model, accepts first). None for
    a run with no time-domain model to predict (the frequency and steady rungs, a registered rung)."""
    from .rungs import TIME_DOMAIN_RUNGS
    from .run_settings import QUASI_STATIC_METHOD, integrator_settings, stated_room
    if choice.name not in TIME_DOMAIN_RUNGS:
        return None
    sc = rung_scene(scene, choice.name, choice.segments)
    elements = sum(c.segments for c in cables(sc))
    s = integrator_settings(sc, tol, elements, method=kw.get("method"), rtol=kw.get("rtol"), atol=kw.get("atol"),
                            rung=None, stated=stated_room(choice))
    s = dataclasses.replace(s, compiled=bool((s.compiled or kernel_compiled(sc, choice.name, str(s.method)))
                                             and compiles()))
    guessed = choice.name == "quasi-static" and kw.get("method") is None and s.method not in FIXED_STEP and s.compiled
    if guessed:
        s = dataclasses.replace(s, method=QUASI_STATIC_METHOD)     # uncompiled, the guard falls back to CVODES
    times = kw.get("times")
    if times is not None:      # the caller's grid: its outputs and span
        import numpy as np
        t = np.asarray(times, dtype=float)
        scene = scene.with_numerics(duration=float(t[-1] - t[0]) or scene.numerics.duration,
                                    output_step=float(np.min(np.diff(t))) if t.size > 1 else scene.numerics.output_step)
    return predict(scene, choice, s, guard_decides=guessed)


def announce(prediction: Prediction | None, kw: dict) -> None:
    """Hand ``prediction`` to the caller's ``on_plan`` (the ``run`` command prints :meth:`Prediction.line`) and the
    log, before the build."""
    if prediction is None:
        return
    log.info("%s", prediction.line())
    on_plan = kw.get("on_plan")
    if on_plan is not None:
        on_plan(prediction)
