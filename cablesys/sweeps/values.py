"""Put a case's values into a scene by label, and name their units.

Labels follow the parameter vector (:mod:`cablesys.model.params`): ``cable.ae`` (one section),
``sections[1].body.weight``, ``environment.current_speeds[0]``, ``top_motion.y[0].frequency``,
and any other scene field such as ``numerics.drag_segments`` or ``numerics.integrator``
(those may change the model's structure; the sweep then builds a model for it). A slack or towed
scene's fields are named the same way (``span``, ``cable.ae``, ``masses[0].mass``, ``limits.least_tension``;
``speed``, ``cable.cd_normal``, ``xi[1]``). Labels that
start with the analysis name (``stochastic.hs``, ``design.tp``, ``run.periods``) are options
of the analysis, not scene values. Each value passes the scene's own validation, so a bad
value fails its case with the field, the value and the allowed range.
"""

from __future__ import annotations

import dataclasses
import math
import re

from ..errors import ParameterError
from ..scene.fields import SI_UNIT
from .analyses import ANALYSES

_TOKEN = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")
# units of analysis options that can be varied (others are dimensionless)
OPTION_UNITS = {"hs": "m", "tp": "s", "omega_min": "rad/s", "omega_max": "rad/s", "periods": "-", "gamma": "-"}


def split_label(label: str) -> list:
    """``sections[1].body.weight`` -> [("sections", 1), ("body", None), ("weight", None)]."""
    out = []
    for part in label.split("."):
        m = _TOKEN.match(part)
        if not m:
            raise ParameterError("vary", label, "is not a label like cable.ae, sections[1].body.weight or "
                                                "top_motion.y[0].frequency")
        out.append((m.group(1), None if m.group(2) is None else int(m.group(2))))
    return out


def is_option(label: str, analysis: str) -> bool:
    """True for labels of analysis options (``stochastic.hs``), False for scene values."""
    return label.split(".", 1)[0] in ANALYSES and label.split(".", 1)[0] == analysis


def _scene_tokens(scene, label: str) -> list:
    tokens = split_label(label)
    if tokens[0][0] in ("cable", "body") and tokens[0][1] is None and hasattr(scene, "sections"):
        if len(scene.sections) != 1:
            raise ParameterError("vary", label, f"is ambiguous for {len(scene.sections)} sections: "
                                                f"use sections[i].{label}")
        tokens = [("sections", 0)] + tokens
    if label.split(".")[-1] in ("axis_angle", "slack"):
        raise ParameterError("vary", label, "is set by the scene (vary body.axis_angle_deg) or by the simulator")
    return tokens


def _convert(old, value, label):
    """``value`` as the type of the field's current value ``old`` (ParameterError naming ``label`` if it cannot be)."""
    if old is None:                   # an optional field that is unset: the scene's validation decides
        return value
    if isinstance(old, bool):
        if isinstance(value, str) and value.lower() in ("true", "false"):
            return value.lower() == "true"
        if isinstance(value, str) or value not in (0, 1):
            raise ParameterError(label, value, "must be true or false (1 or 0)")
        return bool(value)
    if isinstance(old, int):
        if isinstance(value, str) or not math.isfinite(float(value)) or float(value) != int(float(value)):
            raise ParameterError(label, value, "must be an integer")
        return int(float(value))
    if isinstance(old, str):
        return str(value)
    if isinstance(value, str):
        raise ParameterError(label, value, "must be a number")
    return float(value)


def _set(obj, tokens, value, label):
    name, idx = tokens[0]
    if not dataclasses.is_dataclass(obj) or name not in {f.name for f in dataclasses.fields(obj)}:
        have = [f.name for f in dataclasses.fields(obj)] if dataclasses.is_dataclass(obj) else []
        raise ParameterError("vary", label, f"names no scene field ({name!r}); fields here: {have}")
    child = getattr(obj, name)
    if idx is None:
        new = _convert(child, value, label) if len(tokens) == 1 else _set(child, tokens[1:], value, label)
    else:
        if not isinstance(child, tuple) or idx >= len(child):
            raise ParameterError("vary", label, f"index {idx} out of range ({name} has "
                                                f"{len(child) if isinstance(child, tuple) else 0} entries)")
        item = _convert(child[idx], value, label) if len(tokens) == 1 else _set(child[idx], tokens[1:], value, label)
        new = child[:idx] + (item,) + child[idx + 1:]
    if name in ("spectrum", "rao", "vessel", "track") and hasattr(obj, "series"):
        return dataclasses.replace(obj, **_user_sinusoids(obj), **{name: new})   # the new sea or circle replaces the old
    return dataclasses.replace(obj, **{name: new})


