"""Tension extremes and snap peaks located between output samples, by re-integrating the intervals
where they can lie.

A run's outputs are samples: a snap that lasts a fraction of the output step peaks between them, and
the grid's maximum misses it. :func:`refine_extremes` re-runs only the output intervals where the
true extreme can lie, each from the state stored at its start (:attr:`RunRecord.states` keeps the
state at every output time), on a local grid ``FINE`` times finer (a fixed-step method: at its own
steps, one step per local sample, so the local run repeats the run's arithmetic), with the same model,
parameters and integrator settings (a :class:`~cablesys.time_domain.run.Simulator` of the same class, so
the switches inside the interval are located as in the run, :mod:`.events`), and takes the extreme of
the fine samples.

Which intervals (every tension output, its maximum and its minimum, over the run and over the
statistics window):

* every interval whose slack modes differ at its ends, or that holds a located switch or snap load:
  the dynamics change inside it, and its end samples bound nothing;
* the intervals on both sides of the ``TOP`` largest local maxima of the grid;
* every interval whose Lipschitz bound reaches the grid maximum: with ``|dy/dt| <= R`` on an interval
  of length h, y <= (y_a + y_b)/2 + R h/2 inside it (the rise from one end meets the fall to the other),
  with R the largest sample slope ``|dy|/h`` of the interval and its two neighbours. Intervals are
  refined in the order of that bound and the search stops when the next bound is below the best
  refined value (branch and bound) or after ``MAX_INTERVALS`` intervals for that extreme (then
  ``complete`` is False; the intervals already run serve every extreme).

How well a peak is resolved: the gap between the largest fine sample and the vertex of the parabola
through it and its two neighbours (the leading term of the sampling error of a smooth peak, Taylor),
relative to the extreme (or to the run's largest tension, when larger: a minimum near 0 N has no scale of its
own).
The located snap loads of the 2-DOF model (Newton on dF/dt = 0, :meth:`.events.EventLocator._snap`)
are kept as they are; a segmented cable's snap peaks (first element tension maximum after
re-tensioning, located on a Hermite cubic, :func:`cablesys.profiles.snap_events`) are re-estimated as
the largest fine sample of that element over the intervals around the peak.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from ..errors import NumericalWarning
from .integrators import ADAPTIVE

FINE = 64            # samples of an adaptive method's local grid per output interval
TOP = 3              # local maxima of the grid whose neighbouring intervals are always refined
MAX_INTERVALS = 24   # output intervals re-integrated per extreme at most


@dataclasses.dataclass(frozen=True)
class PeakEstimate:
    """The extreme of one tension output: grid value, refined value and how well it is resolved.

    ``key``: the summary entry it replaces (``tension_top_max_N``, ``tension.top_max_N``,
    ``slack.snap_peak_N``); ``grid`` (the summary's value without refinement: the grid's extreme, for a
    segmented snap peak its Hermite estimate) and ``refined`` in N, ``time`` (s) of the refined extreme,
    ``resolution``: how far the refined value may lie below the true extreme, relative to it or to the run's
    largest tension when that is larger (:func:`_resolution`, 1);
    ``complete``: False when the search stopped at :data:`MAX_INTERVALS` with intervals left whose bound
    reaches the refined value.
    """

    key: str
    grid: float
    refined: float
    time: float
    resolution: float
    complete: bool = True


@dataclasses.dataclass(frozen=True)
class Peaks:
    """Every refined extreme of a run and the intervals re-integrated (``intervals``: output indices k of
    the intervals [t_k, t_k+1]; ``failed``: those whose local run failed, left at their grid values)."""

    estimates: tuple
    intervals: tuple
    failed: tuple = ()
    fine: int = FINE

    @property
    def resolution(self) -> float:
        """The largest relative resolution estimate of the extremes (1)."""
        return max((e.resolution for e in self.estimates), default=0.0)

    def apply(self, summary: dict) -> dict:
        """``summary`` (:meth:`TimeResult.summary`) with the refined extremes in place of the grid's (never
        below 0 N, as there), the line ``peaks`` and the details under ``peak_refinement``."""
        out = dict(summary)
        for e in self.estimates:
            group, _, name = e.key.rpartition(".")
            target = out if not group else out.setdefault(group, {})
            if group:
                target = out[group] = dict(target)
            if name in target:
                target[name] = max(e.refined, 0.0)
        complete = all(e.complete for e in self.estimates) and not self.failed
        out["peaks"] = (f"refined between samples (resolution {100 * self.resolution:.2g} %)"
                        + ("" if complete else "; search incomplete, see peak_refinement"))
        out["peak_refinement"] = {
            "fine_per_interval": self.fine, "intervals": len(self.intervals), "failed_intervals": list(self.failed),
            "estimates": [dataclasses.asdict(e) for e in self.estimates]}
        return out


def _is_tension(label: str) -> bool:
    return label.startswith("tension") and not label.endswith("rate")


def _lipschitz_bounds(t, y):
    """Upper bound of y inside every interval, (y_a + y_b)/2 + R h/2, R the largest sample slope of the
    interval and its neighbours."""
    h = np.diff(t)
    s = np.abs(np.diff(y)) / h
    R = s.copy()
    R[1:] = np.maximum(R[1:], s[:-1])
    R[:-1] = np.maximum(R[:-1], s[1:])
    return 0.5 * (y[:-1] + y[1:]) + 0.5 * R * h


def _forced(t, y, switching):
    """Intervals always refined: the switching ones and those next to the TOP largest local maxima of y."""
    n = y.size
    inner = np.nonzero((y[1:-1] >= y[:-2]) & (y[1:-1] >= y[2:]))[0] + 1 if n > 2 else np.array([], int)
    ends = [k for k in (0, n - 1) if n > 1 and (y[k] >= y[1] if k == 0 else y[k] >= y[-2])]
    peaks = np.concatenate([inner, np.array(ends, int)])
    top = peaks[np.argsort(-y[peaks], kind="stable")][:TOP]
    out = set(int(j) for j in np.nonzero(switching)[0])
    for k in top:
        out.update(int(j) for j in (k - 1, k) if 0 <= j < n - 1)
    return out


class PeakRefiner:
    """Fine local runs of one run's output intervals (each run once, kept by its interval index) and the
    extremes they give (:meth:`peaks`); a :class:`RunRecord` holding one reports them in its summary.

    Parameters
    ----------
    simulator : Simulator
        The simulator that ran the record (its class, model and integrator settings are used).
    p : array_like
        The run's parameter vector.
    record : RunRecord
        The run: its output times and the states stored at them (the starting points).
    """

    def __init__(self, simulator, p, record):
        self.model, self._cls = simulator.model, type(simulator)
        settings = simulator.settings
        fixed = not (getattr(settings.custom, "adaptive", True) if settings.custom is not None
                     else settings.method in ADAPTIVE)
        # a fixed-step method: the local grid is the run's own steps (one step per sample), so the local run
        # repeats the run's arithmetic; an adaptive one: FINE samples of its dense output
        self.fine = int(settings.steps_per_output) if fixed else FINE
        self.settings = dataclasses.replace(settings, steps_per_output=1) if fixed else settings
        self.p = np.asarray(p, float)
        self.time, self.states = record.time, record.states
        self.runs, self.failed = {}, []
        self._local = {}            # interval length -> a Simulator over FINE intervals of that length

    def run(self, j: int):
        """The fine local run of interval j ([t_j, t_j+1] from the stored state at t_j), or None if it failed."""
        if j in self.runs:
            return self.runs[j]
        t = self.time
        h = float(t[j + 1] - t[j])
        grid = np.linspace(0.0, h, self.fine + 1)
        key = round(h, 12)
        sim = self._local.get(key)
        if sim is None:       # the run's own class, model and settings; its chunk integrators see only steps
            sim = self._local[key] = self._cls(self.model, t[j] + grid, self.settings)
        sim.times = t[j] + grid            # a uniform grid: the same integrators at any start time
        sim.times[-1] = t[j + 1]
        try:
            with warnings.catch_warnings():        # a fixed-step stability note was the run's own warning
                warnings.simplefilter("ignore", NumericalWarning)
                rec = sim.run(self.p, self.states[:, j])
        except (RuntimeError, FloatingPointError):
            rec = None
        if rec is not None and not (rec.success and rec.time.size == self.fine + 1):
            rec = None
        if rec is None:
            self.failed.append(j)
        self.runs[j] = rec
        return rec

    def peaks(self, record) -> Peaks:
        """The refined extremes of ``record`` (this run, with its current statistics window): :func:`refine_extremes`."""
        if record.states is not self.states:
            raise ValueError("the record is not the run this refiner re-integrates (other states)")
        return _refined(self, record)

    def apply(self, record, summary: dict) -> dict:
        """``summary`` with the refined extremes of ``record`` (:meth:`Peaks.apply`); a record whose states are
        not this run's (a copy with other states) keeps its grid extremes, and its ``peaks`` line says so."""
        if record.states is not self.states:
            return {**summary, "peaks": "maxima of the output samples (the record's states are not the run's "
                                        "that would refine them)"}
        return self.peaks(record).apply(summary)


