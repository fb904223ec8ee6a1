"""How far one run is from another: the errors the model tolerance speaks of.

Over the run's statistics window (:func:`cablesys.statistics.window`, the one window of a run's summary):
``body``, the largest difference of the body's x and y (and z in 3-D) amplitudes (half peak-to-peak) relative to
the larger reference amplitude; ``tension``, the largest difference of the top and body-end tension
extremes relative to the largest reference tension. A system of lines joined at points (model/system.py) has no
``x_b`` or ``tension_top``: its points' coordinates (``point.NAME.x``) are the body group, its lines' end tensions
(``line.NAME.tension_from``, ``tension_to``) the tension group.
"""

from __future__ import annotations

import re

import numpy as np

from .. import statistics as st

BODY = ("x_b", "y_b", "z_b")        # z_b: the sway of a 3-D run (absent from planar runs)
TENSIONS = ("tension_top", "tension_bottom")
_SUFFIX = re.compile(r"_\d+$")
# the same groups of a system of lines (model/system.py): every point's coordinates, every line's end tensions
_SYSTEM = {BODY: re.compile(r"^point\.[^.]+\.[xyz]$"), TENSIONS: re.compile(r"^line\.[^.]+\.tension_(from|to)$")}


def base_label(label: str) -> str:
    """``label`` without its section suffix (``tension_top_2`` -> ``tension_top``; a chain of sections labels
    its outputs with :func:`cablesys.scene.labels.section_suffix`)."""
    return _SUFFIX.sub("", label)


def _labels(result, bases) -> list:
    """The labels of ``result`` with these base names (a record without ``labels``: the bases themselves)."""
    labels = getattr(result, "labels", None)
    if labels is None:
        return list(bases)
    system = _SYSTEM.get(tuple(bases))
    return [k for k in labels if base_label(k) in bases or (system is not None and system.match(k))]


def window(time: np.ndarray, period: float | None, ramp_s: float = 0.0) -> np.ndarray:
    """Boolean mask of the statistics window (:func:`cablesys.statistics.window`; forcing period and smooth start
    in s)."""
    return st.window_mask(time, *st.window(time, period, ramp_s)[:2])


def _ramp(result, ramp_s):
    """``ramp_s`` (s), else the smooth start the run ``result`` carries (0 without one)."""
    return float(getattr(result, "ramp_s", 0.0) or 0.0) if ramp_s is None else float(ramp_s)


def statistics(result, period: float | None, ramp_s: float | None = None) -> dict:
    """Body amplitudes and means and tension extremes of ``result`` (a TimeResult) over the window (every section's
    bodies and end tensions in a chain: ``x_b_2_amplitude``, ``x_b_2_mean``, ``tension_top_2_max``, ...); the smooth
    start ``ramp_s`` (s) defaults to the run's own."""
    w = window(np.asarray(result.time), period, _ramp(result, ramp_s))
    out = {f"{k}_amplitude": a for k, a in _amplitudes(result, w).items()}
    out.update({f"{k}_mean": float(np.mean(np.asarray(result[k])[w])) for k in _labels(result, BODY)})
    for k in _labels(result, TENSIONS):
        y = np.asarray(result[k])[w]
        out[f"{k}_max"], out[f"{k}_min"] = max(float(y.max()), 0.0), max(float(y.min()), 0.0)
    return out


def _amplitudes(result, mask) -> dict:
    """{body label: half peak-to-peak} of ``result`` over the samples ``mask``."""
    return {k: st.half_range(np.asarray(result[k])[mask]) for k in _labels(result, BODY)}


def window_change(result, period: float | None, ramp_s: float | None = None) -> float:
    """How much the body amplitudes still change within the statistics window: the largest difference of the
    x and y amplitudes (half peak-to-peak) between its first and second half, relative to the larger second-half
    amplitude (the body error's normalization). Settled runs: below 1e-3 (Dale 60 s 0, the 1000 m wire 120 s
    8e-4); runs still building up: 0.02-0.2 (the 1000 m wire over 40 s 0.046, a cable forced at its first
    string mode over 7 periods 0.11, over 25 periods 2e-4)."""
    t = np.asarray(result.time)
    w = window(t, period, _ramp(result, ramp_s))
    tw = t[w]
    if tw.size < 4:
        return 0.0
    mid = 0.5 * (tw[0] + tw[-1])
    halves = [_amplitudes(result, w & (t <= mid)), _amplitudes(result, w & (t >= mid))]
    scale = max(max(halves[1].values(), default=0.0), st.FLOORS["m"])
    return max((st.amplitude_change(halves[0][k], halves[1][k], st.FLOORS["m"], scale) for k in halves[0]), default=0.0)


