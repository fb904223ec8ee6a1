"""``simulate_auto(scene)``: run the rung the scene needs, check it afterwards, say which and why.

The choice (:func:`~cablesys.ladder.choice.choose`) is checked a posteriori:
- quasi-static: the stretch must stay taut (a quasi-static stretch cannot go slack); if the
  tension falls to the floor, the run is rejected and Wang's model (or the segmented cable) runs;
- wang: a run that goes slack is outside the straight cable's validity (one stretch makes the whole
  cable slack at once): rejected for the segmented cable;
- segmented with N: a second run with N/2 gives the Richardson estimate |y_N - y_N/2| / (2^p - 1);
  N is doubled while that exceeds the tolerance.
The result's ``stats["model"]`` holds ``{name, segments, reason, estimated_error}``.
"""

from __future__ import annotations

import logging
import math
import warnings

import numpy as np

from ..errors import NumericalWarning
from ..scene import Scene
from . import estimate as est
from . import metrics
from .choice import MAX_SEGMENTS, SLACK_MAX_SEGMENTS, Choice, choose, forced, tolerances
from .rungs import build_rung, check_rung, rung_scene

log = logging.getLogger(__name__)


def run_rung(scene: Scene, name: str, segments: int = 1, **kw):
    """One time-domain run of rung ``name``.

    Parameters
    ----------
    scene : Scene
        The scene.
    name : str
        A rung; ``frequency`` gives the periodic orbit (Fourier collocation) sampled at the output times.
    segments : int, optional
        Elements per section of the segmented rung.
    **kw
        Passed to :func:`cablesys.time_domain.simulate`.

    Returns
    -------
    TimeResult
        The run (``success`` False with the reason when the integrator failed).
    """
    from ..time_domain import simulate
    if name == "frequency":
        return _periodic_run(scene)
    sc = rung_scene(scene, name, segments)
    model = build_rung(sc, name, segments)
    return simulate(sc, model=model, **kw)


def _periodic_run(scene: Scene):
    from ..linear import periodic_steady_state
    from ..linear.periodic import scene_input_amplitude
    from ..results import TimeResult
    sc = rung_scene(scene, "wang")
    model = build_rung(sc, "wang")
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
    E = np.array(model.top.map(times.size)(times[None, :], np.tile(p[:, None], (1, times.size))))
    data["x_s"], data["y_s"] = E[1], E[2]
    stats = dict(per.stats, method="periodic collocation", nsteps=0, wall_s=float(per.stats.get("wall_time_s", 0.0)),
                 build_s=0.0)
    return TimeResult(time=times, data=data, success=bool(per.success), message=per.message, stats=stats,
                      scene_name=scene.name)


def _went_slack(result, scene: Scene) -> bool:
    floor = max(s.cable.tension_floor for s in scene.sections)
    low = min(float(np.min(result[k])) for k in ("tension_bottom", "tension") if k in result.labels)
    return bool(result.events) or result.time_slack() > 0 or low <= floor


def _decide(scene: Scene, model, tolerance, segments):
    """(Choice, tolerances, auto?) for the rung ``model`` (default ``numerics.model``); a rung the
    user forced outside its validity warns with the reason (stacklevel: the public caller's caller)."""
    name = check_rung(model or getattr(scene.numerics, "model", "auto"))
    tol = tolerances(scene, tolerance)
    if name == "auto":
        return choose(scene, tol), tol, True
    choice = forced(scene, name, segments, tol)
    if not choice.numbers.get("valid", True):
        warnings.warn(f"model '{name}': {choice.reason}", NumericalWarning, stacklevel=3)
    return choice, tol, False


def simulate_auto(scene: Scene, *, model: str | None = None, tolerance=None, segments: int | None = None,
                  **kw):
    """Simulate ``scene`` with the rung ``model`` ("auto": chosen; default ``scene.numerics.model``).

    Parameters
    ----------
    scene : Scene
        The scene.
    model : str, optional
        "auto" or a rung name (:data:`~cablesys.ladder.rungs.MODEL_CHOICES`).
    tolerance : float or (float, float), optional
        Body-motion (and tension) tolerance; default ``numerics.model_tolerance`` or 1 % / 2 %.
    segments : int, optional
        Elements per section for a forced segmented rung (default: chosen for the tolerance).
    **kw
        Passed to :func:`cablesys.time_domain.simulate` (method, rtol, atol, times, jit).

    Returns
    -------
    TimeResult
        ``stats["model"] = {name, segments, reason, estimated_error}``; a rung forced outside its
        validity warns (:class:`~cablesys.errors.NumericalWarning`) with the reason.
    """
    choice, tol, auto = _decide(scene, model, tolerance, segments)
    result, choice = _run_checked(scene, choice, tol, auto=auto, **kw)
    result.stats["model"] = choice.as_dict()
    log.info("model %s (N = %d): %s", choice.name, choice.segments, choice.reason)
    return result


