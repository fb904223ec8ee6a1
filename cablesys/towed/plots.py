"""Figures of towed-cable results (reads results only; matplotlib imported lazily)."""

from __future__ import annotations

from pathlib import Path

from ..plots import save_figure
from .analysis import TowedAnalysis

__all__ = ["plot_response"]


def plot_response(res: TowedAnalysis, path: str | Path) -> Path:
    """|H| (eq. 26) and c* in m/s (eq. 27b) against the tow-point frequency (Hz), one line per xi.

    Parameters
    ----------
    res : TowedAnalysis
        The analysed towed scene.
    path : str or pathlib.Path
        Output image.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True, constrained_layout=True)
    f = res.frequency
    for i, x in enumerate(res.xi):
        a1.loglog(f, abs(res.H[i]), label=f"xi = x/L = {x:.3g}")
        a2.semilogx(f, res.c_star_m_s[i], label=f"xi = {x:.3g}")
    a2.axhline(res.water_pulley_c_star * res.scene.speed, color="gray", ls="--",
               label="low-frequency limit (1 + 1/p) U (eq. 14)")
    a1.set_ylabel("|H| = cross-track motion / tow-point motion (-)")
    a1.set_title(f"Towed cable L = {res.scene.cable.length:.4g} m, U = {res.scene.speed:.4g} m/s "
                 "(Kennedy & Strahan 1981)", fontsize=10)
    a2.set_ylabel("mean phase velocity c* (m/s)")
    a2.set_xlabel("frequency of the tow-point motion (Hz)")
    for ax in (a1, a2):
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="best")
    return save_figure(fig, path, dpi=110)
