"""The a priori check of the mean shape: a rung's static equilibrium in the scene's current against the converged one.

The ladder's a priori estimates (:mod:`.estimate`) see the dynamic response through a linear model and the static
bow through a closed form (sag / chord of a uniformly loaded string, :func:`.estimate.static_bow_error`). In a
sheared current the bowed static shape, and with it the body's mean offset, differs between a straight cable, a
coarse polygon of N chords and the converged cable by more than those say: the ROV-lift example (1.0 / 0.6 / 0.2
m/s) has its body 21.28 m downstream on Wang's straight cable, 18.31 m with N = 4 elements and 17.87 m converged
(N = 64; 17.89 m at N = 32). The statics cost a fraction of a second per model, so before any run the chosen rung's
equilibrium (Wang's straight cable for the straight rungs, the node model at N for the element rungs: the
quasi-static segmented cable has the node model's statics) is compared with the node model's at
REFERENCE_SEGMENTS, quantity by quantity with the floors of :func:`.metrics.quantity_errors`; a rung that misses
the tolerance there is replaced, before it runs, by the least N of the node model (or of the same element rung)
that meets it.

Equilibria: :func:`cablesys.statics.steady.steady_state` (Wang 1971 eq. 42-46 at rest in the current) and
:func:`cablesys.statics.catenary.segmented_steady` (the node model's elastic catenary).
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import SolverError
from ..scene import Scene
from ..statics.catenary import segmented_steady
from ..statics.steady import steady_state
from . import estimate as est
from . import metrics
from .choice import EXPLICIT_COST_MAX_ELEMENTS, MAX_SEGMENTS, Choice, checkable, quasistatic_max_segments
from .rungs import RungCache, rung_scene

REFERENCE_SEGMENTS = 64      # the converged statics (ROV lift: 0.08 % from N = 32 on the body's offset)
STATIC_KEYS = ("static_x_b", "static_y_b", "static_z_b", "static_tension_top", "static_tension_bottom")


def _group(key: str) -> str:
    return "tension" if "tension" in key else "body"


def static_values(scene: Scene, name: str, segments: int, cache: RungCache) -> dict:
    """{STATIC_KEYS: value} of the equilibrium of rung ``name`` with ``segments`` elements (m, N): Wang's straight
    cable for N = 1, else the node model at N (the quasi-static segmented cable's statics are the node model's);
    ``static_z_b`` is NaN in the plane (no sway: :func:`static_errors` skips it)."""
    n = int(segments)
    model = cache.model(scene, "wang" if n <= 1 else "segmented", n)
    sc = rung_scene(scene, "wang" if n <= 1 else "segmented", n)
    p = model.parameters(sc)
    state = steady_state(model, p) if n <= 1 else segmented_steady(model, p)
    out = state.outputs
    get = lambda k: float(out[k]) if k in out else math.nan
    return {"static_x_b": get("x_b"), "static_y_b": get("y_b"), "static_z_b": get("z_b"),
            "static_tension_top": get("tension_top"), "static_tension_bottom": get("tension_bottom")}


def static_errors(values: dict, reference: dict) -> dict:
    """{key: relative error} of ``values`` against ``reference`` (:func:`static_values`), each relative to its own
    reference value with the floors of :func:`.metrics.quantity_errors` (1 cm: a static shape has no amplitude to scale
    it; 1 % of the top tension)."""
    floor_n = metrics.TENSION_FLOOR_FRACTION * abs(reference["static_tension_top"])
    out = {}
    for k, ref in reference.items():
        if not (math.isfinite(ref) and math.isfinite(values.get(k, math.nan))):
            continue
        floor = floor_n if _group(k) == "tension" else metrics.LENGTH_FLOOR_M
        out[k] = float(abs(values[k] - ref) / max(abs(ref), floor, 1e-300))
    return out


def _worst(errors: dict) -> dict:
    return {g: max((e for k, e in errors.items() if _group(k) == g), default=0.0) for g in ("body", "tension")}


def applies(scene: Scene, choice: Choice) -> bool:
    """Whether the mean shape is worth checking: a current bows the static cable (``static_bow`` > 0 in the
    choice's deciding numbers); hanging in still water every rung's static cable is the same vertical line."""
    return float(choice.numbers.get("scene", {}).get("static_bow", 0.0)) > 0.0


def _candidates(scene: Scene, n: int, top: int):
    """N to try above ``n``: 1.5x steps (at least +1) up to ``top``, skipping N >= 4 whose a posteriori check at
    N / 2 would not run the scene's own drag rule (:func:`~.choice.checkable`: the two across the drag rule's switch;
    such an N is checked with one drag point per element, :func:`~.choice.check_scene`), as the plans do."""
    while n < top:
        n = min(top, max(n + 1, math.ceil(1.5 * n)))
        while n < top and n >= 4 and not checkable(scene, n):
            n += 1
        yield n


def check(scene: Scene, choice: Choice, tol, cache: RungCache) -> Choice:
    """``choice`` with its static errors (``numbers["static_errors"]``, in summary.json's model block), or,
    when they miss the tolerance ``tol`` (body, tension), the least N that meets it: of the same element rung (the
    quasi-static segmented cable up to its size cap, :func:`~.choice.quasistatic_max_segments`, and when the plan took it
    for its cost with the explicit pair, ``explicit_only``, up to EXPLICIT_COST_MAX_ELEMENTS, as
    :func:`~.choice.element_plan` does), else of the node model, at most MAX_SEGMENTS. A statics solve that fails
    leaves ``choice`` as it is, with a note."""
    if not applies(scene, choice):
        return choice
    try:
        ref_n = min(MAX_SEGMENTS, max(REFERENCE_SEGMENTS, 2 * choice.segments))
        reference = static_values(scene, "segmented", ref_n, cache)
        errs = static_errors(static_values(scene, choice.name, choice.segments, cache), reference)
    except SolverError as err:
        return dataclasses.replace(choice, reason=f"{choice.reason}; the static shape was not checked ({err})")
    worst = _worst(errs)
    note = (f"static shape in the current against the node model's at N = {ref_n}: body {worst['body']:.2g}, "
            f"tension {worst['tension']:.2g}")
    if worst["body"] <= tol[0] and worst["tension"] <= tol[1]:
        return _stated(choice, errs, note, ref_n, reference)
    # the element rungs share the node model's statics: one search over N; past the quasi-static segmented cable's
    # size cap, or past the N up to which it was chosen for its cost (explicit_only: the plan's own cap), the node
    # model runs instead
    name = choice.name if choice.segments > 1 else "segmented"
    top, cap_why = MAX_SEGMENTS, ""
    if name == "quasi-static":
        top, cap_why = min(MAX_SEGMENTS, quasistatic_max_segments(scene)), "capped by its size"
        if choice.numbers.get("plan", {}).get("explicit_only", False) and top > EXPLICIT_COST_MAX_ELEMENTS:
            top, cap_why = EXPLICIT_COST_MAX_ELEMENTS, (f"cheaper than the node model only up to N = "
                                                        f"{EXPLICIT_COST_MAX_ELEMENTS}, stepped by the explicit pair")
    first = () if choice.segments > 1 else (2,)
    for n in (*first, *_candidates(scene, max(choice.segments, 2), MAX_SEGMENTS)):
        try:
            e = static_errors(static_values(scene, "segmented", n, cache), reference)
        except SolverError:
            continue
        w = _worst(e)
        if w["body"] <= tol[0] and w["tension"] <= tol[1]:
            rung = name if n <= top else "segmented"
            why = "" if rung == name else f" (the node model: the quasi-static segmented cable is {cap_why})"
            return _raised(choice, rung, n, e, f"{note} at N = {choice.segments}, within the tolerance from N = {n}{why}",
                           ref_n, reference)
    return _stated(choice, errs, f"{note}: outside the tolerance, and no N up to {MAX_SEGMENTS} meets it", ref_n,
                   reference)


def refresh(scene: Scene, choice: Choice, cache: RungCache) -> Choice:
    """``choice`` with its static errors at the N that ran, where the a posteriori check grew N after the static
    check (the reference's values are kept in the block: one statics solve at the new N); unchanged when nothing
    was checked, N is the same, or the solve fails (the block then keeps the N it speaks of)."""
    block = choice.numbers.get("static_errors")
    if block is None or block["segments"] == choice.segments or "reference" not in block:
        return choice
    try:
        errs = static_errors(static_values(scene, choice.name, choice.segments, cache), block["reference"])
    except SolverError:
        return choice
    return dataclasses.replace(choice, numbers=dict(choice.numbers, static_errors=dict(
        block, segments=choice.segments, errors=errs)))


def _stated(choice: Choice, errs: dict, note: str, ref_n: int, reference: dict) -> Choice:
    """``choice`` with the static errors of its N (``numbers["static_errors"]``: their own quantities, judged on
    their own values; the body and tension groups' estimates speak of the motion) and ``note`` in its reason."""
    static = {"segments": choice.segments, "reference_segments": ref_n, "errors": dict(errs), "reference": reference}
    return dataclasses.replace(choice, reason=f"{choice.reason}; {note}" if note else choice.reason,
                               numbers=dict(choice.numbers, static_errors=static))


def _raised(choice: Choice, name: str, n: int, errs: dict, note: str, ref_n: int, reference: dict) -> Choice:
    """The element rung ``name`` at N = ``n`` in place of ``choice``, its estimate at that N, the static errors."""
    e = est.rung_error(choice.numbers["estimates"], name, n)
    plan = dict(choice.numbers.get("plan", {}), name=name, segments=n, checked=True)
    if name != "quasi-static":
        plan["explicit_only"] = False
    raised = Choice(name, n, f"{choice.reason}; {note}: {name} with N = {n}",
                    {"body": e["body"], "tension": e["tension"]}, dict(choice.numbers, plan=plan))
    return _stated(raised, errs, "", ref_n, reference)