def _run_checked(scene: Scene, choice: Choice, tol, *, auto: bool, **kw):
    result = run_rung(scene, choice.name, choice.segments, **kw)
    choice, again = after_run(scene, choice, result, auto=auto)
    if again:
        log.info("rejected a posteriori; running %s with N = %d", choice.name, choice.segments)
        return _run_checked(scene, choice, tol, auto=auto, **kw)
    if choice.name == "segmented" and choice.segments >= 4:
        return _richardson(scene, choice, tol, result, auto=auto, **kw)
    return result, choice


def _richardson(scene: Scene, choice: Choice, tol, result, *, auto: bool, **kw):
    period = metrics.forcing_period(scene)
    n = choice.segments
    while True:
        coarse = run_rung(scene, "segmented", n // 2, **kw)
        if not (coarse.success and result.success):
            return result, choice
        diff = metrics.errors(metrics.statistics(coarse, period), metrics.statistics(result, period))
        order = choice.numbers.get("estimates", {}).get("segmented_1", {}).get("order", est.ORDER)
        factor = 1.0 / (2.0 ** order - 1.0)
        e = {k: v * factor for k, v in diff.items()}
        cap = MAX_SEGMENTS if order >= est.ORDER else SLACK_MAX_SEGMENTS
        if not auto or (e["body"] <= tol[0] and e["tension"] <= tol[1]) or 2 * n > cap:
            reason = choice.reason + f"; a posteriori (N = {n} vs {n // 2}, order {order:g}): body {e['body']:.2g}, tension {e['tension']:.2g}"
            return result, Choice("segmented", n, reason, e, choice.numbers)
        n *= 2
        result = run_rung(scene, "segmented", n, **kw)


def plan_run(scene: Scene, model: str | None = None, tolerance=None):
    """(scene to run, its CasADi model, Choice) for a caller that runs the simulation itself
    (the ``run`` command streams its output). Warns when a forced rung is outside its validity.
    The ``frequency`` rung is not a time-domain model: callers use :func:`simulate_auto` for it."""
    choice, _, _ = _decide(scene, model, tolerance, None)
    if choice.name == "frequency":
        return None, None, choice
    sc = rung_scene(scene, choice.name, choice.segments)
    return sc, build_rung(sc, choice.name, choice.segments), choice


def after_run(scene: Scene, choice: Choice, result, *, auto: bool) -> tuple[Choice, bool]:
    """A posteriori check of one run: (updated Choice, whether to run again with it).

    A straight-cable run (quasi-static or wang) that went slack is outside its validity: under
    "auto" the segmented cable is chosen instead (run again); a forced rung keeps its result with
    a warning and an infinite estimated error."""
    if choice.name not in ("quasi-static", "wang") or not _went_slack(result, scene):
        return choice, False
    note = f"the {choice.name} run went slack: a straight cable with one stretch cannot be partly slack"
    if not auto:
        warnings.warn(f"model '{choice.name}': {note}", NumericalWarning, stacklevel=2)
        return Choice(choice.name, 1, choice.reason + "; " + note, {"body": math.inf, "tension": math.inf},
                      choice.numbers), False
    n = max(choice.segments, 10)
    return Choice("segmented", n, f"{choice.name} rejected a posteriori: {note}; segmented with N = {n}",
                  est.segmented_error(choice.numbers["estimates"], n), choice.numbers), True


def describe(choice_dict: dict) -> str:
    """One console line: which model ran, why, and its estimated error."""
    e = choice_dict.get("estimated_error", {})
    fmt = lambda v: "n/a" if v is None else f"{100 * v:.2g} %"
    seg = f", N = {choice_dict['segments']}" if choice_dict.get("name") == "segmented" else ""
    return (f"model {choice_dict.get('name')}{seg}: estimated error body {fmt(e.get('body'))}, tension "
            f"{fmt(e.get('tension'))}; {choice_dict.get('reason', '')}")
