"""Figures of a sweep Dataset: one summary figure per sweep, and a figure of any one metric.

The summary (:func:`figure_sweep`) has a panel for each case's status and for the headline
metrics: lines over one varied label, heat maps over two. Categorical data (status, pass/fail,
the model's name or its element count N, any metric with a few whole-number values) get one
colour per value and a legend, never a continuous colour bar. Titles name what varies (labels,
units, ranges), not the base scene's own values of them; the base scene is named below. Cases
that did not finish ``ok`` are left blank (grey) in the metric panels so a failed case never
looks like a number. Dimensions beyond the first two are held at their first value and named.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np

from ..plots import save_figure

SKIP_PREFIX = ("stats_", "wall_s")
SKIP = ("status", "message")
MAX_CATEGORIES = 8          # a metric with at most this many distinct whole numbers or short texts is categorical
MAX_TEXT = 32               # longer texts (a model's reason, a message) are not categories: they stay in the Dataset
MAX_PANELS = 9              # metric panels of the summary (the status panel comes on top)
HEADLINE = ("verdict_pass", "pass", "model_name", "model_segments", "tension_max", "tension_min", "amplitude_",
            "std_", "significant_", "omega_n_", "rao_peak_")
STATUS_COLOURS = {"ok": "#2ca02c", "failed": "#ff7f0e", "infeasible": "#9467bd", "error": "#d62728",
                  "missing": "#bbbbbb"}


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


def categories(da) -> list | None:
    """The sorted distinct values of a categorical variable (text, or at most :data:`MAX_CATEGORIES`
    whole numbers), None for continuous data."""
    v = da.values.ravel()
    if da.dtype.kind in "OUS":
        vals = sorted({str(x) for x in v if str(x)})
        return vals if 0 < len(vals) <= MAX_CATEGORIES and max(map(len, vals)) <= MAX_TEXT else None
    v = v[np.isfinite(v)]
    if v.size and np.all(v == np.round(v)):
        vals = sorted(set(v.tolist()))
        return vals if len(vals) <= MAX_CATEGORIES else None
    return None


def _category_label(name: str, value) -> str:
    if isinstance(value, str):
        return value
    if name.endswith("pass") and value in (0.0, 1.0):
        return "pass" if value else "fail"
    if name.endswith("segments"):
        return f"N = {value:g}"
    return f"{value:g}"


def _label(ds, name: str) -> str:
    u = ds[name].attrs.get("units", "")
    return f"{name} [{u}]" if u and u != "-" else name


def _fmt(v) -> str:
    return v if isinstance(v, str) else f"{v:.3g}"


def varied(ds) -> str:
    """What a sweep varies, in words: each label with its unit and range, zipped labels named with their dimension."""
    parts = []
    for d in ds.dims:
        if d not in ds.coords:
            continue
        x = ds[d].values
        u = ds[d].attrs.get("units", "")
        rng = _fmt(x[0]) if len(x) == 1 else f"{_fmt(x[0])} to {_fmt(x[-1])}"
        text = f"{d} {rng}{f' {u}' if u and u != '-' else ''} ({len(x)})"
        step = [c for c in ds.coords if c != d and ds[c].dims == (d,)]
        if step:
            text += " with " + ", ".join(step) + " in step"
        parts.append(text)
    return " x ".join(parts)


def _title(ds, what: str, held: dict) -> str:
    n_ok = int((ds["status"] == "ok").sum()) if "status" in ds else 0
    title = f"{ds.attrs.get('analysis', '')} sweep: {what}\nvarying {varied(ds)}; {n_ok} of {ds['status'].size} cases ok"
    if held:
        title += "\nshown at " + ", ".join(f"{d} = {_fmt(ds[d].values[0])}" for d in held)
        if any(ds.sizes[d] > 1 for d in held):
            title += " (all values in sweep.nc)"
    return title


def _ticks(ax, axis: str, values, n_max: int = 8, offset: float = 0.0):
    idx = np.unique(np.linspace(0, len(values) - 1, min(n_max, len(values))).round().astype(int))
    labels = [_fmt(values[i]) for i in idx]
    (ax.set_xticks if axis == "x" else ax.set_yticks)(idx + offset)
    (ax.set_xticklabels if axis == "x" else ax.set_yticklabels)(labels, rotation=45 if axis == "x" else 0)


def _is_log(values) -> bool:
    v = np.asarray(values, dtype=float)
    return v.size > 2 and np.all(v > 0) and v.max() / v.min() > 30


def _x_axis(ax, ds, d):
    """Positions along dimension ``d`` on the x axis of a line panel (its values, or indices for text)."""
    x = ds[d].values
    if x.dtype.kind == "f":
        if _is_log(x):
            ax.set_xscale("log")
        return x
    _ticks(ax, "x", x)
    return np.arange(len(x))


def _codes(da, cats):
    """Index of each entry's category (NaN where the entry has none)."""
    v = da.values
    out = np.full(v.shape, np.nan)
    for i, c in enumerate(cats):
        out[(v.astype(str) == c) if isinstance(c, str) else (v == c)] = i
    return out


