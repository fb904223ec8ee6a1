"""Plots of RAOs, modes and the nonlinear/linear comparison (reads results only; matplotlib lazily)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..results import unit_of
from ..plots import save_figure


def _plt():
    import matplotlib
    matplotlib.use(matplotlib.get_backend())
    import matplotlib.pyplot as plt
    return plt


def _mark(ax, natural, label=True):
    for k, (name, w) in enumerate(natural.items()):
        ax.axvline(w, color="0.4", ls=":", lw=1.2, label=f"{name} = {w:.3g} rad/s" if label else None)


def plot_rao_bode(raos: dict, output: str, input: str, natural: dict, path, title: str = "") -> Path:
    """Magnitude (log) and phase of ``output`` per unit ``input`` for several RAOs ({legend: RAO})."""
    plt = _plt()
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for name, r in raos.items():
        inp = input if input in r.input_labels else r.input_labels[0]
        amp = r.amplitude(output, inp)
        a1.plot(r.omega, amp, label=name + ("" if np.any(amp > 1e-12 * max(amp.max(), 1e-300)) and amp.max() > 0
                                            else " (identically zero)"))
        a2.plot(r.omega, np.degrees(r.phase(output, inp)), label=name)
    if any(np.any(r.amplitude(output, input if input in r.input_labels else r.input_labels[0]) > 0)
           for r in raos.values()):
        a1.set_yscale("log")
    _mark(a1, natural)
    _mark(a2, natural, label=False)
    u = unit_of(output) or "-"
    a1.set_ylabel(f"|{output}| per unit {input} [{u}/m]")
    a2.set_ylabel("phase [deg]")
    a2.set_xlabel("forcing frequency omega [rad/s]")
    damped = [r.amplitude(output, input if input in r.input_labels else r.input_labels[0]).max()
              for k, r in raos.items() if r.kind != "exact"]
    if damped and max(damped) > 0:
        a1.set_ylim(top=20 * max(damped))          # the undamped exact peak is clipped
    a1.legend(fontsize=8)
    a1.grid(True, which="both", alpha=0.3)
    a2.grid(True, alpha=0.3)
    fig.suptitle(title or f"RAO of {output} for top motion {input}")
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_modes(modes, length: float, path, title: str = "") -> Path:
    """Sketch of each mode: the straight cable at rest and displaced along the mode shape."""
    plt = _plt()
    n = len(modes.omega_undamped)
    fig, axes = plt.subplots(1, n, figsize=(3.5 * n, 4.5), squeeze=False)
    for k, ax in enumerate(axes[0]):
        shape = dict(zip(modes.q_labels, modes.shapes[:, k]))
        for s, style in ((0.0, "k-"), (1.0, "C0-"), (-1.0, "C1--")):
            phi = s * 0.25 * shape.get("phi", 0.0)
            l = length * (1 + s * 0.1 * shape.get("u", 0.0))
            x, y = -l * np.sin(phi), l * np.cos(phi)       # Wang (1971): e_t = (-sin phi, cos phi), y down
            ax.plot([0, x], [0, y], style, lw=2, label={0.0: "at rest", 1.0: "+ mode", -1.0: "- mode"}[s])
            ax.plot(x, y, "o", color=style[:2] if s else "k", ms=8)
        ax.invert_yaxis()
        ax.set_aspect("equal")
        ax.set_xlim(-0.5 * length, 0.5 * length)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("depth y [m]")
        ax.set_title(f"mode {k + 1} ({modes.dominant[k]}): {modes.omega_undamped[k]:.3g} rad/s", fontsize=9)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle(title or "mode shapes (stretch exaggerated)")
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_nonlinear_rao(omega, curves: dict, natural: dict, ylabel: str, path, title: str = "",
                       points: dict | None = None) -> Path:
    """Amplitude-vs-frequency curves ({legend: values}) with optional markers ({legend: (w, a)})."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, vals in curves.items():
        ax.plot(omega, vals, label=name)
    for name, (w, a) in (points or {}).items():
        ax.plot(w, a, "o", mfc="none", ms=8, label=name)
    _mark(ax, natural)
    ax.set_xlabel("forcing frequency omega [rad/s]")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    save_figure(fig, path, dpi=110)
    return Path(path)


def plot_response_spectrum(stoch, output: str, natural: dict, path, title: str = "") -> Path:
    """Sea spectrum and the response spectrum of ``output``."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(stoch.omega, stoch.spectrum, label="sea spectrum S(omega) [m^2 s/rad]")
    u = unit_of(output) or "-"
    ax.plot(stoch.omega, stoch.response_spectrum(output),
            label=f"{output} response spectrum [{u}^2 s/rad], significant amp. {stoch.significant_amplitude(output):.3g} {u}")
    _mark(ax, natural)
    ax.set_xlabel("omega [rad/s]")
    ax.set_ylabel("spectral density")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    save_figure(fig, path, dpi=110)
    return Path(path)
