"""Per-cycle statistics of a periodically forced run (cablesys or MoorDyn, same arrays).

A slack-and-snap response is not steady after a few periods: on the 300 m / 2 t scene at T = 6 s
the first ~100 s are a transient (a period-2 bounce that grows, then the body's mean lifts by
~1.5 m), and extremes taken over a short window ending inside it depend on tiny differences
(tolerance, N) through *when* the transition happens, not through the settled motion. So every
figure here is the mean over the forcing cycles of a window that starts after the transient, with
its spread over those cycles (zero for a periodic response, the sign that the window is settled).

Extremes between samples: a tension peak of a snap lasts about the axial travel time (0.08 s on
300 m of steel wire), so a sampled maximum is refined by the parabola through the largest sample
and its two neighbours. Minima are the sampled ones: a tension minimum sits on the kink of the
tension floor (max(TENS, ...)), where a parabola through three samples overshoots below the floor.
"""

from __future__ import annotations

import numpy as np

from cablesys.ladder.richardson import refined_maximum


def cycle_statistics(time, series: dict, period: float, t0: float, t1: float | None = None,
                     *, strain=None, law_slack=None) -> dict:
    """Means (and spreads) over the whole forcing cycles in [t0, t1] of a run.

    Parameters
    ----------
    time : array_like
        Output times (s), equally spaced.
    series : dict
        ``y_b``, ``x_b`` (m) and ``tension_top``, ``tension_bottom`` (N): arrays over ``time``.
    period : float
        Forcing period (s); cycles start at t0 + k period.
    t0, t1 : float
        The window (s); t1 defaults to the last time.
    strain : array_like, optional
        Element strains (time x element, element 0 at the top): elastic slack fraction (strain <= 0)
        of the top and bottom elements and of the line (any element slack).
    law_slack : array_like, optional
        cablesys's element slack flags (tension law at or below its floor), same layout.

    Returns
    -------
    dict
        ``y_amp`` / ``x_amp`` (m, mean over cycles of half the cycle's range), ``y_min``, ``y_max``
        (m), ``top_max``, ``top_min``, ``bottom_max``, ``bottom_min`` (N, mean of the cycles'
        extremes, maxima refined between samples), each with ``<name>_spread`` (max - min over the cycles), ``cycles``, the
        slack fractions asked for, and ``window_s``.
    """
    t = np.asarray(time, dtype=float)
    t1 = float(t[-1]) if t1 is None else t1
    n_cyc = int(np.floor((t1 - t0) / period + 1e-9))
    if n_cyc < 1:
        raise ValueError(f"window [{t0}, {t1}] s holds no whole cycle of {period} s")
    per = {k: [] for k in ("y_amp", "x_amp", "y_min", "y_max", "top_max", "top_min", "bottom_max", "bottom_min")}
    for c in range(n_cyc):
        m = np.nonzero((t >= t0 + c * period - 1e-9) & (t < t0 + (c + 1) * period - 1e-9))[0]
        y, x = np.asarray(series["y_b"])[m], np.asarray(series["x_b"])[m]
        per["y_amp"].append(0.5 * (y.max() - y.min()))
        per["x_amp"].append(0.5 * (x.max() - x.min()))
        per["y_min"].append(y.min())
        per["y_max"].append(y.max())
        for name, key in (("top", "tension_top"), ("bottom", "tension_bottom")):
            full = np.asarray(series[key])
            i_max, i_min = m[np.argmax(full[m])], m[np.argmin(full[m])]
            per[f"{name}_max"].append(refined_maximum(full, i_max))
            per[f"{name}_min"].append(float(full[i_min]))
    out = {"window_s": [t0, t0 + n_cyc * period], "cycles": n_cyc}
    for k, v in per.items():
        out[k] = float(np.mean(v))
        out[f"{k}_spread"] = float(np.ptp(v))
    w = (t >= t0 - 1e-9) & (t < t0 + n_cyc * period - 1e-9)
    if strain is not None:
        s = np.asarray(strain)[w] <= 0.0
        out.update(slack_top=float(s[:, 0].mean()), slack_bottom=float(s[:, -1].mean()),
                   slack_any=float(s.any(axis=1).mean()), slack_all=float(s.all(axis=1).mean()),
                   slack_per_element=[float(v) for v in s.mean(axis=0)])
    if law_slack is not None:
        s = np.asarray(law_slack)[w] > 0.5
        out.update(law_slack_top=float(s[:, 0].mean()), law_slack_bottom=float(s[:, -1].mean()))
    return out


# -- shared with studies/model_ladder.py: the settled figures in the ladder's error terms ---------------

def settled_window_start(ramp_s: float, period: float, duration: float) -> float:
    """Start of the statistics window: the second half of the run, on the forcing-cycle grid after
    the ramp (the slack scene, 360 s with a 18 s ramp at T = 6 s: 180 s), or the ramp's end when the
    run is shorter than twice the ramp."""
    return ramp_s + max(0, int(np.floor((duration / 2 - ramp_s) / period + 1e-9))) * period


def ladder_statistics(result, period: float, t0: float, t1: float | None = None) -> dict:
    """:func:`cycle_statistics` of a run, named as :func:`cablesys.ladder.metrics.statistics` names
    its figures (so :func:`cablesys.ladder.metrics.errors` compares them): ``x_b_amplitude``,
    ``y_b_amplitude`` (m), ``tension_top_max`` / ``_min``, ``tension_bottom_max`` / ``_min`` (N),
    each a mean over the whole forcing cycles of [t0, t1], with ``spread`` (max - min over the
    cycles of each), ``window_s`` and ``cycles``."""
    series = {k: np.asarray(result[k]) for k in ("x_b", "y_b", "tension_top", "tension_bottom")}
    st = cycle_statistics(result.time, series, period, t0, t1)
    names = {"x_b_amplitude": "x_amp", "y_b_amplitude": "y_amp", "tension_top_max": "top_max",
             "tension_top_min": "top_min", "tension_bottom_max": "bottom_max", "tension_bottom_min": "bottom_min"}
    out = {k: st[v] for k, v in names.items()}
    out["spread"] = {k: st[f"{v}_spread"] for k, v in names.items()}
    return {**out, "window_s": st["window_s"], "cycles": st["cycles"]}
