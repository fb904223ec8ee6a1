"""The rungs of the model ladder, cheapest first, and the registry that holds them with the rungs registered from
outside: each built-in rung is one module of :mod:`cablesys.ladder.rung` (what it builds, which scenes it can run,
its error estimate and its cost), and the ladder asks the registry (:func:`ladder_rungs`, :func:`get_rung`).

- ``frequency``: the periodic steady state of Wang's model (Fourier collocation,
  :func:`cablesys.linear.periodic_steady_state`), for a steady amplitude under one forcing frequency;
- ``quasi-static``: the swing with the stretch following the tension (:mod:`cablesys.model.quasistatic`),
  Wang's straight cable (``segments = 1``) or N elements whose stretches follow their tensions (``segments = N``);
- ``wang``: Wang's (1971) 2-DOF straight cable per section (:mod:`cablesys.model.build`);
- ``steady``: a towing ship's steady straight tow or steady turn (a circle), the node model's steady state at N
  carried with the tow to the output times and checked for stability, where the run is that steady state for all time
  (:mod:`cablesys.ladder.steady_tow`); under auto in place of the node model's run;
- ``segmented``: N straight tension-only elements per section (:mod:`cablesys.model.segmented`).
"""

from __future__ import annotations

import dataclasses
import time
from typing import Protocol, runtime_checkable

import numpy as np

from ..errors import ParameterError
from ..model import CableModel
from ..model.params import structure_of
from ..scene import Scene
from ..scene.components import MODEL_CHOICES, RUNGS
from .rung import frequency, quasistatic, segmented, steady, wang
from .rung.base import with_segments  # noqa: F401 - re-exported: the scene of N elements, as before the split

BUILTIN = (frequency.RUNG, quasistatic.RUNG, wang.RUNG, steady.RUNG, segmented.RUNG)     # in ladder order: RUNGS
_BUILTIN = {r.name: r for r in BUILTIN}
TIME_DOMAIN_RUNGS = tuple(r.name for r in BUILTIN if r.time_domain)


@runtime_checkable
class Rung(Protocol):
    """A model the ladder may choose besides its own rungs: a name, how to build it, its error and its cost.

    ``estimate(scene, assessment)`` returns ``{"body": e, "tension": e, "note": str}``, the relative errors of the
    body motion and of the tension extremes against the converged segmented cable; ``assessment`` is the ladder's
    :class:`Assessment` of the scene (its numbers and every built-in rung's estimate, to build on).
    ``cost(scene, assessment)`` is the run's cost relative to Wang's straight cable (1; the node model with N
    elements costs N, the quasi-static straight cable 0.5, the frequency rung 0.2: the built-in rungs' ``cost``).
    ``build(scene)`` returns the :class:`~cablesys.model.CableModel` that runs (in the time domain as built).
    Optionally ``valid(scene) -> str``: "" when the rung can run ``scene``, else why not (without it, every scene;
    the ladder never chooses a rung for a scene it says it cannot run: :func:`validity`).
    Register one with :func:`register_rung`; the ladder then takes it under "auto" where it is valid, its estimate
    is within the tolerance and it costs less than the built-in choice, and ``numerics.model`` may not name it
    (scene files are checked against the built-in names) but ``cablesys.simulate(scene, model=name)`` may.
    The built-in rungs (:mod:`cablesys.ladder.rung`) are Rungs too, whose ``build``, ``estimate`` and ``cost`` also
    take the elements per section.
    """

    name: str

    def build(self, scene: Scene) -> CableModel: ...

    def estimate(self, scene: Scene, assessment) -> dict: ...

    def cost(self, scene: Scene, assessment) -> float: ...


def validity(rung, scene: Scene) -> str:
    """Whether ``rung`` can run ``scene``.

    Parameters
    ----------
    rung : Rung
        A built-in or registered rung (its ``valid(scene)``; a rung without one runs every scene).
    scene : Scene
        The scene.

    Returns
    -------
    str
        "" when the rung can run the scene, else why not (a sentence for the reason or the error).
    """
    valid = getattr(rung, "valid", None)
    return "" if valid is None else str(valid(scene) or "")


