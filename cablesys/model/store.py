"""A model structure's functions kept on disk, so that a second start skips the symbolic build.

Building a model derives its equations of motion symbolically (Lagrange's equations by AD);
CasADi's serialized form of the same functions loads in a fraction of that time
(``studies/bench_start.py`` measures both). The functions
depend on the scene's structure only (every scene number is an entry of ``p``), so they are
stored under a **structure key**: a hash of

- the structure description :func:`~cablesys.model.params.structure_of` (sections, angle mode,
  body drag shapes, drag segments, elements per section, current points, waves, sinusoids,
  time-series grid and values) and the full list of parameter labels (every named input of the model);
- the builder (``build_model``), the versions of cablesys and CasADi, the cache format and the
  fingerprint of the model's source files (:func:`cablesys.disk_cache.code_fingerprint`).

Two scenes with equal keys build identical functions, so a key collision would need a
SHA-256 collision. Each function is deserialized on its first use (a run never asks for the
energy, for instance). The entry is sealed with the SHA-256
of its content (:func:`cablesys.disk_cache.write_sealed`), checked before unpickling: a truncated
or corrupt file is detected, removed with a one-line warning and rebuilt. Only used when
compilation is enabled (the compiled path; ``CABLESYS_COMPILE=0`` keeps everything in memory).
"""

from __future__ import annotations

import contextlib
import dataclasses
import importlib
import logging
import pickle
import time

import casadi as ca

from ..compiled import DerivedStore, compilation_enabled
from ..disk_cache import (
    CACHE_FORMAT,
    cache_dir,
    code_fingerprint,
    digest,
    evict,
    touch,
    unseal,
    write_sealed,
)
from .params import ParameterLayout, structure_of

log = logging.getLogger(__name__)

_SKIP = ("layout",)          # rebuilt from the scene (its SX symbol is not part of the functions)


def structure_key(scene, builder: str = "build_model", layout: ParameterLayout | None = None, options=()) -> str:
    """The hash naming ``scene``'s model structure (see the module docstring).

    Parameters
    ----------
    scene : Scene
        The scene (its values do not enter the key).
    builder : str
        Name of the function that builds the model.
    layout : ParameterLayout, optional
        ``scene``'s layout when already made.
    options : tuple, optional
        The builder's structural options (e.g. unrolled Newton iterations), by their ``repr``.

    Returns
    -------
    str
        32 hexadecimal digits.
    """
    labels = (layout or ParameterLayout.from_scene(scene)).labels
    return digest(CACHE_FORMAT, ca.__version__, code_fingerprint(), builder, repr(tuple(options)),
                  repr(structure_of(scene)), *labels)


def stored_model(scene, builder: str, build, options=()):
    """The model of ``scene`` built by ``build()``, or loaded when this structure was stored before.

    With compilation disabled (``CABLESYS_COMPILE=0``) it is simply ``build()``. Otherwise the
    stored model (:func:`load_model`) or a fresh build, stored (:func:`save_model`); either way
    ``model.cache`` is attached to the disk index of its compiled functions
    (:class:`cablesys.compiled.DerivedStore`) and ``model.build_info`` records ``stored``,
    ``build_s`` and ``structure_key``.

    Parameters
    ----------
    scene : Scene
        The scene (its structure names the entry).
    builder : str
        Name of the building function (part of the key).
    build : callable
        No-argument function building the model symbolically.
    options : tuple, optional
        Structural options of the builder (part of the key).

    Returns
    -------
    CableModel
        The model.
    """
    t0 = time.perf_counter()
    if not compilation_enabled():
        model = build()
        model.build_info.update(stored=False, build_s=time.perf_counter() - t0)
        return model
    layout = ParameterLayout.from_scene(scene)
    key = structure_key(scene, builder, layout, options)
    model = load_model(scene, key, layout)
    stored = model is not None
    if not stored:
        model = build()
        save_model(model, key)
    model.cache.attach(DerivedStore(key))
    model.build_info.update(stored=stored, build_s=time.perf_counter() - t0, structure_key=key)
    return model


def _path(key: str):
    return cache_dir() / "models" / f"{key}.model"


def save_model(model, key: str) -> None:
    """Store ``model``'s functions and fields under ``key`` (atomic; errors only logged)."""
    fields = {}
    for f in dataclasses.fields(model):
        if not f.init or f.name in _SKIP:
            continue
        value = getattr(model, f.name)
        fields[f.name] = ("function", value.serialize()) if isinstance(value, ca.Function) else ("value", value)
    cls = type(model)
    payload = pickle.dumps({"class": (cls.__module__, cls.__qualname__), "fields": fields},
                           protocol=pickle.HIGHEST_PROTOCOL)
    path = _path(key)
    try:
        write_sealed(path, payload)
        evict(keep=[path])
    except OSError as err:
        log.info("model not stored (%s)", err)


def load_model(scene, key: str, layout: ParameterLayout | None = None):
    """The model stored under ``key`` with ``scene``'s parameter layout (``layout`` when already
    made), or None (not stored, or the entry is corrupt: then it is removed)."""
    path = _path(key)
    try:
        blob = path.read_bytes()
    except OSError:
        return None
    try:
        data = pickle.loads(unseal(blob))
        module, name = data["class"]
        cls = getattr(importlib.import_module(module), name)
        functions = {k: v for k, (kind, v) in data["fields"].items() if kind == "function"}
        for k, v in functions.items():       # a corrupt string would crash CasADi: checked above by the digest
            if not isinstance(v, str):
                raise TypeError(f"field {k} is not a serialized function")
        values = {k: v for k, (kind, v) in data["fields"].items() if kind != "function"}
        # a field with a default (SegmentedModel.accel = None) is also a class attribute: deleting the
        # instance's value would expose that default instead of reaching __getattr__, so those load now
        eager = {k: ca.Function.deserialize(functions.pop(k)) for k in list(functions) if hasattr(cls, k)}
        model = cls(layout=layout or ParameterLayout.from_scene(scene), **values, **eager,
                    **dict.fromkeys(functions))
        for k in functions:                  # deserialized on first use (CableModel.__getattr__)
            object.__delattr__(model, k)
        object.__setattr__(model, "_pending", functions)
    except Exception as err:         # noqa: BLE001 (any unreadable entry is rebuilt, never trusted)
        log.warning("stored model %s is unreadable (%s): building it again", path.name, err)
        with contextlib.suppress(OSError):
            path.unlink()
        return None
    touch(path)
    return model