def attach(record, simulator, p):
    """``record`` holding a :class:`PeakRefiner`: its summary reports the extremes located between samples
    (computed when the summary is first asked for, over the record's statistics window then)."""
    if record.time.size < 2 or record.states.shape[1] != record.time.size:
        return record
    return dataclasses.replace(record, peaks=PeakRefiner(simulator, p, record))


def _end_label(data, base: str, end: int):
    """``base``, else ``base_<n>`` with the smallest (end 0: the top section) or largest n (end -1: the lowest),
    as the summary's ``tension`` group takes them."""
    if base in data:
        return base
    found = sorted((int(lb.rsplit("_", 1)[1]), lb) for lb in data
                   if lb.startswith(base + "_") and lb.rsplit("_", 1)[1].isdigit())
    return found[end][1] if found else None


def _series(rec, label: str):
    """(n,) samples of ``label`` of a run: a labelled series, or ``element_tension[k]`` of its profiles."""
    if label.startswith("element_tension["):
        return rec.profiles["element_tension"][:, int(label[16:-1])]
    return np.asarray(rec.data[label], float)


def _resolution(z, scale: float) -> float:
    """How far the largest fine sample of ``z`` may lie below the peak, relative to ``scale``: the gap to the
    vertex of the parabola through it and its two neighbours (the sampling error of a smooth peak, whose
    leading term is that parabola's; 0 at an end sample, whose neighbouring interval is refined too)."""
    i = int(np.argmax(z))
    if not 0 < i < z.size - 1:
        return 0.0
    y0, y1, y2 = (float(v) for v in z[i - 1:i + 2])
    curv = y0 - 2.0 * y1 + y2
    return (-(y2 - y0) ** 2 / (8.0 * curv) if curv < 0 else 0.0) / scale


