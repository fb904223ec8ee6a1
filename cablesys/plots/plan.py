"""The plan view of a run out of the plane (a 3-D scene or a towing ship's track): where the top, the cable and the
bodies go seen from above, and where each body lies relative to the top (reads a TimeResult)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .axes import plain_axis
from .figure import save_figure

SNAPSHOTS = 6            # the cable drawn at this many instants in the plan view
MOVING_TOP_M_S = 1e-6    # a top slower than this (m/s, on average) has no heading: offsets in the scene's axes


def _length(span_m: float, units: str) -> tuple[float, str]:
    from .time_domain import _length_scale
    return _length_scale(span_m, units)


def _headings(t, xs, zs) -> np.ndarray | None:
    """The top's heading psi(t) (rad, from +x towards +z) from its track, or None when it hardly moves."""
    if t.size < 2:
        return None
    vx, vz = np.gradient(xs, t), np.gradient(zs, t)
    if float(np.mean(np.hypot(vx, vz))) < MOVING_TOP_M_S:
        return None
    return np.unwrap(np.arctan2(vz, vx))


def plot_plan_view(result, path, *, title: str | None = None, units: str = "SI", bodies: dict | None = None,
                   lines: tuple | None = None, held: dict | None = None) -> Path:
    """Two panels: the plan view seen from above (x right, z up the page: right-handed with y down) of the top's track,
    each body's path and the cable at :data:`SNAPSHOTS` instants (segmented runs, nodes ``node_x``, ``node_z``); and
    each body's position relative to the top against time, along and across the top's heading when it moves
    (ahead +, to port +: counter-clockwise seen from above) or along x and z when it does not, with its depth below
    the top.

    Parameters
    ----------
    result : TimeResult
        A run whose outputs have ``z_b`` (a 3-D scene) or a planar one (z = 0, a straight track along x).
    path : str or pathlib.Path
        Output image.
    title : str, optional
        Figure title (default: the scene name).
    units : str
        "SI" or "fps": the units of the scene file.
    bodies : dict, optional
        {name: output label prefix} of the bodies to follow (a system of lines: its free points, ``"point.NAME."``
        with outputs ``point.NAME.x``, ``.y``, ``.z``); default the chain's bodies ``x_b``, ``x_b_2``, ...
    lines : tuple, optional
        The node numbers of each line, drawn apart (a system of lines); default one chain of all nodes.
    held : dict, optional
        {name: output label prefix} of further prescribed points (points of the ship besides the tow point: a second
        boom, a davit), their paths drawn dashed beside the top's.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    import matplotlib.pyplot as plt

    t = np.asarray(result.time, float)
    data = result.data
    zero = np.zeros_like(t)
    xs, zs, ys = np.asarray(result["x_s"]), np.asarray(data.get("z_s", zero)), np.asarray(result["y_s"])
    if bodies is None:
        sfx = [""] if "x_b" in data else sorted({lbl[3:] for lbl in data if lbl.startswith("x_b_") and lbl[4:].isdigit()})
        bodies = {(f"body {s[1:]}" if s else "body"): (f"x_b{s}", f"z_b{s}", f"y_b{s}") for s in sfx}
    else:
        bodies = {name: (f"{pre}x", f"{pre}z", f"{pre}y") for name, pre in bodies.items()}
    bodies = [(name, np.asarray(result[lx]), np.asarray(data.get(lz, zero)), np.asarray(result[ly]))
              for name, (lx, lz, ly) in bodies.items()]
    span = max([np.ptp(xs), np.ptp(zs)] + [max(np.ptp(x), np.ptp(z)) for _, x, z, _ in bodies])
    fl, ul = _length(span, units)
    fig, (a_plan, a_rel) = plt.subplots(1, 2, figsize=(13, 5.8), gridspec_kw={"width_ratios": [1.15, 1.0]})
    prof = getattr(result, "profiles", {}) or {}
    if "node_x" in prof:
        nx, nz = np.asarray(prof["node_x"]), np.asarray(prof.get("node_z", np.zeros_like(prof["node_x"])))
        picks = np.unique(np.linspace(0, t.size - 1, SNAPSHOTS).astype(int))
        for k, i in enumerate(picks):
            for m, seq in enumerate(lines or (slice(None),)):
                a_plan.plot(nx[i][list(seq) if lines else seq] * fl, nz[i][list(seq) if lines else seq] * fl, ".-",
                            color="C3", lw=1.3, ms=4, zorder=3,
                            label=f"cable (nodes) at {picks.size} instants, t = {t[picks[0]]:.4g} to "
                                  f"{t[picks[-1]]:.4g} s" if k == 0 and m == 0 else None)
    a_plan.plot(xs * fl, zs * fl, "k-", lw=1.4, label="top (tow point / ship)")
    a_plan.plot(xs[0] * fl, zs[0] * fl, "ks", ms=6, label=f"top at t = {t[0]:.4g} s")
    for name, pre in (held or {}).items():
        a_plan.plot(np.asarray(result[f"{pre}x"]) * fl, np.asarray(data.get(f"{pre}z", zero)) * fl, "k--", lw=1.0,
                    label=f"{name} (a point of the ship)")
    if xs.size > 1 and np.hypot(xs[-1] - xs[-2], zs[-1] - zs[-2]) > 0:
        a_plan.annotate("", xy=(xs[-1] * fl, zs[-1] * fl), xytext=(xs[-2] * fl, zs[-2] * fl),
                        arrowprops=dict(arrowstyle="-|>", color="k", lw=1.2))
    for k, (name, x, z, _) in enumerate(bodies):
        a_plan.plot(x * fl, z * fl, "-", color=f"C{k}", lw=1.1, label=f"{name} path")
        a_plan.plot(x[-1] * fl, z[-1] * fl, "o", color=f"C{k}", ms=6, label=f"{name} at t = {t[-1]:.4g} s")
    a_plan.set_aspect("equal", adjustable="datalim")
    a_plan.set(xlabel=f"x ({ul})", ylabel=f"z ({ul}, 90 deg counter-clockwise from x)",
               title="plan view from above")
    plain_axis(a_plan)
    a_plan.grid(alpha=0.3)
    a_plan.legend(fontsize=7, loc="best")

    psi = _headings(t, xs, zs)
    rel_span = max([1e-12] + [max(np.ptp(x - xs), np.ptp(z - zs), np.max(np.abs(y - ys))) for _, x, z, y in bodies])
    fr, ur = _length(rel_span, units)
    for k, (name, x, z, y) in enumerate(bodies):
        dx, dz = x - xs, z - zs
        if psi is not None:
            along, across = np.cos(psi) * dx + np.sin(psi) * dz, -np.sin(psi) * dx + np.cos(psi) * dz
            names = ("ahead of the top (+)", "to port of the top (+)")
        else:
            along, across = dx, dz
            names = ("x from the top", "z from the top")
        a_rel.plot(t, along * fr, "-", color=f"C{k}", lw=1.2, label=f"{name}: {names[0]}")
        a_rel.plot(t, across * fr, "--", color=f"C{k}", lw=1.2, label=f"{name}: {names[1]}")
        a_rel.plot(t, (y - ys) * fr, ":", color=f"C{k}", lw=1.4, label=f"{name}: depth below the top")
    a_rel.set(xlabel="time (s)", ylabel=f"position relative to the top ({ur})",
              title="bodies relative to the top" + (", along and across its heading" if psi is not None else ""))
    a_rel.set_xlim(t[0], t[-1])
    plain_axis(a_rel)
    a_rel.grid(alpha=0.3)
    a_rel.legend(fontsize=7, loc="best")
    fig.suptitle(title or result.scene_name)
    return save_figure(fig, path)
