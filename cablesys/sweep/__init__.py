"""Parameter sweeps: ``cablesys.sweep(scene, vary={...}, analysis="run")`` -> ``xarray.Dataset``.

Cases run on all local cores (or a Dask cluster), one compiled model per scene structure
and worker, finished cases written as they complete so an interrupted sweep resumes.
The package itself is callable, so ``cablesys.sweep(...)`` and ``from cablesys.sweep import
sweep`` are the same function.
"""

import sys
import types

from .api import sweep
from .grid import Grid, parse_values, parse_vary

__all__ = ["Grid", "parse_values", "parse_vary", "sweep"]


class _CallableModule(types.ModuleType):
    def __call__(self, *args, **kwargs):
        return sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
