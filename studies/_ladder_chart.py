"""The work-precision chart of studies/model_ladder.py: error against the reference versus wall time.

Colour is the rung (the quasi-static segmented cable apart from the straight quasi-static rung),
marker the integrator; failed runs are crosses at error = 1 (their wall time up to the failure),
auto's own run (simulate as a user calls it, compiled in full mode, its wall time choose + run +
checks) a black star with its stated estimate as a bar at the same wall time.
"""

from __future__ import annotations

import math
from pathlib import Path

from _common import setup_matplotlib

RUNG_COLOURS = {"frequency": "tab:purple", "quasi-static": "tab:green", "quasi-static N": "tab:olive",
                "wang": "tab:blue", "segmented": "tab:orange"}
RUNG_LABELS = {"frequency": "frequency domain (periodic orbit)", "quasi-static": "quasi-static stretch",
               "quasi-static N": "quasi-static segmented", "wang": "Wang 2-DOF", "segmented": "segmented"}
MARKERS = {"cvodes": "o", "cvodes-adams": "s", "idas": "D", "rk": "^", "rk-stable": "v", "periodic": "P",
           "auto-extrapolated": "h"}
INTEGRATOR_LABELS = {"cvodes": "CVODES BDF", "cvodes-adams": "CVODES Adams", "idas": "IDAS",
                     "rk": "RK4, 10 steps/output", "rk-stable": "RK4 at its stability step",
                     "periodic": "Fourier collocation",
                     "auto-extrapolated": "auto: RK4 at N/4, N/2, N, statistics extrapolated (slack)"}
FORCED = "forced"    # the rungs within the tolerance run as auto runs its own (hollow circles)
FLOOR = 1e-7          # errors below are drawn at the floor
FAIL_Y = 1.0          # failed runs are drawn here


def _marker(integrator: str) -> str:
    """The integrator's marker; auto's own run (``auto (<method> rtol <r>, compiled)``) a hexagon."""
    return MARKERS.get(integrator, "h" if integrator.startswith("auto") else "o")


def _kind(r: dict) -> str:
    return "quasi-static N" if r["rung"] == "quasi-static" and r["segments"] > 1 else r["rung"]


def _reason(failure: str) -> str:
    """The gist of a failure message: 'nonfinite' for an unstable fixed step, else its first clause."""
    if "nonfinite" in failure:
        return "unstable step (nonfinite)"
    return failure.split(":")[0].split("(")[0].strip()[:45]


def _label(r: dict) -> str:
    if r["integrator"] == "auto-extrapolated":          # auto's slack runs: the N of every run
        return "auto: N = " + ", ".join(str(n) for n in r.get("runs", [r["segments"]])) + " extrapolated"
    if r["integrator"] == FORCED:                        # short: its colour says the rung
        return f"N={r['segments']}" if r["rung"] == "segmented" or r["segments"] > 1 else r["rung"]
    return r["rung"] + (f" N={r['segments']}" if r["rung"] == "segmented" or r["segments"] > 1 else "")


def reference_text(res: dict) -> str:
    """The reference in words, for the title."""
    ref = res["reference"]
    if ref.get("kind") == "richardson":
        w = ref.get("window_s") or [0, 0]
        return (f"reference: 1st-order Richardson limit of segmented N = {ref['segments'][0]}, {ref['segments'][1]} "
                f"(RK4), cycle means {w[0]:g}-{w[1]:g} s of a {ref['duration_s']:g} s run")
    return f"reference: segmented N = {ref['segments']} (CVODES), last 5 forcing periods"


LABEL_CLASH = 10      # a label over another text is unreadable; over a marker it only hides part of it
CANDIDATES = ((7, 2, "left"), (7, -11, "left"), (-7, 2, "right"), (-7, -11, "right"), (0, 8, "center"),
              (0, -18, "center"), (12, 14, "left"), (12, -24, "left"), (-12, 14, "right"), (-12, -24, "right"),
              (0, 22, "center"), (0, -32, "center"), (20, 30, "left"), (20, -40, "left"), (-20, 30, "right"),
              (-20, -40, "right"), (0, 40, "center"), (0, -50, "center"), (30, 0, "left"), (-30, 0, "right"))