@dataclasses.dataclass(frozen=True)
class Assessment:
    """What the ladder knows of a scene before any run: its deciding numbers
    (:class:`~cablesys.ladder.indicators.SceneNumbers`), Wang's linear response and every rung's estimate."""

    numbers: object
    response: object
    estimates: dict


_REGISTERED: dict = {}


def register_rung(rung: Rung) -> None:
    """Let the ladder consider ``rung`` (see :class:`Rung`); its name may not be a built-in model name.

    Parameters
    ----------
    rung : Rung
        An object with ``name``, ``build(scene)``, ``estimate(scene, assessment)`` and ``cost(scene, assessment)``.

    Returns
    -------
    None
        The rung is registered (a rung of the same name before it is replaced).

    Raises
    ------
    ParameterError
        Not a :class:`Rung`, or its name is empty or a built-in model name.
    """
    if not isinstance(rung, Rung):
        raise ParameterError("rung", type(rung).__name__, "must have name, build(scene), estimate(scene, assessment) "
                                                          "and cost(scene, assessment) (cablesys.ladder.Rung)")
    if not isinstance(rung.name, str) or not rung.name or rung.name in MODEL_CHOICES:
        raise ParameterError("rung.name", rung.name, f"must be a new name, not one of {MODEL_CHOICES}")
    _REGISTERED[rung.name] = rung


def unregister_rung(name: str) -> None:
    """Forget the registered rung ``name`` (nothing when it is not registered).

    Parameters
    ----------
    name : str
        The rung's name.

    Returns
    -------
    None
    """
    _REGISTERED.pop(name, None)


def registered_rungs() -> tuple:
    """The registered rungs.

    Returns
    -------
    tuple of Rung
        In the order of registration.
    """
    return tuple(_REGISTERED.values())


def ladder_rungs() -> tuple:
    """Every rung the ladder may choose: the built-in ones in ladder order (cheapest first), then the registered ones.

    Returns
    -------
    tuple of Rung
    """
    return BUILTIN + registered_rungs()


def get_rung(name: str):
    """The built-in or registered rung ``name`` (:class:`ParameterError` for any other name)."""
    check_rung(name)
    return _REGISTERED.get(name) or _BUILTIN[name]


def takes_elements(name: str) -> bool:
    """Whether rung ``name`` runs N elements per section (the segmented and quasi-static rungs)."""
    return getattr(_BUILTIN.get(name), "elements", False)


def check_rung(name: str) -> str:
    """``name`` if it is a model name or a registered rung; :class:`ParameterError` otherwise."""
    if name not in MODEL_CHOICES and name not in _REGISTERED:
        raise ParameterError("numerics.model", name, f"must be one of {MODEL_CHOICES + tuple(_REGISTERED)}")
    return name


def rung_scene(scene: Scene, name: str, segments: int = 1) -> Scene:
    """The scene a rung runs: ``segments`` elements for the segmented and quasi-static rungs (the
    quasi-static segmented cable for N > 1), 1 for the others."""
    if name in _REGISTERED:
        return scene
    return _BUILTIN[name].scene(scene, segments)


def build_rung(scene: Scene, name: str, segments: int = 1) -> CableModel:
    """The CasADi model of rung ``name``.

    Parameters
    ----------
    scene : Scene
        The scene (its ``cable.segments`` are replaced by the rung's).
    name : str
        A rung; ``frequency`` uses Wang's model.
    segments : int, optional
        Elements per section of the segmented rung (>= 2), or of the quasi-static rung (1: Wang's
        straight cable; N > 1: the segmented cable with its element stretches quasi-static).

    Returns
    -------
    CableModel
        The model; ``model.parameters(rung_scene(scene, name, segments))`` gives its ``p``.
    """
    rung = get_rung(name)
    return rung.build(scene) if name in _REGISTERED else rung.build(scene, segments)


