"""A time-domain run as a result (:class:`TimeResult`), with its located slack switches and snap
loads: labelled series, 2-D profiles of a segmented cable, the summary groups over a statistics
window. Follows the protocol of :mod:`cablesys.result_protocol` (re-exported by :mod:`cablesys.results`).
"""

from __future__ import annotations

import dataclasses
import functools
import json
import re
from pathlib import Path
from typing import ClassVar

import numpy as np

from . import statistics as st
from .result_protocol import ResultBase, unit_of


@dataclasses.dataclass(frozen=True)
class SlackEvent:
    """A taut/slack switch of one section (Wang 1971 eq. 54), or of one element of a segmented cable.

    ``section`` is the section's index (0 at the top); None for an element of a segmented cable of several
    sections, whose ``element`` index runs along the whole cable (0 at the top). ``element`` is None for a
    section of the 2-DOF model."""

    time: float          # s: the located switch; an element's: the first output sample in its new state
    section: int | None
    kind: str            # "slack" (F_bc fell to TENS) or "taut" (F_bc rose back above TENS)
    rate: float          # dF_bc/dt at the switch (N/s)
    element: int | None = None


@dataclasses.dataclass(frozen=True)
class SnapLoad:
    """The first tension maximum after a section (or an element of a segmented cable) goes taut again."""

    time: float
    section: int | None  # as in SlackEvent
    tension: float       # N
    element: int | None = None


SETTLED_RTOL = 1e-3     # relative change of the body amplitudes between the window's halves of a settled run


def _union_length(intervals, t0: float = -np.inf, t1: float = np.inf) -> float:
    """Length (s) of the union of the intervals [a, b] clipped to [t0, t1]."""
    total, end = 0.0, -np.inf
    for a, b in sorted((max(a, t0), min(b, t1)) for a, b in intervals):
        if b <= a:
            continue
        if a > end:
            total, end = total + (b - a), b
        elif b > end:
            total, end = total + (b - end), b
    return total


