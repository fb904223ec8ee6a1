"""One typed reader for every input file and command-line value of cablesys.

Every loader (Wang scene TOML, slack-cable TOML, ``[design]`` table, towed-run CSV) goes
through this module, so every input is checked the same way before any computation:

* files are decoded as UTF-8 (a byte-order mark, as spreadsheets write it, is accepted);
  anything else is a :class:`~cablesys.errors.ParameterError` naming the file and the byte;
* a TOML table becomes a frozen dataclass by :func:`build`, generic over the dataclass's
  fields: the type of each value comes from the field's annotation (``float``, ``int``,
  ``str``, ``bool``, a nested dataclass, ``tuple[Item, ...]`` of dataclasses or
  ``metadata["item"]``, or a bare ``tuple`` of numbers) and its unit from
  ``metadata["dim"]``; strings and booleans are refused where numbers belong, a table
  where an array of tables belongs and vice versa; unknown and missing keys are named;
* errors carry the file and, where it can be found, the line (:class:`SourceMap`);
* command-line numbers are checked in :mod:`cablesys.options` (same error style).

The module sits below the scene layer: it knows dataclasses and units, not cables.
"""

from __future__ import annotations

import dataclasses
import math
import re
import tomllib
import types
import typing
from pathlib import Path
from typing import Callable

from .errors import ParameterError

__all__ = ["MAX_INPUT_BYTES", "read_text", "read_toml", "SourceMap", "build", "typed_fields", "located",
           "number", "integer"]

MAX_INPUT_BYTES = 64 * 2**20          # an input file larger than 64 MiB is refused, not parsed
_BOM = b"\xef\xbb\xbf"


def _kind(value) -> str:
    """A user's name for the TOML type of ``value``."""
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an array of tables" if value and all(isinstance(v, dict) for v in value) else "an array"
    if isinstance(value, (int, float)):
        return "a number"
    return f"a {type(value).__name__}"


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


def read_toml(path: str | Path, what: str = "scene file") -> tuple[dict, "SourceMap"]:
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


# ------------------------------------------------------------------------ typed values
def number(field: str, value, *, unit: str = "") -> float:
    """A real number from a parsed value: int or float, never a string or a boolean.

    Parameters
    ----------
    field : str
        Dotted name for messages.
    value : object
        The parsed value.
    unit : str
        Unit named in the message.

    Returns
    -------
    float
        ``float(value)`` (range checks belong to the dataclass it feeds).
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(field, value, f"must be a number{' (' + unit + ')' if unit else ''}, not {_kind(value)}")
    try:
        return float(value)
    except OverflowError:
        raise ParameterError(field, value, "is too large for a floating-point number") from None


def integer(field: str, value) -> int:
    """An integer from a parsed value (an integral float such as ``1e3`` is accepted).

    Parameters
    ----------
    field : str
        Dotted name for messages.
    value : object
        The parsed value.

    Returns
    -------
    int
        The integer (bounds belong to the dataclass it feeds).
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(field, value, f"must be an integer, not {_kind(value)}")
    if isinstance(value, float):
        if not (math.isfinite(value) and value.is_integer()):
            raise ParameterError(field, value, "must be an integer")
        return int(value)
    return value


def _numbers(field: str, value, convert: Callable[[float], float]):
    """A (possibly nested) array of numbers as nested tuples of converted floats."""
    if isinstance(value, list):
        return tuple(_numbers(f"{field}[{i}]", v, convert) for i, v in enumerate(value))
    return convert(number(field, value))


# ------------------------------------------------------------------ dataclasses from tables
def _hints(cls) -> dict:
    try:
        return typing.get_type_hints(cls)
    except Exception:  # an annotation that cannot be resolved: fall back to its text
        return {f.name: f.type for f in dataclasses.fields(cls)}


def _strip_optional(tp):
    """``X | None`` -> ``X``; TOML has no null, so None is only ever a default."""
    if typing.get_origin(tp) in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        if len(args) == 1:
            return args[0]
    return tp


def _item_type(tp, f: dataclasses.Field):
    """The dataclass of an array-of-tables field: ``metadata['item']`` or ``tuple[Item, ...]``."""
    item = f.metadata.get("item")
    if item is not None:
        return item
    if typing.get_origin(tp) in (tuple, list):
        args = [a for a in typing.get_args(tp) if a is not Ellipsis]
        if len(args) == 1 and dataclasses.is_dataclass(args[0]):
            return args[0]
    return None


def _required(f: dataclasses.Field) -> bool:
    return f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING


def _join(where: str, key: str) -> str:
    return f"{where}.{key}" if where else key


def _is(tp, kind: type) -> bool:
    return tp is kind or tp == kind.__name__


