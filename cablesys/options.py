"""Command-line values: numbers and integers checked against their allowed range before any work.

The same error style as the input files (:mod:`cablesys.reader`): a
:class:`~cablesys.errors.ParameterError` naming the option, its value and the allowed range.
"""

from __future__ import annotations

import math

from .errors import ParameterError

__all__ = ["option_number", "option_int"]

def _range_text(lo, hi, lo_open, hi_open) -> str:
    if lo is not None and hi is not None:
        return f"a finite number in {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
    if lo is not None:
        return f"a finite number {'>' if lo_open else '>='} {lo:g}"
    if hi is not None:
        return f"a finite number {'<' if hi_open else '<='} {hi:g}"
    return "a finite number"


def option_number(flag: str, value, *, lo: float | None = None, hi: float | None = None,
                  lo_open: bool = False, hi_open: bool = False, unit: str = "") -> float:
    """Check a command-line number (already parsed by argparse) against its allowed range.

    Parameters
    ----------
    flag : str
        The option as typed (``"--omega-max"``), named in the message.
    value : float
        The parsed value.
    lo, hi : float, optional
        Bounds; open ends when ``lo_open``/``hi_open``.
    lo_open, hi_open : bool
        Exclude the bound itself.
    unit : str
        Unit named in the message.

    Returns
    -------
    float
        ``value`` when it is finite and in range.

    Raises
    ------
    ParameterError
        ``"--flag = value: must be a finite number in [lo, hi] unit"``.
    """
    v = float(value)
    ok = math.isfinite(v)
    ok = ok and (lo is None or (v > lo if lo_open else v >= lo))
    ok = ok and (hi is None or (v < hi if hi_open else v <= hi))
    if not ok:
        raise ParameterError(flag, value, f"must be {_range_text(lo, hi, lo_open, hi_open)}{' ' + unit if unit else ''}")
    return v


def option_int(flag: str, value, *, lo: int, hi: int, why: str = "") -> int:
    """Check a command-line integer against ``[lo, hi]`` (``hi`` is usually a work limit).

    Parameters
    ----------
    flag : str
        The option as typed, named in the message.
    value : int
        The parsed value.
    lo, hi : int
        Inclusive bounds.
    why : str
        Why the bound is there, added to the message.

    Returns
    -------
    int
        ``value`` when in range.

    Raises
    ------
    ParameterError
        ``"--n = 100000000: must be an integer in [2, 20000] (why)"``.
    """
    if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
        raise ParameterError(flag, value, f"must be an integer in [{lo}, {hi}]{' (' + why + ')' if why else ''}")
    return value
