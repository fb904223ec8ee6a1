"""Statistics of a run and its verdict against the scene's ``[limits]`` (pure numpy, reads results).

Criteria (each checked only when its limit is given; values over the statistics window):

``peak_tension``     largest tension of any tension output, or of the located snap loads in the window (between
                     samples: they can exceed the sampled maxima), <= working load (SWL, or MBL / safety factor);
``least_tension``    smallest tension >= the least allowed tension;
``slack``            smallest tension >= slack_fraction x static (mean) tension of the same output. With
                     slack_fraction = 0.1 this is the slack-sling criterion of DNV-RP-H103 (April 2011),
                     sec. 4.7.2 for lifts through the splash zone (hydrodynamic load <= 0.9 x the least
                     static weight), applied here to the rope tension. The wording was not available to
                     check with the search tool; the section number and the 0.9 factor are as commonly cited;
``excursion``        largest excursion of the lowest body from its mean, horizontal or vertical;
``daf``              dynamic amplification factor, largest peak / static (mean) tension of a tension output.

margin = (limit - value) / |limit| for upper limits, (value - limit) / |limit| for lower limits
(absolute when the limit is 0): >= 0 passes.

A static analysis (a slack span's element tensions, a towed cable's steady tensions: results with
``static_tensions()``) is judged by :func:`judge` through the same :func:`evaluate`, on the working load and
the least tension only; its scene refuses the limits that need a time run.

The statistics are those of :mod:`cablesys.statistics`; a tension's are never below 0 N (a Gaussian most probable
minimum below 0 is 0 with the slack probability), and the warnings count the same snap loads the verdict reads.
"""

from __future__ import annotations

import re

import numpy as np

from . import statistics as st


def statistics_window(time, limits=None, result=None) -> np.ndarray:
    """Boolean mask of the statistics window: from ``limits.statistics_start`` when given, else the
    window of the run's own summary (the last 5 forcing periods or the last 20 % of the run, after the
    smooth start: :func:`cablesys.profiles.statistics_window`), so summary.json has one window."""
    from .profiles import statistics_window as default_window
    t = np.asarray(time, float)
    start = getattr(limits, "statistics_start", None)
    if start is None:
        start = default_window(t, getattr(result, "window_s", None), getattr(result, "forcing_period_s", None),
                               getattr(result, "ramp_s", 0.0))[0]
    mask = t >= start
    if mask.sum() < 2:
        mask[:] = True
    return mask


_SYSTEM_TENSION = re.compile(r"^line\.[^.]+\.tension_(from|to)$")      # a system's line-end tensions (model/system.py)
_SYSTEM_POINT = re.compile(r"^point\.([^.]+)\.[xyz]$")                  # a system's point coordinates


def tension_labels(labels) -> list[str]:
    """The tension outputs: ``tension_top``/``tension_bottom``... when present, else ``tension*``; a system's
    ``line.NAME.tension_from`` / ``tension_to``."""
    tens = [lbl for lbl in labels if _is_tension(lbl)]
    return tens


def body_labels(labels) -> tuple[str, str] | None:
    """(x, y) labels of the lowest body: ``x_b``/``y_b`` or the highest-numbered ``x_b_k``/``y_b_k``."""
    xs = [lbl for lbl in labels if re.fullmatch(r"x_b(_\d+)?", lbl)]      # positions, not x_b_rate[_k]
    if not xs:
        return None
    x = max(xs, key=lambda s: int(s[4:]) if len(s) > 3 else 0)
    y = "y" + x[1:]
    return (x, y) if y in labels else None


