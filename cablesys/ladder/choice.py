"""``choose(scene, tolerance)``: the cheapest rung whose estimated error is within the tolerance.

The ladder, cheapest first: frequency (a steady amplitude only) < quasi-static (straight, N = 1) < wang
(the two swap when the stretch is within STIFF_RATIO of the forcing, or when nothing drives the swing)
< quasi-static segmented (N elements, their stretches following the tension) < segmented (N, the node
model, every element stretch stepped). The quasi-static segmented cable replaces the segmented one where
the stretch is stiff (omega/omega_ax <= 1/STIFF_RATIO) and the cable stays taut: it steps no stretch modes and
its tension extremes carry no element-stretch ringing; compiled, it
also competes by cost where the stretch is not that stiff, stepped by the rk23 pair (:func:`element_plan`), and N
is the least within SAFETY x the tolerance or the least within it, whichever costs less; every N >= 4 is
checked a posteriori on every reported quantity (:func:`cablesys.ladder.auto.richardson_step`). The cost weights
below are relative run times measured by ``studies/model_ladder.py`` (its JSON records them and the machine).

The estimates speak of the settled forced response: a scene whose statistics window (:func:`.metrics.window`)
starts before :func:`.estimate.settling_time` gets a note in the reason (:func:`settling_note`).
"""

from __future__ import annotations

import dataclasses
import math
import warnings

from ..compiled import compiles
from ..errors import NumericalWarning, ParameterError
from ..model import build_model
from ..model.segmented import drag_points
from ..scene import Scene
from . import estimate as est
from . import metrics
from .indicators import scene_numbers
from .rung.base import cables, scene_segments, three_d, with_segments
from .rung.quasistatic import (  # noqa: F401 - the plans' weights
    EXPLICIT_COST,
    EXPLICIT_COST_MAX_ELEMENTS,
    SPACE_COST_FACTOR,
    STIFF_QS_COST,
)
from .rung.segmented import CHECK_ACCEPT, CHECK_COST  # noqa: F401 - re-exported with the plans' other numbers
from .rungs import BUILTIN, Assessment, RungCache, get_rung, registered_rungs, rung_scene, validity
from .stiffness import EXPLICIT_MAX_ELEMENTS

DEFAULT_TOLERANCE = 0.01          # body motion; tension extremes get twice this
MAX_SEGMENTS = 128
SLACK_MAX_SEGMENTS = 40     # snap-load runs cost ~N^2 (300 m wire, T = 6 s, 30 s: 16 min at N = 40)


@dataclasses.dataclass(frozen=True)
class Choice:
    """The rung to run, why, and its estimated error against the converged segmented cable."""

    name: str
    segments: int
    reason: str
    estimated_error: dict            # {"body": e, "tension": e}
    numbers: dict                    # the deciding numbers and every rung's estimate

    def as_dict(self) -> dict:
        """``{name, segments, reason, estimated_error}`` for summary.json."""
        return {"name": self.name, "segments": self.segments, "reason": self.reason,
                "estimated_error": {k: _finite(v) for k, v in self.estimated_error.items()}}


def _finite(v):
    return v if math.isfinite(v) else None


def tolerances(scene: Scene, tolerance=None) -> tuple[float, float]:
    """(body, tension) relative tolerances.

    Parameters
    ----------
    scene : Scene
        Its ``numerics.model_tolerance`` is the default.
    tolerance : float or (float, float), optional
        A number (body; tension twice it) or a (body, tension) pair.

    Returns
    -------
    tuple of float
        (body, tension), each in (0, 1).
    """
    tol = tolerance if tolerance is not None else getattr(scene.numerics, "model_tolerance", DEFAULT_TOLERANCE)
    body, tension = (tol, 2 * tol) if isinstance(tol, (int, float)) else tuple(tol)
    for name, v in (("body", body), ("tension", tension)):
        if not (isinstance(v, (int, float)) and 0 < v < 1):
            raise ParameterError("numerics.model_tolerance", tol, f"{name} tolerance must be in (0, 1)")
    return float(body), float(tension)


