"""Files written safely: a temporary name renamed into place, CSV streamed by blocks, JSON of numpy
values, and interrupts held back while a file is half written.

The pieces :class:`~cablesys.outputs.OutputDir` builds on; usable alone (a study writing one
file, a stream of a long run). A killed process never leaves a torn file under the final name,
a full disk never leaves a torn row in a stream, and a write that fails raises
:class:`OutputWriteError` naming the file and the reason. Only ``kill -9`` can cut a stream's last
row: Linux ends a write at a page boundary when a fatal signal is pending, and no process can hold
that signal back; :func:`read_streamed_csv` reads the whole rows before such a cut.

Interrupts (SIGINT, and SIGTERM under the ``cablesys`` command) are noted in :data:`INTERRUPTS`
by :func:`interrupt_handler`, the handler the ``cablesys`` command installs for both and a
time-domain run installs for SIGINT while it runs (in place of Python's default). Inside
:func:`interrupts_deferred` it only notes the signal; the ``KeyboardInterrupt`` is raised when the
section ends, so a block of rows, a rename or a store of results is done whole or not at all.
(Under another Python handler of the caller's, the signal is raised where it lands, as before.)
"""

from __future__ import annotations

import contextlib
import dataclasses
import errno as _errno
import io
import json
import os
import signal
import tempfile
import time as _time
from pathlib import Path

import numpy as np

from .errors import CablesysError
from .results import unit_of

__all__ = ["INTERRUPTS", "CsvStream", "OutputWriteError", "atomic_path", "atomic_write_text",
           "interrupt_handler", "interrupts_deferred", "json_dumps", "read_streamed_csv"]


class OutputWriteError(CablesysError, OSError):
    """A result file could not be written (full disk, quota, read-only or vanished folder...).

    ``str(err)`` is one line: the file, the system's reason and its errno name, e.g.
    ``"cannot write out/timeseries.nc: No space left on device (ENOSPC); free space on that disk
    or choose another --out"``. ``err.path`` is the file, ``err.errno`` the system's error number.
    The ``cablesys`` command exits with :attr:`exit_code` (1: a failed run, not bad input).
    """

    exit_code = 1

    def __init__(self, path, err: BaseException | None = None, note: str = ""):
        code = getattr(err, "errno", None)
        if code is None and err is not None and disk_full(Path(path).parent):
            code = _errno.ENOSPC            # a library (netCDF, matplotlib) reported the full disk its own way
        reason = os.strerror(code) if code else f"{type(err).__name__}: {err}"
        name = _errno.errorcode.get(code, "") if code else ""
        msg = f"cannot write {path}: {reason}{f' ({name})' if name else ''}"
        if code in (_errno.ENOSPC, _errno.EDQUOT):
            msg += "; free space on that disk or choose another --out"
        if note:
            msg += f"; {note}"
        super().__init__(msg)
        self.path, self.errno, self.strerror = Path(path), code, reason

    def __str__(self) -> str:
        return self.args[0]


def disk_full(folder) -> bool:
    """Whether the file system holding ``folder`` has no free block or no free inode left.

    Parameters
    ----------
    folder : str or Path
        A folder on that file system.

    Returns
    -------
    bool
        False when it cannot be told (the folder is gone).
    """
    try:
        st = os.statvfs(folder)
    except OSError:
        return False
    return st.f_bavail == 0 or (st.f_files > 0 and st.f_favail == 0)


# -- interrupts -----------------------------------------------------------------------------------
class Interrupts:
    """The interrupts this process received, and whether they are held back now.

    Attributes
    ----------
    times : list of float
        ``time.monotonic()`` of every SIGINT/SIGTERM noted (s).
    names : list of str
        Their signal names (``"SIGINT"``...).
    pending : bool
        A signal came inside :func:`interrupts_deferred`; the interrupt is raised when it ends.
    absorb_from : int or None
        When set (by the ``cablesys`` command, which stops at its first signal and must then finish
        writing what it computed), the signals after the first one past this count are noted
        and not raised.
    """

    def __init__(self):
        self.times: list[float] = []
        self.names: list[str] = []
        self.depth = 0
        self.pending = False
        self.absorb_from: int | None = None

    @property
    def count(self) -> int:
        """Number of signals noted so far."""
        return len(self.times)

    def note(self, signum: int) -> None:
        """Record a signal (its time and name)."""
        self.times.append(_time.monotonic())
        try:
            self.names.append(signal.Signals(signum).name)
        except ValueError:
            self.names.append(f"signal {signum}")


INTERRUPTS = Interrupts()


