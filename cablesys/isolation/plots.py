"""Figures of an isolation design: RAOs before and after, the objective's history, constraint margins.

Reads a :class:`~cablesys.isolation.DesignResult` (and the model to linearize at the two
parameter vectors); matplotlib is imported lazily.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plots import save_figure
from .solve import OK_STATUS


def plot_rao_before_after(model, p_before, p_after, settings, path, *, title: str = "",
                          outputs: tuple | None = None) -> Path:
    """|RAO| per unit top heave y_s of the lower body's heave and the top tension, for the scene's
    values (before) and the optimum (after), over the design's frequency grid, with the sea
    spectrum of the design shaded (exact linearization about each steady state)."""
    import matplotlib.pyplot as plt

    from ..linear import linearize, rao
    from ..linear.plots import NOISE
    from ..scene.spectra import jonswap
    omega = np.geomspace(settings.omega_min, settings.omega_max, 300)
    before, after = (rao(linearize(model, p), omega) for p in (p_before, p_after))
    labels = before.output_labels
    y_b = "y_b" if "y_b" in labels else max((o for o in labels if o.startswith("y_b_") and o[4:].isdigit()),
                                                 key=lambda o: int(o[4:]))   # the lowest body
    tens = next((o for o in ("tension_top", "tension_top_1", "tension_mid", "tension_mid_1") if o in labels),
                next(o for o in labels if o.startswith("tension")))
    outputs = outputs or (y_b, tens)
    fig, axes = plt.subplots(len(outputs), 1, figsize=(8, 3.2 * len(outputs)), sharex=True, squeeze=False)
    S = jonswap(omega, settings.hs, settings.tp, settings.gamma)
    for ax, o in zip(axes[:, 0], outputs):
        for r, name, style in ((before, "scene (before)", "C0-"), (after, "optimum (after)", "C1-")):
            amp = r.amplitude(o, "y_s")
            if np.max(amp) > NOISE:
                ax.plot(omega, np.where(amp > NOISE * np.max(amp), amp, np.nan), style, label=name)
        drawn = [ln.get_ydata() for ln in ax.get_lines()]
        hi = max((np.nanmax(d) for d in drawn), default=1.0)
        lo = min((np.nanmin(d) for d in drawn), default=1.0)
        if hi > 10 * lo:
            ax.set_yscale("log")
        ax.set_xscale("log")
        unit = "N/m" if o.startswith("tension") else "m/m"
        ax.set_ylabel(f"|{o}| per unit y_s [{unit}]")
        tw = ax.twinx()
        tw.fill_between(omega, S, color="0.5", alpha=0.15, label=f"sea (Hs {settings.hs:g} m, Tp {settings.tp:g} s)")
        tw.set_ylabel("S [m^2 s/rad]", color="0.4")
        tw.set_ylim(bottom=0)
        lines = ax.get_legend_handles_labels()
        extra = tw.get_legend_handles_labels()
        ax.legend(lines[0] + extra[0], lines[1] + extra[1], fontsize=8, loc="best")
        ax.grid(True, which="both", alpha=0.3)
    axes[-1, 0].set_xlabel("omega [rad/s]")
    fig.suptitle(title or "RAOs before and after the design", fontsize=10)
    return save_figure(fig, path, dpi=110)


def plot_objective_history(result, path, *, title: str = "") -> Path:
    """Objective of every IPOPT solve (start x outer pass), failed starts marked, and the outer
    drag-linearization fixed point's objective per pass."""
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for k, r in enumerate(result.runs):
        ok = r["status"] in OK_STATUS
        a1.plot(k + 1, r["objective"], "o" if ok else "x", color="C2" if ok else "C3", ms=7,
                label=("converged" if ok else "failed: " + r["status"]))
    h, lab = a1.get_legend_handles_labels()
    uniq = dict(zip(lab, h))
    a1.legend(uniq.values(), uniq.keys(), fontsize=7)
    a1.set_xlabel("solve (start, outer pass)")
    a1.set_ylabel(f"objective ({result.objective_kind})")
    a1.set_title("every start", fontsize=9)
    a1.set_xticks(range(1, len(result.runs) + 1))
    for ax in (a1, a2):
        ax.ticklabel_format(axis="y", useOffset=False, style="plain")
    a1.grid(True, alpha=0.3)
    outer = [h["outer"] + 1 for h in result.outer_history]
    a2.plot(outer, [h["objective"] for h in result.outer_history], "C0o-")
    a2.set_xlabel("outer pass (drag linearization)")
    a2.set_ylabel("best objective")
    a2.set_title("outer fixed point", fontsize=9)
    a2.set_xticks(outer)
    a2.grid(True, alpha=0.3)
    fig.suptitle(title or "design objective", fontsize=10)
    return save_figure(fig, path, dpi=110)


def plot_constraint_margins(result, path, *, title: str = "") -> Path:
    """Horizontal bars of each constraint's normalized margin (>= 0 met), violated ones in red."""
    import matplotlib.pyplot as plt
    names = list(result.margins)
    vals = [result.margins[n] for n in names]
    fig, ax = plt.subplots(figsize=(8, 0.5 * len(names) + 1.5))
    ax.barh(names, vals, color=["C3" if v < 0 else ("C1" if v < 1e-3 else "C2") for v in vals])
    ax.axvline(0, color="k", lw=1)
    for y, v in enumerate(vals):
        ax.text(v, y, f" {v:+.3g}", va="center", fontsize=8)
    ax.set_xlabel("normalized margin (>= 0 met; 0 active)")
    ax.grid(True, axis="x", alpha=0.3)
    ax.set_title(title or "constraint margins at the optimum", fontsize=10)
    return save_figure(fig, path, dpi=110)
