"""Scenes to and from TOML (stdlib ``tomllib``), in SI or the report's ft/lb/slug.

A scene file has top-level ``name``, ``units`` ("SI" or "fps": ft, lbf, slug, s) and
``angles``; tables ``[cable]`` and ``[body]`` for one section or ``[[sections]]`` with
``cable``/``body`` sub-tables for a chain; ``[environment]`` (with ``[[environment.waves]]``),
``[[top_motion.x]]``, ``[[top_motion.y]]``, ``[top_motion.series]``, ``[initial]``, ``[numerics]``.
Unknown keys are errors.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

from ..errors import ParameterError
from .components import (Body, Cable, Environment, Initial, Numerics, Section, Sinusoid,
                         TimeSeries, TopMotion, Wave)
from .fields import SI_UNIT, UNIT_SYSTEMS, from_si, to_si
from .scene import Scene

_NESTED = {("environment", "waves"): Wave, ("top_motion", "x"): Sinusoid,
           ("top_motion", "y"): Sinusoid, ("top_motion", "series"): TimeSeries}


def _build(cls, table, where: str, units: str):
    if not isinstance(table, dict):
        raise ParameterError(where, table, "must be a table")
    names = {f.name: f for f in dataclasses.fields(cls)}
    unknown = sorted(set(table) - set(names))
    if unknown:
        raise ParameterError(f"{where}.{unknown[0]}", table[unknown[0]],
                             f"unknown key; allowed keys: {', '.join(names)}")
    kw = {}
    for key, value in table.items():
        f = names[key]
        sub = _NESTED.get((where.split("[")[0].split(".")[-1], key))
        if sub is not None:
            if isinstance(value, list):
                kw[key] = tuple(_build(sub, v, f"{where}.{key}[{i}]", units) for i, v in enumerate(value))
            else:
                kw[key] = _build(sub, value, f"{where}.{key}", units)
        elif isinstance(value, (int, float, list)) and not isinstance(value, bool) and f.metadata.get("dim"):
            if isinstance(value, int) and f.type in ("int", int):
                kw[key] = value
            else:
                try:
                    kw[key] = to_si(value, f.metadata["dim"], units)
                except (TypeError, ValueError):
                    raise ParameterError(f"{where}.{key}", value, "must be a number or a list of numbers") from None
        else:
            kw[key] = value
    try:
        return cls(**kw)
    except ParameterError as err:
        if where not in ("cable", "body") and not err.field.startswith(where):
            raise ParameterError(f"{where}.{err.field.split('.')[-1]}", err.value, err.allowed, err.hint) from None
        raise
    except TypeError as err:  # a missing required field
        raise ParameterError(where, "missing field", str(err).split(":")[-1].strip()) from None


def scene_from_dict(data: dict) -> Scene:
    """Build a validated :class:`Scene` from a parsed TOML document."""
    data = dict(data)
    units = data.pop("units", "SI")
    if units not in UNIT_SYSTEMS:
        raise ParameterError("units", units, f"must be one of {UNIT_SYSTEMS}")
    allowed = {"name", "angles", "cable", "body", "sections", "environment", "top_motion", "initial", "numerics"}
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise ParameterError(unknown[0], data[unknown[0]], f"unknown key; allowed: units, {', '.join(sorted(allowed))}")
    if "sections" in data:
        if "cable" in data or "body" in data:
            raise ParameterError("sections", "given with [cable]/[body]", "use either [cable]+[body] or [[sections]]")
        sections = []
        for i, s in enumerate(data["sections"]):
            extra = sorted(set(s) - {"cable", "body"})
            if extra:
                raise ParameterError(f"sections[{i}].{extra[0]}", s[extra[0]], "unknown key; allowed: cable, body")
            sections.append(Section(cable=_build(Cable, s.get("cable", {}), f"sections[{i}].cable", units),
                                    body=_build(Body, s.get("body", {}), f"sections[{i}].body", units)))
    else:
        for key in ("cable", "body"):
            if key not in data:
                raise ParameterError(key, "missing", f"a scene needs a [{key}] table (or [[sections]])")
        sections = [Section(cable=_build(Cable, data["cable"], "cable", units),
                            body=_build(Body, data["body"], "body", units))]
    kw = dict(name=data.get("name", "scene"), sections=tuple(sections), angles=data.get("angles", "per_section"))
    for key, cls in (("environment", Environment), ("top_motion", TopMotion), ("initial", Initial), ("numerics", Numerics)):
        if key in data:
            kw[key] = _build(cls, data[key], key, units)
    return Scene(**kw)


def load_scene(path: str | Path) -> Scene:
    """Read a scene TOML file."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as err:
        raise ParameterError("scene file", str(path), f"cannot be read ({err.strerror})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ParameterError("scene file", str(path), f"is not valid TOML: {err}") from None
    return scene_from_dict(data)


# ---------------------------------------------------------------- writing
def _fmt(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isinf(v):
            return "-inf" if v < 0 else "inf"
        return repr(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    raise TypeError(type(v))


def _unit_label(dim: str, units: str) -> str:
    if units == "fps":
        return {"length": "ft", "force": "lbf", "mass": "slug", "mass_per_length": "slug/ft",
                "force_per_length": "lbf/ft", "density": "slug/ft^3", "velocity": "ft/s",
                "acceleration": "ft/s^2", "area": "ft^2", "force_time": "lbf s"}.get(dim, SI_UNIT[dim])
    return SI_UNIT[dim]


def _table_lines(obj, header: str, units: str, annotate: bool) -> list[str]:
    lines, subtables = [header], []
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        if v is None:
            if annotate:
                lines.append(f"# {f.name} =   # {f.metadata.get('doc', '')} (unset: default)")
            continue
        if dataclasses.is_dataclass(v) or (isinstance(v, tuple) and v and dataclasses.is_dataclass(v[0])):
            subtables.append((f.name, v))
            continue
        if isinstance(v, tuple) and not v:
            continue
        dim = f.metadata.get("dim", "none")
        if isinstance(v, (int, float)) and not isinstance(v, bool) and not (isinstance(v, int) and f.type in ("int", int)):
            v = from_si(v, dim, units)
        elif isinstance(v, tuple):
            v = from_si(v, dim, units)
        line = f"{f.name} = {_fmt(v)}"
        if annotate:
            line += f"   # [{_unit_label(dim, units)}] {f.metadata.get('doc', '')}"
        lines.append(line)
    lines.append("")
    base = header.strip("[]")
    for name, v in subtables:
        if isinstance(v, tuple):
            for item in v:
                lines += _table_lines(item, f"[[{base}.{name}]]", units, annotate)
        else:
            lines += _table_lines(v, f"[{base}.{name}]", units, annotate)
    return lines


def dump_scene(scene: Scene, *, units: str = "SI", annotate: bool = False) -> str:
    """Write a scene as TOML text (loadable by :func:`load_scene`)."""
    if units not in UNIT_SYSTEMS:
        raise ParameterError("units", units, f"must be one of {UNIT_SYSTEMS}")
    out = []
    if annotate:
        out += ["# cablesys scene. Every value is in the units named by `units`;",
                "# each line's comment gives [unit] and meaning (Wang 1971 notation).", ""]
    out += [f"name = {_fmt(scene.name)}", f"units = {_fmt(units)}",
            f"angles = {_fmt(scene.angles)}" + ("   # per_section | shared (dual isolation)" if annotate else ""), ""]
    if len(scene.sections) == 1:
        out += _table_lines(scene.sections[0].cable, "[cable]", units, annotate)
        out += _table_lines(scene.sections[0].body, "[body]", units, annotate)
    else:
        for s in scene.sections:
            out += ["[[sections]]", ""]
            out += _table_lines(s.cable, "[sections.cable]", units, annotate)
            out += _table_lines(s.body, "[sections.body]", units, annotate)
    for key in ("environment", "top_motion", "initial", "numerics"):
        out += _table_lines(getattr(scene, key), f"[{key}]", units, annotate)
    return "\n".join(out).rstrip() + "\n"