def interrupt_handler(signum, frame) -> None:
    """Signal handler: note the signal in :data:`INTERRUPTS`, then raise ``KeyboardInterrupt``, or hold
    it back inside :func:`interrupts_deferred`, or (``absorb_from``) ignore a repeated signal."""
    INTERRUPTS.note(signum)
    if INTERRUPTS.absorb_from is not None and INTERRUPTS.count > INTERRUPTS.absorb_from + 1:
        with contextlib.suppress(OSError):     # os.write: print() is not reentrant inside a handler
            os.write(2, b"cablesys: interrupt noted; still writing what was computed\n")
        return
    if INTERRUPTS.depth > 0:
        INTERRUPTS.pending = True
        return
    raise KeyboardInterrupt(INTERRUPTS.names[-1])


@contextlib.contextmanager
def interrupts_deferred():
    """Context manager: a signal inside is noted and raised as ``KeyboardInterrupt`` when it ends.

    Nested sections raise at the end of the outermost. When the section ends by another
    exception, that exception goes on and the interrupt stays noted in :data:`INTERRUPTS`.

    Returns
    -------
    contextmanager
    """
    INTERRUPTS.depth += 1
    ok = False
    try:
        yield
        ok = True
    finally:
        INTERRUPTS.depth -= 1
        if INTERRUPTS.depth == 0 and INTERRUPTS.pending:
            INTERRUPTS.pending = False
            if ok:
                raise KeyboardInterrupt(INTERRUPTS.names[-1] if INTERRUPTS.names else "interrupt")


def _default(value):
    """JSON for numpy values and anything else (as text)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, complex):
        return {"real": value.real, "imag": value.imag}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return dataclasses.asdict(value)
    return str(value)


def json_dumps(doc, **kw) -> str:
    """JSON text of ``doc``; numpy arrays and scalars, complex numbers and dataclasses converted.

    Parameters
    ----------
    doc : object
        The document.
    **kw
        Passed to :func:`json.dumps` (``indent``, ``sort_keys``...).

    Returns
    -------
    str
        The JSON text.
    """
    return json.dumps(doc, default=_default, **kw)


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def atomic_write_text(path, text: str) -> Path:
    """Write ``text`` to a temporary file beside ``path`` and rename it into place.

    Parameters
    ----------
    path : str or Path
        Destination.
    text : str
        Content (UTF-8).

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path


@contextlib.contextmanager
def atomic_path(path):
    """Context manager yielding a temporary path beside ``path``, renamed to ``path`` on success.

    Parameters
    ----------
    path : str or Path
        Destination; its suffix is kept so that writers choosing a format by suffix still work.

    Returns
    -------
    contextmanager
        Yields the temporary :class:`~pathlib.Path`; on an exception it is removed.

    Raises
    ------
    OutputWriteError
        The file could not be written or renamed (an ``OSError``, or any error of the writer
        while the disk is full).
    """
    path = Path(path)
    try:
        fd, name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}", dir=path.parent)
    except OSError as err:
        raise OutputWriteError(path, err) from None
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        with contextlib.suppress(OSError):      # mkstemp makes 0600; give the usual mode
            os.chmod(tmp, 0o666 & ~_umask())
        with interrupts_deferred():
            os.replace(tmp, path)
    except OutputWriteError:
        raise
    except OSError as err:
        raise OutputWriteError(path, err) from None
    except Exception as err:
        if disk_full(path.parent):              # the writer's own error for a full disk (netCDF, PNG)
            raise OutputWriteError(path, err) from err
        raise
    finally:
        with contextlib.suppress(OSError):
            tmp.unlink()


def read_streamed_csv(path) -> tuple[list[str], np.ndarray, bool]:
    """The whole rows of a streamed (or finished) time-series CSV: its header, its rows, and whether
    a cut last line (a row without its newline, left by ``kill -9`` during a write) was dropped.

    Parameters
    ----------
    path : str or Path
        A file written by :class:`CsvStream` (``<name>.partial.csv`` or the final name).

    Returns
    -------
    header : list of str
        Column names with units, ``time [s]`` first.
    rows : ndarray, shape (n, len(header))
        The whole rows, in SI or the stream's units.
    cut : bool
        True when a cut last line was dropped.
    """
    text = Path(path).read_bytes().decode("utf-8", errors="replace")
    whole, _, tail = text.rpartition("\n")
    lines = whole.split("\n") if whole else []
    if not lines:
        raise ValueError(f"{path}: no header line")
    header = lines[0].split(",")
    body = [ln for ln in lines[1:] if ln]
    rows = (np.array([[float(v) for v in ln.split(",")] for ln in body]) if body
            else np.zeros((0, len(header))))
    return header, rows.reshape(-1, len(header)), bool(tail)