def run_statistics(result, limits=None, free_points=()) -> dict:
    """Time-domain statistics (:func:`cablesys.statistics.time_domain`) of the lowest body's motion (x, y, and z in 3-D) and
    every tension output over the statistics window (tensions never below 0 N, resolutions from
    :data:`cablesys.statistics.FLOORS`); exposure from ``limits.exposure``. A system of lines: the coordinates of its
    bodies and junctions (``free_points``, their names) and every line's end tensions."""
    mask = statistics_window(result.time, limits, result)
    t = result.time[mask]
    exposure = getattr(limits, "exposure", None)
    labels = list(tension_labels(result.labels))
    body = body_labels(result.labels)
    if body:
        sway = "z" + body[0][1:]                 # the lowest body's sway in a 3-D run
        labels = list(body) + ([sway] if sway in result.labels else []) + labels
    labels = [lbl for lbl in result.labels if _SYSTEM_POINT.match(lbl) and _SYSTEM_POINT.match(lbl).group(1)
              in free_points] + labels
    return {lbl: st.time_domain(t, np.asarray(result[lbl])[mask], exposure, floor=st.FLOORS.get(_unit(lbl), 0.0),
                                nonnegative=_is_tension(lbl)) for lbl in labels}


def _is_tension(label: str) -> bool:
    return (label.startswith("tension") and not label.endswith("rate")) or bool(_SYSTEM_TENSION.match(label))


def window_snap_loads(result, limits=None) -> tuple[list, list]:
    """(in the statistics window, before it): the run's snap loads (:meth:`cablesys.results.TimeResult.snap_loads`,
    every model; a record without them: none)."""
    snaps = list(result.snap_loads()) if hasattr(result, "snap_loads") else []
    t = np.asarray(result.time, float)
    t0 = float(t[statistics_window(t, limits, result)][0])
    return [s for s in snaps if s.time >= t0], [s for s in snaps if s.time < t0]


def _where(s) -> str:
    return f"element {s.element}" if getattr(s, "element", None) is not None else f"section {s.section}"


def _upper(value, limit, unit, text):
    m = (limit - value) / abs(limit) if limit else limit - value
    return {"value": float(value), "limit": float(limit), "margin": float(m), "pass": bool(m >= 0),
            "unit": unit, "text": text}


def _lower(value, limit, unit, text):
    m = (value - limit) / abs(limit) if limit else value - limit
    return {"value": float(value), "limit": float(limit), "margin": float(m), "pass": bool(m >= 0),
            "unit": unit, "text": text}


def evaluate(limits, stats: dict, snaps=()) -> dict:
    """The verdict ``{criterion: {value, limit, margin, pass, unit, text}}`` from :func:`run_statistics` (or the
    frequency-domain statistics of :mod:`cablesys.linear.sea_response`), and the located snap loads in the window
    (:func:`window_snap_loads`), which the peak tension includes.

    With ``limits.exposure`` the extremes are the larger of the observed and the most probable
    (Rayleigh) extreme over the exposure. Tension statistics are taken as tensions (never below 0 N,
    :func:`cablesys.statistics.as_tension`) whichever route computed them."""
    if limits is None:
        return {}
    use_mpm = getattr(limits, "exposure", None) is not None
    tens = [k for k in stats if _is_tension(k)]
    stats = {k: st.as_tension(v) if k in tens else v for k, v in stats.items()}

    def hi(s):          # a series without a T_z has no most probable extremes (None): its observed ones
        return max(s["max"], s["most_probable_max"]) if use_mpm and s["most_probable_max"] is not None else s["max"]

    def lo(s):
        return min(s["min"], s["most_probable_min"]) if use_mpm and s["most_probable_min"] is not None else s["min"]

    out = {}
    if tens:
        peak_lbl = max(tens, key=lambda k: hi(stats[k]))
        low_lbl = min(tens, key=lambda k: lo(stats[k]))
        if limits.working_load is not None:
            peak, text = hi(stats[peak_lbl]), peak_lbl
            snap = max(snaps, key=lambda s: s.tension, default=None)
            if snap is not None and snap.tension > peak:
                peak, text = snap.tension, f"snap load at t = {snap.time:.4g} s, {_where(snap)}"
            out["peak_tension"] = _upper(peak, limits.working_load, "N", f"largest tension ({text}) <= working load")
        if limits.least_tension is not None:
            out["least_tension"] = _lower(lo(stats[low_lbl]), limits.least_tension, "N",
                                          f"smallest tension ({low_lbl}) >= least allowed tension")
        if limits.slack_fraction is not None:
            ratios = {k: lo(stats[k]) / stats[k]["mean"] for k in tens if stats[k]["mean"] > 0}
            if ratios:
                k = min(ratios, key=ratios.get)
                out["slack"] = _lower(ratios[k], limits.slack_fraction, "-",
                                      f"smallest / static tension ({k}) >= slack fraction (DNV-RP-H103 slack sling)")
        if limits.max_daf is not None:
            dafs = {k: hi(stats[k]) / stats[k]["mean"] for k in tens if stats[k]["mean"] > 0}
            if dafs:
                k = max(dafs, key=dafs.get)
                out["daf"] = _upper(dafs[k], limits.max_daf, "-", f"peak / static tension ({k}) <= allowed DAF")
    if limits.max_excursion is not None:
        body = [k for k in stats if k.startswith(("x_b", "y_b", "z_b")) or _SYSTEM_POINT.match(k)]
        if body:
            exc = {k: max(hi(stats[k]) - stats[k]["mean"], stats[k]["mean"] - lo(stats[k])) for k in body}
            k = max(exc, key=exc.get)
            out["excursion"] = _upper(exc[k], limits.max_excursion, "m", f"largest excursion of the body ({k}) from its mean")
    return out


