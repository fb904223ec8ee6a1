"""A time-domain run as a result (:class:`TimeResult`), with its located slack switches and snap
loads: labelled series, 2-D profiles of a segmented cable, the summary groups over a statistics
window. Follows the protocol of :mod:`cablesys.result_protocol` (re-exported by :mod:`cablesys.results`).
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import ClassVar

import numpy as np

from .result_protocol import ResultBase, unit_of


@dataclasses.dataclass(frozen=True)
class SlackEvent:
    """A located taut/slack switch of one section (Wang 1971 eq. 54)."""

    time: float
    section: int
    kind: str            # "slack" (F_bc fell to TENS) or "taut" (F_bc rose back above TENS)
    rate: float          # dF_bc/dt at the switch (N/s)


@dataclasses.dataclass(frozen=True)
class SnapLoad:
    """The first tension maximum after a section goes taut again (the snap load)."""

    time: float
    section: int
    tension: float       # N


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
    forcing_period_s: float | None = None    # sets the default window: the last 5 periods
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
        """[t0, t1] (s) of the summary statistics: ``window_s``, else the last 5 forcing periods, else
        the last 20 % of the run, after the smooth start (:func:`cablesys.profiles.statistics_window`)."""
        from .profiles import statistics_window
        return statistics_window(self.time, self.window_s, self.forcing_period_s, self.ramp_s)

    def slack_fraction_per_element(self) -> np.ndarray | None:
        """Fraction of the output samples in the statistics window at which each element is slack
        (segmented runs; None otherwise)."""
        if "element_slack" not in self.profiles:
            return None
        return np.mean(self.profiles["element_slack"][self._window_mask()] > 0.5, axis=0)

    def snap_events(self) -> list:
        """Every re-tensioning of every element and the tension peaks after it, located between samples
        (segmented runs, :func:`cablesys.profiles.snap_events`); each entry also names its ``element``."""
        from .profiles import snap_events
        if "element_slack" not in self.profiles:
            return []
        pr = self.profiles
        out = []
        for k in np.nonzero(np.any(pr["element_slack"] > 0.5, axis=0))[0]:
            for ev in snap_events(self.time, pr["element_tension"][:, k], pr["element_tension_rate"][:, k],
                                  pr["element_slack"][:, k] > 0.5):
                out.append({"element": int(k), **ev})
        return out

    def _window_mask(self) -> np.ndarray:
        t0, t1 = self.statistics_window
        eps = 1e-9 * max(1.0, abs(t1))
        return (self.time >= t0 - eps) & (self.time <= t1 + eps)

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
        """``tension``, ``slack``, ``body``, ``model`` and ``window_s`` over the statistics window."""
        mask = self._window_mask()
        if not np.any(mask):                  # a run that failed before the window: report no statistics
            mask = np.ones_like(self.time, dtype=bool)
        t0, t1 = self.statistics_window
        ext = lambda lbl, f: None if lbl is None or not np.any(mask) else float(f(self.data[lbl][mask]))
        top, bottom = self._first("tension_top"), self._last("tension_bottom")
        out = {"window_s": [t0, t1],
               "tension": {"top_min_N": ext(top, np.min), "top_max_N": ext(top, np.max),
                           "bottom_min_N": ext(bottom, np.min), "bottom_max_N": ext(bottom, np.max)}}
        body = {}
        for axis in ("x", "y"):
            lbl = self._last(f"{axis}_b")
            y = self.data[lbl][mask] if lbl and np.any(mask) else None
            body[f"{axis}_amplitude_m"] = None if y is None else 0.5 * float(np.max(y) - np.min(y))
            body[f"{axis}_mean_m"] = None if y is None else float(np.mean(y))
        out["body"] = body
        per_el = self.slack_fraction_per_element()
        if per_el is not None:
            any_slack = np.any(self.profiles["element_slack"][mask] > 0.5, axis=1)
            snaps = [ev for ev in self.snap_events() if t0 <= ev["retension_s"] <= t1]
            peaks = [pk[1] for ev in snaps for pk in ev["peaks"]]
            out["slack"] = {"time_fraction": float(np.mean(any_slack)), "events": len(snaps),
                            "snap_peak_N": max(peaks) if peaks else None,
                            "element_time_fraction": [float(v) for v in per_el]}
        else:
            taut = [e for e in self.events if e.kind == "taut" and t0 <= e.time <= t1]
            peaks = [s.tension for s in self.snaps if t0 <= s.time <= t1]
            out["slack"] = {"time_fraction": self._slack_time_between(t0, t1) / max(t1 - t0, 1e-300),
                            "events": len(taut), "snap_peak_N": max(peaks) if peaks else None}
        info = dict(self.model_info)
        if not info:
            n_el = self.profiles["element_tension"].shape[1] if "element_tension" in self.profiles else None
            info = {"name": "segmented" if n_el else "wang", "segments": n_el or 1}
        out["model"] = info
        return out

    def _slack_time_between(self, t0: float, t1: float) -> float:
        """Time in [t0, t1] during which any section was slack (from the located switches)."""
        intervals, open_at = [], {i: float(self.time[0]) for i in self.initially_slack}
        for ev in self.events:
            if ev.kind == "slack":
                open_at[ev.section] = ev.time
            elif ev.section in open_at:
                intervals.append((open_at.pop(ev.section), ev.time))
        intervals += [(a, float(self.time[-1])) for a in open_at.values()]
        grid = np.linspace(t0, t1, 4001)
        hit = np.zeros(grid.size, bool)
        for a, b in intervals:
            hit |= (grid >= a) & (grid <= b)
        return float(np.mean(hit)) * (t1 - t0)

    def __getitem__(self, label: str) -> np.ndarray:
        try:
            return self.data[label]
        except KeyError:
            raise KeyError(f"{label!r} is not a result series; available: {', '.join(self.data)}") from None

    def steady_amplitude(self, label: str, period: float, n_periods: int = 3) -> float:
        """Half the peak-to-peak of ``label`` over the last ``n_periods`` periods."""
        t = self.time
        if t[-1] - t[0] < n_periods * period * (1 - 1e-9):
            raise ValueError(f"the run lasts {t[-1] - t[0]:.4g} s, shorter than {n_periods} periods of {period:.4g} s")
        y = self[label][t >= t[-1] - n_periods * period - 1e-12]
        return 0.5 * float(np.max(y) - np.min(y))

    def time_slack(self) -> float:
        """Total time any section spent slack, from the located switch times."""
        total, open_at = 0.0, {i: float(self.time[0]) for i in self.initially_slack}
        for ev in self.events:
            if ev.kind == "slack":
                open_at[ev.section] = ev.time
            elif ev.section in open_at:
                total += ev.time - open_at.pop(ev.section)
        return total + sum(self.time[-1] - t0 for t0 in open_at.values())

    def summary(self) -> dict:
        """Numbers for ``summary.json``: extremes, slack time, snap loads, statistics."""
        out = {"scene": self.scene_name, "success": self.success, "message": self.message,
               "t_end_s": float(self.time[-1]), "stats": self.stats,
               "slack_events": [dataclasses.asdict(e) for e in self.events],
               "snap_loads": [dataclasses.asdict(s) for s in self.snaps],
               "time_slack_s": self.time_slack()}
        for lbl, y in self.data.items():
            if lbl.startswith("tension"):
                out[f"{lbl}_min_N"] = float(np.min(y))
                out[f"{lbl}_max_N"] = float(np.max(y))
        out.update(self._statistics_groups())
        return out

    def to_xarray(self):
        """An ``xarray.Dataset`` with dimension ``time`` and units in attributes."""
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
        return ds

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