class CsvStream:
    """Time series appended block by block to ``<name>.partial.csv``; :meth:`close` renames it.

    The header is ``time [s],label [unit],...`` (the format of
    :meth:`~cablesys.results.TimeResult.to_csv`); every block is written whole with interrupts held
    back (:func:`interrupts_deferred`), and a block the disk cannot take is cut off again, so the
    file is a readable prefix of whole rows at any time, except after ``kill -9`` in the middle of a
    block: the kernel may stop that write at a page boundary, leaving a last line without its
    newline (every line that ends is a whole row; :func:`read_streamed_csv` drops the cut one).
    ``rows``, ``t_first`` and ``t_last`` (s) describe what is on disk.
    """

    def __init__(self, path, table=None):
        self.path = Path(path)
        self.table = table            # (time, data) -> (header, rows); default: SI columns as below
        self.partial = self.path.with_name(self.path.stem + ".partial" + self.path.suffix)
        self._fh = None
        self._labels = None
        self.rows = 0
        self.size = 0                 # bytes on disk (whole rows)
        self.t_first = self.t_last = None

    def append(self, time, data: dict) -> None:
        """Append rows: ``time`` (n,) and ``data`` {label: (n,)} (labels fixed by the first block).

        Parameters
        ----------
        time : array_like
            Output times (s).
        data : dict
            Series of the same length.

        Returns
        -------
        None
        """
        if self.table is not None:
            head, block = self.table(time, data)
        else:
            head = ["time [s]"] + [f"{c} [{unit_of(c) or '-'}]" for c in data]
            block = np.column_stack([np.asarray(time, float)] + [np.asarray(v, float) for v in data.values()])
        if self._fh is not None and list(head) != self._labels:
            raise ValueError(f"a block with other columns ({head}) than the first ({self._labels})")
        text = io.StringIO()
        if self._fh is None:
            text.write(",".join(head) + "\n")
        np.savetxt(text, block, delimiter=",", fmt="%.10g")
        data = text.getvalue().encode("utf-8")
        t = np.asarray(time, float)
        with interrupts_deferred():       # the block whole, or (full disk) not at all
            if self._fh is None:
                try:
                    self._fh = open(self.partial, "wb", buffering=0)   # noqa: SIM115 (open across blocks; unbuffered)
                except OSError as err:
                    raise OutputWriteError(self.partial, err) from None
                self._labels = list(head)
            self._write(data)
            self.rows += block.shape[0]
            if t.size:
                self.t_first = float(t[0]) if self.t_first is None else self.t_first
                self.t_last = float(t[-1])

    def _write(self, data: bytes) -> None:
        view = memoryview(data)
        try:
            while view:
                view = view[self._fh.write(view):]
        except OSError as err:
            with contextlib.suppress(OSError):    # cut the torn block off: the file ends with a whole row
                os.ftruncate(self._fh.fileno(), self.size)
                os.lseek(self._fh.fileno(), self.size, os.SEEK_SET)
            raise OutputWriteError(self.partial, err, note=self.kept()) from None
        self.size += len(data)

    def holds(self, time) -> bool:
        """Whether the rows on disk are exactly the output times ``time`` (s): the streamed series of a
        record, so that it need not be written again.

        Parameters
        ----------
        time : array_like
            The record's output times.

        Returns
        -------
        bool
        """
        t = np.asarray(time, float)
        return bool(self.rows == t.size and self.rows and self.t_first == t[0] and self.t_last == t[-1])

    def kept(self) -> str:
        """What the stream holds on disk, in words (for messages)."""
        if not self.rows:
            return f"{self.partial.name} holds no rows"
        name = self.partial.name if self._fh is not None or not self.path.exists() else self.path.name
        return f"{name} holds {self.rows} whole rows, t = {self.t_first:.6g} to {self.t_last:.6g} s"

    def discard(self) -> None:
        """Close and remove the partial file (its rows are written again from a complete result).

        Returns
        -------
        None
        """
        if self._fh is not None:
            self._fh.close()
            self._fh = None
        with contextlib.suppress(FileNotFoundError):
            self.partial.unlink()

    def close(self) -> Path | None:
        """Close and rename the stream to its final name; the final path (None if nothing was written).

        Returns
        -------
        Path or None
        """
        if self._fh is None:
            return None
        with interrupts_deferred():
            self._fh.close()
            self._fh = None
            try:
                os.replace(self.partial, self.path)
            except OSError as err:
                raise OutputWriteError(self.path, err, note=self.kept()) from None
        return self.path
