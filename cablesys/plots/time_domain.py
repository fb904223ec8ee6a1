"""Time-domain figures: lower-body path, angle, stretch and tension (reads a TimeResult)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import save_figure


def plot_time_series(result, path, *, title: str | None = None) -> Path:
    """2 x 2 panel: body path x_b-y_b (y down), phi(t), u(t), tension(t), slack events marked.

    Parameters
    ----------
    result : TimeResult
        A time-domain run.
    path : str or pathlib.Path
        Output image.
    title : str, optional
        Figure title (default: the scene name).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    import matplotlib.pyplot as plt

    t = result.time
    sfx = [""] if "u" in result.data else [lbl[1:] for lbl in result.data if lbl.startswith("u_") and lbl[2:].isdigit()]
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5))
    for s in sfx:
        name = f"section {s[1:]}" if s else "lower body"
        phi = result[f"phi{s}"] if f"phi{s}" in result.data else result["phi"]
        xb, yb = result[f"x_b{s}"], result[f"y_b{s}"]
        ax[0, 0].plot((xb - xb.mean()) * 1e3, (yb - yb.mean()) * 1e3, lw=0.8, label=name)
        ax[0, 1].plot(t, np.degrees(phi), lw=0.8, label=name)
        ax[1, 0].plot(t, result[f"u{s}"] * 1e3, lw=0.8, label=name)
        ax[1, 1].plot(t, result[f"tension{s}"], lw=0.8, label=name)
    xs, ys = result["x_s"], result["y_s"]
    ax[0, 0].plot((xs - xs.mean()) * 1e3, (ys - ys.mean()) * 1e3, "k", lw=0.8, label="top (ship)")
    ax[0, 0].invert_yaxis()
    ax[0, 0].set(xlabel="x - mean (mm, + right)", ylabel="y - mean (mm, + down)", title="paths about their mean positions")
    ax[0, 0].axis("equal")
    ax[0, 1].set(xlabel="time (s)", ylabel=r"cable angle $\phi$ (deg)", title="swing angle")
    ax[1, 0].set(xlabel="time (s)", ylabel="stretch u (mm)", title="cable stretch")
    ax[1, 1].set(xlabel="time (s)", ylabel="tension at the body (N)", title="cable tension (eq. 54)")
    slack = [e.time for e in result.events if e.kind == "slack"]
    if slack:
        ax[1, 1].plot(slack, np.zeros(len(slack)), "rv", ms=5, label="goes slack")
    for s in result.snaps:
        ax[1, 1].plot(s.time, s.tension, "k^", ms=5)
    for a in ax.flat:
        a.grid(alpha=0.3)
        if len(a.get_legend_handles_labels()[0]) > 1:
            a.legend(fontsize=8)
    fig.suptitle(title or result.scene_name)
    return save_figure(fig, path)
