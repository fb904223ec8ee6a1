"""Winch limits of a heave-compensation problem: speed, acceleration, power and tension band.

A limit of ``math.inf`` means unbounded; zero or negative limits are refused (a winch that
cannot move is not a compensation problem). The tension band [floor, working load] (N) comes
from the scene's ``[limits]`` unless given: floor = slack_fraction x static tension (else
``least_tension``, else 0: no slack), working load = SWL or MBL / safety factor.
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import ParameterError


@dataclasses.dataclass(frozen=True)
class WinchLimits:
    """Bounds of the winch and of the cable tension (SI units)."""

    speed: float = math.inf            # |w| (m/s), payout rate
    acceleration: float = math.inf     # |w'| (m/s^2)
    power: float = math.inf            # |T_top w| (W)
    working_load: float | None = None  # largest top tension (N); None: from the scene
    tension_floor: float | None = None  # least spring force F_bc (N); None: from the scene

    def __post_init__(self):
        for name, unit in (("speed", "m/s"), ("acceleration", "m/s^2"), ("power", "W")):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and v > 0) or math.isnan(v):
                raise ParameterError(f"limits.{name}", v, f"must be > 0 ({unit}; math.inf for unbounded)")
        if self.working_load is not None and not self.working_load > 0:
            raise ParameterError("limits.working_load", self.working_load, "must be > 0 (N)")

    def band(self, scene, static_tension: float) -> tuple[float, float]:
        """(floor, working load) in N for ``scene`` whose static top tension is ``static_tension``.

        Raises
        ------
        ParameterError
            When the band does not contain the static tension: no payout can hold the weight.
        """
        lim = scene.limits
        wl = self.working_load if self.working_load is not None else (lim.working_load if lim else None)
        wl = math.inf if wl is None else float(wl)
        if self.tension_floor is not None:
            floor = float(self.tension_floor)
        elif lim is not None and lim.slack_fraction is not None:
            floor = lim.slack_fraction * static_tension
        elif lim is not None and lim.least_tension is not None:
            floor = float(lim.least_tension)
        else:
            floor = 0.0
        if wl <= static_tension:
            raise ParameterError("limits.working_load", wl,
                                 f"must exceed the static top tension {static_tension:.6g} N (the weight hanging "
                                 "at rest): no payout can hold the load")
        if floor >= static_tension:
            raise ParameterError("limits.tension_floor", floor,
                                 f"must be below the static tension {static_tension:.6g} N")
        return floor, wl