def _extreme(ref: PeakRefiner, label: str, sign: float, t, y, mask, switching, key, scale: float):
    """Branch and bound over the intervals of ``mask`` for max(sign * y): a :class:`PeakEstimate`."""
    idx = np.nonzero(mask[:-1] & mask[1:])[0]
    if idx.size == 0:
        return None
    a, b = int(idx[0]), int(idx[-1]) + 2          # the samples of the scope
    z = sign * y
    grid_k = a + int(np.argmax(z[a:b]))
    grid_best = float(z[grid_k])
    bounds = np.full(t.size - 1, -np.inf)
    bounds[a:b - 1] = _lipschitz_bounds(t[a:b], z[a:b])
    forced = {j + a for j in _forced(t[a:b], z[a:b], switching[a:b - 1])}
    rank = lambda j: -max(bounds[j], z[j], z[j + 1])
    order = sorted(forced, key=rank) + sorted((int(j) for j in idx if int(j) not in forced), key=rank)
    best, best_t, res, complete, done = grid_best, float(t[grid_k]), 0.0, True, 0
    for j in order:
        if j not in forced and bounds[j] <= best:
            break                              # no interval left whose bound reaches the refined value
        if done >= MAX_INTERVALS:
            complete = False
            break
        done += 1
        rec = ref.run(j)
        if rec is None:
            continue
        zf = sign * _series(rec, label)
        i = int(np.argmax(zf))
        if zf[i] >= best:
            best, best_t = float(zf[i]), float(rec.time[i])
            res = _resolution(zf, max(scale, abs(best)))
    return PeakEstimate(key=key, grid=sign * grid_best, refined=sign * best, time=best_t, resolution=float(res),
                        complete=complete)