def _user_sinusoids(top) -> dict:
    """The user's own sinusoids of a TopMotion (a realised sea, or a circle's track, is appended again on replace)."""
    from ..scene.sea import user_count
    return {axis: getattr(top, axis)[:user_count(top, axis)] for axis in ("x", "y", "z")}


def apply_values(scene, values: dict, analysis: str):
    """(scene with the scene values set, {option: value} for the analysis options)."""
    options = {}
    for label, value in values.items():
        if is_option(label, analysis):
            options[label.split(".", 1)[1]] = value
        else:
            scene = _set(scene, _scene_tokens(scene, label), value, label)
    return scene, options


def _leaf(scene, label: str):
    """(dataclass field, current value) of a scene label; ParameterError for a name or index the scene lacks."""
    obj, field = scene, None
    for name, idx in _scene_tokens(scene, label):
        fields = {f.name: f for f in dataclasses.fields(obj)} if dataclasses.is_dataclass(obj) else {}
        if name not in fields:
            raise ParameterError("vary", label, f"names no scene field ({name!r}); fields here: {list(fields)}")
        field, obj = fields[name], getattr(obj, name)
        if idx is not None:
            if not isinstance(obj, tuple) or idx >= len(obj):
                raise ParameterError("vary", label, f"index {idx} out of range ({name} has "
                                                    f"{len(obj) if isinstance(obj, tuple) else 0} entries)")
            obj = obj[idx]
    return field, obj


def unit_of_label(scene, label: str, analysis: str) -> str:
    """SI unit of a varied label (from the scene field metadata), '' when unknown."""
    if is_option(label, analysis):
        return OPTION_UNITS.get(label.split(".", 1)[1], "")
    try:
        field, _ = _leaf(scene, label)
    except ParameterError:
        return ""
    return SI_UNIT.get(field.metadata.get("dim", ""), "") if field is not None else ""


def long_name_of_label(scene, label: str, analysis: str) -> str:
    """What a varied label is, in words: the scene field's ``doc`` (or the analysis option), with the label."""
    if is_option(label, analysis):
        return f"{analysis} option {label.split('.', 1)[1]} ({label})"
    try:
        field, _ = _leaf(scene, label)
    except ParameterError:
        return label
    doc = field.metadata.get("doc", "") if field is not None else ""
    return f"{doc} ({label})" if doc else label


def check_labels(scene, labels, analysis: str) -> None:
    """Refuse unknown labels, and two labels of one value (``cable.ae`` and ``sections[0].cable.ae``),
    before any computation."""
    seen = {}
    for label in labels:
        key = label if is_option(label, analysis) else tuple(_scene_tokens(scene, label))
        if not is_option(label, analysis):
            _leaf(scene, label)
        if key in seen:
            raise ParameterError("vary", label, f"names the same value as {seen[key]!r}: vary each value once")
        seen[key] = label


def check_values(scene, grid, analysis: str) -> None:
    """Refuse, before any case runs, an entry that does not fit its label: text for a numeric field or
    option, a fraction for an integer field, anything but true/false for a flag. Ranges are the scene's
    own validation, per case (a bad value fails its case, not the sweep)."""
    for names, lists in zip(grid.names, grid.values):
        for label, values in zip(names, lists):
            field = f"vary[{label!r}]"
            shown = ", ".join(map(str, values))
            if is_option(label, analysis):
                key = label.split(".", 1)[1]
                bad = [v for v in values if isinstance(v, str)]
                if key in OPTION_UNITS and bad:
                    raise ParameterError(field, bad[0], f"must be a number ({OPTION_UNITS[key]}); values given: {shown}")
                continue
            _, old = _leaf(scene, label)
            unit = unit_of_label(scene, label, analysis)
            for v in values:
                try:
                    _convert(old, v, field)
                except ParameterError as err:
                    raise ParameterError(field, v, f"{err.allowed}{f' ({unit})' if unit not in ('', '-') else ''}; "
                                                   f"values given: {shown}") from None
