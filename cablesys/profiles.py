"""Profiles along the cable and snap loads from sampled series (a leaf module: numpy only).

A segmented run (:mod:`cablesys.model.segmented`) outputs, besides the per-section series, the
tension, tension rate, strain and slack flag of every element and the position of every node,
as labels ``name[k]``. :func:`split_profiles` gathers them into 2-D arrays (time x element, time
x node) with their unstretched arc lengths ``element_s`` and ``node_s`` as coordinates.

Snap loads: an element that was slack (its law fell to the floor, Wang 1971 eq. 54) and tenses
again is followed by tension peaks. :func:`snap_events` finds every re-tensioning and every local
maximum of the tension after it, until the element goes slack again; each peak is located
between the output samples on the cubic Hermite interpolant of the tension and its rate (the
model's exact dT/dt), so a peak between two samples is not cut off.
"""

from __future__ import annotations

import re

import numpy as np

from . import statistics as st

_LABEL = re.compile(r"^(\w+)\[(\d+)\]$")
COORDINATES = {"element": "element_s", "node": "node_s"}


def split_profiles(data: dict) -> tuple[dict, dict]:
    """Split labelled series into scalar series and profiles.

    Parameters
    ----------
    data : dict
        ``{label: (n_times,) array}``; labels ``name[k]`` belong to the profile ``name``.

    Returns
    -------
    (dict, dict)
        The scalar series, and ``{name: (n_times, n_k) array}``; the arc-length coordinates
        ``element_s`` and ``node_s`` (constant in time) become 1-D arrays.
    """
    scalars, groups = {}, {}
    for label, series in data.items():
        m = _LABEL.match(label)
        if m is None:
            scalars[label] = series
        else:
            groups.setdefault(m.group(1), {})[int(m.group(2))] = np.asarray(series)
    profiles = {}
    for name, cols in groups.items():
        arr = np.column_stack([cols[k] for k in sorted(cols)])
        profiles[name] = arr[0] if name in COORDINATES.values() else arr
    return scalars, profiles


def dimension_of(name: str) -> str:
    """'element' or 'node' for a profile name (``element_tension`` -> ``element``)."""
    return name.split("_", 1)[0]


def statistics_window(time, window_s=None, period=None, settled_s=0.0) -> tuple[float, float]:
    """The statistics window [t0, t1] (s): as given (``window_s``), else :func:`cablesys.statistics.window` of the
    run with forcing period ``period`` (s) and smooth start ``settled_s`` (s)."""
    if window_s is not None:
        return float(window_s[0]), float(window_s[1])
    return st.window(time, period, settled_s)[:2]


def hermite_peak(t0, t1, y0, y1, d0, d1) -> tuple[float, float]:
    """Maximum of the cubic Hermite interpolant on [t0, t1] through (y, dy/dt) at both ends.

    Returns
    -------
    (float, float)
        Time and value of the maximum (an end point when the cubic has no interior maximum).
    """
    h = t1 - t0
    # p(s) = a s^3 + b s^2 + c s + y0, s in [0, 1]
    c = d0 * h
    a = 2 * (y0 - y1) + (d0 + d1) * h
    b = 3 * (y1 - y0) - (2 * d0 + d1) * h
    cand = [0.0, 1.0]
    roots = np.roots([3 * a, 2 * b, c]) if abs(a) + abs(b) > 0 else []
    cand += [float(r.real) for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and 0.0 < r.real < 1.0]
    vals = [((a * s + b) * s + c) * s + y0 for s in cand]
    k = int(np.argmax(vals))
    return float(t0 + cand[k] * h), float(vals[k])


def snap_events(time, tension, rate, slack) -> list[dict]:
    """Every re-tensioning of one element and the tension peaks that follow it.

    Parameters
    ----------
    time : (n,) array
        Output times (s).
    tension, rate : (n,) arrays
        Tension (N) and its time derivative (N/s).
    slack : (n,) array of bool
        True where the element is slack (its law at or below the floor).

    Returns
    -------
    list of dict
        ``{"retension_s", "peaks": [(time_s, tension_N), ...]}`` per re-tensioning, peaks located
        between samples (:func:`hermite_peak`).
    """
    t, y, d = (np.asarray(a, float) for a in (time, tension, rate))
    s = np.asarray(slack, bool)
    out = []
    starts = np.nonzero(s[:-1] & ~s[1:])[0] + 1          # first taut sample after a slack one
    for i in starts:
        stop = i + np.argmax(s[i:]) if s[i:].any() else t.size
        j = np.arange(max(i, 1), stop)
        j = j[(d[j - 1] > 0) & (d[j] <= 0)]                  # dT/dt falls through zero in (t_{j-1}, t_j]
        peaks = [hermite_peak(t[k - 1], t[k], y[k - 1], y[k], d[k - 1], d[k]) for k in j]
        out.append({"retension_s": float(t[i]), "peaks": peaks})
    return out