def static_statistics(tensions: dict) -> dict:
    """{label: statistics} of static tensions {label: array of N} in the form :func:`evaluate` reads: the largest,
    smallest and mean value over the array (elements along the cable, or one steady value), no spread (std 0)
    and no most probable extremes (nothing varies in time)."""
    out = {}
    for label, values in tensions.items():
        t = np.asarray(values, float)
        out[label] = {"max": float(np.max(t)), "min": float(np.min(t)), "mean": float(np.mean(t)), "std": 0.0,
                      "most_probable_max": None, "most_probable_min": None}
    return out


def judge(result) -> dict:
    """The verdict of a static analysis result against its scene's ``limits`` (:func:`evaluate`, the one
    definition): the largest tension against the working load, the smallest against ``least_tension``.

    A result is static when it offers ``static_tensions()`` (:mod:`cablesys.result_protocol`): a slack span's
    element tensions (:class:`cablesys.slack.SlackAnalysis`, Griffin & Rosenthal 1985), a towed cable's steady
    tensions at the tow point and the drogue (:class:`cablesys.towed.TowedAnalysis`). A time run is judged by
    :func:`report` (statistics over its window). Without limits the verdict is {} (passes vacuously).

    Raises
    ------
    ParameterError
        ``result``: not a static result (its kind and what the verdict reads instead); ``limits.<name>``: a
        limit that needs a time run (slack fraction, excursion, DAF, statistics window, exposure).
    """
    from .errors import ParameterError
    from .scene.limits import static_limits
    tensions = getattr(result, "static_tensions", None)
    if tensions is None:
        raise ParameterError("result", type(result).__name__, "the static verdict reads static_tensions() (a slack "
                             "or towed analysis); judge a time run with cablesys.verdict.report(scene, result)")
    limits = static_limits(getattr(getattr(result, "scene", None), "limits", None))
    return evaluate(limits, static_statistics(tensions()))


