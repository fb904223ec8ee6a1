"""Time-domain figures: cable shape, lower-body path, angle, stretch and tension (reads a TimeResult)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .axes import attitude_traces, clean, is_steady, legend_outside, limit_lines, plain_axis, series_panel, tension_marks
from .figure import save_figure

# steady-series tolerances (SI): below these ranges a series is integrator noise, stated by its value
ATOL_LENGTH = 1e-9      # m
ATOL_ANGLE = 1e-9       # rad
ATOL_FORCE = 1e-6       # N


def _length_scale(span_m: float, units: str) -> tuple[float, str]:
    """(factor, name) for lengths of about ``span_m``: mm or m (SI), in or ft (fps)."""
    from ..units import FT, INCH
    if units == "fps":
        return (1 / INCH, "in") if span_m < 0.3 else (1 / FT, "ft")
    return (1e3, "mm") if span_m < 0.1 else (1.0, "m")


def _force_scale(peak_n: float, units: str) -> tuple[float, str]:
    """(factor, name) for forces of about ``peak_n``: N or kN (SI), lbf or kip (fps)."""
    from ..units import LBF
    if units == "fps":
        return (1 / LBF, "lbf") if peak_n < 1e5 else (1 / (1000 * LBF), "kip")
    return (1.0, "N") if peak_n < 2e4 else (1e-3, "kN")


def _snap_marks(result) -> tuple[list, str]:
    """Snap loads to mark: [(time s, tension N)] and their legend label. The located snap loads of a
    2-DOF run (``result.snaps``); for a segmented run the first tension peak after each element
    re-tensions (:meth:`TimeResult.snap_events`)."""
    if result.snaps:
        return [(s.time, s.tension) for s in result.snaps], "snap load (first peak after going taut)"
    marks = [ev["peaks"][0] for ev in result.snap_events() if ev["peaks"]]
    return marks, "snap load (element tension, first peak after re-tensioning)"


def _shape_panel(ax, result, units: str, anchored: bool = False, towed: bool = False) -> None:
    """The cable's node positions (segmented runs): the mean shape, the extreme shapes of the body's
    depth, the body's depth and layback from the top, in lengths of ``units``. With ``anchored`` the
    line's last node is the anchor (it does not move), so the extreme shapes and the title name the
    anchor's depth and its horizontal distance from the top instead of a body's. With ``towed`` (a top on a
    track) x is measured from the top's x at each instant (x - x_s), the shape carried along with it."""
    nx, ny = result.profiles["node_x"], result.profiles["node_y"]
    if towed:
        nx = nx - np.asarray(result["x_s"])[:, None]
    fl, ul = _length_scale(max(np.ptp(nx), np.ptp(ny)), units)
    xm, ym = nx.mean(axis=0), ny.mean(axis=0)
    moving = not all(is_steady(p[:, j], ATOL_LENGTH) for p in (nx, ny) for j in range(p.shape[1]))
    end = "anchor" if anchored else "body"
    if moving:
        # the extremes of the moving end: the top for an anchored line, the body otherwise
        jx = 0 if anchored else -1
        picks = ((int(np.argmin(ny[:, jx])), "shallowest"), (int(np.argmax(ny[:, jx])), "deepest"))
        for k, (i, name) in enumerate(picks):
            ax.plot(nx[i] * fl, ny[i] * fl, color="0.55", ls=("--", ":")[k], lw=0.9,
                    label=f"{name} {'top' if anchored else 'body'}, t = {result.time[i]:.4g} s")
    ax.plot(xm * fl, ym * fl, "k.-", lw=1.2, ms=4, label="mean shape (nodes)" if moving else "shape (steady, nodes)")
    ax.plot(xm[0] * fl, ym[0] * fl, "ks", ms=6, label="top")
    ax.plot(xm[-1] * fl, ym[-1] * fl, "^" if anchored else "o", color="C0", ms=8, label=end)
    depth, layback = (clean(v, ATOL_LENGTH) * fl for v in (ym[-1] - ym[0], xm[-1] - xm[0]))
    ax.invert_yaxis()
    ax.set_aspect("equal", adjustable="datalim")
    ax.set(xlabel=f"x - x_s ({ul}, from the top)" if towed else f"x ({ul}, + right)", ylabel=f"depth y ({ul}, + down)")
    ax.set_title(f"cable shape: {end} depth {depth:.4g} {ul},\n{'distance' if anchored else 'layback'} "
                 f"{layback:+.4g} {ul} from the top", fontsize=10)
    plain_axis(ax)
    ax.legend(fontsize=7, loc="best")


