"""Files written safely: a temporary name renamed into place, CSV streamed by blocks, JSON of numpy values.

The pieces :class:`~cablesys.outputs.OutputDir` builds on; usable alone (a study writing one
file, a stream of a long run). A killed process never leaves a torn file under the final name.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import os
import tempfile
from pathlib import Path

import numpy as np

from .results import unit_of

__all__ = ["CsvStream", "atomic_path", "atomic_write_text", "json_dumps"]


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
    """
    path = Path(path)
    fd, name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}", dir=path.parent)
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        with contextlib.suppress(OSError):      # mkstemp makes 0600; give the usual mode
            os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()


class CsvStream:
    """Time series appended block by block to ``<name>.partial.csv``; :meth:`close` renames it.

    The header is ``time [s],label [unit],...`` (the format of
    :meth:`~cablesys.results.TimeResult.to_csv`); every block is flushed, so the file is a
    readable prefix of the run at any time.
    """

    def __init__(self, path, table=None):
        self.path = Path(path)
        self.table = table            # (time, data) -> (header, rows); default: SI columns as below
        self.partial = self.path.with_name(self.path.stem + ".partial" + self.path.suffix)
        self._fh = None
        self._labels = None
        self.rows = 0

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
        if self._fh is None:
            self._labels = list(head)
            self._fh = open(self.partial, "wb", buffering=0)   # noqa: SIM115 (open across blocks; unbuffered)
            self._write(",".join(head) + "\n")
        elif list(head) != self._labels:
            raise ValueError(f"a block with other columns ({head}) than the first ({self._labels})")
        text = io.StringIO()
        np.savetxt(text, block, delimiter=",", fmt="%.10g")
        self._write(text.getvalue())      # whole lines in one write: a killed run leaves no torn row
        self.rows += block.shape[0]

    def _write(self, text: str) -> None:
        data = memoryview(text.encode("utf-8"))
        while data:
            data = data[self._fh.write(data):]

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
        self._fh.close()
        self._fh = None
        os.replace(self.partial, self.path)
        return self.path
