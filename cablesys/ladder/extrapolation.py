"""Richardson extrapolation of the segmented cable's statistics where it converges at first order.

Under partial slack the snap front is resolved to one element and the segmented cable converges at
first order in N (300 m wire, 2 t sphere, T = 6 s: observed 0.98-1.03 from N = 10, 20, 40, 80), so
the tolerance would need hundreds of elements. The statistics the tolerance speaks of (body
amplitudes, tension extremes, :mod:`.metrics`) are extrapolated instead (Richardson 1911), from
three runs at N / 4, N / 2 and N (RK4 at its stable step: :func:`settings`).

With f(N) = f* + a N^-1 + b N^-q + ... (q > 1, the remainder's order; q = 2 for an expansion in
integer powers), the first-order limit of (N / 2, N) is

    L(N) = f(N) + (f(N) - f(N / 2)) / (2 - 1) = f* + c N^-q,  c = b (2 - 2^q),

and L(N / 2) = f* + c 2^q N^-q, so L(N / 2) - L(N) = c N^-q (2^q - 1) and the error of the
extrapolated value is

    L(N) - f* = (L(N / 2) - L(N)) / (2^q - 1)          (factor 1/3 for q = 2).

That holds whatever a is, also when a = 0 (a sequence converging at second order: the limit then
does not gain, and the estimate still states its error). The observed order of the three runs,
p = log2(|f(N/4) - f(N/2)| / |f(N/2) - f(N)|), tells whether they are in the asymptotic range of
the first-order term: outside [ORDER_RANGE] (300 m slack scene at N = 4, 8, 16: p = -0.9 on the
body amplitude; at 8, 16, 32: 0.98) N doubles (one more run), up to MAX_SEGMENTS; at the cap the
stated error is the larger of the whole difference of the two limits (factor 1) and the extrapolation's
own correction |L(N) - f(N)| (it may not help), with a warning (the scene file's 60 s run of that scene,
whose window lies in its ~100 s transient: body 29 %, against 14 % for the N = 64 series).

The time series the user gets is the N run's: its own first-order Richardson estimate
|f(N) - L(N)| is stated apart (``time_series_error``), so nothing is hidden.

Time step: RK4 at h |lambda|_max = RK4_MARGIN (issue 11: on snap loads the fast and accurate method; the
compiled element kernel makes it cheap). Against half that step the statistics of the 300 m slack
scene (360 s, output 0.01 s) move by < 1e-5 relative at N = 8, 16, 32 (body amplitude 7e-6, top
maximum 4e-6, bottom maximum 5e-6): far below the extrapolated values' errors (3e-4 to 3e-3).
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from .. import statistics as st
from ..errors import NumericalWarning
from ..scene import Scene
from . import estimate as est
from . import metrics
from .choice import within
from .hooks import checking, hooks
from .rungs import RungCache, rung_scene
from .run_settings import integrator_settings, start

ORDER = 1.0                 # the leading order extrapolated away (estimate.SLACK_ORDER)
REMAINDER_ORDER = est.REMAINDER_ORDER   # q of the next term (an expansion in integer powers of 1/N)
ORDER_RANGE = (0.5, 3.0)    # observed orders accepted as asymptotic (above 1: the remainder dominates, still N^-q)
MAX_SEGMENTS = 80           # doubling stops here (RK4, compiled kernel: 0.14 s per simulated s at N = 80)
RK4_MARGIN = 2.0            # h |lambda|_max of the stable step (RK4's boundary is 2.78; issue 11's choice)
SAMPLES_PER_SNAP = 6        # output samples per axial travel time in the statistics runs (see statistics_step)
_PASS = ("x0", "max_num_steps")


def applies(choice, auto: bool) -> bool:
    """True when auto chose the segmented cable in its first-order regime (partial slack predicted:
    the segmented estimate's ``order`` below :data:`estimate.ORDER`)."""
    order = choice.numbers.get("estimates", {}).get("segmented_1", {}).get("order", est.ORDER)
    return bool(auto and choice.name == "segmented" and order < est.ORDER)


def settings(scene_run: Scene, model, method: str | None = None, x0=None, **kw):
    """Integrator settings of one extrapolation run: RK4 at its stable step (h |lambda|_max <= RK4_MARGIN
    at the static state, and at least the scene's steps per output), compiled (the element kernel),
    unless the caller names another method (then :func:`.auto.integrator_settings`).

    Parameters
    ----------
    scene_run : Scene
        The segmented rung's scene.
    model : CableModel
        Its model.
    method : str, optional
        The caller's method (default "rk" at its stable step).
    x0 : array_like, optional
        The static start whose fastest rate sets the stable step (default: computed here).
    **kw
        ``rtol``, ``atol``, ``max_num_steps`` for another method.

    Returns
    -------
    IntegratorSettings
    """
    from ..time_domain import IntegratorSettings
    from ..time_domain.failures import largest_rate, rk4_steps_per_output
    from ..time_domain.integrators import compiled_by_default
    if method not in (None, "rk"):
        # the caller's method and tolerances (the model tolerance only sets rtol without a method)
        return integrator_settings(scene_run, (1.0, 1.0), int(getattr(model, "n_elements", 1)), method=method, **kw)
    p = model.parameters(scene_run)
    lam = largest_rate(model, start(scene_run, model) if x0 is None else x0, 0.0, p)
    num = scene_run.numerics
    spo = max(num.steps_per_output, rk4_steps_per_output(lam, num.output_step, RK4_MARGIN))
    extra = {} if kw.get("max_num_steps") is None else {"max_num_steps": int(kw["max_num_steps"])}
    return IntegratorSettings(method="rk", steps_per_output=spo, compiled=compiled_by_default(model, "rk"), **extra)


def run(scene: Scene, n: int, cache: RungCache, kw: dict | None = None, candidate: bool = True):
    """One run of the segmented cable at ``n`` elements with :func:`settings` (models and simulators
    from ``cache``). ``kw``: ``method``, ``rtol``, ``atol``, ``max_num_steps``, ``times``, ``x0``,
    ``on_block``, ``progress``, ``on_run`` as :func:`.auto.simulate` takes them (``candidate``: the run whose
    series is returned, :mod:`.hooks`)."""
    from ..time_domain import simulate
    kw = dict(kw or {})
    sc = rung_scene(scene, "segmented", n)
    model = cache.model(scene, "segmented", n)
    if kw.get("x0") is None:                   # once: the stable step is probed there and the run starts there
        kw["x0"] = start(sc, model, cache)
    s = settings(sc, model, kw.get("method"), kw["x0"], **{k: kw.get(k) for k in ("rtol", "atol", "max_num_steps")})
    times = kw.get("times")
    sim = cache.simulator(model, sc.output_times if times is None else times, s)
    what = f"segmented N = {n}" + ("" if candidate else " (extrapolation)")
    return simulate(sc, model=model, simulator=sim, x0=kw["x0"], **hooks(kw, what, candidate))


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


def refined_maximum(y, i: int) -> float:
    """The vertex of the parabola through samples i - 1, i, i + 1 (equally spaced) of a maximum at i, or y[i]
    at an end or where the three samples do not bend down. (A minimum is not refined: a tension minimum
    sits on the kink of the tension floor, where the parabola overshoots below it.)"""
    y = np.asarray(y, dtype=float)
    if i == 0 or i == len(y) - 1:
        return float(y[i])
    a, b, c = y[i - 1], y[i], y[i + 1]
    den = a - 2 * b + c
    return float(b) if den >= 0 else float(b - (c - a) ** 2 / (8 * den))


def statistics(result, period: float | None) -> dict:
    """:func:`.metrics.statistics` of ``result`` with the tension maxima refined between samples
    (:func:`refined_maximum`)."""
    st = metrics.statistics(result, period)
    t = np.asarray(result.time)
    idx = np.nonzero(metrics.window(t, period))[0]
    for k in result.labels:
        if metrics.base_label(k) in metrics.TENSIONS:
            y = np.asarray(result[k])
            st[f"{k}_max"] = refined_maximum(y, int(idx[np.argmax(y[idx])]))
    return st


def _numbers(*dicts) -> list:
    """The keys whose values are floats in every dict (statistics; counts and labels are left out)."""
    return [k for k, v in dicts[-1].items() if all(isinstance(d.get(k), float) for d in dicts)]


def limits(coarse: dict, fine: dict, order: float = ORDER, ratio: float = 2.0) -> dict:
    """Richardson limit f + (f - f_c) / (r^p - 1) of every number of ``fine`` (N) and ``coarse`` (N / r), for a
    discretisation error ~ N^-p (Richardson 1911)."""
    return {k: fine[k] + (fine[k] - coarse[k]) / (ratio**order - 1.0) for k in _numbers(coarse, fine)}


def observed_orders(f4: dict, f2: dict, f1: dict, ratio: float = 2.0) -> dict:
    """log_r(|f(N/r^2) - f(N/r)| / |f(N/r) - f(N)|) per number, coarsest run first (None where a difference is
    zero)."""
    out = {}
    for k in _numbers(f4, f2, f1):
        a, b = abs(f4[k] - f2[k]), abs(f2[k] - f1[k])
        out[k] = float(math.log(a / b) / math.log(ratio)) if a > 0 and b > 0 else None
    return out


def _leading(stats: dict) -> list:
    """The numbers whose order decides the asymptotic range: the largest body amplitude and the largest
    tension maximum (the scales of the relative errors)."""
    amps = [k for k in stats if k.endswith("_amplitude")]
    tops = [k for k in stats if k.endswith("_max")]
    return [max(amps, key=stats.get), max(tops, key=stats.get)]


def extrapolate(stats: dict, n: int, floor: float = 0.0) -> dict:
    """The extrapolated statistics of the runs at ``n`` / 4, ``n`` / 2, ``n`` and their estimated errors.

    Parameters
    ----------
    stats : dict
        {N: :func:`.metrics.statistics` of the run at N} holding n / 4, n / 2 and n.
    n : int
        The finest run.
    floor : float, optional
        The tension floor (N): an extrapolated tension minimum below it is set to it (the true one is not lower).

    Returns
    -------
    dict
        ``segments`` [n/4, n/2, n]; ``statistics``: first-order limits of (n/2, n); ``statistics_coarse``:
        of (n/4, n/2); ``observed_order`` per number and ``asymptotic`` (the leading numbers' orders within
        ORDER_RANGE); ``estimated_error`` {body, tension} of ``statistics``: |L(n/2) - L(n)| / (2^q - 1)
        (``remainder_factor``; when not asymptotic 1, and at least the correction |L(n) - f(n)|); ``time_series_error``: the n run's own,
        |f(n) - L(n)| relative (:func:`.metrics.errors`).
    """
    f4, f2, f1 = stats[n // 4], stats[n // 2], stats[n]
    fine, crossed = st.bound_extremes(limits(f2, f1), f1, max(floor, 0.0))
    coarse, _ = st.bound_extremes(limits(f4, f2), f2, max(floor, 0.0))
    orders = observed_orders(f4, f2, f1)
    lead = {k: orders.get(k) for k in _leading(f1)}
    asymptotic = not crossed and all(p is not None and ORDER_RANGE[0] <= p <= ORDER_RANGE[1] for p in lead.values())
    factor = 1.0 / (2.0**REMAINDER_ORDER - 1.0) if asymptotic else 1.0
    diff = metrics.errors(coarse, fine)
    series = metrics.errors(f1, fine)
    stated = {k: v * factor if asymptotic else max(v, series[k]) for k, v in diff.items()}
    return {"segments": [n // 4, n // 2, n], "order_assumed": ORDER, "remainder_order": REMAINDER_ORDER,
            "remainder_factor": factor, "statistics": fine, "statistics_coarse": coarse,
            "observed_order": orders, "leading_orders": lead, "asymptotic": asymptotic,
            "estimated_error": stated, "time_series_error": series, "not_extrapolated": crossed}


def until_done(scene: Scene, choice, tol, result, cache: RungCache, kw: dict | None = None) -> tuple:
    """(result, choice) after the coarse runs and the extrapolation (:func:`complete`) of ``result``, the
    run at ``choice.segments`` (by :func:`run`), N doubling (one more run each) while :func:`complete` asks."""
    known: dict = {}
    while True:
        choice, _, again = complete(scene, choice, result, tol, cache, kw, known)
        if not again:
            return result, choice
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
    ``estimated_error_time_series`` (the N run's own estimated error) and ``estimated_error_refers_to``."""
    d = choice.as_dict()
    block = choice.numbers.get("extrapolated")
    if block is not None:
        d.update(estimated_error_refers_to="the extrapolated statistics (model.extrapolated.statistics)",
                 estimated_error_time_series=dict(block["time_series_error"]), extrapolated=block)
    return d


def complete(scene: Scene, choice, result, tol, cache: RungCache, kw: dict | None = None,
             known: dict | None = None) -> tuple:
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
    period = metrics.forcing_period(scene)
    n = choice.segments
    if not result.success:
        return choice, None, False
    fine = scene.with_numerics(output_step=statistics_step(scene))
    coarse_kw = checking(kw or {})
    if fine.numerics.output_step == scene.numerics.output_step and (kw or {}).get("times") is None:
        known[n] = statistics(result, period)
    for m in (n, n // 2, n // 4):       # the N run again only when its output step does not resolve the snaps
        if m not in known:
            r = run(fine, m, cache, coarse_kw, candidate=False)
            if not r.success:
                reason = choice.reason + f"; extrapolation failed: the run at N = {m} failed ({r.message})"
                return dataclasses.replace(choice, reason=reason), None, False
            known[m] = statistics(r, period)
    block = extrapolate(known, n, max(s.cable.tension_floor for s in scene.sections))
    w = metrics.window(np.asarray(result.time), period)
    block["window_s"] = [float(np.asarray(result.time)[w][0]), float(result.time[-1])]
    e = block["estimated_error"]
    if (not block["asymptotic"] or not within(e, tol)) and 2 * n <= MAX_SEGMENTS:
        return dataclasses.replace(choice, segments=2 * n), block, True
    reason = (choice.reason + f"; statistics extrapolated (Richardson, order 1) from N = {n // 4}, {n // 2}, {n}: "
              f"estimated error of the extrapolated statistics body {e['body']:.2g}, tension {e['tension']:.2g} "
              f"(their difference to the limits of N = {n // 4}, {n // 2} x {block['remainder_factor']:.3g}); the time "
              f"series is the N = {n} run's, estimated error body {block['time_series_error']['body']:.2g}, "
              f"tension {block['time_series_error']['tension']:.2g}")
    if not block["asymptotic"]:
        orders = ", ".join(f"{k} {v:.2g}" if v is not None else f"{k} n/a" for k, v in block["leading_orders"].items())
        reason += (f"; NOT in the asymptotic range (observed orders {orders}): the stated error is the larger of the "
                   "whole difference of the two limits and the extrapolation's correction; a statistics window that "
                   "still holds the start-up transient does not converge smoothly in N (slack scenes settle slowly): "
                   "a longer duration helps")
        warnings.warn(f"model auto: {reason}", NumericalWarning, stacklevel=3)
    elif not within(e, tol):
        warnings.warn(f"model auto: tolerance not reached at N = {n}: {reason}", NumericalWarning, stacklevel=3)
    numbers = dict(choice.numbers, extrapolated=block)
    return dataclasses.replace(choice, reason=reason, estimated_error=dict(e), numbers=numbers), block, False
