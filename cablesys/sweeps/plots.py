"""Figures of a sweep Dataset: a line plot (one varied label) or a heat map (two or more) per metric.

Cases that did not finish ``ok`` are left blank (grey) so a failed case never looks like a
number. With more than two dimensions the third gives one panel per value (at most six) and
any further ones are held at their first value (named in the title).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plots import save_figure

SKIP_PREFIX = ("stats_", "wall_s")


def plottable(ds) -> list:
    """Numeric metrics worth a figure (not timing statistics, not constant over the sweep)."""
    out = []
    for name, da in ds.data_vars.items():
        if da.dtype.kind != "f" or name.startswith(SKIP_PREFIX):
            continue
        v = da.values[np.isfinite(da.values)]
        if v.size and np.ptp(v) > 1e-12 * max(1.0, float(np.max(np.abs(v)))):
            out.append(name)
    return out


def _label(ds, name: str) -> str:
    u = ds[name].attrs.get("units", "")
    return f"{name} [{u}]" if u and u != "-" else name


def _is_log(values) -> bool:
    v = np.asarray(values, dtype=float)
    return v.size > 2 and np.all(v > 0) and v.max() / v.min() > 30


def _ticks(ax, axis: str, values, n_max: int = 8, offset: float = 0.0):
    idx = np.unique(np.linspace(0, len(values) - 1, min(n_max, len(values))).round().astype(int))
    labels = [f"{values[i]:.3g}" if not isinstance(values[i], str) else values[i] for i in idx]
    (ax.set_xticks if axis == "x" else ax.set_yticks)(idx + offset)
    (ax.set_xticklabels if axis == "x" else ax.set_yticklabels)(labels, rotation=45 if axis == "x" else 0)


def plot_metric(ds, name: str, path) -> Path:
    """Write :func:`figure_metric` of ``name`` to ``path`` (PNG)."""
    return save_figure(figure_metric(ds, name), path)


def figure_metric(ds, name: str):
    """One metric of a sweep as a matplotlib figure: a line for one dimension, heat map(s) for two or more.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result (:func:`cablesys.sweep`).
    name : str
        A numeric metric of ``ds``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt
    da = ds[name].where(ds["status"] == "ok")
    dims = list(da.dims)
    held = {d: 0 for d in dims[3:]}
    if held:
        da = da.isel(held)
    title = f"{ds.attrs.get('scene', '')}\n{name} ({ds.attrs.get('analysis', '')} sweep)"
    if held:
        title += " at " + ", ".join(f"{d} = {ds[d].values[0]:.3g}" for d in held)
    if len(dims) == 1:
        d = dims[0]
        x = ds[d].values
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        xs = x if x.dtype.kind == "f" else np.arange(len(x))
        ax.plot(xs, da.values, "o-", ms=4)
        if _is_log(xs):
            ax.set_xscale("log")
        if x.dtype.kind != "f":
            _ticks(ax, "x", x)
        ax.set(xlabel=_label(ds, d), ylabel=_label(ds, name))
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        return fig
    panels = [None] if len(dims) == 2 else list(range(min(6, da.sizes[dims[2]])))
    ncol = min(3, len(panels))
    nrow = -(-len(panels) // ncol)
    fig, grid_axes = plt.subplots(nrow, ncol + 1, figsize=(4.6 * ncol + 1.2, 3.9 * nrow + 0.6), squeeze=False,
                                  gridspec_kw={"width_ratios": [1.0] * ncol + [0.06]})
    axes, cbar_axes = grid_axes[:, :ncol], grid_axes[:, ncol]
    vals = da.values[np.isfinite(da.values)]
    vmin, vmax = (float(vals.min()), float(vals.max())) if vals.size else (0.0, 1.0)
    cmap = plt.get_cmap("viridis").with_extremes(bad="0.85")
    yd, xd = dims[0], dims[1]
    for ax, k in zip(axes.ravel(), panels):
        z = da.values if k is None else da.isel({dims[2]: k}).values
        im = ax.pcolormesh(np.ma.masked_invalid(z), cmap=cmap, vmin=vmin, vmax=vmax)
        if z.size <= 64:
            for (i, j), v in np.ndenumerate(z):
                if np.isfinite(v):
                    ax.text(j + 0.5, i + 0.5, f"{v:.3g}", ha="center", va="center", fontsize=7,
                            color="w" if v < vmin + 0.5 * (vmax - vmin) else "k")
        _ticks(ax, "x", ds[xd].values, offset=0.5)
        _ticks(ax, "y", ds[yd].values, offset=0.5)
        ax.set(xlabel=_label(ds, xd), ylabel=_label(ds, yd))
        if k is not None:
            v = ds[dims[2]].values[k]
            ax.set_title(f"{dims[2]} = {v:.3g}" if not isinstance(v, str) else f"{dims[2]} = {v}", fontsize=9)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    fig.colorbar(im, cax=cbar_axes[0], label=_label(ds, name))
    for ax in cbar_axes[1:]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


def plot_sweep(ds, out, metrics=None) -> list:
    """A PNG per metric in ``out``.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result.
    out : path
        Folder for the figures (created).
    metrics : list of str, optional
        Metrics to plot (default: :func:`plottable`).

    Returns
    -------
    list of Path
        The PNG files written.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    names = metrics or plottable(ds)
    return [plot_metric(ds, n, out / f"{n}.png") for n in names]
