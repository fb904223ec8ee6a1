"""Figure of a time-domain design (:class:`cablesys.control.design.TimeDesignResult`): IPOPT's history
and the baseline and designed responses of one seed."""

from __future__ import annotations

from textwrap import fill as wrap

import numpy as np

from .design_problem import describe_theta

# what the series the no-slack floor bounds is, by the model's output name
FLOOR_NAMES = {"tension_mid": "F_bc (Wang's spring force, tension_mid)", "tension_least": "least element tension"}


def plot_time_design(result, path, *, title: str = "", frequency_theta=None):
    """Objective and primal infeasibility per IPOPT iteration; top tension and body heave of the first
    seed, baseline (the scene's line) against the design, with the working load and the slack floor."""
    import matplotlib.pyplot as plt
    fig = plt.figure(figsize=(12, 8.5))
    gs = fig.add_gridspec(3, 2, height_ratios=[1, 1.1, 1.1])
    a0, a1 = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1])
    a2, a3 = fig.add_subplot(gs[1, :]), fig.add_subplot(gs[2, :])
    hist = result.history
    starts = int(result.stats.get("starts", 1) or 1)
    xlabel = "IPOPT iteration" + (f" (the best of {starts} starts)" if starts > 1 else "")
    it = np.arange(len(hist.get("objective", [])))
    a0.plot(it, hist.get("objective", []), "o-", color="k", ms=3)
    a0.axhline(result.objective_baseline, color="0.5", ls=":", label=f"baseline {result.objective_baseline:.4g} m^2")
    a0.set_xlabel(xlabel)
    a0.set_ylabel("mean heave variance [m^2]")
    a0.set_yscale("log")
    a0.legend(fontsize=8)
    inf = np.maximum(np.asarray(hist.get("infeasibility", []), float), 1e-16)
    a1.semilogy(it, inf, "s-", color="tab:red", ms=3)
    a1.set_xlabel(xlabel)
    a1.set_ylabel("max violation (normalized)")
    for ax in (a0, a1):
        ax.grid(alpha=0.3)
    t = result.times
    lim = result.limits
    s = result.seeds[0]
    base = wrap(f"baseline {describe_theta(result.names, result.theta_baseline)}", 48)
    des = wrap(f"time-domain design {describe_theta(result.names, result.theta)}", 48)
    a2.plot(t, result.tension_top_baseline[0] / 1e3, color="0.55", lw=1.0, label=base)
    a2.plot(t, result.tension_top[0] / 1e3, color="tab:blue", lw=1.3, label=des)
    a2.plot(t, result.tension_floor[0] / 1e3, color="tab:blue", lw=0.8, ls="--",
            label=f"design: {FLOOR_NAMES.get(result.floor_output, result.floor_output)}")
    wl = np.ravel(lim["working_load_n"])[0]          # the top section's
    top = max(np.max(result.tension_top[0]), np.max(result.tension_top_baseline[0]))
    if np.isfinite(wl) and wl <= 1.5 * top:          # on the tensions' scale: drawn
        a2.axhline(wl / 1e3, color="tab:red", lw=1.2, label=f"working load {wl / 1e3:.3g} kN")
    elif np.isfinite(wl):
        a2.plot([], [], color="none", label=f"working load {wl / 1e3:.3g} kN (off scale)")
    if lim.get("slack_fraction") is not None:
        floor = lim["slack_fraction"] * np.mean(result.tension_floor[0])
        a2.axhline(floor / 1e3, color="tab:red", ls="--", lw=1.0, label=f"slack floor {lim['slack_fraction']:g} x its mean")
    a2.axvline(lim["statistics_start_s"], color="0.3", ls=":", lw=0.8)
    a2.set_ylabel("tension [kN]")
    a2.set_title(f"seed {s}: tensions (the window starts at the dotted line)", fontsize=9)
    win = t >= lim["statistics_start_s"] - 1e-9
    std = lambda h: float(np.sqrt(np.mean(h[win] ** 2)))
    a3.plot(t, result.heave_baseline[0], color="0.55", lw=1.0,
            label=f"baseline: {std(result.heave_baseline[0]):.3f} m std in the window "
                  f"({np.sqrt(result.objective_baseline):.3f} m, all seeds)")
    a3.plot(t, result.heave[0], color="tab:blue", lw=1.3,
            label=f"design: {std(result.heave[0]):.3f} m std ({np.sqrt(result.objective):.3f} m, all seeds)")
    a3.axvline(lim["statistics_start_s"], color="0.3", ls=":", lw=0.8)
    a3.set_ylabel("body heave from mean [m] (down +)")
    a3.set_xlabel("time [s]")
    for ax in (a2, a3):
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    if frequency_theta is not None:
        a3.plot([], [], color="none", label=wrap("frequency-domain optimum: "
                                                 + describe_theta(result.names, frequency_theta), 48))
        a3.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    model = result.model.split(" (cablesys")[0] if result.model else ""      # the model's name, not its module
    lines = ([wrap(title, 150)] if title else []) + ([f"model: {model}"] if model else [])
    if lines:
        text = "\n".join(lines)
        fig.suptitle(text, fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 1.0 - 0.018 * (text.count("\n") + 1) - 0.01 if lines else 1.0))
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
