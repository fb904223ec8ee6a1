"""Time-domain figures: lower-body path, angle, stretch and tension (reads a TimeResult)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .figure import save_figure


def _length_scale(span_m: float, units: str) -> tuple[float, str]:
    """(factor, name) for lengths of about ``span_m``: mm or m (SI), in or ft (fps)."""
    from ..units import FT, INCH
    if units == "fps":
        return (1 / INCH, "in") if span_m < 0.3 else (1 / FT, "ft")
    return (1e3, "mm") if span_m < 0.1 else (1.0, "m")


def _force_scale(peak_n: float, units: str) -> tuple[float, str]:
    from ..units import LBF
    if units == "fps":
        return (1 / LBF, "lbf") if peak_n < 1e5 else (1 / (1000 * LBF), "kip")
    return (1.0, "N") if peak_n < 2e4 else (1e-3, "kN")


def plot_time_series(result, path, *, title: str | None = None, units: str = "SI", limits=None,
                     window_start: float | None = None) -> Path:
    """2 x 2 panel: body path x_b-y_b (y down), phi(t), u(t), tensions(t), slack events marked.

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
        Draws the working load and the least allowed tension on the tension panel.
    window_start : float, optional
        Start of the statistics window (s), shaded before it.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    import matplotlib.pyplot as plt

    t = result.time
    data = result.data
    sfx = [""] if "u" in data else [lbl[1:] for lbl in data if lbl.startswith("u_") and lbl[2:].isdigit()]
    spans = [np.ptp(result[f"{q}{s}"]) for s in sfx for q in ("x_b", "y_b")] + [np.ptp(result["x_s"]), np.ptp(result["y_s"])]
    fl, ul = _length_scale(max(spans), units)
    fu, uu = _length_scale(max(np.ptp(result[f"u{s}"]) for s in sfx), units)
    tens = [lbl for lbl in data if lbl.startswith("tension")]
    ff, uf = _force_scale(max(float(np.max(np.abs(data[k]))) for k in tens), units)
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5))
    for k, s in enumerate(sfx):
        name = f"section {s[1:]}" if s else "lower body"
        phi = result[f"phi{s}"] if f"phi{s}" in data else result["phi"]
        xb, yb = result[f"x_b{s}"], result[f"y_b{s}"]
        ax[0, 0].plot((xb - xb.mean()) * fl, (yb - yb.mean()) * fl, lw=0.8, label=name)
        ax[0, 1].plot(t, np.degrees(phi), lw=0.8, label=name)
        ax[1, 0].plot(t, result[f"u{s}"] * fu, lw=0.8, label=name)
        ends = [(f"tension_top{s}", "top"), (f"tension_bottom{s}", "at the body")]
        ends = [(lbl, where) for lbl, where in ends if lbl in data] or [(f"tension{s}", "")]
        for j, (lbl, where) in enumerate(ends):
            ax[1, 1].plot(t, result[lbl] * ff, lw=0.8, color=f"C{2 * k + j}",
                          label=" ".join(x for x in (name if len(sfx) > 1 else "", where) if x) or name)
    xs, ys = result["x_s"], result["y_s"]
    ax[0, 0].plot((xs - xs.mean()) * fl, (ys - ys.mean()) * fl, "k", lw=0.8, label="top (ship)")
    ax[0, 0].invert_yaxis()
    ax[0, 0].set(xlabel=f"x - mean ({ul}, + right)", ylabel=f"y - mean ({ul}, + down)",
                 title="paths about their mean positions")
    ax[0, 0].axis("equal")
    ax[0, 1].set(xlabel="time (s)", ylabel=r"cable angle $\phi$ (deg)", title="swing angle")
    ax[1, 0].set(xlabel="time (s)", ylabel=f"stretch u ({uu})", title="cable stretch")
    ax[1, 1].set(xlabel="time (s)", ylabel=f"tension ({uf})", title="cable tension (eq. 54)")
    if limits is not None:
        if getattr(limits, "working_load", None) is not None:
            ax[1, 1].axhline(limits.working_load * ff, color="r", ls="--", lw=1, label="working load")
        if getattr(limits, "least_tension", None) is not None:
            ax[1, 1].axhline(limits.least_tension * ff, color="r", ls=":", lw=1, label="least allowed tension")
    slack = [e.time for e in result.events if e.kind == "slack"]
    if slack:
        ax[1, 1].plot(slack, np.zeros(len(slack)), "rv", ms=5, label="goes slack")
    for s in result.snaps:
        ax[1, 1].plot(s.time, s.tension * ff, "k^", ms=5)
    for a in ax.flat:
        a.grid(alpha=0.3)
        if window_start is not None and a is not ax[0, 0] and window_start > t[0]:
            a.axvspan(t[0], window_start, color="0.85", alpha=0.5, lw=0)
        if len(a.get_legend_handles_labels()[0]) > 1:
            a.legend(fontsize=8)
    fig.suptitle(title or result.scene_name)
    return save_figure(fig, path)