STIFF_RATIO = 30.0   # omega_ax / omega above which the quasi-static rung is the cheaper one (model_ladder study)
SAFETY = 0.5       # N is chosen for half the tolerance: the estimates are good to a factor of 2


def segments_for(errors: dict, tol: tuple[float, float], name: str = "segmented") -> int:
    """Least N (2 <= N <= the cap) whose estimated errors (:func:`~.estimate.rung_error` of the segmented
    rung, or of the quasi-static segmented rung for ``name`` "quasi-static") are within SAFETY x ``tol``, else the
    cap: a margin for the estimate's factor of 2 (on the Dale scene at omega_n the body error is 1.26, 0.72,
    0.55 % at N = 2, 3, 4 against N = 80, estimated 0.97, 0.52, 0.40 %: N = 4)."""
    cap = MAX_SEGMENTS if errors["segmented_1"].get("order", est.ORDER) >= est.ORDER else SLACK_MAX_SEGMENTS
    n = _least_n(errors, tol, name, SAFETY, 2, cap)
    return cap if n is None else n


EXTRAPOLATION_MIN_SEGMENTS = 16   # the coarsest extrapolation run N / 4 >= 4 elements


def extrapolated_segments(errors: dict, tol: tuple[float, float]) -> int:
    """N of auto's segmented run in the first-order regime (partial slack), whose statistics are
    extrapolated from runs at N / 4, N / 2, N (:mod:`.extrapolation`).

    The extrapolated statistics keep the next term of the expansion in 1/N, b N^-q (q = 2,
    :data:`.estimate.REMAINDER_ORDER`); its coefficient is taken of the size of the first-order
    term's, the straight cable's O(1) error (``segmented_1``: 1 under partial slack), so N is the least
    multiple of 4 with e_1 N^-q <= SAFETY x tol, and at least EXTRAPOLATION_MIN_SEGMENTS (1 % / 2 %: 16).
    The runs check it a posteriori (their observed order and the remainder's estimate; N doubles when
    either misses). 300 m wire, 2 t sphere, T = 6 s (360 s, RK4): the limits of N = 8, 16 and 16, 32 differ
    by 0.11 % (body) and 0.6 % (tension), b is 1-2 x e_1 / 4 there."""
    base = errors["segmented_1"]
    need = max((base[k] / (SAFETY * t)) ** (1.0 / est.REMAINDER_ORDER) for k, t in zip(("body", "tension"), tol))
    return max(EXTRAPOLATION_MIN_SEGMENTS, 4 * math.ceil(need / 4.0))


def extrapolated_error(errors: dict, n: int) -> dict:
    """A-priori error of the statistics extrapolated from N / 4, N / 2, N (see :func:`extrapolated_segments`):
    e_1 N^-q, at least the estimates' resolution."""
    base = errors["segmented_1"]
    return {k: max(base[k] * float(n) ** -est.REMAINDER_ORDER, est.RESOLUTION) for k in ("body", "tension")}


def quasistatic_segments_available(scene: Scene) -> bool:
    """True when the quasi-static rung can run ``scene`` (:func:`~.rungs.validity`) and takes elements
    (:func:`~.rungs.rung_scene` keeps ``segments`` for it: the segmented cable with its stretches following the
    tension, :mod:`cablesys.model.quasistatic`)."""
    return (not validity(get_rung("quasi-static"), scene)
            and all(s.cable.segments == 2 for s in rung_scene(scene, "quasi-static", 2).sections))


