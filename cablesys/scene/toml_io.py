"""Scenes to and from TOML (stdlib ``tomllib``), in SI or the report's ft/lb/slug.

A scene file has top-level ``name``, ``units`` ("SI" or "fps": ft, lbf, slug, s) and
``angles``; tables ``[cable]`` and ``[body]`` for one section or ``[[sections]]`` with
``cable``/``body`` sub-tables for a chain; ``[environment]`` (with ``[[environment.waves]]``),
``[[top_motion.x]]``, ``[[top_motion.y]]``, ``[top_motion.series]``, ``[initial]``, ``[numerics]``,
and optionally ``[anchor]`` (x, y) and ``[seabed]`` (depth, slope_deg, stiffness, damping, friction_axial,
friction_lateral, friction_speed) and ``[winch]`` (speed, start, duration, ramp, max_length: the
first section's payout, :class:`~cablesys.scene.ends.Winch`; or start, ramp, max_length and ``[[winch.leg]]``
tables of speed and duration: payout, hold, haul-in).
Instead of ``[cable]``/``[body]`` or ``[[sections]]`` a scene may describe a cable system: ``[[point]]`` tables (name,
kind, position, and a body's or junction's body fields in the same table) and ``[[line]]`` tables (name, ``from``,
``to`` and ``[[line.section]]`` cable tables), :mod:`cablesys.scene.system`.
Unknown keys are errors.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from ..errors import ParameterError
from ..reader import SourceMap, build, located, read_toml, typed_fields
from .body import Body
from .components import Cable, Section
from .fields import SI_UNIT, UNIT_SYSTEMS, from_si, to_si
from .scene import Scene
from .system import Line, Point, System

# top-level keys read as tables/values of Scene's own fields (generic: a new Scene field is read too); the system is
# read from [[point]] and [[line]]
_SCENE_FIELDS = {f.name: f for f in dataclasses.fields(Scene) if f.init and f.name not in ("sections", "system")}
_POINT_KEYS = tuple(f.name for f in dataclasses.fields(Point) if f.name != "body")
_BODY_KEYS = tuple(f.name for f in dataclasses.fields(Body))
_LINE_KEYS = ("name", "from", "to", "section")


def _converter(units: str):
    def convert(value: float, dim: str) -> float:
        return to_si(value, dim, units)
    return convert


def scene_from_dict(data: dict, source: SourceMap | str | None = None) -> Scene:
    """Build a validated :class:`Scene` from a parsed TOML document.

    Parameters
    ----------
    data : dict
        The parsed document (see the module docstring for its tables).
    source : SourceMap or str, optional
        Where the document came from; errors then name the file and line.

    Returns
    -------
    Scene
        The frozen scene in SI.

    Raises
    ------
    ParameterError
        Naming the field (``sections[1].cable.ae``), its value and the allowed range.
    """
    try:
        return _scene_from_dict(data)
    except ParameterError as err:
        raise located(err, source) from None


def _scene_from_dict(data: dict) -> Scene:
    if not isinstance(data, dict):
        raise ParameterError("scene", data, "must be a TOML document (a table)")
    data = dict(data)
    units = data.pop("units", "SI")
    if units not in UNIT_SYSTEMS:
        raise ParameterError("units", units, f"must be one of {UNIT_SYSTEMS}")
    convert = _converter(units)
    allowed = set(_SCENE_FIELDS) | {"cable", "body", "sections", "point", "line"}
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise ParameterError(unknown[0], data[unknown[0]], f"unknown key; allowed: units, {', '.join(sorted(allowed))}")
    if "point" in data or "line" in data:
        given = [k for k in ("sections", "cable", "body") if k in data]
        if given:
            raise ParameterError(given[0], "given with [[point]]/[[line]]", "describe the cable either as sections "
                                 "([cable]+[body] or [[sections]]) or as a system of [[point]] and [[line]] tables")
        system = _system_from(data.pop("point", None), data.pop("line", None), convert)
        return Scene(system=system, **typed_fields(Scene, data, "", convert=convert, skip=("sections", "system")))
    if "sections" in data:
        if "cable" in data or "body" in data:
            raise ParameterError("sections", "given with [cable]/[body]", "use either [cable]+[body] or [[sections]]")
        secs = data.pop("sections")
        if isinstance(secs, dict):
            raise ParameterError("sections", "one table", "must be an array of tables: write [[sections]] per section")
        if not isinstance(secs, list) or not all(isinstance(s, dict) for s in secs):
            raise ParameterError("sections", secs, "must be an array of tables [[sections]], each with "
                                 "[sections.cable] and [sections.body]")
        sections = [build(Section, s, f"sections[{i}]", convert=convert) for i, s in enumerate(secs)]
    else:
        for key in ("cable", "body"):
            if key not in data:
                raise ParameterError(key, "missing", f"a scene needs a [{key}] table (or [[sections]])")
        sections = [build(Section, {"cable": data.pop("cable"), "body": data.pop("body")}, "", convert=convert)]
    # every other top-level key is a field of Scene, typed by its annotation
    return Scene(sections=tuple(sections), **typed_fields(Scene, data, "", convert=convert, skip=("sections",)))


def _tables(key: str, value) -> list:
    """The array of tables ``[[key]]`` (a named error for anything else)."""
    if value is None:
        raise ParameterError(key, "missing", f"a system needs [[point]] and [[line]] tables ([[{key}]] is missing)")
    if isinstance(value, dict):
        raise ParameterError(key, "one table", f"must be an array of tables: write [[{key}]] per {key}")
    if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
        raise ParameterError(key, value, f"must be an array of tables [[{key}]]")
    return value


def _system_from(points, lines, convert) -> System:
    """The :class:`System` of the ``[[point]]`` and ``[[line]]`` tables: a point's own keys (name, kind, x, y, z) and,
    for a body or junction, its body fields in the same table; a line's name, from, to and ``[[line.section]]``."""
    pts = []
    for i, t in enumerate(_tables("point", points)):
        where = f"point[{i}]"
        unknown = sorted(set(t) - set(_POINT_KEYS) - set(_BODY_KEYS))
        if unknown:
            raise ParameterError(f"{where}.{unknown[0]}", t[unknown[0]], "unknown key; allowed: "
                                 f"{', '.join(_POINT_KEYS)} and a body's or junction's {', '.join(_BODY_KEYS)}")
        own = {k: v for k, v in t.items() if k in _POINT_KEYS}
        body_keys = {k: v for k, v in t.items() if k not in _POINT_KEYS}
        kind = own.get("kind")
        if body_keys and kind in ("prescribed", "fixed"):
            key = sorted(body_keys)[0]
            raise ParameterError(f"{where}.{key}", body_keys[key], f"must be unset for a {kind} point: it does not "
                                 "move, so a body there would load only the support")
        if kind in ("body", "junction"):
            if not body_keys:
                raise ParameterError(f"{where}.weight", "missing", f"a {kind} needs its body fields (weight, mass_x, "
                                     "mass_y; drag_area_normal, ...): Wang's body")
        kw = typed_fields(Point, own, where, convert=convert, skip=("body",))
        if kind in ("body", "junction"):
            kw["body"] = build(Body, body_keys, where, convert=convert)
        try:
            pts.append(Point(**kw))
        except ParameterError as err:
            raise ParameterError(f"{where}.{err.field.split('.')[-1]}", err.value, err.allowed, err.hint) from None
    lns = []
    for k, t in enumerate(_tables("line", lines)):
        where = f"line[{k}]"
        unknown = sorted(set(t) - set(_LINE_KEYS))
        if unknown:
            raise ParameterError(f"{where}.{unknown[0]}", t[unknown[0]], f"unknown key; allowed: {', '.join(_LINE_KEYS)}")
        for key in _LINE_KEYS:
            if key not in t:
                raise ParameterError(f"{where}.{key}", "missing", "is required" + (" ([[line.section]] cable tables)"
                                                                                   if key == "section" else ""))
        for key in ("name", "from", "to"):
            if not isinstance(t[key], str):
                raise ParameterError(f"{where}.{key}", t[key], "must be a string (a point's name)" if key != "name"
                                     else "must be a string")
        secs = _tables(f"{where}.section", t["section"])
        cables = tuple(build(Cable, c, f"{where}.section[{s}]", convert=convert) for s, c in enumerate(secs))
        try:
            lns.append(Line(name=t["name"], start=t["from"], end=t["to"], section=cables))
        except ParameterError as err:
            raise ParameterError(f"{where}.{err.field.split('.', 1)[-1]}", err.value, err.allowed, err.hint) from None
    return System(point=tuple(pts), line=tuple(lns))


