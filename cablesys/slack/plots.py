"""Figures of slack-cable results (reads results only; matplotlib imported lazily)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plots import save_figure
from .results import MODE_TYPES, Equilibrium, ModeSet

COLORS = {"O": "0.45", "A": "tab:red", "S": "tab:blue", "H": "tab:purple"}


def _plt():
    import matplotlib
    import matplotlib.pyplot as plt
    del matplotlib
    return plt


def plot_equilibrium(eq: Equilibrium, path: str | Path) -> Path:
    """Static shape (m) and element tension (N) along the cable.

    Parameters
    ----------
    eq : Equilibrium
        The static shape.
    path : str or pathlib.Path
        Output image.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    plt = _plt()
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), constrained_layout=True)
    a1.plot(eq.x, eq.z, "k-", lw=1.5, label="cable")
    a1.plot([eq.x[0], eq.x[-1]], [eq.z[0], eq.z[-1]], "k:", lw=1, label="chord")
    sc = eq.scene
    for pm, i in zip(sc.masses, _mass_nodes(eq)):
        a1.plot(eq.x[i], eq.z[i], "o", ms=4 + pm.mass, color="tab:orange")
    if sc.masses:
        a1.plot([], [], "o", color="tab:orange", label="point masses")
    a1.set_xlabel("x, horizontal (m)")
    a1.set_ylabel("z, up (m)")
    a1.set_aspect("equal", adjustable="datalim")
    a1.set_title(f"Equilibrium: sag/L = {eq.sag_to_length:.4f}, H = {eq.horizontal_tension:.4g} N")
    a1.legend(loc="best")
    sm = 0.5 * (eq.s[1:] + eq.s[:-1])
    a2.plot(sm, eq.tension, "b-", label="tension T")
    a2.axhline(eq.horizontal_tension, color="gray", ls="--", label="horizontal component H")
    a2.set_xlabel("unstretched arc length s from support A (m)")
    a2.set_ylabel("tension (N)")
    a2.legend(loc="best")
    return save_figure(fig, path, dpi=110)


def _mass_nodes(eq: Equilibrium):
    return [int(np.argmin(np.abs(eq.s - pm.position))) for pm in eq.scene.masses]


def plot_mode_shapes(eq: Equilibrium, modes: ModeSet, path: str | Path, n: int = 6) -> Path:
    """The first ``n`` mode shapes (eq. 25 normalization) against arc length.

    Parameters
    ----------
    eq : Equilibrium
        The static shape.
    modes : ModeSet
        Its modes.
    path : str or pathlib.Path
        Output image.
    n : int, optional
        Number of modes drawn.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    plt = _plt()
    n = min(n, len(modes))
    fig, axes = plt.subplots(n, 1, figsize=(7, 1.6 * n + 0.8), sharex=True, constrained_layout=True)
    axes = np.atleast_1d(axes)
    th = eq.scene.inclination
    for k, ax in enumerate(axes):
        sh = modes.shapes[k]
        t = modes.mode_type[k]
        if t == "O":
            ax.plot(modes.s, sh[:, 1], color=COLORS[t], label="out-of-plane y")
        else:
            un = -sh[:, 0] * np.sin(th) + sh[:, 2] * np.cos(th)
            uc = sh[:, 0] * np.cos(th) + sh[:, 2] * np.sin(th)
            ax.plot(modes.s, un, color=COLORS[t], label="normal to chord")
            ax.plot(modes.s, uc, color=COLORS[t], ls="--", label="along chord")
        for i in _mass_nodes(eq):
            ax.axvline(eq.s[i], color="tab:orange", lw=0.8, alpha=0.6)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_ylabel(r"$\psi/\psi_R$ (kg$^{-1/2}$)", fontsize=8)
        ax.set_title(f"mode {k + 1}: {MODE_TYPES[t]}, omega = {modes.omega[k]:.4g} rad/s", fontsize=9)
        ax.legend(loc="upper right", fontsize=7)
    axes[-1].set_xlabel("unstretched arc length s from support A (m)")
    return save_figure(fig, path, dpi=110)