def _labels(ax, ok: list, key: str, wall, renderer, keep_clear=()) -> None:
    """One label per rung and N, at its fastest run: the first of CANDIDATES offsets whose text box lies
    inside the axes and overlaps no marker and no label already placed (measured on the drawn figure),
    else the inside one with the fewest overlaps; a leader line beyond the first four offsets. ``keep_clear``:
    display boxes no label may cover either (the tolerance's caption, auto's star)."""
    from matplotlib.transforms import Bbox
    pts = ax.transData.transform([(wall(r), max(r[key], FLOOR)) for r in ok])
    r_px = 5.0 * ax.figure.dpi / 72.0
    taken = [Bbox.from_extents(x - r_px, y - r_px, x + r_px, y + r_px) for x, y in pts]
    placed = list(keep_clear)            # text already there: covering it costs LABEL_CLASH markers
    frame = ax.get_window_extent(renderer)
    group = lambda q: (_kind(q), q["integrator"] == FORCED, _label(q))    # one label per rung, N (and forced or not)
    for g in dict.fromkeys(group(q) for q in ok):
        r = min((q for q in ok if group(q) == g), key=wall)
        lab = g[2]
        xy = (wall(r), max(r[key], FLOOR))
        best = None                     # (overlaps, candidate) of the candidates inside the axes
        for i, (dx, dy, ha) in enumerate(CANDIDATES):
            t = _place(ax, lab, xy, r, i, dx, dy, ha)
            box = t.get_window_extent(renderer)
            t.remove()
            inside = frame.contains(box.x0, box.y0) and frame.contains(box.x1, box.y1)
            hits = sum(box.overlaps(b) for b in taken) + LABEL_CLASH * sum(box.overlaps(b) for b in placed)
            if inside and (best is None or hits < best[0]):
                best = (hits, i)
            if inside and hits == 0:
                break
        i = best[1] if best else 0      # nowhere inside: the first offset
        placed.append(_place(ax, lab, xy, r, i, *CANDIDATES[i]).get_window_extent(renderer))


def _place(ax, lab, xy, r, i, dx, dy, ha):
    return ax.annotate(lab, xy, textcoords="offset points", xytext=(dx, dy), ha=ha, fontsize=7.5,
                       color=RUNG_COLOURS[_kind(r)],
                       arrowprops={"arrowstyle": "-", "color": "0.35", "lw": 0.6} if i >= 4 else None)


