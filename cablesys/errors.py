"""Errors and input checks shared by every part of cablesys.

Bad input gets a :class:`ParameterError` that names the field, its value and the
allowed range, before any computation starts.
"""

from __future__ import annotations

import math
from typing import Any


class CablesysError(Exception):
    """Base class of cablesys errors."""


class ParameterError(CablesysError, ValueError):
    """An input value outside its allowed range.

    ``str(err)`` reads ``"<field> = <value>: <allowed>"``, e.g.
    ``"cable.length = -3.0: must be > 0 (m)"``; an error read from a file starts with the
    file and line: ``"my.toml, line 7: cable.length = -3.0: must be > 0 (m)"``.
    """

    def __init__(self, field: str, value: Any, allowed: str, hint: str = "", *,
                 file: str | None = None, line: int | None = None):
        self.field, self.value, self.allowed, self.hint = field, value, allowed, hint
        self.file, self.line = file, line
        msg = f"{field} = {_short(value)}: {allowed}"
        if hint:
            msg += f" ({hint})"
        if file:
            msg = f"{file}{f', line {line}' if line else ''}: {msg}"
        super().__init__(msg)

    def __reduce__(self):  # picklable (worker processes) with its keyword arguments
        return (_rebuild, (self.field, self.value, self.allowed, self.hint, self.file, self.line))


def _rebuild(field, value, allowed, hint, file, line):
    return ParameterError(field, value, allowed, hint, file=file, line=line)


def _short(value: Any, limit: int = 200) -> str:
    """``repr(value)``, cut to ``limit`` characters so a huge input does not flood the message."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 20] + f"... ({len(text)} characters)"


class SolverError(CablesysError, RuntimeError):
    """A numerical solver failed on valid input; the message says where, why and what to try.

    The ``cablesys`` command exits with :attr:`exit_code` 1 (a failed computation), not 2
    (which it keeps for bad input).
    """

    exit_code = 1


def require_finite(field: str, value: float) -> float:
    """Return ``float(value)`` or raise if it is not a finite real number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(field, value, "must be a real number") from None
    if not math.isfinite(v):
        raise ParameterError(field, value, "must be finite")
    return v


def require_positive(field: str, value: float, unit: str = "") -> float:
    """A finite number > 0."""
    v = require_finite(field, value)
    if v <= 0.0:
        raise ParameterError(field, value, f"must be > 0{' (' + unit + ')' if unit else ''}")
    return v


def require_nonnegative(field: str, value: float, unit: str = "") -> float:
    """A finite number >= 0."""
    v = require_finite(field, value)
    if v < 0.0:
        raise ParameterError(field, value, f"must be >= 0{' (' + unit + ')' if unit else ''}")
    return v


def require_range(field: str, value: float, lo: float, hi: float, unit: str = "",
                  lo_open: bool = False, hi_open: bool = False) -> float:
    """A finite number within [lo, hi] (ends open when asked)."""
    v = require_finite(field, value)
    bad = (v <= lo if lo_open else v < lo) or (v >= hi if hi_open else v > hi)
    if bad:
        lb = "(" if lo_open else "["
        rb = ")" if hi_open else "]"
        raise ParameterError(field, value, f"must be in {lb}{lo}, {hi}{rb}{' ' + unit if unit else ''}")
    return v


class NumericalWarning(UserWarning):
    """A numerical caveat: the computation goes on, but read its result with care."""
