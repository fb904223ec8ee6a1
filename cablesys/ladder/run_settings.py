"""The integrator settings of a ladder run: which method, rtol and atol each rung runs with when
neither the caller nor the scene names them, and the stiffness guard's part in it (:mod:`.stiffness`).

The rungs with undamped stretch modes step with A-stable BDF2; the quasi-static rungs with the compiled
explicit rk23 pair where the guard finds that stability does not set its step, else variable-order BDF; every
rung's rtol is at most min(AUTO_RTOL, body tolerance / 100) and, where no a posteriori check measures its integration
error (:func:`stated_room`), its stated body error / STATED_ROOM.
"""

from __future__ import annotations

import dataclasses
import logging
import math

import numpy as np

from ..compiled import compiles
from ..scene import Numerics, Scene
from ..time_domain.initial import initial_state
from ..time_domain.integrators import (  # one rule, simulate's default too
    COMPILE_MAX_ELEMENTS,
    compiled_by_default,
)
from . import checks
from .choice import Choice, tolerances
from .rung.base import cables
from .rungs import rung_scene
from .stiffness import EXPLICIT_MAX_ELEMENTS, explicit_fit

log = logging.getLogger(__name__)

AUTO_METHOD = "cvodes-bdf2"   # A-stable BDF steps over the undamped stretch modes (Dale: 1.7k steps vs 41k)
# the quasi-static rungs have no stretch modes left (eliminated): the compiled explicit rk23 pair where its
# stiffness guard accepts them (fewer operations per step than CVODES's, studies/work_precision.py), else
# variable-order BDF (fewer steps than BDF2 at the same rtol); measurements in :mod:`.stiffness`. Every rung's
# rtol is at most the stated body error / STATED_ROOM, rounded down to a decade: the run must not add an error
# comparable to the one it states (:mod:`.stiffness`, accuracy; Wang's BDF2 at a swing resonance, random
# short-2: stated 0.13 %, rtol 1e-4 added 0.15 % by numerical damping, 1e-5 adds 0.02 %, 2.8x the steps)
QUASI_STATIC_METHOD = "rk23"
QUASI_STATIC_FALLBACK = "cvodes"
STATED_ROOM = 20.0
AUTO_RTOL = 1e-4     # at most; rtol = body tolerance / 100 (Dale, N = 3: 1e-4 leaves 0.01 % body, 0.2 % tension
#                      vs its own tight run; 1e-3 leaves 9 % on the tension extremes from the element ringing)


def _scene_sets_integrator(scene: Scene) -> bool:
    """True when the scene's [numerics] names an integrator or tolerances other than the defaults."""
    d = {f.name: f.default for f in dataclasses.fields(Numerics)}
    num = scene.numerics
    return (num.integrator, num.rtol, num.atol) != (d["integrator"], d["rtol"], d["atol"])


def integrator_settings(scene: Scene, tol, elements: int = 1, *, method=None, rtol=None, atol=None,
                        max_num_steps=None, jit: bool = False, rung: str | None = None, model=None, x0=None,
                        stated: float | None = None, cache=None):
    """The integrator settings of a ladder run.

    Parameters
    ----------
    scene : Scene
        Its ``numerics`` integrator and tolerances are used when they differ from the defaults.
    tol : (float, float)
        The model tolerance (body, tension).
    elements : int, optional
        Elements of the rung's model (compiled C up to COMPILE_MAX_ELEMENTS, else the VM, unless ``model``
        is given: then :func:`~cablesys.time_domain.integrators.compiled_by_default` decides).
    method, rtol, atol, max_num_steps, jit : optional
        The caller's choices (they win).
    rung : str, optional
        The rung run: the quasi-static rungs step with QUASI_STATIC_METHOD (no stretch modes to damp)
        where its guard accepts ``model`` at ``x0``, else QUASI_STATIC_FALLBACK.
    model, x0 : optional
        The rung's model (of ``scene``) and its initial state, for the quasi-static rungs' guard
        (:func:`_quasi_static_method`); without them those rungs run QUASI_STATIC_FALLBACK.
    stated : float, optional
        The rung's stated body error: the rtol is at most stated / STATED_ROOM.
    cache : RungCache, optional
        Keeps the guard's verdict per model, rtol and start (:meth:`~.rungs.RungCache.memo`).

    Returns
    -------
    IntegratorSettings
        Without any choice from the caller or the scene: AUTO_METHOD (see ``rung``) with rtol =
        min(AUTO_RTOL, tol[0] / 100) and atol = rtol / 10 relative to each state's natural scale (the integrators
        scale the states by :mod:`cablesys.model.scales`: stretch by its static value, angle by the
        top's amplitude over the length, rates by these times the forcing frequency).
    """
    from ..time_domain import IntegratorSettings
    num = scene.numerics
    if method is None and rtol is None and atol is None and not _scene_sets_integrator(scene):
        rtol = min(AUTO_RTOL, tol[0] / 100.0)
        if stated is not None and 0.0 < stated < math.inf:   # every rung (Wang at a resonance: random short-2)
            # in decades: a simulator is built per rtol, and scenes of one structure share it (RungCache)
            rtol = min(rtol, 10.0 ** math.floor(math.log10(stated / STATED_ROOM)))
        method = _quasi_static_method(scene, model, x0, rtol, elements, cache) if rung == "quasi-static" else AUTO_METHOD
        atol = rtol / 10   # scaled states (rtol / 1000 in SI was 3 % of Dale's dynamic stretch; 300 m N = 20: 502 vs 742 steps)
    extra = {} if max_num_steps is None else {"max_num_steps": int(max_num_steps)}
    method = method or num.integrator
    compiled = elements <= COMPILE_MAX_ELEMENTS if model is None else compiled_by_default(model, method)
    return IntegratorSettings(method=method, rtol=rtol or num.rtol, atol=atol or num.atol,
                              steps_per_output=num.steps_per_output, compiled=compiled, jit=jit, **extra)


