"""Figures of a heave-compensation comparison (:class:`cablesys.control.mpc.Comparison`)."""

from __future__ import annotations

import numpy as np

from ..plots.figure import save_figure

_STYLE = {"none": ("uncompensated", "0.55", "-"), "passive": ("passive compensator", "tab:green", "-"),
          "pi": ("PI + feed-forward AHC", "tab:orange", "-"), "mpc": ("MPC (preview)", "tab:blue", "-"),
          "optimal": ("open-loop optimum", "k", "--")}


def _lines(ax, times, series, names):
    for name in names:
        if name in series:
            label, color, ls = _STYLE[name]
            ax.plot(times, series[name], color=color, ls=ls, lw=1.1, label=label)


def plot_heave_tension(result, path, *, title: str = ""):
    """Body heave and top tension of every strategy against time, with the tension limits."""
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6.5), sharex=True)
    names = [n for n in _STYLE if n in result.heave]
    _lines(a1, result.times, result.heave, names)
    a1.set_ylabel("body heave from rest [m] (down +)")
    a1.legend(loc="upper right", ncol=3, fontsize=8)
    _lines(a2, result.times, {k: v / 1e3 for k, v in result.tension_top.items()}, names)
    lim = result.limits
    a2.axhline(lim["static_tension_n"] / 1e3, color="0.3", lw=0.8, ls=":", label="static")
    a2.axhline(lim["tension_floor_n"] / 1e3, color="tab:red", lw=1.0, ls="--", label="tension floor")
    if np.isfinite(lim["working_load_n"]) and lim["working_load_n"] < 3 * max(np.max(v) for v in result.tension_top.values()):
        a2.axhline(lim["working_load_n"] / 1e3, color="tab:red", lw=1.0, ls="-.", label="working load")
    a2.set_ylabel("tension at the sheave [kN]")
    a2.set_xlabel("time [s]")
    a2.legend(loc="upper right", ncol=3, fontsize=8)
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
    rms = ", ".join(f"{_STYLE[n][0]} {m['heave_rms_m']:.3f} m" for n, m in result.metrics.items())
    a1.set_title((title + "\n" if title else "") + f"rms heave: {rms}", fontsize=9)
    return save_figure(fig, path)


def plot_winch(result, path, *, title: str = ""):
    """Payout (L - L_0), payout rate and winch power of the active strategies against their limits."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, figsize=(10, 7.5), sharex=True)
    names = [n for n in ("pi", "mpc", "optimal") if n in result.speed]
    _lines(axes[0], result.times, {k: v - v[0] for k, v in result.length.items()}, names)
    axes[0].set_ylabel("payout L - L0 [m]")
    _lines(axes[1], result.times, result.speed, names)
    _lines(axes[2], result.times, {k: v / 1e3 for k, v in result.power.items()}, names)
    lim = result.limits
    for ax, value, scale, label in ((axes[1], lim["speed_m_s"], 1.0, "speed limit"),
                                    (axes[2], lim["power_w"], 1e3, "power limit")):
        if np.isfinite(value):
            for sgn in (1, -1):
                ax.axhline(sgn * value / scale, color="tab:red", lw=1.0, ls="--", label=label if sgn > 0 else None)
    axes[1].set_ylabel("payout rate w [m/s]")
    axes[2].set_ylabel("winch power T w [kW]")
    axes[2].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", ncol=4, fontsize=8)
    if title:
        axes[0].set_title(title, fontsize=9)
    return save_figure(fig, path)