def warnings_of(result, limits=None) -> list[str]:
    """Slack and snap-load warnings of a run, every model (Wang 1971 eq. 54 switches; a segmented cable's elements):
    the slack switches and time over the run, and the snap loads in the statistics window (those the verdict's peak
    tension reads) and before it."""
    out = []
    events = result.slack_events()
    n_slack = sum(1 for e in events if e.kind == "slack")
    slack_s = result.time_slack()
    if n_slack or slack_s > 0:
        who = "an element of the cable" if getattr(result, "segmented", False) else "the cable"
        out.append(f"WARNING: {who} went slack {n_slack} times ({slack_s:.3g} s with a slack "
                   f"{'element' if who != 'the cable' else 'section'} in total)")
    inside, before = window_snap_loads(result, limits)
    if inside:
        s = max(inside, key=lambda s: s.tension)
        out.append(f"WARNING: {len(inside)} snap loads in the statistics window; largest {s.tension:.4g} N at "
                   f"t = {s.time:.4g} s ({_where(s)})")
    if before:
        s = max(before, key=lambda s: s.tension)
        out.append(f"WARNING: {len(before)} snap loads before the statistics window (not in the verdict); largest "
                   f"{s.tension:.4g} N at t = {s.time:.4g} s ({_where(s)})")
    return out


def passed(verdict: dict) -> bool:
    """True when every criterion passes (vacuously true without limits)."""
    return all(v["pass"] for v in verdict.values())


def format_table(verdict: dict, scale=None) -> list[str]:
    """Console lines: criterion, value, limit, margin and PASS/FAIL. ``scale(unit) -> (factor, name)``
    converts SI values for display (shown = SI x factor, e.g. :func:`cablesys.units.output_unit`)."""
    if not verdict:
        return ["verdict: no [limits] given"]
    lines = [f"{'criterion':<14} {'value':>12} {'limit':>12} {'margin':>8}  result"]
    for name, v in verdict.items():
        f, u = scale(v["unit"]) if scale else (1.0, v["unit"])
        unit = "" if u == "-" else f" {u}"
        val, lim = v["value"] * f, v["limit"] * f
        lines.append(f"{name:<14} {val:>12.5g} {lim:>12.5g} {v['margin']:>+8.1%}  {'PASS' if v['pass'] else 'FAIL'}"
                     f"{unit and '  [' + unit.strip() + ']'}")
    lines.append("verdict: " + ("PASS" if passed(verdict) else "FAIL"))
    return lines



QUANTITY = {"N": "force_N", "m": "length_m", "rad": "angle_rad", "m/s": "velocity_m_s", "rad/s": "rate_rad_s"}


def _unit(label: str) -> str:
    from .results import unit_of
    return unit_of(label) or ("N" if label.startswith("tension") else "-")


def group_by_quantity(stats: dict) -> dict:
    """{"force_N": {label: ...}, "length_m": {...}}: per-label entries grouped by SI quantity; tension entries as
    tensions (never below 0 N, :func:`cablesys.statistics.as_tension`)."""
    grouped: dict = {}
    for lbl, s in stats.items():
        grouped.setdefault(QUANTITY.get(_unit(lbl), "other"), {})[lbl] = st.as_tension(s) if _is_tension(lbl) else s
    return grouped


def steady_shape(scene, result) -> dict | None:
    """The shape of a steady tow (``environment.system_speed`` != 0 and a top that does not move) at the
    run's last sample, or None for any other run: ``top_tension_N`` (the top section's pull on its top
    point), ``body_depth_m`` (the lowest body's y_b, m below the top point's mean depth, y down) and
    ``layback_m`` (x_s - x_b, m: how far the lowest body trails behind the top point; the system moves in +x),
    with ``body_labels`` the lowest body's (x, y) output labels they are read from."""
    env = getattr(scene, "environment", None)
    labels = list(result.labels)
    body = body_labels(labels)
    tops = sorted(lbl for lbl in labels if re.fullmatch(r"tension_top(_\d+)?", lbl))
    if env is None or env.system_speed == 0.0 or body is None or not tops or "x_s" not in labels:
        return None
    if np.ptp(result["x_s"]) > 0.0 or ("y_s" in labels and np.ptp(result["y_s"]) > 0.0):
        return None
    x_b, y_b = (float(np.asarray(result[k])[-1]) for k in body)
    return {"time_s": float(result.time[-1]), "system_speed_m_s": float(env.system_speed),
            "top_tension_N": float(np.asarray(result[tops[0]])[-1]), "body_depth_m": y_b,
            "layback_m": float(np.asarray(result["x_s"])[-1]) - x_b, "body_labels": list(body)}