def _quasi_static_method(scene: Scene, model, x0, rtol: float, elements: int, cache=None) -> str:
    """QUASI_STATIC_METHOD where :func:`.stiffness.explicit_fit` accepts ``model`` at ``x0`` (compiled runs
    only: uncompiled, the explicit pair would fall back to CVODES anyway), else QUASI_STATIC_FALLBACK; up to
    EXPLICIT_MAX_ELEMENTS angles (the guard's dense probe grows with them: one per element in the plane, two in 3-D)."""
    if model is None or x0 is None or max(elements, model.nq) > EXPLICIT_MAX_ELEMENTS or not compiles():
        return QUASI_STATIC_FALLBACK
    p = np.asarray(model.parameters(scene), dtype=float).ravel()
    x0 = np.asarray(x0, dtype=float).ravel()
    fit = lambda: explicit_fit(model, p, x0, rtol, QUASI_STATIC_METHOD)
    fit = fit() if cache is None else cache.memo(model, "explicit_fit", (rtol, p, x0), fit)
    log.debug("quasi-static rung: %s", fit.reason)
    return QUASI_STATIC_METHOD if fit.accepted else QUASI_STATIC_FALLBACK


def start(scene_run: Scene, model, cache=None):
    """The static start of ``model`` on its rung scene ``scene_run`` (:func:`~cablesys.time_domain.initial.initial_state`),
    once per model and parameters on ``cache``: the guard probes it and the run starts there."""
    p = np.asarray(model.parameters(scene_run), dtype=float).ravel()
    compute = lambda: initial_state(scene_run, model, p)
    return compute() if cache is None else cache.memo(model, "x0", (p,), compute)


def stated_room(choice: Choice) -> float | None:
    """The stated body error the rtol of a run of ``choice`` answers to (``stated`` of :func:`integrator_settings`): its
    a priori estimate, or None where the a posteriori check measures the run's integration error and states it
    (:func:`.checks.checked`): there rtol = min(AUTO_RTOL, body tolerance / 100) leaves that part within
    the tolerance, and tightening it to a stated error far below the tolerance bought nothing the check does not
    show (the ROV lift in Hs 6 m, segmented N = 46, stated body 1.8e-4: rtol 1e-5 and its check at 1e-6 took
    2.2x the steps of 1e-4 and 1e-5, for an integration part of 7e-5 of a tension)."""
    if checks.checked(choice.name, choice.segments):
        return None
    return choice.estimated_error.get("body")


def rung_settings(scene_run: Scene, tol, choice: Choice, model, *, cache=None, x0=None, method=None, rtol=None,
                  atol=None, max_num_steps=None, jit: bool = False):
    """(IntegratorSettings, x0) of a run of ``choice`` on its rung scene ``scene_run``: :func:`integrator_settings`
    with the rung's elements and stated error; ``x0`` for the quasi-static rungs their static start (:func:`start`,
    unless given), which their guard probes (with ``model`` and no ``method`` of the caller's), else the given one
    (None: the simulator's own start)."""
    elements = sum(c.segments for c in cables(scene_run))
    if choice.name == "quasi-static" and x0 is None and model is not None and method is None:
        x0 = start(scene_run, model, cache)
    s = integrator_settings(scene_run, tol, elements, method=method, rtol=rtol, atol=atol, max_num_steps=max_num_steps,
                            jit=jit, rung=choice.name, model=model, x0=x0, stated=stated_room(choice), cache=cache)
    return s, x0