def _value(f: dataclasses.Field, tp, value, where: str, convert: Callable, nested: Callable):
    """One field's value, typed by its annotation ``tp``."""
    name = _join(where, f.name)
    tp = _strip_optional(tp)
    item = _item_type(tp, f)
    if item is not None:
        if isinstance(value, dict):
            raise ParameterError(name, "one table", f"must be an array of tables: write [[{name}]] (one per item), "
                                 f"not [{name}]")
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise ParameterError(name, value, f"must be an array of tables [[{name}]], not {_kind(value)}")
        return tuple(nested(item, v, f"{name}[{i}]") for i, v in enumerate(value))
    if isinstance(tp, type) and dataclasses.is_dataclass(tp):
        return nested(tp, value, name)
    dim = f.metadata.get("dim", "none")
    if _is(tp, bool):
        if not isinstance(value, bool):
            raise ParameterError(name, value, f"must be true or false, not {_kind(value)}")
        return value
    if _is(tp, int):
        return integer(name, value)
    if _is(tp, float):
        return convert(number(name, value), dim)
    if _is(tp, str):
        if not isinstance(value, str):
            raise ParameterError(name, value, f"must be a string, not {_kind(value)}")
        return value
    if _is(tp, tuple) or typing.get_origin(tp) is tuple:
        if not isinstance(value, list):
            raise ParameterError(name, value, f"must be an array of numbers, not {_kind(value)}")
        return _numbers(name, value, lambda v: convert(v, dim))
    return value          # a type the reader does not know: the dataclass checks it


def typed_fields(cls, table, where: str, *, convert: Callable[[float, str], float] | None = None,
                 skip: tuple = ()) -> dict:
    """The keyword arguments of ``cls`` from ``table``, typed and converted, not yet validated.

    Parameters
    ----------
    cls : type
        A dataclass.
    table : dict
        The parsed table.
    where : str
        Dotted name of the table ("" for the top level of a document).
    convert : callable, optional
        ``convert(value, dim) -> SI value``; identity when omitted.
    skip : tuple of str
        Fields the caller reads itself (neither allowed in ``table`` nor required).

    Returns
    -------
    dict
        ``{field name: typed value}`` for the keys present in ``table``.
    """
    convert = convert or (lambda v, dim: v)
    label = where or "document"
    if isinstance(table, list):
        raise ParameterError(label, f"{len(table)} tables" if all(isinstance(v, dict) for v in table) else table,
                             f"must be one table [{where}], not {_kind(table)}")
    if not isinstance(table, dict):
        raise ParameterError(label, table, f"must be a table [{where}], not {_kind(table)}")
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init and f.name not in skip}
    unknown = sorted(set(table) - set(fields))
    if unknown:
        raise ParameterError(_join(where, unknown[0]), table[unknown[0]],
                             f"unknown key; allowed keys: {', '.join(fields)}")
    missing = [n for n, f in fields.items() if _required(f) and n not in table]
    if missing:
        doc = fields[missing[0]].metadata.get("doc", "")
        raise ParameterError(_join(where, missing[0]), "missing", "is required" + (f": {doc}" if doc else ""))
    hints = _hints(cls)

    def nested(sub, value, name):
        return build(sub, value, name, convert=convert)

    return {key: _value(fields[key], hints.get(key, fields[key].type), value, where, convert, nested)
            for key, value in table.items()}


def build(cls, table, where: str, *, convert: Callable[[float, str], float] | None = None,
          rename: Callable[[str], str] | None = None):
    """An instance of the frozen dataclass ``cls`` from a parsed TOML table.

    Generic over ``cls``'s fields (see :func:`typed_fields`): a field added to a component
    is read without any change here.

    Parameters
    ----------
    cls : type
        A dataclass whose ``__post_init__`` validates ranges.
    table : dict
        The parsed table.
    where : str
        Dotted name of the table for messages (``"sections[1].cable"``).
    convert : callable, optional
        ``convert(value, dim) -> SI value``; identity when omitted.
    rename : callable, optional
        Maps the field names of errors raised by ``cls`` to full dotted names; by default
        a name outside ``where`` (``"waves.length"``) keeps its last part under ``where``.

    Returns
    -------
    object
        The validated instance.

    Raises
    ------
    ParameterError
        Naming the full dotted field, its value and what is allowed.
    """
    kw = typed_fields(cls, table, where, convert=convert)
    try:
        return cls(**kw)
    except ParameterError as err:
        raise _renamed(err, where, rename) from None
    except (TypeError, ValueError, ArithmeticError) as err:   # a check the dataclass did not phrase
        raise ParameterError(where or cls.__name__, {k: table[k] for k in kw}, f"is not valid: {err}") from None


def _renamed(err: ParameterError, where: str, rename) -> ParameterError:
    """The error of a component named from the table it was read from.

    Components name their fields by their own kind (``"cable.ae"``, ``"waves.length"``);
    read from ``sections[1].cable`` or ``environment.waves[2]`` the name gets that path.
    """
    field = err.field
    if rename is not None:
        field = rename(field)
    elif where and not (field == where or field.startswith(where + ".") or field.startswith(where + "[")):
        field = f"{where}.{field.split('.')[-1]}"
    if field == err.field:
        return err
    return ParameterError(field, err.value, err.allowed, err.hint)
