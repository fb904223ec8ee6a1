"""Parameter sweeps: ``cablesys.sweep(scene, vary={...}, analysis="run")`` -> ``xarray.Dataset``.

The analyses are the registry :data:`cablesys.sweeps.analyses.ANALYSES` (the Wang model's run, rao,
periodic, stochastic, design and ladder; the slack and towed models' slack and towed). Cases run on all local cores (or a Dask cluster), one compiled model per scene structure
and worker, finished cases written as they complete so an interrupted sweep resumes.
``cablesys.sweep`` is :func:`cablesys.sweeps.sweep` (the package is a noun, its verb is exported
at the top level).
"""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "sweep": ".api",
    "Grid": ".grid",
    "parse_values": ".grid",
    "parse_vary": ".grid",
}

__all__ = ["Grid", "parse_values", "parse_vary", "sweep"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