def _panel_categorical(ax, ds, name, da, cats, colours):
    """One colour per category and a legend (a line panel: markers; a heat map: coloured cells)."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    codes = _codes(da, cats)
    if codes.ndim == 1:
        xs = _x_axis(ax, ds, da.dims[0])
        for i, c in enumerate(cats):
            sel = codes == i
            ax.scatter(np.asarray(xs)[sel], np.full(sel.sum(), i), color=colours[i], s=36, zorder=3)
        ax.set_yticks(range(len(cats)))
        ax.set_yticklabels([_category_label(name, c) for c in cats])
        ax.set_ylim(-0.6, len(cats) - 0.4)
        ax.set_xlabel(_label(ds, da.dims[0]))
    else:
        cmap = ListedColormap(colours).with_extremes(bad="0.85")
        ax.pcolormesh(np.ma.masked_invalid(codes), cmap=cmap, vmin=-0.5, vmax=len(cats) - 0.5,
                      edgecolors="w", linewidth=0.5)
        _heat_axes(ax, ds, da.dims)
    ax.legend(handles=[Patch(color=colours[i], label=_category_label(name, c)) for i, c in enumerate(cats)],
              fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, frameon=False)
    ax.set_title(name, fontsize=9)


def _heat_axes(ax, ds, dims):
    yd, xd = dims[0], dims[1]
    _ticks(ax, "x", ds[xd].values, offset=0.5)
    _ticks(ax, "y", ds[yd].values, offset=0.5)
    ax.set(xlabel=_label(ds, xd), ylabel=_label(ds, yd))


def _panel_continuous(fig, ax, ds, name, da):
    """A line over one dimension, a heat map with its colour bar over two (values written in small maps)."""
    import matplotlib.pyplot as plt
    if da.ndim == 1:
        xs = _x_axis(ax, ds, da.dims[0])
        ax.plot(xs, da.values, "o-", ms=4)
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.set(xlabel=_label(ds, da.dims[0]), ylabel=_label(ds, name))
        ax.grid(alpha=0.3)
    else:
        z = da.values
        vals = z[np.isfinite(z)]
        vmin, vmax = (float(vals.min()), float(vals.max())) if vals.size else (0.0, 1.0)
        im = ax.pcolormesh(np.ma.masked_invalid(z), cmap=plt.get_cmap("viridis").with_extremes(bad="0.85"),
                           vmin=vmin, vmax=vmax)
        if z.size <= 64:
            for (i, j), v in np.ndenumerate(z):
                if np.isfinite(v):
                    ax.text(j + 0.5, i + 0.5, f"{v:.3g}", ha="center", va="center", fontsize=7,
                            color="w" if v < vmin + 0.5 * (vmax - vmin) else "k")
        _heat_axes(ax, ds, da.dims)
        cb = fig.colorbar(im, ax=ax, label=_label(ds, name))
        cb.formatter.set_useOffset(False)        # the values themselves, not an offset above the bar
        cb.update_ticks()
    ax.set_title(name, fontsize=9)


def summary_metrics(ds, metrics=None) -> tuple[list, list]:
    """(drawn, not drawn): the metrics of the summary figure, headline ones first (:data:`HEADLINE`), at most
    :data:`MAX_PANELS`; ``metrics`` given: those, in that order. Constant and many-valued or long text metrics
    are not drawn (they are in the Dataset; the figure names the ones left out)."""
    if metrics is not None:
        drawable = [n for n in metrics if ds[n].dtype.kind == "f" or categories(ds[n]) is not None]
        return drawable, [n for n in metrics if n not in drawable]
    else:
        names = []
        for name, da in ds.data_vars.items():
            if name in SKIP or name.startswith(SKIP_PREFIX):
                continue
            if name in plottable(ds) or (categories(da) is not None and len(categories(da)) > 1):
                names.append(name)
        rank = {n: next((k for k, h in enumerate(HEADLINE) if n.startswith(h) or n.endswith(h)), len(HEADLINE))
                for n in names}
        names.sort(key=lambda n: rank[n])         # stable: the Dataset's order within a rank
    return names[:MAX_PANELS], names[MAX_PANELS:]


def figure_sweep(ds, metrics=None):
    """The summary figure of a sweep: each case's status and the headline metrics, titled by what varies.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result (:func:`cablesys.sweep`).
    metrics : list of str, optional
        Metrics to draw (default :func:`summary_metrics`: headline metrics first, at most nine).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt
    long = [d for d in ds["status"].dims if ds.sizes[d] > 1] or list(ds["status"].dims[:1])
    dims = long[:2]
    held = {d: 0 for d in ds["status"].dims if d not in dims}       # one value, or beyond the first two
    sub = ds.isel(held) if held else ds
    drawn, rest = summary_metrics(sub, metrics)
    names = ["status", *drawn]
    ncol = min(3, len(names))
    nrow = -(-len(names) // ncol)
    one_d = len(dims) == 1
    width = max(5.2 * ncol, 8.0)
    fig, axes = plt.subplots(nrow, ncol, figsize=(width, (3.0 if one_d else 3.8) * nrow + 1.4),
                             squeeze=False, layout="constrained")
    ok = sub["status"] == "ok"
    for ax, name in zip(axes.ravel(), names):
        if name == "status":
            cats = [s for s in STATUS_COLOURS if (sub["status"] == s).any()]
            _panel_categorical(ax, sub, "status", sub["status"], cats, [STATUS_COLOURS[s] for s in cats])
            continue
        da = sub[name].where(ok) if sub[name].dtype.kind == "f" else sub[name].where(ok, "")
        cats = categories(da)
        if cats is not None:
            colours = [plt.get_cmap("tab10")(i % 10) for i in range(len(cats))]
            _panel_categorical(ax, sub, name, da, cats, colours)
        else:
            _panel_continuous(fig, ax, sub, name, da)
    for ax in axes.ravel()[len(names):]:
        ax.set_visible(False)
    fig.suptitle(_title(ds, "status and headline metrics", held), fontsize=10)
    note = f"base scene: {ds.attrs.get('scene', '')} (its values of the varied labels are replaced case by case)"
    if rest:
        note += f"\n{len(rest)} more metrics in sweep.nc, not drawn: {', '.join(rest[:8])}{', ...' if len(rest) > 8 else ''}"
    fig.supxlabel("\n".join(textwrap.fill(line, int(17 * width)) for line in note.split("\n")),
                  fontsize=7, x=0.01, ha="left", color="0.35")
    return fig


def plot_metric(ds, name: str, path) -> Path:
    """Write :func:`figure_metric` of ``name`` to ``path`` (PNG)."""
    return save_figure(figure_metric(ds, name), path)


def figure_metric(ds, name: str):
    """One metric of a sweep as a matplotlib figure: a line for one dimension, heat map(s) for two or more
    (a third dimension gives a panel per value, at most six; further ones are held at their first value).

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
    cats = categories(da)
    panels = [None] if len(dims) <= 2 else list(range(min(6, da.sizes[dims[2]])))
    ncol = min(3, len(panels))
    nrow = -(-len(panels) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.4 * ncol, (3.6 if len(dims) == 1 else 4.2) * nrow + 0.8),
                             squeeze=False, layout="constrained")
    for ax, k in zip(axes.ravel(), panels):
        part = da if k is None else da.isel({dims[2]: k})
        if cats is not None:
            _panel_categorical(ax, ds, name, part, cats, [plt.get_cmap("tab10")(i % 10) for i in range(len(cats))])
        else:
            _panel_continuous(fig, ax, ds, name, part)
        if k is not None:
            ax.set_title(f"{name} at {dims[2]} = {_fmt(ds[dims[2]].values[k])}", fontsize=9)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(_title(ds, name, held), fontsize=9)
    return fig


def plot_sweep(ds, out, metrics=None) -> list:
    """The summary figure :func:`figure_sweep` as ``out/sweep.png``.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result.
    out : path
        Folder for the figure (created).
    metrics : list of str, optional
        Metrics to draw (default: :func:`summary_metrics`).

    Returns
    -------
    list of Path
        The PNG file written.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    return [save_figure(figure_sweep(ds, metrics), out / "sweep.png")]