def plot_time_series(result, path, *, title: str | None = None, units: str = "SI", limits=None,
                     window_start: float | None = None, anchored: bool = False, towed: bool = False) -> Path:
    """Panels of a run: cable shape (segmented runs), body path x_b-y_b (y down), phi(t) (with a rigid body's roll,
    pitch and yaw), u(t) and tensions(t).

    The tension axis is scaled to the traces and the snap loads (from zero when they come within
    25 % of it); a working load or least allowed
    tension outside that range is an arrow at the edge ("working load 126 kN above"), not a line
    that flattens the traces. A steady series (range below 1e-6 of its magnitude plus 1e-9 m,
    1e-9 rad or 1e-6 N) is drawn flat and its value stated. Every mark is in a legend.

    Parameters
    ----------
    result : TimeResult
        A time-domain run.
    path : str or pathlib.Path
        Output image.
    title : str, optional
        Figure title (default: the scene name).
    units : str
        "SI" (mm/m, N/kN) or "fps" (in/ft, lbf/kip): the units of the scene file.
    limits : cablesys.scene.limits.Limits, optional
        Its working load, least allowed tension (N) and slack limit (``slack_fraction`` x each trace's
        mean from ``window_start``, the verdict's DNV-RP-H103 slack check) on the tension panel.
    window_start : float, optional
        Start of the statistics window (s), shaded before it.
    anchored : bool, optional
        The last section ends at an ``[anchor]``: its lower end and ``tension_bottom`` are named the anchor's.
    towed : bool, optional
        The top follows a track (``top_motion.track``): the shape and the paths are drawn relative to the top's x (its
        plan view is :func:`cablesys.plots.plan.plot_plan_view`'s).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    t = result.time
    data = result.data
    sfx = [""] if "u" in data else [lbl[1:] for lbl in data if lbl.startswith("u_") and lbl[2:].isdigit()]
    x_top = np.asarray(result["x_s"]) if towed else 0.0           # a towed run: x from the top
    spans = [np.ptp(result[f"{q}{s}"] - (x_top if q == "x_b" else 0.0)) for s in sfx for q in ("x_b", "y_b")]
    spans += [] if towed else [np.ptp(result["x_s"]), np.ptp(result["y_s"])]
    fl, ul = _length_scale(max(spans), units)
    fu, uu = _length_scale(max(np.ptp(result[f"u{s}"]) for s in sfx), units)
    tens = [lbl for lbl in data if lbl.startswith("tension")]
    snaps, snap_label = _snap_marks(result)
    ff, uf = _force_scale(max([float(np.max(np.abs(data[k]))) for k in tens] + [v for _, v in snaps]), units)
    shape = "node_x" in result.profiles and "node_y" in result.profiles
    fig = plt.figure(figsize=(14, 8) if shape else (12, 7.5))
    gs = fig.add_gridspec(2, 6)
    if shape:
        a_shape, a_path, a_phi = (fig.add_subplot(gs[0, 2 * k:2 * k + 2]) for k in range(3))
        a_u, a_t = fig.add_subplot(gs[1, :2]), fig.add_subplot(gs[1, 2:])
        _shape_panel(a_shape, result, units, anchored, towed)
    else:
        a_path, a_phi = fig.add_subplot(gs[0, :3]), fig.add_subplot(gs[0, 3:])
        a_u, a_t = fig.add_subplot(gs[1, :3]), fig.add_subplot(gs[1, 3:])
    phis, us, traces = [], [], []
    still = []
    for k, s in enumerate(sfx):
        name = f"section {s[1:]}" if s else "lower body"
        last = k == len(sfx) - 1
        if anchored and last:              # the last section's lower end is the anchor, its "body" sits there
            name = "anchor" if not s else f"section {s[1:]} (anchor)"
        phi = result[f"phi{s}"] if f"phi{s}" in data else result["phi"]
        xb, yb = result[f"x_b{s}"] - x_top, result[f"y_b{s}"]
        if is_steady(xb, ATOL_LENGTH) and is_steady(yb, ATOL_LENGTH):
            x0, y0 = (clean(float(v.mean()), ATOL_LENGTH) for v in (xb, yb))
            fr, ur = _length_scale(max(abs(x0), abs(y0)), units)
            still.append(f"{name} at rest: x {x0 * fr:.5g} {ur}, y {y0 * fr:.5g} {ur}")
        else:
            a_path.plot((xb - xb.mean()) * fl, (yb - yb.mean()) * fl, lw=0.8, label=name)
        phis.append((name, np.degrees(phi), f"C{k}"))
        us.append((name, result[f"u{s}"] * fu, f"C{k}"))
        ends = [(f"tension_top{s}", "top"), (f"tension_bottom{s}", "at the anchor" if anchored and last else "at the body")]
        ends = [(lbl, where) for lbl, where in ends if lbl in data] or [(f"tension_mid{s}", "at mid-length")]
        for j, (lbl, where) in enumerate(ends):
            traces.append((" ".join(x for x in (name if len(sfx) > 1 else "", where) if x) or name,
                           result[lbl] * ff, f"C{2 * k + j}"))
    xs, ys = result["x_s"], result["y_s"]
    if towed:
        pass                                # the top is the origin of the towed paths
    elif is_steady(xs, ATOL_LENGTH) and is_steady(ys, ATOL_LENGTH):
        still.append("top fixed")
    else:
        a_path.plot((xs - xs.mean()) * fl, (ys - ys.mean()) * fl, "k", lw=0.8, label="top (ship)")
    if still and not a_path.lines:          # nothing moves: say where it is, no empty axes
        a_path.set(xticks=[], yticks=[])
    if still:
        a_path.text(0.5, 0.5, "\n".join(still), transform=a_path.transAxes, ha="center", va="center", fontsize=8)
    a_path.invert_yaxis()
    a_path.set(xlabel=f"x - x_s - mean ({ul}, from the top)" if towed else f"x - mean ({ul}, + right)",
               ylabel=f"y - mean ({ul}, + down)",
               title="paths relative to the top, about their means" if towed else "paths about their mean positions")
    if a_path.lines:
        a_path.axis("equal")
        a_path.xaxis.set_major_locator(MaxNLocator(5))
    plain_axis(a_path)
    body = [(label, np.degrees(result[k]), f"C{len(phis) + j}") for j, (label, k) in enumerate(attitude_traces(data))]
    if body:                                # the swing angle is the cable's: say so beside the body's angles
        phis = [(f"cable $\\phi$ ({name})", y, c) for name, y, c in phis]
    series_panel(a_phi, t, phis + body, "deg", np.degrees(ATOL_ANGLE))
    a_phi.set(xlabel="time (s)", ylabel=r"cable angle $\phi$, body angles (deg)" if body else r"cable angle $\phi$ (deg)",
              title="swing angle and body attitude" if body else "swing angle")
    series_panel(a_u, t, us, uu, ATOL_LENGTH * fu)
    a_u.set(xlabel="time (s)", ylabel=f"stretch u ({uu})", title="cable stretch")
    series_panel(a_t, t, traces, uf, ATOL_FORCE * ff)
    a_t.set(xlabel="time (s)", ylabel=f"tension ({uf})", title="cable tension (eq. 54)")
    values = [v for _, y, _ in traces for v in (float(np.nanmin(y)), float(np.nanmax(y)))]
    values += [v * ff for _, v in snaps]
    values, marks = tension_marks(values, limits, ff)
    if limits is not None:
        frac = getattr(limits, "slack_fraction", None)
        if frac is not None:              # the verdict's slack check: each trace's least >= frac x its static mean
            after = t >= (window_start if window_start is not None else t[0])
            for name, y, _ in traces:
                mean = float(np.mean(y[after]))
                if mean > 0:
                    marks[f"slack limit ({name}: {100 * frac:.3g} % of its mean)"] = frac * mean
    slack = [e.time for e in result.events if e.kind == "slack"]
    if slack:
        a_t.plot(slack, np.zeros(len(slack)), "rv", ms=5, label="goes slack")
    if snaps:
        a_t.plot([s[0] for s in snaps], [s[1] * ff for s in snaps], "k^", ms=5, label=snap_label)
    limit_lines(a_t, marks, min(values), max(values), uf)
    for a in (a_phi, a_u, a_t):
        a.set_xlim(t[0], t[-1])
        if window_start is not None and window_start > t[0]:
            a.axvspan(t[0], window_start, color="0.85", alpha=0.5, lw=0,
                      label=f"before the statistics window (t < {window_start:.4g} s)")
    for a in (a_path, a_phi, a_u, a_t):
        a.grid(alpha=0.3)
    for a in (a_path, a_u) + (() if body else (a_phi,)):
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7, loc="best")
    if body:                                # the body's angles span the panel: their legend beside it
        legend_outside(a_phi)
    legend_outside(a_t)
    fig.suptitle(title or result.scene_name)
    return save_figure(fig, path)