@dataclasses.dataclass(frozen=True, eq=False)
class TimeResult(ResultBase):
    """A time-domain run: labelled series at the output times, events and statistics.

    ``success`` is False when the integrator failed; the series then stop at the last
    output time reached and ``message`` says where and why.
    """

    time: np.ndarray
    data: dict
    success: bool = True
    message: str = ""
    stats: dict = dataclasses.field(default_factory=dict)
    events: tuple = ()
    snaps: tuple = ()
    scene_name: str = ""
    initially_slack: tuple = ()   # sections slack at the first output time
    # profiles along a segmented cable: name -> (time x element | node) array, with the arc lengths
    # element_s / node_s (1-D); labels ``name[k]`` given in ``data`` are moved here
    profiles: dict = dataclasses.field(default_factory=dict)
    window_s: tuple | None = None            # statistics window [t0, t1] (s); None: the default
    forcing_period_s: float | None = None    # sets the default window (cablesys.statistics.window)
    ramp_s: float = 0.0                      # the smooth start (s): a default window starts after it
    model_info: dict = dataclasses.field(default_factory=dict)   # {"name", "segments"} of the model run

    VARIABLES: ClassVar[dict] = {
        "tension_top": ("N", "force of the cable on its top point"),
        "tension_bottom": ("N", "force of the cable on its body"),
        "element_tension": ("N", "element tension"), "element_tension_rate": ("N/s", "element tension rate"),
        "element_strain": ("1", "element strain"), "element_slack": ("1", "element slack flag"),
        "node_x": ("m", "node horizontal position"), "node_y": ("m", "node depth below the mean top"),
        "element_s": ("m", "unstretched arc length of the element mid-point from the top"),
        "node_s": ("m", "unstretched arc length of the node from the top"),
    }

    def __post_init__(self):
        from .profiles import split_profiles
        scalars, profiles = split_profiles(self.data)
        if profiles:
            object.__setattr__(self, "data", scalars)
            object.__setattr__(self, "profiles", {**profiles, **self.profiles})

    @property
    def labels(self) -> tuple:
        return tuple(self.data)

    @property
    def statistics_window(self) -> tuple:
        """[t0, t1] (s) of the summary statistics: ``window_s``, else :func:`cablesys.statistics.window` of the
        run (the last 5 forcing periods, in the second half of the run, after the smooth start)."""
        return tuple(self.statistics_window_chosen[:2])

    @property
    def statistics_window_chosen(self) -> tuple:
        """(t0, t1, how): :attr:`statistics_window` and the rule that set it (text)."""
        if self.window_s is not None:
            return float(self.window_s[0]), float(self.window_s[1]), "given (window_s)"
        return st.window(self.time, self.forcing_period_s, self.ramp_s)

    def window_mask(self) -> np.ndarray:
        """The samples of :attr:`statistics_window` (:func:`cablesys.statistics.window_mask`)."""
        return st.window_mask(self.time, *self.statistics_window)

    @property
    def segmented(self) -> bool:
        """True for a segmented cable's run (element profiles with slack flags)."""
        return "element_slack" in self.profiles

    def _element_rate(self) -> np.ndarray:
        """dT/dt of every element (N/s): the model's output, else the finite difference of the tension."""
        rate = self.profiles.get("element_tension_rate")
        return np.gradient(self.profiles["element_tension"], self.time, axis=0) if rate is None else rate

    def _element_section(self) -> int | None:
        """The section of every element: 0 for a one-section cable, None (unknown here) for several."""
        return 0 if self._n_sections() == 1 else None

    def slack_intervals(self) -> dict:
        """Slack intervals [t_start, t_end] (s) of every section (Wang 1971 eq. 54: from the located switches and
        the sections slack at the first output; a section without a located switch whose tension output reaches
        0 N, as in a model without the switch: from those samples) or, for a segmented cable, of every element
        (from its slack flag), the samples' intervals by :func:`cablesys.statistics.flagged_intervals`; an
        interval still open ends at the last time.

        Returns
        -------
        dict
            ``{("section", i) or ("element", k): [(t_start, t_end), ...]}`` for the sections / elements that went
            slack.
        """
        t = self.time
        if self.segmented:
            flags = self.profiles["element_slack"] > 0.5
            return {("element", int(k)): st.flagged_intervals(t, flags[:, k]) for k in np.nonzero(np.any(flags, axis=0))[0]}
        out, open_at = {}, {i: float(t[0]) for i in self.initially_slack}
        for ev in self.events:
            if ev.kind == "slack":
                open_at[ev.section] = ev.time
            elif ev.section in open_at:
                out.setdefault(("section", ev.section), []).append((open_at.pop(ev.section), ev.time))
        for i, a in open_at.items():
            out.setdefault(("section", i), []).append((a, float(t[-1])))
        switched = {ev.section for ev in self.events} | set(self.initially_slack)
        n = self._n_sections()
        for i in range(n):      # a model without the slack switch (quasi-static, a -inf floor): its tension's samples
            lbl = "tension_mid" + ("" if n == 1 else f"_{i + 1}")
            if i not in switched and lbl in self.data and np.any(self.data[lbl] <= 0.0):
                out[("section", i)] = st.flagged_intervals(t, np.asarray(self.data[lbl]) <= 0.0)
        return out

    def slack_events(self) -> tuple:
        """Every taut/slack switch (:class:`SlackEvent`): the located switches of the sections (``events``), or
        for a segmented cable every change of an element's slack flag, at the first output sample in the new
        state, with the element's dT/dt there (N/s), in time order."""
        return self._slack_events

    @functools.cached_property
    def _slack_events(self) -> tuple:
        if not self.segmented:
            return tuple(self.events)
        flags = self.profiles["element_slack"] > 0.5
        rate = self._element_rate()
        sec = self._element_section()
        i, k = np.nonzero(flags[1:] != flags[:-1])
        i = i + 1
        out = [SlackEvent(time=float(self.time[a]), section=sec, kind="slack" if flags[a, b] else "taut",
                          rate=float(rate[a, b]), element=int(b)) for a, b in zip(i, k)]
        return tuple(sorted(out, key=lambda e: (e.time, e.element)))

    def snap_loads(self) -> tuple:
        """Every snap load (:class:`SnapLoad`): the sections' located ones (``snaps``), or for a segmented cable
        the first tension maximum of an element after each re-tensioning (:meth:`snap_events`), in time order."""
        return self._snap_loads

    @functools.cached_property
    def _snap_loads(self) -> tuple:
        if not self.segmented:
            return tuple(self.snaps)
        sec = self._element_section()
        out = [SnapLoad(time=ev["peaks"][0][0], section=sec, tension=ev["peaks"][0][1], element=ev["element"])
               for ev in self.snap_events() if ev["peaks"]]
        return tuple(sorted(out, key=lambda s: (s.time, s.element)))

    def slack_fraction_per_element(self) -> np.ndarray | None:
        """Fraction of the statistics window during which each element is slack (:meth:`slack_intervals`;
        segmented runs, None otherwise)."""
        if not self.segmented:
            return None
        t0, t1 = self.statistics_window
        ivals = self.slack_intervals()
        n = self.profiles["element_slack"].shape[1]
        return np.array([_union_length(ivals.get(("element", k), ()), t0, t1) for k in range(n)]) / max(t1 - t0, 1e-300)

    def snap_events(self) -> list:
        """Every re-tensioning of every element and the tension peaks after it, located between samples
        (segmented runs, :func:`cablesys.profiles.snap_events`); each entry also names its ``element``."""
        from .profiles import snap_events
        if not self.segmented:
            return []
        pr = self.profiles
        rate = self._element_rate()
        out = []
        for k in np.nonzero(np.any(pr["element_slack"] > 0.5, axis=0))[0]:
            for ev in snap_events(self.time, pr["element_tension"][:, k], rate[:, k], pr["element_slack"][:, k] > 0.5):
                out.append({"element": int(k), **ev})
        return out

    def _last(self, base: str) -> str | None:
        """``base`` or ``base_<n>`` with the largest n (the lowest section), if present."""
        if base in self.data:
            return base
        found = sorted((int(lb.rsplit("_", 1)[1]), lb) for lb in self.data
                       if lb.startswith(base + "_") and lb.rsplit("_", 1)[1].isdigit())
        return found[-1][1] if found else None

    def _first(self, base: str) -> str | None:
        return base if base in self.data else (f"{base}_1" if f"{base}_1" in self.data else None)

    def _statistics_groups(self) -> dict:
        """``tension``, ``slack``, ``body``, ``model`` and ``window_s`` over the statistics window (tensions never
        below 0 N, :mod:`cablesys.statistics`; slack from :meth:`slack_intervals`, :meth:`slack_events` and
        :meth:`snap_loads` for every model). ``body.settled``: the lowest body's x and y (and z in 3-D) amplitudes changed between
        the halves of the window by at most SETTLED_RTOL or 1 micrometre (:func:`cablesys.statistics.settled`);
        ``body.amplitude_change`` the larger relative change."""
        mask = self.window_mask()
        if not np.any(mask):                  # a run that failed before the window: report no statistics
            mask = np.ones_like(self.time, dtype=bool)
        t0, t1, how = self.statistics_window_chosen
        ext = lambda lbl, f: None if lbl is None else max(float(f(self.data[lbl][mask])), 0.0)
        top, bottom = self._first("tension_top"), self._last("tension_bottom")
        out = {"window_s": [t0, t1], "window": {"start_s": t0, "end_s": t1, "how": how},
               "tension": {"top_min_N": ext(top, np.min), "top_max_N": ext(top, np.max),
                           "bottom_min_N": ext(bottom, np.min), "bottom_max_N": ext(bottom, np.max)}}
        body, changes = {}, []
        for axis in ("x", "y", "z"):
            lbl = self._last(f"{axis}_b")
            if axis == "z" and lbl is None:       # a planar run: no sway keys
                continue
            y = self.data[lbl][mask] if lbl else None
            body[f"{axis}_amplitude_m"] = None if y is None else st.half_range(y)
            body[f"{axis}_mean_m"] = None if y is None else float(np.mean(y))
            if y is not None:
                changes.append(st.settled(self.time[mask], y, SETTLED_RTOL, st.FLOORS["m"]))
        body["settled"] = all(ok for ok, _ in changes)
        body["amplitude_change"] = max((c for _, c in changes), default=0.0)
        out["body"] = body
        out["slack"] = self._slack_group(t0, t1)
        info = dict(self.model_info)
        if not info:
            n_el = self.profiles["element_tension"].shape[1] if "element_tension" in self.profiles else None
            info = {"name": "segmented" if n_el else "wang", "segments": n_el or 1}
        out["model"] = info
        return out

    def _slack_group(self, t0: float, t1: float) -> dict:
        """Slack over [t0, t1]: the time (s) and fraction of it any section / element is slack, the top and bottom
        section's / element's fractions, the re-tensionings (``events``), the number and largest of the snap
        loads, and for a segmented cable every element's fraction."""
        span = max(t1 - t0, 1e-300)
        ivals = self.slack_intervals()
        snaps = [s.tension for s in self.snap_loads() if t0 <= s.time <= t1]
        if self.segmented:
            kind, n = "element", self.profiles["element_slack"].shape[1]
        else:
            kind, n = "section", self._n_sections()
        slack_s = _union_length([iv for v in ivals.values() for iv in v], t0, t1)
        out = {"time_fraction": slack_s / span, "time_s": slack_s,
               "top_time_fraction": _union_length(ivals.get((kind, 0), ()), t0, t1) / span,
               "bottom_time_fraction": _union_length(ivals.get((kind, n - 1), ()), t0, t1) / span,
               "events": sum(1 for e in self.slack_events() if e.kind == "taut" and t0 <= e.time <= t1),
               "snap_loads": len(snaps), "snap_peak_N": max(snaps) if snaps else None}
        if self.segmented:
            out["element_time_fraction"] = [float(v) for v in self.slack_fraction_per_element()]
        return out

    def _n_sections(self) -> int:
        """Number of sections (from the section suffixes of the labels)."""
        return max([1] + [int(lb.rsplit("_", 1)[1]) for lb in self.data
                          if lb.startswith(("x_b_", "tension_")) and lb.rsplit("_", 1)[1].isdigit()])

    def __getitem__(self, label: str) -> np.ndarray:
        try:
            return self.data[label]
        except KeyError:
            raise KeyError(f"{label!r} is not a result series; available: {', '.join(self.data)}") from None

    def steady_amplitude(self, label: str, period: float, n_periods: int = 3) -> float:
        """Half the peak-to-peak of ``label`` over the last ``n_periods`` periods (:func:`cablesys.statistics.half_range`)."""
        t = self.time
        if t[-1] - t[0] < n_periods * period * (1 - 1e-9):
            raise ValueError(f"the run lasts {t[-1] - t[0]:.4g} s, shorter than {n_periods} periods of {period:.4g} s")
        return st.half_range(self[label][t >= t[-1] - n_periods * period - 1e-12])

    def time_slack(self) -> float:
        """Total time (s) any section (any element of a segmented cable) was slack over the run
        (:meth:`slack_intervals`)."""
        return _union_length([iv for v in self.slack_intervals().values() for iv in v])

    def summary(self) -> dict:
        """Numbers for ``summary.json``: extremes over the run (tensions never below 0 N), slack events, snap
        loads and slack time of every model (:meth:`slack_events`, :meth:`snap_loads`, :meth:`time_slack`),
        and the statistics groups over the window."""
        out = {"scene": self.scene_name, "success": self.success, "message": self.message,
               "t_end_s": float(self.time[-1]), "stats": self.stats,
               "slack_events": [dataclasses.asdict(e) for e in self.slack_events()],
               "snap_loads": [dataclasses.asdict(s) for s in self.snap_loads()],
               "time_slack_s": self.time_slack()}
        for lbl, y in self.data.items():
            if lbl.startswith("tension") and not lbl.endswith("rate"):   # a rope's tension: never below 0 N
                out[f"{lbl}_min_N"] = max(float(np.min(y)), 0.0)
                out[f"{lbl}_max_N"] = max(float(np.max(y)), 0.0)
        out.update(self._statistics_groups())
        return out

    def to_xarray(self):
        """An ``xarray.Dataset`` with dimension ``time`` and units in attributes; the profiles along the cable with
        ``element`` or ``node``; and every position vector with an ``axis`` dimension (x, y down, z in 3-D): each body's
        ``r_b`` (and ``v_b``, from ``x_b``, ``y_b``, ``z_b`` and their rates; a chain's ``r_b_2``, ...), a rigid body's
        centre of gravity ``r_cg``, and the nodes' ``node_position`` (time, node, axis), beside the series they are
        made of."""
        import xarray as xr
        ds = xr.Dataset({k: ("time", v, {"units": unit_of(k)}) for k, v in self.data.items()},
                        coords={"time": ("time", self.time, {"units": "s"})},
                        attrs={"scene": self.scene_name, "success": int(self.success), "message": self.message,
                               "stats": json.dumps(self.stats)})
        from .profiles import COORDINATES, dimension_of
        for dim, coord in COORDINATES.items():          # profiles: time x element / node, arc length coordinate
            if coord in self.profiles:
                ds = ds.assign_coords({coord: (dim, self.profiles[coord])})
        for name, arr in self.profiles.items():
            if name not in COORDINATES.values():
                ds[name] = (("time", dimension_of(name)), arr)
        return _with_axes(ds, self.data, self.profiles)

    def to_csv(self, path) -> Path:
        """Write ``time`` and every series as CSV columns (SI units in the header)."""
        path = Path(path)
        cols = ["time"] + list(self.data)
        header = ",".join(f"{c} [{unit_of(c) or 's'}]" if c != "time" else "time [s]" for c in cols)
        np.savetxt(path, np.column_stack([self.time] + [self.data[c] for c in self.data]),
                   delimiter=",", header=header, comments="", fmt="%.10g")
        return path

    def to_netcdf(self, path) -> Path:
        """Write a netCDF3 file (scipy backend: no netCDF C library needed)."""
        path = Path(path)
        self.to_xarray().to_netcdf(path, engine="scipy")
        return path


