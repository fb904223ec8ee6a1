"""CasADi's console warnings (KINSOL, IPOPT, CVODES flags) routed to logging.

CasADi writes solver warnings such as ``WARNING("Module "KINSol" returned flag
"KIN_LINESEARCH_NONCONV" ...")`` through Python's ``sys.stderr``. A rootfinder that
fails on one starting guess and succeeds on the next is normal for cablesys (the
steady state tries several guesses), so these messages are noise on a run that
succeeds. :func:`casadi_messages_to_log` filters them out of ``sys.stderr`` line by line
and sends them to the ``cablesys.casadi`` logger at DEBUG level; everything else written
to ``sys.stderr`` passes through unchanged. With ``verbose`` nothing is filtered.

The statics call KINSOL from several guesses and keep the best root; a line search that stalls
on one guess (``KIN_LINESEARCH_NONCONV``) is expected there, and CasADi 3.8 prints it through
``casadi_warning`` whatever the rootfinder's ``print_level`` or ``disable_internal_warnings``
(``KinsolInterface::solve``: ``if (flag < KIN_SUCCESS) kinsol_error(..., error_on_fail_)``).
:func:`casadi_warnings_captured` collects those blocks around such calls, from the API as well
as the command, so the caller can name the solver's flags in its own error when the outcome is
a failure, and say nothing when a later guess succeeds.
"""

from __future__ import annotations

import contextlib
import io
import logging
import re
import sys

__all__ = ["casadi_messages_to_log", "casadi_warnings_captured", "kinsol_flags"]

log = logging.getLogger("cablesys.casadi")


class _Filter(io.TextIOBase):
    """A text stream that drops CasADi warning blocks and forwards every other line."""

    def __init__(self, target, sink=None):
        self._target = target
        self._sink = sink or (lambda block: log.debug("%s", block))
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
            self._sink("".join(self._block).strip())
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
def _filtered_stderr(sink=None):
    original = sys.stderr
    filt = _Filter(original, sink)
    sys.stderr = filt
    try:
        yield
    finally:
        sys.stderr = original
        filt.close_filter()


@contextlib.contextmanager
def casadi_warnings_captured():
    """Within the block, CasADi warning blocks written to ``sys.stderr`` are collected, not printed.

    Each block also goes to the ``cablesys.casadi`` logger at DEBUG level; every other line
    written to ``sys.stderr`` passes through unchanged.

    Returns
    -------
    contextmanager
        Yields the list the blocks (str, one per warning) are appended to.
    """
    blocks: list[str] = []

    def sink(block: str) -> None:
        blocks.append(block)
        log.debug("%s", block)

    with _filtered_stderr(sink):
        yield blocks


_FLAG = re.compile(r'returned flag "([A-Z0-9_]+)"')


def kinsol_flags(blocks) -> list[str]:
    """The distinct SUNDIALS return flags (``KIN_LINESEARCH_NONCONV``, ...) named in CasADi warning
    blocks, in order of first appearance."""
    out: list[str] = []
    for block in blocks:
        for flag in _FLAG.findall(block):
            if flag not in out:
                out.append(flag)
    return out


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
    with _filtered_stderr():
        yield
