"""The figure of a cable system's run (lines joined at points, model/system.py): its shape, its points' paths and
its lines' end tensions (reads a TimeResult and the lines' node numbers)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .axes import attitude_traces, is_steady, legend_outside, limit_lines, plain_axis, series_panel, tension_marks
from .figure import save_figure
from .time_domain import ATOL_ANGLE, ATOL_FORCE, ATOL_LENGTH, _force_scale, _length_scale

_MARK = {"prescribed": "s", "fixed": "^", "body": "o", "junction": "D"}


def _nodes(result, towed: bool) -> dict:
    """The node profiles ``node_x``, ``node_y`` (``node_z``), (times, nodes), measured from the tow point (its x and z)
    when ``towed``."""
    prof = {k: np.asarray(v) for k, v in result.profiles.items() if k in ("node_x", "node_y", "node_z")}
    if towed:
        prof["node_x"] = prof["node_x"] - np.asarray(result["x_s"])[:, None]
        if "node_z" in prof:
            prof["node_z"] = prof["node_z"] - np.asarray(result.data.get("z_s", 0.0 * result.time))[:, None]
    return prof


def _shape(ax, prof: dict, lines: dict, points: dict, fl: float, ul: str, plan: bool, towed: bool) -> None:
    """The mean shape of every line (its nodes ``prof``, :func:`_nodes`) and its extremes where it moves; the points
    marked by kind and named. ``plan``: seen from above (x, z) instead of the elevation (x, y down)."""
    nx, nv = prof["node_x"], prof["node_z" if plan else "node_y"]
    for k, (name, (nodes, _, _)) in enumerate(lines.items()):
        idx = list(nodes)
        xm, vm = nx[:, idx].mean(axis=0), nv[:, idx].mean(axis=0)
        ax.plot(xm * fl, vm * fl, ".-", color=f"C{k}", lw=1.2, ms=3, label=f"line {name} (mean)")
        if not (is_steady(nx[:, idx], ATOL_LENGTH) and is_steady(nv[:, idx], ATOL_LENGTH)):
            for i in (int(np.argmin(nv[:, idx].mean(axis=1))), int(np.argmax(nv[:, idx].mean(axis=1)))):
                ax.plot(nx[i, idx] * fl, nv[i, idx] * fl, color=f"C{k}", lw=0.6, ls=":")
    seen = {}                                # points drawn at one place (a package above its sinker, seen from above)
    scale = max(np.ptp(nx), np.ptp(nv), 1e-9) * fl
    for name, (kind, node) in points.items():
        x, v = nx[:, node].mean() * fl, nv[:, node].mean() * fl
        ax.plot(x, v, _MARK[kind], color="k", ms=6, mfc="w" if kind == "fixed" else "k")
        at = (round(x / scale, 2), round(v / scale, 2))
        k = seen[at] = seen.get(at, -1) + 1      # the k-th name at that place goes k lines lower
        ax.annotate(f"{name} ({kind})", (x, v), textcoords="offset points", xytext=(4, 4 - 9 * k), fontsize=7)
    if not plan:
        ax.invert_yaxis()
    ax.set_aspect("equal", adjustable="datalim")
    frm = ", from the tow point" if towed else ""
    ax.set(xlabel=f"x ({ul}, + right{frm})", ylabel=f"z ({ul}, sway{frm})" if plan else f"depth y ({ul}, + down)",
           title="seen from above" if plan else "shape (elevation); dotted: extremes")
    plain_axis(ax)


def plot_system_series(result, path, *, lines: dict, points: dict, title: str | None = None, units: str = "SI",
                       limits=None, window_start: float | None = None, towed: bool = False) -> Path:
    """Panels of a system's run: its shape (elevation, and a plan view in 3-D), the paths of its bodies and junctions
    about their mean positions, the tension at both ends of every line against time, and every rigid body's roll,
    pitch and yaw (deg) against time.

    Parameters
    ----------
    result : TimeResult
        The run (its ``point.NAME.x`` ... and ``line.NAME.tension_from`` / ``tension_to`` series, node profiles).
    path : str or pathlib.Path
        Output image.
    lines : dict
        {line name: (its node numbers from its start to its end, its from point, its to point)}
        (:attr:`cablesys.model.system.SystemModel.line_nodes`).
    points : dict
        {point name: (kind, node number)}.
    title, units, limits, window_start
        As for :func:`.time_domain.plot_time_series`.
    towed : bool
        The prescribed point follows a track: shapes and paths are measured from it (x and z from the tow point).
    """
    import matplotlib.pyplot as plt

    t, data = result.time, result.data
    prof = _nodes(result, towed)
    three_d = "node_z" in prof and not is_steady(prof["node_z"], ATOL_LENGTH)
    span = max(np.ptp(prof["node_x"]), np.ptp(prof["node_y"]))
    fl, ul = _length_scale(span, units)
    tens = [(f"line.{name}.tension_{end}", f"{name} at {at}") for name, (_, a, b) in lines.items()
            for end, at in (("from", a), ("to", b))]
    ff, uf = _force_scale(max(float(np.max(np.abs(data[k]))) for k, _ in tens), units)
    attitude = attitude_traces(data)
    fig = plt.figure(figsize=(14, 11.5 if attitude else 8.5))
    gs = fig.add_gridspec(3 if attitude else 2, 6)
    a_shape = fig.add_subplot(gs[0, :2])
    a_plan = fig.add_subplot(gs[0, 2:4]) if three_d else None
    a_path = fig.add_subplot(gs[0, 4:] if three_d else gs[0, 2:])
    a_t = fig.add_subplot(gs[1, :])
    a_att = fig.add_subplot(gs[2, :]) if attitude else None
    _shape(a_shape, prof, lines, points, fl, ul, False, towed)
    a_shape.legend(fontsize=7, loc="best")
    if three_d:
        _shape(a_plan, prof, lines, points, fl, ul, True, towed)
    moving = [(name, prof["node_x"][:, node], prof["node_y"][:, node]) for name, (kind, node) in points.items()
              if kind != "fixed"]
    moving = [(n, x, y) for n, x, y in moving if not (is_steady(x, ATOL_LENGTH) and is_steady(y, ATOL_LENGTH))]
    pspan = max([max(np.ptp(x), np.ptp(y)) for _, x, y in moving], default=0.0)
    fp, up = _length_scale(pspan, units)
    for k, (name, x, y) in enumerate(moving):
        a_path.plot((x - x.mean()) * fp, (y - y.mean()) * fp, lw=0.8, color=f"C{k}", label=f"{name}")
    if not moving:
        a_path.set(xticks=[], yticks=[])
        a_path.text(0.5, 0.5, "no point moves", transform=a_path.transAxes, ha="center", va="center", fontsize=8)
    else:
        a_path.axis("equal")
        a_path.legend(fontsize=7, loc="best")
    a_path.invert_yaxis()
    a_path.set(xlabel=f"x - mean ({up}, + right" + (", from the tow point)" if towed else ")"),
               ylabel=f"y - mean ({up}, + down)", title="paths of the moving points about their means")
    plain_axis(a_path)
    traces = [(label, result[k] * ff, f"C{i}") for i, (k, label) in enumerate(tens)]
    series_panel(a_t, t, traces, uf, ATOL_FORCE * ff)
    a_t.set(xlabel="time (s)", ylabel=f"tension ({uf})", title="line tensions at both ends (force on the end point)")
    values, marks = tension_marks([v for _, y, _ in traces for v in (float(np.nanmin(y)), float(np.nanmax(y)))],
                                  limits, ff)
    limit_lines(a_t, marks, min(values), max(values), uf)
    if a_att is not None:
        series_panel(a_att, t, [(label, np.degrees(result[k]), f"C{j}") for j, (label, k) in enumerate(attitude)],
                     "deg", np.degrees(ATOL_ANGLE))
        a_att.set(xlabel="time (s)", ylabel="angle (deg)", title="rigid bodies' attitude (roll, pitch, yaw)")
    for a in (a_t,) + ((a_att,) if a_att is not None else ()):
        a.set_xlim(t[0], t[-1])
        if window_start is not None and window_start > t[0]:
            a.axvspan(t[0], window_start, color="0.85", alpha=0.5, lw=0,
                      label=f"before the statistics window (t < {window_start:.4g} s)")
    for a in (a_shape, a_path, a_t) + tuple(a for a in (a_plan, a_att) if a is not None):
        a.grid(alpha=0.3)
    for a in (a_t,) + ((a_att,) if a_att is not None else ()):
        legend_outside(a)
    fig.suptitle(title or result.scene_name)
    return save_figure(fig, path)


__all__ = ["plot_system_series"]
