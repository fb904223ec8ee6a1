"""Parameter sweeps: ``cablesys.sweep(scene, vary={...}, analysis="run")`` -> ``xarray.Dataset``.

Cases run on all local cores (or a Dask cluster), one compiled model per scene structure
and worker, finished cases written as they complete so an interrupted sweep resumes.
``cablesys.sweep`` is :func:`cablesys.sweeps.sweep` (the package is a noun, its verb is exported
at the top level).
"""

from .api import sweep
from .grid import Grid, parse_values, parse_vary

__all__ = ["Grid", "parse_values", "parse_vary", "sweep"]
