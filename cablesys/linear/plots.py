"""Plots of RAOs, modes and the nonlinear/linear comparison (reads results only; matplotlib lazily)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plots import save_figure
from ..plots.axes import legend_outside, plain_axis
from ..results import unit_of
from .frequency_response import is_tension


def _plt():
    import matplotlib
    matplotlib.use(matplotlib.get_backend())
    import matplotlib.pyplot as plt
    return plt


NOISE = 1e-9      # a response below 1e-9 of its input (per unit input) is numerical zero


def noise_floor(curves) -> float:
    """The amplitude below which a curve of these RAOs is numerical noise: 1e-9 of the largest
    response per unit input (and at least 1e-300)."""
    peak = max((float(np.max(c)) for c in curves if len(c)), default=0.0)
    return max(NOISE * peak, NOISE if peak == 0.0 else 0.0, 1e-300)


def is_noise(amplitude, floor: float) -> bool:
    """True when no point of ``amplitude`` rises above ``floor`` (identically zero or rounding noise)."""
    return not np.any(np.asarray(amplitude) > floor)


MAX_NAMED_MODES = 4      # more natural frequencies than this are numbered on the axis, one legend entry


def _mark(ax, natural, label=True, forcing=None):
    """Natural frequencies dashed, forcing frequencies solid red, a sea band shaded.

    Up to :data:`MAX_NAMED_MODES` natural frequencies get a colour and a legend entry each; more are
    grey, numbered (1 = lowest in ``natural``'s order) at the top of the axes, under one legend entry.
    """
    numbered = len(natural) > MAX_NAMED_MODES
    for k, (name, w) in enumerate(natural.items()):
        if numbered:
            ax.axvline(w, color="0.45", ls="--", lw=0.9, label=("natural frequencies (mode numbers on top)"
                                                                 if label and k == 0 else None))
            if label:
                ax.text(w, 1.0, _mode_number(name, k), transform=ax.get_xaxis_transform(), ha="center",
                        va="bottom", fontsize=6, color="0.3")
        else:
            ax.axvline(w, color=f"C{(k + 3) % 10}", ls="--", lw=1.1,
                       label=f"natural {name} = {w:.3g} rad/s" if label else None)
    forcing = dict(forcing or {})
    lo, hi = forcing.pop("sea band low", None), forcing.pop("sea band high", None)
    if lo is not None and hi is not None:
        ax.axvspan(lo, hi, color="C0", alpha=0.07, label="sea band (99.8 % of the energy)" if label else None)
    for name, w in forcing.items():
        ax.axvline(w, color="red", ls="-", lw=1.3, alpha=0.8, label=name if label else None)


def _mode_number(name: str, k: int) -> str:
    """The number drawn for natural frequency ``name`` (``"mode 3 (x[10])"`` -> ``"3"``), else ``k + 1``."""
    parts = name.split()
    return parts[1] if len(parts) > 1 and parts[0] == "mode" and parts[1].isdigit() else f"{k + 1}"


MAX_TABLE_ROWS = 20      # rows of the natural-frequency table beside an RAO; the rest counted (all in rao_summary.json)


def _natural_table(natural: dict) -> str:
    """The numbered natural frequencies of :func:`_mark` as text lines "number  omega rad/s  name", the first
    MAX_TABLE_ROWS and a line counting the rest."""
    def what(name):                  # "mode 3 (x[10])" -> "x[10]": the number is already in the row
        return name.split("(", 1)[1].rstrip(")") if name.startswith("mode ") and "(" in name else name
    rows = [f"{_mode_number(name, k):>2} {w:>6.4g} rad/s  {what(name)}" for k, (name, w) in enumerate(natural.items())]
    more = len(rows) - MAX_TABLE_ROWS
    if more > 0:
        rows = rows[:MAX_TABLE_ROWS] + [f"... {more} more to {max(natural.values()):.4g} rad/s"]
    return "\n".join([" #  omega        largest"] + rows)


def _wrap(title: str, width: int = 70) -> str:
    import textwrap
    return "\n".join(textwrap.wrap(title, width)) if title else title


DYNAMIC_RANGE = 1e-4     # the amplitude axis spans four decades below the largest response shown


def _band_of_interest(omega, natural: dict, forcing: dict) -> tuple[dict, float, float]:
    """(the natural frequencies inside the range shown, lowest, highest frequency shown, rad/s).

    The range spans the forcing (sea band included) and the natural frequencies it can excite
    (:func:`~cablesys.linear.band.relevant_modes`; all of them without forcing) with a factor 3
    margin, within ``omega``; every natural frequency in that range is marked.
    """
    from .band import relevant_modes
    f = [w for w in (forcing or {}).values() if np.isfinite(w) and w > 0]
    ws = list(relevant_modes(natural.values(), f)) + f
    lo, hi = float(omega[0]), float(omega[-1])
    if ws:
        lo, hi = max(lo, min(ws) / 3.0), min(hi, max(ws) * 3.0)
    return {k: w for k, w in natural.items() if lo <= w <= hi}, lo, hi


def plot_rao_bode(raos: dict, output: str, input: str, natural: dict, path, title: str = "",
                  forcing: dict | None = None, units: str = "SI") -> Path:
    """Magnitude and unwrapped phase (deg) of ``output`` per unit ``input`` for several RAOs ({legend: RAO}).

    The frequency axis spans the forcing (and sea band) and the natural frequencies it can excite
    (:func:`~cablesys.linear.band.relevant_modes`), with a factor 3 margin; every natural frequency
    in that range is marked, those outside are counted in a note. The amplitude axis spans :data:`DYNAMIC_RANGE` below the largest response in
    that range (an undamped exact peak clipped at 20 x the damped ones). Curves that are numerical
    zero (below :data:`NOISE` of the largest response per unit input) are not drawn but named;
    points of a drawn curve below that floor are blanked (with their phase). The legend and the
    table of natural frequencies sit right of the axes. ``units`` "fps" shows the amplitude per ft
    of top motion in ft/lbf.
    """
    from ..units import per_input_unit
    plt = _plt()
    fu, u = per_input_unit(unit_of(output) or "-", units, unit_of(input) or "m")
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10.5, 6.5), sharex=True)
    curves = {}
    for name, r in raos.items():
        inp = input if input in r.input_labels else r.input_labels[0]
        curves[name] = (r, inp, r.amplitude(output, inp) * fu)
    omega = next(iter(curves.values()))[0].omega
    shown, w_lo, w_hi = _band_of_interest(omega, natural, forcing)
    inside = (omega >= w_lo) & (omega <= w_hi)
    floor = noise_floor([c[2] for c in curves.values()])
    zero, drawn, phases = [], [], []
    for k, (name, (r, inp, amp)) in enumerate(curves.items()):
        if is_noise(amp, floor):
            zero.append(name)
            continue
        keep = amp > floor
        a1.plot(r.omega, np.where(keep, amp, np.nan), color=f"C{k}", label=name)
        ph = np.degrees(np.unwrap(np.angle(r(output, inp)[keep])))
        phase = np.full(len(r.omega), np.nan)
        phase[keep] = ph
        a2.plot(r.omega, phase, color=f"C{k}")
        sel = keep & ((r.omega >= w_lo) & (r.omega <= w_hi))
        if np.any(sel):
            drawn.append((r.kind, amp[sel]))
            phases.append(phase[sel])
    if w_hi / max(w_lo, 1e-300) >= 10.0:
        a1.set_xscale("log")
    if drawn:
        a1.set_yscale("log")
        lo = min(float(np.min(a)) for _, a in drawn)
        damped = [float(np.max(a)) for kind, a in drawn if kind != "exact"]
        hi = max(float(np.max(a)) for _, a in drawn)
        if damped and hi > 20 * max(damped):
            hi = 20 * max(damped)               # the undamped exact peak is clipped
        a1.set_ylim(max(lo, hi * DYNAMIC_RANGE) / 1.5, hi * 1.5)
        p_lo, p_hi = min(float(np.min(p)) for p in phases), max(float(np.max(p)) for p in phases)
        pad = max(5.0, 0.05 * (p_hi - p_lo))
        a2.set_ylim(p_lo - pad, p_hi + pad)
    else:
        a1.text(0.5, 0.5, "identically zero (below 1e-9 of the input)", transform=a1.transAxes, ha="center")
    plain_axis(a2)
    _mark(a1, shown, forcing=forcing)
    _mark(a2, shown, label=False, forcing=forcing)
    a1.set_xlim(w_lo, w_hi)
    a1.set_ylabel(f"|{output}|" + ("\n" if len(output) > 12 else " ") + f"per unit {input} [{u}]")
    a2.set_ylabel("phase, unwrapped [deg]")
    a2.set_xlabel("forcing frequency omega [rad/s]")
    if zero:
        a1.text(0.01, 0.02, "not drawn (numerical zero): " + "; ".join(zero), transform=a1.transAxes, fontsize=7,
                va="bottom")
    legend_outside(a1)
    notes = []
    if len(shown) > MAX_NAMED_MODES:
        notes.append("natural frequencies\n" + _natural_table(shown))
    above = [w for k, w in natural.items() if k not in shown]
    if above:
        notes.append(f"{len(above)} more mode{'s' * (len(above) > 1)} from {min(above):.3g} to {max(above):.3g} rad/s,\n"
                     "outside what the forcing excites\n(rao_summary.json)")
    if notes:
        a2.text(1.01, 1.0, "\n\n".join(notes), transform=a2.transAxes, fontsize=7, va="top", ha="left",
                family="DejaVu Sans Mono")
    a1.grid(True, which="both", alpha=0.3)
    a2.grid(True, which="both", alpha=0.3)
    fig.suptitle(_wrap(title or f"RAO of {output} for top motion {input}"), fontsize=10)
    save_figure(fig, path, dpi=110)
    return Path(path)


MAX_MODE_PANELS = 6      # mode shapes drawn; every mode is in the table


def _rest_geometry(rest, q_labels):
    """(points (n, 2) m, displacement matrix (2 n, nq)) of the rest shape: node or body positions
    (x right, y down from the mean top) and their linear change per unit generalized coordinate.

    ``rest`` is a :class:`~cablesys.linear.linearization.LinearModel` (its outputs ``node_x[k]``,
    ``node_y[k]`` of a segmented cable, else ``x_b``/``y_b`` of each section, at the operating point
    ``y0`` and through ``Cq``), or a float: the depth of a straight vertical cable, displaced by
    dx = -l phi, dy = u (Wang 1971 e_t = (-sin phi, cos phi) linearized about phi = 0).
    """
    if not hasattr(rest, "output_labels"):
        length = float(rest)
        D = np.zeros((4, len(q_labels)))
        for j, q in enumerate(q_labels):
            D[2, j] = -length if q == "phi" else 0.0
            D[3, j] = 1.0 if q == "u" else 0.0
        return np.array([[0.0, 0.0], [0.0, length]]), D
    out = list(rest.output_labels)
    if "node_x[0]" in out:
        n = sum(1 for o in out if o.startswith("node_x["))
        rows = [(f"node_x[{k}]", f"node_y[{k}]") for k in range(n)]
    else:
        sections = [""] if "x_b" in out and "x_b_1" not in out else sorted(
            {o[3:] for o in out if o.startswith("x_b_") and o[4:].isdigit()}, key=lambda s: int(s[1:]))
        rows = [(f"x_b{s}", f"y_b{s}") for s in sections]
    idx = [out.index(c) for pair in rows for c in pair]
    y0, Cq = np.asarray(rest.y0, float)[idx], np.real(np.asarray(rest.Cq))[idx]
    points = y0.reshape(-1, 2)
    D = Cq
    if "node_x[0]" not in out:                     # the top (origin) first, fixed
        points = np.vstack([[0.0, 0.0], points])
        D = np.vstack([np.zeros((2, Cq.shape[1])), Cq])
    return points, D


def _mode_table(modes, shown: int) -> str:
    """Every mode as monospace text (three column groups beyond 8 modes): number, undamped frequency
    (rad/s), damping ratio, largest coordinate, and whether it is drawn."""
    head = f"{'#':>3} {'omega rad/s':>11} {'zeta':>7}  {'largest':<8}"
    rows = [f"{k + 1:>3} {w:>11.4g} {0.0 if abs(z) < 1e-9 else z:>7.2g}  {d:<8}"
            for k, (w, z, d) in enumerate(zip(modes.omega_undamped, modes.damping_ratio, modes.dominant))]
    per = -(-len(rows) // 3) if len(rows) > 8 else len(rows)
    cols = [rows[i:i + per] for i in range(0, len(rows), per)]
    lines = ["    ".join(head for _ in cols)]
    lines += ["    ".join(c[i] if i < len(c) else " " * len(head) for c in cols) for i in range(per)]
    drawn = "mode 1 drawn above" if shown == 1 else f"modes 1-{shown} drawn above"
    return "\n".join([f"all {len(rows)} modes ({drawn}; zeta: damping ratio, largest: largest coordinate)"] + lines)


def plot_modes(modes, rest, path, title: str = "", *, n_shown: int | None = None, units: str = "SI",
               lines: tuple | None = None, points: dict | None = None) -> Path:
    """Mode shapes about the real rest shape (offset, tow angle) on a bounded grid, and a table of every mode.

    Parameters
    ----------
    modes : Modes
        Undamped modes (:func:`cablesys.linear.modal.modes`), sorted by frequency.
    rest : LinearModel or float
        The linearization the modes come from: its operating point gives the rest shape (nodes of a
        segmented cable, or the body of each section) and ``Cq`` each mode's displacement. A float is
        the depth (m) of a straight vertical cable (phi and u modes only).
    path : str or pathlib.Path
        Output image.
    title : str
        Figure title.
    n_shown : int, optional
        Number of modes drawn, lowest first (default and at most :data:`MAX_MODE_PANELS`); the rest
        are in the table.
    units : str
        "SI" (m) or "fps" (ft) for the positions.
    lines, points : optional
        A system of lines joined at points (:mod:`cablesys.model.system`): the node numbers of each line, drawn
        apart, and {point name: (kind, node number)}, marked by kind (square prescribed, triangle fixed, dot a body
        or junction); default one chain from the top (square) to the body (dot).

    Each drawn displacement is scaled so that its largest point moves 10 % of the rest shape's extent.
    """
    from ..units import output_unit
    plt = _plt()
    f, ul = output_unit("m", units)
    n = len(modes.omega_undamped)
    shown = max(1, min(n, MAX_MODE_PANELS if n_shown is None else n_shown, MAX_MODE_PANELS))
    nodes, D = _rest_geometry(rest, modes.q_labels)
    extent = max(float(np.ptp(nodes[:, 0])), float(np.ptp(nodes[:, 1])), 1e-9)
    marks = (list(points.values()) if points is not None
             else [("prescribed", 0), ("body", len(nodes) - 1)])       # a chain: the top, the last body
    ncol = min(3, shown)
    nrow = -(-shown // ncol)
    table_h = 0.13 * ((n if n <= 8 else -(-n // 3)) + 2) + 0.2      # inches: the table's text lines
    fig = plt.figure(figsize=(3.7 * ncol + 0.6, 3.9 * nrow + table_h + 0.6), constrained_layout=True)
    grid = fig.add_gridspec(nrow + 1, ncol, height_ratios=[3.9] * nrow + [table_h])
    for k in range(shown):
        ax = fig.add_subplot(grid[k // ncol, k % ncol])
        d = (D @ np.real(modes.shapes[:, k])).reshape(-1, 2)
        big = float(np.max(np.hypot(d[:, 0], d[:, 1])))
        d = d * (0.1 * extent / big if big > 0 else 0.0)
        for s, style, name in ((0.0, "k-", "at rest"), (1.0, "C0-", "+ mode"), (-1.0, "C1--", "- mode")):
            p = (nodes + s * d) * f
            for m, seq in enumerate(lines or (range(len(nodes)),)):
                ax.plot(p[list(seq), 0], p[list(seq), 1], style, lw=1.6 if s == 0 else 1.2, label=name if m == 0 else None)
            for kind, j in marks:
                if kind in ("body", "junction"):
                    ax.plot(p[j, 0], p[j, 1], "o", color=style[:2] if s else "k", ms=7 if kind == "body" else 5)
        for kind, j in marks:
            if kind in ("prescribed", "fixed"):
                ax.plot(nodes[j, 0] * f, nodes[j, 1] * f, "ks" if kind == "prescribed" else "k^", ms=5,
                        mfc="k" if kind == "prescribed" else "w")
        ax.invert_yaxis()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"x [{ul}]")
        ax.set_ylabel(f"depth y [{ul}]")
        zeta = float(modes.damping_ratio[k])
        ax.set_title(f"mode {k + 1}: {modes.omega_undamped[k]:.4g} rad/s, zeta {0.0 if abs(zeta) < 1e-9 else zeta:.2g}\n"
                     f"largest: {modes.dominant[k]}", fontsize=9)
        ax.grid(alpha=0.3)
        if k == 0:
            ax.legend(fontsize=7, loc="best")
    ax = fig.add_subplot(grid[nrow, :])
    ax.axis("off")
    ax.text(0.0, 1.0, _mode_table(modes, shown), family="DejaVu Sans Mono", fontsize=7, va="top", ha="left",
                transform=ax.transAxes)
    fig.suptitle(_wrap(title or "mode shapes about the rest shape") + "\n(displacements scaled to 10 % of the cable's "
                 "extent; " + ("square = prescribed, triangle = fixed, dot = body or junction)" if points is not None
                               else "square = top, dot = body)"), fontsize=10)
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


def plot_sea_response(resp, natural: dict, path, title: str = "", forcing: dict | None = None,
                      units: str = "SI") -> Path:
    """The sea spectrum with the motion response spectra (top) and the tension response spectra (bottom)
    of a :class:`~cablesys.linear.sea_response.SeaResponse`; legends give sigma and the most probable
    maximum over the exposure. Responses below 1e-9 of the largest are listed, not drawn."""
    from ..units import output_unit
    plt = _plt()
    fm, um = output_unit("m", units)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    a1.plot(resp.omega, resp.sea * fm**2, "k", lw=1.5, label="sea elevation S(omega)")
    peak = max(float(np.max(v)) for v in resp.spectra.values()) if resp.spectra else 0.0
    zero = []
    for k, (o, S) in enumerate(resp.spectra.items()):
        s = resp.statistics[o]
        tension = is_tension(o)
        f, u = output_unit("N" if tension else (unit_of(o) or "-"), units)
        if is_noise(S, NOISE * peak if tension else NOISE * float(np.max(resp.sea))):
            zero.append(o)
            continue
        (a2 if tension else a1).plot(resp.omega, S * f**2, color=f"C{k}", label=f"{o}: sigma {s['std'] * f:.3g} {u}, "
                                     f"MPM {(s['most_probable_max'] - s['mean']) * f:+.3g} {u} over {resp.exposure:.4g} s")
    for ax in (a1, a2):
        _mark(ax, {k: w for k, w in natural.items() if resp.omega[0] <= w <= resp.omega[-1]}, label=ax is a1,
              forcing={k: w for k, w in (forcing or {}).items() if not k.startswith("sea band")})
        ax.grid(True, alpha=0.3)
    a1.set_ylabel(f"spectral density [{um}^2 s/rad]")
    a2.set_ylabel(f"tension spectral density [{output_unit('N', units)[1]}^2 s/rad]")
    a2.set_xlabel("omega [rad/s]")
    a1.legend(fontsize=7)
    if a2.lines:
        a2.legend(fontsize=7)
    if zero:
        a1.text(0.99, 0.5, "not drawn (numerical zero): " + ", ".join(zero), transform=a1.transAxes, fontsize=7,
                ha="right")
    fig.suptitle(_wrap(title or "response spectra in the sea"), fontsize=10)
    save_figure(fig, path, dpi=110)
    return Path(path)