# The cost of N elements, relative to the node model's N stepped by BDF2 (compiled, the same run), are the element
# rungs' own: STIFF_QS_COST, EXPLICIT_COST and EXPLICIT_COST_MAX_ELEMENTS the quasi-static segmented cable's
# (:mod:`.rung.quasistatic`), CHECK_COST and CHECK_ACCEPT of a run checked a posteriori against N / 2
# (:mod:`.rung.segmented`); ratios of wall times measured by studies/model_ladder.py on the Dale scene and the
# 1000 m wire (cablesys.heavy_wire_scene).
# The quasi-static segmented cable's functions grow as about A^2.75 per section in its A angles (A = N in the plane,
# 2 N in 3-D: the chord solve's rows for every element stretch, each through the dense eliminated mass matrix of the
# angles), the node model's linearly: operation counts of
# the ODE plus the outputs measured on the Dale scene (CasADi SX, cse on): quasi-static 0.07 M / 0.2 M / 0.42 M /
# 1.27 M at N = 16 / 24 / 32 / 48 (0.7 GB to build at 48, before any compile); node model 0.01 M / 0.02 M /
# 0.03 M at N = 16 / 32 / 48. An N past MAX_MODEL_OPERATIONS is not built: the quasi-static segmented cable at
# N = 82 (Dale in a 2.5 m/s current) is 5 M operations, and building and compiling it takes over 14 GB.
QS_OPERATIONS_PER_SECTION = 30.2        # x N^QS_OPERATIONS_EXPONENT: the fit through N = 32 and 48
QS_OPERATIONS_EXPONENT = 2.75
NODE_OPERATIONS_PER_ELEMENT = 600.0     # x N per section, the node model's ODE plus outputs
MAX_MODEL_OPERATIONS = 500_000          # the quasi-static segmented cable up to N = 33 for one section
CHECK_MIN_SEGMENTS = 4   # the check runs N / 2 >= 2 elements


def model_operations(scene: Scene, name: str, segments: int) -> float:
    """Predicted operation count of a rung's generated functions (the ODE plus the outputs, CasADi SX operations)
    before it is built: the quasi-static segmented cable QS_OPERATIONS_PER_SECTION x A^QS_OPERATIONS_EXPONENT per
    section in its A angles (N in the plane, 2 N in 3-D: the heave line of studies/_bench_3d.py with its current at
    45 deg has 25 k / 98 k / 571 k operations at N = 4 / 8 / 16, along x 10 k / 26 k / 103 k), the node model
    NODE_OPERATIONS_PER_ELEMENT x N per section (fits to the counts above); the straight rungs (N = 1) a node model's
    element."""
    sections = len(cables(scene))
    if name == "quasi-static" and segments > 1:
        angles = float(segments) * (2 if three_d(scene) else 1)
        return sections * QS_OPERATIONS_PER_SECTION * angles ** QS_OPERATIONS_EXPONENT
    return sections * NODE_OPERATIONS_PER_ELEMENT * max(int(segments), 1)


def quasistatic_max_segments(scene: Scene) -> int:
    """The largest N of the quasi-static segmented cable whose predicted size (:func:`model_operations`) is within
    MAX_MODEL_OPERATIONS (1 when none is)."""
    per = QS_OPERATIONS_PER_SECTION * len(cables(scene))
    n = int((MAX_MODEL_OPERATIONS / per) ** (1.0 / QS_OPERATIONS_EXPONENT))
    while n > 1 and model_operations(scene, "quasi-static", n) > MAX_MODEL_OPERATIONS:
        n -= 1
    return max(n, 1)


def check_model_size(scene: Scene, name: str, segments: int) -> None:
    """Raise :class:`~cablesys.errors.ParameterError` (field ``cable.segments``) before a model is built when its predicted
    size (:func:`model_operations`) exceeds MAX_MODEL_OPERATIONS, saying what would run instead."""
    ops = model_operations(scene, name, segments)
    if ops <= MAX_MODEL_OPERATIONS:
        return
    top = quasistatic_max_segments(scene)
    raise ParameterError(
        "cable.segments", segments,
        f"the quasi-static segmented cable with N = {segments} would have about {ops / 1e6:.2g} M operations "
        f"(its functions grow as N^{QS_OPERATIONS_EXPONENT:g}; more than {MAX_MODEL_OPERATIONS / 1e6:.2g} M is not "
        f"built: gigabytes and many minutes); it is built up to N = {top} here",
        "run --model segmented (the node model, whose size grows linearly in N), --model wang, or a looser "
        "numerics.model_tolerance")


