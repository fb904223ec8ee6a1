"""Richardson extrapolation of the statistics of runs at N / 4, N / 2 and N (Richardson 1911), and its stated error.

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

Two triples outside the range keep their conservative (factor 1) error instead of doubling N
(:func:`needs_doubling`): one whose error is below NOISE_FRACTION x the tolerance (its differences are then too
small for their order to mean anything), and one whose leading differences keep one sign and shrink faster than
the range, with its error within the tolerance (the packaged light-cage lift, ``cablesys scene --example
light-lift``, is such a case over 600 s; tests/test_ladder_extrapolation.py holds both rules).
"""

from __future__ import annotations

import math

import numpy as np

from .. import statistics as st
from . import estimate as est
from . import metrics
from .choice import within

ORDER = 1.0                 # the leading order extrapolated away (estimate.SLACK_ORDER)
REMAINDER_ORDER = est.REMAINDER_ORDER   # q of the next term (an expansion in integer powers of 1/N)
ORDER_RANGE = (0.5, 3.0)    # observed orders accepted as asymptotic (above 1: the remainder dominates, still N^-q)
NOISE_FRACTION = 0.1        # a non-asymptotic triple whose conservative error is below this x the tolerance is kept


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


def statistics(result, period: float | None, ramp_s: float | None = None) -> dict:
    """:func:`.metrics.statistics` of ``result`` (forcing period and smooth start ``ramp_s`` in s, default the
    run's own) with the tension maxima refined between samples (:func:`refined_maximum`)."""
    st = metrics.statistics(result, period, ramp_s)
    t = np.asarray(result.time)
    idx = np.nonzero(metrics.window(t, period, ramp_s))[0]
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
        (``remainder_factor``; when not asymptotic 1, and at least the correction |L(n) - f(n)|); ``estimated_error_per_quantity``:
        the same per number of ``statistics``, each relative to its own value with the floors of
        :func:`.metrics.quantity_errors`, the remainder factor only where that number's own observed order is within
        ORDER_RANGE too (else the whole difference, at least the correction), at least est.RESOLUTION; ``time_series_error``: the n run's own,
        |f(n) - L(n)| relative (:func:`.metrics.errors`; per number: ``time_series_error_per_quantity``).
    """
    f4, f2, f1 = stats[n // 4], stats[n // 2], stats[n]
    fine, crossed = st.bound_extremes(limits(f2, f1), f1, max(floor, 0.0))
    coarse, _ = st.bound_extremes(limits(f4, f2), f2, max(floor, 0.0))
    orders = observed_orders(f4, f2, f1)
    lead = {k: orders.get(k) for k in _leading(f1)}
    asymptotic = not crossed and all(p is not None and ORDER_RANGE[0] <= p <= ORDER_RANGE[1] for p in lead.values())
    # converging at least as fast as the range: every leading number's differences of one sign and shrinking at an
    # order >= ORDER_RANGE[0] (above the range: faster than the remainder, the conservative error then holds the tail)
    monotone = {k: (f4[k] - f2[k]) * (f2[k] - f1[k]) > 0 for k in lead}
    converging = not crossed and all(p is not None and p >= ORDER_RANGE[0] and monotone[k] for k, p in lead.items())
    factor = 1.0 / (2.0**REMAINDER_ORDER - 1.0) if asymptotic else 1.0
    diff = metrics.errors(coarse, fine)
    series = metrics.errors(f1, fine)
    stated = {k: v * factor if asymptotic else max(v, series[k]) for k, v in diff.items()}
    # per quantity: the same rule on each number, relative to its own value with the floors of
    # metrics.quantity_errors (a mean offset or a small amplitude is judged on itself, not on the largest one), and on
    # its own observed order: a number outside ORDER_RANGE is not first order in N whatever the leading ones are
    # (the light lift in Hs 7 m, N = 16, 32, 64: leading orders 0.64 and 2.1, the top tension minimum's -1.2; its limit
    # was 27 % off the reference's while the remainder estimate said 18 %: studies/slack_convergence.py)
    diff_q, series_q = metrics.quantity_errors(coarse, fine), metrics.quantity_errors(f1, fine)
    in_range = {k: p is not None and ORDER_RANGE[0] <= p <= ORDER_RANGE[1] for k, p in orders.items()}
    per = {k: max(v * factor if asymptotic and in_range.get(k, False) else max(v, series_q[k]), est.RESOLUTION)
           for k, v in diff_q.items()}
    return {"segments": [n // 4, n // 2, n], "order_assumed": ORDER, "remainder_order": REMAINDER_ORDER,
            "remainder_factor": factor, "statistics": fine, "statistics_coarse": coarse,
            "observed_order": orders, "leading_orders": lead, "asymptotic": asymptotic,
            "estimated_error": stated, "estimated_error_per_quantity": per, "time_series_error": series,
            "time_series_error_per_quantity": series_q, "not_extrapolated": crossed, "converging": converging}


def needs_doubling(block: dict, tol) -> bool:
    """Whether the extrapolation ``block`` (:func:`extrapolate`) asks for 2 N under the tolerances ``tol`` (body,
    tension): its stated error misses them, or its runs are not in the asymptotic range while their conservative
    error (factor 1, at least the correction) is above NOISE_FRACTION x the tolerances. Below that the observed order
    is of differences too small to mean anything, the conservative error stands and doubling would buy an order the
    tolerance does not need (``block["settled_in_noise"]`` is set True then). Runs converging faster than the range
    (``block["converging"]``: the leading numbers' differences of one sign, shrinking at an order above
    ORDER_RANGE[1] or within it) keep their conservative error
    when it is within the tolerance: shrinking by 2^p >= 8 per doubling, the differences past N sum to at most 1/7 of
    the last one, which the conservative error holds; a number within the range has 3x its remainder estimate
    (``block["kept_converging"]``)."""
    e = block["estimated_error"]
    block["settled_in_noise"] = bool(not block["asymptotic"]
                                     and within(e, (NOISE_FRACTION * tol[0], NOISE_FRACTION * tol[1])))
    block["kept_converging"] = bool(not block["asymptotic"] and not block["settled_in_noise"]
                                    and block.get("converging", False) and within(e, tol))
    return not within(e, tol) or not (block["asymptotic"] or block["settled_in_noise"] or block["kept_converging"])