def plot_case(res: dict, path: Path):
    """One scene's chart: body-amplitude error and tension-extremes error against wall time."""
    plt = setup_matplotlib()
    from matplotlib.lines import Line2D

    from cablesys.plots import save_figure
    fig, axes = plt.subplots(1, 2, figsize=(13, 7.5), sharex=True, layout="constrained")
    captions, star = {}, {}               # boxes the rung labels keep clear of
    ok = [r for r in res["rows"] if r.get("success") and r.get("error_body") is not None]
    bad = [r for r in res["rows"] if not r.get("success")]
    a = res["auto"]
    tol = a["tolerance"]
    hit = [r for r in ok if r["rung"] == a["name"] and r["integrator"] in (a.get("integrator", "cvodes"), "periodic")
           and (r["segments"] == a["segments"] or a["name"] not in ("segmented", "quasi-static"))]
    wall = lambda r: max(r["wall_s"], 1e-4)
    forced = [dict(c, integrator=FORCED, success=True) for c in a.get("candidates") or [] if c.get("error_body") is not None]
    for ax, key, tl, title in ((axes[0], "error_body", tol["body"], "body amplitude error"),
                               (axes[1], "error_tension", tol["tension"], "tension-extremes error")):
        for r in ok:
            ax.loglog(wall(r), max(r[key], FLOOR), _marker(r["integrator"]), color=RUNG_COLOURS[_kind(r)],
                      ms=8, alpha=0.8)
        for r in forced:
            ax.loglog(wall(r), max(r[key], FLOOR), "o", color=RUNG_COLOURS[_kind(r)], mfc="none", ms=9, mew=1.6)
        for r in bad:
            ax.plot(wall(r), FAIL_Y, "x", color=RUNG_COLOURS[_kind(r)], ms=10, mew=2)
        if bad and ax is axes[0]:                # which runs failed, grouped by integrator
            groups, why = {}, {}
            for r in bad:
                k = INTEGRATOR_LABELS.get(r["integrator"], r["integrator"])
                groups.setdefault(k, []).append(_label(r))
                why.setdefault(k, _reason(r.get("failure", "")))
            text = "\n".join(f"failed ({k}): " + ", ".join(v) + f" - {why[k]}" for k, v in groups.items())
            ax.annotate(text, (0.98, FAIL_Y), xycoords=("axes fraction", "data"), xytext=(0, -5),
                        textcoords="offset points", ha="right", va="top", fontsize=7, color="tab:red")
        if hit:
            h = hit[0]
            star[ax] = ax.loglog(wall(h), max(h[key], FLOOR), "*", color="k", ms=20, mfc="none", mew=1.6, zorder=5)[0]
            stated = (a.get("stated_estimate") or {}).get(key.removeprefix("error_"))
            if stated is not None and math.isfinite(stated):   # auto's stated estimate: a bar at the star's wall time
                ax.loglog(wall(h), max(stated, FLOOR), "_", color="k", ms=24, mew=2.5, zorder=5)
        ax.axhline(tl, ls="--", color="grey", lw=1)
        captions[ax] = [ax.annotate(f"tolerance {tl:.0%}", (0.01, tl), xycoords=("axes fraction", "data"),
                                    xytext=(0, 3), textcoords="offset points", fontsize=8, color="grey")]
        ax.axhline(FAIL_Y, ls=":", color="red", lw=0.8)
        stated = (a.get("stated_estimate") or {}).get(key.removeprefix("error_")) if hit else None
        lows = [max(r[key], FLOOR) for r in ok + forced] + [tl] + ([max(stated, FLOOR)] if stated and math.isfinite(stated) else [])
        lo = min(lows) / 4     # room below the lowest point (and auto's stated estimate) for its label
        ax.set_ylim(lo, 2.0)
        ax.set_title(title)
        ax.set_xlabel("wall time [s], build apart")
        ax.set_ylabel("relative error vs reference")
        ax.grid(True, which="both", alpha=0.3)
        xl = ax.get_xlim()
        ax.set_xlim(xl[0] / 2.5, xl[1] * 2.5)     # room for the labels of the fastest and the slowest runs
    kinds = {_kind(r) for r in res["rows"]}
    handles = [Line2D([], [], color=c, marker="o", ls="", label=RUNG_LABELS[k]) for k, c in RUNG_COLOURS.items() if k in kinds]
    handles += [Line2D([], [], color="k", marker=m, ls="", label=INTEGRATOR_LABELS[k]) for k, m in MARKERS.items()
                if any(r["integrator"] == k for r in res["rows"])]
    auto = f"auto's choice: {a['name']}" + (f" N={a['segments']}" if a["name"] in ("segmented",) or a["segments"] > 1 else "")
    how = a.get("integrator", "")          # the slack row's "auto-extrapolated" is in the integrator legend
    how = how.removeprefix("auto ").strip("()") if how.startswith("auto (") else ""
    handles += [Line2D([], [], color="k", marker="*", mfc="none", ls="", ms=12,
                       label=auto + (f" ({how})" if how else "") + ("" if hit else " (not measured)")),
                Line2D([], [], color="k", marker="_", ls="", ms=14, mew=2.5, label="auto's stated estimate"),
                Line2D([], [], color="k", marker="o", mfc="none", ls="", ms=9, mew=1.6,
                       label="rung within tolerance, run as auto runs it"),
                Line2D([], [], color="k", marker="x", ls="", label=f"failed run (drawn at error = {FAIL_Y:g})")]
    handles = [h for h in handles if forced or not h.get_label().startswith("rung within")]
    fig.legend(handles=handles, fontsize=8, loc="outside lower center", ncol=math.ceil(len(handles) / 4))
    mode = "compiled" if a.get("compiled") else "CasADi VM"
    fig.suptitle(f"{res['scene']}: model ladder work-precision\n{reference_text(res)}\nwall time: table runs in CasADi's "
                 f"VM, integration only; auto (star){' and the rungs run as auto runs them (hollow)' if forced else ''}: {mode}, "
                 "choose + run + a posteriori checks", fontsize=10)
    fig.canvas.draw()                    # lay out once, then keep it: labels are placed on the drawn axes
    fig.set_layout_engine("none")
    renderer = fig.canvas.get_renderer()
    for ax, key in zip(axes, ("error_body", "error_tension")):
        clear = [t.get_window_extent(renderer) for t in captions.get(ax, [])]
        clear += [star[ax].get_window_extent(renderer)] if ax in star else []
        _labels(ax, ok + forced, key, wall, renderer, clear)
    return save_figure(fig, path, dpi=110)
