"""Figures from results only; matplotlib is imported lazily inside each function."""

from __future__ import annotations

from pathlib import Path


def save_figure(fig, path, **savefig_kw) -> Path:
    """Lay out, write and close a figure (every plot of the package and the studies ends here)."""
    import matplotlib.pyplot as plt
    savefig_kw.setdefault("dpi", 120)
    fig.tight_layout()
    fig.savefig(path, **savefig_kw)
    plt.close(fig)
    return Path(path)
