"""The ``cablesys`` command: parses arguments, calls the API, writes files.

Each sub-command lives in the module that owns its analysis and exposes
``register(subparsers)``; this file only wires them together.
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import importlib
import logging
import signal
import sys
import warnings

from .atomic import INTERRUPTS, OutputWriteError, interrupt_handler
from .errors import CablesysError
from .messages import casadi_messages_to_log

# module -> provides register(subparsers); order is the order in --help
COMMAND_MODULES = (
    "cablesys.commands.run",    # run, scene (the model ladder's choice in the time domain)
    "cablesys.slack.cli",       # slack  (Griffin & Rosenthal 1985)
    "cablesys.linear.cli",      # rao    (steady state, linearization, RAOs)
    "cablesys.isolation.cli",      # design (dual-isolation NLP)
    "cablesys.towed.cli",       # towed  (Kennedy & Strahan 1981)
    "cablesys.sweeps.cli",       # sweep  (parameter sweeps of any analysis)
    "cablesys.control.cli",      # control (heave compensation by the winch: optimum, MPC)
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="cablesys",
        description="Dynamics of suspended and towed marine cables (CasADi).")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        importlib.import_module(name).register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    command = "?"
    try:
        with _signals_as_interrupt():          # from the start: a signal while the modules load is noted too
            parser = build_parser()
            args = parser.parse_args(argv)
            command = args.command
            logging.basicConfig(level=logging.INFO if args.verbose else logging.WARNING,
                                format="%(levelname)s %(name)s: %(message)s")
            if not getattr(args, "func", None):
                parser.print_help()
                return 2
            # CasADi's solver warnings (KINSOL retries of a run that succeeds) go to the log unless -v;
            # Python warnings are one clean line each, without the source line
            with casadi_messages_to_log(args.verbose), _warnings_as_lines(command):
                return int(args.func(args) or 0)
    except CablesysError as err:
        print(f"cablesys {command}: error: {err}", file=sys.stderr)
        return int(getattr(err, "exit_code", 2))      # 2: bad input; a failed write (OutputWriteError): 1
    except KeyboardInterrupt:
        print(f"cablesys {command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except OSError as err:          # a full disk met outside the output folder's writers: one line, exit 1
        if err.errno not in DISK_ERRNOS:
            raise
        print(f"cablesys {command}: error: {OutputWriteError(err.filename or '-', err)}", file=sys.stderr)
        return 1


DISK_ERRNOS = (errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EIO)


@contextlib.contextmanager
def _warnings_as_lines(command: str):
    """Each warning while a sub-command runs as one line on stderr, ``cablesys COMMAND: warning: message``, once per
    message (Python's default prints the file, the line number and the source line of the call)."""
    seen: set = set()

    def show(message, category, filename, lineno, file=None, line=None):
        text = " ".join(str(message).split())
        if text not in seen:
            seen.add(text)
            print(f"cablesys {command}: warning: {text}", file=sys.stderr)

    previous = warnings.showwarning
    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = previous


EXIT_INTERRUPTED = 130     # the shell's code for a run stopped by SIGINT (also used for SIGTERM)


@contextlib.contextmanager
def _signals_as_interrupt():
    """SIGINT and SIGTERM go to :func:`cablesys.atomic.interrupt_handler` while a sub-command runs:
    the first raises KeyboardInterrupt (held back while a file or a block of results is half
    written), so the computation stops, what was computed is written and marked ``interrupted``,
    exit 130; repeated signals are noted and do not cut that writing short."""
    previous = {}
    try:
        for sig in (signal.SIGINT, signal.SIGTERM):
            previous[sig] = signal.signal(sig, interrupt_handler)
    except ValueError:          # not the main thread: leave signals alone
        yield
        return
    absorb, INTERRUPTS.absorb_from = INTERRUPTS.absorb_from, INTERRUPTS.count
    try:
        yield
    finally:
        INTERRUPTS.absorb_from = absorb
        for sig, prev in previous.items():
            signal.signal(sig, prev)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