@dataclasses.dataclass(frozen=True)
class ElementPlan:
    """How auto divides the cable: the rung (``segmented``, or ``quasi-static`` for the quasi-static
    segmented cable), N, whether N is checked a posteriori (its estimate within the tolerance but not within
    SAFETY x it: Richardson against N / 2, :func:`cablesys.ladder.auto.richardson_step`), whether the rung is
    worth it only stepped by the explicit pair (``explicit_only``: else the node model runs at the same N),
    and its relative cost (elements x the weights above)."""

    name: str
    segments: int
    checked: bool
    explicit_only: bool
    cost: float
    fallback: dict | None = None     # a checked plan's cheapest sure option ({name, segments, explicit_only}), if any
    note: str = ""                   # what the plan left out and why (a rung past MAX_MODEL_OPERATIONS)

    def as_dict(self) -> dict:
        """The plan's fields for summary.json (``note`` only when there is one)."""
        d = dataclasses.asdict(self)
        if not d["note"]:
            del d["note"]
        return d


def checkable(scene: Scene, n: int) -> bool:
    """Whether N and N / 2 lie on the same side of the drag rule's switch from several points per element to one
    (:func:`cablesys.model.segmented.drag_points`; 10 drag points: N <= 6 against N >= 7), across which the
    segmented error changes sign (:mod:`.estimate`, the 1000 m wire: settled errors -0.59 % at N = 6, +1.23 % at
    7), so that |y_N - y_N/2| / 3 between the scene's own models may understate the error of N. Such an N is still
    checked: its check run takes one drag point per element as N does (:func:`check_scene`); the plans prefer a
    checkable N, whose check runs the scene's own drag rule."""
    return (drag_points(scene, n) > 1) == (drag_points(scene, n // 2) > 1)


def check_scene(scene: Scene, n: int, m: int | None = None) -> Scene:
    """The scene of the a posteriori check run at m = N / 2 (or the given ``m`` < N, the third run at N / 4) for a run
    at N: ``scene`` itself when N and m lie on the same side of the drag rule's switch (:func:`checkable` for N / 2),
    else with ``numerics.drag_segments`` = m, so that the check run, like the N run, takes one drag point per
    element (its mid-point: round(m / m) = 1 in :func:`~cablesys.model.segmented.drag_points`).
    The two runs then belong to one discretization, the mid-point rule on every element, whose error in the
    drag resultant is O(h^2) in the element length h (the composite mid-point rule's error (b - a) h^2 f''/24:
    Davis & Rabinowitz, *Methods of Numerical Integration*, 2nd ed. 1984, ch. 2) as the chords' is, so the Richardson estimate |y_N - y_N/2| / (2^p - 1) speaks of
    the N run's error against the cable both converge to (one drag point per element, N -> infinity: every
    count of drag points per element has the same limit)."""
    m = n // 2 if m is None else int(m)
    if (drag_points(scene, n) > 1) == (drag_points(scene, m) > 1):
        return scene
    return scene.with_numerics(drag_segments=max(1, m))


def _least_n(errs: dict, tol, name: str, fraction: float, lo: int, hi: int, ok=lambda n: True) -> int | None:
    """Least N in [lo, hi] with ``ok(N)`` whose estimate of rung ``name`` is within ``fraction`` x ``tol``."""
    for n in range(lo, hi + 1):
        if not ok(n):
            continue
        e = est.rung_error(errs, name, n)
        if e["body"] <= fraction * tol[0] and e["tension"] <= fraction * tol[1]:
            return n
    return None


def element_plan(scene: Scene, numbers, errs: dict, tol, compiled: bool | None = None) -> ElementPlan | None:
    """The cheapest way to N elements within the tolerance (None: no N up to the cap reaches it).

    Two rungs take elements: the node model (``segmented``) and the quasi-static segmented cable, whose
    stretches follow the tension (:func:`quasistatic_segments_available`; its estimate adds the stretch part,
    infinite under partial slack). The latter replaces the node model where the stretch is stiff
    (omega/omega_ax <= 1/STIFF_RATIO), and competes with it by cost where it is not, compiled and up to
    EXPLICIT_COST_MAX_ELEMENTS (it is cheaper only stepped by the rk23 pair: ``explicit_only``; in a 3-D scene its
    weights are SPACE_COST_FACTOR x the plane's, and stepped by the pair it is no cheaper there). For each, two
    N: the least within SAFETY x the tolerance (sure, the estimates being good to a factor of 2), and the least
    N >= CHECK_MIN_SEGMENTS within the tolerance that :func:`checkable` allows, checked a posteriori against N / 2
    (CHECK_COST x its cost;
    kept when the check's estimate is within CHECK_ACCEPT x the tolerance, else the cheapest sure option runs:
    ``fallback``). The least cost wins, a sure N on a tie (heavy1000, 1000 m wire forced at 2.7 x its first string mode,
    compiled: the node model sure at N = 9, cost 9, and checked at N = 6, cost 9; the quasi-static segmented
    checked at N = 6, cost 6.3, sure at none up to 8: it runs N = 6 and checks it against N = 3)."""
    families = [("segmented", 1.0, MAX_SEGMENTS, False)]
    space = SPACE_COST_FACTOR if three_d(scene) else 1.0      # 3-D: two angles per element
    if quasistatic_segments_available(scene):
        if numbers.axial_ratio <= 1.0 / STIFF_RATIO:
            families.append(("quasi-static", STIFF_QS_COST * space, min(MAX_SEGMENTS, quasistatic_max_segments(scene)),
                             False))
        elif (compiles() if compiled is None else compiled) and EXPLICIT_COST * space < 1.0:
            families.append(("quasi-static", EXPLICIT_COST, min(EXPLICIT_COST_MAX_ELEMENTS, EXPLICIT_MAX_ELEMENTS), True))
    options = []
    for name, weight, top, explicit in families:
        n = _least_n(errs, tol, name, SAFETY, 2, top)
        if n is not None:
            options.append(ElementPlan(name, n, False, explicit, weight * n))
        n = _least_n(errs, tol, name, 1.0, CHECK_MIN_SEGMENTS, top, lambda k: checkable(scene, k))
        if n is not None:
            options.append(ElementPlan(name, n, True, explicit, weight * CHECK_COST * n))
    best = min(options, key=lambda o: (o.cost, o.checked), default=None)
    note = _size_note(scene, errs, tol, families)
    if best is not None and note:
        best = dataclasses.replace(best, note=note)
    sure = min((o for o in options if not o.checked), key=lambda o: o.cost, default=None)
    if best is not None and best.checked and sure is not None:
        best = dataclasses.replace(best, fallback={"name": sure.name, "segments": sure.segments,
                                                   "explicit_only": sure.explicit_only})
    return best


def _size_note(scene: Scene, errs: dict, tol, families) -> str:
    """"" unless the quasi-static segmented cable was capped by its size (:func:`quasistatic_max_segments`) below the
    N it needs for the tolerance: then a note naming that N and its predicted operation count."""
    capped = [top for name, _, top, _ in families if name == "quasi-static" and top < MAX_SEGMENTS]
    if not capped or _least_n(errs, tol, "quasi-static", 1.0, 2, capped[0]) is not None:
        return ""
    need = _least_n(errs, tol, "quasi-static", SAFETY, capped[0] + 1, MAX_SEGMENTS)
    if need is None:
        return ""
    return (f"the quasi-static segmented cable would need N = {need}, about "
            f"{model_operations(scene, 'quasi-static', need) / 1e6:.2g} M operations (it is built up to N = "
            f"{capped[0]}, {MAX_MODEL_OPERATIONS / 1e6:.2g} M): the node model runs instead")


def _plan_text(plan: ElementPlan, numbers) -> tuple[str, str]:
    """(what runs, how its N was chosen) for the reason."""
    if plan.name == "quasi-static":
        how = (f"stepped by the compiled rk23 pair, cheaper than the node model at N <= {EXPLICIT_COST_MAX_ELEMENTS} "
               f"(omega/omega_ax = {numbers.axial_ratio:.3g})" if plan.explicit_only
               else f"omega/omega_ax = {numbers.axial_ratio:.3g} <= 1/{STIFF_RATIO:g}")
        what = f"quasi-static segmented with N = {plan.segments} (the element stretches follow the tension, {how})"
    else:
        what = f"segmented with N = {plan.segments}"
    how_n = (f"the least N >= {CHECK_MIN_SEGMENTS} with its estimate within the tolerance, checked a posteriori "
             f"against N = {plan.segments // 2} (cheaper than the least N within {SAFETY:g} x the tolerance)"
             if plan.checked else f"the least N with its estimate within {SAFETY:g} x the tolerance")
    return what, how_n + (f"; {plan.note}" if plan.note else "")


def settling_note(scene: Scene, transverse: bool = True, settle: float | None = None) -> str:
    """"" when the statistics window of the scene's run (:func:`.metrics.window`: the last 5 forcing periods, in
    the second half, after the ramp) starts after :func:`.estimate.settling_time` (``transverse``: with the transverse wave's
    travel down the cable and the slow drift of the mean offset in a current; False where nothing drives the swing:
    the ramp alone; ``settle``: that settling time if already known), else a note for the reason, on
    the console and in summary.json, that it holds the start-up transient, of which the estimates (of the settled
    response) say nothing. A note, not a warning: short runs are legitimate (quick looks, tests, sweeps)."""
    times = scene.output_times
    period = metrics.forcing_period(scene)
    if period is None or times.size < 2:
        return ""
    start = float(times[metrics.window(times, period, scene.top_motion.effective_ramp_s)][0])
    if not transverse:
        settle = float(scene.top_motion.effective_ramp_s)
    elif settle is None:
        settle = est.settling_time(scene)
    if start >= settle:
        return ""
    return (f"the run's statistics window starts at {start:.4g} s, before the forced response settles "
            f"({settle:.4g} s: the smooth start, the wave's travel down the hanging cable and the mean offset's "
            f"drift in the current): the estimated "
            f"error is the settled response's; run at least {settle + min(5 * period, settle):.4g} s for it to apply")


def within(e: dict, tol) -> bool:
    """Both estimated errors (body, tension) within the tolerances ``tol``."""
    return e["body"] <= tol[0] and e["tension"] <= tol[1]


def _swing_free(scene: Scene, numbers) -> bool:
    """True when nothing drives the swing: sinusoidal top motion along the static cable only, no current
    bow, no waves, no sampled series. The quasi-static rung then steps nothing (300 m / 2 t heave at
    T = 10 s: 11 steps against Wang's 1560); in CasADi's VM its outputs, a Newton solve each, cost more than
    Wang's steps: it is chosen first only when compiled."""
    env, top = scene.environment, scene.top_motion
    return (numbers.transverse_fraction == 0.0 and numbers.static_bow == 0.0 and not env.waves
            and top.series is None and all(u == env.system_speed for u in env.current_speeds))


def _assess(scene: Scene, tol, cache: RungCache | None = None):
    """(numbers, Wang's linear response, every rung's estimated errors, info dict) of ``scene``."""
    numbers = scene_numbers(scene)
    wang = cache.model(scene, "wang") if cache is not None else build_model(with_segments(scene, 1))
    response = est.linear_response(scene, numbers, model=wang)
    est.check_response(response)
    errs = est.estimate_errors(scene, numbers, response)
    info = {"scene": numbers.as_dict(), "linear_response": dataclasses.asdict(response),
            "settling_time_s": est.settling_time(scene, wang),
            "estimates": {k: dict(v) for k, v in errs.items()}, "tolerance": {"body": tol[0], "tension": tol[1]}}
    return numbers, response, errs, info


def choose(scene: Scene, tolerance=None, *, question: str = "time", cache: RungCache | None = None) -> Choice:
    """The cheapest rung of :data:`~cablesys.ladder.rungs.RUNGS` within the tolerance.

    Parameters
    ----------
    scene : Scene
        The scene (its ``cable.segments`` are ignored: the ladder sets them).
    tolerance : float or (float, float), optional
        Relative error allowed on body motion (and tension extremes: twice it, or the pair's second).
    question : {"time", "steady"}
        "steady" when only the steady periodic amplitude is wanted: the frequency-domain rung is
        then a candidate (it has no start-up transient).
    cache : RungCache, optional
        Built models to reuse (Wang's model and its describing-function solver).

    Returns
    -------
    Choice
        Rung, elements per section, the reason with its deciding numbers, the estimated errors.
    """
    tol = tolerances(scene, tolerance)
    numbers, response, errs, info = _assess(scene, tol, cache)
    compiled = compiles()
    choice = _pick(scene, tol, question, numbers, response, errs, info, compiled)
    choice = _registered(scene, tol, Assessment(numbers, response, errs), choice) if registered_rungs() else choice
    if not compiled:       # the choice prices rungs as they run: say what the compiled code would run instead
        other = _pick(scene, tol, question, numbers, response, errs, dict(info), True, warn=False)
        if (other.name, other.segments) != (choice.name, choice.segments):
            n = f" N = {other.segments}" if other.segments > 1 else ""
            choice = dataclasses.replace(choice, reason=f"{choice.reason}; compiled code is off (CasADi's virtual "
                                         f"machine): with it the ladder would run {other.name}{n}")
    return choice


def _cost(scene: Scene, choice: Choice) -> float:
    """The relative cost of ``choice`` (a built-in rung's): its element plan's, else the rung's own."""
    plan = choice.numbers.get("plan")
    if plan and (plan.get("name"), plan.get("segments")) == (choice.name, choice.segments):
        return float(plan["cost"])
    return get_rung(choice.name).cost(scene, None, choice.segments)


def _registered(scene: Scene, tol, assessment: Assessment, choice: Choice) -> Choice:
    """``choice``, or the cheapest registered rung (:func:`~.rungs.register_rung`) valid for ``scene``
    (:func:`~.rungs.validity`) whose estimate is within the tolerance and whose cost is below ``choice``'s."""
    best, best_cost = choice, _cost(scene, choice)
    for rung in registered_rungs():
        if validity(rung, scene):
            continue
        e = rung.estimate(scene, assessment)
        c = float(rung.cost(scene, assessment))
        if within(e, tol) and c < best_cost:
            reason = (f"{rung.name} (a registered rung): within {tol[0]:.3g} (body) / {tol[1]:.3g} (tension), cost "
                      f"{c:.3g} against {best_cost:.3g} of {choice.name}; {e.get('note', '')}")
            best, best_cost = Choice(rung.name, 1, reason, {"body": e["body"], "tension": e["tension"]},
                                     dict(choice.numbers)), c
    return best


def _pick(scene: Scene, tol, question: str, numbers, response, errs: dict, info: dict, compiled: bool,
          warn: bool = True) -> Choice:
    """The choice of :func:`choose` from the scene's assessment, pricing the rungs as run ``compiled`` or not."""
    deciding = (f"omega/omega_ax = {numbers.axial_ratio:.3g}, omega/omega_string = {numbers.string_ratio:.3g}, "
                f"cable/body mass {numbers.mass_ratio:.3g}, weight {numbers.weight_ratio:.3g}, "
                f"bow/chord static {numbers.static_bow:.2g} dynamic {numbers.dynamic_bow:.2g}, "
                f"least tension (linear) {response.least_tension:.4g} N vs floor {numbers.tension_floor:.4g} N")
    # the straight rungs (one element per section) valid for the scene; the periodic orbit for a steady amplitude only
    order = [r.name for r in BUILTIN if r.straight and not r.valid(scene) and (question == "steady" or r.time_domain)]
    swing_free = _swing_free(scene, numbers)
    note = settling_note(scene, transverse=not swing_free, settle=info["settling_time_s"])
    if note:
        deciding += "; " + note
    if numbers.axial_ratio > 1.0 / STIFF_RATIO and not (swing_free and compiled) and "quasi-static" in order:
        # the stretch mode is within STIFF_RATIO of the forcing: stepping it costs less than the
        # quasi-static reduction (whose stretch is a Newton solve at every evaluation), and is exact
        # (without a quasi-static rung, a 3-D scene, Wang's cable keeps its place)
        order.remove("wang")
        order.insert(order.index("quasi-static"), "wang")
    for name in order:
        e = errs[name]
        if within(e, tol):
            reason = (f"{name}: the cheapest rung within {tol[0]:.3g} (body) / {tol[1]:.3g} (tension); "
                      f"{e['note']}; {deciding}")
            if name == "quasi-static" and swing_free:
                reason += ("; nothing drives the swing (top motion along the cable, no current, waves or series): "
                           "the quasi-static rung has no dynamics left to step, its cost is its outputs")
            return Choice(name, 1, reason, {"body": e["body"], "tension": e["tension"]}, info)
    if errs["segmented_1"].get("order", est.ORDER) < est.ORDER:
        # first order in N (partial slack): the statistics are extrapolated from N / 4, N / 2, N (simulate)
        n = extrapolated_segments(errs, tol)
        e = extrapolated_error(errs, n)
        reason = (f"segmented with N = {n}, its statistics extrapolated from N = {n // 4}, {n // 2}, {n} (Richardson: "
                  f"partial slack, the cable converges at first order in N): the straight cable misses the tolerance "
                  f"({errs['wang']['note']}); N for the remainder e_1 N^-2 within {SAFETY:g} x the tolerance; {deciding}")
        return Choice("segmented", n, reason, {"body": e["body"], "tension": e["tension"]}, info)
    plan = element_plan(scene, numbers, errs, tol, compiled)
    if plan is None:                                 # not reachable up to the cap: checked a posteriori, N doubling
        n = segments_for(errs, tol)
        plan = ElementPlan("segmented", n, True, False, float(n))
    name, n = plan.name, plan.segments
    info["plan"] = plan.as_dict()
    e = est.rung_error(errs, name, n)
    why = errs["wang"]["note"] if not within(errs["wang"], tol) else ""
    what, how_n = _plan_text(plan, numbers)
    reason = (f"{what}: the straight cable misses the tolerance ({why}, estimated body "
              f"{errs['wang']['body']:.3g}, tension {errs['wang']['tension']:.3g}); {how_n}; {deciding}")
    if not within(e, tol):
        reason += (f"; the tolerance is not reachable at an affordable N: estimated body {e['body']:.2g}, "
                   f"tension {e['tension']:.2g} at N = {n}")
        if warn:
            warnings.warn(f"model auto: {reason}", NumericalWarning, stacklevel=3)
    return Choice(name, n, reason, {"body": e["body"], "tension": e["tension"]}, info)


def forced(scene: Scene, name: str, segments: int | None = None, tolerance=None,
           cache: RungCache | None = None) -> Choice:
    """The Choice for a rung the user named, with its estimate.

    Parameters
    ----------
    scene : Scene
        The scene.
    name : str
        A rung of :data:`~cablesys.ladder.rungs.RUNGS`.
    segments : int, optional
        Elements per section for the segmented rung (default: the scene's ``segments``, else chosen for
        the tolerance), or for the quasi-static rung (> 1: the quasi-static segmented cable; default the
        scene's ``segments``, 1 the straight cable).
    tolerance : float or (float, float), optional
        See :func:`tolerances`.
    cache : RungCache, optional
        Built models to reuse.

    Returns
    -------
    Choice
        ``numbers["valid"]`` is False (and the reason says why) when the estimate misses the tolerance.
    """
    tol = tolerances(scene, tolerance)
    numbers, response, errs, info = _assess(scene, tol, cache)
    registered = {r.name: r for r in registered_rungs()}
    if name in registered:
        e = registered[name].estimate(scene, Assessment(numbers, response, errs))
        ok = within(e, tol)
        reason = f"{name} (a registered rung) requested by the user" + ("" if ok else "; OUTSIDE its validity: "
                                                                          + str(e.get("note", "")))
        return Choice(name, 1, reason, {"body": e["body"], "tension": e["tension"]}, dict(info, valid=ok))
    scene_n = scene_segments(scene)                                  # the user's own `segments = N`
    if name == "segmented":
        n = segments or (scene_n if scene_n > 1 else segments_for(errs, tol))
    elif name == "quasi-static" and quasistatic_segments_available(scene):
        n = segments or scene_n                                      # > 1: the quasi-static segmented rung
        check_model_size(scene, name, n)
    else:
        n = 1
    e = est.rung_error(errs, name, n)
    ok = within(e, tol)
    reason = f"{name} requested by the user" + ("" if ok else f"; OUTSIDE its validity at this tolerance: {e['note']}")
    return Choice(name, n, reason, {"body": e["body"], "tension": e["tension"]}, dict(info, valid=ok))
