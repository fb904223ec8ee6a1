"""The ``[limits]`` table: what a run is checked against (see :mod:`cablesys.verdict`).

Every limit is optional; a criterion is checked only when its limit is given.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from ..errors import (
    ParameterError,
    require_nonnegative,
    require_positive,
    require_range,
)
from .fields import spec


@dataclasses.dataclass(frozen=True, kw_only=True)
class Limits:
    """Rope strength, slack, excursion and amplification limits of a lift or tow."""

    minimum_breaking_load: float | None = spec("force", "rope minimum breaking load MBL", None)
    safety_factor: float | None = spec("none", "required MBL / peak tension (with minimum_breaking_load)", None)
    safe_working_load: float | None = spec("force", "largest allowed tension (instead of MBL / safety_factor)", None)
    least_tension: float | None = spec("force", "least allowed tension anywhere in the rope", None)
    slack_fraction: float | None = spec(
        "none", "least tension as a fraction of the static (mean) tension; 0.1 is the slack-sling criterion "
                "dynamic load <= 0.9 x static load of DNV-RP-H103 (2011) for lifts through the splash zone "
                "(as commonly cited; the text itself was not available to check)", None)
    max_excursion: float | None = spec("length", "largest allowed excursion of the (lowest) body from its mean position, "
                                                 "horizontal or vertical", None)
    max_daf: float | None = spec("none", "largest allowed dynamic amplification factor peak / static (mean) tension", None)
    statistics_start: float | None = spec("time", "start of the statistics window (default: the last 5 forcing "
                                                  "periods in the run's second half, after the smooth start)", None)
    exposure: float | None = spec("time", "duration of the operation for the most probable maxima (default: the "
                                          "statistics window); with a longer exposure the verdict uses the larger of "
                                          "the observed and the most probable extreme", None)

    def __post_init__(self):
        for name in ("minimum_breaking_load", "safe_working_load", "max_excursion", "max_daf", "exposure"):
            v = getattr(self, name)
            if v is not None:
                require_positive(f"limits.{name}", v)
        if self.safety_factor is not None:
            require_range("limits.safety_factor", self.safety_factor, 1.0, 100.0)
            if self.minimum_breaking_load is None:
                raise ParameterError("limits.safety_factor", self.safety_factor, "needs limits.minimum_breaking_load")
        if self.slack_fraction is not None:
            require_range("limits.slack_fraction", self.slack_fraction, 0.0, 1.0)
        if self.statistics_start is not None:
            require_nonnegative("limits.statistics_start", self.statistics_start, "s")
        if self.least_tension is not None:
            require_range("limits.least_tension", self.least_tension, -1e12, 1e12)

    @property
    def working_load(self) -> float | None:
        """The largest allowed tension: SWL, else MBL / safety factor, else MBL (N)."""
        if self.safe_working_load is not None:
            return self.safe_working_load
        if self.minimum_breaking_load is not None:
            return self.minimum_breaking_load / (self.safety_factor or 1.0)
        return None

    # limits that need a motion or a time series: a static analysis (a slack span's or a towed cable's
    # steady tensions) has neither
    DYNAMIC_FIELDS: ClassVar[tuple] = ("slack_fraction", "max_excursion", "max_daf", "statistics_start", "exposure")

    def require_static(self, where: str = "limits") -> Limits:
        """These limits, if a static analysis can judge all of them: the working load (peak tension) and
        ``least_tension``; a ParameterError names the first limit that needs a time run (slack fraction,
        excursion, DAF, statistics window, exposure)."""
        for name in self.DYNAMIC_FIELDS:
            value = getattr(self, name)
            if value is not None:
                raise ParameterError(f"{where}.{name}", value,
                                     "needs a time run (statistics of a motion or a tension history); a static "
                                     "analysis is judged on safe_working_load (or minimum_breaking_load / "
                                     "safety_factor) and least_tension only: remove it")
        return self


def static_limits(limits, where: str = "limits") -> Limits | None:
    """``limits`` checked for a static analysis (None, or a :class:`Limits` passing
    :meth:`Limits.require_static`); a ParameterError otherwise."""
    if limits is None:
        return None
    if not isinstance(limits, Limits):
        raise ParameterError(where, limits, "must be a cablesys.scene.limits.Limits (or None)")
    return limits.require_static(where)
