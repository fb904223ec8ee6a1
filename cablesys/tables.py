"""Typed values and frozen dataclasses from parsed tables (TOML documents, CSV rows).

Generic over a dataclass's fields: the type of each value comes from the field's annotation
(``float``, ``int``, ``str``, ``bool``, a nested dataclass, ``tuple[Item, ...]`` of dataclasses
or ``metadata["item"]``, or a bare ``tuple`` of numbers) and its unit from ``metadata["dim"]``.
Strings and booleans are refused where numbers belong, unknown and missing keys are named.
:mod:`cablesys.reader` reads the files and re-exports these functions.
"""

from __future__ import annotations

import dataclasses
import math
import types
import typing
from collections.abc import Callable

from .errors import ParameterError

__all__ = ["build", "integer", "number", "typed_fields"]


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
    elif where and not (field == where or field.startswith((where + ".", where + "["))):
        field = f"{where}.{field.split('.')[-1]}"
    if field == err.field:
        return err
    return ParameterError(field, err.value, err.allowed, err.hint)
