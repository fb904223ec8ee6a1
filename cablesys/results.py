"""Results of every analysis: the protocol (:mod:`cablesys.result_protocol`) and the time-domain result
(:mod:`cablesys.time_result`), in one namespace.

The protocol lives in :mod:`cablesys.result_protocol`, which imports nothing of the package, and the
time-domain result builds on it; this module imports both, and neither imports this one, so the three
form no import cycle. See :mod:`cablesys.result_protocol` for what a result offers and how to add one.
"""

from .result_protocol import (  # noqa: F401  (re-exports)
    QUANTITIES,
    UNITS,
    AnalysisResult,
    ResultBase,
    annotate,
    long_name_of,
    timed,
    unit_of,
)
from .time_result import SlackEvent, SnapLoad, TimeResult  # noqa: F401  (re-exports)

__all__ = ["QUANTITIES", "UNITS", "AnalysisResult", "ResultBase", "SlackEvent", "SnapLoad", "TimeResult", "annotate",
           "long_name_of", "timed", "unit_of"]