def load_scene(path: str | Path) -> Scene:
    """Read a scene TOML file.

    Parameters
    ----------
    path : str or Path
        A UTF-8 TOML file (a byte-order mark is accepted).

    Returns
    -------
    Scene
        The validated scene in SI.

    Raises
    ------
    ParameterError
        The file cannot be read or decoded, is not TOML, or a value is out of range; the
        message names the file, the line where it can be found, the field and the value.
    """
    data, source = read_toml(path, "scene file")
    return scene_from_dict(data, source)


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
                "acceleration": "ft/s^2", "area": "ft^2", "force_time": "lbf s",
                "stiffness_per_area": "lbf/ft^3", "damping_per_area": "lbf s/ft^3",
                "angle_deg_per_length": "deg/ft"}.get(dim, SI_UNIT[dim])
    return SI_UNIT[dim]


def _table_lines(obj, header: str, units: str, annotate: bool, skip: tuple = ()) -> list[str]:
    lines, subtables = [header], []
    for f in dataclasses.fields(obj):
        if f.name in skip:
            continue
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


def _system_lines(system: System, units: str, annotate: bool) -> list[str]:
    """The ``[[point]]`` tables (a body's or junction's fields in the point's table) and the ``[[line]]`` tables with
    their ``from``, ``to`` and ``[[line.section]]`` cables."""
    out = []
    for p in system.point:
        lines = _table_lines(p, "[[point]]", units, annotate, skip=("body",))
        if p.body is not None:
            lines = lines[:-1] + _table_lines(p.body, "", units, annotate)[1:]
        out += lines
    for ln in system.line:
        out += ["[[line]]", f"name = {_fmt(ln.name)}", f"from = {_fmt(ln.start)}" + (
            "   # the point the line starts from: its first section begins there" if annotate else ""),
                f"to = {_fmt(ln.end)}", ""]
        for c in ln.section:
            out += _table_lines(c, "[[line.section]]", units, annotate)
    return out


