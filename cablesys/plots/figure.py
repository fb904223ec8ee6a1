"""Writing a figure to a file: the one step every figure of the package ends with."""

from __future__ import annotations

from pathlib import Path


def save_figure(fig, path, **savefig_kw) -> Path:
    """Lay out (tight, unless the figure has its own layout engine), write and close a figure.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; it is closed afterwards.
    path : str or pathlib.Path
        Output file; the format follows the suffix (``.png``, ``.pdf``, ``.svg``).
    **savefig_kw
        Passed to ``Figure.savefig`` (``dpi`` defaults to 120).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    import matplotlib.pyplot as plt
    savefig_kw.setdefault("dpi", 120)
    if fig.get_layout_engine() is None:      # keep a figure's own engine (constrained_layout=True)
        fig.tight_layout()
    fig.savefig(path, **savefig_kw)
    plt.close(fig)
    return Path(path)
