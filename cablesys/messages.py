"""CasADi's console warnings (KINSOL, IPOPT, CVODES flags) routed to logging.

CasADi writes solver warnings such as ``WARNING("Module "KINSol" returned flag
"KIN_LINESEARCH_NONCONV" ...")`` through Python's ``sys.stderr``. A rootfinder that
fails on one starting guess and succeeds on the next is normal for cablesys (the
steady state tries several guesses), so these messages are noise on a run that
succeeds. :func:`casadi_messages_to_log` filters them out of ``sys.stderr`` line by line
and sends them to the ``cablesys.casadi`` logger at DEBUG level; everything else written
to ``sys.stderr`` passes through unchanged. With ``verbose`` nothing is filtered.
"""

from __future__ import annotations

import contextlib
import io
import logging
import sys

__all__ = ["casadi_messages_to_log"]

log = logging.getLogger("cablesys.casadi")


class _Filter(io.TextIOBase):
    """A text stream that drops CasADi warning blocks and forwards every other line."""

    def __init__(self, target):
        self._target = target
        self._line = ""
        self._block: list[str] | None = None

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        self._line += text
        while "\n" in self._line:
            line, self._line = self._line.split("\n", 1)
            self._emit(line + "\n")
        return len(text)

    def _emit(self, line: str) -> None:
        if self._block is None and line.startswith("CasADi - ") and "WARNING(" in line:
            self._block = []
        if self._block is None:
            self._target.write(line)
            return
        self._block.append(line)
        if line.rstrip().endswith("]") and ".cpp:" in line:     # CasADi closes with [.../file.cpp:NNN]
            log.debug("%s", "".join(self._block).strip())
            self._block = None

    def flush(self) -> None:
        if self._line and self._block is None and not self._line.startswith("CasADi - "):
            self._target.write(self._line)
            self._line = ""
        self._target.flush()

    def close_filter(self) -> None:
        """Forward whatever is left (an unterminated block is forwarded, not lost)."""
        rest = "".join(self._block or []) + self._line
        if rest:
            self._target.write(rest)
        self._block, self._line = None, ""
        self._target.flush()


@contextlib.contextmanager
def casadi_messages_to_log(verbose: bool = False):
    """Within the block, CasADi warning messages on ``sys.stderr`` go to logging (DEBUG).

    Parameters
    ----------
    verbose : bool
        Pass everything through unchanged (``cablesys -v``).

    Returns
    -------
    contextmanager
        Restores ``sys.stderr`` on exit, also on an exception.
    """
    if verbose:
        yield
        return
    original = sys.stderr
    filt = _Filter(original)
    sys.stderr = filt
    try:
        yield
    finally:
        sys.stderr = original
        filt.close_filter()