def errors(stats: dict, reference: dict, factors: dict | None = None) -> dict:
    """{"body": e, "tension": e} of ``stats`` against ``reference`` (both from :func:`statistics`), each difference
    times its ``factors`` entry when given (default 1). A system's body group (its points' coordinates) is relative to
    the larger of its largest amplitude and :func:`body_floor`, a chain's to its body's largest amplitude."""
    amps = [k for k in reference if k.endswith("_amplitude")]
    tops = [k for k in reference if k.endswith("_max")]
    ext = tops + [k for k in reference if k.endswith("_min")]
    a_ref = max(reference[k] for k in amps)
    t_ref = max(reference[k] for k in tops)
    f = factors or {}
    # a system's points (held ones among them) may all stand still (a mooring in a current): its body group is judged
    # on at least body_floor(reference), the scale its every body quantity is judged on (quantity_differences)
    scale = max(a_ref, body_floor(reference)) if any(k.startswith("point.") for k in amps) else a_ref
    body = max(abs(stats[k] - reference[k]) * f.get(k, 1.0) for k in amps) / max(scale, 1e-300)
    tension = max(abs(stats[k] - reference[k]) * f.get(k, 1.0) for k in ext) / max(t_ref, 1e-300)
    return {"body": float(body), "tension": float(tension)}


LENGTH_FLOOR_M = 0.01           # a body coordinate's error is judged on at least 1 cm
BODY_FLOOR_FRACTION = 0.1       # ... and on at least a tenth of the largest body amplitude
TENSION_FLOOR_FRACTION = 0.01   # a tension extreme's on at least 1 % of the largest top tension


def group(key: str) -> str:
    """The tolerance a quantity of :func:`statistics` answers to: "body" (m) or "tension" (N)."""
    return "tension" if key.endswith(("_max", "_min")) else "body"


def body_floor(reference: dict) -> float:
    """The least length (m) a body quantity of ``reference`` (:func:`statistics`) is judged on: LENGTH_FLOOR_M, or
    BODY_FLOOR_FRACTION x the largest body amplitude when that is more. A coordinate that barely moves beside a large
    motion is judged on the motion's scale, as a small tension extreme is on the top tension's: in a steady turn of
    75 m radius the depth amplitude is zero and the integrator's millimetres there (rtol 1e-4 on 75 m coordinates)
    are 1e-5 of the motion, not 40 % of a centimetre; a surge amplitude of a few centimetres under a 1 m heave (the
    sheared current of ``tests/test_ladder_quantities.py``) is still judged on a decimetre, so an error of half of
    it stays visible."""
    amps = [abs(v) for k, v in reference.items() if k.endswith("_amplitude")]
    return max(LENGTH_FLOOR_M, BODY_FLOOR_FRACTION * max(amps, default=0.0))


def quantity_errors(stats: dict, reference: dict) -> dict:
    """{quantity: relative error} of ``stats`` against ``reference`` (both from :func:`statistics`), each relative to
    its own reference value with a floor: :func:`body_floor` for the body's amplitudes and means (a 2 cm sway under a
    10 cm heave is judged on centimetres, not on the heave; a millimetre depth wobble in a 75 m turn is judged on the
    turn), TENSION_FLOOR_FRACTION x the largest top tension for the tension extremes (a slack minimum of 0 N is judged
    on that)."""
    return quantity_differences(stats, reference, reference)


def quantity_differences(a: dict, b: dict, reference: dict) -> dict:
    """{quantity: |a - b|} relative to the scale :func:`quantity_errors` gives each quantity of ``reference`` (its own
    value, or the floor): differences of two runs judged on a third's scales."""
    tops = [v for k, v in reference.items() if k.endswith("_max")]
    floor_n = TENSION_FLOOR_FRACTION * max(tops, default=0.0)
    floor_m = body_floor(reference)
    out = {}
    for k, ref in reference.items():
        if k not in a or k not in b:
            continue
        floor = floor_n if group(k) == "tension" else floor_m
        out[k] = float(abs(a[k] - b[k]) / max(abs(ref), floor, 1e-300))
    return out


def forcing_period(scene) -> float | None:
    """The forcing period (s) that sets every statistics window: the longest period of the top-motion
    sinusoids; None without sinusoids and for an irregular sea or a recorded motion, whose window is the run's
    second half (:attr:`cablesys.scene.TopMotion.window_period_s`)."""
    return scene.top_motion.window_period_s