AXES = ("x", "y", "z")


def _with_axes(ds, data: dict, profiles: dict):
    """``ds`` with the position vectors of :meth:`TimeResult.to_xarray` stacked on an ``axis`` dimension (the axes
    the run has: x, y in the plane, x, y, z in 3-D)."""
    axes = AXES if any(re.fullmatch(r"z_b(_\d+)?", k) for k in data) or "node_z" in profiles else AXES[:2]
    out = {}
    for key in data:
        m = re.fullmatch(r"x_(b|cg)(_\d+)?", key)
        if m is None:
            continue
        what, sfx = m.group(1), m.group(2) or ""
        names = [f"{a}_{what}{sfx}" for a in axes]
        if all(n in data for n in names):
            out[f"r_{what}{sfx}"] = (("time", "axis"), np.column_stack([data[n] for n in names]), {"units": "m"})
            rates = [f"{n}_rate" for n in names]
            if all(r in data for r in rates):
                out[f"v_{what}{sfx}"] = (("time", "axis"), np.column_stack([data[r] for r in rates]), {"units": "m/s"})
    nodes = [f"node_{a}" for a in axes]
    if all(n in profiles for n in nodes):
        out["node_position"] = (("time", "node", "axis"), np.stack([profiles[n] for n in nodes], axis=-1),
                                {"units": "m"})
    if not out:
        return ds
    ds = ds.assign_coords(axis=("axis", list(axes), {"long_name": "axis of (x, y, z): right-handed, y down"}))
    for k, v in out.items():
        ds[k] = v
    return ds

