"""A body resting on the seabed: the quantities that converge at first order in N, extrapolated at that order.

Landed under a hanging line (a package lowered onto the bed), a body's node carries the half element above it,
w h / 2 (h = L / N), and the bed takes it with the body: stretched, the line is a little longer than the depth, so its
last element is slack (the continuum lays that excess, millimetres, on the bed and hangs from the top with T = w s,
s from the bed). So while the body rests, the top tension is w (L - h / 2) and the line's pull on the body the half
element's weight w h / 2, both first order in 1 / N with exactly that term (tests/test_seabed_landing.py; the
continuum's are w L and 0). The a posteriori check, which assumes the taut line's second order (:mod:`.checks`),
judged such a run at the wrong order: it understated the error 3x and doubled N to its cap for the line's pull on the
body, whose first-order part no N resolves to a hundredth of the top tension.

The check judges it at its true order instead: with runs at N / 4, N / 2 and N, each quantity whose observed order
p = log2(|f(N/4) - f(N/2)| / |f(N/2) - f(N)|) is within :data:`FIRST_ORDER`, with a difference above the least stated
error (est.RESOLUTION, relative; smaller ones are the integrator's noise, whose ratios mean nothing), is reported by its first-order limit
L(N) = 2 f(N) - f(N / 2) (Richardson 1911), its stated error the difference of the limits |L(N) - L(N / 2)| (the
conservative factor 1 of :mod:`.richardson`: the remainder's order is not assumed); the others (converged at the taut
line's second order, or to the integrator's noise) keep the N run's value and the taut check's |f(N) - f(N / 2)| / 3.
The time series is the N run's, whose own error against these statistics is stated apart, as for partial slack
(:mod:`.extrapolation`).
"""

from __future__ import annotations

import math

import numpy as np

from . import estimate as est
from . import metrics

FIRST_ORDER = (0.75, 1.5)     # observed orders read as the first-order term's (the landed tensions': 1.00)
TAUT_ORDER = est.ORDER         # the other quantities' order, as in the taut check (.checks.richardson)


def landed_sections(scene, result, period, ramp_s) -> list[int]:
    """The sections whose body is free (not at an ``[anchor]``) and rests on the ``[seabed]`` at some time of the
    statistics window: its node's normal force from the bed (``seabed_normal``, :mod:`cablesys.model.segmented_seabed`)
    above zero. Empty without a seabed. ``scene`` is the scene the run ran (its sections' ``segments``)."""
    if getattr(scene, "seabed", None) is None or "seabed_normal" not in getattr(result, "profiles", {}):
        return []
    normal = np.asarray(result.profiles["seabed_normal"])
    w = metrics.window(np.asarray(result.time), period, ramp_s)
    out, node = [], 0
    last = len(scene.sections) - 1
    for i, sec in enumerate(scene.sections):
        node += sec.cable.segments
        if i == last and scene.anchor is not None:
            break
        if node < normal.shape[1] and np.any(normal[w, node] > 0.0):
            out.append(i)
    return out


def _orders(f4: dict, f2: dict, f1: dict) -> dict:
    out = {}
    for k in f1:
        a, b = abs(f4[k] - f2[k]), abs(f2[k] - f1[k])
        out[k] = float(math.log2(a / b)) if a > 0 and b > 0 else None
    return out


