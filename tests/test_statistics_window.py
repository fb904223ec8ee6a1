"""One statistics window per run: the last 5 forcing periods (else the last 20 %), after the smooth start,
shared by summary.json's groups and the verdict's statistics (issue 11's window_s, issue 13's ramp)."""

import numpy as np

from cablesys.profiles import statistics_window
from cablesys.time_result import TimeResult
from cablesys.verdict import statistics_window as verdict_mask

T = np.linspace(0.0, 60.0, 1201)


def test_last_five_periods_when_they_follow_the_ramp():
    assert statistics_window(T, period=6.0, settled_s=18.0) == (30.0, 60.0)


def test_a_window_never_starts_inside_the_ramp_when_a_period_is_left():
    # 300 m heave at T = 10 s over 60 s with the default 3-period ramp: 5 periods would start at 10 s,
    # inside the ramp (0..30 s); the last 20 % (48 s) is after it
    assert statistics_window(T, period=10.0, settled_s=30.0) == (48.0, 60.0)
    # a ramp over the last 20 % of the run: the window is what follows the ramp
    assert statistics_window(T, period=4.0, settled_s=52.0) == (52.0, 60.0)
    # nothing left after the ramp (less than a period): the last 20 %, the best there is
    assert statistics_window(T, period=10.0, settled_s=55.0) == (48.0, 60.0)


def test_given_window_wins_and_verdict_uses_the_same_window():
    assert statistics_window(T, (5.0, 9.0), period=1.0, settled_s=30.0) == (5.0, 9.0)
    result = TimeResult(time=T, data={"x_b": np.sin(T)}, forcing_period_s=6.0, ramp_s=18.0)
    mask = verdict_mask(T, None, result)
    assert (T[mask][0], T[mask][-1]) == result.statistics_window
