"""Immutable results with labels, success flag, message and statistics (a leaf module)."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

UNITS = {"phi": "rad", "phi_rate": "rad/s", "u": "m", "u_rate": "m/s", "x_b": "m", "x_b_rate": "m/s",
         "y_b": "m", "y_b_rate": "m/s", "tension": "N", "x_s": "m", "y_s": "m"}


def unit_of(label: str) -> str:
    base = label.rsplit("_", 1)[0] if label[-1].isdigit() else label
    return UNITS.get(base, "")


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
class TimeResult:
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

    @property
    def labels(self) -> tuple:
        return tuple(self.data)

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
        return out

    def to_xarray(self):
        """An ``xarray.Dataset`` with dimension ``time`` and units in attributes."""
        import xarray as xr
        ds = xr.Dataset({k: ("time", v, {"units": unit_of(k)}) for k, v in self.data.items()},
                        coords={"time": ("time", self.time, {"units": "s"})},
                        attrs={"scene": self.scene_name, "success": int(self.success), "message": self.message,
                               "stats": json.dumps(self.stats)})
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
