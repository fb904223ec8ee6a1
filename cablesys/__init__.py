"""cablesys: dynamics of suspended and towed marine cables, built on CasADi.

Data flows one way: scene description -> model (CasADi functions) -> analyses
(statics, time domain, linear, design) -> results and plots. Three physical models:
the Wang (1971) cable-body system (this namespace), slack cables (:mod:`cablesys.slack`,
Griffin & Rosenthal 1985) and towed cables (:mod:`cablesys.towed`, Kennedy & Strahan 1981).

Every analysis returns a result that satisfies :class:`AnalysisResult` (``success``,
``message``, ``stats``, ``summary()``, ``to_xarray()``).

>>> import cablesys
>>> scene = cablesys.dale_scene()                         # doctest: +SKIP
>>> model = cablesys.build_model(scene)                   # doctest: +SKIP
>>> lin = cablesys.linearize(model, scene.parameters())   # doctest: +SKIP
>>> cablesys.modes(lin).omega_undamped                    # doctest: +SKIP

Names are imported lazily (``import cablesys`` does not import CasADi).
"""

import importlib

__version__ = "0.1.0"

# public name -> module that defines it (one table: the public API of the top level)
_EXPORTS = {
    "AnalysisResult": ".results", "TimeResult": ".results",
    "ParameterError": ".errors", "SolverError": ".errors", "NumericalWarning": ".errors",
    "Scene": ".scene", "load_scene": ".scene", "dump_scene": ".scene", "dale_scene": ".scene",
    "default_scene": ".scene", "heavy_wire_scene": ".scene",
    "CableModel": ".model", "build_model": ".model",
    "Simulator": ".time_domain", "simulate": ".ladder", "design": ".isolation", "sweep": ".sweeps",
    "steady_state": ".linear", "linearize": ".linear", "modes": ".linear", "rao": ".linear",
    "harmonic_response": ".linear", "periodic_steady_state": ".linear", "stochastic_response": ".linear",
    "jonswap": ".linear", "pierson_moskowitz": ".linear",
}
# subpackages reachable as attributes (``cablesys.slack.solve_equilibrium``); packages are nouns
# (``time_domain``, ``isolation``, ``sweeps``) and their verbs (``simulate``, ``design``, ``sweep``)
# are exported above, so no module and function share a name
_SUBPACKAGES = ("isolation", "ladder", "linear", "model", "plots", "scene", "slack", "sweeps", "time_domain", "towed")

__all__ = ["AnalysisResult", "CableModel", "NumericalWarning", "ParameterError", "Scene", "Simulator",
           "SolverError", "TimeResult", "build_model", "dale_scene", "default_scene", "design", "dump_scene",
           "harmonic_response", "heavy_wire_scene", "isolation", "jonswap", "ladder", "linear", "linearize", "load_scene", "model",
           "modes", "periodic_steady_state", "pierson_moskowitz", "plots", "rao", "scene", "simulate", "slack",
           "steady_state", "stochastic_response", "sweep", "sweeps", "time_domain", "towed"]


def __getattr__(name):
    """Import a public name or subpackage on first use (PEP 562)."""
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
        globals()[name] = value
        return value
    if name in _SUBPACKAGES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'cablesys' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