def steady_shape_lines(summary: dict, scale=None) -> list[str]:
    """Console lines of a steady tow's shape (the ``steady_shape`` entry of :func:`report`); [] for other runs.
    ``scale(unit) -> (factor, name)`` converts SI values for display, as in :func:`format_table`."""
    shape = summary.get("steady_shape")
    if not shape:
        return []
    sc = scale or (lambda u: (1.0, u))
    (fn, un), (fm, um) = sc("N"), sc("m")
    return [f"steady tow at {shape['system_speed_m_s'] * fm:.4g} {um}/s (t = {shape['time_s']:.4g} s): "
            f"top tension {shape['top_tension_N'] * fn:.5g} {un}, body depth {shape['body_depth_m'] * fm:.5g} {um} "
            f"below the top point, layback {shape['layback_m'] * fm:.5g} {um}"]


def report(scene, result) -> dict:
    """``summary.json`` entries of a run: ``statistics`` grouped by quantity (SI units in the group
    names), ``verdict`` against ``scene.limits``, the slack/snap ``warnings`` and, for a steady tow,
    its ``steady_shape`` (:func:`steady_shape`)."""
    limits = getattr(scene, "limits", None)
    system = getattr(scene, "system", None)
    stats = run_statistics(result, limits, tuple(p.name for p in system.point if p.free) if system is not None else ())
    grouped = group_by_quantity(stats)
    mask = statistics_window(result.time, limits, result)
    window = [float(result.time[mask][0]), float(result.time[mask][-1])]
    out = {"statistics": {"window_s": window, "exposure_s": getattr(limits, "exposure", None) or window[1] - window[0],
                          **grouped},
           "verdict": evaluate(limits, stats, window_snap_loads(result, limits)[0]),
           "warnings": warnings_of(result, limits)}
    shape = steady_shape(scene, result)
    if shape is not None:
        out["steady_shape"] = shape
    return out


def format_statistics(statistics: dict, system: str = "SI") -> list[str]:
    """Console lines of the ``statistics`` entry of :func:`report`, shown in ``system`` (SI or fps)."""
    from .units import output_unit
    lines = []
    if "window_s" in statistics:
        w = statistics["window_s"]
        lines.append(f"statistics over t = {w[0]:.4g} .. {w[1]:.4g} s; most probable extremes for "
                     f"{statistics['exposure_s']:.5g} s")
    lines.append(f"{'output':<18} {'mean':>11} {'std':>10} {'min':>11} {'max':>11} {'MPM max':>11} {'Tz s':>7}")
    for group, rows in statistics.items():
        if not isinstance(rows, dict):
            continue
        f, unit = output_unit(group.split("_", 1)[1].replace("_", "/") if "_" in group else "", system)
        for lbl, s in rows.items():
            lines.append(f"{lbl + ' [' + unit + ']':<18} {s['mean'] * f:>11.5g} {s['std'] * f:>10.4g} "
                         f"{s['min'] * f:>11.5g} {s['max'] * f:>11.5g} {_scaled(s['most_probable_max'], f):>11} "
                         f"{_num(s['zero_upcrossing_period_s']):>7}")
    for group, rows in statistics.items():
        for lbl, s in (rows.items() if isinstance(rows, dict) else ()):
            if isinstance(s, dict) and s.get("note"):
                lines.append(f"note (SI units): {lbl}: {s['note']}")
    return lines


def _num(v) -> str:
    return "-" if v is None else f"{v:.3g}"


def _scaled(v, factor: float) -> str:
    return "-" if v is None else f"{v * factor:.5g}"
