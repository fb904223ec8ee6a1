"""One typed reader for every input file and command-line value of cablesys.

Every loader (Wang scene TOML, slack-cable TOML, ``[design]`` table, towed-run CSV) goes
through this module, so every input is checked the same way before any computation:

* files are decoded as UTF-8 (a byte-order mark, as spreadsheets write it, is accepted);
  anything else is a :class:`~cablesys.errors.ParameterError` naming the file and the byte;
* a TOML table becomes a frozen dataclass by :func:`build` (in :mod:`cablesys.tables`),
  generic over the dataclass's fields: the type of each value comes from the field's
  annotation and its unit from ``metadata["dim"]``; strings and booleans are refused where
  numbers belong, a table where an array of tables belongs and vice versa; unknown and
  missing keys are named;
* errors carry the file and, where it can be found, the line (:class:`SourceMap`);
* command-line numbers are checked in :mod:`cablesys.options` (same error style).

The module sits below the scene layer: it knows dataclasses and units, not cables.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from .errors import ParameterError
from .tables import (  # re-exported: one reader for every input
    build,
    integer,
    number,
    typed_fields,
)

__all__ = [
    "MAX_INPUT_BYTES",
    "SourceMap",
    "build",
    "integer",
    "located",
    "number",
    "read_text",
    "read_toml",
    "typed_fields",
]

MAX_INPUT_BYTES = 64 * 2**20          # an input file larger than 64 MiB is refused, not parsed
_BOM = b"\xef\xbb\xbf"


# ------------------------------------------------------------------------------------ files
def read_text(path: str | Path, what: str = "input file") -> str:
    """The text of ``path`` decoded as UTF-8 (an optional byte-order mark is dropped).

    Parameters
    ----------
    path : str or Path
        The file to read.
    what : str
        What the file is, for messages ("scene file", "RUNS.csv").

    Returns
    -------
    str
        The decoded text.

    Raises
    ------
    ParameterError
        The file cannot be read, is larger than :data:`MAX_INPUT_BYTES`, or is not UTF-8
        (the message gives the byte offset, line and column of the first bad byte).
    """
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > MAX_INPUT_BYTES:
            raise ParameterError(what, str(path), f"is {size} bytes; the limit for an input file is {MAX_INPUT_BYTES}")
        raw = path.read_bytes()
    except OSError as err:
        raise ParameterError(what, str(path), f"cannot be read ({err.strerror or err})") from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        # offset in the file's bytes: utf-8-sig counts from after the byte-order mark
        start = err.start + (len(_BOM) if raw.startswith(_BOM) else 0)
        line = raw[:start].count(b"\n") + 1
        col = start - (raw.rfind(b"\n", 0, start) + 1) + 1
        raise ParameterError(what, str(path),
                             f"is not UTF-8 text: byte {start} (0x{raw[start]:02x}) at line {line}, column {col} "
                             f"cannot be decoded ({err.reason}); save the file as UTF-8") from None


def read_toml(path: str | Path, what: str = "scene file") -> tuple[dict, SourceMap]:
    """Parse a TOML file (stdlib ``tomllib``); returns the document and its :class:`SourceMap`.

    Parameters
    ----------
    path : str or Path
        The TOML file.
    what : str
        What the file is, for messages.

    Returns
    -------
    doc : dict
        The parsed document.
    source : SourceMap
        Where each key of the document was written (file and line), for error messages.

    Raises
    ------
    ParameterError
        Unreadable, non-UTF-8 or invalid TOML (with tomllib's line and column).
    """
    text = read_text(path, what)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(what, str(path), f"is not valid TOML: {err}") from None
    except RecursionError:
        raise ParameterError(what, str(path), "is not valid TOML: nested too deeply") from None
    return doc, SourceMap(text, str(path))


_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?")
_KEY = re.compile(r"^\s*([A-Za-z0-9_\-\.\"' ]+?)\s*=")
_LAST = re.compile(r"(\[\d+\]|\.[^.\[\]]*)$")


class SourceMap:
    """Line numbers of the keys and tables of a TOML text (best effort, for error messages).

    ``line("sections[1].cable.ae")`` is the line of ``ae = ...`` under the second
    ``[[sections]]``' ``[sections.cable]``; an unknown path falls back to its nearest
    enclosing table's header line, or ``None``.

    Parameters
    ----------
    text : str
        The TOML text.
    file : str
        Its file name, for messages.
    """

    def __init__(self, text: str, file: str):
        self.file = file
        self._lines: dict[str, int] = {}
        counts: dict[str, int] = {}
        table = ""
        for n, ln in enumerate(text.splitlines(), start=1):
            m = _HEADER.match(ln)
            if m:
                parts = [p.strip().strip('"').strip("'") for p in m.group(2).split(".")]
                path = ""
                for k, part in enumerate(parts):
                    path = f"{path}.{part}" if path else part
                    if k == len(parts) - 1 and m.group(1) == "[[":
                        counts[path] = counts.get(path, -1) + 1
                        path = f"{path}[{counts[path]}]"
                    elif path in counts:          # inside the latest element of an array of tables
                        path = f"{path}[{counts[path]}]"
                table = path
                self._lines.setdefault(table, n)
                continue
            m = _KEY.match(ln)
            if m:
                key = ".".join(p.strip().strip('"').strip("'") for p in m.group(1).split("."))
                self._lines.setdefault(f"{table}.{key}" if table else key, n)

    def line(self, field: str) -> int | None:
        """Line of ``field`` (a dotted path with ``[i]`` indices), or of its nearest table.

        Parameters
        ----------
        field : str
            E.g. ``"environment.waves[1].length"``.

        Returns
        -------
        int or None
            1-based line number, or None when nothing on the path was found.
        """
        f = field
        while f:
            for key in (f, f + "[0]"):
                if key in self._lines:
                    return self._lines[key]
            f = _LAST.sub("", f) if _LAST.search(f) else ""
        return None


def located(err: ParameterError, source: SourceMap | str | None, line: int | None = None) -> ParameterError:
    """A copy of ``err`` that also names the file (and line) it came from.

    Parameters
    ----------
    err : ParameterError
        The error raised while building from a document.
    source : SourceMap or str or None
        The document's source map, or just a file name; None leaves ``err`` unchanged.
    line : int, optional
        The line, when the caller knows it (CSV rows).

    Returns
    -------
    ParameterError
        ``err`` itself when it already names a file or there is no source.
    """
    if source is None or getattr(err, "file", None):
        return err
    file = source.file if isinstance(source, SourceMap) else str(source)
    if line is None and isinstance(source, SourceMap):
        line = source.line(err.field)
    return ParameterError(err.field, err.value, err.allowed, err.hint, file=file, line=line)