def dump_scene(scene: Scene, *, units: str = "SI", annotate: bool = False) -> str:
    """Write a scene as TOML text (loadable by :func:`load_scene`).

    Parameters
    ----------
    scene : Scene
        The scene (SI inside).
    units : str, optional
        'SI' or 'fps' (the report's ft/lb/slug); values are converted on the way out.
    annotate : bool, optional
        Add each field's unit and meaning as comments.

    Returns
    -------
    str
        TOML text.
    """
    if units not in UNIT_SYSTEMS:
        raise ParameterError("units", units, f"must be one of {UNIT_SYSTEMS}")
    out = []
    if annotate:
        out += ["# cablesys scene. Every value is in the units named by `units`;",
                "# each line's comment gives [unit] and meaning (Wang 1971 notation).", ""]
    out += [f"name = {_fmt(scene.name)}", f"units = {_fmt(units)}",
            f"angles = {_fmt(scene.angles)}" + ("   # per_section | shared (dual isolation)" if annotate else ""), ""]
    if scene.system is not None:       # points and lines: a system that is not a chain
        out += _system_lines(scene.system, units, annotate)
    elif len(scene.sections) == 1:
        out += _table_lines(scene.sections[0].cable, "[cable]", units, annotate)
        out += _table_lines(scene.sections[0].body, "[body]", units, annotate)
    else:
        for s in scene.sections:
            out += ["[[sections]]", ""]
            out += _table_lines(s.cable, "[sections.cable]", units, annotate)
            out += _table_lines(s.body, "[sections.body]", units, annotate)
    for key in ("environment", "top_motion", "initial", "numerics"):
        out += _table_lines(getattr(scene, key), f"[{key}]", units, annotate)
    for key in ("anchor", "seabed", "winch"):   # the fixed lower end, the bed, the winch (segmented cable)
        if getattr(scene, key) is not None:
            out += _table_lines(getattr(scene, key), f"[{key}]", units, annotate)
    if scene.limits is not None:      # what the verdict checks: written so that nothing asked for is dropped
        out += _table_lines(scene.limits, "[limits]", units, annotate)
    if scene.design:                  # the design NLP's table is SI whatever `units` says (DesignSettings)
        out += ["[design]" + ("   # SI, keys of cablesys.isolation.DesignSettings" if annotate else "")]
        out += [f"{k} = {_fmt(v)}" for k, v in scene.design.items()] + [""]
    return "\n".join(out).rstrip() + "\n"