class RungCache:
    """The rungs' models and simulators, built once and reused while the scene structure repeats.

    Building a rung can cost more than running a small one (``studies/bench_start.py``), so
    :func:`~cablesys.ladder.simulate` builds each (rung, elements) once per
    call, and a caller running many scenes of one structure (a sweep, a benchmark) passes one cache
    to every call. Models are keyed by rung, elements and :func:`~cablesys.model.params.structure_of`
    (every scene number is an entry of ``p``), simulators by model, output times and settings.
    ``build_s`` is the wall time spent building so far (s).
    """

    def __init__(self):
        self._models: dict = {}
        self._simulators: dict = {}
        self._memo: list = []
        self.build_s = 0.0

    def _key(self, scene: Scene, name: str, segments: int) -> tuple:
        rung = _BUILTIN[name]
        sc = rung.scene(scene, segments)
        return (name, rung.segments(segments), structure_of(sc)) + rung.structure(sc)

    def model(self, scene: Scene, name: str, segments: int = 1) -> CableModel:
        """The model of rung ``name`` for ``scene``'s structure (built on first use).

        Parameters
        ----------
        scene : Scene
            The scene (its ``cable.segments`` are replaced by the rung's).
        name : str
            A rung (``frequency`` uses Wang's model).
        segments : int, optional
            Elements per section of the segmented rung.

        Returns
        -------
        CableModel
            As the rung builds it (:mod:`cablesys.ladder.rung`); the frequency rung and the straight quasi-static
            rung share the cached Wang model.
        """
        rung = get_rung(name)
        if getattr(rung, "model_of", None):
            return self.model(scene, rung.model_of, segments)
        if name in _REGISTERED:
            key = (name, 1, structure_of(scene), 0)
            if key not in self._models:
                t0 = time.perf_counter()
                self._models[key] = _REGISTERED[name].build(scene)
                self.build_s += time.perf_counter() - t0
            return self._models[key]
        key = self._key(scene, name, segments)
        if key not in self._models:
            t0, b0 = time.perf_counter(), self.build_s
            model = rung.build(scene, segments, cache=self)      # may build another rung's model on self
            self._models[key] = model
            self.build_s = b0 + time.perf_counter() - t0
        return self._models[key]

    MAX_SIMULATORS = 32      # a sweep over output grids or settings keeps the newest ones

    def simulator(self, model: CableModel, times, settings):
        """A :class:`~cablesys.time_domain.Simulator` of ``model`` over ``times`` with ``settings``
        (an :class:`~cablesys.time_domain.IntegratorSettings`), built on first use; found by the model itself
        (one of this cache's models, or the caller's), the output grid and the settings."""
        from ..time_domain import Simulator
        times = np.asarray(times, dtype=float)
        key = (times.size, times.tobytes(), settings)
        for k, (m, sim) in enumerate(self._simulators.get(key, ())):
            if m is model:
                return sim
        t0 = time.perf_counter()
        sim = Simulator(model, times, settings)
        self.build_s += time.perf_counter() - t0
        self._simulators.setdefault(key, []).append((model, sim))
        while sum(len(v) for v in self._simulators.values()) > self.MAX_SIMULATORS:
            oldest = next(iter(self._simulators))
            self._simulators[oldest].pop(0)
            if not self._simulators[oldest]:
                del self._simulators[oldest]
        return sim

    MAX_MEMO = 16            # the last starts and guard verdicts: what one call asks twice

    def memo(self, model: CableModel, what: str, values: tuple, compute):
        """``compute()`` once per (``model``, ``what``, ``values``) among the last MAX_MEMO: what the choice and the run
        both ask of one model and parameter vector (its static start, the stiffness guard's verdict:
        :mod:`.run_settings`). ``values`` (numbers, arrays) are compared by value, the model by identity."""
        key = tuple(np.asarray(v).tobytes() if isinstance(v, np.ndarray) else v for v in values)
        for k, (m, w, vals, result) in enumerate(self._memo):
            if m is model and w == what and vals == key:
                self._memo.append(self._memo.pop(k))
                return result
        result = compute()
        self._memo.append((model, what, key, result))
        del self._memo[:-self.MAX_MEMO]
        return result

    def __len__(self) -> int:
        return len(self._models)
