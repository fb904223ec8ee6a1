"""Axis helpers shared by the figures: steady series, limits that do not set the scale, outside legends.

Each takes matplotlib axes and data in the units drawn; none imports matplotlib at module level.
"""

from __future__ import annotations

import re

import numpy as np

STEADY_RTOL = 1e-6     # a series whose range is below 1e-6 of its magnitude is steady (integrator noise)


def is_steady(values, atol: float, rtol: float = STEADY_RTOL) -> bool:
    """True when the finite ``values`` vary by no more than ``atol + rtol * max|values|`` (same units).

    A steady tow's angle varies by about 1e-11 deg about 58.96 deg: drawn as it is, matplotlib
    shows that noise on an offset axis. Such a series is stated by its value instead.
    """
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return True
    return float(np.ptp(v)) <= atol + rtol * float(np.max(np.abs(v)))


def clean(value: float, atol: float) -> float:
    """``value``, or 0.0 when it is within ``atol`` of zero (a rounding residue, not a result)."""
    return 0.0 if abs(value) <= atol else value


def number(value: float) -> str:
    """A value for a label: 4 significant digits, whole numbers from 1e4 to 1e9 without an exponent."""
    return f"{value:.0f}" if 1e4 <= abs(value) < 1e9 else f"{value:.4g}"


def plain_axis(ax) -> None:
    """No offset or scientific-multiplier notation on either axis (a tick reads as the value)."""
    from matplotlib.ticker import ScalarFormatter
    for axis in (ax.xaxis, ax.yaxis):
        if isinstance(axis.get_major_formatter(), ScalarFormatter):
            axis.get_major_formatter().set_useOffset(False)


def series_panel(ax, t, series, unit: str, atol: float) -> list:
    """Draw ``series`` ([(label, values, colour)], drawn units) against ``t``; return the labels drawn steady.

    A steady series (:func:`is_steady` with ``atol``) is one flat line at its mean whose legend label
    states the value ("phi: steady 58.96 deg"); when every series is steady the axis spans +-5 % of
    their values (or +-1 unit about zero). Ticks never use offset notation.
    """
    steady, means = [], []
    for label, values, color in series:
        if is_steady(values, atol):
            m = clean(float(np.nanmean(values)), atol)
            ax.plot([t[0], t[-1]], [m, m], color=color, lw=1.2, label=f"{label}: steady {m:.5g} {unit}".strip())
            steady.append(label)
            means.append(m)
        else:
            ax.plot(t, values, color=color, lw=0.8, label=label)
    if series and len(steady) == len(series):
        lo, hi = min(means), max(means)
        half = max(0.05 * max(abs(lo), abs(hi)), 0.05 * (hi - lo), 1.0 if hi == lo == 0.0 else 0.0)
        ax.set_ylim(lo - half, hi + half)
    plain_axis(ax)
    return steady


LIMIT_STYLES = (("r", "--"), ("r", ":"), ("m", "-."), ("m", ":"), ("darkred", "--"), ("darkred", ":"))


def limit_lines(ax, limits: dict, data_lo: float, data_hi: float, unit: str, pad: float = 0.08) -> None:
    """Scale ``ax`` to the data [data_lo, data_hi] and draw each limit ({name: value}, drawn units).

    A limit inside the data's range (with ``pad`` margin) is a labelled horizontal line; one outside
    does not widen the axis: a note right of the axes (below an outside legend) says
    "up-arrow name value unit above" or "down-arrow ... below".
    """
    span = data_hi - data_lo
    if span <= 0.0:
        span = max(abs(data_hi), 1.0)
    lo, hi = data_lo - pad * span, data_hi + pad * span
    ax.set_ylim(lo, hi)
    off = []
    for k, (name, value) in enumerate(limits.items()):
        color, ls = LIMIT_STYLES[k % len(LIMIT_STYLES)]
        if lo <= value <= hi:
            ax.axhline(value, color=color, ls=ls, lw=1, label=f"{name} {number(value)} {unit}")
        else:
            off.append(f"\u2191 {name} {number(value)} {unit} above" if value > hi
                       else f"\u2193 {name} {number(value)} {unit} below")
    if off:
        ax.text(1.01, 0.0, "off scale:\n" + "\n".join(off), transform=ax.transAxes, ha="left", va="bottom",
                fontsize=7, color="r")


def legend_outside(ax, fontsize: float = 7, ncol: int = 1):
    """A legend to the right of ``ax`` (outside the data), or none when nothing is labelled."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    return ax.legend(handles, labels, fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                     borderaxespad=0.0, ncol=ncol)


def tension_marks(values: list, limits, factor: float) -> tuple[list, dict]:
    """(values, marks) of a tension panel: the traces' extremes ``values`` (drawn units) with 0 added when they come
    within 25 % of it (near slack: zero on the axis; a taut line keeps its detail), and the ``limits``' working load and
    least allowed tension (N, times ``factor``) to mark (:func:`limit_lines`)."""
    values = list(values)
    if min(values) <= 0.25 * max(values):
        values.append(0.0)
    marks = {}
    if limits is not None:
        if getattr(limits, "working_load", None) is not None:
            marks["working load"] = limits.working_load * factor
        if getattr(limits, "least_tension", None) is not None:
            marks["least allowed tension"] = limits.least_tension * factor
    return values, marks


# a rigid body's attitude outputs (model/rigid_assembly.py RIGID_OUTPUTS, RIGID_OUTPUTS_3D; rad): a chain's body
# (``theta_b``, a section suffix ``_2`` in a chain of sections) or a system's body point (``point.NAME.theta_b``)
_ATTITUDE = re.compile(r"^(?:point\.(?P<point>[^.]+)\.)?(?P<angle>roll_b|theta_b|yaw_b)(?P<sfx>_\d+)?$")
_ANGLE_NAMES = {"roll_b": "roll", "theta_b": "pitch", "yaw_b": "yaw"}


def attitude_traces(labels) -> list:
    """[(trace label, output label)] of every rigid body's roll, pitch and yaw among ``labels`` (a run's output
    labels), body by body in roll, pitch, yaw order; empty without a rigid body."""
    found = {}
    for lbl in labels:
        m = _ATTITUDE.match(lbl)
        if m:
            owner = m["point"] or (f"body {m['sfx'][1:]}" if m["sfx"] else "body")
            found.setdefault(owner, {})[m["angle"]] = lbl
    return [(f"{owner} {_ANGLE_NAMES[a]}", angles[a]) for owner, angles in found.items()
            for a in ("roll_b", "theta_b", "yaw_b") if a in angles]
