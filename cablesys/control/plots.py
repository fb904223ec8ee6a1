"""Figures of a heave-compensation comparison (:class:`cablesys.control.mpc.Comparison`)."""

from __future__ import annotations

import numpy as np

from ..plots.figure import save_figure

_STYLE = {"none": ("uncompensated", "0.55", "-"), "passive": ("passive compensator", "tab:green", "-"),
          "pi": ("PI + feed-forward AHC", "tab:orange", "-"), "mpc": ("MPC (preview)", "tab:blue", "-"),
          "mpc_no_preview": ("MPC (AR prediction, no preview)", "tab:purple", "-"),
          "optimal": ("open-loop optimum", "k", "--")}


def _lines(ax, times, series, names, metrics=None):
    for name in names:
        if name in series:
            label, color, ls = _STYLE[name]
            if metrics is not None and name in metrics:
                label = f"{label}: {metrics[name]['heave_rms_m']:.3f} m rms ({metrics[name]['heave_reduction_db']:+.1f} dB)"
            ax.plot(times, series[name], color=color, ls=ls, lw=2.2 if name == "mpc" else 1.1, label=label)


def _legend(ax):
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)


def _limit_lines(ax, values, scale):
    """Horizontal limit lines that fall near the data; the others are named in the legend as off scale."""
    lo, hi = ax.get_ylim()
    span = hi - lo
    for value, label, ls in values:
        if not np.isfinite(value):
            continue
        v = value / scale
        if lo - 0.5 * span <= v <= hi + 0.5 * span:
            ax.axhline(v, color="tab:red", lw=1.0, ls=ls, label=label or None)
        elif label:
            ax.plot([], [], color="none", label=f"{label}: {v:.4g} (off scale)")


def plot_heave_tension(result, path, *, title: str = ""):
    """Body heave and top tension of every strategy against time, with the tension limits."""
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(12, 6.5), sharex=True)
    names = [n for n in _STYLE if n in result.heave]
    _lines(a1, result.times, result.heave, names, result.metrics)
    a1.set_ylabel("body heave from rest [m] (down +)")
    _lines(a2, result.times, {k: v / 1e3 for k, v in result.tension_top.items()}, names)
    lim = result.limits
    a2.axhline(lim["static_tension_n"] / 1e3, color="0.3", lw=0.8, ls=":", label="static")
    _limit_lines(a2, ((lim["tension_floor_n"], "tension floor [kN]", "--"),
                      (lim["working_load_n"], "working load [kN]", "-.")), 1e3)
    a2.set_ylabel("tension at the sheave [kN]")
    a2.set_xlabel("time [s]")
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        _legend(ax)
    if title:
        a1.set_title(title, fontsize=9)
    return save_figure(fig, path)


def plot_winch(result, path, *, title: str = ""):
    """Payout (L - L_0), payout rate and winch power of the active strategies against their limits."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, figsize=(12, 7.5), sharex=True)
    names = [n for n in ("pi", "mpc", "mpc_no_preview", "optimal") if n in result.speed]
    _lines(axes[0], result.times, {k: v - v[0] for k, v in result.length.items()}, names)
    axes[0].set_ylabel("payout L - L0 [m]")
    _lines(axes[1], result.times, result.speed, names)
    _lines(axes[2], result.times, {k: v / 1e3 for k, v in result.power.items()}, names)
    lim = result.limits
    _limit_lines(axes[1], ((lim["speed_m_s"], "speed limit", "--"), (-lim["speed_m_s"], "", "--")), 1.0)
    _limit_lines(axes[2], ((lim["power_w"], "power limit [kW]", "--"), (-lim["power_w"], "", "--")), 1e3)
    axes[1].set_ylabel("payout rate w [m/s]")
    axes[2].set_ylabel("winch power T w [kW]")
    axes[2].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
        _legend(ax)
    if title:
        axes[0].set_title(title, fontsize=9)
    return save_figure(fig, path)
