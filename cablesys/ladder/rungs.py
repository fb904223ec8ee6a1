"""The rungs of the model ladder, cheapest first, and how to build each one for a scene.

- ``frequency``: the periodic steady state of Wang's model (Fourier collocation,
  :func:`cablesys.linear.periodic_steady_state`), for a steady amplitude under one forcing frequency;
- ``quasi-static``: the swing with the stretch following the tension (:mod:`cablesys.model.quasistatic`);
- ``wang``: Wang's (1971) 2-DOF straight cable per section (:mod:`cablesys.model.build`);
- ``segmented``: N straight tension-only elements per section (:mod:`cablesys.model.segmented`).
"""

from __future__ import annotations

import dataclasses

from ..errors import ParameterError
from ..model import CableModel, build_model
from ..model.quasistatic import build_quasistatic
from ..scene import Scene

RUNGS = ("frequency", "quasi-static", "wang", "segmented")
TIME_DOMAIN_RUNGS = ("quasi-static", "wang", "segmented")
MODEL_CHOICES = ("auto",) + RUNGS


def check_rung(name: str) -> str:
    """``name`` if it is a rung or "auto"; :class:`ParameterError` otherwise."""
    if name not in MODEL_CHOICES:
        raise ParameterError("numerics.model", name, f"must be one of {MODEL_CHOICES}")
    return name


def with_segments(scene: Scene, n: int) -> Scene:
    """``scene`` with every section divided into ``n`` elements (1: Wang's straight cable)."""
    secs = tuple(dataclasses.replace(s, cable=dataclasses.replace(s.cable, segments=int(n))) for s in scene.sections)
    return dataclasses.replace(scene, sections=secs)


def rung_scene(scene: Scene, name: str, segments: int = 1) -> Scene:
    """The scene a rung runs: ``segments`` elements for the segmented rung, 1 for the others."""
    return with_segments(scene, segments if name == "segmented" else 1)


def build_rung(scene: Scene, name: str, segments: int = 1) -> CableModel:
    """The CasADi model of rung ``name``.

    Parameters
    ----------
    scene : Scene
        The scene (its ``cable.segments`` are replaced by the rung's).
    name : str
        A rung; ``frequency`` uses Wang's model.
    segments : int, optional
        Elements per section of the segmented rung (>= 2).

    Returns
    -------
    CableModel
        The model; ``model.parameters(rung_scene(scene, name, segments))`` gives its ``p``.
    """
    check_rung(name)
    if name == "quasi-static":
        return build_quasistatic(rung_scene(scene, name))
    if name == "segmented" and segments < 2:
        raise ParameterError("segments", segments, "the segmented rung needs at least 2 elements per section")
    return build_model(rung_scene(scene, name, segments))
