"""Put a case's values into a scene by label, and name their units.

Labels follow the parameter vector (:mod:`cablesys.model.params`): ``cable.ae`` (one section),
``sections[1].body.weight``, ``environment.current_speeds[0]``, ``top_motion.y[0].frequency``,
and any other scene field such as ``numerics.drag_segments`` or ``numerics.integrator``
(those may change the model's structure; the sweep then builds a model for it). Labels that
start with the analysis name (``stochastic.hs``, ``design.tp``, ``run.periods``) are options
of the analysis, not scene values. Each value passes the scene's own validation, so a bad
value fails its case with the field, the value and the allowed range.
"""

from __future__ import annotations

import dataclasses
import re

from ..errors import ParameterError
from ..scene.fields import SI_UNIT

_TOKEN = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")
ANALYSES = ("run", "rao", "periodic", "stochastic", "design", "ladder")
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
    if tokens[0][0] in ("cable", "body") and tokens[0][1] is None:
        if len(scene.sections) != 1:
            raise ParameterError("vary", label, f"is ambiguous for {len(scene.sections)} sections: "
                                                f"use sections[i].{label}")
        tokens = [("sections", 0)] + tokens
    if label.split(".")[-1] in ("axis_angle", "slack"):
        raise ParameterError("vary", label, "is set by the scene (vary body.axis_angle_deg) or by the simulator")
    return tokens


def _convert(old, value, label):
    if isinstance(old, bool):
        return bool(value)
    if isinstance(old, int):
        if float(value) != int(float(value)):
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
    if name in ("spectrum", "rao") and hasattr(obj, "series"):
        return dataclasses.replace(obj, **_user_sinusoids(obj), **{name: new})   # the new sea replaces the old
    return dataclasses.replace(obj, **{name: new})


def _user_sinusoids(top) -> dict:
    """The user's own sinusoids of a TopMotion (a realised sea is appended again on replace)."""
    from ..scene.sea import user_count
    return {"x": top.x[:user_count(top, "x")], "y": top.y[:user_count(top, "y")]}


def apply_values(scene, values: dict, analysis: str):
    """(scene with the scene values set, {option: value} for the analysis options)."""
    options = {}
    for label, value in values.items():
        if is_option(label, analysis):
            options[label.split(".", 1)[1]] = value
        else:
            scene = _set(scene, _scene_tokens(scene, label), value, label)
    return scene, options


def unit_of_label(scene, label: str, analysis: str) -> str:
    """SI unit of a varied label (from the scene field metadata), '' when unknown."""
    if is_option(label, analysis):
        return OPTION_UNITS.get(label.split(".", 1)[1], "")
    try:
        tokens = _scene_tokens(scene, label)
    except ParameterError:
        return ""
    obj = scene
    for k, (name, idx) in enumerate(tokens):
        if not dataclasses.is_dataclass(obj):
            return ""
        field = {f.name: f for f in dataclasses.fields(obj)}.get(name)
        if field is None:
            return ""
        if k == len(tokens) - 1:
            return SI_UNIT.get(field.metadata.get("dim", ""), "")
        obj = getattr(obj, name)
        if idx is not None:
            obj = obj[idx] if isinstance(obj, tuple) and idx < len(obj) else None
    return ""


def check_labels(scene, labels, analysis: str) -> None:
    """Refuse unknown labels before any computation (apply the first value of each)."""
    for label in labels:
        if not is_option(label, analysis):
            tokens = _scene_tokens(scene, label)
            obj = scene
            for name, idx in tokens:
                if not dataclasses.is_dataclass(obj) or name not in {f.name for f in dataclasses.fields(obj)}:
                    have = [f.name for f in dataclasses.fields(obj)] if dataclasses.is_dataclass(obj) else []
                    raise ParameterError("vary", label, f"names no scene field ({name!r}); fields here: {have}")
                obj = getattr(obj, name)
                if idx is not None:
                    if not isinstance(obj, tuple) or idx >= len(obj):
                        raise ParameterError("vary", label, f"index {idx} out of range")
                    obj = obj[idx]