def _switching(record) -> np.ndarray:
    """(n-1,) True for the output intervals where a slack mode or flag changes or a switch / snap lies."""
    t = record.time
    sw = np.zeros(max(t.size - 1, 0), bool)
    M = np.asarray(record.modes)
    if M.size and M.shape[1] == t.size:
        sw |= np.any(M[:, 1:] != M[:, :-1], axis=0)
    flags = record.profiles.get("element_slack")
    if flags is not None:
        f = np.asarray(flags) > 0.5
        sw |= np.any(f[1:] != f[:-1], axis=1)
    for item in (*record.events, *record.snaps):
        j = int(np.searchsorted(t, item.time, side="left")) - 1
        if 0 <= j < sw.size:
            sw[j] = True
    return sw


def refine_extremes(simulator, p, record) -> Peaks:
    """The tension extremes and snap peaks of ``record`` located between its output samples.

    Parameters
    ----------
    simulator : Simulator
        The simulator that ran ``record`` (its model and integrator settings are used).
    p : array_like
        The run's parameter vector.
    record : RunRecord
        The run (its ``states`` at every output time are the starting points).

    Returns
    -------
    Peaks
        For every tension output (labels ``tension*`` that are not rates) its maximum and minimum over
        the run (``<label>_max_N``, ``<label>_min_N``) and over the statistics window (``tension.top_max_N``...),
        and a segmented cable's largest snap peak in the window (``slack.snap_peak_N``).
    """
    if record.time.size < 2 or record.states.shape[1] != record.time.size:
        return Peaks(estimates=(), intervals=())
    return PeakRefiner(simulator, p, record).peaks(record)


def _refined(ref: PeakRefiner, record) -> Peaks:
    t = record.time
    sw = _switching(record)
    everywhere = np.ones(t.size, bool)
    window = record.window_mask()          # the summary's statistics window
    if not np.any(window):                 # a run that failed before the window: its statistics are the run's
        window = everywhere
    out = []
    labels = [lb for lb in record.data if _is_tension(lb)]
    # resolutions relative to the run's largest tension (a minimum near 0 N has no scale of its own)
    scale = max([float(np.max(np.abs(record.data[lb]))) for lb in labels] + [1e-300])
    for lbl in labels:
        y = np.asarray(record.data[lbl], float)
        for sign, kind in ((1.0, "max"), (-1.0, "min")):
            est = _extreme(ref, lbl, sign, t, y, everywhere, sw, f"{lbl}_{kind}_N", scale)
            if est is not None:
                out.append(est)
    top, bottom = _end_label(record.data, "tension_top", 0), _end_label(record.data, "tension_bottom", -1)
    for lbl, end in ((top, "top"), (bottom, "bottom")):
        if lbl is None:
            continue
        y = np.asarray(record.data[lbl], float)
        for sign, kind in ((1.0, "max"), (-1.0, "min")):
            est = _extreme(ref, lbl, sign, t, y, window, sw, f"tension.{end}_{kind}_N", scale)
            if est is not None:
                out.append(est)
    snap = _segmented_snap_peak(ref, record, window)
    if snap is not None:
        out.append(snap)
    return Peaks(estimates=tuple(out), intervals=tuple(sorted(ref.runs)), failed=tuple(sorted(set(ref.failed))),
                 fine=ref.fine)


def _segmented_snap_peak(ref: PeakRefiner, record, window):
    """The largest snap peak of a segmented cable in the window, each peak re-estimated as the largest fine
    sample of its element over the interval holding it and its two neighbours (the 2-DOF model's located
    snap loads need none)."""
    if not record.segmented:
        return None
    t = record.time
    t0, t1 = record.statistics_window
    best = None
    for n_done, s in enumerate(x for x in record.snap_loads() if t0 <= x.time <= t1 and x.element is not None):
        if n_done >= MAX_INTERVALS:
            best = dataclasses.replace(best, complete=False) if best is not None else None
            break
        j = int(np.clip(np.searchsorted(t, s.time) - 1, 0, t.size - 2))
        runs = [r for i in (j - 1, j, j + 1) if 0 <= i < t.size - 1 and (r := ref.run(i)) is not None]
        if not runs:
            continue
        ys = [_series(r, f"element_tension[{s.element}]") for r in runs]
        k = int(np.argmax([np.max(y) for y in ys]))
        y, i = ys[k], int(np.argmax(ys[k]))
        val = float(y[i])
        res = _resolution(y, max(abs(val), 1e-300))
        if best is None or val > best.refined:
            best = PeakEstimate(key="slack.snap_peak_N", grid=float(s.tension), refined=val,
                                time=float(runs[k].time[i]), resolution=float(res))
    return best