def _relative(abs_err: dict, reference: dict) -> tuple[dict, dict]:
    """({body, tension}, {quantity: e}) of absolute errors, normalised as :func:`.metrics.errors` (the largest
    amplitude, the largest top tension) and :func:`.metrics.quantity_errors` (each its own value, with floors)."""
    amps = [k for k in reference if k.endswith("_amplitude")]
    tops = [k for k in reference if k.endswith("_max")]
    a_ref, t_ref = max((reference[k] for k in amps), default=0.0), max((reference[k] for k in tops), default=0.0)
    floor_n = metrics.TENSION_FLOOR_FRACTION * t_ref
    per = {k: max(v / max(abs(reference[k]), floor_n if metrics.group(k) == "tension" else metrics.LENGTH_FLOOR_M,
                          1e-300), est.RESOLUTION) for k, v in abs_err.items()}
    group = {"body": max((v for k, v in abs_err.items() if metrics.group(k) == "body"), default=0.0) / max(a_ref, 1e-300),
             "tension": max((v for k, v in abs_err.items() if metrics.group(k) == "tension"), default=0.0)
             / max(t_ref, 1e-300)}
    return {k: max(v, est.RESOLUTION) for k, v in group.items()}, per


def extrapolate(f4: dict, f2: dict, f1: dict, n: int) -> dict:
    """The statistics of a landed run (module docstring) from :func:`.metrics.statistics` of its runs at ``n`` / 4,
    ``n`` / 2 and ``n``: a block shaped as :func:`.richardson.extrapolate`'s (``segments``, ``statistics``,
    ``observed_order``, ``estimated_error``, ``estimated_error_per_quantity``, ``time_series_error``,
    ``time_series_error_per_quantity``) with ``extrapolated_quantities``, the first-order ones. Tension extremes are
    kept >= 0."""
    keys = [k for k in f1 if all(isinstance(d.get(k), float) for d in (f4, f2, f1))]
    f4, f2, f1 = ({k: d[k] for k in keys} for d in (f4, f2, f1))
    orders = _orders(f4, f2, f1)
    _, moved = _relative({k: abs(f4[k] - f2[k]) for k in keys}, f1)     # relative differences, floored as stated
    first = [k for k in keys if orders[k] is not None and FIRST_ORDER[0] <= orders[k] <= FIRST_ORDER[1]
             and moved[k] > est.RESOLUTION]
    clip = lambda k, v: max(v, 0.0) if metrics.group(k) == "tension" else v
    stats, err = {}, {}
    for k in keys:
        if k in first:
            fine, coarse = 2.0 * f1[k] - f2[k], 2.0 * f2[k] - f4[k]
            stats[k] = clip(k, fine)
            err[k] = abs(stats[k] - clip(k, coarse))
        else:
            stats[k] = f1[k]
            err[k] = abs(f1[k] - f2[k]) / (2.0 ** TAUT_ORDER - 1.0)
    stated, per = _relative(err, stats)
    series, series_q = _relative({k: abs(f1[k] - stats[k]) for k in keys}, stats)
    return {"segments": [n // 4, n // 2, n], "order_assumed": 1.0, "statistics": stats, "observed_order": orders,
            "extrapolated_quantities": first, "estimated_error": stated, "estimated_error_per_quantity": per,
            "time_series_error": series, "time_series_error_per_quantity": series_q}


def note(scene, sections: list[int], block: dict | None) -> str:
    """The reason's clause on a landed run: which sections' bodies rest on the bed, which quantities were extrapolated
    at first order (``block`` of :func:`extrapolate`, None: none), and for a body without a footprint
    (``body.bed_area`` unset) that its landed state does not converge in N: held by its cable's half element alone,
    whose contact area d h / 2 falls with N, it sinks until the cable takes its weight."""
    which = ", ".join(str(i + 1) for i in sections)
    text = f"a body rests on the seabed (section {which}): "
    if block is not None:
        n = block["segments"]
        text += (f"{', '.join(block['extrapolated_quantities'])} first order in N, their first-order limits from "
                 f"N = {n[0]}, {n[1]}, {n[2]}; ")
    bare = [i for i in sections if not scene.sections[i].body.bed_area]
    if bare:
        text += (f"body.bed_area unset in section {', '.join(str(i + 1) for i in bare)}: a body without a footprint "
                 "is held on the bed by its cable's half element alone, whose contact area falls with N, so its landed "
                 "state does not converge in N (it sinks until the cable takes its weight); ")
    return text
