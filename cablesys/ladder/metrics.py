"""How far one run is from another: the errors the model tolerance speaks of.

Over a statistics window (default: the last 5 forcing periods, at most the last half of the run):
``body``, the largest difference of the body's x and y amplitudes (half peak-to-peak) relative to
the larger reference amplitude; ``tension``, the largest difference of the top and body-end tension
extremes relative to the largest reference tension.
"""

from __future__ import annotations

import re

import numpy as np

from .. import statistics as st

BODY = ("x_b", "y_b")
TENSIONS = ("tension_top", "tension_bottom")
_SUFFIX = re.compile(r"_\d+$")


def base_label(label: str) -> str:
    """``label`` without its section suffix (``tension_top_2`` -> ``tension_top``; a chain of sections labels
    its outputs with :func:`cablesys.scene.labels.section_suffix`)."""
    return _SUFFIX.sub("", label)


def _labels(result, bases) -> list:
    """The labels of ``result`` with these base names (a record without ``labels``: the bases themselves)."""
    labels = getattr(result, "labels", None)
    return list(bases) if labels is None else [k for k in labels if base_label(k) in bases]


def window(time: np.ndarray, period: float | None, n_periods: int = 5) -> np.ndarray:
    """Boolean mask of the statistics window: the last ``n_periods`` periods, at most the last half."""
    t0, t1 = float(time[0]), float(time[-1])
    span = 0.5 * (t1 - t0) if period is None else min(n_periods * period, 0.5 * (t1 - t0))
    return time >= t1 - span - 1e-12


def statistics(result, period: float | None) -> dict:
    """Body amplitudes and tension extremes of ``result`` (a TimeResult) over the window (every section's
    bodies and end tensions in a chain: ``x_b_2_amplitude``, ``tension_top_2_max``, ...)."""
    w = window(np.asarray(result.time), period)
    out = {f"{k}_amplitude": a for k, a in _amplitudes(result, w).items()}
    for k in _labels(result, TENSIONS):
        y = np.asarray(result[k])[w]
        out[f"{k}_max"], out[f"{k}_min"] = max(float(y.max()), 0.0), max(float(y.min()), 0.0)
    return out


def _amplitudes(result, mask) -> dict:
    """{body label: half peak-to-peak} of ``result`` over the samples ``mask``."""
    return {k: st.half_range(np.asarray(result[k])[mask]) for k in _labels(result, BODY)}


def window_change(result, period: float | None) -> float:
    """How much the body amplitudes still change within the statistics window: the largest difference of the
    x and y amplitudes (half peak-to-peak) between its first and second half, relative to the larger second-half
    amplitude (the body error's normalization). Settled runs: below 1e-3 (Dale 60 s 0, the 1000 m wire 120 s
    8e-4); runs still building up: 0.02-0.2 (the 1000 m wire over 40 s 0.046, a cable forced at its first
    string mode over 7 periods 0.11, over 25 periods 2e-4)."""
    t = np.asarray(result.time)
    w = window(t, period)
    tw = t[w]
    if tw.size < 4:
        return 0.0
    mid = 0.5 * (tw[0] + tw[-1])
    halves = [_amplitudes(result, w & (t <= mid)), _amplitudes(result, w & (t >= mid))]
    scale = max(max(halves[1].values(), default=0.0), st.FLOORS["m"])
    return max((st.amplitude_change(halves[0][k], halves[1][k], st.FLOORS["m"], scale) for k in halves[0]), default=0.0)


def errors(stats: dict, reference: dict) -> dict:
    """{"body": e, "tension": e} of ``stats`` against ``reference`` (both from :func:`statistics`)."""
    amps = [k for k in reference if k.endswith("_amplitude")]
    tops = [k for k in reference if k.endswith("_max")]
    ext = tops + [k for k in reference if k.endswith("_min")]
    a_ref = max(reference[k] for k in amps)
    t_ref = max(reference[k] for k in tops)
    body = max(abs(stats[k] - reference[k]) for k in amps) / max(a_ref, 1e-300)
    tension = max(abs(stats[k] - reference[k]) for k in ext) / max(t_ref, 1e-300)
    return {"body": float(body), "tension": float(tension)}


def forcing_period(scene) -> float | None:
    """The longest period of the top-motion sinusoids (None without sinusoids)."""
    freqs = [s.frequency for s in scene.top_motion.x + scene.top_motion.y if s.amplitude != 0.0]
    return 2 * np.pi / min(freqs) if freqs else None
